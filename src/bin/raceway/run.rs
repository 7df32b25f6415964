//! `raceway run [scene.toml] [--out DIR] [--quiet]`: run a scene stand-alone, write the time
//! series, a summary and plots.

use raceway::analysis::{
    amplitude_spectrum, characteristic_marks, envelope_spectrum, find_peaks, whirl_index,
    FoundPeak, Spectrum, Verdict, Window, FOUND_OVER_FLOOR,
};
use raceway::component::scene::DEFAULT_SCENE;
use raceway::component::{schema, Causality, Scene};
use raceway::geometry::kinematics;
use raceway::models::quasi_static::{azimuths, BallResult, BallState, Options, QuasiStatic};
use raceway::plot::{plot, plot_stack, Axes, Marker, Series};
use raceway::runner::{self, Record, Series as Run};
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
    /// Add the stiffness and damping matrices (columns K.i.j and C.i.j, 50 more) to
    /// series.csv.
    #[arg(long)]
    pub kc: bool,
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
    let cpu0 = raceway::report::thread_cpu_s();
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
    let (series, comp) = runner::run_recording(
        &scene,
        Record {
            stiffness_damping: a.kc,
        },
        &mut progress,
    )?;
    if bar_on {
        eprintln!();
    }
    let cpu = raceway::report::thread_cpu_s() - cpu0;

    let csv = out.join("series.csv");
    raceway::fsutil::write_atomic(&csv, series.to_csv()).map_err(|e| io(&csv, e))?;

    let ctx = Ctx::new(&scene, &name, &series, &comp, cpu);
    let sm = summary_of(&ctx);
    let summary = out.join("summary.txt");
    raceway::fsutil::write_atomic(&summary, &sm.text).map_err(|e| io(&summary, e))?;
    let sj = out.join("summary.json");
    raceway::fsutil::write_atomic(
        &sj,
        serde_json::to_string_pretty(&serde_json::Value::Object(sm.json)).unwrap_or_default(),
    )
    .map_err(|e| io(&sj, e))?;

    let pngs = write_plots(&out, &ctx)?;
    if quiet {
        return Ok(String::new());
    }
    let mut s = sm.text;
    writeln!(
        s,
        "results in {}/ (series.csv{}, summary.txt, summary.json, {})",
        out.display(),
        if a.kc { " with K and C" } else { "" },
        pngs.join(", ")
    )
    .ok();
    Ok(s)
}

/// The sections of the summary, in order.
fn summary_of(ctx: &Ctx) -> Summary {
    let mut sm = Summary::default();
    scene_lines(ctx, &mut sm);
    load_lines(ctx, &mut sm);
    cage_lines(ctx, &mut sm);
    frequency_lines(ctx, &mut sm);
    rating_lines(ctx, &mut sm);
    sm
}

/// The summary of a finished run (`cpu_s`: its thread CPU time), as `raceway run` writes it
/// to summary.txt and summary.json; what `raceway sweep` flattens into a row.
pub fn summarize(
    scene: &Scene,
    name: &str,
    series: &Run,
    comp: &raceway::Component,
    cpu_s: f64,
) -> Summary {
    summary_of(&Ctx::new(scene, name, series, comp, cpu_s))
}

/// The summary: text lines and the same facts as JSON. A section is a function
/// `fn x_lines(ctx: &Ctx, s: &mut Summary)` called in [`run`]; add lines with
/// [`Summary::line`] and values with [`Summary::set`].
#[derive(Default)]
pub struct Summary {
    /// summary.txt and standard output.
    pub text: String,
    /// summary.json.
    pub json: serde_json::Map<String, serde_json::Value>,
}

impl Summary {
    /// One line of text.
    pub fn line(&mut self, l: impl AsRef<str>) {
        self.text += l.as_ref();
        self.text.push('\n');
    }
    /// One JSON value.
    pub fn set(&mut self, key: &str, v: serde_json::Value) {
        self.json.insert(key.to_string(), v);
    }
}

/// What the summary sections and plots read: the scene, the run and the analyses.
pub struct Ctx<'a> {
    /// The scene as run.
    pub scene: &'a Scene,
    /// Scene name (file stem).
    pub name: &'a str,
    /// The recorded run.
    pub series: &'a Run,
    /// The component after the run.
    pub comp: &'a raceway::Component,
    /// CPU time of the run, s.
    pub cpu_s: f64,
    /// Shaft frequency at the end, Hz.
    pub shaft_hz: f64,
    /// Index of the first sample analysed (the second half of the run).
    pub start: usize,
    /// Name and unit of the signal whose spectrum is analysed.
    pub signal: (&'static str, &'static str),
    /// Its amplitude spectrum over the analysed part.
    pub spec: Spectrum,
    /// The characteristic frequencies.
    pub marks: Vec<raceway::analysis::Mark>,
    /// The main lines and what became of them.
    pub found: Vec<FoundPeak>,
    /// Defect scenes: the envelope spectrum and its lines.
    pub envelope: Option<Envelope>,
}

/// The envelope spectrum, the band-pass before it (Hz; none: the whole signal) and the
/// lines found in it.
pub type Envelope = (Spectrum, Option<(f64, f64)>, Vec<FoundPeak>);

const MAIN: [&str; 7] = ["fs", "FTF", "BSF", "1xBPFO", "1xBPFI", "1x2BSF", "2xBPFO"];

impl<'a> Ctx<'a> {
    fn new(
        scene: &'a Scene,
        name: &'a str,
        series: &'a Run,
        comp: &'a raceway::Component,
        cpu_s: f64,
    ) -> Ctx<'a> {
        let col = |n: &str| series.column(n).unwrap_or(&[]);
        let omega = col("shaft.omega").last().copied().unwrap_or(0.0);
        let kin = kinematics(comp.bearing(), omega);
        let shaft_hz = omega / (2.0 * std::f64::consts::PI);
        // The signal whose spectrum tells the frequencies: ring motion when load-driven,
        // the force when motion-driven; over the second half of the run (past the start
        // transient).
        let signal = if scene.model.causality == Causality::Load {
            ("shaft.y", "m")
        } else {
            ("force.y", "N")
        };
        let n = series.t.len();
        let start = n / 2;
        let sig = &col(signal.0)[start.min(n)..];
        let dt = scene.run.duration_s / (n - 1).max(1) as f64;
        let spec = amplitude_spectrum(sig, 1.0 / dt, Window::Hann);
        let marks = characteristic_marks(&kin, shaft_hz, 3, 1);
        let main: Vec<_> = marks
            .iter()
            .filter(|m| MAIN.contains(&m.label.as_str()))
            .cloned()
            .collect();
        let tol = 2.0 * spec.resolution();
        let found = find_peaks(&spec, &main, tol);
        // Defects: the envelope spectrum (Randall & Antoni 2011, §4), band-passed above the
        // third multiple of the highest defect frequency (the impacts excite the band, the
        // envelope keeps their repetition rate) up to 0.8 of the Nyquist frequency.
        let envelope = (!scene.effects.defects.is_empty()).then(|| {
            let top = kin.bpfi.max(kin.bpfo).max(2.0 * kin.bsf);
            let nyq = 0.5 / dt;
            let band = (3.0 * top < 0.8 * nyq).then_some((3.0 * top, 0.8 * nyq));
            let env = envelope_spectrum(sig, 1.0 / dt, band);
            let lines: Vec<_> = marks
                .iter()
                .filter(|m| ["fs", "FTF", "1xBPFO", "1xBPFI", "1x2BSF"].contains(&m.label.as_str()))
                .cloned()
                .collect();
            let f = find_peaks(&env, &lines, 2.0 * env.resolution());
            (env, band, f)
        });
        Ctx {
            scene,
            name,
            series,
            comp,
            cpu_s,
            shaft_hz,
            start,
            signal,
            spec,
            marks,
            found,
            envelope,
        }
    }

    fn col(&self, n: &str) -> &[f64] {
        self.series.column(n).unwrap_or(&[])
    }

    fn peak(&self, n: &str) -> f64 {
        self.col(n).iter().fold(0.0f64, |m, v| m.max(v.abs()))
    }

    /// Whether the level integrates the cage (its slip is otherwise 0 by construction).
    fn cage_dynamics(&self) -> bool {
        matches!(self.scene.model.level.name(), "skidding" | "full")
    }

    /// The run length over the length analysed.
    fn record_scale(&self) -> f64 {
        let n = self.series.t.len().max(2);
        (n - 1) as f64 / (n - 1 - self.start.min(n - 2)) as f64
    }
}

fn scene_lines(c: &Ctx, s: &mut Summary) {
    let sc = c.scene;
    let b = c.comp.bearing();
    s.line(format!(
        "scene: {} ({}; level {}, {:?}-driven)",
        c.name,
        sc.title,
        sc.model.level.name(),
        sc.model.causality
    ));
    s.line(format!(
        "bearing: {}, d x D x B {:.3} x {:.3} x {:.3} mm; Z {} balls of Dw {:.3} mm on dm {:.3} mm; diametral clearance Pd {:.2} µm",
        b.name,
        b.bore * 1e3,
        b.outer_diameter * 1e3,
        b.width * 1e3,
        b.z,
        b.d * 1e3,
        b.dm * 1e3,
        b.pd * 1e6
    ));
    let n = c.series.t.len();
    let load = raceway::report::load_average();
    s.line(format!(
        "simulated {:.4} s in {} steps, {:.3} s of thread CPU ({:.2}x real time; load average {load})",
        sc.run.duration_s,
        n.saturating_sub(1),
        c.cpu_s,
        sc.run.duration_s / c.cpu_s.max(1e-9)
    ));
    s.set("scene", c.name.into());
    s.set("level", sc.model.level.name().into());
    s.set("duration_s", sc.run.duration_s.into());
    s.set("cpu_s", c.cpu_s.into());
    s.set("load_average", load.into());
    s.set(
        "bearing",
        serde_json::json!({"name": b.name, "bore_mm": b.bore * 1e3, "outside_diameter_mm": b.outer_diameter * 1e3,
            "width_mm": b.width * 1e3, "z": b.z, "ball_diameter_mm": b.d * 1e3, "pitch_diameter_mm": b.dm * 1e3,
            "diametral_clearance_um": b.pd * 1e6}),
    );
}

fn load_lines(c: &Ctx, s: &mut Summary) {
    let (fx, fy, fz) = (c.peak("force.x"), c.peak("force.y"), c.peak("force.z"));
    s.line(format!(
        "peak |force.x| {fx:.2} N, |force.y| {fy:.2} N, |force.z| {fz:.2} N"
    ));
    s.line(format!(
        "peak contact load {:.2} N, peak Hertz pressure {:.3} GPa",
        c.peak("contact.max_load"),
        c.peak("contact.max_pressure") * 1e-9
    ));
    s.set("peak_force_n", serde_json::json!([fx, fy, fz]));
    s.set("peak_contact_load_n", c.peak("contact.max_load").into());
    s.set("peak_pressure_pa", c.peak("contact.max_pressure").into());
}

fn cage_lines(c: &Ctx, s: &mut Summary) {
    let slip = c.col("cage.slip").last().copied().unwrap_or(0.0);
    if c.cage_dynamics() {
        s.line(format!("cage slip: final {slip:.4}"));
        s.set("final_cage_slip", slip.into());
    } else {
        s.line(format!(
            "cage slip: 0 by construction (the {} level runs the cage at its kinematic speed; the skidding and full levels integrate it)",
            c.scene.model.level.name()
        ));
        s.set("final_cage_slip", serde_json::Value::Null);
    }
    // Cage dynamics (the full level): whirl index over the second half of the run.
    if c.scene.model.level.name() != "full" {
        return;
    }
    let sigma = whirl_index(&c.col("cage.speed")[c.start.min(c.col("cage.speed").len())..]);
    let orbit_max = c
        .col("cage.x")
        .iter()
        .zip(c.col("cage.y"))
        .fold(0.0f64, |m, (x, y)| m.max(x.hypot(*y)));
    s.line(format!(
        "cage: whirl index sigma {} (second half), largest orbit {:.3} guide clearances, \
         peak pocket force {:.2} N, peak guide force {:.2} N, final speed ratio {:.4}",
        sigma.map_or("-".to_string(), |v| format!("{v:.4}")),
        orbit_max,
        c.peak("pocket.max_force"),
        c.peak("guide.force"),
        c.col("cage.speed_ratio").last().copied().unwrap_or(0.0)
    ));
    s.set("cage_whirl_sigma", serde_json::json!(sigma));
    s.set("cage_orbit_max", orbit_max.into());
    s.set("peak_pocket_force_n", c.peak("pocket.max_force").into());
    s.set("peak_guide_force_n", c.peak("guide.force").into());
}

/// ISO ratings, life, static safety and warnings at the run's mean load over the second
/// half (raceway::ratings).
fn rating_lines(c: &Ctx, s: &mut Summary) {
    let rating = raceway::ratings::assess_run(c.comp.bearing(), c.series, c.start);
    match &rating {
        Ok(a) => s.text += &format!("at the mean load of the second half:\n{}", a.text()),
        Err(e) => s.line(format!("ratings and life: not available ({e})")),
    }
    s.set(
        "rating",
        serde_json::to_value(rating.as_ref().ok()).unwrap_or_default(),
    );
    s.set(
        "warnings",
        rating
            .as_ref()
            .map(|a| a.warning_texts())
            .unwrap_or_default()
            .into(),
    );
}

/// The lines of one spectrum: expected, found (or why not), significance.
fn line_table(s: &mut Summary, found: &[FoundPeak], scale: f64) -> serde_json::Value {
    for p in found {
        let f = if p.is_found() {
            format!("{:.3}", p.found)
        } else {
            "-".to_string()
        };
        s.line(format!(
            "  {:<8} {:>10.3} Hz  {:>10} Hz  {}",
            p.label,
            p.expected,
            f,
            p.verdict_text(scale)
        ));
    }
    let finite = |v: f64| v.is_finite().then_some(v);
    serde_json::Value::Array(
        found
            .iter()
            .map(|p| {
                let (verdict, needs) = match p.verdict {
                    Verdict::Found => ("found", None),
                    Verdict::BelowFloor => ("below floor", None),
                    Verdict::Unresolved { needs_s } => ("not resolved", finite(needs_s * scale)),
                };
                serde_json::json!({"label": p.label, "expected_hz": p.expected,
                    "found_hz": if p.is_found() { finite(p.found) } else { None },
                    "over_floor": finite(p.over_floor), "verdict": verdict, "needs_duration_s": needs})
            })
            .collect(),
    )
}

fn frequency_lines(c: &Ctx, s: &mut Summary) {
    let scale = c.record_scale();
    s.line(format!(
        "shaft {:.2} Hz; characteristic frequencies in the {} spectrum ({}, second half of the run: {:.4} s, bins {:.3} Hz); \
         found = a peak within ±2 bins at least {FOUND_OVER_FLOOR} x the median floor in [f/2, 2f]:",
        c.shaft_hz,
        c.signal.0,
        c.signal.1,
        1.0 / c.spec.resolution().max(1e-300),
        c.spec.resolution()
    ));
    s.line(format!(
        "  {:<8} {:>13}  {:>13}",
        "line", "expected", "found"
    ));
    let v = line_table(s, &c.found, scale);
    s.set("frequencies", v);
    if let Some((env, band, found)) = &c.envelope {
        s.line(format!(
            "envelope spectrum of {} (defect scene; band {}):",
            c.signal.0,
            band.map_or("whole signal".to_string(), |(lo, hi)| format!(
                "{lo:.0}-{hi:.0} Hz"
            ))
        ));
        let _ = env;
        let v = line_table(s, found, scale);
        s.set("envelope_frequencies", v);
    }
}

/// Write the plots; returns their file names.
fn write_plots(out: &Path, c: &Ctx) -> Result<Vec<String>> {
    let scene = c.scene;
    let series = c.series;
    let col = |n: &str| c.col(n)[c.start.min(c.col(n).len())..].to_vec();
    let all = |n: &str| c.col(n).to_vec();
    let micro = |v: Vec<f64>| v.into_iter().map(|x| x * 1e6).collect::<Vec<_>>();
    let t = &series.t;
    let t_half = series.t.get(c.start).copied().unwrap_or(0.0);
    let mut written = Vec::new();
    // Orbit over the second half: the start transient (release from the initial state,
    // run-up) is left out, as in the spectrum.
    let (ox, oy, lx, ly, what) = if scene.model.causality == Causality::Load {
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
    let title = format!("{what}, t >= {t_half:.3} s (start transient left out)");
    plot(
        &out.join("orbit.png"),
        &Axes {
            title: &title,
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
    written.push("orbit.png".to_string());
    let f = [all("force.x"), all("force.y"), all("force.z")];
    let panels: Vec<(Axes, Vec<Series>)> = ["Fx (N)", "Fy (N)", "Fz (N)"]
        .iter()
        .zip(&f)
        .enumerate()
        .map(|(k, (l, y))| {
            (
                Axes {
                    x_label: if k == 2 { "t (s)" } else { "" },
                    y_label: l,
                    ..Axes::default()
                },
                vec![Series {
                    label: "",
                    x: t,
                    y,
                    points: false,
                }],
            )
        })
        .collect();
    plot_stack(
        &out.join("force.png"),
        "force of the bearing on the shaft",
        &panels,
    )?;
    written.push("force.png".to_string());
    spectrum_plot(out, "spectrum.png", c, &c.spec, "spectrum", &mut written)?;
    if let Some((env, _, _)) = &c.envelope {
        spectrum_plot(
            out,
            "envelope.png",
            c,
            env,
            "envelope spectrum",
            &mut written,
        )?;
    }
    ball_loads_plot(out, c)?;
    written.push("ball-loads.png".to_string());
    if c.cage_dynamics() {
        let slip = all("cage.slip");
        plot(
            &out.join("cage-slip.png"),
            &Axes {
                title: "cage slip",
                x_label: "t (s)",
                y_label: "1 - omega_c / omega_c,kin (-)",
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
        written.push("cage-slip.png".to_string());
    }
    if scene.model.level.name() == "full" {
        write_cage_plots(out, series)?;
        written.push("cage-orbit.png".to_string());
        written.push("speeds.png".to_string());
    }
    Ok(written)
}

fn spectrum_plot(
    out: &Path,
    file: &str,
    c: &Ctx,
    spec: &Spectrum,
    what: &str,
    written: &mut Vec<String>,
) -> Result<()> {
    let fmax = c
        .marks
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
    let mk: Vec<Marker> = c
        .marks
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
    let ylab = format!("amplitude of {} ({})", c.signal.0, c.signal.1);
    let title = format!(
        "{what} of {}, t >= {:.3} s (Hann window, bins {:.2} Hz)",
        c.signal.0,
        c.series.t.get(c.start).copied().unwrap_or(0.0),
        spec.resolution()
    );
    plot(
        &out.join(file),
        &Axes {
            title: &title,
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
    written.push(file.to_string());
    Ok(())
}

/// Ball loads around the circumference at the end of the run: the level's own loads when
/// it resolves the balls (skidding, full), else the Jones–Harris equilibrium at the final motion
/// and speed with the balls at their reference azimuths (the quasi-static, ring and linear
/// levels' ball model).
fn ball_loads_plot(out: &Path, c: &Ctx) -> Result<()> {
    let b = c.comp.bearing();
    let level = c.scene.model.level.name();
    let (deg, qi, qo, title) = if let Some(l) = c.comp.ball_loads() {
        let mut l: Vec<(f64, f64, f64)> = l
            .into_iter()
            .map(|(p, i, o)| (p.to_degrees().rem_euclid(360.0), i, o))
            .collect();
        l.sort_by(|a, b| a.0.total_cmp(&b.0));
        (
            l.iter().map(|v| v.0).collect::<Vec<_>>(),
            l.iter().map(|v| v.1).collect::<Vec<_>>(),
            l.iter().map(|v| v.2).collect::<Vec<_>>(),
            format!("ball loads of the {level} model at the end of the run"),
        )
    } else {
        let q: [f64; 5] = std::array::from_fn(|k| {
            c.col(["shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry"][k])
                .last()
                .copied()
                .unwrap_or(0.0)
        });
        let omega = c.col("shaft.omega").last().copied().unwrap_or(0.0);
        let qs = QuasiStatic::new(
            b,
            Options {
                race_control: c.scene.model.race_control,
                ..Options::default()
            },
        )?;
        let psi = azimuths(b.z, 0.0);
        let mut st = vec![BallState::default(); b.z];
        let mut res = vec![BallResult::default(); b.z];
        qs.evaluate(&q, omega, &psi, &mut st, None, Some(&mut res))?;
        let title = "ball loads around the circumference (Jones–Harris, final motion)".to_string();
        (
            psi.iter().map(|p| p.to_degrees()).collect(),
            res.iter().map(|r| r.q_i).collect(),
            res.iter().map(|r| r.q_o).collect(),
            title,
        )
    };
    plot(
        &out.join("ball-loads.png"),
        &Axes {
            title: &title,
            x_label: "azimuth (deg)",
            y_label: "contact load (N)",
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
    )
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
