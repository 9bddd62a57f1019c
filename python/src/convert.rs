//! Conversions between Python and settle: errors, TOML values, tables; and [`blocking`], the
//! one way a binding runs a computation (GIL released, Ctrl-C polled, progress watched).

use pyo3::create_exception;
use pyo3::exceptions::{PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{
    PyBool, PyByteArray, PyBytes, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple,
};
use settle::{Column, Drawn, Error, Figure, Table};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

create_exception!(
    settle,
    ScenarioError,
    PyValueError,
    "Bad input: a scenario key that does not exist, a value out of range, a file that cannot be read as a scenario. The message is the command line's; `.key` names the key when one is named, `.file` the file."
);
create_exception!(
    settle,
    UnstableError,
    PyRuntimeError,
    "The run went unstable (the command line's exit 3): the message names the body, the time and a stable time step."
);

/// The Python exception of a settle error: `ScenarioError` (with `key`, `file`) for bad input,
/// `UnstableError`, `OSError` for I/O, `KeyboardInterrupt` for a run stopped by Ctrl-C.
pub fn to_py(e: Error) -> PyErr {
    let msg = e.to_string();
    match e {
        Error::BadInput(b) => Python::with_gil(|py| {
            let err = ScenarioError::new_err(msg);
            let v = err.value(py);
            let key = b.key.clone();
            let _ = v.setattr("key", key);
            let _ = v.setattr("file", b.file.to_string_lossy().into_owned());
            err
        }),
        Error::Unstable(..) => UnstableError::new_err(msg),
        Error::Io(_, cause) => Python::with_gil(|py| {
            let err = PyOSError::new_err(msg);
            let v = err.value(py);
            let _ = v.setattr("errno", cause.raw_os_error());
            err
        }),
        Error::Interrupted(_) | Error::InterruptedUnwritten(_) => PyKeyboardInterrupt::new_err(msg),
    }
}

/// A Python value (bool, int, float, str, list/tuple, dict) as a TOML value.
pub fn toml_value(v: &Bound<'_, PyAny>, at: &str) -> PyResult<toml::Value> {
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(v.extract()?));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract()?));
    }
    if let Ok(d) = v.downcast::<PyDict>() {
        return Ok(toml::Value::Table(toml_table(d, at)?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items = v
            .try_iter()?
            .enumerate()
            .map(|(i, x)| toml_value(&x?, &format!("{at}[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    // numpy scalars and other numbers: through float() when they have it.
    if v.hasattr("__float__")? {
        return Ok(toml::Value::Float(v.call_method0("__float__")?.extract()?));
    }
    Err(PyTypeError::new_err(format!(
        "{at}: a scenario value is a bool, int, float, str, list or dict, not {}",
        v.get_type().name()?
    )))
}

pub fn toml_table(d: &Bound<'_, PyDict>, at: &str) -> PyResult<toml::Table> {
    let mut t = toml::Table::new();
    for (k, v) in d.iter() {
        let k: String = k
            .extract()
            .map_err(|_| PyTypeError::new_err(format!("{at}: scenario keys are strings")))?;
        let path = if at.is_empty() {
            k.clone()
        } else {
            format!("{at}.{k}")
        };
        if v.is_none() {
            continue; // None: the key left out (its default)
        }
        t.insert(k, toml_value(&v, &path)?);
    }
    Ok(t)
}

/// The TOML text of a Python value, as `--set KEY=VALUE` reads VALUE.
#[pyfunction]
pub fn toml_text(value: &Bound<'_, PyAny>) -> PyResult<String> {
    Ok(toml_value(value, "value")?.to_string())
}

/// Every table as `(stem, header, columns, preamble)`: a numeric column is a bytearray of its
/// native f64 values (empty cells NaN; read with numpy.frombuffer), a text column a list of
/// str with None for an empty cell; the preamble the comment lines before the header.
pub fn raw_tables<'py>(py: Python<'py>, tables: &[Table]) -> PyResult<Vec<Bound<'py, PyTuple>>> {
    tables
        .iter()
        .map(|t| {
            let cols = t
                .header()
                .iter()
                .map(|h| match t.column(h) {
                    Some(Column::Numbers(v)) => {
                        // written straight into a Python bytearray, which numpy then views
                        // (writable, no copy) and pandas keeps as the column (copy=False)
                        let b = PyByteArray::new_with(py, v.len() * 8, |buf| {
                            for (cell, x) in buf.chunks_exact_mut(8).zip(&v) {
                                cell.copy_from_slice(&x.unwrap_or(f64::NAN).to_ne_bytes());
                            }
                            Ok(())
                        })?;
                        Ok(b.into_any())
                    }
                    Some(Column::Text(v)) => {
                        let cells: Vec<Option<String>> = v
                            .into_iter()
                            .map(|c| if c.is_empty() { None } else { Some(c) })
                            .collect();
                        Ok(PyList::new(py, cells)?.into_any())
                    }
                    None => Err(PyRuntimeError::new_err(format!(
                        "{}: no column `{h}`",
                        t.name()
                    ))),
                })
                .collect::<PyResult<Vec<_>>>()?;
            PyTuple::new(
                py,
                [
                    t.stem().into_pyobject(py)?.into_any(),
                    PyList::new(py, t.header())?.into_any(),
                    PyList::new(py, cols)?.into_any(),
                    PyList::new(py, t.preamble())?.into_any(),
                ],
            )
        })
        .collect()
}

/// Runs of this process still going (detached ones included): the last one to end withdraws a
/// Ctrl-C's stop request.
static ACTIVE: AtomicUsize = AtomicUsize::new(0);

/// How long a stopped computation may take to return before the `KeyboardInterrupt` is raised
/// without it (it then finishes in the background and its result is dropped), s.
const GRACE_S: f64 = 0.3;

/// Runs `f` on a worker thread with the GIL released, as every binding runs a computation.
/// Every 0.1 s the calling thread takes the GIL to check Python's signals: a Ctrl-C
/// (`KeyboardInterrupt`) asks settle to stop ([`settle::interrupt::request`]); `f` stops at its
/// next check (every step or case) and the KeyboardInterrupt is raised as soon as `f` returns,
/// or after [`GRACE_S`] if `f` is still making the outputs of what it did (they are dropped:
/// nothing is written). Ctrl-C stops every settle run of the process, as on the command line;
/// the last to end withdraws the request, and a new computation waits for that first. When
/// `progress` is a callable it is called (with the GIL) with `(name, pos, len, unit, message)`
/// whenever the computation's progress bar moves.
pub fn blocking<T: Send + 'static>(
    py: Python<'_>,
    progress: Option<&Bound<'_, PyAny>>,
    f: impl FnOnce() -> Result<T, Error> + Send + 'static,
) -> PyResult<T> {
    wait_for_stopped_runs(py)?;
    let watch = settle::Watch::new();
    let (tx, rx) = std::sync::mpsc::channel();
    let w = watch.clone();
    ACTIVE.fetch_add(1, Ordering::SeqCst);
    std::thread::spawn(move || {
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| w.scope(f)));
        if ACTIVE.fetch_sub(1, Ordering::SeqCst) == 1 && settle::interrupt::requested() {
            settle::interrupt::clear();
        }
        let _ = tx.send(r);
    });
    // A Mutex makes the receiver shareable with the GIL-free closure below.
    let rx = std::sync::Mutex::new(rx);
    let mut interrupted: Option<(PyErr, Instant)> = None;
    let mut last = None;
    let outcome = loop {
        let got = py.allow_threads(|| match rx.lock() {
            Ok(rx) => rx.recv_timeout(Duration::from_millis(100)),
            Err(_) => Err(std::sync::mpsc::RecvTimeoutError::Disconnected),
        });
        match got {
            Ok(r) => break Some(r),
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break None,
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
        }
        match &interrupted {
            None => {
                if let Err(e) = py.check_signals() {
                    settle::interrupt::request();
                    interrupted = Some((e, Instant::now()));
                }
            }
            Some((_, at)) if at.elapsed().as_secs_f64() > GRACE_S => break None,
            Some(_) => {}
        }
        if let (Some(cb), Some(shown)) = (progress, watch.shown()) {
            let key = (shown.pos, shown.message.clone());
            if last.as_ref() != Some(&key) {
                last = Some(key);
                let args = (shown.name, shown.pos, shown.len, shown.unit, shown.message);
                if let Err(e) = cb.call1(args) {
                    // A failing callback stops the run as Ctrl-C would, and is raised.
                    settle::interrupt::request();
                    interrupted.get_or_insert((e, Instant::now()));
                }
            }
        }
    };
    if let Some((e, _)) = interrupted {
        return Err(e);
    }
    if let (Some(cb), Some(shown)) = (progress, watch.shown()) {
        let _ = cb.call1((shown.name, shown.pos, shown.len, shown.unit, shown.message));
    }
    match outcome {
        Some(Ok(r)) => r.map_err(to_py),
        Some(Err(_)) | None => Err(PyRuntimeError::new_err(
            "settle panicked: this is a bug, please report it with the scenario",
        )),
    }
}

/// After a Ctrl-C, waits (GIL released, signals checked) until every stopped computation has
/// ended, so that a new one is not stopped by the old request.
fn wait_for_stopped_runs(py: Python<'_>) -> PyResult<()> {
    while settle::interrupt::requested() {
        if ACTIVE.load(Ordering::SeqCst) == 0 {
            settle::interrupt::clear();
            break;
        }
        py.allow_threads(|| std::thread::sleep(Duration::from_millis(20)));
        py.check_signals()?;
    }
    Ok(())
}

/// Numbers as the bytes of native f64 values (read with numpy.frombuffer).
fn f64_bytes<'py>(
    py: Python<'py>,
    v: impl ExactSizeIterator<Item = f64>,
) -> PyResult<Bound<'py, PyBytes>> {
    let n = v.len();
    PyBytes::new_with(py, n * 8, |buf| {
        for (cell, x) in buf.chunks_exact_mut(8).zip(v) {
            cell.copy_from_slice(&x.to_ne_bytes());
        }
        Ok(())
    })
}

/// A chart's data as a dict: `title`, `columns`, `panels` (each `title`, `x_label`, `y_label`,
/// `x_log`, `y_log`, `x_range`, `y_range`, `x_categories`, `items`); an item is a dict with
/// `type` (`series`, `curve`, `band`), `label`, `x`, `y` (f64 bytes; a band has `lower` and
/// `upper` instead of `y`) and its style (`colour`, `filled`, `line`, `dashed`, `shade`).
pub fn figure_dict<'py>(py: Python<'py>, f: &Figure) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("title", &f.title)?;
    d.set_item("columns", f.columns)?;
    let panels = PyList::empty(py);
    for p in &f.panels {
        let pd = PyDict::new(py);
        pd.set_item("title", &p.title)?;
        pd.set_item("x_label", &p.x_label)?;
        pd.set_item("y_label", &p.y_label)?;
        pd.set_item("x_log", p.x_log)?;
        pd.set_item("y_log", p.y_log)?;
        pd.set_item("x_range", p.x_range)?;
        pd.set_item("y_range", p.y_range)?;
        pd.set_item("x_categories", p.x_categories.clone())?;
        let items = PyList::empty(py);
        for it in &p.items {
            let id = PyDict::new(py);
            match it {
                Drawn::Series {
                    label,
                    points,
                    colour,
                    filled,
                    line,
                    max_markers,
                } => {
                    id.set_item("type", "series")?;
                    id.set_item("label", label)?;
                    id.set_item("x", f64_bytes(py, points.iter().map(|p| p.0))?)?;
                    id.set_item("y", f64_bytes(py, points.iter().map(|p| p.1))?)?;
                    id.set_item("colour", *colour)?;
                    id.set_item("filled", *filled)?;
                    id.set_item("line", *line)?;
                    id.set_item("max_markers", *max_markers)?;
                }
                Drawn::Curve {
                    label,
                    points,
                    colour,
                    dashed,
                } => {
                    id.set_item("type", "curve")?;
                    id.set_item("label", label)?;
                    id.set_item("x", f64_bytes(py, points.iter().map(|p| p.0))?)?;
                    id.set_item("y", f64_bytes(py, points.iter().map(|p| p.1))?)?;
                    id.set_item("colour", *colour)?;
                    id.set_item("dashed", *dashed)?;
                }
                Drawn::Band {
                    label,
                    points,
                    shade,
                } => {
                    id.set_item("type", "band")?;
                    id.set_item("label", label)?;
                    id.set_item("x", f64_bytes(py, points.iter().map(|p| p.0))?)?;
                    id.set_item("lower", f64_bytes(py, points.iter().map(|p| p.1))?)?;
                    id.set_item("upper", f64_bytes(py, points.iter().map(|p| p.2))?)?;
                    id.set_item("shade", *shade)?;
                }
            }
            items.append(id)?;
        }
        pd.set_item("items", items)?;
        panels.append(pd)?;
    }
    d.set_item("panels", panels)?;
    Ok(d)
}

/// The names of the charts of `outputs` that have data, in the order they were made.
pub fn figure_names(outputs: &settle::Outputs) -> Vec<String> {
    outputs.figures().iter().map(|(n, _)| n.clone()).collect()
}

/// The data of the chart `name` (file name, or stem) of `outputs`, or None.
pub fn figure<'py>(
    py: Python<'py>,
    outputs: &settle::Outputs,
    name: &str,
) -> PyResult<Option<Bound<'py, PyDict>>> {
    let found = outputs
        .figures()
        .iter()
        .find(|(n, _)| n == name || n.strip_suffix(".svg") == Some(name));
    found.map(|(_, f)| figure_dict(py, f)).transpose()
}
