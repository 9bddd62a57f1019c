//! Contact calibration scenes of f-EDEM's appendices: the restitution drop (App. II) and the
//! tilt test (App. III).

use crate::output::StagedDir;
use crate::run::{Prepared, RunError, SceneReport};

/// Restitution drop (kind `restitution_drop`).
pub fn run_restitution(p: &Prepared, _stage: &StagedDir) -> Result<SceneReport, RunError> {
    Err(RunError::Other(format!(
        "{}: kind restitution_drop is being built",
        p.path.display()
    )))
}

/// Tilt friction (kind `tilt_friction`).
pub fn run_tilt(p: &Prepared, _stage: &StagedDir) -> Result<SceneReport, RunError> {
    Err(RunError::Other(format!(
        "{}: kind tilt_friction is being built",
        p.path.display()
    )))
}
