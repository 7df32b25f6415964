//! Vibration physics on the ring level (docs/physics.md §5.1, §5.3, §5.4, §6): the spectral
//! signatures of a healthy bearing, local defects and waviness, the EHL film laws, and
//! that every effect switched off recovers the plain model bit for bit.
//!
//! The dynamic runs are study \[4\]'s set-up: a 6205 inner ring with 1 kg attached, load-
//! driven under 1000 N downward, 10 µm clearance, 1750 rpm (fs = 29.17 Hz, FTF = 11.62,
//! BPFO = 104.56, BPFI = 157.94, BSF = 68.74 Hz), sampled at 10 kHz for 0.5 s (2 Hz bins).

#[path = "common/outputs.rs"]
mod outputs;
use outputs::outputs;
use raceway::analysis::{
    amplitude_spectrum, envelope_spectrum, find_peaks, Mark, Spectrum, Window,
};
use raceway::component::variables;
use raceway::contact::{series_constant, PointContact, Race};
use raceway::geometry::{kinematics, preset, Kinematics};
use raceway::lubrication::{central_film, minimum_film, FilmModel, Lubricant};
use raceway::models::defects::{edge_depth, Defect, DefectSite};
use raceway::Component;
use std::f64::consts::PI;
use std::sync::OnceLock;

#[path = "common/thread_alloc.rs"]
mod thread_alloc;
#[global_allocator]
static A: thread_alloc::Counting = thread_alloc::Counting;

const OMEGA: f64 = 183.259571; // 1750 rpm
const H: f64 = 1e-4;
const FS: f64 = 1.0 / H;
const SETTLE: usize = 500; // 50 ms
const N: usize = 5000; // 0.5 s

fn scene(effects: &str) -> String {
    format!(
        r#"
bearing = {{ preset = "6205", clearance_um = 10.0 }}
[model]
level = "ring"
causality = "load"
contact_damping = 1000.0
attached_mass_kg = 1.0
[inputs]
rule = "hold"
speed_rpm = 1750.0
initial = {{ "load.x" = 0.0, "load.y" = -1000.0, "load.z" = 0.0, "load.mx" = 0.0, "load.my" = 0.0 }}
[effects]
{effects}
"#
    )
}

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

/// Run a scene; return the ring's y displacement and the bearing's y force after settling.
fn run(text: &str) -> (Vec<f64>, Vec<f64>) {
    let mut c = Component::from_text(text).unwrap();
    let (vy, vf) = (vr("shaft.y"), vr("force.y"));
    let mut y = Vec::with_capacity(N);
    let mut f = Vec::with_capacity(N);
    for i in 0..SETTLE + N {
        c.do_step(i as f64 * H, H).unwrap();
        if i >= SETTLE {
            y.push(c.get_real(vy).unwrap());
            f.push(c.get_real(vf).unwrap());
        }
    }
    (y, f)
}

/// [`run`] of the healthy bearing (`scene("")`), run once per test process: several tests
/// compare against it.
fn healthy() -> &'static (Vec<f64>, Vec<f64>) {
    static HEALTHY: OnceLock<(Vec<f64>, Vec<f64>)> = OnceLock::new();
    HEALTHY.get_or_init(|| run(&scene("")))
}

/// The y displacement of `scene(extra)` and of the healthy bearing, and their amplitude
/// spectra.
fn with_healthy(extra: &str) -> (Vec<f64>, &'static [f64], Spectrum, Spectrum) {
    let (y, _) = run(&scene(extra));
    let yh = &healthy().0;
    let (s, sh) = (spectrum(&y), spectrum(yh));
    (y, yh, s, sh)
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn kin() -> (Kinematics, f64) {
    let b = preset("6205").unwrap().build().unwrap();
    (kinematics(&b, OMEGA), OMEGA / (2.0 * PI))
}

fn spectrum(y: &[f64]) -> Spectrum {
    amplitude_spectrum(y, FS, Window::Hann)
}

/// Envelope spectrum of the force around the ring's contact resonance (about 2 kHz).
fn envelope(f: &[f64]) -> Spectrum {
    envelope_spectrum(f, FS, Some((800.0, 4500.0)))
}

/// The largest local maximum near `f` (within one bin beyond a tolerance of one bin) and
/// its height over the median floor of the octave around it.
fn line(s: &Spectrum, label: &str, f: f64) -> (f64, f64) {
    let p = &find_peaks(
        s,
        &[Mark {
            label: label.into(),
            freq: f,
        }],
        1.0,
    )[0];
    println!(
        "{label}: expected {:.2} Hz, found {:.2} Hz, amplitude {:.3e}, {:.1} x floor",
        p.expected, p.found, p.amplitude, p.over_floor
    );
    (p.found, p.over_floor)
}

fn assert_line(s: &Spectrum, label: &str, f: f64, min_over_floor: f64) {
    let (found, over) = line(s, label, f);
    assert!(
        (found - f).abs() <= s.resolution(),
        "{label}: peak at {found} Hz, expected {f} Hz"
    );
    assert!(
        over >= min_over_floor,
        "{label}: only {over} x the floor (want {min_over_floor})"
    );
}

/// A healthy bearing with clearance vibrates at the varying-compliance frequency
/// Z f_cage = BPFO and its harmonics (Sunnersjö 1978; docs/physics.md §N5.2).
#[test]
fn healthy_bearing_peaks_at_varying_compliance_frequency() {
    let (k, _) = kin();
    let s = spectrum(&healthy().0);
    let (f, _) = s.peak_in(20.0, 2000.0).unwrap();
    println!(
        "largest peak of y in 20..2000 Hz: {f:.2} Hz (BPFO {:.2})",
        k.bpfo
    );
    assert!((f - k.bpfo).abs() <= s.resolution(), "{f} vs {}", k.bpfo);
    assert_line(&s, "BPFO", k.bpfo, 100.0);
    assert_line(&s, "2 BPFO", 2.0 * k.bpfo, 100.0);
    assert_line(&s, "3 BPFO", 3.0 * k.bpfo, 100.0);
}

/// An outer-race spall in the load zone: envelope spectrum lines at BPFO and harmonics,
/// far above the healthy bearing's envelope.
#[test]
fn outer_race_defect_gives_bpfo_and_harmonics() {
    let (k, _) = kin();
    let (_, f) = run(&scene(
        r#"defects = [{ race = "outer", angle_deg = 270.0, width_mm = 1.0, depth_um = 50.0 }]"#,
    ));
    let e = envelope(&f);
    let (fp, _) = e.peak_in(20.0, 1000.0).unwrap();
    assert!((fp - k.bpfo).abs() <= e.resolution(), "{fp}");
    for h in 1..=3 {
        assert_line(&e, &format!("{h} BPFO"), h as f64 * k.bpfo, 20.0);
    }
    let eh = envelope(&healthy().1);
    let ratio = e.at(k.bpfo) / eh.at(k.bpfo);
    println!("envelope at BPFO, spall / healthy = {ratio:.1}");
    assert!(ratio > 10.0, "{ratio}");
}

/// An inner-race spall turns with the shaft: BPFI, with side bands at the shaft speed from
/// its passage through the load zone once a turn.
#[test]
fn inner_race_defect_gives_bpfi_with_shaft_sidebands() {
    let (k, fs) = kin();
    let (_, f) = run(&scene(
        r#"defects = [{ race = "inner", angle_deg = 270.0, width_mm = 1.0, depth_um = 50.0 }]"#,
    ));
    let e = envelope(&f);
    assert_line(&e, "BPFI", k.bpfi, 20.0);
    assert_line(&e, "BPFI - fs", k.bpfi - fs, 5.0);
    assert_line(&e, "BPFI + fs", k.bpfi + fs, 5.0);
    assert_line(&e, "2 BPFI", 2.0 * k.bpfi, 5.0);
    assert_line(&e, "fs", fs, 5.0);
}

/// A ball spall strikes both races: 2 BSF, with side bands at the cage speed (the ball
/// orbits through the load zone once per cage turn).
#[test]
fn ball_defect_gives_twice_bsf_with_cage_sidebands() {
    let (k, _) = kin();
    let (_, f) = run(&scene(
        r#"defects = [{ race = "ball", ball = 0, angle_deg = 0.0, width_mm = 1.0, depth_um = 50.0 }]"#,
    ));
    let e = envelope(&f);
    assert_line(&e, "2 BSF", 2.0 * k.bsf, 10.0);
    assert_line(&e, "2 BSF - FTF", 2.0 * k.bsf - k.ftf, 3.0);
    assert_line(&e, "2 BSF + FTF", 2.0 * k.bsf + k.ftf, 3.0);
    assert_line(&e, "FTF", k.ftf, 3.0);
}

/// Outer-race waviness of order k = pZ (here p = 2, k = 18) excites p BPFO.
#[test]
fn outer_race_waviness_of_order_pz_excites_p_bpfo() {
    let (k, _) = kin();
    let (_, _, s, sh) =
        with_healthy(r#"waviness = [{ race = "outer", order = 18, amplitude_um = 0.5 }]"#);
    let (f, _) = s.peak_in(20.0, 2000.0).unwrap();
    println!(
        "largest peak with k = 18: {f:.2} Hz (2 BPFO {:.2})",
        2.0 * k.bpfo
    );
    assert!((f - 2.0 * k.bpfo).abs() <= s.resolution(), "{f}");
    let ratio = s.at(2.0 * k.bpfo) / sh.at(2.0 * k.bpfo);
    println!("y at 2 BPFO, wavy / healthy = {ratio:.1}");
    assert!(ratio > 10.0, "{ratio}");
}

/// Inner-race waviness of order k = pZ ± m gives the line p BPFI ± m fs: here p = 1,
/// k = 8 gives BPFI - fs and k = 10 gives BPFI + fs, each without its mirror line.
#[test]
fn inner_race_waviness_of_order_pz_pm_m_gives_bpfi_sidebands() {
    let (k, fs) = kin();
    let sh = spectrum(&healthy().0);
    for (order, label, f, mirror) in [
        (8, "BPFI - fs", k.bpfi - fs, k.bpfi + fs),
        (10, "BPFI + fs", k.bpfi + fs, k.bpfi - fs),
    ] {
        let (y, _) = run(&scene(&format!(
            r#"waviness = [{{ race = "inner", order = {order}, amplitude_um = 0.5, phase_deg = 45.0 }}]"#
        )));
        let s = spectrum(&y);
        assert_line(&s, label, f, 100.0);
        let ratio = s.at(f) / sh.at(f);
        let mirror_ratio = s.at(f) / s.at(mirror);
        println!("k = {order}, {label}: wavy / healthy = {ratio:.3e}, line / mirror line = {mirror_ratio:.3e}");
        assert!(ratio > 100.0, "{label}: {ratio}");
        assert!(mirror_ratio > 100.0, "{label}: {mirror_ratio}");
    }
}

fn contacts() -> (PointContact, PointContact, f64, f64, f64) {
    let b = preset("6205").unwrap().build().unwrap();
    let ci = PointContact::ball_race(&b, 0.0, Race::Inner);
    let co = PointContact::ball_race(&b, 0.0, Race::Outer);
    let kn = series_constant(ci.kc, co.kc);
    (ci, co, kn, b.dm, b.d / b.dm)
}

/// Hamrock–Dowson: the central film grows as u^0.67 and falls as Q^-0.067; the minimum
/// film as u^0.68 and Q^-0.073; a 6205 at 1750 rpm under a few hundred N has a film of a
/// few tenths of a micrometre.
#[test]
fn film_thickness_follows_the_hamrock_dowson_exponents() {
    let l = Lubricant::study2();
    let (ci, _, _, dm, gamma) = contacts();
    let u = raceway::lubrication::entrainment_speed(dm, gamma, OMEGA);
    assert!((u - 0.25 * dm * OMEGA * (1.0 - gamma * gamma)).abs() < 1e-15);
    let h = central_film(&l, &ci, u, 300.0);
    println!("h_c(inner, 300 N, 1750 rpm) = {:.3} µm", h * 1e6);
    assert!(h > 0.05e-6 && h < 1e-6, "{h}");
    let r = central_film(&l, &ci, 4.0 * u, 300.0) / h;
    assert!((r - 4f64.powf(0.67)).abs() < 1e-12, "{r}");
    let r = central_film(&l, &ci, u, 3000.0) / h;
    assert!((r - 10f64.powf(-0.067)).abs() < 1e-12, "{r}");
    assert!(r < 1.0 && r > 0.85, "falls slowly with load");
    let hm = minimum_film(&l, &ci, u, 300.0);
    assert!(hm < h, "minimum below central");
    assert!((minimum_film(&l, &ci, 4.0 * u, 300.0) / hm - 4f64.powf(0.68)).abs() < 1e-12);
    assert!((minimum_film(&l, &ci, u, 3000.0) / hm - 10f64.powf(-0.073)).abs() < 1e-12);
    assert_eq!(
        central_film(&l, &ci, 0.0, 300.0),
        0.0,
        "no film at standstill"
    );
}

/// The squeeze damping vanishes with the viscosity, and so does the film: the film law
/// then tends to the dry Hertz law.
#[test]
fn film_damping_vanishes_with_viscosity() {
    let (ci, co, kn, dm, gamma) = contacts();
    let mut last = f64::INFINITY;
    for eta in [0.05, 5e-3, 5e-4, 5e-6, 5e-9] {
        let l = Lubricant {
            viscosity: eta,
            ..Lubricant::study2()
        };
        let m = FilmModel::new(l, ci, co, kn, dm, gamma);
        let b = m.solve(&m.at_speed(OMEGA), 10e-6).unwrap();
        println!(
            "eta = {eta:e} Pa s: ball damping {:.4e} N s/m, load {:.3} N",
            b.damping, b.load
        );
        assert!(b.damping < last);
        last = b.damping;
        if eta <= 5e-6 {
            let dry = kn * (10e-6f64).powf(1.5);
            assert!((b.load - dry).abs() < 1e-3 * dry, "{} vs dry {dry}", b.load);
        }
    }
    assert!(last < 1e-4, "{last}");
}

/// No effects, an empty `[effects]`, empty lists and a dry film are the plain model: bit
/// for bit, over a run, with no extra state.
#[test]
fn effects_off_recover_the_plain_model_exactly() {
    let plain = scene("").replace("[effects]\n", "");
    let variants = [
        scene(""),
        scene("defects = []\nwaviness = []"),
        scene(r#"lubrication = { film = "dry" }"#),
    ];
    let mut a = Component::from_text(&plain).unwrap();
    let mut others: Vec<Component> = variants
        .iter()
        .map(|t| Component::from_text(t).unwrap())
        .collect();
    for i in 0..100 {
        a.do_step(i as f64 * H, H).unwrap();
        for o in &mut others {
            o.do_step(i as f64 * H, H).unwrap();
        }
    }
    for o in &mut others {
        assert_eq!(outputs(&mut a), outputs(o));
        assert_eq!(a.get_state().x.len(), o.get_state().x.len());
    }
    assert_eq!(a.get_real(vr("film.min_thickness")).unwrap(), 0.0);
}

/// Effects through the component: an inner-race effect adds the shaft angle as a state;
/// the EHL film reports its thinnest film, which grows with speed.
#[test]
fn component_reports_film_and_carries_the_shaft_angle() {
    let c = Component::from_text(&scene(
        r#"waviness = [{ race = "inner", order = 8, amplitude_um = 0.5 }]"#,
    ))
    .unwrap();
    let plain = Component::from_text(&scene("")).unwrap();
    assert_eq!(c.get_state().x.len(), plain.get_state().x.len() + 1);
    let lub = r#"lubrication = { film = "ehl" }"#;
    let film_at = |rpm: f64| {
        let mut c = Component::from_text(
            &scene(lub).replace("speed_rpm = 1750.0", &format!("speed_rpm = {rpm:?}")),
        )
        .unwrap();
        for i in 0..100 {
            c.do_step(i as f64 * H, H).unwrap();
        }
        c.get_real(vr("film.min_thickness")).unwrap()
    };
    let (h1, h2) = (film_at(1750.0), film_at(7000.0));
    println!("film.min_thickness: {h1:.3e} m at 1750 rpm, {h2:.3e} m at 7000 rpm");
    assert!(h1 > 1e-8 && h1 < 1e-6, "{h1}");
    // u^0.68 at nearly the same load.
    assert!(
        (h2 / h1 / 4f64.powf(0.68) - 1.0).abs() < 0.05,
        "{}",
        h2 / h1
    );
}

/// The defect profile: zero outside the pit, continuous with a continuous slope, limited by
/// Hr when the pit is deeper than Hr (the ball rides the edges) and by H when shallower
/// (it rests on the floor over part of the span).
#[test]
fn defect_profile_is_c1_and_limited_by_hr_or_h() {
    let r = 7.94e-3 / 2.0;
    let l = 1e-3;
    let hr = edge_depth(r, l);
    assert!((hr - (r - (r * r - l * l / 4.0).sqrt())).abs() < 1e-15);
    assert!((hr * 1e6 - 31.6).abs() < 0.1, "Hr = {hr}");
    for depth in [50e-6, 10e-6] {
        let d = Defect::new(DefectSite::Outer, 0.0, l, depth, r, 20e-3);
        let cap = depth.min(hr);
        let n = 20001;
        let ds = 1.2 * l / (n - 1) as f64;
        let s: Vec<f64> = (0..n).map(|i| -0.6 * l + i as f64 * ds).collect();
        let e: Vec<f64> = s.iter().map(|&x| d.loss_at(x)).collect();
        let max = e.iter().cloned().fold(0.0, f64::max);
        println!(
            "H = {:.0} µm: max loss {:.3} µm (cap {:.3} µm)",
            depth * 1e6,
            max * 1e6,
            cap * 1e6
        );
        assert!(max <= cap + 1e-18 && max >= 0.97 * cap, "{max} vs {cap}");
        assert!(e
            .iter()
            .zip(&s)
            .all(|(v, x)| x.abs() < 0.5 * l || *v == 0.0));
        // C¹: slopes change little from one sample to the next.
        let slope: Vec<f64> = e.windows(2).map(|w| (w[1] - w[0]) / ds).collect();
        let jump = slope
            .windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(0.0, f64::max);
        let smax = slope.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        assert!(jump < 0.02 * smax, "slope jump {jump} vs max slope {smax}");
        let on_floor = e.iter().filter(|v| (**v - depth).abs() < 1e-12).count();
        if depth < hr {
            assert!(
                on_floor as f64 * ds > 0.3 * l,
                "rests on the floor over a span"
            );
        } else {
            assert_eq!(on_floor, 0, "rides the edges, never touches the floor");
        }
    }
}

/// Bad effects are refused with the field and the allowed range.
#[test]
fn bad_effects_name_the_field() {
    for (fx, field) in [
        (
            r#"defects = [{ race = "outer", width_mm = 9.0, depth_um = 10.0 }]"#,
            "effects.defects[0].width_mm",
        ),
        (
            r#"defects = [{ race = "outer", width_mm = 1.0, depth_um = -1.0 }]"#,
            "effects.defects[0].depth_um",
        ),
        (
            r#"defects = [{ race = "ball", ball = 9, width_mm = 1.0, depth_um = 10.0 }]"#,
            "effects.defects[0].ball",
        ),
        (
            r#"waviness = [{ race = "outer", order = 0, amplitude_um = 1.0 }]"#,
            "effects.waviness[0].order",
        ),
        (
            r#"ball_spacing = { scatter = 2.0 }"#,
            "effects.ball_spacing.scatter",
        ),
        (
            r#"lubrication = { viscosity_pa_s = -1.0 }"#,
            "effects.lubrication.viscosity_pa_s",
        ),
        (
            r#"lubrication = { lubricant = "olive" }"#,
            "effects.lubrication.lubricant",
        ),
        (r#"bogus = 1"#, "bogus"),
    ] {
        let e = Component::from_text(&scene(fx)).unwrap_err().to_string();
        println!("{e}");
        assert!(e.contains(field), "{fx} -> {e}");
    }
}

/// The shipped scenes build and run, and with every effect on (defects on all three
/// elements, waviness on all three, spacing scatter, EHL film; 2- and 5-DOF) `do_step`
/// still performs no heap allocation.
#[test]
fn effects_do_not_allocate_in_do_step() {
    let all = r#"
defects = [{ race = "outer", angle_deg = 270.0, width_mm = 1.0, depth_um = 50.0 },
           { race = "inner", angle_deg = 10.0, width_mm = 0.5, depth_um = 5.0 },
           { race = "ball", ball = 3, width_mm = 0.5, depth_um = 20.0 }]
waviness = [{ race = "outer", order = 9, amplitude_um = 0.2 },
            { race = "inner", order = 10, amplitude_um = 0.2 },
            { race = "ball", order = 2, amplitude_um = 0.1 }]
ball_spacing = { scatter = 0.5, seed = 3 }
lubrication = { film = "ehl" }
"#;
    let five = scene(all)
        .replace("\"6205\"", "\"7008ce\"")
        .replace("level = \"ring\"", "level = \"ring\"\nring_dof = 5")
        .replace("\"load.z\" = 0.0", "\"load.z\" = 200.0");
    let probe = thread_alloc::allocations();
    std::hint::black_box(Vec::<u8>::with_capacity(16));
    assert!(thread_alloc::allocations() > probe, "the counter counts");
    for text in [
        scene(all),
        five,
        include_str!("../examples/scenes/6205-outer-spall.toml").to_string(),
        include_str!("../examples/scenes/7008ce-waviness.toml").to_string(),
    ] {
        let mut c = Component::from_text(&text).unwrap();
        for i in 0..3 {
            c.do_step(i as f64 * H, H).unwrap();
        }
        let before = thread_alloc::allocations();
        for i in 3..30 {
            c.do_step(i as f64 * H, H).unwrap();
        }
        assert_eq!(thread_alloc::allocations() - before, 0, "{text}");
        let film = c.get_real(vr("film.min_thickness")).unwrap();
        assert!(film > 0.0 && film < 2e-6, "{film}");
        let fy = c.get_real(vr("force.y")).unwrap();
        assert!(fy.is_finite() && fy > 0.0, "{fy}");
    }
}

/// Several defects at once: an outer- and an inner-race spall together show both BPFO and
/// BPFI in the envelope spectrum.
#[test]
fn outer_and_inner_defects_together_show_both_signatures() {
    let (k, _) = kin();
    let (_, f) = run(&scene(
        r#"defects = [{ race = "outer", angle_deg = 250.0, width_mm = 0.8, depth_um = 50.0 },
                      { race = "inner", angle_deg = 0.0, width_mm = 1.0, depth_um = 50.0 }]"#,
    ));
    let e = envelope(&f);
    assert_line(&e, "BPFO", k.bpfo, 5.0);
    assert_line(&e, "BPFI", k.bpfi, 5.0);
}

/// Ball-spacing scatter (seeded, within the pocket play) breaks the Z-fold symmetry: the
/// load pattern then repeats once per cage turn, not once per ball pass, and lines appear
/// at multiples of the cage frequency n FTF, absent from the evenly spaced bearing.
#[test]
fn spacing_scatter_adds_lines_at_multiples_of_the_cage_frequency() {
    let (k, _) = kin();
    let (_, _, s, sh) = with_healthy("ball_spacing = { scatter = 1.0, seed = 7 }");
    for n in 1..=4 {
        let f = n as f64 * k.ftf;
        let label = format!("{n} FTF");
        assert_line(&s, &label, f, 5.0);
        let ratio = s.at(f) / sh.at(f);
        println!("{label}: scattered / even = {ratio:.3e}");
        assert!(ratio > 1000.0, "{label}: {ratio}");
    }
}

/// The effects section survives a JSON round trip (the form programs send): the component
/// built from the JSON runs bit for bit like the one built from TOML.
#[test]
fn effects_round_trip_through_json() {
    let text = include_str!("../examples/scenes/6205-outer-spall.toml");
    let scene = raceway::Scene::from_text(text).unwrap();
    let json = serde_json::to_string(&scene).unwrap();
    assert!(json.contains("\"defects\"") && json.contains("\"lubrication\""));
    let mut a = Component::from_text(text).unwrap();
    let mut b = Component::from_text(&json).unwrap();
    for i in 0..20 {
        a.do_step(i as f64 * H, H).unwrap();
        b.do_step(i as f64 * H, H).unwrap();
    }
    assert_eq!(outputs(&mut a), outputs(&mut b));
}

/// Ball waviness: a ball's diameter varies with its even orders only (`w(phi) + w(phi+pi)`):
/// order 2 on every ball (same phase) modulates the clearance at 2 BSF; order 3 does
/// nothing at all.
#[test]
fn ball_waviness_of_even_order_excites_its_spin_harmonic() {
    let (k, _) = kin();
    let (y, yh, s, sh) =
        with_healthy(r#"waviness = [{ race = "ball", order = 2, amplitude_um = 0.3 }]"#);
    assert_line(&s, "2 BSF", 2.0 * k.bsf, 100.0);
    let ratio = s.at(2.0 * k.bsf) / sh.at(2.0 * k.bsf);
    println!("ball order 2: y at 2 BSF, wavy / healthy = {ratio:.3e}");
    assert!(ratio > 1000.0, "{ratio}");
    let (y3, _) = run(&scene(
        r#"waviness = [{ race = "ball", order = 3, amplitude_um = 0.3 }]"#,
    ));
    // Unchanged to the integration tolerance (the odd orders' offsets cancel to round-off,
    // but the shaft-angle state they add changes the integrator's error norm and steps).
    let (d3, d2) = (max_diff(&y3, yh), max_diff(&y, yh));
    println!("ball waviness: max |y - healthy| order 3 {d3:.3e} m, order 2 {d2:.3e} m");
    assert!(
        d3 < 1e-4 * d2,
        "odd ball orders leave the response unchanged: {d3:e} vs {d2:e}"
    );
}
