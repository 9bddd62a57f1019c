//! Moved to [`crate::scenario::inputs`] (the spheres of a scenario are an input file, read
//! while the scenario is prepared); re-exported here until the callers switch.

pub use crate::scenario::inputs::{spheres, SphereCase};
