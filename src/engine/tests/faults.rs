//! Numerical faults of the Rapier engine stop the run with the body, the time, the quantity and
//! a suggested dt (issue 8), beyond the explicit integrator's instability (`engine/rest.rs`):
//! contacts overlapping deeper than a fraction of the diameter, and bodies leaving the domain.

use crate::dynamics::Integrator;
use crate::engine::{dim2, dim3, EngineSettings};
use crate::fluid::{DragLaw, SphereDrag};

const G: f64 = 9.81;

fn water(d: f64) -> SphereDrag {
    SphereDrag::new(
        DragLaw::Stokes {
            viscosity_pa_s: 1e-3,
        },
        d,
        1000.0,
    )
}

/// A 1 mm steel ball on a floor whose contact is far too soft (2 Hz instead of 1e4 Hz): it sinks
/// by g′/(2πf)² ≈ 53 mm at rest, through the floor. The run stops once the overlap passes
/// 0.25 d, naming body 0, the depth and a smaller dt, and not before: the overlap reported lies
/// between 0.25 d and 0.25 d plus one step's travel.
#[test]
fn deep_penetration_stops_the_run() {
    let d = 1e-3;
    let mut settings = EngineSettings::for_scene(d, 0.1);
    settings.contact_natural_frequency_hz = 2.0;
    let mut world = dim3::World::new(settings, G);
    world.add_floor(0.0);
    world.add_sphere(dim3::FluidBody::at_rest(
        dim3::Vector::new(0.0, 0.0, 0.5 * d),
        d,
        7800.0,
        water(d),
        G,
    ));
    let dt = 1e-4;
    let mut err = None;
    for _ in 0..100_000 {
        if let Err(e) = world.step(dt, Integrator::Exponential) {
            err = Some(e);
            break;
        }
    }
    let e = err.expect("the run must stop");
    let msg = e.to_string();
    assert_eq!(e.body, "body 0", "{msg}");
    assert!(msg.contains("try dt ≤ 5.000e-5 s"), "{msg}");
    assert!(e.what.starts_with("penetration depth, m = "), "{msg}");
    let depth: f64 = e.what.rsplit(' ').next().unwrap().parse().unwrap();
    assert!(depth >= 0.25 * d && depth < 0.3 * d, "{msg}"); // printed to 4 digits
    assert!(e.stable_dt_s < dt && e.time_s > 0.0, "{msg}");
}

/// Two discs placed overlapping by half a diameter (bad initial positions) stop the run at the
/// first step.
#[test]
fn overlapping_start_stops_at_the_first_step() {
    let d = 1e-4;
    let mut world = dim2::World::new(EngineSettings::for_scene(d, 1e-2), G);
    for x in [0.0, 0.5 * d] {
        world.add_sphere(dim2::FluidBody::at_rest(
            dim2::Vector::new(x, 1.0),
            d,
            2650.0,
            water(d),
            G,
        ));
    }
    let e = world.step(1e-5, Integrator::Exponential).unwrap_err();
    assert_eq!(e.step, 1, "{e}");
    assert!(e.what.starts_with("penetration depth"), "{e}");
}

/// A ball thrown upwards at 10 m/s in air, in a domain of radius 1 m, stops the run when it
/// leaves: at t = (10 − √(100 − 2g))/g = 0.1055 s (air drag neglected: it delays the exit by
/// < 1 %), within 1 % plus a step.
#[test]
fn leaving_the_domain_stops_the_run() {
    let d = 0.01;
    let mut settings = EngineSettings::for_scene(d, 10.0);
    settings.max_distance_m = Some(1.0);
    let mut world = dim3::World::new(settings, G);
    let air = SphereDrag::new(
        DragLaw::Dallavalle {
            viscosity_pa_s: 1.8e-5,
            voidage: 1.0,
        },
        d,
        1.2,
    );
    let mut ball = dim3::FluidBody::at_rest(dim3::Vector::zeros(), d, 7800.0, air, G);
    ball.velocity_m_s = dim3::Vector::new(0.0, 0.0, 10.0);
    world.add_sphere(ball);
    let dt = 1e-4;
    let e = (0..10_000)
        .find_map(|_| world.step(dt, Integrator::Exponential).err())
        .expect("the ball leaves the domain");
    let t_exit = (10.0 - (100.0 - 2.0 * G).sqrt()) / G;
    assert!(e.what.starts_with("distance from the origin"), "{e}");
    assert!(
        (e.time_s - t_exit).abs() < 0.01 * t_exit + dt,
        "stopped at {} s, expected {t_exit} s: {e}",
        e.time_s
    );
}

/// A resting pile is not a fault: 20 discs of 10 µm settle into a pile without tripping the
/// penetration check (overlaps ~1e-3 d).
#[test]
fn a_resting_pile_is_not_a_fault() {
    let d = 1e-5;
    let mut world = dim2::World::new(EngineSettings::for_scene(d, 1e-3), G);
    world.add_floor(0.0);
    for i in 0..20 {
        let x = (i % 5) as f64 * 1.05 * d;
        let y = (0.6 + (i / 5) as f64 * 1.1) * d;
        world.add_sphere(dim2::FluidBody::at_rest(
            dim2::Vector::new(x, y),
            d,
            2650.0,
            water(d),
            G,
        ));
    }
    for _ in 0..2000 {
        world
            .step(1e-4, Integrator::Exponential)
            .expect("no fault in a resting pile");
    }
}
