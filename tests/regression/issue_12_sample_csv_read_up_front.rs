//! Issue 12, "Bad input reaches the user by six paths": as found, a missing or bad `sample.csv`
//! of a sedimentation run (a file that does not exist, or `sample = 9`, a sample the file does
//! not hold) exited 1 at run time, after the earlier files of the same command had run and been
//! written. Every input file is now read while the scenarios are prepared: the command exits 2
//! with a message naming the scenario file and the key `sample.csv`, and nothing is written for
//! any file, not even the good one given first.

use std::path::{Path, PathBuf};
use std::process::Output;

/// The repository's sedimentation scenario of sample 1, with its `[sample]` lines `csv` and
/// `sample` replaced, written as `bad_sample.toml` into `dir`; small, so that a run that is not
/// refused ends quickly.
fn sedimentation_scenario(dir: &Path, csv: &str, sample: u32) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("scenarios/sedimentation_sample1.toml")).unwrap();
    let text: String = text
        .lines()
        .map(|l| {
            if l.starts_with("csv =") {
                format!("csv = {csv:?}")
            } else if l.starts_with("sample =") {
                format!("sample = {sample}")
            } else if l.starts_with("particles =") {
                "particles = 2000".to_string()
            } else if l.starts_with("end_s =") {
                "end_s = 1000.0".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    let path = dir.join("bad_sample.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// `settle run scenarios/stokes_single.toml BAD --out OUT -q`.
fn run(bad: &Path, out: &Path) -> Output {
    crate::common::settle()
        .args(["run", "scenarios/stokes_single.toml"])
        .arg(bad)
        .arg("--out")
        .arg(out)
        .arg("-q")
        .output()
        .unwrap()
}

fn assert_refused_up_front(o: &Output, bad: &Path, out: &Path, also: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(
        err.contains(&bad.display().to_string()),
        "names the scenario file: {err}"
    );
    assert!(err.contains("sample.csv"), "names the key: {err}");
    assert!(err.contains(also), "says `{also}`: {err}");
    assert!(
        !out.exists(),
        "nothing written, not even for the first, good file: {:?}",
        std::fs::read_dir(out).map(|d| d.flatten().map(|e| e.file_name()).collect::<Vec<_>>())
    );
}

#[test]
fn a_missing_sample_csv_exits_2_before_anything_runs() {
    let dir = tempfile::tempdir().unwrap();
    let bad = sedimentation_scenario(dir.path(), "no_such_samples.csv", 1);
    let out = dir.path().join("out");
    let o = run(&bad, &out);
    assert_refused_up_front(&o, &bad, &out, "no_such_samples.csv");
}

#[test]
fn a_sample_the_csv_does_not_hold_exits_2_before_anything_runs() {
    let dir = tempfile::tempdir().unwrap();
    let csv = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/sedimentation_samples.csv");
    let bad = sedimentation_scenario(dir.path(), csv.to_str().unwrap(), 9);
    let out = dir.path().join("out");
    let o = run(&bad, &out);
    assert_refused_up_front(&o, &bad, &out, "for sample 9");
}
