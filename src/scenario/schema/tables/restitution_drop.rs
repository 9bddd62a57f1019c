//! Kind `restitution_drop`: the table `[restitution_drop]` (serde) with its checks. The kind's
//! spec is in `kinds/restitution_drop.rs`.

use crate::error::BadInput;
use crate::scenario::check::{cc, oc, Check};
use serde::{Deserialize, Serialize};

/// Restitution drop test (f-EDEM Appendix II): one ball (the scenario's single `[[spheres]]`)
/// dropped from rest on a fixed plate, in the scenario's fluid (air), once per drop height; the
/// apex after the first bounce is the rebound height. The contact restitution is
/// `contacts.restitution`.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RestitutionDropSpec {
    /// Drop heights of the ball's lowest point above the plate, m.
    pub drop_heights_m: Vec<f64>,
    /// Measured rebound heights, m (same length; optional).
    #[serde(default)]
    pub measured_rebound_heights_m: Vec<f64>,
    /// Relative tolerance on |simulated / measured rebound height − 1| that the source states as
    /// its acceptance (f-EDEM App. II: 3 %). Reported (how many heights meet it), not enforced.
    /// Default 0.03.
    #[serde(default = "default_rebound_tolerance")]
    pub tolerance: f64,
}

fn default_rebound_tolerance() -> f64 {
    0.03
}

impl RestitutionDropSpec {
    /// At least one drop height in (0, 100] m; measured rebounds one per height (or none) in
    /// [0, 100] m; tolerance in (0, 1].
    pub(crate) fn check(&self, c: &Check) -> Result<(), BadInput> {
        if self.drop_heights_m.is_empty() {
            return Err(c.err(
                "restitution_drop.drop_heights_m",
                "missing: give at least one drop height, 0 < h ≤ 100 m",
            ));
        }
        c.each(
            "restitution_drop.drop_heights_m",
            &self.drop_heights_m,
            oc(0.0, 100.0, "m"),
        )?;
        let n = self.measured_rebound_heights_m.len();
        if n != 0 && n != self.drop_heights_m.len() {
            return Err(c.err(
                "restitution_drop.measured_rebound_heights_m",
                format!(
                    "{n} values for {} drop heights: give one per drop height or none",
                    self.drop_heights_m.len()
                ),
            ));
        }
        c.each(
            "restitution_drop.measured_rebound_heights_m",
            &self.measured_rebound_heights_m,
            cc(0.0, 100.0, "m"),
        )?;
        c.range(
            "restitution_drop.tolerance",
            self.tolerance,
            oc(0.0, 1.0, ""),
        )
    }
}
