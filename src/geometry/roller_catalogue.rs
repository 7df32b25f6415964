//! Roller bearings by designation: cylindrical NU/N/NJ/NUP 2xx, 3xx and 22xx and tapered
//! 302xx, 303xx and 320xx(X), bore codes 04..20 (d = 20..100 mm).
//!
//! docs/physics.md §R6, docs/catalogue.md.
//!
//! **What is public and what is estimated.** The boundary dimensions are those of ISO 15
//! (cylindrical, dimension series 02, 03 and 22) and ISO 355 (tapered: `d × D × T`, cone width
//! `B`, cup width `C`), as the maker's table we compared with prints them (URB Group, *ART
//! Rolling Bearings General Catalogue* v.14_2017: NU..E cylindrical and 302..A, 303..A,
//! 320..XA tapered designs). A tapered bearing's contact angle is taken from that table's axial
//! factor `Y = 0.4 cot α` (ISO 281); its `e` disagrees with `Y` in a few rows (30207: e 0.46 but
//! Y 1.6, i.e. 14.0°) while the ISO 355 angle-series code agrees with `Y`. The internal geometry
//! is not published and is **estimated** (and marked so in [`RollerBearingSpec::source`]):
//!
//! - pitch diameter `Dpw = (d + D)/2`;
//! - roller diameter `Dwe = 0.26 (D - d)` to the nearest 0.5 mm (cylindrical rollers come in
//!   half-millimetre steps). The factor is the mean of `(E - F)/2/(D - d)` of the three sizes
//!   for which that catalogue prints both the outer raceway diameter `E` of the N type and the
//!   inner `F` of the NU type (204 E: 0.25, 205 E: 0.25, 206 E: 0.28); the same factor is
//!   **assumed** for tapered rollers (mean diameter), for which no internal data were at hand;
//! - effective roller length `Lwe`: 0.6 `B` (cylindrical) or 0.8 `C` (tapered, the cup width),
//!   to 0.1 mm — **assumed** proportions; overall length `Lw = Lwe + 0.1 Dwe` (end chamfers of
//!   0.05 Dwe, assumed);
//! - roller count `Z = floor(π Dpw / (1.2 Dwe))` (cage bars 0.2 Dwe wide, as the ball
//!   catalogue assumes for angular-contact bearings);
//! - profile: ISO/TS 16281's logarithmic profile (what the TS assumes when the real one is
//!   unknown); flanges of NJ/NUP and tapered bearings: the defaults of
//!   [`super::roller::FlangeSpec`];
//! - cylindrical diametral clearance: the middle of group N (CN) of ISO 5753-1 for cylindrical
//!   roller bearings as the same catalogue prints it; tapered: 0 (a tapered bearing's play is set
//!   at mounting).
//!
//! The estimate's error against the maker's `Cr` and `C0r` is measured by
//! `estimate_against_maker_ratings` in the tests and reported in docs/catalogue.md; use a
//! bearing file with the maker's internal data for design work.

use super::roller::{FlangeSpec, ProfileSpec, RollerBearingSpec, RollerKind};
use crate::error::Error;
use std::f64::consts::PI;

/// ISO 15 outside diameter and width (mm), bore codes 04..20, dimension series 02, 03, 22.
const CRB_02: [(f64, f64); 17] = [
    (47.0, 14.0),
    (52.0, 15.0),
    (62.0, 16.0),
    (72.0, 17.0),
    (80.0, 18.0),
    (85.0, 19.0),
    (90.0, 20.0),
    (100.0, 21.0),
    (110.0, 22.0),
    (120.0, 23.0),
    (125.0, 24.0),
    (130.0, 25.0),
    (140.0, 26.0),
    (150.0, 28.0),
    (160.0, 30.0),
    (170.0, 32.0),
    (180.0, 34.0),
];
const CRB_03: [(f64, f64); 17] = [
    (52.0, 15.0),
    (62.0, 17.0),
    (72.0, 19.0),
    (80.0, 21.0),
    (90.0, 23.0),
    (100.0, 25.0),
    (110.0, 27.0),
    (120.0, 29.0),
    (130.0, 31.0),
    (140.0, 33.0),
    (150.0, 35.0),
    (160.0, 37.0),
    (170.0, 39.0),
    (180.0, 41.0),
    (190.0, 43.0),
    (200.0, 45.0),
    (215.0, 47.0),
];
const CRB_22: [(f64, f64); 17] = [
    (47.0, 18.0),
    (52.0, 18.0),
    (62.0, 20.0),
    (72.0, 23.0),
    (80.0, 23.0),
    (85.0, 23.0),
    (90.0, 23.0),
    (100.0, 25.0),
    (110.0, 28.0),
    (120.0, 31.0),
    (125.0, 31.0),
    (130.0, 31.0),
    (140.0, 33.0),
    (150.0, 36.0),
    (160.0, 40.0),
    (170.0, 43.0),
    (180.0, 46.0),
];

/// Tapered, bore codes 04..20: `(D, T, B, C, Y)` (mm, mm, mm, mm, -).
type TrbRow = (f64, f64, f64, f64, f64);
const TRB_302: [TrbRow; 17] = [
    (47.0, 15.25, 14.0, 12.0, 1.7),
    (52.0, 16.25, 15.0, 13.0, 1.6),
    (62.0, 17.25, 16.0, 14.0, 1.6),
    (72.0, 18.25, 17.0, 15.0, 1.6),
    (80.0, 19.75, 18.0, 16.0, 1.6),
    (85.0, 20.75, 19.0, 16.0, 1.5),
    (90.0, 21.75, 20.0, 17.0, 1.4),
    (100.0, 22.75, 21.0, 18.0, 1.5),
    (110.0, 23.75, 22.0, 19.0, 1.5),
    (120.0, 24.75, 23.0, 20.0, 1.5),
    (125.0, 26.25, 24.0, 21.0, 1.4),
    (130.0, 27.25, 25.0, 22.0, 1.4),
    (140.0, 28.25, 26.0, 22.0, 1.4),
    (150.0, 30.5, 28.0, 24.0, 1.4),
    (160.0, 32.5, 30.0, 26.0, 1.4),
    (170.0, 34.5, 32.0, 27.0, 1.4),
    (180.0, 37.0, 34.0, 29.0, 1.4),
];
const TRB_303: [TrbRow; 17] = [
    (52.0, 16.25, 15.0, 13.0, 2.0),
    (62.0, 18.25, 17.0, 15.0, 2.0),
    (72.0, 20.75, 19.0, 16.0, 1.9),
    (80.0, 22.75, 21.0, 18.0, 1.9),
    (90.0, 25.25, 23.0, 20.0, 1.7),
    (100.0, 27.25, 25.0, 22.0, 1.7),
    (110.0, 29.25, 27.0, 23.0, 1.7),
    (120.0, 31.5, 29.0, 25.0, 1.7),
    (130.0, 33.5, 31.0, 26.0, 1.7),
    (140.0, 36.0, 33.0, 28.0, 1.7),
    (150.0, 38.0, 35.0, 30.0, 1.7),
    (160.0, 40.0, 37.0, 31.0, 1.7),
    (170.0, 42.5, 39.0, 33.0, 1.7),
    (180.0, 44.5, 41.0, 34.0, 1.7),
    (190.0, 46.5, 43.0, 36.0, 1.7),
    (200.0, 49.5, 45.0, 38.0, 1.7),
    (215.0, 51.5, 47.0, 39.0, 1.7),
];
const TRB_320: [TrbRow; 17] = [
    (42.0, 15.0, 15.0, 12.0, 1.6),
    (47.0, 15.0, 15.0, 11.5, 1.4),
    (55.0, 17.0, 17.0, 13.0, 1.4),
    (62.0, 18.0, 18.0, 14.0, 1.3),
    (68.0, 19.0, 19.0, 14.5, 1.6),
    (75.0, 20.0, 20.0, 15.5, 1.5),
    (80.0, 20.0, 20.0, 15.5, 1.4),
    (90.0, 23.0, 23.0, 17.5, 1.5),
    (95.0, 23.0, 23.0, 17.5, 1.4),
    (100.0, 23.0, 23.0, 17.5, 1.3),
    (110.0, 25.0, 25.0, 19.0, 1.4),
    (115.0, 25.0, 25.0, 19.0, 1.3),
    (125.0, 29.0, 29.0, 22.0, 1.4),
    (130.0, 29.0, 29.0, 22.0, 1.4),
    (140.0, 32.0, 32.0, 24.0, 1.4),
    (145.0, 32.0, 32.0, 24.0, 1.4),
    (150.0, 32.0, 32.0, 24.0, 1.3),
];

/// Group N radial clearance of cylindrical roller bearings with cylindrical bore, ISO 5753-1
/// as the catalogue of the module docs prints it: (bore over, incl, min µm, max µm).
const CN_CRB: [(f64, f64, f64, f64); 7] = [
    (10.0, 24.0, 20.0, 45.0),
    (24.0, 30.0, 20.0, 45.0),
    (30.0, 40.0, 25.0, 50.0),
    (40.0, 50.0, 30.0, 60.0),
    (50.0, 65.0, 40.0, 70.0),
    (65.0, 80.0, 40.0, 75.0),
    (80.0, 100.0, 50.0, 85.0),
];

/// Roller diameter as a fraction of `D - d` (module docs).
pub const ROLLER_FRACTION: f64 = 0.26;
/// Effective roller length as a fraction of the width `B` (cylindrical; module docs).
pub const CRB_LENGTH_FRACTION: f64 = 0.6;
/// Effective roller length as a fraction of the cup width `C` (tapered; module docs).
pub const TRB_LENGTH_FRACTION: f64 = 0.8;
/// Roller pitch spacing in roller diameters (module docs).
pub const ROLLER_SPACING: f64 = 1.2;

/// Internal geometry `(Dwe, Lwe, Dpw, Z)` (mm, mm, mm, count) estimated from the envelope and
/// the width that bounds the roller (`B` or `C`), module docs.
pub fn estimate_internal(d: f64, outer: f64, width: f64, tapered: bool) -> (f64, f64, f64, u32) {
    let dpw = 0.5 * (d + outer);
    let dwe = ((ROLLER_FRACTION * (outer - d)) / 0.5).round().max(1.0) * 0.5;
    let frac = if tapered {
        TRB_LENGTH_FRACTION
    } else {
        CRB_LENGTH_FRACTION
    };
    let lwe = (frac * width * 10.0).round() / 10.0;
    let z = (PI * dpw / (ROLLER_SPACING * dwe)).floor() as u32;
    (dwe, lwe, dpw, z)
}

/// The designations the catalogue knows.
pub fn designations() -> Vec<String> {
    let mut v = Vec::new();
    for p in ["NU", "N", "NJ", "NUP"] {
        for s in ["2", "3", "22"] {
            for c in 4..=20 {
                v.push(format!("{p}{s}{c:02}"));
            }
        }
    }
    for s in ["302", "303", "320"] {
        for c in 4..=20 {
            v.push(format!("{s}{c:02}"));
        }
    }
    v
}

/// A roller bearing by designation (case-insensitive, spaces ignored), e.g. `NU206`,
/// `NJ 2210 E`, `30206`, `32008X`; `None` when the text is not one of these designations.
pub fn lookup(name: &str) -> Option<RollerBearingSpec> {
    let n: String = name
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_uppercase();
    if n.starts_with('N') {
        lookup_crb(&n)
    } else {
        lookup_trb(&n)
    }
}

fn lookup_crb(n: &str) -> Option<RollerBearingSpec> {
    let (kind, rest) = if let Some(r) = n.strip_prefix("NUP") {
        (RollerKind::Nup, r)
    } else if let Some(r) = n.strip_prefix("NU") {
        (RollerKind::Nu, r)
    } else if let Some(r) = n.strip_prefix("NJ") {
        (RollerKind::Nj, r)
    } else {
        (RollerKind::N, n.strip_prefix('N')?)
    };
    let rest = rest.strip_suffix('E').unwrap_or(rest);
    if !rest.chars().all(|c| c.is_ascii_digit()) || !(rest.len() == 3 || rest.len() == 4) {
        return None;
    }
    let (series, code) = rest.split_at(rest.len() - 2);
    let code: usize = code.parse().ok().filter(|c| (4..=20).contains(c))?;
    let (table, dim) = match series {
        "2" => (&CRB_02, "02"),
        "3" => (&CRB_03, "03"),
        "22" => (&CRB_22, "22"),
        _ => return None,
    };
    let d = 5.0 * code as f64;
    let (outer, width) = table[code - 4];
    let (dwe, lwe, dpw, z) = estimate_internal(d, outer, width, false);
    let (lo, hi) = CN_CRB
        .iter()
        .find(|r| d > r.0 && d <= r.1)
        .map(|r| (r.2, r.3))?;
    let pd = 0.5 * (lo + hi);
    let designation = format!("{}{series}{code:02}", kind_prefix(kind));
    let source = format!(
        "catalogue {designation}: d x D x B = {d} x {outer} x {width} mm (ISO 15, dimension series {dim}); \
         ESTIMATED internal geometry (raceway::geometry::roller_catalogue): Dpw = (d+D)/2 = {dpw:.1} mm, \
         Dwe = 0.26 (D-d) to 0.5 mm = {dwe} mm, Lwe = 0.6 B = {lwe} mm, Z = {z} (roller spacing 1.2 Dwe), \
         ISO/TS 16281 log profile, Pd = {pd} µm (middle of group N, {lo}-{hi} µm)"
    );
    Some(RollerBearingSpec {
        name: designation,
        kind,
        roller_diameter_mm: dwe,
        roller_effective_length_mm: lwe,
        roller_length_mm: Some(lwe + 0.1 * dwe),
        roller_count: z,
        pitch_diameter_mm: dpw,
        contact_angle_deg: None,
        cone_angle_deg: None,
        clearance_um: Some(pd),
        profile: ProfileSpec::IsoLog,
        laminae: None,
        flange: FlangeSpec::default(),
        bore_mm: Some(d),
        outer_diameter_mm: Some(outer),
        width_mm: Some(width),
        roller_material: None,
        inner_ring_material: None,
        outer_ring_material: None,
        source,
    })
}

fn kind_prefix(k: RollerKind) -> &'static str {
    match k {
        RollerKind::Nu => "NU",
        RollerKind::N => "N",
        RollerKind::Nj => "NJ",
        RollerKind::Nup => "NUP",
        RollerKind::Tapered => "",
    }
}

fn lookup_trb(n: &str) -> Option<RollerBearingSpec> {
    let n = n.strip_suffix('X').unwrap_or(n);
    if n.len() != 5 || !n.chars().all(|c| c.is_ascii_digit()) {
        return None;
    }
    let (series, code) = n.split_at(3);
    let code: usize = code.parse().ok().filter(|c| (4..=20).contains(c))?;
    let table = match series {
        "302" => &TRB_302,
        "303" => &TRB_303,
        "320" => &TRB_320,
        _ => return None,
    };
    let d = 5.0 * code as f64;
    let (outer, t, b, c, y) = table[code - 4];
    let alpha = (0.4 / y).atan().to_degrees();
    let (dwe, lwe, dpw, z) = estimate_internal(d, outer, c, true);
    let x = if series == "320" { "X" } else { "" };
    let designation = format!("{series}{code:02}{x}");
    let source = format!(
        "catalogue {designation}: d x D x T = {d} x {outer} x {t} mm, B = {b} mm, C = {c} mm (ISO 355, as a maker's table prints it), \
         contact angle {alpha:.2}° from the maker's Y = {y} = 0.4 cot(alpha); ESTIMATED internal geometry \
         (raceway::geometry::roller_catalogue): Dpw = (d+D)/2 = {dpw:.1} mm, Dwe = 0.26 (D-d) to 0.5 mm = {dwe} mm (mean), \
         Lwe = 0.8 C = {lwe} mm, Z = {z} (roller spacing 1.2 Dwe), ISO/TS 16281 log profile, flange square to the roller axis, zero clearance"
    );
    Some(RollerBearingSpec {
        name: designation,
        kind: RollerKind::Tapered,
        roller_diameter_mm: dwe,
        roller_effective_length_mm: lwe,
        roller_length_mm: Some(lwe + 0.1 * dwe),
        roller_count: z,
        pitch_diameter_mm: dpw,
        contact_angle_deg: Some(alpha),
        cone_angle_deg: None,
        clearance_um: Some(0.0),
        profile: ProfileSpec::IsoLog,
        laminae: None,
        flange: FlangeSpec::default(),
        bore_mm: Some(d),
        outer_diameter_mm: Some(outer),
        width_mm: Some(t),
        roller_material: None,
        inner_ring_material: None,
        outer_ring_material: None,
        source,
    })
}

/// Error when a name is not a roller catalogue designation.
pub fn unknown(name: &str) -> Error {
    Error::Unknown {
        what: "roller bearing designation",
        name: name.into(),
        known: vec![
            "NU/N/NJ/NUP 2xx, 3xx, 22xx (xx = 04..20)".into(),
            "302xx, 303xx, 320xx[X] (xx = 04..20)".into(),
        ],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ratings::roller::roller_ratings;

    /// `(designation, Cr kN, C0r kN)` printed by the maker's catalogue of the module docs
    /// (URB/ART v.14_2017; cylindrical: the NU..E design, tapered: ..A / ..XA), every size of
    /// the catalogue's range that it lists.
    const MAKER: &[(&str, f64, f64)] = &[
        ("NU204", 27.5, 24.5),
        ("NU205", 29.0, 27.5),
        ("NU206", 39.7, 37.9),
        ("NU207", 50.0, 50.0),
        ("NU208", 53.9, 53.0),
        ("NU209", 61.0, 63.0),
        ("NU210", 64.4, 68.0),
        ("NU211", 83.0, 95.0),
        ("NU212", 95.0, 104.0),
        ("NU213", 108.0, 120.0),
        ("NU214", 120.0, 137.0),
        ("NU215", 132.0, 156.0),
        ("NU216", 140.0, 170.0),
        ("NU217", 165.0, 194.0),
        ("NU218", 183.0, 216.0),
        ("NU220", 251.0, 305.0),
        ("NU304", 31.5, 27.0),
        ("NU305", 41.5, 37.5),
        ("NU306", 51.2, 48.0),
        ("NU307", 66.7, 65.4),
        ("NU308", 81.5, 78.0),
        ("NU309", 98.0, 100.0),
        ("NU310", 110.0, 114.0),
        ("NU311", 134.0, 140.0),
        ("NU312", 150.0, 156.0),
        ("NU313", 180.0, 190.0),
        ("NU314", 205.0, 222.0),
        ("NU315", 240.0, 265.0),
        ("NU316", 255.0, 275.0),
        ("NU317", 288.0, 325.0),
        ("NU318", 315.0, 345.0),
        ("NU320", 380.0, 425.0),
        ("NU2204", 32.5, 31.0),
        ("NU2205", 34.5, 35.0),
        ("NU2206", 49.0, 50.0),
        ("NU2207", 65.0, 70.0),
        ("NU2208", 71.0, 75.0),
        ("NU2209", 76.0, 81.6),
        ("NU2210", 78.0, 88.0),
        ("NU2211", 98.0, 118.0),
        ("NU2212", 129.0, 153.0),
        ("NU2214", 156.0, 196.0),
        ("NU2217", 216.0, 275.0),
        ("NU2218", 240.0, 315.0),
        ("NU2220", 335.0, 440.0),
        ("30204", 25.8, 26.4),
        ("30205", 30.1, 32.9),
        ("30206", 40.5, 45.1),
        ("30207", 50.5, 54.7),
        ("30208", 57.9, 62.4),
        ("30209", 60.1, 67.1),
        ("30210", 69.7, 81.3),
        ("30211", 83.0, 95.2),
        ("30212", 91.6, 105.0),
        ("30213", 111.0, 129.0),
        ("30214", 119.0, 143.0),
        ("30215", 134.0, 166.0),
        ("30216", 145.0, 177.0),
        ("30217", 167.0, 206.0),
        ("30218", 190.0, 238.0),
        ("30219", 210.0, 264.0),
        ("30220", 238.0, 303.0),
        ("30304", 32.0, 32.0),
        ("30305", 43.0, 43.0),
        ("30306", 52.9, 51.8),
        ("30307", 71.2, 72.5),
        ("30308", 83.9, 91.3),
        ("30309", 106.0, 118.0),
        ("30310", 120.0, 133.0),
        ("30311", 146.0, 166.0),
        ("30312", 164.0, 187.0),
        ("30313", 191.0, 220.0),
        ("30314", 224.0, 264.0),
        ("30315", 246.0, 289.0),
        ("30316", 277.0, 329.0),
        ("30317", 298.0, 354.0),
        ("30318", 328.0, 394.0),
        ("30319", 350.0, 449.0),
        ("30320", 404.0, 492.0),
        ("32004X", 26.0, 28.5),
        ("32005X", 26.0, 33.5),
        ("32006X", 34.0, 45.5),
        ("32007X", 35.9, 52.4),
        ("32008X", 48.8, 65.6),
        ("32009X", 57.0, 82.2),
        ("32010X", 58.5, 88.5),
        ("32011X", 77.0, 117.0),
        ("32012X", 78.5, 119.0),
        ("32013X", 80.6, 123.0),
        ("32014X", 95.6, 143.0),
        ("32015X", 97.3, 149.0),
        ("32016X", 130.0, 198.0),
        ("32017X", 136.0, 213.0),
        ("32018X", 159.0, 246.0),
        ("32019X", 163.0, 257.0),
        ("32020X", 171.0, 277.0),
    ];

    #[test]
    fn every_designation_builds_and_rates() {
        for n in designations() {
            let s = lookup(&n).unwrap_or_else(|| panic!("{n}"));
            assert!(s.source.contains("ESTIMATED"), "{n}");
            let b = s.build().unwrap_or_else(|e| panic!("{n}: {e}"));
            roller_ratings(&b).unwrap_or_else(|e| panic!("{n}: {e}"));
            b.laminae().unwrap();
        }
        let s = lookup("nj 2210 e").unwrap();
        assert_eq!(s.kind, RollerKind::Nj);
        assert_eq!(
            (s.bore_mm, s.outer_diameter_mm, s.width_mm),
            (Some(50.0), Some(90.0), Some(23.0))
        );
        let s = lookup("30206").unwrap();
        assert_eq!((s.outer_diameter_mm, s.width_mm), (Some(62.0), Some(17.25)));
        assert!((s.contact_angle_deg.unwrap() - 14.036).abs() < 1e-3);
        assert_eq!(lookup("32008x").unwrap().name, "32008X");
        for bad in [
            "NU221", "NU203", "NU406", "30221", "31306", "NUX206", "6206", "N", "",
        ] {
            assert!(lookup(bad).is_none(), "{bad}");
        }
        assert!(unknown("NU999").to_string().contains("NU999"));
    }

    /// The estimate's `Cr` and `C0r` against the maker's. Prints the table docs/catalogue.md
    /// quotes; asserts the bounds it states (measured, not targets).
    #[test]
    fn estimate_against_maker_ratings() {
        let mut stats: Vec<(&str, Vec<f64>, Vec<f64>)> = vec![
            ("NU2", vec![], vec![]),
            ("NU3", vec![], vec![]),
            ("NU22", vec![], vec![]),
            ("302", vec![], vec![]),
            ("303", vec![], vec![]),
            ("320", vec![], vec![]),
        ];
        for &(n, cr_kn, c0r_kn) in MAKER {
            let s = lookup(n).unwrap();
            let b = s.build().unwrap();
            let r = roller_ratings(&b).unwrap();
            let (ec, e0) = (r.cr / (1e3 * cr_kn) - 1.0, r.c0r / (1e3 * c0r_kn) - 1.0);
            println!(
                "{n:<7} Dwe {:>4} Lwe {:>5} Z {:>2} alpha {:>5.2}  Cr {:>6.1} kN vs {:>6.1} ({:+5.1} %)  C0r {:>6.1} vs {:>6.1} ({:+5.1} %)",
                s.roller_diameter_mm,
                s.roller_effective_length_mm,
                s.roller_count,
                s.contact_angle_deg.unwrap_or(0.0),
                r.cr * 1e-3,
                cr_kn,
                100.0 * ec,
                r.c0r * 1e-3,
                c0r_kn,
                100.0 * e0
            );
            let key = ["NU22", "NU2", "NU3", "302", "303", "320"]
                .into_iter()
                .find(|k| n.starts_with(k))
                .unwrap();
            let slot = stats.iter_mut().find(|s| s.0 == key).unwrap();
            slot.1.push(ec);
            slot.2.push(e0);
        }
        for (k, ec, e0) in &stats {
            let mean = |v: &Vec<f64>| v.iter().sum::<f64>() / v.len() as f64;
            let (lo, hi) = (
                ec.iter().cloned().fold(f64::MAX, f64::min),
                ec.iter().cloned().fold(f64::MIN, f64::max),
            );
            let (lo0, hi0) = (
                e0.iter().cloned().fold(f64::MAX, f64::min),
                e0.iter().cloned().fold(f64::MIN, f64::max),
            );
            println!(
                "{k:<5} n {:>2}: Cr mean {:+.1} % [{:+.1}, {:+.1}], C0r mean {:+.1} % [{:+.1}, {:+.1}]",
                ec.len(),
                100.0 * mean(ec),
                100.0 * lo,
                100.0 * hi,
                100.0 * mean(e0),
                100.0 * lo0,
                100.0 * hi0
            );
            // The bounds docs/catalogue.md states (measured with the rules as first written:
            // worst Cr +19.8 % (32007X, whose maker Y of 1.3 gives the largest angle) and
            // -15.8 % (NU2220); worst C0r -16.2 % (NU2220), +17.8 % (NU210); series means
            // within -5.7..+5.9 % (Cr) and -10.8..+5.3 % (C0r)).
            assert!(lo > -0.17 && hi < 0.20 && lo0 > -0.17 && hi0 < 0.18, "{k}");
            assert!(mean(ec).abs() < 0.06 && mean(e0).abs() < 0.11, "{k}");
        }
    }
}
