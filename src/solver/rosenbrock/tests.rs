use super::*;

/// The controller's roots are the exact roots to rounding (`root^q` gives `x` back to
/// 8 ulp, `q = 1/exponent`) and `powf` by the method's exponent to 1e-15 relative
/// (`powf(x, 1/3)` is off by `1/3`'s own rounding), over the errors the controller
/// meets (1e-12 to 1e12).
#[test]
fn error_roots_are_the_roots() {
    for m in [RosMethod::Rodas4, RosMethod::Ros34pw2] {
        let e = m.error_exponent();
        let q = (1.0 / e).round() as i32;
        for k in -120..=120 {
            for f in [1.0, 1.37, 2.0, 7.9] {
                let x = f * 10f64.powf(k as f64 / 10.0);
                let a = m.error_root(x);
                let back = a.powi(q);
                assert!(
                    (back - x).abs() <= 8.0 * f64::EPSILON * x,
                    "{m:?} {x:e}: {a:e}"
                );
                let b = x.powf(e);
                assert!((a - b).abs() <= 1e-15 * b, "{m:?} {x:e}: {a:e} {b:e}");
            }
        }
    }
}

/// Van der Pol, stiff (`ε = 1e-3`), analytic `J`; `carry` says whether calls may carry
/// `J`; from the `fail_at`-th right-hand side on, every evaluation fails.
struct Vdp {
    carry: bool,
    evals: usize,
    fail_at: usize,
    h_call: f64,
}
impl OdeSystem for Vdp {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        self.evals += 1;
        if self.evals >= self.fail_at {
            return Err("refused".into());
        }
        dy[0] = y[1];
        dy[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / 1e-3;
        Ok(())
    }
    fn jacobian(&mut self, _t: f64, y: &[f64], j: &mut DMatrix<f64>) -> bool {
        j[(0, 0)] = 0.0;
        j[(0, 1)] = 1.0;
        j[(1, 0)] = (-2.0 * y[0] * y[1] - 1.0) / 1e-3;
        j[(1, 1)] = (1.0 - y[0] * y[0]) / 1e-3;
        true
    }
    fn carries_jacobian(&self) -> bool {
        self.carry
    }
}

fn w() -> Rosenbrock {
    Rosenbrock::with_method(RosMethod::Ros34pw2, Box::new(DenseLu::new(2)))
}

const CALLS: usize = 60;
/// Calls of a few steps each, most on the `J` of an earlier call.
const SHORT: f64 = 2e-3;
/// Calls of tens of steps: `J` is often replaced inside a call.
const LONG: f64 = 2e-2;

/// One call `i` of the run (`[i H, (i+1) H]`) from `y`, `h`.
fn call(r: &mut Rosenbrock, sys: &mut Vdp, i: usize, y: &mut [f64; 2], h: &mut f64) -> bool {
    let opts = Options::new(2, 1e-6, 1e-8);
    let t = i as f64 * sys.h_call;
    r.integrate(sys, t, t + sys.h_call, y, h, &opts).is_ok()
}

/// What runs before call `i`: `between(i, r, sys, y, h)`.
type Between<'a> = dyn FnMut(usize, &mut Rosenbrock, &mut Vdp, &mut [f64; 2], &mut f64) + 'a;

/// `(y, h)` bits after every call; `between` runs before every call.
fn run(carry: bool, h_call: f64, between: &mut Between) -> (Vec<[u64; 3]>, Stats) {
    let mut r = w();
    let mut sys = Vdp {
        carry,
        evals: 0,
        fail_at: usize::MAX,
        h_call,
    };
    let (mut y, mut h) = ([2.0, 0.0], 0.0);
    let mut out = Vec::new();
    for i in 0..CALLS {
        between(i, &mut r, &mut sys, &mut y, &mut h);
        assert!(call(&mut r, &mut sys, i, &mut y, &mut h), "call {i}");
        out.push([y[0].to_bits(), y[1].to_bits(), h.to_bits()]);
    }
    (out, r.stats)
}

/// A carried `J` is the last call's: fewer Jacobians than calls (and than the
/// calls-fresh run), the same solution to the tolerance's order, not the same bits.
#[test]
fn calls_that_continue_one_another_carry_the_jacobian() {
    let (fresh, sf) = run(false, SHORT, &mut |_, _, _, _, _| {});
    let (kept, sk) = run(true, SHORT, &mut |_, _, _, _, _| {});
    println!("fresh {sf:?}\ncarried {sk:?}");
    assert!(sf.jac_evals >= CALLS as u64, "{sf:?}");
    assert!(sk.jac_evals < sf.jac_evals / 2, "{sk:?} {sf:?}");
    assert!(sk.lu_decomps < sf.lu_decomps, "{sk:?} {sf:?}");
    assert_ne!(fresh, kept);
    let y = |b: &[u64; 3]| [f64::from_bits(b[0]), f64::from_bits(b[1])];
    let (a, b) = (y(&fresh[CALLS - 1]), y(&kept[CALLS - 1]));
    assert!(
        (a[0] - b[0]).abs() < 1e-3 && (a[1] - b[1]).abs() < 1e-2,
        "{a:?} {b:?}"
    );
}

/// A call that fails (whatever it did to `J` before failing) or whose result is not
/// kept, then repeated, gives the bits of the run without it; some of the dropped
/// calls failed, some had replaced a `J` that the repeat keeps.
#[test]
fn a_failed_or_dropped_call_leaves_the_carried_jacobian_as_it_was() {
    let (plain, _) = run(true, LONG, &mut |_, _, _, _, _| {});
    let (mut replaced, mut failed) = (0, 0);
    for at in 1..CALLS / 3 {
        for fail_after in [1, 3, 6, 9, 14, 25, usize::MAX] {
            let (mut jac_in_dropped, mut young) = (0, false);
            let (with, _) = run(true, LONG, &mut |i, r, sys, y, h| {
                if i != at {
                    return;
                }
                let (y0, h0) = (*y, *h);
                let j0 = r.stats.jac_evals;
                // A J of the call's start would be computed again by the repeat.
                young = r.carry.end_ok && r.carry.end_age < W_JAC_MAX_AGE;
                sys.fail_at = sys.evals.saturating_add(fail_after);
                if !call(r, sys, i, y, h) {
                    failed += 1;
                }
                sys.fail_at = usize::MAX;
                jac_in_dropped = r.stats.jac_evals - j0;
                (*y, *h) = (y0, h0);
            });
            replaced += usize::from(jac_in_dropped > 0 && young);
            assert!(with == plain, "call {at}, failing after {fail_after}");
        }
    }
    println!("{failed} calls failed, {replaced} dropped calls replaced a kept J");
    assert!(replaced > 0 && failed > 0);
}

/// A call that may not carry (a state taken or restored) starts with a fresh `J`;
/// from there a fresh integrator gives the same bits as the used one.
#[test]
fn a_call_that_may_not_carry_starts_fresh_like_a_new_integrator() {
    let at = 23;
    let mut start = None;
    let (used, _) = run(true, SHORT, &mut |i, r, sys, y, h| {
        sys.carry = i != at;
        if i == at {
            start = Some((*y, *h, r.stats.jac_evals));
        }
    });
    let (y0, h0, _) = start.unwrap();
    let mut r = w();
    let mut sys = Vdp {
        carry: false,
        evals: 0,
        fail_at: usize::MAX,
        h_call: SHORT,
    };
    let (mut y, mut h) = (y0, h0);
    for (i, bits) in used.iter().enumerate().skip(at) {
        sys.carry = i != at;
        assert!(call(&mut r, &mut sys, i, &mut y, &mut h));
        assert_eq!(&[y[0].to_bits(), y[1].to_bits(), h.to_bits()], bits, "{i}");
    }
}
