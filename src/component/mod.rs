//! The co-simulation component: created from a scene, stepped by a host with
//! `do_step(t, h)`, sub-stepping its own physics inside; read with `get_real`.
//!
//! This is the one contract the C ABI (`src/capi`) and the FMUs (`src/fmi`) wrap. Every
//! call either succeeds or returns an error that names the cause and leaves the component
//! exactly as it was.

pub mod scene;
pub mod state;
pub mod variables;

pub use scene::{InputRule, Level, Method, Scene};
pub use state::State;
pub use variables::{Causality, Variable};

use crate::error::{Error, Result};
use crate::geometry::Bearing;

/// Cost counters of the internal integration.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Right-hand-side evaluations.
    pub rhs: u64,
    /// Jacobian evaluations.
    pub jacobians: u64,
    /// LU factorisations.
    pub factorizations: u64,
    /// Accepted internal steps.
    pub accepted: u64,
    /// Rejected internal steps.
    pub rejected: u64,
}

/// Number of variables in the table.
pub fn n_variables() -> usize {
    variables::all().count()
}

fn index_of(vr: u32) -> Option<usize> {
    variables::all().position(|v| v.vr == vr)
}

/// A running bearing.
#[derive(Debug, Clone)]
pub struct Component {
    scene: Scene,
    bearing: Bearing,
    state: State,
    stats: Stats,
}

/// FNV-1a over bytes: a stable fingerprint (not cryptographic).
pub fn fingerprint(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= *b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

impl Component {
    /// Create from scene text (TOML or JSON).
    pub fn from_text(text: &str) -> Result<Component> {
        Component::new(Scene::from_text(text)?)
    }

    /// Create from a scene. A bad scene is refused with a message naming the field.
    pub fn new(scene: Scene) -> Result<Component> {
        let bearing = scene.validate()?;
        let n = n_variables();
        let fp = fingerprint(serde_json::to_string(&scene).unwrap_or_default().as_bytes());
        let mut state = State {
            scene_fingerprint: fp,
            inputs: vec![0.0; n],
            input_derivatives: vec![0.0; 3 * n],
            outputs: vec![0.0; n],
            output_derivatives: vec![0.0; n],
            ..State::default()
        };
        let causality = scene.model.causality;
        for (name, value) in &scene.inputs.initial {
            let v = variables::by_name(name).expect("validated");
            let i = index_of(v.vr).expect("in table");
            state.inputs[i] = *value;
            state.inputs_set |= 1 << input_bit(v.vr);
        }
        let _ = causality;
        Ok(Component {
            scene,
            bearing,
            state,
            stats: Stats::default(),
        })
    }

    /// The scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }
    /// The validated bearing.
    pub fn bearing(&self) -> &Bearing {
        &self.bearing
    }
    /// The causality.
    pub fn causality(&self) -> Causality {
        self.scene.model.causality
    }
    /// Current time, s.
    pub fn time(&self) -> f64 {
        self.state.t
    }
    /// Cost counters since creation.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Set an input by value reference.
    pub fn set_real(&mut self, vr: u32, value: f64) -> Result<()> {
        let v = variables::by_vr(vr)
            .ok_or_else(|| Error::invalid("value reference", vr, "a variable of the table"))?;
        if !v.is_input(self.causality()) {
            return Err(Error::CallOrder {
                call: "set_real",
                reason: format!("`{}` is not an input of this causality", v.name),
            });
        }
        if !value.is_finite() {
            return Err(Error::invalid(v.name, value, "a finite number"));
        }
        let i = index_of(vr).expect("in table");
        self.state.inputs[i] = value;
        self.state.inputs_set |= 1 << input_bit(vr);
        Ok(())
    }

    /// Set the `order`-th time derivative (1..=3) of an input, used with
    /// [`InputRule::Derivatives`]. Derivatives are reset to zero after each step.
    pub fn set_input_derivative(&mut self, vr: u32, order: u32, value: f64) -> Result<()> {
        let v = variables::by_vr(vr)
            .ok_or_else(|| Error::invalid("value reference", vr, "a variable of the table"))?;
        if !v.is_input(self.causality()) {
            return Err(Error::CallOrder {
                call: "set_input_derivative",
                reason: format!("`{}` is not an input", v.name),
            });
        }
        if !(1..=3).contains(&order) {
            return Err(Error::invalid("order", order, "1, 2 or 3"));
        }
        if !value.is_finite() {
            return Err(Error::invalid(v.name, value, "a finite number"));
        }
        let i = index_of(vr).expect("in table");
        self.state.input_derivatives[3 * i + (order as usize - 1)] = value;
        Ok(())
    }

    /// Get an input or output by value reference.
    pub fn get_real(&self, vr: u32) -> Result<f64> {
        let v = variables::by_vr(vr)
            .ok_or_else(|| Error::invalid("value reference", vr, "a variable of the table"))?;
        let i = index_of(vr).expect("in table");
        Ok(if v.is_input(self.causality()) {
            self.state.inputs[i]
        } else {
            self.state.outputs[i]
        })
    }

    /// Get the time derivative (order 1) of an output at the current time.
    pub fn get_output_derivative(&self, vr: u32, order: u32) -> Result<f64> {
        let v = variables::by_vr(vr)
            .ok_or_else(|| Error::invalid("value reference", vr, "a variable of the table"))?;
        if !v.is_output(self.causality()) {
            return Err(Error::invalid("value reference", vr, "an output"));
        }
        if order != 1 {
            return Err(Error::invalid("order", order, "1"));
        }
        Ok(self.state.output_derivatives[index_of(vr).expect("in table")])
    }

    /// Advance from `t` to `t + h`. On error the state is unchanged.
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<()> {
        if !(h.is_finite() && h > 0.0) {
            return Err(Error::invalid("h", h, "a finite number > 0"));
        }
        if !t.is_finite() {
            return Err(Error::invalid("t", t, "a finite number"));
        }
        let tol = 1e-9 * (1.0 + self.state.t.abs());
        if self.state.started && (t - self.state.t).abs() > tol {
            return Err(Error::CallOrder {
                call: "do_step",
                reason: format!(
                    "t = {t} but the component is at {} (time must not jump or run backwards)",
                    self.state.t
                ),
            });
        }
        self.check_inputs_set()?;
        // STUB physics: a linear spring, replaced by the model levels.
        let k = 1e8;
        let i = |vr| index_of(vr).unwrap();
        let (x, y) = (self.state.inputs[i(1)], self.state.inputs[i(2)]);
        self.state.outputs[i(101)] = -k * x;
        self.state.outputs[i(102)] = -k * y;
        for d in 0..5 {
            self.state.outputs[i(variables::VR_K0 + 6 * d as u32)] = k;
        }
        self.state.t = t + h;
        self.state.started = true;
        Ok(())
    }

    fn check_inputs_set(&self) -> Result<()> {
        let missing: Vec<&str> = variables::SCALARS
            .iter()
            .filter(|v| {
                v.is_input(self.causality()) && self.state.inputs_set & (1 << input_bit(v.vr)) == 0
            })
            .map(|v| v.name)
            .collect();
        if missing.is_empty() {
            Ok(())
        } else {
            Err(Error::CallOrder {
                call: "do_step",
                reason: format!("inputs never set: {}", missing.join(", ")),
            })
        }
    }

    /// A copy of the complete state.
    pub fn get_state(&self) -> State {
        self.state.clone()
    }

    /// Restore a state taken from this component (or one built from the same scene).
    pub fn set_state(&mut self, s: &State) -> Result<()> {
        if s.scene_fingerprint != self.state.scene_fingerprint
            || s.x.len() != self.state.x.len()
            || s.aux.len() != self.state.aux.len()
            || s.inputs.len() != self.state.inputs.len()
            || s.outputs.len() != self.state.outputs.len()
        {
            return Err(Error::CallOrder {
                call: "set_state",
                reason: "the state belongs to another scene".into(),
            });
        }
        self.state.clone_from(s);
        Ok(())
    }

    /// The state as bytes (versioned, no pointers).
    pub fn serialize_state(&self) -> Vec<u8> {
        self.state.to_bytes()
    }

    /// Restore a state from bytes written by [`Component::serialize_state`].
    pub fn deserialize_state(&mut self, bytes: &[u8]) -> Result<()> {
        let s = State::from_bytes(bytes)?;
        self.set_state(&s)
    }

    /// Directional derivative of outputs `unknowns` with respect to inputs `knowns` along
    /// `seed` (`out = J seed`), at the current state: the stiffness and damping matrices
    /// (and, for `shaft.omega`, a finite difference).
    pub fn directional_derivative(
        &self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
        out: &mut [f64],
    ) -> Result<()> {
        if knowns.len() != seed.len() || unknowns.len() != out.len() {
            return Err(Error::invalid(
                "directional derivative",
                "lengths",
                "seed like knowns, out like unknowns",
            ));
        }
        // Forces and moments: J = -K (displacement knowns), -C (velocity knowns), from the
        // K and C outputs; other unknowns and knowns contribute zero.
        for (o, &u) in out.iter_mut().zip(unknowns) {
            let row = [101u32, 102, 103, 104, 105].iter().position(|&f| f == u);
            *o = 0.0;
            for (&k, &s) in knowns.iter().zip(seed) {
                if variables::by_vr(k).is_none() {
                    return Err(Error::invalid(
                        "directional derivative known",
                        k,
                        "a variable of the table",
                    ));
                }
                let Some(r) = row else { continue };
                if (1..=5).contains(&k) {
                    *o -= self.state.outputs
                        [index_of(variables::VR_K0 + 5 * r as u32 + (k - 1)).unwrap()]
                        * s;
                } else if (6..=10).contains(&k) {
                    *o -= self.state.outputs
                        [index_of(variables::VR_C0 + 5 * r as u32 + (k - 6)).unwrap()]
                        * s;
                }
            }
            if variables::by_vr(u).is_none() {
                return Err(Error::invalid(
                    "directional derivative unknown",
                    u,
                    "a variable of the table",
                ));
            }
        }
        Ok(())
    }
}

/// Bit of an input in the "inputs set" mask: its position among the scalar variables.
fn input_bit(vr: u32) -> u32 {
    variables::SCALARS
        .iter()
        .position(|v| v.vr == vr)
        .unwrap_or(63) as u32
}
