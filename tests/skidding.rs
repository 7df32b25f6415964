//! The skidding level (docs/physics.md §5.2) through the component and the model API.
//!
//! Each test integrates at most a few tenths of a simulated second of a 6012 (14 balls).

use raceway::component::{variables, Component};
use raceway::geometry::{kinematics::kinematics, preset};
use raceway::models::skidding::{SkiddingModel, SkiddingParams};
use raceway::solver::{OdeSystem, Options, Rosenbrock};
use std::f64::consts::PI;

#[path = "common/motion_scene.rs"]
mod motion_scene;
use motion_scene::motion_scene;
#[path = "common/thread_alloc.rs"]
mod thread_alloc;
#[global_allocator]
static A: thread_alloc::Counting = thread_alloc::Counting;

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

/// A motion-driven 6012 scene: radial displacement `y` (m), shaft speed `omega` (rad/s),
/// extra `[model.skidding]` lines.
fn scene_6012(y: f64, omega: f64, skid: &str) -> String {
    motion_scene("6012", "skidding", [0.0, y, 0.0, 0.0, 0.0], omega, skid)
}

/// Run `n` steps of `h`, returning per-step (t, cage slip, cage speed, Fy).
fn run(c: &mut Component, n: usize, h: f64) -> Vec<(f64, f64, f64, f64)> {
    run_ramp(c, n, h, 0.0)
}

/// As [`run`] with the shaft speed ramped at `accel` rad/s² (set each step with its
/// derivative, as a host would).
fn run_ramp(c: &mut Component, n: usize, h: f64, accel: f64) -> Vec<(f64, f64, f64, f64)> {
    let mut out = Vec::with_capacity(n);
    let w0 = c.get_real(vr("shaft.omega")).unwrap();
    for _ in 0..n {
        let t = c.time();
        if accel != 0.0 {
            c.set_real(vr("shaft.omega"), w0 + accel * t).unwrap();
            c.set_input_derivative(vr("shaft.omega"), 1, accel).unwrap();
        }
        c.do_step(t, h).unwrap();
        out.push((
            c.time(),
            c.get_real(vr("cage.slip")).unwrap(),
            c.get_real(vr("cage.omega")).unwrap(),
            c.get_real(vr("force.y")).unwrap(),
        ));
    }
    out
}

fn mean(v: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    s / n as f64
}

/// From rest under a speed ramp (500 rad/s²) the cage slip starts at 100 % and falls as
/// traction spins the balls up and they push the cage.
#[test]
fn runup_from_rest_slip_starts_at_one_and_falls() {
    let mut c = Component::from_text(&scene_6012(-10e-6, 0.0, "")).unwrap();
    assert!((c.get_real(vr("cage.slip")).unwrap() - 1.0).abs() < 1e-12);
    let r = run_ramp(&mut c, 100, 1e-3, 500.0);
    let early = r[0].1;
    let late = mean(r[80..].iter().map(|x| x.1));
    println!("slip at 1 ms {early:.4}, mean over 80-100 ms {late:.4}");
    assert!(early > 0.5, "slip just after start {early}");
    assert!(late < 0.1 && late < early, "slip late in the ramp {late}");
}

/// At constant speed the cage runs near its kinematic speed under a high load, and slips
/// more under a light load at a higher speed.
#[test]
fn slip_small_under_load_larger_when_light_and_fast() {
    let w_lo = 2000.0 * PI / 30.0;
    let mut heavy =
        Component::from_text(&scene_6012(-12e-6, w_lo, "drag_coefficient = 15.0")).unwrap();
    let rh = run(&mut heavy, 60, 1e-3);
    let slip_h = mean(rh[20..].iter().map(|x| x.1));
    let w_hi = 10000.0 * PI / 30.0;
    let mut light =
        Component::from_text(&scene_6012(-5.05e-6, w_hi, "drag_coefficient = 15.0")).unwrap();
    let rl = run(&mut light, 60, 2e-4);
    let slip_l = mean(rl[20..].iter().map(|x| x.1));
    println!("cage slip: heavy 2000 rpm {slip_h:.5}, light 10000 rpm {slip_l:.5}");
    assert!(slip_h.abs() < 0.01, "heavy-load slip {slip_h}");
    assert!(
        slip_l > 5.0 * slip_h.abs() && slip_l > 0.0,
        "light-load slip {slip_l}"
    );
}

/// The ball-pass line `Z w_cage / 2 pi` sits slightly below the kinematic BPFO.
#[test]
fn ball_pass_frequency_slightly_below_kinematic() {
    let b = preset("6012").unwrap().build().unwrap();
    let w = 2000.0 * PI / 30.0;
    let mut c = Component::from_text(&scene_6012(-10e-6, w, "drag_density = 50.0")).unwrap();
    let r = run(&mut c, 80, 1e-3);
    // Cage angle over the window from the cage speed history (trapezoid).
    let wc = mean(r[30..].iter().map(|x| x.2));
    let bpf = b.z as f64 * wc / (2.0 * PI);
    let kin = kinematics(&b, w).bpfo;
    let shift = 1.0 - bpf / kin;
    println!(
        "BPFO kinematic {kin:.3} Hz, from the cage {bpf:.3} Hz, shift {:.3} %",
        100.0 * shift
    );
    assert!(shift > 0.0 && shift < 0.03, "shift {shift}");
}

/// With a very steep traction law the level converges to the ring level: cage at the
/// kinematic speed, and the same mean force.
#[test]
fn stiff_traction_converges_to_ring_level() {
    let w = 500.0 * PI / 30.0;
    let skid = r#"traction = { law = "coulomb", mu_max = 0.2, v_s = 1e-4 }
drag_density = 0.0"#;
    let mut c = Component::from_text(&scene_6012(-12e-6, w, skid)).unwrap();
    let r = run(&mut c, 60, 1e-3);
    let slip = mean(r[20..].iter().map(|x| x.1));
    let fy = mean(r[20..].iter().map(|x| x.3));
    let ring = scene_6012(-12e-6, w, "").replace("level = \"skidding\"", "level = \"ring\"");
    let ring = ring.replace("[model.skidding]\n", "");
    let mut rc = Component::from_text(&ring).unwrap();
    let rr = run(&mut rc, 60, 1e-3);
    let fy_ring = mean(rr[20..].iter().map(|x| x.3));
    println!("stiff traction: slip {slip:.2e}, Fy {fy:.2} vs ring level {fy_ring:.2}");
    assert!(slip.abs() < 1e-3, "cage slip {slip}");
    assert!(
        (fy - fy_ring).abs() < 0.01 * fy_ring.abs(),
        "{fy} vs {fy_ring}"
    );
}

/// Balls plus cage as an ODE with one more state: the time integral of the external
/// torques (race tractions, drags). Angular momentum must equal its start value plus that
/// integral, to the integration tolerance.
struct Balance {
    m: SkiddingModel,
    q: [f64; 5],
    omega: f64,
}

impl OdeSystem for Balance {
    fn dim(&self) -> usize {
        self.m.n_states() + 2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        let n = self.m.n_states();
        let tot = self
            .m
            .eval(&self.q, &[0.0; 5], self.omega, &y[..n], &mut dy[..n]);
        dy[n] = -tot.torque_shaft - tot.torque_outer + tot.torque_drag;
        // Shaft power in, minus everything dissipated.
        dy[n + 1] = -tot.torque_shaft * self.omega - tot.power_contacts - tot.power_other;
        Ok(())
    }
}

/// Kinetic plus pocket-spring energy of balls and cage.
fn energy(m: &mut SkiddingModel, q: &[f64; 5], omega: f64, x: &[f64]) -> f64 {
    let mut dx = vec![0.0; x.len()];
    let tot = m.eval(q, &[0.0; 5], omega, x, &mut dx);
    m.kinetic_energy(x) + tot.pocket_energy
}

/// Spin balls and cage up from rest for `t_end` with the ring held at `q`: returns the
/// balance system at the end (its model holds the final per-ball results), the momentum and
/// energy at start and end, the integral of the external moments and the net work.
struct SpinUp {
    sys: Balance,
    l0: f64,
    l1: f64,
    e0: f64,
    e1: f64,
    moments: f64,
    work: f64,
    y: Vec<f64>,
}

fn spin_up(m: SkiddingModel, q: [f64; 5], omega: f64, t_end: f64) -> SpinUp {
    let n = m.n_states();
    let mut y = vec![0.0; n + 2];
    m.init(0.0, &mut y[..n]);
    let l0 = m.angular_momentum(&y[..n]);
    let mut sys = Balance { m, q, omega };
    let e0 = energy(&mut sys.m, &q, omega, &y[..n]);
    let mut integ = Rosenbrock::new(n + 2);
    let mut opts = Options::new(n + 2, 1e-6, 1e-10);
    opts.max_steps = 1_000_000;
    let mut h = 0.0;
    integ
        .integrate(&mut sys, 0.0, t_end, &mut y, &mut h, &opts)
        .unwrap();
    let l1 = sys.m.angular_momentum(&y[..n]);
    let e1 = energy(&mut sys.m, &q, omega, &y[..n]);
    SpinUp {
        l0,
        l1,
        e0,
        e1,
        moments: y[n],
        work: y[n + 1],
        sys,
        y,
    }
}

#[test]
fn angular_momentum_and_energy_balances_close() {
    let b = preset("6012").unwrap().build().unwrap();
    let p = SkiddingParams {
        spacing_scatter: 0.5,
        cage_drag: 1e-5,
        drag_viscosity: 0.01,
        ..SkiddingParams::default()
    };
    let m = SkiddingModel::new(&b, p).unwrap();
    // Start from rest: strong spin-up, pocket impacts.
    let SpinUp {
        sys,
        l0,
        l1,
        e0,
        e1,
        moments: ext,
        work,
        ..
    } = spin_up(m, [0.0, -12e-6, 0.0, 0.0, 0.0], 200.0, 0.005);
    let scale = sys.m.z() as f64 * 1e-3; // |L| scale of the spun-up set
    println!(
        "L0 {l0:e}, L1 {l1:e}, integral of torques {ext:e}, residual {:e}",
        l1 - l0 - ext
    );
    assert!(l1 > 0.0, "the shaft spun the balls up");
    assert!(
        (l1 - l0 - ext).abs() < 1e-6 * l1.abs().max(scale),
        "balance"
    );
    // Energy: kinetic + pocket springs = start + work in - dissipated, to the tolerance.
    println!(
        "E0 {e0:e}, E1 {e1:e}, net work {work:e}, residual {:e}",
        e1 - e0 - work
    );
    assert!(e1 > 0.0);
    assert!((e1 - e0 - work).abs() < 1e-4 * e1, "energy balance");
}

/// Load-driven (the 6012 scene of study \[2\]): the ring settles where the bearing carries
/// the 500 N load, and stepping allocates nothing.
#[test]
fn load_driven_6012_carries_its_load_without_allocating() {
    let text = include_str!("../examples/scenes/6012-skidding.toml");
    let mut c = Component::from_text(text).unwrap();
    let r = run(&mut c, 40, 1e-3);
    let fy = mean(r[20..].iter().map(|x| x.3));
    let before = thread_alloc::allocations();
    let r2 = run_steps_only(&mut c, 10, 1e-3);
    let allocs = thread_alloc::allocations() - before;
    let slip = c.get_real(vr("cage.slip")).unwrap();
    println!(
        "6012 load-driven: mean Fy {fy:.2} N, slip {slip:.4}, {r2} steps, {allocs} allocations"
    );
    assert!((fy - 500.0).abs() < 10.0, "Fy {fy}");
    assert_eq!(allocs, 0);
    assert!(
        c.get_real(vr("torque.z")).unwrap() < 0.0,
        "friction resists the shaft"
    );
    assert!(c.get_real(vr("power.loss")).unwrap() > 0.0);
}

fn run_steps_only(c: &mut Component, n: usize, h: f64) -> usize {
    for _ in 0..n {
        let t = c.time();
        c.do_step(t, h).unwrap();
    }
    n
}

/// The 7008CE of study \[3\] under 300 N axial at constant speeds: print the cage slip.
#[test]
#[ignore]
fn explore_7008ce_speeds() {
    let text = include_str!("../examples/scenes/7008ce-runup.toml");
    for rpm in [6000.0, 12000.0, 18000.0, 24000.0] {
        let t = text.replace("speed_rpm = 0.0", &format!("speed_rpm = {rpm:?}"));
        let mut c = Component::from_text(&t).unwrap();
        let r = run(&mut c, 60, 5e-4);
        let slip = mean(r[20..].iter().map(|x| x.1));
        println!(
            "{rpm} rpm: cage slip {slip:.3e}, torque {:.3e}, {:?}",
            c.get_real(vr("torque.z")).unwrap(),
            c.stats()
        );
    }
}

#[test]
#[ignore]
fn explore_runup() {
    let mut c = Component::from_text(&scene_6012(-10e-6, 0.0, "")).unwrap();
    let r = run_ramp(&mut c, 100, 1e-3, 500.0);
    for x in r.iter().step_by(5) {
        println!("{x:?} omega {}", 500.0 * x.0);
    }
    println!("{:?}", c.stats());
}

#[test]
#[ignore]
fn explore_7008ce_balls() {
    let b = preset("7008ce").unwrap().build().unwrap();
    let p = SkiddingParams {
        drag_coefficient: 15.0,
        drag_density: 10.0,
        traction: raceway::contact::traction::TractionLaw::Coulomb {
            mu_max: 0.02,
            v_s: 0.05,
        },
        ..SkiddingParams::default()
    };
    let m = SkiddingModel::new(&b, p).unwrap();
    let n = m.n_states();
    let w = 6000.0 * PI / 30.0;
    let mut y = vec![0.0; n + 2];
    m.init(w, &mut y[..n]);
    let mut sys = Balance {
        m,
        q: [0.0, 0.0, 12e-6, 0.0, 0.0],
        omega: w,
    };
    let mut integ = Rosenbrock::new(n + 2);
    let opts = Options::new(n + 2, 1e-6, 1e-10);
    let mut h = 0.0;
    integ
        .integrate(&mut sys, 0.0, 0.02, &mut y, &mut h, &opts)
        .unwrap();
    let mut dy = vec![0.0; n + 2];
    sys.rhs(0.0, &y, &mut dy).unwrap();
    let (wk, _) = sys.m.kinematic(w);
    println!("wk {wk} wc {} ", y[sys.m.cage_index() + 1]);
    for b in sys.m.balls.iter().take(3) {
        println!("{b:?}");
    }
}

/// The 7008CE run-up scene (study \[3\]): load-driven from rest at 500 rad/s².
#[test]
fn runup_7008ce_scene_from_rest() {
    let text = include_str!("../examples/scenes/7008ce-runup.toml");
    let mut c = Component::from_text(text).unwrap();
    let r = run_ramp(&mut c, 60, 1e-3, 500.0);
    let fz = mean(r[40..].iter().map(|_| c.get_real(vr("force.z")).unwrap()));
    println!(
        "7008CE run-up: slip at 1 ms {:.3}, at 60 ms {:.4}, Fz {fz:.1}, {:?}",
        r[0].1,
        r[59].1,
        c.stats()
    );
    assert!(r[0].1 > 0.5);
    assert!(r[59].1 < 0.2 && r[59].1 < r[0].1);
    assert!(
        (fz + 300.0).abs() < 15.0,
        "the ring carries the axial load: {fz}"
    );
}

/// The fitted-curve and mixed-EHL laws are scene choices too; under a high load at
/// 2000 rpm either keeps the cage within a few per cent of its kinematic speed.
#[test]
fn other_traction_laws_through_the_scene() {
    let w = 2000.0 * PI / 30.0;
    for law in [
        r#"traction = { law = "fitted", a = -0.0103, b = 1.1677, c = 13.0, d = 0.0103, s_reg = 1e-3, u_min = 0.01 }"#,
        r#"traction = { law = "mixed_ehl", viscosity = 0.04667, lambda_lim = 0.04 }"#,
    ] {
        let mut c = Component::from_text(&scene_6012(-12e-6, w, law)).unwrap();
        let r = run(&mut c, 30, 1e-3);
        let slip = mean(r[10..].iter().map(|x| x.1));
        println!("{law}: cage slip {slip:.5}");
        assert!(slip > -1e-3 && slip < 0.05, "{law}: {slip}");
    }
    let bad = scene_6012(
        -12e-6,
        w,
        r#"traction = { law = "coulomb", mu_max = 0.05, v_s = -1.0 }"#,
    );
    let e = Component::from_text(&bad).unwrap_err().to_string();
    assert!(e.contains("model.skidding.traction.v_s"), "{e}");
}

/// The 7008CE model with `p`, its states at the kinematic speeds of `omega`.
fn model_7008ce(p: SkiddingParams, omega: f64) -> (SkiddingModel, Vec<f64>) {
    let b = preset("7008ce").unwrap().build().unwrap();
    let m = SkiddingModel::new(&b, p).unwrap();
    let mut x = vec![0.0; m.n_states()];
    m.init(omega, &mut x);
    (m, x)
}

/// Gyroscopic couple (Harris & Kotzalas Vol. 2 ch. 3): at 24 000 rpm under an axial
/// approach, switching it on changes the wrench on the shaft by the lateral friction
/// through the inner contacts, `dFz = -sum_j F_j cos(alpha_j)` with
/// `F = (J w_s w_b sin(alpha0)/D) phi(mu Q_h D / Mg)`; the axial symmetry leaves the radial
/// forces and the moments unchanged. The rates of the balls do not change (the lateral
/// forces balance on each ball and do no work).
#[test]
fn gyroscopic_friction_changes_the_axial_force_by_the_predicted_amount() {
    let b = preset("7008ce").unwrap().build().unwrap();
    let omega = 24000.0 * PI / 30.0;
    let base = SkiddingParams {
        gyro_traction: f64::INFINITY,
        ..SkiddingParams::default()
    };
    let (mut on, mut x) = model_7008ce(base.clone(), omega);
    let (mut off, _) = model_7008ce(
        SkiddingParams {
            gyroscopic: false,
            ..base
        },
        omega,
    );
    // A slipping state near the kinematic one (the balls lag 1 %).
    for j in 0..on.z() {
        x[3 * j + 1] *= 0.99;
    }
    let q = [0.0, 0.0, 15e-6, 0.0, 0.0];
    let n = x.len();
    let (mut d_on, mut d_off) = (vec![0.0; n], vec![0.0; n]);
    let w_on = on.eval(&q, &[0.0; 5], omega, &x, &mut d_on).wrench;
    let w_off = off.eval(&q, &[0.0; 5], omega, &x, &mut d_off).wrench;
    assert_eq!(d_on, d_off, "the ball and cage rates do not change");
    // Prediction from the bearing data and the kinematics (unlimited friction).
    let alpha0 = b.nominal_contact_angle();
    let k = kinematics(&b, omega);
    // w_b lowered by 1 % at a fixed absolute spin w_a: w_s = w_b cos(alpha0) - w_a.
    let (wb, ws) = (
        0.99 * k.cage_speed,
        k.ball_spin_speed - 0.01 * k.cage_speed * alpha0.cos(),
    );
    let mg = b.ball_inertia() * ws * wb * alpha0.sin();
    // The contact line of this approach: the same for every ball.
    let s = on.balls[0];
    assert!(s.q_i > 0.0 && s.gyro > 0.0);
    let f = mg / b.d;
    assert!((s.gyro / f - 1.0).abs() < 1e-12, "F = Mg/D unlimited");
    // cos(alpha) of the loaded contact from the normal-force part of Fz.
    let fz_normal = w_off[2];
    let cos_a = {
        // Fz = -Z Q sin(alpha): recover alpha from it and the load.
        let sin_a = -fz_normal / (b.z as f64 * s.q_i);
        (1.0 - sin_a * sin_a).sqrt()
    };
    let predicted = -(b.z as f64) * f * cos_a;
    let dfz = w_on[2] - w_off[2];
    println!("Mg {mg:.4e} N m, F {f:.3} N per ball, dFz {dfz:.4} N, predicted {predicted:.4} N");
    assert!((dfz / predicted - 1.0).abs() < 1e-9, "{dfz} vs {predicted}");
    assert!(
        dfz < 0.0,
        "the lateral friction pulls the shaft further along -z"
    );
    for r in [0, 1, 3, 4] {
        let scale = if r < 3 { 1.0 } else { 1e-2 };
        assert!((w_on[r] - w_off[r]).abs() < 1e-9 * scale * f, "{r}");
    }
    // With the quasi-static level's default cap (mu = 0.3): smaller, never larger.
    let (mut capped, _) = model_7008ce(
        SkiddingParams {
            gyro_traction: 0.3,
            ..SkiddingParams::default()
        },
        omega,
    );
    let w_cap = capped.eval(&q, &[0.0; 5], omega, &x, &mut d_on).wrench;
    let dcap = w_cap[2] - w_off[2];
    assert!(dcap < 0.0 && dcap > dfz, "{dcap} vs {dfz}");
}

/// Spinning friction `M = (3/8) mu Q a E` (Harris & Kotzalas): a deep-groove bearing at
/// zero contact angle rolls without spin, so it changes nothing; in the 7008CE both
/// contacts spin, the moment dissipates power and adds a resisting torque on the shaft.
#[test]
fn spin_friction_zero_without_contact_angle_positive_power_with_it() {
    let spin = SkiddingParams {
        spin_friction: 0.05,
        ..SkiddingParams::default()
    };
    // 6012 at zero contact angle: no spin, nothing changes.
    let b = preset("6012").unwrap().build().unwrap();
    let mut m = SkiddingModel::new(&b, spin.clone()).unwrap();
    let mut m0 = SkiddingModel::new(&b, SkiddingParams::default()).unwrap();
    let mut x = vec![0.0; m.n_states()];
    m.init(300.0, &mut x);
    let q = [0.0, -12e-6, 0.0, 0.0, 0.0];
    let mut dx = vec![0.0; x.len()];
    let t = m.eval(&q, &[0.0; 5], 300.0, &x, &mut dx);
    let t0 = m0.eval(&q, &[0.0; 5], 300.0, &x, &mut dx);
    assert!(m.balls.iter().all(|s| s.spin_i == 0.0 && s.spin_o == 0.0));
    assert_eq!(t.power_contacts, t0.power_contacts);
    assert_eq!(t.torque_shaft, t0.torque_shaft);
    // 7008CE: spin at both contacts.
    let omega = 6000.0 * PI / 30.0;
    let (mut m, x) = model_7008ce(spin, omega);
    let (mut m0, _) = model_7008ce(SkiddingParams::default(), omega);
    let q = [0.0, 0.0, 12e-6, 0.0, 0.0];
    let mut dx = vec![0.0; x.len()];
    let t = m.eval(&q, &[0.0; 5], omega, &x, &mut dx);
    let t0 = m0.eval(&q, &[0.0; 5], omega, &x, &mut dx);
    let dp = t.power_contacts - t0.power_contacts;
    let dt = t.torque_shaft - t0.torque_shaft;
    let s = m.balls[0];
    println!(
        "7008CE 6000 rpm: spin moments inner {:.3e} outer {:.3e} N m, power +{dp:.3} W, torque {dt:.3e} N m",
        s.spin_i, s.spin_o
    );
    assert!(dp > 0.0, "spinning friction dissipates");
    assert!(dt < 0.0, "and resists the shaft");
    assert!(m.balls.iter().all(|s| s.spin_i < 0.0 && s.spin_o > 0.0));
}

/// Momentum and energy balances of the 7008CE with gyroscopic and spin friction on,
/// spun up from rest (pocket friction off: its component off the rolling axis turns the
/// unmodelled pivoting spin, so only `alpha = 0` closes the momentum balance with it).
#[test]
fn balances_close_with_gyroscopic_and_spin_friction() {
    let p = SkiddingParams {
        spin_friction: 0.05,
        pocket_friction: 0.0,
        spacing_scatter: 0.5,
        cage_drag: 1e-5,
        drag_viscosity: 0.01,
        ..SkiddingParams::default()
    };
    let (m, _) = model_7008ce(p, 0.0);
    let n = m.n_states();
    let SpinUp {
        mut sys,
        l0,
        l1,
        e0,
        e1,
        y,
        ..
    } = spin_up(m, [0.0, 0.0, 12e-6, 0.0, 0.0], 300.0, 0.003);
    let mut dy = vec![0.0; n + 2];
    sys.rhs(0.0, &y, &mut dy).unwrap();
    assert!(sys.m.balls.iter().all(|s| s.spin_i != 0.0 && s.gyro != 0.0));
    println!(
        "L residual {:e} of {l1:e}; E residual {:e} of {e1:e}",
        l1 - l0 - y[n],
        e1 - e0 - y[n + 1]
    );
    assert!(l1 > 0.0);
    assert!((l1 - l0 - y[n]).abs() < 1e-6 * l1.abs(), "momentum balance");
    assert!((e1 - e0 - y[n + 1]).abs() < 1e-4 * e1, "energy balance");
}

/// Balls with radial mass (`ball_radial_mass`): started away from radial equilibrium
/// (placed for a centred ring, then the ring is displaced), the damped radial motion
/// settles within a fraction of a millisecond onto the quasi-static split's loads. With
/// the option off the state vector is the three-per-ball one (nothing added).
#[test]
fn radial_mass_settles_on_the_quasi_static_split() {
    let b = preset("6012").unwrap().build().unwrap();
    let p = SkiddingParams {
        ball_radial_mass: true,
        contact_damping: 200.0,
        ..SkiddingParams::default()
    };
    let m = SkiddingModel::new(&b, p.clone()).unwrap();
    let qs = SkiddingModel::new(&b, SkiddingParams::default()).unwrap();
    assert_eq!(qs.n_states(), 3 * b.z + 2, "off: no extra states");
    assert_eq!(m.n_states(), 5 * b.z + 2);
    let omega = 2000.0 * PI / 30.0;
    let n = m.n_states();
    let mut y = vec![0.0; n + 2];
    m.init(omega, &mut y[..n]); // balls placed for q = 0
    let q = [0.0, -12e-6, 0.0, 0.0, 0.0];
    let mut sys = Balance { m, q, omega };
    let mut dy = vec![0.0; n + 2];
    sys.rhs(0.0, &y, &mut dy).unwrap();
    let first: Vec<(f64, f64)> = sys.m.balls.iter().map(|s| (s.q_i, s.q_o)).collect();
    let mut integ = Rosenbrock::new(n + 2);
    let mut opts = Options::new(n + 2, 1e-7, 1e-12);
    opts.max_steps = 1_000_000;
    let mut h = 0.0;
    integ
        .integrate(&mut sys, 0.0, 0.002, &mut y, &mut h, &opts)
        .unwrap();
    sys.rhs(0.0, &y, &mut dy).unwrap();
    // The quasi-static model at the same orbit and spin states.
    let mut qs = qs;
    let mut xq = vec![0.0; qs.n_states()];
    for j in 0..b.z {
        xq[3 * j..3 * j + 3].copy_from_slice(&y[5 * j..5 * j + 3]);
    }
    xq[3 * b.z..3 * b.z + 2].copy_from_slice(&y[5 * b.z..5 * b.z + 2]);
    let mut dq = vec![0.0; xq.len()];
    qs.eval(&q, &[0.0; 5], omega, &xq, &mut dq);
    let mut worst: f64 = 0.0;
    let mut moved: f64 = 0.0;
    for (j, (a, s)) in sys.m.balls.iter().zip(&qs.balls).enumerate() {
        let scale = s.q_i.max(s.q_o).max(1.0);
        worst = worst
            .max((a.q_i - s.q_i).abs() / scale)
            .max((a.q_o - s.q_o).abs() / scale);
        moved = moved.max((first[j].0 - s.q_i).abs() / scale);
    }
    println!("radial mass: start off by {moved:.3} of the load, settled to {worst:.2e}");
    assert!(moved > 0.1, "the start is away from equilibrium");
    assert!(worst < 1e-4, "settled on the split: {worst}");
}

/// The option through the scene: a motion-driven 6012 with radial mass runs and its
/// force matches the quasi-static level's once settled.
#[test]
fn radial_mass_through_the_scene() {
    let w = 2000.0 * PI / 30.0;
    let on = scene_6012(-12e-6, w, "ball_radial_mass = true").replace(
        "level = \"skidding\"",
        "level = \"skidding\"\ncontact_damping = 200.0",
    );
    let off = scene_6012(-12e-6, w, "").replace(
        "level = \"skidding\"",
        "level = \"skidding\"\ncontact_damping = 200.0",
    );
    let mut c_on = Component::from_text(&on).unwrap();
    let mut c_off = Component::from_text(&off).unwrap();
    let r_on = run(&mut c_on, 10, 1e-3);
    let r_off = run(&mut c_off, 10, 1e-3);
    let (f_on, f_off) = (r_on[9].3, r_off[9].3);
    println!("Fy with radial mass {f_on:.3} N, quasi-static {f_off:.3} N");
    assert!(
        (f_on - f_off).abs() < 1e-3 * f_off.abs(),
        "{f_on} vs {f_off}"
    );
}

/// Contact damping acts on loaded balls only. At 120 000 rpm centrifugal force holds the
/// 7008CE's balls off the inner race; a ring displaced by a few micrometres (total approach
/// positive, inner contact open) and orbiting balls make the total approach change fast.
/// No ball is loaded, so the shaft feels nothing, exactly, and the stiffness output is
/// zero. (Damping blended on the total approach pushed and pulled the shaft through the
/// open contact: tens of newtons at 10 µm, no stiffness to show it, and the static start
/// of a load-driven ring at this speed failed.) With the ring pushed further the inner
/// contacts close and the damping is back: the force changes with `contact_damping`.
#[test]
fn contact_damping_needs_a_loaded_inner_contact() {
    let scene = |s: f64, c: f64| {
        format!(
            r#"
bearing = "7008ce"
[model]
level = "skidding"
contact_damping = {c:e}
[model.skidding]
traction = {{ law = "coulomb", mu_max = 0.02, v_s = 0.05 }}
[inputs]
speed_rpm = 120000.0
initial = {{ "shaft.x" = 0.0, "shaft.y" = {:e}, "shaft.z" = {:e}, "shaft.rx" = 0.0, "shaft.ry" = 0.0,
            "shaft.vx" = 0.0, "shaft.vy" = 0.0, "shaft.vz" = 0.0, "shaft.wx" = 0.0, "shaft.wy" = 0.0 }}
"#,
            -s,
            0.5 * s
        )
    };
    let forces = |s: f64, c: f64| {
        let mut comp = Component::from_text(&scene(s, c)).unwrap();
        comp.refresh_outputs().unwrap();
        let mut g = |n: &str| comp.get_real(vr(n)).unwrap();
        (
            [g("force.x"), g("force.y"), g("force.z")],
            g("balls.loaded"),
            g("K.y.y"),
        )
    };
    // 10 µm along (0, -1, 0.5): inside the centrifugal gap (contacts close near 16 µm).
    let (f, loaded, kyy) = forces(1e-5, 100.0);
    assert_eq!(loaded, 0.0);
    assert_eq!(f, [0.0; 3], "force through an open contact");
    assert_eq!(kyy, 0.0);
    // 30 µm: inner contacts closed, the damping acts (the orbit moves the approach).
    let (f0, loaded, _) = forces(3e-5, 0.0);
    let (f1, _, _) = forces(3e-5, 100.0);
    assert!(loaded > 0.0);
    let d = (0..3).map(|k| (f1[k] - f0[k]).abs()).fold(0.0, f64::max);
    assert!(d > 1e-3, "damping of loaded balls: {f0:?} vs {f1:?}");
}

/// The 6012 load-driven scene with `solver.method = "ros34pw2"`. This level's Jacobian is
/// per-ball finite differences (and leaves a small term out with radial mass): a W-method
/// keeps its order with it, RODAS4 does not, and its error estimate drives it to tiny steps
/// (measured over 40 ms: RODAS4 rtol 1e-8 228 000 steps and 1.6 M right-hand sides,
/// ROS34PW2 7 400 and 32 000, the same slip to 4 digits; at the scene's rtol 1e-5 ROS34PW2's
/// slip is 30 % off at 40 ms, RODAS4's 0.4 %). So: ROS34PW2 at rtol 1e-8 agrees with
/// RODAS4 at the scene's 1e-5 on the load and the slip with fewer right-hand sides, steps
/// without allocating, and a state restored with `set_state` continues bit for bit (the
/// Jacobian it carries from step to step is dropped when a state is taken or set).
#[test]
fn ros34pw2_carries_the_load_like_rodas4_and_restores_bit_for_bit() {
    let text = include_str!("../examples/scenes/6012-skidding.toml");
    let w_text = text
        .replace("method = \"rosenbrock\"", "method = \"ros34pw2\"")
        .replace("rtol = 1e-5", "rtol = 1e-8")
        .replace("atol_m = 1e-9", "atol_m = 1e-12");
    assert_ne!(text, w_text, "the scene names its method");
    let mut r4 = Component::from_text(text).unwrap();
    let mut w = Component::from_text(&w_text).unwrap();
    let a = run(&mut r4, 40, 1e-3);
    let b = run(&mut w, 40, 1e-3);
    let (sa, sb) = (r4.stats(), w.stats());
    println!(
        "6012 RODAS4 rtol 1e-5: Fy {:.4} slip {:.6} {sa:?}; ROS34PW2 rtol 1e-8: Fy {:.4} slip {:.6} {sb:?}",
        a[39].3, a[39].1, b[39].3, b[39].1
    );
    assert!(
        (b[39].3 - a[39].3).abs() < 0.2,
        "Fy {} {}",
        a[39].3,
        b[39].3
    );
    assert!(
        (b[39].1 - a[39].1).abs() < 0.01 * a[39].1,
        "slip {} {}",
        a[39].1,
        b[39].1
    );
    assert!(sb.rhs < sa.rhs, "{sb:?} {sa:?}");
    let before = thread_alloc::allocations();
    run_steps_only(&mut w, 10, 1e-3);
    assert_eq!(thread_alloc::allocations() - before, 0);
    let saved = w.get_state();
    let bits = |c: &mut Component| {
        run(c, 10, 1e-4)
            .iter()
            .map(|x| [x.1.to_bits(), x.2.to_bits(), x.3.to_bits()])
            .collect::<Vec<_>>()
    };
    let first = bits(&mut w);
    w.set_state(&saved).unwrap();
    assert_eq!(first, bits(&mut w));
}

/// The 7008CE at 6000 rpm (the speed goal's scene, settled 20 ms) under ROS34PW2 in
/// 0.1 ms component steps: the W-method
/// carries its Jacobian from step to step (a few per 20 steps, not one a step), the
/// step after a state is taken starts with a fresh one, and the state continues bit for
/// bit when restored in the same component or in a new one. On the way: the peak
/// pressure output (from the largest loads) is the largest of the balls', bit for bit.
#[test]
fn ros34pw2_carries_its_jacobian_across_steps_and_a_taken_state_restores_bit_for_bit() {
    use raceway::component::{variables, Component};
    let text = include_str!("../examples/scenes/7008ce-runup.toml")
        .replace("speed_rpm = 0.0", "speed_rpm = 6000.0")
        .replace("method = \"rosenbrock\"", "method = \"ros34pw2\"");
    let forces =
        ["force.x", "force.y", "force.z", "cage.omega"].map(|n| variables::by_name(n).unwrap().vr);
    let steps = |c: &mut Component, n: usize| -> Vec<u64> {
        let mut bits = Vec::new();
        for _ in 0..n {
            c.do_step(c.time(), 1e-4).unwrap();
            bits.extend(forces.iter().map(|&v| c.get_real(v).unwrap().to_bits()));
        }
        bits
    };
    let mut c = Component::from_text(&text).unwrap();
    for _ in 0..20 {
        c.do_step(c.time(), 1e-3).unwrap();
    }
    let s0 = c.stats();
    steps(&mut c, 20);
    let s1 = c.stats();
    let (jac, acc) = (s1.jacobians - s0.jacobians, s1.accepted - s0.accepted);
    println!("20 steps: {jac} Jacobians, {acc} accepted, {s1:?}");
    assert!(acc >= 20 && jac <= 1 + acc / 5, "{s0:?} {s1:?}");
    // The peak-pressure output (from the largest loads) is the largest of the balls'.
    let p_out = c.get_real(variables::by_name("contact.max_pressure").unwrap().vr);
    let m = c.skidding_mut().unwrap().model();
    let per_ball = m
        .balls
        .iter()
        .map(|b| m.peak_pressure(b.q_i, b.q_o))
        .fold(0.0, f64::max);
    assert!(per_ball > 1e8);
    assert_eq!(p_out.unwrap().to_bits(), per_ball.to_bits());
    let saved = c.get_state();
    let j = c.stats().jacobians;
    c.do_step(c.time(), 1e-4).unwrap();
    assert_eq!(c.stats().jacobians, j + 1, "a fresh J after get_state");
    c.set_state(&saved).unwrap();
    let first = steps(&mut c, 12);
    c.set_state(&saved).unwrap();
    assert_eq!(first, steps(&mut c, 12));
    let mut d = Component::from_text(&text).unwrap();
    d.set_state(&saved).unwrap();
    assert_eq!(first, steps(&mut d, 12));
}
