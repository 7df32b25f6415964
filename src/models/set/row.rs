//! One row of a set: its bearing's quasi-static law, the map from the shaft's motion at the
//! reference point to the row's own displacement, and the row's report.

use crate::error::Result;
use crate::geometry::element::Element;
use crate::geometry::Bearing;
use crate::models::quasi_static::{azimuths, BallResult, BallState, Options, QuasiStatic};
use crate::seam::element::{assemble, ElementLaw, Want};
use serde::Serialize;

/// The row's contact law with its warm starts.
#[derive(Debug)]
enum Law {
    /// Jones–Harris balls (speed effects: centrifugal force, gyroscopic moment).
    Ball(Box<QuasiStatic>, Vec<BallState>),
    /// Any other element law, summed by the element seam, with its memory.
    Other(Box<dyn ElementLaw>, Vec<f64>),
}

/// A row ready to evaluate.
#[derive(Debug)]
pub(crate) struct RowModel {
    pub bearing: Bearing,
    /// Axial position from the reference point, m.
    pub z: f64,
    /// `±1`.
    pub o: f64,
    /// Preload offset added to the row's own axial displacement, m.
    pub offset: f64,
    /// The row's outer ring slides on the preload spring.
    pub floating: bool,
    psi: Vec<f64>,
    law: Law,
    /// Scratch of [`RowModel::mean_inner_angle`] (ball rows): trial warm starts and the
    /// per-ball results, sized once so that a level's output step does not allocate.
    trial: Vec<BallState>,
    balls: Vec<BallResult>,
}

fn build_law(b: &Bearing) -> Result<Law> {
    Ok(match &b.element {
        Element::Ball(_) => Law::Ball(
            Box::new(QuasiStatic::new(b, Options::default())?),
            vec![BallState::default(); b.z],
        ),
        Element::Roller(r) => {
            let l: Box<dyn ElementLaw> = crate::contact::roller_law(r, true)?;
            let n = l.state_len() * b.z;
            Law::Other(l, vec![0.0; n])
        }
    })
}

/// The row's answer at one shaft position, in its own frame (local) and at the reference
/// point (global).
#[derive(Debug, Clone, Default)]
pub(crate) struct RowEval {
    /// The row's own displacement `T (A q) + (0, 0, offset - u, 0, 0)`.
    pub q_loc: [f64; 5],
    /// Forces on the shaft in the row's frame.
    pub f_loc: [f64; 5],
    /// `K` in the row's frame.
    pub k_loc: [[f64; 5]; 5],
    /// Per-ball results (ball rows, when asked).
    pub balls: Vec<BallResult>,
    /// Per-element inner/outer loads (any row, when asked), N.
    pub loads: Vec<[f64; 2]>,
    /// Largest contact pressure over the elements (rows other than ball rows, when asked), Pa.
    pub peak_pressure: f64,
}

impl RowModel {
    pub fn new(bearing: &Bearing, z: f64, orientation: i32) -> Result<Self> {
        Ok(RowModel {
            bearing: bearing.clone(),
            z,
            o: orientation as f64,
            offset: 0.0,
            floating: false,
            psi: azimuths(bearing.z, 0.0),
            law: build_law(bearing)?,
            trial: vec![BallState::default(); bearing.z],
            balls: vec![BallResult::default(); bearing.z],
        })
    }

    /// `T A_r` applied to `q` (module docs of the set): the row's displacement before its
    /// preload offset.
    pub fn to_local(&self, q: &[f64; 5]) -> [f64; 5] {
        let o = self.o;
        [
            q[0] + self.z * q[4],
            q[1] - self.z * q[3],
            o * q[2],
            o * q[3],
            o * q[4],
        ]
    }

    /// `(T A_r)^T` applied to a local force: the force at the reference point.
    pub fn to_global(&self, f: &[f64; 5]) -> [f64; 5] {
        let o = self.o;
        [
            f[0],
            f[1],
            o * f[2],
            o * f[3] - self.z * f[1],
            o * f[4] + self.z * f[0],
        ]
    }

    /// The 5x5 matrix `T A_r` (rows: local, columns: global).
    pub fn map(&self) -> [[f64; 5]; 5] {
        let (o, z) = (self.o, self.z);
        [
            [1.0, 0.0, 0.0, 0.0, z],
            [0.0, 1.0, 0.0, -z, 0.0],
            [0.0, 0.0, o, 0.0, 0.0],
            [0.0, 0.0, 0.0, o, 0.0],
            [0.0, 0.0, 0.0, 0.0, o],
        ]
    }

    /// Evaluate at the row's own displacement `q_loc`; `report` fills the per-element
    /// results. The warm starts are updated only on success.
    pub fn eval_local(&mut self, q_loc: [f64; 5], omega: f64, report: bool) -> Result<RowEval> {
        let mut e = RowEval {
            q_loc,
            ..Default::default()
        };
        let z = self.psi.len();
        match &mut self.law {
            Law::Ball(m, st) => {
                let mut trial = st.clone();
                let mut balls = vec![BallResult::default(); if report { z } else { 0 }];
                e.f_loc = m.evaluate(
                    &q_loc,
                    omega,
                    &self.psi,
                    &mut trial,
                    Some(&mut e.k_loc),
                    report.then_some(&mut balls[..]),
                )?;
                *st = trial;
                if report {
                    e.loads = balls.iter().map(|b| [b.q_i, b.q_o]).collect();
                    e.balls = balls;
                }
            }
            Law::Other(law, mem) => {
                let n = law.state_len();
                let mut trial = mem.clone();
                let mut loads = vec![[0.0; 2]; z];
                let mut peak = 0.0f64;
                let want = Want {
                    stiffness: true,
                    report,
                };
                e.f_loc = assemble(
                    &q_loc,
                    &self.psi,
                    law.moment_arm(),
                    Some(&mut e.k_loc),
                    |j, at, u| {
                        let r = law.react(at, u, omega, &mut trial[n * j..n * (j + 1)], want)?;
                        loads[j] = r.load;
                        peak = peak.max(r.pressure[0]).max(r.pressure[1]);
                        Ok(r)
                    },
                )?;
                *mem = trial;
                if report {
                    e.loads = loads;
                    e.peak_pressure = peak;
                }
            }
        }
        Ok(e)
    }

    /// The load-weighted mean inner contact angle of the loaded balls (rad; 0 when none is
    /// loaded) at the row's own displacement `q_loc`, and whether any is: the ball
    /// equilibrium without the stiffness, in the row's scratch (no allocation). `None`
    /// for a row of other elements. The warm starts are updated only on success.
    pub fn mean_inner_angle(&mut self, q_loc: [f64; 5], omega: f64) -> Result<Option<f64>> {
        let Law::Ball(m, st) = &mut self.law else {
            return Ok(None);
        };
        self.trial.copy_from_slice(st);
        m.evaluate(
            &q_loc,
            omega,
            &self.psi,
            &mut self.trial,
            None,
            Some(&mut self.balls[..]),
        )?;
        st.copy_from_slice(&self.trial);
        let (mut s, mut w) = (0.0, 0.0);
        for b in self.balls.iter().filter(|b| b.q_i > 0.0) {
            s += b.q_i * b.alpha_i;
            w += b.q_i;
        }
        Ok(Some(if w > 0.0 { s / w } else { 0.0 }))
    }

    /// The row's thrust (axial force on its outer ring toward its loading direction) at
    /// its own axial displacement `a` with nothing else moved, and `dP/da`, at speed `omega`.
    pub fn thrust(&mut self, a: f64, omega: f64) -> Result<(f64, f64)> {
        let e = self.eval_local([0.0, 0.0, a, 0.0, 0.0], omega, false)?;
        Ok((-e.f_loc[2], e.k_loc[2][2]))
    }
}

/// What a report says of one row at an equilibrium (SI).
#[derive(Debug, Clone, Serialize)]
pub struct RowReport {
    /// Bearing designation.
    pub bearing: String,
    /// Axial position from the reference point, m.
    pub position: f64,
    /// `±1`.
    pub orientation: i32,
    /// The row's own displacement (its frame), m and rad.
    pub displacement: [f64; 5],
    /// Forces and moments of the row on the shaft at the row, in the shaft's frame
    /// `(Fx, Fy, Fz, Mx, My)`, N and N m.
    pub force: [f64; 5],
    /// Radial load, N.
    pub radial_load: f64,
    /// Axial load (thrust toward the row's loading direction; negative would pull), N.
    pub axial_load: f64,
    /// Per-element inner contact loads, N.
    pub element_loads: Vec<f64>,
    /// Per-element inner and outer contact angles, rad: a ball's from its equilibrium; a
    /// roller's the cone's and cup's raceway angles (0 for a cylindrical row).
    pub contact_angles: Vec<[f64; 2]>,
    /// Elements with a positive inner contact load.
    pub loaded_elements: usize,
    /// No element loaded: the row has lifted off.
    pub lifted_off: bool,
    /// The row's axial stiffness in its own frame, N/m.
    pub axial_stiffness: f64,
    /// Rating life (ball rows: ISO/TS 16281 reference life from the ball loads; roller
    /// rows: ISO 281 basic life), millions of revolutions (`None`: unloaded).
    pub life_mrev: Option<f64>,
    /// Weibull slope of the row's life distribution (10/9 ball, 9/8 roller).
    pub weibull_slope: f64,
    /// Static safety `S0 = C0/P0` (`None`: unloaded).
    pub s0: Option<f64>,
    /// Peak contact pressure, Pa (ball rows; 0 for roller rows).
    pub peak_pressure: f64,
    /// Every ball's equilibrium (ball rows; empty for roller rows), as the single
    /// bearing's quasi-static report has them.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub balls: Vec<BallResult>,
}
