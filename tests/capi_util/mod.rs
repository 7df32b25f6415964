//! Helpers shared by the C ABI tests: where cargo put the cdylib, the system C compilers,
//! running commands with their output in the failure message.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// The crate root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The directory holding the cdylib cargo built for this test run:
/// `target/<profile>/` is the parent of the test executable's `deps/`.
pub fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    let dir = exe
        .parent()
        .and_then(Path::parent)
        .expect("target/<profile>/deps/<test>")
        .to_path_buf();
    let lib = dir.join(format!(
        "{}raceway{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    ));
    // `cargo test` links the tests against the rlib and builds the cdylib only when the
    // library itself is built, and a cdylib left from an earlier build may be stale: run
    // `cargo build --lib` once per test process (same profile, same target directory; a
    // no-op when it is fresh). Serialised: several tests may ask at once.
    static BUILD: std::sync::Once = std::sync::Once::new();
    BUILD.call_once(|| {
        let mut cmd = Command::new(env!("CARGO"));
        cmd.args(["build", "--lib", "--quiet", "--manifest-path"])
            .arg(root().join("Cargo.toml"));
        if dir.file_name().is_some_and(|n| n == "release") {
            cmd.arg("--release");
        }
        if let Some(target) = dir.parent() {
            cmd.arg("--target-dir").arg(target);
        }
        let st = cmd.status().expect("run cargo build --lib");
        assert!(st.success(), "cargo build --lib failed");
    });
    assert!(
        lib.exists(),
        "{} not found after `cargo build --lib`",
        lib.display()
    );
    dir
}

/// A scratch directory for this test's build products.
pub fn scratch(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The C compiler: `$CC` or `cc`.
pub fn cc() -> String {
    std::env::var("CC").unwrap_or_else(|_| "cc".into())
}

/// The C++ compiler: `$CXX` or `c++`.
pub fn cxx() -> String {
    std::env::var("CXX").unwrap_or_else(|_| "c++".into())
}

/// Run a command; panic with its output when it fails; return its stdout.
pub fn run(cmd: &mut Command) -> String {
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("cannot start {cmd:?}: {e}"));
    assert!(
        out.status.success(),
        "{cmd:?} failed ({}):\n{}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// Compile and link C sources against include/raceway.h and the cdylib (rpath set so the
/// program runs in place) with `-std=c99 -Wall -Wextra -pedantic -Werror`.
pub fn build_c_program(sources: &[PathBuf], exe: &Path) {
    let lib = lib_dir();
    let mut cmd = Command::new(cc());
    cmd.args([
        "-std=c99",
        "-Wall",
        "-Wextra",
        "-pedantic",
        "-Werror",
        "-O2",
    ])
    .arg("-I")
    .arg(root().join("include"))
    .args(sources)
    .arg("-o")
    .arg(exe)
    .arg(format!("-L{}", lib.display()))
    .arg(format!("-Wl,-rpath,{}", lib.display()))
    .args(["-lraceway", "-lm"]);
    run(&mut cmd);
}
