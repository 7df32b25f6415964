//! Slow physics (docs/physics.md §7, §8): race wear and thermal growth through the component.
//! Motion-driven 6012 (study \[2\]) with the shaft held off-centre, so each run is a few
//! revolutions of cheap dynamics.

use raceway::component::{variables, Component, Scene};
use raceway::models::ring::level::SlowLayout;
use raceway::models::ring::{RingAt, RingDof, RingEval, RingModel};
use raceway::models::wear;

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

/// 6012 held at `y_um` (downward) turning at `rpm`, with `effects` (TOML lines).
fn scene(y_um: f64, rpm: f64, damping: f64, effects: &str) -> Scene {
    let text = format!(
        r#"
bearing = "6012"
[model]
level = "ring"
contact_damping = {damping}
[solver]
max_substep_s = 1e-4
[inputs]
speed_rpm = {rpm:?}
initial = {{ "shaft.x" = 0.0, "shaft.y" = {y}, "shaft.z" = 0.0, "shaft.rx" = 0.0, "shaft.ry" = 0.0,
            "shaft.vx" = 0.0, "shaft.vy" = 0.0, "shaft.vz" = 0.0, "shaft.wx" = 0.0, "shaft.wy" = 0.0 }}
[effects]
{effects}
"#,
        y = -y_um * 1e-6
    );
    Scene::from_text(&text).unwrap()
}

/// Step for `revs` shaft revolutions at 2000 rpm (or `secs` when not turning), h = 2e-4 s.
fn run(s: &Scene, secs: f64) -> Component {
    let mut c = Component::new(s.clone()).unwrap();
    let h = 2e-4;
    for i in 0..(secs / h).round() as usize {
        c.do_step(i as f64 * h, h).unwrap();
    }
    c
}

const REV: f64 = 0.03; // one revolution at 2000 rpm, s

fn wear_line(extra: &str) -> String {
    let cycles = if extra.contains("cycles") {
        ""
    } else {
        ", cycles = 2"
    };
    format!("wear = {{ cells = 72, window_revs = 1.0, cycle_revs = 1e4{cycles}{extra} }}")
}

fn lubricated(rough: f64) -> String {
    format!(
        "lubrication = {{ film = \"ehl\", lubricant = \"study2\", roughness_um = {rough} }}\n{}",
        wear_line("")
    )
}

fn max_depth(c: &mut Component) -> f64 {
    c.get_real(vr("wear.max_depth")).unwrap()
}

#[test]
fn no_sliding_or_no_load_gives_no_wear() {
    // Loaded but not turning: no sliding, the accumulators stay exactly zero.
    let s = scene(12.0, 0.0, 100.0, &wear_line(", regime = \"dry\""));
    let c = run(&s, 0.01);
    let (x0, _, n) = SlowLayout::of(&s.effects, &s.validate().unwrap())
        .unwrap()
        .wear
        .unwrap();
    let st = c.get_state();
    assert!(st.x[x0..x0 + 2 * n].iter().all(|&v| v == 0.0));
    // Turning but centred inside the clearance: no ball loaded, no wear after two cycles.
    let s = scene(0.0, 2000.0, 100.0, &wear_line(", regime = \"dry\""));
    let mut c = run(&s, 2.2 * REV);
    let st = c.get_state();
    let layout = SlowLayout::of(&s.effects, &s.validate().unwrap()).unwrap();
    assert_eq!(layout.wear_cycles(&st.aux), Some(2.0));
    assert!(st.x[x0..x0 + 2 * n].iter().all(|&v| v == 0.0));
    assert_eq!(max_depth(&mut c), 0.0);
    // The same held off-centre and turning does wear.
    let s = scene(12.0, 2000.0, 100.0, &wear_line(", regime = \"dry\""));
    assert!(max_depth(&mut run(&s, 2.2 * REV)) > 0.0);
}

#[test]
fn wear_concentrates_in_the_load_zone() {
    let s = scene(12.0, 2000.0, 100.0, &wear_line(", regime = \"dry\""));
    let c = run(&s, 2.2 * REV);
    let st = c.get_state();
    let layout = SlowLayout::of(&s.effects, &s.validate().unwrap()).unwrap();
    let (outer, inner) = layout.wear_maps(&st.aux).unwrap();
    let (deep, angle) = wear::deepest(outer);
    // The shaft is pushed to -y: the load line is at 270 deg.
    assert!(
        (angle.to_degrees() - 270.0).abs() <= 5.0,
        "deepest at {}",
        angle.to_degrees()
    );
    // Outside the load zone (the upper half) the outer race is untouched.
    for (k, &d) in outer.iter().enumerate() {
        let a = 360.0 * k as f64 / 72.0;
        if (10.0..170.0).contains(&a) {
            assert_eq!(d, 0.0, "wear at {a} deg");
        }
    }
    assert!(wear::sample(outer, 270f64.to_radians()) > 0.5 * deep);
    // The inner race turns through the load zone: worn all round, more evenly.
    let (di, _) = wear::deepest(inner);
    let mean_i = inner.iter().sum::<f64>() / inner.len() as f64;
    let mean_o = outer.iter().sum::<f64>() / outer.len() as f64;
    assert!(di > 0.0 && mean_i > 0.3 * di, "inner {di} mean {mean_i}");
    assert!(mean_o < 0.5 * deep);
    println!("dry: outer deepest {deep:.3e} m at 270 deg, inner deepest {di:.3e} m");
}

#[test]
fn rougher_races_wear_faster_and_the_dry_limit_much_faster() {
    let smooth = max_depth(&mut run(
        &scene(12.0, 2000.0, 100.0, &lubricated(0.2)),
        2.2 * REV,
    ));
    let rough = max_depth(&mut run(
        &scene(12.0, 2000.0, 100.0, &lubricated(0.42)),
        2.2 * REV,
    ));
    let dry = max_depth(&mut run(
        &scene(
            12.0,
            2000.0,
            100.0,
            &format!(
            "lubrication = {{ film = \"ehl\", lubricant = \"study2\", roughness_um = 0.42 }}\n{}",
            wear_line(", regime = \"dry\"")
        ),
        ),
        2.2 * REV,
    ));
    println!("max depth: Ra 0.2 {smooth:.3e}, Ra 0.42 {rough:.3e}, dry {dry:.3e} m");
    assert!(smooth > 0.0);
    // Same slip and film-defect fraction: the ratio is the asperity shares' ratio, about
    // 5.5 at the study's contact with the restored eq. (8) (lubrication::asperity).
    assert!(rough > 2.0 * smooth, "rough {rough} vs smooth {smooth}");
    assert!(dry > 1e6 * rough, "dry {dry} vs lubricated {rough}");
}

const THERMAL: &str = "thermal = { time_scale = 2000.0, dt_s = 1.0 }";

fn capacities(s: &Scene) -> [f64; 4] {
    let b = s.validate().unwrap();
    let t = s.effects.thermal.as_ref().unwrap();
    [
        b.inner_ring_mass * b.inner_material.heat_capacity,
        b.outer_ring_mass * b.outer_material.heat_capacity,
        b.z as f64 * b.ball_mass() * b.ball_material.heat_capacity,
        t.oil_heat_capacity_j_k,
    ]
}

#[test]
fn heat_balance_closes() {
    let s = scene(12.0, 2000.0, 100.0, THERMAL);
    let mut c = run(&s, 0.05);
    let st = c.get_state();
    let th = SlowLayout::of(&s.effects, &s.validate().unwrap())
        .unwrap()
        .thermal(&st.aux)
        .unwrap()
        .to_vec();
    let cap = capacities(&s);
    let stored: f64 = (0..4).map(|k| cap[k] * th[k]).sum();
    let (generated, removed) = (th[5], th[6]);
    println!(
        "generated {generated:.3} J, removed {removed:.3} J, stored {stored:.3} J, \
         rises {:?} K, power {} W",
        &th[..4],
        c.get_real(vr("power.loss")).unwrap()
    );
    assert!(generated > 0.0 && removed > 0.0 && stored > 0.0);
    assert!(
        (generated - removed - stored).abs() < 1e-9 * generated,
        "imbalance {}",
        generated - removed - stored
    );
    // Friction torque opposes the rotation and carries the power.
    let omega = 2000.0 * std::f64::consts::TAU / 60.0;
    let torque = c.get_real(vr("torque.z")).unwrap();
    let power = c.get_real(vr("power.loss")).unwrap();
    assert!(torque < 0.0 && (torque * omega + power).abs() < 1e-12 * power);
}

#[test]
fn growth_equals_alpha_dt_d_and_closes_the_clearance() {
    let s = scene(12.0, 2000.0, 0.0, THERMAL);
    let mut c = run(&s, 0.05);
    c.refresh_outputs().unwrap();
    let st = c.get_state();
    let th = SlowLayout::of(&s.effects, &s.validate().unwrap())
        .unwrap()
        .thermal(&st.aux)
        .unwrap()
        .to_vec();
    let b = s.validate().unwrap();
    let gamma = b.d * b.nominal_contact_angle().cos() / b.dm;
    let (di, d_o) = (b.dm * (1.0 - gamma), b.dm * (1.0 + gamma));
    let ui = b.inner_material.thermal_expansion * th[0] * di;
    let uo = b.outer_material.thermal_expansion * th[1] * d_o;
    let ub = b.ball_material.thermal_expansion * th[2] * b.d;
    let change = uo - ui - 2.0 * ub;
    println!("growth: u_i {ui:.3e} u_o {uo:.3e} u_b {ub:.3e} m, clearance change {change:.3e} m");
    assert!(ui > 0.0 && uo > 0.0 && ub > 0.0);
    assert!((th[8] - change).abs() <= 1e-15 * change.abs().max(1e-9));
    // The forces are the plain model's with the operating clearance.
    let mut hot = b.clone();
    hot.pd = b.pd + change;
    let model = RingModel::new(&hot, RingDof::Two, 0.0);
    let mut e = RingEval::default();
    let q = [0.0, -12e-6, 0.0, 0.0, 0.0];
    model.eval(
        RingAt {
            theta_c: st.x[0],
            omega_c: 0.0,
            q: &q,
            v: &[0.0; 5],
            t: 0.0,
        },
        None,
        false,
        &mut e,
    );
    let fy = c.get_real(vr("force.y")).unwrap();
    assert!(
        (fy - e.wrench[1]).abs() < 1e-9 * fy.abs(),
        "{fy} vs {}",
        e.wrench[1]
    );
    let mut cold = RingEval::default();
    RingModel::new(&b, RingDof::Two, 0.0).eval(
        RingAt {
            theta_c: st.x[0],
            omega_c: 0.0,
            q: &q,
            v: &[0.0; 5],
            t: 0.0,
        },
        None,
        false,
        &mut cold,
    );
    assert!(
        change < 0.0 && fy.abs() > cold.wrench[1].abs(),
        "tighter when warm"
    );
}

#[test]
fn slow_state_survives_get_set_serialise_bit_for_bit() {
    let s = scene(
        12.0,
        2000.0,
        100.0,
        &format!("{}\n{THERMAL}", wear_line(", regime = \"dry\"")),
    );
    let h = 2e-4;
    let mut a = Component::new(s.clone()).unwrap();
    for i in 0..200 {
        a.do_step(i as f64 * h, h).unwrap();
    }
    assert!(max_depth(&mut a) > 0.0, "a wear cycle has happened");
    let bytes = a.serialize_state();
    let mut b = Component::new(s.clone()).unwrap();
    b.deserialize_state(&bytes).unwrap();
    let mut c = Component::new(s).unwrap();
    c.set_state(&a.get_state()).unwrap();
    for i in 200..400 {
        for k in [&mut a, &mut b, &mut c] {
            k.do_step(i as f64 * h, h).unwrap();
        }
    }
    let (sa, sb, sc) = (a.get_state(), b.get_state(), c.get_state());
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&sa.x), bits(&sb.x));
    assert_eq!(bits(&sa.aux), bits(&sb.aux));
    assert_eq!(bits(&sa.outputs), bits(&sb.outputs));
    assert_eq!(bits(&sa.aux), bits(&sc.aux));
    assert_eq!(bits(&sa.outputs), bits(&sc.outputs));
}

#[test]
fn switching_the_effect_off_recovers_the_plain_model() {
    // Off: the scene without the slow effects is the plain level (same arithmetic).
    let plain = scene(12.0, 2000.0, 100.0, "");
    assert!(plain.effects.is_off());
    // On but inert (no cycle applied, no growth): same forces to rounding, no wear, and the
    // only slow outputs are the power and torque.
    let inert = scene(
        12.0,
        2000.0,
        100.0,
        &format!(
            "{}\nthermal = {{ growth_factor = 0.0 }}",
            wear_line(", cycles = 0")
        ),
    );
    assert!(!inert.effects.is_off());
    let h = 2e-4;
    let mut p = Component::new(plain).unwrap();
    let mut q = Component::new(inert).unwrap();
    for i in 0..100 {
        p.do_step(i as f64 * h, h).unwrap();
        q.do_step(i as f64 * h, h).unwrap();
        for name in ["force.x", "force.y", "contact.max_load"] {
            let (a, b) = (p.get_real(vr(name)).unwrap(), q.get_real(vr(name)).unwrap());
            assert!(
                (a - b).abs() <= 1e-9 * a.abs().max(1.0),
                "{name}: {a} vs {b}"
            );
        }
    }
    assert_eq!(max_depth(&mut q), 0.0);
    assert_eq!(p.get_real(vr("power.loss")).unwrap(), 0.0);
    assert!(q.get_real(vr("power.loss")).unwrap() > 0.0);
}
