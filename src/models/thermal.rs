//! Friction power and thermal growth (docs/physics.md §8, study \[3\]: Wang et al., 7008CE).
//!
//! **Friction** (Harris & Kotzalas, *Essential Concepts of Bearing Technology*, 5th ed.,
//! ch. 9 "Friction in rolling bearings"; Palmgren, *Ball and Roller Bearing Engineering*):
//!
//! - load-independent (viscous) torque `M0 = 1e-7 f0 (nu n)^(2/3) dm³` for `nu n >= 2000`,
//!   `M0 = 1.6e-5 f0 dm³` below (N mm with `nu` in cSt, `n` in rpm, `dm` in mm; converted
//!   to SI in [`palmgren_m0`]);
//! - load-dependent torque `M1 = f1 P1 dm` with `P1 = max(Fr, 0.9 Fa cot(alpha) - 0.1 Fr)`
//!   (angular contact) or `max(Fr, 3 Fa - 0.1 Fr)` (deep groove, `alpha = 0`);
//! - spin friction per contact `M_s = 3 mu_s Q a E(e) / 8` (uniform Coulomb traction over the
//!   Hertz ellipse, Harris & Kotzalas) times the spin speed `omega_rel sin(alpha)` (ball axis
//!   parallel to the bearing axis, no gyroscopic pivoting; `omega_rel` as in
//!   `crate::models::wear`);
//! - elastic hysteresis per contact `F = alpha_h (3/16) Q b / R_x` (Johnson, *Contact
//!   Mechanics* §9.2, sphere rolling with hysteresis loss fraction `alpha_h`, `b` the
//!   semi-axis along rolling) times the rolling speed `|omega_b| D/2`;
//! - cage friction: Petroff shear of the guiding land, `T = 2 pi eta r³ L omega_rel / c`
//!   (land radius `r` = cage outside/bore radius, land width `L` = cage width / 4, radial
//!   guide clearance `c`; zero for a ball-riding cage).
//!
//! The sum follows docs/physics.md §8; Palmgren's empirical `M0 + M1` already contains part of
//! the spin and hysteresis losses, so every term has its own factor and can be set to 0.
//!
//! **Heat** flows through four lumped nodes (inner ring, outer ring, balls, oil), each with
//! a heat capacity: rings and balls from mass and specific heat, oil from the scene.
//! Conduction ball–ring through each loaded contact by Holm's constriction resistance
//! `1/(4 k r_c)` on each side (`r_c = sqrt(a b)`); convection of each solid to the oil with
//! `h = 9.7 + 5.33 v^0.8` W/(m² K) (`v` the surface speed relative to oil turning with the
//! cage, m/s; the rotating-surface correlation study \[3\] uses) over the ring race areas
//! `pi d_race width` and the ball surfaces `Z pi D²`; to the ambient through the shaft
//! (inner ring), the housing (outer ring) and the oil flow (oil), conductances from the
//! scene. Heat sources: `M0` and cage friction into the oil; `M1` half into the balls and a
//! quarter into each ring; spin and hysteresis half into the ball and half into the race.
//! The network is advanced by implicit Euler on its own slow step, which keeps the heat
//! balance exact step by step: generated = removed to ambient + stored.
//!
//! **Growth**: a free ring warmed by `dT` grows in diameter by `u = alpha_T dT d`; the
//! operating diametral clearance is `Pd + u_o(d_o) - u_i(d_i) - 2 u_b(D)`.

use crate::contact::PointContact;
use crate::geometry::{Bearing, Guidance};
use std::f64::consts::PI;

/// Node indices of the network.
pub const INNER: usize = 0;
/// Outer ring.
pub const OUTER: usize = 1;
/// Balls.
pub const BALLS: usize = 2;
/// Oil.
pub const OIL: usize = 3;

/// Convection coefficient `h = 9.7 + 5.33 v^0.8`, W/(m² K), `v` in m/s.
#[inline]
pub fn convection(v: f64) -> f64 {
    9.7 + 5.33 * v.abs().powf(0.8)
}

/// Palmgren's load-independent torque, N m, for kinematic viscosity `nu_cst` (cSt), speed
/// `n_rpm` and pitch diameter `dm` (m), factor `f0` (module notes: the N mm formula with the
/// units converted here).
pub fn palmgren_m0(f0: f64, nu_cst: f64, n_rpm: f64, dm: f64) -> f64 {
    let dm_mm = dm * 1e3;
    let vn = nu_cst * n_rpm.abs();
    let nmm = if vn >= 2000.0 {
        1e-7 * f0 * vn.powf(2.0 / 3.0) * dm_mm.powi(3)
    } else {
        1.6e-5 * f0 * dm_mm.powi(3)
    };
    nmm * 1e-3
}

/// Palmgren's equivalent load `P1` for radial load `fr`, axial `fa`, contact angle `alpha`.
pub fn palmgren_p1(fr: f64, fa: f64, alpha: f64) -> f64 {
    let (fr, fa) = (fr.abs(), fa.abs());
    let p = if alpha.abs() < 1e-6 {
        3.0 * fa - 0.1 * fr
    } else {
        0.9 * fa / alpha.tan() - 0.1 * fr
    };
    p.max(fr)
}

/// Values in a thermal memory block (see [`ThermalModel::advance`]).
pub const THERMAL_SLOTS: usize = 9;

/// Parameters of the friction and thermal model (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct ThermalParams {
    /// Palmgren `f0`.
    pub f0: f64,
    /// Palmgren `f1`.
    pub f1: f64,
    /// Oil kinematic viscosity, cSt.
    pub nu_cst: f64,
    /// Oil dynamic viscosity, Pa s (cage land shear).
    pub eta: f64,
    /// Spin friction coefficient `mu_s`.
    pub mu_spin: f64,
    /// Hysteresis loss fraction `alpha_h`.
    pub hysteresis: f64,
    /// Conductances to the ambient (shaft, housing, oil flow), W/K.
    pub g_shaft: f64,
    /// Outer ring to housing, W/K.
    pub g_housing: f64,
    /// Oil to ambient (flow), W/K.
    pub g_oil: f64,
    /// Oil heat capacity, J/K.
    pub c_oil: f64,
    /// Fixed ball–ring conductance per race, W/K (None: Holm constriction).
    pub g_contact: Option<f64>,
    /// Slow time step, s (thermal time).
    pub dt: f64,
    /// Thermal seconds per dynamic second.
    pub time_scale: f64,
    /// Factor on the growth's change of the clearance (0: off).
    pub growth: f64,
}

/// Losses at one instant, W, with their split into the nodes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Losses {
    /// Palmgren `M0 omega`.
    pub viscous: f64,
    /// Palmgren `M1 omega`.
    pub load: f64,
    /// Spin.
    pub spin: f64,
    /// Hysteresis.
    pub hysteresis: f64,
    /// Cage land shear.
    pub cage: f64,
    /// Heat into each node.
    pub heat: [f64; 4],
    /// Ball–ring conductance through the loaded contacts (inner, outer), W/K.
    pub contact_conductance: [f64; 2],
}

impl Losses {
    /// Total friction power, W.
    pub fn total(&self) -> f64 {
        self.viscous + self.load + self.spin + self.hysteresis + self.cage
    }
}

/// Per-ball sums gathered while the ring model evaluates (allocation-free).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactSums {
    /// Spin power at the inner and outer contacts, W.
    pub spin: [f64; 2],
    /// Hysteresis power at the inner and outer contacts, W.
    pub hysteresis: [f64; 2],
    /// Constriction conductances at the inner and outer contacts, W/K.
    pub conductance: [f64; 2],
}

/// The friction and thermal model of one bearing.
#[derive(Debug, Clone)]
pub struct ThermalModel {
    /// Parameters.
    pub p: ThermalParams,
    /// Heat capacities of the nodes, J/K.
    pub capacity: [f64; 4],
    /// Convection areas of inner ring, outer ring, balls, m².
    pub area: [f64; 3],
    /// Expansion coefficients (inner, outer, ball), 1/K.
    pub expansion: [f64; 3],
    /// Race contact diameters (inner, outer) and ball diameter, m.
    pub diameters: [f64; 3],
    /// Contacts at the nominal angle (inner, outer).
    pub contacts: [PointContact; 2],
    alpha: f64,
    dm: f64,
    d: f64,
    gamma: f64,
    /// `1 / (1/(4 k_b) + 1/(4 k_r))` per race: conductance per metre of `r_c`.
    k_contact: [f64; 2],
    cage_petroff: f64,
    cage_inner: bool,
}

impl ThermalModel {
    /// Build for bearing `b`.
    pub fn new(b: &Bearing, p: ThermalParams, contacts: [PointContact; 2]) -> Self {
        let alpha = b.nominal_contact_angle();
        let gamma = b.d * alpha.cos() / b.dm;
        let (di, d_o) = (b.dm * (1.0 - gamma), b.dm * (1.0 + gamma));
        let mb = b.ball_mass();
        let capacity = [
            b.inner_ring_mass * b.inner_material.heat_capacity,
            b.outer_ring_mass * b.outer_material.heat_capacity,
            b.z as f64 * mb * b.ball_material.heat_capacity,
            p.c_oil,
        ];
        let w = b.width;
        let area = [PI * di * w, PI * d_o * w, b.z as f64 * PI * b.d * b.d];
        let kb = b.ball_material.conductivity;
        let kc = |kr: f64| 1.0 / (0.25 / kb + 0.25 / kr);
        let c = &b.cage;
        let (r, inner) = match c.guidance {
            Guidance::OuterRing => (0.5 * c.outer_diameter, false),
            Guidance::InnerRing => (0.5 * c.inner_diameter, true),
            Guidance::Ball => (0.0, false),
        };
        let cage_petroff = if c.guide_clearance > 0.0 && r > 0.0 {
            2.0 * PI * p.eta * r.powi(3) * 0.25 * c.width / c.guide_clearance
        } else {
            0.0
        };
        ThermalModel {
            capacity,
            area,
            expansion: [
                b.inner_material.thermal_expansion,
                b.outer_material.thermal_expansion,
                b.ball_material.thermal_expansion,
            ],
            diameters: [di, d_o, b.d],
            contacts,
            alpha,
            dm: b.dm,
            d: b.d,
            gamma,
            k_contact: [
                kc(b.inner_material.conductivity),
                kc(b.outer_material.conductivity),
            ],
            cage_petroff,
            cage_inner: inner,
            p,
        }
    }

    /// `(omega_c, |omega_b|)`: cage speed and ball rotation in the cage frame at shaft
    /// speed `omega` (outer ring fixed, nominal angle).
    #[inline]
    pub fn speeds(&self, omega: f64) -> (f64, f64) {
        use crate::geometry::kinematics as kin;
        let wc = kin::cage_speed(self.gamma, omega, 0.0);
        let wb = kin::ball_spin_speed(self.d, self.dm, self.gamma, omega, 0.0);
        (wc, wb)
    }

    /// Ball rotation relative to the inner and outer race (see `crate::models::wear`).
    #[inline]
    pub fn relative_rolling(&self, omega: f64) -> [f64; 2] {
        let (wc, wb) = self.speeds(omega);
        [wb + (omega - wc).abs(), (wb - wc.abs()).abs()]
    }

    /// Add one ball carrying `q` at shaft speed `omega` to `sums`.
    #[inline]
    pub fn add_ball(&self, omega: f64, q: f64, sums: &mut ContactSums) {
        if q <= 0.0 {
            return;
        }
        let rel = self.relative_rolling(omega);
        let (_, wb) = self.speeds(omega);
        let v_roll = wb * 0.5 * self.d;
        let sa = self.alpha.sin().abs();
        for (r, c) in self.contacts.iter().enumerate() {
            let (a, b) = c.semi_axes(q);
            let ms = 3.0 * self.p.mu_spin * q * a * c.ellipse.e / 8.0;
            sums.spin[r] += ms * rel[r] * sa;
            let f = self.p.hysteresis * 3.0 / 16.0 * q * b / c.curvature.rx;
            sums.hysteresis[r] += f * v_roll;
            sums.conductance[r] += self.k_contact[r] * (a * b).sqrt();
        }
    }

    /// Losses at shaft speed `omega` with bearing reaction `wrench` and the per-ball sums.
    pub fn losses(&self, omega: f64, wrench: &[f64; 5], sums: &ContactSums) -> Losses {
        let w = omega.abs();
        let n_rpm = w * 60.0 / (2.0 * PI);
        let m0 = palmgren_m0(self.p.f0, self.p.nu_cst, n_rpm, self.dm);
        let fr = wrench[0].hypot(wrench[1]);
        let m1 = self.p.f1 * palmgren_p1(fr, wrench[2], self.alpha) * self.dm;
        let (wc, _) = self.speeds(omega);
        let w_cage = if self.cage_inner {
            (omega - wc).abs()
        } else {
            wc.abs()
        };
        let viscous = m0 * w;
        let load = m1 * w;
        let cage = self.cage_petroff * w_cage * w_cage;
        let spin = sums.spin[0] + sums.spin[1];
        let hyst = sums.hysteresis[0] + sums.hysteresis[1];
        let c_i = 0.5 * (sums.spin[0] + sums.hysteresis[0]);
        let c_o = 0.5 * (sums.spin[1] + sums.hysteresis[1]);
        let heat = [
            0.25 * load + c_i,
            0.25 * load + c_o,
            0.5 * load + c_i + c_o,
            viscous + cage,
        ];
        Losses {
            viscous,
            load,
            spin,
            hysteresis: hyst,
            cage,
            heat,
            contact_conductance: sums.conductance,
        }
    }

    /// Conductance matrix `G` (network Laplacian plus the ambient links on the diagonal)
    /// at shaft speed `omega`, and the ambient conductances.
    pub fn conductances(&self, omega: f64, l: &Losses) -> ([[f64; 4]; 4], [f64; 4]) {
        let (wc, wb) = self.speeds(omega);
        let [di, d_o, d] = self.diameters;
        let v = [
            (omega - wc).abs() * 0.5 * di,
            wc.abs() * 0.5 * d_o,
            wb * 0.5 * d,
        ];
        let mut g = [[0.0; 4]; 4];
        let mut link = |a: usize, b: usize, c: f64| {
            g[a][a] += c;
            g[b][b] += c;
            g[a][b] -= c;
            g[b][a] -= c;
        };
        let gc = match self.p.g_contact {
            Some(g) => [g, g],
            None => l.contact_conductance,
        };
        link(INNER, BALLS, gc[0]);
        link(OUTER, BALLS, gc[1]);
        for (k, node) in [INNER, OUTER, BALLS].into_iter().enumerate() {
            link(node, OIL, convection(v[k]) * self.area[k]);
        }
        let amb = [self.p.g_shaft, self.p.g_housing, 0.0, self.p.g_oil];
        for k in 0..4 {
            g[k][k] += amb[k];
        }
        (g, amb)
    }

    /// One implicit-Euler step of length `dt` of the temperature rises `theta` (K above
    /// ambient) with losses `l`: `(C/dt + G) theta' = C theta / dt + heat`. Returns the heat
    /// removed to the ambient during the step, J.
    pub fn step(&self, omega: f64, l: &Losses, theta: &mut [f64; 4], dt: f64) -> f64 {
        let (mut a, amb) = self.conductances(omega, l);
        let mut rhs = [0.0; 4];
        for k in 0..4 {
            a[k][k] += self.capacity[k] / dt;
            rhs[k] = self.capacity[k] * theta[k] / dt + l.heat[k];
        }
        let t = solve4(a, rhs);
        *theta = t;
        (0..4).map(|k| amb[k] * t[k]).sum::<f64>() * dt
    }

    /// Advance the network at a communication point `t` (s of simulated time) with losses
    /// `l` held since the last update: over the elapsed time times `time_scale`, in
    /// implicit-Euler steps of at most `dt` (at most 10^4 of them). `mem` is the thermal
    /// memory block ([`THERMAL_SLOTS`] values): the four node temperature rises (K), the
    /// time of the last update (s), energy generated and removed (J), the last power loss
    /// (W) and the clearance change (m); all are updated. Returns the node rises.
    pub fn advance(&self, omega: f64, l: &Losses, t: f64, mem: &mut [f64]) -> [f64; 4] {
        let mut theta = [mem[0], mem[1], mem[2], mem[3]];
        let elapsed = t - mem[4];
        if elapsed > 0.0 {
            let total = elapsed * self.p.time_scale;
            let nsub = (total / self.p.dt).ceil().clamp(1.0, 1e4);
            let h = total / nsub;
            let mut removed = 0.0;
            for _ in 0..nsub as usize {
                removed += self.step(omega, l, &mut theta, h);
            }
            mem[..4].copy_from_slice(&theta);
            mem[5] += l.total() * total;
            mem[6] += removed;
        }
        mem[4] = t;
        mem[7] = l.total();
        mem[8] = self.clearance_change(&theta);
        theta
    }

    /// Diametral growths `(u_i, u_o, u_b) = alpha_T dT d` of the inner race, outer race and
    /// ball at rises `theta`, m.
    pub fn growth(&self, theta: &[f64; 4]) -> [f64; 3] {
        [
            self.expansion[0] * theta[INNER] * self.diameters[0],
            self.expansion[1] * theta[OUTER] * self.diameters[1],
            self.expansion[2] * theta[BALLS] * self.diameters[2],
        ]
    }

    /// Change of the diametral clearance, m: `u_o - u_i - 2 u_b` times the growth factor.
    pub fn clearance_change(&self, theta: &[f64; 4]) -> f64 {
        if self.p.growth == 0.0 {
            return 0.0;
        }
        let [ui, uo, ub] = self.growth(theta);
        (uo - ui - 2.0 * ub) * self.p.growth
    }
}

/// Solve a 4x4 system by Gaussian elimination with partial pivoting.
#[allow(clippy::needless_range_loop)]
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> [f64; 4] {
    for c in 0..4 {
        let p = (c..4)
            .max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))
            .unwrap_or(c);
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..4 {
            let f = a[r][c] / a[c][c];
            for k in c..4 {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; 4];
    for r in (0..4).rev() {
        let s: f64 = (r + 1..4).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palmgren_units_and_branches() {
        // 1e-7 * 2 * (54*6000)^(2/3) * 54^3 N mm.
        let m = palmgren_m0(2.0, 54.0, 6000.0, 0.054);
        let want = 1e-7 * 2.0 * (54.0f64 * 6000.0).powf(2.0 / 3.0) * 54f64.powi(3) * 1e-3;
        assert!((m - want).abs() < 1e-15);
        assert!((palmgren_m0(1.0, 10.0, 100.0, 0.01) - 1.6e-5 * 1000.0 * 1e-3).abs() < 1e-15);
        assert_eq!(palmgren_p1(100.0, 0.0, 0.0), 100.0);
        assert!((palmgren_p1(100.0, 100.0, 0.0) - 290.0).abs() < 1e-12);
    }

    #[test]
    fn solve4_inverts() {
        let a = [
            [4.0, -1.0, 0.0, 0.5],
            [-1.0, 5.0, -2.0, 0.0],
            [0.0, -2.0, 6.0, -1.0],
            [0.5, 0.0, -1.0, 3.0],
        ];
        let x = solve4(a, [1.0, 2.0, 3.0, 4.0]);
        for r in 0..4 {
            let s: f64 = (0..4).map(|k| a[r][k] * x[k]).sum();
            assert!((s - [1.0, 2.0, 3.0, 4.0][r]).abs() < 1e-12);
        }
    }
}
