//! Cylindrical roller bearings through the component (what the C ABI, the FMUs, the
//! command line and Python all drive): a catalogue designation in a scene runs at the
//! quasi-static level, its force is the sum of the ISO/TS 16281 roller loads, and the
//! levels without a roller law refuse it naming both.

use raceway::component::{variables, Component};
use raceway::contact::lamina::roller_constant;
use raceway::geometry::roller_catalogue;

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

fn scene(level: &str, bearing: &str) -> String {
    format!(
        r#"
bearing = {bearing}
[model]
level = "{level}"
[inputs]
speed_rpm = 954.9296586
initial = {{ "shaft.x" = 0.0, "shaft.y" = -20e-6, "shaft.z" = 0.0, "shaft.rx" = 0.0, "shaft.ry" = 0.0,
            "shaft.vx" = 0.0, "shaft.vy" = 0.0, "shaft.vz" = 0.0, "shaft.wx" = 0.0, "shaft.wy" = 0.0 }}
"#
    )
}

/// Straight rollers at zero clearance: each roller at azimuth `psi` (cage angle 0 at the
/// first step) carries `Q = c_L (y cos(psi - 3pi/2))^(10/9)` (ISO/TS 16281's load law, the
/// laminae summing to it for a uniform approach), and the force on the shaft is their sum,
/// computed here by hand from the catalogue geometry.
#[test]
fn straight_rollers_give_the_sum_of_the_roller_loads() {
    let bearing = r#"{ preset = "NU206", clearance_um = 0.0, profile = { type = "none" } }"#;
    let mut c = Component::from_text(&scene("quasi_static", bearing)).unwrap();
    c.do_step(0.0, 1e-6).unwrap();
    let fy = c.get_real(vr("force.y")).unwrap();
    let fx = c.get_real(vr("force.x")).unwrap();

    let spec = roller_catalogue::lookup("NU206").unwrap();
    let rb = spec.build().unwrap();
    let g = rb.line_geometry();
    let cl = roller_constant(g.lwe, g.e_prime);
    let y = 20e-6;
    // The cage turns during the step: at the step's end the cage angle is the kinematic
    // cage speed times 1 µs (its effect on the sum is below 1e-6 relative).
    let (mut sx, mut sy) = (0.0, 0.0);
    for j in 0..rb.z {
        let psi = 2.0 * std::f64::consts::PI * j as f64 / rb.z as f64;
        let delta = -y * psi.sin(); // the ring moves down: rollers below are compressed
        if delta > 0.0 {
            let q = cl * delta.powf(10.0 / 9.0);
            sx -= q * psi.cos();
            sy -= q * psi.sin();
        }
    }
    assert!(
        (fy / sy - 1.0).abs() < 1e-4,
        "force.y {fy} N, hand sum {sy} N"
    );
    assert!(
        (fx - sx).abs() < 1e-4 * sy.abs(),
        "force.x {fx} N, hand sum {sx} N"
    );
    // The outputs a host reads beside the force: the ISO 281 life of the roller bearing
    // ((Cr/P)^(10/3), P = Fr for a cylindrical roller bearing) and the loaded rollers.
    let cr = raceway::ratings::roller::roller_ratings(&rb).unwrap().cr;
    let l10 = c.get_real(vr("life.L10")).unwrap();
    let want = (cr / fx.hypot(fy)).powf(10.0 / 3.0);
    assert!((l10 / want - 1.0).abs() < 1e-9, "L10 {l10} vs {want}");
    // Six rollers below the horizontal carry load (the two on it touch at zero approach).
    let loaded = c.get_real(vr("balls.loaded")).unwrap();
    assert!((6.0..=8.0).contains(&loaded), "{loaded}");
}

/// The roller profile relieves the roller ends: the crowned (ISO/TS 16281 logarithmic,
/// the default) bearing is softer than the straight one at the same displacement.
#[test]
fn the_default_log_profile_is_softer_than_straight_rollers() {
    let force = |bearing: &str| {
        let mut c = Component::from_text(&scene("quasi_static", bearing)).unwrap();
        c.do_step(0.0, 1e-6).unwrap();
        c.get_real(vr("force.y")).unwrap()
    };
    let straight =
        force(r#"{ preset = "NU206", clearance_um = 0.0, profile = { type = "none" } }"#);
    let logp = force(r#"{ preset = "NU206", clearance_um = 0.0 }"#);
    assert!(
        logp > 0.0 && logp < straight,
        "log {logp} N, straight {straight} N"
    );
}

/// A level without a roller law refuses a roller bearing naming the level and the element
/// kind.
#[test]
fn levels_without_a_roller_law_refuse_naming_both() {
    for level in ["skidding", "full", "linear"] {
        let e = Component::from_text(&scene(level, "\"NU206\""))
            .unwrap_err()
            .to_string();
        assert!(e.contains(level) && e.contains("roller"), "{level}: {e}");
    }
}

/// Plausibility limits come from the line contact: a displacement beyond the elastic
/// range of the rollers is refused naming the input.
#[test]
fn roller_limits_refuse_an_impossible_displacement() {
    let mut c = Component::from_text(&scene("quasi_static", "\"NU206\"")).unwrap();
    let e = c.set_real(vr("shaft.y"), -1e-3).unwrap_err().to_string();
    assert!(e.contains("shaft.y"), "{e}");
    // ... and the state is unchanged: a step still gives the scene's force.
    c.do_step(0.0, 1e-6).unwrap();
    assert!(c.get_real(vr("force.y")).unwrap() > 0.0);
}

/// `raceway bearings NU206 --json` gives the catalogue's roller data and the ISO 281/76
/// roller ratings the library computes.
#[test]
fn the_command_line_lists_a_roller_designation_with_its_ratings() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_raceway"))
        .args(["bearings", "NU206", "--json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rb = roller_catalogue::lookup("NU206").unwrap().build().unwrap();
    let r = raceway::ratings::roller::roller_ratings(&rb).unwrap();
    assert_eq!(v["element"], "roller");
    assert_eq!(v["ratings"]["C [N]"].as_f64().unwrap(), r.cr);
    assert_eq!(v["spec"]["Z [1]"].as_u64().unwrap(), rb.z as u64);
}

/// The ring level carries rollers through the same contact law: at rest (no velocity, so
/// no damping) its force equals the quasi-static level's at the same displacement, in 2
/// and 5 DOF; load-driven with contact damping it settles where the rollers carry the
/// load.
#[test]
fn the_ring_level_carries_rollers_through_the_same_law() {
    let force = |text: &str| {
        let mut c = Component::from_text(text).unwrap();
        c.do_step(0.0, 1e-6).unwrap();
        [
            c.get_real(vr("force.x")).unwrap(),
            c.get_real(vr("force.y")).unwrap(),
        ]
    };
    // At rest both levels run the same law; at speed the quasi-static level's rollers carry
    // their centrifugal force (docs/physics.md §R9), which unloads the inner contacts at the
    // same displacement, while the ring level's rollers stay massless.
    let at_rest = |t: String| t.replace("speed_rpm = 954.9296586", "speed_rpm = 0.0");
    let qs = force(&at_rest(scene("quasi_static", "\"NU206\"")));
    for dof in [2, 5] {
        let text =
            scene("ring", "\"NU206\"").replace("[model]", &format!("[model]\nring_dof = {dof}"));
        let ring = force(&at_rest(text.clone()));
        assert!(
            (ring[1] / qs[1] - 1.0).abs() < 1e-12,
            "{dof}-DOF ring {ring:?} vs {qs:?}"
        );
        // At speed only the elements' turn within the step moves the ring level's force.
        assert!((force(&text)[1] / ring[1] - 1.0).abs() < 1e-6);
    }
    let qs_fast = force(&scene("quasi_static", "\"NU206\""));
    assert!(
        qs_fast[1].abs() < qs[1].abs() && qs_fast[1] / qs[1] > 0.99,
        "{qs_fast:?} vs {qs:?}"
    );
    let load = r#"
bearing = "NU206"
[model]
level = "ring"
causality = "load"
contact_damping = 3000.0
attached_mass_kg = 1.0
[inputs]
speed_rpm = 954.9296586
initial = { "load.x" = 0.0, "load.y" = -3000.0, "load.z" = 0.0, "load.mx" = 0.0, "load.my" = 0.0 }
"#;
    let mut c = Component::from_text(load).unwrap();
    let h = 1e-4;
    for i in 0..2000 {
        c.do_step(i as f64 * h, h).unwrap();
    }
    let fy = c.get_real(vr("force.y")).unwrap();
    let y = c.get_real(vr("shaft.y")).unwrap();
    // Settled: the bearing force balances the load (the rollers pass at the cage speed, so
    // the force ripples by a few per cent about it).
    assert!(
        (fy / 3000.0 - 1.0).abs() < 0.05,
        "force.y {fy} N at y {y} m"
    );
    assert!(y < -16.25e-6, "beyond half the clearance: {y}");
}

/// The C ABI takes a roller scene unchanged: the same variables, the same force as the Rust
/// component gives.
#[test]
fn the_c_abi_runs_a_roller_scene_with_the_same_variables() {
    use raceway::capi::*;
    use std::ffi::CString;
    let text = scene("quasi_static", "\"NU206\"");
    let mut err = [0 as std::ffi::c_char; 512];
    let cs = CString::new(text.clone()).unwrap();
    let c = unsafe { raceway_create(cs.as_ptr(), err.as_mut_ptr(), err.len()) };
    assert!(!c.is_null());
    let mut fy = 0.0;
    unsafe {
        assert_eq!(raceway_do_step(c, 0.0, 1e-6), RacewayStatus::Ok);
        assert_eq!(
            raceway_get_real(c, RACEWAY_VR_FORCE_Y, &mut fy),
            RacewayStatus::Ok
        );
        raceway_free(c);
    }
    let mut r = Component::from_text(&text).unwrap();
    r.do_step(0.0, 1e-6).unwrap();
    assert_eq!(fy, r.get_real(vr("force.y")).unwrap());
    assert!(fy > 0.0);
}

/// `raceway quasi-static --bearing NU206 --fy -8000 --json`: the rollers balance the load, every
/// roller lists its 30 lamina loads summing to its load, `K` is 5×5 with an exact zero axial
/// row (an NU has no flange contact), and an axial load on the NU is refused naming `--fz`.
#[test]
fn the_quasi_static_command_solves_a_roller_bearing() {
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_raceway"))
            .args(args)
            .output()
            .unwrap()
    };
    let out = run(&[
        "quasi-static",
        "--bearing",
        "NU206",
        "--fy",
        "-8000",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let sol = &v["solution"];
    let fy = sol["force.y [N]"].as_f64().unwrap();
    assert!((fy - 8000.0).abs() < 1e-3, "{fy}");
    let rollers = sol["rollers"].as_array().unwrap();
    for r in rollers {
        let lam = r["lamina_load_outer [N]"].as_array().unwrap();
        assert_eq!(lam.len(), 30);
        let s: f64 = lam.iter().map(|x| x.as_f64().unwrap()).sum();
        let q = r["q_o [N]"].as_f64().unwrap();
        assert!((s - q).abs() <= 1e-9 * q.max(1.0), "{s} vs {q}");
    }
    let k = sol["stiffness [SI]"].as_array().unwrap();
    assert_eq!(k.len(), 5);
    assert!(k[2]
        .as_array()
        .unwrap()
        .iter()
        .all(|x| x.as_f64() == Some(0.0)));
    let out = run(&[
        "quasi-static",
        "--bearing",
        "NU206",
        "--fy",
        "-8000",
        "--fz",
        "100",
    ]);
    assert!(!out.status.success());
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("--fz"), "{e}");
    // The ball bearings' design-check options are refused by name, not ignored.
    for (flag, value) in [("--kappa", "2"), ("--oil", "VG68"), ("--hold", "rx")] {
        let out = run(&[
            "quasi-static",
            "--bearing",
            "NU206",
            "--fy",
            "-8000",
            flag,
            value,
        ]);
        assert!(!out.status.success());
        let e = String::from_utf8_lossy(&out.stderr);
        assert!(e.contains(&format!("`{flag}`")), "{e}");
    }
}
