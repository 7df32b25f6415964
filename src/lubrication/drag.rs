//! Lubricant (oil–air mixture) drag on balls and cage of the `full` model (docs/physics.md §5.2
//! and §5.5; study \[0\] after Gupta, *Advanced Dynamics of Rolling Elements*, 1984, which
//! uses Schlichting's boundary-layer results). Every law is odd in the speed, zero at zero
//! and finite for finite input; each one joins its Stokes (creeping-flow) limit to its
//! boundary-layer limit.
//!
//! - **Sphere drag**: `F = -1/2 rho C_d (pi d²/4) v |v|` with White's correlation
//!   `C_d = 24/Re + 6/(1 + sqrt(Re)) + 0.4`, `Re = rho |v| d / eta` (White, *Viscous Fluid
//!   Flow*, 2nd ed. 1991, eq. 3-225, quoted as within about 10 % for `0 <= Re <= 2e5`).
//!   Written as `3 pi eta d v + (pi d² rho / 8) v |v| (6/(1 + sqrt(Re)) + 0.4)` so that
//!   `Re -> 0` gives Stokes' `6 pi eta R v` without dividing by `Re`.
//! - **Spinning sphere**: Stokes' `M_S = 8 pi eta R³ w` (Lamb, *Hydrodynamics*, §334) at
//!   low `Re_w = w R²/nu`; the laminar boundary-layer result `M_B = 1/2 rho w² R⁵ C_M`,
//!   `C_M = 6.45/sqrt(Re_w)` (Howarth 1951; Schlichting, *Boundary-Layer Theory*, the
//!   rotating sphere in still fluid) at high `Re_w`. Blended as `sqrt(M_S² + M_B²)`: both
//!   limits exact, at most `sqrt(2)` above either at the crossover (`Re_w ~ 60`), smooth.
//! - **Disk face**: von Kármán's rotating disk with Cochran's solution: wall shear
//!   `tau = 0.616 rho sqrt(nu) w^1.5 r`, so both faces of a full disk carry
//!   `M = 1/2 rho w² R⁵ C_M` with `C_M = 3.87/sqrt(Re)`, `Re = w R²/nu` (Schlichting), and
//!   one face carries half, `0.308 pi rho sqrt(nu) w^1.5 R⁴`; over an annulus
//!   `M_B = (pi/2) 0.616 rho sqrt(nu) w^1.5 (r_out⁴ - r_in⁴)`. Creeping-flow limit: the
//!   edgewise-rotating disk in unbounded Stokes flow, `M = 32/3 eta R³ w` for both faces
//!   (Jeffery, *Proc. LMS* 14, 1915), one face `16/3 eta w (r_out³ - r_in³)` for the annulus
//!   (the full-disk value with the hole's share removed, an approximation for the annulus).
//!   Blended like the sphere.

use std::f64::consts::PI;

/// Oil–air mixture properties.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fluid {
    /// Density, kg/m³.
    pub density: f64,
    /// Dynamic viscosity, Pa s.
    pub viscosity: f64,
}

/// Cochran's `-G'(0)` of von Kármán's rotating disk.
pub const KARMAN_G0: f64 = 0.616;
/// Laminar rotating-sphere moment coefficient numerator (`C_M = 6.45/sqrt(Re)`).
pub const SPHERE_CM: f64 = 6.45;

/// Drag force on a sphere of diameter `d` moving at `v` through the fluid (signed,
/// opposes `v`), N.
pub fn sphere_drag_force(f: &Fluid, d: f64, v: f64) -> f64 {
    let (rho, eta) = (f.density.max(0.0), f.viscosity.max(0.0));
    let stokes = 3.0 * PI * eta * d * v;
    let re = if eta > 0.0 {
        rho * v.abs() * d / eta
    } else {
        f64::INFINITY
    };
    let extra = 6.0 / (1.0 + re.sqrt()) + 0.4;
    -(stokes + PI * d * d * rho / 8.0 * v * v.abs() * extra)
}

/// Combine a creeping-flow and a boundary-layer magnitude (`sqrt(a² + b²)`), sign of `w`.
fn blend(stokes: f64, layer: f64, w: f64) -> f64 {
    if w == 0.0 {
        0.0
    } else {
        -w.signum() * stokes.hypot(layer)
    }
}

/// Moment on a sphere of diameter `d` spinning at `w` (signed, opposes `w`), N m.
pub fn sphere_spin_moment(f: &Fluid, d: f64, w: f64) -> f64 {
    let (rho, eta) = (f.density.max(0.0), f.viscosity.max(0.0));
    let r = 0.5 * d;
    let aw = w.abs();
    let stokes = 8.0 * PI * eta * r.powi(3) * aw;
    // 1/2 rho w² R⁵ 6.45 / sqrt(w R² rho/eta) = 3.225 sqrt(rho eta) w^1.5 R⁴.
    let layer = 0.5 * SPHERE_CM * (rho * eta).sqrt() * aw.powf(1.5) * r.powi(4);
    blend(stokes, layer, w)
}

/// Moment on one face of an annulus (radii `r_in`, `r_out`) spinning at `w` (signed,
/// opposes `w`), N m.
pub fn disk_moment(f: &Fluid, r_in: f64, r_out: f64, w: f64) -> f64 {
    let (rho, eta) = (f.density.max(0.0), f.viscosity.max(0.0));
    let (a, b) = (r_in.abs().min(r_out.abs()), r_in.abs().max(r_out.abs()));
    let aw = w.abs();
    let stokes = 16.0 / 3.0 * eta * aw * (b.powi(3) - a.powi(3));
    let layer = 0.5 * PI * KARMAN_G0 * (rho * eta).sqrt() * aw.powf(1.5) * (b.powi(4) - a.powi(4));
    blend(stokes, layer, w)
}

#[cfg(test)]
mod tests {
    use super::*;

    const OIL_AIR: Fluid = Fluid {
        density: 50.0,
        viscosity: 1e-3,
    };

    /// Stokes limits at Re -> 0 within 1 %: 6 pi eta R v and 8 pi eta R³ w.
    #[test]
    fn stokes_limits() {
        let (d, r) = (8e-3, 4e-3);
        let v = 1e-6; // Re = 50 * 1e-6 * 8e-3 / 1e-3 = 4e-4
        let want = -6.0 * PI * 1e-3 * r * v;
        let got = sphere_drag_force(&OIL_AIR, d, v);
        assert!((got / want - 1.0).abs() < 0.01, "{got} {want}");
        let w = 1e-3; // Re_w = 1e-3 * 16e-6 * 5e4 = 8e-4
        let want = -8.0 * PI * 1e-3 * r.powi(3) * w;
        let got = sphere_spin_moment(&OIL_AIR, d, w);
        assert!((got / want - 1.0).abs() < 0.01, "{got} {want}");
        // Jeffery's disk, one face: 16/3 eta R³ w.
        let want = -16.0 / 3.0 * 1e-3 * 0.02f64.powi(3) * w;
        let got = disk_moment(&OIL_AIR, 0.0, 0.02, w);
        assert!((got / want - 1.0).abs() < 0.01, "{got} {want}");
    }

    /// High Re: drag quadratic (C_d -> 0.4 + 6/sqrt(Re)), moments follow the boundary
    /// layer's w^1.5 laws with Schlichting's constants (disk: 3.87/2 per face).
    #[test]
    fn boundary_layer_limits() {
        let d = 8e-3;
        let (f1, f2) = (
            sphere_drag_force(&OIL_AIR, d, 1e3),
            sphere_drag_force(&OIL_AIR, d, 2e3),
        );
        // Re = 4e5 and 8e5: C_d ~ 0.41; force ratio near 4.
        let ratio = f2 / f1;
        assert!((ratio - 4.0).abs() < 0.1, "{ratio}");
        let re = 50.0 * 1e3 * d / 1e-3;
        let cd = 24.0 / re + 6.0 / (1.0 + re.sqrt()) + 0.4;
        let want = -0.5 * 50.0 * cd * PI * d * d / 4.0 * 1e6;
        assert!((f1 / want - 1.0).abs() < 1e-12);
        // Disk, one face, Re = w R²/nu = 1e4 * 4e-4 * 5e4 = 2e8.
        let (r, w): (f64, f64) = (0.02, 1e4);
        let re = w * r * r * 50.0 / 1e-3;
        let half_cm = 0.5 * 0.5 * 50.0 * w * w * r.powi(5) * 3.87 / re.sqrt();
        let got = -disk_moment(&OIL_AIR, 0.0, r, w);
        assert!((got / half_cm - 1.0).abs() < 0.01, "{got} {half_cm}");
        // Annulus = disk minus hole.
        let ann = disk_moment(&OIL_AIR, 0.01, r, w);
        let hole = disk_moment(&OIL_AIR, 0.0, 0.01, w);
        assert!((ann - (disk_moment(&OIL_AIR, 0.0, r, w) - hole)).abs() < 0.01 * ann.abs());
        // Sphere spin, Re_w = 1e4 * 16e-6 * 5e4 = 8e3.
        let rs: f64 = 4e-3;
        let re = w * rs * rs * 50.0 / 1e-3;
        let want = 0.5 * 50.0 * w * w * rs.powi(5) * 6.45 / re.sqrt();
        let got = -sphere_spin_moment(&OIL_AIR, d, w);
        assert!((got / want - 1.0).abs() < 0.01, "{got} {want}");
    }

    /// Odd in speed, zero at zero, finite with zero viscosity or density.
    #[test]
    fn odd_zero_and_finite() {
        for v in [1e-4, 0.3, 50.0] {
            assert_eq!(
                sphere_drag_force(&OIL_AIR, 8e-3, -v),
                -sphere_drag_force(&OIL_AIR, 8e-3, v)
            );
            assert!(sphere_drag_force(&OIL_AIR, 8e-3, v) < 0.0);
            assert_eq!(
                sphere_spin_moment(&OIL_AIR, 8e-3, -v),
                -sphere_spin_moment(&OIL_AIR, 8e-3, v)
            );
            assert_eq!(
                disk_moment(&OIL_AIR, 0.01, 0.02, -v),
                -disk_moment(&OIL_AIR, 0.01, 0.02, v)
            );
        }
        assert_eq!(sphere_drag_force(&OIL_AIR, 8e-3, 0.0), 0.0);
        assert_eq!(sphere_spin_moment(&OIL_AIR, 8e-3, 0.0), 0.0);
        assert_eq!(disk_moment(&OIL_AIR, 0.01, 0.02, 0.0), 0.0);
        for fl in [
            Fluid {
                density: 0.0,
                viscosity: 0.0,
            },
            Fluid {
                density: 1.2,
                viscosity: 0.0,
            },
            Fluid {
                density: 0.0,
                viscosity: 1e-3,
            },
        ] {
            assert!(sphere_drag_force(&fl, 8e-3, 3.0).is_finite());
            assert!(sphere_drag_force(&fl, 8e-3, 0.0).is_finite());
            assert!(sphere_spin_moment(&fl, 8e-3, 3.0).is_finite());
            assert!(disk_moment(&fl, 0.01, 0.02, 3.0).is_finite());
        }
        // Inviscid: pure form drag with C_d = 0.4.
        let fl = Fluid {
            density: 1.2,
            viscosity: 0.0,
        };
        let want = -0.5 * 1.2 * 0.4 * PI * 64e-6 / 4.0 * 9.0;
        assert!((sphere_drag_force(&fl, 8e-3, 3.0) / want - 1.0).abs() < 1e-12);
    }
}
