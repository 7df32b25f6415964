//! Issue 21: inputs no bearing can have are refused at the door, every step has a work
//! budget, time checks are absolute, tiny inputs work at the quasi-static level, scene
//! tables are never read from lists, and every message names the field, the value and
//! the allowed range. The hang reproducers of the issue's misuse campaign are rebuilt here
//! from its description; each must answer in a few seconds with a clear error.

use raceway::component::{variables, Component};
use raceway::error::Error;
use std::time::Instant;

const FULL_7004: &str = include_str!("../examples/scenes/7004-60000.toml");
/// The default scene (6205, quasi-static, 1750 rpm, 10 µm down) with every input set.
const DEFAULT: &str = r#"bearing = "6205"
[model]
level = "quasi_static"
[inputs]
speed_rpm = 1750.0
initial = { "shaft.x" = 0.0, "shaft.y" = -10e-6, "shaft.z" = 0.0, "shaft.rx" = 0.0, "shaft.ry" = 0.0, "shaft.vx" = 0.0, "shaft.vy" = 0.0, "shaft.vz" = 0.0, "shaft.wx" = 0.0, "shaft.wy" = 0.0 }
[run]
duration_s = 1.0
step_s = 1e-4
"#;

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

/// The 7004 full-level scene with one text substitution (which must apply).
fn full_with(from: &str, to: &str) -> String {
    assert!(FULL_7004.contains(from), "{from}");
    FULL_7004.replacen(from, to, 1)
}

/// Create from `text` and run 2 ms in steps of 0.1 ms (the campaign's `--duration 0.002`),
/// stopping at the first error; the whole attempt must answer within `secs` of wall time
/// (generous: the machine is shared) and an error must name `names`.
fn answers_quickly(text: &str, names: &[&str]) -> Result<(), Error> {
    let t0 = Instant::now();
    let r: Result<(), Error> = (|| {
        let mut c = Component::from_text(text)?;
        for i in 0..20 {
            c.do_step(i as f64 * 1e-4, 1e-4)?;
        }
        Ok(())
    })();
    let wall = t0.elapsed().as_secs_f64();
    assert!(wall < 30.0, "took {wall} s");
    if let Err(e) = &r {
        let m = e.to_string();
        for n in names {
            assert!(m.contains(n), "{m} (expected to name {n})");
        }
    }
    r
}

#[test]
fn full_level_hang_reproducers_are_refused_at_the_door() {
    let y0 = "\"shaft.y\" = -3.072348e-6";
    let z0 = "\"shaft.z\" = 4.331157e-5";
    for (from, to, field) in [
        (
            "\"shaft.x\" = 0.0",
            "\"shaft.x\" = -1.0",
            "inputs.initial.shaft.x",
        ),
        (y0, "\"shaft.y\" = 9.2e18", "inputs.initial.shaft.y"),
        (y0, "\"shaft.y\" = -9.2e18", "inputs.initial.shaft.y"),
        (z0, "\"shaft.z\" = 43.6", "inputs.initial.shaft.z"),
        (z0, "\"shaft.z\" = -43.6", "inputs.initial.shaft.z"),
        (
            "\"shaft.rx\" = 0.0",
            "\"shaft.rx\" = 0.5",
            "inputs.initial.shaft.rx",
        ),
        (
            "speed_rpm = 60000.0",
            "speed_rpm = 1e10",
            "inputs.speed_rpm",
        ),
        ("v_s = 0.05", "v_s = 1e-300", "model.full.traction.v_s"),
    ] {
        let text = full_with(from, to);
        let e = answers_quickly(&text, &[field, "allowed"]).unwrap_err();
        assert!(matches!(e, Error::Invalid { .. }), "{e}");
    }
}

#[test]
fn a_7004_scene_without_shaft_rx_answers() {
    // The scene never sets shaft.rx: it holds 0, the rule for unset inputs.
    let text = full_with("\"shaft.rx\" = 0.0, ", "");
    if let Err(e) = answers_quickly(&text, &["shaft.rx"]) {
        panic!("{e}");
    }
}

#[test]
fn implausible_set_real_is_refused_and_changes_nothing() {
    let mut c = Component::from_text(&full_with("v_s = 0.05", "v_s = 0.05")).unwrap();
    c.do_step(0.0, 1e-4).unwrap();
    let before = c.get_state();
    let l = *c.limits();
    for (name, value) in [
        ("shaft.x", -1.0),
        ("shaft.y", 9.2e18),
        ("shaft.z", 43.6),
        ("shaft.ry", 1.5 * l.tilt),
        ("shaft.vz", -2.0 * l.speed),
        ("shaft.omega", 1.01 * l.omega),
        ("shaft.y", f64::MAX),
    ] {
        let m = c.set_real(vr(name), value).unwrap_err().to_string();
        assert!(m.contains(name) && m.contains("allowed"), "{m}");
        assert_eq!(
            c.get_state(),
            before,
            "{name} = {value} left the state unchanged"
        );
    }
    // Just inside is accepted.
    c.set_real(vr("shaft.z"), 0.99 * l.axial).unwrap();
}

#[test]
fn levels_agree_on_the_same_implausible_input() {
    // shaft.y = -1 mm gave 6e5 N at the ring level and an error at the quasi-static one.
    let mut messages = Vec::new();
    for level in ["linear", "quasi_static", "ring", "skidding", "full"] {
        let text = DEFAULT
            .replace("level = \"quasi_static\"", &format!("level = \"{level}\""))
            .replace("\"shaft.y\" = -10e-6", "\"shaft.y\" = -1e-3");
        let e = Component::from_text(&text).unwrap_err();
        let m = e.to_string();
        assert!(matches!(e, Error::Invalid { .. }), "{level}: {m}");
        assert!(m.contains("inputs.initial.shaft.y"), "{level}: {m}");
        messages.push(m);
    }
    assert!(messages.windows(2).all(|w| w[0] == w[1]), "{messages:?}");
}

#[test]
fn cpu_budget_stops_a_step_cleanly_and_says_how_to_raise_it() {
    let text = full_with("atol_m = 1e-9", "atol_m = 1e-9\nmax_step_cpu_s = 0.05");
    let mut c = Component::from_text(&text).unwrap();
    c.do_step(0.0, 1e-4).unwrap();
    let before = c.get_state();
    let t0 = Instant::now();
    // 20 ms of 60 000 rpm full dynamics in one step is far more than 0.05 s of CPU.
    let e = c.do_step(1e-4, 2e-2).unwrap_err();
    let wall = t0.elapsed().as_secs_f64();
    let m = e.to_string();
    assert!(matches!(e, Error::Budget { .. }), "{m}");
    assert!(
        m.contains("solver.max_step_cpu_s") && m.contains("raise"),
        "{m}"
    );
    assert_eq!(c.get_state(), before, "state as before the call");
    assert!(wall < 10.0, "stopped after {wall} s");
    // Still usable.
    c.do_step(1e-4, 1e-4).unwrap();
}

#[test]
fn the_time_check_is_absolute() {
    let mut c = Component::from_text(DEFAULT).unwrap();
    c.do_step(0.0, 1e-4).unwrap();
    let before = c.get_state();
    // A huge step no longer excuses a jump of 5 s.
    let m = c.do_step(5.0, 1e10).unwrap_err().to_string();
    assert!(m.contains("`h`") && m.contains("1e9"), "{m}");
    let m = c.do_step(5.0, 1.0).unwrap_err().to_string();
    assert!(m.contains("jump"), "{m}");
    // h = DBL_MAX names h and its range (not an internal angle).
    let m = c.do_step(1e-4, f64::MAX).unwrap_err().to_string();
    assert!(m.contains("`h`") && m.contains("<= 1e9"), "{m}");
    assert_eq!(c.get_state(), before);
    // A fresh component at t = 1e15: refused, not a step that leaves time where it was.
    let mut d = Component::from_text(DEFAULT).unwrap();
    let m = d.do_step(1e15, 1e-4).unwrap_err().to_string();
    assert!(m.contains("`t`"), "{m}");
    // t + h == t within the bound: refused with the least step that advances.
    let m = d.do_step(1e8, 1e-12).unwrap_err().to_string();
    assert!(m.contains("`h`") && m.contains("at least"), "{m}");
    // A long time that still resolves the step works and advances by h.
    d.do_step(1e6, 1e-4).unwrap();
    assert_eq!(d.time(), 1e6 + 1e-4);
}

#[test]
fn inputs_carried_off_by_their_velocity_are_refused() {
    let text = DEFAULT.replace("\"shaft.vy\" = 0.0", "\"shaft.vy\" = -1.0");
    let mut c = Component::from_text(&text).unwrap();
    c.do_step(0.0, 1e-6).unwrap();
    let before = c.get_state();
    // 1 m/s for 1 s carries the ring a metre: refused before integrating.
    let m = c.do_step(1e-6, 1.0).unwrap_err().to_string();
    assert!(m.contains("shaft.y at the step end"), "{m}");
    assert_eq!(c.get_state(), before);
}

#[test]
fn quasi_static_accepts_tiny_nonzero_inputs() {
    let reference = {
        let mut c = Component::from_text(DEFAULT).unwrap();
        c.do_step(0.0, 1e-4).unwrap();
        c.get_real(vr("force.y")).unwrap()
    };
    for name in [
        "shaft.z", "shaft.rx", "shaft.ry", "shaft.vz", "shaft.wx", "shaft.wy",
    ] {
        for v in [1e-300, -1e-300, 1e-200, -1e-150, 1e-100, -1e-100] {
            let text =
                DEFAULT.replace(&format!("\"{name}\" = 0.0"), &format!("\"{name}\" = {v:e}"));
            assert_ne!(text, DEFAULT);
            let mut c = Component::from_text(&text).unwrap_or_else(|e| panic!("{name} = {v}: {e}"));
            c.do_step(0.0, 1e-4)
                .unwrap_or_else(|e| panic!("{name} = {v}: {e}"));
            let fy = c.get_real(vr("force.y")).unwrap();
            // A displacement of 1e-100 m changes nothing a double can show.
            assert!(
                (fy - reference).abs() <= 1e-9 * reference.abs(),
                "{name} = {v}: {fy} vs {reference}"
            );
        }
    }
}

#[test]
fn vague_messages_now_name_field_value_and_range() {
    // A -1e6 N load at the quasi-static level (was "did not converge in 0 iterations").
    let qs_load = "bearing = \"6205\"\n[model]\nlevel = \"quasi_static\"\ncausality = \"load\"\n\
                   [inputs]\nspeed_rpm = 954.9296586\ninitial = { \"load.y\" = -1e6 }\n";
    let m = Component::from_text(qs_load).unwrap_err().to_string();
    assert!(
        m.contains("inputs.initial.load.y") && m.contains("N"),
        "{m}"
    );
    // A ramp of -1e308 rpm/s (was "invalid shaft.omega = NaN").
    let ramp = format!("{DEFAULT}speed_ramp_rpm_per_s = -1e308\n");
    let m = Component::from_text(&ramp).unwrap_err().to_string();
    assert!(
        m.contains("run.speed_ramp_rpm_per_s") && m.contains("rpm/s"),
        "{m}"
    );
    // atol_m = 5e-324 (was "step size underflow (h = 0e0)").
    let atol = DEFAULT.replace("[inputs]", "[solver]\natol_m = 5e-324\n[inputs]");
    let m = Component::from_text(&atol).unwrap_err().to_string();
    assert!(m.contains("solver.atol_m") && m.contains("1e-20"), "{m}");
    // An array for bearing.clearance_um names the key.
    let m = Component::from_text("bearing = { preset = \"6205\", clearance_um = [1.0] }\n")
        .unwrap_err()
        .to_string();
    assert!(m.contains("clearance_um") && m.contains("a number"), "{m}");
}

#[test]
fn lists_are_never_read_as_tables() {
    for (text, path) in [
        (
            "bearing = \"6205\"\nmodel = [\"ring\", \"load\"]\n".to_string(),
            "`model`",
        ),
        (
            "bearing = \"6205\"\n[model]\nfull = [\"coulomb\"]\n".to_string(),
            "`model.full`",
        ),
        (
            r#"{"bearing": "6205", "model": ["ring", "load"]}"#.to_string(),
            "`model`",
        ),
        (
            "bearing = \"6205\"\n[inputs]\ninitial = [1.0]\n".to_string(),
            "`inputs.initial`",
        ),
    ] {
        let m = Component::from_text(&text).unwrap_err().to_string();
        assert!(m.contains(path) && m.contains("a table"), "{m}");
    }
    // Lists where the scene has lists still work.
    let ok = format!(
        "{DEFAULT}\n[[effects.waviness]]\nrace = \"outer\"\norder = 9\namplitude_um = 0.1\n"
    );
    let ok = ok.replace("level = \"quasi_static\"", "level = \"ring\"");
    Component::from_text(&ok).unwrap();
    // No Rust type names.
    let m = Component::from_text("bearing = \"6205\"\nrun = 5\n")
        .unwrap_err()
        .to_string();
    assert!(!m.contains("RunSpec") && m.contains("a table"), "{m}");
}

/// The thread-stack need stated in docs/robustness.md: every level is created and stepped in
/// a thread of 64 KiB (32 KiB is not enough for every level: the linear level's creation
/// overflows it in the test build, the full level's step did in the issue's). A stack
/// overflow aborts the test binary; the line printed before names the level.
#[test]
fn every_level_runs_in_a_64_kib_thread_stack() {
    let ring = DEFAULT.replace("level = \"quasi_static\"", "level = \"ring\"");
    let linear = DEFAULT.replace("level = \"quasi_static\"", "level = \"linear\"");
    let skidding = DEFAULT.replace(
        "level = \"quasi_static\"",
        "level = \"skidding\"\n[model.skidding]\ntraction = { law = \"coulomb\", mu_max = 0.05, v_s = 0.05 }",
    );
    for (name, text, kib) in [
        ("linear", linear, 64),
        ("quasi_static", DEFAULT.to_string(), 64),
        ("ring", ring, 64),
        ("skidding", skidding, 64),
        ("full", FULL_7004.to_string(), 64),
    ] {
        eprintln!("{name} in {kib} KiB");
        let r = std::thread::Builder::new()
            .stack_size(kib * 1024)
            .spawn(move || -> Result<f64, String> {
                let mut c = Component::from_text(&text).map_err(|e| e.to_string())?;
                c.do_step(0.0, 1e-4).map_err(|e| e.to_string())?;
                c.get_real(vr("force.y")).map_err(|e| e.to_string())
            })
            .unwrap()
            .join()
            .unwrap();
        let fy = r.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(fy.is_finite(), "{name}");
    }
}

/// The numbers behind the budget's default and its cost (docs/robustness.md): the largest
/// thread CPU time of one communication step over the first 20 steps of every shipped
/// scene, and the cost of one clock read. A measurement, run on demand:
/// `cargo test --release --test robustness -- --ignored --nocapture`.
#[test]
#[ignore]
fn step_cpu_of_shipped_scenes() {
    use raceway::component::thread_cpu_s;
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let n = 1_000_000;
    let c0 = thread_cpu_s();
    let mut acc = 0.0;
    for _ in 0..n {
        acc += thread_cpu_s();
    }
    let per_read = (thread_cpu_s() - c0) / n as f64;
    assert!(acc > 0.0);
    println!("load average {}", load.trim());
    println!("clock read: {:.3} µs of thread CPU time", per_read * 1e6);
    let mut worst: (f64, String) = (0.0, String::new());
    let mut files: Vec<_> = std::fs::read_dir("examples/scenes")
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap();
        // Inputs the scene leaves out hold 0, as in `raceway run`.
        let mut c = Component::from_text(&text).unwrap();
        let h = c.scene().run.step_s;
        let mut most: f64 = 0.0;
        for i in 0..20 {
            let t0 = thread_cpu_s();
            c.do_step(i as f64 * h, h).unwrap();
            most = most.max(thread_cpu_s() - t0);
        }
        let s = c.stats();
        println!(
            "{:<32} step {h:e} s: most {:.4} s CPU per step; {:.2} µs CPU per rhs",
            path.file_name().unwrap().to_string_lossy(),
            most,
            1e6 * most / (s.rhs.max(1) as f64 / 20.0)
        );
        if most > worst.0 {
            worst = (most, path.display().to_string());
        }
    }
    println!("costliest step: {:.4} s ({})", worst.0, worst.1);
    assert!(
        worst.0 < raceway::component::scene::MAX_STEP_CPU_S / 10.0,
        "the default budget must be far above every shipped scene's step"
    );
}

/// The C ABI passes through the same doors: an implausible value is refused with
/// `InvalidArgument` (all or nothing for `set_reals`), a spent budget is `StepFailed`,
/// and the instance stays usable.
#[test]
fn c_abi_refuses_implausible_values_and_reports_the_budget() {
    use raceway::capi::*;
    use std::ffi::{CStr, CString};
    let text = CString::new(full_with(
        "atol_m = 1e-9",
        "atol_m = 1e-9\nmax_step_cpu_s = 0.05",
    ))
    .unwrap();
    let mut err = [0 as std::ffi::c_char; 512];
    // SAFETY: valid NUL-terminated scene and error buffer; the instance is freed below.
    let c = unsafe { raceway_create(text.as_ptr(), err.as_mut_ptr(), err.len()) };
    assert!(!c.is_null());
    let msg = || {
        unsafe { CStr::from_ptr(raceway_last_error(c)) }
            .to_string_lossy()
            .into_owned()
    };
    unsafe {
        assert_eq!(
            raceway_do_step(c, 0.0, 1e-4),
            RacewayStatus::Ok,
            "{}",
            msg()
        );
        let mut y0 = f64::NAN;
        assert_eq!(
            raceway_get_real(c, vr("shaft.y"), &mut y0),
            RacewayStatus::Ok
        );
        let st = raceway_set_real(c, vr("shaft.y"), -1e-3);
        assert_eq!(st, RacewayStatus::InvalidArgument);
        assert!(
            msg().contains("shaft.y") && msg().contains("allowed"),
            "{}",
            msg()
        );
        let vrs = [vr("shaft.y"), vr("shaft.x")];
        let vals = [-1e-6, 5.0];
        let st = raceway_set_reals(c, vrs.as_ptr(), vals.as_ptr(), 2);
        assert_eq!(st, RacewayStatus::InvalidArgument, "{}", msg());
        let mut y = f64::NAN;
        assert_eq!(
            raceway_get_real(c, vr("shaft.y"), &mut y),
            RacewayStatus::Ok
        );
        assert_eq!(y.to_bits(), y0.to_bits(), "nothing set");
        assert_eq!(raceway_do_step(c, 1e-4, 2e-2), RacewayStatus::StepFailed);
        assert!(msg().contains("solver.max_step_cpu_s"), "{}", msg());
        assert_eq!(
            raceway_do_step(c, 1e-4, 1e-4),
            RacewayStatus::Ok,
            "{}",
            msg()
        );
        raceway_free(c);
    }
}

/// A whole `raceway run` stops at its first step over budget with a clean error that names
/// the budget (exit status non-zero, no hang).
#[test]
fn a_run_stops_on_the_budget() {
    let dir = std::env::temp_dir().join(format!("raceway-budget-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("budget.toml");
    std::fs::write(
        &scene,
        full_with("atol_m = 1e-9", "atol_m = 1e-9\nmax_step_cpu_s = 1e-6"),
    )
    .unwrap();
    let t0 = Instant::now();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_raceway"))
        .args(["run", "-q", "--duration", "0.002", "--out"])
        .arg(dir.join("out"))
        .arg(&scene)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.contains("solver.max_step_cpu_s"), "{stderr}");
    assert!(t0.elapsed().as_secs_f64() < 30.0);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The load-driven static start under a light load (issue #38's unclear message, found by
/// the property tests with a load of 7.49e-3 N): the Newton step of a ring floating in its
/// clearance fell short of the contacts and the start failed naming no field. The dead
/// zone is now crossed by doubling the step (the 7008CE then starts), and a start that
/// still finds no equilibrium is refused naming the load field, with the loads in that
/// direction under which it found one, and model.start = "rest".
#[test]
fn a_light_load_starts_or_is_refused_naming_the_load() {
    let with_load = |file: &str, y: &str| {
        let path = format!("{}/examples/scenes/{file}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(path).unwrap();
        let start = text.find("\"load.y\" = ").unwrap() + 11;
        let end = start + text[start..].find([',', ' ', '}']).unwrap();
        let text = format!("{}{y}{}", &text[..start], &text[end..]);
        raceway::runner::prepare(&raceway::component::Scene::from_text(&text).unwrap())
    };
    for y in ["0.00749", "-0.00749", "-3e-5"] {
        with_load("7008ce-thermal.toml", y).unwrap_or_else(|e| panic!("{y}: {e}"));
    }
    let e = with_load("6205-ring2-radial.toml", "-3e-5")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`inputs.initial.load.y` = -3e-5")
            && e.contains("|load| <= ")
            && e.contains("|load| >= ")
            && e.contains("model.start = \"rest\""),
        "{e}"
    );
}
