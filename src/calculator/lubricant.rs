//! Lubrication inputs: an oil by name → its viscosity at the operating temperature → ISO 281's
//! viscosity ratio κ.
//!
//! - **ISO VG grades** (ISO 3448:1992): the grade is the mid-point kinematic viscosity at 40 °C
//!   in mm²/s (VG 2 → 2.2, VG 3 → 3.2, VG 5 → 4.6, VG 7 → 6.8, then 10, 15, 22, …, 3200; the
//!   grade allows ±10 %). The mid-point is used.
//! - **Viscosity index** (ASTM D2270-10, identical in substance to ISO 2909): for a 100 °C
//!   viscosity `Y`, `L` and `H` are the 40 °C viscosities of the reference oils of VI 0 and 100
//!   with that `Y` (the standard's Table 1, linearly interpolated, for `2 ≤ Y ≤ 70` mm²/s; its
//!   equations `L = 0.8353 Y² + 14.67 Y − 216`, `H = 0.1684 Y² + 11.85 Y − 97` above 70).
//!   With `U` the oil's 40 °C viscosity: `VI = 100 (L − U)/(L − H)` when `U ≥ H` (Procedure A,
//!   VI ≤ 100), otherwise `VI = (10^N − 1)/0.00715 + 100` with `N = (log H − log U)/log Y`
//!   (Procedure B). An oil given by grade and VI has its `Y` found by inverting this
//!   (bisection: VI rises with `Y` at a fixed `U`). VI is not defined for `Y < 2` mm²/s.
//! - **Viscosity at temperature** (ASTM D341, Walther's equation):
//!   `log log (ν + 0.7) = A − B log T` (ν in mm²/s, `T` in K, decimal logarithms) through the
//!   40 °C and 100 °C points. The `+ 0.7` form is the one D341 gives for ν ≥ 2 mm²/s; its
//!   low-viscosity corrections are not applied, so a temperature where ν < 2 mm²/s is refused.
//! - **Reference viscosity** (ISO 281:2007, §6.5.1, from the SKF relation it standardises):
//!   `ν1 = 45 000 n^−0.83 Dpw^−0.5` for `n < 1000` rpm and `ν1 = 4 500 n^−0.5 Dpw^−0.5` for
//!   `n ≥ 1000` rpm (mm²/s, `n` in rpm, `Dpw` in mm); `κ = ν/ν1`. The two branches differ by
//!   2.3 % at 1000 rpm (the standard's own step). At standstill κ is not defined.
//!
//! Not offered: the project's `study2` lubricant (its viscosity is given at an unstated
//! temperature, so it has no 40 °C value to place on this scale).

use super::vi_table::ROWS;
use crate::error::{Error, Result};

/// ISO 3448 viscosity grades and their mid-point kinematic viscosity at 40 °C, mm²/s.
pub const ISO_VG: [(u32, f64); 20] = [
    (2, 2.2),
    (3, 3.2),
    (5, 4.6),
    (7, 6.8),
    (10, 10.0),
    (15, 15.0),
    (22, 22.0),
    (32, 32.0),
    (46, 46.0),
    (68, 68.0),
    (100, 100.0),
    (150, 150.0),
    (220, 220.0),
    (320, 320.0),
    (460, 460.0),
    (680, 680.0),
    (1000, 1000.0),
    (1500, 1500.0),
    (2200, 2200.0),
    (3200, 3200.0),
];

/// The viscosity index a grade gets when none is given: 95, a conventional solvent-refined
/// mineral oil (the reference oil of ISO 15312 is a mineral oil; this is a default, not data).
pub const DEFAULT_VI: f64 = 95.0;

/// `L` and `H` of ASTM D2270 for a 100 °C viscosity `y` (mm²/s), `None` below 2 mm²/s.
pub fn reference_oils(y: f64) -> Option<(f64, f64)> {
    if y.is_nan() || y < 2.0 {
        return None;
    }
    if y > 70.0 {
        return Some((
            0.8353 * y * y + 14.67 * y - 216.0,
            0.1684 * y * y + 11.85 * y - 97.0,
        ));
    }
    let k = ROWS.partition_point(|r| r.0 <= y).clamp(1, ROWS.len() - 1);
    let (lo, hi) = (ROWS[k - 1], ROWS[k]);
    let t = (y - lo.0) / (hi.0 - lo.0);
    Some((lo.1 + t * (hi.1 - lo.1), lo.2 + t * (hi.2 - lo.2)))
}

/// ASTM D2270 viscosity index from the kinematic viscosities at 40 and 100 °C (mm²/s),
/// unrounded.
pub fn viscosity_index(nu40_mm2s: f64, nu100_mm2s: f64) -> Result<f64> {
    if !(nu40_mm2s.is_finite() && nu40_mm2s > 0.0) {
        return Err(Error::invalid("oil.nu40_mm2s", nu40_mm2s, "> 0"));
    }
    let (l, h) = reference_oils(nu100_mm2s).ok_or_else(|| {
        Error::invalid(
            "oil.nu100_mm2s",
            nu100_mm2s,
            ">= 2 mm²/s (ASTM D2270 does not define VI below)",
        )
    })?;
    let u = nu40_mm2s;
    Ok(if u >= h {
        100.0 * (l - u) / (l - h)
    } else {
        let n = (h.log10() - u.log10()) / nu100_mm2s.log10();
        (10f64.powf(n) - 1.0) / 0.00715 + 100.0
    })
}

/// The 100 °C viscosity (mm²/s) of an oil of 40 °C viscosity `nu40_mm2s` and index `vi`: the
/// inverse of [`viscosity_index`] by bisection on `Y`.
pub fn nu100_from_vi(nu40_mm2s: f64, vi: f64) -> Result<f64> {
    if !(vi.is_finite() && (-100.0..=400.0).contains(&vi)) {
        return Err(Error::invalid("oil.viscosity_index", vi, "-100 ..= 400"));
    }
    let f = |y: f64| viscosity_index(nu40_mm2s, y).map(|v| v - vi);
    let (mut lo, mut hi) = (2.0, nu40_mm2s.max(2.0));
    if f(lo)? > 0.0 {
        return Err(Error::invalid(
            "oil.viscosity_index",
            vi,
            format!(
                "an index this oil reaches with a 100 °C viscosity of at least 2 mm²/s (ASTM D2270's range); at 2 mm²/s its index is already {:.0}",
                f(lo)? + vi
            ),
        ));
    }
    // The 100 °C viscosity is below the 40 °C one for any real oil; VI rises with Y.
    if f(hi)? < 0.0 {
        return Err(Error::invalid(
            "oil.viscosity_index",
            vi,
            "an index reached with a 100 °C viscosity below the 40 °C one",
        ));
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid)? < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-12 * hi {
            break;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// An oil on the Walther (ASTM D341) line through its 40 °C and 100 °C viscosities.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Oil {
    /// How the user named it, e.g. `ISO VG 68`.
    pub name: String,
    /// Kinematic viscosity at 40 °C, m²/s.
    pub nu40: f64,
    /// Kinematic viscosity at 100 °C, m²/s.
    pub nu100: f64,
    /// ASTM D2270 viscosity index.
    pub viscosity_index: f64,
}

/// `log10 log10 (ν + 0.7)` with ν in mm²/s.
fn walther_z(nu_mm2s: f64) -> f64 {
    (nu_mm2s + 0.7).log10().log10()
}

impl Oil {
    /// An ISO VG grade (its mid-point at 40 °C) with a viscosity index.
    pub fn iso_vg(grade: u32, vi: f64) -> Result<Oil> {
        let nu40 = ISO_VG
            .iter()
            .find(|g| g.0 == grade)
            .map(|g| g.1)
            .ok_or_else(|| unknown(&format!("VG {grade}")))?;
        let nu100 = nu100_from_vi(nu40, vi)?;
        Ok(Oil {
            name: format!("ISO VG {grade}"),
            nu40: nu40 * 1e-6,
            nu100: nu100 * 1e-6,
            viscosity_index: vi,
        })
    }

    /// An oil from its measured viscosities at 40 and 100 °C (mm²/s).
    pub fn measured(name: &str, nu40_mm2s: f64, nu100_mm2s: f64) -> Result<Oil> {
        if nu100_mm2s.is_nan() || nu100_mm2s >= nu40_mm2s {
            return Err(Error::invalid(
                "oil.nu100_mm2s",
                nu100_mm2s,
                format!("< the 40 °C viscosity {nu40_mm2s} mm²/s"),
            ));
        }
        let vi = viscosity_index(nu40_mm2s, nu100_mm2s)?;
        Ok(Oil {
            name: name.to_string(),
            nu40: nu40_mm2s * 1e-6,
            nu100: nu100_mm2s * 1e-6,
            viscosity_index: vi,
        })
    }

    /// An oil by name: `VG68`, `ISO VG 68`, `vg 68` (case and spaces do not matter), with
    /// a viscosity index (default [`DEFAULT_VI`]).
    pub fn by_name(name: &str, vi: Option<f64>) -> Result<Oil> {
        let key: String = name
            .chars()
            .filter(|c| !c.is_whitespace() && *c != '-' && *c != '_')
            .collect::<String>()
            .to_ascii_lowercase();
        let digits = key
            .strip_prefix("isovg")
            .or_else(|| key.strip_prefix("vg"))
            .ok_or_else(|| unknown(name))?;
        let grade: u32 = digits.parse().map_err(|_| unknown(name))?;
        Oil::iso_vg(grade, vi.unwrap_or(DEFAULT_VI)).map_err(|e| match e {
            Error::Unknown { .. } => unknown(name),
            other => other,
        })
    }

    /// Kinematic viscosity at `t_c` °C, m²/s (Walther through the 40 and 100 °C points).
    pub fn nu_at(&self, t_c: f64) -> Result<f64> {
        if !(t_c.is_finite() && t_c > -60.0 && t_c < 250.0) {
            return Err(Error::invalid("oil.temperature_c", t_c, "-60 < T < 250 °C"));
        }
        let (x1, x2) = ((40.0f64 + 273.15).log10(), (100.0f64 + 273.15).log10());
        let (z1, z2) = (walther_z(self.nu40 * 1e6), walther_z(self.nu100 * 1e6));
        let b = (z1 - z2) / (x2 - x1);
        let z = z1 - b * ((t_c + 273.15).log10() - x1);
        let nu = 10f64.powf(10f64.powf(z)) - 0.7;
        if nu < 2.0 {
            return Err(Error::invalid(
                "oil.temperature_c",
                t_c,
                format!(
                    "a temperature where {} stays at or above 2 mm²/s (ASTM D341's simple form; here {nu:.2} mm²/s)",
                    self.name
                ),
            ));
        }
        Ok(nu * 1e-6)
    }
}

fn unknown(name: &str) -> Error {
    Error::Unknown {
        what: "oil (--oil / oil)",
        name: name.to_string(),
        known: ISO_VG.iter().map(|g| format!("VG{}", g.0)).collect(),
    }
}

/// ISO 281:2007's reference (rated) viscosity ν1 (§6.5.1, as SKF's catalogue restates it:
/// `45 000 n^-0.83 dm^-0.5` mm²/s for `n < 1000` rpm, `4 500 n^-0.5 dm^-0.5` at and above, with
/// `dm` the bearing's **mean diameter** `(d + D)/2` in mm, not its pitch diameter:
/// [`mean_diameter`]), m²/s, for `dm` in m at `speed_rpm`; `None` at standstill.
pub fn nu1(dm: f64, speed_rpm: f64) -> Option<f64> {
    let n = speed_rpm.abs();
    if !(n > 0.0 && n.is_finite() && dm > 0.0) {
        return None;
    }
    let d = dm * 1e3;
    let v = if n < 1000.0 {
        45000.0 * n.powf(-0.83) * d.powf(-0.5)
    } else {
        4500.0 * n.powf(-0.5) * d.powf(-0.5)
    };
    Some(v * 1e-6)
}

/// ISO 281's mean diameter `(d + D)/2` of a bearing (m), the `dm` of [`nu1`]; the pitch
/// diameter when the bearing has no envelope (bore and outside diameter unknown).
pub fn mean_diameter(b: &crate::geometry::Bearing) -> f64 {
    if b.bore > 0.0 && b.outer_diameter > b.bore {
        0.5 * (b.bore + b.outer_diameter)
    } else {
        b.dm
    }
}

/// What the oil gives at an operating point.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Lubrication {
    /// Operating temperature, °C.
    pub temperature_c: f64,
    /// Kinematic viscosity at that temperature, m²/s.
    pub nu: f64,
    /// ISO 281 reference viscosity ν1, m²/s (`None` at standstill).
    pub nu1: Option<f64>,
    /// κ = ν/ν1 (`None` at standstill).
    pub kappa: Option<f64>,
}

/// The oil at `t_c` °C in a bearing of mean diameter `dm` (m, [`mean_diameter`]) turning at
/// `speed_rpm`.
pub fn lubrication(oil: &Oil, t_c: f64, dm: f64, speed_rpm: f64) -> Result<Lubrication> {
    let nu = oil.nu_at(t_c)?;
    let nu1 = nu1(dm, speed_rpm);
    Ok(Lubrication {
        temperature_c: t_c,
        nu,
        nu1,
        kappa: nu1.map(|v| nu / v),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ISO 281's ν1 by hand from its two branches: n = 3000 rpm, dm = 38.5 mm:
    /// 4500 / sqrt(3000) / sqrt(38.5) = 13.2406 mm²/s; n = 500 rpm, dm = 380 mm:
    /// 45000 · 500^-0.83 / sqrt(380) = 13.2801 mm²/s. The branches meet within 2.4 % at
    /// 1000 rpm (145.6 vs 142.3 mm²/s at dm = 1 mm), as the source's do.
    #[test]
    fn nu1_worked_values() {
        let v = nu1(38.5e-3, 3000.0).unwrap() * 1e6;
        assert!((v - 13.2406).abs() < 1e-3, "{v}");
        let v = nu1(0.380, 500.0).unwrap() * 1e6;
        assert!((v - 13.2801).abs() < 1e-3, "{v}");
        let below = nu1(1e-3, 999.999_999).unwrap();
        let above = nu1(1e-3, 1000.0).unwrap();
        assert!(
            below > above && (below / above - 1.0) < 0.024,
            "{below} {above}"
        );
        assert_eq!(nu1(0.05, 0.0), None);
        // A 6205 (25 x 52 mm): the mean diameter 38.5 mm, not its pitch diameter.
        let b = crate::geometry::preset("6205").unwrap().build().unwrap();
        assert!((mean_diameter(&b) - 38.5e-3).abs() < 1e-12);
    }

    /// ASTM D2270 §5.1.4's worked example (Procedure A): U = 73.30, Y = 8.86 mm²/s; the
    /// table gives L = 119.94 and H = 69.48 by interpolation, VI = 92.43.
    #[test]
    fn d2270_procedure_a_example() {
        let (l, h) = reference_oils(8.86).unwrap();
        assert!(
            (l - 119.94).abs() < 0.005 && (h - 69.48).abs() < 0.005,
            "{l} {h}"
        );
        let vi = viscosity_index(73.30, 8.86).unwrap();
        assert!((vi - 92.43).abs() < 0.01, "{vi}");
    }

    /// Procedure B by hand: U = 22.83, Y = 5.05: H = 28.975 (between 28.49 at 5.0 and 29.46
    /// at 5.1), N = log(28.975/22.83)/log 5.05 = 0.14719, VI = (10^N − 1)/0.00715 + 100 = 156.42.
    #[test]
    fn d2270_procedure_b_by_hand() {
        let (_, h) = reference_oils(5.05).unwrap();
        assert!((h - 28.975).abs() < 1e-9, "{h}");
        let n = (28.975f64 / 22.83).log10() / 5.05f64.log10();
        let want = (10f64.powf(n) - 1.0) / 0.00715 + 100.0;
        let vi = viscosity_index(22.83, 5.05).unwrap();
        assert!(
            (vi - want).abs() < 1e-9 && (vi - 156.42).abs() < 0.01,
            "{vi} {want}"
        );
        // The two procedures meet at U = H (VI 100) and the table meets the Y > 70 equations.
        assert!((viscosity_index(h, 5.05).unwrap() - 100.0).abs() < 1e-9);
        let (l70, h70) = reference_oils(70.0).unwrap();
        let (le, he) = reference_oils(70.0 + 1e-9).unwrap();
        assert!((l70 / le - 1.0).abs() < 5e-4 && (h70 / he - 1.0).abs() < 5e-4);
    }

    /// The inverse returns the 100 °C viscosity that gives the index back, and a higher index
    /// means a thicker oil at 100 °C (a flatter viscosity–temperature line).
    #[test]
    fn vi_inverse_round_trips() {
        for (nu40, vi) in [(32.0, 95.0), (68.0, 100.0), (68.0, 150.0), (220.0, 40.0)] {
            let y = nu100_from_vi(nu40, vi).unwrap();
            assert!((viscosity_index(nu40, y).unwrap() - vi).abs() < 1e-6);
        }
        assert!(nu100_from_vi(68.0, 150.0).unwrap() > nu100_from_vi(68.0, 95.0).unwrap());
        // A VG 68 mineral oil of VI 95–100 has about 8.5–8.8 mm²/s at 100 °C (Table 1:
        // H = 68.79 at Y = 8.8).
        let y = nu100_from_vi(68.0, 100.0).unwrap();
        assert!((y - 8.73).abs() < 0.01, "{y}");
        assert!(nu100_from_vi(2.2, 95.0).is_err());
    }

    /// Walther passes through its two points, and falls monotonically between and beyond.
    #[test]
    fn walther_line() {
        let oil = Oil::iso_vg(68, 100.0).unwrap();
        assert!((oil.nu_at(40.0).unwrap() / 68e-6 - 1.0).abs() < 1e-12);
        assert!((oil.nu_at(100.0).unwrap() / oil.nu100 - 1.0).abs() < 1e-12);
        let mut last = f64::INFINITY;
        for t in (0..=140).step_by(10) {
            let nu = oil.nu_at(t as f64).unwrap();
            assert!(nu < last);
            last = nu;
        }
        // By hand at 70 °C (Y = 8.731): z40 = loglog(68.7) = 0.26410, z100 = loglog(9.431) =
        // −0.01119, B = (z40 − z100)/log(373.15/313.15) = 3.6159, z70 = z40 − B log(343.15/313.15)
        // → ν = 20.17 mm²/s.
        let nu70 = oil.nu_at(70.0).unwrap() * 1e6;
        assert!((nu70 - 20.17).abs() < 0.01, "{nu70}");
    }

    /// ISO 281 ν1 by hand: Dpw = 38.5 mm at 3000 rpm: 4500/sqrt(3000)/sqrt(38.5) = 13.24;
    /// at 500 rpm: 45000 · 500^−0.83 / sqrt(38.5) = 41.72 mm²/s.
    #[test]
    fn nu1_hand_worked() {
        let a = nu1(38.5e-3, 3000.0).unwrap() * 1e6;
        assert!((a - 13.24).abs() < 0.01, "{a}");
        let b = nu1(38.5e-3, 500.0).unwrap() * 1e6;
        let want = 45000.0 * 500f64.powf(-0.83) / 38.5f64.sqrt();
        assert!((b - want).abs() < 1e-9 && (b - 41.72).abs() < 0.01, "{b}");
        assert_eq!(nu1(38.5e-3, 0.0), None);
        // The branches step by ~2 % at 1000 rpm (the standard's own fit).
        let (lo, hi) = (nu1(0.05, 999.999).unwrap(), nu1(0.05, 1000.0).unwrap());
        assert!((lo / hi - 1.0).abs() < 0.03);
    }

    #[test]
    fn names_and_errors() {
        for n in ["VG68", "ISO VG 68", "vg 68", "iso-vg-68"] {
            assert_eq!(Oil::by_name(n, None).unwrap().nu40, 68e-6, "{n}");
        }
        let e = Oil::by_name("VG69", None).unwrap_err().to_string();
        assert!(e.contains("VG69") && e.contains("VG68"), "{e}");
        let e = Oil::by_name("castor", None).unwrap_err().to_string();
        assert!(e.contains("castor"), "{e}");
        let e = Oil::iso_vg(68, 1000.0).unwrap_err().to_string();
        assert!(e.contains("oil.viscosity_index"), "{e}");
        let oil = Oil::by_name("VG10", None).unwrap();
        let e = oil.nu_at(200.0).unwrap_err().to_string();
        assert!(e.contains("oil.temperature_c"), "{e}");
    }

    /// κ rises with viscosity grade and falls with temperature.
    #[test]
    fn kappa_trends() {
        let k = |g: u32, t: f64| {
            lubrication(&Oil::iso_vg(g, 95.0).unwrap(), t, 38.5e-3, 3000.0)
                .unwrap()
                .kappa
                .unwrap()
        };
        assert!(k(68, 60.0) > k(32, 60.0));
        assert!(k(68, 80.0) < k(68, 60.0));
        // At 40 °C, κ is the grade over ν1.
        assert!((k(68, 40.0) - 68.0 / 13.2403).abs() < 1e-3);
    }
}
