//! Issue 26 ("interruption within about a second in every command and every loop"): a tilt
//! friction run (and so `settle fit` of one) ignored Ctrl-C until every angle had run: the tilt's
//! step loop never looked for a stop, the same fault as the restitution drop's
//! (`issue_26_fit_ctrl_c`). At dt = 1e-7 s each angle is 1e7 Rapier steps, so the old binary ran
//! on for minutes after the signal. Now the loop checks every 4096 steps; exit 130, nothing
//! written.

use crate::common::{settle, signalled, tmp, HANG};

/// A tilt run whose angles take minutes stops at Ctrl-C within the current angle, exits 130
/// and leaves no results folder.
#[cfg(unix)]
#[test]
fn sigint_stops_a_long_tilt_run_and_writes_nothing() {
    use std::time::Duration;
    let dir = tmp();
    let out = dir.path().join("out");
    let mut cmd = settle();
    cmd.args(["run", "scenarios/tilt_friction.toml", "--force"])
        .args(["--set", "time.dt_s=1e-7"])
        .arg("--out")
        .arg(&out);
    // Signalled once the run has used 1 s of CPU, however loaded the machine.
    let o = signalled(cmd, "INT", Duration::from_millis(1000), HANG);
    o.assert_stopped_within(Duration::from_secs(5), "SIGINT during a tilt run");
    assert_eq!(o.code, Some(130), "stderr: {}", o.stderr);
    let left: Vec<_> = std::fs::read_dir(&out)
        .map(|d| d.flatten().map(|e| e.file_name()).collect())
        .unwrap_or_default();
    assert!(left.is_empty(), "an interrupted tilt run wrote {left:?}");
}
