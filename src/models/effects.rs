//! Optional effects a scene can switch on (defects, waviness, lubrication). Every effect
//! is off unless the scene names it, and costs nothing when off.

use serde::{Deserialize, Serialize};

/// The `[effects]` section of a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct Effects {}

impl Effects {
    /// Validate; errors name `effects.<field>`.
    pub fn validate(&self) -> crate::error::Result<()> {
        Ok(())
    }
}
