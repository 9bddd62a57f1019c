//! Output tables and chart of a tilt test:
//!
//! - `summary.csv`: one row per angle run, the given angles and the bisection's, sorted by angle
//!   (`angle_deg, displacement_m, slides, source`; `source` is `given` or `bisection`);
//! - `threshold.csv`: the friction coefficient, atan(μ), the threshold found and its bracket, and
//!   the error (degrees);
//! - `tilt_displacement.svg`: displacement down the slope against the angle.

use super::TiltOutcome;
use crate::io::chart::ticks::significant;
use crate::io::chart::{Chart, Curve, Scale, Series};
use crate::io::fmt::{num, opt};
use crate::io::Table;

/// `summary.csv`.
pub fn summary_table(runs: &[TiltOutcome]) -> Table {
    let rows: Vec<Vec<String>> = runs
        .iter()
        .map(|r| {
            vec![
                num(r.angle_deg),
                num(r.displacement_m),
                r.slides.to_string(),
                if r.bisection { "bisection" } else { "given" }.to_string(),
            ]
        })
        .collect();
    Table::with_rows(
        "summary.csv",
        ["angle_deg", "displacement_m", "slides", "source"],
        rows,
    )
}

/// `threshold.csv`: `friction`, the expected threshold atan(μ) `expected_deg`, the
/// threshold `found_deg` and the `bracket` (sticks at, slides at) of the search, degrees.
pub fn threshold_table(
    friction: f64,
    expected_deg: f64,
    found_deg: Option<f64>,
    bracket: Option<(f64, f64)>,
) -> Table {
    Table::with_rows(
        "threshold.csv",
        [
            "friction",
            "expected_threshold_deg",
            "threshold_deg",
            "sticks_at_deg",
            "slides_at_deg",
            "error_deg",
        ],
        vec![vec![
            num(friction),
            num(expected_deg),
            opt(found_deg),
            opt(bracket.map(|b| b.0)),
            opt(bracket.map(|b| b.1)),
            opt(found_deg.map(|f| f - expected_deg)),
        ]],
    )
}

/// `tilt_displacement.svg`: sticking and sliding runs (displacement in mm against the
/// angle in degrees) and the line θ = atan(μ) = `expected_deg`.
pub fn chart(title: &str, runs: &[TiltOutcome], expected_deg: f64) -> Chart {
    let pts = |slides: bool| -> Vec<(f64, f64)> {
        runs.iter()
            .filter(|r| r.slides == slides)
            .map(|r| (r.angle_deg, r.displacement_m * 1e3))
            .collect()
    };
    let y_max = runs
        .iter()
        .map(|r| r.displacement_m * 1e3)
        .fold(0.0, f64::max);
    Chart::new(title)
        .x("tilt angle θ (°)", Scale::Linear)
        .y("displacement down the slope (mm)", Scale::Linear)
        .series(Series {
            label: "sticks".into(),
            points: pts(false),
            colour: 0,
            filled: true,
            line: false,
        })
        .series(Series {
            label: "slides".into(),
            points: pts(true),
            colour: 3,
            filled: true,
            line: false,
        })
        .curve(
            Curve::new(
                format!(
                    "expected threshold θ = atan(μ) = {}°",
                    significant(expected_deg, 4)
                ),
                vec![(expected_deg, 0.0), (expected_deg, y_max)],
            )
            .dashed(),
        )
}
