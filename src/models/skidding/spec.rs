//! `[model.skidding]`: the skidding level's scene spec, its fields declared once, and its
//! validated model parameters.

use crate::error::Result;
use crate::geometry::Bearing;
use crate::seam::fields::{closed, flag, ge, gt, integer, number, table};
use serde::{Deserialize, Serialize};

/// `[model.skidding]`: options of the skidding level (SI unless the name says otherwise).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SkiddingSpec {
    /// Traction law at the race contacts (`law = "coulomb" | "fitted" | "mixed_ehl" | "fitted_4109"`).
    pub traction: crate::contact::traction::TractionLaw,
    /// Pocket clearance per side, mm (default: the bearing's cage pocket clearance).
    pub pocket_clearance_mm: Option<f64>,
    /// Pocket contact stiffness, N/m.
    pub pocket_stiffness: f64,
    /// Pocket contact damping, N s/m.
    pub pocket_damping: f64,
    /// Pocket friction coefficient.
    pub pocket_friction: f64,
    /// Drag coefficient of an orbiting ball.
    pub drag_coefficient: f64,
    /// Effective density of the oil–air mixture around the balls, kg/m³.
    pub drag_density: f64,
    /// Oil viscosity for the ball spin drag, Pa s.
    pub drag_viscosity: f64,
    /// Cage drag, N m s.
    pub cage_drag: f64,
    /// Ball spacing scatter as a fraction of the pocket clearance (seeded, uniform).
    pub spacing_scatter: f64,
    /// Seed of the scatter.
    pub seed: u64,
    /// Traction coefficient limiting the lateral friction that carries the balls'
    /// gyroscopic couple (as `quasi_static`'s `gyro_traction`); 0 turns it off.
    pub gyro_traction: f64,
    /// Friction coefficient of the spinning moment at the race contacts (0: off).
    pub spin_friction: f64,
    /// Give the balls radial mass (their position along the contact line becomes a
    /// state, damped by `model.contact_damping`) instead of the quasi-static split.
    pub ball_radial_mass: bool,
}

crate::declare_fields!(SkiddingSpec {
    traction: crate::contact::traction::TractionLaw::default() => table(),
    pocket_clearance_mm: None => number("mm", gt(0.0), "skidding level: pocket clearance per side")
        .note("absent: the bearing's cage pocket clearance"),
    pocket_stiffness: 1e7 => number("N/m", gt(0.0), "skidding level: pocket contact stiffness"),
    pocket_damping: 200.0 => number("N s/m", closed(0.0, 1e9), "skidding level: pocket contact damping"),
    pocket_friction: 0.05 => number("-", closed(0.0, 2.0), "skidding level: pocket friction coefficient"),
    drag_coefficient: 0.5 => number("-", closed(0.0, 1e3), "skidding level: drag coefficient of an orbiting ball"),
    drag_density: 10.0 => number("kg/m³", closed(0.0, 1e4), "skidding level: density of the oil–air mixture around the balls"),
    drag_viscosity: 0.0 => number("Pa s", closed(0.0, 10.0), "skidding level: oil viscosity of the ball spin drag"),
    cage_drag: 0.0 => number("N m s", closed(0.0, 1e3), "skidding level: cage drag"),
    spacing_scatter: 0.0 => number("-", closed(0.0, 1.0), "skidding level: ball spacing scatter as a fraction of the pocket clearance"),
    seed: 1 => integer(ge(0.0), "skidding level: seed of the scatter"),
    gyro_traction: 0.3 => number("-", closed(0.0, 10.0), "skidding level: traction coefficient limiting the lateral friction that carries the balls' gyroscopic couple")
        .note("0 turns the gyroscopic friction off"),
    spin_friction: 0.0 => number("-", closed(0.0, 2.0), "skidding level: friction coefficient of the spinning moment (3/8) mu Q a E at the race contacts")
        .note("0: no spinning moment"),
    ball_radial_mass: false => flag("skidding level: give the balls radial mass (position along the contact line as a state, damped by model.contact_damping) instead of the quasi-static split")
        .note("default false"),
});

impl SkiddingSpec {
    /// Validated model parameters for bearing `b`; errors name `model.skidding.<field>`.
    pub fn params(&self, b: &Bearing) -> Result<crate::models::skidding::SkiddingParams> {
        self.traction.validate("model.skidding.traction")?;
        crate::seam::fields::check("model.skidding", Self::FIELDS, self)?;
        let cp = self
            .pocket_clearance_mm
            .map_or(b.cage.pocket_clearance, |v| v * 1e-3);
        Ok(crate::models::skidding::SkiddingParams {
            traction: self.traction,
            pocket_clearance: crate::error::positive("model.skidding.pocket_clearance (m)", cp)?,
            pocket_stiffness: self.pocket_stiffness,
            pocket_damping: self.pocket_damping,
            pocket_friction: self.pocket_friction,
            drag_coefficient: self.drag_coefficient,
            drag_density: self.drag_density,
            drag_viscosity: self.drag_viscosity,
            cage_drag: self.cage_drag,
            spacing_scatter: self.spacing_scatter,
            seed: self.seed,
            contact_damping: 0.0,
            gyroscopic: self.gyro_traction > 0.0,
            gyro_traction: if self.gyro_traction > 0.0 {
                self.gyro_traction
            } else {
                1.0
            },
            spin_friction: self.spin_friction,
            ball_radial_mass: self.ball_radial_mass,
            ..Default::default()
        })
    }
}
