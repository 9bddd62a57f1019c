//! `settle._settle`: the Python extension of settle, a thin layer over the Rust library's public
//! API. The pure-Python package `settle` (python/python/settle) wraps it: DataFrames, the run
//! record as a dict, argument handling. Every computation runs through
//! [`convert::blocking`]: the GIL released, Ctrl-C polled, progress watched.
//!
//! | file | what |
//! |---|---|
//! | `convert.rs` | errors, TOML values, tables as columns, `blocking` |
//! | `scenario.rs` | `Scenario`, `RunResult` (`settle.run`) |
//! | `output.rs` | `Output`: the tables and files of any other command |
//! | `sweep.rs` | `settle.sweep`, `settle.vary` |
//! | `lab.rs` | `settle.reduce`, `settle.invert`, `settle.laws` |
//! | `fit.rs` | `settle.fit` |

mod convert;
mod fit;
mod lab;
mod output;
mod scenario;
mod sweep;

use pyo3::prelude::*;

#[pymodule]
fn _settle(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<scenario::Scenario>()?;
    m.add_class::<scenario::RunResult>()?;
    m.add_class::<output::Output>()?;
    m.add_function(wrap_pyfunction!(convert::toml_text, m)?)?;
    m.add("ScenarioError", py.get_type::<convert::ScenarioError>())?;
    m.add("UnstableError", py.get_type::<convert::UnstableError>())?;
    m.add("TEXT_ORIGIN", settle::api::TEXT_ORIGIN)?;
    sweep::register(m)?;
    lab::register(m)?;
    fit::register(m)?;
    Ok(())
}
