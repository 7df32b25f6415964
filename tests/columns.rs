//! One label style (docs/columns.md): every header and key a person reads is `name [unit]`
//! (text, flags and structure: the bare name), and every one is documented.
//!
//! 1. docs/columns.md equals what `raceway::summary::columns::columns_page` generates from
//!    the variable table and the summary's key table;
//! 2. runs (series.csv header, summary.json keys) of the default scene, a cylindrical
//!    roller bearing on the ring level (`lamina_life`), a set (`set.rows`) and a set with
//!    the thermal effect (`thermal.rows`), a sweep (sweep.csv header), `raceway
//!    quasi-static --json` of a ball bearing with every design-check option, a cylindrical
//!    and a tapered roller bearing and a set, `raceway shaft --json` (two shafts), and `raceway bearings --json` (the list, a
//!    ball and a roller bearing) give only labels that match the pattern, a number always
//!    with its unit, each listed in docs/columns.md.
//!
//! `RACEWAY_BLESS=1 cargo test --test columns` rewrites docs/columns.md.

use serde_json::Value;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("raceway-columns-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn raceway(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_raceway"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "raceway {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn the_columns_page_is_generated_from_the_tables() {
    let generated = raceway::summary::columns::columns_page();
    let path = root().join("docs/columns.md");
    let current = std::fs::read_to_string(&path).unwrap_or_default();
    if current == generated {
        return;
    }
    if std::env::var("RACEWAY_BLESS").is_ok_and(|v| v == "1") {
        std::fs::write(&path, generated).unwrap();
        return;
    }
    let line = current
        .lines()
        .zip(generated.lines())
        .position(|(a, b)| a != b)
        .unwrap_or_else(|| current.lines().count().min(generated.lines().count()));
    panic!(
        "docs/columns.md is stale (first difference at line {}): regenerate with \
         `RACEWAY_BLESS=1 cargo test --test columns`",
        line + 1
    );
}

/// The labels docs/columns.md lists (the first cell of each table row), by section.
fn documented() -> Vec<(String, BTreeSet<String>)> {
    let text = std::fs::read_to_string(root().join("docs/columns.md")).unwrap();
    let mut out: Vec<(String, BTreeSet<String>)> = Vec::new();
    for line in text.lines() {
        if let Some(h) = line.strip_prefix("## ") {
            out.push((h.to_string(), BTreeSet::new()));
        } else if let (Some(cell), Some(last)) = (line.strip_prefix("| `"), out.last_mut()) {
            let first = cell.split(" | ").next().unwrap();
            for l in first.split(", ") {
                last.1.insert(l.trim_matches('`').to_string());
            }
        }
    }
    out
}

fn section(docs: &[(String, BTreeSet<String>)], start: &str) -> BTreeSet<String> {
    docs.iter()
        .find(|(h, _)| h.starts_with(start))
        .unwrap_or_else(|| panic!("docs/columns.md has no section `{start}`"))
        .1
        .clone()
}

/// `name [unit]` or a bare name: segments of letters, digits and `_` joined by `.` (a
/// spectrum line's label may start with a digit, `1xBPFO`), one space, a unit without
/// spaces or brackets.
fn well_formed(label: &str) -> bool {
    let (name, unit) = raceway::units::split_label(label);
    let name_ok = !name.is_empty()
        && name
            .split('.')
            .all(|s| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'));
    let unit_ok = unit.is_none_or(|u| !u.contains([' ', '[', ']']));
    name_ok && unit_ok && !(unit.is_none() && label.contains('['))
}

fn is_number(v: &Value) -> bool {
    v.is_number()
        || v.as_array()
            .is_some_and(|a| !a.is_empty() && a.iter().all(Value::is_number))
}

/// Every key path of a JSON document, `a.b[].c [u]` (array tables as `[]`), with whether
/// its value is a number; a list of documents (a top-level array): each one's.
fn paths(v: &Value, prefix: &str, out: &mut Vec<(String, String, bool)>) {
    if let (Value::Array(a), true) = (v, prefix.is_empty()) {
        for e in a {
            paths(e, prefix, out);
        }
    }
    if let Value::Object(m) = v {
        for (k, x) in m {
            let p = format!("{prefix}{k}");
            out.push((p.clone(), k.clone(), is_number(x)));
            match x {
                Value::Object(_) => paths(x, &format!("{p}."), out),
                Value::Array(a) => {
                    for e in a.iter().filter(|e| e.is_object()) {
                        paths(e, &format!("{p}[]."), out);
                    }
                }
                _ => {}
            }
        }
    }
}

fn check_json(doc: &Value, listed: &BTreeSet<String>, what: &str) -> usize {
    let mut ps = Vec::new();
    paths(doc, "", &mut ps);
    let mut bad = Vec::new();
    for (p, key, number) in &ps {
        if !well_formed(key) {
            bad.push(format!("{p}: not `name [unit]`"));
        }
        if *number && raceway::units::split_label(key).1.is_none() {
            bad.push(format!("{p}: a number without its unit"));
        }
        if !listed.contains(p) {
            bad.push(format!("{p}: not in docs/columns.md"));
        }
    }
    assert!(bad.is_empty(), "{what}:\n{}", bad.join("\n"));
    ps.len()
}

/// A sweep column as the documented key it flattens: `frequencies.fs.expected [Hz]` is
/// `frequencies[].expected [Hz]`, `peak_force.x [N]` is `peak_force [N]`.
fn sweep_column_documented(col: &str, listed: &BTreeSet<String>) -> bool {
    let (name, unit) = raceway::units::split_label(col);
    let segs: Vec<&str> = name.split('.').collect();
    listed.iter().any(|d| {
        let (dn, du) = raceway::units::split_label(d);
        if du != unit {
            return false;
        }
        let mut want: Vec<&str> = Vec::new();
        for s in dn.split('.') {
            match s.strip_suffix("[]") {
                Some(a) => {
                    want.push(a);
                    want.push("*");
                }
                None => want.push(s),
            }
        }
        let same = |w: &[&str], g: &[&str]| {
            w.len() == g.len() && w.iter().zip(g).all(|(a, b)| *a == "*" || a == b)
        };
        same(&want, &segs)
            || (segs.len() == want.len() + 1
                && same(&want, &segs[..want.len()])
                && segs[want.len()]
                    .chars()
                    .all(|c| c.is_ascii_digit() || "xyz".contains(c)))
    })
}

#[test]
fn every_header_and_key_is_labelled_and_documented() {
    let docs = documented();
    let d = tmp("all");

    // A run: series.csv and summary.json.
    let run = d.join("run");
    raceway(&[
        "run",
        "-q",
        "--duration",
        "0.002",
        "--out",
        run.to_str().unwrap(),
    ]);
    let series = std::fs::read_to_string(run.join("series.csv")).unwrap();
    let header: Vec<&str> = series.lines().next().unwrap().split(',').collect();
    let listed = section(&docs, "series.csv");
    for h in &header {
        assert!(well_formed(h) && h.ends_with(']'), "series.csv `{h}`");
        assert!(
            listed.contains(*h),
            "series.csv `{h}` not in docs/columns.md"
        );
    }
    assert!(header.contains(&"life.L10 [Mrev]"), "{header:?}");
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(run.join("summary.json")).unwrap()).unwrap();
    let run_keys = section(&docs, "summary.json");
    let n = check_json(&summary, &run_keys, "summary.json");
    assert!(n > 40, "{n} keys");
    assert!(summary["rating"]["e [1]"].is_number(), "{summary}");
    assert!(summary["rating"]["life_inner [Mrev]"].is_number());

    // A sweep of two points: its summary columns flatten documented keys.
    let sweep = d.join("sweep.toml");
    std::fs::write(
        &sweep,
        format!(
            "scene = \"{}\"\n[[axis]]\nkey = \"run.duration_s\"\nvalues = [0.002]\n\
             [[axis]]\nkey = \"inputs.speed_rpm\"\nvalues = [1000.0, 2000.0]\n",
            root().join("examples/scenes/default.toml").display()
        ),
    )
    .unwrap();
    let out = d.join("sweep");
    raceway(&[
        "sweep",
        sweep.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let cols: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let axes = ["index", "run.duration_s", "inputs.speed_rpm", "error"];
    assert_eq!(cols[..4], axes, "{cols:?}");
    let bad: Vec<&&str> = cols[4..]
        .iter()
        .filter(|c| !well_formed(c) || !sweep_column_documented(c, &run_keys))
        .collect();
    assert!(bad.is_empty(), "sweep columns not documented: {bad:?}");
    for want in [
        "rating.e [1]",
        "rating.L10 [Mrev]",
        "rating.life_inner [Mrev]",
        "rating.life_outer [Mrev]",
        "peak_force.y [N]",
        "peak_pressure [Pa]",
        "rating.ratings.C [N]",
    ] {
        assert!(cols.contains(&want), "{want} not in {cols:?}");
    }

    let _ = std::fs::remove_dir_all(&d);
}

/// A short run of an example scene: its summary.json, with every key checked.
fn run_scene(d: &Path, scene: &str, keys: &BTreeSet<String>) -> Value {
    let out = d.join(scene);
    raceway(&[
        "run",
        root()
            .join(format!("examples/scenes/{scene}.toml"))
            .to_str()
            .unwrap(),
        "-q",
        "--duration",
        "0.004",
        "--out",
        out.to_str().unwrap(),
    ]);
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    check_json(&summary, keys, scene);
    summary
}

/// The runs whose summaries have sections the default scene has not: a cylindrical roller
/// bearing on the ring level (`lamina_life`), a set (`set.rows`), a set with the thermal
/// effect (`thermal.rows`).
#[test]
fn the_sections_of_rollers_and_sets_are_labelled_and_documented() {
    let docs = documented();
    let keys = section(&docs, "summary.json");
    let d = tmp("runs");
    let crb = run_scene(&d, "nu206-ring2-radial", &keys);
    let life = &crb["lamina_life"];
    assert!(
        life["with_edge_factor"]["L10r [Mrev]"].is_number()
            && life["without_edge_factor"]["life_inner [Mrev]"].is_number()
            && life["states [1]"].is_number(),
        "{life}"
    );
    let set = run_scene(&d, "7008ce-db-pair", &keys);
    let row = &set["set"]["rows"][0];
    assert!(
        row["position [mm]"].is_number() && row["orientation [1]"].is_number(),
        "{row}"
    );
    let thermal = run_scene(&d, "7008ce-db-pair-thermal", &keys);
    let rows = &thermal["thermal"]["rows"];
    assert_eq!(rows.as_array().map(Vec::len), Some(2), "{thermal}");
    assert!(rows[1]["inner_race [°C]"].is_number(), "{rows}");
    let _ = std::fs::remove_dir_all(&d);
}

/// `raceway quasi-static --json` of a ball bearing with every option of the design check
/// (oil, fits, ring temperatures, SKF seal and drag, a duty cycle, a held tilt), of a
/// cylindrical and a tapered roller bearing and of a set; `raceway bearings --json` (the
/// list), for a ball and for a roller bearing.
#[test]
fn quasi_static_and_bearings_keys_are_labelled_and_documented() {
    let docs = documented();
    let qs_keys = section(&docs, "`raceway quasi-static");
    let d = tmp("qs");
    let duty = d.join("duty.csv");
    std::fs::write(&duty, "3000, 500, 3000, 0.5\n1500, 0, 1500, 0.5\n").unwrap();
    let ball = |bearing: &str, extra: &[&str]| -> Value {
        let mut args = vec![
            "quasi-static",
            "--bearing",
            bearing,
            "--fy",
            "-3000",
            "--fz",
            "300",
            "--speed-rpm",
            "3000",
            "--oil",
            "VG68",
            "--contamination",
            "0.5",
            "--shaft-interference-um",
            "10",
            "--housing-interference-um",
            "5",
            "--inner-ring-temp-c",
            "50",
            "--outer-ring-temp-c",
            "40",
            "--skf-seal",
            "0.028,2.25,2,25",
            "--skf-drag",
            "0.0005,10",
            "--duty",
            duty.to_str().unwrap(),
            "--json",
        ];
        args.extend_from_slice(extra);
        serde_json::from_str(&raceway(&args)).unwrap()
    };
    let qs = ball("6205", &["--hold", "rx,ry"]);
    let n = check_json(&qs, &qs_keys, "quasi-static 6205 --json");
    assert!(n > 150, "{n} keys");
    let (sol, calc) = (&qs["solution"], &qs["calculator"]);
    assert!(qs["speed [rpm]"].is_number() && qs["rating"]["P [N]"].is_number());
    assert!(sol["displacement.y [m]"].is_number() && sol["force.rx [N.m]"].is_number());
    assert!(sol["balls"][0]["q_i [N]"].is_number(), "{sol}");
    for (section, key) in [
        ("lubrication", "kappa [1]"),
        ("friction", "moment [N.m]"),
        ("clearance", "operating [m]"),
        ("duty", "miner_life [h]"),
        ("thermal_speed", "reference_speed [rpm]"),
        ("skf_friction", "seal_moment [N.m]"),
        ("skf_friction", "drag_moment [N.m]"),
        ("held_moment", "L10r [Mrev]"),
    ] {
        assert!(
            calc[section][key].is_number(),
            "calculator.{section}.{key}: {calc}"
        );
    }
    assert!(calc["equilibrium_clearance [m]"].is_number(), "{calc}");
    // Without the SKF constants of its series (a 7205 is not built in): skf_note.
    let note = ball("7205B", &[]);
    check_json(&note, &qs_keys, "quasi-static 7205B --json");
    // A tapered roller bearing needs an axial load to sit.
    for (bearing, fz) in [("NU206", "0"), ("30206", "2000")] {
        let r: Value = serde_json::from_str(&raceway(&[
            "quasi-static",
            "--bearing",
            bearing,
            "--fy",
            "-5000",
            "--fz",
            fz,
            "--speed-rpm",
            "1500",
            "--json",
        ]))
        .unwrap();
        check_json(&r, &qs_keys, bearing);
        assert!(
            r["speed [rpm]"].is_number()
                && r["L10 [Mrev]"].is_number()
                && r["lamina_life"]["L10r [Mrev]"].is_number()
                && r["solution"]["rollers"][0]["lamina_load_inner [N]"].is_array(),
            "{r}"
        );
    }
    let set: Value = serde_json::from_str(&raceway(&[
        "quasi-static",
        "--scene",
        root()
            .join("examples/scenes/7008ce-db-pair.toml")
            .to_str()
            .unwrap(),
        "--fy",
        "-500",
        "--json",
    ]))
    .unwrap();
    check_json(&set, &qs_keys, "quasi-static --scene");
    assert!(set["solution"]["rows"][1]["balls"][0]["alpha_i [rad]"].is_number());

    let b_keys = section(&docs, "`raceway bearings");
    let list: Value = serde_json::from_str(&raceway(&["bearings", "--json"])).unwrap();
    check_json(&list, &b_keys, "bearings --json");
    assert!(list[0]["C [N]"].is_number(), "{list}");
    for name in ["6205", "NU206", "30206"] {
        let one: Value = serde_json::from_str(&raceway(&["bearings", name, "--json"])).unwrap();
        check_json(&one, &b_keys, name);
        assert!(one["ratings"]["C [N]"].is_number(), "{one}");
    }

    let s_keys = section(&docs, "`raceway shaft");
    for shaft in ["spindle", "gear-shaft"] {
        let file = format!("examples/shafts/{shaft}.toml");
        let v: Value = serde_json::from_str(&raceway(&["shaft", &file, "--json"])).unwrap();
        check_json(&v, &s_keys, &file);
        assert!(v["system_life [Mrev]"].is_number(), "{v}");
        let row = &v["locations"][0]["set"]["rows"][0];
        assert!(row["life [Mrev]"].is_number(), "{v}");
        assert!(row["balls"][0]["q_i [N]"].is_number(), "{v}");
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// A label is read back into name and unit, and written again the same.
#[test]
fn labels_round_trip() {
    for (n, u) in [
        ("force.y", "N"),
        ("rating.e", "1"),
        ("L10", "Mrev"),
        ("scene", ""),
    ] {
        let l = raceway::units::label(n, u);
        let (n2, u2) = raceway::units::split_label(&l);
        assert_eq!((n2, u2.unwrap_or("")), (n, u));
    }
    assert_eq!(raceway::units::split_label("a [b] c"), ("a [b] c", None));
    let _ = Path::new(".");
}
