//! The Exudyn peer rows of the speed page (issue #36): `peers/exudyn_bearing.py` (run by
//! `scripts/peer-exudyn`, which installs exudyn from PyPI into target/venv) builds a bearing
//! like Exudyn's ball-bearing test model and runs it at Exudyn's fixed step 1e-4 s and at a
//! 10× finer step; raceway runs the same geometry and load on the full level, with dynamic
//! ball contacts and with its default quasi-static ones, at [`rtol`] and at a tight
//! reference ([`REFERENCE_RTOL`]). Each side's accuracy is the relative L2 error of its bearing force at
//! the 0.1 ms points against its own refined run. Mounted by benches/speed.rs.

use raceway::component::{variables, Component, Scene};
use raceway::report::{force_error, thread_cpu_s, Samples};

/// One Exudyn run as the peer prints it.
#[derive(Debug, Clone, Copy)]
pub struct PeerRun {
    pub rpm: f64,
    pub step_s: f64,
    pub t_end_s: f64,
    pub cpu_s: f64,
    pub err_l2: Option<f64>,
}

/// Run the peer: `Err` with the reason when it cannot run (exudyn not installable, the
/// script failing).
pub fn run_peer(rpms: &[f64], t_end: f64, repeats: usize) -> Result<Vec<PeerRun>, String> {
    let rpm_arg = rpms
        .iter()
        .map(|r| format!("{r}"))
        .collect::<Vec<_>>()
        .join(",");
    let out = std::process::Command::new("scripts/peer-exudyn")
        .args([
            "--rpm",
            &rpm_arg,
            "--t-end",
            &format!("{t_end}"),
            "--repeats",
            &format!("{repeats}"),
        ])
        .output()
        .map_err(|e| format!("scripts/peer-exudyn: {e}"))?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        let tail: Vec<&str> = err.lines().rev().take(3).collect();
        return Err(format!(
            "scripts/peer-exudyn failed: {}",
            tail.into_iter().rev().collect::<Vec<_>>().join(" / ")
        ));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let mut runs = Vec::new();
    for line in text.lines().skip_while(|l| !l.starts_with("rpm,")).skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        if f.len() != 6 {
            continue;
        }
        let num = |s: &str| s.trim().parse::<f64>().map_err(|e| format!("{line}: {e}"));
        runs.push(PeerRun {
            rpm: num(f[0])?,
            step_s: num(f[1])?,
            t_end_s: num(f[2])?,
            cpu_s: num(f[3])?,
            err_l2: if f[5].trim().is_empty() {
                None
            } else {
                Some(num(f[5])?)
            },
        });
    }
    if runs.is_empty() {
        return Err(format!("scripts/peer-exudyn printed no run: {text}"));
    }
    Ok(runs)
}

/// Shaft of the Exudyn model: a steel cylinder 50 mm × 120 mm (its mass rides on the
/// bearing as raceway's attached mass, its weight as a radial load).
const SHAFT_MASS_KG: f64 = 7800.0 * std::f64::consts::PI * 0.025 * 0.025 * 0.120;

/// Raceway's scene on the geometry and load of the Exudyn model at `rpm`: a 6010-size
/// deep-groove bearing (14 balls of 8.73 mm on a 65 mm pitch diameter, groove radii 1.25×
/// the ball radius, f = 0.625, steel), zero clearance (the grooves' size before Exudyn's 1 %
/// ball enlargement: with Hertz steel contacts that 43.7 µm interference would preload each
/// ball by kilonewtons, against 218 N on Exudyn's linear 5e6 N/m springs), 200 N axial and
/// the shaft's weight, load-driven, the shaft's mass attached; traction 0.2 with Exudyn's
/// 0.01 m/s regularising speed; full level, `ball_contacts` dynamic or the default; RODAS4
/// at [`rtol`] (`atol_m` 1e-4 m of it: 1e-9 m at rtol 1e-5).
pub fn scene(rpm: f64, dynamic: bool) -> String {
    format!(
        "title = \"Exudyn ball-bearing test geometry at {rpm} rpm, 200 N axial, full level\"\n\
         [bearing]\nname = \"exudyn-6010\"\nkind = \"deep_groove\"\nball_diameter_mm = 8.73\n\
         pitch_diameter_mm = 65.0\nball_count = 14\ninner_curvature = 0.625\n\
         outer_curvature = 0.625\nclearance_um = 0.0\nbore_mm = 50.0\nouter_diameter_mm = 80.0\n\
         width_mm = 16.0\n\n[model]\nlevel = \"full\"\ncausality = \"load\"\n\
         attached_mass_kg = {SHAFT_MASS_KG}\n\n[model.full]\nball_contacts = \"{}\"\n\
         traction = {{ law = \"coulomb\", mu_max = 0.2, v_s = 0.01 }}\n\n\
         [solver]\nmethod = \"rosenbrock\"\nrtol = {rtol:e}\natol_m = {atol:e}\n\n\
         [inputs]\nrule = \"velocity\"\nspeed_rpm = {rpm}\n\
         initial = {{ \"load.x\" = 0.0, \"load.y\" = {}, \"load.z\" = 200.0, \"load.mx\" = 0.0, \"load.my\" = 0.0 }}\n\n\
         [run]\nduration_s = 0.05\nstep_s = 1e-4\n",
        if dynamic { "dynamic" } else { "quasi_static" },
        -9.81 * SHAFT_MASS_KG,
        rtol = rtol(dynamic),
        atol = if dynamic { 1e-8 } else { 1e-9 },
    )
}

/// RODAS4's relative tolerance of raceway's run: the 7004 scenes' 1e-5 with the default
/// (quasi-static) ball contacts; 1e-4 with dynamic ones, where the row compares speed at
/// equal or better accuracy than Exudyn's. Force errors over 0.05 s against the rtol 1e-8
/// run (`atol_m` scaled with rtol), rtol 1e-3 / 1e-4 / 1e-5: 3.5e-2 / 3.4e-2 / 2.5e-2 at
/// 3 000 rpm (a plateau: the contact onsets of the first milliseconds' ringing are not
/// resolved by the error estimate; 6.5e-4 at 1e-7, the reference's own level), 3.7e-1 /
/// 6.2e-2 / 4.8e-3 at 30 000 rpm; Exudyn at its 1e-4 s step against its 1e-5 s run: 6.2e-2
/// and 5.2e-1. 1e-4 is one decade looser than the shipped scenes and stays within
/// Exudyn's error at both speeds by a factor 1.8 and 8 (1e-3 would too, by 1.8 and 1.4:
/// not used). docs/history.md, "Exudyn peer: the dynamic-contact Jacobian and the
/// tolerance".
pub fn rtol(dynamic: bool) -> f64 {
    if dynamic {
        1e-4
    } else {
        1e-5
    }
}

/// The reference run's relative tolerance (its `atol_m` 1e-12 m): the same for every
/// case, so a row's tolerance does not move its reference.
pub const REFERENCE_RTOL: f64 = 1e-8;

fn vr(n: &str) -> u32 {
    variables::by_name(n)
        .unwrap_or_else(|| panic!("no variable {n}"))
        .vr
}

/// Load-driven run of `scene` in 0.1 ms steps for `t_end`, reading the force every step:
/// (thread CPU s of the whole run, forces at the points).
pub fn raceway_run(scene: &Scene, t_end: f64) -> Result<(f64, Samples), String> {
    let h = 1e-4;
    let mut c = Component::new(scene.clone()).map_err(|e| e.to_string())?;
    let init = |n: &str| scene.inputs.initial_value(n);
    for name in [
        "load.x",
        "load.y",
        "load.z",
        "load.mx",
        "load.my",
        "shaft.omega",
    ] {
        c.set_real(vr(name), init(name))
            .map_err(|e| e.to_string())?;
    }
    let fv = [vr("force.x"), vr("force.y"), vr("force.z")];
    let n = (t_end / h).round() as usize;
    let mut s = Samples {
        t: Vec::with_capacity(n),
        f: Vec::with_capacity(n),
    };
    let c0 = thread_cpu_s();
    for i in 0..n {
        c.do_step(i as f64 * h, h).map_err(|e| e.to_string())?;
        let mut f = [0.0; 3];
        for (x, &v) in f.iter_mut().zip(&fv) {
            *x = c.get_real(v).map_err(|e| e.to_string())?;
        }
        s.t.push(c.time());
        s.f.push(f);
    }
    Ok((thread_cpu_s() - c0, s))
}

/// Raceway on the Exudyn geometry: for the row's tolerance ([`rtol`]) and then each of
/// `more` (`atol_m` scaled as 1e-4 m × rtol), (rtol, CPU s over `t_end`, force error
/// against the run at [`REFERENCE_RTOL`]), the reference run once.
pub fn raceway_case(
    rpm: f64,
    dynamic: bool,
    t_end: f64,
    more: &[f64],
) -> Result<Vec<(f64, f64, f64)>, String> {
    let scene = Scene::from_text(&scene(rpm, dynamic)).map_err(|e| e.to_string())?;
    let mut tight = scene.clone();
    tight.solver.rtol = REFERENCE_RTOL;
    tight.solver.atol_m = 1e-12;
    let (_, reference) = raceway_run(&tight, t_end)?;
    let mut out = Vec::new();
    let settings = std::iter::once((scene.solver.rtol, scene.solver.atol_m))
        .chain(more.iter().map(|&r| (r, r * 1e-4)));
    for (rtol, atol) in settings {
        let mut sc = scene.clone();
        sc.solver.rtol = rtol;
        sc.solver.atol_m = atol;
        let (cpu, s) = raceway_run(&sc, t_end)?;
        let (err, _) = force_error(&s, &reference).map_err(|e| e.to_string())?;
        out.push((rtol, cpu, err));
    }
    Ok(out)
}
