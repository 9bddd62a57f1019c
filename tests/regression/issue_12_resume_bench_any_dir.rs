//! Regression test for issue 12, "Data loss and hangs" item 9: `--resume DIR` and `bench` worked
//! only from the directory the run started in: the checkpoint stored the scenario files as given
//! (relative), and `bench` read `scenarios/` relative to the current directory (exit 1
//! elsewhere). The checkpoint now stores absolute paths and `bench` finds its scenarios from
//! anywhere.
//!
//! Set `SETTLE_BIN` to run these checks against another binary (e.g. the one before the fix).

use crate::common::{assert_exit, has_checkpoint, settle, signal_when, tmp, HANG};
use std::path::Path;

const REPO: &str = env!("CARGO_MANIFEST_DIR");

#[cfg(unix)]
#[test]
fn resume_works_from_another_directory() {
    let dir = tmp();
    let out = dir.path().join("out");
    // Started from the repository with a relative scenario path, stopped by SIGINT.
    let mut cmd = settle();
    cmd.current_dir(REPO)
        .args(["run", "scenarios/sedimentation_sample2.toml"])
        .args(["--set", "sample.particles=20000", "--quiet"])
        .args(["--checkpoint-every", "0.2", "--out"])
        .arg(&out);
    // Signalled once a first state is checkpointed (however long that takes on a loaded
    // machine); the run (minutes of CPU) is then far from its end.
    let o = signal_when(cmd, "INT", |_, _| has_checkpoint(&out), HANG, "resume");
    assert_eq!(o.code, Some(130), "{}", o.stderr);
    // Resumed from the temporary folder, with a relative DIR.
    let o = settle()
        .current_dir(dir.path())
        .args(["run", "--resume", "out", "--quiet"])
        .output()
        .unwrap();
    assert_exit(&o, 0);
    assert!(out.join("sedimentation_sample2/summary.csv").exists());
    assert!(!out.join("checkpoint").exists());
}

#[test]
fn bench_works_from_another_directory() {
    let dir = tmp();
    let o = settle()
        .current_dir(dir.path())
        .args(["bench", "--quick", "--out", "b"])
        .output()
        .unwrap();
    assert_exit(&o, 0);
    let csv = std::fs::read_to_string(Path::new(dir.path()).join("b/bench/bench.csv")).unwrap();
    assert!(csv.contains("valentik_121"), "{csv}");
}
