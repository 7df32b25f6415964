//! Value calls of an FMU instance, the same for FMI 2 and FMI 3: what a value reference is,
//! get and set of Real/Float64, Integer, Boolean, String, range checks, input and output
//! derivatives, directional derivatives, and the exports' array forms.

use super::*;

/// Refuse `value` outside the range the model description declares for `name`
/// (`variables::RANGES`), naming the variable, the value and the range.
pub(super) fn in_range(name: &str, kind: &str, value: f64) -> Result<(), Fail> {
    match crate::component::variables::range(name) {
        Some((lo, hi)) if !(lo..=hi).contains(&value) => Err(Fail::from(format!(
            "{kind} `{name}` = {value}: allowed [{}, {}] (its declared min and max)",
            md::num(lo),
            md::num(hi)
        ))),
        _ => Ok(()),
    }
}

pub(super) fn name_of(vr: u32) -> String {
    if vr == VR_TIME {
        return "time".into();
    }
    if let Some(i) = params::index(vr) {
        return PARAMETERS[i].name.into();
    }
    variables::by_vr(vr).map_or(format!("#{vr}"), |v| v.name.to_string())
}

// ---------------------------------------------------------------------------------------
// Value calls, the same in both versions but for the argument names in messages
// (`names`: FMI 2's `vr`, `value`; FMI 3's `valueReferences`, `values`).

/// A getter: `value[i] = get(vr[i])` for the `nvr` value references.
///
/// # Safety
/// `vr` and `value` are NULL or valid for `nvr` values.
pub(crate) unsafe fn get_values<T>(
    vr: *const u32,
    value: *mut T,
    nvr: usize,
    names: [&str; 2],
    mut get: impl FnMut(u32) -> Result<T, Fail>,
) -> Result<Status, Fail> {
    let vr = slice(vr, nvr, names[0])?;
    let out = slice_mut(value, nvr, names[1])?;
    for (o, &r) in out.iter_mut().zip(vr) {
        *o = get(r)?;
    }
    Ok(Status::Ok)
}

/// A setter: `set(vr[i], value[i])` for the `nvr` value references.
///
/// # Safety
/// `vr` and `value` are NULL or valid for `nvr` values.
pub(crate) unsafe fn set_values<T: Copy>(
    vr: *const u32,
    value: *const T,
    nvr: usize,
    names: [&str; 2],
    mut set: impl FnMut(u32, T) -> Result<(), Fail>,
) -> Result<Status, Fail> {
    let vr = slice(vr, nvr, names[0])?;
    let vals = slice(value, nvr, names[1])?;
    for (&r, &x) in vr.iter().zip(vals) {
        set(r, x)?;
    }
    Ok(Status::Ok)
}

/// `GetString`: the strings stay valid until the next call (they live in the instance).
///
/// # Safety
/// `vr` and `value` are NULL or valid for `nvr` values.
pub(crate) unsafe fn get_strings(
    inst: &mut Instance,
    vr: *const u32,
    value: *mut *const c_char,
    nvr: usize,
    names: [&str; 2],
) -> Result<Status, Fail> {
    let vr = slice(vr, nvr, names[0])?;
    let out = slice_mut(value, nvr, names[1])?;
    let strings = vr
        .iter()
        .map(|&r| inst.get_string(r))
        .collect::<Result<Vec<_>, _>>()?;
    inst.strings = strings
        .into_iter()
        .map(|s| CString::new(s.replace('\0', " ")).unwrap_or_default())
        .collect();
    for (o, s) in out.iter_mut().zip(&inst.strings) {
        *o = s.as_ptr();
    }
    Ok(Status::Ok)
}

/// `GetRealOutputDerivatives` / `GetOutputDerivatives`: `names` of the value references,
/// the orders and the values.
///
/// # Safety
/// `vr`, `order` and `value` are NULL or valid for `nvr` values.
pub(crate) unsafe fn get_output_derivatives(
    inst: &mut Instance,
    vr: *const u32,
    order: *const i32,
    value: *mut f64,
    nvr: usize,
    names: [&str; 3],
) -> Result<Status, Fail> {
    let vr = slice(vr, nvr, names[0])?;
    let order = slice(order, nvr, names[1])?;
    let out = slice_mut(value, nvr, names[2])?;
    for i in 0..nvr {
        out[i] = inst.get_output_derivative(vr[i], order[i] as i64)?;
    }
    Ok(Status::Ok)
}

/// `SetDebugLogging`.
///
/// # Safety
/// `categories` is NULL or valid for `n` C strings (each NULL or NUL-terminated).
pub(crate) unsafe fn set_debug_logging(
    inst: &mut Instance,
    on: bool,
    n: usize,
    categories: *const *const c_char,
) -> Outcome {
    let cats: Vec<String> = slice(categories, n, "categories")?
        .iter()
        .map(|&p| str_arg(p).unwrap_or_default())
        .collect();
    inst.set_debug_logging(on, &cats)
}

impl Instance {
    pub(super) fn classify(&self, vr: u32) -> Option<Var> {
        classify(self.causality, vr)
    }

    /// A parameter's value: the host's, else its start value.
    pub(super) fn param_value(&self, i: usize) -> ParamValue {
        self.params[i].clone().unwrap_or_else(|| params::start(i))
    }

    pub(crate) fn get_real(&mut self, vr: u32) -> Result<f64, Fail> {
        match self.classify(vr) {
            Some(Var::Time) => Ok(self.time),
            Some(Var::Input(i)) => match &mut self.component {
                Some(c) => Ok(c.get_real(vr)?),
                None if self.inputs_set & (1 << i) != 0 => Ok(self.inputs[i]),
                // Never set: the scene's initial value, the model description's start.
                None => {
                    let starts = params::input_starts(
                        &self.params,
                        self.resource_scene.as_ref(),
                        self.causality,
                    )?;
                    Ok(starts[i])
                }
            },
            Some(Var::Output(VarType::Real)) => Ok(self.component()?.get_real(vr)?),
            Some(Var::Param(i)) if PARAMETERS[i].ty == ParamType::Real => {
                match self.param_value(i) {
                    ParamValue::Real(x) => Ok(x),
                    _ => unreachable!("a real parameter"),
                }
            }
            _ => Err(self.wrong_type(vr, "Real / Float64")),
        }
    }

    /// The refusal of `vr` for an accessor of type `ty`, naming its real type.
    pub(crate) fn wrong_type(&self, vr: u32, ty: &str) -> Fail {
        let is = match self.classify(vr) {
            Some(Var::Output(VarType::Integer)) => "an Integer / Int32 output",
            Some(Var::Output(VarType::Real)) | Some(Var::Input(_)) | Some(Var::Time) => {
                "a Real / Float64 variable"
            }
            Some(Var::Param(i)) => match PARAMETERS[i].ty {
                ParamType::Real => "a Real / Float64 parameter",
                ParamType::String => "a String parameter",
                ParamType::Boolean => "a Boolean parameter",
                ParamType::Enumeration { .. } => "an Enumeration parameter",
            },
            None => {
                let v = md::variant_name(self.causality);
                return Fail::from(match variables::by_vr(vr) {
                    Some(var) => format!(
                        "`{}` (value reference {vr}) is not a variable of the {v}-driven FMU",
                        var.name
                    ),
                    None => format!("no {ty} variable with value reference {vr}"),
                });
            }
        };
        Fail::from(format!(
            "`{}` (value reference {vr}) is {is}, not {ty}",
            name_of(vr)
        ))
    }

    /// Integer outputs and Enumeration parameters (FMI 2 `Integer`, FMI 3 `Int32` /
    /// `Int64` access).
    pub(crate) fn get_integer(&mut self, vr: u32, ty: &str) -> Result<i64, Fail> {
        match self.classify(vr) {
            Some(Var::Output(VarType::Integer)) => {
                let x = self.component()?.get_real(vr)?;
                // counts: exact small integers in the component's f64 outputs
                Ok(x.round().clamp(i32::MIN as f64, i32::MAX as f64) as i64)
            }
            Some(Var::Param(i)) if matches!(PARAMETERS[i].ty, ParamType::Enumeration { .. }) => {
                match self.param_value(i) {
                    ParamValue::Int(k) => Ok(k),
                    _ => unreachable!("an enumeration parameter"),
                }
            }
            _ => Err(self.wrong_type(vr, ty)),
        }
    }

    /// FMI 3 `Int32`: the Integer outputs only.
    pub(crate) fn get_int32(&mut self, vr: u32) -> Result<i32, Fail> {
        match self.classify(vr) {
            Some(Var::Output(VarType::Integer)) => Ok(self.get_integer(vr, "Int32")? as i32),
            _ => Err(self.wrong_type(vr, "Int32")),
        }
    }

    /// FMI 3 `Int64`: the Enumeration parameters only.
    pub(crate) fn get_enumeration(&mut self, vr: u32) -> Result<i64, Fail> {
        match self.classify(vr) {
            Some(Var::Param(_)) => self.get_integer(vr, "Int64 (Enumeration)"),
            _ => Err(self.wrong_type(vr, "Int64 (Enumeration)")),
        }
    }

    /// Enumeration parameters: `value` must be one of the items.
    pub(crate) fn set_integer(&mut self, vr: u32, value: i64, ty: &str) -> Result<(), Fail> {
        let Some(i) = param_of(vr, |t| matches!(t, ParamType::Enumeration { .. })) else {
            return Err(match self.classify(vr) {
                Some(Var::Output(_)) => Fail::from(format!(
                    "`{}` (value reference {vr}) is an output: it cannot be set",
                    name_of(vr)
                )),
                _ => self.wrong_type(vr, ty),
            });
        };
        self.parameter_settable(i)?;
        let ParamType::Enumeration { type_name, items } = PARAMETERS[i].ty else {
            unreachable!("an enumeration parameter")
        };
        if !(0..items.len() as i64).contains(&value) {
            return Err(Fail::from(format!(
                "parameter `{}` = {value}: allowed an item of {type_name}: {}",
                PARAMETERS[i].name,
                items
                    .iter()
                    .enumerate()
                    .map(|(k, n)| format!("{k} ({n})"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        }
        self.params[i] = Some(ParamValue::Int(value));
        self.component = None;
        Ok(())
    }

    /// Boolean parameters.
    pub(crate) fn get_boolean(&self, vr: u32) -> Result<bool, Fail> {
        match param_of(vr, |t| t == ParamType::Boolean) {
            Some(i) => match self.param_value(i) {
                ParamValue::Bool(b) => Ok(b),
                _ => unreachable!("a Boolean parameter"),
            },
            None => Err(self.wrong_type(vr, "Boolean")),
        }
    }

    /// Boolean parameters.
    pub(crate) fn set_boolean(&mut self, vr: u32, value: bool) -> Result<(), Fail> {
        let Some(i) = param_of(vr, |t| t == ParamType::Boolean) else {
            return Err(self.wrong_type(vr, "Boolean"));
        };
        self.parameter_settable(i)?;
        self.params[i] = Some(ParamValue::Bool(value));
        self.component = None;
        Ok(())
    }

    pub(super) fn parameter_settable(&self, i: usize) -> Result<(), Fail> {
        if self.mode & (INSTANTIATED | INIT) == 0 {
            return Err(Fail::from(format!(
                "parameter `{}` is fixed: set it before initialisation ends (state {})",
                PARAMETERS[i].name,
                mode_name(self.mode, self.version)
            )));
        }
        Ok(())
    }

    pub(crate) fn set_real(&mut self, vr: u32, value: f64) -> Result<(), Fail> {
        match self.classify(vr) {
            Some(Var::Input(i)) => {
                if !value.is_finite() {
                    return Err(Fail::from(format!(
                        "input `{}` = {value}: allowed a finite number",
                        name_of(vr)
                    )));
                }
                in_range(&name_of(vr), "input", value)?;
                // Load-driven, an input set before initialisation ends is a start value of
                // the ring's static start: the component is rebuilt with it.
                let initial =
                    self.causality == Causality::Load && self.mode & (INSTANTIATED | INIT) != 0;
                if initial {
                    self.component = None;
                } else if let Some(c) = &mut self.component {
                    c.set_real(vr, value)?;
                }
                self.inputs[i] = value;
                self.inputs_set |= 1 << i;
                Ok(())
            }
            Some(Var::Param(i)) if PARAMETERS[i].ty == ParamType::Real => {
                self.parameter_settable(i)?;
                if !value.is_finite() {
                    return Err(Fail::from(format!(
                        "parameter `{}` = {value}: allowed a finite number",
                        PARAMETERS[i].name
                    )));
                }
                in_range(PARAMETERS[i].name, "parameter", value)?;
                self.params[i] = Some(ParamValue::Real(value));
                self.component = None;
                Ok(())
            }
            Some(Var::Output(VarType::Real)) | Some(Var::Time) => Err(Fail::from(format!(
                "`{}` (value reference {vr}) is not an input or parameter: it cannot be set",
                name_of(vr)
            ))),
            _ => Err(self.wrong_type(vr, "Real / Float64")),
        }
    }

    pub(crate) fn get_string(&self, vr: u32) -> Result<String, Fail> {
        match param_of(vr, |t| t == ParamType::String) {
            Some(i) => match self.param_value(i) {
                ParamValue::Str(s) => Ok(s),
                _ => unreachable!("a string parameter"),
            },
            None => Err(self.wrong_type(vr, "String")),
        }
    }

    pub(crate) fn set_string(&mut self, vr: u32, value: Option<String>) -> Result<(), Fail> {
        let Some(i) = param_of(vr, |t| t == ParamType::String) else {
            return Err(self.wrong_type(vr, "String"));
        };
        self.parameter_settable(i)?;
        let Some(value) = value else {
            return Err(Fail::from(format!(
                "parameter `{}`: the value is NULL or not UTF-8",
                PARAMETERS[i].name
            )));
        };
        self.params[i] = Some(ParamValue::Str(value));
        self.component = None;
        Ok(())
    }

    /// FMI 2 `SetRealInputDerivatives` (input interpolation).
    pub(crate) fn set_input_derivative(
        &mut self,
        vr: u32,
        order: i64,
        value: f64,
    ) -> Result<(), Fail> {
        if !matches!(self.classify(vr), Some(Var::Input(_))) {
            return Err(Fail::from(format!(
                "`{}` (value reference {vr}) is not an input",
                name_of(vr)
            )));
        }
        if !(1..=3).contains(&order) {
            return Err(Fail::from(format!(
                "derivative order {order} of `{}`: allowed 1, 2 or 3",
                name_of(vr)
            )));
        }
        if !value.is_finite() {
            return Err(Fail::from(format!(
                "derivative of `{}` = {value}: allowed a finite number",
                name_of(vr)
            )));
        }
        if let Some(c) = &mut self.component {
            c.set_input_derivative(vr, order as u32, value)?;
        } else {
            self.pending_derivatives.push((vr, order as u32, value));
        }
        Ok(())
    }

    /// `GetRealOutputDerivatives` / `fmi3GetOutputDerivatives`.
    pub(crate) fn get_output_derivative(&mut self, vr: u32, order: i64) -> Result<f64, Fail> {
        if self.classify(vr) != Some(Var::Output(VarType::Real)) {
            return Err(Fail::from(format!(
                "`{}` (value reference {vr}) is not an output of type Real / Float64",
                name_of(vr)
            )));
        }
        if order != 1 {
            return Err(Fail::from(format!(
                "derivative order {order} of `{}`: maxOutputDerivativeOrder is 1",
                name_of(vr)
            )));
        }
        Ok(self.component()?.get_output_derivative(vr, 1)?)
    }

    /// Directional derivative of outputs by inputs at the current state.
    pub(crate) fn directional_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
        out: &mut [f64],
    ) -> Result<(), Fail> {
        for &u in unknowns {
            if self.classify(u) != Some(Var::Output(VarType::Real)) {
                return Err(Fail::from(format!(
                    "unknown `{}` (value reference {u}) is not an output of type Real / Float64",
                    name_of(u)
                )));
            }
        }
        for (&k, &s) in knowns.iter().zip(seed) {
            if !matches!(self.classify(k), Some(Var::Input(_))) {
                return Err(Fail::from(format!(
                    "known `{}` (value reference {k}) is not an input",
                    name_of(k)
                )));
            }
            if !s.is_finite() {
                return Err(Fail::from(format!(
                    "seed for `{}` = {s}: not finite",
                    name_of(k)
                )));
            }
        }
        self.component()?
            .directional_derivative(unknowns, knowns, seed, out)?;
        Ok(())
    }
}
