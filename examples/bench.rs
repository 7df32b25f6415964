//! Work-precision study and stability campaign (what `raceway bench` runs).
//!
//! `cargo run --release --example bench -- --out docs [--quick] [--peer] [--stability-long]`
use raceway::report::work_precision::{self as wp, Config};
use std::path::PathBuf;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let has = |f: &str| args.iter().any(|a| a == f);
    let out = args
        .iter()
        .position(|a| a == "--out")
        .and_then(|i| args.get(i + 1))
        .map_or(PathBuf::from("docs"), PathBuf::from);
    let mut cfg = Config {
        verbose: true,
        ..Config::default()
    };
    if has("--quick") {
        cfg.rtols = vec![1e-3, 1e-5, 1e-7];
        cfg.repeats = 1;
    }
    let rep = match wp::run(&cfg) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("bench: {e}");
            std::process::exit(1);
        }
    };
    if let Err(e) = rep.write(&out) {
        eprintln!("bench: {e}");
        std::process::exit(1);
    }
    println!("wrote {}/work-precision.{{csv,md,png}}", out.display());
}
