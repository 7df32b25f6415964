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
