//! Parameter sweeps: a base scene and axes of values, each run a pure function
//! run index → scene → summary row, so any executor (the `raceway sweep` threads, a
//! `--shard k/n` job array, the Python package and its Dask layer) maps the same index space
//! and gets the same rows.
//!
//! A sweep file (TOML):
//!
//! ```toml
//! scene = "../scenes/default.toml"   # relative to the sweep file; or a [scene] table;
//!                                    # neither: the embedded default scene
//! series = false                     # also write series/<index>.csv for every run
//!
//! [sample]                           # only for axes given by min/max
//! method = "lhs"                     # "lhs" (Latin hypercube) or "random"
//! n = 16
//! seed = 1
//!
//! [[axis]]
//! key = 'inputs.initial."shaft.omega"'   # a scene field by its dotted TOML key
//! values = [100.0, 200.0]                # a list ...
//! [[axis]]
//! key = "run.duration_s"
//! start = 0.01                            # ... a range: start, stop and num (both ends
//! stop = 0.02                             #     included) or step
//! num = 3
//! [[axis]]
//! key = 'inputs.initial."shaft.y"'
//! min = -20e-6                            # ... or sampled in [min, max] by [sample]
//! max = -5e-6
//! ```
//!
//! The index space is the cartesian product of the list and range axes (the first axis
//! varies slowest) times the `[sample].n` samples of the min/max axes (sample index fastest).
//! Each point's values are written into the parsed base scene table, and the resulting scene
//! is checked exactly as `raceway scene --check` checks a file ([`schema::check`]).

use crate::component::schema::{self, Problem};
use crate::component::Scene;
use crate::error::{Error, Result};
use crate::report::thread_cpu_s;
use crate::runner;
use serde_json::Value as Json;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Most points a sweep may have (a guard against a mistyped `num` or `n`).
pub const MAX_POINTS: usize = 10_000_000;

/// The values of one axis.
#[derive(Debug, Clone, PartialEq)]
pub enum AxisValues {
    /// Given or generated values (lists and ranges): a grid axis.
    List(Vec<toml::Value>),
    /// Sampled in `[min, max]` by the sweep's `[sample]` table.
    Sampled {
        /// Lower end.
        min: f64,
        /// Upper end.
        max: f64,
    },
}

/// One axis: a scene field and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The dotted TOML key as written (`inputs.initial."shaft.y"`).
    pub key: String,
    /// The key's segments (`["inputs", "initial", "shaft.y"]`).
    pub path: Vec<String>,
    /// Column name in the table: the segments joined by dots, then `_<unit>` when the field
    /// has a unit (`inputs.initial.shaft.y_m`).
    pub column: String,
    /// Values.
    pub values: AxisValues,
}

/// How the min/max axes are sampled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Independent uniform samples.
    Random,
    /// Latin hypercube: each axis's range cut into `n` equal strata, one sample in each.
    Lhs,
}

/// The `[sample]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct Sampling {
    /// Method.
    pub method: Method,
    /// Number of samples.
    pub n: usize,
    /// Seed of the generator.
    pub seed: u64,
}

/// A parsed and checked sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    /// The base scene as a TOML table.
    pub base: toml::Table,
    /// Axes, in file order.
    pub axes: Vec<Axis>,
    /// Sampling of the min/max axes.
    pub sampling: Option<Sampling>,
    /// Write each run's series too.
    pub series: bool,
    /// Latin-hypercube stratum of each sampled axis for each sample (`perms[axis][sample]`).
    perms: Vec<Vec<usize>>,
}

/// SplitMix64: a small, well-mixed, seedable generator (Steele, Lea & Flood, "Fast
/// splittable pseudorandom number generators", OOPSLA 2014); used as a hash of
/// (seed, axis, sample) so every sample is a pure function of its index.
fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A uniform number in [0, 1) from (seed, stream, k): 53 random bits.
fn uniform(seed: u64, stream: u64, k: u64) -> f64 {
    let h = splitmix(splitmix(splitmix(seed) ^ stream) ^ k);
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// A seeded permutation of 0..n (Fisher–Yates).
fn permutation(n: usize, seed: u64, stream: u64) -> Vec<usize> {
    let mut p: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        let j = (uniform(seed, stream ^ 0x5EED_0000_0000, i as u64) * (i + 1) as f64) as usize;
        p.swap(i, j.min(i));
    }
    p
}

/// The segments of a dotted TOML key (`a."b.c"` → `a`, `b.c`).
fn key_path(key: &str) -> std::result::Result<Vec<String>, String> {
    let doc: toml::Table = format!("{key} = 0")
        .parse()
        .map_err(|e: toml::de::Error| format!("not a dotted TOML key: {}", e.message()))?;
    let mut path = Vec::new();
    let mut t = &doc;
    loop {
        let (k, v) = t.iter().next().ok_or("an empty key")?;
        path.push(k.clone());
        match v {
            toml::Value::Table(inner) => t = inner,
            _ => return Ok(path),
        }
    }
}

/// The unit of a scene field (`-` or empty: none).
fn field_unit(path: &[String]) -> String {
    if path.len() == 3 && path[0] == "inputs" && path[1] == "initial" {
        return crate::component::variables::by_name(&path[2])
            .map(|v| v.unit.to_string())
            .unwrap_or_default();
    }
    schema::field(&path.join("."))
        .map(|f| f.unit.to_string())
        .unwrap_or_default()
}

fn column_name(path: &[String]) -> String {
    let name = path.join(".");
    let unit = field_unit(path);
    // A key that already ends in its unit (`run.duration_s`) is not suffixed twice.
    if unit.is_empty() || unit == "-" || name.ends_with(&format!("_{unit}")) {
        name
    } else {
        format!("{name}_{}", unit.replace(' ', ""))
    }
}

/// Write `v` at `path` in `t`, making the tables on the way.
fn set_path(t: &mut toml::Table, path: &[String], v: toml::Value) -> Result<()> {
    let (last, parents) = path.split_last().expect("a key has a segment");
    let mut cur = t;
    for (i, seg) in parents.iter().enumerate() {
        let entry = cur
            .entry(seg.clone())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        cur = match entry {
            toml::Value::Table(inner) => inner,
            other => {
                return Err(Error::Parse {
                    what: "sweep point".into(),
                    message: format!(
                        "`{}` is {} in the base scene, not a table, so `{}` cannot be set",
                        path[..=i].join("."),
                        other.type_str(),
                        path.join(".")
                    ),
                })
            }
        };
    }
    cur.insert(last.clone(), v);
    Ok(())
}

fn json_of(v: &toml::Value) -> Json {
    match v {
        toml::Value::String(s) => Json::from(s.clone()),
        toml::Value::Integer(i) => Json::from(*i),
        toml::Value::Float(x) => Json::from(*x),
        toml::Value::Boolean(b) => Json::from(*b),
        other => Json::from(other.to_string()),
    }
}

/// Spans of a TOML document, to place problems by a path of keys and array indices.
struct Places<'a> {
    text: &'a str,
    root: Option<toml::de::DeTable<'a>>,
}

impl Places<'_> {
    /// Line and column of the value (or key) at `path` (`"axis"`, `"2"`, `"key"`), or of
    /// its nearest existing parent.
    fn at(&self, path: &[&str]) -> Option<(usize, usize)> {
        use toml::de::DeValue as D;
        let mut best: Option<usize> = Some(0);
        let mut node: Option<&D<'_>> = None;
        let root = self.root.as_ref()?;
        for seg in path {
            let next = match node {
                None => root
                    .iter()
                    .find(|(k, _)| k.get_ref() == seg)
                    .map(|(k, v)| (k.span().start, v)),
                Some(D::Table(t)) => t
                    .iter()
                    .find(|(k, _)| k.get_ref() == seg)
                    .map(|(k, v)| (k.span().start, v)),
                Some(D::Array(a)) => seg
                    .parse::<usize>()
                    .ok()
                    .and_then(|i| a.get(i))
                    .map(|v| (v.span().start, v)),
                Some(_) => None,
            };
            match next {
                Some((ofs, v)) => {
                    best = Some(ofs);
                    node = Some(v.get_ref());
                }
                None => break,
            }
        }
        best.map(|o| schema::line_col(self.text, o))
    }
}

struct Problems<'a> {
    places: Places<'a>,
    list: Vec<Problem>,
}

impl Problems<'_> {
    fn add(&mut self, path: &[&str], message: impl Into<String>) {
        let mut p = String::new();
        for s in path {
            if s.parse::<usize>().is_ok() {
                p += &format!("[{s}]");
            } else {
                if !p.is_empty() {
                    p.push('.');
                }
                p += s;
            }
        }
        self.list.push(Problem {
            path: p,
            line_col: self.places.at(path),
            message: message.into(),
        });
    }
}

fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

impl Sweep {
    /// Parse and check a sweep file; `dir` is the folder a relative `scene` path is taken
    /// from. Every problem at once, each with its line:column, or the sweep.
    pub fn from_text(text: &str, dir: &Path) -> std::result::Result<Sweep, Vec<Problem>> {
        let (doc, errors) = toml::de::DeTable::parse_recoverable(text);
        let mut pr = Problems {
            places: Places { text, root: None },
            list: Vec::new(),
        };
        if !errors.is_empty() {
            for e in errors {
                pr.list.push(Problem {
                    path: String::new(),
                    line_col: e.span().map(|s| schema::line_col(text, s.start)),
                    message: format!("TOML syntax: {}", e.message().trim()),
                });
            }
            return Err(pr.list);
        }
        pr.places.root = Some(doc.into_inner());
        let table: toml::Table = match text.parse() {
            Ok(t) => t,
            Err(e) => {
                pr.add(&[], format!("TOML: {}", e.message()));
                return Err(pr.list);
            }
        };
        for k in table.keys() {
            if !["scene", "series", "sample", "axis"].contains(&k.as_str()) {
                pr.add(
                    &[k],
                    format!("unknown key `{k}`; known here: scene, series, sample, axis"),
                );
            }
        }
        // The base scene.
        let base_text = match table.get("scene") {
            None => Some(crate::component::scene::DEFAULT_SCENE.to_string()),
            Some(toml::Value::String(p)) => {
                let path = dir.join(p);
                match std::fs::read_to_string(&path) {
                    Ok(t) => Some(t),
                    Err(e) => {
                        pr.add(
                            &["scene"],
                            format!("cannot read the base scene `{}`: {e}", path.display()),
                        );
                        None
                    }
                }
            }
            Some(toml::Value::Table(t)) => Some(toml::to_string(t).unwrap_or_default()),
            Some(other) => {
                pr.add(
                    &["scene"],
                    format!(
                        "expected a scene file path or a [scene] table, found {}",
                        other.type_str()
                    ),
                );
                None
            }
        };
        let mut base = toml::Table::new();
        let mut base_ok = false;
        if let Some(bt) = &base_text {
            let problems = schema::check(bt);
            let what = match table.get("scene") {
                Some(toml::Value::String(p)) => format!("base scene `{p}`"),
                Some(_) => "the [scene] table".to_string(),
                None => "the default scene".to_string(),
            };
            for p in &problems {
                pr.add(&["scene"], format!("{what}: {p}"));
            }
            if problems.is_empty() {
                base = bt.parse().unwrap_or_default();
                base_ok = true;
            }
        }
        let series = match table.get("series") {
            None => false,
            Some(toml::Value::Boolean(b)) => *b,
            Some(o) => {
                pr.add(
                    &["series"],
                    format!("expected a boolean, found {}", o.type_str()),
                );
                false
            }
        };
        // Sampling.
        let mut sampling = None;
        match table.get("sample") {
            None => {}
            Some(toml::Value::Table(t)) => {
                for k in t.keys() {
                    if !["method", "n", "seed"].contains(&k.as_str()) {
                        pr.add(
                            &["sample", k],
                            format!("unknown key `{k}`; known here: method, n, seed"),
                        );
                    }
                }
                let method = match t.get("method").and_then(|v| v.as_str()) {
                    Some("lhs") => Some(Method::Lhs),
                    Some("random") => Some(Method::Random),
                    _ => {
                        pr.add(
                            &["sample", "method"],
                            "expected \"lhs\" or \"random\" (a required field)",
                        );
                        None
                    }
                };
                let n = match t.get("n").and_then(|v| v.as_integer()) {
                    Some(n) if n >= 1 && n as usize <= MAX_POINTS => Some(n as usize),
                    _ => {
                        pr.add(
                            &["sample", "n"],
                            format!("expected an integer in [1, {MAX_POINTS}] (the number of samples; a required field)"),
                        );
                        None
                    }
                };
                let seed = match t.get("seed") {
                    None => Some(0),
                    Some(toml::Value::Integer(s)) if *s >= 0 => Some(*s as u64),
                    Some(_) => {
                        pr.add(&["sample", "seed"], "expected an integer >= 0");
                        None
                    }
                };
                if let (Some(method), Some(n), Some(seed)) = (method, n, seed) {
                    sampling = Some(Sampling { method, n, seed });
                }
            }
            Some(o) => pr.add(
                &["sample"],
                format!("expected a table, found {}", o.type_str()),
            ),
        }
        // Axes.
        let mut axes: Vec<Axis> = Vec::new();
        let items: &[toml::Value] = match table.get("axis") {
            Some(toml::Value::Array(a)) => a,
            Some(o) => {
                pr.add(
                    &["axis"],
                    format!("expected [[axis]] tables, found {}", o.type_str()),
                );
                &[]
            }
            None => {
                pr.add(&[], "no [[axis]]: a sweep needs at least one axis");
                &[]
            }
        };
        for (i, item) in items.iter().enumerate() {
            let is = i.to_string();
            let at = |k: &'static str| [String::from("axis"), is.clone(), k.to_string()];
            let Some(t) = item.as_table() else {
                pr.add(&["axis", &is], "expected a table");
                continue;
            };
            for k in t.keys() {
                if ![
                    "key", "values", "start", "stop", "num", "step", "min", "max",
                ]
                .contains(&k.as_str())
                {
                    pr.add(
                        &["axis", &is, k],
                        format!(
                            "unknown key `{k}`; known here: key, values, start, stop, num, step, min, max"
                        ),
                    );
                }
            }
            let key_at = at("key");
            let key_at: Vec<&str> = key_at.iter().map(String::as_str).collect();
            let (key, path) = match t.get("key") {
                Some(toml::Value::String(k)) => match key_path(k) {
                    Ok(p) => (k.clone(), p),
                    Err(m) => {
                        pr.add(&key_at, format!("`{k}`: {m}"));
                        continue;
                    }
                },
                _ => {
                    pr.add(
                        &["axis", &is],
                        "missing `key`: the scene field this axis sets, as a dotted key (e.g. 'inputs.initial.\"shaft.y\"')",
                    );
                    continue;
                }
            };
            if axes.iter().any(|a| a.path == path) {
                pr.add(&key_at, format!("`{key}` is already an axis"));
            }
            let has = |k: &str| t.contains_key(k);
            let forms = [
                has("values"),
                has("start") || has("stop") || has("num") || has("step"),
                has("min") || has("max"),
            ];
            let values = match forms {
                [true, false, false] => match t.get("values") {
                    Some(toml::Value::Array(v)) if !v.is_empty() => {
                        Some(AxisValues::List(v.clone()))
                    }
                    _ => {
                        let p = at("values");
                        let p: Vec<&str> = p.iter().map(String::as_str).collect();
                        pr.add(&p, "expected a non-empty array of values");
                        None
                    }
                },
                [false, true, false] => {
                    let mut bad = |k: &'static str, m: String| {
                        let p = at(k);
                        let p: Vec<&str> = p.iter().map(String::as_str).collect();
                        pr.add(&p, m);
                    };
                    let start = t.get("start").and_then(number);
                    let stop = t.get("stop").and_then(number);
                    if start.is_none_or(|x| !x.is_finite()) {
                        bad("start", "a range needs a finite number `start`".into());
                    }
                    if stop.is_none_or(|x| !x.is_finite()) {
                        bad("stop", "a range needs a finite number `stop`".into());
                    }
                    let ints = ["start", "stop", "step"]
                        .iter()
                        .all(|k| t.get(*k).is_none_or(|v| v.is_integer()))
                        && has("step");
                    match (start, stop, t.get("num"), t.get("step")) {
                        (_, _, Some(_), Some(_)) => {
                            bad("step", "give `num` or `step`, not both".into());
                            None
                        }
                        (Some(a), Some(b), Some(n), None) => match n.as_integer() {
                            Some(n) if n >= 1 && n as usize <= MAX_POINTS => {
                                let n = n as usize;
                                Some(AxisValues::List(
                                    (0..n)
                                        .map(|k| {
                                            let x = if n == 1 {
                                                a
                                            } else if k == n - 1 {
                                                b
                                            } else {
                                                a + (b - a) * k as f64 / (n - 1) as f64
                                            };
                                            toml::Value::Float(x)
                                        })
                                        .collect(),
                                ))
                            }
                            _ => {
                                bad("num", format!("expected an integer in [1, {MAX_POINTS}]"));
                                None
                            }
                        },
                        (Some(a), Some(b), None, Some(s)) => match number(s) {
                            Some(s)
                                if s.is_finite()
                                    && s != 0.0
                                    && (b - a) / s >= 0.0
                                    && (b - a) / s < MAX_POINTS as f64 =>
                            {
                                // The stop is included when it falls on the grid (to a
                                // millionth of a step).
                                let n = ((b - a) / s + 1e-6).floor() as usize + 1;
                                Some(AxisValues::List(
                                    (0..n)
                                        .map(|k| {
                                            let x = a + s * k as f64;
                                            if ints {
                                                toml::Value::Integer(x as i64)
                                            } else {
                                                toml::Value::Float(x)
                                            }
                                        })
                                        .collect(),
                                ))
                            }
                            _ => {
                                bad(
                                    "step",
                                    "expected a finite non-zero number with the sign of stop - start"
                                        .into(),
                                );
                                None
                            }
                        },
                        (_, _, None, None) => {
                            bad("start", "a range needs `num` or `step`".into());
                            None
                        }
                        _ => None,
                    }
                }
                [false, false, true] => {
                    let (lo, hi) = (t.get("min").and_then(number), t.get("max").and_then(number));
                    match (lo, hi) {
                        (Some(lo), Some(hi)) if lo.is_finite() && hi.is_finite() && lo <= hi => {
                            if table.get("sample").is_none() {
                                pr.add(
                                    &key_at,
                                    "an axis with min/max is sampled: add a [sample] table (method, n, seed)",
                                );
                            }
                            Some(AxisValues::Sampled { min: lo, max: hi })
                        }
                        _ => {
                            let p = at("min");
                            let p: Vec<&str> = p.iter().map(String::as_str).collect();
                            pr.add(&p, "expected finite numbers `min` <= `max`");
                            None
                        }
                    }
                }
                _ => {
                    pr.add(
                        &key_at,
                        "an axis has exactly one of: `values`; `start`, `stop` and `num` or `step`; `min` and `max`",
                    );
                    None
                }
            };
            let Some(values) = values else { continue };
            // Each value applied to the base scene alone, checked as `scene --check` does
            // (the first few failing values of the axis are reported).
            if base_ok {
                let probe: Vec<(toml::Value, Vec<String>)> = match &values {
                    AxisValues::List(v) => v
                        .iter()
                        .enumerate()
                        .map(|(k, x)| (x.clone(), vec![k.to_string()]))
                        .collect(),
                    AxisValues::Sampled { min, max } => vec![
                        (toml::Value::Float(*min), vec![]),
                        (toml::Value::Float(*max), vec![]),
                    ],
                };
                let mut failed = 0;
                for (v, sub) in probe.iter().take(1000) {
                    let mut scene = base.clone();
                    let problems = match set_path(&mut scene, &path, v.clone()) {
                        Ok(()) => schema::check(&toml::to_string(&scene).unwrap_or_default()),
                        Err(e) => vec![Problem {
                            path: path.join("."),
                            line_col: None,
                            message: e.to_string(),
                        }],
                    };
                    if let Some(p) = problems.first() {
                        let mut place = vec!["axis".to_string(), is.clone()];
                        match &values {
                            // A wrong key is the key's problem, whatever the value.
                            _ if p.message.starts_with("unknown") && p.path == path.join(".") => {
                                place.push("key".into())
                            }
                            AxisValues::List(_) if t.contains_key("values") => {
                                place.push("values".into());
                                place.extend(sub.iter().cloned());
                            }
                            _ => place.push("key".into()),
                        }
                        let place: Vec<&str> = place.iter().map(String::as_str).collect();
                        let more = if problems.len() > 1 {
                            format!(" (and {} more)", problems.len() - 1)
                        } else {
                            String::new()
                        };
                        pr.add(
                            &place,
                            format!(
                                "`{key}` = {v}: the scene fails its check: {}{more}",
                                p.message
                            ),
                        );
                        failed += 1;
                        if failed == 3 {
                            break;
                        }
                    }
                }
            }
            axes.push(Axis {
                column: column_name(&path),
                key,
                path,
                values,
            });
        }
        let sampled = axes
            .iter()
            .filter(|a| matches!(a.values, AxisValues::Sampled { .. }))
            .count();
        if sampled == 0 && table.contains_key("sample") {
            pr.add(
                &["sample"],
                "a [sample] table but no axis with min/max to sample",
            );
        }
        let mut len: f64 = sampling.as_ref().map_or(1.0, |s| s.n as f64);
        for a in &axes {
            if let AxisValues::List(v) = &a.values {
                len *= v.len() as f64;
            }
        }
        if len > MAX_POINTS as f64 {
            pr.add(
                &["axis"],
                format!("{len} points: more than the {MAX_POINTS} a sweep may have"),
            );
        }
        pr.list.sort_by_key(|p| p.line_col);
        if !pr.list.is_empty() {
            return Err(pr.list);
        }
        let perms = match &sampling {
            Some(s) if s.method == Method::Lhs => (0..axes.len())
                .map(|k| permutation(s.n, s.seed, k as u64))
                .collect(),
            _ => Vec::new(),
        };
        Ok(Sweep {
            base,
            axes,
            sampling,
            series,
            perms,
        })
    }

    /// Read and parse a sweep file; the problems (if any) are in the error, one per line,
    /// each `file:line:column: ...`.
    pub fn from_file(path: &Path) -> Result<Sweep> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::Io(format!("cannot read sweep `{}`: {e}", path.display())))?;
        let dir = path.parent().unwrap_or(Path::new("."));
        Sweep::from_text(&text, dir).map_err(|problems| {
            let mut message = format!("{} problem(s)", problems.len());
            for p in &problems {
                message += &format!("\n{}:{p}", path.display());
            }
            Error::Parse {
                what: format!("sweep `{}`", path.display()),
                message,
            }
        })
    }

    fn samples(&self) -> usize {
        self.sampling.as_ref().map_or(1, |s| s.n)
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.axes
            .iter()
            .map(|a| match &a.values {
                AxisValues::List(v) => v.len(),
                AxisValues::Sampled { .. } => 1,
            })
            .product::<usize>()
            * self.samples()
    }

    /// Whether the sweep has no point (never, once parsed).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The axes' values at point `index` (< [`Sweep::len`]), in axis order.
    pub fn point(&self, index: usize) -> Vec<toml::Value> {
        let s = self.samples();
        let (mut grid, j) = (index / s, index % s);
        let mut out = vec![toml::Value::Integer(0); self.axes.len()];
        for (k, a) in self.axes.iter().enumerate().rev() {
            out[k] = match &a.values {
                AxisValues::List(v) => {
                    let x = v[grid % v.len()].clone();
                    grid /= v.len();
                    x
                }
                AxisValues::Sampled { min, max } => {
                    let sp = self
                        .sampling
                        .as_ref()
                        .expect("checked: sampled axes have [sample]");
                    let u = uniform(sp.seed, k as u64, j as u64);
                    let f = match sp.method {
                        Method::Random => u,
                        Method::Lhs => (self.perms[k][j] as f64 + u) / sp.n as f64,
                    };
                    toml::Value::Float(min + (max - min) * f)
                }
            };
        }
        out
    }

    /// The scene text of point `index`: the base scene with the point's values written in.
    pub fn scene_text(&self, index: usize) -> Result<String> {
        let mut t = self.base.clone();
        for (a, v) in self.axes.iter().zip(self.point(index)) {
            set_path(&mut t, &a.path, v)?;
        }
        toml::to_string(&t).map_err(|e| Error::Parse {
            what: "sweep point".into(),
            message: e.to_string(),
        })
    }

    /// The scene of point `index`, checked as `raceway scene --check` checks a file: every
    /// problem in the error.
    pub fn scene(&self, index: usize) -> Result<Scene> {
        let text = self.scene_text(index)?;
        schema::load(&text, &[]).map_err(|problems| {
            let list: Vec<String> = problems
                .iter()
                .map(|p| {
                    let mut p = p.clone();
                    p.line_col = None;
                    p.to_string()
                })
                .collect();
            Error::Parse {
                what: format!("the scene of sweep point {index}"),
                message: list.join("; "),
            }
        })
    }

    /// Run point `index`: scene, run, the summary `raceway run` writes
    /// ([`crate::summary::summarize`], with the thread CPU time of the run), flattened into a
    /// row. Never fails: an error (or a panic) becomes the row's
    /// `error`. With `series`, the run's series is written there (atomically).
    pub fn run_point(&self, index: usize, series: Option<&Path>) -> Row {
        let axes: Vec<(String, Json)> = self
            .axes
            .iter()
            .zip(self.point(index))
            .map(|(a, v)| (a.column.clone(), json_of(&v)))
            .collect();
        let attempt = || -> Result<Vec<(String, Json)>> {
            let scene = self.scene(index)?;
            let c0 = thread_cpu_s();
            let (run, comp) = runner::run(&scene, &mut |_| {})?;
            let cpu = thread_cpu_s() - c0;
            if let Some(p) = series {
                write_atomic(p, run.to_csv().as_bytes())?;
            }
            let mut cols = Vec::new();
            let summary = crate::summary::summarize(&scene, "sweep point", &run, &comp, cpu);
            flatten("", &Json::Object(summary.json), &mut cols);
            Ok(cols)
        };
        let (error, summary) = match std::panic::catch_unwind(std::panic::AssertUnwindSafe(attempt))
        {
            Ok(Ok(cols)) => (None, cols),
            // One line per row: a multi-line message is joined.
            Ok(Err(e)) => (
                Some(
                    e.to_string()
                        .split_whitespace()
                        .collect::<Vec<_>>()
                        .join(" "),
                ),
                Vec::new(),
            ),
            Err(p) => {
                let what = crate::error::panic_message(&*p).unwrap_or_default();
                (Some(format!("panic: {what}")), Vec::new())
            }
        };
        Row {
            index,
            axes,
            error,
            summary,
        }
    }

    /// A fingerprint of what the sweep computes (base scene, axes, sampling): rows of one
    /// sweep are never mixed with another's.
    pub fn fingerprint(&self) -> String {
        let text = format!(
            "{}\n{:?}\n{:?}\n{}",
            toml::to_string(&self.base).unwrap_or_default(),
            self.axes,
            self.sampling,
            self.series
        );
        // FNV-1a, 64 bits.
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for b in text.bytes() {
            h = (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3);
        }
        format!("{h:016x}")
    }
}

/// The summary columns that are measurements of the machine, not results: they differ from
/// run to run; every other column is the same bit for bit whatever the threads or shards.
pub const MEASUREMENTS: [&str; 2] = ["cpu_s", "load_average"];

/// One finished point.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Row {
    /// Run index.
    pub index: usize,
    /// (column, value) of each axis.
    pub axes: Vec<(String, Json)>,
    /// Why the run failed, if it did.
    pub error: Option<String>,
    /// (column, value) of the flattened summary (empty when the run failed).
    pub summary: Vec<(String, Json)>,
}

/// A summary key's unit suffix (`peak_force_n` → `peak_force`, `N`).
fn split_unit(key: &str) -> (&str, Option<&'static str>) {
    const UNITS: [(&str, &str); 8] = [
        ("_n", "N"),
        ("_pa", "Pa"),
        ("_hz", "Hz"),
        ("_s", "s"),
        ("_m", "m"),
        ("_nm", "Nm"),
        ("_rpm", "rpm"),
        ("_h", "h"),
    ];
    for (suffix, unit) in UNITS {
        if let Some(stem) = key.strip_suffix(suffix) {
            if !stem.is_empty() {
                return (stem, Some(unit));
            }
        }
    }
    (key, None)
}

/// Flatten a summary into columns: nested keys joined by dots, the unit of a key moved to
/// the end (`peak_force_n: [x, y, z]` → `peak_force.x_N`, ...), arrays of labelled tables
/// by their label (`frequencies.BPFO.expected_Hz`), arrays of strings joined by `; `.
pub fn flatten(prefix: &str, v: &Json, out: &mut Vec<(String, Json)>) {
    flatten_unit(prefix, None, v, out)
}

fn flatten_unit(prefix: &str, unit: Option<&str>, v: &Json, out: &mut Vec<(String, Json)>) {
    let join = |k: &str| {
        if prefix.is_empty() {
            k.to_string()
        } else {
            format!("{prefix}.{k}")
        }
    };
    match v {
        Json::Object(m) => {
            for (k, x) in m {
                let (stem, u) = split_unit(k);
                flatten_unit(&join(stem), u.or(unit), x, out);
            }
        }
        Json::Array(a) if a.iter().all(Json::is_string) => {
            let s: Vec<&str> = a.iter().filter_map(Json::as_str).collect();
            out.push((prefix.to_string(), Json::from(s.join("; "))));
        }
        Json::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                let name = match x.get("label").and_then(Json::as_str) {
                    Some(l) => l.to_string(),
                    None if a.len() == 3 => ["x", "y", "z"][i].to_string(),
                    None => i.to_string(),
                };
                let x = match x {
                    Json::Object(m) if m.contains_key("label") => {
                        let mut m = m.clone();
                        m.remove("label");
                        Json::Object(m)
                    }
                    other => other.clone(),
                };
                flatten_unit(&join(&name), unit, &x, out);
            }
        }
        leaf => {
            let name = match unit {
                Some(u) => format!("{prefix}_{u}"),
                None => prefix.to_string(),
            };
            out.push((name, leaf.clone()));
        }
    }
}

/// Write a file atomically ([`crate::fsutil::write_atomic`]: a temporary file in the same
/// folder, then a rename), making the folder first, so a reader (or a resumed sweep) sees the
/// whole file or none.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let io = |e: std::io::Error| Error::Io(format!("cannot write `{}`: {e}", path.display()));
    std::fs::create_dir_all(path.parent().unwrap_or(Path::new("."))).map_err(io)?;
    crate::fsutil::write_atomic(path, bytes).map_err(io)
}

fn row_path(dir: &Path, index: usize) -> PathBuf {
    dir.join("rows").join(format!("{index:08}.json"))
}

/// The finished rows in `dir/rows` (unreadable files are not finished).
pub fn read_rows(dir: &Path) -> Vec<Row> {
    let mut rows: Vec<Row> = std::fs::read_dir(dir.join("rows"))
        .into_iter()
        .flatten()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().ends_with(".json"))
        .filter(|e| !e.file_name().to_string_lossy().starts_with('.'))
        .filter_map(|e| std::fs::read(e.path()).ok())
        .filter_map(|b| serde_json::from_slice(&b).ok())
        .collect();
    rows.sort_by_key(|r| r.index);
    rows.dedup_by_key(|r| r.index);
    rows
}

fn csv_field(v: &Json) -> String {
    let s = match v {
        Json::Null => String::new(),
        Json::Number(n) => match (n.as_i64(), n.as_f64()) {
            (Some(i), _) => i.to_string(),
            // Rust prints the shortest text that reads back to the same f64.
            (None, Some(x)) => format!("{x:?}"),
            _ => n.to_string(),
        },
        Json::Bool(b) => b.to_string(),
        Json::String(s) => s.clone(),
        other => other.to_string(),
    };
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s
    }
}

/// The CSV table of `rows` (sorted by index): `index`, the axes' columns, `error`, then the
/// summary columns in order of first appearance; an absent value is an empty field.
pub fn csv(rows: &[Row]) -> String {
    let mut cols: Vec<String> = vec!["index".into()];
    let push = |c: &str, cols: &mut Vec<String>| {
        if !cols.iter().any(|x| x == c) {
            cols.push(c.to_string());
        }
    };
    for r in rows {
        for (c, _) in &r.axes {
            push(c, &mut cols);
        }
    }
    push("error", &mut cols);
    for r in rows {
        for (c, _) in &r.summary {
            push(c, &mut cols);
        }
    }
    let mut s = cols
        .iter()
        .map(|c| csv_field(&Json::from(c.as_str())))
        .collect::<Vec<_>>()
        .join(",");
    s.push('\n');
    for r in rows {
        let mut fields = vec![String::new(); cols.len()];
        fields[0] = r.index.to_string();
        let error = r.error.clone().map(Json::from).unwrap_or(Json::Null);
        for (c, v) in r
            .axes
            .iter()
            .chain(std::iter::once(&("error".to_string(), error)))
            .chain(&r.summary)
        {
            if let Some(k) = cols.iter().position(|x| x == c) {
                fields[k] = csv_field(v);
            }
        }
        s += &fields.join(",");
        s.push('\n');
    }
    s
}

/// How a sweep is executed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Exec {
    /// Worker threads (>= 1).
    pub jobs: usize,
    /// `(k, n)`: run the indices `i` with `i % n == k` (0-based `k`).
    pub shard: (usize, usize),
}

/// What an execution did.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// Points of the whole sweep.
    pub total: usize,
    /// Points of this shard.
    pub in_shard: usize,
    /// Points run now.
    pub ran: usize,
    /// Points of this shard found finished and skipped.
    pub skipped: usize,
    /// Failed rows among those run now.
    pub failed: usize,
    /// Finished rows in the folder (all shards that wrote there).
    pub finished: usize,
    /// Thread CPU time of the runs made now, s (sum over threads).
    pub cpu_s: f64,
}

const ID_FILE: &str = "sweep.id";

/// Claim `dir` for the sweep of fingerprint `id` ([`Sweep::fingerprint`]): a folder holding
/// another sweep's rows is refused.
pub fn claim_dir(dir: &Path, id: &str) -> Result<()> {
    let path = dir.join(ID_FILE);
    match std::fs::read_to_string(&path) {
        Ok(old) if old.trim() != id => Err(Error::Parse {
            what: format!("output folder `{}`", dir.display()),
            message: format!(
                "it holds rows of another sweep (fingerprint {} here, {id} for this sweep); use another --out or empty it",
                old.trim()
            ),
        }),
        Ok(_) => Ok(()),
        Err(_) => write_atomic(&path, format!("{id}\n").as_bytes()),
    }
}

/// Run the points of `exec.shard` not yet finished in `dir`, `exec.jobs` at a time; each
/// finished row is written atomically to `dir/rows/<index>.json`, and at the end
/// `dir/sweep.csv` holds every finished row of the folder. `progress(done, to_do, failed)`
/// is called after each point.
pub fn execute(
    sweep: &Sweep,
    dir: &Path,
    exec: Exec,
    progress: &(dyn Fn(usize, usize, usize) + Sync),
) -> Result<Outcome> {
    let (k, n) = exec.shard;
    if n == 0 || k >= n {
        return Err(Error::invalid(
            "--shard k/n",
            k as f64,
            "0 <= k < n (k is 0-based, as Slurm's and Kubernetes' array indices)",
        ));
    }
    claim_dir(dir, &sweep.fingerprint())?;
    let total = sweep.len();
    let done: std::collections::BTreeSet<usize> =
        read_rows(dir).into_iter().map(|r| r.index).collect();
    let shard: Vec<usize> = (k..total).step_by(n).collect();
    let todo: Vec<usize> = shard
        .iter()
        .copied()
        .filter(|i| !done.contains(i))
        .collect();
    let next = AtomicUsize::new(0);
    let finished = AtomicUsize::new(0);
    let failed = AtomicUsize::new(0);
    let cpu = Mutex::new(0.0f64);
    let first_error: Mutex<Option<Error>> = Mutex::new(None);
    let jobs = exec.jobs.max(1).min(todo.len().max(1));
    std::thread::scope(|s| {
        for _ in 0..jobs {
            s.spawn(|| {
                let c0 = thread_cpu_s();
                loop {
                    let w = next.fetch_add(1, Ordering::Relaxed);
                    let Some(&i) = todo.get(w) else { break };
                    if first_error.lock().map(|e| e.is_some()).unwrap_or(true) {
                        break;
                    }
                    let series = sweep
                        .series
                        .then(|| dir.join("series").join(format!("{i:08}.csv")));
                    let row = sweep.run_point(i, series.as_deref());
                    if row.error.is_some() {
                        failed.fetch_add(1, Ordering::Relaxed);
                    }
                    let bytes = serde_json::to_vec(&row).expect("a row serialises");
                    if let Err(e) = write_atomic(&row_path(dir, i), &bytes) {
                        if let Ok(mut slot) = first_error.lock() {
                            slot.get_or_insert(e);
                        }
                        break;
                    }
                    let d = finished.fetch_add(1, Ordering::Relaxed) + 1;
                    progress(d, todo.len(), failed.load(Ordering::Relaxed));
                }
                if let Ok(mut c) = cpu.lock() {
                    *c += thread_cpu_s() - c0;
                }
            });
        }
    });
    if let Some(e) = first_error.into_inner().ok().flatten() {
        return Err(e);
    }
    let rows = read_rows(dir);
    write_atomic(&dir.join("sweep.csv"), csv(&rows).as_bytes())?;
    Ok(Outcome {
        total,
        in_shard: shard.len(),
        ran: finished.into_inner(),
        skipped: shard.len() - todo.len(),
        failed: failed.into_inner(),
        finished: rows.len(),
        cpu_s: cpu.into_inner().unwrap_or(0.0),
    })
}

/// Store rows finished elsewhere (another executor, e.g. Dask workers) in `dir` as
/// [`execute`] does: each row atomically into `dir/rows/` (a row already there is kept), then
/// `dir/sweep.csv` from every finished row of the folder. Returns the CSV text. Claim the
/// folder first ([`claim_dir`]).
pub fn store(dir: &Path, rows: &[Row]) -> Result<String> {
    for r in rows {
        let p = row_path(dir, r.index);
        if !p.exists() {
            write_atomic(&p, &serde_json::to_vec(r).expect("a row serialises"))?;
        }
    }
    let text = csv(&read_rows(dir));
    write_atomic(&dir.join("sweep.csv"), text.as_bytes())?;
    Ok(text)
}

/// Join the rows of shard folders (same sweep) into `out`: its rows and `out/sweep.csv`.
/// Returns the number of rows.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<usize> {
    let mut id: Option<String> = None;
    let mut rows: Vec<Row> = Vec::new();
    for d in dirs {
        let this = std::fs::read_to_string(d.join(ID_FILE)).map_err(|e| {
            Error::Io(format!(
                "`{}` is not a sweep output folder (no {ID_FILE}: {e})",
                d.display()
            ))
        })?;
        match &id {
            Some(first) if first.trim() != this.trim() => {
                return Err(Error::Parse {
                    what: format!("sweep folder `{}`", d.display()),
                    message: format!(
                        "its sweep (fingerprint {}) is not the first folder's ({})",
                        this.trim(),
                        first.trim()
                    ),
                })
            }
            _ => id = Some(this),
        }
        rows.extend(read_rows(d));
    }
    let id = id.ok_or_else(|| Error::invalid("--merge", 0.0, "at least one folder"))?;
    rows.sort_by_key(|r| r.index);
    rows.dedup_by_key(|r| r.index);
    claim_dir(out, id.trim())?;
    for r in &rows {
        let p = row_path(out, r.index);
        if !p.exists() {
            write_atomic(&p, &serde_json::to_vec(r).expect("a row serialises"))?;
        }
    }
    write_atomic(&out.join("sweep.csv"), csv(&rows).as_bytes())?;
    Ok(rows.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dotted_keys_split_like_toml() {
        assert_eq!(
            key_path("inputs.initial.\"shaft.y\"").unwrap(),
            ["inputs", "initial", "shaft.y"]
        );
        assert!(key_path("a..b").is_err());
    }

    #[test]
    fn flattened_summary_carries_units_in_names() {
        let mut out = Vec::new();
        flatten(
            "",
            &serde_json::json!({"peak_force_n": [1.0, 2.0, 3.0], "level": "ring",
                "frequencies": [{"label": "BPFO", "expected_hz": 10.0, "found_hz": null}],
                "warnings": ["a", "b"]}),
            &mut out,
        );
        let names: Vec<&str> = out.iter().map(|(n, _)| n.as_str()).collect();
        for want in [
            "peak_force.x_N",
            "peak_force.z_N",
            "level",
            "frequencies.BPFO.expected_Hz",
            "frequencies.BPFO.found_Hz",
            "warnings",
        ] {
            assert!(names.contains(&want), "{want} in {names:?}");
        }
    }

    #[test]
    fn csv_numbers_round_trip_exactly() {
        let x: f64 = 0.1 + 0.2;
        let text = csv_field(&Json::from(x));
        assert_eq!(text.parse::<f64>().unwrap().to_bits(), x.to_bits());
        assert_eq!(csv_field(&Json::from("a,\"b\"")), "\"a,\"\"b\"\"\"");
    }
}
