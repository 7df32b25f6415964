//! The variable table: every name, value reference, unit and role of the co-simulation
//! contract (docs/physics.md §9, §C1–§C5), once. The C header, the FMI model
//! descriptions and the documentation tables are generated from this table.

/// Which causality a scene runs in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Causality {
    /// Shaft motion in, forces out (what rotor codes couple to).
    #[default]
    Motion,
    /// Loads in; the inner ring (with an optional attached mass) is integrated inside;
    /// motion and forces out.
    Load,
}

/// What part a variable plays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Inner-ring motion: an input when motion-driven, an output when load-driven.
    Motion,
    /// Shaft speed: an input in both causalities.
    Speed,
    /// External load: an input when load-driven, unused when motion-driven.
    Load,
    /// An output in both causalities.
    Output,
}

/// The type of a variable's value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VarType {
    /// A real number (FMI 2 `Real`, FMI 3 `Float64`, C `double`).
    Real,
    /// A count (FMI 2 `Integer`, FMI 3 `Int32`, C `int32_t`); discrete: it changes only at
    /// communication points. The Rust API and `raceway_get_real` also give it as an exact
    /// `f64`.
    Integer,
}

/// One variable of the contract.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variable {
    /// Dotted name, e.g. `force.x`.
    pub name: &'static str,
    /// Value reference (stable across versions; FMI and C use it).
    pub vr: u32,
    /// SI unit.
    pub unit: &'static str,
    /// Role.
    pub role: Role,
    /// One-line meaning.
    pub description: &'static str,
    /// Value type.
    pub ty: VarType,
    /// Outputs: which levels and effects set it ([`Sets::EVERY_LEVEL`]: every level).
    /// A recorded run (series.csv, Python's DataFrame) carries only the outputs its level
    /// and effects set ([`crate::component::levels::LevelEntry::sets`]).
    pub set_by: Sets,
}

/// Groups of outputs that only some levels or effects set, as bits: a level's registry
/// entry names the groups it sets, an effect adds its own. Outputs outside every group are
/// set by every level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Sets(pub u8);

impl Sets {
    /// Set by every level.
    pub const EVERY_LEVEL: Sets = Sets(0);
    /// The cage's own speed against the kinematic one (`cage.slip`, `cage.speed_ratio`):
    /// levels that integrate the cage (elsewhere the cage runs at its kinematic speed).
    pub const CAGE_SLIP: Sets = Sets(1);
    /// The cage centre and its guide (`cage.x`, `cage.y`, `cage.speed`, `guide.force`).
    pub const CAGE_WHIRL: Sets = Sets(2);
    /// Ball-pocket forces (`pocket.max_force`).
    pub const POCKET: Sets = Sets(4);
    /// Friction torque and power (`torque.z`, `power.loss`): levels with traction, or the
    /// thermal effect.
    pub const FRICTION: Sets = Sets(8);
    /// The EHL film (`film.min_thickness`): the lubrication effect with an EHL film.
    pub const FILM: Sets = Sets(16);
    /// Race wear (`wear.max_depth`): the wear effect.
    pub const WEAR: Sets = Sets(32);
    /// Per-row outputs of a bearing set (`row<i>.*`): scenes with a `[set]`.
    pub const SET_ROWS: Sets = Sets(64);

    /// Both groups.
    pub const fn with(self, other: Sets) -> Sets {
        Sets(self.0 | other.0)
    }
    /// Does `self` include every group of `group`?
    pub const fn covers(self, group: Sets) -> bool {
        self.0 & group.0 == group.0
    }
}

impl Variable {
    /// Is this an input under `causality`?
    pub fn is_input(&self, causality: Causality) -> bool {
        matches!(
            (self.role, causality),
            (Role::Speed, _) | (Role::Motion, Causality::Motion) | (Role::Load, Causality::Load)
        )
    }
    /// Is this an output under `causality`?
    pub fn is_output(&self, causality: Causality) -> bool {
        matches!(
            (self.role, causality),
            (Role::Output, _) | (Role::Motion, Causality::Load)
        )
    }
    /// Is this an output under `causality` that a run setting the groups `sets` sets
    /// (`crate::component::levels::outputs_set`)?
    pub fn is_set(&self, causality: Causality, sets: Sets) -> bool {
        self.is_output(causality) && sets.covers(self.set_by)
    }
}

/// Generalised coordinates of the inner ring, in the order of the K and C matrices.
pub const DOF: [&str; 5] = ["x", "y", "z", "rx", "ry"];

const fn v(
    name: &'static str,
    vr: u32,
    unit: &'static str,
    role: Role,
    description: &'static str,
) -> Variable {
    Variable {
        name,
        vr,
        unit,
        role,
        description,
        ty: VarType::Real,
        set_by: Sets::EVERY_LEVEL,
    }
}

impl Variable {
    /// The variable set only by the levels and effects of `group`.
    const fn only(self, group: Sets) -> Variable {
        Variable {
            set_by: group,
            ..self
        }
    }
}

/// A count: as [`v`], of type [`VarType::Integer`].
const fn count(name: &'static str, vr: u32, role: Role, description: &'static str) -> Variable {
    Variable {
        ty: VarType::Integer,
        ..v(name, vr, "1", role, description)
    }
}

use Role::*;

/// Value reference of `K.<i>.<j>`: `200 + 5 i + j`.
pub const VR_K0: u32 = 200;
/// Value reference of `C.<i>.<j>`: `300 + 5 i + j`.
pub const VR_C0: u32 = 300;

/// The scalar variables other than the K and C matrices.
pub const SCALARS: &[Variable] = &[
    v(
        "shaft.x",
        1,
        "m",
        Motion,
        "inner-ring centre displacement x relative to the outer ring; plausible: |x| <= radial play + approach at 7.5 GPa Hertz (scene --explain)",
    ),
    v(
        "shaft.y",
        2,
        "m",
        Motion,
        "inner-ring centre displacement y; plausible: |y| <= radial play + approach at 7.5 GPa Hertz (scene --explain)",
    ),
    v(
        "shaft.z",
        3,
        "m",
        Motion,
        "inner-ring centre displacement z (axial); plausible: |z| <= axial play + approach at 7.5 GPa Hertz (scene --explain)",
    ),
    v("shaft.rx", 4, "rad", Motion, "inner-ring tilt about x; plausible: |rx| <= axial limit / inner groove radius"),
    v("shaft.ry", 5, "rad", Motion, "inner-ring tilt about y; plausible: |ry| <= axial limit / inner groove radius"),
    v("shaft.vx", 6, "m/s", Motion, "inner-ring velocity x; plausible: |vx| <= ring burst rim speed"),
    v("shaft.vy", 7, "m/s", Motion, "inner-ring velocity y; plausible: |vy| <= ring burst rim speed"),
    v("shaft.vz", 8, "m/s", Motion, "inner-ring velocity z; plausible: |vz| <= ring burst rim speed"),
    v(
        "shaft.wx",
        9,
        "rad/s",
        Motion,
        "inner-ring tilt rate about x; plausible: |wx| <= ring burst speed",
    ),
    v(
        "shaft.wy",
        10,
        "rad/s",
        Motion,
        "inner-ring tilt rate about y; plausible: |wy| <= ring burst speed",
    ),
    v(
        "shaft.omega",
        11,
        "rad/s",
        Speed,
        "inner-ring spin speed about z; plausible: |omega| <= inner-ring burst speed (scene --explain)",
    ),
    v(
        "load.x",
        21,
        "N",
        Load,
        "external force on the inner ring, x; plausible: |F| <= Z balls at the 7.5 GPa load",
    ),
    v(
        "load.y",
        22,
        "N",
        Load,
        "external force on the inner ring, y; plausible: |F| <= Z balls at the 7.5 GPa load",
    ),
    v(
        "load.z",
        23,
        "N",
        Load,
        "external force on the inner ring, z; plausible: |F| <= Z balls at the 7.5 GPa load",
    ),
    v(
        "load.mx",
        24,
        "N.m",
        Load,
        "external moment on the inner ring about x; plausible: |M| <= Z balls at the 7.5 GPa load on the inner groove radius",
    ),
    v(
        "load.my",
        25,
        "N.m",
        Load,
        "external moment on the inner ring about y; plausible: |M| <= Z balls at the 7.5 GPa load on the inner groove radius",
    ),
    v(
        "force.x",
        101,
        "N",
        Output,
        "force of the bearing on the shaft, x",
    ),
    v(
        "force.y",
        102,
        "N",
        Output,
        "force of the bearing on the shaft, y",
    ),
    v(
        "force.z",
        103,
        "N",
        Output,
        "force of the bearing on the shaft, z",
    ),
    v(
        "moment.x",
        104,
        "N.m",
        Output,
        "moment of the bearing on the shaft about x",
    ),
    v(
        "moment.y",
        105,
        "N.m",
        Output,
        "moment of the bearing on the shaft about y",
    ),
    v(
        "torque.z",
        106,
        "N.m",
        Output,
        "friction (drag) torque on the shaft about z",
    )
    .only(Sets::FRICTION),
    v("cage.omega", 107, "rad/s", Output, "cage speed"),
    v(
        "cage.slip",
        108,
        "1",
        Output,
        "cage slip ratio 1 - omega_c/omega_c,kinematic",
    )
    .only(Sets::CAGE_SLIP),
    count("balls.loaded", 109, Output, "number of balls in contact"),
    v(
        "contact.max_load",
        110,
        "N",
        Output,
        "load of the most loaded contact",
    ),
    v(
        "contact.max_pressure",
        111,
        "Pa",
        Output,
        "Hertz peak pressure of the most loaded contact",
    ),
    v(
        "film.min_thickness",
        112,
        "m",
        Output,
        "thinnest EHL film (0 when lubrication is off)",
    )
    .only(Sets::FILM),
    v("power.loss", 113, "W", Output, "friction power")
    .only(Sets::FRICTION),
    v(
        "wear.max_depth",
        114,
        "m",
        Output,
        "deepest wear on any race",
    )
    .only(Sets::WEAR),
    v(
        "cage.x",
        115,
        "1",
        Output,
        "cage-centre displacement x in units of the guide clearance (full level)",
    )
    .only(Sets::CAGE_WHIRL),
    v(
        "cage.y",
        116,
        "1",
        Output,
        "cage-centre displacement y in units of the guide clearance (full level)",
    )
    .only(Sets::CAGE_WHIRL),
    v(
        "cage.speed",
        117,
        "m/s",
        Output,
        "speed |v| of the cage centre (full level; its std/mean is the whirl index sigma)",
    )
    .only(Sets::CAGE_WHIRL),
    v(
        "cage.speed_ratio",
        118,
        "1",
        Output,
        "cage speed over its kinematic speed, 1 - cage.slip",
    )
    .only(Sets::CAGE_SLIP),
    v(
        "pocket.max_force",
        119,
        "N",
        Output,
        "largest ball-pocket force (skidding and full levels)",
    )
    .only(Sets::POCKET),
    v(
        "guide.force",
        120,
        "N",
        Output,
        "cage guide-land force (full level)",
    )
    .only(Sets::CAGE_WHIRL),
    v(
        "safety.S0",
        121,
        "1",
        Output,
        "static safety factor C0/P0 (ISO 76) of the bearing force; 1e6 when unloaded, 0 where ISO 76 does not cover the bearing",
    ),
    v(
        "life.L10",
        122,
        "Mrev",
        Output,
        "basic rating life (C/P)^3 (ISO 281) of the bearing force, in millions of revolutions; 1e12 when unloaded, 0 where ISO 281 does not cover the bearing",
    ),
    count(
        "warnings.active",
        123,
        Output,
        "number of active warnings: peak contact pressure beyond ISO 76's limit, fewer than two loaded balls",
    ),
];

/// Unit of row `i` (force or moment) divided by column `j` (displacement or tilt).
const fn k_unit(i: usize, j: usize) -> &'static str {
    match (i < 3, j < 3) {
        (true, true) => "N/m",
        (true, false) => "N/rad",
        (false, true) => "N",
        (false, false) => "N.m/rad",
    }
}
const fn c_unit(i: usize, j: usize) -> &'static str {
    match (i < 3, j < 3) {
        (true, true) => "N.s/m",
        (true, false) => "N.s/rad",
        (false, true) => "N.s",
        (false, false) => "N.m.s/rad",
    }
}

macro_rules! matrix_vars {
    ($p:literal, $vr0:expr, $unit:ident, $desc:literal) => {
        [
            matrix_vars!(@row $p, $vr0, $unit, $desc, 0, "x"),
            matrix_vars!(@row $p, $vr0, $unit, $desc, 1, "y"),
            matrix_vars!(@row $p, $vr0, $unit, $desc, 2, "z"),
            matrix_vars!(@row $p, $vr0, $unit, $desc, 3, "rx"),
            matrix_vars!(@row $p, $vr0, $unit, $desc, 4, "ry"),
        ]
    };
    (@row $p:literal, $vr0:expr, $unit:ident, $desc:literal, $i:expr, $ri:literal) => {
        [
            v(concat!($p, ".", $ri, ".x"), $vr0 + 5 * $i, $unit($i, 0), Output, $desc),
            v(concat!($p, ".", $ri, ".y"), $vr0 + 5 * $i + 1, $unit($i, 1), Output, $desc),
            v(concat!($p, ".", $ri, ".z"), $vr0 + 5 * $i + 2, $unit($i, 2), Output, $desc),
            v(concat!($p, ".", $ri, ".rx"), $vr0 + 5 * $i + 3, $unit($i, 3), Output, $desc),
            v(concat!($p, ".", $ri, ".ry"), $vr0 + 5 * $i + 4, $unit($i, 4), Output, $desc),
        ]
    };
}

/// `K.<i>.<j>`: stiffness `-dF_i/dq_j` at the current state.
pub const STIFFNESS: [[Variable; 5]; 5] = matrix_vars!("K", VR_K0, k_unit, "stiffness -dF_i/dq_j");
/// `C.<i>.<j>`: damping `-dF_i/dv_j` at the current state.
pub const DAMPING: [[Variable; 5]; 5] = matrix_vars!("C", VR_C0, c_unit, "damping -dF_i/dv_j");

/// Value reference of `row<i>.<k-th output>`: `400 + 10 i + k`.
pub const VR_ROW0: u32 = 400;
/// Outputs per row of a set.
pub const ROW_OUTPUTS: usize = 8;
/// Rows of a set with declared outputs (`crate::component::scene::MAX_SET_ROWS`).
pub const ROWS: usize = 4;

macro_rules! row_vars {
    ($i:literal) => {
        [
            v(concat!("row", $i, ".force.x"), VR_ROW0 + 10 * $i, "N", Output, "set row: force of the row on the shaft at the row, x").only(Sets::SET_ROWS),
            v(concat!("row", $i, ".force.y"), VR_ROW0 + 10 * $i + 1, "N", Output, "set row: force of the row on the shaft at the row, y").only(Sets::SET_ROWS),
            v(concat!("row", $i, ".force.z"), VR_ROW0 + 10 * $i + 2, "N", Output, "set row: force of the row on the shaft at the row, z (axial)").only(Sets::SET_ROWS),
            v(concat!("row", $i, ".moment.x"), VR_ROW0 + 10 * $i + 3, "N.m", Output, "set row: moment of the row on the shaft about x at the row").only(Sets::SET_ROWS),
            v(concat!("row", $i, ".moment.y"), VR_ROW0 + 10 * $i + 4, "N.m", Output, "set row: moment of the row on the shaft about y at the row").only(Sets::SET_ROWS),
            v(concat!("row", $i, ".contact_angle"), VR_ROW0 + 10 * $i + 5, "rad", Output, "set row: load-weighted mean inner contact angle of the loaded balls (quasi-static ball equilibrium at the row's displacement; roller rows: nominal; 0 when lifted off)").only(Sets::SET_ROWS),
            count(concat!("row", $i, ".lift_off"), VR_ROW0 + 10 * $i + 6, Output, "set row: 1 when no element of the row is loaded, else 0").only(Sets::SET_ROWS),
            v(concat!("row", $i, ".life.L10"), VR_ROW0 + 10 * $i + 7, "Mrev", Output, "set row: basic rating life (ISO 281) of the row's own load, millions of revolutions; 1e12 when unloaded").only(Sets::SET_ROWS),
        ]
    };
}

/// `row<i>.*`: the per-row outputs of a bearing set (set only by scenes with a `[set]`;
/// zeros otherwise). Row `i` is the `i`-th row of the set (a pair: the row at `-z`
/// first). Life and safety of the whole set are `life.L10` (the rows' system life) and
/// `safety.S0` (the smallest row's).
pub const ROW_VARS: [[Variable; ROW_OUTPUTS]; ROWS] =
    [row_vars!(0), row_vars!(1), row_vars!(2), row_vars!(3)];

/// Every variable, in a stable order: scalars, then K row by row, then C, then the
/// per-row outputs of a set.
pub fn all() -> impl Iterator<Item = &'static Variable> {
    SCALARS
        .iter()
        .chain(STIFFNESS.iter().flatten())
        .chain(DAMPING.iter().flatten())
        .chain(ROW_VARS.iter().flatten())
}

/// One past the largest value reference.
const VR_END: usize = VR_ROW0 as usize + 10 * ROWS;

/// The position in [`all`] of each value reference (`u16::MAX`: none), built at compile
/// time: a value reference at or beyond [`VR_END`] or given twice fails the build. The hot
/// path (every `get_real` and `set_real`) looks a reference up here instead of scanning.
static SLOTS: [u16; VR_END] = slots();

const fn slots() -> [u16; VR_END] {
    let mut t = [u16::MAX; VR_END];
    let mut i = 0;
    while i < SCALARS.len() {
        let vr = SCALARS[i].vr as usize;
        assert!(t[vr] == u16::MAX, "value reference used twice");
        t[vr] = i as u16;
        i += 1;
    }
    let mut k = 0;
    while k < 25 {
        let (r, c) = (k / 5, k % 5);
        let (vk, vc) = (STIFFNESS[r][c].vr as usize, DAMPING[r][c].vr as usize);
        assert!(
            t[vk] == u16::MAX && t[vc] == u16::MAX,
            "value reference used twice"
        );
        t[vk] = (SCALARS.len() + k) as u16;
        t[vc] = (SCALARS.len() + 25 + k) as u16;
        k += 1;
    }
    let mut k = 0;
    while k < ROWS * ROW_OUTPUTS {
        let vr = ROW_VARS[k / ROW_OUTPUTS][k % ROW_OUTPUTS].vr as usize;
        assert!(t[vr] == u16::MAX, "value reference used twice");
        t[vr] = (SCALARS.len() + 50 + k) as u16;
        k += 1;
    }
    t
}

/// The position of value reference `vr` in [`all`] (the index into a state's `inputs`
/// and `outputs`), in constant time.
pub fn slot(vr: u32) -> Option<usize> {
    match SLOTS.get(vr as usize) {
        Some(&i) if i != u16::MAX => Some(i as usize),
        _ => None,
    }
}

/// The variable at position `i` of [`all`].
fn at(i: usize) -> &'static Variable {
    let n = SCALARS.len();
    match i {
        _ if i < n => &SCALARS[i],
        _ if i < n + 25 => &STIFFNESS[(i - n) / 5][(i - n) % 5],
        _ if i < n + 50 => &DAMPING[(i - n - 25) / 5][(i - n - 25) % 5],
        _ => &ROW_VARS[(i - n - 50) / ROW_OUTPUTS][(i - n - 50) % ROW_OUTPUTS],
    }
}

/// Look a variable up by value reference (constant time).
pub fn by_vr(vr: u32) -> Option<&'static Variable> {
    slot(vr).map(at)
}

/// Look a variable up by name.
pub fn by_name(name: &str) -> Option<&'static Variable> {
    all().find(|v| v.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The constant-time lookup agrees with a scan of the table for every reference up
    /// to well past the largest.
    #[test]
    fn slot_lookup_matches_a_scan() {
        for vr in 0..2 * VR_END as u32 {
            let scan = all().position(|v| v.vr == vr);
            assert_eq!(slot(vr), scan, "vr {vr}");
            assert_eq!(by_vr(vr).map(|v| v.vr), scan.map(|_| vr));
        }
        assert_eq!(slot(u32::MAX), None);
    }

    #[test]
    fn names_and_value_references_are_unique() {
        let all: Vec<_> = all().collect();
        for (i, a) in all.iter().enumerate() {
            for b in &all[i + 1..] {
                assert_ne!(a.vr, b.vr, "{} / {}", a.name, b.name);
                assert_ne!(a.name, b.name);
            }
        }
        assert_eq!(all.len(), SCALARS.len() + 50 + ROWS * ROW_OUTPUTS);
        assert_eq!(by_name("K.rx.y").unwrap().vr, VR_K0 + 16);
        assert_eq!(by_name("C.x.ry").unwrap().unit, "N.s/rad");
    }
}

/// Type of a parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamType {
    /// A real number (SI unit given).
    Real,
    /// A string.
    String,
    /// A Boolean switch.
    Boolean,
    /// One of named items, numbered from 1 (FMI `Enumeration`; FMI 2 `Integer` access,
    /// FMI 3 `Int64` access). Item 0 of every enumeration here is `scene`: leave the scene's
    /// own choice.
    Enumeration {
        /// Type name in `<TypeDefinitions>`.
        type_name: &'static str,
        /// Item names; item `k` has value `k`.
        items: &'static [&'static str],
    },
}

impl ParamType {
    /// A number per kind (for the GUID hash).
    pub const fn tag(self) -> u8 {
        match self {
            ParamType::Real => 0,
            ParamType::String => 1,
            ParamType::Boolean => 2,
            ParamType::Enumeration { .. } => 3,
        }
    }
}

/// A scene field exposed as a parameter (FMI parameters, C ABI setters).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parameter {
    /// Name.
    pub name: &'static str,
    /// Value reference.
    pub vr: u32,
    /// Type.
    pub ty: ParamType,
    /// SI unit ("" for strings).
    pub unit: &'static str,
    /// Start value as text (as it appears in a model description).
    pub start: &'static str,
    /// One-line meaning.
    pub description: &'static str,
}

/// Items of the `level` parameter: `scene`, then every level's scene spelling.
pub const LEVEL_ITEMS: [&str; 6] = [
    "scene",
    crate::component::scene::Level::NAMES[0],
    crate::component::scene::Level::NAMES[1],
    crate::component::scene::Level::NAMES[2],
    crate::component::scene::Level::NAMES[3],
    crate::component::scene::Level::NAMES[4],
];

/// Items of the `input_rule` parameter: `scene`, then the scene's `inputs.rule` spellings.
pub const INPUT_RULE_ITEMS: [&str; 4] = ["scene", "hold", "velocity", "derivatives"];

/// Items of the `solver` parameter: `scene`, then the scene's `solver.method` spellings.
pub const SOLVER_ITEMS: [&str; crate::solver::methods::METHOD_NAMES.len() + 1] = {
    let names = crate::solver::methods::METHOD_NAMES;
    let mut items = ["scene"; crate::solver::methods::METHOD_NAMES.len() + 1];
    let mut i = 0;
    while i < names.len() {
        items[i + 1] = names[i];
        i += 1;
    }
    items
};

/// The scene rows the named parameters stand for: their unit, range and description are
/// the row's.
const CLEARANCE_UM: &super::fields::FieldDecl =
    super::fields::find(crate::geometry::BearingSpec::FIELDS, "clearance_um");
const SPEED_RPM: &super::fields::FieldDecl =
    super::fields::find(super::scene::InputSpec::FIELDS, "speed_rpm");
const SOLVER_METHOD: &super::fields::FieldDecl =
    super::fields::find(super::scene::SolverSpec::FIELDS, "method");

/// The scene fields exposed as parameters. A parameter the host never sets (or sets to
/// its start value) leaves the field as the scene (or the preset) has it; the named ones
/// (`clearance_um`, `speed_rpm`, `solver`, `rtol`) override the same field of the scene
/// (string or resource) when the host sets them (`solver` item 0, `scene`: not set).
pub const PARAMETERS: &[Parameter] = &[
    Parameter {
        name: "scene",
        vr: 1000,
        ty: ParamType::String,
        unit: "",
        start: "",
        description: "a whole scene as TOML or JSON text (empty: the default scene, or resources/scene.toml if the FMU carries one)",
    },
    Parameter {
        name: "bearing",
        vr: 1001,
        ty: ParamType::String,
        unit: "",
        start: "",
        description: "bearing preset name (overrides the scene's bearing; empty: the scene's)",
    },
    Parameter {
        name: "level",
        vr: 1002,
        ty: ParamType::Enumeration {
            type_name: "Level",
            items: &LEVEL_ITEMS,
        },
        unit: "",
        start: "0",
        description: "model level (scene: as the scene has it)",
    },
    Parameter {
        name: "input_rule",
        vr: 1003,
        ty: ParamType::Enumeration {
            type_name: "InputRule",
            items: &INPUT_RULE_ITEMS,
        },
        unit: "",
        start: "0",
        description: "how inputs move inside a step (scene: as the scene has it)",
    },
    Parameter {
        name: "clearance",
        vr: 1004,
        ty: ParamType::Real,
        unit: "m",
        start: "0",
        description: "diametral clearance, negative for preload; used only when override_clearance is true",
    },
    Parameter {
        name: "rtol",
        vr: 1005,
        ty: ParamType::Real,
        unit: "1",
        start: "1e-6",
        description: "relative tolerance of the internal integrator (applied only when set)",
    },
    Parameter {
        name: "override_clearance",
        vr: 1006,
        ty: ParamType::Boolean,
        unit: "",
        start: "false",
        description: "true: the bearing takes the `clearance` parameter; false: its own clearance",
    },
    Parameter {
        name: "clearance_um",
        vr: 1007,
        ty: ParamType::Real,
        unit: CLEARANCE_UM.unit,
        start: "0",
        description: CLEARANCE_UM.description,
    },
    Parameter {
        name: "speed_rpm",
        vr: 1008,
        ty: ParamType::Real,
        unit: SPEED_RPM.unit,
        start: "1750",
        description: SPEED_RPM.description,
    },
    Parameter {
        name: "solver",
        vr: 1009,
        ty: ParamType::Enumeration {
            type_name: "Solver",
            items: &SOLVER_ITEMS,
        },
        unit: "",
        start: "0",
        description: SOLVER_METHOD.description,
    },
];

/// How people read a unit: `(SI unit, display unit, factor)` with
/// `value in display unit = factor × value in SI unit` (the FMI `DisplayUnit` convention,
/// spec2 §2.2.2, spec3 §2.4.3). The first row of a unit is the one its variables show.
pub const DISPLAY_UNITS: &[(&str, &str, f64)] = &[
    ("m", "µm", 1e6),
    ("m", "mm", 1e3),
    ("rad", "deg", 180.0 / std::f64::consts::PI),
    ("rad/s", "rpm", 30.0 / std::f64::consts::PI),
    ("Pa", "GPa", 1e-9),
    ("Pa", "MPa", 1e-6),
    ("N", "kN", 1e-3),
    ("N/m", "N/µm", 1e-6),
];

/// The display unit a variable of SI unit `unit` shows (and its factor), if any.
pub fn display_unit(unit: &str) -> Option<(&'static str, f64)> {
    DISPLAY_UNITS
        .iter()
        .find(|(u, _, _)| *u == unit)
        .map(|&(_, d, f)| (d, f))
}

/// Declared ranges `(name, min, max)` (SI) of the inputs and parameters: what the FMUs
/// declare as `min`/`max` and refuse outside. They are plausibility bounds, wide enough
/// for any ball bearing the models cover: ring displacements within 1 mm and tilts within
/// 0.1 rad (both far beyond clearance plus contact deflection, tens of µm and a few mrad),
/// ring velocities those of a 1 mm / 0.1 rad vibration up to about 15 kHz, shaft speeds up
/// to 2e4 rad/s (about 191 000 rpm), loads up to 10 MN and 1 MN·m; the parameters' ranges
/// are those the scene accepts (`params.rs`; `rtol` reads its range from the
/// `solver.rtol` row, [`super::scene::SolverSpec::FIELDS`]).
pub const RANGES: &[(&str, f64, f64)] = &[
    ("shaft.x", -1e-3, 1e-3),
    ("shaft.y", -1e-3, 1e-3),
    ("shaft.z", -1e-3, 1e-3),
    ("shaft.rx", -0.1, 0.1),
    ("shaft.ry", -0.1, 0.1),
    ("shaft.vx", -100.0, 100.0),
    ("shaft.vy", -100.0, 100.0),
    ("shaft.vz", -100.0, 100.0),
    ("shaft.wx", -1e4, 1e4),
    ("shaft.wy", -1e4, 1e4),
    ("shaft.omega", -OMEGA_MAX, OMEGA_MAX),
    ("load.x", -1e7, 1e7),
    ("load.y", -1e7, 1e7),
    ("load.z", -1e7, 1e7),
    ("load.mx", -1e6, 1e6),
    ("load.my", -1e6, 1e6),
    ("clearance", -1e-3, 1e-3),
    ("rtol", RTOL.min(), RTOL.max()),
    (
        "clearance_um",
        CLEARANCE_UM.bounds.min(),
        CLEARANCE_UM.bounds.max(),
    ),
    // The scene row bounds the speed by the bearing's burst speed (plausibility limits),
    // no fixed range: the parameter takes the input `shaft.omega`'s, in rpm.
    ("speed_rpm", -OMEGA_MAX * 30.0 / PI, OMEGA_MAX * 30.0 / PI),
];

/// Largest shaft speed an FMU accepts, rad/s (about 191 000 rpm).
const OMEGA_MAX: f64 = 2e4;
const PI: f64 = std::f64::consts::PI;

/// The scene's `solver.rtol` range, as its row declares it.
const RTOL: super::fields::Bounds =
    super::fields::find(super::scene::SolverSpec::FIELDS, "rtol").bounds;

/// The declared range of input or parameter `name`, if it has one.
pub fn range(name: &str) -> Option<(f64, f64)> {
    RANGES
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|&(_, lo, hi)| (lo, hi))
}

#[cfg(test)]
mod metadata_tests {
    use super::*;

    #[test]
    fn every_input_and_real_parameter_has_a_range_and_display_units_are_consistent() {
        for v in all().filter(|v| v.role != Role::Output) {
            let (lo, hi) = range(v.name).unwrap_or_else(|| panic!("{} has no range", v.name));
            assert!(lo < 0.0 && hi > 0.0, "{}: 0 (the start) is inside", v.name);
        }
        for p in PARAMETERS.iter().filter(|p| p.ty == ParamType::Real) {
            let (lo, hi) = range(p.name).unwrap();
            let s: f64 = p.start.parse().unwrap();
            assert!(lo <= s && s <= hi, "{}: start {s} in [{lo}, {hi}]", p.name);
        }
        // rpm: 1750 rpm is 183.26 rad/s; µm and GPa by their prefixes.
        let (d, f) = display_unit("rad/s").unwrap();
        assert_eq!(d, "rpm");
        assert!((183.259_571 * f - 1750.0).abs() < 1e-3);
        assert_eq!(display_unit("m"), Some(("µm", 1e6)));
        assert_eq!(display_unit("Pa"), Some(("GPa", 1e-9)));
    }
}
