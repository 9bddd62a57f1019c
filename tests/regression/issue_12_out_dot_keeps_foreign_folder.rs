//! Regression test for issue 12, "Data loss and hangs" item 2: `settle run project/x.toml
//! --out .` with `name = "project"` replaced the folder holding the scenario: the scenario file
//! and a spreadsheet beside it were deleted (exit 0). A folder settle did not create is never
//! deleted or replaced: the run is refused (exit 2) before anything runs, naming the folder and
//! the way out.
//!
//! Set `SETTLE_BIN` to run these checks against another binary (e.g. the one before the fix).

use crate::common::{assert_exit, settle, tmp};

#[test]
fn out_dot_never_replaces_the_folder_of_the_scenario() {
    let dir = tmp();
    let project = dir.path().join("project");
    std::fs::create_dir(&project).unwrap();
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenarios/stokes_single.toml"
    ))
    .unwrap()
    .replace("name = \"stokes_single\"", "name = \"project\"");
    std::fs::write(project.join("x.toml"), &text).unwrap();
    std::fs::write(project.join("data.xlsx"), "spreadsheet").unwrap();
    let o = settle()
        .current_dir(dir.path())
        .args(["run", "project/x.toml", "--out", "."])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(
        std::fs::read_to_string(project.join("x.toml")).unwrap(),
        text
    );
    assert_eq!(
        std::fs::read_to_string(project.join("data.xlsx")).unwrap(),
        "spreadsheet"
    );
    assert!(err.contains("project") && err.contains("--out"), "{err}");
    // Nothing else was written either.
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, ["project"], "{names:?}");
}

/// `--out` naming a file is bad input (exit 2), not an unclassified failure.
#[test]
fn out_naming_a_file_is_bad_input() {
    let dir = tmp();
    let file = dir.path().join("results");
    std::fs::write(&file, "not a folder").unwrap();
    let o = settle()
        .args(["run", "-q", "--out"])
        .arg(&file)
        .arg(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/scenarios/stokes_single.toml"
        ))
        .output()
        .unwrap();
    assert_exit(&o, 2);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "not a folder");
}

/// The same for a sweep: a folder `<name>_sweep` settle did not create is refused before any
/// case runs (it used to be found only when the results moved into place, exit 4).
#[test]
fn a_sweep_never_replaces_a_folder_settle_did_not_create() {
    let dir = tmp();
    let mine = dir.path().join("stokes_single_sweep");
    std::fs::create_dir(&mine).unwrap();
    std::fs::write(mine.join("notes.txt"), "mine").unwrap();
    let o = settle()
        .args(["sweep", "-q", "--dt", "1e-3", "--out"])
        .arg(dir.path())
        .arg(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/scenarios/stokes_single.toml"
        ))
        .output()
        .unwrap();
    assert_exit(&o, 2);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("not created by settle"), "{err}");
    let left: Vec<_> = std::fs::read_dir(&mine)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, vec!["notes.txt"], "the user's folder was touched");
}
