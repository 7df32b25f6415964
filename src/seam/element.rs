//! The contact law of one rolling element, as a level that sums elements sees it: given the
//! inner ring's displacement relative to the outer ring at the element (in the element's
//! frame), the forces the element puts on the shaft, their derivatives, and what a report
//! reads of its contacts. A ball (Hertz point contact, solved for its own equilibrium at
//! speed) and a roller (line contact by laminae) are two implementations of
//! [`ElementLaw`]; [`assemble`] sums any of them into the wrench and stiffness of the
//! ring, so the quasi-static level needs no change for a new element type.
//!
//! Frames (docs/physics.md §0, §4): element `j` sits at azimuth `psi_j` from `+x` toward
//! `+y`; the ring displacement `q = (x, y, z, rx, ry)` moves the inner raceway at the
//! element by `axial = z`, `radial = x cos psi + y sin psi` and tilts it about the
//! element's tangential axis by `tilt = rx sin psi - ry cos psi` (small rotations). The
//! element's forces on the shaft `(F_a, F_r, m)` (axial, radial outward along the azimuth,
//! moment conjugate to `tilt`) give `Fx += F_r cos psi`, `Fy += F_r sin psi`, `Fz += F_a`,
//! `Mx += m sin psi`, `My -= m cos psi` (virtual work through the same map).

use crate::error::{Error, Result};

/// The inner ring's displacement at one element, in the element's frame (module docs): m,
/// m, rad.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ElementDisplacement {
    /// Along the bearing axis, m.
    pub axial: f64,
    /// Radially outward along the element's azimuth, m.
    pub radial: f64,
    /// Tilt about the element's tangential axis, rad.
    pub tilt: f64,
}

impl ElementDisplacement {
    /// The displacement at the element at `(sin psi, cos psi)` = `(s, c)` for ring
    /// displacement `q`.
    pub fn at(q: &[f64; 5], s: f64, c: f64) -> Self {
        ElementDisplacement {
            axial: q[2],
            radial: q[0] * c + q[1] * s,
            tilt: q[3] * s - q[4] * c,
        }
    }
}

/// Where an element is asked: its index, azimuth (rad) with its sine and cosine, and the
/// ring displacement (for the messages of a refusal, and for a law that forms its own
/// displacement from them).
#[derive(Debug, Clone, Copy)]
pub struct ElementAt<'a> {
    /// Element index.
    pub index: usize,
    /// Azimuth, rad.
    pub psi: f64,
    /// `(sin psi, cos psi)`.
    pub sc: (f64, f64),
    /// Ring displacement `(x, y, z, rx, ry)`, m and rad.
    pub q: &'a [f64; 5],
}

/// What the caller wants beyond the forces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Want {
    /// The derivatives [`ElementReaction::df`].
    pub stiffness: bool,
    /// The contact report ([`ElementReaction::load`], [`ElementReaction::pressure`]).
    pub report: bool,
}

/// One element's answer (SI).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ElementReaction {
    /// Forces on the shaft in the element's frame: axial (N), radial (N), moment conjugate
    /// to the tilt (N m).
    pub f: [f64; 3],
    /// `df[r][k] = d f[r] / d (axial, radial, tilt)[k]` (with [`Want::stiffness`]; zeros
    /// otherwise).
    pub df: [[f64; 3]; 3],
    /// Inner and outer contact loads, N (with [`Want::report`]).
    pub load: [f64; 2],
    /// Inner and outer peak contact pressures, Pa (with [`Want::report`]).
    pub pressure: [f64; 2],
    /// The element's approach along its contact line (both contacts), m; negative: a gap.
    /// What contact damping ramps in with (the ball law fills it when the stiffness or the
    /// report is wanted). A roller's is its most compressed lamina's, at speed its inner
    /// contact's (zero where that contact closes); with no lamina loaded the mid-length
    /// approach capped at zero (`contact::roller_law`, `contact::tapered_law`).
    pub approach: f64,
}

/// One rolling element's contact loads as a level reports them
/// ([`crate::seam::LevelModel::element_loads`]): where it is and what its two contacts carry.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ElementLoad {
    /// Azimuth, rad, in the seam's frame (module docs): from `+x` toward `+y`, so `3 pi / 2`
    /// is `-y`; at a positive shaft speed the elements travel toward increasing azimuth.
    /// As the level has it (not reduced to one turn).
    pub psi: f64,
    /// Inner contact load, N (a roller's: the sum over its laminae, [`ElementReaction::load`]).
    pub inner: f64,
    /// Outer contact load, N (the inner one plus what the element's inertia adds).
    pub outer: f64,
}

/// The contact law of one kind of rolling element.
pub trait ElementLaw: std::fmt::Debug + Send {
    /// The element kind's name, as scenes spell it (`ball`, `roller`).
    fn name(&self) -> &'static str;
    /// The radius (m) at which the element's axial force acts on the inner ring, when the
    /// law folds the ring's tilt into its axial displacement: `axial = z + arm tilt` (a
    /// ball: the radius of the inner groove-centre circle). 0 (the default): the law
    /// takes the tilt as its own input and answers the moment conjugate to it.
    fn moment_arm(&self) -> f64 {
        0.0
    }
    /// For contact damping of the tilt: the second moment of the element's contact line
    /// about its centre per unit of it, m² (a line of length `L` with the damping spread
    /// evenly: `L²/12`, so a tilt rate `w` meets the moment `-c L²/12 w`). 0 (the default):
    /// a point contact, whose tilt carries no damping of its own.
    fn tilt_damping_arm2(&self) -> f64 {
        0.0
    }
    /// Memory per element (warm starts), in numbers; the caller keeps it between calls.
    fn state_len(&self) -> usize;
    /// The element's reaction to the displacement `u` at shaft speed `omega` (rad/s),
    /// updating its memory `state` (length [`ElementLaw::state_len`]; all zeros: cold).
    fn react(
        &self,
        at: ElementAt<'_>,
        u: ElementDisplacement,
        omega: f64,
        state: &mut [f64],
        want: Want,
    ) -> Result<ElementReaction>;
}

/// The azimuths of `psi.len()` evenly spaced elements, the first at `theta` (rad): what the
/// levels that carry elements at the cage's kinematic positions place them at.
pub fn place_evenly(psi: &mut [f64], theta: f64) {
    let z = psi.len() as f64;
    for (j, p) in psi.iter_mut().enumerate() {
        *p = theta + 2.0 * std::f64::consts::PI * j as f64 / z;
    }
}

/// Sum elements at azimuths `psi` into the forces and moments on the shaft
/// `(Fx, Fy, Fz, Mx, My)` and, with `stiffness`, `K = -dF/dq` (module docs). `react(j, at,
/// u)` answers element `j`; `arm` is the laws' [`ElementLaw::moment_arm`] (the axial
/// displacement then carries `arm tilt`, and the moment `arm F_a`, the law's own moment
/// adding to it). Refuses a non-finite `q` or azimuth naming it, and non-finite sums as a
/// failed evaluation.
pub fn assemble(
    q: &[f64; 5],
    psi: &[f64],
    arm: f64,
    stiffness: Option<&mut [[f64; 5]; 5]>,
    react: impl FnMut(usize, ElementAt<'_>, ElementDisplacement) -> Result<ElementReaction>,
) -> Result<[f64; 5]> {
    sum(q, psi, |_, p| p.sin_cos(), arm, stiffness, react)
}

/// The `(sin, cos)` of evenly spaced azimuths `2 pi j/Z` (`Z = base.len()`), for
/// [`place_evenly_sc`].
pub fn even_base(z: usize) -> Vec<(f64, f64)> {
    (0..z)
        .map(|j| (2.0 * std::f64::consts::PI * j as f64 / z as f64).sin_cos())
        .collect()
}

/// [`place_evenly`] with each azimuth's `(sin, cos)` into `sc`, by rotating `base`
/// ([`even_base`]) through `theta`: one `sin_cos` for the whole ring (the sums of angles
/// agree with `sin_cos` of the azimuth to a few units in the last place).
pub fn place_evenly_sc(psi: &mut [f64], sc: &mut [(f64, f64)], base: &[(f64, f64)], theta: f64) {
    place_evenly(psi, theta);
    let (st, ct) = theta.sin_cos();
    for (o, &(sb, cb)) in sc.iter_mut().zip(base) {
        *o = (st * cb + ct * sb, ct * cb - st * sb);
    }
}

/// [`assemble`] with the azimuths' `(sin, cos)` given (`sc`, one per azimuth; from
/// [`place_evenly_sc`]).
pub fn assemble_sc(
    q: &[f64; 5],
    psi: &[f64],
    sc: &[(f64, f64)],
    arm: f64,
    stiffness: Option<&mut [[f64; 5]; 5]>,
    react: impl FnMut(usize, ElementAt<'_>, ElementDisplacement) -> Result<ElementReaction>,
) -> Result<[f64; 5]> {
    assert_eq!(sc.len(), psi.len(), "one (sin, cos) per azimuth");
    sum(q, psi, |j, _| sc[j], arm, stiffness, react)
}

fn sum(
    q: &[f64; 5],
    psi: &[f64],
    sin_cos: impl Fn(usize, f64) -> (f64, f64),
    arm: f64,
    mut stiffness: Option<&mut [[f64; 5]; 5]>,
    mut react: impl FnMut(usize, ElementAt<'_>, ElementDisplacement) -> Result<ElementReaction>,
) -> Result<[f64; 5]> {
    check_finite("q", q)?;
    if let Some(k) = stiffness.as_deref_mut() {
        *k = [[0.0; 5]; 5];
    }
    let mut f = [0.0; 5];
    for (j, &p) in psi.iter().enumerate() {
        if !p.is_finite() {
            return Err(Error::invalid(format!("psi[{j}]"), p, "a finite number"));
        }
        let (s, c) = sin_cos(j, p);
        let at = ElementAt {
            index: j,
            psi: p,
            sc: (s, c),
            q,
        };
        let mut u = ElementDisplacement::at(q, s, c);
        if arm != 0.0 {
            u.axial += arm * u.tilt;
        }
        let r = react(j, at, u)?;
        let [fa, fr, m] = r.f;
        f[0] += fr * c;
        f[1] += fr * s;
        f[2] += fa;
        f[3] += m * s;
        f[4] -= m * c;
        // An unloaded element adds nothing to K (skipped: most of a ring's elements).
        if let Some(k) = stiffness.as_deref_mut().filter(|_| r.df != [[0.0; 3]; 3]) {
            // K = -J^T df J with J the rows of d(axial, radial, tilt)/dq:
            // ja = [0, 0, 1, arm s, -arm c], jr = [c, s, 0, 0, 0], jt = [0, 0, 0, s, -c]. The
            // products with their structural zeros are left out: each is a signed zero, and
            // a signed zero added to a sum or taken from an entry of `k` (never -0: it starts
            // at +0, and x - x rounds to +0) changes no bit of finite entries.
            let [da, dr, dm] = r.df;
            let rows = [
                [dr[0] * c, dr[1] * c, dr[2] * c],
                [dr[0] * s, dr[1] * s, dr[2] * s],
                da,
                [dm[0] * s, dm[1] * s, dm[2] * s],
                [-dm[0] * c, -dm[1] * c, -dm[2] * c],
            ];
            let (as_, ac) = (arm * s, -arm * c);
            for (i, r) in rows.iter().enumerate() {
                let ki = &mut k[i];
                ki[0] -= r[1] * c;
                ki[1] -= r[1] * s;
                ki[2] -= r[0];
                ki[3] -= r[0] * as_ + r[2] * s;
                ki[4] -= r[0] * ac + r[2] * -c;
            }
        }
    }
    check_finite("forces", &f).map_err(|_| Error::NotConverged {
        what: "ring forces of the elements (non-finite)",
        iterations: 0,
        residual: f64::NAN,
    })?;
    Ok(f)
}

fn check_finite(what: &str, v: &[f64]) -> Result<()> {
    for (k, x) in v.iter().enumerate() {
        if !x.is_finite() {
            return Err(Error::invalid(format!("{what}[{k}]"), x, "a finite number"));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A linear radial spring per element, `F_r = -k u_r` (no axial, no tilt).
    fn spring(
        k: f64,
    ) -> impl FnMut(usize, ElementAt<'_>, ElementDisplacement) -> Result<ElementReaction> {
        move |_, _, u| {
            Ok(ElementReaction {
                f: [0.0, -k * u.radial, 0.0],
                df: [[0.0; 3], [0.0, -k, 0.0], [0.0; 3]],
                ..Default::default()
            })
        }
    }

    #[test]
    fn rotated_azimuths_agree_with_sin_cos() {
        let z = 14;
        let base = even_base(z);
        let (mut psi, mut sc) = (vec![0.0; z], vec![(0.0, 0.0); z]);
        for theta in [0.0, 0.3, -2.0, 45.0, 1.0e3] {
            place_evenly_sc(&mut psi, &mut sc, &base, theta);
            for (p, &(s, c)) in psi.iter().zip(&sc) {
                let (s0, c0) = p.sin_cos();
                // The azimuth itself carries theta's rounding, ~1e-16 theta.
                let tol = 4e-16 * (1.0 + theta.abs());
                assert!((s - s0).abs() < tol && (c - c0).abs() < tol, "{theta} {p}");
            }
        }
    }

    #[test]
    fn radial_springs_sum_to_the_isotropic_ring_stiffness() {
        // Z equal radial springs k on a full circle: K_xx = K_yy = Z k / 2, K_xy = 0, and a
        // displacement x gives Fx = -Z k x / 2 (sum of cos² over evenly spaced azimuths).
        let (z, k) = (9usize, 2.0e8);
        let psi: Vec<f64> = (0..z)
            .map(|j| 0.3 + 2.0 * std::f64::consts::PI * j as f64 / z as f64)
            .collect();
        let mut kk = [[0.0; 5]; 5];
        let f = assemble(
            &[1e-6, 0.0, 0.0, 0.0, 0.0],
            &psi,
            0.0,
            Some(&mut kk),
            spring(k),
        )
        .unwrap();
        let want = z as f64 * k / 2.0;
        assert!((kk[0][0] / want - 1.0).abs() < 1e-12, "{}", kk[0][0]);
        assert!((kk[1][1] / want - 1.0).abs() < 1e-12);
        assert!(kk[0][1].abs() < 1e-6 * want);
        assert!((f[0] / (-want * 1e-6) - 1.0).abs() < 1e-12, "{f:?}");
        assert!(f[1].abs() < 1e-9 * want * 1e-6);
    }

    #[test]
    fn stiffness_is_minus_the_derivative_of_the_forces() {
        // An element with axial, radial and tilt coupling: K from the assembly equals the
        // central difference of the assembled forces.
        let law = |_: usize, _: ElementAt<'_>, u: ElementDisplacement| {
            let f = [
                -3e8 * u.axial - 1e7 * u.radial * u.radial * 1e6,
                -2e8 * u.radial - 5e7 * u.tilt * 1e-3,
                -4e3 * u.tilt - 1e5 * u.axial,
            ];
            let df = [
                [-3e8, -2e7 * u.radial * 1e6, 0.0],
                [0.0, -2e8, -5e4],
                [-1e5, 0.0, -4e3],
            ];
            Ok(ElementReaction {
                f,
                df,
                ..Default::default()
            })
        };
        let psi: Vec<f64> = (0..7).map(|j| 0.1 + 0.9 * j as f64).collect();
        let q = [2e-6, -1e-6, 3e-6, 1e-4, -2e-4];
        for arm in [0.0, 0.02] {
            let mut kk = [[0.0; 5]; 5];
            assemble(&q, &psi, arm, Some(&mut kk), law).unwrap();
            for col in 0..5 {
                let h = if col < 3 { 1e-9 } else { 1e-7 };
                let (mut qp, mut qm) = (q, q);
                qp[col] += h;
                qm[col] -= h;
                let fp = assemble(&qp, &psi, arm, None, law).unwrap();
                let fm = assemble(&qm, &psi, arm, None, law).unwrap();
                for row in 0..5 {
                    let fd = -(fp[row] - fm[row]) / (2.0 * h);
                    let scale = kk[row][col].abs().max(1e3);
                    assert!(
                        (kk[row][col] - fd).abs() < 1e-6 * scale,
                        "arm {arm}: K[{row}][{col}] {} vs {fd}",
                        kk[row][col]
                    );
                }
            }
        }
    }

    #[test]
    fn a_non_finite_azimuth_is_refused_by_name() {
        let e = assemble(&[0.0; 5], &[0.0, f64::NAN], 0.0, None, spring(1.0)).unwrap_err();
        assert!(e.to_string().contains("psi[1]"), "{e}");
    }
}
