//! Charts of a sedimentation run drawn with the shared chart module ([`crate::io::chart`]):
//! `max_diameter.svg` (seed 000 Fig. 12), `bulb_density.svg` (Fig. 13), `bulb_mean_density.svg`
//! (Fig. 14) and the instruments against time in minutes on a log axis, as labs read them
//! (Figs. 15–17): `instrument_depths.svg`, `instrument_diameters.svg`, `sphere_mass.svg`,
//! `pipette_mass.svg`, `instruments.svg`.

use super::plot::time_text;
use crate::io::chart::{Chart, Curve, Scale, Series};
use crate::scenes::sedimentation::instruments::{BulbRow, InstrumentKind, InstrumentReading};

/// The three instruments, in chart order, with their colour indices.
const KINDS: [(InstrumentKind, usize); 3] = [
    (InstrumentKind::Hydrometer, 0),
    (InstrumentKind::Buoyancy, 1),
    (InstrumentKind::Pipette, 2),
];

/// One row of `max_diameter.csv`: time (s), depth (m), largest grain above that depth (m) and
/// the limiting diameter of seed eq. 16 (m).
pub type MaxDiameterRow = (f64, f64, f64, f64);

/// Seed Fig. 12: the largest diameter above each depth (markers, every fourth row of
/// `max_diameter.csv` so they stay apart) against eq. 16, d = √(18 μ z / ((ρ_p − ρ_f) g t))
/// (dashed lines), one colour per time. Eq. 16 is drawn up to 1.5 × the largest grain
/// (beyond it no grain exists and the bound says nothing).
pub fn max_diameter_chart(title: &str, rows: &[MaxDiameterRow]) -> Chart {
    let mut times: Vec<f64> = rows.iter().map(|r| r.0).collect();
    times.dedup();
    let d_top = rows.iter().map(|r| r.2).fold(0.0, f64::max) * 1.5;
    let mut chart = Chart::new(title)
        .x("depth below the surface (cm)", Scale::Linear)
        .y("largest diameter above the depth (µm)", Scale::Linear);
    for (i, &t) in times.iter().enumerate() {
        let of_t: Vec<&MaxDiameterRow> = rows.iter().filter(|r| r.0 == t).collect();
        chart = chart
            .series(Series {
                label: format!("simulation, {}", time_text(t)),
                points: of_t
                    .iter()
                    .step_by(4)
                    .map(|r| (r.1 * 100.0, r.2 * 1e6))
                    .collect(),
                colour: i,
                filled: true,
                line: false,
            })
            .curve(
                Curve::new(
                    format!("eq. 16, {}", time_text(t)),
                    of_t.iter()
                        .filter(|r| r.3 <= d_top)
                        .map(|r| (r.1 * 100.0, r.3 * 1e6))
                        .collect(),
                )
                .colour(i)
                .dashed(),
            );
    }
    chart
}

/// Seed Fig. 13: the suspension density along the hydrometer bulb at each reading, averaged over
/// 1 cm of bulb, against the distance below the top of the bulb (h_hd), one line per time.
pub fn bulb_chart(title: &str, rows: &[BulbRow]) -> Chart {
    let mut times: Vec<f64> = rows.iter().map(|r| r.0).collect();
    times.dedup();
    let bin = 0.01;
    let series: Vec<Series> = times
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            let mut acc: Vec<(f64, f64, usize)> = Vec::new();
            for r in rows.iter().filter(|r| r.0 == t) {
                let k = (r.1 / bin).max(0.0) as usize;
                if acc.len() <= k {
                    acc.resize(k + 1, (0.0, 0.0, 0));
                }
                acc[k].0 += r.1;
                acc[k].1 += r.3;
                acc[k].2 += 1;
            }
            let points = acc
                .iter()
                .filter(|a| a.2 > 0)
                .map(|a| (a.0 / a.2 as f64 * 100.0, a.1 / a.2 as f64))
                .collect();
            Series::sorted_line(time_text(t), points, i)
        })
        .collect();
    close_up(
        title,
        (
            "distance below the top of the bulb h_hd (cm)",
            Scale::Linear,
        ),
        "suspension density, mean over 1 cm (kg/m³)",
        &ys(&series),
    )
    .all_series(series)
}

/// A chart whose linear y axis spans the y `values` (padded by 10 % of their spread, at least
/// 0.1 % of their size) rather than starting at zero: densities near the fluid's, a sphere's
/// apparent mass, change by a few % of their values.
fn close_up(title: &str, x: (&str, Scale), y: &str, values: &[f64]) -> Chart {
    let chart = Chart::new(title)
        .x(x.0, x.1)
        .y(y, Scale::Linear)
        .y_from_zero(false);
    let (lo, hi) = values
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |a, &v| {
            (a.0.min(v), a.1.max(v))
        });
    if lo > hi {
        return chart;
    }
    let pad = (0.1 * (hi - lo)).max(1e-3 * hi.abs().max(lo.abs()));
    chart.y_range(lo - pad, hi + pad)
}

/// The y values of `series`.
fn ys(series: &[Series]) -> Vec<f64> {
    series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .collect()
}

/// Seed Fig. 14: the mean suspension density over the bulb (simulation) and the density the
/// hydrometer infers from its depth with eq. 19, ρ_s = ρ_f m / (m − A_s (y_ow − y_o) ρ_f),
/// against time in minutes.
pub fn bulb_mean_chart(title: &str, readings: &[InstrumentReading]) -> Chart {
    let hyd: Vec<(f64, f64, f64)> = readings
        .iter()
        .filter_map(|r| {
            r.hydrometer.map(|h| {
                (
                    r.point.time_s / 60.0,
                    h.bulb_mean_density_kg_m3,
                    h.density_kg_m3,
                )
            })
        })
        .collect();
    let values: Vec<f64> = hyd.iter().flat_map(|h| [h.1, h.2]).collect();
    close_up(
        title,
        ("time, log scale (min)", Scale::Log),
        "suspension density around the bulb (kg/m³)",
        &values,
    )
    .series(Series {
        label: "mean over the bulb (simulation)".into(),
        points: hyd.iter().map(|h| (h.0, h.1)).collect(),
        colour: 0,
        filled: true,
        line: false,
    })
    .curve(Curve::new(
        "eq. 19 from the hydrometer's depth",
        hyd.iter().map(|h| (h.0, h.2)).collect(),
    ))
}

/// One series per instrument of `value` against the reading time in minutes.
fn per_instrument(
    readings: &[InstrumentReading],
    value: impl Fn(&InstrumentReading) -> Option<f64>,
) -> Vec<Series> {
    KINDS
        .iter()
        .map(|&(k, colour)| Series {
            label: k.name().into(),
            points: readings
                .iter()
                .filter(|r| r.kind == k)
                .filter_map(|r| value(r).map(|v| (r.point.time_s / 60.0, v)))
                .collect(),
            colour,
            // Hollow pipette markers: the sphere and the pipette read at the same depth.
            filled: k != InstrumentKind::Pipette,
            line: true,
        })
        .filter(|s| !s.points.is_empty())
        .collect()
}

/// Seed Figs. 15–17, top: the depth each instrument's reading stands for (eq. 16's depth:
/// hydrometer bulb centre, sphere centre, pipette tip), and the hydrometer's ASTM D422 effective
/// depth from its reading, in cm against time in minutes.
pub fn depth_chart(title: &str, readings: &[InstrumentReading]) -> Chart {
    let mut series = per_instrument(readings, |r| Some(r.point.depth_m * 100.0));
    let astm: Vec<(f64, f64)> = readings
        .iter()
        .filter_map(|r| {
            r.hydrometer
                .map(|h| (r.point.time_s / 60.0, h.astm_effective_depth_m * 100.0))
        })
        .collect();
    if !astm.is_empty() {
        series.push(Series {
            label: "hydrometer, ASTM D422 effective depth".into(),
            points: astm,
            colour: 0,
            filled: false,
            line: true,
        });
    }
    close_up(
        title,
        ("time, log scale (min)", Scale::Log),
        "depth below the surface (cm)",
        &ys(&series),
    )
    .all_series(series)
}

/// Seed Figs. 15–17, middle: the limiting diameter φ_o of eq. 16 of each reading, µm (log),
/// against time in minutes.
pub fn diameter_chart(title: &str, readings: &[InstrumentReading]) -> Chart {
    Chart::new(title)
        .x("time, log scale (min)", Scale::Log)
        .y("limiting diameter φ_o, log scale (µm)", Scale::Log)
        .all_series(per_instrument(readings, |r| Some(r.point.diameter_m * 1e6)))
}

/// Seed Figs. 15–17, bottom: the percent finer w_o of each reading against time in minutes.
pub fn time_chart(title: &str, readings: &[InstrumentReading]) -> Chart {
    Chart::new(title)
        .x("time, log scale (min)", Scale::Log)
        .y("percent finer w_o (%)", Scale::Linear)
        .all_series(per_instrument(readings, |r| Some(r.point.percent_finer)))
}

/// Seed Fig. 16 top: the buoyancy sphere's apparent mass in the suspension (eq. 22), and what
/// the pipette draws (dry mass, real cylinder), each on its own axis in g against time in
/// minutes (the sphere's changes are a few % of its mass): (`sphere_mass.svg`,
/// `pipette_mass.svg`), titled after the run `name`.
pub fn mass_charts(name: &str, readings: &[InstrumentReading]) -> (Chart, Chart) {
    let one = |title: String, y: &str, mass: &dyn Fn(&InstrumentReading) -> Option<f64>| {
        let series = per_instrument(readings, mass);
        close_up(
            &title,
            ("time, log scale (min)", Scale::Log),
            y,
            &ys(&series),
        )
        .all_series(series)
    };
    (
        one(
            format!("{name}: apparent mass of the buoyancy sphere (seed 000 Fig. 16, top)"),
            "apparent mass of the sphere (g)",
            &|r| r.buoyancy.map(|b| b.apparent_mass_kg * 1e3),
        ),
        one(
            format!("{name}: dry mass drawn by the pipette (seed 000 Fig. 17)"),
            "dry mass in the pipette (g)",
            &|r| r.pipette.map(|p| p.mass_kg * 1e3),
        ),
    )
}
