//! Ctrl-C during a long run: the run stops at the end of the current step, writes what it has
//! with `status = "interrupted"` in run.toml, leaves no partial folder, and exits with 130.

use crate::common::{settle, tmp};
#[cfg(unix)]
use crate::common::{signalled, HANG};

#[cfg(unix)]
#[test]
fn sigint_stops_a_long_run_and_keeps_what_was_done() {
    use std::time::Duration;
    let dir = tmp();
    let mut cmd = settle();
    cmd.args([
        "run",
        "scenarios/sedimentation_sample5.toml",
        "--set",
        "sample.particles=200000",
        "--set",
        "sample.max_step_s=0.5",
        "--quiet",
        "--out",
    ])
    .arg(dir.path());
    // Signalled once the run has used 1.5 s of CPU (past its setup, into the steps), however
    // loaded the machine; it must then stop promptly (a step of 200 000 grains checks the
    // request every few thousand grains; 30 s leaves room for writing what was done).
    let o = signalled(cmd, "INT", Duration::from_millis(1500), HANG);
    o.assert_stopped_within(Duration::from_secs(30), "SIGINT during a long run");
    assert_eq!(o.code, Some(130), "{}", o.stderr);
    let run = std::fs::read_to_string(dir.path().join("sedimentation_sample5/run.toml")).unwrap();
    assert!(run.contains("status = \"interrupted\""), "{run}");
    assert!(dir
        .path()
        .join("sedimentation_sample5/profiles.csv")
        .exists());
    for e in std::fs::read_dir(dir.path()).unwrap() {
        let name = e.unwrap().file_name().to_string_lossy().to_string();
        assert!(!name.contains("partial"), "left a partial folder: {name}");
    }
}
