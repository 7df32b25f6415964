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
use serde::{Deserialize, Serialize};
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

/// What a profile needs to know about the roller and the contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LineGeometry {
    /// Effective roller length `Lwe`, m.
    pub lwe: f64,
    /// Roller (mean) diameter `Dwe`, m.
    pub dwe: f64,
    /// Pair modulus `E'` of the roller–race contacts, Pa.
    pub e_prime: f64,
    /// A tapered roller (ISO/TS 16281's logarithmic profile takes another coefficient).
    pub tapered: bool,
}

/// Roller profile: the drop `P(x)` of one roller surface from the cylinder (or cone) at `x`
/// from mid-length. SI.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Profile {
    /// Straight roller: `P = 0` (edge loading under tilt).
    None,
    /// Circular crown of radius `radius` (m) over the whole length: `P = x²/(2 R)`.
    Crown {
        /// Crown radius, m.
        radius: f64,
    },
    /// Straight centre of length `flat` (m), circular crown of radius `radius` (m) outside it:
    /// `P = (|x| - flat/2)²/(2 R)` for `|x| > flat/2`.
    PartialCrown {
        /// Length of the straight centre, m.
        flat: f64,
        /// Crown radius, m.
        radius: f64,
    },
    /// The logarithmic profile ISO/TS 16281:2008 prescribes when the real one is unknown:
    /// cylindrical rollers with `Lwe ≤ 2.5 Dwe`: `P = 0.00035 Dwe ln(1/(1 - (2x/Lwe)²))`;
    /// cylindrical rollers with `Lwe > 2.5 Dwe`: straight over `|x| ≤ (Lwe - 2.5 Dwe)/2`, then
    /// `P = 0.0005 Dwe ln(1/(1 - ((2|x| - Lwe + 2.5 Dwe)/(2.5 Dwe))²))`; tapered rollers:
    /// `P = 0.00045 Dwe ln(1/(1 - (2x/Lwe)²))`.
    IsoLog,
    /// Lundberg's logarithmic profile for a design roller load `design_load` (N), which makes
    /// the pressure uniform along an aligned roller at that load ([Lundberg 1939]; [Harris 2007]
    /// vol. 2 ch. 1): `P = (2 Q_d/(pi Lwe E')) ln(1/(1 - (2x/Lwe)²))`.
    Lundberg {
        /// Design roller load `Q_d`, N.
        design_load: f64,
    },
    /// Fujiwara–Kawase's modified logarithmic profile ([Fujiwara 2007], eq. of the profile):
    /// `P = A ln(1/(1 - (1 - exp(-z_m/A)) u²))`, `A = 2 K1 Q_d/(pi Lwe E')`,
    /// `u = (|x| - (1 - K2) Lwe/2)/(K2 Lwe/2)` on the crowned part (`u > 0`), straight inside
    /// it. `K1` scales the design load, `K2` is the crowned share of the half-length, `z_m` the
    /// drop at the end of the effective length (finite, unlike Lundberg's).
    FujiwaraKawase {
        /// Design roller load `Q_d`, N.
        design_load: f64,
        /// Load factor `K1` (> 0).
        k1: f64,
        /// Crowned share of the half-length `K2`, in (0, 1].
        k2: f64,
        /// Drop at the end of the effective length `z_m`, m.
        end_drop: f64,
    },
}

/// `ln(1/(1 - u²))` for `|u| < 1`.
fn log_drop(u: f64) -> f64 {
    -(1.0 - u * u).ln()
}

impl Profile {
    /// The drop `P(x)` (m) of one roller surface at `x` (m) from mid-length; `+inf` at and
    /// beyond the chamfer `|x| ≥ Lwe/2` (no contact there).
    pub fn drop(&self, x: f64, g: &LineGeometry) -> f64 {
        let h = 0.5 * g.lwe;
        let ax = x.abs();
        if ax >= h || ax.is_nan() {
            return f64::INFINITY;
        }
        match *self {
            Profile::None => 0.0,
            Profile::Crown { radius } => x * x / (2.0 * radius),
            Profile::PartialCrown { flat, radius } => {
                let e = (ax - 0.5 * flat).max(0.0);
                e * e / (2.0 * radius)
            }
            Profile::IsoLog => {
                if g.tapered {
                    0.00045 * g.dwe * log_drop(ax / h)
                } else if g.lwe <= 2.5 * g.dwe {
                    0.00035 * g.dwe * log_drop(ax / h)
                } else {
                    let start = 0.5 * (g.lwe - 2.5 * g.dwe);
                    if ax <= start {
                        0.0
                    } else {
                        0.0005 * g.dwe * log_drop((ax - start) / (1.25 * g.dwe))
                    }
                }
            }
            Profile::Lundberg { design_load } => {
                2.0 * design_load / (PI * g.lwe * g.e_prime) * log_drop(ax / h)
            }
            Profile::FujiwaraKawase {
                design_load,
                k1,
                k2,
                end_drop,
            } => {
                let start = (1.0 - k2) * h;
                if ax <= start {
                    return 0.0;
                }
                let u = (ax - start) / (k2 * h);
                let a = 2.0 * k1 * design_load / (PI * g.lwe * g.e_prime);
                let c = -(-end_drop / a).exp_m1(); // 1 - exp(-z_m/A), accurate for small z_m/A
                -a * (1.0 - c * u * u).ln()
            }
        }
    }

    /// Check the parameters; errors name `field.<parameter>` and a range that can be met.
    pub fn validate(&self, field: &str, g: &LineGeometry) -> Result<()> {
        let pos = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(Error::invalid(
                    format!("{field}.{name}"),
                    v,
                    "a finite number > 0",
                ))
            }
        };
        match *self {
            Profile::None | Profile::IsoLog => Ok(()),
            Profile::Crown { radius } => pos("radius", radius),
            Profile::PartialCrown { flat, radius } => {
                pos("radius", radius)?;
                if !(flat.is_finite() && flat >= 0.0 && flat < g.lwe) {
                    return Err(Error::invalid(
                        format!("{field}.flat"),
                        flat,
                        format!("in [0, {:e}) m (shorter than the effective length)", g.lwe),
                    ));
                }
                Ok(())
            }
            Profile::Lundberg { design_load } => pos("design_load", design_load),
            Profile::FujiwaraKawase {
                design_load,
                k1,
                k2,
                end_drop,
            } => {
                pos("design_load", design_load)?;
                pos("k1", k1)?;
                pos("end_drop", end_drop)?;
                if !(k2.is_finite() && k2 > 0.0 && k2 <= 1.0) {
                    return Err(Error::invalid(format!("{field}.k2"), k2, "in (0, 1]"));
                }
                Ok(())
            }
        }
    }
}

/// `y^(1/9)` of `y >= 1` at compile time (Newton on `x^9 = y` from above, run to a fixed
/// point; only the arithmetic a `const fn` may do).
const fn const_ninth_root(y: f64) -> f64 {
    let mut x = if y > 2.0 {
        y / 9.0 + 1.0
    } else {
        1.0 + (y - 1.0) / 9.0 + 1e-3
    };
    let mut k = 0;
    while k < 200 {
        let x2 = x * x;
        let x4 = x2 * x2;
        let x8 = x4 * x4;
        let next = (8.0 * x + y / x8) / 9.0;
        if next >= x {
            break;
        }
        x = next;
        k += 1;
    }
    x
}

/// Cells of the mantissa in [`ninth_root`]: 64, so `|t| < 1/128`.
const CELLS: usize = 64;

/// `(c_i, c_i^(1/9), 1/c_i)` for the cell centres `c_i = 1 + (i + 1/2)/64` of `[1, 2)`.
const CELL_ROOT: [(f64, f64, f64); CELLS] = {
    let mut t = [(0.0, 0.0, 0.0); CELLS];
    let mut i = 0;
    while i < CELLS {
        let c = 1.0 + (i as f64 + 0.5) / CELLS as f64;
        t[i] = (c, const_ninth_root(c), 1.0 / c);
        i += 1;
    }
    t
};

/// `2^(r/9)`, `r = 0..8`.
const TWO_NINTHS: [f64; 9] = {
    let mut t = [0.0; 9];
    let mut r = 0;
    let mut p = 1.0;
    while r < 9 {
        t[r] = const_ninth_root(p);
        p *= 2.0;
        r += 1;
    }
    t
};

/// `2^q 2^(r/9)` for every biased exponent `E` of a positive normal `d` (`E - 1023 = 9 q +
/// r`, `r = 0..8`; index `E`, 0 unused): [`ninth_root`]'s exponent factor in one load. Each
/// entry is `TWO_NINTHS[r]` scaled by a power of two (exact), so the root's bits are those of
/// forming `2^q` and `2^(r/9)` apart.
const EXPONENT_ROOT: [f64; 2047] = {
    let mut t = [0.0; 2047];
    let mut e = 1;
    while e < 2047 {
        let e3 = e as u64 + 3;
        let (n, r) = (e3 / 9, e3 % 9);
        t[e] = f64::from_bits((n + 909) << 52) * TWO_NINTHS[r as usize];
        e += 1;
    }
    t
};

/// Binomial coefficients of `(1 + t)^(1/9)`, `a_n = C(1/9, n)`, `n = 0..6`.
const BINOMIAL: [f64; 7] = {
    let mut a = [0.0; 7];
    a[0] = 1.0;
    let mut n = 1;
    while n < 7 {
        a[n] = a[n - 1] * (1.0 / 9.0 - (n - 1) as f64) / n as f64;
        n += 1;
    }
    a
};

/// `d^(1/9)` for `d > 0`, the lamina law's root, in about 25 instructions against `powf`'s
/// hundred: with `d = 2^(9q + r) m`, `m` in `[1, 2)` near the cell centre `c_i`,
/// `d^(1/9) = 2^q 2^(r/9) c_i^(1/9) (1 + t)^(1/9)`, `t = (m - c_i)/c_i` (`|t| < 1/128`; the
/// binomial series to `t^6` leaves under `3e-17`); within a few units in the last place of
/// `powf(d, 1/9)` (`ninth_root_matches_powf`). Zero, subnormal, infinite or NaN `d` take
/// `powf`.
#[inline]
fn ninth_root(d: f64) -> f64 {
    let bits = d.to_bits();
    // Positive, normal and finite exactly when the bits lie in [MIN_POSITIVE's, INFINITY's)
    // (a negative number's sign bit puts it above): one unsigned comparison.
    const MIN_NORMAL: u64 = 0x0010_0000_0000_0000;
    if bits.wrapping_sub(MIN_NORMAL) >= 0x7ff0_0000_0000_0000 - MIN_NORMAL {
        return d.powf(1.0 / 9.0);
    }
    let m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    let (c, ci9, inv_c) = CELL_ROOT[((bits >> 46) & (CELLS as u64 - 1)) as usize];
    let t = (m - c) * inv_c;
    let a = &BINOMIAL;
    let poly = a[0] + t * (a[1] + t * (a[2] + t * (a[3] + t * (a[4] + t * (a[5] + t * a[6])))));
    // The biased exponent E (1..=2046, d > 0 and normal): E - 1023 = 9 (n - 114) + r with
    // E + 3 = 9 n + r, so 2^q has the biased exponent n - 114 + 1023; `EXPONENT_ROOT[E]` is
    // `2^q 2^(r/9)`. `(2^q 2^(r/9)) c` and `2^q (2^(r/9) c)` round alike (a power of two
    // scales exactly in the normal range, and the roots of normal numbers stay far inside
    // it).
    EXPONENT_ROOT[(bits >> 52) as usize] * ci9 * poly
}

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
            self.loaded += 1;
            if q > self.max_lamina {
                self.max_lamina = q;
            }
            self.force += q;
            self.moment += q * x;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::material::{effective_modulus, Material};

    fn geom(lwe: f64, dwe: f64) -> LineGeometry {
        LineGeometry {
            lwe,
            dwe,
            e_prime: E_PRIME_REFERENCE,
            tapered: false,
        }
    }

    fn profiles(g: &LineGeometry) -> Vec<Profile> {
        vec![
            Profile::None,
            Profile::Crown { radius: 2.0 },
            Profile::PartialCrown {
                flat: 0.5 * g.lwe,
                radius: 0.5,
            },
            Profile::IsoLog,
            Profile::Lundberg { design_load: 5e3 },
            Profile::FujiwaraKawase {
                design_load: 5e3,
                k1: 1.5,
                k2: 0.8,
                end_drop: 10e-6,
            },
        ]
    }

    #[test]
    fn steel_constant_is_iso_ts_16281_in_both_unit_systems() {
        // Q in N from Lwe, delta in mm equals Q in N from the same lengths in m.
        let (l_mm, d_mm) = (12.0_f64, 0.01_f64);
        let q_mm = C_STEEL_N_MM * l_mm.powf(8.0 / 9.0) * d_mm.powf(10.0 / 9.0);
        let q_si = roller_constant(l_mm * 1e-3, E_PRIME_REFERENCE) * (d_mm * 1e-3).powf(10.0 / 9.0);
        assert!((q_si / q_mm - 1.0).abs() < 1e-12, "{q_si} vs {q_mm}");
        // The steel preset pair is the reference exactly.
        let s = Material::by_name("steel").unwrap();
        assert_eq!(effective_modulus(&s, &s), E_PRIME_REFERENCE);
        // Si3N4 rollers on steel rings: the constant scales with E' (about +18.5 %).
        let n = Material::by_name("si3n4").unwrap();
        let ratio = roller_constant(0.01, effective_modulus(&n, &s))
            / roller_constant(0.01, E_PRIME_REFERENCE);
        assert!((ratio - 1.185).abs() < 0.005, "{ratio}");
    }

    #[test]
    fn ninth_root_matches_powf() {
        // Approaches from 1e-12 m to 1 m and every mantissa cell, and the fallbacks.
        let mut worst = 0.0f64;
        let mut d = 1e-12;
        while d < 1.0 {
            for k in 0..7 {
                let x = d * (1.0 + 0.1377 * k as f64);
                let (a, b) = (ninth_root(x), x.powf(1.0 / 9.0));
                worst = worst.max((a / b - 1.0).abs());
            }
            d *= 1.0 + 1.0 / 37.0;
        }
        assert!(
            worst < 4.0 * f64::EPSILON,
            "largest relative difference {worst:e}"
        );
        assert_eq!(ninth_root(512.0), 2.0);
        assert_eq!(ninth_root(1.0), 1.0);
        for x in [0.0, 1e-310, f64::INFINITY] {
            assert_eq!(ninth_root(x), x.powf(1.0 / 9.0));
        }
        assert!(ninth_root(f64::NAN).is_nan());
        // The fallback's one comparison: every number outside the positive normal range
        // takes powf (the same bits, or NaN), the range's own ends the series.
        let largest_subnormal = f64::from_bits(f64::MIN_POSITIVE.to_bits() - 1);
        for x in [
            -0.0,
            -1e-300,
            -1.0,
            -f64::MAX,
            f64::NEG_INFINITY,
            largest_subnormal,
        ] {
            let (a, b) = (ninth_root(x), x.powf(1.0 / 9.0));
            assert!(
                a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                "{x:e}"
            );
        }
        // (Against the ninth power: `powf(x, 1/9)` itself is off by `ln(x)` times the
        // rounding of 1/9 there, about 20 ulp.)
        for x in [
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::from_bits(f64::MAX.to_bits() - 7),
        ] {
            let a = ninth_root(x);
            assert!(
                (a.powi(9) / x - 1.0).abs() < 16.0 * f64::EPSILON,
                "{x:e}: {a:e}"
            );
        }
    }

    /// The exponent table gives the bits of forming `2^q` and `2^(r/9)` apart (the root as
    /// it was before the table), over every normal exponent and a spread of mantissas.
    #[test]
    fn exponent_table_keeps_the_roots_bits() {
        let apart = |d: f64| {
            let bits = d.to_bits();
            let m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
            let (c, ci9, inv_c) = CELL_ROOT[((bits >> 46) & (CELLS as u64 - 1)) as usize];
            let t = (m - c) * inv_c;
            let a = &BINOMIAL;
            let poly =
                a[0] + t * (a[1] + t * (a[2] + t * (a[3] + t * (a[4] + t * (a[5] + t * a[6])))));
            let e3 = (bits >> 52) + 3;
            let (n, r) = (e3 / 9, e3 % 9);
            f64::from_bits((n + 909) << 52) * (TWO_NINTHS[r as usize] * ci9) * poly
        };
        for e in 1..2047u64 {
            for k in 0..16u64 {
                let d = f64::from_bits((e << 52) | (k * 0x0001_1111_1111_1111 % (1 << 52)));
                assert_eq!(ninth_root(d).to_bits(), apart(d).to_bits(), "{d:e}");
            }
        }
    }

    #[test]
    fn aligned_pairs_agree_with_the_lamina_loop() {
        // evaluate (paired laminae at zero tilt) against evaluate_into (every lamina).
        let g = geom(0.012, 0.01);
        for p in profiles(&g) {
            for ns in [1, 2, 30, 31] {
                let l = Laminae::new(&g, &p, ns).unwrap();
                for d in [2e-6, 1e-5, 4e-5] {
                    let a = l.evaluate(d, 0.0);
                    let b = l.evaluate_into(d, 0.0, &mut vec![0.0; ns]);
                    assert_eq!((a.loaded, a.max_lamina), (b.loaded, b.max_lamina), "{p:?}");
                    let close = |u: f64, v: f64, s: f64| (u - v).abs() <= 1e-14 * s;
                    let m = b.force * g.lwe;
                    assert!(close(a.force, b.force, b.force), "{p:?} {ns}");
                    assert!(close(a.dforce_ddelta, b.dforce_ddelta, b.dforce_ddelta));
                    assert!(close(a.dmoment_dtilt, b.dmoment_dtilt, -b.dmoment_dtilt));
                    let k = b.dforce_ddelta * g.lwe;
                    assert!(close(a.moment, b.moment, m), "{p:?} {ns}");
                    assert!(close(a.dforce_dtilt, b.dforce_dtilt, k), "{p:?} {ns}");
                    assert!(close(a.dmoment_ddelta, b.dmoment_ddelta, k), "{p:?} {ns}");
                }
            }
        }
    }

    /// The force-only evaluation a right-hand side takes is the full one's force, moment,
    /// loaded count and largest lamina bit for bit, aligned or tilted, every profile,
    /// paired or not (ns odd), touching or not; its derivatives are zero when aligned.
    #[test]
    fn force_only_evaluation_is_the_full_ones_bits() {
        let g = geom(0.012, 0.01);
        for p in profiles(&g) {
            for ns in [1, 2, 30, 31] {
                let l = Laminae::new(&g, &p, ns).unwrap();
                for d in [-1e-6, 0.0, 3e-7, 2e-6, 1e-5, 4e-5] {
                    for t in [0.0, -0.0, 3e-4, -1e-3] {
                        // With offsets too (a pit's loss on some laminae, waviness).
                        let off: Vec<f64> = (0..ns)
                            .map(|k| 1e-6 * ((k * 7) % 5) as f64 - 2e-6)
                            .collect();
                        let (mut la, mut lb) = (vec![0.0; ns], vec![0.0; ns]);
                        let a = l.evaluate_offsets(d, t, &off, Some(&mut la));
                        let b = l.evaluate_offsets_force(d, t, &off, Some(&mut lb));
                        assert_eq!(
                            (
                                a.force.to_bits(),
                                a.moment.to_bits(),
                                a.max_lamina.to_bits()
                            ),
                            (
                                b.force.to_bits(),
                                b.moment.to_bits(),
                                b.max_lamina.to_bits()
                            )
                        );
                        assert_eq!((a.loaded, &la), (b.loaded, &lb));
                        assert_eq!(b.dforce_ddelta, 0.0);
                        let (a, b) = (l.evaluate_tan(d, t), l.evaluate_tan_force(d, t));
                        let bits = |r: &RollerLoad| {
                            (
                                r.force.to_bits(),
                                r.moment.to_bits(),
                                r.max_lamina.to_bits(),
                            )
                        };
                        assert_eq!(bits(&a), bits(&b), "{p:?} {ns} {d} {t}");
                        assert_eq!(a.loaded, b.loaded);
                        if t == 0.0 {
                            assert_eq!(b.dforce_ddelta, 0.0);
                            assert!(a.dforce_ddelta > 0.0 || a.loaded == 0);
                        } else {
                            assert_eq!(a, b);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn uniform_approach_gives_palmgren_load_for_any_number_of_laminae() {
        let g = geom(0.012, 0.01);
        let exact = roller_constant(g.lwe, g.e_prime) * 1e-5_f64.powf(10.0 / 9.0);
        for ns in [1, 2, 7, 10, 30, 121, 1000] {
            let l = Laminae::new(&g, &Profile::None, ns).unwrap();
            let r = l.evaluate(1e-5, 0.0);
            assert!(
                (r.force / exact - 1.0).abs() < 1e-12,
                "ns {ns}: {}",
                r.force
            );
            assert!(r.moment.abs() < 1e-12 * exact * g.lwe, "ns {ns}");
            assert_eq!(r.loaded, ns);
            // Stiffness = (10/9) Q / delta.
            assert!((r.dforce_ddelta * 1e-5 / (10.0 / 9.0 * exact) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn tilt_gives_a_restoring_moment_and_consistent_derivatives() {
        let g = geom(0.012, 0.01);
        for p in profiles(&g) {
            let l = Laminae::new(&g, &p, 30).unwrap();
            let (d, psi) = (8e-6, 4e-4);
            let r = l.evaluate(d, psi);
            assert!(r.moment < 0.0, "{p:?}: positive tilt, M = {}", r.moment);
            assert!(l.evaluate(d, -psi).moment > 0.0, "{p:?}");
            assert!(r.dmoment_dtilt < 0.0, "{p:?}");
            // Finite differences.
            let (hd, hp) = (1e-11, 1e-8);
            let (a, b) = (l.evaluate(d + hd, psi), l.evaluate(d - hd, psi));
            let (c, e) = (l.evaluate(d, psi + hp), l.evaluate(d, psi - hp));
            let fd = [
                (a.force - b.force) / (2.0 * hd),
                (c.force - e.force) / (2.0 * hp),
                (a.moment - b.moment) / (2.0 * hd),
                (c.moment - e.moment) / (2.0 * hp),
            ];
            let an = [
                r.dforce_ddelta,
                r.dforce_dtilt,
                r.dmoment_ddelta,
                r.dmoment_dtilt,
            ];
            let scale = [
                r.dforce_ddelta,
                r.dforce_ddelta * g.lwe,
                r.dforce_ddelta * g.lwe,
                r.dforce_ddelta * g.lwe * g.lwe,
            ];
            for i in 0..4 {
                assert!(
                    (fd[i] - an[i]).abs() < 1e-5 * scale[i],
                    "{p:?} [{i}] {} vs {}",
                    fd[i],
                    an[i]
                );
            }
        }
    }

    #[test]
    fn aligned_profiled_roller_is_symmetric() {
        let g = geom(0.012, 0.01);
        for p in profiles(&g) {
            for ns in [30, 31] {
                let l = Laminae::new(&g, &p, ns).unwrap();
                let mut q = vec![0.0; ns];
                let r = l.evaluate_into(1e-5, 0.0, &mut q);
                for k in 0..ns {
                    assert!((q[k] - q[ns - 1 - k]).abs() <= 1e-12 * r.force, "{p:?}");
                }
                assert!(r.moment.abs() <= 1e-12 * r.force * g.lwe, "{p:?}");
                if p != Profile::None {
                    assert!(q[0] < q[ns / 2], "{p:?}: the profile unloads the ends");
                }
            }
        }
    }

    #[test]
    fn straight_tilted_roller_edge_loads_and_a_log_profile_removes_the_spike() {
        let g = geom(0.01, 0.01);
        let ns = 30;
        let r_race = 0.004;
        // Each roller at the same load, 4 kN (p0 about 2 GPa aligned), tilted 1 and 3 mrad.
        let run = |prof: &Profile, psi: f64| {
            let l = Laminae::new(&g, prof, ns).unwrap();
            let d = solve_approach(&l, 4e3, psi);
            let (mut q, mut p) = (vec![0.0; ns], vec![0.0; ns]);
            l.evaluate_into(d, psi, &mut q);
            l.pressures(&q, r_race, g.e_prime, &mut p);
            let imax = (0..ns).max_by(|&a, &b| p[a].total_cmp(&p[b])).unwrap();
            (imax, p[imax], p[0])
        };
        for psi in [1e-3, 3e-3] {
            let (i_s, peak_s, edge_s) = run(&Profile::None, psi);
            let (i_l, peak_l, edge_l) = run(&Profile::IsoLog, psi);
            println!(
                "tilt {psi}: straight peak {:.0} MPa at lamina {i_s}; ISO log peak {:.0} MPa at {i_l}, edge {:.0} MPa",
                peak_s * 1e-6,
                peak_l * 1e-6,
                edge_l * 1e-6
            );
            assert_eq!(i_s, 0, "the straight roller's -x edge lamina carries most");
            assert_eq!(peak_s, edge_s);
            assert!(
                i_l > 0 && i_l < ns / 2,
                "log: peak inside, on the loaded side: {i_l}"
            );
            assert!(
                edge_l < 0.75 * edge_s,
                "log edge {edge_l} vs straight edge {edge_s}"
            );
            if psi > 2e-3 {
                // Measured: 2 328 against 2 520 MPa (the slicing model has no elastic coupling
                // along the roller, so the straight roller's true edge singularity is absent).
                assert!(peak_l < 0.95 * peak_s, "{peak_l} vs {peak_s}");
            }
        }
    }

    /// Approach at which the roller carries `load` at tilt `psi` (Newton, test helper).
    fn solve_approach(l: &Laminae, load: f64, psi: f64) -> f64 {
        let mut d = (load / (l.cs * l.len() as f64)).powf(0.9) + l.lwe * psi.abs();
        for _ in 0..100 {
            let r = l.evaluate(d, psi);
            let step = (r.force - load) / r.dforce_ddelta;
            d -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        d
    }

    #[test]
    fn no_nan_without_contact() {
        let g = geom(0.01, 0.01);
        for p in profiles(&g) {
            let l = Laminae::new(&g, &p, 30).unwrap();
            for (d, psi) in [
                (0.0, 0.0),
                (-1e-5, 0.0),
                (-1.0, 0.3),
                (0.0, 1e-3),
                (f64::MIN_POSITIVE, 0.0),
            ] {
                let mut q = vec![1.0; 30];
                let r = l.evaluate_into(d, psi, &mut q);
                for v in [
                    r.force,
                    r.moment,
                    r.dforce_ddelta,
                    r.dforce_dtilt,
                    r.dmoment_ddelta,
                    r.dmoment_dtilt,
                ] {
                    assert!(v.is_finite(), "{p:?} {d} {psi}");
                }
                assert!(q.iter().all(|v| v.is_finite() && *v >= 0.0));
            }
            assert_eq!(l.evaluate(-1e-6, 0.0).force, 0.0);
        }
        assert_eq!(line_hertz(0.0, 0.004, E_PRIME_REFERENCE), (0.0, 0.0));
        assert_eq!(line_hertz(-3.0, 0.004, E_PRIME_REFERENCE), (0.0, 0.0));
    }

    #[test]
    fn line_hertz_carries_the_load_and_matches_johnson() {
        let (q, r, e) = (1.0e6, 0.004, E_PRIME_REFERENCE);
        let (b, p0) = line_hertz(q, r, e);
        // Semi-ellipse integrates to the load per length.
        assert!((0.5 * PI * p0 * b / q - 1.0).abs() < 1e-12);
        // Johnson's two-dimensional Hertz with E* = E'/2: p0 = sqrt(q E*/(pi R)).
        assert!((p0 / (q * 0.5 * e / (PI * r)).sqrt() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn profiles_have_their_defining_values() {
        let g = geom(0.01, 0.008);
        let h = 0.5 * g.lwe;
        // Chamfer: no contact at or beyond the effective end.
        for p in profiles(&g) {
            assert_eq!(p.drop(h, &g), f64::INFINITY);
            assert_eq!(p.drop(-1.2 * h, &g), f64::INFINITY);
            assert_eq!(p.drop(0.0, &g), 0.0, "{p:?}");
        }
        // ISO/TS 16281, CRB: 0.00035 Dwe ln(1/(1 - 0.25)) at x = Lwe/4.
        let iso = Profile::IsoLog.drop(0.5 * h, &g);
        assert!((iso - 0.00035 * 0.008 * (1.0f64 / 0.75).ln()).abs() < 1e-18);
        let t = LineGeometry { tapered: true, ..g };
        assert!((Profile::IsoLog.drop(0.5 * h, &t) / iso - 0.00045 / 0.00035).abs() < 1e-12);
        // Long CRB roller (Lwe > 2.5 Dwe): straight centre, 0.0005 Dwe log outside.
        let long = geom(0.03, 0.008);
        assert_eq!(Profile::IsoLog.drop(0.004, &long), 0.0); // start at (30 - 20)/2 = 5 mm
        let u: f64 = (2.0 * 0.01 - 0.03 + 0.02) / 0.02;
        assert!(
            (Profile::IsoLog.drop(0.01, &long) - 0.0005 * 0.008 * (1.0 / (1.0 - u * u)).ln()).abs()
                < 1e-18
        );
        // Fujiwara–Kawase: z_m at the effective end (limit), straight centre of (1 - K2) Lwe/2.
        let fk = Profile::FujiwaraKawase {
            design_load: 5e3,
            k1: 1.5,
            k2: 0.6,
            end_drop: 12e-6,
        };
        assert_eq!(fk.drop(0.4 * h * 0.999, &g), 0.0);
        assert!((fk.drop(h * (1.0 - 1e-12), &g) / 12e-6 - 1.0).abs() < 1e-6);
        // Lundberg: its uniform-pressure condition. The approach deficit of a uniformly
        // loaded strip at x (Johnson ch. 4, two half-spaces) is (2 q'/(pi E')) ln(1/(1-u²)).
        let lu = Profile::Lundberg { design_load: 5e3 };
        let qd = 5e3 / g.lwe;
        assert!(
            (lu.drop(0.5 * h, &g) - 2.0 * qd / (PI * g.e_prime) * (1.0f64 / 0.75).ln()).abs()
                < 1e-18
        );
    }

    #[test]
    fn bad_input_names_the_field() {
        let g = geom(0.01, 0.008);
        let e = Laminae::new(&g, &Profile::None, 0).unwrap_err().to_string();
        assert!(e.contains("roller.laminae"), "{e}");
        let e = Laminae::new(&g, &Profile::Crown { radius: -1.0 }, 30)
            .unwrap_err()
            .to_string();
        assert!(e.contains("roller.profile.radius"), "{e}");
        let e = Laminae::new(
            &g,
            &Profile::PartialCrown {
                flat: 0.02,
                radius: 1.0,
            },
            30,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("roller.profile.flat"), "{e}");
        let fk = Profile::FujiwaraKawase {
            design_load: 1e3,
            k1: 1.0,
            k2: 1.5,
            end_drop: 1e-5,
        };
        let e = Laminae::new(&g, &fk, 30).unwrap_err().to_string();
        assert!(e.contains("roller.profile.k2"), "{e}");
        let e = Laminae::new(&geom(f64::NAN, 0.008), &Profile::None, 30)
            .unwrap_err()
            .to_string();
        assert!(e.contains("roller.effective_length"), "{e}");
    }

    /// The convergence study the module docs quote: roller load held at 10 kN, tilt 1 mrad,
    /// errors of the approach and of the peak pressure against ns = 4000.
    #[test]
    fn lamina_convergence_study() {
        let g = geom(0.01, 0.01);
        let (load, r_race) = (4.0e3, 0.004);
        let run = |p: &Profile, ns: usize, psi: f64| {
            let l = Laminae::new(&g, p, ns).unwrap();
            let d = solve_approach(&l, load, psi);
            let mut q = vec![0.0; ns];
            let mut pr = vec![0.0; ns];
            let r = l.evaluate_into(d, psi, &mut q);
            l.pressures(&q, r_race, g.e_prime, &mut pr);
            (d, pr.iter().cloned().fold(0.0, f64::max), r.loaded)
        };
        for psi in [1e-3, 3e-3] {
            for (name, p) in [
                ("none", Profile::None),
                ("crown R 2 m", Profile::Crown { radius: 2.0 }),
                ("ISO/TS log", Profile::IsoLog),
            ] {
                let (d_ref, p_ref, n_ref) = run(&p, 4000, psi);
                let mut line_q = format!("| {psi} | {name} | load at the reference approach |");
                let mut line_d = format!("| {psi} | {name} | approach at 4 kN |");
                let mut line_p = format!("| {psi} | {name} | peak pressure at 4 kN |");
                for ns in [10, 20, 30, 50, 100] {
                    let (d, pk, _) = run(&p, ns, psi);
                    let q = Laminae::new(&g, &p, ns).unwrap().evaluate(d_ref, psi).force;
                    let (eq, ed, ep) = (
                        (q / load - 1.0).abs(),
                        (d / d_ref - 1.0).abs(),
                        (pk / p_ref - 1.0).abs(),
                    );
                    line_q += &format!(" {:.2} % |", 100.0 * eq);
                    line_d += &format!(" {:.2} % |", 100.0 * ed);
                    line_p += &format!(" {:.2} % |", 100.0 * ep);
                    if ns == DEFAULT_LAMINAE {
                        assert!(
                            eq < 0.01 && ed < 0.01 && ep < 0.01,
                            "{name}, tilt {psi}: ns = 30: {eq} {ed} {ep}"
                        );
                    }
                }
                println!(
                    "{line_q}\n{line_d}\n{line_p}   (ref: approach {:.3} µm, p0 {:.0} MPa, {:.0} % of the length in contact)",
                    d_ref * 1e6,
                    p_ref * 1e-6,
                    100.0 * n_ref as f64 / 4000.0
                );
            }
        }
    }
}
