//! 3D world (rapier3d-f64): spheres, gravity along −z.
//!
//! The world itself is one source for both dimensions, `engine/world/`, compiled here against
//! rapier3d-f64 and in [`super::dim2`] against rapier2d-f64; this file supplies what differs.

use rapier3d_f64 as rapier;

/// Rapier's linear joint axes in this dimension (the yield-stress hold's motors).
const LIN_AXES: [rapier::prelude::JointAxis; 3] = [
    rapier::prelude::JointAxis::LinX,
    rapier::prelude::JointAxis::LinY,
    rapier::prelude::JointAxis::LinZ,
];

/// |ω| of an angular velocity, rad/s: the length of a vector in 3D.
fn spin_norm(spin: rapier::math::AngVector) -> f64 {
    spin.length()
}

// The same source is this module in both dimensions, on purpose (against each Rapier crate).
// Each dimension uses its own subset of the world (2D: the cylinder's grain clusters; 3D:
// drops, tilts, pours and the Rapier free settling), so what one leaves unused is not dead.
#[allow(clippy::duplicate_mod, dead_code)]
#[path = "world/mod.rs"]
mod world;
pub use world::*;
