//! Materials of the bodies (docs/physics.md §2).
//!
//! Elastic data from the studies' tables; thermal data are typical handbook values
//! (Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed., Vol. 1, Table 5.x; supplier sheets
//! for the ceramics) and only matter for the thermal model.

use crate::error::{Error, Result};
use crate::seam::fields::{between, ge, gt, number, text};
use serde::{Deserialize, Serialize};

/// Mechanical and thermal properties of one body, SI units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Name (a preset key or a free label).
    pub name: String,
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Density, kg/m³.
    pub density: f64,
    /// Linear thermal expansion coefficient, 1/K.
    pub thermal_expansion: f64,
    /// Thermal conductivity, W/(m K).
    pub conductivity: f64,
    /// Specific heat capacity, J/(kg K).
    pub heat_capacity: f64,
}

crate::declare_fields!(Material {
    name => text("label of an inline material (<body>: ball, inner_ring, outer_ring or cage)"),
    youngs_modulus => number("Pa", gt(0.0), "Young's modulus"),
    poisson_ratio => number("-", between(0.0, true, 0.5, false), "Poisson's ratio"),
    density => number("kg/m³", gt(0.0), "density"),
    thermal_expansion => number("1/K", ge(0.0), "linear thermal expansion coefficient"),
    conductivity => number("W/(m K)", ge(0.0), "thermal conductivity"),
    heat_capacity => number("J/(kg K)", ge(0.0), "specific heat capacity"),
});

impl Material {
    fn preset(name: &str, e_gpa: f64, nu: f64, rho: f64, alpha: f64, k: f64, c: f64) -> Self {
        Material {
            name: name.to_string(),
            youngs_modulus: e_gpa * 1e9,
            poisson_ratio: nu,
            density: rho,
            thermal_expansion: alpha,
            conductivity: k,
            heat_capacity: c,
        }
    }

    /// The material presets of docs/physics.md §2, by key.
    pub fn presets() -> Vec<Material> {
        vec![
            Material::preset("steel", 208.0, 0.30, 7850.0, 12.5e-6, 46.6, 475.0),
            Material::preset("steel-7004", 200.0, 0.25, 7750.0, 12.5e-6, 46.6, 475.0),
            Material::preset("si3n4", 310.0, 0.26, 3200.0, 3.2e-6, 30.0, 700.0),
            Material::preset("zro2", 220.0, 0.28, 5670.0, 9.8e-6, 2.5, 460.0),
            Material::preset("phenolic", 1.73, 0.30, 1500.0, 30e-6, 0.3, 1400.0),
        ]
    }

    /// Look a preset up by key (case-insensitive).
    pub fn by_name(name: &str) -> Result<Material> {
        let all = Material::presets();
        all.iter()
            .find(|m| m.name.eq_ignore_ascii_case(name))
            .cloned()
            .ok_or_else(|| Error::Unknown {
                what: "material",
                name: name.to_string(),
                known: all.iter().map(|m| m.name.clone()).collect(),
            })
    }

    /// Check every field; errors name `prefix.field`.
    pub fn validate(&self, prefix: &str) -> Result<()> {
        crate::seam::fields::check(prefix, Self::FIELDS, self)?;
        Ok(())
    }

    /// `(1 - nu²)/E`, this body's share of the contact compliance.
    pub fn compliance(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus
    }
}

/// Effective modulus of a pair, `E' = 2 / ((1 - nu_a²)/E_a + (1 - nu_b²)/E_b)`
/// (Hamrock & Dowson's convention; Johnson's `E*` is `E'/2`).
pub fn effective_modulus(a: &Material, b: &Material) -> f64 {
    2.0 / (a.compliance() + b.compliance())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steel_pair_effective_modulus_matches_hand_value() {
        let s = Material::by_name("steel").unwrap();
        // E' = E/(1-nu^2) for identical bodies.
        let e = effective_modulus(&s, &s);
        assert!((e - 208e9 / (1.0 - 0.09)).abs() / e < 1e-12);
    }

    #[test]
    fn unknown_material_lists_known() {
        let err = Material::by_name("unobtainium").unwrap_err().to_string();
        assert!(
            err.contains("unobtainium") && err.contains("si3n4"),
            "{err}"
        );
    }

    #[test]
    fn poisson_out_of_range_is_named() {
        let mut m = Material::by_name("steel").unwrap();
        m.poisson_ratio = 0.6;
        let err = m.validate("ball").unwrap_err().to_string();
        assert!(err.contains("ball.poisson_ratio"), "{err}");
    }
}
