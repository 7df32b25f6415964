//! A set as its files spell it: the keys a `[set]` table of a scene and a `[[location]]` of
//! a shaft file share (edge units: mm, µm, N, N/µm), their field rows, and the
//! [`SetSpec`] they make. Written once here; the scene mounts [`SetFile::FIELDS`] under
//! `set`, the shaft file reads the same struct under each location.

use super::{bearing_by_name, Arrangement, Preload, Row, SetSpec, ARRANGEMENTS};
use crate::error::{Error, Result};
use crate::geometry::Bearing;
use crate::seam::fields::{choice, ge, gt, int_choice, name, number, table, Names, ANY};
use serde::{Deserialize, Serialize};

/// One row given by hand (`[[set.row]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RowFile {
    /// Bearing name (a preset, a catalogue designation or a roller designation).
    pub bearing: String,
    /// Axial position of the row's centre from the set's reference point, mm.
    pub position_mm: f64,
    /// `+1`: the row carries shaft thrust toward `+z`; `-1`: toward `-z`.
    pub orientation: i32,
}

crate::declare_fields!(RowFile {
    bearing => name(Names::BearingPreset, "the row's bearing: a preset, a catalogue designation (70xx, 72xx + C, AC or B; 60xx ..) or a roller designation (NU206, 30206)"),
    position_mm => number("mm", ANY, "axial position of the row's centre from the set's reference point")
        .note("rows may not overlap: centres at least half the sum of their widths apart"),
    orientation => int_choice(&[-1, 1], "+1: the row carries shaft thrust toward +z (its load centre on its -z side); -1: toward -z"),
});

/// The keys of a set (module docs). Absent `arrangement` and `row`: one row of the
/// bearing, facing `orientation`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SetFile {
    /// A pair of identical rows of the bearing: `db`, `df`, `dt`, `trb_direct`,
    /// `trb_indirect`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arrangement: Option<Arrangement>,
    /// Gap between the pair's side faces, mm.
    #[serde(default)]
    pub spacer_mm: f64,
    /// One row only (no arrangement, no rows): its orientation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<i32>,
    /// Preload force, N: rigid (set by force), or with `spring_n_per_um` a spring's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload_n: Option<f64>,
    /// Rigid preload as an axial interference between the rows facing `+z` and `-z`, µm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload_offset_um: Option<f64>,
    /// Constant-force preload: the spring's stiffness, N/µm (with `preload_n`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spring_n_per_um: Option<f64>,
    /// Rows given one by one (instead of `arrangement`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub row: Vec<RowFile>,
}

crate::declare_fields!(SetFile {
    arrangement => choice(ARRANGEMENTS, "a pair of identical rows of the bearing: back to back (db), face to face (df), tandem (dt), tapered pair in direct (trb_direct) or indirect (trb_indirect) mounting")
        .note("absent: rows from `row`, or one row of the bearing"),
    spacer_mm => number("mm", ge(0.0), "gap between the pair's side faces (0: abutting)"),
    orientation => int_choice(&[-1, 1], "one row only (no arrangement, no row): +1 carries shaft thrust toward +z, -1 toward -z")
        .note("absent: +1"),
    preload_n => number("N", gt(0.0), "preload: the force each direction carries at standstill with no external load (rigid preload set by force), or with spring_n_per_um the spring's force (constant-force preload)")
        .note("needs rows facing both ways; not with preload_offset_um"),
    preload_offset_um => number("µm", ANY, "rigid preload as an axial interference between the rows facing +z and -z (spacer lengths, stand-out; negative: end play)")
        .note("not with preload_n"),
    spring_n_per_um => number("N/µm", gt(0.0), "constant-force preload: the spring's stiffness on the outer rings of the rows facing -z")
        .note("with preload_n"),
    row => table(),
});

impl SetFile {
    /// How many rows these keys give (rows by hand, a pair, or one row).
    pub fn row_count(&self) -> usize {
        match (self.row.len(), &self.arrangement) {
            (0, Some(_)) => 2,
            (0, None) => 1,
            (n, _) => n,
        }
    }

    /// The preload these keys give; `f(key)` names a key in a refusal.
    pub fn preload(&self, f: impl Fn(&str) -> String) -> Result<Preload> {
        Ok(
            match (self.preload_n, self.preload_offset_um, self.spring_n_per_um) {
                (None, None, None) => Preload::None,
                (Some(p), None, None) => Preload::Force(p),
                (None, Some(d), None) => Preload::Offset(d * 1e-6),
                (Some(p), None, Some(k)) => Preload::Spring {
                    stiffness: k * 1e6,
                    force: p,
                },
                (None, _, Some(_)) => {
                    return Err(Error::invalid(
                        f("spring_n_per_um"),
                        "a spring without preload_n",
                        "with preload_n (the spring's force at the standstill, no-load position)",
                    ))
                }
                _ => {
                    return Err(Error::invalid(
                        f("preload_n"),
                        "preload_n with preload_offset_um",
                        "one of: preload_n (rigid, by force); preload_offset_um (rigid, by \
                         offset); preload_n with spring_n_per_um (constant force)",
                    ))
                }
            },
        )
    }

    /// The set: rows from `row`, else a pair of `bearing` in `arrangement`, else one row of
    /// `bearing`. `preload` overrides the keys' preload (the shaft file's catalogue class);
    /// `prefix` is what a refusal names the keys under (`set`, `location[0]`);
    /// `axial_support`: some row must carry thrust (false for a shaft file's floating
    /// location, which carries none).
    pub fn spec(
        &self,
        prefix: &str,
        bearing: Option<&Bearing>,
        preload: Option<Preload>,
        axial_support: bool,
    ) -> Result<SetSpec> {
        let f = |s: &str| format!("{prefix}.{s}");
        let preload = match preload {
            Some(p) => p,
            None => self.preload(f)?,
        };
        let rename = |e: Error| match e {
            Error::Invalid {
                field,
                value,
                allowed,
            } => Error::Invalid {
                field: match field.strip_prefix("set.") {
                    Some(rest) => f(rest),
                    None => field,
                },
                value,
                allowed,
            },
            e => e,
        };
        if !self.row.is_empty() {
            if self.arrangement.is_some() || self.orientation.is_some() {
                return Err(Error::invalid(
                    f("row"),
                    "rows with arrangement or orientation",
                    "either row tables or arrangement (a pair) or orientation (one row), not both",
                ));
            }
            let rows = self
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
            s.validate_rows(axial_support).map_err(rename)?;
            return Ok(s);
        }
        let b = bearing.ok_or_else(|| Error::invalid(f("bearing"), "missing", "a bearing name"))?;
        match &self.arrangement {
            Some(a) => {
                if self.orientation.is_some() {
                    return Err(Error::invalid(
                        f("orientation"),
                        "with an arrangement",
                        "absent: the arrangement gives each row's orientation",
                    ));
                }
                SetSpec::pair(b, *a, self.spacer_mm * 1e-3, preload).map_err(rename)
            }
            None => {
                if self.spacer_mm != 0.0 {
                    return Err(Error::invalid(
                        f("spacer_mm"),
                        self.spacer_mm,
                        "absent or 0 for one row (a spacer belongs to a pair: give arrangement)",
                    ));
                }
                let s = SetSpec {
                    rows: vec![Row {
                        bearing: b.clone(),
                        position: 0.0,
                        orientation: self.orientation.unwrap_or(1),
                    }],
                    preload,
                };
                s.validate_rows(axial_support).map_err(rename)?;
                Ok(s)
            }
        }
    }
}
