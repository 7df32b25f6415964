//! The summary of a bearing set's run (a scene with a `[set]`): the set's net force is not
//! one bearing's load, so each row is rated on its own, from its per-row outputs
//! (`row<i>.force.*`, `row<i>.contact_angle`, `row<i>.lift_off`): its peak and mean load
//! over the second half of the run, its mean contact angle, how long it was lifted off,
//! and its ISO 281 life and ISO 76 static safety at its mean load (what the component's
//! `row<i>.life.L10` computes at each step, [`crate::ratings::RatingOutputs`]). The set's
//! life is the rows' system life ([`crate::models::set::system_life`], Lundberg–Palmgren,
//! docs/physics.md §11), its static safety the smallest row's.

use super::{Ctx, Summary};
use crate::models::set::{system_life, weibull_slope, SetSpec};
use crate::ratings::{RatingOutputs, L10_UNLOADED, S0_UNLOADED};
use serde_json::{json, Value};
use std::fmt::Write as _;

/// One row's figures (SI but the angle, degrees, as the summary shows it).
struct RowFigures {
    bearing: String,
    position_mm: f64,
    orientation: i32,
    mean_force: [f64; 5],
    peak_force: [f64; 3],
    /// Mean radial load, N.
    radial: f64,
    /// Mean thrust toward the row's loading direction, N.
    thrust: f64,
    angle_deg: f64,
    lifted_fraction: f64,
    ever_lifted: bool,
    l10: Option<f64>,
    s0: Option<f64>,
    slope: f64,
}

fn rows_of(c: &Ctx, spec: &SetSpec) -> Vec<RowFigures> {
    spec.rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let n = |k: &str| format!("row{i}.{k}");
            let mean = |k: &str| c.run.mean_second_half(&n(k));
            let mean_force = ["force.x", "force.y", "force.z", "moment.x", "moment.y"].map(mean);
            let peak_force = ["force.x", "force.y", "force.z"].map(|k| c.run.peak(&n(k)));
            let o = f64::from(r.orientation);
            // The row's own frame (mirrored for a row facing -z): what its ratings read.
            let local = [
                mean_force[0],
                mean_force[1],
                o * mean_force[2],
                o * mean_force[3],
                o * mean_force[4],
            ];
            let [s0, l10, _] = RatingOutputs::of(&r.bearing).outputs(&r.bearing, &local, 0.0, 2.0);
            RowFigures {
                bearing: r.bearing.name.clone(),
                position_mm: r.position * 1e3,
                orientation: r.orientation,
                mean_force,
                peak_force,
                radial: local[0].hypot(local[1]),
                thrust: -local[2],
                angle_deg: mean("contact_angle").to_degrees(),
                lifted_fraction: mean("lift_off"),
                ever_lifted: c.run.peak(&n("lift_off")) > 0.0,
                l10: (l10 > 0.0 && l10 < L10_UNLOADED).then_some(l10),
                s0: (s0 > 0.0 && s0 < S0_UNLOADED).then_some(s0),
                slope: weibull_slope(r.bearing.element()),
            }
        })
        .collect()
}

/// Hours of `mrev` million revolutions at `omega` rad/s (`None` at standstill).
fn hours(mrev: Option<f64>, omega: f64) -> Option<f64> {
    let rpm = crate::units::rad_s_to_rpm(omega.abs());
    mrev.filter(|_| rpm > 0.0).map(|l| l * 1e6 / (60.0 * rpm))
}

fn opt(v: Option<f64>, f: impl Fn(f64) -> String, none: &str) -> String {
    v.map(f).unwrap_or_else(|| none.to_string())
}

/// The ratings section of a set's run (in place of one bearing's): `false` (nothing
/// written) when the scene has no set.
pub(super) fn rating_lines(c: &Ctx, s: &mut Summary) -> bool {
    let spec = match c.scene.set_spec(c.comp.bearing()) {
        Ok(Some(spec)) => spec,
        Ok(None) => return false,
        Err(e) => {
            s.line(format!("bearing set: not rated ({e})"));
            s.set("rating", Value::Null);
            s.set("warnings", Value::Array(vec![]));
            return true;
        }
    };
    let omega = c.last("shaft.omega");
    let rows = rows_of(c, &spec);
    let lives: Vec<(Option<f64>, f64)> = rows.iter().map(|r| (r.l10, r.slope)).collect();
    let life = system_life(&lives);
    let s0 = rows
        .iter()
        .filter_map(|r| r.s0)
        .fold(None, |a: Option<f64>, v| Some(a.map_or(v, |a| a.min(v))));
    s.line(format!(
        "bearing set of {} rows, each rated on its own load at its mean over the second half \
         (ISO 281 L10 = (C/P)^p, ISO 76 S0 = C0/P0; means over the second half: forces and moments \
         on the shaft at the row, shaft frame; thrust toward the row's loading direction; \
         contact angle: load-weighted inner, 0 while lifted off):",
        rows.len()
    ));
    s.line(format!(
        "  {:>3} {:<10} {:>8} {:>5} {:>10} {:>10} {:>10} {:>10} {:>10} {:>24} {:>9} {:>9} {:>11} {:>10} {:>8}",
        "row",
        "bearing",
        "at mm",
        "faces",
        "Fz N",
        "Fr N",
        "thrust N",
        "Mx N m",
        "My N m",
        "peak |Fx| |Fy| |Fz| N",
        "angle deg",
        "lifted %",
        "L10 Mrev",
        "L10 h",
        "S0"
    ));
    for (i, r) in rows.iter().enumerate() {
        s.line(format!(
            "  {:>3} {:<10} {:>8.3} {:>5} {:>10.2} {:>10.2} {:>10.2} {:>10.4} {:>10.4} {:>24} {:>9.3} {:>9.1} {:>11} {:>10} {:>8}",
            i,
            r.bearing,
            r.position_mm,
            if r.orientation > 0 { "+z" } else { "-z" },
            r.mean_force[2],
            r.radial,
            r.thrust,
            r.mean_force[3],
            r.mean_force[4],
            format!(
                "{:.1} {:.1} {:.1}",
                r.peak_force[0], r.peak_force[1], r.peak_force[2]
            ),
            r.angle_deg,
            100.0 * r.lifted_fraction,
            // No finite life: beyond the outputs' cap (1e12) while loaded, else unloaded.
            opt(
                r.l10,
                |v| format!("{v:.4e}"),
                if r.radial > 0.0 || r.thrust > 0.0 {
                    "> 1e12"
                } else {
                    "unloaded"
                }
            ),
            opt(hours(r.l10, omega), |v| format!("{v:.4e}"), "-"),
            opt(r.s0, |v| format!("{v:.3}"), "unloaded"),
        ));
    }
    s.line(format!(
        "  set: system life L10 {} Mrev = {} h (the rows' lives together, Lundberg–Palmgren: \
         sum (L/L_i)^e_i = 1, e 10/9 ball rows, 9/8 roller rows); smallest S0 {}",
        opt(life, |v| format!("{v:.4e}"), "infinite (no row loaded)"),
        opt(hours(life, omega), |v| format!("{v:.4e}"), "-"),
        opt(s0, |v| format!("{v:.3}"), "unloaded"),
    ));
    let mut warnings = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        if r.ever_lifted {
            warnings.push(format!(
                "row {i} ({}) lifts off (no element loaded) during {:.1} % of the second half",
                r.bearing,
                100.0 * r.lifted_fraction
            ));
        }
    }
    let peak_p = c.peak("contact.max_pressure");
    if peak_p > crate::ratings::STATIC_PRESSURE_LIMIT {
        warnings.push(format!(
            "peak contact pressure {:.0} MPa over the rows exceeds the ISO 76 limit {:.0} MPa",
            peak_p * 1e-6,
            crate::ratings::STATIC_PRESSURE_LIMIT * 1e-6
        ));
    }
    for w in &warnings {
        s.line(format!("  warning: {w}"));
    }
    let json_rows: Vec<Value> = rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            json!({"label": format!("row{i}"), "bearing": r.bearing, "position_mm": r.position_mm,
                "orientation": r.orientation, "mean_force_n": r.mean_force[..3],
                "mean_moment_nm": r.mean_force[3..], "peak_force_n": r.peak_force,
                "mean_radial_load_n": r.radial, "mean_thrust_n": r.thrust,
                "mean_contact_angle_deg": r.angle_deg, "lift_off_fraction": r.lifted_fraction,
                "l10_mrev": r.l10, "l10_hours": hours(r.l10, omega), "s0": r.s0,
                "weibull_slope": r.slope})
        })
        .collect();
    s.set(
        "set",
        json!({"rows": json_rows, "system_l10_mrev": life, "system_l10_hours": hours(life, omega),
            "smallest_s0": s0}),
    );
    // One bearing's rating of the set's net force would be wrong: none.
    s.set("rating", Value::Null);
    s.set("warnings", warnings.into());
    true
}

/// The rows of a set's summary (its `set` JSON) as an HTML table, for report.html.
pub(super) fn html_table(v: &Value) -> String {
    use super::html::{esc, num};
    let f = |x: &Value| x.as_f64().map_or("–".to_string(), num);
    let mut t = String::from(
        "<table class=\"lines\"><tr><th>row</th><th>bearing</th><th>at (mm)</th><th>faces</th>\
         <th>mean Fz (N)</th><th>mean Fr (N)</th><th>mean thrust (N)</th><th>peak |Fx|, |Fy|, |Fz| (N)</th>\
         <th>mean contact angle (deg)</th><th>lifted off (fraction of the second half)</th>\
         <th>L10 (million revolutions)</th><th>L10 (h)</th><th>S0</th></tr>",
    );
    let empty = vec![];
    for r in v["rows"].as_array().unwrap_or(&empty) {
        let peak: Vec<String> = ["x", "y", "z"]
            .iter()
            .map(|a| f(&r[format!("peak_force.{a} [N]").as_str()]))
            .collect();
        let _ = write!(
            t,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>\
             <td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            esc(r["label"].as_str().unwrap_or("")),
            esc(r["bearing"].as_str().unwrap_or("")),
            f(&r["position [mm]"]),
            if r["orientation [1]"].as_i64() == Some(-1) { "-z" } else { "+z" },
            f(&r["mean_force.z [N]"]),
            f(&r["mean_radial_load [N]"]),
            f(&r["mean_thrust [N]"]),
            peak.join(", "),
            f(&r["mean_contact_angle [deg]"]),
            f(&r["lift_off_fraction [1]"]),
            f(&r["L10 [Mrev]"]),
            f(&r["L10 [h]"]),
            f(&r["S0 [1]"]),
        );
    }
    let _ = write!(
        t,
        "</table><p>System life (the rows' lives together, Lundberg–Palmgren) L10 {} million revolutions \
         = {} h; smallest S0 {}.</p>",
        f(&v["system_L10 [Mrev]"]),
        f(&v["system_L10 [h]"]),
        f(&v["smallest_S0 [1]"])
    );
    t
}

#[cfg(test)]
mod tests {
    use crate::component::Scene;
    use crate::runner::Digest;

    /// The DB pair of the shipped scene at rest, no displacement: the summary's rows
    /// carry the preload, equal and opposite on the shaft; each row's life is ISO 281's
    /// of its own load, and the set's is the Lundberg–Palmgren system life of two equal
    /// rows, `L = L_row 2^(-9/10)`, below each row's.
    #[test]
    fn db_pair_at_rest_rows_carry_the_preload_and_the_system_life_is_below_each_rows() {
        let text = include_str!("../../examples/scenes/7008ce-db-pair.toml")
            .replace("speed_rpm = 12000.0", "speed_rpm = 0.0")
            .replace(
                "initial = { \"shaft.y\" = -5e-6, \"shaft.z\" = 5e-6 }",
                "initial = {}",
            )
            .replace("duration_s = 0.02", "duration_s = 0.002");
        let scene = Scene::from_text(&text).unwrap();
        let (series, comp) = crate::runner::run(&scene, &mut |_| {}).unwrap();
        let run = Digest::of(&series, &[super::super::signal_of(&scene).0], &[]);
        let sm = super::super::summarize(&scene, "db", &run, &comp, 0.0);
        let set = &sm.json["set"];
        let rows = set["rows"].as_array().unwrap();
        assert_eq!(rows.len(), 2);
        let fz = |i: usize| rows[i]["mean_force.z [N]"].as_f64().unwrap();
        let thrust = |i: usize| rows[i]["mean_thrust [N]"].as_f64().unwrap();
        assert!(
            (fz(0) + fz(1)).abs() < 1e-6 * fz(0).abs(),
            "{} {}",
            fz(0),
            fz(1)
        );
        for (i, r) in rows.iter().enumerate() {
            // Rigid preload by force: each row carries the 300 N at rest.
            assert!((thrust(i) - 300.0).abs() < 1e-6 * 300.0, "{}", thrust(i));
            assert_eq!(r["lift_off_fraction [1]"].as_f64().unwrap(), 0.0);
        }
        // Each row's life: ISO 281 of its own 300 N thrust (RatingOutputs, independently).
        let b = comp.bearing();
        let [_, own, _] =
            crate::ratings::RatingOutputs::of(b).outputs(b, &[0.0, 0.0, 300.0, 0.0, 0.0], 0.0, 2.0);
        let l: Vec<f64> = (0..2)
            .map(|i| rows[i]["L10 [Mrev]"].as_f64().unwrap())
            .collect();
        assert!((l[0] - own).abs() < 1e-9 * own && (l[1] - own).abs() < 1e-9 * own);
        let sys = set["system_L10 [Mrev]"].as_f64().unwrap();
        assert!(sys < l[0] && sys < l[1]);
        let want = own * 2f64.powf(-9.0 / 10.0);
        assert!((sys - want).abs() < 1e-9 * want, "{sys} vs {want}");
        // The net force is not rated as one bearing.
        assert!(sm.json["rating"].is_null());
        assert!(sm.text.contains("system life L10"));
    }
}
