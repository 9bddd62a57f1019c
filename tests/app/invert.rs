//! `settle invert` (`src/invert/`): the worked example of docs/commands/invert.md, its output
//! files and chart, and every bad input is one error naming the file or the option, exit 2,
//! nothing written.

use crate::common::chart::assert_readable_chart;
use crate::common::{assert_exit, num, read_csv_records, settle, settle_command, tmp, tree};
use std::path::Path;

const CLAY: &str = "data/lab/envalysis_clayloam_d422.csv";

fn invert(files: &[&str], out: &Path, args: &[&str]) -> std::process::Output {
    settle_command("invert", files, out, args)
}

/// docs/commands/invert.md's worked example: envalysis' clay loam (data/lab/README.md) inverted
/// with the defaults. The figures printed on the page are checked here.
#[test]
fn the_worked_example_inverts_the_clay_loam() {
    let out = tmp();
    let o = invert(&[CLAY], out.path(), &[]);
    assert_exit(&o, 0);
    let text = String::from_utf8_lossy(&o.stdout);
    let dir = out.path().join("envalysis_clayloam_d422_inverted");
    for f in [
        "inverted.csv",
        "misfit.csv",
        "standard.csv",
        "inverted.svg",
        "invert.toml",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing; stdout:\n{text}");
    }
    let curve = read_csv_records(&dir.join("inverted.csv"));
    assert_eq!(curve.len(), 15, "14 bins have 15 edges");
    let mut last = -1.0;
    for r in &curve {
        let (f, lo, hi) = (
            num(r, "percent_finer"),
            num(r, "percent_finer_p5"),
            num(r, "percent_finer_p95"),
        );
        // Monotone, within 0–100 % by construction; the band is ordered.
        assert!((0.0..=100.0).contains(&f) && f >= last - 1e-9, "{r:?}");
        assert!(lo <= hi, "{r:?}");
        last = f;
    }
    // The page's figures (docs/commands/invert.md): 41 % finer than 10.95 µm, 75 % than
    // 55.08 µm, to the 2 significant digits the page quotes.
    let at = |d_um: f64| {
        curve
            .iter()
            .find(|r| (num(r, "diameter_m") * 1e6 - d_um).abs() < 0.01)
            .map(|r| num(r, "percent_finer"))
            .unwrap_or_else(|| panic!("no edge at {d_um} µm"))
    };
    assert!((at(10.95) - 41.0).abs() < 0.5, "{}", at(10.95));
    assert!((at(55.08) - 75.0).abs() < 0.5, "{}", at(55.08));
    // Every reading is explained within its uncertainty (σ = 0.25 g/L): |residual| < 2σ.
    let misfit = read_csv_records(&dir.join("misfit.csv"));
    assert_eq!(misfit.len(), 7);
    for r in &misfit {
        assert!(num(r, "residual").abs() < 2.0 * num(r, "sigma"), "{r:?}");
        assert_eq!(r["instrument"], "hydrometer");
    }
    // The standard reduction beside it is `settle reduce`'s (74 % at 50.9 µm, first reading).
    let std = read_csv_records(&dir.join("standard.csv"));
    assert!((num(&std[0], "percent_finer") - 74.0).abs() < 1e-9);
    assert_readable_chart(
        &dir.join("inverted.svg"),
        "recovered grain-size curve",
        &["diameter", "percent finer"],
    );
    let toml = std::fs::read_to_string(dir.join("invert.toml")).unwrap();
    for k in [
        "lambda = ",
        "chi2 = ",
        "iterations = ",
        "wall_time_s = ",
        "settle_version",
    ] {
        assert!(toml.contains(k), "{k} missing in invert.toml:\n{toml}");
    }
    assert!(text.contains("d_um") && text.contains("finer_%"), "{text}");
}

/// The same seed gives the same band; another seed another one.
#[test]
fn the_band_is_reproducible_by_its_seed() {
    let out = tmp();
    let band = |seed: &str, name: &str| {
        let o = invert(
            &[CLAY],
            &out.path().join(name),
            &["--seed", seed, "--repeats", "30"],
        );
        assert_exit(&o, 0);
        std::fs::read_to_string(
            out.path()
                .join(name)
                .join("envalysis_clayloam_d422_inverted/inverted.csv"),
        )
        .unwrap()
    };
    assert_eq!(band("7", "a"), band("7", "b"));
    assert_ne!(band("7", "a"), band("8", "c"));
}

/// Bad input: one line naming the file or option, exit 2, nothing written.
#[test]
fn bad_input_is_one_line_exit_2_and_nothing_written() {
    let dir = tmp();
    let bad_file = dir.path().join("bad.csv");
    std::fs::write(
        &bad_file,
        "# standard = d422\n# hydrometer = 152H\n# dry_mass_g = 50\n# specific_gravity = 2.65\n\
         # meniscus_correction = 0\n# blank_reading = 2\ntime_min,reading,temperature_c\n\
         2,33,23\n5,x,23\n15,23,23\n",
    )
    .unwrap();
    let missing = dir.path().join("none.csv");
    let cases: Vec<(Vec<&str>, Vec<&str>, &str)> = vec![
        (vec![CLAY], vec!["--model", "hindered"], "--model"),
        (vec![CLAY], vec!["--diameters-um", "80:2"], "reversed"),
        (vec![CLAY], vec!["--diameters-um", "2-80"], "LO:HI"),
        (vec![CLAY], vec!["--lambda", "-1"], "--lambda"),
        (vec![CLAY], vec!["--bins", "40"], "--bins"),
        (vec![CLAY], vec!["--resolution", "0.5,0.1"], "one per file"),
        (
            vec!["data/lab/soiltestr_protocol8_d7928.csv"],
            vec![],
            "at least 3",
        ),
        (
            vec![bad_file.to_str().unwrap()],
            vec![],
            "row 2 (line 9), column 2 `reading`",
        ),
        (
            vec![CLAY, missing.to_str().unwrap()],
            vec![],
            "none.csv: no such readings file",
        ),
    ];
    for (files, args, needle) in cases {
        let out = dir.path().join("out");
        let o = invert(&files, &out, &args);
        assert_exit(&o, 2);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{files:?} {args:?}: {err}");
        assert!(
            err.contains(needle),
            "{files:?} {args:?}: `{needle}` not in {err}"
        );
        assert!(
            !out.exists() || tree(&out).is_empty(),
            "{args:?} wrote {:?}",
            tree(&out)
        );
    }
    // No readings file at all: clap's usage error, exit 2.
    assert_exit(&settle().arg("invert").output().unwrap(), 2);
}

/// `--bounds` (docs/commands/invert.md, Strict bounds): sample 2 simulated with hindered settling
/// (data/invert/sample2_full, N = 100 000), its buoyancy sphere and pipette inverted together with
/// the full model. At every edge the strict bounds contain the recovered curve and the input
/// curve (0.5 point for the input's interpolation between its tabulated diameters), and between
/// the 0.5 and 1 min readings (62–70 µm), where no reading sees the steep part of the curve,
/// they span more than 50 points: the readings alone do not determine it.
#[test]
fn bounds_contain_the_input_and_show_what_the_readings_leave_open() {
    let out = tmp();
    let dir = Path::new("data/invert/sample2_full");
    let files = [
        dir.join("readings_sphere.csv"),
        dir.join("readings_pipette.csv"),
    ];
    let files: Vec<&str> = files.iter().map(|f| f.to_str().unwrap()).collect();
    let args = [
        "--model",
        "full",
        "--resolution",
        "0.01,0.03",
        "--bounds",
        "--repeats",
        "0",
    ];
    let o = invert(&files, out.path(), &args);
    assert_exit(&o, 0);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("min_%") && stdout.contains("max_%"),
        "{stdout}"
    );
    let rows = read_csv_records(&out.path().join("readings_sphere_inverted/inverted.csv"));
    let input: Vec<(f64, f64)> = read_csv_records(&dir.join("granulometry.csv"))
        .iter()
        .filter(|r| r["instrument"] == "input")
        .map(|r| (num(r, "diameter_m"), num(r, "percent_finer")))
        .collect();
    let at = |d: f64| {
        let k = input.partition_point(|p| p.0 < d).clamp(1, input.len() - 1);
        let ((d0, f0), (d1, f1)) = (input[k - 1], input[k]);
        f0 + (f1 - f0) * (d.ln() - d0.ln()) / (d1.ln() - d0.ln())
    };
    let mut widest_between = 0.0f64;
    for r in &rows {
        let (d, f) = (num(r, "diameter_m"), num(r, "percent_finer"));
        let (lo, hi) = (num(r, "percent_finer_min"), num(r, "percent_finer_max"));
        assert!(
            lo - 1e-6 <= f && f <= hi + 1e-6,
            "d = {d}: {f} not in [{lo}, {hi}]"
        );
        let truth = at(d).clamp(0.0, 100.0);
        assert!(
            lo - 0.5 <= truth && truth <= hi + 0.5,
            "d = {} µm: input {truth} not in [{lo}, {hi}]",
            d * 1e6
        );
        if (60e-6..72e-6).contains(&d) {
            widest_between = widest_between.max(hi - lo);
        }
    }
    assert!(widest_between > 50.0, "widest {widest_between}");
}
