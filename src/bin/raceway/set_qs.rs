//! `raceway quasi-static --scene SET.toml [--speed-rpm N] [--fx ..] .. [--my ..] [--json]`:
//! the quasi-static equilibrium of a scene's bearing set (`[set]`) under an external load on
//! the shaft at the set's reference point (`raceway::models::set::Set::solve`): the
//! reference point's wrench and displacement, the 5x5 stiffness there, and each row's loads,
//! contact angles, lift-off, life and ball table (the single bearing's table, row by row).

use raceway::component::{schema, Scene};
use raceway::error::{Error, Result};
use raceway::models::set::{Set, SetSolution};
use raceway::units::rpm_to_rad_s;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// The JSON document.
#[derive(Debug, Serialize)]
pub struct SetQsReport {
    /// The scene file.
    pub scene: String,
    /// `set`.
    pub element: &'static str,
    /// Shaft speed, rpm.
    pub speed_rpm: f64,
    /// External load on the shaft at the reference point `(Fx, Fy, Fz, Mx, My)`, N and N m.
    pub load: [f64; 5],
    /// The equilibrium (SI): displacement `q`, the set's force on the shaft, `stiffness`,
    /// the spring's shift, every row (with its balls) and the system life.
    pub solution: SetSolution,
}

impl SetQsReport {
    /// The document as JSON, its keys labelled from `raceway::summary::columns`
    /// (docs/columns.md).
    pub fn to_json(&self) -> serde_json::Value {
        use raceway::summary::columns::{to_labelled_json, Doc};
        to_labelled_json(Doc::QuasiStatic, self)
    }
}

/// The scene of `path` (checked as `raceway run` checks it).
pub fn read_scene(path: &Path) -> Result<Scene> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| Error::Io(format!("cannot read scene `{file}`: {e}")))?;
    schema::load(&text, &[]).map_err(|p| crate::scene_cmd::problems_error(&file, &p))
}

/// Solve the scene's set at `speed_rpm` (default: the scene's `inputs.speed_rpm`) under
/// `load` (what is not given: zero); `names` name the flags in refusals.
pub fn report(
    path: &Path,
    speed_rpm: Option<f64>,
    load: [Option<f64>; 5],
    names: ([&str; 5], &str),
) -> Result<SetQsReport> {
    let scene = read_scene(path)?;
    let bearing = scene.build_bearing()?;
    let Some(spec) = scene.set_spec(&bearing)? else {
        return Err(Error::invalid(
            "--scene",
            path.display(),
            "a scene with a [set] (a single bearing's quasi-static equilibrium: --bearing)",
        ));
    };
    let speed_rpm = speed_rpm.unwrap_or(scene.inputs.speed_rpm);
    if !(speed_rpm.is_finite() && speed_rpm >= 0.0) {
        return Err(Error::invalid(names.1, speed_rpm, "a finite number >= 0"));
    }
    let load = load.map(|v| v.unwrap_or(0.0));
    for (v, n) in load.iter().zip(names.0) {
        if !v.is_finite() {
            return Err(Error::invalid(n, v, "a finite number"));
        }
    }
    let mut set = Set::new(&spec)?;
    let solution = set.solve(&load, rpm_to_rad_s(speed_rpm))?;
    Ok(SetQsReport {
        scene: path.display().to_string(),
        element: "set",
        speed_rpm,
        load,
        solution,
    })
}

fn mrev(v: Option<f64>, rpm: f64) -> String {
    match v {
        Some(l) if rpm > 0.0 => format!("{l:.4e} Mrev = {:.4e} h", l * 1e6 / (60.0 * rpm)),
        Some(l) => format!("{l:.4e} Mrev"),
        None => "infinite (unloaded)".into(),
    }
}

/// The text report.
pub fn text(r: &SetQsReport) -> String {
    let mut s = String::new();
    let sol = &r.solution;
    let _ = writeln!(
        s,
        "Quasi-static equilibrium of the bearing set of {} ({} rows; Jones-Harris balls), {:.3} rpm",
        r.scene,
        sol.rows.len(),
        r.speed_rpm
    );
    let w = |s: &mut String, label: &str, v: &[f64; 5]| {
        let _ = writeln!(
            s,
            "{label:<38}Fx {:.3} N  Fy {:.3} N  Fz {:.3} N  Mx {:.4} N m  My {:.4} N m",
            v[0], v[1], v[2], v[3], v[4]
        );
    };
    w(&mut s, "external load at the reference point:", &r.load);
    let q = sol.q;
    let _ = writeln!(
        s,
        "shaft displacement at the reference:  x {:.4} µm  y {:.4} µm  z {:.4} µm  rx {:.5} mrad  ry {:.5} mrad",
        q[0] * 1e6,
        q[1] * 1e6,
        q[2] * 1e6,
        q[3] * 1e3,
        q[4] * 1e3
    );
    w(&mut s, "set force on the shaft there:", &sol.force);
    if sol.spring_shift != 0.0 {
        let _ = writeln!(
            s,
            "preload spring's shift:               {:.4} µm",
            sol.spring_shift * 1e6
        );
    }
    let _ = writeln!(
        s,
        "stiffness K at the reference point (SI: N/m, N/rad, N m/m, N m/rad), rows x y z rx ry:"
    );
    for row in &sol.stiffness {
        let _ = writeln!(
            s,
            "  {:>12.4e} {:>12.4e} {:>12.4e} {:>12.4e} {:>12.4e}",
            row[0], row[1], row[2], row[3], row[4]
        );
    }
    for (i, row) in sol.rows.iter().enumerate() {
        let f = row.force;
        let d = row.displacement;
        let _ = writeln!(
            s,
            "\nrow {i}: {} at {:+.3} mm, carrying shaft thrust toward {}; its own displacement x {:.4} µm  \
             y {:.4} µm  z {:.4} µm  rx {:.5} mrad  ry {:.5} mrad",
            row.bearing,
            row.position * 1e3,
            if row.orientation > 0 { "+z" } else { "-z" },
            d[0] * 1e6,
            d[1] * 1e6,
            d[2] * 1e6,
            d[3] * 1e3,
            d[4] * 1e3
        );
        let _ = writeln!(
            s,
            "  force on the shaft at the row (shaft frame): Fx {:.3} N  Fy {:.3} N  Fz {:.3} N  Mx {:.4} N m  My {:.4} N m",
            f[0], f[1], f[2], f[3], f[4]
        );
        let _ = writeln!(
            s,
            "  radial load {:.3} N, thrust {:.3} N; loaded {}/{}{}; axial stiffness {:.4} N/µm; life {}; S0 {}; \
             peak pressure {:.0} MPa",
            row.radial_load,
            row.axial_load,
            row.loaded_elements,
            row.element_loads.len(),
            if row.lifted_off { " (LIFTED OFF)" } else { "" },
            row.axial_stiffness * 1e-6,
            mrev(row.life_mrev, r.speed_rpm),
            row.s0.map_or("- (unloaded)".into(), |v| format!("{v:.3}")),
            row.peak_pressure * 1e-6
        );
        if row.balls.is_empty() {
            let _ = writeln!(
                s,
                "  {:>3} {:>9} {:>9} {:>9}",
                "j", "Q N", "a1 deg", "a2 deg"
            );
            for (j, (q, a)) in row
                .element_loads
                .iter()
                .zip(&row.contact_angles)
                .enumerate()
            {
                let _ = writeln!(
                    s,
                    "  {j:>3} {q:>9.2} {:>9.3} {:>9.3}",
                    a[0].to_degrees(),
                    a[1].to_degrees()
                );
            }
        } else {
            crate::report::ball_table(&mut s, &row.balls);
        }
    }
    let _ = writeln!(
        s,
        "\nForces and moments act on the shaft; moments about the reference point (the set) or the row's centre (a row). \
         Row lives: ball rows the ISO/TS 16281 reference life from the ball loads, roller rows ISO 281's."
    );
    let _ = writeln!(
        s,
        "system life of the set (Lundberg–Palmgren, every row): {}",
        mrev(sol.life_mrev, r.speed_rpm)
    );
    s
}
