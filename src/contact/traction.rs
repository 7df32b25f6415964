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
//! - **The 4109 fit** (`fitted_4109`, [`Fit4109`]): the same curve with A–D computed at each
//!   contact from its load, rolling speed and the oil temperature, the power laws Wang, Yang,
//!   Wang and Zheng's group fitted for the aviation oil 4109, the sister of the 4106 whose
//!   fit study \[0\] uses (that one was not found). **A substitute for 4106, coefficients
//!   from public code** (two MATLAB repositories of one author, `oil_coe_model.m`; medium
//!   confidence): with `W = Q/(E' R²)`, `U = eta0 u/(E' R)`, `Tb = T sqrt(K eta0 beta)/(E' R)`,
//!   the critical load `WF = 7.956015e12 Tb² + 5553.09 Tb + 1.758455e-6`, `e = |WF/W - 1|`:
//!   `A = -4.793526e-8 W^(0.0068361 e) U^-0.4047492 Tb^-0.1833848`,
//!   `B = 8.37449e-15 W^(0.01409715 e) U^-0.5868325 Tb^-0.8173636`,
//!   `C = 1.180823e-4 W^(0.006321 e) U^-0.20617 Tb^-0.3631740`, `D = -A`. Open questions
//!   (stated in `scene --explain` and docs/physics.md §5.2): whether `T` is in °C (as coded,
//!   used here) or K; which radius `R` is (the contact's rolling-direction `Rx` here; one script
//!   uses a 10 mm test ball); whether `eta0` follows the inlet temperature (here: as given,
//!   or MIL-L-7808's at `T` with `oil = "mil_l_7808"`). `form = "constant"` is instead the
//!   fixed set `A = -0.0196, B = 0.39873, C = 39.002, D = 0.01984` of a legacy program in public
//!   code (conditions not stated; within a few per cent of the power laws at 25 °C and 30 m/s).
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

use crate::seam::fields::{between, choice, closed, ge, gt, number, table, ANY};
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

/// `ca` of `a = ca Q^(1/3)` from a contact's state (0 unloaded: the line-contact reading of
/// the asperity share is then 0, its own limit as the load vanishes).
fn semi_axis_coefficient(c: &ContactState) -> f64 {
    if c.q > 0.0 && c.a > 0.0 {
        c.a / c.q.cbrt()
    } else {
        0.0
    }
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
    /// Central film thickness formula of the film share.
    pub film_formula: FilmFormula,
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
            film_formula: FilmFormula::HamrockDowson,
            reading: Default::default(),
            flash: FlashTemperature::default(),
        }
    }
}

/// Central film thickness formula of the mixed-EHL law's film share.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FilmFormula {
    /// Hamrock–Dowson, smooth surfaces (docs/physics.md §6).
    #[default]
    HamrockDowson,
    /// Masjedi–Khonsari with roughness ([`crate::lubrication::rough_film`]; public code,
    /// medium confidence).
    MasjediKhonsari,
}

impl MixedEhl {
    /// Central film thickness, m, at entrainment speed `u`: Hamrock–Dowson (docs/physics.md
    /// §6) or, with [`FilmFormula::MasjediKhonsari`], Masjedi–Khonsari's with the roughness
    /// (§6.3).
    pub fn film_thickness(&self, c: &ContactState, u: f64) -> f64 {
        let (uu, g, w) = self.groups(c, u);
        if uu <= 0.0 || w <= 0.0 {
            return 0.0;
        }
        if self.film_formula == FilmFormula::MasjediKhonsari {
            use crate::lubrication::rough_film::{central, RoughGroups};
            return central(&RoughGroups {
                w,
                u: uu,
                g,
                kappa: c.kappa,
                sigma_b: self.roughness / c.rx,
                v: self.hardness / c.e_eff,
            }) * c.rx;
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
                ca: if self.reading == asperity::AsperityReading::LineContact {
                    semi_axis_coefficient(c)
                } else {
                    0.0
                },
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

/// Which A–D the 4109 law uses (module notes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Form4109 {
    /// A–D from load, speed and temperature (the power laws).
    #[default]
    PowerLaw,
    /// The fixed set of the legacy program.
    Constant,
}

/// Where the 4109 law's oil data (`eta0`, `beta`, `K`) come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Oil4109 {
    /// The values coded beside the fit: 0.033 Pa s, 0.0215 1/K, 0.0966 W/(m K).
    #[default]
    Code,
    /// MIL-L-7808 at `temperature_c` ([`crate::lubrication::oils`]).
    #[serde(rename = "mil_l_7808")]
    MilL7808,
}

/// The 4109 fit (module notes): "4109 substitute for 4106, coefficients from public code".
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Fit4109 {
    /// Power laws or the constant set.
    pub form: Form4109,
    /// Oil temperature `T` of the fit's temperature group, °C (as coded; open question).
    pub temperature_c: Option<f64>,
    /// Source of `eta0`, `beta`, `K`.
    pub oil: Oil4109,
    /// Override of `eta0`, Pa s.
    pub viscosity: Option<f64>,
    /// Override of the viscosity–temperature coefficient `beta`, 1/K.
    pub beta: Option<f64>,
    /// Override of the oil conductivity `K`, W/(m K).
    pub conductivity: Option<f64>,
    /// Regularising slide-to-roll ratio.
    pub s_reg: f64,
    /// Smallest rolling speed in `s` and in `U`, m/s.
    pub u_min: f64,
}

impl Default for Fit4109 {
    fn default() -> Self {
        Fit4109 {
            form: Form4109::PowerLaw,
            temperature_c: None,
            oil: Oil4109::Code,
            viscosity: None,
            beta: None,
            conductivity: None,
            s_reg: 1e-3,
            u_min: 0.1,
        }
    }
}

/// Label of the 4109 presets (scene notes, docs, reports).
pub const FIT_4109_LABEL: &str =
    "4109 substitute for 4106, coefficients from public code (medium confidence)";

/// The legacy program's constant set `[A, B, C, D]` (public code; conditions not stated).
pub const CONSTANT_4109: [f64; 4] = [-0.0196, 0.39873, 39.002, 0.01984];

/// `eta0` (Pa s), `beta` (1/K) and `K` (W/(m K)) coded beside the 4109 fit.
pub const OIL_4109_CODE: [f64; 3] = [0.033, 0.0215, 0.0966];

impl Fit4109 {
    /// `eta0`, `beta`, `K` the fit uses (module notes); `field` names the temperature in an
    /// error (MIL-L-7808 outside its tables).
    pub fn oil_data(&self, field: &str) -> crate::error::Result<[f64; 3]> {
        let mut p = OIL_4109_CODE;
        if self.oil == Oil4109::MilL7808 {
            let t = self.temperature_c.unwrap_or(f64::NAN);
            let o = crate::lubrication::oils::mil_l_7808(t + 273.15, field)?;
            p = [o.viscosity, o.viscosity_temperature, o.conductivity];
        }
        for (slot, v) in p
            .iter_mut()
            .zip([self.viscosity, self.beta, self.conductivity])
        {
            if let Some(v) = v {
                *slot = v;
            }
        }
        Ok(p)
    }

    /// `[A, B, C, D]` at load `q` (N), rolling speed `u` (m/s, floored as in the law by
    /// `u_min`), radius `rx` (m) and modulus `e_eff` (Pa) with the oil data `[eta0, beta, K]`.
    pub fn coefficients(&self, q: f64, u: f64, rx: f64, e_eff: f64, oil: [f64; 3]) -> [f64; 4] {
        if self.form == Form4109::Constant {
            return CONSTANT_4109;
        }
        let [eta0, beta, k] = oil;
        let t = self.temperature_c.unwrap_or(f64::NAN);
        let er = e_eff * rx;
        let w = q / (er * rx);
        let uu = eta0 * (u * u + self.u_min * self.u_min).sqrt() / er;
        let tb = t * (k * eta0 * beta).sqrt() / er;
        let wf = 7.956015e12 * tb * tb + 5553.09 * tb + 1.758455e-6;
        let e = (wf / w - 1.0).abs();
        let (lw, lu, lt) = (w.ln(), uu.ln(), tb.ln());
        let term =
            |c0: f64, ew: f64, eu: f64, et: f64| c0 * (ew * e * lw + eu * lu + et * lt).exp();
        let a = -term(4.793526e-8, 0.0068361, -0.4047492, -0.1833848);
        let b = term(8.37449e-15, 0.01409715, -0.5868325, -0.8173636);
        let c = term(1.180823e-4, 0.006321, -0.20617, -0.3631740);
        [a, b, c, -a]
    }

    /// Traction coefficient `tanh(s/s_reg) [(A + B|s|) exp(-C|s|) + D]` at slide-to-roll
    /// ratio `s` with the coefficients `abcd`.
    pub fn mu(&self, s: f64, abcd: [f64; 4]) -> f64 {
        let [a, b, c, d] = abcd;
        let sa = s.abs();
        tanh(s / self.s_reg) * ((a + b * sa) * (-c * sa).exp() + d)
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
    /// The fitted curve with the 4109 A–D (module notes; a substitute for study \[0\]'s 4106).
    #[serde(rename = "fitted_4109")]
    Fitted4109(Fit4109),
}

crate::declare_fields!(TractionLaw {
    law => choice(&["coulomb", "fitted", "mixed_ehl", "fitted_4109"], "traction law at the race contacts")
        .note("the other traction fields belong to one law each; fitted_4109: mu = (A + B s) exp(-C s) + D of the slide-to-roll ratio s with A-D of the aviation oil 4109, a 4109 substitute for 4106 (study [0]'s oil fit, not found), coefficients from public code, medium confidence"),
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
        .note("law = \"fitted\" (required) or \"fitted_4109\" (default 0.001)"),
    u_min => number("m/s", gt(0.0), "smallest rolling speed in the slide-to-roll ratio")
        .note("law = \"fitted\" (required) or \"fitted_4109\" (default 0.1, also in its speed group U)"),
    viscosity => number("Pa s", gt(0.0), "inlet viscosity of the mixed-EHL law, or eta0 of the 4109 fit")
        .note("law = \"mixed_ehl\" (default 0.04667) or \"fitted_4109\" (default 0.033, the value coded beside the fit, or MIL-L-7808's at temperature_c with oil = \"mil_l_7808\"; open question: whether eta0 follows the inlet temperature)"),
    form => choice(&["power_law", "constant"], "4109 fit: A-D from load, speed and temperature (power_law) or the fixed set A -0.0196, B 0.39873, C 39.002, D 0.01984 (constant)")
        .note("law = \"fitted_4109\" (default power_law); both: 4109 substitute for 4106, coefficients from public code, medium confidence"),
    temperature_c => number("°C", between(0.0, false, 300.0, true), "4109 fit: oil temperature T of the group Tb = T sqrt(K eta0 beta)/(E' R), R the contact's rolling-direction radius Rx")
        .note("law = \"fitted_4109\", required with form = \"power_law\" or oil = \"mil_l_7808\" (then in [37.85, 204.85]); open questions: the public code puts T in °C, as here, not K (in K the coefficients change several-fold); R is Rx here, a 10 mm test ball in one script"),
    oil => choice(&["code", "mil_l_7808"], "4109 fit: eta0, beta and K as coded beside the fit (0.033 Pa s, 0.0215 1/K, 0.0966 W/(m K)) or MIL-L-7808's at temperature_c")
        .note("law = \"fitted_4109\" (default code); viscosity, beta, conductivity override either"),
    beta => number("1/K", gt(0.0), "4109 fit: viscosity-temperature coefficient beta")
        .note("law = \"fitted_4109\" (default: from oil)"),
    conductivity => number("W/(m K)", gt(0.0), "4109 fit: oil thermal conductivity K")
        .note("law = \"fitted_4109\" (default: from oil)"),
    alpha_p => number("1/Pa", closed(0.0, 1e-6), "pressure-viscosity coefficient")
        .note("law = \"mixed_ehl\" (default 2.1e-8)"),
    lambda_lim => number("-", gt(0.0), "limiting-shear coefficient")
        .note("law = \"mixed_ehl\" (default 0.04)"),
    f_c => number("-", closed(0.0, 2.0), "boundary (asperity) friction coefficient")
        .note("law = \"mixed_ehl\" (default 0.1)"),
    roughness => number("m", closed(0.0, 1e-3), "composite rms roughness")
        .note("law = \"mixed_ehl\" (default 4.65e-7)"),
    hardness => number("Pa", gt(0.0), "hardness").note("law = \"mixed_ehl\" (default 2.39e9)"),
    film_formula => choice(&["hamrock_dowson", "masjedi_khonsari"], "central film thickness of the film share: Hamrock-Dowson (smooth) or Masjedi-Khonsari with the roughness")
        .note("law = \"mixed_ehl\" (default hamrock_dowson); masjedi_khonsari: point-contact formula from public code, medium confidence; open questions: the sign of W's exponent in its roughness bracket and whether U divides by E' Rx (here) or 2 E' Rx (the code)"),
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
        if let TractionLaw::Fitted4109(f) = self {
            let t = format!("{field}.temperature_c");
            let needs_t = f.form == Form4109::PowerLaw || f.oil == Oil4109::MilL7808;
            if needs_t && f.temperature_c.is_none() {
                return Err(crate::Error::invalid(
                    t,
                    "absent",
                    "given (°C) with form = \"power_law\" or oil = \"mil_l_7808\"",
                ));
            }
            f.oil_data(&t)?;
        }
        Ok(())
    }

    /// Does the law use the contact's semi-axes, radius and modulus (or only the load)?
    pub fn needs_contact(&self) -> bool {
        match self {
            TractionLaw::MixedEhl(_) => true,
            TractionLaw::Fitted4109(f) => f.form == Form4109::PowerLaw,
            _ => false,
        }
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
            TractionLaw::Fitted4109(f) => {
                // Validated laws have their oil data; a law that was not falls back to the
                // coded values rather than failing inside the dynamics.
                let oil = f.oil_data("temperature_c").unwrap_or(OIL_4109_CODE);
                let abcd = f.coefficients(c.q, u, c.rx, c.e_eff, oil);
                let s = dv / (u * u + f.u_min * f.u_min).sqrt();
                let mu = f.mu(s, abcd);
                if mu.is_finite() {
                    mu * c.q
                } else {
                    0.0
                }
            }
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
            TractionLaw::Fitted4109(Fit4109 {
                temperature_c: Some(60.0),
                ..Default::default()
            }),
            TractionLaw::Fitted4109(Fit4109 {
                form: Form4109::Constant,
                ..Default::default()
            }),
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
            ca: semi_axis_coefficient(&c),
        });
        assert_eq!(
            a,
            crate::lubrication::asperity::asperity_share(&g, shared.reading)
        );
    }

    /// The brief's derived check of the 4109 power laws (Q 29 N, R 10 mm, u 30 m/s, E'
    /// 2.26e11 Pa, the coded oil data): at 25 °C A = -0.0189, B = 0.356, C = 41.4, D = 0.0189
    /// to the printed digits, and the limiting coefficient D falls to 0.011 at 125 °C.
    #[test]
    fn fit_4109_reproduces_the_derived_check() {
        let at = |t: f64| {
            Fit4109 {
                temperature_c: Some(t),
                ..Default::default()
            }
            .coefficients(29.0, 30.0, 0.01, 2.26e11, OIL_4109_CODE)
        };
        let [a, b, c, d] = at(25.0);
        // u_min 0.1 m/s in sqrt(u² + u_min²) moves U by 6e-6 relative: below the digits.
        assert!((a + 0.0189).abs() < 0.00005, "{a}");
        assert!((b - 0.356).abs() < 0.0005, "{b}");
        assert!((c - 41.4).abs() < 0.05, "{c}");
        assert_eq!(d, -a);
        let d125 = at(125.0)[3];
        assert!((d125 - 0.011).abs() < 0.0005, "{d125}");
    }

    /// The curve's limits: `A + D` as `s -> 0` beyond the regularisation (0 for the power
    /// laws, whose `D = -A`), `D` as `s -> inf`, its only maximum at `s* = 1/C - A/B`, odd in
    /// `s` and continuous (no step larger than the slope allows on a fine grid). The constant
    /// set peaks near 0.020 at s about 0.075 and tends to 0.0198, as the brief says.
    #[test]
    fn fit_4109_limits_continuity_and_sign() {
        let f = Fit4109 {
            temperature_c: Some(25.0),
            s_reg: 1e-9,
            ..Default::default()
        };
        for abcd in [
            f.coefficients(29.0, 30.0, 0.01, 2.26e11, OIL_4109_CODE),
            CONSTANT_4109,
        ] {
            let [a, b, c, d] = abcd;
            let near0 = f.mu(1e-7, abcd);
            assert!(
                (near0 - (a + d)).abs() < 1e-6 * b.abs().max(1.0),
                "{near0} {}",
                a + d
            );
            assert!((f.mu(1e3 / c, abcd) - d).abs() < 1e-12);
            let s_star = 1.0 / c - a / b;
            let peak = f.mu(s_star, abcd);
            for k in 1..=2000 {
                let s = 1e-4 * k as f64;
                let m = f.mu(s, abcd);
                assert!(m <= peak + 1e-15, "s {s}: {m} above the peak {peak}");
                assert_eq!(f.mu(-s, abcd), -m, "odd");
                let step = (f.mu(s + 1e-7, abcd) - m).abs();
                assert!(step < 1e-7 * (b + a.abs() * c + 1.0), "continuous at {s}");
            }
        }
        let [a, b, c, d] = CONSTANT_4109;
        let s_star = 1.0 / c - a / b;
        assert!((s_star - 0.075).abs() < 0.005, "{s_star}");
        let peak = f.mu(s_star, CONSTANT_4109);
        assert!((peak - 0.020).abs() < 0.0005, "{peak}");
        assert!((a + d).abs() < 3e-4 && d > 0.0198);
        // The law through force(): the coefficient times the load, odd in the slip.
        let law = TractionLaw::Fitted4109(f);
        let cs = ContactState {
            q: 29.0,
            rx: 0.01,
            e_eff: 2.26e11,
            ..contact()
        };
        let s = 0.05;
        let fp = law.force(s * 30.0, 30.0, &cs);
        let abcd = f.coefficients(29.0, 30.0, 0.01, 2.26e11, OIL_4109_CODE);
        assert!((fp / 29.0 - f.mu(s * 30.0 / (900.0f64 + 0.01).sqrt(), abcd)).abs() < 1e-15);
        assert_eq!(law.force(-s * 30.0, 30.0, &cs), -fp);
    }

    /// The 4109 law's scene checks: the power laws need the temperature; MIL-L-7808 data
    /// only within its tables; explicit oil data override the preset's; only the power laws
    /// need the contact's radius and modulus; finite down to rest.
    #[test]
    fn fit_4109_checks_and_oil_data() {
        let bare = TractionLaw::Fitted4109(Fit4109::default());
        let e = bare
            .validate("model.full.traction")
            .unwrap_err()
            .to_string();
        assert!(e.contains("model.full.traction.temperature_c"), "{e}");
        let constant = Fit4109 {
            form: Form4109::Constant,
            ..Default::default()
        };
        assert!(TractionLaw::Fitted4109(constant).validate("t").is_ok());
        assert!(!TractionLaw::Fitted4109(constant).needs_contact());
        let cold = Fit4109 {
            temperature_c: Some(20.0),
            oil: Oil4109::MilL7808,
            ..Default::default()
        };
        assert!(TractionLaw::Fitted4109(cold).validate("t").is_err());
        let warm = Fit4109 {
            temperature_c: Some(100.0),
            ..cold
        };
        let law = TractionLaw::Fitted4109(warm);
        assert!(law.validate("t").is_ok() && law.needs_contact());
        let [eta, beta, k] = warm.oil_data("t").unwrap();
        assert!((eta - 2.87e-3).abs() < 0.01e-3 && beta > 0.0 && (k - 0.1336).abs() < 1e-3);
        let over = Fit4109 {
            viscosity: Some(0.02),
            ..warm
        };
        assert_eq!(over.oil_data("t").unwrap()[0], 0.02);
        let cs = contact();
        for u in [0.0, 1e-9, 1e-3, 1.0, 100.0] {
            for dv in [-1.0, 0.0, 1e-6, 0.3] {
                let f = law.force(dv, u, &cs);
                assert!(f.is_finite(), "u {u} dv {dv}");
            }
        }
    }

    /// The film-thickness option: Masjedi–Khonsari equals Hamrock–Dowson's form on smooth
    /// surfaces to the fits' difference (a few per cent), is thicker with roughness, and the
    /// thicker film carries less film shear at the same slip.
    #[test]
    fn masjedi_khonsari_film_option() {
        let c = contact();
        let hd = MixedEhl::default();
        let mk = MixedEhl {
            film_formula: FilmFormula::MasjediKhonsari,
            ..hd
        };
        let smooth = |m: MixedEhl| MixedEhl {
            roughness: 0.0,
            ..m
        };
        let r0 = smooth(mk).film_thickness(&c, 5.0) / smooth(hd).film_thickness(&c, 5.0);
        assert!((r0 - 1.0).abs() < 0.05, "{r0}");
        assert!(mk.film_thickness(&c, 5.0) > smooth(mk).film_thickness(&c, 5.0));
        assert_eq!(
            hd.film_thickness(&c, 5.0),
            smooth(hd).film_thickness(&c, 5.0)
        );
        let (a, b) = (
            smooth(hd),
            MixedEhl {
                roughness: 0.0,
                ..mk
            },
        );
        let fa = TractionLaw::MixedEhl(a).force(1e-3, 5.0, &c);
        let fb = TractionLaw::MixedEhl(b).force(1e-3, 5.0, &c);
        assert!((fb / fa - 1.0).abs() < 0.05, "{fa} {fb}");
        let f_rough = TractionLaw::MixedEhl(MixedEhl { f_c: 0.0, ..mk }).force(1e-3, 5.0, &c);
        let f_hd = TractionLaw::MixedEhl(MixedEhl { f_c: 0.0, ..hd }).force(1e-3, 5.0, &c);
        assert!(f_rough < f_hd, "{f_rough} {f_hd}");
        assert_eq!(TractionLaw::MixedEhl(mk).force(0.0, 5.0, &c), 0.0);
    }
}
