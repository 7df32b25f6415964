//! The W-method ROS34PW2 (`RosMethod::Ros34pw2`): its published tableau's order
//! conditions, its order 3 with the exact Jacobian, with a wrong one and with no `∂f/∂t`
//! (the W property, which RODAS4 does not have), L-stability on a stiff problem, the
//! published stiff reference values, and the call contract (a call is a function of its
//! inputs although `J` is kept across the steps of a call).
//!
//! Run with `cargo test --release --test wmethod -- --nocapture` to see the numbers.

use nalgebra::DMatrix;
use raceway::solver::{
    DenseLu, Integrator, OdeSystem, Options, RosMethod, Rosenbrock, WCoeffs, ROS34PW2_ALPHA,
    ROS34PW2_B, ROS34PW2_BHAT, ROS34PW2_GAMMA_MATRIX,
};

fn ros34pw2(n: usize) -> Integrator {
    Integrator::Rosenbrock(Rosenbrock::with_method(
        RosMethod::Ros34pw2,
        Box::new(DenseLu::new(n)),
    ))
}

fn rodas4(n: usize) -> Integrator {
    Integrator::Rosenbrock(Rosenbrock::new(n))
}

fn sci(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.3e}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// Observed orders log2(e_h / e_{h/2}).
fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

// ---------------------------------------------------------------------------------------
// The tableau
// ---------------------------------------------------------------------------------------

type M4 = [[f64; 4]; 4];

fn mv(m: &M4, v: &[f64; 4]) -> [f64; 4] {
    std::array::from_fn(|i| (0..4).map(|j| m[i][j] * v[j]).sum())
}

fn dot(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The order conditions of a W-method (Hairer & Wanner II, §IV.7, "W-methods": the
/// exact solution has no term in the Jacobian approximation `A`, so every tree with an
/// `A` node must vanish): order 1: Σb = 1; order 2: b·c = 1/2, b·Γ1 = 0; order 3:
/// b·c² = 1/3, b·αc = 1/6, b·Γc = 0, b·αΓ1 = 0, b·ΓΓ1 = 0 (8 conditions). The embedded
/// weights satisfy the first three and not all of the order-3 ones.
#[test]
fn ros34pw2_tableau_satisfies_the_w_order_conditions() {
    let (al, g) = (&ROS34PW2_ALPHA, &ROS34PW2_GAMMA_MATRIX);
    let one = [1.0; 4];
    let c = mv(al, &one);
    let g1 = mv(g, &one);
    let c2 = c.map(|x| x * x);
    let conditions = |b: &[f64; 4]| {
        [
            dot(b, &one) - 1.0,
            dot(b, &c) - 0.5,
            dot(b, &g1),
            dot(b, &c2) - 1.0 / 3.0,
            dot(b, &mv(al, &c)) - 1.0 / 6.0,
            dot(b, &mv(g, &c)),
            dot(b, &mv(al, &g1)),
            dot(b, &mv(g, &g1)),
        ]
    };
    let main = conditions(&ROS34PW2_B);
    println!("ROS34PW2 W-order-3 residuals: {main:?}");
    for (k, r) in main.iter().enumerate() {
        assert!(r.abs() < 1e-15, "condition {k}: {r:e}");
    }
    let emb = conditions(&ROS34PW2_BHAT);
    println!("embedded residuals: {emb:?}");
    for (k, r) in emb[..3].iter().enumerate() {
        assert!(r.abs() < 1e-15, "embedded condition {k}: {r:e}");
    }
    // order exactly 2: some order-3 condition fails (else the error estimate would be 0)
    assert!(emb[3..].iter().any(|r| r.abs() > 1e-2), "{emb:?}");
    // stiffly accurate: b_j = α_4j + Γ_4j
    for j in 0..4 {
        assert!((ROS34PW2_B[j] - al[3][j] - g[3][j]).abs() < 1e-15);
    }
}

/// The transformed coefficients computed from the published ones agree with an
/// independent transcription of the same method in transformed form (SciML
/// OrdinaryDiffEq.jl's `ROS34PW2RodasTableau`: A, C, b, c, d, read off by hand).
#[test]
fn ros34pw2_transformed_coefficients_match_a_second_source() {
    let w = WCoeffs::ros34pw2();
    let close = |a: f64, b: f64| (a - b).abs() <= 2e-15 * (1.0 + b.abs());
    let a = [
        (1, 0, 2.0),
        (2, 0, 1.419_217_317_455_764_7),
        (2, 1, -0.259_232_211_672_969_7),
        (3, 0, 4.184_760_482_319_16),
        (3, 1, -0.285_192_017_355_495_93),
        (3, 2, 2.294_280_360_279_042),
    ];
    let c = [
        (1, 0, -4.588_560_720_558_084),
        (2, 0, -4.184_760_482_319_16),
        (2, 1, 0.285_192_017_355_495_93),
        (3, 0, -6.368_179_200_128_359),
        (3, 1, -6.795_620_944_466_837),
        (3, 2, 2.870_098_604_331_056_3),
    ];
    for (i, j, v) in a {
        assert!(close(w.a[i][j], v), "a{i}{j} {} vs {v}", w.a[i][j]);
    }
    for (i, j, v) in c {
        assert!(close(w.cc[i][j], v), "c{i}{j} {} vs {v}", w.cc[i][j]);
    }
    let m = [
        4.184_760_482_319_159_5,
        -0.285_192_017_355_495_65,
        2.294_280_360_279_041_4,
        1.0,
    ];
    let e = [
        0.277_749_947_647_968_1,
        -1.403_239_895_175_999_2,
        1.772_630_127_667_550_7,
        0.5,
    ];
    let ct = [0.0, 0.871_733_043_016_918, 0.731_579_957_788_852_4, 1.0];
    let d = [
        0.435_866_521_508_459,
        -0.435_866_521_508_459,
        -0.413_333_376_233_886_5,
        0.0,
    ];
    for k in 0..4 {
        assert!(close(w.m[k], m[k]), "m{k} {} vs {}", w.m[k], m[k]);
        assert!(close(w.e[k], e[k]), "e{k} {} vs {}", w.e[k], e[k]);
        assert!(close(w.c[k], ct[k]), "c{k}");
        assert!((w.d[k] - d[k]).abs() < 1e-15, "d{k} {} vs {}", w.d[k], d[k]);
    }
    // stiffly accurate in transformed form: the last stage's argument plus u_4 is y_new
    for j in 0..3 {
        assert!(close(w.a[3][j], w.m[j]));
    }
}

// ---------------------------------------------------------------------------------------
// Orders with exact, wrong and no Jacobians
// ---------------------------------------------------------------------------------------

/// y' = −2 t y², y(0) = 1: y = 1/(1 + t²). Nonlinear and non-autonomous. The Jacobian it
/// reports is `scale·J + shift` (exact for 1, 0); `∂f/∂t` only if `dfdt`.
struct Riccati {
    scale: f64,
    shift: f64,
    dfdt: bool,
}
impl OdeSystem for Riccati {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        dy[0] = -2.0 * t * y[0] * y[0];
        Ok(())
    }
    fn jacobian(&mut self, t: f64, y: &[f64], j: &mut DMatrix<f64>) -> bool {
        j[(0, 0)] = self.scale * (-4.0 * t * y[0]) + self.shift;
        true
    }
    fn time_derivative(&mut self, _t: f64, y: &[f64], d: &mut [f64]) -> bool {
        d[0] = -2.0 * y[0] * y[0];
        self.dfdt
    }
}

/// y1' = −2t y2, y2' = 2t y1, y(0) = (1, 0): y = (cos t², sin t²). Linear, non-autonomous,
/// two coupled states; the reported Jacobian is `scale·J + shift·I`.
struct Spiral {
    scale: f64,
    shift: f64,
}
impl OdeSystem for Spiral {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        dy[0] = -2.0 * t * y[1];
        dy[1] = 2.0 * t * y[0];
        Ok(())
    }
    fn jacobian(&mut self, t: f64, _y: &[f64], j: &mut DMatrix<f64>) -> bool {
        j[(0, 0)] = self.shift;
        j[(0, 1)] = -2.0 * t * self.scale;
        j[(1, 0)] = 2.0 * t * self.scale;
        j[(1, 1)] = self.shift;
        true
    }
}

fn riccati_errors(make: fn(usize) -> Integrator, sys: &mut Riccati, steps: &[usize]) -> Vec<f64> {
    let t1 = 2.0;
    steps
        .iter()
        .map(|&n| {
            let mut integ = make(1);
            let (mut y, mut h) = ([1.0], 0.0);
            integ
                .integrate(
                    sys,
                    0.0,
                    t1,
                    &mut y,
                    &mut h,
                    &Options::fixed(1, t1 / n as f64),
                )
                .unwrap();
            (y[0] - 1.0 / (1.0 + t1 * t1)).abs()
        })
        .collect()
}

fn spiral_errors(make: fn(usize) -> Integrator, sys: &mut Spiral, steps: &[usize]) -> Vec<f64> {
    let t1 = 2.0;
    steps
        .iter()
        .map(|&n| {
            let mut integ = make(2);
            let (mut y, mut h) = ([1.0, 0.0], 0.0);
            integ
                .integrate(
                    sys,
                    0.0,
                    t1,
                    &mut y,
                    &mut h,
                    &Options::fixed(2, t1 / n as f64),
                )
                .unwrap();
            let (s, c) = (t1 * t1).sin_cos();
            (y[0] - c).abs().max((y[1] - s).abs())
        })
        .collect()
}

/// Order 3 with the exact Jacobian (kept over `W_JAC_MAX_AGE` fixed steps, so already
/// stale), with a wrong one, with `J = 0` (the method is then the explicit Runge–Kutta
/// method (α, b), itself of order 3) and without `∂f/∂t`. RODAS4 with the same wrong
/// Jacobian loses its order: the test tells the two kinds of method apart.
#[test]
fn ros34pw2_has_order_3_with_any_jacobian_and_without_df_dt() {
    // pre-asymptotic at first (orders near 4): the last ratio is the order's
    let steps = [80, 160, 320, 640, 1280];
    let cases: [(&str, f64, f64, bool); 5] = [
        ("exact J, df/dt", 1.0, 0.0, true),
        ("exact J, no df/dt", 1.0, 0.0, false),
        ("J x 0.3 - 2, df/dt", 0.3, -2.0, true),
        ("J x 2 + 1, no df/dt", 2.0, 1.0, false),
        ("J = 0, no df/dt", 0.0, 0.0, false),
    ];
    for (name, scale, shift, dfdt) in cases {
        let e = riccati_errors(ros34pw2, &mut Riccati { scale, shift, dfdt }, &steps);
        let p = orders(&e);
        println!("ROS34PW2 Riccati {name}: errors {} orders {p:.3?}", sci(&e));
        assert!((2.7..3.3).contains(&p[3]), "{name}: orders {p:?}");
    }
    for (name, scale, shift) in [("exact J", 1.0, 0.0), ("J x 0.5 + 0.5 I", 0.5, 0.5)] {
        let e = spiral_errors(ros34pw2, &mut Spiral { scale, shift }, &steps);
        let p = orders(&e);
        println!("ROS34PW2 spiral {name}: errors {} orders {p:.3?}", sci(&e));
        assert!((2.7..3.3).contains(&p[3]), "{name}: orders {p:?}");
    }
    // RODAS4 needs the exact J: with a wrong one its order drops well below 3
    let e = spiral_errors(
        rodas4,
        &mut Spiral {
            scale: 0.5,
            shift: 0.5,
        },
        &steps,
    );
    let p = orders(&e);
    println!(
        "RODAS4 spiral, J x 0.5 + 0.5 I: errors {} orders {p:.3?}",
        sci(&e)
    );
    assert!(p[3] < 2.5, "RODAS4 kept its order with a wrong J: {p:?}");
}

// ---------------------------------------------------------------------------------------
// Stiff problems
// ---------------------------------------------------------------------------------------

/// Prothero–Robinson: y' = λ(y − cos t) − sin t, y(0) = 1, exact y = cos t.
struct ProtheroRobinson {
    lambda: f64,
}
impl OdeSystem for ProtheroRobinson {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        dy[0] = self.lambda * (y[0] - t.cos()) - t.sin();
        Ok(())
    }
}

/// L-stability: on y' = λ(y − cos t) − sin t with hλ down to −1e8 the fixed-step solution
/// stays on cos t (an A-stable, not L-stable method would carry |R(∞)| ≈ 1 of every
/// error from step to step; the explicit method (α, b) would blow up).
#[test]
fn ros34pw2_is_l_stable_on_prothero_robinson() {
    for lambda in [-1e4, -1e8] {
        let mut errs = Vec::new();
        for n in [10, 20, 40] {
            let mut integ = ros34pw2(1);
            let (mut y, mut h) = ([1.0], 0.0);
            integ
                .integrate(
                    &mut ProtheroRobinson { lambda },
                    0.0,
                    1.0,
                    &mut y,
                    &mut h,
                    &Options::fixed(1, 1.0 / n as f64),
                )
                .unwrap();
            errs.push((y[0] - 1f64.cos()).abs());
        }
        println!(
            "ROS34PW2 Prothero-Robinson lambda {lambda:e}: errors {}",
            sci(&errs)
        );
        for e in &errs {
            assert!(*e < 1e-5, "lambda {lambda:e}: {errs:?}");
        }
    }
    // the stability function at infinity is 0: one step of y' = λy, hλ = −1e12, from 1
    struct Lin;
    impl OdeSystem for Lin {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
            dy[0] = -1e12 * y[0];
            Ok(())
        }
        fn jacobian(&mut self, _t: f64, _y: &[f64], j: &mut DMatrix<f64>) -> bool {
            j[(0, 0)] = -1e12;
            true
        }
    }
    let mut integ = ros34pw2(1);
    let (mut y, mut h) = ([1.0], 0.0);
    integ
        .integrate(&mut Lin, 0.0, 1.0, &mut y, &mut h, &Options::fixed(1, 1.0))
        .unwrap();
    println!("R(-1e12) = {}", y[0]);
    assert!(y[0].abs() < 1e-10, "R(-1e12) = {}", y[0]);
}

/// Van der Pol in Hairer's scaled form, ε = 1e-6.
struct VanDerPol {
    eps: f64,
}
impl OdeSystem for VanDerPol {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        dy[0] = y[1];
        dy[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / self.eps;
        Ok(())
    }
}

/// IVP test set VDPOL, μ = 1000 at t = 2 (the value `tests/integrators.rs` uses).
const VDP_REF: [f64; 2] = [1.706_167_732_170_469, -0.892_809_701_024_812_5];

/// Robertson's kinetics (Hairer & Wanner II §IV.1), finite-difference Jacobian.
struct Robertson;
impl OdeSystem for Robertson {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        dy[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
        dy[2] = 3e7 * y[1] * y[1];
        dy[1] = -dy[0] - dy[2];
        Ok(())
    }
}

/// Robertson at t = 40 (the value `tests/integrators.rs` uses).
const ROBER_40: [f64; 3] = [
    0.715_827_068_719_4,
    9.185_534_764_557_8e-6,
    0.284_163_745_745_83,
];

/// Adaptive ROS34PW2 on two stiff reference problems: the published values to the
/// tolerance's order, with fewer Jacobians than steps (the reuse) and fewer LUs than
/// step attempts.
#[test]
fn ros34pw2_adaptive_matches_stiff_references_with_fewer_jacobians() {
    for tol in [1e-5, 1e-7] {
        let mut integ = ros34pw2(2);
        let (mut y, mut h) = ([2.0, 0.0], 0.0);
        integ
            .integrate(
                &mut VanDerPol { eps: 1e-6 },
                0.0,
                2.0,
                &mut y,
                &mut h,
                &Options::new(2, tol, tol),
            )
            .unwrap();
        let s = *integ.stats();
        let rel = [0, 1].map(|i| (y[i] - VDP_REF[i]).abs() / VDP_REF[i].abs());
        println!("ROS34PW2 VdP tol {tol:e}: rel err {} {s:?}", sci(&rel));
        assert!(rel[0] < 100.0 * tol && rel[1] < 100.0 * tol, "{rel:?}");
        assert!(s.jac_evals < s.accepted, "{s:?}");
        assert!(s.lu_decomps < s.accepted + s.rejected, "{s:?}");
    }
    let rtol = 1e-7;
    let mut opts = Options::new(3, rtol, 1e-6 * rtol);
    opts.atol[1] = 1e-10 * rtol;
    let mut integ = ros34pw2(3);
    let (mut y, mut h) = ([1.0, 0.0, 0.0], 0.0);
    integ
        .integrate(&mut Robertson, 0.0, 40.0, &mut y, &mut h, &opts)
        .unwrap();
    let s = *integ.stats();
    println!("ROS34PW2 Robertson rtol {rtol:e}: y {y:?} {s:?}");
    for i in 0..3 {
        let rel = (y[i] - ROBER_40[i]).abs() / ROBER_40[i];
        assert!(rel < 1e-4, "y{}: rel {rel:e}", i + 1);
    }
    assert!((y.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    assert!(s.jac_evals < s.accepted, "{s:?}");
}

// ---------------------------------------------------------------------------------------
// The call contract
// ---------------------------------------------------------------------------------------

/// The Jacobian kept across steps lives within one call: a call on a used integrator
/// gives the same bits as on a fresh one; dense output is refused, not made up.
#[test]
fn ros34pw2_call_is_a_function_of_its_inputs() {
    let opts = Options::new(2, 1e-6, 1e-6);
    let mut used = ros34pw2(2);
    let (mut y, mut h) = ([2.0, 0.0], 0.0);
    let mut sys = VanDerPol { eps: 1e-3 };
    used.integrate(&mut sys, 0.0, 0.5, &mut y, &mut h, &opts)
        .unwrap();
    let (y_mid, h_mid) = (y, h);
    used.integrate(&mut sys, 0.5, 1.0, &mut y, &mut h, &opts)
        .unwrap();
    let mut fresh = ros34pw2(2);
    let (mut y2, mut h2) = (y_mid, h_mid);
    fresh
        .integrate(&mut sys, 0.5, 1.0, &mut y2, &mut h2, &opts)
        .unwrap();
    assert_eq!(y.map(f64::to_bits), y2.map(f64::to_bits));
    assert_eq!(h.to_bits(), h2.to_bits());
    let mut out = [0.0; 2];
    assert!(used.dense(0.9, &mut out).is_err());
}
