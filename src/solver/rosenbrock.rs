//! RODAS4: the L-stable, stiffly accurate Rosenbrock method of order 4 with an embedded
//! method of order 3 (Hairer & Wanner, *Solving ODEs II*, 2nd ed., §IV.7 for Rosenbrock
//! methods and their implementation, §VI.4 for RODAS; the coefficients are those of
//! Hairer's code RODAS, `METH = 1`, in the transformed variables `u_i = Σ_j γ_ij k_j` of
//! §IV.7, Eq. 7.16–7.19, so that no matrix-vector product with `J` is needed).
//!
//! One step from `(t, y)` with step `h`, `W = I/(hγ) − J`, `γ = 1/4`:
//!
//! ```text
//! W u_i = f(t + c_i h, y + Σ_{j<i} a_ij u_j) + Σ_{j<i} (c_ij/h) u_j + h d_i ∂f/∂t,  i = 1..6
//! y_new = y + Σ_{j<=5} a_5j u_j + u_5 + u_6         (a_6j = a_5j + δ_j5: stiffly accurate)
//! error = u_6                                       (embedded 3rd-order: y_new − u_6)
//! ```
//!
//! The same integrator also runs ROS34PW2 ([`RosMethod::Ros34pw2`]; Rang & Angermann,
//! *BIT* 45 (2005) 761–787), a 4-stage, stiffly accurate, L-stable **W-method** of order 3
//! with an embedded method of order 2: its order holds for any matrix in place of `J`
//! (Hairer & Wanner II, §IV.7, "W-methods"), so `J` and the LU of `I/(hγ) − J` are kept
//! across the steps of one call (refreshed after a rejection and every
//! [`W_JAC_MAX_AGE`] accepted steps; the LU whenever `h` changes) and, when the system
//! allows it ([`OdeSystem::carries_jacobian`]), across calls that continue one another;
//! `∂f/∂t` is taken from the system when it gives it and left out otherwise (the autonomous form's
//! Jacobian approximated without its time column: still a W-method). The published
//! coefficients `α, Γ, b, b̂` are the data; the transformed ones (`A = αΓ⁻¹`,
//! `C = diag(Γ)⁻¹ − Γ⁻¹`, `m = bΓ⁻¹`) are computed from them.

use super::{
    check_call, error_norm, eval, fixed_steps, initial_step, DenseLu, LinearSolver, OdeSystem,
    Options, SolverError, Stats, StepLoop, UROUND,
};
use crate::solver::same_bits;
use nalgebra::DMatrix;

const GAMMA: f64 = 0.25;
const C2: f64 = 0.386;
const C3: f64 = 0.21;
const C4: f64 = 0.63;
const D1: f64 = 0.25;
const D2: f64 = -0.1043;
const D3: f64 = 0.1035;
const D4: f64 = -0.362_000_000_000_002_3e-1;
const A21: f64 = 1.544;
const A31: f64 = 0.946_678_528_081_582_6;
const A32: f64 = 0.255_701_169_898_328_4;
const A41: f64 = 3.314_825_187_068_521;
const A42: f64 = 2.896_124_015_972_201;
const A43: f64 = 0.998_641_913_997_781_7;
const A51: f64 = 1.221_224_509_226_641;
const A52: f64 = 6.019_134_481_288_629;
const A53: f64 = 12.537_083_329_320_87;
const A54: f64 = -0.687_886_036_105_895;
const C21: f64 = -5.6688;
const C31: f64 = -2.430_093_356_833_875;
const C32: f64 = -0.206_359_915_709_191_5;
const C41: f64 = -0.107_352_905_815_137_5;
const C42: f64 = -9.594_562_251_023_355;
const C43: f64 = -20.470_286_148_096_16;
const C51: f64 = 7.496_443_313_967_647;
const C52: f64 = -10.246_804_314_643_52;
const C53: f64 = -33.999_903_528_199_05;
const C54: f64 = 11.708_908_932_061_6;
const C61: f64 = 8.083_246_795_921_522;
const C62: f64 = -7.981_132_988_064_893;
const C63: f64 = -31.521_594_328_743_71;
const C64: f64 = 16.319_305_431_231_36;
const C65: f64 = -6.058_818_238_834_054;
// dense output (3rd order), same source
const H21: f64 = 10.126_235_083_445_86;
const H22: f64 = -7.487_995_877_610_167;
const H23: f64 = -34.800_918_615_557_47;
const H24: f64 = -7.992_771_707_568_823;
const H25: f64 = 1.025_137_723_295_662;
const H31: f64 = -0.676_280_339_280_125_3;
const H32: f64 = 6.087_714_651_680_015;
const H33: f64 = 16.430_843_208_924_78;
const H34: f64 = 24.767_225_114_183_86;
const H35: f64 = -6.594_389_125_716_872;

// Controller constants of RODAS: safety, step-ratio bounds 1/5 <= h_new/h <= 6.
const SAFE: f64 = 0.9;
const FAC1: f64 = 5.0;
const FAC2: f64 = 1.0 / 6.0;
/// Consecutive singular matrices (each halving the step) tolerated before failing.
const MAX_SINGULAR: u32 = 5;

/// The Rosenbrock method an integrator runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RosMethod {
    /// RODAS4, order 4(3), exact Jacobian and `∂f/∂t` at every step (the default).
    #[default]
    Rodas4,
    /// ROS34PW2, W-method of order 3(2): `J` and its LU kept across steps.
    Ros34pw2,
}

impl RosMethod {
    /// Order of the propagated solution (for the initial step size).
    fn order(self) -> i32 {
        match self {
            RosMethod::Rodas4 => 4,
            RosMethod::Ros34pw2 => 3,
        }
    }
    /// Step-size exponent `1/(q+1)`, `q` the embedded method's order.
    #[cfg(test)]
    fn error_exponent(self) -> f64 {
        match self {
            RosMethod::Rodas4 => 0.25,
            RosMethod::Ros34pw2 => 1.0 / 3.0,
        }
    }

    /// `x` to the [`RosMethod::error_exponent`]: `√√x` (RODAS4) or `∛x` (ROS34PW2), each
    /// correctly rounded or within an ulp of `powf`'s, at a fraction of its cost.
    #[inline]
    fn error_root(self, x: f64) -> f64 {
        match self {
            RosMethod::Rodas4 => x.sqrt().sqrt(),
            RosMethod::Ros34pw2 => x.cbrt(),
        }
    }
}

/// Stages of ROS34PW2.
const W_STAGES: usize = 4;
/// W-method: most accepted steps on one Jacobian (a rejection refreshes it sooner).
pub const W_JAC_MAX_AGE: u32 = 10;
/// W-method: a proposed step growth up to this factor keeps the step and its LU.
const W_HOLD: f64 = 1.2;

/// ROS34PW2 as published (Rang & Angermann 2005, the W-method "ROS34PW2" of their
/// Table 3.2): `γ`, the strictly lower `α`, the full lower `Γ` (diagonal `γ`), weights `b`
/// and embedded weights `b̂`. Stiffly accurate: `b_j = α_4j + Γ_4j`. (The digits as
/// published, some beyond `f64`.)
#[allow(clippy::excessive_precision)]
pub const ROS34PW2_GAMMA: f64 = 4.358_665_215_084_590e-1;
/// `α_ij`, `j < i`.
#[allow(clippy::excessive_precision)]
pub const ROS34PW2_ALPHA: [[f64; 4]; 4] = [
    [0.0; 4],
    [8.717_330_430_169_180_1e-1, 0.0, 0.0, 0.0],
    [
        8.445_706_001_536_942_3e-1,
        -1.129_906_423_648_418_5e-1,
        0.0,
        0.0,
    ],
    [0.0, 0.0, 1.0, 0.0],
];
/// `Γ_ij`, `j <= i`.
#[allow(clippy::excessive_precision)]
pub const ROS34PW2_GAMMA_MATRIX: [[f64; 4]; 4] = [
    [ROS34PW2_GAMMA, 0.0, 0.0, 0.0],
    [-8.717_330_430_169_180_1e-1, ROS34PW2_GAMMA, 0.0, 0.0],
    [
        -9.033_805_701_304_408_2e-1,
        5.418_067_238_809_532_6e-2,
        ROS34PW2_GAMMA,
        0.0,
    ],
    [
        2.421_238_070_609_534_6e-1,
        -1.223_250_583_904_514_7,
        5.452_602_553_351_021_4e-1,
        ROS34PW2_GAMMA,
    ],
];
/// Weights `b` (order 3).
#[allow(clippy::excessive_precision)]
pub const ROS34PW2_B: [f64; 4] = [
    2.421_238_070_609_534_6e-1,
    -1.223_250_583_904_514_7,
    1.545_260_255_335_102_0,
    ROS34PW2_GAMMA,
];
/// Embedded weights `b̂` (order 2).
#[allow(clippy::excessive_precision)]
pub const ROS34PW2_BHAT: [f64; 4] = [
    3.781_090_314_581_936_9e-1,
    -9.604_229_221_242_317_8e-2,
    0.5,
    2.179_332_607_542_295e-1,
];

/// A 4-stage W-method in the transformed variables `u_i = Σ_j Γ_ij k_j` (Hairer &
/// Wanner II, §IV.7, Eq. 7.16–7.19, as for RODAS4 above).
#[derive(Debug, Clone, PartialEq)]
pub struct WCoeffs {
    /// `γ`.
    pub gamma: f64,
    /// `A = α Γ⁻¹` (strictly lower).
    pub a: [[f64; 4]; 4],
    /// `C = diag(1/γ) − Γ⁻¹` (strictly lower).
    pub cc: [[f64; 4]; 4],
    /// Stage times `c_i = Σ_j α_ij`.
    pub c: [f64; 4],
    /// `d_i = Σ_j Γ_ij` (the `∂f/∂t` weights).
    pub d: [f64; 4],
    /// `m = b Γ⁻¹`.
    pub m: [f64; 4],
    /// Error weights `m − m̂`, `m̂ = b̂ Γ⁻¹`.
    pub e: [f64; 4],
}

impl WCoeffs {
    /// Transformed coefficients of a method given as published (`α`, `Γ`, `b`, `b̂`).
    #[allow(clippy::needless_range_loop)] // the index formulas of the definitions
    pub fn from_published(
        alpha: &[[f64; 4]; 4],
        gam: &[[f64; 4]; 4],
        b: &[f64; 4],
        bhat: &[f64; 4],
    ) -> Self {
        // Γ⁻¹ by forward substitution (lower triangular).
        let mut gi = [[0.0; 4]; 4];
        for col in 0..4 {
            for i in 0..4 {
                let mut v = if i == col { 1.0 } else { 0.0 };
                for k in 0..i {
                    v -= gam[i][k] * gi[k][col];
                }
                gi[i][col] = v / gam[i][i];
            }
        }
        let mut r = WCoeffs {
            gamma: gam[0][0],
            a: [[0.0; 4]; 4],
            cc: [[0.0; 4]; 4],
            c: [0.0; 4],
            d: [0.0; 4],
            m: [0.0; 4],
            e: [0.0; 4],
        };
        for i in 0..4 {
            for j in 0..i {
                r.a[i][j] = (0..4).map(|k| alpha[i][k] * gi[k][j]).sum();
                r.cc[i][j] = -gi[i][j];
            }
            r.c[i] = alpha[i].iter().sum();
            r.d[i] = gam[i].iter().sum();
            let m: f64 = (0..4).map(|k| b[k] * gi[k][i]).sum();
            let mh: f64 = (0..4).map(|k| bhat[k] * gi[k][i]).sum();
            r.m[i] = m;
            r.e[i] = m - mh;
        }
        r
    }

    /// ROS34PW2.
    pub fn ros34pw2() -> Self {
        Self::from_published(
            &ROS34PW2_ALPHA,
            &ROS34PW2_GAMMA_MATRIX,
            &ROS34PW2_B,
            &ROS34PW2_BHAT,
        )
    }
}

/// RODAS4 integrator (linearly implicit, L-stable, order 4(3)) with one LU per step attempt;
/// or, built [`Rosenbrock::with_method`] `Ros34pw2`, the W-method ROS34PW2 (module docs).
///
/// - Jacobian `∂f/∂y` from [`OdeSystem::jacobian`] or by forward differences with
///   increments `sqrt(ε)·max(|y_j|, 1000·atol_j)`; `∂f/∂t` from
///   [`OdeSystem::time_derivative`] or by a forward difference. Both are computed once per
///   accepted step and reused after a rejection (only the LU is redone).
/// - RODAS4 needs the exact Jacobian for its order (it is not a W-method); a
///   finite-difference Jacobian is accurate to about `sqrt(ε)`, which is enough.
/// - Step control as in RODAS: `h_new = h / clamp(err^(1/4)/0.9, 1/6, 5)`, with Gustafsson's
///   predictive controller after the second accepted step of a call (Hairer & Wanner II,
///   §IV.8, Eq. 8.21).
/// - Dense output [`Rosenbrock::dense`]: RODAS's 3rd-order continuous extension.
///
/// ROS34PW2 differs in: `J` (from the system or by the same differences) at the first
/// step of a call (unless the call carries the last one's, [`OdeSystem::carries_jacobian`]),
/// after a rejected step and every [`W_JAC_MAX_AGE`] accepted steps; the
/// LU only when `h` changes; `∂f/∂t` only from the system; step control with `err^(1/3)`
/// (embedded order 2); no dense output.
pub struct Rosenbrock {
    n: usize,
    method: RosMethod,
    /// ROS34PW2's coefficients in the transformed variables (unused by RODAS4).
    w: Box<WCoeffs>,
    /// The step size the LU in `solver` holds for the current `J` (W-method reuse; NaN:
    /// none).
    lu_h: f64,
    /// W-method: whether `dfdt` holds the system's `∂f/∂t` (else the term is left out).
    dfdt_on: bool,
    /// W-method: what lets a call start with the last call's `J`
    /// ([`OdeSystem::carries_jacobian`]).
    carry: Box<Carry>,
    y: Vec<f64>,
    ynew: Vec<f64>,
    f0: Vec<f64>,
    dfdt: Vec<f64>,
    ytmp: Vec<f64>,
    ftmp: Vec<f64>,
    u: [Vec<f64>; 6],
    jac: DMatrix<f64>,
    solver: Box<dyn LinearSolver>,
    // dense output of the last accepted step
    y_old: Vec<f64>,
    kd1: Vec<f64>,
    kd2: Vec<f64>,
    t_old: f64,
    h_old: f64,
    dense_valid: bool,
    /// Work counters, accumulated over calls.
    pub stats: Stats,
}

impl std::fmt::Debug for Rosenbrock {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Rosenbrock")
            .field("n", &self.n)
            .field("stats", &self.stats)
            .finish_non_exhaustive()
    }
}

impl Rosenbrock {
    /// RODAS4 for `n` states with the dense LU solver.
    pub fn new(n: usize) -> Self {
        Self::with_solver(Box::new(DenseLu::new(n)))
    }

    /// RODAS4 with a given linear solver (its `dim()` sets `n`), e.g. [`super::BlockArrowhead`].
    pub fn with_solver(solver: Box<dyn LinearSolver>) -> Self {
        let n = solver.dim();
        let v = || vec![0.0; n];
        Rosenbrock {
            n,
            method: RosMethod::Rodas4,
            w: Box::new(WCoeffs::ros34pw2()),
            lu_h: f64::NAN,
            dfdt_on: false,
            carry: Box::new(Carry::new(0)),
            y: v(),
            ynew: v(),
            f0: v(),
            dfdt: v(),
            ytmp: v(),
            ftmp: v(),
            u: [v(), v(), v(), v(), v(), v()],
            jac: DMatrix::zeros(n, n),
            solver,
            y_old: v(),
            kd1: v(),
            kd2: v(),
            t_old: 0.0,
            h_old: 0.0,
            dense_valid: false,
            stats: Stats::default(),
        }
    }

    /// Method `method` with a given linear solver (its `dim()` sets `n`).
    pub fn with_method(method: RosMethod, solver: Box<dyn LinearSolver>) -> Self {
        let mut r = Self::with_solver(solver);
        r.method = method;
        if method != RosMethod::Rodas4 {
            r.carry = Box::new(Carry::new(r.n));
        }
        r
    }

    /// The method this integrator runs.
    pub fn method(&self) -> RosMethod {
        self.method
    }

    /// The state dimension.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// The interval `[t_old, t_new]` of the last accepted step, if any.
    pub fn last_step(&self) -> Option<(f64, f64)> {
        self.dense_valid
            .then_some((self.t_old, self.t_old + self.h_old))
    }

    /// 3rd-order dense output at `t` in the last accepted step:
    /// `y(t_old + θh) = (1−θ) y_old + θ (y_new + (1−θ)(kd1 + θ kd2))`.
    /// ROS34PW2 has no published continuous extension: refused.
    pub fn dense(&self, t: f64, out: &mut [f64]) -> Result<(), SolverError> {
        if self.method != RosMethod::Rodas4 {
            return Err(SolverError::invalid(
                "t",
                t,
                "no dense output for ROS34PW2 (a RODAS4 or DOPRI5 integrator gives one)",
            ));
        }
        super::check_dense(self.last_step(), t, out.len(), self.n)?;
        let th = (t - self.t_old) / self.h_old;
        let th1 = 1.0 - th;
        let n = out.len();
        let (y_old, y) = (&self.y_old[..n], &self.y[..n]);
        let (kd1, kd2) = (&self.kd1[..n], &self.kd2[..n]);
        for i in 0..n {
            out[i] = th1 * y_old[i] + th * (y[i] + th1 * (kd1[i] + th * kd2[i]));
        }
        Ok(())
    }

    /// Integrate from `t0` to exactly `t1`; see the [module docs](super) for the contract.
    pub fn integrate<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t0: f64,
        t1: f64,
        y: &mut [f64],
        h_trial: &mut f64,
        opts: &Options,
    ) -> Result<(), SolverError> {
        check_call(self.n, sys.dim(), t0, t1, y, opts)?;
        if t1 == t0 {
            return Ok(());
        }
        self.y.copy_from_slice(y);
        let h_next = if opts.fixed_step {
            self.run_fixed(sys, t0, t1, opts)?
        } else {
            let warm = h_trial.is_finite() && *h_trial > 0.0;
            let h0 = if warm {
                h_trial.min(opts.h_max)
            } else {
                self.f_at_start(sys, t0)?;
                initial_step(
                    sys,
                    &mut self.stats,
                    t0,
                    &self.y,
                    &self.f0,
                    &mut self.ytmp,
                    &mut self.ftmp,
                    self.method.order(),
                    opts,
                )?
            };
            // a cold start evaluated f(t0, y0) for the initial step already
            self.run_adaptive(sys, t0, t1, h0, opts, !warm)?
        };
        y.copy_from_slice(&self.y);
        *h_trial = h_next;
        Ok(())
    }

    /// `f0 = f(t, y)` at an accepted point; a non-finite value there is fatal.
    fn f_at_start<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
    ) -> Result<(), SolverError> {
        if let Some(i) = eval(sys, &mut self.stats, t, &self.y, &mut self.f0)? {
            return Err(SolverError::NonFinite {
                t,
                what: "right-hand side",
                index: i,
            });
        }
        Ok(())
    }

    /// `f0` (unless `have_f0`), `J` and `∂f/∂t` at the accepted point `(t, y)`.
    fn linearise<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        opts: &Options,
        have_f0: bool,
    ) -> Result<(), SolverError> {
        if !have_f0 {
            self.f_at_start(sys, t)?;
        }
        self.jacobian_at(sys, t, opts)?;
        self.time_derivative_at(sys, t, true)
    }

    /// `J` at the accepted point `(t, y)` (`f0` must hold `f(t, y)`).
    fn jacobian_at<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        opts: &Options,
    ) -> Result<(), SolverError> {
        let n = self.n;
        self.stats.jac_evals += 1;
        if !sys.jacobian(t, &self.y, &mut self.jac) {
            self.ytmp.copy_from_slice(&self.y);
            for j in 0..n {
                let yj = self.y[j];
                let delta = UROUND.sqrt() * yj.abs().max(1e3 * opts.atol[j]);
                self.ytmp[j] = yj + delta;
                let delta = self.ytmp[j] - yj; // exactly representable increment
                if let Some(i) = eval(sys, &mut self.stats, t, &self.ytmp, &mut self.ftmp)? {
                    return Err(SolverError::NonFinite {
                        t,
                        what: "right-hand side",
                        index: i,
                    });
                }
                for i in 0..n {
                    self.jac[(i, j)] = (self.ftmp[i] - self.f0[i]) / delta;
                }
                self.ytmp[j] = yj;
            }
        }
        // A branch-free pass first (it vectorises); the index only when something is off.
        if !all_finite(self.jac.as_slice()) {
            let k = self.jac.iter().position(|v| !v.is_finite()).unwrap_or(0);
            return Err(SolverError::NonFinite {
                t,
                what: "jacobian",
                index: k % n,
            });
        }
        Ok(())
    }

    /// `∂f/∂t` at the accepted point `(t, y)` from the system, else by a forward
    /// difference (`fd`, RODAS4) or not at all (`!fd`, the W-method: `dfdt_on` false).
    fn time_derivative_at<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        fd: bool,
    ) -> Result<(), SolverError> {
        let n = self.n;
        self.dfdt_on = true;
        if sys.time_derivative(t, &self.y, &mut self.dfdt) {
            // An exactly zero `∂f/∂t` (an autonomous system) leaves the W-method's stages as
            // without one (no `+ 0.0` terms).
            if !fd && self.dfdt.iter().all(|&v| v == 0.0) {
                self.dfdt_on = false;
            }
        } else {
            if !fd {
                self.dfdt_on = false;
                return Ok(());
            }
            let delta = UROUND.sqrt() * t.abs().max(1e-5);
            let td = t + delta;
            let delta = td - t;
            if let Some(i) = eval(sys, &mut self.stats, td, &self.y, &mut self.ftmp)? {
                return Err(SolverError::NonFinite {
                    t: td,
                    what: "right-hand side",
                    index: i,
                });
            }
            for i in 0..n {
                self.dfdt[i] = (self.ftmp[i] - self.f0[i]) / delta;
            }
        }
        if let Some(i) = self.dfdt.iter().position(|v| !v.is_finite()) {
            return Err(SolverError::NonFinite {
                t,
                what: "time derivative of the right-hand side",
                index: i,
            });
        }
        Ok(())
    }

    /// At an accepted point `(t, y)`: RODAS4 linearises afresh (`f0`, `J`, `∂f/∂t`); the
    /// W-method evaluates `f0` (unless `have_f0`) and the system's `∂f/∂t` if it gives
    /// one, and `J` only when `need_jac` (which also drops the LU).
    fn prepare<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        opts: &Options,
        have_f0: bool,
        need_jac: bool,
    ) -> Result<(), SolverError> {
        match self.method {
            RosMethod::Rodas4 => self.linearise(sys, t, opts, have_f0),
            RosMethod::Ros34pw2 => {
                if !have_f0 {
                    self.f_at_start(sys, t)?;
                }
                if need_jac {
                    // The J a carried call started with, kept until the call is known
                    // good (`carry_back`).
                    let c = &mut *self.carry;
                    if c.start_ok && !c.prev_saved {
                        c.jac_prev.copy_from(&self.jac);
                        c.prev_saved = true;
                    }
                    self.jacobian_at(sys, t, opts)?;
                    self.lu_h = f64::NAN;
                }
                self.time_derivative_at(sys, t, false)
            }
        }
    }

    fn run_fixed<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t0: f64,
        t1: f64,
        opts: &Options,
    ) -> Result<f64, SolverError> {
        let (steps, h) = fixed_steps(t0, t1, opts.h_max);
        let mut jac_age = W_JAC_MAX_AGE;
        for i in 0..steps {
            let t = t0 + i as f64 * h;
            let need_jac = jac_age >= W_JAC_MAX_AGE;
            self.prepare(sys, t, opts, false, need_jac)?;
            if need_jac {
                jac_age = 0;
            }
            match self.attempt(sys, t, h)? {
                Attempt::Done => {}
                Attempt::Singular => return Err(SolverError::Singular { t, h }),
                Attempt::NonFinite(tb, idx) => {
                    return Err(SolverError::NonFinite {
                        t: tb,
                        what: "right-hand side",
                        index: idx,
                    })
                }
            }
            let t_new = if i + 1 == steps { t1 } else { t + h };
            self.accept(t, t_new);
            if sys.observes_steps() {
                sys.step_accepted(t, t_new, &|tt, out| self.dense(tt, out));
            }
            jac_age += 1;
        }
        Ok(h)
    }

    fn run_adaptive<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t0: f64,
        t1: f64,
        h0: f64,
        opts: &Options,
        have_f0: bool,
    ) -> Result<f64, SolverError> {
        // W-method: J wanted at the next preparation; accepted steps since the last J.
        let w_method = self.method != RosMethod::Rodas4;
        let mut need_jac = true;
        let mut jac_age: u32 = 0;
        let carries = w_method && sys.carries_jacobian();
        if carries {
            if let Some(age) = self.carry_in() {
                (need_jac, jac_age) = (age >= W_JAC_MAX_AGE, age);
            }
        } else if w_method {
            self.carry.forget();
        }
        let r = self.adaptive_loop(sys, t0, t1, h0, opts, have_f0, need_jac, jac_age);
        if carries {
            match r {
                Ok((_, age)) => self.carry_out(age),
                Err(_) => self.carry_back(),
            }
        }
        r.map(|(h, _)| h)
    }

    /// W-method, at the start of a call that may carry `J` (`self.y` its start): the age
    /// of the `J` it starts with, or `None` for a fresh one. A call from where the last
    /// one ended continues with that `J`; a call from where the last one began (its result
    /// was not kept: a failed or refused step) starts with the `J` that one started with.
    fn carry_in(&mut self) -> Option<u32> {
        let c = &mut *self.carry;
        if c.end_ok && same_bits(&c.end_y, &self.y) {
            c.start_y.copy_from_slice(&self.y);
            (c.start_ok, c.start_age, c.prev_saved) = (true, c.end_age, false);
            return Some(c.end_age);
        }
        c.end_ok = false;
        if c.start_ok && same_bits(&c.start_y, &self.y) {
            if c.prev_saved {
                self.jac.copy_from(&c.jac_prev);
                c.prev_saved = false;
                self.lu_h = f64::NAN;
            }
            return Some(c.start_age);
        }
        c.start_ok = false;
        None
    }

    /// W-method, after a call that may carry `J` ended: where, and how old its `J` is.
    fn carry_out(&mut self, age: u32) {
        let c = &mut *self.carry;
        c.end_y.copy_from_slice(&self.y);
        (c.end_ok, c.end_age) = (true, age);
    }

    /// W-method, after a call that may carry `J` failed: the `J` it started with back
    /// (its LU is redone when next needed), so the next call starts as this one did.
    fn carry_back(&mut self) {
        let c = &mut *self.carry;
        if c.prev_saved {
            self.jac.copy_from(&c.jac_prev);
            c.prev_saved = false;
            self.lu_h = f64::NAN;
        }
    }

    /// The step loop of [`Rosenbrock::run_adaptive`] from a `J` wanted (`need_jac`) or kept
    /// with `jac_age` accepted steps on it: the next step size and the age at the end.
    #[allow(clippy::too_many_arguments)]
    fn adaptive_loop<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t0: f64,
        t1: f64,
        h0: f64,
        opts: &Options,
        mut have_f0: bool,
        mut need_jac: bool,
        mut jac_age: u32,
    ) -> Result<(f64, u32), SolverError> {
        let mut lp = StepLoop::new(t0, h0);
        let mut need_linearise = true;
        let w_method = self.method != RosMethod::Rodas4;
        let mut accepted_here: u64 = 0;
        let (mut hacc, mut erracc) = (0.0f64, 0.0f64);
        let mut singular_streak = 0u32;
        loop {
            lp.check(opts)?;
            if need_linearise {
                self.prepare(sys, lp.t, opts, have_f0, need_jac)?;
                if need_jac {
                    need_jac = false;
                    jac_age = 0;
                }
                need_linearise = false;
                have_f0 = false;
            }
            let (h_prop, last) = lp.begin(t1);
            let (t, h) = (lp.t, lp.h);
            let err = match self.attempt(sys, t, h)? {
                Attempt::Done => {
                    singular_streak = 0;
                    let err = error_norm(&self.u[5], &self.y, &self.ynew, opts);
                    if !err.is_finite() {
                        lp.nonfinite_error(&mut self.stats);
                    }
                    err
                }
                Attempt::Singular => {
                    self.stats.rejected += 1;
                    singular_streak += 1;
                    if singular_streak > MAX_SINGULAR {
                        return Err(SolverError::Singular { t, h });
                    }
                    lp.h *= 0.5;
                    lp.reject = true;
                    f64::NAN
                }
                Attempt::NonFinite(tb, idx) => {
                    lp.nonfinite(&mut self.stats, tb, idx)?;
                    f64::NAN
                }
            };
            if err.is_finite() {
                lp.nonfinite_streak = 0;
                let mut fac = (self.method.error_root(err) / SAFE).clamp(FAC2, FAC1);
                let mut h_new = h / fac;
                if err <= 1.0 {
                    if accepted_here >= 1 {
                        // Gustafsson's predictive controller (Hairer & Wanner II, Eq. IV.8.21)
                        let root = self.method.error_root(err * err / erracc);
                        let facgus = ((hacc / h) * root / SAFE).clamp(FAC2, FAC1);
                        fac = fac.max(facgus);
                        h_new = h / fac;
                    }
                    hacc = h;
                    erracc = err.max(1e-2);
                    accepted_here += 1;
                    let t_new = if last { t1 } else { t + h };
                    self.accept(t, t_new);
                    if sys.observes_steps() {
                        sys.step_accepted(t, t_new, &|tt, out| self.dense(tt, out));
                    }
                    need_linearise = true;
                    if w_method {
                        jac_age += 1;
                        need_jac = jac_age >= W_JAC_MAX_AGE;
                        // Keep the step (and with it the LU) when the controller would grow
                        // it only a little (RADAU5's rule, Hairer & Wanner II §IV.8).
                        if h_new >= h && h_new <= W_HOLD * h {
                            h_new = h;
                        }
                    }
                    if let Some(h_next) = lp.accepted(t_new, h_new, h_prop, last, opts) {
                        return Ok((h_next, jac_age));
                    }
                    continue;
                }
                self.stats.rejected += 1;
                lp.reject = true;
                lp.h = h_new;
            }
            // Rejected. A kept J (W-method) is refreshed here; f0 still holds f(t, y).
            if w_method && jac_age > 0 {
                (need_jac, need_linearise, have_f0) = (true, true, true);
            }
        }
    }

    /// One step attempt from `(t, self.y)`: fills `ynew` and the error vector `u[5]`.
    fn attempt<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
    ) -> Result<Attempt, SolverError> {
        match self.method {
            RosMethod::Rodas4 => self.attempt_rodas4(sys, t, h),
            RosMethod::Ros34pw2 => self.attempt_w(sys, t, h),
        }
    }

    /// One W-method step attempt from `(t, self.y)` with the current `f0`, `J` (any
    /// approximation) and, if on, `∂f/∂t`; the LU is reused when it is for this `h`:
    ///
    /// ```text
    /// (I/(hγ) − J) u_i = f(t + c_i h, y + Σ_{j<i} a_ij u_j) + Σ_{j<i} (c_ij/h) u_j [+ h d_i ∂f/∂t]
    /// y_new = y + Σ m_i u_i,   error = Σ (m_i − m̂_i) u_i
    /// ```
    fn attempt_w<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
    ) -> Result<Attempt, SolverError> {
        let w = &self.w;
        // `!=` is also true for the NaN of "no LU".
        if self.lu_h != h {
            self.stats.lu_decomps += 1;
            if !self.solver.factor(1.0 / (h * w.gamma), &self.jac) {
                self.lu_h = f64::NAN;
                return Ok(Attempt::Singular);
            }
            self.lu_h = h;
        }
        let ih = 1.0 / h;
        let (y, ytmp, f0, dfdt) = (&self.y, &mut self.ytmp, &self.f0, &self.dfdt);
        let (stages, rest) = self.u.split_at_mut(W_STAGES);
        // The sums run over whole vectors, one stage `j` after the other (each component
        // gets its terms in the order of `j`, as a sum per component would give them).
        for i in 0..W_STAGES {
            let (done, cur) = stages.split_at_mut(i);
            let ui = &mut cur[0];
            if i == 0 {
                ui.copy_from_slice(f0);
            } else {
                ytmp.copy_from_slice(y);
                for (j, uj) in done.iter().enumerate() {
                    let a = w.a[i][j];
                    for (v, u) in ytmp.iter_mut().zip(uj) {
                        *v += a * u;
                    }
                }
                let ti = t + w.c[i] * h;
                if let Some(idx) = eval(sys, &mut self.stats, ti, ytmp, ui)? {
                    return Ok(Attempt::NonFinite(ti, idx));
                }
            }
            for (j, uj) in done.iter().enumerate() {
                let c = ih * w.cc[i][j];
                for (v, u) in ui.iter_mut().zip(uj) {
                    *v += c * u;
                }
            }
            if self.dfdt_on {
                let d = h * w.d[i];
                for (v, g) in ui.iter_mut().zip(dfdt) {
                    *v += d * g;
                }
            }
            self.solver.solve(ui);
        }
        let err = &mut rest[rest.len() - 1];
        self.ynew.copy_from_slice(y);
        err.fill(0.0);
        for (j, uj) in stages.iter().enumerate() {
            let (m, e) = (w.m[j], w.e[j]);
            for ((yn, er), u) in self.ynew.iter_mut().zip(err.iter_mut()).zip(uj) {
                *yn += m * u;
                *er += e * u;
            }
        }
        if let Some(i) = self.ynew.iter().position(|v| !v.is_finite()) {
            return Ok(Attempt::NonFinite(t + h, i));
        }
        Ok(Attempt::Done)
    }

    /// One RODAS4 step attempt from `(t, self.y)` with the current `f0`, `J`, `∂f/∂t`:
    /// fills `u[0..6]` and `ynew`.
    fn attempt_rodas4<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
    ) -> Result<Attempt, SolverError> {
        let n = self.n;
        self.stats.lu_decomps += 1;
        if !self.solver.factor(1.0 / (h * GAMMA), &self.jac) {
            return Ok(Attempt::Singular);
        }
        let st = &mut self.stats;
        // Every vector cut to `n` once, so the stage loops run without bounds checks.
        let (y, ytmp, ftmp, f0, dfdt) = (
            &self.y[..n],
            &mut self.ytmp[..n],
            &mut self.ftmp[..n],
            &self.f0[..n],
            &self.dfdt[..n],
        );
        let [u1, u2, u3, u4, u5, u6] = &mut self.u;
        let (u1, u2, u3, u4, u5, u6) = (
            &mut u1[..n],
            &mut u2[..n],
            &mut u3[..n],
            &mut u4[..n],
            &mut u5[..n],
            &mut u6[..n],
        );
        let ynew = &mut self.ynew[..n];
        let solver = &mut self.solver;
        let ih = 1.0 / h;

        // stage 1
        for i in 0..n {
            u1[i] = f0[i] + h * D1 * dfdt[i];
        }
        solver.solve(u1);
        // stage 2
        for i in 0..n {
            ytmp[i] = y[i] + A21 * u1[i];
        }
        if let Some(i) = eval(sys, st, t + C2 * h, ytmp, ftmp)? {
            return Ok(Attempt::NonFinite(t + C2 * h, i));
        }
        for i in 0..n {
            u2[i] = ftmp[i] + h * D2 * dfdt[i] + ih * C21 * u1[i];
        }
        solver.solve(u2);
        // stage 3
        for i in 0..n {
            ytmp[i] = y[i] + A31 * u1[i] + A32 * u2[i];
        }
        if let Some(i) = eval(sys, st, t + C3 * h, ytmp, ftmp)? {
            return Ok(Attempt::NonFinite(t + C3 * h, i));
        }
        for i in 0..n {
            u3[i] = ftmp[i] + h * D3 * dfdt[i] + ih * (C31 * u1[i] + C32 * u2[i]);
        }
        solver.solve(u3);
        // stage 4
        for i in 0..n {
            ytmp[i] = y[i] + A41 * u1[i] + A42 * u2[i] + A43 * u3[i];
        }
        if let Some(i) = eval(sys, st, t + C4 * h, ytmp, ftmp)? {
            return Ok(Attempt::NonFinite(t + C4 * h, i));
        }
        for i in 0..n {
            u4[i] = ftmp[i] + h * D4 * dfdt[i] + ih * (C41 * u1[i] + C42 * u2[i] + C43 * u3[i]);
        }
        solver.solve(u4);
        // stage 5 (c5 = 1, d5 = 0)
        for i in 0..n {
            ytmp[i] = y[i] + A51 * u1[i] + A52 * u2[i] + A53 * u3[i] + A54 * u4[i];
        }
        let tph = t + h;
        if let Some(i) = eval(sys, st, tph, ytmp, ftmp)? {
            return Ok(Attempt::NonFinite(tph, i));
        }
        for i in 0..n {
            u5[i] = ftmp[i] + ih * (C51 * u1[i] + C52 * u2[i] + C53 * u3[i] + C54 * u4[i]);
        }
        solver.solve(u5);
        // stage 6 (stiffly accurate: its argument is the embedded solution)
        for i in 0..n {
            ytmp[i] += u5[i];
        }
        if let Some(i) = eval(sys, st, tph, ytmp, ftmp)? {
            return Ok(Attempt::NonFinite(tph, i));
        }
        for i in 0..n {
            u6[i] = ftmp[i]
                + ih * (C61 * u1[i] + C62 * u2[i] + C63 * u3[i] + C64 * u4[i] + C65 * u5[i]);
        }
        solver.solve(u6);
        for i in 0..n {
            ynew[i] = ytmp[i] + u6[i];
        }
        if let Some(i) = ynew.iter().position(|v| !v.is_finite()) {
            return Ok(Attempt::NonFinite(tph, i));
        }
        Ok(Attempt::Done)
    }

    /// Accept the attempted step `[t, t_new]`: dense output, new state.
    fn accept(&mut self, t: f64, t_new: f64) {
        if self.method == RosMethod::Rodas4 {
            let [u1, u2, u3, u4, u5, _] = &self.u;
            for i in 0..self.n {
                self.kd1[i] = H21 * u1[i] + H22 * u2[i] + H23 * u3[i] + H24 * u4[i] + H25 * u5[i];
                self.kd2[i] = H31 * u1[i] + H32 * u2[i] + H33 * u3[i] + H34 * u4[i] + H35 * u5[i];
            }
        }
        std::mem::swap(&mut self.y_old, &mut self.y);
        self.y.copy_from_slice(&self.ynew);
        self.t_old = t;
        self.h_old = t_new - t;
        self.dense_valid = true;
        self.stats.accepted += 1;
    }
}

/// W-method memory across calls ([`OdeSystem::carries_jacobian`]): where the last carrying
/// call ended (`end_y`, with `end_age` accepted steps on `J`) and where it began
/// (`start_y`, `start_age`), and the `J` it began with (`jac_prev`) if it replaced it.
#[derive(Debug)]
struct Carry {
    end_y: Vec<f64>,
    end_age: u32,
    end_ok: bool,
    start_y: Vec<f64>,
    start_age: u32,
    start_ok: bool,
    jac_prev: DMatrix<f64>,
    prev_saved: bool,
}

impl Carry {
    fn new(n: usize) -> Self {
        Carry {
            end_y: vec![0.0; n],
            end_age: 0,
            end_ok: false,
            start_y: vec![0.0; n],
            start_age: 0,
            start_ok: false,
            jac_prev: DMatrix::zeros(n, n),
            prev_saved: false,
        }
    }

    /// Nothing to carry: the next carrying call starts with a fresh `J`.
    fn forget(&mut self) {
        (self.end_ok, self.start_ok, self.prev_saved) = (false, false, false);
    }
}

/// No NaN or infinity in `v`: an OR over the exponent bits (all ones for NaN and inf).
fn all_finite(v: &[f64]) -> bool {
    const EXP: u64 = 0x7ff0_0000_0000_0000;
    !v.iter()
        .fold(false, |bad, x| bad | (x.to_bits() & EXP == EXP))
}

/// Outcome of one step attempt.
enum Attempt {
    Done,
    Singular,
    NonFinite(f64, usize),
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The controller's roots are the exact roots to rounding (`root^q` gives `x` back to
    /// 8 ulp, `q = 1/exponent`) and `powf` by the method's exponent to 1e-15 relative
    /// (`powf(x, 1/3)` is off by `1/3`'s own rounding), over the errors the controller
    /// meets (1e-12 to 1e12).
    #[test]
    fn error_roots_are_the_roots() {
        for m in [RosMethod::Rodas4, RosMethod::Ros34pw2] {
            let e = m.error_exponent();
            let q = (1.0 / e).round() as i32;
            for k in -120..=120 {
                for f in [1.0, 1.37, 2.0, 7.9] {
                    let x = f * 10f64.powf(k as f64 / 10.0);
                    let a = m.error_root(x);
                    let back = a.powi(q);
                    assert!(
                        (back - x).abs() <= 8.0 * f64::EPSILON * x,
                        "{m:?} {x:e}: {a:e}"
                    );
                    let b = x.powf(e);
                    assert!((a - b).abs() <= 1e-15 * b, "{m:?} {x:e}: {a:e} {b:e}");
                }
            }
        }
    }

    /// Van der Pol, stiff (`ε = 1e-3`), analytic `J`; `carry` says whether calls may carry
    /// `J`; from the `fail_at`-th right-hand side on, every evaluation fails.
    struct Vdp {
        carry: bool,
        evals: usize,
        fail_at: usize,
        h_call: f64,
    }
    impl OdeSystem for Vdp {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
            self.evals += 1;
            if self.evals >= self.fail_at {
                return Err("refused".into());
            }
            dy[0] = y[1];
            dy[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / 1e-3;
            Ok(())
        }
        fn jacobian(&mut self, _t: f64, y: &[f64], j: &mut DMatrix<f64>) -> bool {
            j[(0, 0)] = 0.0;
            j[(0, 1)] = 1.0;
            j[(1, 0)] = (-2.0 * y[0] * y[1] - 1.0) / 1e-3;
            j[(1, 1)] = (1.0 - y[0] * y[0]) / 1e-3;
            true
        }
        fn carries_jacobian(&self) -> bool {
            self.carry
        }
    }

    fn w() -> Rosenbrock {
        Rosenbrock::with_method(RosMethod::Ros34pw2, Box::new(DenseLu::new(2)))
    }

    const CALLS: usize = 60;
    /// Calls of a few steps each, most on the `J` of an earlier call.
    const SHORT: f64 = 2e-3;
    /// Calls of tens of steps: `J` is often replaced inside a call.
    const LONG: f64 = 2e-2;

    /// One call `i` of the run (`[i H, (i+1) H]`) from `y`, `h`.
    fn call(r: &mut Rosenbrock, sys: &mut Vdp, i: usize, y: &mut [f64; 2], h: &mut f64) -> bool {
        let opts = Options::new(2, 1e-6, 1e-8);
        let t = i as f64 * sys.h_call;
        r.integrate(sys, t, t + sys.h_call, y, h, &opts).is_ok()
    }

    /// What runs before call `i`: `between(i, r, sys, y, h)`.
    type Between<'a> = dyn FnMut(usize, &mut Rosenbrock, &mut Vdp, &mut [f64; 2], &mut f64) + 'a;

    /// `(y, h)` bits after every call; `between` runs before every call.
    fn run(carry: bool, h_call: f64, between: &mut Between) -> (Vec<[u64; 3]>, Stats) {
        let mut r = w();
        let mut sys = Vdp {
            carry,
            evals: 0,
            fail_at: usize::MAX,
            h_call,
        };
        let (mut y, mut h) = ([2.0, 0.0], 0.0);
        let mut out = Vec::new();
        for i in 0..CALLS {
            between(i, &mut r, &mut sys, &mut y, &mut h);
            assert!(call(&mut r, &mut sys, i, &mut y, &mut h), "call {i}");
            out.push([y[0].to_bits(), y[1].to_bits(), h.to_bits()]);
        }
        (out, r.stats)
    }

    /// A carried `J` is the last call's: fewer Jacobians than calls (and than the
    /// calls-fresh run), the same solution to the tolerance's order, not the same bits.
    #[test]
    fn calls_that_continue_one_another_carry_the_jacobian() {
        let (fresh, sf) = run(false, SHORT, &mut |_, _, _, _, _| {});
        let (kept, sk) = run(true, SHORT, &mut |_, _, _, _, _| {});
        println!("fresh {sf:?}\ncarried {sk:?}");
        assert!(sf.jac_evals >= CALLS as u64, "{sf:?}");
        assert!(sk.jac_evals < sf.jac_evals / 2, "{sk:?} {sf:?}");
        assert!(sk.lu_decomps < sf.lu_decomps, "{sk:?} {sf:?}");
        assert_ne!(fresh, kept);
        let y = |b: &[u64; 3]| [f64::from_bits(b[0]), f64::from_bits(b[1])];
        let (a, b) = (y(&fresh[CALLS - 1]), y(&kept[CALLS - 1]));
        assert!(
            (a[0] - b[0]).abs() < 1e-3 && (a[1] - b[1]).abs() < 1e-2,
            "{a:?} {b:?}"
        );
    }

    /// A call that fails (whatever it did to `J` before failing) or whose result is not
    /// kept, then repeated, gives the bits of the run without it; some of the dropped
    /// calls failed, some had replaced a `J` that the repeat keeps.
    #[test]
    fn a_failed_or_dropped_call_leaves_the_carried_jacobian_as_it_was() {
        let (plain, _) = run(true, LONG, &mut |_, _, _, _, _| {});
        let (mut replaced, mut failed) = (0, 0);
        for at in 1..CALLS / 3 {
            for fail_after in [1, 3, 6, 9, 14, 25, usize::MAX] {
                let (mut jac_in_dropped, mut young) = (0, false);
                let (with, _) = run(true, LONG, &mut |i, r, sys, y, h| {
                    if i != at {
                        return;
                    }
                    let (y0, h0) = (*y, *h);
                    let j0 = r.stats.jac_evals;
                    // A J of the call's start would be computed again by the repeat.
                    young = r.carry.end_ok && r.carry.end_age < W_JAC_MAX_AGE;
                    sys.fail_at = sys.evals.saturating_add(fail_after);
                    if !call(r, sys, i, y, h) {
                        failed += 1;
                    }
                    sys.fail_at = usize::MAX;
                    jac_in_dropped = r.stats.jac_evals - j0;
                    (*y, *h) = (y0, h0);
                });
                replaced += usize::from(jac_in_dropped > 0 && young);
                assert!(with == plain, "call {at}, failing after {fail_after}");
            }
        }
        println!("{failed} calls failed, {replaced} dropped calls replaced a kept J");
        assert!(replaced > 0 && failed > 0);
    }

    /// A call that may not carry (a state taken or restored) starts with a fresh `J`;
    /// from there a fresh integrator gives the same bits as the used one.
    #[test]
    fn a_call_that_may_not_carry_starts_fresh_like_a_new_integrator() {
        let at = 23;
        let mut start = None;
        let (used, _) = run(true, SHORT, &mut |i, r, sys, y, h| {
            sys.carry = i != at;
            if i == at {
                start = Some((*y, *h, r.stats.jac_evals));
            }
        });
        let (y0, h0, _) = start.unwrap();
        let mut r = w();
        let mut sys = Vdp {
            carry: false,
            evals: 0,
            fail_at: usize::MAX,
            h_call: SHORT,
        };
        let (mut y, mut h) = (y0, h0);
        for (i, bits) in used.iter().enumerate().skip(at) {
            sys.carry = i != at;
            assert!(call(&mut r, &mut sys, i, &mut y, &mut h));
            assert_eq!(&[y[0].to_bits(), y[1].to_bits(), h.to_bits()], bits, "{i}");
        }
    }
}
