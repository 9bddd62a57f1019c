//! The rows of a lab file, where each is, and what the reader detected; the helpers the text
//! and the workbook readers share.

use crate::error::Error;
use std::fmt;
use std::path::{Path, PathBuf};

/// Where a row (or a cell) of a lab file is: a line of a CSV, or a row of a workbook's sheet.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Loc {
    /// Line `n` (1-based, as an editor numbers it) of a text file.
    Line(usize),
    /// A cell of a sheet: the sheet's name, the row (1-based, as the spreadsheet numbers it)
    /// and the column (0-based).
    Cell {
        /// The sheet's name.
        sheet: String,
        /// Row, 1-based.
        row: usize,
        /// Column, 0-based (`A` is 0).
        col: usize,
    },
}

impl Loc {
    /// The same row, at the field `field` (0-based) of the row.
    pub fn at(&self, field: usize) -> Loc {
        match self {
            Loc::Line(n) => Loc::Line(*n),
            Loc::Cell { sheet, row, col } => Loc::Cell {
                sheet: sheet.clone(),
                row: *row,
                col: col + field,
            },
        }
    }
}

/// `line 9`, or `cell Sheet1!B9`.
impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Loc::Line(n) => write!(f, "line {n}"),
            Loc::Cell { sheet, row, col } => {
                write!(f, "cell {sheet}!{}{row}", column_letters(*col))
            }
        }
    }
}

/// The spreadsheet letters of column `col` (0-based): `A`, …, `Z`, `AA`, ….
pub fn column_letters(col: usize) -> String {
    let mut n = col + 1;
    let mut s = Vec::new();
    while n > 0 {
        let r = (n - 1) % 26;
        s.push(b'A' + r as u8);
        n = (n - 1) / 26;
    }
    s.reverse();
    String::from_utf8(s).unwrap_or_default()
}

/// One row of a lab file: its place and its cells (trimmed; numbers with a decimal point). A
/// `#` row is one cell, its whole text (`# dry_mass_g = 50`).
#[derive(Clone, Debug, PartialEq)]
pub struct LabRow {
    /// Where the row is (its first cell, for a workbook).
    pub loc: Loc,
    /// The cells.
    pub cells: Vec<String>,
}

impl LabRow {
    /// Whether the row is a comment or `# key = value` line.
    pub fn is_comment(&self) -> bool {
        self.cells.first().is_some_and(|c| c.starts_with('#'))
    }
}

/// The kind of a lab file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Text, delimiter-separated.
    Csv,
    /// An Excel workbook (`.xlsx`, `.xlsm`, `.xlsb`, `.xls`).
    Excel,
    /// An OpenDocument spreadsheet (`.ods`).
    Ods,
}

/// What was detected in a lab file, for the run record and the console.
#[derive(Clone, Debug, PartialEq)]
pub struct Detected {
    /// The kind of file.
    pub format: Format,
    /// The sheet read (workbooks).
    pub sheet: Option<String>,
    /// The text encoding (CSV): `UTF-8`, `UTF-8 with BOM`, `UTF-16LE with BOM`, `Windows-1252`.
    pub encoding: Option<String>,
    /// The field delimiter (CSV).
    pub delimiter: Option<char>,
    /// The decimal mark of the numbers: `.` or `,` (a workbook's numeric cells: `.`).
    pub decimal_mark: char,
    /// The line ends (CSV): `LF`, `CRLF`, `CR` (or `none` for a one-line file).
    pub line_ends: Option<String>,
    /// How each choice was made, one sentence each.
    pub notes: Vec<String>,
}

impl Detected {
    /// One line for the console: `CSV, Windows-1252, semicolon-separated, decimal comma, CRLF`.
    pub fn summary(&self) -> String {
        match self.format {
            Format::Csv => format!(
                "CSV, {}, {}-separated, decimal {}, {} line ends",
                self.encoding.as_deref().unwrap_or("?"),
                delimiter_name(self.delimiter.unwrap_or(',')),
                mark_name(self.decimal_mark),
                self.line_ends.as_deref().unwrap_or("?")
            ),
            Format::Excel | Format::Ods => format!(
                "{} workbook, sheet `{}`",
                if self.format == Format::Ods {
                    "OpenDocument"
                } else {
                    "Excel"
                },
                self.sheet.as_deref().unwrap_or("?")
            ),
        }
    }

    /// The `[input]` table of a run record (TOML): format, sheet, encoding, delimiter, decimal
    /// mark, line ends and the notes.
    pub fn toml(&self) -> String {
        let mut t = format!(
            "format = \"{}\"\n",
            match self.format {
                Format::Csv => "csv",
                Format::Excel => "excel",
                Format::Ods => "ods",
            }
        );
        if let Some(s) = &self.sheet {
            t.push_str(&format!("sheet = {s:?}\n"));
        }
        if let Some(e) = &self.encoding {
            t.push_str(&format!("encoding = {e:?}\n"));
        }
        if let Some(d) = self.delimiter {
            t.push_str(&format!("delimiter = \"{}\"\n", delimiter_name(d)));
        }
        t.push_str(&format!("decimal_mark = \"{}\"\n", self.decimal_mark));
        if let Some(l) = &self.line_ends {
            t.push_str(&format!("line_ends = {l:?}\n"));
        }
        t.push_str(&format!("detected = {:?}\n", self.notes));
        t
    }
}

fn delimiter_name(d: char) -> &'static str {
    match d {
        ';' => "semicolon",
        '\t' => "tab",
        _ => "comma",
    }
}

fn mark_name(m: char) -> &'static str {
    if m == ',' {
        "comma"
    } else {
        "point"
    }
}

/// A lab file read: its rows (blank rows left out) and what was detected.
#[derive(Clone, Debug, PartialEq)]
pub struct LabFile {
    /// The file (or the name of the table in memory).
    pub path: PathBuf,
    /// The rows, blank ones left out, `#` rows included.
    pub rows: Vec<LabRow>,
    /// What was detected.
    pub detected: Detected,
}

/// Bad input in `file`.
pub(super) fn bad(file: &Path, msg: String) -> Error {
    Error::bad_input(file, None, msg)
}

pub(super) fn first_line(s: &str) -> &str {
    s.lines().next().unwrap_or(s)
}

/// The text of a `#` row from its cells: `# key = value` in the first cell, or `# key` in the
/// first and its value in the second (a key/value layout).
pub(super) fn comment_text(cells: &[String]) -> String {
    let first = cells[0].trim();
    let rest: Vec<&str> = cells[1..]
        .iter()
        .map(|c| c.trim())
        .filter(|c| !c.is_empty())
        .collect();
    if first.contains('=') || rest.is_empty() {
        if rest.is_empty() {
            first.to_string()
        } else {
            format!("{first} {}", rest.join(" "))
        }
    } else {
        format!("{first} = {}", rest.join(" "))
    }
}

/// Drops the empty cells a spreadsheet leaves after the last column: beyond the header's last
/// named column, in the header and in every row; with `pad` (a workbook, whose empty cells at
/// the end of a row are not stored), fills a short row up to the header's width.
pub(super) fn fit_to_header(rows: &mut [LabRow], pad: bool) {
    let mut width = None;
    for r in rows.iter_mut().filter(|r| !r.is_comment()) {
        let w = *width.get_or_insert_with(|| {
            r.cells
                .iter()
                .rposition(|c| !c.is_empty())
                .map_or(0, |k| k + 1)
        });
        while r.cells.len() > w && r.cells.last().is_some_and(|c| c.is_empty()) {
            r.cells.pop();
        }
        if pad && r.cells.len() < w {
            r.cells.resize(w, String::new());
        }
    }
}

/// `, column 2` for a field of a table row (nothing for a `#` row).
pub(super) fn column_words(r: &LabRow, j: usize) -> String {
    if r.is_comment() {
        String::new()
    } else {
        format!(", column {}", j + 1)
    }
}

pub(super) fn column_words_at(rows: &[LabRow], loc: &Loc, j: usize) -> String {
    rows.iter()
        .find(|r| &r.loc == loc)
        .map(|r| column_words(r, j))
        .unwrap_or_default()
}
