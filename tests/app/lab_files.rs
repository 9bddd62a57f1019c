//! Lab files as labs keep them (issue 26, item 1): the same readings sheet as a UTF-8 CSV, as a
//! semicolon + decimal comma + Windows-1252 (Latin-1) CSV with CRLF, as a UTF-8-with-BOM
//! semicolon CSV, as `.xlsx` (laid out as the CSV, and with the figures as key/value cells) and
//! as `.ods` reduces to identical `percent_finer.csv` and `percent_finer.svg` (byte for byte),
//! and `reduce.toml` says how each was read. Fixtures: `scripts/make_lab_fixtures.py`.

use crate::common::{assert_exit, settle_command, tmp};
use std::path::Path;

/// (folder, file, what reduce.toml's `[input]` must say, the console's `read as` line).
const FORMATS: [(&str, &str, &[&str], Option<&str>); 6] = [
    (
        "utf8",
        "soil_b3.csv",
        &[
            "format = \"csv\"",
            "encoding = \"UTF-8\"",
            "delimiter = \"comma\"",
            "decimal_mark = \".\"",
            "line_ends = \"LF\"",
        ],
        None,
    ),
    (
        "latin1",
        "soil_b3.csv",
        &[
            "encoding = \"Windows-1252\"",
            "delimiter = \"semicolon\"",
            "decimal_mark = \",\"",
            "line_ends = \"CRLF\"",
            "`48,797` on line 5",
        ],
        Some("read as: CSV, Windows-1252, semicolon-separated, decimal comma, CRLF line ends"),
    ),
    (
        "bom",
        "soil_b3.csv",
        &[
            "encoding = \"UTF-8 with BOM\"",
            "delimiter = \"semicolon\"",
            "decimal_mark = \",\"",
        ],
        Some("read as: CSV, UTF-8 with BOM, semicolon-separated, decimal comma"),
    ),
    (
        "xlsx",
        "soil_b3.xlsx",
        &[
            "format = \"excel\"",
            "sheet = \"Sheet1\"",
            "the workbook's only sheet",
        ],
        Some("read as: Excel workbook, sheet `Sheet1`"),
    ),
    (
        "kv",
        "soil_b3.xlsx",
        &["format = \"excel\"", "sheet = \"Sheet1\""],
        Some("read as: Excel workbook, sheet `Sheet1`"),
    ),
    (
        "ods",
        "soil_b3.ods",
        &["format = \"ods\"", "sheet = \"Sheet1\""],
        Some("read as: OpenDocument workbook, sheet `Sheet1`"),
    ),
];

#[test]
fn the_same_sheet_in_every_lab_format_reduces_to_identical_files() {
    let out = tmp();
    let mut first: Option<(Vec<u8>, Vec<u8>)> = None;
    for (dir, name, record, read_as) in FORMATS {
        let file = Path::new("tests/data/lab").join(dir).join(name);
        let o = settle_command(
            "reduce",
            &[file.to_str().unwrap()],
            &out.path().join(dir),
            &[],
        );
        assert_exit(&o, 0);
        let stdout = String::from_utf8_lossy(&o.stdout);
        assert!(
            stdout.contains("ASTM D7928, 152H, 8 readings"),
            "{dir}: {stdout}"
        );
        match read_as {
            Some(r) => assert!(
                stdout.lines().nth(1).unwrap().contains(r),
                "{dir}: {stdout}"
            ),
            None => assert!(!stdout.contains("read as"), "{dir}: {stdout}"),
        }
        let res = out.path().join(dir).join("soil_b3_reduced");
        let csv = std::fs::read(res.join("percent_finer.csv")).unwrap();
        let svg = std::fs::read(res.join("percent_finer.svg")).unwrap();
        let toml = std::fs::read_to_string(res.join("reduce.toml")).unwrap();
        let input = toml
            .split("[input]")
            .nth(1)
            .unwrap_or_else(|| panic!("{dir}: {toml}"));
        for r in record {
            assert!(input.contains(r), "{dir}: no `{r}` in {input}");
        }
        // Everything above [input] is the same for every format but the input's path.
        let above = toml
            .split("[input]")
            .next()
            .unwrap()
            .replace(&file.display().to_string(), "F");
        match &first {
            None => {
                assert_eq!(csv.iter().filter(|b| **b == b'\n').count(), 9);
                first = Some((csv, svg));
                std::fs::write(out.path().join("above.toml"), above).unwrap();
            }
            Some((c0, s0)) => {
                assert!(csv == *c0, "{dir}: percent_finer.csv differs");
                assert!(svg == *s0, "{dir}: percent_finer.svg differs");
                let a0 = std::fs::read_to_string(out.path().join("above.toml")).unwrap();
                assert_eq!(above, a0, "{dir}: reduce.toml differs");
            }
        }
    }
}

/// The README's lab quick start: `settle reduce --template d7928` prints a template whose
/// figures and schedule are the standard's; filled in, it reduces, and inverts.
#[test]
fn the_template_filled_in_reduces() {
    for (standard, n, header) in [
        ("d7928", 8, "time_min,reading,temperature_c,blank_reading"),
        ("d422", 7, "time_min,reading,temperature_c"),
    ] {
        let o = crate::common::settle()
            .args(["reduce", "--template", standard])
            .output()
            .unwrap();
        assert_exit(&o, 0);
        let t = String::from_utf8(o.stdout).unwrap();
        assert!(t.contains(&format!("# standard = {standard}")), "{t}");
        assert!(t.contains(header), "{t}");
        // Fill the readings: 40 g/L falling by 3 per reading, 20 °C, blank 6.
        let mut k = 0;
        let filled: String = t
            .lines()
            .map(|l| {
                if l.ends_with(",,,") || (l.ends_with(",,") && !l.starts_with('#')) {
                    k += 1;
                    let time = l.split(',').next().unwrap();
                    let r = 40.0 - 3.0 * k as f64;
                    if standard == "d7928" {
                        format!("{time},{r},20,6\n")
                    } else {
                        format!("{time},{r},20\n")
                    }
                } else {
                    format!("{l}\n")
                }
            })
            .collect();
        assert_eq!(k, n, "{t}");
        let dir = tmp();
        let f = dir.path().join("sheet.csv");
        std::fs::write(&f, filled).unwrap();
        let o = settle_command(
            "reduce",
            &[f.to_str().unwrap()],
            &dir.path().join("out"),
            &[],
        );
        assert_exit(&o, 0);
        let s = String::from_utf8_lossy(&o.stdout);
        assert!(s.contains(&format!("{n} readings")), "{s}");
        assert!(dir.path().join("out/sheet_reduced/reduce.toml").is_file());
        // The README's step 4: invert the same sheet.
        if standard == "d7928" {
            let o = settle_command(
                "invert",
                &[f.to_str().unwrap()],
                &dir.path().join("out"),
                &["--repeats", "10"],
            );
            assert_exit(&o, 0);
            let t =
                std::fs::read_to_string(dir.path().join("out/sheet_inverted/invert.toml")).unwrap();
            assert!(t.contains("[file.input]\nformat = \"csv\""), "{t}");
        }
    }
}
