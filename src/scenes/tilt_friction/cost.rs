//! The cost of a tilt test ([`crate::scenes::cost`]): one block in a Rapier world.

use crate::scenario::Scenario;
use crate::scenes::cost::{rapier_load, Load};

/// The load of a `tilt_friction` scenario.
pub fn load(s: &Scenario) -> Load {
    rapier_load(s, 1.0, "time.dt_s")
}
