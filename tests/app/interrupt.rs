//! Ctrl-C during a long run: the run stops at the end of the current step, writes what it has
//! with `status = "interrupted"` in run.toml, leaves no partial folder, and exits with 130.

use crate::common::{settle, tmp};

#[cfg(unix)]
#[test]
fn sigint_stops_a_long_run_and_keeps_what_was_done() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let dir = tmp();
    let child = settle()
        .args([
            "run",
            "scenarios/sedimentation_sample5.toml",
            "--set",
            "sample.particles=200000",
            "--set",
            "sample.max_step_s=0.5",
            "--quiet",
            "--out",
        ])
        .arg(dir.path())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let pid = child.id().to_string();
    assert!(Command::new("kill")
        .args(["-INT", &pid])
        .status()
        .unwrap()
        .success());
    let t0 = Instant::now();
    let out = child.wait_with_output().unwrap();
    assert!(
        t0.elapsed() < Duration::from_secs(30),
        "did not stop promptly"
    );
    assert_eq!(
        out.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
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
