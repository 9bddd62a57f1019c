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
fn bad(file: &Path, msg: String) -> Error {
    Error::bad_input(file, None, msg)
}

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

/// The text a date or time cell of a workbook is read as.
const DATE_CELL: &str = "a date or time cell";

/// Reads a workbook: the sheet `readings` if any, else the first sheet that is not empty.
fn workbook(path: &Path, bytes: &[u8], ext: &str) -> Result<LabFile, Error> {
    use calamine::{open_workbook_auto_from_rs, Data, Reader};
    let cursor = std::io::Cursor::new(bytes.to_vec());
    let mut book = open_workbook_auto_from_rs(cursor).map_err(|e| {
        bad(
            path,
            format!(
                "not a workbook settle can read ({}): save it as .xlsx, .ods or CSV",
                first_line(&e.to_string())
            ),
        )
    })?;
    let format = if ext == "ods" || matches!(book, calamine::Sheets::Ods(_)) {
        Format::Ods
    } else {
        Format::Excel
    };
    let names = book.sheet_names().to_vec();
    let mut notes = Vec::new();
    let mut chosen = None;
    if let Some(n) = names.iter().find(|n| n.eq_ignore_ascii_case("readings")) {
        notes.push(format!("sheet `{n}`: named `readings`"));
        chosen = Some((n.clone(), read_range(&mut book, path, n)?));
    } else {
        for n in &names {
            let r = read_range(&mut book, path, n)?;
            if r.get_size().0 > 0 && r.used_cells().next().is_some() {
                notes.push(if names.len() == 1 {
                    format!("sheet `{n}`: the workbook's only sheet")
                } else {
                    format!(
                        "sheet `{n}`: the first that is not empty, of {} (name a sheet \
                         `readings` to choose another)",
                        names.len()
                    )
                });
                chosen = Some((n.clone(), r));
                break;
            }
        }
    }
    let Some((sheet, range)) = chosen else {
        return Err(bad(path, "the workbook has no cell filled in".into()));
    };
    let (r0, c0) = range.start().unwrap_or((0, 0));
    let mut rows = Vec::new();
    for (i, row) in range.rows().enumerate() {
        let line = r0 as usize + i + 1;
        let mut cells: Vec<String> = row
            .iter()
            .map(|d| match d {
                Data::Empty => String::new(),
                Data::String(s) => s.trim().to_string(),
                Data::Float(x) => format!("{x}"),
                Data::Int(x) => x.to_string(),
                Data::Bool(b) => b.to_string(),
                Data::DateTime(_) | Data::DateTimeIso(_) | Data::DurationIso(_) => {
                    DATE_CELL.to_string()
                }
                Data::Error(e) => format!("a cell with the error {e}"),
            })
            .collect();
        while cells.last().is_some_and(|c| c.is_empty()) {
            cells.pop();
        }
        // Leading empty columns of the used range are kept (the table may start in B).
        if cells.iter().all(|c| c.is_empty()) {
            continue;
        }
        let loc = Loc::Cell {
            sheet: sheet.clone(),
            row: line,
            col: c0 as usize,
        };
        let first = cells.iter().position(|c| !c.is_empty()).unwrap_or(0);
        if cells[first].starts_with('#') {
            let text = comment_text(&cells[first..]);
            rows.push(LabRow {
                loc: loc.at(first),
                cells: vec![text],
            });
        } else {
            rows.push(LabRow { loc, cells });
        }
    }
    fit_to_header(&mut rows, true);
    notes.push("numbers: the cells' own values (a text cell is read as written)".into());
    Ok(LabFile {
        path: path.to_path_buf(),
        rows,
        detected: Detected {
            format,
            sheet: Some(sheet),
            encoding: None,
            delimiter: None,
            decimal_mark: '.',
            line_ends: None,
            notes,
        },
    })
}

fn read_range<RS: std::io::Read + std::io::Seek>(
    book: &mut calamine::Sheets<RS>,
    path: &Path,
    name: &str,
) -> Result<calamine::Range<calamine::Data>, Error> {
    use calamine::Reader;
    book.worksheet_range(name).map_err(|e| {
        bad(
            path,
            format!(
                "sheet `{name}` cannot be read ({})",
                first_line(&e.to_string())
            ),
        )
    })
}

fn first_line(s: &str) -> &str {
    s.lines().next().unwrap_or(s)
}

/// The text of a `#` row from its cells: `# key = value` in the first cell, or `# key` in the
/// first and its value in the second (a key/value layout).
fn comment_text(cells: &[String]) -> String {
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

/// Decodes the bytes: a byte-order mark, else UTF-8 if valid, else Windows-1252.
fn decode(bytes: &[u8]) -> (String, String) {
    if let Some((enc, bom_len)) = encoding_rs::Encoding::for_bom(bytes) {
        let (text, _) = enc.decode_without_bom_handling(&bytes[bom_len..]);
        return (text.into_owned(), format!("{} with BOM", enc.name()));
    }
    match std::str::from_utf8(bytes) {
        Ok(s) => (s.to_string(), "UTF-8".into()),
        Err(_) => {
            let (text, _, _) = encoding_rs::WINDOWS_1252.decode(bytes);
            (text.into_owned(), "Windows-1252".into())
        }
    }
}

/// Whether `s` is a number written with `mark` as its decimal mark and digits on both sides
/// or after it (`45,5`, `-0,25`, `,5`, `1,5e-3`).
fn decimal_with(s: &str, mark: char) -> bool {
    let s = s.strip_prefix(['-', '+']).unwrap_or(s);
    let (mant, exp) = match s.find(['e', 'E']) {
        Some(i) => (&s[..i], Some(&s[i + 1..])),
        None => (s, None),
    };
    if let Some(e) = exp {
        let e = e.strip_prefix(['-', '+']).unwrap_or(e);
        if e.is_empty() || !e.bytes().all(|b| b.is_ascii_digit()) {
            return false;
        }
    }
    match mant.split_once(mark) {
        Some((a, b)) => {
            a.bytes().all(|c| c.is_ascii_digit())
                && !b.is_empty()
                && b.bytes().all(|c| c.is_ascii_digit())
        }
        None => false,
    }
}

/// Whether `s` is a number with a thousands separator (`1.234,5`, `1,234.5`, `1.234.567`).
fn thousands(s: &str) -> bool {
    let s = s.strip_prefix('-').unwrap_or(s);
    let digits_and_marks = !s.is_empty()
        && s.bytes()
            .all(|b| b.is_ascii_digit() || b == b'.' || b == b',')
        && s.bytes().next().is_some_and(|b| b.is_ascii_digit());
    let marks = s.bytes().filter(|b| *b == b'.' || *b == b',').count();
    digits_and_marks && (marks >= 2) && (s.contains('.') || s.contains(','))
}

/// The value of a `# key = value` text, if it has one.
fn comment_value(text: &str) -> Option<&str> {
    text.split_once('=').map(|(_, v)| v.trim())
}

/// Reads a delimiter-separated text file (see the module's rules).
fn csv_file(path: &Path, bytes: &[u8]) -> Result<LabFile, Error> {
    let (text, encoding) = decode(bytes);
    let crlf = text.matches("\r\n").count();
    let lf = text.matches('\n').count();
    let cr = text.matches('\r').count();
    let line_ends = if lf == 0 && cr == 0 {
        "none"
    } else if crlf == lf && crlf == cr {
        "CRLF"
    } else if lf == 0 {
        "CR"
    } else if crlf == 0 {
        "LF"
    } else {
        "mixed CRLF and LF"
    };
    let text = text.replace("\r\n", "\n").replace('\r', "\n");
    let lines: Vec<&str> = text.split('\n').collect();
    let line_starts: Vec<usize> = std::iter::once(0)
        .chain(text.match_indices('\n').map(|(i, _)| i + 1))
        .collect();
    let mut notes = vec![match encoding.as_str() {
        "UTF-8" => "encoding: UTF-8 (the bytes are valid UTF-8)".to_string(),
        "Windows-1252" => "encoding: Windows-1252 (Latin-1): the bytes are not UTF-8 and have \
                           no byte-order mark"
            .to_string(),
        e => format!("encoding: {e} (its byte-order mark)"),
    }];
    // The delimiter: decided by the header line.
    let is_comment_line = |l: &str| {
        let t = l.trim_start();
        t.starts_with('#') || t.starts_with("\"#")
    };
    let header = lines.iter().enumerate().find(|(_, l)| {
        let t = l.trim();
        !t.is_empty() && !is_comment_line(t) && t.chars().any(|c| !matches!(c, ',' | ';' | '\t'))
    });
    let delimiter = match header {
        Some((_, h)) if h.contains(';') => {
            notes.push("delimiter: semicolon (the header holds one)".into());
            ';'
        }
        Some((_, h)) if h.contains('\t') => {
            notes.push("delimiter: tab (the header holds one, and no semicolon)".into());
            '\t'
        }
        Some((_, h)) if h.contains(',') => {
            notes.push("delimiter: comma (the header holds one, and no semicolon or tab)".into());
            ','
        }
        _ => {
            notes.push("delimiter: comma (the header has a single column)".into());
            ','
        }
    };
    // Split every line into cells with the csv reader (quotes as RFC 4180).
    let mut rd = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(delimiter as u8)
        .from_reader(text.as_bytes());
    let mut rows = Vec::new();
    for rec in rd.records() {
        let rec = rec.map_err(|e| {
            let line = e.position().map(|p| p.line()).unwrap_or(0);
            bad(
                path,
                format!("line {line}: the line cannot be split into fields (an unclosed quote?)"),
            )
        })?;
        // The line from the record's byte offset (the csv reader's own line count skips blank
        // lines).
        let byte = rec.position().map(|p| p.byte() as usize).unwrap_or(0);
        let mut line = line_starts.partition_point(|&s| s <= byte);
        while lines
            .get(line.wrapping_sub(1))
            .is_some_and(|l| l.trim().is_empty())
            && line < lines.len()
        {
            line += 1;
        }
        let cells: Vec<String> = rec.iter().map(|c| c.trim().to_string()).collect();
        if cells.iter().all(|c| c.is_empty()) {
            continue;
        }
        let raw = lines.get(line.wrapping_sub(1)).copied().unwrap_or("");
        if cells[0].starts_with('#') {
            // A `#` line as written (its commas are text), without a spreadsheet's trailing
            // delimiters; a quoted one as its cells.
            let text = if raw.trim_start().starts_with('#') {
                raw.trim().trim_end_matches([delimiter, ' ']).to_string()
            } else {
                comment_text(&cells)
            };
            rows.push(LabRow {
                loc: Loc::Line(line),
                cells: vec![text],
            });
            continue;
        }
        rows.push(LabRow {
            loc: Loc::Line(line),
            cells,
        });
    }
    fit_to_header(&mut rows, false);
    // The decimal mark.
    let mut comma_at: Option<(Loc, usize, String)> = None;
    let mut point_at: Option<(Loc, usize, String)> = None;
    for r in &rows {
        let cells: Vec<&str> = if r.is_comment() {
            comment_value(&r.cells[0]).into_iter().collect()
        } else {
            r.cells.iter().map(String::as_str).collect()
        };
        for (j, c) in cells.iter().enumerate() {
            if thousands(c) {
                return Err(bad(
                    path,
                    format!(
                        "{}{}: `{c}` has a thousands separator: write numbers without one \
                         ({})",
                        r.loc,
                        column_words(r, j),
                        c.replace(['.', ','], "")
                    ),
                ));
            }
            if comma_at.is_none() && decimal_with(c, ',') {
                comma_at = Some((r.loc.clone(), j, c.to_string()));
            }
            if point_at.is_none() && decimal_with(c, '.') {
                point_at = Some((r.loc.clone(), j, c.to_string()));
            }
        }
    }
    let decimal_mark = if delimiter == ',' {
        notes.push("decimal mark: point (a comma separates the fields)".into());
        '.'
    } else {
        match (&comma_at, &point_at) {
            (Some((lc, jc, c)), Some((lp, jp, p))) => {
                return Err(bad(
                    path,
                    format!(
                        "numbers are written with both decimal marks: `{c}` ({lc}{}) and \
                         `{p}` ({lp}{}): use one throughout",
                        column_words_at(&rows, lc, *jc),
                        column_words_at(&rows, lp, *jp)
                    ),
                ))
            }
            (Some((l, _, c)), None) => {
                notes.push(format!(
                    "decimal mark: comma (`{c}` on {l}, no number written with a point)"
                ));
                ','
            }
            (None, Some(_)) => {
                notes.push("decimal mark: point (numbers are written with one)".into());
                '.'
            }
            (None, None) => {
                notes.push("decimal mark: point (no number has a fraction)".into());
                '.'
            }
        }
    };
    if decimal_mark == ',' {
        for r in &mut rows {
            if r.is_comment() {
                let t = &r.cells[0];
                if let Some((k, v)) = t.split_once('=') {
                    if decimal_with(v.trim(), ',') {
                        r.cells[0] = format!("{k}= {}", v.trim().replace(',', "."));
                    }
                }
            } else {
                for c in &mut r.cells {
                    if decimal_with(c, ',') {
                        *c = c.replace(',', ".");
                    }
                }
            }
        }
    }
    Ok(LabFile {
        path: path.to_path_buf(),
        rows,
        detected: Detected {
            format: Format::Csv,
            sheet: None,
            encoding: Some(encoding),
            delimiter: Some(delimiter),
            decimal_mark,
            line_ends: Some(line_ends.into()),
            notes,
        },
    })
}

/// Drops the empty cells a spreadsheet leaves after the last column: beyond the header's last
/// named column, in the header and in every row; with `pad` (a workbook, whose empty cells at
/// the end of a row are not stored), fills a short row up to the header's width.
fn fit_to_header(rows: &mut [LabRow], pad: bool) {
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
fn column_words(r: &LabRow, j: usize) -> String {
    if r.is_comment() {
        String::new()
    } else {
        format!(", column {}", j + 1)
    }
}

fn column_words_at(rows: &[LabRow], loc: &Loc, j: usize) -> String {
    rows.iter()
        .find(|r| &r.loc == loc)
        .map(|r| column_words(r, j))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(name: &str, bytes: &[u8]) -> LabFile {
        LabFile::from_bytes(Path::new(name), bytes).unwrap()
    }

    #[test]
    fn utf8_comma_csv() {
        let f = read(
            "a.csv",
            b"# dry_mass_g = 50\ntime_min,reading\n1,45.5\n\n2,40\n",
        );
        assert_eq!(f.detected.delimiter, Some(','));
        assert_eq!(f.detected.decimal_mark, '.');
        assert_eq!(f.detected.encoding.as_deref(), Some("UTF-8"));
        assert_eq!(f.detected.line_ends.as_deref(), Some("LF"));
        assert_eq!(f.rows.len(), 4);
        assert_eq!(f.rows[0].cells, vec!["# dry_mass_g = 50"]);
        assert_eq!(f.rows[2].cells, vec!["1", "45.5"]);
        assert_eq!(f.rows[3].loc, Loc::Line(5));
    }

    #[test]
    fn latin1_semicolon_decimal_comma_crlf() {
        let mut b = b"# note = 20 \xb0C; bath;;\r\n# dry_mass_g = 48,797;;\r\n".to_vec();
        b.extend_from_slice(b"time_min;reading;temperature_c\r\n1;45,5;21,5\r\n");
        let f = read("b.csv", &b);
        assert_eq!(f.detected.encoding.as_deref(), Some("Windows-1252"));
        assert_eq!(f.detected.delimiter, Some(';'));
        assert_eq!(f.detected.decimal_mark, ',');
        assert_eq!(f.detected.line_ends.as_deref(), Some("CRLF"));
        assert_eq!(f.rows[0].cells, vec!["# note = 20 °C; bath"]);
        assert_eq!(f.rows[1].cells, vec!["# dry_mass_g = 48.797"]);
        assert_eq!(f.rows[3].cells, vec!["1", "45.5", "21.5"]);
        assert!(f.detected.summary().contains("decimal comma"));
        assert!(f.detected.toml().contains("encoding = \"Windows-1252\""));
    }

    #[test]
    fn bom_and_mixed_marks_and_thousands() {
        let f = read("c.csv", "\u{feff}time_s;reading\n60;45.5\n".as_bytes());
        assert_eq!(f.detected.encoding.as_deref(), Some("UTF-8 with BOM"));
        assert_eq!(f.rows[0].cells, vec!["time_s", "reading"]);
        assert_eq!(f.detected.decimal_mark, '.');
        let e = LabFile::from_bytes(Path::new("d.csv"), b"a;b\n1,5;2.5\n").unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains("both decimal marks") && m.contains("`1,5`"),
            "{m}"
        );
        assert!(m.contains("line 2, column 1"), "{m}");
        let e = LabFile::from_bytes(Path::new("d.csv"), b"a;b\n1.234,5;2\n").unwrap_err();
        assert!(e.to_string().contains("thousands separator"), "{e}");
    }

    #[test]
    fn letters_and_hints() {
        assert_eq!(column_letters(0), "A");
        assert_eq!(column_letters(25), "Z");
        assert_eq!(column_letters(26), "AA");
        let l = Loc::Cell {
            sheet: "Sheet1".into(),
            row: 7,
            col: 0,
        };
        assert_eq!(l.at(2).to_string(), "cell Sheet1!C7");
        let f = read("a.csv", b"a,b\n1,2\n");
        assert!(number_hint("45 g", &f.detected).contains("the unit is the column's"));
        assert!(number_hint("0:01:00", &f.detected).contains("clock time"));
        assert!(number_hint("4,5", &f.detected).contains("comma-separated"));
    }
}
