//! Plausibility limits of the inputs: values that no bearing of a given geometry can have
//! are refused when they are set (scene, C ABI, FMI all pass through
//! [`Limits::check`]), so every level answers the same input the same way and no level is
//! asked to integrate a ring a metre off centre.
//!
//! The limits are derived from the bearing, each generous by design (they reject the
//! impossible, not the unusual):
//!
//! - **Elastic range of a contact.** Hertz's law holds while the contact stays elastic. The
//!   largest ball load taken as plausible, `Q*`, is the one whose peak Hertz pressure
//!   `p0 = 3Q/(2 pi a b)` reaches [`P_CONTACT_MAX`] = 7.5 GPa on the more heavily stressed
//!   race: the Vickers hardness of through-hardened bearing steel (about 750 HV at 62 HRC),
//!   the pressure at which an indentation is fully plastic (Johnson, *Contact Mechanics*,
//!   1985, §6.2: full plasticity at a mean pressure `p_m ≈ 3 Y ≈ H`; here the peak, so the
//!   mean is still below H), 1.8 times the 4.2 GPa that ISO 76 allows at rest and 1.6 times
//!   the highest peak of the stability campaign (4.7 GPa, docs/stability.md). The matching total approach of one ball is `delta* = delta_i(Q*) + delta_o(Q*)`
//!   (Harris & Kotzalas, Vol. 1 ch. 7: the approaches in series add).
//! - **Displacements and tilts.** With the inner groove curvature centre offset
//!   `(A1, A2)` (axial, radial) from the outer one at zero displacement
//!   ([`Bearing::reference_groove_offset`]) and `A = (f_i + f_o - 1) D`, the most loaded
//!   ball is compressed by `sqrt((A2 + r)² + (A1 + z)²) - A`; the limit on each coordinate
//!   alone is the value that makes this `delta*`:
//!   `r* = sqrt((A + delta*)² - A1²) - A2` (radial x and y; for a deep-groove bearing
//!   `Pd/2 + delta*`), `z* = sqrt((A + delta*)² - A2²) - A1` (axial, either sign), and a tilt
//!   moving the inner groove centres (radius `Ri`) axially by `z*`: `theta* = z*/Ri`.
//! - **Speed.** A spinning ring bursts when its hoop stress `rho v²` (thin rotating ring,
//!   Timoshenko, *Strength of Materials*, Part II, §64) reaches the tensile strength, taken
//!   as [`SIGMA_RING_MAX`] = 2.5 GPa (through-hardened 52100 / 100Cr6: 2.0–2.4 GPa). At the
//!   inner raceway radius `(dm - D)/2` that gives `omega* = sqrt(sigma/rho_i) / ((dm - D)/2)`;
//!   the tilt rates are bounded by `omega*` and the translation speeds by the same rim speed
//!   `v* = sqrt(sigma/rho_i)`.
//! - **Loads.** No load beyond every ball at `Q*`: `|F| <= Z Q*` for the forces,
//!   `|M| <= Z Q* Ri` for the moments.

use super::variables;
use crate::contact::hertz::BallRaceContacts;
use crate::error::{Error, Result};
use crate::geometry::element::Element;
use crate::geometry::roller::RollerBearing;
use crate::geometry::Bearing;

/// Peak Hertz pressure taken as the end of the elastic range of a ball–race contact, Pa.
pub const P_CONTACT_MAX: f64 = 7.5e9;

/// Hoop stress taken as the burst limit of a spinning inner ring, Pa.
pub const SIGMA_RING_MAX: f64 = 2.5e9;

/// Smallest regularising slip speed (declared beside the traction laws).
pub use crate::contact::traction::SLIP_SPEED_MIN;

/// Plausible ranges of a bearing's inputs (symmetric: `|value| <= limit`), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest ball load, N (`Q*`).
    pub ball_load: f64,
    /// Largest approach of one ball, m (`delta*`).
    pub approach: f64,
    /// Radial displacement x or y, m.
    pub radial: f64,
    /// Axial displacement z, m.
    pub axial: f64,
    /// Tilt rx or ry, rad.
    pub tilt: f64,
    /// Translation speed vx, vy, vz, m/s.
    pub speed: f64,
    /// Shaft speed and tilt rates, rad/s.
    pub omega: f64,
    /// External force, N.
    pub force: f64,
    /// External moment, N m.
    pub moment: f64,
}

impl Limits {
    /// The limits of bearing `b` (see the module documentation for each formula).
    pub fn of(b: &Bearing) -> Limits {
        if let Element::Roller(r) = &b.element {
            return Self::of_rollers(b, r);
        }
        let c = BallRaceContacts::new(b, b.nominal_contact_angle());
        // p0 grows as Q^(1/3): Q* = (p_max / p0(1 N))³ on the worse race.
        let q_at = |p1: f64| (P_CONTACT_MAX / p1).powi(3);
        let q = q_at(c.inner.peak_pressure(1.0)).min(q_at(c.outer.peak_pressure(1.0)));
        let approach = c.inner.deflection(q) + c.outer.deflection(q);
        let a = b.a();
        let (a1, a2) = b.reference_groove_offset();
        let reach = a + approach;
        let radial = (reach * reach - a1 * a1).sqrt() - a2;
        let axial = (reach * reach - a2 * a2).sqrt() - a1;
        let ri = b.inner_groove_centre_radius();
        let rim = (SIGMA_RING_MAX / b.inner_material.density).sqrt();
        let omega = rim / (0.5 * (b.dm - b.d));
        let force = b.z as f64 * q;
        Limits {
            ball_load: q,
            approach,
            radial,
            axial,
            tilt: axial / ri,
            speed: rim,
            omega,
            force,
            moment: force * ri,
        }
    }

    /// The limits of a roller bearing: the elastic range of a line contact (the load per
    /// length whose line-Hertz peak pressure `p0 = sqrt(q' E'/(2 pi R))` reaches
    /// [`P_CONTACT_MAX`] on the worse race, over the effective length), the matching approach
    /// of the roller's load law `Q = c_L delta^(10/9)` (docs/physics.md §R1), radial
    /// `Pd/2 + delta*`; axially a cylindrical roller is free on its raceway, so the axial
    /// limit is half the effective length (the raceway leaving the roller), and a tilt
    /// brings the roller's end to `delta*` at `(Pd/2 + delta*)/(L_we/2)`. Speeds as for balls.
    fn of_rollers(b: &Bearing, r: &RollerBearing) -> Limits {
        use crate::contact::lamina::{line_hertz, roller_constant};
        let per_len = |rr: f64, e: f64| (P_CONTACT_MAX / line_hertz(1.0, rr, e).1).powi(2);
        let q_len = per_len(r.reduced_radius_inner(), r.e_prime_inner())
            .min(per_len(r.reduced_radius_outer(), r.e_prime_outer()));
        let q = q_len * r.lwe;
        let g = r.line_geometry();
        let approach = (q / roller_constant(g.lwe, g.e_prime)).powf(0.9);
        let radial = 0.5 * r.pd + approach;
        let rim = (SIGMA_RING_MAX / b.inner_material.density).sqrt();
        let force = b.z as f64 * q;
        Limits {
            ball_load: q,
            approach,
            radial,
            axial: 0.5 * r.lwe,
            tilt: radial / (0.5 * r.lwe),
            speed: rim,
            omega: rim / (0.5 * (b.dm - b.d)),
            force,
            moment: force * 0.5 * b.dm,
        }
    }

    /// The limit of input variable `name` (`None`: no limit, or not an input).
    pub fn of_variable(&self, name: &str) -> Option<f64> {
        Some(match name {
            "shaft.x" | "shaft.y" => self.radial,
            "shaft.z" => self.axial,
            "shaft.rx" | "shaft.ry" => self.tilt,
            "shaft.vx" | "shaft.vy" | "shaft.vz" => self.speed,
            "shaft.wx" | "shaft.wy" | "shaft.omega" => self.omega,
            "load.x" | "load.y" | "load.z" => self.force,
            "load.mx" | "load.my" => self.moment,
            _ => return None,
        })
    }

    /// The limit of the input in table slot `i` (below `N_INPUT_SLOTS`), as
    /// [`Limits::of_variable`] gives it for that slot's name, without comparing strings: the
    /// step's input check asks it for every input of every step.
    /// `slot_limits_match_the_names` checks the two against each other.
    #[inline]
    pub fn of_slot(&self, i: usize) -> Option<f64> {
        use super::{I_LOAD, I_OMEGA, I_Q, I_V};
        Some(match i {
            _ if i == I_Q || i == I_Q + 1 => self.radial,
            _ if i == I_Q + 2 => self.axial,
            _ if i == I_Q + 3 || i == I_Q + 4 => self.tilt,
            _ if (I_V..I_V + 3).contains(&i) => self.speed,
            _ if i == I_V + 3 || i == I_V + 4 || i == I_OMEGA => self.omega,
            _ if (I_LOAD..I_LOAD + 3).contains(&i) => self.force,
            _ if i == I_LOAD + 3 || i == I_LOAD + 4 => self.moment,
            _ => return None,
        })
    }

    /// Is `value` finite and within the limit of the input in table slot `i`?
    #[inline]
    pub fn allows_slot(&self, i: usize, value: f64) -> bool {
        value.is_finite() && self.of_slot(i).is_none_or(|lim| value.abs() <= lim)
    }

    /// Is `value` finite and within the limit of input `name`? (No allocation: the hot
    /// path asks this and builds the message only on refusal.)
    pub fn allows(&self, name: &str, value: f64) -> bool {
        value.is_finite() && self.of_variable(name).is_none_or(|lim| value.abs() <= lim)
    }

    /// Refuse `value` for input `name` outside its limit; the message names `field` (the
    /// variable, or its scene path), the value, the range and where it comes from.
    pub fn check(&self, field: &str, name: &str, value: f64) -> Result<()> {
        if !value.is_finite() {
            return Err(Error::invalid(field, value, "a finite number"));
        }
        match self.of_variable(name) {
            Some(lim) if value.abs() > lim => {
                let unit = variables::by_name(name).map_or("", |v| v.unit);
                Err(Error::invalid(
                    field,
                    format!("{value:e} {unit}"),
                    format!(
                        "[{:.4e}, {lim:.4e}] {unit}: {} for this bearing (`raceway scene --explain`, plausibility limits)",
                        -lim,
                        why(name)
                    ),
                ))
            }
            _ => Ok(()),
        }
    }

    /// The limits as text, one line per input, for `raceway scene --explain` and reports.
    pub fn table(&self) -> String {
        let mut s = String::new();
        for v in variables::SCALARS {
            if let Some(lim) = self.of_variable(v.name) {
                s.push_str(&format!(
                    "  |{}| <= {lim:.4e} {}  ({})\n",
                    v.name,
                    v.unit,
                    why(v.name)
                ));
            }
        }
        s
    }
}

/// Where the limit of input `name` comes from (one line).
pub fn why(name: &str) -> &'static str {
    match name {
        "shaft.x" | "shaft.y" => {
            "radial play plus the approach at which the most loaded ball's Hertz pressure reaches 7.5 GPa"
        }
        "shaft.z" => "axial play plus the approach at which a ball's Hertz pressure reaches 7.5 GPa",
        "shaft.rx" | "shaft.ry" => {
            "the tilt that moves the inner groove axially by the axial limit"
        }
        "shaft.vx" | "shaft.vy" | "shaft.vz" => {
            "the rim speed at which a steel ring bursts (rho v² = 2.5 GPa)"
        }
        "shaft.wx" | "shaft.wy" | "shaft.omega" => {
            "the inner ring's burst speed (rho v² = 2.5 GPa at the inner raceway)"
        }
        "load.x" | "load.y" | "load.z" => "every ball at the 7.5 GPa load",
        "load.mx" | "load.my" => "every ball at the 7.5 GPa load on the inner groove radius",
        _ => "",
    }
}

/// The rules, for `raceway scene --explain` (numbers depend on the bearing).
pub const EXPLAIN: &str = "\
Plausibility limits (checked on inputs.initial, on every set_real through the C ABI and
FMI, on the inputs at the end of each step, and on the [run] ramp, orbit and rotating load;
derived from the bearing; the error names the field, the value and the range):
  shaft.x, shaft.y     |q| <= sqrt((A + d*)^2 - A1^2) - A2   (deep groove: Pd/2 + d*)
  shaft.z              |z| <= sqrt((A + d*)^2 - A2^2) - A1
  shaft.rx, shaft.ry   |theta| <= (axial limit) / Ri
  shaft.omega, wx, wy  |w| <= sqrt(2.5 GPa / rho_inner) / ((dm - D)/2)   (ring burst)
  shaft.vx, vy, vz     |v| <= sqrt(2.5 GPa / rho_inner)
  load.x, load.y, load.z   |F| <= Z Q*;   load.mx, load.my   |M| <= Z Q* Ri
  traction and pocket slip speeds v_s >= 1e-6 m/s
where Q* is the ball load whose peak Hertz pressure reaches 7.5 GPa on the worse race (fully
plastic steel), d* the two contacts' approach at Q*, A = (fi + fo - 1) D, (A1, A2) the
axial and radial groove-centre offsets at zero displacement, Ri the inner groove-centre
radius. `raceway bearings` data and these rules give the numbers; a component reports its
own with Limits::of(bearing).
";

#[cfg(test)]
mod tests {
    use super::*;

    fn limits(name: &str) -> (Bearing, Limits) {
        let b = crate::geometry::preset(name).unwrap().build().unwrap();
        let l = Limits::of(&b);
        (b, l)
    }

    #[test]
    fn deep_groove_radial_limit_is_half_the_play_plus_the_elastic_approach() {
        let (b, l) = limits("6205");
        // Deep groove: A1 = 0, A2 = A - Pd/2, so r* = A + delta* - A2 = Pd/2 + delta*.
        assert!((l.radial - (0.5 * b.pd + l.approach)).abs() < 1e-12);
        // The limit load gives 7.5 GPa on the worse race, exactly.
        let c = BallRaceContacts::new(&b, 0.0);
        let p = c
            .inner
            .peak_pressure(l.ball_load)
            .max(c.outer.peak_pressure(l.ball_load));
        assert!((p / P_CONTACT_MAX - 1.0).abs() < 1e-9, "{p}");
        // Tens of µm of approach for a 8 mm ball, not millimetres.
        assert!(l.approach > 10e-6 && l.approach < 300e-6, "{}", l.approach);
        // The level disagreement of issue 21 (shaft.y = -1 mm) is outside for every level.
        assert!(l.check("shaft.y", "shaft.y", -1e-3).is_err());
        assert!(l.check("shaft.y", "shaft.y", -10e-6).is_ok());
    }

    #[test]
    fn slot_limits_match_the_names() {
        // Distinct values per kind, so a slot that reads the wrong kind is caught.
        let l = Limits {
            radial: 1.0,
            axial: 2.0,
            tilt: 3.0,
            speed: 4.0,
            omega: 5.0,
            force: 6.0,
            moment: 7.0,
            ..limits("6205").1
        };
        let table = crate::component::variables::SCALARS;
        for (i, v) in table.iter().enumerate() {
            let by_name = l.of_variable(v.name);
            if i < crate::component::N_INPUT_SLOTS {
                assert_eq!(l.of_slot(i), by_name, "slot {i} ({})", v.name);
                assert!(
                    by_name.is_some(),
                    "input slot {i} ({}) has no limit",
                    v.name
                );
            } else {
                assert_eq!(by_name, None, "{} past the input slots has a limit", v.name);
            }
        }
    }

    #[test]
    fn shipped_operating_points_lie_well_inside() {
        // 7004 at 120 000 rpm (the fastest shipped scene) and its 43 µm axial offset.
        let (_, l) = limits("7004");
        assert!(l.omega > 2.0 * 120_000.0 * std::f64::consts::PI / 30.0);
        assert!(l.axial > 2.0 * 43.3e-6, "{}", l.axial);
        // The 6205 of study [1] at its 10 µm radial offset, 10 kN on the ring.
        let (_, l) = limits("6205");
        assert!(l.radial > 3.0 * 10e-6 && l.force > 10e3);
    }

    #[test]
    fn message_names_field_value_and_range() {
        let (_, l) = limits("7004");
        let e = l
            .check("inputs.initial.shaft.x", "shaft.x", -1.0)
            .unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains("inputs.initial.shaft.x") && m.contains("-1e0 m"),
            "{m}"
        );
        assert!(m.contains(&format!("{:.4e}", l.radial)), "{m}");
    }
}
