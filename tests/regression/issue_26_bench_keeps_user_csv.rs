//! Regression test for issue 26, item 6: `settle bench --out o` replaced a user's own
//! `o/bench.csv` (exit 0), and with `--out` naming a file it failed only after running every
//! benchmark (exit 4). `bench` now writes `OUT/bench/bench.csv`, a folder of its own marked as
//! settle's; a folder `OUT/bench/` settle did not create is refused before any benchmark runs
//! (exit 2), as is an `--out` that is a file.
//!
//! Set `SETTLE_BIN` to run this check against another binary (e.g. the one before the fix).

use crate::common::{assert_exit, settle, tmp};

/// The quickest bench there is (a second or two).
const QUICK: [&str; 5] = [
    "bench",
    "--quick",
    "--sedimentation-only",
    "--grains",
    "200",
];

#[test]
fn bench_never_replaces_a_users_bench_csv() {
    let dir = tmp();
    let out = dir.path().join("o");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("bench.csv"), "my own figures\n").unwrap();
    let o = settle()
        .args(QUICK)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert_exit(&o, 0);
    assert_eq!(
        std::fs::read_to_string(out.join("bench.csv")).unwrap(),
        "my own figures\n"
    );
    assert!(out.join("bench/bench.csv").is_file());
    // A rerun replaces its own results.
    let o = settle()
        .args(QUICK)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert_exit(&o, 0);
    // A user's folder `bench/` is refused before any benchmark runs.
    let mine = dir.path().join("p");
    std::fs::create_dir_all(mine.join("bench")).unwrap();
    std::fs::write(mine.join("bench/bench.csv"), "mine\n").unwrap();
    let o = settle()
        .args(QUICK)
        .arg("--out")
        .arg(&mine)
        .output()
        .unwrap();
    assert_exit(&o, 2);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("not created by settle") && err.contains("--out"),
        "{err}"
    );
    assert!(
        !String::from_utf8_lossy(&o.stdout).contains("valentik"),
        "it ran first"
    );
    assert_eq!(
        std::fs::read_to_string(mine.join("bench/bench.csv")).unwrap(),
        "mine\n"
    );
}
