//! Load ratings, equivalent loads and basic rating life of radial roller bearings (cylindrical
//! and tapered, single row, bearing steel), docs/physics.md §R5.
//!
//! - **Basic dynamic radial load rating** (ISO 281:2007 §7.1.1):
//!   `Cr = bm fc (i Lwe cos α)^(7/9) Z^(3/4) Dwe^(29/27)` (N, mm), `bm = 1.1` for cylindrical and
//!   tapered roller bearings (ISO 281 Table 1), `fc` from ISO 281's table of `fc` for radial
//!   roller bearings by linear interpolation in `γ = Dwe cos α / Dpw`. The table is the closed
//!   form of ISO/TR 1281-1 (Lundberg–Palmgren line contact with the reduction `λν = 0.83` for
//!   edge stresses and uneven load along the roller)
//!   `fc = 0.83 × 207.9 γ^(2/9) (1-γ)^(29/27) (1+γ)^(-1/4)
//!   [1 + (1.04 ((1-γ)/(1+γ))^(143/108))^(9/2)]^(-2/9)`,
//!   rounded to 0.1: tested at every row ([`fc_closed_form`]).
//! - **Basic static radial load rating** (ISO 76:2006 §6.1):
//!   `C0r = 44 (1 - γ) i Z Lwe Dwe cos α` (N, mm), the load at which the most heavily loaded
//!   roller reaches 4 000 MPa at the middle of its contact.
//! - **Equivalent loads**: `P = X Fr + Y Fa`, single row with `α ≠ 0` (ISO 281 §7.1.2):
//!   `X = 1, Y = 0` for `Fa/Fr ≤ e`, `X = 0.4, Y = 0.4 cot α` above, `e = 1.5 tan α`; with
//!   `α = 0` (cylindrical) `P = Fr` (the flanges of NJ/NUP carry axial load by their own limits,
//!   not by the rating). `P0 = max(X0 Fr + Y0 Fa, Fr)`, `X0 = 0.5`, `Y0 = 0.22 cot α` (ISO 76
//!   §6.2); `P0 = Fr` for `α = 0`.
//! - **Basic rating life** `L10 = (Cr/P)^(10/3)` million revolutions (ISO 281).

use crate::error::{Error, Result};
use crate::geometry::roller::RollerBearing;
use serde::Serialize;

/// `bm` of ISO 281 Table 1 for cylindrical and tapered roller bearings.
pub const BM_ROLLER: f64 = 1.1;
/// ISO 76 permissible peak contact pressure for roller bearings, Pa.
pub const STATIC_PRESSURE_LIMIT_ROLLER: f64 = 4000e6;
/// `λν` of ISO/TR 1281-1 for radial roller bearings (the factor between the Lundberg–Palmgren
/// line-contact `fc` and ISO 281's table).
pub const LAMBDA_NU: f64 = 0.83;

/// ISO 281:2007, `fc` of radial roller bearings at `Dwe cos α / Dpw = 0.01, 0.02, .., 0.30`.
const FC_ROLLER_TABLE: [f64; 30] = [
    52.1, 60.8, 66.5, 70.7, 74.1, 76.9, 79.2, 81.2, 82.8, 84.2, 85.4, 86.4, 87.1, 87.7, 88.2, 88.5,
    88.7, 88.8, 88.8, 88.7, 88.5, 88.2, 87.9, 87.5, 87.0, 86.4, 85.8, 85.2, 84.5, 83.8,
];

/// ISO 281's `fc` of radial roller bearings at `gamma = Dwe cos α / Dpw` (linear
/// interpolation in the table), for `Cr` in N with lengths in mm.
pub fn fc_roller(gamma: f64) -> Result<f64> {
    let t = (gamma - 0.01) / 0.01;
    let n = FC_ROLLER_TABLE.len() - 1;
    if !(t >= -1e-9 && t <= n as f64 + 1e-9) {
        return Err(Error::invalid(
            "Dwe cos(alpha)/Dpw",
            format!("{gamma:.4}"),
            "in [0.01, 0.30] (ISO 281's fc table for radial roller bearings)",
        ));
    }
    let t = t.clamp(0.0, n as f64);
    let k = (t.floor() as usize).min(n - 1);
    let w = t - k as f64;
    Ok(FC_ROLLER_TABLE[k] * (1.0 - w) + FC_ROLLER_TABLE[k + 1] * w)
}

/// The closed form behind the table (ISO/TR 1281-1, module docs).
pub fn fc_closed_form(gamma: f64) -> f64 {
    let g = (1.0 - gamma) / (1.0 + gamma);
    let bracket = 1.0 + (1.04 * g.powf(143.0 / 108.0)).powf(4.5);
    LAMBDA_NU * 207.9 * gamma.powf(2.0 / 9.0) * (1.0 - gamma).powf(29.0 / 27.0)
        / (1.0 + gamma).powf(0.25)
        * bracket.powf(-2.0 / 9.0)
}

/// Basic load ratings of a roller bearing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RollerRatings {
    /// `γ = Dwe cos α / Dpw`.
    pub gamma: f64,
    /// `fc` of ISO 281.
    pub fc: f64,
    /// Basic dynamic radial load rating `Cr`, N.
    pub cr: f64,
    /// Basic static radial load rating `C0r`, N.
    pub c0r: f64,
}

/// ISO 281 `Cr` and ISO 76 `C0r` of a single-row roller bearing (module docs).
pub fn roller_ratings(b: &RollerBearing) -> Result<RollerRatings> {
    let g = b.gamma();
    let fc = fc_roller(g)?;
    let (dwe, lwe) = (b.dwe * 1e3, b.lwe * 1e3);
    let (z, i, cos_a) = (b.z as f64, 1.0, b.alpha.cos());
    let cr =
        BM_ROLLER * fc * (i * lwe * cos_a).powf(7.0 / 9.0) * z.powf(0.75) * dwe.powf(29.0 / 27.0);
    let c0r = 44.0 * (1.0 - g) * i * z * lwe * dwe * cos_a;
    Ok(RollerRatings {
        gamma: g,
        fc,
        cr,
        c0r,
    })
}

/// ISO 281 dynamic equivalent radial load `(P, X, Y, e)` for radial load `fr` and axial load
/// `fa` (N, magnitudes).
pub fn equivalent_dynamic_load(b: &RollerBearing, fr: f64, fa: f64) -> (f64, f64, f64, f64) {
    let (fr, fa) = (fr.abs(), fa.abs());
    if b.alpha == 0.0 {
        return (fr, 1.0, 0.0, f64::INFINITY);
    }
    let e = 1.5 * b.alpha.tan();
    if fr > 0.0 && fa / fr <= e || fa == 0.0 {
        (fr, 1.0, 0.0, e)
    } else {
        let y = 0.4 / b.alpha.tan();
        (0.4 * fr + y * fa, 0.4, y, e)
    }
}

/// ISO 76 static equivalent radial load `P0`, N.
pub fn equivalent_static_load(b: &RollerBearing, fr: f64, fa: f64) -> f64 {
    let (fr, fa) = (fr.abs(), fa.abs());
    if b.alpha == 0.0 {
        return fr;
    }
    (0.5 * fr + 0.22 / b.alpha.tan() * fa).max(fr)
}

/// Basic rating life `L10 = (Cr/P)^(10/3)`, million revolutions (infinite at `P = 0`).
pub fn l10_roller(cr: f64, p: f64) -> f64 {
    if p > 0.0 {
        (cr / p).powf(10.0 / 3.0)
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::roller::{FlangeSpec, ProfileSpec, RollerBearingSpec, RollerKind};

    #[test]
    fn fc_table_is_the_closed_form_rounded() {
        for (k, &v) in FC_ROLLER_TABLE.iter().enumerate() {
            let g = 0.01 * (k + 1) as f64;
            let c = fc_closed_form(g);
            assert!(
                (c - v).abs() <= 0.06,
                "gamma {g}: table {v}, closed form {c:.3}"
            );
        }
        assert!(fc_roller(0.005).is_err() && fc_roller(0.31).is_err());
        assert!((fc_roller(0.105).unwrap() - 0.5 * (84.2 + 85.4)).abs() < 1e-12);
    }

    fn spec(kind: RollerKind, alpha: Option<f64>) -> RollerBearingSpec {
        RollerBearingSpec {
            name: "t".into(),
            kind,
            roller_diameter_mm: 10.0,
            roller_effective_length_mm: 10.0,
            roller_length_mm: None,
            roller_count: 14,
            pitch_diameter_mm: 50.0,
            contact_angle_deg: alpha,
            cone_angle_deg: None,
            clearance_um: None,
            profile: ProfileSpec::IsoLog,
            laminae: None,
            flange: FlangeSpec::default(),
            bore_mm: None,
            outer_diameter_mm: None,
            width_mm: Some(20.0),
            roller_material: None,
            inner_ring_material: None,
            outer_ring_material: None,
            source: String::new(),
        }
    }

    #[test]
    fn ratings_by_hand() {
        // Dwe = Lwe = 10 mm, Z = 14, Dpw = 50 mm: gamma = 0.2, fc = 88.7.
        let b = spec(RollerKind::Nu, None).build().unwrap();
        let r = roller_ratings(&b).unwrap();
        let cr = 1.1 * 88.7 * 10f64.powf(7.0 / 9.0) * 14f64.powf(0.75) * 10f64.powf(29.0 / 27.0);
        assert!((r.cr / cr - 1.0).abs() < 1e-12, "{} {cr}", r.cr);
        assert!((r.c0r - 44.0 * 0.8 * 14.0 * 100.0).abs() < 1e-9);
        assert_eq!(equivalent_dynamic_load(&b, 1000.0, 500.0).0, 1000.0);
        assert_eq!(equivalent_static_load(&b, 1000.0, 500.0), 1000.0);
        assert!((l10_roller(r.cr, r.cr / 2.0) - 2f64.powf(10.0 / 3.0)).abs() < 1e-9);
    }

    #[test]
    fn tapered_equivalent_loads_follow_iso_281_and_76() {
        let b = spec(RollerKind::Tapered, Some(15.0)).build().unwrap();
        let (e, y) = (1.5 * b.alpha.tan(), 0.4 / b.alpha.tan());
        let (p, x, yy, ee) = equivalent_dynamic_load(&b, 1000.0, 0.5 * e * 1000.0);
        assert_eq!((p, x, yy), (1000.0, 1.0, 0.0));
        assert!((ee - e).abs() < 1e-15);
        let (p, x, _, _) = equivalent_dynamic_load(&b, 1000.0, 1000.0);
        assert!((p - (400.0 + y * 1000.0)).abs() < 1e-9 && x == 0.4);
        // e Y = 0.6 for every angle.
        assert!((e * y - 0.6).abs() < 1e-12);
        let p0 = equivalent_static_load(&b, 1000.0, 1000.0);
        assert!((p0 - (500.0 + 0.22 / b.alpha.tan() * 1000.0)).abs() < 1e-9);
        assert_eq!(equivalent_static_load(&b, 1000.0, 0.0), 1000.0);
    }
}
