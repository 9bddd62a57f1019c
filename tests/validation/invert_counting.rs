//! Inverting several instruments together (issue 26, item 8): a cylinder run's readings files
//! carry each reading's counting σ (`counting_sigma`, the noise of the representative grains,
//! `settle::instruments::counting`), which `settle invert` adds to the instruments' resolution.
//! Samples 2 and 4 of seed 000, full physics with contacts off, N = 10 000 grains (a few
//! seconds each); the hydrometer (D422), pipette and sphere files inverted together with
//! `--model full --bounds`.
//!
//! Measured here (N = 10 000): sample 2 χ² = 19.2, sample 4 χ² = 19.3 for 27 readings (without
//! the counting σ, sample 2 gave χ² = 216 and empty bounds: the pipette's and sphere's
//! resolution, 1 mg and 10 mg, is far below one grain's noise). Both input curves lie within
//! the strict bounds (`--bounds`, confidence 0.95: χ² ≤ χ²₂₇(0.95) = 40.11) at every resolved
//! diameter. Before issue 26's fix of the bounds (bar m, and a Lagrangian multiplier so large
//! that the solver returned rounding noise) sample 4's upper bounds at 68.5 and 78.7 µm were
//! 99.0 % and 99.96 %, below the input's 99.9 % and 100 % and the recovered curve's 100 %.

use crate::common::{assert_exit, num, read_csv_records, settle, tmp};

/// F(d) of a curve given at increasing diameters (m, %), linear in log d, clamped.
fn at(curve: &[(f64, f64)], d: f64) -> f64 {
    if d <= curve[0].0 {
        return curve[0].1;
    }
    for w in curve.windows(2) {
        let ((d0, f0), (d1, f1)) = (w[0], w[1]);
        if d <= d1 {
            let x = (d.ln() - d0.ln()) / (d1.ln() - d0.ln());
            return f0 + x * (f1 - f0);
        }
    }
    curve[curve.len() - 1].1
}

/// Runs sample `k` at N = 10 000 with contacts off into a temporary folder; the folder and the
/// run's output folder in it.
fn run_sample(k: u32) -> (tempfile::TempDir, std::path::PathBuf) {
    let out = tmp();
    let o = settle()
        .args(["run", &format!("scenarios/sedimentation_sample{k}.toml")])
        .args(["--set", "sample.particles=10000"])
        .args([
            "--set",
            "sample.contacts=false",
            "--set",
            "sample.lubrication=false",
        ])
        .args(["-q", "--out"])
        .arg(out.path())
        .output()
        .expect("spawn settle");
    assert_exit(&o, 0);
    let run = out.path().join(format!("sedimentation_sample{k}"));
    (out, run)
}

/// Runs sample `k` (N = 10 000, contacts off) and inverts its three instruments' readings
/// together; checks χ² ≤ m, strict bounds at every resolved diameter, and the recovered and the
/// input curve within them. Returns χ² and the number of readings.
fn three_instruments(k: u32) -> (f64, usize) {
    let (out, run) = run_sample(k);
    let files = [
        "readings.csv",
        "readings_pipette.csv",
        "readings_sphere.csv",
    ];
    for f in files {
        let text = std::fs::read_to_string(run.join(f)).unwrap();
        assert!(
            text.lines().any(|l| l.ends_with(",counting_sigma")),
            "{f}: no counting_sigma column"
        );
    }
    let inv = out.path().join("inv");
    let o = settle()
        .arg("invert")
        .args(files.map(|f| run.join(f)))
        .args(["--model", "full", "--bounds", "--repeats", "0", "--out"])
        .arg(&inv)
        .output()
        .expect("spawn settle");
    assert_exit(&o, 0);
    let dir = inv.join("readings_inverted");
    let toml = std::fs::read_to_string(dir.join("invert.toml")).unwrap();
    let value = |key: &str| -> f64 {
        let line = toml
            .lines()
            .find(|l| l.starts_with(&format!("{key} = ")))
            .unwrap_or_else(|| panic!("invert.toml has no {key}"));
        line.split(" = ").nth(1).unwrap().parse().unwrap()
    };
    let (chi2, m) = (value("chi2"), value("readings") as usize);
    assert_eq!(m, 27, "sample {k}: 7 + 10 + 10 readings");
    assert!(chi2 <= m as f64, "sample {k}: χ² = {chi2} > {m} readings");
    let gran = read_csv_records(&run.join("granulometry.csv"));
    let input: Vec<(f64, f64)> = gran
        .iter()
        .filter(|r| r["instrument"] == "input")
        .map(|r| (num(r, "diameter_m"), num(r, "percent_finer")))
        .collect();
    let curve = read_csv_records(&dir.join("inverted.csv"));
    assert!(curve.len() >= 10, "sample {k}: {} diameters", curve.len());
    let mut outside = Vec::new();
    for r in &curve {
        let d = num(r, "diameter_m");
        assert!(
            !r["percent_finer_min"].is_empty() && !r["percent_finer_max"].is_empty(),
            "sample {k}: no strict bounds at {} µm",
            d * 1e6
        );
        let (lo, hi) = (num(r, "percent_finer_min"), num(r, "percent_finer_max"));
        // The recovered curve explains the readings (χ² ≤ m), so its own bounds hold it.
        let recovered = num(r, "percent_finer");
        assert!(
            (lo - 1e-6..=hi + 1e-6).contains(&recovered),
            "sample {k}, {} µm: recovered {recovered} % outside its bounds {lo}–{hi} %",
            d * 1e6
        );
        let f = at(&input, d);
        if !(lo - 1e-6..=hi + 1e-6).contains(&f) {
            outside.push(format!(
                "{:.1} µm: input {f:.2} %, bounds {lo:.2}–{hi:.2} %",
                d * 1e6
            ));
        }
    }
    assert!(
        outside.is_empty(),
        "sample {k}: input curve outside the strict bounds at {outside:?}"
    );
    eprintln!("sample {k}: χ² = {chi2} for {m} readings");
    (chi2, m)
}

#[test]
fn three_instruments_together_sample2() {
    three_instruments(2);
}

#[test]
fn three_instruments_together_sample4() {
    three_instruments(4);
}

/// The readings files' counting σ is what invert uses: the same files without the column
/// (a laboratory's readings, resolution only) give χ² far above m for sample 2, and the
/// warning names the files and readings that the model misses and what to change.
#[test]
fn without_counting_sigma_the_misfit_is_named() {
    let (out, run) = run_sample(2);
    let lab = out.path().join("lab");
    std::fs::create_dir(&lab).unwrap();
    for f in [
        "readings.csv",
        "readings_pipette.csv",
        "readings_sphere.csv",
    ] {
        let text = std::fs::read_to_string(run.join(f)).unwrap();
        let stripped: String = text
            .lines()
            .map(|l| match l.rsplit_once(',') {
                Some((keep, _)) if !l.starts_with('#') => format!("{keep}\n"),
                _ => format!("{l}\n"),
            })
            .collect();
        std::fs::write(lab.join(f), stripped).unwrap();
    }
    let o = settle()
        .arg("invert")
        .args(
            [
                "readings.csv",
                "readings_pipette.csv",
                "readings_sphere.csv",
            ]
            .map(|f| lab.join(f)),
        )
        .args(["--model", "full", "--repeats", "0", "--out"])
        .arg(out.path().join("inv"))
        .output()
        .expect("spawn settle");
    assert_exit(&o, 0);
    // The warnings are printed with the summary, on the standard output.
    let err = String::from_utf8_lossy(&o.stdout);
    assert!(err.contains("does not explain the readings"), "{err}");
    assert!(
        err.contains("readings_pipette.csv: χ²") || err.contains("readings_sphere.csv: χ²"),
        "the warning names no file: {err}"
    );
    assert!(
        err.contains(" min ("),
        "the warning names no reading: {err}"
    );
    assert!(err.contains("check the file's figures"), "{err}");
}
