//! Behaviour of the co-simulation component: transactions, state round trips, bad input,
//! and the ring level through the component against the physics directly.

#[path = "common/outputs.rs"]
mod outputs;
use outputs::outputs;
use raceway::component::{index_of, variables, Component};
use raceway::error::Error;

const RING_MOTION: &str = r#"
bearing = "6205"
[model]
level = "ring"
contact_damping = 200.0
[inputs]
speed_rpm = 1750.0040922612443
initial = { "shaft.x" = 0.0, "shaft.y" = -8e-6, "shaft.z" = 0.0, "shaft.rx" = 0.0, "shaft.ry" = 0.0,
            "shaft.vx" = 0.0, "shaft.vy" = 0.0, "shaft.vz" = 0.0, "shaft.wx" = 0.0, "shaft.wy" = 0.0 }
"#;

const RING_LOAD: &str = r#"
bearing = { preset = "6205", clearance_um = 10.0 }
[model]
level = "ring"
causality = "load"
contact_damping = 3000.0
attached_mass_kg = 1.0
[inputs]
speed_rpm = 1750.0
initial = { "load.x" = 0.0, "load.y" = -1000.0, "load.z" = 0.0, "load.mx" = 0.0, "load.my" = 0.0 }
"#;

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

/// Macro steps `range` of `h` (step i from t = i h).
fn steps(c: &mut Component, range: std::ops::Range<usize>, h: f64) {
    for i in range {
        c.do_step(i as f64 * h, h).unwrap();
    }
}

#[test]
fn restored_state_continues_bit_for_bit() {
    let mut c = Component::from_text(RING_LOAD).unwrap();
    let h = 1e-4;
    steps(&mut c, 0..20, h);
    let saved = c.get_state();
    let bytes = c.serialize_state();
    steps(&mut c, 20..40, h);
    let a = outputs(&mut c);
    c.set_state(&saved).unwrap();
    steps(&mut c, 20..40, h);
    assert_eq!(a, outputs(&mut c), "set_state continues identically");
    // Another instance of the same scene, restored from bytes.
    let mut d = Component::from_text(RING_LOAD).unwrap();
    d.deserialize_state(&bytes).unwrap();
    steps(&mut d, 20..40, h);
    assert_eq!(
        a,
        outputs(&mut d),
        "deserialised state continues identically"
    );
    // A state of another scene is refused.
    let mut other = Component::from_text(RING_MOTION).unwrap();
    assert!(other.deserialize_state(&bytes).is_err());
}

/// The force derivatives are computed when first read (a step leaves them pending): read
/// from a state restored from bytes they are the same bits as from the live component,
/// and reading them changes nothing else (outputs and the continuation are bit for bit
/// those of a component whose derivatives were never read).
#[test]
fn force_derivatives_read_late_are_those_of_the_step_and_change_nothing() {
    let names = ["force.x", "force.y", "force.z", "moment.x", "moment.y"];
    let h = 1e-4;
    let mut c = Component::from_text(RING_LOAD).unwrap();
    steps(&mut c, 0..20, h);
    let bytes = c.serialize_state();
    let d1: Vec<u64> = names
        .iter()
        .map(|n| c.get_output_derivative(vr(n), 1).unwrap().to_bits())
        .collect();
    assert!(f64::from_bits(d1[1]).abs() > 0.0, "the ring is moving");
    let mut d = Component::from_text(RING_LOAD).unwrap();
    d.deserialize_state(&bytes).unwrap();
    let d2: Vec<u64> = names
        .iter()
        .map(|n| d.get_output_derivative(vr(n), 1).unwrap().to_bits())
        .collect();
    assert_eq!(d1, d2);
    let mut e = Component::from_text(RING_LOAD).unwrap();
    e.deserialize_state(&bytes).unwrap();
    assert_eq!(outputs(&mut c), outputs(&mut e));
    steps(&mut c, 20..30, h);
    steps(&mut e, 20..30, h);
    assert_eq!(outputs(&mut c), outputs(&mut e));
}

#[test]
fn failed_step_leaves_state_unchanged_and_says_why() {
    let mut c = Component::from_text(RING_LOAD).unwrap();
    c.do_step(0.0, 1e-4).unwrap();
    let before = c.get_state();
    // A huge step needs more sub-steps than the scene allows.
    let e = c.do_step(1e-4, 1e3).unwrap_err();
    assert!(matches!(e, Error::Budget { .. }), "{e}");
    assert!(e.to_string().contains("max_substeps"), "{e}");
    assert_eq!(c.get_state(), before);
    // Still usable.
    c.do_step(1e-4, 1e-4).unwrap();
}

#[test]
fn bad_calls_are_refused_and_the_component_stays_usable() {
    let mut c = Component::from_text(RING_MOTION).unwrap();
    let before = c.get_state();
    for (t, h, why) in [
        (0.0, 0.0, "> 0"),
        (0.0, -1e-3, "> 0"),
        (0.0, f64::NAN, "finite"),
        (f64::INFINITY, 1e-3, "finite"),
    ] {
        let e = c.do_step(t, h).unwrap_err().to_string();
        assert!(e.contains(why), "{e}");
    }
    assert!(c
        .set_real(vr("shaft.x"), f64::NAN)
        .unwrap_err()
        .to_string()
        .contains("shaft.x"));
    assert!(c
        .set_real(vr("force.x"), 1.0)
        .unwrap_err()
        .to_string()
        .contains("not an input"));
    assert!(
        c.set_real(vr("load.x"), 1.0).is_err(),
        "load inputs are not inputs when motion-driven"
    );
    assert!(c.set_real(99_999, 1.0).is_err());
    assert_eq!(c.get_state(), before);
    c.do_step(0.0, 1e-3).unwrap();
    let e = c.do_step(0.5e-3, 1e-3).unwrap_err().to_string();
    assert!(e.contains("backwards") || e.contains("jump"), "{e}");
    c.do_step(1e-3, 1e-3).unwrap();
    assert!((c.time() - 2e-3).abs() < 1e-15);
}

#[test]
fn do_step_before_inputs_holds_the_scenes_values() {
    // Nothing in the scene, nothing set: every input holds 0 and the ring steps.
    let mut c = Component::from_text("bearing = \"6205\"\n[model]\nlevel = \"ring\"\n").unwrap();
    c.do_step(0.0, 1e-3).unwrap();
    assert_eq!(c.get_real(vr("shaft.omega")).unwrap(), 0.0);
    assert_eq!(c.get_real(vr("shaft.x")).unwrap(), 0.0);
}

#[test]
fn bad_scenes_name_the_field() {
    for (text, field) in [
        ("bearing = \"6409\"", "6409"),
        ("bearing = \"6205\"\nbogus = 1", "bogus"),
        ("bearing = \"6205\"\n[solver]\nrtol = -1.0", "solver.rtol"),
        (
            "bearing = { preset = \"6205\", inner_curvature = 0.4 }",
            "bearing.inner_curvature",
        ),
        (
            "bearing = { preset = \"6205\", ball_count = 40 }",
            "bearing.ball_count",
        ),
        (
            "bearing = \"6205\"\n[model]\nring_dof = 3",
            "model.ring_dof",
        ),
        (
            "bearing = \"6205\"\n[inputs]\ninitial = { \"force.x\" = 1.0 }",
            "force.x",
        ),
        ("{ \"bearing\": 12 }", "scene"),
        ("bearing = ", "scene"),
    ] {
        let e = Component::from_text(text).unwrap_err().to_string();
        assert!(e.contains(field), "{text:?} -> {e}");
    }
}

/// Motion-driven ring level: the component's forces equal the physics evaluated directly
/// at the cage angle the component integrated, and K/C match the directional derivative.
#[test]
fn motion_driven_ring_matches_the_model() {
    use raceway::models::ring::{RingAt, RingDof, RingEval, RingModel};
    let mut c = Component::from_text(RING_MOTION).unwrap();
    let h = 1e-3;
    c.do_step(0.0, h).unwrap();
    let b = c.bearing().clone();
    let m = RingModel::new(&b, RingDof::Two, 200.0);
    let wc = raceway::component::levels::cage_speed(&b, 183.26);
    let mut e = RingEval::default();
    m.eval(
        RingAt {
            theta_c: wc * h,
            omega_c: wc,
            q: &[0.0, -8e-6, 0.0, 0.0, 0.0],
            v: &[0.0; 5],
            t: h,
        },
        None,
        true,
        &mut e,
    );
    let fy = c.get_real(vr("force.y")).unwrap();
    assert!(
        (fy - e.wrench[1]).abs() < 1e-9 * e.wrench[1].abs(),
        "{fy} vs {}",
        e.wrench[1]
    );
    assert!(fy > 0.0, "pushed down, the bearing pushes up");
    assert_eq!(c.get_real(vr("balls.loaded")).unwrap(), e.loaded as f64);
    let mut out = [0.0];
    c.directional_derivative(&[vr("force.y")], &[vr("shaft.y")], &[1.0], &mut out)
        .unwrap();
    assert_eq!(out[0], -e.k[1][1]);
    assert!(c.get_real(vr("contact.max_pressure")).unwrap() > 1e8);
    assert!((c.get_real(vr("cage.omega")).unwrap() - wc).abs() < 1e-12);
    assert!(index_of(vr("K.y.y")).is_some());
}

/// Load-driven ring level with damping settles where the bearing force balances the
/// external load.
#[test]
fn load_driven_ring_settles_to_static_balance() {
    let mut c = Component::from_text(RING_LOAD).unwrap();
    let h = 1e-4;
    steps(&mut c, 0..600, h);
    let fy = c.get_real(vr("force.y")).unwrap();
    let y = c.get_real(vr("shaft.y")).unwrap();
    assert!((fy - 1000.0).abs() < 20.0, "force.y = {fy}");
    assert!(y < -5e-6, "the ring sags through the clearance: y = {y}");
}

/// An effect a level does not apply is refused, never silently ignored.
#[test]
fn effects_on_a_level_that_ignores_them_are_refused() {
    let e = Component::from_text(
        "bearing = \"6205\"\n[model]\nlevel = \"quasi_static\"\n[effects]\ndefects = [{ race = \"outer\", angle_deg = 0.0, width_mm = 1.0, depth_um = 20.0 }]\n",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("effects") && e.contains("ring"), "{e}");
}

/// Contact damping reaches the quasi-static level: a load-driven ring released from rest
/// rings down to the static balance with damping, and keeps rattling without it.
#[test]
fn quasi_static_contact_damping_settles_a_released_ring() {
    let scene = |c: f64| {
        format!(
            "bearing = {{ preset = \"6205\", clearance_um = 10.0 }}\n[model]\nlevel = \"quasi_static\"\ncausality = \"load\"\nstart = \"rest\"\nattached_mass_kg = 1.0\ncontact_damping = {c}\n[inputs]\nspeed_rpm = 1750.0\ninitial = {{ \"load.x\" = 0.0, \"load.y\" = -1000.0, \"load.z\" = 0.0, \"load.mx\" = 0.0, \"load.my\" = 0.0 }}\n"
        )
    };
    let spread = |c: f64| {
        let mut comp = Component::from_text(&scene(c)).unwrap();
        let h = 1e-4;
        let mut late = Vec::new();
        for i in 0..400 {
            comp.do_step(i as f64 * h, h).unwrap();
            if i >= 300 {
                late.push(comp.get_real(vr("force.y")).unwrap());
            }
        }
        let (lo, hi) = late
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &f| (a.min(f), b.max(f)));
        let mean = late.iter().sum::<f64>() / late.len() as f64;
        (mean, hi - lo)
    };
    let (mean_d, spread_d) = spread(3000.0);
    let (_, spread_0) = spread(0.0);
    assert!((mean_d - 1000.0).abs() < 20.0, "damped mean force {mean_d}");
    assert!(
        spread_d < 0.1 * spread_0,
        "damped spread {spread_d} N vs undamped {spread_0} N"
    );
}

/// The rating outputs are ISO 76/281 of the bearing force: under the default scene's pure
/// radial load `S0 = C0 / max(0.6 Fr + 0.5 Fa, Fr) = C0/Fr` and `L10 = (C/Fr)^3` exactly;
/// a centred shaft with no clearance and no load reads the documented caps and warns of
/// fewer than two loaded balls; a shaft pushed 100 µm passes ISO 76's 4 200 MPa and
/// warns, with S0 below 1.
#[test]
fn rating_outputs_follow_iso_281_and_76() {
    let text = raceway::component::scene::DEFAULT_SCENE;
    let mut c = Component::from_text(text).unwrap();
    for n in [
        "shaft.x", "shaft.z", "shaft.rx", "shaft.ry", "shaft.vx", "shaft.vy", "shaft.vz",
        "shaft.wx", "shaft.wy",
    ] {
        c.set_real(vr(n), 0.0).unwrap();
    }
    let b = c.bearing().clone();
    let r = raceway::ratings::load_ratings(&b).unwrap();
    let g = |c: &mut Component, n: &str| c.get_real(vr(n)).unwrap();
    let (fx, fy, fz) = (
        g(&mut c, "force.x"),
        g(&mut c, "force.y"),
        g(&mut c, "force.z"),
    );
    assert!(fz.abs() < 1e-9 * fy.abs(), "pure radial: {fz}");
    let fr = fx.hypot(fy);
    let s0 = g(&mut c, "safety.S0");
    let l10 = g(&mut c, "life.L10");
    assert!((s0 - r.c0 / fr).abs() < 1e-12 * s0, "{s0} vs {}", r.c0 / fr);
    assert!(
        (l10 - (r.c / fr).powi(3)).abs() < 1e-12 * l10,
        "{l10} vs {}",
        (r.c / fr).powi(3)
    );
    assert_eq!(g(&mut c, "warnings.active"), 0.0);

    for (y, s0_cap, warned) in [(0.0, true, 1.0), (-100e-6, false, 1.0)] {
        c.set_real(vr("shaft.y"), y).unwrap();
        let s0 = g(&mut c, "safety.S0");
        let l10 = g(&mut c, "life.L10");
        let p = g(&mut c, "contact.max_pressure");
        if s0_cap {
            assert_eq!(s0, raceway::ratings::S0_UNLOADED);
            assert_eq!(l10, raceway::ratings::L10_UNLOADED);
        } else {
            assert!(
                p > raceway::ratings::STATIC_PRESSURE_LIMIT && s0 < 1.0,
                "{p} {s0}"
            );
        }
        assert_eq!(g(&mut c, "warnings.active"), warned, "y = {y}, p = {p}");
    }
}

#[path = "common/cli_rows.rs"]
mod cli_rows;

/// One rule for unset inputs: a component of the default scene that is never given an
/// input holds the scene's initial values (shaft 10 µm down at 1750 rpm, the rest 0), so
/// its force at t = 0 and after one step equals the first two rows of `raceway run`.
#[test]
fn unset_inputs_hold_the_scenes_initial_values_as_the_cli_does() {
    let cli = cli_rows::default_scene_first_rows();
    let mut c = Component::from_text(raceway::component::scene::DEFAULT_SCENE).unwrap();
    let force = |c: &mut Component| [vr("force.x"), vr("force.y")].map(|v| c.get_real(v).unwrap());
    assert_eq!(c.get_real(vr("shaft.y")).unwrap(), -10e-6);
    assert_eq!(c.get_real(vr("shaft.x")).unwrap(), 0.0);
    let at0 = force(&mut c);
    c.do_step(0.0, 1e-4).unwrap();
    let at1 = force(&mut c);
    for (got, want) in [at0, at1].iter().zip(&cli) {
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g - w).abs() <= 1e-9 * cli[0][1].abs(),
                "{got:?} vs the CLI's {want:?}"
            );
        }
    }
    assert!(cli[0][1] > 500.0, "the default scene is loaded: {cli:?}");
}
