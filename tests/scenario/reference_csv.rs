//! The measured curves of `[reference]` (`src/scenario/inputs.rs`, `read_reference`): every bad
//! file refused before anything runs (exit 2, nothing written), naming the scenario, the key,
//! the CSV and the line, data row and column (1-based) with what is allowed.

use crate::common::{assert_exit, settle, tmp};
use std::path::Path;

const SCENARIO: &str = r#"
name = "reference"
kind = "free_settling"
[fluid]
density_kg_m3 = 970.0
rheology = "newtonian"
viscosity_pa_s = 0.373
[drag]
law = "schiller-naumann"
[time]
dt_s = 1e-3
end_s = 0.1
[container]
height_m = 0.16
[[spheres]]
diameter_m = 0.015
density_kg_m3 = 1120.0
[reference]
source = "a test"
velocity_csv = "data/v.csv"
gap_csv = "data/gap.csv"
"#;

/// Writes the scenario (with `replace` applied to its text) and the two CSVs into `dir`.
fn write(dir: &Path, v: &str, gap: &str, replace: (&str, &str)) -> std::path::PathBuf {
    std::fs::create_dir_all(dir.join("data")).unwrap();
    std::fs::write(dir.join("data/v.csv"), v).unwrap();
    std::fs::write(dir.join("data/gap.csv"), gap).unwrap();
    let toml = dir.join("s.toml");
    std::fs::write(&toml, SCENARIO.replace(replace.0, replace.1)).unwrap();
    toml
}

/// A bad case: the velocity CSV, the gap CSV, a (from, to) replacement in the scenario text, and
/// the words the error must hold.
type Case<'a> = (&'a str, &'a str, (&'a str, &'a str), &'a [&'a str]);

const GOOD_V: &str = "time_s,velocity_m_s\n0.1,0.01\n0.2,0.02\n";
const GOOD_GAP: &str = "time_s,gap_over_diameter,gap_m\n-0.01,8.1,0.1215\n0.5,7,0.105\n";

// The curves read relative to the scenario, extra columns ignored:
// `scenario::tests::reference_csv` (a unit test).

/// Each bad input: `settle run` exits 2 before anything runs, nothing written, the message
/// naming the key, the file and where in it.
#[test]
fn a_bad_reference_file_is_refused_naming_file_row_and_column() {
    let cases: [Case; 6] = [
        (
            "time_s,speed\n0.1,0.01\n",
            GOOD_GAP,
            ("", ""),
            &[
                "reference.velocity_csv",
                "v.csv",
                "missing column `velocity_m_s`",
            ],
        ),
        (
            "time_s,velocity_m_s\n0.1,0.01\n0.2,fast\n",
            GOOD_GAP,
            ("", ""),
            &[
                "reference.velocity_csv",
                "line 3 (data row 2), column 2 (`velocity_m_s`)",
                "`fast` is not a number",
            ],
        ),
        (
            GOOD_V,
            "time_s,gap_m\n0.1,inf\n",
            ("", ""),
            &[
                "reference.gap_csv",
                "gap.csv",
                "line 2 (data row 1), column 2",
                "finite",
            ],
        ),
        (
            GOOD_V,
            "time_s,gap_m\n",
            ("", ""),
            &["reference.gap_csv", "no data row"],
        ),
        (
            GOOD_V,
            GOOD_GAP,
            ("data/v.csv", "data/none.csv"),
            &[
                "reference.velocity_csv",
                "none.csv",
                "relative to the scenario file",
            ],
        ),
        (
            GOOD_V,
            GOOD_GAP,
            ("source = \"a test\"", "source = \" \""),
            &["reference.source", "empty"],
        ),
    ];
    for (v, gap, replace, words) in cases {
        let d = tmp();
        let toml = write(d.path(), v, gap, replace);
        let out = d.path().join("out");
        let o = settle()
            .args(["run", "-q", "--out"])
            .arg(&out)
            .arg(&toml)
            .output()
            .unwrap();
        assert_exit(&o, 2);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("s.toml"), "{err}");
        for w in words {
            assert!(err.contains(w), "`{w}` not in {err}");
        }
        assert!(!out.exists(), "{words:?}: something was written");
    }
}
