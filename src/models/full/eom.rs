//! Equations of motion of the full level: ball positions (quasi-static or dynamic), ball and
//! cage rates, the evaluation of all right-hand sides, the wrench on the shaft and the start
//! from the quasi-static solution (docs/physics.md §5.5).

use super::*;
use crate::seam::Motion;

impl FullModel {
    /// Quasi-static ball position for ball states `xb` (warm start in `aux[0..3]`:
    /// `X1, X2, warm flag`); updates the warm start.
    pub(super) fn ball_position(
        &self,
        q: &[f64; 5],
        xb: &[f64],
        aux: &mut [f64],
    ) -> Result<[f64; 2]> {
        Ok(self.ball_position_contacts(q, xb, aux)?.0)
    }

    /// [`Self::ball_position`] with the contacts there when the solve has them.
    pub(super) fn ball_position_contacts(
        &self,
        q: &[f64; 5],
        xb: &[f64],
        aux: &mut [f64],
    ) -> Result<([f64; 2], Option<[ball::Contact; 2]>)> {
        let psi = xb[0];
        let w_orb = xb[1] / self.t0;
        let a = self.groove_offset(q, psi);
        let start = (aux[2] != 0.0).then_some([aux[0], aux[1]]);
        let (x, c) = self
            .pos
            .solve_contacts(a, self.m * w_orb * w_orb, start, POS_TOL)?;
        aux[0] = x[0];
        aux[1] = x[1];
        aux[2] = 1.0;
        Ok((x, c))
    }

    /// Ball kinematics and position `xrel` at its states `xb`: quasi-static, the position
    /// re-solved (warm start in `aux` updated) when `solve`, else the one `aux` holds (the
    /// solution for these `q`, `psi` and `w_orb`, which a solve from it returns unchanged).
    pub(super) fn ball_kin_at(
        &self,
        j: usize,
        q: &[f64; 5],
        xb: &[f64],
        aux: &mut [f64],
        solve: bool,
    ) -> Result<(BallKin, [f64; 2], Option<[ball::Contact; 2]>)> {
        Ok(match self.p.ball_contacts {
            BallContacts::QuasiStatic => {
                let a = &mut aux[3 * j..3 * j + 3];
                let (xr, c) = if solve {
                    self.ball_position_contacts(q, xb, a)?
                } else {
                    ([a[0], a[1]], None)
                };
                (self.ball_kin(xb, xr), xr, c)
            }
            BallContacts::Dynamic => {
                let bk = self.ball_kin(xb, [0.0; 2]);
                (bk, [bk.z - self.z_og, bk.rho - self.pos.r_og], None)
            }
        })
    }

    /// The race part of ball `j`'s terms at the shaft's motion `m` and the ball's states
    /// `xb` ([`Self::ball_kin_at`]).
    pub(super) fn ball_race_at(
        &self,
        j: usize,
        m: &Motion,
        xb: &[f64],
        aux: &mut [f64],
        solve: bool,
    ) -> Result<BallRace> {
        let (bk, xrel, c) = self.ball_kin_at(j, &m.q, xb, aux, solve)?;
        let known = c.map_or(Known::Nothing, Known::Solved);
        Ok(self.ball_race(m, &bk, xrel, known))
    }

    /// Ball rates (stored-state derivatives) from its terms.
    pub(super) fn ball_rates(&self, bt: &BallTerms, xb: &[f64], d: &mut [f64]) {
        let (l, t0) = (self.l, self.t0);
        match self.p.ball_contacts {
            BallContacts::QuasiStatic => {
                d[0] = xb[1] / t0;
                d[1] = bt.acc[1] * t0;
                d[2] = bt.w_dot[0] * t0;
                d[3] = bt.w_dot[1] * t0;
                d[4] = bt.w_dot[2] * t0;
            }
            BallContacts::Dynamic => {
                d[0] = xb[3] / t0;
                d[1] = xb[4] / t0;
                d[2] = xb[5] / t0;
                d[3] = bt.acc[0] * t0 / l;
                d[4] = bt.acc[2] * t0 / l;
                d[5] = bt.acc[1] * t0;
                d[6] = bt.w_dot[0] * t0;
                d[7] = bt.w_dot[1] * t0;
                d[8] = bt.w_dot[2] * t0;
            }
        }
    }

    /// Add to `d` (cage rates) the part linear in a change `(df, dm)` of the balls' force
    /// on the cage and moment about its centre.
    pub(super) fn cage_rates_from(&self, df: V3, dm: V3, d: &mut [f64]) {
        let (l, t0) = (self.l, self.t0);
        match self.p.cage {
            CageModel::Ideal => d[1] += dm[2] / self.ip * t0,
            CageModel::Free => {
                for k in 0..3 {
                    d[6 + k] += df[k] / self.mc * t0 / l;
                }
                d[9] += dm[0] / self.it * t0;
                d[10] += dm[1] / self.it * t0;
                d[11] += dm[2] / self.ip * t0;
            }
        }
    }

    /// The wrench on the shaft alone at motion `(q, v, omega)` and states `x`, as
    /// [`Self::eval`] gives it (the same numbers), without the pockets, the outer contacts
    /// and the rates: what the outputs' stiffness and damping difference. Quasi-static
    /// positions are solved from `aux` (updated) when `solve`, else taken from `aux` (the
    /// solution at this `q`: a velocity `v` does not move them).
    pub fn wrench_at(
        &self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        aux: &mut [f64],
        solve: bool,
    ) -> Result<[f64; 5]> {
        let motion = Motion {
            q: *q,
            v: *v,
            omega,
        };
        let mut w = [0.0; 5];
        // Positions kept at the displacement and states of the last evaluation, from the
        // warm starts it left: its frames, contacts and contact states are these.
        let m = &self.memo;
        let kept = (!solve || self.n_aux() == 0)
            && m.p.as_ref() == Some(&self.p)
            && same_bits(&m.motion[..5], q)
            && same_bits(&m.x, x)
            && same_bits(&m.aux_out, aux);
        for j in 0..self.z {
            let k = self.nc + self.nb * j;
            let (bk, xrel, c) = self.ball_kin_at(j, q, &x[k..k + self.nb], aux, solve)?;
            let (fr, known) = if kept {
                (m.races[j].fr, Known::Kept(&m.races[j]))
            } else {
                (BallFrame::new(&bk), c.map_or(Known::Nothing, Known::Solved))
            };
            let inn = self.inner_contact(&motion, &bk, &fr, xrel, known);
            for (a, b) in w.iter_mut().zip(inn.wrench) {
                *a += b;
            }
        }
        if let (CageModel::Free, Some(guide), true) = (self.p.cage, &self.guide, self.guided_inner)
        {
            let ck = self.cage_kin(x);
            let e = [ck.c[0] - q[0], ck.c[1] - q[1]];
            let e_dot = [ck.v[0] - v[0], ck.v[1] - v[1]];
            let g = guide.force(e, e_dot, ck.w, omega);
            w[0] -= g.f[0];
            w[1] -= g.f[1];
        }
        Ok(w)
    }

    /// Right-hand side: fills `dx` (derivatives of the stored states in physical time),
    /// `self.balls` and the totals. Allocation-free.
    pub fn eval(
        &mut self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        aux: &mut [f64],
        dx: &mut [f64],
    ) -> Result<Totals> {
        self.eval_memo(
            &Motion {
                q: *q,
                v: *v,
                omega,
            },
            x,
            aux,
            dx,
            false,
        )
    }

    /// [`Self::eval`] at the shaft's motion `m`, the balls' race parts kept for
    /// [`Self::jacobian_from`].
    pub(crate) fn eval_keep(
        &mut self,
        m: &Motion,
        x: &[f64],
        aux: &mut [f64],
        dx: &mut [f64],
    ) -> Result<Totals> {
        self.eval_memo(m, x, aux, dx, true)
    }

    /// [`Self::eval`] at the shaft's motion `shaft` (`keep`: [`Self::eval_keep`]), the
    /// numbers of the last one taken when it was at the same point ([`Memo`]).
    pub(super) fn eval_memo(
        &mut self,
        shaft: &Motion,
        x: &[f64],
        aux: &mut [f64],
        dx: &mut [f64],
        keep: bool,
    ) -> Result<Totals> {
        let motion = motion_of(&shaft.q, &shaft.v, shaft.omega);
        let m = &self.memo;
        if m.p.as_ref() == Some(&self.p)
            && same_bits(&m.motion, &motion)
            && same_bits(&m.x, x)
            && (same_bits(&m.aux_in, aux) || same_bits(&m.aux_out, aux))
        {
            aux.copy_from_slice(&m.aux_out);
            dx.copy_from_slice(&m.dx);
            self.balls.copy_from_slice(&m.balls);
            if keep {
                self.races.copy_from_slice(&m.races);
                self.terms.copy_from_slice(&m.terms);
            }
            return Ok(m.tot);
        }
        self.memo.p = None;
        self.memo.aux_in.copy_from_slice(aux);
        let tot = if keep {
            let tot = self.eval_with(shaft, x, aux, dx, Races::Keep)?;
            self.memo.races.copy_from_slice(&self.races);
            self.memo.terms.copy_from_slice(&self.terms);
            tot
        } else {
            // The race parts and terms into the memo's, the kept ones left as they are.
            std::mem::swap(&mut self.races, &mut self.memo.races);
            std::mem::swap(&mut self.terms, &mut self.memo.terms);
            let tot = self.eval_with(shaft, x, aux, dx, Races::Keep);
            std::mem::swap(&mut self.races, &mut self.memo.races);
            std::mem::swap(&mut self.terms, &mut self.memo.terms);
            tot?
        };
        let m = &mut self.memo;
        m.motion = motion;
        m.x.copy_from_slice(x);
        m.aux_out.copy_from_slice(aux);
        m.dx.copy_from_slice(dx);
        m.tot = tot;
        m.balls.copy_from_slice(&self.balls);
        m.p = Some(self.p.clone());
        Ok(tot)
    }

    /// [`Self::eval`] at the shaft's motion `m`, the balls' race parts computed, kept or
    /// taken from the kept ones.
    pub(super) fn eval_with(
        &mut self,
        m: &Motion,
        x: &[f64],
        aux: &mut [f64],
        dx: &mut [f64],
        races: Races,
    ) -> Result<Totals> {
        let (l, t0) = (self.l, self.t0);
        let ck = self.cage_kin(x);
        self.pocket_trig(ck.theta);
        let mut tot = Totals::default();
        let mut cf = [0.0; 3];
        let mut cm = [0.0; 3];
        for j in 0..self.z {
            let k = self.nc + self.nb * j;
            let xb = &x[k..k + self.nb];
            let sc = self.pocket_sc[j];
            let bt = match races {
                Races::Kept => self.ball_cage(&ck, sc, &self.races[j]),
                Races::Ring { moved } if !moved || self.n_aux() == 0 => {
                    let (kr, kt) = (&self.races[j], &self.terms[j]);
                    let known = if moved {
                        Known::Outer(kr)
                    } else {
                        Known::Kept(kr)
                    };
                    let r = self.ball_race(m, &kr.bk, kr.xrel, known);
                    self.ball_terms(&r, &kt.pocket)
                }
                Races::Ring { .. } => {
                    // Quasi-static positions at the moved ring: solved again.
                    let r = self.ball_race_at(j, m, xb, aux, true)?;
                    self.ball_cage(&ck, sc, &r)
                }
                Races::Keep => {
                    self.races[j] = self.ball_race_at(j, m, xb, aux, true)?;
                    let bt = self.ball_cage(&ck, sc, &self.races[j]);
                    self.terms[j] = bt;
                    // The per-ball results with their contact angles (the Jacobian's
                    // evaluations, kept or ring columns, leave them).
                    let [ci, co] = self.races[j].contacts;
                    self.balls[j] = BallInfo {
                        alpha_i: ci.n[0].atan2(ci.n[1]),
                        alpha_o: co.n[0].atan2(co.n[1]),
                        ..bt.info
                    };
                    bt
                }
            };
            self.ball_rates(&bt, xb, &mut dx[k..k + self.nb]);
            cf = add(cf, bt.cage_f);
            cm = add(cm, bt.cage_m);
            let pw = dot(bt.cage_f, ck.v);
            tot.pocket_power_whirl += pw;
            tot.pocket_power += pw + dot(bt.cage_m, ck.omega());
            for (a, b) in tot.wrench.iter_mut().zip(bt.wrench) {
                *a += b;
            }
            tot.torque_shaft += bt.torque;
            tot.external_mz += bt.ext_mz;
            tot.power_contacts += bt.power;
            if bt.info.q_i > 0.0 {
                tot.loaded += 1;
            }
            tot.max_load = tot.max_load.max(bt.info.q_i).max(bt.info.q_o);
            tot.max_pressure = tot.max_pressure.max(bt.info.p_max);
            tot.pocket_max = tot.pocket_max.max(bt.info.pocket);
        }
        // Cage drag (both side faces).
        if self.p.drag > 0.0 {
            let md = -2.0
                * self.p.drag
                * disk_moment(&self.fluid, self.cage_r_in, self.cage_r_out, ck.w.abs()).abs()
                * ck.w.signum();
            cm[2] += md;
            tot.external_mz += md;
            tot.cage_drag_power = md * ck.w;
        }
        match self.p.cage {
            CageModel::Ideal => {
                dx[0] = x[1] / t0;
                dx[1] = cm[2] / self.ip * t0;
            }
            CageModel::Free => {
                let (e, e_dot, w_ring) = if self.guided_inner {
                    let (q, v) = (&m.q, &m.v);
                    (
                        [ck.c[0] - q[0], ck.c[1] - q[1]],
                        [ck.v[0] - v[0], ck.v[1] - v[1]],
                        m.omega,
                    )
                } else {
                    ([ck.c[0], ck.c[1]], [ck.v[0], ck.v[1]], 0.0)
                };
                if let Some(guide) = &self.guide {
                    let g = guide.force(e, e_dot, ck.w, w_ring);
                    cf[0] += g.f[0];
                    cf[1] += g.f[1];
                    cm[2] += g.torque;
                    tot.external_mz += ck.c[0] * g.f[1] - ck.c[1] * g.f[0] + g.torque;
                    tot.guide_force = g.f[0].hypot(g.f[1]);
                    tot.guide_power_whirl = g.f[0] * ck.v[0] + g.f[1] * ck.v[1];
                    tot.guide_power = tot.guide_power_whirl + g.torque * ck.w;
                    if self.guided_inner {
                        tot.wrench[0] -= g.f[0];
                        tot.wrench[1] -= g.f[1];
                        tot.torque_shaft -= g.torque;
                    }
                }
                let mut acc = scale(cf, 1.0 / self.mc);
                // Mass unbalance `u` (module docs): the geometric centre's acceleration is
                // the mass centre's minus that of `u (cos theta, sin theta)` about it.
                let u = self.p.cage_unbalance;
                if u != 0.0 {
                    let (s, c) = ck.theta.sin_cos();
                    let w_dot = cm[2] / self.ip;
                    acc[0] += u * (ck.w * ck.w * c + w_dot * s);
                    acc[1] += u * (ck.w * ck.w * s - w_dot * c);
                }
                let (bx_d, by_d) = (ck.bd[0], ck.bd[1]);
                let bxdd = (cm[0] - self.ip * ck.w * by_d) / self.it;
                let bydd = (cm[1] + self.ip * ck.w * bx_d) / self.it;
                for k in 0..3 {
                    dx[k] = x[6 + k] / t0;
                    dx[6 + k] = acc[k] * t0 / l;
                }
                dx[3] = x[9] / t0;
                dx[4] = x[10] / t0;
                dx[5] = x[11] / t0;
                dx[9] = bxdd * t0;
                dx[10] = bydd * t0;
                dx[11] = cm[2] / self.ip * t0;
            }
        }
        Ok(tot)
    }

    /// Angular momentum about `z` of balls and cage, kg m²/s (module docs).
    pub fn angular_momentum(&self, x: &[f64], aux: &[f64]) -> f64 {
        let ck = self.cage_kin(x);
        let mut lz = self.ip * ck.w + self.mc * (ck.c[0] * ck.v[1] - ck.c[1] * ck.v[0]);
        for j in 0..self.z {
            let k = self.nc + self.nb * j;
            let pos = if self.n_aux() > 0 {
                [aux[3 * j], aux[3 * j + 1]]
            } else {
                [0.0; 2]
            };
            let bk = self.ball_kin(&x[k..k + self.nb], pos);
            lz += self.m * bk.rho * bk.rho * bk.w_orb + self.j * bk.w[2];
        }
        lz
    }

    /// With dynamic ball contacts, move each ball's centre to where it rests at the ring
    /// displacement `q` — the radial/axial balance of its race loads and its centrifugal
    /// force at its orbital speed, solved as the quasi-static ball contacts solve it
    /// (the same position solve, from the ball's present position) — and zero its radial
    /// and axial velocity; the orbital and spin speeds are kept. The load-driven static
    /// start places the balls so at every trial displacement, which makes its equilibrium
    /// the whole bearing's, as with quasi-static ball contacts. `Ok(false)` with
    /// quasi-static ball contacts (their positions are not states): nothing done.
    pub fn place_balls(&self, q: &[f64; 5], x: &mut [f64]) -> Result<bool> {
        if self.p.ball_contacts != BallContacts::Dynamic {
            return Ok(false);
        }
        let (l, t0) = (self.l, self.t0);
        for j in 0..self.z {
            let xb = &mut x[self.nc + self.nb * j..self.nc + self.nb * (j + 1)];
            // [rho, z, psi, rho', z', psi', w]: the position relative to the outer groove
            // centre as `init` sets it.
            let w_orb = xb[5] / t0;
            let start = [xb[1] * l - self.z_og, xb[0] * l - self.pos.r_og];
            let a = self.groove_offset(q, xb[2]);
            let xr = self
                .pos
                .solve(a, self.m * w_orb * w_orb, Some(start), POS_TOL)?;
            xb[0] = (self.pos.r_og + xr[1]) / l;
            xb[1] = (self.z_og + xr[0]) / l;
            xb[3] = 0.0;
            xb[4] = 0.0;
        }
        Ok(true)
    }

    /// Initial states at motion `(q, omega)`: balls at the quasi-static solution
    /// (positions, orbital speeds and spin vectors of the Jones–Harris model with the
    /// scene's race control, no gyroscopic friction), cage centred at the mean orbital
    /// speed. From rest when `omega = 0`.
    pub fn init(&mut self, q: &[f64; 5], omega: f64, x: &mut [f64], aux: &mut [f64]) -> Result<()> {
        let (l, t0) = (self.l, self.t0);
        let z = self.z;
        let mut psi = [0.0; 64];
        let mut st = [BallState::default(); 64];
        let mut res = [BallResult::default(); 64];
        if z > 64 {
            return Err(Error::invalid(
                "bearing.ball_count",
                z,
                "<= 64 for the full level",
            ));
        }
        for (j, p) in psi.iter_mut().enumerate().take(z) {
            *p = 2.0 * PI * j as f64 / z as f64;
        }
        self.qs
            .evaluate(q, omega, &psi[..z], &mut st[..z], None, Some(&mut res[..z]))?;
        x.fill(0.0);
        aux.fill(0.0);
        let mut wsum = 0.0;
        for j in 0..z {
            let r = &res[j];
            let k = self.nc + self.nb * j;
            let (s, c) = psi[j].sin_cos();
            let wr = r.omega_r;
            let (sb, cb) = r.beta.sin_cos();
            // w = w_m e_z + w_R (cos beta e_z - sin beta e_r) (quasi_static/ball.rs).
            let w = [-wr * sb * c, -wr * sb * s, r.omega_m + wr * cb];
            wsum += r.omega_m;
            let xr = match self.p.ball_contacts {
                BallContacts::QuasiStatic => {
                    let a = &mut aux[3 * j..3 * j + 3];
                    a[0] = r.x[0];
                    a[1] = r.x[1];
                    a[2] = 1.0;
                    let xb = [psi[j], r.omega_m * t0, 0.0, 0.0, 0.0];
                    self.ball_position(q, &xb, a)?
                }
                BallContacts::Dynamic => {
                    let a = self.groove_offset(q, psi[j]);
                    self.pos
                        .solve(a, self.m * r.omega_m * r.omega_m, Some(r.x), POS_TOL)?
                }
            };
            let xb = &mut x[k..k + self.nb];
            match self.p.ball_contacts {
                BallContacts::QuasiStatic => {
                    xb.copy_from_slice(&[psi[j], r.omega_m * t0, w[0] * t0, w[1] * t0, w[2] * t0]);
                }
                BallContacts::Dynamic => {
                    xb.copy_from_slice(&[
                        (self.pos.r_og + xr[1]) / l,
                        (self.z_og + xr[0]) / l,
                        psi[j],
                        0.0,
                        0.0,
                        r.omega_m * t0,
                        w[0] * t0,
                        w[1] * t0,
                        w[2] * t0,
                    ]);
                }
            }
        }
        let nc = self.nc;
        x[nc - 1] = wsum / z as f64 * t0;
        Ok(())
    }
}
