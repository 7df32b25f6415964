//! Study \[2\] (Cao et al.) reproduced on the skidding level: mixed-lubrication wear of the
//! 6012's outer race driven by the skidding dynamics, in wear cycles
//! (`raceway::wear_cycles`).
//!
//! ```text
//! cargo run --release --example study_wear -- --write-docs   # docs/study-wear.md + PNGs
//! cargo run --example study_wear -- --quick                   # the short CI version, into out/study-wear/
//! cargo run --release --example study_wear -- --pattern       # only the dry map pattern's trace, printed
//! ```

use raceway::component::Scene;
use raceway::contact::traction::{FilmFormula, MixedEhl, TractionLaw};
use raceway::lubrication::asperity::AsperityReading;
use raceway::models::wear_map::OuterRaceWear;
use raceway::plot::{plot, plot_stack, Axes, Series};
use raceway::wear_cycles::{CycleRecord, Settle, WearCycles};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// The La plot shows cells whose mean ball load is at least this share of the heaviest.
const LOADED: f64 = 0.1;

/// Study \[2\]'s data (docs/physics.md §10).
const ROUGHNESS: [f64; 2] = [0.2e-6, 0.42e-6];

struct Run {
    label: String,
    records: Vec<CycleRecord>,
    settle: Settle,
    cpu_s: f64,
}

fn scene(traction: TractionLaw) -> Res<Scene> {
    let text = include_str!("scenes/6012-skidding.toml");
    let mut s = Scene::from_text(text)?;
    s.model.skidding.traction = traction;
    Ok(s)
}

fn friction(sigma: f64, reading: AsperityReading, film_formula: FilmFormula) -> MixedEhl {
    MixedEhl {
        roughness: sigma,
        reading,
        film_formula,
        ..MixedEhl::default()
    }
}

struct Plan {
    /// Settling check: chunk length (cage revolutions), longest run (s), tolerance.
    settle_chunk: f64,
    settle_max_s: f64,
    settle_tol: f64,
    settle_cage_tol: f64,
    /// Print every settling chunk.
    probe: bool,
    window: f64,
    cycles: u32,
    step_s: f64,
}

#[allow(clippy::too_many_arguments)]
fn run(
    label: &str,
    sigma: Option<f64>,
    (reading, film): (AsperityReading, FilmFormula),
    cycle_revs: f64,
    cycles: u32,
    plan: &Plan,
    out: &Path,
) -> Res<Run> {
    // Dry: the friction law at La = 100 (roughness far above any film: boundary friction).
    let traction = TractionLaw::MixedEhl(friction(sigma.unwrap_or(1e-4), reading, film));
    let mut w = WearCycles {
        scene: scene(traction)?,
        wear: OuterRaceWear::study2(sigma, reading),
        cells: 360,
        settle_s: 0.0,
        window_cage_revs: plan.window,
        cycle_cage_revs: cycle_revs,
        cycles,
        step_s: plan.step_s,
        max_step_fraction: 0.1,
    };
    let t0 = raceway::report::thread_cpu_s();
    // The run-in before each window: measured on the unworn race, not guessed.
    let settle = w.settle_check(
        plan.settle_chunk,
        plan.settle_max_s,
        plan.settle_tol,
        plan.settle_cage_tol,
    )?;
    if plan.probe {
        for k in &settle.chunks {
            eprintln!(
                "{label}: {:.4} s: cage slip {:.5}, ball slip {:.4} mm/s",
                k.t_end,
                k.cage_slip,
                k.ball_slip * 1e3
            );
        }
    }
    w.settle_s = settle.settled_s.unwrap_or(plan.settle_max_s);
    eprintln!(
        "{label}: settle check: {} chunks, settled at {:?} s",
        settle.chunks.len(),
        settle.settled_s
    );
    let dir = out.join(label);
    let records = w.run(Some(&dir), |r| {
        let (d, a) = r.deepest();
        eprintln!(
            "{label}: cycle {} ({:.3e} cage rev): deepest {:.4e} µm at {:.1} deg, slip {:.4}",
            r.cycle,
            r.cage_revs,
            d * 1e6,
            a.to_degrees(),
            r.cage_slip
        );
        Ok(())
    })?;
    Ok(Run {
        label: label.into(),
        records,
        settle,
        cpu_s: raceway::report::thread_cpu_s() - t0,
    })
}

fn angles(n: usize) -> Vec<f64> {
    (0..n).map(|k| 360.0 * k as f64 / n as f64).collect()
}

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let docs = args.iter().any(|a| a == "--write-docs");
    // Only the settling checks of the lubricated σ 0.20 and the dry case, every chunk printed.
    let probe = args.iter().any(|a| a == "--settle-probe");
    let plan = if quick {
        Plan {
            settle_chunk: 1.0 / 14.0,
            settle_max_s: 0.02,
            settle_tol: 0.1,
            settle_cage_tol: 1e-3,
            probe,
            window: 0.25,
            cycles: 2,
            step_s: 1e-4,
        }
    } else {
        Plan {
            settle_chunk: 1.0,
            settle_max_s: if probe { 1.0 } else { 0.3 },
            settle_tol: 0.1,
            settle_cage_tol: 1e-3,
            probe,
            window: 2.0,
            cycles: 10,
            step_s: 1e-4,
        }
    };
    let out: PathBuf = if docs {
        "docs".into()
    } else {
        "out/study-wear".into()
    };
    let maps = if docs {
        PathBuf::from("target/study-wear")
    } else {
        out.join("maps")
    };
    std::fs::create_dir_all(&out)?;
    if probe {
        for (label, sigma) in [("sigma-0.20", Some(ROUGHNESS[0])), ("dry", None)] {
            run(
                label,
                sigma,
                (AsperityReading::FilmParameter, FilmFormula::HamrockDowson),
                1e3,
                1,
                &plan,
                &maps,
            )?;
        }
        return Ok(());
    }
    // Only the dry map's pattern section (its trace, not the variants), printed.
    if args.iter().any(|a| a == "--pattern") {
        let pat = pattern(plan.settle_max_s, &plan, false)?;
        let mut s = String::new();
        write_pattern(&mut s, &pat)?;
        println!("{s}");
        return Ok(());
    }
    // Lubricated: cycles of 1e7 cage revolutions to 1e8; dry: cycles of 100 to 1 000.
    let lub_cycle = 1e8 / plan.cycles as f64;
    let dry_cycle = 1e3 / plan.cycles as f64;
    let hd = FilmFormula::HamrockDowson;
    let r = (AsperityReading::FilmParameter, hd);
    let mut runs = vec![
        run(
            "sigma-0.20",
            Some(ROUGHNESS[0]),
            r,
            lub_cycle,
            plan.cycles,
            &plan,
            &maps,
        )?,
        run(
            "sigma-0.42",
            Some(ROUGHNESS[1]),
            r,
            lub_cycle,
            plan.cycles,
            &plan,
            &maps,
        )?,
        run("dry", None, r, dry_cycle, plan.cycles, &plan, &maps)?,
    ];
    // The other readings of the asperity share and the film with roughness: the first
    // cycle's rates, both roughnesses (runs 3..9 in pairs, in the order of `VARIANTS`).
    for (suffix, variant) in VARIANTS {
        for (sigma, s_label) in [(ROUGHNESS[0], "0.20"), (ROUGHNESS[1], "0.42")] {
            runs.push(run(
                &format!("sigma-{s_label}-{suffix}"),
                Some(sigma),
                variant,
                lub_cycle,
                1,
                &plan,
                &maps,
            )?);
        }
    }
    // The dry map's peaks: the numerics varied (not in the quick version) and the trace.
    let dry_settle = runs[2].settle.settled_s.unwrap_or(plan.settle_max_s);
    let pat = pattern(dry_settle, &plan, !quick)?;
    let load = raceway::report::load_average();
    write_page(&runs, &pat, &out, docs, quick, &plan, load)?;
    Ok(())
}

/// The variants run for their first cycle beside the film-parameter reading with
/// Hamrock–Dowson's film: the quartic reading, the line-contact ratio, and Masjedi–Khonsari's
/// film with roughness (the film-parameter reading).
const VARIANTS: [(&str, (AsperityReading, FilmFormula)); 3] = [
    (
        "quartic",
        (AsperityReading::Quartic, FilmFormula::HamrockDowson),
    ),
    (
        "line-contact",
        (AsperityReading::LineContact, FilmFormula::HamrockDowson),
    ),
    (
        "mk-film",
        (AsperityReading::FilmParameter, FilmFormula::MasjediKhonsari),
    ),
];

fn rate_max(r: &CycleRecord) -> f64 {
    r.rate.iter().fold(0.0f64, |a, &b| a.max(b))
}

fn write_page(
    runs: &[Run],
    pat: &Pattern,
    out: &Path,
    docs: bool,
    quick: bool,
    plan: &Plan,
    load: String,
) -> Res<()> {
    let n = runs[0].records[0].map.len();
    let ang = angles(n);
    // Asperity share around the race, both roughnesses (first cycle), where the balls carry
    // load: La is a share of the ball's load, and outside the load zone that load is the
    // ball's centrifugal force of about a newton (the page gives the numbers).
    let (la_x, la_y): (Vec<Vec<f64>>, Vec<Vec<f64>>) = runs[..2]
        .iter()
        .map(|r| {
            let rec = &r.records[0];
            ang.iter()
                .zip(rec.la.iter().zip(&rec.q))
                .filter(|(_, (l, q))| l.is_finite() && **q >= LOADED * rec.q_max)
                .map(|(a, (l, _))| (*a, *l))
                .unzip()
        })
        .unzip();
    let png = |name: &str| out.join(format!("study-wear-{name}.png"));
    plot(
        &png("asperity-share"),
        &Axes {
            title: "6012 outer race: asperity load share La under the loaded balls",
            x_label: "azimuth (deg; load line at 270)",
            y_label: "La (% of the ball load)",
            ..Axes::default()
        },
        &[
            Series {
                label: "σ 0.20 µm",
                x: &la_x[0],
                y: &la_y[0],
                points: true,
            },
            Series {
                label: "σ 0.42 µm",
                x: &la_x[1],
                y: &la_y[1],
                points: true,
            },
        ],
        &[],
    )?;
    for run in &runs[..3] {
        let um: Vec<(String, Vec<f64>)> = run
            .records
            .iter()
            .map(|r| {
                (
                    format!("{:.1e} cage rev", r.cage_revs),
                    r.map.iter().map(|d| d * 1e6).collect(),
                )
            })
            .collect();
        let series: Vec<Series> = um
            .iter()
            .map(|(l, y)| Series {
                label: l,
                x: &ang,
                y,
                points: false,
            })
            .collect();
        plot(
            &png(&format!("map-{}", run.label)),
            &Axes {
                title: &format!(
                    "6012 outer-race wear depth after each cycle ({})",
                    run.label
                ),
                x_label: "azimuth (deg; load line at 270)",
                y_label: "wear depth (µm)",
                ..Axes::default()
            },
            &series,
            &[],
        )?;
        let first = &run.records[0].orbit;
        let last = &run.records[run.records.len() - 1].orbit;
        let xy = |o: &[[f64; 2]]| -> (Vec<f64>, Vec<f64>) {
            o.iter().map(|p| (p[0] * 1e6, p[1] * 1e6)).unzip()
        };
        let (fx, fy) = xy(first);
        let (lx, ly) = xy(last);
        plot(
            &png(&format!("orbit-{}", run.label)),
            &Axes {
                title: &format!("6012 shaft centre before and after wear ({})", run.label),
                x_label: "x (µm)",
                y_label: "y (µm)",
                equal: true,
                ..Axes::default()
            },
            &[
                Series {
                    label: "cycle 1 (unworn)",
                    x: &fx,
                    y: &fy,
                    points: false,
                },
                Series {
                    label: "last cycle (worn)",
                    x: &lx,
                    y: &ly,
                    points: true,
                },
            ],
            &[],
        )?;
    }
    let tr = &pat.trace;
    let ms: Vec<f64> = tr.t.iter().map(|t| t * 1e3).collect();
    let kin = vec![tr.kinematic; ms.len()];
    plot_stack(
        &png("dry-bursts"),
        "6012 dry: cage speed and slip of the unloaded balls (cycle 1 window)",
        &[
            (
                Axes {
                    title: "",
                    x_label: "time from the scene's start (ms)",
                    y_label: "cage speed (rad/s)",
                    ..Axes::default()
                },
                vec![
                    Series {
                        label: "cage",
                        x: &ms,
                        y: &tr.cage,
                        points: false,
                    },
                    Series {
                        label: "kinematic",
                        x: &ms,
                        y: &kin,
                        points: false,
                    },
                ],
            ),
            (
                Axes {
                    title: "",
                    x_label: "time from the scene's start (ms)",
                    y_label: "median |dv_o|, unloaded balls (mm/s)",
                    ..Axes::default()
                },
                vec![Series {
                    label: "unloaded balls",
                    x: &ms,
                    y: &tr.slip,
                    points: false,
                }],
            ),
        ],
    )?;
    let mut s = String::new();
    writeln!(
        s,
        "# Study [2]: mixed-lubrication wear driven by the skidding dynamics\n"
    )?;
    writeln!(
        s,
        "Generated by `cargo run --release --example study_wear -- --write-docs`{}; do not edit.\n",
        if quick {
            " (QUICK VERSION: short windows, 2 cycles)"
        } else {
            ""
        }
    )?;
    writeln!(s, "## Set-up (docs/physics.md §10)\n")?;
    writeln!(
        s,
        "- Bearing 6012 (deep groove, Z = 14, D = 10.45 mm, dm = 77.6 mm, Pd = 10 µm), \
         500 N radial (−y), 2000 rpm, load-driven shaft (`examples/scenes/6012-skidding.toml`: \
         attached mass 1 kg, contact damping 100 N s/m, drag coefficient 15), **skidding level**.\n\
         - Oil: η0 = 0.04667 Pa s, α = 2.1e-8 m²/N, viscosity–temperature coefficient 0.04 /K, \
         limiting-shear coefficient 0.04, inlet temperature T0 = 293.15 K; composite roughness \
         σ = 0.20 and 0.42 µm; hardness 2.39 GPa.\n\
         - Friction (traction) law: study [2]'s eq. (7), `mixed_ehl` (asperity share \
         f_c Q La/100 with f_c = {}, film share with the flash-temperature viscosity); dry: the \
         same law at La = 100.\n\
         - Wear: Archard, `dh/dt = K ψ (La/100) p u_s / Hv`, K = 5e-4, film-defect constants \
         a_x = 3e-12 m, t0 = 3e-12 s, Ea = 49 kJ/mol, Rg = 8.31 J/(mol K), ψ at T0 + ΔT; \
         u_s = |dv_o| the ball's slip over the outer race from the dynamics. Dry: La = 100, ψ = 1.\n\
         - Cycles: cycle k of n runs the dynamics from the scene's start for the settling time \
         below plus (k−1)/n of a window (each cycle repeats the same trajectory from the same \
         start; the offset makes the cycles sample different stretches of the irregular \
         motion instead of piling one stretch's slip bursts onto the same cells), measures \
         the outer-race wear \
         over {} cage revolution(s) sampled every {} s on 360 cells, extrapolates it over the \
         cycle, adds it to the race profile (the clearance under each ball) and runs again. \
         Lubricated: {} cycles to 1e8 cage revolutions; dry: {} cycles to 1 000.\n",
        MixedEhl::default().f_c,
        plan.window,
        plan.step_s,
        plan.cycles,
        plan.cycles
    )?;
    writeln!(s, "## Settling time (measured, not guessed)\n")?;
    writeln!(
        s,
        "Before its cycles each case runs the dynamics on the unworn race \
         (`WearCycles::settle_check`) in chunks of {:.4} cage revolutions (ball passes at the \
         kinematic cage speed: {}) for at most {} s and records each chunk's mean cage slip \
         and mean slip speed `|dv_o|` of the loaded balls over the outer race (what the wear \
         law integrates). It is settled at the end of the first chunk whose two predecessors \
         and itself agree, successively, within {} % in the ball slip and within {} in the \
         cage slip (absolute: the cage slip may pass through zero); every window of that case \
         then starts after this time (on the worn races too: the check runs on the unworn \
         one). Not settled within the limit: the limit is used and the table says so. \
         `--settle-probe` prints every chunk of a 1 s check for σ 0.20 and dry.\n\n\
         What the check shows: the slip does not come to a steady state. After a short \
         run-in of a few hundredths of a second the motion is stationary but irregular: \
         means over 4 ball passes keep scattering by about ±20 % in ball slip and between \
         0.002 and 0.006 in cage slip up to 1 s (`--settle-probe`). So the test is one of \
         stationarity, on means over one cage revolution at 10 %, and each wear window spans \
         {} cage revolutions. Part of that scatter is the cage's burst cycle described below \
         (a burst every few ball passes): a chunk of a whole number of ball passes but not \
         of burst cycles holds one burst more or less, depending on where it starts.\n",
        plan.settle_chunk,
        (plan.settle_chunk * 14.0).round(),
        plan.settle_max_s,
        plan.settle_tol * 100.0,
        plan.settle_cage_tol,
        plan.window
    )?;
    writeln!(
        s,
        "| case | chunks run | settled at (s) | cage slip, last 3 chunks | ball slip speed, last 3 chunks (mm/s) |\n|---|---|---|---|---|"
    )?;
    for run in runs {
        let c = &run.settle.chunks;
        let last = &c[c.len().saturating_sub(3)..];
        let list = |f: &dyn Fn(&raceway::wear_cycles::SettleChunk) -> f64| {
            last.iter()
                .map(|k| format!("{:.5}", f(k)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        writeln!(
            s,
            "| {} | {} | {} | {} | {} |",
            run.label,
            c.len(),
            run.settle
                .settled_s
                .map_or(format!("not within {} s", plan.settle_max_s), |t| format!(
                    "{t:.4}"
                )),
            list(&|k| k.cage_slip),
            list(&|k| k.ball_slip * 1e3),
        )?;
    }
    writeln!(s)?;
    writeln!(s, "## Results\n")?;
    writeln!(
        s,
        "| case | cage revolutions | deepest (µm) | at (deg) | peak rate, cycle 1 (µm per 1e6 cage rev) | mean cage slip, cycle 1 | thread CPU (s) |\n|---|---|---|---|---|---|---|"
    )?;
    for run in runs {
        let last = &run.records[run.records.len() - 1];
        let (d, a) = last.deepest();
        writeln!(
            s,
            "| {} | {:.3e} | {:.4e} | {:.1} | {:.4e} | {:.4} | {:.1} |",
            run.label,
            last.cage_revs,
            d * 1e6,
            a.to_degrees(),
            rate_max(&run.records[0]) * 1e12,
            run.records[0].cage_slip,
            run.cpu_s
        )?;
    }
    let ratio = |a: &Run, b: &Run| rate_max(&b.records[0]) / rate_max(&a.records[0]);
    writeln!(
        s,
        "\nRatio of the lubricated peak wear rates (σ 0.42 / σ 0.20, cycle 1), one line per \
         reading of the asperity share and film (load average during the run: {load}):\n\n\
         | asperity share La | central film of the traction's film share | ratio |\n|---|---|---|\n\
         | film-parameter reading of the restored eq. (8) (roughness exponent 2.9/0.67) | \
         Hamrock–Dowson | **{:.3}** |\n\
         | quartic reading of the restored eq. (8) (exponent 4) | Hamrock–Dowson | {:.3} |\n\
         | Masjedi–Khonsari's line-contact ratio on the ellipse's central slice | \
         Hamrock–Dowson | {:.3} |\n\
         | film-parameter reading | Masjedi–Khonsari with roughness | {:.3} |\n",
        ratio(&runs[0], &runs[1]),
        ratio(&runs[3], &runs[4]),
        ratio(&runs[5], &runs[6]),
        ratio(&runs[7], &runs[8]),
    )?;
    writeln!(
        s,
        "The line-contact row is a second documented reading, not the study's formula: \
         Masjedi & Khonsari's line-contact regression (J. Tribol. 2012, as coded in public \
         code, medium confidence) applied to the slice through the centre of each ball's \
         Hertz ellipse, which carries `3Q/(4a)` per unit length (`lubrication::asperity`, \
         docs/physics.md §7). The film row changes only the traction's film share (the wear \
         law's La does not use the film thickness): it moves the rates through the slip the \
         dynamics give. No constant was adjusted toward the study's figures.\n"
    )?;
    // La outside the load zone: a share of a near-zero load.
    for run in &runs[..2] {
        let r = &run.records[0];
        let (mut la, mut q, mut n) = (0.0, 0.0, 0.0);
        for (l, w) in r.la.iter().zip(&r.q) {
            if l.is_finite() && *w < LOADED * r.q_max {
                la += l;
                q += w;
                n += 1.0;
            }
        }
        if n > 0.0 {
            writeln!(
                s,
                "{}: outside the load zone (cells whose mean ball load is below {} % of the \
                 heaviest, {:.1} N) the balls carry {:.2} N on average (their centrifugal \
                 force) and La averages {:.1} %, a share of a load that is almost nothing: \
                 these cells are left out of the La plot (their wear is in the maps).\n",
                run.label,
                LOADED * 100.0,
                r.q_max,
                q / n,
                la / n
            )?;
        }
    }
    writeln!(
        s,
        "The asperity load share: study [2]'s eq. (8) is garbled (`0.689^(1/4)` carries no \
         roughness); `lubrication::asperity` restores the roughness factor inside the \
         logarithm and explains the choice. The readings differ a lot: the roughness \
         exponent alone moves La at the heaviest ball by a factor of several, so the \
         lubricated rates and their ratio depend on a term the study's print lost.\n"
    )?;
    write_pattern(&mut s, pat)?;
    for (title, name) in [
        (
            "Asperity load share around the race (cycle 1)",
            "asperity-share",
        ),
        ("Wear depth, σ 0.20 µm", "map-sigma-0.20"),
        ("Wear depth, σ 0.42 µm", "map-sigma-0.42"),
        ("Wear depth, dry", "map-dry"),
        ("Shaft-centre orbit, σ 0.20 µm", "orbit-sigma-0.20"),
        ("Shaft-centre orbit, σ 0.42 µm", "orbit-sigma-0.42"),
        ("Shaft-centre orbit, dry", "orbit-dry"),
        (
            "Dry: cage speed and slip of the unloaded balls",
            "dry-bursts",
        ),
    ] {
        writeln!(s, "### {title}\n\n![{title}](study-wear-{name}.png)\n")?;
    }
    let page = out.join("study-wear.md");
    raceway::fsutil::write_atomic(&page, s)?;
    if !docs {
        println!("{}", page.display());
    }
    Ok(())
}

/// The dry map's out-of-zone peaks: how they respond to the numerics (output step, cells,
/// window length, run-in) and the dynamics behind them (a trace of the cage speed and the
/// slip of the unloaded balls).
struct Pattern {
    rows: Vec<PatternRow>,
    trace: Trace,
}

struct PatternRow {
    label: String,
    /// Peak rate anywhere, µm per 1e6 cage revolutions.
    peak: f64,
    /// Out of the load zone: amplitude of the Z-th harmonic over the mean.
    hz: f64,
    /// Out of the load zone: the six highest local maxima, deg, sorted.
    maxima: Vec<f64>,
}

/// Cells out of the load zone: mean ball load below `LOADED` of the heaviest (or none).
fn out_of_zone(r: &CycleRecord) -> Vec<usize> {
    (0..r.q.len())
        .filter(|&k| r.q[k].is_nan() || r.q[k] < LOADED * r.q_max)
        .collect()
}

fn pattern_row(label: String, r: &CycleRecord, z: f64) -> PatternRow {
    let n = r.rate.len();
    let cells = out_of_zone(r);
    let mean = cells.iter().map(|&k| r.rate[k]).sum::<f64>() / cells.len().max(1) as f64;
    let (mut re, mut im) = (0.0, 0.0);
    for &k in &cells {
        let a = std::f64::consts::TAU * z * k as f64 / n as f64;
        re += r.rate[k] * a.cos();
        im += r.rate[k] * a.sin();
    }
    let hz = 2.0 * re.hypot(im) / cells.len().max(1) as f64 / mean;
    let mut pk: Vec<(f64, f64)> = cells
        .iter()
        .filter(|&&k| r.rate[k] > r.rate[(k + n - 1) % n] && r.rate[k] >= r.rate[(k + 1) % n])
        .map(|&k| (r.rate[k], 360.0 * k as f64 / n as f64))
        .collect();
    pk.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut maxima: Vec<f64> = pk.iter().take(6).map(|p| p.1).collect();
    maxima.sort_by(f64::total_cmp);
    PatternRow {
        label,
        peak: rate_max(r) * 1e12,
        hz,
        maxima,
    }
}

/// What the dry dynamics do between the bursts and in them.
#[derive(Default)]
struct Trace {
    t: Vec<f64>,
    /// Cage speed, rad/s.
    cage: Vec<f64>,
    /// Median slip speed |dv_o| over the unloaded balls, mm/s.
    slip: Vec<f64>,
    /// Kinematic cage speed, rad/s.
    kinematic: f64,
    /// Cage revolutions traced.
    revs: f64,
    /// Mean cage speed over the trace, rad/s.
    mean_cage: f64,
    /// Start of each burst, s.
    bursts: Vec<f64>,
    /// Angles of the unloaded balls at the first burst's highest slip, deg.
    burst_angles: Vec<f64>,
    /// Angle of the ball leaving the load zone at each burst's start, deg (the ball
    /// furthest past the load line with more than 2 % of the heaviest ball's load).
    exit_angle: Vec<f64>,
    /// Median slip of the unloaded balls, mm/s.
    median_slip: f64,
    /// Share of the unloaded balls' wear deposited in burst steps, and their share of steps.
    wear_share: f64,
    step_share: f64,
}

/// One traced step: the unloaded balls' `(angle deg, slip mm/s)`, their wear area rate
/// (m²/s) and the angle of the ball leaving the zone (deg).
type Sample = (Vec<(f64, f64)>, f64, f64);

/// Run the dry dynamics from the scene's start for `settle_s`, then trace `revs` cage
/// revolutions at step `h`. A burst: a run of steps in which the median slip over the
/// unloaded balls (outer load below `LOADED` of the heaviest ball at that instant) is more
/// than 20 times its median over the trace (the big bursts reach about 50 times it; smaller
/// events half-way between them stay below 20).
fn trace_dry(settle_s: f64, revs: f64, h: f64) -> Res<Trace> {
    use raceway::component::{variables, Component};
    let reading = AsperityReading::FilmParameter;
    let wear = OuterRaceWear::study2(None, reading);
    let mut c = Component::new(scene(TractionLaw::MixedEhl(friction(
        1e-4,
        reading,
        FilmFormula::HamrockDowson,
    )))?)?;
    let vr = |s: &str| variables::by_name(s).map_or(0, |v| v.vr);
    let omega = c.get_real(vr("shaft.omega"))?;
    let (wk, _) = c.skidding_mut().expect("skidding").model().kinematic(omega);
    let mut t = c.time();
    let t0 = t;
    while t < t0 + settle_s - 1e-12 {
        c.do_step(t, h)?;
        t += h;
    }
    let mut tr = Trace {
        kinematic: wk,
        revs,
        ..Trace::default()
    };
    // Per step: unloaded balls' (angle, slip) and their wear, and the angle of the loaded
    // ball furthest along (the one leaving the zone).
    let mut steps: Vec<Sample> = Vec::new();
    let mut turned = 0.0;
    while turned < revs * std::f64::consts::TAU {
        c.do_step(t, h)?;
        t += h;
        c.ensure_outputs()?;
        let wc = c.get_real(vr("cage.omega"))?;
        turned += wc.abs() * h;
        let m = c.skidding_mut().expect("skidding").model();
        let q_max = (0..m.z())
            .map(|j| m.outer_contact(j).0.q)
            .fold(0.0, f64::max);
        let (mut free, mut w, mut exit) = (Vec::new(), 0.0, (f64::NAN, f64::INFINITY));
        for j in 0..m.z() {
            let (ct, dv, u) = m.outer_contact(j);
            let psi = m.balls[j]
                .psi
                .rem_euclid(std::f64::consts::TAU)
                .to_degrees();
            if ct.q < LOADED * q_max {
                free.push((psi, dv.abs() * 1e3));
                w += wear.contact(&ct, dv, u).area_rate;
            }
            // The ball leaving the zone: loaded above its centrifugal force (a few % of
            // the heaviest ball's load).
            if ct.q >= 0.02 * q_max {
                // Degrees past the load line (270) in the direction of travel.
                let past = (psi - 270.0).rem_euclid(360.0);
                if past < 180.0 && (exit.1.is_infinite() || past > exit.1) {
                    exit = (psi, past);
                }
            }
        }
        tr.t.push(t - t0);
        tr.cage.push(wc);
        // The median over the unloaded balls: a cage jerk moves them all, a ball just
        // leaving the zone with its own slip spike moves the median little.
        let mut v: Vec<f64> = free.iter().map(|f| f.1).collect();
        v.sort_by(f64::total_cmp);
        tr.slip.push(v.get(v.len() / 2).copied().unwrap_or(0.0));
        steps.push((free, w, exit.0));
    }
    tr.mean_cage = tr.cage.iter().sum::<f64>() / tr.cage.len().max(1) as f64;
    let mut sorted = tr.slip.clone();
    sorted.sort_by(f64::total_cmp);
    tr.median_slip = sorted.get(sorted.len() / 2).copied().unwrap_or(0.0);
    let hot: Vec<bool> = tr.slip.iter().map(|s| *s > 20.0 * tr.median_slip).collect();
    let (mut w_all, mut w_hot, mut n_hot) = (0.0, 0.0, 0.0);
    let mut best = (0.0, 0usize);
    for (i, (_, w, exit)) in steps.iter().enumerate() {
        w_all += w;
        if hot[i] {
            w_hot += w;
            n_hot += 1.0;
            if i == 0 || !hot[i - 1] {
                tr.bursts.push(tr.t[i]);
                tr.exit_angle.push(*exit);
            }
            if tr.bursts.len() == 1 && tr.slip[i] > best.0 {
                best = (tr.slip[i], i);
            }
        }
    }
    if !tr.bursts.is_empty() {
        tr.burst_angles = steps[best.1].0.iter().map(|f| f.0).collect();
        tr.burst_angles.sort_by(f64::total_cmp);
    }
    tr.wear_share = w_hot / w_all.max(1e-300);
    tr.step_share = n_hot / steps.len().max(1) as f64;
    Ok(tr)
}

/// The dry map's pattern: one cycle-1 window per variant of the numerics (docs only) and
/// the trace.
fn pattern(settle_s: f64, plan: &Plan, variants: bool) -> Res<Pattern> {
    let reading = AsperityReading::FilmParameter;
    let base = WearCycles {
        scene: scene(TractionLaw::MixedEhl(friction(
            1e-4,
            reading,
            FilmFormula::HamrockDowson,
        )))?,
        wear: OuterRaceWear::study2(None, reading),
        cells: 360,
        settle_s,
        window_cage_revs: plan.window,
        cycle_cage_revs: 100.0,
        cycles: 1,
        step_s: plan.step_s,
        max_step_fraction: 0.1,
    };
    let z = 14.0;
    let mut rows = Vec::new();
    if variants {
        let pass = 1.0 / z;
        let mut list: Vec<(String, WearCycles)> = vec![(
            format!(
                "as in the study (step {} s, 360 cells, {} cage rev)",
                plan.step_s, plan.window
            ),
            base.clone(),
        )];
        let mut v = base.clone();
        v.step_s = plan.step_s / 2.0;
        list.push((format!("output step halved ({} s)", v.step_s), v));
        let mut v = base.clone();
        v.cells = 720;
        list.push(("720 cells".into(), v));
        let mut v = base.clone();
        v.window_cage_revs += 0.5 * pass;
        list.push(("window + 1/2 ball pass".into(), v));
        let mut v = base.clone();
        v.window_cage_revs += 0.25 * pass;
        list.push(("window + 1/4 ball pass".into(), v));
        let mut v = base.clone();
        v.settle_s += 0.07;
        list.push(("run-in + 0.07 s (about 1 cage rev)".into(), v));
        for (label, w) in list {
            eprintln!("pattern: {label}");
            let rec = w.window(&[])?.record;
            rows.push(pattern_row(label, &rec, z));
        }
    }
    let trace = trace_dry(settle_s, plan.window, plan.step_s)?;
    Ok(Pattern { rows, trace })
}

/// The page's section on the dry map's peaks.
fn write_pattern(s: &mut String, pat: &Pattern) -> Res<()> {
    let tr = &pat.trace;
    let z = 14.0;
    let pass = std::f64::consts::TAU / (z * tr.mean_cage.abs().max(1e-300));
    writeln!(s, "## The dry map's peaks one ball spacing apart\n")?;
    writeln!(
        s,
        "Outside the load zone the dry map has peaks about one ball spacing (360°/14 = \
         25.7°) apart that stay at the same places on the race. Two questions: are they \
         made by the numerics of the wear window, or by the dynamics?\n"
    )?;
    if !pat.rows.is_empty() {
        writeln!(
            s,
            "**The numerics.** The first cycle's dry window again, each time with one thing \
             changed (out of the load zone = cells whose mean ball load is below {} % of the \
             heaviest; |H14|/mean = amplitude of the 14th circumferential harmonic of the rate \
             over those cells, divided by their mean rate; a flat map gives 0):\n",
            LOADED * 100.0
        )?;
        writeln!(
            s,
            "| window | peak rate (µm per 1e6 cage rev) | out of zone: \\|H14\\|/mean | out of zone: six highest maxima (deg) |\n|---|---|---|---|"
        )?;
        for r in &pat.rows {
            writeln!(
                s,
                "| {} | {:.4e} | {:.3} | {} |",
                r.label,
                r.peak,
                r.hz,
                r.maxima
                    .iter()
                    .map(|a| format!("{a:.1}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )?;
        }
        writeln!(
            s,
            "\nThe pattern does not follow the output step (the wear is sampled at each \
             communication point: no aliasing with the ball-pass period), the cell count \
             (no binning effect), a window longer by a fraction of a ball pass (the window \
             is counted in the cage's actual turning, so every ball passes every cell the \
             same number of times; no partial-pass sawtooth) or the run-in. It is in the \
             dynamics. (The peak rate grows with 720 cells: the deepest peak, at the load \
             zone's exit, is narrower than a 1° cell, so finer cells resolve more of its \
             height; the study keeps 360.)\n"
        )?;
    }
    let gaps: Vec<f64> = tr.bursts.windows(2).map(|w| (w[1] - w[0]) / pass).collect();
    let mut g = gaps.clone();
    g.sort_by(f64::total_cmp);
    let lock = g.get(g.len() / 2).map_or(f64::NAN, |g| g.round());
    let passes = tr.revs * z;
    writeln!(
        s,
        "**The dynamics.** The dry window traced step by step (cycle 1, {} cage \
         revolutions after the run-in; unloaded = outer load below {} % of the heaviest \
         ball's at that instant; a burst = the steps in which the median slip over the \
         unloaded balls exceeds 20 × its median over the window, {:.2} mm/s). The cage speed (mean {:.3} rad/s, kinematic {:.3} rad/s) \
         repeats one cycle: it stays near the kinematic speed, then drags down by a few \
         rad/s, then jumps back within a fraction of a millisecond as a ball leaves the \
         load zone (plot at the end of the page). \
         The unloaded balls, held on the race by their centrifugal force only, sit in their \
         pockets: the cage jerks their orbit along and their spin cannot follow, so all of \
         them slip together, at tens of mm/s for about a millisecond.\n",
        tr.revs,
        LOADED * 100.0,
        tr.median_slip,
        tr.mean_cage,
        tr.kinematic
    )?;
    writeln!(
        s,
        "- bursts found: {}, at (ms from the scene's start) {}\n\
         - intervals between bursts, in ball passes at the mean cage speed ({:.3} ms per pass): {}\n\
         - ball leaving the load zone at each burst's start (the ball furthest past the load line with more than 2 % of the heaviest ball's load, deg): {}\n\
         - the unloaded balls at the first burst's highest slip (deg): {}\n\
         - burst steps are {:.1} % of the steps and carry {:.1} % of the unloaded balls' wear\n",
        tr.bursts.len(),
        tr.bursts
            .iter()
            .map(|t| format!("{:.1}", t * 1e3))
            .collect::<Vec<_>>()
            .join(", "),
        pass * 1e3,
        gaps.iter()
            .map(|g| format!("{g:.2}"))
            .collect::<Vec<_>>()
            .join(", "),
        tr.exit_angle
            .iter()
            .map(|a| format!("{a:.1}"))
            .collect::<Vec<_>>()
            .join(", "),
        tr.burst_angles
            .iter()
            .map(|a| format!("{a:.1}"))
            .collect::<Vec<_>>()
            .join(", "),
        tr.step_share * 100.0,
        tr.wear_share * 100.0
    )?;
    if !lock.is_finite() {
        writeln!(
            s,
            "Fewer than two bursts in this window: no interval to measure (the quick \
             version's window is short; the full page has several).\n"
        )?;
        return Ok(());
    }
    writeln!(
        s,
        "A burst comes only when a ball leaves the load zone, and (median interval) every \
         {lock}th time: the cage's relaxation cycle is locked to a whole number of ball \
         passes. After a whole number of passes the balls stand where they stood, so every \
         burst finds the unloaded balls at the same places on the race, one ball spacing \
         apart, and wears them there: the peaks are fixed on the race because the burst \
         cycle is locked to the ball passing, and one ball spacing apart because all the \
         unloaded balls slip at once. The same burst gives the balls leaving the zone a \
         slip spike under a load of tens of newtons, at the load zone's exit side, where \
         the dry map is deepest. This is what the skidding level gives for the study's data \
         (its cage drag, pocket and traction laws), not a numerical effect. \
         `examples/wear_map_probe.rs` repeats the window with other numerics, speeds and \
         drag (`--step`, `--sub`, `--cells`, `--window`, `--settle`, `--rtol`, `--rpm`, \
         `--drag`) and dumps every contact (`--dump FILE`). A window spans a whole number \
         of ball passes ({passes:.0}) but not of burst cycles ({passes:.0}/{lock} = {:.1}), \
         so the burst peaks' heights in one window's extrapolation depend on where it \
         starts by up to one burst in {:.0}; the cycles' window offsets spread that over \
         the run.\n",
        passes / lock,
        (passes / lock).ceil()
    )?;
    Ok(())
}
