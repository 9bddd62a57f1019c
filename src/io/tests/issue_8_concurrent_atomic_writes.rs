//! Issue 8 (moved from `tests/regression/issue_8_concurrent_checkpoint_saves.rs`). Symptom (CI, after issue 12): `settle run pour.toml --set repeats.count=2 --checkpoint-every
//! 0.2` failed 5 times out of 6 with `error: pour.toml: No such file or directory (os error 2)`,
//! exit 4, and left no checkpoint to resume. The two repeats run in parallel and saved their first
//! checkpoint at the same moment; both wrote `checkpoint/request.toml.tmp`, the first rename took
//! it and the second found nothing.

use crate::io::write_atomic;

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("temp dir")
}

/// Many threads writing the same file atomically at once: every write succeeds, the file holds
/// one of the writes whole, and no temporary file is left behind.
#[test]
fn concurrent_atomic_writes_of_one_file_all_succeed() {
    let dir = tmp();
    let path = dir.path().join("request.toml");
    std::thread::scope(|s| {
        for t in 0..8u8 {
            let path = &path;
            s.spawn(move || {
                for _ in 0..200 {
                    write_atomic(path, &[t; 4096]).unwrap();
                }
            });
        }
    });
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(bytes.len(), 4096);
    assert!(bytes.iter().all(|&b| b == bytes[0]), "a torn file");
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(left.len(), 1, "{left:?}");
}
