//! Output tables and chart of a restitution drop:
//!
//! - `summary.csv`: one row per drop height (`drop_height_m, rebound_height_m,
//!   measured_rebound_height_m, rel_error, restitution_effective, restitution_law,
//!   ideal_rebound_height_m, rel_error_vs_ideal, restitution_from_heights, measured_restitution,
//!   impact_speed_m_s, lift_off_speed_m_s`; heights in m, speeds in m/s);
//! - `fit.csv`: the scenario's law as simulated, then each model of
//!   [`crate::contact::restitution_fits`] with its largest relative error, leave-one-out error
//!   and the heights within tolerance (only when measurements are given);
//! - `rebound_height.svg`: rebound against drop height, ideal, simulated and measured.

use super::fit::heights_within;
use super::{Comparison, DropOutcome, Setup, Tally};
use crate::contact::{LawFit, RestitutionLaw};
use crate::io::chart::{Chart, Curve, Scale, Series};
use crate::io::fmt::num;
use crate::io::Table;

/// `summary.csv`: one row per drop and its comparison.
pub fn summary_table(outcomes: &[DropOutcome], rows: &[Comparison]) -> Table {
    let records: Vec<Vec<String>> = outcomes
        .iter()
        .zip(rows)
        .map(|(o, c)| {
            let h = o.drop_height_m;
            vec![
                num(h),
                num(o.rebound_height_m),
                c.measured_rebound_m.map(num).unwrap_or_default(),
                c.rel_error.map(num).unwrap_or_default(),
                num(o.restitution_effective),
                num(c.law_restitution),
                num(c.ideal_rebound_m),
                c.rel_error_vs_ideal.map(num).unwrap_or_default(),
                num((o.rebound_height_m / h).sqrt()),
                c.measured_rebound_m
                    .map(|m| num((m / h).sqrt()))
                    .unwrap_or_default(),
                num(o.impact_speed_m_s),
                num(o.lift_off_speed_m_s),
            ]
        })
        .collect();
    Table::with_rows(
        "summary.csv",
        [
            "drop_height_m",
            "rebound_height_m",
            "measured_rebound_height_m",
            "rel_error",
            "restitution_effective",
            "restitution_law",
            "ideal_rebound_height_m",
            "rel_error_vs_ideal",
            "restitution_from_heights",
            "measured_restitution",
            "impact_speed_m_s",
            "lift_off_speed_m_s",
        ],
        records,
    )
}

/// One row of `fit.csv`.
fn fit_record(
    model: &str,
    law: &RestitutionLaw,
    max_rel_error: f64,
    leave_one_out: Option<f64>,
    within: usize,
    tolerance: f64,
    heights: usize,
) -> Vec<String> {
    vec![
        model.to_string(),
        num(law.coefficient),
        num(law.exponent),
        num(law.reference_speed_m_s),
        num(max_rel_error),
        leave_one_out.map(num).unwrap_or_default(),
        within.to_string(),
        num(tolerance),
        heights.to_string(),
    ]
}

/// `fit.csv`: first the scenario's law as simulated (Rapier, air; its within-count and
/// error from `tally` over `simulated` drops), then every model of `fits` (no air, gravity
/// `g_m_s2`).
pub fn fit_table(
    setup: &Setup,
    g_m_s2: f64,
    tally: &Tally,
    simulated: usize,
    fits: &[LawFit],
) -> Table {
    let spec = setup.spec;
    let (heights, measured) = (&spec.drop_heights_m, &spec.measured_rebound_heights_m);
    let mut records = vec![fit_record(
        "scenario_simulated",
        &setup.law,
        tally.worst,
        None,
        tally.within,
        spec.tolerance,
        simulated,
    )];
    records.extend(fits.iter().map(|f| {
        let within = heights_within(&f.law, heights, measured, g_m_s2, spec.tolerance);
        fit_record(
            f.model,
            &f.law,
            f.max_rel_error,
            f.leave_one_out_max_rel_error,
            within,
            spec.tolerance,
            heights.len(),
        )
    }));
    Table::with_rows(
        "fit.csv",
        [
            "model",
            "restitution",
            "restitution_exponent",
            "restitution_reference_speed_m_s",
            "max_rel_error",
            "leave_one_out_max_rel_error",
            "heights_within_tolerance",
            "tolerance",
            "heights",
        ],
        records,
    )
}

/// `rebound_height.svg`: the ideal rebound e(v)² H of the law (no air, gravity `g_m_s2`;
/// a dashed reference curve), the simulated rebounds (filled) and the measured ones (hollow), mm.
pub fn chart(name: &str, setup: &Setup, g_m_s2: f64, outcomes: &[DropOutcome]) -> Chart {
    let (law, spec) = (&setup.law, setup.spec);
    let heights = &spec.drop_heights_m;
    let e_at = |h: f64| law.at((2.0 * g_m_s2 * h).sqrt());
    let mm = |x: f64| x * 1e3;
    let ideal = if law.is_speed_dependent() {
        format!(
            "ideal e(v)²H, e = {} (v/{} m/s)^-{}",
            law.coefficient, law.reference_speed_m_s, law.exponent
        )
    } else {
        format!("ideal e²H, e = {}", law.coefficient)
    };
    // The ideal curve, dense over the drop heights (it bends when e depends on speed).
    let (h0, h1) = heights
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &h| (a.min(h), b.max(h)));
    let curve: Vec<(f64, f64)> = (0..=100)
        .map(|k| h0.min(h1) + (h1 - h0.min(h1)) * k as f64 / 100.0)
        .map(|h| (mm(h), mm(e_at(h).powi(2) * h)))
        .collect();
    let mut chart = Chart::new(format!("{name}: rebound height against drop height"))
        .x("drop height H_f (mm)", Scale::Linear)
        .x_from_zero(true)
        .y("rebound height H_r (mm)", Scale::Linear)
        .curve(Curve::new(ideal, curve).dashed())
        .series(Series {
            label: "simulated (Rapier 3D, air)".into(),
            points: outcomes
                .iter()
                .map(|o| (mm(o.drop_height_m), mm(o.rebound_height_m)))
                .collect(),
            colour: 3,
            filled: true,
            line: false,
        });
    if !spec.measured_rebound_heights_m.is_empty() {
        chart = chart.series(Series {
            label: "measured (f-EDEM Table A2)".into(),
            points: heights
                .iter()
                .zip(&spec.measured_rebound_heights_m)
                .map(|(&h, &r)| (mm(h), mm(r)))
                .collect(),
            colour: 0,
            filled: false,
            line: false,
        });
    }
    chart
}
