//! Checking a scene text: every problem at once, each with its path, line:column and the
//! nearest known key; loading a scene with overrides.

use super::*;

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
pub(super) enum Node {
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

pub(super) fn from_de(v: &toml::de::DeValue<'_>) -> Node {
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

pub(super) fn from_json(v: &serde_json::Value) -> Node {
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
        // A key whose value is null is absent (as serde reads an optional field, and as
        // `Scene::from_text` reads the tree: `schema::strip_nulls`).
        J::Object(o) => Node::Table(
            o.iter()
                .filter(|(_, x)| !x.is_null())
                .map(|(k, x)| (k.clone(), None, None, from_json(x)))
                .collect(),
        ),
    }
}

/// The nearest of `known` to `name`, if near enough to be a likely misspelling.
pub(super) fn nearest<'a>(name: &str, known: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
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

/// Whether the schema has a field below the normalised path `norm` followed by `sep`
/// (`"."` for a table's fields, `"[]."` for an array of tables'), without building the
/// prefix for each field.
fn has_fields_under(norm: &str, sep: &str) -> bool {
    TABLE.iter().any(|f| {
        f.path
            .strip_prefix(norm)
            .is_some_and(|rest| rest.starts_with(sep))
    })
}

/// Known child keys of a normalised table path.
pub(super) fn children(norm: &str) -> Vec<String> {
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

pub(super) struct Checker<'a> {
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
        // The known keys only for a hint (made for an unknown key, not for every table).
        let known = std::cell::OnceCell::new();
        let known = || known.get_or_init(|| children(norm));
        let has_preset = entries.iter().any(|(k, ..)| k == "preset");
        for (key, kofs, vofs, node) in entries {
            let cpath = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            let cnorm = normalise_child(norm, key);
            self.places.push((cpath.clone(), kofs.or(*vofs)));
            if norm == "inputs.initial" && key == crate::component::scene::SPEED_VARIABLE {
                let rad_s = match node {
                    Node::Float(x) => Some(*x),
                    Node::Int(i) => Some(*i as f64),
                    _ => None,
                };
                let message = match rad_s {
                    Some(w) => format!(
                        "`{key}` (rad/s) is not read here; did you mean `speed_rpm`? {}",
                        InputSpec::old_speed_message(w)
                    ),
                    None => format!("`{key}` is not read here; did you mean `speed_rpm`? give the shaft speed in rpm: `speed_rpm = N` in [inputs]"),
                };
                self.report(&cpath, *kofs, message);
                continue;
            }
            if norm == "inputs.initial" && !input_names().iter().any(|n| n == key) {
                let list = input_names();
                let hint = match nearest(key, list.iter().map(String::as_str)) {
                    Some(crate::component::scene::SPEED_VARIABLE) => {
                        " (did you mean `speed_rpm`? the shaft speed is given in rpm in [inputs])"
                            .to_string()
                    }
                    Some(n) => format!(" (did you mean `{n}`?)"),
                    None => String::new(),
                };
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
                || has_fields_under(&cnorm, ".")
                || has_fields_under(&cnorm, "[]");
            if !is_known {
                let hint = nearest(key, known().iter().map(String::as_str))
                    .map(|n| format!("; did you mean `{n}`?"))
                    .unwrap_or_else(|| format!("; known here: {}", known().join(", ")));
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
                    && has_fields_under(norm, ".")
                    || matches!(entry.map(|e| e.kind), Some(NameOrTable(_)));
                if table_ok {
                    self.table(entries, path, norm, at);
                } else {
                    self.mismatch(path, at, entry, node);
                }
                return;
            }
            Node::Array(items) => {
                if entry.is_none() && has_fields_under(norm, "[].") {
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

pub(super) fn expect(entry: Option<&Field>) -> String {
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
    check_with(text, true).0
}

/// [`check`], with the component built (`build`) or not, and the scene it parsed when it
/// found no problem.
fn check_with(text: &str, build: bool) -> (Vec<Problem>, Option<Scene>) {
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
        return (c.problems, None);
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
                return (c.problems, None);
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
            return (c.problems, None);
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
        return (c.problems, None);
    }
    // Cross-field problems: the library's own checks, in the order a run meets them (the
    // component built, the run's inputs at its end and start set, the first outputs).
    let result = Scene::from_text(text).and_then(|s| {
        let b = s.validate()?;
        s.effects.validate_for(&b)?;
        if build {
            crate::runner::prepare(&s)?;
        }
        Ok(s)
    });
    let e = match result {
        Ok(s) => return (c.problems, Some(s)),
        Err(e) => e,
    };
    {
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
    (c.problems, None)
}

/// Every problem at once, one per line, as `raceway scene --check` prints them:
/// `N problem(s)` and each with its `line:column` (TOML), path and the nearest known name.
pub fn problems_text(problems: &[Problem]) -> String {
    let mut s = format!("{} problem(s)", problems.len());
    for p in problems {
        s.push('\n');
        s.push_str(&p.to_string());
    }
    s
}

/// The message of a scene text that failed to make a component with `e`, for the faces
/// that take scene text (the C ABI, the FMUs): [`check`]'s problems with their
/// `line:column` and "did you mean" ([`problems_text`]), as `raceway scene --check` gives
/// them; `e` itself when the checker finds nothing (a problem it does not locate).
pub fn scene_error_text(text: &str, e: &crate::Error) -> String {
    // The checker parses the text again, with spans: on the host's thread, whose stack may be
    // as small as the one docs/robustness.md promises, a deeply nested text would overflow
    // it. So it runs on a thread of its own (only on a refusal); if that thread cannot be
    // made or fails, the refusal's own message stands.
    let owned = text.to_owned();
    let problems = std::thread::Builder::new()
        .name("raceway-scene-check".into())
        .stack_size(4 << 20)
        .spawn(move || check(&owned))
        .ok()
        .and_then(|h| h.join().ok());
    match problems {
        Some(p) if !p.is_empty() => problems_text(&p),
        _ => e.to_string(),
    }
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
    if overrides.is_empty() {
        return match check_with(text, true) {
            (_, Some(scene)) => Ok(scene),
            (problems, None) => Err(problems),
        };
    }
    let problems = check(text);
    if !problems.is_empty() {
        return Err(problems);
    }
    // The scene as a TOML table (a JSON scene is converted), the overrides written in.
    let doc: std::result::Result<toml::Table, String> = if text.trim_start().starts_with('{') {
        serde_json::from_str::<serde_json::Value>(text)
            .map_err(|e| e.to_string())
            .and_then(|mut v| {
                // A null key is an absent key (TOML has no null).
                super::strip_nulls(&mut v);
                toml::Table::try_from(v).map_err(|e| e.to_string())
            })
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
    match check_with(&text2, true) {
        (_, Some(scene)) => Ok(scene),
        (problems, None) => Err(problems
            .into_iter()
            .map(|p| Problem {
                line_col: None,
                message: format!("{} (with the command-line override {applied})", p.message),
                ..p
            })
            .collect()),
    }
}

/// A scene text checked as [`check`] does, field by field and across fields, but without
/// building the component: for a caller that builds it next and reports the build's own
/// refusal (the sweep, whose point runs build it). Every problem [`check`] finds before
/// the build is in the error.
pub fn load_unbuilt(text: &str) -> std::result::Result<Scene, Vec<Problem>> {
    match check_with(text, false) {
        (_, Some(scene)) => Ok(scene),
        (problems, None) => Err(problems),
    }
}

/// `line L, column C` (TOML) or `line L column C` (JSON) in a parser's message.
pub(super) fn line_col_in(message: &str) -> Option<(usize, usize)> {
    let rest = &message[message.find("line ")? + 5..];
    let (l, rest) = rest
        .split_once(", column ")
        .or_else(|| rest.split_once(" column "))?;
    let c: String = rest.chars().take_while(char::is_ascii_digit).collect();
    Some((l.trim().parse().ok()?, c.parse().ok()?))
}

/// Input variables of either causality ([`crate::component::variables::SCALARS`]), the
/// speed included (refused with its own message): the keys `inputs.initial` takes.
fn input_names() -> Vec<String> {
    use crate::component::variables;
    variables::SCALARS
        .iter()
        .filter(|v| {
            v.is_input(variables::Causality::Motion) || v.is_input(variables::Causality::Load)
        })
        .map(|v| v.name.to_string())
        .collect()
}
