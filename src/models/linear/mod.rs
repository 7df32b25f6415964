//! The `linear` level: constant stiffness and damping at an operating point. Its physics is
//! the quasi-static equilibrium's exact linearisation ([`crate::models::quasi_static`]) and
//! the ring model's contact damping ([`crate::models::ring`]); this folder holds only the
//! level ([`level`]).

pub mod level;
pub mod spec;
