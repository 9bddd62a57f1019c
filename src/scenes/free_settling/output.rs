//! Every table and chart of a free-settling or drop run ([`fill`] adds them to the run's
//! [`Outputs`]).
//!
//! - `kind = "free_settling"`: `summary.csv` (one row per sphere), `metrics.csv` and
//!   `terminal_velocity.svg` (like f-EDEM Fig. 11) when measurements exist; in a Bingham fluid
//!   `cd_re.csv` and `cd_re.svg` (C_d against Re′ with eq. 19, like f-EDEM Fig. 1);
//! - `kind = "drop"`: `summary.csv` with one row per sphere and fall height, and
//!   `settling_distance.svg` (settling distance against fall height, one series per diameter,
//!   like f-EDEM Fig. 16);
//! - both: `timeseries.csv` and `velocity.svg` (v(t), with the analytic Stokes curve under
//!   Stokes drag, like f-EDEM Figs. 5–6, and the measured v(t) of `[reference]`) when
//!   `record.timeseries`, with `gap.svg` when `[reference]` gives a measured gap and there is a
//!   container; `probes.csv` when probe times are set.
//!
//! A several-file run also gets the charts of [`combined_charts`] in `OUT/combined/`.
//!
//! `run.toml` is written by [`crate::run`](mod@crate::run) from the returned [`SceneReport`].

use super::charts;
use super::setup::uses_rapier;
use super::SphereResult;
use crate::error::Error;
use crate::io::chart::{Chart, Scale, Series};
use crate::io::fmt::{num, opt};
use crate::io::metrics::ErrorStats;
use crate::io::{Outputs, Table};
use crate::scenario::{Common, Entry, FreeSettlingSpec, Submergence};
use crate::scenes::{Prepared, SceneReport};
use std::collections::BTreeMap;
use std::io;

/// Adds the tables and charts of a free-settling or drop run to `out` and reports the run's
/// steps, bodies and (Rapier) engine settings. An interruption requested while the time series
/// is built ends it with an [`io::ErrorKind::Interrupted`] error.
pub fn fill(
    p: &Prepared,
    spec: &FreeSettlingSpec,
    results: &[SphereResult],
    out: &mut Outputs,
) -> Result<SceneReport, Error> {
    let s = &p.common;
    let io = |e: io::Error| Error::Io(p.path.clone(), e);
    let integ = s.time.integrator.name();
    if spec.entry == Entry::Drop {
        let sub = match s.submergence {
            Submergence::Full => "full",
            Submergence::Partial => "partial",
        };
        out.table(drop_summary_table(results, s.time.dt_s, integ, sub));
        let title = format!(
            "{}: settling distance against fall height ({sub} submergence)",
            s.name
        );
        out.chart("settling_distance.svg", &drop_chart(&title, results))
            .map_err(io)?;
    } else {
        let rows: Vec<Vec<String>> = results
            .iter()
            .map(|r| summary_row(r, s.time.dt_s, integ))
            .collect();
        out.table(summary_table(rows));
        let stats = metrics(results);
        if !stats.is_empty() {
            out.table(metrics_table(&stats));
            let title = format!(
                "{}: terminal velocity, measured (hollow) and simulated (filled)",
                s.name
            );
            out.chart("terminal_velocity.svg", &chart(&title, results))
                .map_err(io)?;
        }
        let cd_re = charts::cd_re_points(s, results);
        if !cd_re.is_empty() {
            out.table(charts::cd_re_table(&cd_re));
            let title = format!(
                "{}: drag coefficient against Bingham Reynolds number",
                s.name
            );
            out.chart("cd_re.svg", &charts::cd_re_chart(&title, &cd_re))
                .map_err(io)?;
        }
    }
    if s.record.timeseries {
        let height = spec.container.as_ref().map(|c| c.height_m);
        out.table(timeseries_table(results, height).map_err(io)?);
        let title = format!("{}: settling velocity against time", s.name);
        let v0 = spec.release.velocity_m_s;
        let exact = s.transient.as_ref().filter(|t| t.any()).map(|t| {
            if t.history == crate::scenario::History::Basset {
                "exact with added mass and the Basset force (Boussinesq–Basset closed form)"
            } else {
                "exact Stokes solution with the added mass"
            }
        });
        let measured = p.reference.as_ref();
        if let Some(c) = charts::velocity_chart(&title, results, v0, exact, measured) {
            out.chart("velocity.svg", &c).map_err(io)?;
        }
        if let (Some(h), Some(m)) = (height, measured) {
            let title = format!("{}: gap between sphere and bottom against time", s.name);
            if let Some(c) = charts::gap_chart(&title, results, h, m) {
                out.chart("gap.svg", &c).map_err(io)?;
            }
        }
    }
    if results.iter().any(|r| !r.probes.is_empty()) {
        out.table(probes_table(results));
    }
    let engine_settings = uses_rapier(s).then(|| {
        let d_min = p
            .spheres
            .iter()
            .map(|c| c.spec.diameter_m)
            .fold(f64::INFINITY, f64::min);
        let v_max = results
            .iter()
            .map(|r| r.v_force_balance_m_s.abs())
            .fold(0.0, f64::max);
        crate::engine::EngineSettings::for_scene(d_min, 2.0 * v_max)
    });
    Ok(SceneReport {
        warnings: warnings(p, results),
        steps: results.iter().map(|r| r.steps).sum(),
        bodies: results.len(),
        engine_settings,
        lines: Vec::new(),
        interrupted: false,
        reached_s: None,
    })
}

/// The validity warnings of the run: its drag law checked at every sphere's largest speed in the
/// fluid: the simulated or force-balance terminal velocity (a drop also its entry speed).
pub fn warnings(p: &Prepared, results: &[SphereResult]) -> Vec<String> {
    let spheres: Vec<crate::scenes::validity::SphereAt> = results
        .iter()
        .map(|r| crate::scenes::validity::SphereAt {
            id: r.case.id.clone(),
            diameter_m: r.case.spec.diameter_m,
            density_kg_m3: r.case.spec.density_kg_m3,
            speed_m_s: r
                .v_simulated_m_s
                .abs()
                .max(r.v_force_balance_m_s.abs())
                .max(r.entry_velocity_m_s.unwrap_or(0.0).abs()),
        })
        .collect();
    crate::scenes::validity::drag_warnings(p, &spheres)
}

/// Header of `summary.csv` (`reynolds`: ρ_f |v| d / η at the simulated terminal velocity, for a
/// Newtonian drag law; empty for Bingham drag, whose number is `re_bingham`).
pub const SUMMARY_HEADER: [&str; 24] = [
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
    "reynolds",
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
        opt(r.reynolds),
    ]
}

/// `summary.csv` of free settling: the rows of [`summary_row`] under [`SUMMARY_HEADER`].
pub fn summary_table(rows: Vec<Vec<String>>) -> Table {
    Table::with_rows("summary.csv", SUMMARY_HEADER, rows)
}

/// `timeseries.csv`; stops with an [`io::ErrorKind::Interrupted`] error when an interruption
/// is requested (checked before each sphere's rows). `height_m`: the container's fluid height,
/// for the gap between the sphere and the bottom (`gap_to_bottom_m`, empty without a
/// container).
pub fn timeseries_table(results: &[SphereResult], height_m: Option<f64>) -> io::Result<Table> {
    let mut t = Table::new(
        "timeseries.csv",
        [
            "sphere_id",
            "time_s",
            "depth_m",
            "velocity_m_s",
            "velocity_analytic_m_s",
            "depth_analytic_m",
            "gap_to_bottom_m",
        ],
    );
    for r in results {
        if crate::interrupt::requested() {
            return Err(io::Error::new(
                io::ErrorKind::Interrupted,
                "interrupted while writing timeseries.csv",
            ));
        }
        for s in &r.samples {
            t.push(vec![
                r.case.id.clone(),
                num(s.time_s),
                num(s.depth_m),
                num(s.velocity_m_s),
                opt(s.velocity_analytic_m_s),
                opt(s.depth_analytic_m),
                opt(height_m.map(|h| h - s.depth_m - 0.5 * r.case.spec.diameter_m)),
            ]);
        }
    }
    Ok(t)
}

/// `probes.csv` (velocity at the probe times).
pub fn probes_table(results: &[SphereResult]) -> Table {
    let mut t = Table::new(
        "probes.csv",
        [
            "sphere_id",
            "time_s",
            "velocity_m_s",
            "velocity_analytic_m_s",
        ],
    );
    for r in results {
        for (time, v, a) in &r.probes {
            t.push(vec![r.case.id.clone(), num(*time), num(*v), opt(*a)]);
        }
    }
    t
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

/// `metrics.csv`: one row per group of [`metrics`].
pub fn metrics_table(stats: &[ErrorStats]) -> Table {
    Table::with_rows(
        "metrics.csv",
        ErrorStats::HEADER,
        stats.iter().map(|s| s.row()).collect(),
    )
}

/// The tables and charts of a several-file run (`OUT/combined/`) from each file's scenario
/// and results, added to `out`: `parity.svg` and `terminal_velocity.svg` when spheres are
/// measured, and `cd_re.csv` with `cd_re.svg` over every Bingham run (see [`charts`]).
pub fn combined_charts<'a>(
    out: &mut Outputs,
    runs: impl IntoIterator<Item = (&'a Common, &'a [SphereResult])>,
) -> io::Result<()> {
    let runs: Vec<(&Common, &[SphereResult])> = runs.into_iter().collect();
    let all: Vec<&SphereResult> = runs.iter().flat_map(|r| r.1.iter()).collect();
    let n = runs.len();
    let title = format!("{n} scenarios: simulated against measured terminal velocity");
    if let Some(c) = charts::parity_chart(&title, &all) {
        out.chart("parity.svg", &c)?;
    }
    let title =
        format!("{n} scenarios: terminal velocity, measured (hollow) and simulated (filled)");
    if let Some(panels) = charts::combined_terminal_panels(&all) {
        out.grid_chart("terminal_velocity.svg", &title, &panels, 2)?;
    }
    let cd_re: Vec<charts::CdRe> = runs
        .iter()
        .flat_map(|(s, r)| charts::cd_re_points(s, r))
        .collect();
    if !cd_re.is_empty() {
        out.table(charts::cd_re_table(&cd_re));
        let title = format!("{n} scenarios: drag coefficient against Bingham Reynolds number");
        out.chart("cd_re.svg", &charts::cd_re_chart(&title, &cd_re))?;
    }
    Ok(())
}

/// Terminal velocity against sphere density, one colour per diameter: measured (hollow) and
/// simulated (filled), like f-EDEM Fig. 11 (`terminal_velocity.svg`).
pub fn chart(title: &str, results: &[SphereResult]) -> Chart {
    let all: Vec<&SphereResult> = results.iter().collect();
    charts::terminal_velocity_chart(title, &all)
}

/// Header of a drop `summary.csv`. `settling_distance_m` is the depth of the ball's lowest point
/// below the free surface once it has stopped (or at the end of the run); `centre_depth_m` the
/// depth of its centre.
pub const DROP_HEADER: [&str; 12] = [
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

/// The drop `summary.csv` (`kind = "drop"`).
pub fn drop_summary_table(
    results: &[SphereResult],
    dt_s: f64,
    integrator: &str,
    submergence: &str,
) -> Table {
    let mut t = Table::new("summary.csv", DROP_HEADER);
    for r in results {
        let d = r.case.spec.diameter_m;
        t.push(vec![
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
        ]);
    }
    t
}

/// `settling_distance.svg`: settling distance against fall height, one series per diameter
/// (like f-EDEM Fig. 16).
pub fn drop_chart(title: &str, results: &[SphereResult]) -> Chart {
    let mut by_d: BTreeMap<u64, Vec<(f64, f64)>> = BTreeMap::new();
    for r in results {
        let key = (r.case.spec.diameter_m * 1e6).round() as u64;
        by_d.entry(key).or_default().push((
            r.case.fall_height_m.unwrap_or(0.0) * 1e3,
            r.final_bottom_depth_m * 1e3,
        ));
    }
    by_d.into_iter().enumerate().fold(
        Chart::new(title).x("fall height (mm)", Scale::Linear).y(
            "settling distance, ball bottom below surface (mm)",
            Scale::Linear,
        ),
        |c, (i, (d_um, pts))| {
            c.series(Series::sorted_line(
                format!("d = {} mm", d_um as f64 / 1000.0),
                pts,
                i,
            ))
        },
    )
}
