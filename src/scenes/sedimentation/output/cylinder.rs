//! Seed 000 Fig. 11: the cylinder at the snapshot times (default 60, 300 and 900 s), as
//! `cylinder.csv` and `cylinder.svg`. The grey level of a horizontal band is the mass of the
//! grains suspended in it as a fraction of the whole sample's mass (seed: "the proportion of mass
//! with respect to the total mass", averaged over bands of layers); the deposited bed is drawn
//! apart, in brown, to its height, with its own mass fraction.

use super::plot::{err, time_text};
use super::Snapshot;
use crate::io::fmt::{num, sig_shortest};
use crate::io::Table;
use crate::scenes::sedimentation::setup::Setup;
use crate::scenes::sedimentation::state::{State, PICTURE_BANDS};
use plotters::prelude::*;
use std::io;

/// The cylinder at one time: suspended mass per band and the bed.
#[derive(Clone, Debug, PartialEq)]
pub struct CylinderPanel {
    /// Time, s.
    pub time_s: f64,
    /// Mass of the suspended grains in each band (top first, bands of H / [`PICTURE_BANDS`]) as
    /// a fraction of the modelled sample's mass (bed included), -.
    pub suspended_fraction: Vec<f64>,
    /// Bed height, m.
    pub bed_height_m: f64,
    /// Mass in the bed as a fraction of the sample's mass, -.
    pub bed_fraction: f64,
}

impl CylinderPanel {
    /// The panel of the state `st` in the cylinder of `setup`, over `bands` bands.
    pub fn of(st: &State, setup: &Setup, bands: usize) -> Self {
        let mut f = vec![0.0; bands];
        let (mut total, mut bed) = (0.0, 0.0);
        let grains = &setup.grains;
        let volumes: Vec<f64> = grains.kinds.iter().map(|k| k.volume_m3()).collect();
        for ((&y, &settled), &kind) in st.y_m.iter().zip(&st.settled).zip(&grains.kind) {
            let v = volumes[kind as usize];
            total += v;
            if settled {
                bed += v;
                continue;
            }
            let depth = (setup.height_m - y) / setup.height_m;
            f[((depth * bands as f64).max(0.0) as usize).min(bands - 1)] += v;
        }
        let total = if total > 0.0 { total } else { 1.0 };
        f.iter_mut().for_each(|x| *x /= total);
        Self {
            time_s: st.time_s,
            suspended_fraction: f,
            bed_height_m: st.bed_height_m,
            bed_fraction: bed / total,
        }
    }
}

/// The panels of the snapshots, [`PICTURE_BANDS`] bands each.
pub fn panels(snapshots: &[Snapshot], setup: &Setup) -> Vec<CylinderPanel> {
    snapshots
        .iter()
        .map(|sn| CylinderPanel::of(&sn.state(), setup, PICTURE_BANDS))
        .collect()
}

/// `cylinder.csv`: per snapshot time and band (top first) the band's depth range, the suspended
/// mass fraction it holds (the grey level of `cylinder.svg`), and the bed's height and mass
/// fraction at that time.
pub fn table(panels: &[CylinderPanel], height_m: f64) -> Table {
    let mut rows = Vec::new();
    for p in panels {
        let n = p.suspended_fraction.len() as f64;
        for (k, f) in p.suspended_fraction.iter().enumerate() {
            rows.push(vec![
                num(p.time_s),
                num(p.time_s / 60.0),
                k.to_string(),
                num(k as f64 / n * height_m),
                num((k + 1) as f64 / n * height_m),
                num(*f),
                num(p.bed_height_m),
                num(p.bed_fraction),
            ]);
        }
    }
    Table::with_rows(
        "cylinder.csv",
        [
            "time_s",
            "time_min",
            "band",
            "depth_top_m",
            "depth_bottom_m",
            "suspended_mass_fraction",
            "bed_height_m",
            "bed_mass_fraction",
        ],
        rows,
    )
}

const BED: RGBColor = RGBColor(150, 105, 55);

/// Grey of a mass fraction on the scale 0 (white) … `max` (black).
fn grey(f: f64, max: f64) -> RGBColor {
    let g = (255.0 * (1.0 - (f / max).clamp(0.0, 1.0))).round() as u8;
    RGBColor(g, g, g)
}

/// Draws `cylinder.svg` (its text): one panel per snapshot time (depth in cm, width in cm), the
/// grey scale of the suspended mass fraction per band (in % of the sample, shared by the panels)
/// and the bed in brown, with its height and mass fraction listed beside the scale.
pub fn svg(
    title: &str,
    panels: &[CylinderPanel],
    width_m: f64,
    height_m: f64,
) -> io::Result<String> {
    let mut text = String::new();
    {
        let n = panels.len().max(1);
        let root =
            SVGBackend::with_string(&mut text, (230 * n as u32 + 330, 800)).into_drawing_area();
        draw(&root, title, panels, width_m, height_m)?;
        root.present().map_err(err)?;
    }
    Ok(text)
}

/// The panels and the scale of `cylinder.svg` on `root`.
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    panels: &[CylinderPanel],
    width_m: f64,
    height_m: f64,
) -> io::Result<()> {
    let n = panels.len().max(1);
    root.fill(&WHITE).map_err(err)?;
    let (top, body) = root.split_vertically(50);
    top.titled(title, ("sans-serif", 20)).map_err(err)?;
    let (left, right) = body.split_horizontally(230 * n as u32);
    let max = panels
        .iter()
        .flat_map(|p| p.suspended_fraction.iter().copied())
        .fold(1e-12, f64::max);
    let (b_cm, h_cm) = (width_m * 100.0, height_m * 100.0);
    for (area, p) in left.split_evenly((1, n)).iter().zip(panels) {
        let mut chart = ChartBuilder::on(area)
            .caption(time_text(p.time_s), ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..b_cm, -h_cm..0.0)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(3)
            .y_labels(10)
            .x_label_formatter(&|v| sig_shortest(*v, 3))
            .y_label_formatter(&|v| sig_shortest(-*v, 3))
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .x_desc("width (cm)")
            .y_desc("depth below the surface (cm)")
            .draw()
            .map_err(err)?;
        let bands = p.suspended_fraction.len() as f64;
        chart
            .draw_series(p.suspended_fraction.iter().enumerate().map(|(k, f)| {
                // Each band reaches a third into the next, drawn over it, so no hairline seam shows.
                let y0 = -(k as f64) / bands * h_cm;
                let y1 = (-(k as f64 + 1.3) / bands * h_cm).max(-h_cm);
                Rectangle::new([(0.0, y0), (b_cm, y1)], grey(*f, max).filled())
            }))
            .map_err(err)?;
        let bed_top = -h_cm + p.bed_height_m * 100.0;
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(0.0, -h_cm), (b_cm, bed_top)],
                BED.filled(),
            )))
            .map_err(err)?;
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(0.0, -h_cm), (b_cm, 0.0)],
                BLACK.stroke_width(1),
            )))
            .map_err(err)?;
    }
    draw_scale(&right, panels, max, height_m)
}

/// The grey scale (a colour bar in % of the sample's mass per band) and the bed's legend.
fn draw_scale<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    panels: &[CylinderPanel],
    max: f64,
    height_m: f64,
) -> io::Result<()> {
    let (bar, notes) = area.split_vertically(480);
    let max_pct = max * 100.0;
    let mut chart = ChartBuilder::on(&bar)
        .caption("grey scale", ("sans-serif", 15))
        .margin(20)
        .margin_right(170)
        .y_label_area_size(75)
        .build_cartesian_2d(0.0..1.0, 0.0..max_pct)
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_labels(6)
        .y_label_formatter(&|v| sig_shortest(*v, 3))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 14))
        .y_desc("suspended mass fraction per band (%)")
        .draw()
        .map_err(err)?;
    let steps = 60;
    chart
        .draw_series((0..steps).map(|i| {
            let (a, b) = (i as f64 / steps as f64, (i + 1) as f64 / steps as f64);
            Rectangle::new(
                [
                    (0.0, a * max_pct),
                    (1.0, (b + 0.3 / steps as f64).min(1.0) * max_pct),
                ],
                grey(0.5 * (a + b) * max, max).filled(),
            )
        }))
        .map_err(err)?;
    let band_mm = height_m / PICTURE_BANDS as f64 * 1e3;
    let mut lines = vec![
        format!("band: {} mm of depth;", sig_shortest(band_mm, 3)),
        "fraction of the sample's mass".to_string(),
        "held by suspended grains.".to_string(),
        String::new(),
        "brown: the bed (deposited grains)".to_string(),
    ];
    lines.extend(panels.iter().map(|p| {
        format!(
            "{}: {} cm high, {} % of the mass",
            time_text(p.time_s).trim_start_matches("t = "),
            sig_shortest(p.bed_height_m * 100.0, 3),
            sig_shortest(p.bed_fraction * 100.0, 3)
        )
    }));
    notes
        .draw(&Rectangle::new([(20, 82), (44, 96)], BED.filled()))
        .map_err(err)?;
    for (i, l) in lines.iter().enumerate() {
        notes
            .draw(&Text::new(
                l.clone(),
                (if i == 4 { 50 } else { 20 }, 82 + 18 * (i as i32 - 4)),
                ("sans-serif", 13),
            ))
            .map_err(err)?;
    }
    Ok(())
}
