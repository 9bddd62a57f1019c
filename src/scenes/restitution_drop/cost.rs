//! The cost of a restitution drop ([`crate::scenes::cost`]): one ball in a Rapier world.

use crate::scenario::Common;
use crate::scenes::cost::{rapier_load, Load};

/// The load of a `restitution_drop` scenario.
pub fn load(c: &Common) -> Load {
    rapier_load(c, 1.0, "time.dt_s")
}
