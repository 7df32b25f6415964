//! The sweep throughput row of the speed page (issue #36): `examples/sweeps/bench-qs-1000.toml`
//! (1 000 quasi-static points of the default scene) executed by the library's sweep executor
//! with one job, as `raceway sweep examples/sweeps/bench-qs-1000.toml --jobs 1` does, into a
//! fresh folder each time (rows written, sweep.csv at the end). Mounted by benches/speed.rs.

use raceway::sweep::{self, Exec, Sweep};

/// `repeats` runs; returns (points per CPU second of each run, points per run). The CPU time
/// is the worker thread's (`Outcome::cpu_s`, what `raceway sweep` prints).
pub fn points_per_cpu_s(repeats: usize) -> Result<(Vec<f64>, usize), String> {
    let sw = Sweep::from_file(std::path::Path::new("examples/sweeps/bench-qs-1000.toml"))
        .map_err(|e| e.to_string())?;
    let mut rates = Vec::with_capacity(repeats);
    let mut ran = 0;
    for k in 0..repeats {
        let dir =
            std::env::temp_dir().join(format!("raceway-speed-sweep-{}-{k}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let o = sweep::execute(
            &sw,
            &dir,
            Exec {
                jobs: 1,
                shard: (0, 1),
            },
            &|_, _, _| {},
        )
        .map_err(|e| e.to_string())?;
        let _ = std::fs::remove_dir_all(&dir);
        if o.failed > 0 {
            return Err(format!("{} of {} points failed", o.failed, o.ran));
        }
        ran = o.ran;
        rates.push(o.ran as f64 / o.cpu_s);
    }
    Ok((rates, ran))
}
