//! A CSV file as an HTML table a person can read on one screen: numbers to a few significant
//! digits and right-aligned, long tables cut (the rest counted and linked), columns empty in
//! every row left out, columns with one value in every row of a long table said once above it,
//! and two-column tables (`quantity,value`) laid out as a compact grid.

use super::html::{cell, esc, href};
use std::fmt::Write as _;

/// Rows from which a column with the same value in every row is said once instead of repeated.
const FOLD_CONSTANT_FROM_ROWS: usize = 6;

/// Estimated width, px, from which a table takes the whole window's width rather than the
/// text's (the text column is 1180 px wide at most).
const WIDE_FROM_PX: f64 = 1100.0;

/// A rough width of a table as drawn, px: per column the widest of its cells and of the pieces
/// of its header (broken after `_`), at ~7 px a character, plus padding and borders.
fn estimated_width_px(
    header: &[String],
    rows: &[Vec<String>],
    shown: &[usize],
    max_rows: usize,
) -> f64 {
    shown
        .iter()
        .map(|&c| {
            let head = header[c]
                .split('_')
                .map(|p| p.chars().count() + 1)
                .max()
                .unwrap_or(0);
            let cells = rows
                .iter()
                .take(max_rows)
                .map(|r| cell(r.get(c).map_or("", String::as_str)).0.chars().count())
                .max()
                .unwrap_or(0);
            head.max(cells) as f64 * 7.0 + 13.0
        })
        .sum()
}

/// A CSV file's header and rows from its bytes; `None` when it is not readable as CSV.
fn read(bytes: &[u8]) -> Option<(Vec<String>, Vec<Vec<String>>)> {
    let mut rd = csv::ReaderBuilder::new().flexible(true).from_reader(bytes);
    let header: Vec<String> = rd.headers().ok()?.iter().map(str::to_string).collect();
    let rows = rd
        .records()
        .map(|r| r.map(|r| r.iter().map(str::to_string).collect::<Vec<_>>()))
        .collect::<Result<Vec<_>, _>>()
        .ok()?;
    Some((header, rows))
}

/// A table header cell: the CSV column name, with break opportunities after `_` so that long
/// names (`v_force_balance_m_s`) wrap instead of widening the table.
fn header_cell(name: &str) -> String {
    esc(name).replace('_', "_<wbr>")
}

/// One data cell: numbers right-aligned, rounded ones with the CSV's value as a tooltip.
fn data_cell(raw: &str) -> String {
    let (shown, numeric) = cell(raw);
    if numeric && shown != raw.trim() {
        format!(
            "<td class=\"n\" title=\"{}\">{}</td>",
            esc(raw.trim()),
            esc(&shown)
        )
    } else if numeric {
        format!("<td class=\"n\">{}</td>", esc(&shown))
    } else if shown.chars().count() <= SHORT_TEXT_CHARS {
        format!("<td class=\"t\">{}</td>", esc(&shown))
    } else {
        format!("<td>{}</td>", esc(&shown))
    }
}

/// Text cells up to this many characters are never broken over lines (`fedem-table1`).
const SHORT_TEXT_CHARS: usize = 24;

/// The HTML of the CSV file `bytes` (linked as `rel`): at most `max_rows` rows, then a line
/// saying how many more the file has. `None` when the file cannot be read as CSV.
pub fn csv_table(bytes: &[u8], rel: &str, max_rows: usize) -> Option<String> {
    let (header, rows) = read(bytes)?;
    let total = rows.len();
    let value = |r: &Vec<String>, c: usize| r.get(c).map_or("", |v| v.trim()).to_string();
    let empty: Vec<usize> = (0..header.len())
        .filter(|&c| total > 0 && rows.iter().all(|r| value(r, c).is_empty()))
        .collect();
    let constant: Vec<usize> = (0..header.len())
        .filter(|&c| {
            total >= FOLD_CONSTANT_FROM_ROWS
                && !empty.contains(&c)
                && rows.iter().all(|r| value(r, c) == value(&rows[0], c))
        })
        .collect();
    let shown: Vec<usize> = (0..header.len())
        .filter(|c| !empty.contains(c) && !constant.contains(c))
        .collect();
    let mut h = String::new();
    if !constant.is_empty() {
        let items: Vec<String> = constant
            .iter()
            .map(|&c| {
                format!(
                    "<code>{}</code> = {}",
                    esc(&header[c]),
                    esc(&cell(&value(&rows[0], c)).0)
                )
            })
            .collect();
        let _ = write!(
            h,
            "<p class=\"note\">In every row: {}.</p>",
            items.join(", ")
        );
    }
    if header.len() == 2 && empty.is_empty() && constant.is_empty() {
        h.push_str(&key_value_grid(&header, &rows[..total.min(max_rows)]));
    } else {
        let wide = if estimated_width_px(&header, &rows, &shown, max_rows) > WIDE_FROM_PX {
            " wide"
        } else {
            ""
        };
        let _ = write!(h, "<div class=\"scroll{wide}\"><table><thead><tr>");
        for &c in &shown {
            let _ = write!(h, "<th>{}</th>", header_cell(&header[c]));
        }
        h.push_str("</tr></thead><tbody>\n");
        for r in rows.iter().take(max_rows) {
            h.push_str("<tr>");
            for &c in &shown {
                h.push_str(&data_cell(r.get(c).map_or("", String::as_str)));
            }
            h.push_str("</tr>\n");
        }
        h.push_str("</tbody></table></div>\n");
    }
    if !empty.is_empty() {
        let names: Vec<String> = empty
            .iter()
            .map(|&c| format!("<code>{}</code>", esc(&header[c])))
            .collect();
        let _ = write!(
            h,
            "<p class=\"note\">Empty in every row, not shown: {}.</p>",
            names.join(", ")
        );
    }
    if total > max_rows {
        let _ = writeln!(
            h,
            "<p class=\"note\">… {} more rows in <a href=\"{}\">{}</a> ({total} rows in all).</p>",
            total - max_rows,
            href(rel),
            esc(rel)
        );
    }
    Some(h)
}

/// A two-column table (`quantity,value`) as a grid of name–value pairs, several per line.
fn key_value_grid(header: &[String], rows: &[Vec<String>]) -> String {
    let mut h = format!(
        "<div class=\"kv\" title=\"{} / {}\">",
        esc(&header[0]),
        esc(&header[1])
    );
    for r in rows {
        let key = r.first().map_or("", String::as_str);
        let raw = r.get(1).map_or("", String::as_str);
        let (shown, numeric) = cell(raw);
        let _ = write!(
            h,
            "<div><span class=\"k\">{}</span><span class=\"v{}\" title=\"{}\">{}</span></div>",
            esc(key),
            if numeric { " n" } else { "" },
            esc(raw.trim()),
            esc(&shown)
        );
    }
    h.push_str("</div>\n");
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(text: &str, max_rows: usize) -> String {
        csv_table(text.as_bytes(), "t.csv", max_rows).unwrap()
    }

    #[test]
    fn long_tables_are_cut_and_counted() {
        let mut text = String::from("id,x\n");
        for i in 0..40 {
            text.push_str(&format!("r{i},{}.5\n", i));
        }
        let h = table(&text, 30);
        assert!(h.contains("r29") && !h.contains("r30"), "{h}");
        assert!(h.contains("… 10 more rows in <a href=\"t.csv\">"), "{h}");
    }

    #[test]
    fn empty_and_constant_columns_are_said_once() {
        let mut text = String::from("id,dt_s,blank,v\n");
        for i in 0..8 {
            text.push_str(&format!("s{i},0.001,,0.{i}1234567\n"));
        }
        let h = table(&text, 30);
        assert!(h.contains("In every row: <code>dt_s</code> = 0.001"), "{h}");
        assert!(h.contains("not shown: <code>blank</code>"), "{h}");
        assert!(!h.contains("<th>dt_<wbr>s</th>"), "{h}");
        assert!(
            h.contains("<td class=\"n\" title=\"0.71234567\">0.7123</td>"),
            "{h}"
        );
    }

    #[test]
    fn text_cells_are_escaped() {
        let h = table("a,b,c\n<x>,1,2\n", 30);
        assert!(
            h.contains("<td class=\"t\">&lt;x&gt;</td>") && !h.contains("<x>"),
            "{h}"
        );
    }
}
