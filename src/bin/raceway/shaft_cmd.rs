//! `raceway shaft SHAFT.toml [--json]`: a rigid shaft on bearing locations (single
//! bearings or sets), loads at axial positions, solved for its 5-DOF equilibrium
//! (`raceway::models::shaft`); the file format is in `raceway::models::shaft_file`.

use clap::Args;
use raceway::error::{Error, Result};
use raceway::models::shaft::ShaftSolution;
use raceway::models::shaft_file::read;
use raceway::units::rad_s_to_rpm;
use std::fmt::Write;
use std::path::PathBuf;

/// Arguments of `raceway shaft`.
#[derive(Args, Debug)]
pub struct ShaftArgs {
    /// The shaft file (TOML).
    file: PathBuf,
    /// Print JSON (SI units) instead of text.
    #[arg(long)]
    json: bool,
}

fn life(l: Option<f64>, rpm: f64) -> String {
    match l {
        Some(l) if rpm > 0.0 => format!("{l:.4e} Mrev = {:.0} h", l * 1e6 / (60.0 * rpm)),
        Some(l) => format!("{l:.4e} Mrev"),
        None => "- (unloaded)".into(),
    }
}

/// The text report.
pub fn text(s: &ShaftSolution) -> String {
    let rpm = rad_s_to_rpm(s.omega);
    let mut o = String::new();
    let l = s.load;
    let q = s.q;
    let _ = writeln!(o, "rigid shaft at {rpm:.0} rpm");
    let _ = writeln!(
        o,
        "load at the origin:    Fx {:.1} N  Fy {:.1} N  Fz {:.1} N  Mx {:.3} N m  My {:.3} N m",
        l[0], l[1], l[2], l[3], l[4]
    );
    let _ = writeln!(
        o,
        "shaft at the origin:   x {:.3} µm  y {:.3} µm  z {:.3} µm  rx {:.2} µrad  ry {:.2} µrad",
        q[0] * 1e6,
        q[1] * 1e6,
        q[2] * 1e6,
        q[3] * 1e6,
        q[4] * 1e6
    );
    let k = s.stiffness;
    let _ = writeln!(
        o,
        "system stiffness:      radial x {:.2} N/µm  y {:.2} N/µm  axial {:.2} N/µm  tilt x {:.1} N m/mrad  y {:.1} N m/mrad (at the origin)",
        k[0][0] * 1e-6,
        k[1][1] * 1e-6,
        k[2][2] * 1e-6,
        k[3][3] * 1e-3,
        k[4][4] * 1e-3
    );
    for loc in &s.locations {
        let f = loc.set.force;
        let _ = writeln!(
            o,
            "location {} at {:.1} mm{}: reaction on the shaft Fx {:.1} N  Fy {:.1} N  Fz {:.1} N  Mx {:.3} N m  My {:.3} N m;  life {}",
            loc.name,
            loc.position * 1e3,
            if loc.floating { " (floating axially)" } else { "" },
            f[0],
            f[1],
            f[2],
            f[3],
            f[4],
            life(loc.set.life_mrev, rpm)
        );
        for (j, r) in loc.set.rows.iter().enumerate() {
            let amax = r
                .contact_angles
                .iter()
                .zip(&r.element_loads)
                .filter(|(_, q)| **q > 0.0)
                .map(|(a, _)| a[0].to_degrees())
                .fold(f64::NAN, f64::max);
            let _ = writeln!(
                o,
                "  row {j} {} at {:+.2} mm facing {}: Fr {:.1} N  Fa {:.1} N  loaded {}/{}{}  max inner contact angle {}  axial stiffness {:.2} N/µm  life {}  S0 {}  peak pressure {:.0} MPa",
                r.bearing,
                r.position * 1e3,
                if r.orientation > 0 { "+z" } else { "-z" },
                r.radial_load,
                r.axial_load,
                r.loaded_elements,
                r.element_loads.len(),
                if r.lifted_off { " (LIFTED OFF)" } else { "" },
                if amax.is_nan() { "-".into() } else { format!("{amax:.2} deg") },
                r.axial_stiffness * 1e-6,
                life(r.life_mrev, rpm),
                r.s0.map_or("-".into(), |v| format!("{v:.2}")),
                r.peak_pressure * 1e-6
            );
        }
    }
    let _ = writeln!(
        o,
        "system life (every row, Lundberg–Palmgren): {}",
        life(s.life_mrev, rpm)
    );
    for w in &s.warnings {
        let _ = writeln!(o, "WARNING: {w}");
    }
    o
}

/// The subcommand.
pub fn shaft(a: ShaftArgs) -> Result<String> {
    let shaft = read(&a.file)?;
    let sol = shaft.solve()?;
    if a.json {
        use raceway::summary::columns::{to_labelled_json, Doc};
        serde_json::to_string_pretty(&to_labelled_json(Doc::Shaft, &sol))
            .map(|s| s + "\n")
            .map_err(|e| Error::Io(e.to_string()))
    } else {
        Ok(text(&sol))
    }
}
