//! The cost of a funnel pour ([`crate::scenes::cost`]): every ball of every repeat in a
//! Rapier world.

use crate::scenario::{Common, FunnelPourSpec};
use crate::scenes::cost::{rapier_load, Load};

/// The load of a `funnel_pour` scenario.
pub fn load(c: &Common, f: &FunnelPourSpec) -> Load {
    let balls = f.funnel.count as f64;
    let reps = f.repeats.count as f64;
    rapier_load(c, balls * reps, "repeats.count")
}
