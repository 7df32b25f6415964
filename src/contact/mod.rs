//! Contact mechanics: Hertz point contact between a ball and a race.

pub mod hertz;

pub use hertz::{series_constant, Curvature, Ellipse, PointContact, Race};
