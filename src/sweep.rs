//! Time-step sensitivity sweeps (`settle sweep`): every (integrator, dt) of a grid runs the
//! scenario; each measured quantity is compared with its analytic or force-balance reference
//! where one exists and with the finest stable dt of the same integrator. Cases run in
//! parallel; `--shard I/N` runs a slice of the grid so a cluster job array can share it, and
//! `--merge` joins the parts (see README, "Sweeps on a cluster").

use crate::dynamics::Integrator;
use crate::output::chart::{scatter_svg, Scale, Series};
use crate::output::num;
use crate::run::Prepared;
use crate::scenes::free_settling::{self, RunOptions, SphereResult};
use std::collections::BTreeMap;
use std::io;
use std::path::Path;
use std::time::Instant;

/// One case of the sweep grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Case {
    /// Integrator.
    pub integrator: Integrator,
    /// Time step, s.
    pub dt_s: f64,
}

/// The grid: every integrator × every dt, integrators outermost, dt descending.
pub fn grid(integrators: &[Integrator], dts: &[f64]) -> Vec<Case> {
    let mut dts = dts.to_vec();
    dts.sort_by(|a, b| b.total_cmp(a));
    dts.dedup();
    integrators
        .iter()
        .flat_map(|&i| {
            dts.iter().map(move |&dt_s| Case {
                integrator: i,
                dt_s,
            })
        })
        .collect()
}

/// `--dt-range LO:HI --per-decade N`: log-spaced steps from HI down to LO inclusive.
pub fn dt_range(lo: f64, hi: f64, per_decade: u32) -> Vec<f64> {
    let n = ((hi / lo).log10() * per_decade as f64).round() as i64;
    (0..=n)
        .map(|k| {
            let x = hi * 10f64.powf(-(k as f64) / per_decade as f64);
            // Round to 12 significant digits so 1e-3 prints as 1e-3.
            let e = x.log10().floor();
            (x / 10f64.powf(e) * 1e11).round() / 1e11 * 10f64.powf(e)
        })
        .collect()
}

/// Slice `shard` (1-based) of `of` slices: cases whose index ≡ shard − 1 (mod of).
pub fn shard(cases: &[Case], shard: usize, of: usize) -> Vec<Case> {
    cases
        .iter()
        .enumerate()
        .filter(|(i, _)| i % of == shard - 1)
        .map(|(_, c)| *c)
        .collect()
}

/// One row of a sweep: a quantity of a body in a case.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Integrator name.
    pub integrator: String,
    /// Time step, s.
    pub dt_s: f64,
    /// `stable` or `unstable`.
    pub status: String,
    /// Why unstable (empty if stable).
    pub reason: String,
    /// Wall time of the whole case, s.
    pub wall_time_s: f64,
    /// Steps of this body.
    pub steps: u64,
    /// Body identifier.
    pub body: String,
    /// Quantity name (`terminal_velocity_m_s`, `velocity_at_0.01s_m_s`).
    pub quantity: String,
    /// Value (NaN if unstable).
    pub value: f64,
    /// Analytic or force-balance reference (NaN if none).
    pub reference: f64,
    /// Relative error against the reference.
    pub error_vs_reference: f64,
    /// Relative error against the finest stable dt of the same integrator (filled by [`finish`]).
    pub error_vs_finest: f64,
}

/// Column names of `sweep.csv`.
pub const HEADER: [&str; 12] = [
    "integrator",
    "dt_s",
    "status",
    "reason",
    "wall_time_s",
    "steps",
    "body",
    "quantity",
    "value",
    "reference",
    "error_vs_reference",
    "error_vs_finest",
];

fn rel(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        if a == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    } else {
        (a - b) / b
    }
}

/// The measured quantities of one body: (name, value, reference).
fn quantities(r: &SphereResult) -> Vec<(String, f64, f64)> {
    if r.case.fall_height_m.is_some() {
        return vec![(
            "settling_distance_m".to_string(),
            r.final_bottom_depth_m,
            f64::NAN,
        )];
    }
    let mut q = vec![(
        "terminal_velocity_m_s".to_string(),
        r.v_simulated_m_s,
        r.v_force_balance_m_s,
    )];
    for (t, v, a) in &r.probes {
        q.push((format!("velocity_at_{t}s_m_s"), *v, a.unwrap_or(f64::NAN)));
    }
    q
}

/// Runs the cases (in parallel) and returns their rows, without `error_vs_finest`.
pub fn run_cases(p: &Prepared, cases: &[Case]) -> Vec<Row> {
    run_cases_with(p, cases, &|| {})
}

/// As [`run_cases`], calling `done` after each case (for a progress bar).
pub fn run_cases_with(p: &Prepared, cases: &[Case], done: &(dyn Fn() + Sync)) -> Vec<Row> {
    use rayon::prelude::*;
    // Names of quantities and bodies for unstable rows, from the scenario.
    let probe_names: Vec<String> = p
        .scenario
        .measure
        .as_ref()
        .map(|m| {
            m.velocity_at_s
                .iter()
                .map(|t| format!("velocity_at_{t}s_m_s"))
                .collect()
        })
        .unwrap_or_default();
    cases
        .par_iter()
        .map(|c| {
            let opts = RunOptions {
                dt_s: c.dt_s,
                integrator: c.integrator,
                timeseries: false,
            };
            if p.scenario.kind == crate::scenario::Kind::FunnelPour {
                let rows = funnel_case(p, c);
                done();
                return rows;
            }
            let t0 = Instant::now();
            let res = free_settling::run(&p.scenario, &p.spheres, opts);
            let wall = t0.elapsed().as_secs_f64();
            done();
            let base = |status: &str, reason: String| Row {
                integrator: c.integrator.name().to_string(),
                dt_s: c.dt_s,
                status: status.to_string(),
                reason,
                wall_time_s: wall,
                steps: 0,
                body: String::new(),
                quantity: String::new(),
                value: f64::NAN,
                reference: f64::NAN,
                error_vs_reference: f64::NAN,
                error_vs_finest: f64::NAN,
            };
            match res {
                Ok(results) => results
                    .iter()
                    .flat_map(|r| {
                        quantities(r).into_iter().map(|(q, v, refv)| Row {
                            steps: r.steps,
                            body: r.case.id.clone(),
                            quantity: q,
                            value: v,
                            reference: refv,
                            error_vs_reference: rel(v, refv),
                            ..base("stable", String::new())
                        })
                    })
                    .collect::<Vec<_>>(),
                Err(u) => p
                    .spheres
                    .iter()
                    .flat_map(|s| {
                        let first = if s.fall_height_m.is_some() {
                            "settling_distance_m"
                        } else {
                            "terminal_velocity_m_s"
                        };
                        std::iter::once(first.to_string())
                            .chain(
                                probe_names
                                    .iter()
                                    .filter(|_| s.fall_height_m.is_none())
                                    .cloned(),
                            )
                            .map(|q| Row {
                                body: s.id.clone(),
                                quantity: q,
                                ..base("unstable", u.to_string())
                            })
                    })
                    .collect(),
            }
        })
        .flatten()
        .collect()
}

/// One case of a funnel-pour sweep (f-EDEM Fig. 20): the first repeat (seed `repeats.seed`) at
/// the case's dt and integrator; quantities: balls in the paste and in the domain at
/// `funnel.count_time_s`, balls lost through a wall, and the lowest and highest final ball
/// centre. No reference value: errors are against the finest stable dt only.
fn funnel_case(p: &Prepared, c: &Case) -> Vec<Row> {
    let mut q = p.clone();
    q.scenario.time.dt_s = c.dt_s;
    q.scenario.time.integrator = c.integrator;
    let seed = q.scenario.repeats.as_ref().map(|r| r.seed).unwrap_or(0);
    let t0 = Instant::now();
    let res = crate::scenes::funnel::run_repeat(&q, 0, seed);
    let wall = t0.elapsed().as_secs_f64();
    let row = |status: &str, reason: String, steps: u64, quantity: &str, value: f64| Row {
        integrator: c.integrator.name().to_string(),
        dt_s: c.dt_s,
        status: status.to_string(),
        reason,
        wall_time_s: wall,
        steps,
        body: "all".to_string(),
        quantity: quantity.to_string(),
        value,
        reference: f64::NAN,
        error_vs_reference: f64::NAN,
        error_vs_finest: f64::NAN,
    };
    const QUANTITIES: [&str; 5] = [
        "balls_in_paste_at_count",
        "balls_in_domain_at_count",
        "balls_lost",
        "z_min_m",
        "z_max_m",
    ];
    match res {
        Ok(r) => {
            let census = r.census_at_count.unwrap_or_else(|| r.census());
            let (z0, z1) = r.z_range_m().unwrap_or((f64::NAN, f64::NAN));
            let values = [
                census.paste as f64,
                census.in_domain() as f64,
                census.lost as f64,
                z0,
                z1,
            ];
            QUANTITIES
                .iter()
                .zip(values)
                .map(|(name, v)| row("stable", String::new(), r.steps, name, v))
                .collect()
        }
        Err(e) => QUANTITIES
            .iter()
            .map(|name| row("unstable", e.to_string(), 0, name, f64::NAN))
            .collect(),
    }
}

/// Position of an integrator name in [`Integrator::ALL`] (unknown names last): the row order.
fn integrator_rank(name: &str) -> usize {
    Integrator::ALL
        .iter()
        .position(|i| i.name() == name)
        .unwrap_or(Integrator::ALL.len())
}

/// Fills `error_vs_finest`: for each (integrator, body, quantity), relative to the value at the
/// finest dt whose case is stable. Rows are sorted by integrator order, dt descending, body,
/// quantity, so that merged shards equal an unsharded sweep row for row.
pub fn finish(rows: &mut [Row]) {
    let order = integrator_rank;
    rows.sort_by(|a, b| {
        order(&a.integrator)
            .cmp(&order(&b.integrator))
            .then(b.dt_s.total_cmp(&a.dt_s))
            .then(a.body.cmp(&b.body))
            .then(a.quantity.cmp(&b.quantity))
    });
    let mut finest: BTreeMap<(String, String, String), (f64, f64)> = BTreeMap::new();
    for r in rows.iter().filter(|r| r.status == "stable") {
        let k = (r.integrator.clone(), r.body.clone(), r.quantity.clone());
        let e = finest.entry(k).or_insert((f64::INFINITY, f64::NAN));
        if r.dt_s < e.0 {
            *e = (r.dt_s, r.value);
        }
    }
    for r in rows.iter_mut() {
        let k = (r.integrator.clone(), r.body.clone(), r.quantity.clone());
        r.error_vs_finest = match finest.get(&k) {
            Some((_, v)) if r.status == "stable" => rel(r.value, *v),
            _ => f64::NAN,
        };
    }
}

/// Writes rows as CSV.
pub fn write_rows(path: &Path, rows: &[Row]) -> io::Result<()> {
    let mut w = csv::Writer::from_path(path).map_err(io::Error::other)?;
    w.write_record(HEADER).map_err(io::Error::other)?;
    for r in rows {
        w.write_record([
            r.integrator.clone(),
            num(r.dt_s),
            r.status.clone(),
            r.reason.clone(),
            num(r.wall_time_s),
            r.steps.to_string(),
            r.body.clone(),
            r.quantity.clone(),
            num(r.value),
            num(r.reference),
            num(r.error_vs_reference),
            num(r.error_vs_finest),
        ])
        .map_err(io::Error::other)?;
    }
    w.flush()
}

/// Reads rows written by [`write_rows`].
pub fn read_rows(path: &Path) -> io::Result<Vec<Row>> {
    let mut rdr = csv::Reader::from_path(path).map_err(io::Error::other)?;
    let mut out = Vec::new();
    for rec in rdr.records() {
        let rec = rec.map_err(io::Error::other)?;
        let f = |i: usize| rec.get(i).unwrap_or("").to_string();
        let x = |i: usize| {
            rec.get(i)
                .and_then(|s| s.parse::<f64>().ok())
                .unwrap_or(f64::NAN)
        };
        out.push(Row {
            integrator: f(0),
            dt_s: x(1),
            status: f(2),
            reason: f(3),
            wall_time_s: x(4),
            steps: rec.get(5).and_then(|s| s.parse().ok()).unwrap_or(0),
            body: f(6),
            quantity: f(7),
            value: x(8),
            reference: x(9),
            error_vs_reference: x(10),
            error_vs_finest: x(11),
        });
    }
    Ok(out)
}

/// Per (integrator, dt): status, wall time, and the largest |error| over bodies for each quantity.
#[derive(Clone, Debug)]
pub struct CaseSummary {
    /// Integrator name.
    pub integrator: String,
    /// Time step, s.
    pub dt_s: f64,
    /// Stable?
    pub stable: bool,
    /// Wall time, s.
    pub wall_time_s: f64,
    /// Total steps over bodies.
    pub steps: u64,
    /// quantity → (max |error vs finest|, max |error vs reference|).
    pub errors: BTreeMap<String, (f64, f64)>,
}

/// Summarises rows per case.
pub fn summarise(rows: &[Row]) -> Vec<CaseSummary> {
    let mut map: BTreeMap<(String, u64), CaseSummary> = BTreeMap::new();
    for r in rows {
        let key = (r.integrator.clone(), r.dt_s.to_bits());
        let e = map.entry(key).or_insert_with(|| CaseSummary {
            integrator: r.integrator.clone(),
            dt_s: r.dt_s,
            stable: r.status == "stable",
            wall_time_s: r.wall_time_s,
            steps: 0,
            errors: BTreeMap::new(),
        });
        e.steps += r.steps;
        let q = e
            .errors
            .entry(r.quantity.clone())
            .or_insert((0.0, f64::NAN));
        let fin = r.error_vs_finest.abs();
        if fin.is_finite() {
            q.0 = q.0.max(fin);
        }
        let re = r.error_vs_reference.abs();
        if re.is_finite() {
            q.1 = if q.1.is_nan() { re } else { q.1.max(re) };
        }
    }
    let mut v: Vec<CaseSummary> = map.into_values().collect();
    let order = integrator_rank;
    v.sort_by(|a, b| {
        order(&a.integrator)
            .cmp(&order(&b.integrator))
            .then(b.dt_s.total_cmp(&a.dt_s))
    });
    v
}

/// Largest stable dt of `integrator` whose error against the finest is under `tol` for every
/// quantity (and every smaller dt too, so the answer is not a lucky cancellation).
pub fn recommended_dt(summaries: &[CaseSummary], integrator: &str, tol: f64) -> Option<f64> {
    let mut cases: Vec<&CaseSummary> = summaries
        .iter()
        .filter(|s| s.integrator == integrator)
        .collect();
    cases.sort_by(|a, b| a.dt_s.total_cmp(&b.dt_s));
    let mut best = None;
    for c in cases {
        let ok = c.stable && c.errors.values().all(|(f, _)| *f <= tol);
        if !ok {
            break;
        }
        best = Some(c.dt_s);
    }
    best
}

/// Draws `quantity_vs_dt.svg` (max error against the finest dt, per quantity and integrator,
/// against dt) and `speed_accuracy.svg` (worst error against wall time, one line per integrator).
pub fn charts(dir: &Path, title: &str, summaries: &[CaseSummary]) -> Result<(), String> {
    let mut by_q: BTreeMap<(String, String), Vec<(f64, f64)>> = BTreeMap::new();
    let mut speed: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    let floor = 1e-16;
    for s in summaries.iter().filter(|s| s.stable) {
        let mut worst: f64 = 0.0;
        for (q, (fin, re)) in &s.errors {
            by_q.entry((s.integrator.clone(), q.clone()))
                .or_default()
                .push((s.dt_s, fin.max(floor)));
            let e = if re.is_finite() { *re } else { *fin };
            worst = worst.max(e);
        }
        speed
            .entry(s.integrator.clone())
            .or_default()
            .push((s.wall_time_s.max(1e-6), worst.max(floor)));
    }
    let series: Vec<Series> = by_q
        .into_iter()
        .enumerate()
        .map(|(i, ((integ, q), pts))| Series::sorted_line(format!("{integ}: {q}"), pts, i))
        .collect();
    scatter_svg(
        &dir.join("quantity_vs_dt.svg"),
        &format!("{title}: max relative error vs finest stable dt"),
        "dt (s)",
        "max |relative error| over bodies",
        Scale::Log,
        Scale::Log,
        &series,
    )?;
    let series: Vec<Series> = speed
        .into_iter()
        .enumerate()
        .map(|(i, (integ, pts))| Series::sorted_line(integ, pts, i))
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
}
