//! The C ABI's value references of the motion inputs, in the variable table's order.
//! Mount with `#[path = "common/motion.rs"] mod motion;`.

use raceway::capi::*;

/// The motion inputs (shaft displacement, velocity and speed), in the table's order.
pub const MOTION: [u32; 11] = [
    RACEWAY_VR_SHAFT_X,
    RACEWAY_VR_SHAFT_Y,
    RACEWAY_VR_SHAFT_Z,
    RACEWAY_VR_SHAFT_RX,
    RACEWAY_VR_SHAFT_RY,
    RACEWAY_VR_SHAFT_VX,
    RACEWAY_VR_SHAFT_VY,
    RACEWAY_VR_SHAFT_VZ,
    RACEWAY_VR_SHAFT_WX,
    RACEWAY_VR_SHAFT_WY,
    RACEWAY_VR_SHAFT_OMEGA,
];
