//! Validation case: steel balls dropped into paste backfill (f-EDEM §4.2, Table 4, Fig. 16).
//! Scenario: `scenarios/paste_single_ball.toml`. Reference: an independent integration of the
//! same equation of motion (free fall in air, then m dv/dt = (m − m_f) g − F_d(v) with f-EDEM's
//! Bingham drag, eq. 9/14/19) by classical RK4 with a 1e-6 s step and event location at v = 0.

use super::{prepare, scene};
use crate::fluid::bingham::{bingham_drag_n, bingham_static_resistance_n};
use crate::fluid::sphere_mass_kg;
use crate::scenes::free_settling::{run, RunOptions, StopReason};
use std::path::Path;

const RHO_F: f64 = 1843.0;
const TAU_Y: f64 = 136.0;
const ETA_B: f64 = 0.7;
const G: f64 = 9.81;

/// Settling distance of the ball's lowest point, by RK4 on (x, v) after entry at sqrt(2 g H).
fn reference_settling_distance(d: f64, h_fall: f64) -> f64 {
    let m = sphere_mass_kg(d, 8135.0);
    let w = (m - sphere_mass_kg(d, RHO_F)) * G;
    assert!(
        w < bingham_static_resistance_n(d, TAU_Y),
        "the ball must stop"
    );
    let acc = |v: f64| (w - bingham_drag_n(RHO_F, d, TAU_Y, ETA_B, v.max(1e-300))) / m;
    let (mut x, mut v) = (0.0f64, (2.0 * G * h_fall).sqrt());
    let h = 1e-6;
    while v > 0.0 {
        let (k1x, k1v) = (v, acc(v));
        let (k2x, k2v) = (v + 0.5 * h * k1v, acc(v + 0.5 * h * k1v));
        let (k3x, k3v) = (v + 0.5 * h * k2v, acc(v + 0.5 * h * k2v));
        let (k4x, k4v) = (v + h * k3v, acc(v + h * k3v));
        let v_new = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if v_new <= 0.0 {
            // Stop inside the step: the deceleration is nearly constant there.
            let t_stop = h * v / (v - v_new);
            return x + 0.5 * v * t_stop;
        }
        x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        v = v_new;
    }
    x
}

/// Acceptance: every single-ball settling distance (full submergence) agrees with the
/// independent integration within 1 %; the ball released on the surface (H_f = 0) never moves.
#[test]
fn settling_distances_match_an_independent_integration() {
    let p = prepare(Path::new("scenarios/paste_single_ball.toml"), None, &[]).unwrap();
    assert_eq!(p.spheres.len(), 18);
    for dt in [1e-5, 1e-4] {
        let opts = RunOptions {
            dt_s: dt,
            integrator: p.common.time.integrator,
            timeseries: false,
        };
        for r in run(scene(&p), &p.spheres, opts).unwrap() {
            let d = r.case.spec.diameter_m;
            let hf = r.case.fall_height_m.unwrap();
            assert_eq!(r.stop, StopReason::Static, "{} did not stop", r.case.id);
            if hf == 0.0 {
                assert_eq!(r.final_bottom_depth_m, 0.0, "{}", r.case.id);
                continue;
            }
            let reference = reference_settling_distance(d, hf);
            let err = r.final_bottom_depth_m / reference - 1.0;
            assert!(
                err.abs() < 0.01,
                "{} at dt {dt}: {} vs {reference} ({err:+.2e})",
                r.case.id,
                r.final_bottom_depth_m
            );
            let entry = r.entry_velocity_m_s.unwrap();
            assert!(
                (entry / (2.0 * G * hf).sqrt() - 1.0).abs() < 1e-9,
                "{}: entry {entry}",
                r.case.id
            );
        }
    }
}

/// Partial submergence: a ball released at rest on the surface sinks to its static balance,
/// weight − cap buoyancy = static resistance × immersed area fraction, and stops there.
#[test]
fn partial_submergence_sinks_a_ball_at_rest_to_its_static_balance() {
    let p = prepare(
        Path::new("scenarios/paste_single_ball.toml"),
        None,
        &["fluid.submergence=partial".into()],
    )
    .unwrap();
    let opts = RunOptions {
        dt_s: 1e-5,
        integrator: p.common.time.integrator,
        timeseries: false,
    };
    for r in run(scene(&p), &p.spheres, opts).unwrap() {
        if r.case.fall_height_m != Some(0.0) {
            continue;
        }
        assert_eq!(r.stop, StopReason::Static);
        let d = r.case.spec.diameter_m;
        let h = r.final_bottom_depth_m;
        assert!(h > 0.0 && h < d, "{}: {h}", r.case.id);
        let (rad, m) = (0.5 * d, sphere_mass_kg(d, 8135.0));
        let cap = std::f64::consts::PI * h * h * (3.0 * rad - h) / 3.0;
        let net = m * G - RHO_F * cap * G;
        let area_frac = h * (2.0 * rad - h) / (rad * rad);
        let resist = bingham_static_resistance_n(d, TAU_Y) * area_frac;
        // At rest the static resistance holds the ball: net ≤ resistance. With inertia the ball
        // overshoots the equilibrium depth a little, so resistance ≥ net, within a factor 2.
        assert!(
            net <= resist * (1.0 + 1e-9),
            "{}: net {net} > resistance {resist}",
            r.case.id
        );
        assert!(
            resist < 2.0 * net,
            "{}: stopped far beyond its balance",
            r.case.id
        );
    }
}
