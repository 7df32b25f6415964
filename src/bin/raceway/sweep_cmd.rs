//! `raceway sweep SWEEP.toml [--out DIR] [--jobs N] [--shard k/n]` runs a parameter sweep
//! (`raceway::sweep`): one row per point, the summary `raceway run` writes to summary.json,
//! flattened; `raceway sweep --merge DIR... --out DIR` joins shards.
//!
//! Threads: std scoped threads taking the next index from a shared counter. A point is a
//! whole run (milliseconds to minutes), so a counter balances the load as well as a
//! work-stealing pool would, without a new dependency.

use raceway::sweep::{self, Exec, Sweep};
use raceway::{Error, Result};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::PathBuf;

/// Options of `raceway sweep`.
#[derive(clap::Args, Debug)]
pub struct SweepArgs {
    /// Sweep file (TOML): a base scene and axes (see `raceway::sweep`).
    #[arg(required_unless_present = "merge")]
    pub sweep: Option<PathBuf>,
    /// Output folder (default: out/<sweep name>); rows/, series/ and sweep.csv go there.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Worker threads (default: every core).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Run only the indices i with i % n == k (k from 0), e.g. `--shard $SLURM_ARRAY_TASK_ID/8`.
    #[arg(long, value_name = "k/n")]
    pub shard: Option<String>,
    /// Check the sweep file and print its size; run nothing.
    #[arg(long)]
    pub check: bool,
    /// Join the rows of these shard folders into --out.
    #[arg(long, num_args = 1.., value_name = "DIR", conflicts_with_all = ["sweep", "shard", "jobs", "check"])]
    pub merge: Vec<PathBuf>,
    /// No progress line on standard error.
    #[arg(long, short)]
    pub quiet: bool,
}

fn shard(s: &str) -> Result<(usize, usize)> {
    let bad = || Error::Parse {
        what: "--shard".into(),
        message: format!("`{s}` is not k/n with integers 0 <= k < n"),
    };
    let (k, n) = s.split_once('/').ok_or_else(bad)?;
    let (k, n): (usize, usize) = (
        k.trim().parse().map_err(|_| bad())?,
        n.trim().parse().map_err(|_| bad())?,
    );
    if n == 0 || k >= n {
        return Err(bad());
    }
    Ok((k, n))
}

fn clock(s: f64) -> String {
    let s = s.max(0.0).round() as u64;
    format!("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
}

/// Run the subcommand; returns the text for standard output.
pub fn sweep(a: SweepArgs) -> Result<String> {
    if !a.merge.is_empty() {
        let out = a
            .out
            .clone()
            .ok_or_else(|| Error::invalid("--out", 0.0, "a folder for the merged table"))?;
        let n = sweep::merge(&a.merge, &out)?;
        return Ok(format!(
            "merged {n} rows from {} folder(s) into {}\n",
            a.merge.len(),
            out.join("sweep.csv").display()
        ));
    }
    let path = a
        .sweep
        .clone()
        .expect("clap requires a sweep file without --merge");
    let sw = Sweep::from_file(&path)?;
    if a.check {
        return Ok(format!(
            "ok: {}: {} points, {} axes\n",
            path.display(),
            sw.len(),
            sw.axes.len()
        ));
    }
    let out = a.out.clone().unwrap_or_else(|| {
        PathBuf::from("out").join(
            path.file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "sweep".into()),
        )
    });
    let jobs = match a.jobs {
        Some(0) => return Err(Error::invalid("--jobs", 0.0, ">= 1")),
        Some(j) => j,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let exec = Exec {
        jobs,
        shard: a.shard.as_deref().map(shard).transpose()?.unwrap_or((0, 1)),
    };
    let bar_on = !a.quiet && std::io::IsTerminal::is_terminal(&std::io::stderr());
    let started = std::time::Instant::now();
    let progress = |done: usize, todo: usize, failed: usize| {
        if !bar_on {
            return;
        }
        let el = started.elapsed().as_secs_f64();
        let eta = el / done as f64 * (todo - done) as f64;
        eprint!(
            "\r{done}/{todo} points ({:.0}%), {failed} failed, elapsed {}, ETA {}   ",
            100.0 * done as f64 / todo.max(1) as f64,
            clock(el),
            clock(eta)
        );
        let _ = std::io::stderr().flush();
    };
    // Ctrl-C and SIGTERM: the points running stop at their next step and have no row;
    // finished rows stay (the sweep resumes from them).
    crate::run::catch_stop_signals();
    let stop = || crate::run::STOP.load(std::sync::atomic::Ordering::Relaxed);
    let o = sweep::execute_until(&sw, &out, exec, &progress, &stop)?;
    if bar_on {
        eprintln!();
    }
    let wall = started.elapsed().as_secs_f64();
    let mut s = String::new();
    writeln!(
        s,
        "sweep {}: {} points; this shard {}/{}: {} points, ran {}, skipped {} finished, {} failed",
        path.display(),
        o.total,
        exec.shard.0,
        exec.shard.1,
        o.in_shard,
        o.ran,
        o.skipped,
        o.failed
    )
    .ok();
    if o.ran > 0 {
        writeln!(
            s,
            "{} thread(s): {:.3} s CPU (threads' CPU time), {:.3} s wall; {:.2} points per CPU second, {:.2} points per wall second; load average {}",
            exec.jobs.min(o.ran),
            o.cpu_s,
            wall,
            o.ran as f64 / o.cpu_s.max(1e-9),
            o.ran as f64 / wall.max(1e-9),
            raceway::report::load_average()
        )
        .ok();
    }
    writeln!(
        s,
        "{} of {} rows finished in {}",
        o.finished,
        o.total,
        out.join("sweep.csv").display()
    )
    .ok();
    if o.failed > 0 {
        writeln!(
            s,
            "{} point(s) failed: their rows carry the error message (column `error`)",
            o.failed
        )
        .ok();
    }
    Ok(s)
}
