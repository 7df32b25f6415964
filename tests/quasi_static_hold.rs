//! Held ring coordinates in the quasi-static solve (`QuasiStatic::solve_held`, `raceway
//! quasi-static --hold`): holding the tilts of a single angular-contact bearing takes a
//! moment and reduces the radial displacement; holding every coordinate at the free
//! answer's values gives its forces with no reaction; a held coordinate's force is the
//! motion-driven evaluation's at that displacement.

#![allow(clippy::needless_range_loop)] // five coordinates indexed side by side

use raceway::geometry::preset;
use raceway::models::quasi_static::{azimuths, BallState, Options, QuasiStatic};
use std::process::Command;

fn model() -> QuasiStatic {
    QuasiStatic::new(
        &preset("7205B").unwrap().build().unwrap(),
        Options::default(),
    )
    .unwrap()
}

const LOAD: [f64; 5] = [0.0, 1000.0, 2000.0, 0.0, 0.0];

#[test]
fn held_tilts_take_a_moment_and_stiffen_the_radial_direction() {
    let m = model();
    let free = m.solve(&LOAD, 0.0).unwrap();
    assert_eq!(free.held, [false; 5]);
    assert_eq!(free.reaction, [0.0; 5]);
    let held = m
        .solve_held(&LOAD, 0.0, &[None, None, None, Some(0.0), Some(0.0)])
        .unwrap();
    assert_eq!(held.held, [false, false, false, true, true]);
    assert_eq!((held.q[3], held.q[4]), (0.0, 0.0));
    // The solved coordinates balance the load; the held tilt needs a moment about x.
    for i in 0..3 {
        assert!((held.forces[i] + LOAD[i]).abs() < 1e-6 * 2000.0, "{i}");
        assert_eq!(held.reaction[i], 0.0);
    }
    assert!(
        held.reaction[3].abs() > 1.0,
        "Mx reaction {}",
        held.reaction[3]
    );
    for i in 0..5 {
        assert!((LOAD[i] + held.forces[i] + held.reaction[i]).abs() < 1e-9);
    }
    let radial = |q: &[f64; 5]| q[0].hypot(q[1]);
    assert!(
        radial(&held.q) < 0.5 * radial(&free.q),
        "held {} free {}",
        radial(&held.q),
        radial(&free.q)
    );
}

#[test]
fn holding_all_five_at_the_free_answer_reproduces_it() {
    let m = model();
    for omega in [0.0, 1000.0] {
        let free = m.solve(&LOAD, omega).unwrap();
        let hold = free.q.map(Some);
        let held = m.solve_held(&LOAD, omega, &hold).unwrap();
        for i in 0..5 {
            assert!(
                (held.forces[i] - free.forces[i]).abs() < 1e-6 * 2000.0,
                "{omega} {i}: {} vs {}",
                held.forces[i],
                free.forces[i]
            );
            assert!(held.reaction[i].abs() < 1e-6 * 2000.0);
        }
    }
}

#[test]
fn a_held_coordinate_gets_the_motion_driven_force() {
    let m = model();
    let omega = 800.0;
    // Axial displacement held at 20 µm, the rest solved under a radial load.
    let load = [0.0, 1000.0, 0.0, 0.0, 0.0];
    let held = m
        .solve_held(&load, omega, &[None, None, Some(20e-6), None, None])
        .unwrap();
    assert_eq!(held.q[2], 20e-6);
    let psi = azimuths(m.bearing().z, 0.0);
    let mut st = vec![BallState::default(); psi.len()];
    let f = m.forces(&held.q, omega, &psi, &mut st).unwrap();
    for i in 0..5 {
        assert!(
            (f[i] - held.forces[i]).abs() < 1e-9 * 1000.0 + 1e-9,
            "{i}: {} vs {}",
            f[i],
            held.forces[i]
        );
    }
    assert!(held.reaction[2].abs() > 10.0, "a preload reaction");
    // Everything held at an arbitrary displacement: exactly the kinematic evaluation.
    let q = [3e-6, -2e-6, 15e-6, 0.2e-3, -0.1e-3];
    let all = m.solve_held(&[0.0; 5], omega, &q.map(Some)).unwrap();
    let f = m.forces(&q, omega, &psi, &mut st).unwrap();
    for i in 0..5 {
        assert!((f[i] - all.forces[i]).abs() <= 1e-9 * f[i].abs().max(1.0));
        assert!((all.reaction[i] + f[i]).abs() <= 1e-9 * f[i].abs().max(1.0));
    }
}

#[test]
fn the_cli_says_what_it_held() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "quasi-static",
            "--bearing",
            "7205B",
            "--fz",
            "2000",
            "--fy",
            "1000",
        ];
        args.extend_from_slice(extra);
        Command::new(env!("CARGO_BIN_EXE_raceway"))
            .args(&args)
            .output()
            .unwrap()
    };
    let out = run(&["--hold", "rx_mrad=0,ry_mrad=0"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("held coordinates:                 rx, ry"),
        "{text}"
    );
    assert!(text.contains("reaction holding them:"), "{text}");
    let out = run(&["--hold", "rx=0,ry=0", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["solution"]["held"][3], true);
    assert!(v["solution"]["reaction.rx [N.m]"].as_f64().unwrap().abs() > 1.0);
    let out = run(&["--hold", "tilt=0"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--hold"));
}

#[test]
fn a_scene_static_start_holds_and_reports_the_same_reaction() {
    let text = |hold: &str, level: &str| {
        format!(
            "bearing = \"7205B\"\n[model]\nlevel = \"{level}\"\ncausality = \"load\"\n{hold}\n\
             [inputs]\nrule = \"hold\"\nspeed_rpm = 0.0\ninitial = {{ \"load.y\" = 1000.0, \"load.z\" = 2000.0 }}\n"
        )
    };
    let hold = "[model.start_hold]\nrx_mrad = 0.0\nry_mrad = 0.0";
    let scene = raceway::Scene::from_text(&text(hold, "quasi_static")).unwrap();
    let c = raceway::Component::new(scene).unwrap();
    let (held, reaction) = c.start_held();
    assert_eq!(held, [false, false, false, true, true]);
    let lib = model()
        .solve_held(&LOAD, 0.0, &[None, None, None, Some(0.0), Some(0.0)])
        .unwrap();
    assert!(
        (reaction[3] - lib.reaction[3]).abs() < 1e-4 * lib.reaction[3].abs(),
        "scene {} library {}",
        reaction[3],
        lib.reaction[3]
    );
    // Without a hold nothing is held; a 2-DOF ring has no tilt to hold.
    let free = raceway::Scene::from_text(&text("", "quasi_static")).unwrap();
    assert_eq!(
        raceway::Component::new(free).unwrap().start_held().0,
        [false; 5]
    );
    let two = raceway::Scene::from_text(&text(&format!("ring_dof = 2\n{hold}"), "ring")).unwrap();
    let e = raceway::Component::new(two).err().unwrap().to_string();
    assert!(e.contains("model.start_hold.rx_mrad"), "{e}");
}
