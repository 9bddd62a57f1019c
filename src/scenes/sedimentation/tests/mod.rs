//! Unit tests of the sedimentation cylinder (moved from `tests/scenes/`, `tests/instruments/` and
//! `tests/regression/`): contacts and squeeze-film lubrication between representative grains,
//! the instruments on the simulated cylinder.

mod contacts;
mod ideal_stokes;
mod instruments;
mod issue_12_contacts_honoured;

use crate::error::BadInput;
use crate::scenario::Scenario;
use std::path::{Path, PathBuf};

/// What the cylinder reads of a scenario file: the scenario, read as `settle run --dt DT_S
/// --set OVERRIDES` reads it, and the file's path (relative input files are found from it).
pub(super) struct Loaded {
    pub scenario: Scenario,
    pub path: PathBuf,
}

/// The scenario file `path` as `settle run --dt DT_S --set OVERRIDES` reads it for this scene.
pub(super) fn prepare(
    path: &Path,
    dt_s: Option<f64>,
    overrides: &[String],
) -> Result<Loaded, BadInput> {
    let mut ov = overrides.to_vec();
    if let Some(dt) = dt_s {
        ov.push(format!("time.dt_s={dt:e}"));
    }
    let parsed = crate::scenario::parse(path, &ov)?;
    Ok(Loaded {
        scenario: parsed.scenario,
        path: path.to_path_buf(),
    })
}
