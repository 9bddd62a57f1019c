//! The cost of a tilt test ([`crate::scenes::cost`]): one block in a Rapier world.

use crate::scenario::Common;
use crate::scenes::cost::{rapier_load, Load};

/// The load of a `tilt_friction` scenario.
pub fn load(c: &Common) -> Load {
    rapier_load(c, 1.0, "time.dt_s")
}
