//! Cage-whirl study of the hybrid 7004 (study [0], Ye, Wang, Zhang; physics.md §5.5 and the
//! §10 row): the `full` level at 30 000, 60 000, 80 000 and 120 000 rpm under Fa 2000 N,
//! Fr 400 N, from the scenes `examples/scenes/7004-*.toml`.
//!
//! ```text
//! cargo run --release --example cage_whirl                 # full study, table on stdout
//! cargo run --release --example cage_whirl -- --quick      # CI: two speeds, a few ms each
//! cargo run --release --example cage_whirl -- --write-docs # study + docs/cage-whirl.md, PNGs
//! ```
//!
//! Options (each changes one thing against the scenes, for the sensitivity runs):
//! `--speeds 30000,120000`, `--duration S` (simulated time per speed), `--step S`
//! (communication step = sampling of the cage-centre speed), `--viscosity PAS`,
//! `--guide-width-mm MM`, `--guide-clearance-mm MM` (radial), `--pocket-clearance-mm MM`,
//! `--mu MU` (Coulomb traction `mu_max`), `--drag-density KGM3`, `--guide-eps-max E`
//! (where the land's film law is capped and the wall spring starts), `--traction-vs V`
//! (Coulomb traction transition slip speed, m/s), `--pocket-friction MU`, `--no-radial` (ring centred radially:
//! the scene's axial displacement only, so Fr = 0), `--tight` (rtol 1e-5,
//! atol 1e-9 m at every speed).
//!
//! Columns: speed; sigma = std(|v|)/mean(|v|) of the level's `cage.speed` (the 3-D
//! cage-centre speed, as `raceway run`) over the second half of the run; the same index
//! of the in-plane speed from central differences of the sampled orbit, a check on the
//! sampling; the
//! largest orbit radius in guide clearances; the mean guide-land force and the peak pocket
//! force over the second half; the cage speed ratio (cage / kinematic) at the end; CPU
//! seconds per shaft revolution.

use raceway::analysis::whirl_index;
use raceway::geometry::preset;
use raceway::runner;
use raceway::Scene;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One speed's results.
#[derive(Debug, Clone)]
struct Row {
    rpm: f64,
    sigma: f64,
    sigma_xy: f64,
    orbit_max: f64,
    orbit_mean: f64,
    guide_mean: f64,
    pocket_peak: f64,
    pocket_peak_2nd: f64,
    ratio: f64,
    cpu_per_rev: f64,
    /// Orbit (second half), guide clearances.
    ox: Vec<f64>,
    oy: Vec<f64>,
}

/// Options of a study run.
#[derive(Debug, Clone, Default)]
struct Opts {
    speeds: Vec<f64>,
    duration: f64,
    step: f64,
    viscosity: Option<f64>,
    guide_width_mm: Option<f64>,
    guide_clearance_mm: Option<f64>,
    pocket_clearance_mm: Option<f64>,
    mu: Option<f64>,
    drag_density: Option<f64>,
    guide_eps_max: Option<f64>,
    traction_vs: Option<f64>,
    pocket_friction: Option<f64>,
    no_radial: bool,
    tight: bool,
}

fn scene_for(rpm: f64, o: &Opts) -> Result<Scene, Box<dyn std::error::Error>> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes")
        .join(format!("7004-{}.toml", rpm.round() as i64));
    let mut s = Scene::from_text(&std::fs::read_to_string(&path)?)?;
    s.run.duration_s = o.duration;
    s.run.step_s = o.step;
    let f = &mut s.model.full;
    if let Some(v) = o.viscosity {
        f.viscosity = v;
    }
    if let Some(v) = o.guide_width_mm {
        f.guide_width_mm = Some(v);
    }
    if let Some(v) = o.pocket_clearance_mm {
        f.pocket_clearance_mm = Some(v);
    }
    if let Some(v) = o.pocket_friction {
        f.pocket_friction = v;
    }
    if let Some(v) = o.guide_eps_max {
        f.guide_eps_max = v;
    }
    if let Some(v) = o.drag_density {
        f.drag_density = v;
    }
    if let Some(mu) = o.mu {
        if let raceway::contact::traction::TractionLaw::Coulomb { mu_max, .. } = &mut f.traction {
            *mu_max = mu;
        }
    }
    if let Some(v) = o.traction_vs {
        if let raceway::contact::traction::TractionLaw::Coulomb { v_s, .. } = &mut f.traction {
            *v_s = v;
        }
    }
    if let Some(c) = o.guide_clearance_mm {
        // The bearing's cage data: a preset with the clearance replaced, as a table.
        let mut spec = preset("7004")?;
        spec.cage.guide_clearance_mm = Some(c);
        s.bearing = raceway::component::scene::BearingRef::Table(toml::Table::try_from(&spec)?);
    }
    if o.no_radial {
        // Ring centred radially: pure axial displacement (Fr = 0, Fa about the same).
        s.inputs.initial.insert("shaft.y".into(), 0.0);
    }
    if o.tight {
        s.solver.rtol = 1e-5;
        s.solver.atol_m = 1e-9;
    }
    Ok(s)
}

fn run_one(rpm: f64, o: &Opts) -> Result<Row, Box<dyn std::error::Error>> {
    let scene = scene_for(rpm, o)?;
    let t0 = raceway::report::thread_cpu_s();
    let (series, _) = runner::run(&scene, &mut |_| {})?;
    let cpu = raceway::report::thread_cpu_s() - t0;
    let col = |n: &str| series.column(n).map(|c| c.to_vec()).unwrap_or_default();
    let n = series.t.len();
    let start = n / 2;
    let speed = col("cage.speed");
    let (cx, cy) = (col("cage.x"), col("cage.y"));
    let sigma = whirl_index(&speed[start..]).unwrap_or(f64::NAN);
    // In-plane speed from the sampled orbit (central differences), the check on sampling.
    let b = scene.build_bearing()?;
    let cg = b.cage.guide_clearance;
    let h = series.t[1] - series.t[0];
    let vxy: Vec<f64> = (start.max(1)..n - 1)
        .map(|k| {
            let dx = (cx[k + 1] - cx[k - 1]) * cg / (2.0 * h);
            let dy = (cy[k + 1] - cy[k - 1]) * cg / (2.0 * h);
            dx.hypot(dy)
        })
        .collect();
    let sigma_xy = whirl_index(&vxy).unwrap_or(f64::NAN);
    let r: Vec<f64> = cx.iter().zip(&cy).map(|(x, y)| x.hypot(*y)).collect();
    let orbit_max = r.iter().fold(0.0f64, |m, v| m.max(*v));
    let orbit_mean = r[start..].iter().sum::<f64>() / (n - start) as f64;
    let guide = col("guide.force");
    let guide_mean = guide[start..].iter().sum::<f64>() / (n - start) as f64;
    let pocket = col("pocket.max_force");
    let pocket_peak = pocket.iter().fold(0.0f64, |m, v| m.max(*v));
    let pocket_peak_2nd = pocket[start..].iter().fold(0.0f64, |m, v| m.max(*v));
    let ratio = *col("cage.speed_ratio").last().unwrap_or(&f64::NAN);
    let revs = rpm / 60.0 * o.duration;
    Ok(Row {
        rpm,
        sigma,
        sigma_xy,
        orbit_max,
        orbit_mean,
        guide_mean,
        pocket_peak,
        pocket_peak_2nd,
        ratio,
        cpu_per_rev: cpu / revs,
        ox: cx[start..].to_vec(),
        oy: cy[start..].to_vec(),
    })
}

fn header() -> String {
    "| speed, rpm | sigma | sigma (x,y) | orbit max / Cg | orbit mean / Cg | guide force mean, N | pocket peak, N (all / 2nd half) | cage speed ratio | CPU per shaft rev, ms |\n|---|---|---|---|---|---|---|---|---|\n".into()
}

fn line(r: &Row) -> String {
    format!(
        "| {:.0} | {:.4} | {:.4} | {:.3} | {:.3} | {:.3e} | {:.2} / {:.2} | {:.4} | {:.3} |\n",
        r.rpm,
        r.sigma,
        r.sigma_xy,
        r.orbit_max,
        r.orbit_mean,
        r.guide_mean,
        r.pocket_peak,
        r.pocket_peak_2nd,
        r.ratio,
        r.cpu_per_rev * 1e3
    )
}

fn study(o: &Opts) -> Result<(Vec<Row>, String), Box<dyn std::error::Error>> {
    let mut rows = Vec::new();
    let mut s = header();
    for &rpm in &o.speeds {
        let r = run_one(rpm, o)?;
        s += &line(&r);
        rows.push(r);
    }
    Ok((rows, s))
}

fn parse() -> Result<(Opts, bool, bool), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut o = Opts {
        speeds: vec![30_000.0, 60_000.0, 80_000.0, 120_000.0],
        duration: 0.15,
        step: 1e-5,
        ..Opts::default()
    };
    let (mut quick, mut docs) = (false, false);
    let mut i = 0;
    while i < args.len() {
        let a = args[i].as_str();
        let mut val = || -> Result<f64, Box<dyn std::error::Error>> {
            i += 1;
            Ok(args.get(i).ok_or(format!("{a} needs a value"))?.parse()?)
        };
        match a {
            "--quick" => quick = true,
            "--write-docs" => docs = true,
            "--tight" => o.tight = true,
            "--no-radial" => o.no_radial = true,
            "--duration" => o.duration = val()?,
            "--step" => o.step = val()?,
            "--viscosity" => o.viscosity = Some(val()?),
            "--guide-width-mm" => o.guide_width_mm = Some(val()?),
            "--guide-clearance-mm" => o.guide_clearance_mm = Some(val()?),
            "--pocket-clearance-mm" => o.pocket_clearance_mm = Some(val()?),
            "--mu" => o.mu = Some(val()?),
            "--drag-density" => o.drag_density = Some(val()?),
            "--guide-eps-max" => o.guide_eps_max = Some(val()?),
            "--traction-vs" => o.traction_vs = Some(val()?),
            "--pocket-friction" => o.pocket_friction = Some(val()?),
            "--speeds" => {
                i += 1;
                o.speeds = args
                    .get(i)
                    .ok_or("--speeds needs a list")?
                    .split(',')
                    .map(|s| s.trim().parse())
                    .collect::<Result<_, _>>()?;
            }
            other => return Err(format!("unknown option `{other}` (see the file's header)").into()),
        }
        i += 1;
    }
    if quick {
        o.speeds = vec![30_000.0, 120_000.0];
        o.duration = 4e-3;
        o.step = 2e-5;
    }
    Ok((o, quick, docs))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (o, quick, docs) = parse()?;
    println!(
        "cage whirl, 7004, Fa 2000 N, Fr 400 N: {} s per speed, communication step {} s{}",
        o.duration,
        o.step,
        if quick { " (quick)" } else { "" }
    );
    let (rows, table) = study(&o)?;
    print!("{table}");
    if quick {
        // The CI check: finite, inside the clearance (wall spring beyond eps_max).
        for r in &rows {
            if !(r.sigma.is_finite() && r.orbit_max < 1.5 && r.ratio.is_finite()) {
                return Err(format!("bad result at {} rpm: {r:?}", r.rpm).into());
            }
        }
    }
    if docs {
        write_docs(&o, &rows, &table)?;
    }
    Ok(())
}

/// Sampling study at one speed: sigma against the communication step.
fn sampling(o: &Opts, rpm: f64) -> Result<String, Box<dyn std::error::Error>> {
    let mut s = String::from(
        "| step, s | samples per cage revolution | sigma | sigma (x,y) | orbit max / Cg |\n|---|---|---|---|---|\n",
    );
    for step in [1e-4, 5e-5, 2e-5, 1e-5, 5e-6] {
        let r = run_one(rpm, &Opts { step, ..o.clone() })?;
        let cage_hz = r.ratio * 0.38 * rpm / 60.0;
        writeln!(
            s,
            "| {step:.0e} | {:.0} | {:.4} | {:.4} | {:.3} |",
            1.0 / (step * cage_hz),
            r.sigma,
            r.sigma_xy,
            r.orbit_max
        )?;
    }
    Ok(s)
}

/// One-at-a-time sensitivity: sigma at each speed for each variation.
fn sensitivity(o: &Opts) -> Result<String, Box<dyn std::error::Error>> {
    let cases: Vec<(&str, Opts)> = vec![
        ("scenes as they are", o.clone()),
        (
            "oil viscosity 0.012 Pa s (x4; land, pockets, drag)",
            Opts {
                viscosity: Some(0.012),
                ..o.clone()
            },
        ),
        (
            "oil viscosity 0.03 Pa s (x10; land, pockets, drag)",
            Opts {
                viscosity: Some(0.03),
                ..o.clone()
            },
        ),
        (
            "guide land width 6.4 mm (x2, the whole cage width)",
            Opts {
                guide_width_mm: Some(6.4),
                ..o.clone()
            },
        ),
        (
            "guide land width 6.9 mm (land film x10 alone; a probe wider than the cage)",
            Opts {
                guide_width_mm: Some(6.894),
                ..o.clone()
            },
        ),
        (
            "guide clearance 0.125 mm (0.25 mm read as diametral)",
            Opts {
                guide_clearance_mm: Some(0.125),
                ..o.clone()
            },
        ),
        (
            "land film law up to eps 0.99 (guide_eps_max)",
            Opts {
                guide_eps_max: Some(0.99),
                ..o.clone()
            },
        ),
        (
            "pocket clearance 0.5 mm (pocket side play = guide clearance)",
            Opts {
                pocket_clearance_mm: Some(0.5),
                ..o.clone()
            },
        ),
        (
            "traction mu_max 0.1 (x2)",
            Opts {
                mu: Some(0.1),
                ..o.clone()
            },
        ),
        (
            "softer traction: v_s 0.5 m/s (x10)",
            Opts {
                traction_vs: Some(0.5),
                ..o.clone()
            },
        ),
        (
            "Fr = 0 (ring centred radially; sigma of a near-zero orbit is noise)",
            Opts {
                no_radial: true,
                ..o.clone()
            },
        ),
        (
            "drag density 50 kg/m3 (x5)",
            Opts {
                drag_density: Some(50.0),
                ..o.clone()
            },
        ),
    ];
    let mut s = String::from("| variation |");
    for rpm in &o.speeds {
        write!(s, " sigma at {:.0}k (orbit max / Cg) |", rpm / 1e3)?;
    }
    s += "\n|---|";
    for _ in &o.speeds {
        s += "---|";
    }
    s += "\n";
    for (name, oc) in cases {
        write!(s, "| {name} |")?;
        for &rpm in &o.speeds {
            let r = run_one(rpm, &oc)?;
            write!(s, " {:.4} ({:.2}) |", r.sigma, r.orbit_max)?;
        }
        s += "\n";
        eprintln!("{s}");
    }
    Ok(s)
}

fn write_docs(o: &Opts, rows: &[Row], table: &str) -> Result<(), Box<dyn std::error::Error>> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs");
    std::fs::create_dir_all(&dir)?;
    let samp = sampling(
        &Opts {
            duration: o.duration.min(0.04),
            ..o.clone()
        },
        120_000.0,
    )?;
    eprintln!("{samp}");
    let sens = sensitivity(&Opts {
        duration: o.duration.min(0.05),
        step: o.step.max(1e-5),
        ..o.clone()
    })?;
    #[cfg(feature = "plot")]
    plots(&dir, rows)?;
    let here = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut md = String::new();
    md += &std::fs::read_to_string(here.join("cage_whirl_head.md"))?;
    writeln!(
        md,
        "\n## Results\n\n{} s simulated per speed, communication step {} s, second half for the statistics:\n\n{table}",
        o.duration, o.step
    )?;
    writeln!(
        md,
        "\n### Sampling (120 000 rpm, {} s)\n\n{samp}",
        o.duration.min(0.04)
    )?;
    writeln!(
        md,
        "\n### One thing at a time ({} s per run)\n\n{sens}",
        o.duration.min(0.05)
    )?;
    md += &std::fs::read_to_string(here.join("cage_whirl_tail.md"))?;
    std::fs::write(dir.join("cage-whirl.md"), md)?;
    let _ = rows;
    Ok(())
}

#[cfg(feature = "plot")]
fn plots(dir: &Path, rows: &[Row]) -> Result<(), Box<dyn std::error::Error>> {
    use raceway::plot::{plot, Axes, Series};
    let x: Vec<f64> = rows.iter().map(|r| r.rpm).collect();
    let y: Vec<f64> = rows.iter().map(|r| r.sigma).collect();
    plot(
        &dir.join("cage-whirl-sigma.png"),
        &Axes {
            title: "cage whirl index sigma vs shaft speed (7004, Fa 2000 N, Fr 400 N)",
            x_label: "shaft speed, rpm",
            y_label: "sigma = std(|v|)/mean(|v|)",
            ..Axes::default()
        },
        &[Series {
            label: "full level",
            x: &x,
            y: &y,
            points: false,
        }],
        &[],
    )?;
    let labels: Vec<String> = rows.iter().map(|r| format!("{:.0} rpm", r.rpm)).collect();
    let circle: (Vec<f64>, Vec<f64>) = (0..=200)
        .map(|k| {
            let a = 2.0 * std::f64::consts::PI * k as f64 / 200.0;
            (a.cos(), a.sin())
        })
        .unzip();
    let mut series: Vec<Series> = rows
        .iter()
        .zip(&labels)
        .map(|(r, l)| Series {
            label: l,
            x: &r.ox,
            y: &r.oy,
            points: false,
        })
        .collect();
    series.push(Series {
        label: "guide clearance",
        x: &circle.0,
        y: &circle.1,
        points: false,
    });
    plot(
        &dir.join("cage-whirl-orbits.png"),
        &Axes {
            title: "cage-centre orbits, second half (units of the guide clearance)",
            x_label: "x / Cg",
            y_label: "y / Cg",
            equal: true,
            ..Axes::default()
        },
        &series,
        &[],
    )?;
    Ok(())
}
