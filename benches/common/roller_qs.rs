//! A quasi-static solve of a cylindrical roller bearing under a radial load and moments,
//! for the speed bench and the rollers page: the ring displacement `(x, y, rx, ry)` at
//! which the rollers' forces on the shaft balance the load on the inner ring,
//! `F(q) + load = 0`, by Newton's method on the exact stiffness `K = -dF/dq` of the laminae
//! ([`raceway::seam::element::assemble`] over [`CylindricalRollerLaw`]), from a cold start
//! (Stribeck's estimate of the deflection along the load). The axial direction carries no
//! load (NU, N): `z` stays 0. Allocates nothing. Mounted with
//! `#[path = "common/roller_qs.rs"] mod roller_qs;` (a bench and an example use it until the
//! library's quasi-static level solves rollers itself).

use raceway::contact::roller_law::CylindricalRollerLaw;
use raceway::seam::element::{assemble, ElementLaw, Want};

/// The equilibrium found.
#[derive(Debug, Clone, Copy)]
pub struct Solved {
    /// Ring displacement `(x, y, z, rx, ry)`, m and rad.
    pub q: [f64; 5],
    /// Newton iterations.
    pub iterations: usize,
    /// Largest scaled residual at the end (forces over |load|, moments over |load| Lwe).
    pub residual: f64,
}

/// The forces on the shaft at `q` and, with `k`, `K = -dF/dq`.
pub fn forces(
    law: &CylindricalRollerLaw,
    psi: &[f64],
    q: &[f64; 5],
    k: Option<&mut [[f64; 5]; 5]>,
) -> [f64; 5] {
    let want = Want {
        stiffness: k.is_some(),
        report: false,
    };
    assemble(q, psi, law.moment_arm(), k, |_, at, u| {
        law.react(at, u, 0.0, &mut [], want)
    })
    .expect("finite forces")
}

/// Solve `F(q) + load = 0` for rollers at azimuths `psi` (rad); `pd` the diametral
/// clearance (m) and `c_l` the roller constant (N/m^(10/9)) for the start. With `tilt =
/// Some((rx, ry))` the ring's tilt is imposed (a misalignment) and only `(x, y)` are solved
/// (the moments then are the reaction, not balanced).
pub fn solve(
    law: &CylindricalRollerLaw,
    psi: &[f64],
    load: [f64; 5],
    pd: f64,
    c_l: f64,
    lwe: f64,
    tilt: Option<(f64, f64)>,
) -> Result<Solved, String> {
    let fr = load[0].hypot(load[1]);
    if fr <= 0.0 {
        return Err("a radial load > 0 is needed".into());
    }
    // Stribeck: Q_max ≈ 4.08 Fr/Z (line contact, zero clearance); the ring moves along the
    // load by half the clearance plus that roller's approach.
    let qmax = 4.08 * fr / psi.len() as f64;
    let d = 0.5 * pd + (qmax / c_l).powf(0.9);
    let (rx, ry) = tilt.unwrap_or((0.0, 0.0));
    let mut q = [load[0] / fr * d, load[1] / fr * d, 0.0, rx, ry];
    let dofs: &[usize] = if tilt.is_some() {
        &[0, 1]
    } else {
        &[0, 1, 3, 4]
    };
    let n = dofs.len();
    let scale = [fr, fr, fr, fr * lwe, fr * lwe];
    let norm = |f: &[f64; 5]| -> f64 {
        dofs.iter()
            .map(|&i| ((f[i] + load[i]) / scale[i]).abs())
            .fold(0.0, f64::max)
    };
    let mut k = [[0.0; 5]; 5];
    let mut f = forces(law, psi, &q, Some(&mut k));
    let mut res = norm(&f);
    for it in 0..100 {
        if res < 1e-12 {
            return Ok(Solved {
                q,
                iterations: it,
                residual: res,
            });
        }
        // (K + mu I) dq = F + load on the solved directions.
        let mut a = [[0.0; 5]; 4];
        let diag = dofs.iter().map(|&i| k[i][i].abs()).fold(0.0, f64::max);
        for (r, &i) in dofs.iter().enumerate() {
            for (c, &j) in dofs.iter().enumerate() {
                a[r][c] = k[i][j];
            }
            a[r][r] += 1e-12 * diag.max(1.0);
            a[r][n] = f[i] + load[i];
        }
        let dq = gauss(a, n).ok_or("singular stiffness")?;
        // Back-tracking line search on the scaled residual.
        let mut step = 1.0;
        loop {
            let mut trial = q;
            for (r, &i) in dofs.iter().enumerate() {
                trial[i] += step * dq[r];
            }
            let ft = forces(law, psi, &trial, Some(&mut k));
            let rt = norm(&ft);
            if rt < res || step < 1e-3 {
                q = trial;
                f = ft;
                res = rt;
                break;
            }
            step *= 0.5;
        }
    }
    Err(format!("no convergence (residual {res:e})"))
}

/// Gaussian elimination with partial pivoting on an `n`×`n` system (`n` ≤ 4) with its
/// right-hand side in column `n`.
fn gauss(mut a: [[f64; 5]; 4], n: usize) -> Option<[f64; 4]> {
    for c in 0..n {
        let p = (c..n).max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))?;
        if a[p][c] == 0.0 {
            return None;
        }
        a.swap(c, p);
        for r in c + 1..n {
            let m = a[r][c] / a[c][c];
            let (top, rest) = a.split_at_mut(r);
            for (x, y) in rest[0][c..=n].iter_mut().zip(&top[c][c..=n]) {
                *x -= m * y;
            }
        }
    }
    let mut x = [0.0; 4];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|j| a[r][j] * x[j]).sum();
        x[r] = (a[r][n] - s) / a[r][r];
    }
    Some(x)
}
