//! The levels: glue between the [`LevelModel`](super::level::LevelModel) seam and the
//! physics in `crate::models`. Each level's glue lives in its folder, `models/<level>/level.rs`.

pub use crate::models::full::level::FullLevel;
pub use crate::models::linear::level::LinearLevel;
pub use crate::models::quasi_static::level::QuasiStaticLevel;
pub use crate::models::ring::level::RingLevel;
pub use crate::models::skidding::level::SkiddingLevel;

use crate::geometry::Bearing;

/// Kinematic cage speed for the nominal contact angle, outer ring fixed:
/// `omega_c = omega (1 - gamma) / 2` (physics.md §1).
pub fn cage_speed(b: &Bearing, omega: f64) -> f64 {
    let gamma = b.d * b.nominal_contact_angle().cos() / b.dm;
    0.5 * omega * (1.0 - gamma)
}
