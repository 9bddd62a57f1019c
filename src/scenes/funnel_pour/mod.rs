//! The funnel pour of f-EDEM §4.2 (Figs. 17–22): balls held in a funnel above a cylinder of paste
//! are released together, fall through air, enter the paste and stop, held by its yield stress.
//! Repeated with different random initial placements (f-EDEM: 15 repeats) to give presence
//! probabilities on horizontal planes.
//!
//! # Scene (3D, z up, origin at the centre of the cylinder bottom)
//! - The table and the cylinder bottom: one half-space z ≥ 0 (nothing can pass through it).
//! - The cylinder wall, inner radius R = `container.diameter_m`/2, from z = 0 to
//!   `funnel.wall_above_surface_m` (default 0) above the paste surface z = H =
//!   `container.height_m` (f-EDEM's mould is as high as its paste): `funnel.facets` boxes
//!   of thickness `funnel.wall_thickness_m` whose inner faces make a regular polygon circumscribing
//!   the circle of radius R.
//! - The funnel, coaxial, its outlet `funnel.outlet_above_surface_m` above the paste surface: a
//!   cone frustum (`outlet_diameter_m` at the bottom, `top_diameter_m` at `cone_height_m` above)
//!   made of `facets` tilted boxes (a pyramid circumscribing the cone), and above it a vertical
//!   column of height `column_height_m` (boxes at the top radius) to make room for the balls.
//! - A plug: a box closing the outlet from below, removed at t = 0.
//! - Every collider has the `[contacts]` restitution and friction; every contact feels the
//!   rolling resistance `contacts.rolling_resistance` (torque −μ_r r Σ|F_n| ω̂, see
//!   [`crate::engine::dim3::World::set_rolling_resistance`]).
//! - The paste fills the cylinder below z = H: fluid forces (buoyancy, `drag.law`) act only there
//!   ([`crate::engine::dim3::World::set_free_surface`]), from the moment a ball's lowest point
//!   passes the surface (`fluid.submergence = "full"`, f-EDEM) or on the immersed cap
//!   (`"partial"`). A ball at rest in paste is held by the yield stress until pushed harder than
//!   its static resistance (see [`crate::engine::dim3::World::set_yield_hold`]).
//! - With `transient.added_mass`, a ball's inertia is m_p + C_m m_f of its immersed volume, in
//!   free flight and in its contacts, gravity staying m_p g
//!   ([`crate::engine::dim3::World::set_added_mass_coefficient`]).
//!
//! # Run of one repeat
//! Ball i (diameter and density of `[[spheres]]` entry i mod n) is placed at random (ChaCha8,
//! seed `repeats.seed` + repeat index) in the funnel and column, clear of the walls, the plug and
//! the other balls by 5 % of its diameter; the balls fall onto the plug and settle for
//! `funnel.fill_time_s`; the plug is removed at t = 0 and the run goes on to `time.end_s`, or
//! stops earlier once t ≥ `count_time_s` and every ball has been slower than
//! `funnel.rest_speed_m_s` for 0.05 s. Repeats run in parallel (rayon).
//!
//! # Where a ball is (centre position)
//! `paste`: within the cylinder radius, its lowest point below the paste surface (z − r ≤ H: the
//! fluid forces act on it with full submergence). `funnel`: above the outlet minus one radius,
//! within the funnel's top radius. `falling`: between the two, within the funnel's top radius.
//! `outside`: anywhere else in the domain (escaped over the rim, beside the cylinder). `away`: out
//! of the domain (the cylinder about the axis 0.1 m beyond the scene, z from −d to 0.1 m above
//! the column) after escaping over the rim. `lost`: passed through a wall, the funnel or the
//! floor (its centre crossed the cylinder's radius more than d/4 below the rim, or got beyond a
//! funnel wall's outer face, or below z = 0), or non-finite. Checked every step.
//!
//! # Files
//!
//! `balls.csv`, `counts.csv`, `timeseries.csv`, `z_distribution.csv` + `.svg` and
//! `presence.csv` + `.svg` (see [`output`]).
//!
//! # Layout
//!
//! The same shape as every scene: [`setup`] (the geometry and its colliders), [`simulate`](mod@simulate) (the
//! step loop of one repeat as named stages, with checkpoints, and the parallel repeats),
//! [`output`] (the files); and for this kind [`placement`] (the random start), [`census`]
//! (where the balls are, what a repeat records), [`report`] (the console summary).

pub mod census;
pub mod cost;
pub mod output;
pub mod placement;
pub mod report;
pub mod setup;
pub mod simulate;
#[cfg(test)]
mod tests;

pub use census::{Census, Place, RepeatResult};
pub use setup::Geometry;
pub use simulate::{run_repeat, simulate_with};

use crate::error::Error;
use crate::io::Outputs;
use crate::scenario::FunnelPourSpec;
use crate::scenes::{Prepared, RunContext, SceneReport};
use std::time::Instant;
// Re-exported for the unit tests only.
#[cfg(test)]
pub(crate) use census::Ball;
#[cfg(test)]
pub(crate) use placement::place_balls;
#[cfg(test)]
pub(crate) use simulate::simulate;

/// Funnel pour (kind `funnel_pour`): runs the repeats, adds `balls.csv`, `counts.csv`,
/// `timeseries.csv`, `z_distribution.csv` + `.svg` and `presence.csv` + `.svg` to `out` (see
/// [`output`]). Interrupted, it adds the repeats that finished.
pub fn run(
    p: &Prepared,
    f: &FunnelPourSpec,
    out: &mut Outputs,
    ctx: &RunContext,
) -> Result<SceneReport, Error> {
    let t0 = Instant::now();
    let (results, interrupted) = simulate_with(p, f, ctx)?;
    if results.is_empty() {
        return Ok(SceneReport {
            interrupted,
            lines: vec!["interrupted before any repeat finished".into()],
            ..SceneReport::default()
        });
    }
    let wall_s = t0.elapsed().as_secs_f64();
    output::fill(p, f, &results, out)?;
    let balls: Vec<crate::scenes::validity::SphereAt> = p
        .spheres
        .iter()
        .map(|c| crate::scenes::validity::SphereAt {
            id: c.id.clone(),
            diameter_m: c.spec.diameter_m,
            density_kg_m3: c.spec.density_kg_m3,
            speed_m_s: 0.0,
        })
        .collect();
    Ok(SceneReport {
        // The balls' ranges against the drag law (their speeds are not judged here).
        warnings: crate::scenes::validity::drag_warnings(p, &balls),
        steps: results.iter().map(|r| r.steps).sum(),
        bodies: f.funnel.count * results.len(),
        engine_settings: Some(report::engine_settings(p, f)),
        lines: report::lines(p, f, &results, wall_s),
        interrupted,
        reached_s: None,
    })
}
