//! Output files of a free-settling run: `summary.csv`, `timeseries.csv`, `probes.csv`,
//! `metrics.csv` and `terminal_velocity.svg` (like f-EDEM Fig. 11) when measurements exist.

use super::chart::{scatter_svg, Scale, Series};
use super::metrics::ErrorStats;
use super::{num, opt};
use crate::scenes::free_settling::SphereResult;
use std::collections::BTreeMap;
use std::io;
use std::path::Path;

/// Header of `summary.csv`.
pub const SUMMARY_HEADER: [&str; 23] = [
    "sphere_id",
    "suspension",
    "diameter_m",
    "density_kg_m3",
    "v_measured_m_s",
    "v_simulated_m_s",
    "v_force_balance_m_s",
    "rel_error",
    "re_bingham",
    "regime",
    "steps",
    "dt_s",
    "integrator",
    "v_analytic_m_s",
    "rel_error_vs_force_balance",
    "terminal_steady",
    "v_section_m_s",
    "steady_in_section",
    "max_velocity_error_rel",
    "response_time_s",
    "rayleigh_time_s",
    "stop",
    "end_time_s",
];

/// Relative error of the simulated against the measured velocity, if measured.
pub fn rel_error(r: &SphereResult) -> Option<f64> {
    r.case
        .spec
        .v_measured_m_s
        .map(|m| (r.v_simulated_m_s - m) / m)
}

/// Relative difference of the simulated velocity from the force balance (0 when both are 0).
pub fn rel_error_vs_force_balance(r: &SphereResult) -> f64 {
    if r.v_force_balance_m_s == 0.0 {
        r.v_simulated_m_s.abs()
    } else {
        (r.v_simulated_m_s - r.v_force_balance_m_s) / r.v_force_balance_m_s
    }
}

/// One `summary.csv` row.
pub fn summary_row(r: &SphereResult, dt_s: f64, integrator: &str) -> Vec<String> {
    let s = &r.case.spec;
    vec![
        r.case.id.clone(),
        s.suspension.map(|x| x.to_string()).unwrap_or_default(),
        num(s.diameter_m),
        num(s.density_kg_m3),
        opt(s.v_measured_m_s),
        num(r.v_simulated_m_s),
        num(r.v_force_balance_m_s),
        opt(rel_error(r)),
        opt(r.re_bingham),
        r.regime.label().to_string(),
        r.steps.to_string(),
        num(dt_s),
        integrator.to_string(),
        opt(r.v_analytic_m_s),
        num(rel_error_vs_force_balance(r)),
        r.terminal_steady.map(|b| b.to_string()).unwrap_or_default(),
        opt(r.v_section_m_s),
        r.steady_in_section
            .map(|b| b.to_string())
            .unwrap_or_default(),
        opt(r.max_velocity_error_rel),
        num(r.response_time_s),
        opt(r.rayleigh_time_s),
        r.stop.label().to_string(),
        num(r.end_time_s),
    ]
}

fn csv_err(e: csv::Error) -> io::Error {
    io::Error::other(e)
}

/// Writes `summary.csv` rows (with header) to `path`.
pub fn write_summary(path: &Path, rows: &[Vec<String>]) -> io::Result<()> {
    let mut w = csv::Writer::from_path(path).map_err(csv_err)?;
    w.write_record(SUMMARY_HEADER).map_err(csv_err)?;
    for r in rows {
        w.write_record(r).map_err(csv_err)?;
    }
    w.flush()
}

/// Writes `timeseries.csv`.
pub fn write_timeseries(path: &Path, results: &[SphereResult]) -> io::Result<()> {
    let mut w = csv::Writer::from_path(path).map_err(csv_err)?;
    w.write_record([
        "sphere_id",
        "time_s",
        "depth_m",
        "velocity_m_s",
        "velocity_analytic_m_s",
        "depth_analytic_m",
    ])
    .map_err(csv_err)?;
    for r in results {
        for s in &r.samples {
            w.write_record([
                r.case.id.clone(),
                num(s.time_s),
                num(s.depth_m),
                num(s.velocity_m_s),
                opt(s.velocity_analytic_m_s),
                opt(s.depth_analytic_m),
            ])
            .map_err(csv_err)?;
        }
    }
    w.flush()
}

/// Writes `probes.csv` (velocity at the probe times).
pub fn write_probes(path: &Path, results: &[SphereResult]) -> io::Result<()> {
    let mut w = csv::Writer::from_path(path).map_err(csv_err)?;
    w.write_record([
        "sphere_id",
        "time_s",
        "velocity_m_s",
        "velocity_analytic_m_s",
    ])
    .map_err(csv_err)?;
    for r in results {
        for (t, v, a) in &r.probes {
            w.write_record([r.case.id.clone(), num(*t), num(*v), opt(*a)])
                .map_err(csv_err)?;
        }
    }
    w.flush()
}

/// Error statistics per suspension and overall (`all`), for spheres with a measurement.
pub fn metrics(results: &[SphereResult]) -> Vec<ErrorStats> {
    let mut groups: BTreeMap<u32, Vec<f64>> = BTreeMap::new();
    let mut all = Vec::new();
    for r in results {
        if let Some(e) = rel_error(r) {
            groups
                .entry(r.case.spec.suspension.unwrap_or(0))
                .or_default()
                .push(e);
            all.push(e);
        }
    }
    let mut out: Vec<ErrorStats> = groups
        .into_iter()
        .map(|(k, v)| ErrorStats::of(k.to_string(), &v))
        .collect();
    if !all.is_empty() {
        out.push(ErrorStats::of("all", &all));
    }
    out
}

/// Writes `metrics.csv`.
pub fn write_metrics(path: &Path, stats: &[ErrorStats]) -> io::Result<()> {
    let mut w = csv::Writer::from_path(path).map_err(csv_err)?;
    w.write_record(ErrorStats::HEADER).map_err(csv_err)?;
    for s in stats {
        w.write_record(s.row()).map_err(csv_err)?;
    }
    w.flush()
}

/// Terminal velocity against sphere density, one colour per diameter: measured (hollow) and
/// simulated (filled), like f-EDEM Fig. 11.
pub fn write_chart(path: &Path, title: &str, results: &[SphereResult]) -> Result<(), String> {
    type Points = Vec<(f64, f64)>;
    let mut by_d: BTreeMap<u64, (Points, Points)> = BTreeMap::new();
    for r in results {
        let key = (r.case.spec.diameter_m * 1e6).round() as u64;
        let e = by_d.entry(key).or_default();
        if let Some(m) = r.case.spec.v_measured_m_s {
            e.0.push((r.case.spec.density_kg_m3, m));
        }
        e.1.push((r.case.spec.density_kg_m3, r.v_simulated_m_s));
    }
    let mut series = Vec::new();
    for (i, (d_um, (meas, mut sim))) in by_d.into_iter().enumerate() {
        sim.sort_by(|a, b| a.0.total_cmp(&b.0));
        let d_mm = d_um as f64 / 1000.0;
        if !meas.is_empty() {
            series.push(Series {
                label: format!("d = {d_mm} mm, measured"),
                points: meas,
                colour: i,
                filled: false,
                line: false,
            });
        }
        series.push(Series {
            label: format!("d = {d_mm} mm, simulated"),
            points: sim,
            colour: i,
            filled: true,
            line: true,
        });
    }
    scatter_svg(
        path,
        title,
        "sphere density (kg/m³)",
        "terminal velocity (m/s)",
        Scale::Linear,
        Scale::Linear,
        &series,
    )
}
