//! The design calculator: the checks a bearing engineer runs beside the load distribution —
//! subsurface stress below each contact, friction moment, and the like. Plain data in, plain
//! data out; SI units inside.

pub mod check;
pub mod clearance;
pub mod duty;
pub mod friction;
pub mod lubricant;
pub mod skf_friction;
pub mod subsurface;
pub mod thermal_speed;
pub mod vi_table;
