//! The static start of a load-driven inner ring: its equilibrium under the initial loads.

use super::level::{LevelModel, LevelOutputs, Motion, Point};
use crate::error::{Error, Result};

/// The inner ring's static equilibrium under `loads` (external, on the ring) at speed
/// `omega`: damped Newton on `F(q) + load = 0` over the level's ring coordinates with the
/// level's stiffness, moments weighed as forces at the lever `lever` (m); directions with
/// no stiffness yet (inside a clearance, an unloaded tilt) are regularised. When the full
/// load fails from the centre, the load is applied in stages (continuation). Refuses with
/// the residual when it finds no equilibrium. `q0`: the start of every coordinate (the
/// held ones, outside `dofs`, keep it). Returns the displacement and the level's wrench
/// there (the held coordinates' reaction is `-(wrench + loads)`).
///
/// A level whose position states follow the ring ([`LevelModel::follow_ring`]: balls with
/// dynamic contacts) is evaluated with them moved to their rest at every trial
/// displacement (in a copy of `x`), and its stiffness is then the difference of those
/// evaluations (the balls moving with the ring, which the level's own stiffness, its
/// states held, does not give); the caller moves the states to the answer likewise.
#[allow(clippy::too_many_arguments)]
pub(super) fn static_start(
    level: &mut dyn LevelModel,
    dofs: &[usize],
    q0: [f64; 5],
    loads: &[f64; 5],
    omega: f64,
    lever: f64,
    x: &[f64],
    aux: &mut [f64],
) -> Result<([f64; 5], [f64; 5])> {
    let scale = loads
        .iter()
        .enumerate()
        .map(|(d, v)| if d < 3 { v.abs() } else { v.abs() / lever })
        .sum::<f64>()
        + 1.0;
    let mut xs = x.to_vec();
    let m0 = Motion {
        q: q0,
        v: [0.0; 5],
        omega,
    };
    let follow = level.follow_ring(&m0, &mut xs)?;
    let mut sys = StaticSystem {
        level,
        dofs,
        loads: [0.0; 5],
        omega,
        lever,
        x: xs,
        follow,
        aux,
        tol: 1e-9 * scale,
        out: LevelOutputs::default(),
        now: ([0.0; 5], [[0.0; 5]; 5]),
        next: ([0.0; 5], [[0.0; 5]; 5]),
        fresh: false,
    };
    let full = staged(&mut sys, q0, *loads, scale);
    let last = match full {
        Ok(q) => return Ok(q),
        Err(r) => r,
    };
    // No equilibrium under the whole load: the largest fraction of it (to 1/64) with one,
    // so that the refusal names the loads and a magnitude that can be met.
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..6 {
        let mid = 0.5 * (lo + hi);
        let part: [f64; 5] = std::array::from_fn(|d| mid * loads[d]);
        if staged(&mut sys, q0, part, scale).is_ok() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    // Light loads can fail where heavier ones in the same direction succeed (a contact
    // barely engaged): the smallest multiple of the loads (up to 2^20) with an
    // equilibrium, refined by bisection, bounds the range from above.
    let mut above = None;
    let mut m = 2.0;
    while m <= 1048576.0 {
        let part: [f64; 5] = std::array::from_fn(|d| m * loads[d]);
        if staged(&mut sys, q0, part, scale).is_ok() {
            let (mut lo, mut hi) = (0.5 * m, m);
            for _ in 0..6 {
                let mid = 0.5 * (lo + hi);
                let part: [f64; 5] = std::array::from_fn(|d| mid * loads[d]);
                if staged(&mut sys, q0, part, scale).is_ok() {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            above = Some(hi);
            break;
        }
        m *= 2.0;
    }
    Err(refusal(dofs, loads, lo, above, last))
}

/// The equilibrium under `loads` from `q0`: the whole load at once, else in 4 and then 16
/// equal stages (continuation); the displacement and the level's wrench there, or the last
/// residual when none converges.
type Staged = std::result::Result<([f64; 5], [f64; 5]), f64>;
fn staged(sys: &mut StaticSystem, q0: [f64; 5], loads: [f64; 5], scale: f64) -> Staged {
    let mut last = f64::INFINITY;
    for stages in [1usize, 4, 16] {
        let mut q = q0;
        let mut ok = true;
        for k in 1..=stages {
            let f = k as f64 / stages as f64;
            let part: [f64; 5] = std::array::from_fn(|d| f * loads[d]);
            match newton_static(sys, part, &mut q) {
                Ok(r) if r <= 1e-6 * scale => last = r,
                Ok(r) => {
                    last = r;
                    ok = false;
                    break;
                }
                Err(_) => {
                    ok = false;
                    break;
                }
            }
        }
        if ok {
            let wrench = sys.eval(&q).map_err(|_| last)?.0;
            return Ok((q, wrench));
        }
    }
    Err(last)
}

/// Scene names of the initial loads, in the order of the ring coordinates.
const LOAD_FIELDS: [(&str, &str); 5] = [
    ("inputs.initial.load.x", "N"),
    ("inputs.initial.load.y", "N"),
    ("inputs.initial.load.z", "N"),
    ("inputs.initial.load.mx", "N.m"),
    ("inputs.initial.load.my", "N.m"),
];

/// The static start's refusal: the initial loads the ring resolves, named with the
/// fraction `reached` of them under which an equilibrium was found (a range that can be
/// met), or, when none was, `model.start` with `"rest"`.
fn refusal(
    dofs: &[usize],
    loads: &[f64; 5],
    reached: f64,
    above: Option<f64>,
    residual: f64,
) -> Error {
    let on: Vec<usize> = dofs.iter().copied().filter(|&d| loads[d] != 0.0).collect();
    let why = format!(
        "no static equilibrium of the load-driven inner ring under the initial loads (residual {residual:.3e} N)"
    );
    if (reached <= 0.0 && above.is_none()) || on.is_empty() {
        return Error::invalid(
            "model.start",
            "equilibrium",
            format!(
                "\"rest\" (the inner ring starting at zero displacement): {why}, nor under 1/64 of them"
            ),
        );
    }
    let field = on
        .iter()
        .map(|&d| LOAD_FIELDS[d].0)
        .collect::<Vec<_>>()
        .join(", ");
    let value = on
        .iter()
        .map(|&d| format!("{:e}", loads[d]))
        .collect::<Vec<_>>()
        .join(", ");
    let force = on
        .iter()
        .filter(|&&d| d < 3)
        .map(|&d| loads[d] * loads[d])
        .sum::<f64>()
        .sqrt();
    let moment = on
        .iter()
        .filter(|&&d| d >= 3)
        .map(|&d| loads[d] * loads[d])
        .sum::<f64>()
        .sqrt();
    let range = |f: f64, op: &str| {
        let mut parts = Vec::new();
        if force > 0.0 {
            parts.push(format!("|load| {op} {:.4e} N", f * force));
        }
        if moment > 0.0 {
            parts.push(format!("|moment| {op} {:.4e} N.m", f * moment));
        }
        parts.join(" and ")
    };
    let mut ranges = Vec::new();
    let mut found = Vec::new();
    if reached > 0.0 {
        ranges.push(range(reached, "<="));
        found.push(format!("under {reached} of these loads"));
    }
    if let Some(a) = above {
        ranges.push(range(a, ">="));
        found.push(format!("under {a} times them"));
    }
    let limit = ranges.join(", or ");
    Error::invalid(
        field,
        value,
        format!(
            "loads in this direction the static start carries: {limit} (an equilibrium is found {}; {why}), or model.start = \"rest\"",
            found.join(" and ")
        ),
    )
}

/// Newton iterations from `q` towards `F(q) + loads = 0`, `sys` started afresh with these
/// loads; returns the final residual (forces in N, moments divided by the lever).
fn newton_static(sys: &mut StaticSystem, loads: [f64; 5], q: &mut [f64; 5]) -> Result<f64> {
    sys.loads = loads;
    sys.out = LevelOutputs::default();
    sys.now = ([0.0; 5], [[0.0; 5]; 5]);
    sys.next = ([0.0; 5], [[0.0; 5]; 5]);
    sys.fresh = false;
    // Scaled coordinates: translations in m, tilts times the lever.
    let opts = crate::solver::newton::Options {
        max_iterations: 100,
        max_halvings: 40,
        armijo: 0.0,
        scale: [1.0, 1.0, 1.0, sys.lever, sys.lever],
        dead_zone_bisections: 60,
        ..Default::default()
    };
    Ok(crate::solver::newton::solve(sys, q, &opts)?.check.norm)
}

/// `F(q) + loads = 0` over the level's ring coordinates `dofs` as
/// [`crate::solver::newton::solve`] drives it (the other coordinates stay put): residual in
/// forces and moments over the lever, Jacobian the level's stiffness, regularised.
struct StaticSystem<'a> {
    level: &'a mut dyn LevelModel,
    dofs: &'a [usize],
    loads: [f64; 5],
    omega: f64,
    lever: f64,
    /// The level's states (their positions moved with the ring when `follow`).
    x: Vec<f64>,
    follow: bool,
    aux: &'a mut [f64],
    tol: f64,
    out: LevelOutputs,
    /// `(wrench, K)` at the current point and at the last trial.
    now: ([f64; 5], [[f64; 5]; 5]),
    next: ([f64; 5], [[f64; 5]; 5]),
    /// `now` is the accepted trial's.
    fresh: bool,
}

impl StaticSystem<'_> {
    fn w(&self, d: usize) -> f64 {
        if d < 3 {
            1.0
        } else {
            self.lever
        }
    }

    fn eval(&mut self, q: &[f64; 5]) -> Result<([f64; 5], [[f64; 5]; 5])> {
        let w = self.wrench(q)?;
        if !self.follow {
            return Ok((w, self.out.k));
        }
        // The stiffness with the states following the ring: forward differences over the
        // free coordinates (steps as the full level's outputs use for its K, but 10× the
        // translations': the positions are solved to a relative 1e-12).
        const STEPS: [f64; 5] = [1e-8, 1e-8, 1e-8, 1e-7, 1e-7];
        let mut k = [[0.0; 5]; 5];
        for &c in self.dofs {
            let mut qc = *q;
            qc[c] += STEPS[c];
            let wc = self.wrench(&qc)?;
            for r in 0..5 {
                k[r][c] = -(wc[r] - w[r]) / STEPS[c];
            }
        }
        // The level's states (and outputs) back at `q`.
        self.wrench(q)?;
        Ok((w, k))
    }

    /// The level's wrench at the displacement `q`, its position states moved there when
    /// they follow the ring (the outputs, with the level's own stiffness, in `self.out`).
    fn wrench(&mut self, q: &[f64; 5]) -> Result<[f64; 5]> {
        let m = Motion {
            q: *q,
            v: [0.0; 5],
            omega: self.omega,
        };
        if self.follow {
            self.level.follow_ring(&m, &mut self.x)?;
        }
        self.level
            .outputs(Point::new(0.0, &m, &self.x, self.aux), &mut self.out)?;
        Ok(self.out.wrench)
    }

    fn check(&self, wrench: &[f64; 5]) -> crate::solver::newton::Check {
        let norm = self
            .dofs
            .iter()
            .map(|&d| ((wrench[d] + self.loads[d]) / self.w(d)).powi(2))
            .sum::<f64>()
            .sqrt();
        crate::solver::newton::Check {
            norm,
            tol: self.tol,
        }
    }
}

impl crate::solver::newton::NewtonSystem<5> for StaticSystem<'_> {
    type Error = Error;

    fn residual(&mut self, q: &[f64; 5]) -> Result<crate::solver::newton::Check> {
        self.next = self.eval(q)?;
        Ok(self.check(&self.next.0))
    }

    fn linearise(&mut self, q: &[f64; 5]) -> Result<crate::solver::newton::Check> {
        if !self.fresh {
            self.now = self.eval(q)?;
        }
        self.fresh = false;
        Ok(self.check(&self.now.0))
    }

    fn step(&mut self, dq: &mut [f64; 5]) -> bool {
        // The coordinates outside `dofs` get an identity row and no residual: no step.
        let mut a = nalgebra::SMatrix::<f64, 5, 5>::identity();
        let mut b = nalgebra::SVector::<f64, 5>::zeros();
        let mut kmax: f64 = 0.0;
        let (wrench, k) = &self.now;
        for &di in self.dofs {
            b[di] = (wrench[di] + self.loads[di]) / self.w(di);
            for &dj in self.dofs {
                a[(di, dj)] = k[di][dj] / (self.w(di) * self.w(dj));
                kmax = kmax.max(a[(di, dj)].abs());
            }
        }
        for &d in self.dofs {
            a[(d, d)] += 1e-9 * kmax + 1e3;
        }
        match a.lu().solve(&b) {
            Some(x) => {
                *dq = std::array::from_fn(|i| x[i]);
                true
            }
            None => false,
        }
    }

    fn accept(&mut self) {
        self.now = self.next;
        self.fresh = true;
    }
}
