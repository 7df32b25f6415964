//! The C ABI, called from Rust exactly as C calls it: results, state round trips, bad
//! input refused with a status and a message naming the cause (and the instance unharmed),
//! and many instances on several threads.

use raceway::capi::*;
use std::ffi::{c_char, CStr, CString};
use std::ptr::{null, null_mut};

const SCENE: &str = raceway::component::scene::DEFAULT_SCENE;

#[path = "common/cross_process.rs"]
mod cross_process;
#[path = "common/motion.rs"]
mod motion;
use motion::MOTION;

/// Outputs read after each step.
const OUTPUTS: [u32; 6] = [
    RACEWAY_VR_FORCE_X,
    RACEWAY_VR_FORCE_Y,
    RACEWAY_VR_FORCE_Z,
    RACEWAY_VR_MOMENT_X,
    RACEWAY_VR_K_X_X,
    RACEWAY_VR_K_Y_Y,
];

/// An instance that is freed on drop.
struct Inst(*mut RacewayComponent);

impl Drop for Inst {
    fn drop(&mut self) {
        unsafe { raceway_free(self.0) }
    }
}

fn try_create(text: &[u8]) -> Result<Inst, String> {
    let text = CString::new(text).unwrap();
    let mut err = [0 as c_char; 512];
    let c = unsafe { raceway_create(text.as_ptr(), err.as_mut_ptr(), err.len()) };
    if c.is_null() {
        Err(unsafe { CStr::from_ptr(err.as_ptr()) }
            .to_string_lossy()
            .into_owned())
    } else {
        assert_eq!(err[0], 0, "nothing written on success");
        Ok(Inst(c))
    }
}

fn create() -> Inst {
    try_create(SCENE.as_bytes()).unwrap()
}

impl Inst {
    fn msg(&self) -> String {
        unsafe { CStr::from_ptr(raceway_last_error(self.0)) }
            .to_str()
            .unwrap()
            .to_owned()
    }
    /// Motion inputs at step `k` of a deterministic sequence with `seed`.
    fn set_motion(&self, k: usize, seed: f64) {
        let s = k as f64;
        let values = [
            1e-6 * (0.3 * s + seed).sin(),
            -10e-6 + 1e-6 * (0.2 * s).cos(),
            0.0,
            1e-5 * seed,
            0.0,
            1e-3 * (0.3 * s).cos(),
            -2e-4 * (0.2 * s).sin(),
            0.0,
            0.0,
            0.0,
            183.26 + seed,
        ];
        let st = unsafe { raceway_set_reals(self.0, MOTION.as_ptr(), values.as_ptr(), 11) };
        assert_eq!(st, RacewayStatus::Ok, "{}", self.msg());
    }
    fn step(&self, t: f64, h: f64) -> RacewayStatus {
        unsafe { raceway_do_step(self.0, t, h) }
    }
    fn time(&self) -> f64 {
        let mut t = f64::NAN;
        assert_eq!(
            unsafe { raceway_get_time(self.0, &mut t) },
            RacewayStatus::Ok
        );
        t
    }
    fn outputs(&self) -> Vec<f64> {
        let mut out = [f64::NAN; OUTPUTS.len()];
        let st = unsafe { raceway_get_reals(self.0, OUTPUTS.as_ptr(), out.as_mut_ptr(), 6) };
        assert_eq!(st, RacewayStatus::Ok, "{}", self.msg());
        out.to_vec()
    }
    fn get(&self, vr: u32) -> f64 {
        let mut v = f64::NAN;
        let st = unsafe { raceway_get_real(self.0, vr, &mut v) };
        assert_eq!(st, RacewayStatus::Ok, "{}", self.msg());
        v
    }
    /// `n` steps of the sequence from the current time; the outputs after each.
    fn run(&self, from: usize, n: usize, seed: f64, h: f64) -> Vec<f64> {
        let mut all = Vec::new();
        for k in from..from + n {
            self.set_motion(k, seed);
            assert_eq!(
                self.step(self.time(), h),
                RacewayStatus::Ok,
                "{}",
                self.msg()
            );
            all.extend(self.outputs());
        }
        all
    }
    fn state_bytes(&self) -> Vec<u8> {
        let mut s: *mut RacewayState = null_mut();
        assert_eq!(
            unsafe { raceway_state_get(self.0, &mut s) },
            RacewayStatus::Ok
        );
        let mut n = 0usize;
        assert_eq!(
            unsafe { raceway_state_size(self.0, s, &mut n) },
            RacewayStatus::Ok
        );
        let mut buf = vec![0u8; n];
        let st = unsafe { raceway_state_serialize(self.0, s, buf.as_mut_ptr(), n) };
        assert_eq!(st, RacewayStatus::Ok, "{}", self.msg());
        unsafe { raceway_state_free(s) };
        buf
    }
    fn restore_bytes(&self, b: &[u8]) -> RacewayStatus {
        let mut s: *mut RacewayState = null_mut();
        let st = unsafe { raceway_state_deserialize(self.0, b.as_ptr(), b.len(), &mut s) };
        if st != RacewayStatus::Ok {
            assert!(s.is_null(), "no state on failure");
            return st;
        }
        let st = unsafe { raceway_state_set(self.0, s) };
        unsafe { raceway_state_free(s) };
        st
    }
}

#[test]
fn single_and_bulk_access_agree_and_the_stepped_outputs_follow_the_inputs() {
    let c = create();
    let out = c.run(0, 3, 0.5, 1e-4);
    assert_eq!(c.time(), 1e-4 + 1e-4 + 1e-4);
    // Bulk and single reads give the same numbers.
    let last = &out[out.len() - 6..];
    for (i, &vr) in OUTPUTS.iter().enumerate() {
        assert_eq!(c.get(vr).to_bits(), last[i].to_bits());
    }
    // Inputs read back exactly what was set.
    let mut v = [0.0; 11];
    let st = unsafe { raceway_get_reals(c.0, MOTION.as_ptr(), v.as_mut_ptr(), 11) };
    assert_eq!(st, RacewayStatus::Ok);
    assert_eq!(v[10], 183.26 + 0.5);
    // The directional derivative of the forces along a displacement seed is -K seed (the
    // Jacobian the outputs K publish).
    let (kxx, kyy) = (c.get(RACEWAY_VR_K_X_X), c.get(RACEWAY_VR_K_Y_Y));
    assert!(kxx > 0.0 && kyy > 0.0);
    let unknowns = [RACEWAY_VR_FORCE_X, RACEWAY_VR_FORCE_Y];
    let knowns = [RACEWAY_VR_SHAFT_X, RACEWAY_VR_SHAFT_Y];
    let seed = [2e-6, -3e-6];
    let mut dd = [f64::NAN; 2];
    let st = unsafe {
        raceway_directional_derivative(
            c.0,
            unknowns.as_ptr(),
            2,
            knowns.as_ptr(),
            2,
            seed.as_ptr(),
            dd.as_mut_ptr(),
        )
    };
    assert_eq!(st, RacewayStatus::Ok, "{}", c.msg());
    let kxy = c.get(raceway::component::variables::VR_K0 + 1);
    let kyx = c.get(raceway::component::variables::VR_K0 + 5);
    assert!((dd[0] + kxx * seed[0] + kxy * seed[1]).abs() <= 1e-9 * kxx * 3e-6);
    assert!((dd[1] + kyx * seed[0] + kyy * seed[1]).abs() <= 1e-9 * kyy * 3e-6);
    let mut d = f64::NAN;
    let st = unsafe { raceway_get_output_derivative(c.0, RACEWAY_VR_FORCE_X, 1, &mut d) };
    assert_eq!(st, RacewayStatus::Ok);
    assert!(d.is_finite());
    let mut stats = RacewayStats::default();
    assert_eq!(
        unsafe { raceway_get_stats(c.0, &mut stats) },
        RacewayStatus::Ok
    );
    assert!(stats.rejected <= stats.accepted + stats.rejected);
}

#[test]
fn a_serialised_state_restores_and_the_run_continues_bit_for_bit() {
    let c = create();
    c.run(0, 2, 0.1, 2e-4);
    let bytes = c.state_bytes();
    let t = c.time();
    let first = c.run(2, 4, 0.1, 2e-4);
    // Restore in the same instance.
    assert_eq!(c.restore_bytes(&bytes), RacewayStatus::Ok, "{}", c.msg());
    assert_eq!(c.time(), t);
    let again = c.run(2, 4, 0.1, 2e-4);
    assert_eq!(bits(&first), bits(&again));
    // And in a fresh instance of the same scene (another "process").
    let d = create();
    assert_eq!(d.restore_bytes(&bytes), RacewayStatus::Ok, "{}", d.msg());
    assert_eq!(bits(&d.run(2, 4, 0.1, 2e-4)), bits(&first));
    // A state handle reused in place, and set directly.
    let mut s: *mut RacewayState = null_mut();
    assert_eq!(unsafe { raceway_state_get(c.0, &mut s) }, RacewayStatus::Ok);
    let kept = s;
    c.run(6, 1, 0.1, 2e-4);
    assert_eq!(unsafe { raceway_state_get(c.0, &mut s) }, RacewayStatus::Ok);
    assert_eq!(s, kept, "overwritten in place");
    let before = c.outputs();
    c.run(7, 2, 0.1, 2e-4);
    assert_eq!(unsafe { raceway_state_set(c.0, s) }, RacewayStatus::Ok);
    assert_eq!(bits(&c.outputs()), bits(&before));
    unsafe { raceway_state_free(s) };
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Creation refusals: NULL, the message names the cause.
#[test]
fn bad_scenes_are_refused_with_a_message_naming_the_cause() {
    let cases: [(&[u8], &[&str]); 6] = [
        (b"bearing = ", &["1:11: TOML syntax"]),
        (
            b"bearing = \"6205\"\nspeed = 3\n",
            &["2:1: `speed`: unknown key `speed`"],
        ),
        (
            b"bearing = \"6205\"\n[solver]\nrtol = 5.0\n",
            &["solver.rtol", "5"],
        ),
        (
            b"bearing = \"6205\"\n[inputs]\ninitial = { \"shaft.q\" = 1.0 }\n",
            &["shaft.q"],
        ),
        (
            b"bearing = \"6205\"\n[inputs]\ninitial = { \"force.x\" = 1.0 }\n",
            &["inputs.initial.force.x"],
        ),
        (
            b"title = \"\xff\"\nbearing = \"6205\"\n",
            &["not UTF-8", "8"],
        ),
    ];
    for (text, words) in cases {
        let e = try_create(text).err().expect("refused");
        for w in words {
            assert!(e.contains(w), "`{e}` lacks `{w}`");
        }
        assert!(e.starts_with("raceway_create: "), "{e}");
    }
    // NULL scene; a NULL error buffer is allowed; a short buffer truncates.
    let mut err = [1 as c_char; 8];
    assert!(unsafe { raceway_create(null(), err.as_mut_ptr(), 8) }.is_null());
    assert_eq!(
        unsafe { CStr::from_ptr(err.as_ptr()) }.to_bytes(),
        b"raceway"
    );
    let bad = CString::new("bearing = ").unwrap();
    assert!(unsafe { raceway_create(bad.as_ptr(), null_mut(), 0) }.is_null());
    unsafe { raceway_free(null_mut()) };
    unsafe { raceway_state_free(null_mut()) };
}

/// Each bad call is refused with its status and a message naming the cause, and the
/// instance that saw all of them ends bit for bit where an instance given only the good
/// calls ends.
#[test]
fn bad_calls_are_refused_by_name_and_leave_the_instance_unharmed() {
    let good = create();
    let bad = create();
    let h = 1e-4;

    good.run(0, 2, 0.2, h);
    bad.run(0, 2, 0.2, h);
    let t = bad.time();

    type Case<'a> = (
        &'a str,
        Box<dyn Fn(&Inst) -> RacewayStatus>,
        RacewayStatus,
        &'a [&'a str],
    );
    let cases: Vec<Case> = vec![
        (
            "NaN input",
            Box::new(|c| unsafe { raceway_set_real(c.0, RACEWAY_VR_SHAFT_X, f64::NAN) }),
            RacewayStatus::InvalidArgument,
            &["shaft.x", "NaN", "finite"],
        ),
        (
            "infinite input",
            Box::new(|c| unsafe { raceway_set_real(c.0, RACEWAY_VR_SHAFT_OMEGA, f64::INFINITY) }),
            RacewayStatus::InvalidArgument,
            &["shaft.omega", "inf"],
        ),
        (
            "unknown value reference",
            Box::new(|c| unsafe { raceway_set_real(c.0, 9999, 1.0) }),
            RacewayStatus::InvalidArgument,
            &["value reference", "9999"],
        ),
        (
            "writing an output",
            Box::new(|c| unsafe { raceway_set_real(c.0, RACEWAY_VR_FORCE_X, 1.0) }),
            RacewayStatus::CallOrder,
            &["force.x", "not an input"],
        ),
        (
            "bulk set with one bad value: nothing set",
            Box::new(|c| {
                let vrs = [RACEWAY_VR_SHAFT_X, RACEWAY_VR_SHAFT_Y, RACEWAY_VR_SHAFT_VX];
                let vals = [5e-6, 7e-6, f64::NEG_INFINITY];
                unsafe { raceway_set_reals(c.0, vrs.as_ptr(), vals.as_ptr(), 3) }
            }),
            RacewayStatus::InvalidArgument,
            &["values[2]", "shaft.vx", "-inf"],
        ),
        (
            "bulk set with NULL values",
            Box::new(|c| unsafe { raceway_set_reals(c.0, MOTION.as_ptr(), null(), 11) }),
            RacewayStatus::NullPointer,
            &["values", "NULL"],
        ),
        (
            "derivative order out of range",
            Box::new(|c| unsafe { raceway_set_input_derivative(c.0, RACEWAY_VR_SHAFT_X, 4, 1.0) }),
            RacewayStatus::InvalidArgument,
            &["order", "4"],
        ),
        (
            "NaN derivative",
            Box::new(|c| unsafe {
                raceway_set_input_derivative(c.0, RACEWAY_VR_SHAFT_Y, 1, f64::NAN)
            }),
            RacewayStatus::InvalidArgument,
            &["shaft.y", "NaN"],
        ),
        (
            "zero h",
            Box::new(move |c| unsafe { raceway_do_step(c.0, t, 0.0) }),
            RacewayStatus::InvalidArgument,
            &["`h` = 0", "> 0"],
        ),
        (
            "negative h",
            Box::new(move |c| unsafe { raceway_do_step(c.0, t, -1e-4) }),
            RacewayStatus::InvalidArgument,
            &["`h` = -0.0001"],
        ),
        (
            "NaN h",
            Box::new(move |c| unsafe { raceway_do_step(c.0, t, f64::NAN) }),
            RacewayStatus::InvalidArgument,
            &["`h` = NaN"],
        ),
        (
            "time running backwards",
            Box::new(move |c| unsafe { raceway_do_step(c.0, t - 1e-4, 1e-4) }),
            RacewayStatus::CallOrder,
            &["do_step", "backwards"],
        ),
        (
            "time jumping forward",
            Box::new(move |c| unsafe { raceway_do_step(c.0, t + 1.0, 1e-4) }),
            RacewayStatus::CallOrder,
            &["jump"],
        ),
        (
            "NULL out-pointer",
            Box::new(|c| unsafe { raceway_get_real(c.0, RACEWAY_VR_FORCE_X, null_mut()) }),
            RacewayStatus::NullPointer,
            &["`value` is NULL"],
        ),
        (
            "bulk get with an unknown reference: nothing written",
            Box::new(|c| {
                let vrs = [RACEWAY_VR_FORCE_X, 12345];
                let mut out = [7.0; 2];
                let st = unsafe { raceway_get_reals(c.0, vrs.as_ptr(), out.as_mut_ptr(), 2) };
                assert_eq!(out, [7.0; 2]);
                st
            }),
            RacewayStatus::InvalidArgument,
            &["vrs[1] = 12345"],
        ),
        (
            "derivative of an input",
            Box::new(|c| {
                let mut d = 0.0;
                unsafe { raceway_get_output_derivative(c.0, RACEWAY_VR_SHAFT_X, 1, &mut d) }
            }),
            RacewayStatus::InvalidArgument,
            &["an output"],
        ),
        (
            "directional derivative with a NaN seed",
            Box::new(|c| {
                let (u, k, s) = ([RACEWAY_VR_FORCE_X], [RACEWAY_VR_SHAFT_X], [f64::NAN]);
                let mut o = [0.0];
                unsafe {
                    raceway_directional_derivative(
                        c.0,
                        u.as_ptr(),
                        1,
                        k.as_ptr(),
                        1,
                        s.as_ptr(),
                        o.as_mut_ptr(),
                    )
                }
            }),
            RacewayStatus::InvalidArgument,
            &["seed", "NaN"],
        ),
        (
            "serialise into a short buffer",
            Box::new(|c| unsafe {
                let mut s: *mut RacewayState = null_mut();
                assert_eq!(raceway_state_get(c.0, &mut s), RacewayStatus::Ok);
                let mut buf = [0u8; 16];
                let st = raceway_state_serialize(c.0, s, buf.as_mut_ptr(), 16);
                raceway_state_free(s);
                st
            }),
            RacewayStatus::BufferTooSmall,
            &["16 bytes", "needs"],
        ),
        (
            "truncated state bytes",
            Box::new(|c| {
                let b = c.state_bytes();
                c.restore_bytes(&b[..b.len() - 3])
            }),
            RacewayStatus::InvalidArgument,
            &["serialised state"],
        ),
        (
            "damaged magic",
            Box::new(|c| {
                let mut b = c.state_bytes();
                b[0] = b'X';
                c.restore_bytes(&b)
            }),
            RacewayStatus::InvalidArgument,
            &["magic"],
        ),
        (
            "NULL state",
            Box::new(|c| unsafe { raceway_state_set(c.0, null()) }),
            RacewayStatus::NullPointer,
            &["state"],
        ),
    ];
    for (what, call, status, words) in &cases {
        assert_eq!(call(&bad), *status, "{what}: {}", bad.msg());
        let m = bad.msg();
        for w in *words {
            assert!(m.contains(w), "{what}: `{m}` lacks `{w}`");
        }
        // Still usable: a read works, the time has not moved.
        assert_eq!(bad.time(), t, "{what}");
    }

    // A state of another scene, refused by the other instance, with the cause named.
    let other = try_create(b"bearing = \"6205\"\ntitle = \"other\"\n").unwrap();
    assert_eq!(
        other.restore_bytes(&bad.state_bytes()),
        RacewayStatus::CallOrder
    );
    assert!(other.msg().contains("another scene"), "{}", other.msg());

    // NULL instance.
    assert_eq!(
        unsafe { raceway_do_step(null_mut(), 0.0, 1e-3) },
        RacewayStatus::NullPointer
    );
    assert!(unsafe { CStr::from_ptr(raceway_last_error(null())) }
        .to_str()
        .unwrap()
        .contains("NULL"));

    // After every refusal, the bad instance continues exactly like the good one.
    let a = good.run(2, 3, 0.2, h);
    let b = bad.run(2, 3, 0.2, h);
    assert_eq!(bits(&a), bits(&b));
}

#[test]
fn variable_lookup_walks_the_table_both_ways() {
    let n = raceway_variable_count();
    assert_eq!(n, RACEWAY_VARIABLE_COUNT);
    for i in 0..n {
        let mut vr = u32::MAX;
        assert_eq!(
            unsafe { raceway_variable_at(i, &mut vr) },
            RacewayStatus::Ok
        );
        let name = unsafe { CStr::from_ptr(raceway_variable_name(vr)) };
        let mut back = u32::MAX;
        let st = unsafe { raceway_variable_vr(name.as_ptr(), &mut back) };
        assert_eq!(st, RacewayStatus::Ok);
        assert_eq!(back, vr, "{name:?}");
        let v = raceway::component::variables::by_vr(vr).unwrap();
        let unit = unsafe { CStr::from_ptr(raceway_variable_unit(vr)) };
        assert_eq!(unit.to_str().unwrap(), v.unit);
        assert!(!raceway_variable_description(vr).is_null());
    }
    let mut vr = 0;
    assert_eq!(
        unsafe { raceway_variable_at(n, &mut vr) },
        RacewayStatus::InvalidArgument
    );
    let unknown = CString::new("force.w").unwrap();
    assert_eq!(
        unsafe { raceway_variable_vr(unknown.as_ptr(), &mut vr) },
        RacewayStatus::InvalidArgument
    );
    assert_eq!(
        unsafe { raceway_variable_vr(null(), &mut vr) },
        RacewayStatus::NullPointer
    );
    assert!(raceway_variable_name(4242).is_null());
    assert_eq!(
        unsafe { CStr::from_ptr(raceway_version()) }
            .to_str()
            .unwrap(),
        env!("CARGO_PKG_VERSION")
    );
    let scene = unsafe { CStr::from_ptr(raceway_default_scene()) };
    assert_eq!(scene.to_str().unwrap(), SCENE);
}

/// Many instances in one process on several threads give exactly the results of a
/// single-threaded run.
#[test]
fn instances_on_several_threads_match_a_single_threaded_run() {
    const THREADS: usize = 4;
    const PER_THREAD: usize = 3;
    let job = |id: usize| -> Vec<Vec<f64>> {
        // Several instances alive at once, stepped interleaved.
        let insts: Vec<Inst> = (0..PER_THREAD).map(|_| create()).collect();
        let mut out = vec![Vec::new(); PER_THREAD];
        for k in 0..40 {
            for (j, c) in insts.iter().enumerate() {
                let seed = (id * PER_THREAD + j) as f64 * 0.37;
                out[j].extend(c.run(k, 1, seed, 5e-5));
            }
        }
        out
    };
    let serial: Vec<_> = (0..THREADS).map(job).collect();
    let parallel: Vec<_> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..THREADS).map(|id| s.spawn(move || job(id))).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for (a, b) in serial.iter().zip(&parallel) {
        for (x, y) in a.iter().zip(b) {
            assert_eq!(bits(x), bits(y));
        }
    }
    // The runs differ from one another (the comparison is not vacuous).
    assert_ne!(bits(&serial[0][0]), bits(&serial[1][0]));
}

/// Handles are checked: double free, use after free, a made-up handle and a state handle
/// given where an instance is expected are refused with a status, never dereferenced.
#[test]
fn freed_foreign_and_doubly_freed_handles_are_refused() {
    let c = create();
    c.run(0, 1, 0.3, 1e-4);
    let raw = c.0;
    let mut s: *mut RacewayState = null_mut();
    assert_eq!(unsafe { raceway_state_get(raw, &mut s) }, RacewayStatus::Ok);
    drop(c); // raceway_free
    let mut t = 0.0;
    unsafe {
        // Use after free.
        assert_eq!(
            raceway_do_step(raw, 1e-4, 1e-4),
            RacewayStatus::InvalidHandle
        );
        assert_eq!(raceway_get_time(raw, &mut t), RacewayStatus::InvalidHandle);
        assert_eq!(raceway_state_set(raw, s), RacewayStatus::InvalidHandle);
        let msg = CStr::from_ptr(raceway_last_error(raw)).to_str().unwrap();
        assert!(msg.contains("not a live instance"), "{msg}");
        // Double free: ignored, no abort.
        raceway_free(raw);
        // Made-up handles, and a state handle where an instance is expected.
        for fake in [8usize, 0x10_0010 * 1000, s as usize] {
            let f = fake as *mut RacewayComponent;
            assert_eq!(raceway_do_step(f, 0.0, 1e-4), RacewayStatus::InvalidHandle);
            raceway_free(f);
        }
    }
    // The state outlives its instance; freeing it twice is ignored; a freed state is
    // refused by a live instance.
    let d = create();
    assert_eq!(unsafe { raceway_state_set(d.0, s) }, RacewayStatus::Ok);
    unsafe { raceway_state_free(s) };
    unsafe { raceway_state_free(s) };
    assert_eq!(
        unsafe { raceway_state_set(d.0, s) },
        RacewayStatus::InvalidHandle
    );
    assert!(
        d.msg().contains("`state` is not a live handle"),
        "{}",
        d.msg()
    );
    let mut n = 0usize;
    assert_eq!(
        unsafe { raceway_state_size(d.0, s, &mut n) },
        RacewayStatus::InvalidHandle
    );
    // An instance handle where a state is expected.
    assert_eq!(
        unsafe { raceway_state_set(d.0, d.0 as *const RacewayState) },
        RacewayStatus::InvalidHandle
    );
    // A state handle overwritten in place must be live.
    let mut stale = s;
    assert_eq!(
        unsafe { raceway_state_get(d.0, &mut stale) },
        RacewayStatus::InvalidHandle
    );
    // The instance is unharmed.
    d.run(1, 1, 0.3, 1e-4);
}

/// Damaged state bytes are refused with a message and never read: every single-byte
/// change, every truncation, and a NaN written into number slots of a real state.
#[test]
fn damaged_state_bytes_are_refused_and_the_instance_is_unchanged() {
    let c = create();
    c.run(0, 2, 0.4, 1e-4);
    let bytes = c.state_bytes();
    let before = bits(&c.outputs());
    let mut refused = 0;
    for i in (0..bytes.len()).step_by(7) {
        let mut bad = bytes.clone();
        bad[i] ^= 0x20;
        let st = c.restore_bytes(&bad);
        assert_ne!(st, RacewayStatus::Ok, "flip at byte {i} of {}", bytes.len());
        assert!(!c.msg().is_empty());
        refused += 1;
    }
    for n in [0, 3, 8, 40, bytes.len() / 2, bytes.len() - 1] {
        assert_eq!(c.restore_bytes(&bytes[..n]), RacewayStatus::InvalidArgument);
        assert!(c.msg().contains("serialised state"), "{}", c.msg());
    }
    assert!(refused > 100);
    assert_eq!(bits(&c.outputs()), before, "nothing restored");
    assert_eq!(c.restore_bytes(&bytes), RacewayStatus::Ok);
}

/// Child half of `state_bytes_restore_in_another_process_bit_for_bit`: runs only when the
/// parent sets `RACEWAY_STATE_CHILD` to a folder.
#[test]
fn state_bytes_child_process() {
    let Some(dir) = cross_process::child_dir("RACEWAY_STATE_CHILD") else {
        return;
    };
    let c = create();
    c.run(0, 3, 0.7, 1e-4);
    cross_process::write_child(&dir, &c.state_bytes(), &bits(&c.run(3, 5, 0.7, 1e-4)));
}

/// Bytes written by one process restore in another, and the run continues bit for bit.
#[test]
fn state_bytes_restore_in_another_process_bit_for_bit() {
    let (bytes, theirs) = cross_process::run_child(
        "state_bytes_child_process",
        "RACEWAY_STATE_CHILD",
        "raceway-xproc",
    );
    let c = create();
    assert_eq!(c.restore_bytes(&bytes), RacewayStatus::Ok, "{}", c.msg());
    let ours = bits(&c.run(3, 5, 0.7, 1e-4));
    assert_eq!(ours.len(), 5 * OUTPUTS.len());
    assert_eq!(ours, theirs);
}

/// Counts are Integer variables: `raceway_variable_type` says so, `raceway_get_integer`
/// gives exactly what `raceway_get_real` gives, and refuses a Real variable by name.
#[test]
fn counts_read_as_integers_and_reals_are_refused_there() {
    let mut ty = RacewayType::Real;
    assert_eq!(
        unsafe { raceway_variable_type(RACEWAY_VR_BALLS_LOADED, &mut ty) },
        RacewayStatus::Ok
    );
    assert_eq!(ty, RacewayType::Integer);
    assert_eq!(
        unsafe { raceway_variable_type(RACEWAY_VR_FORCE_Y, &mut ty) },
        RacewayStatus::Ok
    );
    assert_eq!(ty, RacewayType::Real);
    assert_eq!(
        unsafe { raceway_variable_type(99_999, &mut ty) },
        RacewayStatus::InvalidArgument
    );
    let c = create();
    c.set_motion(0, 0.0);
    let mut n = -1i32;
    assert_eq!(
        unsafe { raceway_get_integer(c.0, RACEWAY_VR_BALLS_LOADED, &mut n) },
        RacewayStatus::Ok
    );
    // the default scene's shaft is pushed down: some but not all of the 9 balls carry it
    assert!((1..9).contains(&n), "{n}");
    assert_eq!(n as f64, c.get(RACEWAY_VR_BALLS_LOADED));
    let mut w = -1i32;
    assert_eq!(
        unsafe { raceway_get_integer(c.0, RACEWAY_VR_WARNINGS_ACTIVE, &mut w) },
        RacewayStatus::Ok
    );
    assert_eq!(w as f64, c.get(RACEWAY_VR_WARNINGS_ACTIVE));
    assert_eq!(
        unsafe { raceway_get_integer(c.0, RACEWAY_VR_FORCE_Y, &mut n) },
        RacewayStatus::InvalidArgument
    );
    assert!(c.msg().contains("an Integer output"), "{}", c.msg());
}

#[path = "common/cli_rows.rs"]
mod cli_rows;

/// One rule for unset inputs: an instance of the default scene stepped through the C ABI
/// without a `raceway_set_real` holds the scene's initial values, so its force at t = 0
/// and after one step equals the first two rows of `raceway run`.
#[test]
fn unset_inputs_hold_the_scenes_initial_values_as_the_cli_does() {
    let cli = cli_rows::default_scene_first_rows();
    let c = create();
    let force = |c: &Inst| {
        [RACEWAY_VR_FORCE_X, RACEWAY_VR_FORCE_Y].map(|vr| {
            let mut v = f64::NAN;
            assert_eq!(
                unsafe { raceway_get_real(c.0, vr, &mut v) },
                RacewayStatus::Ok
            );
            v
        })
    };
    let at0 = force(&c);
    assert_eq!(c.step(0.0, 1e-4), RacewayStatus::Ok, "{}", c.msg());
    let at1 = force(&c);
    for (got, want) in [at0, at1].iter().zip(&cli) {
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g - w).abs() <= 1e-9 * cli[0][1].abs(),
                "{got:?} vs the CLI's {want:?}"
            );
        }
    }
}

/// A refused scene's message through the C ABI is `raceway scene --check`'s: every problem
/// with its line:column and the nearest known name (the `error` buffer of `raceway_create`:
/// a refused scene makes no instance whose `raceway_last_error` could carry it).
#[test]
fn a_refused_scene_carries_line_column_and_suggestions() {
    let typo = "bearing = \"6205\"\n[model]\nlevl = \"ring\"\n[solver]\nrtol = 0.5\n";
    let m = try_create(typo.as_bytes()).err().unwrap();
    assert!(m.starts_with("raceway_create: scene: 2 problem(s)"), "{m}");
    assert!(
        m.contains("3:1: `model.levl`: unknown key `levl`; did you mean `level`?"),
        "{m}"
    );
    assert!(m.contains("5:8: `solver.rtol`: 0.5 is outside"), "{m}");
    let old = "bearing = \"6205\"\n[inputs]\ninitial = { \"shaft.omega\" = 183.26 }\n";
    let m = try_create(old.as_bytes()).err().unwrap();
    assert!(m.contains("3:13: `inputs.initial.shaft.omega`"), "{m}");
    assert!(m.contains("`speed_rpm = 1750.0041`"), "{m}");
}
