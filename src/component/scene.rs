//! The scene: one serde schema (TOML for people, JSON for programs) that says everything a
//! component needs. Anything a scene leaves out is not computed.

use super::fields::{
    between, choice, closed, ge, gt, int_choice, integer, name, name_or_table, number, table, text,
    Names, ANY,
};
pub use super::levels::Level;
use super::variables::{self, Causality};
use crate::error::{Error, Result};
use crate::geometry::roller::RollerBearingSpec;
use crate::geometry::{presets, roller_catalogue, Bearing, BearingSpec};
pub use crate::models::full::spec::FullSpec;
pub use crate::models::linear::spec::OperatingPoint;
pub use crate::models::quasi_static::RaceControl;
use crate::models::set::SetSpec;
pub use crate::models::set::{RowFile, SetFile};
pub use crate::models::skidding::spec::SkiddingSpec;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The embedded default scene (the README's main job runs it).
pub const DEFAULT_SCENE: &str = include_str!("../../examples/scenes/default.toml");

/// How inputs move inside a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum InputRule {
    /// Held at their values at the start of the step.
    Hold,
    /// Positions extrapolated with the given velocities: `q(t+s) = q + v s`.
    #[default]
    Velocity,
    /// Taylor polynomial of the derivatives the host set (`fmi2SetRealInputDerivatives`).
    Derivatives,
}

/// Where a load-driven inner ring starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Start {
    /// At rest in static equilibrium under the initial loads (no start-up transient).
    #[default]
    Equilibrium,
    /// At rest at zero displacement (the ring falls into its contacts).
    Rest,
}

/// Upper end of `model.contact_damping`, N s/m: a plausibility limit, not a fit. It is
/// above the critical damping 2·sqrt(k·m) of a one-tonne rotor on one heavily loaded ball
/// contact (Hertz stiffness k = 1.5·K^(2/3)·Q^(1/3) ≈ 1.5e8 N/m for K = 1e10 N/m^1.5,
/// Q = 1e4 N: 2·sqrt(1.5e8·1e3) ≈ 7.7e5 N s/m), so no bearing of the presets needs more;
/// without it a value near `f64::MAX` passes the field check and the outputs overflow to
/// infinity at the first step (found by `tests/props_scene.rs`).
pub const MAX_CONTACT_DAMPING: f64 = 1e6;

/// Model section.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ModelSpec {
    /// Level.
    pub level: Level,
    /// Causality.
    pub causality: Causality,
    /// Race control (quasi-static kernels).
    pub race_control: RaceControl,
    /// Ring level: 2 (radial x, y) or 5 (x, y, z, rx, ry) degrees of freedom.
    pub ring_dof: u32,
    /// Contact damping per loaded ball, N s/m (ring level; applied as `c d(delta)/dt`
    /// scaled by the contact's load share so the force stays continuous).
    pub contact_damping: f64,
    /// Linear level: operating point.
    pub operating_point: OperatingPoint,
    /// Load-driven: mass attached to the inner ring, kg (added to the ring's own).
    pub attached_mass_kg: f64,
    /// Skidding level options.
    pub skidding: SkiddingSpec,
    /// Full level options.
    pub full: FullSpec,
    /// Load-driven: where the inner ring starts.
    pub start: Start,
    /// Load-driven static start: ring coordinates held at a value while the others are
    /// solved (the run then integrates every coordinate from there).
    pub start_hold: crate::models::quasi_static::hold::HoldSpec,
}

crate::declare_fields!(ModelSpec {
    level: Level::default() => choice(&Level::NAMES, "model level: constant K and C (linear), per-ball equilibrium at kinematic cage positions (quasi_static), ring on massless balls (ring), ball orbit and spin with cage, traction and drag (skidding), 6-DOF balls and cage with pocket and guide-land forces (full)")
        .note("effects need `ring`"),
    causality: Causality::default() => choice(&["motion", "load"], "motion: shaft motion in, forces out; load: loads in, the inner ring is integrated inside"),
    race_control: RaceControl::default() => choice(&["outer", "none"], "race control of the quasi-static kernels (Harris ch. 8)"),
    ring_dof: 2 => int_choice(&[2, 5], "ring level: 2 (x, y) or 5 (x, y, z, rx, ry) degrees of freedom"),
    contact_damping: 0.0 => number("N s/m", closed(0.0, MAX_CONTACT_DAMPING), "contact damping per loaded ball (ring level)"),
    operating_point: OperatingPoint::default() => table(),
    attached_mass_kg: 0.0 => number("kg", ge(0.0), "load-driven: mass attached to the inner ring (added to its own)"),
    skidding: SkiddingSpec::default() => table(),
    full: FullSpec::default() => table(),
    start: Start::default() => choice(&["equilibrium", "rest"], "load-driven: the inner ring starts at rest in static equilibrium under the initial loads (equilibrium) or at zero displacement (rest)"),
    start_hold: crate::models::quasi_static::hold::HoldSpec::default() => table(),
});

/// Integrator choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// The level's default.
    #[default]
    Auto,
    /// Explicit Dormand–Prince 5(4) with dense output.
    Dopri5,
    /// Linearly implicit, L-stable Rosenbrock method.
    Rosenbrock,
    /// ROS34PW2, a Rosenbrock W-method of order 3 (Jacobian and LU kept across sub-steps
    /// and, unless a state was taken or set, across steps).
    Ros34pw2,
}

impl Method {
    /// The registered method this spelling names, `None` for `auto`
    /// ([`crate::solver::methods::METHODS`]).
    pub fn entry(self) -> Option<&'static crate::solver::methods::MethodEntry> {
        let name = match self {
            Method::Auto => return None,
            Method::Dopri5 => "dopri5",
            Method::Rosenbrock => "rosenbrock",
            Method::Ros34pw2 => "ros34pw2",
        };
        crate::solver::methods::by_name(name)
    }

    /// The method a level of stiffness `stiff` runs with this choice.
    pub fn resolve(self, stiff: bool) -> &'static crate::solver::methods::MethodEntry {
        self.entry()
            .unwrap_or_else(|| crate::solver::methods::auto(stiff))
    }
}

/// Solver section.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSpec {
    /// Method.
    pub method: Method,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance on displacements, m (other states are scaled to match).
    pub atol_m: f64,
    /// Largest internal sub-step, s (0: no limit beyond the communication step).
    pub max_substep_s: f64,
    /// Most internal steps in one communication step before the step fails (the work
    /// budget in sub-steps).
    pub max_substeps: u32,
    /// Most thread CPU time one communication step may take, s, before it stops with
    /// [`Error::Budget`] and the state as before (the work budget in time).
    pub max_step_cpu_s: f64,
}

/// Default of [`SolverSpec::max_step_cpu_s`], s: far above any shipped scene's step (the
/// full level's costliest takes well under a second) and short enough that a host never
/// waits minutes on a step that cannot finish.
pub const MAX_STEP_CPU_S: f64 = 20.0;

crate::declare_fields!(SolverSpec {
    method: Method::Auto => choice(&crate::solver::methods::METHOD_NAMES, "integrator (auto: the level's default)"),
    rtol: 1e-6 => number("-", closed(1e-14, 0.1), "relative tolerance"),
    atol_m: 1e-10 => number("m", closed(1e-20, 1e-3), "absolute tolerance on displacements")
        .why("below 1e-20 m the tolerance is under the rounding of any displacement; the work-precision references use 1e-16 m"),
    max_substep_s: 0.0 => number("s", ge(0.0), "largest internal sub-step (0: the communication step)"),
    max_substeps: 100_000 => integer(closed(1.0, u32::MAX as f64), "work budget: most internal steps per communication step (raise it when a step stops on it)"),
    max_step_cpu_s: MAX_STEP_CPU_S => number("s", between(0.0, false, 1e6, true), "work budget: most CPU time one communication step may take before it stops, state unchanged (raise it when a step stops on it)")
        .note("thread CPU time"),
});

/// Inputs section: the rule and the values at the start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct InputSpec {
    /// How inputs move inside a step.
    pub rule: InputRule,
    /// Shaft speed at the start, rpm: the input `shaft.omega` (rad/s inside).
    pub speed_rpm: f64,
    /// Values at the start, by variable name (e.g. `"shaft.y" = -10e-6`), SI; the speed
    /// is [`InputSpec::speed_rpm`].
    pub initial: BTreeMap<String, f64>,
}

/// The input variable a scene gives in rpm (`inputs.speed_rpm`), never in
/// `inputs.initial`.
pub const SPEED_VARIABLE: &str = "shaft.omega";

crate::declare_fields!(InputSpec {
    rule: InputRule::default() => choice(&["hold", "velocity", "derivatives"], "how inputs move inside a step"),
    speed_rpm: 0.0 => number("rpm", ANY, "shaft speed at the start (the input shaft.omega, rad/s inside)")
        .note("within the bearing's burst speed (plausibility limits)"),
    initial: BTreeMap::new() => table(),
});

impl InputSpec {
    /// The value input `name` holds until a host sets it: the one rule for unset inputs on
    /// every face (Rust, C, Python, FMI, CLI). It is the scene's initial value (its
    /// operating point): the `initial` entry, else 0.
    pub fn initial_value(&self, name: &str) -> f64 {
        if name == SPEED_VARIABLE {
            return crate::units::rpm_to_rad_s(self.speed_rpm);
        }
        self.initial.get(name).copied().unwrap_or(0.0)
    }

    /// Make `value` (SI) the initial value of input `name`: `speed_rpm` for the shaft
    /// speed, the `initial` entry otherwise.
    pub fn set_initial(&mut self, name: &str, value: f64) {
        if name == SPEED_VARIABLE {
            self.speed_rpm = crate::units::rad_s_to_rpm(value);
        } else {
            self.initial.insert(name.to_string(), value);
        }
    }

    /// The refusal of the old spelling `inputs.initial."shaft.omega"` (rad/s), naming the
    /// new one with the value it holds in rpm.
    pub fn old_speed_message(rad_s: f64) -> String {
        format!(
            "the shaft speed is given in rpm now: `speed_rpm = {}` in [inputs] (this entry, in rad/s, is no longer read)",
            (crate::units::rad_s_to_rpm(rad_s) * 1e4).round() / 1e4
        )
    }

    /// The one row of `inputs.initial`, a table keyed by input variable.
    pub const INITIAL: &'static [super::fields::FieldDecl] = &[number(
        "SI unit of the variable",
        ANY,
        "input value at the start, by variable name (e.g. \"shaft.y\" in m)",
    )
    .note("only inputs of the scene's causality, the speed excepted (inputs.speed_rpm); absent: 0; within the bearing's plausibility limits (below)")
    .named("<variable>")];
}

/// The `[run]` section: what a stand-alone run (`raceway run`) does with the scene. Hosts
/// that step the component themselves ignore it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RunSpec {
    /// Simulated time, s.
    pub duration_s: f64,
    /// Communication (output) step, s.
    pub step_s: f64,
    /// Shaft speed ramp, rpm/s, added to `inputs.speed_rpm` (start from rest: initial
    /// speed 0 and a ramp).
    pub speed_ramp_rpm_per_s: f64,
    /// Motion-driven: radius of a circular shaft orbit added to the initial displacement, µm.
    pub orbit_um: f64,
    /// Motion-driven: orbit frequency, Hz (0: once per shaft revolution, i.e. synchronous).
    pub orbit_hz: f64,
    /// Load-driven: a load rotating with the shaft (unbalance), N, added to the initial load.
    pub rotating_load_n: f64,
}

crate::declare_fields!(RunSpec {
    duration_s: 0.2 => number("s", between(0.0, false, 1e4, true), "simulated time of `raceway run`")
        .note("at most 1e7 steps of step_s"),
    step_s: 1e-4 => number("s", gt(0.0), "communication (output) step")
        .note("<= duration_s, at most 1e7 steps"),
    speed_ramp_rpm_per_s: 0.0 => number("rpm/s", ANY, "shaft speed ramp added to inputs.speed_rpm")
        .note("the speed at the end of the run within the burst speed (plausibility limits)"),
    orbit_um: 0.0 => number("µm", ANY, "motion-driven: radius of a circular shaft orbit")
        .note("within the radial displacement limit (plausibility limits)"),
    orbit_hz: 0.0 => number("Hz", ANY, "motion-driven: orbit frequency (0: synchronous)"),
    rotating_load_n: 0.0 => number("N", ANY, "load-driven: load rotating with the shaft (unbalance)")
        .note("within the force limit (plausibility limits)"),
});

/// The bearing of a scene: a preset name, or a table with an optional `preset` and any
/// bearing-file fields overriding it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum BearingRef {
    /// A preset name.
    Preset(String),
    /// A table.
    Table(toml::Table),
}

impl BearingRef {
    /// The key a bearing table has beyond the bearing-file fields.
    pub const FIELDS: &'static [super::fields::FieldDecl] = &[name(
        Names::BearingPreset,
        "preset the table starts from (without it, name, ball_diameter_mm, pitch_diameter_mm and ball_count are required)",
    )
    .named("preset")];

    /// The roller bearing this names, when it names one: a roller designation of the
    /// catalogue (`NU206`, `30206`), alone or as the `preset` of a table whose other keys
    /// override the roller file's fields; `None` for a ball bearing.
    pub fn roller_spec(&self) -> Result<Option<RollerBearingSpec>> {
        let (name, overrides) = match self {
            BearingRef::Preset(name) => (name.as_str(), None),
            BearingRef::Table(t) => match t.get("preset") {
                Some(toml::Value::String(name)) => (name.as_str(), Some(t)),
                _ => return Ok(None),
            },
        };
        if presets::preset(name).is_ok() {
            return Ok(None);
        }
        let Some(base) = roller_catalogue::lookup(name) else {
            return Ok(None);
        };
        let Some(t) = overrides else {
            return Ok(Some(base));
        };
        let mut merged = toml::Table::try_from(&base).map_err(|e| Error::Parse {
            what: "preset".into(),
            message: e.to_string(),
        })?;
        for (k, v) in t.iter().filter(|(k, _)| k.as_str() != "preset") {
            merged.insert(k.clone(), v.clone());
        }
        toml::Value::Table(merged)
            .try_into::<RollerBearingSpec>()
            .map(Some)
            .map_err(|e| Error::Parse {
                what: "scene [bearing] (a roller bearing)".into(),
                message: super::schema::user_words(&e.to_string()),
            })
    }

    /// Resolve to a spec (preset plus overrides).
    pub fn spec(&self) -> Result<BearingSpec> {
        match self {
            BearingRef::Preset(name) => presets::preset(name),
            BearingRef::Table(t) => {
                let mut table = t.clone();
                let base = match table.remove("preset") {
                    Some(toml::Value::String(name)) => {
                        let spec = presets::preset(&name)?;
                        toml::Table::try_from(&spec).map_err(|e| Error::Parse {
                            what: "preset".into(),
                            message: e.to_string(),
                        })?
                    }
                    Some(other) => {
                        return Err(Error::invalid(
                            "bearing.preset",
                            other,
                            "a preset name (string)",
                        ))
                    }
                    None => toml::Table::new(),
                };
                let mut merged = base;
                for (k, v) in table {
                    merged.insert(k, v);
                }
                toml::Value::Table(merged)
                    .try_into::<BearingSpec>()
                    .map_err(|e| Error::Parse {
                        what: "scene [bearing]".into(),
                        message: super::schema::user_words(&e.to_string()),
                    })
            }
        }
    }
}

/// A whole scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Free title.
    #[serde(default)]
    pub title: String,
    /// The bearing.
    pub bearing: BearingRef,
    /// Model.
    #[serde(default)]
    pub model: ModelSpec,
    /// Solver.
    #[serde(default)]
    pub solver: SolverSpec,
    /// Inputs.
    #[serde(default)]
    pub inputs: InputSpec,
    /// Optional effects (defects, waviness, lubrication), all off by default.
    #[serde(default)]
    pub effects: crate::models::effects::Effects,
    /// Stand-alone run settings.
    #[serde(default)]
    pub run: RunSpec,
    /// A bearing set: several rows of bearings on the shaft as one component (absent: the
    /// one bearing).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub set: Option<SetFile>,
}

/// Most rows a set may have: the variable table declares the per-row outputs of this many
/// (`row0.*` .. `row3.*`).
pub const MAX_SET_ROWS: usize = super::variables::ROWS;

crate::declare_fields!(Scene {
    title => text("free title"),
    bearing => name_or_table(Names::BearingPreset, "the bearing: a preset name (`raceway bearings`) or a catalogue designation (60xx, 62xx, 63xx; 70xx, 72xx, 73xx + C, AC or B; internal geometry estimated, `raceway bearings 6206`), or a table with an optional `preset` and bearing-file fields overriding it"),
    model => table(),
    solver => table(),
    inputs => table(),
    effects => table(),
    run => table(),
    set => table(),
});

impl Scene {
    /// The `[run]` excitations within the bearing's plausibility limits: the speed at the
    /// end of the ramp, the orbit radius and the rotating load.
    fn check_run_limits(&self, lim: &super::limits::Limits) -> Result<()> {
        let r = &self.run;
        let rpm = std::f64::consts::PI / 30.0;
        let w0 = self.inputs.initial_value(SPEED_VARIABLE);
        let w_end = w0 + r.speed_ramp_rpm_per_s * rpm * r.duration_s;
        if !(w_end.is_finite() && w_end.abs() <= lim.omega) {
            let most = (lim.omega - w0.abs()).max(0.0) / (rpm * r.duration_s);
            return Err(Error::invalid(
                "run.speed_ramp_rpm_per_s",
                r.speed_ramp_rpm_per_s,
                format!(
                    "|ramp| <= {most:.4e} rpm/s: the speed at the end of the run must stay within the bearing's burst speed {:.4e} rpm",
                    lim.omega / rpm
                ),
            ));
        }
        if r.orbit_um.abs() * 1e-6 > lim.radial {
            return Err(Error::invalid(
                "run.orbit_um",
                r.orbit_um,
                format!(
                    "|orbit| <= {:.4e} µm (the bearing's radial displacement limit)",
                    lim.radial * 1e6
                ),
            ));
        }
        if r.rotating_load_n.abs() > lim.force {
            return Err(Error::invalid(
                "run.rotating_load_n",
                r.rotating_load_n,
                format!(
                    "|load| <= {:.4e} N (every ball at the {} GPa load)",
                    lim.force,
                    super::limits::P_CONTACT_MAX * 1e-9
                ),
            ));
        }
        Ok(())
    }

    /// Parse TOML or JSON (JSON when the first non-blank character is `{`).
    ///
    /// A list where the scene has a table (`run = [0.1]`, `model = ["ring", "load"]`) is
    /// refused, not read by position; messages use the scene's words, not Rust type names.
    pub fn from_text(text: &str) -> Result<Scene> {
        let json = text.trim_start().starts_with('{');
        let what = if json { "scene (JSON)" } else { "scene (TOML)" };
        let parse = |message: String| Error::Parse {
            what: what.into(),
            message: super::schema::user_words(&message),
        };
        // Nesting first, without recursion: the parsers below recurse per level and a
        // small host thread must survive any text.
        crate::nesting::check(text).map_err(|e| parse(e.to_string()))?;
        // The untyped tree first: a list where a table belongs is named as such before
        // serde reads it by position or names a Rust type.
        let mut tree = if json {
            serde_json::from_str::<serde_json::Value>(text).map_err(|e| parse(e.to_string()))?
        } else {
            let table = toml::from_str::<toml::Table>(text).map_err(|e| parse(e.to_string()))?;
            serde_json::to_value(table).map_err(|e| parse(e.to_string()))?
        };
        if let Some((path, expected)) = super::schema::list_for_table(&tree) {
            return Err(parse(format!(
                "`{path}` is a list; expected {expected} (`[{path}]` with its fields, or `{path} = {{ ... }}`)"
            )));
        }
        if json {
            // A null key is an absent key (`schema::strip_nulls`): read the stripped tree
            // when there was one (its errors carry no line), else the text (with lines).
            if super::schema::strip_nulls(&mut tree) {
                serde_json::from_value(tree).map_err(|e| parse(e.to_string()))
            } else {
                serde_json::from_str(text).map_err(|e| parse(e.to_string()))
            }
        } else {
            toml::from_str(text).map_err(|e| parse(e.to_string()))
        }
    }

    /// What a level is built from: the bearing `b` (this scene's, validated) and this
    /// scene's model and effects options, as plain data.
    pub fn level_args<'a>(&'a self, b: &'a Bearing) -> crate::models::LevelArgs<'a> {
        let m = &self.model;
        crate::models::LevelArgs {
            bearing: b,
            race_control: m.race_control,
            ring_dof: m.ring_dof,
            contact_damping: m.contact_damping,
            operating_point: &m.operating_point,
            skidding: &m.skidding,
            full: &m.full,
            effects: &self.effects,
        }
    }

    /// The embedded default scene.
    pub fn default_scene() -> Scene {
        Scene::from_text(DEFAULT_SCENE).expect("the embedded default scene parses")
    }

    /// Resolve and validate the bearing.
    pub fn build_bearing(&self) -> Result<Bearing> {
        match self.bearing.roller_spec()? {
            Some(r) => Bearing::from_roller(r.build()?),
            None => self.bearing.spec()?.build(),
        }
    }

    /// The scene's bearing set (`[set]`, rows defaulting to the scene's bearing `b`),
    /// checked against the level: `None` for one bearing.
    pub fn set_spec(&self, b: &Bearing) -> Result<Option<SetSpec>> {
        let Some(f) = &self.set else {
            return Ok(None);
        };
        super::fields::check("set", SetFile::FIELDS, f)?;
        for (i, r) in f.row.iter().enumerate() {
            super::fields::check(&format!("set.row[{i}]"), RowFile::FIELDS, r)?;
        }
        let m = &self.model;
        let supported = "a set runs at level quasi_static, or ring with ring_dof = 5";
        if m.level != Level::QuasiStatic && m.level != Level::Ring {
            return Err(Error::invalid(
                "model.level",
                format!("{} with a [set]", m.level),
                format!("quasi_static or ring ({supported}: the set's rows are quasi-static contacts; the skidding and full levels carry one bearing's balls and cage)"),
            ));
        }
        if m.level == Level::Ring && m.ring_dof != 5 {
            return Err(Error::invalid(
                "model.ring_dof",
                format!("{} with a [set]", m.ring_dof),
                format!("5 ({supported}: the rows of a set are preloaded axially and hold the shaft's tilt, which the 2-DOF ring does not have)"),
            ));
        }
        if !self.effects.is_off() {
            return Err(Error::invalid(
                "effects",
                "on with a [set]",
                "off: defects, waviness, films, wear and the thermal network belong to one bearing; a set runs without them",
            ));
        }
        let spec = f.spec("set", Some(b), None, true)?;
        if spec.rows.len() > MAX_SET_ROWS {
            return Err(Error::invalid(
                "set.row",
                format!("{} rows", spec.rows.len()),
                format!("at most {MAX_SET_ROWS} rows (the variable table declares the per-row outputs of {MAX_SET_ROWS})"),
            ));
        }
        for (i, r) in spec.rows.iter().enumerate() {
            m.level.accepts(r.bearing.element()).map_err(|e| match e {
                Error::Invalid { value, allowed, .. } => Error::Invalid {
                    field: format!("set.row[{i}].bearing"),
                    value,
                    allowed,
                },
                e => e,
            })?;
        }
        Ok(Some(spec))
    }

    /// Validate everything; each refusal names the field, the value and the allowed range.
    pub fn validate(&self) -> Result<Bearing> {
        use super::fields::check;
        let b = self.build_bearing()?;
        check("solver", SolverSpec::FIELDS, &self.solver)?;
        self.effects.validate()?;
        let r = &self.run;
        check("run", RunSpec::FIELDS, r)?;
        if r.step_s > r.duration_s {
            return Err(Error::invalid(
                "run.step_s",
                r.step_s,
                format!("in (0, run.duration_s = {}] s", r.duration_s),
            ));
        }
        if r.duration_s / r.step_s > 1e7 {
            return Err(Error::invalid(
                "run.step_s",
                r.step_s,
                "at least run.duration_s / 1e7 (at most 1e7 output steps)",
            ));
        }
        let lim = super::limits::Limits::of(&b);
        if !(lim.radial >= 0.0 && lim.axial >= 0.0) {
            // A preload so deep that every ball is past the plastic limit at zero
            // displacement: no input could be accepted (every range would be empty).
            let min_um = -2.0 * lim.approach * 1e6;
            return Err(Error::invalid(
                "bearing.clearance_um",
                format!("{:.1} µm", b.pd * 1e6),
                format!(
                    "at least {min_um:.1} µm for this bearing: a deeper preload presses every ball past the {:.1} GPa plausibility limit at zero displacement (the bound follows from bearing.ball_diameter_mm, the groove curvatures and the materials)",
                    super::limits::P_CONTACT_MAX * 1e-9
                ),
            ));
        }
        let m = &self.model;
        check("model", ModelSpec::FIELDS, m)?;
        m.level.check(self, &b)?;
        self.set_spec(&b)?;
        // The full level's options are checked whatever the level (cheap, and a bad value
        // is named even in a scene that does not use it yet).
        m.full.params(&b, m.race_control)?;
        check(
            "model.operating_point",
            OperatingPoint::FIELDS,
            &m.operating_point,
        )?;
        let op = &m.operating_point;
        let rpm = std::f64::consts::PI / 30.0;
        for (f, name, v) in [
            ("speed_rpm", "shaft.omega", op.speed_rpm * rpm),
            ("fx", "load.x", op.fx),
            ("fy", "load.y", op.fy),
            ("fz", "load.z", op.fz),
            ("mx", "load.mx", op.mx),
            ("my", "load.my", op.my),
        ] {
            lim.check(&format!("model.operating_point.{f} (SI)"), name, v)?;
        }
        let speed = self.inputs.initial_value(SPEED_VARIABLE);
        lim.check("inputs.speed_rpm (SI)", SPEED_VARIABLE, speed)?;
        for (name, value) in &self.inputs.initial {
            if name == SPEED_VARIABLE {
                return Err(Error::invalid(
                    format!("inputs.initial.{name}"),
                    value,
                    InputSpec::old_speed_message(*value),
                ));
            }
            let var = variables::by_name(name).ok_or_else(|| Error::Unknown {
                what: "input variable",
                name: name.clone(),
                known: variables::SCALARS
                    .iter()
                    .filter(|v| v.is_input(m.causality))
                    .map(|v| v.name.to_string())
                    .collect(),
            })?;
            if !var.is_input(m.causality) {
                return Err(Error::invalid(
                    format!("inputs.initial.{name}"),
                    value,
                    "only inputs of this causality",
                ));
            }
            lim.check(&format!("inputs.initial.{name}"), name, *value)?;
        }
        self.check_run_limits(&lim)?;
        Ok(b)
    }
}
