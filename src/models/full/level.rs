//! The `full` level: high-speed dynamics with cage whirl (docs/physics.md §5.5, study \[0\])
//! behind the level seam. States and physics: [`crate::models::full`].
//!
//! Memory (`aux`, in the component state so a restored state continues bit for bit): the
//! quasi-static ball positions' warm starts (`X1, X2, flag` per ball).
//!
//! Jacobian: the model's per-ball block differences ([`FullModel::jacobian`]), with the
//! ring columns and wrench rows when load-driven.
//! RODAS4 is the level's default integrator (`solver.method = "auto"`).
//!
//! Outputs: stiffness `K = -dF/dq` and damping `C = -dF/dv` by forward differences of the
//! wrench with the level's states held (the quasi-static ball positions re-solved: they
//! are not states), on a scratch copy of `aux` so that the outputs never change the run.
//! After a step they are left for the first read of one of them
//! ([`LevelModel::outputs_deferring_matrices`]): ten wrench evaluations that a host reading
//! forces only does not pay for.

use crate::error::{Error, Result};
use crate::geometry::kinematics::nominal_cage_speed as cage_speed;
use crate::geometry::Bearing;
use crate::models::full::{FullModel, FullParams, Totals};
use crate::models::LevelArgs;
use crate::seam::element::ElementLoad;
use crate::seam::{Jacobians, LevelModel, LevelOutputs, Motion, Point};

/// The level.
#[derive(Debug)]
pub struct FullLevel {
    model: FullModel,
    kin_ratio: f64,
    guide_clearance: f64,
    last: Totals,
    /// Scratch (allocated once): rates and aux for the output differences.
    dx: Vec<f64>,
    aux: Vec<f64>,
    aux_k: Vec<f64>,
    /// Jacobian scratch (`3 n + n_aux`).
    jscratch: Vec<f64>,
    /// The last right-hand side: its motion, states, `aux` as it left it, rates and
    /// totals (its race parts are kept in the model). The integrator asks for the Jacobian
    /// right after the right-hand side at the same point, which then needs no evaluation
    /// at `x` of its own.
    last_rhs: Option<(Motion, Totals)>,
    last_x: Vec<f64>,
    last_aux: Vec<f64>,
    last_dx: Vec<f64>,
}

impl FullLevel {
    /// Build.
    pub fn new(b: &Bearing, p: FullParams) -> Result<Self> {
        let model = FullModel::new(b, p)?;
        let (n, na) = (model.n_states(), model.n_aux());
        Ok(FullLevel {
            model,
            kin_ratio: cage_speed(b, 1.0),
            guide_clearance: b.cage.guide_clearance,
            last: Totals::default(),
            dx: vec![0.0; n],
            aux: vec![0.0; na],
            aux_k: vec![0.0; na],
            jscratch: vec![0.0; 3 * n + na],
            last_rhs: None,
            last_x: vec![0.0; n],
            last_aux: vec![0.0; na],
            last_dx: vec![0.0; n],
        })
    }

    /// The model (per-ball results of the last evaluation in `model().balls`).
    pub fn model(&self) -> &FullModel {
        &self.model
    }

    /// Totals of the last evaluation.
    pub fn totals(&self) -> &Totals {
        &self.last
    }
}

/// The registry's constructor (the level registry, `LEVELS` in `component/levels.rs`): the scene's
/// `[model.full]` options with its race control.
pub fn build(a: &LevelArgs) -> Result<Box<dyn LevelModel>> {
    let b = a.bearing;
    Ok(Box::new(FullLevel::new(
        b,
        a.full.params(b, a.race_control)?,
    )?))
}

impl LevelModel for FullLevel {
    /// Its balls are its own state: nothing more to keep.
    fn keep_element_loads(&mut self) -> bool {
        true
    }
    /// The model's own per-ball loads at its last evaluation (the current state's: the
    /// outputs evaluate it last, after their perturbed evaluations).
    fn element_loads(&self, out: &mut Vec<ElementLoad>) -> bool {
        out.clear();
        out.extend(self.model.balls.iter().map(|b| ElementLoad {
            psi: b.psi,
            inner: b.q_i,
            outer: b.q_o,
        }));
        true
    }
    fn n_states(&self) -> usize {
        self.model.n_states()
    }
    fn n_aux(&self) -> usize {
        self.model.n_aux()
    }
    fn blocks(&self) -> Option<(usize, usize)> {
        self.model.blocks()
    }
    fn block_head(&self) -> usize {
        self.model.ball0()
    }
    fn follow_ring(&mut self, m: &Motion, x: &mut [f64]) -> Result<bool> {
        self.model.place_balls(&m.q, x)
    }
    fn state_atol(&self, atol_m: f64, atol: &mut [f64]) -> bool {
        // Nondimensional states: one tolerance, a length atol_m in units of D/2 (and the
        // same number for the scaled rates and angles).
        let (l, _) = self.model.scales();
        atol.fill(atol_m / l);
        true
    }
    fn jacobian(&mut self, p: Point<'_>, j: Jacobians<'_>) -> bool {
        let Point { m, x, aux, .. } = p;
        let kept = match &self.last_rhs {
            Some((lm, tot)) if lm == m && self.last_x == x && self.last_aux == aux => {
                Some((&self.last_dx[..], tot))
            }
            _ => None,
        };
        // With ball blocks the solver reads only the blocks and the border
        // ([`LevelModel::blocks`]): the entries coupling two balls are left.
        self.model
            .jacobian_from(m, x, aux, j, &mut self.jscratch, kept, false)
            .is_ok()
    }
    fn init(&mut self, m: &Motion, x: &mut [f64], aux: &mut [f64]) -> Result<()> {
        if !m.omega.is_finite() {
            return Err(Error::invalid("shaft.omega", m.omega, "a finite number"));
        }
        self.model.init(&m.q, m.omega, x, aux)
    }
    fn rhs(&mut self, p: Point<'_>, dx: &mut [f64], wrench: Option<&mut [f64; 5]>) -> Result<()> {
        let Point { m, x, aux, .. } = p;
        self.last_rhs = None;
        let tot = self.model.eval_keep(m, x, aux, dx)?;
        self.last_x.copy_from_slice(x);
        self.last_aux.copy_from_slice(aux);
        self.last_dx.copy_from_slice(dx);
        self.last_rhs = Some((*m, tot));
        if let Some(w) = wrench {
            *w = tot.wrench;
        }
        self.last = tot;
        Ok(())
    }
    fn outputs(&mut self, p: Point<'_>, out: &mut LevelOutputs) -> Result<()> {
        let Point { m, x, aux, .. } = p;
        self.outputs_but_matrices(m, x, aux, out)?;
        self.matrices_at(m, x, aux, &mut out.k, &mut out.c)
    }
    /// Everything but `K` and `C`, which [`LevelModel::matrices`] gives at the same point
    /// with the same bits (they cost ten wrench evaluations, five of them re-solving every
    /// ball's position: read by few hosts).
    fn outputs_deferring_matrices(&mut self, p: Point<'_>, out: &mut LevelOutputs) -> Result<bool> {
        let Point { m, x, aux, .. } = p;
        self.outputs_but_matrices(m, x, aux, out)?;
        Ok(true)
    }
    fn matrices(
        &mut self,
        p: Point<'_>,
        k: &mut [[f64; 5]; 5],
        c: &mut [[f64; 5]; 5],
    ) -> Result<()> {
        let Point { m, x, aux, .. } = p;
        self.matrices_at(m, x, aux, k, c)
    }
}

impl FullLevel {
    /// The outputs at motion `m`, states `x` and memory `aux` (left as it is) but the
    /// stiffness and damping (`out.k`, `out.c` zero): the unperturbed evaluation, on a
    /// scratch copy of `aux`, whose per-ball results the model keeps.
    fn outputs_but_matrices(
        &mut self,
        m: &Motion,
        x: &[f64],
        aux: &[f64],
        out: &mut LevelOutputs,
    ) -> Result<()> {
        self.aux.copy_from_slice(aux);
        let tot = self
            .model
            .eval(&m.q, &m.v, m.omega, x, &mut self.aux, &mut self.dx)?;
        self.last = tot;
        let wk = self.kin_ratio * m.omega;
        let wc = self.model.cage_omega(x);
        // 1 - w_c/w_k, regularised below 1 mrad/s of kinematic cage speed (as the skidding
        // level): a bearing at rest reports 100 % slip and the output stays finite.
        let eps = 1e-3;
        let slip = 1.0 - wc * wk / (wk * wk + eps * eps);
        let (cxy, cspeed) = self.model.cage_centre(x);
        *out = LevelOutputs {
            wrench: tot.wrench,
            torque: tot.torque_shaft,
            cage_omega: wc,
            cage_slip: slip,
            balls_loaded: tot.loaded as f64,
            max_load: tot.max_load,
            max_pressure: tot.max_pressure,
            power_loss: -tot.torque_shaft * m.omega,
            cage_xy: [cxy[0] / self.guide_clearance, cxy[1] / self.guide_clearance],
            cage_speed: cspeed,
            pocket_force: tot.pocket_max,
            guide_force: tot.guide_force,
            ..LevelOutputs::default()
        };
        Ok(())
    }

    /// `K` and `C` at motion `m`, states `x` and memory `aux` (left as it is) by forward
    /// differences of the wrench, states held. The unperturbed evaluation (on a scratch
    /// copy of `aux`; the last one's numbers when it was at this point) gives the wrench
    /// they difference against; the perturbed ones compute the wrench alone
    /// ([`FullModel::wrench_at`]), each from the same warm starts, so the order changes no
    /// number: a displacement column re-solves the ball positions from them, a velocity
    /// column keeps the positions of the unperturbed evaluation (a velocity does not move
    /// them).
    fn matrices_at(
        &mut self,
        m: &Motion,
        x: &[f64],
        aux: &[f64],
        k: &mut [[f64; 5]; 5],
        c: &mut [[f64; 5]; 5],
    ) -> Result<()> {
        const STEPS: [f64; 10] = [1e-9, 1e-9, 1e-9, 1e-7, 1e-7, 1e-6, 1e-6, 1e-6, 1e-5, 1e-5];
        self.aux.copy_from_slice(aux);
        let tot = self
            .model
            .eval(&m.q, &m.v, m.omega, x, &mut self.aux, &mut self.dx)?;
        let mut perturbed = [[0.0; 5]; 10];
        for (col, (h, w)) in STEPS.iter().zip(perturbed.iter_mut()).enumerate() {
            let (mut q, mut v) = (m.q, m.v);
            *w = if col < 5 {
                q[col] += h;
                self.aux_k.copy_from_slice(aux);
                self.model
                    .wrench_at(&q, &v, m.omega, x, &mut self.aux_k, true)?
            } else {
                v[col - 5] += h;
                self.model
                    .wrench_at(&q, &v, m.omega, x, &mut self.aux, false)?
            };
        }
        for (col, (h, w)) in STEPS.iter().zip(&perturbed).enumerate() {
            for r in 0..5 {
                let d = -(w[r] - tot.wrench[r]) / h;
                if col < 5 {
                    k[r][col] = d;
                } else {
                    c[r][col - 5] = d;
                }
            }
        }
        self.last = tot;
        Ok(())
    }
}
