//! Cage–guide-land interaction: the short (Ocvirk) journal bearing formed by the cage's
//! guiding surface and the land of the guiding ring (docs/physics.md §5.5; Gupta, *Advanced
//! Dynamics of Rolling Elements*, 1984, ch. 5).
//!
//! **Film forces.** Reynolds' equation with the short-bearing approximation (Ocvirk 1952;
//! Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film Lubrication*, 2nd ed. 2004,
//! ch. 12; Childs, *Turbomachinery Rotordynamics*, 1993, ch. 3) for a journal whose centre
//! sits at `e = eps Cg` from the bearing centre, turning with the line of centres at
//! `phi_dot` and approaching the wall at `eps_dot`:
//! `d/dz(h³ dp/dz) = 6 eta (w_j + w_b - 2 phi_dot) dh/dtheta + 12 eta eps_dot Cg (-cos theta)`,
//! `h = Cg (1 - eps cos theta)` (theta from the line of centres). Integrating over the
//! half film that carries pressure (the pi-film / Gümbel condition, the cavitated half
//! chosen by the sign of the wedge speed `w_w = w_j + w_b - 2 phi_dot`) gives, with
//! `K = eta Rg Bg³ / Cg²`,
//! ```text
//! F_r = -K [ eps² |w_w| / (1 - eps²)²  +  pi (1 + 2 eps²) eps_dot / (2 (1 - eps²)^2.5) ]
//! F_t =  K [ pi eps w_w / (4 (1 - eps²)^1.5)  +  s 2 eps eps_dot / (1 - eps²)² ]
//! ```
//! along `e_hat` (radial, negative = back toward the centre) and `e_perp` (+90° about `+z`).
//! At `e_dot = 0` these are exactly docs/physics.md's `W_M` and `W_phi` with
//! `w_w = w_ring + w_c`. `s` is the side on which the squeeze pressure sits: `sign(w_w)`
//! when the wedge dominates; here the smooth `s = a / sqrt(a² + b²)`, `a = e w_w`,
//! `b = 2 e_dot_r`, which is the cosine of the angle by which the pressure zone turns when
//! squeeze and wedge act together (the positive zone of `a sin theta - b cos theta`), so
//! the law has no jump when `w_w` changes sign (start from rest). At `e -> 0` the forces
//! tend to the isotropic squeeze damping `F = -pi eta Rg Bg³ / (2 Cg³) e_dot` (the radial
//! and whirl terms give the same coefficient), which is what the code uses below
//! `|e| = 1e-12 Cg`, so `e/|e|` is never formed at 0.
//!
//! **Sign, inner- or outer-ring guidance.** The law above is for the force on the *journal*
//! (inner member) displaced by `e` from the *bearing* (outer member). It is odd in `e` and
//! symmetric in the two surface speeds, so with `e` defined as here (cage centre relative
//! to the guiding ring's centre) Newton's third law gives the *same* force on the cage
//! whether the cage is the journal (outer-ring guided) or the bearing (inner-ring guided):
//! a restoring radial force and a tangential force that drives whirl in the direction of
//! the mean surface speed `w_ring + w_c`. docs/physics.md's "sign flips for outer-ring guidance"
//! is Gupta's convention, in which the eccentricity is that of the journal in the bearing
//! (the land in the cage for inner-ring guidance); with this module's `e` no flip is
//! needed, and `outer` changes nothing in the force (a test checks the third-law
//! equivalence).
//!
//! **Torque.** Couette (Petroff) drag over the full film, docs/physics.md's `W_rho`, plus the
//! pressure-gradient shear, which acts on both surfaces equally: about each member's own
//! centre it is `-(e x F)/2` (from `tau = -(h/2) dp/dx` on both walls and integration by
//! parts, `∫ h dp/dtheta = -∫ p dh/dtheta`; it makes the moment balance of the film
//! `T_journal + T_bearing + e x F_journal = 0` hold). With `e` and `F` the cage's:
//! `T_c = 2 pi eta Rg³ Bg / (Cg sqrt(1 - eps²)) (w_ring - w_c) - (e x F)/2`, again the same
//! for both guidance types.
//!
//! **Cap and wall.** Beyond `eps_max` the film law is evaluated at `eps_max` (same
//! direction, same rates), so it is continuous there, and a wall spring
//! `contact_stiffness (|e| - eps_max Cg)` pushes the cage back, with a C¹ onset: a quadratic
//! ramp over the first `WALL_RAMP (1 - eps_max) Cg` of penetration.

use std::f64::consts::PI;

/// Width of the quadratic onset of the wall spring, as a fraction of `(1 - eps_max) Cg`.
pub const WALL_RAMP: f64 = 0.1;

/// A cage guide land (see the module notes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuideLand {
    /// Land radius `Rg`, m.
    pub radius: f64,
    /// Land width `Bg`, m.
    pub width: f64,
    /// Radial clearance `Cg`, m.
    pub clearance: f64,
    /// Viscosity `eta`, Pa s.
    pub viscosity: f64,
    /// `true`: outer-ring guided. With `e` the cage's offset from the ring, the law is the
    /// same for both (module notes); kept for the caller's bookkeeping.
    pub outer: bool,
    /// Wall contact stiffness beyond `eps_max`, N/m.
    pub contact_stiffness: f64,
    /// Eccentricity ratio where the hydrodynamic law is capped (e.g. 0.95).
    pub eps_max: f64,
}

/// What the guide land does to the cage.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GuideForce {
    /// Force on the cage, fixed frame `(x, y)`, N.
    pub f: [f64; 2],
    /// Drag torque on the cage about `z`, N m.
    pub torque: f64,
    /// Eccentricity ratio `|e| / Cg` (not capped).
    pub eps: f64,
}

impl GuideLand {
    /// Force and torque on the cage. `e`: cage-centre offset from the guiding ring's centre
    /// (m), `e_dot` its rate (m/s), `w_c` cage speed, `w_ring` guiding-ring speed (rad/s,
    /// about `+z`).
    pub fn force(&self, e: [f64; 2], e_dot: [f64; 2], w_c: f64, w_ring: f64) -> GuideForce {
        let c = self.clearance;
        let (rg, bg, eta) = (self.radius, self.width, self.viscosity);
        let k = eta * rg * bg.powi(3) / (c * c);
        let r = e[0].hypot(e[1]);
        let eps = r / c;
        let eps_max = self.eps_max.clamp(0.0, 0.999_999);
        let w_s = w_c + w_ring;
        let mut f = if r <= 1e-12 * c {
            // Centred: isotropic squeeze damping (module notes); whirl/wedge terms vanish.
            let d = 0.5 * PI * k / c;
            [-d * e_dot[0], -d * e_dot[1]]
        } else {
            let n = [e[0] / r, e[1] / r];
            let t = [-n[1], n[0]];
            let v_r = n[0] * e_dot[0] + n[1] * e_dot[1];
            let v_t = t[0] * e_dot[0] + t[1] * e_dot[1];
            let phi_dot = v_t / r;
            let w_w = w_s - 2.0 * phi_dot;
            let ef = eps.min(eps_max);
            let eps_dot = v_r / c;
            let q = 1.0 - ef * ef;
            let (a, b) = (ef * c * w_w, 2.0 * v_r);
            let m = a.hypot(b);
            let s = if m > 0.0 { a / m } else { 0.0 };
            let f_r = -k
                * (ef * ef * w_w.abs() / (q * q)
                    + PI * (1.0 + 2.0 * ef * ef) * eps_dot / (2.0 * q * q * q.sqrt()));
            let f_t = k * (PI * ef * w_w / (4.0 * q * q.sqrt()) + s * 2.0 * ef * eps_dot / (q * q));
            [f_r * n[0] + f_t * t[0], f_r * n[1] + f_t * t[1]]
        };
        let ef = eps.min(eps_max);
        let petroff = 2.0 * PI * eta * rg.powi(3) * bg / (c * (1.0 - ef * ef).sqrt());
        let torque = petroff * (w_ring - w_c) - 0.5 * (e[0] * f[1] - e[1] * f[0]);
        // Wall spring beyond eps_max, C¹ onset.
        let pen = r - eps_max * c;
        if pen > 0.0 && r > 0.0 {
            let w = (WALL_RAMP * (1.0 - eps_max) * c).max(f64::MIN_POSITIVE);
            let s = if pen < w {
                0.5 * pen * pen / w
            } else {
                pen - 0.5 * w
            };
            let fw = self.contact_stiffness * s;
            f[0] -= fw * e[0] / r;
            f[1] -= fw * e[1] / r;
        }
        GuideForce { f, torque, eps }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn land() -> GuideLand {
        GuideLand {
            radius: 0.03,
            width: 0.006,
            clearance: 0.2e-3,
            viscosity: 0.01,
            outer: false,
            contact_stiffness: 1e8,
            eps_max: 0.95,
        }
    }

    /// At `e_dot = 0` the force is docs/physics.md's `W_M`, `W_phi` (by numbers), resolved on
    /// the line of centres and rotated to x, y.
    #[test]
    fn reduces_to_physics_md_without_squeeze() {
        let g = land();
        let (eps, ang) = (0.6, 0.7f64);
        let e = [eps * g.clearance * ang.cos(), eps * g.clearance * ang.sin()];
        let (w_c, w_ring) = (400.0, 1000.0);
        let out = g.force(e, [0.0, 0.0], w_c, w_ring);
        let (rg, bg, c, eta): (f64, f64, f64, f64) = (0.03, 0.006, 0.2e-3, 0.01);
        let s = w_ring + w_c;
        let wm = eta * rg * bg.powi(3) / (c * c) * eps * eps / (1.0f64 - eps * eps).powi(2) * s;
        let wphi =
            PI * eta * rg * bg.powi(3) / (4.0 * c * c) * eps / (1.0f64 - eps * eps).powf(1.5) * s;
        // Hand numbers: K = 0.01*0.03*2.16e-7/4e-8 = 1.62e-3; W_M = 1.62e-3*0.36/0.4096*1400.
        assert!((wm - 1.62e-3 * 0.36 / 0.4096 * 1400.0).abs() < 1e-12);
        let fx = -wm * ang.cos() - wphi * ang.sin();
        let fy = -wm * ang.sin() + wphi * ang.cos();
        assert!((out.f[0] - fx).abs() < 1e-12 * wm, "{out:?} {fx}");
        assert!((out.f[1] - fy).abs() < 1e-12 * wm, "{out:?} {fy}");
        assert!((out.eps - eps).abs() < 1e-14);
        // Forward whirl: the tangential force is along +e_perp for a positive mean speed.
        let ft = -out.f[0] * ang.sin() + out.f[1] * ang.cos();
        assert!(ft > 0.0);
        // Torque: Petroff term plus -(e x F)/2, dragging the slower cage forward.
        let petroff =
            2.0 * PI * eta * rg.powi(3) * bg / (c * (1.0f64 - eps * eps).sqrt()) * (w_ring - w_c);
        let exf = e[0] * out.f[1] - e[1] * out.f[0];
        assert!((out.torque - (petroff - 0.5 * exf)).abs() < 1e-12 * petroff);
        assert!(out.torque > 0.0);
    }

    /// The force vanishes linearly as eps -> 0, is exactly zero at e = 0 (no NaN), and
    /// vanishes with the viscosity.
    #[test]
    fn linear_at_the_centre_and_zero_without_viscosity() {
        let g = land();
        let f = |eps: f64| g.force([eps * g.clearance, 0.0], [0.0; 2], 300.0, 900.0);
        let (a, b) = (f(1e-4), f(2e-4));
        let ratio = b.f[1] / a.f[1];
        assert!((ratio - 2.0).abs() < 1e-6, "{ratio}");
        assert!(a.f[0].abs() < 1e-3 * a.f[1].abs()); // radial part is O(eps²)
        let z = g.force([0.0, 0.0], [0.0, 0.0], 300.0, 900.0);
        assert_eq!(z.f, [0.0, 0.0]);
        assert!(z.torque.is_finite());
        // Centred with a velocity: isotropic squeeze damping, continuous with tiny eps.
        let v = [0.01, -0.02];
        let z = g.force([0.0, 0.0], v, 0.0, 0.0);
        let y = g.force([1e-9 * g.clearance, 0.0], v, 0.0, 0.0);
        for i in 0..2 {
            assert!(z.f[i].is_finite());
            assert!(
                (z.f[i] - y.f[i]).abs() < 1e-6 * z.f[0].hypot(z.f[1]),
                "{z:?} {y:?}"
            );
        }
        let dry = GuideLand {
            viscosity: 0.0,
            ..g
        };
        let d = dry.force([0.5 * g.clearance, 0.1 * g.clearance], v, 300.0, 900.0);
        assert_eq!(d.f, [0.0, 0.0]);
        assert_eq!(d.torque, 0.0);
    }

    /// The radial stiffness grows without bound toward the wall (like (1 - eps²)^-2), the
    /// capped force is continuous at eps_max, and the wall spring then takes over.
    #[test]
    fn stiffness_grows_toward_the_wall_and_cap_is_continuous() {
        let g = GuideLand {
            eps_max: 0.999,
            ..land()
        };
        let fr = |eps: f64| -g.force([eps * g.clearance, 0.0], [0.0; 2], 0.0, 1000.0).f[0];
        let stiff = |eps: f64| (fr(eps + 1e-6) - fr(eps - 1e-6)) / (2e-6 * g.clearance);
        let (k5, k9, k99) = (stiff(0.5), stiff(0.9), stiff(0.99));
        assert!(k9 > 10.0 * k5 && k99 > 50.0 * k9, "{k5} {k9} {k99}");
        let g = land();
        let f = |eps: f64| g.force([0.0, eps * g.clearance], [1e-3, -2e-3], 200.0, 1000.0);
        let (lo, hi) = (f(0.95 - 1e-12), f(0.95 + 1e-12));
        for i in 0..2 {
            assert!(
                (lo.f[i] - hi.f[i]).abs() < 1e-8 * lo.f[1].abs(),
                "{lo:?} {hi:?}"
            );
        }
        // Past the ramp the wall spring is linear with the given stiffness.
        let w = WALL_RAMP * 0.05 * g.clearance;
        let d = 1e-7;
        let a = g.force([0.0, 0.95 * g.clearance + 2.0 * w], [0.0; 2], 0.0, 1000.0);
        let b = g.force(
            [0.0, 0.95 * g.clearance + 2.0 * w + d],
            [0.0; 2],
            0.0,
            1000.0,
        );
        let k = -(b.f[1] - a.f[1]) / d;
        assert!((k - g.contact_stiffness).abs() < 1e-6 * k, "{k}");
    }

    /// Third law: the same film seen from the ring (the journal in an inner-ring-guided
    /// cage, displaced by -e from the cage) carries the opposite force, so the cage's force
    /// is the law's value with `e` the cage's offset; squeeze resists approach.
    #[test]
    fn squeeze_resists_approach_and_whirl_sign() {
        let g = land();
        let e = [0.5 * g.clearance, 0.0];
        let still = g.force(e, [0.0, 0.0], 0.0, 0.0);
        assert_eq!(still.f, [0.0, 0.0]);
        let app = g.force(e, [0.01, 0.0], 0.0, 0.0);
        let sep = g.force(e, [-0.01, 0.0], 0.0, 0.0);
        assert!(app.f[0] < 0.0 && sep.f[0] > 0.0);
        assert!((app.f[0] + sep.f[0]).abs() < 1e-12 * app.f[0].abs());
        let ring = g.force([-e[0], -e[1]], [0.0, 0.0], 1000.0, 300.0);
        let cage = g.force(e, [0.0, 0.0], 300.0, 1000.0);
        assert!((ring.f[0] + cage.f[0]).abs() < 1e-12 && (ring.f[1] + cage.f[1]).abs() < 1e-12);
        // Reverse rotation: tangential force reverses, radial stays restoring.
        let rev = g.force(e, [0.0, 0.0], -300.0, -1000.0);
        assert!((rev.f[0] - cage.f[0]).abs() < 1e-12 * cage.f[0].abs());
        assert!((rev.f[1] + cage.f[1]).abs() < 1e-12 * cage.f[1].abs());
        // Outer guidance: same law.
        let o = GuideLand { outer: true, ..g }.force(e, [0.0, 0.0], 300.0, 1000.0);
        assert_eq!(o, cage);
    }

    /// The closed forms with squeeze and whirl match a direct quadrature of the short-bearing
    /// pressure `∫p dz = -(eta Bg³/(2h³)) (e w_w sin theta - 2 e_dot_r cos theta)` over the
    /// pi-film `theta in (-pi, 0)` (wedge-dominated case, where `s -> 1`).
    #[test]
    fn closed_form_matches_quadrature() {
        let g = land();
        let (c, eta, rg, bg) = (g.clearance, g.viscosity, g.radius, g.width);
        let (eps, ang) = (0.7f64, -1.2f64);
        let n = [ang.cos(), ang.sin()];
        let t = [-n[1], n[0]];
        let e = [eps * c * n[0], eps * c * n[1]];
        let (v_r, v_t) = (2e-3, 3e-3);
        let e_dot = [v_r * n[0] + v_t * t[0], v_r * n[1] + v_t * t[1]];
        let (w_c, w_ring) = (2000.0, 5000.0);
        let w_w = w_c + w_ring - 2.0 * v_t / (eps * c);
        let m = 200_000;
        let (mut fr, mut ft) = (0.0, 0.0);
        for i in 0..m {
            let th = -PI + PI * (i as f64 + 0.5) / m as f64;
            let h = c * (1.0 - eps * th.cos());
            let p = -eta * bg.powi(3) / (2.0 * h.powi(3))
                * (eps * c * w_w * th.sin() - 2.0 * v_r * th.cos());
            fr -= rg * p * th.cos() * PI / m as f64;
            ft -= rg * p * th.sin() * PI / m as f64;
        }
        let out = g.force(e, e_dot, w_c, w_ring);
        let gr = out.f[0] * n[0] + out.f[1] * n[1];
        let gt = out.f[0] * t[0] + out.f[1] * t[1];
        assert!((gr - fr).abs() < 1e-6 * fr.abs(), "{gr} {fr}");
        assert!((gt - ft).abs() < 1e-6 * ft.abs(), "{gt} {ft}");
    }
}
