//! Contact mechanics: Hertz point contact between a ball and a race, the complete elliptic
//! integrals it needs, and Palmgren's line-contact law.

pub mod elliptic;
pub mod hertz;
pub mod lamina;
pub mod roller_law;
pub mod tapered_law;
pub mod traction;

pub use hertz::{
    ellipse_fit, ellipse_fit_hb83, hertz_load_and_stiffness, series_constant, BallRaceContacts,
    ContactCoefficients, ContactTable, Curvature, Ellipse, EllipseSensitivity, LineContact,
    PointContact, Race,
};
