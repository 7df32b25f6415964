//! One bearing's design check beside a quasi-static solution: the oil's viscosity and κ,
//! Palmgren's and SKF's friction moments and power losses, the moment held tilts carry, the subsurface stresses below the most loaded
//! contacts, and the operating clearance when fits or temperatures are given.

use super::clearance::{operating_clearance, with_clearance, ClearanceInputs, OperatingClearance};
use super::duty::{spectrum_life, DutyLife, SpectrumRow};
use super::friction::{palmgren, FrictionInputs, Palmgren, PalmgrenType};
use super::lubricant::{lubrication, Lubrication, Oil};
use super::skf_friction::{
    series_of, skf_friction, DragInputs, SealConstants, SkfFriction, SkfInputs, SkfKind,
    SkfLubrication, SkfSeries,
};
use super::subsurface::{subsurface, Subsurface};
use super::thermal_speed::{thermal_speeds, ThermalInputs, ThermalSpeed};
use crate::error::Result;
use crate::geometry::{Bearing, BearingKind};
use crate::models::quasi_static::Solution;
use crate::ratings::Assessment;
use serde::Serialize;

/// What the check needs beyond the bearing and its load.
#[derive(Clone, Debug, PartialEq)]
pub struct CalcInputs {
    /// The oil (`None`: no viscosity, κ or friction).
    pub oil: Option<Oil>,
    /// Oil (bearing) operating temperature, °C.
    pub temperature_c: f64,
    /// Palmgren's lubrication factor `f0` (2: oil bath, the sources' value for deep-groove
    /// ball bearings).
    pub f0: f64,
    /// Fits and ring temperatures (`None`: no operating clearance).
    pub clearance: Option<ClearanceInputs>,
    /// A load spectrum (`None`: no duty-cycle life).
    pub duty: Option<Vec<SpectrumRow>>,
    /// ISO 281 contamination factor for the spectrum rows' `a_ISO` (with the oil).
    pub contamination: Option<f64>,
    /// Ambient temperature of the thermally safe speed's heat balance, °C (default 20,
    /// ISO 15312's reference ambient).
    pub ambient_c: f64,
    /// Lubrication method of the SKF model (default: oil bath).
    pub skf_lubrication: SkfLubrication,
    /// Seal constants of the SKF model (`None`: open bearing).
    pub skf_seal: Option<SealConstants>,
    /// Oil-bath drag inputs of the SKF model (`None`: no drag term).
    pub skf_drag: Option<DragInputs>,
    /// Geometry constants typed by the user (`None`: the built-in series table); the kind is
    /// the bearing's.
    pub skf_constants: Option<SkfSeries>,
}

impl Default for CalcInputs {
    fn default() -> Self {
        CalcInputs {
            oil: None,
            temperature_c: 70.0,
            f0: 2.0,
            clearance: None,
            duty: None,
            contamination: None,
            ambient_c: super::thermal_speed::T_AMBIENT_REF_C,
            skf_lubrication: SkfLubrication::OilBath,
            skf_seal: None,
            skf_drag: None,
            skf_constants: None,
        }
    }
}

/// The design check's inputs as a user types them (units in the names; `None`: not given).
/// The command line's flags and Python's keywords carry the same names.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CalcOptions {
    /// ISO VG grade name, e.g. `VG68`.
    pub oil: Option<String>,
    /// Viscosity index of the oil (default [`super::lubricant::DEFAULT_VI`]).
    pub oil_vi: Option<f64>,
    /// Oil operating temperature, °C (default 70).
    pub oil_temp_c: Option<f64>,
    /// Palmgren's `f0` (default 2).
    pub f0: Option<f64>,
    /// Shaft-fit diametral interference, µm.
    pub shaft_interference_um: Option<f64>,
    /// Housing-fit diametral interference, µm.
    pub housing_interference_um: Option<f64>,
    /// Inner-ring temperature, °C.
    pub inner_ring_temp_c: Option<f64>,
    /// Outer-ring temperature, °C.
    pub outer_ring_temp_c: Option<f64>,
    /// Ambient temperature of the thermally safe speed, °C (default 20).
    pub ambient_temp_c: Option<f64>,
    /// SKF model lubrication method: `oil-bath` (default), `oil-jet`, `oil-air`, `grease`.
    pub skf_lubrication: Option<String>,
    /// SKF model seal constants `KS1,BETA,KS2,DS_MM` (both seals).
    pub skf_seal: Option<String>,
    /// SKF model oil-bath drag `VM,H_MM` (drag loss factor from SKF's diagram, oil level).
    pub skf_drag: Option<String>,
    /// SKF model geometry constants `R1,R2,R3,S1,S2,S3` for a series not in the table.
    pub skf_constants: Option<String>,
}

impl CalcInputs {
    /// From the typed options at a shaft speed; `oil_vi` without `oil` is refused, naming
    /// `vi_name`; the SKF options are named with `prefix` (`--skf-` on the command line,
    /// `skf_` in Python).
    pub fn from_options(
        o: &CalcOptions,
        speed_rpm: f64,
        vi_name: &str,
        prefix: &str,
    ) -> Result<CalcInputs> {
        let mut c = CalcInputs::default();
        let sep = if prefix.ends_with('-') { "-" } else { "_" };
        let name = |f: &str| format!("{prefix}{}", f.replace('_', sep));
        if let Some(l) = &o.skf_lubrication {
            c.skf_lubrication = SkfLubrication::parse(l, &name("lubrication"))?;
        }
        if let Some(t) = &o.skf_seal {
            c.skf_seal = Some(SealConstants::parse(t, &name("seal"))?);
        }
        if let Some(t) = &o.skf_drag {
            if c.skf_lubrication != SkfLubrication::OilBath {
                return Err(crate::Error::invalid(
                    name("drag"),
                    t,
                    "given with an oil bath only (the lubrication is not oil-bath)",
                ));
            }
            c.skf_drag = Some(DragInputs::parse(t, &name("drag"))?);
        }
        if let Some(t) = &o.skf_constants {
            c.skf_constants = Some(SkfSeries::given(
                t,
                SkfKind::DeepGroove,
                &name("constants"),
            )?);
        }
        if let Some(name) = &o.oil {
            c.oil = Some(Oil::by_name(name, o.oil_vi)?);
        } else if let Some(vi) = o.oil_vi {
            return Err(crate::Error::invalid(vi_name, vi, "given with the oil"));
        }
        if let Some(t) = o.oil_temp_c {
            c.temperature_c = t;
        }
        if let Some(f0) = o.f0 {
            c.f0 = f0;
        }
        if let Some(t) = o.ambient_temp_c {
            if !t.is_finite() || !(-60.0..=200.0).contains(&t) {
                return Err(crate::Error::invalid(
                    "ambient_temp_c",
                    t,
                    "a finite temperature in [-60, 200] °C",
                ));
            }
            c.ambient_c = t;
        }
        let fits = [
            o.shaft_interference_um,
            o.housing_interference_um,
            o.inner_ring_temp_c,
            o.outer_ring_temp_c,
        ];
        if fits.iter().any(Option::is_some) {
            let d = ClearanceInputs::default();
            c.clearance = Some(ClearanceInputs {
                shaft_interference: o.shaft_interference_um.unwrap_or(0.0) * 1e-6,
                housing_interference: o.housing_interference_um.unwrap_or(0.0) * 1e-6,
                inner_c: o.inner_ring_temp_c.unwrap_or(d.inner_c),
                outer_c: o.outer_ring_temp_c.unwrap_or(d.outer_c),
                speed_rpm,
                ..d
            });
        }
        Ok(c)
    }
}

/// Subsurface stresses below the most loaded ball's contacts.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ContactStress {
    /// Index of the ball.
    pub ball: usize,
    /// Inner contact.
    pub inner: Subsurface,
    /// Outer contact.
    pub outer: Subsurface,
}

/// The design check (SI).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DesignCheck {
    /// The oil, when given.
    pub oil: Option<Oil>,
    /// Its viscosity, ν1 and κ at the operating temperature.
    pub lubrication: Option<Lubrication>,
    /// Which model the `friction` field holds: `palmgren` (ISO/TR 14179-2's); the SKF
    /// four-term model is `skf_friction`.
    pub friction_model: &'static str,
    /// Palmgren's moment (N m) and power loss (W), when the oil and the ratings are known.
    pub friction: Option<Palmgren>,
    /// Below the most loaded ball (`None` when no ball is loaded).
    pub subsurface: Option<ContactStress>,
    /// The operating clearance chain, when fits or temperatures are given.
    pub clearance: Option<OperatingClearance>,
    /// The clearance (m) and free contact angle (rad) the equilibrium was solved with when
    /// the operating clearance was derived (it replaces the bearing's own).
    pub equilibrium_clearance: Option<(f64, f64)>,
    /// The life under the load spectrum, when one is given.
    pub duty: Option<DutyLife>,
    /// ISO 15312's thermal reference speed and the thermally safe speed at the oil's
    /// temperature (with the oil, the ratings and the bearing's envelope).
    pub thermal_speed: Option<ThermalSpeed>,
    /// The SKF four-term model (rolling, sliding, seals, drag), when the oil, the ratings,
    /// the bearing's envelope and its series' constants are known and the bearing turns.
    pub skf_friction: Option<SkfFriction>,
    /// Why there is no SKF friction (`None` when there is).
    pub skf_note: Option<String>,
    /// The moment the support holds on held tilts, and the lives with and without it.
    pub held_moment: Option<HeldMoment>,
}

/// The reaction moment on held tilts: ISO 281's equivalent load has no moment term, so its
/// `L10` does not see it; the per-ball life `L10r` (ISO/TS 16281's form, from the element
/// loads the moment changes) does.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct HeldMoment {
    /// Magnitude of the moment the bearing carries `|M_load + M_reaction|`, N m.
    pub moment: f64,
    /// The reaction moment on the held tilts `(Mx, My)`, N m.
    pub reaction: [f64; 2],
    /// ISO 281's `L10` (no moment), millions of revolutions.
    pub l10_mrev: Option<f64>,
    /// The per-ball `L10r` (with the moment), millions of revolutions.
    pub l10r_mrev: Option<f64>,
}

/// The check of `b` at the solution `sol` (its ISO assessment, when there is one).
pub fn design_check(
    b: &Bearing,
    sol: &Solution,
    speed_rpm: f64,
    rating: Option<&Assessment>,
    x: &CalcInputs,
) -> Result<DesignCheck> {
    let lub = match &x.oil {
        Some(o) => Some(lubrication(
            o,
            x.temperature_c,
            super::lubricant::mean_diameter(b),
            speed_rpm,
        )?),
        None => None,
    };
    let friction = match (lub, rating) {
        (Some(l), Some(a)) => {
            let t = match b.kind {
                BearingKind::DeepGroove => PalmgrenType::DEEP_GROOVE,
                BearingKind::AngularContact => PalmgrenType::ANGULAR_CONTACT,
            };
            Some(palmgren(
                t,
                &FrictionInputs {
                    dm: b.dm,
                    speed_rpm,
                    nu: l.nu,
                    fr: a.radial_load,
                    fa: a.axial_load,
                    p0: a.p0,
                    c0: a.ratings.c0,
                    f0: x.f0,
                },
            )?)
        }
        _ => None,
    };
    let most = sol
        .balls
        .iter()
        .enumerate()
        .filter(|(_, r)| r.q_i > 0.0 && r.q_o > 0.0 && r.p_i > 0.0 && r.p_o > 0.0)
        .max_by(|a, b| a.1.p_i.max(a.1.p_o).total_cmp(&b.1.p_i.max(b.1.p_o)));
    let subsurface = match most {
        Some((j, r)) => Some(ContactStress {
            ball: j,
            inner: subsurface(r.a_i, r.b_i, r.p_i, b.inner_material.poisson_ratio)?,
            outer: subsurface(r.a_o, r.b_o, r.p_o, b.outer_material.poisson_ratio)?,
        }),
        None => None,
    };
    let clearance = match &x.clearance {
        Some(c) => Some(operating_clearance(b, c)?),
        None => None,
    };
    let equilibrium_clearance = match &clearance {
        Some(k) => {
            let solved = with_clearance(b, k.operating)?;
            Some((solved.pd, solved.alpha0))
        }
        None => None,
    };
    let duty = match (&x.duty, rating) {
        (Some(rows), Some(a)) => {
            let kappa_at = |rpm: f64| match &x.oil {
                Some(o) => lubrication(o, x.temperature_c, super::lubricant::mean_diameter(b), rpm)
                    .ok()
                    .and_then(|l| l.kappa),
                None => None,
            };
            Some(spectrum_life(
                b,
                &a.ratings,
                rows,
                &kappa_at,
                x.contamination,
            )?)
        }
        _ => None,
    };
    let thermal_speed = match (lub, rating) {
        (Some(l), Some(a)) if b.width > 0.0 && b.bore > 0.0 && b.outer_diameter > b.bore => {
            Some(thermal_speeds(&ThermalInputs {
                bore: b.bore,
                outer_diameter: b.outer_diameter,
                width: b.width,
                dm: b.dm,
                c0: a.ratings.c0,
                kind: match b.kind {
                    BearingKind::DeepGroove => PalmgrenType::DEEP_GROOVE,
                    BearingKind::AngularContact => PalmgrenType::ANGULAR_CONTACT,
                },
                fr: a.radial_load,
                fa: a.axial_load,
                p0: a.p0,
                nu: l.nu,
                f0: x.f0,
                bearing_c: x.temperature_c,
                ambient_c: x.ambient_c,
            })?)
        }
        _ => None,
    };
    let (skf, skf_note) = skf_check(b, sol, speed_rpm, rating, lub.as_ref(), x);
    let held_moment = (sol.held[3] || sol.held[4]).then(|| {
        let m = [sol.load[3] + sol.reaction[3], sol.load[4] + sol.reaction[4]];
        HeldMoment {
            moment: m[0].hypot(m[1]),
            reaction: [sol.reaction[3], sol.reaction[4]],
            l10_mrev: rating.and_then(|a| a.l10_mrev),
            l10r_mrev: rating.and_then(|a| a.l10r_mrev),
        }
    });
    Ok(DesignCheck {
        oil: x.oil.clone(),
        lubrication: lub,
        friction_model: "palmgren",
        friction,
        subsurface,
        clearance,
        equilibrium_clearance,
        duty,
        thermal_speed,
        skf_friction: skf,
        skf_note,
        held_moment,
    })
}

/// The SKF model at the solution, or why not.
fn skf_check(
    b: &Bearing,
    sol: &Solution,
    speed_rpm: f64,
    rating: Option<&Assessment>,
    lub: Option<&Lubrication>,
    x: &CalcInputs,
) -> (Option<SkfFriction>, Option<String>) {
    let (l, a) = match (lub, rating) {
        (Some(l), Some(a)) => (l, a),
        _ => return (None, Some("needs the oil and the ISO ratings".into())),
    };
    if !(b.bore > 0.0 && b.outer_diameter > b.bore) {
        return (
            None,
            Some("needs the bearing's bore and outside diameter".into()),
        );
    }
    let kind = match b.kind {
        BearingKind::DeepGroove => SkfKind::DeepGroove,
        BearingKind::AngularContact => SkfKind::AngularContact,
    };
    let series = match (&x.skf_constants, series_of(&b.name)) {
        (Some(c), _) => SkfSeries { kind, ..*c },
        (None, Some(s)) if kind == s.kind => *s,
        _ => {
            return (
                None,
                Some(format!(
                    "no geometry constants for {} (built in: deep-groove 60, 62, 63; give --skf-constants R1,R2,R3,S1,S2,S3 from the maker's table)",
                    b.name
                )),
            )
        }
    };
    let r = skf_friction(
        &series,
        &SkfInputs {
            bore: b.bore,
            outer_diameter: b.outer_diameter,
            speed_rpm,
            nu: l.nu,
            fr: a.radial_load,
            fa: a.axial_load,
            c0: a.ratings.c0,
            lubrication: x.skf_lubrication,
            seal: x.skf_seal,
            drag: x.skf_drag,
            tilt: sol.q[3].hypot(sol.q[4]),
        },
    );
    match r {
        Ok(f) => (Some(f), None),
        Err(e) => (None, Some(e.to_string())),
    }
}

/// The check as text lines for `raceway quasi-static` (units at the edge).
pub fn text(c: &DesignCheck) -> String {
    use std::fmt::Write;
    let mut s = String::from("Design check:\n");
    match (&c.oil, &c.lubrication) {
        (Some(o), Some(l)) => {
            let _ = writeln!(
                s,
                "  oil:                            {} (VI {:.0}; 40 °C {:.2} mm²/s, 100 °C {:.2} mm²/s) at {:.1} °C: nu {:.2} mm²/s",
                o.name,
                o.viscosity_index,
                o.nu40 * 1e6,
                o.nu100 * 1e6,
                l.temperature_c,
                l.nu * 1e6
            );
            match (l.nu1, l.kappa) {
                (Some(n1), Some(k)) => {
                    let _ = writeln!(
                        s,
                        "  kappa = nu/nu1 (ISO 281):       {k:.3} (nu1 {:.2} mm²/s)",
                        n1 * 1e6
                    );
                }
                _ => s += "  kappa = nu/nu1 (ISO 281):       not defined at standstill\n",
            }
        }
        _ => s += "  oil:                            not given (--oil VG68 --oil-temp-c 70 gives viscosity, kappa and friction)\n",
    }
    match &c.friction {
        Some(f) => {
            let _ = writeln!(
                s,
                "  friction (Palmgren):            M {:.2} N mm = M0 {:.2} (viscous) + M1 {:.2} (load); power loss {:.2} W",
                f.total * 1e3,
                f.m0 * 1e3,
                f.m1 * 1e3,
                f.power
            );
        }
        None => s += "  friction (Palmgren):            needs the oil and the ISO ratings\n",
    }
    match (&c.skf_friction, &c.skf_note) {
        (Some(f), _) => {
            let opt = |m: Option<f64>, none: &str| match m {
                Some(v) => format!("{:.2}", v * 1e3),
                None => none.to_string(),
            };
            let _ = writeln!(
                s,
                "  friction (SKF four-term):       M {:.2} N mm = rolling {:.2} + sliding {:.2} + seals {} + drag {}; power loss {:.2} W",
                f.total * 1e3,
                f.rolling * 1e3,
                f.sliding * 1e3,
                opt(f.seals, "- (open)"),
                opt(f.drag, "- (not given)"),
                f.power
            );
            let _ = writeln!(
                s,
                "  SKF factors:                    series {}, {}: phi_ish {:.3}, phi_rs {:.3}, mu_sl {:.4}; UNCONFIRMED: {}",
                f.series, f.lubrication, f.phi_ish, f.phi_rs, f.mu_sl, f.unconfirmed
            );
            for w in &f.warnings {
                let _ = writeln!(s, "  SKF model warning:              {w}");
            }
        }
        (None, Some(why)) => {
            let _ = writeln!(s, "  friction (SKF four-term):       not computed: {why}");
        }
        (None, None) => {}
    }
    if let Some(h) = &c.held_moment {
        let life = |l: Option<f64>| l.map_or("-".to_string(), |v| format!("{v:.1}"));
        let _ = writeln!(
            s,
            "  held tilt:                      the bearing carries M {:.2} N m (reaction Mx {:.2}, My {:.2} N m); ISO 281's P has no moment term, so L10 {} Mrev ignores it; the per-ball L10r {} Mrev includes it",
            h.moment,
            h.reaction[0],
            h.reaction[1],
            life(h.l10_mrev),
            life(h.l10r_mrev)
        );
    }
    if let Some(st) = &c.subsurface {
        for (name, q) in [("inner", &st.inner), ("outer", &st.outer)] {
            let _ = writeln!(
                s,
                "  subsurface, ball {} {name}:       tau45 {:.0} MPa at {:.1} µm, tau0 {:.0} MPa at {:.1} µm, von Mises {:.0} MPa at {:.1} µm",
                st.ball,
                q.tau_max * 1e-6,
                q.z_tau_max * 1e6,
                q.tau_orth * 1e-6,
                q.z_tau_orth * 1e6,
                q.von_mises * 1e-6,
                q.z_von_mises * 1e6
            );
        }
    }
    if let Some(d) = &c.duty {
        let _ = writeln!(
            s,
            "  duty cycle (ISO 281, Miner):    P_m {:.1} N at n_m {:.1} rpm: L10 {:.1} Mrev; with each row's a_ISO {:.1} Mrev = {:.0} h",
            d.mean_load, d.mean_speed_rpm, d.l10_mrev, d.miner_mrev, d.miner_hours
        );
    }
    if let Some(t) = &c.thermal_speed {
        let _ = writeln!(
            s,
            "  thermal reference speed:        {:.0} rpm (ISO 15312 conditions: 0.05 C0 = {:.0} N radial, 12 mm²/s, ring 70 °C, ambient 20 °C; A_r {:.0} mm², q_r {:.4} W/mm², {:.1} W)",
            t.reference_speed_rpm,
            t.reference_load,
            t.surface * 1e6,
            t.heat_flow_density * 1e-6,
            t.heat_flow
        );
        match t.safe_speed_rpm {
            Some(n) => {
                let _ = writeln!(
                    s,
                    "  thermally safe speed:           {n:.0} rpm at this load and oil, bearing {:.0} °C, ambient {:.0} °C (the seats' reference heat transfer; no oil-flow cooling)",
                    t.safe_temperatures_c.0, t.safe_temperatures_c.1
                );
            }
            None => s += "  thermally safe speed:           none (the oil temperature is not above the ambient)
",
        }
        let _ = writeln!(s, "  UNSOURCED in these two lines:   {}", t.unsourced);
    }
    if let Some(k) = &c.clearance {
        let _ = writeln!(
            s,
            "  operating clearance:            Pd {:.2} µm = {:.2} unmounted {:+.2} shaft fit {:+.2} housing fit {:+.2} temperatures {:+.2} speed",
            k.operating * 1e6,
            k.unmounted * 1e6,
            k.from_shaft_fit * 1e6,
            k.from_housing_fit * 1e6,
            k.from_temperatures * 1e6,
            k.from_speed * 1e6
        );
        let _ = writeln!(
            s,
            "  fit pressures:                  shaft {:.1} MPa, housing {:.1} MPa; hoop stress at the bore {:.1} MPa",
            k.shaft_pressure * 1e-6,
            k.housing_pressure * 1e-6,
            k.inner_bore_hoop_stress * 1e-6
        );
        if let Some((pd, a0)) = c.equilibrium_clearance {
            let _ = writeln!(
                s,
                "  equilibrium solved with:        Pd {:.2} µm operating clearance, free contact angle {:.2} deg (the load table above)",
                pd * 1e6,
                a0.to_degrees()
            );
        }
    }
    s
}
