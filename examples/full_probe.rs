//! Probe of the full level's step cost (issue #36): a scene (default the 7004 at 30 000 rpm)
//! stepped through the component's `do_step` at a communication step, the host reading the
//! speed bench's 8 outputs after every step (or every output with `--all`). Prints the
//! integrator counters and a fingerprint of the outputs read (bit for bit), so a change
//! can be checked to leave the series as it was, and, with `--dump FILE`, the series.
//! Meant for instruction counts:
//!
//! ```text
//! cargo build --profile profiling --example full_probe
//! valgrind --tool=callgrind --toggle-collect='*Component*do_step*' \
//!     target/profiling/examples/full_probe --window 0.005
//! ```
//!
//! Options: `--scene FILE`, `--window S` (simulated seconds, default 0.005), `--step S`
//! (communication step, default 20e-6), `--method NAME` (the scene's `solver.method`),
//! `--rtol X` (the scene's, and its `atol_m` scaled with it), `--all` (read every output),
//! `--exudyn RPM` (instead of `--scene`: the speed bench's Exudyn-geometry scene at that
//! shaft speed, benches/common/exudyn_peer.rs, with dynamic ball contacts, or the default
//! quasi-static ones with `--quasi-static`; use `--step 1e-4` as the bench; its tolerance
//! is the bench row's, `--rtol` sets another).

use raceway::component::{variables, Component, Scene};
use std::io::Write;

#[allow(dead_code)]
#[path = "../benches/common/exudyn_peer.rs"]
mod exudyn_peer;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

fn opt<'a>(args: &'a [String], name: &str) -> Option<&'a str> {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .map(String::as_str)
}

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().collect();
    let path = opt(&args, "--scene").unwrap_or("examples/scenes/7004-30000.toml");
    let window: f64 = opt(&args, "--window").unwrap_or("0.005").parse()?;
    let h: f64 = opt(&args, "--step").unwrap_or("20e-6").parse()?;
    let mut text = match opt(&args, "--exudyn") {
        Some(rpm) => exudyn_peer::scene(rpm.parse()?, !args.iter().any(|a| a == "--quasi-static")),
        None => std::fs::read_to_string(path)?,
    };
    if let Some(m) = opt(&args, "--method") {
        text = text.replace("method = \"rosenbrock\"", &format!("method = \"{m}\""));
    }
    let mut scene = Scene::from_text(&text)?;
    if let Some(r) = opt(&args, "--rtol") {
        let r: f64 = r.parse()?;
        scene.solver.atol_m *= r / scene.solver.rtol;
        scene.solver.rtol = r;
    }
    let names: Vec<&str> = if args.iter().any(|a| a == "--all") {
        variables::all()
            .filter(|v| v.is_output(scene.model.causality))
            .map(|v| v.name)
            .collect()
    } else {
        vec![
            "force.x",
            "force.y",
            "force.z",
            "moment.x",
            "moment.y",
            "torque.z",
            "cage.omega",
            "contact.max_load",
        ]
    };
    let vrs: Vec<u32> = names
        .iter()
        .map(|n| variables::by_name(n).expect("variable").vr)
        .collect();
    let mut c = Component::new(scene)?;
    let steps = (window / h).round() as usize;
    let mut dump = match opt(&args, "--dump") {
        Some(f) => Some(std::io::BufWriter::new(std::fs::File::create(f)?)),
        None => None,
    };
    let mut fp = 0xcbf2_9ce4_8422_2325u64;
    let mut t = 0.0;
    for _ in 0..steps {
        c.do_step(t, h)?;
        t += h;
        if let Some(d) = dump.as_mut() {
            write!(d, "{t:e}")?;
        }
        for &vr in &vrs {
            let v = c.get_real(vr)?;
            for b in v.to_bits().to_le_bytes() {
                fp = (fp ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
            }
            if let Some(d) = dump.as_mut() {
                write!(d, " {v:e}")?;
            }
        }
        if let Some(d) = dump.as_mut() {
            writeln!(d)?;
        }
    }
    let s = c.stats();
    println!(
        "{steps} steps of {h:e} s: {s:?}\noutputs read: {}, fingerprint {fp:016x}",
        vrs.len()
    );
    Ok(())
}
