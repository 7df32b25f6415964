//! Outer-race wear from the skidding dynamics (study \[2\], docs/physics.md §7): the wear law of
//! [`crate::models::wear`] fed with what the skidding level resolves per ball — the
//! outer-contact load, the slip speed `u_s = |dv_o|` of the ball over the race and the
//! rolling speed — as study \[2\] feeds its dynamic model's slip ("considering clearance,
//! friction and slip") into Archard's law. The ring level, which has no skidding, keeps
//! its kinematic-slip estimate (`crate::models::wear::heathcote_slip`).
//!
//! Per contact: `La` from the shared asperity share ([`crate::lubrication::asperity`]) and
//! the flash temperature `dT` from study \[2\]'s friction law (the `mixed_ehl` traction
//! law, [`crate::contact::traction::MixedEhl::evaluate`]) at this slip and rolling speed;
//! the film-defect fraction `psi` at the surface temperature `T0 + dT`; the wear area rate
//! `K psi (La/100) u_s (3Q/(4a)) / Hv` (the depth rate integrated over the ball's pass,
//! see `crate::models::wear`) deposited at the ball's azimuth on the circumferential map.
//! Dry is the limit `La = 100`, `psi = 1`. The profile acts back through
//! [`crate::models::skidding::SkiddingParams::outer_wear`]; the cycles (run, extrapolate,
//! update, run again) are driven by [`crate::wear_cycles`].

use super::skidding::SkiddingModel;
use super::wear::{self, FilmDefect, WearLaw};
use crate::contact::traction::{ContactState, FlashTemperature, MixedEhl};
use crate::lubrication::asperity::AsperityReading;
use crate::lubrication::Lubricant;

/// The wear of one outer contact at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactWear {
    /// Asperity load share, per cent.
    pub la: f64,
    /// Film-defect fraction.
    pub psi: f64,
    /// Flash temperature rise, K.
    pub flash: f64,
    /// Sliding speed, m/s.
    pub us: f64,
    /// Wear area rate (depth times race length per time), m²/s.
    pub area_rate: f64,
}

/// Outer-race wear law of the skidding level.
#[derive(Debug, Clone, PartialEq)]
pub struct OuterRaceWear {
    /// Archard law, hardness, film-defect constants and the inlet (bulk) temperature `T0`
    /// (`surface_temperature`, K); `film = None` is the dry limit.
    pub law: WearLaw,
    /// Reading of the asperity share's restored roughness term.
    pub reading: AsperityReading,
    /// Limiting-shear coefficient of the friction law (study \[2\]: 0.04).
    pub lambda_lim: f64,
    /// Boundary friction coefficient of the asperities.
    pub f_c: f64,
}

impl OuterRaceWear {
    /// Study \[2\]'s wear data (docs/physics.md §10): `K = 5e-4`, `Hv = 2.39 GPa`, its oil with
    /// composite roughness `sigma` (m; `None`: dry), `a_x = t0 = 3e-12`, `Ea = 49 kJ/mol`,
    /// inlet temperature 293.15 K, limiting shear 0.04 and the traction law's default `f_c`.
    pub fn study2(sigma: Option<f64>, reading: AsperityReading) -> Self {
        OuterRaceWear {
            law: WearLaw {
                k: 5e-4,
                hardness: 2.39e9,
                film: sigma.map(|s| FilmDefect {
                    lubricant: Lubricant {
                        roughness: s,
                        ..Lubricant::study2()
                    },
                    ax: 3e-12,
                    t0: 3e-12,
                    ea: 49e3,
                }),
                surface_temperature: 293.15,
            },
            reading,
            lambda_lim: 0.04,
            f_c: MixedEhl::default().f_c,
        }
    }

    /// The friction law whose flash temperature and asperity share the wear uses.
    pub fn friction(&self) -> Option<MixedEhl> {
        let f = self.law.film.as_ref()?;
        let l = &f.lubricant;
        Some(MixedEhl {
            viscosity: l.viscosity,
            alpha_p: l.pressure_viscosity,
            lambda_lim: self.lambda_lim,
            f_c: self.f_c,
            roughness: l.roughness,
            hardness: self.law.hardness,
            reading: self.reading,
            flash: FlashTemperature {
                beta: l.viscosity_temperature,
                ..FlashTemperature::default()
            },
            ..MixedEhl::default()
        })
    }

    /// Wear of a contact `c` with slip `dv` and rolling speed `u` (m/s).
    pub fn contact(&self, c: &ContactState, dv: f64, u: f64) -> ContactWear {
        if c.q <= 0.0 {
            return ContactWear::default();
        }
        let us = dv.abs();
        let (la, psi, flash) = match (&self.law.film, self.friction()) {
            (Some(f), Some(m)) => {
                let e = m.evaluate(dv, u, c);
                let ts = self.law.surface_temperature + e.flash;
                (
                    e.la,
                    wear::film_defect_fraction(us, f.ax, f.t0, f.ea, ts),
                    e.flash,
                )
            }
            _ => (100.0, 1.0, 0.0),
        };
        ContactWear {
            la,
            psi,
            flash,
            us,
            area_rate: self.law.area_rate(c.q, c.a, us, la, psi),
        }
    }

    /// Add every ball's wear rate at the skidding model's last evaluation to `rates`
    /// (depth rate per cell, m/s; cells of length `cell_len`), weighted by `dt` (s): the
    /// map then holds depth. Also tallies each loaded ball's `La` and outer load at its
    /// nearest cell in `tally`. Returns the largest outer load, N.
    pub fn deposit(
        &self,
        m: &SkiddingModel,
        dt: f64,
        map: &mut [f64],
        cell_len: f64,
        tally: &mut ShareTally,
    ) -> f64 {
        let n = map.len();
        let mut q_max: f64 = 0.0;
        for j in 0..m.z() {
            let (c, dv, u) = m.outer_contact(j);
            if c.q <= 0.0 {
                continue;
            }
            q_max = q_max.max(c.q);
            let w = self.contact(&c, dv, u);
            let psi = m.balls[j].psi;
            wear::deposit(map, psi, w.area_rate * dt, cell_len);
            let k = ((psi.rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU * n as f64)
                .round() as usize)
                % n;
            tally.add(k, w.la, c.q);
        }
        q_max
    }
}

/// Per-cell sums of the asperity share and the outer load of the balls that passed a cell
/// loaded (`q > 0`), and their count.
#[derive(Debug, Clone, Default)]
pub struct ShareTally {
    /// Sum of `La`, per cent.
    pub la: Vec<f64>,
    /// Sum of the outer load, N.
    pub q: Vec<f64>,
    /// Number of samples.
    pub n: Vec<f64>,
}

impl ShareTally {
    /// Empty tally over `cells` cells.
    pub fn new(cells: usize) -> Self {
        ShareTally {
            la: vec![0.0; cells],
            q: vec![0.0; cells],
            n: vec![0.0; cells],
        }
    }

    fn add(&mut self, k: usize, la: f64, q: f64) {
        self.la[k] += la;
        self.q[k] += q;
        self.n[k] += 1.0;
    }

    /// Mean `La` (%) and mean load (N) per cell; NaN where no loaded ball passed.
    pub fn means(&self) -> (Vec<f64>, Vec<f64>) {
        let mean = |s: &[f64]| -> Vec<f64> {
            s.iter()
                .zip(&self.n)
                .map(|(s, n)| if *n > 0.0 { s / n } else { f64::NAN })
                .collect()
        };
        (mean(&self.la), mean(&self.q))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(sigma: Option<f64>) -> OuterRaceWear {
        OuterRaceWear::study2(sigma, AsperityReading::default())
    }

    fn contact() -> ContactState {
        ContactState {
            q: 180.0,
            a: 1.3e-3,
            b: 0.17e-3,
            rx: 5.93e-3,
            kappa: 8.0,
            e_eff: 2.28e11,
        }
    }

    /// A uniform load sampled as the window samples it (balls at a constant orbital speed,
    /// one deposit per output step, hat weights on the cells, normalised per cage
    /// revolution turned) gives a flat map: the binning and the sampling add no pattern of
    /// their own, at the study's step and cell count and at others.
    #[test]
    fn uniform_load_gives_a_flat_map() {
        use std::f64::consts::TAU;
        for (h, n) in [(1e-4, 360), (5e-5, 360), (1e-4, 720), (1e-4, 257)] {
            let (z, w_c, rate) = (14, 90.15, 1e-12);
            let cell_len = TAU * 0.04 / n as f64;
            let mut map = vec![0.0; n];
            let (mut turned, mut t) = (0.0, 0.0);
            while turned < 2.0 * TAU {
                t += h;
                turned += w_c * h;
                for j in 0..z {
                    let psi = w_c * t + TAU * j as f64 / z as f64;
                    wear::deposit(&mut map, psi, rate * h, cell_len);
                }
            }
            let per_rev: Vec<f64> = map.iter().map(|d| d / (turned / TAU)).collect();
            let want = z as f64 * rate * TAU / (n as f64 * w_c * cell_len);
            for (k, d) in per_rev.iter().enumerate() {
                assert!(
                    (d / want - 1.0).abs() < 0.01,
                    "h {h}, {n} cells: cell {k} has {d:e}, uniform {want:e}"
                );
            }
        }
    }

    /// Dry is Archard's law with `La = 100`, `psi = 1`; no slip, no wear; a lubricated
    /// contact wears less, and a rougher one more than a smoother one; the flash
    /// temperature raises the film-defect fraction.
    #[test]
    fn dry_limit_and_ordering() {
        let c = contact();
        let dry = law(None).contact(&c, 0.02, 4.0);
        let want = 5e-4 * 0.02 * 0.75 * c.q / c.a / 2.39e9;
        assert_eq!((dry.la, dry.psi), (100.0, 1.0));
        assert!((dry.area_rate - want).abs() < 1e-15 * want);
        assert_eq!(law(None).contact(&c, 0.0, 4.0).area_rate, 0.0);
        let smooth = law(Some(0.2e-6)).contact(&c, 0.02, 4.0);
        let rough = law(Some(0.42e-6)).contact(&c, 0.02, 4.0);
        assert!(0.0 < smooth.area_rate && smooth.area_rate < rough.area_rate);
        assert!(rough.area_rate < dry.area_rate);
        assert!(smooth.flash > 0.0);
        let cold = wear::film_defect_fraction(0.02, 3e-12, 3e-12, 49e3, 293.15);
        assert!(smooth.psi > cold, "{} vs {cold}", smooth.psi);
    }
}
