//! The rolling element a bearing carries. A bearing description ([`super::Bearing`]) is what
//! every bearing has in common (rings, clearance, pitch diameter, count, materials, cage)
//! plus one [`Element`]: a ball with the groove curvatures it runs in, or a roller with its
//! length, profile and flanges ([`super::roller::RollerBearing`]). The level registry says which [`ElementKind`]s each level accepts and
//! refuses a pair it cannot model with a message naming both; the contact law of an element
//! sits behind [`crate::seam::element::ElementLaw`].

use crate::error::{Error, Result};
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

/// A ball's groove: the curvature ratios of the raceways it runs in (docs/physics.md §1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Groove {
    /// Inner groove curvature ratio `f_i = r_i / D` (> 0.5).
    pub fi: f64,
    /// Outer groove curvature ratio `f_o = r_o / D` (> 0.5).
    pub fo: f64,
}

impl Groove {
    /// Distance between the groove curvature centres at zero load and zero clearance,
    /// `A = (f_i + f_o - 1) D` for ball diameter `d` (docs/physics.md §1): the one place it
    /// is written.
    pub fn centre_distance(&self, d: f64) -> f64 {
        groove_centre_distance(self.fi, self.fo, d)
    }
}

/// The rolling element of a bearing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Element {
    /// A ball in its grooves.
    Ball(Groove),
    /// A roller, with everything line contact needs (its bearing's roller data, SI).
    Roller(Box<super::roller::RollerBearing>),
}

impl Element {
    /// Its kind.
    pub const fn kind(&self) -> ElementKind {
        match self {
            Element::Ball(_) => ElementKind::Ball,
            Element::Roller(_) => ElementKind::Roller,
        }
    }

    /// The groove of a ball; a roller has none: the refusal names the element kind and what
    /// asked (`what`, e.g. "the ISO 281 ball rating").
    pub fn groove(&self, what: &str) -> Result<&Groove> {
        match self {
            Element::Ball(g) => Ok(g),
            Element::Roller(_) => Err(Error::invalid(
                "bearing",
                "a roller bearing",
                format!("a ball bearing: {what} is written for balls"),
            )),
        }
    }
}

/// Distance between the groove curvature centres of a ball bearing at zero load and zero
/// clearance, `A = (f_i + f_o - 1) D` (docs/physics.md §1): the one place it is written.
pub fn groove_centre_distance(fi: f64, fo: f64, d: f64) -> f64 {
    (fi + fo - 1.0) * d
}
