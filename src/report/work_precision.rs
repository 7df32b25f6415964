//! Work-precision: the error of the reaction forces bought with each second of run time,
//! per model level and integrator, over a tolerance sweep (docs/physics.md §N6; the layout of
//! DiffEqDevTools' `WorkPrecisionSet`: x = error, y = CPU time, log-log).
//!
//! - The cases are data ([`cases`]): a scene (any level, any causality), a window and a
//!   communication step. A new level is one more row.
//! - Each case is run through the public component at every tolerance of the sweep with
//!   DOPRI5 and RODAS4; the time is the median of repeats after a warm-up run (stepping
//!   only, setup excluded, one thread), next to the integrator's counters.
//! - The error is that of the reaction forces at the communication points against a
//!   reference, relative L2 over the window and relative peak ([`super::force_error`]).
//! - Two references per case by different methods (DOPRI5 at rtol 1e-12, RODAS4 at
//!   1e-11); their difference is the error floor, below which no point is plotted. They are
//!   cached on disk, keyed by a fingerprint of the case scene, the settings and the crate
//!   version.
//!
//! Tolerances: `atol_m = ATOL_PER_RTOL * rtol` (so rtol 1e-6 pairs with the scene default
//! atol_m 1e-10 m).

use super::{drive, force_error, median, write_file, Machine, Samples};
use crate::component::{fingerprint, Component, Method, Scene, Stats};
use crate::error::{Error, Result};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Absolute displacement tolerance per unit of relative tolerance, m.
pub const ATOL_PER_RTOL: f64 = 1e-4;

/// One case of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Short name (CSV key).
    pub name: &'static str,
    /// What it is, for people.
    pub description: &'static str,
    /// Scene text (TOML); its `[solver]` section is set by the study.
    pub scene: String,
    /// Simulated window, s.
    pub t_end: f64,
    /// Communication (macro) step, s.
    pub h: f64,
}

impl Case {
    /// The scene with the given method and tolerance.
    pub fn scene_with(&self, method: Method, rtol: f64) -> Result<Scene> {
        let mut s = Scene::from_text(&self.scene)?;
        s.solver.method = method;
        s.solver.rtol = rtol;
        s.solver.atol_m = ATOL_PER_RTOL * rtol;
        Ok(s)
    }

    /// Level label, e.g. `ring-2dof`.
    pub fn level(&self) -> Result<String> {
        let s = Scene::from_text(&self.scene)?;
        Ok(match s.model.level {
            crate::component::Level::Ring => format!("ring-{}dof", s.model.ring_dof),
            l => l.name().to_string(),
        })
    }

    /// Run once; returns samples, stepping time and counters.
    pub fn run(&self, method: Method, rtol: f64) -> Result<(Samples, f64, Stats)> {
        let mut c = Component::new(self.scene_with(method, rtol)?)?;
        let (s, dt) = drive(&mut c, self.t_end, self.h, &[], None)?;
        Ok((s, dt, c.stats()))
    }
}

impl Case {
    /// Run once straight through ([`super::drive_through`]): samples, time (the forces at
    /// every communication point included) and counters.
    pub fn run_through(&self, method: Method, rtol: f64) -> Result<(Samples, f64, Stats)> {
        let mut c = Component::new(self.scene_with(method, rtol)?)?;
        let (s, dt) = super::drive_through(&mut c, self.t_end, self.h)?;
        Ok((s, dt, c.stats()))
    }
}

/// A case's scene: `head` (title, bearing, level, ring DOFs), then what every case shares
/// (a load-driven inner ring of 1 kg released from rest, contact damping 3000 N s/m), then
/// the shaft speed (rpm) and the initial inputs.
macro_rules! released {
    ($head:literal, $speed_rpm:literal, $initial:literal) => {
        concat!(
            $head,
            r#"causality = "load"
start = "rest"
contact_damping = 3000.0
attached_mass_kg = 1.0
[inputs]
speed_rpm = "#,
            $speed_rpm,
            "\ninitial = ",
            $initial,
            "\n"
        )
    };
}

const RING2_6205: &str = released!(
    r#"
title = "6205, 10 um clearance, 1 kg on the inner ring, 1 kN radial load, 1750 rpm"
bearing = { preset = "6205", clearance_um = 10.0 }
[model]
level = "LEVEL"
ring_dof = 2
"#,
    "1750.0",
    r#"{ "load.x" = 0.0, "load.y" = -1000.0, "load.z" = 0.0, "load.mx" = 0.0, "load.my" = 0.0 }"#
);

const RING5_7008: &str = released!(
    r#"
title = "7008CE (ZrO2), 1 kg on the inner ring, 1 kN radial + 500 N axial, 6000 rpm"
bearing = "7008ce"
[model]
level = "LEVEL"
ring_dof = 5
"#,
    "6000.0",
    r#"{ "load.x" = 0.0, "load.y" = -1000.0, "load.z" = 500.0, "load.mx" = 0.0, "load.my" = 0.0 }"#
);

/// The cases: load-driven inner rings released from the centre under load (they fall
/// through the clearance, hit the balls and ring down), one row per level and geometry.
/// Levels that are not wired yet are skipped at run time with their error.
pub fn cases() -> Vec<Case> {
    let mk = |name, description, tpl: &str, level: &str, t_end: f64| Case {
        name,
        description,
        scene: tpl.replace("LEVEL", level),
        t_end,
        h: 1e-4,
    };
    vec![
        mk(
            "6205-2dof",
            "6205, 10 µm clearance, 2-DOF ring + 1 kg, 1 kN radial load, 1750 rpm, contact damping 3000 N s/m",
            RING2_6205,
            "ring",
            0.05,
        ),
        mk(
            "7008ce-5dof",
            "7008CE (ZrO2), 5-DOF ring + 1 kg, 1 kN radial + 500 N axial, 6000 rpm, contact damping 3000 N s/m",
            RING5_7008,
            "ring",
            0.02,
        ),
        mk(
            "6205-qs",
            "as 6205-2dof, quasi-static level (Jones–Harris balls, same contact damping) over 20 ms",
            RING2_6205,
            "quasi_static",
            0.02,
        ),
        mk(
            "7008ce-qs",
            "as 7008ce-5dof, quasi-static level (Jones–Harris balls, same contact damping) over 10 ms",
            RING5_7008,
            "quasi_static",
            0.01,
        ),
        mk(
            "6205-linear",
            "as 6205-2dof, linear level (K, C of the scene's operating point)",
            RING2_6205,
            "linear",
            0.05,
        ),
        mk(
            "7008ce-skid",
            "7008CE (ZrO2) skidding level at 6000 rpm under 300 N axial + 100 N radial, balls and cage starting at their kinematic speeds, Coulomb traction (0.02, 0.05 m/s), 10 ms",
            SKID_7008,
            "skidding",
            0.01,
        ),
        Case {
            h: 2e-5,
            ..mk(
                "7004-full-30k",
                "7004 hybrid at 30 000 rpm, Fa 2000 N, Fr 400 N, full level (6-DOF balls and free cage, quasi-static ball-race contacts), motion-driven at the quasi-static displacement, 5 ms = 2.5 shaft revolutions (examples/scenes/7004-30000.toml)",
                FULL_7004_30K,
                "full",
                0.005,
            )
        },
        Case {
            h: 2e-5,
            ..mk(
                "7004-full-120k",
                "as 7004-full-30k at 120 000 rpm (examples/scenes/7004-120000.toml), 2 ms = 4 shaft revolutions",
                FULL_7004_120K,
                "full",
                0.002,
            )
        },
    ]
}

/// The full-level cases use the catalogue's scenes (the study overrides their solver).
const FULL_7004_30K: &str = include_str!("../../examples/scenes/7004-30000.toml");
const FULL_7004_120K: &str = include_str!("../../examples/scenes/7004-120000.toml");

const SKID_7008: &str = r#"
title = "7008CE skidding at 6000 rpm, 300 N axial + 100 N radial"
bearing = "7008ce"
[model]
level = "LEVEL"
causality = "load"
attached_mass_kg = 0.5
contact_damping = 100.0
[model.skidding]
traction = { law = "coulomb", mu_max = 0.02, v_s = 0.05 }
pocket_stiffness = 1e7
pocket_damping = 200.0
pocket_friction = 0.05
drag_coefficient = 15.0
drag_density = 10.0
[inputs]
speed_rpm = 6000.0
initial = { "load.x" = 0.0, "load.y" = -100.0, "load.z" = 300.0, "load.mx" = 0.0, "load.my" = 0.0 }
"#;

/// Settings of a study.
#[derive(Debug, Clone, PartialEq)]
pub struct Config {
    /// Cases to run.
    pub cases: Vec<Case>,
    /// Integrators.
    pub methods: Vec<Method>,
    /// Relative tolerances, loose to tight.
    pub rtols: Vec<f64>,
    /// Timed repeats per point (after one warm-up run); fewer when a run is slow.
    pub repeats: usize,
    /// Time budget per point, s (limits the repeats of slow runs).
    pub budget_s: f64,
    /// Reference cache directory.
    pub cache_dir: PathBuf,
    /// Reference tolerances: DOPRI5 and RODAS4.
    pub reference_rtol: (f64, f64),
    /// Print progress and counters to stdout.
    pub verbose: bool,
    /// Also measure every point straight through ([`Case::run_through`]: one
    /// `step_through` call over the window instead of a stop at every communication
    /// point) into [`Report::through`].
    pub through: bool,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            cases: cases(),
            methods: vec![Method::Dopri5, Method::Rosenbrock],
            rtols: vec![1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9],
            repeats: 7,
            budget_s: 3.0,
            cache_dir: PathBuf::from("target/raceway-bench"),
            reference_rtol: (1e-12, 1e-11),
            verbose: false,
            through: false,
        }
    }
}

/// Scene-file spelling of a method.
pub fn method_name(m: Method) -> &'static str {
    match m {
        Method::Dopri5 => "dopri5",
        Method::Rosenbrock => "rodas4",
        Method::Ros34pw2 => "ros34pw2",
        Method::Auto => "auto",
    }
}

/// One measured point.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Case name.
    pub case: String,
    /// Level label.
    pub level: String,
    /// Integrator.
    pub method: Method,
    /// Relative tolerance.
    pub rtol: f64,
    /// Median stepping time, s.
    pub median_s: f64,
    /// Timed repeats.
    pub repeats: usize,
    /// Counters of one run.
    pub stats: Stats,
    /// Relative L2 force error.
    pub err_l2: f64,
    /// Relative peak force error.
    pub err_peak: f64,
    /// Error floor (L2 difference of the two references).
    pub floor: f64,
    /// Simulated time, s.
    pub sim_s: f64,
}

/// A case's references.
#[derive(Debug, Clone, PartialEq)]
pub struct References {
    /// DOPRI5 at the tight tolerance (the one errors are measured against).
    pub primary: Samples,
    /// RODAS4 at the tight tolerance.
    pub secondary: Samples,
    /// Relative L2 difference of the two.
    pub floor_l2: f64,
    /// Relative peak difference of the two.
    pub floor_peak: f64,
}

/// A finished study.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// Where it was measured.
    pub machine: Machine,
    /// Cases that ran: `(name, level, description)`.
    pub cases: Vec<(String, String, String)>,
    /// Cases skipped, with the reason (e.g. a level not wired yet).
    pub skipped: Vec<(String, String)>,
    /// The points.
    pub rows: Vec<Row>,
    /// The points measured straight through ([`Config::through`]; empty otherwise).
    pub through: Vec<Row>,
    /// Peer results (SciPy), if measured.
    pub peer: Vec<PeerRow>,
    /// Reference tolerances used.
    pub reference_rtol: (f64, f64),
}

/// A real-time factor (simulated over CPU time) with sensible digits.
fn rtf(r: &Row) -> String {
    let x = r.sim_s / r.median_s;
    if x >= 10.0 {
        format!("{x:.0}")
    } else {
        format!("{x:.2}")
    }
}

/// Cache file of a reference run.
pub fn cache_path(dir: &Path, case: &Case, method: Method, rtol: f64) -> Result<PathBuf> {
    let scene = case.scene_with(method, rtol)?;
    let key = format!(
        "{}|{:?}|{:?}|{}",
        serde_json::to_string(&scene).unwrap_or_default(),
        case.t_end,
        case.h,
        env!("CARGO_PKG_VERSION")
    );
    Ok(dir.join(format!(
        "ref-{}-{}-{:016x}.csv",
        case.name,
        method_name(method),
        fingerprint(key.as_bytes())
    )))
}

/// A reference run, from the cache when present (else run and stored).
pub fn reference_run(dir: &Path, case: &Case, method: Method, rtol: f64) -> Result<Samples> {
    let p = cache_path(dir, case, method, rtol)?;
    if let Ok(text) = std::fs::read_to_string(&p) {
        if let Ok(s) = Samples::from_csv(&text) {
            if !s.t.is_empty() {
                return Ok(s);
            }
        }
    }
    let (s, _, _) = case.run(method, rtol)?;
    write_file(&p, &s.to_csv())?;
    Ok(s)
}

/// Both references of a case and their difference.
pub fn references(cfg: &Config, case: &Case) -> Result<References> {
    let primary = reference_run(&cfg.cache_dir, case, Method::Dopri5, cfg.reference_rtol.0)?;
    let secondary = reference_run(
        &cfg.cache_dir,
        case,
        Method::Rosenbrock,
        cfg.reference_rtol.1,
    )?;
    let (floor_l2, floor_peak) = force_error(&secondary, &primary)?;
    Ok(References {
        primary,
        secondary,
        floor_l2,
        floor_peak,
    })
}

/// Measure one point: a warm-up run (samples and counters), then timed repeats.
pub fn measure(
    cfg: &Config,
    case: &Case,
    method: Method,
    rtol: f64,
) -> Result<(Samples, f64, usize, Stats)> {
    measure_runs(cfg, || case.run(method, rtol))
}

/// [`measure`] straight through ([`Case::run_through`]).
pub fn measure_through(
    cfg: &Config,
    case: &Case,
    method: Method,
    rtol: f64,
) -> Result<(Samples, f64, usize, Stats)> {
    measure_runs(cfg, || case.run_through(method, rtol))
}

/// `run` once for the samples and counters, then as often as the time budget and the
/// repeats allow: the median time.
fn measure_runs(
    cfg: &Config,
    run: impl Fn() -> Result<(Samples, f64, Stats)>,
) -> Result<(Samples, f64, usize, Stats)> {
    let (s, first, stats) = run()?;
    let reps = if first > 0.0 {
        ((cfg.budget_s / first).floor() as usize).clamp(1, cfg.repeats.max(1))
    } else {
        cfg.repeats.max(1)
    };
    let mut times = Vec::with_capacity(reps);
    for _ in 0..reps {
        times.push(run()?.1);
    }
    Ok((s, median(&mut times), reps, stats))
}

/// Run the study.
pub fn run(cfg: &Config) -> Result<Report> {
    let mut rep = Report {
        machine: Machine::detect(),
        cases: Vec::new(),
        skipped: Vec::new(),
        rows: Vec::new(),
        through: Vec::new(),
        peer: Vec::new(),
        reference_rtol: cfg.reference_rtol,
    };
    for case in &cfg.cases {
        let level = case.level()?;
        // A level that is not wired yet is skipped with its reason.
        if let Err(e) = Component::new(case.scene_with(Method::Dopri5, 1e-6)?) {
            rep.skipped.push((case.name.to_string(), e.to_string()));
            if cfg.verbose {
                println!("skip {}: {e}", case.name);
            }
            continue;
        }
        let refs = references(cfg, case)?;
        if cfg.verbose {
            println!(
                "{} [{}]: reference floor L2 {:.2e}, peak {:.2e}",
                case.name, level, refs.floor_l2, refs.floor_peak
            );
        }
        rep.cases.push((
            case.name.to_string(),
            level.clone(),
            case.description.to_string(),
        ));
        for &method in &cfg.methods {
            for &rtol in &cfg.rtols {
                for through in [false, true] {
                    if through && !cfg.through {
                        continue;
                    }
                    let (s, t, reps, stats) = if through {
                        measure_through(cfg, case, method, rtol)?
                    } else {
                        measure(cfg, case, method, rtol)?
                    };
                    let (err_l2, err_peak) = force_error(&s, &refs.primary)?;
                    if cfg.verbose {
                        println!(
                            "  {:<7} rtol {:.0e}{}: {:>9.3} ms  err L2 {:.2e} peak {:.2e}  {}",
                            method_name(method),
                            rtol,
                            if through { " straight through" } else { "" },
                            t * 1e3,
                            err_l2,
                            err_peak,
                            super::stats_line(&stats)
                        );
                    }
                    let row = Row {
                        case: case.name.to_string(),
                        level: level.clone(),
                        method,
                        rtol,
                        median_s: t,
                        repeats: reps,
                        stats,
                        err_l2,
                        err_peak,
                        floor: refs.floor_l2,
                        sim_s: case.t_end,
                    };
                    if through {
                        rep.through.push(row);
                    } else {
                        rep.rows.push(row);
                    }
                }
            }
        }
    }
    Ok(rep)
}

/// A peer's measured point (from the peer's CSV).
#[derive(Debug, Clone, PartialEq)]
pub struct PeerRow {
    /// Peer and method, e.g. `scipy-Radau`.
    pub method: String,
    /// Relative tolerance.
    pub rtol: f64,
    /// Median time, s.
    pub median_s: f64,
    /// Right-hand sides.
    pub nfev: u64,
    /// Jacobians.
    pub njev: u64,
    /// LU decompositions.
    pub nlu: u64,
    /// Relative L2 force error against raceway's reference.
    pub err_l2: f64,
    /// Relative peak force error.
    pub err_peak: f64,
}

/// Read the CSV `peers/scipy_ring.py` writes
/// (`method,rtol,median_s,nfev,njev,nlu,err_l2,err_peak`).
pub fn read_peer_csv(text: &str) -> Result<Vec<PeerRow>> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate().skip(1) {
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        let bad = |m: String| Error::Parse {
            what: format!("peer CSV line {}", i + 1),
            message: m,
        };
        if f.len() < 8 {
            return Err(bad(format!("{} fields, expected 8", f.len())));
        }
        let num = |k: usize| f[k].parse::<f64>().map_err(|e| bad(e.to_string()));
        out.push(PeerRow {
            method: f[0].to_string(),
            rtol: num(1)?,
            median_s: num(2)?,
            nfev: num(3)? as u64,
            njev: num(4)? as u64,
            nlu: num(5)? as u64,
            err_l2: num(6)?,
            err_peak: num(7)?,
        });
    }
    Ok(out)
}

/// Parameters of the 2-DOF ring case for a peer, as JSON: everything its right-hand side
/// needs (from the same bearing the component builds), the window and the tolerances rule.
pub fn peer_parameters(case: &Case) -> Result<String> {
    let scene = case.scene_with(Method::Dopri5, 1e-6)?;
    let c = Component::new(scene.clone())?;
    let b = c.bearing();
    let m = crate::models::ring::RingModel::new(
        b,
        crate::models::ring::RingDof::Two,
        scene.model.contact_damping,
    );
    let omega = scene.inputs.initial_value("shaft.omega");
    let v = serde_json::json!({
        "case": case.name,
        "z": b.z,
        "kn": m.kn(),
        "pd": b.pd,
        "ball_d": b.d,
        "mass": b.inner_ring_mass + scene.model.attached_mass_kg,
        "damping": scene.model.contact_damping,
        "damping_ramp": crate::models::ring::DAMPING_RAMP,
        "cage_omega": crate::component::levels::cage_speed(b, omega),
        "load_x": scene.inputs.initial["load.x"],
        "load_y": scene.inputs.initial["load.y"],
        "t_end": case.t_end,
        "h": case.h,
        "atol_per_rtol": ATOL_PER_RTOL,
    });
    Ok(serde_json::to_string_pretty(&v).unwrap_or_default())
}

/// Write the reference series and parameters of `case` for a peer into `dir`
/// (`<case>-reference.csv`, `<case>-parameters.json`).
pub fn export_for_peer(cfg: &Config, case: &Case, dir: &Path) -> Result<()> {
    let refs = references(cfg, case)?;
    write_file(
        &dir.join(format!("{}-reference.csv", case.name)),
        &refs.primary.to_csv(),
    )?;
    write_file(
        &dir.join(format!("{}-parameters.json", case.name)),
        &peer_parameters(case)?,
    )
}

/// Interpolate, in log-log, the time a polyline `(err, time)` needs for error `e`; `None`
/// outside its range.
pub fn time_at_error(curve: &[(f64, f64)], e: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = curve
        .iter()
        .copied()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    for w in pts.windows(2) {
        let ((e0, t0), (e1, t1)) = (w[0], w[1]);
        if e >= e0 && e <= e1 && e1 > e0 {
            let s = (e.ln() - e0.ln()) / (e1.ln() - e0.ln());
            return Some((t0.ln() + s * (t1.ln() - t0.ln())).exp());
        }
    }
    None
}

impl Report {
    /// Rows of one case and method, loose to tight.
    pub fn series(&self, case: &str, method: Method) -> Vec<&Row> {
        self.rows
            .iter()
            .filter(|r| r.case == case && r.method == method)
            .collect()
    }

    /// The CSV text.
    pub fn csv(&self) -> String {
        let mut s = String::from(
            "case,level,method,rtol,median_s,rhs,jacobians,lu,accepted,rejected,err_l2,err_peak,floor,repeats,sim_s\n",
        );
        for r in &self.rows {
            let _ = writeln!(
                s,
                "{},{},{},{:e},{:.6e},{},{},{},{},{},{:.4e},{:.4e},{:.4e},{},{}",
                r.case,
                r.level,
                method_name(r.method),
                r.rtol,
                r.median_s,
                r.stats.rhs,
                r.stats.jacobians,
                r.stats.factorizations,
                r.stats.accepted,
                r.stats.rejected,
                r.err_l2,
                r.err_peak,
                r.floor,
                r.repeats,
                r.sim_s
            );
        }
        s
    }

    /// Cheapest row of `case` whose L2 error is at most `e` (and above the floor's reach).
    pub fn cheapest_within(&self, case: &str, e: f64) -> Option<&Row> {
        self.rows
            .iter()
            .filter(|r| r.case == case && r.err_l2 <= e)
            .min_by(|a, b| a.median_s.total_cmp(&b.median_s))
    }

    /// The Markdown page.
    pub fn markdown(&self, png: Option<&str>) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "# Work-precision: the error each second of run time buys\n\n\
             Generated by `cargo run --release -- bench --peer --out docs` (library: \
             `raceway::report::work_precision::run`). Machine: {}.\n",
            self.machine.describe()
        );
        s += "## Method\n\n\
            Each case is a scene driven through the public component (`do_step` at a fixed \
            communication step, forces read with `get_real`), from rest with its load applied: \
            the inner ring falls through the clearance, meets the balls and rings down, so the \
            window contains contact onsets, the ring's natural oscillation and the \
            varying-compliance excitation. Error: the reaction force `(Fx, Fy, Fz)` at every \
            communication point against a reference, relative L2 over the window \
            (`sqrt(Σ|F-F_ref|² / Σ|F_ref|²)`) and relative peak (`max|F-F_ref| / max|F_ref|`). \
            ";
        let _ = write!(
            s,
            "References: DOPRI5 at rtol {:.0e} (errors are measured against it) and RODAS4 at \
             rtol {:.0e}; their difference is the floor, and points below it are not plotted \
             (they are in the CSV). `atol_m = {:.0e} m × rtol`. Time: the stepping thread's \
             CPU time (`CLOCK_THREAD_CPUTIME_ID`, not a wall clock; the load average is in the \
             machine line), median of up to the given repeats after one warm-up run, stepping \
             only (component creation excluded), one thread. Counters (right-hand sides, Jacobians, LU factorisations, accepted and \
             rejected steps) are those of one run; they do not depend on the machine.\n\n",
            self.reference_rtol.0, self.reference_rtol.1, ATOL_PER_RTOL
        );
        s += "## Cases\n\n| case | level | description |\n|---|---|---|\n";
        for (n, l, d) in &self.cases {
            let _ = writeln!(s, "| {n} | {l} | {d} |");
        }
        for (n, why) in &self.skipped {
            let _ = writeln!(s, "| {n} | — | skipped: {why} |");
        }
        if let Some(p) = png {
            let _ = writeln!(s, "\n![work-precision]({p})\n");
        }
        s += "\n## Table\n\n\
            | case | method | rtol | time (ms) | real-time factor | rhs | jac | LU | accepted | rejected | err L2 | err peak | floor |\n\
            |---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
        for r in &self.rows {
            let _ = writeln!(
                s,
                "| {} | {} | {:.0e} | {:.3} | {} | {} | {} | {} | {} | {} | {:.2e} | {:.2e} | {:.1e} |",
                r.case,
                method_name(r.method),
                r.rtol,
                r.median_s * 1e3,
                rtf(r),
                r.stats.rhs,
                r.stats.jacobians,
                r.stats.factorizations,
                r.stats.accepted,
                r.stats.rejected,
                r.err_l2,
                r.err_peak,
                r.floor
            );
        }
        s += "\nReal-time factor: simulated time over CPU time (above 1 is faster than real time).\n\n";
        s += &self.reading();
        s += &self.recommendations();
        s += &self.peer_section();
        s
    }

    /// Observations computed from the rows: how stiff each case is for DOPRI5 and which
    /// integrator is cheaper at the loose and tight ends of the sweep.
    fn reading(&self) -> String {
        let mut s = String::from(
            "## Reading

",
        );
        for (name, _, _) in &self.cases {
            let (dp, ro) = (
                self.series(name, Method::Dopri5),
                self.series(name, Method::Rosenbrock),
            );
            let (Some(d0), Some(r0), Some(d1), Some(r1)) =
                (dp.first(), ro.first(), dp.last(), ro.last())
            else {
                continue;
            };
            let rej = d0.stats.rejected as f64 / d0.stats.accepted.max(1) as f64;
            let _ = writeln!(
                s,
                "- **{name}**: at rtol {:.0e} DOPRI5 rejects {} of {} steps ({:.0} %){}; RODAS4 / DOPRI5 time {:.2} there and {:.2} at rtol {:.0e} (below 1: RODAS4 is cheaper). Errors at the tight end: DOPRI5 {:.1e}, RODAS4 {:.1e}.",
                d0.rtol,
                d0.stats.rejected,
                d0.stats.accepted,
                100.0 * rej,
                if rej > 0.1 {
                    " even at the loosest tolerance: its step is limited by stability, not accuracy (stiff modes), which is where the L-stable RODAS4 wins"
                } else {
                    ""
                },
                r0.median_s / d0.median_s,
                r1.median_s / d1.median_s,
                d1.rtol,
                d1.err_l2,
                r1.err_l2
            );
        }
        s += "\nThe communication step (1e-4 s) caps the internal step: at loose tolerances an \
              integrator takes about one step per communication step, so the time flattens and \
              the error there is set by the step cap and the contact onsets inside it. The \
              force error responds more steeply than the displacement tolerance asks for \
              (`Q ~ delta^1.5` with the approach `delta` a fraction of the displacement), and the \
              impact of the falling ring makes the peak error larger than the L2 error.\n\n";
        s
    }

    fn recommendations(&self) -> String {
        let mut s = String::from(
            "## Which setting for which need\n\n\
             Picked from the measured rows above: the cheapest setting whose force error stays \
             within the need. Needs: **real-time coupling** (force error ≤ 1e-2: well below \
             a typical co-simulation coupling error, see docs/coupling.md); **vibration \
             spectra** (≤ 1e-4: the varying-compliance line is 0.4–2 % of the deflection, \
             docs/physics.md §N5.2, so this resolves it to about 1 %); **reference accuracy** \
             (≤ 1e-7, or within 10× the floor).\n\n\
             | case | need | method | rtol | time (ms) | real-time factor | err L2 |\n|---|---|---|---|---|---|---|\n",
        );
        for (name, _, _) in &self.cases {
            let floor = self
                .rows
                .iter()
                .find(|r| &r.case == name)
                .map_or(0.0, |r| r.floor);
            for (need, e) in [
                ("real-time coupling", 1e-2),
                ("vibration spectra", 1e-4),
                ("reference accuracy", (1e-7f64).max(10.0 * floor)),
            ] {
                match self.cheapest_within(name, e) {
                    Some(r) => {
                        let _ = writeln!(
                            s,
                            "| {name} | {need} | {} | {:.0e} | {:.3} | {} | {:.1e} |",
                            method_name(r.method),
                            r.rtol,
                            r.median_s * 1e3,
                            rtf(r),
                            r.err_l2
                        );
                    }
                    None => {
                        let _ = writeln!(
                            s,
                            "| {name} | {need} | none of the sweep reaches {e:.0e} | | | | |"
                        );
                    }
                }
            }
        }
        s.push('\n');
        s
    }

    fn peer_section(&self) -> String {
        if self.peer.is_empty() {
            return String::new();
        }
        let mut s = String::from(
            "## Peer: SciPy `solve_ivp` on the same 2-DOF ring\n\n\
             `peers/scipy_ring.py` (run by `scripts/peer-scipy`, called by the bench with \
             `--peer`) integrates the same equations with the same parameters (exported by \
             raceway from the same bearing: `target/raceway-bench/6205-2dof-parameters.json`), \
             NumPy-vectorised right-hand side over the balls, analytic Jacobian, in one \
             `solve_ivp` call over the window with `t_eval` at the communication points, and is \
             scored with the same metric against raceway's reference. Raceway restarts its \
             integrator at every communication step (it is a co-simulation component); SciPy \
             integrates straight through, which favours SciPy. Job for job (both stopping at \
             every point, and both straight through with raceway's `Component::step_through`): \
             docs/speed.md (`cargo bench --bench speed -- --only peer`).\n\n\
             | peer | rtol | time (ms) | nfev | njev | nlu | err L2 | raceway time at that error (ms) | SciPy / raceway |\n\
             |---|---|---|---|---|---|---|---|---|\n",
        );
        let curve = |m: Method| -> Vec<(f64, f64)> {
            self.rows
                .iter()
                .filter(|r| r.case == "6205-2dof" && r.method == m)
                .map(|r| (r.err_l2, r.median_s))
                .collect()
        };
        let (c_dp, c_ro) = (curve(Method::Dopri5), curve(Method::Rosenbrock));
        for p in &self.peer {
            let rt = match (
                time_at_error(&c_dp, p.err_l2),
                time_at_error(&c_ro, p.err_l2),
            ) {
                (Some(a), Some(b)) => Some(a.min(b)),
                (a, b) => a.or(b),
            };
            let _ = writeln!(
                s,
                "| {} | {:.0e} | {:.2} | {} | {} | {} | {:.2e} | {} | {} |",
                p.method,
                p.rtol,
                p.median_s * 1e3,
                p.nfev,
                p.njev,
                p.nlu,
                p.err_l2,
                rt.map_or("outside raceway's range".into(), |t| format!(
                    "{:.3}",
                    t * 1e3
                )),
                rt.map_or("—".into(), |t| format!("{:.0}×", p.median_s / t)),
            );
        }
        s += "\nRatio: SciPy's time over raceway's time interpolated (log-log) at the same L2 \
              error along its faster integrator's line (DOPRI5 or RODAS4).\n";
        s
    }

    /// Write `work-precision.csv`, `.png` (feature `plot`) and `.md` into `dir`.
    pub fn write(&self, dir: &Path) -> Result<()> {
        write_file(&dir.join("work-precision.csv"), &self.csv())?;
        let png = self.plot(&dir.join("work-precision.png"))?;
        write_file(
            &dir.join("work-precision.md"),
            &self.markdown(png.then_some("work-precision.png")),
        )
    }

    /// Draw the log-log plot (x error, y time; points below the floor left out). Returns
    /// whether a plot was written.
    #[cfg(feature = "plot")]
    pub fn plot(&self, path: &Path) -> Result<bool> {
        use crate::plot::{plot, Axes, Series};
        // One colour per case (the plot colours series by position, `N_COLORS` colours):
        // DOPRI5 as lines first, blank series to realign the palette, then RODAS4 as points.
        let mut data: Vec<(String, Vec<f64>, Vec<f64>, bool)> = Vec::new();
        for (k, m) in [Method::Dopri5, Method::Rosenbrock].into_iter().enumerate() {
            if k == 1 {
                let n = crate::plot::N_COLORS;
                let pad = (n - data.len() % n) % n;
                for _ in 0..pad {
                    data.push((String::new(), Vec::new(), Vec::new(), false));
                }
            }
            for (name, _, _) in &self.cases {
                let pts: Vec<&Row> = self
                    .series(name, m)
                    .into_iter()
                    .filter(|r| r.err_l2 >= r.floor)
                    .collect();
                let label = match m {
                    Method::Rosenbrock => format!("{name} rodas4 (dots)"),
                    _ => format!("{name} dopri5 (line)"),
                };
                data.push((
                    label,
                    pts.iter().map(|r| r.err_l2).collect(),
                    pts.iter().map(|r| r.median_s).collect(),
                    m == Method::Rosenbrock,
                ));
            }
        }
        let series: Vec<Series<'_>> = data
            .iter()
            .map(|(l, x, y, p)| Series {
                label: l,
                x,
                y,
                points: *p,
            })
            .collect();
        let title = format!("Work-precision ({})", self.machine.cpu);
        plot(
            path,
            &Axes {
                title: &title,
                x_label: "relative L2 error of the reaction forces",
                y_label: "thread CPU time (s)",
                log_x: true,
                log_y: true,
                equal: false,
            },
            &series,
            &[],
        )?;
        Ok(true)
    }

    /// Without the `plot` feature no plot is drawn.
    #[cfg(not(feature = "plot"))]
    pub fn plot(&self, _path: &Path) -> Result<bool> {
        Ok(false)
    }
}
