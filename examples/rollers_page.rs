//! The rollers page, `docs/rollers.md` with its plots: the ISO/TS 16281 slicing on a worked
//! case, the lamina convergence behind `DEFAULT_LAMINAE`, the pressure along a roller for each
//! profile (aligned and tilted), life against tilt for each profile, and a cylindrical roller
//! bearing's outer-race defect: its envelope spectrum at BPFO.
//!
//! ```text
//! cargo run --release --example rollers_page              # docs/rollers.md and docs/rollers-*.png
//! cargo run --example rollers_page -- --quick             # CI: coarser, into out/rollers/
//! ```
//!
//! `--out DIR` writes elsewhere. The quick version takes a 1000-lamina reference instead of
//! 4000, four tilts instead of thirteen and 0.3 s of the defect scene's run instead of 0.8 s.

use raceway::analysis::envelope_spectrum;
use raceway::component::{variables, Component};
use raceway::contact::lamina::{
    line_hertz, Laminae, LineGeometry, Profile, C_STEEL_N_MM, DEFAULT_LAMINAE, E_PRIME_REFERENCE,
};
use raceway::geometry::roller::RollerBearing;
use raceway::geometry::roller_catalogue::lookup;
use raceway::models::quasi_static::rollers::{solve_with, RollerSolution, SolveOptions};
use raceway::plot::{plot, Axes, Marker, Series};
use raceway::ratings::lamina_life::{
    edge_factor, lamina_life, lamina_static_safety, LaminaLifeOptions,
};
use raceway::ratings::roller::{equivalent_dynamic_load, l10_roller, roller_ratings};
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The load names the solver uses in a refusal.
const NAMES: [&str; 5] = ["fx", "fy", "fz", "mx", "my"];

/// The radial load of the worked case and of the profile sections, N.
const FR: f64 = 8000.0;

/// The six profiles for a roller of geometry `g`, with their labels: the straight roller, a
/// circular crown, a partial crown, ISO/TS 16281's logarithmic profile, Lundberg's for the
/// design load `qd` and Fujiwara–Kawase's for the same design load.
fn profiles(g: &LineGeometry, qd: f64) -> Vec<(String, Profile)> {
    vec![
        ("straight".into(), Profile::None),
        ("crown R 2 m".into(), Profile::Crown { radius: 2.0 }),
        (
            "partial crown (flat Lwe/2, R 0.5 m)".into(),
            Profile::PartialCrown {
                flat: 0.5 * g.lwe,
                radius: 0.5,
            },
        ),
        ("ISO/TS 16281 log".into(), Profile::IsoLog),
        (
            format!("Lundberg, Qd {:.0} N", qd),
            Profile::Lundberg { design_load: qd },
        ),
        (
            format!("Fujiwara-Kawase, Qd {:.0} N, K1 1.5, K2 0.8, zm 10 um", qd),
            Profile::FujiwaraKawase {
                design_load: qd,
                k1: 1.5,
                k2: 0.8,
                end_drop: 10e-6,
            },
        ),
    ]
}

/// A bearing and the azimuth of its roller 0 (`-90°`: a roller on the load line of a downward
/// load), solved by the library's quasi-static roller solver
/// (`raceway::models::quasi_static::rollers`).
struct Ring {
    b: RollerBearing,
    first_azimuth: f64,
}

impl Ring {
    fn new(b: RollerBearing) -> Ring {
        Ring {
            b,
            first_azimuth: -0.5 * PI,
        }
    }

    /// Equilibrium under `fr` downward (and `fa` along `+z`), the ring held tilted `rx` (rad)
    /// about `x` (the moments are the reaction), at rest.
    fn solve_axial(&self, fr: f64, fa: f64, rx: f64) -> RollerSolution {
        let o = SolveOptions {
            tilt: Some([rx, 0.0]),
            first_azimuth: self.first_azimuth,
        };
        solve_with(&self.b, [0.0, -fr, fa, 0.0, 0.0], 0.0, NAMES, o).expect("equilibrium")
    }

    fn solve(&self, fr: f64, rx: f64) -> RollerSolution {
        self.solve_axial(fr, 0.0, rx)
    }
}

/// Inner-contact lamina loads (N) of every roller.
fn lamina_loads(s: &RollerSolution) -> Vec<Vec<f64>> {
    s.rollers
        .iter()
        .map(|r| r.lamina_load_inner.clone())
        .collect()
}

/// Outer-contact lamina loads (N) of every roller.
fn lamina_loads_outer(s: &RollerSolution) -> Vec<Vec<f64>> {
    s.rollers.iter().map(|r| r.lamina_load.clone()).collect()
}

/// Approach carrying `load` for one roller at tilt `psi` (Newton).
fn approach_for(l: &Laminae, load: f64, psi: f64) -> f64 {
    let mut d = (load / (l.cs * l.len() as f64)).powf(0.9) + l.lwe * psi.abs();
    for _ in 0..200 {
        let r = l.evaluate(d, psi);
        let step = (r.force - load) / r.dforce_ddelta;
        d -= step;
        if step.abs() < 1e-16 {
            break;
        }
    }
    d
}

fn png(out: &Path, name: &str) -> PathBuf {
    out.join(format!("rollers-{name}.png"))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let quick = args.iter().any(|a| a == "--quick");
    let out = args
        .iter()
        .position(|a| a == "--out")
        .and_then(|i| args.get(i + 1))
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(if quick { "out/rollers" } else { "docs" }));
    std::fs::create_dir_all(&out).expect("output folder");
    let mut md = String::new();
    let _ = write!(
        md,
        "# Rollers\n\nGenerated by `cargo run --release --example rollers_page`{} \
         (examples/rollers_page.rs). Cylindrical roller bearings as lines of independent laminae \
         after ISO/TS 16281:2008 (docs/physics.md §R1–§R12); the bearing is the catalogue's \
         NU206 (`raceway bearings NU206`: internal geometry ESTIMATED from the envelope), \
         steel, 14 rollers of {} laminae, except in the tapered roller bearing's section \
         (30206). Quasi-static solutions: the library's roller solver \
         (`raceway::models::quasi_static::rollers::solve_with`, the one behind `raceway \
         quasi-static --bearing`), Newton on the ring displacement with the laminae's exact \
         stiffness, the ring's tilt held where a section says so, the rollers at rest (no \
         centrifugal force).\n\n",
        if quick { " -- --quick" } else { "" },
        DEFAULT_LAMINAE
    );
    let nu206 = lookup("NU206").expect("NU206").build().expect("builds");
    worked_case(&mut md, &nu206);
    convergence(&mut md, &out, quick);
    let qd = pressure_along(&mut md, &out, &nu206);
    life_against_tilt(&mut md, &out, &nu206, qd, quick);
    tapered_load_zone(&mut md, &out);
    envelope(&mut md, &out, quick);
    let path = out.join("rollers.md");
    std::fs::write(&path, md).expect("write the page");
    println!("wrote {}", path.display());
}

/// ISO/TS 16281's steel constant by hand against the laminae, and Stribeck's line-contact
/// ratio on NU206 at zero clearance.
fn worked_case(md: &mut String, b: &RollerBearing) {
    let lwe_mm = b.lwe * 1e3;
    let delta_mm: f64 = 0.010;
    let by_hand = C_STEEL_N_MM * lwe_mm.powf(8.0 / 9.0) * delta_mm.powf(10.0 / 9.0);
    let g = LineGeometry {
        e_prime: E_PRIME_REFERENCE,
        ..b.line_geometry()
    };
    let straight = Laminae::new(&g, &Profile::None, DEFAULT_LAMINAE).expect("laminae");
    let sliced = straight.evaluate(delta_mm * 1e-3, 0.0).force;
    // Stribeck: zero clearance, straight rollers, a roller on the load line and the ring
    // turned half a spacing.
    let mut zero = b.clone();
    zero.pd = 0.0;
    zero.profile = Profile::None;
    let ring = Ring::new(zero.clone());
    let sol = ring.solve(FR, 0.0);
    let q = sol.q;
    let qmax = sol.rollers.iter().map(|r| r.load[0]).fold(0.0, f64::max);
    let mut half = Ring::new(zero);
    half.first_azimuth += PI / b.z as f64;
    let qmax_h = half
        .solve(FR, 0.0)
        .rollers
        .iter()
        .map(|r| r.load[0])
        .fold(0.0, f64::max);
    let _ = write!(
        md,
        "## The ISO/TS 16281 method on a worked case\n\n\
         Source: ISO/TS 16281:2008's roller law (the lamina load `q_k = (c_L/ns) delta_k^(10/9)`, \
         `c_L = 35948 Lwe^(8/9)` N/mm^(10/9) for steel) and Stribeck's ratio for line contact at \
         zero clearance, `Q_max ≈ 4.08 Fr/Z` (Harris & Kotzalas 2007, vol. 1 ch. 7). No \
         published per-lamina example was at hand to copy, so the case is computed both from \
         the standard's equations by hand and by the laminae:\n\n\
         | quantity | by hand | laminae | difference |\n|---|---|---|---|\n\
         | load of one NU206 roller (Lwe {lwe_mm:.3} mm, straight) at a uniform approach of 10 µm | \
         35948 × {lwe_mm:.3}^(8/9) × 0.010^(10/9) = {by_hand:.2} N | {sliced:.2} N ({} laminae) | {:.1e} |\n\
         | NU206 at zero clearance, straight rollers, Fr = {FR:.0} N: `Q_max Z / Fr`, a roller on the load line | 4.08 | {:.3} | {:.2} % |\n\
         | the same, rollers half a spacing off the load line | 4.08 | {:.3} | {:.2} % |\n\n\
         Stribeck's 4.08 is the continuous-azimuth limit of the cosine load distribution with \
         the exponent 10/9 (its integral over the half circle); 14 discrete rollers scatter \
         around it with the ring's angle. The ring moves {:.2} µm down for {FR:.0} N (the \
         roller on the load line carries {:.0} N).\n\n",
        DEFAULT_LAMINAE,
        sliced / by_hand - 1.0,
        qmax * b.z as f64 / FR,
        100.0 * (qmax * b.z as f64 / FR / 4.08 - 1.0),
        qmax_h * b.z as f64 / FR,
        100.0 * (qmax_h * b.z as f64 / FR / 4.08 - 1.0),
        -q[1] * 1e6,
        qmax
    );
}

/// The convergence study behind `DEFAULT_LAMINAE` (lamina.rs's test, written out with a plot).
fn convergence(md: &mut String, out: &Path, quick: bool) {
    let g = LineGeometry {
        lwe: 0.01,
        dwe: 0.01,
        e_prime: E_PRIME_REFERENCE,
        tapered: false,
    };
    let (load, r_race) = (4.0e3, 0.004);
    let n_ref = if quick { 1000 } else { 4000 };
    let ns_list = [5usize, 10, 20, 30, 50, 100, 200];
    let run = |p: &Profile, ns: usize, psi: f64| {
        let l = Laminae::new(&g, p, ns).expect("laminae");
        let d = approach_for(&l, load, psi);
        let mut q = vec![0.0; ns];
        l.evaluate_into(d, psi, &mut q);
        let pk = q.iter().cloned().fold(0.0, f64::max);
        (d, line_hertz(pk / l.width(), r_race, g.e_prime).1)
    };
    let _ = write!(
        md,
        "## Lamina convergence\n\n\
         A roller `Dwe = Lwe = 10 mm` held at 4 kN (aligned peak pressure about 2.1 GPa on a \
         race of `R = 4 mm`), tilted 1 mrad (the upper end of what makers allow a cylindrical \
         roller bearing, 2′–4′) and 3 mrad; errors against {n_ref} laminae of the approach that \
         carries 4 kN and of the peak lamina pressure there. The default, \
         `DEFAULT_LAMINAE = {DEFAULT_LAMINAE}`, is the smallest count that keeps every entry \
         within 1 % (0.75 % at most, the straight roller's edge pressure at 3 mrad, which \
         converges as `1/ns`); 10 laminae leave 2.3 %, and the cost grows linearly with the count.\n\n\
         | tilt | profile | quantity |"
    );
    for ns in ns_list {
        let _ = write!(md, " ns = {ns} |");
    }
    md.push_str("\n|---|---|---|");
    md.push_str(&"---|".repeat(ns_list.len()));
    md.push('\n');
    let mut curves: Vec<(String, Vec<f64>)> = Vec::new();
    for psi in [1e-3, 3e-3] {
        for (name, p) in [
            ("straight", Profile::None),
            ("crown R 2 m", Profile::Crown { radius: 2.0 }),
            ("ISO/TS log", Profile::IsoLog),
        ] {
            let (d_ref, p_ref) = run(&p, n_ref, psi);
            let (mut ed, mut ep) = (Vec::new(), Vec::new());
            for ns in ns_list {
                let (d, pk) = run(&p, ns, psi);
                ed.push((d / d_ref - 1.0).abs());
                ep.push((pk / p_ref - 1.0).abs());
            }
            for (q, e) in [("approach at 4 kN", &ed), ("peak pressure at 4 kN", &ep)] {
                let _ = write!(md, "| {} mrad | {name} | {q} |", psi * 1e3);
                for v in e.iter() {
                    let _ = write!(md, " {:.2} % |", 100.0 * v);
                }
                md.push('\n');
            }
            let worst: Vec<f64> = ed
                .iter()
                .zip(&ep)
                .map(|(a, b)| a.max(*b).max(1e-7))
                .collect();
            curves.push((format!("{name}, {} mrad", psi * 1e3), worst));
        }
    }
    let xs: Vec<f64> = ns_list.iter().map(|&n| n as f64).collect();
    let series: Vec<Series> = curves
        .iter()
        .map(|(l, y)| Series {
            label: l,
            x: &xs,
            y,
            points: false,
        })
        .collect();
    let title = format!(
        "Lamina convergence: roller 10 x 10 mm at 4 kN, larger error of approach and peak pressure against {n_ref} laminae"
    );
    plot(
        &png(out, "convergence"),
        &Axes {
            title: &title,
            x_label: "laminae ns",
            y_label: "relative error (1)",
            log_x: false,
            log_y: true,
            equal: false,
        },
        &series,
        &[Marker {
            x: DEFAULT_LAMINAE as f64,
            label: format!("default {DEFAULT_LAMINAE}"),
        }],
    )
    .expect("plot");
    md.push_str("\n![lamina convergence](rollers-convergence.png)\n\n");
}

/// Pressure along the most loaded roller of NU206 under `FR`, aligned and tilted 1 mrad, for
/// each profile; returns the design load used for Lundberg's and Fujiwara–Kawase's profiles.
fn pressure_along(md: &mut String, out: &Path, b: &RollerBearing) -> f64 {
    // Design load: the most loaded roller's at FR by Stribeck's ratio.
    let qd = (4.08 * FR / b.z as f64 / 100.0).round() * 100.0;
    let g = b.line_geometry();
    let _ = write!(
        md,
        "## Pressure along a roller, each profile\n\n\
         NU206 (`Lwe` {:.2} mm, `Dwe` {:.2} mm, clearance {:.0} µm) under Fr = {FR:.0} N \
         downward: the inner-race line-Hertz peak pressure of each lamina of the most loaded \
         roller, with each of the six profiles, aligned and with the inner ring tilted 1 mrad \
         about the horizontal axis across the load (so the most loaded roller sees the whole \
         1 mrad). Lundberg's and Fujiwara–Kawase's profiles are designed for Qd = {qd:.0} N \
         (Stribeck's `4.08 Fr/Z`). The laminae are independent springs, so a Lundberg profile \
         shows as an end relief, not as the uniform pressure it gives with the elastic \
         coupling along the roller it was designed with (docs/physics.md §R2).\n\n\
         | profile | tilt | roller load (N) | peak pressure (MPa) | at x (mm) | end-lamina pressure (MPa) | laminae in contact |\n|---|---|---|---|---|---|---|\n",
        b.lwe * 1e3,
        b.dwe * 1e3,
        b.pd * 1e6
    );
    for (tilt, name) in [(0.0, "aligned"), (1e-3, "tilted")] {
        let mut curves: Vec<(String, Vec<f64>, Vec<f64>)> = Vec::new();
        for (label, p) in profiles(&g, qd) {
            let mut bb = b.clone();
            bb.profile = p;
            let ring = Ring::new(bb);
            let loads = lamina_loads(&ring.solve(FR, tilt));
            let j = (0..loads.len())
                .max_by(|&a, &c| {
                    loads[a]
                        .iter()
                        .sum::<f64>()
                        .total_cmp(&loads[c].iter().sum::<f64>())
                })
                .expect("rollers");
            let l = ring.b.laminae().expect("laminae");
            let mut pr = vec![0.0; l.len()];
            l.pressures(
                &loads[j],
                ring.b.reduced_radius_inner(),
                ring.b.e_prime_inner(),
                &mut pr,
            );
            let k = (0..pr.len())
                .max_by(|&a, &c| pr[a].total_cmp(&pr[c]))
                .expect("laminae");
            let end = pr[0].max(pr[pr.len() - 1]);
            let _ = writeln!(
                md,
                "| {label} | {name} | {:.0} | {:.0} | {:+.2} | {:.0} | {} of {} |",
                loads[j].iter().sum::<f64>(),
                pr[k] * 1e-6,
                l.x[k] * 1e3,
                end * 1e-6,
                loads[j].iter().filter(|&&v| v > 0.0).count(),
                l.len()
            );
            curves.push((
                label,
                l.x.iter().map(|x| x * 1e3).collect(),
                pr.iter().map(|p| p * 1e-6).collect(),
            ));
        }
        let series: Vec<Series> = curves
            .iter()
            .map(|(l, x, y)| Series {
                label: l,
                x,
                y,
                points: false,
            })
            .collect();
        let title = format!(
            "NU206, Fr {FR:.0} N, most loaded roller, {}: inner-race pressure per lamina",
            if tilt == 0.0 {
                "aligned".to_string()
            } else {
                format!("ring tilted {:.0} mrad", tilt * 1e3)
            }
        );
        plot(
            &png(out, &format!("pressure-{name}")),
            &Axes {
                title: &title,
                x_label: "x along the roller from its mid-plane (mm)",
                y_label: "peak pressure (MPa)",
                ..Axes::default()
            },
            &series,
            &[],
        )
        .expect("plot");
    }
    md.push_str(
        "\n![pressure along the roller, aligned](rollers-pressure-aligned.png)\n\n\
         ![pressure along the roller, tilted 1 mrad](rollers-pressure-tilted.png)\n\n",
    );
    qd
}

/// Life against tilt for each profile: ISO/TS 16281's reference rating life from the lamina
/// loads, with and without its edge-stress factor, and the lamina static safety.
fn life_against_tilt(md: &mut String, out: &Path, b: &RollerBearing, qd: f64, quick: bool) {
    let tilts: Vec<f64> = if quick {
        vec![0.0, 1e-3, 2e-3, 3e-3]
    } else {
        (0..=12).map(|k| k as f64 * 0.25e-3).collect()
    };
    let plain = LaminaLifeOptions {
        edge_factor: false,
        ..LaminaLifeOptions::default()
    };
    let r = roller_ratings(b).expect("ratings");
    let l10 = l10_roller(r.cr, FR);
    let g = b.line_geometry();
    // (label, lives with the edge factor, without, S0 per tilt)
    type Row = (String, Vec<f64>, Vec<f64>, Vec<f64>);
    let mut rows: Vec<Row> = Vec::new();
    for (label, p) in profiles(&g, qd) {
        let mut bb = b.clone();
        bb.profile = p;
        let ring = Ring::new(bb);
        let (mut with, mut without, mut s0) = (Vec::new(), Vec::new(), Vec::new());
        for &t in &tilts {
            let sol = ring.solve(FR, t);
            let (i, o) = (lamina_loads(&sol), lamina_loads_outer(&sol));
            let life = |opt| {
                lamina_life(&ring.b, &i, &o, opt)
                    .expect("life")
                    .l10r_mrev
                    .expect("loaded")
            };
            with.push(life(LaminaLifeOptions::default()));
            without.push(life(plain));
            let pmax = sol
                .rollers
                .iter()
                .flat_map(|r| r.lamina_pressure.iter().copied())
                .fold(0.0, f64::max);
            s0.push(lamina_static_safety(pmax).expect("loaded"));
        }
        rows.push((label, with, without, s0));
    }
    let ns = b.laminae;
    let _ = write!(
        md,
        "## Life against tilt, each profile\n\n\
         NU206 under Fr = {FR:.0} N, the inner ring rotating and held tilted as above: \
         ISO/TS 16281's reference rating life `L10r` from the lamina loads \
         (`raceway::ratings::lamina_life`, docs/physics.md §R10), in million revolutions. Per \
         lamina `k` and raceway the equivalent load over the rollers (rotating inner ring \
         `(Σ_j (f_k q_jk)^4 / Z)^(1/4)`, stationary outer ring `(Σ_j (f_k q_jk)^(9/2) / \
         Z)^(2/9)`), the lamina ratings `q_c = Q_c ns^(-7/9)` from ISO 281's `Cr` = {:.0} N \
         through the line-contact `J` ratios 0.378 and 0.364 and `λν` = 0.83, and `L10r = \
         [Σ_k (q_ei,k/q_ci)^(9/2) + (q_ee,k/q_ce)^(9/2)]^(-8/9)`. The edge-stress factor \
         `f_k = 1 - 0.01/ln(1.985 |2k - ns - 1|/(2 ns - 2))` is 1 at the middle and {:.2} on \
         the end laminae ({ns} laminae), so it costs life only where the end laminae carry \
         load. **UNSOURCED**: that factor and the division of `Cr` by `λν` are the method as \
         publicly reproduced, not checked against the standard's text; without both, aligned \
         straight rollers under ISO 281's load distribution give ISO 281's `L = 1` at `P = C` \
         (tested). For comparison ISO 281's `L10 = (Cr/P)^(10/3)` = {l10:.1} million \
         revolutions, the same for every profile and tilt.\n\n\
         `L10r` with the edge-stress factor (million revolutions):\n\n| profile |",
        r.cr,
        edge_factor(0, ns),
    );
    let header = |md: &mut String| {
        for t in &tilts {
            let _ = write!(md, " {:.2} mrad |", t * 1e3);
        }
        md.push_str("\n|---|");
        md.push_str(&"---|".repeat(tilts.len()));
        md.push('\n');
    };
    header(md);
    for (label, with, _, _) in &rows {
        let _ = write!(md, "| {label} |");
        for l in with {
            let _ = write!(md, " {l:.1} |");
        }
        md.push('\n');
    }
    md.push_str("\nWhat the edge-stress factor costs: `L10r` with it over `L10r` without it:\n\n| profile |");
    header(md);
    for (label, with, without, _) in &rows {
        let _ = write!(md, "| {label} |");
        for (a, c) in with.iter().zip(without) {
            let _ = write!(md, " {:.3} |", a / c);
        }
        md.push('\n');
    }
    md.push_str(
        "\nStatic safety of the most loaded lamina, `S0 = (4000 MPa / p_max)²` (line contact: \
         the peak pressure grows as the square root of the lamina load, so `S0` is the factor \
         on that lamina's load to ISO 76's 4 000 MPa):\n\n| profile |",
    );
    header(md);
    for (label, _, _, s0) in &rows {
        let _ = write!(md, "| {label} |");
        for v in s0 {
            let _ = write!(md, " {v:.2} |");
        }
        md.push('\n');
    }
    let xs: Vec<f64> = tilts.iter().map(|t| t * 1e3).collect();
    let iso = vec![l10; xs.len()];
    let mut series: Vec<Series> = rows
        .iter()
        .map(|(l, y, _, _)| Series {
            label: l,
            x: &xs,
            y,
            points: false,
        })
        .collect();
    series.push(Series {
        label: "ISO 281 L10 (no tilt or profile effect)",
        x: &xs,
        y: &iso,
        points: true,
    });
    plot(
        &png(out, "life-tilt"),
        &Axes {
            title: &format!(
                "NU206, Fr {FR:.0} N: ISO/TS 16281 L10r with the edge-stress factor against ring tilt"
            ),
            x_label: "ring tilt (mrad)",
            y_label: "L10r (million revolutions)",
            log_y: true,
            ..Axes::default()
        },
        &series,
        &[],
    )
    .expect("plot");
    md.push_str("\n![life against tilt](rollers-life-tilt.png)\n\n");
}

/// The tapered roller bearing 30206 under a radial load and three axial loads: the roller
/// loads around the circumference (cup, cone, flange), the ring's tilt held at zero.
fn tapered_load_zone(md: &mut String, out: &Path) {
    let b = lookup("30206").expect("30206").build().expect("builds");
    let ring = Ring::new(b.clone());
    let fr = 5000.0;
    let e = 1.5 * b.alpha.tan();
    // Fa/Fr at least tan(alpha): below it no load zone balances the radial load (one roller
    // on the load line carries Fa/Fr = tan(alpha), a wider zone more).
    let fas = [0.8 * e * fr, 1.2 * e * fr, 2.4 * e * fr];
    let r = roller_ratings(&b).expect("ratings");
    let _ = write!(
        md,
        "## Tapered roller bearing: load zone under combined load\n\n\
         The catalogue's 30206 (`raceway bearings 30206`, internal geometry ESTIMATED; cup \
         angle {:.2}°, {} rollers, `e = 1.5 tan α` = {e:.3}), Fr = {fr:.0} N downward with \
         three axial loads, the inner ring pushed along `+z` toward the taper's apex, its tilt \
         held at zero (a shaft's other bearing holds it; the moment is the reaction), at rest. \
         Each roller is in equilibrium between cup, cone and cone back flange \
         (docs/physics.md §R7): the cone carries `Q_i = ρ_i Q_o` and the flange `Q_f = ρ_f \
         Q_o` of the cup load. More axial load widens the load zone toward the whole \
         circumference, the classical behaviour (the load-zone parameter `ε` grows with \
         `Fa/(Fr tan α)`, [Harris 2007] vol. 1 ch. 7). Below `Fa/Fr = tan α` = {:.3} a lone \
         tapered bearing with its tilt held has no equilibrium (a single roller on the load \
         line carries exactly `tan α`, every wider zone more), and the solver reports that it \
         did not converge.\n\n\
         | Fa (N) | Fa/Fr | loaded rollers | Q_o max (N) | Q_i max (N) | Q_f max (N) | ring axial shift (µm) | ring moment reaction (N m) | ISO 281 P (N) | L10 (Mrev) | L10r lamina (Mrev) | S0 lamina |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
        b.alpha.to_degrees(),
        b.z,
        b.alpha.tan()
    );
    let mut curves: Vec<(String, Vec<f64>, Vec<f64>)> = Vec::new();
    let mut moment = 0.0;
    for &fa in &fas {
        let sol = ring.solve_axial(fr, fa, 0.0);
        moment = -sol.rollers_force[3];
        let loaded = sol.rollers.iter().filter(|r| r.load[1] > 0.0).count();
        let mx = |f: &dyn Fn(&raceway::models::quasi_static::rollers::RollerRow) -> f64| {
            sol.rollers.iter().map(f).fold(0.0, f64::max)
        };
        let (p, ..) = equivalent_dynamic_load(&b, fr, fa);
        let life = lamina_life(
            &b,
            &lamina_loads(&sol),
            &lamina_loads_outer(&sol),
            LaminaLifeOptions::default(),
        )
        .expect("life");
        let pmax = mx(&|r| r.lamina_pressure.iter().copied().fold(0.0, f64::max));
        let _ = writeln!(
            md,
            "| {fa:.0} | {:.3} | {loaded} of {} | {:.0} | {:.0} | {:.0} | {:.2} | {:.2} | {p:.0} | {:.1} | {} | {:.2} |",
            fa / fr,
            b.z,
            mx(&|r| r.load[1]),
            mx(&|r| r.load[0]),
            mx(&|r| r.flange_load),
            sol.q[2] * 1e6,
            -sol.rollers_force[3],
            l10_roller(r.cr, p),
            life.l10r_mrev
                .map(|v| format!("{v:.1}"))
                .unwrap_or_else(|| "—".into()),
            lamina_static_safety(pmax).unwrap_or(f64::INFINITY)
        );
        // Azimuth from the load line (the roller at -90° first), degrees, over a full turn.
        let x: Vec<f64> = sol
            .rollers
            .iter()
            .map(|r| (r.psi + 0.5 * PI).to_degrees())
            .collect();
        let y: Vec<f64> = sol.rollers.iter().map(|r| r.load[1]).collect();
        curves.push((format!("Fa {fa:.0} N (Fa/Fr {:.2})", fa / fr), x, y));
    }
    let series: Vec<Series> = curves
        .iter()
        .map(|(l, x, y)| Series {
            label: l,
            x,
            y,
            points: true,
        })
        .collect();
    plot(
        &png(out, "tapered-load-zone"),
        &Axes {
            title: &format!(
                "30206, Fr {fr:.0} N with three axial loads, tilt held at 0: cup load of each roller"
            ),
            x_label: "roller azimuth from the radial load line (degrees)",
            y_label: "cup load Q_o (N)",
            ..Axes::default()
        },
        &series,
        &[],
    )
    .expect("plot");
    let _ = write!(
        md,
        "\nThe moment reaction is the same for every axial load: every roller's force passes \
         through the bearing's effective load centre on the axis, here {:.2} mm from the \
         reference plane (the moment over Fr). ISO 281 `Cr` = {:.0} N for this geometry. The lamina life uses the same method and \
         UNSOURCED steps as the section above, with the cone's lamina loads on the rotating \
         inner raceway and the cup's on the stationary outer one.\n\n\
         ![tapered load zone](rollers-tapered-load-zone.png)\n\n",
        1e3 * moment.abs() / fr,
        r.cr
    );
}

/// The NU206 outer-race defect scene (`examples/scenes/nu206-outer-defect.toml`) and the same
/// scene without its defect: `shaft.y` after `settle` s, `h` the step.
fn shaft_y(text: &str, t_end: f64, settle: f64) -> (Vec<f64>, f64, f64) {
    let mut c = Component::from_text(text).expect("scene");
    let scene = raceway::Scene::from_text(text).expect("scene");
    let h = scene.run.step_s;
    let omega = scene.inputs.initial_value("shaft.omega");
    let vy = variables::by_name("shaft.y").expect("shaft.y").vr;
    let n = (t_end / h).round() as usize;
    let skip = ((settle / h) as usize).min(n / 2);
    let mut y = Vec::with_capacity(n);
    for i in 0..n {
        c.do_step(i as f64 * h, h).expect("step");
        if i >= skip {
            y.push(c.get_real(vy).expect("shaft.y"));
        }
    }
    (y, h, omega)
}

/// The NU206 outer-race defect scene: the envelope spectrum of its `shaft.y` with BPFO and its
/// harmonics marked, beside the healthy bearing's (the same scene without the defect).
fn envelope(md: &mut String, out: &Path, quick: bool) {
    let text = include_str!("scenes/nu206-outer-defect.toml");
    let line = text
        .lines()
        .find(|l| l.starts_with("defects = "))
        .expect("the scene has a defect");
    let healthy_text = text.replace(line, "");
    let scene = raceway::Scene::from_text(text).expect("scene");
    let d = &scene.effects.defects[0];
    // As `raceway run` analyses it: the second half of the run.
    let t_end = if quick { 0.3 } else { scene.run.duration_s };
    let (y, h, omega) = shaft_y(text, t_end, 0.5 * t_end);
    let (y0, _, _) = shaft_y(&healthy_text, t_end, 0.5 * t_end);
    let b = lookup("NU206").expect("NU206").build().expect("builds");
    let fs_hz = omega / (2.0 * PI);
    let ftf = 0.5 * fs_hz * (1.0 - b.gamma());
    let bpfo = b.z as f64 * ftf;
    let bpfi = b.z as f64 * (fs_hz - ftf);
    let bsf = b.dpw / (2.0 * b.dwe) * (1.0 - b.gamma() * b.gamma()) * fs_hz;
    // The band of the run summary: above three times the highest defect frequency, to 0.8 of
    // the Nyquist frequency (the impacts ring there; the envelope keeps their rate).
    let top = bpfi.max(bpfo).max(2.0 * bsf);
    let band = (3.0 * top, 0.8 * 0.5 / h);
    let s = envelope_spectrum(&y, 1.0 / h, Some(band));
    let s0 = envelope_spectrum(&y0, 1.0 / h, Some(band));
    let keep: Vec<usize> = (1..s.freq.len())
        .filter(|&k| s.freq[k] <= 4.5 * bpfo)
        .collect();
    let pick = |s: &raceway::analysis::Spectrum| -> (Vec<f64>, Vec<f64>) {
        keep.iter().map(|&k| (s.freq[k], s.amp[k] * 1e9)).unzip()
    };
    let (f, a) = pick(&s);
    let (_, a0) = pick(&s0);
    let df = s.freq[1] - s.freq[0];
    let (fp, ap) = s
        .peak_in(bpfo - 2.0 * df, bpfo + 2.0 * df)
        .expect("a line at BPFO");
    let floor = s.median_in(0.5 * bpfo, 2.0 * bpfo);
    let at0 = s0.at(bpfo);
    plot(
        &png(out, "envelope"),
        &Axes {
            title: &format!(
                "nu206-outer-defect: envelope spectrum of shaft.y, {:.0} rpm, Fr 4 kN, {:.2} s analysed",
                omega * 30.0 / PI,
                y.len() as f64 * h
            ),
            x_label: "frequency (Hz)",
            y_label: "envelope amplitude of shaft.y (nm)",
            log_y: true,
            ..Axes::default()
        },
        &[
            Series {
                label: "outer-race spall over half the raceway",
                x: &f,
                y: &a,
                points: false,
            },
            Series {
                label: "healthy (same scene, no defect)",
                x: &f,
                y: &a0,
                points: false,
            },
        ],
        &[
            Marker {
                x: bpfo,
                label: "BPFO".into(),
            },
            Marker {
                x: 2.0 * bpfo,
                label: "2 BPFO".into(),
            },
            Marker {
                x: 3.0 * bpfo,
                label: "3 BPFO".into(),
            },
            Marker {
                x: 2.0 * bsf,
                label: "2 BSF".into(),
            },
        ],
    )
    .expect("plot");
    let _ = write!(
        md,
        "## A cylindrical roller bearing's outer-race defect: envelope spectrum at BPFO\n\n\
         The shipped scene `examples/scenes/nu206-outer-defect.toml` (ring level, 2 DOF, \
         load-driven, 4 kN at {:.0} rpm, 1 kg on the inner ring): an outer-race spall at the \
         bottom of the load zone, {} mm around the race and {} µm deep, over {} mm of the \
         roller's {:.1} mm effective length centred {} mm from its mid-plane, so it takes \
         material from half the laminae of each roller that crosses it and leaves the other \
         half as they are (docs/physics.md §R12). `shaft.y` at 10 kHz, the second half of the \
         run ({:.2} s, {:.2} Hz bins, as `raceway run` analyses it), band-passed over \
         {:.0}–{:.0} Hz (above three times the highest characteristic frequency, where the \
         impacts ring) and enveloped (Hilbert). BPFO = `Z/2 fs (1 - γ)` = {bpfo:.2} Hz with the \
         roller's γ = Dwe/Dpw = {:.4}. The defect's line: {fp:.2} Hz ({:+.3} % from BPFO), \
         {:.1} nm, {:.0} times the median floor over [BPFO/2, 2 BPFO]. The healthy bearing's \
         envelope at BPFO, in the same band, is {:.3} nm, {:.0} times lower: the roller \
         passage alone makes a weak line; the spall's impacts make the strong one and its \
         harmonics.\n\n\
         ![envelope spectrum](rollers-envelope.png)\n",
        omega * 30.0 / PI,
        d.width_mm,
        d.depth_um,
        d.axial_width_mm.unwrap_or(b.lwe * 1e3),
        b.lwe * 1e3,
        d.axial_position_mm.unwrap_or(0.0),
        y.len() as f64 * h,
        df,
        band.0,
        band.1,
        b.gamma(),
        100.0 * (fp / bpfo - 1.0),
        ap * 1e9,
        ap / floor,
        at0 * 1e9,
        ap / at0,
    );
}
