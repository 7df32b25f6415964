//! The foreign-function boundary shared by the C ABI ([`crate::capi`]) and both FMI
//! versions ([`crate::fmi`]): what every exported call does with its arguments before any
//! of the library sees them, and with panics after.
//!
//! - [`handles`]: handles are numbers from a registry, never addresses; a freed, foreign
//!   or doubly freed handle is refused, never dereferenced; one call at a time per object.
//! - [`slice`], [`slice_mut`]: a pointer and a count become a slice only when the pointer
//!   is not NULL (or the count is 0) and the length fits in memory.
//! - [`str_arg`], [`c_string`]: C strings in (copied) and out (interior NULs replaced).
//! - [`guarded`], [`catch`], [`panic_text`]: no panic crosses the boundary; a caught panic
//!   poisons the object it happened in (its state may be half-updated), so the faces refuse
//!   every later call on it but the free.
//!
//! Each face maps an [`ArgError`] or a caught panic to its own status (C: `NullPointer`,
//! `InvalidArgument`, `Panic`; FMI: `Error`) and keeps the message text given here.
//! Nothing here knows any physics.

pub(crate) mod handles;

use std::ffi::{c_char, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// A pointer-and-count argument that cannot be a slice.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum ArgError {
    /// The pointer is NULL while values were announced.
    Null {
        /// The argument's name.
        name: String,
        /// How many values were announced.
        n: usize,
    },
    /// More values than fit in memory.
    TooLong {
        /// The argument's name.
        name: String,
        /// How many values were announced.
        n: usize,
    },
}

impl std::fmt::Display for ArgError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ArgError::Null { name, n } => {
                write!(f, "`{name}` is NULL but {n} values were announced")
            }
            ArgError::TooLong { name, n } => {
                write!(f, "`{name}`: {n} values announced, more than fit in memory")
            }
        }
    }
}

fn check<T>(null: bool, n: usize, name: &str) -> Result<bool, ArgError> {
    if n == 0 {
        return Ok(false);
    }
    if null {
        return Err(ArgError::Null {
            name: name.into(),
            n,
        });
    }
    if n > isize::MAX as usize / std::mem::size_of::<T>().max(1) {
        return Err(ArgError::TooLong {
            name: name.into(),
            n,
        });
    }
    Ok(true)
}

/// The `n` values at `p` (argument `name`); `n == 0` gives an empty slice whatever `p`.
///
/// # Safety
/// `p` is NULL or points to `n` valid values that outlive `'a`.
pub(crate) unsafe fn slice<'a, T>(p: *const T, n: usize, name: &str) -> Result<&'a [T], ArgError> {
    if check::<T>(p.is_null(), n, name)? {
        // SAFETY: non-NULL, length checked against isize::MAX, validity promised.
        Ok(unsafe { std::slice::from_raw_parts(p, n) })
    } else {
        Ok(&[])
    }
}

/// The `n` writable values at `p`; see [`slice`].
///
/// # Safety
/// `p` is NULL or points to `n` writable values that outlive `'a`, used by no one else.
pub(crate) unsafe fn slice_mut<'a, T>(
    p: *mut T,
    n: usize,
    name: &str,
) -> Result<&'a mut [T], ArgError> {
    if check::<T>(p.is_null(), n, name)? {
        // SAFETY: as in `slice`.
        Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
    } else {
        Ok(&mut [])
    }
}

/// A C string argument, copied; `None` when NULL or not UTF-8.
///
/// # Safety
/// `p` is NULL or a NUL-terminated string.
#[cfg_attr(not(feature = "fmi"), allow(dead_code))]
pub(crate) unsafe fn str_arg(p: *const c_char) -> Option<String> {
    if p.is_null() {
        None
    } else {
        // SAFETY: non-NULL and NUL-terminated by the caller's promise.
        unsafe { CStr::from_ptr(p) }
            .to_str()
            .ok()
            .map(str::to_string)
    }
}

/// A C string from a Rust one (an interior NUL, impossible in our messages, becomes `?`).
pub(crate) fn c_string(s: &str) -> CString {
    CString::new(s.replace('\0', "?")).unwrap_or_default()
}

/// The text of a panic payload.
pub(crate) fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    crate::error::panic_message(payload).unwrap_or_else(|| "unknown panic".into())
}

/// Run `f`; `on_panic` if it panics (for calls with no object to poison).
pub(crate) fn guarded<T>(on_panic: T, f: impl FnOnce() -> T) -> T {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or(on_panic)
}

/// Run `f` on an object that has not been poisoned; a panic in `f` poisons it. `Err`
/// holds the message: refused (poisoned before) or the panic's text.
pub(crate) fn catch<T>(poisoned: &mut bool, f: impl FnOnce() -> T) -> Result<T, Caught> {
    if *poisoned {
        return Err(Caught::Poisoned);
    }
    catch_unwind(AssertUnwindSafe(f)).map_err(|payload| {
        *poisoned = true;
        Caught::Panicked(panic_text(payload.as_ref()))
    })
}

/// Why [`catch`] did not return `f`'s value.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Caught {
    /// An earlier panic poisoned the object: the call was refused.
    Poisoned,
    /// `f` panicked (its text); the object is poisoned now.
    Panicked(String),
}

impl std::fmt::Display for Caught {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Caught::Poisoned => write!(
                f,
                "refused: the instance was poisoned by an earlier internal error; free it"
            ),
            Caught::Panicked(t) => write!(
                f,
                "internal error (panic: {t}); the instance is poisoned, free it"
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slices_refuse_null_and_impossible_lengths_and_accept_empty() {
        let v = [1.0f64, 2.0];
        assert_eq!(unsafe { slice(v.as_ptr(), 2, "v") }.unwrap(), &v);
        assert!(unsafe { slice(std::ptr::null::<f64>(), 0, "v") }
            .unwrap()
            .is_empty());
        let e = unsafe { slice(std::ptr::null::<f64>(), 3, "vr") }.unwrap_err();
        assert_eq!(e.to_string(), "`vr` is NULL but 3 values were announced");
        let e = unsafe { slice(v.as_ptr(), usize::MAX / 2, "v") }.unwrap_err();
        assert!(matches!(e, ArgError::TooLong { .. }), "{e}");
    }

    #[test]
    fn a_panic_poisons_and_later_calls_are_refused() {
        let mut poisoned = false;
        assert_eq!(catch(&mut poisoned, || 1), Ok(1));
        let r = catch(&mut poisoned, || -> i32 { panic!("boom") });
        assert_eq!(r, Err(Caught::Panicked("boom".into())));
        assert!(poisoned);
        assert_eq!(catch(&mut poisoned, || 2), Err(Caught::Poisoned));
        assert!(Caught::Poisoned.to_string().contains("free it"));
    }
}
