//! Kind `funnel_pour`: `[funnel]` and `[repeats]`.

use super::super::contacts::contact_scene_3d;
use super::super::{Contacts, Container, Scenario};
use crate::error::BadInput;
use crate::scenario::check::{cc, oc, Check};
use serde::{Deserialize, Serialize};

/// Funnel pour (f-EDEM §4.2, Fig. 17): the funnel is not described in the source; see the
/// scenario file for the geometry used.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FunnelSpec {
    /// Number of balls.
    pub count: usize,
    /// Inner diameter of the funnel at its top, m.
    pub top_diameter_m: f64,
    /// Inner diameter of the outlet, m.
    pub outlet_diameter_m: f64,
    /// Height of the conical part, m.
    pub cone_height_m: f64,
    /// Height of the outlet above the fluid surface, m (f-EDEM: 0.15).
    pub outlet_above_surface_m: f64,
    /// Time at which the balls in the fluid and in the domain are counted (f-EDEM Fig. 20), s.
    #[serde(default)]
    pub count_time_s: Option<f64>,
    /// Heights above the cylinder bottom of the horizontal planes of the presence maps, m.
    #[serde(default)]
    pub planes_z_m: Vec<f64>,
    /// Height of a vertical cylindrical section (inner diameter `top_diameter_m`) on top of the
    /// cone, m: room for the random initial placement of the balls. Default 0.
    #[serde(default)]
    pub column_height_m: f64,
    /// Time the balls, placed at random without overlap, fall and settle in the funnel on the
    /// plug closing the outlet before it is removed at t = 0, s. Default 0.3.
    #[serde(default = "default_fill_time")]
    pub fill_time_s: f64,
    /// Height of the cylinder wall above the paste surface, m. Default 0: the mould is filled to
    /// the brim (f-EDEM: paste 150 mm deep in a cylinder 150 mm high).
    #[serde(default)]
    pub wall_above_surface_m: f64,
    /// Wall thickness of the funnel and the cylinder (boxes around the circles), m. Default 4e-3.
    #[serde(default = "default_wall_thickness")]
    pub wall_thickness_m: f64,
    /// Number of flat faces approximating each circle of the funnel and the cylinder. Default 64.
    #[serde(default = "default_facets")]
    pub facets: usize,
    /// The run of a repeat ends before `time.end_s` once t ≥ `count_time_s` and every ball has
    /// been slower than this for 0.05 s, m/s. Default 1e-3.
    #[serde(default = "default_rest_speed")]
    pub rest_speed_m_s: f64,
    /// Bin width of the vertical distribution (`z_distribution.csv`), m. Default 5e-3.
    #[serde(default = "default_z_bin")]
    pub z_bin_m: f64,
    /// Cell size of the presence-probability grids (`presence.csv`), m. Default 2.5e-3.
    #[serde(default = "default_grid_cell")]
    pub grid_cell_m: f64,
}

fn default_fill_time() -> f64 {
    0.3
}
fn default_wall_thickness() -> f64 {
    4e-3
}
fn default_facets() -> usize {
    64
}
fn default_rest_speed() -> f64 {
    1e-3
}
fn default_z_bin() -> f64 {
    5e-3
}
fn default_grid_cell() -> f64 {
    2.5e-3
}

/// Repetitions with different seeds.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Repeats {
    /// Number of runs. Default 1.
    #[serde(default = "one_usize")]
    pub count: usize,
    /// Seed of the first run; run i uses seed + i. Default 0.
    #[serde(default)]
    pub seed: u64,
}

fn one_usize() -> usize {
    1
}

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

impl Repeats {
    /// `1 ≤ count ≤ 10 000`.
    pub(crate) fn check(&self, c: &Check) -> Result<(), BadInput> {
        c.count_in("repeats.count", self.count, 1, 10_000)
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
