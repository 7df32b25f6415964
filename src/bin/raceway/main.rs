//! The `raceway` command-line program.
//!
//! - `raceway bearings [--json]`: the bearing presets with their data (mm, degrees, µm)
//!   and derived quantities (free contact angle, `A`, ball mass, `Kc` at the nominal angle).
//!   `raceway bearings NAME [--json]`: one preset or catalogue designation (`6206`,
//!   `7205B`) with its ISO 281/76 ratings and where each number comes from.
//! - `raceway quasi-static [--bearing <preset|file.toml>] [--speed-rpm N] [--fx ..] [--fy ..]
//!   [--fz ..] [--mx ..] [--my ..] [--race-control outer|none] [--json]`: the Jones–Harris
//!   quasi-static equilibrium under an external load on the inner ring. With none of
//!   `--bearing`, `--speed-rpm`, `--fx` .. `--my` it solves the embedded default scene's
//!   operating point (its bearing, `model.operating_point`, and the speed from
//!   `inputs.speed_rpm` when not 0, else `model.operating_point.speed_rpm`).
//!   Otherwise values not given are zero and the bearing defaults to the scene's. The race
//!   control defaults to the scene's `model.race_control`. The answer carries the ISO
//!   ratings, lives, static safety and warnings (`raceway::ratings`); `--kappa` and
//!   `--contamination` add ISO 281's `a_ISO`. `--hold rx_mrad=0,ry_mrad=0` holds ring
//!   coordinates at a value and reports the reaction on each.
//!
//!   `raceway quasi-static --scene SET.toml [--speed-rpm N] [--fx ..] .. [--json]`: a scene's
//!   bearing set under a load on the shaft at its reference point (`set_qs.rs`).
//!
//! - `raceway shaft SHAFT.toml [--json]`: a rigid shaft on bearing locations (single
//!   bearings or sets such as a preloaded DB pair) under loads at axial positions: its
//!   5-DOF equilibrium, each location's loads, lives and static safety, the system
//!   stiffness (`shaft_cmd.rs` has the file format).
//!
//! Every value is checked: non-finite numbers, a negative speed, an unknown preset or a
//! malformed bearing file are refused with a message naming the cause and exit status 1
//! (clap's own usage errors exit with 2).

mod bench;
mod report;
mod run;
mod scene_cmd;
mod set_qs;
mod shaft_cmd;
mod sweep_cmd;

use clap::{Args, Parser, Subcommand, ValueEnum};
use raceway::component::scene::{RaceControl, Scene};
use raceway::summary::reports::{self, QsProblem};
use raceway::summary::rollers;
use raceway::Result;
use std::process::ExitCode;

#[derive(Parser, Debug)]
#[command(
    name = "raceway",
    version,
    about = "Rolling-element bearing simulation: presets, quasi-static equilibrium"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand, Debug)]
enum Cmd {
    /// Run a scene stand-alone (the embedded default scene without a file): time series,
    /// summary and plots into out/<scene>/.
    Run(run::RunArgs),
    /// Developer tool (hidden): the work-precision study or, with --stability, the
    /// stability campaign, into --out (required).
    #[command(hide = true)]
    Bench(bench::BenchArgs),
    /// List the bearing presets and their data, or show one bearing (a preset or a
    /// catalogue designation such as 6206 or 7205B) with its ISO ratings and provenance.
    Bearings {
        /// A preset name or a designation (60xx, 62xx, 63xx; 70xx, 72xx, 73xx + C, AC or B).
        name: Option<String>,
        /// Machine-readable output.
        #[arg(long)]
        json: bool,
    },
    /// Jones–Harris quasi-static equilibrium under an external load on the inner ring.
    ///
    /// Without --bearing, --speed-rpm and load flags it solves the embedded default scene's
    /// operating point; otherwise what is not given is zero (bearing: the scene's).
    QuasiStatic(Box<QsArgs>),
    /// Scene files: document every field (--explain [--json]) or check one (--check FILE).
    Scene(scene_cmd::SceneArgs),
    /// A rigid shaft on bearing locations (single bearings or preloaded sets): equilibrium, loads, lives, stiffness
    Shaft(shaft_cmd::ShaftArgs),
    /// Parameter sweep: a base scene and axes (lists, ranges, grids, random or Latin-hypercube
    /// samples); one summary row per point in <out>/sweep.csv, all cores, resumable,
    /// shardable (--shard k/n, then --merge).
    Sweep(sweep_cmd::SweepArgs),
}

#[derive(ValueEnum, Clone, Copy, Debug)]
enum RaceControlArg {
    /// Outer-race control (lambda_o = 2, lambda_i = 0).
    Outer,
    /// No race control (lambda_i = lambda_o = 1).
    None,
}

#[derive(Args, Debug)]
struct QsArgs {
    /// Bearing: a preset name (see `raceway bearings`) or a TOML bearing file.
    #[arg(long)]
    bearing: Option<String>,
    /// A scene with a bearing set (`[set]`): the set's equilibrium under the load on the
    /// shaft at its reference point (speed: the scene's unless --speed-rpm); the wrench,
    /// displacement and 5x5 K there and one table per row.
    #[arg(long, conflicts_with = "bearing")]
    scene: Option<std::path::PathBuf>,
    /// Shaft speed, rpm (>= 0; the outer ring is fixed).
    #[arg(long, allow_hyphen_values = true)]
    speed_rpm: Option<f64>,
    /// External radial load on the inner ring along x, N.
    #[arg(long, allow_hyphen_values = true)]
    fx: Option<f64>,
    /// External radial load along y, N.
    #[arg(long, allow_hyphen_values = true)]
    fy: Option<f64>,
    /// External axial load along z, N.
    #[arg(long, allow_hyphen_values = true)]
    fz: Option<f64>,
    /// External moment about x, N m.
    #[arg(long, allow_hyphen_values = true)]
    mx: Option<f64>,
    /// External moment about y, N m.
    #[arg(long, allow_hyphen_values = true)]
    my: Option<f64>,
    /// Race control assumption.
    #[arg(long, value_enum)]
    race_control: Option<RaceControlArg>,
    /// Viscosity ratio kappa = nu/nu1 at the operating temperature (for ISO 281's a_ISO
    /// and the kappa < 1 warning).
    #[arg(long)]
    kappa: Option<f64>,
    /// Contamination factor eC of ISO 281 (0..1; with --kappa gives a_ISO).
    #[arg(long)]
    contamination: Option<f64>,
    /// Oil by ISO VG grade (VG2 .. VG3200): viscosity at --oil-temp-c, kappa (unless --kappa
    /// is given) and Palmgren's friction moment in the design check.
    #[arg(long)]
    oil: Option<String>,
    /// Viscosity index of --oil (ASTM D2270; default 95).
    #[arg(long, allow_hyphen_values = true)]
    oil_vi: Option<f64>,
    /// Oil operating temperature, °C (default 70).
    #[arg(long, allow_hyphen_values = true)]
    oil_temp_c: Option<f64>,
    /// Palmgren's lubrication factor f0 (default 2, oil bath).
    #[arg(long)]
    f0: Option<f64>,
    /// Diametral interference of the inner ring on a solid steel shaft, µm (operating clearance).
    #[arg(long, allow_hyphen_values = true)]
    shaft_interference_um: Option<f64>,
    /// Diametral interference of the outer ring in an unbounded steel housing, µm.
    #[arg(long, allow_hyphen_values = true)]
    housing_interference_um: Option<f64>,
    /// Inner-ring temperature, °C, for the operating clearance (default 20).
    #[arg(long, allow_hyphen_values = true)]
    inner_ring_temp_c: Option<f64>,
    /// Outer-ring temperature, °C, for the operating clearance (default 20).
    #[arg(long, allow_hyphen_values = true)]
    outer_ring_temp_c: Option<f64>,
    /// Ambient temperature, °C, of the thermally safe speed's heat balance (default 20; the
    /// bearing is at --oil-temp-c).
    #[arg(long, allow_hyphen_values = true)]
    ambient_temp_c: Option<f64>,
    /// SKF friction model: lubrication method, oil-bath (default), oil-jet, oil-air or grease
    /// (sets the starvation constant K_rs; drag only in an oil bath).
    #[arg(long)]
    skf_lubrication: Option<String>,
    /// SKF friction model: seal constants of a bearing sealed on both sides,
    /// `KS1,BETA,KS2,DS_MM` from the maker's table (M_seal = KS1 ds^BETA + KS2, N mm).
    #[arg(long)]
    skf_seal: Option<String>,
    /// SKF friction model: oil-bath drag, `VM,H_MM` (the drag loss factor read from SKF's
    /// diagram at the oil level H, and H in mm).
    #[arg(long)]
    skf_drag: Option<String>,
    /// SKF friction model: geometry constants `R1,R2,R3,S1,S2,S3` from the maker's table, for
    /// a series not built in (built in: deep-groove 60, 62, 63).
    #[arg(long)]
    skf_constants: Option<String>,
    /// Load spectrum file, one row per line `fr_n, fa_n, speed_rpm, time_share`: ISO 281 life
    /// under the duty cycle (with --oil and --contamination, each row's a_ISO).
    #[arg(long)]
    duty: Option<std::path::PathBuf>,
    /// Hold ring coordinates at a value while solving the others, e.g. `rx_mrad=0,ry_mrad=0`
    /// (names x_um, y_um, z_um, rx_mrad, ry_mrad or x, y, z, rx, ry; a bare name holds at 0);
    /// the reaction on each held coordinate is reported.
    #[arg(long, allow_hyphen_values = true)]
    hold: Option<String>,
    /// Machine-readable output (SI units).
    #[arg(long)]
    json: bool,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let out = match cli.cmd {
        Cmd::Bearings { name, json } => match name {
            Some(n) => report::bearing_detail(&n, json),
            None => report::bearings(json),
        },
        Cmd::QuasiStatic(a) => quasi_static(*a),
        Cmd::Run(a) => run::run(a),
        Cmd::Bench(a) => bench::bench(a),
        Cmd::Scene(a) => scene_cmd::scene(a),
        Cmd::Shaft(a) => shaft_cmd::shaft(a),
        Cmd::Sweep(a) => sweep_cmd::sweep(a),
    };
    match out {
        Ok(text) => {
            print!("{text}");
            ExitCode::SUCCESS
        }
        Err(e @ raceway::Error::Interrupted { .. }) => {
            eprintln!(
                "stopped: {e}; a run writes nothing and leaves its output folder as before, \
                 a sweep keeps the rows it finished (run it again to resume)"
            );
            ExitCode::from(130)
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}

/// The problem the `quasi-static` subcommand solves, after defaults and checks.
fn problem(a: &QsArgs) -> Result<QsProblem> {
    let scene = Scene::default_scene();
    let bearing = match &a.bearing {
        Some(b) => reports::load_bearing(b)?,
        None => scene.build_bearing()?,
    };
    // No operating-point flag at all: the default scene's operating point. Otherwise what
    // is not given is zero.
    let given = [a.speed_rpm, a.fx, a.fy, a.fz, a.mx, a.my];
    let from_scene = a.bearing.is_none() && given.iter().all(Option::is_none);
    let op = &scene.model.operating_point;
    let (speed0, load0) = if from_scene {
        let speed = if scene.inputs.speed_rpm != 0.0 {
            scene.inputs.speed_rpm
        } else {
            op.speed_rpm
        };
        (speed, [op.fx, op.fy, op.fz, op.mx, op.my])
    } else {
        (0.0, [0.0; 5])
    };
    let race_control = match a.race_control {
        Some(RaceControlArg::Outer) => RaceControl::Outer,
        Some(RaceControlArg::None) => RaceControl::None,
        None => scene.model.race_control,
    };
    QsProblem::new(
        bearing,
        a.speed_rpm.unwrap_or(speed0),
        [
            a.fx.unwrap_or(load0[0]),
            a.fy.unwrap_or(load0[1]),
            a.fz.unwrap_or(load0[2]),
            a.mx.unwrap_or(load0[3]),
            a.my.unwrap_or(load0[4]),
        ],
        race_control,
        a.kappa,
        a.contamination,
        &reports::CLI_NAMES,
    )
}

/// The design check's inputs from the flags.
fn calc_inputs(a: &QsArgs, speed_rpm: f64) -> Result<raceway::calculator::check::CalcInputs> {
    use raceway::calculator::check::{CalcInputs, CalcOptions};
    let o = CalcOptions {
        oil: a.oil.clone(),
        oil_vi: a.oil_vi,
        oil_temp_c: a.oil_temp_c,
        f0: a.f0,
        shaft_interference_um: a.shaft_interference_um,
        housing_interference_um: a.housing_interference_um,
        inner_ring_temp_c: a.inner_ring_temp_c,
        outer_ring_temp_c: a.outer_ring_temp_c,
        ambient_temp_c: a.ambient_temp_c,
        skf_lubrication: a.skf_lubrication.clone(),
        skf_seal: a.skf_seal.clone(),
        skf_drag: a.skf_drag.clone(),
        skf_constants: a.skf_constants.clone(),
    };
    let mut c = CalcInputs::from_options(&o, speed_rpm, "--oil-vi", "--skf-")?;
    if let Some(path) = &a.duty {
        let text = std::fs::read_to_string(path).map_err(|e| raceway::Error::Parse {
            what: format!("--duty {}", path.display()),
            message: e.to_string(),
        })?;
        c.duty = Some(raceway::calculator::duty::parse_spectrum(
            &text,
            &format!("--duty {}", path.display()),
        )?);
    }
    Ok(c)
}

/// The quasi-static options that only a single ball bearing's report reads, each with
/// whether it was given: a set scene and a roller bearing refuse them by name.
fn ball_bearing_options(a: &QsArgs) -> [(&'static str, bool); 18] {
    [
        ("--race-control", a.race_control.is_some()),
        ("--kappa", a.kappa.is_some()),
        ("--contamination", a.contamination.is_some()),
        ("--oil", a.oil.is_some()),
        ("--oil-vi", a.oil_vi.is_some()),
        ("--oil-temp-c", a.oil_temp_c.is_some()),
        ("--f0", a.f0.is_some()),
        ("--shaft-interference-um", a.shaft_interference_um.is_some()),
        (
            "--housing-interference-um",
            a.housing_interference_um.is_some(),
        ),
        ("--inner-ring-temp-c", a.inner_ring_temp_c.is_some()),
        ("--outer-ring-temp-c", a.outer_ring_temp_c.is_some()),
        ("--ambient-temp-c", a.ambient_temp_c.is_some()),
        ("--duty", a.duty.is_some()),
        ("--hold", a.hold.is_some()),
        ("--skf-lubrication", a.skf_lubrication.is_some()),
        ("--skf-seal", a.skf_seal.is_some()),
        ("--skf-drag", a.skf_drag.is_some()),
        ("--skf-constants", a.skf_constants.is_some()),
    ]
}

fn quasi_static(a: QsArgs) -> Result<String> {
    if let Some(path) = &a.scene {
        // The one bearing's options have no meaning for a set: refused by name.
        let given = ball_bearing_options(&a);
        if let Some((flag, _)) = given.iter().find(|(_, g)| *g) {
            return Err(raceway::Error::invalid(
                *flag,
                "given",
                "left out with --scene (a set's quasi-static report has the loads, contact \
                 angles, stiffness, lives and static safety of its rows only)",
            ));
        }
        let n = &reports::CLI_NAMES;
        let r = set_qs::report(
            path,
            a.speed_rpm,
            [a.fx, a.fy, a.fz, a.mx, a.my],
            (n.load, n.speed_rpm),
        )?;
        return if a.json {
            report::json(&r.to_json())
        } else {
            Ok(set_qs::text(&r))
        };
    }
    if let Some(b) = a.bearing.as_deref().and_then(rollers::roller_bearing) {
        // The ball bearings' options have no meaning here: refused by name, not ignored.
        let given = ball_bearing_options(&a);
        if let Some((flag, _)) = given.iter().find(|(_, g)| *g) {
            return Err(raceway::Error::invalid(
                *flag,
                "given",
                "left out for a roller bearing (its quasi-static report has the loads, laminae, \
                 stiffness and ISO 281/76 ratings only)",
            ));
        }
        let l = [a.fx, a.fy, a.fz, a.mx, a.my].map(|v| v.unwrap_or(0.0));
        let n = &reports::CLI_NAMES;
        let r = rollers::report(&b?, a.speed_rpm.unwrap_or(0.0), l, (n.load, n.speed_rpm))?;
        return if a.json {
            report::json(&r.to_json())
        } else {
            Ok(rollers::text(&r))
        };
    }
    let mut p = problem(&a)?;
    p.calc = calc_inputs(&a, p.speed_rpm)?;
    if let Some(h) = &a.hold {
        p.hold = raceway::models::quasi_static::hold::HoldSpec::parse(h, "--hold")?;
    }
    let (sol, rating) = p.solve()?;
    // Bad design-check input (fits, oil temperature) is an error, not a missing line.
    p.design_check(&sol, &rating)?;
    if a.json {
        report::quasi_static_json(&p, &sol, &rating)
    } else {
        Ok(report::quasi_static_text(&p, &sol, &rating))
    }
}
