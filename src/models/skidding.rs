//! Skidding level: ball orbit and spin, cage, traction, lubricant drag (physics.md §5.2;
//! studies [2] and [3]; Harris & Kotzalas Vol. 2 ch. 3 for the slip kinematics, Gupta
//! *Advanced Dynamics of Rolling Elements* ch. 3–4 for the ball and cage equations).
//!
//! # Free-body diagram and sign conventions
//!
//! Fixed frame as physics.md §0: `z` along the shaft, ball `j` at azimuth `psi_j`, radial
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
//! (outer fixed). Slip velocities, as in physics.md §5.2 with the spin relative to the cage
//! frame `w_s = w_b cos(alpha) - w_a`:
//!
//! - `dv_i = (d_i/2) omega - [(dm/2) w_b - (D/2) w_a] = (d_i/2)(omega - w_b) - (D/2) w_s`
//!   (race minus ball: positive when the race drags the ball forward),
//! - `dv_o = (dm/2) w_b + (D/2) w_a = (d_o/2) w_b - (D/2) w_s` (ball minus race: positive
//!   when the ball surface slides forward over the fixed race).
//!
//! Both vanish at the kinematic speeds of physics.md §1: `w_b = omega (1 - gamma)/2`,
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
//! same with both contact angles free; here the two contacts stay collinear, so the
//! gyroscopic moment `J w_R w_b sin(beta)` has no component along `n_j` and does not change
//! the loads — it would be carried by lateral friction, not modelled).
//!
//! Drag (physics.md §5.2): `F_d = C_d rho_eff pi D² v|v|/8` with `v = (dm/2) w_b` (dynamic
//! pressure on the frontal area); ball spin drag `M = pi eta D³ w_a` (Stokes' rotating
//! sphere, `8 pi eta R³ w`); cage drag `M_cage = c_cage w_c` (linear viscous).

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
    /// Slip speed regularising the pocket friction, m/s.
    pub friction_v_s: f64,
    /// Contact damping on the shaft, N s/m per loaded ball (as the ring level:
    /// `c d(delta)/dt` blended in over [`crate::models::ring::DAMPING_RAMP`]).
    pub contact_damping: f64,
}

impl Default for SkiddingParams {
    fn default() -> Self {
        SkiddingParams {
            traction: TractionLaw::default(),
            pocket_clearance: 0.1e-3,
            pocket_stiffness: 1e7,
            pocket_damping: 200.0,
            pocket_friction: 0.05,
            pocket_smoothing: 1e-6,
            drag_coefficient: 0.5,
            drag_density: 10.0,
            drag_viscosity: 0.0,
            cage_drag: 0.0,
            spacing_scatter: 0.0,
            seed: 1,
            friction_v_s: 0.05,
            contact_damping: 0.0,
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
}

/// One ball's terms.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BallOut {
    /// Rates of `(psi, w_b, w_a)`.
    pub dx: [f64; 3],
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

/// State layout: `[theta_c, w_c, (psi_j, w_b_j, w_a_j) for j in 0..Z]`.
pub const BALL0: usize = 2;

/// The skidding model of one bearing.
#[derive(Debug, Clone)]
pub struct SkiddingModel {
    /// Options.
    pub p: SkiddingParams,
    z: usize,
    d: f64,
    dm: f64,
    cos_a: f64,
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
        Ok(SkiddingModel {
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

    /// Number of states `2 + 3 Z`.
    pub fn n_states(&self) -> usize {
        BALL0 + 3 * self.z
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
    /// `omega`, outer ring fixed (physics.md §1).
    pub fn kinematic(&self, omega: f64) -> (f64, f64) {
        let gamma = self.d * self.cos_a / self.dm;
        let wb = 0.5 * omega * (1.0 - gamma);
        (wb, wb * self.do_ / self.d)
    }

    /// Initial states: balls centred in their pockets, everything turning at the
    /// kinematic speeds of `omega` (from rest when `omega = 0`).
    pub fn init(&self, omega: f64, x: &mut [f64]) {
        let (wb, ws) = self.kinematic(omega);
        x[0] = 0.0;
        x[1] = wb;
        for j in 0..self.z {
            let k = BALL0 + 3 * j;
            x[k] = 2.0 * PI * j as f64 / self.z as f64 + self.offsets[j];
            x[k + 1] = wb;
            x[k + 2] = wb * self.cos_a - ws;
        }
    }

    /// Angular momentum about z of balls and cage, kg m²/s.
    pub fn angular_momentum(&self, x: &[f64]) -> f64 {
        let r2 = 0.25 * self.dm * self.dm;
        let mut l = self.jc * x[1];
        for j in 0..self.z {
            let k = BALL0 + 3 * j;
            l += self.m * r2 * x[k + 1] + self.j * self.cos_a * x[k + 2];
        }
        l
    }

    /// Kinetic energy of balls (orbit and rolling spin) and cage, J.
    pub fn kinetic_energy(&self, x: &[f64]) -> f64 {
        let r2 = 0.25 * self.dm * self.dm;
        let mut e = 0.5 * self.jc * x[1] * x[1];
        for j in 0..self.z {
            let k = BALL0 + 3 * j;
            e += 0.5 * self.m * r2 * x[k + 1].powi(2) + 0.5 * self.j * x[k + 2].powi(2);
        }
        e
    }

    /// Ball position along the contact line: solve `Q_o(d_o) - Q_i(delta - d_o) = f` for
    /// the outer approach `d_o` (monotone; safeguarded Newton). Returns `(Q_i, Q_o)`.
    fn split(&self, delta: f64, f: f64) -> (f64, f64) {
        let (ki, ko) = (self.inner.kc, self.outer.kc);
        if f <= 0.0 && delta <= 0.0 {
            return (0.0, 0.0);
        }
        let f = f.max(0.0);
        // Bracket [lo, hi]: g(0) <= 0, g(max(delta, 0) + (f/ko)^(2/3)) >= 0.
        let mut lo = 0.0;
        let fo = {
            let t = f / ko;
            (t * t).cbrt()
        };
        let mut hi = delta.max(0.0) + fo;
        // Start from the f = 0 split (equal loads) or the outer-only contact.
        let mut x = if delta > 0.0 {
            let r = self.kratio;
            (delta * r / (1.0 + r) + fo * 0.5).min(hi)
        } else {
            hi
        };
        let g = |x: f64| {
            let (qo, so) = crate::contact::hertz_load_and_stiffness(ko, x);
            let (qi, si) = crate::contact::hertz_load_and_stiffness(ki, delta - x);
            (qo - qi - f, so + si, qi, qo)
        };
        let tol = 1e-13 * hi.max(1e-9);
        for _ in 0..60 {
            let (r, dr, _, _) = g(x);
            if r > 0.0 {
                hi = x;
            } else {
                lo = x;
            }
            let mut xn = if dr > 0.0 {
                x - r / dr
            } else {
                0.5 * (lo + hi)
            };
            if !(xn > lo && xn < hi) {
                xn = 0.5 * (lo + hi);
            }
            if (xn - x).abs() <= tol || hi - lo <= tol {
                let (_, _, qi, qo) = g(xn);
                return (qi, qo);
            }
            x = xn;
        }
        let (_, _, qi, qo) = g(x);
        (qi, qo)
    }

    fn contact_state(pc: &PointContact, q: f64) -> ContactState {
        let (a, b) = pc.semi_axes(q);
        ContactState {
            q,
            a,
            b,
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

    /// One ball's contribution at shaft motion `(q, v, omega)`, cage `(theta_c, w_c)` and
    /// ball states `(psi, w_b, w_a)`. Allocation-free.
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
        let p = &self.p;
        let r = 0.5 * self.dm;
        let hd = 0.5 * self.d;
        let (s, c) = psi.sin_cos();
        // Normal loads (Jones geometry of the ring level).
        let a1 = self.a10 + q[2] + self.ri * (q[3] * s - q[4] * c);
        let a2 = self.a20 + q[0] * c + q[1] * s;
        let l = a1.hypot(a2);
        let n = [a1 / l, a2 / l];
        let delta = l - self.a;
        let fc = self.m * r * w_b * w_b;
        let (q_i, q_o) = self.split(delta, fc * n[1]);
        // Slip.
        let dv_i = 0.5 * self.di * omega - (r * w_b - hd * w_a);
        let dv_o = r * w_b + hd * w_a;
        let u_i = 0.5 * (0.5 * self.di * (omega - w_b) + hd * (w_b * self.cos_a - w_a));
        let u_o = 0.5 * (0.5 * self.do_ * w_b + hd * (w_b * self.cos_a - w_a));
        let (ci, co) = if p.traction.needs_contact() {
            (
                Self::contact_state(&self.inner, q_i),
                Self::contact_state(&self.outer, q_o),
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
        // Pocket.
        let pocket_angle = theta_c + 2.0 * PI * j as f64 / self.z as f64 + self.offsets[j];
        let xi = r * (psi - pocket_angle);
        let xi_dot = r * (w_b - w_c);
        let cp = p.pocket_clearance;
        let w = p.pocket_smoothing;
        let (pl, bl) = Self::pen(xi - cp, w);
        let (pt, bt) = Self::pen(-xi - cp, w);
        let pocket = -p.pocket_stiffness * (pl - pt) - p.pocket_damping * (bl + bt) * xi_dot;
        let slide = hd * (w_a * self.cos_a - w_c);
        let m_fric = -hd * p.pocket_friction * pocket.abs() * (slide / p.friction_v_s).tanh();
        // Drag.
        let vb = r * w_b;
        let f_d = p.drag_coefficient * p.drag_density * PI * self.d * self.d * vb * vb.abs() / 8.0;
        let m_d = PI * p.drag_viscosity * self.d.powi(3) * w_a;
        let dx = [
            w_b,
            (f_i - f_o + pocket - f_d) / (self.m * r),
            (-hd * (f_i + f_o) + m_fric * self.cos_a - m_d) / self.j,
        ];
        // On the shaft: normal load along -n through the groove centre, traction -f_i e_t
        // at the inner contact.
        let g = [
            n[1] * c,
            n[1] * s,
            n[0],
            n[0] * self.ri * s,
            -n[0] * self.ri * c,
        ];
        let mut fn_ = q_i;
        let mut cd = 0.0;
        if p.contact_damping > 0.0 && delta > 0.0 {
            let da1 =
                v[2] + self.ri * (v[3] * s - v[4] * c) + w_b * self.ri * (q[3] * c + q[4] * s);
            let da2 = v[0] * c + v[1] * s + w_b * (-q[0] * s + q[1] * c);
            let blend = (delta / crate::models::ring::DAMPING_RAMP).min(1.0);
            cd = p.contact_damping * blend;
            fn_ += cd * (n[0] * da1 + n[1] * da2);
        }
        let mut wrench = [0.0; 5];
        for (wk, gk) in wrench.iter_mut().zip(g) {
            *wk = -fn_ * gk;
        }
        wrench[0] += f_i * s;
        wrench[1] -= f_i * c;
        BallOut {
            dx,
            cage_torque: -r * pocket - m_fric,
            wrench,
            torque_shaft: -0.5 * self.di * f_i,
            torque_outer: 0.5 * self.do_ * f_o,
            torque_drag: -(r * f_d + self.cos_a * m_d),
            power: f_i * dv_i + f_o * dv_o,
            pocket_energy: p.pocket_stiffness
                * (Self::pen_energy(xi - cp, w) + Self::pen_energy(-xi - cp, w)),
            dissipation: p.pocket_damping * (bl + bt) * xi_dot * xi_dot
                - m_fric * (w_a * self.cos_a - w_c)
                + f_d * vb
                + m_d * w_a,
            g,
            cd,
            state: BallState {
                psi,
                w_b,
                w_s: w_b * self.cos_a - w_a,
                q_i,
                q_o,
                dv_i,
                dv_o,
                f_i,
                f_o,
                pocket,
            },
        }
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
        let mut tot = SkidTotals::default();
        let (theta_c, w_c) = (x[0], x[1]);
        let mut cage_torque = -self.p.cage_drag * w_c;
        tot.torque_drag -= self.p.cage_drag * w_c;
        tot.power_other += self.p.cage_drag * w_c * w_c;
        for j in 0..self.z {
            let k = BALL0 + 3 * j;
            let b = self.ball(j, q, v, omega, theta_c, w_c, x[k], x[k + 1], x[k + 2]);
            dx[k..k + 3].copy_from_slice(&b.dx);
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
        dx[0] = w_c;
        dx[1] = cage_torque / self.jc;
        tot
    }

    /// Jacobians by per-ball finite differences (each ball's terms depend only on its own
    /// states, the cage's and the ring's, so a column costs one ball evaluation, not a
    /// whole right-hand side): `jx = d(rates)/d(states)` (`n × n`, row-major),
    /// `jm = d(rates)/d(q, v)` (`n × 10`), `wx = d(wrench)/d(states)` (`5 × n`),
    /// `wm = d(wrench)/d(q, v)` (`5 × 10`). Allocation-free.
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
        jx.fill(0.0);
        jm.fill(0.0);
        wx.fill(0.0);
        wm.fill(0.0);
        let (theta_c, w_c) = (x[0], x[1]);
        let jc = self.jc;
        jx[1] = 1.0; // d theta_c' / d w_c
        jx[n + 1] = -self.p.cage_drag / jc;
        let eps = f64::EPSILON.sqrt();
        for j in 0..self.z {
            let k = BALL0 + 3 * j;
            let st = [x[k], x[k + 1], x[k + 2]];
            let base = self.ball(j, q, v, omega, theta_c, w_c, st[0], st[1], st[2]);
            // Ball columns.
            for col in 0..3 {
                let h = if col == 0 {
                    1e-9
                } else {
                    eps * st[col].abs().max(1.0)
                };
                let mut sp = st;
                sp[col] += h;
                let b = self.ball(j, q, v, omega, theta_c, w_c, sp[0], sp[1], sp[2]);
                let c = k + col;
                for r in 0..3 {
                    jx[(k + r) * n + c] = (b.dx[r] - base.dx[r]) / h;
                }
                jx[n + c] = (b.cage_torque - base.cage_torque) / (h * jc);
                if !wx.is_empty() {
                    for r in 0..5 {
                        wx[r * n + c] = (b.wrench[r] - base.wrench[r]) / h;
                    }
                }
            }
            // Cage columns.
            for col in 0..2 {
                let (tc, wc, h) = if col == 0 {
                    (theta_c + 1e-9, w_c, 1e-9)
                } else {
                    let h = eps * w_c.abs().max(1.0);
                    (theta_c, w_c + h, h)
                };
                let b = self.ball(j, q, v, omega, tc, wc, st[0], st[1], st[2]);
                for r in 0..3 {
                    jx[(k + r) * n + col] = (b.dx[r] - base.dx[r]) / h;
                }
                jx[n + col] += (b.cage_torque - base.cage_torque) / (h * jc);
            }
            if jm.is_empty() {
                continue;
            }
            // Velocity columns: only the contact damping `-cd g g^T` depends on v.
            for r in 0..5 {
                for c in 0..5 {
                    wm[r * 10 + 5 + c] -= base.cd * base.g[r] * base.g[c];
                }
            }
            // Displacement columns.
            for col in 0..5 {
                let (mut qp, vp) = (*q, *v);
                if !q_cols.contains(&col) {
                    continue;
                }
                let h = if col < 3 { 1e-11 } else { 1e-9 };
                qp[col] += h;
                let b = self.ball(j, &qp, &vp, omega, theta_c, w_c, st[0], st[1], st[2]);
                for r in 0..3 {
                    jm[(k + r) * 10 + col] = (b.dx[r] - base.dx[r]) / h;
                }
                jm[10 + col] += (b.cage_torque - base.cage_torque) / (h * jc);
                for r in 0..5 {
                    wm[r * 10 + col] += (b.wrench[r] - base.wrench[r]) / h;
                }
            }
        }
    }

    /// Peak Hertz pressure at the larger of a ball's two loads, Pa.
    pub fn peak_pressure(&self, q_i: f64, q_o: f64) -> f64 {
        self.inner
            .peak_pressure(q_i)
            .max(self.outer.peak_pressure(q_o))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::preset;

    /// At the kinematic speeds of physics.md §1 both slips vanish, for a deep-groove and
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

    /// Force split with centrifugal force: `Q_o - Q_i = Fc` and the approaches add up.
    #[test]
    fn split_balances_the_centrifugal_force() {
        let b = preset("6012").unwrap().build().unwrap();
        let m = SkiddingModel::new(&b, SkiddingParams::default()).unwrap();
        for (delta, f) in [(5e-6, 3.0), (5e-6, 0.0), (-2e-6, 3.0), (1e-7, 50.0)] {
            let (qi, qo) = m.split(delta, f);
            assert!(
                (qo - qi - f).abs() < 1e-8 * (1.0 + qo),
                "{delta} {f}: {qi} {qo}"
            );
            if qi > 0.0 {
                let sum = m.inner.deflection(qi) + m.outer.deflection(qo);
                assert!((sum - delta).abs() < 1e-12, "{sum} vs {delta}");
            }
        }
        assert_eq!(m.split(-1e-6, 0.0), (0.0, 0.0));
    }
}
