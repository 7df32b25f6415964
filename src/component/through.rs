//! A window integrated straight through: the scene's integrator takes its own steps over
//! many communication intervals, and the outputs at every communication point come from its
//! dense output (for a stand-alone user who holds the inputs over the window; a host that
//! couples the component steps it with `do_step`).

use super::system::{Sink, Sys, WRENCH_CHUNK};
use super::{index_of, variables, Component, State, I_FORCE};
use crate::error::{Error, Result};

/// Most values (states or variables per point times points) one `step_through` keeps.
const MAX_VALUES: usize = 100_000_000;

/// The communication points of one `step_through` window and what is asked at them: the
/// points `t + k h` for `k = 1..=n`, and the table `slots` (index, whether an input).
#[derive(Debug, Clone, Copy)]
struct Window<'a> {
    /// The window's start, s.
    t: f64,
    /// The communication interval, s.
    h: f64,
    /// The number of intervals.
    n: usize,
    /// The values asked for at each point.
    slots: &'a [(usize, bool)],
}

impl Component {
    /// Advance from `t` over `n` communication intervals of `h` in one integration, and
    /// report the variables `vrs` at each of the `n` points `t + k h` (`k = 1..=n`): `out`
    /// is replaced by `n` rows of `vrs.len()` values.
    ///
    /// - The inputs are those set now, moved along the scene's input rule from `t` as one
    ///   step of `n h` moves them (held under the default rule): a stand-alone run, not a
    ///   coupling (a host that sets inputs at every point steps with [`Component::do_step`]).
    /// - The integrator steps as its error control decides (not stopped at the points);
    ///   the states at the points inside the window come from its dense output (DOPRI5: 4th
    ///   order, RODAS4: 3rd order), and the outputs there are the level's outputs at those
    ///   states and the inputs at that time, as a stop there would compute them from the
    ///   same states. The last point is the integration's end: the component is left at
    ///   `t + n h` exactly as `do_step(t, n h)` leaves it (same bits).
    /// - Asked only for forces and moments (and inputs), the points inside the window take
    ///   the level's wrench from its right-hand side at the interpolated state, not its full
    ///   outputs (stiffness and damping matrices, diagnostics), when at the last point that
    ///   wrench equals the outputs' bit for bit in every slot asked for; otherwise (or when
    ///   anything else is asked for) the full outputs at every point.
    /// - Inputs read back give their value as set (as [`Component::get_real`] does).
    /// - The step budgets (`solver.max_substeps`, `solver.max_step_cpu_s`) count per
    ///   communication interval: the window may use `n` times them.
    /// - Refused, naming the cause, and leaving everything as it was: a level that keeps
    ///   memory it updates at every communication point (warm starts, wear maps, thermal
    ///   state: outputs between stops would need those updates), the ROS34PW2 integrator
    ///   (no dense output), `n = 0` or a window keeping more than 1e8 values (states or
    ///   variables per point times `n`), a value reference not in the table, or the checks
    ///   of `do_step(t, n h)`. A failed integration leaves everything as it was too.
    pub fn step_through(
        &mut self,
        t: f64,
        h: f64,
        n: usize,
        vrs: &[u32],
        out: &mut Vec<f64>,
    ) -> Result<()> {
        const CALL: &str = "step_through";
        if n == 0 || n > u32::MAX as usize {
            return Err(Error::invalid(
                "n",
                n,
                format!("1 to {} communication intervals", u32::MAX),
            ));
        }
        if self.n_level_aux > 0 {
            return Err(Error::invalid(
                "model.level",
                self.scene.model.level.name(),
                "a level without memory it updates at communication points for step_through \
                 (this one keeps warm starts, wear maps or a thermal state: step it with \
                 do_step)",
            ));
        }
        let stiff = self.scene.model.level.entry().stiff;
        let method = self.scene.solver.method.resolve(stiff);
        if !method.dense_output {
            return Err(Error::invalid(
                "solver.method",
                method.name,
                format!(
                    "{} for step_through ({} has no dense output)",
                    crate::solver::methods::with_dense_output(),
                    method.name
                ),
            ));
        }
        let mut slots = Vec::with_capacity(vrs.len());
        for &vr in vrs {
            let (Some(v), Some(i)) = (variables::by_vr(vr), index_of(vr)) else {
                return Err(Error::invalid(
                    "value reference",
                    vr,
                    "a variable of the table",
                ));
            };
            slots.push((i, v.is_input(self.causality())));
        }
        // The states and values kept for the points (one allocation each, of this size).
        let dim = self.state.x.len();
        if n.saturating_mul(dim.max(slots.len()).max(1)) > MAX_VALUES {
            return Err(Error::invalid(
                "n",
                n,
                format!(
                    "at most {MAX_VALUES} values ({} states or {} variables per point) per step_through call: split the window",
                    dim,
                    slots.len()
                ),
            ));
        }
        let span = n as f64 * h;
        if !(h.is_finite() && h > 0.0) {
            return Err(Error::invalid("h", h, "a finite step > 0"));
        }
        self.check_step_call(CALL, t, span)?;
        let rule = self.scene.inputs.rule;
        let continuing = self.work.fsal_matches(&self.state, self.n_level_aux, rule);
        if !continuing {
            self.check_inputs_at(span)?;
        }
        self.scratch.clone_from(&self.state);
        let mut sc = std::mem::take(&mut self.scratch);
        sc.t = t;
        let mut rows = Vec::with_capacity(n * slots.len());
        let win = Window {
            t,
            h,
            n,
            slots: &slots,
        };
        let r = self.through(&mut sc, &win, continuing, &mut rows);
        if r.is_ok() {
            *out = rows;
        }
        self.finish_step(sc, r, t, t + span)
    }

    /// Integrate `sc` (at the window start `t`) over the window `win`, then fill `rows`
    /// with the values of `slots` at the `n` points; `sc` is left as `do_step(t, n h)`
    /// leaves its scratch state.
    fn through(
        &mut self,
        sc: &mut State,
        win: &Window<'_>,
        continuing: bool,
        rows: &mut Vec<f64>,
    ) -> Result<()> {
        let Window { t, h, n, slots } = *win;
        let dim = sc.x.len();
        let span = n as f64 * h;
        let x0 = sc.x.clone();
        let mut sink = Sink {
            t0: t,
            h,
            n,
            next: 1,
            xs: vec![0.0; (n - 1) * dim],
            dim,
            error: None,
        };
        if dim > 0 && self.ring.is_none() && self.level.states_are_quadrature() {
            // States that are a quadrature of the inputs: the quadrature from the window
            // start to each point (exact for the inputs' time dependence, as the one over the
            // window is).
            for k in 1..n {
                sc.x.copy_from_slice(&x0);
                self.quadrature(sc, k as f64 * h)?;
                sink.xs[(k - 1) * dim..k * dim].copy_from_slice(&sc.x);
            }
            sc.x.copy_from_slice(&x0);
            self.integrate_window(sc, span, continuing, None, n as u32)?;
        } else if dim > 0 {
            self.integrate_window(sc, span, continuing, Some(&mut sink), n as u32)?;
            if let Some(e) = sink.error.take() {
                return Err(e.into());
            }
            if sink.next != n {
                return Err(Error::StepFailed {
                    t: sink.time(sink.next),
                    reason: "the integration passed a communication point without its dense \
                             output"
                        .into(),
                });
            }
        }
        // The last point first: the outputs `do_step(t, n h)` leaves.
        self.compute_outputs(sc, span, false)?;
        let last: Vec<f64> = slots.iter().map(|&s| value(sc, s)).collect();
        // Only forces and moments (and inputs) asked for: the level's wrench where the
        // right-hand side gives it, without the rest of the outputs (stiffness and damping
        // matrices, diagnostics) — when, at the last point, that wrench is the outputs'
        // one bit for bit in every slot asked for (a level whose outputs report a wrench
        // its right-hand side does not, e.g. a component it leaves to zero, takes the full
        // outputs at every point).
        let forces_only = n > 1
            && slots
                .iter()
                .all(|&(i, input)| input || (I_FORCE..I_FORCE + 5).contains(&i))
            && {
                let w = self.wrench_at(sc, t, span, &sc.x.clone())?;
                slots
                    .iter()
                    .zip(&last)
                    .all(|(&(i, input), v)| input || w[i - I_FORCE].to_bits() == v.to_bits())
            };
        if forces_only {
            self.forces_inside(sc, win, &sink.xs, rows)?;
        } else if n > 1 {
            let x_end = sc.x.clone();
            for k in 1..n {
                sc.x.copy_from_slice(&sink.xs[(k - 1) * dim..k * dim]);
                self.compute_outputs(sc, k as f64 * h, false)?;
                rows.extend(slots.iter().map(|&s| value(sc, s)));
            }
            sc.x.copy_from_slice(&x_end);
            self.compute_outputs(sc, span, false)?;
        }
        rows.extend(last);
        Ok(())
    }

    /// The values of `slots` at the points `1..n` inside the window `win` from `t0`
    /// (states `xs`, one row each), appended to `rows`: the inputs as set and the level's
    /// wrench ([`wrench`]). One system serves every point (the per-point work is the
    /// level's).
    fn forces_inside(
        &mut self,
        sc: &mut State,
        win: &Window<'_>,
        xs: &[f64],
        rows: &mut Vec<f64>,
    ) -> Result<()> {
        let Window { t: t0, h, n, slots } = *win;
        let dim = sc.x.len();
        let (mut sys, dy) = self.sys_at(sc, t0);
        let chunk = WRENCH_CHUNK.min(n - 1);
        let (mut s, mut w) = (Vec::with_capacity(chunk), Vec::with_capacity(chunk));
        let (mut ms, mut ts) = (Vec::with_capacity(chunk), Vec::with_capacity(chunk));
        let mut k0 = 1;
        while k0 < n {
            let m = (n - k0).min(chunk);
            s.clear();
            s.extend((k0..k0 + m).map(|k| k as f64 * h));
            let rows_x = &xs[(k0 - 1) * dim..(k0 - 1 + m) * dim];
            sys.wrenches(&s, rows_x, dim, dy, (&mut ms, &mut ts), &mut w)?;
            for (w, &s) in w.iter().zip(&s) {
                finite_wrench(&sys, s, w)?;
                for &(i, input) in slots {
                    rows.push(if input {
                        sys.st.inputs[i]
                    } else {
                        w[i - I_FORCE]
                    });
                }
            }
            k0 += m;
        }
        Ok(())
    }

    /// The level's wrench at `s` after the window start `t0` with states `x` ([`wrench`]).
    fn wrench_at(&mut self, sc: &mut State, t0: f64, s: f64, x: &[f64]) -> Result<[f64; 5]> {
        let (mut sys, dy) = self.sys_at(sc, t0);
        wrench(&mut sys, dy, s, x)
    }

    /// The system of the window from `t0` for evaluations outside an integration (no
    /// budget, Jacobian or sink), and the work vector its rates go to.
    fn sys_at<'a>(&'a mut self, sc: &'a mut State, t0: f64) -> (Sys<'a>, &'a mut [f64]) {
        let sys = Sys {
            jw: None,
            level: self.level.as_mut(),
            st: sc,
            ring: self.ring.as_ref(),
            rule: self.scene.inputs.rule,
            causality: self.scene.model.causality,
            nl: self.n_level,
            naux: self.n_level_aux,
            t0,
            last_error: None,
            budget: None,
            continues: false,
            sink: None,
            carries_jac: false,
        };
        (sys, &mut self.work.k[0])
    }
}

/// The level's wrench at `s` after the start of `sys` with states `x` (the right-hand
/// side's, as the integration evaluates it; its rates go to `dy`); refused when not
/// finite.
fn wrench(sys: &mut Sys<'_>, dy: &mut [f64], s: f64, x: &[f64]) -> Result<[f64; 5]> {
    let mut w = [0.0; 5];
    sys.wrench(s, x, dy, &mut w)?;
    finite_wrench(sys, s, &w)?;
    Ok(w)
}

/// The wrench `w` at `s` after the start of `sys`, refused when not finite.
fn finite_wrench(sys: &Sys<'_>, s: f64, w: &[f64; 5]) -> Result<()> {
    if !w.iter().all(|v| v.is_finite()) {
        return Err(Error::StepFailed {
            t: sys.t0 + s,
            reason: "non-finite force".into(),
        });
    }
    Ok(())
}

/// The value of table slot `i` in `sc`: the input as set, or the output.
fn value(sc: &State, (i, input): (usize, bool)) -> f64 {
    if input {
        sc.inputs[i]
    } else {
        sc.outputs[i]
    }
}
