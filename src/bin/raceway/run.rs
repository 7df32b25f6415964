//! `raceway run [scene.toml] [--out DIR] [--quiet]`: run a scene stand-alone, write the time
//! series, a summary, plots (PNG and SVG) and report.html.

use raceway::analysis::{find_peaks, FoundPeak, Mark, Spectrum, LINE_TOLERANCE};
use raceway::component::scene::DEFAULT_SCENE;
use raceway::component::{schema, Causality, Scene};
use raceway::geometry::element::ElementKind;
use raceway::models::quasi_static::{azimuths, BallResult, BallState, Options, QuasiStatic};
use raceway::plot::{plot_pair_dpi, stack_pair_dpi, Axes, Marker, Series, DPI_RANGE};
use raceway::runner::{self, Record, Series as Run};
use raceway::summary::html::{report_html, Figure, Provenance};
use raceway::summary::{summary_of, Ctx};
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
    /// Integrate the whole duration straight through (the integrator takes its own steps;
    /// the series at every step_s from its dense output) instead of stopping at every
    /// step_s. Holds the start's inputs: refused for a speed ramp, orbit or rotating load,
    /// and for levels with memory updated at each point (warm starts, wear, thermal).
    #[arg(long)]
    pub through: bool,
    /// Open report.html when the run is done (xdg-open; without it, the path is printed).
    #[arg(long)]
    pub open: bool,
    /// The spectrum plot as displacement (m), velocity (m/s: amplitude x 2 pi f) or
    /// acceleration (m/s²: amplitude x (2 pi f)²). Load-driven scenes only (their spectrum
    /// is the ring's displacement); the summary's lines and the envelope spectrum stay in
    /// the signal's own unit.
    #[arg(long, value_enum)]
    pub spectrum_unit: Option<SpectrumUnit>,
    /// Resolution of the PNG plots, dots per inch (50 to 400; 100 draws 1000 px wide; the
    /// SVGs are the same at any dpi).
    #[arg(long, default_value_t = raceway::plot::DEFAULT_DPI)]
    pub dpi: u32,
}

/// The quantity of the spectrum plot (`--spectrum-unit`).
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpectrumUnit {
    /// The ring displacement, m.
    #[default]
    Displacement,
    /// Its velocity, m/s.
    Velocity,
    /// Its acceleration, m/s².
    Acceleration,
}

impl SpectrumUnit {
    /// Time derivatives of the displacement, the quantity's name and unit.
    fn of(self) -> (u32, &'static str, &'static str) {
        match self {
            SpectrumUnit::Displacement => (0, "displacement", "m"),
            SpectrumUnit::Velocity => (1, "velocity", "m/s"),
            SpectrumUnit::Acceleration => (2, "acceleration", "m/s²"),
        }
    }
}

/// How the plots are drawn: the spectrum's quantity and the PNGs' resolution.
struct Look {
    unit: SpectrumUnit,
    dpi: u32,
}

/// The options of the plots checked before the run: a refused run writes nothing.
fn check_look(a: &RunArgs, scene: &Scene) -> Result<Look> {
    if !DPI_RANGE.contains(&a.dpi) {
        return Err(Error::invalid(
            "--dpi",
            a.dpi,
            format!("{} to {}", DPI_RANGE.start(), DPI_RANGE.end()),
        ));
    }
    let (signal, unit) = raceway::summary::signal_of(scene);
    if let Some(u) = a.spectrum_unit {
        // A motion-driven scene's spectrum is of the force on the shaft: a force has no
        // velocity or acceleration, and its time derivatives (N/s, N/s²) are not what the
        // flag promises, so the flag is refused rather than given another meaning.
        if unit != "m" {
            return Err(Error::invalid(
                "--spectrum-unit",
                u.of().1,
                format!(
                    "only for load-driven scenes, whose spectrum is the ring displacement \
                     (m); this scene is motion-driven and its spectrum is of the force \
                     {signal} ({unit}): leave --spectrum-unit out"
                ),
            ));
        }
    }
    Ok(Look {
        unit: a.spectrum_unit.unwrap_or_default(),
        dpi: a.dpi,
    })
}

/// Set by SIGINT or SIGTERM: the run stops before its next step and its staged folder is
/// removed (the previous output folder is left as it was); a sweep abandons the points
/// running and keeps the rows it finished.
pub(crate) static STOP: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

extern "C" fn on_signal(_: libc::c_int) {
    STOP.store(true, std::sync::atomic::Ordering::Relaxed);
}

/// Ctrl-C and SIGTERM ask the run to stop instead of killing the process mid-write.
pub(crate) fn catch_stop_signals() {
    let handler = on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
    // SAFETY: the handler only stores to an atomic, which is async-signal-safe.
    unsafe {
        libc::signal(libc::SIGINT, handler);
        libc::signal(libc::SIGTERM, handler);
    }
}

fn io(path: &Path, e: std::io::Error) -> Error {
    Error::Io(format!("cannot write `{}`: {e}", path.display()))
}

/// Run and report; returns the text for standard output.
pub fn run(a: RunArgs) -> Result<String> {
    catch_stop_signals();
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
    let look = check_look(&a, &scene)?;
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out").join(&name));
    // The run is written into a fresh hidden sibling folder and moved into place only when
    // complete: a failed, killed or interrupted run never leaves a folder that mixes its
    // files with a previous run's (the previous folder stays as it was; an interrupted
    // run is the `.<name>.partial-<pid>` folder, removed by the next run into `out`).
    let staging = Staging::new(&out)?;
    match write_run(&a, &look, &scene, &name, &staging.dir, &out) {
        Ok(mut text) => {
            staging.publish()?;
            if a.open {
                text += &open_report(&out.join("report.html"));
            }
            Ok(text)
        }
        Err(e) => {
            staging.discard();
            Err(e)
        }
    }
}

/// A run's output folder while it is written.
struct Staging {
    /// Where the run writes.
    dir: PathBuf,
    /// Where it goes when complete.
    out: PathBuf,
}

impl Staging {
    fn new(out: &Path) -> Result<Staging> {
        let parent = out
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        std::fs::create_dir_all(parent).map_err(|e| io(parent, e))?;
        let base = out
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "out".into());
        // Earlier interrupted runs into the same folder.
        let prefix = format!(".{base}.partial-");
        if let Ok(entries) = std::fs::read_dir(parent) {
            for e in entries.flatten() {
                if e.file_name().to_string_lossy().starts_with(&prefix) {
                    let _ = std::fs::remove_dir_all(e.path());
                }
            }
        }
        let dir = parent.join(format!("{prefix}{}", std::process::id()));
        std::fs::create_dir_all(&dir).map_err(|e| io(&dir, e))?;
        Ok(Staging {
            dir,
            out: out.to_path_buf(),
        })
    }

    /// Move the complete run into place, replacing the previous one as a whole.
    fn publish(&self) -> Result<()> {
        let old = self.dir.with_file_name(
            self.dir
                .file_name()
                .unwrap()
                .to_string_lossy()
                .replace(".partial-", ".replaced-"),
        );
        if self.out.exists() {
            std::fs::rename(&self.out, &old).map_err(|e| io(&self.out, e))?;
        }
        std::fs::rename(&self.dir, &self.out).map_err(|e| io(&self.out, e))?;
        let _ = std::fs::remove_dir_all(&old);
        Ok(())
    }

    fn discard(&self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Run the scene and write everything into `out` (the staging folder); the text for
/// standard output names `shown`, where the folder goes when complete.
fn write_run(
    a: &RunArgs,
    look: &Look,
    scene: &Scene,
    name: &str,
    out: &Path,
    shown: &Path,
) -> Result<String> {
    let out = out.to_path_buf();
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
    // series.csv is written while the run goes (into the staging folder); only the
    // run's digest stays in memory, bounded whatever the duration (docs/reliability.md).
    let mut csv = runner::CsvSink::create(&out.join("series.csv"))?;
    let mut digest = raceway::summary::digest_for(scene);
    // The elements' loads of the run itself, for the ball-load plot.
    let mut loads = runner::LoadRecord::for_scene(scene);
    let comp = runner::run_into_with_loads(
        scene,
        Record {
            stiffness_damping: a.kc,
        },
        a.through,
        &mut progress,
        &mut || STOP.load(std::sync::atomic::Ordering::Relaxed),
        &mut runner::Tee(&mut csv, &mut digest),
        &mut loads,
    )?;
    csv.finish()?;
    if bar_on {
        eprintln!();
    }
    let cpu = raceway::report::thread_cpu_s() - cpu0;

    let ctx = Ctx::new(scene, name, &digest, &comp, cpu);
    let sm = summary_of(&ctx);
    let summary = out.join("summary.txt");
    raceway::fsutil::write_atomic(&summary, &sm.text).map_err(|e| io(&summary, e))?;
    let sj = out.join("summary.json");
    raceway::fsutil::write_atomic(
        &sj,
        serde_json::to_string_pretty(&sm.json).unwrap_or_default(),
    )
    .map_err(|e| io(&sj, e))?;

    let (pngs, skipped) = write_plots(&out, &ctx, look, &loads);
    for w in &skipped {
        eprintln!("warning: {w}");
    }
    let figures: Vec<Figure> = pngs
        .iter()
        .filter_map(|f| {
            let svg = std::fs::read_to_string(out.join(f).with_extension("svg")).ok()?;
            Some(Figure {
                file: f.clone(),
                svg,
            })
        })
        .collect();
    let prov = Provenance {
        version: env!("CARGO_PKG_VERSION").to_string(),
        command: command_line(),
        scene_file: a
            .scene
            .as_ref()
            .map_or("default (embedded)".into(), |p| p.display().to_string()),
    };
    let page = out.join("report.html");
    raceway::fsutil::write_atomic(&page, report_html(&ctx, &sm, &figures, &prov))
        .map_err(|e| io(&page, e))?;
    if quiet {
        return Ok(String::new());
    }
    let mut s = sm.text;
    writeln!(
        s,
        "results in {}/ (report.html, series.csv{}, summary.txt, summary.json, {} and SVGs)",
        shown.display(),
        if a.kc { " with K and C" } else { "" },
        pngs.join(", ")
    )
    .ok();
    Ok(s)
}

/// The command line as typed (arguments with spaces or quotes in single quotes).
fn command_line() -> String {
    std::env::args()
        .map(|a| {
            if a.is_empty() || a.contains(|c: char| c.is_whitespace() || "'\"$\\".contains(c)) {
                format!("'{}'", a.replace('\'', "'\\''"))
            } else {
                a
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// `--open`: hand the page to the desktop's opener, or say where it is.
fn open_report(page: &Path) -> String {
    let opened = std::process::Command::new("xdg-open")
        .arg(page)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if opened {
        format!("opened {}\n", page.display())
    } else {
        format!(
            "report: {} (xdg-open could not open it: open it in a browser)\n",
            page.display()
        )
    }
}

/// Record a plot: written, or skipped with its reason.
fn keep(name: &str, made: Result<()>, written: &mut Vec<String>, skipped: &mut Vec<String>) {
    match made {
        Ok(()) => written.push(name.to_string()),
        Err(e) => skipped.push(format!("{name} skipped: {e}")),
    }
}

/// Write the plots; returns the file names written and, for each plot that could not be
/// made, a warning naming it and why. A plot is an optional product: it never fails a run
/// whose integration finished and whose series and summaries are written.
fn write_plots(
    out: &Path,
    c: &Ctx,
    look: &Look,
    loads: &runner::LoadRecord,
) -> (Vec<String>, Vec<String>) {
    let plot = |p: &Path, axes: &Axes<'_>, series: &[Series<'_>], markers: &[Marker]| {
        plot_pair_dpi(p, look.dpi, axes, series, markers)
    };
    let plot_stack = |p: &Path, title: &str, panels: &[(Axes<'_>, Vec<Series<'_>>)]| {
        stack_pair_dpi(p, look.dpi, title, panels)
    };
    let scene = c.scene;
    let series = c.series;
    let col = |n: &str| c.col(n)[c.start.min(c.col(n).len())..].to_vec();
    let all = |n: &str| c.col(n).to_vec();
    let micro = |v: Vec<f64>| v.into_iter().map(|x| x * 1e6).collect::<Vec<_>>();
    let t = &series.t;
    let t_half = series.t.get(c.start).copied().unwrap_or(0.0);
    let mut written = Vec::new();
    let mut skipped = Vec::new();

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
    let title = headed(c, &format!("{what}, t >= {t_half:.3} s"));
    let made = plot(
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
    );
    keep("orbit.png", made, &mut written, &mut skipped);
    // Only the force components the level has (no Fz panel on 2-DOF scenes).
    // (axis label, output, history column)
    let f: Vec<(&str, &str, Vec<f64>)> = FORCE_PANELS
        .into_iter()
        .map(|(l, n)| (l, n, all(n)))
        .filter(|(_, _, v)| v.iter().any(|x| *x != 0.0))
        .collect();
    let panels = time_panels(t, f.iter().map(|(l, _, y)| (*l, y.as_slice())), 0);
    let made = plot_stack(
        &out.join("force.png"),
        &headed(
            c,
            &format!("force of the bearing on the shaft{}", undersampled(c)),
        ),
        &panels,
    );
    keep("force.png", made, &mut written, &mut skipped);
    // A long history is a solid band: beside it, the last few ball passes.
    if let Some((t0, t1, what)) = zoom_window(c) {
        // The window from the run's full-rate tail when the history skips rows.
        let src = zoom_source(c, t0);
        let i0 = src.t.partition_point(|&v| v < t0);
        let cols = f
            .iter()
            .map(|(l, n, y)| (*l, src.column(n).unwrap_or(y.as_slice())));
        let zp = time_panels(&src.t, cols, i0);
        let made = plot_stack(
            &out.join("force-zoom.png"),
            &headed(
                c,
                &format!("force on the shaft, {what}: t = {t0:.4} to {t1:.4} s"),
            ),
            &zp,
        );
        keep("force-zoom.png", made, &mut written, &mut skipped);
    }
    let made = spectrum_plot(
        out,
        look,
        "spectrum.png",
        c,
        &c.spec,
        "spectrum",
        &mut written,
    );
    if let Err(e) = made {
        skipped.push(format!("spectrum.png skipped: {e}"));
    }
    if let Some((env, _, _)) = &c.envelope {
        let made = spectrum_plot(
            out,
            look,
            "envelope.png",
            c,
            env,
            "envelope spectrum",
            &mut written,
        );
        if let Err(e) = made {
            skipped.push(format!("envelope.png skipped: {e}"));
        }
    }
    keep(
        "ball-loads.png",
        ball_loads_plot(out, look.dpi, c, loads),
        &mut written,
        &mut skipped,
    );
    if c.cage_dynamics() {
        // Per cent of the kinematic cage speed: the slip's size reads off the axis.
        let slip: Vec<f64> = all("cage.slip").into_iter().map(|v| 100.0 * v).collect();
        let made = plot(
            &out.join("cage-slip.png"),
            &Axes {
                title: &headed(c, "cage slip"),
                x_label: "t (s)",
                y_label: "cage slip 1 - ωc/ωc,kin (%)",
                ..Axes::default()
            },
            &[Series {
                label: "",
                x: t,
                y: &slip,
                points: false,
            }],
            &[],
        );
        keep("cage-slip.png", made, &mut written, &mut skipped);
        if let Some((t0, t1, what)) = zoom_window(c) {
            let src = zoom_source(c, t0);
            let (t, slip) = match src.column("cage.slip") {
                Some(s) => (&src.t, s.iter().map(|v| 100.0 * v).collect::<Vec<f64>>()),
                None => (t, slip.clone()),
            };
            let i0 = t.partition_point(|&v| v < t0).min(slip.len());
            let made = plot(
                &out.join("cage-slip-zoom.png"),
                &Axes {
                    title: &headed(c, &format!("cage slip, {what}: t = {t0:.4} to {t1:.4} s")),
                    x_label: "t (s)",
                    y_label: "cage slip 1 - ωc/ωc,kin (%)",
                    ..Axes::default()
                },
                &[Series {
                    label: "",
                    x: &t[i0..],
                    y: &slip[i0..],
                    points: false,
                }],
                &[],
            );
            keep("cage-slip-zoom.png", made, &mut written, &mut skipped);
        }
    }
    if scene.model.level.name() == "full" {
        match write_cage_plots(out, look.dpi, series, &headed(c, "")) {
            Ok(()) => {
                written.push("cage-orbit.png".to_string());
                written.push("speeds.png".to_string());
            }
            Err(e) => skipped.push(format!("cage-orbit.png and speeds.png skipped: {e}")),
        }
    }
    (written, skipped)
}

/// A note for a history whose output step is too coarse for the ball passes: `" (output
/// every 1 ms: ball passes at 685.5 Hz, above its Nyquist 500.0 Hz, alias)"`; empty
/// otherwise.
fn undersampled(c: &Ctx) -> String {
    let Some(bpfo) = c.marks.iter().find(|m| m.label == "1xBPFO").map(|m| m.freq) else {
        return String::new();
    };
    let dt = c.scene.run.duration_s / c.run.rows.saturating_sub(1).max(1) as f64;
    let nyquist = 0.5 / dt;
    if bpfo > nyquist {
        format!(
            " (output every {:.3} ms: ball passes at {bpfo:.1} Hz, above its Nyquist {nyquist:.1} Hz, alias)",
            1e3 * dt
        )
    } else {
        String::new()
    }
}

/// Highest harmonic marked on a spectrum plot.
const TOP_HARMONIC: usize = 5;

/// The harmonics (2x to [`TOP_HARMONIC`]x) of the table's found lines BPFO, BPFI and 2BSF
/// that are themselves found in `spec` by the summary's rule ([`find_peaks`] at
/// [`LINE_TOLERANCE`], searched together with the table's lines, so that a harmonic
/// closer than the resolution to another line is not resolved and not marked). Absent
/// harmonics are left unmarked; the table's own lines keep their marks ("?" when absent).
fn present_harmonics(spec: &Spectrum, lines: &[FoundPeak]) -> Vec<FoundPeak> {
    let has = |l: &str| lines.iter().any(|p| p.label == l);
    let mut marks: Vec<Mark> = lines
        .iter()
        .map(|p| Mark {
            label: p.label.clone(),
            freq: p.expected,
        })
        .collect();
    let n0 = marks.len();
    for p in lines.iter().filter(|p| p.is_found()) {
        let Some(name) = p.label.strip_prefix("1x") else {
            continue;
        };
        if !["BPFO", "BPFI", "2BSF"].contains(&name) {
            continue;
        }
        for h in 2..=TOP_HARMONIC {
            let label = format!("{h}x{name}");
            if !has(&label) {
                marks.push(Mark {
                    label,
                    freq: h as f64 * p.expected,
                });
            }
        }
    }
    find_peaks(spec, &marks, LINE_TOLERANCE)
        .into_iter()
        .skip(n0)
        .filter(|p| p.is_found())
        .collect()
}

/// Number of outer-race ball passes in the zoomed window of a history.
const ZOOM_PASSES: f64 = 5.0;

/// The zoomed window of a long history: the last [`ZOOM_PASSES`] ball passes over the
/// outer race (`ZOOM_PASSES / BPFO` seconds) at the end of the run, with its name; none
/// when the bearing does not turn or the run is not 4 windows long (the whole history
/// then shows them already).
/// Stacked panels of columns against time `t` from row `i0` on, the time label on the last.
fn time_panels<'a>(
    t: &'a [f64],
    cols: impl Iterator<Item = (&'a str, &'a [f64])>,
    i0: usize,
) -> Vec<(Axes<'a>, Vec<Series<'a>>)> {
    let mut panels: Vec<(Axes, Vec<Series>)> = cols
        .map(|(l, y)| {
            (
                Axes {
                    y_label: l,
                    ..Axes::default()
                },
                vec![Series {
                    label: "",
                    x: &t[i0.min(t.len())..],
                    y: &y[i0.min(y.len())..],
                    points: false,
                }],
            )
        })
        .collect();
    if let Some(p) = panels.last_mut() {
        p.0.x_label = "t (s)";
    }
    panels
}

/// The force panels: axis label and output.
const FORCE_PANELS: [(&str, &str); 3] = [
    ("Fx (N)", "force.x"),
    ("Fy (N)", "force.y"),
    ("Fz (N)", "force.z"),
];

/// Where a zoom from `t0` reads its rows: the run's full-rate tail when the history skips
/// rows and the tail reaches back to `t0`, else the history (every row).
fn zoom_source<'a>(c: &'a Ctx, t0: f64) -> &'a raceway::runner::Series {
    match c.run.tail.t.first() {
        Some(&first) if first <= t0 => &c.run.tail,
        _ => c.series,
    }
}

/// Rows per ball pass below which a zoom is not drawn: the output step does not resolve
/// a pass (a line through a handful of samples would pass for its shape).
const ZOOM_MIN_ROWS_PER_PASS: f64 = 8.0;

fn zoom_window(c: &Ctx) -> Option<(f64, f64, String)> {
    let bpfo = c.marks.iter().find(|m| m.label == "1xBPFO")?.freq;
    let (&ts, &te) = (c.series.t.first()?, c.series.t.last()?);
    let w = ZOOM_PASSES / bpfo;
    let rows_per_pass = (c.run.rows.saturating_sub(1)) as f64 / (te - ts).max(1e-300) / bpfo;
    (bpfo.is_finite()
        && bpfo > 0.0
        && 4.0 * w <= te - ts
        && rows_per_pass >= ZOOM_MIN_ROWS_PER_PASS)
        .then(|| {
            (
                te - w,
                te,
                format!(
                    "last {ZOOM_PASSES} {} passes ({ZOOM_PASSES}/BPFO = {:.1} ms)",
                    c.comp.bearing().element(),
                    1e3 * w
                ),
            )
        })
}

fn spectrum_plot(
    out: &Path,
    look: &Look,
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
    // The spectrum (not the envelope spectrum: the envelope of a displacement is not a
    // derivative's envelope) in the quantity asked for.
    let envelope = file == "envelope.png";
    let (n, quantity, unit) = if envelope {
        (0, "", c.signal.1)
    } else {
        look.unit.of()
    };
    let shown = spec.derivative(n);
    let sf: Vec<f64> = keep.iter().map(|&i| shown.freq[i]).collect();
    let sa: Vec<f64> = keep.iter().map(|&i| shown.amp[i].max(1e-30)).collect();
    // The lines this spectrum's summary table reports: a found line is marked with its
    // label, one that is not with "?" (the summary says why); then the harmonics up to 5x
    // of the found lines, only those present.
    let lines = match &c.envelope {
        Some((_, _, f)) if envelope => f,
        _ => &c.found,
    };
    // Lines past the drawn range (above the Nyquist frequency, or the plot's cut) are left
    // unmarked: a mark there points at nothing drawn (the summary says why).
    let top = sf.last().copied().unwrap_or(0.0);
    let mut mk: Vec<Marker> = lines
        .iter()
        .filter(|p| p.expected <= top)
        .map(|p| Marker {
            x: if p.is_found() { p.found } else { p.expected },
            label: format!(
                "{}{}",
                p.label.trim_start_matches("1x"),
                if p.is_found() { "" } else { "?" }
            ),
        })
        .collect();
    mk.extend(
        present_harmonics(spec, lines)
            .into_iter()
            .filter(|p| p.found <= top)
            .map(|p| Marker {
                x: p.found,
                label: p.label,
            }),
    );
    let (ylab, of) = match n {
        0 => (
            // The signal's own unit (N for a force): no conversion.
            format!("amplitude of {} ({})", c.signal.0, c.signal.1),
            c.signal.0.to_string(),
        ),
        _ => (
            format!("{quantity} amplitude ({unit})"),
            format!(
                "{} as {quantity} (amplitude x {})",
                c.signal.0,
                if n == 1 { "2πf" } else { "(2πf)²" }
            ),
        ),
    };
    // A speed that changes over the analysed part smears every line: say so, and at
    // which speed the marks stand.
    let rpm = |w: f64| w * 60.0 / std::f64::consts::TAU;
    let w = &c.col("shaft.omega")[c.start.min(c.col("shaft.omega").len())..];
    let sweep = match (w.first(), w.last()) {
        (Some(&a), Some(&b)) if (b - a).abs() > 0.01 * a.abs().max(b.abs()) => format!(
            "; shaft {:.0} to {:.0} rpm over it, marks at the final speed",
            rpm(a),
            rpm(b)
        ),
        _ => String::new(),
    };
    let title = headed(
        c,
        &format!(
            "{what} of {of}, t >= {:.3} s (Hann, bins {:.2} Hz{sweep}){}",
            c.series.t.get(c.start).copied().unwrap_or(0.0),
            spec.resolution(),
            undersampled(c)
        ),
    );
    plot_pair_dpi(
        &out.join(file),
        look.dpi,
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

/// The elements' loads around the circumference: the run's own when the level resolves its
/// elements ([`runner::LoadRecord`]: the loads at the last step, and their largest and
/// smallest per degree of azimuth over the last shaft revolution), else (the linear level,
/// a set, a run straight through) the Jones–Harris equilibrium at the final motion and
/// speed with the balls at their reference azimuths, titled as that recomputation.
fn ball_loads_plot(out: &Path, dpi: u32, c: &Ctx, loads: &runner::LoadRecord) -> Result<()> {
    let b = c.comp.bearing();
    let element = b.element();
    let level = c.scene.model.level.name();
    // The elements travel with the cage, the way the shaft turns.
    let omega = c.col("shaft.omega").last().copied().unwrap_or(0.0);
    let x_label = format!(
        "azimuth ψ from +x toward +y (deg; 270 = -y){}",
        if omega > 0.0 {
            "; elements travel toward +ψ"
        } else if omega < 0.0 {
            "; elements travel toward -ψ"
        } else {
            ""
        }
    );
    let x_label = x_label.as_str();
    let y_label = if element == ElementKind::Ball {
        "ball contact load (N)".to_string()
    } else {
        format!("{element} contact load, sum over its laminae (N)")
    };
    if !loads.available {
        return recomputed_loads_plot(out, dpi, c, x_label, &y_label);
    }
    let deg = |psi: f64| psi.to_degrees().rem_euclid(360.0);
    let mut last: Vec<(f64, f64, f64)> = loads
        .last
        .iter()
        .map(|l| (deg(l.psi), l.inner, l.outer))
        .collect();
    last.sort_by(|a, b| a.0.total_cmp(&b.0));
    let x: Vec<f64> = last.iter().map(|v| v.0).collect();
    let qi: Vec<f64> = last.iter().map(|v| v.1).collect();
    let qo: Vec<f64> = last.iter().map(|v| v.2).collect();
    // Massless elements (ring levels) carry the same load at both contacts: one set of
    // points. The outer contact's envelope is drawn apart from the inner one's only where
    // they would not draw as one line (2 % of the loads' span apart: an element's inertia
    // at speed).
    let one = loads.last.iter().all(|l| l.inner == l.outer);
    let extreme = |v: &[f64], f: fn(f64, f64) -> f64| v.iter().copied().fold(f64::NAN, f);
    let span = extreme(&loads.outer.max, f64::max).max(extreme(&loads.inner.max, f64::max))
        - extreme(&loads.outer.min, f64::min).min(extreme(&loads.inner.min, f64::min));
    let apart = loads
        .inner
        .max
        .iter()
        .zip(&loads.outer.max)
        .chain(loads.inner.min.iter().zip(&loads.outer.min))
        .any(|(a, b)| (a - b).abs() > 0.02 * span);
    // The envelope at the centres of the bins an element passed through.
    let env = |v: &[f64]| -> (Vec<f64>, Vec<f64>) {
        v.iter()
            .enumerate()
            .filter(|(_, q)| q.is_finite())
            .map(|(k, q)| (runner::LoadRecord::bin_centre_deg(k), *q))
            .unzip()
    };
    let (ix, imax) = env(&loads.inner.max);
    let (_, imin) = env(&loads.inner.min);
    let (ox, omax) = env(&loads.outer.max);
    let (_, omin) = env(&loads.outer.min);
    let (w0, w1) = loads.window;
    let window = if loads.last_revolution {
        "the last shaft revolution"
    } else {
        "the whole run"
    };
    // The quasi-static level's own loads are its elements' Jones–Harris equilibria.
    let what = if level == "quasi_static" && element == ElementKind::Ball {
        " (each ball's Jones–Harris equilibrium)"
    } else {
        ""
    };
    let title = headed(
        c,
        &format!(
            "{element} loads of the {level} level{what}; max/min per {}° over {window} \
             (t = {w0:.3} to {w1:.3} s)",
            runner::BIN_DEG
        ),
    );
    let line = |label, x, y| Series {
        label,
        x,
        y,
        points: false,
    };
    let dots = |label, x, y| Series {
        label,
        x,
        y,
        points: true,
    };
    let at = format!("at t = {:.4} s", loads.t_last);
    let (l_i, l_o) = (format!("inner {at}"), format!("outer {at}"));
    let l_one = format!("each {element} {at}");
    let mut series: Vec<Series<'_>> = if apart {
        vec![
            line("inner, max", &ix, &imax),
            line("inner, min", &ix, &imin),
            line("outer, max", &ox, &omax),
            line("outer, min", &ox, &omin),
        ]
    } else {
        let (hi, lo) = if one {
            ("max", "min")
        } else {
            ("max (inner contact)", "min (inner contact)")
        };
        vec![line(hi, &ix, &imax), line(lo, &ix, &imin)]
    };
    if one {
        series.push(dots(&l_one, &x, &qi));
    } else {
        series.push(dots(&l_i, &x, &qi));
        series.push(dots(&l_o, &x, &qo));
    }
    plot_pair_dpi(
        &out.join("ball-loads.png"),
        dpi,
        &Axes {
            title: &title,
            x_label,
            y_label: &y_label,
            ..Axes::default()
        },
        &series,
        &[],
    )
}

/// The ball-load plot of a run that kept no element loads: the Jones–Harris equilibrium at
/// the final motion and speed, balls at their reference azimuths (ball bearings only).
fn recomputed_loads_plot(
    out: &Path,
    dpi: u32,
    c: &Ctx,
    x_label: &str,
    y_label: &str,
) -> Result<()> {
    if c.scene.set.is_some() {
        // One row's solve at the shaft's motion would leave out the set's mounting (the
        // rows' offsets and preload): not the run's loads, so not drawn.
        return Err(Error::invalid(
            "set",
            "a bearing set",
            "none for this plot: the set level keeps no element loads, and one row solved \
             alone at the shaft's motion would leave out the set's mounting (the rows' \
             offsets and preload)",
        ));
    }
    let b = c.comp.bearing();
    b.groove("the ball-load plot (a Jones–Harris solve)")?;
    let level = c.scene.model.level.name();
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
    let why = if level == "linear" {
        format!("the {level} level keeps no ball loads")
    } else {
        "a run straight through keeps no ball loads".to_string()
    };
    let title = format!(
        "ball loads recomputed (Jones–Harris at the final motion, balls at their reference \
         azimuths; {why})"
    );
    let deg: Vec<f64> = psi.iter().map(|p| p.to_degrees()).collect();
    let qi: Vec<f64> = res.iter().map(|r| r.q_i).collect();
    let qo: Vec<f64> = res.iter().map(|r| r.q_o).collect();
    plot_pair_dpi(
        &out.join("ball-loads.png"),
        dpi,
        &Axes {
            title: &headed(c, &title),
            x_label,
            y_label,
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
/// (with the clearance circle) and the speed histories (shaft; cage and kinematic cage;
/// their difference).
fn write_cage_plots(out: &Path, dpi: u32, series: &Run, who: &str) -> Result<()> {
    let col = |n: &str| series.column(n).unwrap_or(&[]).to_vec();
    let t = &series.t;
    let (cx, cy) = (col("cage.x"), col("cage.y"));
    let circle: Vec<(f64, f64)> = (0..=360)
        .map(|k| (k as f64).to_radians().sin_cos())
        .map(|(s, c)| (c, s))
        .collect();
    let (ux, uy): (Vec<f64>, Vec<f64>) = circle.into_iter().unzip();
    plot_pair_dpi(
        &out.join("cage-orbit.png"),
        dpi,
        &Axes {
            title: &format!("{who}cage-centre orbit (units of the guide clearance)"),
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
    let lead: Vec<f64> = cage.iter().zip(&kin).map(|(c, k)| c - k).collect();
    // The cage on its own axis: against the shaft's scale its slip would not show.
    let line = |label, y| Series {
        label,
        x: t,
        y,
        points: false,
    };
    stack_pair_dpi(
        &out.join("speeds.png"),
        dpi,
        &format!("{who}speed histories"),
        &[
            (
                Axes {
                    y_label: "shaft speed (rpm)",
                    ..Axes::default()
                },
                vec![line("shaft", &shaft)],
            ),
            (
                Axes {
                    y_label: "cage speed (rpm)",
                    ..Axes::default()
                },
                vec![line("cage", &cage), line("cage, kinematic", &kin)],
            ),
            // The slip in rpm: on the speed's scale (0 to 30 000 rpm in a run-up) the two
            // cage lines above overlap.
            (
                Axes {
                    x_label: "t (s)",
                    y_label: "cage - kinematic (rpm)",
                    ..Axes::default()
                },
                vec![line("", &lead)],
            ),
        ],
    )
}

/// The plot title `what`, prefixed with the scene's name and its title (bearing and
/// operating point), so that an exported figure can be identified.
fn headed(c: &Ctx, what: &str) -> String {
    format!("{} ({}): {what}", c.name, c.scene.title)
}
