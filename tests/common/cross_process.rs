//! The cross-process state test, shared by the C ABI's (`tests/capi.rs`) and the FMU's
//! (`src/fmi/state_tests.rs`): a child run of the same test executable writes its state
//! bytes and the outputs of the steps after them into a folder; the parent restores the
//! bytes in a fresh instance and compares. Mount with
//! `#[path = "common/cross_process.rs"] mod cross_process;`.

use std::path::PathBuf;

/// In the child run, the folder the parent named in `env`; `None` in an ordinary run.
pub fn child_dir(env: &str) -> Option<PathBuf> {
    std::env::var_os(env).map(PathBuf::from)
}

/// The child's half: the state bytes and the outputs (bits) of the steps after them.
pub fn write_child(dir: &std::path::Path, state: &[u8], outputs: &[u64]) {
    std::fs::write(dir.join("state.bin"), state).unwrap();
    let out: Vec<u8> = outputs.iter().flat_map(|b| b.to_le_bytes()).collect();
    std::fs::write(dir.join("outputs.bin"), out).unwrap();
}

/// The parent's half: runs the test `child` of this executable alone with `env` naming a
/// fresh folder (`<temp>/<tag>-<pid>`), and returns the state bytes and the outputs it
/// wrote. Panics with the child's stderr when it fails.
pub fn run_child(child: &str, env: &str, tag: &str) -> (Vec<u8>, Vec<u64>) {
    let dir = std::env::temp_dir().join(format!("{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args(["--exact", child, "--nocapture", "--test-threads=1"])
        .env(env, &dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(dir.join("state.bin")).unwrap();
    let outputs: Vec<u64> = std::fs::read(dir.join("outputs.bin"))
        .unwrap()
        .chunks(8)
        .map(|b| u64::from_le_bytes(b.try_into().unwrap()))
        .collect();
    std::fs::remove_dir_all(&dir).unwrap();
    (bytes, outputs)
}
