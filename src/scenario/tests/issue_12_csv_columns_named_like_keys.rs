//! Issue 12, a sphere CSV's columns (moved from `tests/regression/issue_12_accepted_silently.rs`):
//! as found, a sphere CSV whose measured-velocity column is spelled like the TOML key
//! (`v_measured_m_s`) had the column ignored; now `v_measured_m_s` (and `id`) are read as the
//! TOML keys, the old column names still read.

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("temp dir")
}

/// A CSV with the TOML key names `id` and `v_measured_m_s` (spaces around the numbers) gives the
/// same spheres as one with the old names `sphere_id` and `v_terminal_measured_m_s`. The old
/// binary dropped the measured velocity of the first (`None`).
#[test]
fn csv_columns_named_like_the_toml_keys_are_read() {
    let dir = tmp();
    let scenario = |csv: &str| {
        format!(
            "name = \"csv_keys\"\nkind = \"free_settling\"\n\
             [fluid]\ndensity_kg_m3 = 1000.0\nrheology = \"newtonian\"\nviscosity_pa_s = 1e-3\n\
             [drag]\nlaw = \"stokes\"\n[time]\ndt_s = 1e-3\nend_s = 1.0\n\
             [spheres_csv]\npath = \"{csv}\"\n"
        )
    };
    let read = |name: &str, csv_text: &str| {
        std::fs::write(dir.path().join(format!("{name}.csv")), csv_text).expect("write csv");
        let toml = dir.path().join(format!("{name}.toml"));
        std::fs::write(&toml, scenario(&format!("{name}.csv"))).expect("write toml");
        let s = crate::scenario::load(&toml, &[]).expect("good scenario");
        crate::scenario::inputs::spheres(&s, &toml).expect("good CSV")
    };
    let new = read(
        "new",
        "id,diameter_m,density_kg_m3,v_measured_m_s\nA, 1e-4 ,2700, 0.005\nB,2e-4,2700,\n",
    );
    let old = read(
        "old",
        "sphere_id,diameter_m,density_kg_m3,v_terminal_measured_m_s\nA,1e-4,2700,0.005\nB,2e-4,2700,\n",
    );
    assert_eq!(new, old);
    assert_eq!(new[0].spec.v_measured_m_s, Some(0.005));
    assert_eq!(new[1].spec.v_measured_m_s, None);
}
