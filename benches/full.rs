//! CPU time per shaft revolution of the full level (docs/physics.md §5.5, study \[0\]): the 7004
//! at 30 000 and 120 000 rpm under Fa 2000 N, Fr 400 N, motion-driven (the scenes
//! `examples/scenes/7004-30000.toml` and `7004-120000.toml`), through the component
//! (RODAS4 with the level's block Jacobian). Prints the figures and the integrator
//! counters. Run: `cargo bench --bench full`. Under `cargo test` (no `--bench` argument)
//! it takes one short step per scene as a smoke run.
//!
//! Then issue #17's rows: the same scenes with outputs every 20 µs (8 outputs read at
//! every point, as `benches/speed.rs`), one revolution settled and three timed, with the
//! force error over all points against the same run at rtol 1e-9 (atol 1e-13 m).

use raceway::component::{variables, Component};
use raceway::report::{force_error, load_average, thread_cpu_s, Samples};

#[path = "common/counters.rs"]
mod counters;

/// The outputs read at every communication point (as `benches/speed.rs`).
const OUTPUTS: [&str; 8] = [
    "force.x",
    "force.y",
    "force.z",
    "moment.x",
    "moment.y",
    "torque.z",
    "cage.omega",
    "balls.loaded",
];

/// The two scenes: name, scene text, shaft speed (rpm).
const SCENES: [(&str, &str, f64); 2] = [
    (
        "30 000 rpm",
        include_str!("../examples/scenes/7004-30000.toml"),
        30_000.0,
    ),
    (
        "120 000 rpm",
        include_str!("../examples/scenes/7004-120000.toml"),
        120_000.0,
    ),
];

/// `text` with the solver's rtol and atol_m replaced (and no work budget in the way).
fn with_tolerance(text: &str, rtol: f64, atol_m: f64) -> String {
    let mut out = String::new();
    for l in text.lines() {
        if l.starts_with("rtol =") {
            out += &format!("rtol = {rtol:e}\n");
        } else if l.starts_with("atol_m =") {
            out += &format!("atol_m = {atol_m:e}\nmax_substeps = 10000000\nmax_step_cpu_s = 1e5\n");
        } else {
            out += l;
            out += "\n";
        }
    }
    out
}

/// Outputs every 20 µs over one settling and `revs` timed revolutions: ms of thread CPU
/// per timed revolution, the forces at every point, and the counters per revolution.
fn run_20us(text: &str, rpm: f64, revs: usize) -> (f64, Samples, String) {
    let vr = |n: &str| variables::by_name(n).unwrap().vr;
    let mut c = Component::from_text(text).expect("scene");
    let h = 20e-6;
    let per_rev = ((60.0 / rpm) / h).round() as usize;
    let out_vr: Vec<u32> = OUTPUTS.iter().map(|n| vr(n)).collect();
    let mut out = [0.0; 8];
    let mut t = 0.0;
    let mut s = Samples {
        t: vec![],
        f: vec![],
    };
    let mut run = |c: &mut Component, steps: usize, s: &mut Samples| {
        for _ in 0..steps {
            c.do_step(t, h).expect("step");
            t += h;
            for (o, &v) in out.iter_mut().zip(&out_vr) {
                *o = c.get_real(v).expect("output");
            }
            s.t.push(t);
            s.f.push([out[0], out[1], out[2]]);
        }
    };
    run(&mut c, per_rev, &mut s);
    let s0 = c.stats();
    let c0 = thread_cpu_s();
    run(&mut c, per_rev * revs, &mut s);
    let cpu = thread_cpu_s() - c0;
    let s1 = c.stats();
    let sim_revs = (per_rev * revs) as f64 * h / (60.0 / rpm);
    let per = |a: u64, b: u64| (a - b) as f64 / sim_revs;
    let counters = format!(
        "per revolution: rhs {:.0}, jacobians {:.0}, LU {:.0}, accepted {:.0}, rejected {:.0}",
        per(s1.rhs, s0.rhs),
        per(s1.jacobians, s0.jacobians),
        per(s1.factorizations, s0.factorizations),
        per(s1.accepted, s0.accepted),
        per(s1.rejected, s0.rejected)
    );
    (cpu / sim_revs * 1e3, s, counters)
}

fn main() {
    let full = std::env::args().any(|a| a == "--bench");
    let vr = |n: &str| variables::by_name(n).unwrap().vr;
    for (name, text, rpm) in SCENES {
        let mut c = Component::from_text(text).expect("scene");
        let rev = 60.0 / rpm;
        // Communication step: a tenth of a revolution.
        let h = rev / 10.0;
        let (settle, revs) = if full { (20, 10) } else { (1, 0) };
        for i in 0..settle {
            c.do_step(i as f64 * h, h).expect("step");
        }
        if !full {
            assert!(c.get_real(vr("cage.omega")).unwrap().is_finite());
            println!("full {name}: smoke run ok");
            continue;
        }
        let s0 = c.stats();
        let n = revs * 10;
        let t0 = thread_cpu_s();
        for i in settle..settle + n {
            c.do_step(i as f64 * h, h).expect("step");
        }
        let cpu = thread_cpu_s() - t0;
        let s1 = c.stats();
        println!(
            "full 7004 {name}: {:.1} ms thread CPU per shaft revolution ({revs} revolutions; load average {})",
            cpu / revs as f64 * 1e3,
            load_average()
        );
        println!("{}", counters::per("revolution", &s0, &s1, revs as f64));
        println!(
            "  cage speed ratio {:.4}, cage centre ({:.3}, {:.3}) clearances, cage speed {:.3} m/s",
            c.get_real(vr("cage.speed_ratio")).unwrap(),
            c.get_real(vr("cage.x")).unwrap(),
            c.get_real(vr("cage.y")).unwrap(),
            c.get_real(vr("cage.speed")).unwrap(),
        );
    }
    if !full {
        return;
    }
    // Issue #17's rows: outputs every 20 µs, the force error against rtol 1e-9.
    let revs = 3;
    for (name, text, rpm) in SCENES {
        let (_, reference, _) = run_20us(&with_tolerance(text, 1e-9, 1e-13), rpm, revs);
        let mut best = f64::INFINITY;
        let mut last = None;
        for _ in 0..3 {
            let (ms, s, counters) = run_20us(text, rpm, revs);
            best = best.min(ms);
            last = Some((s, counters));
        }
        let (s, counters) = last.expect("three runs");
        let (l2, peak) = force_error(&s, &reference).expect("same points");
        println!(
            "full 7004 {name}, outputs every 20 µs: {best:.1} ms thread CPU per revolution (best of 3; {revs} revolutions after one; load average {}); force error against rtol 1e-9: L2 {l2:.2e}, peak {peak:.2e}",
            load_average()
        );
        println!("  {counters}");
    }
}
