//! Equations of motion of the skidding level: the forces on each ball and on the cage
//! (traction, pocket, gyroscopic limit, drag) and the right-hand sides (docs/physics.md §5.2).

use super::*;
use crate::seam::Motion;

impl SkiddingModel {
    /// One ball's contribution at shaft motion `m`, cage and ball states
    /// `s = [theta_c, w_c, psi, w_b, w_a]`, the ball in quasi-static radial equilibrium
    /// (also with the radial-mass option, whose position states it does not see).
    /// Allocation-free.
    pub fn ball(&self, j: usize, m: &Motion, s: [f64; 5]) -> BallOut {
        let [theta_c, w_c, psi, w_b, w_a] = s;
        // Radial mass or not, this is the quasi-static split (no ball position given).
        let geo = self.geo(&m.q, psi);
        let ld = self.loads(&geo, w_b, None);
        let st = [theta_c, w_c, psi, w_b, w_a, 0.0, 0.0];
        self.forces(j, &geo, &ld, m, st, None)
    }

    /// [`Self::ball`] with all states `[theta_c, w_c, psi, w_b, w_a, u, u']` (the last
    /// two used with radial mass only).
    pub(super) fn ball_r(&self, j: usize, m: &Motion, st: [f64; 7]) -> BallOut {
        let geo = self.geo(&m.q, st[2]);
        let u = (self.bs == 5).then_some(st[5]);
        let ld = self.loads(&geo, st[3], u);
        self.forces(j, &geo, &ld, m, st, None)
    }

    /// Everything but the geometry and the normal loads: tractions, gyroscopic and spin
    /// friction, pocket, drag, the wrench; with `kq`, also adds the wrench's derivative
    /// `dW/dq` (balls and cage held) to it, analytically (see the module docs). At shaft
    /// motion `m`; `st = [theta_c, w_c, psi, w_b, w_a, u, u']`.
    pub(super) fn forces(
        &self,
        j: usize,
        geo: &Geo,
        ld: &Loads,
        m: &Motion,
        st: [f64; 7],
        kq: Option<&mut [[f64; 5]; 5]>,
    ) -> BallOut {
        self.forces_on::<true>(j, geo, ld, m, st, kq)
    }

    /// [`Self::forces`]; with `WRENCH` false only the rates and the cage torque are right
    /// (the gyroscopic friction, which acts on the shaft alone, is left out of the wrench),
    /// for the Jacobian's differences of the rates.
    #[inline(always)]
    pub(super) fn forces_on<const WRENCH: bool>(
        &self,
        j: usize,
        geo: &Geo,
        ld: &Loads,
        m: &Motion,
        st: [f64; 7],
        kq: Option<&mut [[f64; 5]; 5]>,
    ) -> BallOut {
        let (q, v, omega) = (&m.q, &m.v, m.omega);
        let [theta_c, w_c, psi, w_b, w_a, _, u_dot] = st;
        let p = &self.p;
        let r = 0.5 * self.dm;
        let hd = 0.5 * self.d;
        let (s, c, n) = (geo.s, geo.c, geo.n);
        let sp = &ld.sp;
        let (q_i, q_o) = (sp.q_i, sp.q_o);
        // Slip.
        let dv_i = 0.5 * self.di * omega - (r * w_b - hd * w_a);
        let dv_o = r * w_b + hd * w_a;
        let w_s = w_b * self.cos_a - w_a;
        let u_i = 0.5 * (0.5 * self.di * (omega - w_b) + hd * w_s);
        let u_o = 0.5 * (0.5 * self.do_ * w_b + hd * w_s);
        let (ci, co) = if p.traction.needs_contact() {
            (
                self.contact_state(true, q_i, sp.r_i),
                self.contact_state(false, q_o, sp.r_o),
            )
        } else {
            (
                ContactState {
                    q: q_i,
                    ..ContactState::default()
                },
                ContactState {
                    q: q_o,
                    ..ContactState::default()
                },
            )
        };
        let f_i = p.traction.force(dv_i, u_i, &ci);
        let f_o = p.traction.force(dv_o, u_o, &co);
        // Spin about the contact normals: the ball's angular velocity is
        // w_b z + (w_a - w_b cos a) a; its component along n3 = n0 z + n1 e_r, minus the
        // race's (omega z, inner; 0, outer).
        let nd = self.cos_a * n[0] - self.sin_a * n[1]; // a . n3
        let w_rel_b = w_a - w_b * self.cos_a;
        let wn = w_b * n[0] + w_rel_b * nd;
        let (w_sp_i, w_sp_o) = (wn - omega * n[0], wn);
        let (ms_i, msq_i, msw_i) = self.spin_moment(true, q_i, sp.r_i, w_sp_i);
        let (ms_o, _, _) = self.spin_moment(false, q_o, sp.r_o, w_sp_o);
        // Generalised forces of the spin moments -(M_i + M_o) n3 on the ball's states:
        // d w / d w_b = z - cos a a, d w / d w_a = a.
        let gen = -(ms_i + ms_o);
        let gen_b = gen * (n[0] - self.cos_a * nd);
        let gen_a = gen * nd;
        // Gyroscopic couple J w_s w_b sin(a) about e_t, carried by lateral friction
        // +-F (n1, -n0) at the two contacts with the traction cap of the quasi-static
        // kernel (module docs).
        // Not for the rates alone (`WRENCH` false): it acts on the shaft only.
        let (f_g, g_lim) = if WRENCH {
            self.gyro_force(w_b, w_s, q_i, q_o)
        } else {
            (0.0, None)
        };
        // Pocket.
        let Pocket {
            xi,
            xi_dot,
            bl,
            bt,
            force: pocket,
            m_fric,
        } = self.pocket(j, [theta_c, w_c, psi, w_b, w_a]);
        let (cp, w) = (p.pocket_clearance, p.pocket_smoothing);
        // Drag.
        let vb = r * w_b;
        let f_d = p.drag_coefficient * p.drag_density * PI * self.d * self.d * vb * vb.abs() / 8.0;
        let m_d = PI * p.drag_viscosity * self.d.powi(3) * w_a;
        let mut dx = [
            w_b,
            (f_i - f_o + pocket - f_d) / (self.m * r) + gen_b / (self.m * r * r),
            (-hd * (f_i + f_o) + m_fric * self.cos_a - m_d + gen_a) / self.j,
            0.0,
            0.0,
        ];
        // On the shaft: normal load along -n through the groove centre, traction -f_i e_t
        // at the inner contact, the lateral friction -F (n1, -n0) at the inner contact
        // (ball-plane moment about the groove-centre circle as the quasi-static kernel),
        // the spin moment +M_i n3.
        let g = geo.g;
        let mut fn_ = q_i;
        let mut cd = 0.0;
        let (mut da1, mut da2) = (0.0, 0.0);
        // Damping acts on a loaded inner contact only (as the ring level: "on loaded balls
        // only"), blended in over its Hertz approach `r_i²`; the damped rate is the total
        // approach's (massless balls) or the inner one's (radial mass). Blending on the
        // total approach instead let a ball that centrifugal force holds off the inner race
        // (`delta > 0`, `Q_i = 0`, fast) push and pull the shaft through an open contact:
        // a force with no ball loaded, and no stiffness to show it (the static start of a
        // load-driven ring then failed at 120 000 rpm).
        let (app, mut dd) = (sp.r_i * sp.r_i, if ld.radial { -u_dot } else { 0.0 });
        let mut extra_dissipation = 0.0;
        if p.contact_damping > 0.0 && app > 0.0 {
            da1 = v[2] + self.ri * (v[3] * s - v[4] * c) + w_b * self.ri * (q[3] * c + q[4] * s);
            da2 = v[0] * c + v[1] * s + w_b * (-q[0] * s + q[1] * c);
            let blend = (app / crate::models::ring::DAMPING_RAMP).min(1.0);
            cd = p.contact_damping * blend;
            dd += n[0] * da1 + n[1] * da2;
            fn_ += cd * dd;
        }
        if ld.radial {
            // Newton along the contact line: inner load and damping outwards, outer load
            // and damping (on u', the outer ring fixed) inwards, centrifugal force.
            let r_o2 = sp.r_o * sp.r_o;
            let cd_o = p.contact_damping * (r_o2 / crate::models::ring::DAMPING_RAMP).min(1.0);
            let f_out = q_o + if r_o2 > 0.0 { cd_o * u_dot } else { 0.0 };
            dx[3] = u_dot;
            dx[4] = (fn_ - f_out + ld.fc * n[1]) / self.m;
            extra_dissipation = cd * dd * dd
                + if r_o2 > 0.0 {
                    cd_o * u_dot * u_dot
                } else {
                    0.0
                };
        }
        let mut wrench = [0.0; 5];
        for (wk, gk) in wrench.iter_mut().zip(g) {
            *wk = -fn_ * gk;
        }
        wrench[0] += f_i * s;
        wrench[1] -= f_i * c;
        let plane = |fa: f64, fr: f64, m: f64| [fr * c, fr * s, fa, m * s, -m * c];
        if f_g != 0.0 {
            let fa = -f_g * n[1];
            let fr = f_g * n[0];
            let wg = plane(fa, fr, self.ri * fa + self.fid * f_g);
            for (wk, x) in wrench.iter_mut().zip(wg) {
                *wk += x;
            }
        }
        wrench[3] += ms_i * n[1] * c;
        wrench[4] += ms_i * n[1] * s;
        if let Some(k) = kq {
            let g1 = [0.0, 0.0, 1.0, self.ri * s, -self.ri * c];
            let g2 = [c, s, 0.0, 0.0, 0.0];
            let LoadDerivs { dn0, dn1, dqi, dqo } = self.load_derivs(geo, ld);
            // Normal force with damping.
            let mut dfn = dqi;
            if cd > 0.0 {
                let ramp = app < crate::models::ring::DAMPING_RAMP;
                let h1 = [0.0, 0.0, 0.0, w_b * self.ri * c, w_b * self.ri * s];
                let h2 = [-w_b * s, w_b * c, 0.0, 0.0, 0.0];
                for i in 0..5 {
                    let ddd = da1 * dn0[i] + da2 * dn1[i] + n[0] * h1[i] + n[1] * h2[i];
                    // d(r_i²)/dq: the inner approach's, `dQ_i/dq / (dQ_i/d delta_i)`
                    // (the ball held with radial mass: `g`).
                    let dapp = if ld.radial {
                        g[i]
                    } else if sp.s_i > 0.0 {
                        dqi[i] / sp.s_i
                    } else {
                        0.0
                    };
                    let dcd = if ramp {
                        p.contact_damping / crate::models::ring::DAMPING_RAMP * dapp
                    } else {
                        0.0
                    };
                    dfn[i] += dd * dcd + cd * ddd;
                }
            }
            for rr in 0..5 {
                for cc in 0..5 {
                    let dg = (g1[rr] * g1[cc] + g2[rr] * g2[cc] - g[rr] * g[cc]) / geo.l;
                    k[rr][cc] -= g[rr] * dfn[cc] + fn_ * dg;
                }
            }
            // Traction along e_t.
            let tq = if q_i <= 0.0 {
                0.0
            } else if p.traction.needs_contact() {
                let h = 1e-7 * q_i;
                let (ca, cb) = (self.ax_i[0], self.ax_i[1]);
                let r3 = (q_i + h).cbrt() / self.kc3_i;
                let cs = ContactState {
                    a: ca * r3,
                    b: cb * r3,
                    ..self.contact_state(true, q_i + h, 0.0)
                };
                (p.traction.force(dv_i, u_i, &cs) - f_i) / h
            } else {
                f_i / q_i
            };
            for cc in 0..5 {
                k[0][cc] += s * tq * dqi[cc];
                k[1][cc] -= c * tq * dqi[cc];
            }
            // Lateral (gyroscopic) friction.
            if f_g != 0.0 {
                let (fg_qi, fg_qo) = g_lim.map_or((0.0, 0.0), |l| l.derivs());
                for cc in 0..5 {
                    let dfg = fg_qi * dqi[cc] + fg_qo * dqo[cc];
                    let dfa = -n[1] * dfg - f_g * dn1[cc];
                    let dfr = n[0] * dfg + f_g * dn0[cc];
                    let dm = self.ri * dfa + self.fid * dfg;
                    let col = plane(dfa, dfr, dm);
                    for rr in 0..5 {
                        k[rr][cc] += col[rr];
                    }
                }
            }
            // Spin moment on the shaft.
            if ms_i != 0.0 || msq_i != 0.0 {
                let dw0 = w_b - omega + w_rel_b * self.cos_a;
                let dw1 = -w_rel_b * self.sin_a;
                for cc in 0..5 {
                    let dm = msq_i * dqi[cc] + msw_i * (dw0 * dn0[cc] + dw1 * dn1[cc]);
                    let dmx = n[1] * dm + ms_i * dn1[cc];
                    k[3][cc] += c * dmx;
                    k[4][cc] += s * dmx;
                }
            }
        }
        BallOut {
            dx,
            cage_torque: -r * pocket - m_fric,
            wrench,
            torque_shaft: -0.5 * self.di * f_i + ms_i * n[0],
            torque_outer: 0.5 * self.do_ * f_o + ms_o * n[0],
            torque_drag: -(r * f_d + self.cos_a * m_d),
            power: f_i * dv_i + f_o * dv_o + ms_i * w_sp_i + ms_o * w_sp_o,
            pocket_energy: p.pocket_stiffness
                * (Self::pen_energy(xi - cp, w) + Self::pen_energy(-xi - cp, w)),
            dissipation: p.pocket_damping * (bl + bt) * xi_dot * xi_dot
                - m_fric * (w_a * self.cos_a - w_c)
                + f_d * vb
                + m_d * w_a
                + extra_dissipation,
            g,
            cd,
            state: BallState {
                psi,
                w_b,
                w_s,
                q_i,
                q_o,
                dv_i,
                dv_o,
                f_i,
                f_o,
                pocket,
                gyro: f_g,
                spin_i: ms_i,
                spin_o: ms_o,
            },
        }
    }

    /// Pocket force on ball `j` and the pocket friction moment (module docs);
    /// `st = [theta_c, w_c, psi, w_b, w_a]`.
    pub(super) fn pocket(&self, j: usize, st: [f64; 5]) -> Pocket {
        let [theta_c, w_c, psi, w_b, w_a] = st;
        let p = &self.p;
        let r = 0.5 * self.dm;
        let hd = 0.5 * self.d;
        let pocket_angle = theta_c + 2.0 * PI * j as f64 / self.z as f64 + self.offsets[j];
        let xi = r * (psi - pocket_angle);
        let xi_dot = r * (w_b - w_c);
        let cp = p.pocket_clearance;
        let w = p.pocket_smoothing;
        let (pl, bl) = Self::pen(xi - cp, w);
        let (pt, bt) = Self::pen(-xi - cp, w);
        let force = -p.pocket_stiffness * (pl - pt) - p.pocket_damping * (bl + bt) * xi_dot;
        let slide = hd * (w_a * self.cos_a - w_c);
        let m_fric = if force == 0.0 {
            0.0
        } else {
            -hd * p.pocket_friction
                * force.abs()
                * crate::contact::traction::tanh(slide / p.friction_v_s)
        };
        Pocket {
            xi,
            xi_dot,
            bl,
            bt,
            force,
            m_fric,
        }
    }

    /// Lateral friction force `F` that carries the gyroscopic couple
    /// `Mg = J w_s w_b sin(alpha)` (Harris & Kotzalas Vol. 2 ch. 3), `+F` on the ball at
    /// the inner contact and `-F` at the outer one along `(n1, -n0)` (so the ball's lateral
    /// force balance closes and the couple is `F D = Mg`), limited as in the quasi-static
    /// kernel (`models::quasi_static::ball`): `F = (Mg/D) phi(mu Q_h D/|Mg|)`,
    /// `phi(t) = t/(1 + t⁴)^(1/4)`, `Q_h = Q_i Q_o/(Q_i + Q_o)`. Returns `F` and what
    /// [`GyroLimit::derivs`] needs for `(dF/dQ_i, dF/dQ_o)` (only the stiffness reads
    /// them, so the right-hand side does not pay their divisions).
    pub(super) fn gyro_force(
        &self,
        w_b: f64,
        w_s: f64,
        q_i: f64,
        q_o: f64,
    ) -> (f64, Option<GyroLimit>) {
        if !self.p.gyroscopic || q_i <= 0.0 || q_o <= 0.0 {
            return (0.0, None);
        }
        let fb = self.j * w_s * w_b * self.sin_a / self.d;
        if fb == 0.0 {
            return (0.0, None);
        }
        let mu = self.p.gyro_traction;
        if !mu.is_finite() {
            return (fb, None);
        }
        let sum = q_i + q_o;
        let qh = q_i * q_o / sum;
        let t = mu * qh / fb.abs();
        let t4 = 1.0 + t * t * t * t;
        let r4 = t4.sqrt().sqrt();
        let phi = t / r4;
        let lim = GyroLimit {
            mu,
            t4,
            r4,
            sign: fb.signum(),
            q_i,
            q_o,
            sum,
        };
        (fb * phi, Some(lim))
    }

    /// Whether the rates are linear in each normal load through the traction alone and
    /// read no contact data: the Coulomb law (`mu tanh(dv/v_s) Q`), no spin friction,
    /// no radial mass. Then the Jacobian takes some columns analytically
    /// ([`Self::wa_column`], and `d(rates)/dQ = (f/Q)·(d(rates)/df)`).
    pub(super) fn coulomb_rates(&self, ld: &Loads) -> Option<(f64, f64)> {
        #[cfg(test)]
        if tests::FD_ONLY.with(std::cell::Cell::get) {
            return None;
        }
        match self.p.traction {
            TractionLaw::Coulomb { mu_max, v_s } if self.p.spin_friction <= 0.0 && !ld.radial => {
                Some((mu_max, v_s))
            }
            _ => None,
        }
    }

    /// Right-hand side at shaft motion `(q, v, omega)`: fills `dx` and the per-ball and
    /// total results (`self.balls`, return value). Allocation-free.
    pub fn eval(
        &mut self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        dx: &mut [f64],
    ) -> SkidTotals {
        self.eval_inner(
            &Motion {
                q: *q,
                v: *v,
                omega,
            },
            x,
            dx,
            None,
        )
    }

    /// [`Self::eval`] at shaft motion `m` plus the shaft stiffness `k = -dW/dq` and damping
    /// `c = -dW/dv` with the balls and cage held (analytic, at the cost of about one
    /// right-hand side).
    pub fn eval_with_stiffness(
        &mut self,
        m: &Motion,
        x: &[f64],
        dx: &mut [f64],
        k: &mut [[f64; 5]; 5],
        c: &mut [[f64; 5]; 5],
    ) -> SkidTotals {
        let mut kw = [[0.0; 5]; 5];
        let tot = self.eval_inner(m, x, dx, Some((&mut kw, c)));
        for (kr, wr) in k.iter_mut().zip(kw) {
            for (kk, w) in kr.iter_mut().zip(wr) {
                *kk = -w;
            }
        }
        tot
    }

    #[allow(clippy::type_complexity)]
    pub(super) fn eval_inner(
        &mut self,
        m: &Motion,
        x: &[f64],
        dx: &mut [f64],
        mut kc: Option<(&mut [[f64; 5]; 5], &mut [[f64; 5]; 5])>,
    ) -> SkidTotals {
        let mut tot = SkidTotals::default();
        let ic = self.cage_index();
        let (theta_c, w_c) = (x[ic], x[ic + 1]);
        let mut cage_torque = -self.p.cage_drag * w_c;
        tot.torque_drag -= self.p.cage_drag * w_c;
        tot.power_other += self.p.cage_drag * w_c * w_c;
        if let Some((_, c)) = kc.as_mut() {
            **c = [[0.0; 5]; 5];
        }
        for j in 0..self.z {
            let k = BALL0 + self.bs * j;
            let geo = self.geo(&m.q, x[k]);
            let (u, ud) = if self.bs == 5 {
                (Some(x[k + 3]), x[k + 4])
            } else {
                (None, 0.0)
            };
            let ld = self.loads(&geo, x[k + 1], u);
            let st = [theta_c, w_c, x[k], x[k + 1], x[k + 2], u.unwrap_or(0.0), ud];
            let b = self.forces(j, &geo, &ld, m, st, kc.as_mut().map(|(k, _)| &mut **k));
            if let Some((_, c)) = kc.as_mut() {
                for r in 0..5 {
                    for cc in 0..5 {
                        c[r][cc] += b.cd * b.g[r] * b.g[cc];
                    }
                }
            }
            dx[k..k + self.bs].copy_from_slice(&b.dx[..self.bs]);
            cage_torque += b.cage_torque;
            for (t, w) in tot.wrench.iter_mut().zip(b.wrench) {
                *t += w;
            }
            tot.torque_shaft += b.torque_shaft;
            tot.torque_outer += b.torque_outer;
            tot.torque_drag += b.torque_drag;
            tot.power_contacts += b.power;
            tot.power_other += b.dissipation;
            tot.pocket_energy += b.pocket_energy;
            if b.state.q_i > 0.0 {
                tot.loaded += 1;
            }
            tot.max_load = tot.max_load.max(b.state.q_i).max(b.state.q_o);
            self.balls[j] = b.state;
        }
        dx[ic] = w_c;
        dx[ic + 1] = cage_torque / self.jc;
        tot
    }
}
