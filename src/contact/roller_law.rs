//! The contact law of a cylindrical roller for the levels that sum elements
//! ([`crate::seam::element::ElementLaw`]): the laminae of `contact::lamina` (docs/physics.md
//! §R1) driven by the inner ring's displacement at the roller.
//!
//! In the element's frame (`seam::element`: `axial`, `radial` outward along the azimuth,
//! `tilt` about the element's tangential axis) the inner raceway at axial position `x` from the
//! roller's mid-plane moves outward by `radial - x tan(tilt)`, so lamina `k` has the approach
//! `delta_k = radial - Pd/2 - x_k tan(tilt) - 2 P(x_k)`: the roller's approach is
//! `delta = radial - Pd/2` (diametral clearance `Pd`) and its misalignment `psi = tilt`. (For a
//! roller on the `+x` axis a ring rotation `ry` moves the raceway at `z` outward by `z ry`, and
//! `tilt = -ry` there: the two agree.) The roller pushes the shaft inward with its load `Q`, so
//! the forces on the shaft are `F_a = 0`, `F_r = -Q` and, by virtual work through
//! `d delta_k = d radial - x_k sec²(tilt) d tilt`, the moment conjugate to the tilt
//! `m = sec²(tilt) Σ q_k x_k`. The derivatives follow from the laminae's Jacobian; `K` is
//! symmetric (a potential exists).
//!
//! What it leaves out, for the levels to add: the axial load of NJ/NUP flanges (the law carries
//! none: correct for NU and N), the roller's centrifugal force at speed (the laminae carry the
//! same load at both contacts, the massless-roller assumption) and tapered rollers, whose
//! roller is in equilibrium between cup, cone and back flange (`geometry::roller`), which this
//! law refuses.

use crate::contact::lamina::{line_hertz, tan0, Laminae};
use crate::error::{Error, Result};
use crate::geometry::roller::RollerBearing;
use crate::seam::element::{ElementAt, ElementDisplacement, ElementLaw, ElementReaction, Want};

/// A cylindrical roller's line contact, by laminae (module docs).
#[derive(Debug, Clone)]
pub struct CylindricalRollerLaw {
    laminae: Laminae,
    half_pd: f64,
    r_inner: f64,
    r_outer: f64,
    e_inner: f64,
    e_outer: f64,
}

impl CylindricalRollerLaw {
    /// The law of the rollers of `b`; refuses a tapered bearing, naming `bearing.kind`.
    pub fn new(b: &RollerBearing) -> Result<Self> {
        if b.kind.is_tapered() {
            return Err(Error::invalid(
                "bearing.kind",
                "tapered",
                "nu, n, nj or nup: the cylindrical roller law; a tapered roller needs the cup/cone/flange equilibrium, not built yet",
            ));
        }
        Ok(CylindricalRollerLaw {
            laminae: b.laminae()?,
            half_pd: 0.5 * b.pd,
            r_inner: b.reduced_radius_inner(),
            r_outer: b.reduced_radius_outer(),
            e_inner: b.e_prime_inner(),
            e_outer: b.e_prime_outer(),
        })
    }

    /// The laminae it evaluates.
    pub fn laminae(&self) -> &Laminae {
        &self.laminae
    }
}

impl ElementLaw for CylindricalRollerLaw {
    fn name(&self) -> &'static str {
        "roller"
    }

    fn tilt_damping_arm2(&self) -> f64 {
        self.laminae.lwe * self.laminae.lwe / 12.0
    }

    fn state_len(&self) -> usize {
        0
    }

    fn react(
        &self,
        _at: ElementAt<'_>,
        u: ElementDisplacement,
        _omega: f64,
        _state: &mut [f64],
        want: Want,
    ) -> Result<ElementReaction> {
        let approach = u.radial - self.half_pd;
        let t = tan0(u.tilt);
        let r = self.laminae.evaluate_tan(approach, t);
        let sec2 = 1.0 + t * t;
        let mut out = ElementReaction {
            f: [0.0, -r.force, sec2 * r.moment],
            approach,
            ..Default::default()
        };
        if want.stiffness {
            out.df = [
                [0.0; 3],
                [0.0, -r.dforce_ddelta, -r.dforce_dtilt],
                [
                    0.0,
                    sec2 * r.dmoment_ddelta,
                    sec2 * r.dmoment_dtilt + 2.0 * t * sec2 * r.moment,
                ],
            ];
        }
        if want.report {
            let w = self.laminae.width();
            out.load = [r.force, r.force];
            out.pressure = [
                line_hertz(r.max_lamina / w, self.r_inner, self.e_inner).1,
                line_hertz(r.max_lamina / w, self.r_outer, self.e_outer).1,
            ];
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::roller_catalogue::lookup;
    use crate::seam::element::assemble;
    use std::f64::consts::PI;

    fn law(name: &str) -> (CylindricalRollerLaw, Vec<f64>) {
        let b = lookup(name).unwrap().build().unwrap();
        let psi = (0..b.z).map(|j| 2.0 * PI * j as f64 / b.z as f64).collect();
        (CylindricalRollerLaw::new(&b).unwrap(), psi)
    }

    fn sum(
        l: &CylindricalRollerLaw,
        psi: &[f64],
        q: &[f64; 5],
        k: Option<&mut [[f64; 5]; 5]>,
    ) -> [f64; 5] {
        let want = Want {
            stiffness: k.is_some(),
            report: false,
        };
        assemble(q, psi, l.moment_arm(), k, |_, at, u| {
            l.react(at, u, 0.0, &mut [], want)
        })
        .unwrap()
    }

    #[test]
    fn ring_stiffness_is_minus_the_derivative_and_symmetric() {
        let (l, psi) = law("NU2206");
        // Radial displacement beyond the clearance plus a tilt of the ring.
        let q = [40e-6, -10e-6, 0.0, 4e-4, -2e-4];
        let mut k = [[0.0; 5]; 5];
        let f = sum(&l, &psi, &q, Some(&mut k));
        assert!(f[0] < 0.0, "the rollers push the shaft back: {f:?}");
        // The rollers resist a rotation of the ring.
        assert!(k[3][3] > 0.0 && k[4][4] > 0.0, "{k:?}");
        for col in [0, 1, 3, 4] {
            let h = if col < 3 { 1e-10 } else { 1e-8 };
            let (mut qp, mut qm) = (q, q);
            qp[col] += h;
            qm[col] -= h;
            let (fp, fm) = (sum(&l, &psi, &qp, None), sum(&l, &psi, &qm, None));
            for row in [0, 1, 3, 4] {
                let fd = -(fp[row] - fm[row]) / (2.0 * h);
                let scale = k[0][0].abs() * if row > 2 || col > 2 { 1e-4 } else { 1.0 };
                assert!(
                    (k[row][col] - fd).abs() < 1e-5 * scale,
                    "K[{row}][{col}] {} vs {fd}",
                    k[row][col]
                );
            }
        }
        for i in 0..5 {
            for j in 0..5 {
                let scale = (k[i][i].abs() * k[j][j].abs()).sqrt().max(1.0);
                assert!((k[i][j] - k[j][i]).abs() < 1e-9 * scale, "K[{i}][{j}]");
            }
        }
        // No axial stiffness: the law carries no axial load (NU).
        assert_eq!(k[2][2], 0.0);
    }

    #[test]
    fn a_tilted_ring_is_resisted_by_a_moment() {
        let (l, psi) = law("NU206");
        // Radial preload-like displacement so every roller is loaded, then rotate about y.
        let base = [0.0, 0.0, 0.0, 0.0, 0.0];
        let mut q = base;
        q[0] = 60e-6;
        let m0 = sum(&l, &psi, &q, None)[4];
        q[4] = 5e-4;
        let m1 = sum(&l, &psi, &q, None)[4];
        assert!(m1 < m0, "My {m0} -> {m1}: the rollers resist ry");
    }

    #[test]
    fn report_gives_the_peak_pressures_and_tapered_is_refused() {
        let (l, _) = law("NU206");
        let at = ElementAt {
            index: 0,
            psi: 0.0,
            sc: (0.0, 1.0),
            q: &[0.0; 5],
        };
        let u = ElementDisplacement {
            axial: 0.0,
            radial: 40e-6,
            tilt: 0.0,
        };
        let want = Want {
            stiffness: false,
            report: true,
        };
        let r = l.react(at, u, 0.0, &mut [], want).unwrap();
        assert!(r.load[0] > 0.0 && r.load[0] == r.load[1] && r.load[0] == -r.f[1]);
        assert!(
            r.pressure[0] > r.pressure[1] && r.pressure[1] > 0.0,
            "{r:?}"
        );
        // At zero approach nothing, and no NaN.
        let u0 = ElementDisplacement { radial: 0.0, ..u };
        let r0 = l.react(at, u0, 0.0, &mut [], want).unwrap();
        assert_eq!(
            (r0.f, r0.load, r0.pressure),
            ([0.0, 0.0, 0.0], [0.0; 2], [0.0; 2])
        );
        let b = lookup("30206").unwrap().build().unwrap();
        let e = CylindricalRollerLaw::new(&b).unwrap_err().to_string();
        assert!(e.contains("bearing.kind") && e.contains("tapered"), "{e}");
    }
}
