//! One FMU instance, shared by the FMI 2 and FMI 3 exports: the state machine, logging,
//! buffered parameters and inputs, the component, and the FMU state with its byte form.
//!
//! State masks follow the Reference FMUs (`src/fmi2Functions.c`, `src/fmi3Functions.c`):
//! a call outside its states logs "Illegal call sequence" and returns Error. After an Error
//! the instance goes to the error state (FMI 2, spec2 `4_2`) or to Terminated (FMI 3,
//! spec3 `2_3`: "If any function called in super state FMUStateSettable returns
//! fmi3Error, the FMU enters state Terminated"); the host may still roll back with
//! `SetFMUstate`, `Reset` or free the instance.

use super::model_description::{self as md, VR_TIME};
use super::params::{self, ParamValue, ParamValues};
use crate::component::state::ByteReader;
use crate::component::variables::{self, Causality, ParamType, VarType, PARAMETERS};
use crate::component::{Component, State};
use crate::ffi::handles::{Lease, Refusal, Registry};
use crate::ffi::{ArgError, Caught};
use std::ffi::{c_char, c_void, CStr, CString};
use std::path::{Path, PathBuf};

/// `fmi2Status` / `fmi3Status` (the same values; `fmi2Pending` is never returned).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    /// All well.
    Ok = 0,
    /// Done, but something should be looked at (logged).
    Warning = 1,
    /// FMI 3 `DoStep`: the step was not done, the state is as before the call.
    Discard = 2,
    /// The call failed (logged); the instance is in the error / terminated state.
    Error = 3,
    /// Not used by raceway (no error corrupts other instances).
    Fatal = 4,
}

// State bits.
pub(crate) const INSTANTIATED: u32 = 1 << 0;
pub(crate) const INIT: u32 = 1 << 1;
/// FMI 2 stepComplete, FMI 3 Step Mode.
pub(crate) const STEP: u32 = 1 << 2;
pub(crate) const EVENT: u32 = 1 << 3;
pub(crate) const TERMINATED: u32 = 1 << 4;
/// FMI 2 error state.
pub(crate) const ERROR: u32 = 1 << 5;
/// Every state an instance can be in.
pub(crate) const ANY: u32 = INSTANTIATED | INIT | STEP | EVENT | TERMINATED | ERROR;

fn mode_name(mode: u32, version: u8) -> &'static str {
    match mode {
        INSTANTIATED => "Instantiated",
        INIT => "Initialization Mode",
        STEP if version == 2 => "stepComplete",
        STEP => "Step Mode",
        EVENT => "Event Mode",
        TERMINATED => "Terminated",
        ERROR => "Error",
        _ => "unknown",
    }
}

/// The FMI 2 logger (printf-like; always called with `"%s"`).
pub(crate) type Fmi2Logger =
    unsafe extern "C" fn(*mut c_void, *const c_char, i32, *const c_char, *const c_char, ...);
/// The FMI 3 `fmi3LogMessageCallback`.
pub(crate) type Fmi3Logger = unsafe extern "C" fn(*mut c_void, i32, *const c_char, *const c_char);

/// The host's logger, copied at instantiation.
#[derive(Clone, Copy)]
pub(crate) enum Logger {
    Fmi2(Option<Fmi2Logger>, *mut c_void),
    Fmi3(Option<Fmi3Logger>, *mut c_void),
}

use crate::ffi::c_string as cstring;

fn category(status: Status) -> &'static str {
    match status {
        Status::Ok => "logAll",
        Status::Warning => "logStatusWarning",
        Status::Discard => "logStatusDiscard",
        Status::Error => "logStatusError",
        Status::Fatal => "logStatusFatal",
    }
}

impl Logger {
    /// Send one message (no filtering here).
    pub(crate) fn emit(&self, instance_name: &CStr, status: Status, message: &str) {
        let cat = cstring(category(status));
        let msg = cstring(message);
        // SAFETY: the callbacks were given by the host for this purpose; every pointer
        // passed is valid for the duration of the call.
        unsafe {
            match *self {
                Logger::Fmi2(Some(f), env) => f(
                    env,
                    instance_name.as_ptr(),
                    status as i32,
                    cat.as_ptr(),
                    c"%s".as_ptr(),
                    msg.as_ptr(),
                ),
                Logger::Fmi3(Some(f), env) => f(env, status as i32, cat.as_ptr(), msg.as_ptr()),
                _ => {}
            }
        }
    }
}

/// A failed call: status and message (logged by [`guard`]).
#[derive(Debug)]
pub(crate) struct Fail {
    pub status: Status,
    pub msg: String,
}

impl From<String> for Fail {
    fn from(msg: String) -> Fail {
        Fail {
            status: Status::Error,
            msg,
        }
    }
}

impl From<crate::Error> for Fail {
    fn from(e: crate::Error) -> Fail {
        Fail::from(e.to_string())
    }
}

pub(crate) type Outcome = Result<Status, Fail>;

/// What the instance knows of a value reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Var {
    Time,
    /// Input, with its slot in the input buffer.
    Input(usize),
    /// Output, with its type.
    Output(VarType),
    /// Parameter, with its index in `PARAMETERS`.
    Param(usize),
}

/// What value reference `vr` is in the FMU of causality `c`.
pub(crate) fn classify(c: Causality, vr: u32) -> Option<Var> {
    if vr == VR_TIME {
        return Some(Var::Time);
    }
    if let Some(i) = md::inputs(c).position(|v| v.vr == vr) {
        return Some(Var::Input(i));
    }
    if let Some(v) = md::outputs(c).find(|v| v.vr == vr) {
        return Some(Var::Output(v.ty));
    }
    params::index(vr).map(Var::Param)
}

/// Is `vr` a parameter of type `ty` (its index)?
fn param_of(vr: u32, ty: fn(ParamType) -> bool) -> Option<usize> {
    params::index(vr).filter(|&i| ty(PARAMETERS[i].ty))
}

/// Refuse `value` outside the range the model description declares for `name`
/// (`variables::RANGES`), naming the variable, the value and the range.
fn in_range(name: &str, kind: &str, value: f64) -> Result<(), Fail> {
    match crate::component::variables::range(name) {
        Some((lo, hi)) if !(lo..=hi).contains(&value) => Err(Fail::from(format!(
            "{kind} `{name}` = {value}: allowed [{}, {}] (its declared min and max)",
            md::num(lo),
            md::num(hi)
        ))),
        _ => Ok(()),
    }
}

fn name_of(vr: u32) -> String {
    if vr == VR_TIME {
        return "time".into();
    }
    if let Some(i) = params::index(vr) {
        return PARAMETERS[i].name.into();
    }
    variables::by_vr(vr).map_or(format!("#{vr}"), |v| v.name.to_string())
}

const SNAP_TAG: u64 = 0x5241_4345_5741_5953; // "RACEWAYS"

/// Everything that defines an instance's behaviour from now on.
#[derive(Clone)]
pub(crate) struct Snapshot {
    tag: u64,
    causality: Causality,
    mode: u32,
    time: f64,
    start_time: f64,
    stop_time: Option<f64>,
    tolerance: Option<f64>,
    params: ParamValues,
    inputs: Vec<f64>,
    inputs_set: u64,
    pending_derivatives: Vec<(u32, u32, f64)>,
    component: Option<State>,
}

/// One FMU instance (FMI 2 or FMI 3).
pub(crate) struct Instance {
    pub version: u8,
    /// An internal error (a caught panic) happened: every later call but the free is
    /// refused, because the state may be half-updated.
    poisoned: bool,
    /// The variant (the GUID the host instantiated with decides).
    pub causality: Causality,
    pub name: CString,
    pub logger: Logger,
    pub logging_on: bool,
    pub mode: u32,
    /// `resources/scene.toml`: `None` when absent, `Err` when present but unreadable.
    resource_scene: Option<Result<String, String>>,
    params: ParamValues,
    tolerance: Option<f64>,
    pub start_time: f64,
    pub stop_time: Option<f64>,
    /// Current communication time.
    pub time: f64,
    inputs: Vec<f64>,
    inputs_set: u64,
    pending_derivatives: Vec<(u32, u32, f64)>,
    /// Built from `params`/`tolerance` when needed; `None` again when they change.
    component: Option<Component>,
    pub event_mode_used: bool,
    /// Strings returned to the host, valid until the next call that returns strings.
    pub strings: Vec<CString>,
}

/// Percent-decode a `file:` URI (FMI 2 `fmuResourceLocation`) to a path; a string that is
/// not a URI is taken as a path.
pub(crate) fn uri_to_path(uri: &str) -> Option<PathBuf> {
    let rest = if let Some(r) = uri.strip_prefix("file://localhost/") {
        format!("/{r}")
    } else if let Some(r) = uri.strip_prefix("file:///") {
        format!("/{r}")
    } else if let Some(r) = uri.strip_prefix("file://") {
        // a host name other than localhost: a UNC path
        format!("//{r}")
    } else if let Some(r) = uri.strip_prefix("file:") {
        r.to_string()
    } else {
        return Some(PathBuf::from(uri));
    };
    let b = rest.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' && i + 2 < b.len() {
            let hex = std::str::from_utf8(&b[i + 1..i + 3]).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    let mut s = String::from_utf8(out).ok()?;
    // file:///C:/dir -> C:/dir
    let sb = s.as_bytes();
    if sb.len() >= 3 && sb[0] == b'/' && sb[2] == b':' && sb[1].is_ascii_alphabetic() {
        s.remove(0);
    }
    Some(PathBuf::from(s))
}

/// Read `<dir>/scene.toml` if the FMU carries one.
pub(crate) fn read_resource_scene(dir: Option<&Path>) -> Option<Result<String, String>> {
    let file = dir?.join("scene.toml");
    match std::fs::read_to_string(&file) {
        Ok(t) => Some(Ok(t)),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
        Err(e) => Some(Err(format!("cannot read {}: {e}", file.display()))),
    }
}

pub(crate) use crate::ffi::str_arg;

impl From<ArgError> for Fail {
    fn from(e: ArgError) -> Fail {
        Fail::from(e.to_string())
    }
}

/// A slice argument ([`crate::ffi::slice`]); `n == 0` gives an empty slice whatever the
/// pointer.
///
/// # Safety
/// `p` points to `n` values (or is NULL).
pub(crate) unsafe fn slice<'a, T>(p: *const T, n: usize, what: &str) -> Result<&'a [T], Fail> {
    Ok(crate::ffi::slice(p, n, what)?)
}

/// A mutable slice argument; see [`slice`].
///
/// # Safety
/// `p` points to `n` writable values (or is NULL).
pub(crate) unsafe fn slice_mut<'a, T>(
    p: *mut T,
    n: usize,
    what: &str,
) -> Result<&'a mut [T], Fail> {
    Ok(crate::ffi::slice_mut(p, n, what)?)
}

/// Live FMU instances and FMU states: the pointers a host holds are registry handles
/// (`crate::ffi::handles`), never addresses, so a freed or made-up pointer is refused and
/// never dereferenced. Instance handles are `0x300004 + 16 k`, state handles
/// `0x400000 + 16 k + 12`: neither kind ever equals the other or a C ABI handle.
static INSTANCES: Registry<Instance> = Registry::new(0x30_0004);
static STATES: Registry<Snapshot> = Registry::new(0x40_000c);

// SAFETY: the only non-Send members are the host's logger environment pointer and
// callbacks, which FMI lets an instance use from whichever thread calls it; the registry
// lets one call at a time use an instance.
unsafe impl Send for Instance {}

/// Run `body` on the instance behind `ptr` if `mask` allows the current state; log and map
/// failures and panics.
///
/// # Safety
/// `ptr` is NULL or an instance returned by an instantiate function and not yet freed.
pub(crate) unsafe fn guard(
    ptr: *mut c_void,
    func: &str,
    mask: u32,
    body: impl FnOnce(&mut Instance) -> Outcome,
) -> Status {
    no_panic(Status::Error, || {
        // NULL, freed, made-up or busy (another thread inside a call on it): refused
        let Ok(mut lease) = INSTANCES.acquire(ptr as usize) else {
            return Status::Error;
        };
        let inst = lease.get();
        if inst.poisoned {
            inst.log(Status::Error, &format!("{func}: {}", Caught::Poisoned));
            return Status::Error;
        }
        if inst.mode & mask == 0 {
            let msg = format!(
                "{func}: Illegal call sequence: not allowed in state {}",
                mode_name(inst.mode, inst.version)
            );
            inst.fail(Status::Error, &msg);
            return Status::Error;
        }
        let mut poisoned = false;
        match crate::ffi::catch(&mut poisoned, || body(&mut *inst)) {
            Ok(Ok(s)) => s,
            Ok(Err(f)) => {
                inst.fail(f.status, &format!("{func}: {}", f.msg));
                f.status
            }
            Err(caught) => {
                inst.poisoned = poisoned;
                inst.fail(Status::Error, &format!("{func}: {caught}"));
                Status::Error
            }
        }
    })
}

/// Run `f` catching panics; `default` on panic.
pub(crate) fn no_panic<T>(default: T, f: impl FnOnce() -> T) -> T {
    crate::ffi::guarded(default, f)
}

/// The GUID check of both instantiate functions: the variant the GUID names.
pub(crate) fn check_guid(given: Option<&str>) -> Result<Causality, String> {
    let known = || {
        md::VARIANTS
            .map(|c| format!("`{}` ({}-driven)", md::guid(c), md::variant_name(c)))
            .join(" or ")
    };
    match given {
        Some(g) => md::variant_of(g).ok_or_else(|| {
            format!(
                "wrong GUID / instantiationToken `{g}`: this binary is {} (the \
                 modelDescription.xml and the binary do not belong to the same build)",
                known()
            )
        }),
        None => Err(format!(
            "GUID / instantiationToken is NULL: this binary is {}",
            known()
        )),
    }
}

impl Instance {
    pub(crate) fn new(
        version: u8,
        causality: Causality,
        name: &str,
        logger: Logger,
        logging_on: bool,
        resource_dir: Option<&Path>,
    ) -> Instance {
        let inst = Instance {
            version,
            poisoned: false,
            causality,
            name: cstring(name),
            logger,
            logging_on,
            mode: INSTANTIATED,
            resource_scene: read_resource_scene(resource_dir),
            params: params::unset(),
            tolerance: None,
            start_time: 0.0,
            stop_time: None,
            time: 0.0,
            inputs: vec![0.0; md::inputs(causality).count()],
            inputs_set: 0,
            pending_derivatives: Vec::new(),
            component: None,
            event_mode_used: false,
            strings: Vec::new(),
        };
        let res = match (&inst.resource_scene, resource_dir) {
            (Some(_), Some(d)) => format!("scene from {}", d.join("scene.toml").display()),
            (None, Some(d)) => format!("no scene.toml in {}", d.display()),
            _ => "no resource folder".into(),
        };
        inst.debug(&format!(
            "instantiated (FMI {version}.0, {}-driven, {}); {res}",
            md::variant_name(causality),
            md::guid(causality)
        ));
        inst
    }

    /// Into a handle for the host.
    pub(crate) fn into_raw(self) -> *mut c_void {
        INSTANCES.insert(Box::new(self)) as *mut c_void
    }

    /// Free an instance given back by the host (NULL, unknown and busy handles are left
    /// alone).
    pub(crate) fn free(ptr: *mut c_void) {
        if let Ok(inst) = INSTANCES.remove(ptr as usize) {
            drop(inst);
        }
    }

    /// Log a message (warnings and errors always; `Ok` only with debug logging on).
    pub(crate) fn log(&self, status: Status, msg: &str) {
        if status > Status::Ok || self.logging_on {
            self.logger.emit(&self.name, status, msg);
        }
    }

    pub(crate) fn debug(&self, msg: &str) {
        self.log(Status::Ok, msg);
    }

    /// Log a failure and move to the error state (Error/Fatal).
    pub(crate) fn fail(&mut self, status: Status, msg: &str) {
        self.log(status, msg);
        if status >= Status::Error {
            self.mode = if self.version == 2 { ERROR } else { TERMINATED };
        }
    }

    /// `SetDebugLogging`: categories must be known.
    pub(crate) fn set_debug_logging(&mut self, on: bool, categories: &[String]) -> Outcome {
        for c in categories {
            if !md::LOG_CATEGORIES.iter().any(|(n, _)| n == c) {
                return Err(Fail::from(format!(
                    "unknown log category `{c}`; known: {}",
                    md::LOG_CATEGORIES.map(|(n, _)| n).join(", ")
                )));
            }
        }
        self.logging_on = on;
        Ok(Status::Ok)
    }

    /// `Reset`: back to Instantiated with start values.
    pub(crate) fn reset(&mut self) {
        self.mode = INSTANTIATED;
        self.params = params::unset();
        self.tolerance = None;
        self.start_time = 0.0;
        self.stop_time = None;
        self.time = 0.0;
        self.inputs.iter_mut().for_each(|x| *x = 0.0);
        self.inputs_set = 0;
        self.pending_derivatives.clear();
        self.component = None;
        self.strings.clear();
    }

    /// `SetupExperiment` / the arguments of `fmi3EnterInitializationMode`.
    pub(crate) fn setup(
        &mut self,
        tolerance: Option<f64>,
        start: f64,
        stop: Option<f64>,
    ) -> Outcome {
        if !start.is_finite() {
            return Err(Fail::from(format!("startTime = {start}: must be finite")));
        }
        // A tolerance outside the solver's range is ignored when the component is built
        // (`params::scene`), but a non-finite one would be kept in the FMU state, whose
        // bytes then could not be restored (they must hold finite numbers only).
        if let Some(t) = tolerance.filter(|t| !t.is_finite()) {
            return Err(Fail::from(format!(
                "tolerance = {t}: must be a finite number (or toleranceDefined false)"
            )));
        }
        if let Some(s) = stop {
            if !(s.is_finite() && s >= start) {
                return Err(Fail::from(format!(
                    "stopTime = {s}: must be finite and >= startTime = {start}"
                )));
            }
        }
        if self.tolerance != tolerance {
            self.component = None;
        }
        self.tolerance = tolerance;
        self.start_time = start;
        self.time = start;
        self.stop_time = stop;
        Ok(Status::Ok)
    }

    fn build(
        &self,
        values: &ParamValues,
        tolerance: Option<f64>,
        inputs: &[f64],
        inputs_set: u64,
        derivatives: &[(u32, u32, f64)],
    ) -> Result<Component, String> {
        let set = |i: usize| inputs_set & (1 << i) != 0;
        // Load-driven, the inputs set so far are the scene's initial values: the ring's
        // static start solves for them when the component is built.
        let initial: Vec<(&str, f64)> = match self.causality {
            Causality::Motion => Vec::new(),
            Causality::Load => md::inputs(self.causality)
                .enumerate()
                .filter(|&(i, _)| set(i))
                .map(|(i, v)| (v.name, inputs[i]))
                .collect(),
        };
        let scene = params::scene(
            values,
            tolerance,
            self.resource_scene.as_ref(),
            self.causality,
            &initial,
        )?;
        let (mut c, source) = params::component(values, scene)?;
        for (i, v) in md::inputs(self.causality).enumerate() {
            if set(i) {
                c.set_real(v.vr, inputs[i]).map_err(|e| e.to_string())?;
            } else if !c.scene().inputs.initial.contains_key(v.name) {
                c.set_real(v.vr, 0.0).map_err(|e| e.to_string())?;
            }
        }
        for &(vr, order, value) in derivatives {
            c.set_input_derivative(vr, order, value)
                .map_err(|e| e.to_string())?;
        }
        self.debug(&format!(
            "component built from {source} (level {}, {}-driven, bearing {}, clearance {:e} m)",
            c.scene().model.level.name(),
            md::variant_name(self.causality),
            c.bearing().name,
            c.bearing().pd
        ));
        Ok(c)
    }

    /// The component, built from the current parameters if needed.
    pub(crate) fn component(&mut self) -> Result<&mut Component, Fail> {
        if self.component.is_none() {
            let c = self.build(
                &self.params,
                self.tolerance,
                &self.inputs,
                self.inputs_set,
                &self.pending_derivatives,
            )?;
            self.component = Some(c);
        }
        Ok(self.component.as_mut().expect("just built"))
    }

    /// `ExitInitializationMode`: build the component (a bad scene or parameter fails here).
    pub(crate) fn exit_initialization(&mut self) -> Outcome {
        self.component()?;
        self.pending_derivatives.clear();
        Ok(Status::Ok)
    }

    fn classify(&self, vr: u32) -> Option<Var> {
        classify(self.causality, vr)
    }

    /// A parameter's value: the host's, else its start value.
    fn param_value(&self, i: usize) -> ParamValue {
        self.params[i].clone().unwrap_or_else(|| params::start(i))
    }

    pub(crate) fn get_real(&mut self, vr: u32) -> Result<f64, Fail> {
        match self.classify(vr) {
            Some(Var::Time) => Ok(self.time),
            Some(Var::Input(i)) => match &mut self.component {
                Some(c) => Ok(c.get_real(vr)?),
                None => Ok(self.inputs[i]),
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

    fn parameter_settable(&self, i: usize) -> Result<(), Fail> {
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

    /// `DoStep` from `t` over `h`. On failure the state is unchanged; the flag says whether
    /// it was numerical (a failed integration: FMI 3 Discard) rather than an error.
    pub(crate) fn do_step(&mut self, t: f64, h: f64) -> Result<Status, (bool, Fail)> {
        let err = |m: String| (false, Fail::from(m));
        if !t.is_finite() {
            return Err(err(format!("communication point t = {t}: must be finite")));
        }
        if !(h.is_finite() && h > 0.0) {
            return Err(err(format!(
                "communication step size h = {h}: must be finite and > 0"
            )));
        }
        let tc = self.time;
        let mismatch = (t - tc).abs();
        // Relative tolerance on the communication point (docs/physics.md §C4 #9): a mismatch within
        // 1e-6 of the step (or 1e-12 of the time) re-syncs to the FMU's time and lands on
        // t + h; rounding noise (a few ulps) passes silently, more is a warning.
        let tol = (1e-6 * h).max(1e-12 * tc.abs());
        let mut status = Status::Ok;
        let (t0, h0) = if mismatch == 0.0 {
            (t, h)
        } else if mismatch <= tol && t + h > tc {
            if mismatch > 8.0 * f64::EPSILON * tc.abs().max(t.abs()) {
                self.log(
                    Status::Warning,
                    &format!(
                        "fmiDoStep: communication point t = {t} differs from the FMU's time \
                         {tc} by {mismatch:e} s (within the tolerance {tol:e} s): stepping \
                         from {tc} to t + h"
                    ),
                );
                status = Status::Warning;
            }
            (tc, (t + h) - tc)
        } else {
            return Err(err(format!(
                "communication point t = {t} but the FMU is at {tc} (tolerance {tol:e} s); \
                 time must not jump or run backwards (use SetFMUstate to go back)"
            )));
        };
        if let Some(stop) = self.stop_time {
            if t0 + h0 > stop + 1e-9 * h0.max(stop.abs() * 1e-3) {
                return Err(err(format!(
                    "t + h = {} is beyond stopTime = {stop}",
                    t0 + h0
                )));
            }
        }
        let c = self.component().map_err(|f| (false, f))?;
        match c.do_step(t0, h0) {
            Ok(()) => {
                self.time = c.time();
                Ok(status)
            }
            Err(e) => {
                let numerical = matches!(
                    e,
                    crate::Error::StepFailed { .. }
                        | crate::Error::NotConverged { .. }
                        | crate::Error::Budget { .. }
                );
                Err((numerical, Fail::from(e)))
            }
        }
    }

    pub(crate) fn snapshot(&self) -> Snapshot {
        Snapshot {
            tag: SNAP_TAG,
            causality: self.causality,
            mode: self.mode,
            time: self.time,
            start_time: self.start_time,
            stop_time: self.stop_time,
            tolerance: self.tolerance,
            params: self.params.clone(),
            inputs: self.inputs.clone(),
            inputs_set: self.inputs_set,
            pending_derivatives: self.pending_derivatives.clone(),
            component: self.component.as_ref().map(Component::get_state),
        }
    }

    /// Restore a snapshot (of this instance, another instance or another process). The
    /// instance is unchanged if this fails.
    pub(crate) fn restore(&mut self, s: &Snapshot) -> Result<(), Fail> {
        if s.tag != SNAP_TAG {
            return Err(Fail::from("not an FMU state of this FMU".to_string()));
        }
        if s.causality != self.causality {
            return Err(Fail::from(format!(
                "an FMU state of the {}-driven FMU; this instance is {}-driven",
                md::variant_name(s.causality),
                md::variant_name(self.causality)
            )));
        }
        match &s.component {
            Some(state) => {
                let same_build = self.component.is_some()
                    && self.params == s.params
                    && self.tolerance == s.tolerance;
                if same_build {
                    self.component.as_mut().expect("checked").set_state(state)?;
                } else {
                    let mut c = self.build(
                        &s.params,
                        s.tolerance,
                        &s.inputs,
                        s.inputs_set,
                        &s.pending_derivatives,
                    )?;
                    c.set_state(state)?;
                    self.component = Some(c);
                }
            }
            None => self.component = None,
        }
        self.mode = s.mode;
        self.time = s.time;
        self.start_time = s.start_time;
        self.stop_time = s.stop_time;
        self.tolerance = s.tolerance;
        self.params = s.params.clone();
        self.inputs.clone_from(&s.inputs);
        self.inputs_set = s.inputs_set;
        self.pending_derivatives.clone_from(&s.pending_derivatives);
        Ok(())
    }

    /// The FMU state behind a host handle, for this call.
    pub(crate) fn snapshot_lease<'a>(p: *mut c_void) -> Result<Lease<'a, Snapshot>, Fail> {
        if p.is_null() {
            return Err(Fail::from("the FMU state is NULL".to_string()));
        }
        STATES.acquire(p as usize).map_err(|r| {
            Fail::from(match r {
                Refusal::Unknown => {
                    "not a live FMU state of this FMU (freed already, or never created)".to_string()
                }
                Refusal::Busy => "the FMU state is in use by another call right now".to_string(),
            })
        })
    }
}

const STATE_MAGIC: &[u8; 4] = b"RWFU";
/// 2: a checksum (FNV-1a, as `component::state`) over everything before it, at the end.
/// 3: Boolean and Enumeration parameters (tags 3, 4); the GUID names the variant.
const STATE_FORMAT: u32 = 3;

impl Snapshot {
    /// Into a handle for the host.
    pub(crate) fn into_raw(self) -> *mut c_void {
        STATES.insert(Box::new(self)) as *mut c_void
    }

    /// Free a state given back by the host (NULL, unknown and busy handles are left alone).
    pub(crate) fn free(p: *mut c_void) {
        if let Ok(s) = STATES.remove(p as usize) {
            drop(s);
        }
    }

    /// Byte form: magic `RWFU`, format `u32`, the GUID, then every field little-endian; the
    /// component state as its own versioned bytes (`component::State::to_bytes`).
    pub(crate) fn to_bytes(&self) -> Vec<u8> {
        let mut b = Vec::new();
        let bytes = |b: &mut Vec<u8>, x: &[u8]| {
            b.extend_from_slice(&(x.len() as u64).to_le_bytes());
            b.extend_from_slice(x);
        };
        let opt = |b: &mut Vec<u8>, x: Option<f64>| {
            b.push(x.is_some() as u8);
            b.extend_from_slice(&x.unwrap_or(0.0).to_le_bytes());
        };
        b.extend_from_slice(STATE_MAGIC);
        b.extend_from_slice(&STATE_FORMAT.to_le_bytes());
        bytes(&mut b, md::guid(self.causality).as_bytes());
        b.extend_from_slice(&self.mode.to_le_bytes());
        b.extend_from_slice(&self.time.to_le_bytes());
        b.extend_from_slice(&self.start_time.to_le_bytes());
        opt(&mut b, self.stop_time);
        opt(&mut b, self.tolerance);
        b.extend_from_slice(&(self.params.len() as u64).to_le_bytes());
        for p in &self.params {
            match p {
                None => b.push(0),
                Some(ParamValue::Real(x)) => {
                    b.push(1);
                    b.extend_from_slice(&x.to_le_bytes());
                }
                Some(ParamValue::Str(s)) => {
                    b.push(2);
                    bytes(&mut b, s.as_bytes());
                }
                Some(ParamValue::Bool(x)) => {
                    b.push(3);
                    b.push(*x as u8);
                }
                Some(ParamValue::Int(k)) => {
                    b.push(4);
                    b.extend_from_slice(&k.to_le_bytes());
                }
            }
        }
        b.extend_from_slice(&(self.inputs.len() as u64).to_le_bytes());
        for x in &self.inputs {
            b.extend_from_slice(&x.to_le_bytes());
        }
        b.extend_from_slice(&self.inputs_set.to_le_bytes());
        b.extend_from_slice(&(self.pending_derivatives.len() as u64).to_le_bytes());
        for (vr, o, x) in &self.pending_derivatives {
            b.extend_from_slice(&vr.to_le_bytes());
            b.extend_from_slice(&o.to_le_bytes());
            b.extend_from_slice(&x.to_le_bytes());
        }
        match &self.component {
            None => b.push(0),
            Some(s) => {
                b.push(1);
                bytes(&mut b, &s.to_bytes());
            }
        }
        let sum = crate::component::fingerprint(&b);
        b.extend_from_slice(&sum.to_le_bytes());
        b
    }

    /// Read the byte form of an FMU state of the variant of causality `causality`.
    pub(crate) fn from_bytes(b: &[u8], causality: Causality) -> Result<Snapshot, String> {
        let own = md::guid(causality);
        let mut r = Reader {
            b,
            at: 0,
            fail: refused,
        };
        if r.take(4)? != STATE_MAGIC {
            return Err("serialised FMU state: not a raceway FMU state (bad magic)".into());
        }
        let ver = r.u32()?;
        if ver != STATE_FORMAT {
            return Err(format!(
                "serialised FMU state: format {ver}, this binary reads {STATE_FORMAT}"
            ));
        }
        let guid = r.bytes()?;
        if guid != own.as_bytes() {
            let theirs = String::from_utf8_lossy(guid);
            let which = md::variant_of(&theirs).map_or("of another build".to_string(), |c| {
                format!("the {}-driven FMU", md::variant_name(c))
            });
            return Err(format!(
                "serialised FMU state: written by FMU `{theirs}` ({which}), this instance is \
                 `{own}` ({}-driven)",
                md::variant_name(causality)
            ));
        }
        // Damaged bytes are refused before any other field is read (the magic, the
        // format and the GUID name foreign bytes first).
        if b.len() < r.at + 8 {
            return Err(format!(
                "serialised FMU state: truncated at byte {}",
                b.len()
            ));
        }
        let (b, sum) = b.split_at(b.len() - 8);
        if crate::component::fingerprint(b).to_le_bytes() != sum {
            return Err(
                "serialised FMU state: checksum mismatch: the bytes are damaged or truncated"
                    .into(),
            );
        }
        let mut r = Reader {
            b,
            at: r.at,
            fail: refused,
        };
        let mode = r.u32()?;
        if mode.count_ones() != 1 || mode & ANY == 0 {
            return Err(format!("serialised FMU state: bad mode {mode}"));
        }
        let time = r.f64()?;
        let start_time = r.f64()?;
        let stop_time = r.opt()?;
        let tolerance = r.opt()?;
        let n = r.u64()? as usize;
        if n != PARAMETERS.len() {
            return Err(format!(
                "serialised FMU state: {n} parameters, this binary has {}",
                PARAMETERS.len()
            ));
        }
        let mut params = Vec::with_capacity(n);
        for _ in 0..n {
            params.push(match r.take(1)?[0] {
                0 => None,
                1 => Some(ParamValue::Real(r.f64()?)),
                2 => Some(ParamValue::Str(
                    String::from_utf8(r.bytes()?.to_vec())
                        .map_err(|_| "serialised FMU state: parameter not UTF-8".to_string())?,
                )),
                3 => Some(ParamValue::Bool(match r.take(1)?[0] {
                    0 => false,
                    1 => true,
                    x => return Err(format!("serialised FMU state: bad Boolean {x}")),
                })),
                4 => Some(ParamValue::Int(r.u64()? as i64)),
                k => return Err(format!("serialised FMU state: bad parameter tag {k}")),
            });
        }
        for (p, v) in PARAMETERS.iter().zip(&params) {
            let fits = match (p.ty, v) {
                (_, None) => true,
                (ParamType::Real, Some(ParamValue::Real(_))) => true,
                (ParamType::String, Some(ParamValue::Str(_))) => true,
                (ParamType::Boolean, Some(ParamValue::Bool(_))) => true,
                (ParamType::Enumeration { items, .. }, Some(ParamValue::Int(k))) => {
                    (0..items.len() as i64).contains(k)
                }
                _ => false,
            };
            if !fits {
                return Err(format!(
                    "serialised FMU state: parameter `{}` holds a value of another type or \
                     outside its items",
                    p.name
                ));
            }
        }
        let ni = r.u64()? as usize;
        if ni != md::inputs(causality).count() {
            return Err(format!("serialised FMU state: {ni} inputs"));
        }
        let inputs = (0..ni).map(|_| r.f64()).collect::<Result<Vec<_>, _>>()?;
        let inputs_set = r.u64()?;
        let nd = r.u64()? as usize;
        if nd > b.len() / 16 {
            return Err("serialised FMU state: too many input derivatives".into());
        }
        let mut pending_derivatives = Vec::with_capacity(nd);
        for _ in 0..nd {
            pending_derivatives.push((r.u32()?, r.u32()?, r.f64()?));
        }
        let component = match r.take(1)?[0] {
            0 => None,
            1 => Some(
                State::from_bytes(r.bytes()?).map_err(|e| format!("serialised FMU state: {e}"))?,
            ),
            k => return Err(format!("serialised FMU state: bad component tag {k}")),
        };
        if r.at != b.len() {
            return Err(format!(
                "serialised FMU state: {} trailing bytes",
                b.len() - r.at
            ));
        }
        let reals = params.iter().filter_map(|p| match p {
            Some(ParamValue::Real(x)) => Some(*x),
            _ => None,
        });
        let mut numbers = [time, start_time]
            .into_iter()
            .chain(stop_time)
            .chain(tolerance)
            .chain(reals)
            .chain(inputs.iter().copied())
            .chain(pending_derivatives.iter().map(|p| p.2));
        if let Some(x) = numbers.find(|x| !x.is_finite()) {
            return Err(format!(
                "serialised FMU state: a number is {x}: allowed finite numbers only"
            ));
        }
        Ok(Snapshot {
            tag: SNAP_TAG,
            causality,
            mode,
            time,
            start_time,
            stop_time,
            tolerance,
            params,
            inputs,
            inputs_set,
            pending_derivatives,
            component,
        })
    }
}

/// The FMU state's reads: refusals start `serialised FMU state: `.
type Reader<'a> = ByteReader<'a, String>;

fn refused(msg: String) -> String {
    format!("serialised FMU state: {msg}")
}

impl<'a> Reader<'a> {
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(
            self.take(4)?.try_into().expect("4 bytes"),
        ))
    }
    fn f64(&mut self) -> Result<f64, String> {
        Ok(f64::from_bits(self.u64()?))
    }
    fn opt(&mut self) -> Result<Option<f64>, String> {
        let some = self.take(1)?[0] != 0;
        let x = self.f64()?;
        Ok(some.then_some(x))
    }
    fn bytes(&mut self) -> Result<&'a [u8], String> {
        let n = self.u64()?;
        if n > (self.b.len() - self.at) as u64 {
            return Err("serialised FMU state: length exceeds the data".into());
        }
        self.take(n as usize)
    }
}

// ---------------------------------------------------------------------------------------
// FMU state calls, the same in both versions.

/// `GetFMUstate`: a new state in `*state`, or `*state` overwritten when it is not NULL.
///
/// # Safety
/// `state` is NULL or valid for a read and a write (`*state` is compared with the live
/// FMU states only).
pub(crate) unsafe fn get_state(
    inst: &mut Instance,
    state: *mut *mut c_void,
) -> Result<Status, Fail> {
    if state.is_null() {
        return Err(Fail::from("FMUstate pointer is NULL".to_string()));
    }
    put_state(state, inst.snapshot())
}

/// `snap` into `*state`: a new FMU state when `*state` is NULL, else the one it names
/// overwritten.
///
/// # Safety
/// `state` is valid for a read and a write.
unsafe fn put_state(state: *mut *mut c_void, snap: Snapshot) -> Result<Status, Fail> {
    if (*state).is_null() {
        *state = snap.into_raw();
    } else {
        *Instance::snapshot_lease(*state)?.get() = snap;
    }
    Ok(Status::Ok)
}

/// `SetFMUstate`.
///
/// # Safety
/// None beyond the FMI calling convention (`state` is compared with the live FMU states
/// only).
pub(crate) unsafe fn set_state(inst: &mut Instance, state: *mut c_void) -> Result<Status, Fail> {
    inst.restore(Instance::snapshot_lease(state)?.get())?;
    Ok(Status::Ok)
}

/// `FreeFMUstate`: frees `*state` and sets it NULL (NULL is ignored).
///
/// # Safety
/// `state` is NULL or valid for a read and a write.
pub(crate) unsafe fn free_state(state: *mut *mut c_void) -> Result<Status, Fail> {
    if !state.is_null() && !(*state).is_null() {
        Snapshot::free(*state);
        *state = std::ptr::null_mut();
    }
    Ok(Status::Ok)
}

/// `SerializedFMUstateSize`.
///
/// # Safety
/// `size` is NULL or valid for a write.
pub(crate) unsafe fn serialized_size(state: *mut c_void, size: *mut usize) -> Result<Status, Fail> {
    let n = Instance::snapshot_lease(state)?.get().to_bytes().len();
    slice_mut(size, 1, "size")?[0] = n;
    Ok(Status::Ok)
}

/// `SerializeFMUstate`: `size` must be what `SerializedFMUstateSize` gave.
///
/// # Safety
/// `bytes` is NULL or valid for `size` bytes.
pub(crate) unsafe fn serialize(
    state: *mut c_void,
    bytes: *mut u8,
    size: usize,
) -> Result<Status, Fail> {
    let b = Instance::snapshot_lease(state)?.get().to_bytes();
    if size != b.len() {
        return Err(Fail::from(format!(
            "buffer of {size} bytes, the serialised state has {} (ask SerializedFMUstateSize)",
            b.len()
        )));
    }
    slice_mut(bytes, size, "serializedState")?.copy_from_slice(&b);
    Ok(Status::Ok)
}

/// `DeSerializeFMUstate` of an FMU state of `inst`'s variant.
///
/// # Safety
/// `bytes` is NULL or valid for `size` bytes; `state` as in [`get_state`].
pub(crate) unsafe fn deserialize(
    inst: &Instance,
    bytes: *const u8,
    size: usize,
    state: *mut *mut c_void,
) -> Result<Status, Fail> {
    if state.is_null() {
        return Err(Fail::from("FMUstate pointer is NULL".to_string()));
    }
    let snap = Snapshot::from_bytes(slice(bytes, size, "serializedState")?, inst.causality)?;
    put_state(state, snap)
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
