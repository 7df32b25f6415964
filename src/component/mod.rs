//! The co-simulation component: created from a scene, stepped by a host with
//! `do_step(t, h)`, sub-stepping its own physics inside; read with `get_real`.
//!
//! This is the one contract the C ABI (`src/capi`) and the FMUs (`src/fmi`) wrap. Every
//! call either succeeds or returns an error that names the cause and leaves the component
//! exactly as it was.
//!
//! Split by phase: `build` (scene → level from the [registry](levels), ring body, state,
//! integrator), `static_start` (a load-driven ring's equilibrium), `inputs` (setting them
//! and moving them inside a step), `system` (the ODE the integrators see, the CPU budget),
//! `step` (the transaction, integration or quadrature, outputs); here the component's
//! state, reads and directional derivatives.

pub mod fields;
pub mod level;
pub mod levels;
pub mod limits;
pub mod scene;
pub mod schema;
pub mod state;
pub mod variables;

mod build;
mod inputs;
mod static_start;
mod step;
mod system;
mod through;

pub use scene::{InputRule, Level, Method, Scene};
pub use state::State;
pub use variables::{Causality, Variable};

use crate::error::{Error, Result};
use crate::geometry::Bearing;
use crate::solver::{Integrator, Options};
use level::LevelModel;
use system::{JacWork, RingBody, Work};
use variables::SCALARS;

pub use crate::counters::{Stages, Stats};

/// Number of variables in the table.
pub fn n_variables() -> usize {
    variables::all().count()
}

/// Position of a value reference in [`variables::all`] (the index into the state's
/// `inputs` and `outputs` vectors).
pub fn index_of(vr: u32) -> Option<usize> {
    variables::slot(vr)
}

// Positions in the table of the variables the component reads and writes on its hot
// path; `slots_match_the_table` checks them against the names.
const I_Q: usize = 0; // shaft.x .. shaft.ry
const I_V: usize = 5; // shaft.vx .. shaft.wy
const I_OMEGA: usize = 10;
const I_LOAD: usize = 11; // load.x .. load.my
const I_FORCE: usize = 16; // force.x .. moment.y
/// The table slots below this hold every input of either causality (the shaft motion and
/// speed, the loads): all a step reads of `State::inputs` (checked by
/// `slots_match_the_table`).
const N_INPUT_SLOTS: usize = I_FORCE;
const I_TORQUE: usize = 21;
const I_CAGE_OMEGA: usize = 22;
const I_DIAG: usize = 23; // cage.slip, balls.loaded, contact.max_load, contact.max_pressure, film, power, wear
const I_CAGE: usize = 30; // cage.x, cage.y, cage.speed, cage.speed_ratio, pocket.max_force, guide.force
const I_RATING: usize = 36; // safety.S0, life.L10, warnings.active
const I_K: usize = 39;
const I_C: usize = 64;
const I_ROWS: usize = 89; // row0.force.x .. row3.life.L10

/// Component-owned memory slots after the level's `aux`: the integrator's next step size,
/// then the inputs' offset (from the step start) the stored outputs belong to.
const AUX_COMPONENT: usize = 2;

/// Largest communication time and step, s (about 32 years): beyond it a step of a
/// millisecond is no longer resolved by a double.
pub const T_MAX: f64 = 1e9;

pub use crate::counters::thread_cpu_s;

/// FNV-1a over bytes: a stable fingerprint (not cryptographic).
pub fn fingerprint(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= *b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// A running bearing: created from a scene, stepped by a host.
#[derive(Debug)]
pub struct Component {
    scene: Scene,
    bearing: Bearing,
    level: Box<dyn LevelModel>,
    ring: Option<RingBody>,
    n_level: usize,
    n_level_aux: usize,
    state: State,
    scratch: State,
    work: Work,
    jwork: JacWork,
    integrator: Integrator,
    opts: Options,
    limits: limits::Limits,
    /// ISO 281/76 ratings for the `safety.S0`, `life.L10` and `warnings.active` outputs.
    rating: crate::ratings::RatingOutputs,
    /// A set's rows: each row's bearing and ratings (empty for one bearing: nothing per row
    /// is computed then).
    set_rows: Vec<(Bearing, crate::ratings::RatingOutputs)>,
    /// Per-stage CPU timers of `do_step` (off unless [`Component::set_stage_timing`]).
    stages: Stages,
    /// Evaluations before a step's CPU budget first reads the clock: the last step's
    /// estimate (a clock read is a system call, 0.2–0.4 µs).
    budget_gap: u32,
    /// A state was taken or set since the last step: the next step's W-method starts with
    /// a fresh Jacobian, not the one the last step ended with, so that a state continues
    /// bit for bit wherever it is restored ([`OdeSystem::carries_jacobian`]).
    ///
    /// [`OdeSystem::carries_jacobian`]: crate::solver::OdeSystem::carries_jacobian
    state_shared: std::sync::atomic::AtomicBool,
    /// The coordinates the static start held (`model.start_hold`) and the reaction the
    /// support added on each there (N, N m; zero elsewhere).
    start_held: ([bool; 5], [f64; 5]),
}

impl Component {
    /// The coordinates the load-driven static start held (`model.start_hold`, order
    /// `(x, y, z, rx, ry)`) and the reaction on each at the start, N and N m (what the
    /// support adds on the inner ring: `load + bearing force + reaction = 0`); all false
    /// when nothing was held.
    pub fn start_held(&self) -> ([bool; 5], [f64; 5]) {
        self.start_held
    }
    /// The scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }
    /// The validated bearing.
    pub fn bearing(&self) -> &Bearing {
        &self.bearing
    }
    /// The plausibility limits of the inputs (see [`limits`]).
    pub fn limits(&self) -> &limits::Limits {
        &self.limits
    }
    /// Keep the rolling elements' contact loads of every later output evaluation for
    /// [`Component::element_loads`] (what `raceway run` asks for its ball-load plot);
    /// `false` when the level does not resolve its elements one by one (the linear level,
    /// a bearing set). A component never asked stores nothing for them.
    pub fn keep_element_loads(&mut self) -> bool {
        self.level.keep_element_loads()
    }
    /// The rolling elements' contact loads at the last output evaluation (after a step: at
    /// its end), one per element ([`ElementLoad`](crate::seam::element::ElementLoad):
    /// azimuth from `+x` toward `+y`, inner and outer load), into `out` (cleared first;
    /// its allocation reused); read-only. `false`, with `out` empty, when the level has
    /// none: not resolved, or not kept ([`Component::keep_element_loads`]; the full and
    /// skidding levels have them always).
    pub fn element_loads(&self, out: &mut Vec<crate::seam::element::ElementLoad>) -> bool {
        self.level.element_loads(out)
    }
    /// The skidding level (its per-ball contacts and outer-race wear profile, for
    /// `crate::wear_cycles`); `None` for the other levels. Changing the profile makes the
    /// outputs stale.
    pub fn skidding_mut(&mut self) -> Option<&mut crate::models::skidding::level::SkiddingLevel> {
        self.level
            .as_any_mut()
            .and_then(|l| l.downcast_mut::<crate::models::skidding::level::SkiddingLevel>())
    }
    /// The causality.
    pub fn causality(&self) -> Causality {
        self.scene.model.causality
    }
    /// Current time, s.
    pub fn time(&self) -> f64 {
        self.state.t
    }
    /// Cost counters since creation.
    pub fn stats(&self) -> Stats {
        Stats::from(self.integrator.stats())
    }

    /// Turn the per-stage CPU timers of `do_step` on or off (off by default: then no clock
    /// is read). Turning them on resets them.
    pub fn set_stage_timing(&mut self, on: bool) {
        self.stages = Stages {
            enabled: on,
            ..Stages::default()
        };
    }

    /// Per-stage thread CPU time of `do_step` since timing was turned on.
    pub fn stages(&self) -> &Stages {
        &self.stages
    }

    /// Get an input or output by value reference. Outputs always belong to the current
    /// inputs and state: those of the last step, or, when an input or the state was set
    /// since, evaluated now (see [`Component::ensure_outputs`]). An input never set holds
    /// the scene's initial value ([`scene::InputSpec::initial_value`]).
    pub fn get_real(&mut self, vr: u32) -> Result<f64> {
        let v = variables::by_vr(vr)
            .ok_or_else(|| Error::invalid("value reference", vr, "a variable of the table"))?;
        let i = index_of(vr).expect("in table");
        Ok(if v.is_input(self.causality()) {
            self.state.inputs[i]
        } else {
            self.ensure_outputs()?;
            if self.state.matrices_pending && (I_K..I_C + 25).contains(&i) {
                self.compute_matrices()?;
            }
            self.state.outputs[i]
        })
    }

    /// Are the stored outputs behind the inputs or state? (Then the next output read
    /// evaluates them.)
    pub fn outputs_stale(&self) -> bool {
        self.state.outputs_stale
    }

    /// Can an output read still have to compute something, and so fail: the outputs stale
    /// ([`Component::outputs_stale`]) or the stiffness and damping left for their first read
    /// ([`crate::seam::LevelModel::outputs_deferring_matrices`])? When not, a read of a known
    /// output only copies a stored value.
    pub fn reads_may_compute(&self) -> bool {
        self.state.outputs_stale || self.state.matrices_pending
    }

    /// Make the outputs current: evaluate them at the current time and inputs when an input
    /// or the state was set since they were computed; otherwise nothing. The outputs are
    /// computed when read, not when inputs are set, so a host that sets inputs and steps
    /// without reading in between pays nothing extra; every read (after creation, after
    /// setting inputs, after restoring a state, after a step) sees current values.
    pub fn ensure_outputs(&mut self) -> Result<()> {
        if self.state.outputs_stale {
            self.refresh_outputs()?;
        }
        Ok(())
    }

    /// Get the time derivative (order 1) of an output at the current time.
    pub fn get_output_derivative(&mut self, vr: u32, order: u32) -> Result<f64> {
        let v = variables::by_vr(vr)
            .ok_or_else(|| Error::invalid("value reference", vr, "a variable of the table"))?;
        if !v.is_output(self.causality()) {
            return Err(Error::invalid("value reference", vr, "an output"));
        }
        if order != 1 {
            return Err(Error::invalid("order", order, "1"));
        }
        self.ensure_outputs()?;
        let i = index_of(vr).expect("in table");
        if self.state.derivatives_pending && (I_FORCE..I_FORCE + 5).contains(&i) {
            self.compute_force_derivatives()?;
        }
        Ok(self.state.output_derivatives[i])
    }

    /// A copy of the complete state.
    pub fn get_state(&self) -> State {
        self.mark_state_shared();
        self.state.clone()
    }

    /// The complete state (copy it into a state of the same scene with
    /// `clone_from`, which does not allocate).
    pub fn state(&self) -> &State {
        self.mark_state_shared();
        &self.state
    }

    /// Restore a state taken from this component (or one built from the same scene).
    pub fn set_state(&mut self, s: &State) -> Result<()> {
        self.check_state(s)?;
        self.state.clone_from(s);
        self.mark_state_shared();
        Ok(())
    }

    /// [`Component::state_shared`]: set.
    fn mark_state_shared(&self) {
        self.state_shared
            .store(true, std::sync::atomic::Ordering::Relaxed);
    }

    /// Would [`Component::set_state`] accept `s`? (Same scene, same sizes.)
    pub fn check_state(&self, s: &State) -> Result<()> {
        if s.scene_fingerprint != self.state.scene_fingerprint
            || s.x.len() != self.state.x.len()
            || s.aux.len() != self.state.aux.len()
            || s.inputs.len() != self.state.inputs.len()
            || s.input_derivatives.len() != self.state.input_derivatives.len()
            || s.outputs.len() != self.state.outputs.len()
            || s.output_derivatives.len() != self.state.output_derivatives.len()
        {
            return Err(Error::CallOrder {
                call: "set_state",
                reason: "the state belongs to another scene".into(),
            });
        }
        // Values (bytes read back pass `State::from_bytes`, which refuses non-finite
        // numbers; a state built in memory may not have): every number finite, only
        // inputs of this causality marked set, each set input one `set_real` accepts.
        let numbers = std::iter::once(&s.t)
            .chain(&s.x)
            .chain(&s.aux)
            .chain(&s.inputs)
            .chain(&s.input_derivatives)
            .chain(&s.outputs)
            .chain(&s.output_derivatives);
        if let Some(v) = numbers.into_iter().find(|v| !v.is_finite()) {
            return Err(Error::invalid("state value", v, "finite numbers only"));
        }
        for (i, v) in SCALARS.iter().enumerate() {
            if s.inputs_set & (1 << i) == 0 {
                continue;
            }
            if !v.is_input(self.causality()) {
                return Err(Error::invalid(
                    "state input mask",
                    s.inputs_set,
                    "bits of inputs of this causality only",
                ));
            }
            self.input_slot("set_real", v.vr, s.inputs[i])?; // with the plausibility limits
        }
        if SCALARS.len() < 64 && s.inputs_set >> SCALARS.len() != 0 {
            return Err(Error::invalid(
                "state input mask",
                s.inputs_set,
                "bits of inputs of this causality only",
            ));
        }
        Ok(())
    }

    /// The state as bytes (versioned, no pointers).
    pub fn serialize_state(&self) -> Vec<u8> {
        self.state.to_bytes()
    }

    /// Restore a state from bytes written by [`Component::serialize_state`].
    pub fn deserialize_state(&mut self, bytes: &[u8]) -> Result<()> {
        let s = State::from_bytes(bytes)?;
        self.set_state(&s)
    }

    /// Directional derivative `out = J seed` of outputs `unknowns` with respect to inputs
    /// `knowns`, at the current state. Forces and moments respond to displacements through
    /// `-K` and to velocities through `-C` (motion-driven); other pairs have no direct
    /// dependence and give 0.
    ///
    /// Any finite seed gives finite values or a refusal: the seed is scaled by its largest
    /// magnitude before the products (so no intermediate overflows) and scaled back after;
    /// a result beyond the range of `f64` (e.g. `K seed` with a seed of 1e308 m) is refused
    /// naming the seed, not returned as infinity.
    pub fn directional_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
        out: &mut [f64],
    ) -> Result<()> {
        if knowns.len() != seed.len() || unknowns.len() != out.len() {
            return Err(Error::invalid(
                "directional derivative",
                "lengths",
                "seed as long as knowns, out as long as unknowns",
            ));
        }
        for (&k, &s) in knowns.iter().zip(seed) {
            let Some(v) = variables::by_vr(k) else {
                return Err(Error::invalid(
                    "directional derivative known",
                    k,
                    "a variable of the table",
                ));
            };
            if !s.is_finite() {
                return Err(Error::invalid(
                    format!("directional derivative seed of `{}`", v.name),
                    s,
                    "a finite number",
                ));
            }
        }
        self.ensure_outputs()?;
        if self.state.matrices_pending {
            self.compute_matrices()?;
        }
        let scale = seed.iter().fold(0.0f64, |m, s| m.max(s.abs()));
        // s / scale is within [-1, 1] (and no 1/scale overflows for a subnormal scale).
        let unit = |s: f64| if scale > 0.0 { s / scale } else { 0.0 };
        let motion = self.causality() == Causality::Motion;
        for (o, &u) in out.iter_mut().zip(unknowns) {
            let ui = index_of(u).ok_or_else(|| {
                Error::invalid(
                    "directional derivative unknown",
                    u,
                    "a variable of the table",
                )
            })?;
            *o = 0.0;
            if !(motion && (I_FORCE..I_FORCE + 5).contains(&ui)) {
                continue;
            }
            let r = ui - I_FORCE;
            for (&k, &s) in knowns.iter().zip(seed) {
                let ki = index_of(k).expect("checked");
                if (I_Q..I_Q + 5).contains(&ki) {
                    *o -= self.state.outputs[I_K + 5 * r + (ki - I_Q)] * unit(s);
                } else if (I_V..I_V + 5).contains(&ki) {
                    *o -= self.state.outputs[I_C + 5 * r + (ki - I_V)] * unit(s);
                }
            }
            *o *= scale;
            if !o.is_finite() {
                return Err(Error::invalid(
                    "directional derivative seed",
                    format!("of largest magnitude {scale:e}"),
                    format!(
                        "a seed whose product with the Jacobian stays within ±{:e} \
                         (`{}` overflows)",
                        f64::MAX,
                        variables::by_vr(u).map_or("?", |v| v.name)
                    ),
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slots_match_the_table() {
        let at = |i: usize| variables::all().nth(i).unwrap().name;
        assert_eq!(at(I_Q), "shaft.x");
        assert_eq!(at(I_V + 4), "shaft.wy");
        assert_eq!(at(I_OMEGA), "shaft.omega");
        assert_eq!(at(I_LOAD + 4), "load.my");
        assert_eq!(at(I_FORCE + 4), "moment.y");
        assert_eq!(at(I_TORQUE), "torque.z");
        assert_eq!(at(I_CAGE_OMEGA), "cage.omega");
        assert_eq!(at(I_DIAG), "cage.slip");
        assert_eq!(at(I_DIAG + 6), "wear.max_depth");
        assert_eq!(at(I_CAGE), "cage.x");
        assert_eq!(at(I_CAGE + 5), "guide.force");
        assert_eq!(at(I_RATING), "safety.S0");
        assert_eq!(at(I_RATING + 2), "warnings.active");
        assert_eq!(at(I_K), "K.x.x");
        assert_eq!(at(I_C + 24), "C.ry.ry");
        assert_eq!(at(I_ROWS), "row0.force.x");
        assert_eq!(
            at(I_ROWS + variables::ROWS * variables::ROW_OUTPUTS - 1),
            "row3.life.L10"
        );
        assert_eq!(variables::by_vr(variables::VR_K0).unwrap().name, "K.x.x");
        assert_eq!(variables::by_vr(variables::VR_C0).unwrap().name, "C.x.x");
        assert!(SCALARS.len() <= 64, "the inputs-set mask is a u64");
        for (i, v) in variables::all().enumerate() {
            if v.is_input(Causality::Motion) || v.is_input(Causality::Load) {
                assert!(i < N_INPUT_SLOTS, "input `{}` at slot {i}", v.name);
            }
        }
    }

    /// Motion-driven, the cage angle is integrated by quadrature ([`Component::quadrature`]):
    /// under the derivatives rule the shaft speed is a cubic in time inside a step, and the
    /// angle must be the cage ratio times its exact integral (a trapezoid or midpoint rule
    /// misses by 4e-4 of the angle here, far above the 1e-12 asserted).
    #[test]
    fn motion_driven_cage_angle_is_the_exact_integral_of_a_cubic_speed() {
        let text = "title = \"quadrature\"\nbearing = { preset = \"6205\", clearance_um = 10.0 }\n\
                    [model]\nlevel = \"ring\"\ncausality = \"motion\"\nring_dof = 2\n\
                    [inputs]\nrule = \"derivatives\"\n";
        let mut c = Component::from_text(text).unwrap();
        let vr = |n: &str| variables::by_name(n).unwrap().vr;
        for n in [
            "shaft.x", "shaft.z", "shaft.rx", "shaft.ry", "shaft.vx", "shaft.vy", "shaft.vz",
            "shaft.wx", "shaft.wy",
        ] {
            c.set_real(vr(n), 0.0).unwrap();
        }
        c.set_real(vr("shaft.y"), -15e-6).unwrap();
        let (w0, d) = (100.0, [5e3, -2e6, 3e9]);
        c.set_real(vr("shaft.omega"), w0).unwrap();
        for (k, v) in d.iter().enumerate() {
            c.set_input_derivative(vr("shaft.omega"), k as u32 + 1, *v)
                .unwrap();
        }
        let h = 1e-3;
        c.do_step(0.0, h).unwrap();
        let w_end = w0 + h * (d[0] + h * (d[1] / 2.0 + h * d[2] / 6.0));
        let ratio = c.get_real(vr("cage.omega")).unwrap() / w_end;
        let integral = h * (w0 + h * (d[0] / 2.0 + h * (d[1] / 6.0 + h * d[2] / 24.0)));
        let angle = c.state.x[0];
        assert!(ratio > 0.3 && ratio < 0.5, "cage ratio {ratio}");
        assert!(
            (angle - ratio * integral).abs() <= 1e-12 * angle.abs(),
            "cage angle {angle} vs {}",
            ratio * integral
        );
    }
}
