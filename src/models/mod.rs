//! The physics ladder: quasi-static equilibrium and the dynamic levels.

pub mod defects;
pub mod effects;
pub mod full;
pub mod linear;
pub mod quasi_static;
pub mod ring;
pub mod set;
pub mod shaft;
pub mod shaft_file;
pub mod skidding;
pub mod thermal;
pub mod waviness;
pub mod wear;
pub mod wear_map;

use crate::geometry::Bearing;

/// What a level is built from, as plain data: the validated bearing and the scene's model
/// and effects options. The component fills it from its scene
/// (`component::levels::Level::build`); a level never sees the scene itself, so the
/// physics does not depend on the component.
#[derive(Debug, Clone, Copy)]
pub struct LevelArgs<'a> {
    /// The validated bearing.
    pub bearing: &'a Bearing,
    /// Race control of the quasi-static kernels.
    pub race_control: quasi_static::RaceControl,
    /// Ring level: 2 or 5 degrees of freedom.
    pub ring_dof: u32,
    /// Contact damping per loaded ball, N s/m.
    pub contact_damping: f64,
    /// Linear level: the operating point.
    pub operating_point: &'a linear::spec::OperatingPoint,
    /// Skidding level options.
    pub skidding: &'a skidding::spec::SkiddingSpec,
    /// Full level options.
    pub full: &'a full::spec::FullSpec,
    /// The scene's effects (only levels that take effects read them).
    pub effects: &'a effects::Effects,
}
