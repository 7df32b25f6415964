//! The co-simulation component: created from a scene, stepped by a host with
//! `do_step(t, h)`, sub-stepping its own physics inside; read with `get_real`.
//!
//! This is the one contract the C ABI (`src/capi`) and the FMUs (`src/fmi`) wrap. Every
//! call either succeeds or returns an error that names the cause and leaves the component
//! exactly as it was.

pub mod fields;
pub mod level;
pub mod levels;
pub mod limits;
pub mod scene;
pub mod schema;
pub mod state;
pub mod variables;

pub use scene::{InputRule, Level, Method, Scene};
pub use state::State;
pub use variables::{Causality, Variable};

use crate::error::{Error, Result};
use crate::geometry::Bearing;
use crate::solver::{Dopri5, Integrator, OdeSystem, Options, Rosenbrock, SolverError};
use level::{LevelModel, LevelOutputs, Motion};
use variables::SCALARS;

/// Cost counters of the internal integration.
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

/// Number of variables in the table.
pub fn n_variables() -> usize {
    variables::all().count()
}

/// Position of a value reference in [`variables::all`] (the index into the state's
/// `inputs` and `outputs` vectors).
pub fn index_of(vr: u32) -> Option<usize> {
    variables::all().position(|v| v.vr == vr)
}

/// A bulk call's value references and values pair up.
fn same_length(vrs: &[u32], values: &[f64]) -> std::result::Result<(), (usize, Error)> {
    if vrs.len() == values.len() {
        return Ok(());
    }
    let e = Error::invalid("values", values.len(), "as many values as value references");
    Err((0, e))
}

// Positions in the table of the variables the component reads and writes on its hot
// path; `slots_match_the_table` checks them against the names.
const I_Q: usize = 0; // shaft.x .. shaft.ry
const I_V: usize = 5; // shaft.vx .. shaft.wy
const I_OMEGA: usize = 10;
const I_LOAD: usize = 11; // load.x .. load.my
const I_FORCE: usize = 16; // force.x .. moment.y
const I_TORQUE: usize = 21;
const I_CAGE_OMEGA: usize = 22;
const I_DIAG: usize = 23; // cage.slip, balls.loaded, contact.max_load, contact.max_pressure, film, power, wear
const I_CAGE: usize = 30; // cage.x, cage.y, cage.speed, cage.speed_ratio, pocket.max_force, guide.force
const I_RATING: usize = 36; // safety.S0, life.L10, warnings.active
const I_K: usize = 39;
const I_C: usize = 64;

/// Time offset of the central difference that gives output derivatives, s.
const DT_DERIV: f64 = 1e-7;

/// Largest communication time and step, s (about 32 years): beyond it a step of a
/// millisecond is no longer resolved by a double.
pub const T_MAX: f64 = 1e9;

/// Most evaluations between two reads of the CPU clock (a read costs 0.2 µs, one
/// right-hand side of the cheapest level 0.3 µs: at most 0.3 % of a step).
const BUDGET_EVERY: u32 = 256;

/// CPU time aimed at between two reads of the clock, s: evaluations that cost more are
/// checked more often, down to every one, so a step whose every right-hand side takes a
/// second still stops within a second of its budget.
const BUDGET_READ_S: f64 = 1e-3;

/// CPU time of the calling thread, s (`CLOCK_THREAD_CPUTIME_ID`).
pub fn thread_cpu_s() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec; the clock id is a constant.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64
}

/// The CPU-time budget of one communication step.
#[derive(Debug, Clone, Copy)]
struct Budget {
    start: f64,
    limit: f64,
    evals: u32,
    /// Evaluation count at which the clock is read next.
    next: u32,
    /// CPU time used when the budget ran out.
    spent: Option<f64>,
}

impl Budget {
    fn new(limit: f64) -> Self {
        Budget {
            start: thread_cpu_s(),
            limit,
            evals: 0,
            next: 1,
            spent: None,
        }
    }
    /// Count one evaluation; `true` once the budget is spent. The clock is read about
    /// every [`BUDGET_READ_S`] of CPU time as estimated from the evaluations so far, and
    /// at least every [`BUDGET_EVERY`] evaluations.
    fn spent(&mut self) -> bool {
        if self.spent.is_some() {
            return true;
        }
        self.evals = self.evals.saturating_add(1);
        if self.evals >= self.next {
            let used = thread_cpu_s() - self.start;
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
            self.next = self.evals.saturating_add(gap as u32);
        }
        false
    }
}

/// FNV-1a over bytes: a stable fingerprint (not cryptographic).
pub fn fingerprint(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= *b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// The inner ring as a body (load-driven causality).
#[derive(Debug, Clone)]
struct RingBody {
    /// Coordinates integrated (indices into q).
    dofs: &'static [usize],
    /// Mass (translations) or transverse inertia (tilts) per coordinate of `q`.
    inertia: [f64; 5],
}

/// Preallocated work space of a step (no allocation inside `do_step`).
#[derive(Debug, Clone, Default)]
struct Work {
    /// Rates at the output time, rates at a shifted time, and the shifted states (the
    /// central difference that gives `dF/dt`).
    k: [Vec<f64>; 3],
    y: Vec<f64>,
    aux_save: Vec<f64>,
}

/// Work space of the level Jacobians (see [`LevelModel::jacobian`]).
#[derive(Debug, Clone, Default)]
struct JacWork {
    jx: Vec<f64>,
    jm: Vec<f64>,
    wx: Vec<f64>,
    wm: Vec<f64>,
}

/// The whole system a step integrates: the level's states and, load-driven, the ring's.
struct Sys<'a> {
    jw: Option<&'a mut JacWork>,
    level: &'a mut dyn LevelModel,
    st: &'a mut State,
    ring: Option<&'a RingBody>,
    rule: InputRule,
    causality: Causality,
    nl: usize,
    naux: usize,
    t0: f64,
    /// The last error the level raised at a trial point (the integrator sees NaN there and
    /// retries with a smaller step; if it gives up, this is the cause it reports).
    last_error: Option<Error>,
    /// The step's CPU budget (none for output evaluations).
    budget: Option<Budget>,
}

impl Sys<'_> {
    /// Right-hand side at `s` after the step start; with `wrench`, also the bearing force.
    fn eval(
        &mut self,
        s: f64,
        y: &[f64],
        dy: &mut [f64],
        wrench: Option<&mut [f64; 5]>,
    ) -> Result<()> {
        let nl = self.nl;
        let m = motion_at_y(self.st, self.rule, s, self.causality, self.ring, nl, y);
        let t = self.t0 + s;
        let (aux, _) = self.st.aux.split_at_mut(self.naux);
        match self.ring {
            None => self
                .level
                .rhs(t, &m, &y[..nl], aux, &mut dy[..nl], wrench)?,
            Some(ring) => {
                let mut w = [0.0; 5];
                self.level
                    .rhs(t, &m, &y[..nl], aux, &mut dy[..nl], Some(&mut w))?;
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
        if self.budget.as_mut().is_some_and(Budget::spent) {
            return Err("CPU budget spent".into());
        }
        // A trial state can be far off (a too-large trial step through a stiff contact):
        // a level that cannot evaluate there makes the step fail and shrink, not the run.
        if let Err(e) = self.eval(t - self.t0, y, dy, None) {
            dy.fill(f64::NAN);
            self.last_error = Some(e);
        }
        Ok(())
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
        let m = motion_at_y(self.st, self.rule, s, self.causality, self.ring, nl, y);
        let (aux, _) = self.st.aux.split_at_mut(self.naux);
        let (jm, wx, wm) = if self.ring.is_some() {
            (&mut jw.jm[..], &mut jw.wx[..], &mut jw.wm[..])
        } else {
            (&mut [][..], &mut [][..], &mut [][..])
        };
        if !self
            .level
            .jacobian(t, &m, &y[..nl], aux, &mut jw.jx, jm, wx, wm)
        {
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
}

/// The scene's integrator and its options. `Auto` picks DOPRI5: the levels so far are not
/// stiff (a massless-ball ring is a few-kHz oscillator, numerics.md §1.2).
fn make_integrator(
    scene: &Scene,
    b: &Bearing,
    level: &dyn LevelModel,
    nl: usize,
    ring: Option<&RingBody>,
) -> (Integrator, Options) {
    let n = nl + ring.map_or(0, |r| 2 * r.dofs.len());
    // A stiff level (its registry entry) gets RODAS4 by default.
    let stiff = scene.model.level.entry().stiff;
    // A level with independent blocks of states gets the block-arrowhead solver.
    let rodas = || match level.blocks() {
        Some((nb, s)) if nb * s <= nl => Rosenbrock::with_solver(Box::new(
            crate::solver::BlockArrowhead::new(nb, s, n - nb * s),
        )),
        _ => Rosenbrock::new(n),
    };
    let integrator = match scene.solver.method {
        Method::Auto if stiff => Integrator::Rosenbrock(rodas()),
        Method::Auto | Method::Dopri5 => Integrator::Dopri5(Dopri5::new(n)),
        Method::Rosenbrock => Integrator::Rosenbrock(rodas()),
    };
    let s = &scene.solver;
    let mut opts = Options::new(n, s.rtol, s.atol_m);
    // Angles (cage, shaft, balls): an angle error atol_m / (D/2) moves a ball surface by
    // atol_m; a level with other states gives its own scales.
    let angle = s.atol_m / (0.5 * b.d);
    if !level.state_atol(s.atol_m, &mut opts.atol[..nl]) {
        opts.atol[..nl].fill(angle);
    }
    if let Some(r) = ring {
        let nd = r.dofs.len();
        let rate = 2.0 * std::f64::consts::PI * 1e3; // velocities: atol over a 1 kHz period
        for (k, &d) in r.dofs.iter().enumerate() {
            let a = if d < 3 {
                s.atol_m
            } else {
                s.atol_m / (0.5 * b.dm)
            };
            opts.atol[nl + k] = a;
            opts.atol[nl + nd + k] = a * rate;
        }
    }
    opts.max_steps = s.max_substeps as u64;
    if s.max_substep_s > 0.0 {
        opts.h_max = s.max_substep_s;
    }
    (integrator, opts)
}

impl Component {
    /// Create from scene text (TOML or JSON).
    pub fn from_text(text: &str) -> Result<Component> {
        Component::new(Scene::from_text(text)?)
    }

    /// Create from a scene. A bad scene is refused with a message naming the field.
    pub fn new(scene: Scene) -> Result<Component> {
        let bearing = scene.validate()?;
        let mut level = scene.model.level.build(&scene, &bearing)?;
        let n = n_variables();
        let fp = fingerprint(serde_json::to_string(&scene).unwrap_or_default().as_bytes());
        let causality = scene.model.causality;
        let ring = match causality {
            Causality::Motion => None,
            Causality::Load => {
                let m = bearing.inner_ring_mass + scene.model.attached_mass_kg;
                let ro = 0.5 * (bearing.dm - bearing.d);
                let ri = 0.5 * bearing.bore;
                let it = bearing.inner_ring_mass
                    * (3.0 * (ro * ro + ri * ri) + bearing.width.powi(2))
                    / 12.0;
                Some(RingBody {
                    dofs: level.ring_dofs(),
                    inertia: [m, m, m, it, it],
                })
            }
        };
        let n_level = level.n_states();
        let n_level_aux = level.n_aux();
        let n_ring = ring.as_ref().map_or(0, |r| 2 * r.dofs.len());
        let mut state = State {
            scene_fingerprint: fp,
            x: vec![0.0; n_level + n_ring],
            aux: vec![0.0; n_level_aux + 1],
            inputs: vec![0.0; n],
            input_derivatives: vec![0.0; 3 * n],
            outputs: vec![0.0; n],
            output_derivatives: vec![0.0; n],
            outputs_stale: true,
            ..State::default()
        };
        for (name, value) in &scene.inputs.initial {
            let v = variables::by_name(name).expect("validated");
            let i = index_of(v.vr).expect("in table");
            state.inputs[i] = *value;
            state.inputs_set |= 1 << i;
        }
        let motion = motion_at(
            &state,
            scene.inputs.rule,
            0.0,
            causality,
            ring.as_ref(),
            n_level,
        );
        level.init(
            &motion,
            &mut state.x[..n_level],
            &mut state.aux[..n_level_aux],
        )?;
        if let (Some(r), scene::Start::Equilibrium) = (&ring, scene.model.start) {
            let loads: [f64; 5] = std::array::from_fn(|k| state.inputs[I_LOAD + k]);
            let q = static_start(
                level.as_mut(),
                r.dofs,
                &loads,
                motion.omega,
                0.5 * bearing.dm,
                &state.x[..n_level],
                &mut state.aux[..n_level_aux],
            )?;
            for (k, &d) in r.dofs.iter().enumerate() {
                state.x[n_level + k] = q[d];
            }
        }
        let dim = state.x.len();
        let (integrator, opts) =
            make_integrator(&scene, &bearing, level.as_ref(), n_level, ring.as_ref());
        let work = Work {
            k: std::array::from_fn(|_| vec![0.0; dim]),
            y: vec![0.0; dim],
            aux_save: vec![0.0; n_level_aux + 1],
        };
        let jwork = JacWork {
            jx: vec![0.0; n_level * n_level],
            jm: vec![0.0; n_level * 10],
            wx: vec![0.0; 5 * n_level],
            wm: vec![0.0; 50],
        };
        let mut c = Component {
            limits: limits::Limits::of(&bearing),
            rating: crate::ratings::RatingOutputs::of(&bearing),
            jwork,
            scene,
            bearing,
            level,
            ring,
            n_level,
            n_level_aux,
            scratch: state.clone(),
            state,
            work,
            integrator,
            opts,
        };
        if c.missing_inputs().is_empty() {
            c.refresh_outputs()?;
        }
        Ok(c)
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
    /// The level's own ball loads at its last evaluation, `(azimuth rad, inner N, outer
    /// N)` per ball, for the levels that resolve the balls themselves (skidding); `None`
    /// for the others.
    pub fn ball_loads(&self) -> Option<Vec<(f64, f64, f64)>> {
        self.level.ball_loads()
    }
    /// The skidding level (its per-ball contacts and outer-race wear profile, for
    /// `crate::wear_cycles`); `None` for the other levels. Changing the profile makes the
    /// outputs stale.
    pub fn skidding_mut(&mut self) -> Option<&mut crate::models::skidding::level::SkiddingLevel> {
        self.level.as_skidding_mut()
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
        let s = self.integrator.stats();
        Stats {
            rhs: s.rhs_evals,
            jacobians: s.jac_evals,
            factorizations: s.lu_decomps,
            accepted: s.accepted,
            rejected: s.rejected,
        }
    }

    /// Set an input by value reference. Setting a value clears that input's derivatives.
    pub fn set_real(&mut self, vr: u32, value: f64) -> Result<()> {
        let i = self.input_slot("set_real", vr, value)?;
        self.write_input(i, value);
        Ok(())
    }

    fn write_input(&mut self, i: usize, value: f64) {
        self.state.inputs[i] = value;
        self.state.input_derivatives[3 * i..3 * i + 3].fill(0.0);
        self.state.inputs_set |= 1 << i;
        self.state.outputs_stale = true;
    }

    /// Set `values[k]` to `vrs[k]`, all or nothing: every pair is checked before any is
    /// written (no copy of the state, no allocation). A refusal gives the index of the
    /// first refused pair with its error.
    pub fn set_reals(
        &mut self,
        vrs: &[u32],
        values: &[f64],
    ) -> std::result::Result<(), (usize, Error)> {
        same_length(vrs, values)?;
        for (k, (&vr, &v)) in vrs.iter().zip(values).enumerate() {
            self.input_slot("set_real", vr, v).map_err(|e| (k, e))?;
        }
        for (&vr, &v) in vrs.iter().zip(values) {
            let i = index_of(vr).expect("checked above");
            self.write_input(i, v);
        }
        Ok(())
    }

    /// Set the `order`-th derivatives of several inputs, all or nothing, as
    /// [`Component::set_reals`].
    pub fn set_input_derivatives(
        &mut self,
        vrs: &[u32],
        order: u32,
        values: &[f64],
    ) -> std::result::Result<(), (usize, Error)> {
        same_length(vrs, values)?;
        for (k, (&vr, &v)) in vrs.iter().zip(values).enumerate() {
            self.derivative_slot(vr, order, v).map_err(|e| (k, e))?;
        }
        for (&vr, &v) in vrs.iter().zip(values) {
            let i = index_of(vr).expect("checked above");
            self.state.input_derivatives[3 * i + (order as usize - 1)] = v;
            self.state.outputs_stale = true;
        }
        Ok(())
    }

    /// The slot of input `vr` if `call` may set it to `value` (an input of this causality,
    /// a finite value).
    fn input_slot(&self, call: &'static str, vr: u32, value: f64) -> Result<usize> {
        let v = variables::by_vr(vr)
            .ok_or_else(|| Error::invalid("value reference", vr, "a variable of the table"))?;
        if !v.is_input(self.causality()) {
            return Err(Error::CallOrder {
                call,
                reason: format!("`{}` is not an input of this causality", v.name),
            });
        }
        if call == "set_real" {
            self.limits.check(v.name, v.name, value)?;
        } else if !value.is_finite() {
            return Err(Error::invalid(v.name, value, "a finite number"));
        }
        Ok(index_of(vr).expect("in table"))
    }

    /// Set the `order`-th time derivative (1..=3) of an input at the start of the next
    /// step, used with [`InputRule::Derivatives`]. They hold until the input is set again.
    pub fn set_input_derivative(&mut self, vr: u32, order: u32, value: f64) -> Result<()> {
        let i = self.derivative_slot(vr, order, value)?;
        self.state.input_derivatives[3 * i + (order as usize - 1)] = value;
        self.state.outputs_stale = true;
        Ok(())
    }

    fn derivative_slot(&self, vr: u32, order: u32, value: f64) -> Result<usize> {
        let i = self.input_slot("set_input_derivative", vr, value)?;
        if !(1..=3).contains(&order) {
            return Err(Error::invalid("order", order, "1, 2 or 3"));
        }
        Ok(i)
    }

    /// Get an input or output by value reference. Outputs always belong to the current
    /// inputs and state: those of the last step, or, when an input or the state was set
    /// since, evaluated now (see [`Component::ensure_outputs`]); an output read while an
    /// input was never set is refused naming it.
    pub fn get_real(&mut self, vr: u32) -> Result<f64> {
        let v = variables::by_vr(vr)
            .ok_or_else(|| Error::invalid("value reference", vr, "a variable of the table"))?;
        let i = index_of(vr).expect("in table");
        Ok(if v.is_input(self.causality()) {
            self.state.inputs[i]
        } else {
            self.ensure_outputs()?;
            self.state.outputs[i]
        })
    }

    /// Are the stored outputs behind the inputs or state? (Then the next output read
    /// evaluates them.)
    pub fn outputs_stale(&self) -> bool {
        self.state.outputs_stale
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
        Ok(self.state.output_derivatives[index_of(vr).expect("in table")])
    }

    fn missing_inputs(&self) -> Vec<&'static str> {
        SCALARS
            .iter()
            .enumerate()
            .filter(|(i, v)| v.is_input(self.causality()) && self.state.inputs_set & (1 << i) == 0)
            .map(|(_, v)| v.name)
            .collect()
    }

    /// Refuse `call` while some input of this causality was never set (names them).
    fn require_inputs(&self, call: &'static str) -> Result<()> {
        let missing = self.missing_inputs();
        if missing.is_empty() {
            return Ok(());
        }
        Err(Error::CallOrder {
            call,
            reason: format!("inputs never set: {}", missing.join(", ")),
        })
    }

    /// Evaluate the outputs at the current time and inputs (for hosts that read outputs
    /// before the first step, e.g. in FMI initialisation mode). On error nothing changes.
    pub fn refresh_outputs(&mut self) -> Result<()> {
        self.require_inputs("refresh_outputs")?;
        self.scratch.clone_from(&self.state);
        let mut sc = std::mem::take(&mut self.scratch);
        let r = self.compute_outputs(&mut sc, 0.0);
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
                call: "do_step",
                reason: format!(
                    "t = {t} s but the component is at {} s (time must not jump or run backwards)",
                    self.state.t
                ),
            });
        }
        self.require_inputs("do_step")?;
        self.check_inputs_at(h)?;
        self.scratch.clone_from(&self.state);
        let mut sc = std::mem::take(&mut self.scratch);
        // The host owns time: re-sync to its communication point (within the tolerance).
        sc.t = t;
        let r = self
            .integrate(&mut sc, h)
            .and_then(|_| self.compute_outputs(&mut sc, h));
        if r.is_ok() {
            sc.t = t + h;
            sc.started = true;
            sc.outputs_stale = false;
            std::mem::swap(&mut self.state, &mut sc);
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

    /// Integrate the states of `sc` over `h` with the scene's integrator; `sc.t` is the
    /// step start. The step-size memory lives in the last `aux` slot.
    fn integrate(&mut self, sc: &mut State, h: f64) -> Result<()> {
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
            budget: Some(Budget::new(self.scene.solver.max_step_cpu_s)),
        };
        let r = self.integrator.integrate(
            &mut sys,
            t0,
            t0 + h,
            &mut self.work.y,
            &mut h_trial,
            &self.opts,
        );
        if let Err(e) = r {
            if let Some(used) = sys.budget.and_then(|b| b.spent) {
                return Err(Error::Budget {
                    t: t0,
                    field: "solver.max_step_cpu_s",
                    limit: format!("{} s", self.scene.solver.max_step_cpu_s),
                    used: format!("{used:.3e} s of CPU time, reaching t = {}", e_time(&e)),
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
        Ok(())
    }

    /// Motion-driven levels whose states are a quadrature of the inputs (the cage angle):
    /// Simpson's rule over the step, exact for the inputs' time dependence under every
    /// input rule (at most cubic in time, [`input_at`]), as the adaptive DOPRI5 step it
    /// replaces was (its quadrature weights are exact to degree 4), at 3 cheap right-hand
    /// sides instead of 7 and no step-size control (the step-size memory is left as is).
    fn quadrature(&mut self, sc: &mut State, h: f64) -> Result<()> {
        let (nl, naux) = (self.n_level, self.n_level_aux);
        let rule = self.scene.inputs.rule;
        let causality = self.causality();
        let [k0, k1, k2] = &mut self.work.k;
        for (s, k) in [(0.0, &mut *k0), (0.5 * h, &mut *k1), (h, &mut *k2)] {
            let m = motion_at(sc, rule, s, causality, None, nl);
            let (aux, _) = sc.aux.split_at_mut(naux);
            self.level
                .rhs(sc.t + s, &m, &sc.x[..nl], aux, &mut k[..nl], None)?;
        }
        for j in 0..nl {
            sc.x[j] += h / 6.0 * (k0[j] + 4.0 * k1[j] + k2[j]);
        }
        Ok(())
    }

    /// Refuse a step whose inputs, moved along the scene's rule to the step end `h`, leave
    /// their plausibility limits (a velocity or derivative that carries a position off).
    fn check_inputs_at(&self, h: f64) -> Result<()> {
        let c = self.causality();
        for (i, v) in SCALARS.iter().enumerate() {
            if !v.is_input(c) {
                continue;
            }
            let u = input_at(&self.state, i, h, self.scene.inputs.rule);
            if self.limits.allows(v.name, u) {
                continue;
            }
            self.limits
                .check(&format!("{} at the step end t + h", v.name), v.name, u)?;
        }
        Ok(())
    }

    /// Fill the outputs of `sc` at `s` after its time (`sc.x` already at that time).
    fn compute_outputs(&mut self, sc: &mut State, s: f64) -> Result<()> {
        let nl = self.n_level;
        let rule = self.scene.inputs.rule;
        let causality = self.causality();
        let m = motion_at_y(sc, rule, s, causality, self.ring.as_ref(), nl, &sc.x);
        let mut out = LevelOutputs::default();
        {
            let (aux, _) = sc.aux.split_at_mut(self.n_level_aux);
            self.level
                .outputs(sc.t + s, &m, &sc.x[..nl], aux, &mut out)?;
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
        o[I_RATING..I_RATING + 3].copy_from_slice(&self.rating.outputs(
            &self.bearing,
            &out.wrench,
            out.max_pressure,
            out.balls_loaded,
        ));
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
                sc.output_derivatives[I_V + d] = (out.wrench[d] + load) / ring.inertia[d];
            }
        }
        // dF/dt by a central difference in time along the inputs' rule and the states'
        // rates; the level's memory (warm starts) is restored afterwards.
        let n = sc.x.len();
        let w = &mut self.work;
        w.aux_save.copy_from_slice(&sc.aux);
        w.y.copy_from_slice(&sc.x);
        let mut fwd = [0.0; 5];
        let mut bwd = [0.0; 5];
        let t0 = sc.t;
        let mut sys = Sys {
            jw: None,
            level: self.level.as_mut(),
            st: sc,
            ring: self.ring.as_ref(),
            rule,
            causality,
            nl,
            naux: self.n_level_aux,
            t0,
            last_error: None,
            budget: None,
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
        for k in 0..5 {
            sc.output_derivatives[I_FORCE + k] = (fwd[k] - bwd[k]) / (2.0 * DT_DERIV);
        }
        if !all_finite(&sc.outputs) || !all_finite(&sc.output_derivatives) {
            return Err(Error::StepFailed {
                t: sc.t,
                reason: "non-finite output".into(),
            });
        }
        Ok(())
    }

    /// A copy of the complete state.
    pub fn get_state(&self) -> State {
        self.state.clone()
    }

    /// The complete state (copy it into a state of the same scene with
    /// `clone_from`, which does not allocate).
    pub fn state(&self) -> &State {
        &self.state
    }

    /// Restore a state taken from this component (or one built from the same scene).
    pub fn set_state(&mut self, s: &State) -> Result<()> {
        self.check_state(s)?;
        self.state.clone_from(s);
        Ok(())
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

/// The inner ring's static equilibrium under `loads` (external, on the ring) at speed
/// `omega`: damped Newton on `F(q) + load = 0` over the level's ring coordinates with the
/// level's stiffness, moments weighed as forces at the lever `lever` (m); directions with
/// no stiffness yet (inside a clearance, an unloaded tilt) are regularised. When the full
/// load fails from the centre, the load is applied in stages (continuation). Refuses with
/// the residual when it finds no equilibrium.
fn static_start(
    level: &mut dyn LevelModel,
    dofs: &[usize],
    loads: &[f64; 5],
    omega: f64,
    lever: f64,
    x: &[f64],
    aux: &mut [f64],
) -> Result<[f64; 5]> {
    let scale = loads
        .iter()
        .enumerate()
        .map(|(d, v)| if d < 3 { v.abs() } else { v.abs() / lever })
        .sum::<f64>()
        + 1.0;
    let mut last = f64::INFINITY;
    for stages in [1usize, 4, 16] {
        let mut q = [0.0; 5];
        let mut ok = true;
        for k in 1..=stages {
            let f = k as f64 / stages as f64;
            let part: [f64; 5] = std::array::from_fn(|d| f * loads[d]);
            match newton_static(level, dofs, &part, omega, lever, x, aux, &mut q, scale) {
                Ok(r) if r <= 1e-6 * scale => last = r,
                Ok(r) => {
                    last = r;
                    ok = false;
                    break;
                }
                Err(_) => {
                    ok = false;
                    break;
                }
            }
        }
        if ok {
            return Ok(q);
        }
    }
    Err(Error::NotConverged {
        what: "static start of the load-driven inner ring (try model.start = \"rest\")",
        iterations: 100,
        residual: last,
    })
}

/// Newton iterations from `q` towards `F(q) + loads = 0`; returns the final residual (forces
/// in N, moments divided by `lever`).
#[allow(clippy::too_many_arguments)]
fn newton_static(
    level: &mut dyn LevelModel,
    dofs: &[usize],
    loads: &[f64; 5],
    omega: f64,
    lever: f64,
    x: &[f64],
    aux: &mut [f64],
    q: &mut [f64; 5],
    scale: f64,
) -> Result<f64> {
    // Scaled coordinates: translations in m, tilts times the lever.
    let w = |d: usize| if d < 3 { 1.0 } else { lever };
    let mut out = LevelOutputs::default();
    let resid = |q: &[f64; 5],
                 out: &mut LevelOutputs,
                 level: &mut dyn LevelModel,
                 aux: &mut [f64]|
     -> Result<f64> {
        let m = Motion {
            q: *q,
            v: [0.0; 5],
            omega,
        };
        level.outputs(0.0, &m, x, aux, out)?;
        Ok(dofs
            .iter()
            .map(|&d| ((out.wrench[d] + loads[d]) / w(d)).powi(2))
            .sum::<f64>()
            .sqrt())
    };
    let mut r = resid(q, &mut out, level, aux)?;
    let n = dofs.len();
    for _ in 0..100 {
        if r <= 1e-9 * scale {
            break;
        }
        let mut a = nalgebra::DMatrix::<f64>::zeros(n, n);
        let mut b = nalgebra::DVector::<f64>::zeros(n);
        let mut kmax: f64 = 0.0;
        for (i, &di) in dofs.iter().enumerate() {
            b[i] = (out.wrench[di] + loads[di]) / w(di);
            for (j, &dj) in dofs.iter().enumerate() {
                a[(i, j)] = out.k[di][dj] / (w(di) * w(dj));
                kmax = kmax.max(a[(i, j)].abs());
            }
        }
        for i in 0..n {
            a[(i, i)] += 1e-9 * kmax + 1e3;
        }
        let Some(dq) = a.lu().solve(&b) else { break };
        let mut step = 1.0;
        let mut accepted = false;
        // The last step that overshot (residual up) before one that changed nothing.
        let mut over = None;
        for _ in 0..40 {
            let mut trial = *q;
            for (i, &d) in dofs.iter().enumerate() {
                trial[d] += step * dq[i] / w(d);
            }
            if let Ok(rt) = resid(&trial, &mut out, level, aux) {
                if rt < r {
                    (*q, r, accepted) = (trial, rt, true);
                    break;
                }
                if rt == r {
                    // No contact along the whole trial (the residual is exactly the
                    // load's): the band where the contacts engage and the residual falls
                    // lies between this step and the last that overshot, narrower than a
                    // halving (a clearance's dead zone before a Hertzian rise). Bisect it:
                    // residual unchanged, go further; larger, go back.
                    if let Some(mut hi) = over {
                        let mut lo = step;
                        for _ in 0..60 {
                            let mid = 0.5 * (lo + hi);
                            let mut trial = *q;
                            for (i, &d) in dofs.iter().enumerate() {
                                trial[d] += mid * dq[i] / w(d);
                            }
                            match resid(&trial, &mut out, level, aux) {
                                Ok(rt) if rt < r => {
                                    (*q, r, accepted) = (trial, rt, true);
                                    break;
                                }
                                Ok(rt) if rt == r => lo = mid,
                                _ => hi = mid,
                            }
                        }
                    }
                    break;
                }
                over = Some(step);
            }
            step *= 0.5;
        }
        if !accepted {
            break;
        }
        resid(q, &mut out, level, aux)?;
    }
    Ok(r)
}

/// No NaN or infinity in `v`: a branch-free OR over the exponent bits (all ones for NaN
/// and inf), which the compiler vectorises; the outputs are checked after every step.
fn all_finite(v: &[f64]) -> bool {
    const EXP: u64 = 0x7ff0_0000_0000_0000;
    !v.iter()
        .fold(false, |bad, x| bad | (x.to_bits() & EXP == EXP))
}

/// The time an integration failure reached (for messages).
fn e_time(e: &SolverError) -> String {
    match e {
        SolverError::TooManySteps { t, .. }
        | SolverError::StepSizeUnderflow { t, .. }
        | SolverError::Rhs { t, .. }
        | SolverError::NonFinite { t, .. }
        | SolverError::Singular { t, .. } => format!("{t} s"),
        SolverError::Invalid { .. } => "the start".into(),
    }
}

/// Input `i` at `s` after the step start under `rule`.
fn input_at(st: &State, i: usize, s: f64, rule: InputRule) -> f64 {
    let u = st.inputs[i];
    match rule {
        InputRule::Hold => u,
        InputRule::Velocity => {
            if (I_Q..I_Q + 5).contains(&i) {
                u + st.inputs[i - I_Q + I_V] * s
            } else {
                u
            }
        }
        InputRule::Derivatives => {
            let d = &st.input_derivatives[3 * i..3 * i + 3];
            u + s * (d[0] + s * (d[1] / 2.0 + s * d[2] / 6.0))
        }
    }
}

fn motion_at(
    st: &State,
    rule: InputRule,
    s: f64,
    c: Causality,
    ring: Option<&RingBody>,
    nl: usize,
) -> Motion {
    motion_at_y(st, rule, s, c, ring, nl, &st.x)
}

/// The ring's motion at `s` after the step start: from the inputs (motion-driven) or from
/// the states `y` (load-driven).
fn motion_at_y(
    st: &State,
    rule: InputRule,
    s: f64,
    c: Causality,
    ring: Option<&RingBody>,
    nl: usize,
    y: &[f64],
) -> Motion {
    let mut m = Motion {
        omega: input_at(st, I_OMEGA, s, rule),
        ..Motion::default()
    };
    match (c, ring) {
        (Causality::Load, Some(r)) => {
            let nd = r.dofs.len();
            for (k, &d) in r.dofs.iter().enumerate() {
                m.q[d] = y[nl + k];
                m.v[d] = y[nl + nd + k];
            }
        }
        _ => {
            for k in 0..5 {
                m.q[k] = input_at(st, I_Q + k, s, rule);
                m.v[k] = input_at(st, I_V + k, s, rule);
            }
        }
    }
    m
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
        assert_eq!(variables::by_vr(variables::VR_K0).unwrap().name, "K.x.x");
        assert_eq!(variables::by_vr(variables::VR_C0).unwrap().name, "C.x.x");
        assert!(SCALARS.len() <= 64, "the inputs-set mask is a u64");
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
