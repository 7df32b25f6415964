//! Hertz point contact (docs/physics.md §3; docs/physics.md §N3).
//!
//! Sources: Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed., Vol. 1 ch. 6 (curvature
//! sums, `F(rho)`, the ellipticity equation, `Q = K delta^1.5`, contacts in series);
//! Hamrock & Dowson, *Ball Bearing Lubrication* ch. 3 (the `kappa`, `E'`, `Rx`, `Ry`
//! notation used here and `Kc = pi kappa E' sqrt(2 E R / (9 K³))`); Johnson, *Contact
//! Mechanics* §4.2 (the sphere-on-flat limit); Brewe & Hamrock (1977) (the closed-form fits).
//!
//! Notation: `Rx` rolling direction, `Ry` transverse, `1/R = Sum rho = 1/Rx + 1/Ry`,
//! `ratio = Ry/Rx`, `kappa = a/b >= 1`, `m = 1 - 1/kappa²`, `K = K(m)`, `E = E(m)` (complete
//! elliptic integrals, [`super::elliptic`]), `E' = 2 / ((1-nu1²)/E1 + (1-nu2²)/E2)`.
//!
//! - Ellipticity equation (Harris & Kotzalas Vol. 1 ch. 6; docs/physics.md §N3.1):
//!   `ratio = (kappa² E - K)/(K - E)`, the same as
//!   `F(rho) = ((kappa²+1) E - 2K)/((kappa²-1) E)` with `F(rho) = (ratio-1)/(ratio+1)`.
//! - Semi-axes `a = (6 kappa² E Q R/(pi E'))^(1/3)` (along the larger radius, i.e. across
//!   the rolling direction when `Ry > Rx`), `b = (6 E Q R/(pi kappa E'))^(1/3)`.
//! - Approach `delta = K (9/(2 E R) (Q/(pi kappa E'))²)^(1/3)`, so `Q = Kc delta^1.5` with
//!   `Kc = pi kappa E' sqrt(2 E R/(9 K³))`.
//! - Peak pressure `p0 = 3Q/(2 pi a b)`.
//!
//! Three ways to get the ellipse: [`Ellipse::exact`] (Newton on `ln kappa`, machine
//! precision, 3–4 AGM evaluations; 2 when warm-started by [`Ellipse::exact_from`]),
//! [`ellipse_fit`] (Brewe & Hamrock 1977, a few per cent off, measured errors in its doc),
//! and for a bearing race whose contact angle changes [`ContactTable`] (loop-free cubic
//! Hermite lookup of `Kc` and the semi-axis coefficients against `cos alpha`).

use super::elliptic::{agm, Agm};
use crate::error::{positive, Error, Result};
use crate::geometry::Bearing;
use std::f64::consts::PI;

/// Which race a ball touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Race {
    /// The inner race (convex in the rolling direction).
    Inner,
    /// The outer race (concave in the rolling direction).
    Outer,
}

/// Curvature sums of a contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curvature {
    /// Curvature sum `1/Rx + 1/Ry`, 1/m.
    pub sum_rho: f64,
    /// Effective radius in the rolling direction, m.
    pub rx: f64,
    /// Effective radius across the rolling direction, m.
    pub ry: f64,
}

impl Curvature {
    /// Ball of diameter `d` on a race of groove curvature ratio `f` at contact angle `alpha`
    /// in a bearing of pitch diameter `dm` (Harris & Kotzalas Vol. 1 ch. 2 and 6; docs/physics.md
    /// §3): ball `2/D` in both planes; inner race `2/D gamma/(1-gamma)` rolling, outer race
    /// `-2/D gamma/(1+gamma)`; both `-1/(f D)` transverse; `gamma = D cos(alpha)/dm`.
    pub fn ball_race(d: f64, dm: f64, alpha: f64, f: f64, race: Race) -> Self {
        Self::ball_race_cos(d, dm, alpha.cos(), f, race)
    }

    /// [`Curvature::ball_race`] given `cos(alpha)` instead of `alpha`.
    pub fn ball_race_cos(d: f64, dm: f64, cos_alpha: f64, f: f64, race: Race) -> Self {
        let gamma = d * cos_alpha / dm;
        let rho_race_x = match race {
            Race::Inner => 2.0 / d * gamma / (1.0 - gamma),
            Race::Outer => -2.0 / d * gamma / (1.0 + gamma),
        };
        let inv_rx = 2.0 / d + rho_race_x;
        let inv_ry = 2.0 / d - 1.0 / (f * d);
        Curvature {
            sum_rho: inv_rx + inv_ry,
            rx: 1.0 / inv_rx,
            ry: 1.0 / inv_ry,
        }
    }

    /// Sphere of radius `r` on a flat.
    pub fn sphere_on_flat(r: f64) -> Self {
        Curvature {
            sum_rho: 2.0 / r,
            rx: r,
            ry: r,
        }
    }

    /// Two crossed or aligned bodies given by their effective radii `rx`, `ry` (m, > 0).
    pub fn from_radii(rx: f64, ry: f64) -> Self {
        Curvature {
            sum_rho: 1.0 / rx + 1.0 / ry,
            rx,
            ry,
        }
    }

    /// Radius ratio `Ry/Rx` (>= 1 for ball bearings).
    pub fn ratio(&self) -> f64 {
        self.ry / self.rx
    }

    /// Curvature difference `F(rho) = (1/Rx - 1/Ry)/(1/Rx + 1/Ry)`, in magnitude.
    pub fn f_rho(&self) -> f64 {
        ((1.0 / self.rx - 1.0 / self.ry) / self.sum_rho).abs()
    }

    /// Check that both radii and the sum are finite and positive (a point contact between
    /// convex-enough bodies); the error names `field`.
    pub fn validate(&self, field: &str) -> Result<()> {
        positive(&format!("{field}.rx"), self.rx)?;
        positive(&format!("{field}.ry"), self.ry)?;
        positive(&format!("{field}.sum_rho"), self.sum_rho)?;
        let r = self.ratio();
        if !(1.0 / MAX_RATIO..=MAX_RATIO).contains(&r) {
            return Err(Error::invalid(
                format!("{field}.ratio"),
                r,
                format!("Ry/Rx in [1e-12, {MAX_RATIO:e}] (beyond that it is a line contact)"),
            ));
        }
        Ok(())
    }
}

/// Largest `Ry/Rx` (or its inverse) the checked constructors accept.
pub const MAX_RATIO: f64 = 1e12;

/// The dimensionless shape of the contact ellipse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipse {
    /// Ellipticity `kappa = a/b >= 1`.
    pub kappa: f64,
    /// Complete elliptic integral of the first kind `K(m)`, `m = 1 - 1/kappa²`.
    pub k: f64,
    /// Complete elliptic integral of the second kind `E(m)`.
    pub e: f64,
}

/// Logarithmic sensitivities of the exact ellipse to the radius ratio:
/// `d ln(x) / d ln(Ry/Rx)` for `x = kappa, K, E`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipseSensitivity {
    /// `d ln kappa / d ln ratio`.
    pub kappa: f64,
    /// `d ln K / d ln ratio`.
    pub k: f64,
    /// `d ln E / d ln ratio`.
    pub e: f64,
}

/// Result of the Newton solve on `s = ln kappa` for `L = |ln ratio|`.
struct KappaSolve {
    s: f64,
    k: f64,
    e: f64,
    iterations: usize,
}

/// `ln ratio(s)` residual pieces at `s = ln kappa > 0`: returns `(agm, g, g')` with
/// `g = ln((kappa² E - K)/(K - E))` written as `2s + ln(m - S) - ln S` (no cancellation:
/// `m - S = m/2 - T`, `S = m/2 + T`, and `ln((m - S)/S) = ln(1 - 2T/S)`) and
/// `g' = dg/ds = 2 + (2T - S²)/(S (m - S))` (from `dK/dm`, `dE/dm` of DLMF 19.4.1 and
/// `dm/ds = 2(1 - m)`).
fn ln_ratio_of(s: f64) -> (Agm, f64, f64) {
    let m1 = (-2.0 * s).exp();
    let m = -(-2.0 * s).exp_m1();
    let r = agm(m, m1);
    let ms = 0.5 * m - r.t;
    let sv = r.s;
    // ln((m - S)/S) = ln(1 - 2T/S): through ln_1p while 2T/S is small (near-circular
    // contacts, where ln(m - S) and ln S are large and nearly cancel).
    let x = 2.0 * r.t / sv;
    let g = 2.0 * s
        + if x < 0.5 {
            (-x).ln_1p()
        } else {
            ms.ln() - sv.ln()
        };
    let gp = 2.0 + (2.0 * r.t - sv * sv) / (sv * ms);
    (r, g, gp)
}

/// Solve `ln ratio(s) = l` for `s = ln kappa` by safeguarded Newton from `s0`.
/// `l > 0` (ratio > 1). The root is bracketed by `[0, inf)`; a Newton step leaving the
/// current bracket is replaced by bisection (or doubling while no upper bound is known).
fn solve_s(l: f64, s0: f64) -> KappaSolve {
    let mut s = if s0.is_finite() && s0 > 0.0 {
        s0
    } else {
        2.0 / PI * l
    };
    let (mut lo, mut hi) = (0.0_f64, f64::INFINITY);
    let mut iterations = 0;
    loop {
        iterations += 1;
        let (r, g, gp) = ln_ratio_of(s);
        let res = g - l;
        let step = -res / gp;
        if res == 0.0 || iterations >= 60 {
            return KappaSolve {
                s,
                k: r.k,
                e: r.e,
                iterations,
            };
        }
        if step.is_finite() && step.abs() <= NEWTON_FINISH {
            // Quadratic convergence: the error of `s + step` is O(step²) < 1e-16. Move K and
            // E to it by first order (error O(step²) too) instead of another AGM:
            // d ln K/ds = (m - S)/m = 1/2 - T/m, d ln E/ds = -(1/2 + T/m)(1 - m)/(1 - S).
            let m = r.m;
            let tm = if m > 0.0 { r.t / m } else { 0.0 };
            let m1 = (-2.0 * s).exp();
            let dlk = 0.5 - tm;
            let dle = -(0.5 + tm) * m1 / (1.0 - r.s);
            return KappaSolve {
                s: s + step,
                k: r.k * (1.0 + dlk * step),
                e: r.e * (1.0 + dle * step),
                iterations,
            };
        }
        if res > 0.0 {
            hi = s;
        } else {
            lo = s;
        }
        let mut next = s + step;
        if !(next > lo && next < hi && gp.is_finite() && gp > 0.0) {
            next = if hi.is_finite() {
                0.5 * (lo + hi)
            } else {
                2.0 * s.max(lo) + 1.0
            };
        }
        if next == s {
            return KappaSolve {
                s,
                k: r.k,
                e: r.e,
                iterations,
            };
        }
        s = next;
    }
}

/// Newton step on `ln kappa` below which the iteration is finished by one last step (its
/// error is `O(step²)`, below rounding).
const NEWTON_FINISH: f64 = 1e-8;

/// Below this `|ln ratio|` the circular-contact series is used: `ln kappa = 2L/3 + O(L²)`
/// (expanding `ratio = (kappa² E - K)/(K - E) = 1 + 3m/4 + O(m²)`), which is exact to
/// rounding in `kappa`, `K`, `E` there.
const SMALL_L: f64 = 1e-10;

fn circular() -> Ellipse {
    Ellipse {
        kappa: 1.0,
        k: PI / 2.0,
        e: PI / 2.0,
    }
}

impl Ellipse {
    /// Exact ellipse for `ratio = Ry/Rx` (or its inverse: the ellipse depends on
    /// `max(ratio, 1/ratio)`). Solves the Hertz ellipticity equation
    /// `ratio = (kappa² E - K)/(K - E)` (Harris & Kotzalas Vol. 1 ch. 6, Hamrock & Dowson
    /// ch. 3) by Newton on `ln kappa` from `kappa0 = ratio^(2/pi)` (Hamrock & Brewe 1983's
    /// estimate); `ratio = 1` gives exactly `kappa = 1`, `K = E = pi/2`. Machine precision
    /// with 3 AGM evaluations for `ratio` in `[1.2, 1000]` and at most 4 up to `1e12`
    /// (measured on 4000 log-spaced ratios): Newton stops once its step on `ln kappa` is
    /// below 1e-8 and finishes that last step by a first-order update of `K` and `E`
    /// (error `O(step²)`, below rounding); agreement with mpmath at 40 digits is a few ulp.
    /// Input must be finite and positive (see [`Ellipse::try_exact`]); otherwise the
    /// fields are NaN.
    pub fn exact(ratio: f64) -> Ellipse {
        Self::exact_from(ratio, f64::NAN)
    }

    /// [`Ellipse::exact`] warm-started from a previous `kappa` (for a contact angle that
    /// changes slowly between calls: 2 AGM evaluations instead of 3–4 for a 0.01 deg
    /// step, test `warm_start_agrees_with_cold_and_is_short`). A guess that is
    /// not finite or `<= 1` falls back to the cold start.
    pub fn exact_from(ratio: f64, kappa_guess: f64) -> Ellipse {
        Self::solve(ratio, kappa_guess).0
    }

    /// The number of AGM evaluations [`Ellipse::exact_from`] uses (0 at `ratio = 1`); for
    /// tests and benchmarks.
    pub fn exact_iterations(ratio: f64, kappa_guess: f64) -> usize {
        Self::solve(ratio, kappa_guess).1
    }

    fn solve(ratio: f64, kappa_guess: f64) -> (Ellipse, usize, Option<KappaSolve>) {
        if !(ratio.is_finite() && ratio > 0.0) {
            let nan = Ellipse {
                kappa: f64::NAN,
                k: f64::NAN,
                e: f64::NAN,
            };
            return (nan, 0, None);
        }
        let l = ratio.ln().abs();
        if l == 0.0 {
            return (circular(), 0, None);
        }
        if l < SMALL_L {
            let s = 2.0 / 3.0 * l;
            let m = -(-2.0 * s).exp_m1();
            let r = agm(m, (-2.0 * s).exp());
            let el = Ellipse {
                kappa: s.exp(),
                k: r.k,
                e: r.e,
            };
            return (el, 1, None);
        }
        let sol = solve_s(l, kappa_guess.ln());
        let el = Ellipse {
            kappa: sol.s.exp(),
            k: sol.k,
            e: sol.e,
        };
        (el, sol.iterations, Some(sol))
    }

    /// Checked [`Ellipse::exact`]: `ratio` finite, in `[1/MAX_RATIO, MAX_RATIO]`.
    pub fn try_exact(ratio: f64) -> Result<Ellipse> {
        if !(ratio.is_finite() && (1.0 / MAX_RATIO..=MAX_RATIO).contains(&ratio)) {
            return Err(Error::invalid(
                "contact.ratio",
                ratio,
                format!("Ry/Rx finite in [1e-12, {MAX_RATIO:e}]"),
            ));
        }
        Ok(Self::exact(ratio))
    }

    /// The exact ellipse and its sensitivities `d ln(kappa, K, E)/d ln(ratio)` by implicit
    /// differentiation of the ellipticity equation: `d ln kappa/d ln ratio = 1/g'` with
    /// `g' = d ln ratio/d ln kappa`, `d ln K/d ln kappa = (m - S)/m`,
    /// `d ln E/d ln kappa = -S(1-m)/(m(1-S))`, `S = 1 - E/K` (DLMF 19.4.1). Limits at
    /// `ratio = 1`: `2/3`, `1/3`, `-1/3`. Used to build [`ContactTable`].
    pub fn exact_with_sensitivity(ratio: f64) -> (Ellipse, EllipseSensitivity) {
        let (el, _, sol) = Self::solve(ratio, f64::NAN);
        let sign = if ratio >= 1.0 { 1.0 } else { -1.0 };
        let sens = match sol {
            None => EllipseSensitivity {
                kappa: sign * 2.0 / 3.0,
                k: sign / 3.0,
                e: -sign / 3.0,
            },
            Some(sol) => {
                let (r, _, gp) = ln_ratio_of(sol.s);
                let ds = 1.0 / gp;
                let m = r.m;
                let tm = r.t / m;
                let m1 = (-2.0 * sol.s).exp();
                EllipseSensitivity {
                    kappa: sign * ds,
                    k: sign * ds * (0.5 - tm),
                    e: -sign * ds * (0.5 + tm) * m1 / (1.0 - r.s),
                }
            }
        };
        if !ratio.is_finite() || ratio <= 0.0 {
            let nan = EllipseSensitivity {
                kappa: f64::NAN,
                k: f64::NAN,
                e: f64::NAN,
            };
            return (el, nan);
        }
        (el, sens)
    }

    /// Brewe & Hamrock (1977) fits, see [`ellipse_fit`].
    pub fn fit(ratio: f64) -> Ellipse {
        ellipse_fit(ratio)
    }

    /// Elliptic parameter `m = 1 - 1/kappa²`.
    pub fn m(&self) -> f64 {
        1.0 - 1.0 / (self.kappa * self.kappa)
    }

    /// Dimensionless semi-major axis `a* = (2 kappa² E/pi)^(1/3)` (Harris & Kotzalas Vol. 1
    /// ch. 6; `a = a* (3Q/(E' Sum rho))^(1/3)`).
    pub fn a_star(&self) -> f64 {
        (2.0 * self.kappa * self.kappa * self.e / PI).cbrt()
    }

    /// Dimensionless semi-minor axis `b* = (2E/(pi kappa))^(1/3)`.
    pub fn b_star(&self) -> f64 {
        (2.0 * self.e / (PI * self.kappa)).cbrt()
    }

    /// Dimensionless approach `delta* = (2K/pi) (pi/(2 kappa² E))^(1/3)`
    /// (`delta = delta* (3Q/(E' Sum rho))^(2/3) Sum rho/2`).
    pub fn delta_star(&self) -> f64 {
        2.0 * self.k / PI * (PI / (2.0 * self.kappa * self.kappa * self.e)).cbrt()
    }
}

/// Brewe & Hamrock (1977) fits ("HB77" in docs/physics.md §N3.4): `kappa ~ 1.0339 (Ry/Rx)^0.636`,
/// `E ~ 1.0003 + 0.5968 Rx/Ry`, `K ~ 1.5277 + 0.6023 ln(Ry/Rx)`.
///
/// Measured against [`Ellipse::exact`] (test `fit_error_is_as_documented` in
/// tests/hertz.rs, 2000 log-spaced ratios): maximum relative error over `Ry/Rx` in
/// `[1.5, 100]`: `kappa` 6.3 %, `K` 1.0 %, `E` 0.51 % (both at ratio 1.5), `a*` 4.2 %,
/// `b*` 2.0 %, `delta*` 3.8 %, `Kc` 5.9 %. At the 209 bearing's contacts (alpha = 0):
/// inner `kappa` +1.55 %, `Kc` +1.64 %, `delta` -1.08 %; outer `kappa` +0.48 %, `Kc`
/// +0.61 %, `delta` -0.40 % (as docs/physics.md §N3.4). Use [`Ellipse::exact`] or
/// [`ContactTable`] in production.
pub fn ellipse_fit(ratio: f64) -> Ellipse {
    let r = ratio.max(1.0 / ratio);
    Ellipse {
        kappa: 1.0339 * r.powf(0.636),
        k: 1.5277 + 0.6023 * r.ln(),
        e: 1.0003 + 0.5968 / r,
    }
}

/// Hamrock & Brewe (1983) simplified fits ("HB83" in docs/physics.md §N3.4):
/// `kappa ~ (Ry/Rx)^(2/pi)`, `E ~ 1 + q Rx/Ry`, `K ~ pi/2 + q ln(Ry/Rx)`, `q = pi/2 - 1`.
/// Exact at `ratio = 1`. Measured maximum relative error over `[1.5, 100]`: `kappa` 3.8 %,
/// `K` 2.1 %, `E` 0.91 %, `a*` 2.7 %, `b*` 1.2 %, `delta*` 4.1 %, `Kc` 6.5 % (test
/// `fit_error_is_as_documented`).
pub fn ellipse_fit_hb83(ratio: f64) -> Ellipse {
    let r = ratio.max(1.0 / ratio);
    let q = PI / 2.0 - 1.0;
    Ellipse {
        kappa: r.powf(2.0 / PI),
        k: PI / 2.0 + q * r.ln(),
        e: 1.0 + q / r,
    }
}

/// Everything needed to go between load and approach at one contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointContact {
    /// Curvatures.
    pub curvature: Curvature,
    /// Ellipse shape.
    pub ellipse: Ellipse,
    /// Effective modulus `E'`, Pa.
    pub e_eff: f64,
    /// Load–deflection constant `Kc` in `Q = Kc delta^1.5`, N/m^1.5.
    pub kc: f64,
}

impl PointContact {
    /// Build from curvature and effective modulus with the exact ellipse
    /// ([`Ellipse::exact`]). Unchecked: see [`PointContact::try_new`].
    pub fn new(curvature: Curvature, e_eff: f64) -> Self {
        Self::from_ellipse(curvature, Ellipse::exact(curvature.ratio()), e_eff)
    }

    /// Checked [`PointContact::new`]: curvature radii positive, ratio in range, `E' > 0`.
    pub fn try_new(curvature: Curvature, e_eff: f64) -> Result<Self> {
        curvature.validate("contact.curvature")?;
        positive("contact.e_eff", e_eff)?;
        Ok(Self::new(curvature, e_eff))
    }

    /// [`PointContact::new`] with the exact solve warm-started from `kappa_guess` (e.g. the
    /// previous step's `ellipse.kappa`).
    pub fn new_warm(curvature: Curvature, e_eff: f64, kappa_guess: f64) -> Self {
        Self::from_ellipse(
            curvature,
            Ellipse::exact_from(curvature.ratio(), kappa_guess),
            e_eff,
        )
    }

    /// Build with the Brewe–Hamrock fits ([`ellipse_fit`]); for measuring the fit error.
    pub fn with_fit(curvature: Curvature, e_eff: f64) -> Self {
        Self::from_ellipse(curvature, ellipse_fit(curvature.ratio()), e_eff)
    }

    /// Build from a given ellipse: `Kc = pi kappa E' sqrt(2 E R/(9 K³))`, `R = 1/Sum rho`
    /// (Hamrock & Dowson ch. 3; equal to Harris's `2^(5/2)/(3 eta) Sum rho^(-1/2)
    /// delta*^(-3/2)` with `eta = 2/E'`).
    pub fn from_ellipse(curvature: Curvature, ellipse: Ellipse, e_eff: f64) -> Self {
        let r = 1.0 / curvature.sum_rho;
        let Ellipse { kappa, k, e } = ellipse;
        let kc = PI * kappa * e_eff * (2.0 * e * r / (9.0 * k.powi(3))).sqrt();
        PointContact {
            curvature,
            ellipse,
            e_eff,
            kc,
        }
    }

    /// Ball of `bearing` on one race at contact angle `alpha` (rad), exact ellipse, the
    /// race's groove curvature and the ball–race `E'`.
    pub fn ball_race(bearing: &Bearing, alpha: f64, race: Race) -> Self {
        let (f, e_eff) = race_data(bearing, race);
        Self::new(
            Curvature::ball_race(bearing.d, bearing.dm, alpha, f, race),
            e_eff,
        )
    }

    /// Load for approach `delta` (zero for `delta <= 0`), N.
    pub fn load(&self, delta: f64) -> f64 {
        if delta > 0.0 {
            self.kc * delta * delta.sqrt()
        } else {
            0.0
        }
    }

    /// Load and contact stiffness `(Q, dQ/d delta) = (Kc delta^1.5, 1.5 Kc delta^0.5)` for
    /// `delta > 0`, `(0, 0)` otherwise: the law is C¹ at `delta = 0` (both vanish there).
    pub fn load_and_stiffness(&self, delta: f64) -> (f64, f64) {
        hertz_load_and_stiffness(self.kc, delta)
    }

    /// Approach for load `q`, m.
    pub fn deflection(&self, q: f64) -> f64 {
        (q.max(0.0) / self.kc).powf(2.0 / 3.0)
    }

    /// Semi-axis coefficients `(ca, cb)` with `a = ca Q^(1/3)`, `b = cb Q^(1/3)`:
    /// `ca = (6 kappa² E R/(pi E'))^(1/3)`, `cb = (6 E R/(pi kappa E'))^(1/3)`.
    pub fn semi_axis_coefficients(&self) -> (f64, f64) {
        let Ellipse { kappa, e, .. } = self.ellipse;
        let r = 1.0 / self.curvature.sum_rho;
        let ca = (6.0 * kappa * kappa * e * r / (PI * self.e_eff)).cbrt();
        let cb = (6.0 * e * r / (PI * kappa * self.e_eff)).cbrt();
        (ca, cb)
    }

    /// Semi-axes `(a, b)` at load `q`, m (`a` along the larger radius: across the rolling
    /// direction when `Ry > Rx`, as in every ball bearing). Zero for `q <= 0`.
    pub fn semi_axes(&self, q: f64) -> (f64, f64) {
        let (ca, cb) = self.semi_axis_coefficients();
        let q3 = q.max(0.0).cbrt();
        (ca * q3, cb * q3)
    }

    /// Peak (Hertz) pressure at load `q`, `p0 = 3Q/(2 pi a b)`, Pa (zero for `q <= 0`).
    pub fn peak_pressure(&self, q: f64) -> f64 {
        let (a, b) = self.semi_axes(q);
        if a > 0.0 && b > 0.0 {
            1.5 * q / (PI * a * b)
        } else {
            0.0
        }
    }
}

/// `(Q, dQ/d delta)` of `Q = kc delta^1.5` (Harris & Kotzalas Vol. 1 ch. 6), zero for
/// `delta <= 0`; C¹ at zero.
pub fn hertz_load_and_stiffness(kc: f64, delta: f64) -> (f64, f64) {
    if delta > 0.0 {
        let r = delta.sqrt();
        (kc * delta * r, 1.5 * kc * r)
    } else {
        (0.0, 0.0)
    }
}

fn race_data(b: &Bearing, race: Race) -> (f64, f64) {
    match race {
        Race::Inner => (b.fi(), b.e_eff_inner()),
        Race::Outer => (b.fo(), b.e_eff_outer()),
    }
}

/// Load–deflection constant of two contacts in series (Harris & Kotzalas Vol. 1 ch. 7:
/// the approaches add, `delta_n = delta_i + delta_o`):
/// `K_n = (K_i^(-2/3) + K_o^(-2/3))^(-3/2)`.
pub fn series_constant(k_i: f64, k_o: f64) -> f64 {
    (k_i.powf(-2.0 / 3.0) + k_o.powf(-2.0 / 3.0)).powf(-1.5)
}

/// The inner and outer contacts of one ball of a bearing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallRaceContacts {
    /// Ball on the inner race.
    pub inner: PointContact,
    /// Ball on the outer race.
    pub outer: PointContact,
}

impl BallRaceContacts {
    /// Both contacts at the same contact angle `alpha` (rad), exact ellipses.
    pub fn new(bearing: &Bearing, alpha: f64) -> Self {
        Self::at_angles(bearing, alpha, alpha)
    }

    /// Inner contact at `alpha_i`, outer at `alpha_o` (rad), as in the high-speed
    /// quasi-static model (docs/physics.md §4).
    pub fn at_angles(bearing: &Bearing, alpha_i: f64, alpha_o: f64) -> Self {
        BallRaceContacts {
            inner: PointContact::ball_race(bearing, alpha_i, Race::Inner),
            outer: PointContact::ball_race(bearing, alpha_o, Race::Outer),
        }
    }

    /// Series constant `K_n` of the ball between both races ([`series_constant`]).
    pub fn series_constant(&self) -> f64 {
        series_constant(self.inner.kc, self.outer.kc)
    }
}

/// `Kc` and the semi-axis coefficients of a race contact at one contact angle, as read from
/// a [`ContactTable`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactCoefficients {
    /// Load–deflection constant `Kc`, N/m^1.5.
    pub kc: f64,
    /// `dKc/d alpha`, N/m^1.5 per rad.
    pub dkc_dalpha: f64,
    /// `ca` in `a = ca Q^(1/3)` (semi-axis along the larger radius), m/N^(1/3).
    pub a_coef: f64,
    /// `cb` in `b = cb Q^(1/3)`, m/N^(1/3).
    pub b_coef: f64,
}

impl ContactCoefficients {
    /// Load `Kc delta^1.5` for approach `delta` (zero for `delta <= 0`), N.
    pub fn load(&self, delta: f64) -> f64 {
        hertz_load_and_stiffness(self.kc, delta).0
    }

    /// `(Q, dQ/d delta)`; zero for `delta <= 0`, C¹ at zero.
    pub fn load_and_stiffness(&self, delta: f64) -> (f64, f64) {
        hertz_load_and_stiffness(self.kc, delta)
    }

    /// `(Q, dQ/d delta, dQ/d alpha)` at approach `delta` (for a Newton Jacobian in which
    /// the contact angle is a function of the unknowns).
    pub fn load_and_derivatives(&self, delta: f64) -> (f64, f64, f64) {
        let (q, dq) = hertz_load_and_stiffness(self.kc, delta);
        let dqa = if self.kc > 0.0 {
            q * self.dkc_dalpha / self.kc
        } else {
            0.0
        };
        (q, dq, dqa)
    }

    /// Approach for load `q`, m.
    pub fn deflection(&self, q: f64) -> f64 {
        (q.max(0.0) / self.kc).powf(2.0 / 3.0)
    }

    /// Semi-axes `(a, b)` at load `q`, m.
    pub fn semi_axes(&self, q: f64) -> (f64, f64) {
        let q3 = q.max(0.0).cbrt();
        (self.a_coef * q3, self.b_coef * q3)
    }

    /// Peak pressure `3Q/(2 pi a b) = 3 Q^(1/3)/(2 pi ca cb)` at load `q`, Pa.
    pub fn peak_pressure(&self, q: f64) -> f64 {
        1.5 * q.max(0.0).cbrt() / (PI * self.a_coef * self.b_coef)
    }
}

/// Number of table intervals [`ContactTable::new`] uses.
pub const TABLE_INTERVALS: usize = 32;

/// Largest contact angle [`ContactTable::new`] tabulates, rad (80 deg).
pub const TABLE_MAX_ANGLE: f64 = 80.0 * PI / 180.0;

/// Number of table intervals [`ContactTable::fine`] uses: the interpolation error falls
/// like `h^4`, so four times [`TABLE_INTERVALS`] takes the semi-axis coefficients from
/// ~1e-11 to the exact solve's own rounding (test `report_table_matches_exact_solve_to_rounding`
/// in tests/qs_contact_table.rs; 12 KiB per race).
pub const FINE_TABLE_INTERVALS: usize = 128;

/// Fast path for one bearing race: `Kc`, `dKc/d alpha` and the semi-axis coefficients
/// against the contact angle, by piecewise cubic Hermite interpolation in `x = cos alpha`
/// on a uniform grid over `[cos alpha_max, 1]` (node values and `x`-derivatives from the
/// exact solve and [`Ellipse::exact_with_sensitivity`]; docs/physics.md §N3.3). Lookup is
/// loop-free (one index computation, three cubics). Even in `alpha` (the curvatures depend
/// on `cos alpha` only). Angles with `|alpha| > alpha_max` fall back to the exact solve
/// (several times slower, same values to the table's error).
///
/// Measured maximum relative error against the exact solve with the default 32 intervals
/// over `[0, 80 deg]` (test `table_matches_exact_solve` in tests/hertz.rs: every preset,
/// both races, 1281 points uniform in `cos alpha`): `Kc` 8.5e-12, `a_coef` 6.8e-12,
/// `b_coef` 1.5e-11, `dKc/d alpha` 1.1e-8 of `max |dKc/d alpha|`. Asserted bounds: `Kc`,
/// `a_coef`, `b_coef` 1e-10; `dKc/d alpha` 1e-7. (Interpolation error falls like `h^4`:
/// 64 intervals give 5e-13.)
#[derive(Debug, Clone, PartialEq)]
pub struct ContactTable {
    race: Race,
    x_lo: f64,
    inv_h: f64,
    /// Per interval, per quantity (kc, ca, cb): cubic coefficients in `t in [0, 1]`.
    coef: Vec<[[f64; 4]; 3]>,
    d: f64,
    dm: f64,
    f: f64,
    e_eff: f64,
}

impl ContactTable {
    /// Table for `race` of `bearing`, default grid ([`TABLE_INTERVALS`] over
    /// `[0, TABLE_MAX_ANGLE]`).
    pub fn new(bearing: &Bearing, race: Race) -> Self {
        Self::for_race(bearing, race, TABLE_INTERVALS)
    }

    /// Table for `race` of `bearing` on the fine grid ([`FINE_TABLE_INTERVALS`] over
    /// `[0, TABLE_MAX_ANGLE]`): the exact solve's values to rounding, for reports that
    /// must not differ from it (the quasi-static ball reports).
    pub fn fine(bearing: &Bearing, race: Race) -> Self {
        Self::for_race(bearing, race, FINE_TABLE_INTERVALS)
    }

    /// Table for `race` of `bearing`, `intervals` over `[0, TABLE_MAX_ANGLE]`.
    fn for_race(bearing: &Bearing, race: Race, intervals: usize) -> Self {
        let (f, e_eff) = race_data(bearing, race);
        Self::build(
            bearing.d,
            bearing.dm,
            f,
            e_eff,
            race,
            TABLE_MAX_ANGLE,
            intervals,
        )
    }

    /// Tables for both races of `bearing`: `(inner, outer)`.
    pub fn for_bearing(bearing: &Bearing) -> (Self, Self) {
        (
            Self::new(bearing, Race::Inner),
            Self::new(bearing, Race::Outer),
        )
    }

    /// Checked general constructor: ball diameter `d` < pitch diameter `dm`, groove
    /// curvature ratio `f` in `(0.5, 1)`, `E' > 0`, `alpha_max` in `(0, pi/2)` rad,
    /// `intervals` in `[1, 100000]`.
    pub fn from_parts(
        d: f64,
        dm: f64,
        f: f64,
        e_eff: f64,
        race: Race,
        alpha_max: f64,
        intervals: usize,
    ) -> Result<Self> {
        positive("contact_table.d", d)?;
        positive("contact_table.dm", dm)?;
        if d >= dm {
            return Err(Error::invalid("contact_table.d", d, format!("< dm = {dm}")));
        }
        if !(f > 0.5 && f < 1.0) {
            return Err(Error::invalid("contact_table.f", f, "in (0.5, 1)"));
        }
        positive("contact_table.e_eff", e_eff)?;
        if !(alpha_max > 0.0 && alpha_max < PI / 2.0) {
            return Err(Error::invalid(
                "contact_table.alpha_max",
                alpha_max,
                "in (0, pi/2) rad",
            ));
        }
        if !(1..=100_000).contains(&intervals) {
            return Err(Error::invalid(
                "contact_table.intervals",
                intervals,
                "in [1, 100000]",
            ));
        }
        Ok(Self::build(d, dm, f, e_eff, race, alpha_max, intervals))
    }

    fn build(d: f64, dm: f64, f: f64, e_eff: f64, race: Race, alpha_max: f64, n: usize) -> Self {
        let x_lo = alpha_max.cos();
        let h = (1.0 - x_lo) / n as f64;
        let nodes: Vec<[f64; 6]> = (0..=n)
            .map(|j| {
                let x = if j == n { 1.0 } else { x_lo + j as f64 * h };
                node_values(d, dm, f, e_eff, race, x)
            })
            .collect();
        let coef = nodes
            .windows(2)
            .map(|w| {
                let mut c = [[0.0; 4]; 3];
                for (q, cq) in c.iter_mut().enumerate() {
                    let (y0, dy0) = (w[0][2 * q], w[0][2 * q + 1] * h);
                    let (y1, dy1) = (w[1][2 * q], w[1][2 * q + 1] * h);
                    // p(t) = y0 + dy0 t + (3(y1-y0) - 2dy0 - dy1) t² + (2(y0-y1) + dy0 + dy1) t³
                    *cq = [
                        y0,
                        dy0,
                        3.0 * (y1 - y0) - 2.0 * dy0 - dy1,
                        2.0 * (y0 - y1) + dy0 + dy1,
                    ];
                }
                c
            })
            .collect();
        ContactTable {
            race,
            x_lo,
            inv_h: 1.0 / h,
            coef,
            d,
            dm,
            f,
            e_eff,
        }
    }

    /// The race this table is for.
    pub fn race(&self) -> Race {
        self.race
    }

    /// Largest tabulated `|alpha|`, rad.
    pub fn alpha_max(&self) -> f64 {
        self.x_lo.acos()
    }

    /// Coefficients at contact angle `alpha` (rad).
    pub fn eval(&self, alpha: f64) -> ContactCoefficients {
        let (sin_a, cos_a) = alpha.sin_cos();
        self.eval_cos_sin(cos_a, sin_a)
    }

    /// Coefficients given `cos alpha` and `sin alpha` (the quasi-static model has them from
    /// the geometry without an `atan2`).
    pub fn eval_cos_sin(&self, cos_a: f64, sin_a: f64) -> ContactCoefficients {
        let u = (cos_a - self.x_lo) * self.inv_h;
        let n = self.coef.len();
        if !(u >= 0.0 && u <= n as f64 * (1.0 + 1e-12)) {
            return self.eval_exact(cos_a, sin_a);
        }
        let i = (u as usize).min(n - 1);
        let t = u - i as f64;
        let c = &self.coef[i];
        let p = |c: &[f64; 4]| c[0] + t * (c[1] + t * (c[2] + t * c[3]));
        let dp = c[0][1] + t * (2.0 * c[0][2] + t * 3.0 * c[0][3]);
        ContactCoefficients {
            kc: p(&c[0]),
            dkc_dalpha: -sin_a * dp * self.inv_h,
            a_coef: p(&c[1]),
            b_coef: p(&c[2]),
        }
    }

    /// The exact values (cold Newton solve) at `cos alpha`, `sin alpha`: the fallback and
    /// the reference the table is tested against.
    pub fn eval_exact(&self, cos_a: f64, sin_a: f64) -> ContactCoefficients {
        let v = node_values(self.d, self.dm, self.f, self.e_eff, self.race, cos_a);
        ContactCoefficients {
            kc: v[0],
            dkc_dalpha: -sin_a * v[1],
            a_coef: v[2],
            b_coef: v[4],
        }
    }
}

/// `[Kc, dKc/dx, ca, dca/dx, cb, dcb/dx]` at `x = cos alpha` from the exact solve.
/// `d(1/Rx)/dx = (2/dm)/(1-gamma)²` (inner) or `-(2/dm)/(1+gamma)²` (outer), `1/Ry` does not
/// depend on `x`; `d ln ratio/dx = Rx d(1/Rx)/dx`; then
/// `d ln Kc = d ln kappa + (d ln E)/2 - 3(d ln K)/2 - (d ln Sum rho)/2`,
/// `d ln ca = (2 d ln kappa + d ln E - d ln Sum rho)/3`,
/// `d ln cb = (d ln E - d ln kappa - d ln Sum rho)/3`.
fn node_values(d: f64, dm: f64, f: f64, e_eff: f64, race: Race, x: f64) -> [f64; 6] {
    let cv = Curvature::ball_race_cos(d, dm, x, f, race);
    let gamma = d * x / dm;
    let dinv_rx = match race {
        Race::Inner => 2.0 / dm / ((1.0 - gamma) * (1.0 - gamma)),
        Race::Outer => -2.0 / dm / ((1.0 + gamma) * (1.0 + gamma)),
    };
    let dl = dinv_rx * cv.rx;
    let dls = dinv_rx / cv.sum_rho;
    let (el, s) = Ellipse::exact_with_sensitivity(cv.ratio());
    let pc = PointContact::from_ellipse(cv, el, e_eff);
    let (ca, cb) = pc.semi_axis_coefficients();
    let dlkc = (s.kappa + 0.5 * s.e - 1.5 * s.k) * dl - 0.5 * dls;
    let dlca = ((2.0 * s.kappa + s.e) * dl - dls) / 3.0;
    let dlcb = ((s.e - s.kappa) * dl - dls) / 3.0;
    [pc.kc, pc.kc * dlkc, ca, ca * dlca, cb, cb * dlcb]
}

/// Line (roller) contact load law `Q = K_l delta^(10/9)` (Palmgren; Harris & Kotzalas
/// Vol. 1 ch. 6: `delta = 3.84e-5 Q^0.9 / l^0.8`, mm and N, steel on steel). Written
/// dimensionally as `delta = C (Q/E')^0.9 / l^0.8` with `C` fixed by Palmgren's steel
/// constant at `E' = 2 * 206.8 GPa/(1 - 0.3²)`; the scaling with `E'` for other materials is
/// the dimensional one (an assumption: Palmgren's formula is empirical for steel).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineContact {
    /// Effective roller length `l`, m.
    pub length: f64,
    /// Effective modulus `E'`, Pa.
    pub e_eff: f64,
    /// `K_l` in `Q = K_l delta^(10/9)`, N/m^(10/9).
    pub kl: f64,
}

/// `E'` of Harris's steel (206.8 GPa, nu = 0.3), Pa.
pub const E_EFF_STEEL_HARRIS: f64 = 2.0 * 206.8e9 / (1.0 - 0.09);

impl LineContact {
    /// Palmgren's law for a roller of effective length `length` (m) and pair modulus `E'`.
    pub fn palmgren(length: f64, e_eff: f64) -> Self {
        // delta [m] = 3.84e-5 * 1e-3 * Q^0.9 * (1e3 l)^-0.8 at E' = E_EFF_STEEL_HARRIS.
        let c_steel = 3.84e-8 * 1e3_f64.powf(-0.8);
        let c = c_steel * (E_EFF_STEEL_HARRIS / e_eff).powf(0.9);
        // Q = (delta l^0.8 / c)^(1/0.9) = K_l delta^(10/9).
        let kl = (length.powf(0.8) / c).powf(1.0 / 0.9);
        LineContact { length, e_eff, kl }
    }

    /// `(Q, dQ/d delta) = (K_l delta^(10/9), (10/9) K_l delta^(1/9))`, zero for
    /// `delta <= 0` (continuous at zero; the stiffness is `delta^(1/9)`, continuous but
    /// not C¹ in the load).
    pub fn load_and_stiffness(&self, delta: f64) -> (f64, f64) {
        if delta > 0.0 {
            let p = delta.powf(1.0 / 9.0);
            (self.kl * delta * p, 10.0 / 9.0 * self.kl * p)
        } else {
            (0.0, 0.0)
        }
    }

    /// Approach for load `q`, m.
    pub fn deflection(&self, q: f64) -> f64 {
        (q.max(0.0) / self.kl).powf(0.9)
    }
}
