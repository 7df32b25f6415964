//! The levels: glue between the [`LevelModel`](super::level::LevelModel) seam and the
//! physics in `crate::models`. One file per level.

pub mod full;
pub mod linear;
pub mod quasi_static;
pub mod ring;
pub mod skidding;

pub use full::FullLevel;
pub use linear::LinearLevel;
pub use quasi_static::QuasiStaticLevel;
pub use ring::RingLevel;
pub use skidding::SkiddingLevel;

use crate::geometry::Bearing;

/// Kinematic cage speed for the nominal contact angle, outer ring fixed:
/// `omega_c = omega (1 - gamma) / 2` (physics.md §1).
pub fn cage_speed(b: &Bearing, omega: f64) -> f64 {
    let gamma = b.d * b.nominal_contact_angle().cos() / b.dm;
    0.5 * omega * (1.0 - gamma)
}
