//! Integrator behaviour: convergence orders, tolerance proportionality, published stiff
//! reference values, transactions, landing on t1, step-size memory, dense output; the
//! W-method ROS34PW2's tableau, orders with any Jacobian, and stiff behaviour.
//!
//! Run with `cargo test --test integrators -- --nocapture` to see the measured numbers.

use nalgebra::DMatrix;
use raceway::solver::{
    BlockArrowhead, DenseLu, Dopri5, Integrator, OdeSystem, Options, RosMethod, Rosenbrock,
    SolverError, WCoeffs, ROS34PW2_ALPHA, ROS34PW2_B, ROS34PW2_BHAT, ROS34PW2_GAMMA_MATRIX,
};
use std::f64::consts::PI;

// ---------------------------------------------------------------------------------------
// Test systems
// ---------------------------------------------------------------------------------------

/// y' = −y + sin t, y(0) = y0: y(t) = (y0 + 1/2) e^{−t} + (sin t − cos t)/2.
/// Non-autonomous on purpose (exercises the ∂f/∂t terms of the Rosenbrock method).
struct Forced;
impl Forced {
    fn exact(t: f64, y0: f64) -> f64 {
        (y0 + 0.5) * (-t).exp() + 0.5 * (t.sin() - t.cos())
    }
}
impl OdeSystem for Forced {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        dy[0] = -y[0] + t.sin();
        Ok(())
    }
    fn jacobian(&mut self, _t: f64, _y: &[f64], j: &mut DMatrix<f64>) -> bool {
        j[(0, 0)] = -1.0;
        true
    }
    fn time_derivative(&mut self, t: f64, _y: &[f64], d: &mut [f64]) -> bool {
        d[0] = t.cos();
        true
    }
}

/// Kepler two-body problem, eccentricity e, period 2π: y(2π) = y(0)
/// (Hairer, Nørsett & Wanner I, §II.10, problem "AREN"-style orbit).
struct Kepler;
impl Kepler {
    fn y0(e: f64) -> [f64; 4] {
        [1.0 - e, 0.0, 0.0, ((1.0 + e) / (1.0 - e)).sqrt()]
    }
}
impl OdeSystem for Kepler {
    fn dim(&self) -> usize {
        4
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        let r3 = (y[0] * y[0] + y[1] * y[1]).powf(1.5);
        dy[0] = y[2];
        dy[1] = y[3];
        dy[2] = -y[0] / r3;
        dy[3] = -y[1] / r3;
        Ok(())
    }
    fn jacobian(&mut self, _t: f64, y: &[f64], j: &mut DMatrix<f64>) -> bool {
        let r2 = y[0] * y[0] + y[1] * y[1];
        let r3 = r2.powf(1.5);
        let r5 = r3 * r2;
        j.fill(0.0);
        j[(0, 2)] = 1.0;
        j[(1, 3)] = 1.0;
        j[(2, 0)] = -1.0 / r3 + 3.0 * y[0] * y[0] / r5;
        j[(2, 1)] = 3.0 * y[0] * y[1] / r5;
        j[(3, 0)] = 3.0 * y[0] * y[1] / r5;
        j[(3, 1)] = -1.0 / r3 + 3.0 * y[1] * y[1] / r5;
        true
    }
    fn time_derivative(&mut self, _t: f64, _y: &[f64], d: &mut [f64]) -> bool {
        d.fill(0.0);
        true
    }
}

/// Van der Pol in Hairer's scaled form, ε = 1/μ² = 1e-6 (μ = 1000):
/// y1' = y2, y2' = ((1 − y1²) y2 − y1)/ε, y(0) = (2, 0).
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
    fn jacobian(&mut self, _t: f64, y: &[f64], j: &mut DMatrix<f64>) -> bool {
        j[(0, 0)] = 0.0;
        j[(0, 1)] = 1.0;
        j[(1, 0)] = (-2.0 * y[0] * y[1] - 1.0) / self.eps;
        j[(1, 1)] = (1.0 - y[0] * y[0]) / self.eps;
        true
    }
    fn time_derivative(&mut self, _t: f64, _y: &[f64], d: &mut [f64]) -> bool {
        d.fill(0.0);
        true
    }
}

/// Robertson's chemical kinetics (Hairer & Wanner II, §IV.1, Eq. 1.4).
struct Robertson {
    analytic_jacobian: bool,
}
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
    fn jacobian(&mut self, _t: f64, y: &[f64], j: &mut DMatrix<f64>) -> bool {
        if !self.analytic_jacobian {
            return false;
        }
        j[(0, 0)] = -0.04;
        j[(0, 1)] = 1e4 * y[2];
        j[(0, 2)] = 1e4 * y[1];
        j[(2, 0)] = 0.0;
        j[(2, 1)] = 6e7 * y[1];
        j[(2, 2)] = 0.0;
        for c in 0..3 {
            j[(1, c)] = -j[(0, c)] - j[(2, c)];
        }
        true
    }
}

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

/// Wraps a system and fails (Err or NaN) for t beyond a time.
struct FailsAfter<S> {
    inner: S,
    t_fail: f64,
    nan: bool,
}
impl<S: OdeSystem> OdeSystem for FailsAfter<S> {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        if t > self.t_fail {
            if self.nan {
                dy.fill(f64::NAN);
                return Ok(());
            }
            return Err(format!("contact model out of range at t = {t}"));
        }
        self.inner.rhs(t, y, dy)
    }
}

/// Integrates `Forced` over [0, 1] at tolerance 1e-6, failing beyond t = 0.5 (an Err, or
/// a NaN right-hand side with `nan`); returns the error the integrator reports.
fn fails_after_half(integ: &mut Integrator, nan: bool, y: &mut [f64], h: &mut f64) -> SolverError {
    let mut sys = FailsAfter {
        inner: Forced,
        t_fail: 0.5,
        nan,
    };
    integ
        .integrate(&mut sys, 0.0, 1.0, y, h, &Options::new(1, 1e-6, 1e-6))
        .unwrap_err()
}

fn dopri(n: usize) -> Integrator {
    Integrator::Dopri5(Dopri5::new(n))
}
fn rodas(n: usize) -> Integrator {
    Integrator::Rosenbrock(Rosenbrock::new(n))
}

fn sci(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|x| format!("{x:.3e}")).collect();
    format!("[{}]", parts.join(", "))
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Observed orders log2(e_h / e_{h/2}) for a sequence of halved step sizes.
fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

// ---------------------------------------------------------------------------------------
// Orders of convergence (fixed steps)
// ---------------------------------------------------------------------------------------

fn forced_errors(mut integ: Integrator, steps: &[usize]) -> Vec<f64> {
    let t1 = 3.0;
    steps
        .iter()
        .map(|&n| {
            let mut y = [1.0];
            let mut h = 0.0;
            let opts = Options::fixed(1, t1 / n as f64);
            integ
                .integrate(&mut Forced, 0.0, t1, &mut y, &mut h, &opts)
                .unwrap();
            (y[0] - Forced::exact(t1, 1.0)).abs()
        })
        .collect()
}

/// Kepler orbit at time t from perihelion (eccentric anomaly from Kepler's equation
/// E − e sin E = t by Newton): position (cos E − e, √(1−e²) sin E), velocity its derivative.
fn kepler_exact(t: f64, e: f64) -> [f64; 4] {
    let mut ea = t;
    for _ in 0..50 {
        ea -= (ea - e * ea.sin() - t) / (1.0 - e * ea.cos());
    }
    let w = (1.0 - e * e).sqrt();
    let d = 1.0 - e * ea.cos();
    [ea.cos() - e, w * ea.sin(), -ea.sin() / d, w * ea.cos() / d]
}

fn kepler_errors(mut integ: Integrator, steps: &[usize]) -> Vec<f64> {
    let (e, t1) = (0.5, 4.0);
    steps
        .iter()
        .map(|&n| {
            let mut y = Kepler::y0(e);
            let mut h = 0.0;
            let opts = Options::fixed(4, t1 / n as f64);
            integ
                .integrate(&mut Kepler, 0.0, t1, &mut y, &mut h, &opts)
                .unwrap();
            max_abs_diff(&y, &kepler_exact(t1, e))
        })
        .collect()
}

#[test]
fn dopri5_converges_with_order_5() {
    let e = forced_errors(dopri(1), &[10, 20, 40, 80]);
    let p = orders(&e);
    println!("DOPRI5 forced linear: errors {} orders {p:.3?}", sci(&e));
    for q in &p {
        assert!((q - 5.0).abs() <= 0.3, "order {q}");
    }
    assert!(max_abs_diff(&kepler_exact(2.0 * PI, 0.5), &Kepler::y0(0.5)) < 1e-14);
    let e = kepler_errors(dopri(4), &[100, 200, 400]);
    let p = orders(&e);
    println!("DOPRI5 Kepler e=0.5: errors {} orders {p:.3?}", sci(&e));
    for q in &p {
        assert!((q - 5.0).abs() <= 0.3, "order {q}");
    }
}

#[test]
fn rodas4_converges_with_order_4() {
    // exact ∂f/∂y and ∂f/∂t: RODAS4 is not a W-method, its order needs them (with forward
    // differences the error levels off near 1e-10, the size of their truncation error)
    let e = forced_errors(rodas(1), &[5, 10, 20, 40, 80]);
    let p = orders(&e);
    println!("RODAS4 forced linear: errors {} orders {p:.3?}", sci(&e));
    for q in &p {
        assert!((q - 4.0).abs() <= 0.3, "order {q}");
    }
    let e = kepler_errors(rodas(4), &[400, 800, 1600, 3200]);
    let p = orders(&e);
    println!("RODAS4 Kepler e=0.5: errors {} orders {p:.3?}", sci(&e));
    for q in &p {
        assert!((q - 4.0).abs() <= 0.3, "order {q}");
    }
    for q in &p {
        assert!((q - 4.0).abs() <= 0.3, "order {q}");
    }
}

#[test]
fn rodas4_is_stiffly_accurate_on_prothero_robinson() {
    // λ = −1e8, h = 0.1: far outside any explicit stability region; an L-stable, stiffly
    // accurate method follows the smooth solution cos t to O(h^p/λ) + O(h^q) accuracy.
    let mut sys = ProtheroRobinson { lambda: -1e8 };
    let mut integ = rodas(1);
    let mut y = [1.0];
    let mut h = 0.0;
    integ
        .integrate(&mut sys, 0.0, 2.0, &mut y, &mut h, &Options::fixed(1, 0.1))
        .unwrap();
    let err = (y[0] - 2.0f64.cos()).abs();
    println!("RODAS4 Prothero-Robinson lambda=-1e8, h=0.1: error {err:.3e}");
    assert!(err < 1e-6, "error {err}");
    // the explicit method cannot take that step
    let mut y = [1.0];
    let r = dopri(1).integrate(&mut sys, 0.0, 2.0, &mut y, &mut h, &Options::fixed(1, 0.1));
    assert!(
        r.is_err() || (y[0] - 2.0f64.cos()).abs() > 1.0,
        "DOPRI5 should blow up"
    );
}

// ---------------------------------------------------------------------------------------
// Tolerance proportionality
// ---------------------------------------------------------------------------------------

fn kepler_adaptive_error(integ: &mut Integrator, tol: f64) -> f64 {
    let mut y = Kepler::y0(0.5);
    let mut h = 0.0;
    let opts = Options::new(4, tol, tol);
    integ
        .integrate(&mut Kepler, 0.0, 2.0 * PI, &mut y, &mut h, &opts)
        .unwrap();
    max_abs_diff(&y, &Kepler::y0(0.5))
}

#[test]
fn achieved_error_scales_with_the_tolerance() {
    for (name, mut integ) in [("DOPRI5", dopri(4)), ("RODAS4", rodas(4))] {
        let tols = [1e-5, 1e-7, 1e-9];
        let errs: Vec<f64> = tols
            .iter()
            .map(|&t| kepler_adaptive_error(&mut integ, t))
            .collect();
        // slope of log(err) against log(tol) per decade pair
        let slopes: Vec<f64> = errs
            .windows(2)
            .zip(tols.windows(2))
            .map(|(e, t)| (e[0] / e[1]).log10() / (t[0] / t[1]).log10())
            .collect();
        println!(
            "{name} Kepler: tol {} -> error {}, slopes {slopes:.3?}, stats {:?}",
            sci(&tols),
            sci(&errs),
            integ.stats()
        );
        for s in &slopes {
            assert!((0.6..=1.3).contains(s), "{name} slope {s}");
        }
        for (e, t) in errs.iter().zip(&tols) {
            // calibrated: within three decades above the tolerance
            // (a whole eccentric orbit: the global error is ~100× the local tolerance)
            assert!(*e < 1e3 * t && *e > 0.1 * t, "{name} error {e} at tol {t}");
        }
    }
}

// ---------------------------------------------------------------------------------------
// Stiff reference problems
// ---------------------------------------------------------------------------------------

/// IVP test set (Mazzia & Magherini, Univ. Bari), problem VDPOL, μ = 1000 on [0, 2000];
/// identical to the scaled form at t = 2 (y2 scaled by μ). Also Hairer & Wanner II §IV.10.
const VDP_REF: [f64; 2] = [1.706_167_732_170_469, -0.892_809_701_024_812_5];

/// Van der Pol ε = 1e-6 from (2, 0) to t = 2 at rtol = atol = `tol`: the state and its
/// relative error against [`VDP_REF`].
fn vdp_to_2(integ: &mut Integrator, tol: f64) -> ([f64; 2], [f64; 2]) {
    let mut y = [2.0, 0.0];
    let mut h = 0.0;
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
    (
        y,
        [0, 1].map(|i| (y[i] - VDP_REF[i]).abs() / VDP_REF[i].abs()),
    )
}

#[test]
fn rodas4_van_der_pol_mu_1000_matches_the_reference() {
    for tol in [1e-6, 1e-9] {
        let mut integ = rodas(2);
        let (y, rel) = vdp_to_2(&mut integ, tol);
        println!(
            "RODAS4 VdP eps=1e-6 tol {tol:e}: y {y:?} rel err {} {:?}",
            sci(&rel),
            integ.stats()
        );
        assert!(rel[0] < 100.0 * tol && rel[1] < 100.0 * tol, "{rel:?}");
    }
}

/// Robertson at t = 40: Hairer & Wanner II §IV.10 / SUNDIALS cvRoberts_dns example
/// (0.71583, 9.1856e-6, 0.28416 printed); more digits from independent Radau/CVODE runs at
/// rtol 1e-12 (IVP test set convention), agreeing to 1e-12.
const ROBER_40: [f64; 3] = [
    0.715_827_068_719_4,
    9.185_534_764_557_8e-6,
    0.284_163_745_745_83,
];
/// Robertson at t = 1e5 (SciPy Radau, rtol 1e-12, atol 1e-18).
const ROBER_1E5: [f64; 3] = [
    0.017_865_921_142_108_87,
    7.274_751_468_440_222e-8,
    0.982_134_006_110_375_8,
];

fn rober_opts(rtol: f64) -> Options {
    let mut o = Options::new(3, rtol, 1e-6 * rtol);
    o.atol[1] = 1e-10 * rtol; // y2 lives at 1e-5 .. 1e-8
    o
}

#[test]
fn rodas4_robertson_matches_the_reference_and_dopri5_finds_it_stiff() {
    let rtol = 1e-8;
    let mut results = Vec::new();
    for analytic in [true, false] {
        let mut integ = rodas(3);
        let mut y = [1.0, 0.0, 0.0];
        let mut h = 0.0;
        let mut sys = Robertson {
            analytic_jacobian: analytic,
        };
        integ
            .integrate(&mut sys, 0.0, 40.0, &mut y, &mut h, &rober_opts(rtol))
            .unwrap();
        let s40 = *integ.stats();
        for i in 0..3 {
            let rel = (y[i] - ROBER_40[i]).abs() / ROBER_40[i];
            assert!(
                rel < 1e-6,
                "y{} at 40: {} vs {} (rel {rel:e})",
                i + 1,
                y[i],
                ROBER_40[i]
            );
        }
        // the linear invariant y1 + y2 + y3 = 1 is kept by any Runge–Kutta-type method
        assert!((y.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        integ
            .integrate(&mut sys, 40.0, 1e5, &mut y, &mut h, &rober_opts(rtol))
            .unwrap();
        for i in 0..3 {
            let rel = (y[i] - ROBER_1E5[i]).abs() / ROBER_1E5[i];
            assert!(
                rel < 1e-5,
                "y{} at 1e5: {} vs {} (rel {rel:e})",
                i + 1,
                y[i],
                ROBER_1E5[i]
            );
        }
        println!(
            "RODAS4 Robertson rtol {rtol:e} (analytic J: {analytic}): to t=40 {s40:?}; to t=1e5 {:?}",
            integ.stats()
        );
        results.push(s40);
    }
    // DOPRI5 to t = 40 at the same tolerance: stability, not accuracy, limits its step
    let mut d = dopri(3);
    let mut y = [1.0, 0.0, 0.0];
    let mut h = 0.0;
    let mut sys = Robertson {
        analytic_jacobian: false,
    };
    d.integrate(&mut sys, 0.0, 40.0, &mut y, &mut h, &rober_opts(rtol))
        .unwrap();
    let ds = *d.stats();
    println!("DOPRI5 Robertson to t=40: {ds:?}");
    for i in 0..3 {
        let rel = (y[i] - ROBER_40[i]).abs() / ROBER_40[i];
        assert!(rel < 1e-5, "DOPRI5 y{}: rel {rel:e}", i + 1);
    }
    assert!(ds.stiff_alarms > 0, "the stiffness detector should fire");
    assert!(
        ds.accepted > 20 * results[0].accepted,
        "DOPRI5 {} steps vs RODAS4 {}",
        ds.accepted,
        results[0].accepted
    );
}

// ---------------------------------------------------------------------------------------
// Transactions and failure reporting
// ---------------------------------------------------------------------------------------

#[test]
fn a_failing_rhs_leaves_the_state_untouched_and_names_the_cause() {
    for make in [dopri as fn(usize) -> Integrator, rodas] {
        let mut integ = make(1);
        let y_before = [0.75];
        let mut y = y_before;
        let mut h = 0.01;
        let err = fails_after_half(&mut integ, false, &mut y, &mut h);
        assert_eq!(y, y_before);
        assert_eq!(h, 0.01);
        match &err {
            SolverError::Rhs { t, message } => {
                assert!(*t > 0.5 && *t <= 1.0);
                assert!(message.contains("contact model out of range"));
            }
            e => panic!("wrong error {e:?}"),
        }
        let text = raceway::Error::from(err).to_string();
        assert!(
            text.contains("state unchanged") && text.contains("contact model"),
            "{text}"
        );

        // a non-finite right-hand side: rejected, retried smaller, then reported
        let err = fails_after_half(&mut integ, true, &mut y, &mut h);
        assert_eq!(y, y_before);
        assert_eq!(h, 0.01);
        assert!(
            matches!(err, SolverError::NonFinite { what: "right-hand side", index: 0, t } if t > 0.5),
            "{err:?}"
        );
    }
}

#[test]
fn too_many_steps_and_bad_options_are_refused() {
    let mut integ = dopri(4);
    let mut y = Kepler::y0(0.5);
    let mut h = 0.0;
    let mut opts = Options::new(4, 1e-10, 1e-10);
    opts.max_steps = 10;
    let err = integ
        .integrate(&mut Kepler, 0.0, 2.0 * PI, &mut y, &mut h, &opts)
        .unwrap_err();
    assert!(matches!(
        err,
        SolverError::TooManySteps { max_steps: 10, .. }
    ));
    assert_eq!(y, Kepler::y0(0.5));
    let bad = Options::new(3, 1e-6, 1e-6);
    let err = integ
        .integrate(&mut Kepler, 0.0, 1.0, &mut y, &mut h, &bad)
        .unwrap_err();
    assert!(err.to_string().contains("atol.len()"), "{err}");
    let mut bad = Options::new(4, 1e-6, 1e-6);
    bad.atol[2] = 0.0;
    let err = integ
        .integrate(&mut Kepler, 0.0, 1.0, &mut y, &mut h, &bad)
        .unwrap_err();
    assert!(err.to_string().contains("atol[2]"), "{err}");
    let err = integ
        .integrate(
            &mut Kepler,
            1.0,
            0.0,
            &mut y,
            &mut h,
            &Options::new(4, 1e-6, 1e-6),
        )
        .unwrap_err();
    assert!(err.to_string().contains("t1"), "{err}");
}

// ---------------------------------------------------------------------------------------
// Landing on t1 and step-size memory
// ---------------------------------------------------------------------------------------

#[test]
fn lands_exactly_on_t1() {
    for make in [dopri as fn(usize) -> Integrator, rodas] {
        let mut integ = make(1);
        let mut y = [1.0];
        let mut h = 0.0;
        let opts = Options::new(1, 1e-8, 1e-8);
        let mut t = 0.0;
        // communication points that are not representable sums of the internal steps
        for k in 1..=7 {
            let t1 = 0.1 * k as f64 * 1.000_000_1;
            integ
                .integrate(&mut Forced, t, t1, &mut y, &mut h, &opts)
                .unwrap();
            assert_eq!(integ.last_step().unwrap().1, t1, "last step must end on t1");
            assert!((y[0] - Forced::exact(t1, 1.0)).abs() < 1e-7);
            t = t1;
        }
        // fixed-step mode lands too, with equal steps
        let t1 = 1.0 / 3.0;
        let mut y = [1.0];
        integ
            .integrate(
                &mut Forced,
                0.0,
                t1,
                &mut y,
                &mut h,
                &Options::fixed(1, 0.05),
            )
            .unwrap();
        let (a, b) = integ.last_step().unwrap();
        assert_eq!(b, t1);
        assert!(((b - a) - t1 / 7.0).abs() < 1e-15);
    }
}

#[test]
fn step_size_memory_carries_across_calls() {
    for (name, make) in [
        ("DOPRI5", dopri as fn(usize) -> Integrator),
        ("RODAS4", rodas),
    ] {
        let tol = 1e-8;
        let opts = Options::new(4, tol, tol);
        let t_end = 2.0 * PI;
        // one call
        let mut one = make(4);
        let mut y_one = Kepler::y0(0.5);
        let mut h = 0.0;
        one.integrate(&mut Kepler, 0.0, t_end, &mut y_one, &mut h, &opts)
            .unwrap();
        // two halves with the memory carried
        let mut two = make(4);
        let mut y_two = Kepler::y0(0.5);
        let mut h = 0.0;
        two.integrate(&mut Kepler, 0.0, 0.5 * t_end, &mut y_two, &mut h, &opts)
            .unwrap();
        assert!(h > 0.0 && h.is_finite());
        two.integrate(&mut Kepler, 0.5 * t_end, t_end, &mut y_two, &mut h, &opts)
            .unwrap();
        let d = max_abs_diff(&y_one, &y_two);
        assert!(
            d < 100.0 * tol,
            "{name}: halves differ from one call by {d}"
        );

        // many communication steps on a mildly stiff Van der Pol (ε = 1e-3, relaxation
        // jumps): warm (memory carried) against cold (h reset at every call)
        let comm = 0.02;
        let vdp_opts = Options::new(2, 1e-6, 1e-6);
        let run = |warm: bool| {
            let mut integ = make(2);
            let mut y = [2.0, 0.0];
            let mut h = 0.0;
            for k in 0..100 {
                if !warm {
                    h = 0.0;
                }
                integ
                    .integrate(
                        &mut VanDerPol { eps: 1e-3 },
                        k as f64 * comm,
                        (k + 1) as f64 * comm,
                        &mut y,
                        &mut h,
                        &vdp_opts,
                    )
                    .unwrap();
            }
            (*integ.stats(), y)
        };
        let (warm, yw) = run(true);
        let (cold, yc) = run(false);
        println!("{name} VdP eps=1e-3, 100 comm steps: warm {warm:?}; cold {cold:?}");
        assert!(
            max_abs_diff(&yw, &yc) < 1e-5,
            "{name}: warm and cold disagree"
        );
        assert!(
            warm.rhs_evals < cold.rhs_evals,
            "{name}: warm start should be cheaper"
        );
        assert!(
            warm.rejected <= cold.rejected,
            "{name}: warm start should reject less"
        );
        if name == "DOPRI5" {
            // the cold initial guess overshoots on the fast phases again and again
            assert!(2 * warm.rejected < cold.rejected, "{name}: rejections");
        }
    }
}

#[test]
fn a_call_is_a_function_of_its_inputs() {
    // same (t0, t1, y, h_trial) on a used and a fresh integrator: bit-identical
    for make in [dopri as fn(usize) -> Integrator, rodas] {
        let opts = Options::new(4, 1e-7, 1e-7);
        let mut used = make(4);
        let mut y = Kepler::y0(0.5);
        let mut h = 0.0;
        used.integrate(&mut Kepler, 0.0, 1.0, &mut y, &mut h, &opts)
            .unwrap();
        let (y_mid, h_mid) = (y, h);
        used.integrate(&mut Kepler, 1.0, 2.0, &mut y, &mut h, &opts)
            .unwrap();
        let mut fresh = make(4);
        let (mut y2, mut h2) = (y_mid, h_mid);
        fresh
            .integrate(&mut Kepler, 1.0, 2.0, &mut y2, &mut h2, &opts)
            .unwrap();
        assert_eq!(y, y2);
        assert_eq!(h, h2);
    }
}

// ---------------------------------------------------------------------------------------
// Dense output
// ---------------------------------------------------------------------------------------

/// Largest dense-output error at interior points of single steps of size h (local error).
fn dense_local_error(integ: &mut Integrator, h: f64) -> f64 {
    let mut worst: f64 = 0.0;
    let mut out = [0.0];
    for k in 0..4 {
        let t0 = 0.3 + k as f64;
        let mut y = [Forced::exact(t0, 1.0)];
        let mut hh = 0.0;
        integ
            .integrate(
                &mut Forced,
                t0,
                t0 + h,
                &mut y,
                &mut hh,
                &Options::fixed(1, h),
            )
            .unwrap();
        for th in [0.2, 0.5, 0.8] {
            let t = t0 + th * h;
            integ.dense(t, &mut out).unwrap();
            worst = worst.max((out[0] - Forced::exact(t, 1.0)).abs());
        }
    }
    worst
}

#[test]
fn dense_output_is_accurate_between_steps() {
    let hs = [0.4, 0.2, 0.1, 0.05];
    let mut d = dopri(1);
    let e: Vec<f64> = hs.iter().map(|&h| dense_local_error(&mut d, h)).collect();
    let p = orders(&e);
    println!("DOPRI5 dense local errors {} orders {p:.3?}", sci(&e));
    // 4th-order continuous extension: local error O(h^5)
    for q in &p {
        assert!((q - 5.0).abs() <= 0.4, "DOPRI5 dense order {q}");
    }
    let mut r = rodas(1);
    let e: Vec<f64> = hs.iter().map(|&h| dense_local_error(&mut r, h)).collect();
    let p = orders(&e);
    println!("RODAS4 dense local errors {} orders {p:.3?}", sci(&e));
    // 3rd-order continuous extension: local error O(h^4)
    for q in &p {
        assert!(*q >= 3.6, "RODAS4 dense order {q}");
    }
    // adaptive run: dense output inside the last step against the exact solution
    let mut y = [1.0];
    let mut h = 0.0;
    d.integrate(
        &mut Forced,
        0.0,
        5.0,
        &mut y,
        &mut h,
        &Options::new(1, 1e-9, 1e-9),
    )
    .unwrap();
    let (a, b) = d.last_step().unwrap();
    let mut out = [0.0];
    for th in [0.0, 0.25, 0.5, 0.75, 1.0] {
        let t = a + th * (b - a);
        d.dense(t, &mut out).unwrap();
        assert!((out[0] - Forced::exact(t, 1.0)).abs() < 1e-8);
    }
    assert!(d.dense(b + 1.0, &mut out).is_err());
}

// ---------------------------------------------------------------------------------------
// Structured linear solve inside the Rosenbrock method
// ---------------------------------------------------------------------------------------

/// A "bearing-shaped" stiff system: nb balls with 2 states each, coupled only to a 2-state
/// ring (and the ring to all balls): an arrowhead Jacobian.
struct BallsAndRing {
    nb: usize,
}
impl OdeSystem for BallsAndRing {
    fn dim(&self) -> usize {
        2 * self.nb + 2
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), String> {
        let r = 2 * self.nb;
        let (rx, rv) = (y[r], y[r + 1]);
        let mut force = 0.0;
        for b in 0..self.nb {
            let (x, v) = (y[2 * b], y[2 * b + 1]);
            let phase = b as f64;
            // stiff, damped ball attached to the ring by a nonlinear spring
            let d = x - rx;
            let f = 1e4 * d + 1e3 * d * d * d;
            dy[2 * b] = v;
            dy[2 * b + 1] = -f - 1e4 * v + (t + phase).sin();
            force += f;
        }
        dy[r] = rv;
        dy[r + 1] = force / self.nb as f64 - 10.0 * rx - rv;
        Ok(())
    }
    fn jacobian(&mut self, _t: f64, y: &[f64], j: &mut DMatrix<f64>) -> bool {
        let r = 2 * self.nb;
        let nbf = self.nb as f64;
        j.fill(0.0);
        let mut sum = 0.0;
        for b in 0..self.nb {
            let d = y[2 * b] - y[r];
            let fp = 1e4 + 3e3 * d * d;
            j[(2 * b, 2 * b + 1)] = 1.0;
            j[(2 * b + 1, 2 * b)] = -fp;
            j[(2 * b + 1, 2 * b + 1)] = -1e4;
            j[(2 * b + 1, r)] = fp;
            j[(r + 1, 2 * b)] = fp / nbf;
            sum += fp;
        }
        j[(r, r + 1)] = 1.0;
        j[(r + 1, r)] = -sum / nbf - 10.0;
        j[(r + 1, r + 1)] = -1.0;
        true
    }
    fn time_derivative(&mut self, t: f64, _y: &[f64], d: &mut [f64]) -> bool {
        d.fill(0.0);
        for b in 0..self.nb {
            d[2 * b + 1] = (t + b as f64).cos();
        }
        true
    }
}

#[test]
fn rodas4_with_block_arrowhead_solver_matches_dense_lu() {
    let nb = 6;
    let n = 2 * nb + 2;
    let y0: Vec<f64> = (0..n).map(|i| 0.01 * (i as f64).cos()).collect();
    let run = |solver: Option<BlockArrowhead>, opts: &Options| {
        let mut r = match solver {
            Some(b) => Rosenbrock::with_solver(Box::new(b)),
            None => Rosenbrock::new(n),
        };
        let mut y = y0.clone();
        let mut h = 0.0;
        r.integrate(&mut BallsAndRing { nb }, 0.0, 2.0, &mut y, &mut h, opts)
            .unwrap();
        (y, r.stats)
    };
    // same step sequence (and analytic Jacobian, so no finite-difference noise): the two
    // solvers agree to rounding
    let fixed = Options::fixed(n, 0.01);
    let (yd, _) = run(None, &fixed);
    let (yb, _) = run(Some(BlockArrowhead::new(nb, 2, 2)), &fixed);
    let d = max_abs_diff(&yd, &yb);
    assert!(d < 1e-14, "fixed steps: block and dense differ by {d}");
    let mut j = DMatrix::zeros(n, n);
    BallsAndRing { nb }.jacobian(0.0, &y0, &mut j);
    assert!(BlockArrowhead::new(nb, 2, 2).fits(&j));
    // adaptive: rounding may change an accept/reject decision, agreement to tolerance
    let opts = Options::new(n, 1e-6, 1e-8);
    let (yd, sd) = run(None, &opts);
    let (yb, sb) = run(Some(BlockArrowhead::new(nb, 2, 2)), &opts);
    let d = max_abs_diff(&yd, &yb);
    println!("RODAS4 balls+ring n={n}: dense {sd:?} block {sb:?} max diff {d:.2e}");
    assert!(d < 1e-7, "adaptive: block and dense differ by {d}");
    // and the problem is genuinely stiff for DOPRI5 (ball modes λ ≈ −1e4 and −1)
    let mut dp = Dopri5::new(n);
    let mut y = y0.clone();
    let mut h = 0.0;
    dp.integrate(&mut BallsAndRing { nb }, 0.0, 2.0, &mut y, &mut h, &opts)
        .unwrap();
    println!("DOPRI5 balls+ring: {:?}", dp.stats);
    let dd = max_abs_diff(&y, &yd);
    println!("DOPRI5 vs RODAS4 max diff {dd:.2e}");
    // both within their global error (rtol = 1e-6 on states up to ~0.7)
    assert!(dd < 5e-5, "DOPRI5 and RODAS4 differ by {dd}");
    // DOPRI5 sits on its stability bound h ≈ 3.3/1e4 (2 s / 3.3e-4 ≈ 6000 steps); RODAS4 is
    // limited by accuracy on the 100 rad/s ring mode
    assert!(dp.stats.accepted > 3 * sb.accepted);
    assert!(dp.stats.accepted as f64 > 0.9 * 2.0 / (3.3 / 1e4));
}

// ---------------------------------------------------------------------------------------
// The W-method ROS34PW2 (`RosMethod::Ros34pw2`): its published tableau's order
// conditions, order 3 with the exact Jacobian, with a wrong one and with no `∂f/∂t` (the W
// property, which RODAS4 does not have), L-stability, the stiff reference values, and the
// call contract (a call is a function of its inputs although `J` is kept across the steps
// of a call).
// ---------------------------------------------------------------------------------------

fn ros34pw2(n: usize) -> Integrator {
    Integrator::Rosenbrock(Rosenbrock::with_method(
        RosMethod::Ros34pw2,
        Box::new(DenseLu::new(n)),
    ))
}

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

/// Fixed-step errors at t = 2 for each step count, against `exact`.
fn fixed_errors<S: OdeSystem>(
    make: fn(usize) -> Integrator,
    sys: &mut S,
    y0: &[f64],
    exact: &[f64],
    steps: &[usize],
) -> Vec<f64> {
    let (n, t1) = (y0.len(), 2.0);
    steps
        .iter()
        .map(|&k| {
            let mut integ = make(n);
            let (mut y, mut h) = (y0.to_vec(), 0.0);
            integ
                .integrate(
                    sys,
                    0.0,
                    t1,
                    &mut y,
                    &mut h,
                    &Options::fixed(n, t1 / k as f64),
                )
                .unwrap();
            max_abs_diff(&y, exact)
        })
        .collect()
}

/// y(2) of [`Riccati`] and [`Spiral`].
const RICCATI_2: [f64; 1] = [0.2];
fn spiral_2() -> [f64; 2] {
    let (s, c) = 4f64.sin_cos();
    [c, s]
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
        let mut sys = Riccati { scale, shift, dfdt };
        let e = fixed_errors(ros34pw2, &mut sys, &[1.0], &RICCATI_2, &steps);
        let p = orders(&e);
        println!("ROS34PW2 Riccati {name}: errors {} orders {p:.3?}", sci(&e));
        assert!((2.7..3.3).contains(&p[3]), "{name}: orders {p:?}");
    }
    for (name, scale, shift) in [("exact J", 1.0, 0.0), ("J x 0.5 + 0.5 I", 0.5, 0.5)] {
        let mut sys = Spiral { scale, shift };
        let e = fixed_errors(ros34pw2, &mut sys, &[1.0, 0.0], &spiral_2(), &steps);
        let p = orders(&e);
        println!("ROS34PW2 spiral {name}: errors {} orders {p:.3?}", sci(&e));
        assert!((2.7..3.3).contains(&p[3]), "{name}: orders {p:?}");
    }
    // RODAS4 needs the exact J: with a wrong one its order drops well below 3
    let mut sys = Spiral {
        scale: 0.5,
        shift: 0.5,
    };
    let e = fixed_errors(rodas, &mut sys, &[1.0, 0.0], &spiral_2(), &steps);
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

/// Adaptive ROS34PW2 on two stiff reference problems: the published values to the
/// tolerance's order, with fewer Jacobians than steps (the reuse) and fewer LUs than
/// step attempts.
#[test]
fn ros34pw2_adaptive_matches_stiff_references_with_fewer_jacobians() {
    for tol in [1e-5, 1e-7] {
        let mut integ = ros34pw2(2);
        let (_, rel) = vdp_to_2(&mut integ, tol);
        let s = *integ.stats();
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
    let mut sys = Robertson {
        analytic_jacobian: false,
    };
    integ
        .integrate(&mut sys, 0.0, 40.0, &mut y, &mut h, &opts)
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
