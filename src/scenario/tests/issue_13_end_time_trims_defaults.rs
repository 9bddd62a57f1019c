//! Issue 13, "Reproducible runs" (item 5 of "What to build"): as found, a sedimentation run
//! could not be shortened with one `--set time.end_s=600`: the default snapshot times (60, 300,
//! 900 s) then failed validation (`sample.record_times_s/snapshot_times_s[2]`: 900 is out of
//! range). Now the default snapshot and instrument times after the end are dropped; times
//! written explicitly after the end are still refused, naming their key.

use crate::scenario::parse;
use std::path::Path;

const SED: &str = "scenarios/sedimentation_sample1.toml";

fn set(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

#[test]
fn a_shorter_end_time_trims_the_default_times_only() {
    let p = parse(Path::new(SED), &set(&["time.end_s=600"])).unwrap();
    let sm = p.scenario.sample.as_ref().unwrap();
    assert_eq!(sm.snapshot_times_s, [60.0, 300.0]);
    // An [instruments] table that leaves its times to the defaults: those within 600 s.
    let p = parse(
        Path::new(SED),
        &set(&["time.end_s=600", "instruments.sphere_depth_fraction=0.4"]),
    )
    .unwrap();
    let ins = p.scenario.instruments.as_ref().unwrap();
    assert_eq!(ins.hydrometer_times_s, [120.0, 300.0]);
    assert!(ins.buoyancy_times_s.iter().all(|&t| t <= 600.0));
    assert_eq!(ins.buoyancy_times_s.len(), 4);
    // Explicit times after the end: refused, naming the key.
    let e = parse(
        Path::new(SED),
        &set(&["time.end_s=600", "sample.snapshot_times_s=[60.0, 900.0]"]),
    )
    .unwrap_err();
    assert_eq!(e.key.as_deref(), Some("sample.snapshot_times_s[1]"), "{e}");
    assert!(e.message.contains("≤ 600"), "{e}");
    let e = parse(
        Path::new(SED),
        &set(&[
            "time.end_s=600",
            "instruments.hydrometer_times_s=[120.0, 900.0]",
        ]),
    )
    .unwrap_err();
    assert_eq!(
        e.key.as_deref(),
        Some("instruments.hydrometer_times_s[1]"),
        "{e}"
    );
}
