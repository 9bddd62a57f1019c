//! Kind `tilt_friction`: the table `[tilt]` (serde). Its checks (which read the whole scenario)
//! and the kind's spec are in `kinds/tilt_friction.rs`.

use serde::{Deserialize, Serialize};

/// Tilt friction test (f-EDEM Appendix III): a cuboid block at rest on a fixed plate tilted by
/// each angle (gravity is tilted instead of the plate: the same thing in the plate's frame).
/// The contact friction is `contacts.friction`; the threshold angle is bracketed by the angles
/// given and refined by bisection.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TiltSpec {
    /// Block edge lengths (x, y, z), m: x along the slope, z normal to the plate.
    pub block_size_m: Vec<f64>,
    /// Block density, kg/m³.
    pub block_density_kg_m3: f64,
    /// Tilt angles to test, degrees (0 ≤ angle < 90).
    pub angles_deg: Vec<f64>,
    /// Simulated time at each angle, s.
    pub duration_s: f64,
    /// Displacement along the slope after `duration_s` above which the block counts as sliding,
    /// m. Default 1e-3.
    #[serde(default = "default_slide_distance")]
    pub slide_distance_m: f64,
    /// The threshold angle is bisected until the bracket (largest sticking angle, smallest
    /// sliding angle) is at most this wide, degrees. Default 0.1.
    #[serde(default = "default_bisection_tolerance")]
    pub bisection_tolerance_deg: f64,
}

fn default_slide_distance() -> f64 {
    1e-3
}

fn default_bisection_tolerance() -> f64 {
    0.1
}
