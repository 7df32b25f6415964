//! Timing of the quasi-static and skidding rows of issue #17 (benches/speed.rs's cases),
//! with their force errors, for before/after comparisons while working on them:
//!
//! ```sh
//! cargo run --release --example qsskid_timing -- qs      # quasi-static C ABI loop
//! cargo run --release --example qsskid_timing -- skid    # skidding, outputs every 0.1 ms
//! ```
//!
//! Times are the thread's CPU time; the load average is printed beside each figure.
//! Quasi-static force error: the C ABI loop's forces at every communication point against
//! the Jones–Harris kernel solved cold at `ball_tolerance` 1e-13 at the same ring motion and
//! ball azimuths. Skidding force error: against the same run at rtol 1e-9.

use raceway::capi::{
    raceway_create, raceway_do_step, raceway_free, raceway_get_reals, raceway_set_reals,
    RacewayComponent, RacewayStatus,
};
use raceway::component::{variables, Component, Scene};
use raceway::models::quasi_static::{self as qsm, BallState, QuasiStatic};
use raceway::report::{force_error, load_average, median, thread_cpu_s, Samples};
use std::ffi::CString;

fn vr(n: &str) -> u32 {
    variables::by_name(n).expect("variable").vr
}

const OUTPUTS: [&str; 8] = [
    "force.x",
    "force.y",
    "force.z",
    "moment.x",
    "moment.y",
    "torque.z",
    "cage.omega",
    "contact.max_load",
];

fn qs(reps: usize, n: usize) {
    let scene = include_str!("scenes/7008ce-qs-motion.toml");
    let text = CString::new(scene).unwrap();
    let mut err = vec![0 as std::ffi::c_char; 512];
    // SAFETY: NUL-terminated text, an error buffer of the stated length.
    let c: *mut RacewayComponent =
        unsafe { raceway_create(text.as_ptr(), err.as_mut_ptr(), err.len()) };
    assert!(!c.is_null());
    let s = Scene::from_text(scene).unwrap();
    let init = |n: &str| s.inputs.initial.get(n).copied().unwrap_or(0.0);
    let (x0, y0, z0) = (init("shaft.x"), init("shaft.y"), init("shaft.z"));
    let omega = init("shaft.omega");
    let a = 1e-6;
    let h = 1e-4;
    let in_vr = [vr("shaft.x"), vr("shaft.y"), vr("shaft.vx"), vr("shaft.vy")];
    let out_vr: Vec<u32> = OUTPUTS.iter().map(|n| vr(n)).collect();
    let held = [
        "shaft.z", "shaft.rx", "shaft.ry", "shaft.vz", "shaft.wx", "shaft.wy",
    ];
    let held_vr: Vec<u32> = held.iter().map(|n| vr(n)).collect();
    let held_v: Vec<f64> = held.iter().map(|n| init(n)).collect();
    // SAFETY: a live instance, arrays of the stated lengths.
    let r = unsafe { raceway_set_reals(c, held_vr.as_ptr(), held_v.as_ptr(), held.len()) };
    assert!(matches!(r, RacewayStatus::Ok));
    let mut outputs = [0.0; 8];
    let mut t = 0.0;
    let mut qs_at = Vec::new();
    let mut run = Samples {
        t: Vec::new(),
        f: Vec::new(),
    };
    let mut step = |t: &mut f64, qs_at: &mut Vec<(f64, [f64; 5])>, run: &mut Samples| {
        let (sn, cs) = (omega * *t).sin_cos();
        let inputs = [x0 + a * cs, y0 + a * sn, -a * omega * sn, a * omega * cs];
        // SAFETY: a live instance, arrays of the stated lengths.
        unsafe {
            let r = raceway_set_reals(c, in_vr.as_ptr(), inputs.as_ptr(), 4);
            assert!(matches!(r, RacewayStatus::Ok));
            let r = raceway_do_step(c, *t, h);
            assert!(matches!(r, RacewayStatus::Ok), "do_step at {t}");
            let r = raceway_get_reals(c, out_vr.as_ptr(), outputs.as_mut_ptr(), 8);
            assert!(matches!(r, RacewayStatus::Ok));
        }
        *t += h;
        let q = [
            inputs[0] + inputs[2] * h,
            inputs[1] + inputs[3] * h,
            z0,
            0.0,
            0.0,
        ];
        qs_at.push((*t, q));
        run.t.push(*t);
        run.f.push([outputs[0], outputs[1], outputs[2]]);
    };
    for _ in 0..n / 4 {
        step(&mut t, &mut qs_at, &mut run);
    }
    let mut times = Vec::new();
    for _ in 0..reps {
        let c0 = thread_cpu_s();
        for _ in 0..n {
            step(&mut t, &mut qs_at, &mut run);
        }
        times.push((thread_cpu_s() - c0) / n as f64);
    }
    // SAFETY: created above, freed once.
    unsafe { raceway_free(c) };
    let per = median(&mut times);
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    println!(
        "quasi-static 7008CE 12000 rpm C ABI: {:.2} µs/step (blocks min {:.2} max {:.2}), {:.2}x real time, load {}",
        per * 1e6,
        sorted[0] * 1e6,
        sorted[sorted.len() - 1] * 1e6,
        h / per,
        load_average()
    );
    // Reference: the kernel, cold and tight, at the same motion and azimuths.
    let b = s.validate().unwrap();
    let tight = QuasiStatic::new(
        &b,
        qsm::Options {
            race_control: s.model.race_control,
            ball_tolerance: 1e-13,
            ..qsm::Options::default()
        },
    )
    .unwrap();
    let ratio = raceway::component::levels::cage_speed(&b, 1.0);
    let mut reference = Samples {
        t: Vec::new(),
        f: Vec::new(),
    };
    for &(t, q) in &qs_at {
        let psi = qsm::azimuths(b.z, ratio * omega * t);
        let mut st = vec![BallState::default(); b.z];
        let f = tight.forces(&q, omega, &psi, &mut st).unwrap();
        reference.t.push(t);
        reference.f.push([f[0], f[1], f[2]]);
    }
    let (l2, peak) = force_error(&run, &reference).unwrap();
    println!("  force error against the tight cold kernel: L2 {l2:.2e}, peak {peak:.2e}");
    if let Ok(path) = std::env::var("QSSKID_DUMP") {
        let mut s = String::new();
        for (t, f) in run.t.iter().zip(&run.f) {
            s += &format!("{t:e} {:e} {:e} {:e}\n", f[0], f[1], f[2]);
        }
        std::fs::write(path, s).unwrap();
    }
}

fn skidding_run(rtol: f64, t_end: f64) -> (f64, Samples) {
    let text = include_str!("scenes/7008ce-runup.toml");
    let omega = 6000.0 * std::f64::consts::PI / 30.0;
    let text = text.replace(
        "\"shaft.omega\" = 0.0",
        &format!("\"shaft.omega\" = {omega}"),
    );
    let mut scene = Scene::from_text(&text).expect("scene");
    scene.solver.rtol = rtol;
    scene.solver.atol_m = rtol * 1e-4;
    let mut c = Component::new(scene).expect("scene");
    for i in 0..20 {
        c.do_step(i as f64 * 1e-3, 1e-3).expect("settle");
    }
    let h = 1e-4;
    let t0 = c.time();
    let n = (t_end / h).round() as usize;
    let out_vr: Vec<u32> = OUTPUTS.iter().map(|n| vr(n)).collect();
    let mut s = Samples {
        t: Vec::new(),
        f: Vec::new(),
    };
    let mut out = [0.0; 8];
    let c0 = thread_cpu_s();
    for i in 0..n {
        c.do_step(t0 + i as f64 * h, h).expect("step");
        for (o, &v) in out.iter_mut().zip(&out_vr) {
            *o = c.get_real(v).expect("output");
        }
        s.t.push(c.time());
        s.f.push([out[0], out[1], out[2]]);
    }
    ((thread_cpu_s() - c0) / n as f64, s)
}

fn skid(reps: usize) {
    let t_end = 0.02;
    let (_, reference) = skidding_run(1e-9, t_end);
    for rtol in [1e-5, 1e-4, 1e-3] {
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..reps {
            let (cpu, s) = skidding_run(rtol, t_end);
            times.push(cpu);
            last = Some(s);
        }
        let per = median(&mut times);
        let (l2, peak) = force_error(&last.unwrap(), &reference).unwrap();
        println!(
            "skidding 7008CE 6000 rpm rtol {rtol:e}: {:.1} µs/step, {:.2}x real time, force error L2 {l2:.2e} peak {peak:.2e}, load {}",
            per * 1e6,
            1e-4 / per,
            load_average()
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let what = args.get(1).map_or("qs", String::as_str);
    let reps = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(5);
    match what {
        "qs" => qs(reps, 500),
        "skid" => skid(reps),
        _ => eprintln!("qs | skid [reps]"),
    }
}
