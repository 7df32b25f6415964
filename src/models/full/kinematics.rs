//! Cage and ball kinematics of the full level: the cage's and balls' velocities and frames,
//! the groove-centre offset of the moved inner ring (docs/physics.md §5.5).

use super::*;

/// Angular velocity of the inner ring (small tilts `rx = q\[3\]`, `ry = q\[4\]` and their rates
/// `v\[3\]`, `v\[4\]`, spin `omega`): `(rx' + omega ry, ry' - omega rx, omega)`, as for the
/// cage ([`CageKin::omega`]); the groove's axial lift `ri (rx sin - ry cos)` moves with it.
pub(super) fn ring_omega(q: &[f64; 5], v: &[f64; 5], omega: f64) -> V3 {
    [v[3] + omega * q[4], v[4] - omega * q[3], omega]
}

impl FullModel {
    pub(super) fn cage_kin(&self, x: &[f64]) -> CageKin {
        let (l, t0) = (self.l, self.t0);
        let v = l / t0;
        match self.p.cage {
            CageModel::Ideal => CageKin {
                theta: x[0],
                w: x[1] / t0,
                ..CageKin::default()
            },
            CageModel::Free => CageKin {
                c: [x[0] * l, x[1] * l, x[2] * l],
                b: [x[3], x[4]],
                theta: x[5],
                v: [x[6] * v, x[7] * v, x[8] * v],
                bd: [x[9] / t0, x[10] / t0],
                w: x[11] / t0,
            },
        }
    }

    /// Ball kinematics from its states; `rho, z` in quasi-static mode come from `pos`.
    pub(super) fn ball_kin(&self, xb: &[f64], pos: [f64; 2]) -> BallKin {
        let (l, t0) = (self.l, self.t0);
        match self.p.ball_contacts {
            BallContacts::QuasiStatic => BallKin {
                psi: xb[0],
                w_orb: xb[1] / t0,
                w: [xb[2] / t0, xb[3] / t0, xb[4] / t0],
                rho: self.pos.r_og + pos[1],
                z: self.z_og + pos[0],
                ..BallKin::default()
            },
            BallContacts::Dynamic => BallKin {
                rho: xb[0] * l,
                z: xb[1] * l,
                psi: xb[2],
                rho_d: xb[3] * l / t0,
                z_d: xb[4] * l / t0,
                w_orb: xb[5] / t0,
                w: [xb[6] / t0, xb[7] / t0, xb[8] / t0],
            },
        }
    }

    /// Groove offset `(A1, A2)` at azimuth `psi` (Jones geometry, as `models::quasi_static`).
    pub(super) fn groove_offset(&self, q: &[f64; 5], psi: f64) -> [f64; 2] {
        let (s, c) = psi.sin_cos();
        self.groove_offset_sc(q, s, c)
    }

    /// [`Self::groove_offset`] from `sin psi`, `cos psi`.
    pub(super) fn groove_offset_sc(&self, q: &[f64; 5], s: f64, c: f64) -> [f64; 2] {
        [
            self.a10 + q[2] + self.ri * (q[3] * s - q[4] * c),
            self.a20 + q[0] * c + q[1] * s,
        ]
    }
}
