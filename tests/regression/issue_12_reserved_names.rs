//! Regression test for issue 12, "Data loss and hangs" items 3 and 4: `name = "checkpoint"`
//! printed a destination and left an empty folder (the checkpoint folder's cleanup removed its
//! outputs); `name = "combined"` in a two-file run had its outputs replaced by the joint summary.
//! Both exited 0. Names the output layout uses are refused (exit 2) before anything runs, naming
//! the file and the key `name`.
//!
//! Set `SETTLE_BIN` to run these checks against another binary (e.g. the one before the fix).

use crate::common::{settle, tmp};
use std::path::{Path, PathBuf};
use std::process::Output;

fn write_scenario(dir: &Path, file: &str, name: &str) -> PathBuf {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenarios/stokes_single.toml"
    ))
    .unwrap()
    .replace("name = \"stokes_single\"", &format!("name = \"{name}\""));
    let path = dir.join(file);
    std::fs::write(&path, text).unwrap();
    path
}

fn run(files: &[PathBuf], out: &Path) -> Output {
    settle()
        .args(["run", "-q", "--out"])
        .arg(out)
        .args(files)
        .output()
        .unwrap()
}

#[test]
fn checkpoint_is_refused_as_a_name() {
    let dir = tmp();
    let f = write_scenario(dir.path(), "a.toml", "checkpoint");
    let out = dir.path().join("out");
    let o = run(&[f], &out);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("a.toml") && err.contains("`name`"), "{err}");
    assert!(!out.exists(), "something was written");
}

#[test]
fn combined_is_refused_as_a_name() {
    let dir = tmp();
    let a = write_scenario(dir.path(), "a.toml", "combined");
    let b = write_scenario(dir.path(), "b.toml", "other");
    let out = dir.path().join("out");
    let o = run(&[a, b], &out);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("a.toml") && err.contains("`name`"), "{err}");
    assert!(!out.exists(), "something was written");
}
