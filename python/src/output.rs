//! `Output`: what a command other than `run` made, in memory (`settle::Outputs`: its tables
//! and files), with its warnings and console lines; `write` writes its folder as the command
//! line does.

use crate::convert::{figure, figure_names, raw_tables, to_py};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use std::path::PathBuf;

/// The tables and files of a command (`settle sweep`, `vary`, `reduce`, `invert`, `laws`,
/// `fit`) in memory.
#[pyclass(frozen, module = "settle._settle")]
pub struct Output {
    /// The results folder's name (`<name>_sweep`, `<stem>_reduced`, `laws`, ...).
    pub name: String,
    /// The tables and files.
    pub outputs: settle::Outputs,
    /// Validity warnings.
    pub warnings: Vec<String>,
    /// The command line's console lines.
    pub lines: Vec<String>,
}

impl Output {
    /// An output named `name` (its folder's name).
    pub fn new(
        name: impl Into<String>,
        outputs: settle::Outputs,
        warnings: Vec<String>,
        lines: Vec<String>,
    ) -> Self {
        Self {
            name: name.into(),
            outputs,
            warnings,
            lines,
        }
    }
}

#[pymethods]
impl Output {
    /// Every table as `(stem, header, columns, preamble)` ([`raw_tables`]).
    fn raw_tables<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyTuple>>> {
        raw_tables(py, self.outputs.tables())
    }

    /// The CSV bytes of the table `name` (stem or file name), as the file holds them.
    fn csv<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Option<Bound<'py, PyBytes>>> {
        match self.outputs.get(name) {
            Some(t) => {
                let b = t.to_csv().map_err(|e| PyOSError::new_err(e.to_string()))?;
                Ok(Some(PyBytes::new(py, &b)))
            }
            None => Ok(None),
        }
    }

    /// The names of the files that are not tables (charts, pages, records).
    fn file_names(&self) -> Vec<String> {
        self.outputs.file_names().map(str::to_string).collect()
    }

    /// The bytes of the file `name` (a chart's SVG text, a record's TOML), or None.
    fn file<'py>(&self, py: Python<'py>, name: &str) -> Option<Bound<'py, PyBytes>> {
        self.outputs.bytes(name).map(|b| PyBytes::new(py, &b))
    }

    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// The names of the charts that have data (`velocity.svg`, ...), in the order made.
    fn figure_names(&self) -> Vec<String> {
        figure_names(&self.outputs)
    }

    /// The data of the chart `name` (file name or stem) as a dict, or None.
    fn figure<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Option<Bound<'py, PyDict>>> {
        figure(py, &self.outputs, name)
    }

    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    #[getter]
    fn lines(&self) -> Vec<String> {
        self.lines.clone()
    }

    /// Writes `out_dir/<name>/` as the command line does; returns that folder.
    fn write(&self, py: Python<'_>, out_dir: PathBuf) -> PyResult<PathBuf> {
        py.allow_threads(|| self.outputs.write_folder(&out_dir, &self.name))
            .map_err(to_py)
    }
}
