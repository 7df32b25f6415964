//! The `skidding` level: ball orbit and spin, cage, traction and drag (docs/physics.md §5.2)
//! behind the level seam. States: `[(psi_j, w_b_j, w_a_j[, u_j, u_j']), theta_c, w_c]`
//! (balls first, so the Jacobian is block-arrowhead), see [`crate::models::skidding`].
//!
//! Cost at a communication point: the outputs' stiffness `-dF/dq` is analytic (one
//! right-hand side, not a Jacobian), and the last right-hand side is memoised, so the
//! component's repeated evaluations of the same point (outputs, the base of its `dF/dt`
//! difference, the next step's first stage and `df/dt`) cost nothing.

use crate::error::{Error, Result};
use crate::geometry::Bearing;
use crate::models::skidding::{BallState, SkidTotals, SkiddingModel, SkiddingParams, BALL0};
use crate::models::LevelArgs;
use crate::seam::element::ElementLoad;
use crate::seam::{Jacobians, LevelModel, LevelOutputs, Motion, Point};

/// Skidding level.
#[derive(Debug)]
pub struct SkiddingLevel {
    model: SkiddingModel,
    dofs: &'static [usize],
    last: SkidTotals,
    /// The last right-hand side and its arguments `(q, v, omega, x)`: the component
    /// evaluates the same point several times (the outputs, the base of the `dF/dt`
    /// difference, the next step's first stage), so an exact repeat is served from here.
    memo_key: Vec<f64>,
    memo_dx: Vec<f64>,
    memo_valid: bool,
}

impl SkiddingLevel {
    /// Build. Deep-groove bearings resolve the radial ring coordinates, angular-contact
    /// ones all five.
    pub fn new(b: &Bearing, p: SkiddingParams) -> Result<Self> {
        let dofs: &'static [usize] = match b.kind {
            crate::geometry::BearingKind::DeepGroove => &[0, 1],
            _ => &[0, 1, 2, 3, 4],
        };
        let model = SkiddingModel::new(b, p)?;
        let n = model.n_states();
        Ok(SkiddingLevel {
            model,
            dofs,
            last: SkidTotals::default(),
            memo_key: vec![0.0; 11 + n],
            memo_dx: vec![0.0; n],
            memo_valid: false,
        })
    }

    /// The model (per-ball results of the last evaluation in `model().balls`).
    pub fn model(&self) -> &SkiddingModel {
        &self.model
    }

    /// Per-ball slip velocities `(dv_i, dv_o)` of the last evaluation, m/s (positive: the
    /// inner race drags the ball forward / the ball slides forward over the outer race).
    pub fn slip_velocities(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.model
            .balls
            .iter()
            .map(|b: &BallState| (b.dv_i, b.dv_o))
    }

    /// Is `(m, x)` the point of the last evaluation (bit for bit)?
    fn memo_hit(&self, m: &Motion, x: &[f64]) -> bool {
        let k = &self.memo_key;
        self.memo_valid && k[..5] == m.q && k[5..10] == m.v && k[10] == m.omega && k[11..] == *x
    }

    fn memo_store(&mut self, m: &Motion, x: &[f64], dx: &[f64]) {
        let k = &mut self.memo_key;
        k[..5].copy_from_slice(&m.q);
        k[5..10].copy_from_slice(&m.v);
        k[10] = m.omega;
        k[11..].copy_from_slice(x);
        self.memo_dx.copy_from_slice(dx);
        // NaN never compares equal, so a NaN point is never served from the memo.
        self.memo_valid = true;
    }

    /// Totals of the last evaluation.
    pub fn totals(&self) -> &SkidTotals {
        &self.last
    }

    /// Set the worn depth of the outer race per cell, m (`crate::models::wear_map`); an
    /// empty map is the unworn race. Errors name `wear map` when a depth is negative or not
    /// finite; nothing changes then.
    pub fn set_outer_wear(&mut self, map: &[f64]) -> Result<()> {
        if let Some(&d) = map.iter().find(|d| !(d.is_finite() && **d >= 0.0)) {
            return Err(Error::invalid("wear map (m)", d, "finite depths >= 0"));
        }
        self.model.p.outer_wear = map.to_vec();
        self.memo_valid = false;
        Ok(())
    }
}

/// The registry's check of the scene's `[model.skidding]` options against the bearing.
pub fn check(a: &LevelArgs) -> Result<()> {
    a.skidding.params(a.bearing).map(|_| ())
}

/// The registry's constructor (the level registry, `LEVELS` in `component/levels.rs`): the scene's
/// `[model.skidding]` options with its contact damping.
pub fn build(a: &LevelArgs) -> Result<Box<dyn LevelModel>> {
    let mut p = a.skidding.params(a.bearing)?;
    p.contact_damping = a.contact_damping;
    Ok(Box::new(SkiddingLevel::new(a.bearing, p)?))
}

impl LevelModel for SkiddingLevel {
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        Some(self)
    }
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
    fn rhs_time_invariant(&self) -> bool {
        // `rhs` reads the motion and the states, never `Point::t`; what it keeps (the
        // balls' last contact states, the memo of the last point) is overwritten by every
        // evaluation and read only by the outputs.
        true
    }
    fn ring_dofs(&self) -> &'static [usize] {
        self.dofs
    }
    fn blocks(&self) -> Option<(usize, usize)> {
        // One independent 3-state block per ball, then the cage (and the ring) as border.
        Some((self.model.z(), self.model.ball_states()))
    }
    fn state_atol(&self, atol_m: f64, atol: &mut [f64]) -> bool {
        // Angles: a ball-surface error of atol_m; speeds: that error over a 1 kHz period.
        let angle = atol_m / (0.5 * self.model.d_ball());
        let rate = angle * 2.0 * std::f64::consts::PI * 1e3;
        let ic = self.model.cage_index();
        atol[ic] = angle;
        atol[ic + 1] = rate;
        let bs = self.model.ball_states();
        for j in 0..self.model.z() {
            let k = BALL0 + bs * j;
            atol[k] = angle;
            atol[k + 1] = rate;
            atol[k + 2] = rate;
            if bs == 5 {
                // The ball's radial position and its rate.
                atol[k + 3] = atol_m;
                atol[k + 4] = atol_m * 2.0 * std::f64::consts::PI * 1e3;
            }
        }
        true
    }
    fn jacobian(&mut self, p: Point<'_>, j: Jacobians<'_>) -> bool {
        let (Point { m, x, .. }, Jacobians { jx, jm, wx, wm }) = (p, j);
        // `wx` and `wm` lent, not given: the radial level clears rows of them below.
        let jac = Jacobians {
            jx,
            jm,
            wx: &mut *wx,
            wm: &mut *wm,
        };
        self.model.jacobian(m, x, jac, self.dofs);
        if self.dofs.len() == 2 && !wm.is_empty() {
            // The radial level reports no axial force or moments.
            let n = wx.len() / 5;
            wx[2 * n..].fill(0.0);
            wm[20..].fill(0.0);
        }
        true
    }
    fn init(&mut self, m: &Motion, x: &mut [f64], _aux: &mut [f64]) -> Result<()> {
        if !m.omega.is_finite() {
            return Err(Error::invalid("shaft.omega", m.omega, "a finite number"));
        }
        self.model.init_at(&m.q, m.omega, x);
        Ok(())
    }
    fn rhs(&mut self, p: Point<'_>, dx: &mut [f64], wrench: Option<&mut [f64; 5]>) -> Result<()> {
        let Point { m, x, .. } = p;
        let tot = if self.memo_hit(m, x) {
            dx.copy_from_slice(&self.memo_dx);
            self.last
        } else {
            let tot = self.model.eval(&m.q, &m.v, m.omega, x, dx);
            self.memo_store(m, x, dx);
            tot
        };
        if let Some(w) = wrench {
            *w = tot.wrench;
            if self.dofs.len() == 2 {
                w[2..].fill(0.0);
            }
        }
        self.last = tot;
        Ok(())
    }
    fn outputs(&mut self, p: Point<'_>, out: &mut LevelOutputs) -> Result<()> {
        let Point { m, x, .. } = p;
        let n = self.model.n_states();
        // Fixed-size scratch (no allocation) for the rates.
        let mut buf = [0.0; 2 + 5 * MAX_BALLS];
        if n > buf.len() {
            return Err(Error::invalid(
                "bearing.ball_count",
                self.model.z(),
                "<= 64 for the skidding level",
            ));
        }
        // The rates, the wrench and its stiffness -dF/dq and damping -dF/dv at the current
        // ball positions (balls held), analytically in one pass.
        let mut kf = [[0.0; 5]; 5];
        let mut cf = [[0.0; 5]; 5];
        let tot = self
            .model
            .eval_with_stiffness(m, x, &mut buf[..n], &mut kf, &mut cf);
        self.memo_store(m, x, &buf[..n]);
        self.last = tot;
        let mut w = tot.wrench;
        if self.dofs.len() == 2 {
            w[2..].fill(0.0);
        }
        let (wk, _) = self.model.kinematic(m.omega);
        // 1 - w_c/w_k, regularised below 1 mrad/s of kinematic cage speed so that a
        // bearing at rest reports 100 % slip and the output stays finite.
        let eps = 1e-3;
        let w_c = x[self.model.cage_index() + 1];
        let slip = 1.0 - w_c * wk / (wk * wk + eps * eps);
        // The peak pressure grows with the load (as its cube root), so the largest is that
        // of the largest inner or outer load: two cube roots, not two per ball.
        let (mut q_i_max, mut q_o_max) = (0.0f64, 0.0f64);
        let mut pocket: f64 = 0.0;
        for b in &self.model.balls {
            pocket = pocket.max(b.pocket.abs());
            q_i_max = q_i_max.max(b.q_i);
            q_o_max = q_o_max.max(b.q_o);
        }
        let max_p = self.model.peak_pressure(q_i_max, q_o_max);
        let mut k = [[0.0; 5]; 5];
        let mut c = [[0.0; 5]; 5];
        for &r in self.dofs {
            for &col in self.dofs {
                k[r][col] = kf[r][col];
                c[r][col] = cf[r][col];
            }
        }
        *out = LevelOutputs {
            wrench: w,
            k,
            c,
            torque: tot.torque_shaft,
            cage_omega: w_c,
            cage_slip: slip,
            balls_loaded: tot.loaded as f64,
            max_load: tot.max_load,
            max_pressure: max_p,
            power_loss: -tot.torque_shaft * m.omega,
            pocket_force: pocket,
            ..LevelOutputs::default()
        };
        Ok(())
    }
}

/// Most balls the level's output scratch holds.
pub const MAX_BALLS: usize = 64;
