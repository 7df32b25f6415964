//! The ring level for a rolling element with its own contact law (rollers, through
//! [`crate::seam::element::ElementLaw`]): rigid rings on massless elements at the cage's
//! kinematic positions, summed by [`assemble_sc`], with contact damping `c d(delta)/dt` per
//! loaded element along its radial line (the element's approach rate from the ring's radial
//! motion at the element, including the element's travel with the cage), blended in over
//! the first [`DAMPING_RAMP`] of approach as for balls (docs/physics.md §5.1): the approach
//! the law reports ([`ElementReaction::approach`]), a roller's at its most compressed lamina's
//! contact (an edge-loaded roller is damped from its first lamina's touch; at speed from the
//! inner contact's closing, docs/physics.md §R9). The ball
//! bearing's ring level keeps its own inlined Hertz loop (`RingModel`): the same law,
//! specialised for the speed rows of the straight-through and coupling jobs.
//!
//! With 5 DOF the damping spreads evenly along a roller's contact line, so the tilt rate
//! `w` at the element meets the moment `-c L²/12 w` ([`ElementLaw::tilt_damping_arm2`]).
//!
//! Defects and waviness on a cylindrical roller bearing, and cup and cone defects and waviness
//! on a tapered one, act per lamina ([`super::roller_effects`], docs/physics.md §R12): a roller with an
//! offset on some lamina runs [`CylindricalRollerLaw::react_offsets`] (or
//! [`TaperedRollerLaw::react_offsets`]), every other roller the plain law, so a scene whose
//! effects add nothing (a defect of zero depth, say) runs the healthy arithmetic bit for bit.
//! Not modelled here yet: the other effects (spacing, film, wear, thermal; a tapered roller's
//! own defects and waviness), refused by name; damping of the axial motion (cylindrical
//! rollers carry no axial load).

use super::roller_effects::RollerEffects;
use super::{RingDof, DAMPING_RAMP};
use crate::contact::roller_law::CylindricalRollerLaw;
use crate::contact::tapered_law::TaperedRollerLaw;
use crate::error::{Error, Result};
use crate::geometry::element::Element;
use crate::geometry::kinematics::nominal_cage_speed as cage_speed;
use crate::models::effects::Effects;
use crate::models::LevelArgs;
use crate::seam::element::{
    assemble_sc, even_base, place_evenly_sc, ElementDisplacement, ElementLaw, ElementLoad,
    ElementReaction, Want,
};
use crate::seam::{LevelModel, LevelOutputs, Motion, Point};

/// The stiffness and damping matrices an evaluation fills.
type Matrices<'a> = (&'a mut [[f64; 5]; 5], &'a mut [[f64; 5]; 5]);

/// The level.
#[derive(Debug)]
pub struct LawRingLevel {
    law: Box<dyn ElementLaw>,
    dof: RingDof,
    damping: f64,
    cage_ratio: f64,
    psi: Vec<f64>,
    /// `(sin, cos)` of `psi`, and of the element spacing (`even_base`).
    sc: Vec<(f64, f64)>,
    base: Vec<(f64, f64)>,
    /// Defects and waviness (None: none, nothing evaluated).
    profiled: Option<Profiled>,
    /// The massless cylindrical roller law itself when `law` is one
    /// ([`LawRingLevel::massless_cylindrical`]): called directly, not through the trait.
    cylindrical: Option<CylindricalRollerLaw>,
    /// The elements' loads of the last outputs, when asked to keep them
    /// ([`LevelModel::keep_element_loads`]; `None`: nothing stored).
    loads: Option<Vec<ElementLoad>>,
    /// Every evaluation through the general sum (the reference of
    /// [`LawRingLevel::aligned_two`]'s test).
    general_only: bool,
}

/// A roller bearing's per-lamina effects: the massless law that takes offsets, the compiled
/// effects and one roller's offsets (set up once: an evaluation allocates nothing).
#[derive(Debug)]
struct Profiled {
    law: OffsetLaw,
    fx: RollerEffects,
    offsets: Vec<f64>,
}

/// The massless roller law of a bearing with per-lamina effects.
#[derive(Debug)]
enum OffsetLaw {
    Cylindrical(CylindricalRollerLaw),
    Tapered(TaperedRollerLaw),
}

impl OffsetLaw {
    fn react_offsets(
        &self,
        u: ElementDisplacement,
        offsets: &[f64],
        want: Want,
    ) -> ElementReaction {
        match self {
            OffsetLaw::Cylindrical(l) => l.react_offsets(u, offsets, want, None),
            OffsetLaw::Tapered(l) => l.react_offsets(u, offsets, want, None),
        }
    }
}

impl LawRingLevel {
    /// The ring level of `a`'s bearing with the element law `law`: a cylindrical roller
    /// bearing takes defects and waviness (module docs); other effects, and any on another
    /// element, are refused naming them.
    pub fn new(a: &LevelArgs, law: Box<dyn ElementLaw>, dof: RingDof) -> Result<Self> {
        let profiled = if *a.effects == Effects::default() {
            None
        } else if let Element::Roller(r) = &a.bearing.element {
            // Lamina positions along +z: a tapered roller's along the raceway generatrix.
            let (law, x) = if r.kind.is_tapered() {
                let law = TaperedRollerLaw::new(r)?.massless();
                let x = law.generatrix_positions();
                (OffsetLaw::Tapered(law), x)
            } else {
                let law = CylindricalRollerLaw::new(r)?.massless();
                let x = law.laminae().x.clone();
                (OffsetLaw::Cylindrical(law), x)
            };
            Some(Profiled {
                fx: RollerEffects::new(a.effects, a.bearing, &x)?,
                offsets: vec![0.0; x.len()],
                law,
            })
        } else {
            return Err(Error::invalid(
                "effects",
                format!("effects on a {} bearing", law.name()),
                format!(
                    "none: the ring level on massless {} elements models no effects",
                    law.name()
                ),
            ));
        };
        Ok(LawRingLevel {
            law,
            dof,
            damping: a.contact_damping,
            cage_ratio: cage_speed(a.bearing, 1.0),
            psi: vec![0.0; a.bearing.z],
            sc: vec![(0.0, 1.0); a.bearing.z],
            base: even_base(a.bearing.z),
            profiled,
            cylindrical: None,
            loads: None,
            general_only: false,
        })
    }

    /// The same level told that its law is the massless cylindrical roller law of `a`'s
    /// bearing (the ring level's, `contact::roller_law(r, false)`): it calls
    /// [`CylindricalRollerLaw::react_massless`] directly, the same arithmetic without the
    /// dispatch. Other bearings are left as they are.
    pub fn massless_cylindrical(mut self, a: &LevelArgs) -> Result<Self> {
        if let Element::Roller(r) = &a.bearing.element {
            if !r.kind.is_tapered() {
                self.cylindrical = Some(CylindricalRollerLaw::new(r)?.massless());
            }
        }
        Ok(self)
    }

    /// Wrench on the shaft at `p` (and with `kc` the stiffness and damping matrices, the
    /// report of each element to `element(j, psi, reaction)`).
    fn evaluate(
        &mut self,
        p: Point<'_>,
        mut kc: Option<Matrices<'_>>,
        report: &mut (usize, f64, f64),
        mut element: impl FnMut(usize, f64, &ElementReaction),
    ) -> Result<[f64; 5]> {
        let Point { m, x, .. } = p;
        place_evenly_sc(&mut self.psi, &mut self.sc, &self.base, x[0]);
        let wc = self.cage_ratio * m.omega;
        let want = Want {
            stiffness: kc.is_some(),
            report: kc.is_some(),
        };
        // The shaft has turned by the cage angle over the cage ratio (both start at 0).
        let theta_s = x[0] / self.cage_ratio;
        if let Some(w) = self.aligned_two(m, theta_s, &mut kc, want, report, &mut element) {
            return Ok(w);
        }
        let mut profiled = self.profiled.as_mut();
        let cylindrical = self.cylindrical.as_ref();
        let (law, c0, jac) = (&self.law, self.damping, kc.is_some());
        let arm2 = if self.dof == RingDof::Five {
            law.tilt_damping_arm2()
        } else {
            0.0
        };
        let mut cmat = [[0.0; 5]; 5];
        let mut w = assemble_sc(
            &m.q,
            &self.psi,
            &self.sc,
            law.moment_arm(),
            kc.as_mut().map(|(k, _)| &mut **k),
            |j, at, u| {
                let pf = profiled.as_deref_mut().and_then(|pf| {
                    let any = pf.fx.offsets_sc(j, at.psi, at.sc, theta_s, &mut pf.offsets);
                    any.then_some(&*pf)
                });
                let mut r = match (pf, cylindrical) {
                    (Some(pf), _) => pf.law.react_offsets(u, &pf.offsets, want),
                    (None, Some(cl)) => cl.react_massless(u, want),
                    (None, None) => law.react(at, u, m.omega, &mut [], want)?,
                };
                let d = Damping {
                    c0,
                    wc,
                    arm2,
                    jac,
                    report: want.report,
                };
                settle(
                    &mut r,
                    j,
                    at.psi,
                    at.sc,
                    m,
                    d,
                    report,
                    &mut element,
                    &mut cmat,
                );
                Ok(r)
            },
        )?;
        if self.dof == RingDof::Two {
            w[2..].fill(0.0);
        }
        if let Some((k, c)) = kc {
            if self.dof == RingDof::Two {
                for (i, row) in k.iter_mut().enumerate() {
                    for (j, v) in row.iter_mut().enumerate() {
                        if i >= 2 || j >= 2 {
                            *v = 0.0;
                        }
                    }
                }
            }
            *c = cmat;
        }
        Ok(w)
    }

    /// [`LawRingLevel::evaluate`] of the common case it is timed on: a 2-DOF ring on massless
    /// cylindrical rollers without flange contact (with or without defects and waviness), the
    /// ring not tilted (`rx = ry = 0`, so every roller is aligned) and its displacement
    /// finite; the shaft turned by `theta_s` (rad). `None` in any other case (the general sum
    /// then runs). The same numbers bit for bit as the general sum ([`assemble_sc`] over
    /// [`CylindricalRollerLaw::react_massless`], or [`CylindricalRollerLaw::react_offsets`]
    /// for a roller with an offset): a roller without an offset no lamina of which can touch
    /// ([`CylindricalRollerLaw::aligned_untouched`]) would give the zero reaction, whose `±0`
    /// forces add no bit to the sums and which adds nothing to `K`, so it is reported to
    /// `element` and skipped; any other roller's reaction is the law's own, damped and
    /// reported as there, its radial force summed into `(Fx, Fy)` in the same order and its
    /// radial stiffness into the 2×2 block of `K` by the same products (the other entries,
    /// and `Fz, Mx, My`, among them a defective roller's moment and its cross terms, are the
    /// zeros the 2-DOF ring keeps).
    #[inline]
    fn aligned_two(
        &mut self,
        m: &Motion,
        theta_s: f64,
        kc: &mut Option<Matrices<'_>>,
        want: Want,
        report: &mut (usize, f64, f64),
        element: &mut impl FnMut(usize, f64, &ElementReaction),
    ) -> Option<[f64; 5]> {
        let cl = self.cylindrical.as_ref()?;
        let q = &m.q;
        // Per-lamina effects through the cylindrical law that takes offsets (a cylindrical
        // bearing's: `cylindrical` is set for those only).
        let mut profiled = match self.profiled.as_mut() {
            None => None,
            Some(pf) => match &pf.law {
                OffsetLaw::Cylindrical(l) => Some((l, &pf.fx, &mut pf.offsets)),
                OffsetLaw::Tapered(_) => return None,
            },
        };
        if self.dof != RingDof::Two
            || self.general_only
            || q[3] != 0.0
            || q[4] != 0.0
            || !q.iter().all(|v| v.is_finite())
            || self.law.moment_arm() != 0.0
        {
            return None;
        }
        let d = Damping {
            c0: self.damping,
            wc: self.cage_ratio * m.omega,
            arm2: 0.0,
            jac: kc.is_some(),
            report: want.report,
        };
        let mut cmat = [[0.0; 5]; 5];
        let mut k2 = [[0.0; 2]; 2];
        let mut f = [0.0; 2];
        for (j, (&psi, &(s, c))) in self.psi.iter().zip(&self.sc).enumerate() {
            if !psi.is_finite() {
                return None;
            }
            let offsets = profiled.as_mut().and_then(|(l, fx, o)| {
                fx.offsets_sc(j, psi, (s, c), theta_s, o)
                    .then_some((*l, &**o))
            });
            let mut r = match offsets {
                Some((l, o)) => l.react_offsets(ElementDisplacement::at(q, s, c), o, want, None),
                None => {
                    if let Some(r) = cl.aligned_untouched(q[0] * c + q[1] * s) {
                        element(j, psi, &r);
                        continue;
                    }
                    cl.react_massless(ElementDisplacement::at(q, s, c), want)
                }
            };
            settle(&mut r, j, psi, (s, c), m, d, report, element, &mut cmat);
            let fr = r.f[1];
            f[0] += fr * c;
            f[1] += fr * s;
            if want.stiffness && r.df != [[0.0; 3]; 3] {
                let dr = r.df[1][1];
                let (rc, rs) = (dr * c, dr * s);
                k2[0][0] -= rc * c;
                k2[0][1] -= rc * s;
                k2[1][0] -= rs * c;
                k2[1][1] -= rs * s;
            }
        }
        if !(f[0].is_finite() && f[1].is_finite()) {
            // The general sum names the failure.
            return None;
        }
        if let Some((k, c)) = kc {
            **k = [[0.0; 5]; 5];
            k[0][..2].copy_from_slice(&k2[0]);
            k[1][..2].copy_from_slice(&k2[1]);
            **c = cmat;
        }
        Some([f[0], f[1], 0.0, 0.0, 0.0])
    }
}

/// What [`settle`] damps an element with: the contact damping `c0`, the cage speed `wc`, the
/// tilt damping's squared arm `arm2` (0: none) and whether the damping matrix is wanted;
/// and whether the report is (a right-hand side's evaluation reads none).
#[derive(Debug, Clone, Copy)]
struct Damping {
    c0: f64,
    wc: f64,
    arm2: f64,
    jac: bool,
    report: bool,
}

/// One element's reaction `r` at azimuth `psi` (`(sin, cos)` = `sc`) finished as the ring
/// level sums it: counted into `report` (loaded elements, largest load and pressure; when
/// `d.report`), handed
/// to `element`, then damped along its radial line (and tilt) with the damping matrix into
/// `cmat` (module docs).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn settle(
    r: &mut ElementReaction,
    j: usize,
    psi: f64,
    sc: (f64, f64),
    m: &Motion,
    d: Damping,
    report: &mut (usize, f64, f64),
    element: &mut impl FnMut(usize, f64, &ElementReaction),
    cmat: &mut [[f64; 5]; 5],
) {
    if d.report && r.f[1] < 0.0 {
        report.0 += 1;
        report.1 = report.1.max(r.load[0]).max(r.load[1]);
        report.2 = report.2.max(r.pressure[0]).max(r.pressure[1]);
    }
    element(j, psi, r);
    // The element's contact approach (the roller laws': its most compressed lamina's, the
    // inner contact's at speed), positive exactly while it touches.
    if d.c0 > 0.0 && r.approach > 0.0 {
        let (s, c) = sc;
        let (q, v, wc) = (&m.q, &m.v, d.wc);
        let rate = v[0] * c + v[1] * s + wc * (-q[0] * s + q[1] * c);
        let cd = d.c0 * (r.approach / DAMPING_RAMP).min(1.0);
        r.f[1] -= cd * rate;
        if d.jac {
            add_outer(cmat, 0, [c, s], cd);
        }
        if d.arm2 > 0.0 {
            // The tilt about the element's tangential axis, `rx s - ry c`, and its
            // rate as the element travels with the cage.
            let wt = v[3] * s - v[4] * c + wc * (q[3] * c + q[4] * s);
            let ct = cd * d.arm2;
            r.f[2] -= ct * wt;
            if d.jac {
                add_outer(cmat, 3, [s, -c], ct);
            }
        }
    }
}

/// `m[o + a][o + b] += k g_a g_b`: a damper `k` along the unit direction `g` of the two
/// coordinates from `o` (x, y or rx, ry).
fn add_outer(m: &mut [[f64; 5]; 5], o: usize, g: [f64; 2], k: f64) {
    for (a, ga) in g.iter().enumerate() {
        for (b, gb) in g.iter().enumerate() {
            m[o + a][o + b] += k * ga * gb;
        }
    }
}

impl LevelModel for LawRingLevel {
    fn n_states(&self) -> usize {
        1
    }
    fn states_are_quadrature(&self) -> bool {
        true
    }
    fn ring_dofs(&self) -> &'static [usize] {
        match self.dof {
            RingDof::Two => &[0, 1],
            RingDof::Five => &[0, 1, 2, 3, 4],
        }
    }
    fn init(&mut self, _m: &crate::seam::Motion, x: &mut [f64], _aux: &mut [f64]) -> Result<()> {
        x[0] = 0.0;
        Ok(())
    }
    fn rhs(&mut self, p: Point<'_>, dx: &mut [f64], wrench: Option<&mut [f64; 5]>) -> Result<()> {
        dx[0] = self.cage_ratio * p.m.omega;
        if let Some(w) = wrench {
            *w = self.evaluate(p, None, &mut (0, 0.0, 0.0), |_, _, _| {})?;
        }
        Ok(())
    }
    fn keep_element_loads(&mut self) -> bool {
        self.loads = Some(vec![ElementLoad::default(); self.psi.len()]);
        true
    }
    fn element_loads(&self, out: &mut Vec<ElementLoad>) -> bool {
        out.clear();
        out.extend(self.loads.iter().flatten());
        self.loads.is_some()
    }
    fn outputs(&mut self, p: Point<'_>, out: &mut LevelOutputs) -> Result<()> {
        let omega = p.m.omega;
        let (mut k, mut c) = ([[0.0; 5]; 5], [[0.0; 5]; 5]);
        let mut report = (0, 0.0, 0.0);
        let kc = Some((&mut k, &mut c));
        // A roller's loads are its laminae's sums ([`ElementReaction::load`]).
        let wrench = match self.loads.take() {
            None => self.evaluate(p, kc, &mut report, |_, _, _| {}),
            Some(mut loads) => {
                let w = self.evaluate(p, kc, &mut report, |j, psi, r| {
                    loads[j] = ElementLoad {
                        psi,
                        inner: r.load[0],
                        outer: r.load[1],
                    }
                });
                self.loads = Some(loads);
                w
            }
        }?;
        *out = LevelOutputs {
            wrench,
            k,
            c,
            cage_omega: self.cage_ratio * omega,
            balls_loaded: report.0 as f64,
            max_load: report.1,
            max_pressure: report.2,
            ..LevelOutputs::default()
        };
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::component::Scene;

    /// The bench's ring: NU206, 2 DOF, with contact damping (`damping` N s/m) and the
    /// `[effects]` table `effects` (TOML; empty: none).
    fn level(damping: f64, general: bool, effects: &str) -> LawRingLevel {
        let text = format!(
            "bearing = \"NU206\"\n[model]\nlevel = \"ring\"\ncausality = \"motion\"\n\
             ring_dof = 2\ncontact_damping = {damping:?}\n[effects]\n{effects}\n"
        );
        let scene = Scene::from_text(&text).unwrap();
        let b = scene.build_bearing().unwrap();
        let a = scene.level_args(&b);
        let opts = crate::models::quasi_static::Options {
            race_control: a.race_control,
            ..Default::default()
        };
        let law = crate::models::quasi_static::level::element_law(&a, opts, false).unwrap();
        let mut l = LawRingLevel::new(&a, law, RingDof::Two)
            .unwrap()
            .massless_cylindrical(&a)
            .unwrap();
        l.general_only = general;
        l.keep_element_loads();
        l
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    /// The shipped scene's outer-race spall (`nu206-outer-defect.toml`: 20 µm deep, 1 mm
    /// wide, over the `+z` half of the raceway at 270°) and an inner-race one over the `-z`
    /// half.
    const DEFECTS: &str = "defects = [\
        { race = \"outer\", angle_deg = 270.0, width_mm = 1.0, depth_um = 20.0, axial_width_mm = 4.8, axial_position_mm = 2.4 },\
        { race = \"inner\", angle_deg = 100.0, width_mm = 0.8, depth_um = 10.0, axial_width_mm = 3.0, axial_position_mm = -2.0 }]";

    /// Race waviness on both rings.
    const WAVES: &str =
        "waviness = [{ race = \"outer\", order = 14, amplitude_um = 0.3, phase_deg = 0.0 },\
        { race = \"inner\", order = 15, amplitude_um = 0.2, phase_deg = 30.0 }]";

    #[test]
    fn aligned_two_dof_is_the_general_sum_bit_for_bit() {
        assert_eq!(aligned_two_matches_the_general_sum("", &[0.0, 0.37]), 0);
    }

    /// With defects (`DEFECTS`): the same, at cage angles that put a roller on the outer
    /// spall's entry, floor and exit (the spall spans ±18 mrad of azimuth around 270°; roller
    /// 0 sits at the cage angle) and on the inner one, so rollers with and without offsets
    /// are summed in one evaluation; with waviness (every roller has an offset), alone and
    /// with the defects.
    #[test]
    fn aligned_two_dof_with_effects_is_the_general_sum_bit_for_bit() {
        let on = 1.5 * std::f64::consts::PI;
        let thetas = [
            on,
            on - 0.015,
            on - 0.008,
            on + 0.004,
            on + 0.016,
            0.37,
            2.1,
        ];
        // Rollers evaluated: 14 per evaluation, at 7 positions, 2 zero tilts, 2 dampings.
        let per_theta = 14 * 7 * 2 * 2;
        let z = per_theta * (thetas.len() + 1);
        let n = aligned_two_matches_the_general_sum(DEFECTS, &thetas);
        assert!(
            n >= 28 * 5 && n < z / 4,
            "{n} of {z} rollers with an offset"
        );
        let n = aligned_two_matches_the_general_sum(WAVES, &[0.0, 0.37]);
        assert_eq!(n, per_theta * 3);
        let both = format!("{DEFECTS}\n{WAVES}");
        aligned_two_matches_the_general_sum(&both, &thetas);
    }

    /// Asserts the fast path's outputs, loads and right-hand side are the general sum's bit
    /// for bit at several ring positions and cage angles `thetas` (and one more), both with
    /// and without damping; returns how many rollers the fast path met with an offset.
    fn aligned_two_matches_the_general_sum(effects: &str, thetas: &[f64]) -> usize {
        let mut offset_rollers = 0;
        for damping in [0.0, 2e3] {
            let (mut fast, mut general) = (
                level(damping, false, effects),
                level(damping, true, effects),
            );
            let mut taken = 0;
            for (i, &(x, y)) in [
                (0.0, -30e-6),
                (1e-6, -31e-6),
                (-7e-6, 12e-6),
                (20e-6, 20e-6),
                (0.0, 0.0),
                (-40e-6, -3e-6),
                (3e-7, -18.3e-6),
            ]
            .iter()
            .enumerate()
            {
                let spins = thetas.iter().map(|&t| (t, 157.0));
                for (theta, omega) in spins.chain([(5.1 + i as f64, -80.0)]) {
                    for q3 in [0.0, -0.0, 1e-4] {
                        let m = Motion {
                            q: [x, y, 2e-6, q3, 0.0],
                            v: [1e-3, -2e-3, 0.0, 0.0, 0.0],
                            omega,
                        };
                        let xs = [theta];
                        let (mut oa, mut ob) = (LevelOutputs::default(), LevelOutputs::default());
                        fast.outputs(Point::new(0.0, &m, &xs, &mut []), &mut oa)
                            .unwrap();
                        general
                            .outputs(Point::new(0.0, &m, &xs, &mut []), &mut ob)
                            .unwrap();
                        assert_eq!(bits(&oa.wrench), bits(&ob.wrench), "{x} {y} {theta}");
                        assert_eq!(bits(oa.k.as_flattened()), bits(ob.k.as_flattened()));
                        assert_eq!(bits(oa.c.as_flattened()), bits(ob.c.as_flattened()));
                        let rep = |o: &LevelOutputs| {
                            bits(&[o.balls_loaded, o.max_load, o.max_pressure, o.cage_omega])
                        };
                        assert_eq!(rep(&oa), rep(&ob));
                        let (mut la, mut lb) = (Vec::new(), Vec::new());
                        assert!(fast.element_loads(&mut la) && general.element_loads(&mut lb));
                        let flat = |l: &[ElementLoad]| {
                            bits(
                                &l.iter()
                                    .flat_map(|e| [e.psi, e.inner, e.outer])
                                    .collect::<Vec<_>>(),
                            )
                        };
                        assert_eq!(flat(&la), flat(&lb));
                        let (mut wa, mut wb) = ([0.0; 5], [0.0; 5]);
                        let mut dx = [0.0];
                        fast.rhs(Point::new(0.0, &m, &xs, &mut []), &mut dx, Some(&mut wa))
                            .unwrap();
                        general
                            .rhs(Point::new(0.0, &m, &xs, &mut []), &mut dx, Some(&mut wb))
                            .unwrap();
                        assert_eq!(bits(&wa), bits(&wb));
                        if q3 == 0.0 {
                            assert!(oa.balls_loaded > 0.0 || y > -1e-6 || damping > 0.0);
                            taken += 1;
                            if let Some(pf) = fast.profiled.as_mut() {
                                let ts = theta / fast.cage_ratio;
                                offset_rollers += (0..fast.psi.len())
                                    .filter(|&j| pf.fx.offsets(j, fast.psi[j], ts, &mut pf.offsets))
                                    .count();
                            }
                            let mut none = None;
                            let w = fast.aligned_two(
                                &m,
                                theta / fast.cage_ratio,
                                &mut none,
                                Want::default(),
                                &mut (0, 0.0, 0.0),
                                &mut |_, _, _| {},
                            );
                            assert_eq!(w.map(|w| bits(&w)), Some(bits(&wa)));
                        }
                    }
                }
            }
            assert!(taken > 0);
        }
        offset_rollers
    }
}
