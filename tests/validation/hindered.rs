//! Validation case: hindered settling in the sedimentation cylinder against the laws it must
//! reduce to (issue 17; docs/validation/hindered.md). Suspensions of `data/hindered_samples.csv`
//! (sample 1: 20 µm grains; sample 2: 10 and 20 µm, half the mass each) in the 63.5 mm × 457 mm
//! cylinder, full physics without contacts, 50 000 grains, 5 mm voidage cells (43 grains a
//! cell: the grid counts each grain in its own cell, which at a few grains a cell adds
//! φ/λ to the solid fraction a grain sees), 300 s.
//!
//! - Monodisperse, φ = 0.5, 1, 2, 5 %: the settling front's velocity (from the suspended solid
//!   volume above a depth of 0.35 m at 30 and 300 s: z_f = 0.35 m − ∫c dz / φ₀) over the lone
//!   grain's terminal velocity U₀ (`terminal_time.csv`) against Richardson–Zaki (1 − φ)^4.65
//!   and Batchelor 1 − 6.55 φ, within 5 %. The model's fluid does not move, so its velocities
//!   are in the frame of the closed cylinder, the frame of both laws: their return flow is in
//!   the law, not in the model ([`settle::fluid::hindered`]).
//! - Bidisperse, φ = 2 and 5 %: each class's mean velocity in the mixed zone (grains tracked
//!   between the snapshots at 60 and 300 s) against Masliyah (1979) / Lockett & Bassoon (1979)
//!   within 10 %.

use crate::common::{col, read_csv, settle, tmp};
use settle::fluid::hindered::{
    batchelor_ratio, masliyah_velocities_m_s, richardson_zaki_ratio, RICHARDSON_ZAKI_N,
};
use std::path::{Path, PathBuf};

const H_M: f64 = 0.457;
const B_M: f64 = 0.0635;
const RHO_P: f64 = 2500.0;

/// Runs sample `sample` of `data/hindered_samples.csv` at solid fraction `phi` with hindered
/// law `law` for 300 s; returns the run's folder (inside `dir`).
fn run(dir: &Path, sample: u32, phi: f64, law: &str) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let csv = root.join("data/hindered_samples.csv");
    let mass = phi * RHO_P * std::f64::consts::PI / 4.0 * B_M * B_M * H_M;
    let name = format!("s{sample}_{law}_{phi}");
    let sets = [
        format!("name={name}"),
        format!("sample.csv={}", csv.display()),
        format!("sample.sample={sample}"),
        "sample.n_diameters=2".into(),
        format!("sample.mass_kg={mass}"),
        "sample.contacts=false".into(),
        "sample.lubrication=false".into(),
        format!("sample.hindered={law}"),
        "time.end_s=300".into(),
        "sample.layers=400".into(),
        "sample.particles=50000".into(),
        "sample.voidage_cell_m=0.005".into(),
        "sample.record_times_s=[30, 300]".into(),
        "sample.snapshot_times_s=[60, 300]".into(),
    ];
    let mut cmd = settle();
    cmd.arg("run")
        .arg(root.join("scenarios/sedimentation_sample1.toml"))
        .arg("--out")
        .arg(dir)
        .arg("--quiet");
    for s in &sets {
        cmd.arg("--set").arg(s);
    }
    let o = cmd.output().expect("spawn settle");
    assert!(
        o.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    dir.join(name)
}

/// Lone-grain terminal velocity U₀ per diameter (m → m/s), from `terminal_time.csv`.
fn lone_speeds(run: &Path) -> Vec<(f64, f64)> {
    let (h, rows) = read_csv(&run.join("terminal_time.csv"));
    rows.iter()
        .map(|r| {
            (
                col(&h, r, "diameter_m"),
                col(&h, r, "terminal_velocity_m_s"),
            )
        })
        .collect()
}

/// (φ₀, U/U₀) of a monodisperse run: φ₀ the mean concentration between 5 cm and 35 cm deep at
/// 30 s, U the front's velocity between 30 and 300 s.
fn front_ratio(run: &Path) -> (f64, f64) {
    let (h, rows) = read_csv(&run.join("profiles.csv"));
    let z_ref = 0.35;
    let at = |t: f64| -> Vec<(f64, f64)> {
        rows.iter()
            .filter(|r| col(&h, r, "time_s") == t)
            .map(|r| (col(&h, r, "depth_m"), col(&h, r, "concentration")))
            .collect()
    };
    let (p30, p300) = (at(30.0), at(300.0));
    let dz = p30[1].0 - p30[0].0;
    let band: Vec<f64> = p30
        .iter()
        .filter(|(z, _)| *z > 0.05 && *z < z_ref)
        .map(|p| p.1)
        .collect();
    let phi0 = band.iter().sum::<f64>() / band.len() as f64;
    let front = |p: &[(f64, f64)]| {
        z_ref
            - p.iter()
                .filter(|(z, _)| *z < z_ref)
                .map(|(_, c)| c * dz)
                .sum::<f64>()
                / phi0
    };
    let u = (front(&p300) - front(&p30)) / 270.0;
    (phi0, u / lone_speeds(run)[0].1)
}

/// Mean velocity (m/s, downwards) of each class of a run, by diameter (ascending): the grains
/// suspended at 300 s between 5 cm above the bottom and 12 cm below the surface (below both
/// fronts and above the bed for the whole window), tracked from the 60 s snapshot.
fn class_speeds(run: &Path) -> Vec<(f64, f64, f64)> {
    let snap = |t: &str| read_csv(&run.join(format!("snapshots/t000{t}.0s.csv")));
    let ((h, a), (_, b)) = (snap("060"), snap("300"));
    let mut out: Vec<(f64, f64, f64)> = Vec::new(); // diameter, Σ velocity, count
    for (r1, r2) in a.iter().zip(&b) {
        let (y1, y2, d) = (
            col(&h, r1, "y_m"),
            col(&h, r2, "y_m"),
            col(&h, r1, "diameter_m"),
        );
        if r2[4] == "true" || !(0.05 < y2 && y2 < H_M - 0.12) {
            continue;
        }
        match out.iter_mut().find(|c| c.0 == d) {
            Some(c) => (c.1, c.2) = (c.1 + (y1 - y2) / 240.0, c.2 + 1.0),
            None => out.push((d, (y1 - y2) / 240.0, 1.0)),
        }
    }
    out.sort_by(|x, y| x.0.total_cmp(&y.0));
    out.iter().map(|c| (c.0, c.1 / c.2, c.2)).collect()
}

/// The Richardson–Zaki option reproduces Richardson–Zaki (measured: within 0.12 %) and
/// Batchelor in its range φ ≤ 2 % (measured: 0.3, 1.9, 4.8 %), within 5 %. At φ = 5 % Batchelor's
/// first-order law is outside its range (0.79 against 0.67): not checked there.
#[test]
fn richardson_zaki_option_settles_at_richardson_zaki_and_batchelor() {
    let dir = tmp();
    for phi in [0.005, 0.01, 0.02, 0.05] {
        let (phi0, ratio) = front_ratio(&run(dir.path(), 1, phi, "richardson-zaki"));
        assert!((phi0 / phi - 1.0).abs() < 0.01, "φ₀ = {phi0} for {phi}");
        let rz = richardson_zaki_ratio(phi, RICHARDSON_ZAKI_N);
        assert!(
            (ratio / rz - 1.0).abs() < 0.05,
            "φ = {phi}: U/U₀ = {ratio}, Richardson–Zaki {rz}"
        );
        if phi <= 0.02 {
            let b = batchelor_ratio(phi);
            assert!(
                (ratio / b - 1.0).abs() < 0.05,
                "φ = {phi}: U/U₀ = {ratio}, Batchelor {b}"
            );
        }
    }
}

/// The seed's Di Felice factor (the default) settles at ≈ ε^3.7 in the one-way model, not at
/// Richardson–Zaki's ε^4.65: 0.5 % fast at φ = 0.5 %, 5.0 % at 5 %; against Batchelor 6.8 % fast
/// at 2 %. Checked against the lone-grain force balance of its own law (within 0.5 %: ε^3.7 at
/// Re → 0), and that it misses Richardson–Zaki at 5 % and Batchelor at 2 % by more than 4 %,
/// which is why the option exists (docs/validation/hindered.md).
#[test]
fn di_felice_factor_settles_at_voidage_to_the_3_7_not_at_richardson_zaki() {
    let dir = tmp();
    for phi in [0.005, 0.02, 0.05] {
        let (_, ratio) = front_ratio(&run(dir.path(), 1, phi, "di-felice"));
        let own = (1.0 - phi).powf(3.7);
        assert!(
            (ratio / own - 1.0).abs() < 0.005,
            "φ = {phi}: U/U₀ = {ratio}, ε^3.7 = {own}"
        );
        let rz = richardson_zaki_ratio(phi, RICHARDSON_ZAKI_N);
        if phi == 0.05 {
            assert!(ratio / rz - 1.0 > 0.04, "φ = {phi}: {ratio} vs {rz}");
        }
        if phi == 0.02 {
            assert!(ratio / batchelor_ratio(phi) - 1.0 > 0.04, "{ratio}");
        }
    }
}

/// Bidisperse 10 + 20 µm (half the mass each) against Masliyah / Lockett & Bassoon, within
/// 10 %: the Richardson–Zaki option at φ = 2 % and 5 % (measured −0.8/+3.0 % and −2.1/+8.1 %,
/// large/small), Di Felice at 2 % (+1.2/+5.0 %). Di Felice at 5 % misses the small class by
/// 13.6 % (docs/validation/hindered.md), which this test also states.
#[test]
fn bidisperse_suspension_against_masliyah() {
    let dir = tmp();
    for (law, phi, within) in [
        ("richardson-zaki", 0.02, true),
        ("richardson-zaki", 0.05, true),
        ("di-felice", 0.02, true),
        ("di-felice", 0.05, false),
    ] {
        let r = run(dir.path(), 2, phi, law);
        let speeds = class_speeds(&r);
        let u0 = lone_speeds(&r);
        assert_eq!((speeds.len(), u0.len()), (2, 2));
        // Half the mass (and volume) each.
        let phis = [0.5 * phi, 0.5 * phi];
        let expect = masliyah_velocities_m_s(&phis, &[u0[0].1, u0[1].1], RICHARDSON_ZAKI_N);
        let worst = speeds
            .iter()
            .zip(&expect)
            .map(|(s, e)| {
                assert!(s.2 > 5000.0, "{law} {phi}: {} grains tracked", s.2);
                (s.1 / e - 1.0).abs()
            })
            .fold(0.0, f64::max);
        assert_eq!(
            worst < 0.10,
            within,
            "{law}, φ = {phi}: worst deviation {worst} from Masliyah ({speeds:?} vs {expect:?})"
        );
    }
}
