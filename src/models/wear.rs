//! Race wear (docs/physics.md §7, study \[2\]: Cao et al., 6012): Archard's law with the
//! lubrication-aware factors of study \[2\],
//!
//! `dh/dt = K psi (La/100) p u_s / Hv`,
//!
//! accumulated on a circumferential map of each race and fed back into the clearance.
//!
//! - `K` dimensionless wear coefficient, `Hv` hardness (study \[2\]: 5e-4 dry, 2.39 GPa).
//! - `psi = 1 - exp(-(a_x / (u_s t0)) exp(-Ea / (Rg Ts)))`, the film-defect fraction of
//!   Stolarski's adsorption model as study \[2\] uses it (`a_x = 3e-12 m`, `t0 = 3e-12 s`,
//!   `Ea = 49 kJ/mol`, `Rg = 8.31 J/(mol K)`).
//! - `La` the asperity load share in percent: the crate's one asperity-share function,
//!   [`crate::lubrication::asperity`] (study \[2\]'s eq. (8), Masjedi & Khonsari's
//!   point-contact regression, its lost roughness term restored as documented there),
//!   from the contact's load, rolling speed, radius, modulus, the oil, the composite
//!   roughness and the hardness `Hv`. The dry limit is `La = 100`, `psi = 1`.
//!
//! Per ball contact the map receives a wear *area* rate (depth times race length per unit
//! time): a race point under the contact centre line sees `int p dt = (int p dx) / v_pass`
//! with `int p dx = p0 pi b / 2 = 3Q/(4a)` for the Hertz ellipse (`b` along rolling), and
//! is swept at `v_pass`, so the area rate is `K psi (La/100) u_s (3Q/(4a)) / Hv`,
//! independent of the passing speed. It is spread on the two nearest cells with linear
//! (hat) weights, which conserves it and keeps the rate continuous in the ball angle.
//!
//! Sliding speed [`heathcote_slip`]: the differential (Heathcote) slip of a ball in a
//! conforming groove (Harris & Kotzalas, *Essential Concepts*, ch. "Friction"; Johnson,
//! *Contact Mechanics* §8.5): the contact surface is curved with radius
//! `R_c = 2 f D / (2f + 1)`, so across the contact width the ball and race surface speeds
//! differ by `omega_rel y² / (2 R_c)` plus a constant; free rolling puts the two rolling
//! lines where the net Coulomb traction vanishes, `y0 = s0 a` with
//! `s0 - s0³/3 = 1/3`, i.e. `s0 = 2 cos 80° = 0.3473`. The wear uses the line-load-weighted
//! mean slip `u_s = omega_rel a² m / (2 R_c)`, `m = int |s² - s0²| (1 - s²) ds / (4/3)`.
//! `omega_rel` is the ball's rotation relative to the race (`|omega_b| - omega_c` at the
//! outer race, `|omega_b| + omega - omega_c` at the inner). **This is the ring level's
//! kinematic-slip estimate**: the ring level has massless balls at the kinematic cage
//! speed, so it has no skidding slip of its own. The skidding level's wear
//! ([`crate::models::wear_map`]) uses the per-ball slip speeds of the dynamics instead, as
//! study \[2\] does.

use crate::contact::PointContact;
use crate::lubrication::asperity::{self, AsperityReading, Groups, ShareAt};
use crate::lubrication::Lubricant;

/// Universal gas constant used by study \[2\], J/(mol K).
pub const RG: f64 = 8.31;

/// Lubricated wear: the lubricant and the film-defect constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmDefect {
    /// Lubricant (film thickness and composite roughness).
    pub lubricant: Lubricant,
    /// `a_x`, m.
    pub ax: f64,
    /// `t0`, s.
    pub t0: f64,
    /// Activation energy `Ea`, J/mol.
    pub ea: f64,
}

/// Archard wear law of one bearing (both races).
#[derive(Debug, Clone, PartialEq)]
pub struct WearLaw {
    /// Dimensionless wear coefficient `K`.
    pub k: f64,
    /// Hardness `Hv`, Pa.
    pub hardness: f64,
    /// Film (None: dry limit `La = 100`, `psi = 1`).
    pub film: Option<FilmDefect>,
    /// Surface temperature `Ts` without the thermal model, K.
    pub surface_temperature: f64,
}

/// Mean Heathcote slip factor `m` for rolling lines at `s0 = 2 cos 80°`.
pub fn heathcote_mean_factor() -> f64 {
    let s0 = 2.0 * 80f64.to_radians().cos();
    // Exact polynomial integral of |s² - s0²| (1 - s²) over [-1, 1], divided by 4/3.
    let f = |s: f64| s0 * s0 * s - s.powi(3) / 3.0 * (1.0 + s0 * s0) + s.powi(5) / 5.0;
    // (s0² - s²)(1 - s²) = s0² - s² (1 + s0²) + s⁴, antiderivative f.
    let inner = f(s0) - f(0.0);
    let outer = -(f(1.0) - f(s0));
    2.0 * (inner + outer) / (4.0 / 3.0)
}

/// Rolling-line position `s0` (fraction of the semi-axis `a`) of free Heathcote rolling:
/// the root of `s³ - 3 s + 1 = 0` in (0, 1).
pub fn heathcote_rolling_line() -> f64 {
    2.0 * 80f64.to_radians().cos()
}

/// Differential (Heathcote) sliding speed of a contact with transverse semi-axis `a`, in a
/// groove of conformity `f` for a ball of diameter `d`, the ball turning at `omega_rel`
/// relative to the race, m/s (see the module notes; `m` from [`heathcote_mean_factor`]).
#[inline]
pub fn heathcote_slip(omega_rel: f64, a: f64, f: f64, d: f64, m: f64) -> f64 {
    let rc = 2.0 * f * d / (2.0 * f + 1.0);
    omega_rel.abs() * a * a * m / (2.0 * rc)
}

/// Film-defect fraction `psi` (study \[2\]); 1 at zero sliding.
#[inline]
pub fn film_defect_fraction(us: f64, ax: f64, t0: f64, ea: f64, ts: f64) -> f64 {
    film_defect_with(us, ax, t0, (-ea / (RG * ts)).exp())
}

/// [`film_defect_fraction`] with its Arrhenius factor `exp(-Ea/(R Ts))` given.
#[inline]
fn film_defect_with(us: f64, ax: f64, t0: f64, arrhenius: f64) -> f64 {
    if us <= 0.0 {
        return 1.0;
    }
    let x = ax / (us * t0) * arrhenius;
    -(-x).exp_m1()
}

/// [`WearLaw::factors`] of one contact at one entrainment speed and surface temperature,
/// with what does not depend on the load and the sliding computed once
/// ([`WearLaw::prepare`]): the asperity share's logarithms ([`ShareAt`]) and the film
/// defect's Arrhenius factor. The same bits as `factors` (which is this, prepared afresh).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FactorsAt {
    /// `None`: the dry limit (La = 100, psi = 1).
    film: Option<FilmFactorsAt>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct FilmFactorsAt {
    share: ShareAt,
    /// `E' Rx²` (the load group is `W = Q / (E' Rx²)`, as in [`Groups::new`]).
    w_den: f64,
    ax: f64,
    t0: f64,
    arrhenius: f64,
}

impl FactorsAt {
    /// `(La, psi)` at load `q` and sliding `us`.
    #[inline]
    pub fn factors(&self, q: f64, us: f64) -> (f64, f64) {
        match &self.film {
            None => (100.0, 1.0),
            Some(f) => (
                f.share.share(q / f.w_den),
                film_defect_with(us, f.ax, f.t0, f.arrhenius),
            ),
        }
    }
}

impl WearLaw {
    /// Wear-depth rate at a point of pressure `p` under sliding `us`, with asperity share
    /// `la` (percent) and film-defect fraction `psi`: `K psi (La/100) p us / Hv`, m/s.
    #[inline]
    pub fn depth_rate(&self, p: f64, us: f64, la: f64, psi: f64) -> f64 {
        self.k * psi * 0.01 * la * p * us / self.hardness
    }

    /// `(La, psi)` of a contact carrying `q` with entrainment speed `u`, sliding `us`,
    /// surface temperature `ts` (the asperity share's default reading).
    #[inline]
    pub fn factors(&self, c: &PointContact, q: f64, u: f64, us: f64, ts: f64) -> (f64, f64) {
        self.factors_read(c, q, u, us, ts, AsperityReading::default())
    }

    /// [`Self::factors`] with a chosen reading of the asperity share's roughness term.
    #[inline]
    pub fn factors_read(
        &self,
        c: &PointContact,
        q: f64,
        u: f64,
        us: f64,
        ts: f64,
        reading: AsperityReading,
    ) -> (f64, f64) {
        self.prepare_read(c, u, ts, reading).factors(q, us)
    }

    /// [`Self::factors`]' load- and sliding-free part at entrainment speed `u` and surface
    /// temperature `ts` (the default reading).
    #[inline]
    pub fn prepare(&self, c: &PointContact, u: f64, ts: f64) -> FactorsAt {
        self.prepare_read(c, u, ts, AsperityReading::default())
    }

    /// [`Self::prepare`] with a chosen reading.
    #[inline]
    pub fn prepare_read(
        &self,
        c: &PointContact,
        u: f64,
        ts: f64,
        reading: AsperityReading,
    ) -> FactorsAt {
        FactorsAt {
            film: self.film.as_ref().map(|f| {
                let l = &f.lubricant;
                // The groups without a load (`w` unused by `ShareAt`).
                let g = Groups::new(&asperity::Contact {
                    q: 0.0,
                    u,
                    rx: c.curvature.rx,
                    e_eff: c.e_eff,
                    eta0: l.viscosity,
                    alpha_p: l.pressure_viscosity,
                    sigma: l.roughness,
                    h: self.hardness,
                    kappa: c.ellipse.kappa,
                    // Only the line-contact reading uses the semi-axis (a cube root saved).
                    ca: if reading == AsperityReading::LineContact {
                        c.semi_axis_coefficients().0
                    } else {
                        0.0
                    },
                });
                let (rx, e_eff) = (c.curvature.rx, c.e_eff);
                FilmFactorsAt {
                    share: ShareAt::new(&g, reading),
                    w_den: e_eff * rx * rx,
                    ax: f.ax,
                    t0: f.t0,
                    arrhenius: (-f.ea / (RG * ts)).exp(),
                }
            }),
        }
    }

    /// Wear area rate of one contact (depth times race length per time, m²/s): load `q`,
    /// transverse semi-axis `a`, sliding `us`, factors `la`, `psi` (module notes).
    #[inline]
    pub fn area_rate(&self, q: f64, a: f64, us: f64, la: f64, psi: f64) -> f64 {
        if q <= 0.0 || a <= 0.0 {
            return 0.0;
        }
        self.depth_rate(0.75 * q / a, us, la, psi)
    }
}

/// `theta` (rad) in cells of a periodic map of `n` cells, in [0, n]: the fraction of a
/// turn (`theta / 2 pi` less its floor) times `n`. Within a few ulp of `theta / 2 pi` times
/// `n` of the exact remainder's `rem_euclid(2 pi) / 2 pi n` (test
/// `cell_coordinate_matches_rem_euclid`), at a fraction of `fmod`'s cost; NaN stays NaN.
#[inline]
fn cell_coordinate(theta: f64, n: usize) -> f64 {
    let turns = theta * (1.0 / std::f64::consts::TAU);
    // The floor by the 1.5 x 2^52 shift (nearest whole number, exact for |x| < 2^51, less
    // one if above): `floor` is a libm call on the baseline x86-64 target. `floor` itself
    // beyond 2^51 turns and for NaN.
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let whole = if turns.abs() < 2_251_799_813_685_248.0 {
        let r = (turns + SHIFT) - SHIFT;
        if r > turns {
            r - 1.0
        } else {
            r
        }
    } else {
        turns.floor()
    };
    (turns - whole) * n as f64
}

/// Add `area_rate` (m²/s) at angle `theta` (rad) to a periodic map of `n = map.len()` cells
/// of length `cell_len` (m), hat-weighted on the two nearest cell centres (cell `k` centred
/// at `2 pi k / n`): the sum of `map * cell_len` grows by exactly `area_rate`.
#[inline]
pub fn deposit(map: &mut [f64], theta: f64, area_rate: f64, cell_len: f64) {
    let n = map.len();
    if n == 0 || area_rate == 0.0 {
        return;
    }
    let u = cell_coordinate(theta, n);
    // u is in [0, n] (or NaN): the truncating cast is its floor (NaN -> 0 as
    // `floor`'s NaN cast), without `floor`'s libm call.
    let k = (u as usize).min(n - 1);
    let w = (u - k as f64).clamp(0.0, 1.0);
    let r = area_rate / cell_len;
    map[k] += (1.0 - w) * r;
    map[(k + 1) % n] += w * r;
}

/// Depth of a periodic map at angle `theta` (linear interpolation between cell centres).
#[inline]
pub fn sample(map: &[f64], theta: f64) -> f64 {
    let n = map.len();
    if n == 0 {
        return 0.0;
    }
    let u = cell_coordinate(theta, n);
    // The floor of u in [0, n] by the cast, as in `deposit`.
    let k = (u as usize).min(n - 1);
    let w = (u - k as f64).clamp(0.0, 1.0);
    (1.0 - w) * map[k] + w * map[(k + 1) % n]
}

/// Deepest cell of a map: `(depth, angle of its centre in rad)`.
pub fn deepest(map: &[f64]) -> (f64, f64) {
    let n = map.len().max(1);
    map.iter().enumerate().fold((0.0, 0.0), |(d, a), (k, &v)| {
        if v > d {
            (v, std::f64::consts::TAU * k as f64 / n as f64)
        } else {
            (d, a)
        }
    })
}

/// Revolutions to reach `depth` given the deepest point after each cycle:
/// `history = [(revolutions, max depth)]` in order; linear interpolation inside the
/// history, linear extrapolation from the last cycle's rate beyond it; None if no wear.
pub fn revolutions_to(history: &[(f64, f64)], depth: f64) -> Option<f64> {
    let mut prev = (0.0, 0.0);
    for &(r, d) in history {
        if d >= depth {
            let f = (depth - prev.1) / (d - prev.1);
            return Some(prev.0 + f * (r - prev.0));
        }
        prev = (r, d);
    }
    let (&(r1, d1), rest) = history.split_last()?;
    let (r0, d0) = rest.last().copied().unwrap_or((0.0, 0.0));
    let rate = (d1 - d0) / (r1 - r0);
    (rate > 0.0).then(|| r1 + (depth - d1) / rate)
}

/// Close a wear window (docs/physics.md §7's time-scale separation): once the shaft has turned
/// `window` revolutions since the window began (`revs` is the turn now), the depth
/// accumulated in the window is scaled to a cycle of `cycle` revolutions and added to the
/// maps, at most `cycles` times. `acc` holds the depths accumulated since the start (one
/// value per cell, every race's cells in a row); `mem` the maps (as `acc`), the
/// accumulators at the window's start (as `acc`), the window's start (revolutions) and the
/// cycles done. Returns whether a window closed.
pub fn close_window(
    acc: &[f64],
    mem: &mut [f64],
    revs: f64,
    window: f64,
    cycle: f64,
    cycles: f64,
) -> bool {
    let n = acc.len();
    let (start, done) = (mem[2 * n], mem[2 * n + 1]);
    if done >= cycles || revs - start < window * (1.0 - 1e-9) {
        return false;
    }
    let scale = cycle / (revs - start);
    let (maps, rest) = mem.split_at_mut(n);
    let (snap, tail) = rest.split_at_mut(n);
    for ((m, s), a) in maps.iter_mut().zip(snap.iter()).zip(acc) {
        *m += (a - s) * scale;
    }
    snap.copy_from_slice(acc);
    tail[0] = revs;
    tail[1] = done + 1.0;
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A window closes only once complete, adds the window's depth scaled by cycle/window
    /// exactly (linear in the accumulators), and stops after the cycle count.
    #[test]
    fn wear_window_scales_to_the_cycle_and_stops_after_the_cycles() {
        let acc = [1e-9, 2e-9, 0.0, 4e-9];
        let mut mem = [0.0; 10];
        assert!(!close_window(&acc, &mut mem, 0.999, 1.0, 1e6, 2.0));
        assert_eq!(mem, [0.0; 10]);
        assert!(close_window(&acc, &mut mem, 2.0, 1.0, 1e6, 2.0));
        for c in 0..4 {
            assert!((mem[c] - acc[c] * 0.5e6).abs() <= 1e-12 * acc[c] * 0.5e6);
            assert_eq!(mem[4 + c], acc[c]);
        }
        assert_eq!((mem[8], mem[9]), (2.0, 1.0));
        let acc2 = acc.map(|a| 3.0 * a);
        assert!(close_window(&acc2, &mut mem, 3.0, 1.0, 1e6, 2.0));
        assert!((mem[1] - (2e-9 * 0.5e6 + 4e-9 * 1e6)).abs() < 1e-15);
        assert!(
            !close_window(&acc2, &mut mem, 9.0, 1.0, 1e6, 2.0),
            "two cycles done"
        );
    }

    #[test]
    fn rolling_line_root_and_mean_factor() {
        let s0 = heathcote_rolling_line();
        assert!((s0.powi(3) - 3.0 * s0 + 1.0).abs() < 1e-14);
        // Midpoint check of the closed form.
        let n = 200_000;
        let mut acc = 0.0;
        for i in 0..n {
            let s = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
            acc += (s * s - s0 * s0).abs() * (1.0 - s * s) * 2.0 / n as f64;
        }
        assert!((acc / (4.0 / 3.0) - heathcote_mean_factor()).abs() < 1e-8);
    }

    #[test]
    fn limits_of_the_factors() {
        assert_eq!(film_defect_fraction(0.0, 3e-12, 3e-12, 49e3, 293.15), 1.0);
        let p = film_defect_fraction(0.02, 3e-12, 3e-12, 49e3, 293.15);
        assert!(p > 0.0 && p < 1e-6, "{p}");
    }

    /// Dry is the limit La = 100, psi = 1; lubricated, La is the shared function and
    /// rises with the roughness.
    #[test]
    fn factors_dry_and_lubricated() {
        use crate::contact::{Curvature, Race};
        let c = PointContact::new(
            Curvature::ball_race(10.45e-3, 77.6e-3, 0.0, 0.52, Race::Outer),
            2.28e11,
        );
        let law = |sigma: f64| WearLaw {
            k: 5e-4,
            hardness: 2.39e9,
            film: Some(FilmDefect {
                lubricant: Lubricant {
                    roughness: sigma,
                    ..Lubricant::study2()
                },
                ax: 3e-12,
                t0: 3e-12,
                ea: 49e3,
            }),
            surface_temperature: 293.15,
        };
        let dry = WearLaw {
            film: None,
            ..law(0.2e-6)
        };
        assert_eq!(dry.factors(&c, 180.0, 4.0, 0.01, 293.15), (100.0, 1.0));
        let (l1, _) = law(0.2e-6).factors(&c, 180.0, 4.0, 0.01, 293.15);
        let (l2, _) = law(0.42e-6).factors(&c, 180.0, 4.0, 0.01, 293.15);
        assert!(0.0 < l1 && l1 < l2 && l2 < 100.0, "{l1} {l2}");
    }

    /// The prepared factors (load-free part once: the asperity share's logarithms, the
    /// Arrhenius factor) are the direct ones bit for bit: the formulas as they stood
    /// before the split (the groups with the load, the printed `La` and `psi`) over loads,
    /// sliding, speeds (beyond the turning point too), temperatures, both readings, and
    /// the limits (no entrainment, no roughness, no sliding, dry).
    #[test]
    fn prepared_factors_are_the_direct_ones_bit_for_bit() {
        use crate::contact::{Curvature, Race};
        // The asperity share as printed before `ShareAt` (module notes of `asperity`).
        let past_turn = std::cell::Cell::new(0usize);
        let share = |g: &Groups, s: f64| -> f64 {
            if g.sigma.is_nan() || g.sigma <= 0.0 {
                return 0.0;
            }
            if g.u.is_nan() || g.u <= 0.0 {
                return 100.0;
            }
            let ln_x1 = (0.689f64).ln() + s * g.sigma.ln() + 0.509 * g.v.ln()
                - 0.501 * g.w.ln()
                - 2.87 * g.g.ln();
            let ln_x = ln_x1 - 2.9 * g.u.ln();
            let ln_xt = crate::lubrication::asperity::x_turn().ln();
            let (ln_x, ln_u, beyond) = if ln_x > ln_xt {
                past_turn.set(past_turn.get() + 1);
                let ln_ut = (ln_x1 - ln_xt) / 2.9;
                (ln_xt, ln_ut, Some(g.u.ln() - ln_ut))
            } else {
                (ln_x, g.u.ln(), None)
            };
            let log_term = if ln_x > 30.0 {
                ln_x
            } else {
                ln_x.exp().ln_1p()
            };
            let la = 10.0 * (-0.083 * g.w.ln() + 0.143 * ln_u + 0.314 * g.g.ln()).exp() * log_term;
            if la.is_nan() {
                return 100.0;
            }
            let la = la.clamp(0.0, 100.0);
            match beyond {
                Some(r) => la + (100.0 - la) * (1.0 - (0.143 * r).exp()),
                None => la,
            }
        };
        let c = PointContact::new(
            Curvature::ball_race(10.45e-3, 77.6e-3, 0.0, 0.52, Race::Inner),
            2.28e11,
        );
        let mut n = 0;
        for sigma in [0.0, 0.2e-6, 0.42e-6, 3e-6] {
            let law = WearLaw {
                k: 5e-4,
                hardness: 2.39e9,
                film: Some(FilmDefect {
                    lubricant: Lubricant {
                        roughness: sigma,
                        ..Lubricant::study2()
                    },
                    ax: 3e-12,
                    t0: 3e-12,
                    ea: 49e3,
                }),
                surface_temperature: 293.15,
            };
            let dry = WearLaw {
                film: None,
                ..law.clone()
            };
            let f = law.film.as_ref().unwrap();
            let l = &f.lubricant;
            for reading in [AsperityReading::FilmParameter, AsperityReading::Quartic] {
                for u in [0.0, 1e-9, 1e-4, 0.3, 4.0, 25.0] {
                    for ts in [293.15, 350.0] {
                        let prep = law.prepare_read(&c, u, ts, reading);
                        assert_eq!(
                            dry.prepare_read(&c, u, ts, reading).factors(1.0, 1.0),
                            (100.0, 1.0)
                        );
                        for q in [0.0, 1e-3, 0.7, 180.0, 2.5e3] {
                            for us in [0.0, 1e-6, 0.01, 0.3] {
                                let g = Groups::new(&asperity::Contact {
                                    q,
                                    u,
                                    rx: c.curvature.rx,
                                    e_eff: c.e_eff,
                                    eta0: l.viscosity,
                                    alpha_p: l.pressure_viscosity,
                                    sigma: l.roughness,
                                    h: law.hardness,
                                    kappa: c.ellipse.kappa,
                                    ca: c.semi_axis_coefficients().0,
                                });
                                let la = share(&g, reading.exponent());
                                let psi = if us <= 0.0 {
                                    1.0
                                } else {
                                    let x = f.ax / (us * f.t0) * (-f.ea / (RG * ts)).exp();
                                    -(-x).exp_m1()
                                };
                                let got = prep.factors(q, us);
                                assert_eq!(
                                    (got.0.to_bits(), got.1.to_bits()),
                                    (la.to_bits(), psi.to_bits()),
                                    "{sigma} {reading:?} {u} {ts} {q} {us}: {got:?} vs {la} {psi}"
                                );
                                let direct = law.factors_read(&c, q, u, us, ts, reading);
                                assert_eq!(direct, got);
                                n += 1;
                            }
                        }
                    }
                }
            }
        }
        // Both sides of the turning point were compared.
        let past = past_turn.get();
        assert!(n == 1920 && past > 100 && past < 1000, "{n} {past}");
    }

    /// The cell coordinate is the exact remainder's to a few ulp of the turn count (times
    /// the cells), modulo a whole map at the seam, for angles of either sign up to 1e7 rad.
    #[test]
    fn cell_coordinate_matches_rem_euclid() {
        use std::f64::consts::TAU;
        let n = 180usize;
        for i in 0..100_000 {
            let x = i as f64 / 100_000.0;
            for theta in [(x - 0.5) * 50.0, x * x * 1e7, -x * 1e5] {
                let exact = theta.rem_euclid(TAU) / TAU * n as f64;
                let fast = cell_coordinate(theta, n);
                assert!((0.0..=n as f64).contains(&fast), "{theta}: {fast}");
                let d = (fast - exact).abs();
                let d = d.min((d - n as f64).abs());
                let tol = 4.0 * f64::EPSILON * (theta.abs() / TAU + 1.0) * n as f64;
                assert!(d <= tol, "{theta}: {fast} vs {exact}");
            }
        }
        // Beyond 2^51 turns `floor` itself; NaN stays NaN.
        for theta in [1e17, -3e16] {
            let turns = theta * (1.0 / TAU);
            assert_eq!(
                cell_coordinate(theta, n),
                (turns - turns.floor()) * n as f64
            );
        }
        assert!(cell_coordinate(f64::NAN, n).is_nan());
    }

    #[test]
    fn cast_floor_cell_matches_floor() {
        // The cell index of `deposit` and `sample` (the cast) is `floor`'s over angles far
        // beyond a turn, both signs, cell boundaries, 2^51 turns and beyond, and NaN.
        let n = 180;
        let tau = std::f64::consts::TAU;
        let mut thetas: Vec<f64> = (0..20_000)
            .map(|i| (i as f64 - 10_000.0) * 0.0123)
            .collect();
        thetas.extend((0..=n).map(|k| tau * k as f64 / n as f64));
        thetas.extend([
            0.0,
            -0.0,
            -1e-300,
            1e-300,
            tau * 2f64.powi(51),
            -tau * 2f64.powi(60),
        ]);
        thetas.extend([f64::NAN, f64::INFINITY, 1e300]);
        for theta in thetas {
            let u = cell_coordinate(theta, n);
            let by_floor = (u.floor() as usize).min(n - 1);
            assert_eq!((u as usize).min(n - 1), by_floor, "{theta} {u}");
        }
    }

    #[test]
    fn deposit_conserves_and_samples() {
        let mut m = vec![0.0; 36];
        deposit(&mut m, 1.234, 2.0, 0.5);
        let s: f64 = m.iter().sum::<f64>() * 0.5;
        assert!((s - 2.0).abs() < 1e-15);
        let mut m = vec![0.0; 4];
        m[1] = 1.0;
        assert!((sample(&m, std::f64::consts::FRAC_PI_4) - 0.5).abs() < 1e-15);
        assert_eq!(revolutions_to(&[(10.0, 1.0), (20.0, 2.0)], 3.0), Some(30.0));
        assert_eq!(revolutions_to(&[(10.0, 1.0), (20.0, 2.0)], 1.5), Some(15.0));
    }
}
