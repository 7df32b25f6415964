//! Load ratings, rating life, static safety and the warnings a bearing engineer expects
//! beside a quasi-static answer.
//!
//! What is implemented (single-row deep-groove and angular-contact ball bearings of
//! through-hardened bearing steel):
//!
//! - **Basic dynamic load rating** `C` (ISO 281:2007 §6.1.1, eq. (2) and (3)):
//!   `C = bm fc (i cos α)^0.7 Z^(2/3) Dw^1.8` for `Dw ≤ 25.4 mm`,
//!   `C = 3.647 bm fc (i cos α)^0.7 Z^(2/3) Dw^1.4` above (N, mm), `bm = 1.3` (Table 1),
//!   `fc` from Table 2 (column "single-row radial contact groove and single- and double-row
//!   angular contact groove ball bearings") by linear interpolation in
//!   `Dw cos α / Dpw`, as the standard allows. The table is valid for groove radii up to
//!   `0.52 Dw` (inner) and `0.53 Dw` (outer); for larger radii the standard asks for "a
//!   correspondingly reduced fc", which we take as the ratio of the Lundberg–Palmgren
//!   conformity factor ([`lp_conformity`]) at the bearing's radii to that at 0.52/0.53,
//!   never above 1.
//! - **Basic static load rating** `C0 = f0 i Z Dw² cos α` (ISO 76:2006 eq. (1)), `f0` from
//!   its Table 2 by linear interpolation. Its values correspond to a 4 200 MPa contact
//!   pressure at the most heavily loaded contact (tested against our own Hertz solution);
//!   for grooves wider than 0.52/0.53 Dw `f0` is recomputed from that pressure
//!   ([`static_groove_factor`]).
//! - **Equivalent loads** `P = X Fr + Y Fa` (ISO 281 Table 3, single row, normal clearance;
//!   `e`, `Y` interpolated in `f0 Fa / C0`, and between the tabulated contact angles) and
//!   `P0 = max(X0 Fr + Y0 Fa, Fr)` (ISO 76 Table 3).
//! - **Basic rating life** `L10 = (C/P)^3` million revolutions, in hours `L10 10^6/(60 n)`.
//! - **Reference rating life from the per-ball loads** in the Lundberg–Palmgren form that
//!   ISO/TS 16281:2008 uses for ball bearings: a basic dynamic load rating of each raceway
//!   `Qc`, the dynamic equivalent ball load of the rotating (inner) raceway
//!   `Qe = (Σ Q³ / Z)^(1/3)` and of the stationary (outer) one `Qe = (Σ Q^(10/3) / Z)^0.3`,
//!   the raceway lives `L = (Qc/Qe)^3` and the bearing life
//!   `L = (Li^(-10/9) + Lo^(-10/9))^(-9/10)`. `Qc` is Harris & Kotzalas's (Vol. 2 §11.3)
//!   `Qc = A (2f/(2f-1))^0.41 (1 ∓ γ)^1.39 / (1 ± γ)^(1/3) (Dw/Dpw)^0.3 Dw^1.8 Z^(-1/3)`
//!   (upper signs inner) with `A = bm 38.2 / 0.407`: the factor `38.2` is the constant for
//!   which the Lundberg–Palmgren `fc` reproduces ISO 281's Table 2 (within its rounding,
//!   tested), and `0.407` is the bearing-to-raceway factor of the same derivation, so that
//!   the per-ball life falls back on ISO 281's under its own assumptions.
//!   Left out: the TS's stress-based `a_ISO` per slice (we use the whole-bearing `a_ISO`
//!   of ISO 281 below) and its tilt/edge-stress treatment of roller bearings.
//! - **Life modification factor** `a_ISO` (ISO 281:2007 §9.3.2, eq. (16)–(18) for ball
//!   bearings) from the viscosity ratio κ and the contamination factor `eC`, with the
//!   fatigue load limit `Cu = C0/22` (`× (100/Dpw)^0.5` above 100 mm pitch diameter;
//!   ISO 281 Annex B's approximation); κ is clipped to 4 and `a_ISO` to 50 as the standard
//!   says; κ < 0.1 is outside it and gives no value.
//! - **Static safety** `S0 = C0/P0` and the peak Hertz pressure against ISO 76's limit
//!   (4 200 MPa for ball bearings, 4 600 MPa self-aligning).
//!
//! The warnings ([`Warning`]) are what a user should not be left to discover: pressure
//! beyond the static limit, a contact ellipse that runs over the groove shoulder, fewer
//! than two loaded balls, κ < 1.

pub mod lamina_life;
pub mod roller;

use crate::error::{Error, Result};
use crate::geometry::{Bearing, BearingKind};
use crate::models::quasi_static::Solution;
use serde::Serialize;
use std::fmt::Write;

/// ISO 76 permissible peak contact pressure for ball bearings (other than self-aligning), Pa.
pub const STATIC_PRESSURE_LIMIT: f64 = 4200e6;
/// ISO 76 permissible peak contact pressure for self-aligning ball bearings, Pa.
pub const STATIC_PRESSURE_LIMIT_SELF_ALIGNING: f64 = 4600e6;
/// `bm` of ISO 281 Table 1 for radial and angular contact groove ball bearings (not
/// filling-slot).
pub const BM: f64 = 1.3;
/// The constant of the Lundberg–Palmgren `fc` that reproduces ISO 281 Table 2 (N, mm).
pub const FC_CONSTANT: f64 = 38.2;
/// Shoulder height assumed for the groove edges of a deep-groove bearing (the bearing
/// data carry none), as a fraction of `Dw`: an assumption (typical proportions of
/// deep-groove rings), not a standard's value.
pub const ASSUMED_SHOULDER_HEIGHT: f64 = 0.2;
/// The same for the thrust-side shoulder of an angular-contact bearing, which is made
/// higher to carry the axial load: also an assumption.
pub const ASSUMED_SHOULDER_HEIGHT_AC: f64 = 0.3;

/// ISO 281:2007 Table 2, `fc` at `Dw cos α / Dpw = 0.01, 0.02, .., 0.40` (single-row radial
/// and angular contact groove ball bearings).
const FC_TABLE: [f64; 40] = [
    29.1, 35.8, 40.3, 43.8, 46.7, 49.1, 51.1, 52.8, 54.3, 55.5, 56.6, 57.5, 58.2, 58.8, 59.3, 59.6,
    59.8, 59.9, 60.0, 59.9, 59.8, 59.6, 59.3, 59.0, 58.6, 58.2, 57.7, 57.1, 56.6, 56.0, 55.3, 54.6,
    53.9, 53.2, 52.4, 51.7, 50.9, 50.0, 49.2, 48.4,
];

/// ISO 76:2006 Table 2, `f0` at `Dw cos α / Dpw = 0, 0.01, .., 0.40` (radial and angular
/// contact groove ball bearings).
const F0_TABLE: [f64; 41] = [
    14.7, 14.9, 15.1, 15.3, 15.5, 15.7, 15.9, 16.1, 16.3, 16.5, 16.4, 16.1, 15.9, 15.6, 15.4, 15.2,
    14.9, 14.7, 14.4, 14.2, 14.0, 13.7, 13.5, 13.2, 13.0, 12.8, 12.5, 12.3, 12.1, 11.8, 11.6, 11.4,
    11.2, 10.9, 10.7, 10.5, 10.3, 10.0, 9.8, 9.6, 9.4,
];

/// Linear interpolation in a table sampled at `x0, x0 + dx, ..`; `None` outside it.
fn interp(table: &[f64], x0: f64, dx: f64, x: f64) -> Option<f64> {
    let t = (x - x0) / dx;
    let n = table.len() - 1;
    if !(t >= -1e-9 && t <= n as f64 + 1e-9) {
        return None;
    }
    let t = t.clamp(0.0, n as f64);
    let k = (t.floor() as usize).min(n - 1);
    let w = t - k as f64;
    Some(table[k] * (1.0 - w) + table[k + 1] * w)
}

/// Linear interpolation in `(x, y)` rows sorted by `x`, clamped at the ends.
fn interp_rows(rows: &[(f64, f64, f64)], x: f64) -> (f64, f64) {
    if x <= rows[0].0 {
        return (rows[0].1, rows[0].2);
    }
    for w in rows.windows(2) {
        if x <= w[1].0 {
            let t = (x - w[0].0) / (w[1].0 - w[0].0);
            return (
                w[0].1 + t * (w[1].1 - w[0].1),
                w[0].2 + t * (w[1].2 - w[0].2),
            );
        }
    }
    let l = rows[rows.len() - 1];
    (l.1, l.2)
}

/// `Dw cos α / Dpw` of a bearing at its nominal contact angle.
pub fn gamma(b: &Bearing) -> f64 {
    b.d * b.nominal_contact_angle().cos() / b.dm
}

/// ISO 281 Table 2 `fc` at `gamma = Dw cos α / Dpw` (N, mm units of eq. (2)).
pub fn fc(gamma: f64) -> Result<f64> {
    interp(&FC_TABLE, 0.01, 0.01, gamma).ok_or_else(|| {
        Error::invalid(
            "Dw cos(alpha)/Dpw",
            format!("{gamma:.4}"),
            "in [0.01, 0.40] (ISO 281 Table 2)",
        )
    })
}

/// ISO 76 Table 2 `f0` at `gamma = Dw cos α / Dpw` (N/mm²).
pub fn f0(gamma: f64) -> Result<f64> {
    interp(&F0_TABLE, 0.0, 0.01, gamma).ok_or_else(|| {
        Error::invalid(
            "Dw cos(alpha)/Dpw",
            format!("{gamma:.4}"),
            "in [0, 0.40] (ISO 76 Table 2)",
        )
    })
}

/// The conformity-dependent factor of the Lundberg–Palmgren `fc` (Harris & Kotzalas
/// Vol. 2 eq. (11.x), ISO/TR 1281-1):
/// `[1 + (1.04 ((1-γ)/(1+γ))^1.72 (fi (2fo-1) / (fo (2fi-1)))^0.41)^(10/3)]^(-0.3)
///  (2fi/(2fi-1))^0.41`.
pub fn lp_conformity(gamma: f64, fi: f64, fo: f64) -> f64 {
    let g = (1.0 - gamma) / (1.0 + gamma);
    let r = fi * (2.0 * fo - 1.0) / (fo * (2.0 * fi - 1.0));
    let bracket = 1.0 + (1.04 * g.powf(1.72) * r.powf(0.41)).powf(10.0 / 3.0);
    bracket.powf(-0.3) * (2.0 * fi / (2.0 * fi - 1.0)).powf(0.41)
}

/// The Lundberg–Palmgren `fc` with [`FC_CONSTANT`]:
/// `38.2 lp_conformity γ^0.3 (1-γ)^1.39 / (1+γ)^(1/3)`.
pub fn fc_lundberg_palmgren(gamma: f64, fi: f64, fo: f64) -> f64 {
    FC_CONSTANT * lp_conformity(gamma, fi, fo) * gamma.powf(0.3) * (1.0 - gamma).powf(1.39)
        / (1.0 + gamma).powf(1.0 / 3.0)
}

/// Reduction of `fc` for groove radii larger than ISO 281's 0.52 Dw (inner) / 0.53 Dw
/// (outer): the ratio of [`lp_conformity`] at the bearing's radii to that at 0.52/0.53,
/// at most 1 (a closer conformity does "not necessarily" raise the rating).
pub fn conformity_reduction(gamma: f64, fi: f64, fo: f64) -> f64 {
    (lp_conformity(gamma, fi.max(0.52), fo.max(0.53)) / lp_conformity(gamma, 0.52, 0.53)).min(1.0)
}

/// Basic load ratings of a bearing (N).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LoadRatings {
    /// `Dw cos α / Dpw`.
    pub gamma: f64,
    /// `fc` of ISO 281 Table 2 (after the conformity reduction).
    pub fc: f64,
    /// Conformity reduction applied to `fc` (1: none).
    pub fc_reduction: f64,
    /// `f0` of ISO 76 Table 2 (times [`static_groove_factor`] for wide grooves).
    pub f0: f64,
    /// Basic dynamic radial load rating `C`, N.
    pub c: f64,
    /// Basic static radial load rating `C0`, N.
    pub c0: f64,
    /// Fatigue load limit `Cu`, N (ISO 281 Annex B approximation).
    pub cu: f64,
}

/// ISO 281 / ISO 76 ratings from the internal geometry (module docs). The contact angle is
/// the nominal one (0 for deep-groove, the free angle for angular-contact).
pub fn load_ratings(b: &Bearing) -> Result<LoadRatings> {
    let alpha = b.nominal_contact_angle();
    let g = gamma(b);
    let red = conformity_reduction(g, b.fi(), b.fo());
    let fc = fc(g)? * red;
    let f0 = f0(g)? * static_groove_factor(g, b.fi(), b.fo());
    let dw = b.d * 1e3;
    let dpw = b.dm * 1e3;
    let z = b.z as f64;
    let ca = alpha.cos();
    let c = if dw <= 25.4 {
        BM * fc * ca.powf(0.7) * z.powf(2.0 / 3.0) * dw.powf(1.8)
    } else {
        3.647 * BM * fc * ca.powf(0.7) * z.powf(2.0 / 3.0) * dw.powf(1.4)
    };
    let c0 = f0 * z * dw * dw * ca;
    let cu = if dpw <= 100.0 {
        c0 / 22.0
    } else {
        c0 / 22.0 * (100.0 / dpw).sqrt()
    };
    Ok(LoadRatings {
        gamma: g,
        fc,
        fc_reduction: red,
        f0,
        c,
        c0,
        cu,
    })
}

/// ISO 281 Table 3 factors `(X, Y, e)` for a single-row bearing and the combined load
/// `(Fr, Fa)` (N). Deep-groove: `e`, `Y` interpolated in `f0 Fa/C0r`; angular-contact:
/// by contact angle (15° also in `f0 Fa/C0r`), linearly between the tabulated angles,
/// clamped to 15°..45°.
pub fn dynamic_factors(b: &Bearing, r: &LoadRatings, fr: f64, fa: f64) -> (f64, f64, f64) {
    // (f0 Fa / C0r, e, Y)
    const DG: [(f64, f64, f64); 9] = [
        (0.172, 0.19, 2.30),
        (0.345, 0.22, 1.99),
        (0.689, 0.26, 1.71),
        (1.03, 0.28, 1.55),
        (1.38, 0.30, 1.45),
        (2.07, 0.34, 1.31),
        (3.45, 0.38, 1.15),
        (5.17, 0.42, 1.04),
        (6.89, 0.44, 1.00),
    ];
    const AC15: [(f64, f64, f64); 9] = [
        (0.178, 0.38, 1.47),
        (0.357, 0.40, 1.40),
        (0.714, 0.43, 1.30),
        (1.07, 0.46, 1.23),
        (1.43, 0.47, 1.19),
        (2.14, 0.50, 1.12),
        (3.57, 0.55, 1.02),
        (5.35, 0.56, 1.00),
        (7.14, 0.56, 1.00),
    ];
    // (alpha deg, e, X, Y) for 20° .. 45°.
    const AC: [(f64, f64, f64, f64); 6] = [
        (20.0, 0.57, 0.43, 1.00),
        (25.0, 0.68, 0.41, 0.87),
        (30.0, 0.80, 0.39, 0.76),
        (35.0, 0.95, 0.37, 0.66),
        (40.0, 1.14, 0.35, 0.57),
        (45.0, 1.34, 0.33, 0.50),
    ];
    let rel = r.f0 * fa.abs() / r.c0;
    let (e, x_over, y_over) = match b.kind {
        BearingKind::DeepGroove => {
            let (e, y) = interp_rows(&DG, rel);
            (e, 0.56, y)
        }
        BearingKind::AngularContact => {
            let a = b.alpha0.to_degrees().clamp(15.0, 45.0);
            let (e15, y15) = interp_rows(&AC15, rel);
            // A fixed array, not a Vec: the co-simulation outputs call this every step.
            let mut rows = [(15.0, e15, 0.44, y15); 7];
            rows[1..].copy_from_slice(&AC);
            let k = rows
                .windows(2)
                .position(|w| a <= w[1].0)
                .unwrap_or(rows.len() - 2);
            let (lo, hi) = (rows[k], rows[k + 1]);
            let t = (a - lo.0) / (hi.0 - lo.0);
            let l = |u: f64, v: f64| u + t * (v - u);
            (l(lo.1, hi.1), l(lo.2, hi.2), l(lo.3, hi.3))
        }
    };
    if fr <= 0.0 || fa.abs() / fr > e {
        (x_over, y_over, e)
    } else {
        (1.0, 0.0, e)
    }
}

/// ISO 76 Table 3 `(X0, Y0)` for a single-row bearing.
pub fn static_factors(b: &Bearing) -> (f64, f64) {
    match b.kind {
        BearingKind::DeepGroove => (0.6, 0.5),
        BearingKind::AngularContact => {
            const Y0: [(f64, f64, f64); 7] = [
                (15.0, 0.46, 0.0),
                (20.0, 0.42, 0.0),
                (25.0, 0.38, 0.0),
                (30.0, 0.33, 0.0),
                (35.0, 0.29, 0.0),
                (40.0, 0.26, 0.0),
                (45.0, 0.22, 0.0),
            ];
            (0.5, interp_rows(&Y0, b.alpha0.to_degrees()).0)
        }
    }
}

/// What a rating needs beyond the bearing and its loads.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct LifeInputs {
    /// Shaft speed, rpm (the inner ring turns, the outer ring is fixed); 0: no hours.
    pub speed_rpm: f64,
    /// Viscosity ratio κ = ν/ν1 at the operating temperature, when known.
    pub kappa: Option<f64>,
    /// Contamination factor `eC` of ISO 281 Table 13 (0..1), when known.
    pub contamination: Option<f64>,
}

/// ISO 281 §9.3.2 life modification factor for ball bearings (eq. (16)–(18)); `None` for
/// κ < 0.1 (outside the standard). κ above 4 is taken as 4; the result is capped at 50.
pub fn a_iso(kappa: f64, ec: f64, cu: f64, p: f64) -> Option<f64> {
    if kappa.is_nan() || kappa < 0.1 || p.is_nan() || p <= 0.0 {
        return None;
    }
    let k = kappa.min(4.0);
    let inner = if k < 0.4 {
        2.5671 - 2.2649 / k.powf(0.054381)
    } else if k < 1.0 {
        2.5671 - 1.9987 / k.powf(0.19087)
    } else {
        2.5671 - 1.9987 / k.powf(0.071739)
    };
    let arg = 1.0 - inner.powf(0.83) * (ec * cu / p).powf(1.0 / 3.0);
    if arg <= 0.0 {
        return Some(50.0);
    }
    Some((0.1 * arg.powf(-9.3)).min(50.0))
}

/// Hours from millions of revolutions at `speed_rpm` (`None` at standstill).
fn hours(mrev: f64, speed_rpm: f64) -> Option<f64> {
    (speed_rpm > 0.0 && mrev.is_finite()).then(|| mrev * 1e6 / (60.0 * speed_rpm))
}

/// A condition the user should know about.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Warning {
    /// The peak contact pressure exceeds ISO 76's static limit.
    PressureAboveStaticLimit {
        /// Peak pressure, Pa.
        pressure: f64,
        /// The limit, Pa.
        limit: f64,
        /// Ball index and race of the peak.
        ball: usize,
        /// `inner` or `outer`.
        race: &'static str,
    },
    /// The contact ellipse runs over the groove shoulder.
    EllipseTruncated {
        /// Ball index.
        ball: usize,
        /// `inner` or `outer`.
        race: &'static str,
        /// Contact angle plus the ellipse's angular half-width, rad.
        edge_angle: f64,
        /// Groove shoulder angle, rad.
        shoulder_angle: f64,
    },
    /// Fewer than two balls carry load.
    FewLoadedBalls {
        /// Balls with a positive inner contact load.
        count: usize,
    },
    /// The lubricant film does not separate the surfaces well (κ < 1).
    KappaBelowOne {
        /// κ.
        kappa: f64,
    },
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Warning::PressureAboveStaticLimit {
                pressure,
                limit,
                ball,
                race,
            } => write!(
                f,
                "peak contact pressure {:.0} MPa (ball {ball}, {race} race) exceeds the ISO 76 static limit {:.0} MPa: permanent deformation beyond 0.0001 Dw",
                pressure * 1e-6,
                limit * 1e-6
            ),
            Warning::EllipseTruncated {
                ball,
                race,
                edge_angle,
                shoulder_angle,
            } => write!(
                f,
                "contact ellipse of ball {ball} ({race} race) reaches {:.1} deg, beyond the groove shoulder at {:.1} deg (assumed shoulder height, raceway::ratings::shoulder_angles): the ellipse is truncated (edge loading; Hertz theory does not hold)",
                edge_angle.to_degrees(),
                shoulder_angle.to_degrees()
            ),
            Warning::FewLoadedBalls { count } => write!(
                f,
                "{count} loaded ball(s): the ring is not located by the rolling elements (life and stiffness are not meaningful)"
            ),
            Warning::KappaBelowOne { kappa } => write!(
                f,
                "viscosity ratio kappa = {kappa:.2} < 1: the film does not separate the surfaces (ISO 281 a_ISO reduced)"
            ),
        }
    }
}

/// Ratings, life and safety of one quasi-static equilibrium.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Assessment {
    /// Load ratings of the bearing.
    pub ratings: LoadRatings,
    /// Radial load `Fr` on the bearing, N.
    pub radial_load: f64,
    /// Axial load `Fa`, N.
    pub axial_load: f64,
    /// Dynamic equivalent load `P`, N (ISO 281).
    pub p: f64,
    /// Factors `(X, Y, e)` used for `P`.
    pub xye: [f64; 3],
    /// Static equivalent load `P0`, N (ISO 76).
    pub p0: f64,
    /// Basic rating life `L10 = (C/P)^3`, millions of revolutions (`None` at zero load).
    pub l10_mrev: Option<f64>,
    /// `L10` in hours at the speed (`None` at standstill or zero load).
    pub l10_hours: Option<f64>,
    /// Reference rating life from the per-ball loads (module docs), millions of revolutions.
    pub l10r_mrev: Option<f64>,
    /// The same in hours.
    pub l10r_hours: Option<f64>,
    /// Inner and outer raceway lives, millions of revolutions.
    pub raceway_lives_mrev: [Option<f64>; 2],
    /// `a_ISO` from κ and `eC` (`None` when either is not given or κ < 0.1).
    pub a_iso: Option<f64>,
    /// Modified reference rating life `a_ISO L10r`, hours.
    pub l10mr_hours: Option<f64>,
    /// Static safety factor `S0 = C0/P0` (`None` at zero load).
    pub s0: Option<f64>,
    /// Peak contact pressure over every ball and race, Pa.
    pub peak_pressure: f64,
    /// Static pressure limit used, Pa.
    pub pressure_limit: f64,
    /// `peak_pressure / pressure_limit`.
    pub pressure_limit_ratio: f64,
    /// Balls with a positive inner contact load.
    pub loaded_balls: usize,
    /// Warnings (empty: none).
    pub warnings: Vec<Warning>,
}

/// Groove shoulder angles `(inner, outer)` measured from the groove bottom (radial
/// direction), rad, from [`ASSUMED_SHOULDER_HEIGHT`] (deep-groove) or
/// [`ASSUMED_SHOULDER_HEIGHT_AC`] (angular-contact): `acos(1 - h/(f Dw))`.
pub fn shoulder_angles(b: &Bearing) -> (f64, f64) {
    let h = match b.kind {
        BearingKind::DeepGroove => ASSUMED_SHOULDER_HEIGHT,
        BearingKind::AngularContact => ASSUMED_SHOULDER_HEIGHT_AC,
    } * b.d;
    let ang = |f: f64| (1.0 - h / (f * b.d)).clamp(-1.0, 1.0).acos();
    (ang(b.fi()), ang(b.fo()))
}

/// Per-raceway basic dynamic load ratings `(Qci, Qco)`, N (module docs).
pub fn raceway_ratings(b: &Bearing) -> (f64, f64) {
    let g = gamma(b);
    let dw = b.d * 1e3;
    let z = b.z as f64;
    let a = BM * FC_CONSTANT / 0.407;
    let size = if dw <= 25.4 {
        dw.powf(1.8)
    } else {
        3.647 * dw.powf(1.4)
    };
    let common = a * (b.d / b.dm).powf(0.3) * size * z.powf(-1.0 / 3.0);
    let conf = |f: f64| (2.0 * f / (2.0 * f - 1.0)).powf(0.41);
    let qci = common * conf(b.fi()) * (1.0 - g).powf(1.39) / (1.0 + g).powf(1.0 / 3.0);
    let qco = common * conf(b.fo()) * (1.0 + g).powf(1.39) / (1.0 - g).powf(1.0 / 3.0);
    (qci, qco)
}

/// Rate a quasi-static equilibrium: ratings, ISO 281 life from the external load, the
/// reference life from the per-ball loads, static safety, peak pressure, warnings.
pub fn assess(b: &Bearing, sol: &Solution, inputs: &LifeInputs) -> Result<Assessment> {
    let r = load_ratings(b)?;
    // The forces the bearing carries: the external load plus what the support adds on
    // held coordinates (zero when nothing is held). ISO 281's P has no moment term: a
    // reaction moment on held tilts enters the per-ball life below, not P.
    let carried = |i: usize| sol.load[i] + sol.reaction[i];
    let fr = carried(0).hypot(carried(1));
    let fa = carried(2).abs();
    let (x, y, e) = dynamic_factors(b, &r, fr, fa);
    let p = x * fr + y * fa;
    let (x0, y0) = static_factors(b);
    let p0 = (x0 * fr + y0 * fa).max(fr);
    let l10 = (p > 0.0).then(|| (r.c / p).powi(3));
    let s0 = (p0 > 0.0).then(|| r.c0 / p0);

    // Per-ball life (inner ring rotating).
    let (qci, qco) = raceway_ratings(b);
    let z = sol.balls.len().max(1) as f64;
    let qei = (sol
        .balls
        .iter()
        .map(|q| q.q_i.max(0.0).powi(3))
        .sum::<f64>()
        / z)
        .cbrt();
    let qeo = (sol
        .balls
        .iter()
        .map(|q| q.q_o.max(0.0).powf(10.0 / 3.0))
        .sum::<f64>()
        / z)
        .powf(0.3);
    let li = (qei > 0.0).then(|| (qci / qei).powi(3));
    let lo = (qeo > 0.0).then(|| (qco / qeo).powi(3));
    let l10r = match (li, lo) {
        (Some(li), Some(lo)) => Some((li.powf(-10.0 / 9.0) + lo.powf(-10.0 / 9.0)).powf(-0.9)),
        _ => None,
    };
    let a = match (inputs.kappa, inputs.contamination) {
        (Some(k), Some(ec)) => a_iso(k, ec, r.cu, p),
        _ => None,
    };

    let mut warnings = Vec::new();
    let mut peak = (0.0, 0, "inner");
    let (shi, sho) = shoulder_angles(b);
    let mut loaded = 0;
    for (j, ball) in sol.balls.iter().enumerate() {
        if ball.q_i > 0.0 {
            loaded += 1;
        }
        for (race, pr, q, alpha, a_semi, f, shoulder) in [
            (
                "inner",
                ball.p_i,
                ball.q_i,
                ball.alpha_i,
                ball.a_i,
                b.fi(),
                shi,
            ),
            (
                "outer",
                ball.p_o,
                ball.q_o,
                ball.alpha_o,
                ball.a_o,
                b.fo(),
                sho,
            ),
        ] {
            if pr > peak.0 {
                peak = (pr, j, race);
            }
            // The ellipse's half-width `a` across the rolling direction spans the angle
            // a/(f Dw) on the groove radius f Dw.
            let edge = alpha.abs() + a_semi / (f * b.d);
            if q > 0.0 && edge > shoulder {
                warnings.push(Warning::EllipseTruncated {
                    ball: j,
                    race,
                    edge_angle: edge,
                    shoulder_angle: shoulder,
                });
            }
        }
    }
    let limit = STATIC_PRESSURE_LIMIT;
    if peak.0 > limit {
        warnings.insert(
            0,
            Warning::PressureAboveStaticLimit {
                pressure: peak.0,
                limit,
                ball: peak.1,
                race: peak.2,
            },
        );
    }
    if loaded <= 1 {
        warnings.push(Warning::FewLoadedBalls { count: loaded });
    }
    if let Some(k) = inputs.kappa {
        if k < 1.0 {
            warnings.push(Warning::KappaBelowOne { kappa: k });
        }
    }
    let l10r_hours = l10r.and_then(|l| hours(l, inputs.speed_rpm));
    Ok(Assessment {
        ratings: r,
        radial_load: fr,
        axial_load: fa,
        p,
        xye: [x, y, e],
        p0,
        l10_mrev: l10,
        l10_hours: l10.and_then(|l| hours(l, inputs.speed_rpm)),
        l10r_mrev: l10r,
        l10r_hours,
        raceway_lives_mrev: [li, lo],
        a_iso: a,
        l10mr_hours: match (a, l10r_hours) {
            (Some(a), Some(h)) => Some(a * h),
            _ => None,
        },
        s0,
        peak_pressure: peak.0,
        pressure_limit: limit,
        pressure_limit_ratio: peak.0 / limit,
        loaded_balls: loaded,
        warnings,
    })
}

fn opt(v: Option<f64>, prec: usize) -> String {
    match v {
        Some(x) if x >= 1e7 => format!("{x:.3e}"),
        Some(x) if x < 10.0 => format!("{x:.3}"),
        Some(x) => format!("{x:.prec$}"),
        None => "-".into(),
    }
}

/// The ratings block shared by `quasi-static` (text) and `bearings NAME`.
fn ratings_text(s: &mut String, r: &LoadRatings) {
    let _ = writeln!(
        s,
        "ISO 281/76 ratings:               C {:.0} N  C0 {:.0} N  Cu {:.0} N  (Dw cos a/Dpw {:.4}, fc {:.2}{}, f0 {:.2})",
        r.c,
        r.c0,
        r.cu,
        r.gamma,
        r.fc,
        if r.fc_reduction < 1.0 {
            format!(" incl. conformity reduction {:.3}", r.fc_reduction)
        } else {
            String::new()
        },
        r.f0
    );
}

/// Text lines of an [`Assessment`] (life, safety, pressure, warnings).
fn assessment_text(s: &mut String, a: &Assessment) {
    ratings_text(s, &a.ratings);
    let _ = writeln!(
        s,
        "equivalent loads:                 P {:.1} N (X {:.2} Y {:.2} e {:.3})  P0 {:.1} N  (Fr {:.1} N, Fa {:.1} N)",
        a.p, a.xye[0], a.xye[1], a.xye[2], a.p0, a.radial_load, a.axial_load
    );
    let _ = writeln!(
        s,
        "life:                             L10 {} Mrev = {} h (ISO 281, (C/P)^3);  L10r {} Mrev = {} h (per-ball loads, inner {} / outer {} Mrev)",
        opt(a.l10_mrev, 1),
        opt(a.l10_hours, 0),
        opt(a.l10r_mrev, 1),
        opt(a.l10r_hours, 0),
        opt(a.raceway_lives_mrev[0], 1),
        opt(a.raceway_lives_mrev[1], 1)
    );
    if a.a_iso.is_some() {
        let _ = writeln!(
            s,
            "modified life:                    a_ISO {}  L10mr {} h",
            opt(a.a_iso, 3),
            opt(a.l10mr_hours, 0)
        );
    }
    let _ = writeln!(
        s,
        "static safety:                    S0 = C0/P0 {}  peak contact pressure {:.0} MPa = {:.3} x the ISO 76 limit {:.0} MPa;  loaded balls {}",
        opt(a.s0, 2),
        a.peak_pressure * 1e-6,
        a.pressure_limit_ratio,
        a.pressure_limit * 1e-6,
        a.loaded_balls
    );
    if a.warnings.is_empty() {
        let _ = writeln!(s, "warnings:                         none");
    }
    for w in &a.warnings {
        let _ = writeln!(s, "WARNING: {w}");
    }
}

impl LoadRatings {
    /// One text line: C, C0, Cu and the factors.
    pub fn text(&self) -> String {
        let mut s = String::new();
        ratings_text(&mut s, self);
        s
    }
}

impl Assessment {
    /// Text lines (edge units: N, MPa, hours) with one `WARNING:` line per warning, as
    /// `raceway quasi-static` and `raceway run`'s summary print them.
    pub fn text(&self) -> String {
        let mut s = String::new();
        assessment_text(&mut s, self);
        s
    }

    /// The warnings as sentences.
    pub fn warning_texts(&self) -> Vec<String> {
        self.warnings.iter().map(|w| w.to_string()).collect()
    }
}

/// Solve the quasi-static equilibrium of `b` under the external `load` on the inner ring
/// `(Fx, Fy, Fz, Mx, My)` (N, N m) at `inputs.speed_rpm` and rate it: what a run summary
/// calls with the mean load of a run.
pub fn assess_load(b: &Bearing, load: &[f64; 5], inputs: &LifeInputs) -> Result<Assessment> {
    let m = crate::models::quasi_static::QuasiStatic::new(
        b,
        crate::models::quasi_static::Options::default(),
    )?;
    let sol = m.solve(load, crate::units::rpm_to_rad_s(inputs.speed_rpm))?;
    assess(b, &sol, inputs)
}

/// Ratings at the mean load of a recorded run: `load` is the load on the inner ring (minus
/// the run's mean bearing force `(force.x, force.y, force.z, moment.x, moment.y)`), solved
/// again at the quasi-static level at the shaft speed `omega` (rad/s; the run's last). What
/// `raceway run` puts in its summary (the run's means are taken by the summary).
pub fn assess_run(b: &Bearing, load: &[f64; 5], omega: f64) -> Result<Assessment> {
    b.groove("the run's rating summary (the roller bearing's S0 and L10 are in the series)")?;
    let inputs = LifeInputs {
        speed_rpm: crate::units::rad_s_to_rpm(omega.abs()),
        ..LifeInputs::default()
    };
    assess_load(b, load, &inputs)
}

/// Correction of ISO 76's `f0` for groove radii larger than 0.52 Dw (inner) / 0.53 Dw
/// (outer), where its Table 2 does not apply: ISO 76:2006 §5.1 defines `C0` by the 4 200 MPa
/// contact pressure at the most heavily loaded contact, so `f0` scales with the ball load
/// that reaches a given Hertz pressure, `Q ∝ (p0 / E*)³ / f(ΣρN)`. The factor is the ratio of
/// that load at the bearing's radii to the one at 0.52/0.53 (the smaller of the two races in
/// each case); radii closer than 0.52/0.53 keep the table value (factor 1), as the standard
/// gives no increase for them. Independent of the elastic constants.
pub fn static_groove_factor(gamma: f64, fi: f64, fo: f64) -> f64 {
    use crate::contact::{Curvature, PointContact, Race};
    if fi <= 0.52 && fo <= 0.53 {
        return 1.0;
    }
    let dm = if gamma > 0.0 { 1.0 / gamma } else { 1e3 };
    let q_at = |race: Race, f: f64| {
        let c = PointContact::new(Curvature::ball_race(1.0, dm, 0.0, f, race), 1.0);
        (1.0 / c.peak_pressure(1.0)).powi(3)
    };
    let load = |fi: f64, fo: f64| q_at(Race::Inner, fi).min(q_at(Race::Outer, fo));
    (load(fi.max(0.52), fo.max(0.53)) / load(0.52, 0.53)).min(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{Curvature, PointContact, Race};
    use crate::geometry::{preset, BearingSpec};
    use crate::models::quasi_static::{Options, QuasiStatic};

    fn bearing(name: &str) -> Bearing {
        preset(name).unwrap().build().unwrap()
    }

    fn solve(b: &Bearing, load: [f64; 5]) -> Solution {
        QuasiStatic::new(b, Options::default())
            .unwrap()
            .solve(&load, 0.0)
            .unwrap()
    }

    /// Assessment at standstill without lubrication data.
    fn rate(b: &Bearing, load: [f64; 5]) -> Assessment {
        assess(b, &solve(b, load), &LifeInputs::default()).unwrap()
    }

    fn truncated(a: &Assessment) -> bool {
        a.warnings
            .iter()
            .any(|w| matches!(w, Warning::EllipseTruncated { .. }))
    }

    /// The transcribed ISO 281 Table 2 is the Lundberg–Palmgren `fc` (fi = fo = 0.52, the
    /// conformity ISO/TR 1281-1 gives for the table) times one constant, within the
    /// table's rounding: a typo in the table would show here.
    #[test]
    fn fc_table_is_lundberg_palmgren_within_rounding() {
        for k in 1..=40 {
            let g = 0.01 * k as f64;
            let t = fc(g).unwrap();
            let f = fc_lundberg_palmgren(g, 0.52, 0.52);
            assert!(
                (t / f - 1.0).abs() < 0.004,
                "gamma {g}: table {t} formula {f}"
            );
        }
        assert!(fc(0.005).is_err() && fc(0.41).is_err());
        assert!((fc(0.205).unwrap() - 59.85).abs() < 1e-9);
    }

    /// ISO 76's f0 is the load at which the most heavily loaded contact reaches 4 200 MPa
    /// with `Qmax = 5 Fr / (Z cos α)`, ri = 0.52 Dw, re = 0.53 Dw: `f0 = Qmax / (5 Dw²)`.
    /// Checked against our own Hertz solution (steel, E = 208 GPa, ν = 0.3).
    #[test]
    fn f0_table_is_4200_mpa_hertz() {
        let b = bearing("6205");
        let e = b.e_eff_inner();
        let dw = 10e-3;
        for k in 0..=40 {
            let g = 0.01 * k as f64;
            let dm = if g > 0.0 { dw / g } else { 1e3 };
            let q_at = |race: Race, f: f64| {
                let c = PointContact::new(Curvature::ball_race(dw, dm, 0.0, f, race), e);
                1000.0 * (STATIC_PRESSURE_LIMIT / c.peak_pressure(1000.0)).powi(3)
            };
            let q = q_at(Race::Inner, 0.52).min(q_at(Race::Outer, 0.53));
            let f0_hertz = q / (5.0 * 100.0);
            let t = f0(g).unwrap();
            assert!(
                (t / f0_hertz - 1.0).abs() < 0.02,
                "gamma {g}: table {t} Hertz {f0_hertz:.2}"
            );
        }
    }

    /// Catalogue values of bearings whose internal geometry is public: the CWRU 6205
    /// (Dw 7.94 mm, Dpw 39.04 mm, Z 9) and the 6206 (Dw 3/8 in, Z 9, Dpw ≈ (d + D)/2):
    /// NSK lists Cr 14.0 kN / C0r 7.85 kN and 19.5 kN / 11.3 kN, computed by ISO 281/76.
    /// Tolerance 2 %: the makers' rounding to 3 figures and their exact Dpw.
    #[test]
    fn ratings_match_catalogue_values() {
        let r = load_ratings(&bearing("6205")).unwrap();
        assert!((r.c / 14.0e3 - 1.0).abs() < 0.02, "C {}", r.c);
        assert!((r.c0 / 7.85e3 - 1.0).abs() < 0.02, "C0 {}", r.c0);
        let mut s = preset("6205").unwrap();
        s.ball_diameter_mm = 9.525;
        s.pitch_diameter_mm = 46.0;
        s.bore_mm = Some(30.0);
        s.outer_diameter_mm = Some(62.0);
        s.width_mm = Some(16.0);
        let r = load_ratings(&s.build().unwrap()).unwrap();
        assert!((r.c / 19.5e3 - 1.0).abs() < 0.02, "C {}", r.c);
        assert!((r.c0 / 11.3e3 - 1.0).abs() < 0.02, "C0 {}", r.c0);
    }

    /// The formulas themselves: C0 = f0 Z Dw² cos α exactly; the Dw > 25.4 mm branch of
    /// ISO 281 joins the small-ball one (3.647 = 25.4^0.4); a groove radius above 0.52 Dw
    /// lowers C, one below does not raise it.
    #[test]
    fn rating_formulas_and_branches() {
        let b = bearing("218");
        let r = load_ratings(&b).unwrap();
        let g = b.d * b.alpha0.cos() / b.dm;
        assert!((r.gamma - g).abs() < 1e-15);
        // 218's grooves are wider than 0.52/0.53 Dw: f0 is the table's times the ISO 76
        // 4 200 MPa correction (issue #35), the formula otherwise unchanged.
        let f0_218 = f0(g).unwrap() * static_groove_factor(g, b.fi(), b.fo());
        assert!(f0_218 < f0(g).unwrap() && (r.f0 - f0_218).abs() < 1e-12);
        let want = f0_218 * 16.0 * 22.23f64.powi(2) * b.alpha0.cos();
        assert!((r.c0 - want).abs() < 1e-9 * want);
        assert!(
            r.fc_reduction < 0.99 && r.fc_reduction > 0.9,
            "{}",
            r.fc_reduction
        );
        let small = |dw: f64| {
            let mut s: BearingSpec = preset("218").unwrap();
            s.ball_diameter_mm = dw;
            s.ball_count = 12;
            s.inner_curvature = Some(0.52);
            s.outer_curvature = Some(0.53);
            load_ratings(&s.build().unwrap()).unwrap()
        };
        let (lo, hi) = (small(25.4), small(25.4 + 1e-9));
        // 3.647 is 25.4^0.4 to the standard's four digits.
        assert!((hi.c / lo.c - 1.0).abs() < 1e-4, "{} {}", lo.c, hi.c);
        assert_eq!(lo.fc_reduction, 1.0);
        assert!(conformity_reduction(0.2, 0.51, 0.52) == 1.0);
        assert!(conformity_reduction(0.2, 0.54, 0.53) < 0.97);
    }

    /// Pure radial load on a deep-groove bearing: P = Fr, L10 = (C/P)^3, S0 = C0/Fr, hours
    /// at speed; the per-ball (Lundberg–Palmgren) life falls close to ISO 281's (which
    /// assumes a Stribeck distribution with some clearance; zero clearance here).
    #[test]
    fn l10_and_s0_limits() {
        let b = bearing("6205");
        let sol = solve(&b, [2000.0, 0.0, 0.0, 0.0, 0.0]);
        let a = assess(
            &b,
            &sol,
            &LifeInputs {
                speed_rpm: 1800.0,
                ..Default::default()
            },
        )
        .unwrap();
        let r = a.ratings;
        assert_eq!(a.p, 2000.0);
        assert_eq!(a.l10_mrev, Some((r.c / 2000.0).powi(3)));
        assert!((a.l10_hours.unwrap() - a.l10_mrev.unwrap() * 1e6 / 108_000.0).abs() < 1e-9);
        assert_eq!(a.s0, Some(r.c0 / 2000.0));
        let ratio = a.l10r_mrev.unwrap() / a.l10_mrev.unwrap();
        // Zero clearance: the Stribeck-type distribution ISO 281 assumes (0.407 factor).
        assert!(ratio > 0.97 && ratio < 1.03, "L10r/L10 = {ratio}");
        assert!(a.warnings.is_empty(), "{:?}", a.warnings);
        // Zero load: no life, no S0, and a warning that no ball is loaded.
        let a0 = rate(&b, [0.0; 5]);
        assert!(a0.l10_mrev.is_none() && a0.s0.is_none());
        assert_eq!(a0.warnings, vec![Warning::FewLoadedBalls { count: 0 }]);
    }

    /// Combined load on a deep-groove bearing: X = 0.56 and Y from f0 Fa/C0 (ISO 281
    /// Table 3), P0 = 0.6 Fr + 0.5 Fa but never below Fr.
    #[test]
    fn equivalent_loads() {
        let b = bearing("6205");
        let r = load_ratings(&b).unwrap();
        // f0 Fa / C0 = 1.03 → e = 0.28, Y = 1.55.
        let fa = 1.03 * r.c0 / r.f0;
        let (x, y, e) = dynamic_factors(&b, &r, fa, fa);
        assert_eq!((x, y, e), (0.56, 1.55, 0.28));
        let (x, y, _) = dynamic_factors(&b, &r, 10.0 * fa, fa);
        assert_eq!((x, y), (1.0, 0.0));
        assert_eq!(static_factors(&b), (0.6, 0.5));
        // 40° angular contact: e = 1.14, X = 0.35, Y = 0.57, Y0 = 0.26.
        let b = bearing("218");
        let r = load_ratings(&b).unwrap();
        let (x, y, e) = dynamic_factors(&b, &r, 100.0, 1000.0);
        assert!((x - 0.35).abs() < 1e-12 && (y - 0.57).abs() < 1e-12 && (e - 1.14).abs() < 1e-12);
        assert!((static_factors(&b).1 - 0.26).abs() < 1e-12);
    }

    /// a_ISO: eC = 0 gives the standard's floor 0.1; the three κ branches join at 0.4 and
    /// 1; the cap is 50; κ < 0.1 is outside the standard.
    #[test]
    fn a_iso_limits_and_continuity() {
        assert!((a_iso(1.0, 0.0, 1e3, 1e3).unwrap() - 0.1).abs() < 1e-12);
        for k in [0.4, 1.0] {
            let lo = a_iso(k - 1e-9, 0.5, 1e3, 2e3).unwrap();
            let hi = a_iso(k, 0.5, 1e3, 2e3).unwrap();
            // The standard's coefficients have five digits: the branches join to ~1e-3.
            assert!((lo / hi - 1.0).abs() < 1e-3, "kappa {k}: {lo} {hi}");
        }
        assert_eq!(a_iso(4.0, 1.0, 1e4, 1e3), Some(50.0));
        assert_eq!(a_iso(8.0, 0.5, 1e3, 2e3), a_iso(4.0, 0.5, 1e3, 2e3));
        assert!(a_iso(0.09, 0.5, 1e3, 2e3).is_none());
        // More lubricant film, cleaner oil, lighter load: longer life.
        let base = a_iso(1.0, 0.5, 1e3, 2e3).unwrap();
        assert!(a_iso(2.0, 0.5, 1e3, 2e3).unwrap() > base);
        assert!(a_iso(1.0, 0.8, 1e3, 2e3).unwrap() > base);
        assert!(a_iso(1.0, 0.5, 1e3, 4e3).unwrap() < base);
    }

    /// Each warning switches on across its threshold and not before.
    #[test]
    fn warnings_at_thresholds() {
        let b = bearing("6205");
        // Zero clearance, zero speed: the load distribution keeps its shape, so the peak
        // pressure scales as Fr^(1/3) and the limit load follows from one solve.
        let p1 = rate(&b, [1000.0, 0.0, 0.0, 0.0, 0.0]).peak_pressure;
        let f_lim = 1000.0 * (STATIC_PRESSURE_LIMIT / p1).powi(3);
        let at = |f: f64, kappa: Option<f64>| {
            assess(
                &b,
                &solve(&b, [f, 0.0, 0.0, 0.0, 0.0]),
                &LifeInputs {
                    speed_rpm: 1000.0,
                    kappa,
                    contamination: Some(0.5),
                },
            )
            .unwrap()
        };
        let below = at(0.98 * f_lim, Some(1.0));
        let above = at(1.02 * f_lim, Some(0.99));
        assert!(
            below.pressure_limit_ratio < 1.0 && below.warnings.is_empty(),
            "{:?}",
            below.warnings
        );
        assert!(above.pressure_limit_ratio > 1.0);
        assert!(matches!(
            above.warnings[0],
            Warning::PressureAboveStaticLimit { race: "inner", .. }
        ));
        assert!(above
            .warnings
            .contains(&Warning::KappaBelowOne { kappa: 0.99 }));
        assert!(below.a_iso.is_some() && below.l10mr_hours.is_some());
        // ISO 76 puts the static limit at C0 with a Stribeck factor 5 that covers normal
        // clearance; at zero clearance the factor is 4.37, so the limit load is above C0.
        let s0 = below.ratings.c0 / f_lim;
        assert!(s0 > 0.8 && s0 < 1.0, "C0 / F(4200 MPa) = {s0}");

        // One loaded ball: a small radial load on a bearing with a large clearance (the
        // neighbours at ±25.7° need x cos 25.7° > Pd/2).
        let mut s = preset("6012").unwrap();
        s.clearance_um = Some(30.0);
        let b = s.build().unwrap();
        let a = rate(&b, [5.0, 0.0, 0.0, 0.0, 0.0]);
        assert_eq!(a.loaded_balls, 1);
        assert!(a.warnings.contains(&Warning::FewLoadedBalls {
            count: a.loaded_balls
        }));
        let b = bearing("6012");
        let a = rate(&b, [0.0, 0.0, 500.0, 0.0, 0.0]);
        assert_eq!(a.loaded_balls, 14);
        assert!(a.warnings.is_empty(), "{:?}", a.warnings);

        // Ellipse truncation: heavy axial load on a deep-groove bearing drives the contact
        // angle and the ellipse up the groove towards the shoulder.
        let b = bearing("6205");
        let (shi, _) = shoulder_angles(&b);
        let light = rate(&b, [0.0, 0.0, 200.0, 0.0, 0.0]);
        assert!(!truncated(&light));
        // At 10 kN the inner ellipse reaches 51.9° of the 52.0° shoulder (h = 0.2 Dw on
        // f = 0.52); at 14 kN it runs over.
        let edge_free = rate(&b, [0.0, 0.0, 10e3, 0.0, 0.0]);
        assert!(!truncated(&edge_free));
        let heavy = rate(&b, [0.0, 0.0, 14e3, 0.0, 0.0]);
        let t = heavy.warnings.iter().find_map(|w| match w {
            Warning::EllipseTruncated {
                edge_angle,
                shoulder_angle,
                ..
            } => Some((*edge_angle, *shoulder_angle)),
            _ => None,
        });
        let (edge, sh) = t.expect("truncation warning at 14 kN axial");
        assert!(edge > sh && (sh - shi).abs() < 1e-12, "{edge} {sh} {shi}");
    }

    /// ISO 76 for every groove: at the reported C0, `Qmax = 5 C0 / (Z cos α)` gives 4 200 MPa
    /// (within the table's 2 % rounding) also for wide grooves (acbb16, 218: 4 332 and
    /// 4 340 MPa with the table f0 unchanged), deeper grooves give a lower C0, and the
    /// standard groove keeps the table value exactly.
    #[test]
    fn c0_from_4200_mpa_for_every_groove() {
        for name in ["acbb16", "218", "6205"] {
            let b = bearing(name);
            let r = load_ratings(&b).unwrap();
            let ca = b.nominal_contact_angle().cos();
            let q = 5.0 * r.c0 / (b.z as f64 * ca);
            // ISO 76's geometry: the contact angle in gamma, Dpw = Dw / gamma.
            let dm_g = b.d / gamma(&b);
            let p = |race: Race, f: f64, e: f64| {
                PointContact::new(Curvature::ball_race(b.d, dm_g, 0.0, f, race), e).peak_pressure(q)
            };
            let pmax_g = p(Race::Inner, b.fi(), b.e_eff_inner()).max(p(
                Race::Outer,
                b.fo(),
                b.e_eff_outer(),
            ));
            assert!(
                (pmax_g / STATIC_PRESSURE_LIMIT - 1.0).abs() < 0.02,
                "{name}: {:.0} MPa at C0 {:.0} N",
                pmax_g / 1e6,
                r.c0
            );
        }
        let mut spec = preset("6205").unwrap();
        let std = load_ratings(&spec.clone().build().unwrap()).unwrap();
        assert_eq!(static_groove_factor(std.gamma, 0.52, 0.53), 1.0);
        assert_eq!(std.f0, f0(std.gamma).unwrap());
        let mut last = std.c0;
        for f in [0.54, 0.56, 0.58] {
            spec.inner_curvature = Some(f);
            spec.outer_curvature = Some(f);
            let r = load_ratings(&spec.clone().build().unwrap()).unwrap();
            assert!(r.c0 < last, "fi = fo = {f}: C0 {} not below {last}", r.c0);
            last = r.c0;
        }
    }
}

/// Largest static safety factor reported as an output (an unloaded bearing's `C0/0`).
pub const S0_UNLOADED: f64 = 1e6;
/// Largest basic rating life reported as an output, millions of revolutions.
pub const L10_UNLOADED: f64 = 1e12;

/// What the co-simulation outputs `safety.S0`, `life.L10` and `warnings.active` need of
/// the ratings, computed once when a component is built: `None` where ISO 281/76 do not
/// cover the bearing (the outputs then read 0).
#[derive(Debug, Clone, Copy)]
pub struct RatingOutputs {
    ratings: Option<LoadRatings>,
    x0y0: (f64, f64),
    limit: f64,
}

impl RatingOutputs {
    /// The ratings of `b` (computed here, once).
    pub fn of(b: &Bearing) -> Self {
        if let crate::geometry::element::Element::Roller(r) = &b.element {
            // ISO 281/76 for roller bearings (`ratings::roller`): the ratings go in `c`
            // and `c0`, the load factors are taken per load in `outputs`.
            return RatingOutputs {
                ratings: roller::roller_ratings(r).ok().map(|rr| LoadRatings {
                    gamma: rr.gamma,
                    fc: rr.fc,
                    fc_reduction: 1.0,
                    f0: 0.0,
                    c: rr.cr,
                    c0: rr.c0r,
                    cu: 0.0,
                }),
                x0y0: (1.0, 0.0),
                limit: roller::STATIC_PRESSURE_LIMIT_ROLLER,
            };
        }
        RatingOutputs {
            ratings: load_ratings(b).ok(),
            x0y0: static_factors(b),
            limit: STATIC_PRESSURE_LIMIT,
        }
    }

    /// `[S0, L10, warnings]` for the bearing force `wrench` (force on the shaft, N; its
    /// radial and axial parts are the loads `Fr`, `Fa`), the peak contact pressure (Pa) and
    /// the loaded-ball count. `S0 = C0/P0` (ISO 76) capped at [`S0_UNLOADED`], `L10 =
    /// (C/P)^3` (ISO 281, millions of revolutions) capped at [`L10_UNLOADED`]; the warning
    /// count is the pressure beyond ISO 76's limit plus fewer than two loaded balls (the
    /// cheap ones of [`Warning`]; the ellipse truncation and κ need the per-ball solution
    /// and the oil, and are in [`assess`]). Finite for any finite input.
    pub fn outputs(&self, b: &Bearing, wrench: &[f64; 5], pressure: f64, loaded: f64) -> [f64; 3] {
        let warnings = f64::from(u8::from(pressure > self.limit) + u8::from(loaded < 2.0));
        let Some(r) = &self.ratings else {
            return [0.0, 0.0, warnings];
        };
        let fr = wrench[0].hypot(wrench[1]);
        let fa = wrench[2].abs();
        if let crate::geometry::element::Element::Roller(rb) = &b.element {
            let p0 = roller::equivalent_static_load(rb, fr, fa);
            let s0 = if p0 * S0_UNLOADED > r.c0 {
                r.c0 / p0
            } else {
                S0_UNLOADED
            };
            let p = roller::equivalent_dynamic_load(rb, fr, fa).0;
            let l10 = if p > 0.0 {
                roller::l10_roller(r.c, p).min(L10_UNLOADED)
            } else {
                L10_UNLOADED
            };
            return [s0, l10, warnings];
        }
        let (x0, y0) = self.x0y0;
        let p0 = (x0 * fr + y0 * fa).max(fr);
        let s0 = if p0 * S0_UNLOADED > r.c0 {
            r.c0 / p0
        } else {
            S0_UNLOADED
        };
        let (x, y, _) = dynamic_factors(b, r, fr, fa);
        let p = x * fr + y * fa;
        let l10 = if p > 0.0 {
            (r.c / p).powi(3).min(L10_UNLOADED)
        } else {
            L10_UNLOADED
        };
        [s0, l10, warnings]
    }
}
