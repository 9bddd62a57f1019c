//! `settle reduce` (`src/reduce/`): the worked examples of docs/commands/reduce.md reduce to
//! their published figures, and every bad input is one error naming the file, the row and the
//! column (or the key) and what is allowed, exit 2, nothing written.

use crate::common::chart::assert_readable_chart;
use crate::common::{assert_exit, read_csv_records, settle, tmp, tree};
use std::path::Path;

fn reduce(file: &Path, out: &Path, args: &[&str]) -> std::process::Output {
    settle()
        .arg("reduce")
        .arg(file)
        .arg("--out")
        .arg(out)
        .args(args)
        .output()
        .expect("spawn settle")
}

fn num(r: &std::collections::HashMap<String, String>, k: &str) -> f64 {
    r[k].parse()
        .unwrap_or_else(|e| panic!("{k} = `{}`: {e}", r[k]))
}

/// docs/commands/reduce.md, D422: envalysis' clay loam (data/lab/README.md).
#[test]
fn the_d422_example_reduces_to_its_published_figures() {
    let out = tmp();
    let o = reduce(
        Path::new("data/lab/envalysis_clayloam_d422.csv"),
        out.path(),
        &[],
    );
    assert_exit(&o, 0);
    let dir = out.path().join("envalysis_clayloam_d422_reduced");
    let rows = read_csv_records(&dir.join("percent_finer.csv"));
    assert_eq!(rows.len(), 7);
    // P = (R − 2) / 50 g × 100 (a = 1 at G = 2.65); L = 16.29 − 0.164 R cm.
    for (r, (reading, p)) in rows.iter().zip([(39.0, 74.0), (33.0, 62.0), (18.0, 32.0)]) {
        if num(r, "reading") == reading {
            assert!((num(r, "percent_finer") - p).abs() < 1e-9);
            let l = 0.1629 - 0.00164 * reading;
            assert!((num(r, "effective_depth_m") - l).abs() < 1e-12);
        }
    }
    assert_eq!(rows[0]["time_s"], "39.6");
    assert_eq!(rows[0]["effective_depth_m"], "0.09894");
    // 0.66 min at 23 °C: 50.91 µm (envalysis: 51.55 µm with its deeper L, see
    // tests/instruments/reduction.rs).
    assert!((num(&rows[0], "diameter_m") / 50.913e-6 - 1.0).abs() < 1e-4);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("ASTM D422, 152H, 7 readings"), "{stdout}");
    assert_readable_chart(
        &dir.join("percent_finer.svg"),
        "percent finer (ASTM D422, 152H)",
        &["particle diameter", "percent finer"],
    );
    let toml = std::fs::read_to_string(dir.join("reduce.toml")).unwrap();
    assert!(toml.contains("standard = \"d422\""), "{toml}");
}

/// docs/commands/reduce.md, D7928: soiltestr's protocol 8 (data/lab/README.md).
#[test]
fn the_d7928_example_reduces_to_the_hand_calculation() {
    let out = tmp();
    let o = reduce(
        Path::new("data/lab/soiltestr_protocol8_d7928.csv"),
        out.path(),
        &[],
    );
    assert_exit(&o, 0);
    let dir = out.path().join("soiltestr_protocol8_d7928_reduced");
    let rows = read_csv_records(&dir.join("percent_finer.csv"));
    assert_eq!(rows.len(), 2);
    // H = 8.6 + 0.18 (60 − (r + 1.0)) − 55/(2 × 26.1) cm; N = 0.6226 (2.7/1.7)(1000/48.797)
    // (r − 6.25) × 0.1.
    for (r, reading) in rows.iter().zip([13.0, 11.75]) {
        let h = 8.6 + 0.18 * (60.0 - (reading + 1.0)) - 55.0 / 52.2;
        assert!((num(r, "effective_depth_m") * 100.0 - h).abs() < 1e-9);
        let n = 1.65 / 2.65 * (2.7 / 1.7) * (1000.0 / 48.797) * (reading - 6.25) * 0.1;
        assert!((num(r, "percent_finer") - n).abs() < 1e-9);
        assert_eq!(r["net_reading"], format!("{}", reading - 6.25));
    }
    // 75 120 s, 21.5 °C: 1.494 µm (the sheet's 1.511 µm at its 0.36 cm deeper H).
    assert!((num(&rows[1], "diameter_m") / 1.4943e-6 - 1.0).abs() < 1e-3);
    assert_readable_chart(
        &dir.join("percent_finer.svg"),
        "percent finer (ASTM D7928, 152H)",
        &["particle diameter", "percent finer"],
    );
    let toml = std::fs::read_to_string(dir.join("reduce.toml")).unwrap();
    assert!(toml.contains("h_r1_cm = 20.3"), "{toml}");
    // The same file saved by a spreadsheet (byte-order mark, CRLF) reads the same.
    let text = std::fs::read_to_string("data/lab/soiltestr_protocol8_d7928.csv").unwrap();
    let bom = out.path().join("bom.csv");
    std::fs::write(&bom, format!("\u{feff}{}", text.replace('\n', "\r\n"))).unwrap();
    assert_exit(&reduce(&bom, out.path(), &[]), 0);
    assert_eq!(
        std::fs::read_to_string(out.path().join("bom_reduced/percent_finer.csv")).unwrap(),
        std::fs::read_to_string(dir.join("percent_finer.csv")).unwrap()
    );
    // A rerun replaces settle's folder; --standard overrides the file's (d422 refuses the
    // D7928 dimensions).
    assert_exit(
        &reduce(
            Path::new("data/lab/soiltestr_protocol8_d7928.csv"),
            out.path(),
            &[],
        ),
        0,
    );
    let o = reduce(
        Path::new("data/lab/soiltestr_protocol8_d7928.csv"),
        out.path(),
        &["--standard", "d422"],
    );
    assert_exit(&o, 2);
    assert!(String::from_utf8_lossy(&o.stderr).contains("used by d7928 only"));
}

const D422_HEAD: &str = "# standard = d422\n# hydrometer = 152H\n# dry_mass_g = 50\n\
# specific_gravity = 2.65\n# meniscus_correction = 1\n# blank_reading = 2\n";

/// Writes `text` as a readings file, reduces it with `args`, and checks: exit 2, one error line
/// naming the file and every part of `expect`, nothing written.
fn refused(text: &str, args: &[&str], expect: &[&str]) {
    let dir = tmp();
    let file = dir.path().join("readings.csv");
    std::fs::write(&file, text).unwrap();
    let out = dir.path().join("out");
    let o = reduce(&file, &out, args);
    assert_exit(&o, 2);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("readings.csv"), "{err}");
    for e in expect {
        assert!(err.contains(e), "`{e}` not in: {err}");
    }
    assert!(!out.exists() || tree(&out).is_empty(), "{:?}", tree(&out));
}

#[test]
fn bad_readings_are_refused_naming_row_and_column() {
    let table = |rows: &str| format!("{D422_HEAD}time_min,reading,temperature_c\n{rows}");
    // A reading above the 152H's scale.
    refused(
        &table("2,40,20\n5,61,20\n"),
        &[],
        &["row 2 (line 9), column 2 `reading`", "61", "-5 to 60 g/L"],
    );
    // Below it.
    refused(
        &table("2,-6,20\n"),
        &[],
        &["row 1", "column 2 `reading`", "-5 to 60"],
    );
    // Times not strictly increasing.
    refused(
        &table("2,40,20\n5,35,20\n5,33,20\n"),
        &[],
        &[
            "row 3 (line 10), column 1 `time_min`",
            "not after",
            "increase strictly",
        ],
    );
    // A temperature outside D422's Table 3 (16–30 °C).
    refused(
        &table("2,40,20\n5,35,15.5\n"),
        &[],
        &["row 2", "column 3 `temperature_c`", "16–30 °C for d422"],
    );
    // Not a number; a negative time; a missing field.
    refused(
        &table("2,forty,20\n"),
        &[],
        &["row 1", "column 2 `reading`", "not a number"],
    );
    refused(
        &table("-1,40,20\n"),
        &[],
        &["row 1", "column 1 `time_min`", "> 0"],
    );
    refused(
        &table("2,40\n"),
        &[],
        &["row 1 (line 8)", "2 fields, the header has 3"],
    );
    // The 151H's scale.
    let h151 = D422_HEAD
        .replace("152H", "151H")
        .replace("meniscus_correction = 1", "meniscus_correction = 0.001")
        .replace("blank_reading = 2", "blank_reading = 1.002");
    refused(
        &format!("{h151}time_min,reading,temperature_c\n2,1.045,20\n"),
        &[],
        &[
            "column 2 `reading`",
            "1.045",
            "0.995 to 1.038 specific gravity",
        ],
    );
    // A blank reading off the scale, in its column.
    refused(
        &format!(
            "{}time_min,reading,temperature_c,blank_reading\n2,40,20,70\n",
            D422_HEAD.replace("# blank_reading = 2\n", "")
        ),
        &[],
        &["column 4 `blank_reading`", "-5 to 60"],
    );
}

#[test]
fn bad_figures_and_columns_are_refused() {
    let rows = "time_min,reading,temperature_c\n2,40,20\n";
    // Missing figures.
    for key in ["dry_mass_g", "specific_gravity", "meniscus_correction"] {
        let text = D422_HEAD
            .lines()
            .filter(|l| !l.contains(key))
            .map(|l| format!("{l}\n"))
            .collect::<String>();
        refused(&format!("{text}{rows}"), &[], &[key, "missing"]);
    }
    refused(
        &format!("{}{rows}", D422_HEAD.replace("# blank_reading = 2\n", "")),
        &[],
        &["blank_reading", "missing"],
    );
    // A figure out of range; an unknown or duplicated key.
    refused(
        &format!(
            "{}{rows}",
            D422_HEAD.replace("dry_mass_g = 50", "dry_mass_g = 0")
        ),
        &[],
        &["dry_mass_g", "line 3", "0.001–10000 g"],
    );
    refused(
        &format!("{D422_HEAD}# dry_mass = 50\n{rows}"),
        &[],
        &["dry_mass", "unknown key"],
    );
    refused(
        &format!("{D422_HEAD}# dry_mass_g = 51\n{rows}"),
        &[],
        &["dry_mass_g", "given twice"],
    );
    // Missing, unknown or ambiguous columns.
    refused(
        &format!("{D422_HEAD}time_min,reading\n2,40\n"),
        &[],
        &["missing column `temperature_c`"],
    );
    refused(
        &format!("{D422_HEAD}time_min,reading,temperature_c,depth\n2,40,20,1\n"),
        &[],
        &["column 4", "unknown column `depth`"],
    );
    refused(
        &format!("{D422_HEAD}time_min,time_s,reading,temperature_c\n2,120,40,20\n"),
        &[],
        &["one time column"],
    );
    refused(D422_HEAD, &[], &["no header"]);
    refused(
        &format!("{D422_HEAD}{}", "time_min,reading,temperature_c\n"),
        &[],
        &["no readings"],
    );
    // Unknown standard or hydrometer, from the command line or the file.
    refused(
        &format!("{D422_HEAD}{rows}"),
        &["--standard", "d999"],
        &["--standard", "unknown standard `d999`", "d422, d7928"],
    );
    refused(
        &format!("{}{rows}", D422_HEAD.replace("152H", "150H")),
        &[],
        &["hydrometer", "line 2", "152H, 151H"],
    );
    // D7928 without the hydrometer's measured dimensions.
    refused(
        &format!("{D422_HEAD}{rows}"),
        &["--standard", "d7928"],
        &["h_r1_cm", "missing"],
    );
}

#[test]
fn a_folder_settle_did_not_create_is_not_replaced() {
    let dir = tmp();
    let out = dir.path().join("out");
    let mine = out.join("envalysis_clayloam_d422_reduced");
    std::fs::create_dir_all(&mine).unwrap();
    std::fs::write(mine.join("notes.txt"), "mine").unwrap();
    let o = reduce(Path::new("data/lab/envalysis_clayloam_d422.csv"), &out, &[]);
    assert_exit(&o, 2);
    assert!(String::from_utf8_lossy(&o.stderr).contains("not created by settle"));
    assert_eq!(tree(&out).len(), 2, "{:?}", tree(&out));
}

/// Human and file numbers: significant digits without `-0`, files without float noise.
#[test]
fn numbers_print_without_noise() {
    use settle::reduce::{clean, sig};
    assert_eq!(sig(0.66, 4), "0.6600");
    assert_eq!(sig(1252.0, 4), "1252");
    assert_eq!(sig(-1e-12, 3), "-0.00000000000100");
    assert_eq!(sig(-0.0004, 1), "-0.0004");
    assert_eq!(sig(-0.0, 3), "0");
    assert_eq!(clean(0.1629 - 0.00164 * 39.0), "0.09894");
    assert_eq!(clean(55e-6 * 1e6), "55");
    assert_eq!(clean(-0.0), "0");
}
