//! Traction (tangential force) laws of a lubricated ball–race contact (docs/physics.md §5.2).
//!
//! Each law gives the tangential force `f` a contact transmits as a function of the slip
//! velocity `dv` (the faster surface minus the slower, in the rolling direction), the
//! rolling (entrainment) speed `u` and the contact's state. All laws are odd in `dv` and
//! continuous through `dv = 0` (an integrator with error control needs at least that; the
//! smooth Coulomb and mixed-EHL laws are C¹ there).
//!
//! - **Smooth Coulomb** `mu = mu_max tanh(dv / v_s)`: the regularised Coulomb law used by
//!   skidding models since Walters (1971); study \[3\] uses a piecewise-linear law that rises
//!   to about 0.02 at 0.05 m/s, which `tanh` reproduces as a continuous curve.
//! - **Fitted traction curve** `mu = (A + B s) exp(-C s) + D` of the slide-to-roll ratio
//!   `s = dv / u` (Gupta, *Advanced Dynamics of Rolling Elements*, 1984, ch. 3; study \[0\]),
//!   odd-extended: `mu(s) = tanh(s / s_reg) [(A + B|s|) exp(-C|s|) + D]`, so it passes
//!   through 0 continuously even when `A + D != 0`. `s` uses a regularised rolling speed
//!   `sqrt(u² + u_min²)` so it stays finite at rest.
//! - **Mixed EHL** (study \[2\]'s eq. (7), after Masjedi & Khonsari): the load is shared
//!   between the asperities (`La` per cent) and the film. Asperity share
//!   `f_a = f_c Q (La/100) tanh(dv/v_s)` (boundary friction coefficient `f_c`, made
//!   continuous); film share `f_f = Lambda_lim p_h (1 - exp(-eta |dv| / (Lambda_lim p_h h_c)))
//!   pi a b sign(dv)` (a limiting-shear-stress Newtonian film: the shear stress
//!   `eta dv / h_c` saturating at `Lambda_lim p_h`; Bair & Winer's limiting-shear model),
//!   with `p_h = (1 - La/100) Q / (pi a b)` the film's share of the mean pressure, `h_c` the
//!   Hamrock–Dowson central film thickness (docs/physics.md §6). `La` is the one asperity-share
//!   function of the crate, [`crate::lubrication::asperity`] (study \[2\]'s eq. (8), its
//!   roughness term restored; the user-set power law [`AsperityFit`] remains only as an
//!   override, `fit = {...}` in the scene). The viscosity `eta` is corrected for pressure
//!   (Barus, at `p_h`, exponent capped at 50) and for the flash temperature
//!   (`eta = eta0 exp(alpha_p p_h - beta dT)`, `beta` the viscosity–temperature
//!   coefficient, 0.04 /K for study \[2\]'s oil):
//!   `dT = 2 b (q_a + q_h) / (sqrt(pi) [k1 sqrt(1 + Pe1) + k2 sqrt(1 + Pe2)])`, study \[2\]'s
//!   form with `k1 = 60.5` and `k2 = 0.145 W/(m K)`, `q_a + q_h = (f_a + f_f) |dv| / (pi a b)`
//!   the frictional heat flux of both shares, and the Péclet numbers `Pe = |u| b / (2 chi)`
//!   of the surfaces moving at the rolling speed `u` through the contact half-width `b`.
//!   The study does not give the diffusivities `chi`; `k1 = 60.5` and `k2 = 0.145` are
//!   Incropera & DeWitt's plain carbon steel and engine oil at 300 K (*Fundamentals of
//!   Heat and Mass Transfer*, Tables A.1 and A.5), whose diffusivities are
//!   `chi1 = 17.7e-6` and `chi2 = 0.0859e-6 m²/s` — used here ([`FlashTemperature`]). The
//!   temperature and the friction depend on each other: `dT = r (f_a + f_f(dT))` is solved
//!   by Newton's method (one root, as `f_f` falls with `dT`), so the law stays a
//!   continuous function of the slip.

use crate::seam::fields::{choice, closed, ge, gt, number, table, ANY};
use std::f64::consts::PI;
/// Smallest regularising slip speed of a traction or pocket friction law, m/s. A law
/// `mu(dv) = mu_max tanh(dv/v_s)` with `v_s` below it is a step no integrator resolves:
/// elastic creep alone (Kalker) slips a rolling contact by ~1e-4 of its rolling speed,
/// mm/s at the slowest speeds a bearing model is run at, three orders above this floor.
pub const SLIP_SPEED_MIN: f64 = 1e-6;

/// Where [`tanh`]'s quotient is exactly `1.0` in `f64`.
const TANH_ONE: f64 = 19.0;

/// `tanh(x)` through one `exp` (about twice as fast as `f64::tanh`, which goes through
/// `expm1`): `(1 - e^(-2|x|)) / (1 + e^(-2|x|))` with the sign of `x`, and the odd Taylor
/// series `x - x³/3 + 2x⁵/15` below `|x| = 1e-3` (where the quotient would lose digits).
/// Exactly odd; relative error below `1e-13` everywhere (checked in a unit test).
/// From `|x| = 19` on the quotient is exactly `±1` in `f64` (`e^(-38) ≈ 3.1e-17` is below
/// half an ulp of 1), so it returns `±1` without the `exp`: far beyond the regularising
/// speed, `exp` of a large negative argument went through libm's slow underflow path.
#[inline]
pub fn tanh(x: f64) -> f64 {
    let a = x.abs();
    if a >= TANH_ONE {
        1.0f64.copysign(x)
    } else if a < 1e-3 {
        let x2 = x * x;
        x * (1.0 - x2 * (1.0 / 3.0 - x2 * (2.0 / 15.0)))
    } else {
        let e = (-2.0 * a).exp();
        ((1.0 - e) / (1.0 + e)).copysign(x)
    }
}

/// Contact data a traction law may need. SI units.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactState {
    /// Normal load, N.
    pub q: f64,
    /// Semi-axes `a` (across rolling) and `b` (along rolling), m.
    pub a: f64,
    /// Semi-axis along rolling, m.
    pub b: f64,
    /// Effective radius in the rolling direction, m.
    pub rx: f64,
    /// Ellipticity `a/b`.
    pub kappa: f64,
    /// Effective modulus `E'`, Pa.
    pub e_eff: f64,
}

/// A user-set power law of the asperity load ratio (per cent), an override of
/// [`crate::lubrication::asperity`]: `La = 100 (1 - exp(-La_fit/100))`,
/// `La_fit = c kappa^e_kappa W^e_w U^e_u G^e_g (sigma/Rx)^e_sigma V^e_v`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AsperityFit {
    /// Leading constant.
    pub c: f64,
    /// Exponent of the ellipticity.
    pub e_kappa: f64,
    /// Exponent of the load parameter `W = Q/(E' Rx²)`.
    pub e_w: f64,
    /// Exponent of the speed parameter `U = eta0 u/(E' Rx)`.
    pub e_u: f64,
    /// Exponent of the material parameter `G = alpha_p E'`.
    pub e_g: f64,
    /// Exponent of the roughness `sigma/Rx`.
    pub e_sigma: f64,
    /// Exponent of the hardness ratio `V = H/E'`.
    pub e_v: f64,
}

impl Default for AsperityFit {
    fn default() -> Self {
        // The coefficients this law carried before the shared function; not from a source.
        AsperityFit {
            c: 0.0871,
            e_kappa: 0.0,
            e_w: 0.39,
            e_u: -0.7,
            e_g: -0.59,
            e_sigma: 1.65,
            e_v: 0.0,
        }
    }
}

/// Flash-temperature data of the mixed-EHL law (module notes; study \[2\] and Incropera).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlashTemperature {
    /// Conductivity of body 1 (steel), W/(m K).
    pub k1: f64,
    /// Conductivity of body 2 (oil, as study \[2\] gives it), W/(m K).
    pub k2: f64,
    /// Diffusivity of body 1, m²/s.
    pub chi1: f64,
    /// Diffusivity of body 2, m²/s.
    pub chi2: f64,
    /// Viscosity–temperature coefficient `beta`, 1/K.
    pub beta: f64,
}

impl Default for FlashTemperature {
    fn default() -> Self {
        FlashTemperature {
            k1: 60.5,
            k2: 0.145,
            chi1: 17.7e-6,
            chi2: 0.0859e-6,
            beta: 0.04,
        }
    }
}

impl FlashTemperature {
    /// `dT` of a contact of half-width `b` (along rolling) rolling at `u` under the heat
    /// flux `q` (W/m²), K.
    #[inline]
    pub fn rise(&self, q: f64, b: f64, u: f64) -> f64 {
        let (pe1, pe2) = (
            u.abs() * b / (2.0 * self.chi1),
            u.abs() * b / (2.0 * self.chi2),
        );
        2.0 * b * q / (PI.sqrt() * (self.k1 * (1.0 + pe1).sqrt() + self.k2 * (1.0 + pe2).sqrt()))
    }
}

/// What the mixed-EHL law gives at one contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MixedEhlOut {
    /// Tangential force, N.
    pub force: f64,
    /// Asperity load share, per cent.
    pub la: f64,
    /// Flash temperature rise, K.
    pub flash: f64,
    /// Central film thickness, m.
    pub h_c: f64,
}

/// Lubricant and surface data of the mixed-EHL law.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MixedEhl {
    /// Inlet viscosity `eta0`, Pa s.
    pub viscosity: f64,
    /// Pressure–viscosity coefficient `alpha_p`, 1/Pa.
    pub alpha_p: f64,
    /// Limiting-shear coefficient `Lambda_lim`.
    pub lambda_lim: f64,
    /// Boundary (asperity) friction coefficient `f_c`.
    pub f_c: f64,
    /// Composite RMS roughness `sigma`, m.
    pub roughness: f64,
    /// Hardness, Pa.
    pub hardness: f64,
    /// Regularising slip speed of the asperity share, m/s.
    pub v_s: f64,
    /// Override of the asperity load ratio (absent: [`crate::lubrication::asperity`]).
    pub fit: Option<AsperityFit>,
    /// Reading of the asperity share's restored roughness term (Rust API only).
    #[serde(skip)]
    pub reading: crate::lubrication::asperity::AsperityReading,
    /// Flash-temperature data (Rust API only; study \[2\]'s values).
    #[serde(skip)]
    pub flash: FlashTemperature,
}

impl Default for MixedEhl {
    fn default() -> Self {
        // Study [2]'s lubricant (docs/physics.md §10): 0.04667 Pa s, 2.1e-8 1/Pa, Lambda 0.04,
        // roughness sqrt(0.2² + 0.42²) um, hardness 2.39 GPa.
        MixedEhl {
            viscosity: 0.04667,
            alpha_p: 2.1e-8,
            lambda_lim: 0.04,
            f_c: 0.1,
            roughness: (0.2e-6_f64.powi(2) + 0.42e-6_f64.powi(2)).sqrt(),
            hardness: 2.39e9,
            v_s: 0.01,
            fit: None,
            reading: Default::default(),
            flash: FlashTemperature::default(),
        }
    }
}

impl MixedEhl {
    /// Hamrock–Dowson central film thickness (docs/physics.md §6), m, at entrainment speed `u`.
    pub fn film_thickness(&self, c: &ContactState, u: f64) -> f64 {
        let (uu, g, w) = self.groups(c, u);
        if uu <= 0.0 || w <= 0.0 {
            return 0.0;
        }
        2.69 * uu.powf(0.67)
            * g.powf(0.53)
            * w.powf(-0.067)
            * (1.0 - 0.61 * (-0.73 * c.kappa).exp())
            * c.rx
    }

    fn groups(&self, c: &ContactState, u: f64) -> (f64, f64, f64) {
        let uu = self.viscosity * u.abs() / (c.e_eff * c.rx);
        let g = self.alpha_p * c.e_eff;
        let w = c.q / (c.e_eff * c.rx * c.rx);
        (uu, g, w)
    }

    /// Asperity load ratio `La`, per cent, in `[0, 100]`: the shared function, or the
    /// override `fit`.
    pub fn asperity_load_ratio(&self, c: &ContactState, u: f64) -> f64 {
        let Some(f) = &self.fit else {
            use crate::lubrication::asperity;
            let g = asperity::Groups::new(&asperity::Contact {
                q: c.q,
                u,
                rx: c.rx,
                e_eff: c.e_eff,
                eta0: self.viscosity,
                alpha_p: self.alpha_p,
                sigma: self.roughness,
                h: self.hardness,
                kappa: c.kappa,
            });
            return asperity::asperity_share(&g, self.reading);
        };
        let (uu, g, w) = self.groups(c, u);
        if self.roughness <= 0.0 {
            return 0.0;
        }
        if uu <= 0.0 {
            return 100.0;
        }
        let la = f.c
            * c.kappa.max(1.0).powf(f.e_kappa)
            * w.max(1e-30).powf(f.e_w)
            * uu.powf(f.e_u)
            * g.max(1e-30).powf(f.e_g)
            * (self.roughness / c.rx).powf(f.e_sigma)
            * (self.hardness / c.e_eff).powf(f.e_v);
        if !la.is_finite() {
            return 100.0;
        }
        100.0 * (1.0 - (-la / 100.0).exp())
    }

    /// Force, asperity share, flash temperature and film of one contact at slip `dv` and
    /// rolling speed `u` (module notes). Odd in `dv`.
    pub fn evaluate(&self, dv: f64, u: f64, c: &ContactState) -> MixedEhlOut {
        if c.q <= 0.0 {
            return MixedEhlOut::default();
        }
        let la = self.asperity_load_ratio(c, u);
        let fa = self.f_c * c.q * la / 100.0 * tanh(dv / self.v_s);
        let area = PI * c.a * c.b;
        let h_c = self.film_thickness(c, u);
        let ph = (1.0 - la / 100.0) * c.q / area;
        let film = area > 0.0 && ph > 0.0 && h_c > 0.0;
        let tau_l = self.lambda_lim * ph;
        let barus = (self.alpha_p * ph).min(50.0);
        // Film share at flash temperature dt and its derivative, magnitudes:
        // ff = tau_l A (1 - exp(-k e^(-beta dt))), k = eta(0) |dv| / (tau_l h_c).
        let k = if film {
            self.viscosity * barus.exp() * dv.abs() / (tau_l * h_c)
        } else {
            0.0
        };
        let beta = self.flash.beta;
        let film_force = |dt: f64| {
            if !film {
                return (0.0, 0.0);
            }
            let z = k * (-beta * dt).exp();
            let e = (-z).exp();
            (tau_l * area * -(-z).exp_m1(), -tau_l * area * e * z * beta)
        };
        // dT = r (|f_a| + f_f(dT)), r the rise per newton of friction.
        let r = if area > 0.0 {
            self.flash.rise(dv.abs() / area, c.b, u)
        } else {
            0.0
        };
        // g(dT) = dT - r (|f_a| + f_f(dT)) rises with slope >= 1 (f_f falls with dT): one
        // root, solved to 1e-9 K; converged, the law is continuous in the slip.
        let mut flash = 0.0;
        for _ in 0..50 {
            let (f, df) = film_force(flash);
            let g = flash - r * (fa.abs() + f);
            let step = g / (1.0 - r * df);
            flash = (flash - step).max(0.0);
            if step.abs() <= 1e-9 * (1.0 + flash) {
                break;
            }
        }
        let ff = film_force(flash).0;
        MixedEhlOut {
            force: fa + ff.copysign(dv),
            la,
            flash,
            h_c,
        }
    }
}

/// A traction law (a scene choice).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "law", rename_all = "snake_case", deny_unknown_fields)]
pub enum TractionLaw {
    /// `mu = mu_max tanh(dv / v_s)`.
    Coulomb {
        /// Largest traction coefficient.
        mu_max: f64,
        /// Slip speed of the transition, m/s.
        v_s: f64,
    },
    /// `mu = tanh(s/s_reg) [(A + B|s|) exp(-C|s|) + D]`, `s` the slide-to-roll ratio.
    Fitted {
        /// A.
        a: f64,
        /// B.
        b: f64,
        /// C.
        c: f64,
        /// D.
        d: f64,
        /// Regularising slide-to-roll ratio.
        s_reg: f64,
        /// Smallest rolling speed in `s`, m/s.
        u_min: f64,
    },
    /// Mixed-EHL asperity + film law.
    MixedEhl(MixedEhl),
}

crate::declare_fields!(TractionLaw {
    law => choice(&["coulomb", "fitted", "mixed_ehl"], "traction law at the race contacts")
        .note("the other traction fields belong to one law each"),
    mu_max => number("-", closed(0.0, 2.0), "largest traction coefficient of mu = mu_max tanh(dv/v_s)")
        .note("law = \"coulomb\", required there")
        .why("a traction coefficient; dry steel on steel stays below 1 (the one-hour fuzz run found 5e298 passing the check and failing the static start with no field named)"),
    v_s => number("m/s", ge(SLIP_SPEED_MIN), "regularising slip speed")
        .note("law = \"coulomb\" (required) or \"mixed_ehl\" (default 0.01)")
        .why("a floor no contact creeps below; smaller makes the law a step no integrator resolves"),
    a => number("-", ANY, "A of mu = tanh(s/s_reg) [(A + B|s|) exp(-C|s|) + D]")
        .note("law = \"fitted\", required there"),
    b => number("-", ANY, "B of the fitted law").note("law = \"fitted\", required there"),
    c => number("-", closed(0.0, 1e6), "C of the fitted law").note("law = \"fitted\", required there"),
    d => number("-", ANY, "D of the fitted law").note("law = \"fitted\", required there"),
    s_reg => number("-", gt(0.0), "regularising slide-to-roll ratio")
        .note("law = \"fitted\", required there"),
    u_min => number("m/s", gt(0.0), "smallest rolling speed in the slide-to-roll ratio")
        .note("law = \"fitted\", required there"),
    viscosity => number("Pa s", gt(0.0), "inlet viscosity of the mixed-EHL law")
        .note("law = \"mixed_ehl\" (default 0.04667)"),
    alpha_p => number("1/Pa", closed(0.0, 1e-6), "pressure-viscosity coefficient")
        .note("law = \"mixed_ehl\" (default 2.1e-8)"),
    lambda_lim => number("-", gt(0.0), "limiting-shear coefficient")
        .note("law = \"mixed_ehl\" (default 0.04)"),
    f_c => number("-", closed(0.0, 2.0), "boundary (asperity) friction coefficient")
        .note("law = \"mixed_ehl\" (default 0.1)"),
    roughness => number("m", closed(0.0, 1e-3), "composite rms roughness")
        .note("law = \"mixed_ehl\" (default 4.65e-7)"),
    hardness => number("Pa", gt(0.0), "hardness").note("law = \"mixed_ehl\" (default 2.39e9)"),
    fit => table(),
});

crate::declare_fields!(AsperityFit {
    c => number("-", ANY, "asperity load ratio regression: leading constant").note(MIXED),
    e_kappa => number("-", ANY, "asperity regression: exponent of the ellipticity").note(MIXED),
    e_w => number("-", ANY, "asperity regression: exponent of the load parameter W").note(MIXED),
    e_u => number("-", ANY, "asperity regression: exponent of the speed parameter U").note(MIXED),
    e_g => number("-", ANY, "asperity regression: exponent of the material parameter G").note(MIXED),
    e_sigma => number("-", ANY, "asperity regression: exponent of the roughness sigma/Rx").note(MIXED),
    e_v => number("-", ANY, "asperity regression: exponent of the hardness ratio H/E'").note(MIXED),
});

const MIXED: &str = "law = \"mixed_ehl\"; the whole fit table is an optional override of the shared asperity share (lubrication::asperity)";

impl Default for TractionLaw {
    fn default() -> Self {
        TractionLaw::Coulomb {
            mu_max: 0.05,
            v_s: 0.05,
        }
    }
}

impl TractionLaw {
    /// Check the coefficients against [`TractionLaw::FIELDS`]; errors name
    /// `field.<coefficient>`.
    pub fn validate(&self, field: &str) -> crate::error::Result<()> {
        use crate::seam::fields::check;
        check(field, Self::FIELDS, self)?;
        if let TractionLaw::MixedEhl(m) = self {
            check(&format!("{field}.fit"), AsperityFit::FIELDS, &m.fit)?;
        }
        Ok(())
    }

    /// Does the law use the contact's semi-axes, radius and modulus (or only the load)?
    pub fn needs_contact(&self) -> bool {
        matches!(self, TractionLaw::MixedEhl(_))
    }

    /// Tangential force, N, for slip `dv` (m/s), rolling speed `u` (m/s) and contact `c`.
    /// Odd in `dv`, zero when the contact carries no load.
    pub fn force(&self, dv: f64, u: f64, c: &ContactState) -> f64 {
        if c.q <= 0.0 {
            return 0.0;
        }
        match *self {
            TractionLaw::Coulomb { mu_max, v_s } => mu_max * tanh(dv / v_s) * c.q,
            TractionLaw::Fitted {
                a,
                b,
                c: cc,
                d,
                s_reg,
                u_min,
            } => {
                let s = dv / (u * u + u_min * u_min).sqrt();
                let sa = s.abs();
                (s / s_reg).tanh() * ((a + b * sa) * (-cc * sa).exp() + d) * c.q
            }
            TractionLaw::MixedEhl(m) => m.evaluate(dv, u, c).force,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The early return beyond `|x| = 19` gives the quotient's own bits: `(1 - e)/(1 + e)`
    /// with `e = exp(-2|x|)` is exactly 1 there, and also just below the threshold the
    /// quotient already rounds to 1 (from about 18.72), so moving the threshold down to
    /// 18.8 would still be bit for bit; 18.7 would not.
    #[test]
    fn tanh_early_return_is_the_quotients_bits() {
        let quotient = |x: f64| {
            let e = (-2.0 * x.abs()).exp();
            ((1.0 - e) / (1.0 + e)).copysign(x)
        };
        let mut x = 18.0;
        while x < 800.0 {
            for s in [x, -x] {
                assert_eq!(tanh(s).to_bits(), quotient(s).to_bits(), "x = {s}");
            }
            x *= 1.0 + 1e-4;
        }
        assert_eq!(quotient(18.8), 1.0);
        assert!(quotient(18.7) < 1.0);
        assert_eq!(tanh(f64::INFINITY), 1.0);
        assert_eq!(tanh(-1e300), -1.0);
    }

    fn contact() -> ContactState {
        ContactState {
            q: 200.0,
            a: 1.2e-3,
            b: 0.15e-3,
            rx: 4.5e-3,
            kappa: 8.0,
            e_eff: 2.28e11,
        }
    }

    #[test]
    fn laws_are_odd_and_continuous_through_zero() {
        let c = contact();
        let laws = [
            TractionLaw::default(),
            TractionLaw::Fitted {
                a: -0.0103,
                b: 1.1677,
                c: 13.0,
                d: 0.0103,
                s_reg: 1e-3,
                u_min: 0.01,
            },
            TractionLaw::MixedEhl(MixedEhl::default()),
        ];
        for law in laws {
            for dv in [1e-3, 0.1, 2.0] {
                let (fp, fm) = (law.force(dv, 5.0, &c), law.force(-dv, 5.0, &c));
                assert!((fp + fm).abs() < 1e-12 * fp.abs(), "{law:?} odd");
                assert!(fp > 0.0, "{law:?} drives the slower surface");
            }
            let tiny = law.force(1e-12, 5.0, &c);
            assert!(tiny.abs() < 1e-6, "{law:?} continuous at 0: {tiny}");
        }
    }

    /// The fast `tanh` against the library's, over twenty decades and both signs.
    #[test]
    fn fast_tanh_matches_the_library() {
        let mut worst: f64 = 0.0;
        for k in 0..=4000 {
            let x = 10f64.powf(-16.0 + 18.0 * k as f64 / 4000.0);
            for s in [x, -x] {
                let (a, b) = (tanh(s), s.tanh());
                assert_eq!(tanh(-s), -a, "odd");
                worst = worst.max(((a - b) / b).abs());
            }
        }
        assert!(worst < 1e-13, "{worst:e}");
        assert_eq!(tanh(0.0), 0.0);
        assert_eq!(tanh(800.0), 1.0);
    }

    #[test]
    fn coulomb_saturates_at_mu_max() {
        let c = contact();
        let f = TractionLaw::Coulomb {
            mu_max: 0.07,
            v_s: 0.05,
        }
        .force(5.0, 5.0, &c);
        assert!((f / c.q - 0.07).abs() < 1e-12);
    }

    /// Smooth surfaces carry no asperity load; with no film (no entrainment) the
    /// asperities carry it all; rougher surfaces or slower rolling raise the share.
    #[test]
    fn asperity_load_ratio_limits() {
        let c = contact();
        let mut m = MixedEhl::default();
        let la = m.asperity_load_ratio(&c, 5.0);
        assert!(la > 0.0 && la < 100.0, "{la}");
        assert!(m.asperity_load_ratio(&c, 0.5) > la, "slower: thinner film");
        assert_eq!(m.asperity_load_ratio(&c, 0.0), 100.0);
        let l9 = m.asperity_load_ratio(&c, 1e-13);
        assert!(l9 > 99.9, "{l9} {la}");
        m.roughness = 1e-12;
        assert!(m.asperity_load_ratio(&c, 5.0) < 1e-6);
        m.roughness = 0.0;
        assert_eq!(m.asperity_load_ratio(&c, 5.0), 0.0);
        // Dry (La = 100): pure boundary friction f_c Q at large slip.
        let dry = MixedEhl {
            roughness: 1e-3,
            ..MixedEhl::default()
        };
        let f = TractionLaw::MixedEhl(dry).force(10.0, 1e-12, &c);
        assert!((f / c.q - dry.f_c).abs() < 1e-6, "{}", f / c.q);
    }

    /// With smooth surfaces the film share saturates at the limiting shear `Lambda_lim Q`.
    #[test]
    fn film_share_saturates_at_limiting_shear() {
        let c = contact();
        let m = MixedEhl {
            roughness: 0.0,
            ..MixedEhl::default()
        };
        let f = TractionLaw::MixedEhl(m).force(50.0, 5.0, &c);
        assert!((f / c.q - m.lambda_lim).abs() < 1e-3, "{}", f / c.q);
    }

    /// The flash temperature: zero without slip, the stationary-source limit
    /// `2 b q / (sqrt(pi) (k1 + k2))` at zero Péclet number, falling with rolling speed;
    /// a hotter film carries less shear below the limiting stress.
    #[test]
    fn flash_temperature_limits() {
        let f = FlashTemperature::default();
        let (q, b) = (1e8, 0.15e-3);
        let still = f.rise(q, b, 0.0);
        let want = 2.0 * b * q / (PI.sqrt() * (f.k1 + f.k2));
        assert!((still - want).abs() < 1e-12 * want);
        assert!(f.rise(q, b, 5.0) < still);
        let c = contact();
        let m = MixedEhl {
            roughness: 0.0,
            ..MixedEhl::default()
        };
        assert_eq!(m.evaluate(0.0, 5.0, &c).flash, 0.0);
        let hot = m.evaluate(0.05, 5.0, &c);
        let cold = MixedEhl {
            flash: FlashTemperature {
                beta: 0.0,
                ..FlashTemperature::default()
            },
            ..m
        }
        .evaluate(0.05, 5.0, &c);
        assert!(
            hot.flash > 0.0 && hot.force < cold.force,
            "{hot:?} {cold:?}"
        );
    }

    /// The user-set power law still overrides the shared function.
    #[test]
    fn fit_overrides_the_shared_share() {
        let c = contact();
        let shared = MixedEhl::default();
        let over = MixedEhl {
            fit: Some(AsperityFit::default()),
            ..shared
        };
        let (a, b) = (
            shared.asperity_load_ratio(&c, 5.0),
            over.asperity_load_ratio(&c, 5.0),
        );
        assert!(a != b && a > 0.0 && b > 0.0, "{a} {b}");
        use crate::lubrication::asperity;
        let g = asperity::Groups::new(&asperity::Contact {
            q: c.q,
            u: 5.0,
            rx: c.rx,
            e_eff: c.e_eff,
            eta0: shared.viscosity,
            alpha_p: shared.alpha_p,
            sigma: shared.roughness,
            h: shared.hardness,
            kappa: c.kappa,
        });
        assert_eq!(
            a,
            crate::lubrication::asperity::asperity_share(&g, shared.reading)
        );
    }
}
