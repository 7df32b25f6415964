//! FMU states of an instance: snapshots, their handles, their byte form (magic, format,
//! checksum) and the Get/Set/Free/Serialize/DeSerialize calls of both versions.

use super::*;

pub(super) const STATE_MAGIC: &[u8; 4] = b"RWFU";
/// 2: a checksum (FNV-1a, as `component::state`) over everything before it, at the end.
/// 3: Boolean and Enumeration parameters (tags 3, 4); the GUID names the variant.
pub(super) const STATE_FORMAT: u32 = 3;

impl Snapshot {
    /// Into a handle for the host.
    pub(crate) fn into_raw(self) -> *mut c_void {
        STATES.insert(Box::new(self)) as *mut c_void
    }

    /// Free a state given back by the host (NULL, unknown and busy handles are left alone).
    pub(crate) fn free(p: *mut c_void) {
        if let Ok(s) = STATES.remove(p as usize) {
            drop(s);
        }
    }

    /// Byte form: magic `RWFU`, format `u32`, the GUID, then every field little-endian; the
    /// component state as its own versioned bytes (`component::State::to_bytes`).
    pub(crate) fn to_bytes(&self) -> Vec<u8> {
        let mut b = Vec::new();
        let bytes = |b: &mut Vec<u8>, x: &[u8]| {
            b.extend_from_slice(&(x.len() as u64).to_le_bytes());
            b.extend_from_slice(x);
        };
        let opt = |b: &mut Vec<u8>, x: Option<f64>| {
            b.push(x.is_some() as u8);
            b.extend_from_slice(&x.unwrap_or(0.0).to_le_bytes());
        };
        b.extend_from_slice(STATE_MAGIC);
        b.extend_from_slice(&STATE_FORMAT.to_le_bytes());
        bytes(&mut b, md::guid(self.causality).as_bytes());
        b.extend_from_slice(&self.mode.to_le_bytes());
        b.extend_from_slice(&self.time.to_le_bytes());
        b.extend_from_slice(&self.start_time.to_le_bytes());
        opt(&mut b, self.stop_time);
        opt(&mut b, self.tolerance);
        b.extend_from_slice(&(self.params.len() as u64).to_le_bytes());
        for p in &self.params {
            match p {
                None => b.push(0),
                Some(ParamValue::Real(x)) => {
                    b.push(1);
                    b.extend_from_slice(&x.to_le_bytes());
                }
                Some(ParamValue::Str(s)) => {
                    b.push(2);
                    bytes(&mut b, s.as_bytes());
                }
                Some(ParamValue::Bool(x)) => {
                    b.push(3);
                    b.push(*x as u8);
                }
                Some(ParamValue::Int(k)) => {
                    b.push(4);
                    b.extend_from_slice(&k.to_le_bytes());
                }
            }
        }
        b.extend_from_slice(&(self.inputs.len() as u64).to_le_bytes());
        for x in &self.inputs {
            b.extend_from_slice(&x.to_le_bytes());
        }
        b.extend_from_slice(&self.inputs_set.to_le_bytes());
        b.extend_from_slice(&(self.pending_derivatives.len() as u64).to_le_bytes());
        for (vr, o, x) in &self.pending_derivatives {
            b.extend_from_slice(&vr.to_le_bytes());
            b.extend_from_slice(&o.to_le_bytes());
            b.extend_from_slice(&x.to_le_bytes());
        }
        match &self.component {
            None => b.push(0),
            Some(s) => {
                b.push(1);
                bytes(&mut b, &s.to_bytes());
            }
        }
        let sum = crate::component::fingerprint(&b);
        b.extend_from_slice(&sum.to_le_bytes());
        b
    }

    /// Read the byte form of an FMU state of the variant of causality `causality`.
    pub(crate) fn from_bytes(b: &[u8], causality: Causality) -> Result<Snapshot, String> {
        let own = md::guid(causality);
        let mut r = Reader {
            b,
            at: 0,
            fail: refused,
        };
        if r.take(4)? != STATE_MAGIC {
            return Err("serialised FMU state: not a raceway FMU state (bad magic)".into());
        }
        let ver = r.u32()?;
        if ver != STATE_FORMAT {
            return Err(format!(
                "serialised FMU state: format {ver}, this binary reads {STATE_FORMAT}"
            ));
        }
        let guid = r.bytes()?;
        if guid != own.as_bytes() {
            let theirs = String::from_utf8_lossy(guid);
            let which = md::variant_of(&theirs).map_or("of another build".to_string(), |c| {
                format!("the {}-driven FMU", md::variant_name(c))
            });
            return Err(format!(
                "serialised FMU state: written by FMU `{theirs}` ({which}), this instance is \
                 `{own}` ({}-driven)",
                md::variant_name(causality)
            ));
        }
        // Damaged bytes are refused before any other field is read (the magic, the
        // format and the GUID name foreign bytes first).
        if b.len() < r.at + 8 {
            return Err(format!(
                "serialised FMU state: truncated at byte {}",
                b.len()
            ));
        }
        let (b, sum) = b.split_at(b.len() - 8);
        if crate::component::fingerprint(b).to_le_bytes() != sum {
            return Err(
                "serialised FMU state: checksum mismatch: the bytes are damaged or truncated"
                    .into(),
            );
        }
        let mut r = Reader {
            b,
            at: r.at,
            fail: refused,
        };
        let mode = r.u32()?;
        if mode.count_ones() != 1 || mode & ANY == 0 {
            return Err(format!("serialised FMU state: bad mode {mode}"));
        }
        let time = r.f64()?;
        let start_time = r.f64()?;
        let stop_time = r.opt()?;
        let tolerance = r.opt()?;
        let n = r.u64()? as usize;
        if n != PARAMETERS.len() {
            return Err(format!(
                "serialised FMU state: {n} parameters, this binary has {}",
                PARAMETERS.len()
            ));
        }
        let mut params = Vec::with_capacity(n);
        for _ in 0..n {
            params.push(match r.take(1)?[0] {
                0 => None,
                1 => Some(ParamValue::Real(r.f64()?)),
                2 => Some(ParamValue::Str(
                    String::from_utf8(r.bytes()?.to_vec())
                        .map_err(|_| "serialised FMU state: parameter not UTF-8".to_string())?,
                )),
                3 => Some(ParamValue::Bool(match r.take(1)?[0] {
                    0 => false,
                    1 => true,
                    x => return Err(format!("serialised FMU state: bad Boolean {x}")),
                })),
                4 => Some(ParamValue::Int(r.u64()? as i64)),
                k => return Err(format!("serialised FMU state: bad parameter tag {k}")),
            });
        }
        for (p, v) in PARAMETERS.iter().zip(&params) {
            let fits = match (p.ty, v) {
                (_, None) => true,
                (ParamType::Real, Some(ParamValue::Real(_))) => true,
                (ParamType::String, Some(ParamValue::Str(_))) => true,
                (ParamType::Boolean, Some(ParamValue::Bool(_))) => true,
                (ParamType::Enumeration { items, .. }, Some(ParamValue::Int(k))) => {
                    (0..items.len() as i64).contains(k)
                }
                _ => false,
            };
            if !fits {
                return Err(format!(
                    "serialised FMU state: parameter `{}` holds a value of another type or \
                     outside its items",
                    p.name
                ));
            }
        }
        let ni = r.u64()? as usize;
        if ni != md::inputs(causality).count() {
            return Err(format!("serialised FMU state: {ni} inputs"));
        }
        let inputs = (0..ni).map(|_| r.f64()).collect::<Result<Vec<_>, _>>()?;
        let inputs_set = r.u64()?;
        let nd = r.u64()? as usize;
        if nd > b.len() / 16 {
            return Err("serialised FMU state: too many input derivatives".into());
        }
        let mut pending_derivatives = Vec::with_capacity(nd);
        for _ in 0..nd {
            pending_derivatives.push((r.u32()?, r.u32()?, r.f64()?));
        }
        let component = match r.take(1)?[0] {
            0 => None,
            1 => Some(
                State::from_bytes(r.bytes()?).map_err(|e| format!("serialised FMU state: {e}"))?,
            ),
            k => return Err(format!("serialised FMU state: bad component tag {k}")),
        };
        if r.at != b.len() {
            return Err(format!(
                "serialised FMU state: {} trailing bytes",
                b.len() - r.at
            ));
        }
        let reals = params.iter().filter_map(|p| match p {
            Some(ParamValue::Real(x)) => Some(*x),
            _ => None,
        });
        let mut numbers = [time, start_time]
            .into_iter()
            .chain(stop_time)
            .chain(tolerance)
            .chain(reals)
            .chain(inputs.iter().copied())
            .chain(pending_derivatives.iter().map(|p| p.2));
        if let Some(x) = numbers.find(|x| !x.is_finite()) {
            return Err(format!(
                "serialised FMU state: a number is {x}: allowed finite numbers only"
            ));
        }
        Ok(Snapshot {
            tag: SNAP_TAG,
            causality,
            mode,
            time,
            start_time,
            stop_time,
            tolerance,
            params,
            inputs,
            inputs_set,
            pending_derivatives,
            component,
        })
    }
}

/// The FMU state's reads: refusals start `serialised FMU state: `.
pub(super) type Reader<'a> = ByteReader<'a, String>;

pub(super) fn refused(msg: String) -> String {
    format!("serialised FMU state: {msg}")
}

impl<'a> Reader<'a> {
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(
            self.take(4)?.try_into().expect("4 bytes"),
        ))
    }
    fn f64(&mut self) -> Result<f64, String> {
        Ok(f64::from_bits(self.u64()?))
    }
    fn opt(&mut self) -> Result<Option<f64>, String> {
        let some = self.take(1)?[0] != 0;
        let x = self.f64()?;
        Ok(some.then_some(x))
    }
    fn bytes(&mut self) -> Result<&'a [u8], String> {
        let n = self.u64()?;
        if n > (self.b.len() - self.at) as u64 {
            return Err("serialised FMU state: length exceeds the data".into());
        }
        self.take(n as usize)
    }
}

// ---------------------------------------------------------------------------------------
// FMU state calls, the same in both versions.

/// `GetFMUstate`: a new state in `*state`, or `*state` overwritten when it is not NULL.
///
/// # Safety
/// `state` is NULL or valid for a read and a write (`*state` is compared with the live
/// FMU states only).
pub(crate) unsafe fn get_state(
    inst: &mut Instance,
    state: *mut *mut c_void,
) -> Result<Status, Fail> {
    if state.is_null() {
        return Err(Fail::from("FMUstate pointer is NULL".to_string()));
    }
    put_state(state, inst.snapshot())
}

/// `snap` into `*state`: a new FMU state when `*state` is NULL, else the one it names
/// overwritten.
///
/// # Safety
/// `state` is valid for a read and a write.
pub(super) unsafe fn put_state(state: *mut *mut c_void, snap: Snapshot) -> Result<Status, Fail> {
    if (*state).is_null() {
        *state = snap.into_raw();
    } else {
        *Instance::snapshot_lease(*state)?.get() = snap;
    }
    Ok(Status::Ok)
}

/// `SetFMUstate`.
///
/// # Safety
/// None beyond the FMI calling convention (`state` is compared with the live FMU states
/// only).
pub(crate) unsafe fn set_state(inst: &mut Instance, state: *mut c_void) -> Result<Status, Fail> {
    inst.restore(Instance::snapshot_lease(state)?.get())?;
    Ok(Status::Ok)
}

/// `FreeFMUstate`: frees `*state` and sets it NULL (NULL is ignored).
///
/// # Safety
/// `state` is NULL or valid for a read and a write.
pub(crate) unsafe fn free_state(state: *mut *mut c_void) -> Result<Status, Fail> {
    if !state.is_null() && !(*state).is_null() {
        Snapshot::free(*state);
        *state = std::ptr::null_mut();
    }
    Ok(Status::Ok)
}

/// `SerializedFMUstateSize`.
///
/// # Safety
/// `size` is NULL or valid for a write.
pub(crate) unsafe fn serialized_size(state: *mut c_void, size: *mut usize) -> Result<Status, Fail> {
    let n = Instance::snapshot_lease(state)?.get().to_bytes().len();
    slice_mut(size, 1, "size")?[0] = n;
    Ok(Status::Ok)
}

/// `SerializeFMUstate`: `size` must be what `SerializedFMUstateSize` gave.
///
/// # Safety
/// `bytes` is NULL or valid for `size` bytes.
pub(crate) unsafe fn serialize(
    state: *mut c_void,
    bytes: *mut u8,
    size: usize,
) -> Result<Status, Fail> {
    let b = Instance::snapshot_lease(state)?.get().to_bytes();
    if size != b.len() {
        return Err(Fail::from(format!(
            "buffer of {size} bytes, the serialised state has {} (ask SerializedFMUstateSize)",
            b.len()
        )));
    }
    slice_mut(bytes, size, "serializedState")?.copy_from_slice(&b);
    Ok(Status::Ok)
}

/// `DeSerializeFMUstate` of an FMU state of `inst`'s variant.
///
/// # Safety
/// `bytes` is NULL or valid for `size` bytes; `state` as in [`get_state`].
pub(crate) unsafe fn deserialize(
    inst: &Instance,
    bytes: *const u8,
    size: usize,
    state: *mut *mut c_void,
) -> Result<Status, Fail> {
    if state.is_null() {
        return Err(Fail::from("FMUstate pointer is NULL".to_string()));
    }
    let snap = Snapshot::from_bytes(slice(bytes, size, "serializedState")?, inst.causality)?;
    put_state(state, snap)
}

impl Instance {
    pub(crate) fn snapshot(&self) -> Snapshot {
        Snapshot {
            tag: SNAP_TAG,
            causality: self.causality,
            mode: self.mode,
            time: self.time,
            start_time: self.start_time,
            stop_time: self.stop_time,
            tolerance: self.tolerance,
            params: self.params.clone(),
            inputs: self.inputs.clone(),
            inputs_set: self.inputs_set,
            pending_derivatives: self.pending_derivatives.clone(),
            component: self.component.as_ref().map(Component::get_state),
        }
    }

    /// Restore a snapshot (of this instance, another instance or another process). The
    /// instance is unchanged if this fails.
    pub(crate) fn restore(&mut self, s: &Snapshot) -> Result<(), Fail> {
        if s.tag != SNAP_TAG {
            return Err(Fail::from("not an FMU state of this FMU".to_string()));
        }
        if s.causality != self.causality {
            return Err(Fail::from(format!(
                "an FMU state of the {}-driven FMU; this instance is {}-driven",
                md::variant_name(s.causality),
                md::variant_name(self.causality)
            )));
        }
        match &s.component {
            Some(state) => {
                let same_build = self.component.is_some()
                    && self.params == s.params
                    && self.tolerance == s.tolerance;
                if same_build {
                    self.component.as_mut().expect("checked").set_state(state)?;
                } else {
                    let mut c = self.build(
                        &s.params,
                        s.tolerance,
                        &s.inputs,
                        s.inputs_set,
                        &s.pending_derivatives,
                    )?;
                    c.set_state(state)?;
                    self.component = Some(c);
                }
            }
            None => self.component = None,
        }
        self.mode = s.mode;
        self.time = s.time;
        self.start_time = s.start_time;
        self.stop_time = s.stop_time;
        self.tolerance = s.tolerance;
        self.params = s.params.clone();
        self.inputs.clone_from(&s.inputs);
        self.inputs_set = s.inputs_set;
        self.pending_derivatives.clone_from(&s.pending_derivatives);
        Ok(())
    }

    /// The FMU state behind a host handle, for this call.
    pub(crate) fn snapshot_lease<'a>(p: *mut c_void) -> Result<Lease<'a, Snapshot>, Fail> {
        if p.is_null() {
            return Err(Fail::from("the FMU state is NULL".to_string()));
        }
        STATES.acquire(p as usize).map_err(|r| {
            Fail::from(match r {
                Refusal::Unknown => {
                    "not a live FMU state of this FMU (freed already, or never created)".to_string()
                }
                Refusal::Busy => "the FMU state is in use by another call right now".to_string(),
            })
        })
    }
}
