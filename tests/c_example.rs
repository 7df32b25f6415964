//! examples/c/rotor.c, built with the system C compiler against include/raceway.h and the
//! cdylib cargo built, run, and checked against the bearing's own solution through the
//! Rust API:
//!
//! (a) the static sag of a rotor under gravity equals the bearing's static solution at
//!     half the weight (and the bearings carry exactly the weight);
//! (b) the steady unbalance orbit converges as the macro step shrinks, the differences
//!     falling by at least the coupling order (2), to the orbit the bearing's K and C
//!     predict.

mod capi_util;

use capi_util::*;
use raceway::component::variables::{self, VR_C0, VR_K0};
use raceway::models::quasi_static::{Options, QuasiStatic};
use raceway::Component;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

/// Rotor parameters shared by the runs (rotor.c defaults unless given).
const MASS: f64 = 5.0;
const GRAVITY: f64 = 9.81;
const SPEED_RPM: f64 = 10000.0;
const UNBALANCE: f64 = 1.2e-5;
const DAMPING: f64 = 2000.0;

fn scene_path() -> PathBuf {
    root().join("examples/c/bearing.toml")
}

fn omega() -> f64 {
    SPEED_RPM * std::f64::consts::PI / 30.0
}

fn rotor_exe() -> &'static PathBuf {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(|| {
        let exe = scratch("c_example").join("rotor");
        build_c_program(&[root().join("examples/c/rotor.c")], &exe);
        exe
    })
}

/// Run rotor.c with `key=value` arguments; its `key value` output lines.
fn rotor(args: &[String]) -> BTreeMap<String, f64> {
    let mut cmd = Command::new(rotor_exe());
    cmd.arg(format!("scene={}", scene_path().display()))
        .arg(format!("mass={MASS}"))
        .arg(format!("gravity={GRAVITY}"))
        .arg(format!("speed_rpm={SPEED_RPM}"))
        .arg(format!("damping={DAMPING}"))
        .args(args);
    run(&mut cmd)
        .lines()
        .map(|l| {
            let (k, v) = l.split_once(' ').expect("key value");
            (k.to_string(), v.trim().parse().expect("a number"))
        })
        .collect()
}

/// A bearing of the example's scene held at `y` (x = 0, no tilt, at rest apart from
/// spinning at `omega`), stepped once: (force.y, K.y.y).
fn bearing_at(c: &mut Component, y: f64, omega: f64) -> (f64, f64) {
    let causality = c.causality();
    for v in variables::SCALARS.iter().filter(|v| v.is_input(causality)) {
        let value = match v.name {
            "shaft.y" => y,
            "shaft.omega" => omega,
            _ => 0.0,
        };
        c.set_real(v.vr, value).unwrap();
    }
    c.do_step(c.time(), 1e-4).unwrap();
    (
        c.get_real(variables::by_name("force.y").unwrap().vr)
            .unwrap(),
        c.get_real(variables::by_name("K.y.y").unwrap().vr).unwrap(),
    )
}

/// The bearing's static solution: the Jones–Harris quasi-static equilibrium under half
/// the rotor's weight (external load `-load` along y on the inner ring) at the shaft speed,
/// balls at their reference azimuths; returns the displacement `(x, y)`.
fn expected_static_sag(scene: &str, load: f64, omega: f64) -> (f64, f64) {
    let c = Component::from_text(scene).unwrap();
    let opts = Options {
        race_control: c.scene().model.race_control,
        ..Options::default()
    };
    let qs = QuasiStatic::new(c.bearing(), opts).unwrap();
    let sol = qs.solve(&[0.0, -load, 0.0, 0.0, 0.0], omega).unwrap();
    (sol.q[0], sol.q[1])
}

/// The steady unbalance orbit the bearing's linearisation at the static sag predicts for
/// the symmetric rigid rotor's cylindrical mode (two bearings, pedestal damping `c` each):
/// `(2K - m Omega^2 + i Omega (2C + 2c)) Q = U Omega^2 (1, -i)`, amplitudes `(|Qx|, |Qy|)`
/// (Genta 2005, ch. 4; exact for a linear bearing).
fn expected_orbit_amplitudes(scene: &str, sag: f64, omega: f64) -> (f64, f64) {
    let mut c = Component::from_text(scene).unwrap();
    bearing_at(&mut c, sag, omega);
    let mut get = |vr: u32| c.get_real(vr).unwrap();
    let k = [
        [get(VR_K0), get(VR_K0 + 1)],
        [get(VR_K0 + 5), get(VR_K0 + 6)],
    ];
    let d = [
        [get(VR_C0), get(VR_C0 + 1)],
        [get(VR_C0 + 5), get(VR_C0 + 6)],
    ];
    // Complex 2x2 solve, numbers as (re, im).
    type Cx = (f64, f64);
    let mul = |a: Cx, b: Cx| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let sub = |a: Cx, b: Cx| (a.0 - b.0, a.1 - b.1);
    let div = |a: Cx, b: Cx| {
        let n = b.0 * b.0 + b.1 * b.1;
        ((a.0 * b.0 + a.1 * b.1) / n, (a.1 * b.0 - a.0 * b.1) / n)
    };
    let w2 = omega * omega;
    let z = |i: usize, j: usize| {
        let diag = if i == j { 1.0 } else { 0.0 };
        (
            2.0 * k[i][j] - MASS * w2 * diag,
            omega * (2.0 * d[i][j] + 2.0 * DAMPING * diag),
        )
    };
    let f = [(UNBALANCE * w2, 0.0), (0.0, -UNBALANCE * w2)];
    let det = sub(mul(z(0, 0), z(1, 1)), mul(z(0, 1), z(1, 0)));
    let qx = div(sub(mul(z(1, 1), f[0]), mul(z(0, 1), f[1])), det);
    let qy = div(sub(mul(z(0, 0), f[1]), mul(z(1, 0), f[0])), det);
    (qx.0.hypot(qx.1), qy.0.hypot(qy.1))
}

#[test]
fn static_sag_under_gravity_is_the_bearings_static_solution() {
    // The quasi-static level: balls pass under the load, so the sag carries the
    // varying-compliance ripple (a few per cent of the deflection, docs/physics.md §N5.2); its
    // mean is the static solution.
    let out = rotor(&["unbalance=0".into(), "revs=30".into(), "avg_revs=10".into()]);
    let scene = std::fs::read_to_string(scene_path()).unwrap();
    let half = MASS * GRAVITY / 2.0;
    let (ex, ey) = expected_static_sag(&scene, half, omega());
    assert!(ey < 0.0);
    for ab in ["A", "B"] {
        let y = out[&format!("bearing.{ab}.y.mean")];
        let x = out[&format!("bearing.{ab}.x.mean")];
        let fy = out[&format!("bearing.{ab}.force.y.mean")];
        eprintln!("{ab}: sag ({x:.4e}, {y:.4e}) m, static solution ({ex:.4e}, {ey:.4e}) m, force.y {fy} N");
        assert!(
            ((y - ey) / ey).abs() < 0.02,
            "{ab}: sag {y} m, the bearing's static solution {ey} m"
        );
        // Across the load line the static solution at fixed ball positions leans a little
        // (Z = 9 is not symmetric about y); over a cage revolution that averages out.
        assert!(
            x.abs() < 0.01 * ey.abs() && ex.abs() < 0.05 * ey.abs(),
            "{ab}: x = {x}, static {ex}"
        );
        assert!(
            ((fy - half) / half).abs() < 1e-3,
            "{ab}: mean force.y {fy} N balances {half} N"
        );
    }
    // The linear level at the same operating point: the coupling is exact at equilibrium,
    // so the sag equals the static solution to the solver's precision, whatever the step.
    let lin = scene_path().with_file_name("bearing-linear.toml");
    let out = rotor(&[
        "unbalance=0".into(),
        "revs=30".into(),
        "avg_revs=5".into(),
        format!("scene={}", lin.display()),
    ]);
    for ab in ["A", "B"] {
        let y = out[&format!("bearing.{ab}.y.mean")];
        assert!(
            ((y - ey) / ey).abs() < 1e-6,
            "{ab}: linear-level sag {y} m vs {ey} m"
        );
        assert!(out[&format!("bearing.{ab}.y.amplitude")] < 1e-6 * ey.abs());
    }
}

#[test]
fn unbalance_orbit_converges_with_the_macro_step_at_least_at_the_coupling_order() {
    // The linear level: the orbit has a closed-form prediction to converge to.
    let lin = scene_path().with_file_name("bearing-linear.toml");
    let amp = |steps: u32| {
        let out = rotor(&[
            format!("unbalance={UNBALANCE}"),
            format!("steps_per_rev={steps}"),
            format!("scene={}", lin.display()),
        ]);
        (out["bearing.A.x.amplitude"], out["bearing.A.y.amplitude"])
    };
    let (a1, a2, a3) = (amp(32), amp(64), amp(128));
    let scene = std::fs::read_to_string(&lin).unwrap();
    let (_, sag) = expected_static_sag(&scene, MASS * GRAVITY / 2.0, omega());
    let (ex, ey) = expected_orbit_amplitudes(&scene, sag, omega());
    for (axis, h1, h2, h3, e) in [("x", a1.0, a2.0, a3.0, ex), ("y", a1.1, a2.1, a3.1, ey)] {
        let (d1, d2) = ((h1 - h2).abs(), (h2 - h3).abs());
        eprintln!(
            "{axis}: amplitudes {h1:.9e} {h2:.9e} {h3:.9e}; differences {d1:.3e} {d2:.3e}, \
             ratio {:.2} (order {:.2}); linear prediction {e:.9e}",
            d1 / d2,
            (d1 / d2).log2()
        );
        // Second-order coupling: each halving divides the difference by >= 4 (slack 0.85).
        assert!(d1 / d2 >= 4.0 * 0.85, "{axis}: {d1:e} then {d2:e}");
        assert!(d2 < 1e-3 * h3, "{axis}: not converged: {d2:e} of {h3:e}");
        // The converged orbit is the one the bearing's K and C predict (exact for a
        // linear bearing; a small orbit about the static point for a nonlinear one).
        assert!(((h3 - e) / e).abs() < 1e-2, "{axis}: {h3:e} against {e:e}");
    }
}

/// The measurement sees the coupling order: holding the bearing force over the macro step
/// (explicit zero-order hold, no K and C) converges at first order only (each halving
/// divides the difference by about 2; Kübler & Schiehlen 2000).
#[test]
fn zero_order_hold_coupling_converges_at_first_order_only() {
    let amp = |steps: u32| {
        let out = rotor(&[
            "coupling=hold".into(),
            format!("unbalance={UNBALANCE}"),
            format!("steps_per_rev={steps}"),
            "revs=20".into(),
            "avg_revs=5".into(),
        ]);
        out["bearing.A.y.amplitude"]
    };
    let (a1, a2, a3) = (amp(256), amp(512), amp(1024));
    let (d1, d2) = ((a1 - a2).abs(), (a2 - a3).abs());
    eprintln!("hold: {a1:.9e} {a2:.9e} {a3:.9e}; ratio {:.2}", d1 / d2);
    assert!((1.6..2.6).contains(&(d1 / d2)), "{d1:e} then {d2:e}");
}
