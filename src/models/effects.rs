//! Optional effects a scene can switch on (defects, waviness, ball-spacing scatter,
//! lubrication). Every effect is off unless the scene names it, and costs nothing when off:
//! a scene without an `[effects]` section (or with empty lists and a dry film) evaluates
//! exactly the plain model, bit for bit.
//!
//! ```toml
//! [effects]
//! defects = [{ race = "outer", angle_deg = 270.0, width_mm = 1.0, depth_um = 50.0 }]
//! waviness = [{ race = "inner", order = 10, amplitude_um = 0.5, phase_deg = 0.0 }]
//! ball_spacing = { scatter = 0.5, seed = 7 }
//! lubrication = { film = "ehl", lubricant = "study2", viscosity_pa_s = 0.05 }
//! ```

use super::defects::{Defect, DefectSite};
use super::waviness::{spacing_offsets, Harmonic, WavySite};
use crate::error::{Error, Result};
use crate::geometry::{kinematics, Bearing};
use crate::lubrication::Lubricant;
use crate::seam::fields::{
    between, check, choice, closed, ge, gt, integer, name, number, Names, ANY,
};
use serde::{Deserialize, Serialize};

/// Which element a defect or a waviness sits on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Element {
    /// Outer race (fixed).
    Outer,
    /// Inner race (turns with the shaft).
    Inner,
    /// A ball (spins).
    Ball,
}

/// One local defect (spall).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DefectSpec {
    /// Element: `outer`, `inner` or `ball`.
    pub race: Element,
    /// Angle of the defect centre at t = 0, degrees: azimuth from +x on a race; on a ball,
    /// spin angle from its outer-race contact point.
    #[serde(default)]
    pub angle_deg: f64,
    /// Circumferential width, mm (< ball diameter).
    pub width_mm: f64,
    /// Depth, µm.
    pub depth_um: f64,
    /// Ball carrying the defect (0-based; `race = "ball"` only).
    #[serde(default)]
    pub ball: Option<u32>,
    /// Roller bearings: the defect's axial width on the raceway (or the roller), mm; absent:
    /// the whole effective length `Lwe`. It removes material from the laminae whose centres
    /// it spans (docs/physics.md §R12).
    #[serde(default)]
    pub axial_width_mm: Option<f64>,
    /// Roller bearings: the axial position of the defect's centre from the roller's
    /// mid-plane, along `+z`, mm; absent: 0.
    #[serde(default)]
    pub axial_position_mm: Option<f64>,
}

/// The spellings of [`Element`].
const ELEMENTS: &[&str] = &["outer", "inner", "ball"];

crate::declare_fields!(DefectSpec {
    race => choice(ELEMENTS, "element carrying the defect"),
    angle_deg => number("deg", ANY, "defect centre at t = 0: azimuth from +x on a race, spin angle on a ball"),
    width_mm => number("mm", gt(0.0), "circumferential width").note("< ball diameter"),
    depth_um => number("µm", closed(0.0, 5000.0), "depth").note("0: no loss, the healthy run"),
    ball => integer(ge(0.0), "ball carrying the defect (0-based)")
        .note("< Z; race = \"ball\" only (absent: ball 0)"),
    axial_width_mm => number("mm", gt(0.0), "axial width of a roller bearing's defect")
        .note("roller bearings only, <= the roller's effective length Lwe (absent: Lwe, every lamina)"),
    axial_position_mm => number("mm", ANY, "axial position of a roller bearing's defect centre from the roller's mid-plane, along +z")
        .note("roller bearings only; the defect stays within the effective length: |position| <= (Lwe - axial width)/2 (absent: 0)"),
});

/// One waviness harmonic `A sin(k theta + beta)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WavinessSpec {
    /// Element: `outer`, `inner` or `ball`.
    pub race: Element,
    /// Order `k` (>= 1).
    pub order: u32,
    /// Amplitude `A`, µm.
    pub amplitude_um: f64,
    /// Phase `beta`, degrees.
    #[serde(default)]
    pub phase_deg: f64,
    /// Ball (0-based) for `race = "ball"`; absent: every ball.
    #[serde(default)]
    pub ball: Option<u32>,
}

crate::declare_fields!(WavinessSpec {
    race => choice(ELEMENTS, "element carrying the waviness"),
    order => integer(closed(1.0, 10000.0), "order k of A sin(k theta + beta)"),
    amplitude_um => number("µm", closed(-100.0, 100.0), "amplitude A"),
    phase_deg => number("deg", ANY, "phase beta"),
    ball => integer(ge(0.0), "ball carrying the waviness (0-based)")
        .note("< Z; race = \"ball\" only (absent: every ball)"),
});

/// Seeded random scatter of the ball spacing within the pocket play (study \[3\]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpacingSpec {
    /// Fraction of the pocket play `±c_p/2`, in [0, 1].
    pub scatter: f64,
    /// Seed of the SplitMix64 generator.
    #[serde(default)]
    pub seed: u64,
}

crate::declare_fields!(SpacingSpec {
    scatter => number("-", closed(0.0, 1.0), "ball-spacing scatter as a fraction of the pocket play"),
    seed => integer(ge(0.0), "seed of the SplitMix64 generator"),
});

/// Film law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum FilmKind {
    /// Hamrock–Dowson film in series with Hertz, squeeze damping in parallel.
    #[default]
    Ehl,
    /// No film (the plain dry contact).
    Dry,
}

/// Lubrication: a lubricant preset with optional overrides.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LubricationSpec {
    /// `ehl` or `dry`.
    #[serde(default)]
    pub film: FilmKind,
    /// Preset: `study2` (docs/physics.md §10).
    #[serde(default = "default_lubricant")]
    pub lubricant: String,
    /// Inlet viscosity, Pa s.
    #[serde(default)]
    pub viscosity_pa_s: Option<f64>,
    /// Pressure–viscosity coefficient, m²/N.
    #[serde(default)]
    pub pressure_viscosity_m2_per_n: Option<f64>,
    /// Density, kg/m³.
    #[serde(default)]
    pub density_kg_m3: Option<f64>,
    /// Composite rms roughness of ball and race, µm.
    #[serde(default)]
    pub roughness_um: Option<f64>,
    /// Bulk oil temperature of a temperature-dependent preset (`mil_l_7808`), °C.
    #[serde(default)]
    pub temperature_c: Option<f64>,
}

crate::declare_fields!(LubricationSpec {
    film => choice(&["ehl", "dry"], "Hamrock–Dowson EHL film in series with Hertz (ehl) or none (dry)"),
    lubricant => name(Names::Lubricant, "lubricant preset"),
    viscosity_pa_s => number("Pa s", closed(0.0, 100.0), "inlet viscosity").note("absent: the preset's"),
    pressure_viscosity_m2_per_n => number("m²/N", closed(0.0, 1e-6), "pressure-viscosity coefficient")
        .note("absent: the preset's"),
    density_kg_m3 => number("kg/m³", between(0.0, false, 1e5, true), "lubricant density")
        .note("absent: the preset's"),
    roughness_um => number("µm", closed(0.0, 100.0), "composite rms roughness of ball and race")
        .note("absent: the preset's (mil_l_7808: 0, no source gives one)"),
    temperature_c => number("°C", closed(37.85, 204.85), "bulk oil temperature at which a temperature-dependent preset is evaluated")
        .note("lubricant = \"mil_l_7808\", required there: viscosity, pressure-viscosity, density and viscosity-temperature coefficient from the MIL-L-7808 correlations of a public ADORE-style lubricant library (public code, medium confidence; the span of its tables, 311-478 K)"),
});

fn default_lubricant() -> String {
    "study2".into()
}

/// The `[effects]` section of a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct Effects {
    /// Local defects, any number.
    pub defects: Vec<DefectSpec>,
    /// Waviness harmonics, any number.
    pub waviness: Vec<WavinessSpec>,
    /// Ball-spacing scatter.
    pub ball_spacing: Option<SpacingSpec>,
    /// Lubrication.
    pub lubrication: Option<LubricationSpec>,
    /// Race wear (docs/physics.md §7; `crate::models::wear`).
    pub wear: Option<WearSpec>,
    /// Friction power and thermal growth (docs/physics.md §8; `crate::models::thermal`).
    pub thermal: Option<ThermalSpec>,
}

/// `[effects.wear]`: Archard wear of both races with study \[2\]'s lubrication-aware
/// factors (`crate::models::wear`). Lubricated when `[effects.lubrication]` has an EHL
/// film (its lubricant and roughness), else the dry limit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WearSpec {
    /// Cells of the circumferential map of each race.
    pub cells: u32,
    /// Dimensionless wear coefficient `K` (study \[2\]: 5e-4).
    pub coefficient: f64,
    /// Hardness `Hv`, GPa (study \[2\]: 2.39).
    pub hardness_gpa: f64,
    /// `auto`: lubricated with an EHL film in the scene, else dry; `dry`: the dry limit
    /// (`La = 100`, `psi = 1`) even with a film.
    pub regime: WearRegime,
    /// Film-defect length `a_x`, m (study \[2\]: 3e-12).
    pub defect_length_m: f64,
    /// Film-defect time `t0`, s (study \[2\]: 3e-12).
    pub defect_time_s: f64,
    /// Activation energy `Ea`, J/mol (study \[2\]: 49e3).
    pub activation_energy_j_mol: f64,
    /// Surface temperature `Ts` without the thermal model, °C (study \[2\]: 20).
    pub surface_temperature_c: f64,
    /// Shaft revolutions of dynamics per wear cycle (the window the rate is measured on).
    pub window_revs: f64,
    /// Shaft revolutions each cycle stands for (the rate is extrapolated over them).
    pub cycle_revs: f64,
    /// Number of cycles; after them the wear map stays as it is.
    pub cycles: u32,
}

/// Lubricated or dry wear.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum WearRegime {
    /// Lubricated when the scene has an EHL film, else dry.
    #[default]
    Auto,
    /// The dry limit.
    Dry,
}

crate::declare_fields!(WearSpec {
    cells: 360 => integer(closed(1.0, 1000.0), "cells of the circumferential wear map of each race"),
    coefficient: 5e-4 => number("-", gt(0.0), "Archard wear coefficient K"),
    hardness_gpa: 2.39 => number("GPa", gt(0.0), "hardness Hv"),
    regime: WearRegime::Auto => choice(&["auto", "dry"], "auto: lubricated with an EHL film in the scene, else dry; dry: the dry limit La = 100, psi = 1"),
    defect_length_m: 3e-12 => number("m", gt(0.0), "film-defect length a_x"),
    defect_time_s: 3e-12 => number("s", gt(0.0), "film-defect time t0"),
    activation_energy_j_mol: 49e3 => number("J/mol", ge(0.0), "adsorption activation energy Ea"),
    surface_temperature_c: 20.0 => number("°C", gt(-273.15), "surface temperature Ts without the thermal model"),
    window_revs: 2.0 => number("rev", gt(0.0), "shaft revolutions of dynamics per wear cycle"),
    cycle_revs: 1e6 => number("rev", gt(0.0), "shaft revolutions each wear cycle stands for")
        .note(">= window_revs"),
    cycles: 10 => integer(ge(0.0), "wear cycles applied"),
});

/// `[effects.thermal]`: friction power (Palmgren, spin, hysteresis, cage), a lumped
/// thermal network and the ring growth it causes (`crate::models::thermal`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ThermalSpec {
    /// Palmgren `f0` (about 1 oil mist or jet on angular contact, 2 oil bath).
    pub f0: f64,
    /// Palmgren `f1`.
    pub f1: f64,
    /// Oil kinematic viscosity, cSt (absent: from the lubricant, else 20).
    pub viscosity_cst: Option<f64>,
    /// Spin friction coefficient `mu_s`.
    pub spin_friction: f64,
    /// Hysteresis loss fraction `alpha_h`.
    pub hysteresis_loss: f64,
    /// Ambient and initial temperature, °C.
    pub ambient_c: f64,
    /// Inner ring to ambient through the shaft, W/K.
    pub shaft_conductance_w_k: f64,
    /// Outer ring to ambient through the housing, W/K.
    pub housing_conductance_w_k: f64,
    /// Oil to ambient (oil flow `m_dot c_p`), W/K.
    pub oil_conductance_w_k: f64,
    /// Heat capacity of the oil in the bearing, J/K.
    pub oil_heat_capacity_j_k: f64,
    /// Ball–ring conductance per race, W/K (absent: Holm constriction of the loaded
    /// contacts, a static lower bound; rolling contacts conduct more).
    pub contact_conductance_w_k: Option<f64>,
    /// Slow (thermal) time step, s.
    pub dt_s: f64,
    /// Thermal seconds per second of dynamics (time-scale separation).
    pub time_scale: f64,
    /// Factor on the growth's change of the clearance (1: as computed, 0: off).
    pub growth_factor: f64,
}

crate::declare_fields!(ThermalSpec {
    f0: 2.0 => number("-", ge(0.0), "Palmgren factor f0 (load-independent torque)"),
    f1: 7e-4 => number("-", ge(0.0), "Palmgren factor f1 (load-dependent torque)"),
    viscosity_cst: None => number("cSt", gt(0.0), "oil kinematic viscosity")
        .note("absent: from the lubricant, else 20"),
    spin_friction: 0.03 => number("-", ge(0.0), "spin friction coefficient mu_s"),
    hysteresis_loss: 0.01 => number("-", ge(0.0), "hysteresis loss fraction alpha_h"),
    ambient_c: 20.0 => number("°C", gt(-273.15), "ambient and initial temperature"),
    shaft_conductance_w_k: 5.0 => number("W/K", ge(0.0), "inner ring to ambient through the shaft"),
    housing_conductance_w_k: 10.0 => number("W/K", ge(0.0), "outer ring to ambient through the housing"),
    oil_conductance_w_k: 5.0 => number("W/K", ge(0.0), "oil to ambient (oil flow)"),
    oil_heat_capacity_j_k: 20.0 => number("J/K", gt(0.0), "heat capacity of the oil in the bearing"),
    contact_conductance_w_k: None => number("W/K", ge(0.0), "ball–ring conductance per race")
        .note("absent: Holm constriction of the loaded contacts"),
    dt_s: 0.5 => number("s", gt(0.0), "thermal time step"),
    time_scale: 1.0 => number("-", gt(0.0), "thermal seconds per second of dynamics"),
    growth_factor: 1.0 => number("-", ge(0.0), "factor on the thermal growth's change of the clearance (0: off)"),
});

impl LubricationSpec {
    /// The lubricant: preset plus overrides.
    pub fn lubricant(&self) -> Result<Lubricant> {
        const T: &str = "effects.lubrication.temperature_c";
        let mut l = match (self.lubricant.as_str(), self.temperature_c) {
            ("study2", None) => Lubricant::study2(),
            ("study2", Some(t)) => {
                return Err(Error::invalid(
                    T,
                    t,
                    "absent with lubricant = \"study2\" (its data are at one temperature)",
                ))
            }
            ("mil_l_7808", Some(t)) => Lubricant::mil_l_7808(t + 273.15, T)?,
            ("mil_l_7808", None) => {
                return Err(Error::invalid(
                    T,
                    "absent",
                    "given with lubricant = \"mil_l_7808\", in [37.85, 204.85] °C",
                ))
            }
            (other, _) => {
                return Err(Error::Unknown {
                    what: "lubricant preset (effects.lubrication.lubricant)",
                    name: other.into(),
                    known: crate::lubrication::LUBRICANT_PRESETS
                        .iter()
                        .map(|s| s.to_string())
                        .collect(),
                })
            }
        };
        if let Some(v) = self.viscosity_pa_s {
            l.viscosity = v;
        }
        if let Some(v) = self.pressure_viscosity_m2_per_n {
            l.pressure_viscosity = v;
        }
        if let Some(v) = self.density_kg_m3 {
            l.density = v;
        }
        if let Some(v) = self.roughness_um {
            l.roughness = v * 1e-6;
        }
        Ok(l)
    }
}

impl Effects {
    /// Nothing switched on (the plain model).
    pub fn is_off(&self) -> bool {
        self.defects.is_empty()
            && self.waviness.is_empty()
            && self.ball_spacing.is_none()
            && self
                .lubrication
                .as_ref()
                .is_none_or(|l| l.film == FilmKind::Dry)
            && self.wear.is_none()
            && self.thermal.is_none()
    }

    /// Validate; errors name `effects.<field>` and the allowed range. Bounds that depend on
    /// the bearing (width below the ball diameter, ball index below Z) are checked by
    /// [`Effects::validate_for`].
    pub fn validate(&self) -> Result<()> {
        // `ball` names one ball of a ball defect or ball waviness only.
        let ball_only = |p: &str, race: Element, ball: Option<u32>| match ball {
            Some(b) if race != Element::Ball => Err(Error::invalid(
                format!("{p}.ball"),
                b,
                "only with race = \"ball\"",
            )),
            _ => Ok(()),
        };
        for (i, d) in self.defects.iter().enumerate() {
            let p = format!("effects.defects[{i}]");
            check(&p, DefectSpec::FIELDS, d)?;
            ball_only(&p, d.race, d.ball)?;
        }
        for (i, w) in self.waviness.iter().enumerate() {
            let p = format!("effects.waviness[{i}]");
            check(&p, WavinessSpec::FIELDS, w)?;
            ball_only(&p, w.race, w.ball)?;
        }
        if let Some(s) = &self.ball_spacing {
            check("effects.ball_spacing", SpacingSpec::FIELDS, s)?;
        }
        if let Some(l) = &self.lubrication {
            check("effects.lubrication", LubricationSpec::FIELDS, l)?;
            l.lubricant()?;
        }
        if let Some(w) = &self.wear {
            check("effects.wear", WearSpec::FIELDS, w)?;
            if w.cycle_revs < w.window_revs {
                return Err(Error::invalid(
                    "effects.wear.cycle_revs",
                    w.cycle_revs,
                    ">= window_revs",
                ));
            }
        }
        if let Some(t) = &self.thermal {
            check("effects.thermal", ThermalSpec::FIELDS, t)?;
        }
        Ok(())
    }

    /// Validate the bearing-dependent bounds.
    pub fn validate_for(&self, b: &Bearing) -> Result<()> {
        self.validate()?;
        let dmm = b.d * 1e3;
        for (i, d) in self.defects.iter().enumerate() {
            if d.width_mm >= dmm {
                return Err(Error::invalid(
                    format!("effects.defects[{i}].width_mm"),
                    d.width_mm,
                    format!("> 0 and < the ball diameter {dmm} mm"),
                ));
            }
            if d.race == Element::Ball && d.ball.unwrap_or(0) as usize >= b.z {
                return Err(Error::invalid(
                    format!("effects.defects[{i}].ball"),
                    d.ball.unwrap_or(0),
                    format!("a ball index in [0, {}]", b.z - 1),
                ));
            }
            axial_extent(i, d, b)?;
        }
        for (i, w) in self.waviness.iter().enumerate() {
            if let Some(j) = w.ball {
                if j as usize >= b.z {
                    return Err(Error::invalid(
                        format!("effects.waviness[{i}].ball"),
                        j,
                        format!("a ball index in [0, {}]", b.z - 1),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// The axial extent `(centre, width)` (m) of defect `i` on bearing `b`: on a roller bearing
/// within the roller's effective length `Lwe` (absent width: `Lwe`; absent position: 0),
/// refused naming `effects.defects[i].axial_width_mm` or `.axial_position_mm` with the range
/// that can be met; on a ball bearing `None`, and either field given is refused.
pub fn axial_extent(i: usize, d: &DefectSpec, b: &Bearing) -> Result<Option<(f64, f64)>> {
    let p = format!("effects.defects[{i}]");
    let crate::geometry::element::Element::Roller(r) = &b.element else {
        for (field, v) in [
            ("axial_width_mm", d.axial_width_mm),
            ("axial_position_mm", d.axial_position_mm),
        ] {
            if let Some(v) = v {
                return Err(Error::invalid(
                    format!("{p}.{field}"),
                    v,
                    "absent: a ball bearing's defect spans the whole contact (roller bearings only)",
                ));
            }
        }
        return Ok(None);
    };
    let lwe_mm = r.lwe * 1e3;
    let w = d.axial_width_mm.unwrap_or(lwe_mm);
    // The schema's own check (> 0) ran before; the roller's length bounds it above.
    if w > lwe_mm * (1.0 + 1e-12) {
        return Err(Error::invalid(
            format!("{p}.axial_width_mm"),
            w,
            format!("> 0 and <= the roller's effective length Lwe = {lwe_mm} mm"),
        ));
    }
    let w = w.min(lwe_mm);
    let c = d.axial_position_mm.unwrap_or(0.0);
    let reach = 0.5 * (lwe_mm - w);
    if c.abs() > reach * (1.0 + 1e-12) + 1e-12 {
        return Err(Error::invalid(
            format!("{p}.axial_position_mm"),
            c,
            format!(
                "in [-{reach}, {reach}] mm: the defect ({w} mm wide) within the roller's effective length Lwe = {lwe_mm} mm"
            ),
        ));
    }
    Ok(Some((c * 1e-3, w * 1e-3)))
}

/// The effects of a scene compiled for one bearing (SI), evaluated per ball.
#[derive(Debug, Clone, Default)]
pub struct RingEffects {
    /// Defects.
    pub defects: Vec<Defect>,
    /// Waviness harmonics.
    pub waviness: Vec<Harmonic>,
    /// Ball azimuth offsets, rad (empty: none).
    pub spacing: Vec<f64>,
    /// Lubricant when the EHL film is on.
    pub lubricant: Option<Lubricant>,
    /// Ball spin angle per radian of shaft angle (kinematic, relative to the cage).
    pub spin_ratio: f64,
    /// Whether some effect turns with the shaft or the balls (needs the shaft angle).
    pub needs_shaft_angle: bool,
    /// `(sin, cos)` of `k a_j` for every race harmonic (row) and ball `j` (column), with
    /// `a_j = 2 pi j / Z + spacing_j` the ball's place relative to the cage angle: with
    /// them a race harmonic at ball `j` costs two products, not a `sin` (see
    /// [`RingEffects::at`]). Empty when there are more than [`FAST_HARMONICS`] harmonics.
    ball_phase: Vec<(f64, f64)>,
    /// Balls.
    z: usize,
}

/// Most waviness harmonics [`RingEffects::at`] prepares on the stack; a scene with more
/// evaluates each harmonic's `sin` per ball.
pub const FAST_HARMONICS: usize = 8;

/// The profile of [`RingEffects`] at one cage and shaft angle: each harmonic's phase at
/// the cage angle, computed once per evaluation instead of once per ball.
#[derive(Debug, Clone, Copy)]
pub struct ProfileAt<'a> {
    fx: &'a RingEffects,
    theta_s: f64,
    phi: f64,
    /// Race harmonic `i`: `(sin, cos)` of `k theta_ref + beta` (`theta_ref` the cage angle
    /// for the outer race, the cage angle less the shaft angle for the inner); ball
    /// harmonic `i`: `(w(phi) + w(phi + pi), 0)`, the same for every ball it is on.
    phase: [(f64, f64); FAST_HARMONICS],
}

impl RingEffects {
    /// Compile the scene's effects for bearing `b`.
    pub fn new(e: &Effects, b: &Bearing) -> Result<RingEffects> {
        e.validate_for(b)?;
        let alpha = b.nominal_contact_angle();
        let (r_in, r_out) = (
            0.5 * (b.dm - b.d * alpha.cos()),
            0.5 * (b.dm + b.d * alpha.cos()),
        );
        let r = 0.5 * b.d;
        let defects: Vec<Defect> = e
            .defects
            .iter()
            .map(|d| {
                let (site, r_arc) = match d.race {
                    Element::Outer => (DefectSite::Outer, r_out),
                    Element::Inner => (DefectSite::Inner, r_in),
                    Element::Ball => (DefectSite::Ball(d.ball.unwrap_or(0) as usize), r),
                };
                Defect::new(
                    site,
                    d.angle_deg.to_radians(),
                    d.width_mm * 1e-3,
                    d.depth_um * 1e-6,
                    r,
                    r_arc,
                )
            })
            .collect();
        let waviness: Vec<Harmonic> = e
            .waviness
            .iter()
            .map(|w| Harmonic {
                site: match w.race {
                    Element::Outer => WavySite::Outer,
                    Element::Inner => WavySite::Inner,
                    Element::Ball => WavySite::Ball(w.ball.map(|j| j as usize)),
                },
                order: w.order,
                amplitude: w.amplitude_um * 1e-6,
                phase: w.phase_deg.to_radians(),
            })
            .collect();
        let spacing = e
            .ball_spacing
            .as_ref()
            .map(|s| spacing_offsets(b.z, s.scatter, b.cage.pocket_clearance, b.dm, s.seed))
            .unwrap_or_default();
        let lubricant = match &e.lubrication {
            Some(l) if l.film == FilmKind::Ehl => Some(l.lubricant()?),
            _ => None,
        };
        let needs_shaft_angle = defects.iter().any(|d| d.site != DefectSite::Outer)
            || waviness.iter().any(|w| w.site != WavySite::Outer);
        let ball_phase = if waviness.len() <= FAST_HARMONICS {
            let pitch = 2.0 * std::f64::consts::PI / b.z as f64;
            waviness
                .iter()
                .flat_map(|w| {
                    let spacing = &spacing;
                    (0..b.z).map(move |j| {
                        let a = pitch * j as f64 + spacing.get(j).copied().unwrap_or(0.0);
                        (w.order as f64 * a).sin_cos()
                    })
                })
                .collect()
        } else {
            Vec::new()
        };
        Ok(RingEffects {
            defects,
            waviness,
            spacing,
            lubricant,
            spin_ratio: kinematics(b, 1.0).ball_spin_speed,
            needs_shaft_angle,
            ball_phase,
            z: b.z,
        })
    }

    /// The profile at cage angle `theta_c` and shaft angle `theta_s` (rad), for the balls
    /// at `psi_j = theta_c + 2 pi j / Z + spacing_j` (the ring model's azimuths). Race
    /// harmonic `A sin(k psi_j + beta) = A (sin(k theta_c + beta) cos(k a_j) + cos(k theta_c
    /// + beta) sin(k a_j))`: one `sin_cos` per harmonic and evaluation; the same value as
    /// [`RingEffects::offset`] to rounding (test `prepared_profile_matches_offset`).
    pub fn at(&self, theta_c: f64, theta_s: f64) -> ProfileAt<'_> {
        let phi = self.spin_ratio * theta_s;
        let mut phase = [(0.0, 0.0); FAST_HARMONICS];
        if !self.ball_phase.is_empty() {
            for (p, w) in phase.iter_mut().zip(&self.waviness) {
                let k = w.order as f64;
                *p = match w.site {
                    WavySite::Outer => (k * theta_c + w.phase).sin_cos(),
                    WavySite::Inner => (k * (theta_c - theta_s) + w.phase).sin_cos(),
                    // The ball it is on (every ball: any index) sees the same value.
                    WavySite::Ball(b) => (w.interference(b.unwrap_or(0), 0.0, 0.0, phi), 0.0),
                };
            }
        }
        ProfileAt {
            fx: self,
            theta_s,
            phi,
            phase,
        }
    }

    /// Whether a deflection profile is needed (defects or waviness).
    pub fn has_profile(&self) -> bool {
        !(self.defects.is_empty() && self.waviness.is_empty())
    }

    /// Deflection offset of ball `j` at azimuth `psi` with the shaft turned by `theta_s`:
    /// waviness interference minus defect depth loss (docs/physics.md §5.1: `- H_j + w_j`), m.
    /// Each harmonic's `sin` evaluated afresh: the reference for [`RingEffects::at`].
    #[inline]
    pub fn offset(&self, j: usize, psi: f64, theta_s: f64) -> f64 {
        let phi = self.spin_ratio * theta_s;
        let mut o = 0.0;
        for w in &self.waviness {
            o += w.interference(j, psi, theta_s, phi);
        }
        for d in &self.defects {
            o -= d.loss(j, psi, theta_s, phi);
        }
        o
    }
}

impl ProfileAt<'_> {
    /// [`RingEffects::offset`] of ball `j` at its azimuth `psi` (that of
    /// [`RingEffects::at`]'s cage angle), m.
    #[inline]
    pub fn offset(&self, j: usize, psi: f64) -> f64 {
        let fx = self.fx;
        if fx.ball_phase.is_empty() {
            return fx.offset(j, psi, self.theta_s);
        }
        let mut o = 0.0;
        for (i, (w, &(s, c))) in fx.waviness.iter().zip(&self.phase).enumerate() {
            o += match w.site {
                WavySite::Outer | WavySite::Inner => {
                    let (sj, cj) = fx.ball_phase[i * fx.z + j];
                    w.amplitude * (s * cj + c * sj)
                }
                WavySite::Ball(b) => {
                    if b.is_some_and(|b| b != j) {
                        0.0
                    } else {
                        s
                    }
                }
            };
        }
        for d in &fx.defects {
            o -= d.loss(j, psi, self.theta_s, self.phi);
        }
        o
    }
}

#[cfg(test)]
mod tests {
    /// The prepared profile (one `sin_cos` per harmonic) gives the per-ball reference
    /// `offset` to rounding, for race and ball harmonics, scattered balls and a defect, at
    /// small and large cage angles.
    #[test]
    fn prepared_profile_matches_offset() {
        let text = r#"
waviness = [
  { race = "outer", order = 16, amplitude_um = 0.3, phase_deg = 10.0 },
  { race = "inner", order = 15, amplitude_um = 0.2, phase_deg = 30.0 },
  { race = "ball", order = 4, amplitude_um = 0.1, phase_deg = 60.0, ball = 3 },
  { race = "ball", order = 6, amplitude_um = 0.05 },
]
defects = [{ race = "outer", angle_deg = 200.0, width_mm = 1.0, depth_um = 5.0 }]
ball_spacing = { scatter = 0.5, seed = 7 }
"#;
        let effects: super::Effects = toml::from_str(text).unwrap();
        let b = crate::geometry::preset("7008ce").unwrap().build().unwrap();
        let fx = super::RingEffects::new(&effects, &b).unwrap();
        assert_eq!(fx.spacing.len(), b.z);
        let a_sum = 0.65e-6;
        let pitch = 2.0 * std::f64::consts::PI / b.z as f64;
        for (theta_c, theta_s) in [(0.0, 0.0), (0.3, 1.1), (3.9, -2.0), (1.2e4, 2.9e4)] {
            let at = fx.at(theta_c, theta_s);
            for j in 0..b.z {
                let psi = theta_c + pitch * j as f64 + fx.spacing[j];
                let want = fx.offset(j, psi, theta_s);
                let got = at.offset(j, psi);
                let tol = 1e-14 * a_sum * (1.0 + theta_c.abs() + theta_s.abs());
                assert!((got - want).abs() <= tol, "{theta_c} {j}: {got} vs {want}");
            }
        }
    }
}
