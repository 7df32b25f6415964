//! The FMU binary: links the raceway library with only its `fmi` feature, so the shared
//! library exports exactly the FMI 2.0 and FMI 3.0 function sets (see `src/fmi/`).
pub use raceway_core::fmi;
