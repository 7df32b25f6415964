//! Life under a duty cycle: a list of (equivalent dynamic load, speed, time share) rows.
//!
//! ISO 281:2007 for variable operating conditions (its equivalent-load relations, as in
//! Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., vol. 2, "Fatigue life: variable
//! loading"): with `U_i = n_i t_i / Σ n_j t_j` the share of revolutions spent in row `i`,
//!
//! - the mean equivalent load `P_m = (Σ U_i P_i^p)^(1/p)` (`p = 3` for ball bearings), the mean
//!   speed `n_m = Σ t_i n_i`, and `L10 = (C/P_m)^p` millions of revolutions;
//! - with a life-modification factor per row (ISO 281's `a_ISO`, which changes with the speed
//!   through κ), the Palmgren–Miner sum `1/L = Σ U_i / L_i` with `L_i = a_i (C/P_i)^p`. Without
//!   factors the two are the same number (a check in the tests).
//!
//! Hours: `L · 10⁶ / (60 n_m)`. Rows at standstill add time but no revolutions.

use crate::error::{Error, Result};
use serde::Serialize;

/// One operating condition of a duty cycle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DutyRow {
    /// Equivalent dynamic load `P_i`, N.
    pub load: f64,
    /// Speed, rpm.
    pub speed_rpm: f64,
    /// Share of the time, 0..1 (the shares add to 1).
    pub time_share: f64,
    /// Life-modification factor `a_i` (1: basic life).
    pub factor: f64,
}

/// The life of a bearing of dynamic rating `C` under a duty cycle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DutyLife {
    /// Mean equivalent load `P_m`, N.
    pub mean_load: f64,
    /// Mean speed `n_m`, rpm.
    pub mean_speed_rpm: f64,
    /// Basic life `(C/P_m)^p`, millions of revolutions.
    pub l10_mrev: f64,
    /// Palmgren–Miner life with the rows' factors, millions of revolutions.
    pub miner_mrev: f64,
    /// `miner_mrev` in hours at the mean speed.
    pub miner_hours: f64,
}

/// The life of a bearing of rating `c` (N) and life exponent `p` under `rows`.
pub fn duty_life(c: f64, p: f64, rows: &[DutyRow]) -> Result<DutyLife> {
    if rows.is_empty() {
        return Err(Error::invalid("duty", "no rows", "at least one row"));
    }
    if !(c > 0.0 && c.is_finite()) {
        return Err(Error::invalid("duty.c", c, "> 0"));
    }
    let mut share = 0.0;
    for (k, r) in rows.iter().enumerate() {
        let bad = |f: &str, v: f64, a: &str| Err(Error::invalid(format!("duty[{k}].{f}"), v, a));
        if !(r.load.is_finite() && r.load >= 0.0) {
            return bad("load", r.load, ">= 0");
        }
        if !(r.speed_rpm.is_finite() && r.speed_rpm >= 0.0) {
            return bad("speed_rpm", r.speed_rpm, ">= 0");
        }
        if !(r.time_share.is_finite() && r.time_share >= 0.0 && r.time_share <= 1.0) {
            return bad("time_share", r.time_share, "0 ..= 1");
        }
        if !(r.factor.is_finite() && r.factor > 0.0) {
            return bad("factor", r.factor, "> 0");
        }
        share += r.time_share;
    }
    if (share - 1.0).abs() > 1e-6 {
        return Err(Error::invalid(
            "duty.time_share",
            share,
            "the rows' time shares add to 1",
        ));
    }
    let revs: f64 = rows.iter().map(|r| r.speed_rpm * r.time_share).sum();
    if revs.is_nan() || revs <= 0.0 {
        return Err(Error::invalid(
            "duty.speed_rpm",
            0.0,
            "a row that turns (> 0 rpm) with a time share > 0",
        ));
    }
    let mut pm = 0.0;
    let mut damage = 0.0;
    for r in rows {
        let u = r.speed_rpm * r.time_share / revs;
        pm += u * r.load.powf(p);
        damage += u * (r.load / c).powf(p) / r.factor;
    }
    let mean_load = pm.powf(1.0 / p);
    let miner = 1.0 / damage;
    Ok(DutyLife {
        mean_load,
        mean_speed_rpm: revs,
        l10_mrev: (c / mean_load).powf(p),
        miner_mrev: miner,
        miner_hours: miner * 1e6 / (60.0 * revs),
    })
}

/// One row of a load spectrum as a user gives it: radial and axial load (N), speed (rpm),
/// time share.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SpectrumRow {
    /// Radial load, N.
    pub fr: f64,
    /// Axial load, N.
    pub fa: f64,
    /// Speed, rpm.
    pub speed_rpm: f64,
    /// Share of the time.
    pub time_share: f64,
}

/// Parse a spectrum: one row per line, `fr_n, fa_n, speed_rpm, time_share` (commas or
/// whitespace; `#` starts a comment; a first line of names is skipped).
pub fn parse_spectrum(text: &str, what: &str) -> Result<Vec<SpectrumRow>> {
    let mut rows = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let cells: Vec<&str> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|c| !c.is_empty())
            .collect();
        let nums: std::result::Result<Vec<f64>, _> = cells.iter().map(|c| c.parse()).collect();
        match nums {
            Ok(v) if v.len() == 4 => rows.push(SpectrumRow {
                fr: v[0],
                fa: v[1],
                speed_rpm: v[2],
                time_share: v[3],
            }),
            Err(_) if rows.is_empty() && k == 0 => continue,
            _ => {
                return Err(Error::Parse {
                    what: what.to_string(),
                    message: format!(
                    "line {}: expected 4 numbers `fr_n, fa_n, speed_rpm, time_share`, got `{line}`",
                    k + 1
                ),
                })
            }
        }
    }
    Ok(rows)
}

/// The life of bearing `b` under a spectrum: each row's equivalent load from ISO 281's X and
/// Y, and, when `kappa_at` gives κ at a row's speed and `ec` is given, that row's `a_ISO`
/// (otherwise factor 1). Ball bearings: `p = 3`.
pub fn spectrum_life(
    b: &crate::geometry::Bearing,
    r: &crate::ratings::LoadRatings,
    rows: &[SpectrumRow],
    kappa_at: &dyn Fn(f64) -> Option<f64>,
    ec: Option<f64>,
) -> Result<DutyLife> {
    let mut out = Vec::with_capacity(rows.len());
    for (k, s) in rows.iter().enumerate() {
        for (f, v) in [("fr", s.fr), ("fa", s.fa)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::invalid(format!("duty[{k}].{f}"), v, ">= 0"));
            }
        }
        let (x, y, _) = crate::ratings::dynamic_factors(b, r, s.fr, s.fa);
        let p = x * s.fr + y * s.fa;
        let factor = match (kappa_at(s.speed_rpm), ec) {
            (Some(kappa), Some(ec)) => crate::ratings::a_iso(kappa, ec, r.cu, p).unwrap_or(1.0),
            _ => 1.0,
        };
        out.push(DutyRow {
            load: p,
            speed_rpm: s.speed_rpm,
            time_share: s.time_share,
            factor,
        });
    }
    duty_life(r.c, 3.0, &out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(load: f64, speed_rpm: f64, time_share: f64) -> DutyRow {
        DutyRow {
            load,
            speed_rpm,
            time_share,
            factor: 1.0,
        }
    }

    /// By hand: C = 14 000 N; 2000 N at 1000 rpm half the time, 4000 N at 2000 rpm the other
    /// half: U = 1/3, 2/3; P_m = (8e9/3 + 2·64e9/3)^(1/3) = 3 565.7 N; n_m = 1500 rpm;
    /// L10 = (14 000/3 565.7)³ = 60.53 Mrev = 672.5 h.
    #[test]
    fn hand_worked_spectrum() {
        let r = duty_life(
            14000.0,
            3.0,
            &[row(2000.0, 1000.0, 0.5), row(4000.0, 2000.0, 0.5)],
        )
        .unwrap();
        assert!((r.mean_load - 3565.65).abs() < 0.01, "{r:?}");
        assert_eq!(r.mean_speed_rpm, 1500.0);
        assert!((r.l10_mrev - 60.53).abs() < 0.01, "{r:?}");
        assert!((r.miner_mrev / r.l10_mrev - 1.0).abs() < 1e-12);
        assert!((r.miner_hours - 672.55).abs() < 0.01, "{r:?}");
    }

    /// One row is the constant-load life; a standstill row adds time but no damage, so the
    /// life in revolutions stays and the hours grow; a factor < 1 on a row shortens the life.
    #[test]
    fn limits() {
        let one = duty_life(14000.0, 3.0, &[row(3000.0, 1000.0, 1.0)]).unwrap();
        assert!((one.l10_mrev - (14000.0f64 / 3000.0).powi(3)).abs() < 1e-9);
        let idle = duty_life(
            14000.0,
            3.0,
            &[row(3000.0, 1000.0, 0.5), row(9000.0, 0.0, 0.5)],
        )
        .unwrap();
        assert!((idle.l10_mrev - one.l10_mrev).abs() < 1e-9);
        assert!((idle.miner_hours / one.miner_hours - 2.0).abs() < 1e-12);
        let mut rows = [row(2000.0, 1000.0, 0.5), row(4000.0, 2000.0, 0.5)];
        let base = duty_life(14000.0, 3.0, &rows).unwrap();
        rows[1].factor = 0.5;
        let worse = duty_life(14000.0, 3.0, &rows).unwrap();
        assert!(worse.miner_mrev < base.miner_mrev && worse.l10_mrev == base.l10_mrev);
    }

    /// A pure radial spectrum on a 6205 gives the same numbers as the rows' loads directly;
    /// the parser skips a header and comments and names the bad line.
    #[test]
    fn spectrum_on_a_bearing() {
        let b = crate::geometry::presets::preset("6205")
            .unwrap()
            .build()
            .unwrap();
        let r = crate::ratings::load_ratings(&b).unwrap();
        let rows = parse_spectrum(
            "fr_n, fa_n, speed_rpm, time_share\n2000,0,1000,0.5 # light\n4000 0 2000 0.5\n",
            "spectrum",
        )
        .unwrap();
        let got = spectrum_life(&b, &r, &rows, &|_| None, None).unwrap();
        let want = duty_life(
            r.c,
            3.0,
            &[row(2000.0, 1000.0, 0.5), row(4000.0, 2000.0, 0.5)],
        )
        .unwrap();
        assert!((got.miner_mrev / want.miner_mrev - 1.0).abs() < 1e-12);
        let e = parse_spectrum("1,2,3\n", "spectrum")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 1"), "{e}");
    }

    #[test]
    fn shares_must_add_to_one() {
        let e = duty_life(
            14000.0,
            3.0,
            &[row(2000.0, 1000.0, 0.5), row(4000.0, 2000.0, 0.4)],
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("duty.time_share") && e.contains("add to 1"),
            "{e}"
        );
        let e = duty_life(14000.0, 3.0, &[row(-1.0, 1000.0, 1.0)])
            .unwrap_err()
            .to_string();
        assert!(e.contains("duty[0].load"), "{e}");
    }
}
