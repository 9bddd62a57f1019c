//! Kind `tilt_friction`: the checks of `[tilt]` (which read the whole scenario), and the
//! kind's spec. The table is in `tables/tilt_friction.rs`.

use super::super::rules::contact_scene_3d;
use super::super::{Contacts, Scenario, TiltSpec};
use crate::error::BadInput;
use crate::scenario::check::{cc, oc, Check, MAX_STEPS};

impl TiltSpec {
    /// Three edge lengths in (0, 10] m, density, at least one angle in [0°, 90°), a duration
    /// of at least one step and at most [`MAX_STEPS`] steps, slide distance and bisection
    /// tolerance in range.
    pub(crate) fn check(&self, c: &Check, s: &Scenario) -> Result<(), BadInput> {
        if self.block_size_m.len() != 3 {
            return Err(c.err(
                "tilt.block_size_m",
                format!(
                    "{} values: give the three edge lengths [x, y, z], each 0 < l ≤ 10 m",
                    self.block_size_m.len()
                ),
            ));
        }
        c.each("tilt.block_size_m", &self.block_size_m, oc(0.0, 10.0, "m"))?;
        c.range(
            "tilt.block_density_kg_m3",
            self.block_density_kg_m3,
            oc(0.0, 25_000.0, "kg/m³"),
        )?;
        if self.angles_deg.is_empty() {
            return Err(c.err(
                "tilt.angles_deg",
                "missing: give at least one angle, 0 ≤ angle < 90°",
            ));
        }
        for (i, a) in self.angles_deg.iter().enumerate() {
            if !(a.is_finite() && (0.0..90.0).contains(a)) {
                return Err(c.err(
                    &format!("tilt.angles_deg[{i}]"),
                    format!("{a} is out of range: allowed 0 ≤ angle < 90°"),
                ));
            }
        }
        let dt = s.time.dt_s;
        c.range(
            "tilt.duration_s",
            self.duration_s,
            cc(dt, 1e4, "s (at least time.dt_s)"),
        )?;
        if self.duration_s / dt > MAX_STEPS {
            return Err(c.err("time.dt_s", format!(
                "{:.3e} steps per angle (tilt.duration_s/dt_s) exceed the limit of {MAX_STEPS:.0e}: raise dt_s",
                self.duration_s / dt)));
        }
        c.table(
            "tilt",
            &[
                ("slide_distance_m", self.slide_distance_m, oc(0.0, 1e3, "m")),
                (
                    "bisection_tolerance_deg",
                    self.bisection_tolerance_deg,
                    oc(0.0, 90.0, "°"),
                ),
            ],
        )
    }
}

/// A block on a tilted plate (kind `tilt_friction`).
#[derive(Clone, Debug, PartialEq)]
pub struct TiltFrictionSpec {
    /// The `[tilt]` table: block, angles, duration, slide distance, bisection tolerance.
    pub tilt: TiltSpec,
    /// The block's edge lengths [x, y, z], m (`tilt.block_size_m`).
    pub block_size_m: [f64; 3],
    /// The contact properties (`[contacts]`).
    pub contacts: Contacts,
}

/// The spec of a `tilt_friction` scenario: `[tilt]`, `[contacts]` in 3D.
pub(crate) fn spec(c: &Check, s: &Scenario) -> Result<TiltFrictionSpec, BadInput> {
    let t = s.tilt.as_ref().ok_or_else(|| {
        c.err(
            "tilt",
            "missing: kind = \"tilt_friction\" needs a [tilt] table (block_size_m, block_density_kg_m3, angles_deg, duration_s)",
        )
    })?;
    let contacts = contact_scene_3d(c, s)?;
    t.check(c, s)?;
    let block_size_m: [f64; 3] = t
        .block_size_m
        .as_slice()
        .try_into()
        .map_err(|_| c.err("tilt.block_size_m", "give the three edge lengths [x, y, z]"))?;
    Ok(TiltFrictionSpec {
        tilt: t.clone(),
        block_size_m,
        contacts,
    })
}
