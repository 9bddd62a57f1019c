//! Kind `funnel_pour`: the checks of `[funnel]` that read the whole scenario, and the kind's
//! spec. The tables `[funnel]` and `[repeats]` are in `tables/funnel_pour.rs`.

use super::super::rules::contact_scene_3d;
use super::super::{Contacts, Container, FunnelSpec, Repeats, Scenario};
use crate::error::BadInput;
use crate::scenario::check::{cc, oc, Check};

impl FunnelSpec {
    /// Counts and geometry in range: the outlet wider than the largest ball and at most the
    /// top, bins and planes within the cylinder (`container`, checked present by the caller).
    pub(crate) fn check(&self, c: &Check, s: &Scenario) -> Result<(), BadInput> {
        let Some(ct) = s.container.as_ref() else {
            return Err(c.err(
                "container",
                "missing: kind = \"funnel_pour\" needs a [container]",
            ));
        };
        c.count_in("funnel.count", self.count, 1, 100_000)?;
        c.range(
            "funnel.top_diameter_m",
            self.top_diameter_m,
            oc(0.0, 10.0, "m"),
        )?;
        let d_max = s.spheres.iter().map(|sp| sp.diameter_m).fold(0.0, f64::max);
        c.range(
            "funnel.outlet_diameter_m",
            self.outlet_diameter_m,
            oc(
                d_max,
                self.top_diameter_m,
                "m (wider than the largest ball, at most top_diameter_m)",
            ),
        )?;
        c.table(
            "funnel",
            &[
                ("cone_height_m", self.cone_height_m, oc(0.0, 10.0, "m")),
                (
                    "outlet_above_surface_m",
                    self.outlet_above_surface_m,
                    cc(0.0, 100.0, "m"),
                ),
                ("column_height_m", self.column_height_m, cc(0.0, 10.0, "m")),
                ("fill_time_s", self.fill_time_s, cc(0.0, 1e3, "s")),
                (
                    "wall_above_surface_m",
                    self.wall_above_surface_m,
                    cc(0.0, 10.0, "m"),
                ),
                ("wall_thickness_m", self.wall_thickness_m, oc(0.0, 1.0, "m")),
            ],
        )?;
        c.count_in("funnel.facets", self.facets, 8, 1024)?;
        c.table(
            "funnel",
            &[
                ("rest_speed_m_s", self.rest_speed_m_s, oc(0.0, 1e3, "m/s")),
                (
                    "z_bin_m",
                    self.z_bin_m,
                    oc(0.0, ct.height_m, "m (at most container.height_m)"),
                ),
                (
                    "grid_cell_m",
                    self.grid_cell_m,
                    oc(
                        0.0,
                        ct.diameter_m.unwrap_or(f64::INFINITY),
                        "m (at most container.diameter_m)",
                    ),
                ),
            ],
        )?;
        if let Some(tc) = self.count_time_s {
            c.range(
                "funnel.count_time_s",
                tc,
                super::super::within_run(s.time.end_s),
            )?;
        }
        c.each(
            "funnel.planes_z_m",
            &self.planes_z_m,
            cc(
                0.0,
                ct.height_m,
                "m (within the paste, above the cylinder bottom)",
            ),
        )
    }
}

/// Balls poured from a funnel into the fluid-filled cylinder (kind `funnel_pour`).
#[derive(Clone, Debug, PartialEq)]
pub struct FunnelPourSpec {
    /// The `[funnel]` table: ball count and funnel geometry.
    pub funnel: FunnelSpec,
    /// Radius of the cylinder, m (half of `container.diameter_m`).
    pub cylinder_radius_m: f64,
    /// Height of the fluid column, m (`container.height_m`).
    pub height_m: f64,
    /// The contact properties (`[contacts]`).
    pub contacts: Contacts,
    /// Repeats and their first seed (`[repeats]`; absent: one run, seed 0).
    pub repeats: Repeats,
}

/// The spec of a `funnel_pour` scenario: `[funnel]`, a cylindrical `[container]`, `[contacts]`
/// in 3D, `[repeats]` if given.
pub(crate) fn spec(c: &Check, s: &Scenario) -> Result<FunnelPourSpec, BadInput> {
    let missing =
        |key: &str, what: &str| c.err(key, format!("missing: kind = \"funnel_pour\" needs {what}"));
    let f = s
        .funnel
        .as_ref()
        .ok_or_else(|| missing("funnel", "a [funnel] table (count, geometry)"))?;
    let (height_m, diameter_m) = match &s.container {
        Some(Container {
            height_m,
            diameter_m: Some(d),
            ..
        }) => (*height_m, *d),
        _ => {
            return Err(missing(
                "container.diameter_m",
                "a cylindrical [container] with diameter_m",
            ))
        }
    };
    let contacts = contact_scene_3d(c, s)?;
    f.check(c, s)?;
    Ok(FunnelPourSpec {
        funnel: f.clone(),
        cylinder_radius_m: 0.5 * diameter_m,
        height_m,
        contacts,
        repeats: s.repeats.clone().unwrap_or(Repeats { count: 1, seed: 0 }),
    })
}
