//! Output tables in memory: what a CSV file of settle holds (its header and its cells, as the
//! file prints them), with a typed view of each column. A scene or a command builds its tables
//! here; [`super::outputs::Outputs::write_into`] writes them, and the library API hands them
//! to a caller (Rust or Python) without a file. A cell is kept as the text the file holds, so
//! a table and its file are equal cell for cell by construction: the numbers of settle's CSV
//! files are printed in a form that reads back to the same `f64` ([`super::fmt::num`]).

use std::io;

/// One output table: a file name relative to the run's folder (`summary.csv`,
/// `pictures/t_10s.csv`), comment lines before the header (the `# key = value` lines of a
/// readings file; usually none), a header and rows of cells.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Table {
    name: String,
    preamble: Vec<String>,
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

/// A column of a [`Table`], typed: numbers when every non-empty cell reads as a number
/// (`inf`, `-inf` and `NaN` included), text otherwise.
#[derive(Clone, Debug, PartialEq)]
pub enum Column {
    /// Numbers; an empty cell is `None`.
    Numbers(Vec<Option<f64>>),
    /// Text cells as written.
    Text(Vec<String>),
}

impl Column {
    /// The numbers of a numeric column (empty cells as NaN); None for a text column.
    pub fn to_f64(&self) -> Option<Vec<f64>> {
        match self {
            Column::Numbers(v) => Some(v.iter().map(|x| x.unwrap_or(f64::NAN)).collect()),
            Column::Text(_) => None,
        }
    }
}

impl Table {
    /// An empty table named `name` (a file name relative to the run's folder, ending in `.csv`)
    /// with the column names `header`.
    pub fn new<S: Into<String>>(
        name: impl Into<String>,
        header: impl IntoIterator<Item = S>,
    ) -> Self {
        Self {
            name: name.into(),
            preamble: Vec::new(),
            header: header.into_iter().map(Into::into).collect(),
            rows: Vec::new(),
        }
    }

    /// A table with its rows.
    pub fn with_rows<S: Into<String>>(
        name: impl Into<String>,
        header: impl IntoIterator<Item = S>,
        rows: Vec<Vec<String>>,
    ) -> Self {
        let mut t = Self::new(name, header);
        t.rows = rows;
        t
    }

    /// The table with the comment lines `lines` before its header (each written as given, `#`
    /// included, followed by a newline).
    pub fn with_preamble(mut self, lines: Vec<String>) -> Self {
        self.preamble = lines;
        self
    }

    /// The comment lines before the header (`# instrument = pipette`), as written.
    pub fn preamble(&self) -> &[String] {
        &self.preamble
    }

    /// Appends a row (one cell per column).
    pub fn push(&mut self, row: Vec<String>) {
        debug_assert_eq!(row.len(), self.header.len(), "{}: row width", self.name);
        self.rows.push(row);
    }

    /// The file name, relative to the run's folder (`summary.csv`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The file name without `.csv`: `summary`, `pictures/t_10s` (the key of the table in the
    /// library API).
    pub fn stem(&self) -> &str {
        self.name.strip_suffix(".csv").unwrap_or(&self.name)
    }

    /// The column names.
    pub fn header(&self) -> &[String] {
        &self.header
    }

    /// The rows, each one cell per column, as the file prints them.
    pub fn rows(&self) -> &[Vec<String>] {
        &self.rows
    }

    /// Number of rows (without the header).
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// True without rows.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The column named `name`, typed ([`Column`]); None when the table has no such column.
    pub fn column(&self, name: &str) -> Option<Column> {
        let k = self.header.iter().position(|h| h == name)?;
        let cells = self.rows.iter().map(|r| r[k].as_str());
        let numbers: Option<Vec<Option<f64>>> = cells
            .clone()
            .map(|c| {
                if c.is_empty() {
                    Some(None)
                } else {
                    c.parse::<f64>().ok().map(Some)
                }
            })
            .collect();
        Some(match numbers {
            Some(v) => Column::Numbers(v),
            None => Column::Text(cells.map(str::to_string).collect()),
        })
    }

    /// The numbers of column `name` (empty cells as NaN); None when absent or not numeric.
    pub fn f64s(&self, name: &str) -> Option<Vec<f64>> {
        self.column(name)?.to_f64()
    }

    /// The table as the bytes of its CSV file (RFC 4180 quoting where a cell needs it): the
    /// preamble lines, the header, the rows.
    pub fn to_csv(&self) -> io::Result<Vec<u8>> {
        let mut head = Vec::new();
        for l in &self.preamble {
            head.extend_from_slice(l.as_bytes());
            head.push(b'\n');
        }
        let mut w = csv::Writer::from_writer(head);
        w.write_record(&self.header).map_err(io::Error::other)?;
        for r in &self.rows {
            w.write_record(r).map_err(io::Error::other)?;
        }
        w.into_inner().map_err(|e| io::Error::other(e.to_string()))
    }

    /// Reads a table back from CSV bytes (leading `#` lines as the preamble, then the header),
    /// named `name`.
    pub fn from_csv(name: impl Into<String>, bytes: &[u8]) -> io::Result<Self> {
        let mut preamble = Vec::new();
        let mut bytes = bytes;
        while bytes.first() == Some(&b'#') {
            let end = bytes.iter().position(|&b| b == b'\n').unwrap_or(bytes.len());
            preamble.push(String::from_utf8_lossy(&bytes[..end]).into_owned());
            bytes = &bytes[(end + 1).min(bytes.len())..];
        }
        let mut r = csv::ReaderBuilder::new()
            .has_headers(true)
            .flexible(false)
            .from_reader(bytes);
        let header: Vec<String> = r
            .headers()
            .map_err(io::Error::other)?
            .iter()
            .map(str::to_string)
            .collect();
        let mut t = Self::new(name, header).with_preamble(preamble);
        for rec in r.records() {
            let rec = rec.map_err(io::Error::other)?;
            t.rows.push(rec.iter().map(str::to_string).collect());
        }
        Ok(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_bytes_read_back_to_the_same_table() {
        let mut t = Table::new("a.csv", ["x_m", "label"]);
        t.push(vec!["0.5".into(), "one, two".into()]);
        t.push(vec!["".into(), "say \"hi\"".into()]);
        let bytes = t.to_csv().unwrap();
        assert_eq!(
            String::from_utf8(bytes.clone()).unwrap(),
            "x_m,label\n0.5,\"one, two\"\n,\"say \"\"hi\"\"\"\n"
        );
        assert_eq!(Table::from_csv("a.csv", &bytes).unwrap(), t);
        assert_eq!(t.stem(), "a");
        let p = t.clone().with_preamble(vec!["# instrument = pipette".into()]);
        let bytes = p.to_csv().unwrap();
        assert!(bytes.starts_with(b"# instrument = pipette\nx_m,label\n"));
        assert_eq!(Table::from_csv("a.csv", &bytes).unwrap(), p);
    }

    #[test]
    fn columns_are_numbers_when_every_cell_reads_as_one() {
        let mut t = Table::new("b.csv", ["v", "s"]);
        t.push(vec!["1.25e-7".into(), "1".into()]);
        t.push(vec!["".into(), "x".into()]);
        t.push(vec!["inf".into(), "2".into()]);
        assert_eq!(
            t.column("v"),
            Some(Column::Numbers(vec![
                Some(1.25e-7),
                None,
                Some(f64::INFINITY)
            ]))
        );
        assert_eq!(
            t.column("s"),
            Some(Column::Text(vec!["1".into(), "x".into(), "2".into()]))
        );
        assert!(t.column("nope").is_none());
        assert!(t.f64s("s").is_none());
    }
}
