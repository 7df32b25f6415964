//! Parameter sweeps: a base scene and axes of values, each run a pure function
//! run index → scene → summary row, so any executor (the `raceway sweep` threads, a
//! `--shard k/n` job array, the Python package and its Dask layer) maps the same index space
//! and gets the same rows.
//!
//! A sweep file (TOML):
//!
//! ```toml
//! scene = "../scenes/default.toml"   # relative to the sweep file; or a [scene] table;
//!                                    # neither: the embedded default scene
//! series = false                     # also write series/<index>.csv for every run
//!
//! [sample]                           # only for axes given by min/max
//! method = "lhs"                     # "lhs" (Latin hypercube) or "random"
//! n = 16
//! seed = 1
//!
//! [[axis]]
//! key = "inputs.speed_rpm"              # a scene field by its dotted TOML key
//! values = [1000.0, 2000.0]              # a list ...
//! [[axis]]
//! key = "run.duration_s"
//! start = 0.01                            # ... a range: start, stop and num (both ends
//! stop = 0.02                             #     included) or step
//! num = 3
//! [[axis]]
//! key = 'inputs.initial."shaft.y"'
//! min = -20e-6                            # ... or sampled in [min, max] by [sample]
//! max = -5e-6
//! ```
//!
//! The index space is the cartesian product of the list and range axes (the first axis
//! varies slowest) times the `[sample].n` samples of the min/max axes (sample index fastest).
//! Each point's values are written into the parsed base scene table, and the resulting scene
//! is checked exactly as `raceway scene --check` checks a file ([`schema::check`]).

mod exec;
mod file;
mod rows;
pub use exec::*;
use file::*;
pub use rows::*;
#[cfg(test)]
mod tests;

use crate::component::schema::{self, Problem};
use crate::component::Scene;
use crate::error::{Error, Result};
use crate::report::thread_cpu_s;
use crate::runner;
use serde_json::Value as Json;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Most points a sweep may have (a guard against a mistyped `num` or `n`).
pub const MAX_POINTS: usize = 10_000_000;

/// The values of one axis.
#[derive(Debug, Clone, PartialEq)]
pub enum AxisValues {
    /// Given or generated values (lists and ranges): a grid axis.
    List(Vec<toml::Value>),
    /// Sampled in `[min, max]` by the sweep's `[sample]` table.
    Sampled {
        /// Lower end.
        min: f64,
        /// Upper end.
        max: f64,
    },
}

/// One axis: a scene field and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The dotted TOML key as written (`inputs.initial."shaft.y"`).
    pub key: String,
    /// The key's segments (`["inputs", "initial", "shaft.y"]`).
    pub path: Vec<String>,
    /// Column name in the table: the segments joined by dots, then `_<unit>` when the field
    /// has a unit (`inputs.initial.shaft.y_m`).
    pub column: String,
    /// Values.
    pub values: AxisValues,
}

/// How the min/max axes are sampled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Independent uniform samples.
    Random,
    /// Latin hypercube: each axis's range cut into `n` equal strata, one sample in each.
    Lhs,
}

/// The `[sample]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct Sampling {
    /// Method.
    pub method: Method,
    /// Number of samples.
    pub n: usize,
    /// Seed of the generator.
    pub seed: u64,
}

/// A parsed and checked sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    /// The base scene as a TOML table.
    pub base: toml::Table,
    /// Axes, in file order.
    pub axes: Vec<Axis>,
    /// Sampling of the min/max axes.
    pub sampling: Option<Sampling>,
    /// Write each run's series too.
    pub series: bool,
    /// Latin-hypercube stratum of each sampled axis for each sample (`perms[axis][sample]`).
    perms: Vec<Vec<usize>>,
}

/// SplitMix64: a small, well-mixed, seedable generator (Steele, Lea & Flood, "Fast
/// splittable pseudorandom number generators", OOPSLA 2014); used as a hash of
/// (seed, axis, sample) so every sample is a pure function of its index.
fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A uniform number in [0, 1) from (seed, stream, k): 53 random bits.
fn uniform(seed: u64, stream: u64, k: u64) -> f64 {
    let h = splitmix(splitmix(splitmix(seed) ^ stream) ^ k);
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// A seeded permutation of 0..n (Fisher–Yates).
fn permutation(n: usize, seed: u64, stream: u64) -> Vec<usize> {
    let mut p: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        let j = (uniform(seed, stream ^ 0x5EED_0000_0000, i as u64) * (i + 1) as f64) as usize;
        p.swap(i, j.min(i));
    }
    p
}

impl Sweep {
    fn samples(&self) -> usize {
        self.sampling.as_ref().map_or(1, |s| s.n)
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.axes
            .iter()
            .map(|a| match &a.values {
                AxisValues::List(v) => v.len(),
                AxisValues::Sampled { .. } => 1,
            })
            .product::<usize>()
            * self.samples()
    }

    /// Whether the sweep has no point (never, once parsed).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The axes' values at point `index` (< [`Sweep::len`]), in axis order.
    pub fn point(&self, index: usize) -> Vec<toml::Value> {
        let s = self.samples();
        let (mut grid, j) = (index / s, index % s);
        let mut out = vec![toml::Value::Integer(0); self.axes.len()];
        for (k, a) in self.axes.iter().enumerate().rev() {
            out[k] = match &a.values {
                AxisValues::List(v) => {
                    let x = v[grid % v.len()].clone();
                    grid /= v.len();
                    x
                }
                AxisValues::Sampled { min, max } => {
                    let sp = self
                        .sampling
                        .as_ref()
                        .expect("checked: sampled axes have [sample]");
                    let u = uniform(sp.seed, k as u64, j as u64);
                    let f = match sp.method {
                        Method::Random => u,
                        Method::Lhs => (self.perms[k][j] as f64 + u) / sp.n as f64,
                    };
                    toml::Value::Float(min + (max - min) * f)
                }
            };
        }
        out
    }

    /// The scene text of point `index`: the base scene with the point's values written in.
    pub fn scene_text(&self, index: usize) -> Result<String> {
        let mut t = self.base.clone();
        for (a, v) in self.axes.iter().zip(self.point(index)) {
            set_path(&mut t, &a.path, v)?;
        }
        toml::to_string(&t).map_err(|e| Error::Parse {
            what: "sweep point".into(),
            message: e.to_string(),
        })
    }

    /// The scene of point `index`, checked as `raceway scene --check` checks a file (every
    /// problem in the error) up to building the component: the point's run builds it and
    /// reports its refusal as the point's error (building it here too cost a quasi-static
    /// point an eighth of its instructions).
    pub fn scene(&self, index: usize) -> Result<Scene> {
        let text = self.scene_text(index)?;
        schema::load_unbuilt(&text).map_err(|problems| {
            let list: Vec<String> = problems
                .iter()
                .map(|p| {
                    let mut p = p.clone();
                    p.line_col = None;
                    p.to_string()
                })
                .collect();
            Error::Parse {
                what: format!("the scene of sweep point {index}"),
                message: list.join("; "),
            }
        })
    }

    /// A fingerprint of what the sweep computes (base scene, axes, sampling): rows of one
    /// sweep are never mixed with another's.
    pub fn fingerprint(&self) -> String {
        let text = format!(
            "{}\n{:?}\n{:?}\n{}",
            toml::to_string(&self.base).unwrap_or_default(),
            self.axes,
            self.sampling,
            self.series
        );
        // FNV-1a, 64 bits.
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for b in text.bytes() {
            h = (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3);
        }
        format!("{h:016x}")
    }
}

/// One finished point.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Row {
    /// Run index.
    pub index: usize,
    /// (column, value) of each axis.
    pub axes: Vec<(String, Json)>,
    /// Why the run failed, if it did.
    pub error: Option<String>,
    /// (column, value) of the flattened summary (empty when the run failed).
    pub summary: Vec<(String, Json)>,
}

/// How a sweep is executed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Exec {
    /// Worker threads (>= 1).
    pub jobs: usize,
    /// `(k, n)`: run the indices `i` with `i % n == k` (0-based `k`).
    pub shard: (usize, usize),
}

/// What an execution did.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// Points of the whole sweep.
    pub total: usize,
    /// Points of this shard.
    pub in_shard: usize,
    /// Points run now.
    pub ran: usize,
    /// Points of this shard found finished and skipped.
    pub skipped: usize,
    /// Failed rows among those run now.
    pub failed: usize,
    /// Finished rows in the folder (all shards that wrote there).
    pub finished: usize,
    /// Thread CPU time of the runs made now, s (sum over threads).
    pub cpu_s: f64,
}
