//! Integrators and nonlinear solvers written for the bearing problem.
//!
//! Two one-step integrators share one calling convention ([`Integrator::integrate`]):
//!
//! - [`Dopri5`]: explicit Dormand–Prince 5(4) with FSAL, Hairer's PI step-size controller,
//!   4th-order dense output and Hairer's stiffness detection (Hairer, Nørsett & Wanner,
//!   *Solving ODEs I*, 2nd ed., §II.4–II.6 and §IV.2; the code DOPRI5 is the model).
//! - [`Rosenbrock`]: RODAS4, the L-stable, stiffly accurate 6-stage Rosenbrock method of
//!   order 4(3) (Hairer & Wanner, *Solving ODEs II*, 2nd ed., §VI.4, Table 4.1 / the code
//!   RODAS), one LU per step attempt, with a pluggable linear solver ([`LinearSolver`]:
//!   [`DenseLu`] by default, [`BlockArrowhead`] for ball-structured systems, [`SecondOrderLu`]
//!   for positions and velocities with `dq/dt = v`). The same
//!   integrator runs the W-method ROS34PW2 ([`RosMethod::Ros34pw2`], order 3(2)), which
//!   keeps `J` and its LU across the steps of a call and needs no `∂f/∂t`.
//!
//! Conventions the co-simulation component relies on:
//!
//! - `integrate(sys, t0, t1, y, h_trial, opts)` integrates from `t0` to exactly `t1` with
//!   adaptive internal sub-steps. `h_trial` is the step-size memory: on entry the first trial
//!   step (`<= 0` or not finite: choose one automatically, Hairer's `HINIT`), on success the
//!   proposal for the next call. It is a plain `f64` the caller stores in its serialisable
//!   state; all other controller memory is reset at every call, so the result of a call is a
//!   function of `(t0, t1, y, h_trial, opts)` only (bit-for-bit restartable).
//! - Transaction: the integrator works in its own buffers and writes `y` and `h_trial` only
//!   on success. On failure they are untouched and a [`SolverError`] names the cause.
//! - No heap allocation while stepping: every work vector and matrix is allocated when the
//!   integrator is created for a dimension `n`.
//! - Error control with a per-component absolute tolerance vector and a scalar relative
//!   tolerance, in Hairer's RMS norm
//!   `err = sqrt(1/n · Σ (e_i / (atol_i + rtol·max(|y0_i|, |y1_i|)))²)`.
//! - Work counters ([`Stats`]) accumulate across calls.

mod dopri5;
mod linalg;
pub mod methods;
pub mod newton;
mod rosenbrock;

pub use dopri5::Dopri5;
pub use linalg::{lu_factor, lu_solve, BlockArrowhead, DenseLu, LinearSolver, SecondOrderLu};
pub use rosenbrock::{
    RosMethod, Rosenbrock, WCoeffs, ROS34PW2_ALPHA, ROS34PW2_B, ROS34PW2_BHAT, ROS34PW2_GAMMA,
    ROS34PW2_GAMMA_MATRIX, W_JAC_MAX_AGE,
};

use nalgebra::DMatrix;
use std::fmt;

/// Unit round-off of `f64` (Hairer's `UROUND`).
pub(crate) const UROUND: f64 = f64::EPSILON;

/// Most consecutive step attempts that may meet a non-finite right-hand side value (each
/// one cuts the step by 5) before the integration gives up.
const MAX_NONFINITE_RETRIES: u32 = 12;

/// Check a dense-output request: `t` inside the last accepted step (to round-off) and an
/// output buffer of the system's dimension.
pub(crate) fn check_dense(
    last: Option<(f64, f64)>,
    t: f64,
    out_len: usize,
    n: usize,
) -> Result<(), SolverError> {
    let Some((a, b)) = last else {
        return Err(SolverError::invalid(
            "t",
            t,
            "a time after an accepted step",
        ));
    };
    let slack = 1e-12 * (b - a).abs().max(UROUND * b.abs());
    if !(t >= a - slack && t <= b + slack) || out_len != n {
        return Err(SolverError::invalid(
            "t",
            t,
            format!("in the last accepted step [{a}, {b}] with out.len() = n"),
        ));
    }
    Ok(())
}

/// Dense output of the last accepted step: `dense(t, out)` fills the solution at `t`
/// ([`OdeSystem::step_accepted`]).
pub type DenseFn<'a> = dyn Fn(f64, &mut [f64]) -> Result<(), SolverError> + 'a;

/// A system of ordinary differential equations `y' = f(t, y)` of fixed dimension.
///
/// Time-dependent inputs are the system's business: it knows `t`.
pub trait OdeSystem {
    /// Number of states `n`.
    fn dim(&self) -> usize;

    /// Evaluate `dy = f(t, y)`. An `Err` aborts the integration (state unchanged) and its
    /// message is passed on in [`SolverError::Rhs`].
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String>;

    /// [`OdeSystem::rhs`] at the end of a step that lands on the end of the call (DOPRI5's
    /// last stage there): where the caller looks next, e.g. for outputs, so a system may
    /// keep more of this evaluation. The rates must be those of `rhs`. Default: `rhs`.
    fn rhs_at_end(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        self.rhs(t, y, dy)
    }

    /// Whether this call continues the integrator's last one with the same function: `f`
    /// does not depend on time and nothing it reads changed since that call's last stage.
    /// Then DOPRI5 starts with that stage when `y` is bit for bit where the last call left
    /// it (first same as last across calls: the same bits, one evaluation cheaper); RODAS4
    /// integrates as usual. Default `false`.
    fn continues(&self) -> bool {
        false
    }

    /// Whether the system watches the accepted steps ([`OdeSystem::step_accepted`]). Default
    /// `false` (then the integrators do not call it).
    fn observes_steps(&self) -> bool {
        false
    }

    /// Called after every accepted step `[t_old, t_new]` when [`OdeSystem::observes_steps`]:
    /// `dense(t, out)` fills the integrator's dense output at any `t` in that interval (an
    /// `Err` for a `t` outside it or an `out` of another length). For sampling the solution
    /// between the ends of a call (a window integrated straight through). Default: nothing.
    fn step_accepted(&mut self, _t_old: f64, _t_new: f64, _dense: &DenseFn<'_>) {}

    /// Whether a W-method (ROS34PW2) may start this call with the Jacobian approximation
    /// (and its age) that its last call ended with, when `y` is bit for bit where that
    /// call left it, or where it began when its result was not kept (a repeated call then
    /// starts as that one did). Any matrix keeps a W-method's order; its error estimate
    /// and the refresh after a rejection keep it honest. The bits of a call then depend
    /// on the calls before it, not only on its inputs: a system says yes only when that
    /// history is reproducible for its users. Default `false`.
    fn carries_jacobian(&self) -> bool {
        false
    }

    /// Fill the Jacobian `∂f/∂y` at `(t, y)` into `jac` (n × n) and return `true`, or return
    /// `false` (the default) to let the integrator build it by forward differences.
    fn jacobian(&mut self, _t: f64, _y: &[f64], _jac: &mut DMatrix<f64>) -> bool {
        false
    }

    /// Fill `∂f/∂t` at `(t, y)` and return `true`, or return `false` (the default) to let the
    /// integrator build it by a forward difference. An autonomous system fills zeros.
    fn time_derivative(&mut self, _t: f64, _y: &[f64], _dfdt: &mut [f64]) -> bool {
        false
    }
}

/// Settings of one `integrate` call.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Relative tolerance (`>= 0`, finite).
    pub rtol: f64,
    /// Absolute tolerance per state (length `n`, each `> 0`): the size below which a state's
    /// error no longer matters.
    pub atol: Vec<f64>,
    /// Most step attempts (accepted plus rejected) in one call.
    pub max_steps: u64,
    /// Largest step (`> 0`; `f64::INFINITY` for no limit).
    pub h_max: f64,
    /// Fixed-step mode: cover `[t0, t1]` with the fewest equal steps no longer than `h_max`,
    /// without error control (for convergence studies and deterministic HIL runs). The
    /// step-size memory returns the step used.
    pub fixed_step: bool,
}

impl Options {
    /// Adaptive stepping with the same absolute tolerance for all `n` states.
    pub fn new(n: usize, rtol: f64, atol: f64) -> Self {
        Options {
            rtol,
            atol: vec![atol; n],
            max_steps: 100_000,
            h_max: f64::INFINITY,
            fixed_step: false,
        }
    }

    /// Fixed steps no longer than `h` (tolerances unused but kept valid).
    pub fn fixed(n: usize, h: f64) -> Self {
        Options {
            rtol: 1e-6,
            atol: vec![1e-6; n],
            max_steps: u64::MAX,
            h_max: h,
            fixed_step: true,
        }
    }

    /// Check the options against the dimension `n` (no allocation unless refused).
    fn check(&self, n: usize) -> Result<(), SolverError> {
        // Every call checks its options: the usual case (all valid) in one branch-free
        // pass, the message of a refusal below.
        // `0 < a < inf` is `a.is_finite() && a > 0` (NaN fails both comparisons).
        let atol_ok = self
            .atol
            .iter()
            .fold(true, |ok, a| ok & (*a > 0.0) & (*a < f64::INFINITY));
        if self.rtol.is_finite()
            & (self.rtol >= 0.0)
            & (self.atol.len() == n)
            & atol_ok
            & (self.h_max > 0.0)
            & (!self.fixed_step | self.h_max.is_finite())
            & (self.max_steps != 0)
        {
            return Ok(());
        }
        if !(self.rtol.is_finite() && self.rtol >= 0.0) {
            return Err(SolverError::invalid(
                "rtol",
                self.rtol,
                "a finite number >= 0",
            ));
        }
        if self.atol.len() != n {
            return Err(SolverError::invalid(
                "atol.len()",
                self.atol.len(),
                format!("the system dimension {n}"),
            ));
        }
        if let Some((i, a)) = self
            .atol
            .iter()
            .enumerate()
            .find(|(_, a)| !(a.is_finite() && **a > 0.0))
        {
            return Err(SolverError::invalid(
                format!("atol[{i}]"),
                a,
                "a finite number > 0",
            ));
        }
        if self.h_max.is_nan() || self.h_max <= 0.0 {
            return Err(SolverError::invalid("h_max", self.h_max, "> 0"));
        }
        if self.fixed_step && !self.h_max.is_finite() {
            return Err(SolverError::invalid(
                "h_max",
                self.h_max,
                "a finite step in fixed-step mode",
            ));
        }
        if self.max_steps == 0 {
            return Err(SolverError::invalid("max_steps", 0, ">= 1"));
        }
        Ok(())
    }
}

/// Work counters of an integrator (kept with every other counter in [`crate::counters`]).
/// `a` and `b` bit for bit (a branch-free OR of the XORs, which the compiler vectorises).
pub(crate) fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .fold(0u64, |d, (x, y)| d | (x.to_bits() ^ y.to_bits()))
            == 0
}

pub use crate::counters::IntegratorStats as Stats;

/// Why an integration failed. The caller's state and step-size memory are unchanged.
#[derive(Debug, Clone, PartialEq)]
pub enum SolverError {
    /// A bad argument (tolerances, dimension, interval).
    Invalid {
        /// The argument.
        field: String,
        /// Its value as text.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// More than `max_steps` step attempts in one call.
    TooManySteps {
        /// Time reached.
        t: f64,
        /// The limit.
        max_steps: u64,
    },
    /// The step size fell below the resolution of `t`.
    StepSizeUnderflow {
        /// Time reached.
        t: f64,
        /// The step size.
        h: f64,
    },
    /// The right-hand side returned an error.
    Rhs {
        /// Time of the failing evaluation.
        t: f64,
        /// The system's message.
        message: String,
    },
    /// A non-finite value that step-size reduction could not remove.
    NonFinite {
        /// Time of the offending evaluation.
        t: f64,
        /// Which quantity: `"right-hand side"`, `"jacobian"`, `"initial state"`.
        what: &'static str,
        /// The offending component (row for a Jacobian).
        index: usize,
    },
    /// The Rosenbrock matrix `I/(hγ) − J` stayed singular after repeated step reductions.
    Singular {
        /// Time reached.
        t: f64,
        /// Last step size tried.
        h: f64,
    },
}

impl SolverError {
    fn invalid(
        field: impl Into<String>,
        value: impl fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        SolverError::Invalid {
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}

impl fmt::Display for SolverError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolverError::Invalid {
                field,
                value,
                allowed,
            } => write!(
                f,
                "invalid integrator argument `{field}` = {value}: allowed {allowed}"
            ),
            SolverError::TooManySteps { t, max_steps } => {
                write!(f, "more than {max_steps} steps (max_steps) before t = {t}")
            }
            SolverError::StepSizeUnderflow { t, h } => {
                write!(f, "step size underflow (h = {h:e}) at t = {t}")
            }
            SolverError::Rhs { t, message } => {
                write!(f, "right-hand side failed at t = {t}: {message}")
            }
            SolverError::NonFinite { t, what, index } => {
                write!(f, "{what} is not finite (component {index}) at t = {t}")
            }
            SolverError::Singular { t, h } => write!(
                f,
                "Rosenbrock matrix I/(h gamma) - J singular at t = {t} (h = {h:e})"
            ),
        }
    }
}

impl std::error::Error for SolverError {}

impl From<SolverError> for crate::Error {
    fn from(e: SolverError) -> Self {
        match e {
            SolverError::Invalid {
                field,
                value,
                allowed,
            } => crate::Error::Invalid {
                field: format!("solver.{field}"),
                value,
                allowed,
            },
            SolverError::TooManySteps { t, .. }
            | SolverError::StepSizeUnderflow { t, .. }
            | SolverError::Rhs { t, .. }
            | SolverError::NonFinite { t, .. }
            | SolverError::Singular { t, .. } => crate::Error::StepFailed {
                t,
                reason: e.to_string(),
            },
        }
    }
}

/// One of the integrators behind one calling convention.
#[derive(Debug)]
pub enum Integrator {
    /// Explicit Dormand–Prince 5(4).
    Dopri5(Dopri5),
    /// Linearly implicit RODAS4.
    Rosenbrock(Rosenbrock),
}

impl Integrator {
    /// Integrate `sys` from `t0` to exactly `t1` (`t1 >= t0`), see the [module docs](self).
    pub fn integrate<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t0: f64,
        t1: f64,
        y: &mut [f64],
        h_trial: &mut f64,
        opts: &Options,
    ) -> Result<(), SolverError> {
        match self {
            Integrator::Dopri5(m) => m.integrate(sys, t0, t1, y, h_trial, opts),
            Integrator::Rosenbrock(m) => m.integrate(sys, t0, t1, y, h_trial, opts),
        }
    }

    /// Keep (the default) or skip the dense output of the accepted steps the system does
    /// not observe: [`Dopri5::set_dense_output`]. RODAS4 keeps its own (its coefficients
    /// come with its stages).
    pub fn set_dense_output(&mut self, keep: bool) {
        if let Integrator::Dopri5(m) = self {
            m.set_dense_output(keep);
        }
    }

    /// Work counters (accumulated over all calls).
    pub fn stats(&self) -> &Stats {
        match self {
            Integrator::Dopri5(m) => &m.stats,
            Integrator::Rosenbrock(m) => &m.stats,
        }
    }

    /// Mutable work counters (e.g. to reset them).
    pub fn stats_mut(&mut self) -> &mut Stats {
        match self {
            Integrator::Dopri5(m) => &mut m.stats,
            Integrator::Rosenbrock(m) => &mut m.stats,
        }
    }

    /// Dense output at `t` inside the last accepted step (see [`Dopri5::dense`],
    /// [`Rosenbrock::dense`]).
    pub fn dense(&self, t: f64, out: &mut [f64]) -> Result<(), SolverError> {
        match self {
            Integrator::Dopri5(m) => m.dense(t, out),
            Integrator::Rosenbrock(m) => m.dense(t, out),
        }
    }

    /// The interval `[t_old, t_new]` of the last accepted step, if any.
    pub fn last_step(&self) -> Option<(f64, f64)> {
        match self {
            Integrator::Dopri5(m) => m.last_step(),
            Integrator::Rosenbrock(m) => m.last_step(),
        }
    }

    /// The state dimension the integrator was built for.
    pub fn dim(&self) -> usize {
        match self {
            Integrator::Dopri5(m) => m.dim(),
            Integrator::Rosenbrock(m) => m.dim(),
        }
    }
}

// ---------------------------------------------------------------------------------------
// Shared pieces
// ---------------------------------------------------------------------------------------

/// Check the common arguments of `integrate`.
fn check_call(
    n: usize,
    sys_dim: usize,
    t0: f64,
    t1: f64,
    y: &[f64],
    opts: &Options,
) -> Result<(), SolverError> {
    if sys_dim != n {
        return Err(SolverError::invalid(
            "system.dim()",
            sys_dim,
            format!("the integrator dimension {n}"),
        ));
    }
    if y.len() != n {
        return Err(SolverError::invalid(
            "y.len()",
            y.len(),
            format!("the integrator dimension {n}"),
        ));
    }
    if !t0.is_finite() {
        return Err(SolverError::invalid("t0", t0, "a finite number"));
    }
    if !(t1.is_finite() && t1 >= t0) {
        return Err(SolverError::invalid(
            "t1",
            t1,
            format!("finite and >= t0 = {t0}"),
        ));
    }
    if let Some(i) = y.iter().position(|v| !v.is_finite()) {
        return Err(SolverError::NonFinite {
            t: t0,
            what: "initial state",
            index: i,
        });
    }
    opts.check(n)
}

/// Evaluate the right-hand side, count it, and report the first non-finite component.
///
/// `Ok(None)`: finite; `Ok(Some(i))`: component `i` is not finite; `Err`: the system failed.
#[inline]
fn eval<S: OdeSystem + ?Sized>(
    sys: &mut S,
    stats: &mut Stats,
    t: f64,
    y: &[f64],
    dy: &mut [f64],
) -> Result<Option<usize>, SolverError> {
    eval_stage(sys, stats, t, y, dy, false)
}

/// [`eval`], through [`OdeSystem::rhs_at_end`] when `at_end` (the last stage of a step
/// landing on the end of the call).
///
/// Inlined into the stages: it wraps every evaluation (the count, the system's
/// right-hand side, the finiteness scan), so a call of its own per stage is overhead.
#[inline]
fn eval_stage<S: OdeSystem + ?Sized>(
    sys: &mut S,
    stats: &mut Stats,
    t: f64,
    y: &[f64],
    dy: &mut [f64],
    at_end: bool,
) -> Result<Option<usize>, SolverError> {
    stats.rhs_evals += 1;
    let r = if at_end {
        sys.rhs_at_end(t, y, dy)
    } else {
        sys.rhs(t, y, dy)
    };
    r.map_err(|message| SolverError::Rhs { t, message })?;
    Ok(dy.iter().position(|v| !v.is_finite()))
}

/// Hairer's RMS error norm `sqrt(1/n Σ (e_i / sk_i)²)`, `sk_i = atol_i + rtol·max(|y0_i|,|y1_i|)`.
fn error_norm(e: &[f64], y0: &[f64], y1: &[f64], opts: &Options) -> f64 {
    let n = e.len();
    let mut s = 0.0;
    for i in 0..n {
        let sk = opts.atol[i] + opts.rtol * y0[i].abs().max(y1[i].abs());
        let r = e[i] / sk;
        s += r * r;
    }
    (s / n.max(1) as f64).sqrt()
}

/// Where an integration starts: time `t0`, states `y0` and their rates `f0 = f(t0, y0)`.
#[derive(Debug, Clone, Copy)]
struct Start<'a> {
    t0: f64,
    y0: &'a [f64],
    f0: &'a [f64],
}

/// Initial step size, Hairer's `HINIT` (Hairer, Nørsett & Wanner I, §II.4, "Starting step
/// size"), from `start`: balance `h·‖f0‖` and `h²·‖f'‖` against the tolerance for a
/// method of order `order`. Uses `y1`, `f1` as scratch and one extra right-hand side
/// evaluation.
fn initial_step<S: OdeSystem + ?Sized>(
    sys: &mut S,
    stats: &mut Stats,
    start: &Start<'_>,
    y1: &mut [f64],
    f1: &mut [f64],
    order: i32,
    opts: &Options,
) -> Result<f64, SolverError> {
    let Start { t0, y0, f0 } = *start;
    let n = y0.len();
    let (mut dnf, mut dny) = (0.0, 0.0);
    for i in 0..n {
        let sk = opts.atol[i] + opts.rtol * y0[i].abs();
        dnf += (f0[i] / sk).powi(2);
        dny += (y0[i] / sk).powi(2);
    }
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
        1e-6
    } else {
        (dny / dnf).sqrt() * 0.01
    };
    h = h.min(opts.h_max);
    for i in 0..n {
        y1[i] = y0[i] + h * f0[i];
    }
    let bad = eval(sys, stats, t0 + h, y1, f1)?;
    if bad.is_some() {
        // The explicit Euler probe left the domain: fall back to a tiny step; the
        // controller grows it.
        return Ok((h * 1e-3).min(opts.h_max));
    }
    let mut der2 = 0.0;
    for i in 0..n {
        let sk = opts.atol[i] + opts.rtol * y0[i].abs();
        der2 += ((f1[i] - f0[i]) / sk).powi(2);
    }
    let der2 = der2.sqrt() / h;
    let der12 = der2.abs().max(dnf.sqrt());
    let h1 = if der12 <= 1e-15 {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / order as f64)
    };
    Ok((100.0 * h).min(h1).min(opts.h_max))
}

/// The step-size proposal to store after the last (possibly shortened) step of a call.
///
/// `h_used` was the last step (shortened to land on `t1`), `h_prop` the step the controller
/// had proposed before shortening, `h_new` the controller's proposal after the step. If the
/// shortened step was no harder than asked (`h_new >= h_used`), the earlier, larger proposal
/// still stands; otherwise the new, smaller one.
fn carry_step(h_used: f64, h_prop: f64, h_new: f64, h_max: f64) -> f64 {
    let h = if h_new >= h_used {
        h_new.max(h_prop)
    } else {
        h_new
    };
    h.min(h_max)
}

/// The error for a step size that fell below the resolution of `t`: if non-finite values
/// forced the reductions (the solution ran into a wall where `f` is not finite), that is the
/// cause to name.
fn underflow(t: f64, h: f64, last_nonfinite: Option<(f64, usize)>) -> SolverError {
    match last_nonfinite {
        Some((tb, index)) => SolverError::NonFinite {
            t: tb,
            what: "right-hand side",
            index,
        },
        None => SolverError::StepSizeUnderflow { t, h },
    }
}

/// The bookkeeping both adaptive loops share (DOPRI5 and the Rosenbrock methods): the
/// attempt budget, the step-size underflow, the retry after non-finite values, and the
/// last step of a call landing on `t1` with the step-size memory it leaves.
#[derive(Debug, Clone)]
struct StepLoop {
    /// Time reached.
    t: f64,
    /// The step to try next (after [`StepLoop::begin`]: the one being tried).
    h: f64,
    /// The last attempt was rejected.
    reject: bool,
    attempts: u64,
    nonfinite_streak: u32,
    last_nonfinite: Option<(f64, usize)>,
}

impl StepLoop {
    fn new(t0: f64, h0: f64) -> Self {
        StepLoop {
            t: t0,
            h: h0,
            reject: false,
            attempts: 0,
            nonfinite_streak: 0,
            last_nonfinite: None,
        }
    }

    /// The budget and the underflow checks before an attempt.
    fn check(&self, opts: &Options) -> Result<(), SolverError> {
        if self.attempts >= opts.max_steps {
            return Err(SolverError::TooManySteps {
                t: self.t,
                max_steps: opts.max_steps,
            });
        }
        if 0.1 * self.h <= self.t.abs() * UROUND || self.h < f64::MIN_POSITIVE {
            return Err(underflow(self.t, self.h, self.last_nonfinite));
        }
        Ok(())
    }

    /// Count an attempt and shorten its step to land on `t1` when it (nearly) reaches it:
    /// `(the step proposed before shortening, whether this is the call's last step)`.
    fn begin(&mut self, t1: f64) -> (f64, bool) {
        self.attempts += 1;
        let h_prop = self.h;
        let last = self.t + 1.01 * self.h >= t1;
        if last {
            self.h = t1 - self.t;
        }
        (h_prop, last)
    }

    /// A stage was not finite (component `index` at `t`): reject and retry with a fifth of
    /// the step, at most [`MAX_NONFINITE_RETRIES`] times in a row.
    fn nonfinite(&mut self, stats: &mut Stats, t: f64, index: usize) -> Result<(), SolverError> {
        stats.rejected += 1;
        self.nonfinite_streak += 1;
        self.last_nonfinite = Some((t, index));
        if self.nonfinite_streak > MAX_NONFINITE_RETRIES {
            return Err(SolverError::NonFinite {
                t,
                what: "right-hand side",
                index,
            });
        }
        self.h *= 0.2;
        self.reject = true;
        Ok(())
    }

    /// The error estimate is not finite: reject and retry with a fifth of the step.
    fn nonfinite_error(&mut self, stats: &mut Stats) {
        stats.rejected += 1;
        self.h *= 0.2;
        self.reject = true;
    }

    /// The step was accepted to `t_new` and the controller proposes `h_new`: the step to
    /// try next, or, after the call's last step, `Some` step-size memory to return.
    fn accepted(
        &mut self,
        t_new: f64,
        h_new: f64,
        h_prop: f64,
        last: bool,
        opts: &Options,
    ) -> Option<f64> {
        self.t = t_new;
        let mut h_new = h_new.min(opts.h_max);
        if self.reject {
            h_new = h_new.min(self.h);
        }
        if last {
            return Some(carry_step(self.h, h_prop, h_new, opts.h_max));
        }
        self.reject = false;
        self.h = h_new;
        None
    }
}

/// Number and size of equal fixed steps no longer than `h_max` covering `[t0, t1]`.
fn fixed_steps(t0: f64, t1: f64, h_max: f64) -> (u64, f64) {
    let span = t1 - t0;
    let n = ((span / h_max) * (1.0 - 1e-12)).ceil().max(1.0) as u64;
    (n, span / n as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrators_can_move_between_threads() {
        fn is_send<T: Send>() {}
        is_send::<Integrator>();
    }

    #[test]
    fn step_memory_after_a_shortened_last_step() {
        // shortened step that went well: the earlier, larger proposal stands
        assert_eq!(carry_step(0.1, 0.5, 0.3, f64::INFINITY), 0.5);
        // shortened step that was already too large: the smaller proposal wins
        assert_eq!(carry_step(0.1, 0.5, 0.05, f64::INFINITY), 0.05);
        assert_eq!(carry_step(0.1, 0.5, 0.3, 0.2), 0.2);
        // fixed steps: fewest equal steps of at most h_max, tolerant to rounding in t1/h_max
        assert_eq!(fixed_steps(0.0, 1.0, 0.1).0, 10);
        assert_eq!(fixed_steps(0.0, 1.0, 0.3).0, 4);
        assert_eq!(fixed_steps(0.0, 0.3, 0.1).0, 3);
    }
}
