//! Line contact of a roller by laminae (slicing), after ISO/TS 16281:2008
//! (docs/physics.md §R1–§R3).
//!
//! **The method.** The roller's effective length `Lwe` is cut into `ns` laminae of equal width
//! `w = Lwe/ns`; lamina `k` is centred at `x_k = (k + 1/2) w - Lwe/2` from the roller's
//! mid-plane. Its approach is
//!
//! `delta_k = delta - x_k tan(psi) - 2 P(x_k)`
//!
//! with `delta` the roller's approach at mid-length (both contacts, inner plus outer), `psi` the
//! misalignment (tilt) between the raceways that roller sees and `P(x)` the drop of the roller
//! profile; `P` counts twice because the same profiled roller touches both raceways
//! ([ISO/TS 16281]). The lamina carries
//!
//! `q_k = (c_L / ns) delta_k^(10/9)` for `delta_k > 0`, else `0`,
//!
//! with `c_L = 35948 Lwe^(8/9)` N/mm^(10/9) (`Lwe` in mm) for a steel roller between steel
//! raceways ([ISO/TS 16281]). The split `c_L/ns` makes the lamina stiffness per unit length
//! `35948 Lwe^(-1/9)` depend on the whole roller's length, not on the lamina width: so a uniform
//! approach gives `Q = c_L delta^(10/9)` whatever `ns` is (Palmgren's roller law,
//! [Palmgren 1959]), while a lamina taken alone with Palmgren's law at its own width would give
//! `ns^(1/9)` times more. In SI, with `Lwe` and `delta` in metres,
//! `35948 N/mm^(10/9) × (10³)^(8/9) × (10³)^(10/9) = 35948e6 N/m²` exactly ([`C_STEEL_SI`]).
//!
//! **Other materials** (ceramic rollers). ISO/TS 16281 gives the constant for bearing steel
//! only. The elastic approach of a line contact depends on the load per length `q'` and the
//! pair's modulus through `q'/E'`, besides logarithms of the body size over the contact width
//! ([Johnson 1985] ch. 4; [Houpert 2001]; [Teutsch 2004]); at equal geometry and approach the load
//! therefore scales with `E'`: `c_L(E') = c_L,steel E'/E'_ref`. `E'_ref` is taken as the pair of
//! the project's `steel` preset (208 GPa, ν = 0.30), so steel reproduces ISO/TS 16281's constant
//! exactly ([`E_PRIME_REFERENCE`]; the TS itself states no modulus). Limits: the law keeps
//! Palmgren's exponent 10/9, a fit for steel over bearing loads; the Poisson ratios enter the
//! exact two-dimensional approach also through constant terms beside the logarithms, not only
//! through `E'`, so a pair whose ratios differ from steel's 0.3 (Si3N4: 0.26) carries a further
//! error, small but not quantified here; and the laminae are independent springs (no elastic
//! coupling along the roller), the TS's simplification, so the true edge-stress singularity of
//! a straight roller is not resolved — it shows as a large but finite edge-lamina load.
//!
//! **Pressure per lamina.** Line Hertz on each lamina with its load per length
//! `q' = q_k / w` and the reduced radius `R` in the rolling direction of the roller–race contact:
//! half-width `b = sqrt(8 q' R / (pi E'))`, peak pressure `p0 = 2 q' / (pi b) =
//! sqrt(q' E' / (2 pi R))` ([Johnson 1985] ch. 4, two-dimensional contact of cylinders,
//! written with the project's `E' = 2 E*`, docs/physics.md §2).
//!
//! **Profiles and independent laminae.** Lundberg's and Fujiwara–Kawase's profiles are designed
//! with the elastic coupling along the roller (the compliance of a strip falls towards its ends);
//! the laminae are independent springs, so here every profile, Lundberg's too, shows as an end
//! relief, never as the uniform pressure it gives in an elastically coupled model
//! ([Teutsch 2004] discusses the gap). What the slicing does resolve is the relative effect of
//! the profiles under load and tilt, which is what ISO/TS 16281 uses it for.
//!
//! **Profiles** ([`Profile`]), the drop `P(x)` of one roller surface from the cylinder, defined on
//! `|x| < Lwe/2`; the roller's end chamfer begins at `|x| = Lwe/2`, where no lamina reaches, so a
//! logarithmic profile's infinity at the ends is never evaluated (the edge lamina's centre is
//! `w/2` inside), and [`Profile::drop`] returns `+inf` at and beyond the chamfer (no contact).
//!
//! **Number of laminae.** [`DEFAULT_LAMINAE`] = 30, from the study in the tests
//! (`lamina_convergence_study`): a roller `Dwe = Lwe = 10 mm` held at 4 kN (aligned peak pressure
//! about 2.1 GPa on a race of `R = 4 mm`), tilted 1 mrad (the maker's catalogue of
//! docs/physics.md §R6 allows cylindrical roller bearings 2′–4′, 0.6–1.2 mrad) and 3 mrad;
//! errors against `ns = 4000` of the load at the reference approach, of the approach that
//! carries 4 kN and of the peak pressure there (rows whose every entry is below 0.02 % left out):
//!
//! | tilt | profile | quantity | ns = 10 | 20 | 30 | 50 | 100 |
//! |---|---|---|---|---|---|---|---|
//! | 1 mrad | none | peak pressure at 4 kN | 1.03 % | 0.51 % | 0.34 % | 0.20 % | 0.10 % |
//! | 1 mrad | crown R 2 m | load at the reference approach | 0.20 % | 0.05 % | 0.02 % | 0.01 % | 0.00 % |
//! | 1 mrad | crown R 2 m | approach at 4 kN | 0.15 % | 0.04 % | 0.02 % | 0.01 % | 0.00 % |
//! | 1 mrad | crown R 2 m | peak pressure at 4 kN | 0.34 % | 0.09 % | 0.04 % | 0.01 % | 0.00 % |
//! | 1 mrad | ISO/TS log | load at the reference approach | 1.63 % | 0.55 % | 0.21 % | 0.08 % | 0.01 % |
//! | 1 mrad | ISO/TS log | approach at 4 kN | 1.24 % | 0.42 % | 0.16 % | 0.06 % | 0.01 % |
//! | 1 mrad | ISO/TS log | peak pressure at 4 kN | 0.68 % | 0.24 % | 0.10 % | 0.04 % | 0.01 % |
//! | 3 mrad | none | peak pressure at 4 kN | 2.28 % | 1.13 % | 0.75 % | 0.45 % | 0.22 % |
//! | 3 mrad | crown R 2 m | load at the reference approach | 0.08 % | 0.02 % | 0.00 % | 0.01 % | 0.00 % |
//! | 3 mrad | crown R 2 m | approach at 4 kN | 0.06 % | 0.02 % | 0.00 % | 0.00 % | 0.00 % |
//! | 3 mrad | crown R 2 m | peak pressure at 4 kN | 0.26 % | 0.05 % | 0.03 % | 0.01 % | 0.00 % |
//! | 3 mrad | ISO/TS log | load at the reference approach | 0.69 % | 0.60 % | 0.32 % | 0.19 % | 0.08 % |
//! | 3 mrad | ISO/TS log | approach at 4 kN | 0.55 % | 0.49 % | 0.26 % | 0.15 % | 0.07 % |
//! | 3 mrad | ISO/TS log | peak pressure at 4 kN | 0.47 % | 0.23 % | 0.12 % | 0.08 % | 0.03 % |
//!
//! (The printout of that test, which asserts every ns = 30 entry below 1 %; reference
//! approaches 21.9, 26.1, 26.0 µm at 1 mrad and peak pressures 2 136, 2 120, 2 133 MPa; at
//! 3 mrad 2 539, 2 282, 2 331 MPa.) The straight roller's load and approach errors stay below
//! 0.02 % (`delta_k^(10/9)` of a linear `delta_k` is nearly linear, which the midpoint rule
//! integrates exactly); its edge-lamina pressure converges as `1/ns` (the centre sits `w/2`
//! from the edge); the logarithmic profile's load about as `ln(ns)/ns` (its drop is integrably
//! infinite at the ends). Ten laminae keep every entry within 2.3 %, 30 within 0.75 %, at 30
//! roots `d^(1/9)` per loaded roller and evaluation (15 for an aligned one, whose mirrored
//! laminae pair): 30 is the default. `docs/rollers.md` (`cargo run --release --example
//! rollers_page`) writes the study out with a plot.

use crate::error::{Error, Result};
use serde::Serialize;
use std::f64::consts::PI;

/// ISO/TS 16281 constant of a steel roller between steel raceways, N/mm^(10/9), with `Lwe` in
/// mm: `Q = 35948 Lwe^(8/9) delta^(10/9)`.
pub const C_STEEL_N_MM: f64 = 35948.0;

/// [`C_STEEL_N_MM`] in SI, N/m² (N per m^(8/9) of length per m^(10/9) of approach): the factor
/// is `(10³)^(8/9) (10³)^(10/9) = 10⁶` exactly.
pub const C_STEEL_SI: f64 = C_STEEL_N_MM * 1.0e6;

/// `E'` (docs/physics.md §2, `2/((1-ν1²)/E1 + (1-ν2²)/E2)`) of two bodies of the `steel` preset
/// (208 GPa, ν = 0.30), Pa: the modulus at which [`roller_constant`] is ISO/TS 16281's.
pub const E_PRIME_REFERENCE: f64 = 208.0e9 / (1.0 - 0.30 * 0.30);

/// Default number of laminae (module docs: the convergence study).
pub const DEFAULT_LAMINAE: usize = 30;

/// Largest number of laminae accepted.
pub const MAX_LAMINAE: usize = 10_000;

/// Roller constant `c_L` (N/m^(10/9)) of a roller of effective length `lwe` (m) whose two
/// contacts have the pair modulus `e_prime` (Pa): `35948e6 Lwe^(8/9) E'/E'_ref`
/// (module docs). `Q = c_L delta^(10/9)` for a uniform approach `delta` of both contacts.
pub fn roller_constant(lwe: f64, e_prime: f64) -> f64 {
    C_STEEL_SI * lwe.powf(8.0 / 9.0) * (e_prime / E_PRIME_REFERENCE)
}

/// Line-Hertz half-width `b` (m) and peak pressure `p0` (Pa) for a load per length `q_per_m`
/// (N/m), reduced radius `r` (m) in the rolling direction and pair modulus `e_prime` (Pa,
/// `E' = 2 E*`): `b = sqrt(8 q' R/(pi E'))`, `p0 = 2 q'/(pi b)`. Zero for a load ≤ 0.
pub fn line_hertz(q_per_m: f64, r: f64, e_prime: f64) -> (f64, f64) {
    if q_per_m > 0.0 {
        let b = (8.0 * q_per_m * r / (PI * e_prime)).sqrt();
        (b, 2.0 * q_per_m / (PI * b))
    } else {
        (0.0, 0.0)
    }
}

mod profile;
mod root;
#[cfg(test)]
mod tests;

pub use profile::{LineGeometry, Profile};
use root::ninth_root;

/// `tan(psi)`, with an aligned roller's (`psi = ±0`) without the call: `tan(±0) = ±0`.
#[inline]
pub(crate) fn tan0(psi: f64) -> f64 {
    if psi == 0.0 {
        psi
    } else {
        psi.tan()
    }
}

/// The approach (m) of one lamina carrying `q` (N) under the lamina constant `c`
/// (N/m^(10/9)): the lamina law `q = c delta^(10/9)` inverted.
#[inline]
pub(crate) fn lamina_approach(q: f64, c: f64) -> f64 {
    (q / c).powf(0.9)
}

/// Roller force, tilting moment and their derivatives from one evaluation of the laminae.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct RollerLoad {
    /// Roller load `Q = Σ q_k`, N.
    pub force: f64,
    /// Moment of the lamina loads about the roller's mid-plane, `M = Σ q_k x_k`, N m. A
    /// positive tilt unloads the `+x` end, so `M < 0`: the contact resists the tilt.
    pub moment: f64,
    /// `∂Q/∂delta`, N/m.
    pub dforce_ddelta: f64,
    /// `∂Q/∂psi`, N/rad.
    pub dforce_dtilt: f64,
    /// `∂M/∂delta`, N.
    pub dmoment_ddelta: f64,
    /// `∂M/∂psi`, N m/rad.
    pub dmoment_dtilt: f64,
    /// Number of laminae in contact.
    pub loaded: usize,
    /// Largest lamina load, N (for the peak pressure without storing the laminae).
    pub max_lamina: f64,
}

impl RollerLoad {
    /// [`RollerLoad::add`] without the derivatives.
    #[inline]
    pub(crate) fn add_force(&mut self, q: f64, x: f64) {
        if q > 0.0 {
            self.loaded += 1;
            if q > self.max_lamina {
                self.max_lamina = q;
            }
            self.force += q;
            self.moment += q * x;
        }
    }

    /// Adds one lamina at `x` carrying `q` with `dq/d delta` = `dq` (`sec2 = sec² psi`, the
    /// tilt's chain factor); an unloaded lamina adds nothing.
    #[inline]
    pub(crate) fn add(&mut self, q: f64, dq: f64, x: f64, sec2: f64) {
        if q > 0.0 {
            self.add_force(q, x);
            self.dforce_ddelta += dq;
            self.dforce_dtilt -= dq * x * sec2;
            self.dmoment_ddelta += dq * x;
            self.dmoment_dtilt -= dq * x * x * sec2;
        }
    }
}

/// A roller's laminae, set up once (centres, profile drops, lamina constant); evaluating them
/// allocates nothing.
#[derive(Debug, Clone, PartialEq)]
pub struct Laminae {
    /// Effective length `Lwe`, m.
    pub lwe: f64,
    /// Lamina centres `x_k` from the roller's mid-plane, m.
    pub x: Vec<f64>,
    /// `2 P(x_k)`: the profile drop of both contacts at each lamina, m.
    pub drop2: Vec<f64>,
    /// Lamina constant `c_s = c_L/ns`, N/m^(10/9).
    pub cs: f64,
    /// `(max |x_k|, min 2P(x_k))`: a lamina's approach is at most `delta + max|x| |tan psi|
    /// - min 2P`, so at or below zero no lamina is loaded (the early exit of `eval`).
    reach: (f64, f64),
    /// The aligned roller's pairs (`eval_aligned`): true when every pair `k`, `ns - 1 - k`
    /// is mirrored with equal drops and the drops do not grow toward the centre
    /// (`drop2[k] >= drop2[k + 1]` over the first half: every [`Profile`]), so the pairs
    /// loaded at an approach are a run ending at the centre; false: checked pair by pair.
    sorted_pairs: bool,
}

impl Laminae {
    /// What contact damping ramps in with ([`crate::seam::element::ElementReaction::approach`]),
    /// for the evaluation `r` of these laminae at the mid-length approach `delta`: the
    /// approach of the most compressed lamina, `(q_max/c_s)^0.9` (the lamina law inverted),
    /// or, with no lamina loaded, `delta` capped at zero. `aligned`: the roller at zero tilt
    /// without offsets, whose most compressed lamina is the one of least profile drop
    /// (`delta - min 2P`, no root taken). A tilted roller's edge lamina thus ramps the
    /// damping in from its own first touch, where the mid-length approach may be negative
    /// (docs/physics.md §R9).
    #[inline]
    pub(crate) fn contact_approach(&self, r: &RollerLoad, delta: f64, aligned: bool) -> f64 {
        if r.loaded == 0 {
            delta.min(0.0)
        } else if aligned {
            delta - self.reach.1
        } else {
            lamina_approach(r.max_lamina, self.cs)
        }
    }

    /// Slice a roller of geometry `g` with profile `profile` into `ns` laminae. Errors name
    /// `roller.laminae`, `roller.effective_length`, `roller.diameter`, `roller.e_prime` or
    /// `roller.profile.<parameter>`.
    pub fn new(g: &LineGeometry, profile: &Profile, ns: usize) -> Result<Laminae> {
        if !(1..=MAX_LAMINAE).contains(&ns) {
            return Err(Error::invalid(
                "roller.laminae",
                ns,
                format!("an integer in [1, {MAX_LAMINAE}] (default {DEFAULT_LAMINAE})"),
            ));
        }
        for (field, v) in [
            ("roller.effective_length", g.lwe),
            ("roller.diameter", g.dwe),
            ("roller.e_prime", g.e_prime),
        ] {
            crate::error::positive(field, v)?;
        }
        profile.validate("roller.profile", g)?;
        let w = g.lwe / ns as f64;
        let mut x: Vec<f64> = (0..ns)
            .map(|k| (k as f64 + 0.5) * w - 0.5 * g.lwe)
            .collect();
        // The centres mirrored exactly about the mid-plane (`x_(ns-1-k) = -x_k`; the formula
        // above can differ in the last bit), which `eval_aligned` pairs.
        for k in 0..ns / 2 {
            x[ns - 1 - k] = -x[k];
        }
        if ns % 2 == 1 {
            x[ns / 2] = 0.0;
        }
        let drop2: Vec<f64> = x.iter().map(|&xk| 2.0 * profile.drop(xk, g)).collect();
        let reach = (
            x.iter().fold(0.0f64, |m, v| m.max(v.abs())),
            drop2.iter().fold(f64::INFINITY, |m, &v| m.min(v)),
        );
        let half = ns / 2;
        let mirrored = (0..half).all(|k| drop2[k] == drop2[ns - 1 - k] && x[k] == -x[ns - 1 - k]);
        let monotone = (1..half).all(|k| drop2[k - 1] >= drop2[k]);
        Ok(Laminae {
            lwe: g.lwe,
            x,
            drop2,
            reach,
            sorted_pairs: mirrored && monotone,
            cs: roller_constant(g.lwe, g.e_prime) / ns as f64,
        })
    }

    /// Number of laminae `ns`.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// Always false: a roller has at least one lamina.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// Lamina width `w = Lwe/ns`, m.
    pub fn width(&self) -> f64 {
        self.lwe / self.len() as f64
    }

    /// True when no lamina can touch at approach `delta` and `tan_psi`: every lamina's approach
    /// is at most `delta + max|x| |tan psi| - min 2P`, and that is at or below zero (then
    /// [`Laminae::evaluate`] answers zeros without evaluating a lamina).
    #[inline]
    pub(crate) fn untouched(&self, delta: f64, tan_psi: f64) -> bool {
        delta + self.reach.0 * tan_psi.abs() - self.reach.1 <= 0.0
    }

    /// Roller force, moment and derivatives at approach `delta` (m, both contacts, at
    /// mid-length) and tilt `psi` (rad). Zero (never NaN) when no lamina is in contact.
    pub fn evaluate(&self, delta: f64, psi: f64) -> RollerLoad {
        self.eval(delta, tan0(psi), None)
    }

    /// As [`Laminae::evaluate`] with the tilt given by its tangent `tan_psi` (a caller that
    /// needs the tangent itself forms it once).
    pub(crate) fn evaluate_tan(&self, delta: f64, tan_psi: f64) -> RollerLoad {
        self.eval(delta, tan_psi, None)
    }

    /// As [`Laminae::evaluate`], writing each lamina's load (N) into `loads` (length `ns`).
    pub fn evaluate_into(&self, delta: f64, psi: f64, loads: &mut [f64]) -> RollerLoad {
        assert_eq!(loads.len(), self.len(), "one load per lamina");
        self.eval(delta, tan0(psi), Some(loads))
    }

    /// As [`Laminae::evaluate_tan`] without the derivatives (left at zero) when the roller
    /// is aligned: its force, moment, loaded count and largest lamina are the same bits,
    /// for a caller that wants no stiffness (a right-hand side).
    #[inline]
    pub(crate) fn evaluate_tan_force(&self, delta: f64, tan_psi: f64) -> RollerLoad {
        if tan_psi == 0.0 && !self.untouched(delta, tan_psi) {
            return self.eval_aligned::<false>(delta);
        }
        self.eval(delta, tan_psi, None)
    }

    fn eval(&self, delta: f64, tan_psi: f64, mut loads: Option<&mut [f64]>) -> RollerLoad {
        let sec2 = 1.0 + tan_psi * tan_psi;
        let mut r = RollerLoad::default();
        // No lamina can touch: nothing to evaluate (the loop would give the same zeros).
        if loads.is_none() && self.untouched(delta, tan_psi) {
            return r;
        }
        if tan_psi == 0.0 && loads.is_none() {
            return self.eval_aligned::<true>(delta);
        }
        let (cs, dcs) = (self.cs, 10.0 / 9.0 * self.cs);
        for (k, (&x, &d2)) in self.x.iter().zip(&self.drop2).enumerate() {
            let d = delta - x * tan_psi - d2;
            let (q, dq) = if d > 0.0 {
                let p = ninth_root(d);
                (cs * d * p, dcs * p)
            } else {
                (0.0, 0.0)
            };
            if let Some(l) = loads.as_deref_mut() {
                l[k] = q;
            }
            r.add(q, dq, x, sec2);
        }
        r
    }

    /// As [`Laminae::evaluate`] with each lamina's approach moved by `offsets[k]` (m, length `ns`;
    /// waviness adds, a defect's depth loss subtracts: docs/physics.md §R12):
    /// `delta_k = delta - x_k tan(psi) - 2 P(x_k) + offsets[k]`. Every lamina through the
    /// general loop (an offset breaks the aligned roller's mirror pairs). `loads` (length
    /// `ns`) receives the lamina loads.
    pub fn evaluate_offsets(
        &self,
        delta: f64,
        tan_psi: f64,
        offsets: &[f64],
        loads: Option<&mut [f64]>,
    ) -> RollerLoad {
        self.eval_offsets::<true>(delta, tan_psi, offsets, loads)
    }

    /// As [`Laminae::evaluate_offsets`] without the derivatives (left at zero): the same
    /// force, moment, loaded count, largest lamina and lamina loads, for a caller that wants
    /// no stiffness (a right-hand side).
    pub(crate) fn evaluate_offsets_force(
        &self,
        delta: f64,
        tan_psi: f64,
        offsets: &[f64],
        loads: Option<&mut [f64]>,
    ) -> RollerLoad {
        self.eval_offsets::<false>(delta, tan_psi, offsets, loads)
    }

    fn eval_offsets<const D: bool>(
        &self,
        delta: f64,
        tan_psi: f64,
        offsets: &[f64],
        mut loads: Option<&mut [f64]>,
    ) -> RollerLoad {
        assert_eq!(offsets.len(), self.len(), "one offset per lamina");
        let sec2 = 1.0 + tan_psi * tan_psi;
        let mut r = RollerLoad::default();
        let (cs, dcs) = (self.cs, 10.0 / 9.0 * self.cs);
        for (k, ((&x, &d2), &o)) in self.x.iter().zip(&self.drop2).zip(offsets).enumerate() {
            let d = delta - x * tan_psi - d2 + o;
            let (q, dq) = if d > 0.0 {
                let p = ninth_root(d);
                (cs * d * p, if D { dcs * p } else { 0.0 })
            } else {
                (0.0, 0.0)
            };
            if let Some(l) = loads.as_deref_mut() {
                l[k] = q;
            }
            if D {
                r.add(q, dq, x, sec2);
            } else {
                r.add_force(q, x);
            }
        }
        r
    }

    /// The inner contacts of the laminae when the roller presses on the outer raceway with
    /// `f` (N) on every lamina (its centrifugal force split evenly, docs/physics.md §R9): at
    /// approach `delta` (m, both contacts) and tilt `tan_psi`, the force, moment and
    /// derivatives of the inner lamina loads `q_i,k`, each lamina's outer load being
    /// `q_i,k + f`. Each contact of a lamina takes half the approach of ISO/TS 16281's law at
    /// equal loads, `q = c_s (2 delta_c)^(10/9)`; with `u`, `v` twice the inner and outer
    /// approaches, `u + v = 2 delta_k` and `c_s (v^(10/9) - u^(10/9)) = f`. The inner contact
    /// is open while `2 delta_k <= (f/c_s)^0.9`. Newton from `u = delta_k` (where the residual
    /// is `-f/c_s`) on the residual, concave and decreasing on `(0, delta_k]`, converges
    /// monotonically from above. `dq_i/d delta_k = 2 (10/9) c_s u^(1/9) v^(1/9)/(u^(1/9) +
    /// v^(1/9))` (implicit differentiation); at `f = 0` every quantity is [`Laminae::eval`]'s.
    /// `max_lamina` is the largest inner lamina load. `loads` (length `ns`) receives the inner
    /// lamina loads.
    pub(crate) fn eval_pressed(
        &self,
        delta: f64,
        tan_psi: f64,
        f: f64,
        mut loads: Option<&mut [f64]>,
    ) -> RollerLoad {
        const P: f64 = 10.0 / 9.0;
        let sec2 = 1.0 + tan_psi * tan_psi;
        let mut r = RollerLoad::default();
        let cs = self.cs;
        let phi = f.max(0.0) / cs;
        // 2 delta_k at which the inner contact closes.
        let v0 = phi.powf(0.9);
        if let Some(l) = loads.as_deref_mut() {
            l.fill(0.0);
        }
        if 2.0 * (delta + self.reach.0 * tan_psi.abs() - self.reach.1) <= v0 {
            return r;
        }
        for (k, (&x, &d2)) in self.x.iter().zip(&self.drop2).enumerate() {
            let dd = 2.0 * (delta - x * tan_psi - d2);
            if dd <= v0 {
                continue;
            }
            let mut u = 0.5 * dd;
            for _ in 0..100 {
                let v = dd - u;
                let (ru, rv) = (ninth_root(u), ninth_root(v));
                let g = v * rv - u * ru - phi;
                let step = g / (P * (ru + rv));
                // g <= 0 from above: u falls toward the root.
                let next = (u + step).max(0.0);
                let done = u - next <= 4.0 * f64::EPSILON * u;
                u = next;
                if done {
                    break;
                }
            }
            let (ru, rv) = (ninth_root(u), ninth_root(dd - u));
            let q = cs * u * ru;
            let dq = if ru + rv > 0.0 {
                2.0 * P * cs * ru * rv / (ru + rv)
            } else {
                0.0
            };
            if let Some(l) = loads.as_deref_mut() {
                l[k] = q;
            }
            r.add(q, dq, x, sec2);
        }
        r
    }

    /// [`Laminae::eval`] of an aligned roller (`tan psi = 0`): laminae `k` and `ns - 1 - k`
    /// at `x` and `-x` (exactly: `new` mirrors the centres) with equal profile drops (every
    /// [`Profile`] is even in `x`; checked pair by pair) carry the same load, so each such pair
    /// takes one root, and their moments and the moment's cross derivatives cancel exactly
    /// (summed as zeros, not as rounding noise). `D`: with the derivatives (without, they
    /// stay zero and the rest is the same bits).
    fn eval_aligned<const D: bool>(&self, delta: f64) -> RollerLoad {
        let (cs, dcs) = (self.cs, 10.0 / 9.0 * self.cs);
        let mut r = RollerLoad::default();
        // Lamina (pair) at `x` with approach `d` and, when `d > 0`, its root `p = d^(1/9)`.
        let with_root = |r: &mut RollerLoad, x: f64, d: f64, n: usize, p: f64| {
            if d > 0.0 {
                let q = cs * d * p;
                if q > 0.0 {
                    let w = n as f64;
                    r.loaded += n;
                    if q > r.max_lamina {
                        r.max_lamina = q;
                    }
                    r.force += w * q;
                    if n == 1 {
                        r.moment += q * x;
                    }
                    if D {
                        let dq = dcs * p;
                        r.dforce_ddelta += w * dq;
                        r.dmoment_dtilt -= w * dq * x * x;
                        if n == 1 {
                            r.dforce_dtilt -= dq * x;
                            r.dmoment_ddelta += dq * x;
                        }
                    }
                }
            }
        };
        let root = |d: f64| if d > 0.0 { ninth_root(d) } else { 0.0 };
        let one = |r: &mut RollerLoad, x: f64, d: f64, n: usize| with_root(r, x, d, n, root(d));
        let ns = self.len();
        let (x, d2) = (&self.x[..ns], &self.drop2[..ns]);
        if self.sorted_pairs {
            // Mirrored pairs whose drops fall toward the centre: the unloaded pairs
            // (`delta <= drop`) come first; skip them by bisection and sum the loaded ones in
            // the same order as the loop below (the same bits).
            let half = &d2[..ns / 2];
            let first = half.partition_point(|&d| delta - d <= 0.0);
            // Two pairs' roots at a time (independent: they overlap in the processor), summed
            // in the same order.
            let mut k = first;
            while k + 1 < ns / 2 {
                let (da, db) = (delta - d2[k], delta - d2[k + 1]);
                let (pa, pb) = (root(da), root(db));
                with_root(&mut r, x[k], da, 2, pa);
                with_root(&mut r, x[k + 1], db, 2, pb);
                k += 2;
            }
            if k < ns / 2 {
                one(&mut r, x[k], delta - d2[k], 2);
            }
        } else {
            for k in 0..ns / 2 {
                let m = ns - 1 - k;
                if d2[k] == d2[m] && x[k] == -x[m] {
                    one(&mut r, x[k], delta - d2[k], 2);
                } else {
                    one(&mut r, x[k], delta - d2[k], 1);
                    one(&mut r, x[m], delta - d2[m], 1);
                }
            }
        }
        if ns % 2 == 1 {
            one(&mut r, x[ns / 2], delta - d2[ns / 2], 1);
        }
        r
    }

    /// Per-lamina line-Hertz peak pressures (Pa) into `out` from lamina loads `loads` (N), for
    /// a contact of reduced radius `r` (m) and pair modulus `e_prime` (Pa).
    pub fn pressures(&self, loads: &[f64], r: f64, e_prime: f64, out: &mut [f64]) {
        let w = self.width();
        for (p, &q) in out.iter_mut().zip(loads) {
            *p = line_hertz(q / w, r, e_prime).1;
        }
    }
}
