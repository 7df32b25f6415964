//! The rolling elements' contact loads a run records for its ball-load plot
//! (`runner::run_into_with_loads`): the levels' own loads, checked against the quasi-static
//! solver, against the force they put on the shaft (their vector sum), and at a spall.

use raceway::component::{Component, Scene};
use raceway::geometry::kinematics::nominal_cage_speed;
use raceway::models::quasi_static::{BallResult, BallState, Options, QuasiStatic};
use raceway::runner::{self, LoadRecord, Record, Series};
use raceway::seam::element::ElementLoad;

/// Run `scene` recording its element loads: the series and the record.
fn run_with_loads(scene: &Scene) -> (Series, LoadRecord, Component) {
    let mut series = Series::default();
    let mut loads = LoadRecord::for_scene(scene);
    let c = runner::run_into_with_loads(
        scene,
        Record::default(),
        false,
        &mut |_| {},
        &mut || false,
        &mut series,
        &mut loads,
    )
    .unwrap();
    (series, loads, c)
}

fn last(s: &Series, name: &str) -> f64 {
    *s.column(name).unwrap().last().unwrap()
}

/// `sum_j Q_j (cos psi_j, sin psi_j)` of the inner contacts, each radial part scaled by
/// `radial[j]` (the cosine of its contact angle; 1 for a radial contact).
fn vector_sum(loads: &[ElementLoad], radial: impl Fn(usize) -> f64) -> (f64, f64) {
    loads.iter().enumerate().fold((0.0, 0.0), |(x, y), (j, l)| {
        let q = l.inner * radial(j);
        (x + q * l.psi.cos(), y + q * l.psi.sin())
    })
}

/// The default scene (quasi-static level, shaft held 10 µm down at 1750 rpm): the loads
/// recorded at the last step are the quasi-static solver's Jones–Harris loads at the same
/// azimuths and motion, ball by ball, to 1e-6 of the largest (the level's warm-started
/// solves against cold ones, both converged far below that); the azimuths are the cage's
/// kinematic travel from 0 (`+x`) toward `+y`, as the plot's axis says; and the inner
/// contacts' radial parts sum to the force on the shaft, reversed.
#[test]
fn the_quasi_static_levels_loads_are_its_jones_harris_table() {
    let mut scene = Scene::default_scene();
    scene.run.duration_s = 0.01;
    let (s, rec, c) = run_with_loads(&scene);
    assert!(rec.available && rec.points > 0);
    assert_eq!(rec.t_last, 0.01);
    let b = c.bearing().clone();
    assert_eq!(rec.last.len(), b.z);
    let q: [f64; 5] = std::array::from_fn(|k| {
        last(
            &s,
            ["shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry"][k],
        )
    });
    let omega = last(&s, "shaft.omega");
    // The cage angle: the kinematic cage speed times the time, toward +y at positive speed.
    let theta = nominal_cage_speed(&b, omega) * rec.t_last;
    assert!(theta > 0.0);
    for (j, l) in rec.last.iter().enumerate() {
        let want = theta + 2.0 * std::f64::consts::PI * j as f64 / b.z as f64;
        assert!((l.psi - want).abs() < 1e-9, "ball {j}: {} vs {want}", l.psi);
    }
    let qs = QuasiStatic::new(&b, Options::default()).unwrap();
    let psi: Vec<f64> = rec.last.iter().map(|l| l.psi).collect();
    let mut st = vec![BallState::default(); b.z];
    let mut res = vec![BallResult::default(); b.z];
    qs.evaluate(&q, omega, &psi, &mut st, None, Some(&mut res))
        .unwrap();
    let top = res.iter().fold(0.0f64, |m, r| m.max(r.q_i));
    assert!(top > 100.0, "a loaded bearing: {top} N");
    for (l, r) in rec.last.iter().zip(&res) {
        println!("{} {} {} | {} {}", l.psi, l.inner, l.outer, r.q_i, r.q_o);
        assert!(
            (l.inner - r.q_i).abs() <= 1e-6 * top,
            "{} vs {}",
            l.inner,
            r.q_i
        );
        assert!(
            (l.outer - r.q_o).abs() <= 1e-6 * top,
            "{} vs {}",
            l.outer,
            r.q_o
        );
    }
    let (sx, sy) = vector_sum(&rec.last, |j| res[j].alpha_i.cos());
    let (fx, fy) = (last(&s, "force.x"), last(&s, "force.y"));
    println!("sum {sx} {sy} force {fx} {fy}");
    let f = fx.hypot(fy);
    assert!((sx + fx).abs() < 1e-6 * f && (sy + fy).abs() < 1e-6 * f);
}

/// The ring level on the default scene's motion (2 DOF, dry, no damping): its massless
/// balls' loads sum to the force on the shaft (reversed) to rounding at the last step;
/// under the held motion each envelope bin's largest and smallest load differ only by
/// the load's change across the bin; and the loads are the Jones–Harris loads of the quasi-static solver to within the
/// centrifugal force the massless model leaves out (a 6205 ball at 1750 rpm: 0.21 N of
/// about 270 N).
#[test]
fn the_ring_levels_loads_sum_to_the_force_and_match_jones_harris() {
    let mut scene = Scene::from_text(
        &raceway::component::scene::DEFAULT_SCENE
            .replace("level = \"quasi_static\"", "level = \"ring\"\nring_dof = 2"),
    )
    .unwrap();
    scene.run.duration_s = 0.05;
    let (s, rec, c) = run_with_loads(&scene);
    assert!(rec.available && rec.last_revolution);
    let (sx, sy) = vector_sum(&rec.last, |_| 1.0);
    let (fx, fy) = (last(&s, "force.x"), last(&s, "force.y"));
    let f = fx.hypot(fy);
    println!("ring sum {sx} {sy} force {fx} {fy}");
    assert!(f > 100.0);
    assert!((sx + fx).abs() < 1e-12 * f && (sy + fy).abs() < 1e-12 * f);
    let b = c.bearing().clone();
    let q: [f64; 5] = std::array::from_fn(|k| {
        last(
            &s,
            ["shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry"][k],
        )
    });
    let qs = QuasiStatic::new(&b, Options::default()).unwrap();
    let psi: Vec<f64> = rec.last.iter().map(|l| l.psi).collect();
    let mut st = vec![BallState::default(); b.z];
    let mut res = vec![BallResult::default(); b.z];
    qs.evaluate(
        &q,
        last(&s, "shaft.omega"),
        &psi,
        &mut st,
        None,
        Some(&mut res),
    )
    .unwrap();
    let top = res.iter().fold(0.0f64, |m, r| m.max(r.q_i));
    let worst = rec
        .last
        .iter()
        .zip(&res)
        .fold(0.0f64, |m, (l, r)| m.max((l.inner - r.q_i).abs()));
    // The centrifugal force: what the table's outer contact carries over its inner one.
    let fc = res.iter().fold(0.0f64, |m, r| m.max(r.q_o - r.q_i));
    println!("ring vs JH worst {worst} of {top}; centrifugal {fc}");
    assert!(
        fc > 0.0 && worst < fc,
        "{worst} N (centrifugal {fc} N) of {top} N"
    );
    // Held motion: each bin's extremes differ only by the load's change over one bin.
    for (k, (hi, lo)) in rec.inner.max.iter().zip(&rec.inner.min).enumerate() {
        if hi.is_finite() {
            assert!(hi - lo < 0.05 * top, "bin {k}: {lo} to {hi}");
        }
    }
}

/// Step `scene`'s component (its inputs held at their initial values, as the shipped
/// defect scenes hold them) for `steps` steps of its `run.step_s`, and hand the element
/// loads at each step's end to `each`.
fn step_with_loads(scene: &Scene, steps: usize, mut each: impl FnMut(f64, &[ElementLoad])) {
    let mut c = Component::new(scene.clone()).unwrap();
    assert!(c.keep_element_loads());
    let h = scene.run.step_s;
    let mut loads = Vec::new();
    for i in 0..steps {
        c.do_step(i as f64 * h, h).unwrap();
        assert!(c.element_loads(&mut loads));
        each((i + 1) as f64 * h, &loads);
    }
}

/// At every step where an element sits within `within` (rad) of the azimuth `at`, its
/// load over the loads of the elements before and after it (the largest such ratio, and
/// how many steps had one there).
fn worst_ratio_at(scene: &Scene, steps: usize, at: f64, within: f64) -> (f64, usize) {
    let (mut worst, mut n) = (0.0f64, 0);
    step_with_loads(scene, steps, |_, l| {
        let z = l.len();
        for j in 0..z {
            let d = raceway::models::defects::wrap_exact(l[j].psi - at);
            if d.abs() < within {
                let beside = l[(j + 1) % z].inner.min(l[(j + z - 1) % z].inner);
                assert!(beside > 0.0, "neighbours loaded");
                worst = worst.max(l[j].inner / beside);
                n += 1;
            }
        }
    });
    (worst, n)
}

/// The 6205 outer-race spall (1 mm wide, 50 µm deep at 270°, deeper than the 31.6 µm a
/// ball's edge ride reaches): at every step of the first 0.1 s where a ball is within
/// 0.2° of the spall's middle (where the spall takes more than its approach of about
/// 15 µm away) it carries less than a twentieth of the load of either of its neighbours
/// (they take the load it loses); the envelope over the last shaft revolution
/// shows it: the smallest load in the bins over the spall's middle (269° to 271°) is below
/// a quarter of the smallest a few degrees either side. The loads' vector sum is the force
/// on the shaft (reversed) but for the contact and squeeze damping, which the loads leave
/// out: within 2 % of the force.
#[test]
fn a_ball_over_the_spall_carries_less_than_its_neighbours() {
    let text = include_str!("../examples/scenes/6205-outer-spall.toml");
    let scene = Scene::from_text(text).unwrap();
    let spall = 270f64.to_radians();
    let (worst, n) = worst_ratio_at(&scene, 1000, spall, 0.2f64.to_radians());
    println!("ball over the spall: worst ratio {worst} at {n} steps");
    assert!(n >= 3 && worst < 0.05, "{worst} at {n} steps");
    let (s, rec, _) = run_with_loads(&scene);
    assert!(rec.available && rec.last_revolution);
    let lo = &rec.inner.min;
    let over = lo[269].min(lo[270]);
    let beside = (262..266)
        .chain(275..279)
        .fold(f64::INFINITY, |m, k| m.min(lo[k]));
    println!("over {over} beside {beside}");
    assert!(
        over < 0.25 * beside,
        "{over} N over the spall, {beside} N beside"
    );
    let (sx, sy) = vector_sum(&rec.last, |_| 1.0);
    let (fx, fy) = (last(&s, "force.x"), last(&s, "force.y"));
    println!("spall sum {sx} {sy} force {fx} {fy}");
    let f = fx.hypot(fy);
    assert!(
        (sx + fx).hypot(sy + fy) < 0.02 * f,
        "{sx} {sy} vs {fx} {fy}"
    );
}

/// The NU206 with a 20 µm spall over half its raceway's width at 270°: each roller's load
/// is its laminae's sum, so the rollers' vector sum is the force on the shaft (reversed)
/// but for the contact damping (within 2 %); a roller within 0.3° of the spall's middle
/// loses the laminae the spall spans and carries less than the rollers before and after
/// it at every such step, which the envelope shows as a dip below three quarters of the
/// smallest load a few degrees either side.
#[test]
fn a_roller_over_the_half_spall_carries_less() {
    let text = include_str!("../examples/scenes/nu206-outer-defect.toml");
    let mut scene = Scene::from_text(text).unwrap();
    let spall = 270f64.to_radians();
    let (worst, n) = worst_ratio_at(&scene, 1000, spall, 0.3f64.to_radians());
    println!("roller over the spall: worst ratio {worst} at {n} steps");
    assert!(n >= 3 && worst < 1.0, "{worst} at {n} steps");
    scene.run.duration_s = 0.2;
    let (s, rec, _) = run_with_loads(&scene);
    assert!(rec.available && rec.last_revolution);
    let lo = &rec.inner.min;
    let over = lo[269].min(lo[270]);
    let beside = (264..267)
        .chain(273..276)
        .fold(f64::INFINITY, |m, k| m.min(lo[k]));
    println!("over {over} beside {beside}");
    assert!(
        over < 0.75 * beside,
        "{over} N over the spall, {beside} N beside"
    );
    let (sx, sy) = vector_sum(&rec.last, |_| 1.0);
    let (fx, fy) = (last(&s, "force.x"), last(&s, "force.y"));
    println!("roller sum {sx} {sy} force {fx} {fy}");
    let f = fx.hypot(fy);
    assert!(
        (sx + fx).hypot(sy + fy) < 0.02 * f,
        "{sx} {sy} vs {fx} {fy}"
    );
}

/// Recording the loads changes no bit of a run: the series with and without are equal
/// (the ring level evaluates its outputs again instead of reusing the last stage's, the
/// same arithmetic), and a run not asked keeps nothing.
#[test]
fn recording_the_loads_changes_no_bit_of_the_run() {
    for text in [
        raceway::component::scene::DEFAULT_SCENE,
        include_str!("../examples/scenes/6205-outer-spall.toml"),
        include_str!("../examples/scenes/nu206-outer-defect.toml"),
    ] {
        let mut scene = Scene::from_text(text).unwrap();
        scene.run.duration_s = 0.01;
        let (with, rec, _) = run_with_loads(&scene);
        assert!(rec.available);
        let (without, c) = runner::run(&scene, &mut |_| {}).unwrap();
        assert_eq!(with, without, "{}", scene.title);
        assert!(!c.element_loads(&mut Vec::new()));
    }
    // A level that does not resolve its elements records none.
    let text = include_str!("../examples/scenes/6205-linear.toml");
    let mut scene = Scene::from_text(text).unwrap();
    scene.run.duration_s = 0.005;
    let (_, rec, mut c) = run_with_loads(&scene);
    assert!(!rec.available && rec.last.is_empty() && !c.keep_element_loads());
}
