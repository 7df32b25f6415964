//! Explicit Dormand–Prince 5(4) (Dormand & Prince, J. Comput. Appl. Math. 6 (1980) 19–26),
//! organised as Hairer's code DOPRI5 (Hairer, Nørsett & Wanner, *Solving ODEs I*, 2nd ed.,
//! §II.5 Table 5.2 for the coefficients, §II.4 for the PI step-size controller, §II.6 for the
//! dense output, §IV.2 for the stiffness detection).

use super::{
    check_call, error_norm, eval, eval_stage, fixed_steps, initial_step, OdeSystem, Options,
    SolverError, Start, Stats, StepLoop,
};

// Dormand–Prince coefficients (Hairer, Nørsett & Wanner I, Table II.5.2).
const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
// 5th-order weights (= the last row, FSAL)
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
// error weights: 5th-order minus 4th-order weights
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
// dense output (Hairer, Nørsett & Wanner I, §II.6, Dormand & Prince's continuous extension)
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

// Controller constants of DOPRI5: safety factor, step ratio bounds, PI exponent β.
const SAFE: f64 = 0.9;
const FAC_MIN: f64 = 0.2; // h_new / h >= 0.2
const FAC_MAX: f64 = 10.0; // h_new / h <= 10
const BETA: f64 = 0.04;
const EXPO1: f64 = 0.2 - BETA * 0.75;
/// The PI controller's `err_old` at the start of a call, and its floor.
const FACOLD0: f64 = 1e-4;

/// Stiffness test threshold: `h·|λ|` beyond the border of the DOPRI5 stability region on
/// the negative real axis (≈ 3.3), Hairer, Nørsett & Wanner I, §IV.2 (Eq. 2.6).
const STIFF_HLAMBDA: f64 = 3.25;

/// Explicit Dormand–Prince 5(4) integrator with FSAL, PI control, dense output and
/// stiffness detection.
///
/// - Error estimate: the embedded 4th-order solution, weighted in Hairer's RMS norm.
/// - Step control (Hairer's DOPRI5): `h_new = h / clamp(err^(0.2−0.75β) / err_old^β / 0.9,
///   1/10, 5)` with `β = 0.04`; after a rejection the step does not grow.
/// - Dense output [`Dopri5::dense`]: the 4th-order continuous extension of the last
///   accepted step.
/// - Stiffness detection: on every accepted step the estimate
///   `h·|λ| ≈ h·‖k7 − k6‖ / ‖y1 − y6‖` (the two stages evaluated at `t + h`) is compared
///   with 3.25; 15 exceedances in a row (without 6 non-stiff steps between) raise
///   [`Stats::stiff_alarms`] by one. The integration goes on (it is a diagnosis).
#[derive(Debug, Clone)]
pub struct Dopri5 {
    n: usize,
    y: Vec<f64>,
    y1: Vec<f64>,
    ysti: Vec<f64>,
    e: Vec<f64>,
    k1: Vec<f64>,
    k2: Vec<f64>,
    k3: Vec<f64>,
    k4: Vec<f64>,
    k5: Vec<f64>,
    k6: Vec<f64>,
    k7: Vec<f64>,
    /// Dense output coefficients of the last accepted step.
    rcont: [Vec<f64>; 5],
    t_old: f64,
    h_old: f64,
    dense_valid: bool,
    /// Accepted steps the system does not observe keep their dense output coefficients
    /// ([`Dopri5::set_dense_output`]).
    dense_output: bool,
    /// `k1 = f(t, y)` holds for `y` as the last call left it (that call succeeded): the last
    /// stage of its last step, which the next call reuses when its system
    /// [continues](OdeSystem::continues) this one (FSAL across calls).
    fsal_ready: bool,
    /// `(x, x^β)` of the last `err_old^β` of the PI controller: every call starts from
    /// `err_old = 1e-4`, and small errors keep it there (a `powf` saved per step; the same
    /// bits, `powf` being a function).
    pow_memo: (f64, f64),
    /// Stiffness detector counters (consecutive stiff / non-stiff tests).
    iasti: u32,
    nonsti: u32,
    /// Work counters, accumulated over calls.
    pub stats: Stats,
}

impl Dopri5 {
    /// Allocate every work vector for `n` states.
    pub fn new(n: usize) -> Self {
        let v = || vec![0.0; n];
        Dopri5 {
            n,
            y: v(),
            y1: v(),
            ysti: v(),
            e: v(),
            k1: v(),
            k2: v(),
            k3: v(),
            k4: v(),
            k5: v(),
            k6: v(),
            k7: v(),
            rcont: [v(), v(), v(), v(), v()],
            t_old: 0.0,
            h_old: 0.0,
            dense_valid: false,
            dense_output: true,
            fsal_ready: false,
            pow_memo: (FACOLD0, FACOLD0.powf(BETA)),
            iasti: 0,
            nonsti: 0,
            stats: Stats::default(),
        }
    }

    /// The state dimension.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Keep (`true`, the default) or skip the dense output coefficients of the accepted
    /// steps the system does not observe ([`OdeSystem::observes_steps`]: observed steps
    /// always keep them for [`OdeSystem::step_accepted`]). Skipped, [`Dopri5::last_step`]
    /// and [`Dopri5::dense`] see no accepted step after such a step. For a caller that reads
    /// the dense output only while observing (the co-simulation component): the
    /// coefficients cost about a tenth of a step of a cheap system; the trajectory is the
    /// same bit for bit.
    pub fn set_dense_output(&mut self, keep: bool) {
        self.dense_output = keep;
    }

    /// The interval `[t_old, t_new]` of the last accepted step, if any.
    pub fn last_step(&self) -> Option<(f64, f64)> {
        self.dense_valid
            .then_some((self.t_old, self.t_old + self.h_old))
    }

    /// Whether the stiffness detector is currently counting stiff steps.
    pub fn looks_stiff(&self) -> bool {
        self.iasti > 0
    }

    /// 4th-order dense output at `t` in the last accepted step `[t_old, t_new]` (Hairer's
    /// `CONTD5`): `y(t_old + θh) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5)))`.
    pub fn dense(&self, t: f64, out: &mut [f64]) -> Result<(), SolverError> {
        super::check_dense(self.last_step(), t, out.len(), self.n)?;
        let th = (t - self.t_old) / self.h_old;
        let th1 = 1.0 - th;
        // Cut to `n`: no bounds checks, as in `attempt` (checked above: `out.len() == n`).
        let n = self.n;
        let out = &mut out[..n];
        let [r1, r2, r3, r4, r5] = &self.rcont;
        let (r1, r2, r3, r4, r5) = (&r1[..n], &r2[..n], &r3[..n], &r4[..n], &r5[..n]);
        for i in 0..n {
            out[i] = r1[i] + th * (r2[i] + th1 * (r3[i] + th * (r4[i] + th1 * r5[i])));
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
        let reuse = self.fsal_ready && sys.continues() && super::same_bits(&self.y, y);
        self.fsal_ready = false;
        if !reuse {
            self.y.copy_from_slice(y);
            if let Some(i) = eval(sys, &mut self.stats, t0, &self.y, &mut self.k1)? {
                return Err(SolverError::NonFinite {
                    t: t0,
                    what: "right-hand side",
                    index: i,
                });
            }
        }
        let h_next = if opts.fixed_step {
            self.run_fixed(sys, t0, t1, opts)?
        } else {
            let h0 = if h_trial.is_finite() && *h_trial > 0.0 {
                h_trial.min(opts.h_max)
            } else {
                let start = Start {
                    t0,
                    y0: &self.y,
                    f0: &self.k1,
                };
                initial_step(
                    sys,
                    &mut self.stats,
                    &start,
                    &mut self.y1,
                    &mut self.k2,
                    5,
                    opts,
                )?
            };
            self.run_adaptive(sys, t0, t1, h0, opts)?
        };
        y.copy_from_slice(&self.y);
        *h_trial = h_next;
        self.fsal_ready = true;
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
            if let Some((tb, idx)) = self.attempt(sys, t, h, i + 1 == steps)? {
                return Err(SolverError::NonFinite {
                    t: tb,
                    what: "right-hand side",
                    index: idx,
                });
            }
            let t_new = if i + 1 == steps { t1 } else { t + h };
            let observed = sys.observes_steps();
            self.accept(t, h, t_new, self.dense_output || observed);
            if observed {
                sys.step_accepted(t, t_new, &|tt, out| self.dense(tt, out));
            }
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
    ) -> Result<f64, SolverError> {
        let mut lp = StepLoop::new(t0, h0);
        let mut facold: f64 = FACOLD0;
        loop {
            lp.check(opts)?;
            let (h_prop, last) = lp.begin(t1);
            let (t, h) = (lp.t, lp.h);
            if let Some((tb, idx)) = self.attempt(sys, t, h, last)? {
                // a stage left the domain where f is finite: retry with a much smaller step
                lp.nonfinite(&mut self.stats, tb, idx)?;
                continue;
            }
            // error estimate (vectors cut to `n`: no bounds checks, as in `attempt`)
            let n = self.n;
            let (e, k1, k3, k4) = (
                &mut self.e[..n],
                &self.k1[..n],
                &self.k3[..n],
                &self.k4[..n],
            );
            let (k5, k6, k7) = (&self.k5[..n], &self.k6[..n], &self.k7[..n]);
            for i in 0..n {
                e[i] = h
                    * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
            }
            let err = error_norm(&self.e, &self.y, &self.y1, opts);
            if !err.is_finite() {
                lp.nonfinite_error(&mut self.stats);
                continue;
            }
            lp.nonfinite_streak = 0;
            let fac11 = err.powf(EXPO1);
            // Lund-stabilisation (PI control): divide by err_old^β
            if facold.to_bits() != self.pow_memo.0.to_bits() {
                self.pow_memo = (facold, facold.powf(BETA));
            }
            let fac = (fac11 / self.pow_memo.1 / SAFE).clamp(1.0 / FAC_MAX, 1.0 / FAC_MIN);
            let h_new = h / fac;
            if err <= 1.0 {
                facold = err.max(FACOLD0);
                self.stiffness_test(h);
                let t_new = if last { t1 } else { t + h };
                let observed = sys.observes_steps();
                self.accept(t, h, t_new, self.dense_output || observed);
                if observed {
                    sys.step_accepted(t, t_new, &|tt, out| self.dense(tt, out));
                }
                if let Some(h_next) = lp.accepted(t_new, h_new, h_prop, last, opts) {
                    return Ok(h_next);
                }
            } else {
                lp.h /= (1.0 / FAC_MIN).min(fac11 / SAFE);
                lp.reject = true;
                self.stats.rejected += 1;
            }
        }
    }

    /// One step attempt from `(t, self.y)` with `self.k1 = f(t, y)`: fills `k2..k7`, `ysti`
    /// (the stage-6 argument) and `y1`. `Some((t, i))`: component `i` of an evaluation at `t`
    /// was not finite. `last`: the step lands on the end of the call (its last stage, at the
    /// step's end, through [`OdeSystem::rhs_at_end`]).
    fn attempt<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
        last: bool,
    ) -> Result<Option<(f64, usize)>, SolverError> {
        let n = self.n;
        let st = &mut self.stats;
        // Every vector cut to `n` here, so the stage loops below carry no bounds checks and
        // vectorise (the same operations per element, so the same bits).
        let (y, y1) = (&self.y[..n], &mut self.y1[..n]);
        let (k1, k2, k3, k4, k5, k6, k7) = (
            &self.k1[..n],
            &mut self.k2[..n],
            &mut self.k3[..n],
            &mut self.k4[..n],
            &mut self.k5[..n],
            &mut self.k6[..n],
            &mut self.k7[..n],
        );
        for i in 0..n {
            y1[i] = y[i] + h * A21 * k1[i];
        }
        if let Some(i) = eval(sys, st, t + C2 * h, y1, k2)? {
            return Ok(Some((t + C2 * h, i)));
        }
        for i in 0..n {
            y1[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i]);
        }
        if let Some(i) = eval(sys, st, t + C3 * h, y1, k3)? {
            return Ok(Some((t + C3 * h, i)));
        }
        for i in 0..n {
            y1[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i]);
        }
        if let Some(i) = eval(sys, st, t + C4 * h, y1, k4)? {
            return Ok(Some((t + C4 * h, i)));
        }
        for i in 0..n {
            y1[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i]);
        }
        if let Some(i) = eval(sys, st, t + C5 * h, y1, k5)? {
            return Ok(Some((t + C5 * h, i)));
        }
        let ysti = &mut self.ysti[..n];
        for i in 0..n {
            ysti[i] =
                y[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i]);
        }
        let tph = t + h;
        if let Some(i) = eval(sys, st, tph, ysti, k6)? {
            return Ok(Some((tph, i)));
        }
        for i in 0..n {
            y1[i] =
                y[i] + h * (A71 * k1[i] + A73 * k3[i] + A74 * k4[i] + A75 * k5[i] + A76 * k6[i]);
        }
        if let Some(i) = eval_stage(sys, st, tph, y1, k7, last)? {
            return Ok(Some((tph, i)));
        }
        Ok(None)
    }

    /// Hairer's stiffness test on an accepted step (before `k7` replaces `k1`).
    fn stiffness_test(&mut self, h: f64) {
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..self.n {
            num += (self.k7[i] - self.k6[i]).powi(2);
            den += (self.y1[i] - self.ysti[i]).powi(2);
        }
        if den > 0.0 {
            let hlamb = h * (num / den).sqrt();
            if hlamb > STIFF_HLAMBDA {
                self.nonsti = 0;
                self.iasti += 1;
                if self.iasti == 15 {
                    self.stats.stiff_alarms += 1;
                    self.iasti = 0;
                }
            } else {
                self.nonsti += 1;
                if self.nonsti == 6 {
                    self.iasti = 0;
                }
            }
        }
    }

    /// Accept the attempted step `[t, t_new]` (`t_new = t + h`, or exactly `t1` on the last
    /// step): dense output coefficients (with `dense`), FSAL, new state.
    fn accept(&mut self, t: f64, h: f64, t_new: f64, dense: bool) {
        if dense {
            self.dense_coefficients(t, h, t_new);
        }
        self.dense_valid = dense;
        std::mem::swap(&mut self.k1, &mut self.k7);
        std::mem::swap(&mut self.y, &mut self.y1);
        self.stats.accepted += 1;
    }

    /// The dense output coefficients of the attempted step `[t, t_new]` (before
    /// [`Dopri5::accept`] swaps the stages).
    fn dense_coefficients(&mut self, t: f64, h: f64, t_new: f64) {
        let n = self.n;
        let [r1, r2, r3, r4, r5] = &mut self.rcont;
        // Cut to `n`: no bounds checks, as in `attempt`.
        let (r1, r2, r3, r4, r5) = (
            &mut r1[..n],
            &mut r2[..n],
            &mut r3[..n],
            &mut r4[..n],
            &mut r5[..n],
        );
        let (y, y1, k1, k3) = (&self.y[..n], &self.y1[..n], &self.k1[..n], &self.k3[..n]);
        let (k4, k5, k6, k7) = (&self.k4[..n], &self.k5[..n], &self.k6[..n], &self.k7[..n]);
        for i in 0..n {
            let ydiff = y1[i] - y[i];
            let bspl = h * k1[i] - ydiff;
            r1[i] = y[i];
            r2[i] = ydiff;
            r3[i] = bspl;
            r4[i] = ydiff - h * k7[i] - bspl;
            r5[i] =
                h * (D1 * k1[i] + D3 * k3[i] + D4 * k4[i] + D5 * k5[i] + D6 * k6[i] + D7 * k7[i]);
        }
        self.t_old = t;
        self.h_old = t_new - t;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::{DenseFn, Options};

    /// `y' = -y` (2 states), optionally watching the accepted steps: the dense output at
    /// each step's midpoint is collected.
    struct Decay {
        observe: bool,
        mids: Vec<f64>,
    }

    impl OdeSystem for Decay {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
            dy[0] = -y[0];
            dy[1] = -2.0 * y[1];
            Ok(())
        }
        fn observes_steps(&self) -> bool {
            self.observe
        }
        fn step_accepted(&mut self, t_old: f64, t_new: f64, dense: &DenseFn<'_>) {
            let mut out = [0.0; 2];
            dense(0.5 * (t_old + t_new), &mut out).unwrap();
            self.mids.extend(out);
        }
    }

    fn run(keep: bool, observe: bool) -> (Dopri5, Vec<u64>, Vec<f64>) {
        let mut d = Dopri5::new(2);
        d.set_dense_output(keep);
        let mut sys = Decay {
            observe,
            mids: Vec::new(),
        };
        let opts = Options::new(2, 1e-6, 1e-9);
        let (mut y, mut h) = ([1.0, 1.0], 0.0);
        d.integrate(&mut sys, 0.0, 1.0, &mut y, &mut h, &opts)
            .unwrap();
        d.integrate(&mut sys, 1.0, 2.0, &mut y, &mut h, &opts)
            .unwrap();
        let bits = y.iter().chain([&h]).map(|v| v.to_bits()).collect();
        (d, bits, sys.mids)
    }

    /// Skipping the dense output of unobserved steps changes no bit of the trajectory; it
    /// leaves no dense output to read afterwards, and observed steps still give theirs (the
    /// same bits as with it kept).
    #[test]
    fn skipped_dense_output_changes_no_bit() {
        let (kept, y_kept, _) = run(true, false);
        let (skipped, y_skipped, _) = run(false, false);
        assert_eq!(y_kept, y_skipped);
        assert_eq!(kept.stats, skipped.stats);
        let mut out = [0.0; 2];
        assert!(kept.last_step().is_some() && kept.dense(1.99, &mut out).is_ok());
        assert!(skipped.last_step().is_none() && skipped.dense(1.99, &mut out).is_err());
        let (_, y_obs_kept, mids_kept) = run(true, true);
        let (observed, y_obs, mids) = run(false, true);
        assert_eq!(y_obs, y_kept);
        assert_eq!(y_obs_kept, y_kept);
        assert!(!mids.is_empty());
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&mids), bits(&mids_kept));
        assert!(observed.last_step().is_some());
    }
}
