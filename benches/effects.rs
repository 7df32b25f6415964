//! Pay only for what you use: a scene with an effect switched off against the same scene
//! without the effect's entry at all (the code path without the effect), timed in one run
//! with interleaved repeats, ratio of medians printed. A ratio near 1 means "off" costs
//! nothing; the "on" rows show what the effect costs when it is used (per right-hand side:
//! with damping on the ring also settles, so the run itself needs fewer steps).
//!
//! `cargo bench --bench effects`
use raceway::report::{drive, median};
use raceway::Component;

const BASE: &str = r#"
bearing = { preset = "6205", clearance_um = 10.0 }
[model]
level = "ring"
causality = "load"
attached_mass_kg = 1.0
MODEL_EXTRA
[inputs]
speed_rpm = 1750.0
initial = { "load.x" = 0.0, "load.y" = -1000.0, "load.z" = 0.0, "load.mx" = 0.0, "load.my" = 0.0 }
EXTRA
"#;

fn scene(model_extra: &str, extra: &str) -> String {
    BASE.replace("MODEL_EXTRA", model_extra)
        .replace("EXTRA", extra)
}

/// The comparisons: (what, scene with the effect off / on, scene without it).
fn pairs() -> Vec<(&'static str, String, String)> {
    vec![
        (
            "contact damping 0 vs absent",
            scene("contact_damping = 0.0", ""),
            scene("", ""),
        ),
        (
            "empty [effects] vs absent",
            scene("", "[effects]"),
            scene("", ""),
        ),
        (
            "empty defects list vs absent",
            scene("", "[effects]\ndefects = []"),
            scene("", ""),
        ),
        (
            "1 mm outer spall (on) vs absent",
            scene(
                "",
                "[effects]\ndefects = [{ race = \"outer\", angle_deg = 270.0, width_mm = 1.0, depth_um = 50.0 }]",
            ),
            scene("", ""),
        ),
        (
            "contact damping 3000 (on) vs absent",
            scene("contact_damping = 3000.0", ""),
            scene("", ""),
        ),
    ]
}

/// Stepping time of one run, s, and its time per right-hand side, s.
fn time_once(text: &str) -> Result<(f64, f64), String> {
    let first_line = |e: raceway::Error| e.to_string().lines().next().unwrap_or("").to_string();
    let mut c = Component::from_text(text).map_err(first_line)?;
    let (_, t) = drive(&mut c, 0.05, 1e-4, &[], None).map_err(first_line)?;
    Ok((t, t / c.stats().rhs.max(1) as f64))
}

fn main() {
    // Interleaved runs, so both sides see the same machine load; the spread of the
    // identical-scene rows shows the noise of the machine.
    let reps = 31;
    println!(
        "{:<40} {:>10} {:>12} {:>7} {:>14} {:>7} {:>9}",
        "comparison", "with (ms)", "without (ms)", "ratio", "ns/rhs w / wo", "ratio", "min ratio"
    );
    for (what, with, without) in pairs() {
        // Warm-up, and a clean skip for a section that does not exist yet.
        if let Err(e) = time_once(&with).and(time_once(&without)) {
            println!("{what:<40} not available: {e}");
            continue;
        }
        let (mut a, mut b, mut ra, mut rb) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for _ in 0..reps {
            // Alternate the order (ABBA) so neither side always runs first.
            let (x, y) = if a.len() % 2 == 0 {
                let x = time_once(&with).unwrap();
                (x, time_once(&without).unwrap())
            } else {
                let y = time_once(&without).unwrap();
                (time_once(&with).unwrap(), y)
            };
            a.push(x.0);
            ra.push(x.1);
            b.push(y.0);
            rb.push(y.1);
        }
        let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let min_ratio = min(&a) / min(&b);
        let (ma, mb) = (median(&mut a), median(&mut b));
        let (pa, pb) = (median(&mut ra), median(&mut rb));
        println!(
            "{what:<40} {:>10.4} {:>12.4} {:>7.3} {:>6.0} / {:<6.0} {:>7.3} {:>9.3}",
            ma * 1e3,
            mb * 1e3,
            ma / mb,
            pa * 1e9,
            pb * 1e9,
            pa / pb,
            min_ratio
        );
    }
}
