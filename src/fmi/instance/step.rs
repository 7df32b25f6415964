//! The step phase of an FMU instance: `DoStep` against the component, with the
//! communication-point tolerance (docs/physics.md §C4).

use super::*;

impl Instance {
    /// `DoStep` from `t` over `h`. On failure the state is unchanged; the flag says whether
    /// it was numerical (a failed integration: FMI 3 Discard) rather than an error.
    pub(crate) fn do_step(&mut self, t: f64, h: f64) -> Result<Status, (bool, Fail)> {
        let err = |m: String| (false, Fail::from(m));
        if !t.is_finite() {
            return Err(err(format!("communication point t = {t}: must be finite")));
        }
        if !(h.is_finite() && h > 0.0) {
            return Err(err(format!(
                "communication step size h = {h}: must be finite and > 0"
            )));
        }
        let tc = self.time;
        let mismatch = (t - tc).abs();
        // Relative tolerance on the communication point (docs/physics.md §C4 #9): a mismatch within
        // 1e-6 of the step (or 1e-12 of the time) re-syncs to the FMU's time and lands on
        // t + h; rounding noise (a few ulps) passes silently, more is a warning.
        let tol = (1e-6 * h).max(1e-12 * tc.abs());
        let mut status = Status::Ok;
        let (t0, h0) = if mismatch == 0.0 {
            (t, h)
        } else if mismatch <= tol && t + h > tc {
            if mismatch > 8.0 * f64::EPSILON * tc.abs().max(t.abs()) {
                self.log(
                    Status::Warning,
                    &format!(
                        "fmiDoStep: communication point t = {t} differs from the FMU's time \
                         {tc} by {mismatch:e} s (within the tolerance {tol:e} s): stepping \
                         from {tc} to t + h"
                    ),
                );
                status = Status::Warning;
            }
            (tc, (t + h) - tc)
        } else {
            return Err(err(format!(
                "communication point t = {t} but the FMU is at {tc} (tolerance {tol:e} s); \
                 time must not jump or run backwards (use SetFMUstate to go back)"
            )));
        };
        if let Some(stop) = self.stop_time {
            if t0 + h0 > stop + 1e-9 * h0.max(stop.abs() * 1e-3) {
                return Err(err(format!(
                    "t + h = {} is beyond stopTime = {stop}",
                    t0 + h0
                )));
            }
        }
        let c = self.component().map_err(|f| (false, f))?;
        match c.do_step(t0, h0) {
            Ok(()) => {
                self.time = c.time();
                Ok(status)
            }
            Err(e) => {
                let numerical = matches!(
                    e,
                    crate::Error::StepFailed { .. }
                        | crate::Error::NotConverged { .. }
                        | crate::Error::Budget { .. }
                );
                Err((numerical, Fail::from(e)))
            }
        }
    }
}
