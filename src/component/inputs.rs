//! Inputs: setting them (checked all or nothing against their plausibility limits) and
//! how they move inside a step under the scene's rule (hold, velocity, derivatives).

use super::level::Motion;
use super::system::RingBody;
use super::variables::SCALARS;
use super::{
    index_of, variables, Causality, Component, InputRule, State, I_OMEGA, I_Q, I_V, N_INPUT_SLOTS,
};
use crate::error::{Error, Result};

impl Component {
    /// Set an input by value reference. Setting a value clears that input's derivatives.
    pub fn set_real(&mut self, vr: u32, value: f64) -> Result<()> {
        let i = self.input_slot("set_real", vr, value)?;
        self.write_input(i, value);
        Ok(())
    }

    pub(super) fn write_input(&mut self, i: usize, value: f64) {
        self.state.inputs[i] = value;
        self.state.input_derivatives[3 * i..3 * i + 3].fill(0.0);
        self.state.inputs_set |= 1 << i;
        self.state.outputs_stale = true;
    }

    /// Set `values[k]` to `vrs[k]`, all or nothing: every pair is checked before any is
    /// written (no copy of the state, no allocation). A refusal gives the index of the
    /// first refused pair with its error.
    pub fn set_reals(
        &mut self,
        vrs: &[u32],
        values: &[f64],
    ) -> std::result::Result<(), (usize, Error)> {
        same_length(vrs, values)?;
        for (k, (&vr, &v)) in vrs.iter().zip(values).enumerate() {
            self.input_slot("set_real", vr, v).map_err(|e| (k, e))?;
        }
        for (&vr, &v) in vrs.iter().zip(values) {
            let i = index_of(vr).expect("checked above");
            self.write_input(i, v);
        }
        Ok(())
    }

    /// Set the `order`-th derivatives of several inputs, all or nothing, as
    /// [`Component::set_reals`].
    pub fn set_input_derivatives(
        &mut self,
        vrs: &[u32],
        order: u32,
        values: &[f64],
    ) -> std::result::Result<(), (usize, Error)> {
        same_length(vrs, values)?;
        for (k, (&vr, &v)) in vrs.iter().zip(values).enumerate() {
            self.derivative_slot(vr, order, v).map_err(|e| (k, e))?;
        }
        for (&vr, &v) in vrs.iter().zip(values) {
            let i = index_of(vr).expect("checked above");
            self.state.input_derivatives[3 * i + (order as usize - 1)] = v;
            self.state.outputs_stale = true;
        }
        Ok(())
    }

    /// The slot of input `vr` if `call` may set it to `value` (an input of this causality,
    /// a finite value).
    pub(super) fn input_slot(&self, call: &'static str, vr: u32, value: f64) -> Result<usize> {
        let v = variables::by_vr(vr)
            .ok_or_else(|| Error::invalid("value reference", vr, "a variable of the table"))?;
        if !v.is_input(self.causality()) {
            return Err(Error::CallOrder {
                call,
                reason: format!("`{}` is not an input of this causality", v.name),
            });
        }
        let i = index_of(vr).expect("in table");
        if call == "set_real" {
            // By slot (no string compare; `slot_limits_match_the_names`), the message by name
            // only on a refusal.
            if !self.limits.allows_slot(i, value) {
                self.limits.check(v.name, v.name, value)?;
            }
        } else if !value.is_finite() {
            return Err(Error::invalid(v.name, value, "a finite number"));
        }
        Ok(i)
    }

    /// Set the `order`-th time derivative (1..=3) of an input at the start of the next
    /// step, used with [`InputRule::Derivatives`]. They hold until the input is set again.
    pub fn set_input_derivative(&mut self, vr: u32, order: u32, value: f64) -> Result<()> {
        let i = self.derivative_slot(vr, order, value)?;
        self.state.input_derivatives[3 * i + (order as usize - 1)] = value;
        self.state.outputs_stale = true;
        Ok(())
    }

    pub(super) fn derivative_slot(&self, vr: u32, order: u32, value: f64) -> Result<usize> {
        let i = self.input_slot("set_input_derivative", vr, value)?;
        if !(1..=3).contains(&order) {
            return Err(Error::invalid("order", order, "1, 2 or 3"));
        }
        Ok(i)
    }

    /// Refuse a step whose inputs, moved along the scene's rule to the step end `h`, leave
    /// their plausibility limits (a velocity or derivative that carries a position off).
    pub(super) fn check_inputs_at(&self, h: f64) -> Result<()> {
        let c = self.causality();
        // Every input of either causality sits below N_INPUT_SLOTS (slots_match_the_table).
        for (i, v) in SCALARS[..N_INPUT_SLOTS].iter().enumerate() {
            if !v.is_input(c) {
                continue;
            }
            let u = input_at(&self.state, i, h, self.scene.inputs.rule);
            if self.limits.allows_slot(i, u) {
                continue;
            }
            self.limits
                .check(&format!("{} at the step end t + h", v.name), v.name, u)?;
        }
        Ok(())
    }
}

/// A bulk call's value references and values pair up.
pub(super) fn same_length(vrs: &[u32], values: &[f64]) -> std::result::Result<(), (usize, Error)> {
    if vrs.len() == values.len() {
        return Ok(());
    }
    let e = Error::invalid("values", values.len(), "as many values as value references");
    Err((0, e))
}

/// Input `i` at `s` after the step start under `rule`.
///
/// Inlined: every right-hand side reads the speed and, load-driven, one load per ring
/// coordinate through it; inlined, a held input is a plain load and the `match` on the
/// rule is one predictable branch (the call and its bounds check cost more than the read).
#[inline]
pub(super) fn input_at(st: &State, i: usize, s: f64, rule: InputRule) -> f64 {
    let u = st.inputs[i];
    match rule {
        InputRule::Hold => u,
        InputRule::Velocity => {
            if (I_Q..I_Q + 5).contains(&i) {
                u + st.inputs[i - I_Q + I_V] * s
            } else {
                u
            }
        }
        InputRule::Derivatives => {
            let d = &st.input_derivatives[3 * i..3 * i + 3];
            u + s * (d[0] + s * (d[1] / 2.0 + s * d[2] / 6.0))
        }
    }
}

/// The ring's motion at `s` after the step start: from the inputs (motion-driven) or from
/// the states `y` (load-driven).
///
/// Always inlined into the right-hand side (built in place, not returned through memory:
/// its arguments and the copy-out cost as much as the few loads), with the ring's states
/// read from slices cut once (no bounds check per coordinate).
#[inline(always)]
pub(super) fn motion_at(
    st: &State,
    rule: InputRule,
    s: f64,
    c: Causality,
    ring: Option<&RingBody>,
    nl: usize,
    y: &[f64],
) -> Motion {
    let mut m = Motion {
        omega: input_at(st, I_OMEGA, s, rule),
        ..Motion::default()
    };
    match (c, ring) {
        (Causality::Load, Some(r)) => {
            let nd = r.dofs.len();
            let (q, v) = y[nl..nl + 2 * nd].split_at(nd);
            for ((&d, &q), &v) in r.dofs.iter().zip(q).zip(v) {
                m.q[d] = q;
                m.v[d] = v;
            }
        }
        _ => {
            for k in 0..5 {
                m.q[k] = input_at(st, I_Q + k, s, rule);
                m.v[k] = input_at(st, I_V + k, s, rule);
            }
        }
    }
    m
}
