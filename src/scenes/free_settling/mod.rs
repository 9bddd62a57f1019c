//! Free settling (`kind = "free_settling"`) and drops (`kind = "drop"`): independent spheres
//! released in a still fluid, each in its own world, no contacts (f-EDEM §3 single sphere in
//! water; §4.1 Valentik & Whitmore's 3 m tank; §4.2 balls dropped into a paste).
//!
//! # Scene
//!
//! Each sphere is advanced by [`crate::dynamics::advance`] alone (`engine = "free"`, the default
//! for this kind: there is nothing for a contact solver to do), or through a Rapier world with the
//! force hook (`engine = "rapier"`), which must give the same answer (src/scenes/free_settling/tests/rapier.rs)
//! at ~300× the cost per step. A free-settling sphere is released submerged at `release.depth_m`
//! (one radius when 0) and feels constant forces; a drop starts `fall_height_m` above the free
//! surface and crosses it, its drag and buoyancy scaled by [`immersion`](fn@crate::fluid::immersion).
//!
//! # Equations
//!
//! - Net weight `W = (m − m_f) g`, `m = ρ π d³/6`, `m_f = ρ_f π d³/6`; drag from the scenario's law
//!   ([`crate::scenario::Common::sphere_drag`]).
//! - The force-balance terminal velocity solves drag = net weight (f-EDEM eq. 15); it may sit on a
//!   jump of eq. 19 or be zero (`static`: the yield stress holds the sphere).
//! - For Stokes drag, the analytic solution v(t) = v_t + (v₀ − v_t) e^{−t/τ}, τ = m/(3π μ d)
//!   (f-EDEM eq. 20–21), compared at every step.
//! - The Bingham Reynolds number at the simulated terminal velocity (f-EDEM eq. 18).
//!
//! # Measurements per sphere
//!
//! - the section reading, as the experiment takes it: the section length divided by the transit
//!   time between two detectors (`[measure]`), flagged steady when the velocities at the two
//!   detectors differ by less than `steady_tolerance` of the section velocity;
//! - the terminal velocity of the simulation: the mean velocity over a rolling window of
//!   `terminal_window_m` once the velocities at its two ends differ by less than
//!   `terminal_tolerance` (the sphere keeps falling past the tank bottom if it needs to);
//! - velocities at probe times (dense output: the same scheme over the part of the step);
//! - for drops, the entry speed at the surface and the settling distance of the lowest point.
//!
//! # Limits
//!
//! - No wall effect and no hindered settling: the spheres do not see each other or the container
//!   walls (the container only sets the bottom at which a sphere stops).
//! - An explicit step of a yield-stress drag chatters about rest; that is reported as unstable,
//!   not cured by a smaller dt.
//! - Interruption (Ctrl-C/SIGTERM) is checked every [`simulate::INTERRUPT_CHECK_STEPS`] steps of
//!   every sphere; an interrupted run writes nothing (a partial set of spheres is no result).
//!
//! # Files
//!
//! [`setup`]: run options, dimension, per-sphere quantities fixed at release;
//! [`simulate`]: the step loop as named stages, free engine and Rapier path;
//! [`output`]: every table and chart of the kind; [`charts`]: its charts and the combined ones;
//! [`run_scene`] is the entry point of `settle run`.

pub mod charts;
pub mod console;
pub mod cost;
pub mod output;
mod scene;
pub mod setup;
pub mod simulate;
mod submerged;
#[cfg(test)]
mod tests;
mod transient;

pub use scene::Scene;
pub use setup::{release_depth_m, RunOptions};
pub use simulate::{run, run_scene_cases, Halt, SphereResult};

use crate::error::Error;
use crate::scenario::FreeSettlingSpec;
use crate::scenes::{Prepared, SceneReport};
// Re-exported for the unit tests only.
#[cfg(test)]
pub(crate) use simulate::{run_rapier, run_sphere, StopReason};

/// State variables per body of the history force (v, x and one per exponential of the kernel)
/// of the first sphere of `cases` in the scene `sc`; None without a history force.
pub fn history_states(sc: Scene, cases: &[crate::scenario::inputs::SphereCase]) -> Option<usize> {
    let c = cases.first()?;
    let su = setup::SphereSetup::<3>::new(sc, c, RunOptions::of_common(sc.common));
    su.transient.as_ref()?.history.as_ref().map(|m| m.states())
}

/// Runs the spheres of a free-settling or drop scenario and adds its tables and charts to
/// `out`: the entry point of `settle run` for these kinds. Interrupted (Ctrl-C/SIGTERM), it adds
/// nothing and returns [`Error::InterruptedUnwritten`] with the scenario file.
pub fn run_scene(
    p: &Prepared,
    spec: &FreeSettlingSpec,
    out: &mut crate::io::Outputs,
) -> Result<(Vec<SphereResult>, SceneReport), Error> {
    let interrupted = || Error::InterruptedUnwritten(p.path.clone());
    let sc = Scene {
        common: &p.common,
        spec,
    };
    let results = match run_scene_cases(sc, &p.spheres, RunOptions::of_common(&p.common)) {
        Ok(r) => r,
        Err(Halt::Unstable(u)) => return Err(Error::Unstable(p.path.clone(), u)),
        Err(Halt::Interrupted) => return Err(interrupted()),
    };
    let mut made = crate::io::Outputs::new();
    let report = output::fill(p, spec, &results, &mut made).map_err(|e| match e {
        Error::Io(_, io) if io.kind() == std::io::ErrorKind::Interrupted => interrupted(),
        e => e,
    })?;
    out.extend(made);
    Ok((results, report))
}
