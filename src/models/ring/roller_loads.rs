//! Every lamina load of a cylindrical roller bearing on the ring level at a given state, as
//! the ring level evaluates them ([`super::elements::LawRingLevel`]: massless rollers at the
//! cage's kinematic positions, the scene's defects and waviness per lamina,
//! [`super::roller_effects`]), gathered into a [`LaminaWindow`] for the run's lamina life
//! (ISO/TS 16281 over the recorded window, docs/physics.md §R10). A tapered roller bearing is
//! refused, naming `bearing.kind`.

use super::roller_effects::RollerEffects;
use crate::contact::roller_law::CylindricalRollerLaw;
use crate::error::{Error, Result};
use crate::geometry::element::Element;
use crate::geometry::kinematics::nominal_cage_speed as cage_speed;
use crate::geometry::Bearing;
use crate::models::effects::Effects;
use crate::ratings::lamina_life::LaminaWindow;
use crate::seam::element::{even_base, place_evenly_sc, ElementDisplacement, Want};

/// The ring level's rollers, set up once; [`RingLaminae::add_state`] allocates nothing.
#[derive(Debug)]
pub struct RingLaminae {
    law: CylindricalRollerLaw,
    fx: Option<RollerEffects>,
    cage_ratio: f64,
    psi: Vec<f64>,
    sc: Vec<(f64, f64)>,
    base: Vec<(f64, f64)>,
    offsets: Vec<f64>,
    loads: Vec<f64>,
}

impl RingLaminae {
    /// The rollers of `b` with the scene's `effects` (refused as the ring level refuses
    /// them); a ball or tapered roller bearing is refused naming `bearing.kind`.
    pub fn new(b: &Bearing, effects: &Effects) -> Result<RingLaminae> {
        let r =
            match &b.element {
                Element::Roller(r) if !r.kind.is_tapered() => r,
                _ => return Err(Error::invalid(
                    "bearing.kind",
                    b.element().name(),
                    "a cylindrical roller bearing (nu, n, nj, nup): the ring level's lamina loads",
                )),
            };
        let law = CylindricalRollerLaw::new(r)?.massless();
        let ns = law.laminae().len();
        let fx = if *effects == Effects::default() {
            None
        } else {
            Some(RollerEffects::new(effects, b, &law.laminae().x)?)
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
        })
    }

    /// An empty window for these rollers.
    pub fn window(&self) -> LaminaWindow {
        LaminaWindow::new(self.psi.len(), self.loads.len())
    }

    /// Adds to `w` the lamina loads of every roller at ring displacement `q` (m, rad) with the
    /// cage turned by `cage_angle` (rad; the ring level's state, 0 at the start): inner and
    /// outer contacts alike (massless rollers).
    pub fn add_state(&mut self, q: &[f64; 5], cage_angle: f64, w: &mut LaminaWindow) {
        place_evenly_sc(&mut self.psi, &mut self.sc, &self.base, cage_angle);
        let theta_s = cage_angle / self.cage_ratio;
        for (j, (&psi, &(s, c))) in self.psi.iter().zip(&self.sc).enumerate() {
            let u = ElementDisplacement::at(q, s, c);
            let any = self
                .fx
                .as_ref()
                .is_some_and(|fx| fx.offsets(j, psi, theta_s, &mut self.offsets));
            if any {
                self.law
                    .react_offsets(u, &self.offsets, Want::default(), Some(&mut self.loads));
            } else {
                self.law.lamina_loads(u, 0.0, &mut self.loads);
            }
            w.add_roller(&self.loads, &self.loads);
        }
        w.end_state();
    }

    /// The cage's angle per radian of shaft angle (kinematic).
    pub fn cage_ratio(&self) -> f64 {
        self.cage_ratio
    }
}
