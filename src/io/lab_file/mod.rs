//! Lab files as laboratories keep them: one reader of tabular input files for every command
//! that reads a lab's table (the readings of `settle reduce` / `settle invert`, the spheres,
//! sample and reference tables of a scenario). It turns the bytes of
//!
//! - a CSV as spreadsheets export it: comma-, semicolon- or tab-separated, decimal point or
//!   decimal comma, UTF-8 with or without a byte-order mark, UTF-16 with its mark,
//!   Windows-1252 / Latin-1, LF, CRLF or CR line ends, quoted fields;
//! - an `.xlsx`, `.xlsm`, `.xlsb`, `.xls` or `.ods` workbook (crate `calamine`), laid out as the
//!   CSV: one row per line, one cell per field, the `# key = value` lines in the first cell (or
//!   the key `# key` in the first cell and its value in the second);
//!
//! into rows of text cells with numbers written with a decimal point, each row knowing where it
//! is (`line 9`, or `Sheet1!B9` for a cell), and says what it detected ([`Detected`]): the
//! callers put that into their run record. Nothing is guessed silently.
//!
//! # The rules (documented in `docs/commands/reduce.md`)
//!
//! - **Encoding**: a byte-order mark decides (UTF-8, UTF-16LE/BE); else UTF-8 if the bytes are
//!   valid UTF-8; else Windows-1252 (the superset of Latin-1 that Excel and LibreOffice write on
//!   Western-European Windows). The record says which.
//! - **Delimiter**: decided by the header (the first line that is neither blank nor a `#` line):
//!   a semicolon if it holds one, else a tab if it holds one, else a comma.
//! - **Decimal mark**: a point in a comma-separated file (a comma there separates fields). In a
//!   semicolon- or tab-separated file, a comma if some number is written with one (`45,5`) and
//!   none with a point; a point otherwise. A file that writes numbers both ways is refused,
//!   naming one of each; so is a number with a thousands separator (`1.234,5`, `1,234.5`).
//! - **Workbook sheet**: the sheet named `readings` (any case) if there is one, else the first
//!   sheet that is not empty. Numeric cells are read as the numbers they hold; a text cell
//!   is read as written.

mod rows;
#[cfg(test)]
mod tests;
mod text;
mod workbook;

pub use rows::{Detected, Format, LabFile, LabRow, Loc};

use crate::error::Error;
use std::path::Path;
use text::csv_file;
use workbook::{workbook, DATE_CELL};

impl LabFile {
    /// Reads the file `path` (a missing or unreadable file is [`Error::Io`]).
    pub fn read(path: &Path) -> Result<Self, Error> {
        let bytes = std::fs::read(path).map_err(|e| Error::Io(path.to_path_buf(), e))?;
        Self::from_bytes(path, &bytes)
    }

    /// Reads a lab file's bytes; `path` names it (its extension and the errors).
    pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<Self, Error> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        let zip = bytes.starts_with(b"PK\x03\x04");
        let ole = bytes.starts_with(&[0xD0, 0xCF, 0x11, 0xE0]);
        let workbook_ext = matches!(ext.as_str(), "xlsx" | "xlsm" | "xlsb" | "xls" | "ods");
        if zip || ole || workbook_ext {
            return workbook(path, bytes, &ext);
        }
        csv_file(path, bytes)
    }

    /// Reads CSV text (a table in memory written as its CSV); `path` names it in errors.
    pub fn from_text(path: &Path, text: &str) -> Result<Self, Error> {
        csv_file(path, text.as_bytes())
    }

    /// The file as a plain table: its header (the first row that is not a `#` row) and the
    /// data rows after it, `#` rows left out. A file without a header, or a data row with more
    /// fields than the header, is bad input naming the row's line (or cell); a shorter row is
    /// padded with empty cells (a spreadsheet does not store the empty cells at a row's end).
    pub fn table(self) -> Result<(Vec<String>, Vec<LabRow>), Error> {
        let path = self.path;
        let mut rows = self.rows.into_iter().filter(|r| !r.is_comment());
        let header = rows.next().map(|r| r.cells).ok_or_else(|| {
            Error::bad_input(&path, None, "the file has no header line (nor any row)")
        })?;
        let mut data = Vec::new();
        for (i, mut r) in rows.enumerate() {
            if r.cells.len() > header.len() {
                return Err(Error::bad_input(
                    &path,
                    Some(&format!("row {} ({})", i + 1, r.loc)),
                    format!(
                        "{} fields where the header has {}: one field per column (an empty \
                         field for an absent value)",
                        r.cells.len(),
                        header.len()
                    ),
                ));
            }
            r.cells.resize(header.len(), String::new());
            data.push(r);
        }
        Ok((header, data))
    }
}

/// A hint for a cell that is not a number, in words a lab engineer reads (empty when none
/// applies): a decimal comma in a comma-separated file, a unit in the cell, a clock time.
pub fn number_hint(cell: &str, detected: &Detected) -> String {
    let t = cell.trim();
    if t.contains(',') && t.chars().any(|c| c.is_ascii_digit()) {
        return if detected.format == Format::Csv && detected.delimiter == Some(',') {
            " (a decimal comma in a comma-separated file: write a decimal point, or save the \
             sheet as CSV with semicolons)"
                .into()
        } else {
            " (a decimal comma in a text cell: write a decimal point, or format the cell as a \
             number)"
                .into()
        };
    }
    if t == DATE_CELL || t.contains(':') {
        return " (a date or clock time: enter the elapsed time as a number in the column's unit)"
            .into();
    }
    let lead: String = t
        .chars()
        .take_while(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E'))
        .collect();
    if !lead.is_empty() && lead.parse::<f64>().is_ok() && lead.len() < t.len() {
        return format!(
            " (a number followed by `{}`: give the number alone, the unit is the column's)",
            t[lead.len()..].trim()
        );
    }
    String::new()
}
