//! The C ABI over [`crate::component::Component`] (header: `include/raceway.h`, generated
//! from this module by cbindgen; regenerate with `RACEWAY_BLESS=1 cargo test --test
//! capi_header`).
//!
//! Conventions, the same for every function:
//!
//! - Functions return a [`RacewayStatus`]; results go through out-pointers. A refused call
//!   changes nothing (a bulk call is all or nothing, a failed step leaves the state as it
//!   was) and stores a message naming the cause in the instance, read with
//!   [`raceway_last_error`] (valid until the next call on that instance).
//! - Creation errors go to a caller-provided buffer (there is no instance yet).
//! - Handles are numbers from a registry, never addresses, and never issued twice: a
//!   freed, doubly freed or made-up handle is refused with
//!   [`RacewayStatus::InvalidHandle`] (freeing one is ignored), never dereferenced.
//! - Threads: many instances may live in one process and be stepped in parallel, each in
//!   its own thread, with results bit for bit those of a serial run. One instance is used
//!   by one thread at a time: a call on an instance that another thread is inside right
//!   now is refused with [`RacewayStatus::CallOrder`]. The last error is per instance.
//! - The coupling loop (`set_real(s)`, `do_step`, `get_real(s)`, `last_error` after a
//!   successful call) performs no heap allocation.
//! - Every body runs inside `catch_unwind`: a panic never crosses the boundary. After an
//!   internal panic the instance is poisoned (every later call returns
//!   [`RacewayStatus::Panic`]) because its state may be half-updated; free it.
//! - NULL pointers, wrong lengths, unknown value references, non-finite values and calls
//!   out of order are refused with a status and a message.

use crate::component::{variables, Component, State};
use crate::error::Error;
use crate::ffi::handles::{self, Refusal, Registry};
use crate::ffi::{c_string, guarded, panic_text, ArgError, Caught};
use std::ffi::{c_char, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::OnceLock;

mod vr;
pub use vr::*;

/// Result of every call.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RacewayStatus {
    /// Success.
    Ok = 0,
    /// Any other failure (input/output).
    Error = 1,
    /// A value outside its allowed range, an unknown name or value reference, text that
    /// does not parse, a length that does not fit.
    InvalidArgument = 2,
    /// A required pointer was NULL.
    NullPointer = 3,
    /// A call not allowed now (time running backwards, writing an
    /// output, a state of another scene).
    CallOrder = 4,
    /// The internal integration failed; the state is unchanged.
    StepFailed = 5,
    /// A caller buffer is too small.
    BufferTooSmall = 6,
    /// An internal error (a caught panic); the instance is poisoned and must be freed.
    Panic = 7,
    /// A handle that is not a live instance or state of this library (freed already,
    /// never created, or of the other kind).
    InvalidHandle = 8,
}

/// The type of a variable's value (see [`raceway_variable_type`]).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RacewayType {
    /// A real number: [`raceway_get_real`].
    Real = 0,
    /// A count (`int32_t`): [`raceway_get_integer`]; [`raceway_get_real`] gives it too, as
    /// an exact `double`.
    Integer = 1,
}

/// Cost counters of the internal integration (see [`raceway_get_stats`]).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RacewayStats {
    /// Right-hand-side evaluations.
    pub rhs: u64,
    /// Jacobian evaluations.
    pub jacobians: u64,
    /// LU factorisations.
    pub factorizations: u64,
    /// Accepted internal steps.
    pub accepted: u64,
    /// Rejected internal steps.
    pub rejected: u64,
}

/// An opaque bearing instance (from [`raceway_create`], freed by [`raceway_free`]). The
/// pointer is a handle, not an address: never dereference it.
pub struct RacewayComponent {
    _opaque: [u8; 0],
}

/// An opaque copy of an instance's complete state (from [`raceway_state_get`] or
/// [`raceway_state_deserialize`], freed by [`raceway_state_free`]); a handle like
/// [`RacewayComponent`].
pub struct RacewayState {
    _opaque: [u8; 0],
}

/// What an instance handle stands for.
struct Instance {
    component: Component,
    last_error: CString,
    poisoned: bool,
}

/// Live instances and states. Instance handles are `0x100000 + 16 k`, state handles
/// `0x200008 + 16 k`: the two kinds never share a number.
static INSTANCES: Registry<Instance> = Registry::new(0x10_0000);
static STATES: Registry<State> = Registry::new(0x20_0008);

/// The refusal of a handle argument `name`.
fn handle_failure(name: &str, r: Refusal) -> Failure {
    match r {
        Refusal::Unknown => Failure::new(
            RacewayStatus::InvalidHandle,
            format!(
                "`{name}` is not a live handle of this library (freed already, or never created)"
            ),
        ),
        Refusal::Busy => Failure::new(
            RacewayStatus::CallOrder,
            format!("`{name}` is in use by another thread right now (one thread at a time)"),
        ),
    }
}

/// Exclusive use of state handle `s` for this call (NULL refused).
fn state_lease<'a>(
    s: *const RacewayState,
    name: &str,
) -> Result<handles::Lease<'a, State>, Failure> {
    if s.is_null() {
        return Err(Failure::null(name));
    }
    STATES
        .acquire(s as usize)
        .map_err(|r| handle_failure(name, r))
}

/// A refusal: status and message.
struct Failure {
    status: RacewayStatus,
    message: String,
}

impl Failure {
    fn new(status: RacewayStatus, message: impl Into<String>) -> Failure {
        Failure {
            status,
            message: message.into(),
        }
    }
    fn null(arg: &str) -> Failure {
        Failure::new(RacewayStatus::NullPointer, format!("`{arg}` is NULL"))
    }
}

impl From<Error> for Failure {
    fn from(e: Error) -> Failure {
        let status = match &e {
            Error::Invalid { .. } | Error::Unknown { .. } | Error::Parse { .. } => {
                RacewayStatus::InvalidArgument
            }
            Error::CallOrder { .. } => RacewayStatus::CallOrder,
            Error::StepFailed { .. } | Error::NotConverged { .. } | Error::Budget { .. } => {
                RacewayStatus::StepFailed
            }
            Error::Io(_) | Error::Interrupted { .. } => RacewayStatus::Error,
        };
        Failure::new(status, e.to_string())
    }
}

type Outcome = Result<(), Failure>;

/// The failure of value `i` (for value reference `vr`) of a bulk set.
fn bad_value(i: usize, vr: u32, e: Error) -> Failure {
    let f = Failure::from(e);
    Failure::new(f.status, format!("values[{i}] (vr {vr}): {}", f.message))
}

/// The failure of value reference `i` of a bulk get.
fn bad_vr(i: usize, vr: u32, e: Error) -> Failure {
    let f = Failure::from(e);
    Failure::new(f.status, format!("vrs[{i}] = {vr}: {}", f.message))
}

/// Run `f` on the instance behind handle `c`: refuse NULL, unknown, busy and poisoned
/// instances, clear the last error (without allocating when it is clear already), store
/// the new one, catch panics.
fn with_instance(
    c: *const RacewayComponent,
    call: &str,
    f: impl FnOnce(&mut Component) -> Outcome,
) -> RacewayStatus {
    guarded(RacewayStatus::Panic, || {
        if c.is_null() {
            return RacewayStatus::NullPointer;
        }
        let mut lease = match INSTANCES.acquire(c as usize) {
            Ok(l) => l,
            Err(r) => return handle_failure("c", r).status,
        };
        let inst = lease.get();
        if inst.poisoned {
            inst.last_error = c_string(&format!("{call}: {}", Caught::Poisoned));
            return RacewayStatus::Panic;
        }
        if !inst.last_error.is_empty() {
            inst.last_error = CString::default();
        }
        let component = &mut inst.component;
        match crate::ffi::catch(&mut inst.poisoned, || f(component)) {
            Ok(Ok(())) => RacewayStatus::Ok,
            Ok(Err(fail)) => {
                inst.last_error = c_string(&format!("{call}: {}", fail.message));
                fail.status
            }
            Err(caught) => {
                inst.last_error = c_string(&format!("{call}: {caught}"));
                RacewayStatus::Panic
            }
        }
    })
}

impl From<ArgError> for Failure {
    fn from(e: ArgError) -> Failure {
        let status = match e {
            ArgError::Null { .. } => RacewayStatus::NullPointer,
            ArgError::TooLong { .. } => RacewayStatus::InvalidArgument,
        };
        Failure::new(status, e.to_string())
    }
}

/// A slice from a C pointer and a count (NULL allowed when `n == 0`): [`crate::ffi::slice`]
/// with the C statuses.
///
/// # Safety
/// `p` points to `n` valid values (or `n == 0`).
unsafe fn slice<'a, T>(p: *const T, n: usize, name: &str) -> Result<&'a [T], Failure> {
    // SAFETY: promised by the caller.
    Ok(unsafe { crate::ffi::slice(p, n, name) }?)
}

/// A mutable slice from a C pointer and a count; see [`slice`].
///
/// # Safety
/// `p` points to `n` writable values (or `n == 0`).
unsafe fn slice_mut<'a, T>(p: *mut T, n: usize, name: &str) -> Result<&'a mut [T], Failure> {
    // SAFETY: promised by the caller.
    Ok(unsafe { crate::ffi::slice_mut(p, n, name) }?)
}

/// Write through an out-pointer, refusing NULL.
///
/// # Safety
/// `p` is NULL or valid for a write of `T`.
unsafe fn put<T>(p: *mut T, name: &str, value: T) -> Outcome {
    if p.is_null() {
        return Err(Failure::null(name));
    }
    // SAFETY: non-NULL and valid by the caller's promise.
    unsafe { p.write(value) };
    Ok(())
}

/// Copy `msg` into a caller buffer of `len` bytes, truncated at a character boundary and
/// NUL-terminated. Nothing is written when `buf` is NULL or `len` is 0.
///
/// # Safety
/// `buf` is NULL or valid for `len` bytes.
unsafe fn write_message(buf: *mut c_char, len: usize, msg: &str) {
    if buf.is_null() || len == 0 {
        return;
    }
    let mut n = msg.len().min(len - 1);
    while !msg.is_char_boundary(n) {
        n -= 1;
    }
    // SAFETY: `n + 1 <= len` bytes, valid by the caller's promise.
    unsafe {
        std::ptr::copy_nonoverlapping(msg.as_ptr() as *const c_char, buf, n);
        buf.add(n).write(0);
    }
}

/// The variable table as C strings (immutable once built).
struct CVariable {
    vr: u32,
    name: CString,
    unit: CString,
    description: CString,
}

fn c_variables() -> &'static [CVariable] {
    static TABLE: OnceLock<Vec<CVariable>> = OnceLock::new();
    TABLE.get_or_init(|| {
        variables::all()
            .map(|v| CVariable {
                vr: v.vr,
                name: c_string(v.name),
                unit: c_string(v.unit),
                description: c_string(v.description),
            })
            .collect()
    })
}

/// The C constant of a variable name in `include/raceway.h`: `"K.rx.y"` ->
/// `RACEWAY_VR_K_RX_Y` (upper case, dots to underscores). `src/capi/vr.rs` holds one
/// `pub const` per variable under this name, generated from the table.
pub fn c_constant_name(name: &str) -> String {
    format!("RACEWAY_VR_{}", name.to_uppercase().replace('.', "_"))
}

fn c_variable(vr: u32) -> Option<&'static CVariable> {
    c_variables().iter().find(|v| v.vr == vr)
}

// ---------------------------------------------------------------------------------------
// Library

/// The library version, e.g. `"0.1.0"` (static; never freed).
#[no_mangle]
pub extern "C" fn raceway_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr() as *const c_char
}

/// The embedded default scene as TOML text (static; never freed).
#[no_mangle]
pub extern "C" fn raceway_default_scene() -> *const c_char {
    static TEXT: OnceLock<CString> = OnceLock::new();
    guarded(std::ptr::null(), || {
        TEXT.get_or_init(|| c_string(crate::component::scene::DEFAULT_SCENE))
            .as_ptr()
    })
}

// ---------------------------------------------------------------------------------------
// Variable table

/// Number of variables in the table (`RACEWAY_VARIABLE_COUNT`).
#[no_mangle]
pub extern "C" fn raceway_variable_count() -> usize {
    guarded(0, || c_variables().len())
}

/// The value reference of the `index`-th variable (`0 <= index < count`), for walking the
/// table.
///
/// # Safety
/// `vr` is NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn raceway_variable_at(index: usize, vr: *mut u32) -> RacewayStatus {
    guarded(RacewayStatus::Panic, || {
        let Some(v) = c_variables().get(index) else {
            return RacewayStatus::InvalidArgument;
        };
        // SAFETY: promised by the caller.
        match unsafe { put(vr, "vr", v.vr) } {
            Ok(()) => RacewayStatus::Ok,
            Err(f) => f.status,
        }
    })
}

/// The value reference of the variable called `name` (NUL-terminated, e.g.
/// `"force.x"`); `RACEWAY_STATUS_INVALID_ARGUMENT` when there is none.
///
/// # Safety
/// `name` is NULL or a NUL-terminated string; `vr` is NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn raceway_variable_vr(name: *const c_char, vr: *mut u32) -> RacewayStatus {
    guarded(RacewayStatus::Panic, || {
        if name.is_null() || vr.is_null() {
            return RacewayStatus::NullPointer;
        }
        // SAFETY: non-NULL, NUL-terminated by the caller's promise.
        let name = unsafe { CStr::from_ptr(name) };
        match c_variables().iter().find(|v| v.name.as_c_str() == name) {
            Some(v) => {
                // SAFETY: non-NULL, valid by the caller's promise.
                unsafe { vr.write(v.vr) };
                RacewayStatus::Ok
            }
            None => RacewayStatus::InvalidArgument,
        }
    })
}

/// The name of variable `vr` (static), or NULL when `vr` is not in the table.
#[no_mangle]
pub extern "C" fn raceway_variable_name(vr: u32) -> *const c_char {
    guarded(std::ptr::null(), || {
        c_variable(vr).map_or(std::ptr::null(), |v| v.name.as_ptr())
    })
}

/// The SI unit of variable `vr` (static, e.g. `"N/m"`), or NULL when unknown.
#[no_mangle]
pub extern "C" fn raceway_variable_unit(vr: u32) -> *const c_char {
    guarded(std::ptr::null(), || {
        c_variable(vr).map_or(std::ptr::null(), |v| v.unit.as_ptr())
    })
}

/// The one-line description of variable `vr` (static), or NULL when unknown.
#[no_mangle]
pub extern "C" fn raceway_variable_description(vr: u32) -> *const c_char {
    guarded(std::ptr::null(), || {
        c_variable(vr).map_or(std::ptr::null(), |v| v.description.as_ptr())
    })
}

/// The type of variable `vr` into `*ty`; `RACEWAY_STATUS_INVALID_ARGUMENT` when `vr` is
/// not in the table.
///
/// # Safety
/// `ty` is NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn raceway_variable_type(vr: u32, ty: *mut RacewayType) -> RacewayStatus {
    guarded(RacewayStatus::Panic, || {
        let Some(v) = variables::by_vr(vr) else {
            return RacewayStatus::InvalidArgument;
        };
        let t = match v.ty {
            variables::VarType::Real => RacewayType::Real,
            variables::VarType::Integer => RacewayType::Integer,
        };
        // SAFETY: promised by the caller.
        match unsafe { put(ty, "ty", t) } {
            Ok(()) => RacewayStatus::Ok,
            Err(f) => f.status,
        }
    })
}

// ---------------------------------------------------------------------------------------
// Instances

/// Create an instance from scene text (TOML or JSON, NUL-terminated UTF-8). Returns NULL
/// when the scene is refused, with the message (every problem of the scene as `raceway
/// scene --check` gives it: `line:column`, the field, the allowed range, "did you mean")
/// copied into `error` (at most `error_len` bytes including the terminating NUL;
/// `error` may be NULL). Every input starts at the scene's initial value
/// (`[inputs] initial`, absent: 0) and holds it until it is set.
///
/// # Safety
/// `scene` is NULL or NUL-terminated; `error` is NULL or valid for `error_len` bytes.
#[no_mangle]
pub unsafe extern "C" fn raceway_create(
    scene: *const c_char,
    error: *mut c_char,
    error_len: usize,
) -> *mut RacewayComponent {
    let made = catch_unwind(AssertUnwindSafe(|| -> Result<Component, String> {
        if scene.is_null() {
            return Err("raceway_create: `scene` is NULL".into());
        }
        // SAFETY: non-NULL and NUL-terminated by the caller's promise.
        let bytes = unsafe { CStr::from_ptr(scene) }.to_bytes();
        let text = std::str::from_utf8(bytes).map_err(|e| {
            format!(
                "raceway_create: the scene text is not UTF-8 (invalid byte at {})",
                e.valid_up_to()
            )
        })?;
        Component::from_text(text).map_err(|e| {
            let why = crate::component::schema::scene_error_text(text, &e);
            format!("raceway_create: scene: {why}")
        })
    }));
    let message = match made {
        Ok(Ok(component)) => {
            let inst = Box::new(Instance {
                component,
                last_error: CString::default(),
                poisoned: false,
            });
            return INSTANCES.insert(inst) as *mut RacewayComponent;
        }
        Ok(Err(m)) => m,
        Err(p) => format!(
            "raceway_create: internal error (panic: {})",
            panic_text(&*p)
        ),
    };
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: promised by the caller.
        unsafe { write_message(error, error_len, &message) }
    }));
    std::ptr::null_mut()
}

/// Free an instance. NULL, a handle freed before, a handle never created and an instance
/// another thread is inside a call on right now are ignored (nothing is freed).
///
/// # Safety
/// None beyond the C signature: `c` is only compared with the live handles.
#[no_mangle]
pub unsafe extern "C" fn raceway_free(c: *mut RacewayComponent) {
    if c.is_null() {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        if let Ok(inst) = INSTANCES.remove(c as usize) {
            drop(inst)
        }
    }));
}

/// The message of the last refused call on `c` (`""` when the last call succeeded). Valid
/// until the next call on `c`. For NULL or a handle that is not live, a static message
/// saying so.
///
/// # Safety
/// None beyond the C signature: `c` is only compared with the live handles.
#[no_mangle]
pub unsafe extern "C" fn raceway_last_error(c: *const RacewayComponent) -> *const c_char {
    if c.is_null() {
        return c"raceway_last_error: the instance is NULL".as_ptr();
    }
    guarded(c"raceway_last_error: internal error".as_ptr(), || {
        match INSTANCES.acquire(c as usize) {
            // The string lives in the instance until its next call.
            Ok(mut inst) => inst.get().last_error.as_ptr(),
            Err(Refusal::Busy) => {
                c"raceway_last_error: the instance is in use by another thread right now".as_ptr()
            }
            Err(Refusal::Unknown) => {
                c"raceway_last_error: not a live instance (freed already, or never created)"
                    .as_ptr()
            }
        }
    })
}

/// Set one input by value reference. Refused: unknown references, outputs, non-finite
/// values.
///
/// # Safety
/// `c` is NULL or a live instance.
#[no_mangle]
pub unsafe extern "C" fn raceway_set_real(
    c: *mut RacewayComponent,
    vr: u32,
    value: f64,
) -> RacewayStatus {
    with_instance(c, "raceway_set_real", |comp| Ok(comp.set_real(vr, value)?))
}

/// Set `n` inputs: `values[i]` to `vrs[i]`. All or nothing: when one is refused, none is
/// set and the message names its index.
///
/// # Safety
/// `c` is NULL or a live instance; `vrs` and `values` are NULL or hold `n` values.
#[no_mangle]
pub unsafe extern "C" fn raceway_set_reals(
    c: *mut RacewayComponent,
    vrs: *const u32,
    values: *const f64,
    n: usize,
) -> RacewayStatus {
    // SAFETY: promised by the caller.
    unsafe {
        with_instance(c, "raceway_set_reals", |comp| {
            let vrs = slice(vrs, n, "vrs")?;
            let values = slice(values, n, "values")?;
            comp.set_reals(vrs, values)
                .map_err(|(i, e)| bad_value(i, vrs[i], e))
        })
    }
}

/// Set the `order`-th time derivative (1, 2 or 3) of input `vr` (used by scenes with
/// `inputs.rule = "derivatives"`; reset to zero after each step).
///
/// # Safety
/// `c` is NULL or a live instance.
#[no_mangle]
pub unsafe extern "C" fn raceway_set_input_derivative(
    c: *mut RacewayComponent,
    vr: u32,
    order: u32,
    value: f64,
) -> RacewayStatus {
    with_instance(c, "raceway_set_input_derivative", |comp| {
        Ok(comp.set_input_derivative(vr, order, value)?)
    })
}

/// Set the `order`-th derivatives of `n` inputs; all or nothing.
///
/// # Safety
/// `c` is NULL or a live instance; `vrs` and `values` are NULL or hold `n` values.
#[no_mangle]
pub unsafe extern "C" fn raceway_set_input_derivatives(
    c: *mut RacewayComponent,
    vrs: *const u32,
    order: u32,
    values: *const f64,
    n: usize,
) -> RacewayStatus {
    // SAFETY: promised by the caller.
    unsafe {
        with_instance(c, "raceway_set_input_derivatives", |comp| {
            let vrs = slice(vrs, n, "vrs")?;
            let values = slice(values, n, "values")?;
            comp.set_input_derivatives(vrs, order, values)
                .map_err(|(i, e)| bad_value(i, vrs[i], e))
        })
    }
}

/// Advance from `t` (the instance's current time) to `t + h`. Refused: `h <= 0` or not
/// finite, `t` not the current time (time never jumps or runs backwards), inputs never
/// set. A failed step leaves the state unchanged.
///
/// # Safety
/// `c` is NULL or a live instance.
#[no_mangle]
pub unsafe extern "C" fn raceway_do_step(
    c: *mut RacewayComponent,
    t: f64,
    h: f64,
) -> RacewayStatus {
    with_instance(c, "raceway_do_step", |comp| Ok(comp.do_step(t, h)?))
}

/// Get one input or output by value reference into `*value`.
///
/// # Safety
/// `c` is NULL or a live instance; `value` is NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn raceway_get_real(
    c: *mut RacewayComponent,
    vr: u32,
    value: *mut f64,
) -> RacewayStatus {
    // SAFETY: promised by the caller.
    unsafe {
        with_instance(c, "raceway_get_real", |comp| {
            if value.is_null() {
                return Err(Failure::null("value"));
            }
            let v = comp.get_real(vr)?;
            put(value, "value", v)
        })
    }
}

/// Get one Integer output (a count, e.g. `RACEWAY_VR_BALLS_LOADED`) into `*value`.
/// Refused with `RACEWAY_STATUS_INVALID_ARGUMENT` for a variable of another type.
///
/// # Safety
/// `c` is NULL or a live instance; `value` is NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn raceway_get_integer(
    c: *mut RacewayComponent,
    vr: u32,
    value: *mut i32,
) -> RacewayStatus {
    // SAFETY: promised by the caller.
    unsafe {
        with_instance(c, "raceway_get_integer", |comp| {
            if value.is_null() {
                return Err(Failure::null("value"));
            }
            match variables::by_vr(vr) {
                Some(v) if v.ty == variables::VarType::Integer => {}
                _ => return Err(Error::invalid("value reference", vr, "an Integer output").into()),
            }
            let x = comp.get_real(vr)?;
            // counts: exact small integers in the component's f64 outputs
            put(
                value,
                "value",
                x.round().clamp(i32::MIN as f64, i32::MAX as f64) as i32,
            )
        })
    }
}

/// Get `n` inputs or outputs: `values[i]` from `vrs[i]`. All or nothing: `values` is
/// written only when every reference is valid.
///
/// # Safety
/// `c` is NULL or a live instance; `vrs` is NULL or holds `n` values; `values` is NULL or
/// has room for `n`.
#[no_mangle]
pub unsafe extern "C" fn raceway_get_reals(
    c: *mut RacewayComponent,
    vrs: *const u32,
    values: *mut f64,
    n: usize,
) -> RacewayStatus {
    // SAFETY: promised by the caller.
    unsafe {
        with_instance(c, "raceway_get_reals", |comp| {
            let vrs = slice(vrs, n, "vrs")?;
            let out = slice_mut(values, n, "values")?;
            // Every reference checked before `values` is written (all or nothing). With
            // nothing left to compute a read can fail only on an unknown reference (then
            // `get_real` gives its message); otherwise the first read of a stale output, or
            // of a deferred stiffness or damping, computes it and may fail.
            if comp.reads_may_compute() {
                for (i, &vr) in vrs.iter().enumerate() {
                    comp.get_real(vr).map_err(|e| bad_vr(i, vr, e))?;
                }
            } else if let Some(i) = vrs.iter().position(|&vr| variables::by_vr(vr).is_none()) {
                comp.get_real(vrs[i]).map_err(|e| bad_vr(i, vrs[i], e))?;
            }
            for (i, (o, &vr)) in out.iter_mut().zip(vrs).enumerate() {
                *o = comp.get_real(vr).map_err(|e| bad_vr(i, vr, e))?;
            }
            Ok(())
        })
    }
}

/// Get the `order`-th time derivative (only 1 now) of output `vr` at the current time.
///
/// # Safety
/// `c` is NULL or a live instance; `value` is NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn raceway_get_output_derivative(
    c: *mut RacewayComponent,
    vr: u32,
    order: u32,
    value: *mut f64,
) -> RacewayStatus {
    // SAFETY: promised by the caller.
    unsafe {
        with_instance(c, "raceway_get_output_derivative", |comp| {
            if value.is_null() {
                return Err(Failure::null("value"));
            }
            let v = comp.get_output_derivative(vr, order)?;
            put(value, "value", v)
        })
    }
}

/// Directional derivative `out = J seed` of outputs `unknowns` (`n_unknowns`) with
/// respect to inputs `knowns` (`n_knowns`); `seed` holds `n_knowns` values and `out` has
/// room for `n_unknowns`.
///
/// # Safety
/// `c` is NULL or a live instance; the arrays are NULL or hold the stated counts.
#[no_mangle]
pub unsafe extern "C" fn raceway_directional_derivative(
    c: *mut RacewayComponent,
    unknowns: *const u32,
    n_unknowns: usize,
    knowns: *const u32,
    n_knowns: usize,
    seed: *const f64,
    out: *mut f64,
) -> RacewayStatus {
    // SAFETY: promised by the caller.
    unsafe {
        with_instance(c, "raceway_directional_derivative", |comp| {
            let unknowns = slice(unknowns, n_unknowns, "unknowns")?;
            let knowns = slice(knowns, n_knowns, "knowns")?;
            let seed = slice(seed, n_knowns, "seed")?;
            let out = slice_mut(out, n_unknowns, "out")?;
            if let Some(&s) = seed.iter().find(|s| !s.is_finite()) {
                return Err(Error::invalid("seed", s, "finite numbers").into());
            }
            let mut tmp = vec![0.0; n_unknowns];
            comp.directional_derivative(unknowns, knowns, seed, &mut tmp)?;
            out.copy_from_slice(&tmp);
            Ok(())
        })
    }
}

/// The instance's current time, s.
///
/// # Safety
/// `c` is NULL or a live instance; `t` is NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn raceway_get_time(c: *mut RacewayComponent, t: *mut f64) -> RacewayStatus {
    // SAFETY: promised by the caller.
    unsafe { with_instance(c, "raceway_get_time", |comp| put(t, "t", comp.time())) }
}

/// The cost counters since creation.
///
/// # Safety
/// `c` is NULL or a live instance; `stats` is NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn raceway_get_stats(
    c: *mut RacewayComponent,
    stats: *mut RacewayStats,
) -> RacewayStatus {
    // SAFETY: promised by the caller.
    unsafe {
        with_instance(c, "raceway_get_stats", |comp| {
            let s = comp.stats();
            put(
                stats,
                "stats",
                RacewayStats {
                    rhs: s.rhs,
                    jacobians: s.jacobians,
                    factorizations: s.factorizations,
                    accepted: s.accepted,
                    rejected: s.rejected,
                },
            )
        })
    }
}

// ---------------------------------------------------------------------------------------
// State

/// Copy the instance's complete state into `*state`: when `*state` is NULL a new state is
/// made (free it with [`raceway_state_free`]); otherwise `*state` must be a live state
/// and is overwritten in place (no allocation).
///
/// # Safety
/// `c` is any handle; `state` is NULL or valid for a read and a write.
#[no_mangle]
pub unsafe extern "C" fn raceway_state_get(
    c: *mut RacewayComponent,
    state: *mut *mut RacewayState,
) -> RacewayStatus {
    with_instance(c, "raceway_state_get", |comp| {
        if state.is_null() {
            return Err(Failure::null("state"));
        }
        // SAFETY: non-NULL, valid by the caller's promise.
        let existing = unsafe { *state };
        if existing.is_null() {
            let id = STATES.insert(Box::new(comp.get_state()));
            // SAFETY: as above.
            unsafe { *state = id as *mut RacewayState };
        } else {
            state_lease(existing, "*state")?
                .get()
                .clone_from(comp.state());
        }
        Ok(())
    })
}

/// Restore a state taken from this instance (or one built from the same scene); the
/// instance continues bit for bit as from the moment the state was taken. A state of
/// another scene is refused.
///
/// # Safety
/// None beyond the C signature: `c` and `state` are only compared with the live handles.
#[no_mangle]
pub unsafe extern "C" fn raceway_state_set(
    c: *mut RacewayComponent,
    state: *const RacewayState,
) -> RacewayStatus {
    with_instance(c, "raceway_state_set", |comp| {
        Ok(comp.set_state(state_lease(state, "state")?.get())?)
    })
}

/// Free a state. NULL, a handle freed before, one never created and a state in use by
/// another thread right now are ignored.
///
/// # Safety
/// None beyond the C signature: `state` is only compared with the live handles.
#[no_mangle]
pub unsafe extern "C" fn raceway_state_free(state: *mut RacewayState) {
    if state.is_null() {
        return;
    }
    let _ = catch_unwind(AssertUnwindSafe(|| {
        if let Ok(s) = STATES.remove(state as usize) {
            drop(s)
        }
    }));
}

/// The number of bytes [`raceway_state_serialize`] writes for `state`.
///
/// # Safety
/// `c` is any handle (it receives the error message); `state` is any handle; `size` is
/// NULL or valid for a write.
#[no_mangle]
pub unsafe extern "C" fn raceway_state_size(
    c: *mut RacewayComponent,
    state: *const RacewayState,
    size: *mut usize,
) -> RacewayStatus {
    with_instance(c, "raceway_state_size", |_| {
        let n = state_lease(state, "state")?.get().byte_len();
        // SAFETY: promised by the caller.
        unsafe { put(size, "size", n) }
    })
}

/// Serialise `state` into `buffer` (`len` bytes, at least [`raceway_state_size`]). The
/// bytes hold no pointers and carry a format version, the scene's fingerprint and a
/// checksum: they may be stored and restored by another process of the same library
/// version; damaged bytes are refused on reading.
///
/// # Safety
/// `c` and `state` are any handles; `buffer` is NULL or valid for `len` bytes.
#[no_mangle]
pub unsafe extern "C" fn raceway_state_serialize(
    c: *mut RacewayComponent,
    state: *const RacewayState,
    buffer: *mut u8,
    len: usize,
) -> RacewayStatus {
    with_instance(c, "raceway_state_serialize", |_| {
        let mut lease = state_lease(state, "state")?;
        let s = lease.get();
        let need = s.byte_len();
        if len < need {
            return Err(Failure::new(
                RacewayStatus::BufferTooSmall,
                format!("buffer of {len} bytes, the state needs {need}"),
            ));
        }
        // SAFETY: promised by the caller.
        let out = unsafe { slice_mut(buffer, need, "buffer")? };
        s.write_into(out);
        Ok(())
    })
}

/// Read a state from `len` bytes written by [`raceway_state_serialize`] into a new state
/// `*state` (free it with [`raceway_state_free`]; restore it with [`raceway_state_set`]).
/// Refused with a message, before any value is used: truncated or damaged bytes (the
/// checksum), another format version, a state of another scene than `c`'s, a number not
/// finite or outside its range. `*state` is written only on success.
///
/// # Safety
/// `c` is any handle; `buffer` is NULL or valid for `len` bytes; `state` is NULL or valid
/// for a write.
#[no_mangle]
pub unsafe extern "C" fn raceway_state_deserialize(
    c: *mut RacewayComponent,
    buffer: *const u8,
    len: usize,
    state: *mut *mut RacewayState,
) -> RacewayStatus {
    with_instance(c, "raceway_state_deserialize", |comp| {
        if state.is_null() {
            return Err(Failure::null("state"));
        }
        // SAFETY: promised by the caller.
        let bytes = unsafe { slice(buffer, len, "buffer")? };
        let s = State::from_bytes(bytes)?;
        // Check it fits this instance now rather than at `raceway_state_set`.
        comp.check_state(&s)?;
        let id = STATES.insert(Box::new(s));
        // SAFETY: non-NULL, valid by the caller's promise.
        unsafe { *state = id as *mut RacewayState };
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_are_truncated_at_character_boundaries_and_terminated() {
        let mut buf = [0x55 as c_char; 6];
        // "µ" is two bytes: 5 bytes of room would split it after "abcd".
        unsafe { write_message(buf.as_mut_ptr(), 6, "abcdµef") };
        let got = unsafe { CStr::from_ptr(buf.as_ptr()) }.to_str().unwrap();
        assert_eq!(got, "abcd");
        let mut one = [0x55 as c_char; 1];
        unsafe { write_message(one.as_mut_ptr(), 1, "abc") };
        assert_eq!(one[0], 0);
    }

    #[test]
    fn a_panic_poisons_only_its_instance_and_is_reported() {
        let text = std::ffi::CString::new(crate::component::scene::DEFAULT_SCENE).unwrap();
        let c = unsafe { raceway_create(text.as_ptr(), std::ptr::null_mut(), 0) };
        assert!(!c.is_null());
        let status = with_instance(c, "test", |_| panic!("boom"));
        assert_eq!(status, RacewayStatus::Panic);
        let msg = unsafe { CStr::from_ptr(raceway_last_error(c)) };
        assert!(msg.to_str().unwrap().contains("boom"), "{msg:?}");
        let mut t = 0.0;
        assert_eq!(unsafe { raceway_get_time(c, &mut t) }, RacewayStatus::Panic);
        let msg = unsafe { CStr::from_ptr(raceway_last_error(c)) };
        assert!(msg.to_str().unwrap().contains("poisoned"), "{msg:?}");
        unsafe { raceway_free(c) };
    }

    #[test]
    fn constant_names_are_unique_c_identifiers() {
        let names: Vec<String> = variables::all().map(|v| c_constant_name(v.name)).collect();
        for (i, n) in names.iter().enumerate() {
            assert!(
                n.chars()
                    .all(|ch| ch.is_ascii_uppercase() || ch.is_ascii_digit() || ch == '_'),
                "{n}"
            );
            assert!(!names[i + 1..].contains(n), "{n} twice");
        }
    }

    #[test]
    fn every_library_error_maps_to_a_status_other_than_ok() {
        let errors = [
            Error::invalid("a", 1, "b"),
            Error::Parse {
                what: "x".into(),
                message: "y".into(),
            },
            Error::CallOrder {
                call: "c",
                reason: "r".into(),
            },
            Error::StepFailed {
                t: 0.0,
                reason: "r".into(),
            },
            Error::Io("io".into()),
        ];
        let statuses: Vec<_> = errors
            .into_iter()
            .map(|e| Failure::from(e).status)
            .collect();
        assert_eq!(
            statuses,
            [
                RacewayStatus::InvalidArgument,
                RacewayStatus::InvalidArgument,
                RacewayStatus::CallOrder,
                RacewayStatus::StepFailed,
                RacewayStatus::Error
            ]
        );
    }
}
