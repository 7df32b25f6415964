//! ISO/TS 16281 lamina life at the ring level (docs/physics.md §R10): the run's summary gathers
//! every recorded state's lamina loads over the analysed window (`summary::rollers::
//! ring_lamina_life`), and a steady run agrees with the quasi-static table at the same
//! displacement.

use raceway::component::Scene;
use raceway::runner::{run_into, Record, Series, Tee};
use raceway::summary::rollers::{report, ring_lamina_life};
use raceway::summary::{digest_for, summarize};

/// NU206 on the 2-DOF ring level, motion-driven, the shaft held `y0` (m) off centre at
/// `rpm`, `steps` steps of 0.1 ms.
fn scene(y0: f64, rpm: f64, steps: usize) -> Scene {
    Scene::from_text(&format!(
        "title = \"NU206 steady\"\nbearing = \"NU206\"\n\n[model]\nlevel = \"ring\"\ncausality = \"motion\"\nring_dof = 2\n\n\
         [inputs]\nrule = \"velocity\"\nspeed_rpm = {rpm:?}\ninitial = {{ \"shaft.y\" = {y0:e} }}\n\n\
         [run]\nduration_s = {:e}\nstep_s = 1e-4\n",
        steps as f64 * 1e-4
    ))
    .unwrap()
}

/// The run's lamina life (with and without the edge factor), the window's states and the
/// force on the shaft at the end.
fn run(s: &Scene) -> (f64, f64, usize, [f64; 5], serde_json::Value) {
    let mut series = Series::default();
    let mut digest = digest_for(s);
    let comp = run_into(
        s,
        Record::default(),
        false,
        &mut |_| {},
        &mut || false,
        &mut Tee(&mut series, &mut digest),
    )
    .unwrap();
    let (life, plain, n) = ring_lamina_life(s, &digest, &comp).unwrap();
    let force = ["force.x", "force.y", "force.z", "moment.x", "moment.y"].map(|n| digest.last(n));
    let sm = summarize(s, "steady", &digest, &comp, 0.0);
    assert!(
        sm.text
            .contains("ISO/TS 16281 lamina life over the analysed window"),
        "{}",
        sm.text
    );
    assert!(sm.text.contains("UNSOURCED"), "{}", sm.text);
    (
        life.l10r_mrev.unwrap(),
        plain.l10r_mrev.unwrap(),
        n,
        force,
        sm.json["lamina_life"].clone(),
    )
}

/// The quasi-static table of the bearing `designation` under the load that balances the
/// force `force` a run ended with, at rest.
fn table_for(designation: &str, force: [f64; 5]) -> raceway::summary::rollers::RollerQsReport {
    let b = raceway::geometry::roller_catalogue::lookup(designation)
        .unwrap()
        .build()
        .unwrap();
    let names = (["fx", "fy", "fz", "mx", "my"], "speed");
    report(&b, 0.0, force.map(|f| -f), names).unwrap()
}

/// A steady run (shaft held 30 µm down, not turning: every state is the same state, the
/// rollers at the quasi-static table's azimuths `2 pi j/Z`) has the table's lamina life at
/// the same displacement: the table solved for the run's force lands on the run's
/// displacement, and its life (power means over the Z rollers of one state) equals the
/// window's (over the rollers of every state) to rounding, with and without the edge factor.
#[test]
fn a_steady_run_has_the_quasi_static_tables_lamina_life() {
    let y0 = -30e-6;
    let s = scene(y0, 0.0, 20);
    let (life, plain, n, force, json) = run(&s);
    assert_eq!(n, 11, "the second half of 21 rows");
    assert_eq!(json["states [1]"], 11);
    let qs = table_for("NU206", force);
    let q = qs.solution.q;
    assert!(
        (q[1] / y0 - 1.0).abs() < 1e-9 && q[0].abs() < 1e-12,
        "the table's displacement {q:?}"
    );
    let t = qs.lamina_life.l10r_mrev.unwrap();
    let tp = qs.lamina_life_without_edge_factor.l10r_mrev.unwrap();
    assert!((life / t - 1.0).abs() < 1e-8, "ring {life} table {t}");
    assert!((plain / tp - 1.0).abs() < 1e-8, "ring {plain} table {tp}");
    // The edge factor shortens the life of these profiled rollers only a little (their end
    // laminae are relieved): a check that the two are not the same figure.
    assert!(life < plain, "{life} {plain}");
}

/// Turning, the rollers visit every azimuth over the window: the life over many roller
/// passes differs from the one state's (rollers at `2 pi j/Z` only) by the spread of the
/// load zone's sampling, a little; a heavier displacement shortens it as the lamina loads'
/// power law says (`q ∝ delta^(10/9)`, life `∝ q^-4` and more for the laminae that close).
#[test]
fn a_turning_run_averages_the_rollers_over_the_window() {
    let (still, ..) = run(&scene(-30e-6, 0.0, 20));
    // 1500 rpm: a roller passes an azimuth every 1/BPFO = 7 ms; 400 steps analyse 20 ms.
    let (turning, _, n, ..) = run(&scene(-30e-6, 1500.0, 400));
    assert_eq!(n, 201);
    let rel = turning / still - 1.0;
    assert!(
        rel.abs() < 0.05 && rel != 0.0,
        "turning {turning} still {still}"
    );
    let (heavier, ..) = run(&scene(-40e-6, 1500.0, 400));
    assert!(
        heavier < turning * (30.0f64 / 40.0).powf(40.0 / 9.0),
        "{heavier} {turning}"
    );
}

/// 30206 on the 5-DOF ring level, motion-driven, the cone held at `q0 = (y, z, rx)` (m, m,
/// rad) at `rpm`, `steps` steps of 0.1 ms.
fn tapered(q0: [f64; 3], rpm: f64, steps: usize) -> Scene {
    Scene::from_text(&format!(
        "title = \"30206 steady\"\nbearing = \"30206\"\n\n[model]\nlevel = \"ring\"\ncausality = \"motion\"\nring_dof = 5\n\n\
         [inputs]\nrule = \"velocity\"\nspeed_rpm = {rpm:?}\n\
         initial = {{ \"shaft.y\" = {:e}, \"shaft.z\" = {:e}, \"shaft.rx\" = {:e} }}\n\n\
         [run]\nduration_s = {:e}\nstep_s = 1e-4\n",
        q0[0],
        q0[1],
        q0[2],
        steps as f64 * 1e-4
    ))
    .unwrap()
}

/// A tapered roller bearing held still on the ring level (cone 10 µm down and 20 µm along
/// `+z`, the direction that loads it) has the quasi-static table's lamina life at the same
/// displacement: cone laminae on the inner raceway, cup laminae on the outer, the same
/// ratings (ISO 281's `Cr` with the cup angle), to rounding, with and without the edge factor.
#[test]
fn a_steady_tapered_run_has_the_quasi_static_tables_lamina_life() {
    let q0 = [-10e-6, 20e-6, 0.0];
    let s = tapered(q0, 0.0, 20);
    let (life, plain, n, force, json) = run(&s);
    assert_eq!(n, 11);
    assert_eq!(json["states [1]"], 11);
    let qs = table_for("30206", force);
    let q = qs.solution.q;
    assert!(
        (q[1] / q0[0] - 1.0).abs() < 1e-7 && (q[2] / q0[1] - 1.0).abs() < 1e-7,
        "the table's displacement {q:?}"
    );
    assert!(q[0].abs() < 1e-12 && q[3].abs() < 1e-9 && q[4].abs() < 1e-9);
    let t = qs.lamina_life.l10r_mrev.unwrap();
    let tp = qs.lamina_life_without_edge_factor.l10r_mrev.unwrap();
    let r = &qs.lamina_life;
    eprintln!(
        "30206 still: L10r {life:.1} Mrev (table {t:.1}, relative gap {:.1e}), inner {:.0}, \
         outer {:.0}, without the edge factor {plain:.0} Mrev",
        (life / t - 1.0).abs(),
        r.inner_mrev.unwrap(),
        r.outer_mrev.unwrap()
    );
    assert!((life / t - 1.0).abs() < 1e-8, "ring {life} table {t}");
    assert!((plain / tp - 1.0).abs() < 1e-8, "ring {plain} table {tp}");
    // The cone (inner, rotating) raceway is the weaker one: its rating `Q_ci` is the lower
    // (the `(1 - gamma)` side of the Lundberg–Palmgren ratings) and the catalogue's flange,
    // square to the roller axis, gives the cone the cup's load (`rho_i = 1`).
    let r = &qs.lamina_life;
    assert!(r.ratings.q_ci < r.ratings.q_ce);
    assert!(r.inner_mrev.unwrap() < r.outer_mrev.unwrap(), "{r:?}");
    assert!(life < plain);
}

/// Limits on the tapered bearing turning at 1500 rpm: more axial approach (more load)
/// shortens the life; and with the cone pushed along `+z` alone (every roller loaded alike), a
/// misalignment of 0.2 mrad at the same displacement shortens it too (the rollers on one side
/// press harder, and each roller's load moves toward one end), the more so with the
/// edge-stress factor, which weights the end laminae.
#[test]
fn more_load_or_a_tilt_shortens_the_tapered_life() {
    let (base, ..) = run(&tapered([-10e-6, 20e-6, 0.0], 1500.0, 200));
    let (heavier, ..) = run(&tapered([-10e-6, 30e-6, 0.0], 1500.0, 200));
    eprintln!("30206 at 1500 rpm: 20 µm along +z {base:.0} Mrev, 30 µm {heavier:.0} Mrev");
    assert!(heavier < 0.5 * base, "{heavier} {base}");
    let (axial, axial_plain, ..) = run(&tapered([0.0, 20e-6, 0.0], 1500.0, 200));
    eprintln!("30206 pushed along +z alone: aligned {axial:.0} Mrev");
    let mut last = (axial, axial_plain);
    for rx in [0.2e-3, -0.2e-3, 0.4e-3] {
        let (t, tp, ..) = run(&tapered([0.0, 20e-6, rx], 1500.0, 200));
        eprintln!("  tilt {:.1} mrad: {t:.0} Mrev", rx * 1e3);
        assert!(t < axial && tp < axial_plain, "rx {rx}: {t} {axial}");
        assert!(
            t / tp < axial / axial_plain,
            "rx {rx}: the edge factor bites harder tilted"
        );
        if rx > 0.3e-3 {
            assert!(t < last.0, "a larger tilt, a shorter life: {t} {}", last.0);
        }
        last = (t, tp);
    }
}
