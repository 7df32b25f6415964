//! `raceway quasi-static --scene` with a bearing set: the shipped 7008CE DB pair, rigidly
//! preloaded to 300 N, under no external load carries equal and opposite row loads (the
//! preload, each row) and its axial stiffness at the reference point is the sum of its
//! rows' own; the text shows one ball table per row; a scene without a set and a ball
//! bearing's option are refused by name.

use std::process::Command;

fn raceway(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_raceway"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap()
}

const PAIR: &str = "examples/scenes/7008ce-db-pair.toml";

#[test]
fn a_rigid_db_pair_at_no_load_balances_its_rows_and_sums_their_axial_stiffness() {
    let out = raceway(&[
        "quasi-static",
        "--scene",
        PAIR,
        "--speed-rpm",
        "0",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let sol = &v["solution"];
    let rows = sol["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    let fz = |i: usize| rows[i]["force.z [N]"].as_f64().unwrap();
    // Equal and opposite on the shaft, each the 300 N preload.
    assert!((fz(0) + fz(1)).abs() < 1e-6 * 300.0, "{} {}", fz(0), fz(1));
    for (i, r) in rows.iter().enumerate() {
        let a = r["axial_load [N]"].as_f64().unwrap();
        assert!((a - 300.0).abs() < 1e-3 * 300.0, "row {i}: {a}");
        assert_eq!(r["lifted_off"], false);
        assert_eq!(r["balls"].as_array().unwrap().len(), 16);
    }
    // No net force at the reference point.
    for k in ["x [N]", "y [N]", "z [N]", "rx [N.m]", "ry [N.m]"] {
        assert!(sol[format!("force.{k}").as_str()].as_f64().unwrap().abs() < 1e-6 * 300.0);
    }
    let kzz = sol["stiffness [SI]"][2][2].as_f64().unwrap();
    let sum: f64 = rows
        .iter()
        .map(|r| r["axial_stiffness [N/m]"].as_f64().unwrap())
        .sum();
    assert!(
        kzz > 0.0 && (kzz - sum).abs() < 0.01 * sum,
        "{kzz} vs {sum}"
    );
    // The system life is below each row's (two loaded rows).
    let life = sol["system_life [Mrev]"].as_f64().unwrap();
    for r in rows {
        assert!(life < r["life [Mrev]"].as_f64().unwrap());
    }

    let text = raceway(&["quasi-static", "--scene", PAIR, "--fy", "-500"]);
    assert!(text.status.success());
    let t = String::from_utf8_lossy(&text.stdout);
    assert!(
        t.contains("row 0:") && t.contains("row 1:") && t.contains("psi deg"),
        "{t}"
    );
    assert_eq!(t.matches("psi deg").count(), 2, "{t}");
}

#[test]
fn a_scene_without_a_set_and_ball_options_are_refused() {
    let out = raceway(&[
        "quasi-static",
        "--scene",
        "examples/scenes/6205-linear.toml",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("--scene") && e.contains("[set]"), "{e}");
    let out = raceway(&["quasi-static", "--scene", PAIR, "--kappa", "1"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--kappa"));
}
