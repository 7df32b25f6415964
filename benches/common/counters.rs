//! The integrator counters between two snapshots, per unit of run (revolution, simulated
//! second). A bench mounts it with `#[path = "common/counters.rs"] mod counters;`.

use raceway::component::Stats;

/// `  per <unit>: rhs …, jacobians …, LU …, accepted …, rejected …` over `n` units.
pub fn per(unit: &str, s0: &Stats, s1: &Stats, n: f64) -> String {
    format!(
        "  per {unit}: rhs {:.0}, jacobians {:.0}, LU {:.0}, accepted {:.0}, rejected {:.0}",
        (s1.rhs - s0.rhs) as f64 / n,
        (s1.jacobians - s0.jacobians) as f64 / n,
        (s1.factorizations - s0.factorizations) as f64 / n,
        (s1.accepted - s0.accepted) as f64 / n,
        (s1.rejected - s0.rejected) as f64 / n
    )
}
