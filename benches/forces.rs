//! Timing of the motion-driven quasi-static force evaluation (the right-hand side of a time
//! integration): `acbb16` at 10 000 rpm, at the operating displacement of Fa = 20 kN,
//! Fr = 2 kN, warm-started from the previous call while the cage turns a little between
//! calls, as in time integration.
//!
//! Median of repeats (numerics.md §6: minimum or median of repeated runs after warm-up,
//! setup excluded, single thread), of both wall-clock time (`std::time::Instant`) and the
//! thread's CPU time (`CLOCK_THREAD_CPUTIME_ID`), which is less disturbed by other processes
//! on a shared machine. Run with `cargo bench --bench forces`.

use raceway::geometry::preset;
use raceway::models::quasi_static::{azimuths, BallState, Options, QuasiStatic};
use raceway::units::rpm_to_rad_s;
use std::hint::black_box;
use std::time::Instant;

/// CPU time consumed by this thread, ns.
fn thread_cpu_ns() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec; the clock id is a constant.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 * 1e9 + ts.tv_nsec as f64
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

    let mut time = |with_k: bool| -> (f64, f64) {
        let mut wall = Vec::with_capacity(repeats);
        let mut cpu = Vec::with_capacity(repeats);
        let mut sink = 0.0;
        for r in 0..repeats + 2 {
            let t0 = Instant::now();
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
            let ns = t0.elapsed().as_nanos() as f64 / evals as f64;
            if r >= 2 {
                // the first two are warm-up
                wall.push(ns);
                cpu.push((c1 - c0) / evals as f64);
            }
        }
        black_box(sink);
        (median(wall), median(cpu))
    };
    let (wall, cpu) = time(false);
    println!(
        "quasi-static forces, acbb16 (Z = {z}) at 10000 rpm, Fa 20 kN, Fr 2 kN, warm-started:"
    );
    println!(
        "  forces only:      median {wall:.0} ns/eval wall, {cpu:.0} ns/eval thread CPU ({:.0} ns per ball)",
        cpu / z as f64
    );
    let (wall, cpu) = time(true);
    println!("  forces + 5x5 K:   median {wall:.0} ns/eval wall, {cpu:.0} ns/eval thread CPU");
}
