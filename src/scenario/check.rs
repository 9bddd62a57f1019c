//! Small declarative range checks: each failure names the file, the key and the allowed range.
//!
//! A table's checks are a list of `(key, value, range)` rows given to [`Check::table`]; list
//! keys go to [`Check::each`]. The messages read `X is out of range: allowed LO < key ≤ HI UNIT`.

use crate::error::BadInput;
use std::path::Path;

/// Largest number of steps a run may take before it is refused as unbounded.
pub const MAX_STEPS: f64 = 1e10;

/// The file being checked; builds errors naming it.
pub(crate) struct Check<'a> {
    /// The scenario file.
    pub file: &'a Path,
}

/// An allowed interval for one value, with its unit (and any note) for the message.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Range<'u> {
    lo: f64,
    hi: f64,
    /// `lo < x` (true) or `lo ≤ x` (false). The upper bound is always closed.
    open_below: bool,
    unit: &'u str,
}

/// `lo < x ≤ hi`.
pub(crate) fn oc(lo: f64, hi: f64, unit: &str) -> Range<'_> {
    Range {
        lo,
        hi,
        open_below: true,
        unit,
    }
}

/// `lo ≤ x ≤ hi`.
pub(crate) fn cc(lo: f64, hi: f64, unit: &str) -> Range<'_> {
    Range {
        lo,
        hi,
        open_below: false,
        unit,
    }
}

impl Range<'_> {
    fn holds(&self, x: f64) -> bool {
        let above = if self.open_below {
            x > self.lo
        } else {
            x >= self.lo
        };
        x.is_finite() && above && x <= self.hi
    }
}

impl Check<'_> {
    /// An error on `key`.
    pub fn err(&self, key: &str, msg: impl Into<String>) -> BadInput {
        BadInput::new(self.file, Some(key), msg)
    }

    /// `x` within `r`, or an error naming `key` and the range.
    pub fn range(&self, key: &str, x: f64, r: Range) -> Result<(), BadInput> {
        if r.holds(x) {
            return Ok(());
        }
        let op = if r.open_below { "<" } else { "≤" };
        Err(self.err(
            key,
            format!(
                "{x} is out of range: allowed {} {op} {} ≤ {} {}",
                r.lo,
                short(key),
                r.hi,
                r.unit
            ),
        ))
    }

    /// Every `(name, value, range)` row of table `table` (keys `table.name`), in order.
    pub fn table(&self, table: &str, rows: &[(&str, f64, Range)]) -> Result<(), BadInput> {
        for &(name, x, r) in rows {
            let key = if table.is_empty() {
                name.to_string()
            } else {
                format!("{table}.{name}")
            };
            self.range(&key, x, r)?;
        }
        Ok(())
    }

    /// Every element of the list `key` (keys `key[i]`) within `r`.
    pub fn each(&self, key: &str, xs: &[f64], r: Range) -> Result<(), BadInput> {
        for (i, x) in xs.iter().enumerate() {
            self.range(&format!("{key}[{i}]"), *x, r)?;
        }
        Ok(())
    }

    /// A count with `lo ≤ n ≤ hi`.
    pub fn count_in(&self, key: &str, n: usize, lo: usize, hi: usize) -> Result<(), BadInput> {
        if (lo..=hi).contains(&n) {
            Ok(())
        } else {
            Err(self.err(
                key,
                format!("{n} is out of range: allowed {lo} ≤ {} ≤ {hi}", short(key)),
            ))
        }
    }
}

/// The last segment of a dotted key (`fluid.density_kg_m3` → `density_kg_m3`).
fn short(key: &str) -> &str {
    key.rsplit('.').next().unwrap_or(key)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn open_and_closed_bounds() {
        let c = Check {
            file: Path::new("f.toml"),
        };
        assert!(c.range("a.x", 0.0, cc(0.0, 1.0, "m")).is_ok());
        assert!(c.range("a.x", 1.0, oc(0.0, 1.0, "m")).is_ok());
        let e = c.range("a.x", 0.0, oc(0.0, 1.0, "m")).unwrap_err();
        assert_eq!(e.key.as_deref(), Some("a.x"));
        assert_eq!(e.message, "0 is out of range: allowed 0 < x ≤ 1 m");
        let e = c.range("a.x", f64::NAN, cc(0.0, 1.0, "m")).unwrap_err();
        assert_eq!(e.message, "NaN is out of range: allowed 0 ≤ x ≤ 1 m");
        let e = c
            .table(
                "t",
                &[("y", 0.5, cc(0.0, 1.0, "")), ("z", 2.0, cc(0.0, 1.0, ""))],
            )
            .unwrap_err();
        assert_eq!(e.key.as_deref(), Some("t.z"));
        let e = c.each("t.l", &[0.5, -1.0], cc(0.0, 1.0, "s")).unwrap_err();
        assert_eq!(e.key.as_deref(), Some("t.l[1]"));
    }
}
