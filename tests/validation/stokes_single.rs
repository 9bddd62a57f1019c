//! Validation case: f-EDEM §3, a 0.1 mm sphere settling from rest in water (Table 1), against
//! the analytic solution of eq. 20 (v = v_t (1 − e^{−t/τ}), eq. 21 for v_t).
//! Scenario: `scenarios/stokes_single.toml`.

use crate::common::{settle, tmp};

const SCENARIO: &str = "scenarios/stokes_single.toml";

// The scene's runner against the analytic solution (integrators, probes, Rayleigh time,
// overrides): `scenes::free_settling::tests::stokes_single` (unit tests).

#[test]
fn cli_unstable_run_exits_3_and_writes_nothing() {
    let dir = tmp();
    let out = settle()
        .args([
            "run",
            SCENARIO,
            "--dt",
            "5e-3",
            "--set",
            "time.integrator=explicit",
            "--out",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(3));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("fedem-table1") && err.contains("t = ") && err.contains("3.000e-3"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "something was written"
    );
}

#[test]
fn run_writes_summary_timeseries_probes_and_run_toml() {
    let dir = tmp();
    let d = settle::load(SCENARIO)
        .unwrap()
        .run()
        .unwrap()
        .write(dir.path())
        .unwrap();
    assert_eq!(d, dir.path().join("stokes_single"));
    let ts = std::fs::read_to_string(d.join("timeseries.csv")).unwrap();
    let header = ts.lines().next().unwrap();
    for col in [
        "time_s",
        "velocity_m_s",
        "velocity_analytic_m_s",
        "depth_m",
        "depth_analytic_m",
    ] {
        assert!(header.split(',').any(|c| c == col), "missing {col}");
    }
    // Every recorded depth matches the analytic depth to 1e-9 m.
    for line in ts.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (x, xa): (f64, f64) = (f[2].parse().unwrap(), f[5].parse().unwrap());
        assert!((x - xa).abs() < 1e-9, "{line}");
    }
    let summary = std::fs::read_to_string(d.join("summary.csv")).unwrap();
    assert!(summary.starts_with("sphere_id,suspension,diameter_m,density_kg_m3,v_measured_m_s,v_simulated_m_s,v_force_balance_m_s"));
    let run: toml::Table = std::fs::read_to_string(d.join("run.toml"))
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(run["run"]["steps"].as_integer(), Some(3000));
    assert_eq!(run["scenario"]["time"]["dt_s"].as_float(), Some(1e-5));
    assert!(d.join("probes.csv").exists());
}
