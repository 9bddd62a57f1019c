//! Issue 12, "Data loss and hangs" item 8, the sweep's part: as found, `settle sweep --tol 5`
//! ran and recommended a dt for a 500 % error, `--tol=-1` ran and recommended none (`--tol -1`
//! failed only as an "unexpected argument"), and `--dt` together with `--dt-range` silently ran
//! the union of both. Command-line errors posed as a scenario error of a file named
//! `<command line>`, and a missing `--merge` folder exited 1. Each must exit 2 with a message
//! naming the option (and for `--tol` the allowed range 0 < TOL ≤ 1: a relative error against
//! the finest stable dt), writing nothing.

use crate::common::{assert_exit, settle, tmp};
use std::path::Path;
use std::process::Output;

fn sweep(args: &[&str], out: &Path) -> Output {
    settle()
        .args(["sweep", "scenarios/stokes_single.toml"])
        .args(args)
        .arg("--out")
        .arg(out)
        .arg("-q")
        .output()
        .unwrap()
}

fn assert_refused(args: &[&str], option: &str, also: &str) {
    let dir = tmp();
    let out = dir.path().join("out");
    let o = sweep(args, &out);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains(option), "{args:?} names {option}: {err}");
    assert!(err.contains(also), "{args:?} says `{also}`: {err}");
    assert!(!err.contains("<command line>"), "{args:?}: {err}");
    assert!(!out.exists(), "{args:?}: nothing written");
}

#[test]
fn tolerances_outside_zero_to_one_are_refused_naming_the_range() {
    for tol in [
        ["--tol", "-1"],
        ["--tol", "5"],
        ["--tol", "0"],
        ["--tol", "-1e-3"],
    ] {
        let args = [tol[0], tol[1], "--dt", "1e-3"];
        assert_refused(&args, "--tol", "0 < TOL ≤ 1");
    }
    assert_refused(&["--tol=-1", "--dt", "1e-3"], "--tol", "0 < TOL ≤ 1");
}

#[test]
fn a_tolerance_of_one_is_accepted() {
    let dir = tmp();
    let out = dir.path().join("out");
    let o = sweep(
        &["--tol", "1", "--dt", "1e-3", "--integrator", "exponential"],
        &out,
    );
    assert_exit(&o, 0);
    let rec = std::fs::read_to_string(out.join("stokes_single_sweep/recommended_dt.csv")).unwrap();
    assert!(rec.contains("exponential,0.001,1,"), "{rec}");
}

#[test]
fn dt_and_dt_range_together_are_refused() {
    assert_refused(
        &["--dt", "1e-3", "--dt-range", "1e-4:1e-2"],
        "--dt",
        "--dt-range",
    );
}

#[test]
fn command_line_errors_name_the_option_not_a_file() {
    assert_refused(&["--shard", "3/2", "--dt", "1e-3"], "--shard", "1 ≤ I ≤ N");
    assert_refused(&["--dt-range", "1e-2:1e-4"], "--dt-range", "0 < LO < HI");
    assert_refused(&["--dt", "-1e-3"], "--dt", "dt > 0");
    assert_refused(
        &["--integrator", "rk4", "--dt", "1e-3"],
        "--integrator",
        "exponential",
    );
}

#[test]
fn a_missing_merge_folder_is_bad_input() {
    let dir = tmp();
    let missing = dir.path().join("no_such_folder");
    let o = settle()
        .args(["sweep", "--merge"])
        .arg(&missing)
        .arg("-q")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--merge") && err.contains("no_such_folder"),
        "{err}"
    );
    assert!(!missing.exists());
}
