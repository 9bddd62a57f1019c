//! Issue 12, data loss and hangs, item 6 (interruption): a sedimentation run of millions of
//! grains did not honour Ctrl-C within 45 s. The interrupt was checked only between steps, and one
//! step of a many-grain cylinder (free update with Dallavalle drag, pair search, cluster solves)
//! takes minutes: with 1.5 million grains and SIGINT after 3 s, the old binary was still running
//! 12 minutes later. The run must now stop within about a second (the loops of the step check
//! the request every few thousand grains and inside each cluster solve), undo the unfinished
//! step and still write its resumable state.

use crate::common::{settle, tmp};
#[cfg(unix)]
use crate::common::{signalled, HANG};

#[cfg(unix)]
#[test]
fn sigint_stops_a_many_grain_cylinder_within_seconds() {
    use std::time::Duration;
    let dir = tmp();
    let mut cmd = settle();
    cmd.args([
        "run",
        "scenarios/sedimentation_sample1.toml",
        "--set",
        "sample.particles=1500000",
        "--force",
        "--quiet",
        "--out",
    ])
    .arg(dir.path());
    // Setup takes about a second of CPU; the first step then runs for tens of seconds: the
    // signal comes once the run has used 3 s of CPU, inside that step, however loaded the
    // machine. The aim is about a second to stop; with writing the ~70 MB resumable state, 5 s
    // (wall, or CPU on a loaded machine) leaves room for a busy two-core runner and still
    // catches the old binary, which ran on for minutes.
    let o = signalled(cmd, "INT", Duration::from_secs(3), HANG);
    o.assert_stopped_within(Duration::from_secs(5), "SIGINT in a 1.5e6-grain step");
    assert_eq!(o.code, Some(130), "stderr: {}", o.stderr);
    let run_toml =
        std::fs::read_to_string(dir.path().join("sedimentation_sample1/run.toml")).unwrap();
    assert!(run_toml.contains("status = \"interrupted\""), "{run_toml}");
    assert!(
        dir.path()
            .join("checkpoint/sedimentation_sample1.state.bin")
            .exists(),
        "no resumable state"
    );
}
