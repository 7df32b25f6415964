//! The system a step integrates, as the integrators see it ([`OdeSystem`]): the level's
//! states and, load-driven, the inner ring's, with the step's CPU budget and the
//! preallocated work space.

use super::inputs::{input_at, motion_at};
use super::level::{Jacobians, LevelModel, Point};
use super::{thread_cpu_s, Causality, InputRule, State, I_LOAD, I_V};
use crate::error::{Error, Result};
use crate::solver::{OdeSystem, SolverError};
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
    /// CPU time used when the budget ran out.
    pub(super) spent: Option<f64>,
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

    /// CPU time used since the start, s (see the type's notes).
    fn used(&mut self) -> f64 {
        match self.first {
            Some((cpu1, wall1)) => wall1 + (thread_cpu_s() - cpu1),
            None => {
                let wall1 = self.wall0.elapsed().as_secs_f64();
                self.first = Some((thread_cpu_s(), wall1));
                wall1
            }
        }
    }

    /// Count one evaluation; `true` once the budget is spent. The clock is read about
    /// every [`BUDGET_READ_S`] of CPU time as estimated from the evaluations so far (and
    /// from the last step's before the first read), and at least every [`BUDGET_EVERY`]
    /// evaluations.
    pub(super) fn spent(&mut self) -> bool {
        if self.spent.is_some() {
            return true;
        }
        self.evals = self.evals.saturating_add(1);
        if self.evals >= self.next {
            let used = self.used();
            if used > self.limit {
                self.spent = Some(used);
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
        }
        false
    }
}

/// The inner ring as a body (load-driven causality).
#[derive(Debug, Clone)]
pub(super) struct RingBody {
    /// Coordinates integrated (indices into q).
    pub(super) dofs: &'static [usize],
    /// Mass (translations) or transverse inertia (tilts) per coordinate of `q`.
    pub(super) inertia: [f64; 5],
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
    /// inputs and the level's memory (`inputs | aux[..n_level_aux]`), when `fsal` is set
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
        let ni = st.inputs.len();
        let k = &self.fsal_key;
        same_bits(&k[..ni], &st.inputs)
            && same_bits(&k[ni..], &st.aux[..naux])
            && inputs_constant(st, rule)
    }

    /// After a successful integration of `st`: remember what its last stage read, if the
    /// next step may start from it (`reusable`: the level's rates do not depend on time,
    /// [`super::level::LevelModel::rhs_time_invariant`]; and the inputs did not move
    /// inside the step, so the last stage saw them as the next step's first will).
    pub(super) fn fsal_store(&mut self, st: &State, naux: usize, rule: InputRule, reusable: bool) {
        self.fsal = reusable && inputs_constant(st, rule);
        if self.fsal {
            let ni = st.inputs.len();
            let k = &mut self.fsal_key;
            k[..ni].copy_from_slice(&st.inputs);
            k[ni..].copy_from_slice(&st.aux[..naux]);
        }
    }
}

/// `a` and `b` bit for bit (a branch-free OR of the XORs, which the compiler vectorises).
fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .fold(0u64, |d, (x, y)| d | (x.to_bits() ^ y.to_bits()))
            == 0
}

/// Whether every input keeps its value through a step under `rule` ([`input_at`] gives
/// the same bits at every offset): always when held; with velocities, when the velocity
/// inputs are zero; with derivatives, when every derivative is zero.
pub(super) fn inputs_constant(st: &State, rule: InputRule) -> bool {
    match rule {
        InputRule::Hold => true,
        InputRule::Velocity => st.inputs[I_V..I_V + 5].iter().all(|v| *v == 0.0),
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
}

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

    /// [`Sys::eval`]; `at_end`: through [`LevelModel::rhs_at_end`] (the last stage of a
    /// step landing on the end of the integration, where the outputs are evaluated next).
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
                for (k, &d) in ring.dofs.iter().enumerate() {
                    let load = input_at(self.st, I_LOAD + d, s, self.rule);
                    dy[nl + k] = y[nl + nd + k];
                    dy[nl + nd + k] = (w[d] + load) / ring.inertia[d];
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
        jac.fill(0.0);
        for r in 0..nl {
            for c in 0..nl {
                jac[(r, c)] = jw.jx[r * nl + c];
            }
        }
        if let Some(ring) = self.ring {
            let nd = ring.dofs.len();
            for (k, &d) in ring.dofs.iter().enumerate() {
                let (iq, iv) = (nl + k, nl + nd + k);
                let inv = 1.0 / ring.inertia[d];
                for r in 0..nl {
                    jac[(r, iq)] = jw.jm[r * 10 + d];
                    jac[(r, iv)] = jw.jm[r * 10 + 5 + d];
                }
                jac[(iq, iv)] = 1.0;
                for c in 0..nl {
                    jac[(iv, c)] = jw.wx[d * nl + c] * inv;
                }
                for (k2, &d2) in ring.dofs.iter().enumerate() {
                    jac[(iv, nl + k2)] = jw.wm[d * 10 + d2] * inv;
                    jac[(iv, nl + nd + k2)] = jw.wm[d * 10 + 5 + d2] * inv;
                }
            }
        }
        true
    }
}

impl Sys<'_> {
    /// The integrator's right-hand side (`at_end`: [`OdeSystem::rhs_at_end`]).
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
            dy.fill(f64::NAN);
            self.last_error = Some(e);
        }
        Ok(())
    }
}

/// No NaN or infinity in `v`: a branch-free OR over the exponent bits (all ones for NaN
/// and inf), which the compiler vectorises; the outputs are checked after every step.
pub(super) fn all_finite(v: &[f64]) -> bool {
    const EXP: u64 = 0x7ff0_0000_0000_0000;
    !v.iter()
        .fold(false, |bad, x| bad | (x.to_bits() & EXP == EXP))
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
