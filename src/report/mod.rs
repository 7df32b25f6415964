//! Reports on what a run costs and what it is worth: work-precision (error bought per
//! second of run time, [`work_precision`]) and the stability campaign ([`stability`]).
//!
//! Methodology after docs/physics.md §N6 (DiffEqDevTools' `WorkPrecisionSet`; Hairer, Nørsett &
//! Wanner, *Solving ODEs I*, §II.10 "numerical comparisons"): reference solutions by two
//! different methods at tight tolerance, their difference as the error floor, the median of
//! repeated timings after a warm-up, and the hardware-independent counters beside the time.
//!
//! Everything here drives the public [`Component`] exactly as a host
//! would (`set_real`, `do_step`, `get_real`): the numbers describe the product, not a
//! side path.

pub mod stability;
pub mod work_precision;

use crate::component::{variables, Component, Stats};
use crate::error::{Error, Result};
use std::path::Path;

/// Variable names of the reaction forces compared by the error metric.
pub const FORCE_NAMES: [&str; 3] = ["force.x", "force.y", "force.z"];

/// Reaction forces sampled at every communication point.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Samples {
    /// Communication times, s.
    pub t: Vec<f64>,
    /// `(Fx, Fy, Fz)` at each time, N.
    pub f: Vec<[f64; 3]>,
}

impl Samples {
    /// CSV text (`t,fx,fy,fz`), every number in Rust's shortest round-trip form, so
    /// [`Samples::from_csv`] gives back the same bits.
    pub fn to_csv(&self) -> String {
        let mut s = String::from("t,fx,fy,fz\n");
        for (t, f) in self.t.iter().zip(&self.f) {
            s += &format!("{t:?},{:?},{:?},{:?}\n", f[0], f[1], f[2]);
        }
        s
    }

    /// Parse text written by [`Samples::to_csv`].
    pub fn from_csv(text: &str) -> Result<Samples> {
        let mut out = Samples::default();
        for (i, line) in text.lines().enumerate().skip(1) {
            let v: Vec<f64> = line
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<std::result::Result<_, _>>()
                .map_err(|e| Error::Parse {
                    what: format!("samples line {}", i + 1),
                    message: e.to_string(),
                })?;
            if v.len() != 4 {
                return Err(Error::Parse {
                    what: format!("samples line {}", i + 1),
                    message: format!("{} fields, expected 4", v.len()),
                });
            }
            out.t.push(v[0]);
            out.f.push([v[1], v[2], v[3]]);
        }
        Ok(out)
    }
}

/// Error of `run` against `reference` (same communication times):
/// `(relative L2 over the window, relative peak)` with
/// `L2 = sqrt(sum |F - F_ref|^2 / sum |F_ref|^2)` and
/// `peak = max |F - F_ref| / max |F_ref|` (Euclidean norm over the force components;
/// docs/physics.md §N6.2, metric 1: reaction forces at communication points).
pub fn force_error(run: &Samples, reference: &Samples) -> Result<(f64, f64)> {
    if run.t.len() != reference.t.len()
        || run
            .t
            .iter()
            .zip(&reference.t)
            .any(|(a, b)| (a - b).abs() > 1e-9 * (1.0 + b.abs()))
    {
        return Err(Error::invalid(
            "samples",
            run.t.len(),
            format!("the reference's {} communication times", reference.t.len()),
        ));
    }
    let (mut num, mut den, mut peak_e, mut peak_r) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for (a, r) in run.f.iter().zip(&reference.f) {
        let e2: f64 = (0..3).map(|k| (a[k] - r[k]).powi(2)).sum();
        let r2: f64 = r.iter().map(|x| x * x).sum();
        num += e2;
        den += r2;
        peak_e = peak_e.max(e2.sqrt());
        peak_r = peak_r.max(r2.sqrt());
    }
    if den <= 0.0 {
        return Err(Error::invalid(
            "reference",
            "all forces zero",
            "a reference with a force",
        ));
    }
    Ok(((num / den).sqrt(), peak_e / peak_r))
}

/// An input change at a communication time (a step input, or a ramp set through input
/// derivatives).
#[derive(Debug, Clone, PartialEq)]
pub struct InputEvent {
    /// Time at which it applies, s (applied before the step that starts at or after it).
    pub t: f64,
    /// Variable name.
    pub name: String,
    /// New value.
    pub value: f64,
}

/// Drive `c` from 0 to `t_end` at macro step `h` (the last step shortened to land on
/// `t_end`), applying `events` when their time comes, and `ramp` (variable, rate) as a
/// linear input with its first derivative (input rule `derivatives`). Returns the forces at
/// every communication point, and the thread CPU time spent stepping, s (setup excluded).
pub fn drive(
    c: &mut Component,
    t_end: f64,
    h: f64,
    events: &[InputEvent],
    ramp: Option<(&str, f64)>,
) -> Result<(Samples, f64)> {
    let (s, cpu, _) = drive_until(c, t_end, h, events, ramp, |_, _| Ok(None))?;
    Ok((s, cpu))
}

/// [`drive`]'s loop with a check after every macro step: `check(c, t)` (t = the
/// communication point just reached, s) returns `Some(reason)` to stop the run there.
/// Returns the forces up to the stop, the thread CPU time spent (checks included), s, and
/// the reason it stopped early, if it did.
pub(crate) fn drive_until(
    c: &mut Component,
    t_end: f64,
    h: f64,
    events: &[InputEvent],
    ramp: Option<(&str, f64)>,
    mut check: impl FnMut(&mut Component, f64) -> Result<Option<String>>,
) -> Result<(Samples, f64, Option<String>)> {
    let vr = |n: &str| {
        variables::by_name(n)
            .map(|v| v.vr)
            .ok_or_else(|| Error::invalid("variable", n, "a variable of the table"))
    };
    let fvr = [
        vr(FORCE_NAMES[0])?,
        vr(FORCE_NAMES[1])?,
        vr(FORCE_NAMES[2])?,
    ];
    let ramp = match ramp {
        Some((n, rate)) => Some((vr(n)?, rate)),
        None => None,
    };
    let evr: Vec<u32> = events.iter().map(|e| vr(&e.name)).collect::<Result<_>>()?;
    let n = (t_end / h - 1e-9).ceil().max(1.0) as usize;
    let mut s = Samples {
        t: Vec::with_capacity(n),
        f: Vec::with_capacity(n),
    };
    let mut next_event = 0;
    let start = thread_cpu_s();
    for i in 0..n {
        let t = i as f64 * h;
        let step = if i + 1 == n { t_end - t } else { h };
        while next_event < events.len() && events[next_event].t <= t + 1e-12 {
            c.set_real(evr[next_event], events[next_event].value)?;
            next_event += 1;
        }
        if let Some((v, rate)) = ramp {
            c.set_real(v, rate * t)?;
            c.set_input_derivative(v, 1, rate)?;
        }
        c.do_step(t, step)?;
        s.t.push(t + step);
        s.f.push([
            c.get_real(fvr[0])?,
            c.get_real(fvr[1])?,
            c.get_real(fvr[2])?,
        ]);
        if let Some(stop) = check(c, t + step)? {
            return Ok((s, thread_cpu_s() - start, Some(stop)));
        }
    }
    Ok((s, thread_cpu_s() - start, None))
}

/// [`drive`] straight through: the whole window `[0, t_end]` in one
/// [`Component::step_through`] call (the integrator takes its own steps), the forces at the
/// communication points from its dense output. `t_end` must be a whole number of steps `h`
/// (to 1e-9). Returns the forces and the thread CPU time of the call, which includes
/// computing the forces at every point, s.
pub fn drive_through(c: &mut Component, t_end: f64, h: f64) -> Result<(Samples, f64)> {
    let n = (t_end / h).round().max(1.0) as usize;
    if (n as f64 * h - t_end).abs() > 1e-9 * t_end.abs().max(h) {
        return Err(Error::invalid(
            "t_end",
            t_end,
            format!("a whole number of communication steps of {h} s"),
        ));
    }
    let mut fvr = [0u32; 3];
    for (v, name) in fvr.iter_mut().zip(FORCE_NAMES) {
        *v = variables::by_name(name)
            .map(|v| v.vr)
            .ok_or_else(|| Error::invalid("variable", name, "a variable of the table"))?;
    }
    let mut out = Vec::new();
    let start = thread_cpu_s();
    c.step_through(0.0, h, n, &fvr, &mut out)?;
    let cpu = thread_cpu_s() - start;
    let s = Samples {
        t: (1..=n).map(|k| k as f64 * h).collect(),
        f: out.chunks_exact(3).map(|r| [r[0], r[1], r[2]]).collect(),
    };
    Ok((s, cpu))
}

pub use crate::counters::thread_cpu_s;

/// The 1-, 5- and 15-minute load averages (`/proc/loadavg`), e.g. `"1.52 1.10 0.80"`, or
/// `"unknown"`: printed beside every timing, since a load above the core count means the
/// measured thread shared its core (its CPU time stays honest, its caches less so).
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

/// Median of a non-empty list.
pub fn median(v: &mut [f64]) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// The machine a report was measured on.
#[derive(Debug, Clone, PartialEq)]
pub struct Machine {
    /// CPU model (from /proc/cpuinfo).
    pub cpu: String,
    /// Logical cores.
    pub cores: usize,
    /// `rustc --version`.
    pub rustc: String,
    /// Crate version.
    pub version: &'static str,
    /// Build profile of the measuring binary.
    pub profile: &'static str,
    /// 1-, 5- and 15-minute load averages when measured (/proc/loadavg): a shared machine
    /// with a load above its core count makes timings noisy.
    pub load: String,
}

impl Machine {
    /// Describe this machine.
    pub fn detect() -> Machine {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split(':').nth(1))
                    .map(|s| s.trim().to_string())
            })
            .unwrap_or_else(|| "unknown".into());
        let rustc = std::process::Command::new(std::env::var("RUSTC").unwrap_or("rustc".into()))
            .arg("--version")
            .output()
            .ok()
            .and_then(|o| String::from_utf8(o.stdout).ok())
            .map(|s| s.trim().to_string())
            .filter(|s| !s.is_empty())
            .unwrap_or_else(|| "unknown".into());
        let load = load_average();
        Machine {
            load,
            cpu,
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            rustc,
            version: env!("CARGO_PKG_VERSION"),
            profile: if cfg!(debug_assertions) {
                "debug"
            } else {
                "release"
            },
        }
    }

    /// One line.
    pub fn describe(&self) -> String {
        format!(
            "{} ({} logical cores, load average {} when measured), {}, raceway {} ({} build), single thread",
            self.cpu, self.cores, self.load, self.rustc, self.version, self.profile
        )
    }
}

/// Counters of a run as a short string.
pub fn stats_line(s: &Stats) -> String {
    format!(
        "rhs {} jac {} lu {} acc {} rej {}",
        s.rhs, s.jacobians, s.factorizations, s.accepted, s.rejected
    )
}

pub(crate) fn write_file(path: &Path, text: &str) -> Result<()> {
    if let Some(d) = path.parent() {
        std::fs::create_dir_all(d).map_err(|e| Error::Io(format!("{}: {e}", d.display())))?;
    }
    crate::fsutil::write_atomic(path, text)
        .map_err(|e| Error::Io(format!("{}: {e}", path.display())))
}
