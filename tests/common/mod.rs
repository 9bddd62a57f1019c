//! Helpers shared by the tests: one way to spawn the `settle` binary, temporary output folders,
//! the files a run left, the CSV files it wrote and the figures it printed.

pub mod chart;
pub mod child;

pub use child::{
    cpu_time, has_checkpoint, random_between, run_measured, test_seed, wait_for, HANG,
};
#[cfg(unix)]
pub use child::{signal_when, signalled, try_signal_when, Signalled};

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A command running the `settle` binary of this build, or the one named by the environment
/// variable `SETTLE_BIN` (e.g. the binary before a fix, to see a regression test fail on it).
pub fn settle() -> Command {
    Command::new(
        std::env::var_os("SETTLE_BIN")
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_settle"))),
    )
}

/// A fresh temporary folder, removed when dropped.
pub fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("temp dir")
}

/// Every file and folder under `dir`, relative to it, sorted; empty when nothing was written.
pub fn tree(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("read_dir") {
            let p = e.expect("dir entry").path();
            out.push(p.strip_prefix(dir).expect("prefix").to_path_buf());
            if p.is_dir() {
                stack.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The number printed right after `key` in `text` (up to the next space), e.g. the `2.5e-5` of
/// `… use dt < 2.5e-5 s …` for the key `"use dt < "`. Panics naming the key if it is absent.
pub fn number_after(text: &str, key: &str) -> f64 {
    let tail = text
        .split(key)
        .nth(1)
        .unwrap_or_else(|| panic!("no `{key}` in {text}"));
    tail.split(' ').next().unwrap().parse().unwrap()
}

/// Reads a CSV written by a run into (header, rows): the one CSV reader of the tests (the csv
/// crate, so that a quoted field with a comma is one field); rows may be shorter or longer
/// than the header.
pub fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_path(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut records = r.records().map(|x| {
        x.unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            .iter()
            .map(str::to_string)
            .collect::<Vec<String>>()
    });
    let header = records.next().unwrap_or_default();
    (header, records.collect())
}

/// The number in column `name` of `row` (a row of [`read_csv`] with its `header`).
pub fn col(header: &[String], row: &[String], name: &str) -> f64 {
    let i = header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    row[i]
        .parse()
        .unwrap_or_else(|e| panic!("{name} = `{}`: {e}", row[i]))
}

/// [`read_csv`] as rows of named fields (header → value).
pub fn read_csv_records(path: &Path) -> Vec<HashMap<String, String>> {
    let (header, rows) = read_csv(path);
    rows.into_iter()
        .map(|r| header.iter().cloned().zip(r).collect())
        .collect()
}

/// The number in field `k` of a CSV record (panics naming the field if it is not one).
pub fn num(r: &HashMap<String, String>, k: &str) -> f64 {
    r[k].parse()
        .unwrap_or_else(|e| panic!("{k} = `{}`: {e}", r[k]))
}

/// Runs `settle SUB INPUTS... --out OUT ARGS...` and returns its output.
pub fn settle_command(
    sub: &str,
    inputs: &[&str],
    out: &Path,
    args: &[&str],
) -> std::process::Output {
    settle()
        .arg(sub)
        .args(inputs)
        .arg("--out")
        .arg(out)
        .args(args)
        .output()
        .expect("spawn settle")
}

/// Runs the calling test's body in a child process of its own, for a test that changes
/// process-wide state (such as requesting an interrupt): all tests share one process.
///
/// `test` is the test's full path (`regression::…::name`). In the parent, spawns this test
/// binary on that one test with `SETTLE_TEST_ISOLATED=test`, asserts that it ran and passed,
/// and returns false; in that child, returns true: run the body then.
pub fn isolated(test: &str) -> bool {
    const VAR: &str = "SETTLE_TEST_ISOLATED";
    if std::env::var_os(VAR).is_some_and(|v| v == test) {
        return true;
    }
    let o = Command::new(std::env::current_exe().expect("test binary"))
        .args([test, "--exact", "--test-threads=1", "--nocapture"])
        .env(VAR, test)
        .output()
        .expect("spawn the test binary");
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{test} failed in its own process:\n{out}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        out.contains("1 passed"),
        "{test} did not run in its own process (wrong path?):\n{out}"
    );
    false
}

/// Asserts that a finished run exited with `code`, showing its stderr otherwise.
pub fn assert_exit(o: &std::process::Output, code: i32) {
    assert_eq!(
        o.status.code(),
        Some(code),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}
