//! Symptom (CI, after issue 12): `settle run pour.toml --set repeats.count=2 --checkpoint-every
//! 0.2` failed 5 times out of 6 with `error: pour.toml: No such file or directory (os error 2)`,
//! exit 4, and left no checkpoint to resume. The two repeats run in parallel and saved their first
//! checkpoint at the same moment; both wrote `checkpoint/request.toml.tmp`, the first rename took
//! it and the second found nothing.

use crate::common::{settle, tmp};

// Many threads writing the same file atomically at once: `io::tests::issue_8_concurrent_atomic_writes`
// (a unit test).

/// A two-repeat pour with frequent checkpoints finishes and removes its checkpoint folder.
#[test]
fn parallel_repeats_with_checkpoints_finish() {
    let dir = tmp();
    let out = dir.path().join("out");
    for _ in 0..3 {
        let o = settle()
            .args([
                "run",
                "scenarios/paste_68_balls.toml",
                "--set",
                "repeats.count=2",
                "--set",
                "time.end_s=0.05",
                "--set",
                "funnel.count_time_s=0.04",
                "--dt",
                "1e-4",
                "--checkpoint-every",
                "0.01",
                "--quiet",
                "--out",
            ])
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(!out.join("checkpoint").exists());
    }
}
