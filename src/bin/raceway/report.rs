//! Text and JSON reports of the `raceway` program (edge units in text: mm, µm, degrees,
//! rpm, GPa; SI in JSON).

use raceway::geometry::{preset, presets, BearingKind};
use raceway::models::quasi_static::Solution;
use raceway::ratings::Assessment;
use raceway::summary::reports::{self, control_name, preset_row, QsProblem};
use raceway::units::rad_s_to_rpm;
use raceway::{Error, Result};
use serde::Serialize;
use std::fmt::Write;

pub fn json<T: Serialize>(v: &T) -> Result<String> {
    serde_json::to_string_pretty(v)
        .map(|s| s + "\n")
        .map_err(|e| Error::Io(format!("cannot write JSON: {e}")))
}

/// `raceway bearings`.
pub fn bearings(as_json: bool) -> Result<String> {
    let mut rows = Vec::new();
    for spec in presets() {
        let b = spec.build()?;
        rows.push(preset_row(&spec.source, &b));
    }
    if as_json {
        return json(&reports::bearings_json()?);
    }
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<13} {:<15} {:>7} {:>7} {:>3} {:>6} {:>6} {:>7} {:>8} {:>7} {:>9} {:>10} {:>10} {:>6} {:>6}  balls/rings",
        "name", "kind", "D mm", "dm mm", "Z", "f_i", "f_o", "a0 deg", "Pd µm", "A mm", "ball kg",
        "Kc_i N/m1.5", "Kc_o N/m1.5", "C kN", "C0 kN"
    );
    for r in &rows {
        let kind = match r.kind {
            BearingKind::DeepGroove => "deep-groove",
            BearingKind::AngularContact => "angular-contact",
        };
        let _ = writeln!(
            s,
            "{:<13} {:<15} {:>7.3} {:>7.2} {:>3} {:>6.4} {:>6.4} {:>7.2} {:>8.2} {:>7.4} {:>9.3e} {:>10.4e} {:>10.4e} {:>6} {:>6}  {}/{}",
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
            r.dynamic_rating_n.map_or("-".into(), |c| format!("{:.2}", c * 1e-3)),
            r.static_rating_n.map_or("-".into(), |c| format!("{:.2}", c * 1e-3)),
            r.ball_material,
            r.ring_material
        );
    }
    let _ = writeln!(
        s,
        "a0: free contact angle; Kc at the nominal contact angle (0 for deep-groove); C, C0: ISO 281/76 from the internal geometry.\n\
         Catalogue designations 60xx/62xx/63xx and 70xx/72xx/73xx + C|AC|B (xx = 00..20) are also known, with ESTIMATED internal geometry: `raceway bearings 6206`."
    );
    Ok(s)
}

/// `raceway quasi-static --json`.
pub fn quasi_static_json(
    p: &QsProblem,
    sol: &Solution,
    rating: &std::result::Result<Assessment, String>,
) -> Result<String> {
    json(&reports::quasi_static_report(p, sol, rating).to_json())
}

/// `raceway bearings NAME`: one bearing, its data, ratings and provenance.
pub fn bearing_detail(name: &str, as_json: bool) -> Result<String> {
    if preset(name).is_err() {
        if let Some(r) = raceway::geometry::roller_catalogue::lookup(name) {
            return roller_detail(&r, as_json);
        }
    }
    let spec = preset(name)?;
    let b = spec.build()?;
    let d = reports::bearing_detail(name)?;
    let (r, estimated) = (&d.ratings, d.estimated);
    if as_json {
        return json(&reports::bearing_json(name)?);
    }
    let mut s = String::new();
    let kind = match b.kind {
        BearingKind::DeepGroove => "deep-groove",
        BearingKind::AngularContact => "angular-contact",
    };
    let tag = if estimated { " (estimated)" } else { "" };
    let _ = writeln!(s, "{} ({kind})", b.name);
    let _ = writeln!(
        s,
        "envelope d x D x B:        {:.0} x {:.0} x {:.0} mm",
        d.bore_mm, d.outer_diameter_mm, d.width_mm
    );
    let _ = writeln!(s, "ball diameter Dw:          {:.3} mm{tag}", b.d * 1e3);
    let _ = writeln!(s, "pitch diameter Dpw:        {:.3} mm{tag}", b.dm * 1e3);
    let _ = writeln!(s, "ball count Z:              {}{tag}", b.z);
    let _ = writeln!(
        s,
        "groove curvatures f_i/f_o: {:.4} / {:.4}{tag}",
        b.fi(),
        b.fo()
    );
    let _ = writeln!(
        s,
        "contact angle:             {:.2} deg nominal, {:.2} deg free",
        b.nominal_contact_angle().to_degrees(),
        b.alpha0.to_degrees()
    );
    let _ = writeln!(s, "diametral clearance Pd:    {:.2} µm{tag}", b.pd * 1e6);
    let _ = writeln!(
        s,
        "materials (balls/rings):   {}/{}",
        b.ball_material.name, b.inner_material.name
    );
    s += &r.text();
    let _ = writeln!(s, "source: {}", spec.source);
    if estimated {
        let _ = writeln!(
            s,
            "The internal geometry is ESTIMATED from the envelope (method and its error: docs/catalogue.md); \
             give a bearing file with the maker's data for a real design check."
        );
    }
    Ok(s)
}

/// One line of a 5-vector of forces and moments (Fx, Fy, Fz N; Mx, My N m) after its
/// label, the values aligned with the other lines of [`quasi_static_text`].
fn wrench_line(s: &mut String, label: &str, w: &[f64; 5]) {
    let _ = writeln!(
        s,
        "{label:<34}Fx {:.3} N  Fy {:.3} N  Fz {:.3} N  Mx {:.4} N m  My {:.4} N m",
        w[0], w[1], w[2], w[3], w[4]
    );
}

pub fn quasi_static_text(
    p: &QsProblem,
    sol: &Solution,
    rating: &std::result::Result<Assessment, String>,
) -> String {
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
    wrench_line(&mut s, "external load on the inner ring:", &sol.load);
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
    wrench_line(&mut s, "bearing force on the shaft:", &sol.forces);
    if sol.held.iter().any(|&h| h) {
        let names = raceway::models::quasi_static::hold::held_names(&sol.held);
        let _ = writeln!(
            s,
            "held coordinates:                 {names} (at the displacement above; the others solved)"
        );
        wrench_line(&mut s, "reaction holding them:", &sol.reaction);
    } else {
        let _ = writeln!(
            s,
            "held coordinates:                 none (all five solved; --hold to hold some)"
        );
    }
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
    ball_table(&mut s, &sol.balls);
    let _ = writeln!(
        s,
        "\nForces and moments act on the shaft (the reaction to the load); moments about the bearing centre. \
         a: contact semi-axis across the rolling direction, b: along it; d: approach (negative: gap)."
    );
    let _ = writeln!(s);
    match rating {
        Ok(a) => s += &a.text(),
        Err(e) => s += &format!("ISO ratings and life: not available ({e})\n"),
    }
    let _ = writeln!(s);
    match p.design_check(sol, rating) {
        Ok(c) => s += &raceway::calculator::check::text(&c),
        Err(e) => s += &format!("Design check: not available ({e})\n"),
    }
    s
}

/// The per-ball table of a quasi-static equilibrium (one bearing's, or one row's of a set).
pub fn ball_table(s: &mut String, balls: &[raceway::models::quasi_static::BallResult]) {
    let _ = writeln!(
        *s,
        "{:>3} {:>7} {:>9} {:>9} {:>7} {:>7} {:>8} {:>8} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} {:>8} {:>8} {:>9} {:>10} {:>6} {:>6}",
        "j", "psi deg", "Qi N", "Qo N", "ai deg", "ao deg", "di µm", "do µm", "pi GPa", "po GPa",
        "ai mm", "bi mm", "ao mm", "bo mm", "Fc N", "Mg N m", "cage rpm", "spin rpm", "s/r i", "s/r o"
    );
    for (j, r) in balls.iter().enumerate() {
        let _ = writeln!(
            *s,
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
}

/// `raceway bearings NAME` for a roller designation: the roller file's data, the derived
/// geometry and the ISO 281/76 ratings for roller bearings.
fn roller_detail(
    spec: &raceway::geometry::roller::RollerBearingSpec,
    as_json: bool,
) -> Result<String> {
    let b = spec.build()?;
    let r = raceway::ratings::roller::roller_ratings(&b)?;
    if as_json {
        return json(&reports::bearing_json(&spec.name)?);
    }
    let mut s = String::new();
    let _ = writeln!(s, "{} ({:?} roller bearing)", b.name, b.kind);
    let _ = writeln!(
        s,
        "envelope d x D x B/T:      {:.0} x {:.0} x {:.0} mm",
        b.bore * 1e3,
        b.outer_diameter * 1e3,
        b.width * 1e3
    );
    let _ = writeln!(
        s,
        "roller diameter Dwe:       {:.3} mm (estimated)",
        b.dwe * 1e3
    );
    let _ = writeln!(
        s,
        "effective length Lwe:      {:.3} mm (estimated)",
        b.lwe * 1e3
    );
    let _ = writeln!(
        s,
        "pitch diameter Dpw:        {:.3} mm (estimated)",
        b.dpw * 1e3
    );
    let _ = writeln!(s, "roller count Z:            {} (estimated)", b.z);
    let _ = writeln!(
        s,
        "contact angle (cup):       {:.2} deg",
        b.alpha.to_degrees()
    );
    let _ = writeln!(s, "diametral clearance Pd:    {:.2} µm", b.pd * 1e6);
    let _ = writeln!(
        s,
        "profile:                   {:?}, {} laminae",
        spec.profile, b.laminae
    );
    let _ = writeln!(
        s,
        "ISO 281/76 ratings:        Cr {:.0} N  C0r {:.0} N  (Dwe cos a/Dpw {:.4}, fc {:.2})",
        r.cr, r.c0r, r.gamma, r.fc
    );
    let _ = writeln!(s, "source: {}", spec.source);
    let _ = writeln!(
        s,
        "The internal geometry is ESTIMATED from the envelope (docs/catalogue.md); give the maker's data for a real design check. Scenes take it as bearing = \"{}\" (quasi-static level; cylindrical types).",
        b.name
    );
    Ok(s)
}
