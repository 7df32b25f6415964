//! Complete elliptic integrals of the first and second kind by the arithmetic–geometric
//! mean (Abramowitz & Stegun §17.6; docs/physics.md §N3.2).
//!
//! Parameter convention: `m = k²` (A&S), `K(m) = ∫₀^{π/2} dθ / sqrt(1 - m sin²θ)`,
//! `E(m) = ∫₀^{π/2} sqrt(1 - m sin²θ) dθ`.
//!
//! The AGM runs `a₀ = 1`, `b₀ = sqrt(1 - m)`, `c₀² = m`,
//! `a_{n+1} = (a_n + b_n)/2`, `b_{n+1} = sqrt(a_n b_n)`, `c_{n+1} = c_n² / (4 a_{n+1})`
//! (the last is the identity `c_{n+1} = (a_n - b_n)/2` written without cancellation), and
//! gives `K = π / (2 a_N)` and `E = K (1 - S)` with `S = Σ_{n≥0} 2^{n-1} c_n²`
//! (A&S 17.6.3–4). Convergence is quadratic: 4–6 iterations reach machine precision for
//! `m <= 0.99999` (docs/physics.md §N3.2).
//!
//! `S = (K - E)/K` is returned as well: the Hertz ellipticity equation needs `K - E` and
//! `κ²E - K`, both of which vanish like `m` at `m → 0`; `K S` and `K κ² (m - S)` give them
//! without cancellation.

use std::f64::consts::FRAC_PI_2;

/// The raw AGM result for parameter `m` and complementary parameter `m1 = 1 - m`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Agm {
    /// The parameter `m`.
    pub m: f64,
    /// `K(m)`.
    pub k: f64,
    /// `E(m)`.
    pub e: f64,
    /// `S = (K - E)/K = Σ 2^{n-1} c_n²`, accurate to relative machine precision near `m = 0`.
    pub s: f64,
    /// `T = S - m/2 = Σ_{n≥1} 2^{n-1} c_n²` (so `m - S = m/2 - T` without cancellation).
    pub t: f64,
}

/// Run the AGM for `m` given the complement `m1 = 1 - m` directly (so that `m` close to
/// 1, i.e. a long contact ellipse with `m1 = 1/κ²`, keeps full relative precision).
/// Domain: `m1 >= 0` (`m <= 1`); `m < 0` is allowed. `m1 = 0` gives `K = ∞`, `E = 1`.
pub fn agm(m: f64, m1: f64) -> Agm {
    if m1 == 0.0 {
        return Agm {
            m,
            k: f64::INFINITY,
            e: 1.0,
            s: 1.0,
            t: 1.0 - 0.5 * m,
        };
    }
    let mut a = 1.0_f64;
    let mut b = m1.sqrt();
    let mut c2 = m; // c_n², n = 0
    let mut t = 0.0_f64;
    let mut w = 0.5_f64; // 2^{n-1}
    for _ in 0..40 {
        let a1 = 0.5 * (a + b);
        let b1 = (a * b).sqrt();
        let c1 = c2 / (4.0 * a1); // c_{n+1}; c2 may be negative only for n = 0 (m < 0)
        a = a1;
        b = b1;
        c2 = c1 * c1;
        w *= 2.0;
        let term = w * c2;
        t += term;
        if term <= 1e-17 * t.max(f64::MIN_POSITIVE) || c2 == 0.0 {
            break;
        }
    }
    let k = FRAC_PI_2 / a;
    let s = 0.5 * m + t;
    Agm {
        m,
        k,
        e: k * (1.0 - s),
        s,
        t,
    }
}

/// `(K(m), E(m))` for `m <= 1` (A&S 17.6). `K(1) = ∞`, `E(1) = 1`. NaN for `m > 1` or NaN.
pub fn ellip_ke(m: f64) -> (f64, f64) {
    if m.is_nan() || m > 1.0 {
        return (f64::NAN, f64::NAN);
    }
    let r = agm(m, 1.0 - m);
    (r.k, r.e)
}

/// Complete elliptic integral of the first kind `K(m)`, `m <= 1`.
pub fn ellip_k(m: f64) -> f64 {
    ellip_ke(m).0
}

/// Complete elliptic integral of the second kind `E(m)`, `m <= 1`.
pub fn ellip_e(m: f64) -> f64 {
    ellip_ke(m).1
}

/// Derivatives `(dK/dm, dE/dm)` from the AGM result (DLMF 19.4.1 with `m = k²`;
/// docs/physics.md §N3.1):
/// `dK/dm = (E - (1-m) K) / (2 m (1-m)) = K (m - S) / (2 m (1-m))`,
/// `dE/dm = (E - K) / (2m) = -K S / (2m)`; written with `S` and `T` so that they keep full
/// precision at small `m` (the limits at `m = 0` are `π/8` and `-π/8`).
pub fn ke_derivatives(r: &Agm) -> (f64, f64) {
    let m = r.m;
    if m == 0.0 {
        return (FRAC_PI_2 / 4.0, -FRAC_PI_2 / 4.0);
    }
    let m1 = 1.0 - m;
    // (m - S)/m = 1/2 - T/m, S/m = 1/2 + T/m.
    let tm = r.t / m;
    let dk = r.k * (0.5 - tm) / (2.0 * m1);
    let de = -r.k * (0.5 + tm) / 2.0;
    (dk, de)
}

/// `(K, E, dK/dm, dE/dm)` at `m < 1`.
pub fn ellip_ke_with_derivatives(m: f64) -> (f64, f64, f64, f64) {
    if m.is_nan() || m >= 1.0 {
        let (k, e) = ellip_ke(m);
        return (k, e, f64::INFINITY, f64::NEG_INFINITY);
    }
    let r = agm(m, 1.0 - m);
    let (dk, de) = ke_derivatives(&r);
    (r.k, r.e, dk, de)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    #[test]
    fn known_values() {
        // docs/physics.md §N3.5 and A&S table 17.1 (K, E at m = sin²(alpha)).
        let (k, e) = ellip_ke(0.5);
        assert!(rel(k, 1.854074677301372) < 4e-16, "{k}");
        assert!(rel(e, 1.350643881047675) < 4e-16, "{e}");
        let (k, e) = ellip_ke(0.0);
        assert_eq!((k, e), (FRAC_PI_2, FRAC_PI_2));
        assert_eq!(ellip_ke(1.0), (f64::INFINITY, 1.0));
        assert!(ellip_k(1.5).is_nan());
    }

    #[test]
    fn series_limit_near_zero() {
        // K = π/2 (1 + m/4 + 9m²/64 + ...), E = π/2 (1 - m/4 - 3m²/64 - ...): A&S 17.3.11–12.
        let m = 1e-6;
        let (k, e) = ellip_ke(m);
        assert!(rel(k, FRAC_PI_2 * (1.0 + m / 4.0 + 9.0 * m * m / 64.0)) < 1e-15);
        assert!(rel(e, FRAC_PI_2 * (1.0 - m / 4.0 - 3.0 * m * m / 64.0)) < 1e-15);
        // K - E from the AGM sum keeps relative precision: K - E = π/2 (m/2 + 3m²/16 + ...).
        let r = agm(m, 1.0 - m);
        assert!(rel(r.k * r.s, FRAC_PI_2 * (m / 2.0 + 3.0 * m * m / 16.0)) < 1e-12);
    }

    #[test]
    fn legendre_relation() {
        // E K' + E' K - K K' = π/2 (A&S 17.3.13) over the range, complementary pairs.
        for &m in &[0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.999999] {
            let (k, e) = ellip_ke(m);
            let (k1, e1) = ellip_ke(1.0 - m);
            let l = e * k1 + e1 * k - k * k1;
            assert!(
                (l - FRAC_PI_2).abs() < 4e-15 * k.max(k1).powi(2),
                "m = {m}: {l}"
            );
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for &m in &[1e-3, 0.2, 0.5, 0.9, 0.999] {
            let (_, _, dk, de) = ellip_ke_with_derivatives(m);
            let h = 1e-4 * m.min(1.0 - m);
            let (kp, ep) = ellip_ke(m + h);
            let (km, em) = ellip_ke(m - h);
            let fdk = (kp - km) / (2.0 * h);
            let fde = (ep - em) / (2.0 * h);
            let tol = 1e-7;
            assert!(rel(dk, fdk) < tol, "m = {m}: {dk} vs {fdk}");
            assert!(rel(de, fde) < tol, "m = {m}: {de} vs {fde}");
        }
        // Small m against the series dK/dm = π/2 (1/4 + 9m/32), dE/dm = -π/2 (1/4 + 3m/32).
        let m = 1e-9;
        let (_, _, dk, de) = ellip_ke_with_derivatives(m);
        assert!(rel(dk, FRAC_PI_2 * (0.25 + 9.0 * m / 32.0)) < 1e-15, "{dk}");
        assert!(
            rel(de, -FRAC_PI_2 * (0.25 + 3.0 * m / 32.0)) < 1e-15,
            "{de}"
        );
        let (_, _, dk, de) = ellip_ke_with_derivatives(0.0);
        assert!(rel(dk, std::f64::consts::PI / 8.0) < 1e-15);
        assert!(rel(de, -std::f64::consts::PI / 8.0) < 1e-15);
    }
}
