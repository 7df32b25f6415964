//! The quasi-static ball reports' contact table (semi-axes and peak pressure at each
//! ball's contact angles): its accuracy against the exact ellipse solve over the whole
//! tabulated range of contact angles (hence of radius ratios `Ry/Rx`), every preset, both
//! races.

use raceway::contact::hertz::{FINE_TABLE_INTERVALS, TABLE_MAX_ANGLE};
use raceway::contact::{ContactTable, Race};
use raceway::geometry::presets;

fn rel(x: f64, want: f64) -> f64 {
    ((x - want) / want).abs()
}

#[test]
fn report_table_matches_exact_solve_to_rounding() {
    let mut worst = [0.0_f64; 3];
    for spec in presets() {
        let b = spec.build().unwrap();
        for race in [Race::Inner, Race::Outer] {
            let (f, e_eff) = match race {
                Race::Inner => (b.fi(), b.e_eff_inner()),
                Race::Outer => (b.fo(), b.e_eff_outer()),
            };
            let t = ContactTable::from_parts(
                b.d,
                b.dm,
                f,
                e_eff,
                race,
                TABLE_MAX_ANGLE,
                FINE_TABLE_INTERVALS,
            )
            .unwrap();
            let n = 128 * 40;
            let x_lo = TABLE_MAX_ANGLE.cos();
            for i in 0..=n {
                // Uniform in cos(alpha), offset from the nodes.
                let x = 1.0 - (1.0 - x_lo) * (i as f64 + 0.37) / (n as f64 + 1.0);
                let s = (1.0 - x * x).sqrt();
                let tb = t.eval_cos_sin(x, s);
                let ex = t.eval_exact(x, s);
                // What the reports use: ca, cb and the peak-pressure coefficient.
                let e = [
                    rel(tb.a_coef, ex.a_coef),
                    rel(tb.b_coef, ex.b_coef),
                    rel(tb.peak_pressure(1.0), ex.peak_pressure(1.0)),
                ];
                for (w, e) in worst.iter_mut().zip(e) {
                    *w = w.max(e);
                }
            }
        }
    }
    println!(
        "report table max rel err ca, cb, p0: {:?}",
        worst.map(|w| format!("{w:.2e}"))
    );
    assert!(worst.iter().all(|&w| w < 2e-13), "{worst:?}");
}
