//! Waviness and ball-spacing scatter (docs/physics.md §5.4; study \[3\], Wang et al.; the
//! harmonic description of Wardle, *Proc. IMechE C* 202 (1988) and Harsha, *J. Sound Vib.*
//! 290 (2006)).
//!
//! A race or ball radius deviation `w(theta) = sum_k A_k sin(k theta + beta_k)` whose
//! interference adds to the ball's deflection `delta_j`:
//! - outer race, fixed: `theta = psi_j`;
//! - inner race, turning with the shaft: `theta = psi_j - theta_s`;
//! - ball, spinning by `phi` relative to the cage: the ball meets the outer race at spin
//!   angle `phi` and the inner race at `phi + pi`, so its diameter deviation
//!   `w(phi) + w(phi + pi)` enters (odd orders cancel, as they must).
//!
//! The optional ball-spacing scatter moves each ball's azimuth by a fixed, seeded random
//! fraction of its pocket play (study \[3\]); it is scene data, not state, so runs repeat.

/// Which element is wavy.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WavySite {
    /// Outer race.
    Outer,
    /// Inner race.
    Inner,
    /// One ball (0-based index), or every ball when `None`.
    Ball(Option<usize>),
}

/// One harmonic of waviness (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Harmonic {
    /// Element.
    pub site: WavySite,
    /// Order `k` (lobes per circumference).
    pub order: u32,
    /// Amplitude `A_k`, m.
    pub amplitude: f64,
    /// Phase `beta_k`, rad.
    pub phase: f64,
}

impl Harmonic {
    #[inline]
    fn w(&self, theta: f64) -> f64 {
        self.amplitude * (self.order as f64 * theta + self.phase).sin()
    }

    /// Interference this harmonic adds to ball `j` at azimuth `psi`, shaft angle `theta_s`,
    /// ball spin angle `phi` (rad).
    #[inline]
    pub fn interference(&self, j: usize, psi: f64, theta_s: f64, phi: f64) -> f64 {
        match self.site {
            WavySite::Outer => self.w(psi),
            WavySite::Inner => self.w(psi - theta_s),
            WavySite::Ball(b) => {
                if b.is_some_and(|b| b != j) {
                    0.0
                } else {
                    self.w(phi) + self.w(phi + std::f64::consts::PI)
                }
            }
        }
    }
}

/// SplitMix64 (Steele, Lea & Flood, *OOPSLA* 2014): a tiny, well-mixed seeded generator.
#[derive(Debug, Clone)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)` (53 random bits).
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// Azimuth offsets (rad) of `z` balls: each uniform in `±scatter * c_p / dm`, i.e. a
/// fraction `scatter` of the play `±c_p/2` a ball has in its pocket (diametral pocket
/// clearance `c_p`) along the pitch circle of diameter `dm`. Same seed, same offsets.
pub fn spacing_offsets(
    z: usize,
    scatter: f64,
    pocket_clearance: f64,
    dm: f64,
    seed: u64,
) -> Vec<f64> {
    let mut g = SplitMix64(seed);
    let half = scatter * pocket_clearance / dm;
    (0..z).map(|_| half * (2.0 * g.next_f64() - 1.0)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix_reference_values() {
        // Reference outputs for seed 1234567 (Rosetta Code, "Pseudo-random numbers/Splitmix64").
        let mut g = SplitMix64(1234567);
        assert_eq!(g.next_u64(), 6457827717110365317);
        assert_eq!(g.next_u64(), 3203168211198807973);
    }

    #[test]
    fn odd_ball_orders_cancel() {
        let h = Harmonic {
            site: WavySite::Ball(None),
            order: 3,
            amplitude: 1e-6,
            phase: 0.3,
        };
        for phi in [0.0, 0.7, 2.0] {
            assert!(h.interference(0, 0.0, 0.0, phi).abs() < 1e-20);
        }
        let h2 = Harmonic { order: 2, ..h };
        assert!((h2.interference(4, 1.0, 2.0, 0.1) - 2e-6 * (0.2f64 + 0.3).sin()).abs() < 1e-18);
    }

    #[test]
    fn spacing_repeats_and_stays_in_the_pocket() {
        let a = spacing_offsets(9, 0.8, 0.16e-3, 39.04e-3, 42);
        let b = spacing_offsets(9, 0.8, 0.16e-3, 39.04e-3, 42);
        let c = spacing_offsets(9, 0.8, 0.16e-3, 39.04e-3, 43);
        assert_eq!(a, b);
        assert_ne!(a, c);
        let lim = 0.8 * 0.16e-3 / 39.04e-3;
        assert!(a.iter().all(|x| x.abs() <= lim));
        assert!(a.iter().any(|x| x.abs() > 0.1 * lim));
    }
}
