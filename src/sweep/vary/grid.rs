//! The grid of a parameter sweep (`--vary KEY=GRID`): each axis is a scenario key and its
//! values; several axes make the full grid (the first key outermost). A value is a number or,
//! for a categorical axis (`transient.history=off,basset`), a text passed as `--set` passes it.
//! Pure: no I/O.

use crate::error::Error;
use crate::sweep::values::BadValue;
use std::cmp::Ordering;
use std::fmt;
use std::path::Path;

/// Most values on one axis, and most cases in a whole grid: a larger grid is a typo more often
/// than a plan (each case is a whole run).
pub const MAX_CASES: usize = 10_000;

/// What `--vary` accepts.
pub const VARY_ALLOWED: &str = "KEY=LO:HI:N (N ≥ 2 values from LO to HI, LO < HI, linear), \
    KEY=log:LO:HI:N (log-spaced, 0 < LO < HI) or KEY=V1,V2,… (numbers, or words and booleans \
    taken as --set takes them), with N ≤ 10000; e.g. fluid.yield_stress_pa=10:40:13 or \
    transient.history=off,basset";

/// How an axis's values are spaced (the chart's x scale follows it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Spacing {
    /// `LO:HI:N` or a list: a linear axis (a categorical one when a value is a text).
    Linear,
    /// `log:LO:HI:N`: a log axis.
    Log,
}

/// One value of a varied key: a number, or a text (a word such as `basset`, a boolean `true`)
/// that `--set` reads as TOML (a boolean, a number) or else as a string.
#[derive(Clone, Debug, PartialEq)]
pub enum Level {
    /// A number, in the key's unit.
    Num(f64),
    /// Any other value, as written (trimmed).
    Text(String),
}

impl Level {
    /// The value of a cell or a list item: a number if it reads as one, else the text.
    pub fn parse(s: &str) -> Level {
        let s = s.trim();
        match s.parse::<f64>() {
            Ok(x) => Level::Num(x),
            Err(_) => Level::Text(s.to_string()),
        }
    }

    /// The number, if the value is one.
    pub fn num(&self) -> Option<f64> {
        match self {
            Level::Num(x) => Some(*x),
            Level::Text(_) => None,
        }
    }

    /// The value as `--set KEY=VALUE` takes it (for a number: an integer when whole, else
    /// exponent notation).
    pub fn override_text(&self) -> String {
        match self {
            Level::Num(x) => override_text(*x),
            Level::Text(t) => t.clone(),
        }
    }

    /// Canonical order: numbers ascending (total order), then texts in byte order.
    pub fn order(&self, other: &Level) -> Ordering {
        match (self, other) {
            (Level::Num(a), Level::Num(b)) => a.total_cmp(b),
            (Level::Num(_), Level::Text(_)) => Ordering::Less,
            (Level::Text(_), Level::Num(_)) => Ordering::Greater,
            (Level::Text(a), Level::Text(b)) => a.cmp(b),
        }
    }
}

/// As written to `vary.csv` and the console: a number in its shortest form that reads back to
/// the same value, a text as is.
impl fmt::Display for Level {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Level::Num(x) => f.write_str(&crate::io::fmt::num(*x)),
            Level::Text(t) => f.write_str(t),
        }
    }
}

/// One `--vary` axis: a scenario key (as `--set` takes it) and its values, ascending
/// ([`Level::order`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// The key, e.g. `fluid.yield_stress_pa` or `spheres[0].diameter_m`.
    pub key: String,
    /// Its values, ascending, without repeats, in the key's unit; a categorical axis holds
    /// texts (and may hold numbers beside them).
    pub values: Vec<Level>,
    /// Linear or log spacing.
    pub spacing: Spacing,
}

/// `x` rounded to 12 significant digits, so that grid arithmetic prints as the user wrote it
/// (`0.1 + 2 × 0.1` is 0.3, not 0.30000000000000004).
pub fn round12(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x.abs();
    }
    // Through decimal text: the nearest double to the 12-digit decimal, as a person reads it.
    format!("{x:.11e}").parse().unwrap_or(x)
}

/// The value as `--set` writes it: an integer when whole (a count such as `sample.particles`
/// reads it, and so does a real key), else exponent notation (TOML reads `1.25e1`).
pub fn override_text(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        format!("{x:e}")
    }
}

/// Parses one `--vary KEY=GRID` (see [`VARY_ALLOWED`]).
pub fn parse_vary(s: &str) -> Result<Axis, BadValue> {
    let bad = BadValue {
        allowed: VARY_ALLOWED,
    };
    let (key, grid) = s.split_once('=').ok_or(bad)?;
    let key = key.trim();
    if !crate::scenario::is_key_path(key) {
        return Err(bad);
    }
    let number = |t: &str| t.trim().parse::<f64>().ok().filter(|x| x.is_finite());
    let count = |t: &str| {
        t.trim()
            .parse::<usize>()
            .ok()
            .filter(|n| (2..=MAX_CASES).contains(n))
    };
    let grid = grid.trim();
    let (spacing, values) = if let Some(rest) = grid.strip_prefix("log:") {
        let p: Vec<&str> = rest.split(':').collect();
        let [lo, hi, n] = p[..] else { return Err(bad) };
        let (lo, hi, n) = (
            number(lo).ok_or(bad)?,
            number(hi).ok_or(bad)?,
            count(n).ok_or(bad)?,
        );
        if !(lo > 0.0 && lo < hi) {
            return Err(bad);
        }
        let r = (hi / lo).ln();
        let v = (0..n)
            .map(|i| Level::Num(round12(lo * (r * i as f64 / (n - 1) as f64).exp())))
            .collect();
        (Spacing::Log, v)
    } else if grid.contains(':') {
        let p: Vec<&str> = grid.split(':').collect();
        let [lo, hi, n] = p[..] else { return Err(bad) };
        let (lo, hi, n) = (
            number(lo).ok_or(bad)?,
            number(hi).ok_or(bad)?,
            count(n).ok_or(bad)?,
        );
        if lo >= hi {
            return Err(bad);
        }
        let v = (0..n)
            .map(|i| Level::Num(round12(lo + (hi - lo) * i as f64 / (n - 1) as f64)))
            .collect();
        (Spacing::Linear, v)
    } else {
        (Spacing::Linear, list(grid.split(',')).ok_or(bad)?)
    };
    Ok(Axis::sorted(key, values, spacing))
}

/// The values of a list `V1,V2,…`: each a number or a word `--set` takes (a text that is not a
/// number, nor NaN or ±inf); None if one is not, or for none or over [`MAX_CASES`] values.
fn list<'a>(items: impl Iterator<Item = &'a str>) -> Option<Vec<Level>> {
    let level = |t: &str| match Level::parse(t) {
        Level::Num(x) if !x.is_finite() => None,
        Level::Text(w) if w.is_empty() => None,
        l => Some(l),
    };
    let v: Vec<Level> = items.map(level).collect::<Option<_>>()?;
    (!v.is_empty() && v.len() <= MAX_CASES).then_some(v)
}

impl Axis {
    /// The axis of `key` with `values` sorted and without repeats.
    fn sorted(key: &str, mut values: Vec<Level>, spacing: Spacing) -> Self {
        values.sort_by(Level::order);
        values.dedup();
        Axis {
            key: key.to_string(),
            values,
            spacing,
        }
    }

    /// An axis as `--vary KEY=GRID` gives it ([`VARY_ALLOWED`]): `KEY=LO:HI:N`,
    /// `KEY=log:LO:HI:N` or `KEY=V1,V2,…`; a bad one is a bad argument of `--vary` naming it.
    ///
    /// ```
    /// let a = settle::sweep::Axis::parse("fluid.viscosity_pa_s=log:1e-3:1e-1:3")?;
    /// assert_eq!(a.values.len(), 3); // 1e-3, 1e-2, 1e-1 Pa·s
    /// # Ok::<(), settle::Error>(())
    /// ```
    pub fn parse(text: &str) -> Result<Self, Error> {
        parse_vary(text).map_err(|e| Error::bad_argument("--vary", Path::new(text), e.to_string()))
    }

    /// The axis of `key` (a scenario key, as `--set` takes it) over `values`, each a number
    /// (in the key's unit) or a word or boolean `--set` takes: `--vary KEY=V1,V2,…`. Sorted
    /// and without repeats; a bad key or value is a bad argument of `--vary` naming it.
    ///
    /// ```
    /// let a = settle::sweep::Axis::list("drag.law", &["stokes", "dallavalle"])?;
    /// assert_eq!(a.values[0].to_string(), "dallavalle");
    /// # Ok::<(), settle::Error>(())
    /// ```
    pub fn list(key: &str, values: &[impl AsRef<str>]) -> Result<Self, Error> {
        let items: Vec<&str> = values.iter().map(AsRef::as_ref).collect();
        let text = format!("{key}={}", items.join(","));
        let bad = || {
            Error::bad_argument(
                "--vary",
                Path::new(&text),
                BadValue {
                    allowed: VARY_ALLOWED,
                }
                .to_string(),
            )
        };
        let key = key.trim();
        // A value holding a comma would be two values of `--vary KEY=V1,V2`.
        if !crate::scenario::is_key_path(key) || items.iter().any(|v| v.contains(',')) {
            return Err(bad());
        }
        let values = list(items.into_iter()).ok_or_else(bad)?;
        Ok(Axis::sorted(key, values, Spacing::Linear))
    }
}

/// Every point of the full grid of `axes` (one value per axis, in axis order), the first axis
/// outermost; empty for no axes.
pub fn points(axes: &[Axis]) -> Vec<Vec<Level>> {
    if axes.is_empty() {
        return Vec::new();
    }
    let mut out: Vec<Vec<Level>> = vec![Vec::new()];
    for a in axes {
        out = out
            .into_iter()
            .flat_map(|p| {
                a.values.iter().map(move |v| {
                    let mut q = p.clone();
                    q.push(v.clone());
                    q
                })
            })
            .collect();
    }
    out
}

/// The number of points of the full grid, saturating (to refuse a huge grid before building it).
pub fn count(axes: &[Axis]) -> usize {
    axes.iter()
        .fold(1usize, |n, a| n.saturating_mul(a.values.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nums(x: &[f64]) -> Vec<Level> {
        x.iter().map(|&v| Level::Num(v)).collect()
    }

    fn text(x: &str) -> Level {
        Level::Text(x.to_string())
    }

    #[test]
    fn a_list_of_words_is_a_categorical_axis_passed_as_set_passes_it() {
        let a = parse_vary("transient.history=off, basset,mei-adrian,off").unwrap();
        assert_eq!(a.key, "transient.history");
        assert_eq!(a.values, [text("basset"), text("mei-adrian"), text("off")]);
        assert_eq!(a.values[1].override_text(), "mei-adrian");
        let b = parse_vary("transient.added_mass=true,false").unwrap();
        assert_eq!(b.values, [text("false"), text("true")]);
        assert_eq!(b.values[0].to_string(), "false");
        // Numbers beside words stay numbers, first.
        let c = parse_vary("k=auto,2,1.5").unwrap();
        assert_eq!(c.values, [Level::Num(1.5), Level::Num(2.0), text("auto")]);
        assert_eq!(c.values[0].override_text(), "1.5e0");
        assert_eq!(c.values[0].to_string(), "1.5");
        assert_eq!(Level::parse(" 2e-3 "), Level::Num(2e-3));
        assert_eq!(Level::parse("basset"), text("basset"));
    }

    #[test]
    fn a_linear_grid_has_n_round_values_from_lo_to_hi() {
        let a = parse_vary("fluid.yield_stress_pa=10:40:13").unwrap();
        assert_eq!(a.key, "fluid.yield_stress_pa");
        assert_eq!(a.spacing, Spacing::Linear);
        assert_eq!(a.values.len(), 13);
        assert_eq!(a.values[0], Level::Num(10.0));
        assert_eq!(a.values[1], Level::Num(12.5));
        assert_eq!(a.values[12], Level::Num(40.0));
        let a = parse_vary("x=0:0.3:4").unwrap();
        assert_eq!(a.values, nums(&[0.0, 0.1, 0.2, 0.3]));
    }

    #[test]
    fn a_log_grid_is_geometric_and_prints_round() {
        let a = parse_vary("fluid.viscosity_pa_s=log:1e-4:1e-2:5").unwrap();
        assert_eq!(a.spacing, Spacing::Log);
        assert_eq!(a.values.len(), 5);
        assert_eq!(a.values[0], Level::Num(1e-4));
        assert_eq!(a.values[2], Level::Num(1e-3));
        assert_eq!(a.values[4], Level::Num(1e-2));
        assert_eq!(a.values[2].override_text(), "1e-3");
    }

    #[test]
    fn a_list_is_sorted_and_deduplicated() {
        let a = parse_vary("sample.particles=3000,1000,2000,1000").unwrap();
        assert_eq!(a.values, nums(&[1000.0, 2000.0, 3000.0]));
        assert_eq!(override_text(2000.0), "2000");
        assert_eq!(override_text(12.5), "1.25e1");
        assert_eq!(override_text(-0.5), "-5e-1");
    }

    #[test]
    fn bad_grids_are_refused_with_what_is_allowed() {
        for s in [
            "novalue",
            "=1,2",
            "k=1:2",
            "k=2:1:3",
            "k=1:2:1",
            "k=1:2:100001",
            "k=log:0:1:3",
            "k=log:1:1:3",
            "k=a,,b",
            "k=1,,2",
            "k=inf,1",
            "k=1:2:x",
            "k=nan,1",
            "bad key=1,2",
        ] {
            let e = parse_vary(s).unwrap_err();
            assert!(e.to_string().contains("KEY=LO:HI:N"), "{s}: {e}");
        }
    }

    #[test]
    fn the_full_grid_has_the_product_of_the_axes_first_key_outermost() {
        let a = parse_vary("a=1,2").unwrap();
        let b = parse_vary("b=10:30:3").unwrap();
        let p = points(&[a.clone(), b.clone()]);
        assert_eq!(p.len(), 6);
        assert_eq!(count(&[a, b]), 6);
        assert_eq!(p[0], nums(&[1.0, 10.0]));
        assert_eq!(p[1], nums(&[1.0, 20.0]));
        assert_eq!(p[5], nums(&[2.0, 30.0]));
        assert!(points(&[]).is_empty());
    }

    #[test]
    fn round12_removes_float_noise_only() {
        assert_eq!(round12(0.30000000000000004), 0.3);
        assert_eq!(round12(-0.30000000000000004), -0.3);
        assert_eq!(round12(123456.0), 123456.0);
        assert_eq!(round12(1.0000000000000002e-14), 1e-14);
        assert_eq!(round12(0.0), 0.0);
        assert_eq!(round12(-0.0).to_bits(), 0.0f64.to_bits());
    }
}
