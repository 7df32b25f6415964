//! The rollers page, `docs/rollers.md` with its plots: the ISO/TS 16281 slicing on a worked
//! case, the lamina convergence behind `DEFAULT_LAMINAE`, the pressure along a roller for each
//! profile (aligned and tilted), life against tilt for each profile, and a cylindrical roller
//! bearing's envelope spectrum at its BPFO.
//!
//! ```text
//! cargo run --release --example rollers_page              # docs/rollers.md and docs/rollers-*.png
//! cargo run --example rollers_page -- --quick             # CI: coarser, into out/rollers/
//! ```
//!
//! `--out DIR` writes elsewhere. The quick version takes a 1000-lamina reference instead of
//! 4000, four tilts instead of thirteen and 0.2 s of the ring run instead of 0.7 s.

use raceway::analysis::envelope_spectrum;
use raceway::component::{variables, Component};
use raceway::contact::lamina::{
    line_hertz, roller_constant, Laminae, LineGeometry, Profile, C_STEEL_N_MM, DEFAULT_LAMINAE,
    E_PRIME_REFERENCE,
};
use raceway::contact::roller_law::CylindricalRollerLaw;
use raceway::geometry::roller::RollerBearing;
use raceway::geometry::roller_catalogue::lookup;
use raceway::plot::{plot, Axes, Marker, Series};
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

#[path = "../benches/common/roller_qs.rs"]
mod roller_qs;

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

/// A bearing with its law and the rollers' azimuths (a roller at `psi = -90°`, on the load
/// line of a downward load).
struct Ring {
    b: RollerBearing,
    law: CylindricalRollerLaw,
    psi: Vec<f64>,
}

impl Ring {
    fn new(b: RollerBearing) -> Ring {
        let law = CylindricalRollerLaw::new(&b).expect("cylindrical");
        let psi = (0..b.z)
            .map(|j| -0.5 * PI + 2.0 * PI * j as f64 / b.z as f64)
            .collect();
        Ring { b, law, psi }
    }

    /// Equilibrium under `FR` downward, the ring tilted `rx` (rad) about `x`.
    fn solve(&self, fr: f64, rx: f64) -> [f64; 5] {
        let c_l = roller_constant(self.b.lwe, self.b.e_prime_roller());
        let s = roller_qs::solve(
            &self.law,
            &self.psi,
            [0.0, -fr, 0.0, 0.0, 0.0],
            self.b.pd,
            c_l,
            self.b.lwe,
            Some((rx, 0.0)),
        )
        .expect("equilibrium");
        assert!(s.residual < 1e-12 && s.iterations < 100, "{s:?}");
        s.q
    }

    /// Per roller: (approach at mid-length, tilt) at ring displacement `q`.
    fn rollers(&self, q: &[f64; 5]) -> Vec<(f64, f64)> {
        self.psi
            .iter()
            .map(|p| {
                let (s, c) = p.sin_cos();
                (q[0] * c + q[1] * s - 0.5 * self.b.pd, q[3] * s - q[4] * c)
            })
            .collect()
    }

    /// Lamina loads (N) of every roller at `q`.
    fn lamina_loads(&self, q: &[f64; 5]) -> Vec<Vec<f64>> {
        let l = self.law.laminae();
        self.rollers(q)
            .iter()
            .map(|&(d, t)| {
                let mut v = vec![0.0; l.len()];
                l.evaluate_into(d, t, &mut v);
                v
            })
            .collect()
    }
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
         after ISO/TS 16281:2008 (docs/physics.md §R1–§R5); the bearing throughout is the \
         catalogue's NU206 (`raceway bearings NU206`: internal geometry ESTIMATED from the \
         envelope), steel, 14 rollers of {} laminae. Quasi-static solutions: Newton on the ring \
         displacement with the laminae's exact stiffness (benches/common/roller_qs.rs), the \
         rollers at rest (no centrifugal force).\n\n",
        if quick { " -- --quick" } else { "" },
        DEFAULT_LAMINAE
    );
    let nu206 = lookup("NU206").expect("NU206").build().expect("builds");
    worked_case(&mut md, &nu206);
    convergence(&mut md, &out, quick);
    let qd = pressure_along(&mut md, &out, &nu206);
    life_against_tilt(&mut md, &out, &nu206, qd, quick);
    md += "## Tapered roller bearing: load zone under combined load\n\n\
           **Placeholder.** The tapered roller's equilibrium between cup, cone and back flange \
           is being built into the levels; until it is, a tapered bearing is refused by the \
           cylindrical roller law (`bearing.kind`: tapered). This section will show a TRB's \
           roller loads around the circumference under combined radial and axial load.\n\n";
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
    let q = ring.solve(FR, 0.0);
    let loads: Vec<f64> = ring
        .lamina_loads(&q)
        .iter()
        .map(|v| v.iter().sum())
        .collect();
    let qmax = loads.iter().cloned().fold(0.0, f64::max);
    let mut half = Ring::new(zero);
    for p in half.psi.iter_mut() {
        *p += PI / b.z as f64;
    }
    let qh = half.solve(FR, 0.0);
    let qmax_h = half
        .lamina_loads(&qh)
        .iter()
        .map(|v| v.iter().sum::<f64>())
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
            let q = ring.solve(FR, tilt);
            let loads = ring.lamina_loads(&q);
            let j = (0..loads.len())
                .max_by(|&a, &c| {
                    loads[a]
                        .iter()
                        .sum::<f64>()
                        .total_cmp(&loads[c].iter().sum::<f64>())
                })
                .expect("rollers");
            let l = ring.law.laminae();
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

/// Life against tilt for each profile, relative, by the lamina summation of ISO/TS 16281.
fn life_against_tilt(md: &mut String, out: &Path, b: &RollerBearing, qd: f64, quick: bool) {
    let tilts: Vec<f64> = if quick {
        vec![0.0, 1e-3, 2e-3, 3e-3]
    } else {
        (0..=12).map(|k| k as f64 * 0.25e-3).collect()
    };
    let gamma = b.gamma();
    let g_ratio = (1.0 - gamma) / (1.0 + gamma);
    // Lamina ratings inner over outer, (1-γ)^(29/27)/(1+γ)^(1/4) over (1+γ)^(29/27)/(1-γ)^(1/4).
    let rho = g_ratio.powf(143.0 / 108.0).powf(4.5);
    let damage = |loads: &[Vec<f64>]| -> f64 {
        let z = loads.len() as f64;
        let ns = loads[0].len();
        (0..ns)
            .map(|k| {
                let qi = (loads.iter().map(|v| v[k].powi(4)).sum::<f64>() / z).powf(0.25);
                let qo = (loads.iter().map(|v| v[k].powf(4.5)).sum::<f64>() / z).powf(1.0 / 4.5);
                qi.powf(4.5) + rho * qo.powf(4.5)
            })
            .sum()
    };
    let g = b.line_geometry();
    let mut rows: Vec<(String, Vec<f64>)> = Vec::new();
    let mut reference = f64::NAN;
    for (label, p) in profiles(&g, qd) {
        let mut bb = b.clone();
        bb.profile = p;
        let ring = Ring::new(bb);
        let mut lives = Vec::new();
        for &t in &tilts {
            let q = ring.solve(FR, t);
            lives.push(damage(&ring.lamina_loads(&q)).powf(-8.0 / 9.0));
        }
        if reference.is_nan() {
            reference = lives[0];
        }
        rows.push((label, lives));
    }
    let _ = write!(
        md,
        "## Life against tilt, each profile\n\n\
         NU206 under Fr = {FR:.0} N, the inner ring rotating and tilted as above, life relative \
         to the aligned straight roller. The life sums the laminae as ISO/TS 16281 does in \
         the Lundberg–Palmgren manner for line contact: per lamina `k` and ring, the \
         equivalent load over the rollers (the rotating inner ring's lamina meets every \
         roller: `(Σ_j q_jk^4 / Z)^(1/4)`; the stationary outer ring's point sees the load \
         zone: `(Σ_j q_jk^4.5 / Z)^(1/4.5)`), then `L ∝ [Σ_k (q_ei,k/q_ci)^(9/2) + \
         (q_eo,k/q_co)^(9/2)]^(-8/9)`, with the lamina ratings in the ratio \
         `q_ci/q_co = ((1-γ)/(1+γ))^(143/108)` of ISO/TR 1281-1's line-contact rating \
         (γ = {gamma:.4}). **What it leaves out**: the standard's edge-stress factor and its \
         absolute lamina rating; so the figures are ratios, and a straight roller's edge \
         loading is penalised only through its larger lamina loads — the page states this \
         reading of the method, it was not checked against the standard's text.\n\n\
         | profile |"
    );
    for t in &tilts {
        let _ = write!(md, " {:.2} mrad |", t * 1e3);
    }
    md.push_str("\n|---|");
    md.push_str(&"---|".repeat(tilts.len()));
    md.push('\n');
    for (label, lives) in &rows {
        let _ = write!(md, "| {label} |");
        for l in lives {
            let _ = write!(md, " {:.3} |", l / reference);
        }
        md.push('\n');
    }
    let xs: Vec<f64> = tilts.iter().map(|t| t * 1e3).collect();
    let ys: Vec<Vec<f64>> = rows
        .iter()
        .map(|(_, l)| l.iter().map(|v| v / reference).collect())
        .collect();
    let series: Vec<Series> = rows
        .iter()
        .zip(&ys)
        .map(|((l, _), y)| Series {
            label: l,
            x: &xs,
            y,
            points: false,
        })
        .collect();
    plot(
        &png(out, "life-tilt"),
        &Axes {
            title: &format!(
                "NU206, Fr {FR:.0} N: life against ring tilt, relative to the aligned straight roller"
            ),
            x_label: "ring tilt (mrad)",
            y_label: "relative life (1)",
            ..Axes::default()
        },
        &series,
        &[],
    )
    .expect("plot");
    md.push_str("\n![life against tilt](rollers-life-tilt.png)\n\n");
}

/// The NU206 ring scene: its force's envelope spectrum with BPFO marked.
fn envelope(md: &mut String, out: &Path, quick: bool) {
    let text = include_str!("scenes/nu206-ring2-radial.toml");
    let mut c = Component::from_text(text).expect("scene");
    let scene = raceway::Scene::from_text(text).expect("scene");
    let h = scene.run.step_s;
    let t_end = if quick { 0.2 } else { scene.run.duration_s };
    let omega = scene.inputs.initial_value("shaft.omega");
    for name in [
        "load.x",
        "load.y",
        "load.z",
        "load.mx",
        "load.my",
        "shaft.omega",
    ] {
        let vr = variables::by_name(name).expect("variable").vr;
        let v = scene.inputs.initial_value(name);
        c.set_real(vr, v).expect("input");
    }
    let fy = variables::by_name("force.y").expect("force.y").vr;
    let n = (t_end / h).round() as usize;
    let mut y = Vec::with_capacity(n);
    for i in 0..n {
        c.do_step(i as f64 * h, h).expect("step");
        y.push(c.get_real(fy).expect("force.y"));
    }
    // The first 0.1 s: the ring settling under the load it was released with.
    let settle = ((0.1 / h) as usize).min(n / 2);
    let sig = &y[settle..];
    let b = lookup("NU206").expect("NU206").build().expect("builds");
    let fs_hz = omega / (2.0 * PI);
    let bpfo = 0.5 * b.z as f64 * fs_hz * (1.0 - b.gamma());
    let s = envelope_spectrum(sig, 1.0 / h, None);
    let keep: Vec<usize> = (1..s.freq.len())
        .filter(|&k| s.freq[k] <= 4.5 * bpfo)
        .collect();
    let (f, a): (Vec<f64>, Vec<f64>) = keep.iter().map(|&k| (s.freq[k], s.amp[k])).unzip();
    let kmax = (0..f.len())
        .max_by(|&i, &j| a[i].total_cmp(&a[j]))
        .expect("bins");
    plot(
        &png(out, "envelope"),
        &Axes {
            title: &format!(
                "nu206-ring2-radial: envelope spectrum of force.y, {:.0} rpm, Fr 4 kN, {:.2} s",
                omega * 30.0 / PI,
                sig.len() as f64 * h
            ),
            x_label: "frequency (Hz)",
            y_label: "envelope amplitude (N)",
            log_y: true,
            ..Axes::default()
        },
        &[Series {
            label: "envelope of force.y",
            x: &f,
            y: &a,
            points: false,
        }],
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
        ],
    )
    .expect("plot");
    let _ = write!(
        md,
        "## A cylindrical roller bearing's envelope spectrum at BPFO\n\n\
         The shipped scene `examples/scenes/nu206-ring2-radial.toml` (ring level, 2 DOF, \
         load-driven, 4 kN at {:.0} rpm), its `force.y` at 10 kHz after 0.1 s of settling \
         ({:.2} s analysed, {:.2} Hz bins), envelope spectrum (Hilbert, whole band). BPFO = \
         `Z/2 fs (1 - γ)` = {bpfo:.2} Hz with the roller's γ = Dwe/Dpw = {:.4}; the largest \
         line is at {:.2} Hz ({:+.2} % from BPFO). **What it shows is the roller passage**, the \
         varying compliance of 14 rollers over the load zone: an outer-race defect cannot be \
         put on a roller bearing yet (the law-driven ring level refuses effects until the \
         laminae carry defects), so the defect variant of this section follows when they do; \
         the defect's impacts will sit on the same BPFO lines.\n\n\
         ![envelope spectrum](rollers-envelope.png)\n",
        omega * 30.0 / PI,
        sig.len() as f64 * h,
        s.freq[1] - s.freq[0],
        b.gamma(),
        f[kmax],
        100.0 * (f[kmax] / bpfo - 1.0)
    );
}
