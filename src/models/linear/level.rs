//! The `linear` level: constant stiffness and damping from the quasi-static linearisation
//! at the scene's operating point, `F = F0 - K (q - q0) - C v`. No states; the cheapest
//! level with a physical stiffness (rotor-dynamics eigenvalue and unbalance studies).
//! `K` is the exact Jones–Harris stiffness at the operating point; `C` is the contact
//! damping of the ring level (`model.contact_damping` per loaded ball) at `q0`.

use crate::error::Result;
use crate::geometry::kinematics::nominal_cage_speed as cage_speed;
use crate::models::quasi_static::{Options, QuasiStatic};
use crate::models::ring::{RingAt, RingDof, RingEval, RingModel};
use crate::models::LevelArgs;
use crate::seam::{LevelModel, LevelOutputs, Motion, Point};
use crate::units::rpm_to_rad_s;

/// The level.
#[derive(Debug)]
pub struct LinearLevel {
    q0: [f64; 5],
    f0: [f64; 5],
    k: [[f64; 5]; 5],
    c: [[f64; 5]; 5],
    loaded: f64,
    max_load: f64,
    max_pressure: f64,
    cage_ratio: f64,
}

impl LinearLevel {
    /// Linearise at the scene's operating point.
    pub fn new(a: &LevelArgs) -> Result<Self> {
        let b = a.bearing;
        let op = a.operating_point;
        let qs = QuasiStatic::new(
            b,
            Options {
                race_control: a.race_control,
                ..Options::default()
            },
        )?;
        let sol = qs.solve(
            &[op.fx, op.fy, op.fz, op.mx, op.my],
            rpm_to_rad_s(op.speed_rpm),
        )?;
        let ring = RingModel::new(b, RingDof::Five, a.contact_damping);
        let mut e = RingEval::default();
        ring.eval(
            RingAt {
                theta_c: 0.0,
                omega_c: 0.0,
                q: &sol.q,
                v: &[0.0; 5],
                t: 0.0,
            },
            None,
            true,
            &mut e,
        );
        let mut max_p: f64 = 0.0;
        let mut max_load: f64 = 0.0;
        let mut loaded = 0.0;
        for r in &sol.balls {
            max_p = max_p.max(r.p_i).max(r.p_o);
            max_load = max_load.max(r.q_i).max(r.q_o);
            if r.q_i > 0.0 {
                loaded += 1.0;
            }
        }
        Ok(LinearLevel {
            q0: sol.q,
            f0: sol.forces,
            k: sol.stiffness,
            c: e.c,
            loaded,
            max_load,
            max_pressure: max_p,
            cage_ratio: cage_speed(b, 1.0),
        })
    }

    fn wrench(&self, m: &Motion) -> [f64; 5] {
        std::array::from_fn(|i| {
            self.f0[i]
                - (0..5)
                    .map(|j| self.k[i][j] * (m.q[j] - self.q0[j]) + self.c[i][j] * m.v[j])
                    .sum::<f64>()
        })
    }
}

/// The registry's constructor (the level registry, `LEVELS` in `component/levels.rs`).
pub fn build(a: &LevelArgs) -> Result<Box<dyn LevelModel>> {
    Ok(Box::new(LinearLevel::new(a)?))
}

impl LevelModel for LinearLevel {
    fn n_states(&self) -> usize {
        0
    }
    fn init(&mut self, _m: &Motion, _x: &mut [f64], _aux: &mut [f64]) -> Result<()> {
        Ok(())
    }
    fn rhs(&mut self, p: Point<'_>, _dx: &mut [f64], wrench: Option<&mut [f64; 5]>) -> Result<()> {
        if let Some(w) = wrench {
            *w = self.wrench(p.m);
        }
        Ok(())
    }
    fn outputs(&mut self, p: Point<'_>, out: &mut LevelOutputs) -> Result<()> {
        *out = LevelOutputs {
            wrench: self.wrench(p.m),
            k: self.k,
            c: self.c,
            cage_omega: self.cage_ratio * p.m.omega,
            balls_loaded: self.loaded,
            max_load: self.max_load,
            max_pressure: self.max_pressure,
            ..LevelOutputs::default()
        };
        Ok(())
    }
}
