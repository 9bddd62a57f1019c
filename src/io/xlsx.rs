//! A table as an `.xlsx` workbook (crate `rust_xlsxwriter`): one sheet named after the table's
//! stem, the header in row 1, one row per table row below it. A cell that reads as a finite
//! number (as the CSV writes it) is written as a number, anything else as text, so that a
//! spreadsheet and `pandas.read_excel` give back the CSV's values.

use super::table::Table;
use rust_xlsxwriter::{DocProperties, ExcelDateTime, Format, Workbook, XlsxError};
use std::io;

/// The workbook of `t`, as bytes: sheet `t.stem()` (cut to Excel's 31 characters), the header
/// in bold and frozen, numbers as numbers. The document's creation time is fixed (2000-01-01),
/// so that the same table always gives the same bytes.
pub fn table_xlsx(t: &Table) -> io::Result<Vec<u8>> {
    workbook(t).map_err(|e| io::Error::other(format!("writing the workbook of {}: {e}", t.name())))
}

fn workbook(t: &Table) -> Result<Vec<u8>, XlsxError> {
    let mut wb = Workbook::new();
    let created = ExcelDateTime::from_ymd(2000, 1, 1)?;
    wb.set_properties(&DocProperties::new().set_creation_datetime(&created));
    let sheet = wb.add_worksheet();
    let name: String = t
        .stem()
        .chars()
        .filter(|c| !"[]:*?/\\".contains(*c))
        .take(31)
        .collect();
    if !name.is_empty() {
        sheet.set_name(name)?;
    }
    let bold = Format::new().set_bold();
    for (c, h) in t.header().iter().enumerate() {
        sheet.write_string_with_format(0, col(c)?, h, &bold)?;
    }
    for (r, row) in t.rows().iter().enumerate() {
        let r = u32::try_from(r + 1).map_err(|_| XlsxError::RowColumnLimitError)?;
        for (c, cell) in row.iter().enumerate() {
            match cell.trim().parse::<f64>() {
                Ok(x) if x.is_finite() => sheet.write_number(r, col(c)?, x)?,
                _ => sheet.write_string(r, col(c)?, cell)?,
            };
        }
    }
    sheet.set_freeze_panes(1, 0)?;
    wb.save_to_buffer()
}

fn col(c: usize) -> Result<u16, XlsxError> {
    u16::try_from(c).map_err(|_| XlsxError::RowColumnLimitError)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The workbook is a zip holding the sheet; calamine (the crate settle reads workbooks with)
    /// reads back the numbers and the text.
    #[test]
    fn reads_back_with_calamine() {
        use calamine::{Data, Reader, Xlsx};
        let t = Table::with_rows(
            "percent_finer.csv",
            ["diameter_m", "note"],
            vec![
                vec!["1.5e-5".into(), "a".into()],
                vec!["0.25".into(), "".into()],
            ],
        );
        let bytes = table_xlsx(&t).unwrap();
        assert_eq!(&bytes[..2], b"PK");
        assert_eq!(bytes, table_xlsx(&t).unwrap(), "not deterministic");
        let mut wb = Xlsx::new(std::io::Cursor::new(bytes)).unwrap();
        let r = wb.worksheet_range("percent_finer").unwrap();
        assert_eq!(r.get((0, 0)), Some(&Data::String("diameter_m".into())));
        assert_eq!(r.get((1, 0)), Some(&Data::Float(1.5e-5)));
        assert_eq!(r.get((1, 1)), Some(&Data::String("a".into())));
        assert_eq!(r.get((2, 0)), Some(&Data::Float(0.25)));
    }
}
