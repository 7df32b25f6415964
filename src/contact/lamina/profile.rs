//! Roller profiles: the drop of the roller surface from the cylinder along its length
//! (docs/physics.md §R2).

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

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
