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

mod ball;
pub mod level;
pub mod spec;

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

/// Angular velocity of the inner ring (small tilts `rx = q\[3\]`, `ry = q\[4\]` and their rates
/// `v\[3\]`, `v\[4\]`, spin `omega`): `(rx' + omega ry, ry' - omega rx, omega)`, as for the
/// cage ([`CageKin::omega`]); the groove's axial lift `ri (rx sin - ry cos)` moves with it.
fn ring_omega(q: &[f64; 5], v: &[f64; 5], omega: f64) -> V3 {
    [v[3] + omega * q[4], v[4] - omega * q[3], omega]
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
    ni2: [f64; 2],
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
    /// Computed (positions solved).
    Compute,
    /// Computed and kept in [`FullModel::races`].
    Keep,
    /// The kept ones (the ball states, `q`, `v` and `omega` are those they were kept at).
    Kept,
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
    /// Per-ball results of the last evaluation.
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
        let ro_free = (b.fo - 0.5) * b.d;
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
                ri_free: (b.fi - 0.5) * b.d,
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

    fn cage_kin(&self, x: &[f64]) -> CageKin {
        let (l, t0) = (self.l, self.t0);
        let v = l / t0;
        match self.p.cage {
            CageModel::Ideal => CageKin {
                theta: x[0],
                w: x[1] / t0,
                ..CageKin::default()
            },
            CageModel::Free => CageKin {
                c: [x[0] * l, x[1] * l, x[2] * l],
                b: [x[3], x[4]],
                theta: x[5],
                v: [x[6] * v, x[7] * v, x[8] * v],
                bd: [x[9] / t0, x[10] / t0],
                w: x[11] / t0,
            },
        }
    }

    /// Ball kinematics from its states; `rho, z` in quasi-static mode come from `pos`.
    fn ball_kin(&self, xb: &[f64], pos: [f64; 2]) -> BallKin {
        let (l, t0) = (self.l, self.t0);
        match self.p.ball_contacts {
            BallContacts::QuasiStatic => BallKin {
                psi: xb[0],
                w_orb: xb[1] / t0,
                w: [xb[2] / t0, xb[3] / t0, xb[4] / t0],
                rho: self.pos.r_og + pos[1],
                z: self.z_og + pos[0],
                ..BallKin::default()
            },
            BallContacts::Dynamic => BallKin {
                rho: xb[0] * l,
                z: xb[1] * l,
                psi: xb[2],
                rho_d: xb[3] * l / t0,
                z_d: xb[4] * l / t0,
                w_orb: xb[5] / t0,
                w: [xb[6] / t0, xb[7] / t0, xb[8] / t0],
            },
        }
    }

    /// Groove offset `(A1, A2)` at azimuth `psi` (Jones geometry, as `models::quasi_static`).
    fn groove_offset(&self, q: &[f64; 5], psi: f64) -> [f64; 2] {
        let (s, c) = psi.sin_cos();
        self.groove_offset_sc(q, s, c)
    }

    /// [`Self::groove_offset`] from `sin psi`, `cos psi`.
    fn groove_offset_sc(&self, q: &[f64; 5], s: f64, c: f64) -> [f64; 2] {
        [
            self.a10 + q[2] + self.ri * (q[3] * s - q[4] * c),
            self.a20 + q[0] * c + q[1] * s,
        ]
    }

    /// Contact state at the actual contact angle (semi-axes from the table); the film
    /// laws' effective radius and modulus are taken at the nominal contact angle.
    fn contact_state(c: &ball::Contact, nominal: &PointContact) -> ContactState {
        let q = c.q;
        let (a, b) = c.co.semi_axes(q);
        ContactState {
            q,
            a,
            b,
            rx: nominal.curvature.rx,
            kappa: if b > 0.0 {
                a / b
            } else {
                nominal.ellipse.kappa
            },
            e_eff: nominal.e_eff,
        }
    }

    /// Tangential traction on the ball from slip `dv` (3-D, in the contact plane).
    fn traction(&self, dv: V3, u: f64, cs: &ContactState) -> V3 {
        let s = norm(dv);
        let se = s.max(1e-12);
        let t = self.p.traction.force(se, u, cs);
        scale(dv, -t / se)
    }

    /// Spin moment on the ball about the normal `n` for relative spin `ws`.
    fn spin_moment(&self, ws: f64, u: f64, cs: &ContactState, n: V3) -> V3 {
        if cs.q <= 0.0 {
            return [0.0; 3];
        }
        let m = 3.0 * PI / 16.0 * cs.a * self.p.traction.force(ws * cs.a, u, cs);
        scale(n, -m)
    }

    /// The inner race contact of a ball: its load and traction, and what they do to the
    /// shaft (the part of [`Self::ball_race`] the wrench needs, shared with
    /// [`Self::wrench_at`] so that both compute the same numbers).
    #[allow(clippy::too_many_arguments)]
    fn inner_contact(
        &self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        bk: &BallKin,
        fr: &BallFrame,
        xrel: [f64; 2],
        known: Known,
    ) -> InnerContact {
        let hd = 0.5 * self.d;
        let (s, c) = (fr.s, fr.c);
        let (er, et, ez) = (fr.er(), fr.et(), EZ);
        let (ci, csi) = match known {
            Known::Kept(k) => (k.contacts[0], k.cs[0]),
            _ => {
                let ci = match known {
                    Known::Solved(c) => c[0],
                    _ => {
                        let a = self.groove_offset_sc(q, s, c);
                        ball::contact_full(
                            &self.pos.inner,
                            self.pos.ri_free,
                            [a[0] - xrel[0], a[1] - xrel[1]],
                        )
                    }
                };
                (ci, Self::contact_state(&ci, &self.nominal.inner))
            }
        };
        let (qi, ni2) = (ci.q, ci.n);
        let ni = add(scale(ez, ni2[0]), scale(er, ni2[1]));
        let w = bk.w;
        let wo = [0.0, 0.0, bk.w_orb];
        let ri_ = scale(ni, -hd);
        let rci = add(fr.rb, ri_);
        let vbs_i = add(fr.vb, cross(w, ri_));
        // Inner ring angular velocity: spin plus tilt rates.
        let wr = ring_omega(q, v, omega);
        let vq = [v[0], v[1], v[2]];
        let vr_i = add(vq, cross(wr, sub(rci, [q[0], q[1], q[2]])));
        let vcp_i = cross(wo, rci);
        let u_i = (0.5 * dot(add(sub(vbs_i, vcp_i), sub(vr_i, vcp_i)), et)).abs();
        let dv_i = tangential(sub(vbs_i, vr_i), ni);
        let ft_i = self.traction(dv_i, u_i, &csi);
        let ms_i = self.spin_moment(dot(sub(w, wr), ni), u_i, &csi, ni);
        // On the shaft: the inner normal load through the groove centre (the quasi-static
        // level's convention), the traction and spin reactions at the contact point.
        let mut wrench = [0.0; 5];
        let (fa, frr) = (-qi * ni2[0], -qi * ni2[1]);
        let mb = self.ri * fa;
        wrench[0] = frr * c;
        wrench[1] = frr * s;
        wrench[2] = fa;
        wrench[3] = mb * s;
        wrench[4] = -mb * c;
        let fs = scale(ft_i, -1.0);
        let ms = sub(cross(rci, fs), ms_i);
        wrench[0] += fs[0];
        wrench[1] += fs[1];
        wrench[2] += fs[2];
        wrench[3] += ms[0];
        wrench[4] += ms[1];
        InnerContact {
            ci,
            qi,
            ni2,
            ni,
            ri_,
            rci,
            wr,
            csi,
            dv_i,
            ft_i,
            ms_i,
            wrench,
            torque: ms[2],
        }
    }

    /// The part of ball `j`'s terms that does not depend on the cage: race contacts,
    /// tractions, spin moments and drag at the ball position `xrel` (the ball centre
    /// relative to the outer groove centre `(X1, X2)`), with the shaft's wrench.
    fn ball_race(
        &self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        bk: &BallKin,
        xrel: [f64; 2],
        known: Known,
    ) -> BallRace {
        let hd = 0.5 * self.d;
        let fr = match known {
            Known::Kept(k) => k.fr,
            _ => BallFrame::new(bk),
        };
        let (er, et, ez) = (fr.er(), fr.et(), EZ);
        let inn = self.inner_contact(q, v, omega, bk, &fr, xrel, known);
        let (qi, ni2, ni) = (inn.qi, inn.ni2, inn.ni);
        let (co, cso) = match known {
            Known::Kept(k) => (k.contacts[1], k.cs[1]),
            _ => {
                let co = match known {
                    Known::Solved(c) => c[1],
                    _ => ball::contact_full(&self.pos.outer, self.pos.ro_free, xrel),
                };
                (co, Self::contact_state(&co, &self.nominal.outer))
            }
        };
        let (qo, no2) = (co.q, co.n);
        let no = add(scale(ez, no2[0]), scale(er, no2[1]));
        let (rb, vb) = (fr.rb, fr.vb);
        let w = bk.w;
        let wo = [0.0, 0.0, bk.w_orb];
        // Outer contact.
        let ro_ = scale(no, hd);
        let rco = add(rb, ro_);
        let vbs_o = add(vb, cross(w, ro_));
        let vcp_o = cross(wo, rco);
        let u_o = (0.5 * dot(add(sub(vbs_o, vcp_o), scale(vcp_o, -1.0)), et)).abs();
        let dv_o = tangential(vbs_o, no);
        let ft_o = self.traction(dv_o, u_o, &cso);
        let ms_o = self.spin_moment(dot(w, no), u_o, &cso, no);
        // Inner contact.
        let (ri_, rci, ft_i, ms_i, dv_i, wr) =
            (inn.ri_, inn.rci, inn.ft_i, inn.ms_i, inn.dv_i, inn.wr);
        // Forces and moments on the ball.
        let mut f = add(add(scale(ni, qi), scale(no, -qo)), add(ft_i, ft_o));
        let mut mom = add(add(cross(ri_, ft_i), cross(ro_, ft_o)), add(ms_i, ms_o));
        let mut ext_mz = cross(rci, ft_i)[2] + cross(rco, ft_o)[2] + ms_i[2] + ms_o[2];
        // Drag.
        if self.p.drag > 0.0 {
            let k = self.p.drag;
            let sv = norm(vb);
            if sv > 0.0 {
                let fd = scale(
                    vb,
                    -k * sphere_drag_force(&self.fluid, self.d, sv).abs() / sv,
                );
                f = add(f, fd);
                ext_mz += cross(rb, fd)[2];
            }
            let sw = norm(w);
            if sw > 0.0 {
                let md = scale(
                    w,
                    -k * sphere_spin_moment(&self.fluid, self.d, sw).abs() / sw,
                );
                mom = add(mom, md);
                ext_mz += md[2];
            }
        }
        let power = -dot(ft_i, dv_i) - dot(ft_o, dv_o) - dot(ms_i, sub(w, wr)) - dot(ms_o, w);
        let p_max = csi_peak(&inn.csi).max(csi_peak(&cso));
        BallRace {
            bk: *bk,
            fr,
            xrel,
            f,
            mom,
            ext_mz,
            wrench: inn.wrench,
            torque: inn.torque,
            power,
            info: BallInfo {
                psi: bk.psi,
                w_orb: bk.w_orb,
                rho: bk.rho,
                z: bk.z,
                q_i: qi,
                q_o: qo,
                alpha_i: ni2[0].atan2(ni2[1]),
                alpha_o: no2[0].atan2(no2[1]),
                slide_i: norm(dv_i),
                slide_o: norm(dv_o),
                pocket: 0.0,
                p_max,
            },
            contacts: [inn.ci, co],
            cs: [inn.csi, cso],
        }
    }

    /// `sin`, `cos` of each pocket's angle at the cage angle `theta` into `pocket_sc`
    /// (computed again only when the angle changed).
    fn pocket_trig(&mut self, theta: f64) {
        if self.pocket_theta == Some(theta.to_bits()) {
            return;
        }
        for (j, sc) in self.pocket_sc.iter_mut().enumerate() {
            let th = theta + 2.0 * PI * j as f64 / self.z as f64;
            let (s, c) = th.sin_cos();
            *sc = [s, c];
        }
        self.pocket_theta = Some(theta.to_bits());
    }

    /// Ball `j`'s terms from its race part `r` and the cage: pocket forces (equal and
    /// opposite on the cage) and the ball's accelerations. `sc`: `sin`, `cos` of the
    /// pocket's angle ([`Self::pocket_trig`]).
    fn ball_cage(&self, ck: &CageKin, sc: [f64; 2], r: &BallRace) -> BallTerms {
        let hd = 0.5 * self.d;
        let ez = EZ;
        let (er, et) = (r.fr.er(), r.fr.et());
        let (bk, rb, vb, w) = (&r.bk, r.fr.rb, r.fr.vb, r.bk.w);
        let (mut f, mut mom) = (r.f, r.mom);
        // Pocket.
        let [sp, cp] = sc;
        let rp = 0.5 * self.dm;
        let etp = [-sp, cp, 0.0];
        let pc = ck.point_sc(sp, cp, rp);
        let d = sub(rb, pc);
        // Rate of the offset seen from the cage (the walls turn with it): the ball's
        // velocity minus the cage material's at the ball centre.
        let dd = sub(vb, ck.velocity_at(rb));
        let side = 0.5 * self.p.pocket_clearance;
        let mut cage_f = [0.0; 3];
        let mut cage_m = [0.0; 3];
        let mut pocket_max: f64 = 0.0;
        let dirs: &[V3] = match self.p.cage {
            CageModel::Free => &[etp, ez],
            CageModel::Ideal => &[etp],
        };
        // Both walls of each direction (films on both sides; contact on one at most):
        // their laws first, then their forces in the same order (the walls' divisions and
        // roots overlap).
        let mut walls = [Wall::default(); 4];
        let mut nwall = 0;
        for &nvec in dirs {
            let dn = dot(d, nvec);
            for sgn in [1.0, -1.0] {
                let nw = scale(nvec, sgn);
                let h = side - sgn * dn;
                let h_dot = -dot(dd, nw);
                let arm = scale(nw, hd);
                let rc = add(rb, arm);
                let vbs = add(vb, cross(w, arm));
                let vwall = ck.velocity_at(rc);
                let slide = tangential(sub(vbs, vwall), nw);
                let vs = norm(slide);
                // Entrainment: mean surface speed relative to the contact point, which
                // moves with the ball centre.
                let u = norm(tangential(
                    scale(add(sub(vbs, vb), sub(vwall, vb)), 0.5),
                    nw,
                ));
                walls[nwall] = Wall {
                    nw,
                    arm,
                    rc,
                    slide,
                    vs,
                    pf: self.pocket.force(h, h_dot, u, vs),
                };
                nwall += 1;
            }
        }
        for wl in &walls[..nwall] {
            let (nw, pf, vs) = (wl.nw, wl.pf, wl.vs);
            let mut fb = scale(nw, -pf.normal);
            if vs > 0.0 {
                fb = add(fb, scale(wl.slide, -pf.friction.abs() / vs));
            }
            f = add(f, fb);
            mom = add(mom, cross(wl.arm, fb));
            cage_f = sub(cage_f, fb);
            cage_m = sub(cage_m, cross(sub(wl.rc, ck.c), fb));
            pocket_max = pocket_max.max(pf.normal.abs());
        }
        // Accelerations.
        let (fr, ft, fz) = (dot(f, er), dot(f, et), dot(f, ez));
        let acc = match self.p.ball_contacts {
            BallContacts::QuasiStatic => [0.0, ft / (self.m * bk.rho), 0.0],
            BallContacts::Dynamic => [
                fr / self.m + bk.rho * bk.w_orb * bk.w_orb,
                (ft / self.m - 2.0 * bk.rho_d * bk.w_orb) / bk.rho,
                fz / self.m,
            ],
        };
        BallTerms {
            acc,
            w_dot: scale(mom, 1.0 / self.j),
            cage_f,
            cage_m,
            wrench: r.wrench,
            torque: r.torque,
            ext_mz: r.ext_mz,
            power: r.power,
            info: BallInfo {
                pocket: pocket_max,
                ..r.info
            },
        }
    }

    /// Quasi-static ball position for ball states `xb` (warm start in `aux[0..3]`:
    /// `X1, X2, warm flag`); updates the warm start.
    fn ball_position(&self, q: &[f64; 5], xb: &[f64], aux: &mut [f64]) -> Result<[f64; 2]> {
        Ok(self.ball_position_contacts(q, xb, aux)?.0)
    }

    /// [`Self::ball_position`] with the contacts there when the solve has them.
    fn ball_position_contacts(
        &self,
        q: &[f64; 5],
        xb: &[f64],
        aux: &mut [f64],
    ) -> Result<([f64; 2], Option<[ball::Contact; 2]>)> {
        let psi = xb[0];
        let w_orb = xb[1] / self.t0;
        let a = self.groove_offset(q, psi);
        let start = (aux[2] != 0.0).then_some([aux[0], aux[1]]);
        let (x, c) = self
            .pos
            .solve_contacts(a, self.m * w_orb * w_orb, start, POS_TOL)?;
        aux[0] = x[0];
        aux[1] = x[1];
        aux[2] = 1.0;
        Ok((x, c))
    }

    /// Ball kinematics and position `xrel` at its states `xb`: quasi-static, the position
    /// re-solved (warm start in `aux` updated) when `solve`, else the one `aux` holds (the
    /// solution for these `q`, `psi` and `w_orb`, which a solve from it returns unchanged).
    fn ball_kin_at(
        &self,
        j: usize,
        q: &[f64; 5],
        xb: &[f64],
        aux: &mut [f64],
        solve: bool,
    ) -> Result<(BallKin, [f64; 2], Option<[ball::Contact; 2]>)> {
        Ok(match self.p.ball_contacts {
            BallContacts::QuasiStatic => {
                let a = &mut aux[3 * j..3 * j + 3];
                let (xr, c) = if solve {
                    self.ball_position_contacts(q, xb, a)?
                } else {
                    ([a[0], a[1]], None)
                };
                (self.ball_kin(xb, xr), xr, c)
            }
            BallContacts::Dynamic => {
                let bk = self.ball_kin(xb, [0.0; 2]);
                (bk, [bk.z - self.z_og, bk.rho - self.pos.r_og], None)
            }
        })
    }

    /// The race part of ball `j`'s terms at its states `xb` ([`Self::ball_kin_at`]).
    #[allow(clippy::too_many_arguments)]
    fn ball_race_at(
        &self,
        j: usize,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        xb: &[f64],
        aux: &mut [f64],
        solve: bool,
    ) -> Result<BallRace> {
        let (bk, xrel, c) = self.ball_kin_at(j, q, xb, aux, solve)?;
        let known = c.map_or(Known::Nothing, Known::Solved);
        Ok(self.ball_race(q, v, omega, &bk, xrel, known))
    }

    /// Ball rates (stored-state derivatives) from its terms.
    fn ball_rates(&self, bt: &BallTerms, xb: &[f64], d: &mut [f64]) {
        let (l, t0) = (self.l, self.t0);
        match self.p.ball_contacts {
            BallContacts::QuasiStatic => {
                d[0] = xb[1] / t0;
                d[1] = bt.acc[1] * t0;
                d[2] = bt.w_dot[0] * t0;
                d[3] = bt.w_dot[1] * t0;
                d[4] = bt.w_dot[2] * t0;
            }
            BallContacts::Dynamic => {
                d[0] = xb[3] / t0;
                d[1] = xb[4] / t0;
                d[2] = xb[5] / t0;
                d[3] = bt.acc[0] * t0 / l;
                d[4] = bt.acc[2] * t0 / l;
                d[5] = bt.acc[1] * t0;
                d[6] = bt.w_dot[0] * t0;
                d[7] = bt.w_dot[1] * t0;
                d[8] = bt.w_dot[2] * t0;
            }
        }
    }

    /// Add to `d` (cage rates) the part linear in a change `(df, dm)` of the balls' force
    /// on the cage and moment about its centre.
    fn cage_rates_from(&self, df: V3, dm: V3, d: &mut [f64]) {
        let (l, t0) = (self.l, self.t0);
        match self.p.cage {
            CageModel::Ideal => d[1] += dm[2] / self.ip * t0,
            CageModel::Free => {
                for k in 0..3 {
                    d[6 + k] += df[k] / self.mc * t0 / l;
                }
                d[9] += dm[0] / self.it * t0;
                d[10] += dm[1] / self.it * t0;
                d[11] += dm[2] / self.ip * t0;
            }
        }
    }

    /// Jacobians by block-wise forward differences, all row-major: `jx = d(rates)/d(states)`
    /// (`n × n`), and when load-driven (non-empty slices) `jm = d(rates)/d(q, v)`
    /// (`n × 10`), `wx = d(wrench)/d(states)` (`5 × n`), `wm = d(wrench)/d(q, v)`
    /// (`5 × 10`). A ball's column costs one ball evaluation (its rates, its share of the
    /// cage's and of the wrench, differenced against the ball's terms kept from the
    /// evaluation at `x`; a spin column keeps the ball's position), a cage column
    /// the pockets of every ball on the race parts kept from the evaluation at `x` (the
    /// cage reaches a ball only through its pocket), a ring column one right-hand side.
    /// The cage columns equal whole-evaluation differences bit for bit. `scratch` holds
    /// `3 n + n_aux` values. Allocation-free.
    #[allow(clippy::too_many_arguments)]
    pub fn jacobian(
        &mut self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        aux: &[f64],
        jx: &mut [f64],
        jm: &mut [f64],
        wx: &mut [f64],
        wm: &mut [f64],
        scratch: &mut [f64],
    ) -> Result<()> {
        self.jacobian_from(q, v, omega, x, aux, jx, jm, wx, wm, scratch, None)
    }

    /// [`Self::jacobian`]; `kept`: the rates and totals of an evaluation with
    /// [`Races::Keep`] at this motion, these states and with `aux` as it left it (its
    /// positions are then those a solve from `aux` returns, bit for bit), which stands in
    /// for the evaluation at `x`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn jacobian_from(
        &mut self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        aux: &[f64],
        jx: &mut [f64],
        jm: &mut [f64],
        wx: &mut [f64],
        wm: &mut [f64],
        scratch: &mut [f64],
        kept: Option<(&[f64], &Totals)>,
    ) -> Result<()> {
        let n = self.n_states();
        let na = self.n_aux();
        let (xs, rest) = scratch.split_at_mut(n);
        let (d0, rest) = rest.split_at_mut(n);
        let (col, rest) = rest.split_at_mut(n);
        let auxs = &mut rest[..na];
        let load = !jm.is_empty() && !wx.is_empty() && !wm.is_empty();
        jx.fill(0.0);
        jm.fill(0.0);
        wx.fill(0.0);
        wm.fill(0.0);
        auxs.copy_from_slice(aux);
        // The balls' race parts at `x` are kept for the cage and ball columns.
        let tot0 = match kept {
            Some((dk, tk)) => {
                d0.copy_from_slice(dk);
                *tk
            }
            None => self.eval_with(q, v, omega, x, auxs, d0, Races::Keep)?,
        };
        let step = |xv: f64| 1.5e-8 * xv.abs().max(1.0);
        if load {
            // Ring columns: displacements and velocities (steps as the outputs' K and C).
            for c in 0..10 {
                let (mut qp, mut vp) = (*q, *v);
                let h = match c {
                    0..=2 => 1e-10,
                    3 | 4 => 1e-8,
                    5..=7 => 1e-6,
                    _ => 1e-4,
                };
                if c < 5 {
                    qp[c] += h;
                } else {
                    vp[c - 5] += h;
                }
                auxs.copy_from_slice(aux);
                let t = self.eval_with(&qp, &vp, omega, x, auxs, col, Races::Compute)?;
                for r in 0..n {
                    jm[r * 10 + c] = (col[r] - d0[r]) / h;
                }
                for r in 0..5 {
                    wm[r * 10 + c] = (t.wrench[r] - tot0.wrench[r]) / h;
                }
            }
        }
        // Cage columns: the cage reaches the balls only through the pockets (the race
        // parts, with the positions solved, are the kept ones).
        xs.copy_from_slice(x);
        for c in 0..self.nc {
            let h = step(x[c]);
            xs[c] = x[c] + h;
            let t = self.eval_with(q, v, omega, xs, auxs, col, Races::Kept)?;
            for r in 0..n {
                jx[r * n + c] = (col[r] - d0[r]) / h;
            }
            if load {
                for r in 0..5 {
                    wx[r * n + c] = (t.wrench[r] - tot0.wrench[r]) / h;
                }
            }
            xs[c] = x[c];
        }
        // Ball columns: ball j's rates and the cage's.
        // The base: the terms of the evaluation at `x`, kept with its race parts.
        let ck = self.cage_kin(x);
        self.pocket_trig(ck.theta);
        let nb = self.nb;
        let qs = self.p.ball_contacts == BallContacts::QuasiStatic;
        for j in 0..self.z {
            let k = self.nc + nb * j;
            let xrel = self.races[j].xrel;
            let base = self.terms[j];
            let mut r0 = [0.0; 9];
            self.ball_rates(&base, &x[k..k + nb], &mut r0[..nb]);
            for c in 0..nb {
                let h = step(x[k + c]);
                let mut xb = [0.0; 9];
                xb[..nb].copy_from_slice(&x[k..k + nb]);
                xb[c] += h;
                if qs {
                    // Warm start: the position at `x`.
                    auxs[3 * j..3 * j + 3].copy_from_slice(&[xrel[0], xrel[1], 1.0]);
                }
                // The quasi-static position depends on the orbital angle and speed
                // (states 0 and 1), not on the spin: the spin columns keep it.
                // They keep its frame, contacts and contact states too.
                let race = if qs && c >= 2 {
                    let (bk, xrel, _) = self.ball_kin_at(j, q, &xb[..nb], auxs, false)?;
                    self.ball_race(q, v, omega, &bk, xrel, Known::Kept(&self.races[j]))
                } else {
                    self.ball_race_at(j, q, v, omega, &xb[..nb], auxs, true)?
                };
                let bt = self.ball_cage(&ck, self.pocket_sc[j], &race);
                let mut r1 = [0.0; 9];
                self.ball_rates(&bt, &xb[..nb], &mut r1[..nb]);
                for r in 0..nb {
                    jx[(k + r) * n + k + c] = (r1[r] - r0[r]) / h;
                }
                let mut dc = [0.0; 12];
                self.cage_rates_from(
                    sub(bt.cage_f, base.cage_f),
                    sub(bt.cage_m, base.cage_m),
                    &mut dc[..self.nc],
                );
                for (r, dcr) in dc.iter().enumerate().take(self.nc) {
                    jx[r * n + k + c] = dcr / h;
                }
                if load {
                    for r in 0..5 {
                        wx[r * n + k + c] = (bt.wrench[r] - base.wrench[r]) / h;
                    }
                }
            }
        }
        Ok(())
    }

    /// The wrench on the shaft alone at motion `(q, v, omega)` and states `x`, as
    /// [`Self::eval`] gives it (the same numbers), without the pockets, the outer contacts
    /// and the rates: what the outputs' stiffness and damping difference. Quasi-static
    /// positions are solved from `aux` (updated) when `solve`, else taken from `aux` (the
    /// solution at this `q`: a velocity `v` does not move them).
    pub fn wrench_at(
        &self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        aux: &mut [f64],
        solve: bool,
    ) -> Result<[f64; 5]> {
        let mut w = [0.0; 5];
        // Positions kept at the displacement and states of the last evaluation, from the
        // warm starts it left: its frames, contacts and contact states are these.
        let m = &self.memo;
        let kept = (!solve || self.n_aux() == 0)
            && m.p.as_ref() == Some(&self.p)
            && same_bits(&m.motion[..5], q)
            && same_bits(&m.x, x)
            && same_bits(&m.aux_out, aux);
        for j in 0..self.z {
            let k = self.nc + self.nb * j;
            let (bk, xrel, c) = self.ball_kin_at(j, q, &x[k..k + self.nb], aux, solve)?;
            let (fr, known) = if kept {
                (m.races[j].fr, Known::Kept(&m.races[j]))
            } else {
                (BallFrame::new(&bk), c.map_or(Known::Nothing, Known::Solved))
            };
            let inn = self.inner_contact(q, v, omega, &bk, &fr, xrel, known);
            for (a, b) in w.iter_mut().zip(inn.wrench) {
                *a += b;
            }
        }
        if let (CageModel::Free, Some(guide), true) = (self.p.cage, &self.guide, self.guided_inner)
        {
            let ck = self.cage_kin(x);
            let e = [ck.c[0] - q[0], ck.c[1] - q[1]];
            let e_dot = [ck.v[0] - v[0], ck.v[1] - v[1]];
            let g = guide.force(e, e_dot, ck.w, omega);
            w[0] -= g.f[0];
            w[1] -= g.f[1];
        }
        Ok(w)
    }

    /// Right-hand side: fills `dx` (derivatives of the stored states in physical time),
    /// `self.balls` and the totals. Allocation-free.
    pub fn eval(
        &mut self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        aux: &mut [f64],
        dx: &mut [f64],
    ) -> Result<Totals> {
        self.eval_memo(q, v, omega, x, aux, dx, false)
    }

    /// [`Self::eval`], the balls' race parts kept for [`Self::jacobian_from`].
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn eval_keep(
        &mut self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        aux: &mut [f64],
        dx: &mut [f64],
    ) -> Result<Totals> {
        self.eval_memo(q, v, omega, x, aux, dx, true)
    }

    /// [`Self::eval`] (`keep`: [`Self::eval_keep`]), the numbers of the last one taken
    /// when it was at the same point ([`Memo`]).
    #[allow(clippy::too_many_arguments)]
    fn eval_memo(
        &mut self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        aux: &mut [f64],
        dx: &mut [f64],
        keep: bool,
    ) -> Result<Totals> {
        let motion = motion_of(q, v, omega);
        let m = &self.memo;
        if m.p.as_ref() == Some(&self.p)
            && same_bits(&m.motion, &motion)
            && same_bits(&m.x, x)
            && (same_bits(&m.aux_in, aux) || same_bits(&m.aux_out, aux))
        {
            aux.copy_from_slice(&m.aux_out);
            dx.copy_from_slice(&m.dx);
            self.balls.copy_from_slice(&m.balls);
            if keep {
                self.races.copy_from_slice(&m.races);
                self.terms.copy_from_slice(&m.terms);
            }
            return Ok(m.tot);
        }
        self.memo.p = None;
        self.memo.aux_in.copy_from_slice(aux);
        let tot = if keep {
            let tot = self.eval_with(q, v, omega, x, aux, dx, Races::Keep)?;
            self.memo.races.copy_from_slice(&self.races);
            self.memo.terms.copy_from_slice(&self.terms);
            tot
        } else {
            // The race parts and terms into the memo's, the kept ones left as they are.
            std::mem::swap(&mut self.races, &mut self.memo.races);
            std::mem::swap(&mut self.terms, &mut self.memo.terms);
            let tot = self.eval_with(q, v, omega, x, aux, dx, Races::Keep);
            std::mem::swap(&mut self.races, &mut self.memo.races);
            std::mem::swap(&mut self.terms, &mut self.memo.terms);
            tot?
        };
        let m = &mut self.memo;
        m.motion = motion;
        m.x.copy_from_slice(x);
        m.aux_out.copy_from_slice(aux);
        m.dx.copy_from_slice(dx);
        m.tot = tot;
        m.balls.copy_from_slice(&self.balls);
        m.p = Some(self.p.clone());
        Ok(tot)
    }

    /// [`Self::eval`], the balls' race parts computed, kept or taken from the kept ones.
    #[allow(clippy::too_many_arguments)]
    fn eval_with(
        &mut self,
        q: &[f64; 5],
        v: &[f64; 5],
        omega: f64,
        x: &[f64],
        aux: &mut [f64],
        dx: &mut [f64],
        races: Races,
    ) -> Result<Totals> {
        let (l, t0) = (self.l, self.t0);
        let ck = self.cage_kin(x);
        self.pocket_trig(ck.theta);
        let mut tot = Totals::default();
        let mut cf = [0.0; 3];
        let mut cm = [0.0; 3];
        for j in 0..self.z {
            let k = self.nc + self.nb * j;
            let xb = &x[k..k + self.nb];
            let sc = self.pocket_sc[j];
            let bt = match races {
                Races::Kept => self.ball_cage(&ck, sc, &self.races[j]),
                Races::Compute => {
                    let r = self.ball_race_at(j, q, v, omega, xb, aux, true)?;
                    self.ball_cage(&ck, sc, &r)
                }
                Races::Keep => {
                    self.races[j] = self.ball_race_at(j, q, v, omega, xb, aux, true)?;
                    let bt = self.ball_cage(&ck, sc, &self.races[j]);
                    self.terms[j] = bt;
                    bt
                }
            };
            self.ball_rates(&bt, xb, &mut dx[k..k + self.nb]);
            cf = add(cf, bt.cage_f);
            cm = add(cm, bt.cage_m);
            let pw = dot(bt.cage_f, ck.v);
            tot.pocket_power_whirl += pw;
            tot.pocket_power += pw + dot(bt.cage_m, ck.omega());
            for (a, b) in tot.wrench.iter_mut().zip(bt.wrench) {
                *a += b;
            }
            tot.torque_shaft += bt.torque;
            tot.external_mz += bt.ext_mz;
            tot.power_contacts += bt.power;
            if bt.info.q_i > 0.0 {
                tot.loaded += 1;
            }
            tot.max_load = tot.max_load.max(bt.info.q_i).max(bt.info.q_o);
            tot.max_pressure = tot.max_pressure.max(bt.info.p_max);
            tot.pocket_max = tot.pocket_max.max(bt.info.pocket);
            self.balls[j] = bt.info;
        }
        // Cage drag (both side faces).
        if self.p.drag > 0.0 {
            let md = -2.0
                * self.p.drag
                * disk_moment(&self.fluid, self.cage_r_in, self.cage_r_out, ck.w.abs()).abs()
                * ck.w.signum();
            cm[2] += md;
            tot.external_mz += md;
            tot.cage_drag_power = md * ck.w;
        }
        match self.p.cage {
            CageModel::Ideal => {
                dx[0] = x[1] / t0;
                dx[1] = cm[2] / self.ip * t0;
            }
            CageModel::Free => {
                let (e, e_dot, w_ring) = if self.guided_inner {
                    (
                        [ck.c[0] - q[0], ck.c[1] - q[1]],
                        [ck.v[0] - v[0], ck.v[1] - v[1]],
                        omega,
                    )
                } else {
                    ([ck.c[0], ck.c[1]], [ck.v[0], ck.v[1]], 0.0)
                };
                if let Some(guide) = &self.guide {
                    let g = guide.force(e, e_dot, ck.w, w_ring);
                    cf[0] += g.f[0];
                    cf[1] += g.f[1];
                    cm[2] += g.torque;
                    tot.external_mz += ck.c[0] * g.f[1] - ck.c[1] * g.f[0] + g.torque;
                    tot.guide_force = g.f[0].hypot(g.f[1]);
                    tot.guide_power_whirl = g.f[0] * ck.v[0] + g.f[1] * ck.v[1];
                    tot.guide_power = tot.guide_power_whirl + g.torque * ck.w;
                    if self.guided_inner {
                        tot.wrench[0] -= g.f[0];
                        tot.wrench[1] -= g.f[1];
                        tot.torque_shaft -= g.torque;
                    }
                }
                let mut acc = scale(cf, 1.0 / self.mc);
                // Mass unbalance `u` (module docs): the geometric centre's acceleration is
                // the mass centre's minus that of `u (cos theta, sin theta)` about it.
                let u = self.p.cage_unbalance;
                if u != 0.0 {
                    let (s, c) = ck.theta.sin_cos();
                    let w_dot = cm[2] / self.ip;
                    acc[0] += u * (ck.w * ck.w * c + w_dot * s);
                    acc[1] += u * (ck.w * ck.w * s - w_dot * c);
                }
                let (bx_d, by_d) = (ck.bd[0], ck.bd[1]);
                let bxdd = (cm[0] - self.ip * ck.w * by_d) / self.it;
                let bydd = (cm[1] + self.ip * ck.w * bx_d) / self.it;
                for k in 0..3 {
                    dx[k] = x[6 + k] / t0;
                    dx[6 + k] = acc[k] * t0 / l;
                }
                dx[3] = x[9] / t0;
                dx[4] = x[10] / t0;
                dx[5] = x[11] / t0;
                dx[9] = bxdd * t0;
                dx[10] = bydd * t0;
                dx[11] = cm[2] / self.ip * t0;
            }
        }
        Ok(tot)
    }

    /// Angular momentum about `z` of balls and cage, kg m²/s (module docs).
    pub fn angular_momentum(&self, x: &[f64], aux: &[f64]) -> f64 {
        let ck = self.cage_kin(x);
        let mut lz = self.ip * ck.w + self.mc * (ck.c[0] * ck.v[1] - ck.c[1] * ck.v[0]);
        for j in 0..self.z {
            let k = self.nc + self.nb * j;
            let pos = if self.n_aux() > 0 {
                [aux[3 * j], aux[3 * j + 1]]
            } else {
                [0.0; 2]
            };
            let bk = self.ball_kin(&x[k..k + self.nb], pos);
            lz += self.m * bk.rho * bk.rho * bk.w_orb + self.j * bk.w[2];
        }
        lz
    }

    /// Initial states at motion `(q, omega)`: balls at the quasi-static solution
    /// (positions, orbital speeds and spin vectors of the Jones–Harris model with the
    /// scene's race control, no gyroscopic friction), cage centred at the mean orbital
    /// speed. From rest when `omega = 0`.
    pub fn init(&mut self, q: &[f64; 5], omega: f64, x: &mut [f64], aux: &mut [f64]) -> Result<()> {
        let (l, t0) = (self.l, self.t0);
        let z = self.z;
        let mut psi = [0.0; 64];
        let mut st = [BallState::default(); 64];
        let mut res = [BallResult::default(); 64];
        if z > 64 {
            return Err(Error::invalid(
                "bearing.ball_count",
                z,
                "<= 64 for the full level",
            ));
        }
        for (j, p) in psi.iter_mut().enumerate().take(z) {
            *p = 2.0 * PI * j as f64 / z as f64;
        }
        self.qs
            .evaluate(q, omega, &psi[..z], &mut st[..z], None, Some(&mut res[..z]))?;
        x.fill(0.0);
        aux.fill(0.0);
        let mut wsum = 0.0;
        for j in 0..z {
            let r = &res[j];
            let k = self.nc + self.nb * j;
            let (s, c) = psi[j].sin_cos();
            let wr = r.omega_r;
            let (sb, cb) = r.beta.sin_cos();
            // w = w_m e_z + w_R (cos beta e_z - sin beta e_r) (quasi_static/ball.rs).
            let w = [-wr * sb * c, -wr * sb * s, r.omega_m + wr * cb];
            wsum += r.omega_m;
            let xr = match self.p.ball_contacts {
                BallContacts::QuasiStatic => {
                    let a = &mut aux[3 * j..3 * j + 3];
                    a[0] = r.x[0];
                    a[1] = r.x[1];
                    a[2] = 1.0;
                    let xb = [psi[j], r.omega_m * t0, 0.0, 0.0, 0.0];
                    self.ball_position(q, &xb, a)?
                }
                BallContacts::Dynamic => {
                    let a = self.groove_offset(q, psi[j]);
                    self.pos
                        .solve(a, self.m * r.omega_m * r.omega_m, Some(r.x), POS_TOL)?
                }
            };
            let xb = &mut x[k..k + self.nb];
            match self.p.ball_contacts {
                BallContacts::QuasiStatic => {
                    xb.copy_from_slice(&[psi[j], r.omega_m * t0, w[0] * t0, w[1] * t0, w[2] * t0]);
                }
                BallContacts::Dynamic => {
                    xb.copy_from_slice(&[
                        (self.pos.r_og + xr[1]) / l,
                        (self.z_og + xr[0]) / l,
                        psi[j],
                        0.0,
                        0.0,
                        r.omega_m * t0,
                        w[0] * t0,
                        w[1] * t0,
                        w[2] * t0,
                    ]);
                }
            }
        }
        let nc = self.nc;
        x[nc - 1] = wsum / z as f64 * t0;
        Ok(())
    }
}

fn csi_peak(cs: &ContactState) -> f64 {
    if cs.a > 0.0 && cs.b > 0.0 {
        1.5 * cs.q / (PI * cs.a * cs.b)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 7004 at 30 000 rpm at the scene's displacement (examples/scenes/7004-30000.toml),
    /// started, with the cage off centre and slower so the pockets act.
    fn started_7004() -> (FullModel, [f64; 5], f64, Vec<f64>, Vec<f64>) {
        let b = crate::geometry::preset("7004").unwrap().build().unwrap();
        let mut m = FullModel::new(&b, FullParams::for_bearing(&b)).unwrap();
        let q = [0.0, -2.96568e-6, 4.364864e-5, 0.0, 0.0];
        let omega = 3141.592654;
        let mut x = vec![0.0; m.n_states()];
        let mut aux = vec![0.0; m.n_aux()];
        m.init(&q, omega, &mut x, &mut aux).unwrap();
        x[0] = 0.05;
        x[11] *= 0.99;
        (m, q, omega, x, aux)
    }

    /// The motion-driven Jacobian `jx` (row-major) at `q`, `omega`, no velocity.
    fn motion_jacobian(
        m: &mut FullModel,
        q: &[f64; 5],
        omega: f64,
        x: &[f64],
        aux: &[f64],
    ) -> Vec<f64> {
        let n = x.len();
        let mut jx = vec![0.0; n * n];
        let mut scratch = vec![0.0; 3 * n + aux.len()];
        let (jm, wx, wm) = (&mut [], &mut [], &mut []);
        m.jacobian(
            q,
            &[0.0; 5],
            omega,
            x,
            aux,
            &mut jx,
            jm,
            wx,
            wm,
            &mut scratch,
        )
        .unwrap();
        jx
    }

    /// The wrench alone ([`FullModel::wrench_at`], what the outputs' K and C difference) is
    /// the evaluation's, bit for bit: positions solved from the warm starts, or kept from
    /// the evaluation at the same displacement for a velocity change.
    #[test]
    fn wrench_alone_is_the_evaluations_wrench() {
        let (mut m, q, omega, x, aux) = started_7004();
        let mut dx = vec![0.0; x.len()];
        for (dq, dv) in [(0.0, 0.0), (1e-9, 0.0), (0.0, 1e-6)] {
            let qp = [q[0], q[1] + dq, q[2], q[3], q[4]];
            let v = [dv, 0.0, 0.0, 0.0, 0.0];
            let mut a = aux.clone();
            let tot = m.eval(&qp, &v, omega, &x, &mut a, &mut dx).unwrap();
            let mut b = aux.clone();
            assert_eq!(
                m.wrench_at(&qp, &v, omega, &x, &mut b, true).unwrap(),
                tot.wrench
            );
            assert_eq!(a, b);
            // `a` now holds the solved positions.
            let vb = [0.0, dv + 1e-5, 0.0, 0.0, 0.0];
            let mut c = aux.clone();
            let w = m.eval(&qp, &vb, omega, &x, &mut c, &mut dx).unwrap().wrench;
            assert_eq!(m.wrench_at(&qp, &vb, omega, &x, &mut a, false).unwrap(), w);
        }
    }

    /// An evaluation repeated at the same motion and states, from the warm starts the
    /// last one found or left ([`Memo`]), gives what a model without that memo computes:
    /// rates, totals, warm starts, per-ball results and the race parts the Jacobian keeps,
    /// bit for bit; a changed state, motion or warm start is evaluated anew.
    #[test]
    fn a_repeated_evaluation_is_a_fresh_one() {
        let (m0, q, omega, x, aux) = started_7004();
        let n = x.len();
        let v = [0.0; 5];
        let bits = |a: &[f64]| a.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        // A first evaluation (the memo's), then repeats from the warm starts it found and
        // from those it left, against a fresh model's.
        let mut m = m0.clone();
        let mut a1 = aux.clone();
        let mut d1 = vec![0.0; n];
        m.eval(&q, &v, omega, &x, &mut a1, &mut d1).unwrap();
        for start in [aux.clone(), a1.clone()] {
            for keep in [false, true] {
                let mut fresh = m0.clone();
                let (mut af, mut df) = (start.clone(), vec![0.0; n]);
                let tf = fresh
                    .eval_memo(&q, &v, omega, &x, &mut af, &mut df, keep)
                    .unwrap();
                let (mut am, mut dm) = (start.clone(), vec![0.0; n]);
                let tm = m
                    .eval_memo(&q, &v, omega, &x, &mut am, &mut dm, keep)
                    .unwrap();
                assert_eq!(format!("{tf:?}"), format!("{tm:?}"));
                assert_eq!(bits(&df), bits(&dm));
                assert_eq!(bits(&af), bits(&am));
                assert_eq!(fresh.balls, m.balls);
                if keep {
                    assert_eq!(format!("{:?}", fresh.races), format!("{:?}", m.races));
                    assert_eq!(format!("{:?}", fresh.terms), format!("{:?}", m.terms));
                }
            }
        }
        assert!(m.memo.p.is_some());
        // Anything else moved: a new evaluation, not the memo's numbers.
        let mut xp = x.clone();
        xp[11] *= 1.001;
        let mut q2 = q;
        q2[1] += 1e-7;
        let mut a2 = a1.clone();
        a2[0] += 1e-9;
        for (qq, xx, aa, moved) in [
            (q, &xp, &a1, true),
            (q2, &x, &a1, true),
            (q, &x, &a2, false),
        ] {
            let (mut af, mut df) = (aa.clone(), vec![0.0; n]);
            let tf = m0
                .clone()
                .eval(&qq, &v, omega, xx, &mut af, &mut df)
                .unwrap();
            let mut mm = m.clone();
            let (mut am, mut dm) = (aa.clone(), vec![0.0; n]);
            let tm = mm.eval(&qq, &v, omega, xx, &mut am, &mut dm).unwrap();
            assert_eq!(format!("{tf:?}"), format!("{tm:?}"));
            assert_eq!(bits(&df), bits(&dm));
            if moved {
                assert_ne!(bits(&dm), bits(&d1));
            }
        }
        // Changed options: a new evaluation too.
        let (mut fresh, mut mm) = (m0.clone(), m.clone());
        fresh.p.drag *= 2.0;
        mm.p.drag *= 2.0;
        let (mut af, mut df) = (a1.clone(), vec![0.0; n]);
        fresh.eval(&q, &v, omega, &x, &mut af, &mut df).unwrap();
        let (mut am, mut dm) = (a1.clone(), vec![0.0; n]);
        mm.eval(&q, &v, omega, &x, &mut am, &mut dm).unwrap();
        assert_eq!(bits(&df), bits(&dm));
        assert_ne!(bits(&dm), bits(&d1));
    }

    /// The Jacobian's cage columns, which re-evaluate only the pockets on the balls' kept
    /// race parts, equal whole evaluations' forward differences bit for bit.
    #[test]
    fn cage_columns_equal_whole_differences_exactly() {
        let (mut m, q, omega, x, aux) = started_7004();
        let n = x.len();
        let v = [0.0; 5];
        let jx = motion_jacobian(&mut m, &q, omega, &x, &aux);
        let (mut d0, mut d1) = (vec![0.0; n], vec![0.0; n]);
        m.eval(&q, &v, omega, &x, &mut aux.clone(), &mut d0)
            .unwrap();
        for c in 0..12 {
            let mut xp = x.clone();
            let h = 1.5e-8 * x[c].abs().max(1.0);
            xp[c] += h;
            m.eval(&q, &v, omega, &xp, &mut aux.clone(), &mut d1)
                .unwrap();
            for r in 0..n {
                assert_eq!(jx[r * n + c], (d1[r] - d0[r]) / h, "row {r} col {c}");
            }
        }
    }

    /// The Jacobian's ball columns (spin columns on the kept frame, contacts and contact
    /// states) equal whole evaluations' forward differences bit for bit in the ball's own
    /// rows, the positions solved from the warm starts the evaluation at `x` left.
    #[test]
    fn ball_columns_equal_whole_differences_in_their_rows() {
        let (mut m, q, omega, x, aux) = started_7004();
        let n = x.len();
        let v = [0.0; 5];
        let (mut a1, mut d0, mut d1) = (aux.clone(), vec![0.0; n], vec![0.0; n]);
        m.eval(&q, &v, omega, &x, &mut a1, &mut d0).unwrap();
        let jx = motion_jacobian(&mut m, &q, omega, &x, &a1);
        let (nc, nb) = (m.ball0(), m.per_ball());
        let mut nonzero = 0;
        for j in 0..m.z() {
            for c in 0..nb {
                let col = nc + nb * j + c;
                let mut xp = x.clone();
                let h = 1.5e-8 * x[col].abs().max(1.0);
                xp[col] += h;
                m.eval(&q, &v, omega, &xp, &mut a1.clone(), &mut d1)
                    .unwrap();
                for r in nc + nb * j..nc + nb * (j + 1) {
                    assert_eq!(jx[r * n + col], (d1[r] - d0[r]) / h, "row {r} col {col}");
                    nonzero += usize::from(jx[r * n + col] != 0.0);
                }
            }
        }
        assert!(nonzero > m.z() * m.per_ball(), "{nonzero}");
    }

    /// The velocities the contacts use are the time derivatives of the material points'
    /// positions: cage pocket walls of a tilted, eccentric, spinning cage, and the inner
    /// groove of a tilted spinning ring (central differences along the motion).
    #[test]
    fn material_velocities_are_position_rates() {
        let ck = CageKin {
            c: [1e-5, -2e-5, 3e-6],
            b: [1e-3, -2e-3],
            theta: 0.3,
            v: [0.02, -0.01, 0.005],
            bd: [0.5, -0.3],
            w: 1200.0,
        };
        let dt = 1e-7;
        let at = |t: f64| CageKin {
            c: add(ck.c, scale(ck.v, t)),
            b: [ck.b[0] + ck.bd[0] * t, ck.b[1] + ck.bd[1] * t],
            theta: ck.theta + ck.w * t,
            ..ck
        };
        for (phi, r) in [(0.0, 0.0155), (1.1, 0.0155), (2.5, 0.019)] {
            let p = |t: f64| {
                let k = at(t);
                k.point(k.theta + phi, r)
            };
            let fd = scale(sub(p(dt), p(-dt)), 0.5 / dt);
            let v = ck.velocity_at(p(0.0));
            // 1e-5: the positions are linear in the tilts, so terms of order |b|² (2e-6
            // relative here) differ; a missing first-order term (the tilt lift's rate from
            // the spin) would be ~ w r |b| = 0.04 m/s against a 0.02 m/s axial speed.
            for i in 0..3 {
                assert!(
                    (fd[i] - v[i]).abs() < 1e-5 * norm(v),
                    "{i}: {fd:?} vs {v:?}"
                );
            }
        }
        // Inner ring: groove point at body angle phi, radius ri, lifted by the tilts.
        let q = [1e-5, 2e-5, -1e-5, 1e-3, -5e-4];
        let v = [0.01, 0.0, 0.002, 0.4, 0.7];
        let omega = 3000.0;
        let ri = 0.0115;
        let pt = |t: f64, phi: f64| {
            let qq: [f64; 5] = std::array::from_fn(|k| q[k] + v[k] * t);
            let (s, c) = (phi + omega * t).sin_cos();
            [
                qq[0] + ri * c,
                qq[1] + ri * s,
                qq[2] + ri * (qq[3] * s - qq[4] * c),
            ]
        };
        let wr = ring_omega(&q, &v, omega);
        for phi in [0.0, 0.7, 2.0, 4.0] {
            let fd = scale(sub(pt(dt, phi), pt(-dt, phi)), 0.5 / dt);
            let p0 = pt(0.0, phi);
            let vel = add([v[0], v[1], v[2]], cross(wr, sub(p0, [q[0], q[1], q[2]])));
            for i in 0..3 {
                assert!(
                    (fd[i] - vel[i]).abs() < 1e-5 * norm(vel),
                    "{i}: {fd:?} vs {vel:?}"
                );
            }
        }
    }
}
