//! Unit tests of the free-settling scene (moved from `tests/engine/free_settling.rs` and
//! `tests/validation/{paste_drop,transient,valentik,stokes_single,sphere_drag}.rs`): one sphere
//! through the scene's own integrator and through Rapier, against analytic solutions and
//! reference data.

use crate::error::BadInput;
use crate::scenario::inputs::{self, SphereCase};
use crate::scenario::{RheologyModel, Scenario};
use std::path::Path;

mod paste_drop;
mod rapier;
mod sphere_drag;
mod stokes_single;
mod transient;
mod valentik;

/// What the free-settling scene reads of a scenario file, read as `settle run` reads it (the
/// scenario with `overrides` and the time step `dt_s` applied, its fluid, its spheres).
#[derive(Debug)]
pub(super) struct Loaded {
    pub scenario: Scenario,
    pub rheology: RheologyModel,
    pub spheres: Vec<SphereCase>,
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
    let spheres = inputs::spheres(&parsed.scenario, path)?;
    Ok(Loaded {
        scenario: parsed.scenario,
        rheology: parsed.rheology,
        spheres,
    })
}
