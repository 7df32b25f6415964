//! Wear cycles on the skidding level (study \[2\]'s procedure, its §3.1; docs/physics.md §7):
//! run the dynamics, measure the outer race's wear rate per cage revolution over a window
//! ([`crate::models::wear_map`]), extrapolate it over a cycle of many revolutions, add it
//! to the race profile (which widens the clearance under the balls), run the dynamics
//! again on the worn race, repeat. Wear and vibration evolve together on two time scales.
//!
//! Each cycle starts the component afresh from the scene (the dynamics settle for
//! `settle_s`, then the window is measured), on the profile of the cycles before. The
//! motion is stationary but irregular, and every cycle repeats the same trajectory from
//! the same start (the profile changes by nanometres): cycle `k` of `n` therefore starts
//! its window `(k-1)/n` of a window later, so that the cycles sample different stretches
//! of the motion instead of piling one stretch's slip bursts onto the same cells. A cycle
//! must be short enough that the profile changes little within it: the depth it adds may
//! not exceed `max_step_fraction` of the outer contact's Hertz approach at the heaviest
//! ball (else the error names `wear.cycle_cage_revs` and its largest allowed value). With
//! an output folder, each completed cycle's map is written at once, atomically
//! ([`crate::fsutil`]): a run failing in cycle `k` leaves the maps of cycles `1..k-1`.

use crate::component::{variables, Component, Scene};
use crate::error::{Error, Result};
use crate::models::wear_map::{OuterRaceWear, ShareTally};
use std::f64::consts::TAU;
use std::path::Path;

/// The cycle procedure.
#[derive(Debug, Clone)]
pub struct WearCycles {
    /// Scene: the skidding level, no `[effects]` (the wear acts through the level's
    /// outer-race profile).
    pub scene: Scene,
    /// Wear law.
    pub wear: OuterRaceWear,
    /// Cells of the circumferential map.
    pub cells: usize,
    /// Dynamics before the measured window, s.
    pub settle_s: f64,
    /// Cage revolutions of the measured window.
    pub window_cage_revs: f64,
    /// Cage revolutions each cycle stands for.
    pub cycle_cage_revs: f64,
    /// Number of cycles.
    pub cycles: u32,
    /// Communication step (sampling of the contacts), s.
    pub step_s: f64,
    /// Largest depth one cycle may add, as a fraction of the outer Hertz approach.
    pub max_step_fraction: f64,
}

/// What one cycle gives.
#[derive(Debug, Clone, Default)]
pub struct CycleRecord {
    /// Cycle number, from 1.
    pub cycle: u32,
    /// Cage revolutions after this cycle.
    pub cage_revs: f64,
    /// Outer-race depth per cell after this cycle, m.
    pub map: Vec<f64>,
    /// Depth per cage revolution measured in this cycle's window, m.
    pub rate: Vec<f64>,
    /// Mean asperity share per cell in the window (NaN where no ball was loaded), %.
    pub la: Vec<f64>,
    /// Mean outer-contact load of the loaded balls per cell in the window (NaN where no
    /// ball was loaded), N: what `la` is a share of.
    pub q: Vec<f64>,
    /// Shaft centre `(x, y)` over the window, m.
    pub orbit: Vec<[f64; 2]>,
    /// Mean cage slip over the window.
    pub cage_slip: f64,
    /// Largest outer-contact load in the window, N.
    pub q_max: f64,
}

impl CycleRecord {
    /// Deepest cell `(depth m, angle rad)`.
    pub fn deepest(&self) -> (f64, f64) {
        crate::models::wear::deepest(&self.map)
    }

    /// The map as CSV: angle (deg), depth (µm), rate (µm per 1e6 cage revolutions),
    /// asperity share (%), mean load (N).
    pub fn csv(&self) -> String {
        let n = self.map.len();
        let mut s =
            String::from("angle_deg,depth_um,rate_um_per_1e6_cage_revs,la_percent,load_n\n");
        for k in 0..n {
            s.push_str(&format!(
                "{:.3},{:.6e},{:.6e},{:.4},{:.4}\n",
                360.0 * k as f64 / n as f64,
                self.map[k] * 1e6,
                self.rate[k] * 1e12,
                self.la[k],
                self.q[k]
            ));
        }
        s
    }
}

impl WearCycles {
    /// Check the options; errors name `wear.<field>`.
    pub fn validate(&self) -> Result<()> {
        use crate::error::{in_range, positive};
        if self.scene.model.level != crate::component::Level::Skidding {
            return Err(Error::invalid(
                "model.level",
                self.scene.model.level.name(),
                "\"skidding\" (the wear cycles use its per-ball slip)",
            ));
        }
        if !(1..=10_000).contains(&self.cells) {
            return Err(Error::invalid(
                "wear.cells",
                self.cells,
                "an integer in [1, 10000]",
            ));
        }
        positive("wear.coefficient", self.wear.law.k)?;
        positive("wear.hardness (Pa)", self.wear.law.hardness)?;
        if let Some(f) = &self.wear.law.film {
            in_range("wear.roughness (m)", f.lubricant.roughness, 0.0, 1e-4)?;
            positive("wear.viscosity (Pa s)", f.lubricant.viscosity)?;
        }
        positive(
            "wear.surface_temperature (K)",
            self.wear.law.surface_temperature,
        )?;
        in_range("wear.settle_s", self.settle_s, 0.0, 1e3)?;
        positive("wear.window_cage_revs", self.window_cage_revs)?;
        if !(self.cycle_cage_revs.is_finite() && self.cycle_cage_revs >= self.window_cage_revs) {
            return Err(Error::invalid(
                "wear.cycle_cage_revs",
                self.cycle_cage_revs,
                format!(">= window_cage_revs ({})", self.window_cage_revs),
            ));
        }
        in_range("wear.step_s", self.step_s, 1e-7, 1e-2)?;
        in_range("wear.max_step_fraction", self.max_step_fraction, 1e-6, 1.0)?;
        Ok(())
    }

    /// Run every cycle; `out` receives `cycle-NN.csv` after each (atomically). `each` is
    /// told of every completed cycle before its map is written (its error stops the run
    /// like a failed cycle: that cycle's map is not written).
    pub fn run(
        &self,
        out: Option<&Path>,
        mut each: impl FnMut(&CycleRecord) -> Result<()>,
    ) -> Result<Vec<CycleRecord>> {
        self.validate()?;
        if let Some(d) = out {
            std::fs::create_dir_all(d)
                .map_err(|e| Error::invalid("wear output folder", d.display(), e.to_string()))?;
        }
        let mut map = vec![0.0; self.cells];
        let mut revs = 0.0;
        let mut done = Vec::new();
        for k in 1..=self.cycles {
            let w = self.window_at(&map, (k - 1) as f64 / self.cycles as f64)?;
            let step_max = w.rate.iter().fold(0.0f64, |a, &b| a.max(b)) * self.cycle_cage_revs;
            let limit = self.max_step_fraction * w.approach;
            if step_max > limit {
                return Err(Error::invalid(
                    "wear.cycle_cage_revs",
                    self.cycle_cage_revs,
                    format!(
                        "<= {:.4e} in cycle {k}: a cycle may add at most {} of the outer Hertz approach ({:.3e} m), this one adds {:.3e} m",
                        self.cycle_cage_revs * limit / step_max,
                        self.max_step_fraction,
                        w.approach,
                        step_max
                    ),
                ));
            }
            for (m, r) in map.iter_mut().zip(&w.rate) {
                *m += r * self.cycle_cage_revs;
            }
            revs += self.cycle_cage_revs;
            let rec = CycleRecord {
                cycle: k,
                cage_revs: revs,
                map: map.clone(),
                ..w.record
            };
            each(&rec)?;
            if let Some(d) = out {
                let p = d.join(format!("cycle-{k:02}.csv"));
                crate::fsutil::write_atomic(&p, rec.csv())
                    .map_err(|e| Error::invalid("wear output", p.display(), e.to_string()))?;
            }
            done.push(rec);
        }
        Ok(done)
    }

    /// A fresh component of the scene on outer-race profile `map`.
    fn start(&self, map: &[f64]) -> Result<Component> {
        let mut c = Component::new(self.scene.clone())?;
        let lvl = c
            .skidding_mut()
            .ok_or_else(|| Error::invalid("model.level", "not skidding", "\"skidding\""))?;
        lvl.set_outer_wear(map)?;
        c.refresh_outputs()?;
        Ok(c)
    }

    /// How long the dynamics on the unworn race take to settle, measured rather than
    /// guessed: run from the scene's start in chunks of `chunk_cage_revs` cage revolutions
    /// at the kinematic cage speed (a whole number of ball passes, `k / Z`, keeps the ball
    /// passing out of the chunk means) up to `max_s`, and record each chunk's mean cage
    /// slip and mean slip speed `|dv_o|` of the loaded balls over the outer race (what the
    /// wear law integrates). Settled at the end of the first chunk `k` for which chunks
    /// `k-2, k-1, k` agree, each successive pair, within the relative tolerance `tol` in
    /// the ball slip and within the absolute tolerance `cage_tol` in the cage slip (a
    /// fraction of the cage speed that may pass through zero: a relative test would never
    /// pass there).
    pub fn settle_check(
        &self,
        chunk_cage_revs: f64,
        max_s: f64,
        tol: f64,
        cage_tol: f64,
    ) -> Result<Settle> {
        self.validate()?;
        crate::error::positive("wear.settle_chunk_cage_revs", chunk_cage_revs)?;
        crate::error::in_range("wear.settle_max_s", max_s, 0.0, 1e3)?;
        crate::error::in_range("wear.settle_tol", tol, 0.0, 1.0)?;
        crate::error::in_range("wear.settle_cage_tol", cage_tol, 0.0, 1.0)?;
        let mut c = self.start(&vec![0.0; self.cells])?;
        let vs = variables::by_name("cage.slip").map_or(0, |v| v.vr);
        let omega = c.get_real(variables::by_name("shaft.omega").map_or(0, |v| v.vr))?;
        let (wk, _) = c
            .skidding_mut()
            .expect("skidding level")
            .model()
            .kinematic(omega);
        let h = self.step_s;
        let steps = if wk.abs() > 0.0 {
            ((chunk_cage_revs * TAU / wk.abs()) / h).round().max(1.0) as usize
        } else {
            1
        };
        let agree = |a: f64, b: f64| (a - b).abs() <= tol * a.abs().max(b.abs());
        let near = |a: f64, b: f64| (a - b).abs() <= cage_tol;
        let mut t = c.time();
        let t_start = t;
        let mut chunks: Vec<SettleChunk> = Vec::new();
        let mut settled_s = None;
        while settled_s.is_none() && t - t_start + steps as f64 * h <= max_s + 1e-12 {
            let (mut cage, mut ball, mut nb) = (0.0, 0.0, 0.0f64);
            for _ in 0..steps {
                c.do_step(t, h)?;
                t += h;
                c.ensure_outputs()?;
                cage += c.get_real(vs)?;
                let m = c.skidding_mut().expect("skidding level").model();
                for j in 0..m.z() {
                    let (ct, dv, _) = m.outer_contact(j);
                    if ct.q > 0.0 {
                        ball += dv.abs();
                        nb += 1.0;
                    }
                }
            }
            chunks.push(SettleChunk {
                t_end: t - t_start,
                cage_slip: cage / steps as f64,
                ball_slip: ball / nb.max(1.0),
            });
            if let [a, b, d] = chunks[chunks.len().saturating_sub(3)..] {
                if near(a.cage_slip, b.cage_slip)
                    && near(b.cage_slip, d.cage_slip)
                    && agree(a.ball_slip, b.ball_slip)
                    && agree(b.ball_slip, d.ball_slip)
                {
                    settled_s = Some(d.t_end);
                }
            }
        }
        Ok(Settle {
            chunks,
            tol,
            cage_tol,
            settled_s,
        })
    }

    /// Run the dynamics on profile `map` and measure the window.
    pub fn window(&self, map: &[f64]) -> Result<Window> {
        self.window_at(map, 0.0)
    }

    /// [`Self::window`] starting `phase` (in `[0, 1)`) of a window (at the kinematic cage
    /// speed) after `settle_s`.
    pub fn window_at(&self, map: &[f64], phase: f64) -> Result<Window> {
        let mut c = self.start(map)?;
        let omega0 = c.get_real(variables::by_name("shaft.omega").map_or(0, |v| v.vr))?;
        let (wk0, _) = c
            .skidding_mut()
            .expect("skidding level")
            .model()
            .kinematic(omega0);
        let extra = if wk0.abs() > 0.0 {
            phase.clamp(0.0, 1.0) * self.window_cage_revs * TAU / wk0.abs()
        } else {
            0.0
        };
        let vr = |n: &str| variables::by_name(n).map_or(0, |v| v.vr);
        let (vx, vy, vw, vs) = (
            vr("shaft.x"),
            vr("shaft.y"),
            vr("cage.omega"),
            vr("cage.slip"),
        );
        let h = self.step_s;
        let mut t = c.time();
        let end = t + self.settle_s + extra;
        while t < end - 1e-12 {
            c.do_step(t, h)?;
            t += h;
        }
        let n = self.cells;
        let cell_len = TAU * 0.5 * c.bearing().outer_race_diameter() / n as f64;
        let mut dep = vec![0.0; n];
        let mut tally = ShareTally::new(n);
        let mut orbit = Vec::new();
        let (mut turned, mut slip, mut steps, mut q_max) = (0.0, 0.0, 0.0f64, 0.0f64);
        let target = self.window_cage_revs * TAU;
        // A cage at a thousandth of its kinematic speed is not turning: give up then.
        let omega = c.get_real(vr("shaft.omega"))?;
        let (wk, _) = c
            .skidding_mut()
            .expect("skidding level")
            .model()
            .kinematic(omega);
        let max_steps = if wk.abs() > 0.0 {
            (1e3 * target / (wk.abs() * h)).min(1e7) as usize
        } else {
            1_000_000
        };
        let mut i = 0;
        while turned < target {
            c.do_step(t, h)?;
            t += h;
            c.ensure_outputs()?;
            let wc = c.get_real(vw)?;
            turned += wc.abs() * h;
            slip += c.get_real(vs)?;
            steps += 1.0;
            orbit.push([c.get_real(vx)?, c.get_real(vy)?]);
            let lvl = c.skidding_mut().expect("skidding level");
            let q = self
                .wear
                .deposit(lvl.model(), h, &mut dep, cell_len, &mut tally);
            q_max = q_max.max(q);
            i += 1;
            if i > max_steps {
                return Err(Error::invalid(
                    "wear.window_cage_revs",
                    self.window_cage_revs,
                    "a window the cage completes (it barely turns)",
                ));
            }
        }
        let revs = turned / TAU;
        let rate: Vec<f64> = dep.iter().map(|d| d / revs).collect();
        let (la, q) = tally.means();
        let approach = c
            .skidding_mut()
            .expect("skidding level")
            .model()
            .outer_approach(q_max);
        Ok(Window {
            rate: rate.clone(),
            approach,
            record: CycleRecord {
                rate,
                la,
                q,
                orbit,
                cage_slip: slip / steps.max(1.0),
                q_max,
                ..CycleRecord::default()
            },
        })
    }
}

/// One chunk of [`WearCycles::settle_check`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SettleChunk {
    /// End of the chunk, s from the start of the dynamics.
    pub t_end: f64,
    /// Mean cage slip over the chunk.
    pub cage_slip: f64,
    /// Mean slip speed `|dv_o|` of the loaded balls over the outer race, m/s.
    pub ball_slip: f64,
}

/// What [`WearCycles::settle_check`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct Settle {
    /// Every chunk run.
    pub chunks: Vec<SettleChunk>,
    /// Relative tolerance on the ball slip between successive chunks.
    pub tol: f64,
    /// Absolute tolerance on the cage slip between successive chunks.
    pub cage_tol: f64,
    /// Time after which three successive chunks agree, s (`None`: not within `max_s`).
    pub settled_s: Option<f64>,
}

/// One measured window.
#[derive(Debug, Clone)]
pub struct Window {
    /// Depth per cage revolution per cell, m.
    pub rate: Vec<f64>,
    /// Outer Hertz approach at the heaviest ball, m.
    pub approach: f64,
    /// The rest of the record (map and counts filled by the cycle).
    pub record: CycleRecord,
}
