//! Hertz point contact (physics.md §3; Harris & Kotzalas Vol. 1 ch. 6; Hamrock & Dowson
//! ch. 3; Johnson, *Contact Mechanics*, §4.2).
//!
//! PLACEHOLDER: only the Hamrock–Brewe fits are implemented here; the exact solve, the
//! elliptic integrals and the fast path replace this (issue 2). The public names and
//! signatures below are the contract other modules code against.

/// Which race a ball touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Race {
    /// The inner race (convex in the rolling direction).
    Inner,
    /// The outer race (concave in the rolling direction).
    Outer,
}

/// Curvature sums of a contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curvature {
    /// Curvature sum `1/Rx + 1/Ry`, 1/m.
    pub sum_rho: f64,
    /// Effective radius in the rolling direction, m.
    pub rx: f64,
    /// Effective radius across the rolling direction, m.
    pub ry: f64,
}

impl Curvature {
    /// Ball of diameter `d` on a race of groove curvature ratio `f` at contact angle `alpha`
    /// in a bearing of pitch diameter `dm`.
    pub fn ball_race(d: f64, dm: f64, alpha: f64, f: f64, race: Race) -> Self {
        let gamma = d * alpha.cos() / dm;
        let rho_race_x = match race {
            Race::Inner => 2.0 / d * gamma / (1.0 - gamma),
            Race::Outer => -2.0 / d * gamma / (1.0 + gamma),
        };
        let inv_rx = 2.0 / d + rho_race_x;
        let inv_ry = 2.0 / d - 1.0 / (f * d);
        Curvature {
            sum_rho: inv_rx + inv_ry,
            rx: 1.0 / inv_rx,
            ry: 1.0 / inv_ry,
        }
    }

    /// Sphere of radius `r` on a flat.
    pub fn sphere_on_flat(r: f64) -> Self {
        Curvature {
            sum_rho: 2.0 / r,
            rx: r,
            ry: r,
        }
    }

    /// Radius ratio `Ry/Rx` (>= 1 for ball bearings).
    pub fn ratio(&self) -> f64 {
        self.ry / self.rx
    }

    /// Curvature difference `F(rho) = (1/Rx - 1/Ry)/(1/Rx + 1/Ry)`, in magnitude.
    pub fn f_rho(&self) -> f64 {
        ((1.0 / self.rx - 1.0 / self.ry) / self.sum_rho).abs()
    }
}

/// The dimensionless shape of the contact ellipse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipse {
    /// Ellipticity `kappa = a/b >= 1`.
    pub kappa: f64,
    /// Complete elliptic integral of the first kind `K(m)`, `m = 1 - 1/kappa²`.
    pub k: f64,
    /// Complete elliptic integral of the second kind `E(m)`.
    pub e: f64,
}

/// Hamrock–Brewe fits (Brewe & Hamrock 1977): `kappa ~ 1.0339 (Ry/Rx)^0.636`,
/// `E ~ 1.0003 + 0.5968 Rx/Ry`, `K ~ 1.5277 + 0.6023 ln(Ry/Rx)`.
pub fn ellipse_fit(ratio: f64) -> Ellipse {
    let r = ratio.max(1.0 / ratio);
    Ellipse {
        kappa: 1.0339 * r.powf(0.636),
        k: 1.5277 + 0.6023 * r.ln(),
        e: 1.0003 + 0.5968 / r,
    }
}

/// Everything needed to go between load and approach at one contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointContact {
    /// Curvatures.
    pub curvature: Curvature,
    /// Ellipse shape.
    pub ellipse: Ellipse,
    /// Effective modulus `E'`, Pa.
    pub e_eff: f64,
    /// Load–deflection constant `Kc` in `Q = Kc delta^1.5`, N/m^1.5.
    pub kc: f64,
}

impl PointContact {
    /// Build from curvature and effective modulus.
    pub fn new(curvature: Curvature, e_eff: f64) -> Self {
        let ellipse = ellipse_fit(curvature.ratio());
        let r = 1.0 / curvature.sum_rho;
        let Ellipse { kappa, k, e } = ellipse;
        let kc = std::f64::consts::PI * kappa * e_eff * (2.0 * e * r / (9.0 * k.powi(3))).sqrt();
        PointContact {
            curvature,
            ellipse,
            e_eff,
            kc,
        }
    }

    /// Load for approach `delta` (zero for `delta <= 0`), N.
    pub fn load(&self, delta: f64) -> f64 {
        if delta > 0.0 {
            self.kc * delta * delta.sqrt()
        } else {
            0.0
        }
    }

    /// Approach for load `q`, m.
    pub fn deflection(&self, q: f64) -> f64 {
        (q.max(0.0) / self.kc).powf(2.0 / 3.0)
    }

    /// Semi-axes `(a, b)` at load `q`, m (`a` across the rolling direction).
    pub fn semi_axes(&self, q: f64) -> (f64, f64) {
        let Ellipse { kappa, e, .. } = self.ellipse;
        let r = 1.0 / self.curvature.sum_rho;
        let pi = std::f64::consts::PI;
        let a = (6.0 * kappa * kappa * e * q * r / (pi * self.e_eff)).cbrt();
        let b = (6.0 * e * q * r / (pi * kappa * self.e_eff)).cbrt();
        (a, b)
    }

    /// Peak (Hertz) pressure at load `q`, Pa.
    pub fn peak_pressure(&self, q: f64) -> f64 {
        let (a, b) = self.semi_axes(q);
        if a > 0.0 {
            1.5 * q / (std::f64::consts::PI * a * b)
        } else {
            0.0
        }
    }
}

/// Load–deflection constant of two contacts in series:
/// `K_n = (K_i^(-2/3) + K_o^(-2/3))^(-3/2)`.
pub fn series_constant(k_i: f64, k_o: f64) -> f64 {
    (k_i.powf(-2.0 / 3.0) + k_o.powf(-2.0 / 3.0)).powf(-1.5)
}
