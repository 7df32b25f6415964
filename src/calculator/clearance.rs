//! Operating clearance from the fits, the ring temperatures and the inner ring's speed.
//!
//! Lamé's thick-cylinder solution in plane stress (Timoshenko & Goodier, *Theory of Elasticity*,
//! 3rd ed., 1970, §28), as applied to bearing fits by Harris & Kotzalas (*Rolling Bearing
//! Analysis*, 5th ed., vol. 1, ch. "Bearing internal clearance", fitting practice). Each ring is
//! a cylinder from its seat to its raceway diameter (`d → Di` inner, `Do → D` outer); all
//! interferences are diametral and measured at the clearance's reference temperature (20 °C).
//!
//! - **Shaft fit**, interference `I_s` on the bore `d` of an inner ring of raceway diameter `Di`,
//!   hollow shaft of bore `d_s` (0: solid): the fit pressure
//!   `p = I_s / (d [ (Di² + d²)/(E_r (Di² − d²)) + ν_r/E_r + (d² + d_s²)/(E_s (d² − d_s²)) − ν_s/E_s ])`
//!   widens the raceway by `ΔDi = 2 p d² Di / (E_r (Di² − d²))`. For a solid shaft of the ring's
//!   material this is `ΔDi = I_s d/Di` (a check in the tests).
//! - **Housing fit**, interference `I_h` on the outside `D` of an outer ring of raceway diameter
//!   `Do`, housing of outside diameter `D_h` (∞: a rigid-in-extent housing):
//!   `p = I_h / (D [ (D² + Do²)/(E_r (D² − Do²)) − ν_r/E_r + (D_h² + D²)/(E_h (D_h² − D²)) + ν_h/E_h ])`
//!   narrows the raceway by `ΔDo = 2 p D² Do / (E_r (D² − Do²))`; with an unbounded housing of
//!   the ring's material `ΔDo = I_h Do/D`.
//! - **Temperatures**: each part grows by `α (T − 20 °C)` times its diameter, so
//!   `ΔPd = α_o ΔT_o Do − α_i ΔT_i Di − 2 α_b ΔT_b Dw` (the balls' temperature is an input; when
//!   absent the mean of the rings'). The fits are taken at 20 °C: the fits' change with the
//!   shaft's and housing's own temperatures is not modelled.
//! - **Inner-ring speed**: the raceway of a free rotating annulus grows by
//!   `ΔDi = (ρ ω² Di / (2 E)) ((1 − ν) (Di/2)² + (3 + ν) (d/2)²)` (Timoshenko & Goodier §32,
//!   rotating disc with a central hole, plane stress). The shaft turning with it is left out, so
//!   this is an upper bound of the growth while the fit holds.
//!
//! Operating clearance `Pd = Pd0 − ΔDi(fit) − ΔDo(fit) + ΔPd(thermal) − ΔDi(speed)`. Elastic only:
//! an interference of 1 % of its diameter or more is refused (far beyond the elastic strain of
//! any bearing steel); the hoop stress at the inner ring's bore is reported so the user can hold
//! it against the ring's strength.

use crate::error::{Error, Result};
use crate::geometry::Bearing;
use serde::Serialize;

/// Fits, temperatures and speed for the operating clearance (SI; temperatures °C).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClearanceInputs {
    /// Diametral interference of the inner ring on the shaft, m (negative: a loose fit).
    pub shaft_interference: f64,
    /// Bore of a hollow shaft, m (0: solid).
    pub shaft_bore: f64,
    /// Shaft Young's modulus, Pa, and Poisson ratio (`None`: the inner ring's material).
    pub shaft_material: Option<(f64, f64)>,
    /// Diametral interference of the outer ring in the housing, m (negative: loose).
    pub housing_interference: f64,
    /// Housing outside diameter, m (`None`: unbounded).
    pub housing_outer_diameter: Option<f64>,
    /// Housing Young's modulus, Pa, and Poisson ratio (`None`: the outer ring's material).
    pub housing_material: Option<(f64, f64)>,
    /// Inner-ring temperature, °C.
    pub inner_c: f64,
    /// Outer-ring temperature, °C.
    pub outer_c: f64,
    /// Ball temperature, °C (`None`: the mean of the rings').
    pub ball_c: Option<f64>,
    /// Shaft speed, rpm (inner ring rotating).
    pub speed_rpm: f64,
}

impl Default for ClearanceInputs {
    fn default() -> Self {
        ClearanceInputs {
            shaft_interference: 0.0,
            shaft_bore: 0.0,
            shaft_material: None,
            housing_interference: 0.0,
            housing_outer_diameter: None,
            housing_material: None,
            inner_c: REFERENCE_C,
            outer_c: REFERENCE_C,
            ball_c: None,
            speed_rpm: 0.0,
        }
    }
}

/// Temperature at which the clearance and the fits are given, °C.
pub const REFERENCE_C: f64 = 20.0;

/// The chain from the unmounted to the operating diametral clearance (m; pressures Pa).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OperatingClearance {
    /// Unmounted diametral clearance `Pd0`.
    pub unmounted: f64,
    /// Shaft-fit pressure.
    pub shaft_pressure: f64,
    /// Change of `Pd` from the shaft fit (≤ 0).
    pub from_shaft_fit: f64,
    /// Housing-fit pressure.
    pub housing_pressure: f64,
    /// Change of `Pd` from the housing fit (≤ 0).
    pub from_housing_fit: f64,
    /// Change of `Pd` from the temperatures.
    pub from_temperatures: f64,
    /// Change of `Pd` from the inner ring's centrifugal growth (≤ 0).
    pub from_speed: f64,
    /// Operating diametral clearance (negative: preload).
    pub operating: f64,
    /// Hoop stress at the inner ring's bore from the shaft fit, Pa (tension).
    pub inner_bore_hoop_stress: f64,
}

fn check(field: &str, v: f64, diameter: f64) -> Result<f64> {
    if !v.is_finite() {
        return Err(Error::invalid(field, v, "a finite number"));
    }
    if v >= 0.01 * diameter {
        return Err(Error::invalid(
            field,
            v,
            format!(
                "< 1 % of the seat diameter ({:.1} µm): beyond that the ring would not stay elastic",
                0.01 * diameter * 1e6
            ),
        ));
    }
    Ok(v)
}

/// The bearing `b` with its diametral clearance replaced by `pd` (m; negative: a radial
/// preload), its free contact angle following from the groove geometry as the bearing file's
/// does: `cos a0 = 1 − Pd/(2A)` for `Pd > 0`, and 0 at or below zero clearance (a deep-groove
/// bearing). The quasi-static equilibrium then runs in the operating clearance.
///
/// Errors: a clearance the grooves cannot take (at or above `2A`, or below −0.1 `D`), and
/// an angular-contact bearing left without clearance (no free contact angle: a single
/// angular-contact bearing cannot be preloaded radially by its fits), naming
/// `operating clearance`.
pub fn with_clearance(b: &Bearing, pd: f64) -> Result<Bearing> {
    let a = b.a();
    if !pd.is_finite() || pd >= 2.0 * a || pd <= -0.1 * b.d {
        return Err(Error::invalid(
            "operating clearance",
            format!("{:.3} µm", pd * 1e6),
            format!(
                "in ({:.3}, {:.3}) µm, what the grooves take (change the fits or temperatures)",
                -0.1e6 * b.d,
                2e6 * a
            ),
        ));
    }
    let mut out = b.clone();
    out.pd = pd;
    out.alpha0 = if pd > 0.0 {
        (1.0 - pd / (2.0 * a)).acos()
    } else if b.kind == crate::geometry::BearingKind::AngularContact {
        return Err(Error::invalid(
            "operating clearance",
            format!("{:.3} µm", pd * 1e6),
            "> 0 for a single angular-contact bearing (at zero clearance it has no free contact angle; looser fits or a smaller ring temperature difference)",
        ));
    } else {
        0.0
    };
    Ok(out)
}

/// The operating clearance of `b` under `x`.
pub fn operating_clearance(b: &Bearing, x: &ClearanceInputs) -> Result<OperatingClearance> {
    let (d, dd) = (b.bore, b.outer_diameter);
    let (di, do_) = (b.inner_race_diameter(), b.outer_race_diameter());
    let (er, nr) = (
        b.inner_material.youngs_modulus,
        b.inner_material.poisson_ratio,
    );
    let (eo, no) = (
        b.outer_material.youngs_modulus,
        b.outer_material.poisson_ratio,
    );
    if !(d > 0.0 && di > d && dd > do_) {
        return Err(Error::invalid(
            "bearing.bore_mm",
            d * 1e3,
            "a bore below the inner raceway and an outside diameter above the outer raceway",
        ));
    }
    let is = check("clearance.shaft_interference", x.shaft_interference, d)?;
    let ih = check("clearance.housing_interference", x.housing_interference, dd)?;
    if !(x.shaft_bore >= 0.0 && x.shaft_bore < d) {
        return Err(Error::invalid(
            "clearance.shaft_bore",
            x.shaft_bore,
            "0 <= bore < the bearing's bore",
        ));
    }
    if let Some(dh) = x.housing_outer_diameter {
        if dh.is_nan() || dh <= dd {
            return Err(Error::invalid(
                "clearance.housing_outer_diameter",
                dh,
                "> the bearing's outside diameter",
            ));
        }
    }
    for (f, v) in [
        ("clearance.inner_c", x.inner_c),
        ("clearance.outer_c", x.outer_c),
        ("clearance.ball_c", x.ball_c.unwrap_or(0.0)),
        ("clearance.speed_rpm", x.speed_rpm),
    ] {
        if !v.is_finite() {
            return Err(Error::invalid(f, v, "a finite number"));
        }
    }
    let (es, ns) = x.shaft_material.unwrap_or((er, nr));
    let (eh, nh) = x.housing_material.unwrap_or((eo, no));

    // Shaft fit.
    let ring_i = (di * di + d * d) / (er * (di * di - d * d)) + nr / er;
    let ds = x.shaft_bore;
    let shaft = (d * d + ds * ds) / (es * (d * d - ds * ds)) - ns / es;
    let ps = is.max(0.0) / (d * (ring_i + shaft));
    let grow_i = 2.0 * ps * d * d * di / (er * (di * di - d * d));
    let hoop = ps * (di * di + d * d) / (di * di - d * d);

    // Housing fit.
    let ring_o = (dd * dd + do_ * do_) / (eo * (dd * dd - do_ * do_)) - no / eo;
    let housing = match x.housing_outer_diameter {
        Some(dh) => (dh * dh + dd * dd) / (eh * (dh * dh - dd * dd)) + nh / eh,
        None => (1.0 + nh) / eh,
    };
    let ph = ih.max(0.0) / (dd * (ring_o + housing));
    let shrink_o = 2.0 * ph * dd * dd * do_ / (eo * (dd * dd - do_ * do_));

    // Temperatures.
    let tb = x.ball_c.unwrap_or(0.5 * (x.inner_c + x.outer_c));
    let thermal = b.outer_material.thermal_expansion * (x.outer_c - REFERENCE_C) * do_
        - b.inner_material.thermal_expansion * (x.inner_c - REFERENCE_C) * di
        - 2.0 * b.ball_material.thermal_expansion * (tb - REFERENCE_C) * b.d;

    // Centrifugal growth of the inner ring's raceway.
    let w = x.speed_rpm * std::f64::consts::PI / 30.0;
    let rho = b.inner_material.density;
    let (ri, rb) = (0.5 * di, 0.5 * d);
    let spin = rho * w * w * di / (2.0 * er) * ((1.0 - nr) * ri * ri + (3.0 + nr) * rb * rb);

    let operating = b.pd - grow_i - shrink_o + thermal - spin;
    Ok(OperatingClearance {
        unmounted: b.pd,
        shaft_pressure: ps,
        from_shaft_fit: -grow_i,
        housing_pressure: ph,
        from_housing_fit: -shrink_o,
        from_temperatures: thermal,
        from_speed: -spin,
        operating,
        inner_bore_hoop_stress: hoop,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bearing() -> Bearing {
        crate::geometry::presets::preset("6205")
            .unwrap()
            .build()
            .unwrap()
    }

    /// Solid shaft of the ring's material: the raceway widens by I d/Di (the classical
    /// result); an unbounded housing of the ring's material narrows it by I Do/D.
    #[test]
    fn fits_against_closed_forms() {
        let b = bearing();
        let i = 10e-6;
        let r = operating_clearance(
            &b,
            &ClearanceInputs {
                shaft_interference: i,
                ..Default::default()
            },
        )
        .unwrap();
        let want = i * b.bore / b.inner_race_diameter();
        assert!((-r.from_shaft_fit / want - 1.0).abs() < 1e-12, "{r:?}");
        assert!((r.operating - (b.pd - want)).abs() < 1e-15);
        let r = operating_clearance(
            &b,
            &ClearanceInputs {
                housing_interference: i,
                ..Default::default()
            },
        )
        .unwrap();
        let want = i * b.outer_race_diameter() / b.outer_diameter;
        assert!((-r.from_housing_fit / want - 1.0).abs() < 1e-12, "{r:?}");
    }

    /// Interference reduces the clearance; a hollow shaft or a thin housing takes less of it
    /// into the raceway; a loose fit changes nothing.
    #[test]
    fn limits() {
        let b = bearing();
        let at = |x: ClearanceInputs| operating_clearance(&b, &x).unwrap();
        let solid = at(ClearanceInputs {
            shaft_interference: 10e-6,
            ..Default::default()
        });
        let hollow = at(ClearanceInputs {
            shaft_interference: 10e-6,
            shaft_bore: 0.8 * b.bore,
            ..Default::default()
        });
        assert!(solid.operating < b.pd && hollow.operating > solid.operating);
        let thin = at(ClearanceInputs {
            housing_interference: 10e-6,
            housing_outer_diameter: Some(1.1 * b.outer_diameter),
            ..Default::default()
        });
        let thick = at(ClearanceInputs {
            housing_interference: 10e-6,
            ..Default::default()
        });
        assert!(thin.operating > thick.operating && thick.operating < b.pd);
        let loose = at(ClearanceInputs {
            shaft_interference: -5e-6,
            housing_interference: -5e-6,
            ..Default::default()
        });
        assert_eq!(loose.operating, b.pd);
    }

    /// A warmer inner ring than outer ring takes clearance away; equal temperatures of one
    /// steel leave Pd · (1 + α ΔT) (every diameter grows alike).
    #[test]
    fn temperatures() {
        let b = bearing();
        let r = operating_clearance(
            &b,
            &ClearanceInputs {
                inner_c: 80.0,
                outer_c: 60.0,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(r.from_temperatures < 0.0);
        let r = operating_clearance(
            &b,
            &ClearanceInputs {
                inner_c: 70.0,
                outer_c: 70.0,
                ..Default::default()
            },
        )
        .unwrap();
        let a = b.inner_material.thermal_expansion;
        let gap = b.outer_race_diameter() - b.inner_race_diameter() - 2.0 * b.d;
        assert!(
            (r.from_temperatures - a * 50.0 * gap).abs() < 1e-15,
            "{r:?}"
        );
    }

    /// Centrifugal growth ∝ ω², by hand for the 6205 at 10 000 rpm.
    #[test]
    fn speed_growth_and_errors() {
        let b = bearing();
        let g = |rpm: f64| {
            operating_clearance(
                &b,
                &ClearanceInputs {
                    speed_rpm: rpm,
                    ..Default::default()
                },
            )
            .unwrap()
            .from_speed
        };
        assert!((g(20000.0) / g(10000.0) - 4.0).abs() < 1e-12);
        let (e, n, rho) = (
            b.inner_material.youngs_modulus,
            b.inner_material.poisson_ratio,
            b.inner_material.density,
        );
        let (di, d) = (b.inner_race_diameter(), b.bore);
        let w = 10000.0 * std::f64::consts::PI / 30.0;
        let want =
            rho * w * w * di / (2.0 * e) * ((1.0 - n) * di * di / 4.0 + (3.0 + n) * d * d / 4.0);
        assert!(
            (-g(10000.0) - want).abs() < 1e-18 && want > 0.1e-6 && want < 2e-6,
            "{want}"
        );
        let e = operating_clearance(
            &b,
            &ClearanceInputs {
                shaft_interference: 0.5e-3,
                ..Default::default()
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("clearance.shaft_interference"), "{e}");
    }
}
