//! Validation case: the sedimentation cylinder of seed 000 in its `ideal-stokes` reference
//! (scenarios/sedimentation_sample*.toml). Every grain falls at its Stokes velocity, so the solid
//! concentration at depth y and time t is c0·F(d*), d* = √(18 μ y / ((ρ_p − ρ_f) g t)), with F the
//! mass fraction finer than d* (seed eq. 16 and the ASTM D422 analysis). Tolerance: 4 standard
//! deviations of the representative-grain count in the band (σ/c = 1/√n), plus one size class.
//!
//! The cylinder's own tests are unit tests (`src/scenes/sedimentation/tests/`); here the binary
//! refuses an explicit blow-up.

use crate::common::{number_after, settle, tmp};

/// Regression: the explicit integrator at the cylinder's steps (1–10 s, against a response time
/// of µs for a 5 µm grain) sent every grain through the floor in the first step; the floor
/// absorbed them into the bed and the run "succeeded" with every instrument 85–100 % off. The run
/// must stop instead, naming the grain, the time, the speed against its physical bound (twice the
/// largest grain's Stokes terminal speed) and the explicit scheme's stable dt (2τ = ρ d²/(9μ)
/// for that grain, to the 4 digits printed), and write nothing.
#[test]
fn an_explicit_blow_up_stops_the_run_instead_of_filling_the_bed() {
    let dir = tmp();
    let out = settle()
        .args([
            "run",
            "scenarios/sedimentation_sample5.toml",
            "--set",
            "physics=ideal-stokes",
            "--set",
            "time.integrator=explicit",
            "--set",
            "sample.particles=1000",
            "--quiet",
            "--out",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(3));
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("grain ") && e.contains("speed (bound"), "{e}");
    assert!(e.contains("step 1)"), "{e}");
    // The grain's diameter and the stable dt it prints: 2τ = ρ_p d²/(9 μ).
    let (d, stable) = (number_after(&e, "(d = "), number_after(&e, "use dt < "));
    let two_tau = 2500.0 * d * d / (9.0 * 1e-3);
    assert!(
        (stable / two_tau - 1.0).abs() < 1e-3,
        "{stable} vs 2τ = {two_tau}"
    ); // 4 digits printed
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "nothing written"
    );
}
