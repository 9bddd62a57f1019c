//! SVG charts (plotters).

use plotters::prelude::*;
use std::path::Path;

/// One series of a scatter chart.
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points (x, y).
    pub points: Vec<(f64, f64)>,
    /// Colour index (series with the same index share a colour).
    pub colour: usize,
    /// Filled markers (simulated) or hollow circles (measured).
    pub filled: bool,
    /// Join the points with a line.
    pub line: bool,
}

impl Series {
    /// A line through `points` sorted by x, with filled markers.
    pub fn sorted_line(label: String, mut points: Vec<(f64, f64)>, colour: usize) -> Self {
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        Self {
            label,
            points,
            colour,
            filled: true,
            line: true,
        }
    }
}

/// Axis scale.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// Linear axis.
    Linear,
    /// Log₁₀ axis.
    Log,
}

/// Draws a scatter/line chart as SVG at `path`; a drawing failure is an [`std::io::Error`] of kind
/// `Other` (the caller names the path).
pub fn scatter_svg(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    x_scale: Scale,
    y_scale: Scale,
    series: &[Series],
) -> std::io::Result<()> {
    let pts = series.iter().flat_map(|s| s.points.iter().copied());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in pts {
        if !(x.is_finite() && y.is_finite()) {
            continue;
        }
        if (x_scale == Scale::Log && x <= 0.0) || (y_scale == Scale::Log && y <= 0.0) {
            continue;
        }
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if x0 > x1 {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let pad = |lo: f64, hi: f64, s: Scale| match s {
        Scale::Linear => {
            let p = 0.05 * (hi - lo).max(1e-12);
            (lo - p, hi + p)
        }
        Scale::Log => (lo / 1.5, hi * 1.5),
    };
    let (x0, x1) = pad(x0, x1, x_scale);
    let (y0, y1) = pad(y0, y1, y_scale);
    let root = SVGBackend::new(path, (900, 600)).into_drawing_area();
    let e = |e: &dyn std::fmt::Display| std::io::Error::other(e.to_string());
    root.fill(&WHITE).map_err(|x| e(&x))?;
    macro_rules! draw {
        ($xr:expr, $yr:expr) => {{
            let mut chart = ChartBuilder::on(&root)
                .caption(title, ("sans-serif", 22))
                .margin(15)
                .x_label_area_size(45)
                .y_label_area_size(70)
                .build_cartesian_2d($xr, $yr)
                .map_err(|x| e(&x))?;
            chart
                .configure_mesh()
                .x_desc(x_label)
                .y_desc(y_label)
                .draw()
                .map_err(|x| e(&x))?;
            for s in series {
                let col = Palette99::pick(s.colour).to_rgba();
                let pts: Vec<(f64, f64)> = s
                    .points
                    .iter()
                    .copied()
                    .filter(|(x, y)| x.is_finite() && y.is_finite())
                    .collect();
                if s.line {
                    chart
                        .draw_series(LineSeries::new(pts.clone(), col.stroke_width(2)))
                        .map_err(|x| e(&x))?;
                }
                let style = if s.filled {
                    col.filled()
                } else {
                    col.stroke_width(2)
                };
                chart
                    .draw_series(pts.iter().map(|p| Circle::new(*p, 5, style)))
                    .map_err(|x| e(&x))?
                    .label(s.label.clone())
                    .legend(move |(x, y)| Circle::new((x, y), 5, style));
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .draw()
                .map_err(|x| e(&x))?;
        }};
    }
    match (x_scale, y_scale) {
        (Scale::Linear, Scale::Linear) => draw!(x0..x1, y0..y1),
        (Scale::Log, Scale::Linear) => draw!((x0..x1).log_scale(), y0..y1),
        (Scale::Linear, Scale::Log) => draw!(x0..x1, (y0..y1).log_scale()),
        (Scale::Log, Scale::Log) => draw!((x0..x1).log_scale(), (y0..y1).log_scale()),
    }
    root.present().map_err(|x| e(&x))?;
    Ok(())
}
