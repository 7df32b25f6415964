//! FMI 2.0 and FMI 3.0 co-simulation exports over [`crate::component::Component`].
//!
//! This module only translates: C types to Rust, the FMI state machines, value references
//! to component calls, parameters to a scene. All physics lives in the component.
//!
//! - [`fmi2`]: the 25 common + 9 co-simulation functions of FMI 2.0
//!   (spec2 `2_1_common_api`, `4_2_co-simulation_api`);
//! - [`fmi3`]: all 75 functions of `fmi3Functions.h` (FMI 3.0.2), the model-exchange,
//!   scheduled-execution, clock and configuration ones as logged `fmi3Error` stubs;
//! - [`model_description`]: `modelDescription.xml` for both versions, the variable table of
//!   `docs/fmi.md`, and the GUID / instantiation token shared by binary and XML, all
//!   generated from `component::variables`;
//! - `instance`: one instance type for both versions (state masks after the Reference FMUs'
//!   `fmi2Functions.c` / `fmi3Functions.c`, logging, FMU state and its byte form);
//! - `params`: how the `PARAMETERS` map onto a scene.
//!
//! Rules kept here (see docs/physics.md §C4): every export runs inside
//! `catch_unwind`; no global mutable state; callbacks are `Option<extern fn>` copied at
//! instantiation; the FMI 2 logger is called with `"%s"`; strings are copied; the FMI 2
//! resource location is a percent-decoded `file:` URI and FMI 3's `resourcePath` may be NULL.

pub mod fmi2;
pub mod fmi3;
mod instance;
pub mod model_description;
mod params;

pub use instance::Status;
pub use model_description::GUID;

#[cfg(test)]
mod state_tests;
#[cfg(test)]
mod tests;
