//! How the FMU parameters (`component::variables::PARAMETERS`) make a scene.
//!
//! 1. The scene text: the `scene` parameter when set and not empty, else the FMU's
//!    `resources/scene.toml` when it carries one, else `Scene::default_scene()`.
//! 2. On top of it, each parameter the host set (a string parameter set to "" and an
//!    enumeration set to item 0, `scene`, count as not set):
//!    - `bearing` -> `bearing = "<preset>"` (replaces the scene's bearing);
//!    - `level` -> `model.level`; `input_rule` -> `inputs.rule`;
//!    - `clearance` (m), when `override_clearance` is true -> the bearing's `clearance_um`
//!      (the preset or table kept, only the clearance overridden);
//!    - `clearance_um` (µm) -> the bearing's `clearance_um`, as `clearance` does but
//!      without `override_clearance` (after it, so it wins when both are set);
//!    - `speed_rpm` -> `inputs.speed_rpm` (the start value of the input `shaft.omega`);
//!      these two apply when set to a value other than their start (the default scene's
//!      0 µm and 1750 rpm), so writing every start value changes nothing;
//!    - `solver` -> `solver.method`;
//!    - `rtol` -> `solver.rtol`; when `rtol` is not set, a tolerance the host gave in
//!      `fmi2SetupExperiment` / `fmi3EnterInitializationMode` is used if it lies in the
//!      range the solver accepts.
//! 3. The FMU's variant decides the causality: the motion-driven FMU refuses a load-driven
//!    scene; the load-driven FMU runs any scene load-driven (`model.causality` = motion is
//!    the scene default), and with the default scene drops its motion start values. The
//!    load-driven FMU's inputs set before initialisation ends become `inputs.initial`, so
//!    the ring's static start solves for the host's loads.
//!
//! Every refusal names the parameter (or the scene source) and the cause.

use crate::component::scene::{BearingRef, InputRule, Level};
use crate::component::variables::{self, Causality, ParamType, PARAMETERS};
use crate::component::{Component, Scene};

/// A value the host set for a parameter.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum ParamValue {
    Real(f64),
    Str(String),
    Bool(bool),
    /// An enumeration item.
    Int(i64),
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
        Some(ParamValue::Int(0)) => None,
        v => v.as_ref(),
    }
}

/// The item an enumeration parameter was set to (item 0, `scene`, is "not set").
fn item(values: &ParamValues, name: &str) -> Option<&'static str> {
    let p = PARAMETERS.iter().find(|p| p.name == name)?;
    match (get(values, name), p.ty) {
        (Some(ParamValue::Int(k)), ParamType::Enumeration { items, .. }) => {
            items.get(usize::try_from(*k).ok()?).copied()
        }
        _ => None,
    }
}

fn boolean(values: &ParamValues, name: &str) -> bool {
    matches!(get(values, name), Some(ParamValue::Bool(true)))
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

/// A named real parameter (`clearance_um`, `speed_rpm`) the host set to a value other than
/// its start: its start (the default scene's value) changes nothing, so a host that writes
/// every start value leaves a scene string's field as it is.
fn named_real(values: &ParamValues, name: &str) -> Option<f64> {
    let start = PARAMETERS.iter().position(|p| p.name == name).map(start)?;
    real(values, name).filter(|&x| ParamValue::Real(x) != start)
}

/// The start value of parameter `i` as the model description gives it.
pub(crate) fn start(i: usize) -> ParamValue {
    let p = &PARAMETERS[i];
    match p.ty {
        ParamType::Real => ParamValue::Real(p.start.parse().unwrap_or(0.0)),
        ParamType::String => ParamValue::Str(p.start.to_string()),
        ParamType::Boolean => ParamValue::Bool(p.start == "true"),
        ParamType::Enumeration { .. } => ParamValue::Int(p.start.parse().unwrap_or(0)),
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

/// The scene the parameters describe for the FMU of causality `causality`, with the
/// host's `initial` input values, and where its text came from.
pub(crate) fn scene(
    values: &ParamValues,
    tolerance: Option<f64>,
    resource_scene: Option<&Result<String, String>>,
    causality: Causality,
    initial: &[(&str, f64)],
) -> Result<(Scene, &'static str), String> {
    let (mut scene, source) = if let Some(text) = string(values, "scene") {
        let s = Scene::from_text(text).map_err(|e| scene_error("parameter `scene`", text, &e))?;
        (s, "the `scene` parameter")
    } else if let Some(r) = resource_scene {
        let text = r
            .as_ref()
            .map_err(|e| format!("resources/scene.toml: {e}"))?;
        let s =
            Scene::from_text(text).map_err(|e| scene_error("resources/scene.toml", text, &e))?;
        (s, "resources/scene.toml")
    } else {
        (Scene::default_scene(), "the default scene")
    };
    match (causality, scene.model.causality) {
        (Causality::Motion, Causality::Load) => {
            return Err(format!(
                "{source}: `model.causality` = load, but this is the motion-driven FMU \
                 (shaft motion in, forces out); use the load-driven FMU (raceway-load-fmi2/3.fmu)"
            ))
        }
        (Causality::Load, _) => {
            scene.model.causality = Causality::Load;
            if source == "the default scene" {
                scene
                    .inputs
                    .initial
                    .retain(|k, _| variables::by_name(k).is_some_and(|v| v.is_input(causality)));
            }
        }
        (Causality::Motion, Causality::Motion) => {}
    }
    for &(name, value) in initial {
        scene.inputs.set_initial(name, value);
    }
    if let Some(name) = string(values, "bearing") {
        crate::geometry::preset(name).map_err(|e| format!("parameter `bearing`: {e}"))?;
        scene.bearing = BearingRef::Preset(name.to_string());
    }
    if let Some(level) = item(values, "level") {
        scene.model.level = parse_enum::<Level>("level", level, &Level::NAMES.join(", "))?;
    }
    if let Some(rule) = item(values, "input_rule") {
        scene.inputs.rule =
            parse_enum::<InputRule>("input_rule", rule, "hold, velocity or derivatives")?;
    }
    // The clearance applies only when `override_clearance` is true, so a host that pushes
    // every start value changes nothing.
    if boolean(values, "override_clearance") {
        let c = real(values, "clearance").unwrap_or(0.0);
        if !(c.is_finite() && c.abs() <= 1e-3) {
            return Err(format!(
                "parameter `clearance` = {c} m: allowed a finite number in [-1e-3, 1e-3] m \
                 (negative: preload)"
            ));
        }
        set_clearance_um(&mut scene, c * 1e6);
    }
    if let Some(um) = named_real(values, "clearance_um") {
        in_range("clearance_um", um, "µm")?;
        set_clearance_um(&mut scene, um);
    }
    if let Some(rpm) = named_real(values, "speed_rpm") {
        in_range("speed_rpm", rpm, "rpm")?;
        scene.inputs.speed_rpm = rpm;
    }
    if let Some(m) = item(values, "solver") {
        scene.solver.method = parse_enum::<crate::component::scene::Method>(
            "solver",
            m,
            &crate::solver::methods::METHOD_NAMES.join(", "),
        )?;
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

/// The bearing's diametral clearance set to `um` µm: a preset becomes `{ preset, clearance_um }`
/// (its table kept), a table gets the entry.
fn set_clearance_um(scene: &mut Scene, um: f64) {
    let um = toml::Value::Float(um);
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

/// A named parameter's value within its declared range (the scene row's), or the refusal
/// naming the parameter and the range.
fn in_range(name: &str, value: f64, unit: &str) -> Result<(), String> {
    match variables::range(name) {
        Some((lo, hi)) if !(lo..=hi).contains(&value) => Err(format!(
            "parameter `{name}` = {value} {unit}: allowed [{}, {}] {unit}",
            super::model_description::num(lo),
            super::model_description::num(hi)
        )),
        _ => Ok(()),
    }
}

/// The value each input of the FMU of causality `causality` holds until the host sets it,
/// in the order of [`md::inputs`](super::model_description::inputs): the scene's initial
/// value ([`crate::component::scene::InputSpec::initial_value`]) of the scene the
/// parameters make. The model description's `start` attributes are these numbers for the
/// scene the FMU carries.
pub(crate) fn input_starts(
    values: &ParamValues,
    resource_scene: Option<&Result<String, String>>,
    causality: Causality,
) -> Result<Vec<f64>, String> {
    let (scene, _) = scene(values, None, resource_scene, causality, &[])?;
    Ok(super::model_description::inputs(causality)
        .map(|v| scene.inputs.initial_value(v.name))
        .collect())
}

/// A scene text that failed with `e`: every problem with its `line:column` and "did you
/// mean", as `raceway scene --check` gives them.
fn scene_error(source: &str, text: &str, e: &crate::Error) -> String {
    format!(
        "{source}: {}",
        crate::component::schema::scene_error_text(text, e)
    )
}

/// Build the component of a [`scene`] and where its text came from (`values`: the
/// parameters it was made with; `resource_scene`: the FMU's own scene, as for [`scene`]).
/// The error names the cause; a scene text the host's parameters left as it was is checked
/// as `raceway scene --check` does (every problem, with its `line:column`).
pub(crate) fn component(
    values: &ParamValues,
    resource_scene: Option<&Result<String, String>>,
    (scene, source): (Scene, &'static str),
) -> Result<(Component, &'static str), String> {
    let c = Component::new(scene).map_err(|e| {
        let set: Vec<&str> = PARAMETERS
            .iter()
            .zip(values)
            .filter(|(p, v)| v.is_some() && p.name != "scene")
            .map(|(p, _)| p.name)
            .collect();
        let text = match source {
            "the `scene` parameter" => string(values, "scene"),
            "resources/scene.toml" => resource_scene
                .and_then(|r| r.as_ref().ok())
                .map(String::as_str),
            _ => None,
        };
        if let (true, Some(text)) = (set.is_empty(), text) {
            scene_error(source, text, &e)
        } else if set.is_empty() {
            format!("{source}: {e}")
        } else {
            format!("{source} with parameters {}: {e}", set.join(", "))
        }
    })?;
    Ok((c, source))
}
