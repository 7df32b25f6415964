//! The level seam as the component sees it: [`crate::seam`], re-exported here.

pub use crate::seam::*;
