//! How the FMU parameters (`component::variables::PARAMETERS`) make a scene.
//!
//! 1. The scene text: the `scene` parameter when set and not empty, else the FMU's
//!    `resources/scene.toml` when it carries one, else `Scene::default_scene()`.
//! 2. On top of it, each parameter the host set (a string parameter set to "" counts as
//!    not set):
//!    - `bearing` -> `bearing = "<preset>"` (replaces the scene's bearing);
//!    - `level` -> `model.level`; `input_rule` -> `inputs.rule`;
//!    - `clearance` (m) -> the bearing's `clearance_um` (the preset or table kept, only the
//!      clearance overridden);
//!    - `rtol` -> `solver.rtol`; when `rtol` is not set, a tolerance the host gave in
//!      `fmi2SetupExperiment` / `fmi3EnterInitializationMode` is used if it lies in the
//!      range the solver accepts.
//! 3. The scene must be motion-driven (the FMUs' inputs are the shaft's motion).
//!
//! Every refusal names the parameter (or the scene source) and the cause.

use crate::component::scene::{BearingRef, InputRule, Level};
use crate::component::variables::{Causality, ParamType, PARAMETERS};
use crate::component::{Component, Scene};

/// A value the host set for a parameter.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum ParamValue {
    Real(f64),
    Str(String),
}

/// The values the host set, indexed like `PARAMETERS` (`None`: not set).
pub(crate) type ParamValues = Vec<Option<ParamValue>>;

pub(crate) fn unset() -> ParamValues {
    vec![None; PARAMETERS.len()]
}

/// Index in `PARAMETERS` of value reference `vr`.
pub(crate) fn index(vr: u32) -> Option<usize> {
    PARAMETERS.iter().position(|p| p.vr == vr)
}

fn get<'a>(values: &'a ParamValues, name: &str) -> Option<&'a ParamValue> {
    let i = PARAMETERS.iter().position(|p| p.name == name)?;
    match values.get(i)? {
        Some(ParamValue::Str(s)) if s.trim().is_empty() => None,
        v => v.as_ref(),
    }
}

fn string<'a>(values: &'a ParamValues, name: &str) -> Option<&'a str> {
    match get(values, name) {
        Some(ParamValue::Str(s)) => Some(s.trim()),
        _ => None,
    }
}

fn real(values: &ParamValues, name: &str) -> Option<f64> {
    match get(values, name) {
        Some(ParamValue::Real(x)) => Some(*x),
        _ => None,
    }
}

/// The start value of parameter `i` as the model description gives it.
pub(crate) fn start(i: usize) -> ParamValue {
    let p = &PARAMETERS[i];
    match p.ty {
        ParamType::Real => ParamValue::Real(p.start.parse().unwrap_or(0.0)),
        ParamType::String => ParamValue::Str(p.start.to_string()),
    }
}

fn parse_enum<T: serde::de::DeserializeOwned>(
    param: &str,
    value: &str,
    allowed: &str,
) -> Result<T, String> {
    serde_json::from_value(serde_json::Value::String(value.to_string()))
        .map_err(|_| format!("parameter `{param}` = \"{value}\": allowed {allowed}"))
}

/// The scene the parameters describe, and where its text came from.
pub(crate) fn scene(
    values: &ParamValues,
    tolerance: Option<f64>,
    resource_scene: Option<&Result<String, String>>,
) -> Result<(Scene, &'static str), String> {
    let (mut scene, source) = if let Some(text) = string(values, "scene") {
        let s = Scene::from_text(text).map_err(|e| format!("parameter `scene`: {e}"))?;
        (s, "the `scene` parameter")
    } else if let Some(r) = resource_scene {
        let text = r
            .as_ref()
            .map_err(|e| format!("resources/scene.toml: {e}"))?;
        let s = Scene::from_text(text).map_err(|e| format!("resources/scene.toml: {e}"))?;
        (s, "resources/scene.toml")
    } else {
        (Scene::default_scene(), "the default scene")
    };
    if scene.model.causality != Causality::Motion {
        return Err(format!(
            "{source}: `model.causality` = load is not supported by the FMU, which is \
             motion-driven (shaft motion in, forces out); use the Rust API or the C ABI for \
             load-driven runs"
        ));
    }
    if let Some(name) = string(values, "bearing") {
        crate::geometry::preset(name).map_err(|e| format!("parameter `bearing`: {e}"))?;
        scene.bearing = BearingRef::Preset(name.to_string());
    }
    if let Some(level) = string(values, "level") {
        scene.model.level = parse_enum::<Level>("level", level, &Level::NAMES.join(", "))?;
    }
    if let Some(rule) = string(values, "input_rule") {
        scene.inputs.rule =
            parse_enum::<InputRule>("input_rule", rule, "hold, velocity or derivatives")?;
    }
    // The start value -1 (no bearing has a metre of interference) means "as the bearing
    // has it", so a host that pushes every start value changes nothing.
    if let Some(c) = real(values, "clearance").filter(|&c| c != -1.0) {
        if !(c.is_finite() && c.abs() < 1e-3) {
            return Err(format!(
                "parameter `clearance` = {c} m: allowed a finite number in (-1e-3, 1e-3) m \
                 (negative: preload), or -1 for the bearing's own"
            ));
        }
        let um = toml::Value::Float(c * 1e6);
        scene.bearing =
            match std::mem::replace(&mut scene.bearing, BearingRef::Table(toml::Table::new())) {
                BearingRef::Preset(name) => {
                    let mut t = toml::Table::new();
                    t.insert("preset".into(), toml::Value::String(name));
                    t.insert("clearance_um".into(), um);
                    BearingRef::Table(t)
                }
                BearingRef::Table(mut t) => {
                    t.insert("clearance_um".into(), um);
                    BearingRef::Table(t)
                }
            };
    }
    if let Some(r) = real(values, "rtol") {
        if !r.is_finite() {
            return Err(format!("parameter `rtol` = {r}: allowed a finite number"));
        }
        scene.solver.rtol = r;
    } else if let Some(tol) = tolerance {
        let rtol =
            crate::component::fields::find(crate::component::scene::SolverSpec::FIELDS, "rtol");
        if rtol.bounds.contains(tol) {
            scene.solver.rtol = tol;
        }
    }
    Ok((scene, source))
}

/// Build the component the parameters describe. The error names the cause.
pub(crate) fn component(
    values: &ParamValues,
    tolerance: Option<f64>,
    resource_scene: Option<&Result<String, String>>,
) -> Result<(Component, &'static str), String> {
    let (scene, source) = scene(values, tolerance, resource_scene)?;
    let c = Component::new(scene).map_err(|e| {
        let set: Vec<&str> = PARAMETERS
            .iter()
            .zip(values)
            .filter(|(_, v)| v.is_some())
            .map(|(p, _)| p.name)
            .collect();
        if set.is_empty() {
            format!("{source}: {e}")
        } else {
            format!("{source} with parameters {}: {e}", set.join(", "))
        }
    })?;
    Ok((c, source))
}
