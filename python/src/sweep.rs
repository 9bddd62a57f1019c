//! `settle.sweep` and `settle.vary`: the in-memory commands of the library, each returning an
//! [`crate::output::Output`]; and their parts (`sweep_part`, `vary_part`: one shard, as the
//! text of its part file) and merges, through which `settle.sweep(..., executor=...)` spreads
//! a sweep over a `concurrent.futures.Executor`.

use crate::convert::blocking;
use crate::output::Output;
use crate::scenario::Scenario;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyList, PyString, PyTuple};
use settle::sweep::{Axis, SweepOptions, SweepPart, VaryOptions, VaryPart};

/// The options of a dt sweep from the arguments of `sweep` (each None: the command line's
/// default).
fn sweep_options(
    dt: Option<Vec<f64>>,
    dt_range: Option<(f64, f64)>,
    per_decade: Option<i64>,
    integrators: Option<Vec<String>>,
    tol: Option<f64>,
) -> SweepOptions {
    SweepOptions {
        dts: dt.unwrap_or_default(),
        dt_range,
        // Below 1 (or beyond u32) is refused by the library as `--per-decade` is.
        per_decade: per_decade.map(|n| u32::try_from(n).unwrap_or(0)),
        integrators: integrators.unwrap_or_default(),
        tol,
        progress: false,
    }
}

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
    let opts = sweep_options(dt, dt_range, per_decade, integrators, tol);
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
    let axes = axes_of(axes)?;
    let s = scenario.0.clone();
    let opts = VaryOptions { progress: false };
    let r = blocking(py, progress, move || settle::sweep::vary(&s, &axes, &opts))?;
    let name = r.name().to_string();
    Ok(Output::new(name, r.outputs, r.warnings, r.lines))
}

/// The number of cases of the dt sweep `sweep` runs with these arguments, every option
/// checked as `sweep` checks it (`settle::sweep::sweep_cases`); nothing runs.
#[pyfunction]
#[pyo3(signature = (scenario, dt, dt_range, per_decade, integrators, tol))]
fn sweep_cases(
    scenario: &Scenario,
    dt: Option<Vec<f64>>,
    dt_range: Option<(f64, f64)>,
    per_decade: Option<i64>,
    integrators: Option<Vec<String>>,
    tol: Option<f64>,
) -> PyResult<usize> {
    let opts = sweep_options(dt, dt_range, per_decade, integrators, tol);
    settle::sweep::sweep_cases(&scenario.0, &opts)
        .map(|c| c.len())
        .map_err(crate::convert::to_py)
}

/// Shard `index` of `count` (1-based) of that dt sweep, as the text of its part file
/// `sweep_part_I_of_N.csv` (`settle::sweep::sweep_part`). Runs through [`blocking`].
#[pyfunction]
#[pyo3(signature = (scenario, dt, dt_range, per_decade, integrators, tol, index, count))]
#[allow(clippy::too_many_arguments)]
fn sweep_part(
    py: Python<'_>,
    scenario: &Scenario,
    dt: Option<Vec<f64>>,
    dt_range: Option<(f64, f64)>,
    per_decade: Option<i64>,
    integrators: Option<Vec<String>>,
    tol: Option<f64>,
    index: usize,
    count: usize,
) -> PyResult<String> {
    let opts = sweep_options(dt, dt_range, per_decade, integrators, tol);
    let s = scenario.0.clone();
    blocking(py, None, move || {
        settle::sweep::sweep_part(&s, &opts, index, count)?.to_csv()
    })
}

/// The dt sweep from its parts, each `(index, count, text of its part file)`, one whole split
/// in any order (`settle::sweep::sweep_merge`): what `sweep` returns. Runs through
/// [`blocking`].
#[pyfunction]
#[pyo3(signature = (scenario, dt, dt_range, per_decade, integrators, tol, parts))]
#[allow(clippy::too_many_arguments)]
fn sweep_merge(
    py: Python<'_>,
    scenario: &Scenario,
    dt: Option<Vec<f64>>,
    dt_range: Option<(f64, f64)>,
    per_decade: Option<i64>,
    integrators: Option<Vec<String>>,
    tol: Option<f64>,
    parts: Vec<(usize, usize, String)>,
) -> PyResult<Output> {
    let opts = sweep_options(dt, dt_range, per_decade, integrators, tol);
    let s = scenario.0.clone();
    let r = blocking(py, None, move || {
        let parts = parts
            .iter()
            .map(|(i, n, text)| SweepPart::from_csv(*i, *n, text))
            .collect::<Result<Vec<_>, _>>()?;
        settle::sweep::sweep_merge(&s, &opts, parts)
    })?;
    let name = r.name().to_string();
    Ok(Output::new(name, r.outputs, r.warnings, r.lines))
}

/// The number of cases of the parameter sweep `vary` runs with these axes, every point
/// prepared and validated as `vary` does it (`settle::sweep::vary_cases`); nothing runs.
#[pyfunction]
fn vary_cases(py: Python<'_>, scenario: &Scenario, axes: &Bound<'_, PyList>) -> PyResult<usize> {
    let axes = axes_of(axes)?;
    let s = scenario.0.clone();
    blocking(py, None, move || {
        settle::sweep::vary_cases(&s, &axes).map(|c| c.len())
    })
}

/// Shard `index` of `count` (1-based) of that parameter sweep, as the text of its part file
/// `vary_part_I_of_N.csv` (`settle::sweep::vary_part`). Runs through [`blocking`].
#[pyfunction]
fn vary_part(
    py: Python<'_>,
    scenario: &Scenario,
    axes: &Bound<'_, PyList>,
    index: usize,
    count: usize,
) -> PyResult<String> {
    let axes = axes_of(axes)?;
    let s = scenario.0.clone();
    let opts = VaryOptions { progress: false };
    blocking(py, None, move || {
        settle::sweep::vary_part(&s, &axes, &opts, index, count)?.to_csv()
    })
}

/// The parameter sweep from its parts, each `(index, count, text of its part file)`, one
/// whole split in any order (`settle::sweep::vary_merge`): what `vary` returns. Runs through
/// [`blocking`].
#[pyfunction]
fn vary_merge(
    py: Python<'_>,
    scenario: &Scenario,
    axes: &Bound<'_, PyList>,
    parts: Vec<(usize, usize, String)>,
) -> PyResult<Output> {
    let axes = axes_of(axes)?;
    let s = scenario.0.clone();
    let opts = VaryOptions { progress: false };
    let r = blocking(py, None, move || {
        let parts = parts
            .iter()
            .map(|(i, n, text)| VaryPart::from_csv(*i, *n, text))
            .collect::<Result<Vec<_>, _>>()?;
        settle::sweep::vary_merge(&s, &axes, &opts, parts)
    })?;
    let name = r.name().to_string();
    Ok(Output::new(name, r.outputs, r.warnings, r.lines))
}

/// The axes of a list of `(key, grid)` ([`axis`]).
fn axes_of(axes: &Bound<'_, PyList>) -> PyResult<Vec<Axis>> {
    axes.iter().map(|item| axis(&item)).collect()
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
    m.add_function(wrap_pyfunction!(sweep_cases, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_part, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_merge, m)?)?;
    m.add_function(wrap_pyfunction!(vary_cases, m)?)?;
    m.add_function(wrap_pyfunction!(vary_part, m)?)?;
    m.add_function(wrap_pyfunction!(vary_merge, m)?)?;
    Ok(())
}
