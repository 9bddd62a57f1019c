//! Contact calibration of f-EDEM (Zhang & Li 2024), Appendices II and III.
//!
//! - `scenarios/restitution_drop.toml`: an 8 mm steel ball (8135 kg/m³) dropped in air on a steel
//!   plate from 95–398 mm, rebound heights of Table A2, with the speed-dependent restitution
//!   e(v) = 0.6318 (v / 1 m/s)^(−0.0492) calibrated on them (f-EDEM: constant e = 0.612).
//! - `scenarios/tilt_friction.toml`: a steel block on a tilted steel plate, μ_s = 0.341 of
//!   Table A3: sticks below atan(0.341) = 18.83°, slides above.
//!
//! f-EDEM states that its simulated rebounds "match the test results perfectly" and the issue asks
//! for 3 %; no constant e can do that for Table A2 (see
//! `no_constant_restitution_matches_table_a2_within_3_percent`). The scenario therefore uses a
//! speed-dependent law, and the drop is checked three ways: Rapier's contact restitution equals
//! the law at the impact speed, the rebound equals an independent integration of the same fall and
//! rise in air, and each height is within 3 % of the measurement. Because the law is calibrated
//! on those five heights, its predictive error is stated too (leave-one-out, 4.4 %).

use crate::common::{col, read_csv, tmp};
use settle::contact::{constant_fit, restitution_fits, RestitutionLaw};
use settle::fluid::{buoyancy_n, sphere_mass_kg, DragLaw, SphereDrag};

const G: f64 = 9.81;
/// f-EDEM Table A2: drop heights and measured rebound heights, m.
#[allow(clippy::approx_constant)] // 0.318 m is a drop height, not 1/π
const DROP_M: [f64; 5] = [0.095, 0.188, 0.252, 0.318, 0.398];
const REBOUND_M: [f64; 5] = [0.0370, 0.0720, 0.0909, 0.1180, 0.1469];

/// Rebound apex of the ball's lowest point after a drop from `h` in air (Dallavalle drag,
/// buoyancy), the plate reversing the velocity with factor `e(impact speed)`: RK4 with a 1 µs
/// step, impact and apex located within the step. Independent of Rapier and of the engine's
/// integrators.
fn reference_rebound(h: f64, e: impl Fn(f64) -> f64) -> f64 {
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
    let (mut z, mut v) = (0.0, -e(v.abs()) * v);
    loop {
        let (z1, v1) = rk4(z, v, dt);
        if v1 <= 0.0 {
            return z + v * v / (2.0 * G);
        }
        (z, v) = (z1, v1);
    }
}

/// The effective scenario (defaults filled in) as TOML values.
fn effective(scenario: &settle::Scenario) -> toml::Table {
    scenario.to_toml().unwrap().parse().unwrap()
}

/// The number `key` of the TOML table `t`.
fn number(t: &toml::Value, key: &str) -> f64 {
    let v = &t[key];
    v.as_float()
        .or_else(|| v.as_integer().map(|i| i as f64))
        .unwrap_or_else(|| panic!("`{key}` is not a number: {v}"))
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
/// - Rapier's contact restitution (lift-off / impact speed at the plate) is the law's e(v) at the
///   impact speed within 0.1 % (the contact-modification hook sets it per manifold);
/// - the rebound is within 0.1 % of `reference_rebound` (same fall and rise in air, integrated
///   independently) and within 0.5 % of the vacuum rebound e(v)²H: air drag (Re ≈ 1500 at impact)
///   lowers it by 0.13 % (95 mm) to 0.46 % (398 mm);
/// - each rebound is within 3 % of Table A2 (the acceptance of issue 5, item 4);
/// - `fit.csv` reports the scenario's law as the minimax power fit, and the constant e's 3.83 %.
#[test]
fn restitution_drop_reproduces_the_law_and_table_a2_within_3_percent() {
    let scenario = settle::load("scenarios/restitution_drop.toml").unwrap();
    let contacts = &effective(&scenario)["contacts"];
    let law = RestitutionLaw {
        coefficient: number(contacts, "restitution"),
        exponent: number(contacts, "restitution_exponent"),
        reference_speed_m_s: number(contacts, "restitution_reference_speed_m_s"),
    };
    assert!(law.is_speed_dependent());
    let dir = tmp();
    let out = scenario.run().unwrap().write(dir.path()).unwrap();
    assert!(out.join("rebound_height.svg").is_file());
    assert!(out.join("run.toml").is_file());
    let (header, rows) = read_csv(&out.join("summary.csv"));
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
        let impact = col(&header, row, "impact_speed_m_s");
        assert_eq!(h, DROP_M[i]);
        assert_eq!(measured, REBOUND_M[i]);
        let e = law.at(impact);
        assert!(
            (e_eff / e - 1.0).abs() < 1e-3,
            "H = {h}: contact e {e_eff} vs law {e}"
        );
        let reference = reference_rebound(h, |v| law.at(v));
        assert!(
            (hr / reference - 1.0).abs() < 1e-3,
            "H = {h}: rebound {hr} vs reference {reference}"
        );
        let vacuum = law.at((2.0 * G * h).sqrt()).powi(2) * h;
        assert!(
            hr < vacuum && hr / vacuum - 1.0 > -5e-3,
            "H = {h}: rebound {hr} vs e²H {vacuum}"
        );
        let err = hr / measured - 1.0;
        assert!((err - col(&header, row, "rel_error")).abs() < 1e-12);
        assert!(err.abs() < 0.03, "H = {h}: {err:+.4} against Table A2");
    }
    let (fh, fit) = read_csv(&out.join("fit.csv"));
    let row = |model: &str| {
        fit.iter()
            .find(|r| r[0] == model)
            .unwrap_or_else(|| panic!("no {model} row in fit.csv"))
            .clone()
    };
    let sim = row("scenario_simulated");
    assert_eq!(col(&fh, &sim, "heights_within_tolerance"), 5.0);
    assert!(col(&fh, &sim, "max_rel_error") < 0.03);
    assert!(col(&fh, &row("constant_minimax"), "max_rel_error") > 0.038);
    let power = row("power_minimax");
    assert!((col(&fh, &power, "restitution") - law.coefficient).abs() < 1e-4);
    assert!((col(&fh, &power, "restitution_exponent") - law.exponent).abs() < 1e-4);
}

/// The power law is a calibration on five points: what it predicts at a height it was not fitted
/// on (leave-one-out) is worse than what it fits. Both figures against an independent
/// brute-force minimax (grid over k, midrange of ln e): fitted 2.30 %, predicted 4.38 %; a
/// constant e fits 3.83 % and predicts 5.07 %.
#[test]
fn restitution_fits_state_fitted_and_predicted_errors() {
    let fits = restitution_fits(&DROP_M, &REBOUND_M, G, 1.0);
    let get = |m: &str| *fits.iter().find(|f| f.model == m).unwrap();
    // Brute force: k on a 1e-5 grid.
    let brute = |idx: &[usize]| {
        let mut best = (f64::INFINITY, 0.0, 0.0);
        for i in 0..=20_000 {
            let k = i as f64 * 1e-5;
            let r: Vec<f64> = idx
                .iter()
                .map(|&j| {
                    0.5 * (REBOUND_M[j] / DROP_M[j]).ln() + k * (2.0 * G * DROP_M[j]).sqrt().ln()
                })
                .collect();
            let lo = r.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = r.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            if hi - lo < best.0 {
                best = (hi - lo, k, (0.5 * (hi + lo)).exp());
            }
        }
        best
    };
    let (range, k, e_ref) = brute(&[0, 1, 2, 3, 4]);
    let power = get("power_minimax");
    assert!((power.law.exponent - k).abs() < 2e-5, "{power:?} vs k {k}");
    assert!((power.law.coefficient - e_ref).abs() < 1e-5);
    assert!((power.max_rel_error - (range.exp() - 1.0)).abs() < 1e-6);
    assert!((power.max_rel_error - 0.0230).abs() < 5e-4);
    let mut loo: f64 = 0.0;
    for out in 0..5 {
        let idx: Vec<usize> = (0..5).filter(|&j| j != out).collect();
        let (_, k, e_ref) = brute(&idx);
        let e = e_ref * (2.0 * G * DROP_M[out]).sqrt().powf(-k);
        loo = loo.max((e * e * DROP_M[out] / REBOUND_M[out] - 1.0).abs());
    }
    let predicted = power.leave_one_out_max_rel_error.unwrap();
    assert!((predicted - loo).abs() < 1e-3, "{predicted} vs {loo}");
    assert!((predicted - 0.0438).abs() < 1e-3);
    let constant = get("constant_minimax");
    assert!((constant.max_rel_error - 0.0383).abs() < 5e-4);
    assert!((constant.leave_one_out_max_rel_error.unwrap() - 0.0507).abs() < 1e-3);
    assert!(predicted > power.max_rel_error && constant.max_rel_error > power.max_rel_error);
}

/// `settle run scenarios/tilt_friction.toml` (μ = 0.341, dt = 1e-4 s, 1 s per angle):
/// - the threshold found by bisection (bracket ≤ 0.1° wide) is within 0.5° of atan(0.341) =
///   18.83° (the acceptance of issue 5, item 5);
/// - every given angle below atan μ sticks (displacement < 1 µm) and every one above slides;
/// - sliding follows Coulomb's law with the same μ (Rapier has one coefficient, static =
///   dynamic): displacement ½ g (sin θ − μ cos θ) t² within 1 % at the given sliding angles.
#[test]
fn tilt_threshold_is_atan_mu() {
    let scenario = settle::load("scenarios/tilt_friction.toml").unwrap();
    let eff = effective(&scenario);
    let angles = eff["tilt"]["angles_deg"]
        .as_array()
        .expect("tilt.angles_deg")
        .len();
    let duration_s = number(&eff["tilt"], "duration_s");
    let mu = number(&eff["contacts"], "friction");
    assert_eq!(mu, 0.341);
    let expected = mu.atan().to_degrees();
    let dir = tmp();
    let out = scenario.run().unwrap().write(dir.path()).unwrap();
    assert!(out.join("tilt_displacement.svg").is_file());
    let (th, t) = read_csv(&out.join("threshold.csv"));
    let found = col(&th, &t[0], "threshold_deg");
    let width = col(&th, &t[0], "slides_at_deg") - col(&th, &t[0], "sticks_at_deg");
    assert!(width > 0.0 && width <= 0.1, "bracket {width}°");
    assert!(
        (found - expected).abs() < 0.5,
        "threshold {found}° vs atan(μ) {expected}°"
    );

    let (header, rows) = read_csv(&out.join("summary.csv"));
    assert_eq!(header[..3], ["angle_deg", "displacement_m", "slides"]);
    let given = rows.iter().filter(|r| r[3] == "given").count();
    assert_eq!(given, angles);
    for row in &rows {
        let a = col(&header, row, "angle_deg");
        let x = col(&header, row, "displacement_m");
        let slides: bool = row[2].parse().unwrap();
        let th = a.to_radians();
        let predicted = 0.5 * G * (th.sin() - mu * th.cos()) * duration_s.powi(2);
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

// The drop's and the tilt's own units (the restitution and added mass through the drop's
// simulation, the threshold search): `scenes::restitution_drop::tests` and
// `scenes::tilt_friction::tests` (unit tests).
