//! The scene schema, documented and checked.
//!
//! - [`rows`] lists every field a scene may hold (dotted paths; `[]` stands for any item of
//!   an array of tables, `<variable>` for a key of `inputs.initial`, `<body>` for one of the
//!   four material bodies) with its type, unit, default, allowed range and meaning. The list
//!   of paths is not written by hand: it is enumerated from the serde serialisation of a
//!   scene whose every optional field and list is filled ([`schema_paths`]), and the
//!   defaults come from deserialising a scene that gives only the required fields (the
//!   specs' `Default`s, declared in their rows). Unit, range and description come from each
//!   spec's declared rows ([`super::fields`]), which [`MOUNTS`] places under the spec's
//!   prefix to make [`TABLE`]; a test fails when a serialised path has no entry or an entry
//!   names no path.
//! - [`check`] reports every problem of a scene text at once, each with its place
//!   (`line:column` for TOML, the field path for JSON): syntax errors, unknown keys (with
//!   the nearest known name), wrong types, values outside [`TABLE`]'s ranges, unknown
//!   presets, materials, lubricants, variables and enum spellings, missing required fields;
//!   then, when none of those remain, the library's own [`Scene::validate`] and
//!   [`Component::new`](crate::Component::new) for the cross-field problems, located by the
//!   field path their message names. TOML spans come from the `toml` crate's spanned
//!   document tables ([`toml::de::DeTable::parse_recoverable`]).

mod check;
mod defaults;
pub use check::*;
pub use defaults::*;

use super::fields::FieldDecl;
use super::scene::{
    BearingRef, FullSpec, InputSpec, ModelSpec, OperatingPoint, RunSpec, Scene, SkiddingSpec,
    SolverSpec,
};
use super::variables;
use crate::contact::traction::{AsperityFit, TractionLaw};
use crate::geometry::bearing::{CageSpec, MaterialSpec, MaterialsSpec};
use crate::geometry::{BearingSpec, Material};
use crate::models::effects::{
    DefectSpec, Effects, Element, FilmKind, LubricationSpec, SpacingSpec, ThermalSpec,
    WavinessSpec, WearSpec,
};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

pub use super::fields::{Bounds, Kind, Names};

/// One documented field: a declared row ([`FieldDecl`], whose fields it derefs to) at its
/// full path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Field {
    /// Dotted path (`[]`: any array item; `<variable>`, `<body>`: placeholders).
    pub path: &'static str,
    /// The row as its spec declares it.
    pub decl: FieldDecl,
}

impl std::ops::Deref for Field {
    type Target = FieldDecl;
    fn deref(&self) -> &FieldDecl {
        &self.decl
    }
}

/// Where each spec's declared fields sit in a scene: `(prefix, rows)`. The schema writes
/// no row itself: every row is declared once beside its spec ([`super::fields`]); a spec
/// used in two places (the traction law) is mounted twice.
pub const MOUNTS: &[(&str, &[FieldDecl])] = &[
    ("", Scene::FIELDS),
    ("bearing", BearingRef::FIELDS),
    ("bearing", BearingSpec::FIELDS),
    ("bearing.cage", CageSpec::FIELDS),
    ("bearing.materials", MaterialsSpec::FIELDS),
    ("bearing.materials.<body>", Material::FIELDS),
    ("model", ModelSpec::FIELDS),
    ("model.operating_point", OperatingPoint::FIELDS),
    (
        "model.start_hold",
        crate::models::quasi_static::hold::HoldSpec::FIELDS,
    ),
    ("model.skidding", SkiddingSpec::FIELDS),
    ("model.skidding.traction", TractionLaw::FIELDS),
    ("model.skidding.traction.fit", AsperityFit::FIELDS),
    ("model.full", FullSpec::FIELDS),
    ("model.full.traction", TractionLaw::FIELDS),
    ("model.full.traction.fit", AsperityFit::FIELDS),
    ("solver", SolverSpec::FIELDS),
    ("inputs", InputSpec::FIELDS),
    ("inputs.initial", InputSpec::INITIAL),
    ("effects.defects[]", DefectSpec::FIELDS),
    ("effects.waviness[]", WavinessSpec::FIELDS),
    ("effects.ball_spacing", SpacingSpec::FIELDS),
    ("effects.lubrication", LubricationSpec::FIELDS),
    ("effects.wear", WearSpec::FIELDS),
    ("effects.thermal", ThermalSpec::FIELDS),
    ("run", RunSpec::FIELDS),
    ("set", crate::models::set::SetFile::FIELDS),
    ("set.row[]", crate::models::set::RowFile::FIELDS),
];

/// Every documented field: the mounted rows ([`MOUNTS`]) with their full paths. Iterate
/// it (`for f in TABLE`, `TABLE.iter()`); paths match the serde schema exactly
/// (`tests: table_matches_schema`).
pub const TABLE: Table = Table;

/// The mounted rows, built once (see [`TABLE`]).
#[derive(Debug, Clone, Copy)]
pub struct Table;

impl Table {
    /// The rows, in mount order.
    pub fn iter(self) -> std::slice::Iter<'static, Field> {
        static ROWS: std::sync::LazyLock<Vec<Field>> = std::sync::LazyLock::new(|| {
            MOUNTS
                .iter()
                .flat_map(|(prefix, rows)| rows.iter().map(move |d| (*prefix, d)))
                .filter(|(_, d)| d.kind != Kind::Table)
                .map(|(prefix, d)| Field {
                    // Once per row for the life of the process: the paths are `'static`.
                    path: if prefix.is_empty() {
                        d.name
                    } else {
                        Box::leak(format!("{prefix}.{}", d.name).into_boxed_str())
                    },
                    decl: *d,
                })
                .collect()
        });
        ROWS.iter()
    }

    /// Number of rows.
    pub fn len(self) -> usize {
        self.iter().len()
    }

    /// No rows?
    pub fn is_empty(self) -> bool {
        self.len() == 0
    }
}

impl IntoIterator for Table {
    type Item = &'static Field;
    type IntoIter = std::slice::Iter<'static, Field>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

use Kind::*;

/// The entry of a normalised path.
pub fn field(path: &str) -> Option<&'static Field> {
    TABLE.iter().find(|f| f.path == path)
}

const BODIES: [&str; 4] = ["ball", "inner_ring", "outer_ring", "cage"];

/// Normalise a concrete path: array indices become `[]`, keys of `inputs.initial` become
/// `<variable>`, the body of an inline material becomes `<body>`.
fn normalise_child(parent_norm: &str, key: &str) -> String {
    if parent_norm == "inputs.initial" {
        return "inputs.initial.<variable>".into();
    }
    if let Some(body) = parent_norm.strip_prefix("bearing.materials.") {
        if BODIES.contains(&body) {
            return format!("bearing.materials.<body>.{key}");
        }
    }
    if parent_norm.is_empty() {
        key.to_string()
    } else {
        format!("{parent_norm}.{key}")
    }
}

/// Remove every key whose value is JSON `null` from a scene tree, at any depth; returns
/// whether one was removed. A null key is an absent key on every face: serde reads a null
/// optional field as absent but refuses a null where a value is required, while the check
/// walks the tree; removing the keys first makes both read the same tree (a null inside a
/// list stays, and is refused by both). What a serialised `Scene` writes for an unset
/// optional field (`null`) so reads back as unset. The tree's depth is bounded by
/// [`crate::nesting`] before this runs.
pub fn strip_nulls(v: &mut serde_json::Value) -> bool {
    match v {
        serde_json::Value::Object(m) => {
            let before = m.len();
            m.retain(|_, x| !x.is_null());
            let mut removed = m.len() != before;
            for x in m.values_mut() {
                removed |= strip_nulls(x);
            }
            removed
        }
        serde_json::Value::Array(items) => {
            let mut removed = false;
            for x in items {
                removed |= strip_nulls(x);
            }
            removed
        }
        _ => false,
    }
}

/// The first place in a parsed scene where a list stands for a table (serde would read
/// `model = ["ring", "load"]` by position), as `(path, expected)` with the path as the
/// scene spells it; `None` when there is none.
pub fn list_for_table(v: &serde_json::Value) -> Option<(String, &'static str)> {
    fn is_table(norm: &str) -> bool {
        let body = norm
            .strip_prefix("bearing.materials.")
            .is_some_and(|b| BODIES.contains(&b));
        body || TABLE.iter().any(|f| {
            f.path.len() > norm.len() + 1
                && f.path.starts_with(norm)
                && f.path.as_bytes()[norm.len()] == b'.'
        })
    }
    fn is_list(norm: &str) -> bool {
        let p = format!("{norm}[]");
        TABLE.iter().any(|f| f.path.starts_with(&p))
    }
    fn walk(v: &serde_json::Value, norm: &str, path: &str) -> Option<(String, &'static str)> {
        match v {
            serde_json::Value::Array(items) => {
                if is_list(norm) {
                    let item = format!("{norm}[]");
                    items
                        .iter()
                        .enumerate()
                        .find_map(|(i, x)| walk(x, &item, &format!("{path}[{i}]")))
                } else if is_table(norm) || norm.is_empty() {
                    Some((path.to_string(), "a table"))
                } else {
                    None
                }
            }
            serde_json::Value::Object(m) => m.iter().find_map(|(k, x)| {
                let child = normalise_child(norm, k);
                let p = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                walk(x, &child, &p)
            }),
            _ => None,
        }
    }
    walk(v, "", "")
}

/// A serde message in the scene's words: Rust type names (`struct RunSpec`, `enum Level`,
/// `f64`, `u32`, `a sequence`, `a map`) become what a scene writes.
pub fn user_words(message: &str) -> String {
    let message = message
        .replace(
            "data did not match any variant of untagged enum BearingRef",
            "expected a bearing preset name or a table of bearing fields",
        )
        .replace("internally tagged enum ", "struct ");
    let mut out = String::with_capacity(message.len());
    let mut rest = message.as_str();
    while let Some(i) = rest.find("struct ").or_else(|| rest.find("enum ")) {
        let (head, tail) = rest.split_at(i);
        out.push_str(head);
        let (word, after) = tail.split_at(tail.find(' ').unwrap_or(tail.len()) + 1);
        let end = after
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(after.len());
        if end > 0 && after.starts_with(|c: char| c.is_ascii_uppercase()) {
            out.push_str(if word == "struct " {
                "a table"
            } else {
                "one of the allowed names"
            });
            rest = &after[end..];
        } else {
            out.push_str(word);
            rest = after;
        }
    }
    out.push_str(rest);
    for (from, to) in [
        ("expected f64", "expected a number"),
        ("expected u32", "expected a non-negative integer"),
        ("expected u64", "expected a non-negative integer"),
        ("expected usize", "expected a non-negative integer"),
        ("a sequence", "a list"),
        ("sequence", "list"),
        ("a map", "a table"),
    ] {
        out = out.replace(from, to);
    }
    out
}

// ---------------------------------------------------------------------------------------
// Explain.

/// One documented row: the table entry with its default.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Row {
    /// Path.
    pub path: String,
    /// Type.
    #[serde(rename = "type")]
    pub type_name: String,
    /// Unit.
    pub unit: String,
    /// Default.
    pub default: String,
    /// Allowed range.
    pub range: String,
    /// Meaning.
    pub description: String,
}

/// The allowed range of a field as text.
pub fn range_text(f: &Field) -> String {
    let base = match f.kind {
        Float | Int => f.bounds.text(),
        Text => "any text".into(),
        Enum(v) => format!("one of {}", v.join(", ")),
        IntChoice(v) => format!(
            "one of {}",
            v.iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
        Name(n) | NameOrTable(n) => format!("one of {}", n.list().join(", ")),
        Bool => "true or false".into(),
        Kind::Table => "a table".into(),
    };
    let base = if matches!(f.kind, NameOrTable(_)) {
        format!("{base}, or a table")
    } else {
        base
    };
    if f.note.is_empty() {
        base
    } else {
        format!("{base}; {}", f.note)
    }
}

/// Every field, in schema order.
pub fn rows() -> Vec<Row> {
    let defaults = defaults();
    TABLE
        .iter()
        .map(|f| Row {
            path: f.path.into(),
            type_name: f.kind.type_name().into(),
            unit: f.unit.into(),
            default: defaults
                .get(f.path)
                .map(Default_::text)
                .unwrap_or_else(|| "absent".into()),
            range: range_text(f),
            description: f.description.into(),
        })
        .collect()
}

/// `raceway scene --explain`: text or JSON.
pub fn explain(json: bool) -> String {
    let rows = rows();
    if json {
        return serde_json::to_string_pretty(&rows).expect("rows serialise") + "\n";
    }
    let mut s = String::from(
        "Scene fields (TOML; JSON takes the same names). `[]`: any item of the list;\n\
         <variable>: an input variable name; <body>: ball, inner_ring, outer_ring or cage.\n\n",
    );
    let mut section = "";
    for r in &rows {
        let top = r.path.split(['.', '[']).next().unwrap_or("");
        if top != section {
            section = if r.path.contains('.') { top } else { "" };
            if !section.is_empty() {
                let _ = writeln!(s, "[{section}]");
            }
        }
        let _ = writeln!(
            s,
            "  {}  ({}, {})  default {}\n      range: {}\n      {}",
            r.path, r.type_name, r.unit, r.default, r.range, r.description
        );
    }
    s.push('\n');
    s.push_str(super::limits::EXPLAIN);
    s
}

// ---------------------------------------------------------------------------------------
/// One-line summary of a clean scene.
pub fn summary(scene: &Scene) -> String {
    let bearing = match &scene.bearing {
        BearingRef::Preset(p) => p.clone(),
        BearingRef::Table(_) => scene
            .bearing
            .spec()
            .map(|s| s.name)
            .unwrap_or_else(|_| "table".into()),
    };
    let e = &scene.effects;
    let mut effects = Vec::new();
    if !e.defects.is_empty() {
        effects.push(format!("{} defect(s)", e.defects.len()));
    }
    if !e.waviness.is_empty() {
        effects.push(format!("{} waviness harmonic(s)", e.waviness.len()));
    }
    if e.ball_spacing.is_some() {
        effects.push("ball spacing".into());
    }
    if let Some(l) = &e.lubrication {
        if l.film == FilmKind::Ehl {
            effects.push("EHL film".into());
        }
    }
    if let Some(w) = &e.wear {
        effects.push(format!("race wear ({} cycles)", w.cycles));
    }
    if e.thermal.is_some() {
        effects.push("thermal network".into());
    }
    let m = &scene.model;
    let level = if m.level == super::Level::Ring {
        format!("ring {}-DOF", m.ring_dof)
    } else {
        m.level.name().to_string()
    };
    format!(
        "{bearing}, {level}, {}-driven, {}, run {} s at {} s steps",
        match m.causality {
            variables::Causality::Motion => "motion",
            variables::Causality::Load => "load",
        },
        if effects.is_empty() {
            "no effects".to_string()
        } else {
            effects.join(", ")
        },
        scene.run.duration_s,
        scene.run.step_s
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `scene --check`'s one line names every effect the scene runs, wear and the thermal
    /// network included (they used to read "no effects" beside an EHL film or alone).
    #[test]
    fn summary_names_wear_and_thermal() {
        let read = |name: &str| {
            let path = format!("{}/examples/scenes/{name}", env!("CARGO_MANIFEST_DIR"));
            Scene::from_text(&std::fs::read_to_string(path).unwrap()).unwrap()
        };
        let wear = summary(&read("6012-wear.toml"));
        assert!(wear.contains("race wear (5 cycles)"), "{wear}");
        assert!(!wear.contains("thermal"), "{wear}");
        let thermal = summary(&read("7008ce-thermal.toml"));
        assert!(thermal.contains("EHL film, thermal network"), "{thermal}");
        let pair = summary(&read("7008ce-db-pair-thermal.toml"));
        assert!(
            pair.contains("thermal network") && !pair.contains("no effects"),
            "{pair}"
        );
        let plain = summary(&Scene::default_scene());
        assert!(plain.contains("no effects"), "{plain}");
    }

    #[test]
    fn table_matches_schema() {
        let schema: BTreeSet<String> = schema_paths().into_keys().collect();
        let table: BTreeSet<String> = TABLE.iter().map(|f| f.path.to_string()).collect();
        let missing: Vec<_> = schema.difference(&table).collect();
        let stale: Vec<_> = table.difference(&schema).collect();
        assert!(
            missing.is_empty(),
            "schema fields without a table entry: {missing:?}"
        );
        assert!(
            stale.is_empty(),
            "table entries naming no schema field: {stale:?}"
        );
        assert_eq!(table.len(), TABLE.len(), "duplicate table entries");
    }
}
