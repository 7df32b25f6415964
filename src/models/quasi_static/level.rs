//! The `quasi_static` level: Jones–Harris equilibrium of every ball at the current ring
//! motion (docs/physics.md §4), balls at the cage's kinematic positions so the force varies as
//! balls pass. State: the cage angle. Memory (in the component state, so a restored state
//! continues bit for bit): each ball's warm start.
//!
//! Contact damping (`model.contact_damping`, N s/m per loaded ball) acts as in the ring
//! level: `c d(delta)/dt` along each loaded ball's contact line (the ring level's massless
//! ball geometry), blended in over the first 0.1 µm of approach; off (no cost) at 0.

use crate::error::Result;
use crate::geometry::kinematics::nominal_cage_speed as cage_speed;
use crate::models::quasi_static::{BallState, Options, QuasiStatic};
use crate::models::ring::{RingDof, RingEval, RingModel};
use crate::models::LevelArgs;
use crate::seam::{LevelModel, LevelOutputs, Motion, Point};
use std::f64::consts::PI;

/// Values per ball in the component's `aux`: `X` (2), the groove offset it was solved at
/// (2), `dX/dA` (4), warm flag.
const AUX_PER_BALL: usize = 9;

/// The level.
#[derive(Debug)]
pub struct QuasiStaticLevel {
    qs: QuasiStatic,
    cage_ratio: f64,
    psi: Vec<f64>,
    balls: Vec<BallState>,
    /// Contact damping: the ring model with and without damping (their difference is the
    /// damping force); `None` when the scene has none.
    damping: Option<(RingModel, RingModel, RingEval, RingEval)>,
}

impl QuasiStaticLevel {
    /// Build for the scene's bearing and race control.
    pub fn new(a: &LevelArgs) -> Result<Self> {
        let b = a.bearing;
        let opts = Options {
            race_control: a.race_control,
            ..Options::default()
        };
        let qs = QuasiStatic::new(b, opts)?;
        Ok(QuasiStaticLevel {
            qs,
            cage_ratio: cage_speed(b, 1.0),
            psi: vec![0.0; b.z],
            balls: vec![BallState::default(); b.z],
            damping: (a.contact_damping > 0.0).then(|| {
                (
                    RingModel::new(b, RingDof::Five, a.contact_damping),
                    RingModel::new(b, RingDof::Five, 0.0),
                    RingEval::default(),
                    RingEval::default(),
                )
            }),
        })
    }

    fn load_aux(&mut self, theta: f64, aux: &[f64]) {
        let z = self.psi.len();
        for j in 0..z {
            self.psi[j] = theta + 2.0 * PI * j as f64 / z as f64;
            let a = &aux[AUX_PER_BALL * j..AUX_PER_BALL * (j + 1)];
            self.balls[j] = BallState {
                x: [a[0], a[1]],
                a: [a[2], a[3]],
                dxda: [[a[4], a[5]], [a[6], a[7]]],
                warm: a[8] != 0.0,
            };
        }
    }

    /// Add the contact-damping force (and, with `c`, its matrix) at cage angle `theta`.
    fn add_damping(
        &mut self,
        theta: f64,
        m: &Motion,
        w: &mut [f64; 5],
        c: Option<&mut [[f64; 5]; 5]>,
    ) {
        if let Some((with, without, e1, e0)) = &mut self.damping {
            let wc = self.cage_ratio * m.omega;
            let jac = c.is_some();
            with.eval(theta, wc, &m.q, &m.v, 0.0, None, jac, e1);
            without.eval(theta, wc, &m.q, &m.v, 0.0, None, false, e0);
            for ((w, a), b) in w.iter_mut().zip(e1.wrench).zip(e0.wrench) {
                *w += a - b;
            }
            if let Some(c) = c {
                *c = e1.c;
            }
        }
    }

    fn store_aux(&self, aux: &mut [f64]) {
        for (j, b) in self.balls.iter().enumerate() {
            aux[AUX_PER_BALL * j..AUX_PER_BALL * (j + 1)].copy_from_slice(&[
                b.x[0],
                b.x[1],
                b.a[0],
                b.a[1],
                b.dxda[0][0],
                b.dxda[0][1],
                b.dxda[1][0],
                b.dxda[1][1],
                b.warm as u8 as f64,
            ]);
        }
    }
}

/// The registry's constructor (the level registry, `LEVELS` in `component/levels.rs`).
pub fn build(a: &LevelArgs) -> Result<Box<dyn LevelModel>> {
    Ok(Box::new(QuasiStaticLevel::new(a)?))
}

impl LevelModel for QuasiStaticLevel {
    fn n_states(&self) -> usize {
        1
    }
    fn states_are_quadrature(&self) -> bool {
        // The cage angle, at cage_ratio * omega.
        true
    }
    fn n_aux(&self) -> usize {
        AUX_PER_BALL * self.psi.len()
    }
    fn init(&mut self, _m: &Motion, x: &mut [f64], aux: &mut [f64]) -> Result<()> {
        x[0] = 0.0;
        aux.fill(0.0);
        Ok(())
    }
    fn rhs(&mut self, p: Point<'_>, dx: &mut [f64], wrench: Option<&mut [f64; 5]>) -> Result<()> {
        let Point { m, x, aux, .. } = p;
        dx[0] = self.cage_ratio * m.omega;
        if let Some(w) = wrench {
            self.load_aux(x[0], aux);
            *w = self
                .qs
                .evaluate(&m.q, m.omega, &self.psi, &mut self.balls, None, None)?;
            self.store_aux(aux);
            self.add_damping(x[0], m, w, None);
        }
        Ok(())
    }
    fn outputs(&mut self, p: Point<'_>, out: &mut LevelOutputs) -> Result<()> {
        let Point { m, x, aux, .. } = p;
        self.load_aux(x[0], aux);
        let mut k = [[0.0; 5]; 5];
        // Loaded balls, largest load and pressure: all the outputs read of the balls
        // (their contact angles and semi-axes are not formed).
        let (mut loaded, mut max_load, mut max_p) = (0usize, 0.0f64, 0.0f64);
        let qs = &self.qs;
        let mut wrench = qs.evaluate_with(
            &m.q,
            m.omega,
            &self.psi,
            &mut self.balls,
            Some(&mut k),
            true,
            |_, e, _, _| {
                if e.qi > 0.0 {
                    loaded += 1;
                }
                max_load = max_load.max(e.qi).max(e.qo);
                let (p_i, p_o) = qs.peak_pressures(e);
                max_p = max_p.max(p_i).max(p_o);
            },
        )?;
        self.store_aux(aux);
        let mut c = [[0.0; 5]; 5];
        self.add_damping(x[0], m, &mut wrench, Some(&mut c));
        *out = LevelOutputs {
            wrench,
            k,
            c,
            cage_omega: self.cage_ratio * m.omega,
            balls_loaded: loaded as f64,
            max_load,
            max_pressure: max_p,
            ..LevelOutputs::default()
        };
        Ok(())
    }
}
