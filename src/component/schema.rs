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
// Paths and defaults from serde.

fn steel_inline() -> MaterialSpec {
    MaterialSpec::Custom(Material::by_name("steel").expect("preset"))
}

/// A bearing spec with every optional field given (struct literals: a new field does not
/// compile until it is added here, and then the schema test asks for its table entry).
fn full_bearing(materials: MaterialsSpec) -> BearingSpec {
    BearingSpec {
        name: "6205".into(),
        kind: Default::default(),
        ball_diameter_mm: 7.94,
        pitch_diameter_mm: 39.04,
        ball_count: 9,
        inner_curvature: Some(0.52),
        outer_curvature: Some(0.52),
        contact_angle_deg: Some(0.0),
        clearance_um: Some(0.0),
        bore_mm: Some(25.0),
        outer_diameter_mm: Some(52.0),
        width_mm: Some(15.0),
        inner_ring_mass_kg: Some(0.05),
        outer_ring_mass_kg: Some(0.07),
        cage: CageSpec {
            inner_diameter_mm: Some(36.3),
            outer_diameter_mm: Some(41.8),
            width_mm: Some(6.3),
            mass_kg: Some(0.01),
            inertia_kg_m2: Some(4e-6),
            pocket_clearance_mm: Some(0.16),
            guide_clearance_mm: Some(0.2),
            guidance: Default::default(),
        },
        materials,
        source: String::new(),
    }
}

/// A scene with every optional section, field, list and map filled (two list items per
/// effect would add nothing: the paths of items are normalised to `[]`). Fields with a
/// value by default come with it (`..Default::default()`); an optional field must be given
/// `Some` here, or `table_matches_schema` names its row.
fn full_scene(bearing: BearingRef, traction: TractionLaw) -> Scene {
    let mut initial = BTreeMap::new();
    initial.insert("shaft.omega".to_string(), 100.0);
    Scene {
        title: "full".into(),
        bearing,
        model: ModelSpec {
            level: super::Level::Ring,
            skidding: SkiddingSpec {
                traction,
                pocket_clearance_mm: Some(0.1),
                spin_friction: 0.02,
                ..Default::default()
            },
            full: super::scene::FullSpec {
                traction,
                pocket_clearance_mm: Some(0.1),
                guide_width_mm: Some(3.0),
                guidance: Some(crate::geometry::Guidance::InnerRing),
                cage_unbalance_um: 2.0,
                ..Default::default()
            },
            ..Default::default()
        },
        solver: SolverSpec::default(),
        inputs: InputSpec {
            rule: Default::default(),
            initial,
        },
        effects: Effects {
            defects: vec![DefectSpec {
                race: Element::Ball,
                angle_deg: 0.0,
                width_mm: 0.5,
                depth_um: 10.0,
                ball: Some(0),
            }],
            waviness: vec![WavinessSpec {
                race: Element::Ball,
                order: 2,
                amplitude_um: 0.1,
                phase_deg: 0.0,
                ball: Some(0),
            }],
            ball_spacing: Some(SpacingSpec {
                scatter: 0.5,
                seed: 1,
            }),
            lubrication: Some(LubricationSpec {
                film: FilmKind::Ehl,
                lubricant: "study2".into(),
                viscosity_pa_s: Some(0.05),
                pressure_viscosity_m2_per_n: Some(2e-8),
                density_kg_m3: Some(870.0),
                roughness_um: Some(0.1),
            }),
            wear: Some(crate::models::effects::WearSpec::default()),
            thermal: Some(crate::models::effects::ThermalSpec {
                viscosity_cst: Some(30.0),
                contact_conductance_w_k: Some(1.0),
                ..Default::default()
            }),
        },
        run: RunSpec::default(),
    }
}

fn bearing_table(spec: &BearingSpec, preset: Option<&str>) -> toml::Table {
    let mut t = toml::Table::try_from(spec).expect("a bearing spec serialises");
    if let Some(p) = preset {
        t.insert("preset".into(), toml::Value::String(p.into()));
    }
    t
}

/// Full scenes covering every form: bearing as a table (with inline and preset
/// materials) and as a preset name, each traction law. Every one is a valid scene
/// (`tests`).
pub fn full_scenes() -> Vec<Scene> {
    let inline = MaterialsSpec {
        ball: steel_inline(),
        inner_ring: steel_inline(),
        outer_ring: steel_inline(),
        cage: MaterialSpec::Custom(Material::by_name("phenolic").expect("preset")),
    };
    let fitted = TractionLaw::Fitted {
        a: -0.01,
        b: 0.1,
        c: 10.0,
        d: 0.02,
        s_reg: 0.01,
        u_min: 0.1,
    };
    vec![
        full_scene(
            BearingRef::Table(bearing_table(&full_bearing(inline), Some("6205"))),
            TractionLaw::default(),
        ),
        full_scene(
            BearingRef::Table(bearing_table(&full_bearing(MaterialsSpec::default()), None)),
            fitted,
        ),
        full_scene(
            BearingRef::Preset("6205".into()),
            // With the optional override of the asperity share, so its rows are walked.
            TractionLaw::MixedEhl(crate::contact::traction::MixedEhl {
                fit: Some(Default::default()),
                ..Default::default()
            }),
        ),
    ]
}

fn walk_value(v: &toml::Value, norm: &str, out: &mut BTreeMap<String, toml::Value>) {
    match v {
        toml::Value::Table(t) => {
            for (k, c) in t {
                walk_value(c, &normalise_child(norm, k), out);
            }
        }
        toml::Value::Array(a) if a.iter().all(|x| x.is_table()) && !a.is_empty() => {
            for c in a {
                walk_value(c, &format!("{norm}[]"), out);
            }
        }
        leaf => {
            out.entry(norm.to_string()).or_insert_with(|| leaf.clone());
        }
    }
}

/// Every leaf path of the serde schema, normalised, with the value the full scenes give
/// it (used for its TOML type).
pub fn schema_paths() -> BTreeMap<String, toml::Value> {
    let mut out = BTreeMap::new();
    for s in full_scenes() {
        let v = toml::Value::try_from(&s).expect("a scene serialises");
        walk_value(&v, "", &mut out);
    }
    out
}

/// The smallest scene serde accepts: only the required fields of the scene, of one item of
/// each effect list and of the effect tables.
pub const MINIMAL_SCENE: &str = r#"
bearing = "6205"
[effects]
defects = [{ race = "outer", width_mm = 1.0, depth_um = 1.0 }]
waviness = [{ race = "outer", order = 1, amplitude_um = 0.1 }]
ball_spacing = { scatter = 0.0 }
lubrication = {}
"#;

/// The fields a bearing table without `preset` must give, and those of an inline material
/// (required whenever a material is given as a table).
pub const MINIMAL_BEARING: &str = r#"
name = "x"
ball_diameter_mm = 1.0
pitch_diameter_mm = 10.0
ball_count = 3
materials = { ball = { name = "m", youngs_modulus = 2e11, poisson_ratio = 0.3, density = 7800.0, thermal_expansion = 0.0, conductivity = 0.0, heat_capacity = 0.0 } }
"#;

/// A field's default as documented.
#[derive(Debug, Clone, PartialEq)]
pub enum Default_ {
    /// Must be given.
    Required,
    /// Required in a bearing table without `preset` (else the preset's).
    RequiredWithoutPreset,
    /// Absent unless given (see the note for what is used then).
    Absent,
    /// The value serde fills in.
    Value(toml::Value),
}

impl Default_ {
    /// Text for the documentation.
    pub fn text(&self) -> String {
        match self {
            Default_::Required => "required".into(),
            Default_::RequiredWithoutPreset => "the preset's; required without preset".into(),
            Default_::Absent => "absent".into(),
            Default_::Value(v) => match v {
                toml::Value::String(s) => format!("\"{s}\""),
                toml::Value::Float(x) if *x != 0.0 && !(1e-3..1e5).contains(&x.abs()) => {
                    format!("{x:e}")
                }
                toml::Value::Float(x) => format!("{x:?}"),
                other => other.to_string(),
            },
        }
    }
}

/// Concrete leaf paths of a TOML text (array items as `[i]`), for removal.
fn concrete_leaves(v: &toml::Value, path: Vec<PathSeg>, out: &mut Vec<Vec<PathSeg>>) {
    match v {
        toml::Value::Table(t) => {
            for (k, c) in t {
                let mut p = path.clone();
                p.push(PathSeg::Key(k.clone()));
                concrete_leaves(c, p, out);
            }
        }
        toml::Value::Array(a) if a.iter().all(|x| x.is_table()) && !a.is_empty() => {
            for (i, c) in a.iter().enumerate() {
                let mut p = path.clone();
                p.push(PathSeg::Index(i));
                concrete_leaves(c, p, out);
            }
        }
        _ => out.push(path),
    }
}

#[derive(Debug, Clone)]
enum PathSeg {
    Key(String),
    Index(usize),
}

fn remove_at(v: &mut toml::Value, path: &[PathSeg]) {
    match (path, v) {
        ([PathSeg::Key(k)], toml::Value::Table(t)) => {
            t.remove(k);
        }
        ([PathSeg::Key(k), rest @ ..], toml::Value::Table(t)) => {
            if let Some(c) = t.get_mut(k) {
                remove_at(c, rest)
            }
        }
        ([PathSeg::Index(i), rest @ ..], toml::Value::Array(a)) => {
            if let Some(c) = a.get_mut(*i) {
                remove_at(c, rest)
            }
        }
        _ => {}
    }
}

fn norm_of(prefix: &str, path: &[PathSeg]) -> String {
    let mut n = prefix.to_string();
    for s in path {
        match s {
            PathSeg::Key(k) => n = normalise_child(&n, k),
            PathSeg::Index(_) => n.push_str("[]"),
        }
    }
    n
}

/// The leaves of a minimal text that serde cannot do without: removing one makes `parses`
/// fail. Normalised with `prefix`.
fn required_of(
    text: &str,
    prefix: &str,
    parses: impl Fn(&toml::Value) -> bool,
) -> BTreeSet<String> {
    let v: toml::Value = toml::from_str(text).expect("minimal text parses");
    assert!(parses(&v), "the minimal text is accepted");
    let mut leaves = Vec::new();
    concrete_leaves(&v, Vec::new(), &mut leaves);
    leaves
        .into_iter()
        .filter(|p| {
            let mut w = v.clone();
            remove_at(&mut w, p);
            !parses(&w)
        })
        .map(|p| norm_of(prefix, &p))
        .collect()
}

/// The leaves serde requires in a scene, and in a bearing table without `preset`.
pub fn required_paths() -> (BTreeSet<String>, BTreeSet<String>) {
    let scene = required_of(MINIMAL_SCENE, "", |v| v.clone().try_into::<Scene>().is_ok());
    let bearing = required_of(MINIMAL_BEARING, "bearing", |v| {
        v.clone().try_into::<BearingSpec>().is_ok()
    });
    (scene, bearing)
}

/// Defaults of every path: serde's own, read back from the minimal scene and bearing;
/// required-ness from removing each field of them in turn.
pub fn defaults() -> BTreeMap<String, Default_> {
    let scene = Scene::from_text(MINIMAL_SCENE).expect("the minimal scene parses");
    let mut values = BTreeMap::new();
    walk_value(
        &toml::Value::try_from(&scene).expect("serialises"),
        "",
        &mut values,
    );
    let spec: BearingSpec = toml::from_str(MINIMAL_BEARING).expect("the minimal bearing parses");
    walk_value(
        &toml::Value::Table(bearing_table(&spec, None)),
        "bearing",
        &mut values,
    );
    let (req_scene, req_bearing) = required_paths();
    schema_paths()
        .into_keys()
        .map(|path| {
            let inline_material = path.starts_with("bearing.materials.<body>.");
            let d = if req_scene.contains(&path) || (inline_material && req_bearing.contains(&path))
            {
                Default_::Required
            } else if req_bearing.contains(&path) {
                Default_::RequiredWithoutPreset
            } else {
                values
                    .get(&path)
                    .cloned()
                    .map(Default_::Value)
                    .unwrap_or(Default_::Absent)
            };
            (path, d)
        })
        .collect()
}

/// The required fields, by normalised parent table (`""`: the scene; `bearing`: a bearing
/// table without preset).
fn required() -> BTreeMap<String, Vec<String>> {
    let mut out: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (p, d) in defaults() {
        if matches!(d, Default_::Required | Default_::RequiredWithoutPreset) {
            let (parent, key) = match p.rfind('.') {
                Some(i) => (p[..i].to_string(), p[i + 1..].to_string()),
                None => (String::new(), p.clone()),
            };
            out.entry(parent).or_default().push(key);
        }
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
// Check.

/// One problem of a scene.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Problem {
    /// Field path (`""`: the whole scene).
    pub path: String,
    /// 1-based line and column (TOML only).
    pub line_col: Option<(usize, usize)>,
    /// What is wrong.
    pub message: String,
}

impl std::fmt::Display for Problem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if let Some((l, c)) = self.line_col {
            write!(f, "{l}:{c}: ")?;
        }
        if self.path.is_empty() {
            write!(f, "{}", self.message)
        } else {
            write!(f, "`{}`: {}", self.path, self.message)
        }
    }
}

/// A parsed value with its place, from TOML or JSON.
#[derive(Debug, Clone)]
enum Node {
    Str(String),
    Int(i128),
    Float(f64),
    Bool,
    Other(&'static str),
    Array(Vec<(Option<usize>, Node)>),
    /// Key, key offset, value offset, value.
    Table(Vec<(String, Option<usize>, Option<usize>, Node)>),
}

impl Node {
    fn type_name(&self) -> &'static str {
        match self {
            Node::Str(_) => "a string",
            Node::Int(_) => "an integer",
            Node::Float(_) => "a float",
            Node::Bool => "a boolean",
            Node::Other(t) => t,
            Node::Array(_) => "an array",
            Node::Table(_) => "a table",
        }
    }
}

fn from_de(v: &toml::de::DeValue<'_>) -> Node {
    use toml::de::DeValue as D;
    match v {
        D::String(s) => Node::Str(s.to_string()),
        D::Integer(i) => i128::from_str_radix(&i.as_str().replace('_', ""), i.radix())
            .map(Node::Int)
            .unwrap_or(Node::Other("an integer out of range")),
        D::Float(x) => {
            let t = x.as_str().replace('_', "");
            let v = match t.trim_start_matches(['+', '-']) {
                "inf" => f64::INFINITY,
                "nan" => f64::NAN,
                _ => t.parse().unwrap_or(f64::NAN),
            };
            Node::Float(if t.starts_with('-') && v.is_infinite() {
                -v.abs()
            } else {
                v
            })
        }
        D::Boolean(_) => Node::Bool,
        D::Datetime(_) => Node::Other("a date-time"),
        D::Array(a) => Node::Array(
            a.iter()
                .map(|x| (Some(x.span().start), from_de(x.get_ref())))
                .collect(),
        ),
        D::Table(t) => Node::Table(
            t.iter()
                .map(|(k, x)| {
                    (
                        k.get_ref().to_string(),
                        Some(k.span().start),
                        Some(x.span().start),
                        from_de(x.get_ref()),
                    )
                })
                .collect(),
        ),
    }
}

fn from_json(v: &serde_json::Value) -> Node {
    use serde_json::Value as J;
    match v {
        J::Null => Node::Other("null"),
        J::Bool(_) => Node::Bool,
        J::Number(n) => {
            if let Some(i) = n.as_i64() {
                Node::Int(i as i128)
            } else if let Some(u) = n.as_u64() {
                Node::Int(u as i128)
            } else {
                Node::Float(n.as_f64().unwrap_or(f64::NAN))
            }
        }
        J::String(s) => Node::Str(s.clone()),
        J::Array(a) => Node::Array(a.iter().map(|x| (None, from_json(x))).collect()),
        J::Object(o) => Node::Table(
            o.iter()
                .map(|(k, x)| (k.clone(), None, None, from_json(x)))
                .collect(),
        ),
    }
}

/// The nearest of `known` to `name`, if near enough to be a likely misspelling.
fn nearest<'a>(name: &str, known: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    known
        .into_iter()
        .map(|k| {
            (
                strsim::levenshtein(&name.to_lowercase(), &k.to_lowercase()),
                k,
            )
        })
        .filter(|(d, k)| *d <= (k.len().max(name.len()) / 2).max(2))
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

/// Known child keys of a normalised table path.
fn children(norm: &str) -> Vec<String> {
    let prefix = if norm.is_empty() {
        String::new()
    } else {
        format!("{norm}.")
    };
    let mut out: Vec<String> = TABLE
        .iter()
        .filter_map(|f| f.path.strip_prefix(prefix.as_str()))
        .filter(|rest| !rest.starts_with('<'))
        .map(|rest| rest.split(['.', '[']).next().unwrap_or(rest).to_string())
        .collect();
    // Children below a `<body>` placeholder.
    if let Some(body) = norm.strip_prefix("bearing.materials.") {
        if BODIES.contains(&body) {
            out.extend(
                TABLE
                    .iter()
                    .filter_map(|f| f.path.strip_prefix("bearing.materials.<body>."))
                    .map(str::to_string),
            );
        }
    }
    out.sort();
    out.dedup();
    out
}

/// The 1-based line and column (in characters) of a byte offset of `text`; also what
/// `raceway sweep` uses to place the problems of a sweep file.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut off = offset.min(text.len());
    while !text.is_char_boundary(off) {
        off -= 1;
    }
    let before = &text[..off];
    let line = before.matches('\n').count() + 1;
    let col = before
        .rfind('\n')
        .map_or(before.chars().count(), |i| before[i + 1..].chars().count())
        + 1;
    (line, col)
}

struct Checker<'a> {
    text: Option<&'a str>,
    problems: Vec<Problem>,
    /// Concrete path -> offset of its key (or value), for locating library errors.
    places: Vec<(String, Option<usize>)>,
}

impl Checker<'_> {
    fn line_col(&self, offset: Option<usize>) -> Option<(usize, usize)> {
        Some(line_col(self.text?, offset?))
    }

    fn report(&mut self, path: &str, offset: Option<usize>, message: String) {
        let line_col = self.line_col(offset);
        self.problems.push(Problem {
            path: path.to_string(),
            line_col,
            message,
        });
    }

    fn table(
        &mut self,
        entries: &[(String, Option<usize>, Option<usize>, Node)],
        path: &str,
        norm: &str,
        at: Option<usize>,
    ) {
        let known = children(norm);
        let has_preset = entries.iter().any(|(k, ..)| k == "preset");
        for (key, kofs, vofs, node) in entries {
            let cpath = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            let cnorm = normalise_child(norm, key);
            self.places.push((cpath.clone(), kofs.or(*vofs)));
            if norm == "inputs.initial" && !Names::InputVariable.contains(key) {
                let list = Names::InputVariable.list();
                let hint = nearest(key, list.iter().map(String::as_str))
                    .map(|n| format!(" (did you mean `{n}`?)"))
                    .unwrap_or_default();
                self.report(
                    &cpath,
                    *kofs,
                    format!(
                        "unknown input variable `{key}`{hint}; inputs: {}",
                        list.join(", ")
                    ),
                );
                continue;
            }
            let is_known = field(&cnorm).is_some()
                || TABLE.iter().any(|f| {
                    f.path.starts_with(&format!("{cnorm}."))
                        || f.path.starts_with(&format!("{cnorm}[]"))
                });
            if !is_known {
                let hint = nearest(key, known.iter().map(String::as_str))
                    .map(|n| format!("; did you mean `{n}`?"))
                    .unwrap_or_else(|| format!("; known here: {}", known.join(", ")));
                self.report(&cpath, *kofs, format!("unknown key `{key}`{hint}"));
                continue;
            }
            self.value(node, &cpath, &cnorm, vofs.or(*kofs));
        }
        // Missing required fields.
        let req = required();
        let group = match norm.strip_prefix("bearing.materials.") {
            Some(b) if BODIES.contains(&b) => "bearing.materials.<body>",
            _ => norm,
        };
        if let Some(keys) = req.get(group) {
            if norm == "bearing" && has_preset {
                return;
            }
            for k in keys {
                if !entries.iter().any(|(e, ..)| e == k) {
                    let here = if path.is_empty() { "the scene" } else { path };
                    self.report(
                        &if path.is_empty() {
                            k.clone()
                        } else {
                            format!("{path}.{k}")
                        },
                        at,
                        format!("missing required field `{k}` in {here}"),
                    );
                }
            }
        }
    }

    fn value(&mut self, node: &Node, path: &str, norm: &str, at: Option<usize>) {
        let entry = field(norm);
        // Tables and arrays of tables.
        match node {
            Node::Table(entries) => {
                let table_ok = matches!(entry.map(|e| e.kind), None | Some(NameOrTable(_)))
                    && TABLE
                        .iter()
                        .any(|f| f.path.starts_with(&format!("{norm}.")))
                    || matches!(entry.map(|e| e.kind), Some(NameOrTable(_)));
                if table_ok {
                    self.table(entries, path, norm, at);
                } else {
                    self.mismatch(path, at, entry, node);
                }
                return;
            }
            Node::Array(items) => {
                if entry.is_none()
                    && TABLE
                        .iter()
                        .any(|f| f.path.starts_with(&format!("{norm}[].")))
                {
                    for (i, (ofs, item)) in items.iter().enumerate() {
                        let ipath = format!("{path}[{i}]");
                        self.places.push((ipath.clone(), ofs.or(at)));
                        match item {
                            Node::Table(entries) => {
                                self.table(entries, &ipath, &format!("{norm}[]"), ofs.or(at))
                            }
                            other => self.mismatch(&ipath, ofs.or(at), None, other),
                        }
                    }
                } else {
                    self.mismatch(path, at, entry, node);
                }
                return;
            }
            _ => {}
        }
        let Some(entry) = entry else {
            self.mismatch(path, at, None, node);
            return;
        };
        match (entry.kind, node) {
            (Float, Node::Int(i)) => self.bounds(entry, path, at, *i as f64),
            (Float, Node::Float(x)) => self.bounds(entry, path, at, *x),
            (Int, Node::Int(i)) => self.bounds(entry, path, at, *i as f64),
            (IntChoice(v), Node::Int(i)) => {
                if !v.iter().any(|x| *x as i128 == *i) {
                    self.report(
                        path,
                        at,
                        format!("{i} is not allowed: {}", range_text(entry)),
                    );
                }
            }
            (Text, Node::Str(_)) | (Bool, Node::Bool) => {}
            (Enum(v), Node::Str(s)) => {
                if !v.contains(&s.as_str()) {
                    let hint = nearest(s, v.iter().copied())
                        .map(|n| format!(" (did you mean \"{n}\"?)"))
                        .unwrap_or_default();
                    self.report(
                        path,
                        at,
                        format!("unknown spelling \"{s}\"{hint}; allowed: {}", v.join(", ")),
                    );
                }
            }
            (Name(n) | NameOrTable(n), Node::Str(s)) => {
                if !n.contains(s) {
                    let list = n.list();
                    let hint = nearest(s, list.iter().map(String::as_str))
                        .map(|x| format!(" (did you mean \"{x}\"?)"))
                        .unwrap_or_default();
                    let what = match n {
                        Names::BearingPreset => "bearing preset",
                        Names::Material => "material",
                        Names::Lubricant => "lubricant",
                        Names::InputVariable => "input variable",
                    };
                    self.report(
                        path,
                        at,
                        format!("unknown {what} \"{s}\"{hint}; known: {}", list.join(", ")),
                    );
                }
            }
            _ => self.mismatch(path, at, Some(entry), node),
        }
    }

    /// `expected <what the field takes (a table where there is none)>, found <the node>`.
    fn mismatch(&mut self, path: &str, at: Option<usize>, entry: Option<&Field>, node: &Node) {
        self.report(
            path,
            at,
            format!("expected {}, found {}", expect(entry), node.type_name()),
        );
    }

    fn bounds(&mut self, entry: &Field, path: &str, at: Option<usize>, v: f64) {
        if !entry.bounds.contains(v) {
            self.report(
                path,
                at,
                format!("{v} is outside the allowed range {}", entry.bounds.text()),
            );
        }
    }

    /// The place of a library error's field: the path itself or its nearest given parent.
    fn locate(&self, field: &str) -> (String, Option<usize>) {
        let mut p = field.to_string();
        loop {
            if let Some((_, ofs)) = self.places.iter().find(|(q, _)| *q == p) {
                return (field.to_string(), *ofs);
            }
            match p.rfind(['.', '[']) {
                Some(i) => p.truncate(i),
                None => return (field.to_string(), None),
            }
        }
    }
}

fn expect(entry: Option<&Field>) -> String {
    match entry.map(|e| e.kind) {
        None => "a table".into(),
        Some(Float) => "a number".into(),
        Some(Int) | Some(IntChoice(_)) => "an integer".into(),
        Some(NameOrTable(_)) => "a name or a table".into(),
        Some(Bool) => "a boolean".into(),
        Some(_) => "a string".into(),
    }
}

/// Check a scene text (TOML, or JSON when it starts with `{`): every problem at once.
/// An empty list means the scene builds a component.
pub fn check(text: &str) -> Vec<Problem> {
    let json = text.trim_start().starts_with('{');
    let mut c = Checker {
        text: if json { None } else { Some(text) },
        problems: Vec::new(),
        places: Vec::new(),
    };
    if let Err(e) = crate::nesting::check(text) {
        c.problems.push(Problem {
            path: String::new(),
            line_col: Some((e.line, e.column)),
            message: e.to_string(),
        });
        return c.problems;
    }
    let root = if json {
        match serde_json::from_str::<serde_json::Value>(text) {
            Ok(v) => from_json(&v),
            Err(e) => {
                c.problems.push(Problem {
                    path: String::new(),
                    line_col: Some((e.line(), e.column())),
                    message: format!("JSON syntax: {e}"),
                });
                return c.problems;
            }
        }
    } else {
        let (doc, errors) = toml::de::DeTable::parse_recoverable(text);
        if !errors.is_empty() {
            for e in errors {
                let at = e.span().map(|s| s.start);
                let msg = e.message().trim().to_string();
                c.report("", at, format!("TOML syntax: {msg}"));
            }
            return c.problems;
        }
        from_de(&toml::de::DeValue::Table(doc.into_inner()))
    };
    match &root {
        Node::Table(entries) => c.table(entries, "", "", Some(0)),
        other => c.report(
            "",
            None,
            format!("expected a table, found {}", other.type_name()),
        ),
    }
    c.problems.sort_by_key(|p| p.line_col);
    if !c.problems.is_empty() {
        return c.problems;
    }
    // Cross-field problems: the library's own checks, in the order a run meets them (the
    // component built, the run's inputs at its end and start set, the first outputs).
    let result = Scene::from_text(text).and_then(|s| {
        let b = s.validate()?;
        s.effects.validate_for(&b)?;
        crate::runner::prepare(&s).map(|_| ())
    });
    if let Err(e) = result {
        let field = match &e {
            crate::Error::Invalid { field, .. } => Some(field.clone()),
            crate::Error::Unknown { what, .. } if what.contains("effects.lubrication") => {
                Some("effects.lubrication.lubricant".to_string())
            }
            _ => None,
        };
        let (path, ofs) = field
            .as_deref()
            .map(|f| c.locate(f))
            .unwrap_or((String::new(), None));
        // A serde refusal the structural pass cannot see (e.g. a traction field of another
        // law): TOML's own message carries its line and column.
        let from_message = match (&e, ofs) {
            (crate::Error::Parse { message, .. }, None) => line_col_in(message),
            _ => None,
        };
        c.report(&path, ofs, e.to_string());
        if let (Some(lc), Some(last)) = (from_message, c.problems.last_mut()) {
            last.line_col = Some(lc);
            last.message = e
                .to_string()
                .lines()
                .last()
                .unwrap_or("")
                .trim()
                .to_string();
        }
    }
    c.problems
}

/// The one validation path of a scene file, shared by `raceway run` and `raceway scene
/// --check`: the text is checked exactly as [`check`] does (every problem at once); then
/// the command-line `overrides` (`(field path, value)`, e.g. `("run.duration_s", 0.1)`)
/// are written into it and the result is checked again the same way, so an override can
/// neither smuggle in a value the file could not hold nor hide one it holds. Problems of
/// the second pass carry no line (the file does not hold the overridden scene) and say
/// which overrides were applied. `Ok` is a scene that builds a component.
pub fn load(text: &str, overrides: &[(&str, f64)]) -> std::result::Result<Scene, Vec<Problem>> {
    let whole = |message: String| {
        vec![Problem {
            path: String::new(),
            line_col: None,
            message,
        }]
    };
    let problems = check(text);
    if !problems.is_empty() {
        return Err(problems);
    }
    if overrides.is_empty() {
        return Scene::from_text(text).map_err(|e| whole(e.to_string()));
    }
    // The scene as a TOML table (a JSON scene is converted), the overrides written in.
    let doc: std::result::Result<toml::Table, String> = if text.trim_start().starts_with('{') {
        serde_json::from_str::<serde_json::Value>(text)
            .map_err(|e| e.to_string())
            .and_then(|v| toml::Table::try_from(v).map_err(|e| e.to_string()))
    } else {
        toml::from_str(text).map_err(|e| e.to_string())
    };
    let mut doc = doc.map_err(|e| whole(format!("cannot apply the overrides: {e}")))?;
    for (path, value) in overrides {
        let mut keys: Vec<&str> = path.split('.').collect();
        let last = keys.pop().unwrap_or_default();
        let mut table = &mut doc;
        for k in keys {
            let entry = table
                .entry(k.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            table = match entry {
                toml::Value::Table(t) => t,
                _ => return Err(whole(format!("cannot apply the override of `{path}`"))),
            };
        }
        table.insert(last.to_string(), toml::Value::Float(*value));
    }
    let applied = overrides
        .iter()
        .map(|(p, v)| format!("{p} = {v}"))
        .collect::<Vec<_>>()
        .join(", ");
    let text2 = toml::to_string(&doc)
        .map_err(|e| whole(format!("cannot apply the overrides ({applied}): {e}")))?;
    let problems = check(&text2);
    if !problems.is_empty() {
        return Err(problems
            .into_iter()
            .map(|p| Problem {
                line_col: None,
                message: format!("{} (with the command-line override {applied})", p.message),
                ..p
            })
            .collect());
    }
    Scene::from_text(&text2).map_err(|e| whole(e.to_string()))
}

/// `line L, column C` (TOML) or `line L column C` (JSON) in a parser's message.
fn line_col_in(message: &str) -> Option<(usize, usize)> {
    let rest = &message[message.find("line ")? + 5..];
    let (l, rest) = rest
        .split_once(", column ")
        .or_else(|| rest.split_once(" column "))?;
    let c: String = rest.chars().take_while(char::is_ascii_digit).collect();
    Some((l.trim().parse().ok()?, c.parse().ok()?))
}

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
