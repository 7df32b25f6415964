//! Reference rating life of a radial roller bearing from its lamina loads, in the
//! Lundberg–Palmgren line-contact form of ISO/TS 16281:2008, with the edge-stress factor, and
//! the static safety of the most loaded lamina (docs/physics.md §R10).
//!
//! - **Raceway ratings** (Lundberg–Palmgren line contact, [Harris 2007] vol. 2 ch. 11;
//!   ISO/TR 1281-1): the roller load of the basic dynamic rating of the inner raceway
//!   `Q_ci = C / (λν J_ri Z cos α i^(7/9)) [1 + (J_ri/J_re X)^(9/2)]^(2/9)` and of the outer
//!   `Q_ce = C / (λν J_re Z cos α i^(7/9)) [1 + (J_ri/J_re X)^(-9/2)]^(2/9)` with
//!   `X = ((1-γ)/(1+γ))^(143/108)` (the ratio `Q_ci/Q_ce` of the Lundberg–Palmgren roller
//!   ratings, the `(1∓γ)^(29/27)/(1±γ)^(1/4)` factors), `J_ri = J_r/J_1 = 0.378` and
//!   `J_re = J_r/J_2 = 0.364` the Sjövall integrals' ratios for line contact at the ISO 281
//!   load distribution (`ε = 0.5`: `J_r` the radial load integral, `J_1` (exponent 4) the
//!   rotating raceway's and `J_2` (exponent 9/2) the stationary raceway's equivalent-load
//!   integral, tested by quadrature). These make the two raceway lives recombine
//!   into ISO 281's `C` at `P = C` within their rounding, 1.6 % (the consistency test below). A lamina of width
//!   `Lwe/ns` rates `q_c,k = Q_c ns^(-7/9)` (the `Lwe^(7/9)` of the roller rating).
//! - **Equivalent lamina loads**, inner ring rotating: `q_ei,k = (Σ_j (f_k q_i,jk)^4 / Z)^(1/4)`
//!   on the rotating inner raceway (each lamina track meets every roller), `q_ee,k = (Σ_j
//!   (f_k q_e,jk)^(9/2) / Z)^(2/9)` on the stationary outer one (a point of it sees the load
//!   zone).
//! - **Life** `L10r = [Σ_k (q_ei,k/q_ci,k)^(9/2) + (q_ee,k/q_ce,k)^(9/2)]^(-8/9)` million
//!   revolutions (raceway lives `∝ q^-4` combined with the Weibull exponent 9/8). With a
//!   roller's load spread evenly over its laminae and `f_k = 1` the sum collapses to the
//!   roller-level Lundberg–Palmgren life for any `ns` (tested).
//! - **`λν`**: ISO 281's line-contact `fc` carries the reduction `λν = 0.83` for edge stress
//!   and uneven load along the roller (ISO/TR 1281-1), which the lamina loads resolve; the
//!   lamina ratings therefore divide `C` by `λν` ([`LaminaLifeOptions::remove_lambda_nu`]).
//!   UNSOURCED: the division is the method as commonly reproduced, not checked against the
//!   standard's text; with it off the method gives ISO 281's `L = 1` at `P = C`.
//! - **Edge-stress factor** `f_k = 1 - 0.01 / ln(1.985 |2k - ns - 1| / (2 ns - 2))`
//!   (`k = 1..ns`; 1 at a centre lamina): it multiplies each lamina load before the
//!   equivalent loads, so a loaded end lamina (2.33 at the very ends) shortens the life, a
//!   relieved one (profiled roller) does not. UNSOURCED: the expression is the one public
//!   reproductions of ISO/TS 16281 give; it was not checked against the standard's text
//!   ([`EDGE_FACTOR_NOTE`]).
//! - **Static safety of a lamina**: the line-contact Hertz peak pressure grows as the square
//!   root of the load per length (`p0 = sqrt(q E' / (2 pi R l))`, [Harris 2007] vol. 1 ch. 6),
//!   so the factor on the most loaded lamina's load that brings its peak to ISO 76's
//!   4 000 MPa is `S0 = (4000 MPa / p_max)²`.

use crate::error::{Error, Result};
use crate::geometry::roller::RollerBearing;
use crate::ratings::roller::{roller_ratings, STATIC_PRESSURE_LIMIT_ROLLER};
use serde::Serialize;

/// `λν` of ISO/TR 1281-1 for radial roller bearings (ISO 281's line-contact reduction).
pub const LAMBDA_NU: f64 = crate::ratings::roller::LAMBDA_NU;
/// `J_r/J_1` at `ε = 0.5`, line contact (rotating raceway).
pub const J_RATIO_INNER: f64 = 0.378;
/// `J_r/J_2` at `ε = 0.5`, line contact (stationary raceway).
pub const J_RATIO_OUTER: f64 = 0.364;
/// What the output says of the two unsourced steps.
pub const EDGE_FACTOR_NOTE: &str = "UNSOURCED: the edge-stress factor f_k = 1 - 0.01/ln(1.985 |2k-ns-1|/(2ns-2)) and the division of C by lambda*nu = 0.83 are ISO/TS 16281 as publicly reproduced, not checked against the standard's text";

/// Which of the method's steps to apply (both on: ISO/TS 16281 as reproduced).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LaminaLifeOptions {
    /// Multiply each lamina load by the edge-stress factor `f_k`.
    pub edge_factor: bool,
    /// Rate the laminae from `C / λν` (module docs).
    pub remove_lambda_nu: bool,
}

impl Default for LaminaLifeOptions {
    fn default() -> Self {
        LaminaLifeOptions {
            edge_factor: true,
            remove_lambda_nu: true,
        }
    }
}

/// The raceway ratings (N): rollers `Q_ci`, `Q_ce` and laminae `q_ci`, `q_ce`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LaminaRatings {
    /// Roller load of the inner raceway's basic dynamic rating, N.
    pub q_ci: f64,
    /// Roller load of the outer raceway's basic dynamic rating, N.
    pub q_ce: f64,
    /// A lamina's inner rating `Q_ci ns^(-7/9)`, N.
    pub qk_ci: f64,
    /// A lamina's outer rating, N.
    pub qk_ce: f64,
}

/// Raceway ratings from the bearing's `C` (N), `Z`, `α`, `γ` and `ns` (module docs).
pub fn lamina_ratings(
    c: f64,
    z: usize,
    alpha: f64,
    gamma: f64,
    ns: usize,
    o: LaminaLifeOptions,
) -> LaminaRatings {
    let ln = if o.remove_lambda_nu { LAMBDA_NU } else { 1.0 };
    let x = J_RATIO_INNER / J_RATIO_OUTER * ((1.0 - gamma) / (1.0 + gamma)).powf(143.0 / 108.0);
    let base = c / (ln * z as f64 * alpha.cos());
    let q_ci = base / J_RATIO_INNER * (1.0 + x.powf(4.5)).powf(2.0 / 9.0);
    let q_ce = base / J_RATIO_OUTER * (1.0 + x.powf(-4.5)).powf(2.0 / 9.0);
    let s = (ns as f64).powf(-7.0 / 9.0);
    LaminaRatings {
        q_ci,
        q_ce,
        qk_ci: q_ci * s,
        qk_ce: q_ce * s,
    }
}

/// The edge-stress factor of lamina `k` (0-based) of `ns` (module docs; UNSOURCED).
pub fn edge_factor(k: usize, ns: usize) -> f64 {
    if ns < 2 {
        return 1.0;
    }
    let x = (2.0 * (k + 1) as f64 - ns as f64 - 1.0).abs() / (2.0 * ns as f64 - 2.0);
    if x == 0.0 {
        1.0
    } else {
        1.0 - 0.01 / (1.985 * x).ln()
    }
}

/// The reference rating life from the lamina loads.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LaminaLife {
    /// `L10r`, million revolutions (`None`: nothing loaded).
    pub l10r_mrev: Option<f64>,
    /// The inner raceway's life alone, million revolutions.
    pub inner_mrev: Option<f64>,
    /// The outer raceway's life alone, million revolutions.
    pub outer_mrev: Option<f64>,
    /// The dynamic equivalent reference load `C / L10r^(3/10)`, N.
    pub p_ref: f64,
    /// The steps applied.
    pub options: LaminaLifeOptions,
    /// The ratings used.
    pub ratings: LaminaRatings,
}

/// What the lamina ratings of roller bearing `b` take from its geometry: `(Cr, alpha,
/// gamma)`, ISO 281's basic dynamic radial load rating (N; `ratings::roller`: the roller's
/// mean diameter `Dwe`, its effective length `Lwe`, `Z`, the nominal contact angle), that
/// angle and `gamma = Dwe cos(alpha)/Dpw`, one pair for both raceways. A cylindrical bearing's
/// angle is 0; a tapered bearing's is the cup's (ISO 281's nominal contact angle of a tapered
/// roller bearing, the one that sets its `e` and `Y`): its cone's lamina loads (normal to the
/// cone, `rho_i` times the cup's at rest) are rated against the inner raceway's rating at the
/// same `gamma`. The cone's own angle in the inner raceway's `gamma` would lower that rating
/// by 0.44 % for the 30206 (docs/physics.md §R10).
pub fn rating_geometry(b: &RollerBearing) -> Result<(f64, f64, f64)> {
    Ok((roller_ratings(b)?.cr, b.alpha, b.gamma()))
}

/// `L10r` of bearing `b` (its ISO 281 `Cr`, [`rating_geometry`]) from the inner- and
/// outer-contact lamina loads of every roller (`inner[j][k]`, `outer[j][k]`, N; a tapered
/// bearing's cone and cup), the inner ring rotating.
pub fn lamina_life(
    b: &RollerBearing,
    inner: &[Vec<f64>],
    outer: &[Vec<f64>],
    o: LaminaLifeOptions,
) -> Result<LaminaLife> {
    let (c, alpha, gamma) = rating_geometry(b)?;
    life_from(c, alpha, gamma, inner, outer, o)
}

/// [`lamina_life`] with the rating `c` (N), `α` and `γ` given.
pub fn life_from(
    c: f64,
    alpha: f64,
    gamma: f64,
    inner: &[Vec<f64>],
    outer: &[Vec<f64>],
    o: LaminaLifeOptions,
) -> Result<LaminaLife> {
    let z = inner.len();
    let ns = inner.first().map_or(0, |v| v.len());
    if z == 0 || ns == 0 || outer.len() != z || inner.iter().chain(outer).any(|v| v.len() != ns) {
        return Err(Error::invalid(
            "lamina loads",
            format!("{z} rollers"),
            "one row per roller on each race, every row one load per lamina",
        ));
    }
    let r = lamina_ratings(c, z, alpha, gamma, ns, o);
    let (mut si, mut se) = (0.0, 0.0);
    for k in 0..ns {
        let f = if o.edge_factor {
            edge_factor(k, ns)
        } else {
            1.0
        };
        let qi = (inner
            .iter()
            .map(|v| (f * v[k].max(0.0)).powi(4))
            .sum::<f64>()
            / z as f64)
            .powf(0.25);
        let qe = (outer
            .iter()
            .map(|v| (f * v[k].max(0.0)).powf(4.5))
            .sum::<f64>()
            / z as f64)
            .powf(2.0 / 9.0);
        si += (qi / r.qk_ci).powf(4.5);
        se += (qe / r.qk_ce).powf(4.5);
    }
    Ok(combine(c, si, se, o, r))
}

/// The life from the laminae's summed raceway terms `si = Σ_k (q_ei,k/q_ci,k)^(9/2)` and
/// `se` (module docs).
fn combine(c: f64, si: f64, se: f64, o: LaminaLifeOptions, r: LaminaRatings) -> LaminaLife {
    let life = |s: f64| (s > 0.0).then(|| s.powf(-8.0 / 9.0));
    let l = life(si + se);
    LaminaLife {
        l10r_mrev: l,
        inner_mrev: life(si),
        outer_mrev: life(se),
        p_ref: l.map_or(0.0, |l| c / l.powf(0.3)),
        options: o,
        ratings: r,
    }
}

/// The lamina loads of a run's states (the ring level's, over a recorded window) gathered
/// for ISO/TS 16281's treatment of a varying load: the raceways' equivalent lamina loads are
/// their power means over every roller and every state, `q_ei,k = (Σ_s Σ_j (f_k
/// q_i,sjk)^4 / (Z n))^(1/4)` on the rotating inner raceway and `q_ee,k = (Σ_s Σ_j (f_k
/// q_e,sjk)^(9/2) / (Z n))^(2/9)` on the stationary outer one (`n` states, equally spaced
/// in time: each state stands for an equal share of the revolutions). A lamina track of the
/// inner raceway meets the rollers at every azimuth the run visits, a point of the outer one
/// the rollers that pass it, so the mean over the window replaces the one state's mean over
/// the `Z` rollers; with one state, or with every state alike, it is [`lamina_life`]'s
/// (to rounding: the edge factor multiplies the sums, `f^4 Σ q^4`, not each load).
/// Gathering allocates nothing after [`LaminaWindow::new`].
#[derive(Debug, Clone, PartialEq)]
pub struct LaminaWindow {
    z: usize,
    states: usize,
    /// `Σ_s Σ_j q_i^4` per lamina.
    inner4: Vec<f64>,
    /// `Σ_s Σ_j q_e^(9/2)` per lamina.
    outer45: Vec<f64>,
}

impl LaminaWindow {
    /// An empty window for `z` rollers of `ns` laminae.
    pub fn new(z: usize, ns: usize) -> LaminaWindow {
        LaminaWindow {
            z,
            states: 0,
            inner4: vec![0.0; ns],
            outer45: vec![0.0; ns],
        }
    }

    /// Laminae per roller.
    pub fn laminae(&self) -> usize {
        self.inner4.len()
    }

    /// Rollers.
    pub fn rollers(&self) -> usize {
        self.z
    }

    /// States gathered.
    pub fn states(&self) -> usize {
        self.states
    }

    /// Adds one roller's inner and outer lamina loads (N, one per lamina) of the current
    /// state; call [`LaminaWindow::end_state`] after the `Z` rollers of a state.
    pub fn add_roller(&mut self, inner: &[f64], outer: &[f64]) {
        debug_assert_eq!(inner.len(), self.laminae());
        debug_assert_eq!(outer.len(), self.laminae());
        for ((s, &q), (t, &p)) in self
            .inner4
            .iter_mut()
            .zip(inner)
            .zip(self.outer45.iter_mut().zip(outer))
        {
            let q = q.max(0.0);
            *s += (q * q) * (q * q);
            *t += p.max(0.0).powf(4.5);
        }
    }

    /// Closes the state whose `Z` rollers were added.
    pub fn end_state(&mut self) {
        self.states += 1;
    }

    /// `L10r` of bearing `b` over the states gathered (struct docs); refused when nothing was
    /// gathered or the window's shape is not the bearing's.
    pub fn life(&self, b: &RollerBearing, o: LaminaLifeOptions) -> Result<LaminaLife> {
        let ns = self.laminae();
        if self.states == 0 || ns == 0 || self.z != b.z {
            return Err(Error::invalid(
                "lamina loads",
                format!("{} states of {} rollers", self.states, self.z),
                format!("at least one state of the bearing's {} rollers", b.z),
            ));
        }
        let (c, alpha, gamma) = rating_geometry(b)?;
        let r = lamina_ratings(c, self.z, alpha, gamma, ns, o);
        let n = (self.z * self.states) as f64;
        let (mut si, mut se) = (0.0, 0.0);
        for k in 0..ns {
            let f = if o.edge_factor {
                edge_factor(k, ns)
            } else {
                1.0
            };
            let qi = f * (self.inner4[k] / n).powf(0.25);
            let qe = f * (self.outer45[k] / n).powf(2.0 / 9.0);
            si += (qi / r.qk_ci).powf(4.5);
            se += (qe / r.qk_ce).powf(4.5);
        }
        Ok(combine(c, si, se, o, r))
    }
}

/// Static safety of the most loaded lamina against ISO 76's 4 000 MPa for its peak line-Hertz
/// pressure `p_max` (Pa): `(4000 MPa / p_max)²`; `None` when nothing is loaded.
pub fn lamina_static_safety(p_max: f64) -> Option<f64> {
    (p_max > 0.0).then(|| (STATIC_PRESSURE_LIMIT_ROLLER / p_max).powi(2))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Simpson's rule of `f` on `[a, b]` with `n` (even) panels.
    fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
        let h = (b - a) / n as f64;
        let mut s = f(a) + f(b);
        for i in 1..n {
            s += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        s * h / 3.0
    }

    /// The constants 0.378 and 0.364 are the ratios of Sjövall's integrals for line contact
    /// at `ε = 0.5` (`Q(ψ) = Q_max cos(ψ)^(10/9)` over `|ψ| < π/2`) within 0.5 % (the
    /// integrals give 0.3764 and 0.3630; with Harris's load exponent 1.1, `J_r` = 0.2453 of
    /// his table and 0.3767, 0.3634):
    /// `J_r = (1/2π) ∫ cos^(10/9) ψ cos ψ`, `J_1 = ((1/2π) ∫ cos^(40/9) ψ)^(1/4)`,
    /// `J_2 = ((1/2π) ∫ cos^5 ψ)^(2/9)`.
    #[test]
    fn j_ratios_are_sjovalls_integrals() {
        use std::f64::consts::PI;
        let h = 0.5 * PI;
        let int = |p: f64| simpson(|s: f64| s.cos().max(0.0).powf(p), -h, h, 20_000) / (2.0 * PI);
        let jr = int(10.0 / 9.0 + 1.0);
        let j1 = int(40.0 / 9.0).powf(0.25);
        let j2 = int(5.0).powf(2.0 / 9.0);
        assert!((jr - 0.24480).abs() < 1e-5, "J_r {jr}");
        assert!((jr / j1 / J_RATIO_INNER - 1.0).abs() < 5e-3, "{}", jr / j1);
        assert!((jr / j2 / J_RATIO_OUTER - 1.0).abs() < 5e-3, "{}", jr / j2);
    }

    /// Lamina loads of `z` rollers (roller `j` at `2π j/z`) under `fr` with the ISO 281 load
    /// distribution (`ε = 0.5`, Stribeck's `Q_max = fr/(Z J_r)`), each spread evenly over `ns`
    /// laminae.
    fn iso_distribution(fr: f64, z: usize, ns: usize) -> Vec<Vec<f64>> {
        use std::f64::consts::PI;
        let psi: Vec<f64> = (0..z).map(|j| 2.0 * PI * j as f64 / z as f64).collect();
        let shape: Vec<f64> = psi
            .iter()
            .map(|p| p.cos().max(0.0).powf(10.0 / 9.0))
            .collect();
        let sum: f64 = psi.iter().zip(&shape).map(|(p, s)| s * p.cos()).sum();
        let qmax = fr / sum;
        shape
            .iter()
            .map(|s| vec![qmax * s / ns as f64; ns])
            .collect()
    }

    /// The consistency limit: aligned straight rollers loaded evenly along their length in
    /// ISO 281's load distribution give ISO 281's life `L = 1` at `P = C` (without the two
    /// unsourced steps), for any lamina count, within 2 % (1.6 %: the standard's rounded
    /// `J` ratios, 0.378 against the integrals' 0.3764, to the fourth power); the life scales as `P^-4` (line contact); and
    /// each unsourced step shortens it by its own factor, `λν^4` and
    /// `(Σ f_k^(9/2)/ns)^(-8/9)`.
    #[test]
    fn uniform_aligned_rollers_give_iso_281_at_p_equal_c() {
        let (c, alpha, gamma) = (50_000.0, 0.0, 0.2);
        let plain = LaminaLifeOptions {
            edge_factor: false,
            remove_lambda_nu: false,
        };
        let mut last = 0.0;
        for ns in [1, 10, 30] {
            let q = iso_distribution(c, 3600, ns);
            let l = life_from(c, alpha, gamma, &q, &q, plain).unwrap();
            let l = l.l10r_mrev.unwrap();
            assert!((l - 1.0).abs() < 0.02, "ns {ns}: L {l}");
            if ns > 1 {
                assert!(
                    (l / last - 1.0).abs() < 1e-12,
                    "slicing is exact: {l} vs {last}"
                );
            }
            last = l;
        }
        let q = iso_distribution(0.5 * c, 3600, 30);
        let l = life_from(c, alpha, gamma, &q, &q, plain)
            .unwrap()
            .l10r_mrev
            .unwrap();
        assert!((l / (16.0 * last) - 1.0).abs() < 1e-9, "P^-4: {l}");
        let no_edge = LaminaLifeOptions {
            edge_factor: false,
            remove_lambda_nu: true,
        };
        let l2 = life_from(c, alpha, gamma, &q, &q, no_edge)
            .unwrap()
            .l10r_mrev
            .unwrap();
        assert!((l2 / l - LAMBDA_NU.powi(-4)).abs() < 1e-9, "{}", l2 / l);
        let l3 = life_from(c, alpha, gamma, &q, &q, LaminaLifeOptions::default())
            .unwrap()
            .l10r_mrev
            .unwrap();
        let fsum: f64 = (0..30).map(|k| edge_factor(k, 30).powf(4.5)).sum::<f64>() / 30.0;
        assert!((l3 / l2 - fsum.powf(-8.0 / 9.0)).abs() < 1e-9);
        assert!(l3 < l2);
    }

    /// A tapered bearing (30206, the cup angle 14.04°) rated the same way: ISO 281's load
    /// distribution of the normal roller loads whose radial parts `Q cos(alpha)` carry `Fr =
    /// Cr`, equal on cone and cup, gives ISO 281's `L = 1` within the same 2 % (the rating
    /// geometry's `cos(alpha)` and `gamma` are the ones of `Cr`); the 30206's ratings are its
    /// own `Cr` with `alpha` the cup angle and `gamma = Dwe cos(alpha)/Dpw`.
    #[test]
    fn a_tapered_bearing_at_p_equal_c_gives_iso_281() {
        let b = crate::geometry::roller_catalogue::lookup("30206")
            .unwrap()
            .build()
            .unwrap();
        let (c, alpha, gamma) = rating_geometry(&b).unwrap();
        assert_eq!(c, roller_ratings(&b).unwrap().cr);
        assert!(
            (alpha.to_degrees() - 14.036).abs() < 1e-3,
            "{}",
            alpha.to_degrees()
        );
        assert!((gamma - b.dwe * alpha.cos() / b.dpw).abs() < 1e-15);
        let plain = LaminaLifeOptions {
            edge_factor: false,
            remove_lambda_nu: false,
        };
        let q = iso_distribution(c / alpha.cos(), 3600, 30);
        let l = life_from(c, alpha, gamma, &q, &q, plain).unwrap();
        let l = l.l10r_mrev.unwrap();
        assert!((l - 1.0).abs() < 0.02, "L {l}");
    }

    /// The edge factor: 1 at a centre lamina, symmetric, growing toward the ends, 2.33 at the
    /// very ends for any count.
    #[test]
    fn edge_factor_shape() {
        assert_eq!(edge_factor(15, 31), 1.0);
        for ns in [10, 30, 31] {
            for k in 0..ns {
                assert_eq!(edge_factor(k, ns), edge_factor(ns - 1 - k, ns));
                if 2 * k + 2 < ns {
                    assert!(edge_factor(k, ns) > edge_factor(k + 1, ns));
                }
            }
            assert!(
                (edge_factor(0, ns) - 2.328).abs() < 1e-3,
                "{}",
                edge_factor(0, ns)
            );
        }
        assert_eq!(edge_factor(0, 1), 1.0);
    }

    /// `S0 = (4000 MPa/p)^2`: 1 at 4000 MPa, 4 at 2000 MPa; none unloaded.
    #[test]
    fn static_safety_is_the_load_factor_to_4000_mpa() {
        assert_eq!(lamina_static_safety(4000e6), Some(1.0));
        assert_eq!(lamina_static_safety(2000e6), Some(4.0));
        assert_eq!(lamina_static_safety(0.0), None);
    }

    #[test]
    fn ragged_loads_are_refused() {
        let e = life_from(
            1e4,
            0.0,
            0.2,
            &[vec![1.0; 3]],
            &[vec![1.0; 2]],
            Default::default(),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("lamina loads"), "{e}");
    }
}
