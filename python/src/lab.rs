//! `settle.reduce`, `settle.invert` and `settle.laws`: the in-memory commands of the library, each returning an
//! [`crate::output::Output`]. The readings of `reduce` and `invert` come as a path or, from a
//! DataFrame (python/python/settle/_lab.py), as `(name, header, rows, figures)`: the table's
//! name (standing for the file), its columns, its cells as text and the `# key = value` figures.

use crate::convert::{blocking, to_py};
use crate::output::Output;
use pyo3::prelude::*;
use settle::invert::InvertOptions;
use settle::laws::LawsOptions;
use settle::reduce::{Readings, ReduceOptions};
use settle::{Error, Table};
use std::path::{Path, PathBuf};

/// Readings as the package passes them.
#[derive(FromPyObject)]
enum LabReadings {
    /// A readings file.
    Path(PathBuf),
    /// A table in memory: (name, header, rows, figures).
    Table(String, Vec<String>, Vec<Vec<String>>, Vec<(String, String)>),
}

impl From<LabReadings> for Readings {
    fn from(r: LabReadings) -> Self {
        match r {
            LabReadings::Path(p) => Readings::File(p),
            LabReadings::Table(name, header, rows, figures) => {
                Readings::table(figures, Table::with_rows(name, header, rows))
            }
        }
    }
}

/// Writes the results (when `out` is given, through `write`) and returns the folder the console
/// lines name: the folder written, else the results' name.
fn written(
    name: &str,
    out: Option<&Path>,
    write: impl FnOnce(&Path) -> Result<PathBuf, Error>,
) -> Result<PathBuf, Error> {
    match out {
        Some(dir) => write(dir),
        None => Ok(PathBuf::from(name)),
    }
}

/// `settle reduce READINGS [--standard S] [--hydrometer H] [--out OUT]` in memory: an
/// `Output` named `<stem>_reduced`; with `out`, also written to `out/<stem>_reduced/`.
#[pyfunction]
#[pyo3(signature = (readings, standard=None, hydrometer=None, out=None))]
fn reduce(
    py: Python<'_>,
    readings: LabReadings,
    standard: Option<String>,
    hydrometer: Option<String>,
    out: Option<PathBuf>,
) -> PyResult<Output> {
    let readings = Readings::from(readings);
    let opts = ReduceOptions {
        standard,
        hydrometer,
    };
    // computed apart, written after: a computation stopped by Ctrl-C never writes
    let r = blocking(py, None, move || settle::reduce::reduce(readings, &opts))?;
    let dest = py
        .allow_threads(|| written(&r.name, out.as_deref(), |d| r.write(d)))
        .map_err(to_py)?;
    let lines = r.lines(&dest);
    Ok(Output::new(r.name, r.outputs, r.warnings, lines))
}

/// `settle invert READINGS... [options] [--out OUT]` in memory: an `Output` named
/// `<stem of the first>_inverted`; with `out`, also written to `out/<stem>_inverted/`.
#[pyfunction]
#[pyo3(signature = (
    readings, model="ideal-stokes".to_string(), bins=None, diameters_um=None,
    lambda_="discrepancy".to_string(), resolution=Vec::new(), repeats=100, seed=1,
    bounds=None, out=None
))]
#[allow(clippy::too_many_arguments)]
fn invert(
    py: Python<'_>,
    readings: Vec<LabReadings>,
    model: String,
    bins: Option<usize>,
    diameters_um: Option<String>,
    lambda_: String,
    resolution: Vec<f64>,
    repeats: usize,
    seed: u64,
    bounds: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Output> {
    let readings: Vec<Readings> = readings.into_iter().map(Readings::from).collect();
    let opts = InvertOptions {
        model,
        bins,
        diameters_um,
        lambda: lambda_,
        resolution,
        repeats,
        seed,
        bounds,
    };
    // computed apart, written after: a computation stopped by Ctrl-C never writes
    let r = blocking(py, None, move || settle::invert::invert(&readings, &opts))?;
    let dest = py
        .allow_threads(|| written(&r.name, out.as_deref(), |d| r.write(d)))
        .map_err(to_py)?;
    let lines = r.lines(&dest);
    Ok(Output::new(r.name, r.outputs, r.warnings, lines))
}

/// `settle laws [SPHERES --fluids FLUIDS] [--out OUT]` in memory: an `Output` named `laws`;
/// with `out`, also written to `out/laws/`.
#[pyfunction]
#[pyo3(signature = (spheres=None, fluids=None, out=None))]
fn laws(
    py: Python<'_>,
    spheres: Option<PathBuf>,
    fluids: Option<PathBuf>,
    out: Option<PathBuf>,
) -> PyResult<Output> {
    let opts = LawsOptions { spheres, fluids };
    // computed apart, written after: a computation stopped by Ctrl-C never writes
    let r = blocking(py, None, move || settle::laws::laws(&opts))?;
    let dest = py
        .allow_threads(|| written(&r.name, out.as_deref(), |d| r.write(d)))
        .map_err(to_py)?;
    let lines = r.lines(&dest);
    Ok(Output::new(r.name, r.outputs, r.warnings, lines))
}

/// Adds this file's functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(reduce, m)?)?;
    m.add_function(wrap_pyfunction!(invert, m)?)?;
    m.add_function(wrap_pyfunction!(laws, m)?)?;
    Ok(())
}
