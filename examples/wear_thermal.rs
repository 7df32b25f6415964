//! Slow physics: race wear of study \[2\]'s 6012 and thermal growth of study \[3\]'s 7008CE.
//!
//! ```text
//! cargo run --release --example wear_thermal -- [wear|thermal|all]
//! ```
//!
//! Wear: `examples/scenes/6012-wear.toml` with the composite roughness 0.2 and 0.42 µm and
//! in the dry limit; prints the deepest point, its angle and the revolutions to 1 µm, and
//! plots the outer-race map after each cycle and the shaft orbit in the first and the last
//! window (`out/wear-map-<case>.png`, `out/wear-orbit-<case>.png`). Thermal:
//! `examples/scenes/7008ce-thermal.toml` from 6000 to 20 000 rpm; prints the node
//! temperatures, power loss, friction torque and operating clearance
//! (`out/thermal-sweep.png`).

use raceway::component::{variables, Scene};
use raceway::models::ring::level::SlowLayout;
use raceway::models::wear;
use raceway::plot::{plot, Axes, Series};
use raceway::Component;
use std::path::Path;

fn vr(name: &str) -> u32 {
    variables::by_name(name).expect("variable").vr
}

/// Step `scene` for `duration` s at `h`; call `each` after every step.
fn run(
    scene: &Scene,
    duration: f64,
    h: f64,
    mut each: impl FnMut(&mut Component),
) -> Result<Component, Box<dyn std::error::Error>> {
    let mut c = Component::new(scene.clone())?;
    let n = (duration / h).round() as usize;
    for i in 0..n {
        c.do_step(i as f64 * h, h)?;
        each(&mut c);
    }
    Ok(c)
}

fn wear_case(label: &str, scene: &Scene) -> Result<(), Box<dyn std::error::Error>> {
    let layout = SlowLayout::of(&scene.effects, &scene.validate()?)?;
    let w = scene.effects.wear.clone().expect("wear on");
    let omega = scene.inputs.initial_value("shaft.omega");
    let rev_s = std::f64::consts::TAU / omega;
    let duration = (w.cycles as f64 * w.window_revs + 0.5) * rev_s;
    let h = scene.run.step_s;
    let mut maps: Vec<(f64, Vec<f64>)> = Vec::new();
    let mut history = Vec::new();
    let mut orbits: Vec<(Vec<f64>, Vec<f64>)> = vec![(vec![], vec![]); w.cycles as usize + 1];
    let (vx, vy) = (vr("shaft.x"), vr("shaft.y"));
    let mut c = run(scene, duration, h, |c| {
        let st = c.get_state();
        let done = layout.wear_cycles(&st.aux).unwrap_or(0.0) as usize;
        if done > maps.len() {
            let (outer, inner) = layout.wear_maps(&st.aux).expect("wear");
            let revs = done as f64 * w.cycle_revs;
            let deepest = wear::deepest(outer).0.max(wear::deepest(inner).0);
            history.push((revs, deepest));
            maps.push((revs, outer.to_vec()));
        }
        // Skip the first revolution's settling from the centre in the "before" orbit.
        let settled = done > 0 || c.time() > rev_s;
        if let (true, Some(o)) = (settled, orbits.get_mut(done)) {
            o.0.push(c.get_real(vx).unwrap_or(0.0) * 1e6);
            o.1.push(c.get_real(vy).unwrap_or(0.0) * 1e6);
        }
    })?;
    let st = c.get_state();
    let (outer, inner) = layout.wear_maps(&st.aux).expect("wear");
    let (d_o, a_o) = wear::deepest(outer);
    let (d_i, a_i) = wear::deepest(inner);
    let to_1um = wear::revolutions_to(&history, 1e-6);
    println!(
        "{label:>10}: wear.max_depth {:.3e} m after {:.1e} rev; outer deepest {:.3e} m at {:.1} deg, \
         inner {:.3e} m at {:.1} deg (shaft frame); revolutions to 1 um: {}",
        c.get_real(vr("wear.max_depth"))?,
        history.last().map_or(0.0, |h| h.0),
        d_o,
        a_o.to_degrees(),
        d_i,
        a_i.to_degrees(),
        to_1um.map_or("never".into(), |r| format!("{r:.3e}"))
    );
    std::fs::create_dir_all("out")?;
    let n = outer.len();
    let angles: Vec<f64> = (0..n).map(|k| 360.0 * k as f64 / n as f64).collect();
    let labels: Vec<String> = maps.iter().map(|(r, _)| format!("{r:.1e} rev")).collect();
    let um: Vec<Vec<f64>> = maps
        .iter()
        .map(|(_, m)| m.iter().map(|v| v * 1e6).collect())
        .collect();
    let series: Vec<Series> = labels
        .iter()
        .zip(&um)
        .map(|(l, m)| Series {
            label: l,
            x: &angles,
            y: m,
            points: false,
        })
        .collect();
    plot(
        Path::new(&format!("out/wear-map-{label}.png")),
        &Axes {
            title: &format!("6012 outer-race wear map ({label})"),
            x_label: "azimuth (deg, load line at 270)",
            y_label: "wear depth (um)",
            ..Axes::default()
        },
        &series,
        &[],
    )?;
    let first = &orbits[0];
    let last = orbits
        .iter()
        .rev()
        .find(|o| !o.0.is_empty())
        .unwrap_or(first);
    plot(
        Path::new(&format!("out/wear-orbit-{label}.png")),
        &Axes {
            title: &format!("6012 shaft orbit before and after wear ({label})"),
            x_label: "x (um)",
            y_label: "y (um)",
            equal: true,
            ..Axes::default()
        },
        &[
            Series {
                label: "first window",
                x: &first.0,
                y: &first.1,
                points: false,
            },
            Series {
                label: "last window",
                x: &last.0,
                y: &last.1,
                points: false,
            },
        ],
        &[],
    )?;
    Ok(())
}

fn wear_study() -> Result<(), Box<dyn std::error::Error>> {
    let text = std::fs::read_to_string("examples/scenes/6012-wear.toml")?;
    let base = Scene::from_text(&text)?;
    for (label, rough, dry) in [
        ("ra0.2", 0.2, false),
        ("ra0.42", 0.42, false),
        ("dry", 0.2, true),
    ] {
        let mut s = base.clone();
        if let Some(l) = s.effects.lubrication.as_mut() {
            l.roughness_um = Some(rough);
        }
        if let Some(w) = s.effects.wear.as_mut() {
            if dry {
                w.regime = raceway::models::effects::WearRegime::Dry;
            }
            if dry {
                // The dry limit wears about 1e9 times faster: shorter cycles.
                w.cycle_revs = 1e3;
            }
        }
        wear_case(label, &s)?;
    }
    Ok(())
}

fn thermal_study() -> Result<(), Box<dyn std::error::Error>> {
    let text = std::fs::read_to_string("examples/scenes/7008ce-thermal.toml")?;
    let base = Scene::from_text(&text)?;
    let layout = SlowLayout::of(&base.effects, &base.validate()?)?;
    let pd = base.validate()?.pd;
    let mut rpm = vec![];
    let mut rise = [vec![], vec![], vec![], vec![]];
    let mut clearance = vec![];
    println!("   rpm  dT_inner dT_outer dT_balls dT_oil (K)  power (W)  torque (N m)  Pd_op (um)");
    for n in (6000..=20000).step_by(2000) {
        let mut s = base.clone();
        let omega = n as f64 * std::f64::consts::TAU / 60.0;
        s.inputs.set_initial("shaft.omega", omega);
        let mut c = run(&s, s.run.duration_s, s.run.step_s, |_| {})?;
        let st = c.get_state();
        let th = layout.thermal(&st.aux).expect("thermal on");
        let pd_op = pd + th[8];
        println!(
            "{n:>6}  {:8.2} {:8.2} {:8.2} {:8.2}   {:9.1}  {:12.4}  {:10.2}",
            th[0],
            th[1],
            th[2],
            th[3],
            c.get_real(vr("power.loss"))?,
            c.get_real(vr("torque.z"))?,
            pd_op * 1e6
        );
        rpm.push(n as f64);
        for k in 0..4 {
            rise[k].push(th[k]);
        }
        clearance.push(pd_op * 1e6);
    }
    std::fs::create_dir_all("out")?;
    let names = ["inner ring", "outer ring", "balls", "oil"];
    let series: Vec<Series> = (0..4)
        .map(|k| Series {
            label: names[k],
            x: &rpm,
            y: &rise[k],
            points: false,
        })
        .collect();
    plot(
        Path::new("out/thermal-sweep.png"),
        &Axes {
            title: "7008CE temperature rise after the heating time",
            x_label: "shaft speed (rpm)",
            y_label: "temperature rise (K)",
            ..Axes::default()
        },
        &series,
        &[],
    )?;
    plot(
        Path::new("out/thermal-clearance.png"),
        &Axes {
            title: "7008CE operating clearance",
            x_label: "shaft speed (rpm)",
            y_label: "diametral clearance (um)",
            ..Axes::default()
        },
        &[Series {
            label: "Pd + u_o - u_i - 2 u_b",
            x: &rpm,
            y: &clearance,
            points: false,
        }],
        &[],
    )?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let what = std::env::args().nth(1).unwrap_or_else(|| "all".into());
    if what == "wear" || what == "all" {
        wear_study()?;
    }
    if what == "thermal" || what == "all" {
        thermal_study()?;
    }
    Ok(())
}
