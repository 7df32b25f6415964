//! The `ring` level: ring on massless balls (physics.md §5.1) behind the level seam.

use super::cage_speed;
use crate::component::level::{LevelModel, LevelOutputs, Motion};
use crate::error::Result;
use crate::geometry::Bearing;
use crate::models::ring::{RingDof, RingEval, RingModel};

/// Ring on massless balls (physics.md §5.1). State: the cage angle.
#[derive(Debug)]
pub struct RingLevel {
    model: RingModel,
    cage_ratio: f64,
    dof: RingDof,
    eval: RingEval,
}

impl RingLevel {
    /// Build.
    pub fn new(b: &Bearing, dof: RingDof, damping: f64) -> Self {
        RingLevel {
            model: RingModel::new(b, dof, damping),
            cage_ratio: cage_speed(b, 1.0),
            dof,
            eval: RingEval::default(),
        }
    }
}

impl LevelModel for RingLevel {
    fn name(&self) -> &'static str {
        "ring"
    }
    fn n_states(&self) -> usize {
        1
    }
    fn ring_dofs(&self) -> &'static [usize] {
        match self.dof {
            RingDof::Two => &[0, 1],
            RingDof::Five => &[0, 1, 2, 3, 4],
        }
    }
    fn init(&mut self, _m: &Motion, x: &mut [f64], _aux: &mut [f64]) -> Result<()> {
        x[0] = 0.0;
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
        if let Some(w) = wrench {
            self.model
                .eval(x[0], wc, &m.q, &m.v, t, None, false, &mut self.eval);
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
        self.model
            .eval(x[0], wc, &m.q, &m.v, t, None, true, &mut self.eval);
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
            ..LevelOutputs::default()
        };
        Ok(())
    }
}
