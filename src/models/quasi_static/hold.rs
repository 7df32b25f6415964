//! Held ring coordinates: which of the inner ring's five coordinates `(x, y, z, rx, ry)` a
//! quasi-static solve keeps at a given value, in the edge units a user types (µm, mrad).
//! One spelling for the command line (`--hold rx_mrad=0,ry_mrad=0`), Python
//! (`hold={"rx_mrad": 0}`) and scenes (`[model.start_hold]`).

use super::Hold;
use crate::error::{Error, Result};
use crate::seam::fields::{number, ANY};
use serde::{Deserialize, Serialize};

/// The coordinates' names with their edge unit, in the order `(x, y, z, rx, ry)`.
pub const NAMES: [&str; 5] = ["x_um", "y_um", "z_um", "rx_mrad", "ry_mrad"];

/// Edge unit to SI of each coordinate (µm → m, mrad → rad).
const TO_SI: [f64; 5] = [1e-6, 1e-6, 1e-6, 1e-3, 1e-3];

/// `[model.start_hold]` and the hold of `raceway quasi-static`: the coordinates given are
/// held at that value (absent: solved). In a scene it acts on the load-driven static start
/// (`model.causality = "load"`, `model.start = "equilibrium"`) and is ignored otherwise.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct HoldSpec {
    /// Radial displacement along x, µm.
    pub x_um: Option<f64>,
    /// Radial displacement along y, µm.
    pub y_um: Option<f64>,
    /// Axial displacement, µm.
    pub z_um: Option<f64>,
    /// Tilt about x, mrad.
    pub rx_mrad: Option<f64>,
    /// Tilt about y, mrad.
    pub ry_mrad: Option<f64>,
}

crate::declare_fields!(HoldSpec {
    x_um: None => number("µm", ANY, "load-driven static start: hold the inner ring's x displacement at this value while solving the others")
        .note("absent: solved"),
    y_um: None => number("µm", ANY, "load-driven static start: hold the y displacement")
        .note("absent: solved"),
    z_um: None => number("µm", ANY, "load-driven static start: hold the axial displacement (5-DOF ring)")
        .note("absent: solved"),
    rx_mrad: None => number("mrad", ANY, "load-driven static start: hold the tilt about x (5-DOF ring)")
        .note("absent: solved"),
    ry_mrad: None => number("mrad", ANY, "load-driven static start: hold the tilt about y (5-DOF ring)")
        .note("absent: solved"),
});

impl HoldSpec {
    /// The values in edge units, `(x, y, z, rx, ry)`.
    pub fn edge(&self) -> [Option<f64>; 5] {
        [self.x_um, self.y_um, self.z_um, self.rx_mrad, self.ry_mrad]
    }

    /// From values in edge units.
    pub fn from_edge(v: [Option<f64>; 5]) -> HoldSpec {
        HoldSpec {
            x_um: v[0],
            y_um: v[1],
            z_um: v[2],
            rx_mrad: v[3],
            ry_mrad: v[4],
        }
    }

    /// The hold in SI (m, rad); a non-finite value is refused naming `field.<name>`.
    pub fn to_si(&self, field: &str) -> Result<Hold> {
        let e = self.edge();
        let mut h = [None; 5];
        for i in 0..5 {
            if let Some(v) = e[i] {
                if !v.is_finite() {
                    return Err(Error::invalid(
                        format!("{field}.{}", NAMES[i]),
                        v,
                        "a finite number",
                    ));
                }
                h[i] = Some(v * TO_SI[i]);
            }
        }
        Ok(h)
    }

    /// True when nothing is held.
    pub fn is_free(&self) -> bool {
        self.edge().iter().all(Option::is_none)
    }

    /// The held coordinates' names, `"rx_mrad, ry_mrad"` (empty: none).
    pub fn names(&self) -> String {
        held_names(&std::array::from_fn(|i| self.edge()[i].is_some()))
    }

    /// Parse `NAME=VALUE[,NAME=VALUE...]` (a bare `NAME` holds at 0), names from
    /// [`NAMES`] (the short `x`, `y`, `z`, `rx`, `ry` too); errors name `field`.
    pub fn parse(text: &str, field: &str) -> Result<HoldSpec> {
        let mut v: [Option<f64>; 5] = [None; 5];
        let allowed = || {
            format!(
                "comma-separated NAME=VALUE with NAME one of {} (µm, mrad), e.g. rx_mrad=0,ry_mrad=0",
                NAMES.join(", ")
            )
        };
        for part in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            let (name, value) = match part.split_once('=') {
                Some((n, x)) => (n.trim(), Some(x.trim())),
                None => (part, None),
            };
            let i = NAMES
                .iter()
                .position(|n| *n == name || n.split('_').next() == Some(name))
                .ok_or_else(|| Error::invalid(field, format!("`{part}`"), allowed()))?;
            let x = match value {
                None => 0.0,
                Some(s) => s
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| Error::invalid(field, format!("`{part}`"), allowed()))?,
            };
            if v[i].is_some() {
                return Err(Error::invalid(
                    field,
                    format!("`{text}`"),
                    format!("each coordinate once ({} given twice)", NAMES[i]),
                ));
            }
            v[i] = Some(x);
        }
        Ok(HoldSpec::from_edge(v))
    }
}

/// The names of the held coordinates, comma-separated.
pub fn held_names(held: &[bool; 5]) -> String {
    (0..5)
        .filter(|&i| held[i])
        .map(|i| NAMES[i].split('_').next().unwrap_or(NAMES[i]))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_round_trips_and_names_bad_input() {
        let h = HoldSpec::parse("rx_mrad=0, ry=0.5,z_um", "--hold").unwrap();
        assert_eq!(h.edge(), [None, None, Some(0.0), Some(0.0), Some(0.5)]);
        assert_eq!(
            h.to_si("h").unwrap(),
            [None, None, Some(0.0), Some(0.0), Some(0.5e-3)]
        );
        assert_eq!(held_names(&[false, false, true, true, true]), "z, rx, ry");
        for bad in ["tilt=0", "rx=abc", "rx=0,rx=1", "x=inf"] {
            let e = HoldSpec::parse(bad, "--hold").unwrap_err().to_string();
            assert!(e.contains("--hold"), "{bad}: {e}");
        }
        assert!(HoldSpec::parse("", "--hold").unwrap().is_free());
    }
}
