//! A chart's data, for a caller that draws it itself (the Python package's `plot`, with
//! matplotlib): what [`super::Chart`] would draw, as plain values.

use super::{Chart, Item, Scale};

/// One chart file: one panel, or the panels of a grid (small multiples).
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// The title above the panels (the panel's own title for a single chart).
    pub title: String,
    /// Panels per row.
    pub columns: usize,
    /// The panels, row by row.
    pub panels: Vec<Panel>,
}

/// One chart: its axes and what it draws, in legend order.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// Title.
    pub title: String,
    /// x axis label with its unit, e.g. `time (s)`.
    pub x_label: String,
    /// y axis label with its unit.
    pub y_label: String,
    /// Log₁₀ x axis.
    pub x_log: bool,
    /// Log₁₀ y axis.
    pub y_log: bool,
    /// Fixed x range, data units.
    pub x_range: Option<(f64, f64)>,
    /// Fixed y range, data units.
    pub y_range: Option<(f64, f64)>,
    /// A categorical x axis: category i at x = i.
    pub x_categories: Option<Vec<String>>,
    /// What is drawn.
    pub items: Vec<Drawn>,
}

/// What a panel draws.
#[derive(Clone, Debug, PartialEq)]
pub enum Drawn {
    /// Points with markers (filled: simulated, hollow: measured), joined by a line or not.
    Series {
        /// Legend label (empty: no entry).
        label: String,
        /// The points (x, y).
        points: Vec<(f64, f64)>,
        /// Palette index (category10).
        colour: usize,
        /// Filled markers.
        filled: bool,
        /// Joined by a line.
        line: bool,
        /// The most markers shown, evenly spaced (0: a marker on every point).
        max_markers: usize,
    },
    /// A reference line without markers.
    Curve {
        /// Legend label.
        label: String,
        /// The points (x, y), in drawing order.
        points: Vec<(f64, f64)>,
        /// Palette index, None for near-black.
        colour: Option<usize>,
        /// Dashed.
        dashed: bool,
    },
    /// A shaded band: (x, lower y, upper y).
    Band {
        /// Legend label.
        label: String,
        /// The points (x, lower, upper).
        points: Vec<(f64, f64, f64)>,
        /// Grey level, 0 (white) to 1 (black).
        shade: f64,
    },
}

impl Chart {
    /// What this chart draws, as plain values.
    pub fn panel(&self) -> Panel {
        let items = self
            .items
            .iter()
            .map(|it| match it {
                Item::Series(p) => Drawn::Series {
                    label: p.series.label.clone(),
                    points: p.series.points.clone(),
                    colour: p.series.colour,
                    filled: p.series.filled,
                    line: p.series.line,
                    max_markers: p.max_markers,
                },
                Item::Curve(c) => Drawn::Curve {
                    label: c.label.clone(),
                    points: c.points.clone(),
                    colour: c.colour,
                    dashed: c.dashed,
                },
                Item::Band(b) => Drawn::Band {
                    label: b.label.clone(),
                    points: b.points.clone(),
                    shade: b.shade,
                },
            })
            .collect();
        Panel {
            title: self.title.clone(),
            x_label: self.x.label.clone(),
            y_label: self.y.label.clone(),
            x_log: self.x.scale == Scale::Log,
            y_log: self.y.scale == Scale::Log,
            x_range: self.x.range,
            y_range: self.y.range,
            x_categories: self.x.categories.clone(),
            items,
        }
    }
}

impl Figure {
    /// The figure of one chart.
    pub fn single(c: &Chart) -> Self {
        Self {
            title: c.title.clone(),
            columns: 1,
            panels: vec![c.panel()],
        }
    }

    /// The figure of a grid of charts under `title`, `columns` per row.
    pub fn grid(title: &str, charts: &[Chart], columns: usize) -> Self {
        Self {
            title: title.to_string(),
            columns: columns.max(1),
            panels: charts.iter().map(Chart::panel).collect(),
        }
    }
}
