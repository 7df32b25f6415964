//! One FMU instance, shared by the FMI 2 and FMI 3 exports: the state machine, logging,
//! buffered parameters and inputs, the component, and the FMU state with its byte form.
//!
//! State masks follow the Reference FMUs (`src/fmi2Functions.c`, `src/fmi3Functions.c`):
//! a call outside its states logs "Illegal call sequence" and returns Error. After an Error
//! the instance goes to the error state (FMI 2, spec2 `4_2`) or to Terminated (FMI 3,
//! spec3 `2_3`: "If any function called in super state FMUStateSettable returns
//! fmi3Error, the FMU enters state Terminated"); the host may still roll back with
//! `SetFMUstate`, `Reset` or free the instance.

mod state;
mod step;
mod values;
pub(crate) use state::*;
pub(crate) use values::*;

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
        // The component steps only while |t| + h <= `T_MAX`: a start beyond it was
        // accepted here and then every step refused. Half of it leaves room for steps up
        // to T_MAX / 2 (each at least 2.2e-10 |t| long, to be resolved by a double).
        let t_max = 0.5 * crate::component::T_MAX;
        if !(start.is_finite() && start.abs() <= t_max) {
            return Err(Fail::from(format!(
                "startTime = {start:e} s: allowed a finite time in [{:e}, {t_max:e}] s \
                 (steps from t must be at least 2.2e-10 |t| s long)",
                -t_max
            )));
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
        let (mut c, source) = params::component(values, self.resource_scene.as_ref(), scene)?;
        for (i, v) in md::inputs(self.causality).enumerate() {
            // An input never set holds the scene's initial value, as the component
            // starts it (and as the model description's start says).
            if set(i) {
                c.set_real(v.vr, inputs[i]).map_err(|e| e.to_string())?;
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
}
