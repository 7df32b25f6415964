//! The rolling element a bearing carries, as the levels see it: which kind it is, so the
//! level registry can say which kinds each level accepts and refuse a pair it cannot model
//! with a message naming both. Balls (point contact, docs/physics.md §3) are the only kind
//! built today; rollers (line contact by laminae, §3 and ISO/TS 16281) are named so a
//! scene that asks for them is refused clearly rather than read as a ball bearing.

use serde::{Deserialize, Serialize};

/// The kind of rolling element.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum ElementKind {
    /// Balls: Hertz point contact with the grooves.
    #[default]
    Ball,
    /// Cylindrical or tapered rollers: line contact.
    Roller,
}

impl ElementKind {
    /// Every kind.
    pub const ALL: [ElementKind; 2] = [ElementKind::Ball, ElementKind::Roller];

    /// Its spelling in scenes and messages.
    pub const fn name(self) -> &'static str {
        match self {
            ElementKind::Ball => "ball",
            ElementKind::Roller => "roller",
        }
    }
}

impl std::fmt::Display for ElementKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Distance between the groove curvature centres of a ball bearing at zero load and zero
/// clearance, `A = (f_i + f_o - 1) D` (docs/physics.md §1): the one place it is written.
pub fn groove_centre_distance(fi: f64, fo: f64, d: f64) -> f64 {
    (fi + fo - 1.0) * d
}
