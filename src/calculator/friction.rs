//! Friction moment and power loss of a ball bearing, Palmgren's empirical method.
//!
//! Palmgren (*Ball and Roller Bearing Engineering*, 3rd ed., SKF Industries, 1959, ch. 4), as
//! restated in Harris & Kotzalas (*Rolling Bearing Analysis*, 5th ed., vol. 1, "Friction in
//! rolling bearings") and ISO/TR 14179-2:2001 §4 (whose bearing friction model it is), in the
//! units of the sources (N·mm, mm, rpm, mm²/s), converted to SI at the edge:
//!
//! - load-independent (viscous) part: `M0 = 1e-7 f0 (ν n)^(2/3) dm³` for `ν n ≥ 2000`, and
//!   `M0 = 160e-7 f0 dm³` below (`2000^(2/3) ≈ 160`: the two join);
//! - load-dependent part: `M1 = f1 P1 dm`, with `f1 = z (P0 / C0)^y` and the friction load `P1`:
//!   deep-groove ball bearings `z = 0.0004 .. 0.0006` (0.0005 used), `y = 0.55`,
//!   `P1 = max(3 Fa − 0.1 Fr, Fr)`; single-row angular-contact `z = 0.001`, `y = 0.33`,
//!   `P1 = max(Fa − 0.1 Fr, Fr)`; `P0` is ISO 76's static equivalent load;
//! - the total `M = M0 + M1` and the power loss `N = M ω`.
//!
//! `f0` depends on the bearing type and the lubrication method (deep-groove ball bearings:
//! 0.7 .. 2 for grease or oil mist, 2 oil bath, 4 oil jet or vertical shaft, per the sources'
//! table); it is an input.
//!
//! The SKF four-term model (rolling, sliding, seals, drag) is [`super::skf_friction`].

use crate::error::{Error, Result};

/// Palmgren's load-dependent coefficients for a bearing type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PalmgrenType {
    /// `z` in `f1 = z (P0/C0)^y`.
    pub z: f64,
    /// `y` in `f1 = z (P0/C0)^y`.
    pub y: f64,
    /// Weight of `Fa` in the friction load `P1 = max(ka Fa − 0.1 Fr, Fr)`.
    pub ka: f64,
}

impl PalmgrenType {
    /// Radial deep-groove ball bearing (`z` the middle of the published 0.0004 .. 0.0006).
    pub const DEEP_GROOVE: PalmgrenType = PalmgrenType {
        z: 0.0005,
        y: 0.55,
        ka: 3.0,
    };
    /// Single-row angular-contact ball bearing.
    pub const ANGULAR_CONTACT: PalmgrenType = PalmgrenType {
        z: 0.001,
        y: 0.33,
        ka: 1.0,
    };
}

/// Operating point for the friction moment (SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrictionInputs {
    /// Pitch diameter `dm` (m).
    pub dm: f64,
    /// Speed of the rotating ring relative to the other (rpm).
    pub speed_rpm: f64,
    /// Kinematic viscosity of the oil at operating temperature (m²/s).
    pub nu: f64,
    /// Radial load (N).
    pub fr: f64,
    /// Axial load (N).
    pub fa: f64,
    /// Static equivalent load `P0` (N, ISO 76).
    pub p0: f64,
    /// Basic static load rating `C0` (N).
    pub c0: f64,
    /// Palmgren's lubrication factor `f0`.
    pub f0: f64,
}

/// The friction moment, each part labelled (N·m) and the power loss (W).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Palmgren {
    /// Load-independent (viscous) moment `M0`.
    pub m0: f64,
    /// Load-dependent moment `M1`.
    pub m1: f64,
    /// `M0 + M1`.
    pub total: f64,
    /// `f1`.
    pub f1: f64,
    /// Friction load `P1` (N).
    pub p1: f64,
    /// Power loss `M ω` (W).
    pub power: f64,
}

/// Palmgren's friction moment for a bearing type at an operating point.
pub fn palmgren(t: PalmgrenType, x: &FrictionInputs) -> Result<Palmgren> {
    let pos = |f: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(Error::invalid(format!("friction.{f}"), v, "> 0"))
        }
    };
    let nonneg = |f: &str, v: f64| {
        if v.is_finite() && v >= 0.0 {
            Ok(())
        } else {
            Err(Error::invalid(format!("friction.{f}"), v, ">= 0"))
        }
    };
    pos("dm", x.dm)?;
    pos("nu", x.nu)?;
    pos("c0", x.c0)?;
    pos("f0", x.f0)?;
    nonneg("fr", x.fr)?;
    nonneg("p0", x.p0)?;
    if !x.speed_rpm.is_finite() || !x.fa.is_finite() {
        return Err(Error::invalid("friction.speed_rpm", x.speed_rpm, "finite"));
    }
    let dm_mm = x.dm * 1e3;
    let n = x.speed_rpm.abs();
    let nu_cst = x.nu * 1e6;
    let vn = nu_cst * n;
    let m0_nmm = if vn >= 2000.0 {
        1e-7 * x.f0 * vn.powf(2.0 / 3.0) * dm_mm.powi(3)
    } else {
        160e-7 * x.f0 * dm_mm.powi(3)
    };
    let f1 = t.z * (x.p0 / x.c0).powf(t.y);
    let p1 = (t.ka * x.fa.abs() - 0.1 * x.fr).max(x.fr);
    let m1_nmm = f1 * p1 * dm_mm;
    let (m0, m1) = (m0_nmm * 1e-3, m1_nmm * 1e-3);
    let total = m0 + m1;
    let omega = n * std::f64::consts::PI / 30.0;
    Ok(Palmgren {
        m0,
        m1,
        total,
        f1,
        p1,
        power: total * omega,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point() -> FrictionInputs {
        FrictionInputs {
            dm: 38.5e-3,
            speed_rpm: 3000.0,
            nu: 20e-6,
            fr: 2000.0,
            fa: 0.0,
            p0: 2000.0,
            c0: 7850.0,
            f0: 2.0,
        }
    }

    /// The formula by hand: ν n = 60 000 mm²/s·rpm, (ν n)^(2/3) = 1 532.6, dm³ = 57 066 mm³:
    /// M0 = 1e-7 · 2 · 1 532.6 · 57 066 = 17.49 N·mm; f1 = 5e-4 (2000/7850)^0.55 = 2.36e-4,
    /// M1 = f1 · 2000 · 38.5 = 18.2 N·mm.
    #[test]
    fn hand_worked_point() {
        let r = palmgren(PalmgrenType::DEEP_GROOVE, &point()).unwrap();
        assert!((r.m0 * 1e3 - 17.49).abs() < 0.01, "{}", r.m0 * 1e3);
        assert!((r.f1 - 2.364e-4).abs() < 1e-6, "{}", r.f1);
        assert!((r.m1 * 1e3 - r.f1 * 2000.0 * 38.5).abs() < 1e-9);
        assert!((r.power - r.total * 3000.0 * std::f64::consts::PI / 30.0).abs() < 1e-12);
    }

    #[test]
    fn rises_with_load_and_viscosity_unloaded_is_viscous_only() {
        let t = PalmgrenType::DEEP_GROOVE;
        let base = palmgren(t, &point()).unwrap();
        let loaded = palmgren(
            t,
            &FrictionInputs {
                fr: 4000.0,
                p0: 4000.0,
                ..point()
            },
        )
        .unwrap();
        assert!(loaded.total > base.total && loaded.m0 == base.m0);
        let thick = palmgren(
            t,
            &FrictionInputs {
                nu: 100e-6,
                ..point()
            },
        )
        .unwrap();
        assert!(thick.total > base.total && thick.m1 == base.m1);
        let free = palmgren(
            t,
            &FrictionInputs {
                fr: 0.0,
                p0: 0.0,
                ..point()
            },
        )
        .unwrap();
        assert_eq!(free.m1, 0.0);
        assert_eq!(free.total, free.m0);
        assert_eq!(free.m0, base.m0);
    }

    /// The two branches of M0 meet at ν n = 2000 (2000^(2/3) = 158.7 against 160: < 1 %).
    #[test]
    fn low_speed_branch_joins() {
        let t = PalmgrenType::ANGULAR_CONTACT;
        let at = |rpm: f64| {
            palmgren(
                t,
                &FrictionInputs {
                    speed_rpm: rpm,
                    ..point()
                },
            )
            .unwrap()
            .m0
        };
        let (lo, hi) = (at(99.999), at(100.0));
        assert!((hi / lo - 1.0).abs() < 0.01, "{lo} {hi}");
        assert_eq!(at(10.0), lo);
    }

    /// Axial load enters through P1 = max(ka Fa − 0.1 Fr, Fr).
    #[test]
    fn friction_load() {
        let x = FrictionInputs {
            fa: 1000.0,
            ..point()
        };
        assert_eq!(palmgren(PalmgrenType::DEEP_GROOVE, &x).unwrap().p1, 2800.0);
        assert_eq!(
            palmgren(PalmgrenType::ANGULAR_CONTACT, &x).unwrap().p1,
            2000.0
        );
        let e = palmgren(PalmgrenType::DEEP_GROOVE, &FrictionInputs { nu: 0.0, ..x });
        assert!(e.unwrap_err().to_string().contains("friction.nu"));
    }
}
