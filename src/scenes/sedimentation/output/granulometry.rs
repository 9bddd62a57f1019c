//! Outputs of the instruments of a sedimentation run (seed 000 §4.5, §5.4–5.5):
//! `granulometry.csv` (the (φ_o, w_o) pairs of each instrument and the input curve),
//! `granulometry.svg` (seed Fig. 18), `instruments.csv` (raw readings over time, seed
//! Figs. 15–17), `bulb_density.csv` (seed Fig. 13), `instrument_errors.csv` (each instrument
//! against the input curve) and the combined `instrument_errors.csv` of several runs.

use super::charts;
use crate::io::chart::{Chart, Curve, Scale, Series};
use crate::io::fmt::{num, opt};
use crate::io::{Outputs, Table};
use crate::sample::Distribution;
use crate::scenes::sedimentation::instruments::{BulbRow, InstrumentKind, InstrumentReading};
use crate::scenes::sedimentation::setup::Setup;
use std::io;

/// Adds every instrument output of a run of `setup` to `out`: `granulometry.csv`/`.svg`,
/// `instruments.csv`/`.svg`, `instrument_depths.svg`, `instrument_diameters.svg`,
/// `sphere_mass.svg`, `pipette_mass.svg`,
/// `bulb_density.csv`/`.svg`, `bulb_mean_density.svg` (with hydrometer readings) and
/// `instrument_errors.csv`; returns the error rows (each instrument against the input curve).
pub fn write_all(
    out: &mut Outputs,
    setup: &Setup,
    readings: &[InstrumentReading],
    bulb: &[BulbRow],
) -> io::Result<Vec<ErrorRow>> {
    let c = &setup.common;
    let sm = &setup.spec.sample;
    let instrument_errors = errors(&setup.distribution, readings);
    let full = super::physics_label(c.physics, true);
    let name = &c.name;
    out.table(granulometry_table(sm.sample, &setup.distribution, readings));
    out.table(instruments_table(readings));
    out.table(bulb_density_table(bulb));
    out.chart(
        "granulometry.svg",
        &chart(
            &format!("{name}: percent finer, input and instruments ({full}; seed 000 Fig. 18)"),
            &setup.distribution,
            readings,
        ),
    )?;
    out.chart(
        "instruments.svg",
        &charts::time_chart(
            &format!("{name}: percent finer read against time (seed 000 Figs. 15–17, bottom)"),
            readings,
        ),
    )?;
    out.chart(
        "instrument_depths.svg",
        &charts::depth_chart(
            &format!("{name}: depth of each reading (seed 000 Figs. 15–17, top)"),
            readings,
        ),
    )?;
    out.chart(
        "instrument_diameters.svg",
        &charts::diameter_chart(
            &format!("{name}: limiting diameter of each reading (seed 000 Figs. 15–17, middle)"),
            readings,
        ),
    )?;
    let (sphere, pipette) = charts::mass_charts(name, readings);
    out.chart("sphere_mass.svg", &sphere)?;
    out.chart("pipette_mass.svg", &pipette)?;
    out.chart(
        "bulb_density.svg",
        &charts::bulb_chart(
            &format!("{name}: suspension density along the hydrometer bulb (seed 000 Fig. 13)"),
            bulb,
        ),
    )?;
    if readings.iter().any(|r| r.hydrometer.is_some()) {
        out.chart(
            "bulb_mean_density.svg",
            &charts::bulb_mean_chart(
                &format!("{name}: mean density around the bulb against eq. 19 (seed 000 Fig. 14)"),
                readings,
            ),
        )?;
    }
    out.table(errors_table(
        &c.name,
        sm.sample,
        super::physics_label(c.physics, false),
        setup.grains.len(),
        &instrument_errors,
    ));
    Ok(instrument_errors)
}

/// Diameters at which the input curve is written: its points and 60 log-spaced ones.
pub fn input_diameters(input: &Distribution) -> Vec<f64> {
    let (d0, d1) = input.range_m();
    let mut d: Vec<f64> = (0..=60)
        .map(|i| d0 * (d1 / d0).powf(i as f64 / 60.0))
        .chain(input.points.iter().map(|p| p.0))
        .collect();
    d.sort_by(f64::total_cmp);
    d.dedup_by(|a, b| (*a / *b - 1.0).abs() < 1e-9);
    d
}

/// `granulometry.csv`: `sample, instrument, time_s, time_min, depth_m, diameter_m, percent_finer`,
/// then
/// `input_percent_finer` (the input curve at that diameter), `sd_percent` (1σ of w_o from the
/// grain count) and `ideal_percent_finer` (the same instrument on the ideal Stokes suspension of
/// the input curve: its own approximation). Instrument `input` rows are the input curve.
pub fn granulometry_table(
    sample: u32,
    input: &Distribution,
    readings: &[InstrumentReading],
) -> Table {
    let mut t = Table::new(
        "granulometry.csv",
        [
            "sample",
            "instrument",
            "time_s",
            "time_min",
            "depth_m",
            "diameter_m",
            "percent_finer",
            "input_percent_finer",
            "sd_percent",
            "ideal_percent_finer",
        ],
    );
    for d in input_diameters(input) {
        let f = num(input.percent_finer(d));
        t.push(vec![
            sample.to_string(),
            "input".into(),
            String::new(),
            String::new(),
            String::new(),
            num(d),
            f.clone(),
            f,
            String::new(),
            String::new(),
        ]);
    }
    for r in readings {
        let p = &r.point;
        t.push(vec![
            sample.to_string(),
            r.kind.name().into(),
            num(p.time_s),
            num(p.time_s / 60.0),
            num(p.depth_m),
            num(p.diameter_m),
            num(p.percent_finer),
            num(input.percent_finer(p.diameter_m)),
            num(p.sd_percent),
            opt(r.ideal.map(|x| x.percent_finer)),
        ]);
    }
    t
}

/// `instruments.csv`: the raw readings over time (seed Figs. 15–17), one row per instrument and
/// time (`time_s` and `time_min`). Hydrometer: tip depth, stem immersed, reading R (g/L, G_s = 2.65), ASTM effective depth
/// and the mean density over the bulb; sphere: apparent mass; pipette: dry mass drawn (real
/// cylinder) and grains in the sampled disc. All: the suspension density measured, φ_o and w_o.
pub fn instruments_table(readings: &[InstrumentReading]) -> Table {
    let mut t = Table::new(
        "instruments.csv",
        [
            "time_s",
            "time_min",
            "instrument",
            "depth_m",
            "tip_depth_m",
            "stem_immersed_m",
            "reading_g_per_l",
            "astm_effective_depth_m",
            "bulb_mean_density_kg_m3",
            "apparent_mass_g",
            "pipette_mass_g",
            "pipette_grains",
            "density_kg_m3",
            "diameter_m",
            "percent_finer",
            "sd_percent",
            "ideal_diameter_m",
            "ideal_percent_finer",
        ],
    );
    for r in readings {
        let h = r.hydrometer;
        t.push(vec![
            num(r.point.time_s),
            num(r.point.time_s / 60.0),
            r.kind.name().into(),
            num(r.point.depth_m),
            opt(h.map(|h| h.tip_depth_m)),
            opt(h.map(|h| h.stem_immersed_m)),
            opt(h.map(|h| h.reading)),
            opt(h.map(|h| h.astm_effective_depth_m)),
            opt(h.map(|h| h.bulb_mean_density_kg_m3)),
            opt(r.buoyancy.map(|b| b.apparent_mass_kg * 1e3)),
            opt(r.pipette.map(|p| p.mass_kg * 1e3)),
            r.pipette.map(|p| p.grains.to_string()).unwrap_or_default(),
            num(r.density_kg_m3),
            num(r.point.diameter_m),
            num(r.point.percent_finer),
            num(r.point.sd_percent),
            opt(r.ideal.map(|x| x.diameter_m)),
            opt(r.ideal.map(|x| x.percent_finer)),
        ]);
    }
    t
}

/// `bulb_density.csv`: `time_s, time_min, position_m` (below the top of the bulb, seed Fig. 13's h_hd),
/// `depth_m, density_kg_m3`, per layer crossed by the bulb at each hydrometer reading (and at
/// t = 0).
pub fn bulb_density_table(rows: &[BulbRow]) -> Table {
    let mut t = Table::new(
        "bulb_density.csv",
        [
            "time_s",
            "time_min",
            "position_m",
            "depth_m",
            "density_kg_m3",
        ],
    );
    for (time, p, y, rho) in rows {
        t.push(vec![
            num(*time),
            num(*time / 60.0),
            num(*p),
            num(*y),
            num(*rho),
        ]);
    }
    t
}

/// Chart of percent finer against log diameter: the input curve (a line) and the three
/// instruments (markers; seed Fig. 18).
pub fn chart(title: &str, input: &Distribution, readings: &[InstrumentReading]) -> Chart {
    let input_curve = Curve::new(
        "input",
        input_diameters(input)
            .into_iter()
            .map(|d| (d * 1e6, input.percent_finer(d)))
            .collect(),
    );
    let series = [
        InstrumentKind::Hydrometer,
        InstrumentKind::Buoyancy,
        InstrumentKind::Pipette,
    ]
    .into_iter()
    .enumerate()
    .map(|(i, k)| Series {
        label: k.name().into(),
        points: readings
            .iter()
            .filter(|r| r.kind == k)
            .map(|r| (r.point.diameter_m * 1e6, r.point.percent_finer))
            .collect(),
        colour: i,
        filled: true,
        line: true,
    });
    Chart::new(title)
        .x("diameter, log scale (µm)", Scale::Log)
        .y("percent finer (%)", Scale::Linear)
        .curve(input_curve)
        .all_series(series)
}

/// Errors of one instrument against the input curve over its readings.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorRow {
    /// Instrument name.
    pub instrument: String,
    /// Readings.
    pub readings: usize,
    /// Largest |w_o − F(φ_o)|, %.
    pub max_abs_error: f64,
    /// Mean |w_o − F(φ_o)|, %.
    pub mean_abs_error: f64,
    /// Largest |w_ideal − F(φ_ideal)|: the instrument's own approximation, %.
    pub max_abs_ideal_error: f64,
    /// Mean |w_ideal − F(φ_ideal)|, %.
    pub mean_abs_ideal_error: f64,
    /// Largest |w_o − w_ideal|: the simulation against the ideal suspension, %.
    pub max_abs_dev_from_ideal: f64,
    /// Mean 1σ of w_o from the grain count, %.
    pub mean_sd: f64,
}

/// Error of each instrument against the input curve.
pub fn errors(input: &Distribution, readings: &[InstrumentReading]) -> Vec<ErrorRow> {
    let mut out = Vec::new();
    for k in [
        InstrumentKind::Hydrometer,
        InstrumentKind::Buoyancy,
        InstrumentKind::Pipette,
    ] {
        let rs: Vec<&InstrumentReading> = readings.iter().filter(|r| r.kind == k).collect();
        if rs.is_empty() {
            continue;
        }
        let n = rs.len() as f64;
        let err = |p: &crate::instruments::Point| {
            (p.percent_finer - input.percent_finer(p.diameter_m)).abs()
        };
        let e: Vec<f64> = rs.iter().map(|r| err(&r.point)).collect();
        let ei: Vec<f64> = rs.iter().filter_map(|r| r.ideal.map(|p| err(&p))).collect();
        let dev = rs
            .iter()
            .filter_map(|r| {
                r.ideal
                    .map(|p| (r.point.percent_finer - p.percent_finer).abs())
            })
            .fold(0.0, f64::max);
        out.push(ErrorRow {
            instrument: k.name().into(),
            readings: rs.len(),
            max_abs_error: e.iter().copied().fold(0.0, f64::max),
            mean_abs_error: e.iter().sum::<f64>() / n,
            max_abs_ideal_error: ei.iter().copied().fold(0.0, f64::max),
            mean_abs_ideal_error: ei.iter().sum::<f64>() / (ei.len().max(1) as f64),
            max_abs_dev_from_ideal: dev,
            mean_sd: rs.iter().map(|r| r.point.sd_percent).sum::<f64>() / n,
        });
    }
    out
}

const ERROR_HEADER: [&str; 12] = [
    "scenario",
    "sample",
    "physics",
    "particles",
    "instrument",
    "readings",
    "max_abs_error_percent",
    "mean_abs_error_percent",
    "max_abs_ideal_error_percent",
    "mean_abs_ideal_error_percent",
    "max_abs_dev_from_ideal_percent",
    "mean_sd_percent",
];

/// `instrument_errors.csv` of one run: per instrument, the largest and mean difference between
/// its percent finer and the input curve at its diameters; the same for the instrument on the
/// ideal suspension (its own approximation); the largest difference between the two; the mean
/// statistical 1σ.
pub fn errors_table(
    scenario: &str,
    sample: u32,
    physics: &str,
    particles: usize,
    rows: &[ErrorRow],
) -> Table {
    let mut t = Table::new("instrument_errors.csv", ERROR_HEADER);
    for r in rows {
        t.push(vec![
            scenario.to_string(),
            sample.to_string(),
            physics.to_string(),
            particles.to_string(),
            r.instrument.clone(),
            r.readings.to_string(),
            num(r.max_abs_error),
            num(r.mean_abs_error),
            num(r.max_abs_ideal_error),
            num(r.mean_abs_ideal_error),
            num(r.max_abs_dev_from_ideal),
            num(r.mean_sd),
        ]);
    }
    t
}

/// The combined `instrument_errors.csv` of several runs: the rows of each run's
/// `instrument_errors.csv` table (`runs`: their outputs; a run without one adds nothing), in
/// order.
pub fn combined_errors_table<'a>(runs: impl IntoIterator<Item = &'a Outputs>) -> Table {
    let mut t = Table::new("instrument_errors.csv", ERROR_HEADER);
    for o in runs {
        if let Some(e) = o.get("instrument_errors.csv") {
            for r in e.rows().iter() {
                t.push(r.clone());
            }
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(instrument: &str, max: f64) -> ErrorRow {
        ErrorRow {
            instrument: instrument.into(),
            readings: 3,
            max_abs_error: max,
            mean_abs_error: 0.5 * max,
            max_abs_ideal_error: 0.25,
            mean_abs_ideal_error: 0.125,
            max_abs_dev_from_ideal: 1.5,
            mean_sd: 2.0,
        }
    }

    #[test]
    fn combined_errors_are_each_runs_rows_in_order_as_its_file_prints_them() {
        let mut a = Outputs::new();
        a.table(errors_table(
            "s1",
            1,
            "full",
            100,
            &[row("hydrometer", 1.0), row("pipette", 3.0)],
        ));
        let b = Outputs::new(); // a run without the table adds nothing
        let mut c = Outputs::new();
        c.table(errors_table(
            "s2",
            2,
            "ideal-stokes",
            50,
            &[row("buoyancy", 0.1)],
        ));
        let t = combined_errors_table([&a, &b, &c]);
        assert_eq!(t.name(), "instrument_errors.csv");
        assert_eq!(t.header(), ERROR_HEADER);
        let rows = t.rows();
        let firsts: Vec<(&str, &str)> = rows
            .iter()
            .map(|r| (r[0].as_str(), r[4].as_str()))
            .collect();
        assert_eq!(
            firsts,
            [("s1", "hydrometer"), ("s1", "pipette"), ("s2", "buoyancy")]
        );
        // The bytes: the header, then the runs' rows exactly as their own files print them.
        let text = String::from_utf8(t.to_csv().unwrap()).unwrap();
        let own = |o: &Outputs| {
            String::from_utf8(o.bytes("instrument_errors.csv").unwrap())
                .unwrap()
                .lines()
                .skip(1)
                .map(|l| format!("{l}\n"))
                .collect::<String>()
        };
        assert_eq!(
            text,
            format!("{}\n{}{}", ERROR_HEADER.join(","), own(&a), own(&c))
        );
    }
}
