//! The lab file reader on small files written in memory.

use super::rows::column_letters;
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
