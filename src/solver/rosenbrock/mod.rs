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
//! across the steps of one call (refreshed after a rejection on a `J` older than
//! [`W_REJECT_KEEP`] accepted steps and every [`W_JAC_MAX_AGE`] accepted steps; the LU
//! whenever `h` changes; the rest of a call under [`W_SPLIT`] steps in two equal ones) and,
//! when the system
//! allows it ([`OdeSystem::carries_jacobian`]), across calls that continue one another;
//! `∂f/∂t` is taken from the system when it gives it and left out otherwise (the autonomous form's
//! Jacobian approximated without its time column: still a W-method). The published
//! coefficients `α, Γ, b, b̂` are the data; the transformed ones (`A = αΓ⁻¹`,
//! `C = diag(Γ)⁻¹ − Γ⁻¹`, `m = bΓ⁻¹`) are computed from them.

mod stages;
mod tableau;
pub use tableau::*;
#[cfg(test)]
mod tests;

use super::{
    check_call, error_norm, eval, fixed_steps, initial_step, DenseLu, LinearSolver, OdeSystem,
    Options, SolverError, Start, Stats, StepLoop, UROUND,
};
use crate::solver::same_bits;
use nalgebra::DMatrix;

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
/// after a rejected step on a `J` older than `W_REJECT_KEEP` accepted steps and every
/// [`W_JAC_MAX_AGE`] accepted steps; the
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
                let start = Start {
                    t0,
                    y0: &self.y,
                    f0: &self.f0,
                };
                initial_step(
                    sys,
                    &mut self.stats,
                    &start,
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
        let lin = Linearisation {
            have_f0,
            need_jac,
            jac_age,
        };
        let r = self.adaptive_loop(sys, t0, t1, h0, opts, lin);
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

    /// The step loop of [`Rosenbrock::run_adaptive`] from the linearisation `lin` (a `J`
    /// wanted, or kept with `jac_age` accepted steps on it): the next step size and the age
    /// at the end.
    fn adaptive_loop<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t0: f64,
        t1: f64,
        h0: f64,
        opts: &Options,
        lin: Linearisation,
    ) -> Result<(f64, u32), SolverError> {
        let Linearisation {
            mut have_f0,
            mut need_jac,
            mut jac_age,
        } = lin;
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
                    if w_method && !last {
                        // The rest of the call in two equal steps rather than a full one
                        // and a short last one (which costs an LU of its own and starts
                        // the next call from a step out of scale).
                        let rest = t1 - t_new;
                        if rest > 1.01 * h_new && rest < W_SPLIT * h_new {
                            h_new = 0.5 * rest;
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
            // Rejected. A J kept over more than `W_REJECT_KEEP` accepted steps (W-method)
            // is refreshed here (f0 still holds f(t, y)); a younger one is kept: its
            // rejection is the step size's, which the smaller step answers (the method's
            // order holds for any J).
            if w_method && jac_age > W_REJECT_KEEP {
                (need_jac, need_linearise, have_f0) = (true, true, true);
            }
        }
    }
}

/// What the step loop starts from ([`Rosenbrock::adaptive_loop`]): `f(t0, y0)` already
/// in `f0` (`have_f0`), and a `J` wanted (`need_jac`) or kept with `jac_age` accepted steps
/// on it.
#[derive(Debug, Clone, Copy)]
struct Linearisation {
    have_f0: bool,
    need_jac: bool,
    jac_age: u32,
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
