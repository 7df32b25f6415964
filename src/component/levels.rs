//! The level registry: every model level in one list, [`LEVELS`]. An entry tells the
//! component the level's scene name (written only there), whether it is stiff, whether it
//! takes the scene's `[effects]`, and how to build it from a validated scene. The level
//! itself lives in its own folder, `models/<level>/` (physics in `mod.rs` and beside it,
//! the [`LevelModel`] glue in `level.rs`); adding a level is that folder plus one line
//! here. The component asks the registry and never matches on the level.

use super::level::LevelModel;
use super::scene::Scene;
use super::variables::Sets;
use crate::error::{Error, Result};
use crate::geometry::{Bearing, ElementKind};
use crate::models::LevelArgs;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Builds a level from plain data (one signature for every level).
pub type Build = fn(&LevelArgs) -> Result<Box<dyn LevelModel>>;

/// What the component knows about a level.
#[derive(Clone, Copy)]
pub struct LevelEntry {
    /// Scene spelling (`model.level`).
    pub name: &'static str,
    /// Stiff (docs/physics.md §N1.2: traction slopes): `solver.method = "auto"` picks RODAS4;
    /// otherwise DOPRI5.
    pub stiff: bool,
    /// Takes the scene's `[effects]` (defects, waviness, films, wear, thermal); a scene
    /// with effects on and a level that does not take them is refused.
    pub effects: bool,
    /// Constructor.
    pub build: Build,
    /// The rolling-element kinds the level models; a bearing of another kind is refused
    /// naming both.
    pub elements: &'static [ElementKind],
    /// Checks of the level's own options at scene validation (before anything is built).
    pub check: Check,
    /// The groups of outputs the level sets itself beyond those every level sets (the
    /// variable table tags each output with its group); the effects add theirs
    /// ([`outputs_set`]).
    pub sets: Sets,
}

/// Checks a level's own options (one signature for every level).
pub type Check = fn(&LevelArgs) -> Result<()>;

/// For levels whose options need no check beyond their field rows.
fn no_check(_: &LevelArgs) -> Result<()> {
    Ok(())
}

/// Balls only.
const BALLS: &[ElementKind] = &[ElementKind::Ball];

impl LevelEntry {
    const fn new(name: &'static str, stiff: bool, effects: bool, build: Build) -> Self {
        LevelEntry {
            name,
            stiff,
            effects,
            build,
            elements: BALLS,
            check: no_check,
            sets: Sets::EVERY_LEVEL,
        }
    }

    /// The groups of outputs the level sets beyond those every level sets.
    const fn with_sets(mut self, sets: Sets) -> Self {
        self.sets = sets;
        self
    }

    const fn with_check(mut self, check: Check) -> Self {
        self.check = check;
        self
    }

    /// The element kinds the level takes (default: balls).
    const fn with_elements(mut self, elements: &'static [ElementKind]) -> Self {
        self.elements = elements;
        self
    }
}

impl std::fmt::Debug for LevelEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LevelEntry")
            .field("name", &self.name)
            .field("stiff", &self.stiff)
            .field("effects", &self.effects)
            .finish()
    }
}

/// Every level, lowest fidelity first (the order of [`Level::ALL`]).
#[rustfmt::skip]
pub const LEVELS: &[LevelEntry] = &[
    //              name            stiff  effects  constructor
    LevelEntry::new("linear",       false, false,   crate::models::linear::level::build),
    LevelEntry::new("quasi_static", false, false,   crate::models::quasi_static::level::build)
        .with_elements(crate::models::quasi_static::level::ELEMENTS),
    LevelEntry::new("ring",         false, true,    crate::models::ring::level::build)
        .with_elements(crate::models::ring::level::ELEMENTS),
    LevelEntry::new("skidding",     true,  false,   crate::models::skidding::level::build)
        .with_check(crate::models::skidding::level::check)
        .with_sets(Sets::CAGE_SLIP.with(Sets::POCKET).with(Sets::FRICTION)),
    LevelEntry::new("full",         true,  false,   crate::models::full::level::build)
        .with_sets(Sets::CAGE_SLIP.with(Sets::POCKET).with(Sets::FRICTION).with(Sets::CAGE_WHIRL)),
];

/// The groups of outputs a run of `scene` sets: its level's own, and those of its effects
/// when the level takes effects (an EHL film sets `film.min_thickness`, wear
/// `wear.max_depth`, the thermal effect the friction torque and power).
pub fn outputs_set(scene: &Scene) -> Sets {
    let entry = scene.model.level.entry();
    let mut sets = entry.sets;
    if entry.effects {
        let e = &scene.effects;
        let on = |b: bool, g: Sets| if b { g } else { Sets::EVERY_LEVEL };
        let film = e
            .lubrication
            .as_ref()
            .is_some_and(|l| l.film == crate::models::effects::FilmKind::Ehl);
        sets = sets
            .with(on(film, Sets::FILM))
            .with(on(e.wear.is_some(), Sets::WEAR))
            .with(on(e.thermal.is_some(), Sets::FRICTION));
    }
    if scene.set.is_some() {
        sets = sets.with(Sets::SET_ROWS);
    }
    sets
}

/// Number of levels.
const N: usize = LEVELS.len();

/// A model level: a position in [`LEVELS`]. Scenes spell it by its entry's name.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Level(u8);

#[allow(non_upper_case_globals)]
impl Level {
    /// Constant K and C from the quasi-static linearisation at an operating point.
    pub const Linear: Level = Level::named("linear");
    /// Per-ball Jones–Harris equilibrium at the current motion, balls at the cage's
    /// kinematic positions.
    pub const QuasiStatic: Level = Level::named("quasi_static");
    /// Ring on massless balls (docs/physics.md §5.1).
    pub const Ring: Level = Level::named("ring");
    /// Ball orbit and spin, cage, traction and drag (docs/physics.md §5.2).
    pub const Skidding: Level = Level::named("skidding");
    /// High-speed dynamics with cage whirl (docs/physics.md §5.5).
    pub const Full: Level = Level::named("full");

    /// Every level, lowest fidelity first.
    pub const ALL: [Level; N] = {
        let mut all = [Level(0); N];
        let mut i = 0;
        while i < N {
            all[i] = Level(i as u8);
            i += 1;
        }
        all
    };
    /// Every scene spelling, in the order of [`Level::ALL`].
    pub const NAMES: [&'static str; N] = {
        let mut names = [""; N];
        let mut i = 0;
        while i < N {
            names[i] = LEVELS[i].name;
            i += 1;
        }
        names
    };

    /// The level registered as `name` (a name not in [`LEVELS`] fails to compile when
    /// used in a constant).
    pub const fn named(name: &str) -> Level {
        let mut i = 0;
        while i < N {
            if same(LEVELS[i].name.as_bytes(), name.as_bytes()) {
                return Level(i as u8);
            }
            i += 1;
        }
        panic!("no such level in LEVELS")
    }

    /// The level a scene spells `name`, if any.
    pub fn from_name(name: &str) -> Option<Level> {
        Level::NAMES
            .iter()
            .position(|n| *n == name)
            .map(|i| Level(i as u8))
    }

    /// Scene spelling.
    pub const fn name(self) -> &'static str {
        LEVELS[self.0 as usize].name
    }

    /// The level's registry entry.
    pub fn entry(self) -> &'static LevelEntry {
        &LEVELS[self.0 as usize]
    }

    /// Does the level model bearings with `element`? Refused naming both, and the levels
    /// that do.
    pub fn accepts(self, element: ElementKind) -> Result<()> {
        let entry = self.entry();
        if entry.elements.contains(&element) {
            return Ok(());
        }
        let takers: Vec<&str> = LEVELS
            .iter()
            .filter(|l| l.elements.contains(&element))
            .map(|l| l.name)
            .collect();
        Err(Error::invalid(
            "model.level",
            entry.name,
            format!(
                "a level that models {element} bearings (level `{}` takes {}; levels that take {element}s: {})",
                entry.name,
                entry
                    .elements
                    .iter()
                    .map(|e| format!("{e}s"))
                    .collect::<Vec<_>>()
                    .join(", "),
                if takers.is_empty() {
                    "none yet".to_string()
                } else {
                    takers.join(", ")
                }
            ),
        ))
    }

    /// Check the level's own options for a scene (its registry entry's check).
    pub fn check(self, scene: &Scene, b: &Bearing) -> Result<()> {
        self.accepts(b.element())?;
        (self.entry().check)(&scene.level_args(b))
    }

    /// Build the level for a validated scene: refuses an element kind or effects the
    /// level does not take, then calls the level's constructor.
    pub fn build(self, scene: &Scene, b: &Bearing) -> Result<Box<dyn LevelModel>> {
        let entry = self.entry();
        self.accepts(b.element())?;
        if !scene.effects.is_off() && !entry.effects {
            let takers: Vec<String> = LEVELS
                .iter()
                .filter(|l| l.effects)
                .map(|l| format!("\"{}\"", l.name))
                .collect();
            return Err(Error::invalid(
                "effects",
                format!("on with level {}", entry.name),
                format!(
                    "only with level = {} (the levels that apply defects, waviness and films)",
                    takers.join(" or ")
                ),
            ));
        }
        if let Some(spec) = scene.set_spec(b)? {
            // A set: every row built by this level's own constructor for its bearing.
            return crate::models::set::level::build(&scene.level_args(b), &spec, entry.build);
        }
        (entry.build)(&scene.level_args(b))
    }
}

/// Byte-wise equality in a `const fn`.
const fn same(a: &[u8], b: &[u8]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

impl Default for Level {
    fn default() -> Self {
        Level::QuasiStatic
    }
}

impl std::fmt::Debug for Level {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::fmt::Display for Level {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl Serialize for Level {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Level {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct Names;
        impl serde::de::Visitor<'_> for Names {
            type Value = Level;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("enum Level")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<Level, E> {
                Level::from_name(v).ok_or_else(|| E::unknown_variant(v, &Level::NAMES))
            }
        }
        d.deserialize_str(Names)
    }
}

/// Kinematic cage speed for the nominal contact angle (written once, in the geometry).
pub use crate::geometry::kinematics::nominal_cage_speed as cage_speed;

#[cfg(test)]
mod tests {
    use super::*;

    /// Names are unique, every level round-trips through its scene spelling, and a name
    /// no level has is refused listing the allowed ones.
    #[test]
    fn names_round_trip_and_unknown_names_are_refused() {
        for (i, l) in Level::ALL.iter().enumerate() {
            assert_eq!(Level::from_name(l.name()), Some(*l));
            assert_eq!(Level::NAMES[i], l.name());
            let json = serde_json::to_string(l).unwrap();
            assert_eq!(json, format!("\"{}\"", l.name()));
            assert_eq!(serde_json::from_str::<Level>(&json).unwrap(), *l);
        }
        for (i, a) in Level::NAMES.iter().enumerate() {
            assert!(!Level::NAMES[..i].contains(a), "`{a}` registered twice");
        }
        let e = serde_json::from_str::<Level>("\"best\"")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("unknown variant `best`") && e.contains("`full`"),
            "{e}"
        );
        assert_eq!(Level::default().name(), "quasi_static");
    }

    /// The registry says which element kinds each level takes: every level takes balls, the
    /// quasi-static and ring levels rollers too, and a bearing of a kind a level does not take is
    /// refused naming the level, the kind and the levels that do take it.
    #[test]
    fn a_level_refuses_an_element_kind_it_does_not_take_naming_both() {
        for l in Level::ALL {
            assert!(l.accepts(ElementKind::Ball).is_ok(), "{}", l.name());
            if l == Level::QuasiStatic || l == Level::Ring {
                assert!(l.accepts(ElementKind::Roller).is_ok());
                continue;
            }
            let e = l.accepts(ElementKind::Roller).unwrap_err().to_string();
            assert!(
                e.contains("model.level")
                    && e.contains(&format!("level `{}`", l.name()))
                    && e.contains("roller")
                    && e.contains("levels that take rollers: quasi_static, ring"),
                "{e}"
            );
        }
        let b = crate::geometry::preset("6205").unwrap().build().unwrap();
        assert_eq!(b.element(), ElementKind::Ball);
    }
}
