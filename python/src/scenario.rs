//! `Scenario` and `RunResult`: `settle::Scenario` and `settle::RunResult` for Python.

use crate::convert::{blocking, figure, figure_names, raw_tables, to_py, toml_table};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use settle::RunOptions;
use std::path::PathBuf;

/// A scenario ready to run (`settle::Scenario`).
#[pyclass(frozen, module = "settle._settle")]
pub struct Scenario(pub settle::Scenario);

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

    /// Runs in memory through [`blocking`] (GIL released, Ctrl-C polled); `progress`, a
    /// callable, is called with `(name, pos, len, unit, message)` as the run moves.
    #[pyo3(signature = (progress=None, force=false, threads=None))]
    fn run(
        &self,
        py: Python<'_>,
        progress: Option<&Bound<'_, PyAny>>,
        force: bool,
        threads: Option<usize>,
    ) -> PyResult<RunResult> {
        let opts = RunOptions {
            progress: false,
            force,
            threads,
        };
        let s = self.0.clone();
        blocking(py, progress, move || s.run_with(&opts)).map(RunResult)
    }
}

/// The outcome of a run, in memory (`settle::RunResult`).
#[pyclass(frozen, module = "settle._settle")]
pub struct RunResult(pub settle::RunResult);

#[pymethods]
impl RunResult {
    #[getter]
    fn scenario(&self) -> Scenario {
        Scenario(self.0.scenario().clone())
    }

    /// Every table as `(stem, header, columns, preamble)` ([`crate::convert::raw_tables`]).
    fn raw_tables<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyTuple>>> {
        raw_tables(py, self.0.tables())
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

    /// The file name of the kind's main chart.
    #[getter]
    fn main_chart(&self) -> &'static str {
        self.0.main_chart()
    }

    /// The names of the charts that have data (`velocity.svg`, ...), in the order made.
    fn figure_names(&self) -> Vec<String> {
        figure_names(self.0.outputs())
    }

    /// The data of the chart `name` (file name or stem) as a dict, or None.
    fn figure<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Option<Bound<'py, PyDict>>> {
        figure(py, self.0.outputs(), name)
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
