//! Text and JSON reports of the `raceway` program (edge units in text: mm, µm, degrees,
//! rpm, GPa; SI in JSON).

use crate::Problem;
use raceway::component::scene::RaceControl;
use raceway::contact::{Curvature, PointContact, Race};
use raceway::geometry::{presets, Bearing, BearingKind};
use raceway::models::quasi_static::Solution;
use raceway::units::rad_s_to_rpm;
use raceway::{Error, Result};
use serde::Serialize;
use std::fmt::Write;

/// One preset, as `raceway bearings --json` lists it.
#[derive(Debug, Serialize)]
pub struct PresetRow {
    /// Designation.
    pub name: String,
    /// `deep_groove` or `angular_contact`.
    pub kind: BearingKind,
    /// Ball diameter, mm.
    pub ball_diameter_mm: f64,
    /// Pitch diameter, mm.
    pub pitch_diameter_mm: f64,
    /// Number of balls.
    pub ball_count: usize,
    /// Inner groove curvature ratio.
    pub inner_curvature: f64,
    /// Outer groove curvature ratio.
    pub outer_curvature: f64,
    /// Free contact angle, degrees.
    pub free_contact_angle_deg: f64,
    /// Nominal contact angle (0 for deep-groove), degrees.
    pub nominal_contact_angle_deg: f64,
    /// Diametral clearance, µm.
    pub clearance_um: f64,
    /// Groove-centre distance `A = (f_i + f_o - 1) D`, mm.
    pub groove_centre_distance_mm: f64,
    /// Ball mass, kg.
    pub ball_mass_kg: f64,
    /// Hertz constant, inner contact at the nominal angle, N/m^1.5.
    pub kc_inner: f64,
    /// Hertz constant, outer contact at the nominal angle, N/m^1.5.
    pub kc_outer: f64,
    /// Ball material.
    pub ball_material: String,
    /// Ring material (inner).
    pub ring_material: String,
    /// Where the data come from.
    pub source: String,
}

fn kc(b: &Bearing, race: Race) -> f64 {
    let (f, e) = match race {
        Race::Inner => (b.fi, b.e_eff_inner()),
        Race::Outer => (b.fo, b.e_eff_outer()),
    };
    PointContact::new(
        Curvature::ball_race(b.d, b.dm, b.nominal_contact_angle(), f, race),
        e,
    )
    .kc
}

fn row(spec_source: &str, b: &Bearing) -> PresetRow {
    PresetRow {
        name: b.name.clone(),
        kind: b.kind,
        ball_diameter_mm: b.d * 1e3,
        pitch_diameter_mm: b.dm * 1e3,
        ball_count: b.z,
        inner_curvature: b.fi,
        outer_curvature: b.fo,
        free_contact_angle_deg: b.alpha0.to_degrees(),
        nominal_contact_angle_deg: b.nominal_contact_angle().to_degrees(),
        clearance_um: b.pd * 1e6,
        groove_centre_distance_mm: b.a() * 1e3,
        ball_mass_kg: b.ball_mass(),
        kc_inner: kc(b, Race::Inner),
        kc_outer: kc(b, Race::Outer),
        ball_material: b.ball_material.name.clone(),
        ring_material: b.inner_material.name.clone(),
        source: spec_source.to_string(),
    }
}

fn json<T: Serialize>(v: &T) -> Result<String> {
    serde_json::to_string_pretty(v)
        .map(|s| s + "\n")
        .map_err(|e| Error::Io(format!("cannot write JSON: {e}")))
}

/// `raceway bearings`.
pub fn bearings(as_json: bool) -> Result<String> {
    let mut rows = Vec::new();
    for spec in presets() {
        let b = spec.build()?;
        rows.push(row(&spec.source, &b));
    }
    if as_json {
        return json(&rows);
    }
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<13} {:<15} {:>7} {:>7} {:>3} {:>6} {:>6} {:>7} {:>8} {:>7} {:>9} {:>10} {:>10}  balls/rings",
        "name", "kind", "D mm", "dm mm", "Z", "f_i", "f_o", "a0 deg", "Pd µm", "A mm", "ball kg",
        "Kc_i N/m1.5", "Kc_o N/m1.5"
    );
    for r in &rows {
        let kind = match r.kind {
            BearingKind::DeepGroove => "deep-groove",
            BearingKind::AngularContact => "angular-contact",
        };
        let _ = writeln!(
            s,
            "{:<13} {:<15} {:>7.3} {:>7.2} {:>3} {:>6.4} {:>6.4} {:>7.2} {:>8.2} {:>7.4} {:>9.3e} {:>10.4e} {:>10.4e}  {}/{}",
            r.name,
            kind,
            r.ball_diameter_mm,
            r.pitch_diameter_mm,
            r.ball_count,
            r.inner_curvature,
            r.outer_curvature,
            r.free_contact_angle_deg,
            r.clearance_um,
            r.groove_centre_distance_mm,
            r.ball_mass_kg,
            r.kc_inner,
            r.kc_outer,
            r.ball_material,
            r.ring_material
        );
    }
    let _ = writeln!(
        s,
        "a0: free contact angle; Kc at the nominal contact angle (0 for deep-groove)."
    );
    Ok(s)
}

fn control_name(c: RaceControl) -> &'static str {
    match c {
        RaceControl::Outer => "outer",
        RaceControl::None => "none",
    }
}

/// The JSON document of `raceway quasi-static --json`.
#[derive(Serialize)]
struct QsJson<'a> {
    bearing: &'a str,
    speed_rpm: f64,
    race_control: &'static str,
    /// Everything else in SI: the library's [`Solution`].
    solution: &'a Solution,
}

pub fn quasi_static_json(p: &Problem, sol: &Solution) -> Result<String> {
    json(&QsJson {
        bearing: &p.bearing.name,
        speed_rpm: p.speed_rpm,
        race_control: control_name(p.race_control),
        solution: sol,
    })
}

pub fn quasi_static_text(p: &Problem, sol: &Solution) -> String {
    let mut s = String::new();
    let b = &p.bearing;
    let _ = writeln!(
        s,
        "Jones-Harris quasi-static equilibrium: bearing {} ({} balls), {:.3} rpm, race control {}",
        b.name,
        b.z,
        p.speed_rpm,
        control_name(p.race_control)
    );
    let l = sol.load;
    let _ = writeln!(
        s,
        "external load on the inner ring:  Fx {:.3} N  Fy {:.3} N  Fz {:.3} N  Mx {:.4} N m  My {:.4} N m",
        l[0], l[1], l[2], l[3], l[4]
    );
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
    let f = sol.forces;
    let _ = writeln!(
        s,
        "bearing force on the shaft:       Fx {:.3} N  Fy {:.3} N  Fz {:.3} N  Mx {:.4} N m  My {:.4} N m",
        f[0], f[1], f[2], f[3], f[4]
    );
    let k = sol.stiffness;
    let _ = writeln!(
        s,
        "stiffness diagonal:               kxx {:.4} N/µm  kyy {:.4} N/µm  kzz {:.4} N/µm  krx {:.4} N m/mrad  kry {:.4} N m/mrad",
        k[0][0] * 1e-6,
        k[1][1] * 1e-6,
        k[2][2] * 1e-6,
        k[3][3] * 1e-3,
        k[4][4] * 1e-3
    );
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "{:>3} {:>7} {:>9} {:>9} {:>7} {:>7} {:>8} {:>8} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} {:>8} {:>8} {:>9} {:>10} {:>6} {:>6}",
        "j", "psi deg", "Qi N", "Qo N", "ai deg", "ao deg", "di µm", "do µm", "pi GPa", "po GPa",
        "ai mm", "bi mm", "ao mm", "bo mm", "Fc N", "Mg N m", "cage rpm", "spin rpm", "s/r i", "s/r o"
    );
    for (j, r) in sol.balls.iter().enumerate() {
        let _ = writeln!(
            s,
            "{:>3} {:>7.2} {:>9.2} {:>9.2} {:>7.3} {:>7.3} {:>8.3} {:>8.3} {:>6.3} {:>6.3} {:>6.3} {:>6.3} {:>6.3} {:>6.3} {:>8.2} {:>8.4} {:>9.1} {:>10.1} {:>6.3} {:>6.3}",
            j,
            r.psi.to_degrees(),
            r.q_i,
            r.q_o,
            r.alpha_i.to_degrees(),
            r.alpha_o.to_degrees(),
            r.delta_i * 1e6,
            r.delta_o * 1e6,
            r.p_i * 1e-9,
            r.p_o * 1e-9,
            r.a_i * 1e3,
            r.b_i * 1e3,
            r.a_o * 1e3,
            r.b_o * 1e3,
            r.fc,
            r.mg,
            rad_s_to_rpm(r.omega_m),
            rad_s_to_rpm(r.omega_r),
            r.spin_roll_i,
            r.spin_roll_o
        );
    }
    let _ = writeln!(
        s,
        "\nForces and moments act on the shaft (the reaction to the load); moments about the bearing centre. \
         a: contact semi-axis across the rolling direction, b: along it; d: approach (negative: gap)."
    );
    s
}
