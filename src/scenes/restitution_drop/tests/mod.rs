//! Unit tests of the restitution drop (moved from `tests/scenes/restitution_drop_and_tilt.rs`,
//! f-EDEM Appendix II): the drop's simulation follows the scenario's restitution law, and the
//! added mass in air.

use crate::contact::RestitutionLaw;
use crate::fluid::{buoyancy_n, sphere_mass_kg, DragLaw, SphereDrag};
use crate::scenes::restitution_drop::{drop_settings, simulate_drop, Setup};
use crate::scenes::tests::prepare;
use std::path::Path;

const G: f64 = 9.81;

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

/// The contact restitution follows a constant `contacts.restitution` (not halved by a plate left
/// at e = 0, as Rapier's average combine rule would do): 0.3, 0.612 (f-EDEM) and 0.9 within 0.1 %,
/// from 188 mm.
#[test]
fn restitution_follows_the_scenario_value() {
    for e in [0.3, 0.612, 0.9] {
        let p = prepare(
            Path::new("scenarios/restitution_drop.toml"),
            None,
            &[
                format!("contacts.restitution={e}"),
                "contacts.restitution_exponent=0".into(),
            ],
        )
        .unwrap();
        let setup = Setup::of(p.scene.restitution_drop().unwrap());
        let settings = drop_settings(&p.common, &setup, 0.188);
        let o = simulate_drop(&p.common, &setup, 0.188, settings).unwrap();
        assert!(
            (o.restitution_effective / e - 1.0).abs() < 1e-3,
            "e = {e}: contact e {}",
            o.restitution_effective
        );
        let reference = reference_rebound(0.188, |_| e);
        assert!(
            (o.rebound_height_m / reference - 1.0).abs() < 1e-3,
            "e = {e}: rebound {} vs {reference}",
            o.rebound_height_m
        );
    }
}

/// A speed-dependent law reaches Rapier through the contact-modification hook: with a steep
/// k = 0.5 about 2 m/s, the contact e from 95 mm (1.37 m/s) and 398 mm (2.79 m/s) follows
/// e(v) = 0.5 (v/2)^(−1/2) within 0.1 % (0.605 and 0.423), far from any constant.
#[test]
fn speed_dependent_restitution_reaches_the_contact() {
    let law = RestitutionLaw {
        coefficient: 0.5,
        exponent: 0.5,
        reference_speed_m_s: 2.0,
    };
    let p = prepare(
        Path::new("scenarios/restitution_drop.toml"),
        None,
        &[
            "contacts.restitution=0.5".into(),
            "contacts.restitution_exponent=0.5".into(),
            "contacts.restitution_reference_speed_m_s=2".into(),
        ],
    )
    .unwrap();
    let setup = Setup::of(p.scene.restitution_drop().unwrap());
    let settings = drop_settings(&p.common, &setup, 0.398);
    for h in [0.095, 0.398] {
        let o = simulate_drop(&p.common, &setup, h, settings).unwrap();
        let e = law.at(o.impact_speed_m_s);
        assert!(
            (o.restitution_effective / e - 1.0).abs() < 1e-3,
            "H = {h}: contact e {} vs law {e}",
            o.restitution_effective
        );
    }
}

#[test]
fn added_mass_in_the_drop_is_off_bit_for_bit_at_zero_and_tiny_in_air() {
    // `[transient]` with C_m = 0 drops exactly as without it; with C_m = ½ in air the ball's
    // inertia grows by ½ ρ_air/ρ_steel = 7.4e-5: its fall and rise in air (drag ~0.4 % of the
    // rebound) change by far less than 1e-3, the contact's restitution not at all.
    let drop = |extra: &[&str]| {
        let ov: Vec<String> = extra.iter().map(|s| s.to_string()).collect();
        let p = prepare(Path::new("scenarios/restitution_drop.toml"), None, &ov).unwrap();
        let setup = Setup::of(p.scene.restitution_drop().unwrap());
        let settings = drop_settings(&p.common, &setup, 0.398);
        simulate_drop(&p.common, &setup, 0.398, settings).unwrap()
    };
    let off = drop(&[]);
    let zero = drop(&[
        "transient.added_mass=true",
        "transient.added_mass_coefficient=0",
    ]);
    let half = drop(&["transient.added_mass=true"]);
    assert_eq!(off, zero);
    let rel = half.rebound_height_m / off.rebound_height_m - 1.0;
    println!(
        "398 mm: rebound {} m off, {} m with added mass ({rel:+.2e}); e {} / {}",
        off.rebound_height_m,
        half.rebound_height_m,
        off.restitution_effective,
        half.restitution_effective
    );
    assert_ne!(off, half);
    assert!(rel.abs() < 1e-3, "{rel}");
}
