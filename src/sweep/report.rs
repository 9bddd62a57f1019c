//! The outputs of a finished sweep: `sweep.csv`, the charts `quantity_vs_dt.svg` and
//! `speed_accuracy.svg`, `recommended_dt.csv`, and the console table.

use super::analysis::{recommended_dt, summarise, CaseSummary, RAYLEIGH_FRACTION};
use super::table::{write_rows, Row};
use crate::dynamics::Integrator;
use crate::error::Error;
use crate::io::chart::{scatter_svg, Scale, Series};
use crate::io::{num, write_atomic};
use std::collections::BTreeMap;
use std::io;
use std::path::Path;

/// What the report needs besides the rows.
#[derive(Clone, Debug)]
pub struct Context<'a> {
    /// Chart title and console heading (the scenario name, or `sweep`).
    pub title: &'a str,
    /// Tolerance of the recommended dt (relative error against the finest stable dt).
    pub tol: f64,
    /// Rayleigh time of the scenario's first elastic sphere, s, if any.
    pub rayleigh_time_s: Option<f64>,
    /// Print nothing.
    pub quiet: bool,
}

/// Writes every output of finished `rows` (see [`super::table::finish`]) into `dir`.
pub fn write_results(dir: &Path, rows: &[Row], cx: &Context) -> Result<(), Error> {
    let io_err = |file: &str| {
        let path = dir.join(file);
        move |e: io::Error| Error::Io(path, e)
    };
    write_rows(&dir.join("sweep.csv"), rows).map_err(io_err("sweep.csv"))?;
    let sums = summarise(rows);
    charts(dir, cx.title, &sums)?;
    if !cx.quiet {
        print_table(cx.title, &sums);
    }
    let recommended: Vec<(Integrator, Option<f64>)> = Integrator::ALL
        .into_iter()
        .filter(|i| sums.iter().any(|s| s.integrator == *i))
        .map(|i| (i, recommended_dt(&sums, i, cx.tol)))
        .collect();
    let csv = recommended_csv(&recommended, cx).map_err(io_err("recommended_dt.csv"))?;
    write_atomic(&dir.join("recommended_dt.csv"), &csv).map_err(io_err("recommended_dt.csv"))?;
    if !cx.quiet {
        print_recommended(&recommended, cx);
    }
    Ok(())
}

/// `recommended_dt.csv`: integrator, recommended dt (empty if none in the grid), tol, Rayleigh
/// time and its 20 % rule.
fn recommended_csv(rec: &[(Integrator, Option<f64>)], cx: &Context) -> io::Result<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "integrator",
        "recommended_dt_s",
        "tol",
        "rayleigh_time_s",
        "rayleigh_20pct_dt_s",
    ])?;
    for (integ, dt) in rec {
        w.write_record([
            integ.name().to_string(),
            dt.map(num).unwrap_or_default(),
            num(cx.tol),
            cx.rayleigh_time_s.map(num).unwrap_or_default(),
            cx.rayleigh_time_s
                .map(|r| num(RAYLEIGH_FRACTION * r))
                .unwrap_or_default(),
        ])?;
    }
    w.into_inner().map_err(|e| io::Error::other(e.to_string()))
}

fn print_table(title: &str, sums: &[CaseSummary]) {
    println!("{title}: {} cases", sums.len());
    println!(
        "  {:<12} {:>10} {:>9} {:>10} {:>9}  max |error vs finest| per quantity",
        "integrator", "dt_s", "status", "wall_s", "steps"
    );
    for s in sums {
        let errs: Vec<String> = s
            .errors
            .iter()
            .map(|(q, (f, _))| format!("{q}={f:.1e}"))
            .collect();
        println!(
            "  {:<12} {:>10.1e} {:>9} {:>10.4} {:>9}  {}",
            s.integrator.name(),
            s.dt_s,
            if s.stable { "stable" } else { "UNSTABLE" },
            s.wall_time_s,
            s.steps,
            errs.join(" ")
        );
    }
}

fn print_recommended(rec: &[(Integrator, Option<f64>)], cx: &Context) {
    for (integ, dt) in rec {
        let r = dt
            .map(|d| format!("{d:.1e} s"))
            .unwrap_or_else(|| "none in the grid".into());
        print!(
            "  recommended dt ({}, error vs finest < {}): {r}",
            integ.name(),
            cx.tol
        );
        if let Some(tr) = cx.rayleigh_time_s {
            print!(
                "   [Rayleigh time {tr:.3e} s; 20 % rule {:.3e} s]",
                RAYLEIGH_FRACTION * tr
            );
        }
        println!();
    }
}

/// Draws `quantity_vs_dt.svg` (max error against the finest dt, per quantity and integrator,
/// against dt) and `speed_accuracy.svg` (worst error against wall time, one line per integrator).
pub fn charts(dir: &Path, title: &str, summaries: &[CaseSummary]) -> Result<(), Error> {
    // Keyed by name, as the charts always were: series in alphabetical order.
    let mut by_q: BTreeMap<(&str, String), Vec<(f64, f64)>> = BTreeMap::new();
    let mut speed: BTreeMap<&str, Vec<(f64, f64)>> = BTreeMap::new();
    let floor = 1e-16;
    for s in summaries.iter().filter(|s| s.stable) {
        let mut worst: f64 = 0.0;
        for (q, (fin, re)) in &s.errors {
            by_q.entry((s.integrator.name(), q.clone()))
                .or_default()
                .push((s.dt_s, fin.max(floor)));
            let e = if re.is_finite() { *re } else { *fin };
            worst = worst.max(e);
        }
        speed
            .entry(s.integrator.name())
            .or_default()
            .push((s.wall_time_s.max(1e-6), worst.max(floor)));
    }
    let series: Vec<Series> = by_q
        .into_iter()
        .enumerate()
        .map(|(i, ((integ, q), pts))| Series::sorted_line(format!("{integ}: {q}"), pts, i))
        .collect();
    let chart_err = |file: &str| {
        let path = dir.join(file);
        move |e: io::Error| Error::Io(path, e)
    };
    scatter_svg(
        &dir.join("quantity_vs_dt.svg"),
        &format!("{title}: max relative error vs finest stable dt"),
        "dt (s)",
        "max |relative error| over bodies",
        Scale::Log,
        Scale::Log,
        &series,
    )
    .map_err(chart_err("quantity_vs_dt.svg"))?;
    let series: Vec<Series> = speed
        .into_iter()
        .enumerate()
        .map(|(i, (integ, pts))| Series::sorted_line(integ.to_string(), pts, i))
        .collect();
    scatter_svg(
        &dir.join("speed_accuracy.svg"),
        &format!("{title}: accuracy against cost"),
        "wall time (s)",
        "worst |relative error| (vs analytic/force balance, else vs finest)",
        Scale::Log,
        Scale::Log,
        &series,
    )
    .map_err(chart_err("speed_accuracy.svg"))
}
