//! The Rapier engine wrapper (`crate::engine`): free fall against the analytic Stokes solution,
//! grains coming to rest on a floor and in a small pile, and the instability report of the explicit
//! integrator.
//!
//! `cargo test --release --test main engine::rest:: -- --ignored --nocapture` prints the dt
//! survey behind the chosen steps (penetration, contact force / net weight, residual speed for
//! each grain size and dt).

use crate::dynamics::Integrator;
use crate::engine::{dim2, dim3, ContactDrag, EngineSettings};
use crate::fluid::{DragLaw, SphereDrag};

const G: f64 = 9.81;
const WATER_RHO: f64 = 1000.0;
const WATER_MU: f64 = 1e-3;

fn stokes(d: f64) -> SphereDrag {
    SphereDrag::new(
        DragLaw::Stokes {
            viscosity_pa_s: WATER_MU,
        },
        d,
        WATER_RHO,
    )
}

/// Stokes terminal velocity (buoyancy included) and response time of a sphere in water.
fn stokes_vt_tau(d: f64, rho_p: f64) -> (f64, f64) {
    let vt = d * d * (rho_p - WATER_RHO) * G / (18.0 * WATER_MU);
    let tau = rho_p * d * d / (18.0 * WATER_MU);
    (vt, tau)
}

fn net_weight_n(d: f64, rho_p: f64) -> f64 {
    (rho_p - WATER_RHO) * std::f64::consts::PI * d.powi(3) / 6.0 * G
}

// ---------------------------------------------------------------------------------------------
// 1. Free fall through Rapier = the analytic solution, at small and large dt.

fn free_sphere_3d(
    d: f64,
    rho_p: f64,
    integrator: Integrator,
    dt: f64,
    steps: usize,
) -> Vec<(f64, f64, f64)> {
    let (vt, _) = stokes_vt_tau(d, rho_p);
    let mut world = dim3::World::new(EngineSettings::for_scene(d, vt), G);
    let id = world.add_sphere(dim3::FluidBody::at_rest(
        dim3::Vector::zeros(),
        d,
        rho_p,
        stokes(d),
        G,
    ));
    let mut out = Vec::with_capacity(steps);
    for _ in 0..steps {
        world
            .step(dt, integrator)
            .expect("free sphere stays stable");
        let x = world.position_m(id);
        let v = world.velocity_m_s(id);
        assert_eq!(
            (x[0], x[1], v[0], v[1]),
            (0.0, 0.0, 0.0, 0.0),
            "motion stays vertical"
        );
        out.push((world.time_s(), -x[2], -v[2]));
    }
    out
}

#[test]
fn free_sphere_matches_the_analytic_stokes_solution_at_any_dt() {
    let (d, rho_p) = (1e-4, 2700.0);
    let (vt, tau) = stokes_vt_tau(d, rho_p);
    for (dt, steps) in [(1e-5, 2000), (1e-2, 10)] {
        let mut worst: f64 = 0.0;
        for (t, depth, speed) in free_sphere_3d(d, rho_p, Integrator::Exponential, dt, steps) {
            let e = (-t / tau).exp();
            let v_exact = vt * (1.0 - e);
            let x_exact = vt * (t - tau * (1.0 - e));
            let ev = (speed / v_exact - 1.0).abs();
            let ex = (depth / x_exact - 1.0).abs();
            assert!(ev < 1e-6, "dt {dt}, t {t}: v = {speed}, exact {v_exact}");
            assert!(ex < 1e-6, "dt {dt}, t {t}: x = {depth}, exact {x_exact}");
            worst = worst.max(ev).max(ex);
        }
        eprintln!(
            "dt = {dt:e} s (dt/tau = {:.3}): worst relative error {worst:.1e}",
            dt / tau
        );
    }
}

// ---------------------------------------------------------------------------------------------
// 3. The explicit integrator beyond 2τ is reported, not hidden by Rapier's speed cap.

#[test]
fn explicit_drag_beyond_two_tau_is_reported_unstable() {
    let (d, rho_p) = (1e-4, 2700.0);
    let (vt, tau) = stokes_vt_tau(d, rho_p);
    // The 2d sphere sets the speed scale (4 v_t).
    let mut world = dim3::World::new(EngineSettings::for_scene(d, 4.0 * vt), G);
    let _other = world.add_sphere(dim3::FluidBody::at_rest(
        dim3::Vector::new(1.0, 0.0, 0.0),
        2.0 * d,
        rho_p,
        stokes(2.0 * d),
        G,
    ));
    let id = world.add_sphere(dim3::FluidBody::at_rest(
        dim3::Vector::zeros(),
        d,
        rho_p,
        stokes(d),
        G,
    ));
    // τ is 4× longer for the 2d sphere: dt = 2.7 τ is unstable only for `id`.
    let dt = 2.7 * tau;
    let err = (0..1000)
        .find_map(|_| world.step(dt, Integrator::Explicit).err())
        .expect("explicit drag at dt > 2τ must be reported");
    eprintln!("{err}");
    assert_eq!(err.body, id.to_string());
    assert!(
        err.stable_dt_s <= 2.0 * tau,
        "suggested {} s, 2τ = {} s",
        err.stable_dt_s,
        2.0 * tau
    );
    assert!(err.what.contains("speed"), "{}", err.what);
    let line = err.to_string();
    assert!(
        line.contains("body 1") && line.contains("largest stable dt") && !line.contains('\n'),
        "{line}"
    );
    // A refused step leaves the world as it was: retried at the suggested dt, it recovers.
    for _ in 0..50 {
        world
            .step(err.stable_dt_s, Integrator::Explicit)
            .expect("stable at the suggested dt");
    }
    let v = -world.velocity_m_s(id)[2];
    assert!((v / vt - 1.0).abs() < 1e-3, "v = {v}, v_t = {vt}");

    // Below 2τ the same scene runs, and the exponential integrator runs at any dt.
    for (integrator, dt) in [
        (Integrator::Explicit, 0.5 * tau),
        (Integrator::Exponential, 100.0 * tau),
    ] {
        let mut world = dim3::World::new(EngineSettings::for_scene(d, vt), G);
        world.add_sphere(dim3::FluidBody::at_rest(
            dim3::Vector::zeros(),
            d,
            rho_p,
            stokes(d),
            G,
        ));
        for _ in 0..200 {
            world.step(dt, integrator).expect("stable");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 2. Grains settling onto a floor (2D) and into a small pile.

/// What a grain looks like once it has come to rest on the floor.
#[derive(Debug)]
struct Rest {
    /// Penetration into the floor / d.
    penetration: f64,
    /// Vertical contact force / net weight.
    force_ratio: f64,
    /// Residual speed / terminal velocity.
    speed_ratio: f64,
}

/// A grain of diameter `d` released `gap` diameters above a floor at y = 0, stepped at `dt` until
/// `settle_s` after it should have landed; `None` if the step failed.
fn grain_on_floor_2d(d: f64, rho_p: f64, dt: f64, gap: f64, contact: ContactDrag) -> Option<Rest> {
    let (vt, tau) = stokes_vt_tau(d, rho_p);
    let mut settings = EngineSettings::for_scene(d, vt);
    settings.contact_drag = contact;
    let mut world = dim2::World::new(settings, G);
    world.add_floor(0.0);
    let id = world.add_sphere(dim2::FluidBody::at_rest(
        dim2::Vector::new(0.0, (0.5 + gap) * d),
        d,
        rho_p,
        stokes(d),
        G,
    ));
    // Fall time + 20 τ + 20 ms of contact settling, in whole steps.
    let t_end = gap * d / vt + 20.0 * tau + 0.02;
    let steps = (t_end / dt).ceil() as usize;
    for _ in 0..steps {
        world.step(dt, Integrator::Exponential).ok()?;
        assert!(
            !world.is_sleeping(id),
            "grain fell asleep at t = {} s",
            world.time_s()
        );
    }
    let y = world.position_m(id)[1];
    Some(Rest {
        penetration: (0.5 * d - y) / d,
        force_ratio: world.contact_force_n(id)[1] / net_weight_n(d, rho_p),
        speed_ratio: world.velocity_m_s(id).norm() / vt,
    })
}

#[test]
fn a_sphere_comes_to_rest_on_a_3d_floor_and_may_then_sleep_if_allowed() {
    let (d, rho_p, dt) = (70e-6, 2500.0, 1e-4);
    let (vt, _) = stokes_vt_tau(d, rho_p);
    for can_sleep in [false, true] {
        let mut settings = EngineSettings::for_scene(d, vt);
        settings.can_sleep = can_sleep;
        let mut world = dim3::World::new(settings, G);
        world.add_floor(0.0);
        let id = world.add_sphere(dim3::FluidBody::at_rest(
            dim3::Vector::new(0.0, 0.0, d),
            d,
            rho_p,
            stokes(d),
            G,
        ));
        let mut slept_at = None;
        for _ in 0..20_000 {
            world.step(dt, Integrator::Exponential).expect("stable");
            if slept_at.is_none() && world.is_sleeping(id) {
                slept_at = Some(world.time_s());
            }
        }
        let z = world.position_m(id)[2];
        let f = world.contact_force_n(id);
        eprintln!(
            "3D, can_sleep {can_sleep}: penetration {:.2e} d, force/weight {:.6}, slept at {slept_at:?} s",
            (0.5 * d - z) / d,
            f[2] / net_weight_n(d, rho_p)
        );
        assert!(((0.5 * d - z) / d).abs() < 0.01);
        assert_eq!(slept_at.is_some(), can_sleep, "sleeping only if allowed");
        if !can_sleep {
            assert!((f[2] / net_weight_n(d, rho_p) - 1.0).abs() < 0.02);
            assert!(f[0].abs() + f[1].abs() < 1e-6 * f[2]);
        }
    }
    // The settings go to run.toml.
    let text = toml::to_string(&EngineSettings::for_scene(d, vt)).expect("serializes");
    assert!(
        text.contains("length_unit_m") && text.contains("contact_drag = \"effective-mass\""),
        "{text}"
    );
}

#[test]
fn fine_and_coarse_grains_come_to_rest_on_the_floor() {
    let rho_p = 2500.0;
    for (d, dt) in [(2.5e-6, 1e-5), (70e-6, 1e-4)] {
        let rest =
            grain_on_floor_2d(d, rho_p, dt, 0.5, ContactDrag::EffectiveMass).expect("stable");
        eprintln!("d = {d:e} m, dt = {dt:e} s: {rest:?}");
        assert!(rest.penetration.abs() < 0.01, "d = {d}: {rest:?}");
        assert!((rest.force_ratio - 1.0).abs() < 0.02, "d = {d}: {rest:?}");
        assert!(rest.speed_ratio < 1e-3, "d = {d}: {rest:?}");
    }
}

/// A pile at rest.
#[derive(Debug)]
struct Pile {
    /// Largest overlap between grains or with the floor and walls at the end, / d.
    overlap: f64,
    /// Largest overlap seen at any step, / d.
    worst_overlap: f64,
    /// Σ vertical contact force / Σ net weight (= floor normal force / weight: grain–grain normal
    /// forces cancel in the sum and the walls' normals are horizontal).
    force_ratio: f64,
    /// Largest speed / v_t at the end.
    speed_ratio: f64,
}

/// Largest overlap / d among equal grains in a box [0, width] × [0, ∞).
fn max_overlap(world: &dim2::World, ids: &[crate::engine::BodyId], d: f64, width: f64) -> f64 {
    let mut overlap: f64 = 0.0;
    for (a, &i) in ids.iter().enumerate() {
        let p = world.position_m(i);
        overlap = overlap
            .max(0.5 * d - p[1])
            .max(0.5 * d - p[0])
            .max(p[0] - (width - 0.5 * d));
        for &j in &ids[a + 1..] {
            overlap = overlap.max(d - (p - world.position_m(j)).norm());
        }
    }
    overlap / d
}

/// `n` grains of diameter `d` dropped in rows into a 2D box `width_d` diameters wide; stepped
/// until well after the last has landed. `None` if a step failed.
fn pile_2d(
    n: usize,
    d: f64,
    dt: f64,
    width_d: f64,
    friction: f64,
    contact: ContactDrag,
) -> Option<Pile> {
    let rho_p = 2500.0;
    let (vt, tau) = stokes_vt_tau(d, rho_p);
    let mut settings = EngineSettings::for_scene(d, vt);
    settings.friction = friction;
    settings.contact_drag = contact;
    let mut world = dim2::World::new(settings, G);
    let width = width_d * d;
    world.add_floor(0.0);
    world.add_wall(dim2::Vector::new(0.0, 0.0), dim2::Vector::new(1.0, 0.0));
    world.add_wall(dim2::Vector::new(width, 0.0), dim2::Vector::new(-1.0, 0.0));
    // Rows of `per_row` grains spaced by `pitch` > d, alternately shifted by d/4 so that the grains
    // do not stack in columns.
    let per_row = ((width_d - 1.35) / 1.05).floor() as usize + 1;
    let pitch = (width_d - 1.35) / (per_row - 1).max(1) as f64;
    let ids: Vec<_> = (0..n)
        .map(|i| {
            let (row, col) = (i / per_row, i % per_row);
            let shift = if row.is_multiple_of(2) { 0.1 } else { 0.35 };
            let x = (0.5 + shift + col as f64 * pitch) * d;
            let y = (0.6 + 1.3 * row as f64) * d;
            world.add_sphere(dim2::FluidBody::at_rest(
                dim2::Vector::new(x, y),
                d,
                rho_p,
                stokes(d),
                G,
            ))
        })
        .collect();
    let rows = n.div_ceil(per_row) as f64;
    // Three times the fall time of the top row: grains rolling over others take that long to stop.
    let t_end = 3.0 * 1.3 * rows * d / vt + 50.0 * tau;
    let steps = (t_end / dt).ceil() as usize;
    let mut worst_overlap: f64 = 0.0;
    for step in 0..steps {
        world.step(dt, Integrator::Exponential).ok()?;
        for &id in &ids {
            assert!(!world.is_sleeping(id));
        }
        if step.is_multiple_of(10) {
            worst_overlap = worst_overlap.max(max_overlap(&world, &ids, d, width));
        }
    }
    let overlap = max_overlap(&world, &ids, d, width);
    let total_force: f64 = ids.iter().map(|&i| world.contact_force_n(i)[1]).sum();
    let max_speed = ids
        .iter()
        .map(|&i| world.velocity_m_s(i).norm())
        .fold(0.0, f64::max);
    Some(Pile {
        overlap,
        worst_overlap: worst_overlap.max(overlap),
        force_ratio: total_force / (n as f64 * net_weight_n(d, rho_p)),
        speed_ratio: max_speed / vt,
    })
}

#[test]
fn twenty_coarse_grains_pile_up_in_a_narrow_box() {
    let d = 70e-6;
    // Frictionless: the floor carries the whole weight.
    let pile = pile_2d(20, d, 1e-4, 4.6, 0.0, ContactDrag::EffectiveMass).expect("stable");
    eprintln!("frictionless pile: {pile:?}");
    assert!(pile.worst_overlap < 0.01, "{pile:?}");
    assert!((pile.force_ratio - 1.0).abs() < 0.02, "{pile:?}");
    assert!(pile.speed_ratio < 1e-2, "{pile:?}");
    // With friction (0.5): overlaps stay small; the walls carry part of the weight (Janssen).
    let pile = pile_2d(20, d, 1e-4, 4.6, 0.5, ContactDrag::EffectiveMass).expect("stable");
    eprintln!("frictional pile:   {pile:?}");
    assert!(pile.worst_overlap < 0.01, "{pile:?}");
    assert!(
        pile.force_ratio > 0.5 && pile.force_ratio < 1.02,
        "{pile:?}"
    );
    assert!(pile.speed_ratio < 1e-2, "{pile:?}");
}

#[test]
fn twenty_fine_grains_pile_up_at_a_thousand_response_times_per_step() {
    // 2.5 µm: τ = 0.87 µs, dt = 1e-3 s = 1150 τ. Damping-style contact drag fails here (overlaps
    // of 1.5 d already at dt = 1e-5 s, see the survey); the effective mass holds.
    let d = 2.5e-6;
    for friction in [0.0, 0.5] {
        let pile = pile_2d(20, d, 1e-3, 4.6, friction, ContactDrag::EffectiveMass).expect("stable");
        eprintln!("fine pile, friction {friction}: {pile:?}");
        assert!(pile.worst_overlap < 0.01, "{pile:?}");
        assert!(pile.speed_ratio < 1e-2, "{pile:?}");
        if friction == 0.0 {
            assert!((pile.force_ratio - 1.0).abs() < 0.02, "{pile:?}");
        }
    }
}

/// The dt survey behind the steps chosen above (run with `--ignored --nocapture`).
#[test]
#[ignore]
fn survey_dt_for_fine_and_coarse_grains() {
    let rho_p = 2500.0;
    for contact in [ContactDrag::EffectiveMass, ContactDrag::Damping] {
        for d in [2.5e-6, 70e-6] {
            let (vt, tau) = stokes_vt_tau(d, rho_p);
            for dt in [1e-6, 1e-5, 1e-4, 1e-3] {
                if (0.5 * d / vt + 0.02) / dt > 2e6 {
                    continue;
                }
                match grain_on_floor_2d(d, rho_p, dt, 0.5, contact) {
                    Some(r) => eprintln!(
                        "{contact:?} grain d {d:.1e} dt {dt:.0e} (dt/tau {:7.2}): penetration {:+.2e} d, force/weight {:.4}, speed {:.1e} v_t",
                        dt / tau,
                        r.penetration,
                        r.force_ratio,
                        r.speed_ratio
                    ),
                    None => eprintln!("{contact:?} grain d {d:.1e} dt {dt:.0e}: unstable"),
                }
            }
        }
        let fine_dts: &[f64] = match contact {
            ContactDrag::EffectiveMass => &[1e-5, 1e-4, 1e-3],
            ContactDrag::Damping => &[1e-5, 1e-4],
        };
        for (d, dts) in [(2.5e-6, fine_dts), (70e-6, &[1e-5, 1e-4, 1e-3])] {
            let (_, tau) = stokes_vt_tau(d, rho_p);
            for &dt in dts {
                for friction in [0.0, 0.5] {
                    match pile_2d(20, d, dt, 4.6, friction, contact) {
                        Some(p) => eprintln!(
                            "{contact:?} pile d {d:.1e} dt {dt:.0e} (dt/tau {:7.2}) friction {friction}: overlap {:.2e} d (worst {:.2e} d), floor force/weight {:.4}, speed {:.1e} v_t",
                            dt / tau,
                            p.overlap,
                            p.worst_overlap,
                            p.force_ratio,
                            p.speed_ratio
                        ),
                        None => eprintln!("{contact:?} pile d {d:.1e} dt {dt:.0e} friction {friction}: unstable"),
                    }
                }
            }
        }
    }
}
