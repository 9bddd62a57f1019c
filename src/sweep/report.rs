//! The outputs of a finished sweep, in memory ([`Outputs`]): `sweep.csv`, the charts
//! `quantity_vs_dt.svg`, `speed_accuracy.svg` and (funnel pours) `counts_vs_dt.svg`,
//! `recommended_dt.csv`, and the console table.

use super::analysis::{recommended_dt, summarise, verified, CaseSummary, RAYLEIGH_FRACTION};
use super::table::{integrator_rank, to_csv, Row, Status};
use crate::dynamics::Integrator;
use crate::error::Error;
use crate::io::chart::{Chart, Marker, Scale, Series};
use crate::io::fmt::num;
use crate::io::fmt::{g, short, sig};
use crate::io::{Outputs, Table};
use std::collections::BTreeMap;
use std::io;
use std::path::PathBuf;

/// What the report needs besides the rows.
#[derive(Clone, Debug)]
pub struct Context<'a> {
    /// Chart title and console heading (the scenario name, or `sweep`).
    pub title: &'a str,
    /// Tolerance of the recommended dt (relative error against the finest stable dt).
    pub tol: f64,
    /// Rayleigh time of the scenario's first elastic sphere, s, if any.
    pub rayleigh_time_s: Option<f64>,
}

/// The outputs of finished rows, in memory: what [`results`] makes.
#[derive(Clone, Debug)]
pub struct Report {
    /// `sweep.csv`, `recommended_dt.csv` and the charts (no report page).
    pub outputs: Outputs,
    /// The recommended dt of every integrator swept, in [`Integrator::ALL`] order.
    pub recommended: Vec<Recommended>,
    /// The console lines: the table of cases, then one line per recommended dt.
    pub lines: Vec<String>,
}

/// Every output of finished `rows` (see [`super::table::finish`]): `sweep.csv`, the charts,
/// `recommended_dt.csv`, and the console lines.
pub fn results(rows: &[Row], cx: &Context) -> Result<Report, Error> {
    let io_err = |file: &'static str| move |e: io::Error| Error::Io(PathBuf::from(file), e);
    let mut outputs = Outputs::new();
    outputs.table(
        Table::from_csv("sweep.csv", &to_csv(rows).map_err(io_err("sweep.csv"))?)
            .map_err(io_err("sweep.csv"))?,
    );
    let sums = summarise(rows);
    charts(&mut outputs, cx.title, &sums)?;
    counts_chart(&mut outputs, cx.title, rows)?;
    let mut lines = table_lines(cx.title, cx.tol, &sums);
    let recommended: Vec<Recommended> = Integrator::ALL
        .into_iter()
        .filter(|i| sums.iter().any(|s| s.integrator == *i))
        .map(|i| {
            let dt_s = recommended_dt(&sums, i, cx.tol);
            Recommended {
                integrator: i,
                dt_s,
                verified: dt_s.is_some_and(|d| verified(&sums, i, d)),
            }
        })
        .collect();
    outputs.table(recommended_table(&recommended, cx));
    lines.extend(recommended.iter().map(|r| recommended_line(r, cx)));
    Ok(Report {
        outputs,
        recommended,
        lines,
    })
}

/// The recommended dt of one integrator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Recommended {
    /// Integrator.
    pub integrator: Integrator,
    /// Largest dt of the grid whose error against the finest stable dt is within the tolerance
    /// at every finer dt too, s (None: none in the grid).
    pub dt_s: Option<f64>,
    /// A finer stable dt of the grid confirms it; false when it is the finest stable dt tried.
    pub verified: bool,
}

/// `recommended_dt.csv`: integrator, recommended dt (empty if none in the grid), tol, Rayleigh
/// time and its 20 % rule.
fn recommended_table(rec: &[Recommended], cx: &Context) -> Table {
    let rows = rec
        .iter()
        .map(|r| {
            vec![
                r.integrator.name().to_string(),
                r.dt_s.map(num).unwrap_or_default(),
                num(cx.tol),
                cx.rayleigh_time_s.map(num).unwrap_or_default(),
                cx.rayleigh_time_s
                    .map(|t| num(RAYLEIGH_FRACTION * t))
                    .unwrap_or_default(),
                r.verified.to_string(),
            ]
        })
        .collect();
    Table::with_rows(
        "recommended_dt.csv",
        [
            "integrator",
            "recommended_dt_s",
            "tol",
            "rayleigh_time_s",
            "rayleigh_20pct_dt_s",
            "verified",
        ],
        rows,
    )
}

/// The console table of a sweep, one line per case, numbers as [`crate::io::fmt`] writes them
/// (dt as given, errors with 2 significant digits). An unstable case shows `unstable` and its
/// reason instead of errors (its values are NaN in `sweep.csv`).
pub fn table_lines(title: &str, tol: f64, sums: &[CaseSummary]) -> Vec<String> {
    let mut lines = vec![
        format!("{title}: {} cases", sums.len()),
        format!(
            "  {:<12} {:>10} {:>10} {:>10} {:>9}  max |error vs finest| per quantity",
            "integrator", "dt_s", "status", "wall_s", "steps"
        ),
    ];
    for s in sums {
        let errs = if s.stable {
            s.errors
                .iter()
                .map(|(q, (f, _))| format!("{q}={}%", sig(100.0 * *f, 2)))
                .collect::<Vec<_>>()
                .join(" ")
        } else {
            // The reason is the engine's report, which starts with "unstable:".
            s.reason.clone()
        };
        lines.push(format!(
            "  {:<12} {:>10} {:>10} {:>10} {:>9}  {}",
            s.integrator.name(),
            short(s.dt_s),
            status_label(s, tol),
            g(s.wall_time_s),
            s.steps,
            errs
        ));
    }
    lines
}

/// The status a person reads: `UNSTABLE` (the run blew up), `inaccurate` (bounded, but some
/// quantity is further than `tol` from the finest dt: issue 13 found `explicit 3.0e-2` labelled
/// stable with a 32 000 % error), `reference` (the finest stable dt, every error 0 by
/// definition) or `ok` (within `tol`).
fn status_label(s: &CaseSummary, tol: f64) -> &'static str {
    if !s.stable {
        return "UNSTABLE";
    }
    let worst = s.errors.values().map(|(f, _)| *f).fold(0.0, f64::max);
    if s.errors.values().any(|(f, _)| f.is_nan()) || worst > tol {
        "inaccurate"
    } else if worst == 0.0 {
        "reference"
    } else {
        "ok"
    }
}

/// The console line of one recommended dt; `unverified` when it is the finest stable dt tried.
pub fn recommended_line(r: &Recommended, cx: &Context) -> String {
    let mut line = format!(
        "  recommended dt ({}, error vs finest < {}): {}",
        r.integrator.name(),
        cx.tol,
        match r.dt_s {
            None => "none in the grid".to_string(),
            Some(d) if r.verified => format!("{} s", short(d)),
            Some(d) => format!(
                "{} s, unverified: it is the finest stable dt tried (the reference of every \
                 error); add a finer dt to confirm it",
                short(d)
            ),
        }
    );
    if let Some(tr) = cx.rayleigh_time_s {
        line.push_str(&format!(
            "   [Rayleigh time {} s; 20 % rule {} s]",
            g(tr),
            g(RAYLEIGH_FRACTION * tr)
        ));
    }
    line
}

/// The caveat of a recommended dt, as a warning of the sweep: none found in the grid, or one
/// that no finer stable dt confirms (the finest stable dt tried); None when it is verified.
pub fn caveat(r: &Recommended, cx: &Context) -> Option<String> {
    let name = r.integrator.name();
    match r.dt_s {
        None => Some(format!(
            "{name}: no recommended dt in the grid (none within error vs finest < {}): add \
             finer time steps",
            cx.tol
        )),
        Some(d) if !r.verified => Some(format!(
            "{name}: the recommended dt {} s is unverified: it is the finest stable dt tried \
             (the reference of every error); add a finer dt to confirm it",
            short(d)
        )),
        Some(_) => None,
    }
}

/// Draws `quantity_vs_dt.svg` (max error against the finest dt, per quantity and integrator,
/// against dt: one colour per integrator, one marker shape per quantity) and `speed_accuracy.svg`
/// (worst error against wall time, one line per integrator) into `out`. Errors of exactly zero
/// are drawn at 1e-16 (the log axis has no zero).
pub fn charts(out: &mut Outputs, title: &str, summaries: &[CaseSummary]) -> Result<(), Error> {
    // Keyed by integrator order, then quantity name.
    let mut by_q: BTreeMap<(usize, String), Vec<(f64, f64)>> = BTreeMap::new();
    let mut speed: BTreeMap<usize, Vec<(f64, f64)>> = BTreeMap::new();
    let floor = 1e-16;
    for s in summaries.iter().filter(|s| s.stable) {
        let rank = integrator_rank(s.integrator);
        let mut worst: f64 = 0.0;
        for (q, (fin, re)) in &s.errors {
            by_q.entry((rank, q.clone()))
                .or_default()
                .push((s.dt_s, fin.max(floor)));
            let e = if re.is_finite() { *re } else { *fin };
            worst = worst.max(e);
        }
        speed
            .entry(rank)
            .or_default()
            .push((s.wall_time_s.max(1e-6), worst.max(floor)));
    }
    let quantities: Vec<String> = by_q
        .keys()
        .map(|k| k.1.clone())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    let name = |rank: usize| Integrator::ALL.get(rank).map_or("?", |i| i.name());
    let chart_err = |file: &'static str| move |e: io::Error| Error::Io(PathBuf::from(file), e);
    let mut chart = Chart::new(format!(
        "{title}: max relative error against the finest stable dt"
    ))
    .x("time step dt (s)", Scale::Log)
    .y("max |relative error| over bodies (-)", Scale::Log);
    for ((rank, q), pts) in by_q {
        let shape = quantities.iter().position(|x| *x == q).unwrap_or(0);
        chart = chart.series_marked(
            Series::sorted_line(format!("{}: {q}", name(rank)), pts, rank),
            Marker::nth(shape),
        );
    }
    out.chart("quantity_vs_dt.svg", &chart)
        .map_err(chart_err("quantity_vs_dt.svg"))?;
    let speed = speed.into_iter().fold(
        Chart::new(format!("{title}: accuracy against cost"))
            .x("wall time (s)", Scale::Log)
            .y(
                "worst |relative error| vs analytic, force balance or finest dt (-)",
                Scale::Log,
            ),
        |c, (rank, pts)| c.series(Series::sorted_line(name(rank).to_string(), pts, rank)),
    );
    out.chart("speed_accuracy.svg", &speed)
        .map_err(chart_err("speed_accuracy.svg"))
}

/// Draws `counts_vs_dt.svg` into `out` when the rows hold ball counts (a funnel-pour sweep, like
/// f-EDEM Fig. 20): each count (`balls_*` quantities) against dt, one colour per integrator,
/// one shape per count. Returns false (nothing drawn) for other sweeps.
pub fn counts_chart(out: &mut Outputs, title: &str, rows: &[Row]) -> Result<bool, Error> {
    let mut by_q: BTreeMap<(usize, String), Vec<(f64, f64)>> = BTreeMap::new();
    for r in rows.iter().filter(|r| r.status == Status::Stable) {
        if r.quantity.starts_with("balls_") && r.value.is_finite() {
            by_q.entry((integrator_rank(r.integrator), r.quantity.clone()))
                .or_default()
                .push((r.dt_s, r.value));
        }
    }
    if by_q.is_empty() {
        return Ok(false);
    }
    let quantities: Vec<String> = by_q
        .keys()
        .map(|k| k.1.clone())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    let mut chart = Chart::new(format!("{title}: ball counts against time step"))
        .x("time step dt (s)", Scale::Log)
        .y("balls (count)", Scale::Linear);
    for ((rank, q), pts) in by_q {
        let shape = quantities.iter().position(|x| *x == q).unwrap_or(0);
        let integ = Integrator::ALL.get(rank).map_or("?", |i| i.name());
        chart = chart.series_marked(
            Series::sorted_line(
                format!("{integ}: {q}"),
                pts,
                rank * quantities.len() + shape,
            ),
            Marker::nth(shape),
        );
    }
    let name = "counts_vs_dt.svg";
    out.chart(name, &chart)
        .map_err(|e| Error::Io(PathBuf::from(name), e))?;
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case(integrator: Integrator, dt_s: f64, stable: bool, err: f64) -> CaseSummary {
        CaseSummary {
            integrator,
            dt_s,
            stable,
            wall_time_s: 0.1,
            steps: 10,
            errors: [("terminal_velocity_m_s".to_string(), (err, f64::NAN))].into(),
            reason: if stable {
                String::new()
            } else {
                "unstable: velocity oscillates with growing amplitude".into()
            },
        }
    }

    fn cx() -> Context<'static> {
        Context {
            title: "t",
            tol: 0.01,
            rayleigh_time_s: None,
        }
    }

    /// Issue 13: unstable rows printed an error of `0.0e0` (their values are NaN).
    #[test]
    fn an_unstable_case_shows_its_reason_not_an_error() {
        let sums = [
            case(Integrator::Explicit, 1e-2, false, 0.0),
            case(Integrator::Explicit, 1e-3, true, 0.0),
        ];
        let lines = table_lines("t", 0.01, &sums);
        assert!(lines[2].contains("UNSTABLE"), "{}", lines[2]);
        assert!(lines[2].contains("velocity oscillates"), "{}", lines[2]);
        assert!(
            !lines[2].contains("0.0e0") && !lines[2].contains("=0"),
            "{}",
            lines[2]
        );
        assert!(
            lines[3].ends_with("terminal_velocity_m_s=0%"),
            "{}",
            lines[3]
        );
        assert!(lines[3].contains(" 0.001 "), "dt as given: {}", lines[3]);
    }

    /// Issue 13: `explicit 3.0e-2` was labelled stable with a 32 000 % error. A bounded case
    /// beyond the tolerance reads `inaccurate`, its error in percent; the finest reads
    /// `reference`; one within the tolerance `ok`.
    #[test]
    fn a_bounded_case_far_from_the_finest_is_inaccurate() {
        let sums = [
            case(Integrator::Explicit, 3e-2, true, 320.0),
            case(Integrator::Explicit, 1e-3, true, 0.004),
            case(Integrator::Explicit, 1e-4, true, 0.0),
        ];
        let lines = table_lines("t", 0.01, &sums);
        assert!(lines[2].contains(" inaccurate "), "{}", lines[2]);
        assert!(lines[2].contains("=32000%"), "{}", lines[2]);
        assert!(lines[3].contains(" ok "), "{}", lines[3]);
        assert!(lines[3].contains("=0.40%"), "{}", lines[3]);
        assert!(lines[4].contains(" reference "), "{}", lines[4]);
    }

    /// Issue 13: the recommended dt was simply the finest dt tried, with nothing saying that no
    /// finer step confirms it.
    #[test]
    fn the_finest_stable_dt_is_recommended_as_unverified() {
        let sums = [
            case(Integrator::Explicit, 1e-2, false, 0.0),
            case(Integrator::Explicit, 1e-3, true, 0.0),
            case(Integrator::Exponential, 1e-2, true, 1e-4),
            case(Integrator::Exponential, 1e-3, true, 0.0),
        ];
        for (integ, dt, ok) in [
            (Integrator::Explicit, 1e-3, false),
            (Integrator::Exponential, 1e-2, true),
        ] {
            let d = recommended_dt(&sums, integ, 0.01);
            assert_eq!(d, Some(dt), "{integ:?}");
            let r = Recommended {
                integrator: integ,
                dt_s: d,
                verified: verified(&sums, integ, dt),
            };
            assert_eq!(r.verified, ok, "{integ:?}");
            let line = recommended_line(&r, &cx());
            assert_eq!(line.contains("unverified"), !ok, "{line}");
        }
    }
}
