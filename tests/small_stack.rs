//! The stack a host thread must give an instance, and scene texts nested deeply enough to
//! overflow a small stack inside the parsers (issue #38, item 1).
//!
//! Before the nesting check, a 1.4 kB scene of TOML inline tables nested 45 deep overflowed
//! a 64 KiB thread inside `raceway_create` and killed the host (SIGSEGV): this test binary
//! died. Now every such text is refused with its line and column, and a whole
//! create–step–read cycle of the default scene runs on a thread of [`PROMISED_KIB`].
//! The FMI part runs with `--features fmi` (`scripts/test.d/35-props-fmi.sh`).

use raceway::capi::*;
use std::ffi::{CStr, CString};

#[path = "common/motion.rs"]
mod motion;
use motion::MOTION;

/// The smallest thread stack the project promises an instance for a whole
/// create–step–read cycle (docs/reliability.md). 32 KiB is not enough for it (measured:
/// the cycle overflows 32 KiB in the release and the test build).
const PROMISED_KIB: usize = 64;
/// Any scene text, however nested, is refused or accepted on a stack this small.
const PARSE_KIB: usize = 32;

/// Run `f` on a thread with a stack of `kib` KiB; a stack overflow aborts this process.
fn on_stack<T: Send + 'static>(kib: usize, f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(kib * 1024)
        .spawn(f)
        .expect("thread")
        .join()
        .expect("no panic")
}

/// The texts of the misuse campaign, each nested past the limit.
fn nested_texts() -> Vec<(&'static str, String)> {
    let inline = format!("x = {}1{}\n", "{ a = ".repeat(45), " }".repeat(45));
    let arrays = format!("x = {}1{}\n", "[".repeat(60), "]".repeat(60));
    let json = format!("{}1{}", "{\"a\": ".repeat(85), "}".repeat(85));
    let header = format!("[{}]\n", vec!["a"; 100_000].join("."));
    let dotted = format!("{} = 1\n", vec!["k"; 1_000].join("."));
    let deep_json_arrays = format!("{{\"x\": {}1{}}}", "[".repeat(100_000), "]".repeat(100_000));
    vec![
        ("inline tables 45 deep", inline),
        ("arrays 60 deep", arrays),
        ("JSON objects 85 deep", json),
        ("a header of 100 000 parts", header),
        ("a key of 1 000 parts", dotted),
        ("JSON arrays 100 000 deep", deep_json_arrays),
    ]
}

fn create(text: &str) -> Result<*mut RacewayComponent, String> {
    let c_text = CString::new(text).unwrap();
    let mut err = vec![0 as std::ffi::c_char; 512];
    let c = unsafe { raceway_create(c_text.as_ptr(), err.as_mut_ptr(), err.len()) };
    if c.is_null() {
        Err(unsafe { CStr::from_ptr(err.as_ptr()) }
            .to_string_lossy()
            .into_owned())
    } else {
        Ok(c)
    }
}

/// The deepest nesting the check lets through, at the places a parser walks deepest, is
/// refused or accepted on 56 KiB: the promised stack less 8 KiB for the host's own frames.
/// Found by the fuzzer (issue #38): `bearing` as 31 inline tables (the limit was 32) took
/// 60 KiB and overflowed its 64 KiB thread.
#[test]
fn the_deepest_nesting_allowed_fits_the_promised_stack() {
    let n = raceway::nesting::MAX_NESTING;
    let base = raceway::component::scene::DEFAULT_SCENE;
    let nest = |v: &str| format!("{}{v}{}", "{ x = ".repeat(n), " }".repeat(n));
    let texts = [
        base.replacen(
            "bearing = \"6205\"",
            &format!("bearing = {}", nest("\"6205\"")),
            1,
        ),
        base.replacen("bearing = \"6205\"", &format!("bearing = {}", nest("1")), 1),
        format!(
            "{base}\n[run]\nstep_s = {}\n",
            nest("1e-4").replacen("{ x = ", "", 1).replacen(" }", "", 1)
        ),
        format!(
            "{base}\n[model]\nx = {}1{}\n",
            "[".repeat(n - 1),
            "]".repeat(n - 1)
        ),
    ];
    for text in texts {
        let deeper = format!("a = {}1{}\n{text}", "[".repeat(n + 1), "]".repeat(n + 1));
        let msg = on_stack(PROMISED_KIB - 8, move || create(&text).err());
        let msg = msg.expect("a scene with an unknown nested field is refused");
        assert!(!msg.contains("nested"), "{msg}");
        let msg = on_stack(PARSE_KIB, move || create(&deeper).err()).unwrap();
        assert!(msg.contains("nested 17 levels deep at line 1"), "{msg}");
    }
}

#[test]
fn nested_scenes_are_refused_on_a_small_stack_with_their_place() {
    for (what, text) in nested_texts() {
        let msg = on_stack(PARSE_KIB, move || create(&text).err());
        let msg = msg.unwrap_or_else(|| panic!("{what}: accepted"));
        assert!(
            msg.contains("nested") && msg.contains("line 1, column"),
            "{what}: {msg}"
        );
    }
    // `scene --check` and the scene parser say the same, with the place.
    for (what, text) in nested_texts() {
        let problems = on_stack(PARSE_KIB, move || raceway::component::schema::check(&text));
        assert_eq!(problems.len(), 1, "{what}");
        assert_eq!(problems[0].line_col.map(|(l, _)| l), Some(1), "{what}");
    }
}

/// A whole cycle on the promised stack: create from the default scene, set the motion,
/// step, read the forces; the same numbers as on the main thread.
#[test]
fn the_default_scene_runs_on_the_promised_stack() {
    fn cycle() -> Vec<f64> {
        let c = create(raceway::component::scene::DEFAULT_SCENE).expect("created");
        let mut out = Vec::new();
        unsafe {
            for &vr in &MOTION {
                assert_eq!(raceway_set_real(c, vr, 0.0), RacewayStatus::Ok);
            }
            assert_eq!(
                raceway_set_real(c, RACEWAY_VR_SHAFT_Y, -5e-6),
                RacewayStatus::Ok
            );
            assert_eq!(
                raceway_set_real(c, RACEWAY_VR_SHAFT_OMEGA, 183.0),
                RacewayStatus::Ok
            );
            for k in 0..20 {
                assert_eq!(raceway_do_step(c, k as f64 * 1e-4, 1e-4), RacewayStatus::Ok);
                let mut fy = 0.0;
                assert_eq!(
                    raceway_get_real(c, RACEWAY_VR_FORCE_Y, &mut fy),
                    RacewayStatus::Ok
                );
                out.push(fy);
            }
            raceway_free(c);
        }
        out
    }
    let small = on_stack(PROMISED_KIB, cycle);
    let main = cycle();
    assert_eq!(small, main);
    assert!(small.iter().all(|f| f.is_finite() && *f > 0.0), "{small:?}");
}

#[cfg(feature = "fmi")]
#[path = "common/fmi_callbacks.rs"]
mod fmi_callbacks;

#[cfg(feature = "fmi")]
#[test]
fn an_fmu_refuses_a_nested_scene_on_a_small_stack() {
    use raceway::fmi::fmi2::*;
    use raceway::fmi::{Status, GUID};
    for (what, text) in nested_texts() {
        let status = on_stack(PARSE_KIB, move || unsafe {
            let name = CString::new("nested").unwrap();
            let guid = CString::new(GUID).unwrap();
            let c = fmi2Instantiate(
                name.as_ptr(),
                1,
                guid.as_ptr(),
                std::ptr::null(),
                fmi_callbacks::callbacks(),
                0,
                0,
            );
            assert!(!c.is_null());
            let scene = CString::new(text).unwrap();
            let p = scene.as_ptr();
            let vr = 1000u32; // the `scene` parameter
            let set = fmi2SetString(c, &vr, 1, &p);
            assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), Status::Ok);
            assert_eq!(fmi2EnterInitializationMode(c), Status::Ok);
            let exit = fmi2ExitInitializationMode(c);
            fmi2FreeInstance(c);
            (set, exit)
        });
        assert!(
            status.0 == Status::Error || status.1 == Status::Error,
            "{what}: {status:?}"
        );
    }
}
