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

pub mod level;
pub mod spec;

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
            fid: b.fi * b.d,
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

    /// Ball position along the contact line: solve `Q_o(d_o) - Q_i(delta - d_o) = f` for
    /// the outer approach `d_o` (monotone; safeguarded Newton). Returns the loads, their
    /// stiffnesses `dQ/d(approach)` and the square roots of the approaches.
    fn split(&self, delta: f64, f: f64) -> Split {
        let (ki, ko) = (self.inner.kc, self.outer.kc);
        if f <= 0.0 && delta <= 0.0 {
            return Split::default();
        }
        let f = f.max(0.0);
        // Bracket [lo, hi] with g(lo) <= 0 <= g(hi): when the outer contact alone carries
        // at least f at the whole approach (the usual case), hi = delta; otherwise the ball
        // may leave the inner race and hi = max(delta, 0) + (f/ko)^(2/3) (one cube root).
        let lo = 0.0;
        let outer_alone = if delta > 0.0 {
            ko * delta * delta.sqrt()
        } else {
            0.0
        };
        let hi = if delta > 0.0 && outer_alone >= f {
            delta
        } else {
            let t = f / ko;
            delta.max(0.0) + (t * t).cbrt()
        };
        // Start from the f = 0 split (equal loads).
        let x = if delta > 0.0 {
            (delta * self.kratio / (1.0 + self.kratio)).min(hi)
        } else {
            hi
        };
        let g = |x: f64| {
            let (qo, so) = crate::contact::hertz_load_and_stiffness(ko, x);
            let (qi, si) = crate::contact::hertz_load_and_stiffness(ki, delta - x);
            (qo - qi - f, so + si)
        };
        let tol = 1e-13 * hi.max(1e-9);
        // A Newton step below 1e-8 of the bracket leaves an error of order its square
        // over the approach (quadratic convergence): accept it without another pass.
        let tol_newton = 1e-8 * hi.max(1e-9);
        let x = crate::solver::newton::bracketed(g, lo, hi, x, tol, tol_newton, 60);
        let (r_o, r_i) = (x.max(0.0).sqrt(), (delta - x).max(0.0).sqrt());
        Split {
            q_i: ki * r_i * r_i * r_i,
            q_o: ko * r_o * r_o * r_o,
            s_i: 1.5 * ki * r_i,
            s_o: 1.5 * ko * r_o,
            r_i,
            r_o,
        }
    }

    /// Contact data for the traction law from the load and the square root of the
    /// approach (`Q^(1/3) = Kc^(1/3) sqrt(delta)`: no cube root on the hot path).
    fn contact_state(&self, inner: bool, q: f64, r: f64) -> ContactState {
        let (pc, ca, cb) = if inner {
            (&self.inner, self.ax_i[0], self.ax_i[1])
        } else {
            (&self.outer, self.ax_o[0], self.ax_o[1])
        };
        ContactState {
            q,
            a: ca * r,
            b: cb * r,
            rx: pc.curvature.rx,
            kappa: pc.ellipse.kappa,
            e_eff: pc.e_eff,
        }
    }

    /// C¹ positive part with smoothing width `w`, and its slope.
    fn pen(x: f64, w: f64) -> (f64, f64) {
        if x <= 0.0 {
            (0.0, 0.0)
        } else if x < w {
            (0.5 * x * x / w, x / w)
        } else {
            (x - 0.5 * w, 1.0)
        }
    }

    /// Geometry of ball `j` at azimuth `psi` for ring displacement `q` (Jones geometry of
    /// the ring level).
    fn geo(&self, q: &[f64; 5], psi: f64) -> Geo {
        let (s, c) = psi.sin_cos();
        let a1 = self.a10 + q[2] + self.ri * (q[3] * s - q[4] * c);
        let a2 = self.a20 + q[0] * c + q[1] * s;
        // Millimetre-sized: no overflow, so the plain root (hypot is several times slower).
        let l = (a1 * a1 + a2 * a2).sqrt();
        let n = [a1 / l, a2 / l];
        Geo {
            s,
            c,
            n,
            l,
            delta: if self.p.outer_wear.is_empty() {
                l - self.a
            } else {
                l - self.a - crate::models::wear::sample(&self.p.outer_wear, psi)
            },
            g: [
                n[1] * c,
                n[1] * s,
                n[0],
                n[0] * self.ri * s,
                -n[0] * self.ri * c,
            ],
        }
    }

    /// Normal loads of a ball at geometry `geo` and orbital speed `w_b` (centrifugal
    /// force `m (dm/2) w_b²` along the contact line's radial component).
    /// With radial mass the ball's outer approach `u` is given (`Some`) and the loads
    /// follow from it and the total approach.
    fn loads(&self, geo: &Geo, w_b: f64, u: Option<f64>) -> Loads {
        let fc = self.m * 0.5 * self.dm * w_b * w_b;
        let f = fc * geo.n[1];
        let sp = match u {
            None => self.split(geo.delta, f),
            Some(u) => {
                let (r_o, r_i) = (u.max(0.0).sqrt(), (geo.delta - u).max(0.0).sqrt());
                let (ki, ko) = (self.inner.kc, self.outer.kc);
                Split {
                    q_i: ki * r_i * r_i * r_i,
                    q_o: ko * r_o * r_o * r_o,
                    s_i: 1.5 * ki * r_i,
                    s_o: 1.5 * ko * r_o,
                    r_i,
                    r_o,
                }
            }
        };
        Loads {
            sp,
            fc,
            f_active: f > 0.0,
            radial: u.is_some(),
        }
    }

    /// Spinning moment of a contact in full spin sliding, `M = (3/8) mu Q a E(k)`
    /// (Harris & Kotzalas Vol. 2 ch. 2, the spinning friction moment of an elliptical
    /// contact; `3 pi/16 mu Q a` for a circle), regularised by `tanh(w a / v_s)` so that it
    /// is continuous through zero spin. Returns `(M, dM/dQ, dM/dw)` at spin `w` (rad/s).
    fn spin_moment(&self, inner: bool, q: f64, r: f64, w: f64) -> (f64, f64, f64) {
        let mu = self.p.spin_friction;
        if mu <= 0.0 || q <= 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let (ca, e) = if inner {
            (self.ax_i[0], self.inner.ellipse.e)
        } else {
            (self.ax_o[0], self.outer.ellipse.e)
        };
        let a = ca * r;
        let ms = 0.375 * mu * q * a * e;
        let z = w * a / self.p.friction_v_s;
        let th = crate::contact::traction::tanh(z);
        let sech2 = 1.0 - th * th;
        // ms ~ Q^(4/3), z ~ Q^(1/3).
        let m_q = (4.0 / 3.0) * ms * th / q + ms * sech2 * z / (3.0 * q);
        (ms * th, m_q, ms * sech2 * a / self.p.friction_v_s)
    }

    /// One ball's contribution at shaft motion `(q, v, omega)`, cage `(theta_c, w_c)` and
    /// ball states `(psi, w_b, w_a)`, the ball in quasi-static radial equilibrium (also
    /// with the radial-mass option, whose position states it does not see).
    /// Allocation-free.
    #[allow(clippy::too_many_arguments)]
    pub fn ball(
        &self,
        j: usize,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        theta_c: f64,
        w_c: f64,
        psi: f64,
        w_b: f64,
        w_a: f64,
    ) -> BallOut {
        // Radial mass or not, this is the quasi-static split (no ball position given).
        let geo = self.geo(q, psi);
        let ld = self.loads(&geo, w_b, None);
        let st = [theta_c, w_c, psi, w_b, w_a, 0.0, 0.0];
        self.forces(j, &geo, &ld, q, v, omega, st, None)
    }

    /// [`Self::ball`] with all states `[theta_c, w_c, psi, w_b, w_a, u, u']` (the last
    /// two used with radial mass only).
    fn ball_r(&self, j: usize, q: &[f64; 5], v: &[f64; 5], omega: f64, st: [f64; 7]) -> BallOut {
        let geo = self.geo(q, st[2]);
        let u = (self.bs == 5).then_some(st[5]);
        let ld = self.loads(&geo, st[3], u);
        self.forces(j, &geo, &ld, q, v, omega, st, None)
    }

    /// Everything but the geometry and the normal loads: tractions, gyroscopic and spin
    /// friction, pocket, drag, the wrench; with `kq`, also adds the wrench's derivative
    /// `dW/dq` (balls and cage held) to it, analytically (see the module docs).
    /// `s = [theta_c, w_c, psi, w_b, w_a]`.
    #[allow(clippy::too_many_arguments)]
    fn forces(
        &self,
        j: usize,
        geo: &Geo,
        ld: &Loads,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        st: [f64; 7],
        kq: Option<&mut [[f64; 5]; 5]>,
    ) -> BallOut {
        self.forces_on::<true>(j, geo, ld, q, v, omega, st, kq)
    }

    /// [`Self::forces`]; with `WRENCH` false only the rates and the cage torque are right
    /// (the gyroscopic friction, which acts on the shaft alone, is left out of the wrench),
    /// for the Jacobian's differences of the rates.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn forces_on<const WRENCH: bool>(
        &self,
        j: usize,
        geo: &Geo,
        ld: &Loads,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        st: [f64; 7],
        kq: Option<&mut [[f64; 5]; 5]>,
    ) -> BallOut {
        let [theta_c, w_c, psi, w_b, w_a, _, u_dot] = st;
        let p = &self.p;
        let r = 0.5 * self.dm;
        let hd = 0.5 * self.d;
        let (s, c, n) = (geo.s, geo.c, geo.n);
        let sp = &ld.sp;
        let (q_i, q_o) = (sp.q_i, sp.q_o);
        // Slip.
        let dv_i = 0.5 * self.di * omega - (r * w_b - hd * w_a);
        let dv_o = r * w_b + hd * w_a;
        let w_s = w_b * self.cos_a - w_a;
        let u_i = 0.5 * (0.5 * self.di * (omega - w_b) + hd * w_s);
        let u_o = 0.5 * (0.5 * self.do_ * w_b + hd * w_s);
        let (ci, co) = if p.traction.needs_contact() {
            (
                self.contact_state(true, q_i, sp.r_i),
                self.contact_state(false, q_o, sp.r_o),
            )
        } else {
            (
                ContactState {
                    q: q_i,
                    ..ContactState::default()
                },
                ContactState {
                    q: q_o,
                    ..ContactState::default()
                },
            )
        };
        let f_i = p.traction.force(dv_i, u_i, &ci);
        let f_o = p.traction.force(dv_o, u_o, &co);
        // Spin about the contact normals: the ball's angular velocity is
        // w_b z + (w_a - w_b cos a) a; its component along n3 = n0 z + n1 e_r, minus the
        // race's (omega z, inner; 0, outer).
        let nd = self.cos_a * n[0] - self.sin_a * n[1]; // a . n3
        let w_rel_b = w_a - w_b * self.cos_a;
        let wn = w_b * n[0] + w_rel_b * nd;
        let (w_sp_i, w_sp_o) = (wn - omega * n[0], wn);
        let (ms_i, msq_i, msw_i) = self.spin_moment(true, q_i, sp.r_i, w_sp_i);
        let (ms_o, _, _) = self.spin_moment(false, q_o, sp.r_o, w_sp_o);
        // Generalised forces of the spin moments -(M_i + M_o) n3 on the ball's states:
        // d w / d w_b = z - cos a a, d w / d w_a = a.
        let gen = -(ms_i + ms_o);
        let gen_b = gen * (n[0] - self.cos_a * nd);
        let gen_a = gen * nd;
        // Gyroscopic couple J w_s w_b sin(a) about e_t, carried by lateral friction
        // +-F (n1, -n0) at the two contacts with the traction cap of the quasi-static
        // kernel (module docs).
        // Not for the rates alone (`WRENCH` false): it acts on the shaft only.
        let (f_g, g_lim) = if WRENCH {
            self.gyro_force(w_b, w_s, q_i, q_o)
        } else {
            (0.0, None)
        };
        // Pocket.
        let Pocket {
            xi,
            xi_dot,
            bl,
            bt,
            force: pocket,
            m_fric,
        } = self.pocket(j, [theta_c, w_c, psi, w_b, w_a]);
        let (cp, w) = (p.pocket_clearance, p.pocket_smoothing);
        // Drag.
        let vb = r * w_b;
        let f_d = p.drag_coefficient * p.drag_density * PI * self.d * self.d * vb * vb.abs() / 8.0;
        let m_d = PI * p.drag_viscosity * self.d.powi(3) * w_a;
        let mut dx = [
            w_b,
            (f_i - f_o + pocket - f_d) / (self.m * r) + gen_b / (self.m * r * r),
            (-hd * (f_i + f_o) + m_fric * self.cos_a - m_d + gen_a) / self.j,
            0.0,
            0.0,
        ];
        // On the shaft: normal load along -n through the groove centre, traction -f_i e_t
        // at the inner contact, the lateral friction -F (n1, -n0) at the inner contact
        // (ball-plane moment about the groove-centre circle as the quasi-static kernel),
        // the spin moment +M_i n3.
        let g = geo.g;
        let mut fn_ = q_i;
        let mut cd = 0.0;
        let (mut da1, mut da2) = (0.0, 0.0);
        // Damping acts on a loaded inner contact only (as the ring level: "on loaded balls
        // only"), blended in over its Hertz approach `r_i²`; the damped rate is the total
        // approach's (massless balls) or the inner one's (radial mass). Blending on the
        // total approach instead let a ball that centrifugal force holds off the inner race
        // (`delta > 0`, `Q_i = 0`, fast) push and pull the shaft through an open contact:
        // a force with no ball loaded, and no stiffness to show it (the static start of a
        // load-driven ring then failed at 120 000 rpm).
        let (app, mut dd) = (sp.r_i * sp.r_i, if ld.radial { -u_dot } else { 0.0 });
        let mut extra_dissipation = 0.0;
        if p.contact_damping > 0.0 && app > 0.0 {
            da1 = v[2] + self.ri * (v[3] * s - v[4] * c) + w_b * self.ri * (q[3] * c + q[4] * s);
            da2 = v[0] * c + v[1] * s + w_b * (-q[0] * s + q[1] * c);
            let blend = (app / crate::models::ring::DAMPING_RAMP).min(1.0);
            cd = p.contact_damping * blend;
            dd += n[0] * da1 + n[1] * da2;
            fn_ += cd * dd;
        }
        if ld.radial {
            // Newton along the contact line: inner load and damping outwards, outer load
            // and damping (on u', the outer ring fixed) inwards, centrifugal force.
            let r_o2 = sp.r_o * sp.r_o;
            let cd_o = p.contact_damping * (r_o2 / crate::models::ring::DAMPING_RAMP).min(1.0);
            let f_out = q_o + if r_o2 > 0.0 { cd_o * u_dot } else { 0.0 };
            dx[3] = u_dot;
            dx[4] = (fn_ - f_out + ld.fc * n[1]) / self.m;
            extra_dissipation = cd * dd * dd
                + if r_o2 > 0.0 {
                    cd_o * u_dot * u_dot
                } else {
                    0.0
                };
        }
        let mut wrench = [0.0; 5];
        for (wk, gk) in wrench.iter_mut().zip(g) {
            *wk = -fn_ * gk;
        }
        wrench[0] += f_i * s;
        wrench[1] -= f_i * c;
        let plane = |fa: f64, fr: f64, m: f64| [fr * c, fr * s, fa, m * s, -m * c];
        if f_g != 0.0 {
            let fa = -f_g * n[1];
            let fr = f_g * n[0];
            let wg = plane(fa, fr, self.ri * fa + self.fid * f_g);
            for (wk, x) in wrench.iter_mut().zip(wg) {
                *wk += x;
            }
        }
        wrench[3] += ms_i * n[1] * c;
        wrench[4] += ms_i * n[1] * s;
        if let Some(k) = kq {
            let g1 = [0.0, 0.0, 1.0, self.ri * s, -self.ri * c];
            let g2 = [c, s, 0.0, 0.0, 0.0];
            let LoadDerivs { dn0, dn1, dqi, dqo } = self.load_derivs(geo, ld);
            // Normal force with damping.
            let mut dfn = dqi;
            if cd > 0.0 {
                let ramp = app < crate::models::ring::DAMPING_RAMP;
                let h1 = [0.0, 0.0, 0.0, w_b * self.ri * c, w_b * self.ri * s];
                let h2 = [-w_b * s, w_b * c, 0.0, 0.0, 0.0];
                for i in 0..5 {
                    let ddd = da1 * dn0[i] + da2 * dn1[i] + n[0] * h1[i] + n[1] * h2[i];
                    // d(r_i²)/dq: the inner approach's, `dQ_i/dq / (dQ_i/d delta_i)`
                    // (the ball held with radial mass: `g`).
                    let dapp = if ld.radial {
                        g[i]
                    } else if sp.s_i > 0.0 {
                        dqi[i] / sp.s_i
                    } else {
                        0.0
                    };
                    let dcd = if ramp {
                        p.contact_damping / crate::models::ring::DAMPING_RAMP * dapp
                    } else {
                        0.0
                    };
                    dfn[i] += dd * dcd + cd * ddd;
                }
            }
            for rr in 0..5 {
                for cc in 0..5 {
                    let dg = (g1[rr] * g1[cc] + g2[rr] * g2[cc] - g[rr] * g[cc]) / geo.l;
                    k[rr][cc] -= g[rr] * dfn[cc] + fn_ * dg;
                }
            }
            // Traction along e_t.
            let tq = if q_i <= 0.0 {
                0.0
            } else if p.traction.needs_contact() {
                let h = 1e-7 * q_i;
                let (ca, cb) = (self.ax_i[0], self.ax_i[1]);
                let r3 = (q_i + h).cbrt() / self.kc3_i;
                let cs = ContactState {
                    a: ca * r3,
                    b: cb * r3,
                    ..self.contact_state(true, q_i + h, 0.0)
                };
                (p.traction.force(dv_i, u_i, &cs) - f_i) / h
            } else {
                f_i / q_i
            };
            for cc in 0..5 {
                k[0][cc] += s * tq * dqi[cc];
                k[1][cc] -= c * tq * dqi[cc];
            }
            // Lateral (gyroscopic) friction.
            if f_g != 0.0 {
                let (fg_qi, fg_qo) = g_lim.map_or((0.0, 0.0), |l| l.derivs());
                for cc in 0..5 {
                    let dfg = fg_qi * dqi[cc] + fg_qo * dqo[cc];
                    let dfa = -n[1] * dfg - f_g * dn1[cc];
                    let dfr = n[0] * dfg + f_g * dn0[cc];
                    let dm = self.ri * dfa + self.fid * dfg;
                    let col = plane(dfa, dfr, dm);
                    for rr in 0..5 {
                        k[rr][cc] += col[rr];
                    }
                }
            }
            // Spin moment on the shaft.
            if ms_i != 0.0 || msq_i != 0.0 {
                let dw0 = w_b - omega + w_rel_b * self.cos_a;
                let dw1 = -w_rel_b * self.sin_a;
                for cc in 0..5 {
                    let dm = msq_i * dqi[cc] + msw_i * (dw0 * dn0[cc] + dw1 * dn1[cc]);
                    let dmx = n[1] * dm + ms_i * dn1[cc];
                    k[3][cc] += c * dmx;
                    k[4][cc] += s * dmx;
                }
            }
        }
        BallOut {
            dx,
            cage_torque: -r * pocket - m_fric,
            wrench,
            torque_shaft: -0.5 * self.di * f_i + ms_i * n[0],
            torque_outer: 0.5 * self.do_ * f_o + ms_o * n[0],
            torque_drag: -(r * f_d + self.cos_a * m_d),
            power: f_i * dv_i + f_o * dv_o + ms_i * w_sp_i + ms_o * w_sp_o,
            pocket_energy: p.pocket_stiffness
                * (Self::pen_energy(xi - cp, w) + Self::pen_energy(-xi - cp, w)),
            dissipation: p.pocket_damping * (bl + bt) * xi_dot * xi_dot
                - m_fric * (w_a * self.cos_a - w_c)
                + f_d * vb
                + m_d * w_a
                + extra_dissipation,
            g,
            cd,
            state: BallState {
                psi,
                w_b,
                w_s,
                q_i,
                q_o,
                dv_i,
                dv_o,
                f_i,
                f_o,
                pocket,
                gyro: f_g,
                spin_i: ms_i,
                spin_o: ms_o,
            },
        }
    }

    /// Derivatives with respect to `q` of the contact line `n` and of the normal loads
    /// (balls held): `dn = (G - n g)/|A|` with `G = dA/dq`, and from the split
    /// `Q_o(x) - Q_i(delta - x) = f`: `dQ_i = (s_i s_o d delta - s_i df)/(s_i + s_o)`,
    /// `dQ_o = (s_i s_o d delta + s_o df)/(s_i + s_o)` (`s` the contact stiffnesses,
    /// `f = Fc n_r`); a ball on the outer race only has `dQ_o = df`.
    fn load_derivs(&self, geo: &Geo, ld: &Loads) -> LoadDerivs {
        let (s, c, n, g) = (geo.s, geo.c, geo.n, geo.g);
        let g1 = [0.0, 0.0, 1.0, self.ri * s, -self.ri * c];
        let g2 = [c, s, 0.0, 0.0, 0.0];
        let dn0: [f64; 5] = std::array::from_fn(|i| (g1[i] - n[0] * g[i]) / geo.l);
        let dn1: [f64; 5] = std::array::from_fn(|i| (g2[i] - n[1] * g[i]) / geo.l);
        let df: [f64; 5] = std::array::from_fn(|i| if ld.f_active { ld.fc * dn1[i] } else { 0.0 });
        let sp = &ld.sp;
        let (ai, bi, ao, bo) = if ld.radial {
            // The ball held: only the inner approach changes.
            (sp.s_i, 0.0, 0.0, 0.0)
        } else if sp.q_i > 0.0 && sp.q_o > 0.0 {
            let ss = sp.s_i + sp.s_o;
            let h = sp.s_i * sp.s_o / ss;
            (h, -sp.s_i / ss, h, sp.s_o / ss)
        } else if sp.q_o > 0.0 {
            (0.0, 0.0, 0.0, 1.0)
        } else {
            (0.0, 0.0, 0.0, 0.0)
        };
        LoadDerivs {
            dn0,
            dn1,
            dqi: std::array::from_fn(|i| ai * g[i] + bi * df[i]),
            dqo: std::array::from_fn(|i| ao * g[i] + bo * df[i]),
        }
    }

    /// Pocket force on ball `j` and the pocket friction moment (module docs);
    /// `st = [theta_c, w_c, psi, w_b, w_a]`.
    fn pocket(&self, j: usize, st: [f64; 5]) -> Pocket {
        let [theta_c, w_c, psi, w_b, w_a] = st;
        let p = &self.p;
        let r = 0.5 * self.dm;
        let hd = 0.5 * self.d;
        let pocket_angle = theta_c + 2.0 * PI * j as f64 / self.z as f64 + self.offsets[j];
        let xi = r * (psi - pocket_angle);
        let xi_dot = r * (w_b - w_c);
        let cp = p.pocket_clearance;
        let w = p.pocket_smoothing;
        let (pl, bl) = Self::pen(xi - cp, w);
        let (pt, bt) = Self::pen(-xi - cp, w);
        let force = -p.pocket_stiffness * (pl - pt) - p.pocket_damping * (bl + bt) * xi_dot;
        let slide = hd * (w_a * self.cos_a - w_c);
        let m_fric = if force == 0.0 {
            0.0
        } else {
            -hd * p.pocket_friction
                * force.abs()
                * crate::contact::traction::tanh(slide / p.friction_v_s)
        };
        Pocket {
            xi,
            xi_dot,
            bl,
            bt,
            force,
            m_fric,
        }
    }

    /// Lateral friction force `F` that carries the gyroscopic couple
    /// `Mg = J w_s w_b sin(alpha)` (Harris & Kotzalas Vol. 2 ch. 3), `+F` on the ball at
    /// the inner contact and `-F` at the outer one along `(n1, -n0)` (so the ball's lateral
    /// force balance closes and the couple is `F D = Mg`), limited as in the quasi-static
    /// kernel (`models::quasi_static::ball`): `F = (Mg/D) phi(mu Q_h D/|Mg|)`,
    /// `phi(t) = t/(1 + t⁴)^(1/4)`, `Q_h = Q_i Q_o/(Q_i + Q_o)`. Returns `F` and what
    /// [`GyroLimit::derivs`] needs for `(dF/dQ_i, dF/dQ_o)` (only the stiffness reads
    /// them, so the right-hand side does not pay their divisions).
    fn gyro_force(&self, w_b: f64, w_s: f64, q_i: f64, q_o: f64) -> (f64, Option<GyroLimit>) {
        if !self.p.gyroscopic || q_i <= 0.0 || q_o <= 0.0 {
            return (0.0, None);
        }
        let fb = self.j * w_s * w_b * self.sin_a / self.d;
        if fb == 0.0 {
            return (0.0, None);
        }
        let mu = self.p.gyro_traction;
        if !mu.is_finite() {
            return (fb, None);
        }
        let sum = q_i + q_o;
        let qh = q_i * q_o / sum;
        let t = mu * qh / fb.abs();
        let t4 = 1.0 + t * t * t * t;
        let r4 = t4.sqrt().sqrt();
        let phi = t / r4;
        let lim = GyroLimit {
            mu,
            t4,
            r4,
            sign: fb.signum(),
            q_i,
            q_o,
            sum,
        };
        (fb * phi, Some(lim))
    }

    /// Whether the rates are linear in each normal load through the traction alone and
    /// read no contact data: the Coulomb law (`mu tanh(dv/v_s) Q`), no spin friction,
    /// no radial mass. Then the Jacobian takes some columns analytically
    /// ([`Self::wa_column`], and `d(rates)/dQ = (f/Q)·(d(rates)/df)`).
    fn coulomb_rates(&self, ld: &Loads) -> Option<(f64, f64)> {
        #[cfg(test)]
        if tests::FD_ONLY.with(std::cell::Cell::get) {
            return None;
        }
        match self.p.traction {
            TractionLaw::Coulomb { mu_max, v_s } if self.p.spin_friction <= 0.0 && !ld.radial => {
                Some((mu_max, v_s))
            }
            _ => None,
        }
    }

    /// `dT/d(dv)` of the Coulomb law `T = mu tanh(dv/v_s) Q` at force `f` (`tanh` from
    /// `f/(mu Q)`, no second `exp`): `mu Q (1 - tanh²)/v_s`.
    fn coulomb_slope(mu: f64, v_s: f64, q: f64, f: f64) -> f64 {
        if q <= 0.0 || mu == 0.0 {
            return 0.0;
        }
        let th = f / (mu * q);
        mu * q * (1.0 - th * th) / v_s
    }

    /// The `w_a` column of one ball under [`Self::coulomb_rates`], analytically (the
    /// geometry and loads do not depend on `w_a`): `d(rates)/dw_a`, `d(cage torque)/dw_a`
    /// and `d(wrench)/dw_a` at the point `b` of [`Self::forces`] with its pocket `pk`.
    /// `w_a` enters the slips (`d dv_i = d dv_o = (D/2) d w_a`), the gyroscopic couple
    /// through `w_s` (`d w_s = -d w_a`; the limited force `F = F_b phi(t)`,
    /// `t = mu Q_h/|F_b|`, has `dF/dF_b = phi - t phi'(t) = phi t⁴/(1 + t⁴)`), the pocket
    /// friction through its slide and the spin drag (the terms of the module docs; the
    /// limiter is the quasi-static kernel's, Harris & Kotzalas Vol. 2 ch. 3). Checked
    /// against central differences in a unit test.
    fn wa_column(
        &self,
        (mu, v_s): (f64, f64),
        geo: &Geo,
        b: &BallOut,
        pk: &Pocket,
    ) -> ([f64; 3], f64, [f64; 5]) {
        let p = &self.p;
        let (r, hd) = (0.5 * self.dm, 0.5 * self.d);
        let st = &b.state;
        let dfi = Self::coulomb_slope(mu, v_s, st.q_i, st.f_i) * hd;
        let dfo = Self::coulomb_slope(mu, v_s, st.q_o, st.f_o) * hd;
        // Pocket friction M = -(D/2) mu_c |P| tanh(slide/v_s), slide = (D/2)(w_a cos a - w_c).
        // (`tanh` from the moment itself, no second `exp`.)
        let dmf = if pk.force == 0.0 || p.pocket_friction == 0.0 {
            0.0
        } else {
            let m0 = -hd * p.pocket_friction * pk.force.abs();
            let th = pk.m_fric / m0;
            m0 * (1.0 - th * th) / p.friction_v_s * (hd * self.cos_a)
        };
        let dmd = PI * p.drag_viscosity * self.d.powi(3);
        let dx = [
            0.0,
            (dfi - dfo) / (self.m * r),
            (-hd * (dfi + dfo) + dmf * self.cos_a - dmd) / self.j,
        ];
        let (s, c, n) = (geo.s, geo.c, geo.n);
        let mut dw = [dfi * s, -dfi * c, 0.0, 0.0, 0.0];
        if p.gyroscopic && st.q_i > 0.0 && st.q_o > 0.0 {
            let fb = self.j * st.w_s * st.w_b * self.sin_a / self.d;
            let mu_g = p.gyro_traction;
            let slope = if fb == 0.0 || !mu_g.is_finite() {
                1.0
            } else {
                let t = mu_g * (st.q_i * st.q_o / (st.q_i + st.q_o)) / fb.abs();
                let t4 = t * t * t * t;
                (st.gyro / fb) * t4 / (1.0 + t4)
            };
            let dfg = -slope * self.j * st.w_b * self.sin_a / self.d;
            let (fa, fr) = (-dfg * n[1], dfg * n[0]);
            let m = self.ri * fa + self.fid * dfg;
            for (w, x) in dw.iter_mut().zip([fr * c, fr * s, fa, m * s, -m * c]) {
                *w += x;
            }
        }
        (dx, -dmf, dw)
    }

    /// Integral of [`Self::pen`]: the pocket spring's energy per unit stiffness.
    fn pen_energy(x: f64, w: f64) -> f64 {
        if x <= 0.0 {
            0.0
        } else if x < w {
            x * x * x / (6.0 * w)
        } else {
            0.5 * x * x - 0.5 * w * x + w * w / 6.0
        }
    }

    /// Right-hand side at shaft motion `(q, v, omega)`: fills `dx` and the per-ball and
    /// total results (`self.balls`, return value). Allocation-free.
    pub fn eval(
        &mut self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        dx: &mut [f64],
    ) -> SkidTotals {
        self.eval_inner(q, v, omega, x, dx, None)
    }

    /// [`Self::eval`] plus the shaft stiffness `k = -dW/dq` and damping `c = -dW/dv` with
    /// the balls and cage held (analytic, at the cost of about one right-hand side).
    #[allow(clippy::too_many_arguments)]
    pub fn eval_with_stiffness(
        &mut self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        dx: &mut [f64],
        k: &mut [[f64; 5]; 5],
        c: &mut [[f64; 5]; 5],
    ) -> SkidTotals {
        let mut kw = [[0.0; 5]; 5];
        let tot = self.eval_inner(q, v, omega, x, dx, Some((&mut kw, c)));
        for (kr, wr) in k.iter_mut().zip(kw) {
            for (kk, w) in kr.iter_mut().zip(wr) {
                *kk = -w;
            }
        }
        tot
    }

    #[allow(clippy::type_complexity)]
    fn eval_inner(
        &mut self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        dx: &mut [f64],
        mut kc: Option<(&mut [[f64; 5]; 5], &mut [[f64; 5]; 5])>,
    ) -> SkidTotals {
        let mut tot = SkidTotals::default();
        let ic = self.cage_index();
        let (theta_c, w_c) = (x[ic], x[ic + 1]);
        let mut cage_torque = -self.p.cage_drag * w_c;
        tot.torque_drag -= self.p.cage_drag * w_c;
        tot.power_other += self.p.cage_drag * w_c * w_c;
        if let Some((_, c)) = kc.as_mut() {
            **c = [[0.0; 5]; 5];
        }
        for j in 0..self.z {
            let k = BALL0 + self.bs * j;
            let geo = self.geo(q, x[k]);
            let (u, ud) = if self.bs == 5 {
                (Some(x[k + 3]), x[k + 4])
            } else {
                (None, 0.0)
            };
            let ld = self.loads(&geo, x[k + 1], u);
            let st = [theta_c, w_c, x[k], x[k + 1], x[k + 2], u.unwrap_or(0.0), ud];
            let b = self.forces(
                j,
                &geo,
                &ld,
                q,
                v,
                omega,
                st,
                kc.as_mut().map(|(k, _)| &mut **k),
            );
            if let Some((_, c)) = kc.as_mut() {
                for r in 0..5 {
                    for cc in 0..5 {
                        c[r][cc] += b.cd * b.g[r] * b.g[cc];
                    }
                }
            }
            dx[k..k + self.bs].copy_from_slice(&b.dx[..self.bs]);
            cage_torque += b.cage_torque;
            for (t, w) in tot.wrench.iter_mut().zip(b.wrench) {
                *t += w;
            }
            tot.torque_shaft += b.torque_shaft;
            tot.torque_outer += b.torque_outer;
            tot.torque_drag += b.torque_drag;
            tot.power_contacts += b.power;
            tot.power_other += b.dissipation;
            tot.pocket_energy += b.pocket_energy;
            if b.state.q_i > 0.0 {
                tot.loaded += 1;
            }
            tot.max_load = tot.max_load.max(b.state.q_i).max(b.state.q_o);
            self.balls[j] = b.state;
        }
        dx[ic] = w_c;
        dx[ic + 1] = cage_torque / self.jc;
        tot
    }

    /// Jacobians by per-ball finite differences (each ball's terms depend only on its own
    /// states, the cage's and the ring's, so a column costs one ball evaluation, not a
    /// whole right-hand side; the columns of `w_a` and of the cage reuse the ball's
    /// geometry and loads, which do not depend on them): `jx = d(rates)/d(states)`
    /// (`n × n`, row-major), `jm = d(rates)/d(q, v)` (`n × 10`), `wx = d(wrench)/d(states)`
    /// (`5 × n`), `wm = d(wrench)/d(q, v)` (`5 × 10`). Allocation-free. The entries of
    /// `jx` coupling two different balls are zero and are not written (give a zeroed
    /// buffer; the component's block copy never reads them).
    #[allow(clippy::too_many_arguments)]
    pub fn jacobian(
        &self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        jx: &mut [f64],
        jm: &mut [f64],
        wx: &mut [f64],
        wm: &mut [f64],
        q_cols: &[usize],
    ) {
        let n = self.n_states();
        let ic = self.cage_index();
        // Cleared: each ball row's cage columns (its block is overwritten below) and the
        // cage rows; not the `n²` entries between balls.
        for r in 0..ic {
            jx[r * n + ic..r * n + ic + 2].fill(0.0);
        }
        jx[ic * n..].fill(0.0);
        jm.fill(0.0);
        wx.fill(0.0);
        wm.fill(0.0);
        let (theta_c, w_c) = (x[ic], x[ic + 1]);
        let jc = self.jc;
        let cr = (ic + 1) * n; // the cage speed's row
        jx[ic * n + ic + 1] = 1.0; // d theta_c' / d w_c
        jx[cr + ic + 1] = -self.p.cage_drag / jc;
        let eps = f64::EPSILON.sqrt();
        for j in 0..self.z {
            let bs = self.bs;
            let k = BALL0 + bs * j;
            let mut st = [0.0; 5];
            st[..bs].copy_from_slice(&x[k..k + bs]);
            let radial = |s: &[f64; 5]| (bs == 5).then_some(s[3]);
            let geo = self.geo(q, st[0]);
            let ld = self.loads(&geo, st[1], radial(&st));
            let at = |s5: [f64; 7]| self.forces(j, &geo, &ld, q, v, omega, s5, None);
            let st5 = [theta_c, w_c, st[0], st[1], st[2], st[3], st[4]];
            // The base point, with the analytic wrench stiffness when the ring's columns
            // are wanted.
            let mut kw = [[0.0; 5]; 5];
            let base = if jm.is_empty() {
                at(st5)
            } else {
                self.forces(j, &geo, &ld, q, v, omega, st5, Some(&mut kw))
            };
            let pk0 = self.pocket(j, [theta_c, w_c, st[0], st[1], st[2]]);
            let coulomb = self.coulomb_rates(&ld);
            // Ball columns.
            for col in 0..bs {
                if let (2, Some(law)) = (col, coulomb) {
                    let (d, dc, dw) = self.wa_column(law, &geo, &base, &pk0);
                    let c = k + 2;
                    for (r, dr) in d.iter().enumerate() {
                        jx[(k + r) * n + c] = *dr;
                    }
                    jx[cr + c] = dc / jc;
                    if !wx.is_empty() {
                        for (r, dr) in dw.iter().enumerate() {
                            wx[r * n + c] = *dr;
                        }
                    }
                    continue;
                }
                // psi: 1e-7 rad (the loads' solve leaves a relative noise of ~1e-13 in
                // the rates, which a 1e-9 step would amplify to ~30 %).
                let h = match col {
                    0 => 1e-7,
                    3 => 1e-4 * st[3].abs().max(1e-8),
                    4 => 1e-6,
                    _ => eps * st[col].abs().max(1.0),
                };
                let mut sp = st;
                sp[col] += h;
                let s5 = [theta_c, w_c, sp[0], sp[1], sp[2], sp[3], sp[4]];
                let b = match col {
                    // w_a, u': same geometry and loads.
                    2 | 4 => at(s5),
                    // w_b, u: same geometry, new loads.
                    1 | 3 => {
                        let ld1 = self.loads(&geo, sp[1], radial(&sp));
                        self.forces(j, &geo, &ld1, q, v, omega, s5, None)
                    }
                    _ => self.ball_r(j, q, v, omega, s5),
                };
                let c = k + col;
                for r in 0..bs {
                    jx[(k + r) * n + c] = (b.dx[r] - base.dx[r]) / h;
                }
                jx[cr + c] = (b.cage_torque - base.cage_torque) / (h * jc);
                if !wx.is_empty() {
                    for r in 0..5 {
                        wx[r * n + c] = (b.wrench[r] - base.wrench[r]) / h;
                    }
                }
            }
            // Cage columns: only the pocket terms depend on the cage.
            let rr = 0.5 * self.dm;
            for col in 0..2 {
                let (tc, wc, h) = if col == 0 {
                    (theta_c + 1e-9, w_c, 1e-9)
                } else {
                    let h = eps * w_c.abs().max(1.0);
                    (theta_c, w_c + h, h)
                };
                let pk = self.pocket(j, [tc, wc, st[0], st[1], st[2]]);
                let (dp, dmf) = (pk.force - pk0.force, pk.m_fric - pk0.m_fric);
                jx[(k + 1) * n + ic + col] = dp / (self.m * rr * h);
                jx[(k + 2) * n + ic + col] = dmf * self.cos_a / (self.j * h);
                jx[cr + ic + col] += (-rr * dp - dmf) / (h * jc);
            }
            if jm.is_empty() {
                continue;
            }
            // Velocity columns: only the contact damping `-cd g g^T` depends on v (and,
            // with radial mass, the ball's radial acceleration through the same term).
            for r in 0..5 {
                for c in 0..5 {
                    wm[r * 10 + 5 + c] -= base.cd * base.g[r] * base.g[c];
                }
            }
            if bs == 5 {
                for c in 0..5 {
                    jm[(k + 4) * 10 + 5 + c] = base.cd * base.g[c] / self.m;
                }
            }
            // Displacement columns. The rates depend on q only through three scalars:
            // the loads Q_i, Q_o and the direction of the contact line (n rotates by
            // d theta = n1 dn0 - n0 dn1, a unit vector). Difference along each and chain
            // with their analytic derivatives (no new geometry or split); the wrench's
            // columns are the analytic stiffness. (With radial mass the damping of the
            // ball's radial motion also sees q through the ring-geometry rate `delta'`; that
            // small term is left out of this Jacobian, which only costs step efficiency.)
            let dl = self.load_derivs(&geo, &ld);
            let mut dpar = [[0.0; 5]; 3]; // dpar[param][rate]: d(rates)/d(Q_i, Q_o, theta)
            let mut dcage = [0.0; 3];
            let sp0 = ld.sp;
            for (kp, dp) in dpar.iter_mut().enumerate() {
                let (mut gp, mut lp) = (geo, ld);
                let h;
                match kp {
                    0 | 1 => {
                        let (q0, s0) = if kp == 0 {
                            (sp0.q_i, sp0.s_i)
                        } else {
                            (sp0.q_o, sp0.s_o)
                        };
                        if s0 <= 0.0 {
                            continue;
                        }
                        if let Some((mu, v_s)) = coulomb {
                            // Linear in the load through the traction: dT/dQ = T/Q
                            // (mu tanh(dv/v_s) at no load); the cage does not see it.
                            let (f, dv) = if kp == 0 {
                                (base.state.f_i, base.state.dv_i)
                            } else {
                                (base.state.f_o, base.state.dv_o)
                            };
                            let df = if q0 > 0.0 {
                                f / q0
                            } else {
                                mu * crate::contact::traction::tanh(dv / v_s)
                            };
                            let sign = if kp == 0 { 1.0 } else { -1.0 };
                            dp[1] = sign * df / (self.m * 0.5 * self.dm);
                            dp[2] = -0.5 * self.d * df / self.j;
                            continue;
                        }
                        h = 1e-7 * q0.max(1e-3);
                        let sp = &mut lp.sp;
                        let (qq, rr) = if kp == 0 {
                            (&mut sp.q_i, &mut sp.r_i)
                        } else {
                            (&mut sp.q_o, &mut sp.r_o)
                        };
                        *qq += h;
                        *rr = (*rr * *rr + h / s0).sqrt();
                    }
                    _ => {
                        // Without spin friction and radial mass the rates and the cage
                        // torque do not read the contact line's direction (only the
                        // wrench does): the difference is exactly zero, as left.
                        if self.p.spin_friction <= 0.0 && !ld.radial {
                            continue;
                        }
                        h = 1e-8;
                        gp.n = [geo.n[0] + h * geo.n[1], geo.n[1] - h * geo.n[0]];
                    }
                }
                let b = self.forces_on::<false>(j, &gp, &lp, q, v, omega, st5, None);
                for ((d, bx), b0) in dp.iter_mut().zip(b.dx).zip(base.dx) {
                    *d = (bx - b0) / h;
                }
                dcage[kp] = (b.cage_torque - base.cage_torque) / h;
            }
            for &col in q_cols {
                for r in 0..5 {
                    wm[r * 10 + col] += kw[r][col];
                }
                let dth = geo.n[1] * dl.dn0[col] - geo.n[0] * dl.dn1[col];
                let chain = [dl.dqi[col], dl.dqo[col], dth];
                for r in 0..bs {
                    jm[(k + r) * 10 + col] = (0..3).map(|kp| dpar[kp][r] * chain[kp]).sum();
                }
                jm[(ic + 1) * 10 + col] += (0..3).map(|kp| dcage[kp] * chain[kp]).sum::<f64>() / jc;
            }
        }
    }

    /// Ball `j`'s outer-race contact at the last evaluation: the contact data of the
    /// traction law, the slip `dv_o` and the rolling speed `u_o` (m/s).
    pub fn outer_contact(&self, j: usize) -> (ContactState, f64, f64) {
        let b = &self.balls[j];
        let r = (b.q_o.max(0.0) / self.outer.kc).cbrt().sqrt();
        let u_o = 0.5 * (0.5 * self.do_ * b.w_b + 0.5 * self.d * b.w_s);
        (self.contact_state(false, b.q_o.max(0.0), r), b.dv_o, u_o)
    }

    /// Hertz approach of the outer contact under load `q`, m.
    pub fn outer_approach(&self, q: f64) -> f64 {
        (q.max(0.0) / self.outer.kc).powf(2.0 / 3.0)
    }

    /// Peak Hertz pressure at the larger of a ball's two loads, Pa.
    pub fn peak_pressure(&self, q_i: f64, q_o: f64) -> f64 {
        // p0 = 3Q/(2 pi a b) with a b = ca cb Q^(2/3) (coefficients per sqrt(delta) here).
        let p0 = |q: f64, ax: [f64; 2], k3: f64| {
            if q > 0.0 {
                let q3 = q.cbrt();
                1.5 * q3 * k3 * k3 / (PI * ax[0] * ax[1])
            } else {
                0.0
            }
        };
        p0(q_i, self.ax_i, self.kc3_i).max(p0(q_o, self.ax_o, self.kc3_o))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::preset;

    /// At the kinematic speeds of docs/physics.md §1 both slips vanish, for a deep-groove and
    /// an angular-contact bearing.
    #[test]
    fn zero_slip_at_kinematic_speeds() {
        for name in ["6012", "7008ce"] {
            let b = preset(name).unwrap().build().unwrap();
            let mut m = SkiddingModel::new(&b, SkiddingParams::default()).unwrap();
            let mut x = vec![0.0; m.n_states()];
            let omega = 300.0;
            m.init(omega, &mut x);
            let mut dx = vec![0.0; x.len()];
            m.eval(&[0.0; 5], &[0.0; 5], omega, &x, &mut dx);
            for bs in &m.balls {
                assert!(bs.dv_i.abs() < 1e-12 && bs.dv_o.abs() < 1e-12, "{bs:?}");
            }
            let k = crate::geometry::kinematics::kinematics(&b, omega);
            assert!((m.balls[0].w_b - k.cage_speed).abs() < 1e-12);
            assert!((m.balls[0].w_s - k.ball_spin_speed).abs() < 1e-9);
        }
    }

    /// The analytic stiffness `-dW/dq` and damping `-dW/dv` of the outputs equal the
    /// finite-difference Jacobian of the wrench (balls held), with every term on: contact
    /// damping at a moving ring, gyroscopic and spin friction (and none), each traction
    /// law, a ball off the inner race.
    #[test]
    fn analytic_stiffness_matches_finite_differences() {
        use crate::contact::traction::MixedEhl;
        let b = preset("7008ce").unwrap().build().unwrap();
        // The last case without spin friction: the contact line's direction then drops
        // out of the rates (its column of d(rates)/dq is not differenced).
        for (law, omega, spin_friction) in [
            (TractionLaw::default(), 2500.0, 0.05),
            (TractionLaw::MixedEhl(MixedEhl::default()), 1500.0, 0.05),
            (TractionLaw::default(), 2500.0, 0.0),
        ] {
            let p = SkiddingParams {
                traction: law,
                contact_damping: 50.0,
                spin_friction,
                spacing_scatter: 0.5,
                ..SkiddingParams::default()
            };
            let mut m = SkiddingModel::new(&b, p).unwrap();
            let n = m.n_states();
            let mut x = vec![0.0; n];
            m.init(omega, &mut x);
            // Perturb the ball speeds so that every contact slips and spins.
            for j in 0..m.z() {
                x[BALL0 + 3 * j + 1] *= 1.0 + 0.01 * (j as f64 - 7.0) / 7.0;
                x[BALL0 + 3 * j + 2] *= 1.0 - 0.02 * (j as f64 - 3.0) / 7.0;
            }
            // Axial preload, radial offset (unloads some balls), tilt, a moving ring.
            let q = [4e-6, -12e-6, 10e-6, 2e-4, -1e-4];
            let v = [1e-3, -2e-3, 5e-4, 0.02, 0.01];
            let mut dx = vec![0.0; n];
            let (mut k, mut c) = ([[0.0; 5]; 5], [[0.0; 5]; 5]);
            m.eval_with_stiffness(&q, &v, omega, &x, &mut dx, &mut k, &mut c);
            assert!(m.balls.iter().any(|s| s.q_i == 0.0), "a ball off the race");
            assert!(m
                .balls
                .iter()
                .any(|s| s.gyro != 0.0 && (s.spin_i != 0.0) == (spin_friction > 0.0)));
            let mut dx2 = vec![0.0; n];
            m.eval(&q, &v, omega, &x, &mut dx2);
            assert_eq!(dx, dx2, "the same rates");
            let (mut jx, mut jm, mut wx, mut wm) = (
                vec![0.0; n * n],
                vec![0.0; n * 10],
                vec![0.0; 5 * n],
                vec![0.0; 50],
            );
            // Central differences of the wrench in q for the reference.
            let mut kfd = [[0.0; 5]; 5];
            for col in 0..5 {
                let h = if col < 3 { 1e-10 } else { 1e-8 };
                let (mut qp, mut qm) = (q, q);
                qp[col] += h;
                qm[col] -= h;
                let wp = m.eval(&qp, &v, omega, &x, &mut dx2).wrench;
                let wn = m.eval(&qm, &v, omega, &x, &mut dx2).wrench;
                for r in 0..5 {
                    kfd[r][col] = -(wp[r] - wn[r]) / (2.0 * h);
                }
            }
            m.jacobian(
                &q,
                &v,
                omega,
                &x,
                &mut jx,
                &mut jm,
                &mut wx,
                &mut wm,
                &[0, 1, 2, 3, 4],
            );
            // The integrator's d(rates)/dq (differenced along the analytic load
            // derivatives) against central differences of whole right-hand sides.
            let (mut dp, mut dm) = (vec![0.0; n], vec![0.0; n]);
            for col in 0..5 {
                let h = if col < 3 { 1e-10 } else { 1e-8 };
                let (mut qp, mut qm) = (q, q);
                qp[col] += h;
                qm[col] -= h;
                m.eval(&qp, &v, omega, &x, &mut dp);
                m.eval(&qm, &v, omega, &x, &mut dm);
                for r in 0..n {
                    let fd = (dp[r] - dm[r]) / (2.0 * h);
                    let an = jm[r * 10 + col];
                    let scale = (0..5).map(|c| jm[r * 10 + c].abs()).fold(1e-3, f64::max);
                    assert!(
                        (an - fd).abs() <= 1e-2 * scale,
                        "{law:?} jm[{r}][{col}] {an:e} vs {fd:e}"
                    );
                }
                for r in 0..5 {
                    let (w, kk) = (wm[r * 10 + col], -k[r][col]);
                    assert!(
                        (w - kk).abs() <= 1e-12 * kk.abs(),
                        "wm is the analytic stiffness"
                    );
                }
            }
            // d(rates)/d(states), every column, against central differences.
            for col in 0..n {
                let h = 1e-7 * x[col].abs().max(1e-2);
                let (mut xp, mut xm) = (x.clone(), x.clone());
                xp[col] += h;
                xm[col] -= h;
                m.eval(&q, &v, omega, &xp, &mut dp);
                m.eval(&q, &v, omega, &xm, &mut dm);
                for r in 0..n {
                    let fd = (dp[r] - dm[r]) / (2.0 * h);
                    let an = jx[r * n + col];
                    let scale = (0..n).map(|c| jx[r * n + c].abs()).fold(1e-3, f64::max);
                    assert!(
                        (an - fd).abs() <= 1e-2 * scale,
                        "{law:?} jx[{r}][{col}] {an:e} vs {fd:e}"
                    );
                }
            }
            for r in 0..5 {
                let scale = kfd[r].iter().map(|v| v.abs()).fold(0.0, f64::max);
                for col in 0..5 {
                    let (a, f) = (k[r][col], kfd[r][col]);
                    assert!(
                        (a - f).abs() <= 1e-5 * scale,
                        "{law:?} K[{r}][{col}] analytic {a:e} vs fd {f:e}"
                    );
                    assert!(
                        (c[r][col] + wm[r * 10 + 5 + col]).abs() <= 1e-9 * c[r][r].abs().max(1.0)
                    );
                }
            }
        }
    }

    thread_local! {
        /// Test switch: difference every column (no analytic Coulomb columns).
        pub(super) static FD_ONLY: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    }

    /// Under the Coulomb law without spin friction the `w_a` columns and the load slopes
    /// `d(rates)/dQ` are analytic. Relative to each row's largest entry (rates, cage and
    /// wrench rows; every ball, one off the inner race, pockets in contact): the `w_a`
    /// columns equal central differences to 1e-7 and the forward differences they replace
    /// to 1e-4 (those carry a truncation error); `d(rates)/dq` equals its forward-difference
    /// form to 1e-5 (1e-3 in the rows of a ball pressed into its pocket: the
    /// difference's rounding noise); every other entry is unchanged bit for bit.
    #[test]
    fn analytic_coulomb_columns_match_the_differences() {
        let b = preset("7008ce").unwrap().build().unwrap();
        let p = SkiddingParams {
            contact_damping: 50.0,
            spacing_scatter: 0.5,
            ..SkiddingParams::default()
        };
        assert!(p.spin_friction == 0.0 && matches!(p.traction, TractionLaw::Coulomb { .. }));
        let mut m = SkiddingModel::new(&b, p).unwrap();
        let n = m.n_states();
        let omega = 2500.0;
        let mut x = vec![0.0; n];
        m.init(omega, &mut x);
        for j in 0..m.z() {
            x[BALL0 + 3 * j] += 6e-3 * (j as f64 - 7.5) / 7.5; // some pockets in contact
            x[BALL0 + 3 * j + 1] *= 1.0 + 0.01 * (j as f64 - 7.0) / 7.0;
            x[BALL0 + 3 * j + 2] *= 1.0 - 0.02 * (j as f64 - 3.0) / 7.0;
        }
        let q = [4e-6, -12e-6, 10e-6, 2e-4, -1e-4];
        let v = [1e-3, -2e-3, 5e-4, 0.02, 0.01];
        let mut dx = vec![0.0; n];
        m.eval(&q, &v, omega, &x, &mut dx);
        assert!(m.balls.iter().any(|s| s.q_i == 0.0), "a ball off the race");
        let pockets: Vec<bool> = m.balls.iter().map(|s| s.pocket != 0.0).collect();
        assert!(pockets.contains(&true) && pockets.contains(&false));
        assert!(m.balls.iter().any(|s| s.gyro != 0.0));
        let run = |fd: bool| {
            FD_ONLY.with(|c| c.set(fd));
            let mut out = (vec![0.0; n * n], vec![0.0; n * 10], vec![0.0; 5 * n]);
            let mut wm = vec![0.0; 50];
            m.jacobian(
                &q,
                &v,
                omega,
                &x,
                &mut out.0,
                &mut out.1,
                &mut out.2,
                &mut wm,
                &[0, 1, 2, 3, 4],
            );
            FD_ONLY.with(|c| c.set(false));
            out
        };
        let (ax, am, aw) = run(false);
        let (fx, fm, fw) = run(true);
        // Central differences of whole right-hand sides in each ball's w_a (the reference:
        // the forward differences replaced carry a truncation error of ~1e-5).
        let z = m.z();
        let (mut cx, mut cw) = (vec![0.0; n * n], vec![0.0; 5 * n]);
        let (mut dp, mut dm) = (vec![0.0; n], vec![0.0; n]);
        for j in 0..z {
            let c = BALL0 + 3 * j + 2;
            let h = 1e-7 * x[c].abs().max(1.0);
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[c] += h;
            xm[c] -= h;
            let wp = m.eval(&q, &v, omega, &xp, &mut dp).wrench;
            let wn = m.eval(&q, &v, omega, &xm, &mut dm).wrench;
            for r in 0..n {
                cx[r * n + c] = (dp[r] - dm[r]) / (2.0 * h);
            }
            for r in 0..5 {
                cw[r * n + c] = (wp[r] - wn[r]) / (2.0 * h);
            }
        }
        let (mut to_central, mut to_forward, mut slopes): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for (a, f, cd, cols) in [
            (&ax, &fx, Some(&cx), n),
            (&aw, &fw, Some(&cw), n),
            (&am, &fm, None, 10),
        ] {
            for r in 0..a.len() / cols {
                let row = r * cols..(r + 1) * cols;
                let scale = f[row.clone()].iter().fold(1e-300f64, |s, v| s.max(v.abs()));
                for i in row {
                    let c = i % cols;
                    let rel = |u: f64, w: f64| (u - w).abs() / scale;
                    match cd {
                        // A w_a column: against central differences, and what moved.
                        Some(cd) if c < BALL0 + 3 * z && c % 3 == 2 => {
                            to_central = to_central.max(rel(a[i], cd[i]));
                            to_forward = to_forward.max(rel(a[i], f[i]));
                        }
                        // d(rates)/dq through the load slopes (the forward differences of a
                        // function linear in the load differ by rounding only).
                        // (Loose where a pocket force dominates the rate: the forward
                        // difference's rounding noise.)
                        None if r < BALL0 + 3 * z && pockets[r / 3] => {
                            assert!(rel(a[i], f[i]) <= 1e-3, "row {r} col {c}");
                        }
                        None => slopes = slopes.max(rel(a[i], f[i])),
                        _ => assert_eq!(a[i].to_bits(), f[i].to_bits(), "row {r} col {c}"),
                    }
                }
            }
        }
        assert!(
            to_central <= 1e-7,
            "w_a columns vs central differences: {to_central:e}"
        );
        assert!(
            to_forward <= 1e-4,
            "w_a columns vs forward differences: {to_forward:e}"
        );
        assert!(
            slopes <= 1e-5,
            "load slopes vs forward differences: {slopes:e}"
        );
        assert!(to_forward > 0.0 && slopes > 0.0, "computed differently");
        eprintln!("w_a columns: {to_central:.1e} from central, {to_forward:.1e} from forward differences; d(rates)/dq: {slopes:.1e} (of each row's largest entry)");
    }

    /// Force split with centrifugal force: `Q_o - Q_i = Fc` and the approaches add up.
    #[test]
    fn split_balances_the_centrifugal_force() {
        let b = preset("6012").unwrap().build().unwrap();
        let m = SkiddingModel::new(&b, SkiddingParams::default()).unwrap();
        for (delta, f) in [(5e-6, 3.0), (5e-6, 0.0), (-2e-6, 3.0), (1e-7, 50.0)] {
            let Split {
                q_i: qi, q_o: qo, ..
            } = m.split(delta, f);
            assert!(
                (qo - qi - f).abs() < 1e-8 * (1.0 + qo),
                "{delta} {f}: {qi} {qo}"
            );
            if qi > 0.0 {
                let sum = m.inner.deflection(qi) + m.outer.deflection(qo);
                assert!((sum - delta).abs() < 1e-12, "{sum} vs {delta}");
            }
        }
        assert_eq!(m.split(-1e-6, 0.0), Split::default());
        // The semi-axes from sqrt(delta) and the peak pressure agree with the Hertz API.
        let sp = m.split(5e-6, 3.0);
        let ci = m.contact_state(true, sp.q_i, sp.r_i);
        let (a, bb) = m.inner.semi_axes(sp.q_i);
        assert!((ci.a / a - 1.0).abs() < 1e-12 && (ci.b / bb - 1.0).abs() < 1e-12);
        let p = m.peak_pressure(sp.q_i, 0.0);
        assert!((p / m.inner.peak_pressure(sp.q_i) - 1.0).abs() < 1e-12);
        let p = m.peak_pressure(0.0, sp.q_o);
        assert!((p / m.outer.peak_pressure(sp.q_o) - 1.0).abs() < 1e-12);
    }

    /// The 7008CE at 6000 rpm (the speed goal's scene, settled 20 ms) under ROS34PW2 in
    /// 0.1 ms component steps: the W-method
    /// carries its Jacobian from step to step (a few per 20 steps, not one a step), the
    /// step after a state is taken starts with a fresh one, and the state continues bit for
    /// bit when restored in the same component or in a new one. On the way: the peak
    /// pressure output (from the largest loads) is the largest of the balls', bit for bit.
    #[test]
    fn ros34pw2_carries_its_jacobian_across_steps_and_a_taken_state_restores_bit_for_bit() {
        use crate::component::{variables, Component};
        let omega = 6000.0 * std::f64::consts::PI / 30.0;
        let text = include_str!("../../../examples/scenes/7008ce-runup.toml")
            .replace(
                "\"shaft.omega\" = 0.0",
                &format!("\"shaft.omega\" = {omega}"),
            )
            .replace("method = \"rosenbrock\"", "method = \"ros34pw2\"");
        let forces = ["force.x", "force.y", "force.z", "cage.omega"]
            .map(|n| variables::by_name(n).unwrap().vr);
        let steps = |c: &mut Component, n: usize| -> Vec<u64> {
            let mut bits = Vec::new();
            for _ in 0..n {
                c.do_step(c.time(), 1e-4).unwrap();
                bits.extend(forces.iter().map(|&v| c.get_real(v).unwrap().to_bits()));
            }
            bits
        };
        let mut c = Component::from_text(&text).unwrap();
        for _ in 0..20 {
            c.do_step(c.time(), 1e-3).unwrap();
        }
        let s0 = c.stats();
        steps(&mut c, 20);
        let s1 = c.stats();
        let (jac, acc) = (s1.jacobians - s0.jacobians, s1.accepted - s0.accepted);
        println!("20 steps: {jac} Jacobians, {acc} accepted, {s1:?}");
        assert!(acc >= 20 && jac <= 1 + acc / 5, "{s0:?} {s1:?}");
        // The peak-pressure output (from the largest loads) is the largest of the balls'.
        let p_out = c.get_real(variables::by_name("contact.max_pressure").unwrap().vr);
        let m = c.skidding_mut().unwrap().model();
        let per_ball = m
            .balls
            .iter()
            .map(|b| m.peak_pressure(b.q_i, b.q_o))
            .fold(0.0, f64::max);
        assert!(per_ball > 1e8);
        assert_eq!(p_out.unwrap().to_bits(), per_ball.to_bits());
        let saved = c.get_state();
        let j = c.stats().jacobians;
        c.do_step(c.time(), 1e-4).unwrap();
        assert_eq!(c.stats().jacobians, j + 1, "a fresh J after get_state");
        c.set_state(&saved).unwrap();
        let first = steps(&mut c, 12);
        c.set_state(&saved).unwrap();
        assert_eq!(first, steps(&mut c, 12));
        let mut d = Component::from_text(&text).unwrap();
        d.set_state(&saved).unwrap();
        assert_eq!(first, steps(&mut d, 12));
    }
}
