//! The charts of `settle laws`: f-EDEM Fig. 1 with every law, parity per law, and the velocity
//! error against the yield number.

use super::data::DataSet;
use super::eval::{yield_number, Law, LawResult, State};
use crate::fluid::bingham::beris::BERIS_CRITICAL_YIELD_NUMBER;
use crate::fluid::bingham::cd_fedem;
use crate::io::chart::{Band, Chart, Curve, Scale, Series};
use crate::io::fmt::sig;

/// C_d against Re′ (log–log): the measured points (Table 3's, where given), f-EDEM's eq. 19 and
/// the (Re′, C_d) each other law predicts for the spheres it lets move (f-EDEM Fig. 1).
pub fn cd_vs_re(data: &DataSet, results: &[LawResult]) -> Chart {
    let measured: Vec<(f64, f64)> = data
        .spheres
        .iter()
        .filter_map(|s| super::loso::point(data, s))
        .filter(|(re, cd)| *re > 0.0 && *cd > 0.0)
        .collect();
    let mut chart = Chart::new("Drag coefficient against Bingham Reynolds number (f-EDEM Fig. 1)")
        .x("Bingham Reynolds number Re′ (-)", Scale::Log)
        .y("drag coefficient C_d (-)", Scale::Log)
        .series(Series {
            label: "measured (Table 3)".into(),
            points: measured.clone(),
            colour: 0,
            filled: false,
            line: false,
        });
    let lo = measured
        .iter()
        .map(|p| p.0)
        .fold(f64::INFINITY, f64::min)
        .min(0.1);
    let hi = measured.iter().map(|p| p.0).fold(0.0, f64::max).max(1e3);
    let eq19: Vec<(f64, f64)> = (0..=200)
        .map(|k| lo * (hi / lo).powf(k as f64 / 200.0))
        .map(|re| (re, cd_fedem(re)))
        .collect();
    chart = chart.curve(Curve::new("bingham-fedem (eq. 19)", eq19));
    for (c, r) in results
        .iter()
        .filter(|r| matches!(r.law, Law::Plastic(_, false)))
        .enumerate()
    {
        let pts: Vec<(f64, f64)> = r
            .predictions
            .iter()
            .filter(|p| p.state == State::Moving)
            .filter_map(|p| super::loso::re_cd(data, p.sphere, p.v_predicted_m_s))
            .collect();
        chart = chart.series(Series {
            label: format!("{} (predicted)", r.law.key()),
            points: pts,
            colour: c + 1,
            filled: true,
            line: false,
        });
    }
    chart
}

/// The title of `parity.svg` above its panels ([`parity`]).
pub const PARITY_TITLE: &str = "Predicted against measured terminal velocity, per law";

/// Predicted against measured terminal velocity, one panel per law (drawn as a grid of three
/// columns under [`PARITY_TITLE`]), with the parity line and the ±25 % band; spheres a law
/// holds at rest sit on the x axis.
pub fn parity(data: &DataSet, results: &[LawResult]) -> Vec<Chart> {
    let vmax = data
        .spheres
        .iter()
        .map(|s| s.v_measured_m_s)
        .fold(0.0, f64::max);
    let top = results
        .iter()
        .flat_map(|r| r.predictions.iter().map(|p| p.v_predicted_m_s))
        .filter(|v| v.is_finite())
        .fold(vmax, f64::max)
        * 1.05;
    results
        .iter()
        .enumerate()
        .map(|(c, r)| {
            let pts: Vec<(f64, f64)> = r
                .predictions
                .iter()
                .map(|p| (data.spheres[p.sphere].v_measured_m_s, p.v_predicted_m_s))
                .filter(|p| p.1.is_finite())
                .collect();
            Chart::new(format!(
                "{}: mean |error| {} %",
                r.law.key(),
                sig(100.0 * r.velocity.mean_abs, 3)
            ))
            .x("measured velocity (m/s)", Scale::Linear)
            .y("predicted velocity (m/s)", Scale::Linear)
            .x_range(0.0, top)
            .y_range(0.0, top)
            .size(420, 360)
            .band(Band {
                label: "±25 %".into(),
                points: vec![(0.0, 0.0, 0.0), (top, 0.75 * top, 1.25 * top)],
                shade: 0.12,
            })
            .curve(Curve::new("parity", vec![(0.0, 0.0), (top, top)]))
            .series(Series {
                label: "spheres".into(),
                points: pts,
                colour: c,
                filled: true,
                line: false,
            })
        })
        .collect()
}

/// Velocity error (%) against the yield number τ_y/(Δρ g d) (log), one series per law (without
/// the `+beris` variants), with Beris et al.'s critical yield number.
pub fn error_vs_yield_number(data: &DataSet, results: &[LawResult]) -> Chart {
    let mut chart = Chart::new("Velocity error against yield number")
        .x("yield number τ_y/(Δρ g d) (-)", Scale::Log)
        .y("velocity error (%)", Scale::Linear)
        .y_from_zero(false);
    let mut lo = f64::INFINITY;
    let mut hi = 0.0f64;
    let (mut ylo, mut yhi) = (0.0f64, 0.0f64);
    // The `+beris` variants differ from their law only for spheres above the critical Y, which
    // the dashed line marks; drawing both would hide the law under its variant.
    for (c, r) in results
        .iter()
        .enumerate()
        .filter(|(_, r)| !matches!(r.law, Law::Plastic(_, true)))
    {
        let pts: Vec<(f64, f64)> = r
            .predictions
            .iter()
            .map(|p| {
                (
                    yield_number(data, &data.spheres[p.sphere]),
                    100.0 * p.rel_error,
                )
            })
            .filter(|(y, e)| *y > 0.0 && e.is_finite())
            .collect();
        for &(y, e) in &pts {
            lo = lo.min(y);
            hi = hi.max(y);
            ylo = ylo.min(e);
            yhi = yhi.max(e);
        }
        chart = chart.series(Series {
            label: r.law.key(),
            points: pts,
            colour: c,
            filled: true,
            line: false,
        });
    }
    if hi > 0.0 {
        let yc = BERIS_CRITICAL_YIELD_NUMBER;
        chart = chart
            .curve(Curve::new("zero error", vec![(lo, 0.0), (hi, 0.0)]))
            .curve(
                Curve::new(
                    "Beris et al. critical Y = 0.0477",
                    vec![(yc, ylo), (yc, yhi)],
                )
                .dashed(),
            );
    }
    chart
}
