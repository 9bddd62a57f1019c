//! Issue 13, "honest console tables" and "validity warnings": as found, the drop's console table
//! printed `v_sim 0.00000e0 … static` for its 18 rows and omitted the settling distance, its
//! result; one table mixed `0.1000`, `1.54686e-1` and `1.24795e0`; and Stokes drag on a 10 mm
//! steel ball in water ran silently to a 373 m/s "force balance".

use crate::app::console::{assert_one_number_format, run, shows, toml_warnings};
use crate::common::{read_csv_records, tmp};

/// The drop's table shows entry speed, settling distance and stop time per ball, the settling
/// distance as summary.csv has it (in mm); no velocity column of zeros.
#[test]
fn the_drop_table_shows_the_settling_distance() {
    let dir = tmp();
    let text = run("scenarios/paste_single_ball.toml", dir.path(), &[]);
    let header: Vec<&str> = text.lines().nth(1).unwrap().split_whitespace().collect();
    for c in ["entry_speed_m_s", "settling_distance_mm", "stop_time_s"] {
        assert!(header.contains(&c), "{header:?}");
    }
    assert!(!header.iter().any(|c| c.starts_with("v_sim")), "{header:?}");
    let at = header
        .iter()
        .position(|c| *c == "settling_distance_mm")
        .unwrap();
    let rows = read_csv_records(&dir.path().join("paste_single_ball/summary.csv"));
    assert_eq!(rows.len(), 18);
    for (r, line) in rows.iter().zip(text.lines().skip(2)) {
        let cells: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(cells[0], r["sphere_id"], "{line}");
        let mm = r["settling_distance_m"].parse::<f64>().unwrap() * 1e3;
        assert!(shows(cells[at], mm), "{line} lacks {mm}");
    }
    assert!(!text.contains("0.00000e0"), "{text}");
    assert_one_number_format(&text);
}

/// Valentik's suspension 1 printed `0.1000`, `1.54686e-1` and `1.24795e0` in one table: now every
/// number has the same significant digits and no `e0`.
#[test]
fn one_table_one_number_format() {
    let dir = tmp();
    let text = run("scenarios/valentik_susp1.toml", dir.path(), &[]);
    assert!(
        text.contains(" 0.1547 ") && text.contains(" 1.248 "),
        "{text}"
    );
    assert_one_number_format(&text);
}

/// A 10 mm steel ball under Stokes drag in water: its force balance is 371 m/s at Re ≈ 3.7e6;
/// the run warns, names the Reynolds number and suggests Dallavalle's law.
#[test]
fn stokes_drag_far_outside_its_range_warns() {
    let dir = tmp();
    let text = run(
        "scenarios/stokes_single.toml",
        dir.path(),
        &[
            "spheres[0].diameter_m=0.01",
            "spheres[0].density_kg_m3=7800",
        ],
    );
    let w = toml_warnings(&dir.path().join("stokes_single"));
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].contains("Stokes drag used above its range Re < 0.5"),
        "{}",
        w[0]
    );
    assert!(w[0].contains("largest Re = 3.706e6"), "{}", w[0]);
    assert!(w[0].contains("drag.law = \"dallavalle\""), "{}", w[0]);
    assert!(text.contains(&format!("  warning: {}", w[0])), "{text}");
}
