//! The measured curves of `[reference]` (`src/scenario/inputs.rs`, [`read_reference`]; moved
//! from `tests/scenario/reference_csv.rs`, where the bad files are refused through `settle run`):
//! read relative to the scenario file, any extra column ignored.

use crate::scenario::inputs::read_reference;
use std::path::Path;

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("temp dir")
}

const SCENARIO: &str = r#"
name = "reference"
kind = "free_settling"
[fluid]
density_kg_m3 = 970.0
rheology = "newtonian"
viscosity_pa_s = 0.373
[drag]
law = "schiller-naumann"
[time]
dt_s = 1e-3
end_s = 0.1
[container]
height_m = 0.16
[[spheres]]
diameter_m = 0.015
density_kg_m3 = 1120.0
[reference]
source = "a test"
velocity_csv = "data/v.csv"
gap_csv = "data/gap.csv"
"#;

/// Writes the scenario (with `replace` applied to its text) and the two CSVs into `dir`.
fn write(dir: &Path, v: &str, gap: &str, replace: (&str, &str)) -> std::path::PathBuf {
    std::fs::create_dir_all(dir.join("data")).unwrap();
    std::fs::write(dir.join("data/v.csv"), v).unwrap();
    std::fs::write(dir.join("data/gap.csv"), gap).unwrap();
    let toml = dir.join("s.toml");
    std::fs::write(&toml, SCENARIO.replace(replace.0, replace.1)).unwrap();
    toml
}

const GOOD_V: &str = "time_s,velocity_m_s\n0.1,0.01\n0.2,0.02\n";
const GOOD_GAP: &str = "time_s,gap_over_diameter,gap_m\n-0.01,8.1,0.1215\n0.5,7,0.105\n";

#[test]
fn the_curves_are_read_relative_to_the_scenario_with_extra_columns_ignored() {
    let d = tmp();
    let toml = write(d.path(), GOOD_V, GOOD_GAP, ("", ""));
    let s = crate::scenario::load(&toml, &[]).unwrap();
    let m = read_reference(&s, &toml).unwrap().expect("a [reference]");
    assert_eq!(m.source, "a test");
    assert_eq!(m.velocity, [(0.1, 0.01), (0.2, 0.02)]);
    assert_eq!(m.gap, [(-0.01, 0.1215), (0.5, 0.105)]);
    // Another kind refuses the table, as every table its kind does not use.
    let toml = write(
        d.path(),
        GOOD_V,
        GOOD_GAP,
        ("kind = \"free_settling\"", "kind = \"drop\""),
    );
    let e = crate::scenario::load(&toml, &[]).unwrap_err().to_string();
    assert!(e.contains("reference"), "{e}");
}
