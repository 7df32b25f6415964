//! FMI 2 host callbacks with no logger and no allocator, for tests that instantiate FMUs
//! in-process. Mount with `#[path = "common/fmi_callbacks.rs"] mod fmi_callbacks;` (needs the
//! `fmi` feature).

use raceway::fmi::fmi2::Fmi2CallbackFunctions;

/// The callbacks, for `fmi2Instantiate`.
pub fn callbacks() -> &'static Fmi2CallbackFunctions {
    struct Cb(Fmi2CallbackFunctions);
    // SAFETY: only NULL pointers and None callbacks inside.
    unsafe impl Sync for Cb {}
    static CB: Cb = Cb(Fmi2CallbackFunctions {
        logger: None,
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: std::ptr::null_mut(),
    });
    &CB.0
}
