//! Unit tests of the scenes' shared parts (moved from `tests/regression/` and `tests/app/`): the
//! cost guard and its `--force`; and
//! [`prepare`], which the scenes' unit tests load their scenarios with.

use crate::error::BadInput;
use crate::scenes::Prepared;
use std::path::Path;

mod cost_guard_force;
mod issue_17_cylinder_cost_estimate;

/// The scenario file `path` as `settle run --dt DT_S --set OVERRIDES` prepares it (read,
/// overridden, validated, its input files read), with [`Prepared::parse`] as `run::prepare` does (without its
/// check of the output folder's name), for the scenes' unit tests (which may not import the application layer).
pub(crate) fn prepare(
    path: &Path,
    dt_s: Option<f64>,
    overrides: &[String],
) -> Result<Prepared, BadInput> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| BadInput::new(path, None, format!("cannot read the file: {e}")))?;
    Prepared::parse(&text, path, dt_s, overrides, |_| Ok(()))
}
