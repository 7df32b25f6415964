//! Cage-whirl study of the hybrid 7004 (study \[0\], Ye, Wang, Zhang; docs/physics.md §5.5 and the
//! §10 row): the `full` level at 30 000, 60 000, 80 000 and 120 000 rpm under Fa 2000 N,
//! Fr 400 N, from the scenes `examples/scenes/7004-*.toml`, for both cage guidances
//! (outer- and inner-ring land) and both readings of the study's 0.25 mm guide clearance
//! (radial, or diametral = 0.125 mm radial); and the start-up from rest
//! (`examples/scenes/7004-startup.toml`).
//!
//! ```text
//! cargo run --release --example cage_whirl                 # study, tables on stdout
//! cargo run --release --example cage_whirl -- --quick      # CI: two speeds, a few ms each
//! cargo run --release --example cage_whirl -- --write-docs # study + docs/cage-whirl.md, PNGs
//! ```
//!
//! Options: `--speeds 30000,120000`, `--duration S` (simulated time per speed),
//! `--windows N` (equal windows over which sigma is computed, the convergence check),
//! `--step S` (communication step = sampling of the cage-centre speed), `--unbalance-um U`
//! (cage mass unbalance, `model.full.cage_unbalance_um`), `--startup-ms MS`, `--config TAG`
//! (one of `outer-radial`, `outer-diametral`, `inner-radial`, `inner-diametral`; default all),
//! `--oil-temp-c T` (study \[0\]'s oil: MIL-L-7808 at T °C for the level's viscosity and the
//! `fitted_4109` traction law at T with MIL-L-7808's data, instead of the scenes' Coulomb
//! traction and 0.003 Pa s; docs/physics.md §5.2, §6.2), `--constant-4109` (with it: the
//! 4109 constant set instead of the power laws), `--with-oil` (with `--write-docs`: the page
//! gains a part that repeats every configuration on MIL-L-7808 at 100 and 60 °C with the 4109
//! fit, with a computed verdict on the trend; three times the CPU), `--rtol R` (the solver's
//! relative tolerance instead of the scenes' 1e-5: the check of the energy balance's rest).
//!
//! Per run: sigma = std(|v|)/mean(|v|) of the level's `cage.speed` (3-D cage-centre speed)
//! over each of `N` equal windows of the run (the last is the settled value, the change
//! from the one before its convergence measure); the orbit (guide clearances); the whirl
//! frequency (mean rate of the cage centre's polar angle over the last window) against the
//! cage rotation frequency; the cage power balance per cage revolution over the last window
//! (pocket, guide land, drag; whirl parts from the centre's velocity), from the model's
//! totals re-evaluated at the recorded states; CPU seconds of this thread per shaft
//! revolution.

use raceway::analysis::whirl_index;
use raceway::component::variables;
use raceway::component::{Causality, Component};
use raceway::geometry::{preset, Guidance};
use raceway::models::full::FullModel;
use raceway::Scene;
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

#[path = "cage_whirl/energy.rs"]
mod energy;
#[cfg(feature = "plot")]
use energy::energy_plot;
use energy::{balance, balance_section, Balance};

/// One guidance and clearance reading.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Config {
    guidance: Guidance,
    /// The study's 0.25 mm read as diametral (radial clearance 0.125 mm).
    diametral: bool,
}

impl Config {
    /// Guidance and clearance reading: (long, short) names.
    fn names(&self) -> [(&'static str, &'static str); 2] {
        [
            match self.guidance {
                Guidance::InnerRing => ("inner-ring land", "inner"),
                Guidance::OuterRing => ("outer-ring land", "outer"),
                Guidance::Ball => ("ball-riding", "ball"),
            },
            if self.diametral {
                ("0.125 (0.25 diametral)", "diametral")
            } else {
                ("0.25 (radial)", "radial")
            },
        ]
    }
    fn label(&self) -> String {
        let [g, c] = self.names();
        format!("{}, Cg {} mm", g.0, c.0)
    }
    fn tag(&self) -> String {
        let [g, c] = self.names();
        format!("{}-{}", g.1, c.1)
    }
}

/// Options of a study run.
#[derive(Debug, Clone)]
struct Opts {
    speeds: Vec<f64>,
    duration: f64,
    windows: usize,
    step: f64,
    unbalance_um: f64,
    startup_ms: f64,
    /// Only this configuration (its tag).
    config: Option<String>,
    /// Study [0]'s oil: MIL-L-7808 at this bulk temperature (°C) for the level's viscosity,
    /// and the 4109 traction fit at it, instead of the scenes' Coulomb traction and 0.003 Pa s.
    oil_temp_c: Option<f64>,
    /// With `oil_temp_c`: the 4109 constant set instead of the power laws.
    constant_4109: bool,
    /// The solver's relative tolerance instead of the scenes' (`--rtol`).
    rtol: Option<f64>,
    /// With `--write-docs`: add the page's part on study [0]'s oil (every configuration at
    /// [`OIL_TEMPS_C`]).
    with_oil: bool,
}

/// The scene's oil and traction replaced by MIL-L-7808 at `o.oil_temp_c` with the 4109 fit
/// ("4109 substitute for 4106, coefficients from public code").
fn apply_oil(s: &mut Scene, o: &Opts) -> Result<(), Box<dyn std::error::Error>> {
    use raceway::contact::traction::{Fit4109, Form4109, Oil4109, TractionLaw};
    if let Some(t) = o.oil_temp_c {
        let oil = raceway::lubrication::oils::mil_l_7808(t + 273.15, "--oil-temp-c")?;
        s.model.full.viscosity = oil.viscosity;
        let law = TractionLaw::Fitted4109(Fit4109 {
            form: if o.constant_4109 {
                Form4109::Constant
            } else {
                Form4109::PowerLaw
            },
            temperature_c: Some(t),
            oil: Oil4109::MilL7808,
            ..Default::default()
        });
        law.validate("model.full.traction")?;
        s.model.full.traction = law;
    }
    Ok(())
}

/// What one recorded run gives.
#[derive(Debug, Clone, Default)]
struct Record {
    t: Vec<f64>,
    cx: Vec<f64>,
    cy: Vec<f64>,
    speed: Vec<f64>,
    ratio: Vec<f64>,
    guide: Vec<f64>,
    /// Cage rotation speed, rad/s.
    w_cage: Vec<f64>,
    /// Pocket normal force of each ball at each sample, N.
    pockets: Vec<Vec<f64>>,
    /// Powers on the cage at each sample: pocket, pocket whirl, guide, guide whirl, drag, W.
    powers: Vec<[f64; 5]>,
    /// Kinetic energy of the cage at each sample, from its states: of the centre's motion
    /// (`mc |v|² / 2`, the whirl) and in all (with the spin and tilt rates), J.
    ke: Vec<[f64; 2]>,
    cpu: f64,
}

/// Kinetic energy of the free cage from its state block `[x, y, z, bx, by, theta, vx, vy,
/// vz, bx', by', w_c]` (scaled by the model's length `l` and time `t0`): the centre's
/// `mc |v|² / 2` and the total with `ip w² / 2 + it (bx'² + by'²) / 2`, J (the energy whose
/// rate is the power of the cage's forces and moments in the level's equations,
/// docs/physics.md §5.5).
fn cage_energy(b: &raceway::geometry::Bearing, x: &[f64], l: f64, t0: f64) -> [f64; 2] {
    let (cri, cro, cw) = (
        0.5 * b.cage.inner_diameter,
        0.5 * b.cage.outer_diameter,
        b.cage.width,
    );
    let (mc, ip) = (b.cage.mass, b.cage.inertia);
    let it = mc * ((cri * cri + cro * cro) / 4.0 + cw * cw / 12.0);
    let v = l / t0;
    let v2 = (x[6] * v).powi(2) + (x[7] * v).powi(2) + (x[8] * v).powi(2);
    let whirl = 0.5 * mc * v2;
    let (bx, by, w) = (x[9] / t0, x[10] / t0, x[11] / t0);
    [
        whirl,
        whirl + 0.5 * ip * w * w + 0.5 * it * (bx * bx + by * by),
    ]
}

fn var(name: &str) -> u32 {
    variables::by_name(name).expect("a contract variable").vr
}

/// Step the scene's component at its `[run]` step with the scene's initial (motion) inputs
/// and speed ramp, recording the cage outputs and, from the model re-evaluated at each
/// recorded state, the per-ball pocket forces and the cage powers.
fn simulate(scene: &Scene) -> Result<Record, Box<dyn std::error::Error>> {
    if scene.model.causality != Causality::Motion {
        return Err("the study's scenes are motion-driven".into());
    }
    let b = scene.build_bearing()?;
    let mut model = FullModel::new(&b, scene.model.full.params(&b, scene.model.race_control)?)?;
    let na = model.n_aux();
    let mut dx = vec![0.0; model.n_states()];
    let mut c = Component::new(scene.clone())?;
    let init = |n: &str| scene.inputs.initial_value(n);
    let ramp = raceway::units::rpm_to_rad_s(scene.run.speed_ramp_rpm_per_s);
    let omega0 = init("shaft.omega");
    let names = [
        "shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry", "shaft.vx", "shaft.vy",
        "shaft.vz", "shaft.wx", "shaft.wy",
    ];
    let q = [0, 1, 2, 3, 4].map(|k| init(names[k]));
    let v = [5, 6, 7, 8, 9].map(|k| init(names[k]));
    let set = |c: &mut Component, t: f64| -> Result<f64, Box<dyn std::error::Error>> {
        for n in names {
            c.set_real(var(n), init(n))?;
        }
        let omega = omega0 + ramp * t;
        c.set_real(var("shaft.omega"), omega)?;
        if ramp != 0.0 {
            c.set_input_derivative(var("shaft.omega"), 1, ramp)?;
        }
        Ok(omega)
    };
    let n = (scene.run.duration_s / scene.run.step_s).round().max(1.0) as usize;
    let h = scene.run.duration_s / n as f64;
    let mut r = Record {
        pockets: vec![Vec::with_capacity(n + 1); b.z],
        ..Record::default()
    };
    let (l, t0) = model.scales();
    // The cage block of the free cage: `[x, y, z, bx, by, theta, vx, vy, vz, bx', by', w_c T0]`.
    let cage_w = |x: &[f64]| x[11] / t0;
    let cpu0 = raceway::report::thread_cpu_s();
    set(&mut c, 0.0)?;
    c.refresh_outputs()?;
    for i in 0..=n {
        let t = i as f64 * h;
        if i > 0 {
            set(&mut c, t - h)?;
            c.do_step(t - h, h)?;
        }
        let omega = omega0 + ramp * t;
        let st = c.get_state();
        let mut aux = st.aux[..na].to_vec();
        let tot = model.eval(&q, &v, omega, &st.x, &mut aux, &mut dx)?;
        r.t.push(t);
        r.cx.push(c.get_real(var("cage.x"))?);
        r.cy.push(c.get_real(var("cage.y"))?);
        r.speed.push(c.get_real(var("cage.speed"))?);
        r.ratio.push(c.get_real(var("cage.speed_ratio"))?);
        r.guide.push(c.get_real(var("guide.force"))?);
        r.w_cage.push(cage_w(&st.x));
        for (j, p) in r.pockets.iter_mut().enumerate() {
            p.push(model.balls[j].pocket);
        }
        r.powers.push([
            tot.pocket_power,
            tot.pocket_power_whirl,
            tot.guide_power,
            tot.guide_power_whirl,
            tot.cage_drag_power,
        ]);
        r.ke.push(cage_energy(&b, &st.x, l, t0));
    }
    r.cpu = raceway::report::thread_cpu_s() - cpu0;
    Ok(r)
}

/// One speed's results.
#[derive(Debug, Clone)]
struct Row {
    rpm: f64,
    /// Sigma over each window.
    sigmas: Vec<f64>,
    orbit_max: f64,
    orbit_mean: f64,
    guide_mean: f64,
    pocket_peak: f64,
    ratio: f64,
    /// Whirl and cage rotation frequencies over the last window, Hz.
    f_whirl: f64,
    f_cage: f64,
    /// Energies per cage revolution over the last window (pocket, pocket whirl, guide,
    /// guide whirl, drag), J.
    energy: [f64; 5],
    /// The energy balance per cage revolution over the last window (time integrals).
    balance: Balance,
    cpu_per_rev: f64,
    /// Orbit over the last window, guide clearances.
    ox: Vec<f64>,
    oy: Vec<f64>,
}

impl Row {
    fn sigma(&self) -> f64 {
        *self.sigmas.last().unwrap_or(&f64::NAN)
    }
    /// Relative change of sigma between the last two windows.
    fn change(&self) -> f64 {
        let n = self.sigmas.len();
        if n < 2 {
            return f64::NAN;
        }
        (self.sigmas[n - 1] - self.sigmas[n - 2]).abs() / self.sigmas[n - 1]
    }
}

fn scene_for(rpm: f64, cfg: Config, o: &Opts) -> Result<Scene, Box<dyn std::error::Error>> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes")
        .join(format!("7004-{}.toml", rpm.round() as i64));
    let mut s = Scene::from_text(&std::fs::read_to_string(&path)?)?;
    s.run.duration_s = o.duration;
    s.run.step_s = o.step;
    s.model.full.guidance = Some(cfg.guidance);
    s.model.full.cage_unbalance_um = o.unbalance_um;
    if let Some(r) = o.rtol {
        s.solver.rtol = r;
    }
    apply_oil(&mut s, o)?;
    if cfg.diametral {
        let mut spec = preset("7004")?;
        spec.cage.guide_clearance_mm = Some(0.125);
        s.bearing = raceway::component::scene::BearingRef::Table(toml::Table::try_from(&spec)?);
    }
    Ok(s)
}

fn run_one(rpm: f64, cfg: Config, o: &Opts) -> Result<Row, Box<dyn std::error::Error>> {
    let scene = scene_for(rpm, cfg, o)?;
    let r = simulate(&scene)?;
    let n = r.t.len();
    let nw = o.windows.max(1);
    let wl = (n - 1) / nw;
    let sigmas: Vec<f64> = (0..nw)
        .map(|k| whirl_index(&r.speed[1 + k * wl..1 + (k + 1) * wl]).unwrap_or(f64::NAN))
        .collect();
    let last = 1 + (nw - 1) * wl..n;
    let rad: Vec<f64> = r.cx.iter().zip(&r.cy).map(|(x, y)| x.hypot(*y)).collect();
    let orbit_max = rad.iter().fold(0.0f64, |m, v| m.max(*v));
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let orbit_mean = mean(&rad[last.clone()]);
    let guide_mean = mean(&r.guide[last.clone()]);
    let pocket_peak = r
        .pockets
        .iter()
        .flat_map(|p| p[last.clone()].iter())
        .fold(0.0f64, |m, v| m.max(*v));
    // Whirl: mean rate of the unwrapped polar angle of the orbit.
    let mut ang = 0.0;
    let mut prev = r.cy[last.start].atan2(r.cx[last.start]);
    for k in last.clone().skip(1) {
        let a = r.cy[k].atan2(r.cx[k]);
        let mut d = a - prev;
        d -= 2.0 * PI * (d / (2.0 * PI)).round();
        ang += d;
        prev = a;
    }
    let span = r.t[n - 1] - r.t[last.start];
    let f_whirl = ang / (2.0 * PI * span);
    let w_c = mean(&r.w_cage[last.clone()]);
    let f_cage = w_c / (2.0 * PI);
    let mut energy = [0.0; 5];
    for (e, k) in energy.iter_mut().zip(0..5) {
        // Mean power times the cage revolution period.
        *e = mean(
            &r.powers[last.clone()]
                .iter()
                .map(|p| p[k])
                .collect::<Vec<_>>(),
        ) / f_cage;
    }
    let balance = balance(&r, last.clone(), span * f_cage);
    Ok(Row {
        rpm,
        balance,
        sigmas,
        orbit_max,
        orbit_mean,
        guide_mean,
        pocket_peak,
        ratio: *r.ratio.last().unwrap_or(&f64::NAN),
        f_whirl,
        f_cage,
        energy,
        cpu_per_rev: r.cpu / (rpm / 60.0 * o.duration),
        ox: r.cx[last.clone()].to_vec(),
        oy: r.cy[last].to_vec(),
    })
}

/// One configuration's rows and its three Markdown tables (main, convergence, energy).
type Tables = (Vec<Row>, String, String, String);

fn study(cfg: Config, o: &Opts) -> Result<Tables, Box<dyn std::error::Error>> {
    let mut rows = Vec::new();
    let mut main = String::from(
        "| speed, rpm | sigma (last window) | change from the window before | orbit max / Cg | orbit mean / Cg | guide force mean, N | pocket peak, N | cage speed ratio | whirl / cage frequency | CPU per shaft rev, ms |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut conv = String::from("| speed, rpm |");
    for k in 0..o.windows {
        let w = o.duration / o.windows as f64;
        write!(
            conv,
            " {:.0}–{:.0} ms |",
            k as f64 * w * 1e3,
            (k + 1) as f64 * w * 1e3
        )?;
    }
    conv += "\n|---|";
    for _ in 0..o.windows {
        conv += "---|";
    }
    conv += "\n";
    let mut energy = String::from(
        "| speed, rpm | pocket, mJ | of it whirl, mJ | guide land, mJ | of it whirl, mJ | drag, mJ | sum, mJ |\n|---|---|---|---|---|---|---|\n",
    );
    for &rpm in &o.speeds {
        let r = run_one(rpm, cfg, o)?;
        eprintln!(
            "  {rpm:.0} rpm: {:.1} ms of thread CPU per shaft rev (load average {}); per cage rev: net work {:.3e} mJ, its kinetic energy's change {:.3e} mJ (whirl {:.3e}, {:.3e})",
            r.cpu_per_rev * 1e3,
            raceway::report::load_average(),
            r.balance.net() * 1e3,
            r.balance.dke * 1e3,
            r.balance.whirl_net() * 1e3,
            r.balance.dke_whirl * 1e3
        );
        writeln!(
            main,
            "| {:.0} | {:.4} | {:.0} % | {:.3} | {:.3} | {:.3e} | {:.2} | {:.4} | {:.0} / {:.0} Hz = {:.3} | {:.1} |",
            r.rpm,
            r.sigma(),
            100.0 * r.change(),
            r.orbit_max,
            r.orbit_mean,
            r.guide_mean,
            r.pocket_peak,
            r.ratio,
            r.f_whirl,
            r.f_cage,
            r.f_whirl / r.f_cage,
            r.cpu_per_rev * 1e3
        )?;
        write!(conv, "| {:.0} |", r.rpm)?;
        for s in &r.sigmas {
            write!(conv, " {s:.4} |")?;
        }
        conv += "\n";
        let e = r.energy.map(|v| v * 1e3);
        writeln!(
            energy,
            "| {:.0} | {:.3e} | {:.3e} | {:.3e} | {:.3e} | {:.3e} | {:.1e} |",
            r.rpm,
            e[0],
            e[1],
            e[2],
            e[3],
            e[4],
            e[0] + e[2] + e[4]
        )?;
        eprintln!("{}: {rpm} rpm done", cfg.label());
        rows.push(r);
    }
    Ok((rows, main, conv, energy))
}

/// Start-up from rest: ball–pocket impacts over the first `ms` milliseconds and the cage
/// speed history.
struct Startup {
    impacts: usize,
    impacts_per_ball: Vec<usize>,
    threshold: f64,
    /// Impacts counted at a tenth of the threshold.
    impacts_low: usize,
    z: usize,
    t: Vec<f64>,
    ratio: Vec<f64>,
    w_cage: Vec<f64>,
    w_kin: Vec<f64>,
    pocket_max: Vec<f64>,
}

/// An impact: a ball's pocket force rising through `threshold` (counted once until it
/// falls below half of it again, so a contact that chatters around the threshold counts
/// once).
fn count_impacts(p: &[f64], threshold: f64) -> usize {
    let mut n = 0;
    let mut on = false;
    for &f in p {
        if !on && f >= threshold {
            n += 1;
            on = true;
        } else if on && f < 0.5 * threshold {
            on = false;
        }
    }
    n
}

fn startup(ms: f64, step: f64, o: &Opts) -> Result<Startup, Box<dyn std::error::Error>> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/7004-startup.toml");
    let mut s = Scene::from_text(&std::fs::read_to_string(&path)?)?;
    apply_oil(&mut s, o)?;
    s.run.duration_s = ms * 1e-3;
    s.run.step_s = step;
    let b = s.build_bearing()?;
    let r = simulate(&s)?;
    // Threshold: 1 % of the ball's share of the axial load, Fa/Z (the scale of the race
    // loads that drive the balls), i.e. 2.5 N for the study.
    let threshold = 0.01 * 2000.0 / b.z as f64;
    let impacts_per_ball: Vec<usize> = r
        .pockets
        .iter()
        .map(|p| count_impacts(p, threshold))
        .collect();
    let ramp = raceway::units::rpm_to_rad_s(s.run.speed_ramp_rpm_per_s);
    let w_kin: Vec<f64> =
        r.t.iter()
            .map(|t| raceway::component::levels::cage_speed(&b, ramp * t))
            .collect();
    let pocket_max: Vec<f64> = (0..r.t.len())
        .map(|k| r.pockets.iter().fold(0.0f64, |m, p| m.max(p[k])))
        .collect();
    Ok(Startup {
        impacts: impacts_per_ball.iter().sum(),
        impacts_low: r
            .pockets
            .iter()
            .map(|p| count_impacts(p, 0.1 * threshold))
            .sum(),
        z: b.z,
        impacts_per_ball,
        threshold,
        t: r.t,
        ratio: r.ratio,
        w_cage: r.w_cage,
        w_kin,
        pocket_max,
    })
}

fn parse() -> Result<(Opts, bool, bool), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut o = Opts {
        speeds: vec![30_000.0, 60_000.0, 80_000.0, 120_000.0],
        duration: 0.15,
        windows: 5,
        step: 1e-5,
        unbalance_um: 0.0,
        startup_ms: 10.0,
        config: None,
        oil_temp_c: None,
        constant_4109: false,
        rtol: None,
        with_oil: false,
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
            "--duration" => o.duration = val()?,
            "--windows" => o.windows = val()? as usize,
            "--step" => o.step = val()?,
            "--unbalance-um" => o.unbalance_um = val()?,
            "--startup-ms" => o.startup_ms = val()?,
            "--oil-temp-c" => o.oil_temp_c = Some(val()?),
            "--constant-4109" => o.constant_4109 = true,
            "--rtol" => o.rtol = Some(val()?),
            "--with-oil" => o.with_oil = true,
            "--config" => {
                i += 1;
                let t = args.get(i).ok_or("--config needs a tag")?;
                if !CONFIGS.iter().any(|c| &c.tag() == t) {
                    return Err(format!("unknown --config `{t}`").into());
                }
                o.config = Some(t.clone());
            }
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
        o.windows = 2;
        o.step = 2e-5;
        o.startup_ms = 2.0;
    }
    if o.windows == 0 || !(o.duration > 0.0 && o.step > 0.0) {
        return Err("--windows, --duration and --step must be positive".into());
    }
    Ok((o, quick, docs))
}

const CONFIGS: [Config; 4] = [
    Config {
        guidance: Guidance::OuterRing,
        diametral: false,
    },
    Config {
        guidance: Guidance::OuterRing,
        diametral: true,
    },
    Config {
        guidance: Guidance::InnerRing,
        diametral: false,
    },
    Config {
        guidance: Guidance::InnerRing,
        diametral: true,
    },
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (o, quick, docs) = parse()?;
    println!(
        "cage whirl, 7004, Fa 2000 N, Fr 400 N: {} s per speed in {} windows, communication step {} s, cage unbalance {} µm{}{}",
        o.duration,
        o.windows,
        o.step,
        o.unbalance_um,
        if quick { " (quick)" } else { "" },
        match o.oil_temp_c {
            Some(t) => format!(
                "; MIL-L-7808 at {t} °C with the 4109 traction fit ({}; {})",
                if o.constant_4109 { "constant set" } else { "power laws" },
                raceway::contact::traction::FIT_4109_LABEL
            ),
            None => String::new(),
        }
    );
    let configs: Vec<Config> = match (&o.config, quick) {
        (_, true) => CONFIGS[..1].to_vec(),
        (Some(t), _) => CONFIGS.iter().filter(|c| &c.tag() == t).copied().collect(),
        (None, _) => CONFIGS.to_vec(),
    };
    let mut all = Vec::new();
    for &cfg in &configs {
        let (rows, main, conv, energy) = study(cfg, &o)?;
        println!("\n{}\n\n{main}\n{conv}\n{energy}", cfg.label());
        if quick {
            // The CI check: finite, inside the clearance (wall spring beyond eps_max).
            for r in &rows {
                if !(r.sigma().is_finite() && r.orbit_max < 1.5 && r.ratio.is_finite()) {
                    return Err(format!("bad result at {} rpm: {r:?}", r.rpm).into());
                }
            }
        }
        all.push((cfg, rows, main, conv, energy));
    }
    let st = startup(o.startup_ms, if quick { 2e-5 } else { 5e-6 }, &o)?;
    // The page's second part: study [0]'s oil at two bulk temperatures, every configuration.
    let mut oils = Vec::new();
    if docs && o.with_oil && o.oil_temp_c.is_none() {
        for t in OIL_TEMPS_C {
            let ot = Opts {
                oil_temp_c: Some(t),
                ..o.clone()
            };
            let mut sets = Vec::new();
            for &cfg in &configs {
                let (rows, main, conv, energy) = study(cfg, &ot)?;
                println!(
                    "\nMIL-L-7808 at {t} °C, 4109 fit: {}\n\n{main}\n{conv}\n{energy}",
                    cfg.label()
                );
                sets.push((cfg, rows, main, conv, energy));
            }
            let st_oil = startup(o.startup_ms, 5e-6, &ot)?;
            oils.push((t, sets, st_oil));
        }
    }
    println!(
        "start-up from rest, first {} ms: {} ball–pocket impacts (pocket force rising through {:.2} N), per ball {:?}; {} through {:.2} N; largest pocket force {:.3} N; cage speed ratio at the end {:.3}",
        o.startup_ms,
        st.impacts,
        st.threshold,
        st.impacts_per_ball,
        st.impacts_low,
        0.1 * st.threshold,
        st.pocket_max.iter().fold(0.0f64, |m, v| m.max(*v)),
        st.ratio.last().unwrap_or(&f64::NAN)
    );
    if docs {
        if o.config.is_some() {
            return Err("--write-docs runs every configuration (drop --config)".into());
        }
        if o.oil_temp_c.is_some() {
            return Err("--write-docs writes the page of the scenes' own oil and traction (drop --oil-temp-c)".into());
        }
        write_docs(&o, &all, &st, &oils)?;
    }
    Ok(())
}

type Study = (Config, Vec<Row>, String, String, String);

/// Bulk oil temperatures of the page's MIL-L-7808 part, °C: 100 (stated: MIL-L-7808 has
/// 2.87 mPa s there, the scenes' 0.003 Pa s, so the traction law is what changes) and 60.
const OIL_TEMPS_C: [f64; 2] = [100.0, 60.0];

/// One temperature's runs: the temperature, each configuration, the start-up.
type OilSet = (f64, Vec<Study>, Startup);

/// The page's MIL-L-7808 part: tables per temperature and configuration, and the plain
/// verdict on the trend computed from them.
fn oil_section(
    o: &Opts,
    coulomb: &[Study],
    oils: &[OilSet],
) -> Result<String, Box<dyn std::error::Error>> {
    let mut md = String::new();
    writeln!(
        md,
        "\n## Study [0]'s oil: MIL-L-7808 with the 4109 traction fit\n\n\
         The same runs (same scenes, speeds, durations, windows) with the study's oil: the level's viscosity \
         (drag, pockets, guide land) is MIL-L-7808's at the bulk temperature T (docs/physics.md §6.2: public code, \
         medium confidence), and the race traction is the `fitted_4109` law at T with MIL-L-7808's data \
         (`--oil-temp-c T`; docs/physics.md §5.2): **{}**. The study gives no bulk temperature: T = 100 °C is the \
         one stated here (MIL-L-7808 has 2.87 mPa s there, close to the scenes' 0.003 Pa s, so what changes is the \
         traction law), and 60 °C (6.56 mPa s) the second. Open questions of the fit, which these runs cannot \
         settle: whether its T is in °C (as coded, used here) or K; which radius R it means (the contact's Rx here); \
         whether its eta0 follows the temperature (here: MIL-L-7808's at T).\n",
        raceway::contact::traction::FIT_4109_LABEL
    )?;
    let first_last = |rows: &[Row]| (rows[0].sigma(), rows[rows.len() - 1].sigma());
    let mut falls = 0;
    let mut total = 0;
    writeln!(md, "| bulk T | configuration | sigma, {} rpm | whirl / cage frequency, same speeds | sigma at the top speed / at the lowest |\n|---|---|---|---|---|",
        o.speeds.iter().map(|s| format!("{s:.0}")).collect::<Vec<_>>().join(" → "))?;
    let row_line = |md: &mut String, t: &str, cfg: &Config, rows: &[Row]| -> std::fmt::Result {
        let (a, b) = first_last(rows);
        writeln!(
            md,
            "| {t} | {} | {} | {} | {:.2} |",
            cfg.label(),
            rows.iter()
                .map(|r| format!("{:.4}", r.sigma()))
                .collect::<Vec<_>>()
                .join(" → "),
            rows.iter()
                .map(|r| format!("{:.3}", r.f_whirl / r.f_cage))
                .collect::<Vec<_>>()
                .join(" → "),
            b / a
        )
    };
    for (cfg, rows, ..) in coulomb {
        row_line(&mut md, "Coulomb, 0.003 Pa s", cfg, rows)?;
    }
    for (t, sets, _) in oils {
        for (cfg, rows, ..) in sets {
            row_line(&mut md, &format!("{t:.0} °C"), cfg, rows)?;
            let (a, b) = first_last(rows);
            total += 1;
            if b < a {
                falls += 1;
            }
        }
    }
    let outer_falls = oils
        .iter()
        .flat_map(|(_, sets, _)| sets.iter())
        .filter(|(c, r, ..)| c.guidance == Guidance::OuterRing && first_last(r).1 < first_last(r).0)
        .count();
    writeln!(
        md,
        "\n**Does the trend now fall?** {} Sigma at the top speed is below sigma at the lowest in {falls} of the {total} \
         runs with the study's oil ({outer_falls} of them on the outer-ring land, the study's guidance); the last column \
         of the table above is the evidence, the convergence tables below the check that the windows are settled.\n",
        if falls == total {
            "Yes."
        } else if falls == 0 {
            "No: the trend is still reversed."
        } else {
            "Only in part."
        }
    )?;
    for (t, sets, st) in oils {
        for (cfg, _, main, conv, energy) in sets {
            writeln!(
                md,
                "### {t:.0} °C, {}\n\n{main}\nSigma over successive windows:\n\n{conv}\n\
                 Cage energy per cage revolution over the last window:\n\n{energy}",
                cfg.label()
            )?;
        }
        writeln!(
            md,
            "Start-up from rest at {t:.0} °C, first {} ms: **{} ball–pocket impacts** (threshold {:.2} N); {} through a tenth of it; \
             largest pocket force {:.3} N.\n",
            o.startup_ms,
            st.impacts,
            st.threshold,
            st.impacts_low,
            st.pocket_max.iter().fold(0.0f64, |m, v| m.max(*v)),
        )?;
    }
    Ok(md)
}

fn write_docs(
    o: &Opts,
    all: &[Study],
    st: &Startup,
    oils: &[OilSet],
) -> Result<(), Box<dyn std::error::Error>> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs");
    std::fs::create_dir_all(&dir)?;
    #[cfg(feature = "plot")]
    plots(&dir, all, st)?;
    let here = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut md = String::new();
    md += &std::fs::read_to_string(here.join("cage_whirl_head.md"))?;
    writeln!(
        md,
        "\n## Results\n\n{} s simulated per speed from the quasi-static start, communication step {} s; \
         statistics over the last of {} equal windows ({:.0} ms); cage unbalance {} µm.\n",
        o.duration,
        o.step,
        o.windows,
        o.duration / o.windows as f64 * 1e3,
        o.unbalance_um
    )?;
    md += "![sigma vs speed](cage-whirl-sigma.png)\n\n![whirl frequency over cage frequency](cage-whirl-frequency.png)\n\n";
    for (cfg, _, main, conv, energy) in all {
        writeln!(
            md,
            "### {}\n\n{main}\nSigma over successive windows (convergence check):\n\n{conv}\n\
             Cage energy per cage revolution over the last window (work done on the cage; \
             \"whirl\" = the part through the centre's velocity):\n\n{energy}\n\
             ![orbits {}](cage-whirl-orbits-{}.png)\n",
            cfg.label(),
            cfg.label(),
            cfg.tag()
        )?;
    }
    writeln!(
        md,
        "### Start-up from rest (`7004-startup.toml`, 0 to 30 000 rpm in 50 ms, outer-ring land, Cg 0.25 mm)\n\n\
         Over the first {} ms: **{} ball–pocket impacts** (a ball's pocket force rising through {:.2} N = 1 % of Fa/Z, \
         counted again only after falling below half of it); per ball {:?}; {} rising through a tenth of that ({:.2} N); \
         largest pocket force {:.3} N. Cage speed ratio (cage / kinematic) at {} ms: {:.3}.\n\n\
         ![start-up cage speed](cage-whirl-startup.png)\n\n![start-up pocket force](cage-whirl-startup-pocket.png)\n",
        o.startup_ms,
        st.impacts,
        st.threshold,
        st.impacts_per_ball,
        st.impacts_low,
        0.1 * st.threshold,
        st.pocket_max.iter().fold(0.0f64, |m, v| m.max(*v)),
        o.startup_ms,
        st.ratio.last().unwrap_or(&f64::NAN)
    )?;
    md += &std::fs::read_to_string(here.join("cage_whirl_tail.md"))?;
    if !oils.is_empty() {
        md += &oil_section(o, all, oils)?;
        md += &balance_section(o, all, oils)?;
        #[cfg(feature = "plot")]
        energy_plot(&dir, o, all, oils)?;
    }
    std::fs::write(dir.join("cage-whirl.md"), md)?;
    Ok(())
}

#[cfg(feature = "plot")]
fn plots(dir: &Path, all: &[Study], st: &Startup) -> Result<(), Box<dyn std::error::Error>> {
    use raceway::plot::{plot, Axes, Series};
    let labels: Vec<String> = all.iter().map(|(c, ..)| c.label()).collect();
    let xs: Vec<Vec<f64>> = all
        .iter()
        .map(|(_, r, ..)| r.iter().map(|r| r.rpm).collect())
        .collect();
    let sig: Vec<Vec<f64>> = all
        .iter()
        .map(|(_, r, ..)| r.iter().map(|r| r.sigma()).collect())
        .collect();
    let fr: Vec<Vec<f64>> = all
        .iter()
        .map(|(_, r, ..)| r.iter().map(|r| r.f_whirl / r.f_cage).collect())
        .collect();
    fn lines<'a>(labels: &'a [String], xs: &'a [Vec<f64>], ys: &'a [Vec<f64>]) -> Vec<Series<'a>> {
        (0..labels.len())
            .map(|k| Series {
                label: &labels[k],
                x: &xs[k],
                y: &ys[k],
                points: false,
            })
            .collect()
    }
    plot(
        &dir.join("cage-whirl-sigma.png"),
        &Axes {
            title: "cage whirl index sigma vs shaft speed (7004, Fa 2000 N, Fr 400 N)",
            x_label: "shaft speed, rpm",
            y_label: "sigma = std(|v|)/mean(|v|), -",
            ..Axes::default()
        },
        &lines(&labels, &xs, &sig),
        &[],
    )?;
    let one = vec![1.0; xs[0].len()];
    let mut s = lines(&labels, &xs, &fr);
    s.push(Series {
        label: "whirl = cage frequency",
        x: &xs[0],
        y: &one,
        points: false,
    });
    plot(
        &dir.join("cage-whirl-frequency.png"),
        &Axes {
            title: "cage whirl frequency over cage rotation frequency (study [0] Fig. 11 reading)",
            x_label: "shaft speed, rpm",
            y_label: "f_whirl / f_cage, -",
            ..Axes::default()
        },
        &s,
        &[],
    )?;
    for (cfg, rows, ..) in all {
        orbit_plot(
            &dir.join(format!("cage-whirl-orbits-{}.png", cfg.tag())),
            rows,
            &format!("cage-centre orbits, last window: {}", cfg.label()),
        )?;
    }
    let t_ms: Vec<f64> = st.t.iter().map(|t| t * 1e3).collect();
    let rpm = |w: &[f64]| -> Vec<f64> { w.iter().map(|w| w * 30.0 / PI).collect() };
    let (wc, wk) = (rpm(&st.w_cage), rpm(&st.w_kin));
    plot(
        &dir.join("cage-whirl-startup.png"),
        &Axes {
            title: "start-up from rest: cage speed (7004, shaft 0 to 30 000 rpm in 50 ms)",
            x_label: "time, ms",
            y_label: "cage speed, rpm",
            ..Axes::default()
        },
        &[
            Series {
                label: "cage",
                x: &t_ms,
                y: &wc,
                points: false,
            },
            Series {
                label: "kinematic (no slip)",
                x: &t_ms,
                y: &wk,
                points: false,
            },
        ],
        &[],
    )?;
    let pl = format!("largest of the {} pockets", st.z);
    plot(
        &dir.join("cage-whirl-startup-pocket.png"),
        &Axes {
            title: "start-up from rest: largest ball-pocket force",
            x_label: "time, ms",
            y_label: "pocket force, N",
            ..Axes::default()
        },
        &[Series {
            label: &pl,
            x: &t_ms,
            y: &st.pocket_max,
            points: false,
        }],
        &[],
    )?;
    Ok(())
}

/// Orbits of `rows` (guide clearances) with the clearance circle.
#[cfg(feature = "plot")]
fn orbit_plot(path: &Path, rows: &[Row], title: &str) -> Result<(), Box<dyn std::error::Error>> {
    use raceway::plot::{plot, Axes, Series};
    let circle: (Vec<f64>, Vec<f64>) = (0..=200)
        .map(|k| {
            let a = 2.0 * PI * k as f64 / 200.0;
            (a.cos(), a.sin())
        })
        .unzip();
    let labels: Vec<String> = rows.iter().map(|r| format!("{:.0} rpm", r.rpm)).collect();
    let mut s: Vec<Series> = rows
        .iter()
        .zip(&labels)
        .map(|(r, l)| Series {
            label: l,
            x: &r.ox,
            y: &r.oy,
            points: false,
        })
        .collect();
    s.push(Series {
        label: "guide clearance",
        x: &circle.0,
        y: &circle.1,
        points: false,
    });
    plot(
        path,
        &Axes {
            title,
            x_label: "x / Cg, -",
            y_label: "y / Cg, -",
            equal: true,
            ..Axes::default()
        },
        &s,
        &[],
    )?;
    Ok(())
}
