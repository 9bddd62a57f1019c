//! Regression test for issue 26, item 6: a run of a scenario named `X_sweep` into the folder of
//! the sweep of `X` deleted the sweep's `sweep.csv`, `recommended_dt.csv` and charts (exit 0):
//! both folders are `OUT/X_sweep/`, and a run replaced whatever settle had written there. Each
//! folder's marker now names the command and input that wrote it; another command's folder is
//! refused (exit 2, naming it) before anything runs, and a rerun of the same command still
//! replaces its own results.
//!
//! Set `SETTLE_BIN` to run this check against another binary (e.g. the one before the fix).

use crate::common::{assert_exit, settle, tmp};

const STOKES: &str = include_str!("../../scenarios/stokes_single.toml");

#[test]
fn a_run_never_replaces_the_folder_of_a_sweep() {
    let dir = tmp();
    let x = dir.path().join("x.toml");
    std::fs::write(
        &x,
        STOKES.replace("name = \"stokes_single\"", "name = \"x\""),
    )
    .unwrap();
    let x_sweep = dir.path().join("x_sweep.toml");
    std::fs::write(
        &x_sweep,
        STOKES.replace("name = \"stokes_single\"", "name = \"x_sweep\""),
    )
    .unwrap();
    let out = dir.path().join("out");
    let o = settle()
        .args(["sweep", "-q", "--dt", "1e-3,1e-4", "--out"])
        .arg(&out)
        .arg(&x)
        .output()
        .unwrap();
    assert_exit(&o, 0);
    let sweep_csv = out.join("x_sweep/sweep.csv");
    let before = std::fs::read(&sweep_csv).unwrap();
    let o = settle()
        .args(["run", "-q", "--out"])
        .arg(&out)
        .arg(&x_sweep)
        .output()
        .unwrap();
    assert_exit(&o, 2);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("x_sweep") && err.contains("settle sweep") && err.contains("--out"),
        "{err}"
    );
    assert_eq!(
        std::fs::read(&sweep_csv).unwrap(),
        before,
        "sweep.csv changed"
    );
    assert!(out.join("x_sweep/recommended_dt.csv").is_file());
    // The sweep itself may run again into its own folder.
    let o = settle()
        .args(["sweep", "-q", "--dt", "1e-3,1e-4", "--out"])
        .arg(&out)
        .arg(&x)
        .output()
        .unwrap();
    assert_exit(&o, 0);
    assert!(sweep_csv.is_file());
}
