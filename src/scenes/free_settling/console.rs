//! The console table of a free-settling or drop run: one row per sphere (and fall height),
//! printed by `settle run` after the run. Every number in the format of [`crate::io::fmt`].

use super::output::{rel_error, rel_error_vs_force_balance};
use super::SphereResult;
use crate::scenario::Entry;

/// The rows of the console table of `results`: free settling ([`Entry::Submerged`]) or drops.
pub fn rows(results: &[SphereResult], entry: Entry) -> Vec<String> {
    match entry {
        Entry::Submerged => settling_rows(results),
        Entry::Drop => drop_rows(results),
    }
}

/// Right-aligned columns: `rows[0]` is the header; the first column is left-aligned.
fn columns(rows: &[Vec<String>]) -> Vec<String> {
    let n = rows.iter().map(|r| r.len()).max().unwrap_or(0);
    let width: Vec<usize> = (0..n)
        .map(|i| {
            rows.iter()
                .filter_map(|r| r.get(i))
                .map(|c| c.chars().count())
                .max()
                .unwrap_or(0)
        })
        .collect();
    rows.iter()
        .map(|r| {
            let cells: Vec<String> = r
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    if i == 0 {
                        format!("{c:<w$}", w = width[i])
                    } else {
                        format!("{c:>w$}", w = width[i])
                    }
                })
                .collect();
            format!("  {}", cells.join("  ").trim_end())
        })
        .collect()
}

/// Free settling: per sphere, diameter, density, measured, simulated and force-balance
/// velocity, errors, Reynolds number (Re, or Re′ of eq. 14 in a Bingham fluid) and regime; then
/// the statistics against the measurements.
fn settling_rows(results: &[SphereResult]) -> Vec<String> {
    use crate::io::fmt::{g, g_opt, pct};
    let bingham = results.iter().any(|x| x.re_bingham.is_some());
    let mut rows = vec![[
        "sphere",
        "d_mm",
        "rho_kg_m3",
        "v_meas_m_s",
        "v_sim_m_s",
        "v_balance_m_s",
        "err_vs_meas",
        "sim/balance-1",
        if bingham { "Re'" } else { "Re" },
        "regime",
    ]
    .map(String::from)
    .to_vec()];
    for x in results {
        let sp = &x.case.spec;
        rows.push(vec![
            x.case.id.clone(),
            g(sp.diameter_m * 1e3),
            g(sp.density_kg_m3),
            g_opt(sp.v_measured_m_s),
            g(x.v_simulated_m_s),
            g(x.v_force_balance_m_s),
            rel_error(x)
                .map(|e| pct(e, 3))
                .unwrap_or_else(|| "-".into()),
            pct(rel_error_vs_force_balance(x), 3),
            g_opt(x.reynolds.or(x.re_bingham)),
            x.regime.label().to_string(),
        ]);
    }
    let mut out = columns(&rows);
    let stats = crate::scenes::free_settling::output::metrics(results);
    out.extend(stats.last().map(|all| format!("  {}", stats_line(all))));
    out
}

/// Drops: per sphere and fall height, the entry speed at the surface, the settling distance
/// (lowest point below the surface once stopped) and the stop time (`-` if it did not stop).
fn drop_rows(results: &[SphereResult]) -> Vec<String> {
    use crate::io::fmt::{g, g_opt};
    let mut rows = vec![[
        "sphere",
        "d_mm",
        "fall_height_mm",
        "entry_speed_m_s",
        "settling_distance_mm",
        "stop_time_s",
        "stop",
    ]
    .map(String::from)
    .to_vec()];
    for x in results {
        rows.push(vec![
            x.case.id.clone(),
            g(x.case.spec.diameter_m * 1e3),
            g_opt(x.case.fall_height_m.map(|h| h * 1e3)),
            g_opt(x.entry_velocity_m_s.map(f64::abs)),
            g(x.final_bottom_depth_m * 1e3),
            g_opt(x.stop_time_s),
            x.stop.label().to_string(),
        ]);
    }
    columns(&rows)
}

/// The error statistics of a set of spheres against their measurements, one line.
pub fn stats_line(s: &crate::io::metrics::ErrorStats) -> String {
    use crate::io::fmt::{pct, sig};
    format!(
        "vs measured: N = {}, mean |err| = {}, median = {}, max = {}, bias = {}, within 10%: {}%, within 25%: {}%",
        s.n,
        pct(s.mean_abs, 3).trim_start_matches('+'),
        pct(s.median_abs, 3).trim_start_matches('+'),
        pct(s.max_abs, 3).trim_start_matches('+'),
        pct(s.bias, 3),
        sig(100.0 * s.within_10pct, 3),
        sig(100.0 * s.within_25pct, 3)
    )
}
