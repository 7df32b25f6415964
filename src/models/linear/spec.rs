//! `[model.operating_point]`: the linear level's scene spec, its fields declared once.

use crate::seam::fields::{number, ANY};
use serde::{Deserialize, Serialize};

/// The operating point the `linear` level linearises about.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OperatingPoint {
    /// Shaft speed, rpm.
    pub speed_rpm: f64,
    /// Loads on the inner ring, N and N m.
    pub fx: f64,
    /// y load, N.
    pub fy: f64,
    /// z (axial) load, N.
    pub fz: f64,
    /// Moment about x, N m.
    pub mx: f64,
    /// Moment about y, N m.
    pub my: f64,
}

crate::declare_fields!(OperatingPoint {
    speed_rpm: 0.0 => number("rpm", ANY, "linear level: shaft speed of the operating point"),
    fx: 0.0 => number("N", ANY, "linear level: load x"),
    fy: 1000.0 => number("N", ANY, "linear level: load y"),
    fz: 0.0 => number("N", ANY, "linear level: axial load z"),
    mx: 0.0 => number("N m", ANY, "linear level: moment about x"),
    my: 0.0 => number("N m", ANY, "linear level: moment about y"),
});
