//! Unit conversions. SI inside the library; rpm, mm, µm and degrees only at the edges
//! (bearing files, scenes, the command line and reports).

use std::f64::consts::PI;

/// rpm → rad/s.
pub fn rpm_to_rad_s(rpm: f64) -> f64 {
    rpm * PI / 30.0
}
/// rad/s → rpm.
pub fn rad_s_to_rpm(w: f64) -> f64 {
    w * 30.0 / PI
}
/// mm → m.
pub fn mm(v: f64) -> f64 {
    v * 1e-3
}
/// µm → m.
pub fn um(v: f64) -> f64 {
    v * 1e-6
}
/// degrees → radians.
pub fn deg(v: f64) -> f64 {
    v.to_radians()
}
/// GPa → Pa.
pub fn gpa(v: f64) -> f64 {
    v * 1e9
}

/// The label of a value in a table a person reads (CSV headers, DataFrame columns, JSON
/// summary keys): `name [unit]`, SI symbols, `1` for a dimensionless number, `Mrev` for
/// millions of revolutions; the bare name for text, flags and structure (`unit` empty).
/// Programs address variables by the bare name (FMI, C, `Component.get`) with the unit in
/// the variable table. docs/columns.md lists every label.
pub fn label(name: &str, unit: &str) -> String {
    if unit.is_empty() {
        name.to_string()
    } else {
        format!("{name} [{unit}]")
    }
}

/// A label split into its name and unit (`"force.y [N]"` → `("force.y", Some("N"))`,
/// `"scene"` → `("scene", None)`): the inverse of [`label`].
pub fn split_label(label: &str) -> (&str, Option<&str>) {
    match label.strip_suffix(']').and_then(|s| s.rsplit_once(" [")) {
        Some((name, unit)) if !name.is_empty() && !unit.is_empty() => (name, Some(unit)),
        _ => (label, None),
    }
}
