//! The per-ball kernel of the Jones–Harris model: contact geometry, race-control kinematics,
//! centrifugal force, gyroscopic moment, the two ball equilibrium equations and their damped
//! Newton solve (docs/physics.md §4; Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed., Vol. 2
//! ch. 3; Jones 1960).
//!
//! # Geometry (the ball plane at azimuth `psi`)
//!
//! Coordinates `(axial, radial)`. `X = (X1, X2)` is the ball centre relative to the outer
//! groove curvature centre, `A = (A1, A2)` the inner groove curvature centre relative to the
//! outer one. With `u_o = X`, `u_i = A - X`:
//! `l_o = |u_o|`, `delta_o = l_o - (f_o - 1/2) D`, `(sin a_o, cos a_o) = u_o / l_o`;
//! `l_i = |u_i|`, `delta_i = l_i - (f_i - 1/2) D`, `(sin a_i, cos a_i) = u_i / l_i`;
//! `Q = Kc(a) delta^1.5` (zero for `delta <= 0`). The outer contact point is at
//! `X + (D/2)(sin a_o, cos a_o)`, the inner one at `X - (D/2)(sin a_i, cos a_i)`.
//!
//! # Kinematics (race control)
//!
//! The ball spins relative to the cage at `omega_R` about an axis in the ball plane with unit
//! vector `(cos beta, -sin beta)` (axial, radial); pure rolling in the rolling direction at
//! both contact centres, outer ring fixed, inner ring at `omega`. With `g = D/dm`,
//! `C_k = cos(a_k - beta)`:
//!
//! - `omega_m / omega = (1 - g cos a_i) C_o / ((1 - g cos a_i) C_o + (1 + g cos a_o) C_i)`
//! - `omega_R / omega = -1 / (g (C_o / (1 + g cos a_o) + C_i / (1 - g cos a_i)))`
//!
//! which are Harris & Kotzalas Vol. 2 eqs. (3.x) (Jones's ratios, written with
//! `cos(a - beta) = cos beta (cos a + tan beta sin a)`) for a rotating inner ring. The
//! attitude: outer-race control `tan beta = sin a_o / (cos a_o + g)` (zero spin at the outer
//! contact: checked in a test); "no control": the mean of the outer- and inner-control
//! attitudes, `beta = (atan2(sin a_o, cos a_o + g) + atan2(sin a_i, cos a_i - g)) / 2` (our
//! choice: Harris leaves the no-control attitude to a minimum-friction argument; the mean
//! lies between the two limits).
//!
//! Spin-to-roll ratios (components of the ball's angular velocity relative to the race along
//! the contact normal and along the in-plane tangent):
//! `(w_s/w_roll)_o = (1 + g cos a_o) tan(a_o - beta) - g sin a_o`,
//! `(w_s/w_roll)_i = (1 - g cos a_i) tan(a_i - beta) + g sin a_i`; written with `tan beta`
//! these are Harris's `(sin a - tan beta cos a -+ g tan beta) / (cos a + tan beta sin a)`.
//!
//! `Fc = m (dm/2) omega_m^2`; `Mg = -J omega_R omega_m sin beta` (`J = m D^2/10`), which is
//! `>= 0` for either direction of rotation because `omega_R omega_m < 0`.
//!
//! # Gyroscopic friction: sign and limit
//!
//! The spin vector `omega_R (cos beta, -sin beta)` turns with the cage, so the moment the
//! contacts must apply to the ball is `dH/dt = -J omega_m omega_R sin beta e_t = +Mg e_t`
//! (`e_t` the orbital direction, `(e_z, e_r, e_t)` right-handed). Friction forces
//! `f_o (-cos a_o, sin a_o)` at the outer contact and `f_i (cos a_i, -sin a_i)` at the inner
//! contact, `f_k = lambda_k Mg / D`, give exactly `+Mg e_t`. This is the sign we use; it is
//! the opposite of the friction terms as docs/physics.md §4 prints them (Harris's figure draws the
//! couple for the mirrored ball), which would give `-Mg e_t` in this frame.
//!
//! Friction cannot exceed what the contacts can carry: a ball that touches one race only
//! cannot resist the gyroscopic moment at all. We therefore use
//! `T_k = lambda_k (Mg/D) phi(mu Q_h D / Mg)`, `phi(t) = t / (1 + t^4)^(1/4)`,
//! `Q_h = Q_i Q_o / (Q_i + Q_o)`: `phi -> 1` (Harris's full couple) when `mu Q_h >> Mg/D`,
//! and the couple fades smoothly (C¹) to zero when either contact unloads, so the ring forces
//! stay continuous when a ball loses contact. `mu = inf` gives Harris's unlimited couple.
//!
//! # Ball equilibrium (forces on the ball)
//!
//! ```text
//! g1 = Q_i sin a_i + T_i cos a_i - Q_o sin a_o - T_o cos a_o       = 0   (axial)
//! g2 = Q_i cos a_i - T_i sin a_i - Q_o cos a_o + T_o sin a_o + Fc  = 0   (radial)
//! ```
//!
//! The inner ring receives `(F_a, F_r) = (-Q_i sin a_i - T_i cos a_i, -Q_i cos a_i +
//! T_i sin a_i)` and, about the centre of the inner groove-centre circle, the moment
//! `m = Ri F_a + T_i f_i D` in the ball plane (the normal force passes through the groove
//! centre at radius `Ri`; the friction force acts at the contact point, `f_i D` from it;
//! with `T_i = lambda_i Mg/D` the last term is docs/physics.md's `lambda_i f_i Mg` couple).

use super::dual::Dual;
use super::kc::KcTable;
use super::RaceControl;
use crate::error::{Error, Result};
use crate::solver::newton;

/// Per-ball unknowns carried from one call to the next (warm start).
///
/// The next solve starts from the first-order prediction
/// `X + dX/dA (A_new - A)`, so that in a time integration (small changes of `A` between
/// calls) one Newton step usually converges.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BallState {
    /// Ball centre relative to the outer groove curvature centre, `(X1, X2)`, m.
    pub x: [f64; 2],
    /// Groove offset `(A1, A2)` at which `x` was solved, m.
    pub a: [f64; 2],
    /// Sensitivity `dX/dA` there (row `r`: `X_r`), from the last Newton Jacobian.
    pub dxda: [[f64; 2]; 2],
    /// `false`: no previous solution; the solve starts from the static guess.
    pub warm: bool,
}

impl Default for BallState {
    fn default() -> Self {
        BallState {
            x: [0.0, 0.0],
            a: [0.0, 0.0],
            dxda: [[0.0; 2]; 2],
            warm: false,
        }
    }
}

impl BallState {
    /// The predicted start for groove offset `a`.
    fn predict(&self, a: [f64; 2]) -> [f64; 2] {
        let da = [a[0] - self.a[0], a[1] - self.a[1]];
        let p = [
            self.x[0] + self.dxda[0][0] * da[0] + self.dxda[0][1] * da[1],
            self.x[1] + self.dxda[1][0] * da[0] + self.dxda[1][1] * da[1],
        ];
        if p[0].is_finite() && p[1].is_finite() {
            p
        } else {
            self.x
        }
    }

    fn store(&mut self, x: [f64; 2], a: [f64; 2], dxda: [[f64; 2]; 2]) {
        self.x = x;
        self.a = a;
        self.dxda = dxda;
        self.warm = true;
    }
}

/// `dX/dA = -(dg/dX)^-1 dg/dA` from an `N = 4` evaluation (zero when singular).
pub(crate) fn sensitivity(e: &Eval<4>) -> [[f64; 2]; 2] {
    let gx = e.jac_x();
    let col = |c: usize| {
        newton::solve2(&gx, [-e.g[0].d[2 + c], -e.g[1].d[2 + c]], SINGULAR).unwrap_or([0.0; 2])
    };
    let (c0, c1) = (col(0), col(1));
    [[c0[0], c1[0]], [c0[1], c1[1]]]
}

/// Constants of the kernel, precomputed once per bearing and options.
#[derive(Debug, Clone)]
pub(crate) struct Geo {
    pub d: f64,
    pub dm: f64,
    /// `(f_i - 1/2) D`.
    pub ri_free: f64,
    /// `(f_o - 1/2) D`.
    pub ro_free: f64,
    /// `f_i D`.
    pub fid: f64,
    /// `Ri`, m.
    pub ri: f64,
    /// `D / dm`.
    pub g: f64,
    pub mass: f64,
    pub inertia: f64,
    pub lam_i: f64,
    pub lam_o: f64,
    pub mu: f64,
    pub control: RaceControl,
    pub kc_i: KcTable,
    pub kc_o: KcTable,
    pub tol: f64,
    pub max_iter: usize,
}

/// Everything evaluated at one ball position. With `N = 4` the duals carry
/// d/d(u_o1, u_o2, u_i1, u_i2) (for the stiffness), with `N = 2` d/d(X1, X2) (for the
/// Newton step), with `N = 0` values only (line search, convergence check).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Eval<const N: usize> {
    pub g: [Dual<N>; 2],
    /// Forces on the shaft: axial, radial, and the ball-plane moment.
    pub fa: Dual<N>,
    pub fr: Dual<N>,
    pub m: Dual<N>,
    pub qi: f64,
    pub qo: f64,
    pub di: f64,
    pub do_: f64,
    /// `(sin, cos)` of the inner and outer contact angles and of the attitude `beta`
    /// (angles are formed only for reports: `atan2` is costly in the kernel).
    pub sc_i: [f64; 2],
    pub sc_o: [f64; 2],
    pub sc_b: [f64; 2],
    pub fc: f64,
    pub mg: f64,
    pub wm: f64,
    pub wr: f64,
    pub sr_i: f64,
    pub sr_o: f64,
}

impl<const N: usize> Eval<N> {
    /// Residual norm, N (infinite when not finite).
    pub fn norm(&self) -> f64 {
        let n = (self.g[0].v * self.g[0].v + self.g[1].v * self.g[1].v).sqrt();
        if n.is_finite() {
            n
        } else {
            f64::INFINITY
        }
    }
    /// Inner contact angle, rad.
    pub fn alpha_i(&self) -> f64 {
        self.sc_i[0].atan2(self.sc_i[1])
    }
    /// Outer contact angle, rad.
    pub fn alpha_o(&self) -> f64 {
        self.sc_o[0].atan2(self.sc_o[1])
    }
    /// Attitude angle, rad.
    pub fn beta(&self) -> f64 {
        self.sc_b[0].atan2(self.sc_b[1])
    }
    /// Force scale for the convergence test.
    pub fn scale(&self) -> f64 {
        self.qi + self.qo + self.fc.abs() + 1e-9
    }
    /// `dg/dX` (2x2, row-major); zero for `N = 0`.
    pub fn jac_x(&self) -> [[f64; 2]; 2] {
        let r = |k: usize| {
            let d = &self.g[k].d;
            match N {
                4 => [d[0] - d[2], d[1] - d[3]],
                2 => [d[0], d[1]],
                _ => [0.0, 0.0],
            }
        };
        [r(0), r(1)]
    }
}

impl Geo {
    /// Evaluate the ball at `x` for groove offset `a` and shaft speed `omega`.
    pub fn eval<const N: usize>(&self, omega: f64, x: [f64; 2], a: [f64; 2]) -> Eval<N> {
        let mut uo1 = Dual::<N>::cst(x[0]);
        let mut uo2 = Dual::<N>::cst(x[1]);
        let mut ui1 = Dual::<N>::cst(a[0] - x[0]);
        let mut ui2 = Dual::<N>::cst(a[1] - x[1]);
        match N {
            4 => {
                uo1.d[0] = 1.0;
                uo2.d[1] = 1.0;
                ui1.d[2] = 1.0;
                ui2.d[3] = 1.0;
            }
            2 => {
                uo1.d[0] = 1.0;
                uo2.d[1] = 1.0;
                ui1.d[0] = -1.0;
                ui2.d[1] = -1.0;
            }
            _ => {}
        }
        let lo = (uo1 * uo1 + uo2 * uo2).sqrt();
        let li = (ui1 * ui1 + ui2 * ui2).sqrt();
        let lo_safe = if lo.v > 0.0 { lo } else { Dual::cst(1e-300) };
        let li_safe = if li.v > 0.0 { li } else { Dual::cst(1e-300) };
        let so = uo1 / lo_safe;
        let co = uo2 / lo_safe;
        let mut si = ui1 / li_safe;
        let mut ci = ui2 / li_safe;
        let dlo = lo - self.ro_free;
        let mut dli = li - self.ri_free;
        // A loose ball whose centre lies beyond its inner groove's centre (the ring moved
        // more than `ri_free` away from it: default 6205, `shaft.y` past -1.6e-4 m, the ball
        // at the top resting on the outer race) faces the inner raceway across that centre:
        // the raceway is on the shaft side of the groove centre, so the contact normal is
        // the mirrored one and the gap is `li + ri_free`. Taken as it was (`ci < 0`), the
        // rolling kinematics divided by `p_i c_o + p_o c_i = 0` (rm = inf, fc = inf: the
        // solve failed at its start with residual inf, issue #38 item 5). Unloaded either
        // way: no force changes.
        if ci.v < 0.0 && dli.v <= 0.0 {
            si = -si;
            ci = -ci;
            dli = -li - self.ri_free;
        }
        let kco = {
            let (k, dk) = self.kc_o.eval(co.v);
            co.chain(k, dk)
        };
        let kci = {
            let (k, dk) = self.kc_i.eval(ci.v);
            ci.chain(k, dk)
        };
        let qo = kco * dlo.pos_pow15();
        let qi = kci * dli.pos_pow15();

        let zero = Dual::cst(0.0);
        let (mut fc, mut fi, mut fo) = (zero, zero, zero);
        let (mut mgv, mut wm, mut wr, mut sr_i, mut sr_o) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let mut sc_b = [0.0, 1.0];
        if omega != 0.0 {
            let g = self.g;
            let (sb, cb) = match self.control {
                RaceControl::Outer => {
                    let y = so;
                    let xx = co + g;
                    let n = (y * y + xx * xx).sqrt();
                    (y / n, xx / n)
                }
                RaceControl::None => {
                    let bo = Dual::atan2(so, co + g);
                    let bi = Dual::atan2(si, ci - g);
                    let bb = (bo + bi) * 0.5;
                    (bb.sin(), bb.cos())
                }
            };
            let c_o = co * cb + so * sb;
            let c_i = ci * cb + si * sb;
            // Reports only: values.
            let s_o = so.v * cb.v - co.v * sb.v;
            let s_i = si.v * cb.v - ci.v * sb.v;
            let po = 1.0 + co * g;
            let pi = 1.0 - ci * g;
            let rm = pi * c_o / (pi * c_o + po * c_i);
            let rr = Dual::cst(-1.0) / ((c_o / po + c_i / pi) * g);
            let w2 = omega * omega;
            fc = rm * rm * (self.mass * 0.5 * self.dm * w2);
            let mg = -(rm * rr * sb) * (self.inertia * w2);
            // Friction couple with its traction limit (module docs).
            let fbase = mg / self.d;
            // phi = t / (1 + t^4)^(1/4) with t = mu Q_h / |F_base|, evaluated as
            // 1 / (1 + s^4)^(1/4) with s = 1/t when t > 1: the same function, but a tiny
            // couple (a groove offset of 1e-200 m gives |F_base| ~ 1e-200 N) no longer
            // overflows t^4 and its derivatives to inf and NaN. A subnormal couple (a ball
            // on the plane of symmetry, its axial offset ~1e-317 m) counts as none: `1/den`
            // would overflow to inf and `0 * inf` give NaN (the couple is ~0 either way).
            let sum = qi + qo;
            let qh = if sum.v > 0.0 { qi * qo / sum } else { zero };
            let (num, den) = (qh * self.mu, fbase.abs());
            let phi = if fbase.v.abs() < f64::MIN_POSITIVE || !self.mu.is_finite() {
                Dual::cst(1.0)
            } else if num.v <= den.v {
                let t = num / den;
                let t2 = t * t;
                t / (1.0 + t2 * t2).sqrt().sqrt()
            } else {
                let s = den / num;
                let s2 = s * s;
                Dual::cst(1.0) / (1.0 + s2 * s2).sqrt().sqrt()
            };
            if self.lam_i != 0.0 {
                fi = fbase * phi * self.lam_i;
            }
            fo = fbase * phi * self.lam_o;
            mgv = mg.v;
            wm = rm.v * omega;
            wr = rr.v * omega;
            sc_b = [sb.v, cb.v];
            sr_o = po.v * s_o / c_o.v - so.v * g;
            sr_i = pi.v * s_i / c_i.v + si.v * g;
        }
        let (g1, g2, fa, fr, m) = if self.lam_i != 0.0 && omega != 0.0 {
            let fa = -(qi * si) - fi * ci;
            (
                qi * si + fi * ci - qo * so - fo * co,
                qi * ci - fi * si - qo * co + fo * so + fc,
                fa,
                -(qi * ci) + fi * si,
                fa * self.ri + fi * self.fid,
            )
        } else {
            // No inner friction (outer-race control, or at rest): the same sums without
            // the terms in `fi = 0` (adding an exact zero changes no bit).
            let fa = -(qi * si);
            (
                qi * si - qo * so - fo * co,
                qi * ci - qo * co + fo * so + fc,
                fa,
                -(qi * ci),
                fa * self.ri,
            )
        };
        Eval {
            g: [g1, g2],
            fa,
            fr,
            m,
            qi: qi.v,
            qo: qo.v,
            di: dli.v,
            do_: dlo.v,
            sc_i: [si.v, ci.v],
            sc_o: [so.v, co.v],
            sc_b,
            fc: fc.v,
            mg: mgv,
            wm,
            wr,
            sr_i,
            sr_o,
        }
    }

    /// The zero-speed equilibrium, in closed form: both contacts lie on the line of the
    /// groove centres, `Q_i = Q_o`, `delta_i + delta_o = |A| - A0` with
    /// `A0 = (f_i + f_o - 1) D`. A loose ball (`|A| <= A0`) carries nothing; it is placed on
    /// the line of centres with equal gaps to both races.
    pub fn static_position(&self, a: [f64; 2]) -> [f64; 2] {
        let la = a[0].hypot(a[1]);
        let a0 = self.ri_free + self.ro_free;
        if la <= 0.0 {
            return [0.0, self.ro_free];
        }
        let n = [a[0] / la, a[1] / la];
        let lo = if la <= a0 {
            self.ro_free + 0.5 * (la - a0)
        } else {
            let ki = self.kc_i.eval(n[1]).0;
            let ko = self.kc_o.eval(n[1]).0;
            let total = la - a0;
            // Q equal: ko do^1.5 = ki di^1.5  =>  di = do (ko/ki)^(2/3).
            let r = (ko / ki).powf(2.0 / 3.0);
            self.ro_free + total / (1.0 + r)
        };
        [n[0] * lo, n[1] * lo]
    }

    /// The ball resting on the outer race under its centrifugal force alone.
    fn free_position(&self, omega: f64, a: [f64; 2]) -> [f64; 2] {
        let mut x = [0.0, self.ro_free];
        let k = self.kc_o.eval(1.0).0;
        for _ in 0..4 {
            let e = self.eval::<0>(omega, x, a);
            x[1] = self.ro_free + (e.fc.max(0.0) / k).powf(2.0 / 3.0);
        }
        x
    }

    /// Solve the ball's two equilibrium equations for groove offset `a` at shaft speed
    /// `omega`, starting from (and updating) `state`: damped Newton from the warm start
    /// (the first-order prediction of [`BallState`]), the step from the exact 2x2 Jacobian
    /// (`N = 2` duals), back-tracking on the residual norm; one restart from the static
    /// (or free-ball) position if the warm solve fails; then [`Error::NotConverged`].
    ///
    /// **The answer is a function of `(omega, a)` to rounding, whatever the start** (the
    /// warm start changes the cost, never the answer; the right-hand side of a time
    /// integration must not depend on the path, or the finite-difference Jacobian and the
    /// error estimate see noise). Newton stops on the size of its update, not on a
    /// residual tolerance: once the update `dx` at `x` is below [`Geo::rounding_step`]
    /// (`sqrt(eps)/8` of the smallest loaded approach, or rounding of `x`), the root is
    /// `x + dx` to `O(|dx|²/delta)`, i.e. to rounding. The forces are then taken there:
    /// by the first-order update `F(x) + dF/dX dx` from the last linearisation (its error
    /// `O(|dx|²)` relative to the force is below `eps`). With `full` (the caller wants the
    /// stiffness or the reports) the last linearisation carries the four slots (`N = 4`,
    /// [`Geo::newton`]) and gives `K`, the reports and `dX/dA` for the next warm start at
    /// `x`, within `|dx|` of the root (relative `|dx|/delta`: at most `sqrt(eps)/8`; `K`
    /// agrees to 1.3e-12 from any start in tests/qs_path_independence.rs); when Newton ended on an `N = 2` linearisation, an
    /// `N = 4` evaluation at `x + dx` gives them at the root. Without `full` the state
    /// keeps its sensitivity (a stale predictor costs iterations, not accuracy). A solve whose update
    /// stops contracting at the rounding floor (or whose line search fails there) is
    /// accepted when its residual is within `ball_tolerance` of the force scale.
    pub fn solve(
        &self,
        omega: f64,
        a: [f64; 2],
        state: &mut BallState,
        full: bool,
    ) -> Result<Solved> {
        if omega == 0.0 {
            let x = self.static_position(a);
            state.store(x, a, [[0.0; 2]; 2]);
            return Ok(if full {
                Solved::from_full(self.eval::<4>(0.0, x, a))
            } else {
                let e = self.eval::<0>(0.0, x, a);
                Solved {
                    f: [e.fa.v, e.fr.v, e.m.v],
                    full: None,
                }
            });
        }
        // Millimetre-sized: the plain root (no overflow; `hypot` is several times slower).
        let la = (a[0] * a[0] + a[1] * a[1]).sqrt();
        let loaded_static = la > self.ri_free + self.ro_free;
        let fallback = |geo: &Geo| {
            if loaded_static {
                geo.static_position(a)
            } else {
                geo.free_position(omega, a)
            }
        };
        let warm = state.warm && state.x[0].is_finite() && state.x[1].is_finite();
        let start = if warm {
            state.predict(a)
        } else {
            fallback(self)
        };
        let (x, dx, last) = match self.newton(omega, a, start, full) {
            Err(_) if warm => self.newton(omega, a, fallback(self), full),
            r => r,
        }
        .map_err(|f| Error::NotConverged {
            what: "quasi-static ball equilibrium",
            iterations: f.iterations,
            residual: f.residual,
        })?;
        let root = [x[0] + dx[0], x[1] + dx[1]];
        match last {
            Last::Final(e4) => {
                // Forces at the root to first order; `K`, `dX/dA` and the reports at `x`.
                let lin = |d: &Dual<4>| d.v + (d.d[0] - d.d[2]) * dx[0] + (d.d[1] - d.d[3]) * dx[1];
                state.store(root, a, sensitivity(&e4));
                Ok(Solved {
                    f: [lin(&e4.fa), lin(&e4.fr), lin(&e4.m)],
                    full: Some(e4),
                })
            }
            Last::Plain(_) if full => {
                let e4 = self.eval::<4>(omega, root, a);
                state.store(root, a, sensitivity(&e4));
                Ok(Solved::from_full(e4))
            }
            Last::Plain(e) => {
                let lin = |d: &Dual<2>| d.v + d.d[0] * dx[0] + d.d[1] * dx[1];
                let dxda = state.dxda;
                state.store(root, a, dxda);
                Ok(Solved {
                    f: [lin(&e.fa), lin(&e.fr), lin(&e.m)],
                    full: None,
                })
            }
        }
    }

    /// The smallest loaded approach of an evaluation, m (infinite when neither contact
    /// is loaded).
    fn approach_min<const N: usize>(e: &Eval<N>) -> f64 {
        let mut d = f64::INFINITY;
        for v in [e.di, e.do_] {
            if v > 0.0 {
                d = d.min(v);
            }
        }
        d
    }

    /// Newton update below which the answer is final: `sqrt(eps)/8` of the smallest
    /// loaded approach `dmin` (the root is then `x + dx` to `O(|dx|²/delta)`, relative
    /// error `< eps/64` in the forces; the scale of the Hertz law's curvature is the
    /// approach), or 8 ulp of `x` (the update cannot be resolved below that).
    fn rounding_step(x: [f64; 2], dmin: f64) -> f64 {
        let ulp = 8.0 * f64::EPSILON * x[0].abs().max(x[1].abs());
        let quad = if dmin.is_finite() {
            0.125 * f64::EPSILON.sqrt() * dmin
        } else {
            0.0
        };
        ulp.max(quad)
    }

    /// The damped Newton iteration from `x` (see [`Geo::solve`]) on the shared
    /// [`newton::solve_to_rounding`]: the last point, the update there and its evaluation.
    /// With `full`, a full step predicted to land within [`Geo::rounding_step`] of the
    /// root (`|dx|²/dmin` below it: Newton's quadratic contraction with the Hertz law's
    /// curvature scale) is evaluated with the four slots (`N = 4`), which then serve the
    /// stiffness and the reports without another evaluation at the root.
    fn newton(
        &self,
        omega: f64,
        a: [f64; 2],
        x: [f64; 2],
        full: bool,
    ) -> std::result::Result<Root, newton::Failure> {
        let sys = BallSystem {
            geo: self,
            omega,
            a,
            full,
        };
        let opts = newton::RoundingOptions {
            max_iterations: self.max_iter,
            max_halvings: MAX_HALVINGS,
            armijo: ARMIJO,
            rtol: self.tol,
            atol: 1e-12,
        };
        newton::solve_to_rounding(&sys, x, &opts)
    }
}

/// A ball's two equilibrium equations at shaft speed `omega` and groove offset `a`, as
/// [`newton::solve_to_rounding`] drives them: `N = 2` duals (`d/dX`) for the iteration,
/// four slots for a step predicted final when `full`.
struct BallSystem<'a> {
    geo: &'a Geo,
    omega: f64,
    a: [f64; 2],
    full: bool,
}

impl newton::RoundingSystem<2> for BallSystem<'_> {
    type Eval = Eval<2>;
    type Final = Eval<4>;
    #[inline]
    fn eval(&self, x: &[f64; 2]) -> Eval<2> {
        self.geo.eval::<2>(self.omega, *x, self.a)
    }
    #[inline]
    fn eval_final(&self, x: &[f64; 2]) -> Eval<4> {
        self.geo.eval::<4>(self.omega, *x, self.a)
    }
    #[inline]
    fn predicts_root(&self, e: &Eval<2>, step: f64, resolution: f64) -> bool {
        let dmin = Geo::approach_min(e);
        self.full && dmin.is_finite() && step * step <= resolution * dmin
    }
}

impl<const N: usize> newton::Linearised<2> for Eval<N> {
    #[inline]
    fn norm(&self) -> f64 {
        Eval::<N>::norm(self)
    }
    #[inline]
    fn scale(&self) -> f64 {
        Eval::<N>::scale(self)
    }
    #[inline]
    fn step(&self) -> Option<[f64; 2]> {
        newton::solve2(&self.jac_x(), [-self.g[0].v, -self.g[1].v], SINGULAR)
    }
    #[inline]
    fn resolution(&self, x: &[f64; 2]) -> f64 {
        Geo::rounding_step(*x, Geo::approach_min(self))
    }
}

/// The evaluation at the Newton iteration's last point: `d/dX` duals, or the four slots
/// when the last step was predicted final with `full`.
type Last = newton::Last<Eval<2>, Eval<4>>;

/// The Newton iteration's last point, its update and its evaluation.
type Root = ([f64; 2], [f64; 2], Last);

/// A ball's answer: the forces on the shaft `(F_a, F_r, m)` at the root, and with
/// [`Geo::solve`]'s `full` its `N = 4` evaluation there (stiffness, reports).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Solved {
    pub f: [f64; 3],
    pub full: Option<Eval<4>>,
}

impl Solved {
    fn from_full(e: Eval<4>) -> Self {
        Solved {
            f: [e.fa.v, e.fr.v, e.m.v],
            full: Some(e),
        }
    }
}

/// Step halvings per line search of the ball Newton.
const MAX_HALVINGS: usize = 40;

/// Sufficient-decrease constant of the ball Newton's line search.
const ARMIJO: f64 = 1e-4;

/// Relative determinant below which a ball's 2×2 Jacobian counts as singular (no contact).
const SINGULAR: f64 = 1e-13;
