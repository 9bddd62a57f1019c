//! 2D world (rapier2d-f64): discs standing for spheres, gravity along −y.
//!
//! The world itself is one source for both dimensions, `engine/world/`, compiled here against
//! rapier2d-f64 and in [`super::dim3`] against rapier3d-f64; this file supplies what differs.

use rapier2d_f64 as rapier;

/// Rapier's linear joint axes in this dimension (the yield-stress hold's motors).
const LIN_AXES: [rapier::prelude::JointAxis; 2] = [
    rapier::prelude::JointAxis::LinX,
    rapier::prelude::JointAxis::LinY,
];

/// |ω| of an angular velocity, rad/s: a scalar in 2D.
fn spin_norm(spin: rapier::math::AngVector) -> f64 {
    spin.abs()
}

// The same source is this module in both dimensions, on purpose (against each Rapier crate).
// Each dimension uses its own subset of the world (2D: the cylinder's grain clusters; 3D:
// drops, tilts, pours and the Rapier free settling), so what one leaves unused is not dead.
#[allow(clippy::duplicate_mod, dead_code)]
#[path = "world/mod.rs"]
mod world;
pub use world::*;
