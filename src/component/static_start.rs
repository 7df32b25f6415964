//! The static start of a load-driven inner ring: its equilibrium under the initial loads.

use super::level::{LevelModel, LevelOutputs, Motion};
use crate::error::{Error, Result};

/// The inner ring's static equilibrium under `loads` (external, on the ring) at speed
/// `omega`: damped Newton on `F(q) + load = 0` over the level's ring coordinates with the
/// level's stiffness, moments weighed as forces at the lever `lever` (m); directions with
/// no stiffness yet (inside a clearance, an unloaded tilt) are regularised. When the full
/// load fails from the centre, the load is applied in stages (continuation). Refuses with
/// the residual when it finds no equilibrium.
pub(super) fn static_start(
    level: &mut dyn LevelModel,
    dofs: &[usize],
    loads: &[f64; 5],
    omega: f64,
    lever: f64,
    x: &[f64],
    aux: &mut [f64],
) -> Result<[f64; 5]> {
    let scale = loads
        .iter()
        .enumerate()
        .map(|(d, v)| if d < 3 { v.abs() } else { v.abs() / lever })
        .sum::<f64>()
        + 1.0;
    let mut last = f64::INFINITY;
    for stages in [1usize, 4, 16] {
        let mut q = [0.0; 5];
        let mut ok = true;
        for k in 1..=stages {
            let f = k as f64 / stages as f64;
            let part: [f64; 5] = std::array::from_fn(|d| f * loads[d]);
            match newton_static(level, dofs, &part, omega, lever, x, aux, &mut q, scale) {
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
            return Ok(q);
        }
    }
    Err(Error::NotConverged {
        what: "static start of the load-driven inner ring (try model.start = \"rest\")",
        iterations: 100,
        residual: last,
    })
}

/// Newton iterations from `q` towards `F(q) + loads = 0`; returns the final residual (forces
/// in N, moments divided by `lever`).
#[allow(clippy::too_many_arguments)]
fn newton_static(
    level: &mut dyn LevelModel,
    dofs: &[usize],
    loads: &[f64; 5],
    omega: f64,
    lever: f64,
    x: &[f64],
    aux: &mut [f64],
    q: &mut [f64; 5],
    scale: f64,
) -> Result<f64> {
    // Scaled coordinates: translations in m, tilts times the lever.
    let w = |d: usize| if d < 3 { 1.0 } else { lever };
    let mut out = LevelOutputs::default();
    let resid = |q: &[f64; 5],
                 out: &mut LevelOutputs,
                 level: &mut dyn LevelModel,
                 aux: &mut [f64]|
     -> Result<f64> {
        let m = Motion {
            q: *q,
            v: [0.0; 5],
            omega,
        };
        level.outputs(0.0, &m, x, aux, out)?;
        Ok(dofs
            .iter()
            .map(|&d| ((out.wrench[d] + loads[d]) / w(d)).powi(2))
            .sum::<f64>()
            .sqrt())
    };
    let mut r = resid(q, &mut out, level, aux)?;
    let n = dofs.len();
    for _ in 0..100 {
        if r <= 1e-9 * scale {
            break;
        }
        let mut a = nalgebra::DMatrix::<f64>::zeros(n, n);
        let mut b = nalgebra::DVector::<f64>::zeros(n);
        let mut kmax: f64 = 0.0;
        for (i, &di) in dofs.iter().enumerate() {
            b[i] = (out.wrench[di] + loads[di]) / w(di);
            for (j, &dj) in dofs.iter().enumerate() {
                a[(i, j)] = out.k[di][dj] / (w(di) * w(dj));
                kmax = kmax.max(a[(i, j)].abs());
            }
        }
        for i in 0..n {
            a[(i, i)] += 1e-9 * kmax + 1e3;
        }
        let Some(dq) = a.lu().solve(&b) else { break };
        let mut step = 1.0;
        let mut accepted = false;
        // The last step that overshot (residual up) before one that changed nothing.
        let mut over = None;
        for _ in 0..40 {
            let mut trial = *q;
            for (i, &d) in dofs.iter().enumerate() {
                trial[d] += step * dq[i] / w(d);
            }
            if let Ok(rt) = resid(&trial, &mut out, level, aux) {
                if rt < r {
                    (*q, r, accepted) = (trial, rt, true);
                    break;
                }
                if rt == r {
                    // No contact along the whole trial (the residual is exactly the
                    // load's): the band where the contacts engage and the residual falls
                    // lies between this step and the last that overshot, narrower than a
                    // halving (a clearance's dead zone before a Hertzian rise). Bisect it:
                    // residual unchanged, go further; larger, go back.
                    if let Some(mut hi) = over {
                        let mut lo = step;
                        for _ in 0..60 {
                            let mid = 0.5 * (lo + hi);
                            let mut trial = *q;
                            for (i, &d) in dofs.iter().enumerate() {
                                trial[d] += mid * dq[i] / w(d);
                            }
                            match resid(&trial, &mut out, level, aux) {
                                Ok(rt) if rt < r => {
                                    (*q, r, accepted) = (trial, rt, true);
                                    break;
                                }
                                Ok(rt) if rt == r => lo = mid,
                                _ => hi = mid,
                            }
                        }
                    }
                    break;
                }
                over = Some(step);
            }
            step *= 0.5;
        }
        if !accepted {
            break;
        }
        resid(q, &mut out, level, aux)?;
    }
    Ok(r)
}
