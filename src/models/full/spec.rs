//! `[model.full]`: the full level's scene spec, its fields declared once, and its validated
//! model parameters.

use crate::error::Result;
use crate::geometry::Bearing;
use crate::models::quasi_static::RaceControl;
use crate::seam::fields::{choice, closed, gt, number, table};
use serde::{Deserialize, Serialize};

/// `[model.full]`: options of the full level (SI unless the name says otherwise); see
/// [`crate::models::full`]. Absent optional fields take the bearing's cage data.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FullSpec {
    /// Traction law at the race contacts.
    pub traction: crate::contact::traction::TractionLaw,
    /// `quasi_static` (ball radial/axial position in equilibrium) or `dynamic`.
    pub ball_contacts: crate::models::full::BallContacts,
    /// `free` (6 DOF) or `ideal` (rotation only).
    pub cage: crate::models::full::CageModel,
    /// Reference force of the nondimensional states, N.
    pub reference_load_n: f64,
    /// Factor on the boundary-layer drag of balls and cage (0: off).
    pub drag_factor: f64,
    /// Effective density of the oil–air mixture, kg/m³.
    pub drag_density: f64,
    /// Oil viscosity (drag, pockets, guide land), Pa s.
    pub viscosity: f64,
    /// Diametral pocket play, mm (absent: the bearing's).
    pub pocket_clearance_mm: Option<f64>,
    /// Pocket friction coefficient.
    pub pocket_friction: f64,
    /// Composite roughness of ball and pocket, µm.
    pub pocket_roughness_um: f64,
    /// Regularising slip speed of the pocket friction, m/s.
    pub pocket_v_s: f64,
    /// Guide land width, mm (absent: half the cage width).
    pub guide_width_mm: Option<f64>,
    /// Guide-land contact stiffness beyond `guide_eps_max`, N/m.
    pub guide_stiffness: f64,
    /// Eccentricity ratio where the guide-land contact starts.
    pub guide_eps_max: f64,
    /// Cage guidance: `outer_ring`, `inner_ring` or `ball` (absent: the bearing's
    /// `cage.guidance`).
    pub guidance: Option<crate::geometry::Guidance>,
    /// Cage mass unbalance: offset of the cage's mass centre from its geometric centre, µm.
    pub cage_unbalance_um: f64,
}

crate::declare_fields!(FullSpec {
    traction: crate::contact::traction::TractionLaw::default() => table(),
    ball_contacts: crate::models::full::BallContacts::default() => choice(BALL_CONTACTS, "full level: ball radial/axial position in quasi-static equilibrium (study [0]) or integrated with the ball mass (dynamic)"),
    cage: crate::models::full::CageModel::default() => choice(CAGE_MODELS, "full level: cage with six degrees of freedom (free) or centred, rotation only (ideal)"),
    reference_load_n: 1000.0 => number("N", closed(1e-3, 1e9), "full level: reference force F_ref of the nondimensional states (time scale sqrt(m_b D / (2 F_ref)))"),
    drag_factor: 1.0 => number("-", closed(0.0, 1e3), "full level: factor on the boundary-layer drag of balls and cage (0: off)"),
    drag_density: 10.0 => number("kg/m³", closed(0.0, 1e4), "full level: effective density of the oil–air mixture"),
    viscosity: 3e-3 => number("Pa s", closed(0.0, 10.0), "full level: oil viscosity (drag, pockets, guide land)"),
    pocket_clearance_mm: None => number("mm", gt(0.0), "full level: diametral pocket play")
        .note("absent: the bearing's cage pocket clearance"),
    pocket_friction: 0.1 => number("-", closed(0.0, 2.0), "full level: ball–pocket friction coefficient"),
    pocket_roughness_um: 0.3 => number("µm", closed(0.0, 1e3), "full level: composite roughness of ball and pocket"),
    pocket_v_s: 0.05 => number("m/s", closed(crate::contact::traction::SLIP_SPEED_MIN, 1e3), "full level: regularising slip speed of the pocket friction"),
    guide_width_mm: None => number("mm", gt(0.0), "full level: guide land width")
        .note("absent: half the cage width"),
    guide_stiffness: 1e7 => number("N/m", gt(0.0), "full level: guide-land contact stiffness beyond guide_eps_max"),
    guide_eps_max: 0.9 => number("-", closed(0.05, 0.999), "full level: eccentricity ratio where the guide-land contact starts"),
    guidance: None => choice(crate::geometry::bearing::GUIDANCE, "full level: cage guidance, on the outer-ring land (land radius = cage OD/2) or the inner-ring land (= cage bore/2), or ball-riding (no land)")
        .note("absent: bearing.cage.guidance"),
    cage_unbalance_um: 0.0 => number("µm", closed(0.0, 1e3), "full level: cage mass unbalance, offset of the mass centre from the geometric centre (a load rotating with the cage, m_c u w_c²)")
        .note("default 0"),
});

const BALL_CONTACTS: &[&str] = &["quasi_static", "dynamic"];
const CAGE_MODELS: &[&str] = &["free", "ideal"];

impl FullSpec {
    /// Validated model parameters for bearing `b`; errors name `model.full.<field>`.
    pub fn params(
        &self,
        b: &Bearing,
        race_control: RaceControl,
    ) -> Result<crate::models::full::FullParams> {
        self.traction.validate("model.full.traction")?;
        crate::seam::fields::check("model.full", Self::FIELDS, self)?;
        Ok(crate::models::full::FullParams {
            traction: self.traction,
            ball_contacts: self.ball_contacts,
            cage: self.cage,
            reference_load: self.reference_load_n,
            race_control,
            drag: self.drag_factor,
            drag_density: self.drag_density,
            viscosity: self.viscosity,
            pocket_clearance: self
                .pocket_clearance_mm
                .map_or(b.cage.pocket_clearance, |v| v * 1e-3),
            pocket_friction: self.pocket_friction,
            pocket_roughness: self.pocket_roughness_um * 1e-6,
            pocket_v_s: self.pocket_v_s,
            guide_width: self.guide_width_mm.map_or(0.5 * b.cage.width, |v| v * 1e-3),
            guide_stiffness: self.guide_stiffness,
            guide_eps_max: self.guide_eps_max,
            guidance: self.guidance.unwrap_or(b.cage.guidance),
            cage_unbalance: self.cage_unbalance_um * 1e-6,
        })
    }
}
