//! Counters in one place (as rapier keeps its counters in their own folder): the
//! integrators' work ([`IntegratorStats`], `solver::Stats`), the component's cost summary
//! built from it ([`Stats`], `component::Stats`, the shape the C ABI's `RacewayStats`
//! mirrors), and per-stage CPU timers ([`Stages`]) read from the thread CPU clock
//! ([`thread_cpu_s`]).
//!
//! Timers cost nothing when off (the default): a stage's start returns `None` without
//! reading the clock and its stop ignores `None`. Turned on
//! (`Component::set_stage_timing(true)`), each stage costs two clock reads
//! (`clock_gettime(CLOCK_THREAD_CPUTIME_ID)`, a system call of a few hundred ns).

/// CPU time consumed by the calling thread, s (`CLOCK_THREAD_CPUTIME_ID`, POSIX): unlike a
/// wall clock it does not count time the thread waits while other processes hold the
/// cores, so it is the figure every "CPU" timing in the project reports. Differences
/// between two calls on the same thread are meaningful; the origin is arbitrary. Returns
/// NaN where the clock is not available (non-Unix), so a timing is never silently a wall
/// clock.
pub fn thread_cpu_s() -> f64 {
    #[cfg(unix)]
    {
        let mut ts = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `ts` is a valid, writable timespec for the duration of the call.
        let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
        if rc == 0 {
            return ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64;
        }
        f64::NAN
    }
    #[cfg(not(unix))]
    {
        f64::NAN
    }
}

/// Work counters of an integrator; they accumulate across calls (reset with
/// `IntegratorStats::default()`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct IntegratorStats {
    /// Right-hand side evaluations (including those for finite-difference Jacobians).
    pub rhs_evals: u64,
    /// Jacobian evaluations (analytic or finite-difference).
    pub jac_evals: u64,
    /// LU factorisations.
    pub lu_decomps: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected step attempts (error test failed, non-finite value, singular matrix).
    pub rejected: u64,
    /// DOPRI5 only: how often Hairer's stiffness test fired (15 tests in a row with
    /// `h·|λ| > 3.25`, see `solver::Dopri5`).
    pub stiff_alarms: u64,
}

/// Cost counters of a component's internal integration (the C ABI's `RacewayStats`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Right-hand-side evaluations.
    pub rhs: u64,
    /// Jacobian evaluations.
    pub jacobians: u64,
    /// LU factorisations.
    pub factorizations: u64,
    /// Accepted internal steps.
    pub accepted: u64,
    /// Rejected internal steps.
    pub rejected: u64,
}

impl From<&IntegratorStats> for Stats {
    fn from(s: &IntegratorStats) -> Self {
        Stats {
            rhs: s.rhs_evals,
            jacobians: s.jac_evals,
            factorizations: s.lu_decomps,
            accepted: s.accepted,
            rejected: s.rejected,
        }
    }
}

/// Thread CPU time spent in one stage and how often it ran.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Timer {
    /// Times the stage ran while timing was on.
    pub calls: u64,
    /// Thread CPU time spent in it, s.
    pub cpu_s: f64,
}

impl Timer {
    /// Mean CPU time per call, s (0 before the first).
    pub fn mean_s(&self) -> f64 {
        if self.calls == 0 {
            0.0
        } else {
            self.cpu_s / self.calls as f64
        }
    }
}

/// The stages of a component's `do_step`, each with its CPU timer.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Stages {
    /// Timing on (off by default: then nothing reads the clock).
    pub enabled: bool,
    /// Input checks and the transaction's state copy.
    pub inputs: Timer,
    /// The integration of the states over the step.
    pub integrate: Timer,
    /// The outputs at the communication point (forces, K, C; their time derivatives are computed when first read).
    pub outputs: Timer,
}

impl Stages {
    /// Start timing a stage: the clock when timing is on, else `None` (no clock read).
    #[inline]
    pub fn start(&self) -> Option<f64> {
        if self.enabled {
            Some(thread_cpu_s())
        } else {
            None
        }
    }

    /// Stop timing: add the CPU time since `started` (from [`Stages::start`]) to `timer`.
    #[inline]
    pub fn stop(timer: &mut Timer, started: Option<f64>) {
        if let Some(t0) = started {
            timer.calls += 1;
            timer.cpu_s += thread_cpu_s() - t0;
        }
    }

    /// One line: each stage's mean CPU time per call and share.
    pub fn summary(&self) -> String {
        let total = self.inputs.cpu_s + self.integrate.cpu_s + self.outputs.cpu_s;
        let part = |name: &str, t: &Timer| {
            format!(
                "{name} {:.2} µs ({:.0} %)",
                1e6 * t.mean_s(),
                100.0 * t.cpu_s / total.max(f64::MIN_POSITIVE)
            )
        };
        format!(
            "per do_step, thread CPU: {}, {}, {}",
            part("inputs", &self.inputs),
            part("integrate", &self.integrate),
            part("outputs", &self.outputs)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timers_off_read_no_clock_and_on_accumulate_cpu_time() {
        let mut s = Stages::default();
        assert_eq!(s.start(), None);
        let off = s.start();
        Stages::stop(&mut s.integrate, off);
        assert_eq!(s.integrate, Timer::default());
        s.enabled = true;
        let t0 = s.start();
        // Burn some CPU: the thread clock must see it.
        let mut x = 0.0f64;
        for i in 0..200_000 {
            x += (i as f64).sqrt();
        }
        assert!(x > 0.0);
        Stages::stop(&mut s.integrate, t0);
        assert_eq!(s.integrate.calls, 1);
        assert!(s.integrate.cpu_s > 0.0 && s.integrate.cpu_s < 10.0);
    }

    #[test]
    fn component_stats_are_the_integrator_counters() {
        let w = IntegratorStats {
            rhs_evals: 7,
            jac_evals: 2,
            lu_decomps: 3,
            accepted: 4,
            rejected: 1,
            stiff_alarms: 5,
        };
        let s = Stats::from(&w);
        assert_eq!((s.rhs, s.jacobians, s.factorizations), (7, 2, 3));
        assert_eq!((s.accepted, s.rejected), (4, 1));
    }
}
