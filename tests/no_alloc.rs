//! No heap allocation once running (a counting global allocator): `Component::do_step` on
//! every level, and the C coupling loop a host runs (issue #17): `raceway_set_reals`,
//! `raceway_do_step`, `raceway_get_reals`, `raceway_get_real` and `raceway_last_error`
//! after a clean call, at 10 kHz on the ring level reading 8 outputs each step; a roller
//! bearing's ring level (laminae) among the levels; a bearing set (the shipped 7008CE DB
//! pair: its rows' levels, per-row outputs, ratings and system life) rigid and with a
//! constant-force spring, at the quasi-static and the 5-DOF ring level, and with the
//! rows' thermal networks.

use raceway::capi::*;
use raceway::component::Component;
use std::ffi::{CStr, CString};
use std::ptr::null_mut;

#[path = "common/thread_alloc.rs"]
mod thread_alloc;

#[global_allocator]
static A: thread_alloc::Counting = thread_alloc::Counting;

fn allocations_in_steps(scene: &str, h: f64) -> usize {
    let mut c = Component::from_text(scene).unwrap();
    for i in 0..3 {
        c.do_step(i as f64 * h, h).unwrap();
    }
    let before = thread_alloc::allocations();
    for i in 3..50 {
        c.do_step(i as f64 * h, h).unwrap();
    }
    thread_alloc::allocations() - before
}

#[path = "common/motion.rs"]
mod motion;
use motion::MOTION;

const OUTPUTS: [u32; 8] = [
    RACEWAY_VR_FORCE_X,
    RACEWAY_VR_FORCE_Y,
    RACEWAY_VR_FORCE_Z,
    RACEWAY_VR_MOMENT_X,
    RACEWAY_VR_MOMENT_Y,
    RACEWAY_VR_TORQUE_Z,
    RACEWAY_VR_K_Y_Y,
    RACEWAY_VR_CAGE_OMEGA,
];

/// One step of the host loop: inputs, step, 8 outputs, one more output, the error text.
/// Returns the sum of the outputs (so the reads are used).
fn host_step(c: *mut RacewayComponent, k: usize, h: f64) -> f64 {
    let s = k as f64;
    let values = [
        1e-6 * (0.3 * s).sin(),
        -8e-6 + 1e-6 * (0.2 * s).cos(),
        0.0,
        0.0,
        0.0,
        3e-4 * (0.3 * s).cos(),
        -2e-4 * (0.2 * s).sin(),
        0.0,
        0.0,
        0.0,
        183.26,
    ];
    let mut out = [0.0; 8];
    let mut one = 0.0;
    unsafe {
        assert_eq!(
            raceway_set_reals(c, MOTION.as_ptr(), values.as_ptr(), MOTION.len()),
            RacewayStatus::Ok
        );
        assert_eq!(raceway_do_step(c, s * h, h), RacewayStatus::Ok);
        assert_eq!(
            raceway_get_reals(c, OUTPUTS.as_ptr(), out.as_mut_ptr(), out.len()),
            RacewayStatus::Ok
        );
        assert_eq!(
            raceway_get_real(c, RACEWAY_VR_FORCE_Y, &mut one),
            RacewayStatus::Ok
        );
        assert_eq!(*raceway_last_error(c), 0, "no error after a clean call");
    }
    out.iter().sum::<f64>() + one
}

/// Allocations in 195 steps of the C loop (after 5 warm-up steps).
fn allocations_in_the_c_loop() -> usize {
    let scene = CString::new(
        "bearing = \"6205\"\n[model]\nlevel = \"ring\"\n[inputs]\nspeed_rpm = 1750.004092\ninitial = { \"shaft.x\" = 0.0, \"shaft.y\" = -8e-6, \"shaft.z\" = 0.0, \"shaft.rx\" = 0.0, \"shaft.ry\" = 0.0, \"shaft.vx\" = 0.0, \"shaft.vy\" = 0.0, \"shaft.vz\" = 0.0, \"shaft.wx\" = 0.0, \"shaft.wy\" = 0.0 }\n",
    )
    .unwrap();
    let mut err = [0; 256];
    let c = unsafe { raceway_create(scene.as_ptr(), err.as_mut_ptr(), err.len()) };
    assert!(!c.is_null(), "{:?}", unsafe {
        CStr::from_ptr(err.as_ptr())
    });
    let h = 1e-4; // 10 kHz
    let mut sum = 0.0;
    for k in 0..5 {
        sum += host_step(c, k, h);
    }
    // A state handle reused in place does not allocate either.
    let mut st: *mut RacewayState = null_mut();
    assert_eq!(unsafe { raceway_state_get(c, &mut st) }, RacewayStatus::Ok);
    let before = thread_alloc::allocations();
    for k in 5..200 {
        sum += host_step(c, k, h);
    }
    assert_eq!(unsafe { raceway_state_get(c, &mut st) }, RacewayStatus::Ok);
    assert_eq!(unsafe { raceway_state_set(c, st) }, RacewayStatus::Ok);
    let allocations = thread_alloc::allocations() - before;
    assert!(sum.is_finite() && sum != 0.0);
    // The counter sees allocations (a zero above is not vacuous): a refused call formats
    // its message.
    let before = thread_alloc::allocations();
    assert_eq!(
        unsafe { raceway_do_step(c, 0.0, -1.0) },
        RacewayStatus::InvalidArgument
    );
    assert!(thread_alloc::allocations() > before);
    unsafe {
        raceway_state_free(st);
        raceway_free(c);
    }
    allocations
}

// One test function: the counter counts this thread's allocations, all in one place.
#[test]
fn do_step_and_the_c_loop_do_not_allocate() {
    assert_eq!(
        allocations_in_the_c_loop(),
        0,
        "heap allocations in 195 steps of the C loop"
    );
    for scene in [
        "bearing = \"6205\"\n[model]\nlevel = \"ring\"\n[inputs]\nspeed_rpm = 1750.004092\ninitial = { \"shaft.x\" = 0.0, \"shaft.y\" = -8e-6, \"shaft.z\" = 0.0, \"shaft.rx\" = 0.0, \"shaft.ry\" = 0.0, \"shaft.vx\" = 0.0, \"shaft.vy\" = 1e-4, \"shaft.vz\" = 0.0, \"shaft.wx\" = 0.0, \"shaft.wy\" = 0.0 }\n",
        "bearing = \"7008ce\"\n[model]\nlevel = \"quasi_static\"\n[inputs]\nspeed_rpm = 19098.59317\ninitial = { \"shaft.x\" = 0.0, \"shaft.y\" = -3e-6, \"shaft.z\" = 10e-6, \"shaft.rx\" = 0.0, \"shaft.ry\" = 0.0, \"shaft.vx\" = 0.0, \"shaft.vy\" = 0.0, \"shaft.vz\" = 0.0, \"shaft.wx\" = 0.0, \"shaft.wy\" = 0.0 }\n",
        "bearing = \"6205\"\n[model]\nlevel = \"quasi_static\"\ncausality = \"load\"\n[inputs]\nspeed_rpm = 1750.004092\ninitial = { \"load.x\" = 0.0, \"load.y\" = -500.0, \"load.z\" = 0.0, \"load.mx\" = 0.0, \"load.my\" = 0.0 }\n",
        "bearing = \"6205\"\n[model]\nlevel = \"linear\"\ncausality = \"load\"\ncontact_damping = 100.0\n[inputs]\nspeed_rpm = 1750.004092\ninitial = { \"load.x\" = 0.0, \"load.y\" = -900.0, \"load.z\" = 0.0, \"load.mx\" = 0.0, \"load.my\" = 0.0 }\n",
        "bearing = \"7008ce\"\n[model]\nlevel = \"ring\"\nring_dof = 5\ncausality = \"load\"\ncontact_damping = 500.0\n[inputs]\nspeed_rpm = 5729.577951\ninitial = { \"load.x\" = 0.0, \"load.y\" = -300.0, \"load.z\" = 200.0, \"load.mx\" = 0.0, \"load.my\" = 0.0 }\n",
        // RODAS4 on a load-driven 2-DOF ring: the reduced second-order solve (analytic
        // Jacobian), and with waviness its dense fallback (differenced Jacobian).
        "bearing = \"6205\"\n[model]\nlevel = \"ring\"\ncausality = \"load\"\ncontact_damping = 3000.0\n[solver]\nmethod = \"rosenbrock\"\n[inputs]\nspeed_rpm = 1750.004092\ninitial = { \"load.x\" = 0.0, \"load.y\" = -1000.0, \"load.z\" = 0.0, \"load.mx\" = 0.0, \"load.my\" = 0.0 }\n",
        "bearing = \"6205\"\n[model]\nlevel = \"ring\"\ncausality = \"load\"\ncontact_damping = 3000.0\n[solver]\nmethod = \"rosenbrock\"\n[inputs]\nspeed_rpm = 1750.004092\ninitial = { \"load.x\" = 0.0, \"load.y\" = -1000.0, \"load.z\" = 0.0, \"load.mx\" = 0.0, \"load.my\" = 0.0 }\n[effects]\nwaviness = [{ race = \"outer\", order = 12, amplitude_um = 0.3, phase_deg = 0.0 }]\n",
        // Cylindrical roller bearing NU206 (14 rollers x 30 laminae): the speed bench's
        // motion-driven 2-DOF ring, and a load-driven tilted 5-DOF ring with contact damping.
        "bearing = \"NU206\"\n[model]\nlevel = \"ring\"\nring_dof = 2\n[inputs]\nspeed_rpm = 1500.003508\ninitial = { \"shaft.x\" = 0.0, \"shaft.y\" = -30e-6, \"shaft.z\" = 0.0, \"shaft.rx\" = 0.0, \"shaft.ry\" = 0.0, \"shaft.vx\" = 0.0, \"shaft.vy\" = 1e-4, \"shaft.vz\" = 0.0, \"shaft.wx\" = 0.0, \"shaft.wy\" = 0.0 }\n",
        "bearing = \"NU206\"\n[model]\nlevel = \"ring\"\nring_dof = 5\ncausality = \"load\"\ncontact_damping = 200.0\nattached_mass_kg = 1.0\n[inputs]\nspeed_rpm = 1500.003508\ninitial = { \"load.x\" = 0.0, \"load.y\" = -4000.0, \"load.z\" = 0.0, \"load.mx\" = 20.0, \"load.my\" = 0.0 }\n",
        "bearing = \"7004\"\n[model]\nlevel = \"full\"\n[inputs]\nspeed_rpm = 29999.97466\ninitial = { \"shaft.x\" = 0.0, \"shaft.y\" = -2.96568e-6, \"shaft.z\" = 4.364864e-5, \"shaft.rx\" = 0.0, \"shaft.ry\" = 0.0, \"shaft.vx\" = 0.0, \"shaft.vy\" = 0.0, \"shaft.vz\" = 0.0, \"shaft.wx\" = 0.0, \"shaft.wy\" = 0.0 }\n",
    ] {
        assert_eq!(allocations_in_steps(scene, 1e-4), 0, "{scene}");
    }
    let pair = include_str!("../examples/scenes/7008ce-db-pair.toml");
    let spring = pair.replace("preload_n = 300", "preload_n = 300\nspring_n_per_um = 1");
    let ring = pair
        .replace(
            "level = \"quasi_static\"\ncausality = \"motion\"",
            "level = \"ring\"\nring_dof = 5\ncausality = \"load\"\ncontact_damping = 500.0",
        )
        .replace(
            "initial = { \"shaft.y\" = -5e-6, \"shaft.z\" = 5e-6 }",
            "initial = { \"load.y\" = -300.0, \"load.z\" = 100.0 }",
        );
    assert!(ring.contains("level = \"ring\"") && ring.contains("load.y"));
    for scene in [pair.to_string(), spring, ring] {
        assert_eq!(allocations_in_steps(&scene, 1e-4), 0, "{scene}");
    }
    // The pair with the thermal network (one per row): the networks alone (growth off) do
    // not allocate; with the growth on, a row is formed again (its level rebuilt) only when
    // its temperatures moved by more than 0.01 K since it was last formed, so once the
    // networks have settled (0.3 s of the scene = 150 s of heating) no step allocates.
    let thermal = include_str!("../examples/scenes/7008ce-db-pair-thermal.toml");
    let off = thermal.replace(
        "contact_conductance_w_k = 1.0",
        "contact_conductance_w_k = 1.0, growth_factor = 0.0",
    );
    assert_ne!(off, thermal);
    assert_eq!(allocations_in_steps(&off, 1e-4), 0, "{off}");
    let mut c = Component::from_text(thermal).unwrap();
    for i in 0..300 {
        c.do_step(i as f64 * 1e-3, 1e-3).unwrap();
    }
    let before = thread_alloc::allocations();
    for i in 0..47 {
        c.do_step(0.3 + i as f64 * 1e-3, 1e-3).unwrap();
    }
    assert_eq!(
        thread_alloc::allocations() - before,
        0,
        "the thermal pair, settled"
    );
}
