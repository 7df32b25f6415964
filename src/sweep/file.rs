//! The sweep file: parsing and checking its axes against the base scene (every problem at
//! once, with line:column), key paths, units and column names.

use super::*;

/// The segments of a dotted TOML key (`a."b.c"` → `a`, `b.c`).
pub(super) fn key_path(key: &str) -> std::result::Result<Vec<String>, String> {
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
pub(super) fn field_unit(path: &[String]) -> String {
    if path.len() == 3 && path[0] == "inputs" && path[1] == "initial" {
        return crate::component::variables::by_name(&path[2])
            .map(|v| v.unit.to_string())
            .unwrap_or_default();
    }
    schema::field(&path.join("."))
        .map(|f| f.unit.to_string())
        .unwrap_or_default()
}

pub(super) fn column_name(path: &[String]) -> String {
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
pub(super) fn set_path(t: &mut toml::Table, path: &[String], v: toml::Value) -> Result<()> {
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

pub(super) fn json_of(v: &toml::Value) -> Json {
    match v {
        toml::Value::String(s) => Json::from(s.clone()),
        toml::Value::Integer(i) => Json::from(*i),
        toml::Value::Float(x) => Json::from(*x),
        toml::Value::Boolean(b) => Json::from(*b),
        other => Json::from(other.to_string()),
    }
}

pub(super) fn number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// Spans of a TOML document, to place problems by a path of keys and array indices.
pub(super) struct Places<'a> {
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

pub(super) struct Problems<'a> {
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

impl Sweep {
    /// Parse and check a sweep file; `dir` is the folder a relative `scene` path is taken
    /// from. Every problem at once, each with its line:column, or the sweep.
    pub fn from_text(text: &str, dir: &Path) -> std::result::Result<Sweep, Vec<Problem>> {
        if let Err(e) = crate::nesting::check_toml(text, crate::nesting::MAX_NESTING) {
            return Err(vec![Problem {
                path: String::new(),
                line_col: Some((e.line, e.column)),
                message: e.to_string(),
            }]);
        }
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
}
