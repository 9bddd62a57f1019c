//! Issue 13, "Parameter sweeps on any key" (item 6 of "What to build"): as found, only dt could
//! be swept; finding the yield stress that stops a ball took a shell loop with one `--out` per
//! value. Now `settle sweep S.toml --vary KEY=LO:HI:N` runs the grid into one table, the varied
//! key as its first column.

use crate::common::{assert_exit, col, read_csv, settle, tmp};

#[test]
fn the_yield_stress_is_swept_in_one_command() {
    let dir = tmp();
    let o = settle()
        .args([
            "sweep",
            "scenarios/paste_single_ball.toml",
            "--set",
            "release.fall_heights_m=[0.3]",
            "--set",
            "time.dt_s=1e-4",
            "--vary",
            "fluid.yield_stress_pa=100:300:3",
            "-q",
            "--out",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    assert_exit(&o, 0);
    let (h, rows) = read_csv(&dir.path().join("paste_single_ball_vary/vary.csv"));
    assert_eq!(h[0], "fluid.yield_stress_pa");
    assert!(h.iter().any(|c| c == "settling_distance_m"), "{h:?}");
    let stresses: Vec<f64> = rows
        .iter()
        .map(|r| col(&h, r, "fluid.yield_stress_pa"))
        .collect();
    assert!(stresses.contains(&100.0) && stresses.contains(&200.0) && stresses.contains(&300.0));
    // A higher yield stress stops each ball sooner.
    let body = &rows[0][1];
    let depth = |tau: f64| {
        let r = rows
            .iter()
            .find(|r| &r[1] == body && col(&h, r, "fluid.yield_stress_pa") == tau)
            .unwrap();
        col(&h, r, "settling_distance_m")
    };
    assert!(
        depth(100.0) > depth(300.0),
        "{} vs {}",
        depth(100.0),
        depth(300.0)
    );
}
