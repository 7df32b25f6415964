//! `raceway shaft`: the spindle example solves, its JSON balances the load, the gear shaft's
//! floating NU location carries no thrust, and a shaft on one single-row bearing is refused
//! as statically undetermined.

use std::process::Command;

fn raceway(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_raceway"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap()
}

#[test]
fn spindle_example_balances_its_load() {
    let out = raceway(&["shaft", "examples/shafts/spindle.toml", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // Five numbers split into their labelled keys (docs/columns.md).
    let five = |o: &serde_json::Value, name: &str, units: [&str; 2]| -> Vec<f64> {
        ["x", "y", "z", "rx", "ry"]
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let u = units[usize::from(i >= 3)];
                o[format!("{name}.{c} [{u}]")].as_f64().unwrap()
            })
            .collect()
    };
    let load = five(&v, "load", ["N", "N.m"]);
    // Sum of the reactions moved to the origin plus the load: zero.
    let mut sum = load.clone();
    for l in v["locations"].as_array().unwrap() {
        let z = l["position [m]"].as_f64().unwrap();
        let f = five(&l["set"], "force", ["N", "N.m"]);
        sum[0] += f[0];
        sum[1] += f[1];
        sum[2] += f[2];
        sum[3] += f[3] - z * f[1];
        sum[4] += f[4] + z * f[0];
    }
    for (i, s) in sum.iter().enumerate() {
        assert!(s.abs() < 1e-6 * 800.0, "component {i}: {s}");
    }
    assert!(v["system_life [Mrev]"].as_f64().unwrap() > 0.0);
    let text = raceway(&["shaft", "examples/shafts/spindle.toml"]);
    let t = String::from_utf8_lossy(&text.stdout);
    assert!(
        t.contains("front DB pair") && t.contains("system life"),
        "{t}"
    );
}

#[test]
fn one_single_row_bearing_is_refused() {
    let dir = std::env::temp_dir().join(format!("raceway-shaft-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("one.toml");
    std::fs::write(
        &f,
        "[[load]]\nposition_mm = 50\nforce_n = [0, -500, 0]\n[[location]]\nposition_mm = 0\nbearing = \"6206\"\n",
    )
    .unwrap();
    let out = raceway(&["shaft", f.to_str().unwrap()]);
    let e = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1));
    assert!(e.contains("location") && e.contains("tilt"), "{e}");
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "[[location]]\nposition_mm = 0\nbearing = \"7008CE\"\narrangement = \"db\"\nspacer_mm = -2\n[[location]]\nposition_mm = 100\nbearing = \"6008\"\n",
    )
    .unwrap();
    let out = raceway(&["shaft", bad.to_str().unwrap()]);
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("location[0].spacer_mm"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The gear shaft: the floating NU206 carries no axial load, the locating 6206 all of it,
/// and the rollers' contact angle (0) is in the JSON.
#[test]
fn gear_shaft_floating_location_carries_no_thrust() {
    let out = raceway(&["shaft", "examples/shafts/gear-shaft.toml", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let locs = v["locations"].as_array().unwrap();
    let fz = |i: usize| locs[i]["set"]["force.z [N]"].as_f64().unwrap();
    assert!(locs[1]["floating"].as_bool().unwrap());
    assert!(fz(1).abs() < 1e-6 * 600.0, "{}", fz(1));
    assert!((fz(0) + 600.0).abs() < 1e-6 * 600.0, "{}", fz(0));
    let angles = &locs[1]["set"]["rows"][0]["contact_angles [rad]"];
    assert_eq!(angles.as_array().unwrap().len(), 14);
    assert_eq!(angles[0][0].as_f64(), Some(0.0));
}
