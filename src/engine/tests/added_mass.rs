//! Added mass in the Rapier worlds (`World::set_added_mass_coefficient`, issue 16): a sphere
//! released from rest follows the Stokes solution with the effective mass m_p + C_m m_f (and not
//! the one with m_p, nor with added mass off the one with the effective mass), its terminal
//! velocity does not change, gravity stays m_p g (a resting sphere loads the floor with its net
//! weight), the added mass follows the immersed volume across a free surface, and C_m = 0 is
//! added mass off bit for bit.

use crate::dynamics::Integrator;
use crate::engine::coupling::free_flight;
use crate::engine::{dim2, dim3, EngineSettings};
use crate::fluid::{immersion, sphere_mass_kg, DragLaw, SphereDrag, Submergence};
use std::f64::consts::PI;

const G: f64 = 9.81;
/// ten Cate et al.'s (2002) E1 sphere and oil: C_m m_f / m_p = 0.5 × 970/1120 = 0.43.
const D: f64 = 0.015;
const RHO_P: f64 = 1120.0;
const RHO_F: f64 = 970.0;
const MU: f64 = 0.373;

fn stokes() -> SphereDrag {
    SphereDrag::new(DragLaw::Stokes { viscosity_pa_s: MU }, D, RHO_F)
}

/// Stokes terminal velocity (buoyancy included) and response time (m_p + C_m m_f)/(3π μ d).
fn vt_tau(c_m: f64) -> (f64, f64) {
    let vol = PI * D.powi(3) / 6.0;
    let k = 3.0 * PI * MU * D;
    (
        (RHO_P - RHO_F) * vol * G / k,
        (RHO_P + c_m * RHO_F) * vol / k,
    )
}

/// (t, downward speed, depth) after every step of a sphere released from rest at the origin,
/// no contacts, added mass coefficient `c_m` (None: the setter never called).
macro_rules! fall {
    ($dim:ident, $c_m:expr, $dt:expr, $steps:expr) => {{
        let (vt, _) = vt_tau(0.0);
        let mut world = $dim::World::new(EngineSettings::for_scene(D, vt), G);
        if let Some(c) = $c_m {
            world.set_added_mass_coefficient(c);
        }
        let id = world.add_sphere($dim::FluidBody::at_rest(
            $dim::Vector::zeros(),
            D,
            RHO_P,
            stokes(),
            G,
        ));
        let last = $dim::DIM - 1;
        (0..$steps)
            .map(|_| {
                world.step($dt, Integrator::Exponential).expect("stable");
                let (x, v) = (world.position_m(id), world.velocity_m_s(id));
                (world.time_s(), -v[last], -x[last])
            })
            .collect::<Vec<(f64, f64, f64)>>()
    }};
}

fn fall(dim: usize, c_m: Option<f64>, dt: f64, steps: usize) -> Vec<(f64, f64, f64)> {
    if dim == 2 {
        fall!(dim2, c_m, dt, steps)
    } else {
        fall!(dim3, c_m, dt, steps)
    }
}

/// Largest |v − v_exact|/v_t and |x − x_exact|/(v_t τ) over a run against the exponential
/// approach with response time `tau`: v = v_t (1 − e^{−t/τ}), x = v_t (t − τ (1 − e^{−t/τ})).
fn errors(run: &[(f64, f64, f64)], vt: f64, tau: f64) -> (f64, f64) {
    run.iter().fold((0.0f64, 0.0f64), |(ev, ex), &(t, v, x)| {
        let e = (-t / tau).exp();
        let (v_exact, x_exact) = (vt * (1.0 - e), vt * (t - tau * (1.0 - e)));
        (
            ev.max((v - v_exact).abs() / vt),
            ex.max((x - x_exact).abs() / (vt * tau)),
        )
    })
}

#[test]
fn a_released_sphere_follows_stokes_with_the_effective_mass() {
    let (vt, tau) = vt_tau(0.0);
    let (_, tau_am) = vt_tau(0.5);
    for dim in [2, 3] {
        for dt in [1e-4f64, 1e-3, 1e-2, 0.1] {
            let steps = (0.6 / dt).round() as usize;
            let on = fall(dim, Some(0.5), dt, steps);
            let off = fall(dim, None, dt, steps);
            let (on_v, on_x) = errors(&on, vt, tau_am);
            let (off_v, off_x) = errors(&off, vt, tau);
            // The other model's curve, to show the comparison can fail.
            let (on_vs_plain, _) = errors(&on, vt, tau);
            let (off_vs_am, _) = errors(&off, vt, tau_am);
            eprintln!(
                "{dim}D dt {dt:e}: added mass on vs tau' {on_v:.1e} (x {on_x:.1e}), vs tau \
                 {on_vs_plain:.3}; off vs tau {off_v:.1e} (x {off_x:.1e}), vs tau' {off_vs_am:.3}"
            );
            assert!(on_v < 1e-9 && on_x < 1e-9, "{dim}D dt {dt}: {on_v} {on_x}");
            assert!(
                off_v < 1e-9 && off_x < 1e-9,
                "{dim}D dt {dt}: {off_v} {off_x}"
            );
            assert!(on_vs_plain > 0.05, "{dim}D dt {dt}: on vs τ {on_vs_plain}");
            assert!(off_vs_am > 0.05, "{dim}D dt {dt}: off vs τ' {off_vs_am}");
        }
    }
    // Another coefficient: C_m = 2.
    let (_, tau2) = vt_tau(2.0);
    let (ev, ex) = errors(&fall(3, Some(2.0), 1e-3, 1000), vt, tau2);
    assert!(ev < 1e-9 && ex < 1e-9, "C_m = 2: {ev} {ex}");
}

#[test]
fn added_mass_leaves_the_terminal_velocity_unchanged() {
    let (vt, _) = vt_tau(0.0);
    for dim in [2, 3] {
        // 3 s = 56 τ' = 80 τ.
        let on = fall(dim, Some(0.5), 1e-3, 3000).last().unwrap().1;
        let off = fall(dim, None, 1e-3, 3000).last().unwrap().1;
        eprintln!("{dim}D terminal: on {on:.12e}, off {off:.12e}, Stokes {vt:.12e}");
        assert!((on / vt - 1.0).abs() < 1e-10, "{dim}D on: {on} vs {vt}");
        assert!((off / vt - 1.0).abs() < 1e-10, "{dim}D off: {off} vs {vt}");
    }
}

#[test]
fn a_resting_sphere_loads_the_floor_with_its_net_weight_not_its_added_mass() {
    // With C_m = 2 the added mass 2 m_f is 13 × the net mass m_p − m_f: a gravity acting on it
    // would load the floor 14 × too much.
    let net = (sphere_mass_kg(D, RHO_P) - sphere_mass_kg(D, RHO_F)) * G;
    for c_m in [0.0, 0.5, 2.0] {
        let (vt, _) = vt_tau(0.0);
        let mut world = dim3::World::new(EngineSettings::for_scene(D, vt), G);
        world.set_added_mass_coefficient(c_m);
        world.add_floor(0.0);
        let id = world.add_sphere(dim3::FluidBody::at_rest(
            dim3::Vector::new(0.0, 0.0, 0.5 * D + 1e-4),
            D,
            RHO_P,
            stokes(),
            G,
        ));
        for _ in 0..2000 {
            world.step(1e-3, Integrator::Exponential).expect("stable");
        }
        let f = world.contact_force_n(id)[2];
        eprintln!("C_m {c_m}: floor force / net weight = {:.9}", f / net);
        assert!((f / net - 1.0).abs() < 1e-3, "C_m {c_m}: {f} N vs {net} N");
        assert!(world.velocity_m_s(id).norm() < 1e-9 * vt);
    }
}

#[test]
fn across_a_free_surface_the_added_mass_follows_the_immersed_volume() {
    // A sphere falling from air through the surface (partial submergence): the world against the
    // same exact scheme stepped by hand with m_p + C_m ρ_f V f_V (f_V the immersed volume
    // fraction at the start of the step), and against a hand loop without added mass to show
    // the difference.
    let (c_m, dt) = (0.5, 1e-3);
    let (m, m_f) = (sphere_mass_kg(D, RHO_P), sphere_mass_kg(D, RHO_F));
    let z0 = 2.0 * D;
    let mut world = dim3::World::new(EngineSettings::for_scene(D, 1.0), G);
    world.set_added_mass_coefficient(c_m);
    world.set_free_surface(dim3::FreeSurface {
        height_m: 0.0,
        radius_m: None,
        submergence: Submergence::Partial,
    });
    let id = world.add_sphere(dim3::FluidBody::at_rest(
        dim3::Vector::new(0.0, 0.0, z0),
        D,
        RHO_P,
        stokes(),
        G,
    ));
    let by_hand = |c: f64, steps: usize| {
        let (mut z, mut v) = (z0, dim3::Vector::zeros());
        let mut out = Vec::new();
        for _ in 0..steps {
            let (fv, fa) = immersion(-z, D, Submergence::Partial);
            let w = dim3::Vector::new(0.0, 0.0, -m * G + fv * m_f * G);
            let s = free_flight(
                Integrator::Exponential,
                &stokes().scaled(fa),
                m + c * m_f * fv,
                &w,
                &v,
                dt,
                4.0,
            )
            .target;
            z += s.displacement_m[2];
            v = s.velocity_m_s;
            out.push((z, v[2]));
        }
        out
    };
    let steps = 200;
    let (with, without) = (by_hand(c_m, steps), by_hand(0.0, steps));
    let (mut worst, mut apart) = (0.0f64, 0.0f64);
    for (i, (&(z, vz), &(_, vz0))) in with.iter().zip(&without).enumerate() {
        world.step(dt, Integrator::Exponential).expect("stable");
        let (zw, vw) = (world.position_m(id)[2], world.velocity_m_s(id)[2]);
        worst = worst
            .max((zw - z).abs() / D)
            .max((vw - vz).abs() / vz.abs());
        apart = apart.max((vw - vz0).abs() / vz0.abs());
        assert!(
            (zw - z).abs() < 1e-9 * D && (vw - vz).abs() < 1e-9 * vz.abs(),
            "step {i}: world ({zw}, {vw}), by hand ({z}, {vz})"
        );
    }
    eprintln!(
        "surface crossing: worst relative difference {worst:.1e}; without added mass {apart:.3}"
    );
    assert!(apart > 0.05, "{apart}");
}

/// Positions and velocities after every step of three spheres dropped from air through a free
/// surface onto a floor and onto each other (free flight, contacts, the surface), with the
/// added-mass coefficient `c_m` (None: never set).
fn pile(c_m: Option<f64>) -> Vec<[f64; 12]> {
    let mut world = dim3::World::new(EngineSettings::for_scene(D, 1.0), G);
    if let Some(c) = c_m {
        world.set_added_mass_coefficient(c);
    }
    world.add_floor(0.0);
    world.set_free_surface(dim3::FreeSurface {
        height_m: 3.0 * D,
        radius_m: None,
        submergence: Submergence::Partial,
    });
    let ids: Vec<_> = [(0.0, 4.0), (0.3, 5.5), (-0.2, 7.0)]
        .iter()
        .map(|&(x, z)| {
            world.add_sphere(dim3::FluidBody::at_rest(
                dim3::Vector::new(x * D, 0.0, z * D),
                D,
                RHO_P,
                stokes(),
                G,
            ))
        })
        .collect();
    (0..1500)
        .map(|_| {
            world.step(2e-4, Integrator::Exponential).expect("stable");
            let mut row = [0.0; 12];
            for (k, &id) in ids.iter().enumerate().take(2) {
                let (x, v) = (world.position_m(id), world.velocity_m_s(id));
                row[6 * k..6 * k + 3].copy_from_slice(x.as_slice());
                row[6 * k + 3..6 * k + 6].copy_from_slice(v.as_slice());
            }
            row
        })
        .collect()
}

#[test]
fn a_zero_coefficient_is_added_mass_off_bit_for_bit() {
    let off = pile(None);
    let zero = pile(Some(0.0));
    assert_eq!(off, zero, "C_m = 0 must be added mass off");
    // And the pile does feel the added mass when it is on.
    let on = pile(Some(0.5));
    assert_ne!(off, on);
}
