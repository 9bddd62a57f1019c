//! Reproducible runs (issue 13 item 5): `settle run OUT/NAME/run.toml` runs the same case again,
//! from any folder, giving every output file byte for byte; `run.toml` records the overrides as
//! given; a record's own overrides are not applied a second time, and new ones apply on top.

use crate::common::{assert_exit, settle, tmp, tree};
use std::path::{Path, PathBuf};

/// The repository root (the tests run there; a rerun below runs from elsewhere).
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs `settle run ARGS --quiet --out OUT` from folder `cwd`, expecting success.
fn run_in(cwd: &Path, args: &[&str], out: &Path) {
    let o = settle()
        .current_dir(cwd)
        .arg("run")
        .args(args)
        .arg("--quiet")
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    assert_exit(&o, 0);
}

/// Files that differ between a run and its rerun: `run.toml` (wall time), the folder marker,
/// and `report.html`, which shows run.toml's record.
const SKIPPED: &[&str] = &["run.toml", ".settle-run", "report.html"];

/// Asserts that folders `a` and `b` hold the same files with the same bytes, [`SKIPPED`]
/// aside; returns how many data files (CSV) were compared.
fn assert_same_outputs(a: &Path, b: &Path) -> usize {
    let files: Vec<PathBuf> = tree(a)
        .into_iter()
        .filter(|f| a.join(f).is_file())
        .filter(|f| !SKIPPED.iter().any(|s| f == Path::new(s)))
        .collect();
    let other: Vec<PathBuf> = tree(b)
        .into_iter()
        .filter(|f| b.join(f).is_file())
        .filter(|f| !SKIPPED.iter().any(|s| f == Path::new(s)))
        .collect();
    assert_eq!(files, other, "the two runs wrote different files");
    for f in &files {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(
            x == y,
            "{} differs between the run and its rerun",
            f.display()
        );
    }
    files
        .iter()
        .filter(|f| f.extension().is_some_and(|e| e == "csv"))
        .count()
}

fn run_toml(dir: &Path) -> toml::Table {
    std::fs::read_to_string(dir.join("run.toml"))
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn a_run_with_set_and_dt_reruns_from_its_record_with_identical_csvs() {
    let dir = tmp();
    let (first, second) = (dir.path().join("a"), dir.path().join("b"));
    run_in(
        &root(),
        &[
            "scenarios/stokes_single.toml",
            "--set",
            "fluid.viscosity_pa_s=0.002",
            "--set",
            "spheres[0].diameter_m=1.5e-4",
            "--dt",
            "2e-5",
        ],
        &first,
    );
    let rec = run_toml(&first.join("stokes_single"));
    let ov = rec["run"]["overrides"].as_table().expect("[run.overrides]");
    let set: Vec<&str> = ov["set"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(
        set,
        ["fluid.viscosity_pa_s=0.002", "spheres[0].diameter_m=1.5e-4"]
    );
    assert_eq!(ov["dt_s"].as_float(), Some(2e-5));
    assert_eq!(rec["scenario"]["time"]["dt_s"].as_float(), Some(2e-5));
    // Rerun from another folder, into another --out.
    let record = first.join("stokes_single/run.toml");
    run_in(dir.path(), &[record.to_str().unwrap()], &second);
    let n = assert_same_outputs(&first.join("stokes_single"), &second.join("stokes_single"));
    assert!(n >= 3, "{n} CSV files compared");
    let again = run_toml(&second.join("stokes_single"));
    assert_eq!(
        again["scenario"], rec["scenario"],
        "the same effective scenario"
    );
    assert_eq!(
        again["run"]["overrides"]["set"].as_array().map(Vec::len),
        Some(0),
        "the rerun itself had no --set"
    );
}

#[test]
fn a_spheres_csv_path_still_resolves_when_the_record_lives_elsewhere() {
    let dir = tmp();
    let first = dir.path().join("a");
    run_in(
        &root(),
        &["scenarios/valentik_susp1.toml", "--set", "time.end_s=3"],
        &first,
    );
    let rec = run_toml(&first.join("valentik_susp1"));
    let path = rec["scenario"]["spheres_csv"]["path"].as_str().unwrap();
    assert!(Path::new(path).is_absolute(), "{path}");
    assert!(Path::new(path).is_file(), "{path}");
    // The record copied to a folder of its own, run from a third folder.
    let copy = dir.path().join("elsewhere/deeper/case.toml");
    std::fs::create_dir_all(copy.parent().unwrap()).unwrap();
    std::fs::copy(first.join("valentik_susp1/run.toml"), &copy).unwrap();
    let second = dir.path().join("b");
    run_in(dir.path(), &[copy.to_str().unwrap()], &second);
    let n = assert_same_outputs(
        &first.join("valentik_susp1"),
        &second.join("valentik_susp1"),
    );
    assert!(n >= 3, "{n} CSV files compared");
    // A rerun into the run's own folder replaces it with the same outputs.
    let third = dir.path().join("c");
    run_in(
        &root(),
        &["scenarios/valentik_susp1.toml", "--set", "time.end_s=3"],
        &third,
    );
    let own = first.join("valentik_susp1/run.toml");
    run_in(dir.path(), &[own.to_str().unwrap()], &first);
    assert_same_outputs(&first.join("valentik_susp1"), &third.join("valentik_susp1"));
}

#[test]
fn a_sedimentation_run_reruns_from_its_record() {
    let dir = tmp();
    let (first, second) = (dir.path().join("a"), dir.path().join("b"));
    run_in(
        &root(),
        &[
            "scenarios/sedimentation_sample1.toml",
            "--set",
            "time.end_s=120",
            "--set",
            "sample.particles=1000",
        ],
        &first,
    );
    let out = first.join("sedimentation_sample1");
    let rec = run_toml(&out);
    let csv = rec["scenario"]["sample"]["csv"].as_str().unwrap();
    assert!(
        Path::new(csv).is_absolute() && Path::new(csv).is_file(),
        "{csv}"
    );
    // Only the tables of its kind are recorded (no [release], a table of free settling).
    assert!(rec["scenario"].get("release").is_none(), "{rec:?}");
    run_in(
        dir.path(),
        &[out.join("run.toml").to_str().unwrap()],
        &second,
    );
    let n = assert_same_outputs(&out, &second.join("sedimentation_sample1"));
    assert!(n >= 8, "{n} CSV files compared");
}

#[test]
fn a_record_takes_new_overrides_on_top_and_needs_its_scenario() {
    let dir = tmp();
    let first = dir.path().join("a");
    run_in(
        &root(),
        &["scenarios/stokes_single.toml", "--set", "time.end_s=0.02"],
        &first,
    );
    let record = first.join("stokes_single/run.toml");
    let s = settle::load(&record)
        .unwrap()
        .set("fluid.viscosity_pa_s", "0.003")
        .unwrap();
    let effective: toml::Table = s.to_toml().unwrap().parse().unwrap();
    assert_eq!(
        effective["time"]["end_s"].as_float(),
        Some(0.02),
        "the recorded override"
    );
    assert_eq!(
        effective["fluid"]["viscosity_pa_s"].as_float(),
        Some(0.003),
        "the new one"
    );
    // A [run] table without [scenario] is refused, naming the missing table.
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[run]\nstatus = \"complete\"\n").unwrap();
    let Err(settle::Error::BadInput(e)) = settle::load(&bad) else {
        panic!("{} accepted", bad.display());
    };
    assert_eq!(e.key.as_deref(), Some("scenario"), "{e}");
    assert!(e.message.contains("run record"), "{e}");
    let o = settle()
        .args(["run", bad.to_str().unwrap(), "--out"])
        .arg(dir.path().join("c"))
        .output()
        .unwrap();
    assert_exit(&o, 2);
    assert!(!dir.path().join("c").exists());
}
