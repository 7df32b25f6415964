//! Probe of the dry wear map's ball-spacing pattern (issue #15): one window of study \[2\]'s
//! 6012, dry, with the output step, the window length and the cell count as options; prints
//! the map's Z-th circumferential harmonic outside the load zone and, with `--dump FILE`,
//! every loaded ball's `(t, j, psi, q_o, dv_o, area_rate)` at every sample.
//!
//! ```text
//! cargo run --release --example wear_map_probe -- --step 1e-4 --cells 360 --window 2 --settle 0.3
//! ```

use raceway::component::{variables, Component, Scene};
use raceway::contact::traction::{MixedEhl, TractionLaw};
use raceway::lubrication::asperity::AsperityReading;
use raceway::models::wear_map::OuterRaceWear;
use std::f64::consts::TAU;
use std::io::Write;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

fn arg(args: &[String], name: &str, def: f64) -> f64 {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(def)
}

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let h = arg(&args, "--step", 1e-4);
    let n = arg(&args, "--cells", 360.0) as usize;
    let window = arg(&args, "--window", 2.0);
    let settle = arg(&args, "--settle", 0.3);
    let sub = arg(&args, "--sub", 1.0) as usize;
    let dump = args
        .iter()
        .position(|a| a == "--dump")
        .and_then(|i| args.get(i + 1))
        .cloned();
    let mut scene = Scene::from_text(include_str!("scenes/6012-skidding.toml"))?;
    scene.model.skidding.traction = TractionLaw::MixedEhl(MixedEhl {
        roughness: 1e-4,
        ..MixedEhl::default()
    });
    scene.solver.rtol = arg(&args, "--rtol", scene.solver.rtol);
    scene.solver.atol_m = arg(&args, "--atol", scene.solver.atol_m);
    scene.model.skidding.drag_coefficient =
        arg(&args, "--drag", scene.model.skidding.drag_coefficient);
    let rpm = arg(&args, "--rpm", 2000.0);
    scene.inputs.set_initial("shaft.omega", rpm * TAU / 60.0);
    let rtol = scene.solver.rtol;
    let wear = OuterRaceWear::study2(None, AsperityReading::default());
    let mut c = Component::new(scene)?;
    let vr = |s: &str| variables::by_name(s).map_or(0, |v| v.vr);
    let mut t = c.time();
    let end = t + settle;
    while t < end - 1e-12 {
        c.do_step(t, h)?;
        t += h;
    }
    let cell_len = TAU * 0.5 * c.bearing().outer_race_diameter() / n as f64;
    let mut dep = vec![0.0; n];
    let mut tally = raceway::models::wear_map::ShareTally::new(n);
    let mut out = dump.map(|p| std::io::BufWriter::new(std::fs::File::create(p).unwrap()));
    let (mut turned, target) = (0.0, window * TAU);
    let hs = h / sub as f64;
    while turned < target {
        // `sub` deposits per output step: the step split into `sub` communication steps.
        for _ in 0..sub {
            c.do_step(t, hs)?;
            t += hs;
            c.ensure_outputs()?;
            turned += c.get_real(vr("cage.omega"))?.abs() * hs;
            let m = c.skidding_mut().expect("skidding").model();
            wear.deposit(m, hs, &mut dep, cell_len, &mut tally);
            if let Some(f) = out.as_mut() {
                writeln!(
                    f,
                    "{t:.7},99,{:.6},{:.6},0,0",
                    c.get_real(vr("cage.omega"))?,
                    c.get_real(vr("shaft.y"))? * 1e6
                )?;
                let m = c.skidding_mut().expect("skidding").model();
                for j in 0..m.z() {
                    let (ct, dv, u) = m.outer_contact(j);
                    if ct.q > 0.0 {
                        let w = wear.contact(&ct, dv, u);
                        writeln!(
                            f,
                            "{t:.7},{j},{:.6},{:.5},{:.6e},{:.6e}",
                            m.balls[j].psi.rem_euclid(TAU).to_degrees(),
                            ct.q,
                            dv,
                            w.area_rate
                        )?;
                    }
                }
            }
        }
    }
    let revs = turned / TAU;
    let rate: Vec<f64> = dep.iter().map(|d| d / revs).collect();
    // Outside the load zone: 0..200 deg (load line at 270).
    let lo: Vec<usize> = (0..n)
        .filter(|&k| (k as f64 * 360.0 / n as f64) < 200.0)
        .collect();
    let mean = lo.iter().map(|&k| rate[k]).sum::<f64>() / lo.len() as f64;
    let harm = |m: f64| {
        let (mut re, mut im) = (0.0, 0.0);
        for &k in &lo {
            let a = TAU * k as f64 / n as f64;
            re += rate[k] * (m * a).cos();
            im += rate[k] * (m * a).sin();
        }
        2.0 * (re * re + im * im).sqrt() / lo.len() as f64
    };
    let peak = rate.iter().fold(0.0f64, |a, &b| a.max(b));
    let peak_lo = lo.iter().fold(0.0f64, |a, &k| a.max(rate[k]));
    println!(
        "rtol {:e} rpm {rpm} step {h:e} sub {sub} cells {n} window {window} settle {settle}: revs {revs:.4}, peak {:.4e} µm/rev, 0-200 deg: mean {:.4e}, max/mean {:.2}, |H14|/mean {:.3}, |H28|/mean {:.3}, |H7|/mean {:.3}",
        rtol,
        peak * 1e6,
        mean * 1e6,
        peak_lo / mean,
        harm(14.0) / mean,
        harm(28.0) / mean,
        harm(7.0) / mean
    );
    let mut pk: Vec<(f64, f64)> = (0..n)
        .filter(|&k| rate[k] > rate[(k + n - 1) % n] && rate[k] >= rate[(k + 1) % n])
        .map(|k| (rate[k], k as f64 * 360.0 / n as f64))
        .collect();
    pk.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut top: Vec<f64> = pk.iter().take(12).map(|p| p.1).collect();
    top.sort_by(f64::total_cmp);
    println!("  12 highest local maxima at (deg): {top:.1?}");
    Ok(())
}
