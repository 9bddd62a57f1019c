//! Kind `funnel_pour`: the tables `[funnel]` and `[repeats]` (serde), and the check of
//! `[repeats]`. The checks that read the whole scenario and the kind's spec are in
//! `kinds/funnel_pour.rs`.

use crate::error::BadInput;
use crate::scenario::check::Check;
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

impl Repeats {
    /// `1 ≤ count ≤ 10 000`.
    pub(crate) fn check(&self, c: &Check) -> Result<(), BadInput> {
        c.count_in("repeats.count", self.count, 1, 10_000)
    }
}
