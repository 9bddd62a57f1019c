//! Regression test for issue 17 (the cylinder at ten times the grains), found when a run of
//! N = 10⁶ with contacts was started: the cost guard charged every sedimentation run 500 ns and
//! 2 600 bytes per grain, whatever its physics. It announced 10⁶ grains without contacts at
//! 1.2 h and 2.6 GB (they take 18–75 s of CPU and 187 MB since the suspended grains were packed),
//! and 10⁶ grains with contacts at the same 1.2 h, where the close pairs grow as N² and the run
//! takes 5 h or more: a run of days passed the 24-hour guard, and 3.5·10⁶ grains without
//! contacts (650 MB, a few minutes) were refused for their memory.
//!
//! The estimate now follows what `settle bench` and `settle run` measured on the 2-core machine
//! (`docs/validation/performance.md`, issue 17 stops 21–22): each bound below is a measured CPU
//! time or peak memory, and the estimate must cover it without overstating it by more than the
//! stated factor.

use crate::scenes::cost::{check, estimate, Cost};
use std::path::Path;

fn cost(sample: u32, sets: &[&str]) -> Cost {
    let path = format!("scenarios/sedimentation_sample{sample}.toml");
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let p = crate::scenes::tests::prepare(Path::new(&path), None, &sets).unwrap();
    estimate(&p)
}

/// Full physics without contacts at N = 10⁶, CPU (user + sys) of `settle run` per sample
/// (performance.md, "The suspended grains packed", N = 10⁶ every sample): 41 / 18.5 / 75 / 31 /
/// 55 s; peak RSS 186–187 MB. The estimate (one core) covers the costliest, within 5×.
#[test]
fn a_million_grains_without_contacts_are_estimated_from_their_measured_cost() {
    let measured_cpu_s = [41.0, 18.5, 75.0, 31.0, 55.0];
    let worst = measured_cpu_s.iter().copied().fold(0.0, f64::max);
    for sample in 1..=5 {
        let c = cost(sample, &["sample.particles=1000000"]);
        assert!(
            c.wall_s >= worst && c.wall_s <= 5.0 * worst,
            "sample {sample}: {} s against {worst} s measured",
            c.wall_s
        );
        assert!(
            c.memory_bytes >= 187e6 && c.memory_bytes <= 2.0 * 240e6,
            "sample {sample}: {} B against 187 MB measured",
            c.memory_bytes
        );
    }
}

/// With contacts and lubrication, CPU of `settle run` (performance.md, "The cost with contacts
/// against N", and the convergence runs of sedimentation.md): samples 4 / 2 / 5 at N = 10⁵:
/// 174.7 / 331.8 / 270.1 s; at 3·10⁵: sample 4 1 927 s, sample 2 5 016 s. The estimate covers
/// the costliest at each N, within 3×, and is at least 10× the estimate without contacts at
/// N = 10⁵ (the old guard charged both alike).
#[test]
fn contacts_are_estimated_to_grow_as_the_close_pairs() {
    let measured: [(u32, u32, f64); 5] = [
        (4, 100_000, 174.7),
        (2, 100_000, 331.8),
        (5, 100_000, 270.1),
        (4, 300_000, 1927.0),
        (2, 300_000, 5016.0),
    ];
    for &(sample, n, cpu_s) in &measured {
        let worst = measured
            .iter()
            .filter(|m| m.1 == n)
            .map(|m| m.2)
            .fold(0.0, f64::max);
        let c = cost(
            sample,
            &[&format!("sample.particles={n}"), "sample.contacts=true"],
        );
        assert!(
            c.wall_s >= worst && c.wall_s <= 3.0 * worst,
            "sample {sample}, N = {n}: {} s against {cpu_s} s measured (costliest {worst} s)",
            c.wall_s
        );
    }
    let with = cost(2, &["sample.particles=100000", "sample.contacts=true"]);
    let without = cost(2, &["sample.particles=100000"]);
    assert!(with.wall_s >= 10.0 * without.wall_s, "{with:?} {without:?}");
}

/// 10⁶ grains with contacts (projected from the measured growth: 5–30 h of CPU) are over the
/// 24-hour guard: refused, naming the key that drives the cost and the ways round, and accepted
/// with --force; without contacts the same run passes.
#[test]
fn a_million_grains_with_contacts_are_refused_without_force() {
    let path = Path::new("scenarios/sedimentation_sample2.toml");
    let sets = |contacts: bool| {
        vec![
            "sample.particles=1000000".to_string(),
            format!("sample.contacts={contacts}"),
        ]
    };
    let p = crate::scenes::tests::prepare(path, None, &sets(true)).unwrap();
    let e = check(&p, false).unwrap_err().to_string();
    for w in [
        "sedimentation_sample2.toml",
        "sample.particles",
        "sample.contacts = false",
        "--force",
        "h of wall time",
    ] {
        assert!(e.contains(w), "`{w}` missing: {e}");
    }
    assert!(check(&p, true).is_ok());
    let p = crate::scenes::tests::prepare(path, None, &sets(false)).unwrap();
    assert!(check(&p, false).is_ok());
}
