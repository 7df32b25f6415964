//! Shared by the property tests (`tests/props_*.rs`): the proptest configuration and the
//! nasty numbers the strategies draw from.
//!
//! Cases per test: the test's CI default (chosen so the three files take about a minute
//! of a 2-core machine together), or `PROPTEST_CASES` when set, times
//! `RACEWAY_PROPS_SCALE` (a factor, default 1; `scripts/fuzz --minutes N` sets it so the
//! property tests take their share of the N minutes). The generator seed is fixed, so CI
//! is reproducible, unless `PROPTEST_RNG_SEED` is set (`scripts/fuzz` passes its seed).
//! A failing case is shrunk to a minimal one and printed; proptest also records its seed
//! in `tests/<file>.regressions` so it is retried first next time (commit it with the fix).

#![allow(dead_code)]

use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, RngSeed, TestCaseError, TestRunner};

/// The fixed seed of CI runs.
const CI_SEED: u64 = 0x5eed_2026_1124_0021;

/// Run the property `test` over `strategy` with the configuration of [`config`] and print
/// one line for `scripts/fuzz` (cases, thread CPU time, load average); on a failure,
/// panic with proptest's report: the reason and the minimal (shrunk) failing input.
/// `source` is the calling file (`file!()`), where a failure's seed is recorded.
pub fn check<S>(
    name: &str,
    source: &'static str,
    ci_cases: u32,
    strategy: S,
    test: impl Fn(S::Value) -> Result<(), TestCaseError>,
) where
    S: Strategy,
    S::Value: std::fmt::Debug,
{
    let mut c = config(ci_cases);
    c.source_file = Some(source);
    let cases = c.cases;
    let seed = c.rng_seed;
    let mut runner = TestRunner::new(c);
    let cpu0 = thread_cpu();
    let result = runner.run(&strategy, test);
    println!(
        "props {name}: {cases} cases, seed {seed}, {:.1} s of thread CPU (load average {}): {}",
        thread_cpu() - cpu0,
        raceway::report::load_average(),
        if result.is_ok() { "passed" } else { "FAILED" }
    );
    if let Err(e) = result {
        panic!("{e}");
    }
}

/// The configuration of a property test whose CI default is `ci_cases` cases.
pub fn config(ci_cases: u32) -> Config {
    // `Config::default()` has already read the PROPTEST_* variables.
    let mut c = Config::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = ci_cases;
    }
    let scale: f64 = std::env::var("RACEWAY_PROPS_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .filter(|s: &f64| s.is_finite() && *s > 0.0)
        .unwrap_or(1.0);
    c.cases = ((c.cases as f64 * scale).round() as u32).max(1);
    // Next to the test file (`tests/props_scene.regressions`): proptest's default looks
    // for a lib.rs above it, which integration tests do not have.
    c.failure_persistence = Some(Box::new(FileFailurePersistence::WithSource("regressions")));
    if c.rng_seed == RngSeed::Random {
        c.rng_seed = RngSeed::Fixed(CI_SEED);
    }
    c
}

/// Numbers no input should survive unchecked, and a few ordinary ones.
pub const NASTY: [f64; 16] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    5e-324,
    -1e-300,
    1e-100,
    1e300,
    -1e308,
    f64::MAX,
    f64::MIN_POSITIVE,
    1e18,
    -1.0,
    1.0,
    1e-4,
];

/// A nasty number, or any finite one of any magnitude.
pub fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => proptest::sample::select(NASTY.to_vec()),
        1 => proptest::num::f64::NORMAL | proptest::num::f64::SUBNORMAL | proptest::num::f64::ZERO,
        1 => (-12i32..12, -1.0f64..1.0).prop_map(|(e, m)| m * 10f64.powi(e)),
    ]
}

/// CPU time of the calling thread, s.
pub fn thread_cpu() -> f64 {
    raceway::report::thread_cpu_s()
}
