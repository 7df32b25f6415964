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

/// Test support shared by the element laws' tests.
#[cfg(test)]
pub(crate) mod test_util {
    /// `k` (the law's 5x5 stiffness at `q`, `k = -dF/dq`) against central differences of
    /// `f` over the coordinates `dofs` (steps 1e-10 m and 1e-8 rad), each entry within 1e-5
    /// of `reference` (`cross` times it where a rotation is involved); and `k` symmetric
    /// within `sym` of the geometric mean of its diagonal.
    pub(crate) fn assert_k_matches_differences(
        k: &[[f64; 5]; 5],
        q: [f64; 5],
        dofs: &[usize],
        f: impl Fn(&[f64; 5]) -> [f64; 5],
        reference: f64,
        cross: f64,
        sym: f64,
    ) {
        for &col in dofs {
            let h = if col < 3 { 1e-10 } else { 1e-8 };
            let (mut qp, mut qm) = (q, q);
            qp[col] += h;
            qm[col] -= h;
            let (fp, fm) = (f(&qp), f(&qm));
            for &row in dofs {
                let fd = -(fp[row] - fm[row]) / (2.0 * h);
                let scale = reference * if row > 2 || col > 2 { cross } else { 1.0 };
                assert!(
                    (k[row][col] - fd).abs() < 1e-5 * scale,
                    "K[{row}][{col}] {} vs {fd}",
                    k[row][col]
                );
            }
        }
        for i in 0..5 {
            for j in 0..5 {
                let scale = (k[i][i].abs() * k[j][j].abs()).sqrt().max(1.0);
                assert!((k[i][j] - k[j][i]).abs() < sym * scale, "K[{i}][{j}]");
            }
        }
    }
}
