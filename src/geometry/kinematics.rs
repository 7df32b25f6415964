//! Rigid-body rolling kinematics and the characteristic frequencies (docs/physics.md §1;
//! Harris & Kotzalas Vol. 1 ch. 8). Pure rolling, no skid.

use super::bearing::Bearing;
use serde::Serialize;
use std::f64::consts::PI;

/// Kinematic speeds (rad/s) and characteristic frequencies (Hz).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Kinematics {
    /// `gamma = D cos(alpha) / dm`.
    pub gamma: f64,
    /// Cage (orbital) speed, rad/s.
    pub cage_speed: f64,
    /// Ball spin speed about its own axis, relative to the cage, rad/s (magnitude).
    pub ball_spin_speed: f64,
    /// Fundamental train frequency (cage rotation), Hz.
    pub ftf: f64,
    /// Ball-pass frequency over an outer-race point, Hz (= varying-compliance frequency
    /// when the outer ring is fixed).
    pub bpfo: f64,
    /// Ball-pass frequency over an inner-race point, Hz.
    pub bpfi: f64,
    /// Ball spin frequency, Hz (a ball defect strikes at twice this).
    pub bsf: f64,
}

/// `gamma = D cos(alpha) / dm` at contact angle `alpha`.
#[inline]
pub fn gamma(b: &Bearing, alpha: f64) -> f64 {
    b.d * alpha.cos() / b.dm
}

/// Kinematic (pure-rolling) cage speed, rad/s, with inner-ring speed `omega_i` and
/// outer-ring speed `omega_o` (rad/s, same sign convention) and `gamma = D cos(alpha) / dm`:
/// `(omega_i (1 - gamma) + omega_o (1 + gamma)) / 2` (Harris & Kotzalas Vol. 1 §8.2; with
/// the outer ring fixed, `omega_i (1 - gamma) / 2`). The one place this is written.
#[inline]
pub fn cage_speed(gamma: f64, omega_i: f64, omega_o: f64) -> f64 {
    0.5 * (omega_i * (1.0 - gamma) + omega_o * (1.0 + gamma))
}

/// Kinematic ball spin speed about its own axis relative to the cage, rad/s (magnitude):
/// `dm / (2 D) (1 - gamma²) |omega_i - omega_o|` (Harris & Kotzalas Vol. 1 §8.2), for ball
/// diameter `d` on pitch diameter `dm`.
#[inline]
pub fn ball_spin_speed(d: f64, dm: f64, gamma: f64, omega_i: f64, omega_o: f64) -> f64 {
    dm / (2.0 * d) * (1.0 - gamma * gamma) * (omega_i - omega_o).abs()
}

/// Kinematics at contact angle `alpha` with inner-ring speed `omega_i` and outer-ring
/// speed `omega_o` (rad/s, same sign convention); speeds from [`cage_speed`] and
/// [`ball_spin_speed`].
pub fn kinematics_at(b: &Bearing, alpha: f64, omega_i: f64, omega_o: f64) -> Kinematics {
    let gamma = gamma(b, alpha);
    let cage = cage_speed(gamma, omega_i, omega_o);
    let spin = ball_spin_speed(b.d, b.dm, gamma, omega_i, omega_o);
    let z = b.z as f64;
    Kinematics {
        gamma,
        cage_speed: cage,
        ball_spin_speed: spin,
        ftf: cage.abs() / (2.0 * PI),
        bpfo: z * (cage - omega_o).abs() / (2.0 * PI),
        bpfi: z * (omega_i - cage).abs() / (2.0 * PI),
        bsf: spin / (2.0 * PI),
    }
}

/// Kinematic cage speed for the nominal contact angle, outer ring fixed:
/// `omega_c = omega (1 - gamma) / 2` (docs/physics.md §1).
pub fn nominal_cage_speed(b: &Bearing, omega: f64) -> f64 {
    cage_speed(gamma(b, b.nominal_contact_angle()), omega, 0.0)
}

/// Kinematics at the nominal contact angle with the outer ring fixed.
pub fn kinematics(b: &Bearing, omega_i: f64) -> Kinematics {
    kinematics_at(b, b.nominal_contact_angle(), omega_i, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::presets::preset;

    /// CWRU 6205-2RS drive-end orders (docs/physics.md §N5.1), which follow exactly from
    /// D = 0.3126 in, dm = 1.537 in: FTF 0.39831, BPFO 3.58478, BPFI 5.41522, 2 BSF 4.71344.
    #[test]
    fn cwru_6205_orders() {
        let mut s = preset("6205").unwrap();
        s.ball_diameter_mm = 0.3126 * 25.4;
        s.pitch_diameter_mm = 1.537 * 25.4;
        let b = s.build().unwrap();
        let k = kinematics(&b, 2.0 * PI); // 1 Hz shaft
        assert!((k.ftf - 0.39831).abs() < 5e-5, "{}", k.ftf);
        assert!((k.bpfo - 3.58478).abs() < 5e-5, "{}", k.bpfo);
        assert!((k.bpfi - 5.41522).abs() < 5e-5, "{}", k.bpfi);
        assert!((2.0 * k.bsf - 4.71344).abs() < 5e-5, "{}", k.bsf);
    }

    #[test]
    fn rotating_outer_ring_only() {
        // Inner fixed, outer turning: the cage turns at omega_o (1 + gamma)/2 and BPFO + BPFI
        // still equals Z |omega_i - omega_o| / (2 pi).
        let b = preset("209").unwrap().build().unwrap();
        let w = 100.0;
        let k = kinematics_at(&b, 0.0, 0.0, w);
        assert!((k.cage_speed - w * (1.0 + k.gamma) / 2.0).abs() < 1e-12);
        assert!((k.bpfo + k.bpfi - 9.0 * w / (2.0 * PI)).abs() < 1e-9);
        // Both rings at the same speed: a rigid body, nothing rolls.
        let k = kinematics_at(&b, 0.0, w, w);
        assert!((k.cage_speed - w).abs() < 1e-12 && k.bpfo.abs() < 1e-12 && k.bsf == 0.0);
    }
}
