//! `raceway bench`: the work-precision study (error of the reaction forces against a tight
//! two-method reference, against CPU time, for every level and integrator) and the
//! stability campaign: developer tools, hidden from `raceway --help`. They write only where
//! `--out` says (required: regenerating the project's pages is `--out docs`, asked for by
//! name, never a default that rewrites tracked files when run inside a clone).
//!
//! - `raceway bench --out DIR [--quick] [--peer]`: DIR/work-precision.{csv,md,png};
//!   `--quick`: three tolerances, one repeat; `--peer`: also the SciPy peer
//!   (scripts/peer-scipy) with its speed ratio at equal error.
//! - `raceway bench --stability [--long] [--cell TEXT]... --out DIR`: DIR/stability.md
//!   (`--cell`: only the cells whose label contains TEXT).

use raceway::report::stability;
use raceway::report::work_precision::{self as wp, Config};
use raceway::{Error, Result};
use std::path::{Path, PathBuf};

/// Options of `raceway bench`.
#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    /// Output folder (required; `--out docs` regenerates the project's pages).
    #[arg(long)]
    pub out: PathBuf,
    /// Three tolerances and one repeat (a quick look).
    #[arg(long)]
    pub quick: bool,
    /// Also run the SciPy peer (needs Python; scripts/peer-scipy makes its venv).
    #[arg(long)]
    pub peer: bool,
    /// Run the stability campaign instead of the work-precision study.
    #[arg(long)]
    pub stability: bool,
    /// With --stability: the long matrix.
    #[arg(long)]
    pub long: bool,
    /// With --stability: only the cells whose label (`base | speed (rpm) | load |
    /// clearance | material | H | step input`, as on the page, or `set: NAME`) contains
    /// this text (repeatable: any of them). A developer's filter for rerunning a few
    /// cells; the page then holds only those.
    #[arg(long = "cell")]
    pub cells: Vec<String>,
    /// Recompute the cached references (target/raceway-bench, keyed by scene and version,
    /// not by the model's code: use this after changing a model).
    #[arg(long)]
    pub fresh: bool,
    /// Only these work-precision cases (repeatable; default all). For a quick look into
    /// another folder: the docs are regenerated from all cases.
    #[arg(long = "case")]
    pub cases: Vec<String>,
}

/// Run; returns what to print.
pub fn bench(a: BenchArgs) -> Result<String> {
    let out = a.out;
    if a.stability {
        let res = stability::campaign_of(a.long, &a.cells, &out, true)?;
        let failed = res.iter().filter(|(_, o)| !o.passed()).count();
        return Ok(format!(
            "wrote {}/stability.md ({} cells, {failed} failed)\n",
            out.display(),
            res.len()
        ));
    }
    let mut cfg = Config {
        verbose: true,
        ..Config::default()
    };
    if a.fresh {
        match std::fs::remove_dir_all(&cfg.cache_dir) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(Error::Io(format!("{}: {e}", cfg.cache_dir.display()))),
        }
    }
    if !a.cases.is_empty() {
        let known: Vec<&str> = cfg.cases.iter().map(|c| c.name).collect();
        if let Some(bad) = a.cases.iter().find(|n| !known.contains(&n.as_str())) {
            return Err(Error::invalid(
                "--case",
                bad,
                format!("one of {}", known.join(", ")),
            ));
        }
        cfg.cases.retain(|c| a.cases.iter().any(|n| n == c.name));
    }
    if a.quick {
        cfg.rtols = vec![1e-3, 1e-5, 1e-7];
        cfg.repeats = 1;
    }
    let mut rep = wp::run(&cfg)?;
    if a.peer {
        let case = cfg
            .cases
            .iter()
            .find(|c| c.name == "6205-2dof")
            .ok_or_else(|| Error::Io("no 6205-2dof case".into()))?;
        wp::export_for_peer(&cfg, case, &cfg.cache_dir)?;
        let status = std::process::Command::new("scripts/peer-scipy")
            .arg(&cfg.cache_dir)
            .status()
            .map_err(|e| Error::Io(format!("scripts/peer-scipy: {e}")))?;
        if !status.success() {
            return Err(Error::Io("scripts/peer-scipy failed".into()));
        }
        let p = Path::new(&cfg.cache_dir).join("6205-2dof-scipy.csv");
        let text =
            std::fs::read_to_string(&p).map_err(|e| Error::Io(format!("{}: {e}", p.display())))?;
        rep.peer = wp::read_peer_csv(&text)?;
    }
    rep.write(&out)?;
    Ok(format!(
        "wrote {}/work-precision.{{csv,md,png}}\n",
        out.display()
    ))
}
