//! The Hertz load–deflection constant `Kc` as a function of the contact angle, for one race.
//!
//! This is the ONE place the quasi-static model gets `Kc(alpha)` from. It samples
//! [`PointContact::new`]`(Curvature::ball_race(D, dm, alpha, f, race), E').kc` (docs/physics.md
//! §3; Harris & Kotzalas Vol. 1 ch. 6) on a uniform grid in `c = cos(alpha)` once per bearing
//! and interpolates with cubic Hermite polynomials (node slopes by central differences of the
//! exact function), so the per-ball kernel gets `Kc` and `dKc/dc` without solving the
//! ellipticity equation. Swapping in the contact module's own fast table means changing
//! [`KcTable::new`] and [`KcTable::eval`] only.

use crate::contact::{ContactTable, Curvature, PointContact, Race};
use crate::geometry::Bearing;

/// Number of grid intervals over `c in [0, 1]`.
const N: usize = 128;

/// `Kc(cos alpha)` for one race of one bearing.
#[derive(Debug, Clone)]
pub(crate) struct KcTable {
    /// Per interval, the cubic `Kc = c0 + t (c1 + t (c2 + t c3))` in `t in [0, 1]` (the
    /// Hermite interpolant of the node values and slopes in power form: one contiguous
    /// 32-byte read and Horner's rule per lookup).
    coef: Vec<[f64; 4]>,
}

/// The exact constant at `cos(alpha) = c` (through the contact module).
pub(crate) fn kc_exact(b: &Bearing, race: Race, c: f64) -> f64 {
    let (f, e) = match race {
        Race::Inner => (b.fi(), b.e_eff_inner()),
        Race::Outer => (b.fo(), b.e_eff_outer()),
    };
    let alpha = c.clamp(0.0, 1.0).acos();
    PointContact::new(Curvature::ball_race(b.d, b.dm, alpha, f, race), e).kc
}

impl KcTable {
    /// Sample the exact constant.
    pub fn new(b: &Bearing, race: Race) -> Self {
        let h = 1.0 / N as f64;
        let eps = 1e-4 * h;
        let mut v = Vec::with_capacity(N + 1);
        let mut dv = Vec::with_capacity(N + 1);
        for k in 0..=N {
            let c = k as f64 * h;
            v.push(kc_exact(b, race, c));
            // One-sided at the ends of [0, 1], central inside.
            let (lo, hi) = ((c - eps).max(0.0), (c + eps).min(1.0));
            dv.push((kc_exact(b, race, hi) - kc_exact(b, race, lo)) / (hi - lo));
        }
        let coef = (0..N)
            .map(|k| {
                let (y0, y1) = (v[k], v[k + 1]);
                let (m0, m1) = (dv[k] * h, dv[k + 1] * h);
                [
                    y0,
                    m0,
                    3.0 * (y1 - y0) - 2.0 * m0 - m1,
                    2.0 * (y0 - y1) + m0 + m1,
                ]
            })
            .collect();
        KcTable { coef }
    }

    /// `(Kc, dKc/dc)` at `c = cos(alpha)`; `Kc` depends on `|c|` (clamped to 1).
    #[inline]
    pub fn eval(&self, c: f64) -> (f64, f64) {
        let ca = c.abs().min(1.0);
        let s = ca * N as f64;
        let k = (s as usize).min(N - 1); // s >= 0: truncation is floor
        let t = s - k as f64;
        let p = &self.coef[k];
        let val = p[0] + t * (p[1] + t * (p[2] + t * p[3]));
        let dval = (p[1] + t * (2.0 * p[2] + t * 3.0 * p[3])) * N as f64;
        (val, if c < 0.0 { -dval } else { dval })
    }
}

/// The contact tables of one bearing: `Kc` (inner, outer) and the reports' fine tables.
#[derive(Clone)]
pub(crate) struct Tables {
    pub kc: (KcTable, KcTable),
    pub report: (ContactTable, ContactTable),
}

/// The contact tables of `bearing`, built once per process for each distinct
/// `(D, dm, f_i, f_o, E'_i, E'_o)` (the only inputs of the tables, compared bit for bit, so a
/// table from the memo is the table a fresh build gives): a sweep of one bearing over speed
/// and displacement builds them once instead of at every point (they were 70 % of a
/// quasi-static point's instructions). The last 8 bearings are kept.
pub(crate) fn contact_tables(bearing: &Bearing) -> Tables {
    type Key = [u64; 6];
    static MEMO: std::sync::Mutex<Vec<(Key, Tables)>> = std::sync::Mutex::new(Vec::new());
    let key: Key = [
        bearing.d,
        bearing.dm,
        bearing.fi(),
        bearing.fo(),
        bearing.e_eff_inner(),
        bearing.e_eff_outer(),
    ]
    .map(f64::to_bits);
    if let Ok(memo) = MEMO.lock() {
        if let Some((_, t)) = memo.iter().find(|(k, _)| *k == key) {
            return t.clone();
        }
    }
    let t = Tables {
        kc: (
            KcTable::new(bearing, Race::Inner),
            KcTable::new(bearing, Race::Outer),
        ),
        report: (
            ContactTable::fine(bearing, Race::Inner),
            ContactTable::fine(bearing, Race::Outer),
        ),
    };
    if let Ok(mut memo) = MEMO.lock() {
        if memo.len() >= 8 {
            memo.remove(0);
        }
        memo.push((key, t.clone()));
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::preset;

    /// The memo hands out the tables a fresh build gives, bit for bit, and never another
    /// bearing's: the 6205 and the 6012 (other D, dm, f) and the 6205 again after them.
    #[test]
    fn memoised_tables_are_the_fresh_tables_of_that_bearing() {
        let bits = |t: &KcTable| -> Vec<u64> {
            (0..=200)
                .map(|k| t.eval(k as f64 / 200.0).0.to_bits())
                .collect()
        };
        for name in ["6205", "6012", "6205", "7008ce"] {
            let b = preset(name).unwrap().build().unwrap();
            let m = contact_tables(&b);
            let again = contact_tables(&b);
            for race in [Race::Inner, Race::Outer] {
                let (got, got2) = match race {
                    Race::Inner => (&m.kc.0, &again.kc.0),
                    Race::Outer => (&m.kc.1, &again.kc.1),
                };
                let fresh = KcTable::new(&b, race);
                assert_eq!(bits(got), bits(&fresh), "{name} {race:?}");
                assert_eq!(bits(got2), bits(&fresh), "{name} {race:?} from the memo");
            }
            assert_eq!(m.report.0, ContactTable::fine(&b, Race::Inner), "{name}");
            assert_eq!(m.report.1, ContactTable::fine(&b, Race::Outer), "{name}");
        }
        let (a, b) = (
            contact_tables(&preset("6205").unwrap().build().unwrap()),
            contact_tables(&preset("6012").unwrap().build().unwrap()),
        );
        assert_ne!(bits(&a.kc.0), bits(&b.kc.0));
    }

    #[test]
    fn table_matches_the_exact_constant_between_nodes() {
        let b = preset("acbb16").unwrap().build().unwrap();
        for race in [Race::Inner, Race::Outer] {
            let t = KcTable::new(&b, race);
            for k in 0..57 {
                let c = (k as f64 + 0.37) / 57.0;
                let exact = kc_exact(&b, race, c);
                let (v, dv) = t.eval(c);
                assert!((v / exact - 1.0).abs() < 1e-7, "c {c}: {v} vs {exact}");
                let h = 1e-5;
                let fd = (kc_exact(&b, race, c + h) - kc_exact(&b, race, c - h)) / (2.0 * h);
                assert!(
                    (dv - fd).abs() <= 1e-4 * fd.abs() + 1e-6 * exact,
                    "{dv} {fd}"
                );
            }
        }
    }
}
