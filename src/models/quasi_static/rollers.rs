//! The quasi-static load table of a roller bearing: the inner ring's displacement
//! `q = (x, y, z, rx, ry)` at which the massless rollers (cylindrical: `contact::roller_law`,
//! tapered: `contact::tapered_law`) balance an external load on the shaft, found by Newton's
//! method on `F(q) + load = 0` with `K = -dF/dq` from [`crate::seam::element::assemble`],
//! and what each roller and lamina carries there.
//!
//! A direction the rollers cannot support (an NU's axial, `K[2][2] = 0` at every `q`) is held
//! at zero when its load is zero and refused naming the load when it is not. The rollers sit
//! at azimuths `2 pi j/Z` (the cage at angle 0).

use crate::contact::lamina::Laminae;
use crate::contact::roller_law::CylindricalRollerLaw;
use crate::contact::tapered_law::TaperedRollerLaw;
use crate::error::{Error, Result};
use crate::geometry::roller::RollerBearing;
use crate::seam::element::{
    assemble, ElementAt, ElementDisplacement, ElementLaw, ElementReaction, Want,
};

/// One roller at the solution.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RollerRow {
    /// Azimuth, rad.
    pub psi: f64,
    /// Inner and outer (cone and cup) contact loads, N.
    pub load: [f64; 2],
    /// Inner and outer peak pressures, Pa.
    pub pressure: [f64; 2],
    /// Flange load, N (tapered: the cone back flange; zero otherwise).
    pub flange_load: f64,
    /// Outer-contact load of each lamina, N (roller's small end/first lamina first).
    pub lamina_load: Vec<f64>,
    /// Inner-contact (cone) load of each lamina, N.
    pub lamina_load_inner: Vec<f64>,
    /// Inner-contact peak pressure of each lamina, Pa.
    pub lamina_pressure: Vec<f64>,
    /// The larger inner-contact pressure of the two end laminae, Pa (the edge stress).
    pub edge_pressure: f64,
}

/// The solution.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RollerSolution {
    /// Displacement `(x, y, z, rx, ry)`, m and rad.
    pub q: [f64; 5],
    /// Force of the rollers on the shaft, N and N m.
    pub rollers_force: [f64; 5],
    /// `K = -dF/dq`, SI.
    pub k: [[f64; 5]; 5],
    /// Newton iterations.
    pub iterations: usize,
    /// Every roller.
    pub rollers: Vec<RollerRow>,
}

/// The law of either roller kind.
#[derive(Debug)]
enum Law {
    Cyl(CylindricalRollerLaw),
    Tap(TaperedRollerLaw),
}

impl Law {
    fn law(&self) -> &dyn ElementLaw {
        match self {
            Law::Cyl(l) => l,
            Law::Tap(l) => l,
        }
    }
    fn laminae(&self) -> &Laminae {
        match self {
            Law::Cyl(l) => l.laminae(),
            Law::Tap(l) => l.laminae(),
        }
    }
}

/// How to solve: a misalignment held fixed, where the rollers sit.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SolveOptions {
    /// The inner ring's tilt `(rx, ry)` (rad) held fixed (a misalignment): only the other
    /// directions are solved and the moments are the reaction, not balanced.
    pub tilt: Option<[f64; 2]>,
    /// Azimuth of roller 0, rad (the others follow at `2 pi j/Z`).
    pub first_azimuth: f64,
}

/// Solve the bearing `b` under the external load `load` (N, N m) on the shaft at shaft speed
/// `omega` (rad/s); `names` name the five loads in a refusal.
pub fn solve(
    b: &RollerBearing,
    load: [f64; 5],
    omega: f64,
    names: [&str; 5],
) -> Result<RollerSolution> {
    solve_with(b, load, omega, names, SolveOptions::default())
}

/// [`solve`] with a held misalignment or another roller position ([`SolveOptions`]).
pub fn solve_with(
    b: &RollerBearing,
    load: [f64; 5],
    omega: f64,
    names: [&str; 5],
    opts: SolveOptions,
) -> Result<RollerSolution> {
    let law = if b.kind.is_tapered() {
        Law::Tap(TaperedRollerLaw::new(b)?)
    } else {
        Law::Cyl(CylindricalRollerLaw::new(b)?)
    };
    let l = law.law();
    let psi: Vec<f64> = (0..b.z)
        .map(|j| opts.first_azimuth + 2.0 * std::f64::consts::PI * j as f64 / b.z as f64)
        .collect();
    let eval = |q: &[f64; 5], k: Option<&mut [[f64; 5]; 5]>| {
        let want = Want {
            stiffness: k.is_some(),
            report: false,
        };
        assemble(q, &psi, l.moment_arm(), k, |_, at, u| {
            l.react(at, u, omega, &mut [], want)
        })
    };
    // Start beyond the clearance along the load: the rollers then touch and K is regular.
    let fr = load[0].hypot(load[1]);
    let mut q = [0.0; 5];
    if fr > 0.0 {
        let d = 0.5 * b.pd.max(0.0) + 2e-6;
        q[0] = d * load[0] / fr;
        q[1] = d * load[1] / fr;
    }
    if load[2] != 0.0 {
        q[2] = 2e-6 * load[2].signum();
    }
    // Which directions the rollers can support: probe K at a displacement that loads all.
    let mut held = [false; 5];
    {
        let mut probe = q;
        probe[0] += b.pd.abs() + 5e-6;
        probe[2] += if b.kind.is_tapered() { 5e-5 } else { 5e-6 };
        let mut k = [[0.0; 5]; 5];
        eval(&probe, Some(&mut k))?;
        for i in 0..5 {
            if k[i][i] == 0.0 {
                if load[i] != 0.0 {
                    return Err(Error::invalid(
                        names[i],
                        load[i],
                        format!(
                            "0: a {:?} roller bearing carries no load in this direction (no flange contact holds the rollers)",
                            b.kind
                        ),
                    ));
                }
                held[i] = true;
                q[i] = 0.0;
            }
        }
    }
    if let Some(t) = opts.tilt {
        for (i, v) in [(3, t[0]), (4, t[1])] {
            if !v.is_finite() {
                return Err(Error::invalid(
                    if i == 3 { "tilt rx" } else { "tilt ry" },
                    v,
                    "a finite angle in rad",
                ));
            }
            held[i] = true;
            q[i] = v;
        }
    }
    let scale = load.iter().map(|v| v.abs()).fold(1.0, f64::max);
    let mut iterations = 0;
    let mut k = [[0.0; 5]; 5];
    let mut f = eval(&q, Some(&mut k))?;
    let resid = |f: &[f64; 5]| {
        (0..5)
            .filter(|&i| !held[i])
            .map(|i| {
                let w = if i < 3 { 1.0 } else { 100.0 };
                (w * (f[i] + load[i])).powi(2)
            })
            .sum::<f64>()
            .sqrt()
    };
    let mut r = resid(&f);
    while r > 1e-9 * scale {
        iterations += 1;
        if iterations > 200 {
            return Err(Error::NotConverged {
                what: "roller bearing quasi-static equilibrium",
                iterations,
                residual: r,
            });
        }
        // K dq = F + load (F(q + dq) ≈ F - K dq), on the free directions; a little
        // regularisation keeps a just-touching ring regular.
        let free: Vec<usize> = (0..5).filter(|&i| !held[i]).collect();
        let n = free.len();
        let mut a = vec![0.0; n * n];
        let mut rhs = vec![0.0; n];
        let dmax = free.iter().map(|&i| k[i][i].abs()).fold(0.0, f64::max);
        for (ii, &i) in free.iter().enumerate() {
            for (jj, &j) in free.iter().enumerate() {
                a[ii * n + jj] = k[i][j];
            }
            a[ii * n + ii] += 1e-9 * dmax.max(1.0) + if k[i][i] <= 0.0 { 1e3 } else { 0.0 };
            rhs[ii] = f[i] + load[i];
        }
        let dq = gauss(&mut a, &mut rhs, n)?;
        // Backtrack on the residual.
        let mut step = 1.0;
        loop {
            let mut qn = q;
            for (ii, &i) in free.iter().enumerate() {
                // No step larger than 20 µm or 2 mrad.
                let cap = if i < 3 { 2e-5 } else { 2e-3 };
                qn[i] += (step * dq[ii]).clamp(-cap, cap);
            }
            let mut kn = [[0.0; 5]; 5];
            let fnew = eval(&qn, Some(&mut kn))?;
            let rn = resid(&fnew);
            if rn < r || step < 1e-4 {
                q = qn;
                f = fnew;
                k = kn;
                r = rn;
                break;
            }
            step *= 0.5;
        }
    }
    let mut rollers = Vec::with_capacity(b.z);
    let lam = law.laminae();
    let want = Want {
        stiffness: false,
        report: true,
    };
    let (ri, ei) = (b.reduced_radius_inner(), b.e_prime_inner());
    for (j, &p) in psi.iter().enumerate() {
        let (s, c) = p.sin_cos();
        let at = ElementAt {
            index: j,
            psi: p,
            sc: (s, c),
            q: &q,
        };
        let mut u = ElementDisplacement::at(&q, s, c);
        u.axial += l.moment_arm() * u.tilt;
        let rr: ElementReaction = l.react(at, u, omega, &mut [], want)?;
        let mut ll = vec![0.0; lam.len()];
        let (flange_load, inner) = match &law {
            Law::Cyl(cl) => {
                // The inner laminae; at speed each outer one carries F_c/ns more.
                cl.lamina_loads(u, omega, &mut ll);
                let inner = ll.clone();
                if omega != 0.0 {
                    let fk = cl.centrifugal_force(omega) / ll.len() as f64;
                    ll.iter_mut().for_each(|v| *v += fk);
                }
                (0.0, inner)
            }
            Law::Tap(tl) => {
                let mut cone = vec![0.0; lam.len()];
                let (_, qf) = tl.lamina_loads_at(u, omega, &mut ll, &mut cone);
                (qf, cone)
            }
        };
        let mut lp = vec![0.0; lam.len()];
        lam.pressures(&inner, ri, ei, &mut lp);
        let edge_pressure = lp[0].max(lp[lp.len() - 1]);
        rollers.push(RollerRow {
            psi: p,
            load: rr.load,
            pressure: rr.pressure,
            flange_load,
            lamina_load: ll,
            lamina_load_inner: inner,
            lamina_pressure: lp,
            edge_pressure,
        });
    }
    Ok(RollerSolution {
        q,
        rollers_force: f,
        k,
        iterations,
        rollers,
    })
}

/// Gaussian elimination with partial pivoting of the `n × n` system `a x = b` (row-major).
fn gauss(a: &mut [f64], b: &mut [f64], n: usize) -> Result<Vec<f64>> {
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&x, &y| a[x * n + col].abs().total_cmp(&a[y * n + col].abs()))
            .unwrap_or(col);
        if a[piv * n + col] == 0.0 || !a[piv * n + col].is_finite() {
            return Err(Error::NotConverged {
                what: "roller bearing quasi-static equilibrium (singular stiffness)",
                iterations: 0,
                residual: f64::NAN,
            });
        }
        if piv != col {
            for j in 0..n {
                a.swap(piv * n + j, col * n + j);
            }
            b.swap(piv, col);
        }
        for row in col + 1..n {
            let m = a[row * n + col] / a[col * n + col];
            for j in col..n {
                a[row * n + j] -= m * a[col * n + j];
            }
            b[row] -= m * b[col];
        }
    }
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|j| a[i * n + j] * x[j]).sum();
        x[i] = (b[i] - s) / a[i * n + i];
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::roller_catalogue::lookup;
    use crate::ratings::lamina_life::{lamina_life, lamina_static_safety, LaminaLifeOptions};

    const NAMES: [&str; 5] = ["fx", "fy", "fz", "mx", "my"];

    /// NU206 under a radial load: the rollers balance it, the most loaded roller carries
    /// about `4.08 Fr/Z` at zero clearance (Stribeck's number for line contact, [Harris 2007]
    /// vol. 1 ch. 7; the discrete set and the ISO log profile within 5 %), and an axial load
    /// is refused naming it.
    #[test]
    fn nu206_balances_a_radial_load_with_stribecks_peak() {
        let mut s = lookup("NU206").unwrap();
        s.clearance_um = Some(0.0);
        let b = s.build().unwrap();
        let sol = solve(&b, [0.0, -8000.0, 0.0, 0.0, 0.0], 0.0, NAMES).unwrap();
        assert!((sol.rollers_force[1] - 8000.0).abs() < 1e-5);
        let qmax = sol.rollers.iter().map(|r| r.load[0]).fold(0.0, f64::max);
        let want = 4.08 * 8000.0 / b.z as f64;
        assert!((qmax / want - 1.0).abs() < 0.05, "{qmax} vs {want}");
        // The lamina loads sum to the roller's load.
        for r in &sol.rollers {
            let s: f64 = r.lamina_load.iter().sum();
            assert!((s - r.load[1]).abs() <= 1e-9 * r.load[1].max(1.0));
        }
        assert!(sol.k[2][2] == 0.0 && sol.k.iter().flatten().all(|v| v.is_finite()));
        let e = solve(&b, [0.0, -8000.0, 500.0, 0.0, 0.0], 0.0, NAMES)
            .unwrap_err()
            .to_string();
        assert!(e.contains("fz"), "{e}");
    }

    /// NU206 under 8 kN at 15 000 rpm: the inner contacts still balance the load, every
    /// roller's outer contact carries its inner load plus `F_c` (lamina by lamina too), the
    /// shaft sits further out than at rest (the centrifugal force takes part of each lamina's
    /// approach), and the unloaded rollers press on the outer ring with `F_c` alone.
    #[test]
    fn nu206_at_speed_carries_the_centrifugal_force_on_the_outer_ring() {
        let b = lookup("NU206").unwrap().build().unwrap();
        let omega = 15_000.0 * std::f64::consts::PI / 30.0;
        let fc = CylindricalRollerLaw::new(&b)
            .unwrap()
            .centrifugal_force(omega);
        let load = [0.0, -8000.0, 0.0, 0.0, 0.0];
        let rest = solve(&b, load, 0.0, NAMES).unwrap();
        let fast = solve(&b, load, omega, NAMES).unwrap();
        assert!((fast.rollers_force[1] - 8000.0).abs() < 1e-5);
        assert!(fast.q[1] < rest.q[1], "{:?} vs {:?}", fast.q, rest.q);
        for r in &fast.rollers {
            assert!((r.load[1] - r.load[0] - fc).abs() < 1e-9 * r.load[1]);
            let s: f64 = r.lamina_load.iter().sum();
            assert!((s - r.load[1]).abs() <= 1e-9 * r.load[1]);
        }
        let idle = fast.rollers.iter().filter(|r| r.load[0] == 0.0).count();
        assert!(idle > 0, "a load zone, not all rollers loaded");
    }

    /// 30206 under a combined load: the rollers balance it and the flanges carry
    /// `rho_f Q_o` each.
    #[test]
    fn tapered_balances_a_combined_load() {
        let b = lookup("30206").unwrap().build().unwrap();
        let load = [0.0, -4000.0, 3000.0, 0.0, 0.0];
        let sol = solve(&b, load, 0.0, NAMES).unwrap();
        for (f, l) in sol.rollers_force.iter().zip(load) {
            assert!((f + l).abs() < 1e-5, "{sol:?}");
        }
        let fa: f64 = sol.rollers.iter().map(|r| r.load[1]).sum::<f64>() * b.alpha.sin();
        assert!((fa - 3000.0).abs() < 1e-4, "{fa}");
        assert!(sol.rollers.iter().all(|r| r.flange_load >= 0.0));
    }

    /// 30206 under a combined load at 10 000 rpm: the rollers still balance it (the
    /// centrifugal forces' axial parts reach the shaft through the flanges), every roller
    /// presses the cup harder than at rest and its flange carries more.
    #[test]
    fn tapered_at_speed_balances_and_loads_cup_and_flange() {
        let b = lookup("30206").unwrap().build().unwrap();
        let load = [0.0, -4000.0, 3000.0, 0.0, 0.0];
        let rest = solve(&b, load, 0.0, NAMES).unwrap();
        let fast = solve(&b, load, 10_000.0 * std::f64::consts::PI / 30.0, NAMES).unwrap();
        for (f, l) in fast.rollers_force.iter().zip(load) {
            assert!((f + l).abs() < 1e-4, "{:?}", fast.rollers_force);
        }
        let sum =
            |s: &RollerSolution, f: fn(&RollerRow) -> f64| s.rollers.iter().map(f).sum::<f64>();
        assert!(sum(&fast, |r| r.load[1]) > sum(&rest, |r| r.load[1]));
        assert!(sum(&fast, |r| r.flange_load) > sum(&rest, |r| r.flange_load));
        assert!(
            fast.rollers.iter().all(|r| r.load[1] > 0.0),
            "F_c keeps every roller on the cup"
        );
    }

    fn life(b: &RollerBearing, sol: &RollerSolution, o: LaminaLifeOptions) -> f64 {
        let inner: Vec<Vec<f64>> = sol
            .rollers
            .iter()
            .map(|r| r.lamina_load_inner.clone())
            .collect();
        let outer: Vec<Vec<f64>> = sol.rollers.iter().map(|r| r.lamina_load.clone()).collect();
        lamina_life(b, &inner, &outer, o)
            .unwrap()
            .l10r_mrev
            .unwrap()
    }

    fn tilted(b: &RollerBearing, fr: f64, rx: f64) -> RollerSolution {
        let o = SolveOptions {
            tilt: Some([rx, 0.0]),
            first_azimuth: -0.5 * std::f64::consts::PI,
        };
        solve_with(b, [0.0, -fr, 0.0, 0.0, 0.0], 0.0, NAMES, o).unwrap()
    }

    /// NU206 with straight rollers at zero clearance under `Fr = Cr`, aligned: without the
    /// two unsourced steps the lamina life is ISO 281's `L10 = 1` within the 14 discrete
    /// rollers' departure from the continuous load distribution (a few per cent).
    #[test]
    fn nu206_straight_aligned_at_p_equal_c_gives_iso_281() {
        let mut s = lookup("NU206").unwrap();
        s.clearance_um = Some(0.0);
        s.profile = crate::geometry::roller::ProfileSpec::None;
        let b = s.build().unwrap();
        let cr = crate::ratings::roller::roller_ratings(&b).unwrap().cr;
        let sol = tilted(&b, cr, 0.0);
        let plain = LaminaLifeOptions {
            edge_factor: false,
            remove_lambda_nu: false,
        };
        let l = life(&b, &sol, plain);
        assert!((l - 1.0).abs() < 0.05, "L {l}");
    }

    /// Tilt lowers the lamina life, and an ISO/TS logarithmic profile loses less of its
    /// aligned life under 1 mrad than a straight roller (edge factor on).
    #[test]
    fn tilt_lowers_the_life_and_a_log_profile_loses_less() {
        let base = lookup("NU206").unwrap();
        let mut ratios = Vec::new();
        for p in [
            crate::geometry::roller::ProfileSpec::None,
            crate::geometry::roller::ProfileSpec::IsoLog,
        ] {
            let mut s = base.clone();
            s.profile = p.clone();
            let b = s.build().unwrap();
            let o = LaminaLifeOptions::default();
            let l0 = life(&b, &tilted(&b, 8000.0, 0.0), o);
            let l1 = life(&b, &tilted(&b, 8000.0, 0.5e-3), o);
            let l2 = life(&b, &tilted(&b, 8000.0, 1e-3), o);
            assert!(l0 > l1 && l1 > l2, "{p:?}: {l0} {l1} {l2}");
            ratios.push(l2 / l0);
        }
        assert!(
            ratios[1] > ratios[0],
            "straight keeps {:.3}, log {:.3}",
            ratios[0],
            ratios[1]
        );
    }

    /// S0 of the most loaded lamina is 1 at the radial load whose peak lamina pressure is
    /// 4000 MPa (found by secant on p² ∝ load), NU206 with its ISO log profile.
    #[test]
    fn s0_is_one_at_4000_mpa() {
        let b = lookup("NU206").unwrap().build().unwrap();
        let pmax = |fr: f64| {
            solve(&b, [0.0, -fr, 0.0, 0.0, 0.0], 0.0, NAMES)
                .unwrap()
                .rollers
                .iter()
                .flat_map(|r| r.lamina_pressure.iter().copied())
                .fold(0.0, f64::max)
        };
        let mut fr = 20_000.0;
        for _ in 0..60 {
            let p = pmax(fr);
            let next = fr * (4000e6 / p).powi(2);
            if (next / fr - 1.0).abs() < 1e-13 {
                break;
            }
            fr = next;
        }
        let s0 = lamina_static_safety(pmax(fr)).unwrap();
        assert!((s0 - 1.0).abs() < 1e-9, "S0 {s0} at {fr} N");
        assert!(lamina_static_safety(pmax(0.5 * fr)).unwrap() > 1.0);
    }
}
