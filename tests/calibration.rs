//! Contact calibration of f-EDEM (Zhang & Li 2024), Appendices II and III.
//!
//! - `scenarios/restitution_drop.toml`: an 8 mm steel ball (8135 kg/m³) dropped in air on a steel
//!   plate from 95–398 mm, rebound heights of Table A2, e = 0.612.
//! - `scenarios/tilt_friction.toml`: a steel block on a tilted steel plate, μ_s = 0.341 of
//!   Table A3: sticks below atan(0.341) = 18.83°, slides above.
//!
//! f-EDEM states that its simulated rebounds "match the test results perfectly" and the issue asks
//! for 3 %; no constant e can do that for Table A2 (see
//! `no_constant_restitution_matches_table_a2_within_3_percent`), so the drop is checked against
//! what is physically right: Rapier's contact restitution equals the scenario's e, the rebound
//! equals an independent integration of the same fall and rise in air, and each height is within
//! the data's own scatter of the measurement.

use settle::fluid::{buoyancy_n, sphere_mass_kg, DragLaw, SphereDrag};
use settle::run::{prepare, run_one};
use settle::scenes::calibration::{
    constant_fit, drop_settings, simulate_drop, tilt_threshold, TiltSetup,
};
use std::path::Path;

const G: f64 = 9.81;
/// f-EDEM Table A2: drop heights and measured rebound heights, m.
#[allow(clippy::approx_constant)] // 0.318 m is a drop height, not 1/π
const DROP_M: [f64; 5] = [0.095, 0.188, 0.252, 0.318, 0.398];
const REBOUND_M: [f64; 5] = [0.0370, 0.0720, 0.0909, 0.1180, 0.1469];

/// Reads a CSV written by a run into (header, rows).
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header, rows)
}

fn col(header: &[String], row: &[String], name: &str) -> f64 {
    let i = header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    row[i]
        .parse()
        .unwrap_or_else(|e| panic!("{name} = `{}`: {e}", row[i]))
}

/// Rebound apex of the ball's lowest point after a drop from `h` in air (Dallavalle drag,
/// buoyancy), the plate reversing the velocity with factor `e`: RK4 with a 1 µs step, impact and
/// apex located within the step. Independent of Rapier and of the engine's integrators.
fn reference_rebound(h: f64, e: f64) -> f64 {
    let (d, rho) = (0.008, 8135.0);
    let drag = SphereDrag::new(
        DragLaw::Dallavalle {
            viscosity_pa_s: 1.8e-5,
            voidage: 1.0,
        },
        d,
        1.2,
    );
    let m = sphere_mass_kg(d, rho);
    let b = buoyancy_n(d, 1.2, G);
    let acc = |v: f64| -G + (b - v.signum() * drag.force_n(v.abs())) / m;
    let rk4 = |z: f64, v: f64, dt: f64| {
        let (k1z, k1v) = (v, acc(v));
        let (k2z, k2v) = (v + 0.5 * dt * k1v, acc(v + 0.5 * dt * k1v));
        let (k3z, k3v) = (v + 0.5 * dt * k2v, acc(v + 0.5 * dt * k2v));
        let (k4z, k4v) = (v + dt * k3v, acc(v + dt * k3v));
        (
            z + dt / 6.0 * (k1z + 2.0 * k2z + 2.0 * k3z + k4z),
            v + dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v),
        )
    };
    let dt = 1e-6;
    let (mut z, mut v) = (h, 0.0);
    loop {
        let (z1, v1) = rk4(z, v, dt);
        if z1 <= 0.0 {
            // Impact within the step: interpolate the speed at z = 0.
            let f = z / (z - z1);
            v = v + f * (v1 - v);
            break;
        }
        (z, v) = (z1, v1);
    }
    let (mut z, mut v) = (0.0, -e * v);
    loop {
        let (z1, v1) = rk4(z, v, dt);
        if v1 <= 0.0 {
            return z + v * v / (2.0 * G);
        }
        (z, v) = (z1, v1);
    }
}

/// Table A2 itself: with e_i = √(H_r/H_f) (eq. A4) the mean is f-EDEM's 0.612, and no constant e
/// brings all five rebounds within 3 % of the measurements: the ratios H_r/H_f span 0.3607–0.3895,
/// so the best constant (e = 0.6120, the mean itself) misses the 95 mm and 252 mm drops by
/// 3.83 % each, in opposite directions.
#[test]
fn no_constant_restitution_matches_table_a2_within_3_percent() {
    let fit = constant_fit(&DROP_M, &REBOUND_M).unwrap();
    assert!((fit.e_mean - 0.612).abs() < 5e-4, "mean e {}", fit.e_mean);
    assert!(
        (fit.e_minimax - 0.612).abs() < 5e-4,
        "minimax e {}",
        fit.e_minimax
    );
    assert!(
        (fit.minimax_rel_error - 0.0383).abs() < 5e-4,
        "best achievable error {}",
        fit.minimax_rel_error
    );
    assert!(fit.minimax_rel_error > 0.03);
    // The minimax e really is the best: nudging it either way makes the worst height worse.
    let worst = |e: f64| {
        DROP_M
            .iter()
            .zip(REBOUND_M)
            .map(|(h, r)| (e * e * h / r - 1.0).abs())
            .fold(0.0, f64::max)
    };
    let best = worst(fit.e_minimax);
    assert!((best - fit.minimax_rel_error).abs() < 1e-12);
    for de in [-1e-3, 1e-3] {
        assert!(worst(fit.e_minimax + de) > best);
    }
    // e = 0.612 in vacuum: -3.8 % at 95 mm, +3.8 % at 252 mm.
    assert!((0.612f64.powi(2) * 0.095 / 0.037 - 1.0 + 0.0381).abs() < 5e-4);
    assert!((0.612f64.powi(2) * 0.252 / 0.0909 - 1.0 - 0.0383).abs() < 5e-4);
}

/// `settle run scenarios/restitution_drop.toml` (dt = 1e-5 s), checked per drop height:
/// - Rapier's contact restitution (lift-off / impact speed at the plate) is the scenario's 0.612
///   within 0.1 % (the ball and the plate both carry e; Rapier averages them).
/// - The rebound is within 0.1 % of `reference_rebound` (same fall and rise in air, integrated
///   independently) and within 0.5 % of the vacuum rebound e²H: air drag (Re ≈ 1500 at impact)
///   lowers it by 0.13 % (95 mm) to 0.46 % (398 mm).
/// - Each rebound is within 4 % of Table A2: the 3.83 % that no constant e can beat (see above)
///   plus the 0.13 % of air drag at 95 mm, where the simulation sits at −3.96 %.
#[test]
fn restitution_drop_reproduces_rapier_restitution_and_table_a2() {
    let path = Path::new("scenarios/restitution_drop.toml");
    let p = prepare(path, None, &[]).unwrap();
    let e = p.scenario.contacts.as_ref().unwrap().restitution;
    assert_eq!(e, 0.612);
    let dir = tempfile::tempdir().unwrap();
    let report = run_one(&p, dir.path()).unwrap();
    assert!(report.out.join("rebound_height.svg").is_file());
    assert!(report.out.join("run.toml").is_file());
    let (header, rows) = read_csv(&report.out.join("summary.csv"));
    assert_eq!(
        header[..5],
        [
            "drop_height_m",
            "rebound_height_m",
            "measured_rebound_height_m",
            "rel_error",
            "restitution_effective"
        ]
    );
    assert_eq!(rows.len(), 5);
    for (i, row) in rows.iter().enumerate() {
        let h = col(&header, row, "drop_height_m");
        let hr = col(&header, row, "rebound_height_m");
        let measured = col(&header, row, "measured_rebound_height_m");
        let e_eff = col(&header, row, "restitution_effective");
        assert_eq!(h, DROP_M[i]);
        assert_eq!(measured, REBOUND_M[i]);
        assert!((e_eff / e - 1.0).abs() < 1e-3, "H = {h}: contact e {e_eff}");
        let reference = reference_rebound(h, e);
        assert!(
            (hr / reference - 1.0).abs() < 1e-3,
            "H = {h}: rebound {hr} vs reference {reference}"
        );
        let vacuum = e * e * h;
        assert!(
            hr < vacuum && hr / vacuum - 1.0 > -5e-3,
            "H = {h}: rebound {hr} vs e²H {vacuum}"
        );
        let err = hr / measured - 1.0;
        assert!((err - col(&header, row, "rel_error")).abs() < 1e-12);
        assert!(err.abs() < 0.04, "H = {h}: {err:+.4} against Table A2");
    }
    let (fh, fit) = read_csv(&report.out.join("fit.csv"));
    assert_eq!(col(&fh, &fit[0], "heights_within_tolerance"), 3.0);
    assert!(col(&fh, &fit[0], "minimax_rel_error") > 0.03);
}

/// The contact restitution follows `contacts.restitution` (not halved by a plate left at e = 0,
/// as Rapier's average combine rule would do): 0.3 and 0.9 within 0.1 %, from 188 mm.
#[test]
fn restitution_follows_the_scenario_value() {
    for e in [0.3, 0.9] {
        let p = prepare(
            Path::new("scenarios/restitution_drop.toml"),
            None,
            &[format!("contacts.restitution={e}")],
        )
        .unwrap();
        let ball = &p.spheres[0].spec;
        let settings = drop_settings(&p.scenario, ball, 0.188);
        let o = simulate_drop(&p.scenario, ball, 0.188, settings).unwrap();
        assert!(
            (o.restitution_effective / e - 1.0).abs() < 1e-3,
            "e = {e}: contact e {}",
            o.restitution_effective
        );
        let reference = reference_rebound(0.188, e);
        assert!(
            (o.rebound_height_m / reference - 1.0).abs() < 1e-3,
            "e = {e}: rebound {} vs {reference}",
            o.rebound_height_m
        );
    }
}

/// `settle run scenarios/tilt_friction.toml` (μ = 0.341, dt = 1e-4 s, 1 s per angle):
/// - the threshold found by bisection (bracket ≤ 0.1° wide) is within 0.5° of atan(0.341) =
///   18.83° (the acceptance of issue 5, item 5);
/// - every given angle below atan μ sticks (displacement < 1 µm) and every one above slides;
/// - sliding follows Coulomb's law with the same μ (Rapier has one coefficient, static =
///   dynamic): displacement ½ g (sin θ − μ cos θ) t² within 1 % at the given sliding angles.
#[test]
fn tilt_threshold_is_atan_mu() {
    let p = prepare(Path::new("scenarios/tilt_friction.toml"), None, &[]).unwrap();
    let spec = p.scenario.tilt.as_ref().unwrap();
    let mu = p.scenario.contacts.as_ref().unwrap().friction;
    assert_eq!(mu, 0.341);
    let expected = mu.atan().to_degrees();
    let dir = tempfile::tempdir().unwrap();
    let report = run_one(&p, dir.path()).unwrap();
    assert!(report.out.join("tilt_displacement.svg").is_file());
    let (th, t) = read_csv(&report.out.join("threshold.csv"));
    let found = col(&th, &t[0], "threshold_deg");
    let width = col(&th, &t[0], "slides_at_deg") - col(&th, &t[0], "sticks_at_deg");
    assert!(width > 0.0 && width <= 0.1, "bracket {width}°");
    assert!(
        (found - expected).abs() < 0.5,
        "threshold {found}° vs atan(μ) {expected}°"
    );

    let (header, rows) = read_csv(&report.out.join("summary.csv"));
    assert_eq!(header[..3], ["angle_deg", "displacement_m", "slides"]);
    let given = rows.iter().filter(|r| r[3] == "given").count();
    assert_eq!(given, spec.angles_deg.len());
    for row in &rows {
        let a = col(&header, row, "angle_deg");
        let x = col(&header, row, "displacement_m");
        let slides: bool = row[2].parse().unwrap();
        let th = a.to_radians();
        let predicted = 0.5 * G * (th.sin() - mu * th.cos()) * spec.duration_s.powi(2);
        if a < expected {
            assert!(!slides && x.abs() < 1e-6, "{a}°: moved {x} m");
        } else if row[3] == "given" {
            assert!(slides, "{a}°: moved only {x} m");
            assert!(
                (x / predicted - 1.0).abs() < 0.01,
                "{a}°: slid {x} m, Coulomb {predicted} m"
            );
        }
    }
}

/// The threshold follows `contacts.friction`: with μ = 0.5 it is atan(0.5) = 26.57° within 0.5°.
#[test]
fn tilt_threshold_follows_the_friction() {
    let p = prepare(
        Path::new("scenarios/tilt_friction.toml"),
        None,
        &["contacts.friction=0.5".into()],
    )
    .unwrap();
    let spec = p.scenario.tilt.as_ref().unwrap();
    let setup = TiltSetup::from_scenario(&p.scenario, spec);
    let search = tilt_threshold(&setup, &[20.0, 26.0, 27.0, 35.0], 0.1).unwrap();
    let (lo, hi) = search.bracket.expect("bracketed");
    let expected = 0.5f64.atan().to_degrees();
    assert!(hi - lo <= 0.1);
    assert!(
        (0.5 * (lo + hi) - expected).abs() < 0.5,
        "threshold {lo}–{hi}° vs {expected}°"
    );
}
