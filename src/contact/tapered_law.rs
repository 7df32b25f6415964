//! The contact law of a tapered roller for the levels that sum elements
//! ([`crate::seam::element::ElementLaw`]): each massless roller in equilibrium between the cup
//! (outer raceway, angle `alpha_o`), the cone (inner raceway, `alpha_i`) and the cone back
//! flange (`alpha_f`), its line contacts carried by the laminae of `contact::lamina`
//! (docs/physics.md §R7).
//!
//! Orientation: the taper's apex lies on the `+z` side of the roller, so a displacement of the
//! inner ring toward `+z` (the shaft pushed along `+z`) loads the bearing, as for a single-row
//! angular contact ball bearing at a positive contact angle. The cup's contact normal (from the
//! roller toward the cup) is `n_o = (sin alpha_o, cos alpha_o)` in `(axial, radial)`.
//!
//! Roller equilibrium (the flange taken as a rigid seat, the roller at rest): the cup pushes
//! the roller with `-Q_o n_o`, the cone with `Q_i n_i` and the flange with `Q_f n_f`; their
//! sum is zero, which gives `Q_i/Q_o` and `Q_f/Q_o` from the three angles alone
//! ([`RollerBearing::tapered_load_ratios`], [Harris & Kotzalas 2007] vol. 1 ch. 7), and the
//! roller puts on the inner ring (cone and flange together) exactly `-Q_o n_o`: the force on
//! the shaft is `F_a = -Q_o sin alpha_o`, `F_r = -Q_o cos alpha_o`.
//!
//! Compatibility, reduced to the cup normal: the inner ring's displacement at the roller,
//! `(axial, radial, tilt)`, moves the point of the roller axis at `x` from the roller's
//! mid-point (toward the large end) by `(axial + r_P tilt, radial - z_P tilt)`; along `n_o`
//! that is the lamina approach
//! `delta_k = sin(alpha_o) axial + cos(alpha_o) (radial - Pd/2) + tilt (a + x_k cos beta) - 2 P(x_k)`
//! with `a = (Dpw/2) sin alpha_o` (the projection of the roller's mid-point on the cup
//! generatrix, measured from the bearing's mid-plane) and `beta` the roller's half taper
//! angle (`x_k cos beta` is the lamina's position projected on the cup generatrix). This is
//! the laminae's `evaluate(delta, psi)` with `delta = sin(alpha_o) axial + cos(alpha_o)
//! (radial - Pd/2) + a tilt` and `tan(psi) = -tilt cos(beta)`. `Pd` is the radial play at zero
//! axial shift, so the gap along the cup normal is `cos(alpha_o) Pd/2`.
//!
//! The two line contacts in series carry different loads (the cone `Q_i = rho Q_o`): with the
//! Palmgren approach `∝ q^0.9` of each and the laminae's constant `c_s` written for equal loads
//! (each contact half of the approach), the cup-normal approach is `(1 + rho^0.9)/2` times that
//! of equal loads, so the laminae here use `c_s (2/(1 + rho^0.9))^(10/9)`. Left out (each a
//! few per mille for catalogue tapers, documented in docs/physics.md §R7): the angle `2 beta`
//! between the two normals and the flange's own compliance (a rigid seat).
//!
//! At speed (docs/physics.md §R11; [Harris 2007] vol. 2, high-speed tapered roller bearings)
//! the roller orbits at `omega_c = omega (1 - gamma)/2` and spins at `omega_R = omega (Dpw/(2
//! Dwe)) (1 - gamma²)` (outer ring fixed), so it carries its centrifugal force `F_c = m (Dpw/2)
//! omega_c²` outward and, its axis inclined `phi` (`alpha_roller`) to the bearing axis, the
//! gyroscopic moment `M_g = J omega_R omega_c sin(phi)`, `J = m Dwe²/8`, which the races must
//! supply about the roller's tangential axis (it presses the large end onto the cup; it is
//! even in the speed: reversing the shaft reverses both spin and orbit). Both act lamina by
//! lamina as a radial push `h_k = F_c/ns + M_g x_k/(cos(phi) Σ x_j²)` (the even split, as the
//! cylindrical roller's; the linear part has no resultant and the moment `M_g`). Each lamina
//! is then in equilibrium between cup `t_k`, cone `s_k` and flange: `s_k = rho_i t_k - kappa
//! h_k`, `kappa = sin(alpha_f)/sin(alpha_i + alpha_f)`, and shares the cup-normal approach
//! `delta_k = (t_k/c_1)^0.9 + (s_k/c_1)^0.9` (`c_1` one contact's lamina constant). The force on
//! the inner ring is `-t_k n_o + h_k e_r` per lamina. Massless rollers ([`TaperedRollerLaw::
//! massless`], the ring level) and `omega == 0` run the law above unchanged, bit for bit.
//!
//! By virtual work through `d delta_k` the forces on the shaft are `F_a = -sin(alpha_o) Q`,
//! `F_r = -cos(alpha_o) Q`, `m = -a Q - cos(beta) M` with `Q = Σ q_k`, `M = Σ q_k x_k`; the
//! derivatives follow from the laminae's Jacobian and `K` is symmetric.

use crate::contact::lamina::{line_hertz, Laminae, RollerLoad};
use crate::error::{Error, Result};
use crate::geometry::roller::RollerBearing;
use crate::seam::element::{ElementAt, ElementDisplacement, ElementLaw, ElementReaction, Want};

/// A tapered roller between cup, cone and cone back flange, by laminae (module docs).
#[derive(Debug, Clone)]
pub struct TaperedRollerLaw {
    laminae: Laminae,
    sin_o: f64,
    cos_o: f64,
    cos_beta: f64,
    /// `(Dpw/2) sin alpha_o`, m.
    arm: f64,
    half_pd: f64,
    /// `Q_i/Q_o`, `Q_f/Q_o`.
    rho_inner: f64,
    rho_flange: f64,
    r_inner: f64,
    r_outer: f64,
    e_inner: f64,
    e_outer: f64,
    /// `F_c/omega²`, kg m.
    fc_per_omega2: f64,
    /// `M_g/omega²`, kg m².
    mg_per_omega2: f64,
    /// `kappa = sin(alpha_f)/sin(alpha_i + alpha_f)`: cone load lost per unit radial push.
    kappa: f64,
    /// `sin(alpha_i)/sin(alpha_i + alpha_f)`: flange load gained per unit radial push.
    kappa_flange: f64,
    /// One contact's lamina constant `c_1`, N/m^(10/9).
    c1: f64,
    /// `cos(phi) Σ x_k²`, m².
    x2_cos_phi: f64,
}

impl TaperedRollerLaw {
    /// The law of the rollers of the tapered bearing `b`; refuses a cylindrical one naming
    /// `bearing.kind`, and a bearing without the cone back flange naming `bearing.flange`.
    pub fn new(b: &RollerBearing) -> Result<Self> {
        if !b.kind.is_tapered() {
            return Err(Error::invalid(
                "bearing.kind",
                "cylindrical",
                "tapered (the tapered roller law; nu, n, nj and nup run on the cylindrical one)",
            ));
        }
        let f = b.flange.ok_or_else(|| {
            Error::invalid(
                "bearing.flange",
                "missing",
                "a cone back flange (a tapered roller bearing carries the roller's axial reaction on it)",
            )
        })?;
        let (rho_inner, rho_flange) = b.tapered_load_ratios();
        let (ao, ai, af) = (b.alpha, b.alpha_cone, f.angle);
        if !(rho_inner.is_finite() && rho_inner > 0.0 && rho_flange > 0.0 && (ai + af).sin() > 0.0)
        {
            return Err(Error::invalid(
                "bearing.flange.angle_deg",
                af.to_degrees(),
                format!(
                    "an angle that closes the roller's force triangle with cup {:.2}° and cone {:.2}° (in (0, {:.1}) degrees)",
                    ao.to_degrees(),
                    ai.to_degrees(),
                    180.0 - ao.to_degrees()
                ),
            ));
        }
        let mut laminae = b.laminae()?;
        let c1 = laminae.cs * 2f64.powf(10.0 / 9.0);
        laminae.cs *= (2.0 / (1.0 + rho_inner.powf(0.9))).powf(10.0 / 9.0);
        let cage = crate::geometry::kinematics::cage_speed(b.gamma(), 1.0, 0.0);
        let spin = crate::geometry::kinematics::ball_spin_speed(b.dwe, b.dpw, b.gamma(), 1.0, 0.0);
        let m = b.roller_mass();
        let phi = b.alpha_roller;
        let x2: f64 = laminae.x.iter().map(|x| x * x).sum();
        Ok(TaperedRollerLaw {
            fc_per_omega2: m * 0.5 * b.dpw * cage * cage,
            mg_per_omega2: m * b.dwe * b.dwe / 8.0 * spin * cage * phi.sin(),
            kappa: af.sin() / (ai + af).sin(),
            kappa_flange: ai.sin() / (ai + af).sin(),
            c1,
            x2_cos_phi: x2 * phi.cos(),
            laminae,
            sin_o: ao.sin(),
            cos_o: ao.cos(),
            cos_beta: b.beta.cos(),
            arm: 0.5 * b.dpw * ao.sin(),
            half_pd: 0.5 * b.pd,
            rho_inner,
            rho_flange,
            r_inner: b.reduced_radius_inner(),
            r_outer: b.reduced_radius_outer(),
            e_inner: b.e_prime_inner(),
            e_outer: b.e_prime_outer(),
        })
    }

    /// The same law with massless rollers (no centrifugal force or gyroscopic moment at any
    /// speed): the ring level's elements, as [`crate::contact::roller_law::CylindricalRollerLaw::massless`].
    pub fn massless(mut self) -> Self {
        self.fc_per_omega2 = 0.0;
        self.mg_per_omega2 = 0.0;
        self
    }

    /// The roller's centrifugal force `F_c` (N) and gyroscopic moment `M_g` (N m) at shaft
    /// speed `omega` (rad/s), outer ring fixed (module docs).
    pub fn inertia_loads(&self, omega: f64) -> (f64, f64) {
        let w2 = omega * omega;
        (self.fc_per_omega2 * w2, self.mg_per_omega2 * w2)
    }

    /// The radial push `h_k` (N) of lamina `k` at speed (module docs).
    fn push(&self, k: usize, fc: f64, mg: f64) -> f64 {
        fc / self.laminae.len() as f64 + mg * self.laminae.x[k] / self.x2_cos_phi
    }

    /// Whether the law feels the speed `omega`.
    fn at_speed(&self, omega: f64) -> bool {
        omega != 0.0 && (self.fc_per_omega2 != 0.0 || self.mg_per_omega2 != 0.0)
    }

    /// The cup lamina loads at speed: at approach `delta` (cup normal) and `tan psi` `tau`,
    /// the cup loads' force, moment and derivatives, and the largest cone lamina load (N);
    /// `cup`, `cone` (length `ns`) receive the lamina loads when given (module docs).
    fn pressed(
        &self,
        delta: f64,
        tau: f64,
        omega: f64,
        mut cup: Option<&mut [f64]>,
        mut cone: Option<&mut [f64]>,
    ) -> (RollerLoad, f64) {
        let (fc, mg) = self.inertia_loads(omega);
        let (rho, kap, c1) = (self.rho_inner, self.kappa, self.c1);
        let sec2 = 1.0 + tau * tau;
        let mut r = RollerLoad::default();
        let mut cone_max = 0.0f64;
        let l = &self.laminae;
        for k in 0..l.len() {
            let (x, d2) = (l.x[k], l.drop2[k]);
            let h = self.push(k, fc, mg);
            let dk = delta - x * tau - d2;
            // The state with one contact open: the lamina held by the other and the flange.
            let t_floor = (kap * h / rho).max(0.0);
            let s_floor = rho * t_floor - kap * h;
            let a = |q: f64| (q.max(0.0) / c1).powf(0.9);
            let d_min = a(t_floor) + a(s_floor);
            let (t, dt) = if dk <= d_min {
                (t_floor, 0.0)
            } else {
                // G(t) = a(t) + a(rho t - kappa h) - dk: increasing and concave on
                // (t_floor, inf); Newton kept inside the bracket, bisection when it leaves.
                let g = |t: f64| a(t) + a(rho * t - kap * h) - dk;
                let dg = |t: f64| {
                    let s = rho * t - kap * h;
                    0.9 / c1 * ((t / c1).powf(-0.1) + rho * (s / c1).powf(-0.1))
                };
                let (mut lo, mut hi) = (t_floor, (c1 * dk.powf(10.0 / 9.0)).max(t_floor));
                let mut t = (c1 * (dk / (1.0 + rho.powf(0.9))).powf(10.0 / 9.0)).clamp(lo, hi);
                for _ in 0..200 {
                    let gt = g(t);
                    if gt > 0.0 {
                        hi = t;
                    } else {
                        lo = t;
                    }
                    let mut next = t - gt / dg(t);
                    if !(next > lo && next < hi) {
                        next = 0.5 * (lo + hi);
                    }
                    let done = (next - t).abs() <= 4.0 * f64::EPSILON * t
                        || hi - lo <= 4.0 * f64::EPSILON * hi;
                    t = next;
                    if done {
                        break;
                    }
                }
                (t, 1.0 / dg(t))
            };
            if let Some(c) = cup.as_deref_mut() {
                c[k] = t;
            }
            let s = (rho * t - kap * h).max(0.0);
            cone_max = cone_max.max(s);
            if let Some(c) = cone.as_deref_mut() {
                c[k] = s;
            }
            r.add(t, dt, x, sec2);
        }
        (r, cone_max)
    }

    /// Each lamina's cup and cone loads (N) at `u` and shaft speed `omega`; returns the cup
    /// load `Q_o` and the flange load `Q_f` (at rest the cone's is `rho_i` times the cup's).
    pub fn lamina_loads_at(
        &self,
        u: ElementDisplacement,
        omega: f64,
        cup: &mut [f64],
        cone: &mut [f64],
    ) -> (f64, f64) {
        if !self.at_speed(omega) {
            let qo = self.lamina_loads(u, cup);
            for (c, t) in cone.iter_mut().zip(cup.iter()) {
                *c = t * self.rho_inner;
            }
            return (qo, self.rho_flange * qo);
        }
        let (d, tau) = self.lamina_inputs(u);
        let (r, _) = self.pressed(d, tau, omega, Some(cup), Some(cone));
        let (fc, _) = self.inertia_loads(omega);
        (r.force, self.rho_flange * r.force + self.kappa_flange * fc)
    }

    /// The laminae it evaluates (their constant is the series one of module docs).
    pub fn laminae(&self) -> &Laminae {
        &self.laminae
    }

    /// `(Q_i/Q_o, Q_f/Q_o)`: the cone and flange loads per unit cup load.
    pub fn load_ratios(&self) -> (f64, f64) {
        (self.rho_inner, self.rho_flange)
    }

    /// The approach at the roller's mid-point along the cup normal and `tan(psi)` of the
    /// laminae, for the displacement `u` (module docs).
    pub fn lamina_inputs(&self, u: ElementDisplacement) -> (f64, f64) {
        (
            self.sin_o * u.axial + self.cos_o * (u.radial - self.half_pd) + self.arm * u.tilt,
            -self.cos_beta * u.tilt,
        )
    }

    /// Each lamina's cup load (N) into `loads` (length of the laminae) at `u`; returns the
    /// cup load `Q_o` (the cone's is `rho_i` times, the flange's `rho_f` times it).
    pub fn lamina_loads(&self, u: ElementDisplacement, loads: &mut [f64]) -> f64 {
        let (d, t) = self.lamina_inputs(u);
        self.laminae.evaluate_into(d, t.atan(), loads).force
    }
}

impl ElementLaw for TaperedRollerLaw {
    fn name(&self) -> &'static str {
        "tapered roller"
    }

    fn tilt_damping_arm2(&self) -> f64 {
        self.laminae.lwe * self.laminae.lwe / 12.0
    }

    fn state_len(&self) -> usize {
        0
    }

    fn react(
        &self,
        _at: ElementAt<'_>,
        u: ElementDisplacement,
        omega: f64,
        _state: &mut [f64],
        want: Want,
    ) -> Result<ElementReaction> {
        let (delta, tau) = self.lamina_inputs(u);
        let fast = self.at_speed(omega);
        let (r, contact) = if fast {
            let (r, cone_max) = self.pressed(delta, tau, omega, None, None);
            // The cone contact's own approach at its most loaded lamina (one contact's
            // lamina law inverted): zero where the cone closes, while the cup and flange
            // already carry the roller's inertia.
            let c = if cone_max > 0.0 {
                crate::contact::lamina::lamina_approach(cone_max, self.c1)
            } else {
                delta.min(0.0)
            };
            (r, c)
        } else {
            let r = self.laminae.evaluate(delta, tau.atan());
            let c = self.laminae.contact_approach(&r, delta, false);
            (r, c)
        };
        Ok(self.reaction(r, delta, contact, tau, omega, fast, want))
    }
}

impl TaperedRollerLaw {
    /// Each lamina's position along the raceway generatrix from the roller's mid-point, m,
    /// positive toward `+z` (the small end, the apex's side): `-x_k cos(beta)` (`x_k` runs
    /// toward the large end, module docs). A defect's axial extent is measured there
    /// (docs/physics.md §R12).
    pub fn generatrix_positions(&self) -> Vec<f64> {
        self.laminae.x.iter().map(|x| -x * self.cos_beta).collect()
    }

    /// The reaction of a massless roller ([`TaperedRollerLaw::massless`], the ring level's)
    /// whose laminae's cup-normal approaches are moved by `offsets` (m, one per lamina: a
    /// cup or cone defect's depth loss subtracts; docs/physics.md §R12), with the cup lamina
    /// loads into `loads` when given. Each lamina's load is [`ElementLaw::react`]'s bit for
    /// bit where its offset is zero (the same approach, the same root); the roller's sums
    /// agree to rounding.
    pub fn react_offsets(
        &self,
        u: ElementDisplacement,
        offsets: &[f64],
        want: Want,
        loads: Option<&mut [f64]>,
    ) -> ElementReaction {
        debug_assert!(!self.at_speed(1.0), "massless rollers only");
        let (delta, tau) = self.lamina_inputs(u);
        // The tangent `react` evaluates at (`evaluate(delta, atan tau)`), to the bit.
        let t = crate::contact::lamina::tan0(tau.atan());
        let r = self.laminae.evaluate_offsets(delta, t, offsets, loads);
        let contact = self.laminae.contact_approach(&r, delta, false);
        self.reaction(r, delta, contact, tau, 0.0, false, want)
    }

    /// The element's reaction from the cup laminae's `r` at the cup-normal approach `delta`
    /// (`contact`: what contact damping ramps in with) and `tau = tan(psi)` (module docs);
    /// `fast`: at speed (`omega`).
    #[allow(clippy::too_many_arguments)]
    fn reaction(
        &self,
        r: RollerLoad,
        delta: f64,
        contact: f64,
        tau: f64,
        omega: f64,
        fast: bool,
        want: Want,
    ) -> ElementReaction {
        let (q, m) = (r.force, r.moment);
        let mut out = ElementReaction {
            f: [
                -self.sin_o * q,
                -self.cos_o * q,
                -self.arm * q - self.cos_beta * m,
            ],
            approach: contact,
            ..Default::default()
        };
        if fast {
            // The pushes reach the inner ring through cone and flange: radially their sum
            // F_c, and on the tilt the moment Σ h_k x_k cos(phi) = M_g (module docs).
            let (fc, mg) = self.inertia_loads(omega);
            out.f[1] += fc;
            out.f[2] += mg;
        }
        if want.stiffness {
            // d/d(tan psi) = d/d psi / sec²(psi); tan psi = -cos(beta) tilt.
            let sec2 = 1.0 + tau * tau;
            let g = [self.sin_o, self.cos_o, self.arm];
            let (qd, qt) = (r.dforce_ddelta, r.dforce_dtilt / sec2);
            let (md, mt) = (r.dmoment_ddelta, r.dmoment_dtilt / sec2);
            let dq = [qd * g[0], qd * g[1], qd * g[2] - qt * self.cos_beta];
            let dm = [md * g[0], md * g[1], md * g[2] - mt * self.cos_beta];
            for k in 0..3 {
                let (a, b) = (dq[k], dm[k]);
                out.df[0][k] = -self.sin_o * a;
                out.df[1][k] = -self.cos_o * a;
                out.df[2][k] = -self.arm * a - self.cos_beta * b;
            }
        }
        if want.report && fast {
            let w = self.laminae.width();
            let ns = self.laminae.len();
            let (mut cup, mut cone) = (vec![0.0; ns], vec![0.0; ns]);
            let _ = self.pressed(delta, tau, omega, Some(&mut cup), Some(&mut cone));
            let mx = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
            out.load = [cone.iter().sum(), q];
            out.pressure = [
                line_hertz(mx(&cone) / w, self.r_inner, self.e_inner).1,
                line_hertz(mx(&cup) / w, self.r_outer, self.e_outer).1,
            ];
        } else if want.report {
            let w = self.laminae.width();
            out.load = [self.rho_inner * q, q];
            out.pressure = [
                line_hertz(
                    self.rho_inner * r.max_lamina / w,
                    self.r_inner,
                    self.e_inner,
                )
                .1,
                line_hertz(r.max_lamina / w, self.r_outer, self.e_outer).1,
            ];
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::roller_catalogue::lookup;
    use crate::seam::element::assemble;
    use std::f64::consts::PI;

    fn law(name: &str) -> (TaperedRollerLaw, RollerBearing, Vec<f64>) {
        let b = lookup(name).unwrap().build().unwrap();
        let psi = (0..b.z).map(|j| 2.0 * PI * j as f64 / b.z as f64).collect();
        (TaperedRollerLaw::new(&b).unwrap(), b, psi)
    }

    fn sum(
        l: &TaperedRollerLaw,
        psi: &[f64],
        q: &[f64; 5],
        k: Option<&mut [[f64; 5]; 5]>,
    ) -> [f64; 5] {
        let want = Want {
            stiffness: k.is_some(),
            report: false,
        };
        assemble(q, psi, l.moment_arm(), k, |_, at, u| {
            l.react(at, u, 0.0, &mut [], want)
        })
        .unwrap()
    }

    /// `K = -dF/dq` by central differences in every direction, and symmetric.
    #[test]
    fn ring_stiffness_is_minus_the_derivative_and_symmetric() {
        let (l, _, psi) = law("30206");
        let q = [15e-6, -10e-6, 20e-6, 3e-4, -2e-4];
        let mut k = [[0.0; 5]; 5];
        let f = sum(&l, &psi, &q, Some(&mut k));
        assert!(
            f[2] < 0.0 && f[0] < 0.0,
            "the rollers push the shaft back: {f:?}"
        );
        crate::contact::test_util::assert_k_matches_differences(
            &k,
            q,
            &[0, 1, 2, 3, 4],
            |x| sum(&l, &psi, x, None),
            k[2][2].abs(),
            1e-3,
            1e-9,
        );
    }

    /// A pure axial displacement loads every roller alike: the axial force is `Z Q sin(alpha)`
    /// and the radial forces cancel; the flange carries `Q_f = rho_f Q_o`, which closes the
    /// roller's force triangle (checked as vectors).
    #[test]
    fn axial_displacement_loads_all_rollers_and_the_flange_closes_the_triangle() {
        let (l, b, psi) = law("30206");
        let f = sum(&l, &psi, &[0.0, 0.0, 10e-6, 0.0, 0.0], None);
        assert!(f[0].abs() < 1e-9 * f[2].abs() && f[1].abs() < 1e-9 * f[2].abs());
        let u = ElementDisplacement {
            axial: 10e-6,
            radial: 0.0,
            tilt: 0.0,
        };
        let at = ElementAt {
            index: 0,
            psi: 0.0,
            sc: (0.0, 1.0),
            q: &[0.0; 5],
        };
        let want = Want {
            stiffness: false,
            report: true,
        };
        let r = l.react(at, u, 0.0, &mut [], want).unwrap();
        let qo = r.load[1];
        assert!((f[2] + b.z as f64 * qo * b.alpha.sin()).abs() < 1e-9 * f[2].abs());
        // Forces on the roller: cup -Q_o n_o, cone +Q_i n_i, flange Q_f n_f with the flange's
        // normal from the flange toward the roller, toward the apex: (sin alpha_f,
        // -cos alpha_f) in the (axial, radial) frame of module docs.
        let (ri, rf) = l.load_ratios();
        let (ao, ai, af) = (b.alpha, b.alpha_cone, b.flange.unwrap().angle);
        let n = |a: f64| [a.sin(), a.cos()];
        let (no, ni) = (n(ao), n(ai));
        let nf = [af.sin(), -af.cos()];
        for c in 0..2 {
            let s = -qo * no[c] + ri * qo * ni[c] + rf * qo * nf[c];
            assert!(s.abs() < 1e-9 * qo, "component {c}: {s}");
        }
        assert!((r.load[0] / qo - ri).abs() < 1e-12 && rf > 0.0);
        assert!(r.pressure[0] > r.pressure[1] && r.pressure[1] > 0.0);
    }

    /// The laminae's series constant: a straight roller at a uniform approach `delta` carries
    /// `c_s (2 delta/(1 + rho^0.9))^(10/9)` with `c_s` the equal-load constant.
    #[test]
    fn unequal_cone_and_cup_loads_soften_the_roller() {
        let (l, b, _) = law("30206");
        let base = b.laminae().unwrap();
        let (rho, _) = l.load_ratios();
        let ratio = l.laminae().cs / base.cs;
        assert!((ratio - (2.0 / (1.0 + rho.powf(0.9))).powf(10.0 / 9.0)).abs() < 1e-15);
        assert!(ratio <= 1.0 + 1e-15 && ratio > 0.9, "{ratio}");
    }

    #[test]
    fn a_cylindrical_bearing_is_refused_naming_the_kind() {
        let b = lookup("NU206").unwrap().build().unwrap();
        let e = TaperedRollerLaw::new(&b).unwrap_err().to_string();
        assert!(e.contains("bearing.kind"), "{e}");
    }

    fn at(q: &[f64; 5]) -> ElementAt<'_> {
        ElementAt {
            index: 0,
            psi: 0.0,
            sc: (0.0, 1.0),
            q,
        }
    }

    const REPORT: Want = Want {
        stiffness: true,
        report: true,
    };

    /// At `omega == 0` the law with inertia is the massless one bit for bit, and the massless
    /// law at 20 000 rpm is the law at rest bit for bit (the ring level's rollers).
    #[test]
    fn at_rest_and_massless_the_law_is_unchanged() {
        let (l, _, _) = law("30206");
        let m = l.clone().massless();
        let u = ElementDisplacement {
            axial: 12e-6,
            radial: 3e-6,
            tilt: 2e-4,
        };
        let q0 = [0.0; 5];
        let rest = m.react(at(&q0), u, 0.0, &mut [], REPORT).unwrap();
        for (law_, w) in [(&l, 0.0), (&l, -0.0), (&m, 2094.4)] {
            let r = law_.react(at(&q0), u, w, &mut [], REPORT).unwrap();
            assert_eq!(format!("{r:?}"), format!("{rest:?}"), "omega {w}");
        }
    }

    /// One 30206 roller at 10 000 rpm, hand values: `m = rho pi Dwe² Lw/4`, `omega_c = omega
    /// (1 - gamma)/2`, `omega_R = omega Dpw/(2 Dwe) (1 - gamma²)`, `F_c = m Dpw/2 omega_c²`,
    /// `M_g = m Dwe²/8 omega_R omega_c sin(alpha_roller)`. At a fixed ring displacement the cup
    /// load rises and the cone load falls, by `rho_i Q_o - Q_i = kappa F_c` (no lamina open),
    /// the roller's force triangle with `F_c` closes, the shaft feels `F_c` radially, and the
    /// gyroscopic moment loads the large end more than the small end. The result is the same
    /// for either direction of the shaft (both terms are even in the speed).
    #[test]
    fn at_speed_the_cup_carries_the_centrifugal_force() {
        let (l, b, _) = law("30206");
        let omega = 10_000.0 * PI / 30.0;
        let m = b.roller_material.density * PI / 4.0 * b.dwe * b.dwe * b.lw;
        let g = b.dwe * b.alpha.cos() / b.dpw;
        let (wc, wr) = (
            omega * (1.0 - g) / 2.0,
            omega * b.dpw / (2.0 * b.dwe) * (1.0 - g * g),
        );
        let fc = m * b.dpw / 2.0 * wc * wc;
        let mg = m * b.dwe * b.dwe / 8.0 * wr * wc * b.alpha_roller.sin();
        let (fc_l, mg_l) = l.inertia_loads(omega);
        assert!((fc_l / fc - 1.0).abs() < 1e-12 && (mg_l / mg - 1.0).abs() < 1e-12);
        assert!(fc > 1.0 && mg > 0.0, "F_c {fc} N, M_g {mg} N m");
        let u = ElementDisplacement {
            axial: 15e-6,
            radial: 0.0,
            tilt: 0.0,
        };
        let q0 = [0.0; 5];
        let rest = l.react(at(&q0), u, 0.0, &mut [], REPORT).unwrap();
        let fast = l.react(at(&q0), u, omega, &mut [], REPORT).unwrap();
        let back = l.react(at(&q0), u, -omega, &mut [], REPORT).unwrap();
        assert_eq!(format!("{fast:?}"), format!("{back:?}"));
        let ((qi0, qo0), (qi, qo)) = ((rest.load[0], rest.load[1]), (fast.load[0], fast.load[1]));
        assert!(
            qo > qo0 && qi < qi0,
            "cup {qo0} -> {qo}, cone {qi0} -> {qi}"
        );
        let (rho, _) = l.load_ratios();
        let kappa = l.kappa;
        assert!(
            (rho * qo - qi - kappa * fc).abs() < 1e-9 * qo,
            "{}",
            rho * qo - qi
        );
        // The force triangle with F_c (per roller; flange as lamina_loads_at gives it).
        let ns = l.laminae().len();
        let (mut cup, mut cone) = (vec![0.0; ns], vec![0.0; ns]);
        let (qo2, qf) = l.lamina_loads_at(u, omega, &mut cup, &mut cone);
        assert!((qo2 - qo).abs() < 1e-9 * qo);
        let (ao, ai, af) = (b.alpha, b.alpha_cone, b.flange.unwrap().angle);
        let (no, ni, nf) = (
            [ao.sin(), ao.cos()],
            [ai.sin(), ai.cos()],
            [af.sin(), -af.cos()],
        );
        for c in 0..2 {
            let s = -qo * no[c] + qi * ni[c] + qf * nf[c] + fc * [0.0, 1.0][c];
            assert!(s.abs() < 1e-9 * qo, "component {c}: {s}");
        }
        // The shaft: radially the cup's inward push less F_c.
        assert!((fast.f[1] - (-b.alpha.cos() * qo + fc)).abs() < 1e-9 * qo);
        // The gyroscopic moment presses the large end (last lamina) harder.
        let mut cup0 = vec![0.0; ns];
        l.lamina_loads(u, &mut cup0);
        assert!(cup[ns - 1] - cup0[ns - 1] > cup[0] - cup0[0]);
    }

    /// At speed `K = -dF/dq` by central differences, and symmetric (the pushes are constant
    /// forces: the roller slice keeps a potential).
    #[test]
    fn at_speed_the_stiffness_is_minus_the_derivative() {
        let (l, _, psi) = law("30206");
        let omega = 8000.0 * PI / 30.0;
        let f = |q: &[f64; 5], k: Option<&mut [[f64; 5]; 5]>| {
            let want = Want {
                stiffness: k.is_some(),
                report: false,
            };
            assemble(q, &psi, l.moment_arm(), k, |_, at, u| {
                l.react(at, u, omega, &mut [], want)
            })
            .unwrap()
        };
        let q = [15e-6, -10e-6, 20e-6, 3e-4, -2e-4];
        let mut k = [[0.0; 5]; 5];
        f(&q, Some(&mut k));
        crate::contact::test_util::assert_k_matches_differences(
            &k,
            q,
            &[0, 1, 2, 3, 4],
            |x| f(x, None),
            k[2][2].abs(),
            1e-3,
            1e-8,
        );
    }
}
