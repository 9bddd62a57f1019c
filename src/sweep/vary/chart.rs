//! What a person reads of a parameter sweep: one chart per result quantity against the first
//! varied key (one series per body, and per value of the other keys), and one console line per
//! case. A categorical first key (words such as `off`, `basset`) gets one x position per value,
//! labelled with it, and markers without lines, the series side by side at each position.

use super::grid::Level;
use super::table::VaryTable;
use crate::error::Error;
use crate::io::chart::{Chart, Scale, Series};
use crate::io::fmt::g_whole;
use crate::io::Outputs;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The points of one series, (x, y).
type Points = Vec<(f64, f64)>;

/// The unit of a key or quantity named with its SI unit as suffix (`fluid.viscosity_pa_s` →
/// `Pa·s`, `terminal_velocity_m_s` → `m/s`); `-` for a pure number (`balls_lost`, a count).
pub fn unit_of(name: &str) -> &'static str {
    const UNITS: [(&str, &str); 14] = [
        ("_pa_s", "Pa·s"),
        ("_kg_m3", "kg/m³"),
        ("_m_s2", "m/s²"),
        ("_m_s", "m/s"),
        ("_m3", "m³"),
        ("_m2", "m²"),
        ("_mm", "mm"),
        ("_pa", "Pa"),
        ("_kg", "kg"),
        ("_deg", "°"),
        ("_min", "min"),
        ("_m", "m"),
        ("_s", "s"),
        ("_n", "N"),
    ];
    let name = name.to_ascii_lowercase();
    UNITS
        .iter()
        .find(|(suffix, _)| name.ends_with(suffix))
        .map_or("-", |(_, unit)| unit)
}

/// The x scale of an axis's values: log when they are positive and geometric (at least three,
/// a constant ratio that is not also a constant step), else linear.
fn scale_of(values: &[f64]) -> Scale {
    let mut v: Vec<f64> = values.to_vec();
    v.sort_by(f64::total_cmp);
    v.dedup();
    if v.len() < 3 || v[0] <= 0.0 {
        return Scale::Linear;
    }
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-6 * a.abs().max(b.abs());
    let ratio = v[1] / v[0];
    let geometric = v.windows(2).all(|w| same(w[1] / w[0], ratio));
    let step = v[1] - v[0];
    let arithmetic = v.windows(2).all(|w| same(w[1] - w[0], step));
    if geometric && !arithmetic {
        Scale::Log
    } else {
        Scale::Linear
    }
}

/// A file-name-safe form of a key (`spheres[0].diameter_m` → `spheres_0_.diameter_m`).
fn file_safe(key: &str) -> String {
    key.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "_.-".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Where the first key's values go on the x axis: at the number itself, or, when any value is a
/// text (a categorical axis), at the value's index among the distinct values in canonical order.
enum XAxis {
    /// Numbers on a linear or log scale.
    Numeric(Scale),
    /// The distinct values, one x position (0, 1, …) each.
    Categories(Vec<Level>),
}

impl XAxis {
    fn of(t: &VaryTable) -> Self {
        let mut levels: Vec<Level> = t.rows.iter().map(|r| r.point[0].clone()).collect();
        levels.sort_by(Level::order);
        levels.dedup();
        if levels.iter().all(|l| l.num().is_some()) {
            let xs: Vec<f64> = levels.iter().filter_map(Level::num).collect();
            XAxis::Numeric(scale_of(&xs))
        } else {
            XAxis::Categories(levels)
        }
    }

    /// The x of a value (NaN if not on the axis).
    fn x(&self, l: &Level) -> f64 {
        match self {
            XAxis::Numeric(_) => l.num().unwrap_or(f64::NAN),
            XAxis::Categories(c) => c.iter().position(|v| v == l).map_or(f64::NAN, |i| i as f64),
        }
    }
}

/// Draws `<quantity>_vs_<first key>.svg` for every result quantity of `t` into `out` (the
/// references `reference_…` are drawn as hollow markers beside a single series) and returns
/// their names.
pub fn charts(out: &mut Outputs, title: &str, t: &VaryTable) -> Result<Vec<String>, Error> {
    let Some(key) = t.keys.first() else {
        return Ok(Vec::new());
    };
    let axis = XAxis::of(t);
    let mut written = Vec::new();
    for (qi, q) in t.results.iter().enumerate() {
        if q.starts_with("reference_") {
            continue;
        }
        let refi = t
            .results
            .iter()
            .position(|c| *c == format!("reference_{q}"));
        // Series keyed by (body, values of the other keys), in first-seen order.
        let mut order: Vec<String> = Vec::new();
        let mut pts: BTreeMap<String, (Points, Points)> = BTreeMap::new();
        for r in &t.rows {
            let mut label = r.body.clone();
            for (k, v) in t.keys.iter().zip(&r.point).skip(1) {
                label.push_str(&format!(", {k} = {v}"));
            }
            if !pts.contains_key(&label) {
                order.push(label.clone());
            }
            let x = axis.x(&r.point[0]);
            let e = pts.entry(label).or_default();
            e.0.push((x, r.results[qi]));
            if let Some(i) = refi {
                e.1.push((x, r.results[i]));
            }
        }
        let single = order.len() == 1;
        // On a categorical axis the series stand side by side about each position.
        let n = order.len() as f64;
        let width = (0.5 / n).min(0.12);
        let mut series = Vec::new();
        for (i, label) in order.iter().enumerate() {
            let (sim, reference) = &pts[label];
            let mut s = Series::sorted_line(label.clone(), sim.clone(), i);
            if let XAxis::Categories(_) = axis {
                let dx = (i as f64 - 0.5 * (n - 1.0)) * width;
                s.points.iter_mut().for_each(|p| p.0 += dx);
                s.line = false;
            }
            series.push(s);
            if single && reference.iter().any(|p| p.1.is_finite()) {
                let mut r =
                    Series::sorted_line(format!("{label} (reference)"), reference.clone(), 1);
                r.filled = false;
                r.line = false;
                series.push(r);
            }
        }
        let name = format!("{}_vs_{}.svg", file_safe(q), file_safe(key));
        let x_label = format!("{key} [{}]", unit_of(key));
        let chart = Chart::new(format!("{title}: {q} against {key}"))
            .y(format!("{q} [{}]", unit_of(q)), Scale::Linear);
        let chart = match &axis {
            XAxis::Numeric(scale) => chart.x(x_label, *scale),
            XAxis::Categories(c) => chart.x_categories(x_label, c.iter().map(Level::to_string)),
        };
        out.chart(&name, &chart.all_series(series))
            .map_err(|e| Error::Io(PathBuf::from(&name), e))?;
        written.push(name);
    }
    Ok(written)
}

/// The console lines of a parameter sweep: a heading, then one line per case with its key
/// values, its status and each quantity (its value for one body, its range over several).
pub fn console_lines(title: &str, t: &VaryTable) -> Vec<String> {
    let mut cases: Vec<(&[Level], Vec<usize>)> = Vec::new();
    for (i, r) in t.rows.iter().enumerate() {
        match cases.last_mut() {
            Some((p, rows)) if *p == r.point.as_slice() => rows.push(i),
            _ => cases.push((&r.point, vec![i])),
        }
    }
    let mut lines = vec![format!(
        "{title}: {} cases varying {}",
        cases.len(),
        t.keys.join(", ")
    )];
    for (point, rows) in &cases {
        let keys: Vec<String> = t
            .keys
            .iter()
            .zip(point.iter())
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        let mut line = format!("  {}:", keys.join(", "));
        if let Some(r) = rows
            .iter()
            .map(|&i| &t.rows[i])
            .find(|r| !r.reason.is_empty())
        {
            line.push_str(&format!(" unstable ({})", r.reason));
            lines.push(line);
            continue;
        }
        for (qi, q) in t.results.iter().enumerate() {
            if q.starts_with("reference_") {
                continue;
            }
            let v: Vec<f64> = rows
                .iter()
                .map(|&i| t.rows[i].results[qi])
                .filter(|x| x.is_finite())
                .collect();
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let text = match v.len() {
                0 => "-".to_string(),
                _ if lo == hi => g_whole(lo),
                n => format!("{} to {} ({n} bodies)", g_whole(lo), g_whole(hi)),
            };
            line.push_str(&format!(" {q} {text};"));
        }
        lines.push(line.trim_end_matches(';').to_string());
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_come_from_the_name_suffix() {
        assert_eq!(unit_of("fluid.viscosity_pa_s"), "Pa·s");
        assert_eq!(unit_of("fluid.yield_stress_pa"), "Pa");
        assert_eq!(unit_of("terminal_velocity_m_s"), "m/s");
        assert_eq!(unit_of("velocity_at_0.01s_m_s"), "m/s");
        assert_eq!(unit_of("spheres[0].diameter_m"), "m");
        assert_eq!(unit_of("fluid.density_kg_m3"), "kg/m³");
        assert_eq!(unit_of("gravity_m_s2"), "m/s²");
        assert_eq!(unit_of("time.dt_s"), "s");
        assert_eq!(unit_of("balls_lost"), "-");
        assert_eq!(unit_of("contacts.friction"), "-");
    }

    #[test]
    fn a_geometric_axis_is_drawn_on_a_log_scale() {
        assert!(scale_of(&[1e-4, 1e-3, 1e-2]) == Scale::Log);
        assert!(scale_of(&[1.0, 2.0, 3.0]) == Scale::Linear);
        assert!(scale_of(&[1.0, 10.0]) == Scale::Linear);
        assert!(scale_of(&[0.0, 1.0, 10.0]) == Scale::Linear);
    }
}
