//! Subsurface stress below an elliptical Hertz contact.
//!
//! The stresses on the axis below the contact centre are the superposition of Boussinesq's
//! point-load solution (Johnson, *Contact Mechanics*, 1985, eq. (3.22)) over the semi-ellipsoidal
//! Hertz pressure `p = p0 sqrt(1 - x²/a² - y²/b²)` (Johnson §7.1, eq. (7.2)). On the axis the
//! shear components vanish by symmetry, so `σx`, `σy`, `σz` are principal; they are integrated
//! numerically (polar coordinates about the axis, Gauss–Legendre panels graded around
//! the depth), which is exact up to quadrature error (< 1e-6 p0 against the circular closed form,
//! Johnson eq. (3.46)). From them:
//!
//! - the maximum 45° shear `τmax = max_z (σ1 - σ3)/2` and its depth (Johnson §3.4 and Fig. 4.6:
//!   0.31 p0 at 0.48 a for a circle, 0.30 p0 at 0.78 b for a line contact, ν = 0.3);
//! - the maximum von Mises stress and its depth;
//! - the maximum orthogonal (reversing) shear `τ0` and its depth from Lundberg & Palmgren's
//!   closed form (Lundberg & Palmgren, "Dynamic capacity of rolling bearings", Acta Polytechnica
//!   Mech. Eng. Ser. 1 (3), 1947; Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed., vol. 1,
//!   §6.4): with the auxiliary `t` from `b/a = sqrt((t² - 1)(2t - 1))`,
//!   `τ0 = p0 sqrt(2t - 1) / (2t (t + 1))` at `z0 = b / ((t + 1) sqrt(2t - 1))`
//!   (line contact `t = 1`: 0.25 p0 at 0.5 b);
//! - a required case depth: the depth below which the 45° shear stays under a given allowable
//!   shear stress of the core (Tresca), so the hardened case must reach at least that deep.
//!
//! Plain data, SI units: semi-axes in m, pressures in Pa. `a` is the semi-major axis (across the
//! rolling direction), `b` the semi-minor one (along it).

use crate::error::{Error, Result};

/// Peak stresses below one contact, with their depths below the surface.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Subsurface {
    /// Maximum 45° shear `(σ1 - σ3)/2` on the axis (Pa).
    pub tau_max: f64,
    /// Its depth (m).
    pub z_tau_max: f64,
    /// Maximum von Mises equivalent stress on the axis (Pa).
    pub von_mises: f64,
    /// Its depth (m).
    pub z_von_mises: f64,
    /// Maximum orthogonal shear amplitude (Lundberg–Palmgren `τ0`, Pa).
    pub tau_orth: f64,
    /// Its depth (m).
    pub z_tau_orth: f64,
}

/// Gauss–Legendre nodes and weights on [-1, 1] (Newton on the Legendre recurrence).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-15 {
                break;
            }
        }
        out.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    out
}

/// Panel edges on `[0, hi]` graded geometrically around `centre` (factor 2 each way).
fn graded(hi: f64, centre: f64) -> Vec<f64> {
    let mut e = vec![0.0];
    let c = centre.min(hi);
    let mut k = -8i32;
    while k <= 12 {
        let v = c * 2f64.powi(k);
        if v > 0.0 && v < hi {
            e.push(v);
        }
        k += 1;
    }
    e.push(hi);
    e.sort_by(f64::total_cmp);
    e.dedup();
    e
}

/// Normal stresses `(σx, σy, σz)` (Pa, compression negative) at depth `z` on the axis below
/// the centre of a Hertz ellipse with semi-axes `a` (along x) and `b` (along y), peak
/// pressure `p0` and Poisson's ratio `nu`.
pub fn axis_stresses(a: f64, b: f64, p0: f64, nu: f64, z: f64) -> [f64; 3] {
    use std::f64::consts::{FRAC_PI_2, PI};
    thread_local! {
        static GL: Vec<(f64, f64)> = gauss_legendre(12);
    }
    GL.with(|gl| {
        let mut s = [0.0; 3];
        // θ over a quarter (the pressure is even in x and y), graded near the x axis where the
        // boundary radius changes fastest for a slender ellipse.
        let th_edges = graded(FRAC_PI_2, (b / a).max(1e-6));
        for w in th_edges.windows(2) {
            let (lo, hi) = (w[0], w[1]);
            let (c, h) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            for &(xt, wt) in gl.iter() {
                let th = c + h * xt;
                let (sn, cs) = th.sin_cos();
                let rb = 1.0 / ((cs / a).powi(2) + (sn / b).powi(2)).sqrt();
                let (c2, s2) = (cs * cs, sn * sn);
                // r = rb sin φ: p = p0 cos φ, dr = rb cos φ dφ.
                let phz = (z / rb).min(1.0).asin().max(1e-9);
                let edges = graded(FRAC_PI_2, phz);
                let mut acc = [0.0; 3];
                for pw in edges.windows(2) {
                    let (plo, phi) = (pw[0], pw[1]);
                    let (pc, ph) = (0.5 * (plo + phi), 0.5 * (phi - plo));
                    for &(xp, wp) in gl.iter() {
                        let phv = pc + ph * xp;
                        let (sp, cp) = phv.sin_cos();
                        let r = rb * sp;
                        let rho2 = r * r + z * z;
                        let rho = rho2.sqrt();
                        let rho3 = rho2 * rho;
                        let rho5 = rho3 * rho2;
                        // p r dr = p0 cos φ · rb sin φ · rb cos φ dφ
                        let m = wp * ph * p0 * cp * cp * rb * rb * sp;
                        let t1 = 1.0 / (rho * (rho + z));
                        let kx = (1.0 - 2.0 * nu) * ((c2 - s2) * t1 + z * s2 / rho3)
                            - 3.0 * z * r * r * c2 / rho5;
                        let ky = (1.0 - 2.0 * nu) * ((s2 - c2) * t1 + z * c2 / rho3)
                            - 3.0 * z * r * r * s2 / rho5;
                        let kz = -3.0 * z * z * z / rho5;
                        acc[0] += m * kx;
                        acc[1] += m * ky;
                        acc[2] += m * kz;
                    }
                }
                for i in 0..3 {
                    s[i] += wt * h * acc[i];
                }
            }
        }
        // Four quadrants, Boussinesq's 1/(2π).
        s.map(|v| 4.0 * v / (2.0 * PI))
    })
}

fn tresca(s: [f64; 3]) -> f64 {
    let hi = s[0].max(s[1]).max(s[2]);
    let lo = s[0].min(s[1]).min(s[2]);
    0.5 * (hi - lo)
}

fn mises(s: [f64; 3]) -> f64 {
    (0.5 * ((s[0] - s[1]).powi(2) + (s[1] - s[2]).powi(2) + (s[2] - s[0]).powi(2))).sqrt()
}

/// Maximum of `f` on `[lo, hi]`: a scan then golden-section refinement.
fn maximise(lo: f64, hi: f64, f: impl Fn(f64) -> f64) -> (f64, f64) {
    let n = 40;
    let (mut best, mut fb) = (lo, f64::NEG_INFINITY);
    for i in 0..=n {
        let z = lo + (hi - lo) * i as f64 / n as f64;
        let v = f(z);
        if v > fb {
            best = z;
            fb = v;
        }
    }
    let step = (hi - lo) / n as f64;
    let (mut x0, mut x3) = ((best - step).max(lo), (best + step).min(hi));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let mut x1 = x3 - g * (x3 - x0);
    let mut x2 = x0 + g * (x3 - x0);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..40 {
        if f1 > f2 {
            x3 = x2;
            x2 = x1;
            f2 = f1;
            x1 = x3 - g * (x3 - x0);
            f1 = f(x1);
        } else {
            x0 = x1;
            x1 = x2;
            f1 = f2;
            x2 = x0 + g * (x3 - x0);
            f2 = f(x2);
        }
    }
    let z = 0.5 * (x0 + x3);
    (z, f(z))
}

/// Lundberg–Palmgren auxiliary `t` for `b/a` in (0, 1]: `(t² - 1)(2t - 1) = (b/a)²`.
fn lp_t(ratio: f64) -> f64 {
    let target = ratio * ratio;
    let (mut lo, mut hi) = (1.0, 2.0);
    for _ in 0..200 {
        let t = 0.5 * (lo + hi);
        if (t * t - 1.0) * (2.0 * t - 1.0) < target {
            lo = t;
        } else {
            hi = t;
        }
    }
    0.5 * (lo + hi)
}

/// Lundberg–Palmgren maximum orthogonal shear `(τ0, z0)` for semi-axes `a ≥ b`.
pub fn orthogonal_shear(a: f64, b: f64, p0: f64) -> (f64, f64) {
    let t = lp_t((b / a).min(1.0));
    let q = (2.0 * t - 1.0).sqrt();
    (p0 * q / (2.0 * t * (t + 1.0)), b / ((t + 1.0) * q))
}

fn check(a: f64, b: f64, p0: f64, nu: f64) -> Result<(f64, f64)> {
    if !(a.is_finite() && a > 0.0) {
        return Err(Error::invalid("subsurface.a", a, "> 0 m"));
    }
    if !(b.is_finite() && b > 0.0) {
        return Err(Error::invalid("subsurface.b", b, "> 0 m"));
    }
    if !(p0.is_finite() && p0 >= 0.0) {
        return Err(Error::invalid("subsurface.p0", p0, ">= 0 Pa"));
    }
    if !(nu > -1.0 && nu < 0.5) {
        return Err(Error::invalid("subsurface.nu", nu, "in (-1, 0.5)"));
    }
    Ok((a.max(b), a.min(b)))
}

/// Peak subsurface stresses below an elliptical Hertz contact (semi-axes `a`, `b` in m in either
/// order, peak pressure `p0` in Pa, Poisson's ratio `nu` of both bodies).
pub fn subsurface(a: f64, b: f64, p0: f64, nu: f64) -> Result<Subsurface> {
    let (a, b) = check(a, b, p0, nu)?;
    let at = |z: f64| axis_stresses(a, b, p0, nu, z);
    let (z_tau_max, tau_max) = maximise(0.02 * b, 2.0 * b, |z| tresca(at(z)));
    let (z_von_mises, von_mises) = maximise(0.02 * b, 2.0 * b, |z| mises(at(z)));
    let (tau_orth, z_tau_orth) = orthogonal_shear(a, b, p0);
    Ok(Subsurface {
        tau_max,
        z_tau_max,
        von_mises,
        z_von_mises,
        tau_orth,
        z_tau_orth,
    })
}

/// Required case depth (m): the depth below which the axis 45° shear stays under the core's
/// allowable shear stress `tau_core` (Pa). Zero when the peak is already below it.
pub fn case_depth(a: f64, b: f64, p0: f64, nu: f64, tau_core: f64) -> Result<f64> {
    let (a, b) = check(a, b, p0, nu)?;
    if !(tau_core.is_finite() && tau_core > 0.0) {
        return Err(Error::invalid("subsurface.tau_core", tau_core, "> 0 Pa"));
    }
    let s = subsurface(a, b, p0, nu)?;
    if s.tau_max <= tau_core {
        return Ok(0.0);
    }
    // τ(z) decreases beyond its peak: bisect for τ = tau_core below z_tau_max.
    let tau = |z: f64| tresca(axis_stresses(a, b, p0, nu, z));
    let (mut lo, mut hi) = (s.z_tau_max, s.z_tau_max.max(b));
    while tau(hi) > tau_core {
        lo = hi;
        hi *= 2.0;
        if hi > 1e3 * a {
            break;
        }
    }
    for _ in 0..60 {
        let m = 0.5 * (lo + hi);
        if tau(m) > tau_core {
            lo = m;
        } else {
            hi = m;
        }
    }
    Ok(0.5 * (lo + hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Circular contact on the axis: Johnson eq. (3.46), closed form.
    #[test]
    fn circle_matches_closed_form() {
        let (a, p0, nu) = (1e-3, 1e9, 0.3);
        for &zr in &[0.1, 0.48, 1.0, 2.5] {
            let z = zr * a;
            let s = axis_stresses(a, a, p0, nu, z);
            let sz = -p0 / (1.0 + zr * zr);
            let sr = p0 * (-(1.0 + nu) * (1.0 - zr * (1.0 / zr).atan()) + 0.5 / (1.0 + zr * zr));
            assert!(
                (s[2] - sz).abs() < 1e-6 * p0,
                "σz at {zr}: {} vs {sz}",
                s[2]
            );
            assert!(
                (s[0] - sr).abs() < 1e-6 * p0,
                "σr at {zr}: {} vs {sr}",
                s[0]
            );
            assert!((s[1] - sr).abs() < 1e-6 * p0);
        }
    }

    /// Johnson §3.4: τmax = 0.31 p0 at 0.48 a for a circle, ν = 0.3.
    #[test]
    fn circle_tau_max_johnson() {
        let s = subsurface(1e-3, 1e-3, 1.0, 0.3).unwrap();
        assert!((s.tau_max - 0.31).abs() < 0.005, "{}", s.tau_max);
        assert!((s.z_tau_max / 1e-3 - 0.48).abs() < 0.01, "{}", s.z_tau_max);
    }

    /// Line-contact limit b/a → 0 (Johnson §4.2, Fig. 4.6): τmax = 0.30 p0 at 0.78 b,
    /// orthogonal shear 0.25 p0 at 0.5 b; von Mises 0.56 p0 at 0.70 b (ν = 0.3).
    #[test]
    fn line_contact_limit() {
        let b = 1e-4;
        let s = subsurface(500.0 * b, b, 1.0, 0.3).unwrap();
        assert!((s.tau_max - 0.300).abs() < 0.005, "{}", s.tau_max);
        assert!(
            (s.z_tau_max / b - 0.786).abs() < 0.02,
            "{}",
            s.z_tau_max / b
        );
        assert!((s.von_mises - 0.557).abs() < 0.006, "{}", s.von_mises);
        assert!(
            (s.z_von_mises / b - 0.70).abs() < 0.03,
            "{}",
            s.z_von_mises / b
        );
        assert!((s.tau_orth - 0.25).abs() < 1e-3, "{}", s.tau_orth);
        assert!(
            (s.z_tau_orth / b - 0.5).abs() < 2e-3,
            "{}",
            s.z_tau_orth / b
        );
    }

    /// Stresses scale with p0, depths with the contact size; an ellipse lies between limits.
    #[test]
    fn ellipse_between_circle_and_line() {
        let b = 2e-4;
        let s = subsurface(8.0 * b, b, 2e9, 0.3).unwrap();
        assert!(
            s.tau_max > 0.300 * 2e9 && s.tau_max < 0.32 * 2e9,
            "{}",
            s.tau_max
        );
        assert!(s.z_tau_max > 0.48 * b && s.z_tau_max < 0.80 * b);
        assert!(s.tau_orth > 0.215 * 2e9 && s.tau_orth < 0.25 * 2e9);
    }

    #[test]
    fn case_depth_is_past_the_peak_and_grows_with_load() {
        let (a, b, nu) = (2e-3, 3e-4, 0.3);
        let d1 = case_depth(a, b, 2.5e9, nu, 0.4e9).unwrap();
        let d2 = case_depth(a, b, 3.5e9, nu, 0.4e9).unwrap();
        let s = subsurface(a, b, 2.5e9, nu).unwrap();
        assert!(d1 > s.z_tau_max && d2 > d1, "{d1} {d2}");
        // Shear there equals the core strength.
        let t = tresca(axis_stresses(a, b, 2.5e9, nu, d1));
        assert!((t - 0.4e9).abs() < 1e3);
        assert_eq!(case_depth(a, b, 1e9, nu, 0.5e9).unwrap(), 0.0);
    }

    #[test]
    fn bad_input_names_the_field() {
        let e = subsurface(-1.0, 1e-3, 1e9, 0.3).unwrap_err().to_string();
        assert!(e.contains("subsurface.a"), "{e}");
        let e = case_depth(1e-3, 1e-3, 1e9, 0.3, 0.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("tau_core"), "{e}");
    }
}
