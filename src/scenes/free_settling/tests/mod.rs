//! Unit tests of the free-settling scene (moved from `tests/engine/free_settling.rs` and
//! `tests/validation/{paste_drop,transient,valentik,stokes_single,sphere_drag}.rs`): one sphere
//! through the scene's own integrator and through Rapier, against analytic solutions and
//! reference data.

mod paste_drop;
mod rapier;
mod sphere_drag;
mod stokes_single;
mod transient;
mod valentik;

pub(super) use crate::scenes::tests::prepare;

/// The free-settling scene of a prepared scenario (which must be of kind `free_settling` or
/// `drop`).
pub(super) fn scene(p: &crate::scenes::Prepared) -> super::Scene<'_> {
    super::Scene::of(p).expect("a free-settling or drop scenario")
}
