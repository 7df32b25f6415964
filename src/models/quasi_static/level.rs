//! The `quasi_static` level: every rolling element in equilibrium at the current ring
//! motion (balls: Jones–Harris, docs/physics.md §4), elements at the cage's kinematic
//! positions so the force varies as they pass. State: the cage angle. Memory (in the
//! component state, so a restored state continues bit for bit): each element's warm start.
//!
//! The level sums elements through their contact law ([`ElementLaw`],
//! [`crate::seam::element::assemble`]); [`element_law`] picks the law of the bearing's
//! element: the one place an element type is plugged in.
//!
//! Contact damping (`model.contact_damping`, N s/m per loaded ball) acts as in the ring
//! level: `c d(delta)/dt` along each loaded ball's contact line (the ring level's massless
//! ball geometry), blended in over the first 0.1 µm of approach; off (no cost) at 0.

use crate::error::Result;
use crate::geometry::element::{Element, ElementKind};
use crate::geometry::kinematics::nominal_cage_speed as cage_speed;
use crate::models::quasi_static::{Options, QuasiStatic};
use crate::models::ring::elements::LawRingLevel;
use crate::models::ring::{RingAt, RingDof, RingEval, RingModel};
use crate::models::LevelArgs;
use crate::seam::element::{
    assemble, place_evenly, ElementLaw, ElementLoad, ElementReaction, Want,
};
use crate::seam::{LevelModel, LevelOutputs, Motion, Point};

/// The element kinds this level takes: those [`element_law`] has a law for (the level
/// registry reads it).
pub const ELEMENTS: &[ElementKind] = &[ElementKind::Ball, ElementKind::Roller];

/// The contact law of the bearing's element at this level.
/// The element's contact law; `inertia`: a cylindrical roller's centrifugal force at speed
/// (the quasi-static level), or massless rollers (the ring level; balls: their own model).
pub fn element_law(a: &LevelArgs, opts: Options, inertia: bool) -> Result<Box<dyn ElementLaw>> {
    match &a.bearing.element {
        Element::Ball(_) => Ok(Box::new(QuasiStatic::new(a.bearing, opts)?)),
        Element::Roller(r) => crate::contact::roller_law(r, inertia),
    }
}

/// The level (ball bearings; [`build`] runs other elements on the ring of massless
/// elements).
#[derive(Debug)]
pub struct QuasiStaticLevel {
    law: Box<dyn ElementLaw>,
    cage_ratio: f64,
    psi: Vec<f64>,
    /// The elements' memory while an evaluation runs: it reaches the component's `aux`
    /// only when the whole evaluation succeeds (a failed one leaves the warm starts as
    /// they were, as a refused step leaves everything).
    mem: Vec<f64>,
    /// Contact damping: the ring model with and without damping (their difference is the
    /// damping force); `None` when the scene has none.
    damping: Option<(RingModel, RingModel, RingEval, RingEval)>,
    /// The elements' loads of the last outputs, when asked to keep them
    /// ([`LevelModel::keep_element_loads`]; `None`: nothing stored).
    loads: Option<Vec<ElementLoad>>,
}

impl QuasiStaticLevel {
    /// Build for the scene's bearing and race control.
    pub fn new(a: &LevelArgs) -> Result<Self> {
        let b = a.bearing;
        let opts = Options {
            race_control: a.race_control,
            ..Options::default()
        };
        Ok(QuasiStaticLevel {
            law: element_law(a, opts, true)?,
            cage_ratio: cage_speed(b, 1.0),
            psi: vec![0.0; b.z],
            mem: Vec::new(),
            damping: (a.contact_damping > 0.0).then(|| {
                (
                    RingModel::new(b, RingDof::Five, a.contact_damping),
                    RingModel::new(b, RingDof::Five, 0.0),
                    RingEval::default(),
                    RingEval::default(),
                )
            }),
            loads: None,
        })
    }

    /// Add the contact-damping force (and, with `c`, its matrix) at cage angle `theta`.
    fn add_damping(
        &mut self,
        theta: f64,
        m: &Motion,
        w: &mut [f64; 5],
        c: Option<&mut [[f64; 5]; 5]>,
    ) {
        if let Some((with, without, e1, e0)) = &mut self.damping {
            let at = RingAt {
                theta_c: theta,
                omega_c: self.cage_ratio * m.omega,
                q: &m.q,
                v: &m.v,
                t: 0.0,
            };
            with.eval(at, None, c.is_some(), e1);
            without.eval(at, None, false, e0);
            for ((w, a), b) in w.iter_mut().zip(e1.wrench).zip(e0.wrench) {
                *w += a - b;
            }
            if let Some(c) = c {
                *c = e1.c;
            }
        }
    }
}

/// The registry's constructor (the level registry, `LEVELS` in `component/levels.rs`).
/// A bearing whose element is not a ball runs as the 5-DOF ring on massless elements
/// ([`crate::models::ring::elements::LawRingLevel`]) with the element's law at speed (a
/// cylindrical roller's centrifugal force, docs/physics.md §R9); the ring level runs the same
/// elements massless.
pub fn build(a: &LevelArgs) -> Result<Box<dyn LevelModel>> {
    if a.bearing.element() != ElementKind::Ball {
        let opts = Options {
            race_control: a.race_control,
            ..Options::default()
        };
        let law = element_law(a, opts, true)?;
        return Ok(Box::new(LawRingLevel::new(a, law, RingDof::Five)?));
    }
    Ok(Box::new(QuasiStaticLevel::new(a)?))
}

impl LevelModel for QuasiStaticLevel {
    fn n_states(&self) -> usize {
        1
    }
    fn states_are_quadrature(&self) -> bool {
        // The cage angle, at cage_ratio * omega.
        true
    }
    fn n_aux(&self) -> usize {
        self.law.state_len() * self.psi.len()
    }
    fn init(&mut self, _m: &Motion, x: &mut [f64], aux: &mut [f64]) -> Result<()> {
        x[0] = 0.0;
        aux.fill(0.0);
        Ok(())
    }
    fn rhs(&mut self, p: Point<'_>, dx: &mut [f64], wrench: Option<&mut [f64; 5]>) -> Result<()> {
        let Point { m, x, aux, .. } = p;
        dx[0] = self.cage_ratio * m.omega;
        if let Some(w) = wrench {
            place_evenly(&mut self.psi, x[0]);
            self.mem.clear();
            self.mem.extend_from_slice(aux);
            let (law, n, mem) = (&self.law, self.law.state_len(), &mut self.mem);
            *w = assemble(&m.q, &self.psi, law.moment_arm(), None, |j, at, u| {
                law.react(
                    at,
                    u,
                    m.omega,
                    &mut mem[n * j..n * (j + 1)],
                    Want::default(),
                )
            })?;
            aux.copy_from_slice(&self.mem);
            self.add_damping(x[0], m, w, None);
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
        match self.loads.take() {
            None => self.outputs_with(p, out, |_, _, _| {}),
            Some(mut loads) => {
                let r = self.outputs_with(p, out, |j, psi, r| {
                    loads[j] = ElementLoad {
                        psi,
                        inner: r.load[0],
                        outer: r.load[1],
                    }
                });
                self.loads = Some(loads);
                r
            }
        }
    }
}

impl QuasiStaticLevel {
    /// [`LevelModel::outputs`], handing each element's reaction (with its report) to
    /// `element(j, psi, reaction)`.
    fn outputs_with(
        &mut self,
        p: Point<'_>,
        out: &mut LevelOutputs,
        mut element: impl FnMut(usize, f64, &ElementReaction),
    ) -> Result<()> {
        let Point { m, x, aux, .. } = p;
        place_evenly(&mut self.psi, x[0]);
        let mut k = [[0.0; 5]; 5];
        // Loaded elements, largest load and pressure: all the outputs read of the
        // elements.
        let (mut loaded, mut max_load, mut max_p) = (0usize, 0.0f64, 0.0f64);
        self.mem.clear();
        self.mem.extend_from_slice(aux);
        let (law, n, mem) = (&self.law, self.law.state_len(), &mut self.mem);
        let want = Want {
            stiffness: true,
            report: true,
        };
        let mut wrench = assemble(
            &m.q,
            &self.psi,
            law.moment_arm(),
            Some(&mut k),
            |j, at, u| {
                let r = law.react(at, u, m.omega, &mut mem[n * j..n * (j + 1)], want)?;
                if r.load[0] > 0.0 {
                    loaded += 1;
                }
                max_load = max_load.max(r.load[0]).max(r.load[1]);
                max_p = max_p.max(r.pressure[0]).max(r.pressure[1]);
                element(j, at.psi, &r);
                Ok(r)
            },
        )?;
        aux.copy_from_slice(&self.mem);
        let mut c = [[0.0; 5]; 5];
        self.add_damping(x[0], m, &mut wrench, Some(&mut c));
        *out = LevelOutputs {
            wrench,
            k,
            c,
            cage_omega: self.cage_ratio * m.omega,
            balls_loaded: loaded as f64,
            max_load,
            max_pressure: max_p,
            ..LevelOutputs::default()
        };
        Ok(())
    }
}
