//! FMI 2.0 / 3.0 co-simulation exports over [`crate::component::Component`]. Work in
//! progress (issue 4).
