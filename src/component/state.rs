//! The component's complete mutable state, and its byte form.
//!
//! Byte layout, format 4 (little-endian, no pointers): magic `RWST`, format version `u32`,
//! scene fingerprint `u64`, time `f64`, flags `u64` (bit 0 started, bit 1 outputs stale,
//! bit 2 force derivatives pending, bit 3 stiffness and damping pending), inputs-set mask `u64`,
//! then six vectors (`x`, `aux`, `inputs`, `input_derivatives`, `outputs`,
//! `output_derivatives`), each its length as `u64` followed by the values; last, a
//! checksum `u64`: FNV-1a (Fowler, Noll and Vo; IETF draft-eastlake-fnv) over every byte
//! before it. Each step of FNV-1a (xor a byte, multiply by an odd prime modulo 2^64) is a
//! bijection of the running hash, so a change confined to one byte always changes the sum;
//! wider damage escapes it with probability about 2^-64.
//!
//! Reading checks, in this order and before any value is used: the length, the magic,
//! the version (another version is refused by number, not read), the checksum, the
//! structure, and that every number is finite. The component then checks that the state
//! belongs to its scene and its inputs are inputs it accepts ([`super::Component::check_state`]).

use crate::error::{Error, Result};

/// Magic bytes at the start of a serialised state.
pub const MAGIC: &[u8; 4] = b"RWST";
/// Format version of the serialised state (2: with checksum and value checks; 3: the
/// force derivatives computed when read, flag bit 2 and the outputs' input offset in `aux`;
/// 4: the stiffness and damping computed when read, flag bit 3).
pub const FORMAT_VERSION: u32 = 4;

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
    /// Are the force and moment time derivatives in `output_derivatives` still to be
    /// computed? They cost three force evaluations, so a step leaves them pending and the
    /// first read computes them (at the inputs' offset kept in the last `aux` slot). Stored
    /// as bit 2 of the `started` word.
    pub derivatives_pending: bool,
    /// Are the stiffness and damping outputs (`K`, `C`) still to be computed? A level that
    /// can give them later ([`crate::seam::LevelModel::outputs_deferring_matrices`]) leaves
    /// them to the first read after a step (at the inputs' offset kept in the last `aux`
    /// slot); their slots hold zeros until then. Stored as bit 3 of the `started` word.
    pub matrices_pending: bool,
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
        self.copy_from(o, true, true);
    }
}

impl State {
    /// A step's scratch copy of `o`: every field (with `derivatives`; `clone_from` is this),
    /// or everything a step reads or writes, without the inputs' derivatives unless the
    /// input rule reads them (`derivatives`; a step never
    /// writes them, and [`State::commit_step`] leaves them where they are). No allocation
    /// once the sizes match.
    pub(super) fn begin_step_from(&mut self, o: &Self, derivatives: bool) {
        self.copy_from(o, derivatives, false);
    }

    /// [`State::begin_step_from`]; `all_inputs`: every slot of the inputs and outputs
    /// (a whole copy), else of the inputs only the slots below `N_INPUT_SLOTS` that hold
    /// inputs (a step reads no other, and [`State::commit_step`] leaves the inputs where
    /// they are), and of the outputs only the slots below it (a successful step writes
    /// every other).
    fn copy_from(&mut self, o: &Self, derivatives: bool, all_inputs: bool) {
        self.scene_fingerprint = o.scene_fingerprint;
        self.t = o.t;
        self.started = o.started;
        self.outputs_stale = o.outputs_stale;
        self.derivatives_pending = o.derivatives_pending;
        self.matrices_pending = o.matrices_pending;
        self.inputs_set = o.inputs_set;
        self.x.clone_from(&o.x);
        self.aux.clone_from(&o.aux);
        let ni = super::N_INPUT_SLOTS;
        if !all_inputs && self.inputs.len() == o.inputs.len() && o.inputs.len() >= ni {
            self.inputs[..ni].copy_from_slice(&o.inputs[..ni]);
        } else {
            self.inputs.clone_from(&o.inputs);
        }
        if derivatives {
            self.input_derivatives.clone_from(&o.input_derivatives);
        }
        // A step's outputs (`Component::compute_outputs`, on every successful step) write
        // every slot from `N_INPUT_SLOTS` on but the per-row slots of rows the level does
        // not have, which are zero in both buffers from the build and never written: only
        // the slots below `N_INPUT_SLOTS` are carried over.
        if !all_inputs && self.outputs.len() == o.outputs.len() && o.outputs.len() >= ni {
            self.outputs[..ni].copy_from_slice(&o.outputs[..ni]);
        } else {
            self.outputs.clone_from(&o.outputs);
        }
        self.output_derivatives.clone_from(&o.output_derivatives);
    }

    /// Take what a step wrote from its scratch copy `sc` ([`State::begin_step_from`]):
    /// time, flags, states, memory, outputs and their derivatives (buffers swapped). The
    /// inputs, their derivatives and the mask stay (a step does not change them).
    pub(super) fn commit_step(&mut self, sc: &mut Self) {
        self.t = sc.t;
        self.started = sc.started;
        self.outputs_stale = sc.outputs_stale;
        self.derivatives_pending = sc.derivatives_pending;
        self.matrices_pending = sc.matrices_pending;
        std::mem::swap(&mut self.x, &mut sc.x);
        std::mem::swap(&mut self.aux, &mut sc.aux);
        std::mem::swap(&mut self.outputs, &mut sc.outputs);
        std::mem::swap(&mut self.output_derivatives, &mut sc.output_derivatives);
    }
}

/// Writes bytes into a slice of exactly the right length.
struct Writer<'a> {
    b: &'a mut [u8],
    at: usize,
}

impl Writer<'_> {
    fn put(&mut self, x: &[u8]) {
        self.b[self.at..self.at + x.len()].copy_from_slice(x);
        self.at += x.len();
    }
    fn u64(&mut self, x: u64) {
        self.put(&x.to_le_bytes());
    }
    fn vec(&mut self, v: &[f64]) {
        self.u64(v.len() as u64);
        for x in v {
            self.put(&x.to_le_bytes());
        }
    }
}

fn refused(message: String) -> Error {
    Error::Parse {
        what: "serialised state".into(),
        message,
    }
}

/// Little-endian reads from bytes, shared by the component's state bytes and the FMU state
/// bytes: a read past the end is refused with `fail("truncated at byte <at> of <len>")`.
pub(crate) struct ByteReader<'a, E> {
    /// The bytes.
    pub(crate) b: &'a [u8],
    /// Where the next read starts.
    pub(crate) at: usize,
    /// The error of a refusal from its message.
    pub(crate) fail: fn(String) -> E,
}

impl<'a, E> ByteReader<'a, E> {
    /// The next `n` bytes.
    pub(crate) fn take(&mut self, n: usize) -> std::result::Result<&'a [u8], E> {
        if n > self.b.len() - self.at {
            return Err((self.fail)(format!(
                "truncated at byte {} of {}",
                self.at,
                self.b.len()
            )));
        }
        let s = &self.b[self.at..self.at + n];
        self.at += n;
        Ok(s)
    }
    /// The next `u64`.
    pub(crate) fn u64(&mut self) -> std::result::Result<u64, E> {
        Ok(u64::from_le_bytes(
            self.take(8)?.try_into().expect("8 bytes"),
        ))
    }
}

type Reader<'a> = ByteReader<'a, Error>;

impl Reader<'_> {
    /// A finite number called `what`.
    fn f64(&mut self, what: &str) -> Result<f64> {
        self.finite(what, None)
    }
    fn finite(&mut self, what: &str, index: Option<u64>) -> Result<f64> {
        let at = self.at;
        let x = f64::from_bits(self.u64()?);
        if !x.is_finite() {
            let name = match index {
                Some(i) => format!("{what}[{i}]"),
                None => what.to_string(),
            };
            return Err(refused(format!(
                "`{name}` = {x} at byte {at}: allowed finite numbers only"
            )));
        }
        Ok(x)
    }
    fn vec(&mut self, what: &str) -> Result<Vec<f64>> {
        let n = self.u64()?;
        if n > ((self.b.len() - self.at) / 8) as u64 {
            return Err(refused(format!("`{what}`: length {n} exceeds the data")));
        }
        (0..n).map(|i| self.finite(what, Some(i))).collect()
    }
}

/// Bytes in the fixed part: magic, version, fingerprint, time, started, mask, six
/// lengths, checksum.
const FIXED: usize = 4 + 4 + 8 + 8 + 8 + 8 + 8 * 6 + 8;

impl State {
    /// Serialise to bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = vec![0; self.byte_len()];
        self.write_into(&mut out);
        out
    }

    /// Exact length of [`State::to_bytes`].
    pub fn byte_len(&self) -> usize {
        FIXED
            + 8 * (self.x.len()
                + self.aux.len()
                + self.inputs.len()
                + self.input_derivatives.len()
                + self.outputs.len()
                + self.output_derivatives.len())
    }

    /// Write the byte form into `out` (exactly [`State::byte_len`] bytes; no allocation).
    ///
    /// # Panics
    /// When `out` has another length.
    pub fn write_into(&self, out: &mut [u8]) {
        assert_eq!(out.len(), self.byte_len(), "state buffer length");
        let mut w = Writer { b: out, at: 0 };
        w.put(MAGIC);
        w.put(&FORMAT_VERSION.to_le_bytes());
        w.u64(self.scene_fingerprint);
        w.put(&self.t.to_le_bytes());
        w.u64(
            self.started as u64
                | (self.outputs_stale as u64) << 1
                | (self.derivatives_pending as u64) << 2
                | (self.matrices_pending as u64) << 3,
        );
        w.u64(self.inputs_set);
        w.vec(&self.x);
        w.vec(&self.aux);
        w.vec(&self.inputs);
        w.vec(&self.input_derivatives);
        w.vec(&self.outputs);
        w.vec(&self.output_derivatives);
        let end = w.at;
        let sum = super::fingerprint(&w.b[..end]);
        w.u64(sum);
    }

    /// Parse bytes written by [`State::to_bytes`]; damaged, truncated or foreign bytes
    /// and non-finite numbers are refused with a message.
    pub fn from_bytes(b: &[u8]) -> Result<State> {
        if b.len() < 8 {
            return Err(refused(format!(
                "{} bytes: too short for a raceway state",
                b.len()
            )));
        }
        if &b[..4] != MAGIC {
            return Err(refused("not a raceway state (bad magic)".into()));
        }
        let ver = u32::from_le_bytes(b[4..8].try_into().expect("4 bytes"));
        if ver != FORMAT_VERSION {
            return Err(refused(format!(
                "format version {ver}, this build reads version {FORMAT_VERSION} only"
            )));
        }
        if b.len() < FIXED {
            return Err(refused(format!(
                "truncated: {} bytes, a state has at least {FIXED}",
                b.len()
            )));
        }
        let (body, sum) = b.split_at(b.len() - 8);
        let sum = u64::from_le_bytes(sum.try_into().expect("8 bytes"));
        if super::fingerprint(body) != sum {
            return Err(refused(
                "checksum mismatch: the bytes are damaged or truncated".into(),
            ));
        }
        let mut r = Reader {
            b: body,
            at: 8,
            fail: refused,
        };
        let scene_fingerprint = r.u64()?;
        let t = r.f64("t")?;
        let (started, outputs_stale, derivatives_pending, matrices_pending) = match r.u64()? {
            k @ 0..=15 => (k & 1 != 0, k & 2 != 0, k & 4 != 0, k & 8 != 0),
            k => {
                return Err(refused(format!(
                    "`started` = {k}: allowed 0 to 15 (bit 0 started, bit 1 outputs stale, bit 2 derivatives pending, bit 3 stiffness and damping pending)"
                )))
            }
        };
        let inputs_set = r.u64()?;
        let s = State {
            scene_fingerprint,
            t,
            started,
            outputs_stale,
            derivatives_pending,
            matrices_pending,
            inputs_set,
            x: r.vec("x")?,
            aux: r.vec("aux")?,
            inputs: r.vec("inputs")?,
            input_derivatives: r.vec("input_derivatives")?,
            outputs: r.vec("outputs")?,
            output_derivatives: r.vec("output_derivatives")?,
        };
        if r.at != body.len() {
            return Err(refused(format!("{} trailing bytes", body.len() - r.at)));
        }
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> State {
        State {
            scene_fingerprint: 42,
            t: 0.125,
            started: true,
            outputs_stale: true,
            derivatives_pending: true,
            matrices_pending: true,
            x: vec![1.0, -0.0, f64::MIN_POSITIVE],
            aux: vec![3.5],
            inputs: vec![1e-6; 11],
            input_derivatives: vec![0.0; 33],
            inputs_set: 0b111,
            outputs: vec![2.0; 80],
            output_derivatives: vec![0.5; 80],
        }
    }

    #[test]
    fn bytes_round_trip_exactly_and_refuse_damage() {
        let s = sample();
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

    #[test]
    fn every_single_byte_change_and_every_truncation_is_refused() {
        let b = sample().to_bytes();
        for i in 0..b.len() {
            for flip in [0x01u8, 0x80, 0xff] {
                let mut bad = b.clone();
                bad[i] ^= flip;
                assert!(State::from_bytes(&bad).is_err(), "byte {i} ^ {flip:#x}");
            }
        }
        for n in 0..b.len() {
            let e = State::from_bytes(&b[..n]).unwrap_err().to_string();
            assert!(e.contains("serialised state"), "{n}: {e}");
        }
        let mut longer = b.clone();
        longer.push(0);
        assert!(State::from_bytes(&longer).is_err());
    }

    /// A NaN or infinity in any number slot is refused by name even when the checksum is
    /// made to match (bytes written by a faulty writer, not damaged in transit).
    #[test]
    fn non_finite_numbers_are_refused_even_with_a_valid_checksum() {
        let s = sample();
        let slots = 1
            + s.x.len()
            + s.aux.len()
            + s.inputs.len()
            + s.input_derivatives.len()
            + s.outputs.len()
            + s.output_derivatives.len();
        let mut refused_slots = 0;
        for k in 0..slots {
            for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                let mut m = s.clone();
                let mut all: Vec<&mut f64> = std::iter::once(&mut m.t)
                    .chain(m.x.iter_mut())
                    .chain(m.aux.iter_mut())
                    .chain(m.inputs.iter_mut())
                    .chain(m.input_derivatives.iter_mut())
                    .chain(m.outputs.iter_mut())
                    .chain(m.output_derivatives.iter_mut())
                    .collect();
                *all[k] = bad;
                let e = State::from_bytes(&m.to_bytes()).unwrap_err().to_string();
                assert!(e.contains("allowed finite numbers only"), "{e}");
                refused_slots += 1;
            }
        }
        assert_eq!(refused_slots, 3 * slots);
        let mut other = s.clone();
        other.started = true;
        let mut b = other.to_bytes();
        b[24] = 16; // started = 16
        let n = b.len();
        let sum = crate::component::fingerprint(&b[..n - 8]);
        b[n - 8..].copy_from_slice(&sum.to_le_bytes());
        assert!(State::from_bytes(&b)
            .unwrap_err()
            .to_string()
            .contains("`started` = 16"));
    }

    #[test]
    fn another_format_version_is_refused_by_number() {
        let mut b = sample().to_bytes();
        b[4..8].copy_from_slice(&1u32.to_le_bytes());
        let e = State::from_bytes(&b).unwrap_err().to_string();
        assert!(
            e.contains("format version 1") && e.contains("version 4"),
            "{e}"
        );
    }
}
