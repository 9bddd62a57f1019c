//! The funnel pour (f-EDEM §4.2) and the engine features it needs: rolling resistance, the
//! yield-stress hold of balls at rest in paste, fluid only below a free surface.

use settle::dynamics::Integrator;
use settle::engine::{dim3, EngineSettings};
use settle::fluid::{DragLaw, SphereDrag};

const G: f64 = 9.81;
const D: f64 = 0.0126;
const RHO_STEEL: f64 = 8135.0;
const RHO_PASTE: f64 = 1843.0;

fn paste(d: f64) -> SphereDrag {
    SphereDrag::new(
        DragLaw::Bingham {
            yield_stress_pa: 136.0,
            plastic_viscosity_pa_s: 0.7,
        },
        d,
        RHO_PASTE,
    )
}

/// No fluid: a Stokes law of zero viscosity in a fluid of zero density.
fn air(d: f64) -> SphereDrag {
    SphereDrag::new(
        DragLaw::Stokes {
            viscosity_pa_s: 0.0,
        },
        d,
        0.0,
    )
}

fn v3(x: f64, y: f64, z: f64) -> dim3::Vector {
    dim3::Vector::new(x, y, z)
}

// ---------------------------------------------------------------------------------------------
// Rolling resistance.

/// A steel ball launched sliding at `v0` along x on a plate (friction 0.341, no fluid) with
/// rolling resistance `mu_r`: returns (t, v_x, ω_y) every `every` steps.
fn rolling_ball(mu_r: f64, v0: f64, dt: f64, t_end: f64, every: usize) -> Vec<(f64, f64, f64)> {
    let mut settings = EngineSettings::for_scene(D, 1.0);
    settings.friction = 0.341;
    let mut world = dim3::World::new(settings, G);
    world.add_floor(0.0);
    let mut ball = dim3::FluidBody::at_rest(v3(0.0, 0.0, 0.5 * D), D, RHO_STEEL, air(D), G);
    ball.velocity_m_s = v3(v0, 0.0, 0.0);
    let id = world.add_sphere(ball);
    world.set_rolling_resistance(mu_r);
    let steps = (t_end / dt).round() as usize;
    let mut out = Vec::new();
    for k in 1..=steps {
        world.step(dt, Integrator::Exponential).expect("stable");
        if k % every == 0 {
            let w = world.angular_velocity_rad_s(id);
            out.push((world.time_s(), world.velocity_m_s(id)[0], w[1]));
        }
    }
    out
}

#[test]
fn probe_rolling() {
    for (mu, t_end) in [(0.002, 1.0), (0.05, 0.6)] {
        let out = rolling_ball(mu, 0.1, 1e-5, t_end, 5000);
        for (t, v, w) in &out {
            println!("mu {mu} t {t:.3} v {v:.6} w*r {:.6}", w * 0.5 * D);
        }
    }
}

/// Two steel balls in paste (everywhere): one on the floor, one resting on it with its contact
/// normal tilted `tilt_deg` from the vertical. Returns the upper ball's largest displacement from
/// its position after `settle_s`, over the following `t_s`, and its final speed.
fn ball_on_ball(hold: bool, tilt_deg: f64, dt: f64, settle_s: f64, t_s: f64) -> (f64, f64) {
    let mut settings = EngineSettings::for_scene(D, 1.0);
    settings.friction = 0.341;
    let mut world = dim3::World::new(settings, G);
    world.set_yield_hold(hold);
    world.add_floor(0.0);
    let a = tilt_deg.to_radians();
    world.add_sphere(dim3::FluidBody::at_rest(
        v3(0.0, 0.0, 0.5 * D),
        D,
        RHO_STEEL,
        paste(D),
        G,
    ));
    let top = world.add_sphere(dim3::FluidBody::at_rest(
        v3(D * a.sin(), 0.0, 0.5 * D + D * a.cos()),
        D,
        RHO_STEEL,
        paste(D),
        G,
    ));
    let n_settle = (settle_s / dt).round() as usize;
    for _ in 0..n_settle {
        world.step(dt, Integrator::Exponential).expect("stable");
    }
    let x0 = world.position_m(top);
    let mut worst: f64 = 0.0;
    for _ in 0..(t_s / dt).round() as usize {
        world.step(dt, Integrator::Exponential).expect("stable");
        worst = worst.max((world.position_m(top) - x0).norm());
    }
    (worst, world.velocity_m_s(top).norm())
}

#[test]
fn probe_creep() {
    for hold in [true, false] {
        for tilt in [0.0, 30.0, 60.0] {
            let (w, v) = ball_on_ball(hold, tilt, 1e-5, 0.01, 1.0);
            println!("hold {hold} tilt {tilt} creep {w:.3e} m speed {v:.3e}");
        }
    }
}
