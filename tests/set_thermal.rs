//! A bearing set with the thermal network (docs/physics.md §S1): each row's ring level feeds
//! its own network with its losses, and the rows' ring temperatures move a rigid preload
//! through the same clearance formulas as temperatures given by hand
//! ([`raceway::models::set::Set::set_ring_temperatures`]). The shipped scene
//! `examples/scenes/7008ce-db-pair-thermal.toml`: a 7008CE DB pair, 300 N rigid preload,
//! 6000 rpm, shaft centred.

use raceway::component::Scene;
use raceway::models::set::level::{row_thermal_blocks, SetLevel, REFORM_K};
use raceway::models::set::{RingTemperatures, Set};
use raceway::seam::{LevelModel, LevelOutputs, Motion, Point};
use raceway::Component;

const SCENE: &str = include_str!("../examples/scenes/7008ce-db-pair-thermal.toml");

/// The set's level of scene `text`, with its states and memory initialised at the centred
/// shaft turning at the scene's speed, and that motion.
fn level(text: &str) -> (SetLevel, Vec<f64>, Vec<f64>, Motion) {
    let scene = Scene::from_text(text).unwrap();
    let b = scene.validate().unwrap();
    let spec = scene.set_spec(&b).unwrap().unwrap();
    let mut l = SetLevel::new(
        &scene.level_args(&b),
        &spec,
        raceway::models::ring::level::build,
    )
    .unwrap();
    let m = Motion {
        q: [0.0; 5],
        v: [0.0; 5],
        omega: scene.inputs.speed_rpm * std::f64::consts::PI / 30.0,
    };
    let mut x = vec![0.0; l.n_states()];
    let mut aux = vec![0.0; l.n_aux()];
    l.init(&m, &mut x, &mut aux).unwrap();
    (l, x, aux, m)
}

/// Row 1's thrust (the row facing -z, which slides on a spring preload) at `0.02 k` s, `k`
/// = 0 to 50 (10 s of heating each): the first and the last.
fn warmed(l: &mut SetLevel, x: &[f64], aux: &mut [f64], m: &Motion) -> (f64, f64) {
    let p0 = preload_at(l, x, aux, m, 0.0)[1];
    let mut p = p0;
    for k in 1..=50 {
        p = preload_at(l, x, aux, m, 0.02 * k as f64)[1];
    }
    (p0, p)
}

/// The rows' thrust (row 0's axial force on the shaft, toward -z, sign flipped), N, at
/// the communication point `t` (the networks advance to it).
fn preload_at(l: &mut SetLevel, x: &[f64], aux: &mut [f64], m: &Motion, t: f64) -> [f64; 2] {
    let mut out = LevelOutputs::default();
    l.outputs(Point::new(t, m, x, aux), &mut out).unwrap();
    let r = l.rows();
    [-r[0].force[2], r[1].force[2]]
}

/// The pair warms at speed; its inner rings run warmer than the outer (the network's own
/// answer: the balls, hottest, feed both rings; the inner ring has the weaker path to the
/// ambient, through the shaft), both rows alike; the rigid preload rises with time,
/// monotonically, towards a limit, and that limit is the preload the hand-given-temperature
/// path (the quasi-static set at those temperatures, `preload.rs`) gives: 1e-4 apart, as
/// the two at the temperature the pair is assembled at.
#[test]
fn rigid_pair_warms_and_its_preload_rises_to_the_hand_given_temperatures_value() {
    let (mut l, x, mut aux, m) = level(SCENE);
    let mut last = preload_at(&mut l, &x, &mut aux, &m, 0.0);
    let p0 = last[0];
    assert!((p0 - 300.0).abs() < 0.01 * 300.0, "{p0}");
    let mut history = vec![p0];
    // 0.02 s of dynamics = 10 s of heating each (time_scale 500), to 1 s (500 s).
    for k in 1..=50 {
        let p = preload_at(&mut l, &x, &mut aux, &m, 0.02 * k as f64);
        assert!(
            (p[0] - p[1]).abs() < 1e-9 * p[0],
            "rows equal and opposite: {p:?}"
        );
        assert!(p[0] >= last[0] * (1.0 - 1e-12), "{} then {}", last[0], p[0]);
        history.push(p[0]);
        last = p;
    }
    let temps = l.row_temperatures(&aux).unwrap();
    for t in &temps {
        assert!(t[0] > t[1] + 1.0 && t[1] > 20.5, "{t:?}");
        assert!((t[0] - temps[0][0]).abs() < 1e-9, "{temps:?}");
    }
    // The summary's reading of the memory is the level's.
    let blocks = row_thermal_blocks(&aux, 2);
    assert!((20.0 + blocks[1][0] - temps[1][0]).abs() < 1e-12);
    let n = history.len();
    let pf = history[n - 1];
    assert!(pf > 1.4 * p0, "{p0} -> {pf}");
    // Settled: the last 100 s move it by less than 1e-5 of the rise.
    assert!(pf - history[n - 11] < 1e-5 * (pf - p0), "{history:?}");
    // Half way (after 100 s) it has covered most, not all, of the rise.
    assert!(history[10] > p0 + 0.5 * (pf - p0) && history[10] < pf);
    // The rows are formed at the network's temperatures (within REFORM_K).
    let formed = l.formed_temperatures().unwrap();
    let f = formed[0];
    assert!((f.inner_c - temps[0][0]).abs() <= REFORM_K);
    assert!((f.outer_c - temps[0][1]).abs() <= REFORM_K);
    // The hand-given path at those temperatures (the rows alike: row 0's).
    let scene = Scene::from_text(SCENE).unwrap();
    let b = scene.validate().unwrap();
    let spec = scene.set_spec(&b).unwrap().unwrap();
    let hand = |t: RingTemperatures| {
        let mut s = Set::new(&spec).unwrap();
        s.set_ring_temperatures(t).unwrap();
        s.solve(&[0.0; 5], 0.0).unwrap().rows[0].axial_load
    };
    let cold = hand(RingTemperatures::default());
    let hot = hand(f);
    // The ring level and the quasi-static set agree as assembled ...
    let agree = (p0 - cold).abs() / cold;
    assert!(agree < 1e-4, "{p0} {cold}");
    // ... and at the network's temperatures.
    assert!(
        (pf - hot).abs() / hot < 1e-4,
        "{pf} against {hot} (cold {agree:e})"
    );
    eprintln!("preload {p0:.4} -> {pf:.4} N (hand-given path {hot:.4} N, as assembled {cold:.4} N); temperatures {:?} °C", temps[0]);
    // The same path, by hand, on the ring level: the same bits.
    let (mut h, ..) = level(SCENE);
    for (i, &t) in formed.iter().enumerate() {
        h.set_row_temperatures(i, t).unwrap();
    }
    assert_eq!(h.row_offsets(), l.row_offsets());
}

/// A constant-force (spring) preload keeps its force while the rows warm: the spring
/// (1 N/µm) lets the rows facing -z slide, and their load (the spring's force) changes by
/// far less than a rigid preload's (the shaft is held: the row facing +z, clamped between
/// the held shaft and the housing, is not the spring's).
#[test]
fn spring_preload_keeps_its_force_while_the_pair_warms() {
    let spring = SCENE.replace("preload_n = 300", "preload_n = 300\nspring_n_per_um = 1");
    assert_ne!(spring, SCENE);
    let run = |text: &str| {
        let (mut l, x, mut aux, m) = level(text);
        let (p0, pf) = warmed(&mut l, &x, &mut aux, &m);
        (p0, pf, l.row_temperatures(&aux).unwrap()[0])
    };
    let (r0, rf, rt) = run(SCENE);
    let (s0, sf, st) = run(&spring);
    assert!(rt[0] > 21.0 && st[0] > 21.0, "{rt:?} {st:?}");
    eprintln!("spring {s0:.4} -> {sf:.4} N, rigid {r0:.4} -> {rf:.4} N");
    assert!((s0 - 300.0).abs() < 0.01 * 300.0, "{s0}");
    assert!(
        (sf - s0).abs() < 0.02 * (rf - r0),
        "spring {s0} -> {sf}, rigid {r0} -> {rf}"
    );
}

/// `growth_factor = 0`: the networks run (the pair warms) and the preload stays as
/// assembled; other effects beside the network, another growth factor and a set at the
/// quasi-static level are refused naming the field.
#[test]
fn growth_off_keeps_the_preload_and_bad_scenes_are_refused() {
    let off = SCENE.replace(
        "contact_conductance_w_k = 1.0",
        "contact_conductance_w_k = 1.0, growth_factor = 0.0",
    );
    assert_ne!(off, SCENE);
    let (mut l, x, mut aux, m) = level(&off);
    let (p0, pf) = warmed(&mut l, &x, &mut aux, &m);
    assert!(l.row_temperatures(&aux).unwrap()[0][0] > 21.0);
    assert_eq!(p0.to_bits(), pf.to_bits());
    let refused = |text: String, field: &str| {
        let e = Component::from_text(&text).unwrap_err().to_string();
        assert!(e.contains(field), "{field}: {e}");
    };
    refused(
        SCENE.replace("growth_factor", "x").replace(
            "contact_conductance_w_k = 1.0",
            "contact_conductance_w_k = 1.0, growth_factor = 0.5",
        ),
        "effects.thermal.growth_factor",
    );
    refused(
        SCENE.replace(
            "[effects]",
            "[effects]\nwaviness = [{ race = \"outer\", order = 12, amplitude_um = 0.3, phase_deg = 0.0 }]",
        ),
        "`effects`",
    );
    refused(
        SCENE.replace("level = \"ring\"\nring_dof = 5", "level = \"quasi_static\""),
        "model.level",
    );
}
