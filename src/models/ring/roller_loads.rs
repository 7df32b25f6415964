//! Every lamina load of a roller bearing on the ring level at a given state, as the ring level
//! evaluates them ([`super::elements::LawRingLevel`]: massless rollers at the cage's kinematic
//! positions, the scene's defects and waviness per lamina, [`super::roller_effects`]),
//! gathered into a [`LaminaWindow`] for the run's lamina life (ISO/TS 16281 over the recorded
//! window, docs/physics.md §R10).
//!
//! - A cylindrical roller's inner and outer laminae carry the same loads (massless rollers).
//! - A tapered roller's cup (outer) laminae carry the loads of [`TaperedRollerLaw`] along the
//!   cup normal, and its cone (inner) laminae `rho_i` times them (the roller's force triangle
//!   at rest, docs/physics.md §R7), exactly as the quasi-static table gives them at rest.

use super::roller_effects::RollerEffects;
use crate::contact::roller_law::CylindricalRollerLaw;
use crate::contact::tapered_law::TaperedRollerLaw;
use crate::error::{Error, Result};
use crate::geometry::element::Element;
use crate::geometry::kinematics::nominal_cage_speed as cage_speed;
use crate::geometry::Bearing;
use crate::models::effects::Effects;
use crate::ratings::lamina_life::LaminaWindow;
use crate::seam::element::{even_base, place_evenly_sc, ElementDisplacement, Want};

/// The massless law of either roller kind.
#[derive(Debug)]
enum Law {
    Cylindrical(CylindricalRollerLaw),
    /// The law and its cone-to-cup load ratio `rho_i`.
    Tapered(TaperedRollerLaw, f64),
}

/// The ring level's rollers, set up once; [`RingLaminae::add_state`] allocates nothing.
#[derive(Debug)]
pub struct RingLaminae {
    law: Law,
    fx: Option<RollerEffects>,
    cage_ratio: f64,
    psi: Vec<f64>,
    sc: Vec<(f64, f64)>,
    base: Vec<(f64, f64)>,
    offsets: Vec<f64>,
    /// Outer (cup) lamina loads of one roller, N.
    loads: Vec<f64>,
    /// Inner (cone) lamina loads of one roller (tapered only), N.
    inner: Vec<f64>,
}

impl RingLaminae {
    /// The rollers of `b` with the scene's `effects` (refused as the ring level refuses
    /// them); a ball bearing is refused naming `bearing.kind`.
    pub fn new(b: &Bearing, effects: &Effects) -> Result<RingLaminae> {
        let Element::Roller(r) = &b.element else {
            return Err(Error::invalid(
                "bearing.kind",
                b.element().name(),
                "a roller bearing (nu, n, nj, nup, tapered): the ring level's lamina loads",
            ));
        };
        // Lamina positions along +z as the ring level passes them to the effects: a tapered
        // roller's along the raceway generatrix.
        let (law, x) = if r.kind.is_tapered() {
            let l = TaperedRollerLaw::new(r)?.massless();
            let x = l.generatrix_positions();
            let rho = l.load_ratios().0;
            (Law::Tapered(l, rho), x)
        } else {
            let l = CylindricalRollerLaw::new(r)?.massless();
            let x = l.laminae().x.clone();
            (Law::Cylindrical(l), x)
        };
        let ns = x.len();
        let fx = if *effects == Effects::default() {
            None
        } else {
            Some(RollerEffects::new(effects, b, &x)?)
        };
        Ok(RingLaminae {
            law,
            fx,
            cage_ratio: cage_speed(b, 1.0),
            psi: vec![0.0; b.z],
            sc: vec![(0.0, 1.0); b.z],
            base: even_base(b.z),
            offsets: vec![0.0; ns],
            loads: vec![0.0; ns],
            inner: vec![0.0; ns],
        })
    }

    /// An empty window for these rollers.
    pub fn window(&self) -> LaminaWindow {
        LaminaWindow::new(self.psi.len(), self.loads.len())
    }

    /// Adds to `w` the lamina loads of every roller at ring displacement `q` (m, rad) with the
    /// cage turned by `cage_angle` (rad; the ring level's state, 0 at the start): inner and
    /// outer contacts alike for a cylindrical roller, cone `rho_i` times cup for a tapered
    /// one (module docs).
    pub fn add_state(&mut self, q: &[f64; 5], cage_angle: f64, w: &mut LaminaWindow) {
        place_evenly_sc(&mut self.psi, &mut self.sc, &self.base, cage_angle);
        let theta_s = cage_angle / self.cage_ratio;
        for (j, (&psi, &(s, c))) in self.psi.iter().zip(&self.sc).enumerate() {
            let u = ElementDisplacement::at(q, s, c);
            let any = self
                .fx
                .as_ref()
                .is_some_and(|fx| fx.offsets(j, psi, theta_s, &mut self.offsets));
            match &self.law {
                Law::Cylindrical(l) => {
                    if any {
                        l.react_offsets(u, &self.offsets, Want::default(), Some(&mut self.loads));
                    } else {
                        l.lamina_loads(u, 0.0, &mut self.loads);
                    }
                    w.add_roller(&self.loads, &self.loads);
                }
                Law::Tapered(l, rho) => {
                    if any {
                        l.react_offsets(u, &self.offsets, Want::default(), Some(&mut self.loads));
                    } else {
                        l.lamina_loads(u, &mut self.loads);
                    }
                    for (i, o) in self.inner.iter_mut().zip(&self.loads) {
                        *i = o * rho;
                    }
                    w.add_roller(&self.inner, &self.loads);
                }
            }
        }
        w.end_state();
    }

    /// The cage's angle per radian of shaft angle (kinematic).
    pub fn cage_ratio(&self) -> f64 {
        self.cage_ratio
    }
}
