//! A step: the transaction around the integration (scratch state, swap on success), the
//! integration or quadrature of the states, and the outputs with their time derivatives.

use super::inputs::{input_at, motion_at};
use super::level::{LevelOutputs, Point};
use super::system::{all_finite, e_time, Budget, Sink, Sys};
use super::{
    Component, InputRule, State, I_C, I_CAGE, I_CAGE_OMEGA, I_DIAG, I_FORCE, I_K, I_LOAD, I_Q,
    I_RATING, I_ROWS, I_TORQUE, I_V, T_MAX,
};
use crate::error::{Error, Result};
use crate::solver::SolverError;

/// Time offset of the central difference that gives output derivatives, s.
const DT_DERIV: f64 = 1e-7;

impl Component {
    /// Evaluate the outputs at the current time and inputs (for hosts that read outputs
    /// before the first step, e.g. in FMI initialisation mode). On error nothing changes.
    pub fn refresh_outputs(&mut self) -> Result<()> {
        self.scratch.clone_from(&self.state);
        let mut sc = std::mem::take(&mut self.scratch);
        let r = self.compute_outputs(&mut sc, 0.0, false);
        if r.is_ok() {
            sc.outputs_stale = false;
            std::mem::swap(&mut self.state, &mut sc);
        }
        self.scratch = sc;
        r
    }

    /// Advance from `t` to `t + h`, sub-stepping inside. On error the state is unchanged
    /// and the message says why.
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<()> {
        self.check_step_call("do_step", t, h)?;
        let clock = self.stages.start();
        // The last step's last stage is this step's first when nothing it read changed
        // (then the inputs, constant and as the last step checked them, pass again).
        let rule = self.scene.inputs.rule;
        let continuing = self.work.fsal_matches(&self.state, self.n_level_aux, rule);
        if !continuing {
            self.check_inputs_at(h)?;
        }
        // The inputs' derivatives are read (and copied) only under the rule that moves
        // inputs along them.
        self.scratch
            .begin_step_from(&self.state, rule == InputRule::Derivatives);
        let mut sc = std::mem::take(&mut self.scratch);
        // The host owns time: re-sync to its communication point (within the tolerance).
        sc.t = t;
        super::Stages::stop(&mut self.stages.inputs, clock);
        let clock = self.stages.start();
        let r = self.integrate(&mut sc, h, continuing);
        super::Stages::stop(&mut self.stages.integrate, clock);
        let clock = self.stages.start();
        let r = r.and_then(|_| self.compute_outputs(&mut sc, h, true));
        super::Stages::stop(&mut self.stages.outputs, clock);
        self.finish_step(sc, r, t, t + h)
    }

    /// The end of a step's transaction (`do_step`, `step_through`): the scratch state `sc`,
    /// integrated from `t` and with its outputs, becomes the state at `t_end` when `r` is
    /// ok, else the state stays as it was; `sc` goes back to scratch either way. An error
    /// that is not already a step failure or a budget refusal is reported as the failure
    /// of the step at `t`.
    #[inline]
    pub(super) fn finish_step(
        &mut self,
        mut sc: State,
        r: Result<()>,
        t: f64,
        t_end: f64,
    ) -> Result<()> {
        if r.is_ok() {
            sc.t = t_end;
            sc.started = true;
            sc.outputs_stale = false;
            self.state.commit_step(&mut sc);
        }
        self.scratch = sc;
        r.map_err(|e| match e {
            Error::StepFailed { .. } | Error::Budget { .. } => e,
            other => Error::StepFailed {
                t,
                reason: other.to_string(),
            },
        })
    }

    /// The checks of a step from `t` over `h` (`call` names the caller): a finite step
    /// within [`T_MAX`] that advances time, from the component's own time.
    pub(super) fn check_step_call(&self, call: &'static str, t: f64, h: f64) -> Result<()> {
        if !(h.is_finite() && h > 0.0 && h <= T_MAX) {
            return Err(Error::invalid(
                "h",
                h,
                format!("a finite step > 0 and <= {T_MAX:e} s"),
            ));
        }
        if !(t.is_finite() && t.abs() + h <= T_MAX) {
            return Err(Error::invalid(
                "t",
                t,
                format!("a finite time with |t| + h <= {T_MAX:e} s (h = {h} s)"),
            ));
        }
        // The step must advance time by h as a double can tell (to 1 ppm): from t = 1e15 s
        // a step of 1e-4 s would otherwise leave time where it was.
        if ((t + h) - t - h).abs() > 1e-6 * h {
            let least = 1e6 * f64::EPSILON * (t.abs() + h);
            return Err(Error::invalid(
                "h",
                h,
                format!(
                    "at least {least:.3e} s at t = {t} s (t + h must differ from t by h to 1 ppm)"
                ),
            ));
        }
        // An absolute bound on the mismatch (not one that grows with h: a step of 1e10 s
        // must not excuse a jump of 5 s).
        let tol = 1e-9 * (1.0 + self.state.t.abs());
        if self.state.started && (t - self.state.t).abs() > tol {
            return Err(Error::CallOrder {
                call,
                reason: format!(
                    "t = {t} s but the component is at {} s (time must not jump or run backwards)",
                    self.state.t
                ),
            });
        }
        Ok(())
    }

    /// Integrate the states of `sc` over `h` with the scene's integrator; `sc.t` is the
    /// step start. The step-size memory lives in the last `aux` slot. `continuing`: the
    /// right-hand side is the one the last integration ended with ([`Work::fsal_matches`]).
    ///
    /// [`Work::fsal_matches`]: super::system::Work::fsal_matches
    pub(super) fn integrate(&mut self, sc: &mut State, h: f64, continuing: bool) -> Result<()> {
        self.integrate_window(sc, h, continuing, None, 1)
    }

    /// [`Component::integrate`] over a window of `windows` communication intervals (the
    /// step budgets, `solver.max_substeps` and `solver.max_step_cpu_s`, scale with it),
    /// sampling the states at the window's inner communication points into `sink`.
    pub(super) fn integrate_window(
        &mut self,
        sc: &mut State,
        h: f64,
        continuing: bool,
        sink: Option<&mut Sink>,
        windows: u32,
    ) -> Result<()> {
        self.work.fsal = false;
        let n = sc.x.len();
        if n == 0 {
            return Ok(());
        }
        if self.ring.is_none() && self.level.states_are_quadrature() {
            return self.quadrature(sc, h);
        }
        let t0 = sc.t;
        let naux = self.n_level_aux;
        let mut h_trial = sc.aux[naux];
        self.work.y.copy_from_slice(&sc.x);
        let mut sys = Sys {
            jw: Some(&mut self.jwork),
            level: self.level.as_mut(),
            st: sc,
            ring: self.ring.as_ref(),
            rule: self.scene.inputs.rule,
            causality: self.scene.model.causality,
            nl: self.n_level,
            naux,
            t0,
            last_error: None,
            budget: Some(Budget::new(
                self.scene.solver.max_step_cpu_s * windows as f64,
                self.budget_gap,
            )),
            continues: continuing,
            sink,
            carries_jac: !self
                .state_shared
                .swap(false, std::sync::atomic::Ordering::Relaxed),
        };
        let max_steps = self.opts.max_steps;
        self.opts.max_steps = max_steps.saturating_mul(windows as u64);
        let r = self.integrator.integrate(
            &mut sys,
            t0,
            t0 + h,
            &mut self.work.y,
            &mut h_trial,
            &self.opts,
        );
        self.opts.max_steps = max_steps;
        if let Some(b) = &sys.budget {
            self.budget_gap = b.gap;
        }
        if let Err(e) = r {
            if let Some((wall, cpu)) = sys.budget.and_then(|b| b.spent) {
                return Err(Error::Budget {
                    t: t0,
                    field: "solver.max_step_cpu_s",
                    limit: format!("{} s", self.scene.solver.max_step_cpu_s),
                    used: format!(
                        "{cpu:.3e} s of thread CPU time after the step's first CPU-clock \
                         read plus {wall:.3e} s of wall time before it (counted whole, an upper \
                         bound of the CPU time then), reaching t = {}",
                        e_time(&e)
                    ),
                });
            }
            let hint = match e {
                SolverError::TooManySteps { t, max_steps } => {
                    return Err(Error::Budget {
                        t: t0,
                        field: "solver.max_substeps",
                        limit: format!("{max_steps} sub-steps"),
                        used: format!("all of them, reaching t = {t} s of t = {} s", t0 + h),
                    });
                }
                _ => sys
                    .last_error
                    .map(|m| format!("; the model: {m}"))
                    .unwrap_or_default(),
            };
            return Err(Error::StepFailed {
                t: t0,
                reason: format!("{e}{hint}"),
            });
        }
        sc.x.copy_from_slice(&self.work.y);
        sc.aux[naux] = h_trial;
        let reusable = self.level.rhs_time_invariant();
        self.work
            .fsal_store(sc, naux, self.scene.inputs.rule, reusable);
        Ok(())
    }

    /// Motion-driven levels whose states are a quadrature of the inputs (the cage angle):
    /// Simpson's rule over the step, exact for the inputs' time dependence under every
    /// input rule (at most cubic in time, [`input_at`]), as the adaptive DOPRI5 step it
    /// replaces was (its quadrature weights are exact to degree 4), at 3 cheap right-hand
    /// sides instead of 7 and no step-size control (the step-size memory is left as is).
    pub(super) fn quadrature(&mut self, sc: &mut State, h: f64) -> Result<()> {
        let (nl, naux) = (self.n_level, self.n_level_aux);
        let rule = self.scene.inputs.rule;
        let causality = self.causality();
        let [k0, k1, k2] = &mut self.work.k;
        for (s, k) in [(0.0, &mut *k0), (0.5 * h, &mut *k1), (h, &mut *k2)] {
            let m = motion_at(sc, rule, s, causality, None, nl, &sc.x);
            let (aux, _) = sc.aux.split_at_mut(naux);
            self.level.rhs(
                Point::new(sc.t + s, &m, &sc.x[..nl], aux),
                &mut k[..nl],
                None,
            )?;
        }
        for j in 0..nl {
            sc.x[j] += h / 6.0 * (k0[j] + 4.0 * k1[j] + k2[j]);
        }
        Ok(())
    }

    /// Fill the outputs of `sc` at `s` after its time (`sc.x` already at that time).
    /// `defer`: the stiffness and damping may be left for their first read
    /// ([`LevelModel::outputs_deferring_matrices`], `sc.matrices_pending`).
    ///
    /// [`LevelModel::outputs_deferring_matrices`]: crate::seam::LevelModel::outputs_deferring_matrices
    pub(super) fn compute_outputs(&mut self, sc: &mut State, s: f64, defer: bool) -> Result<()> {
        let nl = self.n_level;
        let rule = self.scene.inputs.rule;
        let causality = self.causality();
        let m = motion_at(sc, rule, s, causality, self.ring.as_ref(), nl, &sc.x);
        let mut out = LevelOutputs::default();
        {
            let (aux, _) = sc.aux.split_at_mut(self.n_level_aux);
            let p = Point::new(sc.t + s, &m, &sc.x[..nl], aux);
            sc.matrices_pending = if defer {
                self.level.outputs_deferring_matrices(p, &mut out)?
            } else {
                self.level.outputs(p, &mut out)?;
                false
            };
        }
        let o = &mut sc.outputs;
        o[I_FORCE..I_FORCE + 5].copy_from_slice(&out.wrench);
        o[I_TORQUE] = out.torque;
        o[I_CAGE_OMEGA] = out.cage_omega;
        let diag = [
            out.cage_slip,
            out.balls_loaded,
            out.max_load,
            out.max_pressure,
            out.film_min,
            out.power_loss,
            out.wear_max,
        ];
        o[I_DIAG..I_DIAG + 7].copy_from_slice(&diag);
        let cage = [
            out.cage_xy[0],
            out.cage_xy[1],
            out.cage_speed,
            1.0 - out.cage_slip,
            out.pocket_force,
            out.guide_force,
        ];
        o[I_CAGE..I_CAGE + 6].copy_from_slice(&cage);
        if self.set_rows.is_empty() {
            o[I_RATING..I_RATING + 3].copy_from_slice(&self.rating.outputs(
                &self.bearing,
                &out.wrench,
                out.max_pressure,
                out.balls_loaded,
            ));
        } else {
            // A set: each row rated on its own load; the set's static safety is the
            // smallest row's, its life the rows' system life, its warnings the rows' sum.
            let (mut s0, mut warn) = (f64::INFINITY, 0.0);
            let mut lives = [(None, 0.0); super::variables::ROWS];
            for (i, (row, (b, rating))) in self.level.rows().iter().zip(&self.set_rows).enumerate()
            {
                let [s, l, w] = rating.outputs(b, &row.local, row.max_pressure, row.loaded);
                s0 = s0.min(s);
                warn += w;
                let slope = crate::models::set::weibull_slope(b.element());
                lives[i] = ((l < crate::ratings::L10_UNLOADED).then_some(l), slope);
                let at = I_ROWS + super::variables::ROW_OUTPUTS * i;
                o[at..at + 5].copy_from_slice(&row.force);
                o[at + 5] = row.contact_angle;
                o[at + 6] = f64::from(u8::from(row.loaded == 0.0));
                o[at + 7] = l;
            }
            let life = crate::models::set::system_life(&lives[..self.set_rows.len()])
                .unwrap_or(crate::ratings::L10_UNLOADED);
            o[I_RATING..I_RATING + 3].copy_from_slice(&[s0, life, warn]);
        }
        for r in 0..5 {
            o[I_K + 5 * r..I_K + 5 * r + 5].copy_from_slice(&out.k[r]);
            o[I_C + 5 * r..I_C + 5 * r + 5].copy_from_slice(&out.c[r]);
        }
        if let Some(ring) = &self.ring {
            o[I_Q..I_Q + 5].copy_from_slice(&m.q);
            o[I_V..I_V + 5].copy_from_slice(&m.v);
            for &d in ring.dofs {
                let load = input_at(sc, I_LOAD + d, s, rule);
                sc.output_derivatives[I_Q + d] = m.v[d];
                sc.output_derivatives[I_V + d] = (out.wrench[d] + load) * ring.inv_inertia[d];
            }
        }
        if !all_finite(&sc.outputs) || !all_finite(&sc.output_derivatives[..I_FORCE]) {
            return Err(Error::StepFailed {
                t: sc.t,
                reason: "non-finite output".into(),
            });
        }
        // The force derivatives (and the deferred stiffness and damping) are left for the
        // first read (three force evaluations): remember the inputs' offset they belong to.
        sc.aux[self.n_level_aux + 1] = s;
        sc.derivatives_pending = true;
        Ok(())
    }

    /// Compute the pending stiffness and damping outputs of the current state
    /// ([`State::matrices_pending`]) at the inputs' offset the outputs were computed at;
    /// the level's memory is left as it was. On error nothing changes.
    pub(super) fn compute_matrices(&mut self) -> Result<()> {
        let nl = self.n_level;
        let naux = self.n_level_aux;
        let rule = self.scene.inputs.rule;
        let causality = self.causality();
        let sc = &mut self.state;
        let s = sc.aux[naux + 1];
        let m = motion_at(sc, rule, s, causality, self.ring.as_ref(), nl, &sc.x);
        let (mut k, mut c) = ([[0.0; 5]; 5], [[0.0; 5]; 5]);
        let w = &mut self.work;
        w.aux_save.copy_from_slice(&sc.aux);
        let r = {
            let (aux, _) = sc.aux.split_at_mut(naux);
            // The state's time is the step's end, where the outputs were computed.
            let p = Point::new(sc.t, &m, &sc.x[..nl], aux);
            self.level.matrices(p, &mut k, &mut c)
        };
        sc.aux.copy_from_slice(&w.aux_save);
        r?;
        if !k.iter().chain(&c).all(|row| all_finite(row)) {
            return Err(Error::StepFailed {
                t: sc.t,
                reason: "non-finite stiffness or damping".into(),
            });
        }
        for r in 0..5 {
            sc.outputs[I_K + 5 * r..I_K + 5 * r + 5].copy_from_slice(&k[r]);
            sc.outputs[I_C + 5 * r..I_C + 5 * r + 5].copy_from_slice(&c[r]);
        }
        sc.matrices_pending = false;
        Ok(())
    }

    /// Compute the pending force and moment time derivatives of the current state: dF/dt
    /// by a central difference in time along the inputs' rule and the states' rates, at
    /// the inputs' offset the outputs were computed at; the level's memory (warm starts)
    /// is restored afterwards. On error nothing changes.
    pub(super) fn compute_force_derivatives(&mut self) -> Result<()> {
        let nl = self.n_level;
        let naux = self.n_level_aux;
        let rule = self.scene.inputs.rule;
        let causality = self.causality();
        let sc = &mut self.state;
        let s = sc.aux[naux + 1];
        let n = sc.x.len();
        let w = &mut self.work;
        w.aux_save.copy_from_slice(&sc.aux);
        w.y.copy_from_slice(&sc.x);
        let mut fwd = [0.0; 5];
        let mut bwd = [0.0; 5];
        // The outputs were computed at `s` after the step start; the state's time is the
        // step end.
        let t0 = sc.t - s;
        let mut sys = Sys {
            jw: None,
            level: self.level.as_mut(),
            st: sc,
            ring: self.ring.as_ref(),
            rule,
            causality,
            nl,
            naux,
            t0,
            last_error: None,
            budget: None,
            continues: false,
            sink: None,
            carries_jac: false,
        };
        let mut r = sys.eval(s, &w.y, &mut w.k[0], None);
        for (sign, dest) in [(1.0, &mut fwd), (-1.0, &mut bwd)] {
            if r.is_err() {
                break;
            }
            for j in 0..n {
                w.k[2][j] = w.y[j] + sign * DT_DERIV * w.k[0][j];
            }
            let [_, dk, yk] = &mut w.k;
            r = sys.eval(s + sign * DT_DERIV, yk, dk, Some(dest));
        }
        sc.aux.copy_from_slice(&w.aux_save);
        r?;
        let mut d = [0.0; 5];
        for k in 0..5 {
            d[k] = (fwd[k] - bwd[k]) / (2.0 * DT_DERIV);
        }
        if !all_finite(&d) {
            return Err(Error::StepFailed {
                t: sc.t,
                reason: "non-finite force derivative".into(),
            });
        }
        sc.output_derivatives[I_FORCE..I_FORCE + 5].copy_from_slice(&d);
        sc.derivatives_pending = false;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::component::{variables, Method};
    use crate::report::work_precision::cases;

    /// The load-driven 2-DOF 6205 of the work-precision study (DOPRI5 at `rtol`).
    fn ring(rtol: f64, rule: InputRule) -> Component {
        let case = cases().into_iter().find(|c| c.name == "6205-2dof").unwrap();
        let mut s = case.scene_with(Method::Dopri5, rtol).unwrap();
        s.inputs.rule = rule;
        Component::new(s).unwrap()
    }

    fn vr(name: &str) -> u32 {
        variables::by_name(name).unwrap().vr
    }

    /// A step writes every output slot from `N_INPUT_SLOTS` on but the per-row slots of rows
    /// the level does not have, which stay zero from the build (its scratch copy carries
    /// only the slots below over): with those slots of the scratch state poisoned before
    /// every step, the steps leave the same bits as without, for every input rule, both
    /// causalities and the levels of the work-precision cases that run here quickly.
    #[test]
    fn a_step_writes_every_output_slot_it_does_not_carry_over() {
        let scenes: Vec<crate::component::Scene> = ["6205-2dof", "6205-qs", "6205-linear"]
            .iter()
            .map(|n| {
                let case = cases().into_iter().find(|c| &c.name == n).unwrap();
                case.scene_with(Method::Dopri5, 1e-6).unwrap()
            })
            .chain(std::iter::once(
                crate::component::Scene::from_text(
                    "bearing = \"6205\"\n[model]\nlevel = \"ring\"\n[inputs]\nspeed_rpm = 1750.004092\ninitial = { \"shaft.x\" = 0.0, \"shaft.y\" = -8e-6, \"shaft.z\" = 0.0, \"shaft.rx\" = 0.0, \"shaft.ry\" = 0.0, \"shaft.vx\" = 0.0, \"shaft.vy\" = 0.0, \"shaft.vz\" = 0.0, \"shaft.wx\" = 0.0, \"shaft.wy\" = 0.0 }\n",
                )
                .unwrap(),
            ))
            .collect();
        for scene in scenes {
            for rule in [InputRule::Hold, InputRule::Velocity, InputRule::Derivatives] {
                let mut s = scene.clone();
                s.inputs.rule = rule;
                let (mut a, mut b) = (
                    Component::new(s.clone()).unwrap(),
                    Component::new(s).unwrap(),
                );
                for i in 0..20 {
                    let t = i as f64 * 1e-4;
                    a.do_step(t, 1e-4).unwrap();
                    let n = b.scratch.outputs.len();
                    if n > super::super::N_INPUT_SLOTS {
                        b.scratch.outputs[super::super::N_INPUT_SLOTS..].fill(f64::NAN);
                        // The per-row slots of rows a level does not have (all four for a
                        // single bearing) are never written: they keep their zero from
                        // the build (pay only for what you use).
                        let rows =
                            super::super::variables::ROWS * super::super::variables::ROW_OUTPUTS;
                        b.scratch.outputs[I_ROWS..I_ROWS + rows].fill(0.0);
                    }
                    b.do_step(t, 1e-4).unwrap();
                    assert_eq!(
                        a.serialize_state(),
                        b.serialize_state(),
                        "{rule:?} step {i}"
                    );
                }
            }
        }
    }

    /// What a step leaves (states, memory, outputs) as bits, and its right-hand sides.
    type Trace = Vec<(Vec<u64>, u64)>;

    /// `n` steps of 0.1 ms, `between(c, i)` before step `i`; `fresh`: forget the last stage
    /// before every step (each step evaluates its first stage).
    fn run(
        mut c: Component,
        n: usize,
        fresh: bool,
        between: &dyn Fn(&mut Component, usize),
    ) -> Trace {
        let h = 1e-4;
        let mut out = Vec::new();
        for i in 0..n {
            between(&mut c, i);
            if fresh {
                c.work.fsal = false;
            }
            let rhs = c.stats().rhs;
            c.do_step(c.time(), h).unwrap();
            let st = c.state();
            let bits =
                st.x.iter()
                    .chain(&st.aux)
                    .chain(&st.outputs)
                    .chain(&st.output_derivatives)
                    .map(|v| v.to_bits())
                    .collect();
            out.push((bits, c.stats().rhs - rhs));
        }
        out
    }

    /// The steps whose first stage was the last step's last (one evaluation fewer than
    /// the same step started afresh), after checking both runs agree bit for bit.
    fn reused(with: &Trace, without: &Trace) -> Vec<usize> {
        assert_eq!(with.len(), without.len());
        let mut v = Vec::new();
        for (i, (a, b)) in with.iter().zip(without).enumerate() {
            assert!(a.0 == b.0, "step {i}: not the same bits");
            match b.1 - a.1 {
                0 => {}
                1 => v.push(i),
                d => panic!("step {i}: {d} evaluations saved"),
            }
        }
        v
    }

    /// Reusing the last stage (first same as last across steps) gives the trajectory and
    /// the outputs bit for bit, one right-hand side cheaper per step: at a loose tolerance
    /// (one sub-step per step) and a tight one (several, with rejections).
    #[test]
    fn the_last_stage_reused_gives_the_same_bits() {
        for rtol in [1e-3, 1e-7] {
            let n = 200;
            let none = &|_: &mut Component, _| {};
            let with = run(ring(rtol, InputRule::Hold), n, false, none);
            let without = run(ring(rtol, InputRule::Hold), n, true, none);
            assert_eq!(
                reused(&with, &without),
                (1..n).collect::<Vec<_>>(),
                "{rtol}"
            );
        }
    }

    /// What the last stage read changing in between starts the next step afresh: a new
    /// load, an input derivative (the load moves inside the step) while it is not zero,
    /// a restored state; the same load set again does not.
    #[test]
    fn a_change_between_steps_starts_afresh() {
        let load = vr("load.y");
        let saved = std::cell::RefCell::new(None);
        let between = |c: &mut Component, i: usize| match i {
            3 => c.set_real(load, -1200.0).unwrap(),
            5 => c.set_real(load, -1200.0).unwrap(),
            8 => *saved.borrow_mut() = Some(c.get_state()),
            10 => c.set_state(saved.borrow().as_ref().unwrap()).unwrap(),
            13 => c.set_input_derivative(load, 1, -1e5).unwrap(),
            16 => c.set_input_derivative(load, 1, 0.0).unwrap(),
            _ => {}
        };
        let with = run(ring(1e-3, InputRule::Derivatives), 20, false, &between);
        *saved.borrow_mut() = None;
        let without = run(ring(1e-3, InputRule::Derivatives), 20, true, &between);
        let expect: Vec<usize> = (1..20)
            .filter(|i| ![3, 10, 13, 14, 15, 16].contains(i))
            .collect();
        assert_eq!(reused(&with, &without), expect);
    }
}
