//! Ring on massless balls (docs/physics.md §5.1; Sunnersjö, *J. Sound Vib.* 58(3) 1978; Harsha,
//! *J. Sound Vib.* 290 (2006); study \[4\]).
//!
//! Balls carry no inertia; ball `j` sits at `psi_j = theta_c + 2 pi j / Z`, the cage angle
//! `theta_c` turning at the kinematic cage speed. Two geometries:
//!
//! - **2-DOF radial**: `delta_j = x cos psi_j + y sin psi_j - Pd/2`, load along the radius.
//! - **5-DOF Jones geometry** with no ball inertia (`omega_m = 0`): the inner groove
//!   curvature centre sits at `A1 = A1_0 + z + Ri (rx sin psi - ry cos psi)` axially and
//!   `A2 = A2_0 + x cos psi + y sin psi` radially from the outer one; a massless ball makes
//!   both contacts collinear, so the total approach is `delta = |A| - A` along the unit
//!   vector `n = A / |A|` (contact angle `atan2(A1, A2)`).
//!
//! Load `Q = K_n delta^1.5` for `delta > 0` with `K_n` the series constant of the inner
//! and outer contacts at the nominal contact angle (massless-ball, low-speed model; the
//! quasi-static level carries the angle dependence). The force on the shaft is
//! `-sum_j Q_j grad(delta_j)`, a gradient, so the stiffness matrix is symmetric:
//! `K = sum_j [Q'(delta_j) g g^T + Q_j H_j]` with `g = J^T n`, `H = J^T (I - n n^T) J / |A|`,
//! `J = d(A1, A2)/dq`.
//!
//! Contact damping `c d(delta)/dt` acts on loaded balls only, blended in over the first
//! `DAMPING_RAMP` of approach so the force stays continuous at contact onset (a
//! Hunt–Crossley-like regularisation; docs/physics.md §N1.3).
//!
//! Effects (all off by default, and then the arithmetic is exactly the plain model's): a
//! per-ball deflection offset (defects and waviness, `crate::models::effects`), fixed ball
//! azimuth offsets (spacing scatter), and an EHL film in every ball contact
//! (`crate::lubrication`: film in series with Hertz, squeeze damping in parallel, the
//! damping blended in over `DAMPING_RAMP` of Hertz approach like the contact damping).

pub mod elements;
pub mod level;
pub mod roller_effects;
pub mod roller_loads;
#[cfg(test)]
mod tests;

use crate::contact::{series_constant, BallRaceContacts, PointContact};
use crate::geometry::Bearing;
use crate::lubrication::{FilmAtSpeed, FilmModel, Lubricant};
use std::f64::consts::PI;

/// Approach over which contact damping is blended in, m.
pub const DAMPING_RAMP: f64 = 1e-7;

/// Radial (2) or full (5) degrees of freedom.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RingDof {
    /// x, y.
    Two,
    /// x, y, z, rx, ry.
    Five,
}

/// The sine and cosine of the cage angle, once per evaluation: the `libm` crate's
/// `sincos` (musl's, from FreeBSD's msun/fdlibm: Cody–Waite reduction by π/2 below 2^20
/// π/2, then the `__sin`/`__cos` kernel polynomials; documented error below 1 ulp), which
/// differs from the platform's `f64::sin_cos` in the last bit of about 3 % of angles (test
/// `cage_sin_cos_is_within_an_ulp_of_the_platforms`) and costs 8.2 ns against 13.0
/// (glibc's `__sincos_fma` on this machine's CPU; `cargo bench --bench forces`).
#[inline]
pub fn cage_sin_cos(theta: f64) -> (f64, f64) {
    libm::sincos(theta)
}

/// A deflection offset per ball added to `delta_j` (defects subtract, waviness adds):
/// `offset(j, psi_j, t)` for ball `j` at azimuth `psi_j`; `None` costs nothing.
pub type Profile<'a> = Option<&'a dyn Fn(usize, f64, f64) -> f64>;

/// What one evaluation returns.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RingEval {
    /// Force and moment on the shaft `(Fx, Fy, Fz, Mx, My)`.
    pub wrench: [f64; 5],
    /// Stiffness `-dF/dq` (filled when asked; not to be read otherwise).
    pub k: [[f64; 5]; 5],
    /// Damping `-dF/dv` (filled when asked; not to be read otherwise).
    pub c: [[f64; 5]; 5],
    /// Balls in contact.
    pub loaded: usize,
    /// Largest ball load, N.
    pub max_load: f64,
    /// Thinnest EHL film over the loaded balls, m (0 without a film or a loaded ball;
    /// filled with the matrices, when `jac` is asked).
    pub film_min: f64,
}

/// Derivatives of the wrench `(Fx, Fy, Fz, Mx, My)` on the shaft
/// ([`RingModel::wrench_jacobian`]), `[row][column]`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RingJacobian {
    /// `d wrench / d q`: minus the stiffness, and the damping force's own dependence on
    /// the displacement (the damping ramp and the turning of the contact normal).
    pub dq: [[f64; 5]; 5],
    /// `d wrench / d v`: minus the damping matrix.
    pub dv: [[f64; 5]; 5],
    /// `d wrench / d theta_c` (the cage angle; every ball turns with it).
    pub dtheta: [f64; 5],
}

/// Where the ring model is evaluated: cage angle `theta_c` (rad) and speed `omega_c`
/// (rad/s), inner-ring displacement `q` and velocity `v` (m, rad; m/s, rad/s), time `t` (s,
/// for a profile that moves).
#[derive(Debug, Clone, Copy)]
pub struct RingAt<'a> {
    /// Cage angle, rad.
    pub theta_c: f64,
    /// Cage speed, rad/s.
    pub omega_c: f64,
    /// Displacement `(x, y, z, rx, ry)`.
    pub q: &'a [f64; 5],
    /// Velocity.
    pub v: &'a [f64; 5],
    /// Time, s.
    pub t: f64,
}

/// The ring-on-massless-balls force law of one bearing.
#[derive(Debug, Clone)]
pub struct RingModel {
    dof: RingDof,
    z: usize,
    kn: f64,
    pd: f64,
    a: f64,
    a10: f64,
    a20: f64,
    ri: f64,
    damping: f64,
    dm: f64,
    inner: PointContact,
    outer: PointContact,
    /// Semi-axis coefficients `(ca, cb)` of the inner and outer contact
    /// ([`PointContact::semi_axis_coefficients`], four cube roots), kept for the peak
    /// pressure every communication point reports.
    axes: [(f64, f64); 2],
    /// Ball azimuth offsets (empty: evenly spaced).
    spacing: Vec<f64>,
    /// `(sin, cos)` of each ball's place relative to the cage, `2 pi j / Z + spacing_j`
    /// (offset 0 when evenly spaced): ball `j`'s azimuth is the cage angle rotated by it
    /// (in every evaluation and the analytic Jacobian).
    spacing_sc: Vec<(f64, f64)>,
    /// Each ball's own `sin_cos` of its azimuth instead (the tests' reference).
    direct_angles: bool,
    /// Every evaluation through the general loop (the tests' reference for the plain
    /// 2-DOF path, [`RingModel::two_plain`]).
    general_only: bool,
    /// EHL film law (None: dry contact).
    film: Option<FilmModel>,
    /// `omega / omega_c` (kinematic), to get the shaft speed back from the cage speed.
    shaft_per_cage: f64,
}

impl RingModel {
    /// Build for bearing `b`, `dof`, contact damping `c` (N s/m per loaded ball).
    pub fn new(b: &Bearing, dof: RingDof, damping: f64) -> Self {
        let alpha = b.nominal_contact_angle();
        let BallRaceContacts { inner, outer } = BallRaceContacts::new(b, alpha);
        let (a10, a20) = b.reference_groove_offset();
        RingModel {
            dof,
            z: b.z,
            kn: series_constant(inner.kc, outer.kc),
            pd: b.pd,
            a: b.a(),
            a10,
            a20,
            ri: b.inner_groove_centre_radius(),
            damping,
            dm: b.dm,
            inner,
            outer,
            axes: [
                inner.semi_axis_coefficients(),
                outer.semi_axis_coefficients(),
            ],
            spacing: Vec::new(),
            spacing_sc: (0..b.z)
                .map(|j| (2.0 * PI / b.z as f64 * j as f64).sin_cos())
                .collect(),
            direct_angles: false,
            general_only: false,
            film: None,
            shaft_per_cage: 1.0
                / crate::geometry::kinematics::cage_speed(
                    crate::geometry::kinematics::gamma(b, alpha),
                    1.0,
                    0.0,
                ),
        }
    }

    /// Move ball `j` by `offsets[j]` rad from its even spacing (one per ball; empty: none).
    pub fn with_spacing(mut self, offsets: Vec<f64>) -> Self {
        assert!(offsets.is_empty() || offsets.len() == self.z);
        let dpsi = 2.0 * PI / self.z as f64;
        self.spacing_sc = (0..self.z)
            .map(|j| (dpsi * j as f64 + offsets.get(j).copied().unwrap_or(0.0)).sin_cos())
            .collect();
        self.spacing = offsets;
        self
    }

    /// Every ball's azimuth by its own `sin_cos` (the reference the rotations are tested
    /// against).
    #[cfg(test)]
    fn with_direct_angles(mut self) -> Self {
        self.direct_angles = true;
        self
    }

    /// Every evaluation through the general loop (the plain 2-DOF path's reference).
    #[cfg(test)]
    fn with_general_loop(mut self) -> Self {
        self.general_only = true;
        self
    }

    /// Put an EHL film of `lubricant` in every ball contact (crate::lubrication).
    pub fn with_film(mut self, lubricant: Lubricant) -> Self {
        let one_minus_gamma = 2.0 / self.shaft_per_cage;
        self.film = Some(FilmModel::new(
            lubricant,
            self.inner,
            self.outer,
            self.kn,
            self.dm,
            1.0 - one_minus_gamma,
        ));
        self
    }

    /// Number of balls.
    pub fn z(&self) -> usize {
        self.z
    }

    /// Ball `j`'s azimuth at cage angle `theta_c`, rad: the `psi` [`RingModel::eval_with`]
    /// hands to `per_ball`, with the same arithmetic.
    pub fn azimuth(&self, theta_c: f64, j: usize) -> f64 {
        let psi = theta_c + 2.0 * PI / self.z as f64 * j as f64;
        match self.spacing.get(j) {
            Some(o) => psi + o,
            None => psi,
        }
    }

    /// Series load–deflection constant `K_n`, N/m^1.5.
    pub fn kn(&self) -> f64 {
        self.kn
    }

    /// Peak Hertz pressure of a ball carrying `q` (the larger of its two contacts), Pa.
    /// The arithmetic of [`PointContact::peak_pressure`] for both contacts, with their
    /// semi-axis coefficients kept and one cube root of `q` for both: the same bits.
    pub fn peak_pressure(&self, q: f64) -> f64 {
        let q3 = q.max(0.0).cbrt();
        let p0 = |(ca, cb): (f64, f64)| {
            let (a, b) = (ca * q3, cb * q3);
            if a > 0.0 && b > 0.0 {
                1.5 * q / (PI * a * b)
            } else {
                0.0
            }
        };
        p0(self.axes[0]).max(p0(self.axes[1]))
    }

    /// Forces at `at` (cage angle and speed, ring displacement and velocity, time for the
    /// profile). With `jac` the stiffness and damping matrices are filled too.
    /// Allocation-free.
    pub fn eval(&self, at: RingAt<'_>, profile: Profile<'_>, jac: bool, out: &mut RingEval) {
        let profile_max = if profile.is_some() {
            f64::INFINITY
        } else {
            0.0
        };
        self.eval_with(at, (profile, profile_max), jac, out, |_, _, _| {});
    }

    /// [`RingModel::eval`] that also hands each loaded ball to `per_ball(j, psi_j, Q_j)`
    /// (ball index, azimuth, Hertz load): what the slow effects (wear, friction power)
    /// accumulate. Same arithmetic as `eval`; allocation-free.
    ///
    /// `profile_max` bounds the profile's offset from above (`INFINITY` when unknown, `0`
    /// without one): a ball whose rigid approach plus that bound plus the thickest film
    /// ([`FilmModel::max_film`]) is below zero carries no load whatever the profile says,
    /// so its profile and film are not evaluated. The bound is widened by a relative 1e-9
    /// and 1 fm, far above the rounding of the sums, so a ball is skipped only where the
    /// full evaluation would find it unloaded: the same results, bit for bit (test
    /// `skipping_unloaded_balls_changes_no_bit`).
    pub fn eval_with<F: FnMut(usize, f64, f64)>(
        &self,
        RingAt {
            theta_c,
            omega_c,
            q,
            v,
            t,
        }: RingAt<'_>,
        (profile, profile_max): (Profile<'_>, f64),
        jac: bool,
        out: &mut RingEval,
        per_ball: F,
    ) {
        let args = (
            theta_c,
            omega_c,
            q,
            v,
            t,
            (profile, profile_max),
            out,
            per_ball,
        );
        if self.dof == RingDof::Two && !self.direct_angles && !self.general_only {
            let plain = profile.is_none() && self.film.is_none() && self.spacing.is_empty();
            return match (plain, jac) {
                (true, false) => self.two::<true, false, F>(args),
                (true, true) => self.two::<true, true, F>(args),
                (false, false) => self.two::<false, false, F>(args),
                (false, true) => self.two::<false, true, F>(args),
            };
        }
        match (self.dof, jac) {
            (RingDof::Two, false) => self.general::<false, false, F>(args),
            (RingDof::Two, true) => self.general::<false, true, F>(args),
            (RingDof::Five, false) => self.general::<true, false, F>(args),
            (RingDof::Five, true) => self.general::<true, true, F>(args),
        }
    }

    /// The exact derivatives of [`RingModel::eval`]'s wrench (dry contacts, no profile)
    /// with respect to the displacement `q`, the velocity `v` and the cage angle
    /// `theta_c`, for an implicit integrator's Jacobian; `false` with an EHL film, whose
    /// squeeze damping's derivative the film law does not give (the caller then
    /// differences). Per loaded ball, with `fn = Q(delta) + c(delta) rate` and
    /// `W = -sum fn g` (`g = d delta / d q`):
    ///
    /// - `dW/dq = -sum [(Q' + c' rate) g g^T + fn H + c g (d rate / d q)^T]`, `H = dg/dq`
    ///   (zero in 2-DOF; `J^T (I - n n^T) J / l` in 5-DOF), which is `-K` plus the damping
    ///   force's terms (the ramp `c' = c / DAMPING_RAMP` below the ramp, the normal turning
    ///   with `q`, the cage-speed part of the approach rate);
    /// - `dW/dv = -sum c g g^T = -C`;
    /// - `dW/dtheta`: the same chain through the ball azimuth `psi = theta_c + ...`.
    ///
    /// Checked against central differences of the wrench (test
    /// `wrench_jacobian_matches_central_differences`).
    pub fn wrench_jacobian(
        &self,
        theta_c: f64,
        omega_c: f64,
        q: &[f64; 5],
        v: &[f64; 5],
        out: &mut RingJacobian,
    ) -> bool {
        if self.film.is_some() {
            return false;
        }
        *out = RingJacobian::default();
        let (cage_s, cage_c) = cage_sin_cos(theta_c);
        let nq = match self.dof {
            RingDof::Two => 2,
            RingDof::Five => 5,
        };
        for j in 0..self.z {
            // The cage angle rotated by the ball's place (a Jacobian needs no bit-for-bit
            // agreement with the right-hand side's rotations).
            let (sa, ca) = self.spacing_sc[j];
            let (s, c) = (cage_s * ca + cage_c * sa, cage_c * ca - cage_s * sa);
            // Per geometry: delta, g, rate, d(rate)/dq, H (as a closure over index pairs),
            // and the azimuth derivatives d(delta)/dpsi, dg/dpsi, d(rate)/dpsi.
            let (delta, g, rate, drate_dq, dd_dpsi, dg_dpsi, drate_dpsi, geo) = match self.dof {
                RingDof::Two => {
                    let g = [c, s, 0.0, 0.0, 0.0];
                    let gp = [-s, c, 0.0, 0.0, 0.0];
                    let delta = q[0] * c + q[1] * s - 0.5 * self.pd;
                    let qg = q[0] * c + q[1] * s;
                    let qgp = q[0] * gp[0] + q[1] * gp[1];
                    let vgp = v[0] * gp[0] + v[1] * gp[1];
                    let rate = v[0] * c + v[1] * s + omega_c * qgp;
                    let drate_dq = [omega_c * gp[0], omega_c * gp[1], 0.0, 0.0, 0.0];
                    let drate_dpsi = vgp - omega_c * qg;
                    (delta, g, rate, drate_dq, qgp, gp, drate_dpsi, None)
                }
                RingDof::Five => {
                    let ri = self.ri;
                    let a = [
                        self.a10 + q[2] + ri * (q[3] * s - q[4] * c),
                        self.a20 + q[0] * c + q[1] * s,
                    ];
                    let l = (a[0] * a[0] + a[1] * a[1]).sqrt();
                    let n = [a[0] / l, a[1] / l];
                    let jm = [[0.0, 0.0, 1.0, ri * s, -ri * c], [c, s, 0.0, 0.0, 0.0]];
                    // dJ/dpsi, dA/dpsi, d2A/dpsi2.
                    let jp = [[0.0, 0.0, 0.0, ri * c, ri * s], [-s, c, 0.0, 0.0, 0.0]];
                    let ap = [ri * (q[3] * c + q[4] * s), -q[0] * s + q[1] * c];
                    let app = [ri * (-q[3] * s + q[4] * c), -q[0] * c - q[1] * s];
                    let dot5 =
                        |x: &[f64; 5], y: &[f64; 5]| (0..5).map(|k| x[k] * y[k]).sum::<f64>();
                    let da = [
                        dot5(&jm[0], v) + omega_c * ap[0],
                        dot5(&jm[1], v) + omega_c * ap[1],
                    ];
                    let g: [f64; 5] = std::array::from_fn(|k| jm[0][k] * n[0] + jm[1][k] * n[1]);
                    let rate = n[0] * da[0] + n[1] * da[1];
                    // P = I - n n^T; P da / l and P A_psi / l.
                    let proj = |x: [f64; 2]| {
                        let d = n[0] * x[0] + n[1] * x[1];
                        [(x[0] - d * n[0]) / l, (x[1] - d * n[1]) / l]
                    };
                    let pda = proj(da);
                    let pap = proj(ap);
                    let drate_dq: [f64; 5] = std::array::from_fn(|k| {
                        jm[0][k] * pda[0]
                            + jm[1][k] * pda[1]
                            + omega_c * (jp[0][k] * n[0] + jp[1][k] * n[1])
                    });
                    let dd_dpsi = n[0] * ap[0] + n[1] * ap[1];
                    let dg_dpsi: [f64; 5] = std::array::from_fn(|k| {
                        jp[0][k] * n[0] + jp[1][k] * n[1] + jm[0][k] * pap[0] + jm[1][k] * pap[1]
                    });
                    let drate_dpsi = pap[0] * da[0]
                        + pap[1] * da[1]
                        + n[0] * (dot5(&jp[0], v) + omega_c * app[0])
                        + n[1] * (dot5(&jp[1], v) + omega_c * app[1]);
                    let p = [
                        [1.0 - n[0] * n[0], -n[0] * n[1]],
                        [-n[0] * n[1], 1.0 - n[1] * n[1]],
                    ];
                    (
                        l - self.a,
                        g,
                        rate,
                        drate_dq,
                        dd_dpsi,
                        dg_dpsi,
                        drate_dpsi,
                        Some((jm, p, l)),
                    )
                }
            };
            if delta <= 0.0 {
                continue;
            }
            let sq = delta.sqrt();
            let (load, dload) = (self.kn * delta * sq, 1.5 * self.kn * sq);
            let (cd, dcd) = if delta < DAMPING_RAMP {
                (
                    self.damping * delta / DAMPING_RAMP,
                    self.damping / DAMPING_RAMP,
                )
            } else {
                (self.damping, 0.0)
            };
            let fn_ = load + cd * rate;
            let dfn_ddelta = dload + dcd * rate;
            for r in 0..nq {
                for col in 0..nq {
                    let h = geo.map_or(0.0, |(jm, p, l): ([[f64; 5]; 2], [[f64; 2]; 2], f64)| {
                        let mut h = 0.0;
                        for a in 0..2 {
                            for b in 0..2 {
                                h += jm[a][r] * p[a][b] * jm[b][col];
                            }
                        }
                        h / l
                    });
                    out.dq[r][col] -=
                        dfn_ddelta * g[r] * g[col] + fn_ * h + cd * g[r] * drate_dq[col];
                    out.dv[r][col] -= cd * g[r] * g[col];
                }
                out.dtheta[r] -= (dfn_ddelta * dd_dpsi + cd * drate_dpsi) * g[r] + fn_ * dg_dpsi[r];
            }
        }
        true
    }

    /// The film at cage speed `omega_c` (`None`: dry) and the rigid approach at or below
    /// which a ball carries no load, whatever the profile (bounded above by
    /// `profile_max`) and the film add ([`RingModel::eval_with`]; NaN bounds skip nothing).
    #[inline]
    fn film_and_bound(
        &self,
        omega_c: f64,
        profile_max: f64,
    ) -> (Option<(&FilmModel, FilmAtSpeed)>, f64) {
        let film = (self.film.as_ref()).map(|f| (f, f.at_speed(omega_c * self.shaft_per_cage)));
        let film_max = film.as_ref().map_or(0.0, |(f, fs)| f.max_film(fs));
        (film, -(profile_max + film_max) * (1.0 + 1e-9) - 1e-15)
    }

    /// A ball's contact at approach `delta` (profile included): `(Q, dQ/d delta, c)` with
    /// `c` the blended damping coefficient, or `None` when it carries no load. Dry: Hertz
    /// `Q = K_n delta^1.5`; with a film (`crate::lubrication`), the film in series with
    /// Hertz and squeeze damping in parallel.
    #[inline(always)]
    fn ball_law(
        &self,
        film: Option<&(&FilmModel, FilmAtSpeed)>,
        delta: f64,
    ) -> Option<(f64, f64, f64)> {
        if let Some((film, fs)) = film {
            let b = film.solve(fs, delta)?;
            let blend = (b.hertz_approach / DAMPING_RAMP).min(1.0);
            return Some((b.load, b.stiffness, (self.damping + b.damping) * blend));
        }
        if delta <= 0.0 {
            return None;
        }
        let sq = delta.sqrt();
        // `(delta / DAMPING_RAMP).min(1.0)`: the division is correctly rounded and
        // monotonic, so at or past the ramp it is at least 1 and the blend is 1.
        let blend = if delta >= DAMPING_RAMP {
            1.0
        } else {
            (delta / DAMPING_RAMP).min(1.0)
        };
        Some((
            self.kn * delta * sq,
            1.5 * self.kn * sq,
            self.damping * blend,
        ))
    }

    /// [`RingModel::eval_with`]'s general loop, for either geometry (`FIVE`: the 5-DOF
    /// Jones geometry, else the 2-DOF radial one) with or without the matrices (`JAC`),
    /// both switches fixed at compile time so the per-coordinate loops have fixed bounds.
    #[inline]
    fn general<const FIVE: bool, const JAC: bool, F: FnMut(usize, f64, f64)>(
        &self,
        (theta_c, omega_c, q, v, t, (profile, profile_max), out, mut per_ball): EvalArgs<'_, F>,
    ) {
        let jac = JAC;
        *out = RingEval::default();
        let (film, unloaded_below) = self.film_and_bound(omega_c, profile_max);
        let dpsi = 2.0 * PI / self.z as f64;
        let even = self.spacing.is_empty();
        // Each ball: the cage angle rotated by the ball's precomputed place (evenly spaced
        // or with offsets), one rotation (~1 ulp, below the rounding of `theta_c + dpsi j`
        // at large angles); the rotations are independent, so they overlap in the CPU
        // where a recurrence from ball to ball would chain them.
        // Coordinates a ball's normal moves: 2-DOF, x and y only (the gradient's other
        // entries are zeros, whose products add nothing to the +0 sums of the stiffness and
        // damping, and the wrench's other components are set to zero below).
        let nq = if FIVE { 5 } else { 2 };
        let (st, ct) = cage_sin_cos(theta_c);
        for (j, &(sj, cj)) in self.spacing_sc.iter().enumerate() {
            let psi = theta_c + dpsi * j as f64;
            let psi = if even { psi } else { psi + self.spacing[j] };
            let (s, c) = if self.direct_angles {
                psi.sin_cos()
            } else {
                (st * cj + ct * sj, ct * cj - st * sj)
            };
            // g: gradient of delta w.r.t. q; rate: d(delta)/dt; plus what the Hessian needs.
            let (delta, g, rate, n, l, jm) = match if FIVE { RingDof::Five } else { RingDof::Two } {
                RingDof::Two => {
                    let delta = q[0] * c + q[1] * s - 0.5 * self.pd;
                    let g = [c, s, 0.0, 0.0, 0.0];
                    let rate = v[0] * c + v[1] * s + omega_c * (-q[0] * s + q[1] * c);
                    (delta, g, rate, [0.0, 1.0], f64::INFINITY, [[0.0; 5]; 2])
                }
                RingDof::Five => {
                    let a1 = self.a10 + q[2] + self.ri * (q[3] * s - q[4] * c);
                    let a2 = self.a20 + q[0] * c + q[1] * s;
                    // Both within millimetres: no overflow for `hypot` to guard against.
                    let l = (a1 * a1 + a2 * a2).sqrt();
                    let n = [a1 / l, a2 / l];
                    let jm = [
                        [0.0, 0.0, 1.0, self.ri * s, -self.ri * c],
                        [c, s, 0.0, 0.0, 0.0],
                    ];
                    let g: [f64; 5] = std::array::from_fn(|k| jm[0][k] * n[0] + jm[1][k] * n[1]);
                    let da1 = v[2]
                        + self.ri * (v[3] * s - v[4] * c)
                        + omega_c * self.ri * (q[3] * c + q[4] * s);
                    let da2 = v[0] * c + v[1] * s + omega_c * (-q[0] * s + q[1] * c);
                    (l - self.a, g, n[0] * da1 + n[1] * da2, n, l, jm)
                }
            };
            if delta <= unloaded_below {
                continue;
            }
            let delta = delta + profile.map_or(0.0, |p| p(j, psi, t));
            let Some((load, dload, cd)) = self.ball_law(film.as_ref(), delta) else {
                continue;
            };
            per_ball(j, psi, load);
            let fn_ = load + cd * rate;
            for (w, gk) in out.wrench[..nq].iter_mut().zip(g) {
                *w -= fn_ * gk;
            }
            out.loaded += 1;
            out.max_load = out.max_load.max(load);
            if jac {
                for r in 0..nq {
                    for col in 0..nq {
                        out.k[r][col] += dload * g[r] * g[col];
                        out.c[r][col] += cd * g[r] * g[col];
                    }
                }
                if FIVE {
                    // Geometric term Q J^T (I - n n^T) J / l.
                    let p = [
                        [1.0 - n[0] * n[0], -n[0] * n[1]],
                        [-n[0] * n[1], 1.0 - n[1] * n[1]],
                    ];
                    // `h = sum_ab J[a][r] P[a][b] J[b][col]` from +0 has one structurally
                    // non-zero term: row 0 of J (the axial offset) moves z, rx, ry only,
                    // row 1 (the radial offset) x, y only. The other three are +-0 and leave
                    // a sum from +0 as the lone term would (x + +-0 = x for x != 0, and a
                    // sum from +0 of zeros is +0), so `0 + term` has the full sum's bits.
                    for r in 0..5 {
                        let a = (r < 2) as usize;
                        for col in 0..5 {
                            let b = (col < 2) as usize;
                            let h = 0.0 + jm[a][r] * p[a][b] * jm[b][col];
                            out.k[r][col] += load * h / l;
                        }
                    }
                }
            }
        }
        // The thinnest film is the most loaded ball's (it thins with the load).
        if let (true, Some((film, fs))) = (jac && out.loaded > 0, &film) {
            out.film_min = film.min_film(fs, out.max_load);
        }
        if !FIVE {
            // Moments and axial force are not modelled by the radial geometry.
            for k in 2..5 {
                out.wrench[k] = 0.0;
            }
        }
    }
}

/// [`RingModel::eval_with`]'s arguments but `jac`, as its loops take them.
type EvalArgs<'a, F> = (
    f64,
    f64,
    &'a [f64; 5],
    &'a [f64; 5],
    f64,
    (Profile<'a>, f64),
    &'a mut RingEval,
    F,
);

impl RingModel {
    /// [`RingModel::eval_with`] of the 2-DOF ring: the general loop's arithmetic,
    /// operation for operation (ball places, unloaded-ball skip, profile, film or dry
    /// contact, damping blend), with the ball's gradient `(cos psi, sin psi)`, the force
    /// sums and (with `JAC`) the 2×2 stiffness and damping sums kept in registers instead
    /// of five-wide arrays, and only the fields the evaluation fills written (without
    /// `JAC`, `k` and `c` are left as they were). The results are the general loop's bit
    /// for bit (test `two_dof_is_the_general_loop_bit_for_bit`). Every right-hand side
    /// and output of a 2-DOF ring comes through here.
    ///
    /// `PLAIN` (evenly spaced balls, dry contacts, no profile) drops those branches at
    /// compile time, and with them the unloaded-ball bound: for a dry ball without a
    /// profile the general loop's two tests (`delta <= -1e-15`, then `delta + 0.0 <= 0`)
    /// pass the same balls as `delta <= 0`, NaN included.
    #[inline]
    fn two<const PLAIN: bool, const JAC: bool, F: FnMut(usize, f64, f64)>(
        &self,
        (theta_c, omega_c, q, v, t, (profile, profile_max), out, mut per_ball): EvalArgs<'_, F>,
    ) {
        let (film, unloaded_below) = if PLAIN {
            (None, -1e-15)
        } else {
            self.film_and_bound(omega_c, profile_max)
        };
        let dpsi = 2.0 * PI / self.z as f64;
        let even = PLAIN || self.spacing.is_empty();
        let half_pd = 0.5 * self.pd;
        let (q0, q1, v0, v1) = (q[0], q[1], v[0], v[1]);
        let (st, ct) = cage_sin_cos(theta_c);
        let (mut fx, mut fy) = (0.0, 0.0);
        let (mut loaded, mut max_load) = (0, 0.0_f64);
        // Row-major [xx, xy, yx, yy] sums of K and C (xy and yx round differently).
        let (mut k, mut cm) = ([0.0; 4], [0.0; 4]);
        for (j, &(sa, ca)) in self.spacing_sc.iter().enumerate() {
            let psi = theta_c + dpsi * j as f64;
            let psi = if even { psi } else { psi + self.spacing[j] };
            let (sj, cj) = (st * ca + ct * sa, ct * ca - st * sa);
            let delta = q0 * cj + q1 * sj - half_pd;
            if !PLAIN && delta <= unloaded_below {
                continue;
            }
            let rate = v0 * cj + v1 * sj + omega_c * (-q0 * sj + q1 * cj);
            let delta = if PLAIN {
                delta
            } else {
                delta + profile.map_or(0.0, |p| p(j, psi, t))
            };
            let Some((load, dload, cd)) = self.ball_law(film.as_ref(), delta) else {
                continue;
            };
            per_ball(j, psi, load);
            let fn_ = load + cd * rate;
            fx -= fn_ * cj;
            fy -= fn_ * sj;
            loaded += 1;
            max_load = max_load.max(load);
            if JAC {
                let g = [cj, sj];
                for r in 0..2 {
                    for col in 0..2 {
                        k[2 * r + col] += dload * g[r] * g[col];
                        cm[2 * r + col] += cd * g[r] * g[col];
                    }
                }
            }
        }
        out.wrench = [fx, fy, 0.0, 0.0, 0.0];
        out.loaded = loaded;
        out.max_load = max_load;
        out.film_min = 0.0;
        if JAC {
            out.k = [[0.0; 5]; 5];
            out.c = [[0.0; 5]; 5];
            for r in 0..2 {
                for col in 0..2 {
                    out.k[r][col] = k[2 * r + col];
                    out.c[r][col] = cm[2 * r + col];
                }
            }
            // The thinnest film is the most loaded ball's (it thins with the load).
            if let (true, Some((film, fs))) = (loaded > 0, &film) {
                out.film_min = film.min_film(fs, max_load);
            }
        }
    }
}
