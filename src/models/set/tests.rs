use super::*;
use crate::models::quasi_static::{Options, QuasiStatic};
use crate::units::rpm_to_rad_s;

fn b7008() -> Bearing {
    bearing_by_name("7008CE", "bearing").unwrap()
}

fn pair(arr: Arrangement, preload: Preload) -> Set {
    Set::new(&SetSpec::pair(&b7008(), arr, 0.0, preload).unwrap()).unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

/// A rigidly preloaded DB pair under no external load: the two rows carry equal and
/// opposite axial loads (the preload), the shaft stays at its reference, and an offset
/// preload gives the same as the force it produces.
#[test]
fn rigid_db_pair_carries_equal_and_opposite_row_loads() {
    let mut s = pair(Arrangement::Db, Preload::Force(300.0));
    let sol = s.solve(&[0.0; 5], 0.0).unwrap();
    let (a, b) = (&sol.rows[0], &sol.rows[1]);
    assert!(rel(a.axial_load, 300.0) < 1e-9, "{}", a.axial_load);
    assert!(rel(b.axial_load, 300.0) < 1e-9, "{}", b.axial_load);
    assert!(
        (a.force[2] + b.force[2]).abs() < 1e-7 * 300.0,
        "{} {}",
        a.force[2],
        b.force[2]
    );
    // The row facing +z pushes the shaft toward -z.
    assert!(a.force[2] < 0.0 && b.force[2] > 0.0);
    assert!(sol.q.iter().all(|v| v.abs() < 1e-12), "{:?}", sol.q);
    // The rigid offset that force corresponds to, given as an offset, gives the force.
    let delta = 2.0 * sol.rows[0].displacement[2];
    let mut s2 = pair(Arrangement::Db, Preload::Offset(delta));
    let sol2 = s2.solve(&[0.0; 5], 0.0).unwrap();
    assert!(
        rel(sol2.rows[0].axial_load, 300.0) < 1e-8,
        "{}",
        sol2.rows[0].axial_load
    );
    assert!(rel(sol2.rows[1].axial_load, 300.0) < 1e-8);
}

/// The pair's axial stiffness is the sum of the two rows' axial stiffnesses at the
/// preload point, each row solved on its own by the quasi-static model under the preload
/// as a pure axial load.
#[test]
fn db_axial_stiffness_is_the_sum_of_the_rows() {
    let f = 300.0;
    let mut s = pair(Arrangement::Db, Preload::Force(f));
    let sol = s.solve(&[0.0; 5], 0.0).unwrap();
    let qs = QuasiStatic::new(&b7008(), Options::default()).unwrap();
    let one = qs.solve(&[0.0, 0.0, f, 0.0, 0.0], 0.0).unwrap();
    let k_row = one.stiffness[2][2];
    assert!(
        rel(sol.stiffness[2][2], 2.0 * k_row) < 0.01,
        "{} vs {}",
        sol.stiffness[2][2],
        2.0 * k_row
    );
    // And an external thrust toward +z loads the row facing +z, unloads the other.
    let sol = s.solve(&[0.0, 0.0, 200.0, 0.0, 0.0], 0.0).unwrap();
    assert!(sol.rows[0].axial_load > f && sol.rows[1].axial_load < f);
    assert!(rel(sol.rows[0].axial_load - sol.rows[1].axial_load, 200.0) < 1e-7);
}

/// Back to back is stiffer in tilt than face to face at equal preload (load centres
/// `dm/2 tan(alpha)` outside against inside the rows); the radial and axial stiffnesses
/// are the same (the mirror changes only the moment arms).
#[test]
fn db_is_stiffer_in_tilt_than_df() {
    let f = 300.0;
    let db = pair(Arrangement::Db, Preload::Force(f))
        .solve(&[0.0; 5], 0.0)
        .unwrap();
    let df = pair(Arrangement::Df, Preload::Force(f))
        .solve(&[0.0; 5], 0.0)
        .unwrap();
    let (kdb, kdf) = (db.stiffness[3][3], df.stiffness[3][3]);
    assert!(kdb > 2.0 * kdf, "DB {kdb} N m/rad, DF {kdf} N m/rad");
    assert!(rel(db.stiffness[2][2], df.stiffness[2][2]) < 1e-9);
    assert!(rel(db.stiffness[0][0], df.stiffness[0][0]) < 1e-9);
    // Symmetric in x and y.
    assert!(rel(db.stiffness[4][4], kdb) < 1e-6);
}

fn fd_check(s: &mut Set, q: [f64; 5], omega: f64) {
    let k = s.evaluate(&q, omega).unwrap().stiffness;
    for col in 0..5 {
        let h = if col < 3 { 1e-9 } else { 1e-7 };
        let (mut qp, mut qm) = (q, q);
        qp[col] += h;
        qm[col] -= h;
        let fp = s.evaluate(&qp, omega).unwrap().force;
        let fm = s.evaluate(&qm, omega).unwrap().force;
        for row in 0..5 {
            let fd = -(fp[row] - fm[row]) / (2.0 * h);
            let scale = (k[row][row].abs() * k[col][col].abs()).sqrt();
            assert!(
                (k[row][col] - fd).abs() < 2e-5 * scale,
                "K[{row}][{col}] {} vs finite difference {fd}",
                k[row][col]
            );
        }
    }
}

/// The analytic 5x5 stiffness at the reference point (rows' K transformed, the spring's
/// shift condensed out) equals the central difference of the set's forces.
#[test]
fn stiffness_matches_finite_differences() {
    let q = [3e-6, -2e-6, 4e-6, 1e-4, -5e-5];
    let w = rpm_to_rad_s(12_000.0);
    let mut rigid = pair(Arrangement::Db, Preload::Force(300.0));
    fd_check(&mut rigid, q, w);
    let mut df = pair(Arrangement::Df, Preload::Force(300.0));
    fd_check(&mut df, q, 0.0);
    let mut spring = pair(
        Arrangement::Db,
        Preload::Spring {
            stiffness: 20e6,
            force: 300.0,
        },
    );
    fd_check(&mut spring, q, w);
}

/// A constant-force (spring) preload keeps its force under speed; a rigid one changes it
/// (the balls' centrifugal force turns the outer contact angles down and the inner ones
/// up, which moves the rings of each row apart against the clamp).
#[test]
fn spring_preload_holds_its_force_under_speed_and_rigid_does_not() {
    let f = 300.0;
    let w = rpm_to_rad_s(30_000.0);
    let mut rigid = pair(Arrangement::Db, Preload::Force(f));
    let r = rigid.solve(&[0.0; 5], w).unwrap();
    // 0.5 N/µm, soft against the pair's axial stiffness (two rows of ~4e7 N/m in series):
    // the force changes by about the rigid change times k_s / (k_s + k_series).
    let mut spring = pair(
        Arrangement::Db,
        Preload::Spring {
            stiffness: 0.5e6,
            force: f,
        },
    );
    let s = spring.solve(&[0.0; 5], w).unwrap();
    let d_rigid = (r.rows[0].axial_load - f).abs() / f;
    let d_spring = (s.rows[0].axial_load - f).abs() / f;
    // The spring's force changes by k_s u exactly.
    assert!(rel(s.rows[1].axial_load, f + 0.5e6 * s.spring_shift) < 1e-8);
    assert!(d_rigid > 0.05, "rigid preload change {d_rigid}");
    assert!(
        d_spring < 0.1 * d_rigid,
        "spring {d_spring} vs rigid {d_rigid}"
    );
    // Contact angles at speed: outer below inner on every loaded ball.
    for a in &r.rows[0].contact_angles {
        assert!(a[1] < a[0], "{a:?}");
    }
}

/// Bad input is refused naming the field.
#[test]
fn bad_sets_are_refused_by_field() {
    let b = b7008();
    let e = SetSpec::pair(&b, Arrangement::Db, -1e-3, Preload::None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("set.spacer_mm") && e.contains(">= 0"), "{e}");
    let overlap = SetSpec {
        rows: vec![
            Row {
                bearing: b.clone(),
                position: 0.0,
                orientation: 1,
            },
            Row {
                bearing: b.clone(),
                position: 5e-3,
                orientation: -1,
            },
        ],
        preload: Preload::None,
    };
    let e = overlap.validate().unwrap_err().to_string();
    assert!(
        e.contains("set.row[1].position_mm") && e.contains("overlap"),
        "{e}"
    );
    let nu = bearing_by_name("NU206", "b").unwrap();
    let rollers = SetSpec {
        rows: vec![
            Row {
                bearing: nu.clone(),
                position: -10e-3,
                orientation: 1,
            },
            Row {
                bearing: nu,
                position: 10e-3,
                orientation: -1,
            },
        ],
        preload: Preload::None,
    };
    let e = rollers.validate().unwrap_err().to_string();
    assert!(e.contains("set.row") && e.contains("axial"), "{e}");
    let e = SetSpec::pair(
        &b,
        Arrangement::Db,
        0.0,
        Preload::Class(PreloadClass::Light),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("set.preload_class") && e.contains("preload_n"),
        "{e}"
    );
    let e = SetSpec::pair(&b, Arrangement::Dt, 0.0, Preload::Force(100.0))
        .unwrap_err()
        .to_string();
    assert!(e.contains("set.preload"), "{e}");
    let e = SetSpec::pair(&b, Arrangement::Db, 0.0, Preload::Force(-1.0))
        .unwrap_err()
        .to_string();
    assert!(e.contains("set.preload_n"), "{e}");
    let mut bad = overlap.clone();
    bad.rows[1].position = 20e-3;
    bad.rows[1].orientation = 0;
    let e = bad.validate().unwrap_err().to_string();
    assert!(e.contains("set.row[1].orientation"), "{e}");
}

/// The system life: equal slopes in closed form, mixed slopes at `sum (L/L_i)^e_i = 1`;
/// an unloaded row does not fail.
#[test]
fn system_life_of_rows() {
    let e = 10.0 / 9.0;
    let l = system_life(&[(Some(100.0), e), (Some(100.0), e), (None, e)]).unwrap();
    assert!(rel(l, 100.0 * 2f64.powf(-1.0 / e)) < 1e-14);
    let lives = [(Some(50.0), e), (Some(80.0), 9.0 / 8.0)];
    let l = system_life(&lives).unwrap();
    let g: f64 = lives
        .iter()
        .map(|(li, ei)| (l / li.unwrap()).powf(*ei))
        .sum();
    assert!((g - 1.0).abs() < 1e-12 && l < 50.0, "{l} {g}");
    assert!(system_life(&[(None, e)]).is_none());
}

/// Each row of a loaded DB pair has a life, and the set's life is below the shorter one.
#[test]
fn loaded_pair_life_is_below_each_rows() {
    let mut s = pair(Arrangement::Db, Preload::Force(300.0));
    let sol = s
        .solve(&[1000.0, 0.0, 500.0, 0.0, 0.0], rpm_to_rad_s(6000.0))
        .unwrap();
    let l0 = sol.rows[0].life_mrev.unwrap();
    let l1 = sol.rows[1].life_mrev.unwrap();
    let l = sol.life_mrev.unwrap();
    assert!(l < l0.min(l1), "{l} {l0} {l1}");
    // Statics: the set's force balances the load.
    for i in 0..5 {
        let scale = if i < 3 { 1000.0 } else { 1000.0 * s.arm() };
        assert!((sol.force[i] + [1000.0, 0.0, 500.0, 0.0, 0.0][i]).abs() < 1e-6 * scale);
    }
}

/// Ring temperatures (physics §S1): a warmer inner ring closes the rows' clearance, so a
/// rigid preload rises (more for a larger difference, the rows still equal and opposite),
/// while a spring preload's rows slide and its force changes only by the spring's stiffness
/// times the slide (exactly: `F = F_s + k_s u`), far less than the rigid one's.
#[test]
fn warmer_inner_ring_raises_a_rigid_preload_not_a_spring_one() {
    let at = |preload: Preload, dt: f64| {
        let mut s = pair(Arrangement::Db, preload);
        s.set_ring_temperatures(RingTemperatures::inner_warmer(dt))
            .unwrap();
        s.solve(&[0.0; 5], 0.0).unwrap()
    };
    let cold = at(Preload::Force(300.0), 0.0);
    let warm = at(Preload::Force(300.0), 5.0);
    let hot = at(Preload::Force(300.0), 10.0);
    assert!(rel(cold.rows[0].axial_load, 300.0) < 1e-9);
    assert!(
        warm.rows[0].axial_load > 300.0 * 1.05 && hot.rows[0].axial_load > warm.rows[0].axial_load,
        "{} {}",
        warm.rows[0].axial_load,
        hot.rows[0].axial_load
    );
    assert!(rel(hot.rows[1].axial_load, hot.rows[0].axial_load) < 1e-8);
    // The axial stiffness rises with the preload.
    assert!(hot.stiffness[2][2] > cold.stiffness[2][2]);
    let (ks, fs) = (0.5e6, 300.0);
    let spring = Preload::Spring {
        stiffness: ks,
        force: fs,
    };
    let s0 = at(spring, 0.0);
    let s1 = at(spring, 10.0);
    let d_spring = s1.rows[0].axial_load - s0.rows[0].axial_load;
    let d_rigid = hot.rows[0].axial_load - cold.rows[0].axial_load;
    let want = ks * (s1.spring_shift - s0.spring_shift);
    assert!(
        (d_spring - want).abs() < 1e-6 * fs,
        "{d_spring} against k_s du = {want}"
    );
    assert!(d_spring.abs() < 0.05 * d_rigid, "{d_spring} {d_rigid}");
}

/// The reference temperatures leave the set bit-identical to the set as assembled, given
/// explicitly or after a warm excursion; a roller row refuses a temperature and a refused
/// call changes nothing.
#[test]
fn reference_temperatures_change_nothing() {
    let base = pair(Arrangement::Db, Preload::Force(300.0))
        .solve(&[50.0, -200.0, 100.0, 0.0, 0.0], rpm_to_rad_s(12_000.0))
        .unwrap();
    let mut s = pair(Arrangement::Db, Preload::Force(300.0));
    s.set_ring_temperatures(RingTemperatures {
        inner_c: 20.0,
        outer_c: 20.0,
        ball_c: Some(20.0),
    })
    .unwrap();
    let same = s
        .solve(&[50.0, -200.0, 100.0, 0.0, 0.0], rpm_to_rad_s(12_000.0))
        .unwrap();
    assert_eq!(format!("{base:?}"), format!("{same:?}"));
    let mut s = pair(Arrangement::Db, Preload::Force(300.0));
    s.set_ring_temperatures(RingTemperatures::inner_warmer(10.0))
        .unwrap();
    s.set_ring_temperatures(RingTemperatures::default())
        .unwrap();
    let back = s
        .solve(&[50.0, -200.0, 100.0, 0.0, 0.0], rpm_to_rad_s(12_000.0))
        .unwrap();
    for i in 0..5 {
        assert!((back.q[i] - base.q[i]).abs() <= 1e-12 * base.q[i].abs().max(1e-9));
    }
    let nu = bearing_by_name("NJ206", "b").unwrap();
    let ball = b7008();
    let spec = SetSpec {
        rows: vec![
            Row {
                bearing: ball.clone(),
                position: -0.05,
                orientation: 1,
            },
            Row {
                bearing: nu,
                position: 0.05,
                orientation: 1,
            },
        ],
        preload: Preload::None,
    };
    let mut s = Set::new(&spec).unwrap();
    let e = s
        .set_ring_temperatures(RingTemperatures::inner_warmer(5.0))
        .unwrap_err()
        .to_string();
    assert!(e.contains("set.temperatures") && e.contains("row 1"), "{e}");
    assert!(s.ring_temperatures().is_reference());
    let e = s
        .set_ring_temperatures(RingTemperatures {
            inner_c: f64::NAN,
            ..Default::default()
        })
        .unwrap_err()
        .to_string();
    assert!(e.contains("set.temperatures.inner_c"), "{e}");
}
