//! Co-simulation coupling of a rigid rotor on two bearing components converges to the
//! monolithic solution as the macro step shrinks, faster with better input rules.

mod common;

use common::rotor::{cosimulated, monolithic, rel_l2, Rotor};
use raceway::component::InputRule;

#[test]
fn coupling_error_falls_with_the_macro_step_and_with_better_input_rules() {
    let r = Rotor::default();
    let (t_end, sample, t0) = (0.03, 1e-4, 0.015);
    let reference = monolithic(&r, t_end, 5e-7, sample);
    let err = |rule, h: f64| {
        let run = cosimulated(
            &r,
            rule,
            t_end,
            h,
            ((h / 5e-7).round() as usize).max(1),
            sample,
        )
        .unwrap();
        rel_l2(&run, &reference, t0)
    };
    let (v10, v5) = (
        err(InputRule::Velocity, 1e-5),
        err(InputRule::Velocity, 5e-6),
    );
    let (d10, d5) = (
        err(InputRule::Derivatives, 1e-5),
        err(InputRule::Derivatives, 5e-6),
    );
    let h10 = err(InputRule::Hold, 1e-5);
    assert!(
        v5 < 0.7 * v10,
        "velocity rule converges: {v10:.3e} -> {v5:.3e}"
    );
    assert!(
        d5 < 0.5 * d10,
        "derivative rule converges at least at second order: {d10:.3e} -> {d5:.3e}"
    );
    assert!(
        d10 < v10 && v10 < h10,
        "hold {h10:.3e} > velocity {v10:.3e} > derivatives {d10:.3e}"
    );
    assert!(d5 < 5e-3, "{d5:.3e}");
}
