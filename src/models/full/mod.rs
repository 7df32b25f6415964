//! Full high-speed dynamics with cage whirl (docs/physics.md §5.5; study \[0\] after Gupta,
//! *Advanced Dynamics of Rolling Elements*, Springer 1984, ch. 3–5; Harris & Kotzalas,
//! *Rolling Bearing Analysis* 5th ed., Vol. 2 ch. 3 for the contact kinematics).
//!
//! # Bodies, frames and states
//!
//! Fixed frame as docs/physics.md §0 (`z` the shaft axis). Ball `j`: centre in cylindrical
//! coordinates `(rho_j, psi_j, z_j)`, angular velocity `w_j` in **fixed-frame Cartesian**
//! components. A sphere's orientation angles never enter the forces (isotropic inertia,
//! `J = m D²/10`, and a ball surface that looks the same in every orientation), so only
//! `w_j` is integrated, and Euler's equations reduce to `J dw/dt = M` in the fixed frame
//! exactly (no gyroscopic term for an isotropic body: the "gyroscopic moment" of the
//! quasi-static model appears here as the moment the contacts must supply to turn `w` with
//! the orbit).
//!
//! - `ball_contacts = quasi_static` (default, study \[0\]'s way): `rho_j, z_j` solved at every
//!   evaluation from the ball's radial/axial balance of the two race normal loads and the
//!   centrifugal force (`ball.rs`), warm-started from `aux`; states `(psi, w_orb, w)`.
//!   The orbital equation is `m rho psi'' = F_t` (the Coriolis term `2 m rho' psi'` is
//!   dropped with `rho'`, which the quasi-static position does not carry).
//! - `dynamic`: `rho, z` and their rates integrated with the ball mass; Newton in
//!   cylindrical coordinates `m (rho'' - rho psi'²) = F_r`, `m (rho psi'' + 2 rho' psi') =
//!   F_t`, `m z'' = F_z`.
//!
//! Cage (`cage = free`, default): centre `(x, y, z)`, small tilts `(bx, by)` about `x`, `y`
//! and rotation `theta_c`; with the polar inertia `I_p` (bearing's `cage.inertia`) and the
//! transverse one `I_t = m_c ((r_i² + r_o²)/4 + w²/12)` (a thick ring, any dynamics text):
//! `m_c c'' = F`, `I_t bx'' + I_p w_c by' = M_x`, `I_t by'' - I_p w_c bx' = M_y`,
//! `I_p w_c' = M_z` (Euler's equations of a symmetric rotor linearised in the tilts; the
//! angular momentum is `I_p w_c (by, -bx, 1) + I_t (bx', by', 0)`). `cage = ideal`: centre
//! held on the ring axis, no tilt, only `theta_c` dynamic; pockets act tangentially only.
//!
//! # Nondimensional states (study \[0\])
//!
//! Lengths in `L = D/2`, time in `T0 = sqrt(m_b D / (2 F_ref))`: stored are `x/L`,
//! `v T0/L`, angles, `w T0`; the right-hand side returns their derivatives in physical time.
//! One absolute tolerance `atol_m / L` then fits every state.
//!
//! Layout: cage block first (`ideal`: `[theta, w_c]`; `free`: `[x, y, z, bx, by, theta,
//! vx, vy, vz, bx', by', w_c]`), then per ball (`quasi_static`: `[psi, psi', wx, wy, wz]`;
//! `dynamic`: `[rho, z, psi, rho', z', psi', wx, wy, wz]`).
//!
//! # Race contacts
//!
//! The inner groove curvature centre moves with the ring exactly as in the quasi-static
//! and skidding levels (Jones geometry with `q = (x, y, z, rx, ry)`); inner and outer
//! contact angles follow from the ball position; loads by Hertz with `Kc(alpha)` and the
//! semi-axes from the bearing's [`ContactTable`]. Contact points `r_b -+ (D/2) n_k` (`n_i`,
//! `n_o` the unit vectors of `A - X` and `X`, lifted to 3-D with `e_z`, `e_r`).
//!
//! Traction from the full 3-D slip: at each contact centre the sliding velocity of the ball
//! surface over the race, `dv = (v_b + w × r) - v_race` (inner race
//! `v_race = v_q + (rx', ry', omega) × (r_c - q)`; outer race fixed),
//! projected on the contact plane (rolling and lateral components together). Force on the
//! ball `-T(|dv|, u) dv/|dv|` with the scene's [`TractionLaw`] (odd, so `T(s)/s` is finite
//! as `s -> 0`); `u` the entrainment speed along the rolling direction (mean surface speed
//! relative to the orbiting contact point), the law's slide-to-roll ratio is `|dv|/u`.
//! Spin: the relative angular velocity along the normal `w_s = (w - w_race)·n` gives the
//! ball the moment `-(3 pi/16) a T(w_s a, u) n` — for the Coulomb law exactly
//! `(3 pi/16) mu Q a tanh(w_s a / v_s)`, the full-sliding spin moment of a circular contact
//! of radius `a` (Harris & Kotzalas Vol. 2 ch. 3; Johnson, *Contact Mechanics* §8.4), used
//! with the ellipse's major semi-axis.
//!
//! # Cage interactions
//!
//! Pocket `j` is a cylindrical hole along the cage-radial direction at
//! `theta_c + 2 pi j/Z`, centre at the pitch radius. The ball centre's offset from the
//! pocket centre has a tangential and an axial component; the two directions are treated
//! independently (docs/physics.md: "the two pocket directions independent"): in each, both
//! walls act, with gaps `h = (D_p - D)/2 -+ offset` (pocket diameter `D_p = D + c_p`, the
//! bearing's diametral pocket play `c_p`), each a force from [`PocketLaw`] normal to the
//! wall (films on both sides, so the force is continuous through the pocket centre) plus
//! its friction opposing the sliding of the ball surface over the wall. Equal and opposite on the cage
//! (force and moment about the cage centre). The pocket axis is taken as the cage radial
//! in the bearing plane (its tilt with the cage, second order in the offsets, is neglected).
//!
//! Guide land: [`GuideLand`] with `e` the cage centre minus the guiding ring's centre
//! (outer ring: the origin; inner ring: the shaft's `(x, y)`), guiding ring speed 0 or
//! `omega`. Its force passes through the cage centre (pressure normal to the land) and adds
//! the shear torque; the land's tilting moment is not modelled. With `cage = ideal` the land
//! is not evaluated (the centre is held by the constraint).
//!
//! Guidance (`FullParams::guidance`, the bearing's unless the scene sets
//! `model.full.guidance`): outer-ring land radius = cage OD/2, inner-ring land radius = cage
//! bore/2 (study \[0\]'s cage, ID 30 mm and OD 35 mm, runs between the inner-ring land below
//! 30 mm and the outer-ring land above 35 mm). Why one force law serves both, with the
//! sign docs/physics.md gives for Gupta's eccentricity: [`GuideLand`]'s notes.
//!
//! Cage mass unbalance `u` (`cage_unbalance`): the mass centre sits at
//! `c + u (cos theta_c, sin theta_c, 0)`, so the geometric centre (the states, the land's
//! eccentricity) obeys `m_c c'' = F + m_c u (w_c² e - w_c' e_perp)` (`e`, `e_perp` the
//! cage's angle-origin direction and its normal): the rotating "centrifugal" load that grows
//! with the square of the cage speed. The `O(u)` changes of the cage's moments and polar
//! inertia are neglected (`u` is micrometres against a 15 mm radius), and
//! [`FullModel::angular_momentum`] is that of `u = 0`.
//!
//! Cage power balance ([`Totals`]): pocket, guide-land and drag powers on the cage, and
//! their parts from the centre's velocity; over a settled orbit their sum averages to
//! zero, and the whirl parts say who feeds the whirl and who takes it out.
//!
//! Boundary-layer drag: each ball moves through oil–air at rest (`sphere_drag_force` on the
//! centre's velocity, `sphere_spin_moment` on `w`); the cage's two side faces by
//! `disk_moment` between its bore and outside diameters.
//!
//! # Momentum
//!
//! Angular momentum about `z`: `L = sum_j [m rho_j² psi_j' + J w_jz] + m_c (c × c')_z +
//! I_p w_c`. Pocket forces and frictions are internal; `dL/dt` is the sum of the race
//! tractions' and spin moments about `z`, the drag moments and the guide land's moment and
//! torque ([`Totals::external_mz`]). Exact for `dynamic` ball contacts (tests/full.rs).

mod cage;
mod contact;
mod eom;
mod jacobian;
mod kinematics;
use kinematics::*;
mod ball;
pub mod level;
pub mod spec;
#[cfg(test)]
mod tests;

use crate::contact::traction::{ContactState, TractionLaw};
use crate::contact::{BallRaceContacts, ContactTable, PointContact, Race};
use crate::error::{Error, Result};
use crate::geometry::{Bearing, Guidance};
use crate::lubrication::drag::{disk_moment, sphere_drag_force, sphere_spin_moment, Fluid};
use crate::lubrication::guide_land::GuideLand;
use crate::lubrication::pocket::{PocketForce, PocketLaw, PreparedPocket};
use crate::models::quasi_static::{BallResult, BallState, Options, QuasiStatic, RaceControl};
use crate::solver::same_bits;
use ball::{add, cross, dot, norm, scale, sub, tangential, PositionSolver, V3};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// How the ball–race contacts enter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum BallContacts {
    /// Ball radial and axial position in quasi-static equilibrium (study \[0\]).
    #[default]
    QuasiStatic,
    /// Radial and axial position integrated with the ball mass.
    Dynamic,
}

/// The cage model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum CageModel {
    /// Six degrees of freedom.
    #[default]
    Free,
    /// Centre held on the axis, no tilt; rotation only, tangential pocket forces.
    Ideal,
}

/// Options of the full model (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct FullParams {
    /// Traction law at the race contacts.
    pub traction: TractionLaw,
    /// Ball contact treatment.
    pub ball_contacts: BallContacts,
    /// Cage model.
    pub cage: CageModel,
    /// Reference force of the nondimensional states, N.
    pub reference_load: f64,
    /// Race control of the quasi-static start.
    pub race_control: RaceControl,
    /// Factor on the boundary-layer drag of balls and cage (0: off).
    pub drag: f64,
    /// Effective density of the oil–air mixture (drag), kg/m³.
    pub drag_density: f64,
    /// Oil viscosity (drag, pockets, guide land), Pa s.
    pub viscosity: f64,
    /// Diametral pocket play, m.
    pub pocket_clearance: f64,
    /// Pocket friction coefficient.
    pub pocket_friction: f64,
    /// Composite roughness of ball and pocket, m.
    pub pocket_roughness: f64,
    /// Regularising slip speed of the pocket friction, m/s.
    pub pocket_v_s: f64,
    /// Guide land width, m.
    pub guide_width: f64,
    /// Guide land contact stiffness beyond `eps_max`, N/m.
    pub guide_stiffness: f64,
    /// Eccentricity ratio where the land's contact starts.
    pub guide_eps_max: f64,
    /// Cage guidance (inner- or outer-ring land, or ball-riding); the bearing's by default.
    pub guidance: Guidance,
    /// Cage mass unbalance: distance of the cage's mass centre from its geometric centre,
    /// m (fixed in the cage, along the cage's angle origin).
    pub cage_unbalance: f64,
}

impl FullParams {
    /// Defaults for bearing `b` (its cage's pocket play and width).
    pub fn for_bearing(b: &Bearing) -> Self {
        // The scene's declared defaults (`[model.full]`).
        let s = spec::FullSpec::default();
        FullParams {
            traction: s.traction,
            ball_contacts: s.ball_contacts,
            cage: s.cage,
            reference_load: s.reference_load_n,
            race_control: RaceControl::Outer,
            drag: s.drag_factor,
            drag_density: s.drag_density,
            viscosity: s.viscosity,
            pocket_clearance: b.cage.pocket_clearance,
            pocket_friction: s.pocket_friction,
            pocket_roughness: s.pocket_roughness_um * 1e-6,
            pocket_v_s: s.pocket_v_s,
            guide_width: 0.5 * b.cage.width,
            guide_stiffness: s.guide_stiffness,
            guide_eps_max: s.guide_eps_max,
            guidance: b.cage.guidance,
            cage_unbalance: s.cage_unbalance_um * 1e-6,
        }
    }
}

/// Per-ball results of the last evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BallInfo {
    /// Orbital angle and speed, rad, rad/s.
    pub psi: f64,
    /// Orbital speed, rad/s.
    pub w_orb: f64,
    /// Ball centre radius and axial position, m.
    pub rho: f64,
    /// Axial position, m.
    pub z: f64,
    /// Inner and outer normal loads, N.
    pub q_i: f64,
    /// Outer load, N.
    pub q_o: f64,
    /// Contact angles, rad.
    pub alpha_i: f64,
    /// Outer contact angle, rad.
    pub alpha_o: f64,
    /// Sliding speeds at the contact centres, m/s.
    pub slide_i: f64,
    /// Outer sliding speed, m/s.
    pub slide_o: f64,
    /// Largest pocket normal force, N.
    pub pocket: f64,
    /// Peak Hertz pressure (larger of the two), Pa.
    pub p_max: f64,
}

/// Totals of one evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Totals {
    /// Wrench on the shaft.
    pub wrench: [f64; 5],
    /// Torque on the shaft about z, N m.
    pub torque_shaft: f64,
    /// External moment about z on balls and cage (races, drag, guide land), N m.
    pub external_mz: f64,
    /// Power dissipated at the race contacts (sliding and spin), W.
    pub power_contacts: f64,
    /// Balls loaded at the inner race.
    pub loaded: usize,
    /// Largest race load, N.
    pub max_load: f64,
    /// Largest Hertz pressure, Pa.
    pub max_pressure: f64,
    /// Largest pocket force, N.
    pub pocket_max: f64,
    /// Guide-land force magnitude, N.
    pub guide_force: f64,
    /// Power of the ball–pocket forces and moments on the cage, W (translation and
    /// rotation of the cage body).
    pub pocket_power: f64,
    /// Its part from the cage centre's velocity (the power feeding the whirl), W.
    pub pocket_power_whirl: f64,
    /// Power of the guide-land film and wall on the cage, W.
    pub guide_power: f64,
    /// Its part from the cage centre's velocity (the power the land takes from the whirl), W.
    pub guide_power_whirl: f64,
    /// Power of the boundary-layer drag on the cage, W.
    pub cage_drag_power: f64,
}

/// Physical cage kinematics.
#[derive(Debug, Clone, Copy, Default)]
struct CageKin {
    c: V3,
    b: [f64; 2],
    theta: f64,
    v: V3,
    bd: [f64; 2],
    w: f64,
}

impl CageKin {
    /// Angular velocity of the tilted, spinning cage (small tilts): the rate of the
    /// orientation `R_z(theta)` tilted by `(bx, by)` is `(bx' + w by, by' - w bx, w)`, the
    /// one under which `I_p w (by, -bx, 1) + I_t (bx', by', 0)` is its angular momentum.
    fn omega(&self) -> V3 {
        [
            self.bd[0] + self.w * self.b[1],
            self.bd[1] - self.w * self.b[0],
            self.w,
        ]
    }
    /// The cage's material point at angle `th` (fixed frame) on the radius `r`: the pocket
    /// centre for `r = dm/2`.
    #[cfg(test)]
    fn point(&self, th: f64, r: f64) -> V3 {
        let (s, c) = th.sin_cos();
        self.point_sc(s, c, r)
    }
    /// [`Self::point`] from `sin th`, `cos th`.
    fn point_sc(&self, s: f64, c: f64, r: f64) -> V3 {
        let lift = r * (self.b[0] * s - self.b[1] * c);
        add(self.c, [r * c, r * s, lift])
    }
    /// Velocity of the cage material at the fixed-frame point `r`.
    fn velocity_at(&self, r: V3) -> V3 {
        add(self.v, cross(self.omega(), sub(r, self.c)))
    }
}

/// Physical ball kinematics.
#[derive(Debug, Clone, Copy, Default)]
struct BallKin {
    psi: f64,
    rho: f64,
    z: f64,
    rho_d: f64,
    z_d: f64,
    w_orb: f64,
    w: V3,
}

/// One ball's terms.
#[derive(Debug, Clone, Copy, Default)]
struct BallTerms {
    /// `(rho'', psi'', z'')`.
    acc: [f64; 3],
    /// `dw/dt`.
    w_dot: V3,
    /// Force on the cage and moment about its centre.
    cage_f: V3,
    cage_m: V3,
    wrench: [f64; 5],
    torque: f64,
    ext_mz: f64,
    power: f64,
    info: BallInfo,
    /// The pocket's forces it was computed with.
    pocket: Pocket,
}

/// The pocket walls' forces on one ball ([`FullModel::pocket`]).
#[derive(Debug, Clone, Copy, Default)]
struct Pocket {
    /// Walls acting (2 or 4) and each one's force on the ball and its moment about the
    /// ball centre.
    walls: usize,
    fb: [V3; 4],
    mb: [V3; 4],
    /// Force on the cage and moment about its centre.
    cage_f: V3,
    cage_m: V3,
    /// Largest wall normal force, N.
    max: f64,
}

/// The axial unit vector.
const EZ: V3 = [0.0, 0.0, 1.0];

/// A ball's frame at its orbital angle and its centre's position and velocity.
#[derive(Debug, Clone, Copy, Default)]
struct BallFrame {
    /// `sin psi`, `cos psi`.
    s: f64,
    c: f64,
    rb: V3,
    vb: V3,
}

impl BallFrame {
    fn new(bk: &BallKin) -> Self {
        let (s, c) = bk.psi.sin_cos();
        Self::with_sc(bk, s, c)
    }
    /// [`Self::new`] from `sin psi`, `cos psi`.
    fn with_sc(bk: &BallKin, s: f64, c: f64) -> Self {
        let er = [c, s, 0.0];
        let et = [-s, c, 0.0];
        BallFrame {
            s,
            c,
            rb: [bk.rho * c, bk.rho * s, bk.z],
            vb: add(
                add(scale(er, bk.rho_d), scale(et, bk.rho * bk.w_orb)),
                scale(EZ, bk.z_d),
            ),
        }
    }
    /// Radial unit vector.
    fn er(&self) -> V3 {
        [self.c, self.s, 0.0]
    }
    /// Tangential unit vector.
    fn et(&self) -> V3 {
        [-self.s, self.c, 0.0]
    }
}

/// What is known of a ball's race contacts where its race part is evaluated.
#[derive(Debug, Clone, Copy)]
enum Known<'a> {
    /// Nothing: evaluated at the position.
    Nothing,
    /// The contacts from the position solve.
    Solved([ball::Contact; 2]),
    /// A race part kept at the same position, orbital angle and speed and groove offset:
    /// its frame, contacts and contact states (all the same numbers, bit for bit).
    Kept(&'a BallRace),
    /// A race part kept at the same position and orbital angle and groove offset, the
    /// velocities changed: its contacts and contact states, the frame's `sin`, `cos`.
    Contacts(&'a BallRace),
    /// A race part kept at the same position and orbital angle, the ring moved: its frame
    /// and outer contact, the inner contact evaluated at the position.
    Outer(&'a BallRace),
}

/// One pocket wall of a ball ([`FullModel::ball_cage`]): its normal, the ball's contact
/// arm and point, the sliding velocity and its speed, and the wall's law there.
#[derive(Debug, Clone, Copy, Default)]
struct Wall {
    nw: V3,
    arm: V3,
    rc: V3,
    slide: V3,
    vs: f64,
    pf: PocketForce,
}

/// The inner race contact of a ball ([`FullModel::inner_contact`]).
#[derive(Debug, Clone, Copy)]
struct InnerContact {
    ci: ball::Contact,
    qi: f64,
    ni: V3,
    ri_: V3,
    rci: V3,
    wr: V3,
    csi: ContactState,
    dv_i: V3,
    ft_i: V3,
    ms_i: V3,
    wrench: [f64; 5],
    torque: f64,
}

/// The part of a ball's terms that does not depend on the cage ([`FullModel::ball_race`]):
/// kept per ball by an evaluation so that the Jacobian's cage columns re-evaluate only the
/// pockets.
#[derive(Debug, Clone, Copy, Default)]
struct BallRace {
    bk: BallKin,
    fr: BallFrame,
    /// Ball position `(X1, X2)`.
    xrel: [f64; 2],
    /// Force and moment on the ball from races and drag.
    f: V3,
    mom: V3,
    ext_mz: f64,
    wrench: [f64; 5],
    torque: f64,
    power: f64,
    info: BallInfo,
    /// The inner and outer contacts and their contact states.
    contacts: [ball::Contact; 2],
    cs: [ContactState; 2],
}

/// Where an evaluation takes the balls' race parts from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Races {
    /// Computed and kept in [`FullModel::races`].
    Keep,
    /// The kept ones (the ball states, `q`, `v` and `omega` are those they were kept at).
    Kept,
    /// A ring column of the Jacobian: the ball states and the cage's those the race parts
    /// and the terms were kept at, the shaft's motion moved (`moved`: its displacement
    /// `q`, else only `v` or `omega`). The pockets' forces are the kept ones where the
    /// ball positions are states or the displacement is held, and with dynamic ball
    /// contacts the outer contacts are kept; the inner contacts are evaluated again when
    /// `q` moved, their tractions always.
    Ring { moved: bool },
}

/// The full model of one bearing.
#[derive(Debug, Clone)]
pub struct FullModel {
    /// Options.
    pub p: FullParams,
    z: usize,
    d: f64,
    dm: f64,
    m: f64,
    j: f64,
    mc: f64,
    ip: f64,
    it: f64,
    a10: f64,
    a20: f64,
    ri: f64,
    z_og: f64,
    pos: PositionSolver,
    qs: QuasiStatic,
    pocket: PreparedPocket,
    guide: Option<GuideLand>,
    nominal: BallRaceContacts,
    fluid: Fluid,
    guided_inner: bool,
    cage_r_in: f64,
    cage_r_out: f64,
    /// Length and time scales.
    l: f64,
    t0: f64,
    nc: usize,
    nb: usize,
    /// Per-ball results of the last evaluation (through [`Self::eval`], or the one at
    /// the Jacobian's point: its perturbed evaluations leave them).
    pub balls: Vec<BallInfo>,
    /// Per-ball race parts kept by an evaluation with [`Races::Keep`], and the ball
    /// terms it computed from them (the Jacobian's ball columns difference against them).
    races: Vec<BallRace>,
    terms: Vec<BallTerms>,
    /// `sin`, `cos` of each pocket's angle at the cage angle `pocket_theta` (bits; the
    /// Jacobian's columns but one keep the cage angle).
    pocket_sc: Vec<[f64; 2]>,
    pocket_theta: Option<u64>,
    /// The last evaluation through [`Self::eval`] or [`Self::eval_keep`].
    memo: Memo,
}

/// What the last evaluation through [`FullModel::eval`] or [`FullModel::eval_keep`]
/// started from and gave. Another one at the same motion and states, with `aux` as that
/// one found it or as it left it, gives the same numbers bit for bit (it computes from the
/// same inputs, or its position solves start at their own answers, which they return
/// with the contacts there: the property the Jacobian's kept evaluation relies on), so it
/// takes them instead. The integrator asks for such repeats twice per step: its
/// forward-difference time derivative re-evaluates the first stage at a time the motion
/// does not depend on, and the outputs evaluate the end of a step, where the next step's
/// first stage starts from the same warm starts.
#[derive(Debug, Clone, Default)]
struct Memo {
    /// The options it was computed with (none: nothing computed).
    p: Option<FullParams>,
    /// Motion `(q, v, omega)`.
    motion: [f64; 11],
    x: Vec<f64>,
    aux_in: Vec<f64>,
    aux_out: Vec<f64>,
    dx: Vec<f64>,
    tot: Totals,
    races: Vec<BallRace>,
    terms: Vec<BallTerms>,
    balls: Vec<BallInfo>,
}

/// The motion `(q, v, omega)` as one array.
fn motion_of(q: &[f64; 5], v: &[f64; 5], omega: f64) -> [f64; 11] {
    let mut m = [0.0; 11];
    m[..5].copy_from_slice(q);
    m[5..10].copy_from_slice(v);
    m[10] = omega;
    m
}

/// Relative tolerance of the quasi-static ball position solve.
const POS_TOL: f64 = 1e-12;

impl FullModel {
    /// Build; errors name the field.
    pub fn new(b: &Bearing, p: FullParams) -> Result<Self> {
        let f = |n: &str| format!("model.full.{n}");
        p.traction.validate(&f("traction"))?;
        crate::error::positive(&f("reference_load_n"), p.reference_load)?;
        crate::error::in_range(&f("cage_unbalance_um"), p.cage_unbalance * 1e6, 0.0, 1e3)?;
        if !(b.cage.mass > 0.0 && b.cage.inertia > 0.0) {
            return Err(Error::invalid(
                "bearing.cage",
                format!("mass {} kg, inertia {} kg m²", b.cage.mass, b.cage.inertia),
                "> 0 (give cage mass and diameters)",
            ));
        }
        let qs = QuasiStatic::new(
            b,
            Options {
                race_control: p.race_control,
                gyroscopic: false,
                ..Options::default()
            },
        )?;
        let (a10, a20) = b.reference_groove_offset();
        let alpha0 = b.nominal_contact_angle();
        let ro_free = (b.fo() - 0.5) * b.d;
        let m = b.ball_mass();
        let l = 0.5 * b.d;
        let t0 = (m * b.d / (2.0 * p.reference_load)).sqrt();
        let (cri, cro, cw) = (
            0.5 * b.cage.inner_diameter,
            0.5 * b.cage.outer_diameter,
            b.cage.width,
        );
        let guided_inner = matches!(p.guidance, Guidance::InnerRing);
        let (nc, nb) = (
            match p.cage {
                CageModel::Free => 12,
                CageModel::Ideal => 2,
            },
            match p.ball_contacts {
                BallContacts::QuasiStatic => 5,
                BallContacts::Dynamic => 9,
            },
        );
        let n_aux = match p.ball_contacts {
            BallContacts::QuasiStatic => 3 * b.z,
            BallContacts::Dynamic => 0,
        };
        let pocket = PocketLaw {
            ball_radius: 0.5 * b.d,
            pocket_radius: 0.5 * (b.d + p.pocket_clearance),
            width: cro - cri,
            roughness: p.pocket_roughness,
            viscosity: p.viscosity,
            e_eff: crate::geometry::material::effective_modulus(&b.ball_material, &b.cage_material),
            friction: p.pocket_friction,
            v_s: p.pocket_v_s,
        };
        Ok(FullModel {
            z: b.z,
            d: b.d,
            dm: b.dm,
            m,
            j: b.ball_inertia(),
            mc: b.cage.mass,
            ip: b.cage.inertia,
            it: b.cage.mass * ((cri * cri + cro * cro) / 4.0 + cw * cw / 12.0),
            a10,
            a20,
            ri: b.inner_groove_centre_radius(),
            z_og: -ro_free * alpha0.sin(),
            pos: PositionSolver {
                ri_free: (b.fi() - 0.5) * b.d,
                ro_free,
                r_og: b.outer_groove_centre_radius(),
                inner: ContactTable::new(b, Race::Inner),
                outer: ContactTable::new(b, Race::Outer),
            },
            qs,
            pocket: pocket.prepare(),
            nominal: BallRaceContacts::new(b, alpha0),
            guide: (!matches!(p.guidance, Guidance::Ball)).then_some(GuideLand {
                radius: if guided_inner { cri } else { cro },
                width: p.guide_width,
                clearance: b.cage.guide_clearance,
                viscosity: p.viscosity,
                outer: !guided_inner,
                contact_stiffness: p.guide_stiffness,
                eps_max: p.guide_eps_max,
            }),
            fluid: Fluid {
                density: p.drag_density,
                viscosity: p.viscosity,
            },
            guided_inner,
            cage_r_in: cri,
            cage_r_out: cro,
            l,
            t0,
            nc,
            nb,
            balls: vec![BallInfo::default(); b.z],
            races: vec![BallRace::default(); b.z],
            terms: vec![BallTerms::default(); b.z],
            pocket_sc: vec![[0.0; 2]; b.z],
            pocket_theta: None,
            memo: Memo {
                x: vec![0.0; nc + nb * b.z],
                aux_in: vec![0.0; n_aux],
                aux_out: vec![0.0; n_aux],
                dx: vec![0.0; nc + nb * b.z],
                races: vec![BallRace::default(); b.z],
                terms: vec![BallTerms::default(); b.z],
                balls: vec![BallInfo::default(); b.z],
                ..Memo::default()
            },
            p,
        })
    }

    /// Number of states.
    pub fn n_states(&self) -> usize {
        self.nc + self.nb * self.z
    }

    /// Number of aux values (quasi-static ball positions).
    pub fn n_aux(&self) -> usize {
        match self.p.ball_contacts {
            BallContacts::QuasiStatic => 3 * self.z,
            BallContacts::Dynamic => 0,
        }
    }

    /// Balls.
    pub fn z(&self) -> usize {
        self.z
    }

    /// Length scale `D/2`, m, and time scale `T0`, s.
    pub fn scales(&self) -> (f64, f64) {
        (self.l, self.t0)
    }

    /// Offset of the first ball block.
    pub fn ball0(&self) -> usize {
        self.nc
    }

    /// States per ball.
    pub fn per_ball(&self) -> usize {
        self.nb
    }

    /// The ball blocks for the block-arrowhead solve ([`crate::seam::LevelModel::blocks`]):
    /// `(balls, states per ball)` after the cage's [`Self::ball0`] states, with dynamic
    /// ball contacts. A ball's rates depend on its own states, the cage's and the ring's
    /// only (the Jacobian's ball columns write the ball's block and the cage's rows), so
    /// the blocks are independent and the cage and ring states form the border.
    /// Quasi-static ball contacts keep the dense solve (`None`).
    pub fn blocks(&self) -> Option<(usize, usize)> {
        (self.p.ball_contacts == BallContacts::Dynamic).then_some((self.z, self.nb))
    }

    /// Cage speed `w_c`, rad/s, from the states.
    pub fn cage_omega(&self, x: &[f64]) -> f64 {
        x[self.nc - 1] / self.t0
    }

    /// Cage centre `(x, y)`, m, and its speed `|v|`, m/s.
    pub fn cage_centre(&self, x: &[f64]) -> ([f64; 2], f64) {
        match self.p.cage {
            CageModel::Ideal => ([0.0; 2], 0.0),
            CageModel::Free => {
                let v = self.l / self.t0;
                ([x[0] * self.l, x[1] * self.l], (x[6] * v).hypot(x[7] * v))
            }
        }
    }
}
