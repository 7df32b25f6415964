//! Defects and waviness on a cylindrical roller bearing at the ring level, per lamina
//! (docs/physics.md §R12), and the characteristic frequencies of roller bearings.

use raceway::component::{variables, Component};
use raceway::contact::roller_law::CylindricalRollerLaw;
use raceway::geometry::kinematics::kinematics;
use raceway::geometry::{roller_catalogue, Bearing};
use raceway::models::effects::Effects;
use raceway::models::ring::roller_effects::RollerEffects;
use raceway::seam::element::{ElementAt, ElementDisplacement, ElementLaw, Want};

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

const SCENE: &str = include_str!("../examples/scenes/nu206-outer-defect.toml");

/// The shipped scene with its defect line replaced by `defects` (empty: no effects at all).
fn scene(defects: &str) -> String {
    let line = SCENE
        .lines()
        .find(|l| l.starts_with("defects = "))
        .expect("the scene has a defect");
    let text = SCENE.replace(line, defects);
    if defects.is_empty() {
        text.replace("[effects]", "")
    } else {
        text
    }
}

/// `force.y`, `shaft.y` at each of `n` steps of 0.1 ms, as bits.
fn history(text: &str, n: usize) -> Vec<[u64; 2]> {
    let mut c = Component::from_text(text).unwrap();
    let h = 1e-4;
    (0..n)
        .map(|i| {
            c.do_step(i as f64 * h, h).unwrap();
            [
                c.get_real(vr("force.y")).unwrap().to_bits(),
                c.get_real(vr("shaft.y")).unwrap().to_bits(),
            ]
        })
        .collect()
}

/// A defect of zero depth takes nothing away: the run is the healthy one, bit for bit, at
/// every step; the shipped 20 µm defect changes it (within 40 ms a roller has crossed it:
/// BPFO = 142.7 Hz).
#[test]
fn a_defect_of_zero_depth_reproduces_the_healthy_run_bit_for_bit() {
    let n = 400;
    let healthy = history(&scene(""), n);
    let zero = history(
        &scene(
            r#"defects = [{ race = "outer", angle_deg = 270.0, width_mm = 1.0, depth_um = 0.0, axial_width_mm = 4.8, axial_position_mm = 2.4 }]"#,
        ),
        n,
    );
    assert_eq!(healthy, zero);
    let spall = history(SCENE, n);
    assert_ne!(healthy, spall);
}

fn nu206() -> (CylindricalRollerLaw, Bearing) {
    let r = roller_catalogue::lookup("NU206").unwrap().build().unwrap();
    let law = CylindricalRollerLaw::new(&r).unwrap().massless();
    (law, Bearing::from_roller(r).unwrap())
}

/// A defect over the `+z` half of the raceway (15 of 30 laminae) under a loaded roller: the
/// laminae outside its span carry exactly the healthy loads (the same bits), those inside
/// carry less, and the roller's load falls by exactly what the spanned laminae lose.
#[test]
fn a_defect_over_half_the_laminae_unloads_only_those_laminae() {
    let (law, b) = nu206();
    let x = law.laminae().x.clone();
    let e: Effects = toml::from_str(
        r#"defects = [{ race = "outer", angle_deg = 270.0, width_mm = 1.0, depth_um = 5.0, axial_width_mm = 4.8, axial_position_mm = 2.4 }]"#,
    )
    .unwrap();
    let fx = RollerEffects::new(&e, &b, &x).unwrap();
    assert_eq!(fx.span(0), (15, 30));
    assert!(x[..15].iter().all(|&v| v < 0.0) && x[15..].iter().all(|&v| v > 0.0));
    let ns = x.len();
    let mut off = vec![0.0; ns];
    // Roller 3 on the pit's centre (the outer race is fixed: the shaft angle does not matter).
    assert!(fx.offsets(3, 270f64.to_radians(), 1.3, &mut off));
    let want = Want {
        stiffness: true,
        report: true,
    };
    // Half the clearance (16.25 µm) plus 20 µm, and a small tilt so the laminae differ.
    let u = ElementDisplacement {
        axial: 0.0,
        radial: 36.25e-6,
        tilt: 1e-4,
    };
    let mut healthy = vec![0.0; ns];
    let q0 = law.lamina_loads(u, 0.0, &mut healthy);
    let mut with = vec![0.0; ns];
    let r = law.react_offsets(u, &off, want, Some(&mut with));
    for k in 0..ns {
        if k < 15 {
            assert_eq!(with[k].to_bits(), healthy[k].to_bits(), "lamina {k}");
        } else {
            assert!(
                with[k] < healthy[k] && with[k] >= 0.0,
                "lamina {k}: {} vs {}",
                with[k],
                healthy[k]
            );
        }
    }
    let lost: f64 = (15..ns).map(|k| healthy[k] - with[k]).sum();
    assert!(lost > 0.05 * q0, "{lost} of {q0} N");
    assert!(
        (q0 - lost - -r.f[1]).abs() < 1e-12 * q0,
        "{q0} {lost} {:?}",
        r.f
    );
    // With no offset the offsets' evaluation is the plain law's to rounding.
    let at = ElementAt {
        index: 3,
        psi: 0.0,
        sc: (0.0, 1.0),
        q: &[0.0; 5],
    };
    let plain = law.react(at, u, 0.0, &mut [], want).unwrap();
    let zero = law.react_offsets(u, &[0.0; 30], want, None);
    for (a, b) in plain.f.iter().zip(zero.f) {
        assert!((a - b).abs() <= 1e-12 * plain.f[1].abs(), "{a} vs {b}");
    }
}

/// Bad input is refused by the component naming the field and a range that can be met: a
/// defect wider than the roller's effective length (9.6 mm for the NU206), one reaching past
/// the roller's end, the axial fields on a ball bearing, and a roller defect on a tapered
/// bearing.
#[test]
fn a_defect_wider_than_the_roller_is_refused_naming_the_field() {
    let err = |text: &str| Component::from_text(text).unwrap_err().to_string();
    let e = err(&scene(
        r#"defects = [{ race = "outer", width_mm = 1.0, depth_um = 20.0, axial_width_mm = 10.0 }]"#,
    ));
    assert!(
        e.contains("effects.defects[0].axial_width_mm") && e.contains("9.6 mm"),
        "{e}"
    );
    let e = err(&scene(
        r#"defects = [{ race = "outer", width_mm = 1.0, depth_um = 20.0, axial_width_mm = 4.8, axial_position_mm = 3.0 }]"#,
    ));
    assert!(
        e.contains("effects.defects[0].axial_position_mm") && e.contains("[-2.4, 2.4]"),
        "{e}"
    );
    let ball = SCENE.replace("bearing = \"NU206\"", "bearing = \"6205\"");
    let e = err(&ball);
    assert!(e.contains("effects.defects[0].axial_width_mm"), "{e}");
    // A tapered bearing takes cup and cone defects (tests/tapered_defects.rs), not a
    // roller's own.
    let tapered = scene(r#"defects = [{ race = "ball", width_mm = 1.0, depth_um = 20.0 }]"#)
        .replace("bearing = \"NU206\"", "bearing = \"30206\"");
    let e = err(&tapered);
    assert!(
        e.contains("effects.defects[0].race") && e.contains("tapered"),
        "{e}"
    );
    let e = err(&scene("defects = []\nball_spacing = { scatter = 0.5 }"));
    assert!(e.contains("effects.ball_spacing"), "{e}");
}

/// The characteristic frequencies of roller bearings take `gamma = Dwe cos(alpha)/Dpw`: at
/// 1500 rpm (25 Hz), by hand from the catalogue's estimated geometry (Dwe 8.5 mm, Dpw 46 mm,
/// Z 14):
/// - NU206, alpha 0: gamma = 8.5/46 = 0.184783, FTF = 25 (1 - gamma)/2 = 10.19022 Hz, BPFO =
///   14 FTF = 142.6630 Hz, BPFI = 14 (25 - FTF) = 207.3370 Hz, BSF = Dpw/(2 Dwe) (1 - gamma²)
///   25 = 65.3373 Hz;
/// - 30206, alpha the cup angle atan(1/4) = 14.036° (the maker's Y = 1.6 = 0.4 cot(alpha)):
///   gamma = 8.5 (4/sqrt 17)/46 = 0.179265, FTF = 10.25918 Hz, BPFO = 143.6285 Hz, BPFI =
///   206.3715 Hz, BSF = 65.4731 Hz.
#[test]
fn characteristic_frequencies_take_the_rollers_gamma() {
    let w = 25.0 * 2.0 * std::f64::consts::PI;
    for (name, gamma, ftf, bpfo, bpfi, bsf) in [
        ("NU206", 0.184783, 10.19022, 142.6630, 207.3370, 65.3373),
        ("30206", 0.179265, 10.25918, 143.6285, 206.3715, 65.4731),
    ] {
        let r = roller_catalogue::lookup(name).unwrap().build().unwrap();
        // Pure rolling at mid-length on the raceway radii Dpw/2 -+ (Dwe/2) cos(alpha_R)
        // (docs/physics.md §R12): the roller axis angle's BPFO, within 0.2 % of the cup angle's.
        let g_r = r.dwe * r.alpha_roller.cos() / r.dpw;
        let bpfo_r = 14.0 * 25.0 * (1.0 - g_r) / 2.0;
        assert!(
            (bpfo_r / bpfo - 1.0).abs() < 2e-3,
            "{name}: {bpfo_r} vs {bpfo}"
        );
        let k = kinematics(&Bearing::from_roller(r).unwrap(), w);
        for (got, want, what) in [
            (k.gamma, gamma, "gamma"),
            (k.ftf, ftf, "FTF"),
            (k.bpfo, bpfo, "BPFO"),
            (k.bpfi, bpfi, "BPFI"),
            (k.bsf, bsf, "BSF"),
        ] {
            assert!(
                (got / want - 1.0).abs() < 5e-6,
                "{name} {what}: {got} vs {want}"
            );
        }
    }
}
