//! A bearing set as one component (the Rust face): the 7008CE DB pair of
//! `examples/scenes/7008ce-db-pair.toml` publishes at its reference point the wrench, K and
//! C a single bearing publishes, its rows' own outputs, and the set module's physics; bad
//! set scenes are refused naming the field.

use raceway::component::variables::by_name;
use raceway::models::set::{bearing_by_name, Arrangement, Preload, Set, SetSpec};
use raceway::Component;

const PAIR: &str = include_str!("../examples/scenes/7008ce-db-pair.toml");

fn get(c: &mut Component, name: &str) -> f64 {
    c.get_real(by_name(name).unwrap().vr).unwrap()
}

fn set(c: &mut Component, name: &str, v: f64) {
    c.set_real(by_name(name).unwrap().vr, v).unwrap();
}

/// The pair at `q` (m, rad), `omega` (rad/s), scene text modified by `edit`.
fn pair_at(edit: impl Fn(String) -> String, q: [f64; 5], omega: f64) -> Component {
    let mut c = Component::from_text(&edit(PAIR.to_string())).unwrap();
    for (n, v) in ["shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry"]
        .iter()
        .zip(q)
    {
        set(&mut c, n, v);
    }
    for n in ["shaft.vx", "shaft.vy", "shaft.vz", "shaft.wx", "shaft.wy"] {
        set(&mut c, n, 0.0);
    }
    set(&mut c, "shaft.omega", omega);
    c.refresh_outputs().unwrap();
    c
}

fn spec(preload: Preload) -> SetSpec {
    let b = bearing_by_name("7008CE", "b").unwrap();
    SetSpec::pair(&b, Arrangement::Db, 0.0, preload).unwrap()
}

/// At zero motion the rigidly preloaded pair carries equal and opposite row loads (the
/// preload, 300 N, each) and no net force; the wrench at the reference point is the sum of
/// the rows' forces carried there (`M = M_r + r_r x F_r`) at a general motion; the life
/// of the pair is the rows' system life and its safety the smaller row's.
#[test]
fn a_preloaded_pair_balances_at_rest_and_its_wrench_is_its_rows_carried_to_the_reference() {
    let mut c = pair_at(|s| s, [0.0; 5], 0.0);
    let (f0, f1) = (get(&mut c, "row0.force.z"), get(&mut c, "row1.force.z"));
    assert!((f0 + 300.0).abs() < 1e-6 * 300.0, "{f0}");
    assert!((f1 - 300.0).abs() < 1e-6 * 300.0, "{f1}");
    assert!(get(&mut c, "force.z").abs() < 1e-9 * 300.0);
    assert_eq!(get(&mut c, "row0.lift_off"), 0.0);
    let a0 = get(&mut c, "row0.contact_angle");
    let a1 = get(&mut c, "row1.contact_angle");
    assert!((a0 - a1).abs() < 1e-9, "{a0} {a1}");
    // 7008CE: 15 degrees nominal, a little more under the preload.
    assert!(
        (15f64.to_radians()..20f64.to_radians()).contains(&a0),
        "{a0}"
    );

    let q = [2e-6, -5e-6, 4e-6, 1e-4, -2e-4];
    let mut c = pair_at(|s| s, q, 1256.6);
    let s = spec(Preload::Force(300.0));
    let z: Vec<f64> = s.rows.iter().map(|r| r.position).collect();
    let row = |c: &mut Component, i: usize, k: &str| get(c, &format!("row{i}.{k}"));
    let mut sum = [0.0; 5];
    for (i, &zr) in z.iter().enumerate() {
        let f = [
            row(&mut c, i, "force.x"),
            row(&mut c, i, "force.y"),
            row(&mut c, i, "force.z"),
            row(&mut c, i, "moment.x"),
            row(&mut c, i, "moment.y"),
        ];
        sum[0] += f[0];
        sum[1] += f[1];
        sum[2] += f[2];
        sum[3] += f[3] - zr * f[1];
        sum[4] += f[4] + zr * f[0];
    }
    for (k, n) in ["force.x", "force.y", "force.z", "moment.x", "moment.y"]
        .iter()
        .enumerate()
    {
        let v = get(&mut c, n);
        assert!(
            (v - sum[k]).abs() <= 1e-9 * (1.0 + v.abs()),
            "{n}: {v} vs {}",
            sum[k]
        );
    }
    // Life: the rows' system life, shorter than the shorter row's.
    let (l0, l1) = (row(&mut c, 0, "life.L10"), row(&mut c, 1, "life.L10"));
    let l = get(&mut c, "life.L10");
    let e = 10.0 / 9.0;
    let expect = (l0.powf(-e) + l1.powf(-e)).powf(-1.0 / e);
    assert!(
        (l - expect).abs() < 1e-9 * expect && l < l0.min(l1),
        "{l} {l0} {l1}"
    );
}

/// K at the reference point is the set module's (the same rows and preload, its balls at
/// fixed azimuths; the component's at the kinematic cage's: the same to the ball-passing
/// ripple, below 1 % for the axial and tilt terms), and the axial stiffness from two small
/// axial displacements (central difference of force.z) is K.z.z within 1 %.
#[test]
fn the_pairs_stiffness_is_the_set_modules() {
    let w = 1256.6;
    let mut set = Set::new(&spec(Preload::Force(300.0))).unwrap();
    let e = set.evaluate(&[0.0; 5], w).unwrap();
    let mut c = pair_at(|s| s, [0.0; 5], w);
    for (i, j, name) in [(2, 2, "K.z.z"), (3, 3, "K.rx.rx"), (0, 0, "K.x.x")] {
        let k = get(&mut c, name);
        let ks = e.stiffness[i][j];
        assert!((k - ks).abs() < 0.01 * ks.abs(), "{name}: {k} vs {ks}");
    }
    let dz = 0.2e-6;
    let fp = get(&mut pair_at(|s| s, [0.0, 0.0, dz, 0.0, 0.0], w), "force.z");
    let fm = get(&mut pair_at(|s| s, [0.0, 0.0, -dz, 0.0, 0.0], w), "force.z");
    let kd = -(fp - fm) / (2.0 * dz);
    let kzz = e.stiffness[2][2];
    assert!((kd - kzz).abs() < 0.01 * kzz, "{kd} vs {kzz}");
    // DB pair: the axial stiffness is the two rows' at the preload point (each row's own).
    assert!(kzz > 0.0);
}

/// A constant-force spring keeps the preload: pushing the shaft axially, the rows' loads
/// change by the spring's small stiffness only, and K condenses the spring out (K.z.z far
/// below the rigid pair's).
#[test]
fn a_spring_preloaded_pair_keeps_its_preload() {
    let spring = |s: String| s.replace("preload_n = 300", "preload_n = 300\nspring_n_per_um = 1");
    let mut c = pair_at(spring, [0.0; 5], 0.0);
    let f1 = get(&mut c, "row1.force.z");
    assert!((f1 - 300.0).abs() < 1e-6 * 300.0, "{f1}");
    let mut c = pair_at(spring, [0.0, 0.0, 5e-6, 0.0, 0.0], 0.0);
    let (f0, f1) = (get(&mut c, "row0.force.z"), get(&mut c, "row1.force.z"));
    // The spring moves 5 µm at most: 5 N.
    assert!((f1 - 300.0).abs() < 5.5, "{f1}");
    let fz = get(&mut c, "force.z");
    assert!((fz - (f0 + f1)).abs() < 1e-9 * 300.0);
    let k_spring = get(&mut c, "K.z.z");
    let mut rigid = pair_at(|s| s, [0.0, 0.0, 5e-6, 0.0, 0.0], 0.0);
    assert!(k_spring < 0.8 * get(&mut rigid, "K.z.z"));
    // The set module agrees.
    let mut s = Set::new(&spec(Preload::Spring {
        stiffness: 1e6,
        force: 300.0,
    }))
    .unwrap();
    let e = s.evaluate(&[0.0, 0.0, 5e-6, 0.0, 0.0], 0.0).unwrap();
    assert!(
        (e.force[2] - fz).abs() < 0.01 * fz.abs().max(1.0),
        "{} vs {fz}",
        e.force[2]
    );
}

/// The ring level runs the set too (rows on the 5-DOF ring of massless balls) and agrees
/// with the quasi-static level at rest; load-driven, the pair's static start balances the
/// load.
#[test]
fn the_ring_level_and_load_driven_sets() {
    let ring = |s: String| s.replace("level = \"quasi_static\"", "level = \"ring\"\nring_dof = 5");
    let q = [0.0, -5e-6, 5e-6, 0.0, 0.0];
    let mut r = pair_at(ring, q, 0.0);
    let mut s = pair_at(|s| s, q, 0.0);
    for n in ["force.y", "force.z", "moment.x"] {
        let (a, b) = (get(&mut r, n), get(&mut s, n));
        assert!(
            (a - b).abs() < 0.02 * b.abs().max(10.0),
            "{n}: ring {a}, qs {b}"
        );
    }
    let load = PAIR
        .replace("causality = \"motion\"", "causality = \"load\"")
        .replace(
            "initial = { \"shaft.y\" = -5e-6, \"shaft.z\" = 5e-6 }",
            "initial = { \"load.y\" = -500.0, \"load.z\" = 400.0 }",
        );
    let mut c = Component::from_text(&load).unwrap();
    for n in ["load.x", "load.mx", "load.my"] {
        set(&mut c, n, 0.0);
    }
    set(&mut c, "load.y", -500.0);
    set(&mut c, "load.z", 400.0);
    c.refresh_outputs().unwrap();
    assert!((get(&mut c, "force.y") - 500.0).abs() < 1e-3 * 500.0);
    assert!((get(&mut c, "force.z") + 400.0).abs() < 1e-3 * 400.0);
    assert!(get(&mut c, "moment.x").abs() < 1e-3);
    c.do_step(0.0, 1e-4).unwrap();
    assert!((get(&mut c, "force.z") + 400.0).abs() < 0.05 * 400.0);
}

/// Bad set scenes are refused naming the field and what is supported.
#[test]
fn bad_set_scenes_are_refused_by_field() {
    let refused = |edit: &dyn Fn(String) -> String| {
        Component::from_text(&edit(PAIR.to_string()))
            .unwrap_err()
            .to_string()
    };
    let e = refused(&|s| s.replace("level = \"quasi_static\"", "level = \"ring\""));
    assert!(e.contains("model.ring_dof") && e.contains("5"), "{e}");
    let e = refused(&|s| s.replace("level = \"quasi_static\"", "level = \"skidding\""));
    assert!(
        e.contains("model.level") && e.contains("quasi_static or ring"),
        "{e}"
    );
    let e = refused(&|s| s.replace("spacer_mm = 0", "spacer_mm = -1"));
    assert!(e.contains("set.spacer_mm"), "{e}");
    let rows = |a: f64, b: f64| {
        move |s: String| {
            s.replace(
                "arrangement = \"db\"",
                &format!(
                    "row = [{{ bearing = \"7008CE\", position_mm = {a}, orientation = 1 }}, \
                     {{ bearing = \"7008CE\", position_mm = {b}, orientation = -1 }}]"
                ),
            )
        }
    };
    let e = refused(&rows(0.0, 10.0));
    assert!(
        e.contains("set.row[1].position_mm") && e.contains("overlap"),
        "{e}"
    );
    let nu = |s: String| {
        rows(-10.0, 10.0)(s)
            .replace("\"7008CE\", position_mm", "\"NU206\", position_mm")
            .replace("preload_n = 300", "")
    };
    let e = refused(&nu);
    assert!(e.contains("set.row") && e.contains("axial"), "{e}");
    let e = refused(&|s| s.replace("preload_n = 300", "preload_n = 300\npreload_offset_um = 5"));
    assert!(e.contains("set.preload_n"), "{e}");
    let e = refused(&|s| {
        s.replace(
            "[model]",
            "[effects]\nball_spacing = { scatter = 0.1 }\n[model]",
        )
        .replace("level = \"quasi_static\"", "level = \"ring\"\nring_dof = 5")
    });
    assert!(e.contains("effects") && e.contains("set"), "{e}");
}
