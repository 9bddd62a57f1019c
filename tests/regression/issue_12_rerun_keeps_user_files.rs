//! Regression test for issue 12, "Data loss and hangs" item 1: rerunning into the same `--out`
//! deleted the files the user had put into `OUT/NAME/` (notes, plots): the whole folder was
//! replaced by the new run's, with exit 0 and no warning.
//!
//! Set `SETTLE_BIN` to run these checks against another binary (e.g. the one before the fix).

use crate::common::{assert_exit, settle, tmp};

fn scenario(name: &str) -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenarios/stokes_single.toml"
    ))
    .unwrap()
    .replace("name = \"stokes_single\"", &format!("name = \"{name}\""))
}

#[test]
fn a_rerun_replaces_only_what_settle_wrote() {
    let dir = tmp();
    let file = dir.path().join("run.toml");
    std::fs::write(&file, scenario("stokes")).unwrap();
    let out = dir.path().join("out");
    let run = || {
        settle()
            .args(["run", "-q", "--out"])
            .arg(&out)
            .arg(&file)
            .output()
            .unwrap()
    };
    let o = run();
    assert_exit(&o, 0);
    let folder = out.join("stokes");
    std::fs::write(folder.join("notes.txt"), "my notes").unwrap();
    std::fs::create_dir(folder.join("plots")).unwrap();
    std::fs::write(folder.join("plots/fig1.png"), "png").unwrap();
    // A stale output of the first run that the second no longer writes goes away.
    assert!(folder.join("timeseries.csv").exists());
    std::fs::write(
        &file,
        scenario("stokes").replace("[record]", "[record]\ntimeseries = false"),
    )
    .unwrap();
    let o = run();
    assert_exit(&o, 0);
    assert_eq!(
        std::fs::read_to_string(folder.join("notes.txt")).unwrap(),
        "my notes",
        "the user's notes were deleted"
    );
    assert!(
        folder.join("plots/fig1.png").exists(),
        "the user's plot was deleted"
    );
    assert!(folder.join("summary.csv").exists());
    assert!(
        !folder.join("timeseries.csv").exists(),
        "settle's old output stayed"
    );
}
