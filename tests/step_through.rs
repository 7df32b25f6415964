//! A window integrated straight through (`Component::step_through`): the outputs at the
//! communication points from dense output agree with the coupling loop's, the component is
//! left as `do_step` over the window leaves it, the force error converges with the
//! tolerance, and refused or failed calls change nothing.

use raceway::component::{variables, Component, Method};
use raceway::error::Error;
use raceway::report::work_precision::cases;
use raceway::report::{drive, drive_through, force_error};

const RING_MOTION: &str = r#"
bearing = "6205"
[model]
level = "ring"
contact_damping = 200.0
[inputs]
speed_rpm = 1750.004092
initial = { "shaft.x" = 0.0, "shaft.y" = -8e-6, "shaft.z" = 0.0, "shaft.rx" = 0.0, "shaft.ry" = 0.0,
            "shaft.vx" = 0.0, "shaft.vy" = 0.0, "shaft.vz" = 0.0, "shaft.wx" = 0.0, "shaft.wy" = 0.0 }
"#;

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

fn case(name: &str) -> raceway::report::work_precision::Case {
    cases().into_iter().find(|c| c.name == name).unwrap()
}

fn ring(method: Method, rtol: f64) -> Component {
    Component::new(case("6205-2dof").scene_with(method, rtol).unwrap()).unwrap()
}

/// The released 6205 ring (contact onsets, ring-down) at tight tolerance: straight through
/// and the coupling loop are two integrations of the same equations, each within its
/// tolerance of the solution, so their forces agree to about that tolerance (measured:
/// relative L2 1.3e-8, peak 7.0e-8 for DOPRI5 at rtol 1e-10; 1.7e-9, 8.6e-9 for RODAS4
/// at 1e-9; asserted L2 1e-6, peak 1e-5).
#[test]
fn straight_through_agrees_with_the_coupling_loop_at_tight_tolerance() {
    let c = case("6205-2dof");
    for (method, rtol) in [(Method::Dopri5, 1e-10), (Method::Rosenbrock, 1e-9)] {
        let (looped, _) = drive(&mut ring(method, rtol), c.t_end, c.h, &[], None).unwrap();
        let (through, _) = drive_through(&mut ring(method, rtol), c.t_end, c.h).unwrap();
        assert_eq!(through.t.len(), looped.t.len());
        let (l2, peak) = force_error(&through, &looped).unwrap();
        assert!(
            l2 < 1e-6 && peak < 1e-5,
            "{method:?}: L2 {l2:e}, peak {peak:e}"
        );
    }
}

/// The force error against a tight reference falls as the tolerance tightens, for both
/// integrators (the dense output is not the accuracy limit). Measured at rtol 1e-4, 1e-6,
/// 1e-8: DOPRI5 1.4e-3, 1.0e-4, 8.1e-7; RODAS4 3.5e-4, 2.5e-6, 2.2e-8 (asserted: each two
/// decades at least 5× smaller, and below 1e-5 at 1e-8).
#[test]
fn straight_through_force_error_converges_with_rtol() {
    let c = case("6205-2dof");
    let (reference, _) = drive_through(&mut ring(Method::Dopri5, 1e-12), c.t_end, c.h).unwrap();
    for method in [Method::Dopri5, Method::Rosenbrock] {
        let errs: Vec<f64> = [1e-4, 1e-6, 1e-8]
            .iter()
            .map(|&rtol| {
                let (s, _, _) = c.run_through(method, rtol).unwrap();
                force_error(&s, &reference).unwrap().0
            })
            .collect();
        assert!(
            errs[0] > 5.0 * errs[1] && errs[1] > 5.0 * errs[2] && errs[2] < 1e-5,
            "{method:?}: {errs:?}"
        );
    }
}

/// The last point is the integration's end: the component is left exactly (every byte of
/// its state) as `do_step` over the whole window leaves it, and reports the same forces.
#[test]
fn straight_through_ends_as_one_step_over_the_window() {
    let (h, n) = (1e-4, 200);
    let mut a = ring(Method::Dopri5, 1e-6);
    let mut b = ring(Method::Dopri5, 1e-6);
    let mut out = Vec::new();
    a.step_through(0.0, h, n, &[vr("force.y"), vr("load.y")], &mut out)
        .unwrap();
    b.do_step(0.0, n as f64 * h).unwrap();
    assert_eq!(a.serialize_state(), b.serialize_state());
    assert_eq!(out.len(), 2 * n);
    assert_eq!(
        out[2 * n - 2].to_bits(),
        b.get_real(vr("force.y")).unwrap().to_bits()
    );
    // Inputs read back as set.
    assert!(out.chunks(2).all(|r| r[1] == -1000.0));
    // And it goes on stepping from there.
    a.do_step(n as f64 * h, h).unwrap();
    b.do_step(n as f64 * h, h).unwrap();
    assert_eq!(a.serialize_state(), b.serialize_state());
}

/// Motion-driven ring: the cage angle is a quadrature of the held speed, from the window
/// start to each point; the forces equal the coupling loop's to round-off.
#[test]
fn motion_driven_straight_through_matches_the_loop() {
    let (h, n) = (1e-4, 300);
    let names = ["force.x", "force.y", "balls.loaded", "K.y.y"];
    let vrs: Vec<u32> = names.iter().map(|n| vr(n)).collect();
    let mut a = Component::from_text(RING_MOTION).unwrap();
    let mut out = Vec::new();
    a.step_through(0.0, h, n, &vrs, &mut out).unwrap();
    let mut b = Component::from_text(RING_MOTION).unwrap();
    let mut varies = false;
    for k in 0..n {
        b.do_step(k as f64 * h, h).unwrap();
        for (j, &v) in vrs.iter().enumerate() {
            let (x, y) = (out[k * vrs.len() + j], b.get_real(v).unwrap());
            assert!(
                (x - y).abs() <= 1e-9 * y.abs().max(1.0),
                "{} at point {k}: {x} vs {y}",
                names[j]
            );
            varies |= j == 1 && (y - out[1]).abs() > 1e-3 * y.abs();
        }
    }
    assert!(varies, "the ball passes move the force");
}

/// Refused calls name the cause and leave every byte of the state as it was (and the
/// caller's buffer untouched); the component keeps working.
#[test]
fn refused_straight_through_leaves_the_component_as_it_was() {
    let fy = [vr("force.y")];
    let check = |c: &mut Component, h: f64, n: usize, vrs: &[u32], field: &str| {
        let before = c.serialize_state();
        let mut out = vec![7.0];
        let e = c.step_through(0.0, h, n, vrs, &mut out).unwrap_err();
        match &e {
            Error::Invalid { field: f, .. } => assert_eq!(f, field, "{e}"),
            _ => panic!("{e}"),
        }
        assert_eq!(c.serialize_state(), before);
        assert_eq!(out, [7.0]);
    };
    // A level with memory it updates at communication points (warm starts).
    let mut qs = Component::new(case("6205-qs").scene_with(Method::Dopri5, 1e-6).unwrap()).unwrap();
    check(&mut qs, 1e-4, 10, &fy, "model.level");
    // No dense output.
    let mut w = Component::new(
        case("6205-2dof")
            .scene_with(Method::Ros34pw2, 1e-6)
            .unwrap(),
    )
    .unwrap();
    check(&mut w, 1e-4, 10, &fy, "solver.method");
    let mut c = ring(Method::Dopri5, 1e-6);
    check(&mut c, 1e-4, 0, &fy, "n");
    check(&mut c, 1e-12, 1 << 40, &fy, "n");
    check(&mut c, 1e-4, 10, &[999_999], "value reference");
    check(&mut c, f64::NAN, 10, &fy, "h");
    check(&mut c, -1e-4, 10, &fy, "h");
    let mut out = Vec::new();
    c.step_through(0.0, 1e-4, 10, &fy, &mut out).unwrap();
    assert_eq!(out.len(), 10);
    // Time must continue where the component is.
    let before = c.serialize_state();
    assert!(matches!(
        c.step_through(0.0, 1e-4, 10, &fy, &mut out),
        Err(Error::CallOrder { .. })
    ));
    assert_eq!(c.serialize_state(), before);
}

/// A failed integration (the sub-step budget, which counts per communication interval)
/// leaves everything as it was, with a message naming the budget.
#[test]
fn failed_straight_through_leaves_the_component_as_it_was() {
    let mut s = case("6205-2dof").scene_with(Method::Dopri5, 1e-8).unwrap();
    s.solver.max_substeps = 1;
    let mut c = Component::new(s).unwrap();
    let before = c.serialize_state();
    let mut out = vec![1.0, 2.0];
    let e = c
        .step_through(0.0, 1e-3, 5, &[vr("force.y")], &mut out)
        .unwrap_err();
    assert!(e.to_string().contains("max_substeps"), "{e}");
    assert_eq!(c.serialize_state(), before);
    assert_eq!(out, [1.0, 2.0]);
}

/// Asked only for forces and moments, the points inside the window take the level's
/// wrench from its right-hand side instead of its full outputs: the same bits as the full
/// outputs give them (asked together with a matrix entry, which needs the full outputs), for
/// both causalities, both integrators, the 5-DOF ring, a ring with race waviness (its
/// points through one right-hand side each) and the skidding level.
#[test]
fn forces_alone_are_the_full_outputs_forces_bit_for_bit() {
    let forces: Vec<u32> = ["force.x", "force.y", "force.z", "moment.x", "moment.y"]
        .iter()
        .map(|n| vr(n))
        .collect();
    let mut with_k = forces.clone();
    with_k.push(vr("K.y.y"));
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for make in [
        &(|| ring(Method::Dopri5, 1e-5)) as &dyn Fn() -> Component,
        &|| ring(Method::Rosenbrock, 1e-5),
        &|| Component::from_text(RING_MOTION).unwrap(),
        &|| {
            let s = case("7008ce-5dof")
                .scene_with(Method::Rosenbrock, 1e-5)
                .unwrap();
            Component::new(s).unwrap()
        },
        &|| {
            let mut s = case("6205-2dof").scene_with(Method::Dopri5, 1e-5).unwrap();
            s.effects = raceway::component::Scene::from_text(
                "bearing = \"6205\"\n[effects]\nwaviness = [{ race = \"outer\", order = 12, amplitude_um = 0.3, phase_deg = 0.0 }]\n",
            )
            .unwrap()
            .effects;
            Component::new(s).unwrap()
        },
        // The skidding level (its own balls; its outputs may leave unresolved components
        // of the wrench at zero, which the guard at the last point catches).
        &|| {
            let s = case("7008ce-skid")
                .scene_with(Method::Rosenbrock, 1e-5)
                .unwrap();
            Component::new(s).unwrap()
        },
    ] {
        let (h, n) = (1e-4, 20);
        let (mut a, mut b) = (make(), make());
        let (mut fa, mut fb) = (Vec::new(), Vec::new());
        a.step_through(0.0, h, n, &forces, &mut fa).unwrap();
        b.step_through(0.0, h, n, &with_k, &mut fb).unwrap();
        let fb: Vec<f64> = fb.chunks(6).flat_map(|r| r[..5].to_vec()).collect();
        assert_eq!(bits(&fa), bits(&fb));
        assert!(fa.iter().any(|v| *v != 0.0));
        assert_eq!(a.serialize_state(), b.serialize_state());
    }
}
