//! `raceway quasi-static --bearing NAME` for a roller designation (and the Python
//! `quasi_static(bearing=...)` through the same functions): the roller equilibrium of
//! [`crate::models::quasi_static::rollers`], as the ball table is shaped (load, displacement,
//! force, stiffness, one row per element), plus each roller's lamina loads and pressures and
//! the edge stress, the 5×5 stiffness and the ISO 281/76 ratings.

use crate::error::{Error, Result};
use crate::geometry::roller::RollerBearing;
use crate::geometry::roller_catalogue;
use crate::models::quasi_static::rollers::{solve, RollerSolution};
use crate::ratings::lamina_life::{
    lamina_life, lamina_static_safety, LaminaLife, LaminaLifeOptions, EDGE_FACTOR_NOTE,
};
use crate::ratings::roller::{
    equivalent_dynamic_load, equivalent_static_load, l10_roller, roller_ratings,
};
use crate::units::rpm_to_rad_s;
use serde::Serialize;
use std::fmt::Write as _;

/// The JSON document.
#[derive(Debug, Serialize)]
pub struct RollerQsReport {
    /// Bearing designation.
    pub bearing: String,
    /// `roller`.
    pub element: &'static str,
    /// Shaft speed, rpm.
    pub speed_rpm: f64,
    /// External load `(Fx, Fy, Fz, Mx, My)` on the shaft, N and N m.
    pub load: [f64; 5],
    /// The equilibrium (SI): displacement, forces, `K`, every roller and lamina.
    pub solution: RollerSolution,
    /// ISO 281 `Cr`, ISO 76 `C0r`, N.
    pub cr: f64,
    /// ISO 76 `C0r`, N.
    pub c0r: f64,
    /// ISO 281 equivalent dynamic load `P`, N.
    pub p: f64,
    /// ISO 76 equivalent static load `P0`, N.
    pub p0: f64,
    /// `L10 = (Cr/P)^(10/3)`, million revolutions.
    pub l10_mrev: Option<f64>,
    /// Largest lamina pressure (inner contact), Pa.
    pub max_pressure: f64,
    /// Largest edge (end-lamina) pressure, Pa.
    pub max_edge_pressure: f64,
    /// ISO/TS 16281 reference rating life from the lamina loads with the edge-stress factor
    /// (`ratings::lamina_life`), inner ring rotating.
    pub lamina_life: LaminaLife,
    /// The same without the edge-stress factor (what the factor costs).
    pub lamina_life_without_edge_factor: LaminaLife,
    /// Static safety of the most loaded lamina, `(4000 MPa / max_pressure)²`.
    pub s0_lamina: Option<f64>,
    /// What in these figures is not sourced.
    pub notes: Vec<&'static str>,
}

impl RollerQsReport {
    /// The document as JSON, its keys labelled from [`super::columns`] (docs/columns.md):
    /// what `raceway quasi-static --bearing NU206 --json` prints and Python's
    /// `quasi_static` reads.
    pub fn to_json(&self) -> serde_json::Value {
        super::columns::to_labelled_json(super::columns::Doc::QuasiStatic, self)
    }
}

/// The roller bearing of a designation, `None` when `name` is not one.
pub fn roller_bearing(name: &str) -> Option<Result<RollerBearing>> {
    roller_catalogue::lookup(name).map(|s| s.build())
}

/// Solve and report (names of the five loads and the speed for refusals).
pub fn report(
    b: &RollerBearing,
    speed_rpm: f64,
    load: [f64; 5],
    names: ([&str; 5], &str),
) -> Result<RollerQsReport> {
    if !(speed_rpm.is_finite() && speed_rpm >= 0.0) {
        return Err(Error::invalid(names.1, speed_rpm, "a finite number >= 0"));
    }
    for (v, n) in load.iter().zip(names.0) {
        if !v.is_finite() {
            return Err(Error::invalid(n, v, "a finite number"));
        }
    }
    let sol = solve(b, load, rpm_to_rad_s(speed_rpm), names.0)?;
    let r = roller_ratings(b)?;
    let (fr, fa) = (load[0].hypot(load[1]), load[2]);
    let (p, ..) = equivalent_dynamic_load(b, fr, fa);
    let p0 = equivalent_static_load(b, fr, fa);
    let l10 = l10_roller(r.cr, p);
    let max_pressure = sol
        .rollers
        .iter()
        .flat_map(|x| x.lamina_pressure.iter())
        .fold(0.0, |a: f64, &v| a.max(v));
    let max_edge_pressure = sol
        .rollers
        .iter()
        .fold(0.0, |a: f64, x| a.max(x.edge_pressure));
    let inner: Vec<Vec<f64>> = sol
        .rollers
        .iter()
        .map(|x| x.lamina_load_inner.clone())
        .collect();
    let outer: Vec<Vec<f64>> = sol.rollers.iter().map(|x| x.lamina_load.clone()).collect();
    let life = lamina_life(b, &inner, &outer, LaminaLifeOptions::default())?;
    let life_plain = lamina_life(
        b,
        &inner,
        &outer,
        LaminaLifeOptions {
            edge_factor: false,
            ..LaminaLifeOptions::default()
        },
    )?;
    Ok(RollerQsReport {
        bearing: b.name.clone(),
        element: "roller",
        speed_rpm,
        load,
        solution: sol,
        cr: r.cr,
        c0r: r.c0r,
        p,
        p0,
        l10_mrev: l10.is_finite().then_some(l10),
        max_pressure,
        max_edge_pressure,
        lamina_life: life,
        lamina_life_without_edge_factor: life_plain,
        s0_lamina: lamina_static_safety(max_pressure),
        notes: vec![EDGE_FACTOR_NOTE],
    })
}

/// The text table.
pub fn text(r: &RollerQsReport) -> String {
    let mut s = String::new();
    let sol = &r.solution;
    let _ = writeln!(
        s,
        "Roller quasi-static equilibrium (ISO/TS 16281 laminae; rollers with their centrifugal force, tapered ones also with their gyroscopic moment): bearing {} ({} rollers), {:.3} rpm",
        r.bearing,
        sol.rollers.len(),
        r.speed_rpm
    );
    let w = |s: &mut String, label: &str, v: &[f64; 5]| {
        let _ = writeln!(
            s,
            "{label:<34}Fx {:.3} N  Fy {:.3} N  Fz {:.3} N  Mx {:.4} N m  My {:.4} N m",
            v[0], v[1], v[2], v[3], v[4]
        );
    };
    w(&mut s, "external load on the inner ring:", &r.load);
    let q = sol.q;
    let _ = writeln!(
        s,
        "ring displacement:                x {:.4} µm  y {:.4} µm  z {:.4} µm  rx {:.5} mrad  ry {:.5} mrad",
        q[0] * 1e6,
        q[1] * 1e6,
        q[2] * 1e6,
        q[3] * 1e3,
        q[4] * 1e3
    );
    w(&mut s, "bearing force on the shaft:", &sol.rollers_force);
    let _ = writeln!(
        s,
        "stiffness K (SI: N/m, N/rad, N m/m, N m/rad), rows x y z rx ry:"
    );
    for row in &sol.k {
        let _ = writeln!(
            s,
            "  {:>12.4e} {:>12.4e} {:>12.4e} {:>12.4e} {:>12.4e}",
            row[0], row[1], row[2], row[3], row[4]
        );
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "{:>3} {:>7} {:>9} {:>9} {:>9} {:>6} {:>6} {:>8} {:>8}  lamina loads N (first .. last)",
        "j", "psi deg", "Qi N", "Qo N", "Qf N", "pi GPa", "po GPa", "edge GPa", "laminae"
    );
    for (j, x) in sol.rollers.iter().enumerate() {
        let loaded = x.lamina_load.iter().filter(|v| **v > 0.0).count();
        let n = x.lamina_load.len();
        let lam = if n > 0 {
            format!(
                "{:.1} {:.1} .. {:.1} .. {:.1} {:.1}",
                x.lamina_load[0],
                x.lamina_load[1.min(n - 1)],
                x.lamina_load[n / 2],
                x.lamina_load[n.saturating_sub(2)],
                x.lamina_load[n - 1]
            )
        } else {
            String::new()
        };
        let _ = writeln!(
            s,
            "{:>3} {:>7.2} {:>9.2} {:>9.2} {:>9.2} {:>6.3} {:>6.3} {:>8.3} {:>3}/{:<4}  {lam}",
            j,
            x.psi.to_degrees(),
            x.load[0],
            x.load[1],
            x.flange_load,
            x.pressure[0] * 1e-9,
            x.pressure[1] * 1e-9,
            x.edge_pressure * 1e-9,
            loaded,
            n
        );
    }
    let _ = writeln!(
        s,
        "\nForces and moments act on the shaft; Qi/Qo inner/outer (cone/cup) contact loads, Qf the flange's; \
         p: peak line-Hertz pressure of the most loaded lamina; edge: the end laminae's inner-contact pressure; \
         every lamina's load and pressure are in --json."
    );
    let _ = writeln!(
        s,
        "ISO 281: Cr {:.0} N, P {:.1} N, L10 {} million revolutions; ISO 76: C0r {:.0} N, P0 {:.1} N, s0 {:.2}; \
         largest lamina pressure {:.3} GPa (static limit 4.000 GPa)",
        r.cr,
        r.p,
        r.l10_mrev
            .map(|v| format!("{v:.4e}"))
            .unwrap_or_else(|| "infinite".into()),
        r.c0r,
        r.p0,
        if r.p0 > 0.0 { r.c0r / r.p0 } else { f64::INFINITY },
        r.max_pressure * 1e-9
    );
    let mrev = |v: Option<f64>| {
        v.map(|v| format!("{v:.4e}"))
            .unwrap_or_else(|| "infinite".into())
    };
    let _ = writeln!(
        s,
        "ISO/TS 16281 from the lamina loads (inner ring rotating): L10r {} million revolutions with the edge-stress factor \
         (inner race {}, outer race {}), {} without it; P_ref {:.1} N. Static safety of the most loaded lamina \
         (4000 MPa / p_max)^2: {}",
        mrev(r.lamina_life.l10r_mrev),
        mrev(r.lamina_life.inner_mrev),
        mrev(r.lamina_life.outer_mrev),
        mrev(r.lamina_life_without_edge_factor.l10r_mrev),
        r.lamina_life.p_ref,
        r.s0_lamina
            .map(|v| format!("{v:.3}"))
            .unwrap_or_else(|| "unloaded".into())
    );
    for n in &r.notes {
        let _ = writeln!(s, "{n}.");
    }
    s
}

/// The columns a roller scene on the ring level keeps at full rate over the analysed window
/// for its lamina life ([`ring_lamina_life`]): the ring's displacement and the cage speed.
pub const RING_LAMINA_COLUMNS: [&str; 6] = [
    "shaft.x",
    "shaft.y",
    "shaft.z",
    "shaft.rx",
    "shaft.ry",
    "cage.omega",
];

/// Whether a run of `scene` on `bearing` gets the ring-level lamina life: a roller bearing
/// (cylindrical or tapered) on the ring level.
pub fn has_ring_lamina_life(scene: &crate::component::Scene, b: &crate::geometry::Bearing) -> bool {
    scene.model.level == crate::component::Level::Ring
        && matches!(&b.element, crate::geometry::element::Element::Roller(_))
}

/// ISO/TS 16281 lamina life of a ring-level roller run over its analysed window (the
/// second half, as the spectra): every recorded state's lamina loads, as the ring level
/// evaluated them (`models::ring::roller_loads`), gathered by `ratings::lamina_life::
/// LaminaWindow` (power means over the rollers and the states; docs/physics.md §R10). The
/// cage angle of each state is the run's final one (the level's state) less the trapezoid
/// integral of the recorded cage speed back to it (exact for a speed constant or linear in
/// time). Returns the life with and without the edge-stress factor and the number of states.
pub fn ring_lamina_life(
    scene: &crate::component::Scene,
    run: &crate::runner::Digest,
    comp: &crate::Component,
) -> Result<(LaminaLife, LaminaLife, usize)> {
    use crate::geometry::element::Element;
    let b = comp.bearing();
    let Element::Roller(rb) = &b.element else {
        return Err(Error::invalid("bearing.kind", "ball", "a roller bearing"));
    };
    let mut probe = crate::models::ring::roller_loads::RingLaminae::new(b, &scene.effects)?;
    let cols = RING_LAMINA_COLUMNS.map(|n| run.second_half(n));
    let n = cols.iter().map(|c| c.len()).max().unwrap_or(0);
    let omega_c = cols[5];
    if n == 0 || omega_c.len() != n {
        return Err(Error::invalid(
            "run",
            "no recorded window",
            "a run with recorded rows (shaft displacement and cage speed)",
        ));
    }
    let rows = run.rows.max(2);
    let dt = scene.run.duration_s / (rows - 1) as f64;
    let at = |c: &[f64], i: usize| c.get(i).copied().unwrap_or(0.0);
    let mut window = probe.window();
    let mut angle = comp.state().x.first().copied().unwrap_or(0.0);
    for i in (0..n).rev() {
        let q = [0, 1, 2, 3, 4].map(|k| at(cols[k], i));
        probe.add_state(&q, angle, &mut window);
        if i > 0 {
            angle -= 0.5 * dt * (omega_c[i] + omega_c[i - 1]);
        }
    }
    let life = window.life(rb, LaminaLifeOptions::default())?;
    let plain = window.life(
        rb,
        LaminaLifeOptions {
            edge_factor: false,
            ..LaminaLifeOptions::default()
        },
    )?;
    Ok((life, plain, n))
}

/// The summary's lines of [`ring_lamina_life`] (nothing for another bearing or level).
pub fn ring_lamina_life_lines(c: &super::Ctx, s: &mut super::Summary) {
    if !has_ring_lamina_life(c.scene, c.comp.bearing()) {
        return;
    }
    let mrev = |v: Option<f64>| {
        v.map(|v| format!("{v:.4e}"))
            .unwrap_or_else(|| "infinite".into())
    };
    match ring_lamina_life(c.scene, c.run, c.comp) {
        Ok((life, plain, n)) => {
            s.line(format!(
                "ISO/TS 16281 lamina life over the analysed window ({n} states, the rollers' lamina loads as the ring level evaluated them, inner ring rotating): \
                 L10r {} million revolutions with the edge-stress factor (inner race {}, outer race {}), {} without it; P_ref {:.1} N",
                mrev(life.l10r_mrev),
                mrev(life.inner_mrev),
                mrev(life.outer_mrev),
                mrev(plain.l10r_mrev),
                life.p_ref
            ));
            s.line(format!("{EDGE_FACTOR_NOTE}."));
            s.set(
                "lamina_life",
                serde_json::json!({
                    "states": n,
                    "with_edge_factor": life,
                    "without_edge_factor": plain,
                    "notes": [EDGE_FACTOR_NOTE],
                }),
            );
        }
        Err(e) => s.line(format!("lamina life: not available ({e})")),
    }
}
