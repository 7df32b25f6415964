//! Fixtures shared by integration tests and examples.
pub mod rotor;
