//! The one table of the labels a person reads in a run's summary.json (and so in
//! `raceway.run`'s summary dict and every summary column of a sweep) and in
//! `raceway quasi-static --json`: for every key the code builds, the label it leaves as,
//! `name [unit]` ([`crate::units::label`]), and what it means. The sections build their
//! JSON with their own keys; [`relabel`] renames them here, in one place, so a unit is
//! written once. docs/columns.md is generated from this table and the variable table
//! (`RACEWAY_BLESS=1 cargo test --test columns`), and that test reads every key of a run,
//! a sweep and a quasi-static solve against it.

use serde_json::{Map, Value};

mod bearings;
mod quasi_static;

/// One key: where the code puts it, the label it leaves as, its unit and meaning.
#[derive(Debug, Clone, Copy)]
pub struct Key {
    /// The key's path in the JSON the code builds: object keys joined by `.`, `[]` for the
    /// elements of an array of tables (`frequencies[].expected_hz`).
    pub from: &'static str,
    /// The name it leaves as (without the unit). Names joined by `|` split an array value
    /// into that many keys (`X|Y|e`).
    pub name: &'static str,
    /// Unit symbol (`1`: dimensionless; empty: text, flags, structure); one per name when
    /// the value is split (joined by `|`), or one for all.
    pub unit: &'static str,
    /// What it is.
    pub what: &'static str,
}

const fn k(from: &'static str, name: &'static str, unit: &'static str, what: &'static str) -> Key {
    Key {
        from,
        name,
        unit,
        what,
    }
}

/// The ISO ratings and life (`crate::ratings::Assessment`), the same under `rating` in a
/// run's summary and in `raceway quasi-static --json`.
const RATING: &[Key] = &[
    k("rating", "rating", "", "ISO 281/76 ratings, life and static safety (a run: at the mean load of its second half; null when not available)"),
    k("rating.ratings", "ratings", "", "the bearing's load ratings"),
    k("rating.ratings.gamma", "gamma", "1", "Dw cos(alpha) / Dpw"),
    k("rating.ratings.fc", "fc", "1", "ISO 281 Table 2 factor fc after the conformity reduction (tabulated for C in N with Dw in mm)"),
    k("rating.ratings.fc_reduction", "fc_reduction", "1", "conformity reduction applied to fc (1: none)"),
    k("rating.ratings.f0", "f0", "1", "ISO 76 Table 2 factor f0"),
    k("rating.ratings.c", "C", "N", "basic dynamic radial load rating (ISO 281)"),
    k("rating.ratings.c0", "C0", "N", "basic static radial load rating (ISO 76)"),
    k("rating.ratings.cu", "Cu", "N", "fatigue load limit (ISO 281 Annex B approximation)"),
    k("rating.radial_load", "radial_load", "N", "radial load Fr on the bearing"),
    k("rating.axial_load", "axial_load", "N", "axial load Fa on the bearing"),
    k("rating.p", "P", "N", "dynamic equivalent load (ISO 281)"),
    k("rating.xye", "X|Y|e", "1", "ISO 281 radial factor X, axial factor Y and limit e used for P"),
    k("rating.p0", "P0", "N", "static equivalent load (ISO 76)"),
    k("rating.l10_mrev", "L10", "Mrev", "basic rating life (C/P)^3 (null at zero load)"),
    k("rating.l10_hours", "L10", "h", "basic rating life in hours at the speed (null at standstill or zero load)"),
    k("rating.l10r_mrev", "L10r", "Mrev", "reference rating life from the per-element loads"),
    k("rating.l10r_hours", "L10r", "h", "reference rating life in hours at the speed"),
    k("rating.raceway_lives_mrev", "life_inner|life_outer", "Mrev", "reference rating lives of the inner and the outer raceway"),
    k("rating.a_iso", "a_ISO", "1", "life modification factor a_ISO from kappa and eC (null when either is not given or kappa < 0.1)"),
    k("rating.l10mr_hours", "L10mr", "h", "modified reference rating life a_ISO L10r in hours"),
    k("rating.s0", "S0", "1", "static safety factor C0/P0 (null at zero load)"),
    k("rating.peak_pressure", "peak_pressure", "Pa", "peak contact pressure over every element and race"),
    k("rating.pressure_limit", "pressure_limit", "Pa", "static pressure limit used (ISO 76)"),
    k("rating.pressure_limit_ratio", "pressure_limit_ratio", "1", "peak_pressure / pressure_limit"),
    k("rating.loaded_balls", "loaded_balls", "1", "elements with a positive inner contact load"),
    k("rating.warnings", "warnings", "", "the rating's warnings (structured)"),
    k("rating.warnings[].kind", "kind", "", "pressure_above_static_limit, ellipse_truncated, few_loaded_balls or kappa_below_one"),
    k("rating.warnings[].pressure", "pressure", "Pa", "peak pressure (pressure_above_static_limit)"),
    k("rating.warnings[].limit", "limit", "Pa", "the static pressure limit (pressure_above_static_limit)"),
    k("rating.warnings[].ball", "ball", "1", "ball index"),
    k("rating.warnings[].race", "race", "", "inner or outer"),
    k("rating.warnings[].edge_angle", "edge_angle", "rad", "contact angle plus the ellipse's angular half-width (ellipse_truncated)"),
    k("rating.warnings[].shoulder_angle", "shoulder_angle", "rad", "groove shoulder angle (ellipse_truncated)"),
    k("rating.warnings[].count", "count", "1", "balls with a positive inner contact load (few_loaded_balls)"),
    k("rating.warnings[].kappa", "kappa", "1", "viscosity ratio (kappa_below_one)"),
    k("warnings", "warnings", "", "the rating's warnings as text"),
];

/// The lines of a spectrum (`frequencies[]`, `envelope_frequencies[]`).
macro_rules! lines {
    ($p:literal, $what:literal) => {
        [
            k($p, $p, "", $what),
            k(
                concat!($p, "[].label"),
                "label",
                "",
                "the line (fs, FTF, BSF, kxBPFO, kxBPFI, kx2BSF)",
            ),
            k(
                concat!($p, "[].expected_hz"),
                "expected",
                "Hz",
                "the line's frequency from the kinematics",
            ),
            k(
                concat!($p, "[].found_hz"),
                "found",
                "Hz",
                "the peak found on the line (null: not found)",
            ),
            k(
                concat!($p, "[].tolerance_hz"),
                "tolerance",
                "Hz",
                "how far from the line a peak counts as on it",
            ),
            k(
                concat!($p, "[].nearest_peak_hz"),
                "nearest_peak",
                "Hz",
                "the nearest peak of the spectrum",
            ),
            k(
                concat!($p, "[].deviation_hz"),
                "deviation",
                "Hz",
                "nearest peak minus the line",
            ),
            k(
                concat!($p, "[].over_floor"),
                "over_floor",
                "1",
                "the peak's amplitude over the spectrum's median floor",
            ),
            k(
                concat!($p, "[].verdict"),
                "verdict",
                "",
                "found, below floor, off line, not resolved, above nyquist",
            ),
            k(
                concat!($p, "[].needs_duration_s"),
                "needs_duration",
                "s",
                "the run duration that would resolve the line (not resolved only)",
            ),
        ]
    };
}

const FREQUENCIES: [Key; 10] = lines!(
    "frequencies",
    "characteristic frequencies in the spectrum of the second half of the run"
);
const ENVELOPE: [Key; 10] = lines!(
    "envelope_frequencies",
    "characteristic frequencies in the envelope spectrum (defect scenes)"
);

/// The run summary's own keys (`crate::summary` sections).
const RUN: &[Key] = &[
    k("scene", "scene", "", "scene name (file stem)"),
    k("level", "level", "", "model level"),
    k("duration_s", "duration", "s", "simulated time"),
    k(
        "cpu_s",
        "cpu",
        "s",
        "thread CPU time of the run (a measurement of the machine)",
    ),
    k(
        "load_average",
        "load_average",
        "",
        "the machine's load average during the run (a measurement of the machine)",
    ),
    k("bearing", "bearing", "", "the bearing"),
    k("bearing.name", "name", "", "designation"),
    k("bearing.bore_mm", "bore", "mm", "bore diameter d"),
    k(
        "bearing.outside_diameter_mm",
        "outside_diameter",
        "mm",
        "outside diameter D",
    ),
    k("bearing.width_mm", "width", "mm", "width B"),
    k("bearing.z", "Z", "1", "number of rolling elements"),
    k(
        "bearing.ball_diameter_mm",
        "element_diameter",
        "mm",
        "rolling-element diameter Dw",
    ),
    k(
        "bearing.pitch_diameter_mm",
        "pitch_diameter",
        "mm",
        "pitch diameter dm",
    ),
    k(
        "bearing.diametral_clearance_um",
        "diametral_clearance",
        "µm",
        "diametral clearance Pd",
    ),
    k(
        "peak_force_n",
        "peak_force",
        "N",
        "largest |force.x|, |force.y|, |force.z| over the run (an array x, y, z)",
    ),
    k(
        "peak_contact_load_n",
        "peak_contact_load",
        "N",
        "largest contact.max_load over the run",
    ),
    k(
        "peak_pressure_pa",
        "peak_pressure",
        "Pa",
        "largest contact.max_pressure over the run",
    ),
    k(
        "start_held",
        "start_held",
        "",
        "model.start_hold: which of x, y, z, rx, ry the static start held",
    ),
    k(
        "start_reaction",
        "start_reaction.x|start_reaction.y|start_reaction.z|start_reaction.rx|start_reaction.ry",
        "N|N|N|N.m|N.m",
        "the support's reaction on each held coordinate at the static start",
    ),
    k(
        "friction",
        "friction",
        "",
        "friction torque and power loss (thermal effect), second half of the run",
    ),
    k(
        "friction.mean_torque_nm",
        "mean_torque",
        "N.m",
        "mean friction torque on the shaft",
    ),
    k(
        "friction.final_torque_nm",
        "final_torque",
        "N.m",
        "friction torque at the end",
    ),
    k(
        "friction.mean_power_loss_w",
        "mean_power_loss",
        "W",
        "mean power loss",
    ),
    k(
        "friction.final_power_loss_w",
        "final_power_loss",
        "W",
        "power loss at the end",
    ),
    k(
        "friction.calculator",
        "calculator",
        "",
        "the calculator's Palmgren and SKF friction at the run's second-half means, beside the run's own",
    ),
    k("friction.calculator.means", "means", "", "which means the calculator was run at"),
    k("friction.calculator.note", "note", "", "why the calculator was not run"),
    k("friction.calculator.mean_speed_rpm", "mean_speed", "rpm", "mean |shaft speed|"),
    k("friction.calculator.radial_load_n", "radial_load", "N", "mean radial load Fr"),
    k("friction.calculator.axial_load_n", "axial_load", "N", "mean axial load Fa"),
    k("friction.calculator.p0_n", "P0", "N", "static equivalent load at the means"),
    k("friction.calculator.c0_n", "C0", "N", "basic static load rating"),
    k(
        "friction.calculator.kinematic_viscosity_mm2_s",
        "kinematic_viscosity",
        "mm2/s",
        "the viscosity the level uses",
    ),
    k("friction.calculator.viscosity_from", "viscosity_from", "", "where the viscosity comes from"),
    k("friction.calculator.f0", "f0", "1", "Palmgren's lubrication factor f0"),
    k("friction.calculator.f0_from", "f0_from", "", "where f0 comes from"),
    k("friction.calculator.palmgren", "palmgren", "", "Palmgren (ISO/TR 14179-2)"),
    k("friction.calculator.palmgren.moment_nm", "moment", "N.m", "friction moment M = M0 + M1"),
    k("friction.calculator.palmgren.viscous_moment_nm", "viscous_moment", "N.m", "load-independent moment M0"),
    k("friction.calculator.palmgren.load_moment_nm", "load_moment", "N.m", "load-dependent moment M1"),
    k("friction.calculator.palmgren.power_w", "power", "W", "power loss M omega"),
    k(
        "friction.calculator.palmgren.run_over_calculator_power",
        "run_over_calculator_power",
        "1",
        "the run's mean power loss over this one",
    ),
    k("friction.calculator.skf", "skf", "", "SKF four-term model (constants unconfirmed)"),
    k("friction.calculator.skf.note", "note", "", "why it was not evaluated"),
    k("friction.calculator.skf.series", "series", "", "the bearing series of its constants"),
    k("friction.calculator.skf.lubrication", "lubrication", "", "lubrication method"),
    k("friction.calculator.skf.moment_nm", "moment", "N.m", "total friction moment"),
    k("friction.calculator.skf.rolling_moment_nm", "rolling_moment", "N.m", "rolling moment"),
    k("friction.calculator.skf.sliding_moment_nm", "sliding_moment", "N.m", "sliding moment"),
    k("friction.calculator.skf.seal_moment_nm", "seal_moment", "N.m", "seal moment (null: open bearing)"),
    k("friction.calculator.skf.drag_moment_nm", "drag_moment", "N.m", "drag moment (null: not counted)"),
    k("friction.calculator.skf.power_w", "power", "W", "power loss M omega"),
    k(
        "friction.calculator.skf.run_over_calculator_power",
        "run_over_calculator_power",
        "1",
        "the run's mean power loss over this one",
    ),
    k("friction.calculator.skf.unconfirmed", "unconfirmed", "", "what of the model is not confirmed from SKF's own text"),
    k("friction.calculator.skf.warnings", "warnings", "", "the model's warnings for this point"),
    k("set", "set", "", "a bearing set's rows, each rated at its own mean load (second half)"),
    k("set.rows", "rows", "", "one entry per row"),
    k("set.rows[].label", "label", "", "the row's output prefix (row0, row1, ...)"),
    k("set.rows[].bearing", "bearing", "", "the row's bearing"),
    k("set.rows[].position_mm", "position", "mm", "axial position from the set's reference point"),
    k("set.rows[].orientation", "orientation", "1", "+1: contact angle opens toward +z; -1: toward -z"),
    k("set.rows[].mean_force_n", "mean_force.x|mean_force.y|mean_force.z", "N", "mean force the row carries"),
    k("set.rows[].mean_moment_nm", "mean_moment.x|mean_moment.y", "N.m", "mean moment the row carries"),
    k("set.rows[].peak_force_n", "peak_force.x|peak_force.y|peak_force.z", "N", "largest |force| per axis"),
    k("set.rows[].mean_radial_load_n", "mean_radial_load", "N", "mean radial load Fr"),
    k("set.rows[].mean_thrust_n", "mean_thrust", "N", "mean axial load in the row's own direction"),
    k("set.rows[].mean_contact_angle_deg", "mean_contact_angle", "deg", "mean inner contact angle (0 while lifted off)"),
    k("set.rows[].lift_off_fraction", "lift_off_fraction", "1", "share of the second half with the row lifted off"),
    k("set.rows[].l10_mrev", "L10", "Mrev", "ISO 281 basic rating life at the row's mean load"),
    k("set.rows[].l10_hours", "L10", "h", "the same in hours at the mean speed"),
    k("set.rows[].s0", "S0", "1", "ISO 76 static safety of the row"),
    k("set.rows[].weibull_slope", "weibull_slope", "1", "the row's Weibull slope for the system life"),
    k("set.system_l10_mrev", "system_L10", "Mrev", "the rows' lives together (Lundberg-Palmgren)"),
    k("set.system_l10_hours", "system_L10", "h", "the same in hours"),
    k("set.smallest_s0", "smallest_S0", "1", "the smallest row's static safety"),
    k("film", "film", "", "EHL film, second half of the run"),
    k(
        "film.smallest_min_thickness_um",
        "smallest_min_thickness",
        "µm",
        "smallest minimum film thickness over the contacts",
    ),
    k(
        "film.mean_min_thickness_um",
        "mean_min_thickness",
        "µm",
        "mean minimum film thickness",
    ),
    k(
        "film.final_min_thickness_um",
        "final_min_thickness",
        "µm",
        "minimum film thickness at the end",
    ),
    k(
        "film.roughness_um",
        "roughness",
        "µm",
        "composite rms roughness sigma of element and race",
    ),
    k(
        "film.smallest_film_parameter",
        "smallest_film_parameter",
        "1",
        "Lambda = h_min / sigma at the smallest film",
    ),
    k(
        "film.mean_film_parameter",
        "mean_film_parameter",
        "1",
        "Lambda at the mean film",
    ),
    k(
        "film.kinematic_viscosity_mm2_s",
        "kinematic_viscosity",
        "mm2/s",
        "kinematic viscosity nu at the inlet viscosity",
    ),
    k(
        "film.nu1_mm2_s",
        "nu1",
        "mm2/s",
        "ISO 281 rated viscosity nu1 at the final speed",
    ),
    k(
        "film.iso_kappa",
        "kappa",
        "1",
        "ISO 281 viscosity ratio nu / nu1",
    ),
    k(
        "thermal",
        "thermal",
        "",
        "thermal effect at the end of the run (ring level)",
    ),
    k(
        "thermal.inner_race_c",
        "inner_race",
        "°C",
        "inner race temperature",
    ),
    k(
        "thermal.outer_race_c",
        "outer_race",
        "°C",
        "outer race temperature",
    ),
    k(
        "thermal.balls_c",
        "elements",
        "°C",
        "rolling-element temperature",
    ),
    k("thermal.oil_c", "oil", "°C", "oil temperature"),
    k("thermal.ambient_c", "ambient", "°C", "ambient temperature"),
    k(
        "thermal.clearance_change_um",
        "clearance_change",
        "µm",
        "thermal change of the diametral clearance",
    ),
    k(
        "thermal.operating_clearance_um",
        "operating_clearance",
        "µm",
        "operating diametral clearance",
    ),
    k("thermal.rows", "rows", "", "a bearing set: each row's temperatures at the end"),
    k("thermal.rows[].inner_race_c", "inner_race", "°C", "the row's inner race temperature"),
    k("thermal.rows[].outer_race_c", "outer_race", "°C", "the row's outer race temperature"),
    k("thermal.rows[].balls_c", "elements", "°C", "the row's rolling-element temperature"),
    k("thermal.rows[].oil_c", "oil", "°C", "the row's oil temperature"),
    k(
        "lamina_life",
        "lamina_life",
        "",
        "ISO/TS 16281 lamina life over the analysed window (a roller bearing on the ring level), inner ring rotating",
    ),
    k("lamina_life.states", "states", "1", "recorded states in the window"),
    k("lamina_life.notes", "notes", "", "what in these figures is not sourced"),
    k(
        "final_cage_slip",
        "final_cage_slip",
        "1",
        "cage slip at the end (null on levels that run the cage at its kinematic speed)",
    ),
    k(
        "cage_whirl_sigma",
        "cage_whirl_sigma",
        "1",
        "whirl index of the cage speed, second half (full level)",
    ),
    k(
        "cage_orbit_max",
        "cage_orbit_max",
        "1",
        "largest cage orbit in guide clearances (full level)",
    ),
    k(
        "peak_pocket_force_n",
        "peak_pocket_force",
        "N",
        "largest pocket force (full level)",
    ),
    k(
        "peak_guide_force_n",
        "peak_guide_force",
        "N",
        "largest guide-land force (full level)",
    ),
];

const LAMINA: [Key; 13] = quasi_static::lamina_life!(
    "lamina_life.with_edge_factor",
    "with_edge_factor",
    "the life with the edge-stress factor"
);
const LAMINA_PLAIN: [Key; 13] = quasi_static::lamina_life!(
    "lamina_life.without_edge_factor",
    "without_edge_factor",
    "the same without the edge-stress factor (what the factor costs)"
);

/// Which document a key belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Doc {
    /// summary.json of `raceway run` (and `raceway.run`'s dict, a sweep's summary columns).
    Run,
    /// `raceway quasi-static --json` (and Python's `quasi_static`): a ball bearing, a
    /// roller bearing (`--bearing NU206`) and a set (`--scene`).
    QuasiStatic,
    /// `raceway bearings --json` (each entry) and `raceway bearings NAME --json` (and
    /// Python's `bearings()`, `bearing(NAME)`).
    Bearings,
    /// `raceway shaft --json` (and Python's `shaft`).
    Shaft,
}

/// Every document, in the page's order.
pub const DOCS: [Doc; 4] = [Doc::Run, Doc::QuasiStatic, Doc::Bearings, Doc::Shaft];

/// Every key of a document, in order.
pub fn keys(doc: Doc) -> Vec<Key> {
    let mut v = match doc {
        Doc::Run => RUN.to_vec(),
        Doc::QuasiStatic => quasi_static::keys(),
        Doc::Bearings => return bearings::KEYS.to_vec(),
        Doc::Shaft => return quasi_static::shaft_keys(),
    };
    v.extend_from_slice(RATING);
    if doc == Doc::Run {
        v.extend_from_slice(&LAMINA);
        v.extend_from_slice(&LAMINA_PLAIN);
        v.extend_from_slice(&FREQUENCIES);
        v.extend_from_slice(&ENVELOPE);
    }
    v
}

/// The labels a key leaves as, with their units: one, or one per part of a split value.
pub fn labels(key: &Key) -> Vec<(String, &'static str)> {
    let names: Vec<&str> = key.name.split('|').collect();
    let units: Vec<&str> = key.unit.split('|').collect();
    names
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let u = if units.len() == names.len() {
                units[i]
            } else {
                units[0]
            };
            (crate::units::label(n, u), u)
        })
        .collect()
}

/// Rename the keys of a document from the table (a key not in the table stays as the code
/// built it; the test `tests/columns.rs` finds it).
pub fn relabel(doc: Doc, json: Map<String, Value>) -> Map<String, Value> {
    walk(label_map(doc), "", json)
}

/// A document's keys by path (the table's first key of a path wins, as a search in order
/// would find it), with the labels each leaves as: made once per document kind (a sweep
/// relabels every point's summary; searching the table and formatting the labels per key
/// was a seventh of a quasi-static point's instructions).
type LabelMap = std::collections::HashMap<&'static str, Vec<String>>;

fn label_map(doc: Doc) -> &'static LabelMap {
    static MAPS: [std::sync::OnceLock<LabelMap>; 4] = [const { std::sync::OnceLock::new() }; 4];
    let i = DOCS.iter().position(|d| *d == doc).unwrap_or(0);
    MAPS[i].get_or_init(|| {
        let mut m = LabelMap::new();
        for k in keys(doc) {
            m.entry(k.from)
                .or_insert_with(|| labels(&k).into_iter().map(|(l, _)| l).collect());
        }
        m
    })
}

/// [`relabel`] of any JSON value: an object's keys, or each object of an array (a list of
/// documents, `raceway bearings --json`); anything else as it is.
pub fn relabel_value(doc: Doc, json: Value) -> Value {
    match json {
        Value::Object(m) => Value::Object(relabel(doc, m)),
        Value::Array(a) => Value::Array(a.into_iter().map(|x| relabel_value(doc, x)).collect()),
        other => other,
    }
}

/// A serialisable document as JSON with its keys labelled from the table.
pub fn to_labelled_json<T: serde::Serialize + ?Sized>(doc: Doc, v: &T) -> Value {
    relabel_value(doc, serde_json::to_value(v).unwrap_or_default())
}

fn walk(table: &LabelMap, path: &str, m: Map<String, Value>) -> Map<String, Value> {
    let mut out = Map::new();
    for (key, v) in m {
        let p = if path.is_empty() {
            key.clone()
        } else {
            format!("{path}.{key}")
        };
        let v = match v {
            Value::Object(o) => Value::Object(walk(table, &p, o)),
            Value::Array(a) => Value::Array(
                a.into_iter()
                    .map(|x| match x {
                        Value::Object(o) => Value::Object(walk(table, &format!("{p}[]"), o)),
                        other => other,
                    })
                    .collect(),
            ),
            other => other,
        };
        match table.get(p.as_str()) {
            None => {
                out.insert(key, v);
            }
            Some(labels) => match (labels.len(), v) {
                (1, v) => {
                    out.insert(labels[0].clone(), v);
                }
                (n, Value::Array(a)) if a.len() == n => {
                    for (l, x) in labels.iter().zip(a) {
                        out.insert(l.clone(), x);
                    }
                }
                (_, v) => {
                    // Not the array the table splits (e.g. null): each part gets it.
                    for l in labels {
                        out.insert(l.clone(), v.clone());
                    }
                }
            },
        }
    }
    out
}

/// docs/columns.md: every column of series.csv (the variable table), every key of a run's
/// summary.json and of `raceway quasi-static --json`, and how a sweep names its columns.
pub fn columns_page() -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    s.push_str(
        "# Columns and keys\n\n\
         <!-- generated by `RACEWAY_BLESS=1 cargo test --test columns` from the variable table \
         (src/component/variables.rs) and src/summary/columns.rs; do not edit -->\n\n\
         One label style for every table a person reads: **`name [unit]`** (series.csv \
         headers, the Python DataFrame's columns, summary.json keys, a sweep's columns, \
         `raceway quasi-static --json` keys), with SI unit symbols (`1` for a dimensionless \
         number, `Mrev` for millions of revolutions, `h` for hours, `mm`/`µm`/`°C` where the \
         value is given so); text, flags and structure keep the bare name. A program that \
         addresses a variable (FMI, the C header, `Component.get`/`set`) uses the bare name, \
         with the unit in the variable table (docs/fmi.md). Why: the unit stays readable \
         beside every number a person reads, and a variable's name stays the same on every \
         face; `crate::units::split_label` turns a label back into name and unit.\n\n\
         `tests/columns.rs` reads every header and key of runs (the default scene, a \
         cylindrical roller bearing on the ring level, a set, a set with the thermal effect), \
         a sweep, quasi-static JSON solves (a ball bearing with the design check's options, a \
         cylindrical and a tapered roller bearing, a set), `raceway shaft --json` (two \
         shafts) and `raceway bearings --json` (a ball and a roller bearing) and checks each against this page and the pattern.\n\n",
    );
    s.push_str(
        "## series.csv and `raceway.run`'s DataFrame\n\n\
         `t [s]`, then one column per output of the run's level and effects (its \
         `[record]` selection), `name [unit]` from the variable table; with `--kc` \
         also `K.i.j` and `C.i.j`.\n\n| column | meaning |\n|---|---|\n| `t [s]` | time |\n",
    );
    for v in crate::component::variables::all() {
        let _ = writeln!(
            s,
            "| `{}` | {} |",
            crate::units::label(v.name, v.unit),
            v.description.replace('|', "\\|")
        );
    }
    let table = |s: &mut String, doc: Doc| {
        s.push_str("\n| key | meaning |\n|---|---|\n");
        for key in keys(doc) {
            let parent = full_parent(doc, key.from).unwrap_or_default();
            let ls: Vec<String> = labels(&key)
                .into_iter()
                .map(|(l, _)| format!("`{parent}{l}`"))
                .collect();
            let _ = writeln!(
                s,
                "| {} | {} |",
                ls.join(", "),
                key.what.replace('|', "\\|")
            );
        }
    };
    s.push_str(
        "\n## summary.json of `raceway run` (and `raceway.run`'s summary dict)\n\n\
         Nested keys are shown joined by `.`; `[]` marks the tables of an array. A section \
         appears when the run computes it (friction and thermal with the thermal effect, \
         film with EHL, cage whirl on the full level, envelope lines for defect scenes).\n",
    );
    table(&mut s, Doc::Run);
    s.push_str(
        "\n## Sweep columns (sweep.csv, `raceway.Sweep`'s DataFrame)\n\n\
         `index`, one column per axis named by its scene key (`inputs.speed_rpm`, \
         `bearing.clearance_um`: scene fields carry their unit in their name), `error`, \
         then the summary above flattened: nested keys joined by `.`, the unit moved to \
         the end (`rating.ratings.C [N]`), an array of three numbers by `x`, `y`, `z` \
         (`peak_force.x [N]`), an array of lines by each line's label \
         (`frequencies.BPFO.expected [Hz]`), a list of texts joined by `; `.\n",
    );
    s.push_str(
        "\n## `raceway quasi-static --json` (and Python's `quasi_static`)\n\n\
         One table for the three documents: a ball bearing (`--bearing 6205`: the top level, \
         `solution`, `rating` as in the run summary, the design check `calculator`), a roller \
         bearing (`--bearing NU206`, `30206`: `element` is `roller`) and a set (`--scene \
         SET.toml`: `element` is `set`); the meaning says which a key belongs to. `solution` \
         is in SI (rad/s, N, N.m, m, rad, Pa); five numbers of a shaft's coordinates or loads \
         are split into `.x`, `.y`, `.z`, `.rx`, `.ry` (m or rad; N or N.m); the 5 x 5 \
         stiffness, whose entries mix N/m, N/rad, N.m/m and N.m/rad, has the unit `SI`; \
         `G_rr` and `G_sl` are in the units of SKF's own formula (`SKF`). Python's \
         `quasi_static(...).balls` and `.rollers` tables have the same `name [unit]` \
         columns.\n",
    );
    table(&mut s, Doc::QuasiStatic);
    s.push_str(
        "\n## `raceway bearings --json` (and Python's `bearings()`, `bearing(NAME)`)\n\n\
         `raceway bearings --json` lists the ball-bearing presets, each entry with the keys \
         down to `source`; `raceway bearings NAME --json` gives one ball bearing's entry with \
         its envelope and `ratings`, or for a roller designation its file's data (`spec`) and \
         `ratings`. Values are in the units the bearing files use (mm, µm, degrees).\n",
    );
    table(&mut s, Doc::Bearings);
    s.push_str(
        "\n## `raceway shaft --json` (and Python's `shaft`)\n\n\
         The shaft's equilibrium at its origin in SI, each location with its bearing or set \
         under `set` (the keys of a set's `solution` above), every ball of a ball row.\n",
    );
    table(&mut s, Doc::Shaft);
    s
}

/// The labelled path of the parent of `from` (`rating.ratings.c` → `rating.ratings.`).
fn full_parent(doc: Doc, from: &str) -> Option<String> {
    let (p, _) = from.rsplit_once('.')?;
    let arr = p.ends_with("[]");
    let p = p.trim_end_matches("[]");
    let k = keys(doc).into_iter().find(|k| k.from == p)?;
    let up = full_parent(doc, p).unwrap_or_default();
    Some(format!("{up}{}{}", k.name, if arr { "[]." } else { "." }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every key of the table is unique, a number's unit is given, and a split value has a
    /// unit per part or one for all.
    #[test]
    fn the_table_is_consistent() {
        for doc in DOCS {
            let ks = keys(doc);
            for (i, a) in ks.iter().enumerate() {
                assert!(
                    ks[i + 1..].iter().all(|b| b.from != a.from),
                    "{} twice",
                    a.from
                );
                let parts = a.name.split('|').count();
                let units = a.unit.split('|').count();
                assert!(units == 1 || units == parts, "{}", a.from);
            }
        }
    }

    /// The renames the issue names: e, the raceway lives, L10 in Mrev.
    #[test]
    fn a_rating_leaves_with_its_labels() {
        let j = serde_json::json!({"rating": {"xye": [1.0, 0.0, 0.19], "l10_mrev": 12.0,
            "raceway_lives_mrev": [13.0, 101.0], "ratings": {"c": 14000.0}}, "peak_force_n": [1.0, 2.0, 3.0]});
        let Value::Object(m) = j else { unreachable!() };
        let out = Value::Object(relabel(Doc::Run, m));
        assert_eq!(out["rating"]["e [1]"], 0.19);
        assert_eq!(out["rating"]["X [1]"], 1.0);
        assert_eq!(out["rating"]["L10 [Mrev]"], 12.0);
        assert_eq!(out["rating"]["life_inner [Mrev]"], 13.0);
        assert_eq!(out["rating"]["life_outer [Mrev]"], 101.0);
        assert_eq!(out["rating"]["ratings"]["C [N]"], 14000.0);
        assert_eq!(out["peak_force [N]"], serde_json::json!([1.0, 2.0, 3.0]));
    }
}
