//! Validation case: f-EDEM §3, a 0.1 mm sphere settling from rest in water (Table 1), against
//! the analytic solution of eq. 20 (v = v_t (1 − e^{−t/τ}), eq. 21 for v_t).
//! Scenario: `scenarios/stokes_single.toml`. Moved from `tests/validation/stokes_single.rs`
//! (which runs it through `settle run` and the library API): the scene's runner itself.

use super::{prepare, scene};
use crate::dynamics::Integrator;
use crate::scenes::free_settling::{run, RunOptions};
use std::path::Path;

const SCENARIO: &str = "scenarios/stokes_single.toml";

type Outcome = Result<crate::scenes::free_settling::SphereResult, crate::dynamics::Unstable>;

fn run_at(dt: f64, integrator: Integrator) -> Outcome {
    run_with(dt, integrator, &[])
}

fn run_with(dt: f64, integrator: Integrator, overrides: &[&str]) -> Outcome {
    let ov: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let p = prepare(Path::new(SCENARIO), Some(dt), &ov).expect("scenario loads");
    let opts = RunOptions {
        dt_s: dt,
        integrator,
        timeseries: false,
    };
    run(scene(&p), &p.spheres, opts).map(|mut v| v.remove(0))
}

/// Acceptance: max |v − v_analytic| / v_t < 1e-6 at every dt from 1e-8 to 1e-2 s
/// (f-EDEM needed < 1e-4 at 1e-5 s), and the end velocity equals v_t within 1e-6.
#[test]
fn exponential_integrator_matches_the_analytic_solution_at_every_dt() {
    for dt in [1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2] {
        let r = run_at(dt, Integrator::Exponential).expect("stable");
        let err = r
            .max_velocity_error_rel
            .expect("Stokes has an analytic solution");
        assert!(err < 1e-6, "dt = {dt}: max rel velocity error {err}");
        let vt = r.v_analytic_m_s.unwrap();
        assert!((r.v_simulated_m_s / vt - 1.0).abs() < 1e-6, "dt = {dt}");
        // Terminal velocity of eq. 21: d²(ρp − ρf)g/(18μ) = 9.265e-3 m/s.
        assert!((vt - 9.265e-3).abs() < 1e-9);
    }
}

#[test]
fn at_seven_response_times_per_step_the_run_is_stable_and_exact() {
    // dt = 1e-2 s ≈ 6.7 τ: three steps cover the whole run.
    let r = run_at(1e-2, Integrator::Exponential).unwrap();
    assert_eq!(r.steps, 3);
    assert!((r.v_simulated_m_s / r.v_analytic_m_s.unwrap() - 1.0).abs() < 1e-6);
    // The implicit scheme is stable there too, and ends at the terminal velocity (it needs more
    // steps: its transient decays as (1 + dt/τ)^−n).
    let r = run_with(1e-2, Integrator::Implicit, &["time.end_s=0.2"]).unwrap();
    assert!((r.v_simulated_m_s / r.v_analytic_m_s.unwrap() - 1.0).abs() < 1e-6);
}

#[test]
fn probes_match_fedem_fig5_and_fig6_analytic_values() {
    // v(1 ms) = v_t (1 − e^{−1/1.5}) = 4.5082e-3 m/s; v(10 ms) = 9.2532e-3 m/s.
    let r = run_at(1e-5, Integrator::Exponential).unwrap();
    assert_eq!(r.probes.len(), 2);
    let (t1, v1, a1) = r.probes[0];
    assert_eq!(t1, 0.001);
    assert!((v1 - 4.508190e-3).abs() < 1e-9 && (v1 - a1.unwrap()).abs() < 1e-12);
    let (_, v2, _) = r.probes[1];
    assert!((v2 - 9.253209e-3).abs() < 1e-9);
}

#[test]
fn rayleigh_time_is_fedem_value() {
    let r = run_at(1e-5, Integrator::Exponential).unwrap();
    let tr = r.rayleigh_time_s.unwrap();
    assert!((tr - 8.12e-8).abs() < 0.01e-8, "{tr}");
    assert!((r.response_time_s - 1.5e-3).abs() < 1e-15);
}

/// The explicit scheme diverges for dt > 2τ = 3 ms and the run stops, naming the body, the time
/// and the largest stable dt; below 2τ it converges.
#[test]
fn explicit_integrator_fails_beyond_two_response_times() {
    let ok =
        run_with(2.5e-3, Integrator::Explicit, &["time.end_s=0.2"]).expect("dt < 2τ is stable");
    assert!((ok.v_simulated_m_s / ok.v_analytic_m_s.unwrap() - 1.0).abs() < 1e-6);
    let e = run_at(3.2e-3, Integrator::Explicit).expect_err("dt > 2τ diverges");
    assert_eq!(e.body, "fedem-table1");
    assert!((e.stable_dt_s - 3e-3).abs() < 1e-12);
    assert!(e.time_s > 0.0 && e.time_s <= 0.03);
    let msg = e.to_string();
    assert!(
        msg.contains("fedem-table1") && msg.contains("largest stable dt"),
        "{msg}"
    );
}

#[test]
fn explicit_at_fedem_step_is_within_their_tolerance() {
    // f-EDEM's own criterion at dt = 1e-5 s: error < 1e-4 (first-order scheme: ≈ dt/(2τ)).
    let r = run_at(1e-5, Integrator::Explicit).unwrap();
    assert!(r.max_velocity_error_rel.unwrap() < 1e-2);
}

#[test]
fn set_overrides_change_the_physics() {
    // Doubling the viscosity halves the terminal velocity (eq. 21).
    let p = prepare(
        Path::new(SCENARIO),
        None,
        &["fluid.viscosity_pa_s=0.002".into()],
    )
    .unwrap();
    let opts = RunOptions {
        dt_s: 1e-4,
        integrator: Integrator::Exponential,
        timeseries: false,
    };
    let r = run(scene(&p), &p.spheres, opts).unwrap().remove(0);
    assert!((r.v_analytic_m_s.unwrap() - 9.265e-3 / 2.0).abs() < 1e-12);
}
