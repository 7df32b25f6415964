//! Local defects (spalls): the depth loss `H_j` a ball sees as it crosses a rectangular
//! pit (docs/physics.md §5.3; study \[4\], Yan et al.; the finite-ball geometry of Moazen-Ahmadi &
//! Howard, *Mech. Syst. Signal Process.* 80 (2016) and Sawalhi & Randall,
//! *Mech. Syst. Signal Process.* 22 (2008)).
//!
//! A pit of circumferential width `L` and depth `H` on a race (or on a ball). A rigid ball
//! of radius `R = D/2` whose contact point sits at arc position `s` from the pit centre
//! sinks by the largest `e` that keeps it clear of both edges and of the floor:
//!
//! ```text
//! e(s) = min( f(L/2 - s), f(L/2 + s), H ),   f(d) = R - sqrt(R² - d²),   |s| < L/2
//! e(s) = 0                                                               |s| >= L/2
//! ```
//!
//! The three arguments are the three phases study \[4\] names: entry (the ball pivots on the
//! entry edge), floor (it rests on the bottom), exit (it climbs out over the exit edge).
//! The deepest it can go with edges only is `Hr = f(L/2) = D/2 - sqrt((D/2)² - (L/2)²)`:
//! for `H >= Hr` it rides the two edges and `e` rises to `Hr` and back; for `H < Hr` it
//! reaches the floor and `e` is capped at `H`. `f` has zero slope at `d = 0`, so the entry
//! and exit are C¹; the corners where two phases meet are rounded with a quadratic smooth
//! minimum of width `SMOOTH * min(H, Hr)` (C¹, lowers the corners by at most a quarter of
//! that width), so an integrator never meets a slope jump.
//!
//! The same sagitta applies to a pit on a ball crossed by a (locally flat) race: the race
//! bridges the chord `L` of the ball's circle.

use std::f64::consts::PI;

/// Width of the smooth minimum at the phase corners, as a fraction of `min(H, Hr)`.
pub const SMOOTH: f64 = 0.1;

/// Largest azimuth (rad) [`Defect::reaches_sc`] answers from the cosine alone (its rounding,
/// 1e-10 rad there, stays far inside the margin).
pub const QUICK_ANGLE: f64 = 1e6;

/// Which element carries a defect.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DefectSite {
    /// Outer race, fixed in the housing.
    Outer,
    /// Inner race, turning with the shaft.
    Inner,
    /// Ball number `j` (0-based), turning with the ball's spin.
    Ball(usize),
}

/// One pit, ready to evaluate (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct Defect {
    /// Element.
    pub site: DefectSite,
    /// Angle of the pit centre at `t = 0`: on a race, azimuth from `+x`; on a ball, the
    /// spin angle from the outer contact point, rad.
    pub angle: f64,
    /// Circumferential width `L`, m.
    pub width: f64,
    /// Depth `H`, m.
    pub depth: f64,
    /// Ball radius `R = D/2`, m.
    pub r_ball: f64,
    /// Radius on which the pit's arc is measured (race contact radius, or `D/2`), m.
    pub r_arc: f64,
    /// Edge-limited depth `Hr`, m.
    pub hr: f64,
    /// Smooth-minimum width, m.
    k: f64,
    /// `(sin, cos)` of `angle` and the cosine of the pit's half-width angle widened by a
    /// margin (`-inf` for a pit wider than about a turn): [`Defect::reaches_sc`]'s quick test.
    sc: (f64, f64),
    cos_reach: f64,
}

/// Quadratic smooth minimum (C¹): equals `min(a, b)` when `|a - b| >= k`, and lies at most
/// `k/4` below it otherwise.
#[inline]
fn smin(a: f64, b: f64, k: f64) -> f64 {
    // A pit of zero depth has no corners to round (and `k = 0` would divide by zero).
    if k <= 0.0 {
        return a.min(b);
    }
    let h = (k - (a - b).abs()).max(0.0) / k;
    a.min(b) - h * h * k * 0.25
}

/// Wrap an angle to `[-pi, pi]`: `a - 2 pi n` with `n` the nearest whole turn, its product
/// rounded once (within an ulp of `|a|` of [`wrap_exact`]'s exact remainder, test
/// `wrap_matches_the_exact_remainder`, at a fraction of `fmod`'s cost); beyond `2^40` rad
/// and for NaN, [`wrap_exact`].
#[inline]
pub fn wrap(a: f64) -> f64 {
    const TAU: f64 = 2.0 * PI;
    if a.is_nan() || a.abs() >= 1.0995e12 {
        return wrap_exact(a);
    }
    // The nearest whole turn by the 1.5 x 2^52 shift (exact for |x| < 2^51; `round` is a
    // libm call on the baseline x86-64 target, which has no `roundsd`).
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let n = (a * (1.0 / TAU) + SHIFT) - SHIFT;
    let t = a - TAU * n;
    if t > PI {
        t - TAU
    } else if t < -PI {
        t + TAU
    } else {
        t
    }
}

/// Wrap an angle to `(-pi, pi]` through the exact remainder (`rem_euclid`).
#[inline]
pub fn wrap_exact(a: f64) -> f64 {
    let t = a.rem_euclid(2.0 * PI);
    if t > PI {
        t - 2.0 * PI
    } else {
        t
    }
}

/// `Hr = R - sqrt(R² - (L/2)²)`: how far a ball of radius `r` sinks into a slot of width
/// `l` when it rides on both edges (docs/physics.md §5.3).
pub fn edge_depth(r: f64, l: f64) -> f64 {
    sagitta(r, 0.5 * l)
}

#[inline]
fn sagitta(r: f64, d: f64) -> f64 {
    let d = d.clamp(0.0, r);
    // r - sqrt(r² - d²), written without cancellation.
    d * d / (r + (r * r - d * d).sqrt())
}

impl Defect {
    /// A pit of width `width` and depth `depth` (m) centred at `angle` (rad) on `site`,
    /// for balls of radius `r_ball`; `r_arc` is the radius its arc length is measured on.
    /// Callers validate `0 < width < 2 r_ball` and `depth > 0`.
    pub fn new(
        site: DefectSite,
        angle: f64,
        width: f64,
        depth: f64,
        r_ball: f64,
        r_arc: f64,
    ) -> Self {
        let hr = edge_depth(r_ball, width);
        // The half-width's angle widened by a millionth of itself and a µrad: far more than
        // the rounding of a (sin, cos) pair against its angle (a few 1e-16) or of an angle
        // below [`QUICK_ANGLE`] (1e-10 rad).
        let reach = 0.5 * width / r_arc * (1.0 + 1e-6) + 1e-6;
        Defect {
            site,
            angle,
            width,
            depth,
            r_ball,
            r_arc,
            hr,
            k: SMOOTH * hr.min(depth),
            sc: angle.sin_cos(),
            cos_reach: if reach < 3.0 {
                reach.cos()
            } else {
                f64::NEG_INFINITY
            },
        }
    }

    /// Largest depth loss: `min(H, Hr)` (before corner rounding).
    pub fn max_loss(&self) -> f64 {
        self.hr.min(self.depth)
    }

    /// Depth loss `e(s)` at arc position `s` (m) of the contact point from the pit centre.
    #[inline]
    pub fn loss_at(&self, s: f64) -> f64 {
        let half = 0.5 * self.width;
        if s.abs() >= half {
            return 0.0;
        }
        let entry = sagitta(self.r_ball, half + s);
        let exit = sagitta(self.r_ball, half - s);
        let e = smin(smin(entry, exit, self.k), self.depth, self.k);
        e.max(0.0)
    }

    /// Depth loss at the angle `a` (rad) of the contact point relative to the pit centre.
    #[inline]
    pub fn loss_at_angle(&self, a: f64) -> f64 {
        let s = self.r_arc * wrap(a);
        self.loss_at(s)
    }

    /// False when [`Defect::loss`] of ball `j` at azimuth `psi` with the shaft turned by
    /// `theta_s` is zero whatever the spin: a race pit's contact point at or beyond the pit's
    /// half-width (the test [`Defect::loss_at`] starts with, on the same numbers), a ball
    /// pit on another ball. Cheaper than the loss itself: a ring's elements are mostly away
    /// from its pits.
    #[inline]
    pub fn reaches(&self, j: usize, psi: f64, theta_s: f64) -> bool {
        let a = match self.site {
            DefectSite::Outer => psi - self.angle,
            DefectSite::Inner => psi - theta_s - self.angle,
            DefectSite::Ball(b) => return b == j,
        };
        // (A NaN reaches: its loss is left to `loss`.)
        let s = (self.r_arc * wrap(a)).abs();
        s < 0.5 * self.width || s.is_nan()
    }

    /// [`Defect::reaches`] given also `sc`, the `(sin, cos)` of `psi` (to a few units in the
    /// last place): an outer-race pit's angular distance is first compared by its cosine,
    /// `cos(psi - angle)` against that of the pit's half-width with a margin, a product and
    /// a comparison, and `false` is answered from that only when the element is well
    /// outside the pit (and `|psi|` below [`QUICK_ANGLE`]); the answer is `reaches`' own.
    #[inline]
    pub fn reaches_sc(&self, j: usize, psi: f64, sc: (f64, f64), theta_s: f64) -> bool {
        !self.well_outside(psi, sc) && self.reaches(j, psi, theta_s)
    }

    /// [`Defect::reaches_sc`]'s quick test: an outer-race pit whose angular distance from
    /// `psi` (`sc` its sine and cosine) has a cosine below the widened half-width's.
    #[inline]
    fn well_outside(&self, psi: f64, sc: (f64, f64)) -> bool {
        self.site == DefectSite::Outer
            && sc.1 * self.sc.1 + sc.0 * self.sc.0 < self.cos_reach
            && psi.abs() < QUICK_ANGLE
    }

    /// Depth loss of ball `j` at azimuth `psi`, with the shaft turned by `theta_s` and the
    /// balls spun (relative to the cage) by `phi` since `t = 0`. A ball pit meets the outer
    /// race at spin angle 0 and the inner race half a turn later; both losses add.
    #[inline]
    pub fn loss(&self, j: usize, psi: f64, theta_s: f64, phi: f64) -> f64 {
        match self.site {
            DefectSite::Outer => self.loss_at_angle(psi - self.angle),
            DefectSite::Inner => self.loss_at_angle(psi - theta_s - self.angle),
            DefectSite::Ball(b) => {
                if b != j {
                    return 0.0;
                }
                let a = phi + self.angle;
                self.loss_at_angle(a) + self.loss_at_angle(a - PI)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_min_is_min_far_apart_and_c1() {
        assert_eq!(smin(1.0, 3.0, 0.5), 1.0);
        assert!((smin(1.0, 1.0, 0.4) - 0.9).abs() < 1e-15);
        // Slope continuity across the blend boundary |a - b| = k.
        let k = 0.2;
        let f = |x: f64| smin(x, 0.0, k);
        let d = 1e-7;
        let slope = |x: f64| (f(x + d) - f(x - d)) / (2.0 * d);
        assert!((slope(k - 1e-5) - slope(k + 1e-5)).abs() < 1e-3);
    }

    /// The fast wrap is the exact remainder's to within two ulp of the angle (and of pi),
    /// on either side of the half-turn, for angles up to 1e9 rad and negative ones, and lies
    /// in [-pi, pi].
    #[test]
    fn wrap_matches_the_exact_remainder() {
        let mut worst = 0.0f64;
        for i in 0..200_000 {
            let x = i as f64 / 200_000.0;
            for a in [
                (x - 0.5) * 40.0,
                x * x * x * 1e9,
                -x * 3e5 - 0.1,
                PI * (2 * i + 1) as f64,
            ] {
                let (fast, exact) = (wrap(a), wrap_exact(a));
                assert!((-PI..=PI).contains(&fast), "{a}: {fast}");
                // At the half-turn the two may pick opposite ends.
                let d = fast - exact;
                let d = d.abs().min((d - 2.0 * PI).abs()).min((d + 2.0 * PI).abs());
                let ulp = f64::EPSILON * a.abs().max(PI);
                assert!(d <= 2.0 * ulp, "{a}: {fast} vs {exact}");
                worst = worst.max(d / ulp);
            }
        }
        assert!(worst > 0.0);
        assert!(wrap(f64::NAN).is_nan());
        assert_eq!(wrap(1e15), wrap_exact(1e15));
    }

    /// Wherever `reaches` says no, the loss is an exact zero, for either race, around the
    /// whole circumference and at the pit's edges; it says yes over the pit.
    #[test]
    fn a_pit_not_reached_loses_nothing() {
        let (r, arc) = (4.25e-3, 27.25e-3);
        let half = 0.5e-3 / arc;
        for site in [DefectSite::Outer, DefectSite::Inner] {
            let d = Defect::new(site, 4.7, 1.0e-3, 20e-6, r, arc);
            let (mut yes, mut no) = (0, 0);
            for i in 0..200_000 {
                let psi = -20.0 + 40.0 * i as f64 / 200_000.0;
                for theta_s in [0.0, 1.3, -250.0] {
                    // The quick test answers as the exact one.
                    let sc = psi.sin_cos();
                    assert_eq!(
                        d.reaches_sc(0, psi, sc, theta_s),
                        d.reaches(0, psi, theta_s)
                    );
                    if d.reaches(0, psi, theta_s) {
                        yes += 1;
                    } else {
                        no += 1;
                        assert_eq!(d.loss(0, psi, theta_s, 0.7).to_bits(), 0, "{psi}");
                    }
                }
            }
            assert!(yes > 0 && no > yes, "{yes} {no}");
            let centre = match site {
                DefectSite::Inner => 4.7 + 1.3,
                _ => 4.7,
            };
            for psi in [centre, centre + 0.99 * half, centre - 0.99 * half] {
                assert!(d.reaches(3, psi, 1.3) && d.loss(3, psi, 1.3, 0.0) > 0.0);
            }
            for psi in [centre + half * (1.0 + 1e-9), centre - half * (1.0 + 1e-9)] {
                assert!(!d.reaches(3, psi, 1.3));
            }
        }
        // The quick test: never out where the pit reaches, out over most of the turn, for
        // a 1 mm pit and a 1 µm one (whose half-angle, 1.8e-5 rad, is near the margin's
        // µrad), at azimuths near zero and near 1e5 rad.
        for width in [1.0e-3, 1.0e-6] {
            let d = Defect::new(DefectSite::Outer, 4.7, width, 1e-7, r, arc);
            let half = 0.5 * width / arc;
            let mut out = 0;
            for turn in [0.0, 15_915.0] {
                for i in -20_000..20_000 {
                    let psi = 4.7 + turn * 2.0 * PI + i as f64 * 1.5 * half / 20_000.0;
                    let sc = psi.sin_cos();
                    assert!(!d.well_outside(psi, sc) || !d.reaches(0, psi, 0.0), "{psi}");
                    let far = psi + 0.1 + 6.0 * i as f64 / 20_000.0;
                    out += usize::from(d.well_outside(far, far.sin_cos()));
                }
            }
            assert!(out > 70_000, "{width}: {out}");
        }
        let b = Defect::new(DefectSite::Ball(2), 0.0, 1.0e-3, 20e-6, r, r);
        assert!(b.reaches_sc(2, 0.3, 0.3f64.sin_cos(), 0.0));
        assert!(!b.reaches_sc(1, 0.3, 0.3f64.sin_cos(), 0.0));
        assert!(b.reaches(2, 0.3, 0.0) && !b.reaches(1, 0.3, 0.0));
        assert_eq!(b.loss(1, 0.3, 0.0, 0.0), 0.0);
        assert!(Defect::new(DefectSite::Outer, 0.0, 1e-3, 1e-5, r, arc).reaches(0, f64::NAN, 0.0));
    }

    #[test]
    fn sagitta_is_exact() {
        let (r, d) = (3.97e-3, 0.5e-3);
        assert!((sagitta(r, d) - (r - (r * r - d * d).sqrt())).abs() < 1e-18);
    }
}
