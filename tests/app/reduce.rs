//! `settle reduce` (`src/reduce/`): the worked examples of docs/commands/reduce.md reduce to
//! their published figures, and every bad input is one error naming the file, the row and the
//! column (or the key) and what is allowed, exit 2, nothing written.

use crate::common::chart::assert_readable_chart;
use crate::common::{assert_exit, num, read_csv_records, settle_command, tmp, tree};
use std::path::Path;

fn reduce(file: &Path, out: &Path, args: &[&str]) -> std::process::Output {
    settle_command("reduce", &[file.to_str().unwrap()], out, args)
}

/// docs/commands/reduce.md, D422: envalysis' clay loam (data/lab/README.md).
#[test]
fn the_d422_example_reduces_to_its_published_figures() {
    let out = tmp();
    let o = reduce(
        Path::new("data/lab/envalysis_clayloam_d422.csv"),
        out.path(),
        &[],
    );
    assert_exit(&o, 0);
    let dir = out.path().join("envalysis_clayloam_d422_reduced");
    let rows = read_csv_records(&dir.join("percent_finer.csv"));
    assert_eq!(rows.len(), 7);
    // P = (R − 2) / 50 g × 100 (a = 1 at G = 2.65); L = 16.29 − 0.164 R cm.
    for (r, (reading, p)) in rows.iter().zip([(39.0, 74.0), (33.0, 62.0), (18.0, 32.0)]) {
        if num(r, "reading") == reading {
            assert!((num(r, "percent_finer") - p).abs() < 1e-9);
            let l = 0.1629 - 0.00164 * reading;
            assert!((num(r, "effective_depth_m") - l).abs() < 1e-12);
        }
    }
    assert_eq!(rows[0]["time_s"], "39.6");
    assert_eq!(rows[0]["effective_depth_m"], "0.09894");
    // 0.66 min at 23 °C: 50.91 µm (envalysis: 51.55 µm with its deeper L, see
    // tests/instruments/reduction.rs).
    assert!((num(&rows[0], "diameter_m") / 50.913e-6 - 1.0).abs() < 1e-4);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("ASTM D422, 152H, 7 readings"), "{stdout}");
    assert_readable_chart(
        &dir.join("percent_finer.svg"),
        "percent finer (ASTM D422, 152H)",
        &["particle diameter", "percent finer"],
    );
    let toml = std::fs::read_to_string(dir.join("reduce.toml")).unwrap();
    assert!(toml.contains("standard = \"d422\""), "{toml}");
}

/// docs/commands/reduce.md, D7928: soiltestr's protocol 8 (data/lab/README.md).
#[test]
fn the_d7928_example_reduces_to_the_hand_calculation() {
    let out = tmp();
    let o = reduce(
        Path::new("data/lab/soiltestr_protocol8_d7928.csv"),
        out.path(),
        &[],
    );
    assert_exit(&o, 0);
    let dir = out.path().join("soiltestr_protocol8_d7928_reduced");
    let rows = read_csv_records(&dir.join("percent_finer.csv"));
    assert_eq!(rows.len(), 2);
    // H = 8.6 + 0.18 (60 − (r + 1.0)) − 55/(2 × 26.1) cm; N = 0.6226 (2.7/1.7)(1000/48.797)
    // (r − 6.25) × 0.1.
    for (r, reading) in rows.iter().zip([13.0, 11.75]) {
        let h = 8.6 + 0.18 * (60.0 - (reading + 1.0)) - 55.0 / 52.2;
        assert!((num(r, "effective_depth_m") * 100.0 - h).abs() < 1e-9);
        let n = 1.65 / 2.65 * (2.7 / 1.7) * (1000.0 / 48.797) * (reading - 6.25) * 0.1;
        assert!((num(r, "percent_finer") - n).abs() < 1e-9);
        assert_eq!(r["net_reading"], format!("{}", reading - 6.25));
    }
    // 75 120 s, 21.5 °C: 1.494 µm (the sheet's 1.511 µm at its 0.36 cm deeper H).
    assert!((num(&rows[1], "diameter_m") / 1.4943e-6 - 1.0).abs() < 1e-3);
    assert_readable_chart(
        &dir.join("percent_finer.svg"),
        "percent finer (ASTM D7928, 152H)",
        &["particle diameter", "percent finer"],
    );
    let toml = std::fs::read_to_string(dir.join("reduce.toml")).unwrap();
    assert!(toml.contains("h_r1_cm = 20.3"), "{toml}");
    // The same file saved by a spreadsheet (byte-order mark, CRLF) reads the same.
    let text = std::fs::read_to_string("data/lab/soiltestr_protocol8_d7928.csv").unwrap();
    let bom = out.path().join("bom.csv");
    std::fs::write(&bom, format!("\u{feff}{}", text.replace('\n', "\r\n"))).unwrap();
    assert_exit(&reduce(&bom, out.path(), &[]), 0);
    assert_eq!(
        std::fs::read_to_string(out.path().join("bom_reduced/percent_finer.csv")).unwrap(),
        std::fs::read_to_string(dir.join("percent_finer.csv")).unwrap()
    );
    // A rerun replaces settle's folder; --standard overrides the file's (d422 refuses the
    // D7928 dimensions).
    assert_exit(
        &reduce(
            Path::new("data/lab/soiltestr_protocol8_d7928.csv"),
            out.path(),
            &[],
        ),
        0,
    );
    let o = reduce(
        Path::new("data/lab/soiltestr_protocol8_d7928.csv"),
        out.path(),
        &["--standard", "d422"],
    );
    assert_exit(&o, 2);
    assert!(String::from_utf8_lossy(&o.stderr).contains("used by d7928 only"));
}

const D422_HEAD: &str = "# standard = d422\n# hydrometer = 152H\n# dry_mass_g = 50\n\
# specific_gravity = 2.65\n# meniscus_correction = 1\n# blank_reading = 2\n";

/// Writes `text` as a readings file, reduces it with `args`, and checks: exit 2, one error line
/// naming the file and every part of `expect`, nothing written.
fn refused(text: &str, args: &[&str], expect: &[&str]) {
    let dir = tmp();
    let file = dir.path().join("readings.csv");
    std::fs::write(&file, text).unwrap();
    let out = dir.path().join("out");
    let o = reduce(&file, &out, args);
    assert_exit(&o, 2);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("readings.csv"), "{err}");
    for e in expect {
        assert!(err.contains(e), "`{e}` not in: {err}");
    }
    assert!(!out.exists() || tree(&out).is_empty(), "{:?}", tree(&out));
}

#[test]
fn bad_readings_are_refused_naming_row_and_column() {
    let table = |rows: &str| format!("{D422_HEAD}time_min,reading,temperature_c\n{rows}");
    // A reading above the 152H's scale.
    refused(
        &table("2,40,20\n5,61,20\n"),
        &[],
        &["row 2 (line 9), column 2 `reading`", "61", "-5 to 60 g/L"],
    );
    // Below it.
    refused(
        &table("2,-6,20\n"),
        &[],
        &["row 1", "column 2 `reading`", "-5 to 60"],
    );
    // Times not strictly increasing.
    refused(
        &table("2,40,20\n5,35,20\n5,33,20\n"),
        &[],
        &[
            "row 3 (line 10), column 1 `time_min`",
            "not after",
            "increase strictly",
        ],
    );
    // A temperature outside D422's Table 3 (16–30 °C).
    refused(
        &table("2,40,20\n5,35,15.5\n"),
        &[],
        &["row 2", "column 3 `temperature_c`", "16–30 °C for d422"],
    );
    // Not a number; a negative time; a missing field.
    refused(
        &table("2,forty,20\n"),
        &[],
        &["row 1", "column 2 `reading`", "not a number"],
    );
    refused(
        &table("-1,40,20\n"),
        &[],
        &["row 1", "column 1 `time_min`", "> 0"],
    );
    refused(
        &table("2,40\n"),
        &[],
        &["row 1 (line 8)", "2 fields, the header has 3"],
    );
    // The 151H's scale.
    let h151 = D422_HEAD
        .replace("152H", "151H")
        .replace("meniscus_correction = 1", "meniscus_correction = 0.001")
        .replace("blank_reading = 2", "blank_reading = 1.002");
    refused(
        &format!("{h151}time_min,reading,temperature_c\n2,1.045,20\n"),
        &[],
        &[
            "column 2 `reading`",
            "1.045",
            "0.995 to 1.038 specific gravity",
        ],
    );
    // A blank reading off the scale, in its column.
    refused(
        &format!(
            "{}time_min,reading,temperature_c,blank_reading\n2,40,20,70\n",
            D422_HEAD.replace("# blank_reading = 2\n", "")
        ),
        &[],
        &["column 4 `blank_reading`", "-5 to 60"],
    );
}

#[test]
fn bad_figures_and_columns_are_refused() {
    let rows = "time_min,reading,temperature_c\n2,40,20\n";
    // Missing figures.
    for key in ["dry_mass_g", "specific_gravity", "meniscus_correction"] {
        let text = D422_HEAD
            .lines()
            .filter(|l| !l.contains(key))
            .map(|l| format!("{l}\n"))
            .collect::<String>();
        refused(&format!("{text}{rows}"), &[], &[key, "missing"]);
    }
    refused(
        &format!("{}{rows}", D422_HEAD.replace("# blank_reading = 2\n", "")),
        &[],
        &["blank_reading", "missing"],
    );
    // A figure out of range; an unknown or duplicated key.
    refused(
        &format!(
            "{}{rows}",
            D422_HEAD.replace("dry_mass_g = 50", "dry_mass_g = 0")
        ),
        &[],
        &["dry_mass_g", "line 3", "0.001–10000 g"],
    );
    refused(
        &format!("{D422_HEAD}# dry_mass = 50\n{rows}"),
        &[],
        &["dry_mass", "unknown key"],
    );
    refused(
        &format!("{D422_HEAD}# dry_mass_g = 51\n{rows}"),
        &[],
        &["dry_mass_g", "given twice"],
    );
    // Missing, unknown or ambiguous columns.
    refused(
        &format!("{D422_HEAD}time_min,reading\n2,40\n"),
        &[],
        &["missing column `temperature_c`"],
    );
    refused(
        &format!("{D422_HEAD}time_min,reading,temperature_c,depth\n2,40,20,1\n"),
        &[],
        &["column 4", "unknown column `depth`"],
    );
    refused(
        &format!("{D422_HEAD}time_min,time_s,reading,temperature_c\n2,120,40,20\n"),
        &[],
        &["one time column"],
    );
    refused(D422_HEAD, &[], &["no header"]);
    refused(
        &format!("{D422_HEAD}{}", "time_min,reading,temperature_c\n"),
        &[],
        &["no readings"],
    );
    // Unknown standard or hydrometer, from the command line or the file.
    refused(
        &format!("{D422_HEAD}{rows}"),
        &["--standard", "d999"],
        &["--standard", "unknown standard `d999`", "d422, d7928"],
    );
    refused(
        &format!("{}{rows}", D422_HEAD.replace("152H", "150H")),
        &[],
        &["hydrometer", "line 2", "152H, 151H"],
    );
    // D7928 without the hydrometer's measured dimensions.
    refused(
        &format!("{D422_HEAD}{rows}"),
        &["--standard", "d7928"],
        &["h_r1_cm", "missing"],
    );
}

#[test]
fn a_folder_settle_did_not_create_is_not_replaced() {
    let dir = tmp();
    let out = dir.path().join("out");
    let mine = out.join("envalysis_clayloam_d422_reduced");
    std::fs::create_dir_all(&mine).unwrap();
    std::fs::write(mine.join("notes.txt"), "mine").unwrap();
    let o = reduce(Path::new("data/lab/envalysis_clayloam_d422.csv"), &out, &[]);
    assert_exit(&o, 2);
    assert!(String::from_utf8_lossy(&o.stderr).contains("not created by settle"));
    assert_eq!(tree(&out).len(), 2, "{:?}", tree(&out));
}

const PIPETTE_HEAD: &str = "# instrument = pipette\n# dry_mass_g = 50\n# specific_gravity = 2.65\n\
# pipette_volume_ml = 10\n# pipette_depth_cm = 10\n# blank_reading = 0.005\n";

const SPHERE_HEAD: &str = "# instrument = buoyancy-sphere\n# dry_mass_g = 50\n\
# specific_gravity = 2.65\n# sphere_diameter_mm = 25\n# sphere_mass_g = 20\n\
# sphere_depth_cm = 10\n";

/// Writes `text` as `name` in a new folder, reduces it, and returns its percent_finer.csv rows
/// and reduce.toml.
fn reduced(name: &str, text: &str) -> (Vec<std::collections::HashMap<String, String>>, String) {
    let dir = tmp();
    let file = dir.path().join(name);
    std::fs::write(&file, text).unwrap();
    let o = reduce(&file, &dir.path().join("out"), &[]);
    assert_exit(&o, 0);
    let stem = name.trim_end_matches(".csv");
    let out = dir.path().join(format!("out/{stem}_reduced"));
    let toml = std::fs::read_to_string(out.join("reduce.toml")).unwrap();
    // The chart and the console name the method: the pipette's eq. 17, the sphere's eq. 22.
    let method = if text.contains("instrument = pipette") {
        "pipette, seed 000 eq. 17"
    } else {
        "buoyancy sphere, seed 000 eq. 22"
    };
    assert!(String::from_utf8_lossy(&o.stdout).contains(method));
    assert_readable_chart(
        &out.join("percent_finer.svg"),
        &format!("percent finer ({method})"),
        &["particle diameter", "percent finer"],
    );
    (read_csv_records(&out.join("percent_finer.csv")), toml)
}

/// Stokes at depth z (m) and time t (s) with μ and ρ_w of water at 25 °C (IAPWS: 0.8900 mPa s,
/// 997.05 kg/m³) or 20 °C (1.0016 mPa s, 998.21 kg/m³), G_s = 2.65, g = 9.807 m/s².
fn stokes_by_hand(mu: f64, rho: f64, z: f64, t: f64) -> f64 {
    (18.0 * mu * z / (rho * 1.65 * 9.807 * t)).sqrt()
}

/// A pipette test by hand: P = 100 (m_p − m_b)/V_p / (M_d/V_sp) (seed 000 eq. 17, BS 1377-2's
/// pipette ratio), D by Stokes at the tip's depth with water at the test's temperature.
#[test]
fn a_pipette_test_reduces_to_the_hand_calculation() {
    let (rows, toml) = reduced(
        "pipette.csv",
        &format!("{PIPETTE_HEAD}time_min,drawn_mass_g,temperature_c\n1,0.4,25\n10,0.2,25\n"),
    );
    assert_eq!(rows.len(), 2);
    // (0.4 − 0.005) g / 10 mL over 50 g / 1000 mL: 79 %; (0.2 − 0.005)/10 / 0.05: 39 %.
    for (r, (p, t)) in rows.iter().zip([(79.0, 60.0), (39.0, 600.0)]) {
        assert!((num(r, "percent_finer") - p).abs() < 1e-9, "{r:?}");
        assert_eq!(num(r, "effective_depth_m"), 0.1);
        let d = stokes_by_hand(0.8900e-3, 997.05, 0.1, t);
        assert!(
            (num(r, "diameter_m") / d - 1.0).abs() < 2e-4,
            "{r:?} vs {d}"
        );
    }
    assert!((num(&rows[0], "diameter_m") - 40.68e-6).abs() < 0.01e-6);
    assert!(toml.contains("instrument = \"pipette\""), "{toml}");
    assert!(toml.contains("pipette_region = \"sphere\""), "{toml}");
    assert!(!toml.contains("standard"), "{toml}");
    // The blank as a column instead, and 0 when not given.
    let (rows, _) = reduced(
        "pipette_col.csv",
        &format!(
            "{}time_min,drawn_mass_g,temperature_c,blank_reading\n1,0.4,25,0.015\n",
            PIPETTE_HEAD.replace("# blank_reading = 0.005\n", "")
        ),
    );
    assert!((num(&rows[0], "percent_finer") - 77.0).abs() < 1e-9);
    let (rows, _) = reduced(
        "pipette_noblank.csv",
        &format!(
            "{}time_min,drawn_mass_g,temperature_c\n1,0.4,25\n",
            PIPETTE_HEAD.replace("# blank_reading = 0.005\n", "")
        ),
    );
    assert!((num(&rows[0], "percent_finer") - 80.0).abs() < 1e-9);
}

/// A buoyancy-sphere test by hand (seed 000 eq. 22): m_sp,w = 20 g − ρ_f π (2.5 cm)³/6,
/// w = 100 (V_sp/M_d) G_s/(G_s − 1) (m_sp,w − m_sp)/V_sp, ρ_f = ρ_w(20 °C) or the file's
/// `fluid_density_kg_m3`.
#[test]
fn a_buoyancy_sphere_test_reduces_to_the_hand_calculation() {
    let v_cm3 = std::f64::consts::PI * 2.5f64.powi(3) / 6.0; // 8.1812 cm³
    let by_hand = |rho_f_g_cm3: f64, m: f64| {
        let net = 20.0 - rho_f_g_cm3 * v_cm3 - m;
        100.0 * (1000.0 / 50.0) * (2.65 / 1.65) * net / v_cm3
    };
    let table = "time_min,apparent_mass_g\n1,11.6\n10,11.7\n";
    let (rows, toml) = reduced(
        "sphere.csv",
        &format!("{SPHERE_HEAD}# temperature_c = 20\n{table}"),
    );
    assert_eq!(rows.len(), 2);
    for (r, (m, t)) in rows.iter().zip([(11.6, 60.0), (11.7, 600.0)]) {
        let w = by_hand(0.998207, m);
        assert!((num(r, "percent_finer") - w).abs() < 2e-3, "{r:?} vs {w}");
        let d = stokes_by_hand(1.0016e-3, 998.21, 0.1, t);
        assert!(
            (num(r, "diameter_m") / d - 1.0).abs() < 2e-5,
            "{r:?} vs {d}"
        );
    }
    // 91.65 % and 52.39 % at 43.13 and 13.64 µm.
    assert!((num(&rows[0], "percent_finer") - 91.65).abs() < 0.01);
    assert!((num(&rows[1], "percent_finer") - 52.39).abs() < 0.01);
    assert!(toml.contains("sphere_diameter_mm = 25"), "{toml}");
    // A dispersant solution of 1010 kg/m³: the clear-fluid apparent mass, and the Stokes Δρ, move.
    let (rows, toml) = reduced(
        "sphere_disp.csv",
        &format!("{SPHERE_HEAD}# temperature_c = 20\n# fluid_density_kg_m3 = 1010\n{table}"),
    );
    let w = by_hand(1.010, 11.6);
    assert!(
        (num(&rows[0], "percent_finer") - w).abs() < 1e-6,
        "{rows:?} vs {w}"
    );
    let d = (18.0f64 * 1.0016e-3 * 0.1 / (1010.0 * 1.65 * 9.807 * 60.0)).sqrt();
    assert!((num(&rows[0], "diameter_m") / d - 1.0).abs() < 1e-5);
    assert!(
        toml.contains("[model]\nfluid_density_kg_m3 = 1010"),
        "{toml}"
    );
}

#[test]
fn bad_pipette_and_sphere_files_are_refused() {
    let pip = |head: &str, rows: &str| format!("{head}time_min,drawn_mass_g,temperature_c\n{rows}");
    let sph =
        |head: &str, rows: &str| format!("{head}time_min,apparent_mass_g,temperature_c\n{rows}");
    // Missing figures.
    for key in ["pipette_volume_ml", "pipette_depth_cm", "dry_mass_g"] {
        let head: String = PIPETTE_HEAD
            .lines()
            .filter(|l| !l.contains(key))
            .map(|l| format!("{l}\n"))
            .collect();
        refused(&pip(&head, "1,0.4,25\n"), &[], &[key, "missing"]);
    }
    for key in ["sphere_diameter_mm", "sphere_mass_g", "sphere_depth_cm"] {
        let head: String = SPHERE_HEAD
            .lines()
            .filter(|l| !l.contains(key))
            .map(|l| format!("{l}\n"))
            .collect();
        refused(&sph(&head, "1,11.6,20\n"), &[], &[key, "missing"]);
    }
    // A negative drawn mass; an apparent mass above the mass in air.
    refused(
        &pip(PIPETTE_HEAD, "1,0.4,25\n2,-0.01,25\n"),
        &[],
        &[
            "row 2 (line 9), column 2 `drawn_mass_g`",
            "-0.01",
            "0 to 50 g",
        ],
    );
    refused(
        &sph(SPHERE_HEAD, "1,20.5,20\n"),
        &[],
        &[
            "row 1",
            "column 2 `apparent_mass_g`",
            "20.5",
            "0 to 20 g",
            "mass in air",
        ],
    );
    // The pipette's tip (and its 10 mL draw, radius 1.34 cm) beyond the column: 1000 mL over
    // 27.8 cm² is 35.97 cm, or the given column_height_cm.
    refused(
        &pip(
            &PIPETTE_HEAD.replace("pipette_depth_cm = 10", "pipette_depth_cm = 40"),
            "1,0.4,25\n",
        ),
        &[],
        &["pipette_depth_cm", "line 5", "1.337–34.63 cm"],
    );
    refused(
        &pip(
            &format!("{PIPETTE_HEAD}# column_height_cm = 9\n"),
            "1,0.4,25\n",
        ),
        &[],
        &["pipette_depth_cm", "1.337–7.663 cm"],
    );
    refused(
        &sph(
            &SPHERE_HEAD.replace("sphere_depth_cm = 10", "sphere_depth_cm = 1"),
            "1,11.6,20\n",
        ),
        &[],
        &["sphere_depth_cm", "1.25–34.72 cm"],
    );
    // An unknown instrument, region; the disc's radius missing, or given for a sphere region.
    refused(
        &pip(&PIPETTE_HEAD.replace("= pipette", "= pipet"), "1,0.4,25\n"),
        &[],
        &[
            "instrument",
            "line 1",
            "unknown instrument `pipet`",
            "hydrometer, pipette, buoyancy-sphere",
        ],
    );
    refused(
        &pip(
            &format!("{PIPETTE_HEAD}# pipette_region = cube\n"),
            "1,0.4,25\n",
        ),
        &[],
        &["pipette_region", "sphere, disc"],
    );
    refused(
        &pip(
            &format!("{PIPETTE_HEAD}# pipette_region = disc\n"),
            "1,0.4,25\n",
        ),
        &[],
        &["pipette_radius_cm", "missing"],
    );
    refused(
        &pip(
            &format!("{PIPETTE_HEAD}# pipette_radius_cm = 1.5\n"),
            "1,0.4,25\n",
        ),
        &[],
        &["pipette_radius_cm", "pipette_region = disc"],
    );
    // Figures of the hydrometer (a D7928 dimension, the standard) for a pipette, from the file
    // or the command line; a pipette figure in a hydrometer file; another instrument's column.
    refused(
        &pip(&format!("{PIPETTE_HEAD}# h_r1_cm = 20.3\n"), "1,0.4,25\n"),
        &[],
        &["h_r1_cm", "line 7", "D7928", "not used by a pipette"],
    );
    refused(
        &pip(&format!("{PIPETTE_HEAD}# standard = d7928\n"), "1,0.4,25\n"),
        &[],
        &["standard", "hydrometer figure", "not used by a pipette"],
    );
    refused(
        &pip(PIPETTE_HEAD, "1,0.4,25\n"),
        &["--standard", "d7928"],
        &["--standard", "for the hydrometer only"],
    );
    refused(
        &format!("{D422_HEAD}# sphere_mass_g = 20\ntime_min,reading,temperature_c\n2,40,20\n"),
        &[],
        &[
            "sphere_mass_g",
            "not used by a hydrometer",
            "instrument = buoyancy-sphere",
        ],
    );
    refused(
        &format!("{PIPETTE_HEAD}time_min,reading,temperature_c\n1,0.4,25\n"),
        &[],
        &["column 2", "not one of this instrument's", "drawn_mass_g"],
    );
    // A sphere that floats; a blank for the sphere; a temperature off the water correlations.
    refused(
        &sph(
            &SPHERE_HEAD.replace("sphere_mass_g = 20", "sphere_mass_g = 8"),
            "1,7,20\n",
        ),
        &[],
        &["sphere_mass_g", "floats", "more than 8.18"],
    );
    refused(
        &sph(
            &format!("{SPHERE_HEAD}# blank_reading = 11.8\n"),
            "1,11.6,20\n",
        ),
        &[],
        &["blank_reading", "fluid_density_kg_m3"],
    );
    refused(
        &pip(PIPETTE_HEAD, "1,0.4,45\n"),
        &[],
        &["column 3 `temperature_c`", "0–40 °C"],
    );
    // A model figure out of range; the temperature twice.
    refused(
        &pip(
            &format!("{PIPETTE_HEAD}# fluid_density_kg_m3 = 100\n"),
            "1,0.4,25\n",
        ),
        &[],
        &["fluid_density_kg_m3", "500–3000 kg/m³"],
    );
    refused(
        &pip(
            &format!("{PIPETTE_HEAD}# temperature_c = 25\n"),
            "1,0.4,25\n",
        ),
        &[],
        &["temperature_c", "given both"],
    );
}

/// A published worked example of D422's percent finer (data/lab/README.md: the Atech Center's
/// hydrometer procedure, Step II): R = 38.0 − 7.5 = 30.5, a = 1.00, w = 81.09 g: P = 37.6 %,
/// checked within its printed rounding.
#[test]
fn the_atech_d422_example_gives_its_printed_percent_finer() {
    let out = tmp();
    let o = reduce(
        Path::new("data/lab/atech_d422_percent_finer.csv"),
        out.path(),
        &[],
    );
    assert_exit(&o, 0);
    let rows = read_csv_records(
        &out.path()
            .join("atech_d422_percent_finer_reduced/percent_finer.csv"),
    );
    assert_eq!(rows.len(), 1);
    assert_eq!(num(&rows[0], "net_reading"), 30.5);
    let p = num(&rows[0], "percent_finer");
    assert!((p - 37.6).abs() <= 0.05, "{p}");
}

/// The library entry `settle::reduce::reduce` makes in memory exactly the files `settle reduce`
/// writes (tables cell for cell, the chart and the record byte for byte), from the file and from
/// the same readings given as an in-memory table.
#[test]
fn the_in_memory_reduction_equals_the_files_the_command_writes() {
    use settle::reduce::{reduce as reduce_in_memory, Readings, ReduceOptions};
    let file = Path::new("data/lab/envalysis_clayloam_d422.csv");
    let out = tmp();
    assert_exit(&reduce(file, out.path(), &[]), 0);
    let dir = out.path().join("envalysis_clayloam_d422_reduced");
    let r = reduce_in_memory(file, &ReduceOptions::default()).unwrap();
    assert_eq!(r.name, "envalysis_clayloam_d422_reduced");
    let on_disk = settle::Table::from_csv(
        "percent_finer.csv",
        &std::fs::read(dir.join("percent_finer.csv")).unwrap(),
    )
    .unwrap();
    assert_eq!(r.table("percent_finer"), Some(&on_disk));
    for f in [
        "percent_finer.svg",
        "percent_finer.xlsx",
        "percent_finer.ags",
        "reduce.toml",
    ] {
        assert_eq!(
            r.outputs.bytes(f).unwrap(),
            std::fs::read(dir.join(f)).unwrap(),
            "{f}"
        );
    }
    // The same readings as figures and a table in memory.
    let text = std::fs::read_to_string(file).unwrap();
    let mut figures = Vec::new();
    let mut lines = Vec::new();
    for l in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
        match l.strip_prefix('#').and_then(|c| c.split_once('=')) {
            Some((k, v)) => figures.push((k.trim().to_string(), v.trim().to_string())),
            None if l.starts_with('#') => {}
            None => lines.push(l.split(',').map(str::to_string).collect::<Vec<_>>()),
        }
    }
    let table = settle::Table::with_rows(
        "envalysis_clayloam_d422.csv",
        lines[0].clone(),
        lines[1..].to_vec(),
    );
    let m = reduce_in_memory(Readings::table(figures, table), &ReduceOptions::default()).unwrap();
    assert_eq!(m.table("percent_finer"), Some(&on_disk));
    assert_eq!(m.name, r.name);
    // Written by the library: the same files as the command line's.
    let lib = tmp();
    let written = m.write(lib.path()).unwrap();
    assert_eq!(
        std::fs::read(written.join("percent_finer.csv")).unwrap(),
        std::fs::read(dir.join("percent_finer.csv")).unwrap()
    );
}
