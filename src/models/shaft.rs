//! A rigid shaft on several bearing locations (docs/physics.md §11): each location a
//! bearing set ([`crate::models::set`], a single bearing being a set of one row) at an
//! axial position along the shaft, the shaft loaded by forces and moments at axial
//! positions, solved for its 5-DOF equilibrium with the nonlinear bearings.
//!
//! The shaft's motion `q = (x, y, z, rx, ry)` is taken at the shaft's origin (`z = 0` of
//! the positions); a location at `z_L` sees `A_L q` (`x + z_L ry`, `y - z_L rx`, the rest
//! unchanged) and gives `A_L^T F_L` there, as the rows of a set do about its reference
//! point. A load `(Fx, Fy, Fz)` at `z_P` with moments `(Mx, My)` is
//! `(Fx, Fy, Fz, Mx - z_P Fy, My + z_P Fx)` at the origin. Equilibrium:
//! `sum_L A_L^T F_L(A_L q) + load = 0`, by damped Newton with the exact stiffness.

use crate::error::{Error, Result};
use crate::models::set::{RingTemperatures, Set, SetSolution, SetSpec};
use serde::Serialize;

/// One bearing location.
#[derive(Debug, Clone)]
pub struct Location {
    /// Name (for reports).
    pub name: String,
    /// Axial position of the set's reference point on the shaft, m.
    pub position: f64,
    /// The set (one row for a single bearing).
    pub set: SetSpec,
    /// The location floats axially (its outer rings slide in the housing, or a
    /// cylindrical roller row without flanges): it carries no axial load, the set finding
    /// its own axial position where its thrust vanishes.
    pub floating: bool,
    /// The rings' temperatures ([`RingTemperatures`]; the reference: as assembled).
    pub temperatures: RingTemperatures,
}

/// A load on the shaft.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShaftLoad {
    /// Axial position, m.
    pub position: f64,
    /// Force `(Fx, Fy, Fz)`, N.
    pub force: [f64; 3],
    /// Moment `(Mx, My)`, N m.
    pub moment: [f64; 2],
}

/// A rigid shaft.
#[derive(Debug, Clone)]
pub struct Shaft {
    /// The bearing locations.
    pub locations: Vec<Location>,
    /// The loads.
    pub loads: Vec<ShaftLoad>,
    /// Shaft speed, rad/s.
    pub omega: f64,
}

/// One location at the equilibrium.
#[derive(Debug, Clone, Serialize)]
pub struct LocationResult {
    /// Name.
    pub name: String,
    /// Axial position, m.
    pub position: f64,
    /// The set's answer (its `q` and forces at its own reference point).
    pub set: SetSolution,
    /// Every row of the location has lifted off.
    pub lifted_off: bool,
    /// The location floats axially (carries no axial load).
    pub floating: bool,
}

/// The shaft's equilibrium.
#[derive(Debug, Clone, Serialize)]
pub struct ShaftSolution {
    /// Shaft speed, rad/s.
    pub omega: f64,
    /// The external load at the origin `(Fx, Fy, Fz, Mx, My)`.
    pub load: [f64; 5],
    /// Shaft displacement at the origin, m and rad.
    pub q: [f64; 5],
    /// System stiffness at the origin, SI.
    pub stiffness: [[f64; 5]; 5],
    /// The locations.
    pub locations: Vec<LocationResult>,
    /// System life of every row of every location, millions of revolutions.
    pub life_mrev: Option<f64>,
    /// Sentences a user must read (lift-off).
    pub warnings: Vec<String>,
}

/// `A_L q` for a location at `z`.
fn at(z: f64, q: &[f64; 5]) -> [f64; 5] {
    [q[0] + z * q[4], q[1] - z * q[3], q[2], q[3], q[4]]
}

/// `A_L^T f` for a location at `z`.
fn back(z: f64, f: &[f64; 5]) -> [f64; 5] {
    [f[0], f[1], f[2], f[3] - z * f[1], f[4] + z * f[0]]
}

/// `A_L^T K A_L`.
fn back_k(z: f64, k: &[[f64; 5]; 5]) -> [[f64; 5]; 5] {
    let a = [
        [1.0, 0.0, 0.0, 0.0, z],
        [0.0, 1.0, 0.0, -z, 0.0],
        [0.0, 0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 0.0, 1.0],
    ];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut s = 0.0;
            for (r, ar) in a.iter().enumerate() {
                for (c, ac) in a.iter().enumerate() {
                    s += ar[i] * k[r][c] * ac[j];
                }
            }
            s
        })
    })
}

const DOF: [&str; 5] = ["x", "y", "z", "tilt about x", "tilt about y"];

impl Shaft {
    /// The external loads summed at the origin.
    pub fn load_at_origin(&self) -> [f64; 5] {
        let mut l = [0.0; 5];
        for p in &self.loads {
            l[0] += p.force[0];
            l[1] += p.force[1];
            l[2] += p.force[2];
            l[3] += p.moment[0] - p.position * p.force[1];
            l[4] += p.moment[1] + p.position * p.force[0];
        }
        l
    }

    fn check(&self) -> Result<()> {
        if self.locations.is_empty() {
            return Err(Error::invalid(
                "location",
                "none",
                "at least one bearing location",
            ));
        }
        if !self.omega.is_finite() {
            return Err(Error::invalid("speed_rpm", self.omega, "a finite number"));
        }
        for (i, l) in self.locations.iter().enumerate() {
            if !l.position.is_finite() {
                return Err(Error::invalid(
                    format!("location[{i}].position_mm"),
                    l.position * 1e3,
                    "a finite number",
                ));
            }
        }
        for (i, p) in self.loads.iter().enumerate() {
            let all = [
                p.position,
                p.force[0],
                p.force[1],
                p.force[2],
                p.moment[0],
                p.moment[1],
            ];
            if all.iter().any(|v| !v.is_finite()) {
                return Err(Error::invalid(
                    format!("load[{i}]"),
                    format!("{all:?}"),
                    "finite position_mm, force_n and moment_nm",
                ));
            }
        }
        // A shaft needs its tilt held: two axial positions carrying radial load, or one
        // location with rows at two positions.
        let mut zs: Vec<f64> = Vec::new();
        for l in &self.locations {
            for r in &l.set.rows {
                zs.push(l.position + r.position);
            }
        }
        let spread = zs.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
            - zs.iter().cloned().fold(f64::INFINITY, f64::min);
        if zs.len() == 1 || spread <= 0.0 {
            return Err(Error::invalid(
                "location",
                format!("{} row(s) at one axial position", zs.len()),
                "a statically determined shaft: a single-row bearing cannot hold the shaft's \
                 tilt; add a second location or use a set of rows at two positions",
            ));
        }
        if !self.locations.iter().any(|l| {
            !l.floating
                && l.set
                    .rows
                    .iter()
                    .any(|r| crate::models::set::carries_axial(&r.bearing))
        }) {
            let floats = self.locations.iter().filter(|l| l.floating).count();
            return Err(Error::invalid(
                "location",
                format!(
                    "no location carries axial load ({floats} of {} floating)",
                    self.locations.len()
                ),
                "a statically determined shaft: at least one location, not floating, with axial support (a ball, tapered roller or flanged NJ/NUP bearing)",
            ));
        }
        Ok(())
    }

    /// Solve the equilibrium and report every location.
    pub fn solve(&self) -> Result<ShaftSolution> {
        self.check()?;
        let mut sets = self
            .locations
            .iter()
            .map(|l| {
                let mut s = if l.floating {
                    Set::new_floating(&l.set)?
                } else {
                    Set::new(&l.set)?
                };
                s.set_ring_temperatures(l.temperatures)?;
                Ok(s)
            })
            .enumerate()
            .map(|(i, s): (usize, Result<Set>)| {
                s.map_err(|e| match e {
                    Error::Invalid {
                        field,
                        value,
                        allowed,
                    } => Error::Invalid {
                        field: format!("location[{i}].{}", field.trim_start_matches("set.")),
                        value,
                        allowed,
                    },
                    e => e,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let load = self.load_at_origin();
        let zs: Vec<f64> = self.locations.iter().map(|l| l.position).collect();
        let arm = self
            .locations
            .iter()
            .zip(&sets)
            .map(|(l, s)| l.position.abs() + s.arm())
            .fold(0.0, f64::max);
        let max_step = sets
            .iter()
            .map(|s| s.max_step())
            .fold(f64::INFINITY, f64::min);
        let scale: f64 = sets.iter().map(|s| s.force_scale()).sum();
        let omega = self.omega;
        let floating: Vec<bool> = self.locations.iter().map(|l| l.floating).collect();
        // The floating locations' own axial positions (warm starts), m.
        let mut float_z = vec![0.0; self.locations.len()];
        // Forces and stiffness at the origin, and each location's own position.
        type Eval = ([f64; 5], [[f64; 5]; 5], Vec<[f64; 5]>);
        let mut eval = |q: &[f64; 5], sets: &mut [Set]| -> Result<Eval> {
            let mut f = [0.0; 5];
            let mut k = [[0.0; 5]; 5];
            let mut local = Vec::with_capacity(sets.len());
            for (i, (s, &z)) in sets.iter_mut().zip(&zs).enumerate() {
                let mut ql = at(z, q);
                let mut e = if floating[i] {
                    float_axially(s, &mut ql, &mut float_z[i], omega)?
                } else {
                    s.evaluate(&ql, omega)?
                };
                if floating[i] {
                    condense_axial(&mut e.stiffness);
                    e.force[2] = 0.0;
                }
                local.push(ql);
                let g = back(z, &e.force);
                let kk = back_k(z, &e.stiffness);
                for i in 0..5 {
                    f[i] += g[i];
                    for j in 0..5 {
                        k[i][j] += kk[i][j];
                    }
                }
            }
            Ok((f, k, local))
        };
        let solved = super::set::newton5_shared(
            |q| eval(q, &mut sets).map(|(f, k, _)| (f, k)),
            &load,
            [0.0; 5],
            arm,
            max_step,
            scale,
            "rigid-shaft equilibrium",
        );
        let q = match solved {
            Ok(q) => q,
            Err(e @ Error::NotConverged { .. }) => {
                // Name the direction the bearings leave free, if that is why.
                let (_, k, _) = eval(&[0.0; 5], &mut sets)?;
                if let Some(d) = free_direction(&k, arm) {
                    return Err(undetermined(d));
                }
                return Err(e);
            }
            Err(e) => return Err(e),
        };
        let (_, k, local) = eval(&q, &mut sets)?;
        if let Some(d) = free_direction(&k, arm) {
            return Err(undetermined(d));
        }
        let mut locations = Vec::new();
        let mut warnings = Vec::new();
        let mut lives = Vec::new();
        for ((s, l), ql) in sets.iter_mut().zip(&self.locations).zip(&local) {
            let sol = s.report(ql, omega)?;
            let lifted = sol.rows.iter().all(|r| r.lifted_off);
            if lifted {
                warnings.push(format!(
                    "location {} lifts off: none of its rows carries load",
                    l.name
                ));
            } else {
                for (i, r) in sol.rows.iter().enumerate() {
                    if r.lifted_off {
                        warnings.push(format!("location {} row {i} lifts off", l.name));
                    }
                }
            }
            lives.extend(sol.rows.iter().map(|r| (r.life_mrev, r.weibull_slope)));
            locations.push(LocationResult {
                name: l.name.clone(),
                position: l.position,
                set: sol,
                lifted_off: lifted,
                floating: l.floating,
            });
        }
        Ok(ShaftSolution {
            omega,
            load,
            q,
            stiffness: k,
            locations,
            life_mrev: crate::models::set::system_life(&lives),
            warnings,
        })
    }
}

/// Evaluate a floating location at the shaft's position `ql` (its own axial position
/// replaced by the one where its thrust vanishes, found by Newton from the warm start `w`
/// with the exact `K_zz`, halved back when the geometry refuses a trial). `ql[2]` and `w`
/// are set to that position.
fn float_axially(
    s: &mut Set,
    ql: &mut [f64; 5],
    w: &mut f64,
    omega: f64,
) -> Result<crate::models::set::SetEval> {
    let tol = 1e-10 * s.force_scale();
    let mut last_good: Option<f64> = None;
    let mut trial = *w;
    for _ in 0..100 {
        ql[2] = trial;
        match s.evaluate(ql, omega) {
            Ok(e) => {
                let (fz, kzz) = (e.force[2], e.stiffness[2][2]);
                if fz.abs() <= tol || kzz <= 0.0 {
                    // No axial force, or none the location can give (an NU row, a ball row
                    // inside its axial play): it sits where it is.
                    *w = trial;
                    if fz.abs() > tol {
                        return Err(Error::NotConverged {
                            what: "floating location's axial position",
                            iterations: 0,
                            residual: fz,
                        });
                    }
                    return Ok(e);
                }
                last_good = Some(trial);
                // F_z(w + dw) = F_z - K_zz dw = 0.
                trial += fz / kzz;
            }
            Err(Error::Invalid { .. }) => match last_good {
                Some(g) => trial = 0.5 * (trial + g),
                None => trial *= 0.5,
            },
            Err(e) => return Err(e),
        }
    }
    Err(Error::NotConverged {
        what: "floating location's axial position",
        iterations: 100,
        residual: f64::NAN,
    })
}

/// Condense the axial coordinate out of a location's stiffness (its axial force held at
/// zero): `K' = K - K e_z e_z^T K / K_zz`, which leaves row and column `z` zero.
fn condense_axial(k: &mut [[f64; 5]; 5]) {
    let kzz = k[2][2];
    if kzz > 0.0 {
        let (col, row): ([f64; 5], [f64; 5]) = (
            std::array::from_fn(|i| k[i][2]),
            std::array::from_fn(|j| k[2][j]),
        );
        for i in 0..5 {
            for j in 0..5 {
                k[i][j] -= col[i] * row[j] / kzz;
            }
        }
    }
    k[2] = [0.0; 5];
    for r in k.iter_mut() {
        r[2] = 0.0;
    }
}

/// The shaft direction the bearings leave without stiffness (scaled `K`'s symmetric part
/// with an eigenvalue below `1e-9` of the largest), named by its largest component.
fn free_direction(k: &[[f64; 5]; 5], arm: f64) -> Option<usize> {
    let t = [1.0, 1.0, 1.0, arm, arm];
    let m =
        nalgebra::SMatrix::<f64, 5, 5>::from_fn(|i, j| 0.5 * (k[i][j] + k[j][i]) / (t[i] * t[j]));
    let e = m.symmetric_eigen();
    let big = e.eigenvalues.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let (imin, vmin) = e
        .eigenvalues
        .iter()
        .enumerate()
        .fold(
            (0, f64::INFINITY),
            |a, (i, v)| if *v < a.1 { (i, *v) } else { a },
        );
    if big == 0.0 || vmin <= 1e-9 * big {
        let v = e.eigenvectors.column(imin);
        let dof = (0..5)
            .max_by(|a, b| v[*a].abs().total_cmp(&v[*b].abs()))
            .unwrap_or(0);
        Some(dof)
    } else {
        None
    }
}

fn undetermined(dof: usize) -> Error {
    Error::invalid(
        "location",
        format!("no stiffness in {}", DOF[dof]),
        format!(
            "a statically determined shaft: the bearings as placed give no stiffness in {} \
             (e.g. one single-row deep-groove bearing cannot hold tilt, radial roller rows \
             carry no axial load); add or change a location",
            DOF[dof]
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::element::Element;
    use crate::models::set::{bearing_by_name, Preload, Row};

    fn single(name: &str, z: f64) -> Location {
        Location {
            name: name.into(),
            position: z,
            set: SetSpec {
                rows: vec![Row {
                    bearing: bearing_by_name("6206", "b").unwrap(),
                    position: 0.0,
                    orientation: 1,
                }],
                preload: Preload::None,
            },
            floating: false,
            temperatures: RingTemperatures::default(),
        }
    }

    /// A shaft on two equal bearings under a load between them shares it by statics
    /// (lever rule): `F_A = F b/L`, `F_B = F a/L`; central: half each exactly (symmetry).
    /// Off centre the shaft tilts and each single row resists the tilt with a small
    /// moment of its own (balls at the moment arm `Ri`), so the lever rule holds to that
    /// moment over the span (1e-5 here); the full balance, the rows' moments included, is
    /// exact to the solve's tolerance.
    #[test]
    fn two_bearings_share_a_load_by_statics() {
        for (zp, share_a) in [(0.1, 0.5), (0.05, 0.75)] {
            let shaft = Shaft {
                locations: vec![single("A", 0.0), single("B", 0.2)],
                loads: vec![ShaftLoad {
                    position: zp,
                    force: [0.0, -2000.0, 0.0],
                    moment: [0.0, 0.0],
                }],
                omega: 0.0,
            };
            let s = shaft.solve().unwrap();
            let fa = s.locations[0].set.force[1];
            let fb = s.locations[1].set.force[1];
            let tol = if share_a == 0.5 { 1e-9 } else { 1e-4 };
            assert!((fa - 2000.0 * share_a).abs() < tol * 2000.0, "{fa} {fb}");
            assert!(
                (fb - 2000.0 * (1.0 - share_a)).abs() < tol * 2000.0,
                "{fa} {fb}"
            );
            // Moments about the origin: load + reactions (their own moments included).
            let m = shaft.load_at_origin()[3]
                + s.locations
                    .iter()
                    .map(|l| l.set.force[3] - l.position * l.set.force[1])
                    .sum::<f64>();
            assert!(m.abs() < 1e-7 * 2000.0 * 0.2, "{m}");
        }
    }

    /// One single-row bearing cannot hold the shaft's tilt: refused by name.
    #[test]
    fn one_single_row_bearing_is_statically_undetermined() {
        let shaft = Shaft {
            locations: vec![single("A", 0.0)],
            loads: vec![ShaftLoad {
                position: 0.05,
                force: [0.0, -1000.0, 0.0],
                moment: [0.0, 0.0],
            }],
            omega: 0.0,
        };
        let e = shaft.solve().unwrap_err().to_string();
        assert!(
            e.contains("statically determined") && e.contains("tilt"),
            "{e}"
        );
    }

    /// Two tapered roller bearings in indirect mounting (30206, rows facing each other's
    /// thrust) under a central radial load and a thrust: the axial reactions balance the
    /// thrust exactly, and the bearing that does not take the thrust still carries an axial
    /// load (the thrust its own inclined contacts induce under its radial load), so the
    /// other carries more than the applied thrust; the radial load splits by symmetry.
    #[test]
    fn a_tapered_pair_carries_its_induced_thrust() {
        let trb = |name: &str, z: f64, o: i32| Location {
            name: name.into(),
            position: z,
            set: SetSpec {
                rows: vec![Row {
                    bearing: bearing_by_name("30206", "b").unwrap(),
                    position: 0.0,
                    orientation: o,
                }],
                preload: Preload::None,
            },
            floating: false,
            temperatures: RingTemperatures::default(),
        };
        let shaft = Shaft {
            locations: vec![trb("A", 0.0, 1), trb("B", 0.2, -1)],
            loads: vec![ShaftLoad {
                position: 0.1,
                force: [0.0, -6000.0, 2000.0],
                moment: [0.0, 0.0],
            }],
            omega: 0.0,
        };
        let s = shaft.solve().unwrap();
        let (a, b) = (&s.locations[0].set.force, &s.locations[1].set.force);
        assert!((a[2] + b[2] + 2000.0).abs() < 1e-6 * 2000.0, "{a:?} {b:?}");
        assert!(b[2] > 100.0 && -a[2] > 2000.0 + 100.0, "{a:?} {b:?}");
        assert!((a[1] + b[1] - 6000.0).abs() < 1e-6 * 6000.0, "{a:?} {b:?}");
        // A tapered row reports its cone's and cup's angles as its contact angles.
        let Element::Roller(rb) = &bearing_by_name("30206", "b").unwrap().element else {
            panic!("30206 is a roller bearing")
        };
        let r = &s.locations[0].set.rows[0];
        assert!(rb.alpha > rb.alpha_cone && rb.alpha_cone > 0.0);
        assert!(r
            .contact_angles
            .iter()
            .all(|x| *x == [rb.alpha_cone, rb.alpha]));
        // Each row's peak pressure against its static safety: C0r is the load of 4 000 MPa
        // and a line contact's pressure goes as the square root of its load, so the peak
        // lies near 4 000 MPa / sqrt(S0) (within the load zone's shape, a factor 2 here).
        for l in &s.locations {
            let r = &l.set.rows[0];
            let expect = 4.0e9 / r.s0.unwrap().sqrt();
            assert!(
                (0.5 * expect..2.0 * expect).contains(&r.peak_pressure),
                "{} vs {expect}",
                r.peak_pressure
            );
        }
    }

    fn at_z(name: &str, bearing: &str, z: f64, floating: bool) -> Location {
        let mut l = single(name, z);
        l.set.rows[0].bearing = bearing_by_name(bearing, "b").unwrap();
        l.floating = floating;
        l
    }

    /// A fixed and a floating deep-groove bearing: the fixed one takes all the thrust, the
    /// floating one none (its axial force is zero to the solve's tolerance), the radial
    /// load still splits by statics; with the thrust alone the floating location lifts off
    /// (inside its clearance) and says so; a floating NU location reports its rollers'
    /// contact angle, 0.
    #[test]
    fn a_floating_location_carries_no_thrust() {
        let load = |fy: f64, fz: f64| ShaftLoad {
            position: 0.1,
            force: [0.0, fy, fz],
            moment: [0.0, 0.0],
        };
        let shaft = Shaft {
            locations: vec![at_z("A", "6206", 0.0, false), at_z("B", "6206", 0.2, true)],
            loads: vec![load(-2000.0, 500.0)],
            omega: 0.0,
        };
        let s = shaft.solve().unwrap();
        let (a, b) = (&s.locations[0].set.force, &s.locations[1].set.force);
        assert!(b[2].abs() < 1e-6 * 500.0, "{b:?}");
        assert!((a[2] + 500.0).abs() < 1e-6 * 500.0, "{a:?}");
        assert!((a[1] + b[1] - 2000.0).abs() < 1e-6 * 2000.0, "{a:?} {b:?}");
        // The lever rule with the fixed row's own moment (its balls all loaded by the
        // thrust give it a tilt stiffness): Fy_B 0.2 m = 200 N m + Mx_A + Mx_B.
        let lever = (2000.0 * 0.1 + a[3] + b[3]) / 0.2;
        assert!((b[1] - lever).abs() < 1e-6 * 2000.0, "{a:?} {b:?}");
        assert!(
            a[3] > 1.0 && (b[1] / 1000.0 - 1.0).abs() < 0.05,
            "{a:?} {b:?}"
        );
        assert!(
            s.locations[1].floating && s.warnings.is_empty(),
            "{:?}",
            s.warnings
        );
        let shaft = Shaft {
            loads: vec![load(0.0, 500.0)],
            ..shaft
        };
        let s = shaft.solve().unwrap();
        assert!(
            s.locations[1].lifted_off,
            "{:?}",
            s.locations[1].set.rows[0]
        );
        assert_eq!(
            s.warnings,
            vec!["location B lifts off: none of its rows carries load"]
        );
        let shaft = Shaft {
            locations: vec![at_z("A", "6206", 0.0, false), at_z("B", "NU206", 0.2, true)],
            loads: vec![load(-2000.0, 500.0)],
            omega: 0.0,
        };
        let s = shaft.solve().unwrap();
        let r = &s.locations[1].set.rows[0];
        assert!(r.loaded_elements > 0 && r.contact_angles.iter().all(|a| *a == [0.0, 0.0]));
    }

    /// Every location floating: no axial support, refused naming it before any solve.
    #[test]
    fn all_floating_is_statically_undetermined() {
        let shaft = Shaft {
            locations: vec![at_z("A", "6206", 0.0, true), at_z("B", "6206", 0.2, true)],
            loads: vec![ShaftLoad {
                position: 0.1,
                force: [0.0, -1000.0, 0.0],
                moment: [0.0, 0.0],
            }],
            omega: 0.0,
        };
        let e = shaft.solve().unwrap_err().to_string();
        assert!(
            e.contains("statically determined") && e.contains("2 of 2 floating"),
            "{e}"
        );
    }
}
