//! FMI 2.0 co-simulation: the 25 common and 9 co-simulation functions
//! (spec2 `2_1_common_api.adoc`, `4_2_co-simulation_api.adoc`), thin over [`Instance`].
//!
//! - `fmi2DoStep` failure returns `fmi2Error` with the component unchanged: the master may
//!   `fmi2SetFMUstate` back and retry (the FMU state carries the FMI state too).
//! - `fmi2SetRealInputDerivatives` goes to `Component::set_input_derivative`; it acts when
//!   `input_rule` = `derivatives`.
//! - `fmi2CancelStep` and the asynchronous status queries are not supported (no
//!   asynchronous steps): they log and return `fmi2Error`.
#![allow(non_snake_case)]

use super::instance::{
    deserialize, free_state, get_output_derivatives, get_state, get_strings, get_values, guard,
    no_panic, serialize, serialized_size, set_debug_logging, set_state, set_values, slice,
    slice_mut, str_arg, Fail, Fmi2Logger, Instance, Logger, Status, ANY, ERROR, INIT, INSTANTIATED,
    STEP, TERMINATED,
};
use std::ffi::{c_char, c_void};
use std::ptr::null_mut;

/// `fmi2Component`.
pub type Fmi2Component = *mut c_void;
/// `fmi2FMUstate`.
pub type Fmi2FmuState = *mut c_void;

/// `fmi2CallbackFunctions`, copied at instantiation (its pointer is valid only during the
/// call). Every member may be NULL (`canNotUseMemoryManagementFunctions="true"`).
#[repr(C)]
pub struct Fmi2CallbackFunctions {
    /// Printf-like logger.
    pub logger: Option<Fmi2Logger>,
    /// Not used.
    pub allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    /// Not used.
    pub free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    /// Not used (no asynchronous steps).
    pub step_finished: Option<unsafe extern "C" fn(*mut c_void, i32)>,
    /// Passed back to the logger.
    pub component_environment: *mut c_void,
}

const GET: u32 = INIT | STEP | TERMINATED | ERROR;
const SET: u32 = INSTANTIATED | INIT | STEP;
const STATUS: u32 = STEP | TERMINATED;
/// The value-reference and value arguments, as messages name them.
const NAMES: [&str; 2] = ["vr", "value"];

/// `fmi2GetTypesPlatform`.
#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

/// `fmi2GetVersion`.
#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

/// `fmi2SetDebugLogging`.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: Fmi2Component,
    logging_on: i32,
    n_categories: usize,
    categories: *const *const c_char,
) -> Status {
    guard(c, "fmi2SetDebugLogging", ANY, |inst| {
        set_debug_logging(inst, logging_on != 0, n_categories, categories)
    })
}

/// `fmi2Instantiate`: NULL (with a logged reason) for a wrong GUID, Model Exchange, an empty
/// instance name or missing callbacks.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    instance_name: *const c_char,
    fmu_type: i32,
    guid: *const c_char,
    resource_location: *const c_char,
    functions: *const Fmi2CallbackFunctions,
    _visible: i32,
    logging_on: i32,
) -> Fmi2Component {
    no_panic(null_mut(), || {
        if functions.is_null() {
            return null_mut();
        }
        let f = &*functions;
        let logger = Logger::Fmi2(f.logger, f.component_environment);
        let name = str_arg(instance_name).unwrap_or_default();
        let refuse = |msg: String| {
            logger.emit(
                &std::ffi::CString::new(name.replace('\0', " ")).unwrap_or_default(),
                Status::Error,
                &format!("fmi2Instantiate: {msg}"),
            );
            null_mut()
        };
        if name.is_empty() {
            return refuse("instanceName is NULL or empty".into());
        }
        if fmu_type != 1 {
            return refuse(format!(
                "fmuType = {fmu_type}: raceway is a co-simulation FMU (fmi2CoSimulation = 1)"
            ));
        }
        let causality = match super::instance::check_guid(str_arg(guid).as_deref()) {
            Ok(c) => c,
            Err(msg) => return refuse(msg),
        };
        let dir = str_arg(resource_location).and_then(|u| super::instance::uri_to_path(&u));
        Instance::new(2, causality, &name, logger, logging_on != 0, dir.as_deref()).into_raw()
    })
}

/// `fmi2FreeInstance` (NULL is ignored).
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: Fmi2Component) {
    no_panic((), || Instance::free(c))
}

/// `fmi2SetupExperiment`.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: Fmi2Component,
    tolerance_defined: i32,
    tolerance: f64,
    start_time: f64,
    stop_time_defined: i32,
    stop_time: f64,
) -> Status {
    guard(c, "fmi2SetupExperiment", INSTANTIATED, |inst| {
        inst.setup(
            (tolerance_defined != 0).then_some(tolerance),
            start_time,
            (stop_time_defined != 0).then_some(stop_time),
        )
    })
}

/// `fmi2EnterInitializationMode`.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: Fmi2Component) -> Status {
    guard(c, "fmi2EnterInitializationMode", INSTANTIATED, |inst| {
        inst.mode = INIT;
        Ok(Status::Ok)
    })
}

/// `fmi2ExitInitializationMode`: builds the component (a bad scene fails here).
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: Fmi2Component) -> Status {
    guard(c, "fmi2ExitInitializationMode", INIT, |inst| {
        let s = inst.exit_initialization()?;
        inst.mode = STEP;
        Ok(s)
    })
}

/// `fmi2Terminate`.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2Terminate(c: Fmi2Component) -> Status {
    guard(c, "fmi2Terminate", STEP, |inst| {
        inst.mode = TERMINATED;
        Ok(Status::Ok)
    })
}

/// `fmi2Reset`.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: Fmi2Component) -> Status {
    guard(c, "fmi2Reset", ANY, |inst| {
        inst.reset();
        Ok(Status::Ok)
    })
}

/// `$get` and `$set` of one type (`$t` in C): `$get` reads each value with `$read`, `$set`
/// writes each with `$write` (both give a `Result`); `$gdoc`, `$sdoc`: what they cover.
macro_rules! get_set {
    ($get:ident, $gdoc:literal, $set:ident, $sdoc:literal, $t:ty,
     |$i:ident, $r:ident| $read:expr, |$j:ident, $w:ident, $x:ident| $write:expr) => {
        #[doc = concat!("`", stringify!($get), "`", $gdoc, ".")]
        ///
        /// # Safety
        /// FMI 2 calling convention.
        #[no_mangle]
        pub unsafe extern "C" fn $get(
            c: Fmi2Component,
            vr: *const u32,
            nvr: usize,
            value: *mut $t,
        ) -> Status {
            guard(c, stringify!($get), GET, |$i| {
                get_values(vr, value, nvr, NAMES, |$r| $read)
            })
        }

        #[doc = concat!("`", stringify!($set), "`", $sdoc, ".")]
        ///
        /// # Safety
        /// FMI 2 calling convention.
        #[no_mangle]
        pub unsafe extern "C" fn $set(
            c: Fmi2Component,
            vr: *const u32,
            nvr: usize,
            value: *const $t,
        ) -> Status {
            guard(c, stringify!($set), SET, |$j| {
                set_values(vr, value, nvr, NAMES, |$w, $x| $write)
            })
        }
    };
}

get_set!(
    fmi2GetReal,
    "",
    fmi2SetReal,
    "",
    f64,
    |inst, r| inst.get_real(r),
    |inst, r, x| inst.set_real(r, x)
);
// counts and enumeration items both fit in an i32
get_set!(
    fmi2GetInteger,
    ": the Integer outputs (counts) and the Enumeration parameters",
    fmi2SetInteger,
    ": the Enumeration parameters",
    i32,
    |inst, r| Ok(inst.get_integer(r, "Integer")? as i32),
    |inst, r, x| inst.set_integer(r, x as i64, "Integer")
);
get_set!(
    fmi2GetBoolean,
    ": the Boolean parameters",
    fmi2SetBoolean,
    ": the Boolean parameters",
    i32,
    |inst, r| Ok(inst.get_boolean(r)? as i32),
    |inst, r, x| inst.set_boolean(r, x != 0)
);

/// `fmi2GetString`: the returned strings stay valid until the next `fmi2GetString`.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetString(
    c: Fmi2Component,
    vr: *const u32,
    nvr: usize,
    value: *mut *const c_char,
) -> Status {
    guard(c, "fmi2GetString", GET, |inst| {
        get_strings(inst, vr, value, nvr, NAMES)
    })
}

/// `fmi2SetString` (the string parameters; copied).
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetString(
    c: Fmi2Component,
    vr: *const u32,
    nvr: usize,
    value: *const *const c_char,
) -> Status {
    guard(c, "fmi2SetString", SET, |inst| {
        set_values(vr, value, nvr, NAMES, |r, p| inst.set_string(r, str_arg(p)))
    })
}

/// `fmi2GetFMUstate`: a new state, or `*state` overwritten when it is not NULL.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(c: Fmi2Component, state: *mut Fmi2FmuState) -> Status {
    guard(c, "fmi2GetFMUstate", ANY, |inst| get_state(inst, state))
}

/// `fmi2SetFMUstate` (also from the error state: rollback after a failed step).
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: Fmi2Component, state: Fmi2FmuState) -> Status {
    guard(c, "fmi2SetFMUstate", ANY, |inst| set_state(inst, state))
}

/// `fmi2FreeFMUstate` (NULL is ignored).
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(c: Fmi2Component, state: *mut Fmi2FmuState) -> Status {
    guard(c, "fmi2FreeFMUstate", ANY, |_| free_state(state))
}

/// `fmi2SerializedFMUstateSize`.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: Fmi2Component,
    state: Fmi2FmuState,
    size: *mut usize,
) -> Status {
    guard(c, "fmi2SerializedFMUstateSize", ANY, |_| {
        serialized_size(state, size)
    })
}

/// `fmi2SerializeFMUstate`: `size` must be what `fmi2SerializedFMUstateSize` gave.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: Fmi2Component,
    state: Fmi2FmuState,
    bytes: *mut c_char,
    size: usize,
) -> Status {
    guard(c, "fmi2SerializeFMUstate", ANY, |_| {
        serialize(state, bytes as *mut u8, size)
    })
}

/// `fmi2DeSerializeFMUstate`: checks magic, format, GUID and sizes.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: Fmi2Component,
    bytes: *const c_char,
    size: usize,
    state: *mut Fmi2FmuState,
) -> Status {
    guard(c, "fmi2DeSerializeFMUstate", ANY, |inst| {
        deserialize(inst, bytes as *const u8, size, state)
    })
}

/// `fmi2GetDirectionalDerivative`: outputs by inputs (the bearing's `-K`, `-C`).
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: Fmi2Component,
    v_unknown: *const u32,
    n_unknown: usize,
    v_known: *const u32,
    n_known: usize,
    dv_known: *const f64,
    dv_unknown: *mut f64,
) -> Status {
    guard(c, "fmi2GetDirectionalDerivative", GET, |inst| {
        let u = slice(v_unknown, n_unknown, "vUnknown_ref")?;
        let k = slice(v_known, n_known, "vKnown_ref")?;
        let seed = slice(dv_known, n_known, "dvKnown")?;
        let out = slice_mut(dv_unknown, n_unknown, "dvUnknown")?;
        inst.directional_derivative(u, k, seed, out)?;
        Ok(Status::Ok)
    })
}

/// `fmi2SetRealInputDerivatives` (`canInterpolateInputs`; used with
/// `input_rule` = `derivatives`).
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: Fmi2Component,
    vr: *const u32,
    nvr: usize,
    order: *const i32,
    value: *const f64,
) -> Status {
    guard(c, "fmi2SetRealInputDerivatives", SET, |inst| {
        let vr = slice(vr, nvr, "vr")?;
        let order = slice(order, nvr, "order")?;
        let value = slice(value, nvr, "value")?;
        for i in 0..nvr {
            inst.set_input_derivative(vr[i], order[i] as i64, value[i])?;
        }
        Ok(Status::Ok)
    })
}

/// `fmi2GetRealOutputDerivatives` (order 1).
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: Fmi2Component,
    vr: *const u32,
    nvr: usize,
    order: *const i32,
    value: *mut f64,
) -> Status {
    guard(
        c,
        "fmi2GetRealOutputDerivatives",
        STEP | TERMINATED | ERROR,
        |inst| get_output_derivatives(inst, vr, order, value, nvr, ["vr", "order", "value"]),
    )
}

/// `fmi2DoStep`: failure gives `fmi2Error` with the component unchanged.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(
    c: Fmi2Component,
    t: f64,
    h: f64,
    _no_set_fmu_state_prior: i32,
) -> Status {
    guard(c, "fmi2DoStep", STEP, |inst| {
        inst.do_step(t, h).map_err(|(_, f)| f)
    })
}

/// `fmi2CancelStep`: no asynchronous steps.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: Fmi2Component) -> Status {
    guard(c, "fmi2CancelStep", STEP, |_| {
        Err(Fail::from(
            "not supported: raceway steps synchronously (canRunAsynchronuously = false)"
                .to_string(),
        ))
    })
}

fn status_kind(kind: i32) -> &'static str {
    match kind {
        0 => "fmi2DoStepStatus",
        1 => "fmi2PendingStatus",
        2 => "fmi2LastSuccessfulTime",
        3 => "fmi2Terminated",
        _ => "an unknown fmi2StatusKind",
    }
}

/// `fmi2GetStatus`: `fmi2DoStepStatus` is always `fmi2OK` (no asynchronous steps).
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(c: Fmi2Component, kind: i32, value: *mut i32) -> Status {
    guard(c, "fmi2GetStatus", STATUS, |_| {
        if kind != 0 {
            return Err(Fail::from(format!(
                "{} is not a Status kind",
                status_kind(kind)
            )));
        }
        slice_mut(value, 1, "value")?[0] = Status::Ok as i32;
        Ok(Status::Ok)
    })
}

/// `fmi2GetRealStatus`: `fmi2LastSuccessfulTime`.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(c: Fmi2Component, kind: i32, value: *mut f64) -> Status {
    guard(c, "fmi2GetRealStatus", STATUS, |inst| {
        if kind != 2 {
            return Err(Fail::from(format!(
                "{} is not a Real status kind",
                status_kind(kind)
            )));
        }
        slice_mut(value, 1, "value")?[0] = inst.time;
        Ok(Status::Ok)
    })
}

/// `fmi2GetIntegerStatus`: no Integer status.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: Fmi2Component,
    kind: i32,
    _value: *mut i32,
) -> Status {
    guard(c, "fmi2GetIntegerStatus", STATUS, |_| {
        Err(Fail::from(format!(
            "{} is not an Integer status kind",
            status_kind(kind)
        )))
    })
}

/// `fmi2GetBooleanStatus`: `fmi2Terminated` is always false.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: Fmi2Component,
    kind: i32,
    value: *mut i32,
) -> Status {
    guard(c, "fmi2GetBooleanStatus", STATUS, |_| {
        if kind != 3 {
            return Err(Fail::from(format!(
                "{} is not a Boolean status kind",
                status_kind(kind)
            )));
        }
        slice_mut(value, 1, "value")?[0] = 0;
        Ok(Status::Ok)
    })
}

/// `fmi2GetStringStatus`: no asynchronous steps, so no pending status.
///
/// # Safety
/// FMI 2 calling convention.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: Fmi2Component,
    kind: i32,
    _value: *mut *const c_char,
) -> Status {
    guard(c, "fmi2GetStringStatus", STATUS, |_| {
        Err(Fail::from(format!(
            "{} is not supported: raceway steps synchronously",
            status_kind(kind)
        )))
    })
}
