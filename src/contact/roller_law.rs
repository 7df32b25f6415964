//! The contact law of a cylindrical roller for the levels that sum elements
//! ([`crate::seam::element::ElementLaw`]): the laminae of `contact::lamina` (docs/physics.md
//! §R1) driven by the inner ring's displacement at the roller.
//!
//! In the element's frame (`seam::element`: `axial`, `radial` outward along the azimuth,
//! `tilt` about the element's tangential axis) the inner raceway at axial position `x` from the
//! roller's mid-plane moves outward by `radial - x tan(tilt)`, so lamina `k` has the approach
//! `delta_k = radial - Pd/2 - x_k tan(tilt) - 2 P(x_k)`: the roller's approach is
//! `delta = radial - Pd/2` (diametral clearance `Pd`) and its misalignment `psi = tilt`. (For a
//! roller on the `+x` axis a ring rotation `ry` moves the raceway at `z` outward by `z ry`, and
//! `tilt = -ry` there: the two agree.) The roller pushes the shaft inward with its load `Q`, so
//! the forces on the shaft are `F_a = 0`, `F_r = -Q` and, by virtual work through
//! `d delta_k = d radial - x_k sec²(tilt) d tilt`, the moment conjugate to the tilt
//! `m = sec²(tilt) Σ q_k x_k`. The derivatives follow from the laminae's Jacobian; `K` is
//! symmetric (a potential exists).
//!
//! Flanges (docs/physics.md §R8): NU and N carry no axial load (their axial stiffness is zero,
//! an exact 0 in `K`, never a NaN). An NJ (and an NUP, both ways) whose roller ends are
//! spherical (`bearing.flange.roller_end_radius_mm`) carries an axial displacement through the
//! inner flange, the roller and the opposite outer flange: two Hertz point contacts in series
//! (`contact::hertz`, curvatures from `RollerBearing::flange_curvature`), with the approach
//! `delta_f = s (axial + r_f tilt)` (`s = +1` for the NJ's one direction, `sign(axial)` for an
//! NUP; `r_f` the inner flange contact radius, zero axial play) and the force on the shaft
//! `F_a = -s Q_f`, moment `-s r_f Q_f`. Flat roller ends meet the flange on the chamfer's edge,
//! which this law does not model: such an NJ carries no axial load, as an NU.
//!
//! At speed (docs/physics.md §R9) the roller orbits with the kinematic cage speed
//! `omega_c = omega (1 - gamma)/2` (outer ring fixed, `gamma = Dwe/Dpw`) and presses on the
//! outer raceway with its centrifugal force `F_c = m (Dpw/2) omega_c²` ([Harris 2007] vol. 2,
//! high-speed cylindrical roller bearings: `Q_o = Q_i + F_c`), split evenly over the laminae
//! (the uniform split, the standard simplification: the outer raceway is not tilted and the
//! roller's own tilt is not solved); each lamina then shares its approach between an inner
//! contact `q_i,k` and an outer `q_i,k + F_c/ns` ([`Laminae`]'s `eval_pressed`). The force on
//! the shaft is the inner contacts' `-Σ q_i,k`; the report gives `Q_o = Q_i + F_c`. At
//! `omega == 0` the massless path runs unchanged, bit for bit.
//!
//! What it leaves out: the roller's own radial and tilt equilibrium as a rigid body (the
//! laminae stay independent, as in ISO/TS 16281), the flange contact's moment on the roller,
//! and tapered rollers (`contact::tapered_law`), which this law refuses.

use crate::contact::hertz::{hertz_load_and_stiffness, series_constant, PointContact};
use crate::contact::lamina::{line_hertz, tan0, Laminae, RollerLoad};
use crate::error::{Error, Result};
use crate::geometry::roller::{FlangeRing, RollerBearing};
use crate::seam::element::{ElementAt, ElementDisplacement, ElementLaw, ElementReaction, Want};

/// A massless roller with no lamina in contact and no flange contact (most of a ring's
/// rollers): `reaction`'s answer for the zero load, written out (the same bits: `-0.0` is
/// `-r.force`; the zeros of `df` and of the report are `reaction`'s up to their signs,
/// which no sum sees), at mid-length approach `approach`.
#[inline]
fn unloaded(approach: f64) -> ElementReaction {
    ElementReaction {
        f: [0.0, -0.0, 0.0],
        approach: approach.min(0.0),
        ..Default::default()
    }
}

/// A cylindrical roller's line contact, by laminae (module docs).
#[derive(Debug, Clone)]
pub struct CylindricalRollerLaw {
    laminae: Laminae,
    half_pd: f64,
    r_inner: f64,
    r_outer: f64,
    e_inner: f64,
    e_outer: f64,
    /// `F_c/omega²` (kg m): the roller's centrifugal force per squared shaft speed.
    fc_per_omega2: f64,
    /// The flange contact: series Hertz constant (N/m^1.5), inner flange contact radius (m),
    /// both directions (NUP) or `+z` only (NJ).
    flange: Option<(f64, f64, bool)>,
}

impl CylindricalRollerLaw {
    /// The law of the rollers of `b`; refuses a tapered bearing, naming `bearing.kind`.
    pub fn new(b: &RollerBearing) -> Result<Self> {
        if b.kind.is_tapered() {
            return Err(Error::invalid(
                "bearing.kind",
                "tapered",
                "nu, n, nj or nup: the cylindrical roller law; a tapered roller needs the cup/cone/flange equilibrium, not built yet",
            ));
        }
        Ok(CylindricalRollerLaw {
            laminae: b.laminae()?,
            half_pd: 0.5 * b.pd,
            r_inner: b.reduced_radius_inner(),
            r_outer: b.reduced_radius_outer(),
            e_inner: b.e_prime_inner(),
            e_outer: b.e_prime_outer(),
            flange: flange_contact(b)?,
            fc_per_omega2: centrifugal_per_omega2(b),
        })
    }

    /// The same law with massless rollers (no centrifugal force at any speed): the ring
    /// level's elements, massless as its balls are (docs/physics.md §5.1, §R9).
    pub fn massless(mut self) -> Self {
        self.fc_per_omega2 = 0.0;
        self
    }

    /// The roller's centrifugal force (N) at shaft speed `omega` (rad/s), outer ring fixed:
    /// `m (Dpw/2) (omega (1 - gamma)/2)²` (module docs).
    pub fn centrifugal_force(&self, omega: f64) -> f64 {
        self.fc_per_omega2 * omega * omega
    }

    /// The inner contacts' laminae at approach `approach` and `tan(tilt)` `t`, at speed.
    fn laminae_at(
        &self,
        approach: f64,
        t: f64,
        omega: f64,
        loads: Option<&mut [f64]>,
    ) -> RollerLoad {
        let f = self.centrifugal_force(omega) / self.laminae.len() as f64;
        self.laminae.eval_pressed(approach, t, f, loads)
    }

    /// Each lamina's inner contact load (N) into `loads` (length of the laminae) at `u` and
    /// shaft speed `omega` (rad/s); returns the roller's inner load (the outer one adds
    /// [`CylindricalRollerLaw::centrifugal_force`], evenly over the laminae).
    pub fn lamina_loads(&self, u: ElementDisplacement, omega: f64, loads: &mut [f64]) -> f64 {
        let approach = u.radial - self.half_pd;
        if omega == 0.0 || self.fc_per_omega2 == 0.0 {
            self.laminae.evaluate_into(approach, u.tilt, loads).force
        } else {
            assert_eq!(loads.len(), self.laminae.len(), "one load per lamina");
            self.laminae_at(approach, tan0(u.tilt), omega, Some(loads))
                .force
        }
    }

    /// The flange contact's series constant `K_f` (N/m^1.5): the axial load of an NJ/NUP roller
    /// is `K_f delta_f^1.5`; `None` for NU, N and flat roller ends.
    pub fn flange_constant(&self) -> Option<f64> {
        self.flange.map(|f| f.0)
    }

    /// The laminae it evaluates.
    pub fn laminae(&self) -> &Laminae {
        &self.laminae
    }
}

/// `m (Dpw/2) ((1 - gamma)/2)²`, kg m: the roller's centrifugal force per squared shaft
/// speed, outer ring fixed (module docs).
fn centrifugal_per_omega2(b: &RollerBearing) -> f64 {
    let ratio = crate::geometry::kinematics::cage_speed(b.gamma(), 1.0, 0.0);
    b.roller_mass() * 0.5 * b.dpw * ratio * ratio
}

/// The NJ/NUP flange contact of module docs: `(K_f, r_f, both ways)`, `None` without one.
fn flange_contact(b: &RollerBearing) -> Result<Option<(f64, f64, bool)>> {
    let has_end = b.flange.is_some_and(|f| f.roller_end_radius.is_some());
    if !b.kind.has_flange_contact() || !has_end {
        return Ok(None);
    }
    let ki = PointContact::try_new(b.flange_curvature(FlangeRing::Inner)?, b.e_prime_inner())?.kc;
    let ko = PointContact::try_new(b.flange_curvature(FlangeRing::Outer)?, b.e_prime_outer())?.kc;
    let rf = b.flange_contact_radius(FlangeRing::Inner).unwrap_or(0.0);
    Ok(Some((
        series_constant(ki, ko),
        rf,
        b.kind.axial_directions() == 2,
    )))
}

impl ElementLaw for CylindricalRollerLaw {
    fn name(&self) -> &'static str {
        "roller"
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
        let approach = u.radial - self.half_pd;
        let t = tan0(u.tilt);
        let massless = omega == 0.0 || self.fc_per_omega2 == 0.0;
        let r = if massless {
            self.laminae.evaluate_tan(approach, t)
        } else if omega.is_finite() {
            self.laminae_at(approach, t, omega, None)
        } else {
            return Err(Error::invalid(
                "omega",
                omega,
                "a finite shaft speed (rad/s)",
            ));
        };
        // At speed `q_max` is the largest inner lamina load: the approach is zero where the
        // inner contact closes, not where the roller starts pressing on the outer raceway
        // (compressed by `F_c` before, docs/physics.md §R9).
        let contact = self
            .laminae
            .contact_approach(&r, approach, massless && t == 0.0);
        Ok(self.reaction(r, u, t, contact, omega, want))
    }
}

impl CylindricalRollerLaw {
    /// [`ElementLaw::react`] of a massless roller ([`CylindricalRollerLaw::massless`]) at any
    /// speed, bit for bit, without the trait's dispatch and `Result` (the ring level's rollers
    /// call it for every element at every evaluation).
    #[inline(always)]
    pub fn react_massless(&self, u: ElementDisplacement, want: Want) -> ElementReaction {
        debug_assert!(self.fc_per_omega2 == 0.0, "massless rollers only");
        let approach = u.radial - self.half_pd;
        let t = tan0(u.tilt);
        // Without stiffness the laminae's derivatives are not read (`reaction`).
        let r = if want.stiffness {
            self.laminae.evaluate_tan(approach, t)
        } else {
            self.laminae.evaluate_tan_force(approach, t)
        };
        if r.loaded == 0 && self.flange.is_none() {
            return unloaded(approach);
        }
        // Massless: the report's centrifugal force is zero at any speed, as at rest.
        let contact = self.laminae.contact_approach(&r, approach, t == 0.0);
        self.reaction(r, u, t, contact, 0.0, want)
    }

    /// The reaction [`CylindricalRollerLaw::react_massless`] gives an aligned roller (tilt
    /// `±0`) at radial displacement `radial` when no lamina can touch there and there is no
    /// flange contact, found without evaluating a lamina (the same comparison on the same
    /// numbers); `None` when a lamina may touch. The ring level's test that skips such a
    /// roller.
    #[inline]
    pub(crate) fn aligned_untouched(&self, radial: f64) -> Option<ElementReaction> {
        let approach = radial - self.half_pd;
        (self.flange.is_none() && self.laminae.untouched(approach, 0.0)).then(|| unloaded(approach))
    }

    /// The reaction of a massless roller (the ring level's, [`CylindricalRollerLaw::massless`])
    /// whose laminae's approaches are moved by `offsets` (m, one per lamina: a race's
    /// waviness adds, a defect's depth loss subtracts; docs/physics.md §R12), with the lamina
    /// loads into `loads` when given. With every offset zero it equals
    /// [`ElementLaw::react`] to rounding (the aligned roller's mirrored pairs are summed
    /// lamina by lamina here); the ring level calls it only for a roller with an offset.
    pub fn react_offsets(
        &self,
        u: ElementDisplacement,
        offsets: &[f64],
        want: Want,
        loads: Option<&mut [f64]>,
    ) -> ElementReaction {
        debug_assert!(self.fc_per_omega2 == 0.0, "massless rollers only");
        let approach = u.radial - self.half_pd;
        let t = tan0(u.tilt);
        // Without stiffness the laminae's derivatives are not read (`reaction`).
        let r = if want.stiffness {
            self.laminae.evaluate_offsets(approach, t, offsets, loads)
        } else {
            self.laminae
                .evaluate_offsets_force(approach, t, offsets, loads)
        };
        let contact = self.laminae.contact_approach(&r, approach, false);
        self.reaction(r, u, t, contact, 0.0, want)
    }

    /// The element's reaction from the laminae's `r` at `u` (`t = tan(tilt)`, `approach` what
    /// contact damping ramps in with, [`Laminae::contact_approach`]), with the flange contact
    /// and the report.
    #[inline(always)]
    fn reaction(
        &self,
        r: RollerLoad,
        u: ElementDisplacement,
        t: f64,
        approach: f64,
        omega: f64,
        want: Want,
    ) -> ElementReaction {
        let sec2 = 1.0 + t * t;
        let mut out = ElementReaction {
            f: [0.0, -r.force, sec2 * r.moment],
            approach,
            ..Default::default()
        };
        if want.stiffness {
            out.df = [
                [0.0; 3],
                [0.0, -r.dforce_ddelta, -r.dforce_dtilt],
                [
                    0.0,
                    sec2 * r.dmoment_ddelta,
                    sec2 * r.dmoment_dtilt + 2.0 * t * sec2 * r.moment,
                ],
            ];
        }
        if let Some((kf, rf, both)) = self.flange {
            let a = u.axial + rf * u.tilt;
            let sgn = if both && a < 0.0 { -1.0 } else { 1.0 };
            let (qf, kq) = hertz_load_and_stiffness(kf, sgn * a);
            out.f[0] -= sgn * qf;
            out.f[2] -= sgn * rf * qf;
            if want.stiffness {
                // d(sgn a)/d(axial, radial, tilt) = sgn (1, 0, rf); sgn² = 1.
                out.df[0][0] -= kq;
                out.df[0][2] -= kq * rf;
                out.df[2][0] -= kq * rf;
                out.df[2][2] -= kq * rf * rf;
            }
        }
        if want.report {
            let w = self.laminae.width();
            // At speed every outer lamina carries F_c/ns more than its inner one.
            let fc = if omega == 0.0 {
                0.0
            } else {
                self.centrifugal_force(omega)
            };
            let fk = fc / self.laminae.len() as f64;
            out.load = [r.force, r.force + fc];
            out.pressure = [
                line_hertz(r.max_lamina / w, self.r_inner, self.e_inner).1,
                line_hertz((r.max_lamina + fk) / w, self.r_outer, self.e_outer).1,
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

    fn law(name: &str) -> (CylindricalRollerLaw, Vec<f64>) {
        let b = lookup(name).unwrap().build().unwrap();
        let psi = (0..b.z).map(|j| 2.0 * PI * j as f64 / b.z as f64).collect();
        (CylindricalRollerLaw::new(&b).unwrap(), psi)
    }

    fn sum(
        l: &CylindricalRollerLaw,
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

    #[test]
    fn ring_stiffness_is_minus_the_derivative_and_symmetric() {
        let (l, psi) = law("NU2206");
        // Radial displacement beyond the clearance plus a tilt of the ring.
        let q = [40e-6, -10e-6, 0.0, 4e-4, -2e-4];
        let mut k = [[0.0; 5]; 5];
        let f = sum(&l, &psi, &q, Some(&mut k));
        assert!(f[0] < 0.0, "the rollers push the shaft back: {f:?}");
        // The rollers resist a rotation of the ring.
        assert!(k[3][3] > 0.0 && k[4][4] > 0.0, "{k:?}");
        crate::contact::test_util::assert_k_matches_differences(
            &k,
            q,
            &[0, 1, 3, 4],
            |x| sum(&l, &psi, x, None),
            k[0][0].abs(),
            1e-4,
            1e-9,
        );
        // No axial stiffness: the law carries no axial load (NU).
        assert_eq!(k[2][2], 0.0);
    }

    #[test]
    fn a_tilted_ring_is_resisted_by_a_moment() {
        let (l, psi) = law("NU206");
        // Radial preload-like displacement so every roller is loaded, then rotate about y.
        let base = [0.0, 0.0, 0.0, 0.0, 0.0];
        let mut q = base;
        q[0] = 60e-6;
        let m0 = sum(&l, &psi, &q, None)[4];
        q[4] = 5e-4;
        let m1 = sum(&l, &psi, &q, None)[4];
        assert!(m1 < m0, "My {m0} -> {m1}: the rollers resist ry");
    }

    /// The ring level's direct call is the trait's answer, to the bit (forces, report; the
    /// stiffness by value, its zeros' signs aside): loaded and unloaded rollers, tilted and
    /// aligned, at rest and at speed (massless: speed changes nothing).
    #[test]
    fn react_massless_is_react_bit_for_bit() {
        let (l, _) = law("NU206");
        let l = l.massless();
        let want = Want {
            stiffness: true,
            report: true,
        };
        let at = ElementAt {
            index: 0,
            psi: 0.0,
            sc: (0.0, 1.0),
            q: &[0.0; 5],
        };
        for radial in [-30e-6, 0.0, 10e-6, 16.25e-6, 20e-6, 40e-6, 80e-6] {
            for tilt in [0.0, -0.0, 1e-4, -3e-4, 2e-3] {
                for omega in [0.0, 300.0] {
                    let u = ElementDisplacement {
                        axial: 1e-6,
                        radial,
                        tilt,
                    };
                    let a = l.react(at, u, omega, &mut [], want).unwrap();
                    let b = l.react_massless(u, want);
                    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&a.f), bits(&b.f), "{radial} {tilt}");
                    assert_eq!(bits(&a.load), bits(&b.load));
                    assert_eq!(bits(&a.pressure), bits(&b.pressure));
                    assert_eq!(a.approach.to_bits(), b.approach.to_bits());
                    assert_eq!(a.df, b.df);
                    // A right-hand side's call (no stiffness; with and without the report):
                    // the laminae without their derivatives, the same forces.
                    for report in [false, true] {
                        let w = Want {
                            stiffness: false,
                            report,
                        };
                        let a = l.react(at, u, omega, &mut [], w).unwrap();
                        let b = l.react_massless(u, w);
                        assert_eq!(bits(&a.f), bits(&b.f), "{radial} {tilt}");
                        assert_eq!(bits(&a.load), bits(&b.load));
                        assert_eq!(bits(&a.pressure), bits(&b.pressure));
                        assert_eq!(a.approach.to_bits(), b.approach.to_bits());
                    }
                }
            }
        }
    }

    #[test]
    fn report_gives_the_peak_pressures_and_tapered_is_refused() {
        let (l, _) = law("NU206");
        let at = ElementAt {
            index: 0,
            psi: 0.0,
            sc: (0.0, 1.0),
            q: &[0.0; 5],
        };
        let u = ElementDisplacement {
            axial: 0.0,
            radial: 40e-6,
            tilt: 0.0,
        };
        let want = Want {
            stiffness: false,
            report: true,
        };
        let r = l.react(at, u, 0.0, &mut [], want).unwrap();
        assert!(r.load[0] > 0.0 && r.load[0] == r.load[1] && r.load[0] == -r.f[1]);
        assert!(
            r.pressure[0] > r.pressure[1] && r.pressure[1] > 0.0,
            "{r:?}"
        );
        // At zero approach nothing, and no NaN.
        let u0 = ElementDisplacement { radial: 0.0, ..u };
        let r0 = l.react(at, u0, 0.0, &mut [], want).unwrap();
        assert_eq!(
            (r0.f, r0.load, r0.pressure),
            ([0.0, 0.0, 0.0], [0.0; 2], [0.0; 2])
        );
        let b = lookup("30206").unwrap().build().unwrap();
        let e = CylindricalRollerLaw::new(&b).unwrap_err().to_string();
        assert!(e.contains("bearing.kind") && e.contains("tapered"), "{e}");
    }

    fn rpm(n: f64) -> f64 {
        n * PI / 30.0
    }

    fn at0() -> ElementAt<'static> {
        ElementAt {
            index: 0,
            psi: 0.0,
            sc: (0.0, 1.0),
            q: &[0.0; 5],
        }
    }

    const REPORT: Want = Want {
        stiffness: true,
        report: true,
    };

    /// The ring level's massless rollers: at 20 000 rpm the reaction is the one at rest, bit
    /// for bit (no centrifugal force), while the law with inertia differs by its `F_c`.
    #[test]
    fn massless_rollers_ignore_the_speed() {
        let (l, _) = law("NU206");
        let m = l.clone().massless();
        let u = ElementDisplacement {
            axial: 0.0,
            radial: 40e-6,
            tilt: 2e-4,
        };
        let omega = 20_000.0 * std::f64::consts::PI / 30.0;
        let rest = l.react(at0(), u, 0.0, &mut [], REPORT).unwrap();
        let fast = m.react(at0(), u, omega, &mut [], REPORT).unwrap();
        assert_eq!(fast.f.map(f64::to_bits), rest.f.map(f64::to_bits));
        assert_eq!(fast.load.map(f64::to_bits), rest.load.map(f64::to_bits));
        let inertia = l.react(at0(), u, omega, &mut [], REPORT).unwrap();
        let fc = l.centrifugal_force(omega);
        assert!(fc > 70.0, "{fc}");
        assert!((inertia.load[1] - inertia.load[0] - fc).abs() < 1e-9 * fc);
    }

    /// At `omega == 0` (either sign of zero) the law is today's massless one, bit for bit: the
    /// reaction is the laminae's own evaluation; and the loaded solve at a zero outer force
    /// agrees with it to rounding (the Newton split lands on half the approach).
    #[test]
    fn at_rest_the_massless_law_is_unchanged() {
        let (l, _) = law("NU206");
        for (radial, tilt) in [(40e-6, 0.0), (35e-6, 3e-4), (10e-6, -1e-3), (0.0, 0.0)] {
            let u = ElementDisplacement {
                axial: 0.0,
                radial,
                tilt,
            };
            let lam = l.laminae();
            let e = lam.evaluate(radial - l.half_pd, tilt);
            let sec2 = 1.0 + tilt.tan() * tilt.tan();
            for omega in [0.0, -0.0] {
                let r = l.react(at0(), u, omega, &mut [], REPORT).unwrap();
                assert_eq!(r.f[1].to_bits(), (-e.force).to_bits());
                assert_eq!(r.f[2].to_bits(), (sec2 * e.moment).to_bits());
                assert_eq!(r.df[1][1].to_bits(), (-e.dforce_ddelta).to_bits());
                assert_eq!(r.load[0].to_bits(), r.load[1].to_bits());
            }
            let p = lam.eval_pressed(radial - l.half_pd, tilt.tan(), 0.0, None);
            for (a, b) in [
                (p.force, e.force),
                (p.moment, e.moment),
                (p.dforce_ddelta, e.dforce_ddelta),
                (p.dmoment_dtilt, e.dmoment_dtilt),
            ] {
                // (An aligned roller's moment is an exact zero in `evaluate`, rounding here.)
                let scale = b.abs() + e.force * lam.lwe;
                assert!((a - b).abs() <= 1e-13 * scale, "{a} vs {b}");
            }
        }
    }

    /// NU206 (catalogue: Dwe = 8.5 mm, Lw = 10.45 mm, Dpw = 46 mm, steel 7 850 kg/m³) at
    /// 10 000 rpm, by hand: m = 7850 π/4 (8.5e-3)² 10.45e-3 = 4.6549 g; gamma = 8.5/46 =
    /// 0.184783, omega_c = 1047.198 (1 - gamma)/2 = 426.847 rad/s; F_c = m (Dpw/2) omega_c²
    /// = 4.6549e-3 × 0.023 × 426.847² = 19.507 N. The outer contact carries the inner one's
    /// load plus F_c, lamina by lamina, and each lamina's two approaches add up to its own.
    #[test]
    fn at_speed_the_outer_contact_carries_the_centrifugal_force() {
        let b = lookup("NU206").unwrap().build().unwrap();
        let l = CylindricalRollerLaw::new(&b).unwrap();
        let omega = rpm(10_000.0);
        let fc = l.centrifugal_force(omega);
        assert!((fc / 19.507 - 1.0).abs() < 5e-5, "{fc}");
        let u = ElementDisplacement {
            axial: 0.0,
            radial: 30e-6,
            tilt: 5e-4,
        };
        let r0 = l.react(at0(), u, 0.0, &mut [], REPORT).unwrap();
        let r = l.react(at0(), u, omega, &mut [], REPORT).unwrap();
        assert!((r.load[1] - r.load[0] - fc).abs() < 1e-12 * r.load[1]);
        assert_eq!(r.load[0], -r.f[1]);
        // Pushed outward, the roller unloads its inner contact and loads its outer one.
        assert!(
            r.load[0] < r0.load[0] && r.load[1] > r0.load[1],
            "{r:?} {r0:?}"
        );
        assert!(r.pressure[0] < r0.pressure[0] && r.pressure[1] > r0.pressure[1]);
        let lam = l.laminae();
        let mut q = vec![0.0; lam.len()];
        let qi = l.lamina_loads(u, omega, &mut q);
        assert!((qi - r.load[0]).abs() < 1e-12 * qi);
        let fk = fc / lam.len() as f64;
        let half = |q: f64| 0.5 * (q / lam.cs).powf(0.9);
        for (k, &qk) in q.iter().enumerate() {
            let dk = u.radial - l.half_pd - lam.x[k] * u.tilt.tan() - lam.drop2[k];
            if qk > 0.0 {
                let sum = half(qk) + half(qk + fk);
                assert!((sum - dk).abs() < 1e-12 * dk, "lamina {k}: {sum} vs {dk}");
            } else {
                // Open inner contact: the approach does not reach the outer one's at F_c/ns.
                assert!(dk <= 2.0 * half(fk) * (1.0 + 1e-12), "lamina {k}");
            }
        }
    }

    /// At speed the ring stiffness still is `-dF/dq` (central differences) and symmetric, and
    /// at 20 000 rpm every answer is finite, loaded or not.
    #[test]
    fn at_speed_the_stiffness_is_the_derivative_and_all_is_finite() {
        let (l, psi) = law("NU206");
        let omega = rpm(10_000.0);
        let want = Want {
            stiffness: true,
            report: false,
        };
        let sum_w = |q: &[f64; 5], w: f64, k: Option<&mut [[f64; 5]; 5]>| {
            assemble(q, &psi, 0.0, k, |_, at, u| l.react(at, u, w, &mut [], want)).unwrap()
        };
        let q = [40e-6, -10e-6, 0.0, 4e-4, -2e-4];
        let mut k = [[0.0; 5]; 5];
        let f = sum_w(&q, omega, Some(&mut k));
        let f0 = sum_w(&q, 0.0, None);
        assert!(
            f[0] < 0.0 && f[0] > f0[0],
            "less load reaches the shaft: {f:?} {f0:?}"
        );
        crate::contact::test_util::assert_k_matches_differences(
            &k,
            q,
            &[0, 1, 3, 4],
            |x| sum_w(x, omega, None),
            k[0][0].abs(),
            1e-4,
            1e-9,
        );
        let fast = rpm(20_000.0);
        for q in [
            [0.0; 5],
            [1e-6, 0.0, 0.0, 0.0, 0.0],
            [80e-6, 20e-6, 0.0, 2e-3, -1e-3],
        ] {
            let mut k = [[0.0; 5]; 5];
            let f = sum_w(&q, fast, Some(&mut k));
            assert!(f.iter().chain(k.iter().flatten()).all(|v| v.is_finite()));
        }
        let u = ElementDisplacement::default();
        let r = l.react(at0(), u, fast, &mut [], REPORT).unwrap();
        assert_eq!(r.load[0], 0.0);
        assert!((r.load[1] - l.centrifugal_force(fast)).abs() < 1e-12 * r.load[1]);
        assert!(r.pressure[1] > 0.0 && r.pressure[1].is_finite());
        let e = l.react(at0(), u, f64::NAN, &mut [], REPORT).unwrap_err();
        assert!(e.to_string().contains("omega"), "{e}");
    }

    fn with_ends(name: &str) -> RollerBearing {
        let mut s = lookup(name).unwrap();
        s.flange.roller_end_radius_mm = Some(4.0 * s.roller_diameter_mm);
        s.build().unwrap()
    }

    /// NJ: an axial displacement `z` toward the flange loads every roller's flange contact
    /// with `K_f z^1.5`, `K_f` the series Hertz constant of the inner and outer flange point
    /// contacts (computed here from `contact::hertz`); the other way nothing. NUP: both ways.
    /// NU: no axial force and an exact zero axial stiffness, finite everywhere.
    #[test]
    fn nj_and_nup_flanges_carry_the_axial_load() {
        let z: f64 = 5e-6;
        let q = |z: f64| [0.0, 0.0, z, 0.0, 0.0];
        for (name, both) in [("NJ206", false), ("NUP206", true)] {
            let b = with_ends(name);
            let l = CylindricalRollerLaw::new(&b).unwrap();
            let psi: Vec<f64> = (0..b.z).map(|j| 2.0 * PI * j as f64 / b.z as f64).collect();
            let ki = PointContact::new(
                b.flange_curvature(FlangeRing::Inner).unwrap(),
                b.e_prime_inner(),
            )
            .kc;
            let ko = PointContact::new(
                b.flange_curvature(FlangeRing::Outer).unwrap(),
                b.e_prime_outer(),
            )
            .kc;
            let kf = (ki.powf(-2.0 / 3.0) + ko.powf(-2.0 / 3.0)).powf(-1.5);
            assert!((l.flange_constant().unwrap() / kf - 1.0).abs() < 1e-12);
            let want = b.z as f64 * kf * z.powf(1.5);
            let mut k = [[0.0; 5]; 5];
            let f = sum(&l, &psi, &q(z), Some(&mut k));
            assert!(
                (f[2] + want).abs() < 1e-9 * want,
                "{name}: {} vs {want}",
                f[2]
            );
            assert!((k[2][2] - 1.5 * want / z).abs() < 1e-9 * k[2][2], "{name}");
            let back = sum(&l, &psi, &q(-z), None)[2];
            if both {
                assert!((back - want).abs() < 1e-9 * want, "{name}: {back}");
            } else {
                assert_eq!(back, 0.0, "{name}");
            }
            // The flange's moment arm: K by central differences in z and the tilts.
            let q0 = [20e-6, 0.0, z, 1e-4, -5e-5];
            let mut k = [[0.0; 5]; 5];
            sum(&l, &psi, &q0, Some(&mut k));
            for col in [2, 3, 4] {
                let h = if col < 3 { 1e-10 } else { 1e-8 };
                let (mut qp, mut qm) = (q0, q0);
                qp[col] += h;
                qm[col] -= h;
                let (fp, fm) = (sum(&l, &psi, &qp, None), sum(&l, &psi, &qm, None));
                for row in [2, 3, 4] {
                    let fd = -(fp[row] - fm[row]) / (2.0 * h);
                    let scale = k[2][2].abs() * if row > 2 || col > 2 { 1e-3 } else { 1.0 };
                    assert!(
                        (k[row][col] - fd).abs() < 1e-5 * scale,
                        "{name} K[{row}][{col}]"
                    );
                }
            }
        }
        let (l, psi) = law("NU206");
        let mut k = [[0.0; 5]; 5];
        let f = sum(&l, &psi, &[30e-6, 0.0, 1e-3, 0.0, 0.0], Some(&mut k));
        assert!(f.iter().all(|v| v.is_finite()) && f[2] == 0.0 && k[2][2] == 0.0);
        assert!(l.flange_constant().is_none());
        // An NJ with flat roller ends carries no axial load (no point contact to model).
        let nj_flat =
            CylindricalRollerLaw::new(&lookup("NJ206").unwrap().build().unwrap()).unwrap();
        assert!(nj_flat.flange_constant().is_none());
    }
}
