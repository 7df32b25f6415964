//! Stability campaign: over model levels, speeds, loads, clearances, ball materials, macro
//! steps and step inputs, every cell must either give finite outputs that converge under
//! refinement (rtol and rtol/10 agree) or end in a clean error (an `Err` naming the cause):
//! never a panic, never a NaN. The axes follow docs/physics.md §N5.5.
//!
//! A cell is data ([`Cell`]); the level bases are a table ([`BASES`]); a new level is one
//! more row there.

use super::{InputEvent, Samples};
use crate::component::Component;
use crate::contact::{Curvature, PointContact, Race};
use crate::error::Result;
use crate::geometry::preset;
use std::fmt::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};

// --- Bearing sets: their cells in a block of their own.
#[path = "stability_sets.rs"]
pub mod sets;
// --- end of the sets' block.

/// Input values by variable name.
type Inputs = Vec<(&'static str, f64)>;

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
    /// Longest window of this base's cells, s (`f64::INFINITY`: the campaign's window).
    /// The dynamic levels cost 10 to 1000 times a ring cell per simulated second.
    pub max_window: f64,
    /// Long campaign: the full product of speed × load × clearance × ball material
    /// (`false`: one factor at a time around the nominal cell at every speed, plus the
    /// product of speed and load; for the expensive dynamic levels).
    pub full_product: bool,
    /// The cell's inputs go into the scene's `[inputs] initial`, so the level starts from
    /// them (skidding balls at their kinematic speeds, full-level balls at their
    /// quasi-static positions, a load-driven ring in static equilibrium), as a scene file,
    /// `raceway run` and an FMI host (inputs set in initialisation mode) start it. `false`:
    /// the inputs are set after the component is built (the ring and quasi-static bases:
    /// a load-driven ring falls from rest through its clearance).
    pub initial_inputs: bool,
    /// A roller bearing (the preset is a roller designation): the material axis sets the
    /// rollers' material and the 4 GPa load is the line contact's.
    pub roller: bool,
    /// The external moment `load.mx` as this arm times the radial load, m (tilts a 5-DOF
    /// ring: edge loading of rollers).
    pub moment_arm: f64,
    /// More fields of the scene's bearing table (e.g. a roller profile), or empty.
    pub bearing_extra: &'static str,
}

/// `[model]` lines of a load-driven base of the cheap levels: the level's own lines, then
/// the causality, contact damping and attached mass they share.
macro_rules! load_driven {
    ($level:literal) => {
        concat!(
            $level,
            "causality = \"load\"\ncontact_damping = 3000.0\nattached_mass_kg = 1.0\n"
        )
    };
}

/// What the bases of the cheap levels (ring, quasi-static, linear) share: the 6205, load
/// driven, radial, the clearance axis, the campaign's window, the full product, inputs
/// set after the build. A row states its name, its `[model]` lines and how it differs.
const CHEAP: Base = Base {
    name: "",
    preset: "6205",
    model: "",
    load_driven: true,
    axial_share: 0.0,
    clearance_axis: true,
    max_window: f64::INFINITY,
    full_product: true,
    initial_inputs: false,
    roller: false,
    moment_arm: 0.0,
    bearing_extra: "",
};

/// What the bases of the dynamic levels (skidding, full) share beyond [`CHEAP`]: a
/// window of 10 ms at the most, and the inputs in the scene's `[inputs] initial`.
const DYNAMIC: Base = Base {
    max_window: 0.01,
    initial_inputs: true,
    ..CHEAP
};

/// `[model]` lines of a load-driven skidding base: the studies' contact damping, Coulomb
/// traction, pocket and drag, with the attached mass (kg), `mu_max` and further lines.
macro_rules! skidding_load {
    ($mass:literal, $mu_max:literal, $more:literal) => {
        concat!(
            "level = \"skidding\"\ncausality = \"load\"\ncontact_damping = 100.0\nattached_mass_kg = ",
            $mass,
            "\n[model.skidding]\ntraction = { law = \"coulomb\", mu_max = ",
            $mu_max,
            ", v_s = 0.05 }\npocket_stiffness = 1e7\npocket_damping = 200.0\npocket_friction = 0.05\n\
             drag_coefficient = 15.0\ndrag_density = 10.0\n",
            $more
        )
    };
}

/// The level bases. Add a row for a new level.
pub const BASES: &[Base] = &[
    Base {
        name: "ring-2dof/load",
        model: load_driven!("level = \"ring\"\nring_dof = 2\n"),
        ..CHEAP
    },
    Base {
        name: "ring-5dof/load",
        model: load_driven!("level = \"ring\"\nring_dof = 5\n"),
        axial_share: 0.5,
        ..CHEAP
    },
    Base {
        name: "ring-5dof/load 7008CE",
        preset: "7008ce",
        model: load_driven!("level = \"ring\"\nring_dof = 5\n"),
        axial_share: 0.5,
        clearance_axis: false,
        ..CHEAP
    },
    Base {
        name: "ring-2dof/motion",
        model: "level = \"ring\"\nring_dof = 2\ncausality = \"motion\"\ncontact_damping = 3000.0\n",
        load_driven: false,
        ..CHEAP
    },
    Base {
        name: "quasi_static/load",
        model: load_driven!("level = \"quasi_static\"\n"),
        ..CHEAP
    },
    Base {
        name: "quasi_static/motion",
        model: "level = \"quasi_static\"\ncausality = \"motion\"\n",
        load_driven: false,
        ..CHEAP
    },
    Base {
        name: "ring-2dof/load NU206",
        preset: "NU206",
        model: load_driven!("level = \"ring\"\nring_dof = 2\n"),
        roller: true,
        ..CHEAP
    },
    Base {
        name: "ring-5dof/load NU206 tilted",
        preset: "NU206",
        model: load_driven!("level = \"ring\"\nring_dof = 5\n"),
        roller: true,
        // A moment of 5 mm times the radial load tilts the ring: the rollers edge-load.
        moment_arm: 0.005,
        ..CHEAP
    },
    Base {
        name: "quasi_static/load NU206",
        preset: "NU206",
        model: load_driven!("level = \"quasi_static\"\n"),
        roller: true,
        ..CHEAP
    },
    Base {
        name: "quasi_static/load 30206",
        preset: "30206",
        model: load_driven!("level = \"quasi_static\"\n"),
        roller: true,
        // A single tapered bearing is seated by an axial load above its induced thrust
        // (1.26 Fr tan(alpha) = 0.31 Fr for the 30206).
        axial_share: 0.5,
        ..CHEAP
    },
    Base {
        name: "ring-5dof/load 30206 tilted",
        preset: "30206",
        model: load_driven!("level = \"ring\"\nring_dof = 5\n"),
        roller: true,
        axial_share: 0.5,
        moment_arm: 0.005,
        ..CHEAP
    },
    Base {
        name: "linear/load",
        model: load_driven!("level = \"linear\"\n"),
        ..CHEAP
    },
    Base {
        name: "skidding/load 7008CE",
        preset: "7008ce",
        // The settings of examples/scenes/7008ce-skidding-24000.toml (study [3]).
        model: skidding_load!("0.5", "0.02", "spacing_scatter = 0.5\nseed = 7\n"),
        axial_share: 0.5,
        clearance_axis: false,
        ..DYNAMIC
    },
    Base {
        name: "skidding/load 6012",
        preset: "6012",
        // The settings of examples/scenes/6012-skidding.toml (study [2]).
        model: skidding_load!("1.0", "0.05", ""),
        ..DYNAMIC
    },
    Base {
        name: "full/motion 7004",
        preset: "7004",
        // The settings of examples/scenes/7004-30000.toml (study [0]): free cage,
        // quasi-static ball-race contacts.
        model: "level = \"full\"\ncausality = \"motion\"\n\
                [model.full]\ntraction = { law = \"coulomb\", mu_max = 0.05, v_s = 0.05 }\n\
                viscosity = 0.003\ndrag_density = 10.0\ncage = \"free\"\n",
        load_driven: false,
        axial_share: 0.5,
        clearance_axis: false,
        max_window: 0.005,
        full_product: false,
        ..DYNAMIC
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
    /// -20 µm: a stiff preload, every roller loaded (the roller cells, [`roller_cells`]; not
    /// in [`Clearance::ALL`]).
    StiffPreload,
}

impl Clearance {
    /// All values.
    pub const ALL: [Clearance; 3] = [Clearance::Preload, Clearance::Zero, Clearance::Large];
    fn um(self) -> f64 {
        match self {
            Clearance::Preload => -5.0,
            Clearance::Zero => 0.0,
            Clearance::Large => 40.0,
            Clearance::StiffPreload => -20.0,
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
    /// in the clearance does after a few Lyapunov times, docs/physics.md §N6.4).
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
    if let Some(r) = crate::geometry::roller_catalogue::lookup(preset_name) {
        // Line contact: the roller load whose line-Hertz peak on the inner race is `p`
        // (`p0 ∝ sqrt(Q)`), times `Z / 4.08` (Stribeck's number for line contact).
        let r = r.build()?;
        let p1 = crate::contact::lamina::line_hertz(
            1.0 / r.lwe,
            r.reduced_radius_inner(),
            r.e_prime_inner(),
        )
        .1;
        return Ok((p / p1).powi(2) * r.z as f64 / 4.08);
    }
    let b = preset(preset_name)?.build()?;
    let a = b.nominal_contact_angle();
    let c = PointContact::new(
        Curvature::ball_race(b.d, b.dm, a, b.fi(), Race::Inner),
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

    /// Shaft displacement `(x, y, z)` of a motion-driven cell. Radial bases (no axial
    /// share): half the clearance plus the Stribeck deflection `(F / (Z K_n J_r))^(2/3)`,
    /// `J_r(0.5) = 0.2288` (Harris §7.2), along `-y`. Bases with an axial share (angular
    /// contact, which must be seated axially): the quasi-static (Jones–Harris, Harris &
    /// Kotzalas Vol. 2 ch. 3) equilibrium of the radial load and its axial share at the
    /// cell's initial speed, tilts then held zero (as examples/scenes/7004-30000.toml); no
    /// load leaves the ring centred, the balls free in their play.
    fn displacement(&self, c: &Component) -> Result<[f64; 3]> {
        let b = c.bearing();
        let f = self.radial_load()?;
        if self.base.axial_share > 0.0 {
            if f == 0.0 {
                return Ok([0.0; 3]);
            }
            return square_equilibrium(b, [0.0, -f, self.base.axial_share * f], self.speed.rad_s());
        }
        let kn =
            crate::models::ring::RingModel::new(b, crate::models::ring::RingDof::Two, 0.0).kn();
        Ok([
            0.0,
            -(0.5 * b.pd + (f / (b.z as f64 * kn * 0.2288)).powf(2.0 / 3.0)),
            0.0,
        ])
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
        let mut material = if self.base.roller {
            format!("roller_material = \"{}\"", self.ball)
        } else {
            format!("materials = {{ ball = \"{}\" }}", self.ball)
        };
        if !self.base.bearing_extra.is_empty() {
            material = format!("{material}, {}", self.base.bearing_extra);
        }
        format!(
            "title = \"stability cell\"\n\
             bearing = {{ preset = \"{}\", {clearance}{material} }}\n\
             [model]\n{}\
             [solver]\nrtol = {:e}\natol_m = {:e}\nmax_substeps = 200000\n\
             [inputs]\nrule = \"{rule}\"\n",
            self.base.preset,
            self.base.model,
            rtol,
            1e-4 * rtol,
        )
    }

    /// The window simulated, s: `t_base`, at most the base's own window, and at least two
    /// macro steps.
    pub fn window(&self, t_base: f64) -> f64 {
        t_base.min(self.base.max_window).max(2.0 * self.h)
    }

    /// The inputs at the start of the window (name, value) and the step-input events.
    fn inputs(&self, c: &Component, t_end: f64) -> Result<(Inputs, Vec<InputEvent>)> {
        let f = self.radial_load()?;
        let omega = self.speed.rad_s();
        let mut v = vec![("shaft.omega", omega)];
        let mut events = Vec::new();
        let mut step = |name: &str, value: f64| {
            if self.step_input {
                events.push(InputEvent {
                    t: 0.5 * t_end,
                    name: name.into(),
                    value,
                });
            }
        };
        if self.base.load_driven {
            v.extend([
                ("load.x", 0.0),
                ("load.y", -f),
                ("load.z", self.base.axial_share * f),
                ("load.mx", self.base.moment_arm * f),
                ("load.my", 0.0),
            ]);
            step("load.y", -f - 1000.0);
        } else {
            let q = self.displacement(c)?;
            v.extend([("shaft.x", q[0]), ("shaft.y", q[1]), ("shaft.z", q[2])]);
            for n in [
                "shaft.rx", "shaft.ry", "shaft.vx", "shaft.vy", "shaft.vz", "shaft.wx", "shaft.wy",
            ] {
                v.push((n, 0.0));
            }
            step("shaft.y", q[1] - 5e-6);
        }
        step("shaft.omega", -omega);
        Ok((v, events))
    }

    /// A scene file that reruns the cell at `rtol` with `raceway run` (`[inputs] initial`
    /// and `[run]`); the step input is noted in a comment (a scene has no events).
    pub fn reproducer(&self, rtol: f64, t_base: f64) -> Result<String> {
        let t_end = self.window(t_base);
        let c = Component::from_text(&self.scene(rtol))?;
        let (v, events) = self.inputs(&c, t_end)?;
        let mut s = with_initial(&self.scene(rtol), &v);
        if !self.base.initial_inputs {
            s += "# the campaign sets these inputs after building the component (its level \
                  starts from zero inputs): build from the scene without `initial`, then \
                  set_real them before the first do_step\n";
        }
        let _ = writeln!(s, "[run]\nduration_s = {t_end:e}\nstep_s = {:e}", self.h);
        if self.speed == Speed::FromRest {
            let _ = writeln!(
                s,
                "speed_ramp_rpm_per_s = {:e}",
                Speed::Nominal.rad_s() / t_end * 30.0 / std::f64::consts::PI
            );
        }
        for e in events {
            let _ = writeln!(
                s,
                "# step input at t = {:e} s: {} = {:e}",
                e.t, e.name, e.value
            );
        }
        Ok(s)
    }

    /// One run: the forces, the peak pressure at the end and the first non-finite output.
    fn run_once(&self, rtol: f64, t_end: f64) -> Result<(Samples, f64, Option<String>)> {
        let c0 = Component::from_text(&self.scene(rtol))?;
        let (v, events) = self.inputs(&c0, t_end)?;
        let mut c = if self.base.initial_inputs {
            Component::from_text(&with_initial(&self.scene(rtol), &v))?
        } else {
            c0
        };
        for (n, x) in v {
            let vr = crate::component::variables::by_name(n)
                .expect("a variable of the table")
                .vr;
            c.set_real(vr, x)?;
        }
        let ramp = (self.speed == Speed::FromRest)
            .then(|| ("shaft.omega", Speed::Nominal.rad_s() / t_end));
        let (s, bad) = drive_checked(&mut c, t_end, self.h, &events, ramp)?;
        let vr = crate::component::variables::by_name("contact.max_pressure")
            .expect("in the table")
            .vr;
        let p = match bad {
            // Reported as a non-finite pressure, with the output named.
            Some(what) => return Ok((s, f64::NAN, Some(what))),
            None => c.get_real(vr)?,
        };
        Ok((s, p, None))
    }

    /// Run the cell: at rtol 1e-6 and 1e-7 over `window(t_base)`.
    pub fn run(&self, t_base: f64) -> Outcome {
        let t_end = self.window(t_base);
        let r = catch_unwind(AssertUnwindSafe(|| {
            let a = self.run_once(1e-6, t_end)?;
            let b = self.run_once(1e-7, t_end)?;
            Ok::<_, crate::Error>((a, b))
        }));
        let ((sa, pa, na), (sb, pb, nb)) = match r {
            Err(p) => return Outcome::Failed(format!("panic: {}", panic_text(&*p))),
            Ok(Err(e)) => return Outcome::CleanError(e.to_string()),
            Ok(Ok(v)) => v,
        };
        if let Some(what) = na.or(nb) {
            return Outcome::Failed(format!("non-finite output: {what}"));
        }
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
            Ok(Ok((_, _, Some(what)))) => {
                return Outcome::Failed(format!("non-finite output at rtol 1e-8: {what}"))
            }
            Ok(Ok((s, p, None))) => (s, p),
            Ok(Err(e)) => return Outcome::CleanError(e.to_string()),
            Err(p) => return Outcome::Failed(format!("panic at rtol 1e-8: {}", panic_text(&*p))),
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

/// The quasi-static (Jones–Harris) displacement `(x, y, z)` that balances the force `load`
/// on the inner ring at shaft speed `omega` with the ring held square (tilts zero, as a
/// spindle's second bearing holds it): Newton on the three force equations with the
/// model's exact stiffness, from the unconstrained equilibrium, halving the step until
/// the residual falls.
pub fn square_equilibrium(
    b: &crate::geometry::Bearing,
    load: [f64; 3],
    omega: f64,
) -> Result<[f64; 3]> {
    use crate::models::quasi_static::{azimuths, BallState, QuasiStatic};
    let qs = QuasiStatic::new(b, Default::default())?;
    let free = qs.solve(&[load[0], load[1], load[2], 0.0, 0.0], omega)?;
    let psi = azimuths(b.z, 0.0);
    let mut st = free.states.clone();
    let mut q = [free.q[0], free.q[1], free.q[2], 0.0, 0.0];
    let scale = load.iter().map(|x| x.abs()).fold(0.0, f64::max).max(1.0);
    let residual = |q: &[f64; 5], st: &mut [BallState], k: &mut [[f64; 5]; 5]| {
        let f = qs.forces_and_stiffness(q, omega, &psi, st, k)?;
        Ok::<_, crate::Error>([f[0] + load[0], f[1] + load[1], f[2] + load[2]])
    };
    let norm = |r: &[f64; 3]| r.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut k = [[0.0; 5]; 5];
    let mut r = residual(&q, &mut st, &mut k)?;
    for _ in 0..100 {
        if norm(&r) <= 1e-9 * scale {
            return Ok([q[0], q[1], q[2]]);
        }
        // Solve K3 dq = r (F(q + dq) ~ F(q) - K dq), Cramer's rule on the 3 x 3 block
        // with a Levenberg–Marquardt shift for the unloaded directions.
        let mut a = [[0.0; 3]; 3];
        let shift = 1e-12 * (0..3).map(|i| k[i][i].abs()).fold(0.0, f64::max);
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] = k[i][j] + if i == j { shift } else { 0.0 };
            }
        }
        let det3 = |m: &[[f64; 3]; 3]| {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        };
        let d = det3(&a);
        if !(d.is_finite() && d != 0.0) {
            break;
        }
        let mut dq = [0.0; 3];
        for (c, x) in dq.iter_mut().enumerate() {
            let mut m = a;
            for row in 0..3 {
                m[row][c] = r[row];
            }
            *x = det3(&m) / d;
        }
        let mut t = 1.0;
        let mut improved = false;
        for _ in 0..40 {
            let mut qn = q;
            for i in 0..3 {
                qn[i] += t * dq[i];
            }
            let mut sn = st.clone();
            if let Ok(rn) = residual(&qn, &mut sn, &mut k) {
                if norm(&rn) < norm(&r) {
                    (q, st, r, improved) = (qn, sn, rn, true);
                    break;
                }
            }
            t *= 0.5;
        }
        if !improved {
            break;
        }
    }
    Err(crate::Error::NotConverged {
        what: "stability campaign: square-held quasi-static displacement",
        iterations: 100,
        residual: norm(&r),
    })
}

/// `scene` (ending in its `[inputs]` table) with the inputs `v` as its initial values.
fn with_initial(scene: &str, v: &[(&str, f64)]) -> String {
    // The speed goes in rpm as `speed_rpm`, the other inputs into `initial`.
    let speed = crate::component::scene::SPEED_VARIABLE;
    let rpm: String = v
        .iter()
        .filter(|(n, _)| *n == speed)
        .map(|(_, x)| format!("speed_rpm = {:e}\n", crate::units::rad_s_to_rpm(*x)))
        .collect();
    let initial: Vec<String> = v
        .iter()
        .filter(|(n, _)| *n != speed)
        .map(|(n, x)| format!("\"{n}\" = {x:e}"))
        .collect();
    format!("{scene}{rpm}initial = {{ {} }}\n", initial.join(", "))
}

/// The message of a caught panic.
fn panic_text(p: &(dyn std::any::Any + Send)) -> String {
    crate::error::panic_message(p).unwrap_or_default()
}

/// The shared driver's loop ([`super::drive_until`]: events when their time comes, the
/// ramp with its derivative) that also checks after every macro step that every output of
/// the variable table (forces, motion, K and C, cage and contact outputs) and its derivative
/// is finite. Returns the forces, and the first non-finite output (the run stops there).
fn drive_checked(
    c: &mut Component,
    t_end: f64,
    h: f64,
    events: &[InputEvent],
    ramp: Option<(&str, f64)>,
) -> Result<(Samples, Option<String>)> {
    use crate::component::variables;
    let outputs: Vec<&'static variables::Variable> = variables::all()
        .filter(|v| v.is_output(c.causality()))
        .collect();
    let (s, _, bad) = super::drive_until(c, t_end, h, events, ramp, |c, t| {
        for v in &outputs {
            let x = c.get_real(v.vr)?;
            let d = c.get_output_derivative(v.vr, 1).unwrap_or(0.0);
            if !(x.is_finite() && d.is_finite()) {
                let at = format!("at t = {t:e} s");
                return Ok(Some(format!("{} = {x}, d/dt = {d} {at}", v.name)));
            }
        }
        Ok(None)
    })?;
    Ok((s, bad))
}

/// The cells of the campaign. `long`: for every level base the full product of speed,
/// load, clearance and ball material at 1e-4 s (bases without [`Base::full_product`]:
/// speed × load, and clearance and ball material one at a time at each speed), plus the
/// macro-step sweep with and without a step input at each speed. Otherwise a sample: one
/// factor at a time around each base's nominal cell, plus a few corners.
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
                        if !base.full_product && clearance != Clearance::Zero {
                            v.push(Cell {
                                speed,
                                clearance,
                                ..n
                            });
                            continue;
                        }
                        for ball in MATERIALS {
                            if !base.full_product && (ball != n.ball && load != n.load) {
                                continue;
                            }
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
    if long {
        v.extend(roller_cells());
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

// ---------------------------------------------------------------------------------------
// Roller cells: stiff preload, heavy tilt, edge loading, high speed.

// --- Roller bearings: their bases and cells in a file of their own.
#[path = "stability_rollers.rs"]
mod rollers;
pub use rollers::{roller_cells, ROLLER_BASES};

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

impl Cell {
    /// The cell's label, its row's first cells on the page: `base | speed | load |
    /// clearance | material | H | step input` (what the developer filter matches).
    pub fn label(&self) -> String {
        row_cells(self)
    }
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

/// The Markdown page of a campaign; `times`: thread CPU time per base, s.
pub fn markdown(
    results: &[(Cell, Outcome)],
    t_base: f64,
    command: &str,
    times: &[(&str, f64)],
) -> String {
    let count = |r: &[&(Cell, Outcome)]| {
        let c = |f: fn(&Outcome) -> bool| r.iter().filter(|(_, o)| f(o)).count();
        (
            r.len(),
            c(|o| matches!(o, Outcome::Converged { .. })),
            c(|o| matches!(o, Outcome::Statistical { .. })),
            c(|o| matches!(o, Outcome::CleanError(_))),
            c(|o| matches!(o, Outcome::Failed(_))),
        )
    };
    let all: Vec<&(Cell, Outcome)> = results.iter().collect();
    let (n, conv, stat, clean, failed) = count(&all);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# Stability campaign\n\n\
         Generated by `{command}` on {}.\n\n\
         Every cell runs the component through its public API over max({t_base} s, 2 macro \
         steps) (a dynamic level's base may cap the window: see the table of bases) at rtol \
         1e-6 and again at 1e-7 (atol_m = 1e-4 m × rtol; the level's default integrator: \
         DOPRI5, RODAS4 for the skidding and full levels). It passes if every output of the \
         variable table (forces, motion, K and C, cage, contact and power outputs) and its \
         derivative is finite after every macro step and the two runs' forces differ by less \
         than {CONVERGENCE_LIMIT:.0e} (RMS difference over RMS force, or over 1 N when the \
         forces are smaller), or if the component refuses cleanly with an error naming the \
         cause. A panic, a NaN or a run that does not converge is a failure.\n\n\
         Axes (docs/physics.md §N5.5): level; speed (standing, ramped from rest through input \
         derivatives, reversed, 1750 rpm, 120 000 rpm); radial load (0, 10 N, 1 kN, the load \
         whose Stribeck ball load gives a 4 GPa Hertz peak, for steel balls at zero \
         clearance); an axial load of a share of it where the base says; diametral clearance \
         (-5 µm preload, 0, 40 µm; angular-contact presets keep their own); ball material \
         (steel, Si3N4, ZrO2, rings steel); macro step; a step input at mid-window (load \
         +1 kN or the shaft 5 µm further, and the speed reversed). Motion-driven radial bases \
         get the Stribeck deflection of the load plus half the clearance; motion-driven \
         angular-contact bases the quasi-static (Jones–Harris) displacement of the radial \
         and axial load at the cell's initial speed with the ring held square (tilts zero, \
         as examples/scenes/7004-30000.toml). Ring and quasi-static bases set their inputs \
         after building the component (a load-driven ring falls from rest through its \
         clearance); the dynamic bases put them in the scene's initial inputs, as a scene \
         file, `raceway run` and an FMI host do (balls at their kinematic speeds or \
         quasi-static positions, a load-driven ring in static equilibrium).\n\n\
         When rtol 1e-6 and 1e-7 disagree, a third run at 1e-8 decides: converged from \
         1e-7 (1e-7 and 1e-8 agree pointwise), converged in statistics (mean and RMS of each \
         force over the second half agree within {STATISTICS_LIMIT} of the RMS force while \
         the trajectories separate: impacts in the clearance or chaotic cage motion, \
         docs/physics.md §N6.4), or failed.\n\n\
         Roller cells (the long campaign, beside the roller bases' own product): a stiff \
         preload of -20 µm, 120 000 rpm and their corner with the 4 GPa load on every roller \
         base, plus bases with a heavy tilt (a moment of 50 mm times the radial load) and \
         edge loading (straight rollers tilted by 5 mm times the load).\n\n\
         **{n} cells: {conv} converged, {stat} converged late or in statistics, {clean} clean \
         errors, {failed} failed.**\n",
        super::Machine::detect().describe()
    );
    s += "## Bases\n\n| base | preset | axial share | window (s) | product | cells | converged | late / statistics | clean errors | failed | CPU time (s) |\n\
          |---|---|---|---|---|---|---|---|---|---|---|\n";
    for b in BASES.iter().chain(ROLLER_BASES) {
        let r: Vec<&(Cell, Outcome)> = results.iter().filter(|(c, _)| c.base == b).collect();
        if r.is_empty() {
            continue;
        }
        let (n, conv, stat, clean, failed) = count(&r);
        let time = times
            .iter()
            .find(|(name, _)| *name == b.name)
            .map_or(String::new(), |(_, t)| format!("{t:.1}"));
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {n} | {conv} | {stat} | {clean} | {failed} | {time} |",
            b.name,
            b.preset,
            b.axial_share,
            t_base.min(b.max_window),
            if b.full_product {
                "full"
            } else {
                "speed × load, others one at a time"
            }
        );
    }
    s += "\n## Cells\n\n";
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
    campaign_of(long, &[], dir, verbose)
}

/// Whether a cell's label ([`Cell::label`], or a set cell's `set: NAME`) is kept by the
/// developer filter `only`: it contains one of the substrings, or `only` is empty.
pub fn kept(label: &str, only: &[String]) -> bool {
    only.is_empty() || only.iter().any(|s| label.contains(s.as_str()))
}

/// [`campaign`] restricted to the cells whose label contains one of the substrings of
/// `only` (`raceway bench --stability --cell SUBSTRING`, repeatable: a developer's filter
/// to rerun a few cells; empty: the whole campaign). The page says which cells it holds.
pub fn campaign_of(
    long: bool,
    only: &[String],
    dir: &std::path::Path,
    verbose: bool,
) -> Result<Vec<(Cell, Outcome)>> {
    let t_base = if long { 0.02 } else { 0.005 };
    let mut cells = matrix(long);
    cells.retain(|c| kept(&c.label(), only));
    if verbose {
        println!("stability campaign: {} cells", cells.len());
    }
    let mut res = Vec::with_capacity(cells.len());
    let mut times = Vec::new();
    for b in BASES.iter().chain(ROLLER_BASES) {
        let these: Vec<Cell> = cells.iter().filter(|c| c.base == b).copied().collect();
        if these.is_empty() {
            continue;
        }
        let start = super::thread_cpu_s();
        res.extend(run(&these, t_base, verbose));
        times.push((b.name, super::thread_cpu_s() - start));
    }
    let mut cmd = if long {
        "cargo run --release -- bench --stability --long --out docs".to_string()
    } else {
        "cargo run --release -- bench --stability --out docs".to_string()
    };
    for s in only {
        let _ = write!(cmd, " --cell {s:?}");
    }
    // Bearing sets (their own block, `sets`): the page gets their section.
    let set_res = sets::run_of(t_base, only, verbose);
    let mut page = markdown(&res, t_base, &cmd, &times);
    if !set_res.is_empty() {
        page += &sets::markdown(&set_res, t_base);
    }
    super::write_file(&dir.join("stability.md"), &page)?;
    Ok(res)
}
