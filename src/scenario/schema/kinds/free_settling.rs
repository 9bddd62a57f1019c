//! Kinds `free_settling` and `drop` (a mode of free settling: the spheres fall through air into
//! the fluid first): the spec built from `[container]`, `[release]` and `[measure]`.

use super::super::{Container, EngineChoice, Measure, Release, Scenario};
use crate::error::BadInput;
use crate::scenario::check::Check;

/// How the spheres of a free-settling scene enter the fluid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Entry {
    /// Released submerged at `release.depth_m` (kind `free_settling`).
    Submerged,
    /// Dropped from each of `release.fall_heights_m` (at least one) above the free surface
    /// (kind `drop`).
    Drop,
}

/// Free settling and drops: each sphere alone in the fluid, no contacts.
#[derive(Clone, Debug, PartialEq)]
pub struct FreeSettlingSpec {
    /// Submerged release (`free_settling`) or drop through air (`drop`).
    pub entry: Entry,
    /// The container (its bottom stops a sphere), or `None` for an unbounded fluid.
    pub container: Option<Container>,
    /// Release depth, speed and (drops) fall heights.
    pub release: Release,
    /// Probe times, detector section and steadiness window, if any.
    pub measure: Option<Measure>,
}

/// The spec of a `free_settling` scenario.
pub(crate) fn free_settling(_: &Check, s: &Scenario) -> Result<FreeSettlingSpec, BadInput> {
    Ok(spec(s, Entry::Submerged))
}

/// The spec of a `drop` scenario: the free engine only (no contacts there yet).
pub(crate) fn drop(c: &Check, s: &Scenario) -> Result<FreeSettlingSpec, BadInput> {
    if s.engine == EngineChoice::Rapier {
        return Err(c.err("engine", "`rapier` is not available for kind = \"drop\" yet (no contacts there): allowed `auto`, `free`"));
    }
    Ok(spec(s, Entry::Drop))
}

fn spec(s: &Scenario, entry: Entry) -> FreeSettlingSpec {
    FreeSettlingSpec {
        entry,
        container: s.container.clone(),
        release: s.release.clone(),
        measure: s.measure.clone(),
    }
}
