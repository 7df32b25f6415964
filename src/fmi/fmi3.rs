//! FMI 3.0 co-simulation: all 75 functions of `fmi3Functions.h` (v3.0.2), thin over
//! [`Instance`]. The model-exchange, scheduled-execution, clock, configuration, adjoint and
//! per-element-dependency functions are stubs that log and return `fmi3Error`
//! (spec3 `2_5_fmu_distribution.adoc`: all functions must be present).
//!
//! - `fmi3DoStep`: a failed integration returns `fmi3Discard` with the state as before the
//!   call and `lastSuccessfulTime` = the current time (spec3 `4_2`); a wrong call (bad `h`,
//!   time jump) returns `fmi3Error`.
//! - `hasEventMode="false"`, but a host passing `eventModeUsed = true` gets trivial Event
//!   Mode functions (`fmi3EnterStepMode`, `fmi3UpdateDiscreteStates`).
#![allow(non_snake_case)]

use super::instance::{
    deserialize, free_state, get_output_derivatives, get_state, get_strings, get_values, guard,
    no_panic, serialize, serialized_size, set_debug_logging, set_state, set_values, slice,
    slice_mut, str_arg, Fail, Fmi3Logger, Instance, Logger, Status, ANY, EVENT, INIT, INSTANTIATED,
    STEP, TERMINATED,
};
use std::ffi::{c_char, c_void, CString};
use std::path::PathBuf;
use std::ptr::null_mut;

/// `fmi3Instance`.
pub type Fmi3Instance = *mut c_void;
/// `fmi3FMUState`.
pub type Fmi3FmuState = *mut c_void;
/// `fmi3IntermediateUpdateCallback` (not used: `providesIntermediateUpdate="false"`).
pub type Fmi3IntermediateUpdate =
    Option<unsafe extern "C" fn(*mut c_void, f64, bool, bool, bool, bool, *mut bool, *mut f64)>;
/// `fmi3ClockUpdateCallback` (scheduled execution; not supported).
pub type Fmi3ClockUpdate = Option<unsafe extern "C" fn(*mut c_void)>;
/// `fmi3LockPreemptionCallback` / `fmi3UnlockPreemptionCallback`.
pub type Fmi3Preemption = Option<unsafe extern "C" fn()>;

const GET: u32 = INIT | EVENT | STEP | TERMINATED;
const SET: u32 = INSTANTIATED | INIT | EVENT | STEP;
const SETTABLE: u32 = INSTANTIATED | INIT | EVENT | STEP | TERMINATED;
/// The value-reference and value arguments, as messages name them.
const NAMES: [&str; 2] = ["valueReferences", "values"];

/// `fmi3GetVersion`.
#[no_mangle]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    c"3.0".as_ptr()
}

/// `fmi3SetDebugLogging`.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetDebugLogging(
    instance: Fmi3Instance,
    logging_on: bool,
    n_categories: usize,
    categories: *const *const c_char,
) -> Status {
    guard(instance, "fmi3SetDebugLogging", ANY, |inst| {
        set_debug_logging(inst, logging_on, n_categories, categories)
    })
}

unsafe fn refuse(
    log: Option<Fmi3Logger>,
    env: *mut c_void,
    name: *const c_char,
    func: &str,
    msg: &str,
) -> Fmi3Instance {
    let name = str_arg(name).unwrap_or_default();
    Logger::Fmi3(log, env).emit(
        &CString::new(name.replace('\0', " ")).unwrap_or_default(),
        Status::Error,
        &format!("{func}: {msg}"),
    );
    null_mut()
}

/// `fmi3InstantiateModelExchange`: not supported (NULL, logged).
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateModelExchange(
    instance_name: *const c_char,
    _token: *const c_char,
    _resource_path: *const c_char,
    _visible: bool,
    _logging_on: bool,
    instance_environment: *mut c_void,
    log_message: Option<Fmi3Logger>,
) -> Fmi3Instance {
    no_panic(null_mut(), || {
        refuse(
            log_message,
            instance_environment,
            instance_name,
            "fmi3InstantiateModelExchange",
            "raceway is a co-simulation FMU (no Model Exchange interface)",
        )
    })
}

/// `fmi3InstantiateCoSimulation`: NULL (with a logged reason) for a wrong token or an empty
/// instance name. `resourcePath` may be NULL.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
    instance_name: *const c_char,
    instantiation_token: *const c_char,
    resource_path: *const c_char,
    _visible: bool,
    logging_on: bool,
    event_mode_used: bool,
    _early_return_allowed: bool,
    _required_intermediate_variables: *const u32,
    _n_required_intermediate_variables: usize,
    instance_environment: *mut c_void,
    log_message: Option<Fmi3Logger>,
    _intermediate_update: Fmi3IntermediateUpdate,
) -> Fmi3Instance {
    no_panic(null_mut(), || {
        let func = "fmi3InstantiateCoSimulation";
        let name = str_arg(instance_name).unwrap_or_default();
        if name.is_empty() {
            return refuse(
                log_message,
                instance_environment,
                instance_name,
                func,
                "instanceName is NULL or empty",
            );
        }
        let causality = match super::instance::check_guid(str_arg(instantiation_token).as_deref()) {
            Ok(c) => c,
            Err(msg) => {
                return refuse(log_message, instance_environment, instance_name, func, &msg)
            }
        };
        let dir = str_arg(resource_path).map(PathBuf::from);
        let mut inst = Instance::new(
            3,
            causality,
            &name,
            Logger::Fmi3(log_message, instance_environment),
            logging_on,
            dir.as_deref(),
        );
        inst.event_mode_used = event_mode_used;
        inst.into_raw()
    })
}

/// `fmi3InstantiateScheduledExecution`: not supported (NULL, logged).
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
    instance_name: *const c_char,
    _token: *const c_char,
    _resource_path: *const c_char,
    _visible: bool,
    _logging_on: bool,
    instance_environment: *mut c_void,
    log_message: Option<Fmi3Logger>,
    _clock_update: Fmi3ClockUpdate,
    _lock_preemption: Fmi3Preemption,
    _unlock_preemption: Fmi3Preemption,
) -> Fmi3Instance {
    no_panic(null_mut(), || {
        refuse(
            log_message,
            instance_environment,
            instance_name,
            "fmi3InstantiateScheduledExecution",
            "raceway is a co-simulation FMU (no Scheduled Execution interface)",
        )
    })
}

/// `fmi3FreeInstance` (NULL is ignored).
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3FreeInstance(instance: Fmi3Instance) {
    no_panic((), || Instance::free(instance))
}

/// `fmi3EnterInitializationMode`.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterInitializationMode(
    instance: Fmi3Instance,
    tolerance_defined: bool,
    tolerance: f64,
    start_time: f64,
    stop_time_defined: bool,
    stop_time: f64,
) -> Status {
    guard(
        instance,
        "fmi3EnterInitializationMode",
        INSTANTIATED,
        |inst| {
            let s = inst.setup(
                tolerance_defined.then_some(tolerance),
                start_time,
                stop_time_defined.then_some(stop_time),
            )?;
            inst.mode = INIT;
            Ok(s)
        },
    )
}

/// `fmi3ExitInitializationMode`: builds the component; Step Mode (or Event Mode when the
/// host asked for it).
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3ExitInitializationMode(instance: Fmi3Instance) -> Status {
    guard(instance, "fmi3ExitInitializationMode", INIT, |inst| {
        let s = inst.exit_initialization()?;
        inst.mode = if inst.event_mode_used { EVENT } else { STEP };
        Ok(s)
    })
}

/// `fmi3EnterEventMode`: only when the host instantiated with `eventModeUsed`.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterEventMode(instance: Fmi3Instance) -> Status {
    guard(instance, "fmi3EnterEventMode", STEP, |inst| {
        if !inst.event_mode_used {
            return Err(Fail::from(
                "Illegal call sequence: the instance was created with eventModeUsed = false"
                    .to_string(),
            ));
        }
        inst.mode = EVENT;
        Ok(Status::Ok)
    })
}

/// `fmi3Terminate`.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3Terminate(instance: Fmi3Instance) -> Status {
    guard(instance, "fmi3Terminate", STEP | EVENT, |inst| {
        inst.mode = TERMINATED;
        Ok(Status::Ok)
    })
}

/// `fmi3Reset`.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3Reset(instance: Fmi3Instance) -> Status {
    guard(instance, "fmi3Reset", ANY, |inst| {
        inst.reset();
        Ok(Status::Ok)
    })
}

fn count(nvr: usize, n_values: usize) -> Result<(), Fail> {
    if nvr != n_values {
        return Err(Fail::from(format!(
            "nValues = {n_values} but {nvr} value references (all raceway variables are scalars)"
        )));
    }
    Ok(())
}

/// `fmi3GetFloat64`.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetFloat64(
    instance: Fmi3Instance,
    vrs: *const u32,
    nvr: usize,
    values: *mut f64,
    n_values: usize,
) -> Status {
    guard(instance, "fmi3GetFloat64", GET, |inst| {
        count(nvr, n_values)?;
        get_values(vrs, values, nvr, NAMES, |r| inst.get_real(r))
    })
}

/// `fmi3SetFloat64`.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetFloat64(
    instance: Fmi3Instance,
    vrs: *const u32,
    nvr: usize,
    values: *const f64,
    n_values: usize,
) -> Status {
    guard(instance, "fmi3SetFloat64", SET, |inst| {
        count(nvr, n_values)?;
        set_values(vrs, values, nvr, NAMES, |r, x| inst.set_real(r, x))
    })
}

/// `fmi3GetString`: the returned strings stay valid until the next `fmi3GetString`.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetString(
    instance: Fmi3Instance,
    vrs: *const u32,
    nvr: usize,
    values: *mut *const c_char,
    n_values: usize,
) -> Status {
    guard(instance, "fmi3GetString", GET, |inst| {
        count(nvr, n_values)?;
        get_strings(inst, vrs, values, nvr, NAMES)
    })
}

/// `fmi3SetString` (the string parameters; copied).
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetString(
    instance: Fmi3Instance,
    vrs: *const u32,
    nvr: usize,
    values: *const *const c_char,
    n_values: usize,
) -> Status {
    guard(instance, "fmi3SetString", SET, |inst| {
        count(nvr, n_values)?;
        set_values(vrs, values, nvr, NAMES, |r, p| {
            inst.set_string(r, str_arg(p))
        })
    })
}

fn no_such(kind: &str, vr: &[u32]) -> Result<Status, Fail> {
    match vr.first() {
        None => Ok(Status::Ok),
        Some(r) => Err(Fail::from(format!(
            "no {kind} variable with value reference {r} (raceway has Float64, Int32, \
             Int64 (enumerations), Boolean and String variables only)"
        ))),
    }
}

/// A getter or setter of variables raceway does not have (`$kind`): zero value references
/// is OK, any value reference is an error. `$arg`s: the arguments after `nvr` (unused).
macro_rules! no_such_variables {
    ($name:ident, $mask:ident, $kind:literal, $doc:expr, ($($arg:ident: $t:ty),*)) => {
        #[doc = $doc]
        ///
        /// # Safety
        /// FMI 3 calling convention.
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            instance: Fmi3Instance,
            vrs: *const u32,
            nvr: usize,
            $($arg: $t),*
        ) -> Status {
            $(let _ = $arg;)*
            guard(instance, stringify!($name), $mask, |_| {
                no_such($kind, slice(vrs, nvr, "valueReferences")?)
            })
        }
    };
}

/// Getters and setters of types raceway has no variables of.
macro_rules! no_variables {
    ($get:ident, $set:ident, $t:ty, $kind:literal) => {
        no_such_variables!($get, GET, $kind,
            concat!("`", stringify!($get), "`: raceway has no ", $kind, " variables."),
            (values: *mut $t, n_values: usize));
        no_such_variables!($set, SET, $kind,
            concat!("`", stringify!($set), "`: raceway has no ", $kind, " variables."),
            (values: *const $t, n_values: usize));
    };
}

no_variables!(fmi3GetFloat32, fmi3SetFloat32, f32, "Float32");
no_variables!(fmi3GetInt8, fmi3SetInt8, i8, "Int8");
no_variables!(fmi3GetUInt8, fmi3SetUInt8, u8, "UInt8");
no_variables!(fmi3GetInt16, fmi3SetInt16, i16, "Int16");
no_variables!(fmi3GetUInt16, fmi3SetUInt16, u16, "UInt16");
/// Getters and setters of the types raceway has variables of besides Float64 and String:
/// `$get` reads each value with `$read`, `$set` writes each with `$write` (both give a
/// `Result`).
macro_rules! typed_variables {
    ($get:ident, $set:ident, $t:ty, $kind:literal, $doc:literal,
     |$i:ident, $r:ident| $read:expr, |$j:ident, $w:ident, $x:ident| $write:expr) => {
        #[doc = concat!("`", stringify!($get), "`: ", $doc, ".")]
        ///
        /// # Safety
        /// FMI 3 calling convention.
        #[no_mangle]
        pub unsafe extern "C" fn $get(
            instance: Fmi3Instance,
            vrs: *const u32,
            nvr: usize,
            values: *mut $t,
            n_values: usize,
        ) -> Status {
            guard(instance, stringify!($get), GET, |$i| {
                count(nvr, n_values)?;
                get_values(vrs, values, nvr, NAMES, |$r| $read)
            })
        }

        #[doc = concat!("`", stringify!($set), "`: ", $doc, ".")]
        ///
        /// # Safety
        /// FMI 3 calling convention.
        #[no_mangle]
        pub unsafe extern "C" fn $set(
            instance: Fmi3Instance,
            vrs: *const u32,
            nvr: usize,
            values: *const $t,
            n_values: usize,
        ) -> Status {
            guard(instance, stringify!($set), SET, |$j| {
                count(nvr, n_values)?;
                set_values(vrs, values, nvr, NAMES, |$w, $x| $write)
            })
        }
    };
}

typed_variables!(
    fmi3GetInt32,
    fmi3SetInt32,
    i32,
    "Int32",
    "the Int32 outputs (counts)",
    |inst, r| inst.get_int32(r),
    |inst, r, _x| Err(inst.wrong_type(r, "Int32"))
);
typed_variables!(
    fmi3GetInt64,
    fmi3SetInt64,
    i64,
    "Int64",
    "the Enumeration parameters",
    |inst, r| inst.get_enumeration(r),
    |inst, r, x| inst.set_integer(r, x, "Int64")
);
typed_variables!(
    fmi3GetBoolean,
    fmi3SetBoolean,
    bool,
    "Boolean",
    "the Boolean parameters",
    |inst, r| inst.get_boolean(r),
    |inst, r, x| inst.set_boolean(r, x)
);
no_variables!(fmi3GetUInt32, fmi3SetUInt32, u32, "UInt32");
no_variables!(fmi3GetUInt64, fmi3SetUInt64, u64, "UInt64");

no_such_variables!(fmi3GetBinary, GET, "Binary",
    "`fmi3GetBinary`: raceway has no Binary variables.",
    (value_sizes: *mut usize, values: *mut *const u8, n_values: usize));
no_such_variables!(fmi3SetBinary, SET, "Binary",
    "`fmi3SetBinary`: raceway has no Binary variables.",
    (value_sizes: *const usize, values: *const *const u8, n_values: usize));
no_such_variables!(fmi3GetClock, GET, "Clock", "`fmi3GetClock`: raceway has no clocks.",
    (values: *mut bool));
no_such_variables!(fmi3SetClock, SET, "Clock", "`fmi3SetClock`: raceway has no clocks.",
    (values: *const bool));

/// Functions of capabilities raceway does not have: log and return `fmi3Error`.
macro_rules! unsupported {
    ($name:ident ( $($arg:ident : $t:ty),* ) => $why:literal) => {
        #[doc = concat!("`", stringify!($name), "`: not supported (", $why, "); logs and returns `fmi3Error`.")]
        ///
        /// # Safety
        /// FMI 3 calling convention.
        #[no_mangle]
        pub unsafe extern "C" fn $name(instance: Fmi3Instance $(, $arg: $t)*) -> Status {
            $(let _ = $arg;)*
            guard(instance, stringify!($name), ANY, |_| {
                Err(Fail::from(concat!("not supported: ", $why).to_string()))
            })
        }
    };
}

unsupported!(fmi3GetNumberOfVariableDependencies(vr: u32, n: *mut usize)
    => "providesPerElementDependencies = false; the dependencies are in modelDescription.xml");
unsupported!(fmi3GetVariableDependencies(dependent: u32, e_dep: *mut usize, independents: *mut u32,
    e_ind: *mut usize, kinds: *mut i32, n: usize)
    => "providesPerElementDependencies = false; the dependencies are in modelDescription.xml");
unsupported!(fmi3GetAdjointDerivative(unknowns: *const u32, n_unknowns: usize, knowns: *const u32,
    n_knowns: usize, seed: *const f64, n_seed: usize, sensitivity: *mut f64, n_sensitivity: usize)
    => "providesAdjointDerivatives = false; use fmi3GetDirectionalDerivative");
unsupported!(fmi3EnterConfigurationMode() => "raceway has no structural parameters");
unsupported!(fmi3ExitConfigurationMode() => "raceway has no structural parameters");
unsupported!(fmi3GetIntervalDecimal(vrs: *const u32, nvr: usize, intervals: *mut f64, q: *mut i32)
    => "raceway has no clocks");
unsupported!(fmi3GetIntervalFraction(vrs: *const u32, nvr: usize, counters: *mut u64,
    resolutions: *mut u64, q: *mut i32) => "raceway has no clocks");
unsupported!(fmi3GetShiftDecimal(vrs: *const u32, nvr: usize, shifts: *mut f64)
    => "raceway has no clocks");
unsupported!(fmi3GetShiftFraction(vrs: *const u32, nvr: usize, counters: *mut u64,
    resolutions: *mut u64) => "raceway has no clocks");
unsupported!(fmi3SetIntervalDecimal(vrs: *const u32, nvr: usize, intervals: *const f64)
    => "raceway has no clocks");
unsupported!(fmi3SetIntervalFraction(vrs: *const u32, nvr: usize, counters: *const u64,
    resolutions: *const u64) => "raceway has no clocks");
unsupported!(fmi3SetShiftDecimal(vrs: *const u32, nvr: usize, shifts: *const f64)
    => "raceway has no clocks");
unsupported!(fmi3SetShiftFraction(vrs: *const u32, nvr: usize, counters: *const u64,
    resolutions: *const u64) => "raceway has no clocks");
unsupported!(fmi3EnterContinuousTimeMode() => "Model Exchange only");
unsupported!(fmi3CompletedIntegratorStep(no_set_prior: bool, enter_event_mode: *mut bool,
    terminate: *mut bool) => "Model Exchange only");
unsupported!(fmi3SetTime(time: f64) => "Model Exchange only");
unsupported!(fmi3SetContinuousStates(x: *const f64, nx: usize) => "Model Exchange only");
unsupported!(fmi3GetContinuousStateDerivatives(dx: *mut f64, nx: usize) => "Model Exchange only");
unsupported!(fmi3GetEventIndicators(z: *mut f64, nz: usize) => "Model Exchange only");
unsupported!(fmi3GetContinuousStates(x: *mut f64, nx: usize) => "Model Exchange only");
unsupported!(fmi3GetNominalsOfContinuousStates(x: *mut f64, nx: usize) => "Model Exchange only");
unsupported!(fmi3GetNumberOfEventIndicators(n: *mut usize) => "Model Exchange only");
unsupported!(fmi3GetNumberOfContinuousStates(n: *mut usize) => "Model Exchange only");
unsupported!(fmi3ActivateModelPartition(clock: u32, t: f64) => "Scheduled Execution only");

/// `fmi3GetFMUState`: a new state, or `*state` overwritten when it is not NULL.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetFMUState(
    instance: Fmi3Instance,
    state: *mut Fmi3FmuState,
) -> Status {
    guard(instance, "fmi3GetFMUState", SETTABLE, |inst| {
        get_state(inst, state)
    })
}

/// `fmi3SetFMUState` (also from Terminated after an error: rollback).
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3SetFMUState(instance: Fmi3Instance, state: Fmi3FmuState) -> Status {
    guard(instance, "fmi3SetFMUState", SETTABLE, |inst| {
        set_state(inst, state)
    })
}

/// `fmi3FreeFMUState` (NULL is ignored).
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3FreeFMUState(
    instance: Fmi3Instance,
    state: *mut Fmi3FmuState,
) -> Status {
    guard(instance, "fmi3FreeFMUState", ANY, |_| free_state(state))
}

/// `fmi3SerializedFMUStateSize`.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3SerializedFMUStateSize(
    instance: Fmi3Instance,
    state: Fmi3FmuState,
    size: *mut usize,
) -> Status {
    guard(instance, "fmi3SerializedFMUStateSize", ANY, |_| {
        serialized_size(state, size)
    })
}

/// `fmi3SerializeFMUState`: `size` must be what `fmi3SerializedFMUStateSize` gave.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3SerializeFMUState(
    instance: Fmi3Instance,
    state: Fmi3FmuState,
    bytes: *mut u8,
    size: usize,
) -> Status {
    guard(instance, "fmi3SerializeFMUState", ANY, |_| {
        serialize(state, bytes, size)
    })
}

/// `fmi3DeserializeFMUState`: checks magic, format, token and sizes.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3DeserializeFMUState(
    instance: Fmi3Instance,
    bytes: *const u8,
    size: usize,
    state: *mut Fmi3FmuState,
) -> Status {
    guard(instance, "fmi3DeserializeFMUState", ANY, |inst| {
        deserialize(inst, bytes, size, state)
    })
}

/// `fmi3GetDirectionalDerivative`: outputs by inputs (the bearing's `-K`, `-C`).
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetDirectionalDerivative(
    instance: Fmi3Instance,
    unknowns: *const u32,
    n_unknowns: usize,
    knowns: *const u32,
    n_knowns: usize,
    seed: *const f64,
    n_seed: usize,
    sensitivity: *mut f64,
    n_sensitivity: usize,
) -> Status {
    guard(instance, "fmi3GetDirectionalDerivative", GET, |inst| {
        if n_seed != n_knowns || n_sensitivity != n_unknowns {
            return Err(Fail::from(format!(
                "nSeed = {n_seed}, nSensitivity = {n_sensitivity}: must equal nKnowns = \
                 {n_knowns} and nUnknowns = {n_unknowns} (scalar variables)"
            )));
        }
        let u = slice(unknowns, n_unknowns, "unknowns")?;
        let k = slice(knowns, n_knowns, "knowns")?;
        let s = slice(seed, n_seed, "seed")?;
        let out = slice_mut(sensitivity, n_sensitivity, "sensitivity")?;
        inst.directional_derivative(u, k, s, out)?;
        Ok(Status::Ok)
    })
}

/// `fmi3EvaluateDiscreteStates`: nothing to evaluate (no discrete states).
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3EvaluateDiscreteStates(instance: Fmi3Instance) -> Status {
    guard(instance, "fmi3EvaluateDiscreteStates", EVENT, |_| {
        Ok(Status::Ok)
    })
}

unsafe fn put<T>(p: *mut T, v: T) {
    if !p.is_null() {
        *p = v;
    }
}

/// `fmi3UpdateDiscreteStates`: no events, nothing changes.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3UpdateDiscreteStates(
    instance: Fmi3Instance,
    discrete_states_need_update: *mut bool,
    terminate_simulation: *mut bool,
    nominals_changed: *mut bool,
    values_changed: *mut bool,
    next_event_time_defined: *mut bool,
    next_event_time: *mut f64,
) -> Status {
    guard(instance, "fmi3UpdateDiscreteStates", EVENT, |_| {
        put(discrete_states_need_update, false);
        put(terminate_simulation, false);
        put(nominals_changed, false);
        put(values_changed, false);
        put(next_event_time_defined, false);
        put(next_event_time, 0.0);
        Ok(Status::Ok)
    })
}

/// `fmi3EnterStepMode`.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3EnterStepMode(instance: Fmi3Instance) -> Status {
    guard(instance, "fmi3EnterStepMode", EVENT, |inst| {
        inst.mode = STEP;
        Ok(Status::Ok)
    })
}

/// `fmi3GetOutputDerivatives` (order 1).
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3GetOutputDerivatives(
    instance: Fmi3Instance,
    vrs: *const u32,
    nvr: usize,
    orders: *const i32,
    values: *mut f64,
    n_values: usize,
) -> Status {
    guard(
        instance,
        "fmi3GetOutputDerivatives",
        STEP | TERMINATED,
        |inst| {
            count(nvr, n_values)?;
            let names = ["valueReferences", "orders", "values"];
            get_output_derivatives(inst, vrs, orders, values, nvr, names)
        },
    )
}

/// `fmi3DoStep`: a failed integration is `fmi3Discard` (state as before the call,
/// `lastSuccessfulTime` = the current time); a wrong call is `fmi3Error`.
///
/// # Safety
/// FMI 3 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi3DoStep(
    instance: Fmi3Instance,
    t: f64,
    h: f64,
    _no_set_fmu_state_prior: bool,
    event_handling_needed: *mut bool,
    terminate_simulation: *mut bool,
    early_return: *mut bool,
    last_successful_time: *mut f64,
) -> Status {
    guard(instance, "fmi3DoStep", STEP, |inst| {
        put(event_handling_needed, false);
        put(terminate_simulation, false);
        put(early_return, false);
        let r = inst.do_step(t, h);
        put(last_successful_time, inst.time);
        match r {
            Ok(s) => Ok(s),
            Err((true, f)) => Err(Fail {
                status: Status::Discard,
                msg: format!(
                    "{} (step discarded; the state is as before the call)",
                    f.msg
                ),
            }),
            Err((false, f)) => Err(f),
        }
    })
}
