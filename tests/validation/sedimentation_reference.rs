//! The full-physics cylinder as regression data (issue 17): samples 2 and 4 of seed 000, full
//! physics (Dallavalle drag, Di Felice hindered settling, deposition), N = 10 000 representative
//! grains, contacts (and with them lubrication) on and off. Each instrument's largest and mean error
//! against the input curve and the contacts' effect (on − off) must stay within 3σ of the
//! stored figures (`data/sedimentation_reference_metrics.toml`, written by
//! `scripts/make_sedimentation_reference.sh`), σ the mean counting noise of the instrument's
//! readings at this N: a change that moves them further changed the physics, not the noise.

use crate::common::{assert_exit, read_csv_records, settle, tmp};
use std::collections::HashMap;

/// Figures of one instrument: (max |error|, mean |error|, σ), points.
type Figures = (f64, f64, f64);

/// The stored figures of sample `k`, contacts `on`/`off`, per instrument.
fn stored(k: u32, contacts: &str) -> HashMap<String, Figures> {
    let text = std::fs::read_to_string("data/sedimentation_reference_metrics.toml").unwrap();
    let table: toml::Table = text.parse().unwrap();
    let case = table[&format!("sample{k}")][&format!("contacts_{contacts}")]
        .as_table()
        .unwrap();
    case.iter()
        .map(|(name, v)| {
            let f = |key: &str| v[key].as_float().unwrap();
            (
                name.clone(),
                (
                    f("max_abs_error_percent"),
                    f("mean_abs_error_percent"),
                    f("mean_sd_percent"),
                ),
            )
        })
        .collect()
}

/// Runs sample `k` at N = 10 000 with contacts `on`/`off`; its figures per instrument.
fn simulated(k: u32, contacts: &str) -> HashMap<String, Figures> {
    let out = tmp();
    let mut cmd = settle();
    cmd.args(["run", &format!("scenarios/sedimentation_sample{k}.toml")])
        .args(["--set", "sample.particles=10000", "-q"]);
    let on = if contacts == "on" { "true" } else { "false" };
    cmd.args(["--set", &format!("sample.contacts={on}")]);
    let o = cmd
        .arg("--out")
        .arg(out.path())
        .output()
        .expect("spawn settle");
    assert_exit(&o, 0);
    let path = out
        .path()
        .join(format!("sedimentation_sample{k}/instrument_errors.csv"));
    read_csv_records(&path)
        .iter()
        .map(|r| {
            let f = |key: &str| r[key].parse::<f64>().unwrap();
            (
                r["instrument"].clone(),
                (
                    f("max_abs_error_percent"),
                    f("mean_abs_error_percent"),
                    f("mean_sd_percent"),
                ),
            )
        })
        .collect()
}

/// Checks both contact settings of sample `k` against the stored figures, and the contacts'
/// effect on each instrument's largest error.
fn check(k: u32) {
    let (on, off) = (simulated(k, "on"), simulated(k, "off"));
    let (ref_on, ref_off) = (stored(k, "on"), stored(k, "off"));
    assert_eq!(on.len(), 3, "hydrometer, buoyancy sphere, pipette");
    for (sim, refs, label) in [(&on, &ref_on, "on"), (&off, &ref_off, "off")] {
        for (name, &(max, mean, sd)) in sim {
            let (rmax, rmean, rsd) = refs[name];
            let tol = 3.0 * rsd;
            assert!(
                (max - rmax).abs() <= tol && (mean - rmean).abs() <= tol,
                "sample {k}, contacts {label}, {name}: max {max:.3} (stored {rmax:.3}), mean \
                 {mean:.3} (stored {rmean:.3}); tolerance 3σ = {tol:.3} points"
            );
            assert!((sd / rsd - 1.0).abs() < 0.1, "{name}: σ {sd} vs {rsd}");
        }
    }
    for name in on.keys() {
        let effect = on[name].0 - off[name].0;
        let stored_effect = ref_on[name].0 - ref_off[name].0;
        let tol = 3.0 * ref_on[name].2;
        assert!(
            (effect - stored_effect).abs() <= tol,
            "sample {k}, {name}: contacts move the largest error by {effect:.3} points (stored \
             {stored_effect:.3}); tolerance {tol:.3}"
        );
    }
}

#[test]
fn sample2_full_physics_figures_hold() {
    check(2);
}

#[test]
fn sample4_full_physics_figures_hold() {
    check(4);
}
