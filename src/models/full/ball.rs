//! Small 3-vector helpers and the quasi-static ball position solve of the full level.
//!
//! # Quasi-static ball position (study \[0\]'s way, docs/physics.md §4 and §5.5)
//!
//! In the ball plane at azimuth `psi`, coordinates `(axial, radial)`: `X = (X1, X2)` is the
//! ball centre relative to the outer groove curvature centre and `A` the inner groove
//! curvature centre relative to the outer one (Jones geometry, as the quasi-static and
//! skidding levels). With `u_o = X`, `u_i = A - X`, `delta_k = |u_k| - (f_k - 1/2) D` and
//! `Q_k = Kc_k(alpha_k) delta_k^1.5` (Hertz, Harris & Kotzalas Vol. 1 ch. 6), the ball's
//! radial and axial force balance of the two race normal loads and the centrifugal force
//! `Fc = m rho w_orb²` (rho the ball centre's radius) is
//!
//! ```text
//! g(X) = Q_i u_i/|u_i| - Q_o u_o/|u_o| + Fc e_radial = 0
//! ```
//!
//! (Harris & Kotzalas Vol. 2 ch. 3, without the gyroscopic friction couple: in the full
//! level the gyroscopic moment is not imposed, it follows from the ball's rotational
//! dynamics and the traction it calls up). Solved by Newton with back-tracking; the Jacobian
//! `dg/dX = -J_i - J_o + m w² e_r e_r^T` uses `J_k = Kc [1.5 delta^0.5 n n^T +
//! delta^1.5/l (I - n n^T)]` and neglects `dKc/d alpha` (it changes the convergence rate
//! only, not the answer).

use crate::contact::{ContactCoefficients, ContactTable};
use crate::error::{Error, Result};
use crate::solver::newton::{self, Check};

pub(crate) type V3 = [f64; 3];

#[inline]
pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
#[inline]
pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline]
pub(crate) fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
#[inline]
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
#[inline]
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
#[inline]
pub(crate) fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}
/// Tangential part of `v` in the plane normal to the unit vector `n`.
#[inline]
pub(crate) fn tangential(v: V3, n: V3) -> V3 {
    sub(v, scale(n, dot(v, n)))
}

/// Constants of the position solve.
#[derive(Debug, Clone)]
pub(crate) struct PositionSolver {
    /// `(f_i - 1/2) D`, `(f_o - 1/2) D`, m.
    pub ri_free: f64,
    pub ro_free: f64,
    /// Radius of the outer groove curvature centre, m.
    pub r_og: f64,
    pub inner: ContactTable,
    pub outer: ContactTable,
}

/// One race contact with the table's coefficients at its angle (for the semi-axes).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Contact {
    /// Normal load, N.
    pub q: f64,
    /// Unit normal `u/|u|` in (axial, radial).
    pub n: [f64; 2],
    /// Approach `|u| - free`, m.
    pub delta: f64,
    /// Table coefficients at the contact angle.
    pub co: ContactCoefficients,
}

impl Default for Contact {
    fn default() -> Self {
        Contact {
            q: 0.0,
            n: [0.0; 2],
            delta: 0.0,
            co: ContactCoefficients {
                kc: 0.0,
                dkc_dalpha: 0.0,
                a_coef: 0.0,
                b_coef: 0.0,
            },
        }
    }
}

/// One race contact evaluated at a relative vector `u` (groove centre to ball centre, or
/// ball centre to groove centre), `n = u/|u|` in (axial, radial).
#[inline]
pub(crate) fn contact_full(t: &ContactTable, free: f64, u: [f64; 2]) -> Contact {
    // sqrt(u0² + u1²), not hypot: lengths of millimetres neither overflow nor underflow,
    // and libm's hypot costs several times more.
    let l = (u[0] * u[0] + u[1] * u[1]).sqrt().max(1e-300);
    let n = [u[0] / l, u[1] / l];
    let delta = l - free;
    let co = t.eval_cos_sin(n[1], n[0]);
    let kc = co.kc;
    let q = if delta > 0.0 {
        kc * delta * delta.sqrt()
    } else {
        0.0
    };
    Contact { q, n, delta, co }
}

/// A contact's part of `dg/dX`: `Kc [1.5 delta^0.5 n n^T + delta^1.5/l (I - n n^T)]`
/// (module notes), zero when unloaded.
#[inline]
fn contact_jac(c: &Contact, free: f64) -> [[f64; 2]; 2] {
    let (n, delta, kc) = (c.n, c.delta, c.co.kc);
    if delta <= 0.0 {
        return [[0.0; 2]; 2];
    }
    let l = delta + free;
    let kn = 1.5 * kc * delta.sqrt();
    let kt = kc * delta * delta.sqrt() / l;
    let mut j = [[0.0; 2]; 2];
    for r in 0..2 {
        for c in 0..2 {
            let nn = n[r] * n[c];
            let id = if r == c { 1.0 } else { 0.0 };
            j[r][c] = kn * nn + kt * (id - nn);
        }
    }
    j
}

impl PositionSolver {
    /// The inner and outer contacts at ball position `x`.
    #[inline]
    fn contacts(&self, x: [f64; 2], a: [f64; 2]) -> [Contact; 2] {
        [
            contact_full(&self.inner, self.ri_free, [a[0] - x[0], a[1] - x[1]]),
            contact_full(&self.outer, self.ro_free, x),
        ]
    }

    /// Residual `g` and force scale from the contacts `c` at `x`.
    #[inline]
    fn residual_of(&self, c: &[Contact; 2], x: [f64; 2], mw2: f64) -> ([f64; 2], f64) {
        let (qi, ni) = (c[0].q, c[0].n);
        let (qo, no) = (c[1].q, c[1].n);
        let fc = mw2 * (self.r_og + x[1]);
        (
            [qi * ni[0] - qo * no[0], qi * ni[1] - qo * no[1] + fc],
            qi + qo + fc.abs(),
        )
    }

    /// Jacobian `dg/dX` from the contacts `c`.
    #[inline]
    fn jac_of(&self, c: &[Contact; 2], mw2: f64) -> [[f64; 2]; 2] {
        let ji = contact_jac(&c[0], self.ri_free);
        let jo = contact_jac(&c[1], self.ro_free);
        let mut j = [[0.0; 2]; 2];
        for r in 0..2 {
            for c in 0..2 {
                j[r][c] = -ji[r][c] - jo[r][c];
            }
        }
        j[1][1] += mw2;
        j
    }

    /// The zero-speed start: on the line of the groove centres, equal loads (or equal gaps
    /// for a loose ball).
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
            let ki = self.inner.eval_cos_sin(n[1], n[0]).kc;
            let ko = self.outer.eval_cos_sin(n[1], n[0]).kc;
            let r = (ko / ki).powf(2.0 / 3.0);
            self.ro_free + (la - a0) / (1.0 + r)
        };
        [n[0] * lo, n[1] * lo]
    }

    /// The ball resting on the outer race under its centrifugal force alone.
    fn free_position(&self, mw2: f64) -> [f64; 2] {
        let k = self.outer.eval_cos_sin(1.0, 0.0).kc;
        let mut x = [0.0, self.ro_free];
        for _ in 0..6 {
            let fc = (mw2 * (self.r_og + x[1])).max(0.0);
            x[1] = self.ro_free + (fc / k).powf(2.0 / 3.0);
        }
        x
    }

    /// Solve `g(X) = 0` for groove offset `a` and `m w_orb²` (`mw2`), from `start` when
    /// given (a warm start), else from the static or free-ball position. Relative tolerance
    /// `tol` on the residual (N over the sum of the forces).
    pub fn solve(
        &self,
        a: [f64; 2],
        mw2: f64,
        start: Option<[f64; 2]>,
        tol: f64,
    ) -> Result<[f64; 2]> {
        Ok(self.solve_contacts(a, mw2, start, tol)?.0)
    }

    /// [`Self::solve`], with the two contacts at the answer when the solve evaluated them
    /// there (the same numbers [`contact_full`] gives at it).
    pub fn solve_contacts(
        &self,
        a: [f64; 2],
        mw2: f64,
        start: Option<[f64; 2]>,
        tol: f64,
    ) -> Result<([f64; 2], Option<[Contact; 2]>)> {
        let la = a[0].hypot(a[1]);
        let loaded = la > self.ri_free + self.ro_free;
        if mw2 == 0.0 && !loaded {
            return Ok((self.static_position(a), None));
        }
        let fallback = || {
            if loaded {
                self.static_position(a)
            } else {
                self.free_position(mw2)
            }
        };
        let mut x = match start {
            Some(s) if s[0].is_finite() && s[1].is_finite() => s,
            _ => fallback(),
        };
        let restarted = start.is_none();
        let mut sys = BallSystem {
            s: self,
            a,
            mw2,
            la,
            tol,
            g: [0.0; 2],
            j: [[0.0; 2]; 2],
            trial: None,
            lin: None,
        };
        let opts = newton::Options {
            max_iterations: 60,
            max_halvings: 30,
            ..newton::Options::default()
        };
        // The contacts of the last linearisation, when it was at the answer.
        let at = |sys: &BallSystem, x: [f64; 2]| match sys.lin {
            Some((xl, c)) if xl == x => Some(c),
            _ => None,
        };
        let Ok(rep) = newton::solve(&mut sys, &mut x, &opts);
        if rep.converged() {
            return Ok((x, at(&sys, x)));
        }
        let rep = if restarted {
            rep
        } else {
            x = fallback();
            let Ok(rep) = newton::solve(&mut sys, &mut x, &opts);
            if rep.converged() {
                return Ok((x, at(&sys, x)));
            }
            rep
        };
        Err(Error::NotConverged {
            what: "full level: quasi-static ball position",
            iterations: rep.iterations,
            residual: rep.check.norm,
        })
    }
}

/// The ball's force balance `g(X) = 0` as [`newton::solve`] drives it.
struct BallSystem<'a> {
    s: &'a PositionSolver,
    a: [f64; 2],
    mw2: f64,
    la: f64,
    tol: f64,
    /// Residual and Jacobian at the current point.
    g: [f64; 2],
    j: [[f64; 2]; 2],
    /// The last trial point and its contacts: the solver linearises at an accepted trial
    /// next, which then costs no new contact evaluation.
    trial: Option<([f64; 2], [Contact; 2])>,
    /// The point of the last linearisation and its contacts.
    lin: Option<([f64; 2], [Contact; 2])>,
}

impl newton::NewtonSystem<2> for BallSystem<'_> {
    type Error = std::convert::Infallible;

    fn residual(&mut self, x: &[f64; 2]) -> std::result::Result<Check, Self::Error> {
        let c = self.s.contacts(*x, self.a);
        let (g, _) = self.s.residual_of(&c, *x, self.mw2);
        self.trial = Some((*x, c));
        // Converged only where the Jacobian gives the rounding floor.
        Ok(Check {
            norm: (g[0] * g[0] + g[1] * g[1]).sqrt(),
            tol: f64::NEG_INFINITY,
        })
    }

    fn linearise(&mut self, x: &[f64; 2]) -> std::result::Result<Check, Self::Error> {
        let c = match self.trial {
            Some((xt, c)) if xt == *x => c,
            _ => self.s.contacts(*x, self.a),
        };
        self.lin = Some((*x, c));
        let (g, sc) = self.s.residual_of(&c, *x, self.mw2);
        let j = self.s.jac_of(&c, self.mw2);
        // Rounding floor of the residual: the contact stiffness times the rounding of the
        // positions it differences (a few ulp of |x| + |a|), so a nearly unloaded ball is
        // not asked for a residual below what its forces can resolve.
        let kmax = j.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        let floor = 64.0 * f64::EPSILON * kmax * ((x[0] * x[0] + x[1] * x[1]).sqrt() + self.la);
        (self.g, self.j) = (g, j);
        Ok(Check {
            norm: (g[0] * g[0] + g[1] * g[1]).sqrt(),
            tol: self.tol * sc + floor.max(1e-13),
        })
    }

    fn step(&mut self, dx: &mut [f64; 2]) -> bool {
        match newton::solve2(&self.j, [-self.g[0], -self.g[1]], 0.0) {
            Some(d) => {
                *dx = d;
                true
            }
            None => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Race;

    fn solver_7004() -> (PositionSolver, [f64; 2], f64) {
        let b = crate::geometry::preset("7004").unwrap().build().unwrap();
        let s = PositionSolver {
            ri_free: (b.fi() - 0.5) * b.d,
            ro_free: (b.fo() - 0.5) * b.d,
            r_og: b.outer_groove_centre_radius(),
            inner: ContactTable::new(&b, Race::Inner),
            outer: ContactTable::new(&b, Race::Outer),
        };
        let (a1, a2) = b.reference_groove_offset();
        (s, [a1, a2], b.ball_mass())
    }

    /// The full level's Jacobian and outputs take a ball position from a solve at the same
    /// groove offset and speed instead of solving again (and its contacts from the solve):
    /// that holds because a solve started at its own answer returns it unchanged, bit for
    /// bit, and the contacts it hands back are those at the answer. Loaded, lightly
    /// loaded, loose and fast balls; cold and warm starts.
    #[test]
    fn a_solve_from_its_answer_returns_it_and_its_contacts() {
        let (s, a0, m) = solver_7004();
        for (da, w_orb) in [
            ([4.4e-5, -3.0e-6], 1300.0),
            ([4.4e-5, 3.0e-6], 5200.0),
            ([1e-6, 1e-6], 5200.0),
            ([-2e-5, 0.0], 1300.0),
            ([2e-5, 1e-5], 0.0),
        ] {
            let a = [a0[0] + da[0], a0[1] + da[1]];
            let mw2 = m * w_orb * w_orb;
            let (x, c) = s.solve_contacts(a, mw2, None, 1e-12).unwrap();
            let (x2, c2) = s.solve_contacts(a, mw2, Some(x), 1e-12).unwrap();
            assert_eq!(x, x2, "{da:?} {w_orb}");
            for c in [c, c2].into_iter().flatten() {
                let want = s.contacts(x, a);
                for k in 0..2 {
                    assert_eq!(
                        (c[k].q, c[k].n, c[k].delta),
                        (want[k].q, want[k].n, want[k].delta)
                    );
                    assert_eq!(c[k].co.kc, want[k].co.kc);
                }
            }
            // The answer balances the ball (to the solve's tolerance and rounding floor).
            let (g, sc) = s.residual_of(&s.contacts(x, a), x, mw2);
            assert!(
                (g[0] * g[0] + g[1] * g[1]).sqrt() <= 1e-10 * sc,
                "{g:?} {sc}"
            );
        }
    }
}
