//! Validation case of issue 16: transient forces (added mass, Basset history force) on f-EDEM's
//! sphere in water (`scenarios/stokes_single.toml` with `[transient]` set by `--set`), against
//! the Boussinesq–Basset closed form ([`crate::fluid::transient::BassetProblem`]), which is
//! itself checked here against an independent quadrature of the integral equation.

use super::{prepare, scene};
use crate::dynamics::Integrator;
use crate::fluid::transient::BassetProblem;
use crate::scenes::free_settling::{run, RunOptions, SphereResult};
use std::f64::consts::PI;
use std::path::Path;

const SCENARIO: &str = "scenarios/stokes_single.toml";
const HISTORY: [&str; 2] = ["transient.added_mass=true", "transient.history=basset"];

fn run_with(dt: f64, overrides: &[&str]) -> SphereResult {
    let ov: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let p = prepare(Path::new(SCENARIO), Some(dt), &ov).expect("scenario loads");
    let opts = RunOptions {
        dt_s: dt,
        integrator: Integrator::Exponential,
        timeseries: false,
    };
    run(scene(&p), &p.spheres, opts).expect("stable").remove(0)
}

/// v′ = A − B v − C ∫₀ᵗ v′(τ)(t − τ)^{−1/2} dτ, v(0) = 0, solved on a grid uniform in σ = √t
/// (v is smooth in √t): v piecewise linear in σ, so the history integral over each cell is
/// exact, ∫ dσ/√(t − σ²) = arcsin(σ/√t); the ODE dv/dσ = 2σ(A − B v − C H) by the trapezoidal
/// rule. Returns (t_i, v_i). O(n²); independent of the Laplace-transform closed form.
fn quadrature(p: &BassetProblem, t_end: f64, n: usize) -> Vec<(f64, f64)> {
    let (a, b, c) = (p.a_m_s2, p.b_per_s, p.c_per_sqrt_s);
    let ds = t_end.sqrt() / n as f64;
    let sig: Vec<f64> = (0..=n).map(|i| i as f64 * ds).collect();
    let mut v = vec![0.0; n + 1];
    let mut h_prev = 0.0; // H at σ_{i−1}
    for i in 1..=n {
        let si = sig[i];
        let mut h_old = 0.0;
        for j in 1..i {
            let slope = (v[j] - v[j - 1]) / ds;
            h_old += slope * ((sig[j] / si).asin() - (sig[j - 1] / si).asin());
        }
        let ai = PI / 2.0 - (sig[i - 1] / si).asin();
        let r_prev = ds * sig[i - 1] * (a - b * v[i - 1] - c * h_prev);
        v[i] = (v[i - 1] * (1.0 + si * c * ai) + ds * si * (a - c * h_old) + r_prev)
            / (1.0 + ds * si * b + si * c * ai);
        h_prev = h_old + (v[i] - v[i - 1]) / ds * ai;
    }
    sig.iter().map(|s| s * s).zip(v).collect()
}

#[test]
fn the_closed_form_agrees_with_an_independent_quadrature() {
    let p = BassetProblem::sphere(1e-4, 2700.0, 1000.0, 1e-3, 0.5, 9.81);
    let vt = p.terminal_m_s();
    let rows = quadrature(&p, 0.01, 3000);
    let worst = rows
        .iter()
        .map(|&(t, v)| (v - p.velocity_m_s(t)).abs() / vt)
        .fold(0.0, f64::max);
    eprintln!("max |v_quad − v_closed|/v_t = {worst:e}");
    assert!(worst < 1e-6, "{worst:e}");
}

/// Acceptance (issue 16): the scene with added mass and the history force follows the closed
/// form within 1e-4 v_t at every step and at the probes, at every dt from 1e-5 s to 1e-2 s (the
/// run lasts 0.03 s).
#[test]
fn stokes_single_with_history_follows_the_closed_form_at_every_dt() {
    let p = BassetProblem::sphere(1e-4, 2700.0, 1000.0, 1e-3, 0.5, 9.81);
    for dt in [1e-5, 1e-4, 1e-3, 1e-2] {
        let r = run_with(dt, &HISTORY);
        let err = r.max_velocity_error_rel.expect("closed form present");
        assert!(err <= 1e-4, "dt {dt}: {err:e}");
        for &(t, v, an) in &r.probes {
            let exact = p.velocity_m_s(t);
            assert!((an.expect("analytic probe") / exact - 1.0).abs() < 1e-12);
            assert!(
                (v - exact).abs() <= 1e-4 * p.terminal_m_s(),
                "dt {dt}, t {t}"
            );
        }
    }
}

/// Added mass alone keeps the exponential form with τ = (m + m_f/2)/(3πμd): the scene's own
/// analytic column is exact, and v(1 ms) drops from 0.00451 to 0.00399 m/s.
#[test]
fn added_mass_alone_slows_the_start_only() {
    let base = run_with(1e-5, &[]);
    let am = run_with(1e-5, &["transient.added_mass=true"]);
    assert!(am.max_velocity_error_rel.unwrap() < 1e-9);
    let (v0, v1) = (base.probes[0].1, am.probes[0].1);
    let tau = |m: f64| m / (3.0 * PI * 1e-3 * 1e-4);
    let vol = PI * 1e-12 / 6.0;
    let vt = base.v_analytic_m_s.unwrap();
    let want = vt * -(-1e-3 / tau((2700.0 + 500.0) * vol)).exp_m1();
    assert!((v1 - want).abs() < 1e-12 && v1 < v0);
    assert_eq!(am.v_analytic_m_s, base.v_analytic_m_s);
}

#[test]
fn the_history_force_is_refused_in_a_bingham_fluid() {
    let set = vec!["transient.history=basset".to_string()];
    let e = prepare(Path::new("scenarios/valentik_susp1.toml"), None, &set).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("Bingham") && msg.contains("transient.history"),
        "{msg}"
    );
    // Added mass applies there.
    let set = vec!["transient.added_mass=true".to_string()];
    prepare(Path::new("scenarios/valentik_susp1.toml"), None, &set).expect("added mass loads");
}

/// Where a transient force is not available, the scenario is refused with the key and the
/// reason: the wall without a container, any transient force on the Rapier engine, the history
/// force in the paste (Bingham) or with another integrator, a coefficient out of range, a
/// Reynolds number for a kernel that has none.
#[test]
fn unsupported_combinations_are_refused() {
    let refuse = |file: &str, set: &[&str], key: &str, words: &str| {
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        let msg = prepare(Path::new(file), None, &set)
            .unwrap_err()
            .to_string();
        assert!(msg.contains(key) && msg.contains(words), "{msg}");
    };
    refuse(
        SCENARIO,
        &["transient.wall=brenner"],
        "transient.wall",
        "[container]",
    );
    refuse(
        SCENARIO,
        &["transient.added_mass=true", "engine=rapier"],
        "transient",
        "free engine",
    );
    refuse(
        "scenarios/paste_single_ball.toml",
        &["transient.history=basset"],
        "transient.history",
        "Bingham",
    );
    refuse(
        SCENARIO,
        &["transient.history=basset", "time.integrator=implicit"],
        "transient.history",
        "exponential",
    );
    refuse(
        SCENARIO,
        &["transient.added_mass_coefficient=3"],
        "transient.added_mass_coefficient",
        "2",
    );
    refuse(
        SCENARIO,
        &[
            "transient.history=basset",
            "transient.history_reynolds=current",
        ],
        "transient.history_reynolds",
        "mei-adrian",
    );
}

/// The side walls (issue 16, `transient.confinement = "haberman-sayre"`): f-EDEM's 0.1 mm
/// sphere on the axis of a 1 mm tube (λ = 0.1, Re ≈ 0.9) reaches v_t/K, K from Faxén's series
/// for a sphere on a cylinder's axis (Happel & Brenner 1965, §7-4; computed here, independently
/// of the code's Haberman–Sayre formula) within 2e-4; without the factor it reaches v_t (the
/// two differ by 21 %, so the test fails if the factor is lost or doubled). A square box is
/// refused (the factor is for a circular cylinder), and so is a sphere with d/D above 0.8.
#[test]
fn the_confinement_factor_slows_the_sphere_by_faxens_k() {
    let tube = [
        "container.height_m=0.5",
        "container.diameter_m=1e-3",
        "transient.confinement=haberman-sayre",
    ];
    let free = run_with(1e-5, &tube[..2]);
    let walled = run_with(1e-5, &tube);
    let l: f64 = 0.1;
    let k = 1.0
        / (1.0 - 2.10444 * l + 2.08877 * l.powi(3) - 0.94813 * l.powi(5) - 1.372 * l.powi(6)
            + 3.87 * l.powi(8)
            - 4.19 * l.powi(10));
    let vt = free.v_simulated_m_s;
    assert!((vt / free.v_force_balance_m_s - 1.0).abs() < 1e-6, "{vt}");
    let ratio = walled.v_simulated_m_s / (vt / k);
    assert!(
        (ratio - 1.0).abs() < 2e-4,
        "v = {} vs v_t/K = {}",
        walled.v_simulated_m_s,
        vt / k
    );
    // The error of loading the scenario with `set`.
    let refusal = |set: [&str; 3]| {
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        prepare(Path::new(SCENARIO), None, &set)
            .unwrap_err()
            .to_string()
    };
    let msg = refusal([
        "container.height_m=0.5",
        "container.width_m=1e-3",
        "transient.confinement=haberman-sayre",
    ]);
    assert!(
        msg.contains("transient.confinement") && msg.contains("container.diameter_m"),
        "{msg}"
    );
    // A sphere beyond Haberman & Sayre's range (d/D = 0.91 > 0.8) is refused with its key.
    let msg = refusal([
        "container.height_m=0.5",
        "container.diameter_m=1.1e-4",
        "transient.confinement=haberman-sayre",
    ]);
    assert!(
        msg.contains("diameter_m") && msg.contains("Haberman") && msg.contains("0.8"),
        "{msg}"
    );
}
