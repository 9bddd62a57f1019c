//! Regression test for issue 26, item 6: every run's readings file is called `readings.csv`, so
//! `settle reduce a/readings.csv` then `settle reduce b/readings.csv` replaced the first result
//! with the second (both `OUT/readings_reduced/`, exit 0); the same for `invert`, and `laws`
//! on other files replaced `OUT/laws/`. The folder's marker now names its input: the second is
//! refused (exit 2) naming the first and the fix, the first result untouched; the same input
//! again still replaces its own results.
//!
//! Set `SETTLE_BIN` to run these checks against another binary (e.g. the one before the fix).

use crate::common::{assert_exit, settle, tmp};
use std::path::Path;

const READINGS: &str = include_str!("../data/lab/utf8/soil_b3.csv");

fn two_readings(dir: &Path) -> (std::path::PathBuf, std::path::PathBuf) {
    let (a, b) = (dir.join("a/readings.csv"), dir.join("b/readings.csv"));
    for p in [&a, &b] {
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
    }
    std::fs::write(&a, READINGS).unwrap();
    // b: another test, its dry mass 10 % higher.
    std::fs::write(
        &b,
        READINGS.replace("dry_mass_g = 48.797", "dry_mass_g = 53.68"),
    )
    .unwrap();
    (a, b)
}

fn second_refused(command: &str, folder: &str) {
    let dir = tmp();
    let (a, b) = two_readings(dir.path());
    let out = dir.path().join("out");
    let run = |f: &Path| {
        settle()
            .args([command, "--out"])
            .arg(&out)
            .arg(f)
            .output()
            .unwrap()
    };
    assert_exit(&run(&a), 0);
    let snapshot = |p: &Path| -> Vec<(String, Vec<u8>)> {
        let mut v: Vec<_> = std::fs::read_dir(p)
            .unwrap()
            .map(|e| {
                let e = e.unwrap();
                (
                    e.file_name().to_string_lossy().into_owned(),
                    std::fs::read(e.path()).unwrap(),
                )
            })
            .collect();
        v.sort();
        v
    };
    let first = snapshot(&out.join(folder));
    let o = run(&b);
    assert_exit(&o, 2);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains(folder) && err.contains("a/readings.csv") && err.contains("another --out"),
        "{err}"
    );
    assert_eq!(
        snapshot(&out.join(folder)),
        first,
        "{command}: the first result changed"
    );
    assert_exit(&run(&a), 0);
}

#[test]
fn a_second_reduction_of_another_readings_csv_is_refused() {
    second_refused("reduce", "readings_reduced");
}

#[test]
fn a_second_inversion_of_another_readings_csv_is_refused() {
    second_refused("invert", "readings_inverted");
}

#[test]
fn laws_on_other_files_never_replace_out_laws() {
    let dir = tmp();
    let out = dir.path().join("out");
    let o = settle().args(["laws", "--out"]).arg(&out).output().unwrap();
    assert_exit(&o, 0);
    let before = std::fs::read(out.join("laws/laws.csv")).unwrap();
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let o = settle()
        .arg("laws")
        .arg(data.join("valentik_whitmore_1965_spheres.csv"))
        .arg("--fluids")
        .arg(data.join("valentik_whitmore_1965_suspensions.csv"))
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert_exit(&o, 2);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("built-in data") && err.contains("another --out"),
        "{err}"
    );
    assert_eq!(std::fs::read(out.join("laws/laws.csv")).unwrap(), before);
}
