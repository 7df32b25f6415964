//! Stand-alone runs of a scene: the component stepped at the scene's `[run]` step with the
//! prescribed shaft motion (motion-driven) or loads (load-driven), every output recorded.
//! What `raceway run` does; usable from Rust too.

mod element_loads;

pub use element_loads::{Envelope, LoadRecord, BIN_DEG};

use crate::component::{variables, Causality, Component, Scene};
use crate::error::Result;
use crate::units::rpm_to_rad_s;
use std::f64::consts::PI;

/// A recorded run: time and one column per variable of the table (inputs and outputs).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Series {
    /// Variable names, in column order.
    pub names: Vec<&'static str>,
    /// Units, in column order.
    pub units: Vec<&'static str>,
    /// Communication times, s.
    pub t: Vec<f64>,
    /// Values, `columns[k][i]` at `t[i]`.
    pub columns: Vec<Vec<f64>>,
}

impl Series {
    /// An empty series with the columns `names` and `units`.
    pub fn with_columns(names: &[&'static str], units: &[&'static str]) -> Series {
        Series {
            names: names.to_vec(),
            units: units.to_vec(),
            t: Vec::new(),
            columns: vec![Vec::new(); names.len()],
        }
    }

    /// The column of a variable.
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.names
            .iter()
            .position(|n| *n == name)
            .map(|k| self.columns[k].as_slice())
    }

    /// The column titles, `t [s]` then `<name> [unit]` per column: series.csv's header and
    /// the Python DataFrame's columns.
    pub fn header(&self) -> Vec<String> {
        header(&self.names, &self.units)
    }

    /// CSV text: a header `t [s],<name> [unit],...` and one row per time (what
    /// [`CsvSink`] streams, byte for byte).
    pub fn to_csv(&self) -> String {
        let mut s = csv_header(&self.names, &self.units);
        let mut row = Vec::with_capacity(self.columns.len());
        for i in 0..self.t.len() {
            row.clear();
            row.extend(self.columns.iter().map(|c| c[i]));
            csv_row(&mut s, self.t[i], &row);
        }
        s
    }
}

/// The column titles: `t [s]`, then `<name> [unit]`.
pub fn header(names: &[&str], units: &[&str]) -> Vec<String> {
    std::iter::once("t [s]".to_string())
        .chain(
            names
                .iter()
                .zip(units)
                .map(|(n, u)| crate::units::label(n, u)),
        )
        .collect()
}

fn csv_header(names: &[&str], units: &[&str]) -> String {
    header(names, units).join(",") + "\n"
}

fn csv_row(s: &mut String, t: f64, values: &[f64]) {
    use std::fmt::Write as _;
    let _ = write!(s, "{t:e}");
    for v in values {
        let _ = write!(s, ",{v:e}");
    }
    s.push('\n');
}

/// Where a run's rows go, as they are made: kept in memory ([`Series`]), digested into
/// what the summary and plots need in bounded memory ([`Digest`]), written to a CSV file
/// ([`CsvSink`]), or several of these ([`Tee`]).
pub trait Sink {
    /// The columns (after the time), before the first row; `rows`: how many rows the
    /// complete run gives (the steps and the start).
    fn begin(&mut self, names: &[&'static str], units: &[&'static str], rows: usize) -> Result<()>;
    /// One row: the time and one value per column.
    fn row(&mut self, t: f64, values: &[f64]) -> Result<()>;
}

impl Sink for Series {
    fn begin(&mut self, names: &[&'static str], units: &[&'static str], rows: usize) -> Result<()> {
        *self = Series::with_columns(names, units);
        self.t.reserve(rows);
        for c in &mut self.columns {
            c.reserve(rows);
        }
        Ok(())
    }
    fn row(&mut self, t: f64, values: &[f64]) -> Result<()> {
        self.t.push(t);
        for (c, v) in self.columns.iter_mut().zip(values) {
            c.push(*v);
        }
        Ok(())
    }
}

/// Two sinks fed the same rows.
pub struct Tee<'a>(pub &'a mut dyn Sink, pub &'a mut dyn Sink);

impl Sink for Tee<'_> {
    fn begin(&mut self, names: &[&'static str], units: &[&'static str], rows: usize) -> Result<()> {
        self.0.begin(names, units, rows)?;
        self.1.begin(names, units, rows)
    }
    fn row(&mut self, t: f64, values: &[f64]) -> Result<()> {
        self.0.row(t, values)?;
        self.1.row(t, values)
    }
}

/// series.csv written while the run goes: the text of [`Series::to_csv`], byte for byte,
/// through a buffer, so a run's memory does not grow with its length. A failed write
/// (disk full) fails the run naming the file.
pub struct CsvSink<W: std::io::Write> {
    out: W,
    /// The file, for messages.
    what: String,
    line: String,
}

impl CsvSink<std::io::BufWriter<std::fs::File>> {
    /// A new file at `path` (replacing one there).
    pub fn create(path: &std::path::Path) -> Result<Self> {
        let f = std::fs::File::create(path).map_err(|e| io_error(&path.display(), e))?;
        Ok(CsvSink::new(
            std::io::BufWriter::with_capacity(1 << 16, f),
            path.display().to_string(),
        ))
    }
}

fn io_error(what: &dyn std::fmt::Display, e: std::io::Error) -> crate::Error {
    crate::Error::Io(format!("cannot write `{what}`: {e}"))
}

impl<W: std::io::Write> CsvSink<W> {
    /// Rows into `out`; `what` names it in messages.
    pub fn new(out: W, what: String) -> Self {
        CsvSink {
            out,
            what,
            line: String::new(),
        }
    }

    /// Flush what is buffered and give the writer back (for a file: synced to disk).
    pub fn finish(mut self) -> Result<W> {
        self.out.flush().map_err(|e| io_error(&self.what, e))?;
        Ok(self.out)
    }

    fn put(&mut self) -> Result<()> {
        let r = self.out.write_all(self.line.as_bytes());
        self.line.clear();
        r.map_err(|e| io_error(&self.what, e))
    }
}

impl<W: std::io::Write> Sink for CsvSink<W> {
    fn begin(&mut self, names: &[&'static str], units: &[&'static str], _: usize) -> Result<()> {
        self.line = csv_header(names, units);
        self.put()
    }
    fn row(&mut self, t: f64, values: &[f64]) -> Result<()> {
        csv_row(&mut self.line, t, values);
        self.put()
    }
}

/// Most rows of a run's history kept for plots: a longer run keeps every `stride`-th row
/// (and its last), so the history stays under this whatever the duration.
pub const HISTORY_ROWS: usize = 20_000;

/// Rows of a run's end kept at full rate beside a decimated history (for plots that zoom on
/// the last few ball passes): at most this many, only when the history skips rows.
pub const TAIL_ROWS: usize = 20_000;

/// Most rows of a column analysed at full rate (the spectra's signal, the whirl index's cage
/// speed): the last `min(second half, ANALYSED_ROWS)` rows, 2^20 (105 s at 10 kHz, a
/// spectrum's bin 0.01 Hz there), so a run's memory has a bound whatever its duration.
pub const ANALYSED_ROWS: usize = 1 << 20;

/// What a run keeps in memory for its summary and plots, fed row by row ([`Sink`]):
/// - per column over every row: the largest magnitude, the last value and the sum over
///   the second half (from row [`Digest::start`]), accumulated in row order so they equal
///   the same folds over the whole column bit for bit;
/// - the history for plots, at most [`HISTORY_ROWS`] + 1 rows ([`Digest::history`]);
/// - the columns analysed at full rate (the spectra's signal, the whirl index's cage
///   speed), over the last `min(second half, ANALYSED_ROWS)` rows (from row
///   [`Digest::analysed_from`]): 8 bytes per row per column analysed;
/// - the peak distance `hypot(x, y)` of the column pairs asked for (the cage orbit).
///
/// So a run keeps at most about `HISTORY_ROWS x (columns + 1) x 8` bytes plus
/// `ANALYSED_ROWS x 8` bytes per analysed column (docs/reliability.md, "Memory").
#[derive(Debug, Clone, Default)]
pub struct Digest {
    /// The history for plots: every row when the run has at most [`HISTORY_ROWS`] rows,
    /// else every `stride`-th row from the first and the last row.
    pub history: Series,
    /// Rows of the run per history row.
    pub stride: usize,
    /// The run's last rows at full rate ([`TAIL_ROWS`] at most) when the history skips rows
    /// (`stride > 1`); empty otherwise (the history then holds every row).
    pub tail: Series,
    tail_from: usize,
    /// Rows of the complete run (steps and the start).
    pub rows: usize,
    /// First row of the second half, `rows / 2`.
    pub start: usize,
    /// First row of the analysed columns: `start`, or `rows - cap` when the second half is
    /// longer than the cap ([`ANALYSED_ROWS`] unless set by [`Digest::with_cap`]).
    pub analysed_from: usize,
    cap: usize,
    /// Rows received so far.
    pub seen: usize,
    peak: Vec<f64>,
    last: Vec<f64>,
    sum_half: Vec<f64>,
    analysed_names: Vec<&'static str>,
    /// Column index and full-rate values from `start` on, per analysed name present.
    analysed: Vec<(usize, Vec<f64>)>,
    pair_names: Vec<(&'static str, &'static str)>,
    /// Column indices and peak hypot, per pair present.
    pairs: Vec<(usize, usize, f64)>,
}

impl Digest {
    /// A digest keeping `analysed` (those of the run's columns) at full rate over the second
    /// half and the peak `hypot` of each pair of `pairs`.
    pub fn new(analysed: &[&'static str], pairs: &[(&'static str, &'static str)]) -> Digest {
        Digest {
            analysed_names: analysed.to_vec(),
            pair_names: pairs.to_vec(),
            stride: 1,
            cap: ANALYSED_ROWS,
            ..Digest::default()
        }
    }

    /// The same digest analysing at most the last `cap` rows (at least 1).
    pub fn with_cap(mut self, cap: usize) -> Digest {
        self.cap = cap.max(1);
        self
    }

    fn index(&self, name: &str) -> Option<usize> {
        self.history.names.iter().position(|n| *n == name)
    }

    /// The largest magnitude of a column over every row (0 when absent).
    pub fn peak(&self, name: &str) -> f64 {
        self.index(name).map_or(0.0, |k| self.peak[k])
    }

    /// The last value of a column (0 when absent or before any row).
    pub fn last(&self, name: &str) -> f64 {
        self.index(name).map_or(0.0, |k| self.last[k])
    }

    /// The mean of a column over the second half (rows `start..`; 0 when absent).
    pub fn mean_second_half(&self, name: &str) -> f64 {
        let n = self.seen.saturating_sub(self.start).max(1);
        self.index(name)
            .map_or(0.0, |k| self.sum_half[k] / n as f64)
    }

    /// An analysed column at full rate over the second half, or its last
    /// [`ANALYSED_ROWS`] rows when longer (from row `analysed_from`; empty when absent).
    pub fn second_half(&self, name: &str) -> &[f64] {
        self.index(name)
            .and_then(|k| self.analysed.iter().find(|(i, _)| *i == k))
            .map_or(&[], |(_, v)| v.as_slice())
    }

    /// The largest `hypot(x, y)` over every row of a pair asked for (0 when absent).
    pub fn pair_peak(&self, x: &str, y: &str) -> f64 {
        match (self.index(x), self.index(y)) {
            (Some(i), Some(j)) => self
                .pairs
                .iter()
                .find(|p| p.0 == i && p.1 == j)
                .map_or(0.0, |p| p.2),
            _ => 0.0,
        }
    }

    /// Values held in memory: the history's (time included) and the analysed columns'.
    /// The history's part is bounded whatever the run's length; the analysed part grows by
    /// one value per analysed column per row of the second half up to its cap.
    pub fn values_kept(&self) -> usize {
        (self.history.t.len() + self.tail.t.len()) * (self.history.columns.len() + 1)
            + self.analysed.iter().map(|(_, v)| v.len()).sum::<usize>()
    }

    /// The digest of a series recorded whole (what a caller holding every row passes to
    /// the summary).
    pub fn of(
        series: &Series,
        analysed: &[&'static str],
        pairs: &[(&'static str, &'static str)],
    ) -> Digest {
        let mut d = Digest::new(analysed, pairs);
        let _ = d.begin(&series.names, &series.units, series.t.len());
        let mut row = Vec::with_capacity(series.columns.len());
        for i in 0..series.t.len() {
            row.clear();
            row.extend(series.columns.iter().map(|c| c[i]));
            let _ = d.row(series.t[i], &row);
        }
        d
    }
}

impl Sink for Digest {
    fn begin(&mut self, names: &[&'static str], units: &[&'static str], rows: usize) -> Result<()> {
        let n = names.len();
        self.history = Series::with_columns(names, units);
        self.rows = rows;
        self.start = rows / 2;
        self.analysed_from = self.start.max(rows.saturating_sub(self.cap.max(1)));
        self.seen = 0;
        self.stride = rows.div_ceil(HISTORY_ROWS).max(1);
        self.tail = Series::with_columns(names, units);
        self.tail_from = if self.stride > 1 {
            rows.saturating_sub(TAIL_ROWS)
        } else {
            usize::MAX
        };
        self.peak = vec![0.0; n];
        self.last = vec![0.0; n];
        // -0.0: the neutral element of `Iterator::sum` for floats, so the sum is the
        // same bits as summing the column.
        self.sum_half = vec![-0.0; n];
        let keep = rows - self.analysed_from;
        self.analysed = self
            .analysed_names
            .iter()
            .filter_map(|a| names.iter().position(|n| n == a))
            .map(|k| (k, Vec::with_capacity(keep)))
            .collect();
        let at = |a: &str| names.iter().position(|n| *n == a);
        self.pairs = self
            .pair_names
            .iter()
            .filter_map(|(x, y)| Some((at(x)?, at(y)?, 0.0)))
            .collect();
        Ok(())
    }

    fn row(&mut self, t: f64, values: &[f64]) -> Result<()> {
        let i = self.seen;
        self.seen += 1;
        for (k, &v) in values.iter().enumerate() {
            self.peak[k] = self.peak[k].max(v.abs());
            self.last[k] = v;
        }
        if i >= self.start {
            for (s, v) in self.sum_half.iter_mut().zip(values) {
                *s += v;
            }
        }
        if i >= self.analysed_from {
            for (k, col) in &mut self.analysed {
                col.push(values[*k]);
            }
        }
        for (x, y, m) in &mut self.pairs {
            *m = m.max(values[*x].hypot(values[*y]));
        }
        if i % self.stride == 0 || i + 1 == self.rows {
            self.history.row(t, values)?;
        }
        if i >= self.tail_from {
            self.tail.row(t, values)?;
        }
        Ok(())
    }
}

fn vr(name: &str) -> u32 {
    variables::by_name(name).expect("a contract variable").vr
}

/// Set the inputs `scene`'s `[run]` prescribes at time `t`: the shaft speed (with its
/// ramp) and, motion-driven, the shaft motion with the orbit, or, load-driven, the loads
/// with the rotating load.
fn set_inputs(c: &mut Component, scene: &Scene, t: f64) -> Result<()> {
    let r = &scene.run;
    let init = |name: &str| scene.inputs.initial_value(name);
    let omega0 = init("shaft.omega");
    let ramp = rpm_to_rad_s(r.speed_ramp_rpm_per_s);
    // Shaft angle at time t under the ramp.
    let shaft_angle = omega0 * t + 0.5 * ramp * t * t;
    let omega = omega0 + ramp * t;
    c.set_real(vr("shaft.omega"), omega)?;
    if ramp != 0.0 {
        c.set_input_derivative(vr("shaft.omega"), 1, ramp)?;
    }
    match scene.model.causality {
        Causality::Motion => {
            let (w, ph) = if r.orbit_hz > 0.0 {
                (2.0 * PI * r.orbit_hz, 2.0 * PI * r.orbit_hz * t)
            } else {
                (omega, shaft_angle)
            };
            let a = r.orbit_um * 1e-6;
            let (s, co) = ph.sin_cos();
            for (name, v) in [
                ("shaft.x", init("shaft.x") + a * co),
                ("shaft.y", init("shaft.y") + a * s),
                ("shaft.vx", init("shaft.vx") - a * w * s),
                ("shaft.vy", init("shaft.vy") + a * w * co),
            ] {
                c.set_real(vr(name), v)?;
            }
            for name in [
                "shaft.z", "shaft.rx", "shaft.ry", "shaft.vz", "shaft.wx", "shaft.wy",
            ] {
                c.set_real(vr(name), init(name))?;
            }
        }
        Causality::Load => {
            let (s, co) = shaft_angle.sin_cos();
            let f = r.rotating_load_n;
            c.set_real(vr("load.x"), init("load.x") + f * co)?;
            c.set_real(vr("load.y"), init("load.y") + f * s)?;
            for name in ["load.z", "load.mx", "load.my"] {
                c.set_real(vr(name), init(name))?;
            }
        }
    }
    Ok(())
}

/// The `[run]` fields that move the inputs over a run (the speed ramp and, by causality,
/// the orbit or the rotating load), with their values: all zero, the inputs stay those of
/// the start.
fn moving_inputs(scene: &Scene) -> [(&'static str, f64); 2] {
    let r = &scene.run;
    let moving = match scene.model.causality {
        Causality::Motion => ("run.orbit_um", r.orbit_um),
        Causality::Load => ("run.rotating_load_n", r.rotating_load_n),
    };
    [("run.speed_ramp_rpm_per_s", r.speed_ramp_rpm_per_s), moving]
}

/// The component of `scene` ready to run: built; the inputs the run prescribes at its end
/// (the speed after the ramp) accepted and the outputs there computed, on a separate
/// component so nothing of it carries over; the inputs of the start set and the outputs
/// computed. This is the last check of `raceway scene --check` too, so a scene that
/// passes it starts running.
pub fn prepare(scene: &Scene) -> Result<Component> {
    let at_end = |e: crate::Error| match e {
        crate::Error::Invalid {
            field,
            value,
            allowed,
        } => crate::Error::Invalid {
            field: format!(
                "{field} (prescribed by [run] at t = {} s)",
                scene.run.duration_s
            ),
            value,
            allowed,
        },
        other => other,
    };
    // Inputs held over the run are those of the start: the end's component would be the
    // start's (building it twice was a sixth of a quasi-static sweep point).
    if moving_inputs(scene).iter().any(|(_, v)| *v != 0.0) {
        let mut end = Component::new(scene.clone())?;
        set_inputs(&mut end, scene, scene.run.duration_s)
            .and_then(|_| end.refresh_outputs())
            .map_err(at_end)?;
    }
    let mut c = Component::new(scene.clone())?;
    set_inputs(&mut c, scene, 0.0)?;
    c.refresh_outputs()?;
    Ok(c)
}

/// What a run records besides the scalar inputs and outputs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Record {
    /// The stiffness `K.i.j` and damping `C.i.j` matrices (50 columns more).
    pub stiffness_damping: bool,
}

/// Run `scene` for its `[run]` duration. `progress` receives the completed fraction now
/// and then. The component's state after the run is returned too.
pub fn run(scene: &Scene, progress: &mut dyn FnMut(f64)) -> Result<(Series, Component)> {
    run_recording(scene, Record::default(), progress)
}

/// [`run`], recording what `record` asks for too.
pub fn run_recording(
    scene: &Scene,
    record: Record,
    progress: &mut dyn FnMut(f64),
) -> Result<(Series, Component)> {
    run_with(scene, record, false, progress)
}

/// [`run_recording`]; `through`: the whole duration in one
/// [`Component::step_through`] (the integrator takes its own steps, the series at the
/// communication points from its dense output) instead of a `do_step` per point. Straight
/// through holds the inputs of the start, so it is refused, naming the field, for a run
/// that moves them (`speed_ramp_rpm_per_s`, `orbit_um`, `rotating_load_n`), and for what
/// `step_through` refuses.
pub fn run_with(
    scene: &Scene,
    record: Record,
    through: bool,
    progress: &mut dyn FnMut(f64),
) -> Result<(Series, Component)> {
    run_until(scene, record, through, progress, &mut || false)
}

/// The variables a run of `scene` records, in column order: the inputs of its causality,
/// the outputs its level and effects set ([`crate::component::levels::outputs_set`]), and
/// the K and C matrices when `record` asks.
pub fn recorded(scene: &Scene, record: Record) -> Vec<&'static variables::Variable> {
    let causality = scene.model.causality;
    let sets = crate::component::levels::outputs_set(scene);
    let matrices = variables::STIFFNESS
        .iter()
        .chain(&variables::DAMPING)
        .flatten()
        .filter(|_| record.stiffness_damping);
    // A set's rows: the outputs of as many rows as it has.
    let rows = scene.set.as_ref().map_or(0, |s| s.row_count());
    let per_row = variables::ROW_VARS
        .iter()
        .take(rows)
        .flatten()
        .filter(|v| v.is_set(causality, sets));
    variables::SCALARS
        .iter()
        .filter(|v| v.is_input(causality) || v.is_set(causality, sets))
        .chain(per_row)
        .chain(matrices)
        .collect()
}

/// [`run_with`], asking `stop` before every communication step: when it answers true the
/// run ends with [`crate::Error::Interrupted`] (Ctrl-C in the command line and in Python).
/// `stop` is called once per step, so it should be cheap (check a flag, or the clock).
pub fn run_until(
    scene: &Scene,
    record: Record,
    through: bool,
    progress: &mut dyn FnMut(f64),
    stop: &mut dyn FnMut() -> bool,
) -> Result<(Series, Component)> {
    let mut series = Series::default();
    let c = run_into(scene, record, through, progress, stop, &mut series)?;
    Ok((series, c))
}

/// [`run_until`], handing each row to `sink` as it is made (`raceway run` streams them to
/// series.csv and keeps a [`Digest`]: its memory does not grow with the run's length).
pub fn run_into(
    scene: &Scene,
    record: Record,
    through: bool,
    progress: &mut dyn FnMut(f64),
    stop: &mut dyn FnMut() -> bool,
    sink: &mut dyn Sink,
) -> Result<Component> {
    run_inner(scene, record, through, progress, stop, sink, None)
}

/// [`run_into`], recording the rolling elements' contact loads into `loads` too (made by
/// [`LoadRecord::for_scene`]): the component keeps them
/// ([`Component::keep_element_loads`]) and they are read at the communication points of
/// the record's window. What `raceway run` asks for its ball-load plot; a run without it
/// (the Python run, a sweep) keeps and reads nothing. A level that does not resolve its
/// elements, or a run straight through (`through`: no communication points of its own),
/// leaves `loads` unavailable.
pub fn run_into_with_loads(
    scene: &Scene,
    record: Record,
    through: bool,
    progress: &mut dyn FnMut(f64),
    stop: &mut dyn FnMut() -> bool,
    sink: &mut dyn Sink,
    loads: &mut LoadRecord,
) -> Result<Component> {
    run_inner(scene, record, through, progress, stop, sink, Some(loads))
}

fn run_inner(
    scene: &Scene,
    record: Record,
    through: bool,
    progress: &mut dyn FnMut(f64),
    stop: &mut dyn FnMut() -> bool,
    sink: &mut dyn Sink,
    mut loads: Option<&mut LoadRecord>,
) -> Result<Component> {
    if through {
        for (field, v) in moving_inputs(scene) {
            if v != 0.0 {
                return Err(crate::Error::invalid(
                    field,
                    v,
                    "0 for a run straight through (--through holds the inputs of the start)",
                ));
            }
        }
    }
    let mut c = prepare(scene)?;
    if through || !loads.as_mut().is_some_and(|_| c.keep_element_loads()) {
        loads = None;
    }
    let r = &scene.run;
    let n = (r.duration_s / r.step_s).round().max(1.0) as usize;
    let h = r.duration_s / n as f64;
    let vars = recorded(scene, record);
    let names: Vec<&'static str> = vars.iter().map(|v| v.name).collect();
    let units: Vec<&'static str> = vars.iter().map(|v| v.unit).collect();
    sink.begin(&names, &units, n + 1)?;
    let mut row = vec![0.0; vars.len()];
    let mut record = |c: &mut Component, sink: &mut dyn Sink, t: f64| {
        for (x, v) in row.iter_mut().zip(&vars) {
            *x = c.get_real(v.vr).unwrap_or(0.0);
        }
        sink.row(t, &row)
    };
    record(&mut c, sink, 0.0)?;
    if through {
        let vrs: Vec<u32> = vars.iter().map(|v| v.vr).collect();
        let mut out = Vec::new();
        c.step_through(0.0, h, n, &vrs, &mut out)?;
        for (k, row) in out.chunks_exact(vrs.len().max(1)).enumerate() {
            sink.row((k + 1) as f64 * h, row)?;
        }
        progress(1.0);
        return Ok(c);
    }
    let every = (n / 100).max(1);
    for i in 0..n {
        let t = i as f64 * h;
        if stop() {
            return Err(crate::Error::Interrupted { at_s: t });
        }
        set_inputs(&mut c, scene, t)?;
        c.do_step(t, h)?;
        record(&mut c, sink, (i + 1) as f64 * h)?;
        if let Some(l) = loads.as_deref_mut() {
            l.take_from(&c, (i + 1) as f64 * h);
        }
        if i % every == 0 {
            progress((i + 1) as f64 / n as f64);
        }
    }
    progress(1.0);
    Ok(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The skidding level's own ball loads: their inner-contact vector sum carries the
    /// 500 N radial load of study \[2\]'s 6012 (small contact angles under a radial load, so
    /// within 5 %) pointing down like the load; the quasi-static level keeps none unless
    /// asked.
    #[test]
    fn skidding_ball_loads_carry_the_load() {
        let text = include_str!("../examples/scenes/6012-skidding.toml");
        let mut scene = Scene::from_text(text).unwrap();
        scene.run.duration_s = 0.02;
        let (_, c) = run(&scene, &mut |_| {}).unwrap();
        let mut loads = Vec::new();
        assert!(
            c.element_loads(&mut loads),
            "the skidding level resolves its balls"
        );
        assert_eq!(loads.len(), c.bearing().z);
        let (sx, sy) = loads.iter().fold((0.0, 0.0), |(x, y), l| {
            (x + l.inner * l.psi.cos(), y + l.inner * l.psi.sin())
        });
        assert!((sy + 500.0).abs() < 25.0 && sx.abs() < 25.0, "{sx} {sy}");
        let mut qs = Component::new(Scene::default_scene()).unwrap();
        assert!(!qs.element_loads(&mut loads) && loads.is_empty());
        assert!(qs.keep_element_loads());
    }

    /// `prepare` builds the run's end only when [`moving_inputs`] says its inputs move:
    /// with every moving field zero, the inputs `set_inputs` prescribes at the end equal
    /// those of the start bit for bit (both causalities, an orbit frequency of its own
    /// given too), and any moving field makes some of them differ.
    #[test]
    fn held_inputs_are_the_same_at_the_end() {
        let inputs = |scene: &Scene, t: f64| -> Vec<u64> {
            let mut c = Component::new(scene.clone()).unwrap();
            set_inputs(&mut c, scene, t).unwrap();
            variables::SCALARS
                .iter()
                .filter(|v| v.is_input(scene.model.causality))
                .map(|v| c.get_real(v.vr).unwrap().to_bits())
                .collect()
        };
        let motion = Scene::default_scene();
        let mut load = Scene::from_text(
            "bearing = \"6205\"\n[model]\nlevel = \"ring\"\ncausality = \"load\"\n[inputs]\nspeed_rpm = 1750\ninitial = { \"load.y\" = -500.0 }\n",
        )
        .unwrap();
        load.run.duration_s = 0.37;
        let mut orbit = motion.clone();
        orbit.run.orbit_hz = 33.0;
        for scene in [&motion, &load, &orbit] {
            assert!(moving_inputs(scene).iter().all(|(_, v)| *v == 0.0));
            assert_eq!(inputs(scene, 0.0), inputs(scene, 0.37));
            let mut ramp = scene.clone();
            ramp.run.speed_ramp_rpm_per_s = 100.0;
            let mut moving = scene.clone();
            match scene.model.causality {
                Causality::Motion => moving.run.orbit_um = 1.0,
                Causality::Load => moving.run.rotating_load_n = 10.0,
            }
            for m in [ramp, moving] {
                assert!(moving_inputs(&m).iter().any(|(_, v)| *v != 0.0));
                assert_ne!(inputs(&m, 0.0), inputs(&m, 0.37));
            }
        }
    }

    /// A motion-driven ring run with a synchronous orbit: the recorded inputs follow the
    /// prescribed circle exactly and the force opposes the displacement.
    #[test]
    fn prescribed_orbit_is_followed_and_resisted() {
        let scene = Scene::from_text(
            "bearing = \"6205\"\n[model]\nlevel = \"ring\"\n[inputs]\nspeed_rpm = 954.9296586\ninitial = { }\n[run]\nduration_s = 0.02\nstep_s = 1e-4\norbit_um = 12.0\n",
        )
        .unwrap();
        let (s, _) = run(&scene, &mut |_| {}).unwrap();
        assert_eq!(s.t.len(), 201);
        let (x, y, fx, fy) = (
            s.column("shaft.x").unwrap(),
            s.column("shaft.y").unwrap(),
            s.column("force.x").unwrap(),
            s.column("force.y").unwrap(),
        );
        for i in 0..s.t.len() {
            assert!(((x[i] * x[i] + y[i] * y[i]).sqrt() - 12e-6).abs() < 1e-12);
            assert!(
                fx[i] * x[i] + fy[i] * y[i] < 0.0,
                "the bearing pushes back at t = {}",
                s.t[i]
            );
        }
        assert!(s.to_csv().starts_with("t [s],shaft.x [m]"));
        // K and C when asked: the same run with 50 columns more; K.x.x, the radial
        // stiffness of the loaded ring, is positive and of the order of 1e7..1e9 N/m.
        let (k, _) = run_recording(
            &scene,
            Record {
                stiffness_damping: true,
            },
            &mut |_| {},
        )
        .unwrap();
        assert_eq!(k.names.len(), s.names.len() + 50);
        assert_eq!(k.column("force.x").unwrap(), s.column("force.x").unwrap());
        let kxx = k.column("K.x.x").unwrap();
        assert!(kxx.iter().all(|v| *v > 1e6), "{:?}", &kxx[..3]);
        assert_eq!(
            k.units[k.names.iter().position(|n| *n == "C.y.y").unwrap()],
            "N.s/m"
        );
    }

    /// series.csv streamed row by row is the text of the whole series byte for byte, and
    /// the digest's peaks, last values, second-half means, analysed signals and pair peak
    /// equal the same folds over the whole columns bit for bit (so the summary is the same
    /// as when every row was kept).
    #[test]
    fn streamed_csv_and_digest_equal_the_whole_series() {
        let scene = Scene::from_text(
            "bearing = \"6205\"\n[model]\nlevel = \"ring\"\n[inputs]\nspeed_rpm = 954.9296586\ninitial = { }\n[run]\nduration_s = 0.0101\nstep_s = 1e-4\norbit_um = 12.0\n",
        )
        .unwrap();
        let mut whole = Series::default();
        let mut csv = CsvSink::new(Vec::new(), "memory".into());
        let mut d = Digest::new(&["force.y", "nothing"], &[("force.x", "force.y")]);
        run_into(
            &scene,
            Record::default(),
            false,
            &mut |_| {},
            &mut || false,
            &mut Tee(&mut whole, &mut Tee(&mut csv, &mut d)),
        )
        .unwrap();
        let text = String::from_utf8(csv.finish().unwrap()).unwrap();
        assert_eq!(text, whole.to_csv());
        assert_eq!(whole.t.len(), 102);
        assert_eq!((d.rows, d.seen, d.start, d.stride), (102, 102, 51, 1));
        assert_eq!(d.history, whole);
        for (k, name) in whole.names.iter().enumerate() {
            let col = &whole.columns[k];
            let peak = col.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let half = &col[51..];
            let mean = half.iter().sum::<f64>() / half.len() as f64;
            assert_eq!(d.peak(name).to_bits(), peak.to_bits(), "{name}");
            assert_eq!(d.last(name).to_bits(), col[101].to_bits(), "{name}");
            assert_eq!(d.mean_second_half(name).to_bits(), mean.to_bits(), "{name}");
        }
        assert_eq!(
            d.second_half("force.y"),
            &whole.column("force.y").unwrap()[51..]
        );
        assert!(d.second_half("nothing").is_empty() && d.second_half("force.x").is_empty());
        let (fx, fy) = (
            whole.column("force.x").unwrap(),
            whole.column("force.y").unwrap(),
        );
        let orbit = fx
            .iter()
            .zip(fy)
            .fold(0.0f64, |m, (x, y)| m.max(x.hypot(*y)));
        assert!(orbit > 0.0);
        assert_eq!(d.pair_peak("force.x", "force.y").to_bits(), orbit.to_bits());
    }

    /// Fed rows of a run 10 times longer, the digest keeps the same history size (at most
    /// HISTORY_ROWS + 1 rows, the first and last included) and exact peaks even of a spike
    /// on a row the history skips; only the analysed column grows, by one value per row of
    /// the second half.
    #[test]
    fn a_digest_keeps_a_history_bounded_whatever_the_duration() {
        let feed = |rows: usize| {
            let mut d = Digest::new(&["b"], &[]);
            d.begin(&["a", "b", "c"], &["m", "N", "1"], rows).unwrap();
            for i in 0..rows {
                let spike = if i == 2 * rows / 3 + 1 { 1e3 } else { 0.0 };
                let x = i as f64;
                d.row(1e-4 * x, &[x.sin() + spike, x, -x]).unwrap();
            }
            d
        };
        let short = feed(3 * HISTORY_ROWS + 7);
        let long = feed(10 * (3 * HISTORY_ROWS + 7));
        for d in [&short, &long] {
            let n = d.history.t.len();
            assert!((HISTORY_ROWS / 2..=HISTORY_ROWS + 1).contains(&n), "{n}");
            assert_eq!(d.history.t[0], 0.0);
            assert_eq!(*d.history.t.last().unwrap(), 1e-4 * (d.rows - 1) as f64);
            assert_eq!(d.history.column("b").unwrap()[1], d.stride as f64);
            assert!(d.peak("a") >= 999.0);
            assert_eq!(d.last("c"), -((d.rows - 1) as f64));
            assert_eq!(d.second_half("b").len(), d.rows - d.rows / 2);
            // History and full-rate tail (TAIL_ROWS) of the three columns and time.
            let history = d.values_kept() - d.second_half("b").len();
            assert!(history <= (HISTORY_ROWS + 1 + TAIL_ROWS) * 4, "{history}");
        }
        let kept = |d: &Digest| d.values_kept() - d.second_half("b").len();
        // Every row of the long run would be 2.4e6 values: history and tail keep under 1/12.
        assert!(kept(&short) <= kept(&long) && kept(&long) * 12 < long.rows * 4);
    }

    /// With a cap on the analysed rows, a run 10 times longer keeps exactly the same number
    /// of values (history and analysed column), the analysed column holds the run's last
    /// `cap` values bit for bit, and the second-half mean still folds every row of the
    /// second half.
    #[test]
    fn a_capped_digest_keeps_the_same_values_whatever_the_duration() {
        let cap = 1_000;
        let feed = |rows: usize| {
            let mut d = Digest::new(&["b"], &[]).with_cap(cap);
            d.begin(&["a", "b"], &["m", "N"], rows).unwrap();
            for i in 0..rows {
                let x = i as f64;
                d.row(1e-4 * x, &[x.cos(), x]).unwrap();
            }
            d
        };
        let (short, long) = (feed(60 * HISTORY_ROWS), feed(600 * HISTORY_ROWS));
        // The tail: the last TAIL_ROWS rows at full rate, in order, whatever the duration.
        for d in [&short, &long] {
            let a = d.tail.column("a").unwrap();
            assert_eq!(d.tail.t.len(), TAIL_ROWS);
            let first = d.rows - TAIL_ROWS;
            assert!(a.iter().zip(first..).all(|(v, i)| *v == (i as f64).cos()));
        }
        assert!(short.values_kept().abs_diff(long.values_kept()) <= 2 * 3);
        for d in [&short, &long] {
            let b = d.second_half("b");
            assert_eq!(b.len(), cap);
            assert_eq!(d.analysed_from, d.rows - cap);
            assert!(b.iter().zip(d.analysed_from..).all(|(v, i)| *v == i as f64));
            let mean: f64 =
                (d.start..d.rows).map(|i| i as f64).sum::<f64>() / (d.rows - d.start) as f64;
            assert_eq!(d.mean_second_half("b").to_bits(), mean.to_bits());
        }
    }

    /// A run records the inputs of its causality and only the outputs its level and
    /// effects set: no cage, pocket, guide, friction, film or wear columns on the linear
    /// level; the wear scene (ring level, EHL film, wear) keeps its film and wear columns;
    /// the full level its cage and guide columns. Every other output is recorded.
    #[test]
    fn a_run_records_the_outputs_its_level_and_effects_set() {
        let names = |text: &str| -> Vec<&'static str> {
            let scene = Scene::from_text(text).unwrap();
            recorded(&scene, Record::default())
                .iter()
                .map(|v| v.name)
                .collect()
        };
        let linear = names(include_str!("../examples/scenes/6205-linear.toml"));
        for gone in [
            "cage.slip",
            "cage.x",
            "cage.y",
            "cage.speed",
            "cage.speed_ratio",
            "pocket.max_force",
            "guide.force",
            "wear.max_depth",
            "film.min_thickness",
            "torque.z",
            "power.loss",
        ] {
            assert!(!linear.contains(&gone), "{gone} on the linear level");
        }
        for kept in [
            "load.y",
            "shaft.y",
            "force.y",
            "cage.omega",
            "contact.max_pressure",
            "life.L10",
        ] {
            assert!(linear.contains(&kept), "{kept} missing");
        }
        let wear = names(include_str!("../examples/scenes/6012-wear.toml"));
        assert!(wear.contains(&"wear.max_depth") && wear.contains(&"film.min_thickness"));
        assert!(!wear.contains(&"guide.force") && !wear.contains(&"power.loss"));
        let thermal = names(include_str!("../examples/scenes/7008ce-thermal.toml"));
        assert!(thermal.contains(&"power.loss") && thermal.contains(&"torque.z"));
        let full = names(include_str!("../examples/scenes/7004-30000.toml"));
        for kept in [
            "guide.force",
            "cage.x",
            "cage.slip",
            "pocket.max_force",
            "power.loss",
        ] {
            assert!(full.contains(&kept), "{kept} missing on the full level");
        }
        assert!(!full.contains(&"wear.max_depth"));
    }
}
