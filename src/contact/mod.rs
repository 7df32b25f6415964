//! Contact mechanics: Hertz point contact between a ball and a race, the complete elliptic
//! integrals it needs, and Palmgren's line-contact law.

pub mod elliptic;
pub mod hertz;
pub mod lamina;
pub mod roller_law;
pub mod tapered_law;
pub mod traction;

/// The contact law of a roller bearing's elements: tapered or cylindrical (the one place a
/// roller kind picks its law); `inertia`: the rollers' centrifugal force (and a tapered roller's
/// gyroscopic moment) at speed (false: massless rollers, as the ring level's elements are).
pub fn roller_law(
    r: &crate::geometry::roller::RollerBearing,
    inertia: bool,
) -> crate::error::Result<Box<dyn crate::seam::element::ElementLaw>> {
    Ok(if r.kind.is_tapered() {
        let l = tapered_law::TaperedRollerLaw::new(r)?;
        Box::new(if inertia { l } else { l.massless() })
    } else if inertia {
        Box::new(roller_law::CylindricalRollerLaw::new(r)?)
    } else {
        Box::new(roller_law::CylindricalRollerLaw::new(r)?.massless())
    })
}

pub use hertz::{
    ellipse_fit, ellipse_fit_hb83, hertz_load_and_stiffness, series_constant, BallRaceContacts,
    ContactCoefficients, ContactTable, Curvature, Ellipse, EllipseSensitivity, LineContact,
    PointContact, Race,
};
