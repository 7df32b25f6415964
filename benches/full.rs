//! CPU time per shaft revolution of the full level (physics.md §5.5, study [0]): the 7004
//! at 30 000 and 120 000 rpm under Fa 2000 N, Fr 400 N, motion-driven (the scenes
//! `examples/scenes/7004-30000.toml` and `7004-120000.toml`), through the component
//! (RODAS4 with the level's block Jacobian). Prints the figures and the integrator
//! counters. Run: `cargo bench --bench full`. Under `cargo test` (no `--bench` argument)
//! it takes one short step per scene as a smoke run.

use raceway::component::{variables, Component};
use raceway::report::{load_average, thread_cpu_s};

fn main() {
    let full = std::env::args().any(|a| a == "--bench");
    let vr = |n: &str| variables::by_name(n).unwrap().vr;
    for (name, text, rpm) in [
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
    ] {
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
        println!(
            "  per revolution: rhs {:.0}, jacobians {:.0}, LU {:.0}, accepted {:.0}, rejected {:.0}",
            (s1.rhs - s0.rhs) as f64 / revs as f64,
            (s1.jacobians - s0.jacobians) as f64 / revs as f64,
            (s1.factorizations - s0.factorizations) as f64 / revs as f64,
            (s1.accepted - s0.accepted) as f64 / revs as f64,
            (s1.rejected - s0.rejected) as f64 / revs as f64
        );
        println!(
            "  cage speed ratio {:.4}, cage centre ({:.3}, {:.3}) clearances, cage speed {:.3} m/s",
            c.get_real(vr("cage.speed_ratio")).unwrap(),
            c.get_real(vr("cage.x")).unwrap(),
            c.get_real(vr("cage.y")).unwrap(),
            c.get_real(vr("cage.speed")).unwrap(),
        );
    }
}
