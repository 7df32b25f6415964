//! Property tests of the C ABI (issue #21 item 4): random call sequences over a pool of
//! live, freed, NULL and made-up handles (and handles of the other kind), with wrong
//! lengths, NULL buffers, NaN and huge values, steps at any `t` and `h`, and state bytes
//! truncated, bit-flipped or with NaN written into a slot. Properties of every call:
//!
//! - never `RACEWAY_STATUS_PANIC`;
//! - a refused call leaves the instance as it was (its time and every variable, read one
//!   by one with the status of each read), leaves the caller's output buffer, the state
//!   it was asked to overwrite and the `*state` out-pointer untouched, and has a clear
//!   message (NULL and invalid handles excepted: they have no instance to hold one);
//! - after a successful call every variable that reads is finite;
//! - damaged state bytes (any truncation, any flipped bit, a NaN in a number slot) are
//!   refused, never restored.
//!
//! Cases: see `tests/props_util`. On a failure proptest shrinks the sequence to a minimal
//! one and prints it with the failing call's index.

mod props_util;

use props_util::number;
use proptest::prelude::*;
use proptest::sample::Index;
#[path = "common/capi_observe.rs"]
mod capi_observe;
use capi_observe::{message, observe};
use raceway::capi::*;
use std::ffi::{c_char, CStr, CString};
use std::ptr::{null, null_mut};

const SCENES: [&str; 3] = [
    // Motion-driven ring (cheap steps).
    "bearing = \"6205\"\n[model]\nlevel = \"ring\"\n[inputs]\nspeed_rpm = 1750.004092\ninitial = { \"shaft.y\" = -8e-6 }\n",
    // The default scene (quasi-static).
    raceway::component::scene::DEFAULT_SCENE,
    // Load-driven linear.
    "bearing = \"6205\"\n[model]\nlevel = \"linear\"\ncausality = \"load\"\nattached_mass_kg = 2.0\noperating_point = { speed_rpm = 1750.0, fy = -1000.0 }\n[inputs]\nspeed_rpm = 1750.004092\ninitial = { \"load.y\" = -1000.0 }\n",
];

/// Which instance handle a call gets.
#[derive(Debug, Clone)]
enum H {
    /// One the sequence created (live or freed by now).
    Made(Index),
    Null,
    /// Never created (aligned or not).
    MadeUp(usize),
    /// A state handle given where an instance belongs.
    AState(Index),
}

/// Which state handle a call gets.
#[derive(Debug, Clone)]
enum S {
    Made(Index),
    Null,
    MadeUp(usize),
    /// An instance handle given where a state belongs.
    AnInstance(Index),
}

/// A value reference: an input (of either causality), any variable, or an unknown one.
#[derive(Debug, Clone)]
enum Vr {
    Input(Index),
    Known(Index),
    Unknown(u32),
}

/// How stored state bytes are damaged before `raceway_state_deserialize`.
#[derive(Debug, Clone)]
enum Damage {
    None,
    Truncate(Index),
    FlipBit(Index, u8),
    NanInSlot(Index),
    /// Bytes of the right length made of one byte value.
    Foreign(u8),
}

#[derive(Debug, Clone)]
enum Call {
    /// Create from a shipped scene; `true`: then set every input to its initial value.
    Create(Index, bool),
    CreateBad(&'static str),
    Free(H),
    SetReal(H, Vr, f64),
    SetReals(H, Vec<(Vr, f64)>),
    /// `n > 0` with NULL arrays.
    SetRealsNull(H, usize),
    /// `t` is the instance's time when `None`.
    DoStep(H, Option<f64>, f64),
    GetReals(H, Vec<Vr>),
    GetRealsNull(H, usize),
    GetReal(H, Vr),
    StateGet(H, Option<S>),
    StateSet(H, S),
    StateFree(S),
    /// Serialise into a buffer `need + delta` bytes long.
    Serialize(H, S, i8),
    Deserialize(H, Index, Damage),
}

fn h() -> impl Strategy<Value = H> {
    prop_oneof![
        8 => any::<Index>().prop_map(H::Made),
        1 => Just(H::Null),
        1 => prop_oneof![Just(8usize), Just(1), Just(usize::MAX), any::<usize>()].prop_map(H::MadeUp),
        1 => any::<Index>().prop_map(H::AState),
    ]
}

fn s() -> impl Strategy<Value = S> {
    prop_oneof![
        8 => any::<Index>().prop_map(S::Made),
        1 => Just(S::Null),
        1 => prop_oneof![Just(8usize), Just(3), any::<usize>()].prop_map(S::MadeUp),
        1 => any::<Index>().prop_map(S::AnInstance),
    ]
}

fn vr() -> impl Strategy<Value = Vr> {
    prop_oneof![
        6 => any::<Index>().prop_map(Vr::Input),
        3 => any::<Index>().prop_map(Vr::Known),
        1 => prop_oneof![Just(u32::MAX), Just(0u32), Just(77777), any::<u32>()].prop_map(Vr::Unknown),
    ]
}

/// A value for an input: mostly a plausible displacement, load or speed, sometimes nasty.
fn value() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => (-10.0f64..10.0).prop_map(|x| 1e-6 * x),
        1 => -1000.0f64..1000.0,
        2 => number(),
    ]
}

fn damage() -> impl Strategy<Value = Damage> {
    prop_oneof![
        2 => Just(Damage::None),
        2 => any::<Index>().prop_map(Damage::Truncate),
        3 => (any::<Index>(), 0u8..8).prop_map(|(i, b)| Damage::FlipBit(i, b)),
        2 => any::<Index>().prop_map(Damage::NanInSlot),
        1 => any::<u8>().prop_map(Damage::Foreign),
    ]
}

fn call() -> impl Strategy<Value = Call> {
    prop_oneof![
        3 => (any::<Index>(), any::<bool>()).prop_map(|(i, init)| Call::Create(i, init)),
        1 => proptest::sample::select(vec!["", "bearing = 6205", "x = [", "{\"bearing\": \"6205\", \"model\": []}", "run = 5"])
            .prop_map(Call::CreateBad),
        1 => h().prop_map(Call::Free),
        3 => (h(), vr(), value()).prop_map(|(h, v, x)| Call::SetReal(h, v, x)),
        3 => (h(), proptest::collection::vec((vr(), value()), 0..12)).prop_map(|(h, v)| Call::SetReals(h, v)),
        1 => (h(), 1usize..5).prop_map(|(h, n)| Call::SetRealsNull(h, n)),
        6 => (h(), prop_oneof![3 => Just(None), 1 => number().prop_map(Some)],
              prop_oneof![3 => Just(1e-4), 1 => number()])
            .prop_map(|(h, t, dt)| Call::DoStep(h, t, dt)),
        2 => (h(), proptest::collection::vec(vr(), 0..10)).prop_map(|(h, v)| Call::GetReals(h, v)),
        1 => (h(), 1usize..5).prop_map(|(h, n)| Call::GetRealsNull(h, n)),
        2 => (h(), vr()).prop_map(|(h, v)| Call::GetReal(h, v)),
        3 => (h(), proptest::option::of(s())).prop_map(|(h, s)| Call::StateGet(h, s)),
        3 => (h(), s()).prop_map(|(h, s)| Call::StateSet(h, s)),
        1 => s().prop_map(Call::StateFree),
        2 => (h(), s(), prop_oneof![3 => Just(0i8), 1 => -9i8..3]).prop_map(|(h, s, d)| Call::Serialize(h, s, d)),
        3 => (h(), any::<Index>(), damage()).prop_map(|(h, i, d)| Call::Deserialize(h, i, d)),
    ]
}

/// Handles and bytes the sequence made.
#[derive(Default)]
struct World {
    insts: Vec<*mut RacewayComponent>,
    states: Vec<*mut RacewayState>,
    bytes: Vec<Vec<u8>>,
}

impl World {
    fn inst(&self, h: &H) -> *mut RacewayComponent {
        match h {
            H::Made(i) if !self.insts.is_empty() => self.insts[i.index(self.insts.len())],
            H::Made(_) | H::Null => null_mut(),
            H::MadeUp(p) => *p as *mut RacewayComponent,
            H::AState(i) if !self.states.is_empty() => {
                self.states[i.index(self.states.len())] as *mut RacewayComponent
            }
            H::AState(_) => null_mut(),
        }
    }
    fn state(&self, s: &S) -> *mut RacewayState {
        match s {
            S::Made(i) if !self.states.is_empty() => self.states[i.index(self.states.len())],
            S::Made(_) | S::Null => null_mut(),
            S::MadeUp(p) => *p as *mut RacewayState,
            S::AnInstance(i) if !self.insts.is_empty() => {
                self.insts[i.index(self.insts.len())] as *mut RacewayState
            }
            S::AnInstance(_) => null_mut(),
        }
    }
    /// A live instance, to serialise states with.
    fn any_live(&self) -> Option<*mut RacewayComponent> {
        self.insts.iter().copied().find(|&c| observe(c).is_some())
    }
    /// The bytes of state `s` (None when it is not a live state).
    fn state_bytes(&self, s: *mut RacewayState) -> Option<Vec<u8>> {
        let c = self.any_live()?;
        let mut n = 0usize;
        if unsafe { raceway_state_size(c, s, &mut n) } != RacewayStatus::Ok {
            return None;
        }
        let mut b = vec![0u8; n];
        (unsafe { raceway_state_serialize(c, s, b.as_mut_ptr(), n) } == RacewayStatus::Ok)
            .then_some(b)
    }
}

impl Drop for World {
    fn drop(&mut self) {
        unsafe {
            for &c in &self.insts {
                raceway_free(c);
            }
            for &s in &self.states {
                raceway_state_free(s);
            }
        }
    }
}

fn vr_of(v: &Vr) -> u32 {
    use raceway::component::{variables, Causality};
    match v {
        Vr::Input(i) => {
            let inputs: Vec<u32> = variables::all()
                .filter(|v| v.is_input(Causality::Motion) || v.is_input(Causality::Load))
                .map(|v| v.vr)
                .collect();
            inputs[i.index(inputs.len())]
        }
        Vr::Known(i) => {
            let mut vr = 0;
            let n = raceway_variable_count();
            unsafe { raceway_variable_at(i.index(n), &mut vr) };
            vr
        }
        Vr::Unknown(x) => *x,
    }
}

/// Sentinel written into output buffers before a call.
const SENTINEL: f64 = -7.25e-77;

/// Run one call; `Err` names the property it broke.
fn run(w: &mut World, call: &Call) -> Result<(), String> {
    // The handle the call is about (for the instance-unchanged check).
    let target = match call {
        Call::Free(h)
        | Call::SetReal(h, ..)
        | Call::SetReals(h, _)
        | Call::SetRealsNull(h, _)
        | Call::DoStep(h, ..)
        | Call::GetReals(h, _)
        | Call::GetRealsNull(h, _)
        | Call::GetReal(h, _)
        | Call::StateGet(h, _)
        | Call::StateSet(h, _)
        | Call::Serialize(h, ..)
        | Call::Deserialize(h, ..) => w.inst(h),
        _ => null_mut(),
    };
    let before = observe(target);
    let c = target;
    // Extra checks of a refused call: (what, before, after) of caller-visible memory.
    let mut untouched: Vec<(&str, Vec<u64>, Vec<u64>)> = Vec::new();
    let mut must_refuse = false;
    let status = unsafe {
        match call {
            Call::Create(i, init) => {
                let text = CString::new(SCENES[i.index(SCENES.len())]).unwrap();
                let mut err = [0 as c_char; 256];
                let p = raceway_create(text.as_ptr(), err.as_mut_ptr(), err.len());
                if p.is_null() {
                    let m = CStr::from_ptr(err.as_ptr()).to_string_lossy().into_owned();
                    return Err(format!("a shipped scene was refused: {m}"));
                }
                w.insts.push(p);
                if *init {
                    // Every input at its initial value (what a host does before stepping).
                    for k in 0..raceway_variable_count() {
                        let mut vr = 0;
                        raceway_variable_at(k, &mut vr);
                        let mut x = 0.0;
                        if raceway_get_real(p, vr, &mut x) == RacewayStatus::Ok {
                            raceway_set_real(p, vr, x);
                        }
                    }
                }
                RacewayStatus::Ok
            }
            Call::CreateBad(text) => {
                let text = CString::new(*text).unwrap();
                let mut err = [0 as c_char; 256];
                let p = raceway_create(text.as_ptr(), err.as_mut_ptr(), err.len());
                let m = CStr::from_ptr(err.as_ptr()).to_string_lossy().into_owned();
                if !p.is_null() {
                    w.insts.push(p);
                    return Err("a broken scene was accepted".into());
                }
                if m.len() < 12 {
                    return Err(format!("unclear refusal of a broken scene: `{m}`"));
                }
                RacewayStatus::Ok
            }
            Call::Free(_) => {
                raceway_free(c);
                // A freed (or never live) handle reads as not live afterwards.
                if observe(c).is_some() {
                    return Err("an instance is still live after raceway_free".into());
                }
                RacewayStatus::Ok
            }
            Call::SetReal(_, v, x) => raceway_set_real(c, vr_of(v), *x),
            Call::SetReals(_, pairs) => {
                let vrs: Vec<u32> = pairs.iter().map(|(v, _)| vr_of(v)).collect();
                let xs: Vec<f64> = pairs.iter().map(|(_, x)| *x).collect();
                raceway_set_reals(c, vrs.as_ptr(), xs.as_ptr(), vrs.len())
            }
            Call::SetRealsNull(_, n) => {
                must_refuse = true;
                raceway_set_reals(c, null(), null(), *n)
            }
            Call::DoStep(_, t, dt) => {
                let mut now = 0.0;
                raceway_get_time(c, &mut now);
                raceway_do_step(c, t.unwrap_or(now), *dt)
            }
            Call::GetReals(_, vs) => {
                let vrs: Vec<u32> = vs.iter().map(vr_of).collect();
                let mut out = vec![SENTINEL; vrs.len()];
                let st = raceway_get_reals(c, vrs.as_ptr(), out.as_mut_ptr(), vrs.len());
                if st == RacewayStatus::Ok && out.iter().any(|x| !x.is_finite()) {
                    return Err(format!("get_reals returned {out:?}"));
                }
                let bits = out.iter().map(|x| x.to_bits()).collect();
                untouched.push((
                    "the values buffer",
                    vec![SENTINEL.to_bits(); vrs.len()],
                    bits,
                ));
                st
            }
            Call::GetRealsNull(_, n) => {
                must_refuse = true;
                raceway_get_reals(c, null(), null_mut(), *n)
            }
            Call::GetReal(_, v) => {
                let mut x = SENTINEL;
                let st = raceway_get_real(c, vr_of(v), &mut x);
                if st == RacewayStatus::Ok && !x.is_finite() {
                    return Err(format!("get_real returned {x}"));
                }
                untouched.push(("the value", vec![SENTINEL.to_bits()], vec![x.to_bits()]));
                st
            }
            Call::StateGet(_, into) => {
                let mut s = into.as_ref().map_or(null_mut(), |s| w.state(s));
                let given = s;
                let old = w.state_bytes(given);
                let st = raceway_state_get(c, &mut s);
                if st == RacewayStatus::Ok {
                    if given.is_null() {
                        w.states.push(s);
                    } else if s != given {
                        return Err("state_get into an existing state moved the handle".into());
                    }
                } else {
                    untouched.push(("*state", vec![given as u64], vec![s as u64]));
                    if let Some(old) = old {
                        let now = w.state_bytes(given).unwrap_or_default();
                        untouched.push((
                            "the state's bytes",
                            old.iter().map(|&b| b as u64).collect(),
                            now.iter().map(|&b| b as u64).collect(),
                        ));
                    }
                }
                st
            }
            Call::StateSet(_, s) => raceway_state_set(c, w.state(s)),
            Call::StateFree(s) => {
                let s = w.state(s);
                raceway_state_free(s);
                if w.any_live().is_some() && w.state_bytes(s).is_some() {
                    return Err("a state is still live after raceway_state_free".into());
                }
                RacewayStatus::Ok
            }
            Call::Serialize(_, s, delta) => {
                let s = w.state(s);
                let mut need = 0usize;
                let st = raceway_state_size(c, s, &mut need);
                if st != RacewayStatus::Ok {
                    st
                } else {
                    let len = (need as isize + *delta as isize).max(0) as usize;
                    let mut buf = vec![0xa5u8; len];
                    let st = raceway_state_serialize(c, s, buf.as_mut_ptr(), len);
                    if st == RacewayStatus::Ok {
                        buf.truncate(need);
                        w.bytes.push(buf);
                    } else {
                        untouched.push((
                            "the buffer",
                            vec![0xa5; len],
                            buf.iter().map(|&b| b as u64).collect(),
                        ));
                    }
                    st
                }
            }
            Call::Deserialize(_, i, damage) => {
                if w.bytes.is_empty() {
                    // Fresh bytes of a live instance's state.
                    let Some(live) = w.any_live() else {
                        return Ok(());
                    };
                    let mut s = null_mut();
                    if raceway_state_get(live, &mut s) != RacewayStatus::Ok {
                        return Err(format!("state_get of a live instance: {}", message(live)));
                    }
                    let b = w.state_bytes(s);
                    raceway_state_free(s);
                    w.bytes.extend(b);
                }
                let mut b = w.bytes[i.index(w.bytes.len())].clone();
                match damage {
                    Damage::None => {}
                    Damage::Truncate(k) => {
                        b.truncate(k.index(b.len()));
                        must_refuse = true;
                    }
                    Damage::FlipBit(k, bit) => {
                        let k = k.index(b.len());
                        b[k] ^= 1 << bit;
                        must_refuse = true;
                    }
                    Damage::NanInSlot(k) => {
                        if b.len() >= 8 {
                            let k = k.index(b.len() / 8) * 8;
                            let old = b[k..k + 8].to_vec();
                            b[k..k + 8].copy_from_slice(&f64::NAN.to_le_bytes());
                            must_refuse = b[k..k + 8] != old[..];
                        }
                    }
                    Damage::Foreign(x) => {
                        let n = b.len();
                        must_refuse = b.iter().any(|&y| y != *x);
                        b = vec![*x; n];
                    }
                }
                let sentinel = 0x40usize as *mut RacewayState;
                let mut s = sentinel;
                let st = raceway_state_deserialize(c, b.as_ptr(), b.len(), &mut s);
                if st == RacewayStatus::Ok {
                    w.states.push(s);
                } else {
                    untouched.push(("*state", vec![sentinel as u64], vec![s as u64]));
                }
                st
            }
        }
    };
    if status == RacewayStatus::Panic {
        return Err(format!("PANIC status: {}", message(c)));
    }
    if must_refuse && status == RacewayStatus::Ok {
        return Err("a call that must be refused returned OK".into());
    }
    if status != RacewayStatus::Ok {
        let bare = matches!(
            status,
            RacewayStatus::NullPointer | RacewayStatus::InvalidHandle
        );
        let m = message(c);
        if !bare && (m.len() < 12 || m.contains("panic")) {
            return Err(format!("unclear message `{m}` ({status:?})"));
        }
        let after = observe(c);
        if before.is_some() && after != before {
            return Err(format!(
                "refused ({status:?}: {m}) but the instance changed"
            ));
        }
        for (what, b, a) in &untouched {
            if a != b {
                return Err(format!("refused ({status:?}: {m}) but {what} changed"));
            }
        }
    } else if let Some(v) = observe(c) {
        if let Some(k) = v
            .iter()
            .position(|&b| b >> 63 == 0 && !f64::from_bits(b).is_finite())
        {
            return Err(format!(
                "non-finite value (slot {k}) after a successful call"
            ));
        }
    }
    // Keep the pools small (the oldest are freed; their handles stay out of reach).
    if w.states.len() > 12 {
        unsafe { raceway_state_free(w.states.remove(0)) };
    }
    if w.bytes.len() > 6 {
        w.bytes.remove(0);
    }
    Ok(())
}

#[test]
fn c_abi_call_sequences_never_panic_and_refusals_change_nothing() {
    let strategy = (any::<Index>(), proptest::collection::vec(call(), 1..40));
    props_util::check("C ABI", file!(), 1024, strategy, |(first, calls)| {
        let mut w = World::default();
        // Every sequence starts with a live, stepping instance.
        if let Err(e) = run(&mut w, &Call::Create(first, true)) {
            prop_assert!(false, "creating the first instance: {}", e);
        }
        for (k, c) in calls.iter().enumerate() {
            if let Err(e) = run(&mut w, c) {
                prop_assert!(false, "call {} of {}: {:?}: {}", k, calls.len(), c, e);
            }
        }
        Ok(())
    });
}
