//! Bearing presets: the bearings of the studies in docs/physics.md §10 and of Harris's worked
//! examples. Each preset records where its numbers come from and what was assumed.

use super::bearing::{BearingKind, BearingSpec, CageSpec, Guidance, MaterialSpec, MaterialsSpec};
use crate::error::Result;

fn mat(ball: &str, ring: &str, cage: &str) -> MaterialsSpec {
    MaterialsSpec {
        ball: MaterialSpec::Preset(ball.into()),
        inner_ring: MaterialSpec::Preset(ring.into()),
        outer_ring: MaterialSpec::Preset(ring.into()),
        cage: MaterialSpec::Preset(cage.into()),
    }
}

#[allow(clippy::too_many_arguments)]
fn spec(
    name: &str,
    kind: BearingKind,
    d: f64,
    dm: f64,
    z: u32,
    f: Option<(f64, f64)>,
    alpha_deg: Option<f64>,
    pd_um: Option<f64>,
    envelope: (f64, f64, f64),
    source: &str,
) -> BearingSpec {
    BearingSpec {
        name: name.into(),
        kind,
        ball_diameter_mm: d,
        pitch_diameter_mm: dm,
        ball_count: z,
        inner_curvature: f.map(|f| f.0),
        outer_curvature: f.map(|f| f.1),
        contact_angle_deg: alpha_deg,
        clearance_um: pd_um,
        bore_mm: Some(envelope.0),
        outer_diameter_mm: Some(envelope.1),
        width_mm: Some(envelope.2),
        inner_ring_mass_kg: None,
        outer_ring_mass_kg: None,
        cage: CageSpec::default(),
        materials: MaterialsSpec::default(),
        source: source.into(),
    }
}

/// All presets, in a stable order.
pub fn presets() -> Vec<BearingSpec> {
    use BearingKind::*;
    let mut v = Vec::new();

    let mut b7004 = spec(
        "7004",
        AngularContact,
        8.0,
        31.0,
        6,
        Some((0.56, 0.52)),
        Some(24.0),
        None,
        (20.0, 42.0, 12.0),
        "study [0] (Ye, Wang, Zhang), hybrid high-speed 7004; Z = 6 as the study gives it; envelope from the 7004 series",
    );
    b7004.materials = mat("si3n4", "steel-7004", "phenolic");
    b7004.cage = CageSpec {
        inner_diameter_mm: Some(30.0),
        outer_diameter_mm: Some(35.0),
        pocket_clearance_mm: Some(0.1),
        guide_clearance_mm: Some(0.25),
        guidance: Guidance::OuterRing,
        ..CageSpec::default()
    };
    v.push(b7004);

    let acbb16 = spec(
        "acbb16",
        AngularContact,
        22.23,
        135.0,
        16,
        Some((0.523, 0.523)),
        Some(40.0),
        None,
        (100.0, 170.0, 28.0),
        "study [1] (Jiang, Yang, Chang), 16-ball angular-contact bearing, steel balls; envelope assumed",
    );
    // The same bearing with other materials: its geometry is acbb16's by construction.
    let hybrid = BearingSpec {
        name: "acbb16-si3n4".into(),
        materials: mat("si3n4", "steel", "phenolic"),
        source: "study [1], the same bearing with Si3N4 balls".into(),
        ..acbb16.clone()
    };
    v.push(acbb16);
    v.push(hybrid);

    let mut b6012 = spec(
        "6012",
        DeepGroove,
        10.45,
        77.6,
        14,
        Some((0.52, 0.52)),
        None,
        Some(10.0),
        (60.0, 95.0, 18.0),
        "study [2] (Cao et al.); race radii 33.5/44.0 mm; f = 0.52 assumed (not given)",
    );
    b6012.cage.inertia_kg_m2 = Some(3.2e-5);
    v.push(b6012);

    let mut b7008 = spec(
        "7008ce",
        AngularContact,
        8.003,
        54.0,
        16,
        None,
        Some(15.0),
        Some(28.37),
        (40.0, 68.0, 15.0),
        "study [3] (Wang et al.), full-ceramic ZrO2; race diameters 46.062/62.096 mm; f_i = f_o derived from alpha0 and Pd",
    );
    b7008.materials = mat("zro2", "zro2", "zro2");
    v.push(b7008);

    v.push(spec(
        "6205",
        DeepGroove,
        7.94,
        39.04,
        9,
        Some((0.52, 0.52)),
        None,
        Some(0.0),
        (25.0, 52.0, 15.0),
        "study [4] (Yan et al.) / CWRU 6205-2RS; f = 0.52 and zero clearance assumed (not given)",
    ));

    v.push(spec(
        "209",
        DeepGroove,
        12.7,
        65.0,
        9,
        Some((0.52, 0.52)),
        None,
        Some(15.0),
        (45.0, 85.0, 19.0),
        "Harris & Kotzalas worked examples, 209 deep-groove bearing (raceway diameters 52.291/77.706 mm)",
    ));

    v.push(spec(
        "218",
        AngularContact,
        22.23,
        125.3,
        16,
        Some((0.5232, 0.5232)),
        Some(40.0),
        None,
        (90.0, 160.0, 30.0),
        "Harris & Kotzalas worked examples, 218 angular-contact bearing",
    ));
    v
}

/// Look a bearing up by name (case-insensitive): a preset, else a catalogue designation
/// (`6206`, `7205B`, .. with estimated internal geometry, see [`super::catalogue`]).
pub fn preset(name: &str) -> Result<BearingSpec> {
    let all = presets();
    all.iter()
        .find(|b| b.name.eq_ignore_ascii_case(name))
        .cloned()
        .or_else(|| super::catalogue::lookup(name))
        .ok_or_else(|| {
            super::catalogue::unknown(name, all.iter().map(|b| b.name.clone()).collect())
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_builds() {
        for p in presets() {
            let b = p.build().unwrap_or_else(|e| panic!("{}: {e}", p.name));
            assert!(b.inner_ring_mass > 0.0 && b.cage.mass > 0.0, "{}", p.name);
        }
    }

    #[test]
    fn harris_209_raceway_diameters() {
        let b = preset("209").unwrap().build().unwrap();
        assert!((b.inner_race_diameter() * 1e3 - 52.2925).abs() < 1e-3);
        assert!((b.outer_race_diameter() * 1e3 - 77.7075).abs() < 1e-3);
    }

    #[test]
    fn b7008ce_curvature_derived_from_angle_and_clearance_matches_race_diameters() {
        let b = preset("7008CE").unwrap().build().unwrap();
        // Pd = 2A(1 - cos alpha0) holds by construction; the study's race diameters give
        // d_o - d_i - 2D = 62.096 - 46.062 - 16.006 = 0.028 mm = Pd to its rounding.
        assert!((b.pd * 1e6 - 28.37).abs() < 1e-9);
        assert!((b.fi() - 0.526).abs() < 1e-3, "f = {}", b.fi());
        assert!((b.alpha0.to_degrees() - 15.0).abs() < 1e-9);
    }

    #[test]
    fn deep_groove_free_contact_angle_from_clearance() {
        // 6012: A = 0.04 D = 0.418 mm, Pd = 10 µm: cos a0 = 1 - Pd/(2A).
        let b = preset("6012").unwrap().build().unwrap();
        let want = (1.0_f64 - 10e-6 / (2.0 * 0.04 * 10.45e-3)).acos();
        assert!((b.alpha0 - want).abs() < 1e-12);
        assert_eq!(b.nominal_contact_angle(), 0.0);
        let (a1, a2) = b.reference_groove_offset();
        assert_eq!(a1, 0.0);
        assert!((b.a() - a2 - 5e-6).abs() < 1e-15);
    }

    #[test]
    fn unknown_preset_is_refused_with_the_known_names() {
        let e = preset("6409").unwrap_err().to_string();
        assert!(
            e.contains("6409") && e.contains("7008ce") && e.contains("62xx"),
            "{e}"
        );
        // A catalogue designation is found, with its estimated geometry marked.
        assert!(preset("6309").unwrap().source.contains("ESTIMATED"));
    }
}
