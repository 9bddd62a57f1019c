//! Output tables and charts of a funnel pour (`kind = "funnel_pour"`, f-EDEM §4.2):
//!
//! - `balls.csv`: every ball at the end of every repeat (`repeat, seed, ball, diameter_m, x_m,
//!   y_m, z_m, speed_m_s, place`), z above the cylinder bottom, x and y from its axis;
//! - `counts.csv`: per repeat, where the balls are at `funnel.count_time_s` and at the end, the
//!   Z range in the paste, steps and wall time;
//! - `timeseries.csv`: per repeat, the census of the balls (`in_paste, falling, in_funnel,
//!   outside, away, lost`, see [`super::Place`]) and the largest speed of the balls in
//!   play (paste, falling, funnel) every `record.every_s` (default 0.01 s; negative times: the
//!   balls settling in the closed funnel);
//! - `z_distribution.csv` + `.svg`: ball centres in the paste per Z bin (`funnel.z_bin_m`, from 0 to
//!   H + the largest radius: a ball counts as in the paste once its lowest point is below the
//!   surface), summed over the repeats and per repeat (f-EDEM Fig. 21);
//! - `presence.csv` + `.svg`: on each horizontal plane `funnel.planes_z_m`, the probability over
//!   the repeats that a cell of the grid (`funnel.grid_cell_m`) lies inside a ball: its centre
//!   point (x, y, Z) inside a ball's sphere, as a cut through the hardened paste shows it
//!   (f-EDEM Fig. 22, 15 repeats).

use super::{Geometry, Place, RepeatResult};
use crate::error::Error;
use crate::io::chart::data::{Drawn, Figure, Panel};
use crate::io::fmt::num;
use crate::io::{Outputs, Table};
use crate::scenario::FunnelPourSpec;
use crate::scenes::Prepared;
use plotters::prelude::*;
use std::io;

/// One bin of the vertical distribution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZBin {
    /// Lower edge, m above the bottom.
    pub z_lo_m: f64,
    /// Upper edge, m.
    pub z_hi_m: f64,
    /// Ball centres in the bin, over all repeats.
    pub count: usize,
}

/// Histogram of the centre heights of the balls in the paste, bins of `bin_m` from 0 to
/// `height_m` (the last bin may be shorter).
pub fn z_histogram(results: &[RepeatResult], bin_m: f64, height_m: f64) -> Vec<ZBin> {
    let n = ((height_m / bin_m).ceil() as usize).max(1);
    let mut bins: Vec<ZBin> = (0..n)
        .map(|i| ZBin {
            z_lo_m: i as f64 * bin_m,
            z_hi_m: ((i + 1) as f64 * bin_m).min(height_m),
            count: 0,
        })
        .collect();
    for b in results.iter().flat_map(|r| &r.balls) {
        if b.place != Place::Paste {
            continue;
        }
        let i = ((b.position_m[2] / bin_m).floor().max(0.0) as usize).min(n - 1);
        bins[i].count += 1;
    }
    bins
}

/// One cell of a presence map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PresenceCell {
    /// Height of the plane, m above the bottom.
    pub plane_z_m: f64,
    /// Cell centre, m from the axis.
    pub x_m: f64,
    /// Cell centre, m from the axis.
    pub y_m: f64,
    /// Fraction of the repeats in which the point (x, y, Z) is inside a ball.
    pub probability: f64,
}

/// Centres of the square grid of cell `cell_m` over the disc of radius `radius_m` (cells whose
/// centre is inside the disc), symmetric about the axis.
pub fn grid(radius_m: f64, cell_m: f64) -> Vec<(f64, f64)> {
    let n = (2.0 * radius_m / cell_m).ceil() as i64;
    let c = |i: i64| (i as f64 + 0.5 - 0.5 * n as f64) * cell_m;
    let mut out = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (c(i), c(j));
            if x.hypot(y) <= radius_m {
                out.push((x, y));
            }
        }
    }
    out
}

/// Presence probabilities on the planes `planes_z_m` over the grid of the cylinder's disc.
pub fn presence(
    results: &[RepeatResult],
    planes_z_m: &[f64],
    radius_m: f64,
    cell_m: f64,
) -> Vec<PresenceCell> {
    let cells = grid(radius_m, cell_m);
    let reps = results.len().max(1) as f64;
    let mut out = Vec::with_capacity(cells.len() * planes_z_m.len());
    for &z in planes_z_m {
        for &(x, y) in &cells {
            let hits = results
                .iter()
                .filter(|r| {
                    r.balls.iter().any(|b| {
                        let [bx, by, bz] = b.position_m;
                        let r = 0.5 * b.diameter_m;
                        (bx - x).powi(2) + (by - y).powi(2) + (bz - z).powi(2) <= r * r
                    })
                })
                .count();
            out.push(PresenceCell {
                plane_z_m: z,
                x_m: x,
                y_m: y,
                probability: hits as f64 / reps,
            });
        }
    }
    out
}

/// `balls.csv`.
pub fn balls_table(results: &[RepeatResult]) -> Table {
    let mut t = Table::new(
        "balls.csv",
        [
            "repeat",
            "seed",
            "ball",
            "diameter_m",
            "x_m",
            "y_m",
            "z_m",
            "speed_m_s",
            "place",
        ],
    );
    for r in results {
        for (i, b) in r.balls.iter().enumerate() {
            t.push(vec![
                r.index.to_string(),
                r.seed.to_string(),
                i.to_string(),
                num(b.diameter_m),
                num(b.position_m[0]),
                num(b.position_m[1]),
                num(b.position_m[2]),
                num(b.speed_m_s),
                b.place.label().to_string(),
            ]);
        }
    }
    t
}

/// `counts.csv`.
pub fn counts_table(results: &[RepeatResult], count_time_s: Option<f64>) -> Table {
    let mut t = Table::new(
        "counts.csv",
        [
            "repeat",
            "seed",
            "count_time_s",
            "in_paste_at_count_time",
            "in_domain_at_count_time",
            "in_paste",
            "in_funnel",
            "falling",
            "outside",
            "away",
            "lost",
            "z_min_m",
            "z_max_m",
            "max_speed_at_opening_m_s",
            "end_time_s",
            "steps",
        ],
    );
    for r in results {
        let c = r.census();
        let at = r.census_at_count;
        let z = r.z_range_m();
        t.push(vec![
            r.index.to_string(),
            r.seed.to_string(),
            count_time_s.map(num).unwrap_or_default(),
            at.map(|c| c.paste.to_string()).unwrap_or_default(),
            at.map(|c| c.in_domain().to_string()).unwrap_or_default(),
            c.paste.to_string(),
            c.funnel.to_string(),
            c.falling.to_string(),
            c.outside.to_string(),
            c.away.to_string(),
            c.lost.to_string(),
            z.map(|z| num(z.0)).unwrap_or_default(),
            z.map(|z| num(z.1)).unwrap_or_default(),
            num(r.max_speed_at_opening_m_s),
            num(r.end_time_s),
            r.steps.to_string(),
        ]);
    }
    t
}

/// `timeseries.csv`.
pub fn timeseries_table(results: &[RepeatResult]) -> Table {
    let mut t = Table::new(
        "timeseries.csv",
        [
            "repeat",
            "time_s",
            "in_paste",
            "falling",
            "in_funnel",
            "outside",
            "away",
            "lost",
            "max_speed_m_s",
        ],
    );
    for r in results {
        for s in &r.samples {
            let c = s.census;
            t.push(vec![
                r.index.to_string(),
                num(s.time_s),
                c.paste.to_string(),
                c.falling.to_string(),
                c.funnel.to_string(),
                c.outside.to_string(),
                c.away.to_string(),
                c.lost.to_string(),
                num(s.max_speed_m_s),
            ]);
        }
    }
    t
}

/// `z_distribution.csv`.
pub fn z_distribution_table(bins: &[ZBin], repeats: usize) -> Table {
    let mut t = Table::new(
        "z_distribution.csv",
        ["z_lo_m", "z_hi_m", "count", "per_repeat", "fraction"],
    );
    let total: usize = bins.iter().map(|b| b.count).sum();
    for b in bins {
        t.push(vec![
            num(b.z_lo_m),
            num(b.z_hi_m),
            b.count.to_string(),
            num(b.count as f64 / repeats.max(1) as f64),
            num(if total > 0 {
                b.count as f64 / total as f64
            } else {
                0.0
            }),
        ]);
    }
    t
}

/// `presence.csv`.
pub fn presence_table(cells: &[PresenceCell]) -> Table {
    Table::with_rows(
        "presence.csv",
        ["plane_z_m", "x_m", "y_m", "probability"],
        cells
            .iter()
            .map(|c| vec![num(c.plane_z_m), num(c.x_m), num(c.y_m), num(c.probability)])
            .collect(),
    )
}

fn err(e: impl std::fmt::Display) -> io::Error {
    io::Error::other(e.to_string())
}

/// A tick label with at most 4 significant digits, no float noise and never `-0`.
fn tick(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v.is_finite() {
            "0".into()
        } else {
            format!("{v}")
        };
    }
    let rounded: f64 = format!("{v:.3e}").parse().unwrap_or(v);
    format!("{rounded}")
}

/// The vertical distribution as horizontal bars (balls per repeat against Z, in cm), with
/// f-EDEM's range 8.5–13.5 cm and the paste surface marked (f-EDEM Fig. 21): the text of
/// `z_distribution.svg`.
pub fn z_chart(title: &str, bins: &[ZBin], repeats: usize, height_m: f64) -> io::Result<String> {
    let mut text = String::new();
    draw_z_chart(&mut text, title, bins, repeats, height_m)?;
    Ok(text)
}

fn draw_z_chart(
    text: &mut String,
    title: &str,
    bins: &[ZBin],
    repeats: usize,
    height_m: f64,
) -> io::Result<()> {
    let reps = repeats.max(1) as f64;
    let x_max = z_chart_x_max(bins, reps);
    let top = bins.last().map_or(height_m, |b| b.z_hi_m.max(height_m));
    let y_max = top * 100.0 * 1.05;
    let root = SVGBackend::with_string(text, (700, 800)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..x_max, 0.0..y_max)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 14))
        .x_desc("ball centres in the bin, mean per repeat (balls)")
        .y_desc("Z above the cylinder bottom (cm)")
        .draw()
        .map_err(err)?;
    chart
        .draw_series(bins.iter().map(|b| {
            Rectangle::new(
                [
                    (0.0, b.z_lo_m * 100.0),
                    (b.count as f64 / reps, b.z_hi_m * 100.0),
                ],
                BLUE.mix(0.6).filled(),
            )
        }))
        .map_err(err)?
        .label("simulation")
        .legend(|(x, y)| Rectangle::new([(x, y - 5), (x + 15, y + 5)], BLUE.mix(0.6).filled()));
    let red = RED.stroke_width(2);
    chart
        .draw_series([8.5, 13.5].map(|z| PathElement::new(vec![(0.0, z), (x_max, z)], red)))
        .map_err(err)?
        .label("f-EDEM range 8.5–13.5 cm")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], red));
    let surface = BLACK.stroke_width(1);
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(0.0, height_m * 100.0), (x_max, height_m * 100.0)],
            surface,
        )))
        .map_err(err)?
        .label("paste surface")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], surface));
    // Lower right: below f-EDEM's range, where no ball rests.
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .label_font(("sans-serif", 13))
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(err)?;
    root.present().map_err(err)?;
    Ok(())
}

/// The right end of the z chart's x axis: 10 % beyond the largest mean count per repeat (at
/// least 1.1 balls).
fn z_chart_x_max(bins: &[ZBin], reps: f64) -> f64 {
    bins.iter()
        .map(|b| b.count as f64 / reps)
        .fold(1.0, f64::max)
        * 1.1
}

/// The data of `z_distribution.svg` for a caller that draws it itself: the bars as a line
/// through each bin's (mean count per repeat, mid-height in cm), f-EDEM's range and the paste
/// surface as reference lines.
fn z_figure(title: &str, bins: &[ZBin], repeats: usize, height_m: f64) -> Figure {
    let reps = repeats.max(1) as f64;
    let x_max = z_chart_x_max(bins, reps);
    let level = |label: &str, z_cm: f64, colour: Option<usize>| Drawn::Curve {
        label: label.to_string(),
        points: vec![(0.0, z_cm), (x_max, z_cm)],
        colour,
        dashed: false,
    };
    let mut items = vec![Drawn::Series {
        label: "simulation".into(),
        points: bins
            .iter()
            .map(|b| (b.count as f64 / reps, 50.0 * (b.z_lo_m + b.z_hi_m)))
            .collect(),
        colour: 0,
        filled: true,
        line: true,
        max_markers: 0,
    }];
    items.push(level("f-EDEM range 8.5–13.5 cm", 8.5, Some(3)));
    items.push(level("", 13.5, Some(3)));
    items.push(level("paste surface", height_m * 100.0, None));
    let panel = Panel {
        title: title.to_string(),
        x_label: "ball centres in the bin, mean per repeat (balls)".into(),
        y_label: "Z above the cylinder bottom (cm)".into(),
        x_log: false,
        y_log: false,
        x_range: Some((0.0, x_max)),
        y_range: None,
        x_categories: None,
        items,
    };
    Figure {
        title: title.to_string(),
        columns: 1,
        panels: vec![panel],
    }
}

/// Colour of a probability: white (0) to dark red (1).
fn heat(p: f64) -> RGBColor {
    let p = p.clamp(0.0, 1.0);
    let lerp = |a: f64, b: f64| (a + (b - a) * p).round() as u8;
    RGBColor(lerp(255.0, 140.0), lerp(255.0, 0.0), lerp(255.0, 0.0))
}

/// The presence maps, one panel per plane (3 per row), cells coloured by probability, with the
/// cylinder's circle (f-EDEM Fig. 22): the text of `presence.svg`.
pub fn presence_chart(
    title: &str,
    cells: &[PresenceCell],
    planes_z_m: &[f64],
    radius_m: f64,
    cell_m: f64,
) -> io::Result<String> {
    let mut text = String::new();
    draw_presence_chart(&mut text, title, cells, planes_z_m, radius_m, cell_m)?;
    Ok(text)
}

fn draw_presence_chart(
    text: &mut String,
    title: &str,
    cells: &[PresenceCell],
    planes_z_m: &[f64],
    radius_m: f64,
    cell_m: f64,
) -> io::Result<()> {
    let cols = planes_z_m.len().clamp(1, 3);
    let rows = planes_z_m.len().div_ceil(3).max(1);
    let root = SVGBackend::with_string(text, (360 * cols as u32, 380 * rows as u32 + 95))
        .into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let (top, body) = root.split_vertically(95);
    top.titled(title, ("sans-serif", 18)).map_err(err)?;
    top.draw(&Text::new(
        "colour: white 0 → dark red 1, the fraction of the repeats in which the point lies inside a ball",
        (10, 40),
        ("sans-serif", 12),
    ))
    .map_err(err)?;
    // Colour bar of the probability, 0 … 1.
    for i in 0..50 {
        let x = 10 + 5 * i;
        top.draw(&Rectangle::new(
            [(x, 55), (x + 5, 70)],
            heat((i as f64 + 0.5) / 50.0).filled(),
        ))
        .map_err(err)?;
    }
    top.draw(&Rectangle::new(
        [(10, 55), (260, 70)],
        BLACK.stroke_width(1),
    ))
    .map_err(err)?;
    for (p, x) in [(0.0, 10), (0.5, 135), (1.0, 260)] {
        top.draw(&Text::new(tick(p), (x - 4, 74), ("sans-serif", 12)))
            .map_err(err)?;
    }
    top.draw(&Text::new(
        "presence probability (-)",
        (275, 57),
        ("sans-serif", 12),
    ))
    .map_err(err)?;
    let panels = body.split_evenly((rows, cols));
    let r_mm = radius_m * 1e3;
    let h = 0.5 * cell_m * 1e3;
    for (area, &z) in panels.iter().zip(planes_z_m) {
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!("plane Z = {} cm above the bottom", tick(z * 100.0)),
                ("sans-serif", 15),
            )
            .margin(8)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d(-r_mm * 1.05..r_mm * 1.05, -r_mm * 1.05..r_mm * 1.05)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(5)
            .y_labels(5)
            .x_label_formatter(&|v| tick(*v))
            .y_label_formatter(&|v| tick(*v))
            .label_style(("sans-serif", 12))
            .axis_desc_style(("sans-serif", 13))
            .x_desc("x from the axis (mm)")
            .y_desc("y from the axis (mm)")
            .draw()
            .map_err(err)?;
        chart
            .draw_series(
                cells
                    .iter()
                    .filter(|c| c.plane_z_m == z && c.probability > 0.0)
                    .map(|c| {
                        let (x, y) = (c.x_m * 1e3, c.y_m * 1e3);
                        Rectangle::new(
                            [(x - h, y - h), (x + h, y + h)],
                            heat(c.probability).filled(),
                        )
                    }),
            )
            .map_err(err)?;
        let circle: Vec<(f64, f64)> = (0..=120)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 120.0;
                (r_mm * a.cos(), r_mm * a.sin())
            })
            .collect();
        chart
            .draw_series(std::iter::once(PathElement::new(circle, BLACK)))
            .map_err(err)?;
    }
    root.present().map_err(err)?;
    Ok(())
}

/// Adds every table and chart of a funnel pour to `out`.
pub fn fill(
    p: &Prepared,
    spec: &FunnelPourSpec,
    results: &[RepeatResult],
    out: &mut Outputs,
) -> Result<(), Error> {
    let s = &p.common;
    let f = &spec.funnel;
    let geo = Geometry::of(spec);
    let io = |e: io::Error| Error::Io(p.path.clone(), e);
    let reps = results.len();
    out.table(balls_table(results));
    out.table(counts_table(results, f.count_time_s));
    out.table(timeseries_table(results));
    // Balls count as in the paste once their lowest point is below the surface: bins up to
    // H + the largest radius.
    let r_max = results
        .iter()
        .flat_map(|r| &r.balls)
        .map(|b| 0.5 * b.diameter_m)
        .fold(0.0, f64::max);
    let bins = z_histogram(results, f.z_bin_m, geo.paste_height_m + r_max);
    out.table(z_distribution_table(&bins, reps));
    let title = format!(
        "{}: ball centres in the paste ({reps} repeat(s); f-EDEM Fig. 21)",
        s.name
    );
    let svg = z_chart(&title, &bins, reps, geo.paste_height_m).map_err(io)?;
    out.file("z_distribution.svg", svg);
    out.add_figure(
        "z_distribution.svg",
        z_figure(&title, &bins, reps, geo.paste_height_m),
    );
    if !f.planes_z_m.is_empty() {
        let cells = presence(results, &f.planes_z_m, geo.cylinder_radius_m, f.grid_cell_m);
        out.table(presence_table(&cells));
        let title = format!(
            "{}: presence probability on horizontal planes ({reps} repeat(s); f-EDEM Fig. 22)",
            s.name
        );
        let svg = presence_chart(
            &title,
            &cells,
            &f.planes_z_m,
            geo.cylinder_radius_m,
            f.grid_cell_m,
        )
        .map_err(io)?;
        out.file("presence.svg", svg);
    }
    Ok(())
}
