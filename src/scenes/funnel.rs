//! The funnel pour of f-EDEM §4.2: many balls released from a funnel into paste, with contacts.

use crate::output::StagedDir;
use crate::run::{Prepared, RunError, SceneReport};

/// Funnel pour (kind `funnel_pour`).
pub fn run(p: &Prepared, _stage: &StagedDir) -> Result<SceneReport, RunError> {
    Err(RunError::Other(format!(
        "{}: kind funnel_pour is being built",
        p.path.display()
    )))
}
