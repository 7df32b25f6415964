//! The SKF four-term friction model of a ball bearing: rolling, sliding, seals and drag.
//!
//! Source: SKF, *Rolling bearings* (PUB BU/P1 10000/1 EN, 2013, section "Friction", "The
//! SKF model for calculating the frictional moment"; the same model as the SKF General
//! Catalogue 6000 EN, 2008). In the source's units (N mm, mm, N, r/min, mm²/s), converted
//! to SI at the edge:
//!
//! - total `M = M_rr + M_sl + M_seal + M_drag`, power loss `N = M ω`;
//! - rolling `M_rr = φ_ish φ_rs G_rr (ν n)^0.6`;
//! - sliding `M_sl = G_sl μ_sl`, `μ_sl = φ_bl μ_bl + (1 − φ_bl) μ_EHL` with the weighting
//!   `φ_bl = 1 / e^(2.6e-8 (n ν)^1.4 dm)`, `μ_bl = 0.15` (the source's usual value) and
//!   `μ_EHL = 0.05` (its value for ball bearings on mineral oil);
//! - `G_rr`, `G_sl` from the catalogue's Table 2a, radial bearings:
//!   - deep-groove, `Fa = 0`: `G_rr = R1 dm^1.96 Fr^0.54`, `G_sl = S1 dm^−0.26 Fr^(5/3)`;
//!   - deep-groove, `Fa > 0`: `G_rr = R1 dm^1.96 (Fr + R2 Fa / sin α_F)^0.54`,
//!     `G_sl = S1 dm^−0.145 (Fr^5 + S2 dm^1.5 Fa^4 / sin α_F)^(1/3)`,
//!     `α_F = 24.6 (Fa/C0)^0.24` degrees;
//!   - angular-contact: `G_rr = R1 dm^1.97 (Fr + F_g + R2 Fa)^0.54` with
//!     `F_g = R3 dm^4 n²`, `G_sl = S1 dm^0.26 ((Fr + F_g)^(4/3) + S2 Fa^(4/3))` with
//!     `F_g = S3 dm^4 n²` (the balls' centrifugal load: not zero in an unloaded bearing);
//! - inlet shear heating `φ_ish = 1 / (1 + 1.84e-9 (n dm)^1.28 ν^0.64)`;
//! - kinematic replenishment (starvation) `φ_rs = 1 / e^(K_rs ν n (d + D) √(K_Z / (2 (D − d))))`,
//!   `K_rs = 3e-8` for a low oil bath and oil jet, `6e-8` for grease and oil–air;
//!   `K_Z = 3.1` deep-groove, `4.4` angular-contact;
//! - seals (an option; a bearing sealed on both sides) `M_seal = K_S1 d_s^β + K_S2`, with the
//!   constants of the seal and its counterface diameter `d_s` given by the user from the
//!   maker's table;
//! - drag in an oil bath (an option) `M_drag = 0.4 V_M K_ball dm^5 n² + 1.093e-7 n² dm³
//!   (n dm² f_t / ν)^−1.379 R_s`, `K_ball = i_rw K_Z (d + D)/(D − d) 1e-12`,
//!   `R_s = 0.36 dm² (t − sin t) f_A`, `t = 2 acos((0.6 dm − H)/(0.6 dm))` (`H ≤ 1.2 dm`),
//!   `f_t = sin(t/2)` for `t ≤ π` else 1, `f_A = 0.05 K_Z (D + d)/(D − d)`; the drag loss
//!   factor `V_M` is read by the user from the source's diagram at the oil level `H`.
//!
//! What was checked against SKF's own text and what was not (both printed with the result):
//! the structure `M_rr + M_sl + M_seal + M_drag`, the forms of `G_rr` and `G_sl` of Table 2a,
//! `α_F`, the `μ_sl` blend, `φ_bl`, `μ_bl = 0.15` and `μ_EHL = 0.05` were read in the
//! catalogue's text. The per-series geometry constants `R1 .. S3` ([`SERIES`]), `K_Z`, `K_rs`
//! and the formulas of `φ_ish`, `φ_rs` and the drag term were **not** confirmed against
//! SKF's own tables here: they come from restatements of the catalogue (their values agree
//! between independent restatements), and the output says so ([`UNCONFIRMED`]).
//!
//! Validity (the source's conditions): a rotating bearing at constant speed below its speed
//! rating, loads above the minimum load, constant in size and direction, normal clearance,
//! an aligned bearing. A bearing at rest is refused (the starting torque is another model);
//! a ring tilt above 2 arcmin, a bearing not in [`SERIES`], and an oil bath without the drag
//! inputs are reported.

use crate::error::{Error, Result};
use serde::Serialize;

/// What the output says is not confirmed against SKF's own text (built-in constants).
pub const UNCONFIRMED: &str = "geometry constants R1..S3, K_Z, K_rs and the phi_ish, phi_rs and drag formulas from restatements of SKF's catalogue, not checked against SKF's own tables";
/// The same with the geometry constants typed by the user.
pub const UNCONFIRMED_GIVEN: &str = "K_Z, K_rs and the phi_ish, phi_rs and drag formulas from restatements of SKF's catalogue, not checked against SKF's own tables (geometry constants as given)";

/// Bearing type of a series (selects the forms of `G_rr` and `G_sl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SkfKind {
    /// Single-row deep-groove ball bearing.
    DeepGroove,
    /// Single-row angular-contact ball bearing.
    AngularContact,
}

impl SkfKind {
    /// `K_Z`, the bearing-type constant of the replenishment and drag terms.
    pub fn kz(self) -> f64 {
        match self {
            SkfKind::DeepGroove => 3.1,
            SkfKind::AngularContact => 4.4,
        }
    }
}

/// Geometry constants of a bearing series (N, mm, r/min units of the source).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SkfSeries {
    /// Series as the catalogue names it (`62`), or `given` for constants typed by the user.
    pub name: &'static str,
    /// Bearing type.
    pub kind: SkfKind,
    /// Rolling constants `R1, R2, R3` (`R3` angular-contact only; 0 otherwise).
    pub r: [f64; 3],
    /// Sliding constants `S1, S2, S3` (`S3` angular-contact only; 0 otherwise).
    pub s: [f64; 3],
}

/// The series with constants: deep-groove 60, 62, 63. Not confirmed against SKF's table
/// ([`UNCONFIRMED`]). The angular-contact series (72 B, 73 B, ...) have no constants here:
/// none was found in a text available to check them, so they are given by the user
/// ([`SkfSeries::given`]).
pub const SERIES: [SkfSeries; 3] = [
    SkfSeries {
        name: "60",
        kind: SkfKind::DeepGroove,
        r: [4.1e-7, 1.7, 0.0],
        s: [3.73e-3, 14.6, 0.0],
    },
    SkfSeries {
        name: "62",
        kind: SkfKind::DeepGroove,
        r: [3.9e-7, 1.7, 0.0],
        s: [3.23e-3, 36.5, 0.0],
    },
    SkfSeries {
        name: "63",
        kind: SkfKind::DeepGroove,
        r: [3.7e-7, 1.7, 0.0],
        s: [2.84e-3, 92.8, 0.0],
    },
];

impl SkfSeries {
    /// Constants typed by the user as `R1,R2,R3,S1,S2,S3` (from the maker's table for the
    /// series; `R3`, `S3` are used by angular-contact bearings only), naming `field`.
    pub fn given(text: &str, kind: SkfKind, field: &str) -> Result<SkfSeries> {
        let v = numbers(
            text,
            6,
            field,
            "R1,R2,R3,S1,S2,S3 (six numbers >= 0 from the maker's table; R1, S1 > 0)",
        )?;
        if v.iter().any(|x| *x < 0.0) || v[0] <= 0.0 || v[3] <= 0.0 {
            return Err(Error::invalid(
                field,
                text,
                "R1,R2,R3,S1,S2,S3 (six numbers >= 0 from the maker's table; R1, S1 > 0)",
            ));
        }
        Ok(SkfSeries {
            name: "given",
            kind,
            r: [v[0], v[1], v[2]],
            s: [v[3], v[4], v[5]],
        })
    }
}

/// The series of a deep-groove designation such as `6205`, `6312` (case-insensitive);
/// `None` for any other.
pub fn series_of(designation: &str) -> Option<&'static SkfSeries> {
    let n: String = designation
        .trim()
        .to_ascii_uppercase()
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect();
    let digits = n.chars().take_while(|c| c.is_ascii_digit()).count();
    if digits != 4 {
        return None;
    }
    let (num, suffix) = n.split_at(4);
    if !suffix.is_empty() {
        return None;
    }
    SERIES.iter().find(|s| s.name == &num[..2])
}

/// Lubrication method (selects `K_rs` and whether drag applies).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SkfLubrication {
    /// Oil bath (low level: `K_rs = 3e-8`); the drag term applies.
    OilBath,
    /// Oil jet (`K_rs = 3e-8`), no drag.
    OilJet,
    /// Oil–air (`K_rs = 6e-8`), no drag.
    OilAir,
    /// Grease (`K_rs = 6e-8`, the base oil's viscosity), no drag.
    Grease,
}

impl SkfLubrication {
    /// The names a user types.
    pub const NAMES: [&'static str; 4] = ["oil-bath", "oil-jet", "oil-air", "grease"];

    /// From its name, naming `field` when unknown.
    pub fn parse(s: &str, field: &str) -> Result<SkfLubrication> {
        Ok(match s.trim().to_ascii_lowercase().as_str() {
            "oil-bath" => SkfLubrication::OilBath,
            "oil-jet" => SkfLubrication::OilJet,
            "oil-air" => SkfLubrication::OilAir,
            "grease" => SkfLubrication::Grease,
            _ => {
                return Err(Error::invalid(
                    field,
                    s,
                    "one of oil-bath, oil-jet, oil-air, grease",
                ))
            }
        })
    }

    /// Its name.
    pub fn name(self) -> &'static str {
        match self {
            SkfLubrication::OilBath => Self::NAMES[0],
            SkfLubrication::OilJet => Self::NAMES[1],
            SkfLubrication::OilAir => Self::NAMES[2],
            SkfLubrication::Grease => Self::NAMES[3],
        }
    }

    /// `K_rs`, the replenishment/starvation constant.
    pub fn krs(self) -> f64 {
        match self {
            SkfLubrication::OilBath | SkfLubrication::OilJet => 3e-8,
            SkfLubrication::OilAir | SkfLubrication::Grease => 6e-8,
        }
    }
}

/// Seal constants from the maker's table: `M_seal = K_S1 d_s^β + K_S2` (N mm, `d_s` in mm),
/// both seals of the bearing.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SealConstants {
    /// `K_S1`.
    pub ks1: f64,
    /// `β`.
    pub beta: f64,
    /// `K_S2`, N mm.
    pub ks2: f64,
    /// Seal counterface diameter `d_s`, m.
    pub ds: f64,
}

impl SealConstants {
    /// From `KS1,BETA,KS2,DS_MM` as typed, naming `field`.
    pub fn parse(text: &str, field: &str) -> Result<SealConstants> {
        let v = numbers(text, 4, field, "KS1,BETA,KS2,DS_MM, e.g. 0.023,2.25,2,40")?;
        if v[0] < 0.0 || v[1] < 0.0 || v[2] < 0.0 || v[3] <= 0.0 || v[3] > 10_000.0 {
            return Err(Error::invalid(
                field,
                text,
                "KS1, BETA, KS2 >= 0 and a counterface diameter in (0, 10000] mm",
            ));
        }
        Ok(SealConstants {
            ks1: v[0],
            beta: v[1],
            ks2: v[2],
            ds: v[3] * 1e-3,
        })
    }
}

/// Oil-bath drag inputs: the drag loss factor `V_M` read from the source's diagram at the
/// oil level `H`, and `H` itself.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DragInputs {
    /// `V_M`.
    pub vm: f64,
    /// Oil level `H` above the lowest point of the outer ring raceway, m.
    pub oil_level: f64,
}

impl DragInputs {
    /// From `VM,H_MM` as typed, naming `field`.
    pub fn parse(text: &str, field: &str) -> Result<DragInputs> {
        let v = numbers(text, 2, field, "VM,H_MM, e.g. 0.0003,10")?;
        if !(v[0] > 0.0 && v[0] < 1.0 && v[1] >= 0.0 && v[1] <= 10_000.0) {
            return Err(Error::invalid(
                field,
                text,
                "V_M in (0, 1) and an oil level in [0, 10000] mm",
            ));
        }
        Ok(DragInputs {
            vm: v[0],
            oil_level: v[1] * 1e-3,
        })
    }
}

fn numbers(text: &str, n: usize, field: &str, form: &str) -> Result<Vec<f64>> {
    let v: Vec<f64> = text
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| Error::invalid(field, text, form))?;
    if v.len() != n || v.iter().any(|x| !x.is_finite()) {
        return Err(Error::invalid(field, text, form));
    }
    Ok(v)
}

/// Operating point and options (SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkfInputs {
    /// Bore `d`, m.
    pub bore: f64,
    /// Outside diameter `D`, m.
    pub outer_diameter: f64,
    /// Speed of the rotating ring relative to the other, rpm.
    pub speed_rpm: f64,
    /// Kinematic viscosity at the operating temperature (of the base oil for grease), m²/s.
    pub nu: f64,
    /// Radial load, N.
    pub fr: f64,
    /// Axial load, N.
    pub fa: f64,
    /// Basic static load rating `C0`, N (deep-groove `α_F`).
    pub c0: f64,
    /// Lubrication method.
    pub lubrication: SkfLubrication,
    /// Seals (`None`: open or shielded).
    pub seal: Option<SealConstants>,
    /// Oil-bath drag inputs (`None`: no drag term).
    pub drag: Option<DragInputs>,
    /// Ring tilt magnitude, rad (the model assumes an aligned bearing).
    pub tilt: f64,
}

/// The four terms (N m), the power loss (W) and the factors behind them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SkfFriction {
    /// Series whose constants were used.
    pub series: &'static str,
    /// Lubrication method.
    pub lubrication: &'static str,
    /// Rolling moment `M_rr`.
    pub rolling: f64,
    /// Sliding moment `M_sl`.
    pub sliding: f64,
    /// Seal moment `M_seal` (`None`: no seal constants given).
    pub seals: Option<f64>,
    /// Drag moment `M_drag` (`None`: not an oil bath, or no drag inputs).
    pub drag: Option<f64>,
    /// The sum of the terms computed.
    pub total: f64,
    /// Power loss `M ω`, W.
    pub power: f64,
    /// `G_rr` (source units).
    pub g_rr: f64,
    /// `G_sl` (source units).
    pub g_sl: f64,
    /// Inlet shear heating factor `φ_ish`.
    pub phi_ish: f64,
    /// Replenishment/starvation factor `φ_rs`.
    pub phi_rs: f64,
    /// Sliding weighting factor `φ_bl`.
    pub phi_bl: f64,
    /// Sliding friction coefficient `μ_sl`.
    pub mu_sl: f64,
    /// Deep-groove axial-load angle `α_F`, rad (`None` without axial load).
    pub alpha_f: Option<f64>,
    /// Angular-contact centrifugal load of the rolling term `R3 dm^4 n²`, N.
    pub centrifugal_load: f64,
    /// What is not confirmed against SKF's own text ([`UNCONFIRMED`],
    /// [`UNCONFIRMED_GIVEN`]).
    pub unconfirmed: &'static str,
    /// Conditions of the source the operating point does not meet, in words.
    pub warnings: Vec<String>,
}

/// SKF's model for the series `s` at `x` (module docs). Refused: a bearing at rest, bad
/// numbers, `D <= d`.
pub fn skf_friction(s: &SkfSeries, x: &SkfInputs) -> Result<SkfFriction> {
    for (f, v) in [
        ("bore", x.bore),
        ("outer_diameter", x.outer_diameter),
        ("nu", x.nu),
        ("c0", x.c0),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::invalid(format!("skf.{f}"), v, "a finite number > 0"));
        }
    }
    for (f, v) in [("fr", x.fr), ("fa", x.fa), ("tilt", x.tilt)] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(Error::invalid(
                format!("skf.{f}"),
                v,
                "a finite number >= 0",
            ));
        }
    }
    if x.outer_diameter <= x.bore {
        return Err(Error::invalid(
            "skf.outer_diameter",
            x.outer_diameter,
            "larger than the bore",
        ));
    }
    let n = x.speed_rpm.abs();
    if !(n.is_finite() && n > 0.0) {
        return Err(Error::invalid(
            "skf.speed_rpm",
            x.speed_rpm,
            "a rotating bearing (the SKF model is for constant speed; the starting torque is another model)",
        ));
    }
    let (d, dd) = (x.bore * 1e3, x.outer_diameter * 1e3);
    let dm = 0.5 * (d + dd);
    let nu = x.nu * 1e6;
    let (fr, fa) = (x.fr, x.fa);
    let [r1, r2, r3] = s.r;
    let [s1, s2, s3] = s.s;
    let mut alpha_f = None;
    let mut centrifugal_load = 0.0;
    let (g_rr, g_sl) = match s.kind {
        SkfKind::DeepGroove if fa > 0.0 => {
            let a = (24.6 * (fa / x.c0).powf(0.24)).to_radians();
            alpha_f = Some(a);
            (
                r1 * dm.powf(1.96) * (fr + r2 / a.sin() * fa).powf(0.54),
                s1 * dm.powf(-0.145)
                    * (fr.powi(5) + s2 * dm.powf(1.5) / a.sin() * fa.powi(4)).cbrt(),
            )
        }
        SkfKind::DeepGroove => (
            r1 * dm.powf(1.96) * fr.powf(0.54),
            s1 * dm.powf(-0.26) * fr.powf(5.0 / 3.0),
        ),
        SkfKind::AngularContact => {
            let fg_rr = r3 * dm.powi(4) * n * n;
            let fg_sl = s3 * dm.powi(4) * n * n;
            centrifugal_load = fg_rr;
            (
                r1 * dm.powf(1.97) * (fr + fg_rr + r2 * fa).powf(0.54),
                s1 * dm.powf(0.26) * ((fr + fg_sl).powf(4.0 / 3.0) + s2 * fa.powf(4.0 / 3.0)),
            )
        }
    };
    let kz = s.kind.kz();
    let phi_ish = 1.0 / (1.0 + 1.84e-9 * (n * dm).powf(1.28) * nu.powf(0.64));
    let phi_rs = (-x.lubrication.krs() * nu * n * (d + dd) * (kz / (2.0 * (dd - d))).sqrt()).exp();
    let m_rr = phi_ish * phi_rs * g_rr * (nu * n).powf(0.6);
    let phi_bl = (-2.6e-8 * (n * nu).powf(1.4) * dm).exp();
    let mu_sl = phi_bl * 0.15 + (1.0 - phi_bl) * 0.05;
    let m_sl = g_sl * mu_sl;
    let m_seal = x.seal.map(|c| c.ks1 * (c.ds * 1e3).powf(c.beta) + c.ks2);
    let mut warnings = Vec::new();
    let m_drag = match (x.lubrication, x.drag) {
        (SkfLubrication::OilBath, Some(g)) => {
            let h = (g.oil_level * 1e3).min(1.2 * dm);
            let t = 2.0 * ((0.6 * dm - h) / (0.6 * dm)).clamp(-1.0, 1.0).acos();
            let f_t = if t <= std::f64::consts::PI {
                (0.5 * t).sin()
            } else {
                1.0
            };
            let f_a = 0.05 * kz * (dd + d) / (dd - d);
            let r_s = 0.36 * dm * dm * (t - t.sin()) * f_a;
            let k_ball = kz * (d + dd) / (dd - d) * 1e-12;
            let viscous = if r_s > 0.0 && f_t > 0.0 {
                1.093e-7 * n * n * dm.powi(3) * (n * dm * dm * f_t / nu).powf(-1.379) * r_s
            } else {
                0.0
            };
            Some(0.4 * g.vm * k_ball * dm.powi(5) * n * n + viscous)
        }
        (SkfLubrication::OilBath, None) => {
            warnings.push(
                "oil bath without --skf-drag VM,H_MM: the drag term is left out (read V_M from SKF's diagram at the oil level H)"
                    .to_string(),
            );
            None
        }
        (_, Some(_)) => {
            return Err(Error::invalid(
                "skf.drag",
                x.lubrication.name(),
                "drag inputs with an oil bath only (--skf-lubrication oil-bath)",
            ))
        }
        (_, None) => None,
    };
    let tilt_arcmin = x.tilt.to_degrees() * 60.0;
    if tilt_arcmin > 2.0 {
        warnings.push(format!(
            "ring tilt {tilt_arcmin:.1} arcmin: the SKF model assumes an aligned bearing"
        ));
    }
    let total_nmm = m_rr + m_sl + m_seal.unwrap_or(0.0) + m_drag.unwrap_or(0.0);
    let total = total_nmm * 1e-3;
    Ok(SkfFriction {
        series: s.name,
        lubrication: x.lubrication.name(),
        rolling: m_rr * 1e-3,
        sliding: m_sl * 1e-3,
        seals: m_seal.map(|m| m * 1e-3),
        drag: m_drag.map(|m| m * 1e-3),
        total,
        power: total * n * std::f64::consts::PI / 30.0,
        g_rr,
        g_sl,
        phi_ish,
        phi_rs,
        phi_bl,
        mu_sl,
        alpha_f,
        centrifugal_load,
        unconfirmed: if s.name == "given" {
            UNCONFIRMED_GIVEN
        } else {
            UNCONFIRMED
        },
        warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 6206 (d 30, D 62 mm), radial 3 000 N, 3 000 rpm, 20 mm²/s, low oil bath, no seals
    /// or drag.
    fn x6206() -> SkfInputs {
        SkfInputs {
            bore: 0.030,
            outer_diameter: 0.062,
            speed_rpm: 3000.0,
            nu: 20e-6,
            fr: 3000.0,
            fa: 0.0,
            c0: 11200.0,
            lubrication: SkfLubrication::OilJet,
            seal: None,
            drag: None,
            tilt: 0.0,
        }
    }

    fn s62() -> &'static SkfSeries {
        series_of("6206").unwrap()
    }

    /// Angular-contact constants of the order of the catalogue's, typed as a user would:
    /// test values, not SKF's.
    fn ac() -> SkfSeries {
        SkfSeries::given("5e-7,2,2e-12,1e-2,0.7,2e-12", SkfKind::AngularContact, "c").unwrap()
    }

    /// The formulas by hand (dm = 46 mm, n ν = 60 000):
    /// G_rr = 3.9e-7 · 46^1.96 · 3000^0.54 = 0.053 42; φ_ish = 1/(1 + 1.84e-9 · 138 000^1.28
    /// · 20^0.64) = 0.954 7; φ_rs = e^(−3e-8 · 20 · 3000 · 92 · √(3.1/64)) = 0.964 2;
    /// M_rr = φ_ish φ_rs G_rr 60 000^0.6 = 36.19 N mm. G_sl = 3.23e-3 · 46^−0.26 · 3000^(5/3)
    /// = 744.9; φ_bl = e^(−2.6e-8 · 60 000^1.4 · 46) = 0.002 880, μ_sl = 0.050 29;
    /// M_sl = 37.46 N mm.
    #[test]
    fn hand_worked_6206() {
        let r = skf_friction(s62(), &x6206()).unwrap();
        assert!((r.g_rr - 0.053_421).abs() < 1e-5, "{}", r.g_rr);
        assert!((r.phi_ish - 0.954_67).abs() < 1e-4, "{}", r.phi_ish);
        assert!((r.phi_rs - 0.964_21).abs() < 1e-4, "{}", r.phi_rs);
        assert!(
            (r.rolling * 1e3 - 36.19).abs() < 0.01,
            "{}",
            r.rolling * 1e3
        );
        assert!((r.g_sl - 744.88).abs() < 0.01, "{}", r.g_sl);
        assert!((r.mu_sl - 0.050_288).abs() < 1e-5, "{}", r.mu_sl);
        assert!(
            (r.sliding * 1e3 - 37.46).abs() < 0.01,
            "{}",
            r.sliding * 1e3
        );
        assert_eq!(r.total, r.rolling + r.sliding);
        assert!((r.power - r.total * 3000.0 * std::f64::consts::PI / 30.0).abs() < 1e-12);
        // Axial load: α_F = 24.6 (500/11 200)^0.24 = 11.66°, G_rr = 0.085 74,
        // G_sl = 1 162.5 by hand.
        let a = skf_friction(
            s62(),
            &SkfInputs {
                fa: 500.0,
                ..x6206()
            },
        )
        .unwrap();
        assert!((a.alpha_f.unwrap().to_degrees() - 11.665).abs() < 1e-3);
        assert!((a.g_rr - 0.085_736).abs() < 1e-5, "{}", a.g_rr);
        assert!((a.g_sl - 1162.48).abs() < 0.05, "{}", a.g_sl);
    }

    /// Load raises every load-dependent term. Viscosity raises the moment in full film
    /// (3 000 rpm, 20 .. 160 mm²/s: φ_bl < 0.003); below, in mixed lubrication, the sliding
    /// term falls as the viscosity rises (φ_bl → 1, μ_sl → μ_bl), as the source's curve
    /// of friction against ν n does.
    #[test]
    fn rises_with_load_and_viscosity() {
        for s in [s62(), &ac()] {
            let mut last = 0.0;
            for fr in [500.0, 1000.0, 2000.0, 4000.0] {
                let m = skf_friction(s, &SkfInputs { fr, ..x6206() }).unwrap().total;
                assert!(m > last, "{}: {fr} N {m}", s.name);
                last = m;
            }
            let mut last = 0.0;
            for nu in [20e-6, 40e-6, 80e-6, 160e-6] {
                let r = skf_friction(s, &SkfInputs { nu, ..x6206() }).unwrap();
                assert!(r.phi_bl < 0.003, "{}", r.phi_bl);
                assert!(r.total > last, "{}: {nu} m²/s {}", s.name, r.total);
                last = r.total;
            }
            let thin = skf_friction(
                s,
                &SkfInputs {
                    nu: 2e-6,
                    ..x6206()
                },
            )
            .unwrap();
            let thick = skf_friction(
                s,
                &SkfInputs {
                    nu: 8e-6,
                    ..x6206()
                },
            )
            .unwrap();
            assert!(thin.phi_bl > thick.phi_bl && thin.sliding > thick.sliding);
            assert!(thin.rolling < thick.rolling);
        }
    }

    /// No load: a deep-groove bearing keeps only the load-independent terms (seals, drag);
    /// an angular-contact one keeps the balls' centrifugal load as well.
    #[test]
    fn unloaded_keeps_the_load_independent_terms() {
        let seal = SealConstants::parse("0.023,2.25,2,40", "seal").unwrap();
        let drag = DragInputs::parse("0.0003,10", "drag").unwrap();
        let x = SkfInputs {
            fr: 0.0,
            fa: 0.0,
            lubrication: SkfLubrication::OilBath,
            seal: Some(seal),
            drag: Some(drag),
            ..x6206()
        };
        let r = skf_friction(s62(), &x).unwrap();
        assert_eq!((r.rolling, r.sliding), (0.0, 0.0));
        let seals = r.seals.unwrap();
        assert!((seals * 1e3 - (0.023 * 40f64.powf(2.25) + 2.0)).abs() < 1e-9);
        assert!(r.drag.unwrap() > 0.0);
        assert!((r.total - (seals + r.drag.unwrap())).abs() < 1e-15 * r.total.max(1.0));
        let loaded = skf_friction(s62(), &SkfInputs { fr: 3000.0, ..x }).unwrap();
        assert_eq!((loaded.seals, loaded.drag), (r.seals, r.drag));
        let ac = skf_friction(&ac(), &SkfInputs { fr: 0.0, ..x6206() }).unwrap();
        assert!(ac.centrifugal_load > 0.0 && ac.rolling > 0.0);
    }

    #[test]
    fn drag_rises_with_oil_level_and_speed() {
        let at = |h: &str, rpm: f64| {
            skf_friction(
                s62(),
                &SkfInputs {
                    lubrication: SkfLubrication::OilBath,
                    drag: Some(DragInputs::parse(h, "d").unwrap()),
                    speed_rpm: rpm,
                    ..x6206()
                },
            )
            .unwrap()
            .drag
            .unwrap()
        };
        assert!(at("0.0003,20", 3000.0) > at("0.0003,5", 3000.0));
        assert!(at("0.0003,10", 6000.0) > at("0.0003,10", 3000.0));
    }

    #[test]
    fn limits_and_names() {
        let e = skf_friction(
            s62(),
            &SkfInputs {
                speed_rpm: 0.0,
                ..x6206()
            },
        )
        .unwrap_err();
        assert!(e.to_string().contains("skf.speed_rpm"), "{e}");
        let e = skf_friction(
            s62(),
            &SkfInputs {
                drag: Some(DragInputs::parse("0.0003,10", "d").unwrap()),
                ..x6206()
            },
        )
        .unwrap_err();
        assert!(e.to_string().contains("skf.drag"), "{e}");
        let w = skf_friction(
            s62(),
            &SkfInputs {
                tilt: 1e-3,
                ..x6206()
            },
        )
        .unwrap();
        assert!(w.warnings[0].contains("arcmin"), "{:?}", w.warnings);
        let bath = skf_friction(
            s62(),
            &SkfInputs {
                lubrication: SkfLubrication::OilBath,
                ..x6206()
            },
        )
        .unwrap();
        assert!(bath.drag.is_none() && bath.warnings[0].contains("--skf-drag"));
        assert_eq!(series_of("6312").unwrap().name, "63");
        assert!(series_of("7205B").is_none() && series_of("6805").is_none());
        assert!(
            SkfSeries::given("1,2,3,4,5", SkfKind::AngularContact, "--skf-constants")
                .unwrap_err()
                .to_string()
                .contains("--skf-constants")
        );
        assert!(series_of("acbb16").is_none());
        assert!(SealConstants::parse("1,2,3", "--skf-seal")
            .unwrap_err()
            .to_string()
            .contains("--skf-seal"));
        assert!(SkfLubrication::parse("mist", "--skf-lubrication").is_err());
    }
}
