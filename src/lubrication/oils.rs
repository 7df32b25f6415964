//! Named lubricants whose properties depend on the temperature (docs/physics.md §6.2).
//!
//! **MIL-L-7808** (the synthetic turbine oil study \[0\] names), from a public lubricant
//! library in the ADORE style (the `Oil_properties.py` of the public repository
//! `Baomaokuan/Bearing`; confidence **medium, public code**: the correlations were not seen
//! in a paper, and no datasheet of the oil was reachable), `T` in kelvin:
//!
//! - viscosity `eta = 9.997e-4 (e^a - 0.87)` Pa s, `a = exp(22.216 - 3.7048 ln T)` (a
//!   Walther-type double exponential): 11.6 mPa s at 40 °C, 2.87 mPa s at 100 °C, which is the
//!   MIL-L-7808 class (about 3 mm²/s at 100 °C);
//! - pressure–viscosity coefficient `alpha = 7.5808e-10 + 1.0742e-6 / (T - 215.56)` 1/Pa;
//! - density, heat capacity and conductivity tabulated at 311, 367, 422 and 478 K, linearly
//!   interpolated between the points;
//! - the viscosity–temperature coefficient `beta = -d ln(eta)/dT` is derived from the
//!   viscosity correlation (not a separate datum).
//!
//! Valid range: 311 to 478 K (38 to 205 °C), the span of the tabulated points; the
//! correlations are refused outside it rather than extrapolated.

use crate::error::{Error, Result};

/// Lowest temperature of the MIL-L-7808 tables, K.
pub const MIL_L_7808_T_MIN: f64 = 311.0;
/// Highest temperature of the MIL-L-7808 tables, K.
pub const MIL_L_7808_T_MAX: f64 = 478.0;

/// Tabulated temperatures, K.
const T_TABLE: [f64; 4] = [311.0, 367.0, 422.0, 478.0];
/// Density, kg/m³.
const RHO_TABLE: [f64; 4] = [954.0, 914.0, 870.0, 826.0];
/// Heat capacity, J/(kg K).
const CP_TABLE: [f64; 4] = [1800.0, 1968.0, 2177.0, 2345.0];
/// Conductivity, W/(m K).
const K_TABLE: [f64; 4] = [0.1449, 0.1340, 0.1327, 0.1314];

/// Source and confidence line shown with the preset (scene notes, docs).
pub const MIL_L_7808_SOURCE: &str = "MIL-L-7808 property correlations of a public ADORE-style lubricant library (Baomaokuan/Bearing, Oil_properties.py); confidence medium (public code), valid 311-478 K";

/// Properties of MIL-L-7808 at one temperature (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OilState {
    /// Temperature, K.
    pub temperature: f64,
    /// Dynamic viscosity, Pa s.
    pub viscosity: f64,
    /// Pressure–viscosity coefficient, 1/Pa.
    pub pressure_viscosity: f64,
    /// Viscosity–temperature coefficient `-d ln(eta)/dT`, 1/K.
    pub viscosity_temperature: f64,
    /// Density, kg/m³.
    pub density: f64,
    /// Heat capacity, J/(kg K).
    pub heat_capacity: f64,
    /// Thermal conductivity, W/(m K).
    pub conductivity: f64,
}

fn interp(t: f64, y: &[f64; 4]) -> f64 {
    let k = T_TABLE
        .windows(2)
        .position(|w| t <= w[1])
        .unwrap_or(T_TABLE.len() - 2);
    let w = (t - T_TABLE[k]) / (T_TABLE[k + 1] - T_TABLE[k]);
    y[k] + w * (y[k + 1] - y[k])
}

/// MIL-L-7808 at `temperature` (K); refused outside 311–478 K naming `field`.
pub fn mil_l_7808(temperature: f64, field: &str) -> Result<OilState> {
    if !(MIL_L_7808_T_MIN..=MIL_L_7808_T_MAX).contains(&temperature) {
        return Err(Error::invalid(
            field,
            temperature,
            "in [311, 478] K (37.85 to 204.85 °C), the span of the MIL-L-7808 tables",
        ));
    }
    let ln_t = temperature.ln();
    let a = (22.216 - 3.7048 * ln_t).exp();
    let ea = a.exp();
    let viscosity = 9.997e-4 * (ea - 0.87);
    // d eta/dT = 9.997e-4 e^a da/dT, da/dT = -3.7048 a / T.
    let deta = 9.997e-4 * ea * (-3.7048 * a / temperature);
    Ok(OilState {
        temperature,
        viscosity,
        pressure_viscosity: 7.5808e-10 + 1.0742e-6 / (temperature - 215.56),
        viscosity_temperature: -deta / viscosity,
        density: interp(temperature, &RHO_TABLE),
        heat_capacity: interp(temperature, &CP_TABLE),
        conductivity: interp(temperature, &K_TABLE),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The brief's points: 11.6 mPa s at 40 °C and 2.87 mPa s at 100 °C (the correlation
    /// evaluated by hand), alpha 1.18e-8 and 7.6e-9 1/Pa there; the tables at their own
    /// temperatures; beta is the logarithmic slope of the viscosity (finite difference).
    #[test]
    fn reproduces_the_tabulated_points() {
        let at = |c: f64| mil_l_7808(c + 273.15, "t").unwrap();
        let (o40, o100) = (at(40.0), at(100.0));
        assert!(
            (o40.viscosity * 1e3 - 11.6).abs() < 0.05,
            "{}",
            o40.viscosity
        );
        assert!(
            (o100.viscosity * 1e3 - 2.87).abs() < 0.005,
            "{}",
            o100.viscosity
        );
        assert!((o40.pressure_viscosity - 1.18e-8).abs() < 0.005e-8);
        assert!((o100.pressure_viscosity - 7.6e-9).abs() < 0.05e-9);
        for (i, &t) in T_TABLE.iter().enumerate() {
            let o = mil_l_7808(t, "t").unwrap();
            assert_eq!(o.density, RHO_TABLE[i]);
            assert_eq!(o.heat_capacity, CP_TABLE[i]);
            assert_eq!(o.conductivity, K_TABLE[i]);
        }
        let t = 350.0;
        let h = 1e-3;
        let fd = -((mil_l_7808(t + h, "t").unwrap().viscosity).ln()
            - (mil_l_7808(t - h, "t").unwrap().viscosity).ln())
            / (2.0 * h);
        let beta = mil_l_7808(t, "t").unwrap().viscosity_temperature;
        assert!((beta / fd - 1.0).abs() < 1e-6, "{beta} {fd}");
        // Thinner and less pressure-sensitive when hot, over the whole range.
        let mut last = mil_l_7808(MIL_L_7808_T_MIN, "t").unwrap();
        for k in 1..=100 {
            let o = mil_l_7808(311.0 + 1.67 * k as f64, "t").unwrap();
            assert!(o.viscosity < last.viscosity && o.pressure_viscosity < last.pressure_viscosity);
            assert!(o.viscosity_temperature > 0.0);
            last = o;
        }
    }

    #[test]
    fn outside_the_tables_is_refused_naming_the_field() {
        for t in [310.9, 478.1, f64::NAN] {
            let e = mil_l_7808(t, "effects.lubrication.temperature_c").unwrap_err();
            assert!(e.to_string().contains("temperature_c"), "{e}");
        }
    }
}
