//! Bearing geometry, materials, presets and kinematics.

pub mod bearing;
pub mod catalogue;
pub mod element;
pub mod kinematics;
pub mod material;
pub mod presets;
pub mod roller;
pub mod roller_catalogue;

pub use bearing::{
    Bearing, BearingKind, BearingSpec, Cage, CageSpec, Guidance, MaterialSpec, MaterialsSpec,
};
pub use element::ElementKind;
pub use kinematics::{kinematics, kinematics_at, Kinematics};
pub use material::{effective_modulus, Material};
pub use presets::{preset, presets};
