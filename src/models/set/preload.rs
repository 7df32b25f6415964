//! Ring temperatures of a set: how the rings' radial thermal growth changes the rows'
//! clearance and hence a rigid preload (docs/physics.md §S1).
//!
//! A set is assembled (its preload offsets set) at the clearance's reference temperature,
//! [`REFERENCE_C`]. In service the rings of each row grow radially: the diametral clearance
//! changes by `ΔPd = α_o ΔT_o Do − α_i ΔT_i Di − 2 α_b ΔT_b D` (the calculator's operating
//! clearance, [`operating_clearance`], whose formulas are reused here, not repeated). A row
//! then runs with the clearance `Pd + ΔPd` and the free contact angle the grooves give it
//! ([`with_clearance`]: `cos a0 = 1 − Pd/(2A)`), while its rings stay where the clamp put
//! them axially: the axial distance between its groove-curvature centres, `A sin a0 + δa`,
//! is unchanged, so the row's preload offset becomes
//! `δa' = δa + A sin a0 − A sin a0'`. A warmer inner ring closes the clearance, so a rigid
//! preload rises; the rows of a spring preload slide to keep the spring's force (it changes
//! only by the spring's stiffness times the slide).
//!
//! Left out: the shaft's and housing's axial growth between the rows (spacers), the fits'
//! change with the shaft's and housing's own temperatures (as in the calculator), and the
//! inner ring's centrifugal growth. Ball rows only: a roller row refuses a temperature other
//! than the reference.

use crate::calculator::clearance::{
    operating_clearance, with_clearance, ClearanceInputs, REFERENCE_C,
};
use crate::error::{Error, Result};
use crate::geometry::element::Element;
use crate::geometry::Bearing;
use serde::Serialize;

/// The temperatures of a set's rings in service, °C (the same for every row).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RingTemperatures {
    /// Inner rings, °C.
    pub inner_c: f64,
    /// Outer rings, °C.
    pub outer_c: f64,
    /// Rolling elements, °C (`None`: the mean of the rings', as the calculator takes it).
    pub ball_c: Option<f64>,
}

impl Default for RingTemperatures {
    /// Every part at the reference temperature: the set as assembled.
    fn default() -> Self {
        RingTemperatures {
            inner_c: REFERENCE_C,
            outer_c: REFERENCE_C,
            ball_c: None,
        }
    }
}

impl RingTemperatures {
    /// Inner rings `dt` kelvin warmer than the outer rings, which sit at the reference.
    pub fn inner_warmer(dt: f64) -> Self {
        RingTemperatures {
            inner_c: REFERENCE_C + dt,
            ..Default::default()
        }
    }

    /// Every part at the reference temperature (nothing changes).
    pub fn is_reference(&self) -> bool {
        self.inner_c == REFERENCE_C
            && self.outer_c == REFERENCE_C
            && self.ball_c.is_none_or(|b| b == REFERENCE_C)
    }

    /// Refuse non-finite or unphysical temperatures, naming the field.
    pub fn validate(&self) -> Result<()> {
        for (f, v) in [
            ("set.temperatures.inner_c", self.inner_c),
            ("set.temperatures.outer_c", self.outer_c),
            (
                "set.temperatures.ball_c",
                self.ball_c.unwrap_or(REFERENCE_C),
            ),
        ] {
            if !(v.is_finite() && (-273.15..=1000.0).contains(&v)) {
                return Err(Error::invalid(f, v, "a temperature in [-273.15, 1000] °C"));
            }
        }
        Ok(())
    }
}

/// A row's bearing at temperatures `t` and the change of its preload offset (module docs),
/// m. `row` names the row in a refusal.
pub(crate) fn row_at(b: &Bearing, t: &RingTemperatures, row: usize) -> Result<(Bearing, f64)> {
    if t.is_reference() {
        return Ok((b.clone(), 0.0));
    }
    if matches!(b.element, Element::Roller(_)) {
        return Err(Error::invalid(
            "set.temperatures",
            format!(
                "inner {} °C, outer {} °C on row {row} ({})",
                t.inner_c, t.outer_c, b.name
            ),
            format!(
                "the reference {REFERENCE_C} °C for roller rows (the rings' thermal growth is \
                 applied to ball rows only)"
            ),
        ));
    }
    let c = operating_clearance(
        b,
        &ClearanceInputs {
            inner_c: t.inner_c,
            outer_c: t.outer_c,
            ball_c: t.ball_c,
            ..Default::default()
        },
    )?;
    let hot = with_clearance(b, b.pd + c.from_temperatures).map_err(|e| {
        Error::invalid(
            "set.temperatures",
            format!("inner {} °C, outer {} °C", t.inner_c, t.outer_c),
            format!("temperatures row {row} ({}) can take: {e}", b.name),
        )
    })?;
    let (a1, _) = b.reference_groove_offset();
    let (a1_hot, _) = hot.reference_groove_offset();
    Ok((hot, a1 - a1_hot))
}
