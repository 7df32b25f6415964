//! The component's complete mutable state, and its byte form.
//!
//! Byte layout (little-endian, no pointers): magic `RWST`, format version `u32`, scene
//! fingerprint `u64`, then each field in declaration order; a `Vec<f64>` is its length as
//! `u64` followed by the values. A state from another scene or format is refused.

use crate::error::{Error, Result};

/// Magic bytes at the start of a serialised state.
pub const MAGIC: &[u8; 4] = b"RWST";
/// Format version of the serialised state.
pub const FORMAT_VERSION: u32 = 1;

/// Everything that changes while a component runs: restoring it makes the component
/// continue bit for bit.
#[derive(Debug, PartialEq, Default)]
pub struct State {
    /// Fingerprint of the scene the state belongs to.
    pub scene_fingerprint: u64,
    /// Time, s.
    pub t: f64,
    /// Has the first step (or initialisation) happened?
    pub started: bool,
    /// Are `outputs` behind the inputs or state (set since they were computed)? The
    /// component recomputes them on the next read. Stored as bit 1 of the `started` word,
    /// so the byte layout is unchanged.
    pub outputs_stale: bool,
    /// Continuous states of the model.
    pub x: Vec<f64>,
    /// Algebraic and solver memory (warm starts, next step size, ...).
    pub aux: Vec<f64>,
    /// Input values (indexed by input slot).
    pub inputs: Vec<f64>,
    /// Input derivatives, orders 1..=3, slot-major.
    pub input_derivatives: Vec<f64>,
    /// Bit mask of the inputs set at least once.
    pub inputs_set: u64,
    /// Output values (indexed by output slot).
    pub outputs: Vec<f64>,
    /// Output time derivatives (indexed by output slot).
    pub output_derivatives: Vec<f64>,
}

impl Clone for State {
    fn clone(&self) -> Self {
        let mut s = State::default();
        s.clone_from(self);
        s
    }

    /// Field-wise, reusing this state's buffers: no allocation once the sizes match (the
    /// component's transactional `do_step` relies on it).
    fn clone_from(&mut self, o: &Self) {
        self.scene_fingerprint = o.scene_fingerprint;
        self.t = o.t;
        self.started = o.started;
        self.outputs_stale = o.outputs_stale;
        self.inputs_set = o.inputs_set;
        self.x.clone_from(&o.x);
        self.aux.clone_from(&o.aux);
        self.inputs.clone_from(&o.inputs);
        self.input_derivatives.clone_from(&o.input_derivatives);
        self.outputs.clone_from(&o.outputs);
        self.output_derivatives.clone_from(&o.output_derivatives);
    }
}

fn put_vec(out: &mut Vec<u8>, v: &[f64]) {
    out.extend_from_slice(&(v.len() as u64).to_le_bytes());
    for x in v {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

struct Reader<'a> {
    b: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8]> {
        if self.at + n > self.b.len() {
            return Err(Error::Parse {
                what: "serialised state".into(),
                message: format!("truncated at byte {} of {}", self.at, self.b.len()),
            });
        }
        let s = &self.b[self.at..self.at + n];
        self.at += n;
        Ok(s)
    }
    fn u64(&mut self) -> Result<u64> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().unwrap()))
    }
    fn f64(&mut self) -> Result<f64> {
        Ok(f64::from_bits(self.u64()?))
    }
    fn vec(&mut self) -> Result<Vec<f64>> {
        let n = self.u64()? as usize;
        if n > (self.b.len() - self.at) / 8 {
            return Err(Error::Parse {
                what: "serialised state".into(),
                message: format!("vector length {n} exceeds the data"),
            });
        }
        (0..n).map(|_| self.f64()).collect()
    }
}

impl State {
    /// Serialise to bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.byte_len());
        self.write_bytes(&mut out);
        out
    }

    /// Exact length of [`State::to_bytes`].
    pub fn byte_len(&self) -> usize {
        4 + 4
            + 8
            + 8
            + 8
            + 8
            + 8 * 6
            + 8 * (self.x.len()
                + self.aux.len()
                + self.inputs.len()
                + self.input_derivatives.len()
                + self.outputs.len()
                + self.output_derivatives.len())
    }

    /// Append the byte form to `out`.
    pub fn write_bytes(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        out.extend_from_slice(&self.scene_fingerprint.to_le_bytes());
        out.extend_from_slice(&self.t.to_le_bytes());
        let flags = self.started as u64 | (self.outputs_stale as u64) << 1;
        out.extend_from_slice(&flags.to_le_bytes());
        out.extend_from_slice(&self.inputs_set.to_le_bytes());
        put_vec(out, &self.x);
        put_vec(out, &self.aux);
        put_vec(out, &self.inputs);
        put_vec(out, &self.input_derivatives);
        put_vec(out, &self.outputs);
        put_vec(out, &self.output_derivatives);
    }

    /// Parse bytes written by [`State::to_bytes`].
    pub fn from_bytes(b: &[u8]) -> Result<State> {
        let mut r = Reader { b, at: 0 };
        if r.take(4)? != MAGIC {
            return Err(Error::Parse {
                what: "serialised state".into(),
                message: "not a raceway state (bad magic)".into(),
            });
        }
        let ver = u32::from_le_bytes(r.take(4)?.try_into().unwrap());
        if ver != FORMAT_VERSION {
            return Err(Error::Parse {
                what: "serialised state".into(),
                message: format!("format version {ver}, this build reads {FORMAT_VERSION}"),
            });
        }
        let scene_fingerprint = r.u64()?;
        let t = r.f64()?;
        let flags = r.u64()?;
        let (started, outputs_stale) = (flags & 1 != 0, flags & 2 != 0);
        let inputs_set = r.u64()?;
        let s = State {
            scene_fingerprint,
            t,
            started,
            outputs_stale,
            inputs_set,
            x: r.vec()?,
            aux: r.vec()?,
            inputs: r.vec()?,
            input_derivatives: r.vec()?,
            outputs: r.vec()?,
            output_derivatives: r.vec()?,
        };
        if r.at != b.len() {
            return Err(Error::Parse {
                what: "serialised state".into(),
                message: format!("{} trailing bytes", b.len() - r.at),
            });
        }
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_round_trip_exactly_and_refuse_damage() {
        let s = State {
            scene_fingerprint: 42,
            t: 0.125,
            started: true,
            outputs_stale: true,
            x: vec![1.0, -0.0, f64::MIN_POSITIVE],
            aux: vec![3.5],
            inputs: vec![1e-6; 11],
            input_derivatives: vec![0.0; 33],
            inputs_set: 0b111,
            outputs: vec![2.0; 80],
            output_derivatives: vec![0.5; 80],
        };
        let b = s.to_bytes();
        assert_eq!(b.len(), s.byte_len());
        let back = State::from_bytes(&b).unwrap();
        assert_eq!(back, s);
        assert!(back.x[1].is_sign_negative());
        assert!(State::from_bytes(&b[..b.len() - 1]).is_err());
        let mut bad = b.clone();
        bad[0] = b'X';
        assert!(State::from_bytes(&bad)
            .unwrap_err()
            .to_string()
            .contains("magic"));
    }
}
