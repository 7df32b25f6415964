//! Defects and waviness on a cylindrical roller bearing, per lamina (docs/physics.md §R12).
//!
//! The effects a ball sees as one offset of its approach (`crate::models::effects`, docs/physics.md
//! §5.3–5.4) act on a roller lamina by lamina:
//!
//! - **a defect** (a pit on the outer or inner race, or on a roller) of circumferential width
//!   `L` and depth `H` takes the depth loss `e(s)` of `crate::models::defects` (the roller's
//!   cross-section in the rolling plane is a circle of radius `Dwe/2`, so the ball's sagitta
//!   geometry holds with `R = Dwe/2`) from the laminae it spans axially: those whose centres
//!   `x_k` lie within `[c - w/2, c + w/2]`, `c` its axial position from the roller's mid-plane
//!   along `+z` and `w` its axial width (absent: the whole effective length `Lwe`, every
//!   lamina). A defect narrower than a lamina that spans no centre acts on the lamina holding
//!   its centre. The other laminae keep their approach: their loads change only through the
//!   ring's motion.
//! - **waviness** of a race (`A sin(k theta + beta)` around the circumference, the same at every
//!   axial position) moves every lamina's approach by the same amount; a roller's waviness (its
//!   diameter deviation `w(phi) + w(phi + pi)`, met at both races) likewise.
//!
//! On a tapered roller bearing a cup (outer) or cone (inner) defect acts the same way on the
//! laminae's approach along the cup normal (`contact::tapered_law`): its axial extent is
//! measured along the raceway generatrix from the roller's mid-point, positive toward `+z`
//! (the small end), where lamina `k` sits at `-x_k cos(beta)`; the caller passes those
//! positions. Its depth, normal to its own raceway, is taken along the cup normal: the cone's
//! normal is `2 beta` (a few degrees) from it, the law's own approximation. Cup and cone
//! waviness likewise: the raceway's deviation, normal to it and the same along its
//! generatrix, moves every lamina's approach along the cup normal by the same amount (exact
//! for the cup, `cos(2 beta)` short of it for the cone, neglected as for the defects).
//!
//! Ball-spacing scatter, lubrication, wear and thermal effects are not built for rollers and
//! are refused by name ([`RollerEffects::new`]); so are a tapered roller's own defects and
//! waviness.

use crate::error::{Error, Result};
use crate::geometry::Bearing;
use crate::models::defects::{Defect, DefectSite};
use crate::models::effects::{axial_extent, Effects, Element, FilmKind, RingEffects};
use crate::models::waviness::Harmonic;

/// A roller bearing's defects and waviness, compiled for its laminae (module docs).
#[derive(Debug, Clone)]
pub struct RollerEffects {
    /// Each defect with the lamina indices `[first, end)` it spans.
    defects: Vec<(Defect, usize, usize)>,
    waviness: Vec<Harmonic>,
    /// Roller spin angle per radian of shaft angle (kinematic, relative to the cage).
    spin_ratio: f64,
    /// Laminae per roller.
    ns: usize,
}

impl RollerEffects {
    /// Compile the scene's effects `e` for roller bearing `b` whose laminae have their centres
    /// at `x` (m from the roller's mid-plane, along `+z`; a tapered roller's along the
    /// raceway generatrix, module docs). Refuses, naming the field, what the ring level does
    /// not model on rollers (spacing scatter, lubrication, wear, thermal; a roller's own
    /// defects and waviness on a tapered bearing) and a defect wider than the roller's effective length or
    /// reaching past it.
    pub fn new(e: &Effects, b: &Bearing, x: &[f64]) -> Result<RollerEffects> {
        let refuse = |field: &str, what: &str| {
            Err(Error::invalid(
                format!("effects.{field}"),
                what.to_string(),
                "absent: the ring level models defects and waviness on cylindrical roller bearings, not this effect",
            ))
        };
        if e.ball_spacing.is_some() {
            return refuse("ball_spacing", "given");
        }
        if e.lubrication
            .as_ref()
            .is_some_and(|l| l.film == FilmKind::Ehl)
        {
            return refuse("lubrication", "an EHL film");
        }
        if e.wear.is_some() {
            return refuse("wear", "given");
        }
        if e.thermal.is_some() {
            return refuse("thermal", "given");
        }
        if let crate::geometry::element::Element::Roller(r) = &b.element {
            if r.kind.is_tapered() {
                if let Some(i) = e.waviness.iter().position(|w| w.race == Element::Ball) {
                    return Err(Error::invalid(
                        format!("effects.waviness[{i}].race"),
                        "a roller's waviness on a tapered roller bearing",
                        "outer (the cup) or inner (the cone): a tapered roller's own waviness is not built",
                    ));
                }
                if let Some(i) = e.defects.iter().position(|d| d.race == Element::Ball) {
                    return Err(Error::invalid(
                        format!("effects.defects[{i}].race"),
                        "a roller defect on a tapered roller bearing",
                        "outer (the cup) or inner (the cone): a tapered roller's own defects are not built",
                    ));
                }
            }
        }
        let fx = RingEffects::new(e, b)?;
        let mut defects = Vec::with_capacity(fx.defects.len());
        for (i, (d, spec)) in fx.defects.iter().zip(&e.defects).enumerate() {
            let (first, end) = match axial_extent(i, spec, b)? {
                Some((c, w)) => span(x, c, w),
                None => (0, x.len()),
            };
            defects.push((d.clone(), first, end));
        }
        Ok(RollerEffects {
            defects,
            waviness: fx.waviness.clone(),
            spin_ratio: fx.spin_ratio,
            ns: x.len(),
        })
    }

    /// Whether the effects need the shaft angle (an inner-race or roller effect).
    pub fn needs_shaft_angle(&self) -> bool {
        self.defects
            .iter()
            .any(|(d, ..)| d.site != DefectSite::Outer)
            || !self
                .waviness
                .iter()
                .all(|w| w.site == crate::models::waviness::WavySite::Outer)
    }

    /// The lamina indices `[first, end)` defect `i` spans.
    pub fn span(&self, i: usize) -> (usize, usize) {
        let (_, a, b) = self.defects[i];
        (a, b)
    }

    /// Each lamina's approach offset (m) of roller `j` at azimuth `psi` with the shaft turned
    /// by `theta_s` (rad) into `out` (length `ns`): the waviness's interference minus the
    /// depth loss of every defect on the laminae it spans. Returns whether any offset is
    /// non-zero (a roller without one runs the plain law, bit for bit); `out` is written only
    /// then (left as it was otherwise: most rollers of a ring are away from a defect, and
    /// their callers do not read it).
    #[inline]
    pub fn offsets(&self, j: usize, psi: f64, theta_s: f64, out: &mut [f64]) -> bool {
        // Most rollers: no waviness and no pit in reach, nothing to evaluate (the same
        // answer: every loss is an exact zero there).
        if self.waviness.is_empty()
            && !self
                .defects
                .iter()
                .any(|(d, ..)| d.reaches(j, psi, theta_s))
        {
            return false;
        }
        self.offsets_at(j, psi, theta_s, out)
    }

    /// [`RollerEffects::offsets`] given also the `(sin, cos)` of `psi` (to a few units in the
    /// last place, as `seam::element::place_evenly_sc` gives them): the same answer, a
    /// roller well away from every outer-race pit found by a product
    /// ([`Defect::reaches_sc`]).
    #[inline]
    pub fn offsets_sc(
        &self,
        j: usize,
        psi: f64,
        sc: (f64, f64),
        theta_s: f64,
        out: &mut [f64],
    ) -> bool {
        if self.waviness.is_empty()
            && !self
                .defects
                .iter()
                .any(|(d, ..)| d.reaches_sc(j, psi, sc, theta_s))
        {
            return false;
        }
        self.offsets_at(j, psi, theta_s, out)
    }

    /// [`RollerEffects::offsets`], every effect evaluated.
    fn offsets_at(&self, j: usize, psi: f64, theta_s: f64, out: &mut [f64]) -> bool {
        debug_assert_eq!(out.len(), self.ns);
        let phi = self.spin_ratio * theta_s;
        let mut w = 0.0;
        for h in &self.waviness {
            w += h.interference(j, psi, theta_s, phi);
        }
        let mut any = w != 0.0;
        if any {
            out.fill(w);
        }
        for (d, first, end) in &self.defects {
            let e = d.loss(j, psi, theta_s, phi);
            if e != 0.0 {
                if !any {
                    // (`w` is a zero here, of either sign: the one a fill would have written.)
                    out.fill(w);
                    any = true;
                }
                for o in &mut out[*first..*end] {
                    *o -= e;
                }
            }
        }
        any
    }
}

/// The laminae (centres `x`) a defect centred at `c` of axial width `w` spans (module docs):
/// `[first, end)`; the lamina nearest `c` when no centre lies within it.
fn span(x: &[f64], c: f64, w: f64) -> (usize, usize) {
    // A relative tolerance so a defect whose edge falls on a lamina centre (an exact half of
    // the roller, say) takes it whatever the rounding of the centres.
    let tol = 1e-9 * w.max(1e-9);
    let inside = |xk: f64| (xk - c).abs() <= 0.5 * w + tol;
    match x.iter().position(|&xk| inside(xk)) {
        Some(first) => {
            let end = first + x[first..].iter().take_while(|&&xk| inside(xk)).count();
            (first, end)
        }
        None => {
            let k = (0..x.len())
                .min_by(|&a, &b| (x[a] - c).abs().total_cmp(&(x[b] - c).abs()))
                .unwrap_or(0);
            (k, k + 1)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nu206(effects: &str) -> Result<(RollerEffects, Vec<f64>)> {
        let b = crate::geometry::roller_catalogue::lookup("NU206")
            .unwrap()
            .build()
            .unwrap();
        let x = b.laminae().unwrap().x;
        let b = Bearing::from_roller(b).unwrap();
        let e: Effects = toml::from_str(effects).unwrap();
        RollerEffects::new(&e, &b, &x).map(|f| (f, x))
    }

    /// A defect over the `+z` half of NU206's 9.6 mm (30 laminae) spans laminae 15..30; one
    /// 0.1 mm wide (under a lamina's 0.32 mm) at 0.05 mm spans the lamina holding that point;
    /// absent width: every lamina.
    #[test]
    fn spans_follow_the_axial_extent() {
        let (f, _) = nu206(
            r#"defects = [
  { race = "outer", width_mm = 1.0, depth_um = 10.0, axial_width_mm = 4.8, axial_position_mm = 2.4 },
  { race = "outer", width_mm = 1.0, depth_um = 10.0, axial_width_mm = 0.1, axial_position_mm = 0.05 },
  { race = "inner", width_mm = 1.0, depth_um = 10.0 },
]"#,
        )
        .unwrap();
        assert_eq!(f.span(0), (15, 30));
        assert_eq!(f.span(1), (15, 16));
        assert_eq!(f.span(2), (0, 30));
        assert!(f.needs_shaft_angle());
    }

    /// At the defect's centre the spanned laminae lose the depth (the floor: 10 µm is below the
    /// edge limit of a 1 mm pit under an 8.5 mm roller, 29.5 µm, less the corner rounding of at
    /// most a quarter of 10 % of it), the others nothing; away from it no offset at all.
    #[test]
    fn offsets_take_the_loss_from_the_spanned_laminae_only() {
        let (f, _) = nu206(
            r#"defects = [{ race = "outer", angle_deg = 270.0, width_mm = 1.0, depth_um = 10.0, axial_width_mm = 4.8, axial_position_mm = -2.4 }]"#,
        )
        .unwrap();
        let mut o = vec![1.0; 30];
        assert!(f.offsets(3, 270f64.to_radians(), 0.7, &mut o));
        for (k, &v) in o.iter().enumerate() {
            if k < 15 {
                assert!((-1e-5..-0.97e-5).contains(&v), "{k}: {v}");
            } else {
                assert_eq!(v, 0.0, "{k}");
            }
        }
        // Away from it: no offset, and `out` left as it was.
        let before = o.clone();
        assert!(!f.offsets(3, 0.3, 0.7, &mut o));
        assert_eq!(o, before);
        // Back on the pit, over a buffer holding another roller's offsets: the same values.
        let mut again = vec![7.0; 30];
        assert!(f.offsets(3, 270f64.to_radians(), 0.7, &mut again));
        assert_eq!(again, o);
    }

    #[test]
    fn what_rollers_do_not_model_is_refused_by_name() {
        for (text, field) in [
            ("ball_spacing = { scatter = 0.5 }", "effects.ball_spacing"),
            ("lubrication = { film = \"ehl\" }", "effects.lubrication"),
            (
                r#"defects = [{ race = "outer", width_mm = 1.0, depth_um = 1.0, axial_width_mm = 9.7 }]"#,
                "effects.defects[0].axial_width_mm",
            ),
            (
                r#"defects = [{ race = "outer", width_mm = 1.0, depth_um = 1.0, axial_width_mm = 4.0, axial_position_mm = 2.9 }]"#,
                "effects.defects[0].axial_position_mm",
            ),
            (
                r#"defects = [{ race = "outer", width_mm = 8.6, depth_um = 1.0 }]"#,
                "effects.defects[0].width_mm",
            ),
        ] {
            let e = nu206(text).unwrap_err().to_string();
            assert!(e.contains(field), "{text}: {e}");
        }
        // The range that can be met is named: the roller's effective length.
        let e = nu206(
            r#"defects = [{ race = "outer", width_mm = 1.0, depth_um = 1.0, axial_width_mm = 12.0 }]"#,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("9.6 mm"), "{e}");
    }
}
