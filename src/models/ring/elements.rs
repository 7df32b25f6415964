//! The ring level for a rolling element with its own contact law (rollers, through
//! [`crate::seam::element::ElementLaw`]): rigid rings on massless elements at the cage's
//! kinematic positions, summed by [`assemble_sc`], with contact damping `c d(delta)/dt` per
//! loaded element along its radial line (the element's approach rate from the ring's radial
//! motion at the element, including the element's travel with the cage), blended in over
//! the first [`DAMPING_RAMP`] of approach as for balls (docs/physics.md §5.1). The ball
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
use crate::seam::{LevelModel, LevelOutputs, Point};

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
                    let any = pf.fx.offsets(j, at.psi, theta_s, &mut pf.offsets);
                    any.then_some(&*pf)
                });
                let mut r = match (pf, cylindrical) {
                    (Some(pf), _) => pf.law.react_offsets(u, &pf.offsets, want),
                    (None, Some(cl)) => cl.react_massless(u, want),
                    (None, None) => law.react(at, u, m.omega, &mut [], want)?,
                };
                if r.f[1] < 0.0 {
                    report.0 += 1;
                    report.1 = report.1.max(r.load[0]).max(r.load[1]);
                    report.2 = report.2.max(r.pressure[0]).max(r.pressure[1]);
                }
                element(j, at.psi, &r);
                if c0 > 0.0 && r.f[1] < 0.0 && r.approach > 0.0 {
                    let (s, c) = at.sc;
                    let (q, v) = (&m.q, &m.v);
                    let rate = v[0] * c + v[1] * s + wc * (-q[0] * s + q[1] * c);
                    let cd = c0 * (r.approach / DAMPING_RAMP).min(1.0);
                    r.f[1] -= cd * rate;
                    if jac {
                        add_outer(&mut cmat, 0, [c, s], cd);
                    }
                    if arm2 > 0.0 {
                        // The tilt about the element's tangential axis, `rx s - ry c`, and its
                        // rate as the element travels with the cage.
                        let wt = v[3] * s - v[4] * c + wc * (q[3] * c + q[4] * s);
                        let ct = cd * arm2;
                        r.f[2] -= ct * wt;
                        if jac {
                            add_outer(&mut cmat, 3, [s, -c], ct);
                        }
                    }
                }
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
