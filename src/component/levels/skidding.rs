//! The `skidding` level: ball orbit and spin, cage, traction and drag (physics.md §5.2)
//! behind the level seam. States: `[theta_c, w_c, (psi_j, w_b_j, w_a_j)]`, see
//! [`crate::models::skidding`].

use crate::component::level::{LevelModel, LevelOutputs, Motion};
use crate::error::{Error, Result};
use crate::geometry::Bearing;
use crate::models::skidding::{BallState, SkidTotals, SkiddingModel, SkiddingParams, BALL0};

/// Skidding level.
#[derive(Debug)]
pub struct SkiddingLevel {
    model: SkiddingModel,
    dofs: &'static [usize],
    last: SkidTotals,
    /// Jacobian scratch for the outputs' stiffness and damping (allocated once).
    jx: Vec<f64>,
    jm: Vec<f64>,
    wx: Vec<f64>,
    wm: Vec<f64>,
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
            jx: vec![0.0; n * n],
            jm: vec![0.0; n * 10],
            wx: vec![0.0; 5 * n],
            wm: vec![0.0; 50],
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

    /// Totals of the last evaluation.
    pub fn totals(&self) -> &SkidTotals {
        &self.last
    }
}

impl LevelModel for SkiddingLevel {
    fn name(&self) -> &'static str {
        "skidding"
    }
    fn n_states(&self) -> usize {
        self.model.n_states()
    }
    fn ring_dofs(&self) -> &'static [usize] {
        self.dofs
    }
    fn state_atol(&self, atol_m: f64, atol: &mut [f64]) -> bool {
        // Angles: a ball-surface error of atol_m; speeds: that error over a 1 kHz period.
        let angle = atol_m / (0.5 * self.model.d_ball());
        let rate = angle * 2.0 * std::f64::consts::PI * 1e3;
        atol[0] = angle;
        atol[1] = rate;
        for j in 0..self.model.z() {
            let k = BALL0 + 3 * j;
            atol[k] = angle;
            atol[k + 1] = rate;
            atol[k + 2] = rate;
        }
        true
    }
    fn jacobian(
        &mut self,
        _t: f64,
        m: &Motion,
        x: &[f64],
        _aux: &mut [f64],
        jx: &mut [f64],
        jm: &mut [f64],
        wx: &mut [f64],
        wm: &mut [f64],
    ) -> bool {
        self.model
            .jacobian(&m.q, &m.v, m.omega, x, jx, jm, wx, wm, self.dofs);
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
        self.model.init(m.omega, x);
        Ok(())
    }
    fn rhs(
        &mut self,
        _t: f64,
        m: &Motion,
        x: &[f64],
        _aux: &mut [f64],
        dx: &mut [f64],
        wrench: Option<&mut [f64; 5]>,
    ) -> Result<()> {
        let tot = self.model.eval(&m.q, &m.v, m.omega, x, dx);
        if let Some(w) = wrench {
            *w = tot.wrench;
            if self.dofs.len() == 2 {
                w[2..].fill(0.0);
            }
        }
        self.last = tot;
        Ok(())
    }
    fn outputs(
        &mut self,
        t: f64,
        m: &Motion,
        x: &[f64],
        aux: &mut [f64],
        out: &mut LevelOutputs,
    ) -> Result<()> {
        // dx is not needed: evaluate into a stack buffer of the cage part only is not
        // possible (the model writes all rates), so reuse the balls' scratch via rhs.
        let mut w = [0.0; 5];
        let n = self.model.n_states();
        // Fixed-size scratch (no allocation): rates are discarded.
        let mut buf = [0.0; 2 + 3 * MAX_BALLS];
        if n > buf.len() {
            return Err(Error::invalid(
                "bearing.ball_count",
                self.model.z(),
                "<= 64 for the skidding level",
            ));
        }
        self.rhs(t, m, x, aux, &mut buf[..n], Some(&mut w))?;
        let tot = self.last;
        let (wk, _) = self.model.kinematic(m.omega);
        // 1 - w_c/w_k, regularised below 1 mrad/s of kinematic cage speed so that a
        // bearing at rest reports 100 % slip and the output stays finite.
        let eps = 1e-3;
        let slip = 1.0 - x[1] * wk / (wk * wk + eps * eps);
        let mut max_p: f64 = 0.0;
        let mut pocket: f64 = 0.0;
        for b in &self.model.balls {
            pocket = pocket.max(b.pocket.abs());
            if b.q_i > 0.0 || b.q_o > 0.0 {
                max_p = max_p.max(self.model.peak_pressure(b.q_i, b.q_o));
            }
        }
        // Stiffness -dF/dq and damping -dF/dv at the current ball positions (balls held).
        self.model.jacobian(
            &m.q,
            &m.v,
            m.omega,
            x,
            &mut self.jx,
            &mut self.jm,
            &mut self.wx,
            &mut self.wm,
            self.dofs,
        );
        let mut k = [[0.0; 5]; 5];
        let mut c = [[0.0; 5]; 5];
        for &r in self.dofs {
            for &col in self.dofs {
                k[r][col] = -self.wm[r * 10 + col];
                c[r][col] = -self.wm[r * 10 + 5 + col];
            }
        }
        *out = LevelOutputs {
            wrench: w,
            k,
            c,
            torque: tot.torque_shaft,
            cage_omega: x[1],
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
