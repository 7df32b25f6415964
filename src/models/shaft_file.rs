//! The shaft file that `raceway shaft` and the docs/sets.md page read: a rigid shaft on
//! bearing locations (single bearings or sets) with loads at axial positions
//! ([`super::shaft`]). Format (edge units: mm, N, N m, rpm, µm):
//!
//! ```toml
//! speed_rpm = 12000
//! [[load]]                  # any number
//! position_mm = 150
//! force_n = [0, -1500, 200] # Fx, Fy, Fz
//! moment_nm = [0, 0]        # Mx, My (optional)
//! [[location]]              # a set: a pair preset ...
//! name = "front"
//! position_mm = 0
//! bearing = "7008CE"
//! arrangement = "db"        # db | df | dt | trb_direct | trb_indirect; absent: one row
//! spacer_mm = 0             # gap between the pair's side faces
//! orientation = 1           # single row only: +1 carries thrust toward +z, -1 toward -z
//! preload_n = 300           # rigid preload set by force; or preload_offset_um = ..;
//! spring_n_per_um = 0.5     #   with preload_n: a constant-force spring; or preload_class
//! floating = false          # true: carries no axial load (outer rings slide, or an NU)
//! inner_ring_c = 20         # ring temperatures, °C (default 20, the set as assembled):
//! outer_ring_c = 20         #   ball rows' clearance and rigid preload follow them
//! [[location.row]]          # ... or rows given one by one (then no bearing/arrangement)
//! bearing = "7008CE"
//! position_mm = -7.5
//! orientation = 1
//! ```

use crate::error::{Error, Result};
use crate::models::set::{
    bearing_by_name, Arrangement, Preload, PreloadClass, RingTemperatures, Row, SetSpec,
};
use crate::models::shaft::{Location, Shaft, ShaftLoad};
use crate::units::rpm_to_rad_s;
use serde::Deserialize;

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct ShaftFile {
    #[serde(default)]
    speed_rpm: f64,
    #[serde(default)]
    load: Vec<LoadFile>,
    #[serde(default)]
    location: Vec<LocationFile>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct LoadFile {
    position_mm: f64,
    #[serde(default)]
    force_n: [f64; 3],
    #[serde(default)]
    moment_nm: [f64; 2],
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RowFile {
    bearing: String,
    position_mm: f64,
    orientation: i32,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct LocationFile {
    name: Option<String>,
    position_mm: f64,
    bearing: Option<String>,
    arrangement: Option<String>,
    #[serde(default)]
    spacer_mm: f64,
    orientation: Option<i32>,
    preload_n: Option<f64>,
    preload_offset_um: Option<f64>,
    spring_n_per_um: Option<f64>,
    preload_class: Option<String>,
    #[serde(default)]
    row: Vec<RowFile>,
    #[serde(default)]
    floating: bool,
    inner_ring_c: Option<f64>,
    outer_ring_c: Option<f64>,
}

fn location(i: usize, l: &LocationFile) -> Result<Location> {
    let f = |s: &str| format!("location[{i}].{s}");
    let preload = match (
        l.preload_n,
        l.preload_offset_um,
        l.spring_n_per_um,
        l.preload_class.as_deref(),
    ) {
        (None, None, None, None) => Preload::None,
        (Some(p), None, None, None) => Preload::Force(p),
        (None, Some(d), None, None) => Preload::Offset(d * 1e-6),
        (Some(p), None, Some(k), None) => Preload::Spring {
            stiffness: k * 1e6,
            force: p,
        },
        (None, None, None, Some(c)) => Preload::Class(match c {
            "light" => PreloadClass::Light,
            "medium" => PreloadClass::Medium,
            "heavy" => PreloadClass::Heavy,
            _ => {
                return Err(Error::invalid(
                    f("preload_class"),
                    c,
                    "light, medium or heavy",
                ))
            }
        }),
        _ => {
            return Err(Error::invalid(
                f("preload_n"),
                "a combination of preload keys",
                "one of: preload_n (rigid, by force); preload_offset_um (rigid, by offset); \
                 preload_n with spring_n_per_um (constant force); preload_class",
            ))
        }
    };
    let rename = |e: Error| match e {
        Error::Invalid {
            field,
            value,
            allowed,
        } => Error::Invalid {
            field: f(field.trim_start_matches("set.")),
            value,
            allowed,
        },
        e => e,
    };
    let set = if !l.row.is_empty() {
        if l.bearing.is_some() || l.arrangement.is_some() {
            return Err(Error::invalid(
                f("row"),
                "rows with bearing/arrangement",
                "either [[location.row]] tables or bearing (with arrangement), not both",
            ));
        }
        let rows = l
            .row
            .iter()
            .enumerate()
            .map(|(j, r)| {
                Ok(Row {
                    bearing: bearing_by_name(&r.bearing, &f(&format!("row[{j}].bearing")))?,
                    position: r.position_mm * 1e-3,
                    orientation: r.orientation,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let s = SetSpec { rows, preload };
        s.validate_rows(!l.floating).map_err(rename)?;
        s
    } else {
        let name = l
            .bearing
            .as_deref()
            .ok_or_else(|| Error::invalid(f("bearing"), "missing", "a bearing name"))?;
        let b = bearing_by_name(name, &f("bearing"))?;
        match &l.arrangement {
            Some(a) => {
                let arr = Arrangement::parse(a, &f("arrangement"))?;
                SetSpec::pair(&b, arr, l.spacer_mm * 1e-3, preload).map_err(rename)?
            }
            None => {
                let s = SetSpec {
                    rows: vec![Row {
                        bearing: b,
                        position: 0.0,
                        orientation: l.orientation.unwrap_or(1),
                    }],
                    preload,
                };
                s.validate_rows(!l.floating).map_err(rename)?;
                s
            }
        }
    };
    let reference = RingTemperatures::default();
    let temperatures = RingTemperatures {
        inner_c: l.inner_ring_c.unwrap_or(reference.inner_c),
        outer_c: l.outer_ring_c.unwrap_or(reference.outer_c),
        ball_c: None,
    };
    temperatures.validate().map_err(|e| match e {
        Error::Invalid {
            field,
            value,
            allowed,
        } => Error::Invalid {
            field: f(if field.ends_with("inner_c") {
                "inner_ring_c"
            } else {
                "outer_ring_c"
            }),
            value,
            allowed,
        },
        e => e,
    })?;
    Ok(Location {
        name: l.name.clone().unwrap_or_else(|| format!("{i}")),
        position: l.position_mm * 1e-3,
        set,
        floating: l.floating,
        temperatures,
    })
}

/// Read a shaft file.
pub fn read(path: &std::path::Path) -> Result<Shaft> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Error::Io(format!("cannot read {}: {e}", path.display())))?;
    from_toml(&text)
}

/// A shaft from the text of a shaft file.
pub fn from_toml(text: &str) -> Result<Shaft> {
    let f: ShaftFile = toml::from_str(text).map_err(|e| Error::Parse {
        what: "shaft file".into(),
        message: e.to_string(),
    })?;
    if !(f.speed_rpm.is_finite() && f.speed_rpm >= 0.0) {
        return Err(Error::invalid(
            "speed_rpm",
            f.speed_rpm,
            "a finite number >= 0",
        ));
    }
    Ok(Shaft {
        locations: f
            .location
            .iter()
            .enumerate()
            .map(|(i, l)| location(i, l))
            .collect::<Result<Vec<_>>>()?,
        loads: f
            .load
            .iter()
            .map(|l| ShaftLoad {
                position: l.position_mm * 1e-3,
                force: l.force_n,
                moment: l.moment_nm,
            })
            .collect(),
        omega: rpm_to_rad_s(f.speed_rpm),
    })
}
