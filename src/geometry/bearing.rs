//! The bearing description: what a preset or a bearing file says (edge units, mm and
//! degrees) and the validated, SI form every model uses.
//!
//! Geometry after Harris & Kotzalas, *Rolling Bearing Analysis* (5th ed.), Vol. 1, ch. 2:
//! `A = (f_i + f_o - 1) D` is the distance between the groove curvature centres at zero
//! load and zero clearance, and the free contact angle and the diametral clearance are tied
//! by `Pd = 2 A (1 - cos alpha0)` (docs/physics.md §1).

use super::element::{Element, ElementKind, Groove};
use super::material::{effective_modulus, Material};
use crate::error::{Error, Result};
use crate::seam::fields::{
    between, choice, closed, gt, integer, name_or_table, number, table, text, Names,
};
use crate::units::{deg, mm, um};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Deep-groove (radial, nominal contact angle 0) or angular-contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum BearingKind {
    /// Radial bearing; zero axial displacement means the inner ring is axially centred.
    #[default]
    DeepGroove,
    /// Angular-contact bearing; zero axial displacement means every ball just touches at the
    /// free contact angle.
    AngularContact,
}

/// How the cage is guided.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Guidance {
    /// Guided on the outer-ring land.
    #[default]
    OuterRing,
    /// Guided on the inner-ring land.
    InnerRing,
    /// Ball-riding cage.
    Ball,
}

/// The spellings of [`Guidance`].
pub const GUIDANCE: &[&str] = &["outer_ring", "inner_ring", "ball"];

/// A material given by preset key or inline (SI fields).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum MaterialSpec {
    /// A key of [`Material::presets`].
    Preset(String),
    /// A full material.
    Custom(Material),
}

impl MaterialSpec {
    fn resolve(&self, field: &str) -> Result<Material> {
        let m = match self {
            MaterialSpec::Preset(name) => Material::by_name(name)?,
            MaterialSpec::Custom(m) => m.clone(),
        };
        m.validate(field)?;
        Ok(m)
    }
}

fn steel() -> MaterialSpec {
    MaterialSpec::Preset("steel".into())
}
fn phenolic() -> MaterialSpec {
    MaterialSpec::Preset("phenolic".into())
}

/// Materials per body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialsSpec {
    /// Balls.
    #[serde(default = "steel")]
    pub ball: MaterialSpec,
    /// Inner ring.
    #[serde(default = "steel")]
    pub inner_ring: MaterialSpec,
    /// Outer ring.
    #[serde(default = "steel")]
    pub outer_ring: MaterialSpec,
    /// Cage.
    #[serde(default = "phenolic")]
    pub cage: MaterialSpec,
}

crate::declare_fields!(MaterialsSpec {
    ball => name_or_table(Names::Material, "ball material: a preset name or a table of material fields"),
    inner_ring => name_or_table(Names::Material, "inner-ring material"),
    outer_ring => name_or_table(Names::Material, "outer-ring material"),
    cage => name_or_table(Names::Material, "cage material"),
});

impl Default for MaterialsSpec {
    fn default() -> Self {
        MaterialsSpec {
            ball: steel(),
            inner_ring: steel(),
            outer_ring: steel(),
            cage: phenolic(),
        }
    }
}

/// Cage data as a file gives it (mm, kg). Everything is optional; defaults are documented
/// on [`Cage`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct CageSpec {
    /// Cage bore, mm.
    pub inner_diameter_mm: Option<f64>,
    /// Cage outside diameter, mm.
    pub outer_diameter_mm: Option<f64>,
    /// Cage width, mm.
    pub width_mm: Option<f64>,
    /// Cage mass, kg.
    pub mass_kg: Option<f64>,
    /// Polar moment of inertia about the bearing axis, kg m².
    pub inertia_kg_m2: Option<f64>,
    /// Pocket clearance (diametral play of a ball in its pocket), mm.
    pub pocket_clearance_mm: Option<f64>,
    /// Guide-land clearance (radial), mm.
    pub guide_clearance_mm: Option<f64>,
    /// Guidance.
    #[serde(default)]
    pub guidance: Guidance,
}

crate::declare_fields!(CageSpec {
    inner_diameter_mm => number("mm", gt(0.0), "cage bore").note("bore < cage bore < dm; absent: dm - 0.35 D"),
    outer_diameter_mm => number("mm", gt(0.0), "cage outside diameter")
        .note("dm < cage OD < outside diameter; absent: dm + 0.35 D"),
    width_mm => number("mm", gt(0.0), "cage width").note("absent: 0.8 D"),
    mass_kg => number("kg", gt(0.0), "cage mass").note("absent: annulus less the pockets"),
    inertia_kg_m2 => number("kg m²", gt(0.0), "cage polar moment of inertia").note("absent: thin annulus"),
    pocket_clearance_mm => number("mm", gt(0.0), "diametral play of a ball in its pocket")
        .note("absent: 0.02 D"),
    guide_clearance_mm => number("mm", gt(0.0), "radial guide-land clearance")
        .note("absent: 0.005 dm"),
    guidance => choice(GUIDANCE, "how the cage is guided"),
});

/// A bearing as a preset or a TOML bearing file describes it (edge units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingSpec {
    /// Designation.
    pub name: String,
    /// Deep-groove or angular-contact.
    #[serde(default)]
    pub kind: BearingKind,
    /// Ball diameter `D`, mm.
    pub ball_diameter_mm: f64,
    /// Pitch diameter `dm`, mm.
    pub pitch_diameter_mm: f64,
    /// Number of balls `Z`.
    pub ball_count: u32,
    /// Inner groove curvature ratio `f_i = r_i / D` (> 0.5). May be left out when both the
    /// contact angle and the clearance are given: then `f_i = f_o = 0.5 + A/(2D)`.
    pub inner_curvature: Option<f64>,
    /// Outer groove curvature ratio `f_o = r_o / D` (> 0.5).
    pub outer_curvature: Option<f64>,
    /// Free contact angle, degrees. Give this or the clearance (or both, to derive `f`).
    pub contact_angle_deg: Option<f64>,
    /// Diametral clearance `Pd`, µm (negative: preload, deep-groove only).
    pub clearance_um: Option<f64>,
    /// Bore, mm.
    pub bore_mm: Option<f64>,
    /// Outside diameter, mm.
    pub outer_diameter_mm: Option<f64>,
    /// Width, mm.
    pub width_mm: Option<f64>,
    /// Inner-ring mass, kg (estimated from the envelope when absent).
    pub inner_ring_mass_kg: Option<f64>,
    /// Outer-ring mass, kg (estimated when absent).
    pub outer_ring_mass_kg: Option<f64>,
    /// Cage data.
    #[serde(default)]
    pub cage: CageSpec,
    /// Materials.
    #[serde(default)]
    pub materials: MaterialsSpec,
    /// Where the data come from.
    #[serde(default)]
    pub source: String,
}

crate::declare_fields!(BearingSpec {
    name => text("designation"),
    kind => choice(&["deep_groove", "angular_contact"], "deep-groove (radial) or angular-contact"),
    ball_diameter_mm => number("mm", gt(0.0), "ball diameter D").note("< pitch_diameter_mm"),
    pitch_diameter_mm => number("mm", gt(0.0), "pitch diameter dm"),
    ball_count => integer(between(1.0, true, u32::MAX as f64, true), "number of balls Z")
        .note("balls must not overlap on the pitch circle: dm sin(pi/Z) > D"),
    inner_curvature => number("-", between(0.5, false, 1.0, false), "inner groove curvature ratio f_i = r_i/D")
        .note("may be left out with outer_curvature when both contact_angle_deg > 0 and clearance_um > 0 are given"),
    outer_curvature => number("-", between(0.5, false, 1.0, false), "outer groove curvature ratio f_o = r_o/D"),
    contact_angle_deg => number("deg", between(0.0, true, 80.0, true), "free contact angle alpha0")
        .note("give this or clearance_um (angular-contact)"),
    clearance_um => number("µm", closed(-1000.0, 1000.0), "diametral clearance Pd (negative: preload)")
        .why("1 mm either way is beyond any catalogue bearing's clearance or preload; the bearing's own range (the note) is checked as well")
        .note("deep-groove (-0.1 D, 2A) and no deeper than the preload that takes every ball to the plausibility limit at zero displacement (computed for the bearing: `raceway scene --check`); angular-contact [0, 2A), A = (f_i + f_o - 1) D"),
    bore_mm => number("mm", gt(0.0), "bore").note("< dm - D; absent: dm - 1.6 D"),
    outer_diameter_mm => number("mm", gt(0.0), "outside diameter").note("> dm + D; absent: dm + 1.6 D"),
    width_mm => number("mm", gt(0.0), "width").note("absent: 1.2 D"),
    inner_ring_mass_kg => number("kg", gt(0.0), "inner-ring mass").note("absent: estimated from the envelope"),
    outer_ring_mass_kg => number("kg", gt(0.0), "outer-ring mass").note("absent: estimated from the envelope"),
    cage => table(),
    materials => table(),
    source => text("where the data come from"),
});

/// Cage, SI. Defaults when a file is silent: bore `dm - 0.35 D`, outside diameter
/// `dm + 0.35 D`, width `0.8 D`, mass from the annulus less the pockets, inertia of a thin
/// annulus, pocket clearance `0.02 D`, guide clearance `0.005 dm`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Cage {
    /// Bore, m.
    pub inner_diameter: f64,
    /// Outside diameter, m.
    pub outer_diameter: f64,
    /// Width, m.
    pub width: f64,
    /// Mass, kg.
    pub mass: f64,
    /// Polar moment of inertia, kg m².
    pub inertia: f64,
    /// Pocket clearance, m.
    pub pocket_clearance: f64,
    /// Guide-land clearance (radial), m.
    pub guide_clearance: f64,
    /// Guidance.
    pub guidance: Guidance,
}

/// A validated bearing in SI units. Field names follow docs/physics.md.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Bearing {
    /// Designation.
    pub name: String,
    /// Deep-groove or angular-contact.
    pub kind: BearingKind,
    /// Rolling-element diameter `D` (ball or roller), m.
    pub d: f64,
    /// Pitch diameter `dm`, m.
    pub dm: f64,
    /// Number of rolling elements `Z`.
    pub z: usize,
    /// The rolling element: a ball with its groove, or a roller.
    pub element: Element,
    /// Free contact angle `alpha0`, rad (for a deep-groove bearing with clearance, the angle
    /// at which the balls would touch under a pure axial shift).
    pub alpha0: f64,
    /// Diametral clearance `Pd`, m (negative: interference).
    pub pd: f64,
    /// Bore, m.
    pub bore: f64,
    /// Outside diameter, m.
    pub outer_diameter: f64,
    /// Width, m.
    pub width: f64,
    /// Inner-ring mass, kg.
    pub inner_ring_mass: f64,
    /// Outer-ring mass, kg.
    pub outer_ring_mass: f64,
    /// Cage.
    pub cage: Cage,
    /// Rolling-element material (balls or rollers).
    pub ball_material: Material,
    /// Inner-ring material.
    pub inner_material: Material,
    /// Outer-ring material.
    pub outer_material: Material,
    /// Cage material.
    pub cage_material: Material,
}

impl BearingSpec {
    /// Validate and convert to SI. Every refusal names the field and the allowed range.
    pub fn build(&self) -> Result<Bearing> {
        // Every field within its declared row ([`BearingSpec::FIELDS`], [`CageSpec::FIELDS`]);
        // the rules across fields follow.
        crate::seam::fields::check("bearing", Self::FIELDS, self)?;
        crate::seam::fields::check("bearing.cage", CageSpec::FIELDS, &self.cage)?;
        let d = mm(self.ball_diameter_mm);
        let dm = mm(self.pitch_diameter_mm);
        let z = self.ball_count as usize;
        if d >= dm {
            return Err(Error::invalid(
                "bearing.ball_diameter_mm",
                self.ball_diameter_mm,
                format!("< pitch diameter ({} mm)", self.pitch_diameter_mm),
            ));
        }
        // Balls must not overlap on the pitch circle: chord dm sin(pi/Z) > D.
        if z >= 2 && dm * (PI / z as f64).sin() <= d {
            let zmax = (PI / (d / dm).asin()).floor();
            return Err(Error::invalid(
                "bearing.ball_count",
                z,
                format!("<= {zmax} (more balls of this size overlap on the pitch circle)"),
            ));
        }
        let (groove, alpha0, pd) = self.ball_groove(d)?;
        let element = Element::Ball(groove);

        let bore = self.bore_mm.map(mm).unwrap_or(dm - 1.6 * d);
        let od = self.outer_diameter_mm.map(mm).unwrap_or(dm + 1.6 * d);
        let width = self.width_mm.map(mm).unwrap_or(1.2 * d);
        if bore >= dm - d {
            return Err(Error::invalid(
                "bearing.bore_mm",
                bore * 1e3,
                format!("< dm - D = {:.3} mm", (dm - d) * 1e3),
            ));
        }
        if od <= dm + d {
            return Err(Error::invalid(
                "bearing.outer_diameter_mm",
                od * 1e3,
                format!(
                    "> dm + D = {:.3} mm (the ball is larger than the annulus)",
                    (dm + d) * 1e3
                ),
            ));
        }
        let ball_material = self.materials.ball.resolve("bearing.materials.ball")?;
        let inner_material = self
            .materials
            .inner_ring
            .resolve("bearing.materials.inner_ring")?;
        let outer_material = self
            .materials
            .outer_ring
            .resolve("bearing.materials.outer_ring")?;
        let cage_material = self.materials.cage.resolve("bearing.materials.cage")?;

        let (inner_est, outer_est) =
            estimated_ring_masses(&inner_material, &outer_material, dm, d, (bore, od, width));
        let inner_ring_mass = self.inner_ring_mass_kg.unwrap_or(inner_est);
        let outer_ring_mass = self.outer_ring_mass_kg.unwrap_or(outer_est);

        let c = &self.cage;
        let cid = c.inner_diameter_mm.map(mm).unwrap_or(dm - 0.35 * d);
        let cod = c.outer_diameter_mm.map(mm).unwrap_or(dm + 0.35 * d);
        if !(cid < dm && cod > dm && cid > bore && cod < od) {
            return Err(Error::invalid(
                "bearing.cage",
                format!("ID {:.3} mm, OD {:.3} mm", cid * 1e3, cod * 1e3),
                "bore < cage ID < dm < cage OD < outside diameter",
            ));
        }
        let cw = c.width_mm.map(mm).unwrap_or(0.8 * d);
        let cmass = c.mass_kg.unwrap_or_else(|| {
            let ring = PI / 4.0 * (cod * cod - cid * cid) * cw;
            let pockets = z as f64 * PI / 4.0 * d * d * (cod - cid) / 2.0;
            cage_material.density * (ring - pockets).max(0.2 * ring)
        });
        let cinertia = c
            .inertia_kg_m2
            .unwrap_or(cmass * (cod * cod + cid * cid) / 8.0);
        let pocket_clearance = c.pocket_clearance_mm.map(mm).unwrap_or(0.02 * d);
        let guide_clearance = c.guide_clearance_mm.map(mm).unwrap_or(0.005 * dm);

        Ok(Bearing {
            name: self.name.clone(),
            kind: self.kind,
            d,
            dm,
            z,
            element,
            alpha0,
            pd,
            bore,
            outer_diameter: od,
            width,
            inner_ring_mass,
            outer_ring_mass,
            cage: Cage {
                inner_diameter: cid,
                outer_diameter: cod,
                width: cw,
                mass: cmass,
                inertia: cinertia,
                pocket_clearance,
                guide_clearance,
                guidance: c.guidance,
            },
            ball_material,
            inner_material,
            outer_material,
            cage_material,
        })
    }

    /// A ball bearing's groove, free contact angle and diametral clearance for ball
    /// diameter `d` (m), from whichever of curvatures, contact angle and clearance are given.
    fn ball_groove(&self, d: f64) -> Result<(Groove, f64, f64)> {
        let alpha_in = self.contact_angle_deg.map(deg);
        let pd_in = self.clearance_um.map(um);

        let (fi, fo) = match (self.inner_curvature, self.outer_curvature) {
            (Some(fi), Some(fo)) => (fi, fo),
            (None, None) => match (alpha_in, pd_in) {
                (Some(a), Some(pd)) if a > 0.0 && pd > 0.0 => {
                    let f = 0.5 + pd / (2.0 * (1.0 - a.cos())) / (2.0 * d);
                    (f, f)
                }
                _ => {
                    return Err(Error::invalid(
                        "bearing.inner_curvature",
                        "missing",
                        "a number > 0.5 (may be left out only when both contact_angle_deg > 0 and clearance_um > 0 are given)",
                    ))
                }
            },
            (None, Some(_)) => return Err(Error::invalid("bearing.inner_curvature", "missing", "a number > 0.5")),
            (Some(_), None) => return Err(Error::invalid("bearing.outer_curvature", "missing", "a number > 0.5")),
        };
        for (field, f) in [
            ("bearing.inner_curvature", fi),
            ("bearing.outer_curvature", fo),
        ] {
            if !(f.is_finite() && f > 0.5 && f < 1.0) {
                return Err(Error::invalid(field, f, "in (0.5, 1.0)"));
            }
        }
        let a = super::element::groove_centre_distance(fi, fo, d);
        let (alpha0, pd) = match (self.kind, alpha_in, pd_in) {
            (BearingKind::AngularContact, Some(al), None) => (al, 2.0 * a * (1.0 - al.cos())),
            (BearingKind::AngularContact, None, Some(pd)) => {
                if !(0.0..2.0 * a).contains(&pd) {
                    return Err(Error::invalid(
                        "bearing.clearance_um",
                        self.clearance_um.unwrap_or_default(),
                        format!(
                            "in [0, {:.3}) for an angular-contact bearing of this conformity",
                            2e6 * a
                        ),
                    ));
                }
                ((1.0 - pd / (2.0 * a)).acos(), pd)
            }
            (BearingKind::AngularContact, Some(al), Some(pd)) => {
                let want = 2.0 * a * (1.0 - al.cos());
                if (want - pd).abs() > 0.02 * pd.abs().max(1e-7) {
                    return Err(Error::invalid(
                        "bearing.clearance_um",
                        self.clearance_um.unwrap_or_default(),
                        format!(
                            "{:.3} µm, which the contact angle and curvatures imply (give one of contact_angle_deg and clearance_um, or leave the curvatures out to derive them)",
                            want * 1e6
                        ),
                    ));
                }
                (al, pd)
            }
            (BearingKind::AngularContact, None, None) => {
                return Err(Error::invalid(
                    "bearing.contact_angle_deg",
                    "missing",
                    "give contact_angle_deg or clearance_um",
                ))
            }
            (BearingKind::DeepGroove, al, pd) => {
                let pd = match (al, pd) {
                    (_, Some(pd)) => pd,
                    (Some(al), None) => 2.0 * a * (1.0 - al.cos()),
                    (None, None) => 0.0,
                };
                if pd >= 2.0 * a || pd <= -0.1 * d {
                    return Err(Error::invalid(
                        "bearing.clearance_um",
                        pd * 1e6,
                        format!("in ({:.3}, {:.3}) µm", -0.1e6 * d, 2e6 * a),
                    ));
                }
                let alpha0 = if pd > 0.0 {
                    (1.0 - pd / (2.0 * a)).acos()
                } else {
                    0.0
                };
                (alpha0, pd)
            }
        };
        Ok((Groove { fi, fo }, alpha0, pd))
    }

    /// Parse a TOML bearing file (same fields as a preset).
    pub fn from_toml(text: &str) -> Result<BearingSpec> {
        crate::nesting::check_toml(text, crate::nesting::MAX_NESTING).map_err(|e| {
            Error::Parse {
                what: "bearing file".into(),
                message: e.to_string(),
            }
        })?;
        toml::from_str(text).map_err(|e| Error::Parse {
            what: "bearing file".into(),
            message: e.to_string(),
        })
    }
}

/// Ring masses when a file does not give them, kg: annuli from the bore to the raceway and
/// from the raceway to the outside diameter (`envelope` = bore, outside diameter, width, m),
/// 90 % full (shoulders and grooves), for element diameter `d` on pitch diameter `dm`.
fn estimated_ring_masses(
    inner: &Material,
    outer: &Material,
    dm: f64,
    d: f64,
    (bore, od, width): (f64, f64, f64),
) -> (f64, f64) {
    let annulus = |rho: f64, outside: f64, inside: f64| {
        0.9 * rho * PI / 4.0 * (outside * outside - inside * inside).max(0.0) * width
    };
    (
        annulus(inner.density, dm - d, bore),
        annulus(outer.density, od, dm + d),
    )
}

impl Bearing {
    /// The common description of a roller bearing, its rollers as the element. A cylindrical
    /// roller bearing is radial (`kind` deep-groove, contact angle 0); the envelope is the
    /// roller file's; ring masses follow the ball rule (annuli to the raceways, 90 % full)
    /// and the cage the ball defaults with the roller diameter (docs/physics.md §1).
    pub fn from_roller(r: super::roller::RollerBearing) -> Result<Bearing> {
        let (d, dm) = (r.dwe, r.dpw);
        let width = r.width;
        let (inner_ring_mass, outer_ring_mass) = estimated_ring_masses(
            &r.inner_material,
            &r.outer_material,
            dm,
            d,
            (r.bore, r.outer_diameter, width),
        );
        let cage_material = Material::by_name("steel")?;
        let (cid, cod, cw) = (dm - 0.35 * d, dm + 0.35 * d, 0.8 * r.lw);
        let ring = PI / 4.0 * (cod * cod - cid * cid) * cw;
        let pockets = r.z as f64 * d * r.lw * (cod - cid) / 2.0;
        let cmass = cage_material.density * (ring - pockets).max(0.2 * ring);
        Ok(Bearing {
            name: r.name.clone(),
            kind: if r.alpha > 0.0 {
                BearingKind::AngularContact
            } else {
                BearingKind::DeepGroove
            },
            d,
            dm,
            z: r.z,
            alpha0: r.alpha,
            pd: r.pd,
            bore: r.bore,
            outer_diameter: r.outer_diameter,
            width,
            inner_ring_mass,
            outer_ring_mass,
            cage: Cage {
                inner_diameter: cid,
                outer_diameter: cod,
                width: cw,
                mass: cmass,
                inertia: cmass * (cod * cod + cid * cid) / 8.0,
                pocket_clearance: 0.02 * d,
                guide_clearance: 0.005 * dm,
                guidance: Guidance::OuterRing,
            },
            ball_material: r.roller_material.clone(),
            inner_material: r.inner_material.clone(),
            outer_material: r.outer_material.clone(),
            cage_material,
            element: Element::Roller(Box::new(r)),
        })
    }

    /// The groove of a ball bearing, for the ball-only geometry below. A roller bearing
    /// has none; the level registry keeps it from every ball-only model, and here it reads
    /// as the conformity limit `f = 0.5` (`A = 0`), so nothing past the registry's refusal
    /// can turn it into a NaN.
    fn ball_groove(&self) -> Groove {
        match &self.element {
            Element::Ball(g) => *g,
            Element::Roller(_) => Groove { fi: 0.5, fo: 0.5 },
        }
    }

    /// The groove of a ball bearing; a roller bearing is refused naming what asked
    /// ([`Element::groove`]).
    pub fn groove(&self, what: &str) -> Result<&Groove> {
        self.element.groove(what)
    }

    /// Inner groove curvature ratio `f_i` of a ball bearing (the conformity limit 0.5 for a
    /// roller bearing, see [`Bearing::groove`]).
    pub fn fi(&self) -> f64 {
        self.ball_groove().fi
    }

    /// Outer groove curvature ratio `f_o` of a ball bearing (0.5 for a roller bearing).
    pub fn fo(&self) -> f64 {
        self.ball_groove().fo
    }

    /// Distance between the groove curvature centres at zero load and zero clearance,
    /// `A = (f_i + f_o - 1) D` (ball bearings; 0 for a roller bearing).
    pub fn a(&self) -> f64 {
        self.ball_groove().centre_distance(self.d)
    }

    /// The kind of rolling element.
    pub fn element(&self) -> ElementKind {
        self.element.kind()
    }

    /// The contact angle used for kinematics and the radial models: 0 for a deep-groove
    /// bearing, the free contact angle for an angular-contact one.
    pub fn nominal_contact_angle(&self) -> f64 {
        match self.kind {
            BearingKind::DeepGroove => 0.0,
            BearingKind::AngularContact => self.alpha0,
        }
    }

    /// Axial and radial offsets `(A1, A2)` of the inner groove curvature centre from the
    /// outer one with the inner ring at its reference position (zero displacement):
    /// angular-contact `(A sin alpha0, A cos alpha0)` (balls just touching); deep-groove
    /// `(0, A - Pd/2)` (ring axially centred). In both `A - A2 = Pd/2`.
    pub fn reference_groove_offset(&self) -> (f64, f64) {
        let a = self.a();
        match self.kind {
            BearingKind::AngularContact => (a * self.alpha0.sin(), a * self.alpha0.cos()),
            BearingKind::DeepGroove => (0.0, a - 0.5 * self.pd),
        }
    }

    /// Radius of the locus of the inner groove curvature centres,
    /// `Ri = dm/2 + (f_i - 0.5) D cos(alpha)` at the nominal contact angle (docs/physics.md §4).
    pub fn inner_groove_centre_radius(&self) -> f64 {
        let fi = self.ball_groove().fi;
        0.5 * self.dm + (fi - 0.5) * self.d * self.nominal_contact_angle().cos()
    }

    /// Radius of the locus of the outer groove curvature centres.
    pub fn outer_groove_centre_radius(&self) -> f64 {
        let fo = self.ball_groove().fo;
        0.5 * self.dm - (fo - 0.5) * self.d * self.nominal_contact_angle().cos()
    }

    /// Mass of one ball, kg.
    pub fn ball_mass(&self) -> f64 {
        self.ball_material.density * PI * self.d.powi(3) / 6.0
    }

    /// Polar moment of inertia of one ball, `J = m D²/10`, kg m².
    pub fn ball_inertia(&self) -> f64 {
        self.ball_mass() * self.d * self.d / 10.0
    }

    /// Effective modulus `E'` of the ball–inner-race pair, Pa.
    pub fn e_eff_inner(&self) -> f64 {
        effective_modulus(&self.ball_material, &self.inner_material)
    }

    /// Effective modulus `E'` of the ball–outer-race pair, Pa.
    pub fn e_eff_outer(&self) -> f64 {
        effective_modulus(&self.ball_material, &self.outer_material)
    }

    /// Inner raceway (groove bottom) diameter, m. The clearance is split equally:
    /// `d_i = dm - D - Pd/2` and `d_o = dm + D + Pd/2`, so that `d_o - d_i - 2D = Pd`.
    pub fn inner_race_diameter(&self) -> f64 {
        self.dm - self.d - 0.5 * self.pd
    }

    /// Outer raceway (groove bottom) diameter, m.
    pub fn outer_race_diameter(&self) -> f64 {
        self.dm + self.d + 0.5 * self.pd
    }
}
