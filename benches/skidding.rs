//! CPU time per simulated second of the skidding level: the 7008CE (16 balls) at
//! 6000 rpm under 300 N axial, load-driven, through the component (RODAS4). Three host
//! step sizes: one long `do_step` (straight through: the integrator picks its own steps),
//! 1 ms, and 0.1 ms (component mode: outputs, stiffness and `dF/dt` every 0.1 ms). Prints
//! the figures and the integrator counters. Then the speed goal's case (benches/speed.rs,
//! issue #17: settled 20 ms in 1 ms steps, then 20 ms in 0.1 ms steps) with each
//! Rosenbrock method at the scene's tolerance, and its force error against RODAS4 at
//! rtol 1e-9. Run: `cargo bench --bench skidding`.

use raceway::component::{variables, Component, Method, Scene};
use raceway::report::{force_error, load_average, thread_cpu_s as cpu_now, Samples};

#[path = "common/counters.rs"]
mod counters;
#[path = "common/runup_6000.rs"]
mod runup_6000;

fn vr(n: &str) -> u32 {
    variables::by_name(n).unwrap().vr
}

/// The shipped run-up scene at a constant 6000 rpm (a fresh component at speed starts at
/// the kinematic speeds).
fn scene_at_speed() -> Scene {
    Scene::from_text(&runup_6000::scene()).expect("scene")
}

/// A component of `scene` after `ms` untimed steps of 1 ms.
fn settled(scene: Scene, ms: usize) -> Component {
    let mut c = Component::new(scene).expect("scene");
    for i in 0..ms {
        c.do_step(i as f64 * 1e-3, 1e-3).expect("settle");
    }
    c
}

/// A fresh component at 6000 rpm, settled 50 ms (not timed); then `sim` simulated seconds
/// in host steps of `h`, with the scene's integrator or `method`. Returns the CPU seconds
/// per simulated second.
fn case(label: &str, h: f64, sim: f64, method: Option<Method>) -> f64 {
    let mut scene = scene_at_speed();
    if let Some(m) = method {
        scene.solver.method = m;
    }
    let mut c = settled(scene, 50);
    let s0 = c.stats();
    let n = (sim / h).round() as usize;
    let t_start = c.time();
    let c0 = cpu_now();
    for i in 0..n {
        c.do_step(t_start + i as f64 * h, h).expect("step");
    }
    let cpu = cpu_now() - c0;
    let s1 = c.stats();
    println!(
        "skidding 7008CE 6000 rpm 300 N, {label}: {:.3} s thread CPU per simulated s ({}x real time; load average {})",
        cpu / sim,
        ((sim / cpu) * 100.0).round() / 100.0,
        load_average()
    );
    println!("{}", counters::per("simulated s", &s0, &s1, sim));
    println!(
        "  cage slip {:.4}, cage speed {:.2} rad/s, Fz {:.1} N, torque {:.3e} N m, power {:.2} W",
        c.get_real(vr("cage.slip")).unwrap(),
        c.get_real(vr("cage.omega")).unwrap(),
        c.get_real(vr("force.z")).unwrap(),
        c.get_real(vr("torque.z")).unwrap(),
        c.get_real(vr("power.loss")).unwrap_or(f64::NAN),
    );
    cpu / sim
}

/// The speed goal's run (as `benches/speed.rs`'s `skidding_run`) with `method` at `rtol`
/// (`atol_m = 1e-4 rtol`): CPU per 0.1 ms step, the force samples and the counters.
fn goal_run(method: Method, rtol: f64, t_end: f64) -> (f64, Samples, raceway::component::Stats) {
    let mut scene = scene_at_speed();
    scene.solver.method = method;
    scene.solver.rtol = rtol;
    scene.solver.atol_m = rtol * 1e-4;
    let mut c = settled(scene, 20);
    let h = 1e-4;
    let t0 = c.time();
    let n = (t_end / h).round() as usize;
    let fv = [vr("force.x"), vr("force.y"), vr("force.z")];
    let mut s = Samples {
        t: Vec::new(),
        f: Vec::new(),
    };
    let s0 = c.stats();
    let c0 = cpu_now();
    for i in 0..n {
        c.do_step(t0 + i as f64 * h, h).expect("step");
        s.t.push(c.time());
        s.f.push(fv.map(|v| c.get_real(v).unwrap()));
    }
    let cpu = (cpu_now() - c0) / n as f64;
    let s1 = c.stats();
    let mut d = s1;
    d.rhs = s1.rhs - s0.rhs;
    d.jacobians = s1.jacobians - s0.jacobians;
    d.factorizations = s1.factorizations - s0.factorizations;
    d.accepted = s1.accepted - s0.accepted;
    d.rejected = s1.rejected - s0.rejected;
    (cpu, s, d)
}

fn main() {
    // `-- goal`: the speed goal's case only; `-- goal ros34pw2`: one method.
    let args: Vec<String> = std::env::args().collect();
    let goal_only = args.iter().any(|a| a == "goal");
    let only_w = args.iter().any(|a| a == "ros34pw2");
    if args.iter().any(|a| a == "profile") {
        // `-- profile`: ROS34PW2's goal run only, 1 s and no reference (for perf).
        let (cpu, s, d) = goal_run(Method::Ros34pw2, 1e-5, 1.0);
        // A fingerprint of every force sample's bits (the same trajectory, bit for bit?).
        let bits = s.f.iter().flatten().fold(0u64, |h, f| {
            (h ^ f.to_bits()).wrapping_mul(0x0100_0000_01b3)
        });
        println!(
            "ROS34PW2 rtol 1e-5: {:.1} us per 0.1 ms step, {d:?}, forces {bits:016x}",
            cpu * 1e6
        );
        return;
    }
    if !goal_only {
        host_steps();
    }
    goal_cases(only_w);
}

/// The three host step sizes with the scene as shipped.
fn host_steps() {
    let straight = case("one 0.2 s step (straight through)", 0.2, 0.2, None);
    let ms = case("host step 1 ms", 1e-3, 0.2, None);
    let comp = case("host step 0.1 ms (component mode)", 1e-4, 0.5, None);
    println!(
        "component mode (0.1 ms) / straight through: {:.2}; / 1 ms steps: {:.2}",
        comp / straight,
        comp / ms
    );
    let w = Some(Method::Ros34pw2);
    case("ROS34PW2, one 0.2 s step (straight through)", 0.2, 0.2, w);
    case("ROS34PW2, host step 1 ms", 1e-3, 0.2, w);
    case("ROS34PW2, host step 0.1 ms (component mode)", 1e-4, 0.5, w);
}

/// The speed goal's case with each method, against RODAS4 at rtol 1e-9.
fn goal_cases(only_w: bool) {
    let t_end = 0.02;
    let (_, reference, _) = goal_run(Method::Rosenbrock, 1e-9, t_end);
    let methods = [
        ("RODAS4", Method::Rosenbrock),
        ("ROS34PW2", Method::Ros34pw2),
    ];
    for &(name, m) in &methods[usize::from(only_w)..] {
        for rtol in [1e-5, 1e-4] {
            let (cpu, s, d) = goal_run(m, rtol, t_end);
            let (l2, peak) = force_error(&s, &reference).unwrap_or((f64::NAN, f64::NAN));
            let n = s.t.len() as f64;
            println!(
                "speed goal case, {name} rtol {rtol:e}: {:.2}x real time ({:.1} us per 0.1 ms step), force error L2 {l2:.2e} peak {peak:.2e} vs RODAS4 rtol 1e-9; per step: rhs {:.2}, jacobians {:.2}, LU {:.2}, accepted {:.2}, rejected {:.2} (load average {})",
                1e-4 / cpu,
                cpu * 1e6,
                d.rhs as f64 / n,
                d.jacobians as f64 / n,
                d.factorizations as f64 / n,
                d.accepted as f64 / n,
                d.rejected as f64 / n,
                load_average()
            );
        }
    }
}
