//! The physics ladder: quasi-static equilibrium and the dynamic levels.

pub mod defects;
pub mod effects;
pub mod full;
pub mod linear;
pub mod quasi_static;
pub mod ring;
pub mod skidding;
pub mod thermal;
pub mod waviness;
pub mod wear;
pub mod wear_map;
