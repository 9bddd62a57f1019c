//! `settle.fit` and `settle.slump`: the calibration of `settle fit` in memory, returning an
//! [`crate::output::Output`], and the slump calculator of `settle fit slump`.

use crate::convert::{blocking, to_py};
use crate::output::Output;
use crate::scenario::Scenario;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use settle::fit::{Bound as FitBound, FitOptions, Measured};
use std::path::PathBuf;

/// Fits the keys of `bounds` (`(key, lo, hi)`, each checked as `--fit KEY=LO:HI`) of
/// `scenario` to the measurements: the file `measured_path`, or `measured_csv` (`(name,
/// text)`: the CSV text of a table standing for the file `name`). Runs through [`blocking`].
#[pyfunction]
#[pyo3(signature = (scenario, bounds, measured_path=None, measured_csv=None, progress=None))]
fn fit(
    py: Python<'_>,
    scenario: &Scenario,
    bounds: Vec<(String, f64, f64)>,
    measured_path: Option<PathBuf>,
    measured_csv: Option<(String, String)>,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<Output> {
    let bounds = bounds
        .iter()
        .map(|(k, lo, hi)| FitBound::new(k, *lo, *hi))
        .collect::<Result<Vec<_>, _>>()
        .map_err(to_py)?;
    let measured = match (measured_path, measured_csv) {
        (Some(p), None) => Measured::File(p),
        (None, Some((name, text))) => {
            let t = settle::Table::from_csv(name.clone(), text.as_bytes()).map_err(|e| {
                to_py(settle::Error::bad_input(
                    std::path::Path::new(&name),
                    None,
                    format!("not a table of measurements: {e}"),
                ))
            })?;
            Measured::Table(t)
        }
        _ => {
            return Err(pyo3::exceptions::PyTypeError::new_err(
                "give the measurements as a path or as a table, not both",
            ))
        }
    };
    let opts = FitOptions { progress: false };
    let s = scenario.0.clone();
    let r = blocking(py, progress, move || {
        settle::fit::fit(&s, &bounds, measured, &opts)
    })?;
    Ok(Output::new(r.name, r.outputs, r.warnings, r.lines))
}

/// The yield stresses of slump tests (`settle fit slump`): a dict with `height_mm`,
/// `density_kg_m3`, `g_m_s2`, `slump_mm`, `relative_slump`, `yield_stress_pa` (one per
/// slump), `mean_yield_stress_pa` and `lines`.
#[pyfunction]
#[pyo3(signature = (height_mm, slump_mm, density, g))]
fn slump<'py>(
    py: Python<'py>,
    height_mm: f64,
    slump_mm: Vec<f64>,
    density: f64,
    g: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let s = blocking(py, None, move || {
        settle::fit::slump(height_mm, &slump_mm, density, g)
    })?;
    let d = PyDict::new(py);
    d.set_item("height_mm", s.height_mm)?;
    d.set_item("density_kg_m3", s.density_kg_m3)?;
    d.set_item("g_m_s2", s.g_m_s2)?;
    let col = |f: fn(&settle::fit::SlumpTest) -> f64| s.tests.iter().map(f).collect::<Vec<f64>>();
    d.set_item("slump_mm", col(|t| t.slump_mm))?;
    d.set_item("relative_slump", col(|t| t.relative_slump))?;
    d.set_item("yield_stress_pa", col(|t| t.yield_stress_pa))?;
    d.set_item("mean_yield_stress_pa", s.mean_yield_stress_pa)?;
    d.set_item("lines", s.lines.clone())?;
    Ok(d)
}

/// Adds this file's functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fit, m)?)?;
    m.add_function(wrap_pyfunction!(slump, m)?)?;
    Ok(())
}
