//! Issue 28, item 3: sample 2 of seed 000 at its real count is the reference its representative
//! grains approximate. `data/sedimentation_real_count/` holds the readings of every instrument
//! (`instruments.csv`), their errors and the record (`run.toml`) of `settle run
//! scenarios/sedimentation_sample2.toml --set sample.particles=real --set
//! 'sample.snapshot_times_s=[]' --set sample.wedge_fraction=1/1800`: every real grain of a
//! wedge a tenth of the scenario's (the same suspension: its projection thickness, and so every
//! concentration, the bed and each instrument's reading, scale with the wedge; the
//! representative runs of the two wedges agree to 7·10⁻¹⁴ relative), 9.19·10⁶ grains of
//! weight 1, full physics, no contacts, 1440 min. A run of N = 30 000 representative grains
//! must read every instrument, at every reading, within 4σ of it, σ = √(σ_N² + σ_real²) the
//! counting noise of the two runs' readings (`sd_percent`), and the RMS of z = Δ/σ over each
//! instrument's readings must be ≤ 2: at this N the representative grains' error is their
//! counting noise (docs/validation/sedimentation.md, "The real count (sample 2)"). Measured when
//! the data were made: RMS z 0.79–1.14, largest |z| 2.14 (the sphere at 30 s).

use crate::common::{assert_exit, read_csv_records, settle, tmp};
use std::collections::BTreeMap;
use std::path::Path;

/// Largest |z| of one reading.
const Z_MAX: f64 = 4.0;
/// Largest RMS of z over an instrument's readings.
const Z_RMS_MAX: f64 = 2.0;

/// The readings of `instruments.csv` at `path`: (instrument, time) → (percent finer, σ), points.
fn readings(path: &Path) -> BTreeMap<(String, String), (f64, f64)> {
    read_csv_records(path)
        .into_iter()
        .filter(|r| !r["percent_finer"].is_empty() && !r["sd_percent"].is_empty())
        .map(|r| {
            let f = |k: &str| r[k].parse::<f64>().unwrap();
            (
                (r["instrument"].clone(), r["time_s"].clone()),
                (f("percent_finer"), f("sd_percent")),
            )
        })
        .collect()
}

/// Runs sample 2 at N = `n` with the extra overrides `set`; its readings.
fn run_sample2(n: &str, set: &[&str]) -> BTreeMap<(String, String), (f64, f64)> {
    let out = tmp();
    let mut cmd = settle();
    cmd.args(["run", "scenarios/sedimentation_sample2.toml", "-q"])
        .args(["--set", &format!("sample.particles={n}")])
        .args(["--set", "sample.snapshot_times_s=[]"]);
    for s in set {
        cmd.args(["--set", s]);
    }
    let o = cmd.arg("--out").arg(out.path()).output().unwrap();
    assert_exit(&o, 0);
    readings(&out.path().join("sedimentation_sample2/instruments.csv"))
}

/// The stored run is a wedge a tenth of the scenario's: the projection thickness π B f/4 scales
/// with the wedge fraction f, and with it the modelled mass, so every concentration, the bed
/// and every reading are those of the scenario's wedge. The same representative grains in the
/// two wedges read the same, to rounding (measured: 7·10⁻¹⁴ relative; tolerance 10⁻¹⁰).
#[test]
fn a_thinner_wedge_reads_the_same_suspension() {
    let thick = run_sample2("10000", &[]);
    let thin = run_sample2("10000", &["sample.wedge_fraction=0.0005555555555555556"]);
    assert_eq!(thick.len(), thin.len());
    for (key, &(p, s)) in &thick {
        let (q, r) = thin[key];
        for (a, b, what) in [(p, q, "percent finer"), (s, r, "σ")] {
            assert!(
                (a - b).abs() <= 1e-10 * a.abs().max(1.0),
                "{key:?} {what}: {a} in the scenario's wedge, {b} in one a tenth as thick"
            );
        }
    }
}

#[test]
fn representative_grains_read_what_every_real_grain_reads() {
    read_as_the_real_count(
        Path::new("data/sedimentation_real_count"),
        &["sample.wedge_fraction=0.0005555555555555556"],
    );
}

/// The same against the full real count of stop 37: every real grain of the scenario's own
/// wedge, 9.19·10⁷ grains (`data/sedimentation_real_count/scenario_wedge/`; measured when the
/// data were made: RMS z 0.78–1.10, largest |z| 2.05, the sphere at 30 s).
#[test]
fn representative_grains_read_what_the_full_real_count_reads() {
    read_as_the_real_count(
        Path::new("data/sedimentation_real_count/scenario_wedge"),
        &[],
    );
}

/// A run of N = 30 000 representative grains (with the overrides `set`) against the stored
/// real-count run in `data`: every reading within [`Z_MAX`]σ, RMS z ≤ [`Z_RMS_MAX`] per
/// instrument.
fn read_as_the_real_count(data: &Path, set: &[&str]) {
    let record = std::fs::read_to_string(data.join("run.toml")).unwrap();
    assert!(
        record.contains("particles = \"real\""),
        "the stored run is at the real count"
    );
    let real = readings(&data.join("instruments.csv"));
    let rep = run_sample2("30000", set);
    let mut by: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for (key, (p, s)) in &rep {
        let Some(&(pr, sr)) = real.get(key) else {
            continue;
        };
        let sigma = s.hypot(sr);
        if sigma == 0.0 {
            // no grain left in either run: both read 0 % (to rounding)
            assert!(p.abs() < 1e-9 && pr.abs() < 1e-9, "{key:?}: {p} and {pr} %");
            continue;
        }
        let z = (p - pr) / sigma;
        assert!(
            z.abs() <= Z_MAX,
            "{} at {} s: {p:.3} % at N = 30 000 against {pr:.3} % at the real count, z = \
             {z:.2} (σ = {sigma:.3} points; tolerance {Z_MAX}σ)",
            key.0,
            key.1
        );
        by.entry(key.0.clone()).or_default().push(z);
    }
    assert_eq!(by.len(), 3, "hydrometer, buoyancy sphere, pipette: {by:?}");
    for (inst, zs) in by {
        let rms = (zs.iter().map(|z| z * z).sum::<f64>() / zs.len() as f64).sqrt();
        assert!(
            rms <= Z_RMS_MAX,
            "{inst}: RMS z = {rms:.2} over {} readings (tolerance {Z_RMS_MAX})",
            zs.len()
        );
    }
}
