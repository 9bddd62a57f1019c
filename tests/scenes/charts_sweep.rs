//! The sweep charts read as issue 13 asks: no float-noise ticks (`9.999999999999999e-5`), labels
//! not clipped, legend outside the curves, nine series apart; and a funnel-pour sweep draws its
//! ball counts against dt (f-EDEM Fig. 20).

use super::charts_free_settling::assert_legend_outside;
use crate::common::chart::{assert_readable_chart, svg_texts};
use crate::common::{settle, tmp};
use std::path::Path;

fn sweep(out: &Path, args: &[&str]) {
    let o = settle()
        .args(["sweep", "-q", "--out"])
        .arg(out)
        .args(args)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Three integrators × three quantities of the Stokes sphere: nine series, each with its own
/// (colour, shape) pair in the SVG legend, ticks at decades.
#[test]
fn nine_sweep_series_are_readable_and_apart() {
    let out = tmp();
    sweep(
        out.path(),
        &["scenarios/stokes_single.toml", "--dt", "1e-3,1e-4,1e-5"],
    );
    let dir = out.path().join("stokes_single_sweep");
    let svg = dir.join("quantity_vs_dt.svg");
    let texts = assert_readable_chart(
        &svg,
        "max relative error against the finest stable dt",
        &["time step dt (s)", "max |relative error| over bodies"],
    );
    for t in ["1e-5", "1e-4", "1e-3"] {
        assert!(
            texts.iter().any(|x| x == t),
            "no decade tick {t} in {texts:?}"
        );
    }
    let labels: Vec<&String> = texts.iter().filter(|t| t.contains(": ")).collect();
    let series: Vec<&str> = labels
        .iter()
        .filter(|t| !t.contains("stokes_single"))
        .map(|t| t.as_str())
        .collect();
    assert_eq!(series.len(), 9, "{series:?}");
    assert_legend_outside(&svg, &series);
    // Colour per integrator, shape per quantity: nine distinct (fill, shape) legend samples.
    let raw = std::fs::read_to_string(&svg).unwrap();
    let legend_x = raw.rfind("<rect").unwrap();
    let samples: std::collections::BTreeSet<String> = raw[legend_x..]
        .split('<')
        .filter(|e| e.starts_with("circle") || e.starts_with("polygon"))
        .map(|e| {
            let fill = e.split("fill=\"").nth(1).unwrap_or("").split('"').next();
            let corners = e.matches(',').count();
            format!("{}:{fill:?}:{corners}", &e[..6])
        })
        .collect();
    assert!(samples.len() >= 9, "legend samples {samples:?}");
    assert_readable_chart(
        &dir.join("speed_accuracy.svg"),
        "accuracy against cost",
        &["wall time (s)", "worst |relative error|"],
    );
    assert!(svg_texts(&dir.join("speed_accuracy.svg"))
        .iter()
        .any(|t| t == "implicit"));
}

/// f-EDEM Fig. 20: the funnel sweep's ball counts against dt.
#[test]
fn a_funnel_sweep_charts_its_ball_counts_against_dt() {
    let out = tmp();
    sweep(
        out.path(),
        &[
            "scenarios/paste_68_balls.toml",
            "--set",
            "repeats.count=1",
            "--dt",
            "1e-3,5e-4",
        ],
    );
    let svg = out.path().join("paste_68_balls_sweep/counts_vs_dt.svg");
    assert_readable_chart(
        &svg,
        "ball counts against time step",
        &["time step dt (s)", "balls (count)"],
    );
    assert_legend_outside(
        &svg,
        &[
            "balls_in_paste_at_count",
            "balls_in_domain_at_count",
            "balls_lost",
        ],
    );
}
