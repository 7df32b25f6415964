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

use super::{
    carry_step, check_call, error_norm, eval, fixed_steps, initial_step, underflow, DenseLu,
    LinearSolver, OdeSystem, Options, SolverError, Stats, MAX_NONFINITE_RETRIES, UROUND,
};
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

/// RODAS4 integrator (linearly implicit, L-stable, order 4(3)) with one LU per step attempt.
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
pub struct Rosenbrock {
    n: usize,
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
    pub fn dense(&self, t: f64, out: &mut [f64]) -> Result<(), SolverError> {
        super::check_dense(self.last_step(), t, out.len(), self.n)?;
        let th = (t - self.t_old) / self.h_old;
        let th1 = 1.0 - th;
        for (i, o) in out.iter_mut().enumerate() {
            *o = th1 * self.y_old[i] + th * (self.y[i] + th1 * (self.kd1[i] + th * self.kd2[i]));
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
                    4,
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
        if !sys.time_derivative(t, &self.y, &mut self.dfdt) {
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

    fn run_fixed<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t0: f64,
        t1: f64,
        opts: &Options,
    ) -> Result<f64, SolverError> {
        let (steps, h) = fixed_steps(t0, t1, opts.h_max);
        for i in 0..steps {
            let t = t0 + i as f64 * h;
            self.linearise(sys, t, opts, false)?;
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
            self.accept(t, if i + 1 == steps { t1 } else { t + h });
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
        mut have_f0: bool,
    ) -> Result<f64, SolverError> {
        let mut t = t0;
        let mut h = h0;
        let mut reject = false;
        let mut need_linearise = true;
        let mut attempts: u64 = 0;
        let mut accepted_here: u64 = 0;
        let (mut hacc, mut erracc) = (0.0f64, 0.0f64);
        let mut singular_streak = 0u32;
        let mut nonfinite_streak = 0u32;
        let mut last_nonfinite: Option<(f64, usize)> = None;
        loop {
            if attempts >= opts.max_steps {
                return Err(SolverError::TooManySteps {
                    t,
                    max_steps: opts.max_steps,
                });
            }
            if 0.1 * h <= t.abs() * UROUND || h < f64::MIN_POSITIVE {
                return Err(underflow(t, h, last_nonfinite));
            }
            if need_linearise {
                self.linearise(sys, t, opts, have_f0)?;
                need_linearise = false;
                have_f0 = false;
            }
            attempts += 1;
            let h_prop = h;
            let last = t + 1.01 * h >= t1;
            if last {
                h = t1 - t;
            }
            match self.attempt(sys, t, h)? {
                Attempt::Done => {}
                Attempt::Singular => {
                    self.stats.rejected += 1;
                    singular_streak += 1;
                    if singular_streak > MAX_SINGULAR {
                        return Err(SolverError::Singular { t, h });
                    }
                    h *= 0.5;
                    reject = true;
                    continue;
                }
                Attempt::NonFinite(tb, idx) => {
                    self.stats.rejected += 1;
                    nonfinite_streak += 1;
                    last_nonfinite = Some((tb, idx));
                    if nonfinite_streak > MAX_NONFINITE_RETRIES {
                        return Err(SolverError::NonFinite {
                            t: tb,
                            what: "right-hand side",
                            index: idx,
                        });
                    }
                    h *= 0.2;
                    reject = true;
                    continue;
                }
            }
            singular_streak = 0;
            let err = error_norm(&self.u[5], &self.y, &self.ynew, opts);
            if !err.is_finite() {
                self.stats.rejected += 1;
                h *= 0.2;
                reject = true;
                continue;
            }
            nonfinite_streak = 0;
            let mut fac = (err.powf(0.25) / SAFE).clamp(FAC2, FAC1);
            let mut h_new = h / fac;
            if err <= 1.0 {
                if accepted_here >= 1 {
                    // Gustafsson's predictive controller (Hairer & Wanner II, Eq. IV.8.21)
                    let facgus =
                        ((hacc / h) * (err * err / erracc).powf(0.25) / SAFE).clamp(FAC2, FAC1);
                    fac = fac.max(facgus);
                    h_new = h / fac;
                }
                hacc = h;
                erracc = err.max(1e-2);
                accepted_here += 1;
                let t_new = if last { t1 } else { t + h };
                self.accept(t, t_new);
                t = t_new;
                need_linearise = true;
                h_new = h_new.min(opts.h_max);
                if reject {
                    h_new = h_new.min(h);
                }
                if last {
                    return Ok(carry_step(h, h_prop, h_new, opts.h_max));
                }
                reject = false;
                h = h_new;
            } else {
                self.stats.rejected += 1;
                reject = true;
                h = h_new;
            }
        }
    }

    /// One RODAS4 step attempt from `(t, self.y)` with the current `f0`, `J`, `∂f/∂t`:
    /// fills `u[0..6]` and `ynew`.
    fn attempt<S: OdeSystem + ?Sized>(
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
        let (y, ytmp, ftmp, f0, dfdt) = (
            &self.y,
            &mut self.ytmp,
            &mut self.ftmp,
            &self.f0,
            &self.dfdt,
        );
        let [u1, u2, u3, u4, u5, u6] = &mut self.u;
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
            self.ynew[i] = ytmp[i] + u6[i];
        }
        if let Some(i) = self.ynew.iter().position(|v| !v.is_finite()) {
            return Ok(Attempt::NonFinite(tph, i));
        }
        Ok(Attempt::Done)
    }

    /// Accept the attempted step `[t, t_new]`: dense output, new state.
    fn accept(&mut self, t: f64, t_new: f64) {
        let [u1, u2, u3, u4, u5, _] = &self.u;
        for i in 0..self.n {
            self.kd1[i] = H21 * u1[i] + H22 * u2[i] + H23 * u3[i] + H24 * u4[i] + H25 * u5[i];
            self.kd2[i] = H31 * u1[i] + H32 * u2[i] + H33 * u3[i] + H34 * u4[i] + H35 * u5[i];
        }
        std::mem::swap(&mut self.y_old, &mut self.y);
        self.y.copy_from_slice(&self.ynew);
        self.t_old = t;
        self.h_old = t_new - t;
        self.dense_valid = true;
        self.stats.accepted += 1;
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
