//! The cost of a funnel pour ([`crate::scenes::cost`]): every ball of every repeat in a
//! Rapier world.

use crate::scenario::Scenario;
use crate::scenes::cost::{rapier_load, Load};

/// The load of a `funnel_pour` scenario.
pub fn load(s: &Scenario) -> Load {
    let balls = s.funnel.as_ref().map_or(1, |f| f.count) as f64;
    let reps = s.repeats.as_ref().map_or(1, |r| r.count) as f64;
    rapier_load(s, balls * reps, "repeats.count")
}
