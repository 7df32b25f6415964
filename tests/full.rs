//! The full level (docs/physics.md §5.5, study \[0\]): quasi-static start, ideal-cage limit
//! against the skidding level, angular-momentum balance, cage orbit and whirl index.
//!
//! Each test integrates at most a few milliseconds of the 7004 (6 balls).

use raceway::component::{variables, Component};
use raceway::contact::traction::TractionLaw;
use raceway::geometry::preset;
use raceway::models::full::{BallContacts, FullModel, FullParams};
use raceway::models::quasi_static::{BallResult, BallState, Options, QuasiStatic};
use raceway::seam::{Jacobians, Motion};
use raceway::solver::{OdeSystem, Options as SolverOptions, Rosenbrock};
use std::f64::consts::PI;

#[path = "common/motion_scene.rs"]
mod motion_scene;
use motion_scene::motion_scene;

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

fn rpm(n: f64) -> f64 {
    n * PI / 30.0
}

/// Study \[0\]'s load: Fa 2000 N, Fr 400 N (external load on the inner ring).
const LOAD: [f64; 5] = [0.0, -400.0, 2000.0, 0.0, 0.0];

/// The quasi-static (Jones–Harris) equilibrium displacement `(x, y, z)` of the 7004 under
/// the forces of [`LOAD`] with the tilts held at zero (the shaft held square by a second
/// bearing, as in a spindle; the moment-free single-bearing answer tilts the ring by
/// 2.9 mrad). Newton on the three forces with a difference Jacobian.
fn qs_displacement(omega: f64) -> [f64; 5] {
    let b = preset("7004").unwrap().build().unwrap();
    let qs = QuasiStatic::new(&b, Options::default()).unwrap();
    let mut q = qs.solve(&LOAD, omega).unwrap().q;
    q[3] = 0.0;
    q[4] = 0.0;
    let psi: Vec<f64> = (0..b.z).map(|j| 2.0 * PI * j as f64 / b.z as f64).collect();
    let mut st = vec![BallState::default(); b.z];
    let mut f = |q: &[f64; 5]| qs.forces(q, omega, &psi, &mut st).unwrap();
    for _ in 0..30 {
        let f0 = f(&q);
        let r = [f0[0] + LOAD[0], f0[1] + LOAD[1], f0[2] + LOAD[2]];
        if r.iter().map(|v| v.abs()).sum::<f64>() < 1e-9 {
            break;
        }
        let mut j = nalgebra::Matrix3::zeros();
        for c in 0..3 {
            let mut qp = q;
            qp[c] += 1e-10;
            let fp = f(&qp);
            for k in 0..3 {
                j[(k, c)] = (fp[k] - f0[k]) / 1e-10;
            }
        }
        let dq = j
            .lu()
            .solve(&nalgebra::Vector3::new(-r[0], -r[1], -r[2]))
            .unwrap();
        for c in 0..3 {
            q[c] += dq[c];
        }
    }
    q
}

/// A motion-driven 7004 scene at displacement `q` and speed `omega`, extra
/// `[model.full]` lines.
fn scene_7004(q: [f64; 5], omega: f64, full: &str) -> String {
    motion_scene("7004", "full", q, omega, full)
}

#[test]
#[ignore]
fn print_displacements() {
    for n in [0.0, 30_000.0, 60_000.0, 80_000.0, 85_000.0, 120_000.0] {
        println!("{n} rpm: q = {:?}", qs_displacement(rpm(n)));
    }
}

/// Test 1: at t = 0 the level's per-ball loads and contact angles equal the quasi-static
/// solver's (configured the same way: no gyroscopic friction couple, which the full level
/// does not impose but lets the ball dynamics call up), and the wrench differs from the
/// quasi-static one only by the race tractions at the inner contacts (the inner ring turns
/// about its displaced centre, which the quasi-static kinematics ignore) and the spin
/// moments.
#[test]
fn quasi_static_start_equals_the_quasi_static_solver() {
    let b = preset("7004").unwrap().build().unwrap();
    let omega = rpm(30_000.0);
    let q = qs_displacement(omega);
    let qs = QuasiStatic::new(
        &b,
        Options {
            gyroscopic: false,
            ..Options::default()
        },
    )
    .unwrap();
    let z = b.z;
    let psi: Vec<f64> = (0..z).map(|j| 2.0 * PI * j as f64 / z as f64).collect();
    let mut st = vec![BallState::default(); z];
    let mut res = vec![BallResult::default(); z];
    let f_qs = qs
        .evaluate(&q, omega, &psi, &mut st, None, Some(&mut res))
        .unwrap();
    let cases = [
        (BallContacts::QuasiStatic, 0.05),
        (BallContacts::Dynamic, 0.05),
        (BallContacts::QuasiStatic, 0.0),
    ];
    for (contacts, mu) in cases {
        let p = FullParams {
            ball_contacts: contacts,
            traction: TractionLaw::Coulomb {
                mu_max: mu,
                v_s: 0.05,
            },
            ..FullParams::for_bearing(&b)
        };
        let mut m = FullModel::new(&b, p).unwrap();
        let mut x = vec![0.0; m.n_states()];
        let mut aux = vec![0.0; m.n_aux()];
        m.init(&q, omega, &mut x, &mut aux).unwrap();
        let mut dx = vec![0.0; x.len()];
        let tot = m.eval(&q, &[0.0; 5], omega, &x, &mut aux, &mut dx).unwrap();
        let mut traction = 0.0;
        for (bf, r) in m.balls.iter().zip(&res) {
            // Loads: the centrifugal force uses the ball centre's radius rho instead of
            // dm/2 (a 1e-4 relative change of Fc, some 1e-6 of the loads).
            assert!(
                (bf.q_i - r.q_i).abs() < 1e-5 * r.q_i,
                "{contacts:?} {bf:?} {r:?}"
            );
            assert!(
                (bf.q_o - r.q_o).abs() < 1e-5 * r.q_o,
                "{contacts:?} {bf:?} {r:?}"
            );
            // Contact angles: the same Fc change turns them by some 1e-6 rad.
            assert!((bf.alpha_i - r.alpha_i).abs() < 1e-5, "{bf:?} {r:?}");
            assert!((bf.alpha_o - r.alpha_o).abs() < 1e-5, "{bf:?} {r:?}");
            // Pure rolling at the outer contact centre (outer race control) up to the
            // quasi-static kinematics' approximation of the ball centre radius by dm/2.
            let approx = (bf.rho - 0.5 * b.dm).abs() * bf.w_orb;
            assert!(bf.slide_o <= 1.01 * approx + 1e-9, "{bf:?} {approx}");
            traction += mu * bf.q_i * (bf.slide_i / 0.05).tanh();
        }
        // Without traction the wrenches agree to the Fc change; with it, they differ by
        // at most the sum of the inner tractions (forces) and their moments (lever < dm).
        let fscale = f_qs[0].hypot(f_qs[1]).hypot(f_qs[2]);
        for k in 0..5 {
            let lever = if k < 3 { 1.0 } else { b.dm };
            assert!(
                (tot.wrench[k] - f_qs[k]).abs() <= traction * lever + 1e-5 * fscale * lever,
                "{k}: {:?} vs {f_qs:?} (traction {traction})",
                tot.wrench
            );
        }
        if mu > 0.0 {
            // The inner ring turns about its displaced centre (q), which the quasi-static
            // kinematics ignore: the balls start with inner slip and the tractions matter.
            assert!((tot.wrench[0] - f_qs[0]).abs() > 1e-3 * fscale);
        }
        println!(
            "{contacts:?}: full {:?}\n qs {f_qs:?}\n traction sum {traction}",
            tot.wrench
        );
    }
}

#[test]
#[ignore]
fn probe_scene() {
    let text = std::fs::read_to_string(std::env::var("SCENE").unwrap()).unwrap();
    let mut c = Component::from_text(&text).unwrap();
    let h = 1e-4;
    let n: usize = std::env::var("N").map(|s| s.parse().unwrap()).unwrap_or(20);
    let t0 = raceway::report::thread_cpu_s();
    for i in 0..n {
        c.do_step(i as f64 * h, h).unwrap();
        if i % (n / 10).max(1) == 0 || i == n - 1 {
            println!(
                "t {:.4} wc {:.2} slip {:.4} cx {:.4} cy {:.4} cv {:.4} pocket {:.2} guide {:.2} Fz {:.1} Fy {:.1} T {:.4}",
                (i + 1) as f64 * h,
                c.get_real(vr("cage.omega")).unwrap(),
                c.get_real(vr("cage.slip")).unwrap(),
                c.get_real(vr("cage.x")).unwrap(),
                c.get_real(vr("cage.y")).unwrap(),
                c.get_real(vr("cage.speed")).unwrap(),
                c.get_real(vr("pocket.max_force")).unwrap(),
                c.get_real(vr("guide.force")).unwrap(),
                c.get_real(vr("force.z")).unwrap(),
                c.get_real(vr("force.y")).unwrap(),
                c.get_real(vr("torque.z")).unwrap(),
            );
        }
    }
    println!(
        "thread CPU {:.3} s (load average {}) stats {:?}",
        raceway::report::thread_cpu_s() - t0,
        raceway::report::load_average(),
        c.stats()
    );
}

/// Mean of the cage speed over `n` steps of `h` after `skip` steps.
fn mean_cage_speed(c: &mut Component, skip: usize, n: usize, h: f64) -> f64 {
    let mut s = 0.0;
    for i in 0..skip + n {
        c.do_step(i as f64 * h, h).unwrap();
        if i >= skip {
            s += c.get_real(vr("cage.omega")).unwrap();
        }
    }
    s / n as f64
}

fn skidding_scene(q: [f64; 5], omega: f64, traction: &str) -> String {
    scene_7004(q, omega, "")
        .replace("level = \"full\"", "level = \"skidding\"")
        .replace(
            "[model.full]\n",
            &format!("[model.skidding]\ntraction = {traction}\ndrag_coefficient = 0.0\ndrag_density = 0.0\n"),
        )
}

/// Test 2: with the cage constraint made ideal (centred, rotation only, tangential
/// pockets), the same traction law and no drag, the full level reproduces the skidding
/// level's steady cage speed at a moderate speed (7004, 10 000 rpm, study \[0\]'s load) up
/// to the one thing the skidding level leaves out: it rolls the balls on the races at the
/// nominal contact angle (24°), while the full level's loaded contact angles are larger
/// (their own Jones geometry). So: the full level's cage speed equals the quasi-static
/// (race-control) orbital speed at the loaded angles within 0.05 %, the skidding level's
/// its kinematic speed at 24° within 0.05 %, and the two differ by the kinematic
/// difference of the two angles within 0.05 % (about 0.9 % in all here).
#[test]
fn ideal_cage_reproduces_the_skidding_level() {
    let tr = "{ law = \"coulomb\", mu_max = 0.05, v_s = 0.05 }";
    let omega = rpm(10_000.0);
    let b = preset("7004").unwrap().build().unwrap();
    let q = qs_displacement(omega);
    let qs = QuasiStatic::new(&b, Options::default()).unwrap();
    let psi: Vec<f64> = (0..b.z).map(|j| 2.0 * PI * j as f64 / b.z as f64).collect();
    let mut st = vec![BallState::default(); b.z];
    let mut res = vec![BallResult::default(); b.z];
    qs.evaluate(&q, omega, &psi, &mut st, None, Some(&mut res))
        .unwrap();
    let w_qs = res.iter().map(|r| r.omega_m).sum::<f64>() / b.z as f64;
    let w_kin = raceway::geometry::kinematics(&b, omega).cage_speed;
    let full = format!("traction = {tr}\ncage = \"ideal\"\ndrag_factor = 0.0");
    let mut cf = Component::from_text(&scene_7004(q, omega, &full)).unwrap();
    let mut cs = Component::from_text(&skidding_scene(q, omega, tr)).unwrap();
    let wf = mean_cage_speed(&mut cf, 30, 30, 1e-4);
    let ws = mean_cage_speed(&mut cs, 30, 30, 1e-4);
    println!("full {wf}, skidding {ws}, quasi-static {w_qs}, kinematic at 24 deg {w_kin}");
    let tol = 5e-4 * w_kin;
    assert!((wf - w_qs).abs() < tol, "full {wf} vs quasi-static {w_qs}");
    assert!(
        (ws - w_kin).abs() < tol,
        "skidding {ws} vs kinematic {w_kin}"
    );
    assert!(((wf - ws) - (w_qs - w_kin)).abs() < tol);
    assert!(
        (wf - ws).abs() > 2.0 * tol,
        "the contact-angle effect is resolved"
    );
}

/// Balls plus cage as an ODE with one more state: the time integral of the external
/// moments about z (races, spin, drag, guide land).
struct Balance {
    m: FullModel,
    q: [f64; 5],
    omega: f64,
    aux: Vec<f64>,
}

impl OdeSystem for Balance {
    fn dim(&self) -> usize {
        self.m.n_states() + 1
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        let n = self.m.n_states();
        let tot = self
            .m
            .eval(
                &self.q,
                &[0.0; 5],
                self.omega,
                &y[..n],
                &mut self.aux,
                &mut dy[..n],
            )
            .map_err(|e| e.to_string())?;
        dy[n] = tot.external_mz;
        Ok(())
    }
}

/// Test 3: with dynamic ball contacts (Newton in cylindrical coordinates, so the Coriolis
/// term is kept) and a free cage thrown off its orbit (pocket impacts, guide-land whirl),
/// the angular momentum about z of balls and cage changes by exactly the integral of the
/// external moments: pocket forces and friction are internal.
#[test]
fn angular_momentum_balance_closes() {
    let b = preset("7004").unwrap().build().unwrap();
    let omega = rpm(30_000.0);
    let q = qs_displacement(omega);
    let p = FullParams {
        ball_contacts: BallContacts::Dynamic,
        ..FullParams::for_bearing(&b)
    };
    let mut m = FullModel::new(&b, p).unwrap();
    let n = m.n_states();
    let mut y = vec![0.0; n + 1];
    let mut aux = vec![0.0; m.n_aux()];
    m.init(&q, omega, &mut y[..n], &mut aux).unwrap();
    // Cage 3 % slow and moving sideways at 0.5 m/s: pocket impacts.
    let (l, t0) = m.scales();
    y[11] *= 0.97;
    y[6] = 0.5 * t0 / l;
    let l0 = m.angular_momentum(&y[..n], &aux);
    let mut sys = Balance { m, q, omega, aux };
    let mut integ = Rosenbrock::new(n + 1);
    let mut opts = SolverOptions::new(n + 1, 1e-8, 1e-9);
    opts.max_steps = 1_000_000;
    let mut h = 0.0;
    integ
        .integrate(&mut sys, 0.0, 1e-3, &mut y, &mut h, &opts)
        .unwrap();
    let l1 = sys.m.angular_momentum(&y[..n], &sys.aux);
    let ext = y[n];
    println!(
        "L0 {l0:e}, L1 {l1:e}, integral of moments {ext:e}, residual {:e}",
        l1 - l0 - ext
    );
    // Something happened: the cage was sped up by the pockets, the moments did work.
    assert!((l1 - l0).abs() > 1e-3 * l0.abs(), "{l0} {l1}");
    assert!((l1 - l0 - ext).abs() < 1e-6 * l0.abs(), "balance");
}

/// Run the 30 000 rpm scene for `n` steps of 0.1 ms: the cage-centre orbit (clearances)
/// and speed samples.
fn run_30000(n: usize) -> (Vec<[f64; 2]>, Vec<f64>) {
    let text = include_str!("../examples/scenes/7004-30000.toml");
    let mut c = Component::from_text(text).unwrap();
    let h = 1e-4;
    let (mut orbit, mut speed) = (Vec::new(), Vec::new());
    for i in 0..n {
        c.do_step(i as f64 * h, h).unwrap();
        orbit.push([
            c.get_real(vr("cage.x")).unwrap(),
            c.get_real(vr("cage.y")).unwrap(),
        ]);
        speed.push(c.get_real(vr("cage.speed")).unwrap());
    }
    (orbit, speed)
}

/// Test 4: in a short 7004 run at 30 000 rpm (2.5 shaft revolutions) the cage centre stays
/// inside the guide clearance — inside `eps_max` even, so the land's wall spring never
/// acts and the film and pocket forces alone hold it — and the whirl index
/// `sigma = std(|v|)/mean(|v|)` is finite and repeats bit for bit.
#[test]
fn cage_orbit_inside_clearance_and_sigma_repeats() {
    let (orbit, speed) = run_30000(50);
    let r_max = orbit.iter().map(|p| p[0].hypot(p[1])).fold(0.0, f64::max);
    let eps_max = FullParams::for_bearing(&preset("7004").unwrap().build().unwrap()).guide_eps_max;
    assert!(r_max < eps_max, "cage orbit reached {r_max} clearances");
    assert!(r_max > 1e-3, "the cage moved: {r_max}");
    let sigma = raceway::analysis::whirl_index(&speed[25..]).unwrap();
    assert!(sigma.is_finite() && sigma > 0.0, "{sigma}");
    let (orbit2, speed2) = run_30000(50);
    let sigma2 = raceway::analysis::whirl_index(&speed2[25..]).unwrap();
    assert_eq!(sigma.to_bits(), sigma2.to_bits());
    assert_eq!(orbit, orbit2);
    println!("r_max {r_max}, sigma {sigma}");
}

/// The block Jacobian equals a whole-system forward difference (free cage, both ball
/// contact treatments).
#[test]
fn block_jacobian_matches_whole_differences() {
    let b = preset("7004").unwrap().build().unwrap();
    let omega = rpm(30_000.0);
    let q = qs_displacement(omega);
    for contacts in [BallContacts::QuasiStatic, BallContacts::Dynamic] {
        let p = FullParams {
            ball_contacts: contacts,
            ..FullParams::for_bearing(&b)
        };
        let mut m = FullModel::new(&b, p).unwrap();
        let n = m.n_states();
        let mut x = vec![0.0; n];
        let mut aux = vec![0.0; m.n_aux()];
        m.init(&q, omega, &mut x, &mut aux).unwrap();
        // Off the start: cage displaced and turning slow, so pockets act.
        x[0] = 0.05;
        x[11] *= 0.99;
        let mut jx = vec![0.0; n * n];
        let mut scratch = vec![0.0; 3 * n + aux.len()];
        let motion = Motion {
            q,
            v: [0.0; 5],
            omega,
        };
        let jac = Jacobians {
            jx: &mut jx,
            jm: &mut [],
            wx: &mut [],
            wm: &mut [],
        };
        m.jacobian(&motion, &x, &aux, jac, &mut scratch).unwrap();
        let mut d0 = vec![0.0; n];
        let mut d1 = vec![0.0; n];
        let mut a = aux.clone();
        m.eval(&q, &[0.0; 5], omega, &x, &mut a, &mut d0).unwrap();
        let mut worst: f64 = 0.0;
        for c in 0..n {
            let mut xp = x.clone();
            let h = 1.5e-8 * x[c].abs().max(1.0);
            xp[c] += h;
            let mut a = aux.clone();
            m.eval(&q, &[0.0; 5], omega, &xp, &mut a, &mut d1).unwrap();
            for r in 0..n {
                let fd = (d1[r] - d0[r]) / h;
                let scale = 1e-4 * (fd.abs() + jx[r * n + c].abs()) + 1e-3 * d0[r].abs().max(1.0);
                let err = (jx[r * n + c] - fd).abs() / scale;
                worst = worst.max(err);
            }
        }
        assert!(worst < 1.0, "{contacts:?}: worst scaled error {worst}");
    }
}

/// Start-up from rest (the 7004-startup scene's ramp, 600 000 rpm/s, for 10 ms): the cage
/// slip starts at 100 % with everything at rest, the balls and cage are spun up by the
/// race tractions (slip falls well below 100 %), and the outputs stay finite.
#[test]
fn startup_from_rest_slip_starts_at_one_and_falls() {
    let text = include_str!("../examples/scenes/7004-startup.toml");
    let mut c = Component::from_text(text).unwrap();
    assert_eq!(c.get_real(vr("cage.slip")).unwrap(), 1.0);
    assert_eq!(c.get_real(vr("cage.omega")).unwrap(), 0.0);
    let accel = rpm(600_000.0);
    let h = 1e-4;
    let mut last = 1.0;
    for _ in 0..100 {
        let t = c.time();
        c.set_real(vr("shaft.omega"), accel * t).unwrap();
        c.set_input_derivative(vr("shaft.omega"), 1, accel).unwrap();
        c.do_step(t, h).unwrap();
        last = c.get_real(vr("cage.slip")).unwrap();
        for name in [
            "cage.x",
            "cage.y",
            "cage.speed",
            "pocket.max_force",
            "force.z",
        ] {
            assert!(c.get_real(vr(name)).unwrap().is_finite(), "{name}");
        }
    }
    let w = c.get_real(vr("cage.omega")).unwrap();
    println!("after 10 ms: cage slip {last}, cage speed {w} rad/s");
    assert!(last < 0.2 && last > -0.1, "slip {last}");
    assert!(w > 0.0);
}

/// Load-driven, the block Jacobian's ring columns and wrench rows equal whole-system
/// differences too (same steps; agreement to 1e-6 of each column's largest entry), so a
/// load-driven run can use it.
#[test]
fn block_jacobian_ring_parts_match() {
    let b = preset("7004").unwrap().build().unwrap();
    let omega = rpm(30_000.0);
    let q = qs_displacement(omega);
    let v = [1e-3, -2e-3, 0.0, 0.0, 0.0];
    let mut m = FullModel::new(&b, FullParams::for_bearing(&b)).unwrap();
    let n = m.n_states();
    let mut x = vec![0.0; n];
    let mut aux = vec![0.0; m.n_aux()];
    m.init(&q, omega, &mut x, &mut aux).unwrap();
    x[0] = 0.05;
    let (mut jx, mut jm, mut wx, mut wm) = (
        vec![0.0; n * n],
        vec![0.0; n * 10],
        vec![0.0; 5 * n],
        vec![0.0; 50],
    );
    let mut scratch = vec![0.0; 3 * n + aux.len()];
    let jac = Jacobians {
        jx: &mut jx,
        jm: &mut jm,
        wx: &mut wx,
        wm: &mut wm,
    };
    m.jacobian(&Motion { q, v, omega }, &x, &aux, jac, &mut scratch)
        .unwrap();
    let mut d0 = vec![0.0; n];
    let mut d1 = vec![0.0; n];
    let t0 = m
        .eval(&q, &v, omega, &x, &mut aux.clone(), &mut d0)
        .unwrap();
    // Compare a column of differences `fd` with the block one `blk`.
    let check = |what: &str, c: usize, blk: &[f64], fd: &[f64]| {
        let big = fd.iter().chain(blk).fold(0.0f64, |a, v| a.max(v.abs()));
        for (r, (a, b)) in blk.iter().zip(fd).enumerate() {
            assert!(
                (a - b).abs() <= 1e-6 * big,
                "{what} row {r} col {c}: {a} vs {b}"
            );
        }
    };
    // Ring columns.
    let hs = [
        1e-10, 1e-10, 1e-10, 1e-8, 1e-8, 1e-6, 1e-6, 1e-6, 1e-4, 1e-4,
    ];
    for (c, h) in hs.iter().enumerate() {
        let (mut qp, mut vp) = (q, v);
        if c < 5 {
            qp[c] += h;
        } else {
            vp[c - 5] += h;
        }
        let t = m
            .eval(&qp, &vp, omega, &x, &mut aux.clone(), &mut d1)
            .unwrap();
        let fd: Vec<f64> = (0..n).map(|r| (d1[r] - d0[r]) / h).collect();
        let blk: Vec<f64> = (0..n).map(|r| jm[r * 10 + c]).collect();
        check("jm", c, &blk, &fd);
        let fd: Vec<f64> = (0..5).map(|r| (t.wrench[r] - t0.wrench[r]) / h).collect();
        let blk: Vec<f64> = (0..5).map(|r| wm[r * 10 + c]).collect();
        check("wm", c, &blk, &fd);
    }
    // Wrench rows.
    for c in 0..n {
        let h = 1.5e-8 * x[c].abs().max(1.0);
        let mut xp = x.clone();
        xp[c] += h;
        let t = m
            .eval(&q, &v, omega, &xp, &mut aux.clone(), &mut d1)
            .unwrap();
        let fd: Vec<f64> = (0..5).map(|r| (t.wrench[r] - t0.wrench[r]) / h).collect();
        let blk: Vec<f64> = (0..5).map(|r| wx[r * n + c]).collect();
        check("wx", c, &blk, &fd);
    }
    // The shaft feels the balls: the axial force depends on the axial displacement.
    assert!(wm[2 * 10 + 2].abs() > 1e7, "axial stiffness {}", wm[22]);
}

/// The 7004's full model with parameters `p`, its states and aux at the quasi-static start
/// for motion `(q, omega)`.
fn started(p: FullParams, q: &[f64; 5], omega: f64) -> (FullModel, Vec<f64>, Vec<f64>) {
    let b = preset("7004").unwrap().build().unwrap();
    let mut m = FullModel::new(&b, p).unwrap();
    let mut y = vec![0.0; m.n_states()];
    let mut aux = vec![0.0; m.n_aux()];
    m.init(q, omega, &mut y, &mut aux).unwrap();
    (m, y, aux)
}

/// The level's use of the guide land (outer-ring guided 7004): with the cage displaced by
/// `e` (inside the pocket play, so the pockets only add their film) and at rest relative
/// to its centre, the land's share of the cage's acceleration — isolated as the difference
/// between a land of width `2 Bg` and one of `Bg` — is exactly the short-bearing law's force
/// on the cage — outer-ring guided: at the cage OD, `e` measured from the fixed outer ring,
/// `w_ring = 0`; inner-ring guided (`FullParams::guidance`): at the cage bore, `e` measured
/// from the displaced shaft, `w_ring` the shaft speed — with the cage's own speed: restoring (radial component toward the centre) and driving
/// forward whirl (tangential component along the rotation). A wrong sign of `e`, the
/// inner ring's speed or the bore radius would all fail it.
#[test]
fn guide_land_in_the_level_restores_and_drives_forward_whirl() {
    use raceway::geometry::Guidance;
    use raceway::lubrication::guide_land::GuideLand;
    let b = preset("7004").unwrap().build().unwrap();
    let omega = rpm(120_000.0);
    let q = qs_displacement(omega);
    let bg = 0.5 * b.cage.width;
    let cg = b.cage.guide_clearance;
    let (e, ang) = (0.2 * cg, 0.7f64);
    let e_xy = [e * ang.cos(), e * ang.sin()];
    for guidance in [Guidance::OuterRing, Guidance::InnerRing] {
        let inner = guidance == Guidance::InnerRing;
        // The guiding ring's centre: the shaft's (x, y) for the inner ring, else the origin.
        let ring = if inner { [q[0], q[1]] } else { [0.0, 0.0] };
        let mut acc = Vec::new();
        let mut wc = 0.0;
        for width in [bg, 2.0 * bg] {
            let p = FullParams {
                guide_width: width,
                drag: 0.0,
                guidance,
                ..FullParams::for_bearing(&b)
            };
            let (mut m, mut y, mut aux) = started(p, &q, omega);
            let (l, t0) = m.scales();
            y[0] = (ring[0] + e_xy[0]) / l;
            y[1] = (ring[1] + e_xy[1]) / l;
            wc = m.cage_omega(&y);
            let mut dx = vec![0.0; y.len()];
            m.eval(&q, &[0.0; 5], omega, &y, &mut aux, &mut dx).unwrap();
            // Cage force (N) from the stored-rate derivative: dx[6..8] = a t0 / l.
            acc.push([dx[6] * l / t0 * b.cage.mass, dx[7] * l / t0 * b.cage.mass]);
        }
        let land = |width: f64| GuideLand {
            radius: 0.5
                * if inner {
                    b.cage.inner_diameter
                } else {
                    b.cage.outer_diameter
                },
            width,
            clearance: cg,
            viscosity: FullParams::for_bearing(&b).viscosity,
            outer: !inner,
            contact_stiffness: 1e7,
            eps_max: 0.9,
        };
        let w_ring = if inner { omega } else { 0.0 };
        let f1 = land(bg).force(e_xy, [0.0; 2], wc, w_ring).f;
        let f2 = land(2.0 * bg).force(e_xy, [0.0; 2], wc, w_ring).f;
        let want = [f2[0] - f1[0], f2[1] - f1[1]];
        let got = [acc[1][0] - acc[0][0], acc[1][1] - acc[0][1]];
        let mag = want[0].hypot(want[1]);
        assert!(mag > 0.0);
        for k in 0..2 {
            assert!(
                (got[k] - want[k]).abs() < 1e-6 * mag,
                "{guidance:?} {got:?} {want:?}"
            );
        }
        // Restoring and forward: along e negative, along e_perp (+90° about z) positive.
        let (c, s) = (ang.cos(), ang.sin());
        assert!(got[0] * c + got[1] * s < 0.0, "{guidance:?} {got:?}");
        assert!(-got[0] * s + got[1] * c > 0.0, "{guidance:?} {got:?}");
    }
}

/// Cage mass unbalance `u`: the geometric centre's acceleration changes by exactly
/// `u (w_c² e - w_c' e_perp)` (`e` the cage's angle-origin direction), i.e. the mass
/// centre `c + u e` obeys `m a = F` with the same forces; at 120 000 rpm and 10 µm that is
/// the rotating load `m_c u w_c²` (tenths of a newton for the 7004's cage), outward along `e`.
#[test]
fn cage_unbalance_adds_the_rotating_load() {
    let b = preset("7004").unwrap().build().unwrap();
    let omega = rpm(120_000.0);
    let q = qs_displacement(omega);
    let u = 10e-6;
    let mut out = Vec::new();
    for unbalance in [0.0, u] {
        let p = FullParams {
            cage_unbalance: unbalance,
            ..FullParams::for_bearing(&b)
        };
        let (mut m, mut y, mut aux) = started(p, &q, omega);
        let (l, t0) = m.scales();
        y[5] = 2.1; // cage angle, rad
        let mut dx = vec![0.0; y.len()];
        m.eval(&q, &[0.0; 5], omega, &y, &mut aux, &mut dx).unwrap();
        let wc = m.cage_omega(&y);
        out.push(([dx[6] * l / t0, dx[7] * l / t0], wc, dx[11] / t0));
    }
    let ((a0, wc, wd), (a1, _, wd1)) = (out[0], out[1]);
    assert_eq!(wd, wd1, "the rotation is not changed");
    let (s, c) = 2.1f64.sin_cos();
    let want = [u * (wc * wc * c + wd * s), u * (wc * wc * s - wd * c)];
    for k in 0..2 {
        assert!(
            (a1[k] - a0[k] - want[k]).abs() < 1e-9 * want[0].hypot(want[1]),
            "{a0:?} {a1:?} {want:?}"
        );
    }
    // Outward along e, of the size m_c u w_c².
    let f = b.cage.mass * ((a1[0] - a0[0]) * c + (a1[1] - a0[1]) * s);
    let fc = b.cage.mass * u * wc * wc;
    assert!(fc > 0.05 && (f - fc).abs() < 1e-3 * fc, "{f} {fc}");
}

/// The component reports the full level's own ball loads (what `raceway run` plots): at
/// the start, from the quasi-static solution, they are the Jones–Harris loads at the same
/// motion ball by ball (to the centrifugal-radius change and the tractions, as
/// `quasi_static_start_equals_the_quasi_static_solver` measures, well inside 2 %), and the
/// loaded balls carry the axial load.
#[test]
fn component_reports_the_full_levels_own_ball_loads() {
    let text = include_str!("../examples/scenes/7004-30000.toml");
    let mut c = Component::from_text(text).unwrap();
    let fz = c.get_real(vr("force.z")).unwrap();
    let mut el = Vec::new();
    assert!(
        c.element_loads(&mut el),
        "the full level resolves its balls"
    );
    let loads: Vec<(f64, f64, f64)> = el.iter().map(|l| (l.psi, l.inner, l.outer)).collect();
    let b = c.bearing().clone();
    assert_eq!(loads.len(), b.z);
    let q: [f64; 5] = std::array::from_fn(|k| {
        c.get_real(vr([
            "shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry",
        ][k]))
            .unwrap()
    });
    let omega = c.get_real(vr("shaft.omega")).unwrap();
    let qs = QuasiStatic::new(&b, Options::default()).unwrap();
    let psi: Vec<f64> = loads.iter().map(|l| l.0).collect();
    let mut st = vec![BallState::default(); b.z];
    let mut res = vec![BallResult::default(); b.z];
    qs.evaluate(&q, omega, &psi, &mut st, None, Some(&mut res))
        .unwrap();
    for ((_, qi, qo), r) in loads.iter().zip(&res) {
        assert!((qi - r.q_i).abs() < 0.02 * r.q_i, "{qi} vs {}", r.q_i);
        assert!((qo - r.q_o).abs() < 0.02 * r.q_o, "{qo} vs {}", r.q_o);
    }
    // The axial load is carried: sum Q_i sin(alpha_i) of the Jones–Harris angles.
    let axial: f64 = loads
        .iter()
        .zip(&res)
        .map(|((_, qi, _), r)| qi * r.alpha_i.sin())
        .sum();
    println!("axial {axial} vs force.z {fz}; loads {loads:?}");
    assert!(
        (axial - fz.abs()).abs() < 0.03 * fz.abs(),
        "{axial} vs {fz}"
    );
    let qs_level = Component::new(raceway::component::scene::Scene::default_scene()).unwrap();
    assert!(!qs_level.element_loads(&mut el), "kept only when asked");
}

/// The stiffness and damping outputs are computed when first read after a step, not by
/// the step: a host that reads them after every step and one that reads only the forces
/// (and the matrices every third step) see the same states, memory, forces and matrices
/// bit for bit (the deferral changes no number of the run), the matrices are those
/// `refresh_outputs` computes at once, and a state saved with the matrices pending gives
/// them, restored into another component, with the same bits.
#[test]
fn stiffness_and_damping_computed_when_read_keep_their_bits() {
    let text = include_str!("../examples/scenes/7004-30000.toml");
    let (mut a, mut b) = (
        Component::from_text(text).unwrap(),
        Component::from_text(text).unwrap(),
    );
    let mats: Vec<u32> = variables::all()
        .filter(|v| v.name.starts_with("K.") || v.name.starts_with("C."))
        .map(|v| v.vr)
        .collect();
    assert_eq!(mats.len(), 50);
    let forces: Vec<u32> = ["force.x", "force.y", "force.z", "moment.x", "moment.y"]
        .iter()
        .map(|n| vr(n))
        .collect();
    let bits = |c: &mut Component, vrs: &[u32]| -> Vec<u64> {
        vrs.iter()
            .map(|&v| c.get_real(v).unwrap().to_bits())
            .collect()
    };
    let h = 20e-6;
    let mut saw_stiffness = false;
    for i in 0..9 {
        let t = i as f64 * h;
        a.do_step(t, h).unwrap();
        b.do_step(t, h).unwrap();
        // After a step a read may still compute (the matrices are pending, so the C ABI's
        // all-or-nothing read checks every reference by reading it); once read, not.
        assert!(a.reads_may_compute() && !a.outputs_stale(), "step {i}");
        let ka = bits(&mut a, &mats);
        assert!(!a.reads_may_compute(), "step {i}");
        assert_eq!(bits(&mut a, &forces), bits(&mut b, &forces), "step {i}");
        assert_eq!(a.state().x, b.state().x, "step {i}");
        assert_eq!(a.state().aux, b.state().aux, "step {i}");
        if i % 3 == 2 {
            // Saved pending, restored elsewhere: the same matrices.
            assert!(b.state().matrices_pending);
            let saved = b.serialize_state();
            let mut r = Component::from_text(text).unwrap();
            r.deserialize_state(&saved).unwrap();
            assert_eq!(bits(&mut r, &mats), ka, "restored, step {i}");
            assert_eq!(bits(&mut b, &mats), ka, "step {i}");
            assert!(!b.state().matrices_pending);
            // All at once, as a read after setting an input computes them.
            b.refresh_outputs().unwrap();
            assert_eq!(bits(&mut b, &mats), ka, "refreshed, step {i}");
        }
        saw_stiffness |= f64::from_bits(ka[0]) > 1e6;
    }
    assert!(saw_stiffness, "K.x.x of a loaded bearing");
}

/// The load-driven start with dynamic ball contacts on the geometry of Exudyn's ball-bearing
/// test model (14 balls, 200 N axial and the shaft's weight; issue #36): at 3 000 and
/// 30 000 rpm the static start finds the whole bearing's equilibrium — the balls placed in
/// their quasi-static positions at every trial ring displacement, not frozen where the
/// ring was at rest (which at 30 000 rpm, with the balls thrown outwards, left no
/// equilibrium under the load) — so it starts at the displacement of the quasi-static ball
/// contacts, and the shaft's wrench balances the loads there.
#[test]
fn dynamic_ball_contacts_start_at_the_quasi_static_equilibrium() {
    let shaft_mass = 7800.0 * PI * 0.025 * 0.025 * 0.120;
    let scene = |rpm: f64, contacts: &str| {
        format!(
            "[bearing]\nname = \"exudyn-6010\"\nkind = \"deep_groove\"\nball_diameter_mm = 8.73\n\
             pitch_diameter_mm = 65.0\nball_count = 14\ninner_curvature = 0.625\n\
             outer_curvature = 0.625\nclearance_um = 0.0\nbore_mm = 50.0\n\
             outer_diameter_mm = 80.0\nwidth_mm = 16.0\n\n[model]\nlevel = \"full\"\n\
             causality = \"load\"\nattached_mass_kg = {shaft_mass}\n\n[model.full]\n\
             ball_contacts = \"{contacts}\"\n\
             traction = {{ law = \"coulomb\", mu_max = 0.2, v_s = 0.01 }}\n\n\
             [inputs]\nrule = \"velocity\"\nspeed_rpm = {rpm}\n\
             initial = {{ \"load.x\" = 0.0, \"load.y\" = {}, \"load.z\" = 200.0, \"load.mx\" = 0.0, \"load.my\" = 0.0 }}\n\n\
             [run]\nduration_s = 1e-3\nstep_s = 1e-4\n",
            -9.81 * shaft_mass
        )
    };
    let read = |c: &mut Component, names: &[&str]| -> Vec<f64> {
        names.iter().map(|n| c.get_real(vr(n)).unwrap()).collect()
    };
    let q_names = ["shaft.x", "shaft.y", "shaft.z"];
    for rpm in [3000.0, 30_000.0] {
        let mut dynamic = Component::from_text(&scene(rpm, "dynamic"))
            .unwrap_or_else(|e| panic!("{rpm} rpm, dynamic: {e}"));
        let mut qs = Component::from_text(&scene(rpm, "quasi_static")).unwrap();
        let (qd, qq) = (read(&mut dynamic, &q_names), read(&mut qs, &q_names));
        println!("{rpm} rpm: dynamic {qd:?}, quasi-static {qq:?} m");
        // The axial displacement under 200 N is micrometres: the two agree to 1e-9 m.
        assert!(qq[2] > 1e-7, "{qq:?}");
        for (a, b) in qd.iter().zip(&qq) {
            assert!((a - b).abs() < 1e-9, "{rpm} rpm: {qd:?} against {qq:?}");
        }
        let f = read(&mut dynamic, &["force.x", "force.y", "force.z"]);
        let load = [0.0, -9.81 * shaft_mass, 200.0];
        for (fk, lk) in f.iter().zip(load) {
            assert!((fk + lk).abs() < 1e-6 * 200.0, "{rpm} rpm: force {f:?}");
        }
    }
}
