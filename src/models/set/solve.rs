//! The set's evaluation (wrench and 5x5 stiffness at the reference point for a shaft
//! position, the spring's internal unknown solved inside), its load-driven equilibrium and
//! its report.

#![allow(clippy::needless_range_loop)] // the index loops read as the matrix formulas

use super::life::{system_life, weibull_slope};
use super::preload::RingTemperatures;
use super::row::{RowEval, RowModel, RowReport};
use super::{Preload, SetSpec};
use crate::error::{Error, Result};
use crate::geometry::element::Element;
use crate::geometry::Bearing;
use crate::models::quasi_static::Solution;
use crate::ratings::{self, LifeInputs};
use serde::Serialize;

/// A set ready to evaluate (module docs of [`super`]).
#[derive(Debug)]
pub struct Set {
    rows: Vec<RowModel>,
    /// `(stiffness N/m, force N)` of the preload spring on the rows facing `-z`.
    spring: Option<(f64, f64)>,
    /// The spring's shift `u` at the last evaluation (warm start), m.
    u: f64,
    /// Length scale for rotations in the solves, m.
    arm: f64,
    /// Force scale (the preload), N.
    scale: f64,
    /// Each row's bearing and preload offset as assembled (reference temperature).
    assembled: Vec<(Bearing, f64)>,
    /// The rings' temperatures the rows are built for.
    temperatures: RingTemperatures,
}

/// The set's answer at one shaft position.
#[derive(Debug, Clone, Serialize)]
pub struct SetEval {
    /// Forces and moments of the set on the shaft at the reference point, N and N m.
    pub force: [f64; 5],
    /// `K = -dF/dq` at the reference point, SI.
    pub stiffness: [[f64; 5]; 5],
    /// The preload spring's shift `u` (0 without a spring), m.
    pub spring_shift: f64,
}

/// A set at an equilibrium, with everything a report reads.
#[derive(Debug, Clone, Serialize)]
pub struct SetSolution {
    /// Shaft speed, rad/s.
    pub omega: f64,
    /// Shaft displacement at the reference point, m and rad.
    pub q: [f64; 5],
    /// Forces and moments of the set on the shaft at the reference point.
    pub force: [f64; 5],
    /// Stiffness at the reference point.
    pub stiffness: [[f64; 5]; 5],
    /// The preload spring's shift, m.
    pub spring_shift: f64,
    /// Per-row reports.
    pub rows: Vec<RowReport>,
    /// System life of the rows, millions of revolutions (`None`: no row loaded).
    pub life_mrev: Option<f64>,
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Solve `P(a) = target` for a nondecreasing `P` (with slope `dp`) from `a = 0`: bracket by
/// doubling, then Newton safeguarded by bisection. `what` names the input in a refusal.
fn solve_monotone(
    mut p: impl FnMut(f64) -> Result<(f64, f64)>,
    target: f64,
    what: &str,
    limit: f64,
) -> Result<f64> {
    let (mut lo, mut hi) = (0.0, 1e-7);
    loop {
        let ok = match p(hi) {
            Ok((v, _)) => v >= target,
            Err(Error::Invalid { .. }) => true,
            Err(e) => return Err(e),
        };
        if ok {
            break;
        }
        lo = hi;
        hi *= 2.0;
        if hi > limit {
            return Err(Error::invalid(
                what,
                format!("{target:.6} N"),
                "a preload these rows can carry (no axial displacement within the geometry reaches it)",
            ));
        }
    }
    let mut a = 0.5 * (lo + hi);
    for _ in 0..200 {
        let (v, d) = match p(a) {
            Ok(x) => x,
            Err(Error::Invalid { .. }) => {
                hi = a;
                a = 0.5 * (lo + hi);
                continue;
            }
            Err(e) => return Err(e),
        };
        if v < target {
            lo = a;
        } else {
            hi = a;
        }
        if (v - target).abs() <= 1e-12 * target {
            return Ok(a);
        }
        let mut next = if d > 0.0 {
            a - (v - target) / d
        } else {
            f64::NAN
        };
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - a).abs() <= 1e-15 * a.abs().max(1e-9) || hi - lo <= 1e-16 {
            return Ok(next);
        }
        a = next;
    }
    Ok(a)
}

/// Damped Newton on `F(q) + load = 0` over 5 shaft unknowns with the exact stiffness,
/// regularised where a direction has none ([`crate::solver::newton::solve_regularised`]),
/// a step cap `max_step` (m, scaled units) and a back-tracking line search on the scaled
/// residual; a trial the geometry refuses is halved. `eval(q)` returns `(F, K)`; the scale
/// of rotations is `arm` (m). `what` names the solve in a failure. Shared with the shaft.
pub(crate) fn newton5(
    mut eval: impl FnMut(&[f64; 5]) -> Result<([f64; 5], [[f64; 5]; 5])>,
    load: &[f64; 5],
    q0: [f64; 5],
    arm: f64,
    max_step: f64,
    force_scale: f64,
    what: &'static str,
) -> Result<[f64; 5]> {
    let t = [1.0, 1.0, 1.0, arm, arm];
    let res = |f: &[f64; 5]| -> [f64; 5] { std::array::from_fn(|i| (f[i] + load[i]) / t[i]) };
    let ls: [f64; 5] = std::array::from_fn(|i| load[i] / t[i]);
    let tol = 1e-10 * (norm(&ls) + force_scale) + 1e-9;
    let mut q = q0;
    let (mut f, mut k) = eval(&q)?;
    let mut r = res(&f);
    let mut nr = norm(&r);
    for it in 0..200 {
        if nr <= tol {
            return Ok(q);
        }
        let ks: [[f64; 5]; 5] =
            std::array::from_fn(|i| std::array::from_fn(|j| k[i][j] / (t[i] * t[j])));
        let Some(mut dx) = crate::solver::newton::solve_regularised(&ks, &r, 1e-12, 8) else {
            return Err(Error::NotConverged {
                what,
                iterations: it,
                residual: nr,
            });
        };
        let big = dx.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if big > max_step {
            dx.iter_mut().for_each(|v| *v *= max_step / big);
        }
        let mut step = 1.0;
        let mut accepted = false;
        for _ in 0..40 {
            let trial: [f64; 5] = std::array::from_fn(|i| q[i] + step * dx[i] / t[i]);
            match eval(&trial) {
                Ok((ft, kt)) => {
                    let rt = res(&ft);
                    let nt = norm(&rt);
                    if nt.is_finite() && nt <= (1.0 - 1e-4 * step) * nr {
                        q = trial;
                        f = ft;
                        k = kt;
                        r = rt;
                        nr = nt;
                        accepted = true;
                        break;
                    }
                }
                Err(Error::Invalid { .. }) | Err(Error::NotConverged { .. }) => {}
                Err(e) => return Err(e),
            }
            step *= 0.5;
        }
        let _ = f;
        if !accepted {
            return Err(Error::NotConverged {
                what,
                iterations: it,
                residual: nr,
            });
        }
    }
    if nr <= tol {
        Ok(q)
    } else {
        Err(Error::NotConverged {
            what,
            iterations: 200,
            residual: nr,
        })
    }
}

impl Set {
    /// Build the rows and set the preload (module docs of [`super`]).
    pub fn new(spec: &SetSpec) -> Result<Set> {
        Set::build(spec, true)
    }

    /// A set that needs no axial support: its place on a shaft floats axially (the shaft
    /// holds its axial force at zero, [`crate::models::shaft`]).
    pub fn new_floating(spec: &SetSpec) -> Result<Set> {
        Set::build(spec, false)
    }

    fn build(spec: &SetSpec, axial: bool) -> Result<Set> {
        spec.validate_rows(axial)?;
        let mut rows = spec
            .rows
            .iter()
            .map(|r| RowModel::new(&r.bearing, r.position, r.orientation))
            .collect::<Result<Vec<_>>>()?;
        let arm = rows
            .iter()
            .map(|r| r.z.abs() + 0.5 * r.bearing.dm)
            .fold(0.0, f64::max);
        let mut spring = None;
        let force = match spec.preload {
            Preload::None | Preload::Class(_) => None,
            Preload::Offset(d) => {
                rows.iter_mut().for_each(|r| r.offset = 0.5 * d);
                None
            }
            Preload::Force(f) => Some(f),
            Preload::Spring { stiffness, force } => {
                spring = Some((stiffness, force));
                rows.iter_mut()
                    .filter(|r| r.o < 0.0)
                    .for_each(|r| r.floating = true);
                Some(force)
            }
        };
        if let Some(f) = force {
            for o in [1.0, -1.0] {
                let limit = rows
                    .iter()
                    .filter(|r| r.o == o)
                    .map(|r| r.bearing.d)
                    .fold(0.0, f64::max);
                let group: Vec<usize> = (0..rows.len()).filter(|&i| rows[i].o == o).collect();
                let a = solve_monotone(
                    |a| {
                        let (mut p, mut dp) = (0.0, 0.0);
                        for &i in &group {
                            let (pi, di) = rows[i].thrust(a, 0.0)?;
                            p += pi;
                            dp += di;
                        }
                        Ok((p, dp))
                    },
                    f,
                    "set.preload_n",
                    limit,
                )?;
                for &i in &group {
                    rows[i].offset = a;
                }
            }
        }
        let assembled = rows.iter().map(|r| (r.bearing.clone(), r.offset)).collect();
        let mut set = Set {
            rows,
            spring,
            u: 0.0,
            arm,
            scale: 1.0,
            assembled,
            temperatures: RingTemperatures::default(),
        };
        let (rows0, _) = set.eval_rows(&[0.0; 5], 0.0, false)?;
        set.scale = 1.0 + rows0.iter().map(|e| e.f_loc[2].abs()).sum::<f64>();
        Ok(set)
    }

    /// Each row's preload offset added to its own axial displacement (m) and whether its
    /// outer ring slides on the preload spring, in row order.
    pub fn row_offsets(&self) -> Vec<(f64, bool)> {
        self.rows.iter().map(|r| (r.offset, r.floating)).collect()
    }

    /// The preload spring `(stiffness N/m, force N)`, if the set has one.
    pub fn spring(&self) -> Option<(f64, f64)> {
        self.spring
    }

    /// Run the rows at ring temperatures `t` (module docs of [`super::preload`]): each ball
    /// row's clearance and free contact angle follow the rings' radial growth while its
    /// rings keep their assembled axial positions, so a rigid preload changes and a spring
    /// preload slides. The reference temperatures restore the set as assembled. A refused
    /// call changes nothing.
    pub fn set_ring_temperatures(&mut self, t: RingTemperatures) -> Result<()> {
        t.validate()?;
        if t == self.temperatures {
            return Ok(());
        }
        let mut rows = Vec::with_capacity(self.rows.len());
        for (i, (r, (b0, off0))) in self.rows.iter().zip(&self.assembled).enumerate() {
            let (b, d_off) = super::preload::row_at(b0, &t, i)?;
            let mut m = RowModel::new(&b, r.z, r.o as i32)?;
            m.offset = off0 + d_off;
            m.floating = r.floating;
            rows.push(m);
        }
        self.rows = rows;
        self.temperatures = t;
        Ok(())
    }

    /// The rings' temperatures the set runs at.
    pub fn ring_temperatures(&self) -> RingTemperatures {
        self.temperatures
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether the set has no rows (never: [`SetSpec::validate`] refuses it).
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Length scale for rotations (the farthest row's distance plus its pitch radius), m.
    pub fn arm(&self) -> f64 {
        self.arm
    }

    /// The rows' own displacements (before the spring's shift) for shaft position `q`.
    fn local(&self, i: usize, q: &[f64; 5], u: f64) -> [f64; 5] {
        let r = &self.rows[i];
        let mut l = r.to_local(q);
        l[2] += r.offset - if r.floating { u } else { 0.0 };
        l
    }

    /// Evaluate every row at `q` (solving the spring's shift), with per-element reports
    /// when `report`.
    fn eval_rows(&mut self, q: &[f64; 5], omega: f64, report: bool) -> Result<(Vec<RowEval>, f64)> {
        let mut u = 0.0;
        if let Some((ks, fs)) = self.spring {
            // h(u) = sum P_r(u) - (F_s + k_s u), decreasing and convex: Newton from the
            // warm start, halved when the geometry refuses a trial.
            let mut uu = self.u;
            let mut done = false;
            let mut last_h = f64::NAN;
            for _ in 0..100 {
                let (mut p, mut kzz) = (0.0, 0.0);
                let mut failed = false;
                for i in 0..self.rows.len() {
                    if !self.rows[i].floating {
                        continue;
                    }
                    let l = self.local(i, q, uu);
                    match self.rows[i].eval_local(l, omega, false) {
                        Ok(e) => {
                            p -= e.f_loc[2];
                            kzz += e.k_loc[2][2];
                        }
                        Err(Error::Invalid { .. }) => failed = true,
                        Err(e) => return Err(e),
                    }
                }
                if failed {
                    // Too far into the rows: step back halfway toward the last good point.
                    uu = 0.5 * (uu + self.u) + 1e-7;
                    continue;
                }
                let h = p - (fs + ks * uu);
                last_h = h;
                if h.abs() <= 1e-11 * (fs + p.abs()) {
                    done = true;
                    break;
                }
                let du = h / (kzz + ks);
                uu += du;
                if du.abs() <= 1e-16 {
                    done = true;
                    break;
                }
            }
            if !done {
                return Err(Error::NotConverged {
                    what: "preload spring's shift in the set",
                    iterations: 100,
                    residual: last_h,
                });
            }
            u = uu;
        }
        let mut out = Vec::with_capacity(self.rows.len());
        for i in 0..self.rows.len() {
            let l = self.local(i, q, u);
            out.push(self.rows[i].eval_local(l, omega, report)?);
        }
        Ok((out, u))
    }

    /// The set's forces on the shaft and its stiffness at the reference point for shaft
    /// position `q` (m, rad) at shaft speed `omega` (rad/s).
    pub fn evaluate(&mut self, q: &[f64; 5], omega: f64) -> Result<SetEval> {
        let (rows, u) = self.eval_rows(q, omega, false)?;
        Ok(self.assemble(&rows, u))
    }

    fn assemble(&mut self, rows: &[RowEval], u: f64) -> SetEval {
        self.u = u;
        let mut f = [0.0; 5];
        let mut k = [[0.0; 5]; 5];
        let (mut b, mut c, mut kzz) = ([0.0; 5], [0.0; 5], 0.0);
        for (r, e) in self.rows.iter().zip(rows) {
            let g = r.to_global(&e.f_loc);
            let m = r.map();
            for i in 0..5 {
                f[i] += g[i];
            }
            // K += M^T K_loc M.
            for i in 0..5 {
                for j in 0..5 {
                    let mut s = 0.0;
                    for a in 0..5 {
                        for bb in 0..5 {
                            s += m[a][i] * e.k_loc[a][bb] * m[bb][j];
                        }
                    }
                    k[i][j] += s;
                }
            }
            if r.floating {
                kzz += e.k_loc[2][2];
                for i in 0..5 {
                    for a in 0..5 {
                        b[i] += m[a][i] * e.k_loc[a][2];
                        c[i] += e.k_loc[2][a] * m[a][i];
                    }
                }
            }
        }
        if let Some((ks, _)) = self.spring {
            let d = kzz + ks;
            for i in 0..5 {
                for j in 0..5 {
                    k[i][j] -= b[i] * c[j] / d;
                }
            }
        }
        SetEval {
            force: f,
            stiffness: k,
            spring_shift: u,
        }
    }

    /// Force scale of the set (the preload at standstill, 1 N at least), N: for the
    /// solves' tolerances.
    pub fn force_scale(&self) -> f64 {
        self.scale
    }

    /// The shaft position at which the set balances the external `load` on the shaft at
    /// the reference point `(Fx, Fy, Fz, Mx, My)` (N, N m) at speed `omega`, and the report
    /// there.
    pub fn solve(&mut self, load: &[f64; 5], omega: f64) -> Result<SetSolution> {
        for (i, v) in load.iter().enumerate() {
            if !v.is_finite() {
                return Err(Error::invalid(format!("load[{i}]"), v, "a finite number"));
            }
        }
        if !omega.is_finite() {
            return Err(Error::invalid("omega", omega, "a finite number"));
        }
        let max_step = self.max_step();
        let scale = self.force_scale();
        let arm = self.arm;
        let q = newton5(
            |q| {
                let e = self.evaluate(q, omega)?;
                Ok((e.force, e.stiffness))
            },
            load,
            [0.0; 5],
            arm,
            max_step,
            scale,
            "set equilibrium",
        )?;
        self.report(&q, omega)
    }

    /// A cap on the Newton step of a solve, m (a quarter of the smallest groove-centre
    /// distance of the ball rows; 10 µm for roller rows).
    pub fn max_step(&self) -> f64 {
        self.rows
            .iter()
            .map(|r| match r.bearing.element {
                Element::Ball(_) => 0.25 * r.bearing.a(),
                Element::Roller(_) => 10e-6,
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Everything at shaft position `q` and speed `omega`: forces, stiffness, per-row loads,
    /// contact angles, lift-off, lives and the system life.
    pub fn report(&mut self, q: &[f64; 5], omega: f64) -> Result<SetSolution> {
        let (rows, u) = self.eval_rows(q, omega, true)?;
        let e = self.assemble(&rows, u);
        let speed_rpm = crate::units::rad_s_to_rpm(omega.abs());
        let mut reports = Vec::with_capacity(rows.len());
        for (r, ev) in self.rows.iter().zip(&rows) {
            reports.push(row_report(r, ev, omega, speed_rpm)?);
        }
        let life = system_life(
            &reports
                .iter()
                .map(|r| (r.life_mrev, r.weibull_slope))
                .collect::<Vec<_>>(),
        );
        Ok(SetSolution {
            omega,
            q: *q,
            force: e.force,
            stiffness: e.stiffness,
            spring_shift: u,
            rows: reports,
            life_mrev: life,
        })
    }
}

/// One row's report: loads in the shaft's frame, contact angles, lift-off and its ratings.
fn row_report(r: &RowModel, e: &RowEval, omega: f64, speed_rpm: f64) -> Result<RowReport> {
    let b = &r.bearing;
    // The row's forces at its own centre in the shaft's frame: `T f_loc`.
    let o = r.o;
    let f = e.f_loc;
    let force = [f[0], f[1], o * f[2], o * f[3], o * f[4]];
    let fr = f[0].hypot(f[1]);
    let fa = -f[2];
    let loaded = e.loads.iter().filter(|l| l[0] > 0.0).count();
    let (life, s0, peak) = match &b.element {
        Element::Ball(_) => {
            let sol = Solution {
                omega,
                load: f.map(|v| -v),
                q: e.q_loc,
                forces: f,
                stiffness: e.k_loc,
                psi: e.balls.iter().map(|x| x.psi).collect(),
                balls: e.balls.clone(),
                states: Vec::new(),
                iterations: 0,
                held: [false; 5],
                reaction: [0.0; 5],
            };
            let a = ratings::assess(
                b,
                &sol,
                &LifeInputs {
                    speed_rpm,
                    ..LifeInputs::default()
                },
            )?;
            (a.l10r_mrev, a.s0, a.peak_pressure)
        }
        Element::Roller(rb) => {
            let rr = ratings::roller::roller_ratings(rb)?;
            let p = ratings::roller::equivalent_dynamic_load(rb, fr, fa).0;
            let p0 = ratings::roller::equivalent_static_load(rb, fr, fa);
            let l = ratings::roller::l10_roller(rr.cr, p);
            (
                l.is_finite().then_some(l),
                (p0 > 0.0).then(|| rr.c0r / p0),
                e.peak_pressure,
            )
        }
    };
    Ok(RowReport {
        bearing: b.name.clone(),
        position: r.z,
        orientation: r.o as i32,
        displacement: e.q_loc,
        force,
        radial_load: fr,
        axial_load: fa,
        element_loads: e.loads.iter().map(|l| l[0]).collect(),
        contact_angles: match &b.element {
            Element::Ball(_) => e.balls.iter().map(|x| [x.alpha_i, x.alpha_o]).collect(),
            // Line contacts along the raceways: the cone's and the cup's angles (0 for a
            // cylindrical row), the rollers' own small tilt left out.
            Element::Roller(rb) => vec![[rb.alpha_cone, rb.alpha]; e.loads.len()],
        },
        loaded_elements: loaded,
        lifted_off: loaded == 0,
        axial_stiffness: e.k_loc[2][2],
        life_mrev: if loaded == 0 { None } else { life },
        weibull_slope: weibull_slope(b.element()),
        s0: if loaded == 0 { None } else { s0 },
        peak_pressure: peak,
        balls: e.balls.clone(),
    })
}
