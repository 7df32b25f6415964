//! A rigid rotor on two bearings, shared by the coupling example and its test.
//!
//! Four degrees of freedom: centre displacement `(x, y)` and tilts `(tx, ty)` about x and
//! y (small angles), mass `m`, transverse inertia `it`, gravity along `-y`, a static
//! unbalance `m_u e` at the centre turning with the shaft. Bearings sit at axial positions
//! `z_k`; a bearing at `z` sees `x_b = x + z ty`, `y_b = y - z tx`. Gyroscopic coupling is
//! left out (a rigid, slender rotor at moderate speed).
//!
//! Two ways to run it:
//! - **co-simulated**: two `raceway::Component`s (motion-driven) at a fixed macro step `H`
//!   (Jacobi: the bearings step with the rotor state at `t_n`; the rotor integrates over
//!   the step with the force extrapolated from the bearings' `F` and `dF/dt` outputs);
//! - **monolithic**: rotor and the bearings' ring physics in one RK4 integration.
#![allow(dead_code, clippy::needless_range_loop)]

use raceway::component::{levels::cage_speed, variables, Component, InputRule};
use raceway::models::ring::{RingAt, RingDof, RingEval, RingModel};

/// Rotor and run parameters.
#[derive(Debug, Clone, Copy)]
pub struct Rotor {
    /// Mass, kg.
    pub m: f64,
    /// Transverse moment of inertia, kg m².
    pub it: f64,
    /// Axial positions of the two bearings, m.
    pub z: [f64; 2],
    /// Unbalance `m_u e`, kg m.
    pub unbalance: f64,
    /// Shaft speed, rad/s.
    pub omega: f64,
    /// Gravity, m/s².
    pub g: f64,
}

impl Default for Rotor {
    fn default() -> Self {
        Rotor {
            m: 8.0,
            it: 0.05,
            z: [-0.1, 0.12],
            unbalance: 2e-4,
            omega: 183.26,
            g: 9.81,
        }
    }
}

/// The bearing scene both ways use: a 6205 with 10 µm clearance, ring level.
pub fn bearing_scene(rule: InputRule) -> String {
    let rule = match rule {
        InputRule::Hold => "hold",
        InputRule::Velocity => "velocity",
        InputRule::Derivatives => "derivatives",
    };
    format!(
        "bearing = {{ preset = \"6205\", clearance_um = 10.0 }}\n[model]\nlevel = \"ring\"\ncontact_damping = 400.0\n\
         [solver]\nmax_substep_s = 2e-6\n[inputs]\nrule = \"{rule}\"\n"
    )
}

fn accel(r: &Rotor, t: f64, s: &[f64; 8], f: &[[f64; 2]; 2], acc: &mut [f64; 4]) {
    let ph = r.omega * t;
    let u = r.unbalance * r.omega * r.omega;
    let (mut fx, mut fy, mut mx, mut my) = (u * ph.cos(), u * ph.sin() - r.m * r.g, 0.0, 0.0);
    for k in 0..2 {
        fx += f[k][0];
        fy += f[k][1];
        my += r.z[k] * f[k][0];
        mx -= r.z[k] * f[k][1];
    }
    let _ = s;
    *acc = [fx / r.m, fy / r.m, mx / r.it, my / r.it];
}

/// Bearing motion (x, y, vx, vy) at axial position `z`.
pub fn bearing_motion(s: &[f64; 8], z: f64) -> [f64; 4] {
    [
        s[0] + z * s[3],
        s[1] - z * s[2],
        s[4] + z * s[7],
        s[5] - z * s[6],
    ]
}

/// Static start: the rotor centred (the bearings take up the clearance in the first
/// milliseconds).
pub fn initial() -> [f64; 8] {
    [0.0; 8]
}

/// Monolithic run to `t_end` with RK4 step `dt`; returns the sampled bearing-1 force
/// `(t, Fx, Fy)` every `sample` seconds.
pub fn monolithic(r: &Rotor, t_end: f64, dt: f64, sample: f64) -> Vec<(f64, f64, f64)> {
    let comp = Component::from_text(&bearing_scene(InputRule::Velocity)).unwrap();
    let b = comp.bearing().clone();
    let model = RingModel::new(&b, RingDof::Two, comp.scene().model.contact_damping);
    let wc = cage_speed(&b, r.omega);
    let mut e = RingEval::default();
    let mut forces = |t: f64, s: &[f64; 8]| -> [[f64; 2]; 2] {
        let mut f = [[0.0; 2]; 2];
        for k in 0..2 {
            let bm = bearing_motion(s, r.z[k]);
            model.eval(
                RingAt {
                    theta_c: wc * t,
                    omega_c: wc,
                    q: &[bm[0], bm[1], 0.0, 0.0, 0.0],
                    v: &[bm[2], bm[3], 0.0, 0.0, 0.0],
                    t,
                },
                None,
                false,
                &mut e,
            );
            f[k] = [e.wrench[0], e.wrench[1]];
        }
        f
    };
    let mut s = initial();
    let mut t = 0.0;
    let mut out = Vec::new();
    let n = (t_end / dt).round() as usize;
    let every = (sample / dt).round() as usize;
    let deriv = |t: f64, s: &[f64; 8], f: &[[f64; 2]; 2]| -> [f64; 8] {
        let mut a = [0.0; 4];
        accel(r, t, s, f, &mut a);
        [s[4], s[5], s[6], s[7], a[0], a[1], a[2], a[3]]
    };
    for i in 0..=n {
        if i % every == 0 {
            let f = forces(t, &s);
            out.push((t, f[0][0], f[0][1]));
        }
        if i == n {
            break;
        }
        let k1 = deriv(t, &s, &forces(t, &s));
        let s2: [f64; 8] = std::array::from_fn(|j| s[j] + 0.5 * dt * k1[j]);
        let k2 = deriv(t + 0.5 * dt, &s2, &forces(t + 0.5 * dt, &s2));
        let s3: [f64; 8] = std::array::from_fn(|j| s[j] + 0.5 * dt * k2[j]);
        let k3 = deriv(t + 0.5 * dt, &s3, &forces(t + 0.5 * dt, &s3));
        let s4: [f64; 8] = std::array::from_fn(|j| s[j] + dt * k3[j]);
        let k4 = deriv(t + dt, &s4, &forces(t + dt, &s4));
        for j in 0..8 {
            s[j] += dt / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
        }
        t = (i + 1) as f64 * dt;
    }
    out
}

/// Co-simulated run at macro step `h` with the bearings' input `rule`; the rotor
/// sub-steps RK4 `sub` times per macro step. Returns bearing-1 force samples every
/// `sample` seconds (a multiple of `h`).
/// A run that blows up (explicit coupling beyond its stability limit) ends in `Err`.
pub fn cosimulated(
    r: &Rotor,
    rule: InputRule,
    t_end: f64,
    h: f64,
    sub: usize,
    sample: f64,
) -> Result<Vec<(f64, f64, f64)>, String> {
    let vr = |n: &str| variables::by_name(n).unwrap().vr;
    let (ix, iy, ivx, ivy, iom) = (
        vr("shaft.x"),
        vr("shaft.y"),
        vr("shaft.vx"),
        vr("shaft.vy"),
        vr("shaft.omega"),
    );
    let (ifx, ify) = (vr("force.x"), vr("force.y"));
    let mut bearings: Vec<Component> = (0..2)
        .map(|_| Component::from_text(&bearing_scene(rule)).unwrap())
        .collect();
    let mut s = initial();
    let mut t = 0.0;
    let n = (t_end / h).round() as usize;
    let every = ((sample / h).round() as usize).max(1);
    let mut out = Vec::new();
    // Forces and their rates at t_n, from the bearings' last step.
    let mut f = [[0.0; 2]; 2];
    let mut df = [[0.0; 2]; 2];
    let mut acc = [0.0; 4];
    for step in 0..=n {
        // Bearings: inputs at t_n, step to t_n + h.
        accel(r, t, &s, &f, &mut acc);
        for (k, b) in bearings.iter_mut().enumerate() {
            let bm = bearing_motion(&s, r.z[k]);
            let z = r.z[k];
            let (ax, ay) = (acc[0] + z * acc[3], acc[1] - z * acc[2]);
            for (v, x) in [
                (ix, bm[0]),
                (iy, bm[1]),
                (ivx, bm[2]),
                (ivy, bm[3]),
                (iom, r.omega),
            ] {
                b.set_real(v, x).unwrap();
            }
            for name in [
                "shaft.z", "shaft.rx", "shaft.ry", "shaft.vz", "shaft.wx", "shaft.wy",
            ] {
                b.set_real(vr(name), 0.0).unwrap();
            }
            if rule == InputRule::Derivatives {
                for (v, d1, d2) in [
                    (ix, bm[2], ax),
                    (iy, bm[3], ay),
                    (ivx, ax, 0.0),
                    (ivy, ay, 0.0),
                ] {
                    b.set_input_derivative(v, 1, d1).unwrap();
                    if d2 != 0.0 {
                        b.set_input_derivative(v, 2, d2).unwrap();
                    }
                }
            }
        }
        if step % every == 0 {
            out.push((t, f[0][0], f[0][1]));
        }
        if step == n {
            break;
        }
        let (f0, df0) = (f, df);
        for b in bearings.iter_mut() {
            b.do_step(t, h).map_err(|e| e.to_string())?;
        }
        for (k, b) in bearings.iter_mut().enumerate() {
            f[k] = [b.get_real(ifx).unwrap(), b.get_real(ify).unwrap()];
            df[k] = [
                b.get_output_derivative(ifx, 1).unwrap(),
                b.get_output_derivative(ify, 1).unwrap(),
            ];
        }
        // Rotor: RK4 sub-steps over [t, t+h] with the force extrapolated linearly from t_n.
        let dt = h / sub as f64;
        let force_at = |tau: f64| -> [[f64; 2]; 2] {
            std::array::from_fn(|k| std::array::from_fn(|i| f0[k][i] + df0[k][i] * tau))
        };
        let deriv = |tt: f64, st: &[f64; 8], tau: f64| -> [f64; 8] {
            let mut a = [0.0; 4];
            accel(r, tt, st, &force_at(tau), &mut a);
            [st[4], st[5], st[6], st[7], a[0], a[1], a[2], a[3]]
        };
        for j in 0..sub {
            let tau = j as f64 * dt;
            let tt = t + tau;
            let k1 = deriv(tt, &s, tau);
            let s2: [f64; 8] = std::array::from_fn(|i| s[i] + 0.5 * dt * k1[i]);
            let k2 = deriv(tt + 0.5 * dt, &s2, tau + 0.5 * dt);
            let s3: [f64; 8] = std::array::from_fn(|i| s[i] + 0.5 * dt * k2[i]);
            let k3 = deriv(tt + 0.5 * dt, &s3, tau + 0.5 * dt);
            let s4: [f64; 8] = std::array::from_fn(|i| s[i] + dt * k3[i]);
            let k4 = deriv(tt + dt, &s4, tau + dt);
            for i in 0..8 {
                s[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        t = (step + 1) as f64 * h;
        if s.iter().any(|v| !v.is_finite()) || s[..4].iter().any(|v| v.abs() > 1e-3) {
            return Err(format!("unstable at t = {t} s"));
        }
    }
    Ok(out)
}

/// Relative L2 error of the `Fy` samples of `a` against `reference` over `t >= t0`
/// (samples at the same times).
pub fn rel_l2(a: &[(f64, f64, f64)], reference: &[(f64, f64, f64)], t0: f64) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    let mut n = 0;
    for (x, y) in a.iter().zip(reference) {
        assert!(
            (x.0 - y.0).abs() < 1e-9,
            "sample times differ: {} vs {}",
            x.0,
            y.0
        );
        if x.0 >= t0 {
            num += (x.1 - y.1).powi(2) + (x.2 - y.2).powi(2);
            den += y.1 * y.1 + y.2 * y.2;
            n += 1;
        }
    }
    assert!(n > 0);
    (num / den).sqrt()
}
