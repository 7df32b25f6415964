//! The data of `raceway bearings --json`, `raceway bearings NAME --json` and
//! `raceway quasi-static --json`, shared by the command line and the Python package so both
//! report the same numbers under the same names (SI, except the presets' table: mm, µm,
//! degrees as the command line prints them).

use crate::component::scene::RaceControl;
use crate::contact::{Curvature, PointContact, Race};
use crate::error::{in_range, positive, Error, Result};
use crate::geometry::{preset, presets, Bearing, BearingKind, BearingSpec};
use crate::models::quasi_static::{Options, QuasiStatic, Solution};
use crate::ratings::{assess, load_ratings, Assessment, LifeInputs, LoadRatings};
use crate::units::rpm_to_rad_s;
use serde::Serialize;

/// One preset, as `raceway bearings --json` lists it.
#[derive(Debug, Clone, Serialize)]
pub struct PresetRow {
    /// Designation.
    pub name: String,
    /// `deep_groove` or `angular_contact`.
    pub kind: BearingKind,
    /// Ball diameter, mm.
    pub ball_diameter_mm: f64,
    /// Pitch diameter, mm.
    pub pitch_diameter_mm: f64,
    /// Number of balls.
    pub ball_count: usize,
    /// Inner groove curvature ratio.
    pub inner_curvature: f64,
    /// Outer groove curvature ratio.
    pub outer_curvature: f64,
    /// Free contact angle, degrees.
    pub free_contact_angle_deg: f64,
    /// Nominal contact angle (0 for deep-groove), degrees.
    pub nominal_contact_angle_deg: f64,
    /// Diametral clearance, µm.
    pub clearance_um: f64,
    /// Groove-centre distance `A = (f_i + f_o - 1) D`, mm.
    pub groove_centre_distance_mm: f64,
    /// Ball mass, kg.
    pub ball_mass_kg: f64,
    /// Hertz constant, inner contact at the nominal angle, N/m^1.5.
    pub kc_inner: f64,
    /// Hertz constant, outer contact at the nominal angle, N/m^1.5.
    pub kc_outer: f64,
    /// Ball material.
    pub ball_material: String,
    /// Ring material (inner).
    pub ring_material: String,
    /// ISO 281 basic dynamic load rating `C`, N (absent outside the standard's range).
    pub dynamic_rating_n: Option<f64>,
    /// ISO 76 basic static load rating `C0`, N.
    pub static_rating_n: Option<f64>,
    /// Where the data come from.
    pub source: String,
}

fn kc(b: &Bearing, race: Race) -> f64 {
    let (f, e) = match race {
        Race::Inner => (b.fi(), b.e_eff_inner()),
        Race::Outer => (b.fo(), b.e_eff_outer()),
    };
    PointContact::new(
        Curvature::ball_race(b.d, b.dm, b.nominal_contact_angle(), f, race),
        e,
    )
    .kc
}

/// The table row of a built bearing (`source`: where its data come from).
pub fn preset_row(source: &str, b: &Bearing) -> PresetRow {
    PresetRow {
        name: b.name.clone(),
        kind: b.kind,
        ball_diameter_mm: b.d * 1e3,
        pitch_diameter_mm: b.dm * 1e3,
        ball_count: b.z,
        inner_curvature: b.fi(),
        outer_curvature: b.fo(),
        free_contact_angle_deg: b.alpha0.to_degrees(),
        nominal_contact_angle_deg: b.nominal_contact_angle().to_degrees(),
        clearance_um: b.pd * 1e6,
        groove_centre_distance_mm: b.a() * 1e3,
        ball_mass_kg: b.ball_mass(),
        kc_inner: kc(b, Race::Inner),
        kc_outer: kc(b, Race::Outer),
        ball_material: b.ball_material.name.clone(),
        ring_material: b.inner_material.name.clone(),
        dynamic_rating_n: load_ratings(b).ok().map(|r| r.c),
        static_rating_n: load_ratings(b).ok().map(|r| r.c0),
        source: source.to_string(),
    }
}

/// Every preset's row (`raceway bearings --json`).
pub fn bearing_rows() -> Result<Vec<PresetRow>> {
    presets()
        .into_iter()
        .map(|spec| Ok(preset_row(&spec.source, &spec.build()?)))
        .collect()
}

/// One bearing's data, ratings and provenance (`raceway bearings NAME --json`).
#[derive(Debug, Clone, Serialize)]
pub struct BearingDetail {
    /// The preset table's row.
    #[serde(flatten)]
    pub row: PresetRow,
    /// Bore d, mm.
    pub bore_mm: f64,
    /// Outside diameter D, mm.
    pub outer_diameter_mm: f64,
    /// Width B, mm.
    pub width_mm: f64,
    /// true when the internal geometry is estimated (catalogue designation).
    pub estimated: bool,
    /// ISO 281/76 ratings.
    pub ratings: LoadRatings,
}

/// The detail of a preset or catalogue designation.
pub fn bearing_detail(name: &str) -> Result<BearingDetail> {
    let spec = preset(name)?;
    let b = spec.build()?;
    Ok(BearingDetail {
        row: preset_row(&spec.source, &b),
        bore_mm: b.bore * 1e3,
        outer_diameter_mm: b.outer_diameter * 1e3,
        width_mm: b.width * 1e3,
        estimated: spec.source.contains("ESTIMATED"),
        ratings: load_ratings(&b)?,
    })
}

/// `raceway bearings --json`: every preset's row, its keys labelled from
/// [`super::columns`] (docs/columns.md).
pub fn bearings_json() -> Result<serde_json::Value> {
    Ok(super::columns::to_labelled_json(
        super::columns::Doc::Bearings,
        &bearing_rows()?,
    ))
}

/// `raceway bearings NAME --json`: a ball bearing's [`BearingDetail`], or for a roller
/// designation its file's data (`spec`) and ISO 281/76 ratings; keys labelled from
/// [`super::columns`].
pub fn bearing_json(name: &str) -> Result<serde_json::Value> {
    let doc = super::columns::Doc::Bearings;
    if preset(name).is_err() {
        if let Some(spec) = crate::geometry::roller_catalogue::lookup(name) {
            let r = crate::ratings::roller::roller_ratings(&spec.build()?)?;
            return Ok(super::columns::to_labelled_json(
                doc,
                &serde_json::json!({
                    "spec": spec,
                    "element": "roller",
                    "ratings": { "gamma": r.gamma, "fc": r.fc, "c_n": r.cr, "c0_n": r.c0r },
                }),
            ));
        }
    }
    Ok(super::columns::to_labelled_json(
        doc,
        &bearing_detail(name)?,
    ))
}

/// A bearing from a preset or catalogue name, or a TOML bearing file.
pub fn load_bearing(arg: &str) -> Result<Bearing> {
    match preset(arg) {
        Ok(spec) => spec.build(),
        Err(unknown) => {
            let path = std::path::Path::new(arg);
            if path.exists() || arg.ends_with(".toml") {
                let text = std::fs::read_to_string(path)
                    .map_err(|e| Error::Io(format!("cannot read bearing file `{arg}`: {e}")))?;
                let spec = BearingSpec::from_toml(&text).map_err(|e| match e {
                    Error::Parse { message, .. } => Error::Parse {
                        what: format!("bearing file `{arg}`"),
                        message,
                    },
                    other => other,
                })?;
                spec.build()
            } else if crate::geometry::roller_catalogue::lookup(arg).is_some() {
                Err(Error::invalid(
                    "--bearing",
                    arg,
                    "a ball bearing: the quasi-static load table solves balls; a roller bearing runs in a scene at the quasi-static or ring level (bearing = \"NAME\" in `raceway run`), and `raceway bearings NAME` lists its data and ratings",
                ))
            } else {
                Err(unknown)
            }
        }
    }
}

/// What the arguments of a quasi-static problem are called where they come from, so an error
/// names the argument the user typed.
#[derive(Debug, Clone, Copy)]
pub struct QsNames {
    /// Shaft speed, rpm.
    pub speed_rpm: &'static str,
    /// Loads and moments `(Fx, Fy, Fz, Mx, My)`.
    pub load: [&'static str; 5],
    /// Viscosity ratio.
    pub kappa: &'static str,
    /// ISO 281 contamination factor.
    pub contamination: &'static str,
}

/// The command line's flags.
pub const CLI_NAMES: QsNames = QsNames {
    speed_rpm: "--speed-rpm",
    load: ["--fx", "--fy", "--fz", "--mx", "--my"],
    kappa: "--kappa",
    contamination: "--contamination",
};

/// The Python package's keyword arguments.
pub const PYTHON_NAMES: QsNames = QsNames {
    speed_rpm: "speed_rpm",
    load: ["fx", "fy", "fz", "mx", "my"],
    kappa: "kappa",
    contamination: "contamination",
};

/// A checked quasi-static problem: the bearing under an external load on the inner ring at a
/// shaft speed (outer ring fixed).
#[derive(Debug, Clone)]
pub struct QsProblem {
    /// The bearing.
    pub bearing: Bearing,
    /// Shaft speed, rpm (>= 0).
    pub speed_rpm: f64,
    /// External load `(Fx, Fy, Fz, Mx, My)`, N and N m.
    pub load: [f64; 5],
    /// Race control assumption.
    pub race_control: RaceControl,
    /// What the life needs beyond the loads.
    pub life: LifeInputs,
    /// The design check's inputs (oil, fits); set after [`QsProblem::new`].
    pub calc: crate::calculator::check::CalcInputs,
    /// Coordinates held at a value (default: none, the free equilibrium); set after
    /// [`QsProblem::new`].
    pub hold: crate::models::quasi_static::hold::HoldSpec,
}

fn finite(field: &str, v: f64) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::invalid(field, v, "a finite number"))
    }
}

impl QsProblem {
    /// Check the arguments (errors name them by `names`).
    pub fn new(
        bearing: Bearing,
        speed_rpm: f64,
        load: [f64; 5],
        race_control: RaceControl,
        kappa: Option<f64>,
        contamination: Option<f64>,
        names: &QsNames,
    ) -> Result<QsProblem> {
        let speed_rpm = finite(names.speed_rpm, speed_rpm)?;
        if speed_rpm < 0.0 {
            return Err(Error::invalid(
                names.speed_rpm,
                speed_rpm,
                ">= 0 (the inner ring turns, the outer ring is fixed; the direction does not change the equilibrium)",
            ));
        }
        // The plausibility limits every face uses (component inputs, scenes), written once
        // in `component::limits`: the rings' burst speed, the loads that would take the most
        // loaded contact past the plastic limit.
        let lim = crate::component::limits::Limits::of(&bearing);
        let omega = rpm_to_rad_s(speed_rpm);
        if omega > lim.omega {
            return Err(Error::invalid(
                names.speed_rpm,
                speed_rpm,
                format!(
                    "<= {:.0} rpm for this bearing: the rings' burst speed, the limit the component enforces on shaft.omega ({:.4e} rad/s)",
                    crate::units::rad_s_to_rpm(lim.omega),
                    lim.omega
                ),
            ));
        }
        let mut checked = [0.0; 5];
        const VARS: [&str; 5] = ["load.x", "load.y", "load.z", "load.mx", "load.my"];
        for k in 0..5 {
            // Refuses a non-finite value too, naming it as `finite` does.
            lim.check(names.load[k], VARS[k], load[k])?;
            checked[k] = load[k];
        }
        Ok(QsProblem {
            bearing,
            speed_rpm,
            load: checked,
            race_control,
            life: LifeInputs {
                speed_rpm,
                kappa: kappa.map(|k| positive(names.kappa, k)).transpose()?,
                contamination: contamination
                    .map(|e| in_range(names.contamination, e, 0.0, 1.0))
                    .transpose()?,
            },
            calc: Default::default(),
            hold: Default::default(),
        })
    }

    /// The Jones–Harris equilibrium and its ISO assessment. A bearing outside the standards'
    /// range (Dw cos a / Dpw > 0.4) still gets its equilibrium; the assessment's error says
    /// why the ratings are missing.
    pub fn solve(&self) -> Result<(Solution, std::result::Result<Assessment, String>)> {
        let opts = Options {
            race_control: self.race_control,
            ..Options::default()
        };
        let model = QuasiStatic::new(&self.solved_bearing()?, opts)?;
        let sol = model.solve_held(
            &self.load,
            rpm_to_rad_s(self.speed_rpm),
            &self.hold.to_si("hold")?,
        )?;
        // An oil without a typed kappa: kappa from the oil at the operating temperature.
        let mut life = self.life;
        if let (None, Some(oil)) = (life.kappa, &self.calc.oil) {
            life.kappa = crate::calculator::lubricant::lubrication(
                oil,
                self.calc.temperature_c,
                crate::calculator::lubricant::mean_diameter(&self.bearing),
                self.speed_rpm,
            )?
            .kappa;
        }
        let rating = assess(&self.bearing, &sol, &life).map_err(|e| e.to_string());
        Ok((sol, rating))
    }

    /// The bearing the equilibrium is solved with: with fits or ring temperatures given
    /// (`calc.clearance`), its clearance is the operating clearance they leave
    /// ([`crate::calculator::clearance::with_clearance`]); otherwise the bearing as given.
    /// The ISO ratings stay the bearing's own.
    pub fn solved_bearing(&self) -> Result<Bearing> {
        match &self.calc.clearance {
            Some(c) => {
                let op = crate::calculator::clearance::operating_clearance(&self.bearing, c)?;
                crate::calculator::clearance::with_clearance(&self.bearing, op.operating)
            }
            None => Ok(self.bearing.clone()),
        }
    }

    /// The design check at a solution of this problem (see [`crate::calculator::check`]).
    pub fn design_check(
        &self,
        sol: &Solution,
        rating: &std::result::Result<Assessment, String>,
    ) -> Result<crate::calculator::check::DesignCheck> {
        let calc = crate::calculator::check::CalcInputs {
            contamination: self.life.contamination,
            ..self.calc.clone()
        };
        crate::calculator::check::design_check(
            &self.bearing,
            sol,
            self.speed_rpm,
            rating.as_ref().ok(),
            &calc,
        )
    }
}

/// The name of a race-control assumption as the command line spells it.
pub fn control_name(c: RaceControl) -> &'static str {
    match c {
        RaceControl::Outer => "outer",
        RaceControl::None => "none",
    }
}

/// The JSON document of `raceway quasi-static --json` (serialise it; the field order is
/// the document's).
#[derive(Serialize)]
pub struct QsReport<'a> {
    /// Bearing designation.
    pub bearing: &'a str,
    /// Shaft speed, rpm.
    pub speed_rpm: f64,
    /// `outer` or `none`.
    pub race_control: &'static str,
    /// Everything else in SI: the library's [`Solution`].
    pub solution: &'a Solution,
    /// ISO ratings, lives (millions of revolutions and hours), static safety, peak
    /// pressure (Pa), typed warnings: the library's [`Assessment`] (null when the bearing
    /// is outside the standards' range; then `rating_error` says why).
    pub rating: Option<&'a Assessment>,
    /// Why there is no rating.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rating_error: Option<&'a str>,
    /// Warnings as sentences (the same list, typed, is `rating.warnings`).
    pub warnings: Vec<String>,
    /// The design check: oil viscosity and kappa, Palmgren friction and power loss,
    /// subsurface stresses below the most loaded ball, operating clearance (null when it
    /// failed; then `calculator_error` says why).
    pub calculator: Option<crate::calculator::check::DesignCheck>,
    /// Why there is no design check.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub calculator_error: Option<String>,
}

impl QsReport<'_> {
    /// The document as JSON, its keys labelled from [`super::columns`] (docs/columns.md):
    /// what `raceway quasi-static --json` prints and Python's `quasi_static` returns.
    pub fn to_json(&self) -> serde_json::Value {
        match serde_json::to_value(self) {
            Ok(serde_json::Value::Object(m)) => serde_json::Value::Object(super::columns::relabel(
                super::columns::Doc::QuasiStatic,
                m,
            )),
            other => other.unwrap_or_default(),
        }
    }
}

/// `raceway quasi-static --json`'s document (write it with [`QsReport::to_json`]).
pub fn quasi_static_report<'a>(
    p: &'a QsProblem,
    sol: &'a Solution,
    rating: &'a std::result::Result<Assessment, String>,
) -> QsReport<'a> {
    let check = p.design_check(sol, rating).map_err(|e| e.to_string());
    QsReport {
        bearing: &p.bearing.name,
        speed_rpm: p.speed_rpm,
        race_control: control_name(p.race_control),
        solution: sol,
        rating: rating.as_ref().ok(),
        rating_error: rating.as_ref().err().map(|e| e.as_str()),
        warnings: rating
            .as_ref()
            .map(|a| a.warning_texts())
            .unwrap_or_default(),
        calculator: check.as_ref().ok().cloned(),
        calculator_error: check.err(),
    }
}

/// The per-ball results as columns, each named `field [unit]` (SI; the units of
/// [`crate::models::quasi_static::BallResult`]'s fields).
pub fn ball_columns(sol: &Solution) -> (Vec<String>, Vec<Vec<f64>>) {
    type Get = fn(&crate::models::quasi_static::BallResult) -> f64;
    const COLUMNS: [(&str, &str, Get); 20] = [
        ("psi", "rad", |b| b.psi),
        ("q_i", "N", |b| b.q_i),
        ("q_o", "N", |b| b.q_o),
        ("alpha_i", "rad", |b| b.alpha_i),
        ("alpha_o", "rad", |b| b.alpha_o),
        ("delta_i", "m", |b| b.delta_i),
        ("delta_o", "m", |b| b.delta_o),
        ("a_i", "m", |b| b.a_i),
        ("b_i", "m", |b| b.b_i),
        ("p_i", "Pa", |b| b.p_i),
        ("a_o", "m", |b| b.a_o),
        ("b_o", "m", |b| b.b_o),
        ("p_o", "Pa", |b| b.p_o),
        ("fc", "N", |b| b.fc),
        ("mg", "N.m", |b| b.mg),
        ("omega_m", "rad/s", |b| b.omega_m),
        ("omega_r", "rad/s", |b| b.omega_r),
        ("beta", "rad", |b| b.beta),
        ("spin_roll_i", "1", |b| b.spin_roll_i),
        ("spin_roll_o", "1", |b| b.spin_roll_o),
    ];
    COLUMNS
        .iter()
        .map(|(n, u, get)| {
            (
                crate::units::label(n, u),
                sol.balls.iter().map(get).collect::<Vec<f64>>(),
            )
        })
        .unzip()
}
