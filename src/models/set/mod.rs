//! A bearing set: several rows on one shaft location, seen by the shaft as one component
//! (docs/physics.md §11).
//!
//! Each row is a [`Bearing`] (any element type the quasi-static level has a law for) at an
//! axial position `z_r` from the set's reference point, facing `+z` or `-z`. A row facing
//! `+z` is the bearing as the quasi-static model describes it: a shaft displacement `+z`
//! loads it, so it carries shaft thrust toward `+z`, and its contact lines meet the axis on
//! its `-z` side (the load centre, `dm/2 tan(alpha)` from the row). A row facing `-z` is its
//! mirror image in its own radial plane.
//!
//! # Shaft motion at a row, forces at the reference point
//!
//! The shaft's motion `q = (x, y, z, rx, ry)` at the reference point moves the row's
//! centre (on the axis, at `(0, 0, z_r)`) by `(rx, ry, 0) x (0, 0, z_r)`:
//! `x_r = x + z_r ry`, `y_r = y - z_r rx`, the same `z`, `rx`, `ry`: `q_r = A_r q`. The row's
//! forces `F_r` (on the shaft, at the row) give at the reference point
//! `Mx = Mx_r - z_r Fy_r`, `My = My_r + z_r Fx_r` (`M = M_r + r_r x F_r`), which is
//! `F = A_r^T F_r` (virtual work), so `K = sum A_r^T K_r A_r`.
//!
//! # Orientation
//!
//! Mirroring in the row's radial plane maps translations `(x, y, z)` to `(x, y, -z)` and,
//! rotations being axial vectors, `(rx, ry)` to `(-rx, -ry)`; forces and moments the same:
//! with `T = diag(1, 1, -1, -1, -1)` a row facing `-z` answers `F_r = T F(T q_r)` and
//! `K_r = T K(T q_r) T`, `F` and `K` the quasi-static model's. The shaft's speed about `z`
//! (an axial vector along the mirror's normal) is unchanged.
//!
//! # Preload
//!
//! - **rigid, by offset** ([`Preload::Offset`]): the rows' rings are clamped with an axial
//!   interference `delta` between the rows facing `+z` and those facing `-z` (spacer
//!   lengths, ground stand-out): each row's own axial displacement is `±z + delta/2`. Only
//!   the sum of the two groups' offsets matters (the shaft's `z` takes up the rest).
//! - **rigid, by force** ([`Preload::Force`]): the same, with the offsets set so that each
//!   group carries the force at standstill with no external load (rows of one group share
//!   it at a common displacement, as tandem rows on one spacer do).
//! - **constant force, by a spring** ([`Preload::Spring`]): the outer rings of the rows
//!   facing `-z` slide in the housing against a spring of stiffness `k_s` that pushes them
//!   with `F_s` at the standstill, no-load position. Their common axial shift `u` is an
//!   internal unknown: `sum_r P_r(u) = F_s + k_s u` (`P_r` the row's thrust), solved inside
//!   every evaluation, and condensed out of the stiffness:
//!   `K = K_0 - b c^T / (sum_r K_r,zz + k_s)` with `b = sum_r A_r^T T_r K_r e_z` and
//!   `c = sum_r A_r^T T_r K_r^T e_z` over the sliding rows.
//! - **catalogue class** ([`Preload::Class`]): refused unless the maker's value for the
//!   bearing is known (none is in the project's data today).

mod file;
pub mod level;
mod life;
pub mod preload;
mod row;
mod solve;
#[cfg(test)]
mod tests;

pub use file::{RowFile, SetFile};
pub use life::{system_life, weibull_slope};
pub use preload::RingTemperatures;
pub use row::RowReport;
pub(crate) use solve::newton5 as newton5_shared;
pub use solve::{Set, SetEval, SetSolution};

use crate::error::{Error, Result};
use crate::geometry::Bearing;
use serde::{Deserialize, Serialize};

/// One row of a set.
#[derive(Debug, Clone)]
pub struct Row {
    /// The bearing.
    pub bearing: Bearing,
    /// Axial position of the row's centre from the set's reference point, m.
    pub position: f64,
    /// `+1`: the row carries shaft thrust toward `+z` (module docs); `-1`: toward `-z`.
    pub orientation: i32,
}

/// A catalogue preload class.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PreloadClass {
    /// Light (class A of some makers).
    Light,
    /// Medium.
    Medium,
    /// Heavy.
    Heavy,
}

/// How a set is preloaded (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Preload {
    /// No preload: the rows sit at their reference positions (axial offsets zero).
    None,
    /// Rigid preload by an axial interference between the rows facing `+z` and `-z`, m.
    Offset(f64),
    /// Rigid preload set by the force each direction carries at standstill, N.
    Force(f64),
    /// Constant-force preload: a spring on the outer rings of the rows facing `-z`.
    Spring {
        /// Spring stiffness, N/m.
        stiffness: f64,
        /// Spring force at the standstill, no-load position, N.
        force: f64,
    },
    /// A maker's catalogue class.
    Class(PreloadClass),
}

/// Arrangements of a pair of identical rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Arrangement {
    /// Back to back ("O"): load centres outside the pair.
    Db,
    /// Face to face ("X"): load centres between the rows.
    Df,
    /// Tandem: both rows carry thrust toward `+z`.
    Dt,
    /// Tapered roller pair, direct mounting (face to face, as [`Arrangement::Df`]).
    TrbDirect,
    /// Tapered roller pair, indirect mounting (back to back, as [`Arrangement::Db`]).
    TrbIndirect,
}

/// The spellings of [`Arrangement`].
pub const ARRANGEMENTS: &[&str] = &["db", "df", "dt", "trb_direct", "trb_indirect"];

impl Arrangement {
    /// The orientations of the row at `-z` and the row at `+z`.
    pub fn orientations(self) -> [i32; 2] {
        match self {
            Arrangement::Db | Arrangement::TrbIndirect => [1, -1],
            Arrangement::Df | Arrangement::TrbDirect => [-1, 1],
            Arrangement::Dt => [1, 1],
        }
    }

    /// By its spelling (case-insensitive), naming `field` when unknown.
    pub fn parse(s: &str, field: &str) -> Result<Self> {
        Ok(match s.to_ascii_lowercase().as_str() {
            "db" => Arrangement::Db,
            "df" => Arrangement::Df,
            "dt" => Arrangement::Dt,
            "trb_direct" => Arrangement::TrbDirect,
            "trb_indirect" => Arrangement::TrbIndirect,
            _ => {
                return Err(Error::invalid(
                    field,
                    s,
                    format!("one of {}", ARRANGEMENTS.join(", ")),
                ))
            }
        })
    }
}

/// A set as plain data: rows and preload (validated by [`SetSpec::validate`]).
#[derive(Debug, Clone)]
pub struct SetSpec {
    /// The rows.
    pub rows: Vec<Row>,
    /// The preload.
    pub preload: Preload,
}

impl SetSpec {
    /// A pair of identical rows in `arrangement`, their side faces `spacer` (m, >= 0) apart,
    /// centred on the reference point.
    pub fn pair(
        bearing: &Bearing,
        arrangement: Arrangement,
        spacer: f64,
        preload: Preload,
    ) -> Result<SetSpec> {
        if !(spacer.is_finite() && spacer >= 0.0) {
            return Err(Error::invalid(
                "set.spacer_mm",
                format!("{} mm", spacer * 1e3),
                ">= 0 mm (the gap between the rows' side faces; 0: rows abutting)",
            ));
        }
        let half = 0.5 * (bearing.width + spacer);
        let [o0, o1] = arrangement.orientations();
        let spec = SetSpec {
            rows: vec![
                Row {
                    bearing: bearing.clone(),
                    position: -half,
                    orientation: o0,
                },
                Row {
                    bearing: bearing.clone(),
                    position: half,
                    orientation: o1,
                },
            ],
            preload,
        };
        spec.validate()?;
        Ok(spec)
    }

    /// Check the set (module docs): at least one row, orientations `±1`, finite positions,
    /// rows not overlapping in space (centres at least half the sum of their widths apart),
    /// some row carrying axial load, and a preload that can be applied.
    pub fn validate(&self) -> Result<()> {
        self.validate_rows(true)
    }

    /// [`SetSpec::validate`], the axial support asked for only when `axial` (a set on a
    /// shaft location that floats axially carries no axial load and needs none).
    pub fn validate_rows(&self, axial: bool) -> Result<()> {
        if self.rows.is_empty() {
            return Err(Error::invalid("set.row", "none", "at least one row"));
        }
        for (i, r) in self.rows.iter().enumerate() {
            if !r.position.is_finite() {
                return Err(Error::invalid(
                    format!("set.row[{i}].position_mm"),
                    r.position * 1e3,
                    "a finite number",
                ));
            }
            if r.orientation != 1 && r.orientation != -1 {
                return Err(Error::invalid(
                    format!("set.row[{i}].orientation"),
                    r.orientation,
                    "+1 (carries shaft thrust toward +z) or -1 (toward -z)",
                ));
            }
        }
        for i in 0..self.rows.len() {
            for j in i + 1..self.rows.len() {
                let (a, b) = (&self.rows[i], &self.rows[j]);
                let gap = (a.position - b.position).abs();
                let need = 0.5 * (a.bearing.width + b.bearing.width);
                if gap < need * (1.0 - 1e-9) {
                    return Err(Error::invalid(
                        format!("set.row[{j}].position_mm"),
                        format!("{:.3} mm", b.position * 1e3),
                        format!(
                            "a position that does not overlap row {i} (at {:.3} mm): their \
                             centres must be at least half the sum of their widths, {:.3} mm, \
                             apart (now {:.3} mm)",
                            a.position * 1e3,
                            need * 1e3,
                            gap * 1e3
                        ),
                    ));
                }
            }
        }
        if axial && !self.rows.iter().any(|r| carries_axial(&r.bearing)) {
            return Err(Error::invalid(
                "set.row",
                "no row carries axial load",
                "at least one row with axial support (a ball bearing, a tapered roller bearing \
                 or an NJ/NUP with spherical roller ends; NU and N rows float axially: on a \
                 shaft, mark such a location floating)",
            ));
        }
        let both = self.rows.iter().any(|r| r.orientation == 1)
            && self.rows.iter().any(|r| r.orientation == -1);
        let pos = |f: &str, v: f64, unit: &str, scale: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(Error::invalid(
                    f,
                    format!("{} {unit}", v * scale),
                    format!("a finite number > 0 {unit}"),
                ))
            }
        };
        match self.preload {
            Preload::None => {}
            Preload::Offset(d) => {
                if !d.is_finite() {
                    return Err(Error::invalid(
                        "set.preload_offset_um",
                        d * 1e6,
                        "a finite number",
                    ));
                }
            }
            Preload::Force(f) => pos("set.preload_n", f, "N", 1.0)?,
            Preload::Spring { stiffness, force } => {
                pos("set.spring_n_per_um", stiffness, "N/µm", 1e-6)?;
                pos("set.preload_n", force, "N", 1.0)?;
            }
            Preload::Class(c) => {
                return Err(Error::invalid(
                    "set.preload_class",
                    format!("{c:?}").to_lowercase(),
                    format!(
                        "a preload the project has values for: no maker's preload classes are \
                         known for {} (give the preload as a force, set.preload_n, or an \
                         offset, set.preload_offset_um, from the maker's catalogue)",
                        self.rows[0].bearing.name
                    ),
                ));
            }
        }
        if !matches!(self.preload, Preload::None) && !both {
            return Err(Error::invalid(
                if matches!(self.preload, Preload::Offset(_)) {
                    "set.preload_offset_um"
                } else {
                    "set.preload_n"
                },
                "a preload on rows that all face one way",
                "no preload (a tandem set is preloaded against another location), or rows \
                 facing both ways (orientation +1 and -1)",
            ));
        }
        Ok(())
    }
}

/// Whether a bearing's rows carry axial load (ball bearings do; the cylindrical roller
/// bearings of the roller levels float axially).
pub fn carries_axial(b: &Bearing) -> bool {
    match &b.element {
        crate::geometry::element::Element::Ball(_) => true,
        // A tapered roller, or a flanged cylindrical one (NJ, NUP) whose roller ends are
        // spherical: the flange contact the law carries (flat ends carry none, §R8).
        crate::geometry::element::Element::Roller(r) => {
            r.kind.is_tapered()
                || r.flange
                    .as_ref()
                    .is_some_and(|f| f.roller_end_radius.is_some())
        }
    }
}

/// A bearing by name: a ball preset or catalogue designation, else a roller catalogue
/// designation (`NU206`, ..). `field` names the input in a refusal.
pub fn bearing_by_name(name: &str, field: &str) -> Result<Bearing> {
    if let Some(r) = crate::geometry::roller_catalogue::lookup(name) {
        return Bearing::from_roller(r.build()?);
    }
    crate::geometry::preset(name)
        .map_err(|e| Error::invalid(field, name, format!("a bearing name ({e})")))?
        .build()
}
