//! Output files of a drop run (`kind = "drop"`): `summary.csv` with one row per sphere and fall
//! height, and `settling_distance.svg` (settling distance against fall height, one series per
//! diameter, like f-EDEM Fig. 16).

use super::chart::{scatter_svg, Scale, Series};
use super::{num, opt};
use crate::scenes::free_settling::SphereResult;
use std::collections::BTreeMap;
use std::io;
use std::path::Path;

/// Header of a drop `summary.csv`. `settling_distance_m` is the depth of the ball's lowest point
/// below the free surface once it has stopped (or at the end of the run); `centre_depth_m` the
/// depth of its centre.
pub const HEADER: [&str; 12] = [
    "sphere_id",
    "diameter_m",
    "density_kg_m3",
    "fall_height_m",
    "entry_velocity_m_s",
    "settling_distance_m",
    "centre_depth_m",
    "stop_time_s",
    "steps",
    "dt_s",
    "integrator",
    "submergence",
];

/// Writes the drop `summary.csv`.
pub fn write_summary(
    path: &Path,
    results: &[SphereResult],
    dt_s: f64,
    integrator: &str,
    submergence: &str,
) -> io::Result<()> {
    let mut w = csv::Writer::from_path(path).map_err(io::Error::other)?;
    w.write_record(HEADER).map_err(io::Error::other)?;
    for r in results {
        let d = r.case.spec.diameter_m;
        w.write_record([
            r.case.id.clone(),
            num(d),
            num(r.case.spec.density_kg_m3),
            opt(r.case.fall_height_m),
            opt(r.entry_velocity_m_s),
            num(r.final_bottom_depth_m),
            num(r.final_bottom_depth_m - 0.5 * d),
            opt(r.stop_time_s),
            r.steps.to_string(),
            num(dt_s),
            integrator.to_string(),
            submergence.to_string(),
        ])
        .map_err(io::Error::other)?;
    }
    w.flush()
}

/// Settling distance against fall height, one series per diameter.
pub fn write_chart(path: &Path, title: &str, results: &[SphereResult]) -> Result<(), String> {
    let mut by_d: BTreeMap<u64, Vec<(f64, f64)>> = BTreeMap::new();
    for r in results {
        let key = (r.case.spec.diameter_m * 1e6).round() as u64;
        by_d.entry(key).or_default().push((
            r.case.fall_height_m.unwrap_or(0.0) * 1e3,
            r.final_bottom_depth_m * 1e3,
        ));
    }
    let series: Vec<Series> = by_d
        .into_iter()
        .enumerate()
        .map(|(i, (d_um, pts))| {
            Series::sorted_line(format!("d = {} mm", d_um as f64 / 1000.0), pts, i)
        })
        .collect();
    scatter_svg(
        path,
        title,
        "fall height (mm)",
        "settling distance, ball bottom below surface (mm)",
        Scale::Linear,
        Scale::Linear,
        &series,
    )
}
