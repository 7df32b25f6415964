use super::*;
use crate::seam::{Jacobians, Motion};

/// The 7004 at 30 000 rpm at the scene's displacement (examples/scenes/7004-30000.toml),
/// started, with the cage off centre and slower so the pockets act.
fn started_7004() -> (FullModel, [f64; 5], f64, Vec<f64>, Vec<f64>) {
    started_7004_with(BallContacts::QuasiStatic)
}

/// [`started_7004`] with the ball contacts `contacts`.
fn started_7004_with(contacts: BallContacts) -> (FullModel, [f64; 5], f64, Vec<f64>, Vec<f64>) {
    let b = crate::geometry::preset("7004").unwrap().build().unwrap();
    let p = FullParams {
        ball_contacts: contacts,
        ..FullParams::for_bearing(&b)
    };
    let mut m = FullModel::new(&b, p).unwrap();
    let q = [0.0, -2.96568e-6, 4.364864e-5, 0.0, 0.0];
    let omega = 3141.592654;
    let mut x = vec![0.0; m.n_states()];
    let mut aux = vec![0.0; m.n_aux()];
    m.init(&q, omega, &mut x, &mut aux).unwrap();
    x[0] = 0.05;
    x[11] *= 0.99;
    (m, q, omega, x, aux)
}

/// The motion-driven Jacobian `jx` (row-major) at `q`, `omega`, no velocity.
fn motion_jacobian(
    m: &mut FullModel,
    q: &[f64; 5],
    omega: f64,
    x: &[f64],
    aux: &[f64],
) -> Vec<f64> {
    let n = x.len();
    let mut jx = vec![0.0; n * n];
    let mut scratch = vec![0.0; 3 * n + aux.len()];
    let (jm, wx, wm) = (&mut [], &mut [], &mut []);
    let motion = Motion {
        q: *q,
        v: [0.0; 5],
        omega,
    };
    let jac = Jacobians {
        jx: &mut jx,
        jm,
        wx,
        wm,
    };
    m.jacobian(&motion, x, aux, jac, &mut scratch).unwrap();
    jx
}

/// The wrench alone ([`FullModel::wrench_at`], what the outputs' K and C difference) is
/// the evaluation's, bit for bit: positions solved from the warm starts, or kept from
/// the evaluation at the same displacement for a velocity change.
#[test]
fn wrench_alone_is_the_evaluations_wrench() {
    let (mut m, q, omega, x, aux) = started_7004();
    let mut dx = vec![0.0; x.len()];
    for (dq, dv) in [(0.0, 0.0), (1e-9, 0.0), (0.0, 1e-6)] {
        let qp = [q[0], q[1] + dq, q[2], q[3], q[4]];
        let v = [dv, 0.0, 0.0, 0.0, 0.0];
        let mut a = aux.clone();
        let tot = m.eval(&qp, &v, omega, &x, &mut a, &mut dx).unwrap();
        let mut b = aux.clone();
        assert_eq!(
            m.wrench_at(&qp, &v, omega, &x, &mut b, true).unwrap(),
            tot.wrench
        );
        assert_eq!(a, b);
        // `a` now holds the solved positions.
        let vb = [0.0, dv + 1e-5, 0.0, 0.0, 0.0];
        let mut c = aux.clone();
        let w = m.eval(&qp, &vb, omega, &x, &mut c, &mut dx).unwrap().wrench;
        assert_eq!(m.wrench_at(&qp, &vb, omega, &x, &mut a, false).unwrap(), w);
    }
}

/// An evaluation repeated at the same motion and states, from the warm starts the
/// last one found or left ([`Memo`]), gives what a model without that memo computes:
/// rates, totals, warm starts, per-ball results and the race parts the Jacobian keeps,
/// bit for bit; a changed state, motion or warm start is evaluated anew.
#[test]
fn a_repeated_evaluation_is_a_fresh_one() {
    let (m0, q, omega, x, aux) = started_7004();
    let n = x.len();
    let v = [0.0; 5];
    let motion = Motion { q, v, omega };
    let bits = |a: &[f64]| a.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    // A first evaluation (the memo's), then repeats from the warm starts it found and
    // from those it left, against a fresh model's.
    let mut m = m0.clone();
    let mut a1 = aux.clone();
    let mut d1 = vec![0.0; n];
    m.eval(&q, &v, omega, &x, &mut a1, &mut d1).unwrap();
    for start in [aux.clone(), a1.clone()] {
        for keep in [false, true] {
            let mut fresh = m0.clone();
            let (mut af, mut df) = (start.clone(), vec![0.0; n]);
            let tf = fresh
                .eval_memo(&motion, &x, &mut af, &mut df, keep)
                .unwrap();
            let (mut am, mut dm) = (start.clone(), vec![0.0; n]);
            let tm = m.eval_memo(&motion, &x, &mut am, &mut dm, keep).unwrap();
            assert_eq!(format!("{tf:?}"), format!("{tm:?}"));
            assert_eq!(bits(&df), bits(&dm));
            assert_eq!(bits(&af), bits(&am));
            assert_eq!(fresh.balls, m.balls);
            if keep {
                assert_eq!(format!("{:?}", fresh.races), format!("{:?}", m.races));
                assert_eq!(format!("{:?}", fresh.terms), format!("{:?}", m.terms));
            }
        }
    }
    assert!(m.memo.p.is_some());
    // Anything else moved: a new evaluation, not the memo's numbers.
    let mut xp = x.clone();
    xp[11] *= 1.001;
    let mut q2 = q;
    q2[1] += 1e-7;
    let mut a2 = a1.clone();
    a2[0] += 1e-9;
    for (qq, xx, aa, moved) in [
        (q, &xp, &a1, true),
        (q2, &x, &a1, true),
        (q, &x, &a2, false),
    ] {
        let (mut af, mut df) = (aa.clone(), vec![0.0; n]);
        let tf = m0
            .clone()
            .eval(&qq, &v, omega, xx, &mut af, &mut df)
            .unwrap();
        let mut mm = m.clone();
        let (mut am, mut dm) = (aa.clone(), vec![0.0; n]);
        let tm = mm.eval(&qq, &v, omega, xx, &mut am, &mut dm).unwrap();
        assert_eq!(format!("{tf:?}"), format!("{tm:?}"));
        assert_eq!(bits(&df), bits(&dm));
        if moved {
            assert_ne!(bits(&dm), bits(&d1));
        }
    }
    // Changed options: a new evaluation too.
    let (mut fresh, mut mm) = (m0.clone(), m.clone());
    fresh.p.drag *= 2.0;
    mm.p.drag *= 2.0;
    let (mut af, mut df) = (a1.clone(), vec![0.0; n]);
    fresh.eval(&q, &v, omega, &x, &mut af, &mut df).unwrap();
    let (mut am, mut dm) = (a1.clone(), vec![0.0; n]);
    mm.eval(&q, &v, omega, &x, &mut am, &mut dm).unwrap();
    assert_eq!(bits(&df), bits(&dm));
    assert_ne!(bits(&dm), bits(&d1));
}

/// The Jacobian's cage columns, which re-evaluate only the pockets on the balls' kept
/// race parts, equal whole evaluations' forward differences bit for bit.
#[test]
fn cage_columns_equal_whole_differences_exactly() {
    let (mut m, q, omega, x, aux) = started_7004();
    let n = x.len();
    let v = [0.0; 5];
    let jx = motion_jacobian(&mut m, &q, omega, &x, &aux);
    let (mut d0, mut d1) = (vec![0.0; n], vec![0.0; n]);
    m.eval(&q, &v, omega, &x, &mut aux.clone(), &mut d0)
        .unwrap();
    for c in 0..12 {
        let mut xp = x.clone();
        let h = 1.5e-8 * x[c].abs().max(1.0);
        xp[c] += h;
        m.eval(&q, &v, omega, &xp, &mut aux.clone(), &mut d1)
            .unwrap();
        for r in 0..n {
            assert_eq!(jx[r * n + c], (d1[r] - d0[r]) / h, "row {r} col {c}");
        }
    }
}

/// The Jacobian's ball columns (spin columns on the kept frame, contacts and contact
/// states) equal whole evaluations' forward differences bit for bit in the ball's own
/// rows, the positions solved from the warm starts the evaluation at `x` left.
#[test]
fn ball_columns_equal_whole_differences_in_their_rows() {
    let (mut m, q, omega, x, aux) = started_7004();
    let n = x.len();
    let v = [0.0; 5];
    let (mut a1, mut d0, mut d1) = (aux.clone(), vec![0.0; n], vec![0.0; n]);
    m.eval(&q, &v, omega, &x, &mut a1, &mut d0).unwrap();
    let jx = motion_jacobian(&mut m, &q, omega, &x, &a1);
    let (nc, nb) = (m.ball0(), m.per_ball());
    let mut nonzero = 0;
    for j in 0..m.z() {
        for c in 0..nb {
            let col = nc + nb * j + c;
            let mut xp = x.clone();
            let h = 1.5e-8 * x[col].abs().max(1.0);
            xp[col] += h;
            m.eval(&q, &v, omega, &xp, &mut a1.clone(), &mut d1)
                .unwrap();
            for r in nc + nb * j..nc + nb * (j + 1) {
                assert_eq!(jx[r * n + col], (d1[r] - d0[r]) / h, "row {r} col {col}");
                nonzero += usize::from(jx[r * n + col] != 0.0);
            }
        }
    }
    assert!(nonzero > m.z() * m.per_ball(), "{nonzero}");
}

/// The velocities the contacts use are the time derivatives of the material points'
/// positions: cage pocket walls of a tilted, eccentric, spinning cage, and the inner
/// groove of a tilted spinning ring (central differences along the motion).
#[test]
fn material_velocities_are_position_rates() {
    let ck = CageKin {
        c: [1e-5, -2e-5, 3e-6],
        b: [1e-3, -2e-3],
        theta: 0.3,
        v: [0.02, -0.01, 0.005],
        bd: [0.5, -0.3],
        w: 1200.0,
    };
    let dt = 1e-7;
    let at = |t: f64| CageKin {
        c: add(ck.c, scale(ck.v, t)),
        b: [ck.b[0] + ck.bd[0] * t, ck.b[1] + ck.bd[1] * t],
        theta: ck.theta + ck.w * t,
        ..ck
    };
    for (phi, r) in [(0.0, 0.0155), (1.1, 0.0155), (2.5, 0.019)] {
        let p = |t: f64| {
            let k = at(t);
            k.point(k.theta + phi, r)
        };
        let fd = scale(sub(p(dt), p(-dt)), 0.5 / dt);
        let v = ck.velocity_at(p(0.0));
        // 1e-5: the positions are linear in the tilts, so terms of order |b|² (2e-6
        // relative here) differ; a missing first-order term (the tilt lift's rate from
        // the spin) would be ~ w r |b| = 0.04 m/s against a 0.02 m/s axial speed.
        for i in 0..3 {
            assert!(
                (fd[i] - v[i]).abs() < 1e-5 * norm(v),
                "{i}: {fd:?} vs {v:?}"
            );
        }
    }
    // Inner ring: groove point at body angle phi, radius ri, lifted by the tilts.
    let q = [1e-5, 2e-5, -1e-5, 1e-3, -5e-4];
    let v = [0.01, 0.0, 0.002, 0.4, 0.7];
    let omega = 3000.0;
    let ri = 0.0115;
    let pt = |t: f64, phi: f64| {
        let qq: [f64; 5] = std::array::from_fn(|k| q[k] + v[k] * t);
        let (s, c) = (phi + omega * t).sin_cos();
        [
            qq[0] + ri * c,
            qq[1] + ri * s,
            qq[2] + ri * (qq[3] * s - qq[4] * c),
        ]
    };
    let wr = ring_omega(&q, &v, omega);
    for phi in [0.0, 0.7, 2.0, 4.0] {
        let fd = scale(sub(pt(dt, phi), pt(-dt, phi)), 0.5 / dt);
        let p0 = pt(0.0, phi);
        let vel = add([v[0], v[1], v[2]], cross(wr, sub(p0, [q[0], q[1], q[2]])));
        for i in 0..3 {
            assert!(
                (fd[i] - vel[i]).abs() < 1e-5 * norm(vel),
                "{i}: {fd:?} vs {vel:?}"
            );
        }
    }
}

/// With dynamic ball contacts the Jacobian's ring columns (the inner contacts evaluated
/// again, or only their tractions for a velocity, on the kept outer contacts and pockets)
/// and its ball velocity and spin columns (on the kept contacts) equal whole evaluations'
/// forward differences bit for bit: in every row for the ring columns and the wrench, in
/// the ball's own rows for the ball columns (their cage and wrench rows difference the
/// ball's share alone, block_jacobian_matches_whole_differences in tests/full.rs).
#[test]
fn dynamic_columns_on_kept_parts_equal_whole_differences_exactly() {
    let (mut m, q, omega, mut x, aux) = started_7004_with(BallContacts::Dynamic);
    let n = x.len();
    let (nc, nb) = (m.ball0(), m.per_ball());
    // Off the rest position: radial and axial ball velocities.
    for j in 0..m.z() {
        x[nc + nb * j + 3] = 1e-3 * (j as f64 - 5.0);
        x[nc + nb * j + 4] = -2e-3;
    }
    let v = [1e-3, -2e-3, 1e-4, 1e-2, -1e-2];
    let (mut jx, mut jm, mut wx, mut wm) = (
        vec![0.0; n * n],
        vec![0.0; n * 10],
        vec![0.0; 5 * n],
        vec![0.0; 50],
    );
    let mut scratch = vec![0.0; 3 * n];
    let jac = Jacobians {
        jx: &mut jx,
        jm: &mut jm,
        wx: &mut wx,
        wm: &mut wm,
    };
    let motion = Motion { q, v, omega };
    m.jacobian(&motion, &x, &aux, jac, &mut scratch).unwrap();
    let (mut d0, mut d1) = (vec![0.0; n], vec![0.0; n]);
    let t0 = m.eval(&q, &v, omega, &x, &mut [], &mut d0).unwrap();
    let hs = [
        1e-10, 1e-10, 1e-10, 1e-8, 1e-8, 1e-6, 1e-6, 1e-6, 1e-4, 1e-4,
    ];
    let mut nonzero = 0;
    for (c, h) in hs.iter().enumerate() {
        let (mut qp, mut vp) = (q, v);
        if c < 5 {
            qp[c] += h;
        } else {
            vp[c - 5] += h;
        }
        let t = m.eval(&qp, &vp, omega, &x, &mut [], &mut d1).unwrap();
        for r in 0..n {
            assert_eq!(jm[r * 10 + c], (d1[r] - d0[r]) / h, "jm row {r} col {c}");
            nonzero += usize::from(jm[r * 10 + c] != 0.0);
        }
        for r in 0..5 {
            let fd = (t.wrench[r] - t0.wrench[r]) / h;
            assert_eq!(wm[r * 10 + c], fd, "wm row {r} col {c}");
        }
    }
    assert!(nonzero > 10 * m.z(), "{nonzero}");
    for j in 0..m.z() {
        for c in 0..nb {
            let col = nc + nb * j + c;
            let mut xp = x.clone();
            let h = 1.5e-8 * x[col].abs().max(1.0);
            xp[col] += h;
            m.eval(&q, &v, omega, &xp, &mut [], &mut d1).unwrap();
            for r in nc + nb * j..nc + nb * (j + 1) {
                assert_eq!(jx[r * n + col], (d1[r] - d0[r]) / h, "row {r} col {col}");
            }
        }
    }
}
