//! The quasi-static motion-driven forces are a function of the ring motion and the ball
//! azimuths alone, to rounding, whatever the balls' warm starts: the right-hand side of a
//! time integration must not depend on the path to it (RODAS4's finite-difference
//! Jacobian and its error estimate would see the difference as noise).
//!
//! Tolerance: 1e-13 of the force scale, not bitwise. The ball Newton ends its iteration
//! when the update is below rounding of the answer (or `sqrt(eps)/8` of the approach, its
//! error then quadratically below rounding), but from another start its last iterate
//! differs in the last bits, and the sum over the balls (forces of opposite balls cancel)
//! carries that difference; a few ulp of each ball's force, well inside 1e-13 of the
//! total. The previous ball solve (a residual tolerance of 1e-11) differed by up to that
//! tolerance from one start to another.

use raceway::geometry::preset;
use raceway::models::quasi_static::{azimuths, BallState, Options, QuasiStatic, RaceControl};
use raceway::units::rpm_to_rad_s;

fn worst(a: &[f64; 5], b: &[f64; 5], ri: f64) -> f64 {
    let t = [1.0, 1.0, 1.0, ri, ri];
    let scale = (0..5).map(|i| a[i].abs() / t[i]).fold(0.0, f64::max);
    (0..5)
        .map(|i| (a[i] - b[i]).abs() / t[i] / scale)
        .fold(0.0, f64::max)
}

fn check(name: &str, control: RaceControl, rpm: f64, q: [f64; 5], far: &[[f64; 5]]) -> f64 {
    let b = preset(name).unwrap().build().unwrap();
    let m = QuasiStatic::new(
        &b,
        Options {
            race_control: control,
            ..Options::default()
        },
    )
    .unwrap();
    let ri = b.inner_groove_centre_radius();
    let w = rpm_to_rad_s(rpm);
    let psi = azimuths(b.z, 0.3);
    // Cold: every ball from its static start.
    let mut cold = vec![BallState::default(); b.z];
    let f0 = m.forces(&q, w, &psi, &mut cold).unwrap();
    let mut k = [[0.0; 5]; 5];
    let mut cold_k = vec![BallState::default(); b.z];
    let f0k = m
        .forces_and_stiffness(&q, w, &psi, &mut cold_k, &mut k)
        .unwrap();
    let mut e = worst(&f0, &f0k, ri);
    // The stiffness comes from the last Newton iterate (within sqrt(eps)/8 of the
    // approach from the root; 1.3e-12 of the largest entry at most here, measured).
    let k0 = k;
    let kmax = k0.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut ek = 0.0f64;
    // Warm: at y, then at a far point (other motion and azimuths), then at y again; with
    // the forces alone and with the stiffness (the two paths of the ball solve).
    let mut st = cold.clone();
    for (n, qf) in far.iter().enumerate() {
        let psi_far = azimuths(b.z, 0.3 + 0.05 * (n + 1) as f64);
        let with_k = n % 2 == 1;
        let ff = if with_k {
            m.forces_and_stiffness(qf, 0.9 * w, &psi_far, &mut st, &mut k)
        } else {
            m.forces(qf, 0.9 * w, &psi_far, &mut st)
        };
        ff.unwrap();
        let f1 = m.forces(&q, w, &psi, &mut st).unwrap();
        e = e.max(worst(&f0, &f1, ri));
        // Twice at the same point: the second starts from the first's answer.
        let f2 = m.forces(&q, w, &psi, &mut st).unwrap();
        e = e.max(worst(&f0, &f2, ri));
        let f3 = m
            .forces_and_stiffness(&q, w, &psi, &mut st, &mut k)
            .unwrap();
        e = e.max(worst(&f0, &f3, ri));
        for (x, y) in k.iter().flatten().zip(k0.iter().flatten()) {
            ek = ek.max((x - y).abs() / kmax);
        }
    }
    println!("{name} {control:?} {rpm} rpm: stiffness difference {ek:.2e} of its largest entry");
    assert!(ek < 1e-10, "stiffness depends on the warm start: {ek:e}");
    println!("{name} {control:?} {rpm} rpm: worst difference {e:.2e} of the force scale");
    e
}

#[test]
fn forces_do_not_depend_on_the_warm_start() {
    // Far points: a micrometre and more away, tilted, and near the bench's orbit.
    let far = [
        [3e-6, -2e-6, 14e-6, 1e-4, -1e-4],
        [-2e-6, -6e-6, 6e-6, 0.0, 2e-4],
        [1e-6, -5e-6, 10e-6, 0.0, 0.0],
        [0.0, 0.0, 20e-6, 0.0, 0.0],
        [2e-7, -4.9e-6, 10.1e-6, 0.0, 0.0],
        [-4e-6, 1e-6, 8e-6, -2e-4, 0.0],
    ];
    let mut e = 0.0f64;
    for (name, rpm, q) in [
        ("7008ce", 12_000.0, [1e-6, -5e-6, 10e-6, 0.0, 0.0]),
        ("7008ce", 30_000.0, [0.0, -3e-6, 12e-6, 5e-5, 0.0]),
        ("acbb16", 6000.0, [2e-6, 1e-6, 15e-6, 0.0, -5e-5]),
    ] {
        for control in [RaceControl::Outer, RaceControl::None] {
            e = e.max(check(name, control, rpm, q, &far));
        }
    }
    assert!(e < 1e-13, "forces depend on the warm start: {e:e}");
}
