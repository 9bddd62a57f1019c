//! SVG charts (plotters), one look for every chart settle draws.
//!
//! A chart has a title, axis labels with units, tick labels with the digits the axis needs
//! ([`ticks`]), and a legend in a panel right of the data. Series get clearly distinct colours
//! (the ten of Tableau/d3 *category10*) and marker shapes ([`Marker`]); measured points are
//! hollow, simulated ones filled. Reference curves ([`Curve`]: analytic laws, parity lines) are
//! lines without markers; shaded bands ([`Band`]) mark tolerances (e.g. ±10 % around parity).
//!
//! [`Chart`] is the builder of a chart of [`Series`], with the curves, bands, fixed ranges and
//! marker shapes a chart may need (a crate-internal module, so the example is not a doctest):
//!
//! ```ignore
//! use crate::io::chart::{Chart, Curve, Scale, Series};
//! let pts = vec![(1.0, 2.0), (2.0, 4.1)];
//! Chart::new("velocity against time")
//!     .x("time (s)", Scale::Linear)
//!     .y("velocity (m/s)", Scale::Linear)
//!     .series(Series::sorted_line("simulated".into(), pts, 0))
//!     .curve(Curve::new("analytic", vec![(0.0, 0.0), (2.0, 4.0)]))
//!     .svg(std::path::Path::new("v.svg"))
//!     .unwrap();
//! ```

pub mod data;
mod draw;
pub mod read;
pub mod ticks;

pub use read::svg_texts;

use std::path::Path;

/// One series of a scatter chart.
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points (x, y).
    pub points: Vec<(f64, f64)>,
    /// Colour index (series with the same index share a colour, and a marker shape unless
    /// [`Chart::series_marked`] sets one).
    pub colour: usize,
    /// Filled markers (simulated) or hollow ones (measured).
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
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Scale {
    /// Linear axis.
    Linear,
    /// Log₁₀ axis.
    Log,
}

/// Marker shapes, in the order series take them by colour index.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Marker {
    /// ●
    Circle,
    /// ■
    Square,
    /// ▲
    TriangleUp,
    /// ◆
    Diamond,
    /// ▼
    TriangleDown,
    /// ★
    Star,
    /// ⬟
    Pentagon,
    /// ⬢
    Hexagon,
    /// +
    Plus,
    /// ×
    Cross,
    /// No marker (a line only).
    None,
}

impl Marker {
    /// The shapes series take in turn (each has a hollow and a filled form).
    pub const CYCLE: [Marker; 8] = [
        Marker::Circle,
        Marker::Square,
        Marker::TriangleUp,
        Marker::Diamond,
        Marker::TriangleDown,
        Marker::Star,
        Marker::Pentagon,
        Marker::Hexagon,
    ];

    /// The shape of colour index `i`.
    pub fn nth(i: usize) -> Marker {
        Self::CYCLE[i % Self::CYCLE.len()]
    }
}

/// A reference curve: a line without markers (an analytic law, a parity line, a threshold).
pub struct Curve {
    /// Legend label.
    pub label: String,
    /// Points (x, y), drawn in the given order.
    pub points: Vec<(f64, f64)>,
    /// Colour index, or None for near-black.
    pub colour: Option<usize>,
    /// Dashed line.
    pub dashed: bool,
}

impl Curve {
    /// A solid near-black curve through `points`.
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            label: label.into(),
            points,
            colour: None,
            dashed: false,
        }
    }

    /// The same curve dashed.
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }

    /// The same curve in palette colour `i`.
    pub fn colour(mut self, i: usize) -> Self {
        self.colour = Some(i);
        self
    }
}

/// A shaded band between two curves sharing their x: (x, lower y, upper y).
pub struct Band {
    /// Legend label.
    pub label: String,
    /// Points (x, lower, upper), sorted by x.
    pub points: Vec<(f64, f64, f64)>,
    /// Grey level of the shade: 0 (white) to 1 (black), e.g. 0.12 light, 0.25 darker.
    pub shade: f64,
}

/// A series as drawn: its marker shape and the most markers it shows (all when 0).
struct Plotted {
    series: Series,
    marker: Marker,
    max_markers: usize,
}

/// What a chart draws, in the order it was added (legend order; an empty label has no entry).
enum Item {
    Series(Plotted),
    Curve(Curve),
    Band(Band),
}

/// One axis: label (with unit), scale, optional fixed range, start at zero when reasonable, and
/// the names of its categories (a categorical axis: category i at x = i).
struct AxisSpec {
    label: String,
    scale: Scale,
    range: Option<(f64, f64)>,
    from_zero: bool,
    categories: Option<Vec<String>>,
}

/// A chart under construction; [`Chart::svg`] draws it.
pub struct Chart {
    title: String,
    x: AxisSpec,
    y: AxisSpec,
    items: Vec<Item>,
    plot_size: (u32, u32),
}

impl Chart {
    /// An empty chart titled `title`: linear axes, a y axis starting at zero when its data are
    /// positive and the smallest is at most half the largest (else ±10 % at least).
    pub fn new(title: impl Into<String>) -> Self {
        let axis = |from_zero| AxisSpec {
            label: String::new(),
            scale: Scale::Linear,
            range: None,
            from_zero,
            categories: None,
        };
        Self {
            title: title.into(),
            x: axis(false),
            y: axis(true),
            items: Vec::new(),
            plot_size: (760, 540),
        }
    }

    /// The x axis: label with its unit in brackets, e.g. `time (s)`, and scale.
    pub fn x(mut self, label: impl Into<String>, scale: Scale) -> Self {
        self.x.label = label.into();
        self.x.scale = scale;
        self
    }

    /// A categorical x axis: label with its unit in brackets, and the names of the categories,
    /// category i drawn at x = i and labelled with its name (the x range is −0.5 … n − 0.5).
    pub fn x_categories(
        mut self,
        label: impl Into<String>,
        names: impl IntoIterator<Item = String>,
    ) -> Self {
        self.x.label = label.into();
        self.x.scale = Scale::Linear;
        self.x.categories = Some(names.into_iter().collect());
        self
    }

    /// The y axis: label with its unit in brackets, and scale.
    pub fn y(mut self, label: impl Into<String>, scale: Scale) -> Self {
        self.y.label = label.into();
        self.y.scale = scale;
        self
    }

    /// Fixes the x range (data units).
    pub fn x_range(mut self, lo: f64, hi: f64) -> Self {
        self.x.range = Some((lo, hi));
        self
    }

    /// Fixes the y range (data units).
    pub fn y_range(mut self, lo: f64, hi: f64) -> Self {
        self.y.range = Some((lo, hi));
        self
    }

    /// Whether a positive linear y axis may start at zero (default true).
    pub fn y_from_zero(mut self, yes: bool) -> Self {
        self.y.from_zero = yes;
        self
    }

    /// Whether a positive linear x axis may start at zero (default false).
    pub fn x_from_zero(mut self, yes: bool) -> Self {
        self.x.from_zero = yes;
        self
    }

    /// Size of the data area with its axes, pixels (the legend panel is added to the right).
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.plot_size = (width, height);
        self
    }

    /// Adds a series; its marker shape follows its colour index ([`Marker::nth`]).
    pub fn series(self, s: Series) -> Self {
        let m = Marker::nth(s.colour);
        self.series_marked(s, m)
    }

    /// Adds several series.
    pub fn all_series(self, all: impl IntoIterator<Item = Series>) -> Self {
        all.into_iter().fold(self, Chart::series)
    }

    /// Adds a series with marker shape `marker` (e.g. colour per integrator, shape per quantity).
    pub fn series_marked(mut self, s: Series, marker: Marker) -> Self {
        self.items.push(Item::Series(Plotted {
            series: s,
            marker,
            max_markers: 0,
        }));
        self
    }

    /// Adds a dense series (a time series): its line through every point, its markers (shape by
    /// colour index) on at most `max_markers` evenly spaced points so lines stay apart.
    pub fn series_thinned(mut self, s: Series, max_markers: usize) -> Self {
        self.items.push(Item::Series(Plotted {
            marker: Marker::nth(s.colour),
            series: s,
            max_markers,
        }));
        self
    }

    /// Adds a reference curve (a line, no markers).
    pub fn curve(mut self, c: Curve) -> Self {
        self.items.push(Item::Curve(c));
        self
    }

    /// Adds a shaded band.
    pub fn band(mut self, b: Band) -> Self {
        self.items.push(Item::Band(b));
        self
    }

    /// Draws the chart as SVG at `path`; a drawing failure is an [`std::io::Error`] of kind
    /// `Other` (the caller names the path).
    pub fn svg(&self, path: &Path) -> std::io::Result<()> {
        draw::svg(self, path)
    }

    /// Draws the chart as the text of an SVG file.
    pub fn svg_string(&self) -> std::io::Result<String> {
        draw::svg_string(self)
    }
}

/// Draws `charts` as panels of one SVG file's text (small multiples, like the six panels of
/// f-EDEM Fig. 11), `columns` per row under the common `title`, each panel with its own title,
/// axes and legend; a drawing failure is an [`std::io::Error`] of kind `Other`.
pub fn grid_svg_string(title: &str, charts: &[Chart], columns: usize) -> std::io::Result<String> {
    draw::grid_svg_string(title, charts, columns)
}
