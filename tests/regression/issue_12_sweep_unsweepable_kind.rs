//! Issue 12, "Sweeps in one module" (item 5 of "What to build"): as found, `settle sweep` of a
//! sedimentation scenario (or a tilt-friction one) printed "0 cases", wrote empty charts and a
//! `recommended_dt.csv` without rows into `OUT/<name>_sweep/`, and exited 0; a restitution drop
//! was swept as if its ball settled in a fluid. A kind the sweep cannot run must be refused with
//! exit 2, a message naming the file, its kind and the kinds that can be swept, and nothing
//! written, not even for the other files of the same command.

use crate::common::{settle, tmp};
use std::path::Path;
use std::process::Output;

fn sweep(args: &[&str], out: &Path) -> Output {
    settle()
        .arg("sweep")
        .args(args)
        .arg("--out")
        .arg(out)
        .arg("-q")
        .output()
        .unwrap()
}

fn assert_refused(o: &Output, file: &str, kind: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(err.contains(file), "names the file: {err}");
    assert!(err.contains(&format!("`{kind}`")), "names the kind: {err}");
    assert!(
        err.contains("free_settling, drop, funnel_pour"),
        "names the kinds that can be swept: {err}"
    );
}

#[test]
fn a_sedimentation_sweep_is_refused_and_writes_nothing() {
    let dir = tmp();
    let out = dir.path().join("out");
    let file = "scenarios/sedimentation_sample1.toml";
    let o = sweep(&[file, "--dt", "1e-3"], &out);
    assert_refused(&o, file, "sedimentation");
    assert!(!out.exists(), "nothing written");
}

#[test]
fn one_unsweepable_file_stops_the_whole_command_before_anything_runs() {
    let dir = tmp();
    let out = dir.path().join("out");
    for (file, kind) in [
        ("scenarios/tilt_friction.toml", "tilt_friction"),
        ("scenarios/restitution_drop.toml", "restitution_drop"),
    ] {
        let o = sweep(
            &["scenarios/stokes_single.toml", file, "--dt", "1e-3"],
            &out,
        );
        assert_refused(&o, file, kind);
        assert!(
            !out.exists(),
            "the first, sweepable file was not swept either"
        );
    }
}
