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
        let p = self.pocket(ck, sc, r);
        self.ball_terms(r, &p)
    }

    /// The pocket walls' forces on a ball at its race part's kinematics `r` (its frame and
    /// spin; the pocket does not see the race contacts) and the cage `ck`.
    pub(super) fn pocket(&self, ck: &CageKin, sc: [f64; 2], r: &BallRace) -> Pocket {
        let hd = 0.5 * self.d;
        let ez = EZ;
        let (rb, vb, w) = (r.fr.rb, r.fr.vb, r.bk.w);
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
        let mut out = Pocket::default();
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
        for (k, wl) in walls[..nwall].iter().enumerate() {
            let (nw, pf, vs) = (wl.nw, wl.pf, wl.vs);
            let mut fb = scale(nw, -pf.normal);
            if vs > 0.0 {
                fb = add(fb, scale(wl.slide, -pf.friction.abs() / vs));
            }
            out.fb[k] = fb;
            out.mb[k] = cross(wl.arm, fb);
            out.cage_f = sub(out.cage_f, fb);
            out.cage_m = sub(out.cage_m, cross(sub(wl.rc, ck.c), fb));
            out.max = out.max.max(pf.normal.abs());
        }
        out.walls = nwall;
        out
    }

    /// A ball's terms from its race part `r` and its pocket's forces `p`: the ball's
    /// accelerations (the walls' forces added to the races' one by one, in the walls'
    /// order) and the pocket's reaction on the cage.
    pub(super) fn ball_terms(&self, r: &BallRace, p: &Pocket) -> BallTerms {
        let ez = EZ;
        let (er, et) = (r.fr.er(), r.fr.et());
        let bk = &r.bk;
        let (mut f, mut mom) = (r.f, r.mom);
        for k in 0..p.walls {
            f = add(f, p.fb[k]);
            mom = add(mom, p.mb[k]);
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
            cage_f: p.cage_f,
            cage_m: p.cage_m,
            wrench: r.wrench,
            torque: r.torque,
            ext_mz: r.ext_mz,
            power: r.power,
            info: BallInfo {
                pocket: p.max,
                ..r.info
            },
            pocket: *p,
        }
    }
}
