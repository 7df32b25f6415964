//! The life of several rows together: the Lundberg–Palmgren system life (docs/physics.md
//! §11). Each row's survival follows a two-parameter Weibull distribution with slope `e`
//! (10/9 for ball bearings, 9/8 for roller bearings, the dispersion exponents of ISO 281's
//! life equations and of ISO/TS 16281); the system survives when every row does, so at
//! the 90 % reliability of the `L10` lives `sum_i (L / L_i)^(e_i) = 1`, which for equal
//! slopes is `L = (sum_i L_i^(-e))^(-1/e)` (Harris & Kotzalas Vol. 2 ch. 11).

use crate::geometry::element::ElementKind;

/// Weibull slope of an element kind's life distribution.
pub fn weibull_slope(kind: ElementKind) -> f64 {
    match kind {
        ElementKind::Ball => 10.0 / 9.0,
        ElementKind::Roller => 9.0 / 8.0,
    }
}

/// The system `L10` from the rows' `(L10, slope)` (any unit of life); a row without a life
/// (unloaded: `None`, or infinite) does not fail. `None` when no row has a finite life.
pub fn system_life(lives: &[(Option<f64>, f64)]) -> Option<f64> {
    // The rows that can fail, read in place (no allocation: a component's output step
    // calls this at every step).
    let finite = || {
        lives
            .iter()
            .filter_map(|(l, e)| l.filter(|l| l.is_finite() && *l > 0.0).map(|l| (l, *e)))
    };
    let (_, e0) = finite().next()?;
    if finite().all(|(_, e)| e == e0) {
        let s: f64 = finite().map(|(l, _)| l.powf(-e0)).sum();
        return Some(s.powf(-1.0 / e0));
    }
    // Mixed slopes: g(L) = sum (L/L_i)^e_i - 1 increases in L; the root lies between
    // min L_i n^(-1/e_min) and min L_i. Bisection in log L.
    let lmin = finite().map(|f| f.0).fold(f64::INFINITY, f64::min);
    let emin = finite().map(|f| f.1).fold(f64::INFINITY, f64::min);
    let g = |l: f64| finite().map(|(li, e)| (l / li).powf(e)).sum::<f64>() - 1.0;
    let (mut lo, mut hi) = (
        (lmin * (finite().count() as f64).powf(-1.0 / emin)).ln(),
        lmin.ln(),
    );
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid.exp()) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
        if hi - lo < 1e-15 {
            break;
        }
    }
    Some((0.5 * (lo + hi)).exp())
}
