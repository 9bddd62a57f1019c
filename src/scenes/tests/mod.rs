//! Unit tests of the scenes' shared parts (moved from `tests/regression/` and `tests/app/`): the
//! cost guard and its `--force`; and
//! [`prepare`], which the scenes' unit tests load their scenarios with.

use crate::error::BadInput;
use crate::scenario::{self, inputs, Overrides};
use crate::scenes::Prepared;
use std::path::Path;

mod cost_guard_force;
mod issue_17_cylinder_cost_estimate;

/// The scenario file `path` as `settle run --dt DT_S --set OVERRIDES` prepares it (read,
/// overridden, validated, its input files read), built from the scenario layer as `run::prepare`
/// builds it, for the scenes' unit tests (which may not import the application layer).
pub(crate) fn prepare(
    path: &Path,
    dt_s: Option<f64>,
    overrides: &[String],
) -> Result<Prepared, BadInput> {
    let mut ov = overrides.to_vec();
    if let Some(dt) = dt_s {
        ov.push(format!("time.dt_s={dt:e}"));
    }
    let scenario::Parsed {
        scenario,
        common,
        scene,
        rheology,
    } = scenario::parse(path, &ov)?;
    let spheres = inputs::spheres(&scenario, path)?;
    let reference = inputs::read_reference(&scenario, path)?;
    Ok(Prepared {
        path: path.to_path_buf(),
        scenario,
        common,
        spheres,
        scene,
        rheology,
        reference,
        overrides: Overrides {
            set: overrides.to_vec(),
            dt_s,
        },
    })
}
