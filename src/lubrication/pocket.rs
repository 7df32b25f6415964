//! Ball–pocket interaction of the `full` cage model (docs/physics.md §5.5, study \[0\] after
//! Gupta, *Advanced Dynamics of Rolling Elements*, 1984): Hertzian contact with friction
//! when the gap is below the composite roughness, a rigid-isoviscous hydrodynamic film
//! beyond it.
//!
//! **Geometry.** A ball of radius `Rb` in a cylindrical pocket of radius `Rp > Rb`. The
//! ball slides and rolls mainly along the pocket axis (`x`, the ball against a straight
//! generator: `Rx = Rb`); across it the contact conforms:
//! `Ry = 1/(1/Rb - 1/Rp) = Rb Rp/(Rp - Rb)` (Harris & Kotzalas, *Rolling Bearing Analysis*
//! Vol. 1, ch. 2, curvature sums; concave surfaces count negative). `Ry/Rx >= 1`.
//!
//! **Hydrodynamic branch** (`h >= sigma`, the composite roughness), rigid surfaces,
//! isoviscous lubricant, no suction (the film cavitates: `normal >= 0`):
//! - squeeze film: Reynolds' equation for an elliptic paraboloid approaching a plane,
//!   `F = 12 pi eta (Rx Ry)^1.5 / ((Rx + Ry) h) (-h_dot)` (the same closed form as
//!   [`super::squeeze_damping`]; `6 pi eta R² (-h_dot)/h` for a sphere on a plane;
//!   Reynolds 1886, Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film Lubrication*,
//!   2004, ch. 11);
//! - entrainment (rolling) film: the isoviscous-rigid point-contact solution of Brewe,
//!   Hamrock & Taylor (*J. Lubr. Technol.* 101(2) 1979, 231–239; Hamrock, Schmid &
//!   Jacobson 2004, ch. 21, the "isoviscous-rigid regime"):
//!   `H_min (W/U)² = 128 a_r lambda_b² (0.131 atan(a_r/2) + 1.683)²`,
//!   `lambda_b = (1 + 2/(3 a_r))^-1`, `a_r = Ry/Rx`, with `H = h/Rx`,
//!   `W = F/(E' Rx²)`, `U = eta u/(E' Rx)`; solved for the load at the gap `h`:
//!   `F = eta |u| Rx sqrt(H_IR Rx / h)` (E' cancels: rigid). It has Kapitza's (1955)
//!   `h ~ (eta u/F)²` dependence (the paper's own remark). Reynolds (not half-Sommerfeld)
//!   exit conditions; the formula is the minimum-film fit, used here as the load law.
//!
//! The gap in both is floored at `max(sigma, H_FLOOR)`, so they stay finite as `h -> 0`.
//!
//! **Contact branch** (`h < sigma`): Hertz at the approach `sigma - h` with the crate's
//! exact ellipse ([`PointContact`]) plus the film force frozen at `h = sigma` (so the normal
//! force is continuous there).
//!
//! **Friction.** Film shear: Couette flow `tau = eta vs / h` integrated over the gap
//! `h + x²/(2Rx) + y²/(2Ry)` out to a radius `~Rb` gives
//! `F = 2 pi eta sqrt(Rx Ry) vs ln(1 + Rb/(2h))` (the logarithmic leading term of the
//! sliding sphere near a wall; Goldman, Cox & Brenner, *Chem. Eng. Sci.* 22, 1967, and
//! O'Neill & Stewartson, *J. Fluid Mech.* 27, 1967). In contact it is frozen at
//! `h = sigma` and the Coulomb term `mu Q_H tanh(vs/v_s)` on the Hertz load is added.
//! Both oppose `vs`.

use super::H_FLOOR;
use crate::contact::{Curvature, PointContact};
use std::f64::consts::PI;

/// Ball–pocket law (see the module notes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PocketLaw {
    /// Ball radius, m.
    pub ball_radius: f64,
    /// Pocket radius (ball radius + radial play), m.
    pub pocket_radius: f64,
    /// Cage web thickness / pocket length along its axis, m.
    pub width: f64,
    /// Composite roughness `sqrt(eps_b² + eps_p²)`, m.
    pub roughness: f64,
    /// Viscosity, Pa s.
    pub viscosity: f64,
    /// Effective modulus `E'` of ball and cage materials, Pa.
    pub e_eff: f64,
    /// Coulomb coefficient in dry (Hertzian) contact.
    pub friction: f64,
    /// Slip speed regularising the friction, m/s.
    pub v_s: f64,
}

/// What the pocket wall does to the ball.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PocketForce {
    /// Normal force (>= 0) pushing the ball away from the wall, N.
    pub normal: f64,
    /// Tangential force on the ball, opposing `vs`, N.
    pub friction: f64,
}

impl PocketLaw {
    /// Effective radii `(Rx, Ry)`: along the pocket axis and across it (conforming).
    pub fn radii(&self) -> (f64, f64) {
        let rb = self.ball_radius;
        let play = (self.pocket_radius - rb).max(1e-6 * rb);
        (rb, rb * (rb + play) / play)
    }

    /// The Hertz contact of the ball in the pocket.
    pub fn contact(&self) -> PointContact {
        let (rx, ry) = self.radii();
        PointContact::new(Curvature::from_radii(rx, ry), self.e_eff)
    }

    /// `H_IR = H_min (W/U)²` of the isoviscous-rigid regime (Brewe, Hamrock & Taylor 1979).
    pub fn h_ir(&self) -> f64 {
        let (rx, ry) = self.radii();
        let ar = ry / rx;
        let lb = 1.0 / (1.0 + 2.0 / (3.0 * ar));
        let t = 0.131 * (0.5 * ar).atan() + 1.683;
        128.0 * ar * lb * lb * t * t
    }

    /// Film normal force at gap `h` (floored), rate `h_dot`, entrainment `u`; `>= 0`.
    pub fn film_normal(&self, h: f64, h_dot: f64, u: f64) -> f64 {
        let (rx, ry) = self.radii();
        let h = h.max(self.roughness).max(H_FLOOR);
        let eta = self.viscosity;
        let squeeze = 12.0 * PI * eta * (rx * ry).powf(1.5) / ((rx + ry) * h) * (-h_dot);
        let roll = eta * u.abs() * rx * (self.h_ir() * rx / h).sqrt();
        (squeeze + roll).max(0.0)
    }

    /// Film (Couette) shear force at gap `h` (floored), sliding `vs`; opposes `vs`.
    pub fn film_shear(&self, h: f64, vs: f64) -> f64 {
        let (rx, ry) = self.radii();
        let h = h.max(self.roughness).max(H_FLOOR);
        -2.0 * PI
            * self.viscosity
            * (rx * ry).sqrt()
            * vs
            * (1.0 + self.ball_radius / (2.0 * h)).ln()
    }

    /// Force at gap `h` (m, negative = penetration), gap rate `h_dot` (m/s, negative =
    /// approaching), entrainment speed `u` and sliding speed `vs` (m/s).
    pub fn force(&self, h: f64, h_dot: f64, u: f64, vs: f64) -> PocketForce {
        self.prepare().force(h, h_dot, u, vs)
    }

    /// The law with its constants computed once ([`PreparedPocket`]), for a caller that
    /// evaluates it many times.
    pub fn prepare(&self) -> PreparedPocket {
        let (rx, ry) = self.radii();
        let eta = self.viscosity;
        PreparedPocket {
            law: *self,
            rx,
            squeeze: 12.0 * PI * eta * (rx * ry).powf(1.5),
            sum_r: rx + ry,
            roll: self.h_ir() * rx,
            shear: -2.0 * PI * self.viscosity * (rx * ry).sqrt(),
            contact: self.contact(),
        }
    }
}

/// A [`PocketLaw`] with its geometric constants (radii, film coefficients, the Hertz
/// contact) computed once: [`PreparedPocket::force`] gives the same numbers as
/// [`PocketLaw::force`], bit for bit, without the ellipse solve and the `atan`, `powf`
/// and divisions of the constants at every call.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PreparedPocket {
    /// The law.
    pub law: PocketLaw,
    rx: f64,
    /// `12 pi eta (Rx Ry)^1.5`.
    squeeze: f64,
    /// `Rx + Ry`.
    sum_r: f64,
    /// `H_IR Rx`.
    roll: f64,
    /// `-2 pi eta sqrt(Rx Ry)`.
    shear: f64,
    contact: PointContact,
}

impl PreparedPocket {
    /// [`PocketLaw::film_normal`].
    #[inline]
    pub fn film_normal(&self, h: f64, h_dot: f64, u: f64) -> f64 {
        let l = &self.law;
        let h = h.max(l.roughness).max(H_FLOOR);
        let squeeze = self.squeeze / (self.sum_r * h) * (-h_dot);
        let roll = l.viscosity * u.abs() * self.rx * (self.roll / h).sqrt();
        (squeeze + roll).max(0.0)
    }

    /// [`PocketLaw::film_shear`].
    #[inline]
    pub fn film_shear(&self, h: f64, vs: f64) -> f64 {
        let l = &self.law;
        let h = h.max(l.roughness).max(H_FLOOR);
        self.shear * vs * (1.0 + l.ball_radius / (2.0 * h)).ln()
    }

    /// [`PocketLaw::force`].
    #[inline]
    pub fn force(&self, h: f64, h_dot: f64, u: f64, vs: f64) -> PocketForce {
        let l = &self.law;
        let normal = self.film_normal(h, h_dot, u);
        let shear = self.film_shear(h, vs);
        let approach = l.roughness - h;
        if approach > 0.0 {
            let q = self.contact.load(approach);
            let mu = if l.v_s > 0.0 {
                l.friction * (vs / l.v_s).tanh()
            } else if vs == 0.0 {
                0.0
            } else {
                l.friction * vs.signum()
            };
            PocketForce {
                normal: normal + q,
                friction: shear - mu * q,
            }
        } else {
            PocketForce {
                normal,
                friction: shear,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law() -> PocketLaw {
        PocketLaw {
            ball_radius: 3.969e-3,
            pocket_radius: 3.969e-3 + 0.15e-3,
            width: 3e-3,
            roughness: 0.3e-6,
            viscosity: 0.02,
            e_eff: 5.0e9,
            friction: 0.1,
            v_s: 0.01,
        }
    }

    /// The normal force (and friction) are continuous at h = roughness.
    #[test]
    fn continuous_at_the_roughness() {
        let p = law();
        for (h_dot, u, vs) in [(-0.01, 2.0, 0.5), (0.0, 3.0, -1.0), (1e-5, 0.5, 0.0)] {
            let a = p.force(p.roughness * (1.0 - 1e-12), h_dot, u, vs);
            let b = p.force(p.roughness * (1.0 + 1e-12), h_dot, u, vs);
            let at = p.force(p.roughness, h_dot, u, vs);
            assert!(at.normal > 0.0);
            assert!(
                (a.normal - b.normal).abs() <= 1e-9 * at.normal,
                "{a:?} {b:?}"
            );
            assert!((a.friction - b.friction).abs() <= 1e-9 * at.friction.abs().max(1e-30));
        }
    }

    /// No viscosity, positive gap: nothing. Separating with no entrainment: no suction.
    #[test]
    fn zero_without_viscosity_and_no_suction() {
        let dry = PocketLaw {
            viscosity: 0.0,
            ..law()
        };
        assert_eq!(dry.force(1e-6, -0.1, 3.0, 2.0), PocketForce::default());
        let p = law();
        assert_eq!(p.force(1e-6, 0.1, 0.0, 0.0).normal, 0.0);
        // Finite at h -> 0+, in penetration and at u = 0.
        for h in [1e-300, 0.0, -1e-5] {
            let f = p.force(h, -1.0, 0.0, 1.0);
            assert!(f.normal.is_finite() && f.friction.is_finite() && f.normal > 0.0);
        }
        let zero_rough = PocketLaw {
            roughness: 0.0,
            ..p
        };
        let f = zero_rough.force(1e-300, -1.0, 5.0, 1.0);
        assert!(f.normal.is_finite() && f.friction.is_finite());
    }

    /// In contact, the normal force is the crate's Hertz load at the approach
    /// `roughness - h` on top of the film force at the roughness; the Hertz constant is the
    /// ball in a conforming cylinder's (sphere on a plane as Rp -> infinity).
    #[test]
    fn hertz_branch_matches_the_crate() {
        let p = PocketLaw {
            viscosity: 0.0,
            ..law()
        };
        let delta = 2e-6;
        let f = p.force(p.roughness - delta, 0.0, 0.0, 0.0);
        let c = PointContact::new(
            Curvature::from_radii(3.969e-3, 3.969e-3 * 4.119e-3 / 0.15e-3),
            5e9,
        );
        let q = c.kc * delta.powf(1.5);
        assert!((f.normal - q).abs() < 1e-9 * q, "{f:?} {q}");
        // Conformity stiffens the contact relative to a ball on a flat.
        let flat = PointContact::new(Curvature::sphere_on_flat(3.969e-3), 5e9);
        assert!(c.kc > 1.5 * flat.kc);
        // Coulomb friction: mu Q tanh(vs/v_s), opposing vs.
        let g = p.force(p.roughness - delta, 0.0, 0.0, 1.0);
        assert!((g.friction + 0.1 * q * (100.0f64).tanh()).abs() < 1e-9 * q);
    }

    /// Film limits: the squeeze term is the sphere's 6 pi eta R² V/h as the pocket
    /// flattens; the entrainment film is linear in u and falls as h^-1/2.
    #[test]
    fn film_limits() {
        let p = PocketLaw {
            pocket_radius: 1e6,
            roughness: 0.0,
            ..law()
        };
        let (r, h, v) = (3.969e-3, 1e-6, 0.01);
        let want = 6.0 * PI * 0.02 * r * r * v / h;
        let got = p.force(h, -v, 0.0, 0.0).normal;
        assert!((got - want).abs() < 1e-6 * want, "{got} {want}");
        // Brewe–Hamrock–Taylor for a sphere (a_r = 1): H_IR = 128 * 0.36 * (0.131 atan 0.5 + 1.683)².
        let hir = 128.0 * 0.36 * (0.131 * 0.5f64.atan() + 1.683).powi(2);
        assert!((p.h_ir() - hir).abs() < 1e-6 * hir);
        assert!((hir - 140.1).abs() < 0.1);
        let a = p.force(h, 0.0, 1.0, 0.0).normal;
        let b = p.force(4.0 * h, 0.0, 2.0, 0.0).normal;
        assert!((a - b).abs() < 1e-12 * a);
        assert!((a - 0.02 * r * (hir * r / h).sqrt()).abs() < 1e-6 * a);
    }
}
