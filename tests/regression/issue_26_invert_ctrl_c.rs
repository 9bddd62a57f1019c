//! Issue 26 ("`settle invert` ignores Ctrl-C"): the first SIGINT was acknowledged and ignored;
//! the inversion either finished with exit 0 and wrote everything, or needed a second Ctrl-C
//! and lost everything. Now the Gauss–Newton iterations, the Monte Carlo repeats and the strict
//! bounds check for a stop: exit 130, "interrupted", nothing written.

use crate::common::{settle, signalled, tmp, HANG};
use std::time::Duration;

#[cfg(unix)]
#[test]
fn sigint_stops_a_long_inversion_and_writes_nothing() {
    let dir = tmp();
    let out = dir.path().join("out");
    // 10 million repeats of the band: hours of work (2000 take about 3 s).
    let mut cmd = settle();
    cmd.args([
        "invert",
        "data/invert/sample2_full/readings.csv",
        "--repeats",
        "10000000",
        "--out",
    ])
    .arg(&out);
    // Signalled once the inversion has used 1 s of CPU, however loaded the machine.
    let o = signalled(cmd, "INT", Duration::from_millis(1000), HANG);
    o.assert_stopped_within(Duration::from_secs(5), "SIGINT during an inversion");
    assert_eq!(o.code, Some(130), "stderr: {}", o.stderr);
    assert!(o.stderr.contains("interrupted"), "stderr: {}", o.stderr);
    let left: Vec<_> = std::fs::read_dir(&out)
        .map(|d| d.flatten().map(|e| e.file_name()).collect())
        .unwrap_or_default();
    assert!(left.is_empty(), "an interrupted inversion wrote {left:?}");
}
