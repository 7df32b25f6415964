//! Handles of the C ABI: the pointers a C host holds are not addresses but numbers issued
//! by a registry, never reused, so a freed, foreign or doubly freed handle is found in no
//! table and refused instead of being dereferenced (no undefined behaviour).
//!
//! Each live object also carries a busy mark, set for the length of one call: a second
//! call on the same handle from another thread at the same time is refused, and a handle
//! freed while another thread is inside a call on it is left alone.
//!
//! Looking a handle up takes a mutex and a hash-map probe: no heap allocation. The map
//! hashes the handle number with one multiplication ([`IdHasher`]): the numbers are issued
//! here, not chosen by a caller, so the standard library's DoS-resistant SipHash buys
//! nothing, and a host calls through a handle three times per macro step.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::sync::{Mutex, MutexGuard};

/// Hash of a handle number: its multiple of 16 times an odd constant (Fibonacci hashing):
/// consecutive handles differ in the low bits (the map's bucket index: the product is a
/// bijection modulo every power of two) and in the top bits (its control byte).
#[derive(Default)]
pub(crate) struct IdHasher(u64);

impl Hasher for IdHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        // Only `usize` keys are hashed here; any other key folds in byte by byte.
        for &b in bytes {
            self.0 = (self.0.rotate_left(8) ^ u64::from(b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        }
    }
    fn write_usize(&mut self, i: usize) {
        self.0 = ((i as u64) >> 4).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

type IdMap<V> = HashMap<usize, V, BuildHasherDefault<IdHasher>>;

/// One registered object: its box (as a raw pointer) and whether a call is using it.
struct Entry<T> {
    ptr: *mut T,
    busy: bool,
}

struct Table<T> {
    next: usize,
    live: Option<IdMap<Entry<T>>>,
}

/// A table of live objects of one type, keyed by handle number.
pub(crate) struct Registry<T> {
    table: Mutex<Table<T>>,
}

// SAFETY: the raw pointers are owned boxes moved in and out under the mutex; each object
// is used by one thread at a time (the busy mark).
unsafe impl<T: Send> Sync for Registry<T> {}

/// Why a handle was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Refusal {
    /// Not a handle of a live object (never issued, freed, or of another kind).
    Unknown,
    /// Another call is using the object right now.
    Busy,
}

/// Exclusive use of a registered object for one call; released on drop.
pub(crate) struct Lease<'a, T> {
    registry: &'a Registry<T>,
    id: usize,
    ptr: *mut T,
}

impl<T> Registry<T> {
    /// An empty registry; handle numbers start at `first` and step by 16 (so they look
    /// like aligned pointers and never equal NULL). Distinct `first` values per registry
    /// (mod 16) keep an instance handle from ever being taken for a state handle.
    pub(crate) const fn new(first: usize) -> Registry<T> {
        Registry {
            table: Mutex::new(Table {
                next: first,
                live: None,
            }),
        }
    }

    fn lock(&self) -> MutexGuard<'_, Table<T>> {
        // A panic never happens while the lock is held; recover anyway.
        self.table.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Register `obj`; its handle number.
    pub(crate) fn insert(&self, obj: Box<T>) -> usize {
        let mut t = self.lock();
        let id = t.next;
        t.next = t.next.wrapping_add(16);
        let ptr = Box::into_raw(obj);
        t.live
            .get_or_insert_with(IdMap::default)
            .insert(id, Entry { ptr, busy: false });
        id
    }

    /// Exclusive use of object `id` until the lease drops.
    pub(crate) fn acquire(&self, id: usize) -> Result<Lease<'_, T>, Refusal> {
        let mut t = self.lock();
        let e = t
            .live
            .as_mut()
            .and_then(|m| m.get_mut(&id))
            .ok_or(Refusal::Unknown)?;
        if e.busy {
            return Err(Refusal::Busy);
        }
        e.busy = true;
        Ok(Lease {
            registry: self,
            id,
            ptr: e.ptr,
        })
    }

    /// Unregister object `id` and give it back (to drop). Refused when unknown or busy.
    pub(crate) fn remove(&self, id: usize) -> Result<Box<T>, Refusal> {
        let mut t = self.lock();
        let m = t.live.as_mut().ok_or(Refusal::Unknown)?;
        match m.get(&id) {
            None => Err(Refusal::Unknown),
            Some(e) if e.busy => Err(Refusal::Busy),
            Some(_) => {
                let e = m.remove(&id).expect("present");
                // SAFETY: the pointer came from `Box::into_raw` in `insert` and left the
                // table just now, so no lease refers to it.
                Ok(unsafe { Box::from_raw(e.ptr) })
            }
        }
    }

    /// Number of live objects.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.lock().live.as_ref().map_or(0, IdMap::len)
    }
}

impl<T> Lease<'_, T> {
    /// The object.
    pub(crate) fn get(&mut self) -> &mut T {
        // SAFETY: the object stays registered (remove refuses busy entries) and this lease
        // is its only user until it drops.
        unsafe { &mut *self.ptr }
    }
}

impl<T> Drop for Lease<'_, T> {
    fn drop(&mut self) {
        let mut t = self.registry.lock();
        if let Some(e) = t.live.as_mut().and_then(|m| m.get_mut(&self.id)) {
            e.busy = false;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn handles_are_never_reused_and_refused_after_removal_or_while_busy() {
        let r: Registry<u32> = Registry::new(0x1000);
        let a = r.insert(Box::new(1));
        let b = r.insert(Box::new(2));
        assert_ne!(a, b);
        assert_eq!(*r.acquire(a).unwrap().get(), 1);
        {
            let _held = r.acquire(a).unwrap();
            assert_eq!(r.acquire(a).err(), Some(Refusal::Busy));
            assert_eq!(r.remove(a).err(), Some(Refusal::Busy));
        }
        assert_eq!(*r.remove(a).unwrap(), 1);
        assert_eq!(r.remove(a).err(), Some(Refusal::Unknown));
        assert_eq!(r.acquire(a).err(), Some(Refusal::Unknown));
        let c = r.insert(Box::new(3));
        assert!(c != a && c != b, "a freed number is never issued again");
        assert_eq!(r.acquire(a + 1).err(), Some(Refusal::Unknown));
        assert_eq!(r.len(), 2);
    }
}
