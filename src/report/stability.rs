//! Stability campaign: over model levels, speeds, loads, clearances, ball materials, macro
//! steps and step inputs, every cell must either give finite outputs that converge under
//! refinement (rtol and rtol/10 agree) or end in a clean error (an `Err` naming the cause):
//! never a panic, never a NaN. The axes follow numerics.md §5.5.
//!
//! A cell is data ([`Cell`]); the level bases are a table ([`BASES`]); a new level is one
//! more row there.

use super::{drive, InputEvent, Samples};
use crate::component::Component;
use crate::contact::{Curvature, PointContact, Race};
use crate::error::Result;
use crate::geometry::preset;
use std::fmt::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// A level base: how a cell's scene is built for that level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Base {
    /// Label.
    pub name: &'static str,
    /// Bearing preset.
    pub preset: &'static str,
    /// Scene `[model]` lines (level, dof, causality, damping, mass).
    pub model: &'static str,
    /// Load-driven (`load.*` inputs) or motion-driven (`shaft.*` inputs).
    pub load_driven: bool,
    /// Axial share of the load (angular-contact bearings are seated axially).
    pub axial_share: f64,
    /// Whether the clearance axis applies (angular-contact presets derive their conformity
    /// from their own clearance and refuse a preload as a clearance: they keep theirs).
    pub clearance_axis: bool,
}

/// The level bases. Add a row for a new level.
pub const BASES: &[Base] = &[
    Base {
        name: "ring-2dof/load",
        preset: "6205",
        model: "level = \"ring\"\nring_dof = 2\ncausality = \"load\"\ncontact_damping = 3000.0\nattached_mass_kg = 1.0\n",
        load_driven: true,
        axial_share: 0.0,
        clearance_axis: true,
    },
    Base {
        name: "ring-5dof/load",
        preset: "6205",
        model: "level = \"ring\"\nring_dof = 5\ncausality = \"load\"\ncontact_damping = 3000.0\nattached_mass_kg = 1.0\n",
        load_driven: true,
        axial_share: 0.5,
        clearance_axis: true,
    },
    Base {
        name: "ring-5dof/load 7008CE",
        preset: "7008ce",
        model: "level = \"ring\"\nring_dof = 5\ncausality = \"load\"\ncontact_damping = 3000.0\nattached_mass_kg = 1.0\n",
        load_driven: true,
        axial_share: 0.5,
        clearance_axis: false,
    },
    Base {
        name: "ring-2dof/motion",
        preset: "6205",
        model: "level = \"ring\"\nring_dof = 2\ncausality = \"motion\"\ncontact_damping = 3000.0\n",
        load_driven: false,
        axial_share: 0.0,
        clearance_axis: true,
    },
    Base {
        name: "quasi_static/load",
        preset: "6205",
        model: "level = \"quasi_static\"\ncausality = \"load\"\ncontact_damping = 3000.0\nattached_mass_kg = 1.0\n",
        load_driven: true,
        axial_share: 0.0,
        clearance_axis: true,
    },
    Base {
        name: "quasi_static/motion",
        preset: "6205",
        model: "level = \"quasi_static\"\ncausality = \"motion\"\n",
        load_driven: false,
        axial_share: 0.0,
        clearance_axis: true,
    },
    Base {
        name: "linear/load",
        preset: "6205",
        model: "level = \"linear\"\ncausality = \"load\"\ncontact_damping = 3000.0\nattached_mass_kg = 1.0\n",
        load_driven: true,
        axial_share: 0.0,
        clearance_axis: true,
    },
];

/// Shaft speed axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Speed {
    /// Standing still.
    Zero,
    /// From rest, ramped to 1750 rpm over the window (input derivatives).
    FromRest,
    /// Reversed: -1750 rpm.
    Reverse,
    /// 1750 rpm.
    Nominal,
    /// 120 000 rpm.
    Max,
}

impl Speed {
    /// All values.
    pub const ALL: [Speed; 5] = [
        Speed::Zero,
        Speed::FromRest,
        Speed::Reverse,
        Speed::Nominal,
        Speed::Max,
    ];
    fn label(self) -> &'static str {
        match self {
            Speed::Zero => "0",
            Speed::FromRest => "0→1750 ramp",
            Speed::Reverse => "-1750",
            Speed::Nominal => "1750",
            Speed::Max => "120000",
        }
    }
    fn rad_s(self) -> f64 {
        let n = 1750.0 * std::f64::consts::PI / 30.0;
        match self {
            Speed::Zero | Speed::FromRest => 0.0,
            Speed::Reverse => -n,
            Speed::Nominal => n,
            Speed::Max => 120_000.0 * std::f64::consts::PI / 30.0,
        }
    }
}

/// Load axis (radial load on the inner ring; motion-driven levels get the Stribeck
/// deflection of that load).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Load {
    /// No load.
    Zero,
    /// 10 N.
    Light,
    /// 1 kN.
    Nominal,
    /// The radial load that gives a 4 GPa peak Hertz pressure (Stribeck's `Q_max`).
    Gpa4,
}

impl Load {
    /// All values.
    pub const ALL: [Load; 4] = [Load::Zero, Load::Light, Load::Nominal, Load::Gpa4];
    fn label(self) -> &'static str {
        match self {
            Load::Zero => "0",
            Load::Light => "10 N",
            Load::Nominal => "1 kN",
            Load::Gpa4 => "4 GPa",
        }
    }
}

/// Diametral clearance axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Clearance {
    /// -5 µm (preload).
    Preload,
    /// 0.
    Zero,
    /// 40 µm.
    Large,
}

impl Clearance {
    /// All values.
    pub const ALL: [Clearance; 3] = [Clearance::Preload, Clearance::Zero, Clearance::Large];
    fn um(self) -> f64 {
        match self {
            Clearance::Preload => -5.0,
            Clearance::Zero => 0.0,
            Clearance::Large => 40.0,
        }
    }
}

/// Ball materials.
pub const MATERIALS: [&str; 3] = ["steel", "si3n4", "zro2"];
/// Macro steps, s.
pub const MACRO_STEPS: [f64; 5] = [1e-6, 1e-5, 1e-4, 1e-3, 1e-2];

/// One cell of the matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    /// Level base.
    pub base: &'static Base,
    /// Speed.
    pub speed: Speed,
    /// Load.
    pub load: Load,
    /// Clearance.
    pub clearance: Clearance,
    /// Ball material.
    pub ball: &'static str,
    /// Macro step, s.
    pub h: f64,
    /// A step input at mid-window (load +1 kN, or the shaft 5 µm further, and the speed
    /// reversed).
    pub step_input: bool,
}

/// What a cell gave.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// Finite outputs; `diff` is the RMS difference of the forces between rtol and rtol/10
    /// relative to their RMS (or 1 N); `max_pressure` the `contact.max_pressure` output at
    /// the end of the window (the larger of the runs), Pa.
    Converged {
        /// Refinement difference.
        diff: f64,
        /// Largest peak pressure, Pa.
        max_pressure: f64,
    },
    /// Finite outputs that agree pointwise only at rtol 1e-7 vs 1e-8 (`tight` true), or
    /// only in statistics (`tight` false: mean and RMS of each force component agree within
    /// [`STATISTICS_LIMIT`] while the trajectories separate, as impacting or chaotic motion
    /// in the clearance does after a few Lyapunov times, numerics.md §6.4).
    Statistical {
        /// Pointwise difference rtol 1e-7 vs 1e-8 (tight) or of the statistics.
        diff: f64,
        /// Whether the tight pair converged pointwise.
        tight: bool,
        /// Largest peak pressure, Pa.
        max_pressure: f64,
    },
    /// A clean refusal (an `Err` with its message).
    CleanError(String),
    /// A panic, a non-finite output or no convergence under refinement.
    Failed(String),
}

impl Outcome {
    /// A pass is a convergence or a clean error.
    pub fn passed(&self) -> bool {
        !matches!(self, Outcome::Failed(_))
    }
}

/// Refinement difference above which a cell counts as not converging.
pub const CONVERGENCE_LIMIT: f64 = 1e-2;
/// Largest relative difference of the force statistics (mean, RMS) in a statistical pass.
pub const STATISTICS_LIMIT: f64 = 0.05;

/// Relative RMS difference of two force series (over their RMS, or 1 N).
fn pointwise(a: &Samples, b: &Samples) -> f64 {
    let n = b.f.len().max(1) as f64;
    let (mut d2, mut f2) = (0.0, 0.0);
    for (x, y) in a.f.iter().zip(&b.f) {
        for k in 0..3 {
            d2 += (x[k] - y[k]).powi(2);
            f2 += y[k] * y[k];
        }
    }
    (d2 / n).sqrt() / (f2 / n).sqrt().max(1.0)
}

/// Largest relative difference of the per-component mean and RMS over the second half of
/// the window (scale: the RMS force, or 1 N).
fn statistics(a: &Samples, b: &Samples) -> f64 {
    let stats = |s: &Samples| {
        let h = &s.f[s.f.len() / 2..];
        let n = h.len().max(1) as f64;
        let mut m = [0.0; 3];
        let mut r = [0.0; 3];
        for f in h {
            for k in 0..3 {
                m[k] += f[k] / n;
                r[k] += f[k] * f[k] / n;
            }
        }
        (m, r.map(f64::sqrt))
    };
    let ((ma, ra), (mb, rb)) = (stats(a), stats(b));
    let scale = rb.iter().map(|x| x * x).sum::<f64>().sqrt().max(1.0);
    (0..3)
        .map(|k| ((ma[k] - mb[k]).abs()).max((ra[k] - rb[k]).abs()) / scale)
        .fold(0.0, f64::max)
}

/// The nominal cell of `base`.
pub fn nominal(base: &'static Base) -> Cell {
    Cell {
        base,
        speed: Speed::Nominal,
        load: Load::Nominal,
        clearance: Clearance::Zero,
        ball: "steel",
        h: 1e-4,
        step_input: false,
    }
}

/// Radial load giving a 4 GPa peak pressure in `preset` with steel balls: the ball load
/// `Q` with `p_max(Q) = 4 GPa` (Hertz, inner contact) times `Z / 4.37` (Stribeck, Harris &
/// Kotzalas §7.2, zero clearance).
pub fn load_for_pressure(preset_name: &str, p: f64) -> Result<f64> {
    let b = preset(preset_name)?.build()?;
    let a = b.nominal_contact_angle();
    let c = PointContact::new(
        Curvature::ball_race(b.d, b.dm, a, b.fi, Race::Inner),
        b.e_eff_inner(),
    );
    let (mut lo, mut hi) = (1.0f64, 1e6f64);
    for _ in 0..100 {
        let mid = (lo * hi).sqrt();
        if c.peak_pressure(mid) < p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(lo * b.z as f64 / 4.37 / a.cos())
}

impl Cell {
    fn radial_load(&self) -> Result<f64> {
        Ok(match self.load {
            Load::Zero => 0.0,
            Load::Light => 10.0,
            Load::Nominal => 1000.0,
            Load::Gpa4 => load_for_pressure(self.base.preset, 4e9)?,
        })
    }

    /// Radial shaft displacement of a motion-driven cell: half the clearance plus the
    /// Stribeck deflection `(F / (Z K_n J_r))^(2/3)`, `J_r(0.5) = 0.2288` (Harris §7.2).
    fn displacement(&self, c: &Component) -> Result<f64> {
        let b = c.bearing();
        let f = self.radial_load()?;
        let kn =
            crate::models::ring::RingModel::new(b, crate::models::ring::RingDof::Two, 0.0).kn();
        Ok(0.5 * b.pd + (f / (b.z as f64 * kn * 0.2288)).powf(2.0 / 3.0))
    }

    /// The scene text of the cell at `rtol`.
    pub fn scene(&self, rtol: f64) -> String {
        let rule = if self.speed == Speed::FromRest {
            "derivatives"
        } else {
            "velocity"
        };
        let clearance = if self.base.clearance_axis {
            format!("clearance_um = {:?}, ", self.clearance.um())
        } else {
            String::new()
        };
        format!(
            "title = \"stability cell\"\n\
             bearing = {{ preset = \"{}\", {clearance}materials = {{ ball = \"{}\" }} }}\n\
             [model]\n{}\
             [solver]\nrtol = {:e}\natol_m = {:e}\nmax_substeps = 200000\n\
             [inputs]\nrule = \"{rule}\"\n",
            self.base.preset,
            self.ball,
            self.base.model,
            rtol,
            1e-4 * rtol,
        )
    }

    /// The window simulated, s.
    pub fn window(&self, t_base: f64) -> f64 {
        t_base.max(2.0 * self.h)
    }

    fn run_once(&self, rtol: f64, t_end: f64) -> Result<(Samples, f64)> {
        let mut c = Component::from_text(&self.scene(rtol))?;
        let set = |c: &mut Component, n: &str, v: f64| -> Result<()> {
            let vr = crate::component::variables::by_name(n)
                .expect("a variable of the table")
                .vr;
            c.set_real(vr, v)
        };
        let f = self.radial_load()?;
        let omega = self.speed.rad_s();
        set(&mut c, "shaft.omega", omega)?;
        let mut events = Vec::new();
        if self.base.load_driven {
            for n in ["load.x", "load.mx", "load.my"] {
                set(&mut c, n, 0.0)?;
            }
            set(&mut c, "load.y", -f)?;
            set(&mut c, "load.z", self.base.axial_share * f)?;
            if self.step_input {
                events.push(InputEvent {
                    t: 0.5 * t_end,
                    name: "load.y".into(),
                    value: -f - 1000.0,
                });
            }
        } else {
            for n in [
                "shaft.x", "shaft.z", "shaft.rx", "shaft.ry", "shaft.vx", "shaft.vy", "shaft.vz",
                "shaft.wx", "shaft.wy",
            ] {
                set(&mut c, n, 0.0)?;
            }
            let y = self.displacement(&c)?;
            set(&mut c, "shaft.y", -y)?;
            if self.step_input {
                events.push(InputEvent {
                    t: 0.5 * t_end,
                    name: "shaft.y".into(),
                    value: -y - 5e-6,
                });
            }
        }
        if self.step_input {
            events.push(InputEvent {
                t: 0.5 * t_end,
                name: "shaft.omega".into(),
                value: -omega,
            });
        }
        let ramp = (self.speed == Speed::FromRest)
            .then(|| ("shaft.omega", Speed::Nominal.rad_s() / t_end));
        let (s, _) = drive(&mut c, t_end, self.h, &events, ramp)?;
        let vr = crate::component::variables::by_name("contact.max_pressure")
            .expect("in the table")
            .vr;
        Ok((s, c.get_real(vr)?))
    }

    /// Run the cell: at rtol 1e-6 and 1e-7 over `window(t_base)`.
    pub fn run(&self, t_base: f64) -> Outcome {
        let t_end = self.window(t_base);
        let r = catch_unwind(AssertUnwindSafe(|| {
            let a = self.run_once(1e-6, t_end)?;
            let b = self.run_once(1e-7, t_end)?;
            Ok::<_, crate::Error>((a, b))
        }));
        let ((sa, pa), (sb, pb)) = match r {
            Err(p) => {
                let msg = p
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                return Outcome::Failed(format!("panic: {msg}"));
            }
            Ok(Err(e)) => return Outcome::CleanError(e.to_string()),
            Ok(Ok(v)) => v,
        };
        let finite =
            |s: &Samples, p: f64| s.f.iter().flatten().all(|v| v.is_finite()) && p.is_finite();
        if !(finite(&sa, pa) && finite(&sb, pb)) {
            return Outcome::Failed("non-finite output".into());
        }
        let diff = pointwise(&sa, &sb);
        if diff <= CONVERGENCE_LIMIT {
            return Outcome::Converged {
                diff,
                max_pressure: pa.max(pb),
            };
        }
        // One more refinement: converging late, or separating trajectories?
        let (sc, pc) = match catch_unwind(AssertUnwindSafe(|| self.run_once(1e-8, t_end))) {
            Ok(Ok(v)) => v,
            Ok(Err(e)) => return Outcome::CleanError(e.to_string()),
            Err(_) => return Outcome::Failed("panic at rtol 1e-8".into()),
        };
        if !finite(&sc, pc) {
            return Outcome::Failed("non-finite output at rtol 1e-8".into());
        }
        let tight = pointwise(&sb, &sc);
        let max_pressure = pa.max(pb).max(pc);
        if tight <= CONVERGENCE_LIMIT {
            return Outcome::Statistical {
                diff: tight,
                tight: true,
                max_pressure,
            };
        }
        let st = statistics(&sb, &sc).max(statistics(&sa, &sc));
        if st <= STATISTICS_LIMIT {
            return Outcome::Statistical {
                diff: st,
                tight: false,
                max_pressure,
            };
        }
        Outcome::Failed(format!(
            "no convergence: rtol 1e-6/1e-7/1e-8 differ pointwise by {diff:.2e}/{tight:.2e} and in mean/RMS by {st:.2e}"
        ))
    }
}

/// The cells of the campaign. `long`: for every level base the full product of speed,
/// load, clearance and ball material at 1e-4 s, plus the macro-step sweep with and
/// without a step input at each speed. Otherwise a sample: one factor at a time around
/// each base's nominal cell, plus a few corners.
pub fn matrix(long: bool) -> Vec<Cell> {
    let mut v = Vec::new();
    for base in BASES {
        let n = nominal(base);
        if long {
            for speed in Speed::ALL {
                for load in Load::ALL {
                    for clearance in Clearance::ALL {
                        if !base.clearance_axis && clearance != Clearance::Zero {
                            continue;
                        }
                        for ball in MATERIALS {
                            v.push(Cell {
                                speed,
                                load,
                                clearance,
                                ball,
                                ..n
                            });
                        }
                    }
                }
                for h in MACRO_STEPS {
                    for step_input in [false, true] {
                        v.push(Cell {
                            speed,
                            h,
                            step_input,
                            ..n
                        });
                    }
                }
            }
        } else {
            v.push(n);
            v.extend(Speed::ALL.iter().map(|&speed| Cell { speed, ..n }));
            v.extend(Load::ALL.iter().map(|&load| Cell { load, ..n }));
            if base.clearance_axis {
                v.extend(
                    Clearance::ALL
                        .iter()
                        .map(|&clearance| Cell { clearance, ..n }),
                );
            }
            v.extend(MATERIALS.iter().map(|&ball| Cell { ball, ..n }));
            v.extend(MACRO_STEPS.iter().map(|&h| Cell { h, ..n }));
            v.push(Cell {
                step_input: true,
                ..n
            });
            // Corners: fastest, hardest, stiffest; and a free ring at rest.
            let (tight, loose) = if base.clearance_axis {
                (Clearance::Preload, Clearance::Large)
            } else {
                (Clearance::Zero, Clearance::Zero)
            };
            v.push(Cell {
                speed: Speed::Max,
                load: Load::Gpa4,
                clearance: tight,
                ball: "si3n4",
                ..n
            });
            v.push(Cell {
                speed: Speed::Zero,
                load: Load::Zero,
                clearance: loose,
                ..n
            });
        }
    }
    v.dedup();
    // Remove repeats (the nominal cell appears once per axis).
    let mut out: Vec<Cell> = Vec::new();
    for c in v {
        if !out.contains(&c) {
            out.push(c);
        }
    }
    out
}

/// Run `cells` over a base window `t_base` (s). Returns each cell with its outcome.
pub fn run(cells: &[Cell], t_base: f64, verbose: bool) -> Vec<(Cell, Outcome)> {
    cells
        .iter()
        .map(|c| {
            let o = c.run(t_base);
            if verbose {
                println!("{} -> {}", row_cells(c), outcome_text(&o));
            }
            (*c, o)
        })
        .collect()
}

fn row_cells(c: &Cell) -> String {
    format!(
        "{} | {} | {} | {} | {} | {:.0e} | {}",
        c.base.name,
        c.speed.label(),
        c.load.label(),
        if c.base.clearance_axis {
            format!("{} µm", c.clearance.um())
        } else {
            "preset".into()
        },
        c.ball,
        c.h,
        if c.step_input { "yes" } else { "" }
    )
}

fn outcome_text(o: &Outcome) -> String {
    match o {
        Outcome::Converged { diff, max_pressure } => {
            format!("converged | {diff:.1e} | {:.2}", max_pressure / 1e9)
        }
        Outcome::Statistical {
            diff,
            tight,
            max_pressure,
        } => format!(
            "{} | {diff:.1e} | {:.2}",
            if *tight {
                "converged from rtol 1e-7 (1e-7 vs 1e-8)"
            } else {
                "converged in mean/RMS only (trajectories separate)"
            },
            max_pressure / 1e9
        ),
        Outcome::CleanError(m) => format!("clean error: {} | | ", m.replace('|', "/")),
        Outcome::Failed(m) => format!("**FAILED**: {} | | ", m.replace('|', "/")),
    }
}

/// The Markdown page of a campaign.
pub fn markdown(results: &[(Cell, Outcome)], t_base: f64, command: &str) -> String {
    let n = results.len();
    let conv = results
        .iter()
        .filter(|(_, o)| matches!(o, Outcome::Converged { .. }))
        .count();
    let clean = results
        .iter()
        .filter(|(_, o)| matches!(o, Outcome::CleanError(_)))
        .count();
    let stat = results
        .iter()
        .filter(|(_, o)| matches!(o, Outcome::Statistical { .. }))
        .count();
    let failed = n - conv - clean - stat;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# Stability campaign\n\n\
         Generated by `{command}` on {}.\n\n\
         Every cell runs the component through its public API over max({t_base} s, 2 macro \
         steps) at rtol 1e-6 and again at 1e-7 (atol_m = 1e-4 m × rtol, DOPRI5). It passes if \
         the outputs are finite and the two runs' forces differ by less than \
         {CONVERGENCE_LIMIT:.0e} (RMS difference over RMS force, or over 1 N when the forces \
         are smaller), or if the component refuses cleanly with an error naming the cause. \
         A panic, a NaN or a run that does not converge is a failure.\n\n\
         Axes (numerics.md §5.5): level; speed (standing, ramped from rest through input \
         derivatives, reversed, 1750 rpm, 120 000 rpm); radial load (0, 10 N, 1 kN, the load \
         whose Stribeck ball load gives a 4 GPa Hertz peak; motion-driven levels get the \
         Stribeck deflection of that load plus half the clearance; the 5-DOF base adds half \
         the load axially); diametral clearance (-5 µm preload, 0, 40 µm); ball material \
         (steel, Si3N4, ZrO2, rings steel); macro step; a step input at mid-window (load \
         +1 kN or the shaft 5 µm further, and the speed reversed).\n\n\
         When rtol 1e-6 and 1e-7 disagree, a third run at 1e-8 decides: converged from \
         1e-7 (1e-7 and 1e-8 agree pointwise), converged in statistics (mean and RMS of each \
         force over the second half agree within {STATISTICS_LIMIT} of the RMS force while \
         the trajectories separate: impacts in the clearance, numerics.md §6.4), or failed.\n\n\
         **{n} cells: {conv} converged, {stat} converged late or in statistics, {clean} clean \
         errors, {failed} failed.**\n",
        super::Machine::detect().describe()
    );
    s += "| level | speed (rpm) | load | clearance | ball | H (s) | step input | outcome | refinement diff | peak contact pressure at the end (GPa) |\n\
          |---|---|---|---|---|---|---|---|---|---|\n";
    for (c, o) in results {
        let _ = writeln!(s, "| {} | {} |", row_cells(c), outcome_text(o));
    }
    s
}

/// The whole campaign as the CLI runs it: the sampled (`long = false`, 5 ms windows) or
/// the long matrix (20 ms windows), its page written to `dir/stability.md`. Returns the
/// results (check [`Outcome::passed`]).
pub fn campaign(long: bool, dir: &std::path::Path, verbose: bool) -> Result<Vec<(Cell, Outcome)>> {
    let t_base = if long { 0.02 } else { 0.005 };
    let cells = matrix(long);
    if verbose {
        println!("stability campaign: {} cells", cells.len());
    }
    let res = run(&cells, t_base, verbose);
    let cmd = if long {
        "cargo run --release -- bench --stability --long"
    } else {
        "cargo run --release -- bench --stability"
    };
    super::write_file(&dir.join("stability.md"), &markdown(&res, t_base, cmd))?;
    Ok(res)
}
