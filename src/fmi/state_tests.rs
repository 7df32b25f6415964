//! FMU state bytes across processes and under damage (run with `cargo test --features fmi
//! --lib fmi::`).

use super::instance::{Instance, Logger, Snapshot, STEP};

fn instance() -> Instance {
    Instance::new(
        2,
        "t",
        Logger::Fmi2(None, std::ptr::null_mut()),
        false,
        None::<&std::path::Path>,
    )
}

/// A stepped instance, `n` steps of 0.1 ms from 0.
fn stepped(n: usize) -> Instance {
    let mut a = instance();
    a.set_real(2, -2e-5).unwrap();
    a.exit_initialization().unwrap();
    a.mode = STEP;
    for k in 0..n {
        a.do_step(k as f64 * 1e-4, 1e-4).unwrap();
    }
    a
}

/// Outputs (as bits) after each of `n` more steps.
fn continue_run(a: &mut Instance, from: usize, n: usize) -> Vec<u64> {
    let mut out = Vec::new();
    for k in from..from + n {
        a.set_real(1, 1e-6 * (k as f64 * 0.3).sin()).unwrap();
        a.do_step(k as f64 * 1e-4, 1e-4).unwrap();
        for vr in [101, 102, 103, 104, 105] {
            out.push(a.get_real(vr).unwrap().to_bits());
        }
    }
    out
}

#[test]
fn every_single_byte_change_of_fmu_state_bytes_is_refused() {
    let bytes = stepped(2).snapshot().to_bytes();
    for i in 0..bytes.len() {
        let mut bad = bytes.clone();
        bad[i] ^= 0x10;
        assert!(Snapshot::from_bytes(&bad).is_err(), "byte {i}");
    }
    for n in 0..bytes.len() {
        assert!(Snapshot::from_bytes(&bytes[..n]).is_err(), "{n} bytes");
    }
}

/// Child half of the cross-process test; runs only when `RACEWAY_FMU_STATE_CHILD` names a
/// folder.
#[test]
fn fmu_state_child_process() {
    let Some(dir) = std::env::var_os("RACEWAY_FMU_STATE_CHILD") else {
        return;
    };
    let dir = std::path::PathBuf::from(dir);
    let mut a = stepped(3);
    std::fs::write(dir.join("state.bin"), a.snapshot().to_bytes()).unwrap();
    let out: Vec<u8> = continue_run(&mut a, 3, 4)
        .iter()
        .flat_map(|b| b.to_le_bytes())
        .collect();
    std::fs::write(dir.join("outputs.bin"), out).unwrap();
}

/// FMU state bytes written by one process restore in a fresh instance of another and the
/// run continues bit for bit.
#[test]
fn fmu_state_bytes_restore_in_another_process_bit_for_bit() {
    let dir = std::env::temp_dir().join(format!("raceway-fmu-xproc-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "fmi::state_tests::fmu_state_child_process",
            "--test-threads=1",
        ])
        .env("RACEWAY_FMU_STATE_CHILD", &dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(dir.join("state.bin")).unwrap();
    let theirs: Vec<u64> = std::fs::read(dir.join("outputs.bin"))
        .unwrap()
        .chunks(8)
        .map(|b| u64::from_le_bytes(b.try_into().unwrap()))
        .collect();
    std::fs::remove_dir_all(&dir).unwrap();
    let mut b = instance();
    b.restore(&Snapshot::from_bytes(&bytes).unwrap()).unwrap();
    let ours = continue_run(&mut b, 3, 4);
    assert_eq!(ours.len(), 20);
    assert_eq!(ours, theirs);
}
