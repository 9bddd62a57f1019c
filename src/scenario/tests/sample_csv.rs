//! The sample CSV of the sedimentation scenarios (moved from `tests/scenario/bad_input.rs`).

use std::path::{Path, PathBuf};

fn good(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(file)
}

/// The good sample CSV reads to the same distribution as the physics layer's reader.
#[test]
fn sample_csv_good_file_matches_distribution_load() {
    let path = good("sedimentation_sample1.toml");
    let s = crate::scenario::load(&path, &[]).expect("good scenario");
    let sm = s.sample.as_ref().expect("[sample]");
    for n in 1..=5 {
        let mut sm = sm.clone();
        sm.sample = n;
        let ours = crate::scenario::inputs::read_sample(&sm, &path).expect("good file");
        let csv = path.parent().unwrap().join(&sm.csv);
        let old = crate::sample::Distribution::load(&csv, n).expect("good file");
        assert_eq!(ours, old, "sample {n}");
    }
}
