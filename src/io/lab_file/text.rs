//! A delimiter-separated text file read as a lab file: its encoding, line ends, delimiter and
//! decimal mark detected (the rules in the parent module's documentation).

use super::rows::{
    bad, column_words, column_words_at, comment_text, fit_to_header, Detected, Format, LabFile,
    LabRow, Loc,
};
use crate::error::Error;
use std::path::Path;

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
pub(super) fn csv_file(path: &Path, bytes: &[u8]) -> Result<LabFile, Error> {
    let (text, encoding) = decode(bytes);
    let line_ends = line_ends(&text);
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
    let delimiter = delimiter(&lines, &mut notes);
    let mut rows = split_rows(path, &text, &lines, &line_starts, delimiter)?;
    fit_to_header(&mut rows, false);
    let decimal_mark = decimal_mark(path, &rows, delimiter, &mut notes)?;
    if decimal_mark == ',' {
        to_decimal_point(&mut rows);
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

/// The line ends of a text, in words for the record.
fn line_ends(text: &str) -> &'static str {
    let crlf = text.matches("\r\n").count();
    let lf = text.matches('\n').count();
    let cr = text.matches('\r').count();
    if lf == 0 && cr == 0 {
        "none"
    } else if crlf == lf && crlf == cr {
        "CRLF"
    } else if lf == 0 {
        "CR"
    } else if crlf == 0 {
        "LF"
    } else {
        "mixed CRLF and LF"
    }
}

/// The delimiter, decided by the header line (the first line that is neither blank nor `#`).
fn delimiter(lines: &[&str], notes: &mut Vec<String>) -> char {
    // The delimiter: decided by the header line.
    let is_comment_line = |l: &str| {
        let t = l.trim_start();
        t.starts_with('#') || t.starts_with("\"#")
    };
    let header = lines.iter().enumerate().find(|(_, l)| {
        let t = l.trim();
        !t.is_empty() && !is_comment_line(t) && t.chars().any(|c| !matches!(c, ',' | ';' | '\t'))
    });
    match header {
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
    }
}

/// Splits every line into cells with the csv reader (quotes as RFC 4180); a `#` line is one
/// cell holding its text.
fn split_rows(
    path: &Path,
    text: &str,
    lines: &[&str],
    line_starts: &[usize],
    delimiter: char,
) -> Result<Vec<LabRow>, Error> {
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
    Ok(rows)
}

/// The decimal mark of a file's numbers (the module's rules); a number with a thousands
/// separator, or numbers written with both marks, refused.
fn decimal_mark(
    path: &Path,
    rows: &[LabRow],
    delimiter: char,
    notes: &mut Vec<String>,
) -> Result<char, Error> {
    // The decimal mark.
    let mut comma_at: Option<(Loc, usize, String)> = None;
    let mut point_at: Option<(Loc, usize, String)> = None;
    for r in rows {
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
    Ok(if delimiter == ',' {
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
                        column_words_at(rows, lc, *jc),
                        column_words_at(rows, lp, *jp)
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
    })
}

/// Rewrites the numbers written with a decimal comma with a point.
fn to_decimal_point(rows: &mut [LabRow]) {
    for r in rows.iter_mut() {
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
