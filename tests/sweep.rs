//! `raceway sweep` and `raceway::sweep`: the index space (grid size and order, Latin-hypercube
//! strata), shards merging bit for bit into the full run, resuming, failed points as rows, and
//! every problem of a bad sweep file at once with its line:column.

use raceway::sweep::{read_rows, AxisValues, Row, Sweep};
use std::path::{Path, PathBuf};
use std::process::Command;

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("raceway-sweep-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn scenes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes")
}

/// A quick sweep (quasi-static level, 10 steps a point): 3 speeds x 2 displacements x 2
/// samples; the step of 10 ms is longer than the 1 ms run, a combination only a point's own
/// check sees (each value alone is valid in the base scene).
fn quick_sweep(dir: &Path) -> PathBuf {
    let p = dir.join("quick.toml");
    std::fs::write(
        &p,
        format!(
            r#"scene = "{}"
[[axis]]
key = "run.duration_s"
values = [0.001]
[[axis]]
key = "inputs.speed_rpm"
values = [100.0, 200.0, 300.0]
[[axis]]
key = "run.step_s"
values = [1e-4, 1e-2]
[sample]
method = "lhs"
n = 2
seed = 3
[[axis]]
key = 'inputs.initial."shaft.x"'
min = -2e-6
max = 2e-6
"#,
            scenes().join("default.toml").display()
        ),
    )
    .unwrap();
    p
}

fn raceway(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_raceway"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The rows without the measurements of the machine (CPU time, load average).
fn results(dir: &Path) -> Vec<Row> {
    read_rows(dir)
        .into_iter()
        .map(|mut r| {
            r.summary
                .retain(|(c, _)| !raceway::sweep::MEASUREMENTS.contains(&c.as_str()));
            r
        })
        .collect()
}

#[test]
fn shards_merge_bit_for_bit_into_the_full_run() {
    let d = tmp("shards");
    let sweep = quick_sweep(&d);
    let s = sweep.to_str().unwrap();
    let full = d.join("full");
    let (ok, out, err) = raceway(&["sweep", s, "--out", full.to_str().unwrap(), "--jobs", "2"]);
    assert!(ok, "{out}{err}");
    assert!(out.contains("12 points"), "{out}");
    let mut parts = Vec::new();
    for k in 0..3 {
        let p = d.join(format!("shard{k}"));
        let (ok, out, err) = raceway(&[
            "sweep",
            s,
            "--out",
            p.to_str().unwrap(),
            "--jobs",
            "1",
            "--shard",
            &format!("{k}/3"),
        ]);
        assert!(ok, "{out}{err}");
        let rows = read_rows(&p);
        assert_eq!(rows.len(), 4);
        assert!(rows.iter().all(|r| r.index % 3 == k));
        parts.push(p);
    }
    let merged = d.join("merged");
    let mut args = vec!["sweep", "--out", merged.to_str().unwrap(), "--merge"];
    args.extend(parts.iter().map(|p| p.to_str().unwrap()));
    let (ok, out, err) = raceway(&args);
    assert!(ok, "{out}{err}");
    let (a, b) = (results(&full), results(&merged));
    assert_eq!(a.len(), 12);
    // serde_json's Value compares numbers exactly: the same f64 bits.
    assert_eq!(a, b);
    // The tables are the same apart from the CPU-time column.
    let strip = |p: &Path| {
        let text = std::fs::read_to_string(p.join("sweep.csv")).unwrap();
        let rows = text.lines().count();
        assert_eq!(rows, 13, "header and one line a point");
        let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
        header.len()
    };
    assert_eq!(strip(&full), strip(&merged));
    // A folder holding another sweep's rows is refused.
    let other = d.join("other.toml");
    std::fs::write(
        &other,
        "[[axis]]\nkey = \"run.duration_s\"\nvalues = [0.001]\n",
    )
    .unwrap();
    let (ok, _, err) = raceway(&[
        "sweep",
        other.to_str().unwrap(),
        "--out",
        full.to_str().unwrap(),
    ]);
    assert!(!ok && err.contains("another sweep"), "{err}");
}

#[test]
fn resume_runs_only_unfinished_rows_and_failures_become_rows() {
    let d = tmp("resume");
    let sweep = quick_sweep(&d);
    let s = sweep.to_str().unwrap();
    let out_dir = d.join("out");
    let o = out_dir.to_str().unwrap();
    let (ok, out, err) = raceway(&["sweep", s, "--out", o]);
    assert!(ok, "{out}{err}");
    assert!(out.contains("ran 12, skipped 0"), "{out}");
    // The step longer than the run fails: 6 error rows with the message, 6 results.
    let rows = read_rows(&out_dir);
    let failed: Vec<&Row> = rows.iter().filter(|r| r.error.is_some()).collect();
    assert_eq!(failed.len(), 6);
    for r in &failed {
        assert_eq!(r.axes[2].1, serde_json::json!(1e-2));
        assert!(r.error.as_ref().unwrap().contains("run.step_s"), "{r:?}");
        assert!(r.summary.is_empty());
    }
    assert!(out.contains("6 point(s) failed"), "{out}");
    let good = rows.iter().find(|r| r.error.is_none()).unwrap();
    let peak = good
        .summary
        .iter()
        .find(|(c, _)| c == "peak_force.y [N]")
        .unwrap();
    assert!(
        peak.1.as_f64().unwrap() > 10.0,
        "the base scene's 10 µm displacement loads the bearing"
    );
    // A crash: two rows lost, one half-written, a temporary file left behind.
    let rows_dir = out_dir.join("rows");
    std::fs::remove_file(rows_dir.join("00000001.json")).unwrap();
    std::fs::remove_file(rows_dir.join("00000010.json")).unwrap();
    let half = std::fs::read(rows_dir.join("00000004.json")).unwrap();
    std::fs::write(rows_dir.join("00000004.json"), &half[..half.len() / 2]).unwrap();
    std::fs::write(rows_dir.join(".00000005.json.1.tmp"), b"{\"ind").unwrap();
    let before = results(&out_dir);
    let (ok, out, err) = raceway(&["sweep", s, "--out", o, "--jobs", "1"]);
    assert!(ok, "{out}{err}");
    assert!(out.contains("ran 3, skipped 9"), "{out}");
    assert_eq!(read_rows(&out_dir).len(), 12);
    let after = results(&out_dir);
    for r in &before {
        assert!(after.contains(r));
    }
    // Nothing left to do.
    let (_, out, _) = raceway(&["sweep", s, "--out", o]);
    assert!(out.contains("ran 0, skipped 12"), "{out}");
}

fn parse(text: &str) -> Result<Sweep, Vec<raceway::component::schema::Problem>> {
    Sweep::from_text(text, &scenes())
}

#[test]
fn grid_size_and_order() {
    let sw = parse(
        r#"scene = "default.toml"
[[axis]]
key = "inputs.speed_rpm"
values = [10.0, 20.0, 30.0]
[[axis]]
key = "run.duration_s"
start = 0.01
stop = 0.02
num = 4
[[axis]]
key = "run.step_s"
start = 0.00025
stop = 0.00125
step = 0.00025
[[axis]]
key = "bearing"
values = ["6205", "6206"]
"#,
    )
    .unwrap_or_else(|p| panic!("{p:?}"));
    assert_eq!(sw.len(), 3 * 4 * 5 * 2);
    // The first axis slowest, the last fastest; both ends of a range included.
    let p0 = sw.point(0);
    let p1 = sw.point(1);
    let last = sw.point(sw.len() - 1);
    assert_eq!(p0[0].as_float(), Some(10.0));
    assert_eq!(p1[3].as_str(), Some("6206"));
    assert_eq!(p1[0].as_float(), Some(10.0));
    assert_eq!(last[0].as_float(), Some(30.0));
    assert_eq!(last[1].as_float(), Some(0.02));
    assert!((last[2].as_float().unwrap() - 0.00125).abs() < 1e-18);
    // Every point is distinct.
    let all: std::collections::BTreeSet<String> = (0..sw.len())
        .map(|i| format!("{:?}", sw.point(i)))
        .collect();
    assert_eq!(all.len(), sw.len());
    // The point's values are in its scene.
    let scene = sw.scene(1).unwrap();
    assert_eq!(scene.run.duration_s, 0.01);
    assert_eq!(scene.inputs.speed_rpm, 10.0);
}

#[test]
fn latin_hypercube_has_one_sample_in_each_stratum() {
    let text = |method: &str| {
        format!(
            r#"[sample]
method = "{method}"
n = 40
seed = 11
[[axis]]
key = 'inputs.initial."shaft.y"'
min = -20e-6
max = -10e-6
[[axis]]
key = 'inputs.initial."shaft.x"'
min = 0.0
max = 4e-6
[[axis]]
key = "inputs.speed_rpm"
values = [1.0, 2.0]
"#
        )
    };
    let sw = parse(&text("lhs")).unwrap_or_else(|p| panic!("{p:?}"));
    assert_eq!(sw.len(), 80);
    for grid in 0..2 {
        for (k, a) in sw.axes.iter().enumerate().take(2) {
            let AxisValues::Sampled { min, max } = a.values else {
                panic!()
            };
            let mut strata: Vec<usize> = (0..40)
                .map(|j| {
                    let v = sw.point(grid * 40 + j)[k].as_float().unwrap();
                    assert!((min..max).contains(&v));
                    ((v - min) / (max - min) * 40.0).floor() as usize
                })
                .collect();
            strata.sort();
            assert_eq!(strata, (0..40).collect::<Vec<_>>(), "axis {k}");
        }
    }
    // The two axes are not paired stratum for stratum (independent permutations).
    let pairs: Vec<(usize, usize)> = (0..40)
        .map(|j| {
            let p = sw.point(j);
            (
                ((p[0].as_float().unwrap() + 20e-6) / 10e-6 * 40.0) as usize,
                (p[1].as_float().unwrap() / 4e-6 * 40.0) as usize,
            )
        })
        .collect();
    assert!(pairs.iter().filter(|(a, b)| a == b).count() < 10);
    // Random sampling of the same seed is something else, and reproducible.
    let r1 = parse(&text("random")).unwrap();
    let r2 = parse(&text("random")).unwrap();
    assert_eq!(r1.point(5), r2.point(5));
    assert_ne!(r1.point(5), sw.point(5));
}

#[test]
fn a_bad_sweep_file_gets_every_problem_with_line_and_column() {
    let text = r#"scene = "default.toml"
colour = "blue"
[sample]
method = "grid"
n = 0
[[axis]]
key = "run.durration_s"
values = [0.1]
[[axis]]
values = [1.0]
[[axis]]
key = "run.step_s"
values = [1e-4, -1.0]
[[axis]]
key = "run.duration_s"
start = 0.1
num = 3
step = 0.1
"#;
    let problems = parse(text).unwrap_err();
    let lines: Vec<usize> = problems.iter().map(|p| p.line_col.unwrap().0).collect();
    let text_of = |l: usize| {
        problems
            .iter()
            .filter(|p| p.line_col.unwrap().0 == l)
            .map(|p| p.to_string())
            .collect::<Vec<_>>()
            .join(" | ")
    };
    for (line, what) in [
        (2, "unknown key `colour`"),
        (4, "\"lhs\" or \"random\""),
        (5, "[1, "),
        (7, "run.durration_s"),
        (9, "missing `key`"),
        (13, "-1"),
        (18, "give `num` or `step`"),
        (14, "needs a finite number `stop`"),
    ] {
        assert!(text_of(line).contains(what), "line {line}: {:?}", problems);
    }
    assert!(lines.windows(2).all(|w| w[0] <= w[1]), "in file order");
    // The column points at the value.
    let neg = problems
        .iter()
        .find(|p| p.line_col.unwrap().0 == 13)
        .unwrap();
    assert_eq!(neg.line_col, Some((13, 17)));
    // The CLI prints them all, each as file:line:column, and exits with 1.
    let d = tmp("bad");
    let f = d.join("bad.toml");
    std::fs::write(
        &f,
        text.replace(
            "default.toml",
            scenes().join("default.toml").to_str().unwrap(),
        ),
    )
    .unwrap();
    let (ok, _, err) = raceway(&[
        "sweep",
        f.to_str().unwrap(),
        "--out",
        d.join("o").to_str().unwrap(),
    ]);
    assert!(!ok);
    assert!(
        err.contains(&format!("{} problem(s)", problems.len())),
        "{err}"
    );
    assert!(err.contains(&format!("{}:13:17:", f.display())), "{err}");
    assert!(!d.join("o").exists(), "nothing run");
    // A syntax error: its place, and nothing else.
    let p = parse("[[axis]\nkey = 1\n").unwrap_err();
    assert_eq!(p.len(), 1);
    assert!(p[0].message.starts_with("TOML syntax"));
    assert_eq!(p[0].line_col.map(|l| l.0), Some(1));
}

#[test]
fn the_example_sweep_checks() {
    let f =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/sweeps/6205-speed-displacement.toml");
    let (ok, out, err) = raceway(&["sweep", f.to_str().unwrap(), "--check"]);
    assert!(ok, "{err}");
    assert!(out.contains("18 points"), "{out}");
}
