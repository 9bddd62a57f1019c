//! Measurement settings: `[measure]`.

use super::base::within_run;
use crate::error::BadInput;
use crate::scenario::check::{cc, oc, Check};
use serde::{Deserialize, Serialize};

/// Measurement settings.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Measure {
    /// Depth below the surface of the first detector of the measuring section, m (optional;
    /// give both detectors or neither).
    #[serde(default)]
    pub section_top_depth_m: Option<f64>,
    /// Depth of the second detector, m (> top, within the container).
    #[serde(default)]
    pub section_bottom_depth_m: Option<f64>,
    /// Steadiness criterion: the velocity at the two detectors may differ by at most this
    /// fraction of the section velocity for the reading to count as terminal. Default 0.005.
    #[serde(default = "default_steady")]
    pub steady_tolerance: f64,
    /// Length of the rolling window used to read the simulated terminal velocity, m (optional).
    /// When set, the sphere keeps falling (past the container bottom if need be, in an
    /// unbounded column) until the velocities at both ends of the last window differ by at
    /// most `terminal_tolerance` of the window's mean velocity; that mean is the terminal
    /// velocity. Without it, the terminal velocity is the section reading or the final velocity.
    #[serde(default)]
    pub terminal_window_m: Option<f64>,
    /// Steadiness criterion of the rolling window (relative). Default 1e-4.
    #[serde(default = "default_terminal_tol")]
    pub terminal_tolerance: f64,
    /// Times at which the velocity is probed (`probes.csv`, used by sweeps), s.
    #[serde(default)]
    pub velocity_at_s: Vec<f64>,
}

fn default_steady() -> f64 {
    0.005
}

fn default_terminal_tol() -> f64 {
    1e-4
}

impl Measure {
    /// Both detectors or neither, top above bottom within a container of height `height_m`
    /// (infinite without one); tolerances in (0, 1]; probe times within the run.
    pub(crate) fn check(&self, c: &Check, height_m: f64, end_s: f64) -> Result<(), BadInput> {
        let both = "missing: give both detectors of the measuring section or neither";
        match (self.section_top_depth_m, self.section_bottom_depth_m) {
            (None, None) => {}
            (Some(top), Some(bot)) => {
                let h = height_m;
                c.range(
                    "measure.section_top_depth_m",
                    top,
                    cc(0.0, h, "m (within the container)"),
                )?;
                if !(bot > top && bot <= h) {
                    return Err(c.err("measure.section_bottom_depth_m", format!(
                        "{bot} is out of range: allowed section_top_depth_m ({top}) < section_bottom_depth_m ≤ container.height_m ({h}) m")));
                }
            }
            (Some(_), None) => return Err(c.err("measure.section_bottom_depth_m", both)),
            (None, Some(_)) => return Err(c.err("measure.section_top_depth_m", both)),
        }
        c.table(
            "measure",
            &[
                ("steady_tolerance", self.steady_tolerance, oc(0.0, 1.0, "")),
                (
                    "terminal_tolerance",
                    self.terminal_tolerance,
                    oc(0.0, 1.0, ""),
                ),
            ],
        )?;
        if let Some(w) = self.terminal_window_m {
            c.range("measure.terminal_window_m", w, oc(0.0, 1e4, "m"))?;
        }
        c.each(
            "measure.velocity_at_s",
            &self.velocity_at_s,
            within_run(end_s),
        )
    }
}
