//! CPU time per simulated second of the skidding level: the 7008CE (16 balls) at
//! 6000 rpm under 300 N axial, load-driven, through the component (RODAS4). Three host
//! step sizes: one long `do_step` (straight through: the integrator picks its own steps),
//! 1 ms, and 0.1 ms (component mode: outputs, stiffness and `dF/dt` every 0.1 ms). Prints
//! the figures and the integrator counters. Run: `cargo bench --bench skidding`.

use raceway::component::{variables, Component};
use raceway::report::{load_average, thread_cpu_s as cpu_now};

#[path = "common/counters.rs"]
mod counters;
#[path = "common/runup_6000.rs"]
mod runup_6000;

fn vr(n: &str) -> u32 {
    variables::by_name(n).unwrap().vr
}

/// A fresh component at 6000 rpm, settled 50 ms (not timed); then `sim` simulated seconds
/// in host steps of `h`. Returns the CPU seconds per simulated second.
fn case(label: &str, h: f64, sim: f64) -> f64 {
    let mut c = Component::from_text(&runup_6000::scene()).expect("scene");
    let settle = 1e-3;
    for i in 0..50 {
        c.do_step(i as f64 * settle, settle).expect("step");
    }
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

fn main() {
    let straight = case("one 0.2 s step (straight through)", 0.2, 0.2);
    let ms = case("host step 1 ms", 1e-3, 0.2);
    let comp = case("host step 0.1 ms (component mode)", 1e-4, 0.5);
    println!(
        "component mode (0.1 ms) / straight through: {:.2}; / 1 ms steps: {:.2}",
        comp / straight,
        comp / ms
    );
}
