//! The cage's energy balance per cage revolution for `examples/cage_whirl.rs` (docs/cage-whirl.md,
//! "Why sigma rises"): the works of the forces on the cage from the level's powers, integrated
//! over time, against the change of the cage's kinetic energy; the page's section comparing the
//! Coulomb and the fitted 4109 traction, and its plot.

use super::*;

/// The cage's energy balance per cage revolution over a window: the work of each force on
/// the cage (its power from the model, integrated over time by the trapezoidal rule over the
/// recorded samples, divided by the cage revolutions in the window) against the change of the
/// cage's kinetic energy from its states. All J per cage revolution.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Balance {
    /// Work of the ball–pocket forces and moments (what the balls put into the cage, net of
    /// what the pockets take back).
    pub(crate) pocket: f64,
    /// Work of the guide land (film and wall): negative = dissipated at the land.
    pub(crate) guide: f64,
    /// Work of the drag on the side faces (dissipated).
    pub(crate) drag: f64,
    /// Change of the cage's kinetic energy over the window, from its states.
    pub(crate) dke: f64,
    /// The pocket forces' work through the centre's velocity, where positive: what the
    /// balls feed into the whirl.
    pub(crate) whirl_in: f64,
    /// The same where negative: what the pockets take out of the whirl (the cage centre
    /// running into balls: pocket impacts and squeeze films).
    pub(crate) whirl_out: f64,
    /// The guide land's work through the centre's velocity: negative = taken out of the
    /// whirl at the land.
    pub(crate) whirl_guide: f64,
    /// Change of the centre's kinetic energy over the window, from its states.
    pub(crate) dke_whirl: f64,
    /// Mean kinetic energy of the centre's motion over the window, J (not per revolution).
    pub(crate) ke_whirl: f64,
}

impl Balance {
    /// Sum of the works (the net), J per cage revolution.
    pub(crate) fn net(&self) -> f64 {
        self.pocket + self.guide + self.drag
    }
    /// Net work on the whirl.
    pub(crate) fn whirl_net(&self) -> f64 {
        self.whirl_in + self.whirl_out + self.whirl_guide
    }
    /// Energy fed into the whirl: the balls' pushes and the land's work where it feeds (the
    /// inner-ring land, turning faster than the cage).
    fn fed(&self) -> f64 {
        self.whirl_in + self.whirl_guide.max(0.0)
    }
    /// Energy taken out of the whirl (pocket impacts, the land where it takes), positive.
    fn taken(&self) -> f64 {
        -self.whirl_out - self.whirl_guide.min(0.0)
    }
    /// What is taken per joule of the centre's mean kinetic energy, 1 per revolution.
    fn damping(&self) -> f64 {
        self.taken() / self.ke_whirl
    }
}

/// [`Balance`] of `r` over the samples `w` (a range of indices), with `revs` cage
/// revolutions in it.
pub(crate) fn balance(r: &Record, w: std::ops::Range<usize>, revs: f64) -> Balance {
    let trap = |f: &dyn Fn(usize) -> f64| -> f64 {
        w.clone()
            .skip(1)
            .map(|k| 0.5 * (f(k) + f(k - 1)) * (r.t[k] - r.t[k - 1]))
            .sum::<f64>()
            / revs
    };
    let (a, b) = (w.start, w.end - 1);
    Balance {
        pocket: trap(&|k| r.powers[k][0]),
        guide: trap(&|k| r.powers[k][2]),
        drag: trap(&|k| r.powers[k][4]),
        dke: (r.ke[b][1] - r.ke[a][1]) / revs,
        whirl_in: trap(&|k| r.powers[k][1].max(0.0)),
        whirl_out: trap(&|k| r.powers[k][1].min(0.0)),
        whirl_guide: trap(&|k| r.powers[k][3]),
        dke_whirl: (r.ke[b][0] - r.ke[a][0]) / revs,
        ke_whirl: w.clone().map(|k| r.ke[k][0]).sum::<f64>() / w.len() as f64,
    }
}

/// The tractions of the energy-balance section: (label, rows of each configuration).
type Tractions<'a> = Vec<(String, &'a [Study])>;

fn tractions<'a>(coulomb: &'a [Study], oils: &'a [OilSet]) -> Tractions<'a> {
    let mut v: Tractions = vec![("Coulomb (scenes)".to_string(), coulomb)];
    for (t, sets, _) in oils {
        v.push((format!("4109 fit, {t:.0} °C"), sets.as_slice()));
    }
    v
}

/// The page's section on the cage's energy balance per cage revolution, Coulomb against the
/// fitted 4109 traction, with the plain reading computed from the numbers.
pub(crate) fn balance_section(
    o: &Opts,
    coulomb: &[Study],
    oils: &[OilSet],
) -> Result<String, Box<dyn std::error::Error>> {
    let tr = tractions(coulomb, oils);
    let mut md = String::new();
    let (lo, hi) = (o.speeds[0], o.speeds[o.speeds.len() - 1]);
    writeln!(
        md,
        "\n## Why sigma rises: the cage's energy balance per cage revolution, Coulomb against the 4109 fit\n\n\
         From the runs above (the same runs, no others: {} s per speed, the last of {} windows, every traction): \
         the power of each force on the cage as the level computes it (`Totals::pocket_power`, `guide_power`, \
         `cage_drag_power` and the parts through the centre's velocity, re-evaluated at every recorded state) \
         integrated over the last window by the trapezoidal rule and divided by the cage revolutions in it; \
         beside it the change of the cage's kinetic energy computed from its states (`mc |v|²/2 + ip w²/2 + \
         it |b'|²/2`, the whirl part `mc |v|²/2`). \"Pockets\" is what the balls put into the cage through \
         the pocket forces and moments, net of what the pockets take back; \"land\" and \"drag\" are negative \
         when they dissipate. For the whirl (the centre's motion, what sigma measures) the pocket work is split \
         by the sign of its power: **balls in** where the pockets push the centre along its motion, **pockets \
         out** where the centre runs into balls (pocket impacts and squeeze films; the level's totals do not \
         separate what the pocket contact dissipates from what it hands back to the ball). The conservation check \
         is the column pair net work against ΔKE (per cage revolution); `tests/cage_energy.rs` checks the same \
         identity over one cage revolution at a 2 µs step.\n",
        o.duration, o.windows
    )?;
    let cfg0 = CONFIGS[0];
    writeln!(
        md,
        "### {} (the study's guidance)\n\n\
         | traction | speed, rpm | sigma | pockets, mJ | land, mJ | drag, mJ | net work, mJ | ΔKE, mJ | whirl: balls in, mJ | whirl: pockets out, mJ | whirl: land, mJ | whirl net, mJ | whirl ΔKE, mJ | centre KE, µJ |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
        cfg0.label()
    )?;
    for (name, studies) in &tr {
        let Some((_, rows, ..)) = studies.iter().find(|s| s.0 == cfg0) else {
            continue;
        };
        for r in rows {
            let b = r.balance;
            let m = |v: f64| format!("{:.3e}", v * 1e3);
            writeln!(
                md,
                "| {name} | {:.0} | {:.4} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.3e} |",
                r.rpm,
                r.sigma(),
                m(b.pocket),
                m(b.guide),
                m(b.drag),
                m(b.net()),
                m(b.dke),
                m(b.whirl_in),
                m(b.whirl_out),
                m(b.whirl_guide),
                m(b.whirl_net()),
                m(b.dke_whirl),
                b.ke_whirl * 1e6
            )?;
        }
    }
    md += "\n![cage energy balance per revolution](cage-whirl-energy.png)\n\n";
    // Growth from the lowest to the top speed, every configuration and traction.
    writeln!(
        md,
        "Every configuration, from {lo:.0} to {hi:.0} rpm (speed ratio {:.0}): the energy fed into the whirl per cage \
         revolution (balls in, plus the land where it feeds: on the inner-ring land, which turns faster than the cage), \
         the energy taken out of it (pockets out and the land where it takes) per revolution per joule of the centre's mean \
         kinetic energy (how hard the orbit is damped, 1/rev), the centre's kinetic energy, and sigma.\n\n\
         | configuration | traction | whirl fed, mJ | growth | taken / centre KE, 1/rev | growth | centre KE, µJ | growth | sigma | growth |\n\
         |---|---|---|---|---|---|---|---|---|---|",
        hi / lo
    )?;
    for cfg in CONFIGS {
        for (name, studies) in &tr {
            let Some((_, rows, ..)) = studies.iter().find(|s| s.0 == cfg) else {
                continue;
            };
            let (a, b) = (&rows[0].balance, &rows[rows.len() - 1].balance);
            let (sa, sb) = (rows[0].sigma(), rows[rows.len() - 1].sigma());
            writeln!(
                md,
                "| {} | {name} | {:.3e} → {:.3e} | {:.0}x | {:.3} → {:.3} | {:.2}x | {:.3e} → {:.3e} | {:.0}x | {:.4} → {:.4} | {:.2}x |",
                cfg.label(),
                a.fed() * 1e3,
                b.fed() * 1e3,
                b.fed() / a.fed(),
                a.damping(),
                b.damping(),
                b.damping() / a.damping(),
                a.ke_whirl * 1e6,
                b.ke_whirl * 1e6,
                b.ke_whirl / a.ke_whirl,
                sa,
                sb,
                sb / sa
            )?;
        }
    }
    // The plain reading, computed from the numbers of every configuration and traction.
    let mut fed_min = f64::INFINITY;
    let mut damp_max: f64 = 0.0;
    let mut close: f64 = 0.0;
    let mut resid: f64 = 0.0;
    for (_, studies) in &tr {
        for (_, rows, ..) in studies.iter() {
            let (a, b) = (&rows[0].balance, &rows[rows.len() - 1].balance);
            fed_min = fed_min.min(b.fed() / a.fed());
            damp_max = damp_max.max(b.damping() / a.damping());
            for r in rows {
                let x = &r.balance;
                close = close.max((x.whirl_net() - x.dke_whirl).abs() / x.fed());
                resid = resid.max((x.net() - x.dke).abs() / x.pocket.abs());
            }
        }
    }
    let ends = |studies: &[Study]| -> Option<(Balance, Balance, f64, f64)> {
        let (_, rows, ..) = studies.iter().find(|s| s.0 == cfg0)?;
        let (a, b) = (&rows[0], &rows[rows.len() - 1]);
        Some((a.balance, b.balance, a.sigma(), b.sigma()))
    };
    let mut parts = Vec::new();
    for (name, studies) in &tr {
        let Some((a, b, sa, sb)) = ends(studies) else {
            continue;
        };
        let g = b.fed() / a.fed();
        parts.push(format!(
            "{name}: {:.2e} → {:.2e} mJ (×{:.0}, about speed^{:.1}) against a damping per joule of orbit ×{:.2}, so the \
             centre's kinetic energy ×{:.0} and sigma ×{:.1}",
            a.fed() * 1e3,
            b.fed() * 1e3,
            g,
            g.ln() / (hi / lo).ln(),
            b.damping() / a.damping(),
            b.ke_whirl / a.ke_whirl,
            sb / sa
        ));
    }
    // The plain sentence: Coulomb against the first fitted traction on the study's guidance.
    let headline = match (ends(tr[0].1), tr.get(1).and_then(|t| ends(t.1))) {
        (Some((ca, cb, csa, csb)), Some((fa, fb, fsa, fsb))) => {
            let (gc, gf) = (cb.fed() / ca.fed(), fb.fed() / fa.fed());
            let (dc, df) = (cb.damping() / ca.damping(), fb.damping() / fa.damping());
            if gc > dc && gf > df && csb > csa && fsb > fsa {
                format!(
                    "Sigma rises instead of falling because, per cage revolution, the energy the balls feed into the cage's \
                     whirl grows with the speed far faster than what the guide land and the pocket impacts take out of a given \
                     orbit: on the outer-ring land from {lo:.0} to {hi:.0} rpm the input grows ×{gc:.0} with Coulomb traction and \
                     ×{gf:.0} with the {}, the damping per joule of orbit only ×{dc:.1} and ×{df:.1}, so the orbit must carry \
                     ×{:.0} and ×{:.0} more energy, is pushed out to the land and runs unevenly there. The fitted traction feeds \
                     the whirl ×{:.1} as much as Coulomb's at {lo:.0} rpm (hence its larger sigma there) and ×{:.2} as much at \
                     {hi:.0} rpm, so it {} the rise (sigma ×{:.1} against ×{:.1}) without turning it: for sigma to fall the input \
                     would have to grow slower than the damping, and under neither law does it.",
                    tr[1].0,
                    cb.ke_whirl / ca.ke_whirl,
                    fb.ke_whirl / fa.ke_whirl,
                    fa.fed() / ca.fed(),
                    fb.fed() / cb.fed(),
                    if fsb / fsa < csb / csa { "flattens" } else { "does not flatten" },
                    fsb / fsa,
                    csb / csa
                )
            } else {
                format!(
                    "The balance does not give one cause here: on the outer-ring land the input grows ×{gc:.0} (Coulomb) and \
                     ×{gf:.0} ({}), the damping per joule ×{dc:.1} and ×{df:.1}, sigma ×{:.1} and ×{:.1}; read the tables.",
                    tr[1].0,
                    csb / csa,
                    fsb / fsa
                )
            }
        }
        _ => String::new(),
    };
    writeln!(
        md,
        "\n**What it shows.** {headline}\n\n\
         The evidence, from the tables: in every run the whirl's budget closes (fed minus taken equals the change of the \
         centre's kinetic energy within {:.1} % of what is fed), so the orbit settles where what the land and the pocket impacts \
         take out equals what the balls put in. On the outer-ring land the input grows — {}. {} Over all configurations and \
         tractions the input grows at least ×{:.0} while the damping per joule of orbit grows at most ×{:.1}{}. The whole cage's \
         works (mostly its spin: tens to hundreds of millijoules per revolution, driven by the pockets, taken by the land's \
         shear and the drag) equal its kinetic energy's change within {:.2} % of the pockets' work; the rest grows with the \
         speed and comes from short contacts that the powers sampled every {:.0} µs do not resolve: a separate run \
         (`cargo run --example cage_whirl -- --config outer-radial --speeds 30000,120000 --duration 0.01 --windows 1 \
         --rtol 1e-9 --step 2e-6`, against the same with `--step 1e-5`) shrinks it at 120 000 rpm from 1.39 to 0.93 mJ \
         per cage revolution, and `tests/cage_energy.rs` closes the identity to 0.9 % of the energy's change over one \
         revolution at 30 000 rpm. The whirl's budget, which the reading above uses, is not affected.\n",
        100.0 * close,
        parts.join("; "),
        if damp_max < 10.0 {
            "With the damping per joule nearly flat, the orbit's energy follows the input."
        } else {
            "The damping per joule of orbit grows too; compare the columns."
        },
        fed_min,
        damp_max,
        if fed_min > 10.0 * damp_max {
            ""
        } else {
            " (not everywhere far apart: read the table)"
        },
        100.0 * resid,
        o.step * 1e6,
    )?;
    Ok(md)
}

/// The energy balance per cage revolution against speed on the study's guidance, each
/// traction: the whirl (balls in, land's take) and the whole cage (pockets, land and drag).
#[cfg(feature = "plot")]
pub(crate) fn energy_plot(
    dir: &Path,
    o: &Opts,
    coulomb: &[Study],
    oils: &[OilSet],
) -> Result<(), Box<dyn std::error::Error>> {
    use raceway::plot::{plot_stack, Axes, Series};
    let _ = o;
    let cfg0 = CONFIGS[0];
    let tr = tractions(coulomb, oils);
    let mut data: Vec<(String, Vec<f64>, Vec<f64>)> = Vec::new();
    let mut data1: Vec<(String, Vec<f64>, Vec<f64>)> = Vec::new();
    let mut data2: Vec<(String, Vec<f64>, Vec<f64>)> = Vec::new();
    for (long, studies) in &tr {
        let Some((_, rows, ..)) = studies.iter().find(|s| s.0 == cfg0) else {
            continue;
        };
        // Short legends ("Coulomb", "4109 100 °C") keep the legend box off the data.
        let name = long.replace(" (scenes)", "").replace(" fit,", "");
        let x: Vec<f64> = rows.iter().map(|r| r.rpm).collect();
        let y = |f: &dyn Fn(&Balance) -> f64| -> Vec<f64> {
            rows.iter().map(|r| f(&r.balance).abs()).collect()
        };
        data.push((format!("{name}: fed"), x.clone(), y(&|b| b.fed() * 1e3)));
        data.push((format!("{name}: taken"), x.clone(), y(&|b| b.taken() * 1e3)));
        data1.push((
            format!("{name}: centre KE, µJ"),
            x.clone(),
            y(&|b| b.ke_whirl * 1e6),
        ));
        data1.push((
            format!("{name}: taken / centre KE, 1/rev"),
            x.clone(),
            y(&|b| b.damping()),
        ));
        data2.push((
            format!("{name}: pockets"),
            x.clone(),
            y(&|b| b.pocket * 1e3),
        ));
        data2.push((
            format!("{name}: land + drag"),
            x.clone(),
            y(&|b| (b.guide + b.drag) * 1e3),
        ));
    }
    fn series(d: &[(String, Vec<f64>, Vec<f64>)]) -> Vec<Series<'_>> {
        d.iter()
            .enumerate()
            .map(|(k, (l, x, y))| Series {
                label: l,
                x,
                y,
                points: k % 2 == 1,
            })
            .collect()
    }
    let title = format!(
        "7004 cage energy per cage revolution vs shaft speed, {}",
        cfg0.label()
    );
    plot_stack(
        &dir.join("cage-whirl-energy.png"),
        &title,
        &[
            (
                Axes {
                    title: "whirl (cage-centre motion): energy fed by the balls (lines), taken by land and impacts (points)",
                    x_label: "shaft speed, rpm",
                    y_label: "work per rev, mJ",
                    log_y: true,
                    ..Axes::default()
                },
                series(&data),
            ),
            (
                Axes {
                    title: "whirl: centre's kinetic energy (lines) and damping per joule of it (points)",
                    x_label: "shaft speed, rpm",
                    y_label: "µJ (lines), 1/rev (points)",
                    log_y: true,
                    ..Axes::default()
                },
                series(&data1),
            ),
            (
                Axes {
                    title: "whole cage: pockets' work (lines), land and drag dissipated (points)",
                    x_label: "shaft speed, rpm",
                    y_label: "work per rev, mJ",
                    log_y: true,
                    ..Axes::default()
                },
                series(&data2),
            ),
        ],
    )?;
    Ok(())
}
