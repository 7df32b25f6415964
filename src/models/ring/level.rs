//! The `ring` level: ring on massless balls (docs/physics.md §5.1) behind the level seam, with
//! the optional effects of the scene (defects, waviness, spacing scatter, EHL film) and the
//! slow effects (wear, docs/physics.md §7; friction power and thermal growth, §8).
//!
//! Slow state (only when the scene turns wear or thermal on; see [`SlowLayout`]):
//! - continuous states after the cage (and shaft) angle: the wear depth accumulated since
//!   the start on each cell of the outer-race map, then of the inner-race map (m), rates
//!   from `crate::models::wear` integrated with the dynamics. The sliding speed is a
//!   **kinematic-slip estimate** (Heathcote slip at the kinematic cage speed: massless
//!   balls do not skid); the skidding level's wear (`crate::models::wear_map`) uses the
//!   dynamics' own slip;
//! - memory (`aux`): the wear maps that act on the clearance (outer, inner), the
//!   accumulated depth at the start of the current window (outer, inner), the window's
//!   start in shaft revolutions and the cycles done; then the thermal block: the four node
//!   temperature rises (K), the time of the last thermal update, energy generated and
//!   removed (J), the last power loss (W) and the clearance change (m).
//!
//! Time-scale separation (docs/physics.md §7): at a communication point where the window of
//! `window_revs` shaft revolutions is complete, the window's accumulated wear is scaled to
//! `cycle_revs` revolutions and added to the maps, which enter every ball's deflection like
//! a defect (`- h_outer(psi) - h_inner(psi - theta_s)`) ([`wear::close_window`]). The
//! thermal network advances at each communication point over the elapsed time times
//! `time_scale`, on its own step ([`ThermalModel::advance`]). This file is the glue: the
//! memory layout and which physics runs when.

use crate::contact::{Curvature, PointContact, Race};
use crate::error::Result;
use crate::geometry::element::ElementKind;
use crate::geometry::kinematics::nominal_cage_speed as cage_speed;
use crate::geometry::Bearing;
use crate::lubrication::entrainment_speed;
use crate::models::effects::{Effects, FilmKind, RingEffects, WearRegime};
use crate::models::ring::{Profile, RingAt, RingDof, RingEval, RingJacobian, RingModel};
use crate::models::thermal::{ContactSums, ThermalModel, ThermalParams};
use crate::models::waviness::WavySite;
use crate::models::wear::{self, FactorsAt, FilmDefect, WearLaw};
use crate::models::LevelArgs;
use crate::seam::element::ElementLoad;
use crate::seam::{wrenches_by_rhs, Jacobians, LevelModel, LevelOutputs, Motion, Point, Points};
use std::cell::Cell;

/// Kelvin at 0 °C.
const T_ZERO: f64 = 273.15;

/// Where the slow state sits in the component state (see the module notes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SlowLayout {
    /// Wear: first continuous state of the accumulators, first aux slot, cells per race.
    pub wear: Option<(usize, usize, usize)>,
    /// Thermal: first aux slot of the thermal block.
    pub thermal: Option<usize>,
}

pub use crate::models::thermal::THERMAL_SLOTS;

impl SlowLayout {
    /// The layout a ring level with effects `e` on bearing `b` uses.
    pub fn of(e: &Effects, b: &Bearing) -> Result<SlowLayout> {
        let nx = if e.is_off() {
            1
        } else {
            1 + RingEffects::new(e, b)?.needs_shaft_angle as usize
        };
        let wear = e.wear.as_ref().map(|w| (nx, 0, w.cells as usize));
        let thermal = e
            .thermal
            .as_ref()
            .map(|_| wear.map_or(0, |(_, _, n)| 4 * n + 2));
        Ok(SlowLayout { wear, thermal })
    }

    /// Wear maps acting on the clearance `(outer, inner)`, m per cell (cell `k` centred at
    /// `2 pi k / n`; outer in the fixed frame, inner in the shaft's).
    /// `aux` is the component state's memory (`State::aux`).
    pub fn wear_maps<'a>(&self, aux: &'a [f64]) -> Option<(&'a [f64], &'a [f64])> {
        let (_, a0, n) = self.wear?;
        Some((&aux[a0..a0 + n], &aux[a0 + n..a0 + 2 * n]))
    }

    /// Wear cycles done.
    pub fn wear_cycles(&self, aux: &[f64]) -> Option<f64> {
        let (_, a0, n) = self.wear?;
        Some(aux[a0 + 4 * n + 1])
    }

    /// Thermal block: `[dT inner, dT outer, dT balls, dT oil]` (K), last update time (s),
    /// energy generated and removed (J), power loss (W), clearance change (m).
    pub fn thermal<'a>(&self, aux: &'a [f64]) -> Option<&'a [f64]> {
        let a0 = self.thermal?;
        Some(&aux[a0..a0 + THERMAL_SLOTS])
    }
}

/// Wear part of the slow effects.
#[derive(Debug)]
struct WearPart {
    law: WearLaw,
    n: usize,
    /// First continuous state (outer map; inner follows).
    x0: usize,
    /// First aux slot.
    a0: usize,
    /// Contacts (inner, outer) at the nominal angle.
    contacts: [PointContact; 2],
    /// Their transverse semi-axis coefficients `ca` (`a = ca Q^(1/3)`,
    /// [`PointContact::semi_axis_coefficients`]), computed once: a ball's two contacts
    /// share its load, so `Q^(1/3)` is taken once per ball and `a` is
    /// [`PointContact::semi_axes`]'s, bit for bit.
    semi_axis_a: [f64; 2],
    /// Groove conformities (inner, outer).
    f: [f64; 2],
    /// Cell lengths on the race (inner, outer), m.
    cell_len: [f64; 2],
    m: f64,
    window: f64,
    cycle: f64,
    cycles: f64,
    /// Surface temperature without the thermal model, K.
    ts: f64,
    /// The wear law's load-free factors of both contacts ([`WearLaw::prepare`]) at the
    /// last entrainment speed and surface temperatures (their bits) asked: a pure function
    /// of that key, so the same bits with or without it (no history); a load-driven ring
    /// at a held speed asks for the same key at every right-hand side.
    last_factors: Cell<Option<([u64; 3], [FactorsAt; 2])>>,
}

impl WearPart {
    /// The contacts' [`FactorsAt`] at entrainment speed `u` and surface temperatures `ts`
    /// (inner, outer).
    fn factors_at(&self, u: f64, ts: [f64; 2]) -> [FactorsAt; 2] {
        let key = [u.to_bits(), ts[0].to_bits(), ts[1].to_bits()];
        if let Some((k, f)) = self.last_factors.get() {
            if k == key {
                return f;
            }
        }
        let f = [0, 1].map(|r| self.law.prepare(&self.contacts[r], u, ts[r]));
        self.last_factors.set(Some((key, f)));
        f
    }
}

/// Thermal part of the slow effects.
#[derive(Debug)]
struct ThermalPart {
    model: ThermalModel,
    a0: usize,
    ambient: f64,
}

/// The slow effects of a ring level.
#[derive(Debug)]
struct Slow {
    wear: Option<WearPart>,
    thermal: Option<ThermalPart>,
    d: f64,
    dm: f64,
    gamma: f64,
    n_aux: usize,
}

impl Slow {
    fn new(b: &Bearing, e: &Effects, x0: usize) -> Result<Option<Slow>> {
        if e.wear.is_none() && e.thermal.is_none() {
            return Ok(None);
        }
        let alpha = b.nominal_contact_angle();
        let contacts = [
            PointContact::new(
                Curvature::ball_race(b.d, b.dm, alpha, b.fi(), Race::Inner),
                b.e_eff_inner(),
            ),
            PointContact::new(
                Curvature::ball_race(b.d, b.dm, alpha, b.fo(), Race::Outer),
                b.e_eff_outer(),
            ),
        ];
        let gamma = b.d * alpha.cos() / b.dm;
        let lubricant = match &e.lubrication {
            Some(l) if l.film == FilmKind::Ehl => Some(l.lubricant()?),
            _ => None,
        };
        let wear = e.wear.as_ref().map(|w| {
            let n = w.cells as usize;
            let film = match (lubricant, w.regime) {
                (Some(l), WearRegime::Auto) => Some(FilmDefect {
                    lubricant: l,
                    ax: w.defect_length_m,
                    t0: w.defect_time_s,
                    ea: w.activation_energy_j_mol,
                }),
                _ => None,
            };
            let circ = |d: f64| std::f64::consts::PI * d / n as f64;
            WearPart {
                law: WearLaw {
                    k: w.coefficient,
                    hardness: w.hardness_gpa * 1e9,
                    film,
                    surface_temperature: w.surface_temperature_c + T_ZERO,
                },
                n,
                x0,
                a0: 0,
                contacts,
                semi_axis_a: contacts.map(|c| c.semi_axis_coefficients().0),
                f: [b.fi(), b.fo()],
                cell_len: [circ(b.dm * (1.0 - gamma)), circ(b.dm * (1.0 + gamma))],
                m: wear::heathcote_mean_factor(),
                window: w.window_revs,
                cycle: w.cycle_revs,
                cycles: w.cycles as f64,
                ts: w.surface_temperature_c + T_ZERO,
                last_factors: Cell::new(None),
            }
        });
        let wear_aux = wear.as_ref().map_or(0, |w| 4 * w.n + 2);
        let thermal = e.thermal.as_ref().map(|t| {
            let nu = t
                .viscosity_cst
                .unwrap_or_else(|| lubricant.map_or(20.0, |l| l.viscosity / l.density * 1e6));
            let eta = lubricant.map_or(nu * 1e-6 * 860.0, |l| l.viscosity);
            let p = ThermalParams {
                f0: t.f0,
                f1: t.f1,
                nu_cst: nu,
                eta,
                mu_spin: t.spin_friction,
                hysteresis: t.hysteresis_loss,
                g_shaft: t.shaft_conductance_w_k,
                g_housing: t.housing_conductance_w_k,
                g_oil: t.oil_conductance_w_k,
                c_oil: t.oil_heat_capacity_j_k,
                g_contact: t.contact_conductance_w_k,
                dt: t.dt_s,
                time_scale: t.time_scale,
                growth: t.growth_factor,
            };
            ThermalPart {
                model: ThermalModel::new(b, p, contacts),
                a0: wear_aux,
                ambient: t.ambient_c + T_ZERO,
            }
        });
        Ok(Some(Slow {
            n_aux: wear_aux + thermal.as_ref().map_or(0, |_| THERMAL_SLOTS),
            wear,
            thermal,
            d: b.d,
            dm: b.dm,
            gamma,
        }))
    }

    fn n_states(&self) -> usize {
        self.wear.as_ref().map_or(0, |w| 2 * w.n)
    }

    /// Deflection offset of a ball at `psi` with the shaft turned by `theta_s`: minus the
    /// wear depths under it, plus half the thermal loss of diametral clearance.
    #[inline]
    fn offset(&self, aux: &[f64], psi: f64, theta_s: f64) -> f64 {
        let mut o = 0.0;
        if let Some(w) = &self.wear {
            let (outer, inner) = (&aux[w.a0..w.a0 + w.n], &aux[w.a0 + w.n..w.a0 + 2 * w.n]);
            o -= wear::sample(outer, psi) + wear::sample(inner, psi - theta_s);
        }
        if let Some(t) = &self.thermal {
            o -= 0.5 * aux[t.a0 + 8];
        }
        o
    }

    /// Ball rotation relative to the inner and outer race at shaft speed `omega`.
    #[inline]
    fn relative_rolling(&self, omega: f64) -> [f64; 2] {
        use crate::geometry::kinematics as kin;
        let wc = kin::cage_speed(self.gamma, omega, 0.0);
        let wb = kin::ball_spin_speed(self.d, self.dm, self.gamma, omega, 0.0);
        [wb + (omega - wc).abs(), (wb - wc.abs()).abs()]
    }
}

/// Ring on massless balls (docs/physics.md §5.1). States: the cage angle, and the shaft angle
/// when an effect turns with the shaft or the balls (inner-race or ball defects/waviness).
#[derive(Debug)]
pub struct RingLevel {
    model: RingModel,
    cage_ratio: f64,
    dof: RingDof,
    eval: RingEval,
    /// Defects and waviness (None: no profile, nothing evaluated).
    profile: Option<RingEffects>,
    /// Whether state 1 is the shaft angle.
    shaft_angle: bool,
    /// Wear and thermal (None: off, nothing evaluated).
    slow: Option<Slow>,
    /// `eval` holds the matrices too ([`LevelModel::rhs_at_end`]), evaluated at the point
    /// of this key ([`RingLevel::point_key`]); `None` once another evaluation overwrote it.
    kept: Option<[u64; 13]>,
    /// The balls' loads of the last outputs, when asked to keep them
    /// ([`LevelModel::keep_element_loads`]; `None`: nothing stored).
    loads: Option<Vec<ElementLoad>>,
}

impl RingLevel {
    /// Build without effects.
    pub fn new(b: &Bearing, dof: RingDof, damping: f64) -> Self {
        RingLevel {
            model: RingModel::new(b, dof, damping),
            cage_ratio: cage_speed(b, 1.0),
            dof,
            eval: RingEval::default(),
            profile: None,
            shaft_angle: false,
            slow: None,
            kept: None,
            loads: None,
        }
    }

    /// Build with the scene's effects (validated here against the bearing).
    pub fn with_effects(b: &Bearing, dof: RingDof, damping: f64, e: &Effects) -> Result<Self> {
        let mut level = RingLevel::new(b, dof, damping);
        if e.is_off() {
            e.validate_for(b)?;
            return Ok(level);
        }
        let mut fx = RingEffects::new(e, b)?;
        let mut model = RingModel::new(b, dof, damping);
        if !fx.spacing.is_empty() {
            model = model.with_spacing(std::mem::take(&mut fx.spacing));
        }
        if let Some(l) = fx.lubricant {
            model = model.with_film(l);
        }
        level.model = model;
        level.shaft_angle = fx.needs_shaft_angle;
        if fx.has_profile() {
            level.profile = Some(fx);
        }
        level.slow = Slow::new(b, e, 1 + level.shaft_angle as usize)?;
        Ok(level)
    }

    /// Shaft angle: state 1 when kept, else from the cage angle (both start at 0 and the
    /// cage turns at a fixed ratio of the shaft).
    #[inline]
    fn shaft_turned(&self, x: &[f64]) -> f64 {
        if self.shaft_angle {
            x[1]
        } else {
            x[0] / self.cage_ratio
        }
    }

    /// What an evaluation without slow effects reads besides the level's fixed parts, as
    /// bits: the cage (and shaft) angle, the shaft speed and the ring's motion (not the
    /// time: the level is time-invariant, [`LevelModel::rhs_time_invariant`]).
    fn point_key(&self, m: &Motion, x: &[f64]) -> [u64; 13] {
        let mut k = [0; 13];
        k[0] = x[0].to_bits();
        k[1] = if self.shaft_angle { x[1].to_bits() } else { 0 };
        k[2] = m.omega.to_bits();
        for i in 0..5 {
            k[3 + i] = m.q[i].to_bits();
            k[8 + i] = m.v[i].to_bits();
        }
        k
    }

    /// `[shaft angle for the fast effects, shaft angle turned]` ([`eval_ring`]).
    #[inline]
    fn angles(&self, x: &[f64]) -> [f64; 2] {
        [
            if self.shaft_angle { x[1] } else { 0.0 },
            self.shaft_turned(x),
        ]
    }

    /// Evaluate the ring model with the level's effects into `self.eval` (cage speed `wc`);
    /// `per_ball(slow, j, psi, q)` sees each ball's load with the slow effects.
    fn evaluate<F: FnMut(Option<&Slow>, usize, f64, f64)>(
        &mut self,
        at: LevelAt<'_>,
        jac: bool,
        mut per_ball: F,
    ) {
        let slow = self.slow.as_ref();
        let sources = Sources {
            profile: self.profile.as_ref(),
            slow,
            angles: self.angles(at.x),
        };
        eval_ring(
            &self.model,
            &mut self.eval,
            sources,
            at,
            jac,
            |j, psi, q| per_ball(slow, j, psi, q),
        );
    }

    /// Wear-depth rates of the accumulators (`dx` of the wear block) at this instant; also
    /// leaves the forces in `self.eval`.
    fn wear_rates(&mut self, t: f64, m: &Motion, x: &[f64], aux: &[f64], wc: f64, dx: &mut [f64]) {
        let angles = self.angles(x);
        let turned = angles[1];
        let slow = self.slow.as_ref().expect("wear on");
        let w = slow.wear.as_ref().expect("wear on");
        let rel = slow.relative_rolling(m.omega);
        let u = entrainment_speed(slow.dm, slow.gamma, m.omega);
        let ts = match &slow.thermal {
            Some(th) => [th.ambient + aux[th.a0], th.ambient + aux[th.a0 + 1]],
            None => [w.ts; 2],
        };
        let factors = w.factors_at(u, ts);
        let (dx_o, dx_i) = dx[w.x0..w.x0 + 2 * w.n].split_at_mut(w.n);
        dx_o.fill(0.0);
        dx_i.fill(0.0);
        let per_ball = |_j: usize, psi: f64, q: f64| {
            // `semi_axes`' own `Q^(1/3)`, once for both contacts.
            let q3 = q.max(0.0).cbrt();
            for r in 0..2 {
                let a = w.semi_axis_a[r] * q3;
                let us = wear::heathcote_slip(rel[r], a, w.f[r], slow.d, w.m);
                // `w.law.factors(contact, q, u, us, ts)`, its load-free part kept.
                let (la, psi_f) = factors[r].factors(q, us);
                let rate = w.law.area_rate(q, a, us, la, psi_f);
                if r == 0 {
                    wear::deposit(dx_i, psi - turned, rate, w.cell_len[0]);
                } else {
                    wear::deposit(dx_o, psi, rate, w.cell_len[1]);
                }
            }
        };
        let sources = Sources {
            profile: self.profile.as_ref(),
            slow: Some(slow),
            angles,
        };
        eval_ring(
            &self.model,
            &mut self.eval,
            sources,
            LevelAt { t, m, x, aux, wc },
            false,
            per_ball,
        );
    }
}

/// Where the level evaluates its ring model: time, motion, the level's states and memory,
/// the cage speed `wc` (rad/s).
#[derive(Clone, Copy)]
struct LevelAt<'a> {
    t: f64,
    m: &'a Motion,
    x: &'a [f64],
    aux: &'a [f64],
    wc: f64,
}

/// The effects a ring evaluation reads: the fast profile, the slow state and the shaft
/// angles `[for the fast effects, turned]`.
#[derive(Clone, Copy)]
struct Sources<'a> {
    profile: Option<&'a RingEffects>,
    slow: Option<&'a Slow>,
    angles: [f64; 2],
}

/// Evaluate the ring model with the profile of the effects and the slow state.
/// `angles = [shaft angle for the fast effects, shaft angle turned]`.
fn eval_ring<F: FnMut(usize, f64, f64)>(
    model: &RingModel,
    eval: &mut RingEval,
    Sources {
        profile,
        slow,
        angles,
    }: Sources<'_>,
    LevelAt { t, m, x, aux, wc }: LevelAt<'_>,
    jac: bool,
    per_ball: F,
) {
    let [theta_s, turned] = angles;
    let ev = |p: Profile<'_>, max: f64, eval: &mut RingEval, per_ball: F| {
        model.eval_with(
            RingAt {
                theta_c: x[0],
                omega_c: wc,
                q: &m.q,
                v: &m.v,
                t,
            },
            (p, max),
            jac,
            eval,
            per_ball,
        )
    };
    match (profile, slow) {
        (None, None) => ev(None, 0.0, eval, per_ball),
        (Some(fx), None) => {
            let at = fx.at(x[0], theta_s);
            let p = |j: usize, psi: f64, _t: f64| at.offset(j, psi);
            ev(Some(&p), profile_max(fx), eval, per_ball)
        }
        // The slow offsets (wear maps, thermal clearance) have no bound kept: no skipping.
        (fx, Some(slow)) => {
            let at = fx.map(|fx| fx.at(x[0], theta_s));
            let p = |j: usize, psi: f64, _t: f64| {
                at.as_ref().map_or(0.0, |at| at.offset(j, psi)) + slow.offset(aux, psi, turned)
            };
            ev(Some(&p), f64::INFINITY, eval, per_ball)
        }
    }
}

/// The largest offset the fast effects can add to a ball's approach, m: a race harmonic
/// `A sin(..)` adds at most `|A|`, a ball harmonic (met at both races, `w(phi) + w(phi +
/// pi)`) at most `2|A|`, a defect only takes away (its loss is `>= 0`).
fn profile_max(fx: &RingEffects) -> f64 {
    fx.waviness
        .iter()
        .map(|w| match w.site {
            WavySite::Outer | WavySite::Inner => w.amplitude.abs(),
            WavySite::Ball(_) => 2.0 * w.amplitude.abs(),
        })
        .sum()
}

/// The element kinds the ring level takes: balls (its own Hertz loop) and every kind the
/// quasi-static level has a contact law for ([`super::elements::LawRingLevel`]).
pub const ELEMENTS: &[ElementKind] = crate::models::quasi_static::level::ELEMENTS;

/// The registry's constructor (the level registry, `LEVELS` in `component/levels.rs`): 2 or 5 ring
/// coordinates (`model.ring_dof`), contact damping and the scene's effects.
pub fn build(a: &LevelArgs) -> Result<Box<dyn LevelModel>> {
    let dof = if a.ring_dof == 5 {
        RingDof::Five
    } else {
        RingDof::Two
    };
    if a.bearing.element() != ElementKind::Ball {
        // Any other element through its contact law (the quasi-static level's laws), massless
        // as the ring level's balls are.
        let opts = crate::models::quasi_static::Options {
            race_control: a.race_control,
            ..Default::default()
        };
        let law = crate::models::quasi_static::level::element_law(a, opts, false)?;
        return Ok(Box::new(
            super::elements::LawRingLevel::new(a, law, dof)?.massless_cylindrical(a)?,
        ));
    }
    Ok(Box::new(RingLevel::with_effects(
        a.bearing,
        dof,
        a.contact_damping,
        a.effects,
    )?))
}

impl LevelModel for RingLevel {
    fn keep_element_loads(&mut self) -> bool {
        self.loads = Some(vec![ElementLoad::default(); self.model.z()]);
        true
    }
    fn element_loads(&self, out: &mut Vec<ElementLoad>) -> bool {
        out.clear();
        out.extend(self.loads.iter().flatten());
        self.loads.is_some()
    }
    fn n_states(&self) -> usize {
        1 + self.shaft_angle as usize + self.slow.as_ref().map_or(0, Slow::n_states)
    }
    fn n_aux(&self) -> usize {
        self.slow.as_ref().map_or(0, |s| s.n_aux)
    }
    fn ring_dofs(&self) -> &'static [usize] {
        match self.dof {
            RingDof::Two => &[0, 1],
            RingDof::Five => &[0, 1, 2, 3, 4],
        }
    }
    fn states_are_quadrature(&self) -> bool {
        // Cage (and shaft) angle only: rates cage_ratio * omega and omega. Wear and thermal
        // states have rates that depend on the contact state.
        self.slow.is_none()
    }
    fn rhs_time_invariant(&self) -> bool {
        // `rhs` reads the motion, the states and `aux` (wear maps, thermal clearance) and
        // writes only `self.eval`, which every evaluation overwrites; the time reaches only
        // the profile, whose offsets depend on the angles, not on `t`.
        true
    }
    /// The analytic Jacobian of the plain ring (dry contacts, no profile, no slow
    /// effects: [`RingModel::wrench_jacobian`]); otherwise `false` and the integrator
    /// differences. The cage angle's rate is the fixed ratio of the shaft speed (an
    /// input), so the rates' rows are zero; the wrench's columns are its derivatives in
    /// the cage angle, the displacement and the velocity. One pass over the balls instead
    /// of a right-hand side per state.
    fn jacobian(&mut self, p: Point<'_>, j: Jacobians<'_>) -> bool {
        if self.slow.is_some() || self.profile.is_some() || self.shaft_angle {
            return false;
        }
        let Point { m, x, .. } = p;
        let wc = self.cage_ratio * m.omega;
        let mut d = RingJacobian::default();
        if !self.model.wrench_jacobian(x[0], wc, &m.q, &m.v, &mut d) {
            return false;
        }
        let Jacobians { jx, jm, wx, wm } = j;
        jx.fill(0.0);
        jm.fill(0.0);
        if !wm.is_empty() {
            let n = wx.len() / 5;
            wx.fill(0.0);
            for r in 0..5 {
                wx[r * n] = d.dtheta[r];
                wm[r * 10..r * 10 + 5].copy_from_slice(&d.dq[r]);
                wm[r * 10 + 5..r * 10 + 10].copy_from_slice(&d.dv[r]);
            }
        }
        true
    }
    fn init(&mut self, _m: &Motion, x: &mut [f64], aux: &mut [f64]) -> Result<()> {
        x.fill(0.0);
        aux.fill(0.0);
        Ok(())
    }
    fn rhs(&mut self, p: Point<'_>, dx: &mut [f64], wrench: Option<&mut [f64; 5]>) -> Result<()> {
        self.kept = None;
        let Point { t, m, x, aux } = p;
        let wc = self.cage_ratio * m.omega;
        dx[0] = wc;
        if self.shaft_angle {
            dx[1] = m.omega;
        }
        if self.profile.is_none() && self.slow.is_none() {
            // Nothing but the model: `evaluate` without the angles it would compute for
            // the effects (the same call `eval_ring` makes then).
            if let Some(w) = wrench {
                self.model.eval_with(
                    RingAt {
                        theta_c: x[0],
                        omega_c: wc,
                        q: &m.q,
                        v: &m.v,
                        t,
                    },
                    (None, 0.0),
                    false,
                    &mut self.eval,
                    |_, _, _| {},
                );
                *w = self.eval.wrench;
            }
        } else if self.slow.as_ref().is_some_and(|s| s.wear.is_some()) {
            self.wear_rates(t, m, x, aux, wc, dx);
            if let Some(w) = wrench {
                *w = self.eval.wrench;
            }
        } else if let Some(w) = wrench {
            self.evaluate(LevelAt { t, m, x, aux, wc }, false, |_, _, _, _| {});
            *w = self.eval.wrench;
        }
        Ok(())
    }
    /// Without effects, the model at each point as `rhs` calls it, in one loop.
    fn wrenches(&mut self, p: Points<'_>, dx: &mut [f64], out: &mut [[f64; 5]]) -> Result<()> {
        if self.profile.is_some() || self.slow.is_some() {
            return wrenches_by_rhs(self, p, dx, out);
        }
        self.kept = None;
        for (k, (w, m)) in out.iter_mut().zip(p.m).enumerate() {
            let wc = self.cage_ratio * m.omega;
            self.model.eval_with(
                RingAt {
                    theta_c: p.x[k * p.stride],
                    omega_c: wc,
                    q: &m.q,
                    v: &m.v,
                    t: p.t[k],
                },
                (None, 0.0),
                false,
                &mut self.eval,
                |_, _, _| {},
            );
            *w = self.eval.wrench;
        }
        Ok(())
    }
    fn rhs_at_end(
        &mut self,
        p: Point<'_>,
        dx: &mut [f64],
        wrench: Option<&mut [f64; 5]>,
    ) -> Result<()> {
        // Without slow effects, the outputs at this point are this evaluation with the
        // matrices (the wrench is the same arithmetic with or without them): keep it.
        let w = match wrench {
            Some(w) if self.slow.is_none() => w,
            wrench => return self.rhs(p, dx, wrench),
        };
        let Point { t, m, x, aux } = p;
        let wc = self.cage_ratio * m.omega;
        dx[0] = wc;
        if self.shaft_angle {
            dx[1] = m.omega;
        }
        self.evaluate(LevelAt { t, m, x, aux, wc }, true, |_, _, _, _| {});
        *w = self.eval.wrench;
        self.kept = Some(self.point_key(m, x));
        Ok(())
    }
    fn outputs(&mut self, p: Point<'_>, out: &mut LevelOutputs) -> Result<()> {
        let Point { t, m, x, aux } = p;
        let wc = self.cage_ratio * m.omega;
        let turned = self.shaft_turned(x);
        // Wear cycle: scale the window's accumulated wear to the cycle, add it to the maps.
        if let Some(w) = self.slow.as_ref().and_then(|s| s.wear.as_ref()) {
            let revs = turned.abs() / std::f64::consts::TAU;
            wear::close_window(
                &x[w.x0..w.x0 + 2 * w.n],
                &mut aux[w.a0..w.a0 + 4 * w.n + 2],
                revs,
                w.window,
                w.cycle,
                w.cycles,
            );
        }
        let mut sums = ContactSums::default();
        let omega = m.omega;
        // Kept from the integration's last stage at this very point (no slow effects: no
        // per-ball sums wanted, no ball loads kept): the same bits without evaluating again.
        let kept =
            self.slow.is_none() && self.loads.is_none() && self.kept == Some(self.point_key(m, x));
        if !kept {
            self.kept = None;
            let at = LevelAt { t, m, x, aux, wc };
            let thermal = |slow: Option<&Slow>, q: f64, sums: &mut ContactSums| {
                if let Some(th) = slow.and_then(|s| s.thermal.as_ref()) {
                    th.model.add_ball(omega, q, sums);
                }
            };
            match self.loads.take() {
                None => self.evaluate(at, true, |slow, _j, _psi, q| thermal(slow, q, &mut sums)),
                Some(mut loads) => {
                    // Every ball at its place, unloaded unless the evaluation loads it (a
                    // massless ball carries the same load at both contacts).
                    for (j, l) in loads.iter_mut().enumerate() {
                        *l = ElementLoad {
                            psi: self.model.azimuth(x[0], j),
                            ..ElementLoad::default()
                        };
                    }
                    self.evaluate(at, true, |slow, j, psi, q| {
                        thermal(slow, q, &mut sums);
                        loads[j] = ElementLoad {
                            psi,
                            inner: q,
                            outer: q,
                        };
                    });
                    self.loads = Some(loads);
                }
            }
        }
        let e = &self.eval;
        *out = LevelOutputs {
            wrench: e.wrench,
            k: e.k,
            c: e.c,
            cage_omega: wc,
            balls_loaded: e.loaded as f64,
            max_load: e.max_load,
            max_pressure: if e.max_load > 0.0 {
                self.model.peak_pressure(e.max_load)
            } else {
                0.0
            },
            film_min: e.film_min,
            ..LevelOutputs::default()
        };
        let Some(slow) = &self.slow else {
            return Ok(());
        };
        if let Some(w) = &slow.wear {
            out.wear_max = aux[w.a0..w.a0 + 2 * w.n]
                .iter()
                .fold(0.0, |a: f64, &b| a.max(b));
        }
        if let Some(tp) = &slow.thermal {
            let l = tp.model.losses(m.omega, &e.wrench, &sums);
            tp.model
                .advance(m.omega, &l, t, &mut aux[tp.a0..tp.a0 + THERMAL_SLOTS]);
            out.power_loss = l.total();
            out.torque = if m.omega != 0.0 {
                -l.total() / m.omega
            } else {
                0.0
            };
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::presets::preset;

    /// The wear closure's semi-axis (the kept coefficient times one `Q^(1/3)` per ball) is
    /// each contact's own `semi_axes`, bit for bit, from zero and negative loads to heavy.
    #[test]
    fn kept_semi_axis_is_the_contacts_own() {
        let b = preset("6012").unwrap().build().unwrap();
        for race in [Race::Inner, Race::Outer] {
            let c = PointContact::ball_race(&b, 0.0, race);
            let ca = c.semi_axis_coefficients().0;
            for q in [-1.0, 0.0, 1e-9, 0.1, 3.7, 123.456, 2.5e3, 1e5] {
                let kept = ca * f64::max(q, 0.0).cbrt();
                assert_eq!(kept.to_bits(), c.semi_axes(q).0.to_bits(), "{race:?} {q}");
            }
        }
    }

    fn outputs(l: &mut RingLevel, m: &Motion, x: &[f64]) -> Vec<u64> {
        let mut out = LevelOutputs::default();
        l.outputs(Point::new(0.1, m, x, &mut []), &mut out).unwrap();
        let mut v = vec![
            out.torque,
            out.cage_omega,
            out.balls_loaded,
            out.max_load,
            out.max_pressure,
            out.film_min,
        ];
        v.extend(out.wrench);
        v.extend(out.k.iter().flatten());
        v.extend(out.c.iter().flatten());
        v.iter().map(|x| x.to_bits()).collect()
    }

    /// One `wrenches` call over many points gives, at each, the wrench of the level's own
    /// right-hand side there and of its full outputs, bit for bit (2 and 5 ring DOFs; free,
    /// loaded and contacts within the damping ramp; states rows wider than the level's).
    #[test]
    fn wrenches_are_each_points_right_hand_side_wrench() {
        for (name, dof) in [("6205", RingDof::Two), ("7008ce", RingDof::Five)] {
            let b = preset(name).unwrap().build().unwrap();
            let mut l = RingLevel::new(&b, dof, 3000.0);
            let n = 40;
            let stride = 3;
            let ms: Vec<Motion> = (0..n)
                .map(|k| {
                    let a = k as f64 * 0.37;
                    // Every fourth point centred: free.
                    let r = if k % 4 == 0 { 0.0 } else { 1.0 };
                    Motion {
                        q: [
                            r * 1.5e-5 * a.cos(),
                            r * (-1.5e-5 * a.sin() - 1e-6),
                            if dof == RingDof::Five {
                                r * 1e-5 * a.cos()
                            } else {
                                0.0
                            },
                            if dof == RingDof::Five {
                                r * 4e-5 * a.sin()
                            } else {
                                0.0
                            },
                            0.0,
                        ],
                        v: [0.02 * a.sin(), -0.03, 0.01, 0.2, -0.1],
                        omega: 100.0 + 10.0 * k as f64,
                    }
                })
                .collect();
            let xs: Vec<f64> = (0..n * stride).map(|i| 0.11 * i as f64).collect();
            let ts: Vec<f64> = (0..n).map(|k| 1e-4 * k as f64).collect();
            let mut out = vec![[0.0; 5]; n];
            let mut dx = [0.0; 1];
            let p = Points {
                t: &ts,
                m: &ms,
                x: &xs,
                stride,
            };
            l.wrenches(p, &mut dx, &mut out).unwrap();
            let mut loaded = 0;
            for k in 0..n {
                let x = &xs[k * stride..k * stride + 1];
                let mut w = [0.0; 5];
                l.rhs(Point::new(ts[k], &ms[k], x, &mut []), &mut dx, Some(&mut w))
                    .unwrap();
                assert_eq!(w.map(f64::to_bits), out[k].map(f64::to_bits), "{name} {k}");
                let full = outputs(&mut l, &ms[k], x);
                assert_eq!(&full[6..11], &out[k].map(f64::to_bits)[..], "{name} {k}");
                loaded += (out[k][1] != 0.0) as usize;
            }
            assert!(
                loaded > n / 2 && loaded < n,
                "{name}: {loaded} of {n} loaded"
            );
        }
    }

    /// The level's Jacobian puts the model's derivatives where the component reads them:
    /// `wm` (wrench by q, then by v) and `wx` (wrench by the cage angle, state 0) match
    /// central differences of the level's own right-hand-side wrench (1e-5 of each
    /// column's scale), the rates' rows are zero; a scene with a film or a profile says
    /// `false` (the integrator differences).
    #[test]
    fn jacobian_matches_differences_of_the_right_hand_side() {
        for (name, dof, q) in [
            ("6205", RingDof::Two, [2e-6, -1.2e-5, 0.0, 0.0, 0.0]),
            ("7008ce", RingDof::Five, [3e-6, -6e-6, 1.4e-5, 5e-5, -8e-5]),
        ] {
            let b = preset(name).unwrap().build().unwrap();
            let mut l = RingLevel::new(&b, dof, 3000.0);
            let m = Motion {
                q,
                v: [0.02, -0.03, 0.01, 0.2, -0.1],
                omega: 300.0,
            };
            let x = [0.7];
            let n = 1;
            let (mut jx, mut jm, mut wx, mut wm) = (
                vec![9.0; n * n],
                vec![9.0; n * 10],
                vec![9.0; 5 * n],
                vec![9.0; 50],
            );
            let j = Jacobians {
                jx: &mut jx,
                jm: &mut jm,
                wx: &mut wx,
                wm: &mut wm,
            };
            assert!(l.jacobian(Point::new(0.0, &m, &x, &mut []), j));
            assert!(jx.iter().chain(&jm).all(|&v| v == 0.0));
            let mut wrench = |m: &Motion, x: &[f64]| {
                let (mut dx, mut w) = ([0.0; 1], [0.0; 5]);
                l.rhs(Point::new(0.0, m, x, &mut []), &mut dx, Some(&mut w))
                    .unwrap();
                w
            };
            for col in 0..11 {
                let h = [
                    1e-11, 1e-11, 1e-11, 1e-9, 1e-9, 1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 1e-8,
                ][col];
                let (mut mp, mut mm, mut xp, mut xm) = (m, m, x, x);
                match col {
                    0..=4 => {
                        mp.q[col] += h;
                        mm.q[col] -= h;
                    }
                    5..=9 => {
                        mp.v[col - 5] += h;
                        mm.v[col - 5] -= h;
                    }
                    _ => {
                        xp[0] += h;
                        xm[0] -= h;
                    }
                }
                let (a, c) = (wrench(&mp, &xp), wrench(&mm, &xm));
                let fd: [f64; 5] = std::array::from_fn(|r| (a[r] - c[r]) / (2.0 * h));
                let an: [f64; 5] = std::array::from_fn(|r| {
                    if col < 10 {
                        wm[r * 10 + col]
                    } else {
                        wx[r * n]
                    }
                });
                let scale = fd.iter().chain(&an).fold(1e-30f64, |a, v| a.max(v.abs()));
                for r in 0..5 {
                    assert!(
                        (an[r] - fd[r]).abs() <= 1e-5 * scale,
                        "{name} row {r} col {col}: {} vs {}",
                        an[r],
                        fd[r]
                    );
                }
            }
        }
        let b = preset("6205").unwrap().build().unwrap();
        for effects in [
            "lubrication = { film = \"ehl\", lubricant = \"study2\" }",
            "defects = [{ race = \"outer\", angle_deg = 0.0, width_mm = 1.0, depth_um = 10.0 }]",
        ] {
            let e: Effects = toml::from_str(effects).unwrap();
            let mut l = RingLevel::with_effects(&b, RingDof::Two, 0.0, &e).unwrap();
            let m = Motion {
                q: [0.0, -1e-5, 0.0, 0.0, 0.0],
                v: [0.0; 5],
                omega: 100.0,
            };
            let x = vec![0.0; l.n_states()];
            let mut aux = vec![0.0; l.n_aux()];
            let ns = x.len();
            let (mut jx, mut jm, mut wx, mut wm) = (
                vec![0.0; ns * ns],
                vec![0.0; ns * 10],
                vec![0.0; 5 * ns],
                vec![0.0; 50],
            );
            let j = Jacobians {
                jx: &mut jx,
                jm: &mut jm,
                wx: &mut wx,
                wm: &mut wm,
            };
            assert!(
                !l.jacobian(Point::new(0.0, &m, &x, &mut aux), j),
                "{effects}"
            );
        }
    }

    /// The last stage's evaluation kept for the outputs at the same point gives them bit
    /// for bit; any other evaluation in between, or another point, evaluates again.
    #[test]
    fn outputs_kept_from_the_last_stage_are_the_same_bits() {
        let b = preset("6205").unwrap().build().unwrap();
        for dof in [RingDof::Two, RingDof::Five] {
            let mut l = RingLevel::new(&b, dof, 3000.0);
            let m = Motion {
                q: [3e-6, -2.1e-5, 1e-7, 2e-5, -1e-5],
                v: [1e-3, -2e-3, 1e-4, 0.01, 0.02],
                omega: 183.259571,
            };
            let x = [0.37];
            let fresh = outputs(&mut RingLevel::new(&b, dof, 3000.0), &m, &x);
            let (mut dx, mut w, mut w_rhs) = ([0.0], [0.0; 5], [0.0; 5]);
            l.rhs(Point::new(0.2, &m, &x, &mut []), &mut dx, Some(&mut w_rhs))
                .unwrap();
            l.rhs_at_end(Point::new(0.3, &m, &x, &mut []), &mut dx, Some(&mut w))
                .unwrap();
            assert_eq!(w.map(f64::to_bits), w_rhs.map(f64::to_bits), "same wrench");
            assert!(l.kept.is_some());
            assert_eq!(outputs(&mut l, &m, &x), fresh, "kept");
            // Another point: evaluated again.
            let x2 = [0.38];
            l.rhs_at_end(Point::new(0.3, &m, &x, &mut []), &mut dx, Some(&mut w))
                .unwrap();
            let fresh2 = outputs(&mut RingLevel::new(&b, dof, 3000.0), &m, &x2);
            assert_eq!(outputs(&mut l, &m, &x2), fresh2);
            // An evaluation in between forgets it.
            l.rhs_at_end(Point::new(0.3, &m, &x, &mut []), &mut dx, Some(&mut w))
                .unwrap();
            l.rhs(Point::new(0.3, &m, &x2, &mut []), &mut dx, Some(&mut w))
                .unwrap();
            assert!(l.kept.is_none());
            assert_eq!(outputs(&mut l, &m, &x), fresh);
        }
    }
}
