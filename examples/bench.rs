//! Work-precision study and stability campaign (what `raceway bench` runs).
//!
//! - `cargo run --release --example bench -- --out docs` : work-precision
//!   (docs/work-precision.{csv,md,png}); `--quick` for a 3-tolerance, 1-repeat sweep;
//!   `--peer` also runs the SciPy peer (scripts/peer-scipy) and puts its ratio in the page.
//! - `... -- --stability-long --out docs` : the long stability campaign (docs/stability.md);
//!   `--stability` the sampled one that tests/stability.rs runs.
use raceway::report::stability;
use raceway::report::work_precision::{self as wp, Config};
use std::path::{Path, PathBuf};

fn fail(e: impl std::fmt::Display) -> ! {
    eprintln!("bench: {e}");
    std::process::exit(1)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let has = |f: &str| args.iter().any(|a| a == f);
    let out = args
        .iter()
        .position(|a| a == "--out")
        .and_then(|i| args.get(i + 1))
        .map_or(PathBuf::from("docs"), PathBuf::from);
    if has("--stability") || has("--stability-long") {
        let res =
            stability::campaign(has("--stability-long"), &out, true).unwrap_or_else(|e| fail(e));
        let failed = res.iter().filter(|(_, o)| !o.passed()).count();
        println!("wrote {}/stability.md ({failed} failed)", out.display());
        return;
    }
    let mut cfg = Config {
        verbose: true,
        ..Config::default()
    };
    if has("--quick") {
        cfg.rtols = vec![1e-3, 1e-5, 1e-7];
        cfg.repeats = 1;
    }
    let mut rep = wp::run(&cfg).unwrap_or_else(|e| fail(e));
    if has("--peer") {
        let case = cfg
            .cases
            .iter()
            .find(|c| c.name == "6205-2dof")
            .unwrap_or_else(|| fail("no 6205-2dof case"));
        wp::export_for_peer(&cfg, case, &cfg.cache_dir).unwrap_or_else(|e| fail(e));
        let status = std::process::Command::new("scripts/peer-scipy")
            .arg(&cfg.cache_dir)
            .status()
            .unwrap_or_else(|e| fail(format!("scripts/peer-scipy: {e}")));
        if !status.success() {
            fail("scripts/peer-scipy failed");
        }
        let p = Path::new(&cfg.cache_dir).join("6205-2dof-scipy.csv");
        let text =
            std::fs::read_to_string(&p).unwrap_or_else(|e| fail(format!("{}: {e}", p.display())));
        rep.peer = wp::read_peer_csv(&text).unwrap_or_else(|e| fail(e));
    }
    rep.write(&out).unwrap_or_else(|e| fail(e));
    println!("wrote {}/work-precision.{{csv,md,png}}", out.display());
}
