//! Timing of the motion-driven quasi-static force evaluation (the right-hand side of a time
//! integration): `acbb16` at 10 000 rpm, at the operating displacement of Fa = 20 kN,
//! Fr = 2 kN, warm-started from the previous call while the cage turns a little between
//! calls, as in time integration. Then the 2-DOF ring's force evaluation (the 6205's nine
//! balls, the 500 states of a 0.05 s window) and, inside it, the cage angle's sine and
//! cosine: the `libm` crate's `sincos` (`models::ring::cage_sin_cos`) against `f64::sin_cos`.
//!
//! Median of repeats (docs/physics.md §N6: minimum or median of repeated runs after warm-up,
//! setup excluded, single thread) of the thread's CPU time (`CLOCK_THREAD_CPUTIME_ID`,
//! [`raceway::report::thread_cpu_s`]), which other processes on a shared machine do not
//! inflate; the load average is printed beside it. Run with `cargo bench --bench forces`.

use raceway::geometry::preset;
use raceway::models::quasi_static::{azimuths, BallState, Options, QuasiStatic};
use raceway::models::ring::{cage_sin_cos, RingAt, RingDof, RingEval, RingModel};
use raceway::report::{load_average, thread_cpu_s};
use raceway::units::rpm_to_rad_s;
use std::hint::black_box;

/// CPU time consumed by this thread, ns.
fn thread_cpu_ns() -> f64 {
    thread_cpu_s() * 1e9
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v[v.len() / 2]
}

fn main() {
    let b = preset("acbb16").unwrap().build().unwrap();
    let m = QuasiStatic::new(&b, Options::default()).unwrap();
    let w = rpm_to_rad_s(10_000.0);
    let sol = m.solve(&[2000.0, 0.0, 20_000.0, 0.0, 0.0], w).unwrap();
    let z = b.z;
    let mut psi = azimuths(z, 0.0);
    let mut state: Vec<BallState> = sol.states.clone();
    let mut k = [[0.0; 5]; 5];

    // Cage advance per call: a time step of 2 µs at the cage speed (about 0.45 omega).
    let dpsi = 0.45 * w * 2e-6;
    // `cargo bench` passes `--bench`; `cargo test --all-targets` runs this once as a smoke test.
    let bench = std::env::args().any(|a| a == "--bench");
    let (evals, repeats) = if bench { (2000, 21) } else { (10, 1) };

    let mut time = |with_k: bool| -> f64 {
        let mut cpu = Vec::with_capacity(repeats);
        let mut sink = 0.0;
        for r in 0..repeats + 2 {
            let c0 = thread_cpu_ns();
            for _ in 0..evals {
                for p in psi.iter_mut() {
                    *p += dpsi;
                }
                let f = if with_k {
                    m.forces_and_stiffness(black_box(&sol.q), w, &psi, &mut state, &mut k)
                } else {
                    m.forces(black_box(&sol.q), w, &psi, &mut state)
                }
                .unwrap();
                sink += black_box(f)[2];
            }
            let c1 = thread_cpu_ns();
            if r >= 2 {
                // the first two are warm-up
                cpu.push((c1 - c0) / evals as f64);
            }
        }
        black_box(sink);
        median(cpu)
    };
    let cpu = time(false);
    println!(
        "quasi-static forces, acbb16 (Z = {z}) at 10000 rpm, Fa 20 kN, Fr 2 kN, warm-started (load average {}):",
        load_average()
    );
    println!(
        "  forces only:      median {cpu:.0} ns/eval thread CPU ({:.0} ns per ball)",
        cpu / z as f64
    );
    let cpu = time(true);
    println!("  forces + 5x5 K:   median {cpu:.0} ns/eval thread CPU");
    ring(bench);
}

/// Median over repeats of `f`'s thread CPU time per call, ns (`calls` calls per repeat, two
/// warm-up repeats).
fn per_call(calls: usize, repeats: usize, mut f: impl FnMut() -> f64) -> f64 {
    let mut cpu = Vec::with_capacity(repeats);
    let mut sink = 0.0;
    for r in 0..repeats + 2 {
        let c0 = thread_cpu_ns();
        sink += f();
        let c1 = thread_cpu_ns();
        if r >= 2 {
            cpu.push((c1 - c0) / calls as f64);
        }
    }
    black_box(sink);
    median(cpu)
}

/// The 2-DOF ring's force evaluation and the cage angle's sine and cosine in it.
fn ring(bench: bool) {
    let repeats = if bench { 201 } else { 1 };
    let b = preset("6205").unwrap().build().unwrap();
    let m = RingModel::new(&b, RingDof::Two, 3000.0);
    // A ring 12 µm down (about half the balls loaded), orbiting 0.1 µm, the cage turning
    // at 73 rad/s: 500 points 0.1 ms apart.
    let pts: Vec<([f64; 5], [f64; 5], f64)> = (0..500)
        .map(|k| {
            let t = k as f64 * 1e-4;
            let q = [1e-7 * (300.0 * t).sin(), -1.2e-5 + 1e-7 * (600.0 * t).cos()];
            let v = [1e-4 * (300.0 * t).cos(), 1e-4];
            (
                [q[0], q[1], 0.0, 0.0, 0.0],
                [v[0], v[1], 0.0, 0.0, 0.0],
                73.0 * t,
            )
        })
        .collect();
    let mut out = RingEval::default();
    let eval = per_call(pts.len(), repeats, || {
        let mut s = 0.0;
        for (q, v, th) in &pts {
            m.eval(
                RingAt {
                    theta_c: black_box(*th),
                    omega_c: 73.0,
                    q,
                    v,
                    t: 0.0,
                },
                None,
                false,
                &mut out,
            );
            s += out.wrench[1];
        }
        s
    });
    let angles: Vec<f64> = pts.iter().map(|p| p.2 + 0.1).collect();
    let sc = |f: fn(f64) -> (f64, f64)| {
        per_call(angles.len(), repeats, || {
            angles
                .iter()
                .map(|&a| {
                    let (s, c) = f(black_box(a));
                    s + c
                })
                .sum()
        })
    };
    let (ours, std) = (sc(cage_sin_cos), sc(f64::sin_cos));
    println!(
        "ring 6205, 2 DOF, 9 balls, forces (load average {}):",
        load_average()
    );
    println!("  forces only:      median {eval:.1} ns/eval thread CPU");
    println!(
        "  cage angle sine and cosine: cage_sin_cos (libm) {ours:.1} ns, f64::sin_cos {std:.1} ns"
    );
}
