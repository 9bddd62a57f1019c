//! Time settings: `[time]`.

use crate::dynamics::Integrator;
use crate::error::BadInput;
use crate::scenario::check::{oc, Check, MAX_STEPS};
use serde::{Deserialize, Serialize};

/// Time settings.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Time {
    /// Time step, s (> 0, ≤ `end_s`). `settle run --dt` overrides it.
    pub dt_s: f64,
    /// Simulated duration, s (> 0). A free-settling sphere also stops at the container bottom
    /// or when it is held at rest by the yield stress.
    pub end_s: f64,
    /// `explicit`, `implicit` or `exponential` (default).
    #[serde(default)]
    pub integrator: Integrator,
}

impl Time {
    /// `0 < end_s ≤ 1e9`, `0 < dt_s ≤ end_s`, at most [`MAX_STEPS`] steps.
    pub(crate) fn check(&self, c: &Check) -> Result<(), BadInput> {
        c.range("time.end_s", self.end_s, oc(0.0, 1e9, "s"))?;
        c.range(
            "time.dt_s",
            self.dt_s,
            oc(0.0, self.end_s, "s (at most time.end_s)"),
        )?;
        let steps = self.end_s / self.dt_s;
        if steps > MAX_STEPS {
            return Err(c.err(
                "time.dt_s",
                format!(
                    "{:.3e} steps (end_s/dt_s) exceed the limit of {MAX_STEPS:.0e}: raise dt_s",
                    steps
                ),
            ));
        }
        Ok(())
    }
}
