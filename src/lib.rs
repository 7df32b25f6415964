//! # raceway
//!
//! Rolling-element (ball) bearing simulation as a co-simulation component.
//!
//! - [`geometry`]: bearing description, presets, materials, kinematics.
//! - [`contact`]: Hertz point contact.
//! - [`models`]: the physics ladder (quasi-static Jones–Harris, ring, ...).
//! - [`solver`]: integrators and nonlinear solvers written for this problem.
//! - [`component`]: the stepped co-simulation component, its scene and variable table.
//! - `capi` (feature `capi`): the C ABI over the component.
//! - `fmi` (feature `fmi`): FMI 2.0 / 3.0 co-simulation exports over the component.
//!
//! SI units everywhere inside; rpm, mm and degrees only at the edges.

#![warn(missing_docs)]

pub mod analysis;
pub mod calculator;
pub mod component;
pub mod contact;
pub mod counters;
pub mod error;
pub mod fsutil;
pub mod geometry;
pub mod lubrication;
pub mod models;
pub mod nesting;
#[cfg(feature = "plot")]
pub mod plot;
pub mod ratings;
pub mod report;
pub mod runner;
pub mod seam;
pub mod solver;
pub mod summary;
pub mod sweep;
pub mod units;
pub mod wear_cycles;

#[cfg(feature = "capi")]
pub mod capi;
#[cfg(any(feature = "capi", feature = "fmi"))]
mod ffi;
#[cfg(feature = "fmi")]
pub mod fmi;

pub use component::{Component, Scene};
pub use error::{Error, Result};

/// The README's Rust examples, compiled and run as doc tests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;

/// docs/rust.md's examples, compiled and run as doc tests.
#[doc = include_str!("../docs/rust.md")]
#[cfg(doctest)]
pub struct RustDocDoctests;
