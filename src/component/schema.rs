//! The scene schema, documented and checked.
//!
//! - [`rows`] lists every field a scene may hold (dotted paths; `[]` stands for any item of
//!   an array of tables, `<variable>` for a key of `inputs.initial`, `<body>` for one of the
//!   four material bodies) with its type, unit, default, allowed range and meaning. The list
//!   of paths is not written by hand: it is enumerated from the serde serialisation of a
//!   scene whose every optional field and list is filled ([`schema_paths`]), and the
//!   defaults come from deserialising a scene that gives only the required fields. The one
//!   hand-written part is [`TABLE`] (unit, range, description per path); a test fails when
//!   a serialised path has no entry or an entry names no path.
//! - [`check`] reports every problem of a scene text at once, each with its place
//!   (`line:column` for TOML, the field path for JSON): syntax errors, unknown keys (with
//!   the nearest known name), wrong types, values outside [`TABLE`]'s ranges, unknown
//!   presets, materials, lubricants, variables and enum spellings, missing required fields;
//!   then, when none of those remain, the library's own [`Scene::validate`] and
//!   [`Component::new`](crate::Component::new) for the cross-field problems, located by the
//!   field path their message names. TOML spans come from the `toml` crate's spanned
//!   document tables ([`toml::de::DeTable::parse_recoverable`]).

use super::scene::{
    BearingRef, InputSpec, Level, ModelSpec, RunSpec, Scene, SkiddingSpec, SolverSpec,
};
use super::variables;
use crate::contact::traction::TractionLaw;
use crate::geometry::bearing::{CageSpec, MaterialSpec, MaterialsSpec};
use crate::geometry::{presets, BearingSpec, Material};
use crate::models::effects::{
    DefectSpec, Effects, Element, FilmKind, LubricationSpec, SpacingSpec, WavinessSpec,
};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

/// Named sets of allowed strings that come from the library's own lists.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Names {
    /// Bearing presets ([`presets::presets`]).
    BearingPreset,
    /// Material presets ([`Material::presets`]).
    Material,
    /// Lubricant presets.
    Lubricant,
    /// Input variables of either causality ([`variables::SCALARS`]).
    InputVariable,
}

impl Names {
    /// The allowed names.
    pub fn list(self) -> Vec<String> {
        match self {
            Names::BearingPreset => presets::presets().into_iter().map(|p| p.name).collect(),
            Names::Material => Material::presets().into_iter().map(|m| m.name).collect(),
            Names::Lubricant => vec!["study2".into()],
            Names::InputVariable => variables::SCALARS
                .iter()
                .filter(|v| {
                    v.is_input(variables::Causality::Motion)
                        || v.is_input(variables::Causality::Load)
                })
                .map(|v| v.name.to_string())
                .collect(),
        }
    }

    /// Is `name` allowed (bearing presets and materials ignore case, as the library does)?
    pub fn contains(self, name: &str) -> bool {
        match self {
            Names::BearingPreset => presets::preset(name).is_ok(),
            Names::Material => Material::by_name(name).is_ok(),
            _ => self.list().iter().any(|n| n == name),
        }
    }
}

/// The type of a field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// A number (integers are accepted).
    Float,
    /// A non-negative integer.
    Int,
    /// Free text.
    Text,
    /// One of fixed spellings (a serde enum).
    Enum(&'static [&'static str]),
    /// One of the integers listed.
    IntChoice(&'static [i64]),
    /// A name from a library list.
    Name(Names),
    /// A name from a library list, or a table of fields (the paths below this one).
    NameOrTable(Names),
    /// `true` or `false`.
    Bool,
}

impl Kind {
    /// Short type name for the documentation.
    pub fn type_name(&self) -> &'static str {
        match self {
            Kind::Float => "number",
            Kind::Int | Kind::IntChoice(_) => "integer",
            Kind::Text | Kind::Enum(_) | Kind::Name(_) => "string",
            Kind::NameOrTable(_) => "string or table",
            Kind::Bool => "boolean",
        }
    }
}

/// Allowed interval of a number: `(value, inclusive)` at each end, `None` unbounded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Lower end.
    pub lo: Option<(f64, bool)>,
    /// Upper end.
    pub hi: Option<(f64, bool)>,
}

const ANY: Bounds = Bounds { lo: None, hi: None };
const fn gt(x: f64) -> Bounds {
    Bounds {
        lo: Some((x, false)),
        hi: None,
    }
}
const fn ge(x: f64) -> Bounds {
    Bounds {
        lo: Some((x, true)),
        hi: None,
    }
}
const fn between(lo: f64, lo_in: bool, hi: f64, hi_in: bool) -> Bounds {
    Bounds {
        lo: Some((lo, lo_in)),
        hi: Some((hi, hi_in)),
    }
}

impl Bounds {
    /// Does `v` lie inside (and is it finite)?
    pub fn contains(&self, v: f64) -> bool {
        v.is_finite()
            && self
                .lo
                .is_none_or(|(lo, inc)| if inc { v >= lo } else { v > lo })
            && self
                .hi
                .is_none_or(|(hi, inc)| if inc { v <= hi } else { v < hi })
    }

    /// `[0, 1]`, `(0, 1e4]`, `> 0`, `>= 1`, `any finite number`.
    pub fn text(&self) -> String {
        match (self.lo, self.hi) {
            (None, None) => "any finite number".into(),
            (Some((lo, inc)), None) => format!("{} {}", if inc { ">=" } else { ">" }, num(lo)),
            (None, Some((hi, inc))) => format!("{} {}", if inc { "<=" } else { "<" }, num(hi)),
            (Some((lo, li)), Some((hi, hi_in))) => format!(
                "{}{}, {}{}",
                if li { "[" } else { "(" },
                num(lo),
                num(hi),
                if hi_in { "]" } else { ")" }
            ),
        }
    }
}

fn num(x: f64) -> String {
    let a = x.abs();
    if a != 0.0 && !(1e-3..1e5).contains(&a) && !(x.fract() == 0.0 && a < 1e10) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// One documented field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Field {
    /// Dotted path (`[]`: any array item; `<variable>`, `<body>`: placeholders).
    pub path: &'static str,
    /// Type.
    pub kind: Kind,
    /// Unit (`-`: none).
    pub unit: &'static str,
    /// Numeric range (numbers only).
    pub bounds: Bounds,
    /// What the range does not say (bounds that depend on other fields).
    pub note: &'static str,
    /// Meaning.
    pub description: &'static str,
}

const fn f(
    path: &'static str,
    kind: Kind,
    unit: &'static str,
    bounds: Bounds,
    note: &'static str,
    description: &'static str,
) -> Field {
    Field {
        path,
        kind,
        unit,
        bounds,
        note,
        description,
    }
}

const LEVELS: &[&str] = &Level::NAMES;
const BALL_CONTACTS: &[&str] = &["quasi_static", "dynamic"];
const CAGE_MODELS: &[&str] = &["free", "ideal"];
const CAUSALITIES: &[&str] = &["motion", "load"];
const RACE_CONTROL: &[&str] = &["outer", "none"];
const METHODS: &[&str] = &["auto", "dopri5", "rosenbrock"];
const RULES: &[&str] = &["hold", "velocity", "derivatives"];
const KINDS: &[&str] = &["deep_groove", "angular_contact"];
const GUIDANCE: &[&str] = &["outer_ring", "inner_ring", "ball"];
const ELEMENTS: &[&str] = &["outer", "inner", "ball"];
const FILMS: &[&str] = &["ehl", "dry"];
const STARTS: &[&str] = &["equilibrium", "rest"];
const LAWS: &[&str] = &["coulomb", "fitted", "mixed_ehl"];
const WEAR_REGIMES: &[&str] = &["auto", "dry"];

use Kind::*;

/// Unit, range and meaning of every scene field: the one hand-written table. Paths must
/// match the serde schema exactly (`tests: table_matches_schema`).
pub const TABLE: &[Field] = &[
    f("title", Text, "-", ANY, "", "free title"),
    // Bearing.
    f("bearing", NameOrTable(Names::BearingPreset), "-", ANY, "", "the bearing: a preset name (`raceway bearings`) or a catalogue designation (60xx, 62xx, 63xx; 70xx, 72xx, 73xx + C, AC or B; internal geometry estimated, `raceway bearings 6206`), or a table with an optional `preset` and bearing-file fields overriding it"),
    f("bearing.preset", Name(Names::BearingPreset), "-", ANY, "", "preset the table starts from (without it, name, ball_diameter_mm, pitch_diameter_mm and ball_count are required)"),
    f("bearing.name", Text, "-", ANY, "", "designation"),
    f("bearing.kind", Enum(KINDS), "-", ANY, "", "deep-groove (radial) or angular-contact"),
    f("bearing.ball_diameter_mm", Float, "mm", gt(0.0), "< pitch_diameter_mm", "ball diameter D"),
    f("bearing.pitch_diameter_mm", Float, "mm", gt(0.0), "", "pitch diameter dm"),
    f("bearing.ball_count", Int, "-", between(1.0, true, u32::MAX as f64, true), "balls must not overlap on the pitch circle: dm sin(pi/Z) > D", "number of balls Z"),
    f("bearing.inner_curvature", Float, "-", between(0.5, false, 1.0, false), "may be left out with outer_curvature when both contact_angle_deg > 0 and clearance_um > 0 are given", "inner groove curvature ratio f_i = r_i/D"),
    f("bearing.outer_curvature", Float, "-", between(0.5, false, 1.0, false), "", "outer groove curvature ratio f_o = r_o/D"),
    f("bearing.contact_angle_deg", Float, "deg", between(0.0, true, 80.0, true), "give this or clearance_um (angular-contact)", "free contact angle alpha0"),
    f("bearing.clearance_um", Float, "µm", ANY, "deep-groove (-0.1 D, 2A); angular-contact [0, 2A), A = (f_i + f_o - 1) D", "diametral clearance Pd (negative: preload)"),
    f("bearing.bore_mm", Float, "mm", gt(0.0), "< dm - D; absent: dm - 1.6 D", "bore"),
    f("bearing.outer_diameter_mm", Float, "mm", gt(0.0), "> dm + D; absent: dm + 1.6 D", "outside diameter"),
    f("bearing.width_mm", Float, "mm", gt(0.0), "absent: 1.2 D", "width"),
    f("bearing.inner_ring_mass_kg", Float, "kg", gt(0.0), "absent: estimated from the envelope", "inner-ring mass"),
    f("bearing.outer_ring_mass_kg", Float, "kg", gt(0.0), "absent: estimated from the envelope", "outer-ring mass"),
    f("bearing.cage.inner_diameter_mm", Float, "mm", gt(0.0), "bore < cage bore < dm; absent: dm - 0.35 D", "cage bore"),
    f("bearing.cage.outer_diameter_mm", Float, "mm", gt(0.0), "dm < cage OD < outside diameter; absent: dm + 0.35 D", "cage outside diameter"),
    f("bearing.cage.width_mm", Float, "mm", gt(0.0), "absent: 0.8 D", "cage width"),
    f("bearing.cage.mass_kg", Float, "kg", gt(0.0), "absent: annulus less the pockets", "cage mass"),
    f("bearing.cage.inertia_kg_m2", Float, "kg m²", gt(0.0), "absent: thin annulus", "cage polar moment of inertia"),
    f("bearing.cage.pocket_clearance_mm", Float, "mm", gt(0.0), "absent: 0.02 D", "diametral play of a ball in its pocket"),
    f("bearing.cage.guide_clearance_mm", Float, "mm", gt(0.0), "absent: 0.005 dm", "radial guide-land clearance"),
    f("bearing.cage.guidance", Enum(GUIDANCE), "-", ANY, "", "how the cage is guided"),
    f("bearing.materials.ball", NameOrTable(Names::Material), "-", ANY, "", "ball material: a preset name or a table of material fields"),
    f("bearing.materials.inner_ring", NameOrTable(Names::Material), "-", ANY, "", "inner-ring material"),
    f("bearing.materials.outer_ring", NameOrTable(Names::Material), "-", ANY, "", "outer-ring material"),
    f("bearing.materials.cage", NameOrTable(Names::Material), "-", ANY, "", "cage material"),
    f("bearing.materials.<body>.name", Text, "-", ANY, "", "label of an inline material (<body>: ball, inner_ring, outer_ring or cage)"),
    f("bearing.materials.<body>.youngs_modulus", Float, "Pa", gt(0.0), "", "Young's modulus"),
    f("bearing.materials.<body>.poisson_ratio", Float, "-", between(0.0, true, 0.5, false), "", "Poisson's ratio"),
    f("bearing.materials.<body>.density", Float, "kg/m³", gt(0.0), "", "density"),
    f("bearing.materials.<body>.thermal_expansion", Float, "1/K", ge(0.0), "", "linear thermal expansion coefficient"),
    f("bearing.materials.<body>.conductivity", Float, "W/(m K)", ge(0.0), "", "thermal conductivity"),
    f("bearing.materials.<body>.heat_capacity", Float, "J/(kg K)", ge(0.0), "", "specific heat capacity"),
    f("bearing.source", Text, "-", ANY, "", "where the data come from"),
    // Model.
    f("model.level", Enum(LEVELS), "-", ANY, "effects need `ring`", "model level: constant K and C (linear), per-ball equilibrium at kinematic cage positions (quasi_static), ring on massless balls (ring), ball orbit and spin with cage, traction and drag (skidding), 6-DOF balls and cage with pocket and guide-land forces (full)"),
    f("model.causality", Enum(CAUSALITIES), "-", ANY, "", "motion: shaft motion in, forces out; load: loads in, the inner ring is integrated inside"),
    f("model.race_control", Enum(RACE_CONTROL), "-", ANY, "", "race control of the quasi-static kernels (Harris ch. 8)"),
    f("model.ring_dof", IntChoice(&[2, 5]), "-", ANY, "", "ring level: 2 (x, y) or 5 (x, y, z, rx, ry) degrees of freedom"),
    f("model.contact_damping", Float, "N s/m", ge(0.0), "", "contact damping per loaded ball (ring level)"),
    f("model.operating_point.speed_rpm", Float, "rpm", ANY, "", "linear level: shaft speed of the operating point"),
    f("model.operating_point.fx", Float, "N", ANY, "", "linear level: load x"),
    f("model.operating_point.fy", Float, "N", ANY, "", "linear level: load y"),
    f("model.operating_point.fz", Float, "N", ANY, "", "linear level: axial load z"),
    f("model.operating_point.mx", Float, "N m", ANY, "", "linear level: moment about x"),
    f("model.operating_point.my", Float, "N m", ANY, "", "linear level: moment about y"),
    f("model.skidding.traction.law", Enum(LAWS), "-", ANY, "the other traction fields belong to one law each", "skidding level: traction law at the race contacts"),
    f("model.skidding.traction.mu_max", Float, "-", ANY, "law = \"coulomb\", required there", "largest traction coefficient of mu = mu_max tanh(dv/v_s)"),
    f("model.skidding.traction.v_s", Float, "m/s", ge(super::limits::SLIP_SPEED_MIN), "law = \"coulomb\" (required) or \"mixed_ehl\" (default 0.01)", "regularising slip speed"),
    f("model.skidding.traction.a", Float, "-", ANY, "law = \"fitted\", required there", "A of mu = tanh(s/s_reg) [(A + B|s|) exp(-C|s|) + D]"),
    f("model.skidding.traction.b", Float, "-", ANY, "law = \"fitted\", required there", "B of the fitted law"),
    f("model.skidding.traction.c", Float, "-", between(0.0, true, 1e6, true), "law = \"fitted\", required there", "C of the fitted law"),
    f("model.skidding.traction.d", Float, "-", ANY, "law = \"fitted\", required there", "D of the fitted law"),
    f("model.skidding.traction.s_reg", Float, "-", gt(0.0), "law = \"fitted\", required there", "regularising slide-to-roll ratio"),
    f("model.skidding.traction.u_min", Float, "m/s", gt(0.0), "law = \"fitted\", required there", "smallest rolling speed in the slide-to-roll ratio"),
    f("model.skidding.traction.viscosity", Float, "Pa s", gt(0.0), "law = \"mixed_ehl\" (default 0.04667)", "inlet viscosity of the mixed-EHL law"),
    f("model.skidding.traction.alpha_p", Float, "1/Pa", between(0.0, true, 1e-6, true), "law = \"mixed_ehl\" (default 2.1e-8)", "pressure-viscosity coefficient"),
    f("model.skidding.traction.lambda_lim", Float, "-", gt(0.0), "law = \"mixed_ehl\" (default 0.04)", "limiting-shear coefficient"),
    f("model.skidding.traction.f_c", Float, "-", between(0.0, true, 2.0, true), "law = \"mixed_ehl\" (default 0.1)", "boundary (asperity) friction coefficient"),
    f("model.skidding.traction.roughness", Float, "m", between(0.0, true, 1e-3, true), "law = \"mixed_ehl\" (default 4.65e-7)", "composite rms roughness"),
    f("model.skidding.traction.hardness", Float, "Pa", gt(0.0), "law = \"mixed_ehl\" (default 2.39e9)", "hardness"),
    f("model.skidding.traction.fit.c", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity load ratio regression: leading constant"),
    f("model.skidding.traction.fit.e_kappa", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the ellipticity"),
    f("model.skidding.traction.fit.e_w", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the load parameter W"),
    f("model.skidding.traction.fit.e_u", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the speed parameter U"),
    f("model.skidding.traction.fit.e_g", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the material parameter G"),
    f("model.skidding.traction.fit.e_sigma", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the roughness sigma/Rx"),
    f("model.skidding.traction.fit.e_v", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the hardness ratio H/E'"),
    f("model.skidding.pocket_clearance_mm", Float, "mm", gt(0.0), "absent: the bearing's cage pocket clearance", "skidding level: pocket clearance per side"),
    f("model.skidding.pocket_stiffness", Float, "N/m", gt(0.0), "", "skidding level: pocket contact stiffness"),
    f("model.skidding.pocket_damping", Float, "N s/m", between(0.0, true, 1e9, true), "", "skidding level: pocket contact damping"),
    f("model.skidding.pocket_friction", Float, "-", between(0.0, true, 2.0, true), "", "skidding level: pocket friction coefficient"),
    f("model.skidding.drag_coefficient", Float, "-", between(0.0, true, 1e3, true), "", "skidding level: drag coefficient of an orbiting ball"),
    f("model.skidding.drag_density", Float, "kg/m³", between(0.0, true, 1e4, true), "", "skidding level: density of the oil–air mixture around the balls"),
    f("model.skidding.drag_viscosity", Float, "Pa s", between(0.0, true, 10.0, true), "", "skidding level: oil viscosity of the ball spin drag"),
    f("model.skidding.cage_drag", Float, "N m s", between(0.0, true, 1e3, true), "", "skidding level: cage drag"),
    f("model.skidding.spacing_scatter", Float, "-", between(0.0, true, 1.0, true), "", "skidding level: ball spacing scatter as a fraction of the pocket clearance"),
    f("model.skidding.seed", Int, "-", ge(0.0), "", "skidding level: seed of the scatter"),
    f("model.full.traction.law", Enum(LAWS), "-", ANY, "the other traction fields belong to one law each", "full level: traction law at the race contacts"),
    f("model.full.traction.mu_max", Float, "-", ANY, "law = \"coulomb\", required there", "largest traction coefficient of mu = mu_max tanh(dv/v_s)"),
    f("model.full.traction.v_s", Float, "m/s", ge(super::limits::SLIP_SPEED_MIN), "law = \"coulomb\" (required) or \"mixed_ehl\" (default 0.01)", "regularising slip speed"),
    f("model.full.traction.a", Float, "-", ANY, "law = \"fitted\", required there", "A of mu = tanh(s/s_reg) [(A + B|s|) exp(-C|s|) + D]"),
    f("model.full.traction.b", Float, "-", ANY, "law = \"fitted\", required there", "B of the fitted law"),
    f("model.full.traction.c", Float, "-", between(0.0, true, 1e6, true), "law = \"fitted\", required there", "C of the fitted law"),
    f("model.full.traction.d", Float, "-", ANY, "law = \"fitted\", required there", "D of the fitted law"),
    f("model.full.traction.s_reg", Float, "-", gt(0.0), "law = \"fitted\", required there", "regularising slide-to-roll ratio"),
    f("model.full.traction.u_min", Float, "m/s", gt(0.0), "law = \"fitted\", required there", "smallest rolling speed in the slide-to-roll ratio"),
    f("model.full.traction.viscosity", Float, "Pa s", gt(0.0), "law = \"mixed_ehl\" (default 0.04667)", "inlet viscosity of the mixed-EHL law"),
    f("model.full.traction.alpha_p", Float, "1/Pa", between(0.0, true, 1e-6, true), "law = \"mixed_ehl\" (default 2.1e-8)", "pressure-viscosity coefficient"),
    f("model.full.traction.lambda_lim", Float, "-", gt(0.0), "law = \"mixed_ehl\" (default 0.04)", "limiting-shear coefficient"),
    f("model.full.traction.f_c", Float, "-", between(0.0, true, 2.0, true), "law = \"mixed_ehl\" (default 0.1)", "boundary (asperity) friction coefficient"),
    f("model.full.traction.roughness", Float, "m", between(0.0, true, 1e-3, true), "law = \"mixed_ehl\" (default 4.65e-7)", "composite rms roughness"),
    f("model.full.traction.hardness", Float, "Pa", gt(0.0), "law = \"mixed_ehl\" (default 2.39e9)", "hardness"),
    f("model.full.traction.fit.c", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity load ratio regression: leading constant"),
    f("model.full.traction.fit.e_kappa", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the ellipticity"),
    f("model.full.traction.fit.e_w", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the load parameter W"),
    f("model.full.traction.fit.e_u", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the speed parameter U"),
    f("model.full.traction.fit.e_g", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the material parameter G"),
    f("model.full.traction.fit.e_sigma", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the roughness sigma/Rx"),
    f("model.full.traction.fit.e_v", Float, "-", ANY, "law = \"mixed_ehl\"", "asperity regression: exponent of the hardness ratio H/E'"),
    f("model.full.ball_contacts", Enum(BALL_CONTACTS), "-", ANY, "", "full level: ball radial/axial position in quasi-static equilibrium (study [0]) or integrated with the ball mass (dynamic)"),
    f("model.full.cage", Enum(CAGE_MODELS), "-", ANY, "", "full level: cage with six degrees of freedom (free) or centred, rotation only (ideal)"),
    f("model.full.reference_load_n", Float, "N", between(1e-3, true, 1e9, true), "", "full level: reference force F_ref of the nondimensional states (time scale sqrt(m_b D / (2 F_ref)))"),
    f("model.full.drag_factor", Float, "-", between(0.0, true, 1e3, true), "", "full level: factor on the boundary-layer drag of balls and cage (0: off)"),
    f("model.full.drag_density", Float, "kg/m³", between(0.0, true, 1e4, true), "", "full level: effective density of the oil–air mixture"),
    f("model.full.viscosity", Float, "Pa s", between(0.0, true, 10.0, true), "", "full level: oil viscosity (drag, pockets, guide land)"),
    f("model.full.pocket_clearance_mm", Float, "mm", gt(0.0), "absent: the bearing's cage pocket clearance", "full level: diametral pocket play"),
    f("model.full.pocket_friction", Float, "-", between(0.0, true, 2.0, true), "", "full level: ball–pocket friction coefficient"),
    f("model.full.pocket_roughness_um", Float, "µm", between(0.0, true, 1e3, true), "", "full level: composite roughness of ball and pocket"),
    f("model.full.pocket_v_s", Float, "m/s", between(super::limits::SLIP_SPEED_MIN, true, 1e3, true), "", "full level: regularising slip speed of the pocket friction"),
    f("model.full.guide_width_mm", Float, "mm", gt(0.0), "absent: half the cage width", "full level: guide land width"),
    f("model.full.guide_stiffness", Float, "N/m", gt(0.0), "", "full level: guide-land contact stiffness beyond guide_eps_max"),
    f("model.full.guide_eps_max", Float, "-", between(0.05, true, 0.999, true), "", "full level: eccentricity ratio where the guide-land contact starts"),
    f("model.full.guidance", Enum(GUIDANCE), "-", ANY, "absent: bearing.cage.guidance", "full level: cage guidance, on the outer-ring land (land radius = cage OD/2) or the inner-ring land (= cage bore/2), or ball-riding (no land)"),
    f("model.full.cage_unbalance_um", Float, "µm", between(0.0, true, 1e3, true), "default 0", "full level: cage mass unbalance, offset of the mass centre from the geometric centre (a load rotating with the cage, m_c u w_c²)"),
    f("model.skidding.gyro_traction", Float, "-", between(0.0, true, 10.0, true), "0 turns the gyroscopic friction off", "skidding level: traction coefficient limiting the lateral friction that carries the balls' gyroscopic couple"),
    f("model.skidding.ball_radial_mass", Bool, "-", ANY, "default false", "skidding level: give the balls radial mass (position along the contact line as a state, damped by model.contact_damping) instead of the quasi-static split"),
    f("model.skidding.spin_friction", Float, "-", between(0.0, true, 2.0, true), "0: no spinning moment", "skidding level: friction coefficient of the spinning moment (3/8) mu Q a E at the race contacts"),
    f("model.start", Enum(STARTS), "-", ANY, "", "load-driven: the inner ring starts at rest in static equilibrium under the initial loads (equilibrium) or at zero displacement (rest)"),
    f("model.attached_mass_kg", Float, "kg", ge(0.0), "", "load-driven: mass attached to the inner ring (added to its own)"),
    // Solver.
    f("solver.method", Enum(METHODS), "-", ANY, "", "integrator (auto: the level's default)"),
    f("solver.rtol", Float, "-", between(1e-14, true, 0.1, true), "", "relative tolerance"),
    f("solver.atol_m", Float, "m", between(1e-20, true, 1e-3, true), "", "absolute tolerance on displacements"),
    f("solver.max_substep_s", Float, "s", ge(0.0), "", "largest internal sub-step (0: the communication step)"),
    f("solver.max_substeps", Int, "-", between(1.0, true, u32::MAX as f64, true), "", "work budget: most internal steps per communication step (raise it when a step stops on it)"),
    f("solver.max_step_cpu_s", Float, "s", between(0.0, false, 1e6, true), "thread CPU time", "work budget: most CPU time one communication step may take before it stops, state unchanged (raise it when a step stops on it)"),
    // Inputs.
    f("inputs.rule", Enum(RULES), "-", ANY, "", "how inputs move inside a step"),
    f("inputs.initial.<variable>", Float, "SI unit of the variable", ANY, "only inputs of the scene's causality; absent: 0; within the bearing's plausibility limits (below)", "input value at the start, by variable name (e.g. \"shaft.omega\" in rad/s)"),
    // Effects.
    f("effects.defects[].race", Enum(ELEMENTS), "-", ANY, "", "element carrying the defect"),
    f("effects.defects[].angle_deg", Float, "deg", ANY, "", "defect centre at t = 0: azimuth from +x on a race, spin angle on a ball"),
    f("effects.defects[].width_mm", Float, "mm", gt(0.0), "< ball diameter", "circumferential width"),
    f("effects.defects[].depth_um", Float, "µm", between(0.0, false, 5000.0, true), "", "depth"),
    f("effects.defects[].ball", Int, "-", ge(0.0), "< Z; race = \"ball\" only (absent: ball 0)", "ball carrying the defect (0-based)"),
    f("effects.waviness[].race", Enum(ELEMENTS), "-", ANY, "", "element carrying the waviness"),
    f("effects.waviness[].order", Int, "-", between(1.0, true, 10000.0, true), "", "order k of A sin(k theta + beta)"),
    f("effects.waviness[].amplitude_um", Float, "µm", between(-100.0, true, 100.0, true), "", "amplitude A"),
    f("effects.waviness[].phase_deg", Float, "deg", ANY, "", "phase beta"),
    f("effects.waviness[].ball", Int, "-", ge(0.0), "< Z; race = \"ball\" only (absent: every ball)", "ball carrying the waviness (0-based)"),
    f("effects.ball_spacing.scatter", Float, "-", between(0.0, true, 1.0, true), "", "ball-spacing scatter as a fraction of the pocket play"),
    f("effects.ball_spacing.seed", Int, "-", ge(0.0), "", "seed of the SplitMix64 generator"),
    f("effects.lubrication.film", Enum(FILMS), "-", ANY, "", "Hamrock–Dowson EHL film in series with Hertz (ehl) or none (dry)"),
    f("effects.lubrication.lubricant", Name(Names::Lubricant), "-", ANY, "", "lubricant preset"),
    f("effects.lubrication.viscosity_pa_s", Float, "Pa s", between(0.0, true, 100.0, true), "absent: the preset's", "inlet viscosity"),
    f("effects.lubrication.pressure_viscosity_m2_per_n", Float, "m²/N", between(0.0, true, 1e-6, true), "absent: the preset's", "pressure-viscosity coefficient"),
    f("effects.lubrication.density_kg_m3", Float, "kg/m³", between(0.0, false, 1e5, true), "absent: the preset's", "lubricant density"),
    f("effects.lubrication.roughness_um", Float, "µm", between(0.0, true, 100.0, true), "absent: the preset's", "composite rms roughness of ball and race"),
    f("effects.wear.cells", Int, "-", between(1.0, true, 1000.0, true), "", "cells of the circumferential wear map of each race"),
    f("effects.wear.coefficient", Float, "-", gt(0.0), "", "Archard wear coefficient K"),
    f("effects.wear.hardness_gpa", Float, "GPa", gt(0.0), "", "hardness Hv"),
    f("effects.wear.regime", Enum(WEAR_REGIMES), "-", ANY, "", "auto: lubricated with an EHL film in the scene, else dry; dry: the dry limit La = 100, psi = 1"),
    f("effects.wear.defect_length_m", Float, "m", gt(0.0), "", "film-defect length a_x"),
    f("effects.wear.defect_time_s", Float, "s", gt(0.0), "", "film-defect time t0"),
    f("effects.wear.activation_energy_j_mol", Float, "J/mol", ge(0.0), "", "adsorption activation energy Ea"),
    f("effects.wear.surface_temperature_c", Float, "°C", gt(-273.15), "", "surface temperature Ts without the thermal model"),
    f("effects.wear.window_revs", Float, "rev", gt(0.0), "", "shaft revolutions of dynamics per wear cycle"),
    f("effects.wear.cycle_revs", Float, "rev", gt(0.0), ">= window_revs", "shaft revolutions each wear cycle stands for"),
    f("effects.wear.cycles", Int, "-", ge(0.0), "", "wear cycles applied"),
    f("effects.thermal.f0", Float, "-", ge(0.0), "", "Palmgren factor f0 (load-independent torque)"),
    f("effects.thermal.f1", Float, "-", ge(0.0), "", "Palmgren factor f1 (load-dependent torque)"),
    f("effects.thermal.viscosity_cst", Float, "cSt", gt(0.0), "absent: from the lubricant, else 20", "oil kinematic viscosity"),
    f("effects.thermal.spin_friction", Float, "-", ge(0.0), "", "spin friction coefficient mu_s"),
    f("effects.thermal.hysteresis_loss", Float, "-", ge(0.0), "", "hysteresis loss fraction alpha_h"),
    f("effects.thermal.ambient_c", Float, "°C", gt(-273.15), "", "ambient and initial temperature"),
    f("effects.thermal.shaft_conductance_w_k", Float, "W/K", ge(0.0), "", "inner ring to ambient through the shaft"),
    f("effects.thermal.housing_conductance_w_k", Float, "W/K", ge(0.0), "", "outer ring to ambient through the housing"),
    f("effects.thermal.oil_conductance_w_k", Float, "W/K", ge(0.0), "", "oil to ambient (oil flow)"),
    f("effects.thermal.oil_heat_capacity_j_k", Float, "J/K", gt(0.0), "", "heat capacity of the oil in the bearing"),
    f("effects.thermal.contact_conductance_w_k", Float, "W/K", ge(0.0), "absent: Holm constriction of the loaded contacts", "ball–ring conductance per race"),
    f("effects.thermal.dt_s", Float, "s", gt(0.0), "", "thermal time step"),
    f("effects.thermal.time_scale", Float, "-", gt(0.0), "", "thermal seconds per second of dynamics"),
    f("effects.thermal.growth_factor", Float, "-", ge(0.0), "", "factor on the thermal growth's change of the clearance (0: off)"),
    // Run.
    f("run.duration_s", Float, "s", between(0.0, false, 1e4, true), "at most 1e7 steps of step_s", "simulated time of `raceway run`"),
    f("run.step_s", Float, "s", gt(0.0), "<= duration_s, at most 1e7 steps", "communication (output) step"),
    f("run.speed_ramp_rpm_per_s", Float, "rpm/s", ANY, "the speed at the end of the run within the burst speed (plausibility limits)", "shaft speed ramp added to the initial shaft.omega"),
    f("run.orbit_um", Float, "µm", ANY, "within the radial displacement limit (plausibility limits)", "motion-driven: radius of a circular shaft orbit"),
    f("run.orbit_hz", Float, "Hz", ANY, "", "motion-driven: orbit frequency (0: synchronous)"),
    f("run.rotating_load_n", Float, "N", ANY, "within the force limit (plausibility limits)", "load-driven: load rotating with the shaft (unbalance)"),
];

/// The entry of a normalised path.
pub fn field(path: &str) -> Option<&'static Field> {
    TABLE.iter().find(|f| f.path == path)
}

const BODIES: [&str; 4] = ["ball", "inner_ring", "outer_ring", "cage"];

/// Normalise a concrete path: array indices become `[]`, keys of `inputs.initial` become
/// `<variable>`, the body of an inline material becomes `<body>`.
fn normalise_child(parent_norm: &str, key: &str) -> String {
    if parent_norm == "inputs.initial" {
        return "inputs.initial.<variable>".into();
    }
    if let Some(body) = parent_norm.strip_prefix("bearing.materials.") {
        if BODIES.contains(&body) {
            return format!("bearing.materials.<body>.{key}");
        }
    }
    if parent_norm.is_empty() {
        key.to_string()
    } else {
        format!("{parent_norm}.{key}")
    }
}

/// The first place in a parsed scene where a list stands for a table (serde would read
/// `model = ["ring", "load"]` by position), as `(path, expected)` with the path as the
/// scene spells it; `None` when there is none.
pub fn list_for_table(v: &serde_json::Value) -> Option<(String, &'static str)> {
    fn is_table(norm: &str) -> bool {
        let body = norm
            .strip_prefix("bearing.materials.")
            .is_some_and(|b| BODIES.contains(&b));
        body || TABLE.iter().any(|f| {
            f.path.len() > norm.len() + 1
                && f.path.starts_with(norm)
                && f.path.as_bytes()[norm.len()] == b'.'
        })
    }
    fn is_list(norm: &str) -> bool {
        let p = format!("{norm}[]");
        TABLE.iter().any(|f| f.path.starts_with(&p))
    }
    fn walk(v: &serde_json::Value, norm: &str, path: &str) -> Option<(String, &'static str)> {
        match v {
            serde_json::Value::Array(items) => {
                if is_list(norm) {
                    let item = format!("{norm}[]");
                    items
                        .iter()
                        .enumerate()
                        .find_map(|(i, x)| walk(x, &item, &format!("{path}[{i}]")))
                } else if is_table(norm) || norm.is_empty() {
                    Some((path.to_string(), "a table"))
                } else {
                    None
                }
            }
            serde_json::Value::Object(m) => m.iter().find_map(|(k, x)| {
                let child = normalise_child(norm, k);
                let p = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                walk(x, &child, &p)
            }),
            _ => None,
        }
    }
    walk(v, "", "")
}

/// A serde message in the scene's words: Rust type names (`struct RunSpec`, `enum Level`,
/// `f64`, `u32`, `a sequence`, `a map`) become what a scene writes.
pub fn user_words(message: &str) -> String {
    let message = message
        .replace(
            "data did not match any variant of untagged enum BearingRef",
            "expected a bearing preset name or a table of bearing fields",
        )
        .replace("internally tagged enum ", "struct ");
    let mut out = String::with_capacity(message.len());
    let mut rest = message.as_str();
    while let Some(i) = rest.find("struct ").or_else(|| rest.find("enum ")) {
        let (head, tail) = rest.split_at(i);
        out.push_str(head);
        let (word, after) = tail.split_at(tail.find(' ').unwrap_or(tail.len()) + 1);
        let end = after
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(after.len());
        if end > 0 && after.starts_with(|c: char| c.is_ascii_uppercase()) {
            out.push_str(if word == "struct " {
                "a table"
            } else {
                "one of the allowed names"
            });
            rest = &after[end..];
        } else {
            out.push_str(word);
            rest = after;
        }
    }
    out.push_str(rest);
    for (from, to) in [
        ("expected f64", "expected a number"),
        ("expected u32", "expected a non-negative integer"),
        ("expected u64", "expected a non-negative integer"),
        ("expected usize", "expected a non-negative integer"),
        ("a sequence", "a list"),
        ("sequence", "list"),
        ("a map", "a table"),
    ] {
        out = out.replace(from, to);
    }
    out
}

// ---------------------------------------------------------------------------------------
// Paths and defaults from serde.

fn steel_inline() -> MaterialSpec {
    MaterialSpec::Custom(Material::by_name("steel").expect("preset"))
}

/// A bearing spec with every optional field given (struct literals: a new field does not
/// compile until it is added here, and then the schema test asks for its table entry).
fn full_bearing(materials: MaterialsSpec) -> BearingSpec {
    BearingSpec {
        name: "6205".into(),
        kind: Default::default(),
        ball_diameter_mm: 7.94,
        pitch_diameter_mm: 39.04,
        ball_count: 9,
        inner_curvature: Some(0.52),
        outer_curvature: Some(0.52),
        contact_angle_deg: Some(0.0),
        clearance_um: Some(0.0),
        bore_mm: Some(25.0),
        outer_diameter_mm: Some(52.0),
        width_mm: Some(15.0),
        inner_ring_mass_kg: Some(0.05),
        outer_ring_mass_kg: Some(0.07),
        cage: CageSpec {
            inner_diameter_mm: Some(36.3),
            outer_diameter_mm: Some(41.8),
            width_mm: Some(6.3),
            mass_kg: Some(0.01),
            inertia_kg_m2: Some(4e-6),
            pocket_clearance_mm: Some(0.16),
            guide_clearance_mm: Some(0.2),
            guidance: Default::default(),
        },
        materials,
        source: String::new(),
    }
}

/// A scene with every optional section, field, list and map filled (two list items per
/// effect would add nothing: the paths of items are normalised to `[]`).
fn full_scene(bearing: BearingRef, traction: TractionLaw) -> Scene {
    let mut initial = BTreeMap::new();
    initial.insert("shaft.omega".to_string(), 100.0);
    let d = ModelSpec::default();
    let sk = SkiddingSpec::default();
    Scene {
        title: "full".into(),
        bearing,
        model: ModelSpec {
            level: super::Level::Ring,
            causality: d.causality,
            race_control: d.race_control,
            ring_dof: d.ring_dof,
            contact_damping: d.contact_damping,
            operating_point: d.operating_point,
            attached_mass_kg: d.attached_mass_kg,
            skidding: SkiddingSpec {
                traction,
                pocket_clearance_mm: Some(0.1),
                pocket_stiffness: sk.pocket_stiffness,
                pocket_damping: sk.pocket_damping,
                pocket_friction: sk.pocket_friction,
                drag_coefficient: sk.drag_coefficient,
                drag_density: sk.drag_density,
                drag_viscosity: sk.drag_viscosity,
                cage_drag: sk.cage_drag,
                spacing_scatter: sk.spacing_scatter,
                seed: sk.seed,
                gyro_traction: sk.gyro_traction,
                spin_friction: 0.02,
                ball_radial_mass: false,
            },
            full: super::scene::FullSpec {
                traction,
                pocket_clearance_mm: Some(0.1),
                guide_width_mm: Some(3.0),
                guidance: Some(crate::geometry::Guidance::InnerRing),
                cage_unbalance_um: 2.0,
                ..Default::default()
            },
            start: d.start,
        },
        solver: SolverSpec::default(),
        inputs: InputSpec {
            rule: Default::default(),
            initial,
        },
        effects: Effects {
            defects: vec![DefectSpec {
                race: Element::Ball,
                angle_deg: 0.0,
                width_mm: 0.5,
                depth_um: 10.0,
                ball: Some(0),
            }],
            waviness: vec![WavinessSpec {
                race: Element::Ball,
                order: 2,
                amplitude_um: 0.1,
                phase_deg: 0.0,
                ball: Some(0),
            }],
            ball_spacing: Some(SpacingSpec {
                scatter: 0.5,
                seed: 1,
            }),
            lubrication: Some(LubricationSpec {
                film: FilmKind::Ehl,
                lubricant: "study2".into(),
                viscosity_pa_s: Some(0.05),
                pressure_viscosity_m2_per_n: Some(2e-8),
                density_kg_m3: Some(870.0),
                roughness_um: Some(0.1),
            }),
            wear: Some(crate::models::effects::WearSpec::default()),
            thermal: Some(crate::models::effects::ThermalSpec {
                viscosity_cst: Some(30.0),
                contact_conductance_w_k: Some(1.0),
                ..Default::default()
            }),
        },
        run: RunSpec::default(),
    }
}

fn bearing_table(spec: &BearingSpec, preset: Option<&str>) -> toml::Table {
    let mut t = toml::Table::try_from(spec).expect("a bearing spec serialises");
    if let Some(p) = preset {
        t.insert("preset".into(), toml::Value::String(p.into()));
    }
    t
}

/// Full scenes covering every form: bearing as a table (with inline and preset
/// materials) and as a preset name, each traction law. Every one is a valid scene
/// (`tests`).
pub fn full_scenes() -> Vec<Scene> {
    let inline = MaterialsSpec {
        ball: steel_inline(),
        inner_ring: steel_inline(),
        outer_ring: steel_inline(),
        cage: MaterialSpec::Custom(Material::by_name("phenolic").expect("preset")),
    };
    let fitted = TractionLaw::Fitted {
        a: -0.01,
        b: 0.1,
        c: 10.0,
        d: 0.02,
        s_reg: 0.01,
        u_min: 0.1,
    };
    vec![
        full_scene(
            BearingRef::Table(bearing_table(&full_bearing(inline), Some("6205"))),
            TractionLaw::default(),
        ),
        full_scene(
            BearingRef::Table(bearing_table(&full_bearing(MaterialsSpec::default()), None)),
            fitted,
        ),
        full_scene(
            BearingRef::Preset("6205".into()),
            TractionLaw::MixedEhl(Default::default()),
        ),
    ]
}

fn walk_value(v: &toml::Value, norm: &str, out: &mut BTreeMap<String, toml::Value>) {
    match v {
        toml::Value::Table(t) => {
            for (k, c) in t {
                walk_value(c, &normalise_child(norm, k), out);
            }
        }
        toml::Value::Array(a) if a.iter().all(|x| x.is_table()) && !a.is_empty() => {
            for c in a {
                walk_value(c, &format!("{norm}[]"), out);
            }
        }
        leaf => {
            out.entry(norm.to_string()).or_insert_with(|| leaf.clone());
        }
    }
}

/// Every leaf path of the serde schema, normalised, with the value the full scenes give
/// it (used for its TOML type).
pub fn schema_paths() -> BTreeMap<String, toml::Value> {
    let mut out = BTreeMap::new();
    for s in full_scenes() {
        let v = toml::Value::try_from(&s).expect("a scene serialises");
        walk_value(&v, "", &mut out);
    }
    out
}

/// The smallest scene serde accepts: only the required fields of the scene, of one item of
/// each effect list and of the effect tables.
pub const MINIMAL_SCENE: &str = r#"
bearing = "6205"
[effects]
defects = [{ race = "outer", width_mm = 1.0, depth_um = 1.0 }]
waviness = [{ race = "outer", order = 1, amplitude_um = 0.1 }]
ball_spacing = { scatter = 0.0 }
lubrication = {}
"#;

/// The fields a bearing table without `preset` must give, and those of an inline material
/// (required whenever a material is given as a table).
pub const MINIMAL_BEARING: &str = r#"
name = "x"
ball_diameter_mm = 1.0
pitch_diameter_mm = 10.0
ball_count = 3
materials = { ball = { name = "m", youngs_modulus = 2e11, poisson_ratio = 0.3, density = 7800.0, thermal_expansion = 0.0, conductivity = 0.0, heat_capacity = 0.0 } }
"#;

/// A field's default as documented.
#[derive(Debug, Clone, PartialEq)]
pub enum Default_ {
    /// Must be given.
    Required,
    /// Required in a bearing table without `preset` (else the preset's).
    RequiredWithoutPreset,
    /// Absent unless given (see the note for what is used then).
    Absent,
    /// The value serde fills in.
    Value(toml::Value),
}

impl Default_ {
    /// Text for the documentation.
    pub fn text(&self) -> String {
        match self {
            Default_::Required => "required".into(),
            Default_::RequiredWithoutPreset => "the preset's; required without preset".into(),
            Default_::Absent => "absent".into(),
            Default_::Value(v) => match v {
                toml::Value::String(s) => format!("\"{s}\""),
                toml::Value::Float(x) if *x != 0.0 && !(1e-3..1e5).contains(&x.abs()) => {
                    format!("{x:e}")
                }
                toml::Value::Float(x) => format!("{x:?}"),
                other => other.to_string(),
            },
        }
    }
}

/// Concrete leaf paths of a TOML text (array items as `[i]`), for removal.
fn concrete_leaves(v: &toml::Value, path: Vec<PathSeg>, out: &mut Vec<Vec<PathSeg>>) {
    match v {
        toml::Value::Table(t) => {
            for (k, c) in t {
                let mut p = path.clone();
                p.push(PathSeg::Key(k.clone()));
                concrete_leaves(c, p, out);
            }
        }
        toml::Value::Array(a) if a.iter().all(|x| x.is_table()) && !a.is_empty() => {
            for (i, c) in a.iter().enumerate() {
                let mut p = path.clone();
                p.push(PathSeg::Index(i));
                concrete_leaves(c, p, out);
            }
        }
        _ => out.push(path),
    }
}

#[derive(Debug, Clone)]
enum PathSeg {
    Key(String),
    Index(usize),
}

fn remove_at(v: &mut toml::Value, path: &[PathSeg]) {
    match (path, v) {
        ([PathSeg::Key(k)], toml::Value::Table(t)) => {
            t.remove(k);
        }
        ([PathSeg::Key(k), rest @ ..], toml::Value::Table(t)) => {
            if let Some(c) = t.get_mut(k) {
                remove_at(c, rest)
            }
        }
        ([PathSeg::Index(i), rest @ ..], toml::Value::Array(a)) => {
            if let Some(c) = a.get_mut(*i) {
                remove_at(c, rest)
            }
        }
        _ => {}
    }
}

fn norm_of(prefix: &str, path: &[PathSeg]) -> String {
    let mut n = prefix.to_string();
    for s in path {
        match s {
            PathSeg::Key(k) => n = normalise_child(&n, k),
            PathSeg::Index(_) => n.push_str("[]"),
        }
    }
    n
}

/// The leaves of a minimal text that serde cannot do without: removing one makes `parses`
/// fail. Normalised with `prefix`.
fn required_of(
    text: &str,
    prefix: &str,
    parses: impl Fn(&toml::Value) -> bool,
) -> BTreeSet<String> {
    let v: toml::Value = toml::from_str(text).expect("minimal text parses");
    assert!(parses(&v), "the minimal text is accepted");
    let mut leaves = Vec::new();
    concrete_leaves(&v, Vec::new(), &mut leaves);
    leaves
        .into_iter()
        .filter(|p| {
            let mut w = v.clone();
            remove_at(&mut w, p);
            !parses(&w)
        })
        .map(|p| norm_of(prefix, &p))
        .collect()
}

/// The leaves serde requires in a scene, and in a bearing table without `preset`.
pub fn required_paths() -> (BTreeSet<String>, BTreeSet<String>) {
    let scene = required_of(MINIMAL_SCENE, "", |v| v.clone().try_into::<Scene>().is_ok());
    let bearing = required_of(MINIMAL_BEARING, "bearing", |v| {
        v.clone().try_into::<BearingSpec>().is_ok()
    });
    (scene, bearing)
}

/// Defaults of every path: serde's own, read back from the minimal scene and bearing;
/// required-ness from removing each field of them in turn.
pub fn defaults() -> BTreeMap<String, Default_> {
    let scene = Scene::from_text(MINIMAL_SCENE).expect("the minimal scene parses");
    let mut values = BTreeMap::new();
    walk_value(
        &toml::Value::try_from(&scene).expect("serialises"),
        "",
        &mut values,
    );
    let spec: BearingSpec = toml::from_str(MINIMAL_BEARING).expect("the minimal bearing parses");
    walk_value(
        &toml::Value::Table(bearing_table(&spec, None)),
        "bearing",
        &mut values,
    );
    let (req_scene, req_bearing) = required_paths();
    schema_paths()
        .into_keys()
        .map(|path| {
            let inline_material = path.starts_with("bearing.materials.<body>.");
            let d = if req_scene.contains(&path) || (inline_material && req_bearing.contains(&path))
            {
                Default_::Required
            } else if req_bearing.contains(&path) {
                Default_::RequiredWithoutPreset
            } else {
                values
                    .get(&path)
                    .cloned()
                    .map(Default_::Value)
                    .unwrap_or(Default_::Absent)
            };
            (path, d)
        })
        .collect()
}

/// The required fields, by normalised parent table (`""`: the scene; `bearing`: a bearing
/// table without preset).
fn required() -> BTreeMap<String, Vec<String>> {
    let mut out: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (p, d) in defaults() {
        if matches!(d, Default_::Required | Default_::RequiredWithoutPreset) {
            let (parent, key) = match p.rfind('.') {
                Some(i) => (p[..i].to_string(), p[i + 1..].to_string()),
                None => (String::new(), p.clone()),
            };
            out.entry(parent).or_default().push(key);
        }
    }
    out
}

// ---------------------------------------------------------------------------------------
// Explain.

/// One documented row: the table entry with its default.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Row {
    /// Path.
    pub path: String,
    /// Type.
    #[serde(rename = "type")]
    pub type_name: String,
    /// Unit.
    pub unit: String,
    /// Default.
    pub default: String,
    /// Allowed range.
    pub range: String,
    /// Meaning.
    pub description: String,
}

/// The allowed range of a field as text.
pub fn range_text(f: &Field) -> String {
    let base = match f.kind {
        Float | Int => f.bounds.text(),
        Text => "any text".into(),
        Enum(v) => format!("one of {}", v.join(", ")),
        IntChoice(v) => format!(
            "one of {}",
            v.iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
        Name(n) | NameOrTable(n) => format!("one of {}", n.list().join(", ")),
        Bool => "true or false".into(),
    };
    let base = if matches!(f.kind, NameOrTable(_)) {
        format!("{base}, or a table")
    } else {
        base
    };
    if f.note.is_empty() {
        base
    } else {
        format!("{base}; {}", f.note)
    }
}

/// Every field, in schema order.
pub fn rows() -> Vec<Row> {
    let defaults = defaults();
    TABLE
        .iter()
        .map(|f| Row {
            path: f.path.into(),
            type_name: f.kind.type_name().into(),
            unit: f.unit.into(),
            default: defaults
                .get(f.path)
                .map(Default_::text)
                .unwrap_or_else(|| "absent".into()),
            range: range_text(f),
            description: f.description.into(),
        })
        .collect()
}

/// `raceway scene --explain`: text or JSON.
pub fn explain(json: bool) -> String {
    let rows = rows();
    if json {
        return serde_json::to_string_pretty(&rows).expect("rows serialise") + "\n";
    }
    let mut s = String::from(
        "Scene fields (TOML; JSON takes the same names). `[]`: any item of the list;\n\
         <variable>: an input variable name; <body>: ball, inner_ring, outer_ring or cage.\n\n",
    );
    let mut section = "";
    for r in &rows {
        let top = r.path.split(['.', '[']).next().unwrap_or("");
        if top != section {
            section = if r.path.contains('.') { top } else { "" };
            if !section.is_empty() {
                let _ = writeln!(s, "[{section}]");
            }
        }
        let _ = writeln!(
            s,
            "  {}  ({}, {})  default {}\n      range: {}\n      {}",
            r.path, r.type_name, r.unit, r.default, r.range, r.description
        );
    }
    s.push('\n');
    s.push_str(super::limits::EXPLAIN);
    s
}

// ---------------------------------------------------------------------------------------
// Check.

/// One problem of a scene.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Problem {
    /// Field path (`""`: the whole scene).
    pub path: String,
    /// 1-based line and column (TOML only).
    pub line_col: Option<(usize, usize)>,
    /// What is wrong.
    pub message: String,
}

impl std::fmt::Display for Problem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if let Some((l, c)) = self.line_col {
            write!(f, "{l}:{c}: ")?;
        }
        if self.path.is_empty() {
            write!(f, "{}", self.message)
        } else {
            write!(f, "`{}`: {}", self.path, self.message)
        }
    }
}

/// A parsed value with its place, from TOML or JSON.
#[derive(Debug, Clone)]
enum Node {
    Str(String),
    Int(i128),
    Float(f64),
    Bool,
    Other(&'static str),
    Array(Vec<(Option<usize>, Node)>),
    /// Key, key offset, value offset, value.
    Table(Vec<(String, Option<usize>, Option<usize>, Node)>),
}

impl Node {
    fn type_name(&self) -> &'static str {
        match self {
            Node::Str(_) => "a string",
            Node::Int(_) => "an integer",
            Node::Float(_) => "a float",
            Node::Bool => "a boolean",
            Node::Other(t) => t,
            Node::Array(_) => "an array",
            Node::Table(_) => "a table",
        }
    }
}

fn from_de(v: &toml::de::DeValue<'_>) -> Node {
    use toml::de::DeValue as D;
    match v {
        D::String(s) => Node::Str(s.to_string()),
        D::Integer(i) => i128::from_str_radix(&i.as_str().replace('_', ""), i.radix())
            .map(Node::Int)
            .unwrap_or(Node::Other("an integer out of range")),
        D::Float(x) => {
            let t = x.as_str().replace('_', "");
            let v = match t.trim_start_matches(['+', '-']) {
                "inf" => f64::INFINITY,
                "nan" => f64::NAN,
                _ => t.parse().unwrap_or(f64::NAN),
            };
            Node::Float(if t.starts_with('-') && v.is_infinite() {
                -v.abs()
            } else {
                v
            })
        }
        D::Boolean(_) => Node::Bool,
        D::Datetime(_) => Node::Other("a date-time"),
        D::Array(a) => Node::Array(
            a.iter()
                .map(|x| (Some(x.span().start), from_de(x.get_ref())))
                .collect(),
        ),
        D::Table(t) => Node::Table(
            t.iter()
                .map(|(k, x)| {
                    (
                        k.get_ref().to_string(),
                        Some(k.span().start),
                        Some(x.span().start),
                        from_de(x.get_ref()),
                    )
                })
                .collect(),
        ),
    }
}

fn from_json(v: &serde_json::Value) -> Node {
    use serde_json::Value as J;
    match v {
        J::Null => Node::Other("null"),
        J::Bool(_) => Node::Bool,
        J::Number(n) => {
            if let Some(i) = n.as_i64() {
                Node::Int(i as i128)
            } else if let Some(u) = n.as_u64() {
                Node::Int(u as i128)
            } else {
                Node::Float(n.as_f64().unwrap_or(f64::NAN))
            }
        }
        J::String(s) => Node::Str(s.clone()),
        J::Array(a) => Node::Array(a.iter().map(|x| (None, from_json(x))).collect()),
        J::Object(o) => Node::Table(
            o.iter()
                .map(|(k, x)| (k.clone(), None, None, from_json(x)))
                .collect(),
        ),
    }
}

/// Levenshtein distance.
fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != *cb))
                .min(prev[j + 1] + 1)
                .min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// The nearest of `known` to `name`, if near enough to be a likely misspelling.
fn nearest<'a>(name: &str, known: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    known
        .into_iter()
        .map(|k| (distance(&name.to_lowercase(), &k.to_lowercase()), k))
        .filter(|(d, k)| *d <= (k.len().max(name.len()) / 2).max(2))
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

/// Known child keys of a normalised table path.
fn children(norm: &str) -> Vec<String> {
    let prefix = if norm.is_empty() {
        String::new()
    } else {
        format!("{norm}.")
    };
    let mut out: Vec<String> = TABLE
        .iter()
        .filter_map(|f| f.path.strip_prefix(prefix.as_str()))
        .filter(|rest| !rest.starts_with('<'))
        .map(|rest| rest.split(['.', '[']).next().unwrap_or(rest).to_string())
        .collect();
    // Children below a `<body>` placeholder.
    if let Some(body) = norm.strip_prefix("bearing.materials.") {
        if BODIES.contains(&body) {
            out.extend(
                TABLE
                    .iter()
                    .filter_map(|f| f.path.strip_prefix("bearing.materials.<body>."))
                    .map(str::to_string),
            );
        }
    }
    out.sort();
    out.dedup();
    out
}

/// The 1-based line and column (in characters) of a byte offset of `text`; also what
/// `raceway sweep` uses to place the problems of a sweep file.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut off = offset.min(text.len());
    while !text.is_char_boundary(off) {
        off -= 1;
    }
    let before = &text[..off];
    let line = before.matches('\n').count() + 1;
    let col = before
        .rfind('\n')
        .map_or(before.chars().count(), |i| before[i + 1..].chars().count())
        + 1;
    (line, col)
}

struct Checker<'a> {
    text: Option<&'a str>,
    problems: Vec<Problem>,
    /// Concrete path -> offset of its key (or value), for locating library errors.
    places: Vec<(String, Option<usize>)>,
}

impl Checker<'_> {
    fn line_col(&self, offset: Option<usize>) -> Option<(usize, usize)> {
        Some(line_col(self.text?, offset?))
    }

    fn report(&mut self, path: &str, offset: Option<usize>, message: String) {
        let line_col = self.line_col(offset);
        self.problems.push(Problem {
            path: path.to_string(),
            line_col,
            message,
        });
    }

    fn table(
        &mut self,
        entries: &[(String, Option<usize>, Option<usize>, Node)],
        path: &str,
        norm: &str,
        at: Option<usize>,
    ) {
        let known = children(norm);
        let has_preset = entries.iter().any(|(k, ..)| k == "preset");
        for (key, kofs, vofs, node) in entries {
            let cpath = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            let cnorm = normalise_child(norm, key);
            self.places.push((cpath.clone(), kofs.or(*vofs)));
            if norm == "inputs.initial" && !Names::InputVariable.contains(key) {
                let list = Names::InputVariable.list();
                let hint = nearest(key, list.iter().map(String::as_str))
                    .map(|n| format!(" (did you mean `{n}`?)"))
                    .unwrap_or_default();
                self.report(
                    &cpath,
                    *kofs,
                    format!(
                        "unknown input variable `{key}`{hint}; inputs: {}",
                        list.join(", ")
                    ),
                );
                continue;
            }
            let is_known = field(&cnorm).is_some()
                || TABLE.iter().any(|f| {
                    f.path.starts_with(&format!("{cnorm}."))
                        || f.path.starts_with(&format!("{cnorm}[]"))
                });
            if !is_known {
                let hint = nearest(key, known.iter().map(String::as_str))
                    .map(|n| format!("; did you mean `{n}`?"))
                    .unwrap_or_else(|| format!("; known here: {}", known.join(", ")));
                self.report(&cpath, *kofs, format!("unknown key `{key}`{hint}"));
                continue;
            }
            self.value(node, &cpath, &cnorm, vofs.or(*kofs));
        }
        // Missing required fields.
        let req = required();
        let group = match norm.strip_prefix("bearing.materials.") {
            Some(b) if BODIES.contains(&b) => "bearing.materials.<body>",
            _ => norm,
        };
        if let Some(keys) = req.get(group) {
            if norm == "bearing" && has_preset {
                return;
            }
            for k in keys {
                if !entries.iter().any(|(e, ..)| e == k) {
                    let here = if path.is_empty() { "the scene" } else { path };
                    self.report(
                        &if path.is_empty() {
                            k.clone()
                        } else {
                            format!("{path}.{k}")
                        },
                        at,
                        format!("missing required field `{k}` in {here}"),
                    );
                }
            }
        }
    }

    fn value(&mut self, node: &Node, path: &str, norm: &str, at: Option<usize>) {
        let entry = field(norm);
        // Tables and arrays of tables.
        match node {
            Node::Table(entries) => {
                let table_ok = matches!(entry.map(|e| e.kind), None | Some(NameOrTable(_)))
                    && TABLE
                        .iter()
                        .any(|f| f.path.starts_with(&format!("{norm}.")))
                    || matches!(entry.map(|e| e.kind), Some(NameOrTable(_)));
                if table_ok {
                    self.table(entries, path, norm, at);
                } else {
                    self.report(
                        path,
                        at,
                        format!("expected {}, found a table", expect(entry)),
                    );
                }
                return;
            }
            Node::Array(items) => {
                if entry.is_none()
                    && TABLE
                        .iter()
                        .any(|f| f.path.starts_with(&format!("{norm}[].")))
                {
                    for (i, (ofs, item)) in items.iter().enumerate() {
                        let ipath = format!("{path}[{i}]");
                        self.places.push((ipath.clone(), ofs.or(at)));
                        match item {
                            Node::Table(entries) => {
                                self.table(entries, &ipath, &format!("{norm}[]"), ofs.or(at))
                            }
                            other => self.report(
                                &ipath,
                                ofs.or(at),
                                format!("expected a table, found {}", other.type_name()),
                            ),
                        }
                    }
                } else {
                    self.report(
                        path,
                        at,
                        format!("expected {}, found an array", expect(entry)),
                    );
                }
                return;
            }
            _ => {}
        }
        let Some(entry) = entry else {
            self.report(
                path,
                at,
                format!("expected a table, found {}", node.type_name()),
            );
            return;
        };
        let wrong = |c: &mut Self| {
            c.report(
                path,
                at,
                format!(
                    "expected {}, found {}",
                    expect(Some(entry)),
                    node.type_name()
                ),
            )
        };
        match (entry.kind, node) {
            (Float, Node::Int(i)) => self.bounds(entry, path, at, *i as f64),
            (Float, Node::Float(x)) => self.bounds(entry, path, at, *x),
            (Int, Node::Int(i)) => self.bounds(entry, path, at, *i as f64),
            (IntChoice(v), Node::Int(i)) => {
                if !v.iter().any(|x| *x as i128 == *i) {
                    self.report(
                        path,
                        at,
                        format!("{i} is not allowed: {}", range_text(entry)),
                    );
                }
            }
            (Text, Node::Str(_)) | (Bool, Node::Bool) => {}
            (Enum(v), Node::Str(s)) => {
                if !v.contains(&s.as_str()) {
                    let hint = nearest(s, v.iter().copied())
                        .map(|n| format!(" (did you mean \"{n}\"?)"))
                        .unwrap_or_default();
                    self.report(
                        path,
                        at,
                        format!("unknown spelling \"{s}\"{hint}; allowed: {}", v.join(", ")),
                    );
                }
            }
            (Name(n) | NameOrTable(n), Node::Str(s)) => {
                if !n.contains(s) {
                    let list = n.list();
                    let hint = nearest(s, list.iter().map(String::as_str))
                        .map(|x| format!(" (did you mean \"{x}\"?)"))
                        .unwrap_or_default();
                    let what = match n {
                        Names::BearingPreset => "bearing preset",
                        Names::Material => "material",
                        Names::Lubricant => "lubricant",
                        Names::InputVariable => "input variable",
                    };
                    self.report(
                        path,
                        at,
                        format!("unknown {what} \"{s}\"{hint}; known: {}", list.join(", ")),
                    );
                }
            }
            _ => wrong(self),
        }
    }

    fn bounds(&mut self, entry: &Field, path: &str, at: Option<usize>, v: f64) {
        if !entry.bounds.contains(v) {
            self.report(
                path,
                at,
                format!("{v} is outside the allowed range {}", entry.bounds.text()),
            );
        }
    }

    /// The place of a library error's field: the path itself or its nearest given parent.
    fn locate(&self, field: &str) -> (String, Option<usize>) {
        let mut p = field.to_string();
        loop {
            if let Some((_, ofs)) = self.places.iter().find(|(q, _)| *q == p) {
                return (field.to_string(), *ofs);
            }
            match p.rfind(['.', '[']) {
                Some(i) => p.truncate(i),
                None => return (field.to_string(), None),
            }
        }
    }
}

fn expect(entry: Option<&Field>) -> String {
    match entry.map(|e| e.kind) {
        None => "a table".into(),
        Some(Float) => "a number".into(),
        Some(Int) | Some(IntChoice(_)) => "an integer".into(),
        Some(NameOrTable(_)) => "a name or a table".into(),
        Some(Bool) => "a boolean".into(),
        Some(_) => "a string".into(),
    }
}

/// Check a scene text (TOML, or JSON when it starts with `{`): every problem at once.
/// An empty list means the scene builds a component.
pub fn check(text: &str) -> Vec<Problem> {
    let json = text.trim_start().starts_with('{');
    let mut c = Checker {
        text: if json { None } else { Some(text) },
        problems: Vec::new(),
        places: Vec::new(),
    };
    let root = if json {
        match serde_json::from_str::<serde_json::Value>(text) {
            Ok(v) => from_json(&v),
            Err(e) => {
                c.problems.push(Problem {
                    path: String::new(),
                    line_col: Some((e.line(), e.column())),
                    message: format!("JSON syntax: {e}"),
                });
                return c.problems;
            }
        }
    } else {
        let (doc, errors) = toml::de::DeTable::parse_recoverable(text);
        if !errors.is_empty() {
            for e in errors {
                let at = e.span().map(|s| s.start);
                let msg = e.message().trim().to_string();
                c.report("", at, format!("TOML syntax: {msg}"));
            }
            return c.problems;
        }
        from_de(&toml::de::DeValue::Table(doc.into_inner()))
    };
    match &root {
        Node::Table(entries) => c.table(entries, "", "", Some(0)),
        other => c.report(
            "",
            None,
            format!("expected a table, found {}", other.type_name()),
        ),
    }
    c.problems.sort_by_key(|p| p.line_col);
    if !c.problems.is_empty() {
        return c.problems;
    }
    // Cross-field problems: the library's own checks, in the order a run meets them (the
    // component built, the run's inputs at its end and start set, the first outputs).
    let result = Scene::from_text(text).and_then(|s| {
        let b = s.validate()?;
        s.effects.validate_for(&b)?;
        crate::runner::prepare(&s).map(|_| ())
    });
    if let Err(e) = result {
        let field = match &e {
            crate::Error::Invalid { field, .. } => Some(field.clone()),
            crate::Error::Unknown { what, .. } if what.contains("effects.lubrication") => {
                Some("effects.lubrication.lubricant".to_string())
            }
            _ => None,
        };
        let (path, ofs) = field
            .as_deref()
            .map(|f| c.locate(f))
            .unwrap_or((String::new(), None));
        // A serde refusal the structural pass cannot see (e.g. a traction field of another
        // law): TOML's own message carries its line and column.
        let from_message = match (&e, ofs) {
            (crate::Error::Parse { message, .. }, None) => line_col_in(message),
            _ => None,
        };
        c.report(&path, ofs, e.to_string());
        if let (Some(lc), Some(last)) = (from_message, c.problems.last_mut()) {
            last.line_col = Some(lc);
            last.message = e
                .to_string()
                .lines()
                .last()
                .unwrap_or("")
                .trim()
                .to_string();
        }
    }
    c.problems
}

/// The one validation path of a scene file, shared by `raceway run` and `raceway scene
/// --check`: the text is checked exactly as [`check`] does (every problem at once); then
/// the command-line `overrides` (`(field path, value)`, e.g. `("run.duration_s", 0.1)`)
/// are written into it and the result is checked again the same way, so an override can
/// neither smuggle in a value the file could not hold nor hide one it holds. Problems of
/// the second pass carry no line (the file does not hold the overridden scene) and say
/// which overrides were applied. `Ok` is a scene that builds a component.
pub fn load(text: &str, overrides: &[(&str, f64)]) -> std::result::Result<Scene, Vec<Problem>> {
    let whole = |message: String| {
        vec![Problem {
            path: String::new(),
            line_col: None,
            message,
        }]
    };
    let problems = check(text);
    if !problems.is_empty() {
        return Err(problems);
    }
    if overrides.is_empty() {
        return Scene::from_text(text).map_err(|e| whole(e.to_string()));
    }
    // The scene as a TOML table (a JSON scene is converted), the overrides written in.
    let doc: std::result::Result<toml::Table, String> = if text.trim_start().starts_with('{') {
        serde_json::from_str::<serde_json::Value>(text)
            .map_err(|e| e.to_string())
            .and_then(|v| toml::Table::try_from(v).map_err(|e| e.to_string()))
    } else {
        toml::from_str(text).map_err(|e| e.to_string())
    };
    let mut doc = doc.map_err(|e| whole(format!("cannot apply the overrides: {e}")))?;
    for (path, value) in overrides {
        let mut keys: Vec<&str> = path.split('.').collect();
        let last = keys.pop().unwrap_or_default();
        let mut table = &mut doc;
        for k in keys {
            let entry = table
                .entry(k.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            table = match entry {
                toml::Value::Table(t) => t,
                _ => return Err(whole(format!("cannot apply the override of `{path}`"))),
            };
        }
        table.insert(last.to_string(), toml::Value::Float(*value));
    }
    let applied = overrides
        .iter()
        .map(|(p, v)| format!("{p} = {v}"))
        .collect::<Vec<_>>()
        .join(", ");
    let text2 = toml::to_string(&doc)
        .map_err(|e| whole(format!("cannot apply the overrides ({applied}): {e}")))?;
    let problems = check(&text2);
    if !problems.is_empty() {
        return Err(problems
            .into_iter()
            .map(|p| Problem {
                line_col: None,
                message: format!("{} (with the command-line override {applied})", p.message),
                ..p
            })
            .collect());
    }
    Scene::from_text(&text2).map_err(|e| whole(e.to_string()))
}

/// `line L, column C` in a parser's message.
fn line_col_in(message: &str) -> Option<(usize, usize)> {
    let rest = &message[message.find("line ")? + 5..];
    let (l, rest) = rest.split_once(", column ")?;
    let c: String = rest.chars().take_while(char::is_ascii_digit).collect();
    Some((l.trim().parse().ok()?, c.parse().ok()?))
}

/// One-line summary of a clean scene.
pub fn summary(scene: &Scene) -> String {
    let bearing = match &scene.bearing {
        BearingRef::Preset(p) => p.clone(),
        BearingRef::Table(_) => scene
            .bearing
            .spec()
            .map(|s| s.name)
            .unwrap_or_else(|_| "table".into()),
    };
    let e = &scene.effects;
    let mut effects = Vec::new();
    if !e.defects.is_empty() {
        effects.push(format!("{} defect(s)", e.defects.len()));
    }
    if !e.waviness.is_empty() {
        effects.push(format!("{} waviness harmonic(s)", e.waviness.len()));
    }
    if e.ball_spacing.is_some() {
        effects.push("ball spacing".into());
    }
    if let Some(l) = &e.lubrication {
        if l.film == FilmKind::Ehl {
            effects.push("EHL film".into());
        }
    }
    let m = &scene.model;
    let level = if m.level == super::Level::Ring {
        format!("ring {}-DOF", m.ring_dof)
    } else {
        m.level.name().to_string()
    };
    format!(
        "{bearing}, {level}, {}-driven, {}, run {} s at {} s steps",
        match m.causality {
            variables::Causality::Motion => "motion",
            variables::Causality::Load => "load",
        },
        if effects.is_empty() {
            "no effects".to_string()
        } else {
            effects.join(", ")
        },
        scene.run.duration_s,
        scene.run.step_s
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_matches_schema() {
        let schema: BTreeSet<String> = schema_paths().into_keys().collect();
        let table: BTreeSet<String> = TABLE.iter().map(|f| f.path.to_string()).collect();
        let missing: Vec<_> = schema.difference(&table).collect();
        let stale: Vec<_> = table.difference(&schema).collect();
        assert!(
            missing.is_empty(),
            "schema fields without a table entry: {missing:?}"
        );
        assert!(
            stale.is_empty(),
            "table entries naming no schema field: {stale:?}"
        );
        assert_eq!(table.len(), TABLE.len(), "duplicate table entries");
    }
}
