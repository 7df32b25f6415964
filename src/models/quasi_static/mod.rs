//! Jones–Harris quasi-static equilibrium of a ball bearing (docs/physics.md §4; Harris &
//! Kotzalas, *Rolling Bearing Analysis* 5th ed., Vol. 2 ch. 3; Jones, *A general theory for
//! elastically constrained ball and radial roller bearings under arbitrary load and speed
//! conditions*, ASME J. Basic Eng. 1960).
//!
//! Every ball is in force equilibrium; inertia enters as its centrifugal force and
//! gyroscopic moment. Two ways to drive it:
//!
//! - **motion-driven** ([`QuasiStatic::evaluate`], [`QuasiStatic::forces`]): given the
//!   inner-ring displacement `q`, the shaft speed and the ball azimuths, solve each ball's two
//!   equations (warm-started from caller-owned [`BallState`]s, no allocation) and sum the
//!   forces and moments on the shaft; optionally the exact 5x5 stiffness `K = -dF/dq` by the
//!   implicit-function theorem on the ball equations;
//! - **load-driven** ([`QuasiStatic::solve`]): given the external load on the inner ring,
//!   find `q` and every ball by a damped Newton–Raphson on the five ring equations with the
//!   ball equations solved inside (nested).
//!
//! # Conventions (docs/physics.md §0)
//!
//! Fixed frame, `z` along the shaft axis, ball `j` at azimuth `psi_j` from `+x` toward `+y`.
//! `q = (x, y, z, rx, ry)`: translation of the inner-ring centre and small rotations about
//! `x` and `y` (right-hand rule). Forces and moments are those the bearing exerts **on the
//! shaft**, `F = (Fx, Fy, Fz, Mx, My)`, moments about the centre of the circle of inner
//! groove curvature centres (the bearing centre).
//!
//! - **Tilt.** A rotation `(rx, ry, 0)` moves a ring point `Ri (cos psi, sin psi, 0)` by
//!   `(rx, ry, 0) x Ri (cos psi, sin psi, 0) = Ri (rx sin psi - ry cos psi) e_z`, so
//!   `A1_j = A1_0 + z + Ri (rx sin psi_j - ry cos psi_j)`,
//!   `A2_j = A2_0 + x cos psi_j + y sin psi_j` (`(A1_0, A2_0)` from
//!   [`Bearing::reference_groove_offset`], `Ri` = [`Bearing::inner_groove_centre_radius`]).
//!   The radial motion of the groove centre caused by tilt (second order) and the tangential
//!   part of the ring translation are neglected, as in Jones and Harris.
//! - **Moment arms.** The inner normal force passes through the inner groove centre, at
//!   radius `Ri` in the bearing plane, so a ball's axial force `F_a` on the shaft gives the
//!   ball-plane moment `m = Ri F_a`; the gyroscopic friction force `T_i` acts at the contact
//!   point, `f_i D` from that centre, and adds the couple `T_i f_i D` (`= lambda_i f_i Mg`,
//!   Harris's term). With `F_r` the radial force on the shaft:
//!   `Fx = sum F_r cos psi`, `Fy = sum F_r sin psi`, `Fz = sum F_a`,
//!   `Mx = sum m sin psi`, `My = -sum m cos psi`. These are the generalised forces conjugate
//!   to `q` through the map above (virtual work), so at zero speed `K` is symmetric (up to
//!   the small non-conservative part from `Kc` depending on the contact angle) and a tilt
//!   `rx > 0` of a loaded angular-contact bearing gives `Mx < 0` (restoring,
//!   `K[rx][rx] > 0`).
//!
//! The per-ball physics (race control, gyroscopic sign, friction limit) is documented in
//! `ball.rs`; the Hertz constant comes from one function, `kc.rs`.

mod ball;
mod dual;
pub mod hold;
mod kc;
pub mod law;
pub mod level;
pub mod rollers;

pub use ball::BallState;

use crate::contact::ContactTable;
use crate::error::{Error, Result};
use crate::geometry::Bearing;
use crate::seam::element::{self, ElementAt, ElementReaction};
use crate::solver::newton;
use ball::{Eval, Geo};
use kc::contact_tables;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Race control assumption of the quasi-static model (Harris ch. 8).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum RaceControl {
    /// Outer-race control: `lambda_o = 2`, `lambda_i = 0`.
    #[default]
    Outer,
    /// No race control: `lambda_i = lambda_o = 1`.
    None,
}

/// Model and solver options.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Options {
    /// Race control: outer (`lambda_o = 2`, `lambda_i = 0`) or none (1 and 1).
    pub race_control: RaceControl,
    /// Include the gyroscopic moment (false: `Mg = 0`).
    pub gyroscopic: bool,
    /// Traction coefficient that limits the gyroscopic friction couple (`ball.rs` docs);
    /// `f64::INFINITY` gives Harris's unlimited couple.
    pub gyro_traction: f64,
    /// Relative tolerance of each ball's force balance (residual / (Q_i + Q_o + Fc)).
    pub ball_tolerance: f64,
    /// Relative tolerance of the ring force balance in the load-driven solve.
    pub ring_tolerance: f64,
    /// Newton iterations allowed per ball solve and per ring solve.
    pub max_iterations: usize,
    /// Largest contact angle the groove can carry (its shoulder), rad; a load-driven answer
    /// beyond it is refused.
    pub max_contact_angle: f64,
    /// Largest contact deflection as a fraction of `D` (Hertz theory is far outside its
    /// range beyond); a load-driven answer beyond it is refused.
    pub max_deflection_ratio: f64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            race_control: RaceControl::Outer,
            gyroscopic: true,
            gyro_traction: 0.3,
            ball_tolerance: 1e-11,
            ring_tolerance: 1e-10,
            max_iterations: 60,
            max_contact_angle: 80f64.to_radians(),
            max_deflection_ratio: 0.02,
        }
    }
}

/// Everything about one ball at an equilibrium (SI: N, m, rad, rad/s, Pa, N m).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct BallResult {
    /// Azimuth, rad.
    pub psi: f64,
    /// Inner contact load, N.
    pub q_i: f64,
    /// Outer contact load, N.
    pub q_o: f64,
    /// Inner contact angle, rad.
    pub alpha_i: f64,
    /// Outer contact angle, rad.
    pub alpha_o: f64,
    /// Inner approach (negative: gap), m.
    pub delta_i: f64,
    /// Outer approach (negative: gap), m.
    pub delta_o: f64,
    /// Inner contact semi-axis across the rolling direction, m.
    pub a_i: f64,
    /// Inner contact semi-axis along the rolling direction, m.
    pub b_i: f64,
    /// Inner peak (Hertz) pressure, Pa.
    pub p_i: f64,
    /// Outer semi-axis across the rolling direction, m.
    pub a_o: f64,
    /// Outer semi-axis along the rolling direction, m.
    pub b_o: f64,
    /// Outer peak pressure, Pa.
    pub p_o: f64,
    /// Centrifugal force, N.
    pub fc: f64,
    /// Gyroscopic moment, N m.
    pub mg: f64,
    /// Orbital (cage) speed, rad/s.
    pub omega_m: f64,
    /// Spin speed relative to the cage, rad/s (signed as in `ball.rs`).
    pub omega_r: f64,
    /// Spin-axis attitude `beta`, rad.
    pub beta: f64,
    /// Spin-to-roll ratio at the inner contact.
    pub spin_roll_i: f64,
    /// Spin-to-roll ratio at the outer contact.
    pub spin_roll_o: f64,
    /// Ball centre relative to the outer groove centre `(X1, X2)`, m.
    pub x: [f64; 2],
}

/// A load-driven equilibrium.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Solution {
    /// Shaft speed, rad/s.
    pub omega: f64,
    /// External load on the inner ring `(Fx, Fy, Fz, Mx, My)`, N and N m.
    pub load: [f64; 5],
    /// Inner-ring displacement `(x, y, z, rx, ry)`, m and rad.
    pub q: [f64; 5],
    /// Forces and moments of the bearing on the shaft at `q` (= `-load` to the tolerance).
    pub forces: [f64; 5],
    /// Stiffness `K = -dF/dq` (row `i`: force `i`), SI.
    pub stiffness: [[f64; 5]; 5],
    /// Ball azimuths, rad.
    pub psi: Vec<f64>,
    /// Per-ball results.
    pub balls: Vec<BallResult>,
    /// Per-ball states (to warm-start a motion-driven run from here).
    pub states: Vec<BallState>,
    /// Ring Newton iterations (all stages).
    pub iterations: usize,
    /// The coordinates held at a given value (`(x, y, z, rx, ry)`, [`Hold`]); the others
    /// were solved. All false for the free (load-driven) equilibrium.
    #[serde(default)]
    pub held: [bool; 5],
    /// What the support must add on the shaft to hold each held coordinate,
    /// `-(forces + load)` there (N, N m), so that `load + forces + reaction = 0` in every
    /// coordinate; zero in the solved ones.
    #[serde(default)]
    pub reaction: [f64; 5],
}

/// Coordinates of the inner ring held at a given value while the others are solved:
/// `Some(v)` holds `(x, y, z, rx, ry)[i]` at `v` (m or rad). `[None; 5]` is the free
/// equilibrium.
pub type Hold = [Option<f64>; 5];

/// The quasi-static model of one bearing, with everything that can be precomputed.
#[derive(Debug, Clone)]
pub struct QuasiStatic {
    bearing: Bearing,
    opts: Options,
    geo: Geo,
    a_ref: [f64; 2],
    ri: f64,
    /// Scale for rotations (m): `q_s = (x, y, z, Ri rx, Ri ry)`.
    t: [f64; 5],
    /// The ball reports' semi-axis and pressure coefficients against the contact angle,
    /// `(inner, outer)`: [`ContactTable::fine`], the exact ellipse solve's values to
    /// rounding (it cost two elliptic-integral Newton solves per ball per report).
    report_tables: (ContactTable, ContactTable),
}

/// Equally spaced azimuths `psi_j = phase + 2 pi j / Z` (ball 0 at `phase`).
pub fn azimuths(z: usize, phase: f64) -> Vec<f64> {
    (0..z)
        .map(|j| phase + 2.0 * PI * j as f64 / z as f64)
        .collect()
}

fn check_finite(what: &str, v: &[f64]) -> Result<()> {
    for (k, x) in v.iter().enumerate() {
        if !x.is_finite() {
            return Err(Error::invalid(format!("{what}[{k}]"), x, "a finite number"));
        }
    }
    Ok(())
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

impl QuasiStatic {
    /// Precompute the model for `bearing`.
    pub fn new(bearing: &Bearing, opts: Options) -> Result<Self> {
        bearing.groove("the Jones–Harris quasi-static ball model")?;
        let pos = |f: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(Error::invalid(f, v, "a finite number > 0"))
            }
        };
        pos("quasi_static.ball_tolerance", opts.ball_tolerance)?;
        pos("quasi_static.ring_tolerance", opts.ring_tolerance)?;
        pos(
            "quasi_static.max_deflection_ratio",
            opts.max_deflection_ratio,
        )?;
        if opts.gyro_traction.is_nan() || opts.gyro_traction <= 0.0 {
            return Err(Error::invalid(
                "quasi_static.gyro_traction",
                opts.gyro_traction,
                "> 0 (inf: unlimited)",
            ));
        }
        if !(opts.max_contact_angle > 0.0 && opts.max_contact_angle <= 0.5 * PI) {
            return Err(Error::invalid(
                "quasi_static.max_contact_angle",
                opts.max_contact_angle,
                "in (0, pi/2] rad",
            ));
        }
        if opts.max_iterations == 0 {
            return Err(Error::invalid("quasi_static.max_iterations", 0, ">= 1"));
        }
        let (lam_i, lam_o) = match opts.race_control {
            RaceControl::Outer => (0.0, 2.0),
            RaceControl::None => (1.0, 1.0),
        };
        let ri = bearing.inner_groove_centre_radius();
        let tables = contact_tables(bearing);
        let geo = Geo {
            d: bearing.d,
            dm: bearing.dm,
            ri_free: (bearing.fi() - 0.5) * bearing.d,
            ro_free: (bearing.fo() - 0.5) * bearing.d,
            fid: bearing.fi() * bearing.d,
            ri,
            g: bearing.d / bearing.dm,
            mass: bearing.ball_mass(),
            inertia: if opts.gyroscopic {
                bearing.ball_inertia()
            } else {
                0.0
            },
            lam_i,
            lam_o,
            mu: opts.gyro_traction,
            control: opts.race_control,
            kc_i: tables.kc.0,
            kc_o: tables.kc.1,
            tol: opts.ball_tolerance,
            max_iter: opts.max_iterations,
        };
        let (a1, a2) = bearing.reference_groove_offset();
        Ok(QuasiStatic {
            bearing: bearing.clone(),
            opts,
            geo,
            a_ref: [a1, a2],
            ri,
            t: [1.0, 1.0, 1.0, ri, ri],
            report_tables: tables.report,
        })
    }

    /// The bearing.
    pub fn bearing(&self) -> &Bearing {
        &self.bearing
    }

    /// The options.
    pub fn options(&self) -> &Options {
        &self.opts
    }

    /// `Kc(alpha)` of the inner and outer contacts, N/m^1.5 (the model's one source of it).
    pub fn kc(&self, alpha: f64) -> (f64, f64) {
        let c = alpha.cos();
        (self.geo.kc_i.eval(c).0, self.geo.kc_o.eval(c).0)
    }

    /// Offset `(A1, A2)` of the inner groove centre from the outer one for ball azimuth
    /// `psi` at displacement `q` (module docs).
    pub fn groove_offset(&self, q: &[f64; 5], psi: f64) -> [f64; 2] {
        let (s, c) = psi.sin_cos();
        self.groove_offset_sc(q, s, c)
    }

    /// [`QuasiStatic::groove_offset`] from `(sin psi, cos psi)`.
    fn groove_offset_sc(&self, q: &[f64; 5], s: f64, c: f64) -> [f64; 2] {
        [
            self.a_ref[0] + q[2] + self.ri * (q[3] * s - q[4] * c),
            self.a_ref[1] + q[0] * c + q[1] * s,
        ]
    }

    /// Motion-driven forces on the shaft. See [`QuasiStatic::evaluate`].
    pub fn forces(
        &self,
        q: &[f64; 5],
        omega: f64,
        psi: &[f64],
        state: &mut [BallState],
    ) -> Result<[f64; 5]> {
        self.evaluate(q, omega, psi, state, None, None)
    }

    /// Motion-driven forces and the stiffness `K = -dF/dq` at fixed ball azimuths.
    pub fn forces_and_stiffness(
        &self,
        q: &[f64; 5],
        omega: f64,
        psi: &[f64],
        state: &mut [BallState],
        k: &mut [[f64; 5]; 5],
    ) -> Result<[f64; 5]> {
        self.evaluate(q, omega, psi, state, Some(k), None)
    }

    /// The motion-driven kernel: ring displacement `q` (m, rad), shaft speed `omega` (rad/s,
    /// outer ring fixed), ball azimuths `psi` (rad) → forces and moments on the shaft
    /// `(Fx, Fy, Fz, Mx, My)`. `state` (one per ball, caller-owned) holds the warm starts and
    /// is updated; `stiffness` and `balls` are filled when given. Does not allocate.
    ///
    /// Errors: non-finite input, mismatched slice lengths, a ball solve that does not
    /// converge. On error `state` may hold partial updates (still valid warm starts).
    pub fn evaluate(
        &self,
        q: &[f64; 5],
        omega: f64,
        psi: &[f64],
        state: &mut [BallState],
        stiffness: Option<&mut [[f64; 5]; 5]>,
        mut balls: Option<&mut [BallResult]>,
    ) -> Result<[f64; 5]> {
        if let Some(b) = balls.as_deref() {
            if b.len() != psi.len() {
                return Err(Error::invalid(
                    "balls.len()",
                    b.len(),
                    format!("= psi.len() = {}", psi.len()),
                ));
            }
        }
        if !omega.is_finite() {
            return Err(Error::invalid("omega", omega, "a finite number"));
        }
        if state.len() != psi.len() {
            return Err(Error::invalid(
                "state.len()",
                state.len(),
                format!("= psi.len() = {}", psi.len()),
            ));
        }
        // The `N = 4` evaluation at each ball's root when the stiffness or the reports
        // are wanted (else the forces alone, `ball.rs`).
        let want_k = stiffness.is_some();
        let full = want_k || balls.is_some();
        element::assemble(q, psi, self.ri, stiffness, |j, at, _| {
            let st = &mut state[j];
            let sol = self.solve_ball(at, omega, st, full)?;
            let mut r = ElementReaction {
                f: sol.f,
                ..Default::default()
            };
            if let Some(e4) = &sol.full {
                if want_k {
                    r.df = self.ball_df(e4);
                }
                if let Some(b) = balls.as_deref_mut() {
                    b[j] = self.ball_result(e4, at.psi, st.x);
                }
            }
            Ok(r)
        })
    }

    /// One ball's equilibrium at its place `at` (module docs: the groove offset from the
    /// ring displacement and the azimuth), after the geometry check that names the ring
    /// displacement when it is impossible.
    fn solve_ball(
        &self,
        at: ElementAt<'_>,
        omega: f64,
        st: &mut BallState,
        full: bool,
    ) -> Result<ball::Solved> {
        let (s, c) = at.sc;
        let a = self.groove_offset_sc(at.q, s, c);
        self.check_geometry(at.q, at.index, at.psi, a)?;
        self.geo.solve(omega, a, st, full)
    }

    /// A ball's `d (F_a, F_r, m) / d (axial, radial, tilt)` at its root (implicit-function
    /// theorem on the ball equations: `dX/dA = -(dg/dX)^-1 dg/dA`). The tilt enters through
    /// the axial displacement at the moment arm `Ri` ([`ElementLaw::moment_arm`]), so its
    /// own column is zero.
    fn ball_df(&self, e: &Eval<4>) -> [[f64; 3]; 3] {
        let dxda = ball::sensitivity(e); // dxda[r][col] = dX_r / dA_col
        let total = |o: &dual::D4| -> [f64; 3] {
            let ox = [o.d[0] - o.d[2], o.d[1] - o.d[3]];
            let da1 = o.d[2] + ox[0] * dxda[0][0] + ox[1] * dxda[1][0];
            let da2 = o.d[3] + ox[0] * dxda[0][1] + ox[1] * dxda[1][1];
            [da1, da2, 0.0]
        };
        [total(&e.fa), total(&e.fr), total(&e.m)]
    }

    /// Largest total approach `|A_j| - A` of a ball (sum of both contact deflections) the
    /// model admits, m: twice [`Options::max_deflection_ratio`] `D`, the per-contact limit
    /// of Hertz theory the load-driven solve also applies.
    pub fn max_approach(&self) -> f64 {
        2.0 * self.opts.max_deflection_ratio * self.bearing.d
    }

    /// Displacement ranges `(radial, axial)` (m) the geometry allows for a pure radial and
    /// a pure (positive) axial ring displacement: every ball's approach at most
    /// [`QuasiStatic::max_approach`], and the inner groove centre never pushed through the
    /// outer one (`A2_j > 0`).
    pub fn displacement_limits(&self) -> (f64, f64) {
        let (a, dmax) = (self.bearing.a(), self.max_approach());
        let [a1, a2] = self.a_ref;
        // Pure radial x: the ball on the x axis has |(a1, a2 + x)| = A + dmax; the ball
        // opposite needs a2 - x > 0.
        let radial = ((a + dmax).powi(2) - a1 * a1).max(0.0).sqrt() - a2;
        let axial = ((a + dmax).powi(2) - a2 * a2).max(0.0).sqrt() - a1;
        (radial.min(a2).max(0.0), axial.max(0.0))
    }

    /// Refuse a displacement no bearing could take (a ball crushed beyond Hertz theory, or
    /// the inner groove centre pushed through the outer one) with the allowed ranges,
    /// instead of letting the ball equations return NaN: ball `j` at azimuth `p` with
    /// groove offset `g` (checked before the ball is solved).
    fn check_geometry(&self, q: &[f64; 5], j: usize, p: f64, g: [f64; 2]) -> Result<()> {
        let (a, dmax) = (self.bearing.a(), self.max_approach());
        // Millimetre-sized: the plain root (no overflow; `hypot` is several times slower).
        let approach = (g[0] * g[0] + g[1] * g[1]).sqrt() - a;
        if approach > dmax || g[1] <= 0.0 {
            let (rad, ax) = self.displacement_limits();
            return Err(Error::invalid(
                    "ring displacement q",
                    format!(
                        "(x {:.3} µm, y {:.3} µm, z {:.3} µm, rx {:.4} mrad, ry {:.4} mrad)",
                        q[0] * 1e6,
                        q[1] * 1e6,
                        q[2] * 1e6,
                        q[3] * 1e3,
                        q[4] * 1e3
                    ),
                    format!(
                        "a displacement the bearing geometry allows: ball {j} at {:.1} deg would be {} \
                         (allowed: ball approach <= {:.1} µm = 2 x {} D; pure radial displacement \
                         <= {:.1} µm, pure axial <= {:.1} µm)",
                        p.to_degrees(),
                        if g[1] <= 0.0 {
                            "pushed through the opposite groove (inner groove centre beyond the outer one)".to_string()
                        } else {
                            format!("compressed by {:.1} µm", approach * 1e6)
                        },
                        dmax * 1e6,
                        self.opts.max_deflection_ratio,
                        rad * 1e6,
                        ax * 1e6
                    ),
                ));
        }
        Ok(())
    }

    /// Semi-axes and peak pressure `(a, b, p)` of a contact at angle `(sin, cos)` = `sc`
    /// carrying `q` (zeros unloaded): `semi_axes` and `peak_pressure` of the report
    /// table's coefficients with one cube root.
    fn contact_report(sc: [f64; 2], q: f64, table: &ContactTable) -> (f64, f64, f64) {
        if q > 0.0 {
            let cc = table.eval_cos_sin(sc[1], sc[0]);
            let q3 = q.cbrt();
            (
                cc.a_coef * q3,
                cc.b_coef * q3,
                1.5 * q3 / (PI * cc.a_coef * cc.b_coef),
            )
        } else {
            (0.0, 0.0, 0.0)
        }
    }

    /// Peak pressures `(p_i, p_o)` of a ball's evaluation (those of its [`BallResult`]).
    pub(crate) fn peak_pressures<const N: usize>(&self, e: &Eval<N>) -> (f64, f64) {
        (
            Self::contact_report(e.sc_i, e.qi, &self.report_tables.0).2,
            Self::contact_report(e.sc_o, e.qo, &self.report_tables.1).2,
        )
    }

    fn ball_result<const N: usize>(&self, e: &Eval<N>, psi: f64, x: [f64; 2]) -> BallResult {
        let (alpha_i, alpha_o) = (e.alpha_i(), e.alpha_o());
        let (a_i, b_i, p_i) = Self::contact_report(e.sc_i, e.qi, &self.report_tables.0);
        let (a_o, b_o, p_o) = Self::contact_report(e.sc_o, e.qo, &self.report_tables.1);
        BallResult {
            psi,
            q_i: e.qi,
            q_o: e.qo,
            alpha_i,
            alpha_o,
            delta_i: e.di,
            delta_o: e.do_,
            a_i,
            b_i,
            p_i,
            a_o,
            b_o,
            p_o,
            fc: e.fc,
            mg: e.mg,
            omega_m: e.wm,
            omega_r: e.wr,
            beta: if e.wm == 0.0 { 0.0 } else { e.beta() },
            spin_roll_i: e.sr_i,
            spin_roll_o: e.sr_o,
            x,
        }
    }

    /// Load-driven equilibrium with the balls at `psi_j = 2 pi j / Z`.
    pub fn solve(&self, load: &[f64; 5], omega: f64) -> Result<Solution> {
        self.solve_at(load, omega, &azimuths(self.bearing.z, 0.0))
    }

    /// Load-driven equilibrium: find `q` such that the bearing's forces on the shaft balance
    /// the external load on the inner ring, `F(q) + load = 0`, at shaft speed `omega`.
    ///
    /// Method: (1) zero-speed start: a 1-D bracketing search along the load direction (in
    /// scaled coordinates `(x, y, z, Ri rx, Ri ry)`) for the displacement whose reaction
    /// balances the load's magnitude, then (2) damped Newton–Raphson on the five ring
    /// equations with the exact `K` (nested ball solves) and a back-tracking line search on
    /// the scaled residual norm; (3) at speed, Newton from the static answer, falling back to
    /// continuation in speed. Singular directions (no stiffness, e.g. tilt about the load
    /// line when only the balls on it carry load, or every direction at zero load) are
    /// regularised Levenberg–Marquardt fashion, `(K_s + mu I) dq = r` with
    /// `mu = 1e-12 max diag K_s`: a direction with neither stiffness nor residual stays at
    /// its start value (zero). Non-convergence is [`Error::NotConverged`]; an answer with a
    /// contact angle beyond [`Options::max_contact_angle`] or a deflection beyond
    /// [`Options::max_deflection_ratio`] `D` is refused as [`Error::Invalid`].
    pub fn solve_at(&self, load: &[f64; 5], omega: f64, psi: &[f64]) -> Result<Solution> {
        self.solve_held_at(load, omega, psi, &[None; 5])
    }

    /// Equilibrium with some coordinates held ([`Hold`]): the held ones stay at their given
    /// value, the others are solved from `F(q) + load = 0` as [`QuasiStatic::solve_at`]
    /// does; [`Solution::reaction`] holds what the support adds on each held coordinate.
    /// Holding all five is the motion-driven evaluation at that displacement.
    pub fn solve_held(&self, load: &[f64; 5], omega: f64, hold: &Hold) -> Result<Solution> {
        self.solve_held_at(load, omega, &azimuths(self.bearing.z, 0.0), hold)
    }

    /// [`QuasiStatic::solve_held`] with the balls at `psi`.
    pub fn solve_held_at(
        &self,
        load: &[f64; 5],
        omega: f64,
        psi: &[f64],
        hold: &Hold,
    ) -> Result<Solution> {
        check_finite("load", load)?;
        for (k, h) in hold.iter().enumerate() {
            if let Some(v) = h {
                if !v.is_finite() {
                    return Err(Error::invalid(
                        format!("hold[{k}]"),
                        v,
                        "a finite displacement (m) or tilt (rad)",
                    ));
                }
            }
        }
        let held: [bool; 5] = std::array::from_fn(|i| hold[i].is_some());
        check_finite("psi", psi)?;
        if !omega.is_finite() {
            return Err(Error::invalid("omega", omega, "a finite number"));
        }
        let n = psi.len();
        let mut state = vec![BallState::default(); n];
        let mut trial = vec![BallState::default(); n];
        let mut q = self.static_start(load, psi, hold, &mut state)?;
        let mut iterations =
            self.ring_newton(load, 0.0, psi, held, &mut q, &mut state, &mut trial)?;
        if omega != 0.0 {
            let q_static = q;
            let s_static = state.clone();
            let mut done = false;
            let mut last_err = None;
            for steps in [1usize, 4, 16] {
                q = q_static;
                state.copy_from_slice(&s_static);
                let mut ok = true;
                for k in 1..=steps {
                    let w = omega * k as f64 / steps as f64;
                    match self.ring_newton(load, w, psi, held, &mut q, &mut state, &mut trial) {
                        Ok(it) => iterations += it,
                        Err(e) => {
                            last_err = Some(e);
                            ok = false;
                            break;
                        }
                    }
                }
                if ok {
                    done = true;
                    break;
                }
            }
            if !done {
                return Err(last_err.unwrap_or(Error::NotConverged {
                    what: "quasi-static ring equilibrium",
                    iterations,
                    residual: f64::NAN,
                }));
            }
        }
        let mut k = [[0.0; 5]; 5];
        let mut balls = vec![BallResult::default(); n];
        let forces = self.evaluate(&q, omega, psi, &mut state, Some(&mut k), Some(&mut balls))?;
        self.check_validity(load, &balls)?;
        let reaction = std::array::from_fn(|i| if held[i] { -(forces[i] + load[i]) } else { 0.0 });
        Ok(Solution {
            omega,
            load: *load,
            q,
            forces,
            stiffness: k,
            psi: psi.to_vec(),
            balls,
            states: state,
            iterations,
            held,
            reaction,
        })
    }

    fn check_validity(&self, load: &[f64; 5], balls: &[BallResult]) -> Result<()> {
        let dmax = self.opts.max_deflection_ratio * self.bearing.d;
        for (j, b) in balls.iter().enumerate() {
            for (name, alpha, q, delta) in [
                ("inner", b.alpha_i, b.q_i, b.delta_i),
                ("outer", b.alpha_o, b.q_o, b.delta_o),
            ] {
                let bad_angle = q > 0.0 && alpha.abs() > self.opts.max_contact_angle;
                if bad_angle || delta > dmax {
                    return Err(Error::invalid(
                        "load",
                        format!(
                            "({:.6e}, {:.6e}, {:.6e}) N, ({:.6e}, {:.6e}) N m",
                            load[0], load[1], load[2], load[3], load[4]
                        ),
                        format!(
                            "loads the bearing can carry: ball {j} {name} contact at {:.2} deg \
                             (limit {:.1} deg, the groove shoulder) with deflection {:.3} µm \
                             (limit {:.3} µm = {} D)",
                            alpha.to_degrees(),
                            self.opts.max_contact_angle.to_degrees(),
                            delta * 1e6,
                            dmax * 1e6,
                            self.opts.max_deflection_ratio
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Scaled residual `T^-1 (F + load)`.
    fn residual(&self, f: &[f64; 5], load: &[f64; 5]) -> [f64; 5] {
        let mut r = [0.0; 5];
        for i in 0..5 {
            r[i] = (f[i] + load[i]) / self.t[i];
        }
        r
    }

    fn load_scale(&self, load: &[f64; 5]) -> f64 {
        let ls: Vec<f64> = (0..5).map(|i| load[i] / self.t[i]).collect();
        norm(&ls) + 1e-9
    }

    /// Zero-speed start: bracket and bisect along the load direction (its free part, from
    /// the held coordinates' values).
    fn static_start(
        &self,
        load: &[f64; 5],
        psi: &[f64],
        hold: &Hold,
        state: &mut [BallState],
    ) -> Result<[f64; 5]> {
        let q0: [f64; 5] = std::array::from_fn(|i| hold[i].unwrap_or(0.0));
        let ls: [f64; 5] = std::array::from_fn(|i| match hold[i] {
            Some(_) => 0.0,
            None => load[i] / self.t[i],
        });
        let lmag = norm(&ls);
        if lmag == 0.0 {
            return Ok(q0);
        }
        let u: [f64; 5] = std::array::from_fn(|i| ls[i] / lmag);
        let q_of = |t: f64| -> [f64; 5] { std::array::from_fn(|i| q0[i] + t * u[i] / self.t[i]) };
        let too_big = || {
            Error::invalid(
                "load",
                format!("{lmag:.6e} N (scaled magnitude)"),
                "a load the bearing can carry (no equilibrium within the displacement the geometry allows)",
            )
        };
        let phi = |t: f64, state: &mut [BallState]| -> Result<f64> {
            let f = match self.forces(&q_of(t), 0.0, psi, state) {
                Err(Error::Invalid { field, .. }) if field == "ring displacement q" => {
                    return Err(too_big())
                }
                other => other?,
            };
            let proj: f64 = (0..5).map(|i| u[i] * f[i] / self.t[i]).sum();
            Ok(-proj - lmag)
        };
        let d = self.bearing.d;
        let (mut lo, mut hi) = (0.0, 1e-8 * d);
        loop {
            if phi(hi, state)? > 0.0 {
                break;
            }
            lo = hi;
            hi *= 2.0;
            if hi > 0.5 * d {
                return Err(Error::invalid(
                    "load",
                    format!("{lmag:.6e} N (scaled magnitude)"),
                    "a load the bearing can carry (no equilibrium within half a ball diameter of displacement)",
                ));
            }
        }
        for _ in 0..50 {
            let mid = 0.5 * (lo + hi);
            if phi(mid, state)? > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
            if hi - lo <= 1e-6 * hi {
                break;
            }
        }
        Ok(q_of(hi))
    }

    /// Damped, regularised Newton on `F(q) + load = 0` at speed `omega` in the coordinates
    /// not `held` (those keep their value in `q`); `q` and `state` are updated in place (to
    /// the answer on success). Returns the iterations used.
    #[allow(clippy::too_many_arguments)]
    fn ring_newton(
        &self,
        load: &[f64; 5],
        omega: f64,
        psi: &[f64],
        held: [bool; 5],
        q: &mut [f64; 5],
        state: &mut [BallState],
        trial: &mut [BallState],
    ) -> Result<usize> {
        let tol = self.opts.ring_tolerance * self.load_scale(load);
        let opts = newton::Options {
            max_iterations: self.opts.max_iterations.max(20) * 2,
            max_halvings: 30,
            max_step: 0.25 * self.bearing.a(),
            scale: self.t,
            ..newton::Options::default()
        };
        let mut sys = RingSystem {
            eq: RingEquations {
                model: self,
                load,
                omega,
                psi,
                tol,
                held,
            },
            state,
            trial,
            now: Point::default(),
            next: Point::default(),
            fresh: false,
        };
        let rep = newton::solve(&mut sys, q, &opts)?;
        let what = match rep.outcome {
            newton::Outcome::Converged => return Ok(rep.iterations),
            newton::Outcome::Singular => "quasi-static ring equilibrium (singular stiffness)",
            newton::Outcome::LineSearch => "quasi-static ring equilibrium (line search)",
            newton::Outcome::MaxIterations => "quasi-static ring equilibrium",
        };
        Err(Error::NotConverged {
            what,
            iterations: rep.iterations,
            residual: rep.check.norm,
        })
    }
}

/// Residual and stiffness at one ring position.
#[derive(Debug, Clone, Copy, Default)]
struct Point {
    /// Scaled residual `T^-1 (F + load)`.
    r: [f64; 5],
    /// `K = -dF/dq`.
    k: [[f64; 5]; 5],
}

/// The five ring equations `F(q) + load = 0` as [`newton::solve`] drives them: each
/// evaluation solves every ball (nested, warm-started from `state`) and gives the exact
/// stiffness with the forces; a trial works on a copy of the ball states, committed when it
/// is accepted.
struct RingSystem<'a> {
    eq: RingEquations<'a>,
    state: &'a mut [BallState],
    trial: &'a mut [BallState],
    /// The current point.
    now: Point,
    /// The last trial.
    next: Point,
    /// `now` holds the accepted trial's evaluation (no need to evaluate again).
    fresh: bool,
}

/// What the ring equations depend on besides `q` and the balls.
struct RingEquations<'a> {
    model: &'a QuasiStatic,
    load: &'a [f64; 5],
    omega: f64,
    psi: &'a [f64],
    tol: f64,
    /// Held coordinates: no residual, no step.
    held: [bool; 5],
}

impl RingEquations<'_> {
    fn eval(&self, q: &[f64; 5], balls: &mut [BallState]) -> Result<(Point, newton::Check)> {
        let mut p = Point::default();
        let f = self
            .model
            .evaluate(q, self.omega, self.psi, balls, Some(&mut p.k), None)?;
        p.r = self.model.residual(&f, self.load);
        for (r, &h) in p.r.iter_mut().zip(&self.held) {
            if h {
                *r = 0.0;
            }
        }
        let c = newton::Check {
            norm: norm(&p.r),
            tol: self.tol,
        };
        Ok((p, c))
    }
}

impl newton::NewtonSystem<5> for RingSystem<'_> {
    type Error = Error;

    fn residual(&mut self, q: &[f64; 5]) -> Result<newton::Check> {
        self.trial.copy_from_slice(self.state);
        let (p, c) = self.eq.eval(q, self.trial)?;
        self.next = p;
        Ok(c)
    }

    fn linearise(&mut self, q: &[f64; 5]) -> Result<newton::Check> {
        if !self.fresh {
            self.now = self.eq.eval(q, self.state)?.0;
        }
        self.fresh = false;
        Ok(newton::Check {
            norm: norm(&self.now.r),
            tol: self.eq.tol,
        })
    }

    fn step(&mut self, dx: &mut [f64; 5]) -> bool {
        let t = &self.eq.model.t;
        let held = self.eq.held;
        let mut ks: [[f64; 5]; 5] =
            std::array::from_fn(|i| std::array::from_fn(|j| self.now.k[i][j] / (t[i] * t[j])));
        // A held coordinate: an identity row and column (its residual is zero), no step.
        if held.iter().any(|&h| h) {
            let dmax = (0..5)
                .filter(|&i| !held[i])
                .map(|i| ks[i][i].abs())
                .fold(0.0, f64::max);
            let one = if dmax > 0.0 { dmax } else { 1.0 };
            for i in (0..5).filter(|&i| held[i]) {
                ks[i] = [0.0; 5];
                for row in ks.iter_mut() {
                    row[i] = 0.0;
                }
                ks[i][i] = one;
            }
        }
        match newton::solve_regularised(&ks, &self.now.r, 1e-12, 8) {
            Some(d) => {
                *dx = d;
                true
            }
            None => false,
        }
    }

    fn accept(&mut self) {
        self.state.copy_from_slice(self.trial);
        self.now = self.next;
        self.fresh = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::preset;

    fn model(name: &str) -> QuasiStatic {
        QuasiStatic::new(&preset(name).unwrap().build().unwrap(), Options::default()).unwrap()
    }

    /// A shaft pushed 1 mm into a 6205 (A = 0.318 mm) is refused with the allowed range,
    /// not answered with a NaN residual; 100 µm is answered.
    #[test]
    fn impossible_displacement_is_a_clear_error() {
        let m = model("6205");
        let psi = azimuths(9, 0.0);
        let mut st = vec![BallState::default(); 9];
        let e = m
            .forces(&[1e-3, 0.0, 0.0, 0.0, 0.0], 0.0, &psi, &mut st)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("x 1000.000 µm")
                && e.contains("geometry allows")
                && e.contains("pure radial displacement <= 317.6 µm"),
            "{e}"
        );
        assert!(!e.contains("NaN"), "{e}");
        let (radial, axial) = m.displacement_limits();
        // Zero clearance: the radial limit is the groove-centre distance A = 0.04 D (the
        // opposite ball's groove centres meet) and the approach limit 2 x 0.02 D.
        assert!((radial - 0.04 * m.bearing.d).abs() < 1e-12, "{radial}");
        assert!(axial > radial);
        let f = m
            .forces(&[100e-6, 0.0, 0.0, 0.0, 0.0], 0.0, &psi, &mut st)
            .unwrap();
        assert!(f[0] < -1e4 && f.iter().all(|v| v.is_finite()), "{f:?}");
        // Just inside and just outside the radial limit.
        let mut st = vec![BallState::default(); 9];
        assert!(m
            .forces(&[0.999 * radial, 0.0, 0.0, 0.0, 0.0], 0.0, &psi, &mut st)
            .is_ok());
        assert!(m
            .forces(&[1.001 * radial, 0.0, 0.0, 0.0, 0.0], 0.0, &psi, &mut st)
            .is_err());
        // Load-driven: an impossible load names the load, not the displacement.
        let e = m
            .solve(&[1e7, 0.0, 0.0, 0.0, 0.0], 0.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("load") && e.contains("can carry"), "{e}");
    }

    /// Under outer-race control the spin at the outer contact vanishes (the attitude formula
    /// is exactly the no-spin condition of the kinematics used).
    #[test]
    fn outer_race_control_has_no_outer_spin() {
        let m = model("acbb16");
        let sol = m.solve(&[0.0, 2000.0, 20000.0, 0.0, 0.0], 1047.0).unwrap();
        for b in &sol.balls {
            assert!(b.spin_roll_o.abs() < 1e-12, "{}", b.spin_roll_o);
            assert!(
                b.spin_roll_i > 0.05 && b.spin_roll_i < 1.0,
                "{}",
                b.spin_roll_i
            );
        }
    }

    /// Ball equations are met at the returned state and the friction couple provides +Mg.
    #[test]
    fn ball_residual_and_gyroscopic_couple() {
        let m = model("7004");
        let psi = azimuths(6, 0.1);
        let mut st = vec![BallState::default(); 6];
        let q = [5e-6, -3e-6, 20e-6, 1e-4, 0.0];
        m.forces(&q, 8000.0, &psi, &mut st).unwrap();
        for (p, s) in psi.iter().zip(&st) {
            let a = m.groove_offset(&q, *p);
            let e = m.geo.eval::<0>(8000.0, s.x, a);
            assert!(e.norm() <= 1e-10 * e.scale(), "{}", e.norm());
            assert!(e.mg > 0.0 && e.fc > 0.0);
        }
    }

    /// With both contacts on one line (equal angles) the race-control speeds reduce to the
    /// rigid rolling kinematics of docs/physics.md §1: cage `omega (1 - gamma)/2` whatever the
    /// attitude, and with `beta = alpha` the ball spin `dm/(2D) (1 - gamma^2) omega`.
    #[test]
    fn equal_angles_reduce_to_rolling_kinematics() {
        let m = model("218");
        let b = m.bearing.clone();
        let w = 1000.0;
        for alpha in [0.2f64, 0.7] {
            let n = [alpha.sin(), alpha.cos()];
            let la = m.geo.ri_free + m.geo.ro_free + 10e-6;
            let a = [n[0] * la, n[1] * la];
            let x = m.geo.static_position(a);
            let e = m.geo.eval::<0>(w, x, a);
            assert!((e.alpha_i() - alpha).abs() < 1e-12 && (e.alpha_o() - alpha).abs() < 1e-12);
            let k = crate::geometry::kinematics_at(&b, alpha, w, 0.0);
            assert!((e.wm - k.cage_speed).abs() < 1e-9 * w);
            let g = b.d * alpha.cos() / b.dm;
            let c = (alpha - e.beta()).cos();
            let spin = b.dm / (2.0 * b.d) * (1.0 - g * g) * w / c;
            assert!((e.wr + spin).abs() < 1e-9 * spin, "{} {}", e.wr, spin);
        }
    }

    /// A ball on the plane of symmetry of a radially loaded bearing (axial groove offset
    /// ~1e-31 m from rounding, its Newton root at a subnormal axial position) with the
    /// inner contact open: the gyroscopic couple is subnormal, and `1/|F_base|` overflowed
    /// to inf (`0 * inf = NaN` in the forces: the 6205-qs work-precision case failed).
    #[test]
    fn subnormal_couple_gives_finite_forces() {
        let m = model("6205");
        let g = &m.geo;
        let w = 183.259571;
        let a = [-3.0201277401483466e-31, g.ro_free + g.ri_free - 5e-6];
        let x = [4.836626e-317, g.ro_free + 1e-7];
        let e = g.eval::<4>(w, x, a);
        for d in [e.g[0], e.g[1], e.fa, e.fr, e.m] {
            assert!(
                d.v.is_finite() && d.d.iter().all(|v| v.is_finite()),
                "{e:?}"
            );
        }
        for full in [false, true] {
            let mut st = BallState::default();
            let s = g.solve(w, a, &mut st, full).unwrap();
            assert!(s.f.iter().all(|v| v.is_finite()), "{s:?}");
            // The inner contact is open: nothing reaches the shaft.
            assert!(s.f.iter().all(|v| v.abs() < 1e-9), "{s:?}");
        }
    }

    /// A warm start far through the races (a ball state left 1e14 m out by a ring Newton
    /// wandering off) where the forces overflow: the residual norm is infinite, and with
    /// it the force scale of the tolerance, so `inf <= inf` passed as converged and the
    /// state stayed there (tests/no_alloc.rs's load-driven 6205 scene failed its static
    /// start). Here the inner groove centre is pushed past the ball: that was degenerate
    /// kinematics, infinite again from the static start, so an error; since the loose
    /// ball's inner contact faces the raceway (issue #38 item 5) the restart finds the
    /// answer: the ball on the outer race under its centrifugal force, nothing on the
    /// shaft. Never the warm start's overflowing state.
    #[test]
    fn overflowing_warm_start_is_not_an_answer() {
        let m = model("6205");
        let g = &m.geo;
        let a = [0.0, 7.71684196747542e-5];
        for full in [false, true] {
            let mut st = BallState {
                x: [0.0, 128813060134693.25],
                a,
                dxda: [[0.0; 2]; 2],
                warm: true,
            };
            let s = g.solve(183.26, a, &mut st, full).unwrap();
            assert!(s.f.iter().all(|v| v.abs() < 1e-9), "{s:?}");
            let on_outer = st.x[1] - g.ro_free;
            assert!(
                st.x[0] == 0.0 && on_outer > 0.0 && on_outer < 1e-6,
                "{st:?}"
            );
        }
    }
}
