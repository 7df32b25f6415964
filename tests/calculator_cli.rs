//! `raceway quasi-static`'s design check (docs/calculator.md): the oil's kappa feeds the ISO
//! life, the friction moment rises with viscosity, a shaft fit takes clearance away, and bad
//! input is refused naming the flag or field.

use std::process::Command;

fn qs_json(extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "quasi-static",
        "--bearing",
        "6205",
        "--speed-rpm",
        "3000",
        "--fy",
        "2000",
        "--json",
    ];
    args.extend_from_slice(extra);
    let out = Command::new(env!("CARGO_BIN_EXE_raceway"))
        .args(&args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn stderr_of(extra: &[&str]) -> String {
    let mut args = vec!["quasi-static", "--bearing", "6205", "--speed-rpm", "3000"];
    args.extend_from_slice(extra);
    let out = Command::new(env!("CARGO_BIN_EXE_raceway"))
        .args(&args)
        .output()
        .unwrap();
    assert!(!out.status.success());
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn oil_gives_kappa_and_friction() {
    let thin = qs_json(&["--oil", "VG32", "--contamination", "0.5"]);
    let thick = qs_json(&["--oil", "VG100", "--contamination", "0.5"]);
    let k = |v: &serde_json::Value| {
        v["calculator"]["lubrication"]["kappa [1]"]
            .as_f64()
            .unwrap()
    };
    let m = |v: &serde_json::Value| {
        v["calculator"]["friction"]["moment [N.m]"]
            .as_f64()
            .unwrap()
    };
    assert!(k(&thick) > k(&thin) && m(&thick) > m(&thin));
    // The kappa from the oil is the one the ISO life used (a_ISO rises with kappa).
    let a = |v: &serde_json::Value| v["rating"]["a_ISO [1]"].as_f64().unwrap();
    assert!(a(&thick) > a(&thin));
    // The subsurface stresses are always there; no oil, no friction.
    let none = qs_json(&[]);
    assert!(none["calculator"]["friction"].is_null());
    let tau = none["calculator"]["subsurface"]["inner"]["tau_max [Pa]"]
        .as_f64()
        .unwrap();
    let p = none["rating"]["peak_pressure [Pa]"].as_f64().unwrap();
    assert!(tau > 0.25 * p && tau < 0.33 * p, "{tau} {p}");
}

#[test]
fn fits_reduce_clearance() {
    let r = qs_json(&["--shaft-interference-um", "10"]);
    let c = &r["calculator"]["clearance"];
    assert!(c["operating [m]"].as_f64().unwrap() < c["unmounted [m]"].as_f64().unwrap());
    let free = qs_json(&[]);
    assert!(free["calculator"]["clearance"].is_null());
    // The equilibrium is solved in the operating clearance: preloaded by the fit, the ring
    // moves less under the same load, and the check says which clearance it used.
    let y = |v: &serde_json::Value| v["solution"]["displacement.y [m]"].as_f64().unwrap();
    assert!(y(&r) < 0.9 * y(&free), "{} vs {}", y(&r), y(&free));
    assert_eq!(
        r["calculator"]["equilibrium_clearance [m]"].as_f64(),
        c["operating [m]"].as_f64()
    );
}

/// The fed-back equilibrium is the equilibrium of the bearing with that clearance.
#[test]
fn fed_back_clearance_is_the_bearing_with_that_clearance() {
    use raceway::calculator::check::{CalcInputs, CalcOptions};
    use raceway::calculator::clearance::{operating_clearance, with_clearance};
    use raceway::summary::reports::{load_bearing, QsProblem, CLI_NAMES};
    let b = load_bearing("6205").unwrap();
    let mk = |b| {
        QsProblem::new(
            b,
            3000.0,
            [0.0, 2000.0, 0.0, 0.0, 0.0],
            Default::default(),
            None,
            None,
            &CLI_NAMES,
        )
        .unwrap()
    };
    let mut fitted = mk(b.clone());
    let o = CalcOptions {
        shaft_interference_um: Some(10.0),
        ..Default::default()
    };
    fitted.calc = CalcInputs::from_options(&o, 3000.0, "--oil-vi", "--skf-").unwrap();
    let op = operating_clearance(&b, fitted.calc.clearance.as_ref().unwrap()).unwrap();
    let direct = mk(with_clearance(&b, op.operating).unwrap());
    let (a, _) = fitted.solve().unwrap();
    let (d, _) = direct.solve().unwrap();
    assert_eq!(a.q, d.q);
    assert!(
        op.operating < 0.0,
        "a 10 µm fit preloads the zero-clearance 6205"
    );
}

#[test]
fn bad_input_names_the_field() {
    assert!(stderr_of(&["--oil", "castor"]).contains("castor"));
    assert!(stderr_of(&["--oil-vi", "100"]).contains("--oil-vi"));
    assert!(stderr_of(&["--oil", "VG68", "--oil-vi", "900"]).contains("oil.viscosity_index"));
    assert!(stderr_of(&["--shaft-interference-um", "500"]).contains("shaft_interference"));
}

#[test]
fn duty_cycle_from_a_spectrum_file() {
    let dir = std::env::temp_dir().join(format!("raceway-duty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let good = dir.join("good.csv");
    std::fs::write(
        &good,
        "fr_n,fa_n,speed_rpm,time_share\n2000,0,1000,0.5\n4000,0,2000,0.5\n",
    )
    .unwrap();
    let r = qs_json(&["--duty", good.to_str().unwrap()]);
    let d = &r["calculator"]["duty"];
    // Mean load by hand: (2000³/3 + 2·4000³/3)^(1/3) = 3565.65 N; mean speed 1500 rpm.
    assert!(
        (d["mean_load [N]"].as_f64().unwrap() - 3565.65).abs() < 0.01,
        "{d}"
    );
    assert_eq!(d["mean_speed [rpm]"].as_f64().unwrap(), 1500.0);
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "2000,0,1000,0.5\n4000,0,2000,0.4\n").unwrap();
    assert!(stderr_of(&["--duty", bad.to_str().unwrap()]).contains("duty.time_share"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn thermal_speeds_from_the_oil() {
    // qs_json's load is Fy 2000 N; adding Fx 2000 N lowers the safe speed, not the reference.
    let light = qs_json(&["--oil", "VG68", "--oil-temp-c", "60"]);
    let heavy = qs_json(&["--oil", "VG68", "--oil-temp-c", "60", "--fx", "2000"]);
    let t = |v: &serde_json::Value, k: &str| v["calculator"]["thermal_speed"][k].as_f64().unwrap();
    assert_eq!(
        t(&light, "reference_speed [rpm]"),
        t(&heavy, "reference_speed [rpm]")
    );
    assert!(t(&heavy, "safe_speed [rpm]") < t(&light, "safe_speed [rpm]"));
    // A warmer ambient leaves less temperature rise: a lower safe speed.
    let warm = qs_json(&[
        "--oil",
        "VG68",
        "--oil-temp-c",
        "60",
        "--ambient-temp-c",
        "40",
    ]);
    assert!(t(&warm, "safe_speed [rpm]") < t(&light, "safe_speed [rpm]"));
    assert!(light["calculator"]["thermal_speed"]["unsourced"]
        .as_str()
        .unwrap()
        .contains("q_r"));
}

/// SKF's four-term model beside Palmgren's: both rise with viscosity; without seals or drag
/// the total is rolling + sliding; seals add their constant term; the per-series constants
/// are labelled as not confirmed.
#[test]
fn skf_friction_beside_palmgren() {
    let thin = qs_json(&["--oil", "VG32", "--skf-lubrication", "oil-jet"]);
    let thick = qs_json(&["--oil", "VG100", "--skf-lubrication", "oil-jet"]);
    let skf = |v: &serde_json::Value, f: &str| v["calculator"]["skf_friction"][f].as_f64().unwrap();
    assert!(skf(&thick, "moment [N.m]") > skf(&thin, "moment [N.m]"));
    assert!(
        (skf(&thin, "moment [N.m]")
            - skf(&thin, "rolling_moment [N.m]")
            - skf(&thin, "sliding_moment [N.m]"))
        .abs()
            < 1e-15 * skf(&thin, "moment [N.m]").max(1.0)
    );
    assert!(thin["calculator"]["skf_friction"]["seal_moment [N.m]"].is_null());
    assert_eq!(thin["calculator"]["skf_friction"]["series"], "62");
    assert!(thin["calculator"]["skf_friction"]["unconfirmed"]
        .as_str()
        .unwrap()
        .contains("not checked"));
    let sealed = qs_json(&[
        "--oil",
        "VG32",
        "--skf-lubrication",
        "oil-jet",
        "--skf-seal",
        "0.02,2.25,2,30",
    ]);
    let seal = skf(&sealed, "seal_moment [N.m]");
    assert!((seal * 1e3 - (0.02 * 30f64.powf(2.25) + 2.0)).abs() < 1e-9);
    assert!((skf(&sealed, "moment [N.m]") - skf(&thin, "moment [N.m]") - seal).abs() < 1e-12);
    // At rest the SKF model is not defined: no SKF line, the reason instead.
    let rest = {
        let out = Command::new(env!("CARGO_BIN_EXE_raceway"))
            .args([
                "quasi-static",
                "--bearing",
                "6205",
                "--fy",
                "2000",
                "--oil",
                "VG32",
                "--json",
            ])
            .output()
            .unwrap();
        serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap()
    };
    assert!(rest["calculator"]["skf_friction"].is_null());
    assert!(rest["calculator"]["skf_note"]
        .as_str()
        .unwrap()
        .contains("skf.speed_rpm"));
    assert!(stderr_of(&["--oil", "VG32", "--skf-seal", "1,2"]).contains("--skf-seal"));
    assert!(
        stderr_of(&["--oil", "VG32", "--skf-lubrication", "mist"]).contains("--skf-lubrication")
    );
    assert!(
        stderr_of(&["--skf-lubrication", "grease", "--skf-drag", "0.0003,10"])
            .contains("--skf-drag")
    );
}

/// A held displacement: ISO 281's P is formed from the force the bearing carries (the load
/// plus the reaction), not the load alone. Held tilts: the moment is reported beside L10
/// (which ignores it) and L10r (which includes it).
#[test]
fn held_coordinates_and_the_equivalent_load() {
    let v = qs_json(&["--hold", "y_um=5"]);
    let carried = v["solution"]["load.y [N]"].as_f64().unwrap()
        + v["solution"]["reaction.y [N]"].as_f64().unwrap();
    let fr = v["rating"]["radial_load [N]"].as_f64().unwrap();
    assert!((fr - carried.abs()).abs() < 1e-9, "{fr} {carried}");
    assert!(
        fr < 1000.0,
        "a 5 µm hold leaves less than the 2000 N load: {fr}"
    );
    assert!(v["calculator"]["held_moment"].is_null());
    let out = Command::new(env!("CARGO_BIN_EXE_raceway"))
        .args([
            "quasi-static",
            "--bearing",
            "7205B",
            "--fy",
            "1000",
            "--fz",
            "2000",
            "--speed-rpm",
            "3000",
            "--hold",
            "rx_mrad=0,ry_mrad=0",
            "--json",
        ])
        .output()
        .unwrap();
    let t: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let h = &t["calculator"]["held_moment"];
    let r = &t["solution"];
    let m = r["reaction.rx [N.m]"]
        .as_f64()
        .unwrap()
        .hypot(r["reaction.ry [N.m]"].as_f64().unwrap());
    assert!(m > 1.0 && (h["moment [N.m]"].as_f64().unwrap() - m).abs() < 1e-12);
    assert_eq!(h["L10 [Mrev]"], t["rating"]["L10 [Mrev]"]);
    assert_eq!(h["L10r [Mrev]"], t["rating"]["L10r [Mrev]"]);
}
