//! Ball–race contacts of the full level: contact state, traction and spin moment at each
//! contact, the inner contact and the ball's two race contacts (docs/physics.md §5.5).

use super::*;
use crate::seam::Motion;

pub(super) fn csi_peak(cs: &ContactState) -> f64 {
    if cs.a > 0.0 && cs.b > 0.0 {
        1.5 * cs.q / (PI * cs.a * cs.b)
    } else {
        0.0
    }
}

impl FullModel {
    /// Contact state at the actual contact angle (semi-axes from the table); the film
    /// laws' effective radius and modulus are taken at the nominal contact angle.
    pub(super) fn contact_state(c: &ball::Contact, nominal: &PointContact) -> ContactState {
        let q = c.q;
        let (a, b) = c.co.semi_axes(q);
        ContactState {
            q,
            a,
            b,
            rx: nominal.curvature.rx,
            kappa: if b > 0.0 {
                a / b
            } else {
                nominal.ellipse.kappa
            },
            e_eff: nominal.e_eff,
        }
    }

    /// Tangential traction on the ball from slip `dv` (3-D, in the contact plane).
    pub(super) fn traction(&self, dv: V3, u: f64, cs: &ContactState) -> V3 {
        let s = norm(dv);
        let se = s.max(1e-12);
        let t = self.p.traction.force(se, u, cs);
        scale(dv, -t / se)
    }

    /// Spin moment on the ball about the normal `n` for relative spin `ws`.
    pub(super) fn spin_moment(&self, ws: f64, u: f64, cs: &ContactState, n: V3) -> V3 {
        if cs.q <= 0.0 {
            return [0.0; 3];
        }
        let m = 3.0 * PI / 16.0 * cs.a * self.p.traction.force(ws * cs.a, u, cs);
        scale(n, -m)
    }

    /// The inner race contact of a ball: its load and traction, and what they do to the
    /// shaft (the part of [`Self::ball_race`] the wrench needs, shared with
    /// [`Self::wrench_at`] so that both compute the same numbers), at the shaft's motion `m`.
    pub(super) fn inner_contact(
        &self,
        m: &Motion,
        bk: &BallKin,
        fr: &BallFrame,
        xrel: [f64; 2],
        known: Known,
    ) -> InnerContact {
        let hd = 0.5 * self.d;
        let (s, c) = (fr.s, fr.c);
        let (er, et, ez) = (fr.er(), fr.et(), EZ);
        let (ci, csi) = match known {
            Known::Kept(k) | Known::Contacts(k) => (k.contacts[0], k.cs[0]),
            _ => {
                let ci = match known {
                    Known::Solved(c) => c[0],
                    _ => {
                        let a = self.groove_offset_sc(&m.q, s, c);
                        ball::contact_full(
                            &self.pos.inner,
                            self.pos.ri_free,
                            [a[0] - xrel[0], a[1] - xrel[1]],
                        )
                    }
                };
                (ci, Self::contact_state(&ci, &self.nominal.inner))
            }
        };
        let (qi, ni2) = (ci.q, ci.n);
        let ni = add(scale(ez, ni2[0]), scale(er, ni2[1]));
        let w = bk.w;
        let wo = [0.0, 0.0, bk.w_orb];
        let ri_ = scale(ni, -hd);
        let rci = add(fr.rb, ri_);
        let vbs_i = add(fr.vb, cross(w, ri_));
        // Inner ring angular velocity: spin plus tilt rates.
        let (q, v) = (&m.q, &m.v);
        let wr = ring_omega(q, v, m.omega);
        let vq = [v[0], v[1], v[2]];
        let vr_i = add(vq, cross(wr, sub(rci, [q[0], q[1], q[2]])));
        let vcp_i = cross(wo, rci);
        let u_i = (0.5 * dot(add(sub(vbs_i, vcp_i), sub(vr_i, vcp_i)), et)).abs();
        let dv_i = tangential(sub(vbs_i, vr_i), ni);
        let ft_i = self.traction(dv_i, u_i, &csi);
        let ms_i = self.spin_moment(dot(sub(w, wr), ni), u_i, &csi, ni);
        // On the shaft: the inner normal load through the groove centre (the quasi-static
        // level's convention), the traction and spin reactions at the contact point.
        let mut wrench = [0.0; 5];
        let (fa, frr) = (-qi * ni2[0], -qi * ni2[1]);
        let mb = self.ri * fa;
        wrench[0] = frr * c;
        wrench[1] = frr * s;
        wrench[2] = fa;
        wrench[3] = mb * s;
        wrench[4] = -mb * c;
        let fs = scale(ft_i, -1.0);
        let ms = sub(cross(rci, fs), ms_i);
        wrench[0] += fs[0];
        wrench[1] += fs[1];
        wrench[2] += fs[2];
        wrench[3] += ms[0];
        wrench[4] += ms[1];
        InnerContact {
            ci,
            qi,
            ni,
            ri_,
            rci,
            wr,
            csi,
            dv_i,
            ft_i,
            ms_i,
            wrench,
            torque: ms[2],
        }
    }

    /// The part of ball `j`'s terms that does not depend on the cage: race contacts,
    /// tractions, spin moments and drag at the ball position `xrel` (the ball centre
    /// relative to the outer groove centre `(X1, X2)`), with the shaft's wrench, at the
    /// shaft's motion `m`.
    pub(super) fn ball_race(
        &self,
        m: &Motion,
        bk: &BallKin,
        xrel: [f64; 2],
        known: Known,
    ) -> BallRace {
        let hd = 0.5 * self.d;
        let fr = match known {
            Known::Kept(k) | Known::Outer(k) => k.fr,
            Known::Contacts(k) => BallFrame::with_sc(bk, k.fr.s, k.fr.c),
            _ => BallFrame::new(bk),
        };
        let (er, et, ez) = (fr.er(), fr.et(), EZ);
        let inn = self.inner_contact(m, bk, &fr, xrel, known);
        let (qi, ni) = (inn.qi, inn.ni);
        let (co, cso) = match known {
            Known::Kept(k) | Known::Contacts(k) | Known::Outer(k) => (k.contacts[1], k.cs[1]),
            _ => {
                let co = match known {
                    Known::Solved(c) => c[1],
                    _ => ball::contact_full(&self.pos.outer, self.pos.ro_free, xrel),
                };
                (co, Self::contact_state(&co, &self.nominal.outer))
            }
        };
        let (qo, no2) = (co.q, co.n);
        let no = add(scale(ez, no2[0]), scale(er, no2[1]));
        let (rb, vb) = (fr.rb, fr.vb);
        let w = bk.w;
        let wo = [0.0, 0.0, bk.w_orb];
        // Outer contact.
        let ro_ = scale(no, hd);
        let rco = add(rb, ro_);
        let vbs_o = add(vb, cross(w, ro_));
        let vcp_o = cross(wo, rco);
        let u_o = (0.5 * dot(add(sub(vbs_o, vcp_o), scale(vcp_o, -1.0)), et)).abs();
        let dv_o = tangential(vbs_o, no);
        let ft_o = self.traction(dv_o, u_o, &cso);
        let ms_o = self.spin_moment(dot(w, no), u_o, &cso, no);
        // Inner contact.
        let (ri_, rci, ft_i, ms_i, dv_i, wr) =
            (inn.ri_, inn.rci, inn.ft_i, inn.ms_i, inn.dv_i, inn.wr);
        // Forces and moments on the ball.
        let mut f = add(add(scale(ni, qi), scale(no, -qo)), add(ft_i, ft_o));
        let mut mom = add(add(cross(ri_, ft_i), cross(ro_, ft_o)), add(ms_i, ms_o));
        let mut ext_mz = cross(rci, ft_i)[2] + cross(rco, ft_o)[2] + ms_i[2] + ms_o[2];
        // Drag.
        if self.p.drag > 0.0 {
            let k = self.p.drag;
            let sv = norm(vb);
            if sv > 0.0 {
                let fd = scale(
                    vb,
                    -k * sphere_drag_force(&self.fluid, self.d, sv).abs() / sv,
                );
                f = add(f, fd);
                ext_mz += cross(rb, fd)[2];
            }
            let sw = norm(w);
            if sw > 0.0 {
                let md = scale(
                    w,
                    -k * sphere_spin_moment(&self.fluid, self.d, sw).abs() / sw,
                );
                mom = add(mom, md);
                ext_mz += md[2];
            }
        }
        let power = -dot(ft_i, dv_i) - dot(ft_o, dv_o) - dot(ms_i, sub(w, wr)) - dot(ms_o, w);
        let p_max = csi_peak(&inn.csi).max(csi_peak(&cso));
        BallRace {
            bk: *bk,
            fr,
            xrel,
            f,
            mom,
            ext_mz,
            wrench: inn.wrench,
            torque: inn.torque,
            power,
            info: BallInfo {
                psi: bk.psi,
                w_orb: bk.w_orb,
                rho: bk.rho,
                z: bk.z,
                q_i: qi,
                q_o: qo,
                // The contact angles: set where an evaluation keeps its per-ball results
                // ([`FullModel::balls`], from `contacts`), not in every Jacobian column.
                alpha_i: 0.0,
                alpha_o: 0.0,
                slide_i: norm(dv_i),
                slide_o: norm(dv_o),
                pocket: 0.0,
                p_max,
            },
            contacts: [inn.ci, co],
            cs: [inn.csi, cso],
        }
    }
}
