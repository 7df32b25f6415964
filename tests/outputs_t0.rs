//! Outputs are current whenever a host may read them: before the first step (after
//! creation and after setting inputs), after restoring a state, after a step — through the
//! Rust API and through the C ABI exactly as C calls it.
//!
//! The reference for the value at t0 is the value after a first step of 1 ns (FMI and the C
//! ABI have no zero-length step) from the same inputs: with the motion held
//! (`rule = "hold"`, zero velocities) a level without states (linear, quasi-static) moves
//! only its cage angle in that time (about 1e-7 rad at 1750 rpm), which changes a force by
//! about 1e-9 of itself, so the two must agree to the finite differences of K and C (1e-6).

use raceway::capi::*;
use raceway::component::variables::{self, Causality};
use raceway::component::Component;
use std::ffi::{c_char, CString};

/// The first step, s.
const H: f64 = 1e-9;

fn scene(level: &str) -> String {
    format!(
        "bearing = \"6205\"\n[model]\nlevel = \"{level}\"\n[inputs]\nrule = \"hold\"\n\
         [solver]\nrtol = 1e-10\n"
    )
}

/// Inputs of the default operating point: 10 µm down, 1750 rpm, no velocity.
fn inputs() -> Vec<(u32, f64)> {
    variables::all()
        .filter(|v| v.is_input(Causality::Motion))
        .map(|v| {
            let x = match v.name {
                "shaft.y" => -10e-6,
                "shaft.x" => 2e-6,
                "shaft.omega" => 183.259571,
                _ => 0.0,
            };
            (v.vr, x)
        })
        .collect()
}

fn outputs() -> Vec<u32> {
    variables::all()
        .filter(|v| v.is_output(Causality::Motion))
        .map(|v| v.vr)
        .collect()
}

fn name(vr: u32) -> &'static str {
    variables::by_vr(vr).unwrap().name
}

fn read(c: &mut Component) -> Vec<f64> {
    outputs()
        .iter()
        .map(|&vr| c.get_real(vr).unwrap())
        .collect()
}

/// Every output read at t0 equals the one after the first step, to `rtol` of the largest
/// value of its kind; the force is not zero.
fn assert_matches_first_step(at_t0: &[f64], after: &[f64]) {
    let big = at_t0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for ((&vr, a), b) in outputs().iter().zip(at_t0).zip(after) {
        let tol = 1e-6 * a.abs().max(b.abs()) + 1e-8 * big;
        assert!(
            (a - b).abs() <= tol,
            "{}: t0 {a:e}, after a step {b:e}",
            name(vr)
        );
    }
    let fy = outputs()
        .iter()
        .position(|&v| name(v) == "force.y")
        .unwrap();
    assert!(at_t0[fy] > 100.0, "force.y at t0 is {} N", at_t0[fy]);
}

#[test]
fn rust_api_outputs_at_t0_are_those_of_the_first_step() {
    for level in ["linear", "quasi_static"] {
        let mut c = Component::from_text(&scene(level)).unwrap();
        let fy = variables::by_name("force.y").unwrap().vr;
        for (vr, x) in inputs() {
            c.set_real(vr, x).unwrap();
        }
        assert!(c.outputs_stale());
        let t0 = read(&mut c);
        assert!(!c.outputs_stale());
        let s0 = c.get_state();
        c.do_step(0.0, H).unwrap();
        let after = read(&mut c);
        assert_matches_first_step(&t0, &after);

        // Restored state: the outputs of that moment, even when inputs changed since.
        c.set_real(variables::by_name("shaft.y").unwrap().vr, -20e-6)
            .unwrap();
        let moved = c.get_real(fy).unwrap();
        assert!(moved > 1.3 * t0[1], "{level}: {moved} vs {}", t0[1]);
        c.set_state(&s0).unwrap();
        assert_eq!(read(&mut c), t0, "{level}: after set_state");
    }
}

/// A state taken before the outputs were read (stale) is evaluated on the first read after
/// it is restored, in this instance or another (through the bytes).
#[test]
fn a_stale_state_restores_stale_and_is_evaluated_on_read() {
    let mut c = Component::from_text(&scene("quasi_static")).unwrap();
    for (vr, x) in inputs() {
        c.set_real(vr, x).unwrap();
    }
    let bytes = c.serialize_state();
    let t0 = read(&mut c);
    let mut d = Component::from_text(&scene("quasi_static")).unwrap();
    d.deserialize_state(&bytes).unwrap();
    assert!(d.outputs_stale());
    assert_eq!(read(&mut d), t0);
}

struct Inst(*mut RacewayComponent);

impl Drop for Inst {
    fn drop(&mut self) {
        unsafe { raceway_free(self.0) }
    }
}

fn c_create(text: &str) -> Inst {
    let text = CString::new(text).unwrap();
    let mut err = [0 as c_char; 512];
    let c = unsafe { raceway_create(text.as_ptr(), err.as_mut_ptr(), err.len()) };
    assert!(!c.is_null());
    Inst(c)
}

fn c_read(c: &Inst) -> Vec<f64> {
    let vrs = outputs();
    let mut v = vec![f64::NAN; vrs.len()];
    let st = unsafe { raceway_get_reals(c.0, vrs.as_ptr(), v.as_mut_ptr(), vrs.len()) };
    assert_eq!(st, RacewayStatus::Ok);
    v
}

#[test]
fn c_abi_outputs_at_t0_are_those_of_the_first_step() {
    for level in ["linear", "quasi_static"] {
        let c = c_create(&scene(level));
        let (vrs, xs): (Vec<u32>, Vec<f64>) = inputs().into_iter().unzip();
        let st = unsafe { raceway_set_reals(c.0, vrs.as_ptr(), xs.as_ptr(), vrs.len()) };
        assert_eq!(st, RacewayStatus::Ok);
        let t0 = c_read(&c);
        assert_eq!(unsafe { raceway_do_step(c.0, 0.0, H) }, RacewayStatus::Ok);
        assert_matches_first_step(&t0, &c_read(&c));
    }
}
