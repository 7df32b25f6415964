//! Asperity load share `La` (per cent of the contact load carried by the asperities) of a
//! rough elliptical EHL contact: the one function the wear law (`crate::models::wear`) and
//! the mixed-EHL traction law (`crate::contact::traction`) share.
//!
//! **Source and form.** Study \[2\] (Cao et al.) takes `La` from the point-contact
//! regression of Masjedi & Khonsari (Tribol. Int. 82 (2015) 228–244; line-contact
//! companion J. Tribol. 134 (2012) 011503), a function `f(kappa, W, U, G, sigma_bar, V)` of
//! `W = Q/(E' Rx²)`, `U = eta0 u/(E' Rx)`, `G = alpha_p E'`, `sigma_bar = sigma/Rx`,
//! `V = H/E'`. The paper's text was not reachable here: four sessions searched the stored
//! pages, docs, code and issues; the last found that a copy of the point-contact paper is
//! among the stored pages (c.coek.info, "pdf-on-the-effect-of-surface-roughness-in-point-
//! contact-ehl-formulas-for-film-thickn…") but only its opening (title, abstract) comes
//! back from the search, and the LSU repository and ASME pages give only the abstracts of
//! both papers; no code implementing the formula was found. So the form is the one study
//! \[2\] prints as its eq. (8):
//!
//! `La = 10 W^-0.083 U^0.143 G^0.314 ln(1 + 0.689^(1/4) V^0.509 W^-0.501 U^-2.9 G^-2.87)`.
//!
//! **The garbled term.** `0.689^(1/4)` raises a constant to a power and carries no
//! roughness, although `La` must depend on it (the paper's stated limit `La -> 0` for
//! smooth surfaces). What is restored: the roughness factor `sigma_bar^s` inside the
//! logarithm, `X = 0.689 sigma_bar^s V^0.509 W^-0.501 U^-2.9 G^-2.87`. The printed exponent
//! `1/4` cannot be `s`: at study \[2\]'s own outer contact (6012, 500 N, 2000 rpm,
//! `sigma = 0.2 um`) it gives `La ≈ 550 %`, an impossible share (see the test
//! `printed_quarter_exponent_is_impossible`). The exponent used, [`SIGMA_EXPONENT`]
//! `= 2.9/0.67 ≈ 4.33`, makes the roughness enter the logarithm through the same combination
//! as the speed enters the film: the film thickness grows as `U^0.67` (Hamrock–Dowson,
//! docs/physics.md §6), so `U^-2.9` is `(h/Rx)^(-2.9/0.67)` and the film parameter
//! `Lambda = h/sigma` appears as `Lambda^-4.33` — roughness and speed trade against each
//! other as they do in `Lambda`. This is a reconstruction, not the paper: the alternative
//! reading `s = 4` (the `4` of the printed `1/4`) is [`AsperityReading::Quartic`], and the
//! study page (docs/study-wear.md) shows both side by side. Dimensions: every group is
//! dimensionless, so any `s` is dimensionally admissible; the limits decide.
//!
//! **Range.** A regression holds inside its data. As `U -> 0` the printed form first
//! rises and then falls again (the prefactor's `U^0.143` wins over the logarithm's
//! `-2.9 ln U` beyond `X* ≈ exp(2.9/0.143)`, see [`x_turn`]). Past that turning point the
//! regression is outside its data, and the share is continued from its value `La*` at the
//! turning speed `U*` to the dry limit, `La = La* + (100 - La*)(1 - (U/U*)^0.143)` (the
//! prefactor's own speed exponent; an extrapolation choice, named here), so `La -> 100`
//! as the film vanishes. The share is capped at 100 %. `u = 0` (no entrainment, no film)
//! is `La = 100` exactly; zero roughness is `La = 0` exactly.
//! The result is continuous in all arguments and monotone: rising with roughness, falling
//! with speed.
//!
//! **A second reading: the line-contact ratio.** Masjedi & Khonsari's line-contact
//! regression (J. Tribol. 134 (2012) 011503; the formula as coded in public code, medium
//! confidence, docs/physics.md §7) gives, with `W1 = w/(E' Rx)` the load per unit length
//! made dimensionless,
//! `La = 0.005 W1^-0.408 U^-0.088 G^0.103 ln(1 + 4470 sigma_bar^6.015 V^1.168 W1^0.485 U^-3.741 G^-2.898)`
//! per cent. Here it is applied to the central slice of the Hertz ellipse: the slice
//! through the centre along the rolling direction carries `w = (pi b/2) p0 = 3Q/(4a)` per
//! unit length (`a` the semi-axis across the rolling direction), so `W1 = 3Q/(4 a E' Rx)`,
//! with `a = ca Q^(1/3)` from the Hertz solution ([`Groups::ha`]). That is an assumption of
//! this project (the ball contact is not a line contact), named as a reading
//! ([`AsperityReading::LineContact`]), not the study's formula. Its limits: `La -> 0` for
//! smooth surfaces and as the load vanishes, rising with roughness, falling with speed (no
//! turning point: both speed exponents are negative); capped at 100 %.

/// Exponent of `sigma_bar` restored in the logarithm (`2.9/0.67`; module notes).
pub const SIGMA_EXPONENT: f64 = 2.9 / 0.67;

/// Which exponent of the roughness the restored form uses (module notes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AsperityReading {
    /// `s = 2.9/0.67`: roughness and speed enter as they enter the film parameter.
    #[default]
    FilmParameter,
    /// `s = 4`: the `4` of the printed `1/4`.
    Quartic,
    /// Masjedi & Khonsari's line-contact ratio on the ellipse's central slice (module
    /// notes), not a reading of the printed point-contact form.
    LineContact,
}

impl AsperityReading {
    /// The roughness exponent `s` of the restored point-contact form (`6.015`, the
    /// line-contact regression's own, for [`AsperityReading::LineContact`]).
    pub fn exponent(self) -> f64 {
        match self {
            AsperityReading::FilmParameter => SIGMA_EXPONENT,
            AsperityReading::Quartic => 4.0,
            AsperityReading::LineContact => LINE_SIGMA,
        }
    }

    /// Every reading, in the order the study page shows them.
    pub const ALL: [AsperityReading; 3] = [
        AsperityReading::FilmParameter,
        AsperityReading::Quartic,
        AsperityReading::LineContact,
    ];

    /// A short label for tables and file names.
    pub fn label(self) -> &'static str {
        match self {
            AsperityReading::FilmParameter => "film-parameter",
            AsperityReading::Quartic => "quartic",
            AsperityReading::LineContact => "line-contact",
        }
    }
}

/// Dimensionless groups of one contact (module notes), all `>= 0`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Groups {
    /// Ellipticity `a/b` (the printed form does not use it).
    pub kappa: f64,
    /// Load `Q/(E' Rx²)`.
    pub w: f64,
    /// Speed `eta0 u/(E' Rx)`.
    pub u: f64,
    /// Material `alpha_p E'`.
    pub g: f64,
    /// Roughness `sigma/Rx`.
    pub sigma: f64,
    /// Hardness `H/E'`.
    pub v: f64,
    /// Hertz semi-axis across the rolling direction over `Rx` at `W = 1`:
    /// `a/Rx = ha W^(1/3)` (used by [`AsperityReading::LineContact`] only; 0 when unknown).
    pub ha: f64,
}

/// One rough lubricated contact in SI units, what [`Groups::new`] makes dimensionless.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Contact {
    /// Load, N.
    pub q: f64,
    /// Entrainment speed, m/s (its magnitude is used).
    pub u: f64,
    /// Effective radius in the rolling direction, m.
    pub rx: f64,
    /// Effective modulus `E'`, Pa.
    pub e_eff: f64,
    /// Inlet viscosity, Pa s.
    pub eta0: f64,
    /// Pressure–viscosity coefficient, 1/Pa.
    pub alpha_p: f64,
    /// Composite rms roughness, m.
    pub sigma: f64,
    /// Hardness, Pa.
    pub h: f64,
    /// Ellipticity `a/b`.
    pub kappa: f64,
    /// Hertz coefficient `ca` of the semi-axis across the rolling direction, `a = ca Q^(1/3)`,
    /// m/N^(1/3) ([`crate::contact::hertz::PointContact::semi_axis_coefficients`]; 0 when
    /// unknown: the line-contact reading then gives 0).
    pub ca: f64,
}

impl Groups {
    /// The groups of the contact `c`.
    pub fn new(c: &Contact) -> Self {
        let Contact {
            q,
            u,
            rx,
            e_eff,
            eta0,
            alpha_p,
            sigma,
            h,
            kappa,
            ca,
        } = *c;
        Groups {
            kappa,
            w: q / (e_eff * rx * rx),
            u: eta0 * u.abs() / (e_eff * rx),
            g: alpha_p * e_eff,
            sigma: sigma / rx,
            v: h / e_eff,
            // a/Rx = ca Q^(1/3)/Rx = ca (W E' Rx²)^(1/3)/Rx.
            ha: if ca > 0.0 {
                ca * (e_eff * rx * rx).cbrt() / rx
            } else {
                0.0
            },
        }
    }
}

/// Exponent of `U` in the prefactor and in the logarithm.
const A_U: f64 = 0.143;
const B_U: f64 = 2.9;

/// Exponent of `sigma_bar` in the line-contact regression's logarithm.
const LINE_SIGMA: f64 = 6.015;

/// The line-contact reading (module notes) at load group `w` of groups `g`, per cent.
fn line_share(g: &Groups, w: f64) -> f64 {
    if g.ha <= 0.0 || w <= 0.0 || g.ha.is_nan() || w.is_nan() {
        return 0.0;
    }
    // W1 = 3Q/(4 a E' Rx) = 3 W /(4 a/Rx) with a/Rx = ha W^(1/3).
    let ln_w1 = (0.75 / g.ha).ln() + (2.0 / 3.0) * w.ln();
    let (ln_u, ln_g) = (g.u.ln(), g.g.ln());
    let ln_x = 4470f64.ln() + LINE_SIGMA * g.sigma.ln() + 1.168 * g.v.ln() + 0.485 * ln_w1
        - 3.741 * ln_u
        - 2.898 * ln_g;
    let log_term = if ln_x > 30.0 {
        ln_x
    } else {
        ln_x.exp().ln_1p()
    };
    let la = 0.005 * (-0.408 * ln_w1 - 0.088 * ln_u + 0.103 * ln_g).exp() * log_term;
    if la.is_nan() {
        100.0
    } else {
        la.clamp(0.0, 100.0)
    }
}

/// `X*`: the logarithm's argument where the printed form of `La` is largest as `U`
/// falls, the root of `(1 + X) ln(1 + X) / X = 2.9/0.143` (module notes).
pub fn x_turn() -> f64 {
    // y = ln(1 + X): y e^y / (e^y - 1) = r; fixed point y = r (1 - e^-y), converging fast
    // from y = r because e^-r is tiny.
    let r = B_U / A_U;
    let mut y = r;
    for _ in 0..8 {
        y = r * (1.0 - (-y).exp());
    }
    y.exp_m1()
}

/// Asperity load share `La`, per cent, in `[0, 100]` (module notes).
pub fn asperity_share(g: &Groups, reading: AsperityReading) -> f64 {
    ShareAt::new(g, reading).share(g.w)
}

/// [`asperity_share`] of one contact at one speed, with every term that does not depend
/// on the load `W` (the logarithms of `sigma_bar`, `V`, `G`, `U`) computed once: the same
/// operations in the same order, so the same bits (`asperity_share` is this with its own
/// groups).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShareAt {
    /// The share whatever the load: 0 without roughness, 100 without entrainment.
    fixed: Option<f64>,
    /// The groups, for the line-contact reading (which has its own form).
    line: Option<Groups>,
    /// `ln 0.689 + s ln sigma_bar + 0.509 ln V` (the leading terms of `ln X1`, summed in
    /// the formula's order).
    lead: f64,
    ln_g: f64,
    ln_u: f64,
}

impl ShareAt {
    /// From the groups (their load `w` is not used).
    pub fn new(g: &Groups, reading: AsperityReading) -> Self {
        let fixed = if g.sigma.is_nan() || g.sigma <= 0.0 {
            Some(0.0)
        } else if g.u.is_nan() || g.u <= 0.0 {
            Some(100.0)
        } else {
            None
        };
        if fixed.is_some() || reading == AsperityReading::LineContact {
            return ShareAt {
                fixed,
                line: (reading == AsperityReading::LineContact).then_some(*g),
                lead: 0.0,
                ln_g: 0.0,
                ln_u: 0.0,
            };
        }
        ShareAt {
            fixed,
            line: None,
            lead: (0.689f64).ln() + reading.exponent() * g.sigma.ln() + 0.509 * g.v.ln(),
            ln_g: g.g.ln(),
            ln_u: g.u.ln(),
        }
    }

    /// The share at load group `w`, per cent.
    pub fn share(&self, w: f64) -> f64 {
        if let Some(la) = self.fixed {
            return la;
        }
        if let Some(g) = &self.line {
            return line_share(g, w);
        }
        let ln_w = w.ln();
        // x1 = X U^2.9 (the speed-free part of the logarithm's argument).
        let ln_x1 = self.lead - 0.501 * ln_w - 2.87 * self.ln_g;
        let ln_x = ln_x1 - B_U * self.ln_u;
        // ln X*: a constant (eight `exp`, an `exp_m1` and a `ln`), computed once.
        static LN_XT: std::sync::OnceLock<f64> = std::sync::OnceLock::new();
        let ln_xt = *LN_XT.get_or_init(|| x_turn().ln());
        // Past the turning point, the share at the turning speed, then blended to 100 %.
        let (ln_x, ln_u, beyond) = if ln_x > ln_xt {
            let ln_ut = (ln_x1 - ln_xt) / B_U;
            (ln_xt, ln_ut, Some(self.ln_u - ln_ut))
        } else {
            (ln_x, self.ln_u, None)
        };
        let log_term = if ln_x > 30.0 {
            ln_x
        } else {
            ln_x.exp().ln_1p()
        };
        let la = 10.0 * (-0.083 * ln_w + A_U * ln_u + 0.314 * self.ln_g).exp() * log_term;
        if la.is_nan() {
            return 100.0;
        }
        let la = la.clamp(0.0, 100.0);
        match beyond {
            // (U/U*)^0.143 falls from 1 at the turning point to 0 with the film.
            Some(ln_ratio) => la + (100.0 - la) * (1.0 - (A_U * ln_ratio).exp()),
            None => la,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Study \[2\]'s outer contact: 6012 (D 10.45 mm, dm 77.6 mm), a ball load near the
    /// peak of 500 N radial, 2000 rpm, its oil (docs/physics.md §10), steel E' = 2.28e11 Pa.
    fn study(sigma: f64) -> Groups {
        let (d, dm) = (10.45e-3, 77.6e-3);
        let gamma = d / dm;
        let rx = 0.5 * d * (1.0 + gamma);
        let omega = 2000.0 * std::f64::consts::PI / 30.0;
        let u = 0.25 * dm * omega * (1.0 - gamma * gamma);
        Groups::new(&Contact {
            q: 180.0,
            u,
            rx,
            e_eff: 2.28e11,
            eta0: 0.04667,
            alpha_p: 2.1e-8,
            sigma,
            h: 2.39e9,
            kappa: 8.0,
            ca: outer_contact().semi_axis_coefficients().0,
        })
    }

    /// The 6012's outer-race contact (groove 0.53 D), steel.
    fn outer_contact() -> crate::contact::hertz::PointContact {
        use crate::contact::hertz::{Curvature, PointContact, Race};
        let c = Curvature::ball_race(10.45e-3, 77.6e-3, 0.0, 0.53, Race::Outer);
        PointContact::new(c, 2.28e11)
    }

    /// The line-contact reading is the regression as written (powers, not logarithms) at
    /// `W1 = 3Q/(4 a E' Rx)` of the ellipse's central slice, and keeps its limits.
    #[test]
    fn line_contact_reading() {
        let line = AsperityReading::LineContact;
        for sigma in [0.2e-6, 0.42e-6] {
            let g = study(sigma);
            let pc = outer_contact();
            let q = 180.0;
            let (a, _) = pc.semi_axes(q);
            let w1 = 3.0 * q / (4.0 * a * 2.28e11 * pc.curvature.rx);
            let rx = pc.curvature.rx;
            // `study` builds its groups with its own Rx (the same formula): rescale.
            let sb = sigma / rx;
            let x = 4470.0
                * sb.powf(6.015)
                * g.v.powf(1.168)
                * w1.powf(0.485)
                * g.u.powf(-3.741)
                * g.g.powf(-2.898);
            let by_hand = 0.005 * w1.powf(-0.408) * g.u.powf(-0.088) * g.g.powf(0.103) * x.ln_1p();
            let got = asperity_share(&g, line);
            assert!(
                (got - by_hand.min(100.0)).abs() < 1e-9 * by_hand.max(1.0),
                "sigma {sigma:e}: {got} vs {by_hand}"
            );
            assert!(got > 0.0 && got < 100.0, "{got}");
            eprintln!("sigma {sigma:e} line-contact: La {got}");
        }
        let g = study(0.2e-6);
        assert_eq!(asperity_share(&Groups { sigma: 0.0, ..g }, line), 0.0);
        assert!(
            asperity_share(
                &Groups {
                    sigma: g.sigma * 1e-2,
                    ..g
                },
                line
            ) < 1e-6
        );
        // Vanishing load: La -> 0, slowly (as W1^0.077).
        let at_study = asperity_share(&g, line);
        let light = asperity_share(
            &Groups {
                w: g.w * 1e-15,
                ..g
            },
            line,
        );
        let lighter = asperity_share(
            &Groups {
                w: g.w * 1e-30,
                ..g
            },
            line,
        );
        assert!(
            lighter < light && light < at_study,
            "{lighter} {light} {at_study}"
        );
        assert!(lighter < 0.1 * at_study, "{lighter} {at_study}");
        assert_eq!(asperity_share(&Groups { u: 0.0, ..g }, line), 100.0);
        // Unknown semi-axis: the reading cannot be formed and gives 0, never NaN.
        assert_eq!(asperity_share(&Groups { ha: 0.0, ..g }, line), 0.0);
        // Monotone: rising with roughness, falling with speed, continuous.
        let mut prev = 0.0;
        for k in 0..400 {
            let s = g.sigma * 10f64.powf(-2.0 + 4.0 * k as f64 / 400.0);
            let l = asperity_share(&Groups { sigma: s, ..g }, line);
            assert!(l >= prev, "sigma {s:e}: {l} < {prev}");
            prev = l;
        }
        let mut prev = 100.0;
        for k in 0..800 {
            let u = g.u * 10f64.powf(-12.0 + 14.0 * k as f64 / 800.0);
            let l = asperity_share(&Groups { u, ..g }, line);
            assert!(l <= prev + 1e-12, "U {u:e}: {l} > {prev}");
            assert!((prev - l) < 5.0, "continuous: {prev} -> {l}");
            prev = l;
        }
        // ShareAt at another load equals the function with that load.
        let at = ShareAt::new(&g, line);
        for w in [g.w * 0.1, g.w, g.w * 7.0] {
            assert_eq!(at.share(w), asperity_share(&Groups { w, ..g }, line));
        }
    }

    #[test]
    fn smooth_and_filmless_limits() {
        let g = study(0.2e-6);
        let la = asperity_share(&g, AsperityReading::default());
        assert!(la > 0.0 && la < 100.0, "{la}");
        // Smooth surfaces: La -> 0 (exactly 0 at sigma = 0).
        let smooth = Groups { sigma: 1e-9, ..g };
        assert!(asperity_share(&smooth, AsperityReading::default()) < 1e-9);
        assert_eq!(
            asperity_share(&Groups { sigma: 0.0, ..g }, AsperityReading::default()),
            0.0
        );
        // Film vanishing (U -> 0): La -> 100 (exactly 100 at U = 0).
        for (f, min) in [(1e-3, 95.0), (1e-6, 99.0), (1e-30, 99.999)] {
            let thin = Groups { u: g.u * f, ..g };
            let l = asperity_share(&thin, AsperityReading::default());
            assert!(l >= min, "{f}: {l}");
        }
        for s in [0.2e-6, 0.42e-6] {
            for r in [AsperityReading::FilmParameter, AsperityReading::Quartic] {
                eprintln!("sigma {s:e} {r:?}: La {}", asperity_share(&study(s), r));
            }
        }
        assert_eq!(
            asperity_share(&Groups { u: 0.0, ..g }, AsperityReading::default()),
            100.0
        );
        // Very rough surfaces: the asperities carry everything.
        let rough = Groups {
            sigma: g.sigma * 100.0,
            ..g
        };
        assert_eq!(asperity_share(&rough, AsperityReading::default()), 100.0);
    }

    /// Monotone: rising with roughness, falling with speed, continuous across the
    /// turning point (both readings).
    #[test]
    fn monotone_in_roughness_and_speed() {
        for reading in [AsperityReading::FilmParameter, AsperityReading::Quartic] {
            let g = study(0.2e-6);
            let mut prev = 0.0;
            for k in 0..400 {
                let s = g.sigma * 10f64.powf(-2.0 + 4.0 * k as f64 / 400.0);
                let l = asperity_share(&Groups { sigma: s, ..g }, reading);
                assert!(l >= prev, "{reading:?} sigma {s:e}: {l} < {prev}");
                prev = l;
            }
            let mut prev = 100.0;
            for k in 0..800 {
                let u = g.u * 10f64.powf(-12.0 + 14.0 * k as f64 / 800.0);
                let l = asperity_share(&Groups { u, ..g }, reading);
                assert!(l <= prev + 1e-12, "{reading:?} U {u:e}: {l} > {prev}");
                assert!((prev - l) < 5.0, "{reading:?} continuous: {prev} -> {l}");
                prev = l;
            }
        }
    }

    /// The turning point solves its equation, and the printed form is flat there.
    #[test]
    fn turning_point() {
        let x = x_turn();
        let r = B_U / A_U;
        assert!(((1.0 + x) * x.ln_1p() / x - r).abs() < 1e-9 * r);
    }

    /// The printed exponent 1/4 on the roughness gives an impossible share (> 100 %) at
    /// study \[2\]'s own operating point: it cannot be the lost roughness exponent.
    #[test]
    fn printed_quarter_exponent_is_impossible() {
        let g = study(0.2e-6);
        let ln_x = 0.689f64.ln() + 0.25 * g.sigma.ln() + 0.509 * g.v.ln()
            - 0.501 * g.w.ln()
            - 2.9 * g.u.ln()
            - 2.87 * g.g.ln();
        let la = 10.0 * g.w.powf(-0.083) * g.u.powf(0.143) * g.g.powf(0.314) * ln_x;
        assert!(la > 300.0, "{la}");
    }
}
