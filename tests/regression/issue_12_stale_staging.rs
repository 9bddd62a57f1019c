//! Regression test for issue 12, "Data loss and hangs" item 6 (staging part): the hidden
//! `.NAME.partial-PID/` folders of killed runs stayed in `OUT` until a scenario of the same name
//! ran there again. Any run into `OUT` now removes the staging folders of dead processes,
//! whatever their name, and leaves those of running processes.
//!
//! Set `SETTLE_BIN` to run these checks against another binary (e.g. the one before the fix).

use crate::common::{assert_exit, settle, tmp};
use std::path::Path;

/// A process id that no process has (above any pid handed out so far on this machine).
fn dead_pid() -> u32 {
    (4_000_000..u32::MAX)
        .find(|p| !Path::new("/proc").join(p.to_string()).exists())
        .unwrap()
}

#[test]
#[cfg(target_os = "linux")]
fn staging_folders_of_dead_processes_are_removed_whatever_their_name() {
    let dir = tmp();
    let out = dir.path().join("out");
    let dead = out.join(format!(".some.other.run.partial-{}", dead_pid()));
    std::fs::create_dir_all(dead.join("snapshots")).unwrap();
    std::fs::write(dead.join("timeseries.csv"), "huge").unwrap();
    // Our own process runs: its (pretend) staging folder must stay.
    let alive = out.join(format!(".mine.partial-{}", std::process::id()));
    std::fs::create_dir_all(&alive).unwrap();
    let o = settle()
        .args(["run", "-q", "--out"])
        .arg(&out)
        .arg(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/scenarios/stokes_single.toml"
        ))
        .output()
        .unwrap();
    assert_exit(&o, 0);
    assert!(!dead.exists(), "the dead process's staging folder stayed");
    assert!(
        alive.exists(),
        "a running process's staging folder was removed"
    );
}
