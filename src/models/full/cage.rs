//! Ball–cage interaction of the full level: the pocket forces between each ball and the cage
//! (docs/physics.md §5.5; the pocket law in `crate::lubrication::pocket`).

use super::*;

impl FullModel {
    /// `sin`, `cos` of each pocket's angle at the cage angle `theta` into `pocket_sc`
    /// (computed again only when the angle changed).
    pub(super) fn pocket_trig(&mut self, theta: f64) {
        if self.pocket_theta == Some(theta.to_bits()) {
            return;
        }
        for (j, sc) in self.pocket_sc.iter_mut().enumerate() {
            let th = theta + 2.0 * PI * j as f64 / self.z as f64;
            let (s, c) = th.sin_cos();
            *sc = [s, c];
        }
        self.pocket_theta = Some(theta.to_bits());
    }

    /// Ball `j`'s terms from its race part `r` and the cage: pocket forces (equal and
    /// opposite on the cage) and the ball's accelerations. `sc`: `sin`, `cos` of the
    /// pocket's angle ([`Self::pocket_trig`]).
    pub(super) fn ball_cage(&self, ck: &CageKin, sc: [f64; 2], r: &BallRace) -> BallTerms {
        let hd = 0.5 * self.d;
        let ez = EZ;
        let (er, et) = (r.fr.er(), r.fr.et());
        let (bk, rb, vb, w) = (&r.bk, r.fr.rb, r.fr.vb, r.bk.w);
        let (mut f, mut mom) = (r.f, r.mom);
        // Pocket.
        let [sp, cp] = sc;
        let rp = 0.5 * self.dm;
        let etp = [-sp, cp, 0.0];
        let pc = ck.point_sc(sp, cp, rp);
        let d = sub(rb, pc);
        // Rate of the offset seen from the cage (the walls turn with it): the ball's
        // velocity minus the cage material's at the ball centre.
        let dd = sub(vb, ck.velocity_at(rb));
        let side = 0.5 * self.p.pocket_clearance;
        let mut cage_f = [0.0; 3];
        let mut cage_m = [0.0; 3];
        let mut pocket_max: f64 = 0.0;
        let dirs: &[V3] = match self.p.cage {
            CageModel::Free => &[etp, ez],
            CageModel::Ideal => &[etp],
        };
        // Both walls of each direction (films on both sides; contact on one at most):
        // their laws first, then their forces in the same order (the walls' divisions and
        // roots overlap).
        let mut walls = [Wall::default(); 4];
        let mut nwall = 0;
        for &nvec in dirs {
            let dn = dot(d, nvec);
            for sgn in [1.0, -1.0] {
                let nw = scale(nvec, sgn);
                let h = side - sgn * dn;
                let h_dot = -dot(dd, nw);
                let arm = scale(nw, hd);
                let rc = add(rb, arm);
                let vbs = add(vb, cross(w, arm));
                let vwall = ck.velocity_at(rc);
                let slide = tangential(sub(vbs, vwall), nw);
                let vs = norm(slide);
                // Entrainment: mean surface speed relative to the contact point, which
                // moves with the ball centre.
                let u = norm(tangential(
                    scale(add(sub(vbs, vb), sub(vwall, vb)), 0.5),
                    nw,
                ));
                walls[nwall] = Wall {
                    nw,
                    arm,
                    rc,
                    slide,
                    vs,
                    pf: self.pocket.force(h, h_dot, u, vs),
                };
                nwall += 1;
            }
        }
        for wl in &walls[..nwall] {
            let (nw, pf, vs) = (wl.nw, wl.pf, wl.vs);
            let mut fb = scale(nw, -pf.normal);
            if vs > 0.0 {
                fb = add(fb, scale(wl.slide, -pf.friction.abs() / vs));
            }
            f = add(f, fb);
            mom = add(mom, cross(wl.arm, fb));
            cage_f = sub(cage_f, fb);
            cage_m = sub(cage_m, cross(sub(wl.rc, ck.c), fb));
            pocket_max = pocket_max.max(pf.normal.abs());
        }
        // Accelerations.
        let (fr, ft, fz) = (dot(f, er), dot(f, et), dot(f, ez));
        let acc = match self.p.ball_contacts {
            BallContacts::QuasiStatic => [0.0, ft / (self.m * bk.rho), 0.0],
            BallContacts::Dynamic => [
                fr / self.m + bk.rho * bk.w_orb * bk.w_orb,
                (ft / self.m - 2.0 * bk.rho_d * bk.w_orb) / bk.rho,
                fz / self.m,
            ],
        };
        BallTerms {
            acc,
            w_dot: scale(mom, 1.0 / self.j),
            cage_f,
            cage_m,
            wrench: r.wrench,
            torque: r.torque,
            ext_mz: r.ext_mz,
            power: r.power,
            info: BallInfo {
                pocket: pocket_max,
                ..r.info
            },
        }
    }
}
