//! Field declarations as the component sees them: [`crate::seam::fields`], re-exported
//! here.

pub use crate::seam::fields::*;
