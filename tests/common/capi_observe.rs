//! What the C ABI property and fuzz tests observe of an instance (`tests/props_capi.rs`,
//! `tests/fuzz.rs`). Mount with `#[path = "common/capi_observe.rs"] mod capi_observe;`.

use raceway::capi::*;
use std::ffi::CStr;

/// The instance's last error message.
pub fn message(c: *mut RacewayComponent) -> String {
    unsafe { CStr::from_ptr(raceway_last_error(c)) }
        .to_string_lossy()
        .into_owned()
}

/// Time and every variable of a live instance (bits, and the status of a refused read
/// with the top bit set); None when `c` is not a live instance. Outputs are evaluated
/// lazily on the first read after an input or the state changed, and refused while an
/// input was never set, so each variable is read on its own and a refused read is part of
/// what is observed.
pub fn observe(c: *mut RacewayComponent) -> Option<Vec<u64>> {
    let mut t = 0.0;
    if unsafe { raceway_get_time(c, &mut t) } != RacewayStatus::Ok {
        return None;
    }
    let mut seen = vec![t.to_bits()];
    for i in 0..raceway_variable_count() {
        let mut vr = 0;
        unsafe { raceway_variable_at(i, &mut vr) };
        let mut v = 0.0;
        let st = unsafe { raceway_get_real(c, vr, &mut v) };
        seen.push(if st == RacewayStatus::Ok {
            v.to_bits()
        } else {
            1 << 63 | st as u64
        });
    }
    Some(seen)
}
