//! The measurements of a fit (`--measured M.csv`) and how each is read from a run's outputs.
//!
//! M.csv has the columns `file` (an output CSV of the scenario's kind, e.g. `summary.csv`),
//! `column` (a numeric column of it), `row` (which row: `NAME=VALUE` picks the row whose column
//! NAME holds VALUE, `id=VALUE` the row whose identifier column — `id`, or the first column
//! named `*_id` — holds it; a bare integer is a 0-based data-row index), `value` (the measured
//! value, in the column's unit) and optionally `sigma` (its 1σ uncertainty, > 0; empty or absent:
//! unweighted).

use crate::error::Error;
use crate::io::lab_file::LabFile;
use crate::io::Table;
use std::path::{Path, PathBuf};

/// One measured quantity.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// The output CSV it is read from, relative to the run's folder.
    pub file: String,
    /// Its column.
    pub column: String,
    /// Its row selector, as written.
    pub row: String,
    /// The measured value, in the column's unit.
    pub value: f64,
    /// Its 1σ uncertainty (None: not given, weight 1).
    pub sigma: Option<f64>,
}

impl Measurement {
    /// The weight's σ: the given uncertainty, or 1.
    pub fn sigma_or_one(&self) -> f64 {
        self.sigma.unwrap_or(1.0)
    }

    /// A short label: `file:column[row]`.
    pub fn label(&self) -> String {
        format!("{}:{}[{}]", self.file, self.column, self.row)
    }
}

/// The measurements of a fit: an M.csv file, or the same table in memory.
#[derive(Clone, Debug, PartialEq)]
pub enum Measured {
    /// A measurements file (CSV: `file, column, row, value [, sigma]`; `#` lines are comments).
    File(PathBuf),
    /// The file's table in memory; its name stands for the file in errors and in `fit.toml`.
    Table(Table),
}

impl Measured {
    /// The path errors and `fit.toml` name: the file, or the table's name.
    pub fn path(&self) -> PathBuf {
        match self {
            Measured::File(p) => p.clone(),
            Measured::Table(t) => PathBuf::from(t.name()),
        }
    }
}

impl From<PathBuf> for Measured {
    fn from(p: PathBuf) -> Self {
        Measured::File(p)
    }
}

impl From<&Path> for Measured {
    fn from(p: &Path) -> Self {
        Measured::File(p.to_path_buf())
    }
}

impl From<&PathBuf> for Measured {
    fn from(p: &PathBuf) -> Self {
        Measured::File(p.clone())
    }
}

impl From<&str> for Measured {
    fn from(p: &str) -> Self {
        Measured::File(PathBuf::from(p))
    }
}

impl From<Table> for Measured {
    fn from(t: Table) -> Self {
        Measured::Table(t)
    }
}

/// Reads the measurements (M.csv, or its table in memory); a missing column, an empty file, a
/// value that is not a finite number or a sigma that is not > 0 is bad input naming the file,
/// the row and the column.
pub fn read(measured: &Measured) -> Result<Vec<Measurement>, Error> {
    let path = &measured.path();
    let bytes = match measured {
        Measured::File(p) => std::fs::read(p)
            .map_err(|e| Error::bad_input(path, None, format!("cannot read: {e}")))?,
        Measured::Table(t) => t
            .to_csv()
            .map_err(|e| Error::bad_input(path, None, e.to_string()))?,
    };
    let bad = |key: String, msg: String| Error::bad_input(path, Some(&key), msg);
    let (header, data) = LabFile::from_bytes(path, &bytes)?.table()?;
    let idx = |name: &str| header.iter().position(|h| h == name);
    let [file, column, row, value] = ["file", "column", "row", "value"].map(idx);
    let (Some(file), Some(column), Some(row), Some(value)) = (file, column, row, value) else {
        return Err(Error::bad_input(
            path,
            None,
            format!(
                "the header is `{}`: needed file, column, row, value [, sigma]",
                header.join(",")
            ),
        ));
    };
    let sigma = idx("sigma");
    let mut out = Vec::new();
    for (i, rec) in data.iter().enumerate() {
        let n = format!("{} ({})", i + 1, rec.loc);
        let cell = |j: usize| rec.cells.get(j).cloned().unwrap_or_default();
        let v: f64 = cell(value)
            .parse()
            .ok()
            .filter(|x: &f64| x.is_finite())
            .ok_or_else(|| {
                bad(
                    format!("row {n}, column value"),
                    format!("`{}` is not a finite number", cell(value)),
                )
            })?;
        let s = match sigma.map(cell).filter(|t| !t.is_empty()) {
            None => None,
            Some(t) => Some(
                t.parse()
                    .ok()
                    .filter(|x: &f64| *x > 0.0 && x.is_finite())
                    .ok_or_else(|| {
                        bad(
                            format!("row {n}, column sigma"),
                            format!("`{t}` is not a number > 0"),
                        )
                    })?,
            ),
        };
        let m = Measurement {
            file: cell(file),
            column: cell(column),
            row: cell(row),
            value: v,
            sigma: s,
        };
        if m.file.is_empty() || m.column.is_empty() || m.row.is_empty() {
            return Err(bad(
                format!("row {n}"),
                "file, column and row must not be empty".into(),
            ));
        }
        out.push(m);
    }
    if out.is_empty() {
        return Err(Error::bad_input(
            path,
            None,
            "no measurements: add at least one row",
        ));
    }
    Ok(out)
}

/// The value of `m` in `table` (the file `m.file` of a run), or why it cannot be read: the
/// column is missing (listing those there are), no row or several rows match, or the cell is
/// not a finite number.
pub fn extract(m: &Measurement, table: &Table) -> Result<f64, String> {
    let (header, rows) = (table.header(), table.rows());
    let col = header.iter().position(|h| *h == m.column).ok_or_else(|| {
        format!(
            "{} has no column `{}`: it has {}",
            m.file,
            m.column,
            header.join(", ")
        )
    })?;
    let row = select(m, header, &rows)?;
    let cell = &rows[row][col];
    cell.parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
        .ok_or_else(|| {
            format!(
                "{} row {} column {}: `{cell}` is not a number",
                m.file, m.row, m.column
            )
        })
}

/// The index of the row `m.row` selects (see the module doc).
fn select(m: &Measurement, header: &[String], rows: &[Vec<String>]) -> Result<usize, String> {
    if let Ok(i) = m.row.parse::<usize>() {
        return if i < rows.len() {
            Ok(i)
        } else {
            Err(format!(
                "{} has {} data rows: row index {i} is out of range (0-based)",
                m.file,
                rows.len()
            ))
        };
    }
    let Some((name, want)) = m.row.split_once('=') else {
        return Err(format!(
            "row `{}`: allowed NAME=VALUE, id=VALUE or a 0-based row index",
            m.row
        ));
    };
    let (name, want) = (name.trim(), want.trim());
    let col = header.iter().position(|h| h == name).or_else(|| {
        (name == "id")
            .then(|| header.iter().position(|h| h.ends_with("_id")))
            .flatten()
    });
    let col = col.ok_or_else(|| format!("{} has no column `{name}` to select a row", m.file))?;
    let hits: Vec<usize> = (0..rows.len())
        .filter(|&i| rows[i].get(col).is_some_and(|c| c == want))
        .collect();
    match hits[..] {
        [i] => Ok(i),
        [] => Err(format!(
            "{} has no row with {} = {want}",
            m.file, header[col]
        )),
        _ => Err(format!(
            "{} has {} rows with {} = {want}: the selector must pick one",
            m.file,
            hits.len(),
            header[col]
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> Table {
        Table::with_rows(
            "summary.csv",
            ["sphere_id", "settling_distance_m"],
            vec![
                vec!["a".into(), "0.01".into()],
                vec!["b".into(), "0.02".into()],
                vec!["c".into(), "-".into()],
            ],
        )
    }

    fn m(column: &str, row: &str) -> Measurement {
        Measurement {
            file: "summary.csv".into(),
            column: column.into(),
            row: row.into(),
            value: 0.0,
            sigma: None,
        }
    }

    #[test]
    fn selectors() {
        let t = table();
        assert_eq!(extract(&m("settling_distance_m", "id=b"), &t), Ok(0.02));
        assert_eq!(
            extract(&m("settling_distance_m", "sphere_id=a"), &t),
            Ok(0.01)
        );
        assert_eq!(extract(&m("settling_distance_m", "1"), &t), Ok(0.02));
        assert!(extract(&m("settling_distance_m", "3"), &t).is_err());
        assert!(extract(&m("settling_distance_m", "id=z"), &t).is_err());
        assert!(extract(&m("settling_distance_m", "id=c"), &t).is_err());
        assert!(extract(&m("nope_m", "0"), &t)
            .unwrap_err()
            .contains("has no column `nope_m`"));
    }

    /// Issue 26 item 1: a measurements file exported with semicolons and decimal commas reads
    /// as its CSV, and a bad value names its row and line.
    #[test]
    fn an_exported_measurements_file_reads_as_the_csv() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
        std::fs::write(
            &a,
            "file,column,row,value,sigma\nsummary.csv,x_m,id=a,0.05063,5e-4\n",
        )
        .unwrap();
        std::fs::write(
            &b,
            "file;column;row;value;sigma\r\nsummary.csv;x_m;id=a;0,05063;5e-4\r\n",
        )
        .unwrap();
        let (ra, rb) = (
            read(&a.as_path().into()).unwrap(),
            read(&b.as_path().into()).unwrap(),
        );
        assert_eq!(ra, rb);
        assert_eq!(ra[0].value, 0.05063);
        std::fs::write(&b, "file;column;row;value\nsummary.csv;x_m;id=a;5 mm\n").unwrap();
        let e = read(&b.as_path().into()).unwrap_err().to_string();
        assert!(e.contains("row 1 (line 2), column value"), "{e}");
    }
}
