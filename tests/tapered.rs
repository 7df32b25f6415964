//! Tapered roller bearings through the component: a `30206` scene runs at the quasi-static and
//! ring levels under combined load, its axial/radial load sharing follows the line-contact
//! load-zone integrals that underlie ISO 281's `e`, and a taper that does not close or rollers
//! that do not fit are refused naming the field.

use raceway::component::{variables, Component};
use raceway::geometry::roller_catalogue;

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

fn scene(level: &str, bearing: &str, y: f64, z: f64) -> String {
    format!(
        r#"
bearing = {bearing}
[model]
level = "{level}"
{dof}
[inputs]
speed_rpm = 954.9296586
initial = {{ "shaft.x" = 0.0, "shaft.y" = {y:e}, "shaft.z" = {z:e}, "shaft.rx" = 0.0, "shaft.ry" = 0.0,
            "shaft.vx" = 0.0, "shaft.vy" = 0.0, "shaft.vz" = 0.0, "shaft.wx" = 0.0, "shaft.wy" = 0.0 }}
"#,
        dof = if level == "ring" { "ring_dof = 5" } else { "" }
    )
}

fn forces(level: &str, bearing: &str, y: f64, z: f64) -> [f64; 3] {
    let mut c = Component::from_text(&scene(level, bearing, y, z)).unwrap();
    c.do_step(0.0, 1e-6).unwrap();
    ["force.x", "force.y", "force.z"].map(|n| c.get_real(vr(n)).unwrap())
}

/// The continuous load-zone ratio `Fa/(Fr tan alpha) = J_a(eps)/J_r(eps)` of a line contact
/// (`Q ∝ [1 - (1 - cos psi)/(2 eps)]^(10/9)`, Sjövall's integrals, [Harris & Kotzalas 2007]
/// vol. 1 ch. 7), by the midpoint rule.
fn ja_over_jr(eps: f64) -> f64 {
    let n = 200_000;
    let (mut a, mut r) = (0.0, 0.0);
    for i in 0..n {
        let p = -std::f64::consts::PI + 2.0 * std::f64::consts::PI * (i as f64 + 0.5) / n as f64;
        let d = 1.0 - (1.0 - p.cos()) / (2.0 * eps);
        if d > 0.0 {
            let q = d.powf(10.0 / 9.0);
            a += q;
            r += q * p.cos();
        }
    }
    a / r
}

/// Straight rollers at zero clearance: a radial displacement alone loads half the rollers
/// (`eps = 0.5`) and induces the axial force `Fa = 1.258 Fr tan(alpha)`; with the axial
/// displacement that just unloads the roller opposite the load (`eps = 1`) `Fa/Fr` is
/// `1.90 tan(alpha)`. ISO 281's `e = 1.5 tan(alpha)`, the `Fa/Fr` where its equivalent load
/// leaves pure radial, lies between the two. The 17 discrete rollers meet the continuous
/// integrals within 2 %. The ring level, on the same law with massless rollers, gives the
/// same forces within the inertia terms.
#[test]
fn axial_radial_load_sharing_follows_the_load_zone_integrals() {
    let bearing = r#"{ preset = "30206", clearance_um = 0.0, profile = { type = "none" } }"#;
    let b = roller_catalogue::lookup("30206").unwrap().build().unwrap();
    let t = b.alpha.tan();
    let y = -20e-6;
    let mut ratios = Vec::new();
    for (eps, z) in [(0.5, 0.0), (1.0, 20e-6 / t)] {
        let f = forces("quasi_static", bearing, y, z);
        assert!(
            f[1] > 0.0 && f[2] < 0.0,
            "the rollers push the shaft back: {f:?}"
        );
        let ratio = f[2].abs() / f[1].abs() / t;
        let want = ja_over_jr(eps);
        assert!(
            (ratio / want - 1.0).abs() < 0.02,
            "eps {eps}: Fa/(Fr tan a) {ratio}, Sjövall {want}"
        );
        // The ring level's rollers are massless; the quasi-static level's carry their
        // centrifugal force and gyroscopic moment (docs/physics.md §R11): at 100 rad/s the
        // two differ by a few parts in 10^5 of the load (a roller's F_c is about 0.2 N there).
        let g = forces("ring", bearing, y, z);
        for k in 0..3 {
            assert!((g[k] - f[k]).abs() <= 1e-4 * f[1].abs(), "{g:?} vs {f:?}");
        }
        ratios.push(ratio);
    }
    assert!(ratios[0] < 1.5 && 1.5 < ratios[1], "{ratios:?}");
}

/// The default (logarithmic profile) 30206 under a combined load, load-driven at the
/// quasi-static level, settles with the rollers carrying the applied force: finite and in
/// equilibrium.
#[test]
fn a_tapered_bearing_carries_a_combined_load() {
    let text = r#"
bearing = "30206"
[model]
level = "quasi_static"
causality = "load"
attached_mass_kg = 1.0
contact_damping = 2000.0
[inputs]
rule = "hold"
speed_rpm = 954.9296586
initial = { "load.x" = 0.0, "load.y" = -4000.0, "load.z" = 3000.0, "load.mx" = 0.0, "load.my" = 0.0 }
"#;
    let mut c = Component::from_text(text).unwrap();
    let mut t = 0.0;
    for _ in 0..400 {
        c.do_step(t, 1e-4).unwrap();
        t += 1e-4;
    }
    let fy = c.get_real(vr("force.y")).unwrap();
    let fz = c.get_real(vr("force.z")).unwrap();
    assert!(
        (fy - 4000.0).abs() < 40.0 && (fz + 3000.0).abs() < 30.0,
        "{fy} {fz}"
    );
}

/// A taper that does not close on the bearing axis, and rollers that do not fit on the pitch
/// circle, are refused naming the field.
#[test]
fn bad_tapers_are_refused_naming_the_field() {
    for (bearing, field) in [
        (
            r#"{ preset = "30206", cone_angle_deg = 20.0 }"#,
            "bearing.cone_angle_deg",
        ),
        (
            r#"{ preset = "30206", roller_count = 40 }"#,
            "bearing.roller_count",
        ),
    ] {
        let e = Component::from_text(&scene("quasi_static", bearing, 0.0, 0.0))
            .unwrap_err()
            .to_string();
        assert!(e.contains(field), "{bearing}: {e}");
    }
}
