//! The spheres CSV of `[spheres_csv]` (`src/scenario/inputs.rs`): columns named like the keys of
//! `[[spheres]]`, the old names still read, spaces around fields accepted, and every error naming
//! the line of the file and the data row (both 1-based) and the column (1-based).

use crate::scenario::inputs::{spheres, SphereCase};
use std::path::Path;

const SCENARIO: &str = r#"
name = "csv"
kind = "free_settling"
[fluid]
density_kg_m3 = 1000.0
rheology = "newtonian"
viscosity_pa_s = 0.001
[drag]
law = "stokes"
[time]
dt_s = 1e-4
end_s = 0.01
[spheres_csv]
path = "spheres.csv"
"#;

/// The spheres of a scenario whose CSV holds `csv`, or the error line.
fn read(dir: &Path, csv: &str) -> Result<Vec<SphereCase>, String> {
    let toml = dir.join("s.toml");
    std::fs::write(&toml, SCENARIO).unwrap();
    std::fs::write(dir.join("spheres.csv"), csv).unwrap();
    let s = crate::scenario::load(&toml, &[]).expect("the scenario itself is good");
    spheres(&s, &toml).map_err(|e| {
        assert_eq!(e.key.as_deref(), Some("spheres_csv.path"), "{e}");
        e.to_string()
    })
}

fn assert_has(line: &str, words: &[&str]) {
    for w in words {
        assert!(line.contains(w), "`{w}` missing from: {line}");
    }
}

#[test]
fn toml_key_names_and_old_names_read_the_same_spheres_with_spaces_around_fields() {
    let d = tmp();
    let new = read(
        d.path(),
        "id,suspension,diameter_m,density_kg_m3,youngs_modulus_pa,poisson_ratio,v_measured_m_s\n\
         a,1,1e-3,2500,3e10,0.25,0.1\nb,2,2e-3,2600,,,\n",
    )
    .unwrap();
    let old = read(
        d.path(),
        "# the old column names, spaces around every field\n\
         sphere_id , suspension , diameter_m , density_kg_m3 , youngs_modulus_pa , poisson_ratio , v_terminal_measured_m_s\n\
          a , 1 , 1e-3 , 2500 , 3e10 , 0.25 , 0.1 \n b ,2, 2e-3 ,2600 , , ,\n",
    )
    .unwrap();
    assert_eq!(new, old);
    assert_eq!(new.len(), 2);
    let a = &new[0].spec;
    assert_eq!((a.diameter_m, a.density_kg_m3), (1e-3, 2500.0));
    assert_eq!(
        (a.youngs_modulus_pa, a.poisson_ratio),
        (Some(3e10), Some(0.25))
    );
    assert_eq!((a.v_measured_m_s, a.suspension), (Some(0.1), Some(1)));
    assert_eq!(
        new[1].spec.youngs_modulus_pa, None,
        "an empty field is absent"
    );
}

/// Line 1 is the header, comment lines count; data row 1 is the first line of data.
#[test]
fn a_bad_number_names_the_line_the_data_row_and_the_column() {
    let d = tmp();
    let e = read(
        d.path(),
        "# comment\nid,diameter_m,density_kg_m3\na,1e-3,2500\nb,1e-3,heavy\n",
    )
    .unwrap_err();
    assert_has(
        &e,
        &[
            "spheres.csv",
            "line 4 (data row 2), column 3 (`density_kg_m3`)",
            "`heavy` is not a number",
        ],
    );
}

#[test]
fn a_value_out_of_range_names_its_column_and_the_allowed_range() {
    let d = tmp();
    let e = read(
        d.path(),
        "id,density_kg_m3,diameter_m\na,2500,1e-3\nb,2500,-2e-3\n",
    )
    .unwrap_err();
    assert_has(
        &e,
        &[
            "line 3 (data row 2), column 3 (`diameter_m`)",
            "-0.002 is out of range",
            "allowed 0 < diameter_m ≤ 10 m",
        ],
    );
    let e = read(
        d.path(),
        "sphere_id,diameter_m,density_kg_m3,v_terminal_measured_m_s\na,1e-3,2500,2000\n",
    )
    .unwrap_err();
    assert_has(
        &e,
        &[
            "line 2 (data row 1), column 4 (`v_terminal_measured_m_s`)",
            "allowed 0 ≤ v_measured_m_s ≤ 1000 m/s",
        ],
    );
}

#[test]
fn a_row_with_missing_fields_names_its_line_and_data_row() {
    let d = tmp();
    let e = read(
        d.path(),
        "id,diameter_m,density_kg_m3\n# comment\na,1e-3,2500\nb,1e-3\n",
    )
    .unwrap_err();
    assert_has(
        &e,
        &["line 4 (data row 2)", "2 fields where the header has 3"],
    );
    assert!(
        !e.contains("CSV error"),
        "worded as the other row errors: {e}"
    );
}

#[test]
fn an_empty_id_and_a_repeated_id_name_their_rows() {
    let d = tmp();
    let e = read(d.path(), "diameter_m,id,density_kg_m3\n1e-3,,2500\n").unwrap_err();
    assert_has(
        &e,
        &[
            "line 2 (data row 1), column 2 (`id`)",
            "every sphere needs an id",
        ],
    );
    let e = read(
        d.path(),
        "id,diameter_m,density_kg_m3\na,1e-3,2500\na,2e-3,2500\n",
    )
    .unwrap_err();
    assert_has(
        &e,
        &[
            "line 3 (data row 2)",
            "already the id of line 2 (data row 1)",
        ],
    );
}

/// A fresh temporary folder, removed when dropped.
fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("temp dir")
}
