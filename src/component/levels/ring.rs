//! The `ring` level: ring on massless balls (physics.md §5.1) behind the level seam, with
//! the optional effects of the scene (defects, waviness, spacing scatter, EHL film).

use super::cage_speed;
use crate::component::level::{LevelModel, LevelOutputs, Motion};
use crate::error::Result;
use crate::geometry::Bearing;
use crate::models::effects::{Effects, RingEffects};
use crate::models::ring::{RingDof, RingEval, RingModel};

/// Ring on massless balls (physics.md §5.1). States: the cage angle, and the shaft angle
/// when an effect turns with the shaft or the balls (inner-race or ball defects/waviness).
#[derive(Debug)]
pub struct RingLevel {
    model: RingModel,
    cage_ratio: f64,
    dof: RingDof,
    eval: RingEval,
    /// Defects and waviness (None: no profile, nothing evaluated).
    profile: Option<RingEffects>,
    /// Whether state 1 is the shaft angle.
    shaft_angle: bool,
}

impl RingLevel {
    /// Build without effects.
    pub fn new(b: &Bearing, dof: RingDof, damping: f64) -> Self {
        RingLevel {
            model: RingModel::new(b, dof, damping),
            cage_ratio: cage_speed(b, 1.0),
            dof,
            eval: RingEval::default(),
            profile: None,
            shaft_angle: false,
        }
    }

    /// Build with the scene's effects (validated here against the bearing).
    pub fn with_effects(b: &Bearing, dof: RingDof, damping: f64, e: &Effects) -> Result<Self> {
        let mut level = RingLevel::new(b, dof, damping);
        if e.is_off() {
            e.validate_for(b)?;
            return Ok(level);
        }
        let mut fx = RingEffects::new(e, b)?;
        let mut model = RingModel::new(b, dof, damping);
        if !fx.spacing.is_empty() {
            model = model.with_spacing(std::mem::take(&mut fx.spacing));
        }
        if let Some(l) = fx.lubricant {
            model = model.with_film(l);
        }
        level.model = model;
        level.shaft_angle = fx.needs_shaft_angle;
        if fx.has_profile() {
            level.profile = Some(fx);
        }
        Ok(level)
    }

    fn evaluate(&mut self, t: f64, m: &Motion, x: &[f64], wc: f64, jac: bool) {
        let theta_s = if self.shaft_angle { x[1] } else { 0.0 };
        match &self.profile {
            None => self
                .model
                .eval(x[0], wc, &m.q, &m.v, t, None, jac, &mut self.eval),
            Some(fx) => {
                let p = |j: usize, psi: f64, _t: f64| fx.offset(j, psi, theta_s);
                self.model
                    .eval(x[0], wc, &m.q, &m.v, t, Some(&p), jac, &mut self.eval)
            }
        }
    }
}

impl LevelModel for RingLevel {
    fn name(&self) -> &'static str {
        "ring"
    }
    fn n_states(&self) -> usize {
        1 + self.shaft_angle as usize
    }
    fn ring_dofs(&self) -> &'static [usize] {
        match self.dof {
            RingDof::Two => &[0, 1],
            RingDof::Five => &[0, 1, 2, 3, 4],
        }
    }
    fn init(&mut self, _m: &Motion, x: &mut [f64], _aux: &mut [f64]) -> Result<()> {
        x.fill(0.0);
        Ok(())
    }
    fn rhs(
        &mut self,
        t: f64,
        m: &Motion,
        x: &[f64],
        _aux: &mut [f64],
        dx: &mut [f64],
        wrench: Option<&mut [f64; 5]>,
    ) -> Result<()> {
        let wc = self.cage_ratio * m.omega;
        dx[0] = wc;
        if self.shaft_angle {
            dx[1] = m.omega;
        }
        if let Some(w) = wrench {
            self.evaluate(t, m, x, wc, false);
            *w = self.eval.wrench;
        }
        Ok(())
    }
    fn outputs(
        &mut self,
        t: f64,
        m: &Motion,
        x: &[f64],
        _aux: &mut [f64],
        out: &mut LevelOutputs,
    ) -> Result<()> {
        let wc = self.cage_ratio * m.omega;
        self.evaluate(t, m, x, wc, true);
        let e = &self.eval;
        *out = LevelOutputs {
            wrench: e.wrench,
            k: e.k,
            c: e.c,
            cage_omega: wc,
            balls_loaded: e.loaded as f64,
            max_load: e.max_load,
            max_pressure: if e.max_load > 0.0 {
                self.model.peak_pressure(e.max_load)
            } else {
                0.0
            },
            film_min: e.film_min,
            ..LevelOutputs::default()
        };
        Ok(())
    }
}
