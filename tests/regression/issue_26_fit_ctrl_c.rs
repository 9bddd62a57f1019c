//! Issue 26 (acceptance: "SIGINT … exits 130 within 1 s, nothing written; the same for `fit`"):
//! `settle fit` of a restitution drop ignored Ctrl-C until the current run ended: the drop's
//! step loop never looked for a stop, so a fit at a small dt ran on for minutes after the
//! signal (60 s without stopping in this test on the old code). Now the drop checks every 4096
//! steps and the fit exits 130 with nothing written.

use crate::common::{settle, signalled, tmp, HANG};

/// A calibration whose runs take minutes (restitution at dt = 1e-7 s, Nelder–Mead over two
/// keys) stops at Ctrl-C within the current run, exits 130 and writes no fit folder.
#[cfg(unix)]
#[test]
fn sigint_stops_a_long_fit_and_writes_nothing() {
    use std::time::Duration;
    let dir = tmp();
    let out = dir.path().join("out");
    let measured = dir.path().join("m.csv");
    std::fs::write(
        &measured,
        "file,column,row,value\nsummary.csv,rebound_height_m,0,0.05\n",
    )
    .unwrap();
    let mut cmd = settle();
    cmd.args(["fit", "scenarios/restitution_drop.toml"])
        .args(["--set", "time.dt_s=1e-7"])
        .args(["--fit", "contacts.restitution=0.5:0.8"])
        .args(["--fit", "contacts.restitution_exponent=0:0.2"])
        .arg("--measured")
        .arg(&measured)
        .arg("--out")
        .arg(&out);
    // Signalled once the fit has used 1 s of CPU, however loaded the machine.
    let o = signalled(cmd, "INT", Duration::from_millis(1000), HANG);
    o.assert_stopped_within(Duration::from_secs(5), "SIGINT during a fit");
    assert_eq!(o.code, Some(130), "stderr: {}", o.stderr);
    let left: Vec<_> = std::fs::read_dir(&out)
        .map(|d| d.flatten().map(|e| e.file_name()).collect())
        .unwrap_or_default();
    assert!(left.is_empty(), "an interrupted fit wrote {left:?}");
}
