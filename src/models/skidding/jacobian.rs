//! The skidding level's Jacobian: the load derivatives and the analytic columns, with the
//! Coulomb (regularised traction) slopes.

use super::*;
use crate::seam::{Jacobians, Motion};

impl SkiddingModel {
    /// Derivatives with respect to `q` of the contact line `n` and of the normal loads
    /// (balls held): `dn = (G - n g)/|A|` with `G = dA/dq`, and from the split
    /// `Q_o(x) - Q_i(delta - x) = f`: `dQ_i = (s_i s_o d delta - s_i df)/(s_i + s_o)`,
    /// `dQ_o = (s_i s_o d delta + s_o df)/(s_i + s_o)` (`s` the contact stiffnesses,
    /// `f = Fc n_r`); a ball on the outer race only has `dQ_o = df`.
    pub(super) fn load_derivs(&self, geo: &Geo, ld: &Loads) -> LoadDerivs {
        let (s, c, n, g) = (geo.s, geo.c, geo.n, geo.g);
        let g1 = [0.0, 0.0, 1.0, self.ri * s, -self.ri * c];
        let g2 = [c, s, 0.0, 0.0, 0.0];
        let dn0: [f64; 5] = std::array::from_fn(|i| (g1[i] - n[0] * g[i]) / geo.l);
        let dn1: [f64; 5] = std::array::from_fn(|i| (g2[i] - n[1] * g[i]) / geo.l);
        let df: [f64; 5] = std::array::from_fn(|i| if ld.f_active { ld.fc * dn1[i] } else { 0.0 });
        let sp = &ld.sp;
        let (ai, bi, ao, bo) = if ld.radial {
            // The ball held: only the inner approach changes.
            (sp.s_i, 0.0, 0.0, 0.0)
        } else if sp.q_i > 0.0 && sp.q_o > 0.0 {
            let ss = sp.s_i + sp.s_o;
            let h = sp.s_i * sp.s_o / ss;
            (h, -sp.s_i / ss, h, sp.s_o / ss)
        } else if sp.q_o > 0.0 {
            (0.0, 0.0, 0.0, 1.0)
        } else {
            (0.0, 0.0, 0.0, 0.0)
        };
        LoadDerivs {
            dn0,
            dn1,
            dqi: std::array::from_fn(|i| ai * g[i] + bi * df[i]),
            dqo: std::array::from_fn(|i| ao * g[i] + bo * df[i]),
        }
    }

    /// `dT/d(dv)` of the Coulomb law `T = mu tanh(dv/v_s) Q` at force `f` (`tanh` from
    /// `f/(mu Q)`, no second `exp`): `mu Q (1 - tanh²)/v_s`.
    pub(super) fn coulomb_slope(mu: f64, v_s: f64, q: f64, f: f64) -> f64 {
        if q <= 0.0 || mu == 0.0 {
            return 0.0;
        }
        let th = f / (mu * q);
        mu * q * (1.0 - th * th) / v_s
    }

    /// The `w_a` column of one ball under [`Self::coulomb_rates`], analytically (the
    /// geometry and loads do not depend on `w_a`): `d(rates)/dw_a`, `d(cage torque)/dw_a`
    /// and `d(wrench)/dw_a` at the point `b` of [`Self::forces`] with its pocket `pk`.
    /// `w_a` enters the slips (`d dv_i = d dv_o = (D/2) d w_a`), the gyroscopic couple
    /// through `w_s` (`d w_s = -d w_a`; the limited force `F = F_b phi(t)`,
    /// `t = mu Q_h/|F_b|`, has `dF/dF_b = phi - t phi'(t) = phi t⁴/(1 + t⁴)`), the pocket
    /// friction through its slide and the spin drag (the terms of the module docs; the
    /// limiter is the quasi-static kernel's, Harris & Kotzalas Vol. 2 ch. 3). Checked
    /// against central differences in a unit test.
    pub(super) fn wa_column(
        &self,
        (mu, v_s): (f64, f64),
        geo: &Geo,
        b: &BallOut,
        pk: &Pocket,
    ) -> ([f64; 3], f64, [f64; 5]) {
        let p = &self.p;
        let (r, hd) = (0.5 * self.dm, 0.5 * self.d);
        let st = &b.state;
        let dfi = Self::coulomb_slope(mu, v_s, st.q_i, st.f_i) * hd;
        let dfo = Self::coulomb_slope(mu, v_s, st.q_o, st.f_o) * hd;
        // Pocket friction M = -(D/2) mu_c |P| tanh(slide/v_s), slide = (D/2)(w_a cos a - w_c).
        // (`tanh` from the moment itself, no second `exp`.)
        let dmf = if pk.force == 0.0 || p.pocket_friction == 0.0 {
            0.0
        } else {
            let m0 = -hd * p.pocket_friction * pk.force.abs();
            let th = pk.m_fric / m0;
            m0 * (1.0 - th * th) / p.friction_v_s * (hd * self.cos_a)
        };
        let dmd = PI * p.drag_viscosity * self.d.powi(3);
        let dx = [
            0.0,
            (dfi - dfo) / (self.m * r),
            (-hd * (dfi + dfo) + dmf * self.cos_a - dmd) / self.j,
        ];
        let (s, c, n) = (geo.s, geo.c, geo.n);
        let mut dw = [dfi * s, -dfi * c, 0.0, 0.0, 0.0];
        if p.gyroscopic && st.q_i > 0.0 && st.q_o > 0.0 {
            let fb = self.j * st.w_s * st.w_b * self.sin_a / self.d;
            let mu_g = p.gyro_traction;
            let slope = if fb == 0.0 || !mu_g.is_finite() {
                1.0
            } else {
                let t = mu_g * (st.q_i * st.q_o / (st.q_i + st.q_o)) / fb.abs();
                let t4 = t * t * t * t;
                (st.gyro / fb) * t4 / (1.0 + t4)
            };
            let dfg = -slope * self.j * st.w_b * self.sin_a / self.d;
            let (fa, fr) = (-dfg * n[1], dfg * n[0]);
            let m = self.ri * fa + self.fid * dfg;
            for (w, x) in dw.iter_mut().zip([fr * c, fr * s, fa, m * s, -m * c]) {
                *w += x;
            }
        }
        (dx, -dmf, dw)
    }

    /// Jacobians at shaft motion `m` into `jac` by per-ball finite differences (each ball's terms depend only on its own
    /// states, the cage's and the ring's, so a column costs one ball evaluation, not a
    /// whole right-hand side; the columns of `w_a` and of the cage reuse the ball's
    /// geometry and loads, which do not depend on them): `jx = d(rates)/d(states)`
    /// (`n × n`, row-major), `jm = d(rates)/d(q, v)` (`n × 10`), `wx = d(wrench)/d(states)`
    /// (`5 × n`), `wm = d(wrench)/d(q, v)` (`5 × 10`). Allocation-free. The entries of
    /// `jx` coupling two different balls are zero and are not written (give a zeroed
    /// buffer; the component's block copy never reads them).
    pub fn jacobian(&self, m: &Motion, x: &[f64], jac: Jacobians<'_>, q_cols: &[usize]) {
        let Jacobians { jx, jm, wx, wm } = jac;
        let n = self.n_states();
        let ic = self.cage_index();
        // Cleared: each ball row's cage columns (its block is overwritten below) and the
        // cage rows; not the `n²` entries between balls.
        for r in 0..ic {
            jx[r * n + ic..r * n + ic + 2].fill(0.0);
        }
        jx[ic * n..].fill(0.0);
        jm.fill(0.0);
        wx.fill(0.0);
        wm.fill(0.0);
        let (theta_c, w_c) = (x[ic], x[ic + 1]);
        let jc = self.jc;
        let cr = (ic + 1) * n; // the cage speed's row
        jx[ic * n + ic + 1] = 1.0; // d theta_c' / d w_c
        jx[cr + ic + 1] = -self.p.cage_drag / jc;
        let eps = f64::EPSILON.sqrt();
        for j in 0..self.z {
            let bs = self.bs;
            let k = BALL0 + bs * j;
            let mut st = [0.0; 5];
            st[..bs].copy_from_slice(&x[k..k + bs]);
            let radial = |s: &[f64; 5]| (bs == 5).then_some(s[3]);
            let geo = self.geo(&m.q, st[0]);
            let ld = self.loads(&geo, st[1], radial(&st));
            let at = |s5: [f64; 7]| self.forces(j, &geo, &ld, m, s5, None);
            let st5 = [theta_c, w_c, st[0], st[1], st[2], st[3], st[4]];
            // The base point, with the analytic wrench stiffness when the ring's columns
            // are wanted.
            let mut kw = [[0.0; 5]; 5];
            let base = if jm.is_empty() {
                at(st5)
            } else {
                self.forces(j, &geo, &ld, m, st5, Some(&mut kw))
            };
            let pk0 = self.pocket(j, [theta_c, w_c, st[0], st[1], st[2]]);
            let coulomb = self.coulomb_rates(&ld);
            // Ball columns.
            for col in 0..bs {
                if let (2, Some(law)) = (col, coulomb) {
                    let (d, dc, dw) = self.wa_column(law, &geo, &base, &pk0);
                    let c = k + 2;
                    for (r, dr) in d.iter().enumerate() {
                        jx[(k + r) * n + c] = *dr;
                    }
                    jx[cr + c] = dc / jc;
                    if !wx.is_empty() {
                        for (r, dr) in dw.iter().enumerate() {
                            wx[r * n + c] = *dr;
                        }
                    }
                    continue;
                }
                // psi: 1e-7 rad (the loads' solve leaves a relative noise of ~1e-13 in
                // the rates, which a 1e-9 step would amplify to ~30 %).
                let h = match col {
                    0 => 1e-7,
                    3 => 1e-4 * st[3].abs().max(1e-8),
                    4 => 1e-6,
                    _ => eps * st[col].abs().max(1.0),
                };
                let mut sp = st;
                sp[col] += h;
                let s5 = [theta_c, w_c, sp[0], sp[1], sp[2], sp[3], sp[4]];
                let b = match col {
                    // w_a, u': same geometry and loads.
                    2 | 4 => at(s5),
                    // w_b, u: same geometry, new loads.
                    1 | 3 => {
                        let ld1 = self.loads(&geo, sp[1], radial(&sp));
                        self.forces(j, &geo, &ld1, m, s5, None)
                    }
                    _ => self.ball_r(j, m, s5),
                };
                let c = k + col;
                for r in 0..bs {
                    jx[(k + r) * n + c] = (b.dx[r] - base.dx[r]) / h;
                }
                jx[cr + c] = (b.cage_torque - base.cage_torque) / (h * jc);
                if !wx.is_empty() {
                    for r in 0..5 {
                        wx[r * n + c] = (b.wrench[r] - base.wrench[r]) / h;
                    }
                }
            }
            // Cage columns: only the pocket terms depend on the cage.
            let rr = 0.5 * self.dm;
            for col in 0..2 {
                let (tc, wc, h) = if col == 0 {
                    (theta_c + 1e-9, w_c, 1e-9)
                } else {
                    let h = eps * w_c.abs().max(1.0);
                    (theta_c, w_c + h, h)
                };
                let pk = self.pocket(j, [tc, wc, st[0], st[1], st[2]]);
                let (dp, dmf) = (pk.force - pk0.force, pk.m_fric - pk0.m_fric);
                jx[(k + 1) * n + ic + col] = dp / (self.m * rr * h);
                jx[(k + 2) * n + ic + col] = dmf * self.cos_a / (self.j * h);
                jx[cr + ic + col] += (-rr * dp - dmf) / (h * jc);
            }
            if jm.is_empty() {
                continue;
            }
            // Velocity columns: only the contact damping `-cd g g^T` depends on v (and,
            // with radial mass, the ball's radial acceleration through the same term).
            for r in 0..5 {
                for c in 0..5 {
                    wm[r * 10 + 5 + c] -= base.cd * base.g[r] * base.g[c];
                }
            }
            if bs == 5 {
                for c in 0..5 {
                    jm[(k + 4) * 10 + 5 + c] = base.cd * base.g[c] / self.m;
                }
            }
            // Displacement columns. The rates depend on q only through three scalars:
            // the loads Q_i, Q_o and the direction of the contact line (n rotates by
            // d theta = n1 dn0 - n0 dn1, a unit vector). Difference along each and chain
            // with their analytic derivatives (no new geometry or split); the wrench's
            // columns are the analytic stiffness. (With radial mass the damping of the
            // ball's radial motion also sees q through the ring-geometry rate `delta'`; that
            // small term is left out of this Jacobian, which only costs step efficiency.)
            let dl = self.load_derivs(&geo, &ld);
            let mut dpar = [[0.0; 5]; 3]; // dpar[param][rate]: d(rates)/d(Q_i, Q_o, theta)
            let mut dcage = [0.0; 3];
            let sp0 = ld.sp;
            for (kp, dp) in dpar.iter_mut().enumerate() {
                let (mut gp, mut lp) = (geo, ld);
                let h;
                match kp {
                    0 | 1 => {
                        let (q0, s0) = if kp == 0 {
                            (sp0.q_i, sp0.s_i)
                        } else {
                            (sp0.q_o, sp0.s_o)
                        };
                        if s0 <= 0.0 {
                            continue;
                        }
                        if let Some((mu, v_s)) = coulomb {
                            // Linear in the load through the traction: dT/dQ = T/Q
                            // (mu tanh(dv/v_s) at no load); the cage does not see it.
                            let (f, dv) = if kp == 0 {
                                (base.state.f_i, base.state.dv_i)
                            } else {
                                (base.state.f_o, base.state.dv_o)
                            };
                            let df = if q0 > 0.0 {
                                f / q0
                            } else {
                                mu * crate::contact::traction::tanh(dv / v_s)
                            };
                            let sign = if kp == 0 { 1.0 } else { -1.0 };
                            dp[1] = sign * df / (self.m * 0.5 * self.dm);
                            dp[2] = -0.5 * self.d * df / self.j;
                            continue;
                        }
                        h = 1e-7 * q0.max(1e-3);
                        let sp = &mut lp.sp;
                        let (qq, rr) = if kp == 0 {
                            (&mut sp.q_i, &mut sp.r_i)
                        } else {
                            (&mut sp.q_o, &mut sp.r_o)
                        };
                        *qq += h;
                        *rr = (*rr * *rr + h / s0).sqrt();
                    }
                    _ => {
                        // Without spin friction and radial mass the rates and the cage
                        // torque do not read the contact line's direction (only the
                        // wrench does): the difference is exactly zero, as left.
                        if self.p.spin_friction <= 0.0 && !ld.radial {
                            continue;
                        }
                        h = 1e-8;
                        gp.n = [geo.n[0] + h * geo.n[1], geo.n[1] - h * geo.n[0]];
                    }
                }
                let b = self.forces_on::<false>(j, &gp, &lp, m, st5, None);
                for ((d, bx), b0) in dp.iter_mut().zip(b.dx).zip(base.dx) {
                    *d = (bx - b0) / h;
                }
                dcage[kp] = (b.cage_torque - base.cage_torque) / h;
            }
            for &col in q_cols {
                for r in 0..5 {
                    wm[r * 10 + col] += kw[r][col];
                }
                let dth = geo.n[1] * dl.dn0[col] - geo.n[0] * dl.dn1[col];
                let chain = [dl.dqi[col], dl.dqo[col], dth];
                for r in 0..bs {
                    jm[(k + r) * 10 + col] = (0..3).map(|kp| dpar[kp][r] * chain[kp]).sum();
                }
                jm[(ic + 1) * 10 + col] += (0..3).map(|kp| dcage[kp] * chain[kp]).sum::<f64>() / jc;
            }
        }
    }
}
