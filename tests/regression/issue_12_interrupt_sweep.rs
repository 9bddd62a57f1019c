//! Issue 12, item 8 ("interruption honoured within about one second in every loop"), the sweep:
//! `settle sweep` ran its cases to the end whatever the signal, because each case was an
//! uninterruptible free-settling run (a fine dt of the 27 spheres of suspension 1 is minutes of
//! work). Now no case starts after SIGTERM, the running ones stop at their next interrupt check,
//! nothing is written for the unfinished sweep and the exit code is 130.

use crate::common::{settle, tmp};
use std::process::Stdio;
use std::time::{Duration, Instant};

#[cfg(unix)]
#[test]
fn sigterm_stops_a_long_sweep_and_writes_nothing() {
    let dir = tmp();
    let out = dir.path().join("out");
    // 27 spheres at dt = 1e-7 s over up to 120 s: far more than the test's patience.
    let mut child = settle()
        .args([
            "sweep",
            "scenarios/valentik_susp1.toml",
            "--dt",
            "1e-7,2e-7",
            "--integrator",
            "exponential",
            "--quiet",
            "--out",
        ])
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn settle");
    std::thread::sleep(Duration::from_millis(1500));
    assert!(
        child.try_wait().expect("wait").is_none(),
        "the sweep ended before the signal: make it longer"
    );
    let pid = child.id().to_string();
    let sent = std::process::Command::new("kill")
        .args(["-TERM", &pid])
        .status()
        .expect("kill");
    assert!(sent.success());
    let t0 = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().expect("wait") {
            break s;
        }
        if t0.elapsed() > Duration::from_secs(5) {
            let _ = child.kill();
            panic!("the sweep did not stop within 5 s of SIGTERM");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let o = child.wait_with_output().expect("output");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(status.code(), Some(130), "stderr: {err}");
    assert!(err.contains("interrupted"), "stderr: {err}");
    let left: Vec<_> = std::fs::read_dir(&out)
        .map(|d| d.flatten().map(|e| e.file_name()).collect())
        .unwrap_or_default();
    assert!(left.is_empty(), "an interrupted sweep wrote {left:?}");
}
