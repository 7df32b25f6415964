//! Cup (outer) and cone (inner) defects on a tapered roller bearing at the ring level, per
//! lamina (docs/physics.md §R12): the defect's axial extent along the raceway generatrix, its
//! depth along the cup normal.

use raceway::component::{variables, Component};
use raceway::contact::tapered_law::TaperedRollerLaw;
use raceway::geometry::{roller_catalogue, Bearing};
use raceway::models::effects::Effects;
use raceway::models::ring::roller_effects::RollerEffects;
use raceway::seam::element::{ElementDisplacement, Want};

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

fn t30206() -> (TaperedRollerLaw, Bearing) {
    let r = roller_catalogue::lookup("30206").unwrap().build().unwrap();
    let law = TaperedRollerLaw::new(&r).unwrap().massless();
    (law, Bearing::from_roller(r).unwrap())
}

/// 30206 on the 2-DOF ring level, motion-driven at 1500 rpm: the cone pushed 20 µm along
/// `+z` (the direction that loads it) and 10 µm down, with `effects` (empty: none).
fn scene(effects: &str) -> String {
    let fx = if effects.is_empty() {
        String::new()
    } else {
        format!("\n[effects]\n{effects}\n")
    };
    format!(
        "title = \"30206 defect\"\nbearing = \"30206\"\n\n[model]\nlevel = \"ring\"\ncausality = \"motion\"\nring_dof = 2\n\n\
         [inputs]\nrule = \"velocity\"\nspeed_rpm = 1500.0\ninitial = {{ \"shaft.y\" = -10e-6, \"shaft.z\" = 20e-6 }}\n{fx}\n\
         [run]\nduration_s = 0.04\nstep_s = 1e-4\n"
    )
}

/// `force.x`, `force.y`, `force.z` at each of `n` steps of 0.1 ms, as bits.
fn history(text: &str, n: usize) -> Vec<[u64; 3]> {
    let mut c = Component::from_text(text).unwrap();
    let h = 1e-4;
    (0..n)
        .map(|i| {
            c.do_step(i as f64 * h, h).unwrap();
            ["force.x", "force.y", "force.z"].map(|v| c.get_real(vr(v)).unwrap().to_bits())
        })
        .collect()
}

/// A cup or cone defect of zero depth takes nothing away: the run is the healthy one, bit for
/// bit, at every step; 20 µm deep it changes it (within 40 ms a roller has crossed a cup pit:
/// BPFO = 143.6 Hz; the cone pit meets the rollers at BPFI).
#[test]
fn a_tapered_defect_of_zero_depth_reproduces_the_healthy_run_bit_for_bit() {
    let n = 400;
    let healthy = history(&scene(""), n);
    for race in ["outer", "inner"] {
        let zero = history(
            &scene(&format!(
                r#"defects = [{{ race = "{race}", angle_deg = 270.0, width_mm = 1.0, depth_um = 0.0, axial_width_mm = 5.0, axial_position_mm = 2.5 }}]"#
            )),
            n,
        );
        assert_eq!(healthy, zero, "{race}");
        let pit = history(
            &scene(&format!(
                r#"defects = [{{ race = "{race}", angle_deg = 270.0, width_mm = 1.0, depth_um = 20.0, axial_width_mm = 5.0, axial_position_mm = 2.5 }}]"#
            )),
            n,
        );
        assert_ne!(healthy, pit, "{race}");
    }
}

/// A cup defect over the `+z` half of the raceway generatrix (toward the small end, where
/// the laminae's `x` is negative) under a loaded roller: the laminae outside its span carry
/// exactly the healthy cup loads (the same bits), those inside carry less, and the roller's
/// cup load falls by exactly what the spanned laminae lose. A cone defect on the other half
/// spans the other laminae.
#[test]
fn a_cup_defect_over_half_the_generatrix_unloads_only_those_laminae() {
    let (law, b) = t30206();
    let x = law.laminae().x.clone();
    let s = law.generatrix_positions();
    let ns = x.len();
    let half = ns / 2;
    assert!(x[..half].iter().all(|&v| v < 0.0) && s[..half].iter().all(|&v| v > 0.0));
    let lwe_mm = law.laminae().lwe * 1e3;
    let e: Effects = toml::from_str(&format!(
        r#"defects = [
  {{ race = "outer", angle_deg = 270.0, width_mm = 1.0, depth_um = 5.0, axial_width_mm = {w}, axial_position_mm = {c} }},
  {{ race = "inner", angle_deg = 0.0, width_mm = 1.0, depth_um = 5.0, axial_width_mm = {w}, axial_position_mm = {m} }},
]"#,
        w = 0.5 * lwe_mm,
        c = 0.25 * lwe_mm,
        m = -0.25 * lwe_mm,
    ))
    .unwrap();
    let fx = RollerEffects::new(&e, &b, &s).unwrap();
    assert_eq!(
        fx.span(0),
        (0, half),
        "the cup pit toward +z: the small end's laminae"
    );
    assert_eq!(fx.span(1), (half, ns), "the cone pit toward -z");
    let mut off = vec![0.0; ns];
    // Roller 3 on the cup pit's centre; the shaft turned so the cone pit is elsewhere (the
    // cone turns with the shaft: at theta_s = 1.3 rad its pit at 0 deg has moved to 74.5 deg).
    assert!(fx.offsets(3, 270f64.to_radians(), 1.3, &mut off));
    assert!(off[half..].iter().all(|&o| o == 0.0), "{off:?}");
    let want = Want {
        stiffness: true,
        report: true,
    };
    let u = ElementDisplacement {
        axial: 20e-6,
        radial: 10e-6,
        tilt: 1e-4,
    };
    let mut healthy = vec![0.0; ns];
    let q0 = law.lamina_loads(u, &mut healthy);
    let mut with = vec![0.0; ns];
    let r = law.react_offsets(u, &off, want, Some(&mut with));
    let mut relieved = 0;
    for k in 0..ns {
        if k >= half {
            assert_eq!(with[k].to_bits(), healthy[k].to_bits(), "lamina {k}");
        } else {
            // An end lamina the profile and the tilt leave unloaded stays so.
            assert!(
                (with[k] < healthy[k] || healthy[k] == 0.0) && with[k] >= 0.0,
                "lamina {k}: {} vs {}",
                with[k],
                healthy[k]
            );
            relieved += usize::from(with[k] < healthy[k]);
        }
    }
    assert!(
        relieved >= half - 3,
        "{relieved} of {half} spanned laminae relieved"
    );
    let lost: f64 = (0..half).map(|k| healthy[k] - with[k]).sum();
    assert!(lost > 0.05 * q0, "{lost} of {q0} N");
    // The force on the shaft is the cup load along the cup normal: its radial part.
    let cos_o = roller_catalogue::lookup("30206")
        .unwrap()
        .build()
        .unwrap()
        .alpha
        .cos();
    assert!(
        ((q0 - lost) * cos_o + r.f[1]).abs() < 1e-12 * q0,
        "{q0} {lost} {:?}",
        r.f
    );
}

/// Bad input names the field: a defect wider than the roller's effective length, one reaching
/// past its end, a roller's own defect or waviness on a tapered bearing.
#[test]
fn tapered_defect_refusals_name_the_field() {
    let err = |fx: &str| Component::from_text(&scene(fx)).unwrap_err().to_string();
    let (law, _) = t30206();
    let lwe_mm = law.laminae().lwe * 1e3;
    let e = err(&format!(
        r#"defects = [{{ race = "outer", width_mm = 1.0, depth_um = 20.0, axial_width_mm = {} }}]"#,
        lwe_mm + 0.5
    ));
    assert!(e.contains("effects.defects[0].axial_width_mm"), "{e}");
    let e = err(&format!(
        r#"defects = [{{ race = "inner", width_mm = 1.0, depth_um = 20.0, axial_width_mm = 2.0, axial_position_mm = {} }}]"#,
        0.5 * lwe_mm
    ));
    assert!(e.contains("effects.defects[0].axial_position_mm"), "{e}");
    let e = err(r#"defects = [{ race = "ball", width_mm = 1.0, depth_um = 20.0 }]"#);
    assert!(e.contains("effects.defects[0].race"), "{e}");
    let e = err(r#"waviness = [{ race = "ball", order = 2, amplitude_um = 1.0 }]"#);
    assert!(e.contains("effects.waviness[0].race"), "{e}");
    // Cup and cone waviness are built (tests/tapered_waviness.rs).
    for race in ["outer", "inner"] {
        let fx = format!(r#"waviness = [{{ race = "{race}", order = 3, amplitude_um = 1.0 }}]"#);
        assert!(Component::from_text(&scene(&fx)).is_ok(), "{race}");
    }
}

/// The shipped scene `30206-cup-defect.toml` (cup spall over the +z half of the generatrix,
/// 0.8 s at 1500 rpm): the envelope spectrum of the force finds BPFO = 143.63 Hz and its
/// second and third harmonics within their tolerances, and the summary gives the run's lamina
/// life.
#[test]
fn the_shipped_cup_defect_scene_finds_bpfo_in_the_envelope() {
    use raceway::runner::{run_into, Record, Series, Tee};
    let text = include_str!("../examples/scenes/30206-cup-defect.toml");
    let s = raceway::component::Scene::from_text(text).unwrap();
    let mut series = Series::default();
    let mut digest = raceway::summary::digest_for(&s);
    let comp = run_into(
        &s,
        Record::default(),
        false,
        &mut |_| {},
        &mut || false,
        &mut Tee(&mut series, &mut digest),
    )
    .unwrap();
    let sm = raceway::summary::summarize(&s, "30206-cup-defect", &digest, &comp, 0.0);
    let env = sm.json["envelope_frequencies"].as_array().unwrap();
    for want in ["1xBPFO", "2xBPFO", "3xBPFO"] {
        let line = env.iter().find(|l| l["label"] == want).unwrap();
        let (f, e, tol) = (
            line["found [Hz]"].as_f64().unwrap_or(f64::NAN),
            line["expected [Hz]"].as_f64().unwrap(),
            line["tolerance [Hz]"].as_f64().unwrap(),
        );
        assert!((f - e).abs() <= tol, "{want}: {line}");
    }
    // A tapered bearing on the ring level is rated from its run's cone and cup laminae.
    assert!(
        sm.text
            .contains("ISO/TS 16281 lamina life over the analysed window"),
        "{}",
        sm.text
    );
    let bpfo = env.iter().find(|l| l["label"] == "1xBPFO").unwrap();
    assert!(
        (bpfo["expected [Hz]"].as_f64().unwrap() - 143.6285).abs() < 1e-3,
        "{bpfo}"
    );
}
