//! `settle._settle`: the Python extension of settle, a thin layer over the Rust library's public
//! API (`settle::{load, Scenario, RunResult, RunOptions, Status, Table, Column, Error, Kind}`).
//! The pure-Python package `settle` (python/python/settle) wraps it: DataFrames, the run
//! record as a dict, argument handling. Runs release the GIL.

use pyo3::create_exception;
use pyo3::exceptions::{PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use settle::{Column, Error, RunOptions};
use std::path::PathBuf;

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
fn to_py(e: Error) -> PyErr {
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
fn toml_value(v: &Bound<'_, PyAny>, at: &str) -> PyResult<toml::Value> {
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

fn toml_table(d: &Bound<'_, PyDict>, at: &str) -> PyResult<toml::Table> {
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
fn toml_text(value: &Bound<'_, PyAny>) -> PyResult<String> {
    Ok(toml_value(value, "value")?.to_string())
}

/// A scenario ready to run (`settle::Scenario`).
#[pyclass(frozen, module = "settle._settle")]
struct Scenario(settle::Scenario);

#[pymethods]
impl Scenario {
    /// Reads a scenario file (or a run record `run.toml`).
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        py.allow_threads(|| settle::load(&path))
            .map(Self)
            .map_err(to_py)
    }

    /// A scenario from the text of a scenario file.
    #[staticmethod]
    #[pyo3(signature = (text, origin=None))]
    fn from_toml(text: &str, origin: Option<PathBuf>) -> PyResult<Self> {
        match origin {
            Some(o) => settle::Scenario::from_toml_at(text, o),
            None => settle::Scenario::from_toml(text),
        }
        .map(Self)
        .map_err(to_py)
    }

    /// A scenario from a dict of the tables and keys of a scenario file.
    #[staticmethod]
    fn from_dict(d: &Bound<'_, PyDict>) -> PyResult<Self> {
        let table = toml_table(d, "")?;
        settle::Scenario::from_table(table).map(Self).map_err(to_py)
    }

    /// A new scenario with `key = value` (`value` as TOML text) applied as `--set` does.
    fn set(&self, key: &str, value: &str) -> PyResult<Self> {
        self.0.set(key, value).map(Self).map_err(to_py)
    }

    /// A new scenario with the time step `dt_s`, s (as `--dt`).
    fn with_dt(&self, dt_s: f64) -> PyResult<Self> {
        self.0.with_dt(dt_s).map(Self).map_err(to_py)
    }

    fn to_toml(&self) -> PyResult<String> {
        self.0.to_toml().map_err(to_py)
    }

    #[getter]
    fn name(&self) -> &str {
        self.0.name()
    }

    #[getter]
    fn kind(&self) -> &'static str {
        self.0.kind().name()
    }

    #[getter]
    fn path(&self) -> PathBuf {
        self.0.path().to_path_buf()
    }

    #[getter]
    fn overrides(&self) -> Vec<String> {
        self.0.overrides().to_vec()
    }

    #[getter]
    fn dt_s(&self) -> f64 {
        self.0.dt_s()
    }

    /// Runs in memory with the GIL released.
    #[pyo3(signature = (progress=false, force=false))]
    fn run(&self, py: Python<'_>, progress: bool, force: bool) -> PyResult<RunResult> {
        let opts = RunOptions { progress, force };
        py.allow_threads(|| self.0.run_with(&opts))
            .map(RunResult)
            .map_err(to_py)
    }
}

/// The outcome of a run, in memory (`settle::RunResult`).
#[pyclass(frozen, module = "settle._settle")]
struct RunResult(settle::RunResult);

#[pymethods]
impl RunResult {
    #[getter]
    fn scenario(&self) -> Scenario {
        Scenario(self.0.scenario().clone())
    }

    /// Every table as `(stem, header, columns, preamble)`: a numeric column is the bytes of its native
    /// f64 values (empty cells NaN; read with numpy.frombuffer), a text column a list of
    /// str with None for an empty cell; the preamble the comment lines before the header.
    fn raw_tables<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyTuple>>> {
        self.0
            .tables()
            .iter()
            .map(|t| {
                let cols = t
                    .header()
                    .iter()
                    .map(|h| match t.column(h) {
                        Some(Column::Numbers(v)) => {
                            // written straight into the Python bytes object
                            let b = PyBytes::new_with(py, v.len() * 8, |buf| {
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

    /// The CSV bytes of the table `name` (stem or file name), as the file holds them.
    fn csv<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Option<Bound<'py, PyBytes>>> {
        match self.0.table(name) {
            Some(t) => {
                let b = t.to_csv().map_err(|e| PyOSError::new_err(e.to_string()))?;
                Ok(Some(PyBytes::new(py, &b)))
            }
            None => Ok(None),
        }
    }

    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.0.warnings().to_vec()
    }

    #[getter]
    fn lines(&self) -> Vec<String> {
        self.0.lines().to_vec()
    }

    #[getter]
    fn status(&self) -> &'static str {
        self.0.status().name()
    }

    #[getter]
    fn record(&self) -> &str {
        self.0.record()
    }

    #[getter]
    fn wall_time_s(&self) -> f64 {
        self.0.wall_time_s()
    }

    #[getter]
    fn steps(&self) -> u64 {
        self.0.steps()
    }

    /// Writes the run's files to `out_dir/<name>/`; returns that folder.
    fn write(&self, py: Python<'_>, out_dir: PathBuf) -> PyResult<PathBuf> {
        py.allow_threads(|| self.0.write(&out_dir)).map_err(to_py)
    }
}

#[pymodule]
fn _settle(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<Scenario>()?;
    m.add_class::<RunResult>()?;
    m.add_function(wrap_pyfunction!(toml_text, m)?)?;
    m.add("ScenarioError", py.get_type::<ScenarioError>())?;
    m.add("UnstableError", py.get_type::<UnstableError>())?;
    m.add("TEXT_ORIGIN", settle::api::TEXT_ORIGIN)?;
    Ok(())
}
