//! A workbook (`.xlsx`, `.xlsm`, `.xlsb`, `.xls`, `.ods`, crate `calamine`) read as a lab file.

use super::rows::{
    bad, comment_text, first_line, fit_to_header, Detected, Format, LabFile, LabRow, Loc,
};
use crate::error::Error;
use std::path::Path;

/// The text a date or time cell of a workbook is read as.
pub(super) const DATE_CELL: &str = "a date or time cell";

/// Reads a workbook: the sheet `readings` if any, else the first sheet that is not empty.
pub(super) fn workbook(path: &Path, bytes: &[u8], ext: &str) -> Result<LabFile, Error> {
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
