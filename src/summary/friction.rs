//! The design calculator's friction beside a dynamic run's: where a scene computes a friction
//! torque and power (the ring level's thermal effect, the skidding and full levels), the
//! summary prints Palmgren's moment ([`crate::calculator::friction`]) and SKF's four-term
//! moment ([`crate::calculator::skf_friction`]) evaluated at the run's means, each labelled,
//! with the ratio of the run's power to each.
//!
//! The means are those of the second half of the run (the part the summary analyses):
//! the load is minus the mean bearing force, rated at the quasi-static level at the mean
//! shaft speed ([`crate::ratings::assess_run`], the same assessment the summary's ratings
//! use), which gives the radial and axial loads, `P0` and `C0` the calculator takes; the
//! speed is the mean `|shaft.omega|`. The oil is the one the level uses, at the viscosity it
//! uses (the levels hold the viscosity fixed over the run; the thermal effect's temperatures
//! do not change it): the thermal effect's `viscosity_cst`, else the EHL lubricant's
//! `ν = η/ρ`, else its default 20 mm²/s (as `crate::models::ring::level` builds it); the
//! skidding and full levels' dynamic viscosity over [`OIL_DENSITY`]. Palmgren's `f0` is the
//! thermal effect's (the level's own), else the calculator's default 2; the SKF model runs
//! with the calculator's defaults (oil bath without the drag term, open bearing), as
//! `raceway quasi-static --oil` does.

use super::{Ctx, Summary};
use crate::calculator::check::CalcInputs;
use crate::calculator::friction::{palmgren, FrictionInputs, Palmgren, PalmgrenType};
use crate::calculator::skf_friction::{series_of, skf_friction, SkfFriction, SkfInputs, SkfKind};
use crate::component::Scene;
use crate::geometry::{Bearing, BearingKind};
use serde::Serialize;
use serde_json::json;

/// Density that turns the skidding and full levels' dynamic viscosity (Pa s) into the
/// kinematic one the calculator takes, kg/m³: a mineral oil's (the ring level's thermal
/// effect uses the same value the other way).
pub const OIL_DENSITY: f64 = 860.0;

/// The oil as the scene's level uses it: kinematic viscosity (m²/s) and where it comes
/// from, in words (`None`: the level has no oil).
pub fn scene_viscosity(scene: &Scene) -> Option<(f64, String)> {
    match scene.model.level.name() {
        "ring" => {
            let t = scene.effects.thermal.as_ref()?;
            if let Some(v) = t.viscosity_cst {
                return Some((v * 1e-6, "effects.thermal.viscosity_cst".into()));
            }
            match super::lubricant(scene) {
                Some(l) => Some((
                    l.viscosity / l.density,
                    format!(
                        "the lubricant {} (eta/rho)",
                        scene.effects.lubrication.as_ref()?.lubricant
                    ),
                )),
                None => Some((20e-6, "the thermal effect's default 20 mm²/s".into())),
            }
        }
        "skidding" if scene.model.skidding.drag_viscosity > 0.0 => Some((
            scene.model.skidding.drag_viscosity / OIL_DENSITY,
            format!("model.skidding.drag_viscosity / {OIL_DENSITY} kg/m³"),
        )),
        "full" if scene.model.full.viscosity > 0.0 => Some((
            scene.model.full.viscosity / OIL_DENSITY,
            format!("model.full.viscosity / {OIL_DENSITY} kg/m³"),
        )),
        _ => None,
    }
}

/// The run's means the calculator is evaluated at (SI, speed in rpm as the calculator takes
/// it).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeanPoint {
    /// Mean `|shaft.omega|` over the second half, rpm.
    pub speed_rpm: f64,
    /// Radial load at the mean load, N.
    pub fr: f64,
    /// Axial load at the mean load, N.
    pub fa: f64,
    /// ISO 76's static equivalent load at the mean load, N.
    pub p0: f64,
    /// Basic static load rating, N.
    pub c0: f64,
    /// Kinematic viscosity, m²/s.
    pub nu: f64,
    /// Where the viscosity comes from.
    pub viscosity_from: String,
    /// Palmgren's `f0`.
    pub f0: f64,
    /// Where `f0` comes from.
    pub f0_from: &'static str,
}

/// The calculator's friction at the run's means.
#[derive(Clone, Debug, PartialEq)]
pub struct CalcFriction {
    /// The means.
    pub point: MeanPoint,
    /// Palmgren's moment and power.
    pub palmgren: Palmgren,
    /// SKF's four-term model, or why not.
    pub skf: std::result::Result<SkfFriction, String>,
}

/// The calculator's inputs at the means for `b`: Palmgren's and SKF's.
pub fn calculator_inputs(b: &Bearing, p: &MeanPoint) -> (PalmgrenType, FrictionInputs, SkfInputs) {
    let t = match b.kind {
        BearingKind::DeepGroove => PalmgrenType::DEEP_GROOVE,
        BearingKind::AngularContact => PalmgrenType::ANGULAR_CONTACT,
    };
    let pal = FrictionInputs {
        dm: b.dm,
        speed_rpm: p.speed_rpm,
        nu: p.nu,
        fr: p.fr,
        fa: p.fa,
        p0: p.p0,
        c0: p.c0,
        f0: p.f0,
    };
    let d = CalcInputs::default();
    let skf = SkfInputs {
        bore: b.bore,
        outer_diameter: b.outer_diameter,
        speed_rpm: p.speed_rpm,
        nu: p.nu,
        fr: p.fr,
        fa: p.fa,
        c0: p.c0,
        lubrication: d.skf_lubrication,
        seal: d.skf_seal,
        drag: d.skf_drag,
        tilt: 0.0,
    };
    (t, pal, skf)
}

/// The calculator's friction at the run's means (`Err`: why there is none, in words).
pub fn calculator_friction(c: &Ctx) -> std::result::Result<CalcFriction, String> {
    let b = c.comp.bearing();
    let (nu, viscosity_from) = scene_viscosity(c.scene)
        .ok_or_else(|| "the scene gives the level no oil viscosity".to_string())?;
    let omega = c.run.mean_second_half("shaft.omega");
    let load = ["force.x", "force.y", "force.z", "moment.x", "moment.y"]
        .map(|n| -c.run.mean_second_half(n));
    let a = crate::ratings::assess_run(b, &load, omega).map_err(|e| e.to_string())?;
    let (f0, f0_from) = match &c.scene.effects.thermal {
        Some(t) if c.scene.model.level.name() == "ring" => (t.f0, "effects.thermal.f0"),
        _ => (CalcInputs::default().f0, "the calculator's default"),
    };
    let point = MeanPoint {
        speed_rpm: crate::units::rad_s_to_rpm(omega.abs()),
        fr: a.radial_load,
        fa: a.axial_load,
        p0: a.p0,
        c0: a.ratings.c0,
        nu,
        viscosity_from,
        f0,
        f0_from,
    };
    let (t, pal, skf_in) = calculator_inputs(b, &point);
    let palmgren = palmgren(t, &pal).map_err(|e| e.to_string())?;
    let kind = match b.kind {
        BearingKind::DeepGroove => SkfKind::DeepGroove,
        BearingKind::AngularContact => SkfKind::AngularContact,
    };
    let skf = match series_of(&b.name) {
        Some(s) if s.kind == kind => skf_friction(s, &skf_in).map_err(|e| e.to_string()),
        _ => Err(format!(
            "no geometry constants for {} (built in: deep-groove 60, 62, 63)",
            b.name
        )),
    };
    Ok(CalcFriction {
        point,
        palmgren,
        skf,
    })
}

/// The lines beside the run's friction (called where the summary prints it; `friction`:
/// that JSON object, which gets a `calculator` member).
pub fn calculator_lines(c: &Ctx, s: &mut Summary, friction: &mut serde_json::Value) {
    let run_power = c.run.mean_second_half("power.loss");
    let run_torque = c.run.mean_second_half("torque.z").abs();
    let r = match calculator_friction(c) {
        Ok(r) => r,
        Err(why) => {
            s.line(format!("  calculator friction: not evaluated ({why})"));
            if let Some(o) = friction.as_object_mut() {
                o.insert("calculator".into(), json!({ "note": why }));
            }
            return;
        }
    };
    let p = &r.point;
    let ratio = |calc: f64| (calc > 0.0).then(|| run_power / calc);
    let text = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
    s.line(format!(
        "  calculator friction at the run's means over the second half: {:.1} rpm, Fr {:.2} N, Fa {:.2} N, P0 {:.2} N, C0 {:.0} N, \
         nu {:.3} mm²/s ({}), f0 {} ({})",
        p.speed_rpm,
        p.fr,
        p.fa,
        p.p0,
        p.c0,
        p.nu * 1e6,
        p.viscosity_from,
        p.f0,
        p.f0_from
    ));
    let pg = &r.palmgren;
    s.line(format!(
        "  calculator, Palmgren (ISO/TR 14179-2): M {:.4} N m = M0 {:.4} (viscous) + M1 {:.4} (load), power {:.3} W; \
         run/Palmgren: power {}, |torque| {}",
        pg.total,
        pg.m0,
        pg.m1,
        pg.power,
        text(ratio(pg.power)),
        text((pg.total > 0.0).then(|| run_torque / pg.total)),
    ));
    let skf_json = match &r.skf {
        Ok(k) => {
            let opt = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
            s.line(format!(
                "  calculator, SKF four-term (series {}, {}): M {:.4} N m = rolling {:.4} + sliding {:.4} + seals {} + drag {}, power {:.3} W; \
                 run/SKF: power {}, |torque| {} (unconfirmed: {})",
                k.series,
                k.lubrication,
                k.total,
                k.rolling,
                k.sliding,
                opt(k.seals),
                opt(k.drag),
                k.power,
                text(ratio(k.power)),
                text((k.total > 0.0).then(|| run_torque / k.total)),
                k.unconfirmed
            ));
            // The run has no oil level: the drag term's absence is said in its own words
            // (the calculator's warning names a `quasi-static` flag).
            let warnings: Vec<String> = k
                .warnings
                .iter()
                .map(|w| {
                    if w.contains("--skf-drag") {
                        "oil bath without the drag term (a run gives no oil level nor V_M)"
                            .to_string()
                    } else {
                        w.clone()
                    }
                })
                .collect();
            for w in &warnings {
                s.line(format!("    SKF: {w}"));
            }
            json!({"series": k.series, "lubrication": k.lubrication, "moment_nm": k.total,
                "rolling_moment_nm": k.rolling, "sliding_moment_nm": k.sliding,
                "seal_moment_nm": k.seals, "drag_moment_nm": k.drag, "power_w": k.power,
                "run_over_calculator_power": ratio(k.power), "unconfirmed": k.unconfirmed,
                "warnings": warnings})
        }
        Err(why) => {
            s.line(format!(
                "  calculator, SKF four-term: not evaluated ({why})"
            ));
            json!({ "note": why })
        }
    };
    if let Some(o) = friction.as_object_mut() {
        o.insert(
            "calculator".into(),
            json!({"means": "second half of the run", "mean_speed_rpm": p.speed_rpm,
                "radial_load_n": p.fr, "axial_load_n": p.fa, "p0_n": p.p0, "c0_n": p.c0,
                "kinematic_viscosity_mm2_s": p.nu * 1e6, "viscosity_from": p.viscosity_from,
                "f0": p.f0, "f0_from": p.f0_from,
                "palmgren": {"moment_nm": pg.total, "viscous_moment_nm": pg.m0,
                    "load_moment_nm": pg.m1, "power_w": pg.power,
                    "run_over_calculator_power": ratio(pg.power)},
                "skf": skf_json}),
        );
    }
}
