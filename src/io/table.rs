//! Output tables in memory: what a CSV file of settle holds (its header and its cells, as the
//! file prints them), with a typed view of each column. A scene or a command builds its tables
//! here; [`super::outputs::Outputs::write_into`] writes them, and the library API hands them
//! to a caller (Rust or Python) without a file. A cell is kept as the text the file holds, so
//! a table and its file are equal cell for cell by construction: the numbers of settle's CSV
//! files are printed in a form that reads back to the same `f64` ([`super::fmt::num`]).

use std::borrow::Cow;
use std::io;
use std::sync::Arc;

/// One output table: a file name relative to the run's folder (`summary.csv`,
/// `pictures/t_10s.csv`), comment lines before the header (the `# key = value` lines of a
/// readings file; usually none), a header and rows of cells.
///
/// The cells are held as text, or, for a table of a row per grain (a snapshot's), as typed
/// columns ([`Cells`]) printed when the table is written or read: the same text either way
/// ([`super::fmt::num`]), in about a tenth of the memory, and a column can be shared with
/// other tables and files without a copy. Two tables are equal when their name, preamble,
/// header and printed cells are.
#[derive(Clone, Debug)]
pub struct Table {
    name: String,
    preamble: Vec<String>,
    header: Vec<String>,
    body: Body,
}

/// The cells of a [`Table`].
#[derive(Clone, Debug)]
enum Body {
    /// Rows of cells as the file prints them.
    Text(Vec<Vec<String>>),
    /// One typed column per header entry, all of the same length.
    Columns(Vec<Cells>),
}

/// A typed column of a [`Table`] held as values, printed as the file prints them: numbers by
/// [`super::fmt::num`] (which reads back to the same `f64`), flags as `true` / `false`. Shared
/// (`Arc`): cloning a table or handing its column to a file made from the same data copies
/// nothing.
#[derive(Clone, Debug)]
pub enum Cells {
    /// Numbers.
    Numbers(Arc<[f64]>),
    /// Flags.
    Flags(Arc<[bool]>),
}

impl Cells {
    /// Number of cells.
    pub fn len(&self) -> usize {
        match self {
            Cells::Numbers(v) => v.len(),
            Cells::Flags(v) => v.len(),
        }
    }

    /// True without cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The cell of row `i` as the file prints it.
    pub fn cell(&self, i: usize) -> String {
        match self {
            Cells::Numbers(v) => super::fmt::num(v[i]),
            Cells::Flags(v) => v[i].to_string(),
        }
    }
}

impl PartialEq for Table {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
            && self.preamble == other.preamble
            && self.header == other.header
            && self.len() == other.len()
            && self.rows() == other.rows()
    }
}

impl Eq for Table {}

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
            body: Body::Text(Vec::new()),
        }
    }

    /// A table of typed columns, one per header entry (see [`Cells`]). Panics (a bug of the
    /// caller) when the columns are not one per header entry, all of the same length.
    pub fn with_columns<S: Into<String>>(
        name: impl Into<String>,
        header: impl IntoIterator<Item = S>,
        columns: Vec<Cells>,
    ) -> Self {
        let mut t = Self::new(name, header);
        assert_eq!(
            columns.len(),
            t.header.len(),
            "{}: one column per header",
            t.name
        );
        assert!(
            columns.windows(2).all(|w| w[0].len() == w[1].len()),
            "{}: columns of one length",
            t.name
        );
        t.body = Body::Columns(columns);
        t
    }

    /// The typed columns of a table made by [`Table::with_columns`] (None for one of text).
    pub fn typed_columns(&self) -> Option<&[Cells]> {
        match &self.body {
            Body::Columns(c) => Some(c),
            Body::Text(_) => None,
        }
    }

    /// A table with its rows.
    pub fn with_rows<S: Into<String>>(
        name: impl Into<String>,
        header: impl IntoIterator<Item = S>,
        rows: Vec<Vec<String>>,
    ) -> Self {
        let mut t = Self::new(name, header);
        t.body = Body::Text(rows);
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

    /// Appends a row (one cell per column); a table of typed columns becomes one of text.
    pub fn push(&mut self, row: Vec<String>) {
        debug_assert_eq!(row.len(), self.header.len(), "{}: row width", self.name);
        if let Body::Columns(_) = self.body {
            self.body = Body::Text(self.rows().into_owned());
        }
        if let Body::Text(rows) = &mut self.body {
            rows.push(row);
        }
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

    /// The rows, each one cell per column, as the file prints them (printed here for a table
    /// of typed columns).
    pub fn rows(&self) -> Cow<'_, [Vec<String>]> {
        match &self.body {
            Body::Text(rows) => Cow::Borrowed(rows),
            Body::Columns(cols) => Cow::Owned(
                (0..self.len())
                    .map(|i| cols.iter().map(|c| c.cell(i)).collect())
                    .collect(),
            ),
        }
    }

    /// Number of rows (without the header).
    pub fn len(&self) -> usize {
        match &self.body {
            Body::Text(rows) => rows.len(),
            Body::Columns(cols) => cols.first().map_or(0, Cells::len),
        }
    }

    /// True without rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The column named `name`, typed ([`Column`]); None when the table has no such column.
    pub fn column(&self, name: &str) -> Option<Column> {
        let k = self.header.iter().position(|h| h == name)?;
        let rows = match &self.body {
            Body::Text(rows) => rows,
            Body::Columns(cols) => {
                return Some(match &cols[k] {
                    Cells::Numbers(v) => Column::Numbers(v.iter().map(|&x| Some(x)).collect()),
                    Cells::Flags(v) => Column::Text(v.iter().map(bool::to_string).collect()),
                })
            }
        };
        let cells = rows.iter().map(|r| r[k].as_str());
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
        let mut bytes = Vec::new();
        self.write_csv(&mut bytes)?;
        Ok(bytes)
    }

    /// Writes the bytes of [`Table::to_csv`] to `out`, a row at a time.
    pub fn write_csv(&self, out: &mut dyn io::Write) -> io::Result<()> {
        for l in &self.preamble {
            out.write_all(l.as_bytes())?;
            out.write_all(b"\n")?;
        }
        let mut w = csv::Writer::from_writer(out);
        w.write_record(&self.header).map_err(io::Error::other)?;
        match &self.body {
            Body::Text(rows) => {
                for r in rows {
                    w.write_record(r).map_err(io::Error::other)?;
                }
            }
            Body::Columns(cols) => {
                for i in 0..self.len() {
                    w.write_record(cols.iter().map(|c| c.cell(i)))
                        .map_err(io::Error::other)?;
                }
            }
        }
        w.flush()
    }

    /// Reads a table back from CSV bytes (leading `#` lines as the preamble, then the header),
    /// named `name`.
    pub fn from_csv(name: impl Into<String>, bytes: &[u8]) -> io::Result<Self> {
        let mut preamble = Vec::new();
        let mut bytes = bytes;
        while bytes.first() == Some(&b'#') {
            let end = bytes
                .iter()
                .position(|&b| b == b'\n')
                .unwrap_or(bytes.len());
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
        let mut rows = Vec::new();
        for rec in r.records() {
            let rec = rec.map_err(io::Error::other)?;
            rows.push(rec.iter().map(str::to_string).collect());
        }
        Ok(Self::with_rows(name, header, rows).with_preamble(preamble))
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
        let p = t
            .clone()
            .with_preamble(vec!["# instrument = pipette".into()]);
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

    #[test]
    fn typed_columns_print_as_the_text_table_prints_them() {
        let x: Arc<[f64]> = vec![0.5, 1.25e-7, 3e8, -0.0].into();
        let flags: Arc<[bool]> = vec![true, false, false, true].into();
        let typed = Table::with_columns(
            "s.csv",
            ["x_m", "settled"],
            vec![Cells::Numbers(x.clone()), Cells::Flags(flags)],
        );
        let mut text = Table::new("s.csv", ["x_m", "settled"]);
        for (x, f) in [
            ("0.5", "true"),
            ("1.25e-7", "false"),
            ("3e8", "false"),
            ("0", "true"),
        ] {
            text.push(vec![x.into(), f.into()]);
        }
        assert_eq!(typed.to_csv().unwrap(), text.to_csv().unwrap());
        assert_eq!(typed, text);
        assert_eq!(typed.len(), 4);
        assert_eq!(typed.f64s("x_m").unwrap(), vec![0.5, 1.25e-7, 3e8, 0.0]);
        assert_eq!(typed.column("settled"), text.column("settled"));
        let back = Table::from_csv("s.csv", &typed.to_csv().unwrap()).unwrap();
        assert_eq!(back, typed);
        // shared, not copied
        assert!(
            matches!(&typed.typed_columns().unwrap()[0], Cells::Numbers(v) if Arc::ptr_eq(v, &x))
        );
        let mut grown = typed.clone();
        grown.push(vec!["2".into(), "true".into()]);
        assert_eq!(grown.len(), 5);
        assert!(grown.typed_columns().is_none());
    }
}
