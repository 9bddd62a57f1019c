//! `settle.fit`: the in-memory commands of the library, each returning an
//! [`crate::output::Output`].

use pyo3::prelude::*;

/// Adds this file's functions to the module.
pub fn register(_m: &Bound<'_, PyModule>) -> PyResult<()> {
    Ok(())
}
