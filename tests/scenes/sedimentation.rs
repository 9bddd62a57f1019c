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

/// Issue 28, item 3: `sample.particles = "real"` simulates every real grain of the modelled
/// wedges at weight 1 (here 1e-6 kg of sample 5: 27 000 grains): the summary counts as many
/// grains as real ones and every weight is 1; `run.toml` records the word, and a rerun from it
/// writes the same readings. A word other than `real` and a real count beyond any machine's
/// memory are refused naming the key (the second with the memory estimate).
#[test]
fn real_particles_simulate_every_grain_at_weight_one() {
    use crate::common::{assert_exit, read_csv_records};
    let dir = tmp();
    let sets = [
        "sample.particles=real",
        "sample.mass_kg=1e-6",
        "time.end_s=600",
        "sample.contacts=false",
        "sample.lubrication=false",
    ];
    let mut cmd = settle();
    cmd.args(["run", "scenarios/sedimentation_sample5.toml", "-q", "--out"])
        .arg(dir.path().join("a"));
    for s in sets {
        cmd.args(["--set", s]);
    }
    assert_exit(&cmd.output().unwrap(), 0);
    let run = dir.path().join("a/sedimentation_sample5");
    let summary: std::collections::HashMap<String, String> =
        read_csv_records(&run.join("summary.csv"))
            .into_iter()
            .map(|r| (r["quantity"].clone(), r["value"].clone()))
            .collect();
    let n: f64 = summary["representative_grains"].parse().unwrap();
    assert!(n > 10_000.0, "{n} grains");
    assert_eq!(
        summary["real_grains_modelled"],
        summary["representative_grains"]
    );
    assert_eq!(summary["weight_min"].parse::<f64>().unwrap(), 1.0);
    assert_eq!(summary["weight_max"].parse::<f64>().unwrap(), 1.0);
    let record = std::fs::read_to_string(run.join("run.toml")).unwrap();
    assert!(record.contains("particles = \"real\""), "{record}");
    let o = settle()
        .arg("run")
        .arg(run.join("run.toml"))
        .args(["-q", "--out"])
        .arg(dir.path().join("b"))
        .output()
        .unwrap();
    assert_exit(&o, 0);
    for f in ["readings.csv", "readings_pipette.csv", "summary.csv"] {
        let a = std::fs::read(run.join(f)).unwrap();
        let b = std::fs::read(dir.path().join("b/sedimentation_sample5").join(f)).unwrap();
        assert!(a == b, "{f} differs after a rerun from run.toml");
    }
    for (set, words) in [
        (
            "sample.particles=many",
            &["sample.particles", "\"real\""][..],
        ),
        (
            "sample.mass_kg=1",
            &[
                "sample.particles",
                "GB of memory",
                "sample.snapshot_times_s",
            ][..],
        ),
    ] {
        let o = settle()
            .args(["run", "scenarios/sedimentation_sample2.toml", "--set"])
            .arg(if set.starts_with("sample.mass") {
                "sample.particles=real"
            } else {
                set
            })
            .args(["--set", set, "--out"])
            .arg(dir.path().join("c"))
            .output()
            .unwrap();
        assert_exit(&o, 2);
        let err = String::from_utf8_lossy(&o.stderr);
        for w in words {
            assert!(err.contains(w), "{set}: {err}");
        }
        assert!(!dir.path().join("c").exists(), "{set}: wrote a folder");
    }
}
