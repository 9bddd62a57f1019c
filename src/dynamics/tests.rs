use super::*;
use crate::fluid::{sphere_mass_kg, DragLaw};
use nalgebra::Vector3;

/// f-EDEM Table 1: d = 0.1 mm, ρ_p = 2700, water. τ = 1.5 ms, v_t = 9.265e-3 m/s.
fn stokes_sphere() -> (SphereDrag, f64, Vector3<f64>) {
    let d = 1e-4;
    let drag = SphereDrag::new(
        DragLaw::Stokes {
            viscosity_pa_s: 1e-3,
        },
        d,
        1000.0,
    );
    let m = sphere_mass_kg(d, 2700.0);
    let w = Vector3::new(0.0, 0.0, -(m - sphere_mass_kg(d, 1000.0)) * 9.81);
    (drag, m, w)
}

fn run(integ: Integrator, dt: f64, t_end: f64) -> (f64, f64) {
    let (drag, m, w) = stokes_sphere();
    let mut v = Vector3::zeros();
    let mut x = Vector3::zeros();
    let n = (t_end / dt).round() as usize;
    for _ in 0..n {
        let s = advance(integ, &drag, m, &w, &v, dt);
        v = s.velocity_m_s;
        x += s.displacement_m;
    }
    (-v.z, -x.z)
}

fn analytic(t: f64) -> (f64, f64) {
    let (vt, tau) = (1e-8 * 1700.0 * 9.81 / 0.018, 1.5e-3);
    (
        vt * (1.0 - (-t / tau).exp()),
        vt * (t - tau * (1.0 - (-t / tau).exp())),
    )
}

#[test]
fn exponential_is_exact_for_stokes_drag_at_any_dt() {
    for dt in [1e-6, 1e-5, 1e-4, 1e-3, 1e-2] {
        let t = 0.02;
        let (v, x) = run(Integrator::Exponential, dt, t);
        let (va, xa) = analytic(t);
        assert!((v - va).abs() / va < 1e-9, "dt {dt}: v {v} vs {va}");
        assert!((x - xa).abs() / xa < 1e-9, "dt {dt}: x {x} vs {xa}");
    }
}

#[test]
fn implicit_is_stable_and_reaches_the_terminal_velocity_at_large_dt() {
    let (v, _) = run(Integrator::Implicit, 1e-2, 0.5);
    let (va, _) = analytic(0.5);
    assert!((v - va).abs() / va < 1e-12);
}

#[test]
fn explicit_diverges_beyond_twice_the_response_time() {
    // τ = 1.5 ms: 2τ = 3 ms. Below: converges; above: the error grows without bound.
    let (va, _) = analytic(0.3);
    let (v_ok, _) = run(Integrator::Explicit, 2.9e-3, 0.3);
    assert!((v_ok - va).abs() / va < 1e-3);
    let (v_bad, _) = run(Integrator::Explicit, 3.1e-3, 0.3);
    assert!((v_bad - va).abs() / va > 1.0);
    let (drag, m, _) = stokes_sphere();
    assert!((explicit_stable_dt_s(m, drag.slope_n_s_m(0.0)) - 3e-3).abs() < 1e-15);
}

fn paste_ball(d: f64) -> (SphereDrag, f64, f64) {
    // f-EDEM Table 4 paste: τ_y = 136 Pa, η_B = 0.7 Pa s, ρ = 1843; steel 8135.
    let drag = SphereDrag::new(
        DragLaw::Bingham {
            yield_stress_pa: 136.0,
            plastic_viscosity_pa_s: 0.7,
        },
        d,
        1843.0,
    );
    let m = sphere_mass_kg(d, 8135.0);
    let wn = (m - sphere_mass_kg(d, 1843.0)) * 9.81;
    (drag, m, wn)
}

#[test]
fn a_ball_below_the_static_resistance_never_creeps() {
    // 2 mm steel ball: net weight 3.2e-4 N < static resistance 6.5e-3 N.
    let (drag, m, wn) = paste_ball(0.002);
    assert!(wn < drag.static_resistance_n());
    let w = Vector3::new(0.0, 0.0, -wn);
    for integ in [Integrator::Implicit, Integrator::Exponential] {
        for dt in [1e-7, 1e-4, 1e-1] {
            let s = advance(integ, &drag, m, &w, &Vector3::zeros(), dt);
            assert_eq!(s.velocity_m_s, Vector3::zeros());
            assert_eq!(s.displacement_m, Vector3::zeros());
            assert_eq!(s.motion, Motion::Stuck);
        }
    }
}

#[test]
fn a_moving_ball_stops_and_stays_stopped_without_chatter() {
    let (drag, m, wn) = paste_ball(0.0126);
    assert!(wn < drag.static_resistance_n());
    let w = Vector3::new(0.0, 0.0, -wn);
    for dt in [1e-5, 1e-3] {
        let mut v = Vector3::new(0.0, 0.0, -1.0);
        let mut stopped_at = None;
        for i in 0..(0.2 / dt) as usize {
            let s = advance(Integrator::Exponential, &drag, m, &w, &v, dt);
            v = s.velocity_m_s;
            if stopped_at.is_some() {
                assert_eq!(v, Vector3::zeros(), "restarted after stopping, dt {dt}");
                assert_eq!(s.displacement_m, Vector3::zeros());
            }
            assert!(v.z <= 0.0, "velocity reversed: chatter");
            if s.motion == Motion::Stuck && stopped_at.is_none() {
                stopped_at = Some(i);
            }
        }
        assert!(stopped_at.is_some());
    }
}

/// Independent reference: RK4 with a tiny step on the smooth (creeping-branch) Bingham law.
#[test]
fn exponential_matches_a_fine_rk4_reference_for_bingham_settling() {
    // Valentik & Whitmore suspension 1, d = 19 mm, ρ_p = 7290: stays below Re' = 1 for t < 0.01 s.
    let d = 0.019;
    let drag = SphereDrag::new(
        DragLaw::Bingham {
            yield_stress_pa: 30.5,
            plastic_viscosity_pa_s: 0.0131,
        },
        d,
        1280.0,
    );
    let m = sphere_mass_kg(d, 7290.0);
    let wn = (m - sphere_mass_kg(d, 1280.0)) * 9.81;
    let f = |s: f64| {
        (wn - if s > 0.0 {
            drag.force_n(s)
        } else {
            drag.static_resistance_n()
        }) / m
    };
    let (mut s, h) = (0.0f64, 1e-7);
    for _ in 0..100_000 {
        let k1 = f(s);
        let k2 = f(s + 0.5 * h * k1);
        let k3 = f(s + 0.5 * h * k2);
        let k4 = f(s + h * k3);
        s += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    let w = Vector3::new(0.0, 0.0, -wn);
    for dt in [1e-4f64, 1e-3, 1e-2] {
        let mut v = Vector3::zeros();
        for _ in 0..(0.01 / dt).round() as usize {
            v = advance(Integrator::Exponential, &drag, m, &w, &v, dt).velocity_m_s;
        }
        assert!((-v.z / s - 1.0).abs() < 1e-6, "dt {dt}: {} vs {s}", -v.z);
    }
}

#[test]
fn every_scheme_that_is_stable_ends_at_the_force_balance() {
    // Valentik & Whitmore suspension 3, d = 25.4 mm, ρ_p = 6123: ends above Re' = 150.
    let d = 0.0254;
    let drag = SphereDrag::new(
        DragLaw::Bingham {
            yield_stress_pa: 17.5,
            plastic_viscosity_pa_s: 0.0081,
        },
        d,
        1226.0,
    );
    let m = sphere_mass_kg(d, 6123.0);
    let wn = (m - sphere_mass_kg(d, 1226.0)) * 9.81;
    let vt = drag.balance_speed(wn).speed_m_s;
    assert!(vt > 1.0);
    let w = Vector3::new(0.0, 0.0, -wn);
    for integ in [Integrator::Implicit, Integrator::Exponential] {
        let mut v = Vector3::zeros();
        for _ in 0..20_000 {
            v = advance(integ, &drag, m, &w, &v, 1e-3).velocity_m_s;
        }
        assert!(
            (-v.z / vt - 1.0).abs() < 1e-9,
            "{integ:?}: {} vs {vt}",
            -v.z
        );
    }
}
