//! The system a step integrates, as the integrators see it ([`OdeSystem`]): the level's
//! states and, load-driven, the inner ring's, with the step's CPU budget and the
//! preallocated work space.

use super::inputs::{input_at, motion_at};
use super::level::{Jacobians, LevelModel, Motion, Point, Points};
use super::{thread_cpu_s, Causality, InputRule, State, I_LOAD, I_OMEGA, I_V, N_INPUT_SLOTS};
use crate::error::{Error, Result};
use crate::solver::{same_bits, DenseFn, OdeSystem, SolverError};
use std::time::Instant;

/// Most evaluations between two reads of the CPU clock (a read costs 0.2 µs, one
/// right-hand side of the cheapest level 0.3 µs: at most 0.3 % of a step).
pub(super) const BUDGET_EVERY: u32 = 256;

/// CPU time aimed at between two reads of the clock, s: evaluations that cost more are
/// checked more often, down to every one, so a step whose every right-hand side takes a
/// second still stops within a second of its budget.
pub(super) const BUDGET_READ_S: f64 = 1e-3;

/// The CPU-time budget of one communication step.
///
/// The thread's CPU clock is a system call (0.2–0.5 µs, as much as a whole cheap step), so
/// a step does not read it when it starts: it reads the wall clock (`Instant`, no system
/// call), and the CPU clock first at its first check. The CPU time counted is the wall
/// time up to that first read (an upper bound: a thread cannot run longer than the time
/// that passed) plus the thread's CPU time after it. A step that ends before its first
/// check reads no CPU clock at all.
#[derive(Debug, Clone, Copy)]
pub(super) struct Budget {
    /// Wall clock at the step start.
    pub(super) wall0: Instant,
    /// At the first check: the thread's CPU time then, and the wall time from the step
    /// start to then, s.
    pub(super) first: Option<(f64, f64)>,
    pub(super) limit: f64,
    pub(super) evals: u32,
    /// Evaluation count at which the clock is read next.
    pub(super) next: u32,
    /// Evaluations between reads as last estimated (the next step's first read comes after
    /// as many: a step of a few cheap evaluations then reads no clock but the wall clock
    /// at its start).
    pub(super) gap: u32,
    /// When the budget ran out: the wall time before the first CPU-clock read and the
    /// thread's CPU time after it, s (their sum is what counted: see the type's notes).
    pub(super) spent: Option<(f64, f64)>,
}

impl Budget {
    /// A budget of `limit` s from now, first checked after `first` evaluations (1 when
    /// nothing is known of their cost; the last step's gap otherwise).
    pub(super) fn new(limit: f64, first: u32) -> Self {
        let first = first.clamp(1, BUDGET_EVERY);
        Budget {
            wall0: Instant::now(),
            first: None,
            limit,
            evals: 0,
            next: first,
            gap: first,
            spent: None,
        }
    }

    /// Time used since the start, s: the wall time before the first CPU-clock read and the
    /// thread's CPU time since (see the type's notes).
    fn used(&mut self) -> (f64, f64) {
        match self.first {
            Some((cpu1, wall1)) => (wall1, thread_cpu_s() - cpu1),
            None => {
                let wall1 = self.wall0.elapsed().as_secs_f64();
                self.first = Some((thread_cpu_s(), wall1));
                (wall1, 0.0)
            }
        }
    }

    /// Count one evaluation; `true` once the budget is spent. The clock is read about
    /// every [`BUDGET_READ_S`] of CPU time as estimated from the evaluations so far (and
    /// from the last step's before the first read), and at least every [`BUDGET_EVERY`]
    /// evaluations.
    ///
    /// Inlined (it runs before every right-hand side): the count and one comparison; the
    /// clock read and the new gap are [`Budget::check`], out of line.
    #[inline]
    pub(super) fn spent(&mut self) -> bool {
        if self.spent.is_some() {
            return true;
        }
        self.evals = self.evals.saturating_add(1);
        self.evals >= self.next && self.check()
    }

    /// The clock read of [`Budget::spent`], due at this evaluation: `true` when the budget
    /// is spent, else the evaluation count of the next read is set.
    #[cold]
    #[inline(never)]
    fn check(&mut self) -> bool {
        let (wall, cpu) = self.used();
        let used = wall + cpu;
        if used > self.limit {
            self.spent = Some((wall, cpu));
            return true;
        }
        // This call precedes its evaluation: `evals - 1` of them are done.
        let done = self.evals - 1;
        let gap = if done == 0 {
            1.0
        } else {
            let per_eval = used / done as f64;
            (BUDGET_READ_S / per_eval.max(1e-12)).clamp(1.0, BUDGET_EVERY as f64)
        };
        self.gap = gap as u32;
        self.next = self.evals.saturating_add(self.gap);
        false
    }
}

/// The inner ring as a body (load-driven causality).
#[derive(Debug, Clone)]
pub(super) struct RingBody {
    /// Coordinates integrated (indices into q).
    pub(super) dofs: &'static [usize],
    /// Reciprocal mass (translations) or transverse inertia (tilts) per coordinate of `q`:
    /// the accelerations multiply by it (a division per coordinate and right-hand side
    /// sat on the integration's critical path).
    pub(super) inv_inertia: [f64; 5],
}

/// Preallocated work space of a step (no allocation inside `do_step`).
#[derive(Debug, Clone, Default)]
pub(super) struct Work {
    /// Rates at the output time, rates at a shifted time, and the shifted states (the
    /// central difference that gives `dF/dt`).
    pub(super) k: [Vec<f64>; 3],
    pub(super) y: Vec<f64>,
    pub(super) aux_save: Vec<f64>,
    /// What the last stage of the last step's integration read besides the states: the
    /// inputs and the level's memory (`inputs[..N_INPUT_SLOTS] | aux[..n_level_aux]`), when `fsal` is set
    /// (the inputs' derivatives were zero then, or unused by the input rule).
    pub(super) fsal_key: Vec<f64>,
    /// The last step's last stage may be the next step's first (see
    /// [`Work::fsal_matches`]).
    pub(super) fsal: bool,
}

impl Work {
    /// Whether the right-hand side the next integration of `st` starts with is the one the
    /// last integration ended with: `fsal` set (a time-invariant level, inputs constant
    /// inside that step), the inputs constant inside the next step too, and the inputs and
    /// the level's memory bit for bit as that last stage read them (the integrator itself
    /// checks the states). Then the inputs also pass [`Component::check_inputs_at`] as they
    /// did for the last step (constant inputs: the same values at every offset).
    ///
    /// [`Component::check_inputs_at`]: super::Component::check_inputs_at
    pub(super) fn fsal_matches(&self, st: &State, naux: usize, rule: InputRule) -> bool {
        if !self.fsal {
            return false;
        }
        let ni = N_INPUT_SLOTS;
        let k = &self.fsal_key;
        same_bits(&k[..ni], &st.inputs[..ni])
            && same_bits(&k[ni..], &st.aux[..naux])
            && inputs_constant(st, rule, false)
    }

    /// After a successful integration of `st`: remember what its last stage read, if the
    /// next step may start from it (`reusable`: the level's rates do not depend on time,
    /// [`super::level::LevelModel::rhs_time_invariant`]; and the inputs did not move
    /// inside the step, so the last stage saw them as the next step's first will).
    pub(super) fn fsal_store(&mut self, st: &State, naux: usize, rule: InputRule, reusable: bool) {
        self.fsal = reusable && inputs_constant(st, rule, false);
        if self.fsal {
            let ni = N_INPUT_SLOTS;
            let k = &mut self.fsal_key;
            k[..ni].copy_from_slice(&st.inputs[..ni]);
            k[ni..].copy_from_slice(&st.aux[..naux]);
        }
    }
}

/// Whether every input the step reads keeps its value through it under `rule`
/// ([`input_at`] gives the same bits at every offset): always when held; with velocities,
/// when the velocity inputs are zero or none is read (`ring_state`: the ring's motion is a
/// state); with derivatives, when every derivative is zero.
pub(super) fn inputs_constant(st: &State, rule: InputRule, ring_state: bool) -> bool {
    match rule {
        InputRule::Hold => true,
        InputRule::Velocity => ring_state || st.inputs[I_V..I_V + 5].iter().all(|v| *v == 0.0),
        InputRule::Derivatives => st.input_derivatives.iter().all(|d| *d == 0.0),
    }
}

/// Work space of the level Jacobians (see [`LevelModel::jacobian`]).
#[derive(Debug, Clone, Default)]
pub(super) struct JacWork {
    pub(super) jx: Vec<f64>,
    pub(super) jm: Vec<f64>,
    pub(super) wx: Vec<f64>,
    pub(super) wm: Vec<f64>,
}

/// The whole system a step integrates: the level's states and, load-driven, the ring's.
pub(super) struct Sys<'a> {
    pub(super) jw: Option<&'a mut JacWork>,
    pub(super) level: &'a mut dyn LevelModel,
    pub(super) st: &'a mut State,
    pub(super) ring: Option<&'a RingBody>,
    pub(super) rule: InputRule,
    pub(super) causality: Causality,
    pub(super) nl: usize,
    pub(super) naux: usize,
    pub(super) t0: f64,
    /// The last error the level raised at a trial point (the integrator sees NaN there and
    /// retries with a smaller step; if it gives up, this is the cause it reports).
    pub(super) last_error: Option<Error>,
    /// The step's CPU budget (none for output evaluations).
    pub(super) budget: Option<Budget>,
    /// The right-hand side is the one the last integration ended with
    /// ([`Work::fsal_matches`]; [`OdeSystem::continues`]).
    pub(super) continues: bool,
    /// The states wanted at communication points inside the integration (a window
    /// integrated straight through, [`Component::step_through`]); `None` for a step.
    ///
    /// [`Component::step_through`]: super::Component::step_through
    pub(super) sink: Option<&'a mut Sink>,
    /// No state was taken or set since the last step ([`OdeSystem::carries_jacobian`]).
    pub(super) carries_jac: bool,
}

/// The states at the communication points strictly inside a window integrated straight
/// through, sampled from the integrator's dense output as its steps pass them.
#[derive(Debug, Clone, Default)]
pub(super) struct Sink {
    /// Window start, s.
    pub(super) t0: f64,
    /// Communication step, s.
    pub(super) h: f64,
    /// Communication intervals in the window (points `1..n` are sampled here).
    pub(super) n: usize,
    /// The next point to sample.
    pub(super) next: usize,
    /// States of points `1..n`, one row of `dim` each.
    pub(super) xs: Vec<f64>,
    /// States per point.
    pub(super) dim: usize,
    /// The first dense-output refusal, if any.
    pub(super) error: Option<SolverError>,
}

impl Sink {
    /// Time of point `k`, s.
    pub(super) fn time(&self, k: usize) -> f64 {
        self.t0 + k as f64 * self.h
    }

    /// Sample the points in `(.., t_new]` of an accepted step.
    fn sample(&mut self, t_new: f64, dense: &DenseFn<'_>) {
        while self.next < self.n && self.error.is_none() {
            let t = self.time(self.next);
            if t > t_new {
                break;
            }
            let row = &mut self.xs[(self.next - 1) * self.dim..self.next * self.dim];
            if let Err(e) = dense(t, row) {
                self.error = Some(e);
            }
            self.next += 1;
        }
    }
}

/// Points per [`Sys::wrenches`] call in a window integrated straight through (their
/// motions are kept between the calls).
pub(super) const WRENCH_CHUNK: usize = 256;

impl Sys<'_> {
    /// Right-hand side at `s` after the step start; with `wrench`, also the bearing force.
    pub(super) fn eval(
        &mut self,
        s: f64,
        y: &[f64],
        dy: &mut [f64],
        wrench: Option<&mut [f64; 5]>,
    ) -> Result<()> {
        self.eval_level(s, y, dy, wrench, false)
    }

    /// The level's wrench at `s` after the step start with states `y`, as [`Sys::eval`]
    /// gives it, into `w` (zeros on entry, as there); the level's rates go to `dy`, the
    /// ring's are not computed (outputs between the integration's stops need the wrench
    /// only).
    pub(super) fn wrench(
        &mut self,
        s: f64,
        y: &[f64],
        dy: &mut [f64],
        w: &mut [f64; 5],
    ) -> Result<()> {
        let nl = self.nl;
        let m = motion_at(self.st, self.rule, s, self.causality, self.ring, nl, y);
        let (aux, _) = self.st.aux.split_at_mut(self.naux);
        let p = Point::new(self.t0 + s, &m, &y[..nl], aux);
        self.level.rhs(p, &mut dy[..nl], Some(w))
    }

    /// [`Sys::wrench`] at the points `s[k]` after the step start with states
    /// `xs[k * dim..(k + 1) * dim]`, into `out` (replaced, one wrench per point): one call
    /// of [`LevelModel::wrenches`] for them all; `ms` and `ts` are the caller's buffers for
    /// their motions and times (kept across calls: no allocation once they hold `s.len()`).
    pub(super) fn wrenches(
        &mut self,
        s: &[f64],
        xs: &[f64],
        dim: usize,
        dy: &mut [f64],
        (ms, ts): (&mut Vec<Motion>, &mut Vec<f64>),
        out: &mut Vec<[f64; 5]>,
    ) -> Result<()> {
        debug_assert!(xs.len() >= s.len() * dim);
        ms.resize(s.len(), Motion::default());
        ts.clear();
        let nl = self.nl;
        for ((&s, y), m) in s.iter().zip(xs.chunks_exact(dim)).zip(ms.iter_mut()) {
            match (self.causality, self.ring) {
                // `motion_at`'s load-driven motion written in place: a motion built on
                // the stack and then copied here would be read back wider than its
                // fields were written (a stalled store forwarding per point).
                (Causality::Load, Some(r)) => {
                    m.omega = input_at(self.st, I_OMEGA, s, self.rule);
                    (m.q, m.v) = ([0.0; 5], [0.0; 5]);
                    let nd = r.dofs.len();
                    let (q, v) = y[nl..nl + 2 * nd].split_at(nd);
                    for ((&d, &q), &v) in r.dofs.iter().zip(q).zip(v) {
                        m.q[d] = q;
                        m.v[d] = v;
                    }
                }
                _ => *m = motion_at(self.st, self.rule, s, self.causality, self.ring, nl, y),
            }
            ts.push(self.t0 + s);
        }
        out.clear();
        out.resize(s.len(), [0.0; 5]);
        let p = Points {
            t: ts,
            m: ms,
            x: xs,
            stride: dim,
        };
        self.level.wrenches(p, &mut dy[..self.nl], out)
    }

    /// [`Sys::eval`]; `at_end`: through [`LevelModel::rhs_at_end`] (the last stage of a
    /// step landing on the end of the integration, where the outputs are evaluated next).
    ///
    /// Inlined into [`Sys::rates`] (the integrators' right-hand side): this layer runs at
    /// every evaluation, so the motion is built in place and the ring's rows are written
    /// through slices cut once, with no bounds check per coordinate; the acceleration is
    /// `(w + load) · (1/inertia)` with the reciprocal kept ([`RingBody::inv_inertia`]).
    #[inline(always)]
    fn eval_level(
        &mut self,
        s: f64,
        y: &[f64],
        dy: &mut [f64],
        wrench: Option<&mut [f64; 5]>,
        at_end: bool,
    ) -> Result<()> {
        let nl = self.nl;
        let m = motion_at(self.st, self.rule, s, self.causality, self.ring, nl, y);
        let (aux, _) = self.st.aux.split_at_mut(self.naux);
        let p = Point::new(self.t0 + s, &m, &y[..nl], aux);
        match self.ring {
            None if at_end => self.level.rhs_at_end(p, &mut dy[..nl], wrench)?,
            None => self.level.rhs(p, &mut dy[..nl], wrench)?,
            Some(ring) => {
                let mut w = [0.0; 5];
                if at_end {
                    self.level.rhs_at_end(p, &mut dy[..nl], Some(&mut w))?;
                } else {
                    self.level.rhs(p, &mut dy[..nl], Some(&mut w))?;
                }
                let nd = ring.dofs.len();
                let (dq, dv) = dy[nl..nl + 2 * nd].split_at_mut(nd);
                let v = &y[nl + nd..nl + 2 * nd];
                for (((dq, dv), &v), &d) in dq.iter_mut().zip(dv).zip(v).zip(ring.dofs) {
                    let load = input_at(self.st, I_LOAD + d, s, self.rule);
                    *dq = v;
                    *dv = (w[d] + load) * ring.inv_inertia[d];
                }
                if let Some(out) = wrench {
                    *out = w;
                }
            }
        }
        Ok(())
    }
}

impl OdeSystem for Sys<'_> {
    fn dim(&self) -> usize {
        self.st.x.len()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> std::result::Result<(), String> {
        self.rates(t, y, dy, false)
    }
    fn rhs_at_end(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> std::result::Result<(), String> {
        self.rates(t, y, dy, true)
    }
    fn continues(&self) -> bool {
        self.continues
    }
    fn observes_steps(&self) -> bool {
        self.sink.is_some()
    }
    fn step_accepted(&mut self, _t_old: f64, t_new: f64, dense: &DenseFn<'_>) {
        if let Some(sink) = self.sink.as_deref_mut() {
            sink.sample(t_new, dense);
        }
    }
    fn carries_jacobian(&self) -> bool {
        self.carries_jac
    }
    /// `∂f/∂t = 0` exactly when the level is [`LevelModel::rhs_time_invariant`] and its
    /// inputs do not move within the step ([`inputs_constant`]): `f(t + δ, y)` is then `f(t, y)` bit
    /// for bit, so the integrator's forward difference would give these zeros too (the
    /// trajectory is the same; one right-hand side fewer per step). The zeros drop the
    /// `h d_i ∂f/∂t` terms of the Rosenbrock stages (Hairer & Wanner II, §IV.7, the
    /// non-autonomous form), as for an autonomous system.
    fn time_derivative(&mut self, _t: f64, _y: &[f64], dfdt: &mut [f64]) -> bool {
        #[cfg(test)]
        if tests::FD_DFDT.with(std::cell::Cell::get) {
            return false;
        }
        let ring_state = self.causality == Causality::Load && self.ring.is_some();
        if !(self.level.rhs_time_invariant() && inputs_constant(self.st, self.rule, ring_state)) {
            return false;
        }
        dfdt.fill(0.0);
        true
    }
    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut nalgebra::DMatrix<f64>) -> bool {
        if self.budget.as_mut().is_some_and(Budget::spent) {
            return false;
        }
        let Some(jw) = self.jw.as_deref_mut() else {
            return false;
        };
        let nl = self.nl;
        let s = t - self.t0;
        let m = motion_at(self.st, self.rule, s, self.causality, self.ring, nl, y);
        let (aux, _) = self.st.aux.split_at_mut(self.naux);
        let (jm, wx, wm) = if self.ring.is_some() {
            (&mut jw.jm[..], &mut jw.wx[..], &mut jw.wm[..])
        } else {
            (&mut [][..], &mut [][..], &mut [][..])
        };
        if !self.level.jacobian(
            Point::new(t, &m, &y[..nl], aux),
            Jacobians {
                jx: &mut jw.jx,
                jm,
                wx,
                wm,
            },
        ) {
            return false;
        }
        // Column-major storage: entry (r, c) at c * n + r.
        let n = jac.nrows();
        let a = jac.as_mut_slice();
        let jx = &jw.jx;
        match self.level.blocks() {
            // Independent blocks ([`LevelModel::blocks`]): the structured solver reads only
            // the diagonal blocks and the border ([`crate::solver::BlockArrowhead`]), and
            // every one of those entries is written below, so the entries coupling two
            // blocks (zero by the contract of `blocks`) are neither cleared nor copied:
            // about `nl²` writes fewer per Jacobian.
            Some((nb, s)) if self.level.block_head() + nb * s <= nl => {
                // The blocks are the level's states `h .. h + nb·s`; the border, the ones
                // before and after them ([`LevelModel::block_head`]).
                let h = self.level.block_head();
                let nb0 = nb * s;
                for b in 0..nb {
                    let o = h + b * s;
                    for c in o..o + s {
                        for r in o..o + s {
                            a[c * n + r] = jx[r * nl + c];
                        }
                    }
                }
                // The level's border columns (every level row) and rows (the block columns).
                let border = (0..h).chain(h + nb0..nl);
                for c in border.clone() {
                    for r in 0..nl {
                        a[c * n + r] = jx[r * nl + c];
                    }
                }
                for r in border {
                    for c in h..h + nb0 {
                        a[c * n + r] = jx[r * nl + c];
                    }
                }
                // The ring's position rows, of which only `d q/dt = v` is set below.
                for r in nl..n - self.ring.map_or(0, |g| g.dofs.len()) {
                    for c in 0..n {
                        a[c * n + r] = 0.0;
                    }
                }
            }
            _ => {
                a.fill(0.0);
                for r in 0..nl {
                    for c in 0..nl {
                        a[c * n + r] = jx[r * nl + c];
                    }
                }
            }
        }
        if let Some(ring) = self.ring {
            let nd = ring.dofs.len();
            for (k, &d) in ring.dofs.iter().enumerate() {
                let (iq, iv) = (nl + k, nl + nd + k);
                let inv = ring.inv_inertia[d];
                for r in 0..nl {
                    a[iq * n + r] = jw.jm[r * 10 + d];
                    a[iv * n + r] = jw.jm[r * 10 + 5 + d];
                }
                a[iv * n + iq] = 1.0;
                for c in 0..nl {
                    a[c * n + iv] = jw.wx[d * nl + c] * inv;
                }
                for (k2, &d2) in ring.dofs.iter().enumerate() {
                    a[(nl + k2) * n + iv] = jw.wm[d * 10 + d2] * inv;
                    a[(nl + nd + k2) * n + iv] = jw.wm[d * 10 + 5 + d2] * inv;
                }
            }
        }
        true
    }
}

impl Sys<'_> {
    /// The integrator's right-hand side (`at_end`: [`OdeSystem::rhs_at_end`]). Inlined
    /// into the integrators' stages with [`Sys::eval_level`]; a failed evaluation is
    /// [`Sys::failed`], out of line.
    #[inline]
    fn rates(
        &mut self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        at_end: bool,
    ) -> std::result::Result<(), String> {
        if self.budget.as_mut().is_some_and(Budget::spent) {
            return Err("CPU budget spent".into());
        }
        // A trial state can be far off (a too-large trial step through a stiff contact):
        // a level that cannot evaluate there makes the step fail and shrink, not the run.
        if let Err(e) = self.eval_level(t - self.t0, y, dy, None, at_end) {
            self.failed(dy, e);
        }
        Ok(())
    }

    /// A level that could not evaluate at a trial point: NaN rates (the integrator retries
    /// with a smaller step) and the error kept as the cause to report if it gives up.
    #[cold]
    #[inline(never)]
    fn failed(&mut self, dy: &mut [f64], e: Error) {
        dy.fill(f64::NAN);
        self.last_error = Some(e);
    }
}

/// No NaN or infinity in `v`, branch-free; the outputs are checked after every step. The
/// exponent bits plus one exponent unit carry into the sign bit exactly when they are all
/// ones (NaN, inf): an OR of these sums over `v` has its top bit set exactly when some
/// value is not finite. An OR of integers vectorises to a mask, an add and an OR per
/// element (the compare of a `bool` fold took twice as many instructions on SSE2).
pub(super) fn all_finite(v: &[f64]) -> bool {
    const EXP: u64 = 0x7ff0_0000_0000_0000;
    const ONE: u64 = 1 << 52;
    let carry = v
        .iter()
        .fold(0u64, |acc, x| acc | ((x.to_bits() & EXP) + ONE));
    carry >> 63 == 0
}

/// The time an integration failure reached (for messages).
pub(super) fn e_time(e: &SolverError) -> String {
    match e {
        SolverError::TooManySteps { t, .. }
        | SolverError::StepSizeUnderflow { t, .. }
        | SolverError::Rhs { t, .. }
        | SolverError::NonFinite { t, .. }
        | SolverError::Singular { t, .. } => format!("{t} s"),
        SolverError::Invalid { .. } => "the start".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::component::{variables, Component, Scene};

    /// The shipped run-up scene (skidding, load-driven, RODAS4) at 6000 rpm.
    fn runup_scene() -> Scene {
        let text = include_str!("../../examples/scenes/7008ce-runup.toml")
            .replace("speed_rpm = 0.0", "speed_rpm = 6000.0");
        Scene::from_text(&text).unwrap()
    }

    thread_local! {
        /// Test switch: let the integrator difference `∂f/∂t` even when it is zero.
        pub(super) static FD_DFDT: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    }

    /// The shipped run-up scene (skidding, load-driven, RODAS4) at 6000 rpm: settled in 1 ms
    /// steps, then component-mode steps of 0.1 ms, with the shaft speed held or ramped
    /// (`ramp` rad/s² as its first derivative). Returns the states, the outputs and the
    /// counters, with the integrator's forward-difference `∂f/∂t` forced on (`fd`) or not.
    fn runup(
        fd: bool,
        ramp: f64,
        method: crate::component::Method,
    ) -> (Vec<f64>, Vec<f64>, crate::component::Stats) {
        FD_DFDT.with(|c| c.set(fd));
        let mut scene = runup_scene();
        scene.solver.method = method;
        let mut c = Component::new(scene).unwrap();
        if ramp != 0.0 {
            let vr = variables::by_name("shaft.omega").unwrap().vr;
            c.set_input_derivative(vr, 1, ramp).unwrap();
        }
        let mut t = 0.0;
        for h in [1e-3; 3].into_iter().chain([1e-4; 30]) {
            c.do_step(t, h).unwrap();
            t += h;
        }
        FD_DFDT.with(|c| c.set(false));
        let st = c.state();
        (st.x.clone(), st.outputs.clone(), c.stats())
    }

    /// The skidding level with its inputs held is autonomous: the integrator's forward
    /// difference `∂f/∂t` is exactly zero, so skipping it leaves every state and output
    /// bit for bit the same and saves one right-hand side per linearisation (per step of
    /// RODAS4). With the speed ramped the difference is taken (the same counts with and
    /// without the switch). ROS34PW2 (no difference) runs the same either way.
    #[test]
    fn held_inputs_skip_the_time_difference_bit_for_bit() {
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        use crate::component::Method;
        let (x_fd, o_fd, s_fd) = runup(true, 0.0, Method::Rosenbrock);
        let (x, o, s) = runup(false, 0.0, Method::Rosenbrock);
        assert_eq!(bits(&x), bits(&x_fd), "states");
        assert_eq!(bits(&o), bits(&o_fd), "outputs");
        assert!(s.jacobians > 0 && s.accepted == s_fd.accepted && s.jacobians == s_fd.jacobians);
        assert_eq!(
            s_fd.rhs - s.rhs,
            s.jacobians,
            "one difference per linearisation"
        );
        // Ramped: no skip (the same counts with and without the switch), and a trajectory
        // that sees the time term.
        let (x_fd, _, s_fd) = runup(true, 500.0, Method::Rosenbrock);
        let (xr, _, sr) = runup(false, 500.0, Method::Rosenbrock);
        assert_eq!(bits(&xr), bits(&x_fd));
        assert_eq!(sr.rhs, s_fd.rhs);
        assert_ne!(bits(&xr), bits(&x));
        // The W-method takes no difference: the zeros change nothing there either.
        let (x_fd, o_fd, s_fd) = runup(true, 0.0, Method::Ros34pw2);
        let (x, o, s) = runup(false, 0.0, Method::Ros34pw2);
        assert_eq!(bits(&x), bits(&x_fd));
        assert_eq!(bits(&o), bits(&o_fd));
        assert_eq!(s.rhs, s_fd.rhs);
    }

    /// With a block-structured level the Jacobian writes only the diagonal blocks and the
    /// border, yet every entry the block-arrowhead solver reads: a matrix full of stale
    /// values comes out equal, bit for bit, to one that started at zero on all of those
    /// entries; and the one from zero is the level's `jx` (and zero between blocks) as the
    /// whole-matrix copy gave it.
    #[test]
    fn block_jacobian_writes_every_entry_the_solver_reads() {
        let mut c = Component::new(runup_scene()).unwrap();
        for i in 0..3 {
            c.do_step(i as f64 * 1e-3, 1e-3).unwrap();
        }
        let (nb, bs) = c.level.blocks().unwrap();
        let nl = c.n_level;
        let n = c.state.x.len();
        let x = c.state.x.clone();
        let t = c.state.t;
        let mut sys = Sys {
            jw: Some(&mut c.jwork),
            level: c.level.as_mut(),
            st: &mut c.state,
            ring: c.ring.as_ref(),
            rule: c.scene.inputs.rule,
            causality: c.scene.model.causality,
            nl,
            naux: c.n_level_aux,
            t0: t,
            last_error: None,
            budget: None,
            continues: false,
            sink: None,
            carries_jac: false,
        };
        let mut zero = nalgebra::DMatrix::zeros(n, n);
        let mut stale = nalgebra::DMatrix::from_element(n, n, 7.0);
        assert!(sys.jacobian(t, &x, &mut zero) && sys.jacobian(t, &x, &mut stale));
        let jx = &sys.jw.as_ref().unwrap().jx;
        let nb0 = nb * bs;
        let mut couplings = 0;
        for r in 0..n {
            for col in 0..n {
                let (z, s) = (zero[(r, col)], stale[(r, col)]);
                if r < nb0 && col < nb0 && r / bs != col / bs {
                    assert_eq!(z, 0.0, "between blocks ({r}, {col})");
                    continue;
                }
                assert_eq!(z.to_bits(), s.to_bits(), "({r}, {col})");
                if r < nl && col < nl {
                    assert_eq!(z.to_bits(), jx[r * nl + col].to_bits());
                }
                couplings += usize::from(z != 0.0 && (r >= nl || col >= nl));
            }
        }
        assert!(couplings > 0, "the ring's rows and columns are filled");
    }

    /// `all_finite` refuses exactly NaN and the infinities, wherever they sit.
    #[test]
    fn all_finite_refuses_exactly_nan_and_inf() {
        let finite = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            5e-324,
        ];
        assert!(all_finite(&finite) && all_finite(&[]));
        for bad in [f64::NAN, -f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for at in 0..=finite.len() {
                let mut v = finite.to_vec();
                v.insert(at, bad);
                assert!(!all_finite(&v), "{bad} at {at}");
            }
        }
    }

    /// Cheap evaluations stretch the gap between clock reads, and the next step's budget
    /// starts with that gap (one clock read for a short step); a spent budget still stops
    /// at the first read after the limit.
    #[test]
    fn budget_reads_the_clock_by_the_last_gap_and_still_stops() {
        let mut b = Budget::new(1e3, 1);
        assert_eq!(b.next, 1);
        for _ in 0..BUDGET_EVERY {
            assert!(!b.spent());
        }
        assert!(b.gap > 1, "cheap evaluations widen the gap: {}", b.gap);
        let next = Budget::new(1e3, b.gap);
        assert_eq!(next.next, b.gap);
        assert_eq!(Budget::new(1e3, 0).next, 1);
        // A step of fewer evaluations than its gap reads no CPU clock (a system call of
        // 0.2-0.5 us, as much as a cheap step).
        let mut short = Budget::new(1e3, 8);
        for _ in 0..7 {
            assert!(!short.spent());
        }
        assert!(
            short.first.is_none(),
            "no CPU clock read before the first check"
        );
        assert!(!short.spent());
        assert!(short.first.is_some(), "the first check reads it");
        let mut tiny = Budget::new(0.0, BUDGET_EVERY);
        let spin = thread_cpu_s();
        while thread_cpu_s() - spin < 1e-4 {}
        let stopped = (0..BUDGET_EVERY).position(|_| tiny.spent());
        assert_eq!(stopped, Some(BUDGET_EVERY as usize - 1));
    }
}
