//! Issue 12, "Data loss and hangs" item 8 (the scenario part; the sweep flags `--tol` and
//! `--dt`/`--dt-range` are tested with the sweep). As found, `settle run` accepted silently, with
//! exit 0 and no warning:
//! - two spheres with one id (two `[[spheres]]` entries, or two rows of a spheres CSV);
//! - a 3 mm sphere in a 2 mm cylinder;
//! - a 10 km drop, which wrote `settling_distance_m = -9980` as a result (the ball was still in
//!   the air at `time.end_s`);
//! - a sphere CSV whose measured-velocity column is spelled like the TOML key
//!   (`v_measured_m_s`): the column was ignored, and so was any other unknown column.
//!
//! Now each is refused with exit 2 before anything is written, naming the file, the key or the
//! CSV row/column, and what is allowed; `v_measured_m_s` (and `id`) are read as the TOML keys,
//! the old column names still read. The bad files are in `tests/bad_scenarios/` (also cases of
//! `tests/scenario/bad_input.rs`).

use crate::common::{settle, tmp};
use std::path::{Path, PathBuf};

fn bad(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("bad_scenarios")
        .join(file)
}

/// `settle run FILE --out TMP` exits 2 with one line naming the file, `key` and `words`, and
/// writes nothing.
fn refused(file: &str, key: &str, words: &[&str]) {
    let tmp = tmp();
    let out = tmp.path().join("out");
    let o = settle()
        .arg("run")
        .arg(bad(file))
        .arg("--out")
        .arg(&out)
        .arg("-q")
        .current_dir(tmp.path())
        .output()
        .expect("run settle");
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{file}: exit code; stderr: {e}");
    assert_eq!(e.lines().count(), 1, "{file}: one line: {e}");
    assert!(e.contains(file), "{file}: names the file: {e}");
    assert!(
        e.contains(&format!("`{key}`")),
        "{file}: names `{key}`: {e}"
    );
    for w in words {
        assert!(e.contains(w), "{file}: `{w}` missing: {e}");
    }
    let written: Vec<_> = std::fs::read_dir(tmp.path())
        .expect("read temp dir")
        .map(|e| e.expect("entry").file_name())
        .filter(|n| n != "out")
        .collect();
    assert!(written.is_empty(), "{file}: wrote {written:?}");
    assert!(
        !out.exists() || std::fs::read_dir(&out).expect("out").next().is_none(),
        "{file}: wrote into --out"
    );
}

#[test]
fn duplicate_sphere_ids_are_refused() {
    refused(
        "duplicate_sphere_id.toml",
        "spheres[1].id",
        &["fedem-table1", "allowed one sphere per id"],
    );
    refused(
        "csv_duplicate_id.toml",
        "spheres_csv.path",
        &[
            "spheres_duplicate_id.csv",
            "line 4 (data row 2)",
            "allowed one row per id",
        ],
    );
}

#[test]
fn sphere_wider_than_its_cylinder_is_refused() {
    refused(
        "sphere_wider_than_cylinder.toml",
        "spheres[0].diameter_m",
        &[
            "0.003",
            "allowed 0 < diameter_m < container.diameter_m = 0.002 m",
        ],
    );
}

#[test]
fn drop_still_in_the_air_at_the_end_is_refused() {
    refused(
        "drop_10km.toml",
        "release.fall_heights_m[0]",
        &[
            "10000",
            "time.end_s = 2 s",
            "allowed 0 ≤ fall height < 19.62",
        ],
    );
}

#[test]
fn unknown_csv_column_is_refused_with_the_known_ones() {
    refused(
        "csv_unknown_column.toml",
        "spheres_csv.path",
        &[
            "column 5 `v_terminal_m_s` is unknown",
            "v_measured_m_s or v_terminal_measured_m_s",
        ],
    );
}

// The CSV columns named like the TOML keys: `scenario::tests::issue_12_csv_columns_named_like_keys`
// (a unit test).
