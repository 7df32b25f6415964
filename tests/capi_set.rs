//! A bearing set through the C ABI, called from Rust exactly as C calls it: the 7008CE DB
//! pair of `examples/scenes/7008ce-db-pair.toml` is one instance with the single bearing's
//! variables (force and moment at the reference point) and its rows' own
//! (`RACEWAY_VR_ROW_<i>_*`).

use raceway::capi::*;
use std::ffi::{c_char, CStr, CString};

#[path = "common/motion.rs"]
mod motion;
use motion::MOTION;

const PAIR: &str = include_str!("../examples/scenes/7008ce-db-pair.toml");

struct Inst(*mut RacewayComponent);

impl Drop for Inst {
    fn drop(&mut self) {
        unsafe { raceway_free(self.0) }
    }
}

impl Inst {
    fn new(text: &str) -> Inst {
        let text = CString::new(text).unwrap();
        let mut err = [0 as c_char; 512];
        let c = unsafe { raceway_create(text.as_ptr(), err.as_mut_ptr(), err.len()) };
        assert!(
            !c.is_null(),
            "{}",
            unsafe { CStr::from_ptr(err.as_ptr()) }.to_string_lossy()
        );
        Inst(c)
    }
    fn motion(&self, q: [f64; 5], omega: f64) {
        let mut v = [0.0; 11];
        v[..5].copy_from_slice(&q);
        v[10] = omega;
        let st = unsafe { raceway_set_reals(self.0, MOTION.as_ptr(), v.as_ptr(), 11) };
        assert_eq!(st, RacewayStatus::Ok);
    }
    fn get(&self, vr: u32) -> f64 {
        let mut v = f64::NAN;
        let st = unsafe { raceway_get_real(self.0, vr, &mut v) };
        assert_eq!(st, RacewayStatus::Ok);
        v
    }
}

const ROW_FORCES: [[u32; 5]; 2] = [
    [
        RACEWAY_VR_ROW0_FORCE_X,
        RACEWAY_VR_ROW0_FORCE_Y,
        RACEWAY_VR_ROW0_FORCE_Z,
        RACEWAY_VR_ROW0_MOMENT_X,
        RACEWAY_VR_ROW0_MOMENT_Y,
    ],
    [
        RACEWAY_VR_ROW1_FORCE_X,
        RACEWAY_VR_ROW1_FORCE_Y,
        RACEWAY_VR_ROW1_FORCE_Z,
        RACEWAY_VR_ROW1_MOMENT_X,
        RACEWAY_VR_ROW1_MOMENT_Y,
    ],
];

const FORCE: [u32; 5] = [
    RACEWAY_VR_FORCE_X,
    RACEWAY_VR_FORCE_Y,
    RACEWAY_VR_FORCE_Z,
    RACEWAY_VR_MOMENT_X,
    RACEWAY_VR_MOMENT_Y,
];

/// At zero external motion the rigidly preloaded pair's net axial force is zero, its rows
/// carrying equal and opposite loads (the 300 N preload); under a combined motion, after
/// steps, the force and moment at the reference point are the rows' forces carried there
/// (`Mx = sum (Mx_r - z_r Fy_r)`, `My = sum (My_r + z_r Fx_r)`, rows at `-/+ B/2`, the
/// 7008CE's width B = 15 mm).
#[test]
fn a_db_pair_through_the_c_abi() {
    let c = Inst::new(PAIR);
    c.motion([0.0; 5], 0.0);
    let (f0, f1) = (
        c.get(RACEWAY_VR_ROW0_FORCE_Z),
        c.get(RACEWAY_VR_ROW1_FORCE_Z),
    );
    assert!((f0 + f1).abs() < 1e-9 * 300.0, "{f0} {f1}");
    assert!((f1 - 300.0).abs() < 1e-6 * 300.0, "{f1}");
    assert!(c.get(RACEWAY_VR_FORCE_Z).abs() < 1e-9 * 300.0);
    let mut lift = 7;
    assert_eq!(
        unsafe { raceway_get_integer(c.0, RACEWAY_VR_ROW0_LIFT_OFF, &mut lift) },
        RacewayStatus::Ok
    );
    assert_eq!(lift, 0);

    c.motion([3e-6, -6e-6, 4e-6, 2e-4, -1e-4], 1256.6);
    let mut t = 0.0;
    for _ in 0..5 {
        assert_eq!(unsafe { raceway_do_step(c.0, t, 1e-4) }, RacewayStatus::Ok);
        t += 1e-4;
    }
    let z = [-7.5e-3, 7.5e-3];
    let mut sum = [0.0; 5];
    for (r, vrs) in ROW_FORCES.iter().enumerate() {
        let f: Vec<f64> = vrs.iter().map(|&vr| c.get(vr)).collect();
        sum[0] += f[0];
        sum[1] += f[1];
        sum[2] += f[2];
        sum[3] += f[3] - z[r] * f[1];
        sum[4] += f[4] + z[r] * f[0];
    }
    for (k, &vr) in FORCE.iter().enumerate() {
        let v = c.get(vr);
        assert!(
            (v - sum[k]).abs() <= 1e-9 * (1.0 + v.abs()),
            "{k}: {v} vs {}",
            sum[k]
        );
    }
    // The pair holds the tilt: a moment against it.
    assert!(c.get(RACEWAY_VR_MOMENT_X) < 0.0 && c.get(RACEWAY_VR_K_RX_RX) > 0.0);
}
