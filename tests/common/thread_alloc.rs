//! A per-thread counting global allocator (tests run on threads; only the calling thread
//! counts). A test file mounts it with
//! `#[path = "common/thread_alloc.rs"] mod thread_alloc;` and
//! `#[global_allocator] static A: thread_alloc::Counting = thread_alloc::Counting;`.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

thread_local! {
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

/// Counts every allocation and reallocation of the calling thread, then defers to
/// [`System`].
pub struct Counting;

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, n: usize) -> *mut u8 {
        let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(p, l, n) }
    }
}

/// Allocations (and reallocations) the calling thread has made so far.
pub fn allocations() -> usize {
    ALLOCS.with(|a| a.get())
}
