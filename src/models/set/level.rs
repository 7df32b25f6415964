//! A set as one level ([`LevelModel`]): an assembly of rows, each a level of its own
//! (built by the level's own constructor for the row's bearing), each seeing the shaft's
//! motion at its own axial position, their forces summed at the set's reference point
//! (module docs of [`super`]: `q_r = T A_r q`, `F = sum A_r^T T F_r`,
//! `K = sum A_r^T T K_r T A_r`, the same for the damping `C`).
//!
//! The preload is the set module's ([`Set`]): each row's axial displacement carries its
//! offset; with a constant-force spring, the sliding rows' common shift `u` is solved at
//! every evaluation (`sum_r P_r(u) = F_s + k_s u`, Newton with a difference slope, its
//! warm start in the level's memory) and condensed out of `K` as in [`Set`]. The spring
//! is taken as quasi-static (its shift's rate does not enter the rows' velocities).
//!
//! The per-row outputs ([`LevelModel::rows`]) are the rows' own forces and load counts;
//! the contact angle is the load-weighted mean inner contact angle of the row's balls at
//! the row's displacement from the quasi-static ball equilibrium (the set module's row
//! model), or the nominal angle of a roller row.
//!
//! With `[effects] thermal` (the only effect a set takes; level ring, 5 DOF, ball rows),
//! each row's ring level runs the single bearing's thermal network (`crate::models::thermal`)
//! fed by its own losses, its own growth off: its block of memory is the row's only memory
//! ([`row_thermal_blocks`]). After the outputs of a communication point, a row whose
//! network's inner-ring, outer-ring or ball temperature has moved more than [`REFORM_K`]
//! since the row was formed is formed again at those temperatures by the path of
//! temperatures given by hand ([`super::preload`]: the hot bearing's clearance and free
//! contact angle, the preload offset moved): its ring level and its contact-angle model are
//! rebuilt (that step allocates; the integrator's sub-steps never re-form), the network's
//! memory kept. [`SetLevel::set_row_temperatures`] is that path by hand.

#![allow(clippy::needless_range_loop)] // the index loops read as the matrix formulas

use super::preload::{row_at, RingTemperatures};
use super::row::RowModel;
use super::{Set, SetSpec};
use crate::error::{Error, Result};
use crate::geometry::element::Element;
use crate::geometry::Bearing;
use crate::models::effects::Effects;
use crate::models::ring::level::{RingLevel, SlowLayout};
use crate::models::ring::RingDof;
use crate::models::thermal::{BALLS, INNER, OIL, OUTER, THERMAL_SLOTS};
use crate::models::LevelArgs;
use crate::seam::{LevelModel, LevelOutputs, Motion, Point, RowOutputs};

/// A level's constructor (the registry's signature).
pub type RowBuild = fn(&LevelArgs) -> Result<Box<dyn LevelModel>>;

/// One row of the assembly.
#[derive(Debug)]
struct Slot {
    /// Axial position, m.
    z: f64,
    /// `±1`.
    o: f64,
    /// Preload offset of the row's own axial displacement, m.
    offset: f64,
    /// The row's outer ring slides on the preload spring.
    floating: bool,
    level: Box<dyn LevelModel>,
    /// The row's states and memory in the set's.
    x0: usize,
    nx: usize,
    a0: usize,
    na: usize,
    /// For the contact angle (ball rows).
    qs: Option<RowModel>,
    /// Element diameter, m (the angle tolerance of a row without its own scales).
    d: f64,
    nominal_angle: f64,
}

impl Slot {
    /// `T A_r` applied to `q` (and to velocities).
    fn local(&self, q: &[f64; 5]) -> [f64; 5] {
        let o = self.o;
        [
            q[0] + self.z * q[4],
            q[1] - self.z * q[3],
            o * q[2],
            o * q[3],
            o * q[4],
        ]
    }

    /// The row's motion for shaft motion `m` and spring shift `u`.
    fn motion(&self, m: &Motion, u: f64) -> Motion {
        let mut q = self.local(&m.q);
        q[2] += self.offset - if self.floating { u } else { 0.0 };
        Motion {
            q,
            v: self.local(&m.v),
            omega: m.omega,
        }
    }

    /// `(T A_r)^T f`: a local force at the reference point.
    fn global(&self, f: &[f64; 5]) -> [f64; 5] {
        let o = self.o;
        [
            f[0],
            f[1],
            o * f[2],
            o * f[3] - self.z * f[1],
            o * f[4] + self.z * f[0],
        ]
    }

    /// The matrix `T A_r`.
    fn map(&self) -> [[f64; 5]; 5] {
        let (o, z) = (self.o, self.z);
        [
            [1.0, 0.0, 0.0, 0.0, z],
            [0.0, 1.0, 0.0, -z, 0.0],
            [0.0, 0.0, o, 0.0, 0.0],
            [0.0, 0.0, 0.0, o, 0.0],
            [0.0, 0.0, 0.0, 0.0, o],
        ]
    }
}

/// `M^T A M` added into `out`.
fn add_congruent(out: &mut [[f64; 5]; 5], m: &[[f64; 5]; 5], a: &[[f64; 5]; 5]) {
    for i in 0..5 {
        for j in 0..5 {
            let mut s = 0.0;
            for r in 0..5 {
                if m[r][i] == 0.0 {
                    continue;
                }
                for c in 0..5 {
                    s += m[r][i] * a[r][c] * m[c][j];
                }
            }
            out[i][j] += s;
        }
    }
}

/// Kelvin a row's network may move from the temperatures its row was formed at before the
/// set forms the row again (module docs: at most once per communication point).
pub const REFORM_K: f64 = 0.01;

/// A ball row of a set with the thermal network: its bearing and offset as assembled, where
/// its network's block sits in its memory and the temperatures it is formed at.
#[derive(Debug)]
struct Formed {
    bearing: Bearing,
    offset: f64,
    block: usize,
    at: RingTemperatures,
}

/// The rows' thermal networks (module docs).
#[derive(Debug)]
struct Thermal {
    /// The rows' effects: the thermal network alone, its own growth off.
    effects: Effects,
    damping: f64,
    /// Ambient and initial temperature, °C.
    ambient: f64,
    /// The network's temperatures move the rows (`growth_factor` 1) or not (0).
    growth: bool,
    rows: Vec<Formed>,
}

/// The temperatures of a row's rings and balls from its network's block (rises over the
/// ambient `ambient`, °C).
fn network_temperatures(block: &[f64], ambient: f64) -> RingTemperatures {
    RingTemperatures {
        inner_c: ambient + block[INNER],
        outer_c: ambient + block[OUTER],
        ball_c: Some(ambient + block[BALLS]),
    }
}

/// The largest difference of two sets of temperatures, K.
fn moved(a: &RingTemperatures, b: &RingTemperatures) -> f64 {
    let ball = |t: &RingTemperatures| t.ball_c.unwrap_or(0.5 * (t.inner_c + t.outer_c));
    (a.inner_c - b.inner_c)
        .abs()
        .max((a.outer_c - b.outer_c).abs())
        .max((ball(a) - ball(b)).abs())
}

/// The rows' thermal networks the scene's effects ask for: the thermal effect alone (any
/// other effect belongs to one bearing), its own growth off in the rows (the set moves
/// the rows by their temperatures instead).
fn thermal_of(args: &LevelArgs) -> Result<Option<Thermal>> {
    let Some(t) = &args.effects.thermal else {
        return Ok(None);
    };
    let mut rest = args.effects.clone();
    rest.thermal = None;
    if !rest.is_off() {
        return Err(Error::invalid(
            "effects",
            "on with a [set] beside the thermal network",
            "the thermal network alone: defects, waviness, films and wear belong to one bearing",
        ));
    }
    if t.growth_factor != 0.0 && t.growth_factor != 1.0 {
        return Err(Error::invalid(
            "effects.thermal.growth_factor",
            t.growth_factor,
            "1 (the rings' growth moves the rows' preload) or 0 (off) with a [set]",
        ));
    }
    let mut own = t.clone();
    own.growth_factor = 0.0;
    Ok(Some(Thermal {
        effects: Effects {
            thermal: Some(own),
            ..Effects::default()
        },
        damping: args.contact_damping,
        ambient: t.ambient_c,
        growth: t.growth_factor != 0.0,
        rows: Vec::new(),
    }))
}

/// Form row `r` at temperatures `t` (module docs): everything is built before anything
/// changes, so a refusal leaves the row as it was.
fn form(
    r: &mut Slot,
    f: &mut Formed,
    effects: &Effects,
    damping: f64,
    t: RingTemperatures,
    i: usize,
) -> Result<()> {
    let (hot, d_off) = row_at(&f.bearing, &t, i)?;
    let level = RingLevel::with_effects(&hot, RingDof::Five, damping, effects)?;
    let qs = RowModel::new(&hot, r.z, r.o as i32)?;
    r.level = Box::new(level);
    r.qs = Some(qs);
    r.offset = f.offset + d_off;
    r.nominal_angle = hot.alpha0;
    f.at = t;
    Ok(())
}

/// The set as a level (module docs).
#[derive(Debug)]
pub struct SetLevel {
    rows: Vec<Slot>,
    /// `(stiffness N/m, force N)` of the preload spring.
    spring: Option<(f64, f64)>,
    /// The spring's shift's warm start in the memory (after the rows').
    u_slot: usize,
    n_x: usize,
    n_aux: usize,
    /// Rates scratch for the spring's solve.
    dx: Vec<f64>,
    /// Per-row outputs of the last `outputs`.
    report: Vec<RowOutputs>,
    /// Per-row displacement limits, for the spring's trial shifts (a quarter of the
    /// smallest ball diameter), m.
    max_du: f64,
    /// The rows' thermal networks (`[effects] thermal`), None without.
    thermal: Option<Thermal>,
}

/// Build the set's level: every row by `build` (the level's own constructor) for the
/// row's bearing with `args`' other options, the preload offsets from the set module.
pub fn build(args: &LevelArgs, spec: &SetSpec, build: RowBuild) -> Result<Box<dyn LevelModel>> {
    Ok(Box::new(SetLevel::new(args, spec, build)?))
}

impl SetLevel {
    /// See [`build`].
    pub fn new(args: &LevelArgs, spec: &SetSpec, build: RowBuild) -> Result<Self> {
        let set = Set::new(spec)?;
        let offsets = set.row_offsets();
        let mut rows = Vec::with_capacity(spec.rows.len());
        let (mut x0, mut a0) = (0, 0);
        let mut thermal = thermal_of(args)?;
        for (i, (r, &(offset, floating))) in spec.rows.iter().zip(&offsets).enumerate() {
            let level = build(&LevelArgs {
                bearing: &r.bearing,
                effects: thermal.as_ref().map_or(args.effects, |t| &t.effects),
                ..*args
            })?;
            let (nx, na) = (level.n_states(), level.n_aux());
            if let Some(th) = &mut thermal {
                let field = || format!("set.row[{i}].bearing");
                if !matches!(r.bearing.element, Element::Ball(_)) || args.ring_dof != 5 {
                    return Err(Error::invalid(
                        field(),
                        &r.bearing.name,
                        "a ball bearing at level ring with ring_dof = 5 (the thermal network \
                         of a set runs on ball rows of the 5-DOF ring level)",
                    ));
                }
                // The network's block is the row's only memory ([`row_thermal_blocks`]).
                let block = SlowLayout::of(&th.effects, &r.bearing)?
                    .thermal
                    .filter(|&b| b == 0 && na == THERMAL_SLOTS)
                    .ok_or_else(|| {
                        Error::invalid(
                            field(),
                            &r.bearing.name,
                            "a row whose level runs the thermal network (level ring)",
                        )
                    })?;
                th.rows.push(Formed {
                    bearing: r.bearing.clone(),
                    offset,
                    block,
                    at: RingTemperatures::default(),
                });
            }
            let qs = match r.bearing.element {
                Element::Ball(_) => Some(RowModel::new(&r.bearing, r.position, r.orientation)?),
                Element::Roller(_) => None,
            };
            rows.push(Slot {
                z: r.position,
                o: r.orientation as f64,
                offset,
                floating,
                level,
                x0,
                nx,
                a0,
                na,
                qs,
                d: r.bearing.d,
                nominal_angle: r.bearing.alpha0,
            });
            x0 += nx;
            a0 += na;
        }
        let spring = set.spring();
        let max_du = spec
            .rows
            .iter()
            .map(|r| 0.25 * r.bearing.d)
            .fold(f64::INFINITY, f64::min);
        Ok(SetLevel {
            report: vec![RowOutputs::default(); rows.len()],
            rows,
            spring,
            u_slot: a0,
            n_x: x0,
            n_aux: a0 + usize::from(spring.is_some()),
            dx: vec![0.0; x0],
            max_du,
            thermal,
        })
    }

    /// The temperatures of each row's network, `[inner ring, outer ring, balls, oil]` °C, in
    /// the memory `aux` (the component state's); `None` without the thermal network.
    pub fn row_temperatures(&self, aux: &[f64]) -> Option<Vec<[f64; 4]>> {
        let th = self.thermal.as_ref()?;
        Some(
            self.rows
                .iter()
                .zip(&th.rows)
                .map(|(r, f)| {
                    let b = &aux[r.a0 + f.block..r.a0 + f.block + 4];
                    [INNER, OUTER, BALLS, OIL].map(|k| th.ambient + b[k])
                })
                .collect(),
        )
    }

    /// The temperatures each row is formed at (its clearance, free contact angle and
    /// preload offset, [`super::preload`]); `None` without the thermal network.
    pub fn formed_temperatures(&self) -> Option<Vec<RingTemperatures>> {
        Some(self.thermal.as_ref()?.rows.iter().map(|f| f.at).collect())
    }

    /// Each row's preload offset now, m (the assembled one plus the rings' growth's).
    pub fn row_offsets(&self) -> Vec<f64> {
        self.rows.iter().map(|r| r.offset).collect()
    }

    /// Form row `i` at temperatures `t` by hand (the path the network's temperatures take,
    /// [`super::preload`]): its bearing with the clearance the rings' growth leaves, its
    /// level and contact-angle model rebuilt, its preload offset moved. Only a set with the
    /// thermal network has its rows' assembled state; a refused call changes nothing.
    pub fn set_row_temperatures(&mut self, i: usize, t: RingTemperatures) -> Result<()> {
        t.validate()?;
        let Some(th) = &mut self.thermal else {
            return Err(Error::invalid(
                "set.temperatures",
                "given to a set without [effects] thermal",
                "a set at level ring with [effects] thermal",
            ));
        };
        let (Some(r), Some(f)) = (self.rows.get_mut(i), th.rows.get_mut(i)) else {
            return Err(Error::invalid("set.row", i, "a row of the set"));
        };
        form(r, f, &th.effects, th.damping, t, i)
    }

    /// Form again every row whose network has moved more than [`REFORM_K`] from the
    /// temperatures it is formed at (module docs).
    fn follow_networks(&mut self, aux: &[f64]) -> Result<()> {
        let Some(th) = &mut self.thermal else {
            return Ok(());
        };
        if !th.growth {
            return Ok(());
        }
        for (i, (r, f)) in self.rows.iter_mut().zip(&mut th.rows).enumerate() {
            let t = network_temperatures(&aux[r.a0 + f.block..], th.ambient);
            if moved(&t, &f.at) > REFORM_K {
                form(r, f, &th.effects, th.damping, t, i)?;
            }
        }
        Ok(())
    }

    /// The sliding rows' thrust `sum P_r` at spring shift `u` (rates into the scratch).
    fn spring_thrust(
        &mut self,
        t: f64,
        m: &Motion,
        x: &[f64],
        aux: &mut [f64],
        u: f64,
    ) -> Result<f64> {
        let mut p = 0.0;
        for r in self.rows.iter_mut().filter(|r| r.floating) {
            let mr = r.motion(m, u);
            let mut w = [0.0; 5];
            r.level.rhs(
                Point::new(t, &mr, &x[r.x0..r.x0 + r.nx], &mut aux[r.a0..r.a0 + r.na]),
                &mut self.dx[r.x0..r.x0 + r.nx],
                Some(&mut w),
            )?;
            p -= w[2];
        }
        Ok(p)
    }

    /// The spring's shift at shaft motion `m` (module docs), from the warm start in `aux`.
    fn solve_spring(&mut self, t: f64, m: &Motion, x: &[f64], aux: &mut [f64]) -> Result<f64> {
        let Some((ks, fs)) = self.spring else {
            return Ok(0.0);
        };
        let mut u = aux[self.u_slot];
        let delta = 1e-10;
        let mut last = f64::NAN;
        for _ in 0..60 {
            let p = self.spring_thrust(t, m, x, aux, u)?;
            let h = p - (fs + ks * u);
            last = h;
            if h.abs() <= 1e-10 * (fs + p.abs()) {
                aux[self.u_slot] = u;
                return Ok(u);
            }
            let p1 = self.spring_thrust(t, m, x, aux, u + delta)?;
            // dh/du = dP/du - k_s < 0 (the thrust falls as the rows slide away).
            let dh = (p1 - p) / delta - ks;
            let du = if dh < 0.0 { -h / dh } else { f64::NAN };
            let du = if du.is_finite() {
                du.clamp(-self.max_du, self.max_du)
            } else {
                // No slope (a row off its contacts): step toward the balance.
                (h / ks).clamp(-self.max_du, self.max_du)
            };
            u += du;
            if du.abs() <= 1e-15 {
                aux[self.u_slot] = u;
                return Ok(u);
            }
        }
        Err(Error::NotConverged {
            what: "preload spring's shift in the set",
            iterations: 60,
            residual: last,
        })
    }
}

impl LevelModel for SetLevel {
    fn n_states(&self) -> usize {
        self.n_x
    }
    fn n_aux(&self) -> usize {
        self.n_aux
    }
    fn rows(&self) -> &[RowOutputs] {
        &self.report
    }
    fn state_atol(&self, atol_m: f64, atol: &mut [f64]) -> bool {
        for r in &self.rows {
            let s = &mut atol[r.x0..r.x0 + r.nx];
            if !r.level.state_atol(atol_m, s) {
                // The component's own default for a level without scales: angles.
                s.fill(atol_m / (0.5 * r.d));
            }
        }
        true
    }
    fn states_are_quadrature(&self) -> bool {
        self.rows.iter().all(|r| r.level.states_are_quadrature())
    }
    fn rhs_time_invariant(&self) -> bool {
        self.spring.is_none() && self.rows.iter().all(|r| r.level.rhs_time_invariant())
    }
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        Some(self)
    }
    fn init(&mut self, m: &Motion, x: &mut [f64], aux: &mut [f64]) -> Result<()> {
        aux.fill(0.0);
        // The networks start at the ambient: the rows run there from the start.
        self.follow_networks(aux)?;
        for r in &mut self.rows {
            let mr = r.motion(m, 0.0);
            r.level
                .init(&mr, &mut x[r.x0..r.x0 + r.nx], &mut aux[r.a0..r.a0 + r.na])?;
        }
        Ok(())
    }
    fn rhs(&mut self, p: Point<'_>, dx: &mut [f64], wrench: Option<&mut [f64; 5]>) -> Result<()> {
        let Point { t, m, x, aux } = p;
        let u = self.solve_spring(t, m, x, aux)?;
        let mut sum = [0.0; 5];
        let want = wrench.is_some();
        for r in &mut self.rows {
            let mr = r.motion(m, u);
            let mut w = [0.0; 5];
            r.level.rhs(
                Point::new(t, &mr, &x[r.x0..r.x0 + r.nx], &mut aux[r.a0..r.a0 + r.na]),
                &mut dx[r.x0..r.x0 + r.nx],
                want.then_some(&mut w),
            )?;
            if want {
                let g = r.global(&w);
                for i in 0..5 {
                    sum[i] += g[i];
                }
            }
        }
        if let Some(w) = wrench {
            *w = sum;
        }
        Ok(())
    }
    fn outputs(&mut self, p: Point<'_>, out: &mut LevelOutputs) -> Result<()> {
        let Point { t, m, x, aux } = p;
        let u = self.solve_spring(t, m, x, aux)?;
        let mut o = LevelOutputs::default();
        let (mut b, mut c, mut kzz) = ([0.0; 5], [0.0; 5], 0.0);
        let mut film = f64::INFINITY;
        let n = self.rows.len() as f64;
        for (r, rep) in self.rows.iter_mut().zip(&mut self.report) {
            let mr = r.motion(m, u);
            let mut lo = LevelOutputs::default();
            r.level.outputs(
                Point::new(t, &mr, &x[r.x0..r.x0 + r.nx], &mut aux[r.a0..r.a0 + r.na]),
                &mut lo,
            )?;
            let g = r.global(&lo.wrench);
            let mm = r.map();
            for i in 0..5 {
                o.wrench[i] += g[i];
            }
            add_congruent(&mut o.k, &mm, &lo.k);
            add_congruent(&mut o.c, &mm, &lo.c);
            if r.floating {
                kzz += lo.k[2][2];
                for i in 0..5 {
                    for a in 0..5 {
                        b[i] += mm[a][i] * lo.k[a][2];
                        c[i] += lo.k[2][a] * mm[a][i];
                    }
                }
            }
            o.torque += lo.torque;
            o.cage_omega += lo.cage_omega / n;
            o.cage_slip += lo.cage_slip / n;
            o.balls_loaded += lo.balls_loaded;
            o.max_load = o.max_load.max(lo.max_load);
            o.max_pressure = o.max_pressure.max(lo.max_pressure);
            if lo.film_min > 0.0 {
                film = film.min(lo.film_min);
            }
            o.power_loss += lo.power_loss;
            o.wear_max = o.wear_max.max(lo.wear_max);
            let w = lo.wrench;
            let angle = match &mut r.qs {
                Some(qs) if lo.balls_loaded > 0.0 => {
                    qs.mean_inner_angle(mr.q, m.omega)?.unwrap_or(0.0)
                }
                Some(_) => 0.0,
                None => r.nominal_angle,
            };
            *rep = RowOutputs {
                force: [w[0], w[1], r.o * w[2], r.o * w[3], r.o * w[4]],
                local: w,
                contact_angle: angle,
                loaded: lo.balls_loaded,
                max_pressure: lo.max_pressure,
            };
        }
        if let Some((ks, _)) = self.spring {
            let d = kzz + ks;
            for i in 0..5 {
                for j in 0..5 {
                    o.k[i][j] -= b[i] * c[j] / d;
                }
            }
        }
        o.film_min = if film.is_finite() { film } else { 0.0 };
        *out = o;
        // The networks advanced in the rows' outputs: the rows follow their temperatures
        // from the next step on.
        self.follow_networks(aux)
    }
}

/// The thermal blocks of a set's rows in the component's memory `aux`, in row order, for a
/// caller that holds the memory but not the level (the run's summary): with `[effects]
/// thermal` every row's level keeps its network's block ([`THERMAL_SLOTS`] values, as
/// [`crate::models::thermal::ThermalModel::advance`] writes them) as its only memory, so
/// row `i`'s starts at `i THERMAL_SLOTS` ([`SetLevel::new`] refuses a row that would not).
pub fn row_thermal_blocks(aux: &[f64], rows: usize) -> Vec<&[f64]> {
    aux.chunks_exact(THERMAL_SLOTS).take(rows).collect()
}

/// The bearings of a set's rows, for a caller that rates them.
pub fn row_bearings(spec: &SetSpec) -> Vec<Bearing> {
    spec.rows.iter().map(|r| r.bearing.clone()).collect()
}
