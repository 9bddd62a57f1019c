//! Reading and checking a readings file (the format of `docs/commands/reduce.md`): the test's
//! figures from its `# key = value` lines, its readings from the table. Every refusal is one
//! [`Error::BadInput`] naming the file, the key or the row and column (1-based), and what is
//! allowed.

use super::figures::{bad, split, Parsed, ReduceOptions};
use super::instrument::{setup, RowRules};
use crate::error::Error;
use crate::instruments::reduction::{LabReading, TestSetup};
use crate::io::fmt::num;
use crate::io::lab_file::{number_hint, Detected, LabFile, Loc};
use crate::io::Table;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The readings of one test: a readings file, or the same in memory.
#[derive(Clone, Debug, PartialEq)]
pub enum Readings {
    /// A readings file (CSV, the format of `docs/commands/reduce.md`).
    File(PathBuf),
    /// A readings file's content in memory: its `# key = value` figures (in order) and its
    /// table (the file's columns: `time_min` or `time_s`, `reading` (or `drawn_mass_g`,
    /// `apparent_mass_g`), `temperature_c` [, `blank_reading`]). The table's name stands for
    /// the file: it names the results folder (`<stem>_reduced`) and the errors.
    Table {
        /// The test's figures, `(key, value)` as the file's `# key = value` lines give them.
        figures: Vec<(String, String)>,
        /// The readings.
        table: Table,
    },
}

impl Readings {
    /// Readings in memory: `figures` (key, value) and the table of readings.
    pub fn table<K: Into<String>, V: Into<String>>(
        figures: impl IntoIterator<Item = (K, V)>,
        table: Table,
    ) -> Self {
        Readings::Table {
            figures: figures
                .into_iter()
                .map(|(k, v)| (k.into(), v.into()))
                .collect(),
            table,
        }
    }

    /// The path errors and records name: the file, or the table's name.
    pub fn path(&self) -> PathBuf {
        match self {
            Readings::File(p) => p.clone(),
            Readings::Table { table, .. } => PathBuf::from(table.name()),
        }
    }

    /// What the results of these readings are of, for the owner of their folder
    /// ([`crate::io::Owner`]): the file's absolute path, or `table NAME`.
    pub fn owner_input(&self) -> String {
        match self {
            Readings::File(p) => crate::io::owner::absolute(p).display().to_string(),
            Readings::Table { table, .. } => format!("table {}", table.name()),
        }
    }

    /// The stem of the results folder's name (`<stem>_reduced`, `<stem>_inverted`).
    pub fn stem(&self) -> String {
        self.path()
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "readings".into())
    }

    /// The readings file through the format layer (CSV as spreadsheets export it, or a
    /// workbook; a table in memory as the CSV it stands for).
    pub(crate) fn lab(&self) -> Result<LabFile, Error> {
        match self {
            Readings::File(file) => LabFile::read(file),
            Readings::Table { figures, table } => {
                let mut t = String::new();
                for (k, v) in figures {
                    t.push_str(&format!("# {k} = {v}\n"));
                }
                t.push_str(&table.header().join(","));
                t.push('\n');
                for r in table.rows().iter() {
                    t.push_str(&r.join(","));
                    t.push('\n');
                }
                LabFile::from_text(&self.path(), &t)
            }
        }
    }
}

impl From<PathBuf> for Readings {
    fn from(p: PathBuf) -> Self {
        Readings::File(p)
    }
}

impl From<&Path> for Readings {
    fn from(p: &Path) -> Self {
        Readings::File(p.to_path_buf())
    }
}

impl From<&str> for Readings {
    fn from(p: &str) -> Self {
        Readings::File(PathBuf::from(p))
    }
}

/// The columns a readings file may have (which apply to which instrument: [`columns`]).
const COLUMNS: [&str; 8] = [
    "time_s",
    "time_min",
    "reading",
    "drawn_mass_g",
    "apparent_mass_g",
    "temperature_c",
    "blank_reading",
    "counting_sigma",
];

/// Readings read and checked: the test's figures, its readings, what the format layer
/// detected, and the doubtful values (warnings).
pub(crate) struct ReadOut {
    /// The test's figures.
    pub setup: TestSetup,
    /// The readings, in order.
    pub readings: Vec<LabReading>,
    /// What was detected (format, sheet, encoding, delimiter, decimal mark).
    pub detected: Detected,
    /// Doubtful values, one sentence each (the console's and the record's warnings).
    pub warnings: Vec<String>,
    /// The `counting_sigma` column when the file has one (a run's readings files: the counting
    /// noise of its representative grains, in the reading's unit), one value per reading;
    /// `settle invert` adds it to the resolution, the reduction does not use it.
    pub counting_sigma: Option<Vec<f64>>,
}

/// Reads and checks readings (a file or in memory) through the format layer, then their
/// plausibility ([`super::checks`]): a clear mistake (a wrong unit) is bad input, a doubtful
/// value a warning.
pub(crate) fn read_checked(readings: &Readings, req: &ReduceOptions) -> Result<ReadOut, Error> {
    let lab = readings.lab()?;
    let file = &readings.path();
    let p = split(file, lab)?;
    let (s, rules) = setup(file, &p, req)?;
    let (lab_readings, locs, time_col, counting_sigma) = rows(file, &p, &rules)?;
    let warnings = super::checks::check(file, &p, &s, &lab_readings, &locs, time_col)?;
    Ok(ReadOut {
        setup: s,
        readings: lab_readings,
        detected: p.detected,
        warnings,
        counting_sigma,
    })
}

/// The column index of each known column; refuses unknown, duplicate and missing ones, and
/// the reading columns of other instruments (`reading` is the instrument's own, `optional`
/// the columns it may have besides the time and the reading).
fn columns(
    file: &Path,
    header: &[String],
    reading: &str,
    optional: &[&str],
) -> Result<BTreeMap<&'static str, usize>, Error> {
    let mut at = BTreeMap::new();
    let allowed: Vec<&str> = ["time_min", "time_s", reading, "counting_sigma"]
        .into_iter()
        .chain(optional.iter().copied())
        .collect();
    for (j, h) in header.iter().enumerate() {
        let c = COLUMNS
            .iter()
            .find(|c| **c == h.as_str() && allowed.contains(c));
        let Some(c) = c else {
            let other = if COLUMNS.contains(&h.as_str()) {
                format!("column `{h}` is not one of this instrument's")
            } else {
                format!("unknown column `{h}`")
            };
            return Err(bad(
                file,
                format!(
                    "header, column {}: {other}; allowed: {}",
                    j + 1,
                    allowed.join(", ")
                ),
            ));
        };
        if at.insert(*c, j).is_some() {
            return Err(bad(
                file,
                format!("header, column {}: `{h}` given twice", j + 1),
            ));
        }
    }
    if at.contains_key("time_s") == at.contains_key("time_min") {
        return Err(bad(
            file,
            "header: give one time column, time_min or time_s".into(),
        ));
    }
    if !at.contains_key(reading) {
        return Err(bad(file, format!("header: missing column `{reading}`")));
    }
    Ok(at)
}

/// The readings, where each row is, the time column's name and index, and the
/// `counting_sigma` column if there is one.
type Rows = (
    Vec<LabReading>,
    Vec<Loc>,
    (&'static str, usize),
    Option<Vec<f64>>,
);

/// The readings of the table, each value checked by `rules`, with where each row is and the
/// time column's name and index.
fn rows(file: &Path, p: &Parsed, rules: &RowRules) -> Result<Rows, Error> {
    let at = columns(file, &p.header, rules.reading, &rules.optional_columns())?;
    let (temperature, blank) = rules.check_columns(file, &at)?;
    if p.rows.is_empty() {
        return Err(bad(
            file,
            "no readings: the table has a header but no rows".into(),
        ));
    }
    let mut out: Vec<LabReading> = Vec::new();
    let mut locs = Vec::new();
    let mut sigma = at.contains_key("counting_sigma").then(Vec::new);
    for (n, (line, fields)) in p.rows.iter().enumerate() {
        let row = n + 1;
        if fields.len() != p.header.len() {
            let hint = if p.detected.delimiter == Some(',') && fields.len() > p.header.len() {
                " (a comma inside a number, a decimal comma or a thousands separator, splits it \
                 in two: write numbers with a decimal point, or save the sheet as CSV with \
                 semicolons)"
            } else {
                ""
            };
            return Err(bad(
                file,
                format!(
                    "row {row} ({line}): {} fields, the header has {}{hint}",
                    fields.len(),
                    p.header.len()
                ),
            ));
        }
        let value = |c: &str, (lo, hi): (f64, f64), allowed: &str| -> Result<f64, Error> {
            let j = at[c];
            let v = &fields[j];
            let where_ = format!("row {row} ({}), column {} `{c}`", line.at(j), j + 1);
            if v.is_empty() {
                return Err(bad(file, format!("{where_}: empty; allowed: {allowed}")));
            }
            let x: f64 = v.parse().map_err(|_| {
                bad(
                    file,
                    format!(
                        "{where_}: `{v}` is not a number{}; allowed: {allowed}",
                        number_hint(v, &p.detected)
                    ),
                )
            })?;
            if !(x.is_finite() && x >= lo && x <= hi) {
                return Err(bad(
                    file,
                    format!(
                        "{where_}: {v} is out of range; allowed: {allowed}{}",
                        super::checks::out_of_range_hint(c, x, rules)
                    ),
                ));
            }
            Ok(x)
        };
        let time_s = if at.contains_key("time_s") {
            value("time_s", (1e-9, 1e7), "a time > 0 s")?
        } else {
            60.0 * value("time_min", (1e-9, 1e6), "a time > 0 min")?
        };
        let reading = value(rules.reading, rules.range, &rules.allowed)?;
        let temp = match temperature {
            Some(t) => t,
            None => value(
                "temperature_c",
                rules.temperature_range,
                &rules.temperature_text,
            )?,
        };
        let blank_reading = match blank {
            Some(b) => b,
            None => value("blank_reading", rules.blank_range, &rules.blank_allowed)?,
        };
        if let Some(prev) = out.last().filter(|prev| time_s <= prev.time_s) {
            let c = if at.contains_key("time_s") {
                "time_s"
            } else {
                "time_min"
            };
            return Err(bad(
                file,
                format!(
                    "row {row} ({}), column {} `{c}`: {} is not after the previous \
                     reading's {}; times must increase strictly",
                    line.at(at[c]),
                    at[c] + 1,
                    fields[at[c]],
                    if c == "time_s" {
                        num(prev.time_s)
                    } else {
                        num(prev.time_s / 60.0)
                    }
                ),
            ));
        }
        if let Some(s) = sigma.as_mut() {
            s.push(value(
                "counting_sigma",
                (0.0, f64::MAX),
                "a standard deviation >= 0, in the reading's unit",
            )?);
        }
        out.push(LabReading {
            time_s,
            reading,
            temperature_c: temp,
            blank_reading,
        });
        locs.push(line.clone());
    }
    let time = if at.contains_key("time_s") {
        "time_s"
    } else {
        "time_min"
    };
    Ok((out, locs, (time, at[time]), sigma))
}
