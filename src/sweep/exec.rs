//! Running a sweep: one point from its scene, claiming the output folder, executing a shard
//! on every core, resuming, storing and merging shards.

use super::*;

pub(super) const ID_FILE: &str = "sweep.id";

/// Claim `dir` for the sweep of fingerprint `id` ([`Sweep::fingerprint`]): a folder holding
/// another sweep's rows is refused.
pub fn claim_dir(dir: &Path, id: &str) -> Result<()> {
    let path = dir.join(ID_FILE);
    match std::fs::read_to_string(&path) {
        Ok(old) if old.trim() != id => Err(Error::Parse {
            what: format!("output folder `{}`", dir.display()),
            message: format!(
                "it holds rows of another sweep (fingerprint {} here, {id} for this sweep); use another --out or empty it",
                old.trim()
            ),
        }),
        Ok(_) => Ok(()),
        Err(_) => write_atomic(&path, format!("{id}\n").as_bytes()),
    }
}

/// Run the points of `exec.shard` not yet finished in `dir`, `exec.jobs` at a time; each
/// finished row is written atomically to `dir/rows/<index>.json`, and at the end
/// `dir/sweep.csv` holds every finished row of the folder. `progress(done, to_do, failed)`
/// is called after each point.
pub fn execute(
    sweep: &Sweep,
    dir: &Path,
    exec: Exec,
    progress: &(dyn Fn(usize, usize, usize) + Sync),
) -> Result<Outcome> {
    execute_until(sweep, dir, exec, progress, &|| false)
}

/// [`execute`], asking `stop` (from every worker, between the steps of its run) whether to
/// stop: when it says so, the points running are abandoned (no row: they run again when
/// the sweep resumes), `dir/sweep.csv` is written from the rows finished so far and the
/// sweep ends with [`Error::Interrupted`] (Ctrl-C in the command line and in Python).
pub fn execute_until(
    sweep: &Sweep,
    dir: &Path,
    exec: Exec,
    progress: &(dyn Fn(usize, usize, usize) + Sync),
    stop: &(dyn Fn() -> bool + Sync),
) -> Result<Outcome> {
    let (k, n) = exec.shard;
    if n == 0 || k >= n {
        return Err(Error::invalid(
            "--shard k/n",
            k as f64,
            "0 <= k < n (k is 0-based, as Slurm's and Kubernetes' array indices)",
        ));
    }
    claim_dir(dir, &sweep.fingerprint())?;
    let total = sweep.len();
    let done: std::collections::BTreeSet<usize> =
        read_rows(dir).into_iter().map(|r| r.index).collect();
    let shard: Vec<usize> = (k..total).step_by(n).collect();
    let todo: Vec<usize> = shard
        .iter()
        .copied()
        .filter(|i| !done.contains(i))
        .collect();
    let next = AtomicUsize::new(0);
    let finished = AtomicUsize::new(0);
    let failed = AtomicUsize::new(0);
    let cpu = Mutex::new(0.0f64);
    let first_error: Mutex<Option<Error>> = Mutex::new(None);
    let interrupted = std::sync::atomic::AtomicBool::new(false);
    let stopped = || {
        if interrupted.load(Ordering::Relaxed) || stop() {
            interrupted.store(true, Ordering::Relaxed);
            return true;
        }
        false
    };
    let jobs = exec.jobs.max(1).min(todo.len().max(1));
    std::fs::create_dir_all(dir.join("rows")).map_err(|e| {
        Error::Io(format!(
            "cannot create `{}`: {e}",
            dir.join("rows").display()
        ))
    })?;
    std::thread::scope(|s| {
        for _ in 0..jobs {
            s.spawn(|| {
                let c0 = thread_cpu_s();
                loop {
                    let w = next.fetch_add(1, Ordering::Relaxed);
                    let Some(&i) = todo.get(w) else { break };
                    if first_error.lock().map(|e| e.is_some()).unwrap_or(true) || stopped() {
                        break;
                    }
                    let series = sweep
                        .series
                        .then(|| dir.join("series").join(format!("{i:08}.csv")));
                    let Some(row) = sweep.run_point_until(i, series.as_deref(), &stopped) else {
                        break;
                    };
                    if row.error.is_some() {
                        failed.fetch_add(1, Ordering::Relaxed);
                    }
                    let bytes = serde_json::to_vec(&row).expect("a row serialises");
                    if let Err(e) = write_row(&row_path(dir, i), &bytes) {
                        if let Ok(mut slot) = first_error.lock() {
                            slot.get_or_insert(e);
                        }
                        break;
                    }
                    let d = finished.fetch_add(1, Ordering::Relaxed) + 1;
                    progress(d, todo.len(), failed.load(Ordering::Relaxed));
                }
                if let Ok(mut c) = cpu.lock() {
                    *c += thread_cpu_s() - c0;
                }
            });
        }
    });
    if let Some(e) = first_error.into_inner().ok().flatten() {
        return Err(e);
    }
    let rows = read_rows(dir);
    write_atomic(&dir.join("sweep.csv"), csv(&rows).as_bytes())?;
    if interrupted.into_inner() {
        return Err(Error::Interrupted { at_s: 0.0 });
    }
    Ok(Outcome {
        total,
        in_shard: shard.len(),
        ran: finished.into_inner(),
        skipped: shard.len() - todo.len(),
        failed: failed.into_inner(),
        finished: rows.len(),
        cpu_s: cpu.into_inner().unwrap_or(0.0),
    })
}

/// Store rows finished elsewhere (another executor, e.g. Dask workers) in `dir` as
/// [`execute`] does: each row atomically into `dir/rows/` (a row already there is kept), then
/// `dir/sweep.csv` from every finished row of the folder. Returns the CSV text. Claim the
/// folder first ([`claim_dir`]).
pub fn store(dir: &Path, rows: &[Row]) -> Result<String> {
    for r in rows {
        let p = row_path(dir, r.index);
        if !p.exists() {
            write_atomic(&p, &serde_json::to_vec(r).expect("a row serialises"))?;
        }
    }
    let text = csv(&read_rows(dir));
    write_atomic(&dir.join("sweep.csv"), text.as_bytes())?;
    Ok(text)
}

/// Join the rows of shard folders (same sweep) into `out`: its rows and `out/sweep.csv`.
/// Returns the number of rows.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<usize> {
    let mut id: Option<String> = None;
    let mut rows: Vec<Row> = Vec::new();
    for d in dirs {
        let this = std::fs::read_to_string(d.join(ID_FILE)).map_err(|e| {
            Error::Io(format!(
                "`{}` is not a sweep output folder (no {ID_FILE}: {e})",
                d.display()
            ))
        })?;
        match &id {
            Some(first) if first.trim() != this.trim() => {
                return Err(Error::Parse {
                    what: format!("sweep folder `{}`", d.display()),
                    message: format!(
                        "its sweep (fingerprint {}) is not the first folder's ({})",
                        this.trim(),
                        first.trim()
                    ),
                })
            }
            _ => id = Some(this),
        }
        rows.extend(read_rows(d));
    }
    let id = id.ok_or_else(|| Error::invalid("--merge", 0.0, "at least one folder"))?;
    rows.sort_by_key(|r| r.index);
    rows.dedup_by_key(|r| r.index);
    claim_dir(out, id.trim())?;
    for r in &rows {
        let p = row_path(out, r.index);
        if !p.exists() {
            write_atomic(&p, &serde_json::to_vec(r).expect("a row serialises"))?;
        }
    }
    write_atomic(&out.join("sweep.csv"), csv(&rows).as_bytes())?;
    Ok(rows.len())
}

impl Sweep {
    /// Run point `index`: scene, run, the summary `raceway run` writes
    /// ([`crate::summary::summarize`], with the thread CPU time of the run), flattened into a
    /// row. Never fails: an error (or a panic) becomes the row's
    /// `error`. With `series`, the run's series is written there (atomically).
    pub fn run_point(&self, index: usize, series: Option<&Path>) -> Row {
        self.run_point_until(index, series, &|| false)
            .expect("a run that is never asked to stop is not interrupted")
    }

    /// [`Sweep::run_point`], asking `stop` between the steps of the run: `None` when it
    /// said stop (the point has no row; it runs again when the sweep resumes).
    pub fn run_point_until(
        &self,
        index: usize,
        series: Option<&Path>,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Row> {
        let axes: Vec<(String, Json)> = self
            .axes
            .iter()
            .zip(self.point(index))
            .map(|(a, v)| (a.column.clone(), json_of(&v)))
            .collect();
        let attempt = || -> Result<Vec<(String, Json)>> {
            let scene = self.scene(index)?;
            let c0 = thread_cpu_s();
            // The point's rows go into its digest (bounded memory) and, when asked, its
            // series file as they are made (a temporary name renamed when complete).
            let mut run = crate::summary::digest_for(&scene);
            let go = |sink: &mut dyn runner::Sink| {
                runner::run_into(
                    &scene,
                    runner::Record::default(),
                    false,
                    &mut |_| {},
                    &mut || stop(),
                    sink,
                )
            };
            let comp = match series {
                Some(p) => crate::fsutil::write_atomic_with(p, |tmp| {
                    let mut csv = runner::CsvSink::create(tmp)?;
                    let comp = go(&mut runner::Tee(&mut csv, &mut run))?;
                    csv.finish()?;
                    Ok::<_, Error>(comp)
                })?,
                None => go(&mut run)?,
            };
            let cpu = thread_cpu_s() - c0;
            let mut cols = Vec::new();
            let summary = crate::summary::summarize(&scene, "sweep point", &run, &comp, cpu);
            flatten("", &Json::Object(summary.json), &mut cols);
            Ok(cols)
        };
        let (error, summary) = match std::panic::catch_unwind(std::panic::AssertUnwindSafe(attempt))
        {
            Ok(Ok(cols)) => (None, cols),
            Ok(Err(Error::Interrupted { .. })) => return None,
            // One line per row: a multi-line message is joined.
            Ok(Err(e)) => (
                Some(
                    e.to_string()
                        .split_whitespace()
                        .collect::<Vec<_>>()
                        .join(" "),
                ),
                Vec::new(),
            ),
            Err(p) => {
                let what = crate::error::panic_message(&*p).unwrap_or_default();
                (Some(format!("panic: {what}")), Vec::new())
            }
        };
        Some(Row {
            index,
            axes,
            error,
            summary,
        })
    }
}
