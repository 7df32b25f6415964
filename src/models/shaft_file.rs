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
use crate::models::set::{bearing_by_name, Preload, PreloadClass, RingTemperatures, SetFile};
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
    location: Vec<toml::Table>,
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

/// The keys of a location beyond the set's ([`SetFile`]).
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct LocationKeys {
    name: Option<String>,
    position_mm: f64,
    bearing: Option<String>,
    preload_class: Option<String>,
    #[serde(default)]
    floating: bool,
    inner_ring_c: Option<f64>,
    outer_ring_c: Option<f64>,
}

fn location(i: usize, table: &toml::Table) -> Result<Location> {
    let f = |s: &str| format!("location[{i}].{s}");
    let parse = |e: toml::de::Error| Error::Parse {
        what: format!("shaft file, location[{i}]"),
        message: e.to_string(),
    };
    // The location's own keys, then the set's (one struct for the scene's `[set]` and this).
    let (mut own, mut set) = (toml::Table::new(), toml::Table::new());
    for (k, v) in table {
        if [
            "name",
            "position_mm",
            "bearing",
            "preload_class",
            "floating",
            "inner_ring_c",
            "outer_ring_c",
        ]
        .contains(&k.as_str())
        {
            own.insert(k.clone(), v.clone());
        } else {
            set.insert(k.clone(), v.clone());
        }
    }
    let l: LocationKeys = own.try_into().map_err(parse)?;
    let keys: SetFile = set.try_into().map_err(parse)?;
    let class = match l.preload_class.as_deref() {
        None => None,
        Some(c) => {
            if keys.preload_n.is_some() || keys.preload_offset_um.is_some() {
                return Err(Error::invalid(
                    f("preload_class"),
                    "preload_class with preload_n or preload_offset_um",
                    "one preload: preload_n, preload_offset_um or preload_class",
                ));
            }
            Some(Preload::Class(match c {
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
            }))
        }
    };
    if !keys.row.is_empty() && l.bearing.is_some() {
        return Err(Error::invalid(
            f("row"),
            "rows with bearing",
            "either [[location.row]] tables or bearing (with arrangement), not both",
        ));
    }
    let b = match (&l.bearing, keys.row.is_empty()) {
        (Some(name), _) => Some(bearing_by_name(name, &f("bearing"))?),
        (None, true) => {
            return Err(Error::invalid(f("bearing"), "missing", "a bearing name"));
        }
        (None, false) => None,
    };
    let set = keys.spec(&format!("location[{i}]"), b.as_ref(), class, !l.floating)?;
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
        name: l.name.unwrap_or_else(|| format!("{i}")),
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
