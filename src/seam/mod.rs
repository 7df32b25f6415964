//! The seam between the component and the physics: every model level implements
//! [`LevelModel`]. The component owns time, inputs, the integrator, transactions and the
//! variable table; a level owns its states and its physics. A new level (skidding, full
//! dynamics) or effect (defects, waviness, EHL, wear, thermal) plugs in here and is seen
//! by the C ABI and the FMUs without any change to them.

pub mod element;
pub mod fields;

use crate::error::Result;

/// The inner ring's motion at one instant (SI): displacement `q = (x, y, z, rx, ry)`, its
/// rate `v`, and the spin speed `omega`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Motion {
    /// Displacement and tilts.
    pub q: [f64; 5],
    /// Velocities and tilt rates.
    pub v: [f64; 5],
    /// Spin speed about z, rad/s.
    pub omega: f64,
}

/// Where a level is evaluated: time `t`, the ring's motion `m`, the level's states `x` and
/// its memory `aux` (warm starts, which the evaluation may update).
#[derive(Debug)]
pub struct Point<'a> {
    /// Time, s.
    pub t: f64,
    /// The ring's motion.
    pub m: &'a Motion,
    /// The level's states (length `n_states`).
    pub x: &'a [f64],
    /// The level's memory (length `n_aux`).
    pub aux: &'a mut [f64],
}

impl<'a> Point<'a> {
    /// The point `(t, m, x, aux)`.
    pub fn new(t: f64, m: &'a Motion, x: &'a [f64], aux: &'a mut [f64]) -> Self {
        Point { t, m, x, aux }
    }
}

/// The Jacobians a level fills ([`LevelModel::jacobian`]). With `n = n_states`, all
/// row-major: `jx = d(rates)/d(states)` (`n × n`), `jm = d(rates)/d(q, v)` (`n × 10`),
/// `wx = d(wrench)/d(states)` (`5 × n`), `wm = d(wrench)/d(q, v)` (`5 × 10`).
/// Motion-driven, `jm`, `wx` and `wm` are empty (not needed).
#[derive(Debug)]
pub struct Jacobians<'a> {
    /// `d(rates)/d(states)`.
    pub jx: &'a mut [f64],
    /// `d(rates)/d(q, v)`.
    pub jm: &'a mut [f64],
    /// `d(wrench)/d(states)`.
    pub wx: &'a mut [f64],
    /// `d(wrench)/d(q, v)`.
    pub wm: &'a mut [f64],
}

/// What a level reports at a communication point. Fields a level does not model stay 0.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LevelOutputs {
    /// `(Fx, Fy, Fz, Mx, My)` on the shaft.
    pub wrench: [f64; 5],
    /// Friction torque on the shaft about z, N m.
    pub torque: f64,
    /// Stiffness `-dF/dq`.
    pub k: [[f64; 5]; 5],
    /// Damping `-dF/dv`.
    pub c: [[f64; 5]; 5],
    /// Cage speed, rad/s.
    pub cage_omega: f64,
    /// Cage slip ratio.
    pub cage_slip: f64,
    /// Balls in contact.
    pub balls_loaded: f64,
    /// Largest contact load, N.
    pub max_load: f64,
    /// Largest Hertz peak pressure, Pa.
    pub max_pressure: f64,
    /// Thinnest EHL film, m.
    pub film_min: f64,
    /// Friction power, W.
    pub power_loss: f64,
    /// Deepest wear, m.
    pub wear_max: f64,
    /// Cage-centre displacement `(x, y)` in units of the guide clearance.
    pub cage_xy: [f64; 2],
    /// Speed of the cage centre, m/s.
    pub cage_speed: f64,
    /// Largest ball-pocket force, N.
    pub pocket_force: f64,
    /// Cage guide-land force, N.
    pub guide_force: f64,
}

/// What an assembly of rows (a bearing set, [`crate::models::set::level`]) reports of one
/// row at its last [`LevelModel::outputs`] (SI).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RowOutputs {
    /// Forces and moments of the row on the shaft at the row's centre, in the shaft's
    /// frame `(Fx, Fy, Fz, Mx, My)`.
    pub force: [f64; 5],
    /// The same in the row's own frame (mirrored for a row facing `-z`): what the row's
    /// ratings read.
    pub local: [f64; 5],
    /// Load-weighted mean inner contact angle of the row's loaded elements, rad.
    pub contact_angle: f64,
    /// Elements in contact.
    pub loaded: f64,
    /// Largest contact pressure, Pa.
    pub max_pressure: f64,
}

/// One model level.
pub trait LevelModel: Send + std::fmt::Debug {
    /// Number of continuous states the level integrates (cage angle, ball states, ...).
    fn n_states(&self) -> usize;
    /// Number of algebraic/memory values (warm starts) kept in the component state.
    fn n_aux(&self) -> usize {
        0
    }
    /// The level as `Any`, for a caller that knows a concrete level (the wear cycles take
    /// the skidding level's per-ball contacts and outer-race wear profile); `None`
    /// (default) for levels nobody needs to see.
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        None
    }
    /// Keep the rolling elements' contact loads of every later [`LevelModel::outputs`] for
    /// [`LevelModel::element_loads`]; `false` (the default) when the level does not resolve
    /// its elements one by one. Called before a run, never in a step: a level allocates
    /// what it keeps here, and a level never asked computes and stores nothing for it.
    fn keep_element_loads(&mut self) -> bool {
        false
    }
    /// The rolling elements' contact loads at the last [`LevelModel::outputs`], one per
    /// element in element order, into `out` (cleared first; its allocation reused):
    /// read-only, nothing evaluated. `false`, with `out` empty, when the level has none:
    /// it does not resolve its elements, or it keeps them only when asked
    /// ([`LevelModel::keep_element_loads`]) and was not. The default: none.
    fn element_loads(&self, out: &mut Vec<element::ElementLoad>) -> bool {
        out.clear();
        false
    }
    /// Per-row outputs of an assembly of rows at its last [`LevelModel::outputs`]; empty
    /// (the default) for one bearing, which pays nothing for them.
    fn rows(&self) -> &[RowOutputs] {
        &[]
    }
    /// Which ring coordinates the level resolves (load-driven integrates only these).
    fn ring_dofs(&self) -> &'static [usize] {
        &[0, 1, 2, 3, 4]
    }
    /// Block structure of the level's states for a structured linear solver: `Some((nb,
    /// s))` when `nb·s` states (the first ones, or those after [`LevelModel::block_head`])
    /// form `nb` independent blocks of `s` (no rate of one block depends on another
    /// block's states) and the rest, with the ring's states, form the border ([`crate::solver::BlockArrowhead`]). `None` (default): dense.
    fn blocks(&self) -> Option<(usize, usize)> {
        None
    }
    /// Move the level's position states to where they rest at the ring motion `m`, the
    /// speeds kept (the full level's balls with dynamic contacts: their radial and axial
    /// positions in the balance of their race loads and centrifugal force). The
    /// load-driven static start does so at every trial displacement, so that its
    /// equilibrium is the whole bearing's, not the ring's against balls frozen where the
    /// ring was at rest, and the run starts from the states there. `Ok(false)` (the
    /// default): the level has no such states (or re-solves its positions itself), nothing
    /// changed.
    fn follow_ring(&mut self, _m: &Motion, _x: &mut [f64]) -> Result<bool> {
        Ok(false)
    }
    /// With [`LevelModel::blocks`]: how many of the level's states come before the blocks
    /// (a head, in the border with the states after the blocks; the full level's cage).
    /// The blocks are then states `h .. h + nb·s`. Default 0: the blocks come first.
    fn block_head(&self) -> usize {
        0
    }
    /// Absolute tolerances of the level's states, given the scene's displacement
    /// tolerance `atol_m`: fill `atol` (length `n_states`) and return `true`, or return
    /// `false` (the default) to let the component treat every state as an angle.
    fn state_atol(&self, _atol_m: f64, _atol: &mut [f64]) -> bool {
        false
    }
    /// Jacobians of the level at `p` into `j` (optional; `false`, the default, lets the
    /// integrator difference the whole right-hand side). Must not allocate.
    fn jacobian(&mut self, _p: Point<'_>, _j: Jacobians<'_>) -> bool {
        false
    }
    /// Whether the states' rates depend on the motion inputs (and time) only, never on the
    /// states or the level's memory: then a motion-driven step integrates them by
    /// quadrature instead of an adaptive integrator (the cage angle at a fixed ratio of the
    /// shaft speed). Default `false`.
    fn states_are_quadrature(&self) -> bool {
        false
    }
    /// Whether the rates and the wrench at a point are a function of the motion, the
    /// states and the memory alone: not of the time `p.t`, no memory outside `aux`, and
    /// `rhs` writes nothing in `aux`. Then, with inputs that do not move within a step:
    /// `∂f/∂t` is exactly zero (the component gives the Rosenbrock methods zeros instead
    /// of a forward difference that would give them too), and DOPRI5 may start a step with
    /// the last stage of the step before (first same as last across steps) when nothing
    /// that stage read changed since. Both give the same bits one evaluation cheaper.
    /// Default `false`.
    fn rhs_time_invariant(&self) -> bool {
        false
    }
    /// Initial states at the start motion.
    fn init(&mut self, m: &Motion, x: &mut [f64], aux: &mut [f64]) -> Result<()>;
    /// Time derivatives of the level's states at `p`; when `wrench` is given, also the
    /// force and moment on the shaft. Must not allocate.
    fn rhs(&mut self, p: Point<'_>, dx: &mut [f64], wrench: Option<&mut [f64; 5]>) -> Result<()>;
    /// [`LevelModel::rhs`] at the end of an integration's last step, where the component
    /// evaluates the outputs next: a level may keep what it evaluates there for
    /// [`LevelModel::outputs`] at the same point. The rates and the wrench must be those of
    /// `rhs`. Default: `rhs`.
    fn rhs_at_end(
        &mut self,
        p: Point<'_>,
        dx: &mut [f64],
        wrench: Option<&mut [f64; 5]>,
    ) -> Result<()> {
        self.rhs(p, dx, wrench)
    }
    /// Everything the level reports at `p`. Must not allocate.
    fn outputs(&mut self, p: Point<'_>, out: &mut LevelOutputs) -> Result<()>;
    /// [`LevelModel::outputs`] at the end of a step, where a level may leave the stiffness
    /// and damping matrices out (`out.k`, `out.c` zero) when it can give them later by
    /// [`LevelModel::matrices`] at the same point, bit for bit as `outputs` computes them:
    /// the component then asks for them only when a host reads one. Returns whether it left
    /// them out. Default: `outputs`, `false`.
    fn outputs_deferring_matrices(&mut self, p: Point<'_>, out: &mut LevelOutputs) -> Result<bool> {
        self.outputs(p, out)?;
        Ok(false)
    }
    /// The stiffness and damping matrices [`LevelModel::outputs`] gives at `p` (the
    /// states, memory and inputs those of a [`LevelModel::outputs_deferring_matrices`]
    /// that left them out), into `k` and `c`; `p.aux` left as it was. Asked only of a
    /// level whose `outputs_deferring_matrices` can return `true`; the default computes
    /// every output and keeps these. Must not allocate.
    fn matrices(
        &mut self,
        p: Point<'_>,
        k: &mut [[f64; 5]; 5],
        c: &mut [[f64; 5]; 5],
    ) -> Result<()> {
        let mut o = LevelOutputs::default();
        self.outputs(p, &mut o)?;
        (*k, *c) = (o.k, o.c);
        Ok(())
    }
    /// The wrench at each of `p`'s points into `out[k]` (zeros on entry), bit for bit as
    /// [`LevelModel::rhs`] gives it there, for the outputs between an integration's stops
    /// (the rates are not wanted: `dx`, of `n_states`, is scratch). Asked only of a level
    /// without memory (`n_aux = 0`). Default: `rhs` at each point ([`wrenches_by_rhs`]);
    /// a level overrides it where one call for many points saves its dispatch.
    fn wrenches(&mut self, p: Points<'_>, dx: &mut [f64], out: &mut [[f64; 5]]) -> Result<()> {
        wrenches_by_rhs(self, p, dx, out)
    }
}

/// The points of [`LevelModel::wrenches`]: point `k` at time `t[k]` with motion `m[k]` and
/// the level's states `x[k * stride..][..n_states]`.
#[derive(Debug, Clone, Copy)]
pub struct Points<'a> {
    /// Times, s.
    pub t: &'a [f64],
    /// The ring's motion at each point.
    pub m: &'a [Motion],
    /// The level's states, one row of `stride` per point.
    pub x: &'a [f64],
    /// Values per row of `x`.
    pub stride: usize,
}

/// [`LevelModel::wrenches`] by one [`LevelModel::rhs`] per point.
pub fn wrenches_by_rhs<L: LevelModel + ?Sized>(
    level: &mut L,
    p: Points<'_>,
    dx: &mut [f64],
    out: &mut [[f64; 5]],
) -> Result<()> {
    let nl = level.n_states();
    for (k, (w, m)) in out.iter_mut().zip(p.m).enumerate() {
        let x = &p.x[k * p.stride..k * p.stride + nl];
        level.rhs(Point::new(p.t[k], m, x, &mut []), &mut dx[..nl], Some(w))?;
    }
    Ok(())
}
