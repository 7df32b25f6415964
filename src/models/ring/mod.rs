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

pub mod level;

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

    /// Forces at cage angle `theta_c` (rad), cage speed `omega_c` (rad/s), ring
    /// displacement `q` and velocity `v`, time `t` (for the profile). With `jac` the
    /// stiffness and damping matrices are filled too. Allocation-free.
    #[allow(clippy::too_many_arguments)]
    pub fn eval(
        &self,
        theta_c: f64,
        omega_c: f64,
        q: &[f64; 5],
        v: &[f64; 5],
        t: f64,
        profile: Profile<'_>,
        jac: bool,
        out: &mut RingEval,
    ) {
        let profile_max = if profile.is_some() {
            f64::INFINITY
        } else {
            0.0
        };
        self.eval_with(
            theta_c,
            omega_c,
            q,
            v,
            t,
            (profile, profile_max),
            jac,
            out,
            |_, _, _| {},
        );
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
    #[allow(clippy::too_many_arguments)]
    pub fn eval_with<F: FnMut(usize, f64, f64)>(
        &self,
        theta_c: f64,
        omega_c: f64,
        q: &[f64; 5],
        v: &[f64; 5],
        t: f64,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::preset;

    /// The kept semi-axis coefficients give each contact's peak pressure bit for bit.
    #[test]
    fn peak_pressure_is_the_contacts_own_bit_for_bit() {
        for name in ["6205", "7008ce"] {
            let b = preset(name).unwrap().build().unwrap();
            let m = RingModel::new(&b, RingDof::Five, 0.0);
            for q in [-1.0, 0.0, 1e-300, 1e-3, 0.37, 1.0, 123.456, 1e4, 3.3e6] {
                let own = m.inner.peak_pressure(q).max(m.outer.peak_pressure(q));
                assert_eq!(
                    m.peak_pressure(q).to_bits(),
                    own.to_bits(),
                    "{name} q = {q}"
                );
            }
        }
    }

    fn eval(m: &RingModel, q: [f64; 5], theta: f64) -> RingEval {
        let mut out = RingEval::default();
        m.eval(theta, 0.0, &q, &[0.0; 5], 0.0, None, true, &mut out);
        out
    }

    /// The 2-DOF ring's own loop ([`RingModel::two`]), with and without the matrices, is
    /// the general loop's bit for bit in the wrench, the stiffness and damping matrices,
    /// the loaded count, the largest load, the thinnest film and the loads handed to
    /// `per_ball`: plain, with scattered balls, an EHL film, a profile (bounded, unbounded
    /// and without bound) and all three; over displacements from free to heavily loaded,
    /// approaches straddling zero and the damping ramp, signed velocities and cage speeds,
    /// cage angles up to 10^4 rad, zero damping, and non-finite inputs.
    #[test]
    fn two_dof_is_the_general_loop_bit_for_bit() {
        let b = preset("6205").unwrap().build().unwrap();
        let half_pd = 0.5 * b.pd;
        let mut qs: Vec<[f64; 2]> = vec![[0.0, 0.0], [f64::NAN, 0.0], [f64::INFINITY, 0.0]];
        // A ball at psi = 0 exactly at, just inside and just past contact and the ramp.
        for d in [
            0.0,
            1e-15,
            -1e-15,
            1e-7,
            1e-7 * (1.0 + 1e-15),
            0.999e-7,
            5e-6,
        ] {
            qs.push([half_pd + d, 0.0]);
        }
        let mut r = 0x9e37_79b9_7f4a_7c15_u64;
        let mut rand = || {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            (r >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..150 {
            qs.push([3e-5 * rand(), 3e-5 * rand()]);
        }
        let amp = 0.3e-6;
        let wavy = |j: usize, psi: f64, t: f64| amp * (5.0 * psi + j as f64 + 40.0 * t).sin();
        let offsets: Vec<f64> = (0..b.z).map(|j| 2e-2 * (j as f64 - 3.3)).collect();
        let lube = crate::lubrication::Lubricant::study2();
        let mut checked = 0;
        for damping in [0.0, 3000.0] {
            let base = RingModel::new(&b, RingDof::Two, damping);
            let models = [
                base.clone(),
                base.clone().with_spacing(offsets.clone()),
                base.clone().with_film(lube),
                base.clone().with_spacing(offsets.clone()).with_film(lube),
            ];
            for (mi, m) in models.iter().enumerate() {
                let reference = m.clone().with_general_loop();
                for (i, q) in qs.iter().enumerate() {
                    let q = [q[0], q[1], 0.0, 0.0, 0.0];
                    let v = [0.3 * rand(), 0.3 * rand(), 0.0, 0.0, 0.0];
                    let theta = [0.0, 0.37 * i as f64, 1e4 + 0.1 * rand()][i % 3];
                    let wc = [0.0, 80.0, -300.0 * rand()][i % 3];
                    let t = 1e-3 * i as f64;
                    let profiles: [(Profile<'_>, f64); 4] = [
                        (None, 0.0),
                        (Some(&wavy), amp),
                        (Some(&wavy), f64::INFINITY),
                        (Some(&wavy), f64::NAN),
                    ];
                    for (profile, jac) in profiles.iter().flat_map(|p| [(p, false), (p, true)]) {
                        let run = |m: &RingModel| {
                            let mut out = RingEval::default();
                            let mut loads = Vec::new();
                            m.eval_with(
                                theta,
                                wc,
                                &q,
                                &v,
                                t,
                                *profile,
                                jac,
                                &mut out,
                                |j, psi, l| loads.push((j, psi.to_bits(), l.to_bits())),
                            );
                            (out, loads)
                        };
                        let ((own, lo), (general, lg)) = (run(m), run(&reference));
                        let bits = |e: &RingEval| {
                            let mut b: Vec<u64> = e.wrench.map(f64::to_bits).to_vec();
                            b.extend([e.max_load.to_bits(), e.film_min.to_bits(), e.loaded as u64]);
                            if jac {
                                b.extend(e.k.iter().chain(&e.c).flatten().map(|x| x.to_bits()));
                            }
                            b
                        };
                        let at = format!("model {mi} q {q:?} v {v:?} at {theta}, jac {jac}");
                        assert_eq!(bits(&own), bits(&general), "{at}");
                        assert_eq!(lo, lg, "{at}");
                        checked += (own.loaded > 0) as usize;
                    }
                }
            }
        }
        assert!(checked > 2000, "{checked} loaded cases");
    }

    /// The 5-DOF geometric stiffness term keeps one of its four products per entry (the
    /// other three are structural zeros of `J`): `0 + term` has the bits of the full sum
    /// from +0, over contact normals in every quadrant, cage angles where `sin` or `cos`
    /// is tiny, and signed zeros.
    #[test]
    fn geometric_term_with_its_lone_product_is_the_full_sum() {
        let ri = 0.0231;
        let mut cases = 0;
        for k in 0..2000 {
            let th = 0.0123 * k as f64 - 3.0;
            let (s, c) = if k % 100 == 0 {
                (0.0, -1.0)
            } else {
                th.sin_cos()
            };
            let phi = 0.731 * k as f64;
            let (mut n0, mut n1) = phi.sin_cos();
            if k % 7 == 0 {
                n0 = -0.0;
            }
            if k % 11 == 0 {
                n1 = 0.0;
            }
            let jm = [[0.0, 0.0, 1.0, ri * s, -ri * c], [c, s, 0.0, 0.0, 0.0]];
            let p = [[1.0 - n0 * n0, -n0 * n1], [-n0 * n1, 1.0 - n1 * n1]];
            for r in 0..5 {
                for col in 0..5 {
                    let mut full = 0.0;
                    for a in 0..2 {
                        for b in 0..2 {
                            full += jm[a][r] * p[a][b] * jm[b][col];
                        }
                    }
                    let (a, b) = ((r < 2) as usize, (col < 2) as usize);
                    let lone = 0.0 + jm[a][r] * p[a][b] * jm[b][col];
                    assert_eq!(lone.to_bits(), full.to_bits(), "{k} ({r}, {col})");
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 50_000);
    }

    /// The wrench's analytic derivatives ([`RingModel::wrench_jacobian`]) against central
    /// differences of the wrench itself, 2-DOF and 5-DOF, with contact damping and a
    /// turning cage, over loaded states (balls on and past the damping ramp): every entry
    /// within 1e-5 of its column's scale. Points where a ball crosses contact or the end of
    /// the ramp within the difference step are skipped (two step sizes disagree there).
    #[test]
    fn wrench_jacobian_matches_central_differences() {
        let mut r = 0x2545_f491_4f6c_dd1d_u64;
        let mut rand = || {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            (r >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut checked = 0;
        for (name, dof) in [("6205", RingDof::Two), ("7008ce", RingDof::Five)] {
            let b = preset(name).unwrap().build().unwrap();
            let m = RingModel::new(&b, dof, 3000.0);
            let wrench = |q: &[f64; 5], v: &[f64; 5], th: f64| {
                let mut e = RingEval::default();
                m.eval(th, 80.0, q, v, 0.0, None, false, &mut e);
                e.wrench
            };
            for case in 0..60 {
                let q = match dof {
                    RingDof::Two => [1.5e-5 * rand(), 1.5e-5 * rand(), 0.0, 0.0, 0.0],
                    RingDof::Five => [
                        8e-6 * rand(),
                        8e-6 * rand(),
                        1.5e-5 + 5e-6 * rand(),
                        2e-4 * rand(),
                        2e-4 * rand(),
                    ],
                };
                // Small velocities put some balls' approach rates near zero, large ones
                // make the damping force a good part of the load.
                let vs = if case % 2 == 0 { 1e-3 } else { 0.2 };
                let v: [f64; 5] =
                    std::array::from_fn(|k| vs * rand() * if k >= 3 { 10.0 } else { 1.0 });
                let th = 0.37 * case as f64;
                let mut jac = RingJacobian::default();
                assert!(m.wrench_jacobian(th, 80.0, &q, &v, &mut jac));
                let nq = if dof == RingDof::Two { 2 } else { 5 };
                // Columns: q_k, v_k, theta.
                for col in 0..2 * nq + 1 {
                    let fd = |h: f64| -> [f64; 5] {
                        let (mut qp, mut qm, mut vp, mut vm) = (q, q, v, v);
                        let (mut tp, mut tm) = (th, th);
                        if col < nq {
                            qp[col] += h;
                            qm[col] -= h;
                        } else if col < 2 * nq {
                            vp[col - nq] += h;
                            vm[col - nq] -= h;
                        } else {
                            tp += h;
                            tm -= h;
                        }
                        let (a, b) = (wrench(&qp, &vp, tp), wrench(&qm, &vm, tm));
                        std::array::from_fn(|k| (a[k] - b[k]) / (2.0 * h))
                    };
                    let h = if col < nq {
                        if col >= 3 {
                            1e-9
                        } else {
                            1e-12
                        }
                    } else if col < 2 * nq {
                        1e-6
                    } else {
                        1e-8
                    };
                    let (f1, f2) = (fd(h), fd(0.5 * h));
                    let an: [f64; 5] = std::array::from_fn(|k| {
                        if col < nq {
                            jac.dq[k][col]
                        } else if col < 2 * nq {
                            jac.dv[k][col - nq]
                        } else {
                            jac.dtheta[k]
                        }
                    });
                    let scale = an.iter().chain(&f1).fold(1e-30f64, |a, x| a.max(x.abs()));
                    if (0..5).any(|k| (f1[k] - f2[k]).abs() > 1e-6 * scale) {
                        continue; // a kink within the step
                    }
                    for k in 0..5 {
                        assert!(
                            (an[k] - f2[k]).abs() <= 1e-5 * scale,
                            "{name} case {case} column {col} row {k}: analytic {} vs {}",
                            an[k],
                            f2[k]
                        );
                    }
                    checked += 1;
                }
            }
        }
        assert!(checked > 500, "{checked} columns checked");
    }

    /// Zero clearance, one ball under the load line: the static radial balance
    /// `Fr = Kn sum_j (delta cos psi_j)^1.5 cos psi_j` (docs/physics.md §N5.2's construction).
    #[test]
    fn two_dof_matches_hand_sum_and_pushes_back() {
        let b = preset("209").unwrap().build().unwrap();
        let mut m = RingModel::new(&b, RingDof::Two, 0.0);
        m.pd = 0.0;
        let x = 12e-6;
        let out = eval(&m, [x, 0.0, 0.0, 0.0, 0.0], 0.0);
        let mut fr = 0.0;
        for j in 0..9 {
            let p = 2.0 * PI * j as f64 / 9.0;
            let d = x * p.cos();
            if d > 0.0 {
                fr += m.kn * d.powf(1.5) * p.cos();
            }
        }
        assert!(
            (out.wrench[0] + fr).abs() < 1e-9 * fr,
            "{} vs {}",
            out.wrench[0],
            -fr
        );
        assert!(
            out.wrench[1].abs() < 1e-9 * fr,
            "symmetric balls give no y force"
        );
        assert_eq!(out.loaded, 5); // balls at 0, ±40°, ±80°
    }

    /// The cage angle's sine and cosine are the platform's to one ulp (each component, over
    /// 200 000 angles from -3 to 143 rad and out to 10^5 rad), and not all the same bits
    /// (the share that differs is printed: `-- --nocapture`).
    #[test]
    fn cage_sin_cos_is_within_an_ulp_of_the_platforms() {
        let ulps = |a: f64, b: f64| (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs();
        let (mut differ, mut n) = (0, 0);
        let angles = (0..200_000)
            .map(|i| i as f64 * 0.000731 - 3.0)
            .chain((0..2000).map(|i| 1e5 * (i as f64 / 2000.0) + 0.3));
        for x in angles {
            let ((s, c), (s0, c0)) = (cage_sin_cos(x), x.sin_cos());
            for (a, b) in [(s, s0), (c, c0)] {
                assert!(ulps(a, b) <= 1, "{x}: {a:e} against {b:e}");
                differ += usize::from(a != b);
                n += 1;
            }
        }
        println!("cage_sin_cos: {differ} of {n} values differ from f64::sin_cos in the last bit");
        assert!(differ > 0);
    }

    /// Balls reached by rotating the cage angle by their precomputed places (evenly spaced
    /// or scattered; one `sin_cos` an evaluation) give the forces and stiffness of each
    /// ball's own `sin_cos` to 1e-12 relative, also at a cage angle of 10^4 rad.
    #[test]
    fn rotated_ball_positions_match_direct_angles() {
        let b = preset("7008ce").unwrap().build().unwrap();
        let offsets: Vec<f64> = (0..b.z).map(|j| 1e-3 * (j as f64 - 7.3)).collect();
        let pairs = [
            (
                RingModel::new(&b, RingDof::Five, 0.0),
                RingModel::new(&b, RingDof::Five, 0.0).with_direct_angles(),
            ),
            (
                RingModel::new(&b, RingDof::Five, 0.0).with_spacing(offsets.clone()),
                RingModel::new(&b, RingDof::Five, 0.0)
                    .with_spacing(offsets)
                    .with_direct_angles(),
            ),
        ];
        let q = [3e-6, -12e-6, 15e-6, 1e-4, -2e-4];
        for ((even, direct), theta) in pairs
            .iter()
            .flat_map(|p| [0.0, 0.37, 1e4 + 0.1].map(|t| (p, t)))
        {
            let (a, d) = (eval(even, q, theta), eval(direct, q, theta));
            let scale = d.wrench.iter().fold(0.0f64, |m, w| m.max(w.abs()));
            for k in 0..5 {
                assert!(
                    (a.wrench[k] - d.wrench[k]).abs() <= 1e-12 * scale,
                    "{k} at {theta}"
                );
            }
            let ks = d.k.iter().flatten().fold(0.0f64, |m, w| m.max(w.abs()));
            for (x, y) in a.k.iter().flatten().zip(d.k.iter().flatten()) {
                assert!((x - y).abs() <= 1e-12 * ks, "K at {theta}");
            }
            assert_eq!(a.loaded, d.loaded);
        }
    }

    /// The stiffness matrix is minus the derivative of the force (central differences),
    /// and symmetric, in the 5-DOF geometry under a combined load.
    #[test]
    fn five_dof_stiffness_matches_finite_differences() {
        let b = preset("7008ce").unwrap().build().unwrap();
        let m = RingModel::new(&b, RingDof::Five, 0.0);
        let q = [3e-6, -2e-6, 8e-6, 1e-4, -5e-5];
        let base = eval(&m, q, 0.3);
        let steps = [1e-9, 1e-9, 1e-9, 1e-7, 1e-7];
        for col in 0..5 {
            let (mut qp, mut qm) = (q, q);
            qp[col] += steps[col];
            qm[col] -= steps[col];
            let (fp, fm) = (eval(&m, qp, 0.3).wrench, eval(&m, qm, 0.3).wrench);
            for r in 0..5 {
                let fd = -(fp[r] - fm[r]) / (2.0 * steps[col]);
                let scale = base.k[r][r].abs().max(base.k[col][col].abs()).max(1.0);
                assert!(
                    (fd - base.k[r][col]).abs() < 1e-4 * scale,
                    "K[{r}][{col}] = {} vs fd {fd}",
                    base.k[r][col]
                );
                assert!((base.k[r][col] - base.k[col][r]).abs() < 1e-9 * scale);
            }
        }
    }

    /// Pure axial push on an angular-contact bearing: every ball carries the same load and
    /// `Fz = -Z Q sin(alpha)` with `alpha` from the Jones geometry.
    #[test]
    fn five_dof_pure_axial_is_uniform() {
        let b = preset("218").unwrap().build().unwrap();
        let m = RingModel::new(&b, RingDof::Five, 0.0);
        let z = 20e-6;
        let out = eval(&m, [0.0, 0.0, z, 0.0, 0.0], 0.1);
        let (a10, a20) = b.reference_groove_offset();
        let (a1, a2) = (a10 + z, a20);
        let l = a1.hypot(a2);
        let q = m.kn * (l - b.a()).powf(1.5);
        assert!((out.wrench[2] + 16.0 * q * a1 / l).abs() < 1e-9 * out.wrench[2].abs());
        assert!(out.wrench[0].abs() < 1e-6 && out.wrench[3].abs() < 1e-6);
        assert_eq!(out.loaded, 16);
    }

    /// Skipping the balls that the profile's bound and the thickest film cannot bring into
    /// contact changes no bit of the forces, matrices and per-ball loads (dry and with a
    /// film, 2 and 5 DOF, ring positions from centred to heavily loaded), while it does
    /// skip profile evaluations; a bound below the profile's true maximum would change
    /// the result (what the comparison would catch).
    #[test]
    fn skipping_unloaded_balls_changes_no_bit() {
        use std::cell::Cell;
        let b = preset("6205").unwrap().build().unwrap();
        let amp = 0.3e-6;
        let calls = Cell::new(0usize);
        let wavy = |j: usize, psi: f64, _t: f64| {
            calls.set(calls.get() + 1);
            amp * (5.0 * psi + j as f64).sin()
        };
        let run = |m: &RingModel, q: [f64; 5], max: f64| {
            let mut out = RingEval::default();
            let mut balls = Vec::new();
            let v = [1e-3, -2e-3, 0.0, 0.0, 0.0];
            m.eval_with(
                0.37,
                70.0,
                &q,
                &v,
                0.0,
                (Some(&wavy), max),
                true,
                &mut out,
                |j, p, l| balls.push((j, p.to_bits(), l.to_bits())),
            );
            (out, balls)
        };
        let (mut skipped, mut changed) = (0, 0);
        for dof in [RingDof::Two, RingDof::Five] {
            let dry = RingModel::new(&b, dof, 100.0);
            let wet = dry
                .clone()
                .with_film(crate::lubrication::Lubricant::study2());
            for m in [&dry, &wet] {
                for k in 0..40 {
                    let r = 1e-6 * (k as f64 - 8.0);
                    let q = [0.3 * r, -r, 0.5e-6, 1e-5, -2e-5];
                    calls.set(0);
                    let full = run(m, q, f64::INFINITY);
                    let all = calls.get();
                    calls.set(0);
                    let bounded = run(m, q, amp);
                    skipped += all - calls.get();
                    assert_eq!(full, bounded, "{dof:?} {k}");
                    // A wrong (too small) bound skips balls the profile would load.
                    changed += (run(m, q, -amp) != full) as usize;
                }
            }
        }
        assert!(skipped > 500 && changed > 10, "{skipped} {changed}");
    }

    /// A profile that removes material (a defect) unloads the ball it passes.
    #[test]
    fn profile_offsets_the_deflection() {
        let b = preset("6205").unwrap().build().unwrap();
        let m = RingModel::new(&b, RingDof::Two, 0.0);
        let q = [10e-6, 0.0, 0.0, 0.0, 0.0];
        let plain = eval(&m, q, 0.0);
        let dent = |_j: usize, psi: f64, _t: f64| if psi.cos() > 0.999 { -20e-6 } else { 0.0 };
        let mut out = RingEval::default();
        m.eval(0.0, 0.0, &q, &[0.0; 5], 0.0, Some(&dent), false, &mut out);
        assert_eq!(out.loaded, plain.loaded - 1);
        assert!(out.wrench[0] > plain.wrench[0]);
    }
    /// With an EHL film, spacing offsets and a profile, the stiffness matrix is still minus
    /// the derivative of the force, the film adds load at a given approach and adds damping,
    /// and it reports a film of a few tenths of a micrometre.
    #[test]
    fn film_and_spacing_keep_k_consistent() {
        let b = preset("6205").unwrap().build().unwrap();
        let offs: Vec<f64> = (0..9).map(|j| 1e-3 * (j as f64 - 4.0)).collect();
        let dry = RingModel::new(&b, RingDof::Two, 100.0).with_spacing(offs.clone());
        let wet = RingModel::new(&b, RingDof::Two, 100.0)
            .with_spacing(offs)
            .with_film(crate::lubrication::Lubricant::study2());
        let wc = 0.4 * 183.26;
        let wavy = |j: usize, psi: f64, _t: f64| 0.2e-6 * (3.0 * psi).sin() - 1e-8 * j as f64;
        let at = |m: &RingModel, q: [f64; 5]| {
            let mut out = RingEval::default();
            m.eval(0.1, wc, &q, &[0.0; 5], 0.0, Some(&wavy), true, &mut out);
            out
        };
        let q = [2e-6, -12e-6, 0.0, 0.0, 0.0];
        let (d, w) = (at(&dry, q), at(&wet, q));
        assert!(
            w.wrench[1] > d.wrench[1] * 1.02,
            "the film fills part of the gap"
        );
        assert!(
            w.c[1][1] > d.c[1][1],
            "squeeze damping adds to contact damping"
        );
        assert!(w.film_min > 5e-8 && w.film_min < 1e-6, "{}", w.film_min);
        assert_eq!(d.film_min, 0.0);
        assert!(
            w.k[1][1] > 1.01 * d.k[1][1],
            "{} vs {}",
            w.k[1][1],
            d.k[1][1]
        );
        let step = 1e-10;
        for col in 0..2 {
            let (mut qp, mut qm) = (q, q);
            qp[col] += step;
            qm[col] -= step;
            for r in 0..2 {
                let fd = -(at(&wet, qp).wrench[r] - at(&wet, qm).wrench[r]) / (2.0 * step);
                // K leaves out the damping force's dependence on q through the rotating
                // rate term `omega_c (-x sin + y cos)` and through c(Q) (as the plain model
                // does): of order Z c omega_c ~ 1e5 N/m, about 1e-3 of K here. The ball-level
                // film stiffness is checked to 1e-5 in `lubrication`.
                assert!(
                    (fd - w.k[r][col]).abs() < 2e-3 * w.k[1][1],
                    "K[{r}][{col}] = {} vs fd {fd}",
                    w.k[r][col]
                );
            }
        }
    }
}
