//! Issue 13, "Reproducible runs" (item 5 of "What to build"): as found, the `run.toml` a run
//! wrote could not be run again (`settle run OUT/NAME/run.toml` → `unknown field run`, exit 2),
//! and the `--set` list was not recorded, only its effect. Now the record runs the same case
//! (its `[scenario]`, overrides already applied) and lists the overrides as given.

use crate::common::{assert_exit, read_csv, settle, tmp};

#[test]
fn run_toml_runs_again_and_records_the_set_list() {
    let dir = tmp();
    let first = dir.path().join("first");
    let o = settle()
        .args([
            "run",
            "scenarios/stokes_single.toml",
            "--set",
            "fluid.viscosity_pa_s=0.002",
            "-q",
            "--out",
        ])
        .arg(&first)
        .output()
        .unwrap();
    assert_exit(&o, 0);
    let record = first.join("stokes_single/run.toml");
    let text = std::fs::read_to_string(&record).unwrap();
    assert!(
        text.contains("set = [\"fluid.viscosity_pa_s=0.002\"]"),
        "the --set list is recorded: {text}"
    );
    let second = dir.path().join("second");
    let o = settle()
        .arg("run")
        .arg(&record)
        .args(["-q", "--out"])
        .arg(&second)
        .output()
        .unwrap();
    assert_exit(&o, 0);
    let a = read_csv(&first.join("stokes_single/summary.csv"));
    let b = read_csv(&second.join("stokes_single/summary.csv"));
    assert_eq!(a, b, "the rerun gives the same summary");
}
