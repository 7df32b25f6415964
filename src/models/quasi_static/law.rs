//! The ball as an [`ElementLaw`]: the quasi-static model answers for one ball at a time
//! (its Jones–Harris equilibrium at the groove offset the displacement gives), so any level
//! that sums elements through [`crate::seam::element::assemble`] can carry balls.

use super::{BallState, QuasiStatic};
use crate::error::Result;
use crate::seam::element::{ElementAt, ElementDisplacement, ElementLaw, ElementReaction, Want};

/// Numbers of a ball's memory: `X` (2), the groove offset it was solved at (2), `dX/dA`
/// (4), warm flag.
pub const BALL_STATE_LEN: usize = 9;

impl BallState {
    /// The state from its [`BALL_STATE_LEN`] numbers (all zeros: cold).
    pub fn from_slice(a: &[f64]) -> Self {
        BallState {
            x: [a[0], a[1]],
            a: [a[2], a[3]],
            dxda: [[a[4], a[5]], [a[6], a[7]]],
            warm: a[8] != 0.0,
        }
    }

    /// Write the state into its [`BALL_STATE_LEN`] numbers.
    pub fn to_slice(&self, out: &mut [f64]) {
        out[..BALL_STATE_LEN].copy_from_slice(&[
            self.x[0],
            self.x[1],
            self.a[0],
            self.a[1],
            self.dxda[0][0],
            self.dxda[0][1],
            self.dxda[1][0],
            self.dxda[1][1],
            self.warm as u8 as f64,
        ]);
    }
}

impl ElementLaw for QuasiStatic {
    fn name(&self) -> &'static str {
        "ball"
    }

    fn state_len(&self) -> usize {
        BALL_STATE_LEN
    }

    /// The inner groove-centre radius `Ri`: a ball's axial force acts on the ring there,
    /// and a tilt moves its groove offset axially by `Ri` times the tilt (module docs of
    /// the quasi-static model).
    fn moment_arm(&self) -> f64 {
        self.ri
    }

    fn react(
        &self,
        at: ElementAt<'_>,
        _u: ElementDisplacement,
        omega: f64,
        state: &mut [f64],
        want: Want,
    ) -> Result<ElementReaction> {
        if !omega.is_finite() {
            return Err(crate::error::Error::invalid(
                "omega",
                omega,
                "a finite number",
            ));
        }
        let mut st = BallState::from_slice(state);
        let sol = self.solve_ball(at, omega, &mut st, want.stiffness || want.report);
        // A failed solve may still have moved the warm start (a valid one).
        st.to_slice(state);
        let sol = sol?;
        let mut r = ElementReaction {
            f: sol.f,
            ..Default::default()
        };
        if let Some(e) = &sol.full {
            r.approach = e.di + e.do_;
            if want.stiffness {
                r.df = self.ball_df(e);
            }
            if want.report {
                let (p_i, p_o) = self.peak_pressures(e);
                r.load = [e.qi, e.qo];
                r.pressure = [p_i, p_o];
            }
        }
        Ok(r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::quasi_static::{azimuths, Options};

    #[test]
    fn the_ball_law_summed_is_the_quasi_static_model() {
        // The element law summed by the assembly gives the model's own forces and
        // stiffness (both go through the same assembly; this holds the law's state
        // round trip and its report to the model's).
        let b = crate::geometry::preset("7008CE").unwrap().build().unwrap();
        let qs = QuasiStatic::new(&b, Options::default()).unwrap();
        let psi = azimuths(b.z, 0.1);
        let q = [5e-6, -3e-6, 8e-6, 1e-4, -5e-5];
        let omega = 1000.0;
        let mut states = vec![BallState::default(); b.z];
        let mut k0 = [[0.0; 5]; 5];
        let mut balls = vec![Default::default(); b.z];
        let f0 = qs
            .evaluate(
                &q,
                omega,
                &psi,
                &mut states,
                Some(&mut k0),
                Some(&mut balls),
            )
            .unwrap();
        let mut mem = vec![0.0; BALL_STATE_LEN * b.z];
        let mut k1 = [[0.0; 5]; 5];
        let want = Want {
            stiffness: true,
            report: true,
        };
        let mut loads = vec![[0.0; 2]; b.z];
        let f1 =
            crate::seam::element::assemble(&q, &psi, qs.moment_arm(), Some(&mut k1), |j, at, u| {
                let r = qs.react(
                    at,
                    u,
                    omega,
                    &mut mem[BALL_STATE_LEN * j..BALL_STATE_LEN * (j + 1)],
                    want,
                )?;
                loads[j] = r.load;
                Ok(r)
            })
            .unwrap();
        for i in 0..5 {
            assert!(
                (f0[i] - f1[i]).abs() <= 1e-9 * f0.iter().map(|x| x.abs()).fold(0.0, f64::max),
                "{f0:?} {f1:?}"
            );
            for c in 0..5 {
                assert!((k0[i][c] - k1[i][c]).abs() <= 1e-9 * k0[i][i].abs().max(k0[0][0].abs()));
            }
        }
        for (j, bl) in balls.iter().enumerate() {
            assert!((loads[j][0] - bl.q_i).abs() <= 1e-9 * bl.q_i.abs().max(1.0));
            assert!((loads[j][1] - bl.q_o).abs() <= 1e-9 * bl.q_o.abs().max(1.0));
        }
        // The memory round trip: every ball left warm at its root.
        for j in 0..b.z {
            let st = BallState::from_slice(&mem[BALL_STATE_LEN * j..]);
            assert!(st.warm);
            assert!(
                (st.x[0] - states[j].x[0]).abs() < 1e-12
                    && (st.x[1] - states[j].x[1]).abs() < 1e-12
            );
        }
    }
}
