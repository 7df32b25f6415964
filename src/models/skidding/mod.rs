//! Skidding level: ball orbit and spin, cage, traction, lubricant drag (docs/physics.md §5.2;
//! studies \[2\] and \[3\]; Harris & Kotzalas Vol. 2 ch. 3 for the slip kinematics, Gupta
//! *Advanced Dynamics of Rolling Elements* ch. 3–4 for the ball and cage equations).
//!
//! # Free-body diagram and sign conventions
//!
//! Fixed frame as docs/physics.md §0: `z` along the shaft, ball `j` at azimuth `psi_j`, radial
//! unit vector `e_r`, rolling direction `e_t = z × e_r` (the direction of increasing `psi`).
//! Every speed is positive in the sense of the shaft's rotation `omega` (about `+z`).
//!
//! Ball `j` has three states: orbital angle `psi_j`, orbital speed `w_b = psi_j'`, and the
//! absolute angular speed `w_a` about the ball's rolling axis
//! `a = cos(alpha) z - sin(alpha) e_r` (perpendicular to the contact line, which is tilted
//! by the contact angle `alpha` from `e_r`). With contact points at `-/+ (D/2) n` from the
//! ball centre (inner/outer, `n = cos(alpha) e_r + sin(alpha) z`), `a × n = e_t`, so the ball
//! surface moves along `e_t` at
//!
//! - inner contact: `(dm/2) w_b - (D/2) w_a`,
//! - outer contact: `(dm/2) w_b + (D/2) w_a`.
//!
//! The race surfaces move at `(d_i/2) omega` (inner, `d_i = dm - D cos(alpha)`) and 0
//! (outer fixed). Slip velocities, as in docs/physics.md §5.2 with the spin relative to the cage
//! frame `w_s = w_b cos(alpha) - w_a`:
//!
//! - `dv_i = (d_i/2) omega - [(dm/2) w_b - (D/2) w_a] = (d_i/2)(omega - w_b) - (D/2) w_s`
//!   (race minus ball: positive when the race drags the ball forward),
//! - `dv_o = (dm/2) w_b + (D/2) w_a = (d_o/2) w_b - (D/2) w_s` (ball minus race: positive
//!   when the ball surface slides forward over the fixed race).
//!
//! Both vanish at the kinematic speeds of docs/physics.md §1: `w_b = omega (1 - gamma)/2`,
//! `w_s = dm/(2D) (1 - gamma²) omega` (a unit test checks it).
//!
//! Forces on the ball along `e_t`: `+f_i = T(dv_i) ` from the inner race, `-f_o = -T(dv_o)`
//! from the outer race (T the traction law, odd), `+P` from the cage pocket, `-F_d` drag.
//! Moments about the rolling axis `a`: `r × F` with `r = -/+ (D/2) n` gives
//! `-(D/2) f_i` and `-(D/2) f_o` (both contacts spin the ball backwards), plus the pocket
//! friction moment and a drag moment. Equations (Newton for the centre along `e_t` on the
//! pitch circle, Euler about `a` for a sphere with isotropic inertia `J = m D²/10`):
//!
//! ```text
//! m (dm/2) w_b'  = f_i - f_o + P - F_d
//! J w_a'         = -(D/2)(f_i + f_o) + M_pocket - M_drag
//! J_c w_c'       = -(dm/2) sum_j P_j - sum_j M_z,j - M_cage
//! ```
//!
//! (plus the spin friction's generalised forces below).
//!
//! Angular momentum about `z` of balls and cage,
//! `L = sum_j [m (dm/2)² w_b + J cos(alpha) w_a] + J_c w_c`, then changes only by the race
//! tractions' moments `sum (d_i/2) f_i - sum (d_o/2) f_o` and the drags (pocket forces and
//! pocket friction are internal): checked in `tests/skidding.rs` for `alpha = 0`.
//!
//! Pocket: ball `j`'s pocket centre is at `theta_c + 2 pi j/Z + e_j` (`e_j` the seeded
//! spacing scatter). With `xi = (dm/2)(psi_j - pocket)` and clearance `c_p`, the pocket
//! face pushes back with `P = -k_p pen(xi - c_p) + k_p pen(-xi - c_p)` where `pen` is the
//! C¹ positive part (`x²/(2w)` for `0 < x < w`, `x - w/2` beyond), plus a damping
//! `c_p xi'` blended in over the same width. The friction at the pocket face is radial and
//! opposes the ball's surface sliding there, `(D/2)(w_a cos(alpha) - w_c)`; it gives the ball the
//! moment `M_z = -(D/2) mu_c |P| tanh((D/2)(w_a cos(alpha) - w_c)/v_s)` about `z` and the
//! cage the opposite one (`M_pocket = M_z cos(alpha)` above). Only its component along
//! `a` turns the
//! ball's rolling spin (the rest would turn the pivoting spin, not modelled).
//!
//! Normal loads: ball `j`'s inner groove curvature centre moves with the ring exactly as in
//! the ring level's 5-DOF Jones geometry (`models::ring`), giving the total approach
//! `delta_j = |A_j| - A` along the unit vector `n_j`. The ball's position along `n_j` is in
//! quasi-static equilibrium with its centrifugal force `Fc = m (dm/2) w_b²`:
//! `Q_o(delta_o) - Q_i(delta_j - delta_o) = Fc n_r` (`n_r` the radial component of
//! `n_j`), solved by safeguarded Newton per ball (Harris & Kotzalas Vol. 2 ch. 3 do the
//! same with both contact angles free; here the two contacts stay collinear).
//!
//! Gyroscopic couple: the ball's angular velocity is `w = w_b z + (w_a - w_b cos a) a` and
//! `a` turns with the orbit (`a' = -sin(a) w_b e_t`), so `dH/dt` has the component
//! `Mg = J w_s w_b sin(a)` about `e_t` (Harris & Kotzalas Vol. 2 ch. 3). Lateral friction
//! `+F` at the inner contact and `-F` at the outer one, along `(n1, -n0)` in the
//! (axial, radial) plane, supplies it (`F D = Mg`, no net force on the ball, no work: the
//! contact points do not slide laterally), limited exactly as the quasi-static kernel
//! (`models::quasi_static::ball`, "no control" `lambda_i = lambda_o = 1`):
//! `F = (Mg/D) phi(mu Q_h D/|Mg|)`, `phi(t) = t/(1 + t⁴)^(1/4)`, `Q_h = Q_i Q_o/(Q_i + Q_o)`.
//! The shaft receives `-F (n1, -n0)` at the inner contact: an axial and radial force and
//! the ball-plane moment `Ri F_a + F f_i D` about the groove-centre circle (as the
//! quasi-static kernel). The normal loads do not change.
//!
//! Spin friction: relative to the races the ball spins about the contact normal
//! `n3 = n0 z + n1 e_r` at `w.n3 - omega n0` (inner) and `w.n3` (outer), zero at `a = 0`.
//! Each contact resists with `M = (3/8) mu Q a E(k) tanh(w_spin a / v_s)` (Harris &
//! Kotzalas Vol. 2 ch. 2, the spinning moment of an elliptical contact in full sliding;
//! `3 pi/16 mu Q a` for a circle; `tanh` makes it continuous). On the ball `-M n3`, whose
//! generalised forces on `(w_b, w_a)` are `-M n3.(z - cos(a) a)` and `-M n3.a` (so the
//! energy and the momentum about `z` balance exactly); on the races `+M n3` (the shaft's
//! torque about `z` and its tilt moments).
//!
//! Radial mass (option `ball_radial_mass`): the ball's outer approach `u` and `u'` become
//! states, `m u'' = Q_i(delta - u) + c_i (delta' - u') - Q_o(u) - c_o u' + Fc n_r` along
//! the contact line (the outer ring fixed; `c_k` the contact damping blended in over
//! [`crate::models::ring::DAMPING_RAMP`] of each approach, so the radial motion settles onto
//! the quasi-static split), and the shaft receives `Q_i + c_i (delta' - u')`. The
//! rotation of the contact line and the Coriolis terms are neglected (the ball moves by
//! micrometres).
//!
//! Shaft stiffness: `-dW/dq` with the balls held is analytic (the load derivatives from
//! the split, `dQ_i = (s_i s_o d delta - s_i df)/(s_i + s_o)`, the contact line's
//! `dn = (dA/dq - n g)/|A|`, and the traction, lateral and spin terms through them),
//! checked against central differences in a unit test.
//!
//! Drag (docs/physics.md §5.2): `F_d = C_d rho_eff pi D² v|v|/8` with `v = (dm/2) w_b` (dynamic
//! pressure on the frontal area); ball spin drag `M = pi eta D³ w_a` (Stokes' rotating
//! sphere, `8 pi eta R³ w`); cage drag `M_cage = c_cage w_c` (linear viscous).

mod contact;
mod eom;
mod jacobian;
pub mod level;
pub mod spec;
#[cfg(test)]
mod tests;

use crate::contact::traction::{ContactState, TractionLaw};
use crate::contact::{BallRaceContacts, PointContact};
use crate::error::{Error, Result};
use crate::geometry::Bearing;
use std::f64::consts::PI;

/// Options of the skidding model (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct SkiddingParams {
    /// Traction law at both race contacts.
    pub traction: TractionLaw,
    /// Pocket clearance (tangential, per side), m.
    pub pocket_clearance: f64,
    /// Pocket contact stiffness, N/m.
    pub pocket_stiffness: f64,
    /// Pocket contact damping, N s/m.
    pub pocket_damping: f64,
    /// Pocket friction coefficient.
    pub pocket_friction: f64,
    /// Smoothing width of the pocket contact, m.
    pub pocket_smoothing: f64,
    /// Drag coefficient of an orbiting ball.
    pub drag_coefficient: f64,
    /// Effective density of the oil–air mixture, kg/m³.
    pub drag_density: f64,
    /// Oil viscosity for the spin drag, Pa s.
    pub drag_viscosity: f64,
    /// Cage drag, N m s.
    pub cage_drag: f64,
    /// Spacing scatter as a fraction of the pocket clearance (uniform in +-).
    pub spacing_scatter: f64,
    /// Seed of the scatter.
    pub seed: u64,
    /// Slip speed regularising the pocket friction and the spinning moment, m/s.
    pub friction_v_s: f64,
    /// Contact damping on the shaft, N s/m per loaded ball (as the ring level:
    /// `c d(delta)/dt` blended in over [`crate::models::ring::DAMPING_RAMP`]).
    pub contact_damping: f64,
    /// Gyroscopic couple carried by lateral friction at the contacts (angular-contact
    /// bearings; zero at `alpha = 0`).
    pub gyroscopic: bool,
    /// Traction coefficient that limits the gyroscopic friction (as the quasi-static
    /// level's `gyro_traction`; `f64::INFINITY`: unlimited).
    pub gyro_traction: f64,
    /// Friction coefficient of the spinning moment at the race contacts (0: off).
    pub spin_friction: f64,
    /// Give each ball radial mass: its position along the contact line (the outer
    /// approach `u`) and `u'` become states instead of the quasi-static split.
    pub ball_radial_mass: bool,
    /// Worn depth of the outer race per cell (cell `k` centred at azimuth `2 pi k / n`), m;
    /// empty: unworn. It widens the clearance under a ball at `psi` by the interpolated
    /// depth (`crate::models::wear_map`; its `d/dpsi` is left out of the Jacobian).
    pub outer_wear: Vec<f64>,
}

impl Default for SkiddingParams {
    /// The scene's declared defaults (`[model.skidding]`), plus those of the settings a
    /// scene does not expose.
    fn default() -> Self {
        let s = spec::SkiddingSpec::default();
        SkiddingParams {
            traction: s.traction,
            pocket_clearance: 0.1e-3,
            pocket_stiffness: s.pocket_stiffness,
            pocket_damping: s.pocket_damping,
            pocket_friction: s.pocket_friction,
            pocket_smoothing: 1e-6,
            drag_coefficient: s.drag_coefficient,
            drag_density: s.drag_density,
            drag_viscosity: s.drag_viscosity,
            cage_drag: s.cage_drag,
            spacing_scatter: s.spacing_scatter,
            seed: s.seed,
            friction_v_s: 0.05,
            contact_damping: 0.0,
            gyroscopic: s.gyro_traction > 0.0,
            gyro_traction: s.gyro_traction,
            spin_friction: s.spin_friction,
            ball_radial_mass: s.ball_radial_mass,
            outer_wear: Vec::new(),
        }
    }
}

/// Per-ball quantities of one evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BallState {
    /// Orbital angle, rad.
    pub psi: f64,
    /// Orbital speed, rad/s.
    pub w_b: f64,
    /// Spin relative to the cage frame `w_s = w_b cos(alpha) - w_a`, rad/s.
    pub w_s: f64,
    /// Inner and outer normal loads, N.
    pub q_i: f64,
    /// Outer normal load, N.
    pub q_o: f64,
    /// Slip velocities `(dv_i, dv_o)`, m/s.
    pub dv_i: f64,
    /// Outer slip velocity, m/s.
    pub dv_o: f64,
    /// Tractions `(f_i, f_o)`, N.
    pub f_i: f64,
    /// Outer traction, N.
    pub f_o: f64,
    /// Pocket force on the ball along `e_t`, N.
    pub pocket: f64,
    /// Lateral friction force carrying the gyroscopic couple, N.
    pub gyro: f64,
    /// Spinning moment on the inner race about the contact normal, N m.
    pub spin_i: f64,
    /// Spinning moment on the outer race about the contact normal, N m.
    pub spin_o: f64,
}

/// Normal loads of one ball from [`SkiddingModel::split`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Split {
    q_i: f64,
    q_o: f64,
    /// `dQ/d(approach)` of each contact.
    s_i: f64,
    s_o: f64,
    /// Square roots of the approaches.
    r_i: f64,
    r_o: f64,
}

/// One ball's geometry (see [`SkiddingModel::geo`]).
#[derive(Debug, Clone, Copy)]
struct Geo {
    s: f64,
    c: f64,
    /// Unit contact line `(axial, radial)`.
    n: [f64; 2],
    /// `|A|`.
    l: f64,
    /// Total approach.
    delta: f64,
    /// `d delta / dq`.
    g: [f64; 5],
}

/// `d/dq` of a ball's contact line and loads ([`SkiddingModel::load_derivs`]).
#[derive(Debug, Clone, Copy)]
struct LoadDerivs {
    dn0: [f64; 5],
    dn1: [f64; 5],
    dqi: [f64; 5],
    dqo: [f64; 5],
}

/// One ball's pocket contact ([`SkiddingModel::pocket`]).
#[derive(Debug, Clone, Copy)]
struct Pocket {
    xi: f64,
    xi_dot: f64,
    bl: f64,
    bt: f64,
    force: f64,
    m_fric: f64,
}

/// The limited gyroscopic friction's state for its load derivatives
/// ([`SkiddingModel::gyro_force`]).
#[derive(Debug, Clone, Copy)]
struct GyroLimit {
    mu: f64,
    /// `1 + t⁴` and its fourth root.
    t4: f64,
    r4: f64,
    /// Sign of the unlimited force.
    sign: f64,
    q_i: f64,
    q_o: f64,
    /// `Q_i + Q_o`.
    sum: f64,
}

impl GyroLimit {
    /// `(dF/dQ_i, dF/dQ_o)`: `phi'(t) = 1/(1 + t⁴)^(5/4)` through `Q_h`.
    fn derivs(&self) -> (f64, f64) {
        let dphi = 1.0 / (self.t4 * self.r4);
        let d = self.mu * dphi * self.sign;
        let s2 = self.sum * self.sum;
        (d * self.q_o * self.q_o / s2, d * self.q_i * self.q_i / s2)
    }
}

/// One ball's loads.
#[derive(Debug, Clone, Copy)]
struct Loads {
    sp: Split,
    /// Centrifugal force, N.
    fc: f64,
    /// Is its component along the contact line positive (not clamped)?
    f_active: bool,
    /// Radial mass: the loads follow from the ball's state, not from the split.
    radial: bool,
}

/// One ball's terms.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BallOut {
    /// Rates of `(psi, w_b, w_a, u, u')` (the last two with radial mass only).
    pub dx: [f64; 5],
    /// Torque on the cage about z, N m.
    pub cage_torque: f64,
    /// Wrench on the shaft.
    pub wrench: [f64; 5],
    /// Traction torque on the shaft about z, N m.
    pub torque_shaft: f64,
    /// Traction torque on the outer ring about z, N m.
    pub torque_outer: f64,
    /// Drag torque on the ball about z, N m.
    pub torque_drag: f64,
    /// Power dissipated in its race contacts, W.
    pub power: f64,
    /// Energy stored in the pocket contact spring, J.
    pub pocket_energy: f64,
    /// Power dissipated by the pocket damping and friction and the ball's drag, W.
    pub dissipation: f64,
    /// Gradient of the total approach with respect to `q`.
    pub g: [f64; 5],
    /// Effective contact damping (0 when unloaded), N s/m.
    pub cd: f64,
    /// Per-ball results.
    pub state: BallState,
}

/// Totals of one evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SkidTotals {
    /// Wrench on the shaft.
    pub wrench: [f64; 5],
    /// Traction torque on the shaft about z, N m.
    pub torque_shaft: f64,
    /// Traction torque on the (fixed) outer ring about z, N m.
    pub torque_outer: f64,
    /// Drag torque on balls and cage about z (acting on them), N m.
    pub torque_drag: f64,
    /// Power dissipated in the race contacts, W.
    pub power_contacts: f64,
    /// Power dissipated by pockets and drag (balls and cage), W.
    pub power_other: f64,
    /// Energy stored in the pocket springs, J.
    pub pocket_energy: f64,
    /// Balls in contact with the inner race.
    pub loaded: usize,
    /// Largest inner or outer load, N.
    pub max_load: f64,
}

/// State layout: `[(psi_j, w_b_j, w_a_j) for j in 0..Z, theta_c, w_c]`: independent
/// three-state blocks (one per ball) followed by the cage, so that with the ring's states
/// after them the Jacobian is block-arrowhead ([`crate::solver::BlockArrowhead`]).
pub const BALL0: usize = 0;

/// The skidding model of one bearing.
#[derive(Debug, Clone)]
pub struct SkiddingModel {
    /// Options.
    pub p: SkiddingParams,
    z: usize,
    d: f64,
    dm: f64,
    cos_a: f64,
    sin_a: f64,
    /// States per ball: 3, or 5 with radial mass.
    bs: usize,
    di: f64,
    do_: f64,
    m: f64,
    j: f64,
    jc: f64,
    a: f64,
    a10: f64,
    a20: f64,
    ri: f64,
    inner: PointContact,
    outer: PointContact,
    kratio: f64,
    /// Semi-axis coefficients per square root of the approach, `(a, b) = ax sqrt(delta)`.
    ax_i: [f64; 2],
    ax_o: [f64; 2],
    /// `Kc_i^(1/3)`.
    kc3_i: f64,
    /// `Kc_o^(1/3)`.
    kc3_o: f64,
    /// Lever of the lateral friction about the inner groove centre, `f_i D`.
    fid: f64,
    /// Pocket centre offsets, rad.
    offsets: Vec<f64>,
    /// Per-ball results of the last evaluation.
    pub balls: Vec<BallState>,
}

impl SkiddingModel {
    /// Build; the cage inertia comes from the bearing (`cage.inertia`).
    pub fn new(b: &Bearing, p: SkiddingParams) -> Result<Self> {
        p.traction.validate("model.skidding.traction")?;
        if b.cage.inertia <= 0.0 || !b.cage.inertia.is_finite() {
            return Err(Error::invalid(
                "bearing.cage (inertia)",
                b.cage.inertia,
                "> 0 (give cage mass and diameters)",
            ));
        }
        let alpha = b.nominal_contact_angle();
        let BallRaceContacts { inner, outer } = BallRaceContacts::new(b, alpha);
        let (a10, a20) = b.reference_groove_offset();
        // Seeded spacing scatter (SplitMix64), uniform in +-scatter * c_p / (dm/2).
        let mut s = p.seed;
        let offsets = (0..b.z)
            .map(|_| {
                s = s.wrapping_add(0x9E37_79B9_7F4A_7C15);
                let mut x = s;
                x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
                x ^= x >> 31;
                let u = (x >> 11) as f64 / (1u64 << 53) as f64;
                (2.0 * u - 1.0) * p.spacing_scatter * p.pocket_clearance / (0.5 * b.dm)
            })
            .collect();
        let cos_a = alpha.cos();
        if p.gyro_traction.is_nan() || p.gyro_traction <= 0.0 {
            return Err(Error::invalid(
                "model.skidding.gyro_traction",
                p.gyro_traction,
                "> 0 (inf: unlimited)",
            ));
        }
        let axes = |pc: &PointContact| {
            let (ca, cb) = pc.semi_axis_coefficients();
            let k3 = pc.kc.cbrt();
            [ca * k3, cb * k3]
        };
        Ok(SkiddingModel {
            bs: if p.ball_radial_mass { 5 } else { 3 },
            sin_a: alpha.sin(),
            ax_i: axes(&inner),
            ax_o: axes(&outer),
            kc3_i: inner.kc.cbrt(),
            kc3_o: outer.kc.cbrt(),
            fid: b.fi() * b.d,
            z: b.z,
            d: b.d,
            dm: b.dm,
            cos_a,
            di: b.dm - b.d * cos_a,
            do_: b.dm + b.d * cos_a,
            m: b.ball_mass(),
            j: b.ball_inertia(),
            jc: b.cage.inertia,
            a: b.a(),
            a10,
            a20,
            ri: b.inner_groove_centre_radius(),
            kratio: (inner.kc / outer.kc).powf(2.0 / 3.0),
            inner,
            outer,
            offsets,
            balls: vec![BallState::default(); b.z],
            p,
        })
    }

    /// Number of states `3 Z + 2`.
    pub fn n_states(&self) -> usize {
        self.bs * self.z + 2
    }

    /// States per ball (3, or 5 with radial mass).
    pub fn ball_states(&self) -> usize {
        self.bs
    }

    /// Index of the cage angle (the cage speed follows it).
    pub fn cage_index(&self) -> usize {
        self.bs * self.z
    }

    /// Balls.
    pub fn z(&self) -> usize {
        self.z
    }

    /// Ball diameter, m.
    pub fn d_ball(&self) -> f64 {
        self.d
    }

    /// Kinematic orbital (cage) speed and ball spin relative to the cage at shaft speed
    /// `omega`, outer ring fixed (docs/physics.md §1).
    pub fn kinematic(&self, omega: f64) -> (f64, f64) {
        let gamma = self.d * self.cos_a / self.dm;
        let wb = crate::geometry::kinematics::cage_speed(gamma, omega, 0.0);
        (wb, wb * self.do_ / self.d)
    }

    /// Initial states: balls centred in their pockets, everything turning at the
    /// kinematic speeds of `omega` (from rest when `omega = 0`).
    pub fn init(&self, omega: f64, x: &mut [f64]) {
        self.init_at(&[0.0; 5], omega, x);
    }

    /// [`Self::init`] at ring displacement `q`: with radial mass, each ball starts at rest
    /// where the quasi-static split puts it.
    pub fn init_at(&self, q: &[f64; 5], omega: f64, x: &mut [f64]) {
        let (wb, ws) = self.kinematic(omega);
        let ic = self.cage_index();
        x[ic] = 0.0;
        x[ic + 1] = wb;
        for j in 0..self.z {
            let k = BALL0 + self.bs * j;
            x[k] = 2.0 * PI * j as f64 / self.z as f64 + self.offsets[j];
            x[k + 1] = wb;
            x[k + 2] = wb * self.cos_a - ws;
            if self.bs == 5 {
                let geo = self.geo(q, x[k]);
                let ld = self.loads(&geo, wb, None);
                x[k + 3] = ld.sp.r_o * ld.sp.r_o;
                x[k + 4] = 0.0;
            }
        }
    }

    /// Angular momentum about z of balls and cage, kg m²/s.
    pub fn angular_momentum(&self, x: &[f64]) -> f64 {
        let r2 = 0.25 * self.dm * self.dm;
        let mut l = self.jc * x[self.cage_index() + 1];
        for j in 0..self.z {
            let k = BALL0 + self.bs * j;
            l += self.m * r2 * x[k + 1] + self.j * self.cos_a * x[k + 2];
        }
        l
    }

    /// Kinetic energy of balls (orbit and rolling spin) and cage, J.
    pub fn kinetic_energy(&self, x: &[f64]) -> f64 {
        let r2 = 0.25 * self.dm * self.dm;
        let wc = x[self.cage_index() + 1];
        let mut e = 0.5 * self.jc * wc * wc;
        for j in 0..self.z {
            let k = BALL0 + self.bs * j;
            e += 0.5 * self.m * r2 * x[k + 1].powi(2) + 0.5 * self.j * x[k + 2].powi(2);
            if self.bs == 5 {
                e += 0.5 * self.m * x[k + 4].powi(2);
            }
        }
        e
    }
}
