//! `settle.sweep` and `settle.vary`: the in-memory commands of the library, each returning an
//! [`crate::output::Output`].

use crate::convert::blocking;
use crate::output::Output;
use crate::scenario::Scenario;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyList, PyString, PyTuple};
use settle::sweep::{Axis, SweepOptions, VaryOptions};

/// A dt sweep of `scenario` (`settle.sweep`, `settle sweep`): `dt` the time steps, s;
/// `dt_range` (lo, hi), s, with `per_decade`; `integrators` by name; `tol` the tolerance of
/// the recommended dt. Every option left None takes the command line's default (the scenario's
/// `[sweep]` table). Runs through [`blocking`].
#[pyfunction]
#[pyo3(signature = (scenario, dt=None, dt_range=None, per_decade=None, integrators=None, tol=None, progress=None))]
#[allow(clippy::too_many_arguments)]
fn sweep(
    py: Python<'_>,
    scenario: &Scenario,
    dt: Option<Vec<f64>>,
    dt_range: Option<(f64, f64)>,
    per_decade: Option<i64>,
    integrators: Option<Vec<String>>,
    tol: Option<f64>,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<Output> {
    let opts = SweepOptions {
        dts: dt.unwrap_or_default(),
        dt_range,
        // Below 1 (or beyond u32) is refused by the library as `--per-decade` is.
        per_decade: per_decade.map(|n| u32::try_from(n).unwrap_or(0)),
        integrators: integrators.unwrap_or_default(),
        tol,
        progress: false,
    };
    let s = scenario.0.clone();
    let r = blocking(py, progress, move || settle::sweep::sweep(&s, &opts))?;
    let name = r.name().to_string();
    Ok(Output::new(name, r.outputs, r.warnings, r.lines))
}

/// A parameter sweep of `scenario` (`settle.vary`, `settle sweep --vary`): `axes` a list of
/// `(key, grid)`, the grid either the text of `--vary KEY=GRID` after the `=` (`"10:40:13"`,
/// `"log:1e-3:1e-1:5"`, `"off,basset"`) or a list of values as text (each a number or a word
/// `--set` takes). Runs through [`blocking`].
#[pyfunction]
#[pyo3(signature = (scenario, axes, progress=None))]
fn vary(
    py: Python<'_>,
    scenario: &Scenario,
    axes: &Bound<'_, PyList>,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<Output> {
    let axes = axes
        .iter()
        .map(|item| axis(&item))
        .collect::<PyResult<Vec<Axis>>>()?;
    let s = scenario.0.clone();
    let opts = VaryOptions { progress: false };
    let r = blocking(py, progress, move || settle::sweep::vary(&s, &axes, &opts))?;
    let name = r.name().to_string();
    Ok(Output::new(name, r.outputs, r.warnings, r.lines))
}

/// One axis from `(key, grid)`: a grid text (`--vary KEY=GRID`) or a list of value texts.
fn axis(item: &Bound<'_, PyAny>) -> PyResult<Axis> {
    let pair = item
        .downcast::<PyTuple>()
        .ok()
        .filter(|t| t.len() == 2)
        .ok_or_else(|| PyTypeError::new_err("an axis is a (key, grid) pair"))?;
    let key: String = pair.get_item(0)?.extract()?;
    let grid = pair.get_item(1)?;
    let made = if grid.is_instance_of::<PyString>() {
        Axis::parse(&format!("{key}={}", grid.extract::<String>()?))
    } else {
        let values: Vec<String> = grid.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "{key}: the values of an axis are a grid text (\"LO:HI:N\", \"log:LO:HI:N\", \
                 \"V1,V2\") or a list of values"
            ))
        })?;
        Axis::list(&key, &values)
    };
    made.map_err(crate::convert::to_py)
}

/// Adds this file's functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(vary, m)?)?;
    Ok(())
}
