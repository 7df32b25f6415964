//! `raceway scene --check` and `--explain`, and the schema table behind them.

use raceway::component::schema::{self, Kind};
use raceway::component::Scene;
use std::collections::BTreeSet;
use std::path::Path;
use std::process::{Command, Output};

fn raceway(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raceway"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn write_tmp(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("raceway-scene-cmd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// 1-based line and column of the first occurrence of `needle` in `text`.
fn place(text: &str, needle: &str) -> String {
    let off = text.find(needle).expect("needle in text");
    let before = &text[..off];
    let line = before.matches('\n').count() + 1;
    let col = off - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    format!("{line}:{col}")
}

#[test]
fn three_independent_problems_are_all_reported_with_their_lines() {
    let text = "# three problems\ntitle = \"bad\"\nbearing = \"6205\"\n\n[model]\nlevl = \"ring\"\ncausality = \"load\"\n\n[solver]\nrtol = 0.5\n\n[effects]\ndefects = [{ race = \"outter\", width_mm = 1.0, depth_um = 10.0 }]\n";
    let p = write_tmp("three.toml", text);
    let out = raceway(&["scene", "--check", p.to_str().unwrap()]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    let expect = [
        (place(text, "levl"), "model.levl", "did you mean `level`"),
        (place(text, "0.5"), "solver.rtol", "[1e-14, 0.1]"),
        (
            place(text, "\"outter\""),
            "effects.defects[0].race",
            "did you mean \"outer\"",
        ),
    ];
    for (at, path, hint) in &expect {
        let line = err
            .lines()
            .find(|l| l.contains(&format!("`{path}`")))
            .unwrap_or_else(|| panic!("no line for {path} in:\n{err}"));
        assert!(
            line.contains(&format!(":{at}: ")),
            "{path} not at {at}: {line}"
        );
        assert!(line.contains(hint), "{line}");
    }
    assert!(err.contains("3 problem(s)"), "{err}");
    // The lines found are the ones expected: 6, 10 and 13.
    assert_eq!(
        expect.iter().map(|e| e.0.as_str()).collect::<Vec<_>>(),
        ["6:1", "10:8", "13:21"]
    );
}

#[test]
fn missing_field_wrong_type_and_unknown_names_are_reported() {
    let text = "bearing = { preset = \"6205\", ball_count = 9.5, materials = { ball = \"si3n5\" } }\n[inputs]\ninitial = { \"shaft.omgea\" = 10.0 }\n[effects]\nwaviness = [{ race = \"inner\", amplitude_um = 0.2 }]\nlubrication = { lubricant = \"study3\" }\n";
    let problems = schema::check(text);
    let find = |path: &str| {
        problems
            .iter()
            .find(|p| p.path == path)
            .unwrap_or_else(|| panic!("no problem at {path}: {problems:#?}"))
    };
    assert!(find("bearing.ball_count")
        .message
        .contains("expected an integer"));
    assert!(find("bearing.materials.ball").message.contains("si3n4"));
    assert!(find("inputs.initial.shaft.omgea")
        .message
        .contains("did you mean `speed_rpm`?"));
    let missing = find("effects.waviness[0].order");
    assert!(missing.message.contains("missing required field `order`"));
    assert_eq!(missing.line_col.map(|l| l.0), Some(5));
    assert!(find("effects.lubrication.lubricant")
        .message
        .contains("study2"));
    assert_eq!(problems.len(), 5, "{problems:#?}");
}

#[test]
fn cross_field_problems_come_from_the_library_and_are_located() {
    // Clean structure, but effects on a level that ignores them.
    let text = "bearing = \"6205\"\n[model]\nlevel = \"quasi_static\"\n\n[effects]\ndefects = [{ race = \"outer\", width_mm = 1.0, depth_um = 10.0 }]\n";
    let problems = schema::check(text);
    assert_eq!(problems.len(), 1, "{problems:#?}");
    assert!(problems[0].message.contains("only with level = \"ring\""));
    assert_eq!(problems[0].line_col, Some((5, 2)), "{problems:#?}");
    // A defect wider than the ball (7.94 mm): only the bearing knows.
    let text = "bearing = \"6205\"\n[model]\nlevel = \"ring\"\n[effects]\ndefects = [{ race = \"outer\", width_mm = 9.0, depth_um = 10.0 }]\n";
    let problems = schema::check(text);
    assert_eq!(problems.len(), 1, "{problems:#?}");
    assert_eq!(problems[0].path, "effects.defects[0].width_mm");
    assert_eq!(problems[0].line_col.map(|l| l.0), Some(5));
    // Geometry that cannot be built.
    let text = "bearing = { preset = \"6205\", ball_count = 20 }\n";
    let problems = schema::check(text);
    assert_eq!(problems.len(), 1, "{problems:#?}");
    assert!(problems[0].message.contains("bearing.ball_count"));
    assert_eq!(problems[0].line_col, Some((1, 30)));
}

#[test]
fn json_scenes_are_checked_by_path() {
    let text = r#"{"bearing": "6205", "model": {"level": "rng", "ring_dof": 3}, "run": {"duration": 1.0}}"#;
    let problems = schema::check(text);
    let paths: BTreeSet<&str> = problems.iter().map(|p| p.path.as_str()).collect();
    assert_eq!(
        paths,
        BTreeSet::from(["model.level", "model.ring_dof", "run.duration"]),
        "{problems:#?}"
    );
    assert!(schema::check(r#"{"bearing": "6205"}"#).is_empty());
}

#[test]
fn every_example_scene_checks_clean() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "toml") {
            let out = raceway(&["scene", "--check", p.to_str().unwrap()]);
            let stdout = String::from_utf8_lossy(&out.stdout);
            assert!(
                out.status.success() && stdout.starts_with("ok: "),
                "{}: {}{}",
                p.display(),
                stdout,
                String::from_utf8_lossy(&out.stderr)
            );
            // Each file starts with a comment saying what it shows.
            let text = std::fs::read_to_string(&p).unwrap();
            assert!(text.starts_with("# "), "{}", p.display());
            n += 1;
        }
    }
    assert!(n >= 12, "{n} scenes");
}

/// The scene catalogue in docs/scenes.md and the README's table name every scene file, and
/// no file that is not there.
#[test]
fn scene_catalogues_list_every_scene() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<String> = std::fs::read_dir(root.join("examples/scenes"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    files.sort();
    for doc in ["docs/scenes.md", "README.md"] {
        let text = std::fs::read_to_string(root.join(doc)).unwrap();
        let mut listed: Vec<String> = text
            .lines()
            .filter_map(|l| l.strip_prefix("| `"))
            // Every name in the row's first cell (a row may list several scenes).
            .flat_map(|l| {
                let cell = l.split(" |").next().unwrap_or("");
                cell.split('`')
                    .step_by(2)
                    .filter(|n| n.ends_with(".toml") && !n.contains('/'))
                    .map(String::from)
                    .collect::<Vec<_>>()
            })
            .collect();
        listed.sort();
        listed.dedup();
        assert_eq!(listed, files, "{doc}: scene table out of date");
    }
}

#[test]
fn explain_covers_exactly_the_schema_fields() {
    let schema: BTreeSet<String> = schema::schema_paths().into_keys().collect();
    let out = raceway(&["scene", "--explain", "--json"]);
    assert!(out.status.success());
    let rows: Vec<serde_json::Value> = serde_json::from_slice(&out.stdout).unwrap();
    let explained: BTreeSet<String> = rows
        .iter()
        .map(|r| r["path"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(explained.len(), rows.len(), "duplicate paths");
    assert_eq!(explained, schema);
    // Bearing-table fields and effect list items are among them.
    for p in [
        "bearing.clearance_um",
        "bearing.cage.guidance",
        "bearing.materials.<body>.poisson_ratio",
        "effects.defects[].width_mm",
        "effects.waviness[].order",
        "effects.lubrication.viscosity_pa_s",
        "run.speed_ramp_rpm_per_s",
    ] {
        assert!(explained.contains(p), "{p}");
    }
}

#[test]
fn explain_json_entries_have_unit_default_and_range() {
    let out = raceway(&["scene", "--explain", "--json"]);
    let rows: Vec<serde_json::Value> = serde_json::from_slice(&out.stdout).unwrap();
    for r in &rows {
        for k in ["unit", "default", "range", "type", "description"] {
            let v = r[k].as_str().unwrap_or("");
            assert!(!v.is_empty(), "{k} of {r}");
        }
    }
    let get = |path: &str| rows.iter().find(|r| r["path"] == path).unwrap().clone();
    // Defaults are serde's own.
    assert_eq!(get("solver.rtol")["default"], "1e-6");
    assert_eq!(get("model.level")["default"], "\"quasi_static\"");
    assert_eq!(get("run.duration_s")["default"], "0.2");
    assert_eq!(get("effects.defects[].depth_um")["default"], "required");
    assert_eq!(get("effects.defects[].angle_deg")["default"], "0.0");
    assert_eq!(get("bearing.materials.cage")["default"], "\"phenolic\"");
    assert_eq!(get("effects.defects[].width_mm")["unit"], "mm");
    assert_eq!(get("solver.rtol")["range"], "[1e-14, 0.1]");
    // The text form lists the same paths.
    let text = raceway(&["scene", "--explain"]);
    let text = String::from_utf8_lossy(&text.stdout);
    for r in &rows {
        assert!(text.contains(r["path"].as_str().unwrap()));
    }
}

/// Set the field at a normalised schema path in a scene value.
fn set(v: &mut toml::Value, path: &str, x: toml::Value) {
    let mut cur = v;
    let segs: Vec<String> = if let Some(rest) = path.strip_prefix("inputs.initial.") {
        assert_eq!(rest, "<variable>");
        vec!["inputs".into(), "initial".into(), "shaft.y".into()]
    } else {
        path.replace("<body>", "ball")
            .split('.')
            .map(str::to_string)
            .collect()
    };
    let n = segs.len();
    for (i, s) in segs.iter().enumerate() {
        let (key, item) = match s.strip_suffix("[]") {
            Some(k) => (k, true),
            None => (s.as_str(), false),
        };
        let t = cur.as_table_mut().expect("a table on the path");
        if i == n - 1 {
            t.insert(key.into(), x);
            return;
        }
        cur = t.get_mut(key).expect("path present");
        if item {
            cur = cur.as_array_mut().unwrap().get_mut(0).unwrap();
        }
    }
}

/// Does the scene value hold the field at a normalised path?
fn has(v: &toml::Value, path: &str) -> bool {
    get(v, path).is_some()
}

/// The field at a normalised path.
fn get<'a>(v: &'a toml::Value, path: &str) -> Option<&'a toml::Value> {
    let mut cur = v;
    let path = path.replace("<body>", "ball");
    let segs: Vec<&str> = if path.starts_with("inputs.initial.") {
        vec!["inputs", "initial", "shaft.y"]
    } else {
        path.split('.').collect()
    };
    for s in segs {
        let (key, item) = match s.strip_suffix("[]") {
            Some(k) => (k, true),
            None => (s, false),
        };
        cur = cur.get(key)?;
        if item {
            cur = cur.get(0)?;
        }
    }
    Some(cur)
}

fn outcome(v: &toml::Value) -> Result<(), String> {
    let text = toml::to_string(v).map_err(|e| e.to_string())?;
    let scene = Scene::from_text(&text).map_err(|e| e.to_string())?;
    raceway::Component::new(scene)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

#[test]
fn full_schema_scenes_are_valid_components() {
    for s in schema::full_scenes() {
        let v = toml::Value::try_from(&s).unwrap();
        outcome(&v).unwrap();
        assert!(schema::check(&toml::to_string(&v).unwrap()).is_empty());
    }
}

/// The table's ranges and spellings are the library's: a value just outside a documented
/// bound is refused by `Component::new` naming the field; every documented spelling is
/// accepted and a wrong one refused.
#[test]
fn table_ranges_and_spellings_agree_with_the_library() {
    let fulls: Vec<toml::Value> = schema::full_scenes()
        .iter()
        .map(|s| toml::Value::try_from(s).unwrap())
        .collect();
    let mut disagreements = Vec::new();
    for f in schema::TABLE {
        // A full scene that holds the field (the traction fields belong to one law each);
        // the skidding options are validated by the skidding level, which takes no effects.
        let mut base = fulls
            .iter()
            .find(|v| has(v, f.path))
            .unwrap_or_else(|| panic!("no full scene holds {}", f.path))
            .clone();
        if f.path.starts_with("model.skidding.") {
            set(
                &mut base,
                "model.level",
                toml::Value::String("skidding".into()),
            );
            base.as_table_mut().unwrap().remove("effects");
        }
        let concrete = f
            .path
            .replace("[]", "[0]")
            .replace("<body>", "ball")
            .replace("<variable>", "shaft.y");
        match f.kind {
            Kind::Float | Kind::Int => {
                let mut outside = Vec::new();
                // Just outside: one unit for integers, a relative 1e-9 for numbers.
                let step = |x: f64| {
                    if f.kind == Kind::Int {
                        1.0
                    } else {
                        1e-9 * x.abs().max(1.0)
                    }
                };
                if let Some((lo, inc)) = f.bounds.lo {
                    outside.push(if inc { lo - step(lo) } else { lo });
                }
                if let Some((hi, inc)) = f.bounds.hi {
                    outside.push(if inc { hi + step(hi) } else { hi });
                }
                for x in outside {
                    let val = if f.kind == Kind::Int {
                        toml::Value::Integer(x as i64)
                    } else {
                        toml::Value::Float(x)
                    };
                    let mut v = base.clone();
                    set(&mut v, f.path, val);
                    match outcome(&v) {
                        Ok(()) => disagreements.push(format!("{} = {x} accepted", f.path)),
                        Err(e) if f.kind == Kind::Float && !e.contains(&concrete) => {
                            disagreements.push(format!("{} = {x}: {e}", f.path))
                        }
                        Err(_) => {}
                    }
                }
                // A value inside is accepted where the range is the whole story.
                if f.note.is_empty() {
                    if let (Some((lo, _)), Some((hi, _))) = (f.bounds.lo, f.bounds.hi) {
                        let mid = 0.5 * (lo + hi);
                        let mut v = base.clone();
                        let val = if f.kind == Kind::Int {
                            toml::Value::Integer(mid.round() as i64)
                        } else {
                            toml::Value::Float(mid)
                        };
                        set(&mut v, f.path, val);
                        if let Err(e) = outcome(&v) {
                            disagreements.push(format!("{} = {mid} refused: {e}", f.path));
                        }
                    }
                }
            }
            Kind::Enum(spellings) => {
                for s in spellings {
                    // A tagged enum's other fields follow its tag: start from the full
                    // scene that already has this spelling when there is one.
                    let mut v = fulls
                        .iter()
                        .find(|v| get(v, f.path).and_then(|x| x.as_str()) == Some(*s))
                        .unwrap_or(&base)
                        .clone();
                    set(&mut v, f.path, toml::Value::String((*s).into()));
                    let text = toml::to_string(&v).unwrap();
                    let parsed =
                        Scene::from_text(&text).and_then(|sc| sc.bearing.spec().map(|_| ()));
                    if let Err(e) = parsed {
                        disagreements.push(format!("{} = \"{s}\" refused: {e}", f.path));
                    }
                }
                let mut v = base.clone();
                set(&mut v, f.path, toml::Value::String("bogus".into()));
                let text = toml::to_string(&v).unwrap();
                if Scene::from_text(&text)
                    .and_then(|sc| sc.bearing.spec().map(|_| ()))
                    .is_ok()
                {
                    disagreements.push(format!("{} = \"bogus\" accepted", f.path));
                }
            }
            Kind::IntChoice(choices) => {
                for x in choices.iter().copied().chain([choices[0] + 1]) {
                    let mut v = base.clone();
                    set(&mut v, f.path, toml::Value::Integer(x));
                    let ok = outcome(&v).is_ok();
                    if ok != choices.contains(&x) {
                        disagreements.push(format!("{} = {x}: accepted {ok}", f.path));
                    }
                }
            }
            _ => {}
        }
    }
    assert!(disagreements.is_empty(), "{disagreements:#?}");
}

#[test]
fn inline_material_fields_are_required_and_located() {
    let text = "bearing = { preset = \"6205\", materials = { ball = { name = \"x\", youngs_modulus = 3e11, poisson_ratio = 0.26 } } }\n";
    let problems = schema::check(text);
    let missing: BTreeSet<&str> = problems.iter().map(|p| p.path.as_str()).collect();
    assert_eq!(
        missing,
        BTreeSet::from([
            "bearing.materials.ball.density",
            "bearing.materials.ball.thermal_expansion",
            "bearing.materials.ball.conductivity",
            "bearing.materials.ball.heat_capacity",
        ]),
        "{problems:#?}"
    );
    // At the inline table that lacks them.
    let at = place(text, "{ name");
    assert!(
        problems
            .iter()
            .all(|p| p.line_col.map(|(l, c)| format!("{l}:{c}")) == Some(at.clone())),
        "{problems:#?}"
    );
}

#[test]
fn check_json_lists_the_problems_and_still_fails() {
    let text = "bearing = \"6250\"\n[run]\nstep_s = -1.0\n";
    let p = write_tmp("two.toml", text);
    let out = raceway(&["scene", "--check", p.to_str().unwrap(), "--json"]);
    assert!(!out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["ok"], false);
    let problems = v["problems"].as_array().unwrap();
    assert_eq!(problems.len(), 2, "{v}");
    assert_eq!(problems[0]["path"], "bearing");
    assert_eq!(problems[0]["line_col"], serde_json::json!([1, 11]));
    assert!(problems[0]["message"].as_str().unwrap().contains("6205"));
    assert_eq!(problems[1]["path"], "run.step_s");
    assert_eq!(problems[1]["line_col"], serde_json::json!([3, 10]));
}

#[test]
fn a_field_of_another_traction_law_is_located_by_the_parser() {
    let text = "bearing = \"6012\"\n[model]\nlevel = \"skidding\"\n[model.skidding]\ntraction = { law = \"fitted\", mu_max = 0.1 }\n";
    let problems = schema::check(text);
    assert_eq!(problems.len(), 1, "{problems:#?}");
    assert_eq!(problems[0].line_col.map(|l| l.0), Some(5), "{problems:#?}");
    assert!(problems[0].message.contains("mu_max"), "{problems:#?}");
}

/// A scene names a catalogue bearing the way it names a preset, alone or with
/// overrides (a maker's ball count, say).
#[test]
fn a_scene_accepts_a_designation() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/209-qs-load.toml"
    ))
    .unwrap();
    let s = raceway::component::Scene::from_text(
        &text.replace("bearing = \"209\"", "bearing = \"6206\""),
    )
    .unwrap();
    let b = s.validate().unwrap();
    assert_eq!((b.name.as_str(), b.z), ("6206", 8));
    let s = raceway::component::Scene::from_text(&text.replace(
        "bearing = \"209\"",
        "bearing = { preset = \"6206\", ball_count = 9 }",
    ))
    .unwrap();
    assert_eq!(s.validate().unwrap().z, 9);
}

/// A preload inside the declared clearance range but past what any input allows is refused
/// at the scene, naming `bearing.clearance_um` with a bound that can be met (issue #38, item
/// 8: the 6205 at -400 µm used to refuse every `shaft.y`, even 0, with the empty range
/// "[8.4663e-6, -8.4663e-6] m" blaming another field).
#[test]
fn a_preload_no_input_could_take_is_refused_at_the_scene() {
    let scene = |um: f64| {
        raceway::component::Scene::from_text(&format!(
            "[bearing]\npreset = \"6205\"\nclearance_um = {um}\n"
        ))
        .unwrap()
    };
    let e = scene(-400.0).validate().unwrap_err().to_string();
    assert!(
        e.contains("bearing.clearance_um") && e.contains("at least -3"),
        "{e}"
    );
    // The bound it names is met.
    let bound: f64 = e
        .split("at least ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|x| x.parse().ok())
        .expect("a number");
    assert!(bound < -300.0 && bound > -400.0, "{bound}");
    scene(bound + 1.0).validate().expect("inside the bound");
}

/// The scene's `solver.method` spellings are the method registry's (plus `auto`), each
/// spelling reads back as the variant that names that registry row, and `auto` resolves by
/// the level's stiffness.
#[test]
fn method_spellings_are_the_registrys() {
    use raceway::component::scene::Method;
    use raceway::solver::methods::{METHODS, METHOD_NAMES};
    assert_eq!(METHOD_NAMES.len(), METHODS.len() + 1);
    for name in METHOD_NAMES {
        let m: Method = serde_json::from_str(&format!("\"{name}\"")).unwrap();
        assert_eq!(serde_json::to_string(&m).unwrap(), format!("\"{name}\""));
        match m.entry() {
            None => assert_eq!(name, "auto"),
            Some(e) => assert_eq!(e.name, name),
        }
    }
    assert_eq!(Method::Auto.resolve(true).name, "rosenbrock");
    assert_eq!(Method::Auto.resolve(false).name, "dopri5");
    assert!(!Method::Ros34pw2.resolve(false).dense_output);
}

/// A JSON `null` key is an absent key on every face: `--check` refused
/// `"roughness_um": null` while `Component::from_text` (the C ABI's and the FMU's path) built
/// the scene with the field's default (found by the property tests, seed 20261130), and a
/// `Scene` serialised to JSON writes `null` for an unset optional field. Both now read the
/// scene without the key; a null where a value is required (inside a list) is refused by
/// both.
#[test]
fn a_json_null_key_is_absent_on_every_face() {
    let text = r#"{"bearing": "6012", "model": {"level": "ring"}, "effects": {"lubrication":
        {"film": "ehl", "lubricant": "study2", "roughness_um": null}}}"#;
    let without = text.replace(r#", "roughness_um": null"#, "");
    let p = write_tmp("null.json", text);
    let out = raceway(&["scene", "--check", p.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (mut a, mut b) = (
        raceway::component::Component::from_text(text).unwrap(),
        raceway::component::Component::from_text(&without).unwrap(),
    );
    for i in 0..5 {
        a.do_step(i as f64 * 1e-4, 1e-4).unwrap();
        b.do_step(i as f64 * 1e-4, 1e-4).unwrap();
    }
    assert_eq!(a.serialize_state(), b.serialize_state());
    // A null inside a list is no key: refused by both faces.
    let listed =
        r#"{"bearing": "6205", "model": {"level": "ring"}, "effects": {"defects": [null]}}"#;
    assert!(raceway::component::Component::from_text(listed).is_err());
    let p = write_tmp("null-list.json", listed);
    assert!(!raceway(&["scene", "--check", p.to_str().unwrap()])
        .status
        .success());
}

/// The speed is given in rpm (`[inputs] speed_rpm`); the old spelling in rad/s,
/// `inputs.initial."shaft.omega"`, is refused at its line:column with the new spelling and
/// the value it holds in rpm, by `scene --check` and by `run`.
#[test]
fn the_old_speed_spelling_is_refused_naming_the_new_one() {
    let text = "bearing = \"6205\"\n[inputs]\ninitial = { \"shaft.y\" = -10e-6, \"shaft.omega\" = 183.259571 }\n";
    let problems = raceway::component::schema::check(text);
    assert_eq!(problems.len(), 1, "{problems:#?}");
    let p = &problems[0];
    assert_eq!(p.path, "inputs.initial.shaft.omega");
    let at = place(text, "\"shaft.omega\"");
    let (l, c) = p.line_col.unwrap();
    assert_eq!(format!("{l}:{c}"), at, "{p}");
    assert!(p.message.contains("did you mean `speed_rpm`?"), "{p}");
    assert!(p.message.contains("`speed_rpm = 1750`"), "{p}");
    let f = write_tmp("old-speed.toml", text);
    for args in [vec!["scene", "--check"], vec!["run", "-q"]] {
        let out = raceway(&[args.as_slice(), &[f.to_str().unwrap()]].concat());
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(&format!(":{at}:")) && err.contains("speed_rpm = 1750"),
            "{err}"
        );
    }
    // The new spelling: the same component input, in rad/s inside.
    let new =
        "bearing = \"6205\"\n[inputs]\nspeed_rpm = 1750\ninitial = { \"shaft.y\" = -10e-6 }\n";
    assert!(raceway::component::schema::check(new).is_empty());
    let mut c = raceway::Component::from_text(new).unwrap();
    let w = raceway::component::variables::by_name("shaft.omega")
        .unwrap()
        .vr;
    assert!((c.get_real(w).unwrap() - 1750.0 * std::f64::consts::PI / 30.0).abs() < 1e-12);
}
