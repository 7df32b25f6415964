//! The summary of a stand-alone run: what `raceway run` prints and writes to summary.txt and
//! summary.json, what `raceway sweep` flattens into a row and what the Python package's
//! `raceway.run` returns. One implementation, so the three agree.
//!
//! Sections: the scene and bearing, peak loads and pressures, cage slip (and whirl on the
//! full level), the characteristic frequencies found in the spectrum of the second half of the
//! run (and in the envelope spectrum for defect scenes), ISO ratings and life.

pub mod columns;
pub mod friction;
pub mod html;
pub mod reports;
pub mod rollers;
mod sets;

use crate::analysis::{
    amplitude_spectrum, characteristic_marks, envelope_spectrum, find_peaks, whirl_index,
    FoundPeak, Spectrum, Verdict, Window, FOUND_OVER_FLOOR, LINE_TOLERANCE,
};
use crate::component::{Causality, Scene};
use crate::geometry::kinematics;
use crate::models::effects::Element;
use crate::runner::{Digest, Series};

/// The sections of the summary, in order.
pub fn summary_of(ctx: &Ctx) -> Summary {
    let mut sm = Summary::default();
    scene_lines(ctx, &mut sm);
    load_lines(ctx, &mut sm);
    start_hold_lines(ctx, &mut sm);
    effect_lines(ctx, &mut sm);
    cage_lines(ctx, &mut sm);
    frequency_lines(ctx, &mut sm);
    rating_lines(ctx, &mut sm);
    rollers::ring_lamina_life_lines(ctx, &mut sm);
    sm.json = columns::relabel(columns::Doc::Run, std::mem::take(&mut sm.json));
    sm
}

/// The summary of a finished run (`cpu_s`: its thread CPU time), as `raceway run` writes it
/// to summary.txt and summary.json; what `raceway sweep` flattens into a row. `run`: the
/// run's [`Digest`] as [`digest_for`] makes it.
pub fn summarize(
    scene: &Scene,
    name: &str,
    run: &Digest,
    comp: &crate::Component,
    cpu_s: f64,
) -> Summary {
    summary_of(&Ctx::new(scene, name, run, comp, cpu_s))
}

/// The name and unit of the signal whose spectrum tells the frequencies: ring motion when
/// load-driven, the force when motion-driven (over the second half of the run, past the
/// start transient).
pub fn signal_of(scene: &Scene) -> (&'static str, &'static str) {
    if scene.model.causality == Causality::Load {
        ("shaft.y", "m")
    } else {
        ("force.y", "N")
    }
}

/// The run's digest the summary reads, to be fed the run's rows
/// ([`crate::runner::run_into`]): the spectrum's signal and the cage speed (whirl index)
/// kept at full rate over the second half (and, for a roller bearing on the ring
/// level, the ring's displacement and the cage speed for its lamina life), the cage orbit's
/// peak.
pub fn digest_for(scene: &Scene) -> Digest {
    let mut analysed = vec![signal_of(scene).0, "cage.speed"];
    // A roller bearing on the ring level: its lamina life over the window
    // (`rollers::ring_lamina_life`) replays the ring's displacement and the cage.
    if scene
        .build_bearing()
        .is_ok_and(|b| rollers::has_ring_lamina_life(scene, &b))
    {
        for n in rollers::RING_LAMINA_COLUMNS {
            if !analysed.contains(&n) {
                analysed.push(n);
            }
        }
    }
    Digest::new(&analysed, &[("cage.x", "cage.y")])
}

/// The summary: text lines and the same facts as JSON. A section is a function
/// `fn x_lines(ctx: &Ctx, s: &mut Summary)` called in [`summary_of`]; add lines with
/// [`Summary::line`] and values with [`Summary::set`].
#[derive(Default)]
pub struct Summary {
    /// summary.txt and standard output.
    pub text: String,
    /// summary.json.
    pub json: serde_json::Map<String, serde_json::Value>,
}

impl Summary {
    /// One line of text.
    pub fn line(&mut self, l: impl AsRef<str>) {
        self.text += l.as_ref();
        self.text.push('\n');
    }
    /// One JSON value.
    pub fn set(&mut self, key: &str, v: serde_json::Value) {
        self.json.insert(key.to_string(), v);
    }
}

/// What the summary sections and plots read: the scene, the run and the analyses.
pub struct Ctx<'a> {
    /// The scene as run.
    pub scene: &'a Scene,
    /// Scene name (file stem).
    pub name: &'a str,
    /// The run's history for plots: every row up to [`crate::runner::HISTORY_ROWS`] rows,
    /// else every `run.stride`-th and the last (the summary reads `run`, exact over every
    /// row).
    pub series: &'a Series,
    /// The run's digest: peaks, last values, second-half means and the analysed signals
    /// over every row.
    pub run: &'a Digest,
    /// The component after the run.
    pub comp: &'a crate::Component,
    /// CPU time of the run, s.
    pub cpu_s: f64,
    /// Shaft frequency at the end, Hz.
    pub shaft_hz: f64,
    /// Index in `series` of the first row of the second half of the run (the part
    /// analysed).
    pub start: usize,
    /// Name and unit of the signal whose spectrum is analysed.
    pub signal: (&'static str, &'static str),
    /// Its amplitude spectrum over the analysed part.
    pub spec: Spectrum,
    /// The characteristic frequencies.
    pub marks: Vec<crate::analysis::Mark>,
    /// The main lines and what became of them.
    pub found: Vec<FoundPeak>,
    /// Defect scenes: the envelope spectrum and its lines.
    pub envelope: Option<Envelope>,
}

/// The envelope spectrum, the band-pass before it (Hz; none: the whole signal) and the
/// lines found in it.
pub type Envelope = (Spectrum, Option<(f64, f64)>, Vec<FoundPeak>);

const MAIN: [&str; 7] = ["fs", "FTF", "BSF", "1xBPFO", "1xBPFI", "1x2BSF", "2xBPFO"];

impl<'a> Ctx<'a> {
    /// The analyses of a finished run (`cpu_s`: its thread CPU time; `name`: the scene's
    /// name in the summary).
    pub fn new(
        scene: &'a Scene,
        name: &'a str,
        run: &'a Digest,
        comp: &'a crate::Component,
        cpu_s: f64,
    ) -> Ctx<'a> {
        let series = &run.history;
        let omega = run.last("shaft.omega");
        let kin = kinematics(comp.bearing(), omega);
        let shaft_hz = omega / (2.0 * std::f64::consts::PI);
        let signal = signal_of(scene);
        let n = run.rows;
        let start = run.start.div_ceil(run.stride.max(1)).min(series.t.len());
        let sig = run.second_half(signal.0);
        let dt = scene.run.duration_s / (n - 1).max(1) as f64;
        let spec = amplitude_spectrum(sig, 1.0 / dt, Window::Hann);
        let marks = characteristic_marks(&kin, shaft_hz, 3, 1);
        // Inner-race waviness of orders Z ± 1 shows as side bands BPFI ± fs
        // (docs/physics.md §5.4: orders pZ ± m give p BPFI ± m fs): the table carries them.
        let z = comp.bearing().z as i64;
        let inner_sidebands = scene
            .effects
            .waviness
            .iter()
            .any(|w| w.race == Element::Inner && (w.order as i64 - z).abs() == 1);
        let main: Vec<_> = marks
            .iter()
            .filter(|m| {
                MAIN.contains(&m.label.as_str())
                    || (inner_sidebands && ["1xBPFI+1fs", "1xBPFI-1fs"].contains(&m.label.as_str()))
            })
            .cloned()
            .collect();
        let found = find_peaks(&spec, &main, LINE_TOLERANCE);
        // Defects: the envelope spectrum (Randall & Antoni 2011, §4), band-passed above the
        // third multiple of the highest defect frequency (the impacts excite the band, the
        // envelope keeps their repetition rate) up to 0.8 of the Nyquist frequency.
        let envelope = (!scene.effects.defects.is_empty()).then(|| {
            let top = kin.bpfi.max(kin.bpfo).max(2.0 * kin.bsf);
            let nyq = 0.5 / dt;
            let band = (3.0 * top < 0.8 * nyq).then_some((3.0 * top, 0.8 * nyq));
            let env = envelope_spectrum(sig, 1.0 / dt, band);
            // Harmonics up to 3x of the defect's own line; an inner-race defect passes
            // through the load zone once per shaft turn, so its BPFI lines carry
            // sidebands at the shaft frequency, a ball's 2BSF lines at FTF (docs/physics.md
            // §5.3-5.4).
            let on = |e: Element| scene.effects.defects.iter().any(|d| d.race == e);
            let mut want: Vec<&str> = vec!["fs", "FTF", "1xBPFO", "1xBPFI", "1x2BSF"];
            if on(Element::Outer) {
                want.extend(["2xBPFO", "3xBPFO"]);
            }
            if on(Element::Inner) {
                want.extend(["2xBPFI", "1xBPFI+1fs", "1xBPFI-1fs"]);
            }
            if on(Element::Ball) {
                want.extend(["2x2BSF", "1x2BSF+1FTF", "1x2BSF-1FTF"]);
            }
            let lines: Vec<_> = marks
                .iter()
                .filter(|m| want.contains(&m.label.as_str()))
                .cloned()
                .collect();
            let f = find_peaks(&env, &lines, LINE_TOLERANCE);
            (env, band, f)
        });
        Ctx {
            scene,
            name,
            series,
            run,
            comp,
            cpu_s,
            shaft_hz,
            start,
            signal,
            spec,
            marks,
            found,
            envelope,
        }
    }

    /// The history's column of a variable (empty when absent), for plots.
    pub fn col(&self, n: &str) -> &[f64] {
        self.series.column(n).unwrap_or(&[])
    }

    /// The largest magnitude of a recorded variable over every row (0 when absent).
    pub fn peak(&self, n: &str) -> f64 {
        self.run.peak(n)
    }

    /// The last value of a recorded variable (0 when absent).
    pub fn last(&self, n: &str) -> f64 {
        self.run.last(n)
    }

    /// Whether the level integrates the cage (its slip is otherwise 0 by construction).
    pub fn cage_dynamics(&self) -> bool {
        matches!(self.scene.model.level.name(), "skidding" | "full")
    }

    /// The run length over the length analysed.
    pub fn record_scale(&self) -> f64 {
        let n = self.run.rows.max(2);
        (n - 1) as f64 / (n - 1 - self.run.analysed_from.min(n - 2)) as f64
    }
}

fn scene_lines(c: &Ctx, s: &mut Summary) {
    let sc = c.scene;
    let b = c.comp.bearing();
    s.line(format!(
        "scene: {} ({}; level {}, {:?}-driven)",
        c.name,
        sc.title,
        sc.model.level.name(),
        sc.model.causality
    ));
    s.line(format!(
        "bearing: {}, d x D x B {:.3} x {:.3} x {:.3} mm; Z {} {}s of Dw {:.3} mm on dm {:.3} mm; diametral clearance Pd {:.2} µm",
        b.name,
        b.bore * 1e3,
        b.outer_diameter * 1e3,
        b.width * 1e3,
        b.z,
        b.element(),
        b.d * 1e3,
        b.dm * 1e3,
        b.pd * 1e6
    ));
    let n = c.run.rows;
    let load = crate::report::load_average();
    s.line(format!(
        "simulated {:.4} s in {} steps, {:.3} s of thread CPU ({:.2}x real time; load average {load})",
        sc.run.duration_s,
        n.saturating_sub(1),
        c.cpu_s,
        sc.run.duration_s / c.cpu_s.max(1e-9)
    ));
    s.set("scene", c.name.into());
    s.set("level", sc.model.level.name().into());
    s.set("duration_s", sc.run.duration_s.into());
    s.set("cpu_s", c.cpu_s.into());
    s.set("load_average", load.into());
    s.set(
        "bearing",
        serde_json::json!({"name": b.name, "bore_mm": b.bore * 1e3, "outside_diameter_mm": b.outer_diameter * 1e3,
            "width_mm": b.width * 1e3, "z": b.z, "ball_diameter_mm": b.d * 1e3, "pitch_diameter_mm": b.dm * 1e3,
            "diametral_clearance_um": b.pd * 1e6}),
    );
}

fn load_lines(c: &Ctx, s: &mut Summary) {
    let (fx, fy, fz) = (c.peak("force.x"), c.peak("force.y"), c.peak("force.z"));
    s.line(format!(
        "peak |force.x| {fx:.2} N, |force.y| {fy:.2} N, |force.z| {fz:.2} N"
    ));
    s.line(format!(
        "peak contact load {:.2} N, peak Hertz pressure {:.3} GPa",
        c.peak("contact.max_load"),
        c.peak("contact.max_pressure") * 1e-9
    ));
    s.set("peak_force_n", serde_json::json!([fx, fy, fz]));
    s.set("peak_contact_load_n", c.peak("contact.max_load").into());
    s.set("peak_pressure_pa", c.peak("contact.max_pressure").into());
}

/// `model.start_hold`: which coordinates the static start held and the reaction on each.
fn start_hold_lines(c: &Ctx, s: &mut Summary) {
    let (held, reaction) = c.comp.start_held();
    if !held.iter().any(|&h| h) {
        return;
    }
    let names = crate::models::quasi_static::hold::held_names(&held);
    let units = ["N", "N", "N", "N m", "N m"];
    let r: Vec<String> = (0..5)
        .filter(|&i| held[i])
        .map(|i| format!("{:.4} {}", reaction[i], units[i]))
        .collect();
    s.line(format!(
        "static start held {names} (model.start_hold); reaction there {}",
        r.join(", ")
    ));
    s.set("start_held", serde_json::json!(held));
    s.set("start_reaction", serde_json::json!(reaction));
}

/// What the effects compute, when the level sets it: friction torque and power loss
/// (thermal effect), the minimum film thickness (EHL film); means over the second half of
/// the run and the final value. Outputs the level leaves at zero are not reported.
fn effect_lines(c: &Ctx, s: &mut Summary) {
    // Means and final values from the run's digest (every row); the smallest film from the
    // plot history (every row up to runner::HISTORY_ROWS, else every k-th).
    let half = |n: &str| -> &[f64] {
        let col = c.col(n);
        &col[c.start.min(col.len())..]
    };
    let set = |n: &str| c.run.peak(n) != 0.0;
    let mean = |n: &str| c.run.mean_second_half(n);
    let last = |n: &str| c.run.last(n);
    if set("torque.z") || set("power.loss") {
        let (tq, pw) = (mean("torque.z"), mean("power.loss"));
        s.line(format!(
            "friction: torque on the shaft mean {tq:.4} N m (final {:.4} N m), power loss mean {pw:.3} W (final {:.3} W), second half",
            last("torque.z"),
            last("power.loss")
        ));
        let mut f = serde_json::json!({"mean_torque_nm": tq, "final_torque_nm": last("torque.z"),
            "mean_power_loss_w": pw, "final_power_loss_w": last("power.loss")});
        friction::calculator_lines(c, s, &mut f);
        s.set("friction", f);
    }
    if set("film.min_thickness") {
        let h = half("film.min_thickness");
        let lo = h.iter().copied().fold(f64::INFINITY, f64::min);
        let mean_h = mean("film.min_thickness");
        s.line(format!(
            "film: minimum thickness over the contacts {:.4} µm at its smallest, mean {:.4} µm (final {:.4} µm), second half",
            lo * 1e6,
            mean_h * 1e6,
            last("film.min_thickness") * 1e6
        ));
        let mut film = serde_json::json!({"smallest_min_thickness_um": lo * 1e6, "mean_min_thickness_um": mean_h * 1e6,
            "final_min_thickness_um": last("film.min_thickness") * 1e6});
        if let Some(l) = lubricant(c.scene) {
            film_parameter_lines(c, s, &l, lo, mean_h, &mut film);
        }
        s.set("film", film);
    }
    thermal_lines(c, s);
}

/// The scene's lubricant when it has an EHL film.
fn lubricant(scene: &Scene) -> Option<crate::lubrication::Lubricant> {
    let spec = scene.effects.lubrication.as_ref()?;
    (spec.film == crate::models::effects::FilmKind::Ehl)
        .then(|| spec.lubricant().ok())
        .flatten()
}

/// The film parameter `Lambda = h_min / sigma` (film over the composite rms roughness of
/// ball and race; docs/physics.md §6) at the smallest and the mean minimum film of the
/// second half, and ISO 281's viscosity ratio `kappa = nu / nu1` of the lubricant at its
/// inlet viscosity (`nu = eta / rho`; `nu1` at the bearing's mean diameter and the final
/// speed, [`crate::calculator::lubricant::nu1`]).
fn film_parameter_lines(
    c: &Ctx,
    s: &mut Summary,
    l: &crate::lubrication::Lubricant,
    smallest: f64,
    mean: f64,
    film: &mut serde_json::Value,
) {
    let b = c.comp.bearing();
    let rpm = c.last("shaft.omega").abs() * 60.0 / std::f64::consts::TAU;
    let nu = l.viscosity / l.density;
    let nu1 =
        crate::calculator::lubricant::nu1(crate::calculator::lubricant::mean_diameter(b), rpm);
    let kappa = nu1.map(|v| nu / v);
    let sigma = l.roughness;
    let lambda = |h: f64| (sigma > 0.0).then(|| h / sigma);
    let text = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
    s.line(format!(
        "lubrication: film parameter Lambda = h_min/sigma {} at the smallest film, {} at the mean (composite roughness sigma {:.3} µm); \
         ISO 281 viscosity ratio kappa = nu/nu1 {} (nu {:.2} mm²/s at the inlet viscosity, nu1 {} mm²/s at {rpm:.0} rpm)",
        text(lambda(smallest)),
        text(lambda(mean)),
        sigma * 1e6,
        text(kappa),
        nu * 1e6,
        text(nu1.map(|v| v * 1e6)),
    ));
    if let Some(o) = film.as_object_mut() {
        o.insert("roughness_um".into(), (sigma * 1e6).into());
        o.insert(
            "smallest_film_parameter".into(),
            serde_json::json!(lambda(smallest)),
        );
        o.insert(
            "mean_film_parameter".into(),
            serde_json::json!(lambda(mean)),
        );
        o.insert("kinematic_viscosity_mm2_s".into(), (nu * 1e6).into());
        o.insert("nu1_mm2_s".into(), serde_json::json!(nu1.map(|v| v * 1e6)));
        o.insert("iso_kappa".into(), serde_json::json!(kappa));
    }
}

/// The thermal effect's state at the end of the run (ring level): the temperatures of the
/// four nodes (ambient plus their rises) and the operating diametral clearance (the
/// bearing's, changed by the ring and ball growth; docs/physics.md §8).
fn thermal_lines(c: &Ctx, s: &mut Summary) {
    let Some(spec) = &c.scene.effects.thermal else {
        return;
    };
    if c.scene.model.level.name() != "ring" {
        return;
    }
    if let Some(set) = &c.scene.set {
        // A set: each row's network (its growth moves the row's preload, physics §S1).
        let n = if !set.row.is_empty() {
            set.row.len()
        } else if set.arrangement.is_some() {
            2
        } else {
            1
        };
        let aux = &c.comp.state().aux;
        let rows = crate::models::set::level::row_thermal_blocks(aux, n);
        let mut json = Vec::new();
        for (i, th) in rows.iter().enumerate() {
            let t = |k: usize| spec.ambient_c + th[k];
            s.line(format!(
                "row {i} temperatures at the end: inner race {:.2} °C, outer race {:.2} °C, balls {:.2} °C, oil {:.2} °C (ambient {:.2} °C)",
                t(0),
                t(1),
                t(2),
                t(3),
                spec.ambient_c
            ));
            json.push(serde_json::json!({"inner_race_c": t(0), "outer_race_c": t(1), "balls_c": t(2), "oil_c": t(3)}));
        }
        s.set(
            "thermal",
            serde_json::json!({"ambient_c": spec.ambient_c, "rows": json}),
        );
        return;
    }
    let b = c.comp.bearing();
    let Ok(layout) = crate::models::ring::level::SlowLayout::of(&c.scene.effects, b) else {
        return;
    };
    let aux = &c.comp.state().aux;
    let Some(th) = layout.thermal(aux) else {
        return;
    };
    let t = |k: usize| spec.ambient_c + th[k];
    let change = th[8];
    s.line(format!(
        "temperatures at the end: inner race {:.2} °C, outer race {:.2} °C, balls {:.2} °C, oil {:.2} °C (ambient {:.2} °C); \
         operating diametral clearance {:.3} µm (Pd {:.3} µm, thermal growth {:+.3} µm)",
        t(0),
        t(1),
        t(2),
        t(3),
        spec.ambient_c,
        (b.pd + change) * 1e6,
        b.pd * 1e6,
        change * 1e6
    ));
    s.set(
        "thermal",
        serde_json::json!({"inner_race_c": t(0), "outer_race_c": t(1), "balls_c": t(2), "oil_c": t(3),
            "ambient_c": spec.ambient_c, "clearance_change_um": change * 1e6,
            "operating_clearance_um": (b.pd + change) * 1e6}),
    );
}

fn cage_lines(c: &Ctx, s: &mut Summary) {
    let slip = c.last("cage.slip");
    if c.cage_dynamics() {
        s.line(format!("cage slip: final {slip:.4}"));
        s.set("final_cage_slip", slip.into());
    } else {
        s.line(format!(
            "cage slip: 0 by construction (the {} level runs the cage at its kinematic speed; the skidding and full levels integrate it)",
            c.scene.model.level.name()
        ));
        s.set("final_cage_slip", serde_json::Value::Null);
    }
    // Cage dynamics (the full level): whirl index over the second half of the run.
    if c.scene.model.level.name() != "full" {
        return;
    }
    let sigma = whirl_index(c.run.second_half("cage.speed"));
    let orbit_max = c.run.pair_peak("cage.x", "cage.y");
    s.line(format!(
        "cage: whirl index sigma {} (second half), largest orbit {:.3} guide clearances, \
         peak pocket force {:.2} N, peak guide force {:.2} N, final speed ratio {:.4}",
        sigma.map_or("-".to_string(), |v| format!("{v:.4}")),
        orbit_max,
        c.peak("pocket.max_force"),
        c.peak("guide.force"),
        c.last("cage.speed_ratio")
    ));
    s.set("cage_whirl_sigma", serde_json::json!(sigma));
    s.set("cage_orbit_max", orbit_max.into());
    s.set("peak_pocket_force_n", c.peak("pocket.max_force").into());
    s.set("peak_guide_force_n", c.peak("guide.force").into());
}

/// ISO ratings, life, static safety and warnings at the run's mean load over the second
/// half (crate::ratings).
fn rating_lines(c: &Ctx, s: &mut Summary) {
    if sets::rating_lines(c, s) {
        return;
    }
    let load = ["force.x", "force.y", "force.z", "moment.x", "moment.y"]
        .map(|n| -c.run.mean_second_half(n));
    let omega = c.last("shaft.omega");
    let rating = crate::ratings::assess_run(c.comp.bearing(), &load, omega);
    match &rating {
        Ok(a) => s.text += &format!("at the mean load of the second half:\n{}", a.text()),
        Err(e) => s.line(format!("ratings and life: not available ({e})")),
    }
    s.set(
        "rating",
        serde_json::to_value(rating.as_ref().ok()).unwrap_or_default(),
    );
    s.set(
        "warnings",
        rating
            .as_ref()
            .map(|a| a.warning_texts())
            .unwrap_or_default()
            .into(),
    );
}

/// The lines of one spectrum: expected, found (or why not), significance.
fn line_table(s: &mut Summary, found: &[FoundPeak], scale: f64) -> serde_json::Value {
    for p in found {
        let f = if p.is_found() {
            format!("{:.3}", p.found)
        } else {
            "-".to_string()
        };
        s.line(format!(
            "  {:<11} {:>10.3} Hz  {:>10} Hz  {}",
            p.label,
            p.expected,
            f,
            p.verdict_text(scale)
        ));
    }
    let finite = |v: f64| v.is_finite().then_some(v);
    serde_json::Value::Array(
        found
            .iter()
            .map(|p| {
                let (verdict, needs) = match p.verdict {
                    Verdict::Found => ("found", None),
                    Verdict::BelowFloor => ("below floor", None),
                    Verdict::OffLine => ("off line", None),
                    Verdict::Unresolved { needs_s } => ("not resolved", finite(needs_s * scale)),
                    Verdict::AboveNyquist { .. } => ("above nyquist", None),
                };
                serde_json::json!({"label": p.label, "expected_hz": p.expected,
                    "found_hz": if p.is_found() { finite(p.found) } else { None },
                    "tolerance_hz": finite(p.tol_hz),
                    "nearest_peak_hz": finite(p.found), "deviation_hz": finite(p.deviation()),
                    "over_floor": finite(p.over_floor), "verdict": verdict, "needs_duration_s": needs})
            })
            .collect(),
    )
}

fn frequency_lines(c: &Ctx, s: &mut Summary) {
    let scale = c.record_scale();
    s.line(format!(
        "shaft {:.2} Hz; characteristic frequencies in the {} spectrum ({}, second half of the run: {:.4} s, bins {:.3} Hz); \
         found = a peak (interpolated between bins) within ±min(1 bin, {:.0} % of f) at least {FOUND_OVER_FLOOR} x the median floor in [f/2, 2f]:",
        c.shaft_hz,
        c.signal.0,
        c.signal.1,
        1.0 / c.spec.resolution().max(1e-300),
        c.spec.resolution(),
        100.0 * LINE_TOLERANCE
    ));
    s.line(format!(
        "  {:<11} {:>13}  {:>13}",
        "line", "expected", "found"
    ));
    let v = line_table(s, &c.found, scale);
    s.set("frequencies", v);
    if let Some((env, band, found)) = &c.envelope {
        s.line(format!(
            "envelope spectrum of {} (defect scene; band {}):",
            c.signal.0,
            band.map_or("whole signal".to_string(), |(lo, hi)| format!(
                "{lo:.0}-{hi:.0} Hz"
            ))
        ));
        let _ = env;
        let v = line_table(s, found, scale);
        s.set("envelope_frequencies", v);
    }
}
