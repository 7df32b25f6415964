//! `raceway._raceway`: the PyO3 binding of the raceway library, the native half of the Python
//! package `raceway` (`python/python/raceway/` adds pandas and numpy on top).
//!
//! FFI only: every number comes from the library (`raceway::component`, `raceway::runner`,
//! `raceway::summary`, `raceway::sweep`); this file converts arguments, releases the GIL
//! around the library's work (`Python::detach`, PyO3's `allow_threads`) and turns the
//! library's errors into `raceway.Error` carrying the library's message.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyString, PyTuple};
use raceway::component::scene::RaceControl;
use raceway::component::{schema, variables, Component as Inner, State as InnerState};
use raceway::summary::reports;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

create_exception!(
    raceway,
    Error,
    PyException,
    "Any failure of the library; `message` is the project's message, `kind` its kind, \
     `field` the field or argument at fault (or None)."
);

/// The kind and the field of a library error.
fn kind_field(e: &raceway::Error) -> (&'static str, Option<String>) {
    use raceway::Error as E;
    match e {
        E::Invalid { field, .. } => ("invalid", Some(field.clone())),
        E::Unknown { what, .. } => ("unknown", Some(what.to_string())),
        E::Parse { .. } => ("parse", None),
        E::NotConverged { .. } => ("not_converged", None),
        E::StepFailed { .. } => ("step_failed", None),
        E::Budget { field, .. } => ("budget", Some(field.to_string())),
        E::CallOrder { .. } => ("call_order", None),
        E::Io(_) => ("io", None),
        E::Interrupted { .. } => ("interrupted", None),
    }
}

/// A `raceway.Error` with the message, kind and field as attributes.
fn py_error(py: Python<'_>, message: String, kind: &str, field: Option<String>) -> PyErr {
    let err = Error::new_err(message.clone());
    let v = err.value(py);
    // Setting attributes on a fresh exception instance cannot fail.
    let _ = v.setattr("message", message);
    let _ = v.setattr("kind", kind);
    let _ = v.setattr("field", field);
    err
}

fn to_py(py: Python<'_>, e: raceway::Error) -> PyErr {
    let (kind, field) = kind_field(&e);
    py_error(py, e.to_string(), kind, field)
}

/// Run `f` with the GIL released (PyO3's `allow_threads`, now `detach`); a library error, or
/// a panic (a bug), becomes `raceway.Error` instead of crossing into Python.
fn compute<T: Send>(py: Python<'_>, f: impl FnOnce() -> raceway::Result<T> + Send) -> PyResult<T> {
    match py.detach(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(f))) {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(e)) => Err(to_py(py, e)),
        Err(p) => {
            let what = raceway::error::panic_message(&*p).unwrap_or_default();
            Err(py_error(
                py,
                format!("internal error (a bug, please report it): panic: {what}"),
                "panic",
                None,
            ))
        }
    }
}

/// [`compute`] for work that runs on other threads (a sweep's workers), where Python's
/// signal handlers never run: `f` works on a helper thread, given a stop flag, while this
/// (the calling, usually main) thread sleeps with the GIL released and every 50 ms of wall
/// time takes it back for `py.check_signals()`. A KeyboardInterrupt (or any exception a
/// signal handler raises) sets the flag, `f` winds down (its points running give no row)
/// and the exception is raised as itself.
fn compute_interruptible<T: Send>(
    py: Python<'_>,
    f: impl FnOnce(&AtomicBool) -> raceway::Result<T> + Send,
) -> PyResult<T> {
    let stop = AtomicBool::new(false);
    let mut interrupt: Option<PyErr> = None;
    let r = compute(py, || {
        std::thread::scope(|s| {
            let worker = s.spawn(|| f(&stop));
            let mut last = std::time::Instant::now();
            while !worker.is_finished() {
                std::thread::sleep(std::time::Duration::from_millis(5));
                if interrupt.is_none() && last.elapsed() >= std::time::Duration::from_millis(50) {
                    last = std::time::Instant::now();
                    if let Err(e) = Python::attach(|py| py.check_signals()) {
                        interrupt = Some(e);
                        stop.store(true, Ordering::Relaxed);
                    }
                }
            }
            match worker.join() {
                Ok(r) => r,
                Err(p) => std::panic::resume_unwind(p),
            }
        })
    });
    match interrupt {
        Some(e) => Err(e),
        None => r,
    }
}

/// Every problem of a scene or sweep at once, one per line, as `raceway scene --check`
/// prints them; the field is the first problem's.
fn problems_error(py: Python<'_>, what: &str, problems: &[schema::Problem]) -> PyErr {
    let mut message = format!("{what}: {} problem(s)", problems.len());
    for p in problems {
        message += &format!("\n{p}");
    }
    let field = problems
        .first()
        .map(|p| p.path.clone())
        .filter(|p| !p.is_empty());
    py_error(py, message, "parse", field)
}

fn io_error(py: Python<'_>, what: &str, path: &Path, e: std::io::Error) -> PyErr {
    py_error(
        py,
        format!("cannot read {what} `{}`: {e}", path.display()),
        "io",
        None,
    )
}

/// A scene or sweep argument as text.
struct Source {
    text: String,
    /// The folder relative paths inside it are taken from (the file's, else the working
    /// directory).
    dir: PathBuf,
    /// The file's stem, when it came from a file.
    stem: Option<String>,
}

/// A scene or sweep argument: TOML/JSON text, a path, or a mapping.
fn text_of(py: Python<'_>, obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Source> {
    let cwd = PathBuf::from(".");
    let read = |p: PathBuf| -> PyResult<Source> {
        let text = std::fs::read_to_string(&p).map_err(|e| io_error(py, what, &p, e))?;
        let dir = p.parent().map(Path::to_path_buf).unwrap_or(cwd.clone());
        let stem = p.file_stem().map(|s| s.to_string_lossy().into_owned());
        Ok(Source { text, dir, stem })
    };
    if let Ok(s) = obj.cast::<PyString>() {
        let s: String = s.extract()?;
        let s = s.as_str();
        let one_line = !s.contains('\n');
        let looks_like_file =
            one_line && (Path::new(s).is_file() || s.ends_with(".toml") || s.ends_with(".json"));
        return if looks_like_file {
            read(PathBuf::from(s))
        } else {
            Ok(Source {
                text: s.to_string(),
                dir: cwd,
                stem: None,
            })
        };
    }
    if obj.hasattr("__fspath__")? {
        let p: PathBuf = obj.extract()?;
        return read(p);
    }
    if obj.cast::<PyDict>().is_ok() || obj.hasattr("keys")? {
        check_scene_value(py, obj, &mut String::new(), 0)?;
        let json: String = py
            .import("json")?
            .call_method1("dumps", (obj,))
            .and_then(|j| j.extract())
            .map_err(|e| {
                py_error(
                    py,
                    format!("{what}: the mapping cannot be written as JSON: {e}"),
                    "invalid",
                    Some(what.to_string()),
                )
            })?;
        return Ok(Source {
            text: json,
            dir: cwd,
            stem: None,
        });
    }
    Err(py_error(
        py,
        format!(
            "{what}: expected TOML or JSON text, a path or a dict, found {}",
            obj.get_type().name()?
        ),
        "invalid",
        Some(what.to_string()),
    ))
}

/// The (name, value) pairs of `Component.set`'s first argument when it is not a name: a
/// mapping or a sequence of pairs. Anything else, or an item that is not a (str, float)
/// pair, is a `raceway.Error` naming the argument (it was an AttributeError or TypeError).
fn input_pairs(py: Python<'_>, arg: &Bound<'_, PyAny>) -> PyResult<Vec<(String, f64)>> {
    let refuse = |what: String| {
        py_error(
            py,
            format!(
                "set: {what}: expected a variable name (str) and a value, a dict of names to \
                 values, or a sequence of (name, value) pairs"
            ),
            "invalid",
            Some("name".into()),
        )
    };
    let kind = |o: &Bound<'_, PyAny>| {
        o.get_type()
            .name()
            .map_or_else(|_| "?".to_string(), |n| n.to_string())
    };
    let items = if arg.hasattr("items").unwrap_or(false) {
        arg.call_method0("items")
            .map_err(|_| refuse(format!("{}.items() failed", kind(arg))))?
    } else if arg.cast::<PyList>().is_ok() || arg.cast::<PyTuple>().is_ok() {
        arg.clone()
    } else {
        return Err(refuse(format!("found {}", kind(arg))));
    };
    let iter = items
        .try_iter()
        .map_err(|_| refuse(format!("found {}", kind(arg))))?;
    let mut out = Vec::new();
    for (i, item) in iter.enumerate() {
        let item = item.map_err(|_| refuse(format!("item {i} could not be read")))?;
        let pair = item.extract::<(String, f64)>().map_err(|_| {
            let shown = item
                .repr()
                .map_or_else(|_| "?".to_string(), |r| r.to_string());
            refuse(format!("item {i} = {shown} is not a (name, number) pair"))
        })?;
        out.push(pair);
    }
    Ok(out)
}

/// A scene given as a dict, checked before it becomes JSON: a number that is not finite is
/// refused naming its field (JSON has no NaN: it was reported as a syntax error without
/// one), and nesting deeper than the scene limit is refused naming where (a deeply nested
/// or self-containing dict raised RecursionError or ValueError). `path` is the dotted
/// field of `obj`.
fn check_scene_value(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    path: &mut String,
    depth: usize,
) -> PyResult<()> {
    let max = raceway::nesting::MAX_NESTING;
    let field = |path: &str| {
        if path.is_empty() {
            "scene".to_string()
        } else {
            path.to_string()
        }
    };
    if depth > max {
        return Err(py_error(
            py,
            format!(
                "scene: `{}` nests deeper than {max} levels (tables and arrays together): a \
                 scene may nest at most {max}",
                field(path)
            ),
            "invalid",
            Some(field(path)),
        ));
    }
    let descend = |key: String, v: &Bound<'_, PyAny>, path: &mut String| -> PyResult<()> {
        let len = path.len();
        path.push_str(&key);
        let r = check_scene_value(py, v, path, depth + 1);
        path.truncate(len);
        r
    };
    if let Ok(d) = obj.cast::<PyDict>() {
        for (k, v) in d.iter() {
            let k = k.str().map_or_else(|_| "?".to_string(), |k| k.to_string());
            let key = if path.is_empty() { k } else { format!(".{k}") };
            descend(key, &v, path)?;
        }
    } else if obj.cast::<PyList>().is_ok() || obj.cast::<PyTuple>().is_ok() {
        for (i, v) in obj.try_iter()?.enumerate() {
            descend(format!("[{i}]"), &v?, path)?;
        }
    } else if obj.cast::<pyo3::types::PyFloat>().is_ok() {
        let x: f64 = obj.extract()?;
        if !x.is_finite() {
            return Err(py_error(
                py,
                format!(
                    "scene: `{}` = {x}: must be a finite number (see `raceway scene --schema` \
                     for its range)",
                    field(path)
                ),
                "invalid",
                Some(field(path)),
            ));
        }
    }
    Ok(())
}

/// The text and name of an optional scene argument (None: the embedded default scene,
/// named `default`; a file: its stem, as `raceway run` names it; else `scene`).
fn scene_text(py: Python<'_>, scene: Option<&Bound<'_, PyAny>>) -> PyResult<(String, String)> {
    match scene.filter(|s| !s.is_none()) {
        None => Ok((
            raceway::component::scene::DEFAULT_SCENE.to_string(),
            "default".into(),
        )),
        Some(s) => {
            let src = text_of(py, s, "scene")?;
            Ok((src.text, src.stem.unwrap_or_else(|| "scene".into())))
        }
    }
}

/// A scene checked as `raceway scene --check` checks a file (every problem at once), with
/// overrides (`run.duration_s`).
fn load_scene(py: Python<'_>, text: &str, overrides: &[(&str, f64)]) -> PyResult<raceway::Scene> {
    schema::load(text, overrides).map_err(|p| problems_error(py, "scene", &p))
}

fn variable(py: Python<'_>, name: &str) -> PyResult<&'static variables::Variable> {
    variables::by_name(name).ok_or_else(|| {
        to_py(
            py,
            raceway::Error::Unknown {
                what: "variable",
                name: name.to_string(),
                known: variables::all().map(|v| v.name.to_string()).collect(),
            },
        )
    })
}

/// An opaque snapshot of a component's state.
#[pyclass(module = "raceway._raceway", frozen)]
pub struct State {
    inner: InnerState,
}

#[pymethods]
impl State {
    /// The time of the snapshot, s.
    #[getter]
    fn time(&self) -> f64 {
        self.inner.t
    }

    fn __bytes__<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.inner.to_bytes())
    }

    /// A state from its bytes (what pickling uses).
    #[staticmethod]
    fn from_bytes(py: Python<'_>, data: &[u8]) -> PyResult<State> {
        InnerState::from_bytes(data)
            .map(|inner| State { inner })
            .map_err(|e| to_py(py, e))
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let ctor = slf.get_type().getattr("from_bytes")?;
        let bytes = PyBytes::new(py, &slf.get().inner.to_bytes());
        PyTuple::new(py, [ctor.into_any(), PyTuple::new(py, [bytes])?.into_any()])
    }

    fn __repr__(&self) -> String {
        format!("<raceway.State at t = {} s>", self.inner.t)
    }
}

/// The bearing as a co-simulation component (see `raceway/__init__.pyi`).
#[pyclass(module = "raceway._raceway")]
pub struct Component {
    // A Mutex makes the class Sync, as PyO3 requires; the `&mut self` methods reach the
    // component without locking (`get_mut`).
    inner: Mutex<Inner>,
}

impl Component {
    fn inner(&self) -> std::sync::MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn inner_mut(&mut self) -> &mut Inner {
        self.inner.get_mut().unwrap_or_else(|e| e.into_inner())
    }
}

#[pymethods]
impl Component {
    #[new]
    #[pyo3(signature = (scene=None))]
    fn new(py: Python<'_>, scene: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        let (text, _) = scene_text(py, scene)?;
        let scene = load_scene(py, &text, &[])?;
        let inner = compute(py, || Inner::new(scene))?;
        Ok(Component {
            inner: Mutex::new(inner),
        })
    }

    #[getter]
    fn time(&self) -> f64 {
        self.inner().time()
    }

    #[getter]
    fn level(&self) -> &'static str {
        self.inner().scene().model.level.name()
    }

    #[getter]
    fn causality(&self) -> &'static str {
        match self.inner().causality() {
            variables::Causality::Motion => "motion",
            variables::Causality::Load => "load",
        }
    }

    #[getter]
    fn bearing(&self) -> String {
        self.inner().bearing().name.clone()
    }

    /// Set one input, or several from a mapping (all or none).
    #[pyo3(signature = (name, value=None))]
    fn set(&mut self, py: Python<'_>, name: &Bound<'_, PyAny>, value: Option<f64>) -> PyResult<()> {
        let pairs: Vec<(String, f64)> = if let Ok(n) = name.extract::<String>() {
            let v = value.ok_or_else(|| {
                py_error(
                    py,
                    format!("set(\"{n}\"): a value is needed"),
                    "invalid",
                    Some(n.clone()),
                )
            })?;
            vec![(n, v)]
        } else {
            input_pairs(py, name)?
        };
        let mut vrs = Vec::with_capacity(pairs.len());
        for (n, _) in &pairs {
            vrs.push(variable(py, n)?.vr);
        }
        let values: Vec<f64> = pairs.iter().map(|p| p.1).collect();
        self.inner_mut()
            .set_reals(&vrs, &values)
            .map_err(|(_, e)| to_py(py, e))
    }

    /// The value of one variable by name.
    fn get(&mut self, py: Python<'_>, name: &str) -> PyResult<f64> {
        let vr = variable(py, name)?.vr;
        let inner = self.inner_mut();
        compute(py, || inner.get_real(vr))
    }

    /// Advance from `t` to `t + h` (the GIL released while the bearing sub-steps).
    fn do_step(&mut self, py: Python<'_>, t: f64, h: f64) -> PyResult<()> {
        let inner = self.inner_mut();
        compute(py, || inner.do_step(t, h))
    }

    /// Every output at the current time, by name.
    fn outputs<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let inner = self.inner_mut();
        let causality = inner.causality();
        let values = compute(py, || {
            inner.ensure_outputs()?;
            variables::all()
                .filter(|v| v.is_output(causality))
                .map(|v| inner.get_real(v.vr).map(|x| (v.name, x)))
                .collect::<raceway::Result<Vec<_>>>()
        })?;
        let d = PyDict::new(py);
        for (k, v) in values {
            d.set_item(k, v)?;
        }
        Ok(d)
    }

    /// Every input of this causality, by name.
    fn inputs<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let inner = self.inner_mut();
        let causality = inner.causality();
        let d = PyDict::new(py);
        for v in variables::all().filter(|v| v.is_input(causality)) {
            let x = inner.get_real(v.vr).map_err(|e| to_py(py, e))?;
            d.set_item(v.name, x)?;
        }
        Ok(d)
    }

    fn get_state(&self) -> State {
        State {
            inner: self.inner().get_state(),
        }
    }

    fn set_state(&mut self, py: Python<'_>, state: &State) -> PyResult<()> {
        self.inner_mut()
            .set_state(&state.inner)
            .map_err(|e| to_py(py, e))
    }

    fn state_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.inner().serialize_state())
    }

    fn set_state_bytes(&mut self, py: Python<'_>, data: &[u8]) -> PyResult<()> {
        self.inner_mut()
            .deserialize_state(data)
            .map_err(|e| to_py(py, e))
    }

    fn __repr__(&self) -> String {
        let c = self.inner();
        format!(
            "<raceway.Component {} at level {}, t = {} s>",
            c.bearing().name,
            c.scene().model.level.name(),
            c.time()
        )
    }
}

/// The variable table: (name, vr, unit, role, description) per variable.
#[pyfunction]
fn variable_table() -> Vec<(&'static str, u32, &'static str, &'static str, &'static str)> {
    variables::all()
        .map(|v| {
            let role = match v.role {
                variables::Role::Motion => "motion",
                variables::Role::Speed => "speed",
                variables::Role::Load => "load",
                variables::Role::Output => "output",
            };
            (v.name, v.vr, v.unit, role, v.description)
        })
        .collect()
}

/// A stand-alone run: (column names with units, columns, summary JSON).
#[pyfunction]
#[pyo3(signature = (scene=None, duration=None, kc=false))]
fn run(
    py: Python<'_>,
    scene: Option<&Bound<'_, PyAny>>,
    duration: Option<f64>,
    kc: bool,
) -> PyResult<(Vec<String>, Vec<Vec<f64>>, String)> {
    let (text, name) = scene_text(py, scene)?;
    let overrides: Vec<(&str, f64)> = duration
        .map(|d| ("run.duration_s", d))
        .into_iter()
        .collect();
    let scene = load_scene(py, &text, &overrides)?;
    // Ctrl-C: the run asks Python for pending signals every 50 ms of wall time (taking the
    // GIL back for that moment); a KeyboardInterrupt stops it before its next step and is
    // raised as itself.
    let mut interrupt: Option<PyErr> = None;
    let result = compute(py, || {
        let c0 = raceway::report::thread_cpu_s();
        let mut last = std::time::Instant::now();
        let mut stop = || {
            if last.elapsed() < std::time::Duration::from_millis(50) {
                return false;
            }
            last = std::time::Instant::now();
            match Python::attach(|py| py.check_signals()) {
                Ok(()) => false,
                Err(e) => {
                    interrupt = Some(e);
                    true
                }
            }
        };
        let mut series = raceway::runner::Series::default();
        let mut digest = raceway::summary::digest_for(&scene);
        let comp = raceway::runner::run_into(
            &scene,
            raceway::runner::Record {
                stiffness_damping: kc,
            },
            false,
            &mut |_| {},
            &mut stop,
            &mut raceway::runner::Tee(&mut series, &mut digest),
        )?;
        let cpu = raceway::report::thread_cpu_s() - c0;
        let summary = raceway::summary::summarize(&scene, &name, &digest, &comp, cpu);
        // The columns of series.csv's header (`t [s]`, `<name> [unit]`), from one place.
        let names = series.header();
        let mut columns = vec![series.t];
        columns.extend(series.columns);
        Ok((
            names,
            columns,
            serde_json::Value::Object(summary.json).to_string(),
        ))
    });
    match interrupt {
        Some(e) => Err(e),
        None => result,
    }
}

/// Numbers as `a,b,c` (each as Rust prints it back exactly).
fn join_numbers(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:?}"))
        .collect::<Vec<_>>()
        .join(",")
}

/// `raceway quasi-static --json` as text, plus (ball columns with units, their values).
#[pyfunction]
#[pyo3(signature = (bearing, speed_rpm, load, race_control, kappa, contamination, oil=None, oil_vi=None, oil_temp_c=None, f0=None, shaft_interference_um=None, housing_interference_um=None, inner_ring_temp_c=None, outer_ring_temp_c=None, hold=None, ambient_temp_c=None, duty=None, skf_lubrication=None, skf_seal=None, skf_drag=None, skf_constants=None))]
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
fn quasi_static(
    py: Python<'_>,
    bearing: Option<String>,
    speed_rpm: f64,
    load: [f64; 5],
    race_control: Option<String>,
    kappa: Option<f64>,
    contamination: Option<f64>,
    oil: Option<String>,
    oil_vi: Option<f64>,
    oil_temp_c: Option<f64>,
    f0: Option<f64>,
    shaft_interference_um: Option<f64>,
    housing_interference_um: Option<f64>,
    inner_ring_temp_c: Option<f64>,
    outer_ring_temp_c: Option<f64>,
    hold: Option<std::collections::BTreeMap<String, f64>>,
    ambient_temp_c: Option<f64>,
    duty: Option<String>,
    skf_lubrication: Option<String>,
    skf_seal: Option<Vec<f64>>,
    skf_drag: Option<Vec<f64>>,
    skf_constants: Option<Vec<f64>>,
) -> PyResult<(String, Vec<String>, Vec<Vec<f64>>)> {
    // A roller designation: the roller equilibrium and its report, the one
    // `raceway quasi-static --bearing NU206 --json` prints (same function, same shape).
    if let Some(b) = bearing
        .as_deref()
        .and_then(raceway::summary::rollers::roller_bearing)
    {
        // The ball-only options have no meaning here: refused by name, not ignored.
        let given = [
            ("race_control", race_control.is_some()),
            ("kappa", kappa.is_some()),
            ("contamination", contamination.is_some()),
            ("oil", oil.is_some()),
            ("oil_vi", oil_vi.is_some()),
            ("oil_temp_c", oil_temp_c.is_some()),
            ("f0", f0.is_some()),
            ("shaft_interference_um", shaft_interference_um.is_some()),
            ("housing_interference_um", housing_interference_um.is_some()),
            ("inner_ring_temp_c", inner_ring_temp_c.is_some()),
            ("outer_ring_temp_c", outer_ring_temp_c.is_some()),
            ("hold", hold.is_some()),
            ("ambient_temp_c", ambient_temp_c.is_some()),
            ("duty", duty.is_some()),
            ("skf_lubrication", skf_lubrication.is_some()),
            ("skf_seal", skf_seal.is_some()),
            ("skf_drag", skf_drag.is_some()),
            ("skf_constants", skf_constants.is_some()),
        ];
        if let Some((name, _)) = given.iter().find(|(_, g)| *g) {
            return Err(to_py(
                py,
                raceway::Error::invalid(
                    *name,
                    "given",
                    "None for a roller bearing (its quasi-static report has the loads, \
                     laminae, stiffness and ISO 281/76 ratings only)",
                ),
            ));
        }
        return compute(py, || {
            let n = &reports::PYTHON_NAMES;
            let r = raceway::summary::rollers::report(&b?, speed_rpm, load, (n.load, n.speed_rpm))?;
            Ok((
                serde_json::to_string(&r.to_json()).expect("the report serialises"),
                Vec::new(),
                Vec::new(),
            ))
        });
    }
    let options = raceway::calculator::check::CalcOptions {
        oil,
        oil_vi,
        oil_temp_c,
        f0,
        shaft_interference_um,
        housing_interference_um,
        inner_ring_temp_c,
        outer_ring_temp_c,
        ambient_temp_c,
        // One parser for the command line and Python: the numbers as `a,b,c`.
        skf_lubrication,
        skf_seal: skf_seal.map(|v| join_numbers(&v)),
        skf_drag: skf_drag.map(|v| join_numbers(&v)),
        skf_constants: skf_constants.map(|v| join_numbers(&v)),
    };
    compute(py, || {
        let scene = raceway::Scene::default_scene();
        let bearing = match bearing.as_deref() {
            Some(b) => reports::load_bearing(b)?,
            None => scene.build_bearing()?,
        };
        let race_control = match race_control.as_deref() {
            None => scene.model.race_control,
            Some("outer") => RaceControl::Outer,
            Some("none") => RaceControl::None,
            Some(other) => {
                return Err(raceway::Error::invalid(
                    "race_control",
                    format!("\"{other}\""),
                    "\"outer\" or \"none\"",
                ))
            }
        };
        let mut problem = reports::QsProblem::new(
            bearing,
            speed_rpm,
            load,
            race_control,
            kappa,
            contamination,
            &reports::PYTHON_NAMES,
        )?;
        problem.calc = raceway::calculator::check::CalcInputs::from_options(
            &options, speed_rpm, "oil_vi", "skf_",
        )?;
        if let Some(text) = &duty {
            // The spectrum's text (the package reads a file or writes a list's rows).
            problem.calc.duty = Some(raceway::calculator::duty::parse_spectrum(text, "duty")?);
        }
        if let Some(h) = &hold {
            // One parser for the command line and Python: `name=value` pairs.
            let text = h
                .iter()
                .map(|(k, v)| format!("{k}={v:?}"))
                .collect::<Vec<_>>()
                .join(",");
            problem.hold = raceway::models::quasi_static::hold::HoldSpec::parse(&text, "hold")?;
        }
        let (sol, rating) = problem.solve()?;
        problem.design_check(&sol, &rating)?;
        let json =
            serde_json::to_string(&reports::quasi_static_report(&problem, &sol, &rating).to_json())
                .expect("the report serialises");
        let (names, columns) = reports::ball_columns(&sol);
        Ok((json, names, columns))
    })
}

/// `raceway shaft FILE --json` as text: the shaft file's text (TOML) solved.
#[pyfunction]
fn shaft_json(py: Python<'_>, shaft: &Bound<'_, PyAny>) -> PyResult<String> {
    let src = text_of(py, shaft, "shaft")?;
    compute(py, || {
        let sol = raceway::models::shaft_file::from_toml(&src.text)?.solve()?;
        let v = raceway::summary::columns::to_labelled_json(
            raceway::summary::columns::Doc::Shaft,
            &sol,
        );
        Ok(serde_json::to_string(&v).expect("the solution serialises"))
    })
}

/// `raceway bearings --json`.
#[pyfunction]
fn bearings_json(py: Python<'_>) -> PyResult<String> {
    reports::bearings_json()
        .map(|rows| serde_json::to_string(&rows).unwrap_or_default())
        .map_err(|e| to_py(py, e))
}

/// `raceway bearings NAME --json`.
#[pyfunction]
fn bearing_json(py: Python<'_>, name: &str) -> PyResult<String> {
    reports::bearing_json(name)
        .map(|d| serde_json::to_string(&d).unwrap_or_default())
        .map_err(|e| to_py(py, e))
}

/// A parsed sweep; pickles as its self-contained TOML text (base scene inlined).
#[pyclass(module = "raceway._raceway", frozen)]
pub struct Sweep {
    inner: raceway::sweep::Sweep,
    text: String,
}

impl Sweep {
    fn parse(py: Python<'_>, text: &str, dir: &Path) -> PyResult<Sweep> {
        // A dict arrives as JSON: the sweep file is TOML, so convert it.
        let text = if text.trim_start().starts_with('{') {
            serde_json::from_str::<serde_json::Value>(text)
                .map_err(|e| e.to_string())
                .and_then(|v| toml::Table::try_from(v).map_err(|e| e.to_string()))
                .and_then(|t| toml::to_string(&t).map_err(|e| e.to_string()))
                .map_err(|e| py_error(py, format!("sweep: {e}"), "parse", None))?
        } else {
            text.to_string()
        };
        let inner = raceway::sweep::Sweep::from_text(&text, dir)
            .map_err(|p| problems_error(py, "sweep", &p))?;
        // Self-contained: the base scene (read from its file, if any) inlined as [scene].
        let mut doc: toml::Table = text.parse().unwrap_or_default();
        doc.insert("scene".into(), toml::Value::Table(inner.base.clone()));
        let text = toml::to_string(&doc).map_err(|e| py_error(py, e.to_string(), "parse", None))?;
        Ok(Sweep { inner, text })
    }

    fn index(&self, py: Python<'_>, index: usize) -> PyResult<usize> {
        if index < self.inner.len() {
            Ok(index)
        } else {
            Err(to_py(
                py,
                raceway::Error::invalid(
                    "index",
                    index,
                    format!("0..{} (the sweep's points)", self.inner.len()),
                ),
            ))
        }
    }
}

fn row_json(row: &raceway::sweep::Row) -> String {
    serde_json::to_string(row).expect("a row serialises")
}

#[pymethods]
impl Sweep {
    #[new]
    fn new(py: Python<'_>, sweep: &Bound<'_, PyAny>) -> PyResult<Self> {
        let src = text_of(py, sweep, "sweep")?;
        Sweep::parse(py, &src.text, &src.dir)
    }

    fn __len__(&self) -> usize {
        self.inner.len()
    }

    #[getter]
    fn columns(&self) -> Vec<String> {
        self.inner.axes.iter().map(|a| a.column.clone()).collect()
    }

    /// The self-contained sweep text (what pickling carries).
    #[getter]
    fn text(&self) -> &str {
        &self.text
    }

    /// The axes' values at a point, as JSON `[[column, value], ...]` in axis order.
    fn point_json(&self, py: Python<'_>, index: usize) -> PyResult<String> {
        let i = self.index(py, index)?;
        let pairs: Vec<(String, serde_json::Value)> = self
            .inner
            .axes
            .iter()
            .zip(self.inner.point(i))
            .map(|(a, v)| {
                (
                    a.column.clone(),
                    serde_json::to_value(&v).unwrap_or_default(),
                )
            })
            .collect();
        Ok(serde_json::to_string(&pairs).expect("values serialise"))
    }

    fn scene_text(&self, py: Python<'_>, index: usize) -> PyResult<String> {
        let i = self.index(py, index)?;
        self.inner.scene_text(i).map_err(|e| to_py(py, e))
    }

    /// Run points (GIL released); each row as JSON. `series_dir`: write each run's series
    /// there as `<index>.csv` when the sweep asks for series.
    #[pyo3(signature = (indices, series_dir=None))]
    fn run_points_json(
        &self,
        py: Python<'_>,
        indices: Vec<usize>,
        series_dir: Option<PathBuf>,
    ) -> PyResult<Vec<String>> {
        for &i in &indices {
            self.index(py, i)?;
        }
        let sw = &self.inner;
        // Ctrl-C: KeyboardInterrupt within 0.2 s (the point running is abandoned).
        compute_interruptible(py, |stop| {
            let stopped = || stop.load(Ordering::Relaxed);
            let mut rows = Vec::with_capacity(indices.len());
            for &i in &indices {
                let series = series_dir
                    .as_ref()
                    .filter(|_| sw.series)
                    .map(|d| d.join(format!("{i:08}.csv")));
                match sw.run_point_until(i, series.as_deref(), &stopped) {
                    Some(row) => rows.push(row_json(&row)),
                    None => return Err(raceway::Error::Interrupted { at_s: 0.0 }),
                }
            }
            Ok(rows)
        })
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let args = PyTuple::new(py, [slf.get().text.clone()])?;
        PyTuple::new(py, [slf.get_type().into_any(), args.into_any()])
    }

    fn __repr__(&self) -> String {
        format!(
            "<raceway.Sweep of {} points over {}>",
            self.inner.len(),
            self.columns().join(", ")
        )
    }
}

fn rows_of(py: Python<'_>, rows: Vec<String>) -> PyResult<Vec<raceway::sweep::Row>> {
    rows.iter()
        .map(|r| {
            serde_json::from_str(r)
                .map_err(|e| py_error(py, format!("not a sweep row: {e}"), "parse", None))
        })
        .collect()
}

/// The CSV table of rows (JSON), exactly as `raceway sweep` writes sweep.csv.
#[pyfunction]
fn sweep_csv(py: Python<'_>, rows: Vec<String>) -> PyResult<String> {
    let mut rows = rows_of(py, rows)?;
    rows.sort_by_key(|r| r.index);
    rows.dedup_by_key(|r| r.index);
    Ok(raceway::sweep::csv(&rows))
}

/// Run a sweep into `out` as `raceway sweep` does (threads, shard, resumable).
#[pyfunction]
#[pyo3(signature = (sweep, out, jobs=None, shard=None))]
fn sweep_execute(
    py: Python<'_>,
    sweep: &Sweep,
    out: PathBuf,
    jobs: Option<usize>,
    shard: Option<(usize, usize)>,
) -> PyResult<()> {
    let jobs = match jobs {
        Some(0) => {
            return Err(to_py(py, raceway::Error::invalid("jobs", 0, ">= 1")));
        }
        Some(j) => j,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let exec = raceway::sweep::Exec {
        jobs,
        shard: shard.unwrap_or((0, 1)),
    };
    let sw = &sweep.inner;
    // Ctrl-C: KeyboardInterrupt within 0.2 s; the finished points keep their rows (the
    // sweep resumes from them), the running ones have none.
    compute_interruptible(py, |stop| {
        raceway::sweep::execute_until(sw, &out, exec, &|_, _, _| {}, &|| {
            stop.load(Ordering::Relaxed)
        })
    })
    .map(|_| ())
}

/// The indices of the finished rows in `out` (claiming the folder for this sweep, as
/// `raceway sweep` does: another sweep's folder is refused).
#[pyfunction]
fn sweep_finished(py: Python<'_>, sweep: &Sweep, out: PathBuf) -> PyResult<Vec<usize>> {
    raceway::sweep::claim_dir(&out, &sweep.inner.fingerprint()).map_err(|e| to_py(py, e))?;
    Ok(raceway::sweep::read_rows(&out)
        .into_iter()
        .map(|r| r.index)
        .collect())
}

/// Write rows (JSON) into `out/rows/` atomically, then `out/sweep.csv` from every finished
/// row there; returns the CSV text.
#[pyfunction]
fn sweep_store(py: Python<'_>, out: PathBuf, rows: Vec<String>) -> PyResult<String> {
    let rows = rows_of(py, rows)?;
    compute(py, || raceway::sweep::store(&out, &rows))
}

#[pymodule]
fn _raceway(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("Error", py.get_type::<Error>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("DOF", PyList::new(py, variables::DOF)?)?;
    m.add_class::<State>()?;
    m.add_class::<Component>()?;
    m.add_class::<Sweep>()?;
    m.add_function(wrap_pyfunction!(variable_table, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(quasi_static, m)?)?;
    m.add_function(wrap_pyfunction!(shaft_json, m)?)?;
    m.add_function(wrap_pyfunction!(bearings_json, m)?)?;
    m.add_function(wrap_pyfunction!(bearing_json, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_csv, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_execute, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_finished, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_store, m)?)?;
    Ok(())
}
