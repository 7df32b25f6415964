//! The roller cells of the stability campaign (mounted by `stability.rs`).

use super::*;

/// `[model]` lines of the 5-DOF load-driven ring of the roller cells.
const RING5: &str = load_driven!("level = \"ring\"\nring_dof = 5\n");

/// The roller bases beyond [`BASES`]' own: a heavy tilt (a moment of 50 mm times the radial
/// load) on the NU206 and the 30206, and edge loading (a straight roller, ISO/TS 16281's
/// worst case, tilted by 5 mm times the load) at the ring and quasi-static levels.
pub const ROLLER_BASES: &[Base] = &[
    Base {
        name: "ring-5dof/load NU206 heavy tilt",
        preset: "NU206",
        model: RING5,
        roller: true,
        moment_arm: 0.05,
        ..CHEAP
    },
    Base {
        name: "ring-5dof/load NU206 straight, edge-loaded",
        preset: "NU206",
        model: RING5,
        roller: true,
        moment_arm: 0.005,
        bearing_extra: "profile = { type = \"none\" }",
        ..CHEAP
    },
    Base {
        name: "quasi_static/load NU206 straight, edge-loaded",
        preset: "NU206",
        model: load_driven!("level = \"quasi_static\"\n"),
        roller: true,
        moment_arm: 0.005,
        bearing_extra: "profile = { type = \"none\" }",
        ..CHEAP
    },
    Base {
        name: "ring-5dof/load 30206 heavy tilt",
        preset: "30206",
        model: RING5,
        roller: true,
        axial_share: 0.5,
        moment_arm: 0.05,
        ..CHEAP
    },
];

/// The roller cells (part of the long campaign, [`matrix`]): on every roller base of
/// [`BASES`] and [`ROLLER_BASES`], a stiff preload ([`Clearance::StiffPreload`]), the highest
/// speed (120 000 rpm, far past a roller bearing's limiting speed: the massless and
/// centrifugal laws must stay finite there) and their corner with the 4 GPa load; on the
/// bases of [`ROLLER_BASES`] also their nominal and 4 GPa cells.
pub fn roller_cells() -> Vec<Cell> {
    let mut v = Vec::new();
    let own = ROLLER_BASES.iter().map(|b| (b, true));
    let shared = BASES.iter().filter(|b| b.roller).map(|b| (b, false));
    for (base, new) in shared.chain(own) {
        let n = nominal(base);
        if new {
            v.push(n);
            v.push(Cell {
                load: Load::Gpa4,
                ..n
            });
        }
        v.push(Cell {
            clearance: Clearance::StiffPreload,
            ..n
        });
        v.push(Cell {
            speed: Speed::Max,
            ..n
        });
        v.push(Cell {
            speed: Speed::Max,
            load: Load::Gpa4,
            clearance: Clearance::StiffPreload,
            ..n
        });
    }
    v
}
