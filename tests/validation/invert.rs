//! Validation of `settle invert` (issue 14): the round trip through the simulation under ideal
//! Stokes settling, and the Monte Carlo band under rounded, noisy readings.

use crate::common::{assert_exit, num, read_csv_records, settle, tmp};
use settle::instruments::ideal_field;
use settle::invert::solve::LambdaRule;
use settle::invert::{bins_for, fit, read_test, Model};
use settle::sample::Distribution;
use std::path::Path;

/// F(d) of a curve given at increasing diameters (m, %), linear in log d between them, clamped.
fn at(curve: &[(f64, f64)], d: f64) -> f64 {
    if d <= curve[0].0 {
        return curve[0].1;
    }
    for p in curve.windows(2) {
        let ((a, fa), (b, fb)) = (p[0], p[1]);
        if d <= b {
            return fa + (fb - fa) * (d / a).ln() / (b / a).ln();
        }
    }
    curve[curve.len() - 1].1
}

/// The (diameter_m, percent_finer) pairs of CSV records: every row, or those of `instrument`.
fn curve_of(
    rows: &[std::collections::HashMap<String, String>],
    instrument: Option<&str>,
) -> Vec<(f64, f64)> {
    rows.iter()
        .filter(|r| instrument.is_none_or(|i| r["instrument"] == i))
        .map(|r| (num(r, "diameter_m"), num(r, "percent_finer")))
        .collect()
}

/// Round trip (issue 14, Validation): sample `k` run with ideal Stokes (N = 20 000 to keep the
/// suite fast; the N = 100 000 figures are in docs/commands/invert.md), its hydrometer's
/// readings.csv inverted with the defaults: at the Stokes diameter of every reading (the bulb
/// centre's, granulometry.csv) the recovered percent finer is within 1 point + 2σ of the input
/// curve, σ the run's own standard deviation of that reading from its grain count (the issue's
/// tolerance), or its relative counting σ (readings.csv's `counting_sigma` over the reading)
/// times the input curve at d, where larger.
/// Returns the number of readings checked and the largest error, points.
fn round_trip(k: u32) -> (usize, f64) {
    let out = tmp();
    let o = settle()
        .args(["run", &format!("scenarios/sedimentation_sample{k}.toml")])
        .args([
            "--set",
            "physics=ideal-stokes",
            "--set",
            "sample.particles=20000",
            "-q",
        ])
        .arg("--out")
        .arg(out.path())
        .output()
        .expect("spawn settle");
    assert_exit(&o, 0);
    let run = out.path().join(format!("sedimentation_sample{k}"));
    let o = settle()
        .arg("invert")
        .arg(run.join("readings.csv"))
        .arg("--out")
        .arg(out.path())
        .args(["--repeats", "0"])
        .output()
        .expect("spawn settle");
    assert_exit(&o, 0);
    let inverted = curve_of(
        &read_csv_records(&out.path().join("readings_inverted/inverted.csv")),
        None,
    );
    let gran = read_csv_records(&run.join("granulometry.csv"));
    let input = curve_of(&gran, Some("input"));
    // Each reading's relative counting σ, σ_count/R (readings.csv's `counting_sigma` over the
    // reading, both in g/L), by time.
    let text = std::fs::read_to_string(run.join("readings.csv")).unwrap();
    let counting: Vec<(f64, f64)> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("time_min"))
        .map(|l| {
            let f: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (f[0], if f[1] > 0.0 { f[3] / f[1] } else { 0.0 })
        })
        .collect();
    let (mut checked, mut worst) = (0, 0.0f64);
    for r in gran.iter().filter(|r| r["instrument"] == "hydrometer") {
        checked += 1;
        let (d, sd_run) = (num(r, "diameter_m"), num(r, "sd_percent"));
        // The tolerance's σ: the run's sd_percent, or the reading's relative counting noise
        // σ_count/R applied to the curve at the reading's diameter, F(d), where larger. invert
        // weighs each reading by σ_i² = σ_res² + σ_count,i² (issue 26, item 8), so the curve
        // recovered at d is only as determined as that reading's counting noise, a relative
        // error of the mass the reading sees, i.e. of F(d); the run's sd_percent applies the
        // same relative noise to the run's own percent finer, which the bulb's averaging puts
        // far below F(d) where the curve is steep (sample 4 at 35 µm: 78.9 % read, F = 97 %:
        // 1.23 against 1.51 points; the error 3.67 points with the counting σ, 1.07 without).
        let t_min = num(r, "time_min");
        let per_point = counting
            .iter()
            .find(|(t, _)| (t - t_min).abs() <= 1e-9 * t_min.max(1.0))
            .map_or(0.0, |c| c.1);
        let sd = sd_run.max(per_point * at(&input, d));
        let err = (at(&inverted, d) - at(&input, d)).abs();
        assert!(
            err <= 1.0 + 2.0 * sd,
            "sample {k}, d = {} µm: recovered {} %, input {} %, tolerance {} points",
            d * 1e6,
            at(&inverted, d),
            at(&input, d),
            1.0 + 2.0 * sd
        );
        worst = worst.max(err);
    }
    eprintln!("sample {k}: {checked} readings, largest error {worst:.2} points");
    (checked, worst)
}

/// Readings of the 152H in each run: D422's seven times (2, 5, 15, 30, 60, 250, 1440 min).
const READINGS: usize = 7;

/// The largest error of a round trip, points: the recorded figures are 1.21 / 0.70 / 0.92 /
/// 1.58 / 1.24 (samples 1–5, docs/commands/invert.md); 2 points is the per-reading tolerance
/// 1 + 2σ at the runs' typical σ of half a point.
const WORST_POINTS: f64 = 2.0;

/// [`round_trip`] of sample `k`: every reading checked, and the largest error within
/// [`WORST_POINTS`].
fn assert_round_trip(k: u32) {
    assert_round_trip_within(k, WORST_POINTS);
}

/// [`round_trip`] of sample `k`: every reading checked, and the largest error within
/// `worst_points`.
fn assert_round_trip_within(k: u32, worst_points: f64) {
    let (checked, worst) = round_trip(k);
    assert!(
        checked >= READINGS,
        "sample {k}: {checked} hydrometer readings checked, expected {READINGS}"
    );
    assert!(
        worst <= worst_points,
        "sample {k}: largest error {worst} points > {worst_points}"
    );
}

#[test]
fn round_trip_ideal_stokes_sample1() {
    assert_round_trip(1);
}
#[test]
fn round_trip_ideal_stokes_sample2() {
    assert_round_trip(2);
}
#[test]
fn round_trip_ideal_stokes_sample3() {
    assert_round_trip(3);
}
/// Sample 4 (5 % to 97 % between 25 and 35 µm): the standard reduction errs by 18 points on
/// the same run; the inversion stays within the tolerance. Its largest error is allowed 4
/// points, not [`WORST_POINTS`]: since the readings carry their counting σ (issue 26, item 8),
/// the 2-min reading at 35 µm weighs σ = 0.55 g/L instead of 0.25 (1.5 points of F(d), so its
/// per-reading tolerance 1 + 2σ is 4.0 points), and the discrepancy principle smooths the steep
/// part more: 3.67 points at 35 µm (1.07 without the counting σ).
#[test]
fn round_trip_ideal_stokes_sample4() {
    assert_round_trip_within(4, 4.0);
}
#[test]
fn round_trip_ideal_stokes_sample5() {
    assert_round_trip(5);
}

/// Noise (issue 14, Validation): the exact readings of sample 1 under ideal Stokes (the 152H in
/// the field of seed eq. 16 for the input curve, at D422's seven times), each perturbed by a
/// reading error N(0, Δ/√6) and rounded to the 152H's resolution Δ = 0.5 g/L, 50 times: the
/// 5–95 % band (40 Monte Carlo repeats each) covers the input curve at ≥ 90 % of the resolved bin edges over all repeats (the
/// issue's figure). 1000 layers (0.5 mm) keep the test fast; the readings and the model share
/// them, so the layering is no error here.
#[test]
fn the_band_covers_the_input_curve_under_rounded_noisy_readings() {
    use rand::{Rng, SeedableRng};
    let dir = tmp();
    let file = dir.path().join("sample1.csv");
    let mut text = String::from(
        "# standard = d422\n# hydrometer = 152H\n# dry_mass_g = 60\n\
         # suspension_volume_ml = 1447.283237\n# specific_gravity = 2.5\n\
         # meniscus_correction = 0\n# blank_reading = 0\ntime_min,reading,temperature_c\n",
    );
    for t in [2, 5, 15, 30, 60, 250, 1440] {
        text.push_str(&format!("{t},10,20.06517314\n"));
    }
    std::fs::write(&file, text).unwrap();
    let (mut test, _) = read_test(&file, None).expect("reads");
    test.col.layers = 1000;
    let dist = Distribution::load(Path::new("data/sedimentation_samples.csv"), 1).unwrap();
    let truth = |d: f64| dist.percent_finer(d);
    let an = test.col.analysis;
    let exact: Vec<f64> = test
        .times_s
        .iter()
        .map(|&t| {
            let f = ideal_field(&an, test.col.height_m, test.col.layers, t, |d| {
                truth(d) / 100.0
            });
            test.probe.read(&an, &f).expect("floats")
        })
        .collect();
    test.readings = exact.clone();
    let bins = bins_for(std::slice::from_ref(&test), 14, None);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(14);
    let (mut covered, mut total) = (0usize, 0usize);
    let delta = test.resolution;
    for repeat in 0..50 {
        let mut noisy = test.clone();
        for (r, e) in noisy.readings.iter_mut().zip(&exact) {
            // Box–Muller N(0, 1).
            let (u, v): (f64, f64) = (rng.random::<f64>().max(1e-300), rng.random());
            let g = (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos();
            *r = ((e + g * delta / 6f64.sqrt()) / delta).round() * delta;
        }
        let f = fit(
            std::slice::from_ref(&noisy),
            &bins,
            Model::IdealStokes,
            LambdaRule::Discrepancy,
            40,
            repeat,
            None,
        )
        .expect("inverts");
        for p in &f.curve {
            let t = truth(p.diameter_m);
            total += 1;
            if p.p5 - 1e-9 <= t && t <= p.p95 + 1e-9 {
                covered += 1;
            }
        }
    }
    let share = covered as f64 / total as f64;
    eprintln!("the band covers the input at {covered} of {total} edges");
    assert!(
        share >= 0.9,
        "the band covers the input at {covered} of {total} edges"
    );
}

/// Round trip, full physics (issue 14, Validation): sample 2 simulated with hindered settling
/// (N = 100 000, contacts off: data/invert/sample2_full, README there), its hydrometer readings
/// inverted with `--model full`: within 3 points (the figure) of the input curve at the
/// Stokes diameter of every reading. Also inverts its sphere and pipette files together (one
/// resolution each) and checks that both instruments are in misfit.csv.
#[test]
fn round_trip_full_physics_sample2() {
    let dir = Path::new("data/invert/sample2_full");
    let out = tmp();
    let o = settle()
        .arg("invert")
        .arg(dir.join("readings.csv"))
        .args(["--model", "full", "--repeats", "0", "--out"])
        .arg(out.path())
        .output()
        .expect("spawn settle");
    assert_exit(&o, 0);
    let inverted = curve_of(
        &read_csv_records(&out.path().join("readings_inverted/inverted.csv")),
        None,
    );
    let gran = read_csv_records(&dir.join("granulometry.csv"));
    let input = curve_of(&gran, Some("input"));
    let mut checked = 0;
    for r in gran.iter().filter(|r| r["instrument"] == "hydrometer") {
        let d = num(r, "diameter_m");
        let err = (at(&inverted, d) - at(&input, d)).abs();
        assert!(err < 3.0, "d = {} µm: error {err} points", d * 1e6);
        checked += 1;
    }
    assert!(checked >= READINGS, "{checked} hydrometer readings checked");
    let o = settle()
        .arg("invert")
        .arg(dir.join("readings_sphere.csv"))
        .arg(dir.join("readings_pipette.csv"))
        .args(["--resolution", "0.01,0.03", "--repeats", "0", "--out"])
        .arg(out.path())
        .output()
        .expect("spawn settle");
    assert_exit(&o, 0);
    let misfit = read_csv_records(&out.path().join("readings_sphere_inverted/misfit.csv"));
    for inst in ["buoyancy-sphere", "pipette"] {
        assert_eq!(
            misfit.iter().filter(|r| r["instrument"] == inst).count(),
            10,
            "{inst}"
        );
    }
}

/// The constrained solver (`invert::solve::simplex_qp`): with Q = I and c = p it is the
/// Euclidean projection of p on the simplex {w ≥ 0, Σw = 1}, whose solution is known in closed
/// form: w_j = max(p_j − τ, 0) with τ such that Σw = 1 (Held, Wolfe & Crowder 1974). Exact to
/// 1e-12.
#[test]
fn the_solver_projects_on_the_simplex() {
    use nalgebra::{DMatrix, DVector};
    use settle::invert::solve::simplex_qp;
    for p in [
        vec![0.5, 0.2, 0.9, -0.3, 0.1],
        vec![0.1, 0.1, 0.1, 0.1],
        vec![3.0, -1.0, 0.0],
    ] {
        let n = p.len();
        let w = simplex_qp(
            &DMatrix::identity(n, n),
            &DVector::from_vec(p.clone()),
            None,
        );
        // τ by bisection on Σ max(p − τ, 0) = 1.
        let (mut lo, mut hi) = (-10.0, 10.0);
        for _ in 0..200 {
            let t = 0.5 * (lo + hi);
            if p.iter().map(|x| (x - t).max(0.0)).sum::<f64>() > 1.0 {
                lo = t;
            } else {
                hi = t;
            }
        }
        for (wj, pj) in w.iter().zip(&p) {
            assert!((wj - (pj - lo).max(0.0)).abs() < 1e-12, "{p:?}: {w:?}");
        }
    }
}

/// The input curve of sample `k` of `data/sedimentation_samples.csv` as bins (its knots; the
/// curve is piecewise linear in log d between them, as the bins spread their mass) and the
/// mass fraction of each.
fn sample_bins(k: u32) -> (settle::instruments::forward::Bins, Vec<f64>) {
    let text = std::fs::read_to_string("data/sedimentation_samples.csv").unwrap();
    let pts: Vec<(f64, f64)> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("sample"))
        .filter_map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[0].trim() == k.to_string())
                .then(|| (f[1].trim().parse().unwrap(), f[2].trim().parse().unwrap()))
        })
        .collect();
    let bins = settle::instruments::forward::Bins {
        edges_m: pts.iter().map(|p: &(f64, f64)| p.0).collect(),
    };
    let w = pts.windows(2).map(|p| (p[1].1 - p[0].1) / 100.0).collect();
    (bins, w)
}

/// The full forward model agrees with the simulation it stands for (issue 14, full-physics
/// round trip): for the input curve of samples 2 and 4, the readings that
/// `Settling::Hindered` predicts (the exact Kynch solution of Dallavalle + Di Felice drag, the
/// bed, each instrument's geometry: the 152H floating, the sphere averaged over its volume, the
/// pipette's disc weighted by its chord) match the readings of the 2D runs with contacts off
/// (N = 100 000, data/invert/sample{2,4}_full) within Δ, the resolutions of the docs' figures
/// (0.5 g/L, 0.01 g, 0.03 g; about twice the runs' statistical sd of the earliest readings).
/// Ideal Stokes settling misses one reading of each sample by more than Δ (the test can fail).
#[test]
fn the_full_forward_model_predicts_the_runs_readings() {
    use settle::instruments::forward::{fields_for, Settling};
    for k in [2u32, 4] {
        let (bins, w) = sample_bins(k);
        let dir = format!("data/invert/sample{k}_full");
        let mut ideal_worst: f64 = 0.0;
        for (file, delta) in [
            ("readings.csv", 0.5),
            ("readings_sphere.csv", 0.01),
            ("readings_pipette.csv", 0.03),
        ] {
            let (test, _) = read_test(&Path::new(&dir).join(file), Some(delta)).unwrap();
            for (settling, full) in [
                (
                    Settling::Hindered {
                        voidage_cell_m: 0.002,
                    },
                    true,
                ),
                (Settling::IdealStokes, false),
            ] {
                let fields = fields_for(&test.col, settling, &bins, &w, &test.times_s);
                for (i, f) in fields.iter().enumerate() {
                    let p = test.probe.read(&test.col.analysis, f).unwrap() + test.offsets[i];
                    let r = (p - test.readings[i]).abs() / delta;
                    if full {
                        assert!(
                            r <= 1.0,
                            "sample {k} {file} t = {} s: predicted {p}, read {}, Δ = {delta}",
                            test.times_s[i],
                            test.readings[i]
                        );
                    } else {
                        ideal_worst = ideal_worst.max(r);
                    }
                }
            }
        }
        eprintln!("sample {k}: ideal Stokes misses by up to {ideal_worst:.2} Δ");
        assert!(ideal_worst > 1.0, "sample {k}: {ideal_worst}");
    }
}

/// Strict bounds (`Linear::strict_bounds`) against their closed form: three bins read directly
/// (J = I, σ = 0.01, b = (0.2, 0.3, 0.5)); over the plane Σw = 1 the set χ² ≤ 1 is a disc of
/// radius σ about b, so w₀ ranges over 0.2 ± σ √(2/3) (the norm of e₀'s projection on the
/// plane). Within 1e-6.
#[test]
fn strict_bounds_match_their_closed_form() {
    use nalgebra::{DMatrix, DVector};
    use settle::invert::solve::Linear;
    let lin = Linear {
        j: DMatrix::identity(3, 3),
        b: DVector::from_vec(vec![0.2, 0.3, 0.5]),
        sigma: DVector::from_element(3, 0.01),
    };
    let (lo, hi) = lin.strict_bounds(&[1.0, 0.0, 0.0], 1.0).unwrap();
    let r = 0.01 * (2.0f64 / 3.0).sqrt();
    assert!((lo - (0.2 - r)).abs() < 1e-6, "{lo}");
    assert!((hi - (0.2 + r)).abs() < 1e-6, "{hi}");
    // Bounds the simplex cuts. χ² ≤ 10⁴ holds the vertex w = (1, 0, 0) (χ² = 9800) and w₀ = 0:
    // [0, 1]. (Before issue 26 the upper end came out below 1: the Lagrangian's μ reached
    // 10¹² s, where simplex_qp is rounding noise.) χ² ≤ 9000: beyond w₀ = 0.8 the closest point
    // has w₁ = 0, w₂ = 1 − w₀, so σ²χ² = (w₀ − 0.2)² + 0.3² + (w₀ − 0.5)² = 0.9 gives
    // w₀ = (1.4 + √6.12)/4 = 0.968465.
    let (lo, hi) = lin.strict_bounds(&[1.0, 0.0, 0.0], 1e4).unwrap();
    assert!(lo.abs() < 1e-6 && (hi - 1.0).abs() < 1e-6, "{lo} {hi}");
    let (_, hi) = lin.strict_bounds(&[1.0, 0.0, 0.0], 9e3).unwrap();
    let exact = (1.4 + 6.12f64.sqrt()) / 4.0;
    assert!((hi - exact).abs() < 1e-6, "{hi} against {exact}");
    assert!(lin.strict_bounds(&[1.0, 0.0, 0.0], 0.5).is_some());
    assert!(Linear {
        b: DVector::from_vec(vec![0.5, 0.5, 0.5]),
        ..lin
    }
    .strict_bounds(&[1.0, 0.0, 0.0], 1.0)
    .is_none());
}

/// The χ² bar of `--bounds=P` (`solve::chi2_bar`) against the table of upper critical values
/// of χ² (NIST/SEMATECH e-Handbook of Statistical Methods, 1.3.6.7.4, printed to 3 decimals):
/// P = 0.95 at 1, 10 and 27 degrees of freedom, P = 0.99 at 10 and P = 0.90 at 27; within the
/// table's rounding (5e-4).
#[test]
fn chi2_bar_matches_the_table_of_critical_values() {
    use settle::invert::solve::chi2_bar;
    for (m, p, table) in [
        (1, 0.95, 3.841),
        (10, 0.95, 18.307),
        (27, 0.95, 40.113),
        (10, 0.99, 23.209),
        (27, 0.90, 36.741),
    ] {
        let got = chi2_bar(m, p);
        assert!(
            (got - table).abs() <= 5e-4,
            "χ²_{m}({p}) = {got}, table {table}"
        );
    }
}

/// What the readings of a steep curve determine (issue 14, full-physics round trip): over every
/// distribution on 60 resolved bins (plus the finer and coarser bins) that explains the readings
/// with χ² ≤ m (m readings; Linear::strict_bounds, the full model linearised at the inversion),
/// the percent finer at the Stokes diameter of the two readings that bracket the steep part
/// ranges over more than 6 points: no inversion of these readings can be within 3 points of
/// every curve they allow. Sample 2 (5 % at 50 µm to 100 % at 70 µm), sphere + pipette: under
/// hindered settling the 0.5 min reading sees 78–85 µm, the 1 min one 53–59 µm, nothing
/// between. Sample 4 (5 % at 25 µm to 97 % at 35 µm), hydrometer: two readings (2 and 5 min).
/// The input curve lies within its bounds. The figures are in docs/commands/invert.md.
#[test]
fn the_readings_do_not_determine_a_steep_curve_between_two_readings() {
    use settle::instruments::forward::{unit_fields, Settling};
    use settle::invert::solve::Linear;
    type Case<'a> = (&'a str, &'a [(&'a str, f64)], &'a [f64]);
    let cases: [Case; 2] = [
        (
            "data/invert/sample2_full",
            &[
                ("readings_sphere.csv", 0.01),
                ("readings_pipette.csv", 0.03),
            ],
            &[74.77e-6, 52.87e-6],
        ),
        (
            "data/invert/sample4_full",
            &[("readings.csv", 0.5)],
            &[35.11e-6, 25.53e-6],
        ),
    ];
    for (dir, files, diameters) in cases {
        let tests: Vec<_> = files
            .iter()
            .map(|(f, d)| read_test(&Path::new(dir).join(f), Some(*d)).unwrap().0)
            .collect();
        let bins = bins_for(&tests, 60, None);
        let f = fit(
            &tests,
            &bins,
            Model::Full,
            LambdaRule::Discrepancy,
            0,
            1,
            None,
        )
        .unwrap();
        let (m, n) = (f.predicted.len(), bins.len());
        let mut lin = Linear {
            j: nalgebra::DMatrix::zeros(m, n),
            b: nalgebra::DVector::zeros(m),
            sigma: nalgebra::DVector::zeros(m),
        };
        let mut row = 0;
        let settling = Settling::Hindered {
            voidage_cell_m: 0.002,
        };
        for t in &tests {
            let units = unit_fields(&t.col, settling, &bins, &f.w, &t.times_s);
            for (i, u) in units.iter().enumerate() {
                let (p, d) = t.predict(i, u, &f.w).unwrap();
                let jw: f64 = d.iter().zip(&f.w).map(|(a, b)| a * b).sum();
                for (k, x) in d.iter().enumerate() {
                    lin.j[(row, k)] = *x;
                }
                lin.b[row] = t.readings[i] - p + jw;
                lin.sigma[row] = t.sigma();
                row += 1;
            }
        }
        let gran = read_csv_records(&Path::new(dir).join("granulometry.csv"));
        let input = curve_of(&gran, Some("input"));
        for &d in diameters {
            let c: Vec<f64> = (0..n).map(|j| bins.fraction_finer(j, d)).collect();
            let (lo, hi) = lin.strict_bounds(&c, m as f64).expect("feasible");
            let (lo, hi) = (100.0 * lo, 100.0 * hi);
            let truth = at(&input, d);
            eprintln!(
                "{dir}: F({:.1} µm) between {lo:.1} and {hi:.1} % (input {truth:.1} %)",
                d * 1e6
            );
            assert!(hi - lo > 6.0, "{dir} at {d}: [{lo}, {hi}]");
            assert!(
                lo - 0.5 <= truth && truth <= hi + 0.5,
                "{dir} at {d}: {truth}"
            );
        }
    }
}
