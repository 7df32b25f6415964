//! The C ABI over [`crate::component::Component`]. Work in progress (issue 3).
