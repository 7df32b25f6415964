//! Stability campaign, CI sample (one factor at a time around each level's nominal cell,
//! plus corners; short windows). The long campaign:
//! `cargo run --release --example bench -- --stability-long --out docs`.
//! Every cell must converge under refinement or refuse cleanly: never a panic or a NaN.

use raceway::report::stability::{self, Cell, Clearance, Load, Outcome, Speed, BASES};

fn base(name: &str) -> &'static stability::Base {
    BASES.iter().find(|b| b.name == name).unwrap()
}

#[test]
fn sampled_matrix_converges_or_refuses_cleanly() {
    let cells = stability::matrix(false);
    assert!(cells.len() >= 60, "{} cells", cells.len());
    let res = stability::run(&cells, 0.002, false);
    let failed: Vec<String> = res
        .iter()
        .filter(|(_, o)| !o.passed())
        .map(|(c, o)| format!("{c:?}: {o:?}"))
        .collect();
    assert!(failed.is_empty(), "failed cells:\n{}", failed.join("\n"));
    // The wired ring level never needs a refusal in this matrix: every ring cell runs.
    for (c, o) in &res {
        if c.base.name.starts_with("ring") {
            assert!(
                matches!(o, Outcome::Converged { .. } | Outcome::Statistical { .. }),
                "{c:?}: {o:?}"
            );
        } else if let Outcome::CleanError(m) = o {
            // A level not wired yet is refused by name.
            assert!(m.contains("model.level"), "{c:?}: {m}");
        }
    }
}

/// The 4 GPa load axis does what it says: Stribeck's ball load reaches about 4 GPa in the
/// component's own peak-pressure output (within the Stribeck factor's accuracy).
#[test]
fn four_gpa_cells_reach_four_gpa() {
    for name in ["ring-2dof/load", "ring-2dof/motion"] {
        let c = Cell {
            load: Load::Gpa4,
            ..stability::nominal(base(name))
        };
        match c.run(0.002) {
            Outcome::Converged { max_pressure, .. } => {
                assert!(
                    (3.6e9..4.4e9).contains(&max_pressure),
                    "{name}: {max_pressure:.3e} Pa"
                )
            }
            o => panic!("{name}: {o:?}"),
        }
    }
}

/// A free ring at rest (no load, large clearance, no speed) touches nothing: zero force,
/// zero pressure, exactly.
#[test]
fn unloaded_ring_in_clearance_feels_nothing() {
    let c = Cell {
        speed: Speed::Zero,
        load: Load::Zero,
        clearance: Clearance::Large,
        ..stability::nominal(base("ring-2dof/load"))
    };
    assert_eq!(
        c.run(0.002),
        Outcome::Converged {
            diff: 0.0,
            max_pressure: 0.0
        }
    );
}

/// A preload given as a negative clearance on an angular-contact preset is refused with
/// the field named (its conformity is derived from a clearance >= 0).
#[test]
fn angular_contact_preload_as_clearance_is_a_clean_error() {
    let mut b = *base("ring-5dof/load 7008CE");
    b.clearance_axis = true;
    let b: &'static stability::Base = Box::leak(Box::new(b));
    let c = Cell {
        clearance: Clearance::Preload,
        ..stability::nominal(b)
    };
    match c.run(0.001) {
        Outcome::CleanError(m) => assert!(m.contains("bearing."), "{m}"),
        o => panic!("{o:?}"),
    }
}
