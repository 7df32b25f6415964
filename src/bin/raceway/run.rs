//! `raceway run [scene.toml] [--out DIR] [--quiet]`: run a scene stand-alone, write the time
//! series, a summary and plots.

use raceway::analysis::{
    amplitude_spectrum, characteristic_marks, find_peaks, whirl_index, Window,
};
use raceway::component::scene::DEFAULT_SCENE;
use raceway::component::{schema, Causality, Scene};
use raceway::geometry::kinematics;
use raceway::models::quasi_static::{azimuths, BallResult, BallState, Options, QuasiStatic};
use raceway::plot::{plot, Axes, Marker, Series};
use raceway::runner::{self, Series as Run};
use raceway::{Error, Result};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// Options of `raceway run`.
#[derive(clap::Args, Debug)]
pub struct RunArgs {
    /// Scene file (TOML or JSON); without it, the embedded default scene.
    pub scene: Option<PathBuf>,
    /// Output folder (default: out/<scene name>).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Override the scene's run duration, s.
    #[arg(long)]
    pub duration: Option<f64>,
    /// No progress bar and no summary on standard output (for scripts).
    #[arg(long, short)]
    pub quiet: bool,
}

fn io(path: &Path, e: std::io::Error) -> Error {
    Error::Io(format!("cannot write `{}`: {e}", path.display()))
}

/// Run and report; returns the text for standard output.
pub fn run(a: RunArgs) -> Result<String> {
    // One validation path: the file is checked as `raceway scene --check` checks it (every
    // problem at once), then again with the command-line overrides applied.
    let (text, file, name) = match &a.scene {
        Some(p) => (
            std::fs::read_to_string(p)
                .map_err(|e| Error::Io(format!("cannot read scene `{}`: {e}", p.display())))?,
            p.display().to_string(),
            p.file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "scene".into()),
        ),
        None => (
            DEFAULT_SCENE.to_string(),
            "default".to_string(),
            "default".to_string(),
        ),
    };
    let mut overrides = Vec::new();
    if let Some(d) = a.duration {
        overrides.push(("run.duration_s", d));
    }
    let scene = schema::load(&text, &overrides)
        .map_err(|problems| crate::scene_cmd::problems_error(&file, &problems))?;
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(&name));
    std::fs::create_dir_all(&out).map_err(|e| io(&out, e))?;
    let quiet = a.quiet;
    let bar_on = !quiet && std::io::IsTerminal::is_terminal(&std::io::stderr());
    let started = std::time::Instant::now();
    let mut last = -1i64;
    let mut progress = |f: f64| {
        if !bar_on {
            return;
        }
        let pct = (f * 100.0).floor() as i64;
        if pct != last {
            last = pct;
            let bar = (f * 40.0).round() as usize;
            eprint!("\r[{}{}] {pct:3}%", "#".repeat(bar), " ".repeat(40 - bar));
            let _ = std::io::stderr().flush();
        }
    };
    let (series, comp) = runner::run(&scene, &mut progress)?;
    if bar_on {
        eprintln!();
    }
    let cpu = started.elapsed().as_secs_f64();

    let csv = out.join("series.csv");
    std::fs::write(&csv, series.to_csv()).map_err(|e| io(&csv, e))?;

    // Summary.
    let b = comp.bearing().clone();
    let omega = series
        .column("shaft.omega")
        .and_then(|c| c.last().copied())
        .unwrap_or(0.0);
    let kin = kinematics(&b, omega);
    let fs_hz = omega / (2.0 * std::f64::consts::PI);
    let col = |n: &str| series.column(n).unwrap_or(&[]);
    let peak = |n: &str| col(n).iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let causality = scene.model.causality;
    // The signal whose spectrum tells the frequencies: ring motion when load-driven, the
    // force when motion-driven; over the second half of the run (past the start transient).
    let signal_name = if causality == Causality::Load {
        "shaft.y"
    } else {
        "force.y"
    };
    let n = series.t.len();
    let start = n / 2;
    let sig: Vec<f64> = col(signal_name)[start..].to_vec();
    let mean = sig.iter().sum::<f64>() / sig.len().max(1) as f64;
    let sig: Vec<f64> = sig.iter().map(|v| v - mean).collect();
    let dt = scene.run.duration_s / (n - 1).max(1) as f64;
    let spec = amplitude_spectrum(&sig, 1.0 / dt, Window::Hann);
    let marks = characteristic_marks(&kin, fs_hz, 3, 1);
    let main: Vec<_> = marks
        .iter()
        .filter(|m| {
            ["fs", "FTF", "BSF", "1xBPFO", "1xBPFI", "1x2BSF", "2xBPFO"].contains(&m.label.as_str())
        })
        .cloned()
        .collect();
    let found = find_peaks(&spec, &main, 2.0 * spec.resolution());
    let mut s = String::new();
    writeln!(
        s,
        "scene: {} ({}; level {}, {:?}-driven)",
        name,
        scene.title,
        scene.model.level.name(),
        causality
    )
    .ok();
    writeln!(
        s,
        "bearing: {} (D {:.3} mm, dm {:.3} mm, Z {}, Pd {:.2} µm)",
        b.name,
        b.d * 1e3,
        b.dm * 1e3,
        b.z,
        b.pd * 1e6
    )
    .ok();
    writeln!(
        s,
        "simulated {:.4} s in {} steps, {:.3} s of CPU ({:.2}x real time)",
        scene.run.duration_s,
        n - 1,
        cpu,
        scene.run.duration_s / cpu
    )
    .ok();
    writeln!(
        s,
        "peak |force.x| {:.2} N, |force.y| {:.2} N, |force.z| {:.2} N",
        peak("force.x"),
        peak("force.y"),
        peak("force.z")
    )
    .ok();
    writeln!(
        s,
        "peak contact load {:.2} N, peak Hertz pressure {:.3} GPa",
        peak("contact.max_load"),
        peak("contact.max_pressure") * 1e-9
    )
    .ok();
    let slip = col("cage.slip");
    writeln!(
        s,
        "cage slip: final {:.4}",
        slip.last().copied().unwrap_or(0.0)
    )
    .ok();
    // Cage dynamics (the full level): whirl index over the second half of the run.
    let cage_level = scene.model.level.name() == "full";
    let sigma = if cage_level {
        whirl_index(&col("cage.speed")[start..])
    } else {
        None
    };
    let orbit_max = col("cage.x")
        .iter()
        .zip(col("cage.y"))
        .fold(0.0f64, |m, (x, y)| m.max(x.hypot(*y)));
    if cage_level {
        writeln!(
            s,
            "cage: whirl index sigma {} (second half), largest orbit {:.3} guide clearances, \
             peak pocket force {:.2} N, peak guide force {:.2} N, final speed ratio {:.4}",
            sigma.map_or("-".to_string(), |v| format!("{v:.4}")),
            orbit_max,
            peak("pocket.max_force"),
            peak("guide.force"),
            col("cage.speed_ratio").last().copied().unwrap_or(0.0)
        )
        .ok();
    }
    writeln!(
        s,
        "shaft {:.2} Hz; characteristic frequencies (expected / found in the {} spectrum):",
        fs_hz, signal_name
    )
    .ok();
    for p in &found {
        writeln!(
            s,
            "  {:<8} {:>10.3} Hz  {:>10} Hz",
            p.label,
            p.expected,
            if p.found.is_nan() {
                "-".to_string()
            } else {
                format!("{:.3}", p.found)
            }
        )
        .ok();
    }
    // ISO ratings, life, static safety and warnings at the run's mean load (raceway::ratings).
    let rating = raceway::ratings::assess_run(&b, &series, start);
    match &rating {
        Ok(a) => s += &format!("at the mean load of the second half:\n{}", a.text()),
        Err(e) => s += &format!("ratings and life: not available ({e})\n"),
    }
    let summary = out.join("summary.txt");
    std::fs::write(&summary, &s).map_err(|e| io(&summary, e))?;
    let json = serde_json::json!({
        "scene": name, "level": scene.model.level.name(), "duration_s": scene.run.duration_s, "cpu_s": cpu,
        "peak_force_n": [peak("force.x"), peak("force.y"), peak("force.z")],
        "peak_contact_load_n": peak("contact.max_load"), "peak_pressure_pa": peak("contact.max_pressure"),
        "final_cage_slip": slip.last().copied().unwrap_or(0.0),
        "cage_whirl_sigma": sigma, "cage_orbit_max": if cage_level { Some(orbit_max) } else { None },
        "peak_pocket_force_n": peak("pocket.max_force"), "peak_guide_force_n": peak("guide.force"),
        "frequencies": found.iter().map(|p| serde_json::json!({"label": p.label, "expected_hz": p.expected, "found_hz": if p.found.is_nan() { None } else { Some(p.found) }})).collect::<Vec<_>>(),
    });
    let mut json = json;
    json["rating"] = serde_json::to_value(rating.as_ref().ok()).unwrap_or_default();
    json["warnings"] = rating
        .as_ref()
        .map(|a| a.warning_texts())
        .unwrap_or_default()
        .into();
    let sj = out.join("summary.json");
    std::fs::write(&sj, serde_json::to_string_pretty(&json).unwrap_or_default())
        .map_err(|e| io(&sj, e))?;

    write_plots(&out, &series, &scene, &spec, &marks, signal_name, &comp)?;
    if quiet {
        return Ok(String::new());
    }
    let extra = if cage_level {
        ", cage-orbit.png, speeds.png"
    } else {
        ""
    };
    writeln!(s, "results in {}/ (series.csv, summary.txt, summary.json, orbit.png, force.png, spectrum.png, ball-loads.png, cage-slip.png{extra})", out.display()).ok();
    Ok(s)
}

fn write_plots(
    out: &Path,
    series: &Run,
    scene: &Scene,
    spec: &raceway::analysis::Spectrum,
    marks: &[raceway::analysis::Mark],
    signal_name: &str,
    comp: &raceway::Component,
) -> Result<()> {
    let col = |n: &str| series.column(n).unwrap_or(&[]).to_vec();
    let micro = |v: Vec<f64>| v.into_iter().map(|x| x * 1e6).collect::<Vec<_>>();
    let t = &series.t;
    // Orbit: the ring centre (load-driven) or the force (motion-driven).
    let (ox, oy, lx, ly, title) = if scene.model.causality == Causality::Load {
        (
            micro(col("shaft.x")),
            micro(col("shaft.y")),
            "x (µm)",
            "y (µm)",
            "inner-ring orbit",
        )
    } else {
        (
            col("force.x"),
            col("force.y"),
            "Fx (N)",
            "Fy (N)",
            "force orbit",
        )
    };
    plot(
        &out.join("orbit.png"),
        &Axes {
            title,
            x_label: lx,
            y_label: ly,
            equal: true,
            ..Axes::default()
        },
        &[Series {
            label: "",
            x: &ox,
            y: &oy,
            points: false,
        }],
        &[],
    )?;
    let (fx, fy, fz) = (col("force.x"), col("force.y"), col("force.z"));
    plot(
        &out.join("force.png"),
        &Axes {
            title: "force of the bearing on the shaft",
            x_label: "t (s)",
            y_label: "force (N)",
            ..Axes::default()
        },
        &[
            Series {
                label: "Fx",
                x: t,
                y: &fx,
                points: false,
            },
            Series {
                label: "Fy",
                x: t,
                y: &fy,
                points: false,
            },
            Series {
                label: "Fz",
                x: t,
                y: &fz,
                points: false,
            },
        ],
        &[],
    )?;
    let fmax = marks
        .iter()
        .filter(|m| m.label == "3xBPFI")
        .map(|m| m.freq * 1.3)
        .next()
        .unwrap_or(f64::INFINITY);
    let keep: Vec<usize> = (1..spec.freq.len())
        .filter(|&i| spec.freq[i] <= fmax)
        .collect();
    let sf: Vec<f64> = keep.iter().map(|&i| spec.freq[i]).collect();
    let sa: Vec<f64> = keep.iter().map(|&i| spec.amp[i].max(1e-30)).collect();
    let mk: Vec<Marker> = marks
        .iter()
        .filter(|m| {
            [
                "FTF", "1xBPFO", "1xBPFI", "1x2BSF", "2xBPFO", "2xBPFI", "fs",
            ]
            .contains(&m.label.as_str())
        })
        .map(|m| Marker {
            x: m.freq,
            label: m.label.trim_start_matches("1x").to_string(),
        })
        .collect();
    let ylab = format!("amplitude of {signal_name}");
    plot(
        &out.join("spectrum.png"),
        &Axes {
            title: "spectrum (second half of the run, Hann window)",
            x_label: "f (Hz)",
            y_label: &ylab,
            log_y: true,
            ..Axes::default()
        },
        &[Series {
            label: "",
            x: &sf,
            y: &sa,
            points: false,
        }],
        &mk,
    )?;
    // Ball loads around the circumference: the Jones–Harris equilibrium at the final motion
    // and speed, balls at their reference azimuths.
    let b = comp.bearing();
    let q: [f64; 5] = std::array::from_fn(|k| {
        col(["shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry"][k])
            .last()
            .copied()
            .unwrap_or(0.0)
    });
    let omega = col("shaft.omega").last().copied().unwrap_or(0.0);
    let qs = QuasiStatic::new(
        b,
        Options {
            race_control: scene.model.race_control,
            ..Options::default()
        },
    )?;
    let psi = azimuths(b.z, 0.0);
    let mut st = vec![BallState::default(); b.z];
    let mut res = vec![BallResult::default(); b.z];
    qs.evaluate(&q, omega, &psi, &mut st, None, Some(&mut res))?;
    let deg: Vec<f64> = psi.iter().map(|p| p.to_degrees()).collect();
    let qi: Vec<f64> = res.iter().map(|r| r.q_i).collect();
    let qo: Vec<f64> = res.iter().map(|r| r.q_o).collect();
    plot(
        &out.join("ball-loads.png"),
        &Axes {
            title: "ball loads around the circumference (final motion)",
            x_label: "azimuth (deg)",
            y_label: "load (N)",
            ..Axes::default()
        },
        &[
            Series {
                label: "inner contact",
                x: &deg,
                y: &qi,
                points: true,
            },
            Series {
                label: "outer contact",
                x: &deg,
                y: &qo,
                points: true,
            },
        ],
        &[],
    )?;
    let slip = col("cage.slip");
    plot(
        &out.join("cage-slip.png"),
        &Axes {
            title: "cage slip",
            x_label: "t (s)",
            y_label: "1 - omega_c / omega_c,kin",
            ..Axes::default()
        },
        &[Series {
            label: "",
            x: t,
            y: &slip,
            points: false,
        }],
        &[],
    )?;
    if scene.model.level.name() == "full" {
        write_cage_plots(out, series)?;
    }
    Ok(())
}

/// The full level's cage plots: the cage-centre orbit in units of the guide clearance
/// (with the clearance circle) and the speed histories (shaft, cage, kinematic cage).
fn write_cage_plots(out: &Path, series: &Run) -> Result<()> {
    let col = |n: &str| series.column(n).unwrap_or(&[]).to_vec();
    let t = &series.t;
    let (cx, cy) = (col("cage.x"), col("cage.y"));
    let circle: Vec<(f64, f64)> = (0..=360)
        .map(|k| (k as f64).to_radians().sin_cos())
        .map(|(s, c)| (c, s))
        .collect();
    let (ux, uy): (Vec<f64>, Vec<f64>) = circle.into_iter().unzip();
    plot(
        &out.join("cage-orbit.png"),
        &Axes {
            title: "cage-centre orbit (units of the guide clearance)",
            x_label: "x / Cg",
            y_label: "y / Cg",
            equal: true,
            ..Axes::default()
        },
        &[
            Series {
                label: "guide clearance",
                x: &ux,
                y: &uy,
                points: false,
            },
            Series {
                label: "cage centre",
                x: &cx,
                y: &cy,
                points: false,
            },
        ],
        &[],
    )?;
    let rpm = |v: Vec<f64>| {
        v.into_iter()
            .map(|w| w * 60.0 / (2.0 * std::f64::consts::PI))
            .collect::<Vec<_>>()
    };
    let shaft = rpm(col("shaft.omega"));
    let cage = rpm(col("cage.omega"));
    let ratio = col("cage.speed_ratio");
    let kin: Vec<f64> = cage
        .iter()
        .zip(&ratio)
        .map(|(c, r)| if *r != 0.0 { c / r } else { 0.0 })
        .collect();
    plot(
        &out.join("speeds.png"),
        &Axes {
            title: "speed histories",
            x_label: "t (s)",
            y_label: "speed (rpm)",
            ..Axes::default()
        },
        &[
            Series {
                label: "shaft",
                x: t,
                y: &shaft,
                points: false,
            },
            Series {
                label: "cage",
                x: t,
                y: &cage,
                points: false,
            },
            Series {
                label: "cage, kinematic",
                x: t,
                y: &kin,
                points: false,
            },
        ],
        &[],
    )
}
