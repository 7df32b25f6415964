use super::*;
use crate::geometry::preset;
use crate::seam::{Jacobians, Motion};

/// At the kinematic speeds of docs/physics.md §1 both slips vanish, for a deep-groove and
/// an angular-contact bearing.
#[test]
fn zero_slip_at_kinematic_speeds() {
    for name in ["6012", "7008ce"] {
        let b = preset(name).unwrap().build().unwrap();
        let mut m = SkiddingModel::new(&b, SkiddingParams::default()).unwrap();
        let mut x = vec![0.0; m.n_states()];
        let omega = 300.0;
        m.init(omega, &mut x);
        let mut dx = vec![0.0; x.len()];
        m.eval(&[0.0; 5], &[0.0; 5], omega, &x, &mut dx);
        for bs in &m.balls {
            assert!(bs.dv_i.abs() < 1e-12 && bs.dv_o.abs() < 1e-12, "{bs:?}");
        }
        let k = crate::geometry::kinematics::kinematics(&b, omega);
        assert!((m.balls[0].w_b - k.cage_speed).abs() < 1e-12);
        assert!((m.balls[0].w_s - k.ball_spin_speed).abs() < 1e-9);
    }
}

/// The analytic stiffness `-dW/dq` and damping `-dW/dv` of the outputs equal the
/// finite-difference Jacobian of the wrench (balls held), with every term on: contact
/// damping at a moving ring, gyroscopic and spin friction (and none), each traction
/// law, a ball off the inner race.
#[test]
fn analytic_stiffness_matches_finite_differences() {
    use crate::contact::traction::MixedEhl;
    let b = preset("7008ce").unwrap().build().unwrap();
    // The last case without spin friction: the contact line's direction then drops
    // out of the rates (its column of d(rates)/dq is not differenced).
    for (law, omega, spin_friction) in [
        (TractionLaw::default(), 2500.0, 0.05),
        (TractionLaw::MixedEhl(MixedEhl::default()), 1500.0, 0.05),
        (TractionLaw::default(), 2500.0, 0.0),
    ] {
        let p = SkiddingParams {
            traction: law,
            contact_damping: 50.0,
            spin_friction,
            spacing_scatter: 0.5,
            ..SkiddingParams::default()
        };
        let mut m = SkiddingModel::new(&b, p).unwrap();
        let n = m.n_states();
        let mut x = vec![0.0; n];
        m.init(omega, &mut x);
        // Perturb the ball speeds so that every contact slips and spins.
        for j in 0..m.z() {
            x[BALL0 + 3 * j + 1] *= 1.0 + 0.01 * (j as f64 - 7.0) / 7.0;
            x[BALL0 + 3 * j + 2] *= 1.0 - 0.02 * (j as f64 - 3.0) / 7.0;
        }
        // Axial preload, radial offset (unloads some balls), tilt, a moving ring.
        let q = [4e-6, -12e-6, 10e-6, 2e-4, -1e-4];
        let v = [1e-3, -2e-3, 5e-4, 0.02, 0.01];
        let mut dx = vec![0.0; n];
        let (mut k, mut c) = ([[0.0; 5]; 5], [[0.0; 5]; 5]);
        m.eval_with_stiffness(&Motion { q, v, omega }, &x, &mut dx, &mut k, &mut c);
        assert!(m.balls.iter().any(|s| s.q_i == 0.0), "a ball off the race");
        assert!(m
            .balls
            .iter()
            .any(|s| s.gyro != 0.0 && (s.spin_i != 0.0) == (spin_friction > 0.0)));
        let mut dx2 = vec![0.0; n];
        m.eval(&q, &v, omega, &x, &mut dx2);
        assert_eq!(dx, dx2, "the same rates");
        let (mut jx, mut jm, mut wx, mut wm) = (
            vec![0.0; n * n],
            vec![0.0; n * 10],
            vec![0.0; 5 * n],
            vec![0.0; 50],
        );
        // Central differences of the wrench in q for the reference.
        let mut kfd = [[0.0; 5]; 5];
        for col in 0..5 {
            let h = if col < 3 { 1e-10 } else { 1e-8 };
            let (mut qp, mut qm) = (q, q);
            qp[col] += h;
            qm[col] -= h;
            let wp = m.eval(&qp, &v, omega, &x, &mut dx2).wrench;
            let wn = m.eval(&qm, &v, omega, &x, &mut dx2).wrench;
            for r in 0..5 {
                kfd[r][col] = -(wp[r] - wn[r]) / (2.0 * h);
            }
        }
        let jac = Jacobians {
            jx: &mut jx,
            jm: &mut jm,
            wx: &mut wx,
            wm: &mut wm,
        };
        m.jacobian(&Motion { q, v, omega }, &x, jac, &[0, 1, 2, 3, 4]);
        // The integrator's d(rates)/dq (differenced along the analytic load
        // derivatives) against central differences of whole right-hand sides.
        let (mut dp, mut dm) = (vec![0.0; n], vec![0.0; n]);
        for col in 0..5 {
            let h = if col < 3 { 1e-10 } else { 1e-8 };
            let (mut qp, mut qm) = (q, q);
            qp[col] += h;
            qm[col] -= h;
            m.eval(&qp, &v, omega, &x, &mut dp);
            m.eval(&qm, &v, omega, &x, &mut dm);
            for r in 0..n {
                let fd = (dp[r] - dm[r]) / (2.0 * h);
                let an = jm[r * 10 + col];
                let scale = (0..5).map(|c| jm[r * 10 + c].abs()).fold(1e-3, f64::max);
                assert!(
                    (an - fd).abs() <= 1e-2 * scale,
                    "{law:?} jm[{r}][{col}] {an:e} vs {fd:e}"
                );
            }
            for r in 0..5 {
                let (w, kk) = (wm[r * 10 + col], -k[r][col]);
                assert!(
                    (w - kk).abs() <= 1e-12 * kk.abs(),
                    "wm is the analytic stiffness"
                );
            }
        }
        // d(rates)/d(states), every column, against central differences.
        for col in 0..n {
            let h = 1e-7 * x[col].abs().max(1e-2);
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[col] += h;
            xm[col] -= h;
            m.eval(&q, &v, omega, &xp, &mut dp);
            m.eval(&q, &v, omega, &xm, &mut dm);
            for r in 0..n {
                let fd = (dp[r] - dm[r]) / (2.0 * h);
                let an = jx[r * n + col];
                let scale = (0..n).map(|c| jx[r * n + c].abs()).fold(1e-3, f64::max);
                assert!(
                    (an - fd).abs() <= 1e-2 * scale,
                    "{law:?} jx[{r}][{col}] {an:e} vs {fd:e}"
                );
            }
        }
        for r in 0..5 {
            let scale = kfd[r].iter().map(|v| v.abs()).fold(0.0, f64::max);
            for col in 0..5 {
                let (a, f) = (k[r][col], kfd[r][col]);
                assert!(
                    (a - f).abs() <= 1e-5 * scale,
                    "{law:?} K[{r}][{col}] analytic {a:e} vs fd {f:e}"
                );
                assert!((c[r][col] + wm[r * 10 + 5 + col]).abs() <= 1e-9 * c[r][r].abs().max(1.0));
            }
        }
    }
}

thread_local! {
    /// Test switch: difference every column (no analytic Coulomb columns).
    pub(super) static FD_ONLY: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Under the Coulomb law without spin friction the `w_a` columns and the load slopes
/// `d(rates)/dQ` are analytic. Relative to each row's largest entry (rates, cage and
/// wrench rows; every ball, one off the inner race, pockets in contact): the `w_a`
/// columns equal central differences to 1e-7 and the forward differences they replace
/// to 1e-4 (those carry a truncation error); `d(rates)/dq` equals its forward-difference
/// form to 1e-5 (1e-3 in the rows of a ball pressed into its pocket: the
/// difference's rounding noise); every other entry is unchanged bit for bit.
#[test]
fn analytic_coulomb_columns_match_the_differences() {
    let b = preset("7008ce").unwrap().build().unwrap();
    let p = SkiddingParams {
        contact_damping: 50.0,
        spacing_scatter: 0.5,
        ..SkiddingParams::default()
    };
    assert!(p.spin_friction == 0.0 && matches!(p.traction, TractionLaw::Coulomb { .. }));
    let mut m = SkiddingModel::new(&b, p).unwrap();
    let n = m.n_states();
    let omega = 2500.0;
    let mut x = vec![0.0; n];
    m.init(omega, &mut x);
    for j in 0..m.z() {
        x[BALL0 + 3 * j] += 6e-3 * (j as f64 - 7.5) / 7.5; // some pockets in contact
        x[BALL0 + 3 * j + 1] *= 1.0 + 0.01 * (j as f64 - 7.0) / 7.0;
        x[BALL0 + 3 * j + 2] *= 1.0 - 0.02 * (j as f64 - 3.0) / 7.0;
    }
    let q = [4e-6, -12e-6, 10e-6, 2e-4, -1e-4];
    let v = [1e-3, -2e-3, 5e-4, 0.02, 0.01];
    let mut dx = vec![0.0; n];
    m.eval(&q, &v, omega, &x, &mut dx);
    assert!(m.balls.iter().any(|s| s.q_i == 0.0), "a ball off the race");
    let pockets: Vec<bool> = m.balls.iter().map(|s| s.pocket != 0.0).collect();
    assert!(pockets.contains(&true) && pockets.contains(&false));
    assert!(m.balls.iter().any(|s| s.gyro != 0.0));
    let run = |fd: bool| {
        FD_ONLY.with(|c| c.set(fd));
        let mut out = (vec![0.0; n * n], vec![0.0; n * 10], vec![0.0; 5 * n]);
        let mut wm = vec![0.0; 50];
        let jac = Jacobians {
            jx: &mut out.0,
            jm: &mut out.1,
            wx: &mut out.2,
            wm: &mut wm,
        };
        m.jacobian(&Motion { q, v, omega }, &x, jac, &[0, 1, 2, 3, 4]);
        FD_ONLY.with(|c| c.set(false));
        out
    };
    let (ax, am, aw) = run(false);
    let (fx, fm, fw) = run(true);
    // Central differences of whole right-hand sides in each ball's w_a (the reference:
    // the forward differences replaced carry a truncation error of ~1e-5).
    let z = m.z();
    let (mut cx, mut cw) = (vec![0.0; n * n], vec![0.0; 5 * n]);
    let (mut dp, mut dm) = (vec![0.0; n], vec![0.0; n]);
    for j in 0..z {
        let c = BALL0 + 3 * j + 2;
        let h = 1e-7 * x[c].abs().max(1.0);
        let (mut xp, mut xm) = (x.clone(), x.clone());
        xp[c] += h;
        xm[c] -= h;
        let wp = m.eval(&q, &v, omega, &xp, &mut dp).wrench;
        let wn = m.eval(&q, &v, omega, &xm, &mut dm).wrench;
        for r in 0..n {
            cx[r * n + c] = (dp[r] - dm[r]) / (2.0 * h);
        }
        for r in 0..5 {
            cw[r * n + c] = (wp[r] - wn[r]) / (2.0 * h);
        }
    }
    let (mut to_central, mut to_forward, mut slopes): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for (a, f, cd, cols) in [
        (&ax, &fx, Some(&cx), n),
        (&aw, &fw, Some(&cw), n),
        (&am, &fm, None, 10),
    ] {
        for r in 0..a.len() / cols {
            let row = r * cols..(r + 1) * cols;
            let scale = f[row.clone()].iter().fold(1e-300f64, |s, v| s.max(v.abs()));
            for i in row {
                let c = i % cols;
                let rel = |u: f64, w: f64| (u - w).abs() / scale;
                match cd {
                    // A w_a column: against central differences, and what moved.
                    Some(cd) if c < BALL0 + 3 * z && c % 3 == 2 => {
                        to_central = to_central.max(rel(a[i], cd[i]));
                        to_forward = to_forward.max(rel(a[i], f[i]));
                    }
                    // d(rates)/dq through the load slopes (the forward differences of a
                    // function linear in the load differ by rounding only).
                    // (Loose where a pocket force dominates the rate: the forward
                    // difference's rounding noise.)
                    None if r < BALL0 + 3 * z && pockets[r / 3] => {
                        assert!(rel(a[i], f[i]) <= 1e-3, "row {r} col {c}");
                    }
                    None => slopes = slopes.max(rel(a[i], f[i])),
                    _ => assert_eq!(a[i].to_bits(), f[i].to_bits(), "row {r} col {c}"),
                }
            }
        }
    }
    assert!(
        to_central <= 1e-7,
        "w_a columns vs central differences: {to_central:e}"
    );
    assert!(
        to_forward <= 1e-4,
        "w_a columns vs forward differences: {to_forward:e}"
    );
    assert!(
        slopes <= 1e-5,
        "load slopes vs forward differences: {slopes:e}"
    );
    assert!(to_forward > 0.0 && slopes > 0.0, "computed differently");
    eprintln!("w_a columns: {to_central:.1e} from central, {to_forward:.1e} from forward differences; d(rates)/dq: {slopes:.1e} (of each row's largest entry)");
}

/// Force split with centrifugal force: `Q_o - Q_i = Fc` and the approaches add up.
#[test]
fn split_balances_the_centrifugal_force() {
    let b = preset("6012").unwrap().build().unwrap();
    let m = SkiddingModel::new(&b, SkiddingParams::default()).unwrap();
    for (delta, f) in [(5e-6, 3.0), (5e-6, 0.0), (-2e-6, 3.0), (1e-7, 50.0)] {
        let Split {
            q_i: qi, q_o: qo, ..
        } = m.split(delta, f);
        assert!(
            (qo - qi - f).abs() < 1e-8 * (1.0 + qo),
            "{delta} {f}: {qi} {qo}"
        );
        if qi > 0.0 {
            let sum = m.inner.deflection(qi) + m.outer.deflection(qo);
            assert!((sum - delta).abs() < 1e-12, "{sum} vs {delta}");
        }
    }
    assert_eq!(m.split(-1e-6, 0.0), Split::default());
    // The semi-axes from sqrt(delta) and the peak pressure agree with the Hertz API.
    let sp = m.split(5e-6, 3.0);
    let ci = m.contact_state(true, sp.q_i, sp.r_i);
    let (a, bb) = m.inner.semi_axes(sp.q_i);
    assert!((ci.a / a - 1.0).abs() < 1e-12 && (ci.b / bb - 1.0).abs() < 1e-12);
    let p = m.peak_pressure(sp.q_i, 0.0);
    assert!((p / m.inner.peak_pressure(sp.q_i) - 1.0).abs() < 1e-12);
    let p = m.peak_pressure(0.0, sp.q_o);
    assert!((p / m.outer.peak_pressure(sp.q_o) - 1.0).abs() < 1e-12);
}
