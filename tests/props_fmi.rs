//! Property tests of the FMI 2 and FMI 3 state machines (issue #21 item 4), through the
//! exported `fmi2*` / `fmi3*` functions (`cargo test --features fmi --test props_fmi`;
//! CI: `scripts/test.d/35-props-fmi.sh`).
//!
//! Random call sequences in any order (setup, enter/exit initialisation, set and get with
//! NaN, huge and unknown references, steps at the right and wrong time, terminate, reset,
//! get/set/serialise/deserialise FMU state) run against a model of the state machine
//! written from the standard's tables (docs/physics.md §C1.6: FMI 2.0 §4.2,
//! FMI 3.0 §2.3 and the Reference FMUs' masks), not from the implementation's masks.
//! Properties of every call:
//!
//! - no panic (counted by a panic hook: the guard would turn it into an error status);
//! - a call the state machine does not allow in the current state returns `Error`;
//! - the calls that only move the state machine (setup, enter/exit initialisation,
//!   terminate, reset, get/set FMU state) succeed whenever they are allowed;
//! - after every call the instance is in the state the model says: on `Error` the one the
//!   standard prescribes (FMI 2: error; FMI 3: Terminated), on success the next state of
//!   the table (read from the mode word of the serialised FMU state);
//! - a refused call (`Error` or `Discard`) changes nothing else: the serialised FMU state
//!   is the same byte for byte apart from that mode word and the checksum (time, start
//!   and stop time, tolerance, parameters, inputs, pending derivatives, the component's
//!   state), and restoring a state taken before the call gives back the same bytes;
//! - no NaN or infinity is read after `OK`.
//!
//! Cases: see `tests/props_util`.

#![cfg(feature = "fmi")]

mod props_util;

use props_util::number;
use proptest::prelude::*;
use proptest::sample::Index;
use raceway::component::{variables, Causality};
use raceway::fmi::fmi2::*;
use raceway::fmi::fmi3::*;
use raceway::fmi::{Status, GUID};
use std::cell::Cell;
use std::ffi::{c_void, CString};
use std::ptr::{null, null_mut};

// The instance states as the serialised FMU state stores them (`fmi::instance`, mode word
// after magic, format and GUID).
const INSTANTIATED: u32 = 1;
const INIT: u32 = 2;
const STEP: u32 = 4;
const EVENT: u32 = 8;
const TERMINATED: u32 = 16;
const ERROR: u32 = 32;

/// Offset of the mode word in the serialised FMU state: magic (4), format (4), GUID length
/// (8) and the GUID.
fn mode_at() -> usize {
    16 + GUID.len()
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Version {
    Fmi2,
    Fmi3,
}

#[derive(Debug, Clone)]
enum Call {
    /// FMI 2 `SetupExperiment` (FMI 3: the same arguments go to `EnterInitializationMode`).
    Setup(Option<f64>, f64),
    EnterInit,
    ExitInit,
    SetReal(Vr, f64),
    GetReal(Vr),
    /// `t` is the model's time when `None`.
    DoStep(Option<f64>, f64),
    Terminate,
    Reset,
    GetState,
    SetState(Index),
    /// Serialise a stored state and deserialise it (optionally with a flipped byte).
    RoundTrip(Index, Option<Index>),
    /// FMI 2 `GetRealStatus(fmi2LastSuccessfulTime)` (FMI 3: `GetFloat64` of nothing).
    GetStatus,
}

#[derive(Debug, Clone)]
enum Vr {
    Input(Index),
    Any(Index),
    Unknown(u32),
}

fn vr() -> impl Strategy<Value = Vr> {
    prop_oneof![
        4 => any::<Index>().prop_map(Vr::Input),
        2 => any::<Index>().prop_map(Vr::Any),
        1 => prop_oneof![Just(0u32), Just(99999), any::<u32>()].prop_map(Vr::Unknown),
    ]
}

fn vr_of(v: &Vr) -> u32 {
    match v {
        Vr::Input(i) => {
            let inputs: Vec<u32> = variables::all()
                .filter(|v| v.is_input(Causality::Motion))
                .map(|v| v.vr)
                .collect();
            inputs[i.index(inputs.len())]
        }
        Vr::Any(i) => {
            let all: Vec<u32> = variables::all().map(|v| v.vr).collect();
            all[i.index(all.len())]
        }
        Vr::Unknown(x) => *x,
    }
}

fn call() -> impl Strategy<Value = Call> {
    let small = prop_oneof![3 => -1e-5f64..1e-5, 1 => number()];
    prop_oneof![
        2 => (proptest::option::of(prop_oneof![Just(1e-6), number()]), prop_oneof![3 => Just(0.0), 1 => number()])
            .prop_map(|(tol, t0)| Call::Setup(tol, t0)),
        2 => Just(Call::EnterInit),
        2 => Just(Call::ExitInit),
        4 => (vr(), small).prop_map(|(v, x)| Call::SetReal(v, x)),
        3 => vr().prop_map(Call::GetReal),
        5 => (prop_oneof![4 => Just(None), 1 => number().prop_map(Some)], prop_oneof![4 => Just(1e-4), 1 => number()])
            .prop_map(|(t, h)| Call::DoStep(t, h)),
        1 => Just(Call::Terminate),
        1 => Just(Call::Reset),
        2 => Just(Call::GetState),
        2 => any::<Index>().prop_map(Call::SetState),
        1 => (any::<Index>(), proptest::option::of(any::<Index>())).prop_map(|(i, f)| Call::RoundTrip(i, f)),
        1 => Just(Call::GetStatus),
    ]
}

/// The state machine of the standard: may `call` be made in `mode`?
fn allowed(v: Version, mode: u32, call: &Call) -> bool {
    let any = true;
    match (v, call) {
        (_, Call::Setup(..) | Call::EnterInit) => mode == INSTANTIATED,
        (_, Call::ExitInit) => mode == INIT,
        (Version::Fmi2, Call::SetReal(..)) => mode & (INSTANTIATED | INIT | STEP) != 0,
        (Version::Fmi3, Call::SetReal(..)) => mode & (INSTANTIATED | INIT | EVENT | STEP) != 0,
        (Version::Fmi2, Call::GetReal(_)) => mode & (INIT | STEP | TERMINATED | ERROR) != 0,
        (Version::Fmi3, Call::GetReal(_) | Call::GetStatus) => {
            mode & (INIT | EVENT | STEP | TERMINATED) != 0
        }
        (_, Call::DoStep(..)) => mode == STEP,
        (Version::Fmi2, Call::Terminate) => mode == STEP,
        (Version::Fmi3, Call::Terminate) => mode & (STEP | EVENT) != 0,
        (_, Call::Reset | Call::GetState | Call::SetState(_) | Call::RoundTrip(..)) => any,
        (Version::Fmi2, Call::GetStatus) => mode & (STEP | TERMINATED) != 0,
    }
}

/// A stored FMU state with the model's view of it.
struct Stored {
    state: *mut c_void,
    mode: u32,
    time: f64,
}

struct Fmu {
    v: Version,
    c: *mut c_void,
    stored: Vec<Stored>,
    /// The model: state and time.
    mode: u32,
    time: f64,
}

#[path = "common/fmi_callbacks.rs"]
mod fmi_callbacks;
use fmi_callbacks::callbacks;

thread_local!(static PANICS: Cell<u64> = const { Cell::new(0) });

impl Fmu {
    fn new(v: Version) -> Fmu {
        let name = CString::new("props").unwrap();
        let guid = CString::new(GUID).unwrap();
        let c = unsafe {
            match v {
                Version::Fmi2 => {
                    fmi2Instantiate(name.as_ptr(), 1, guid.as_ptr(), null(), callbacks(), 0, 0)
                }
                Version::Fmi3 => fmi3InstantiateCoSimulation(
                    name.as_ptr(),
                    guid.as_ptr(),
                    null(),
                    false,
                    false,
                    false,
                    false,
                    null(),
                    0,
                    null_mut(),
                    None,
                    None,
                ),
            }
        };
        assert!(!c.is_null());
        Fmu {
            v,
            c,
            stored: vec![],
            mode: INSTANTIATED,
            time: 0.0,
        }
    }

    /// The serialised FMU state now (taking it changes nothing).
    fn bytes(&self) -> Vec<u8> {
        unsafe {
            let mut s = null_mut();
            let ok = match self.v {
                Version::Fmi2 => fmi2GetFMUstate(self.c, &mut s),
                Version::Fmi3 => fmi3GetFMUState(self.c, &mut s),
            };
            assert_eq!(ok, Status::Ok, "GetFMUstate in mode {}", self.mode);
            let b = self.serialize(s).expect("serialise a fresh state");
            self.free_state(s);
            b
        }
    }

    unsafe fn serialize(&self, s: *mut c_void) -> Option<Vec<u8>> {
        let mut n = 0usize;
        let st = match self.v {
            Version::Fmi2 => fmi2SerializedFMUstateSize(self.c, s, &mut n),
            Version::Fmi3 => fmi3SerializedFMUStateSize(self.c, s, &mut n),
        };
        if st != Status::Ok {
            return None;
        }
        let mut b = vec![0u8; n];
        let st = match self.v {
            Version::Fmi2 => fmi2SerializeFMUstate(self.c, s, b.as_mut_ptr().cast(), n),
            Version::Fmi3 => fmi3SerializeFMUState(self.c, s, b.as_mut_ptr(), n),
        };
        (st == Status::Ok).then_some(b)
    }

    unsafe fn free_state(&self, mut s: *mut c_void) {
        match self.v {
            Version::Fmi2 => fmi2FreeFMUstate(self.c, &mut s),
            Version::Fmi3 => fmi3FreeFMUState(self.c, &mut s),
        };
    }

    unsafe fn set_state(&self, s: *mut c_void) -> Status {
        match self.v {
            Version::Fmi2 => fmi2SetFMUstate(self.c, s),
            Version::Fmi3 => fmi3SetFMUState(self.c, s),
        }
    }

    /// Make the call; returns its status and, for `GetReal`, the value read.
    unsafe fn call(&mut self, call: &Call) -> (Status, Option<f64>) {
        let c = self.c;
        let v = self.v;
        let st = match (v, call) {
            (Version::Fmi2, Call::Setup(tol, t0)) => {
                fmi2SetupExperiment(c, tol.is_some() as i32, tol.unwrap_or(0.0), *t0, 0, 0.0)
            }
            (Version::Fmi2, Call::EnterInit) => fmi2EnterInitializationMode(c),
            (Version::Fmi3, Call::Setup(tol, t0)) => {
                fmi3EnterInitializationMode(c, tol.is_some(), tol.unwrap_or(0.0), *t0, false, 0.0)
            }
            (Version::Fmi3, Call::EnterInit) => {
                fmi3EnterInitializationMode(c, false, 0.0, 0.0, false, 0.0)
            }
            (Version::Fmi2, Call::ExitInit) => fmi2ExitInitializationMode(c),
            (Version::Fmi3, Call::ExitInit) => fmi3ExitInitializationMode(c),
            (_, Call::SetReal(r, x)) => {
                let vr = vr_of(r);
                match v {
                    Version::Fmi2 => fmi2SetReal(c, &vr, 1, x),
                    Version::Fmi3 => fmi3SetFloat64(c, &vr, 1, x, 1),
                }
            }
            (_, Call::GetReal(r)) => {
                let vr = vr_of(r);
                let mut x = 0.0;
                let st = match v {
                    Version::Fmi2 => fmi2GetReal(c, &vr, 1, &mut x),
                    Version::Fmi3 => fmi3GetFloat64(c, &vr, 1, &mut x, 1),
                };
                return (st, Some(x));
            }
            (_, Call::DoStep(t, h)) => {
                let t = t.unwrap_or(self.time);
                match v {
                    Version::Fmi2 => fmi2DoStep(c, t, *h, 0),
                    Version::Fmi3 => {
                        let (mut a, mut b, mut e, mut last) = (false, false, false, 0.0);
                        fmi3DoStep(c, t, *h, false, &mut a, &mut b, &mut e, &mut last)
                    }
                }
            }
            (Version::Fmi2, Call::Terminate) => fmi2Terminate(c),
            (Version::Fmi3, Call::Terminate) => fmi3Terminate(c),
            (Version::Fmi2, Call::Reset) => fmi2Reset(c),
            (Version::Fmi3, Call::Reset) => fmi3Reset(c),
            (_, Call::GetState) => {
                let mut s = null_mut();
                let st = match v {
                    Version::Fmi2 => fmi2GetFMUstate(c, &mut s),
                    Version::Fmi3 => fmi3GetFMUState(c, &mut s),
                };
                if st == Status::Ok {
                    self.stored.push(Stored {
                        state: s,
                        mode: self.mode,
                        time: self.time,
                    });
                }
                st
            }
            (_, Call::SetState(i)) => {
                if self.stored.is_empty() {
                    return (Status::Ok, None);
                }
                let k = i.index(self.stored.len());
                self.set_state(self.stored[k].state)
            }
            (_, Call::RoundTrip(i, flip)) => {
                if self.stored.is_empty() {
                    return (Status::Ok, None);
                }
                let k = i.index(self.stored.len());
                let Some(mut b) = self.serialize(self.stored[k].state) else {
                    return (Status::Error, None);
                };
                if let Some(f) = flip {
                    let j = f.index(b.len());
                    b[j] ^= 0x20;
                }
                let mut s = null_mut();
                let st = match v {
                    Version::Fmi2 => fmi2DeSerializeFMUstate(c, b.as_ptr().cast(), b.len(), &mut s),
                    Version::Fmi3 => fmi3DeserializeFMUState(c, b.as_ptr(), b.len(), &mut s),
                };
                if st == Status::Ok {
                    let (mode, time) = (self.stored[k].mode, self.stored[k].time);
                    self.stored.push(Stored {
                        state: s,
                        mode,
                        time,
                    });
                }
                st
            }
            (Version::Fmi2, Call::GetStatus) => {
                let mut x = 0.0;
                let st = fmi2GetRealStatus(c, 2 /* fmi2LastSuccessfulTime */, &mut x);
                return (st, Some(x));
            }
            (Version::Fmi3, Call::GetStatus) => fmi3GetFloat64(c, null(), 0, null_mut(), 0),
        };
        (st, None)
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        unsafe {
            for s in std::mem::take(&mut self.stored) {
                self.free_state(s.state);
            }
            match self.v {
                Version::Fmi2 => fmi2FreeInstance(self.c),
                Version::Fmi3 => fmi3FreeInstance(self.c),
            }
        }
    }
}

/// The bytes with the mode word and the checksum blanked.
fn without_mode(b: &[u8]) -> Vec<u8> {
    let mut b = b.to_vec();
    let at = mode_at();
    b[at..at + 4].fill(0);
    let n = b.len();
    b[n - 8..].fill(0);
    b
}

fn mode_of(b: &[u8]) -> u32 {
    let at = mode_at();
    u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

/// Run a sequence; `Err` names the call and the property it broke.
fn run(v: Version, calls: &[Call]) -> Result<(), String> {
    let mut f = Fmu::new(v);
    for (k, call) in calls.iter().enumerate() {
        let mode0 = f.mode;
        let fail = |what: String| Err(format!("{v:?} call {k} {call:?} in mode {mode0}: {what}"));
        let before = f.bytes();
        if mode_of(&before) != f.mode {
            return fail(format!("the instance is in mode {}", mode_of(&before)));
        }
        let ok_before = allowed(v, f.mode, call);
        let panics0 = PANICS.with(Cell::get);
        let (st, read) = unsafe { f.call(call) };
        if PANICS.with(Cell::get) != panics0 {
            return fail("panicked".into());
        }
        let after = f.bytes();
        // Calls that only move the state machine succeed whenever they are allowed.
        let must_succeed = ok_before
            && (matches!(
                call,
                Call::EnterInit | Call::ExitInit | Call::Terminate | Call::Reset | Call::GetState // A start time no step could leave (|t| > 5e8 s) is refused at set-up (#38).
            ) || matches!(call, Call::Setup(None, t0) if t0.is_finite() && t0.abs() <= 5e8)
                || matches!(call, Call::SetState(_) if !f.stored.is_empty()));
        if !ok_before && st != Status::Error {
            return fail(format!("not allowed, but returned {st:?}"));
        }
        if must_succeed && st != Status::Ok {
            return fail(format!("allowed, but returned {st:?}"));
        }
        match st {
            Status::Ok | Status::Warning => {
                if let Some(x) = read {
                    if !x.is_finite() {
                        return fail(format!("read {x} with OK"));
                    }
                }
                // The model's next state.
                match call {
                    Call::Setup(..) if v == Version::Fmi3 => f.mode = INIT,
                    Call::EnterInit => f.mode = INIT,
                    Call::ExitInit => f.mode = STEP,
                    Call::DoStep(t, h) => f.time = t.unwrap_or(f.time) + h,
                    Call::Terminate => f.mode = TERMINATED,
                    Call::Reset => {
                        f.mode = INSTANTIATED;
                        f.time = 0.0;
                    }
                    Call::SetState(i) if !f.stored.is_empty() => {
                        let s = &f.stored[i.index(f.stored.len())];
                        f.mode = s.mode;
                        f.time = s.time;
                    }
                    _ => {}
                }
                // The instance's time starts at the start time.
                match call {
                    Call::Setup(_, t0) => f.time = *t0,
                    Call::EnterInit if v == Version::Fmi3 => f.time = 0.0,
                    _ => {}
                }
            }
            Status::Error | Status::Discard => {
                if without_mode(&after) != without_mode(&before) {
                    return fail(format!("refused ({st:?}) but the FMU state changed"));
                }
                if st == Status::Error {
                    f.mode = if v == Version::Fmi2 {
                        ERROR
                    } else {
                        TERMINATED
                    };
                } else if mode_of(&after) != f.mode {
                    return fail("discarded, but the mode changed".into());
                }
                // Restoring a state taken before the call gives back the same bytes.
                unsafe {
                    let mut s = null_mut();
                    let _ = match v {
                        Version::Fmi2 => fmi2DeSerializeFMUstate(
                            f.c,
                            before.as_ptr().cast(),
                            before.len(),
                            &mut s,
                        ),
                        Version::Fmi3 => {
                            fmi3DeserializeFMUState(f.c, before.as_ptr(), before.len(), &mut s)
                        }
                    };
                    if s.is_null() {
                        return fail("the bytes taken before do not deserialise".into());
                    }
                    let st = f.set_state(s);
                    f.free_state(s);
                    if st != Status::Ok {
                        return fail(format!("restoring the state before: {st:?}"));
                    }
                    if f.bytes() != before {
                        return fail("restoring the state before gives other bytes".into());
                    }
                    // Back to the error state the refusal left, as a host would see it
                    // without the rollback: set the bytes taken after.
                    let mut s = null_mut();
                    let _ = match v {
                        Version::Fmi2 => {
                            fmi2DeSerializeFMUstate(f.c, after.as_ptr().cast(), after.len(), &mut s)
                        }
                        Version::Fmi3 => {
                            fmi3DeserializeFMUState(f.c, after.as_ptr(), after.len(), &mut s)
                        }
                    };
                    if s.is_null() || f.set_state(s) != Status::Ok {
                        return fail("the bytes after the refusal do not restore".into());
                    }
                    f.free_state(s);
                }
            }
            other => return fail(format!("status {other:?}")),
        }
        let now = mode_of(&f.bytes());
        if now != f.mode {
            return fail(format!(
                "returned {st:?}; the model says mode {}, the instance is in {now}",
                f.mode
            ));
        }
        if f.stored.len() > 8 {
            let s = f.stored.remove(0);
            unsafe { f.free_state(s.state) };
        }
    }
    Ok(())
}

fn count_panics() {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            PANICS.with(|p| p.set(p.get() + 1));
            previous(info);
        }));
    });
}

/// The start of a normal run, so that sequences often begin in step mode: the first
/// `prologue` of these calls come before the random ones (FMI 3 has no separate setup).
const PROLOGUE2: [Call; 3] = [Call::Setup(None, 0.0), Call::EnterInit, Call::ExitInit];
const PROLOGUE3: [Call; 3] = [Call::GetState, Call::EnterInit, Call::ExitInit];

/// The property for one version: 512 sequences in CI.
fn state_machine_property(v: Version, name: &str, prologue_calls: &'static [Call]) {
    count_panics();
    let strategy = (0usize..4, proptest::collection::vec(call(), 1..30));
    props_util::check(name, file!(), 512, strategy, |(prologue, calls)| {
        let r = run(v, &[&prologue_calls[..prologue], &calls[..]].concat());
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
        Ok(())
    });
}

#[test]
fn fmi2_calls_in_any_order_follow_the_state_machine_and_refusals_change_nothing() {
    state_machine_property(Version::Fmi2, "FMI 2", &PROLOGUE2);
}

#[test]
fn fmi3_calls_in_any_order_follow_the_state_machine_and_refusals_change_nothing() {
    state_machine_property(Version::Fmi3, "FMI 3", &PROLOGUE3);
}

/// The shrunk case the property found, kept as a plain test: a NaN tolerance was kept in
/// the FMU state, whose bytes then did not deserialise.
#[test]
fn found_a_nan_tolerance_is_refused_and_the_state_bytes_still_restore() {
    for v in [Version::Fmi2, Version::Fmi3] {
        let mut f = Fmu::new(v);
        let before = f.bytes();
        let (st, _) = unsafe { f.call(&Call::Setup(Some(f64::NAN), 0.0)) };
        assert_eq!(st, Status::Error, "{v:?}");
        let after = f.bytes();
        assert_eq!(without_mode(&after), without_mode(&before), "{v:?}");
        let mut s = null_mut();
        let st = unsafe {
            match v {
                Version::Fmi2 => {
                    fmi2DeSerializeFMUstate(f.c, after.as_ptr().cast(), after.len(), &mut s)
                }
                Version::Fmi3 => fmi3DeserializeFMUState(f.c, after.as_ptr(), after.len(), &mut s),
            }
        };
        assert_eq!(st, Status::Ok, "{v:?}");
        unsafe { f.free_state(s) };
    }
}
