//! Drawing a [`Chart`] with plotters: title, data area with axes, legend panel on the right.

use super::ticks::{categorical, layout, AxisLayout};
use super::{Chart, Item, Marker, Plotted, Scale};
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::io;
use std::path::Path;

/// Ten clearly distinct colours (Tableau/d3 category10).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];
/// Text, axes and reference curves.
const INK: RGBColor = RGBColor(34, 34, 34);
const FONT: &str = "sans-serif";
// Font sizes as given to plotters, whose SVG backend writes them scaled by 1/1.24 (a title of 22
// is drawn at 17.7 px).
const TITLE_PX: u32 = 22;
const AXIS_PX: u32 = 18;
const TICK_PX: u32 = 16;
const LEGEND_PX: u32 = 16;
/// Average glyph width of the sans-serif font as drawn, as a fraction of the size given (with a
/// margin: 0.62 of the drawn size).
const GLYPH_W: f64 = 0.5;
/// Marker radius, px.
const R: i32 = 5;
/// Longest legend line, characters (longer labels wrap).
const LEGEND_CHARS: usize = 46;

fn palette(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

fn err(e: impl std::fmt::Display) -> io::Error {
    io::Error::other(e.to_string())
}

/// Pixel width of `chars` characters at font size `px`.
fn text_w(chars: usize, px: u32) -> u32 {
    (chars as f64 * GLYPH_W * px as f64).ceil() as u32
}

/// Words of `text` in lines of at most `max` characters (a longer word keeps its own line).
fn wrap(text: &str, max: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(l) if l.chars().count() + 1 + word.chars().count() <= max => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    if lines.is_empty() {
        lines.push(String::new());
    }
    lines
}

/// What a legend entry shows left of its label.
enum Sample {
    Marker {
        marker: Marker,
        colour: RGBColor,
        filled: bool,
        line: bool,
    },
    Curve {
        colour: RGBColor,
        dashed: bool,
    },
    Band(RGBColor),
}

struct Entry {
    lines: Vec<String>,
    sample: Sample,
}

fn grey(shade: f64) -> RGBColor {
    let v = (255.0 * (1.0 - shade.clamp(0.0, 1.0))).round() as u8;
    RGBColor(v, v, v)
}

fn curve_colour(c: Option<usize>) -> RGBColor {
    c.map(palette).unwrap_or(INK)
}

fn entries(c: &Chart) -> Vec<Entry> {
    c.items
        .iter()
        .map(|it| {
            let (label, sample) = match it {
                Item::Series(p) => (
                    &p.series.label,
                    Sample::Marker {
                        marker: p.marker,
                        colour: palette(p.series.colour),
                        filled: p.series.filled,
                        line: p.series.line,
                    },
                ),
                Item::Curve(k) => (
                    &k.label,
                    Sample::Curve {
                        colour: curve_colour(k.colour),
                        dashed: k.dashed,
                    },
                ),
                Item::Band(b) => (&b.label, Sample::Band(grey(b.shade))),
            };
            Entry {
                lines: wrap(label, LEGEND_CHARS),
                sample,
            }
        })
        .filter(|e| !e.lines[0].is_empty())
        .collect()
}

/// The layouts of both axes from every point the chart holds.
fn axes(c: &Chart) -> (AxisLayout, AxisLayout) {
    let mut xs = Vec::new();
    let mut ys = Vec::new();
    for it in &c.items {
        match it {
            Item::Series(p) => p.series.points.iter().for_each(|p| {
                if p.0.is_finite() && p.1.is_finite() {
                    xs.push(p.0);
                    ys.push(p.1);
                }
            }),
            Item::Curve(k) => k.points.iter().for_each(|p| {
                xs.push(p.0);
                ys.push(p.1);
            }),
            Item::Band(b) => b.points.iter().for_each(|p| {
                xs.push(p.0);
                ys.extend([p.1, p.2]);
            }),
        }
    }
    let lin = |s: Scale| s == Scale::Linear;
    let x = match &c.x.categories {
        Some(names) => categorical(names),
        None => layout(
            xs.into_iter(),
            c.x.scale,
            c.x.range,
            c.x.from_zero && lin(c.x.scale),
        ),
    };
    (
        x,
        layout(
            ys.into_iter(),
            c.y.scale,
            c.y.range,
            c.y.from_zero && lin(c.y.scale),
        ),
    )
}

/// A linear coordinate (drawing space) with the ticks of an [`AxisLayout`] as its key points.
struct Ticked {
    inner: RangedCoordf64,
    bold: Vec<f64>,
    light: Vec<f64>,
}

impl Ticked {
    fn of(a: &AxisLayout) -> Self {
        Self {
            inner: (a.lo..a.hi).into(),
            bold: a.ticks.clone(),
            light: a.minor.clone(),
        }
    }
}

impl Ranged for Ticked {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(value, limit)
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.light.clone()
        } else {
            self.bold.clone()
        }
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.inner.range()
    }
}

/// Points mapped to drawing space (log₁₀ on log axes); undrawable points dropped.
fn mapped(pts: &[(f64, f64)], xa: &AxisLayout, ya: &AxisLayout) -> Vec<(f64, f64)> {
    pts.iter()
        .filter_map(|&(x, y)| Some((xa.to_draw(x)?, ya.to_draw(y)?)))
        .collect()
}

/// Where the parts of a chart go: legend entries and sizes, title lines, total size (px).
struct Frame {
    legend: Vec<Entry>,
    legend_w: u32,
    line_h: i32,
    title: Vec<String>,
    title_h: u32,
    size: (u32, u32),
}

fn frame(c: &Chart) -> Frame {
    let legend = entries(c);
    let line_h = LEGEND_PX as i32 + 4;
    let legend_w = legend
        .iter()
        .flat_map(|e| e.lines.iter().map(|l| l.chars().count()))
        .max()
        .map(|n| text_w(n, LEGEND_PX) + 76)
        .unwrap_or(20);
    let legend_h: i32 = legend
        .iter()
        .map(|e| e.lines.len() as i32 * line_h + 8)
        .sum::<i32>()
        + 24;
    let (pw, ph) = c.plot_size;
    let w = pw + legend_w;
    let title = title_lines(&c.title, w);
    let title_h = title.len() as u32 * (TITLE_PX + 6) + 14;
    let h = ph.max(legend_h as u32 + 20) + title_h;
    Frame {
        legend,
        legend_w,
        line_h,
        title,
        title_h,
        size: (w, h),
    }
}

fn title_lines(title: &str, width: u32) -> Vec<String> {
    wrap(
        title,
        ((width as f64 / (GLYPH_W * TITLE_PX as f64)) as usize).max(24) - 4,
    )
}

/// Writes title lines centred at the top of `area`.
fn draw_title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    lines: &[String],
) -> io::Result<()> {
    let w = area.dim_in_pixel().0;
    for (i, line) in lines.iter().enumerate() {
        let style = TextStyle::from((FONT, TITLE_PX).into_font())
            .color(&INK)
            .pos(Pos::new(HPos::Center, VPos::Top));
        let y = 10 + i as i32 * (TITLE_PX as i32 + 6);
        area.draw(&Text::new(line.clone(), ((w / 2) as i32, y), style))
            .map_err(err)?;
    }
    Ok(())
}

/// Draws `c` (title, data area, legend) in `area`, laid out as `f`.
fn draw_chart<DB: DrawingBackend>(
    c: &Chart,
    f: &Frame,
    area: &DrawingArea<DB, Shift>,
) -> io::Result<()> {
    let (xa, ya) = axes(c);
    draw_title(area, &f.title)?;
    let (_, body) = area.split_vertically(f.title_h);
    let (plot, legend_area) = body.split_horizontally(c.plot_size.0);
    data_area(c, area, &plot, &xa, &ya)?;
    draw_legend(&legend_area, &f.legend, f.legend_w as i32, f.line_h)
}

/// Draws `c` as SVG at `path`.
pub fn svg(c: &Chart, path: &Path) -> io::Result<()> {
    std::fs::write(path, svg_string(c)?)
}

/// Draws `c` as the text of an SVG file.
pub fn svg_string(c: &Chart) -> io::Result<String> {
    let f = frame(c);
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, f.size).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        draw_chart(c, &f, &root)?;
        root.present().map_err(err)?;
    }
    Ok(text)
}

/// Draws `charts` as panels of one SVG file's text, `columns` per row, under `title`; every
/// panel gets the size of the largest.
pub fn grid_svg_string(title: &str, charts: &[Chart], columns: usize) -> io::Result<String> {
    let frames: Vec<Frame> = charts.iter().map(frame).collect();
    let cols = columns.clamp(1, charts.len().max(1));
    let rows = charts.len().div_ceil(cols).max(1);
    let cell = frames
        .iter()
        .fold((1, 1), |(w, h), f| (w.max(f.size.0), h.max(f.size.1)));
    let width = cell.0 * cols as u32;
    let lines = title_lines(title, width);
    let title_h = lines.len() as u32 * (TITLE_PX + 6) + 14;
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, (width, title_h + cell.1 * rows as u32))
            .into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        draw_title(&root, &lines)?;
        let (_, body) = root.split_vertically(title_h);
        for (k, (c, f)) in charts.iter().zip(&frames).enumerate() {
            let (r, q) = ((k / cols) as i32, (k % cols) as i32);
            let (x0, y0) = (q * cell.0 as i32, r * cell.1 as i32);
            let panel = body.clone().shrink((x0, y0), f.size);
            draw_chart(c, f, &panel)?;
        }
        root.present().map_err(err)?;
    }
    Ok(text)
}

/// The axes, grid, bands, curves and series of `c` in `plot`; markers drawn on `root` in pixels.
fn data_area<DB: DrawingBackend>(
    c: &Chart,
    root: &DrawingArea<DB, Shift>,
    plot: &DrawingArea<DB, Shift>,
    xa: &AxisLayout,
    ya: &AxisLayout,
) -> io::Result<()> {
    let longest_y = ya.labels.iter().map(|l| l.chars().count()).max();
    let y_area = text_w(longest_y.unwrap_or(1), TICK_PX) + AXIS_PX + 28;
    let mut cc = ChartBuilder::on(plot)
        .margin(14)
        .margin_right(24)
        .x_label_area_size(TICK_PX + AXIS_PX + 30)
        .y_label_area_size(y_area)
        .build_cartesian_2d(Ticked::of(xa), Ticked::of(ya))
        .map_err(err)?;
    // Bands first, opaque, under the grid.
    for it in &c.items {
        if let Item::Band(b) = it {
            let upper: Vec<(f64, f64)> = b.points.iter().map(|p| (p.0, p.2)).collect();
            let lower: Vec<(f64, f64)> = b.points.iter().rev().map(|p| (p.0, p.1)).collect();
            let mut poly = mapped(&upper, xa, ya);
            poly.extend(mapped(&lower, xa, ya));
            cc.draw_series(std::iter::once(Polygon::new(poly, grey(b.shade).filled())))
                .map_err(err)?;
        }
    }
    let fmt_x = |v: &f64| xa.label_at(*v);
    let fmt_y = |v: &f64| ya.label_at(*v);
    cc.configure_mesh()
        .x_desc(c.x.label.as_str())
        .y_desc(c.y.label.as_str())
        .x_label_formatter(&fmt_x)
        .y_label_formatter(&fmt_y)
        .label_style((FONT, TICK_PX).into_font().color(&INK))
        .axis_desc_style((FONT, AXIS_PX).into_font().color(&INK))
        .axis_style(INK)
        .bold_line_style(BLACK.mix(0.16))
        .light_line_style(BLACK.mix(0.05))
        .draw()
        .map_err(err)?;
    // Series lines, then reference curves over them (a dashed analytic curve stays visible on
    // the line it matches), then markers on top.
    for it in &c.items {
        if let Item::Series(Plotted { series: s, .. }) = it {
            if s.line {
                let pts = mapped(&s.points, xa, ya);
                cc.draw_series(LineSeries::new(pts, palette(s.colour).stroke_width(2)))
                    .map_err(err)?;
            }
        }
    }
    for it in &c.items {
        if let Item::Curve(k) = it {
            let style = curve_colour(k.colour).stroke_width(2);
            let pts = mapped(&k.points, xa, ya);
            if k.dashed {
                cc.draw_series(DashedLineSeries::new(pts, 9, 6, style))
                    .map_err(err)?;
            } else {
                cc.draw_series(LineSeries::new(pts, style)).map_err(err)?;
            }
        }
    }
    // Markers are drawn in pixels on `root`, whose origin is at `base` on the backend.
    let base = root.get_base_pixel();
    let inside = |(x, y): (f64, f64)| {
        x >= xa.lo.min(xa.hi)
            && x <= xa.hi.max(xa.lo)
            && y >= ya.lo.min(ya.hi)
            && y <= ya.hi.max(ya.lo)
    };
    for it in &c.items {
        if let Item::Series(p) = it {
            let s = &p.series;
            let pts = mapped(&s.points, xa, ya);
            let every = match p.max_markers {
                0 => 1,
                n => pts.len().div_ceil(n).max(1),
            };
            // Offset by colour so thinned markers of overlapping lines do not coincide.
            let skip = if every > 1 { s.colour % every } else { 0 };
            for q in pts.into_iter().skip(skip).step_by(every) {
                if inside(q) {
                    let (px, py) = cc.backend_coord(&q);
                    let at = (px - base.0, py - base.1);
                    marker(root, p.marker, at, palette(s.colour), s.filled)?;
                }
            }
        }
    }
    Ok(())
}

/// Vertices of a regular polygon of `n` corners and radius `r` about `c`, the first at angle
/// `start` (degrees, clockwise from +x on screen); `inner` > 0 makes a star.
fn polygon(c: (i32, i32), n: usize, r: f64, start: f64, inner: f64) -> Vec<(i32, i32)> {
    let k = if inner > 0.0 { 2 * n } else { n };
    (0..k)
        .map(|i| {
            let a = (start + 360.0 * i as f64 / k as f64).to_radians();
            let rr = if inner > 0.0 && i % 2 == 1 { inner } else { r };
            (
                c.0 + (rr * a.cos()).round() as i32,
                c.1 + (rr * a.sin()).round() as i32,
            )
        })
        .collect()
}

/// Draws one marker at pixel `c` on `area`.
fn marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    m: Marker,
    c: (i32, i32),
    colour: RGBColor,
    filled: bool,
) -> io::Result<()> {
    let r = R as f64;
    let stroke = colour.stroke_width(2);
    let corners = match m {
        Marker::None => return Ok(()),
        Marker::Circle => {
            let style = if filled { colour.filled() } else { stroke };
            return area.draw(&Circle::new(c, R, style)).map_err(err);
        }
        Marker::Plus | Marker::Cross => {
            let s = if m == Marker::Plus { R + 1 } else { R };
            let (a, b) = if m == Marker::Plus {
                (
                    [(c.0 - s, c.1), (c.0 + s, c.1)],
                    [(c.0, c.1 - s), (c.0, c.1 + s)],
                )
            } else {
                (
                    [(c.0 - s, c.1 - s), (c.0 + s, c.1 + s)],
                    [(c.0 - s, c.1 + s), (c.0 + s, c.1 - s)],
                )
            };
            let st = colour.stroke_width(if filled { 3 } else { 2 });
            area.draw(&PathElement::new(a.to_vec(), st)).map_err(err)?;
            return area.draw(&PathElement::new(b.to_vec(), st)).map_err(err);
        }
        Marker::Square => polygon(c, 4, r * 1.25, 45.0, 0.0),
        Marker::TriangleUp => polygon(c, 3, r * 1.35, -90.0, 0.0),
        Marker::TriangleDown => polygon(c, 3, r * 1.35, 90.0, 0.0),
        Marker::Diamond => polygon(c, 4, r * 1.35, -90.0, 0.0),
        Marker::Star => polygon(c, 5, r * 1.5, -90.0, r * 0.65),
        Marker::Pentagon => polygon(c, 5, r * 1.3, -90.0, 0.0),
        Marker::Hexagon => polygon(c, 6, r * 1.25, 0.0, 0.0),
    };
    if filled {
        area.draw(&Polygon::new(corners.clone(), colour.filled()))
            .map_err(err)?;
    }
    let mut closed = corners.clone();
    closed.push(corners[0]);
    area.draw(&PathElement::new(closed, stroke)).map_err(err)
}

/// The legend panel: a frame with one sample and label per entry.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    legend: &[Entry],
    width: i32,
    line_h: i32,
) -> io::Result<()> {
    if legend.is_empty() {
        return Ok(());
    }
    let top = 14;
    let mut y = top + 10;
    let style = TextStyle::from((FONT, LEGEND_PX).into_font())
        .color(&INK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    let mut rows = Vec::new();
    for e in legend {
        let first = y + line_h / 2;
        rows.push((first, e));
        y += e.lines.len() as i32 * line_h + 8;
    }
    area.draw(&Rectangle::new(
        [(4, top), (width - 12, y)],
        BLACK.mix(0.35).stroke_width(1),
    ))
    .map_err(err)?;
    for (cy, e) in rows {
        let (x0, x1) = (14, 46);
        match e.sample {
            Sample::Marker {
                marker: m,
                colour,
                filled,
                line,
            } => {
                if line {
                    area.draw(&PathElement::new(
                        vec![(x0, cy), (x1, cy)],
                        colour.stroke_width(2),
                    ))
                    .map_err(err)?;
                }
                marker(area, m, ((x0 + x1) / 2, cy), colour, filled)?;
            }
            Sample::Curve { colour, dashed } => {
                let style = colour.stroke_width(2);
                if dashed {
                    for (a, b) in [(x0, x0 + 9), (x0 + 14, x0 + 23), (x0 + 28, x1)] {
                        area.draw(&PathElement::new(vec![(a, cy), (b, cy)], style))
                            .map_err(err)?;
                    }
                } else {
                    area.draw(&PathElement::new(vec![(x0, cy), (x1, cy)], style))
                        .map_err(err)?;
                }
            }
            Sample::Band(colour) => {
                area.draw(&Rectangle::new(
                    [(x0, cy - 7), (x1, cy + 7)],
                    colour.filled(),
                ))
                .map_err(err)?;
            }
        }
        for (i, l) in e.lines.iter().enumerate() {
            area.draw(&Text::new(
                l.clone(),
                (x1 + 10, cy + i as i32 * line_h),
                style.clone(),
            ))
            .map_err(err)?;
        }
    }
    Ok(())
}
