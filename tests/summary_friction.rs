//! The design calculator's friction printed beside a dynamic run's (src/summary/friction.rs):
//! the printed values are a direct call of the calculator at the run's means, exactly, and
//! the calculator's power is its moment times the mean speed.

use raceway::calculator::friction::{palmgren, FrictionInputs, PalmgrenType};
use raceway::calculator::skf_friction::{series_of, skf_friction, SkfInputs, SkfLubrication};
use raceway::component::Scene;
use raceway::runner::{self, Record};
use raceway::summary::{digest_for, summary_of, Ctx};
use serde_json::Value;
use std::f64::consts::PI;

/// The shipped thermal scene, shortened, on `bearing`.
fn scene(bearing: &str) -> Scene {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/7008ce-thermal.toml"
    ))
    .unwrap()
    .replace("bearing = \"7008ce\"", &format!("bearing = \"{bearing}\""))
    .replace("duration_s = 0.3", "duration_s = 0.04");
    Scene::from_text(&text).unwrap()
}

fn num(v: &Value, path: &[&str]) -> f64 {
    let mut x = v;
    for p in path {
        x = &x[*p];
    }
    x.as_f64()
        .unwrap_or_else(|| panic!("{path:?} is not a number: {x}"))
}

/// Runs `bearing`'s scene; checks the Palmgren (and, when `skf`, the SKF) values against
/// direct calls at the means taken here from the run's digest.
fn check(bearing: &str, skf: bool) {
    let sc = scene(bearing);
    let mut digest = digest_for(&sc);
    let comp = runner::run_into(
        &sc,
        Record::default(),
        false,
        &mut |_| {},
        &mut || false,
        &mut digest,
    )
    .unwrap();
    let ctx = Ctx::new(&sc, "t", &digest, &comp, 1.0);
    let sm = summary_of(&ctx);
    let calc = &sm.json["friction"]["calculator"];
    assert!(calc.is_object(), "{}", sm.text);

    // The means, independently of the summary.
    let b = comp.bearing();
    let omega = digest.mean_second_half("shaft.omega");
    let load = ["force.x", "force.y", "force.z", "moment.x", "moment.y"]
        .map(|n| -digest.mean_second_half(n));
    let a = raceway::ratings::assess_run(b, &load, omega).unwrap();
    let rpm = omega.abs() * 30.0 / PI;
    let lub = sc
        .effects
        .lubrication
        .as_ref()
        .unwrap()
        .lubricant()
        .unwrap();
    let nu = lub.viscosity / lub.density;
    let f0 = sc.effects.thermal.as_ref().unwrap().f0;
    assert_eq!(num(calc, &["mean_speed [rpm]"]), rpm);
    assert_eq!(num(calc, &["radial_load [N]"]), a.radial_load);
    assert_eq!(num(calc, &["axial_load [N]"]), a.axial_load);
    assert_eq!(num(calc, &["P0 [N]"]), a.p0);
    assert_eq!(num(calc, &["C0 [N]"]), a.ratings.c0);
    assert_eq!(num(calc, &["kinematic_viscosity [mm2/s]"]), nu * 1e6);
    assert_eq!(num(calc, &["f0 [1]"]), f0);

    let kind = if bearing.starts_with('7') {
        PalmgrenType::ANGULAR_CONTACT
    } else {
        PalmgrenType::DEEP_GROOVE
    };
    let p = palmgren(
        kind,
        &FrictionInputs {
            dm: b.dm,
            speed_rpm: rpm,
            nu,
            fr: a.radial_load,
            fa: a.axial_load,
            p0: a.p0,
            c0: a.ratings.c0,
            f0,
        },
    )
    .unwrap();
    let pj = &calc["palmgren"];
    assert_eq!(num(pj, &["moment [N.m]"]), p.total);
    assert_eq!(num(pj, &["viscous_moment [N.m]"]), p.m0);
    assert_eq!(num(pj, &["load_moment [N.m]"]), p.m1);
    assert_eq!(num(pj, &["power [W]"]), p.power);
    assert!(
        sm.text.contains(&format!(
            "Palmgren (ISO/TR 14179-2): M {:.4} N m = M0 {:.4} (viscous) + M1 {:.4} (load), power {:.3} W",
            p.total, p.m0, p.m1, p.power
        )),
        "{}",
        sm.text
    );
    // The run's power over the calculator's, as printed.
    let run_power = digest.mean_second_half("power.loss");
    assert!(run_power > 0.0);
    assert_eq!(
        num(pj, &["run_over_calculator_power [1]"]),
        run_power / p.power
    );
    // P = M ω at the mean speed.
    let w = rpm * PI / 30.0;
    assert!(
        (p.power - p.total * w).abs() <= 1e-12 * p.power,
        "{}",
        p.power
    );

    let sj = &calc["skf"];
    if !skf {
        assert!(sj["note"]
            .as_str()
            .unwrap()
            .contains("no geometry constants"));
        return;
    }
    let k = skf_friction(
        series_of(bearing).unwrap(),
        &SkfInputs {
            bore: b.bore,
            outer_diameter: b.outer_diameter,
            speed_rpm: rpm,
            nu,
            fr: a.radial_load,
            fa: a.axial_load,
            c0: a.ratings.c0,
            lubrication: SkfLubrication::OilBath,
            seal: None,
            drag: None,
            tilt: 0.0,
        },
    )
    .unwrap();
    assert_eq!(num(sj, &["moment [N.m]"]), k.total);
    assert_eq!(num(sj, &["rolling_moment [N.m]"]), k.rolling);
    assert_eq!(num(sj, &["sliding_moment [N.m]"]), k.sliding);
    assert_eq!(num(sj, &["power [W]"]), k.power);
    assert_eq!(
        num(sj, &["run_over_calculator_power [1]"]),
        run_power / k.power
    );
    assert!((k.power - k.total * w).abs() <= 1e-12 * k.power);
    assert!(
        sm.text.contains(&format!(
            "M {:.4} N m = rolling {:.4} + sliding {:.4}",
            k.total, k.rolling, k.sliding
        )),
        "{}",
        sm.text
    );
}

/// The shipped scene's bearing: Palmgren's angular-contact form; no SKF constants for it.
#[test]
fn thermal_7008ce_palmgren_is_the_calculator_at_the_means() {
    check("7008ce", false);
}

/// A 62-series deep-groove bearing: both models.
#[test]
fn thermal_6205_palmgren_and_skf_are_the_calculator_at_the_means() {
    check("6205", true);
}

/// A level without oil: said, not guessed.
#[test]
fn skidding_without_oil_viscosity_is_not_evaluated() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/6012-skidding.toml"
    ))
    .unwrap();
    let sc = Scene::from_text(&text).unwrap();
    assert!(raceway::summary::friction::scene_viscosity(&sc).is_none());
}
