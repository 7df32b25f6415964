//! Profiling harness for the skidding speed row (issue #36): `examples/scenes/
//! 7008ce-skidding-24000.toml` in host steps of 0.1 ms for a short window, as the bench's
//! skidding row runs it, with the integrator's counters and the forces at the points.
//! `cargo run --release --example skid_window -- [ros34pw2|rodas4] [t_end] [rtol] [cap]
//! [--save FILE | --ref FILE]`; under `valgrind --tool=callgrind` for instruction counts.

use raceway::component::{variables, Component, Method, Scene};
use raceway::report::{force_error, Samples};

fn vr(n: &str) -> u32 {
    variables::by_name(n).unwrap().vr
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let method = match args.first().map(String::as_str) {
        Some("rodas4") => Method::Rosenbrock,
        _ => Method::Ros34pw2,
    };
    let t_end: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(0.01);
    let rtol: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1e-5);
    let cap: f64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(0.0);
    let flag = |f: &str| {
        args.iter()
            .position(|a| a == f)
            .map(|i| args[i + 1].clone())
    };
    let text = include_str!("scenes/7008ce-skidding-24000.toml");
    let mut scene = Scene::from_text(text).expect("scene");
    scene.solver.method = method;
    scene.solver.rtol = rtol;
    scene.solver.atol_m = rtol * 1e-4;
    if cap > 0.0 {
        scene.solver.max_substep_s = cap;
        scene.solver.max_substeps = 10_000_000;
    }
    let h = scene.run.step_s;
    let init = |n: &str| scene.inputs.initial_value(n);
    let mut c = Component::new(scene.clone()).expect("scene");
    for name in [
        "load.x",
        "load.y",
        "load.z",
        "load.mx",
        "load.my",
        "shaft.omega",
    ] {
        c.set_real(vr(name), init(name)).expect("input");
    }
    let n = (t_end / h).round() as usize;
    let out_vr: Vec<u32> = [
        "force.x",
        "force.y",
        "force.z",
        "moment.x",
        "moment.y",
        "torque.z",
        "cage.slip",
        "contact.max_load",
    ]
    .iter()
    .map(|n| vr(n))
    .collect();
    let mut s = Samples {
        t: Vec::new(),
        f: Vec::new(),
    };
    let mut out = [0.0; 8];
    for i in 0..n {
        c.do_step(i as f64 * h, h).expect("step");
        for (o, &v) in out.iter_mut().zip(&out_vr) {
            *o = c.get_real(v).expect("output");
        }
        s.t.push((i + 1) as f64 * h);
        s.f.push([out[0], out[1], out[2]]);
    }
    let st = c.stats();
    println!(
        "{n} points: rhs {} jac {} lu {} accepted {} rejected {}; last slip {:.4}, force {:?}",
        st.rhs,
        st.jacobians,
        st.factorizations,
        st.accepted,
        st.rejected,
        out[6],
        s.f.last().unwrap()
    );
    if let Some(f) = flag("--save") {
        let txt: String =
            s.t.iter()
                .zip(&s.f)
                .map(|(t, f)| format!("{t:e} {:e} {:e} {:e}\n", f[0], f[1], f[2]))
                .collect();
        std::fs::write(f, txt).unwrap();
    }
    if let Some(f) = flag("--ref") {
        let txt = std::fs::read_to_string(f).unwrap();
        let mut r = Samples {
            t: Vec::new(),
            f: Vec::new(),
        };
        for l in txt.lines() {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            r.t.push(v[0]);
            r.f.push([v[1], v[2], v[3]]);
        }
        r.t.truncate(n);
        r.f.truncate(n);
        let (l2, peak) = force_error(&s, &r).unwrap();
        println!("force error L2 {l2:.4e} peak {peak:.4e}");
    }
}
