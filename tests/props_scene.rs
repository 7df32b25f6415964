//! Property tests of the scene parser (issue #21 item 4): arbitrary mutations of every
//! shipped scene (a value replaced by NaN, ±inf, a huge, tiny or negative number, a value
//! of the wrong type, an array where a table belongs; keys deleted or duplicated; the same
//! scene as JSON) go through the one validation path of `raceway scene --check`
//! (`schema::check`) and `raceway run` (`schema::load`). Properties:
//!
//! - nothing panics;
//! - `--check`, `run` and `raceway_create` agree: `check` finds no problem exactly when
//!   `load` returns a scene and exactly when `Component::from_text` builds one; the
//!   scene's own duration given as `--duration` does not change the verdict, and an
//!   override hides no problem;
//! - a refused scene has at least one problem, and every problem names its field or, for
//!   a syntax error, its line and column;
//! - an accepted scene builds a component (also through `raceway_create`'s
//!   `Component::from_text`), and three 0.1 ms steps either succeed with every output
//!   finite or are refused with a clear message (never a message about NaN).
//!
//! Cases: see `tests/props_util`. A failure prints the shrunk mutation and the scene text.

mod props_util;

use props_util::number;
use proptest::prelude::*;
use proptest::sample::Index;
use raceway::component::{schema, variables, Component};
use toml::{Table, Value};

/// Every shipped scene: `examples/scenes/*.toml` and the default scene.
fn scenes() -> &'static [(String, Table)] {
    static SCENES: std::sync::OnceLock<Vec<(String, Table)>> = std::sync::OnceLock::new();
    SCENES.get_or_init(|| {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .expect("examples/scenes")
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .collect();
        files.sort();
        let mut out = vec![(
            "default".to_string(),
            toml::from_str(raceway::component::scene::DEFAULT_SCENE).expect("default scene"),
        )];
        for p in files {
            let text = std::fs::read_to_string(&p).expect("scene");
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            out.push((name, toml::from_str(&text).expect("shipped scenes parse")));
        }
        out
    })
}

/// A value put in place of another.
#[derive(Debug, Clone)]
enum New {
    Float(f64),
    Int(i64),
    Str(&'static str),
    Bool(bool),
    EmptyArray,
    EmptyTable,
}

impl New {
    fn value(&self) -> Value {
        match *self {
            New::Float(x) => Value::Float(x),
            New::Int(i) => Value::Integer(i),
            New::Str(s) => Value::String(s.into()),
            New::Bool(b) => Value::Boolean(b),
            New::EmptyArray => Value::Array(vec![]),
            New::EmptyTable => Value::Table(Table::new()),
        }
    }
}

/// One mutation of a scene; `at` picks a key among the scene's keys at that moment (in
/// depth-first order, tables included).
#[derive(Debug, Clone)]
enum Mutation {
    /// The value replaced.
    Set { at: Index, new: New },
    /// The number scaled (sign flips, huge, tiny).
    Scale { at: Index, by: f64 },
    /// The key deleted.
    Delete { at: Index },
    /// The value wrapped in an array (`x = [v]`); a table becomes the array of its values.
    ToArray { at: Index },
    /// The value wrapped in a table (`x = { x = v }`).
    ToTable { at: Index },
}

fn new_value() -> impl Strategy<Value = New> {
    prop_oneof![
        4 => number().prop_map(New::Float),
        1 => prop_oneof![Just(0i64), Just(-1), Just(1), Just(i64::MAX), Just(i64::MIN), any::<i64>()]
            .prop_map(New::Int),
        1 => proptest::sample::select(vec!["", "6205", "ring", "load", "nan", "x"]).prop_map(New::Str),
        1 => any::<bool>().prop_map(New::Bool),
        1 => Just(New::EmptyArray),
        1 => Just(New::EmptyTable),
    ]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<Index>(), new_value()).prop_map(|(at, new)| Mutation::Set { at, new }),
        2 => (any::<Index>(), proptest::sample::select(vec![-1.0, 1e-300, 1e-100, 1e3, 1e300, -1e-3]))
            .prop_map(|(at, by)| Mutation::Scale { at, by }),
        2 => any::<Index>().prop_map(|at| Mutation::Delete { at }),
        1 => any::<Index>().prop_map(|at| Mutation::ToArray { at }),
        1 => any::<Index>().prop_map(|at| Mutation::ToTable { at }),
    ]
}

/// How the mutated scene is written.
#[derive(Debug, Clone)]
enum Form {
    Toml,
    /// TOML with one line written twice (a duplicated key or table header).
    TomlDuplicateLine(Index),
    /// JSON (NaN and infinities become `null`).
    Json,
}

fn form() -> impl Strategy<Value = Form> {
    prop_oneof![
        6 => Just(Form::Toml),
        1 => any::<Index>().prop_map(Form::TomlDuplicateLine),
        2 => Just(Form::Json),
    ]
}

/// Every key path of a table, depth first (tables and arrays of tables included).
fn paths(t: &Table, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    for (k, v) in t {
        prefix.push(k.clone());
        out.push(prefix.clone());
        if let Value::Table(sub) = v {
            paths(sub, prefix, out);
        }
        prefix.pop();
    }
}

/// The parent table of `path` and the last key.
fn parent<'a>(t: &'a mut Table, path: &[String]) -> Option<(&'a mut Table, String)> {
    let (last, up) = path.split_last()?;
    let mut t = t;
    for k in up {
        t = t.get_mut(k)?.as_table_mut()?;
    }
    Some((t, last.clone()))
}

fn apply(t: &mut Table, m: &Mutation) {
    let mut all = Vec::new();
    paths(t, &mut Vec::new(), &mut all);
    if all.is_empty() {
        return;
    }
    let at = match m {
        Mutation::Set { at, .. }
        | Mutation::Scale { at, .. }
        | Mutation::Delete { at }
        | Mutation::ToArray { at }
        | Mutation::ToTable { at } => at.index(all.len()),
    };
    let Some((table, key)) = parent(t, &all[at]) else {
        return;
    };
    match m {
        Mutation::Set { new, .. } => {
            table.insert(key, new.value());
        }
        Mutation::Scale { by, .. } => {
            let v = table.get_mut(&key).unwrap();
            let x = match v {
                Value::Float(x) => *x,
                Value::Integer(i) => *i as f64,
                _ => return,
            };
            *v = Value::Float(x * by);
        }
        Mutation::Delete { .. } => {
            table.remove(&key);
        }
        Mutation::ToArray { .. } => {
            let v = table.remove(&key).unwrap();
            let a = match v {
                Value::Table(sub) => sub.into_iter().map(|(_, v)| v).collect(),
                other => vec![other],
            };
            table.insert(key, Value::Array(a));
        }
        Mutation::ToTable { .. } => {
            let v = table.remove(&key).unwrap();
            let mut sub = Table::new();
            sub.insert("x".into(), v);
            table.insert(key, Value::Table(sub));
        }
    }
}

fn write(t: &Table, form: &Form) -> String {
    match form {
        Form::Toml => toml::to_string(t).expect("a table serialises"),
        Form::TomlDuplicateLine(i) => {
            let text = toml::to_string(t).expect("a table serialises");
            let mut lines: Vec<&str> = text.lines().collect();
            if !lines.is_empty() {
                let k = i.index(lines.len());
                lines.insert(k, lines[k]);
            }
            lines.join("\n") + "\n"
        }
        Form::Json => serde_json::to_string_pretty(&serde_json::to_value(t).expect("json"))
            .expect("json text"),
    }
}

/// A clear refusal: names something, says more than a status, and no internal type names
/// or NaN from a computation.
fn clear(msg: &str) -> bool {
    msg.len() >= 12 && !msg.contains("panic") && !msg.contains("Spec`") && !msg.contains("struct ")
}

/// Build, set every input to its initial value, step three times at 0.1 ms; `Err` is a
/// refused step's message; `Ok(names)` lists the outputs read as NaN or infinite.
fn build_and_step(text: &str) -> Result<Result<Vec<&'static str>, String>, String> {
    let mut c = Component::from_text(text).map_err(|e| e.to_string())?;
    Ok((|| {
        for v in variables::all() {
            if v.is_input(c.causality()) {
                let x = c.get_real(v.vr).map_err(|e| e.to_string())?;
                c.set_real(v.vr, x).map_err(|e| e.to_string())?;
            }
        }
        let h = 1e-4;
        for k in 0..3 {
            c.do_step(k as f64 * h, h).map_err(|e| e.to_string())?;
        }
        let mut bad = Vec::new();
        for v in variables::all() {
            if let Ok(x) = c.get_real(v.vr) {
                if !x.is_finite() {
                    bad.push(v.name);
                }
            }
        }
        Ok(bad)
    })())
}

#[test]
fn mutated_scenes_are_refused_by_field_or_build_and_step_finitely() {
    let strategy = (
        any::<Index>(),
        proptest::collection::vec(mutation(), 1..4),
        form(),
    );
    props_util::check(
        "scenes",
        file!(),
        512,
        strategy,
        |(which, mutations, form)| {
            let all = scenes();
            let (name, base) = &all[which.index(all.len())];
            let mut t = base.clone();
            for m in &mutations {
                apply(&mut t, m);
            }
            let text = write(&t, &form);
            let ctx = format!("scene {name}, mutated:\n{text}");

            let problems = schema::check(&text);
            let loaded = schema::load(&text, &[]);
            // `--check` and `run` agree.
            prop_assert_eq!(
                problems.is_empty(),
                loaded.is_ok(),
                "check: {:?}\nload: {:?}\n{}",
                problems,
                loaded.as_ref().err(),
                ctx
            );
            if problems.is_empty() {
                // The scene's own duration given on the command line (`run --duration`) does
                // not change the verdict, nor the scene.
                let own = loaded.as_ref().unwrap().run.duration_s;
                let with = schema::load(&text, &[("run.duration_s", own)]);
                prop_assert!(
                    with.is_ok(),
                    "refused with --duration {}: {:?}\n{}",
                    own,
                    with.err(),
                    ctx
                );
                // It builds (as `raceway_create` builds it) and steps finitely.
                match build_and_step(&text) {
                    Err(e) => {
                        prop_assert!(false, "passes --check but does not build: {}\n{}", e, ctx)
                    }
                    Ok(Ok(bad)) => {
                        prop_assert!(bad.is_empty(), "non-finite outputs {:?}\n{}", bad, ctx)
                    }
                    Ok(Err(e)) => prop_assert!(
                        clear(&e) && !e.contains("NaN") && !e.contains("= inf"),
                        "unclear step refusal `{}`\n{}",
                        e,
                        ctx
                    ),
                }
            } else {
                // A command-line override hides no problem of the file.
                prop_assert!(
                    schema::load(&text, &[("run.duration_s", 1e-3)]).is_err(),
                    "{}",
                    ctx
                );
                // `raceway_create` (and the FMU's `scene` parameter) refuse it too.
                prop_assert!(
                    Component::from_text(&text).is_err(),
                    "refused by --check, built by Component::from_text: {}\n{}",
                    problems[0],
                    ctx
                );
                for p in &problems {
                    prop_assert!(
                        !p.path.is_empty() || p.line_col.is_some(),
                        "problem names no field and no place: {}\n{}",
                        p,
                        ctx
                    );
                    prop_assert!(clear(&p.message), "unclear problem `{}`\n{}", p, ctx);
                }
            }
            Ok(())
        },
    );
}

/// The shrunk cases the property found, kept as plain tests.
#[test]
fn found_a_huge_contact_damping_is_refused_by_name_everywhere() {
    let text = include_str!("../examples/scenes/6205-linear.toml").replace(
        "contact_damping = 200.0",
        "contact_damping = 1.7976931348623157e308",
    );
    let problems = schema::check(&text);
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert_eq!(problems[0].path, "model.contact_damping");
    assert!(problems[0].line_col.is_some());
    let Err(e) = Component::from_text(&text) else {
        panic!("built with contact_damping = f64::MAX");
    };
    let e = e.to_string();
    assert!(e.contains("model.contact_damping"), "{e}");
    // The upper end itself is accepted.
    let text = text.replace("1.7976931348623157e308", "1e6");
    assert!(schema::check(&text).is_empty());
}

#[test]
fn found_a_serde_refusal_of_a_json_scene_has_its_line_and_column() {
    let json = "{\n  \"bearing\": \"6012\",\n  \"model\": {\n    \"level\": \"skidding\",\n    \"skidding\": { \"traction\": { \"mu_max\": 0.05 } }\n  }\n}\n";
    let problems = schema::check(json);
    assert!(!problems.is_empty());
    for p in &problems {
        assert!(!p.path.is_empty() || p.line_col.is_some(), "{p}");
    }
}
