//! The dimension-free maths of the fluid–Rapier coupling (see the module doc of
//! [`crate::engine`]): what force, velocity correction, mass boost, hold and rolling torque a
//! body gets for one Rapier step. Pure functions, const-generic over the dimension `D`, SI units;
//! the worlds ([`super::dim2`], [`super::dim3`]) only hand the results to Rapier.
//!
//! One Rapier step of length dt does `K` Euler substeps (h = dt/K) with the force held constant:
//! `v ← v + a h`, then `x ← x + v h`. From `x₀, v₀` it lands at
//! `x₀ + v₀ dt + a dt² (K+1)/(2K)` with velocity `v₀ + a dt`.

use crate::dynamics::{self, Integrator, Motion, Step};
use crate::fluid::SphereDrag;
use nalgebra::SVector;

/// The exact free-flight scheme for one body and one step: the integrator's target step, the
/// constant acceleration that makes Rapier's `K` substeps land on its displacement, and the
/// velocity those substeps end with (before the correction).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeFlight<const D: usize> {
    /// Where the integrator says the body goes over the step.
    pub target: Step<D>,
    /// Total acceleration `a = (Δx − v₀dt)·2K/((K+1)dt²)` Rapier must apply, gravity included,
    /// m/s².
    pub acceleration_m_s2: SVector<f64, D>,
    /// Velocity after Rapier's substeps, `v₀ + a dt`, m/s.
    pub substep_velocity_m_s: SVector<f64, D>,
}

impl<const D: usize> FreeFlight<D> {
    /// Velocity to add after the Rapier step, `v_target − (v₀ + a dt)`, m/s.
    pub fn correction_m_s(&self) -> SVector<f64, D> {
        self.target.velocity_m_s - self.substep_velocity_m_s
    }
}

/// The exact free-flight scheme for a body of mass `mass_kg` with velocity `v0_m_s`, under the
/// constant force `weight_n` = W = m g + body force (buoyancy, …) and `drag`, over `dt_s` with
/// `substeps` = K Rapier substeps. The target is the integrator's step ([`dynamics::advance`]),
/// or the ballistic one when the body feels no fluid at all (no drag slope at rest and no static
/// resistance: above a free surface).
pub fn free_flight<const D: usize>(
    integrator: Integrator,
    drag: &SphereDrag,
    mass_kg: f64,
    weight_n: &SVector<f64, D>,
    v0_m_s: &SVector<f64, D>,
    dt_s: f64,
    substeps: f64,
) -> FreeFlight<D> {
    let w = weight_n;
    let target = if drag.slope_n_s_m(0.0) == 0.0 && drag.static_resistance_n() == 0.0 {
        ballistic(&(w / mass_kg), v0_m_s, dt_s)
    } else {
        dynamics::advance(integrator, drag, mass_kg, w, v0_m_s, dt_s)
    };
    let a = substep_acceleration(&target.displacement_m, v0_m_s, dt_s, substeps);
    FreeFlight {
        target,
        acceleration_m_s2: a,
        substep_velocity_m_s: v0_m_s + a * dt_s,
    }
}

/// Constant acceleration with which `substeps` = K Euler substeps of a Rapier step land on the
/// displacement `displacement_m` from velocity `v0_m_s`: `a = (Δx − v₀dt)·2K/((K+1)dt²)`, m/s²
/// (inverse of `Δx = v₀ dt + a dt² (K+1)/(2K)`).
pub fn substep_acceleration<const D: usize>(
    displacement_m: &SVector<f64, D>,
    v0_m_s: &SVector<f64, D>,
    dt_s: f64,
    substeps: f64,
) -> SVector<f64, D> {
    let k = substeps;
    (displacement_m - v0_m_s * dt_s) * (2.0 * k / ((k + 1.0) * dt_s * dt_s))
}

/// Ballistic step under the constant acceleration `a_m_s2`: `v₀ + a dt`, `v₀ dt + a dt²/2`.
pub fn ballistic<const D: usize>(
    a_m_s2: &SVector<f64, D>,
    v0_m_s: &SVector<f64, D>,
    dt_s: f64,
) -> Step<D> {
    Step {
        velocity_m_s: v0_m_s + a_m_s2 * dt_s,
        displacement_m: v0_m_s * dt_s + a_m_s2 * (0.5 * dt_s * dt_s),
        motion: Motion::Moving,
        drag_slope_n_s_m: 0.0,
    }
}

/// The coupling of a body in contact for one step: the drag linearised about the current speed
/// `s`, `F(v) ≈ F₀ v̂ + k v` (`k = dF/dv(s)`), with `F₀ v̂` (or the yield-stress hold) explicit
/// and `k v` left to the effective mass or to Rapier's damping.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InContact<const D: usize> {
    /// Explicit force besides gravity, N: the body force less the clamped `F₀ v̂` (none when the
    /// body is held or at rest).
    pub force_n: SVector<f64, D>,
    /// Force limit of the yield-stress hold for the step, N (0: no hold).
    pub hold_force_n: f64,
    /// `k dt/m`, the drag's share of the effective mass `m (1 + k dt/m)` (dimensionless).
    pub damping: f64,
}

/// The coupling of a body of mass `mass_kg` in contact, with velocity `v0_m_s`, body force
/// `body_force_n` and `drag`, over `dt_s`; `yield_hold` says whether yield-stress holds are on.
/// See [`InContact`], [`hold_force_n`] and [`clamped_f0_n`].
pub fn in_contact<const D: usize>(
    drag: &SphereDrag,
    mass_kg: f64,
    body_force_n: &SVector<f64, D>,
    v0_m_s: &SVector<f64, D>,
    dt_s: f64,
    yield_hold: bool,
) -> InContact<D> {
    let m = mass_kg;
    let s = v0_m_s.norm();
    let slope = drag.slope_n_s_m(s);
    let mut force = *body_force_n;
    let hold = hold_force_n(yield_hold, drag.static_resistance_n(), m, s, dt_s);
    if s > 0.0 && hold == 0.0 {
        let f0 = clamped_f0_n(drag.force_n(s), slope, s, m, dt_s);
        force -= v0_m_s * (f0 / s);
    }
    InContact {
        force_n: force,
        hold_force_n: hold,
        damping: slope / m * dt_s,
    }
}

/// The hold decision: the force limit of a body's yield-stress hold, N. A body with static
/// resistance `static_resistance_n` = F_s > 0 whose momentum the yield stress can cancel within
/// the step (`m s ≤ F_s dt`, rest included) is held with limit F_s, if holds are on; else 0.
pub fn hold_force_n(
    holds_on: bool,
    static_resistance_n: f64,
    mass_kg: f64,
    speed_m_s: f64,
    dt_s: f64,
) -> f64 {
    let fs = static_resistance_n;
    if holds_on && fs > 0.0 && mass_kg * speed_m_s <= fs * dt_s {
        fs
    } else {
        0.0
    }
}

/// The constant part F₀ = F(s) − k s of the drag linearised at speed `speed_m_s` = s
/// (`force_n` = F(s), `slope_n_s_m` = k), clamped to `m s/dt` so that it can at most stop the
/// body within the step, N.
pub fn clamped_f0_n(
    force_n: f64,
    slope_n_s_m: f64,
    speed_m_s: f64,
    mass_kg: f64,
    dt_s: f64,
) -> f64 {
    (force_n - slope_n_s_m * speed_m_s).min(mass_kg * speed_m_s / dt_s)
}

/// Effective-mass factors `(1 + k dt/m, 1 + k_rot dt/I)` of a body in contact, from
/// `damping` = k dt/m and `spin_damping` = k_rot dt/I: its Rapier mass and inertia are multiplied
/// by them for the step and its velocities divided by them (momentum kept), so that Rapier's update
/// is backward Euler on the drag, `(m + k dt) v₁ = m v₀ + F dt + J`. None when either is not
/// positive (no drag to treat so; the body then gets Rapier's damping).
pub fn effective_mass_factors(damping: f64, spin_damping: f64) -> Option<(f64, f64)> {
    (damping > 0.0 && spin_damping > 0.0).then_some((1.0 + damping, 1.0 + spin_damping))
}

/// Largest speed a body in contact may reach over the step, m/s, for the contact prediction
/// distance: its speed `speed_m_s` plus what gravity `gravity_m_s2` (magnitude) adds in dt
/// against the effective mass factor `1 + damping`.
pub fn contact_travel_speed_m_s(speed_m_s: f64, gravity_m_s2: f64, dt_s: f64, damping: f64) -> f64 {
    speed_m_s + gravity_m_s2 * dt_s / (1.0 + damping)
}

/// Magnitude of the rolling-resistance torque `μ_r r Σ|F_n|` on a sphere of diameter
/// `diameter_m` and moment of inertia `inertia_kg_m2` spinning at `spin_rad_s` = |ω`, with
/// `normal_force_sum_n` = Σ|F_n| over its contacts, clamped to `I |ω|/dt` so that it at most
/// stops the spin within the step, N m. None when there is nothing to resist (μ_r, Σ|F_n| or
/// |ω| zero).
pub fn rolling_torque_n_m(
    mu_r: f64,
    diameter_m: f64,
    normal_force_sum_n: f64,
    inertia_kg_m2: f64,
    spin_rad_s: f64,
    dt_s: f64,
) -> Option<f64> {
    (mu_r > 0.0 && normal_force_sum_n > 0.0 && spin_rad_s > 0.0).then(|| {
        (mu_r * 0.5 * diameter_m * normal_force_sum_n).min(inertia_kg_m2 * spin_rad_s / dt_s)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::{DragLaw, SphereDrag};
    use nalgebra::{Vector2, Vector3};

    /// Rapier's K substeps with a constant acceleration, done by hand: (Δx, v₁).
    fn substeps<const D: usize>(
        a: &SVector<f64, D>,
        v0: &SVector<f64, D>,
        dt: f64,
        k: usize,
    ) -> (SVector<f64, D>, SVector<f64, D>) {
        let h = dt / k as f64;
        let (mut x, mut v) = (SVector::zeros(), *v0);
        for _ in 0..k {
            v += a * h;
            x += v * h;
        }
        (x, v)
    }

    fn close<const D: usize>(a: &SVector<f64, D>, b: &SVector<f64, D>, tol: f64) -> bool {
        (a - b).norm() <= tol * b.norm().max(1e-300)
    }

    #[test]
    fn substep_acceleration_lands_on_the_displacement() {
        let v0 = Vector3::new(0.3, -0.2, -1.1);
        let dx = Vector3::new(2e-4, 1e-5, -7e-4);
        for k in [1, 2, 4, 7] {
            for dt in [1e-5, 1e-3, 0.1] {
                let a = substep_acceleration(&dx, &v0, dt, k as f64);
                let (x, v) = substeps(&a, &v0, dt, k);
                assert!(close(&x, &dx, 1e-9), "K = {k}, dt = {dt}: {x} vs {dx}");
                assert!(close(&v, &(v0 + a * dt), 1e-12), "K = {k}, dt = {dt}");
            }
        }
        // Hand value: K = 1, dt = 1, v₀ = 0: Δx = a dt² → a = Δx.
        let a = substep_acceleration(&Vector2::new(1.0, -2.0), &Vector2::zeros(), 1.0, 1.0);
        assert_eq!(a, Vector2::new(1.0, -2.0));
    }

    fn stokes(d: f64) -> SphereDrag {
        SphereDrag::new(
            DragLaw::Stokes {
                viscosity_pa_s: 1e-3,
            },
            d,
            1000.0,
        )
    }

    #[test]
    fn free_flight_follows_the_analytic_stokes_solution() {
        // 0.1 mm quartz in water: τ = ρp d²/(18 η) = 1.5 ms; step dt = 10 τ.
        let (d, rho) = (1e-4, 2700.0);
        let drag = stokes(d);
        let m = rho * std::f64::consts::PI * d.powi(3) / 6.0;
        let g = Vector3::new(0.0, 0.0, -9.81);
        let buoy = Vector3::new(
            0.0,
            0.0,
            1000.0 * std::f64::consts::PI * d.powi(3) / 6.0 * 9.81,
        );
        let v0 = Vector3::new(1e-3, 0.0, 0.0);
        let tau = rho * d * d / (18.0 * 1e-3);
        let dt = 10.0 * tau;
        let f = free_flight(
            Integrator::Exponential,
            &drag,
            m,
            &(g * m + buoy),
            &v0,
            dt,
            4.0,
        );
        // Analytic: v(t) = v_t + (v₀ − v_t) e^{−t/τ}, x(t) = v_t t + (v₀ − v_t) τ (1 − e^{−t/τ}).
        let vt = Vector3::new(0.0, 0.0, -(rho - 1000.0) * 9.81 * d * d / (18.0 * 1e-3));
        let e = (-dt / tau).exp();
        let v_exact = vt + (v0 - vt) * e;
        let x_exact = vt * dt + (v0 - vt) * (tau * (1.0 - e));
        assert!(close(&f.target.velocity_m_s, &v_exact, 1e-9));
        assert!(close(&f.target.displacement_m, &x_exact, 1e-9));
        // Rapier's substeps then land on it, and the correction fixes the velocity.
        let (x, v) = substeps(&f.acceleration_m_s2, &v0, dt, 4);
        assert!(close(&x, &x_exact, 1e-9));
        assert!(close(&(v + f.correction_m_s()), &v_exact, 1e-9));
    }

    #[test]
    fn free_flight_without_fluid_is_ballistic() {
        let drag = stokes(1e-3).scaled(0.0);
        let g = Vector2::new(0.0, -9.81);
        let v0 = Vector2::new(1.0, 2.0);
        let f = free_flight(
            Integrator::Exponential,
            &drag,
            0.5,
            &(g * 0.5),
            &v0,
            0.1,
            4.0,
        );
        // Hand values: v = (1, 2 − 0.981), Δx = (0.1, 0.2 − 0.04905).
        assert!(close(
            &f.target.velocity_m_s,
            &Vector2::new(1.0, 1.019),
            1e-14
        ));
        assert!(close(
            &f.target.displacement_m,
            &Vector2::new(0.1, 0.15095),
            1e-14
        ));
        // Rapier's substeps advance a dt² (K+1)/(2K), not a dt²/2: the acceleration that makes
        // up for it is g K/(K+1), and the substeps then land on the ballistic displacement.
        assert!(close(&f.acceleration_m_s2, &(g * 0.8), 1e-14));
        let (x, _) = substeps(&f.acceleration_m_s2, &v0, 0.1, 4);
        assert!(close(&x, &f.target.displacement_m, 1e-12));
    }

    #[test]
    fn stokes_drag_in_contact_has_no_constant_part() {
        let d = 1e-4;
        let drag = stokes(d);
        let m = 1.4e-9;
        let body_force = Vector3::new(0.0, 0.0, 5e-9);
        let v0 = Vector3::new(1e-3, -2e-3, 3e-4);
        let c = in_contact(&drag, m, &body_force, &v0, 1e-3, true);
        // Stokes: F = 3π η d v, F₀ = 0, k = 3π η d.
        assert!(close(&c.force_n, &body_force, 1e-12), "{}", c.force_n);
        assert_eq!(c.hold_force_n, 0.0);
        let k = 3.0 * std::f64::consts::PI * 1e-3 * d;
        assert!((c.damping - k * 1e-3 / m).abs() < 1e-12 * c.damping);
    }

    #[test]
    fn bingham_in_contact_is_held_or_decelerated() {
        let d = 1e-3;
        let drag = SphereDrag::new(
            DragLaw::Bingham {
                yield_stress_pa: 10.0,
                plastic_viscosity_pa_s: 0.1,
            },
            d,
            1800.0,
        );
        let fs = drag.static_resistance_n();
        // F_s = (π²/4 + 3π) d² τ_y.
        let pi = std::f64::consts::PI;
        assert!((fs - (pi * pi / 4.0 + 3.0 * pi) * d * d * 10.0).abs() < 1e-12 * fs);
        let m = 1e-6;
        let dt = 1e-3;
        let bf = Vector3::zeros();
        // At rest: held, no explicit drag.
        let rest = in_contact(&drag, m, &bf, &Vector3::zeros(), dt, true);
        assert_eq!((rest.hold_force_n, rest.force_n), (fs, Vector3::zeros()));
        // Holds off: nothing held.
        assert_eq!(
            in_contact(&drag, m, &bf, &Vector3::zeros(), dt, false).hold_force_n,
            0.0
        );
        // Fast: m s > F_s dt, not held; F₀ clamped to m s/dt, opposed to v.
        let s = 2.0 * fs * dt / m;
        let v0 = Vector3::new(0.0, s, 0.0);
        let fast = in_contact(&drag, m, &bf, &v0, dt, true);
        assert_eq!(fast.hold_force_n, 0.0);
        let f0 = clamped_f0_n(drag.force_n(s), drag.slope_n_s_m(s), s, m, dt);
        assert!(f0 > 0.0 && f0 <= m * s / dt);
        assert!(close(&fast.force_n, &Vector3::new(0.0, -f0, 0.0), 1e-12));
    }

    #[test]
    fn hold_decision() {
        // F_s = 2 N, m = 1 kg, dt = 0.1 s: held while s ≤ 0.2 m/s.
        assert_eq!(hold_force_n(true, 2.0, 1.0, 0.0, 0.1), 2.0);
        assert_eq!(hold_force_n(true, 2.0, 1.0, 0.2, 0.1), 2.0);
        assert_eq!(hold_force_n(true, 2.0, 1.0, 0.21, 0.1), 0.0);
        assert_eq!(hold_force_n(false, 2.0, 1.0, 0.0, 0.1), 0.0);
        assert_eq!(hold_force_n(true, 0.0, 1.0, 0.0, 0.1), 0.0);
    }

    #[test]
    fn f0_clamp() {
        // F(s) = 5 N, k = 1 N s/m, s = 2 m/s: F₀ = 3 N, unless m s/dt is smaller.
        assert_eq!(clamped_f0_n(5.0, 1.0, 2.0, 1.0, 0.1), 3.0);
        assert_eq!(clamped_f0_n(5.0, 1.0, 2.0, 1.0, 1.0), 2.0);
    }

    #[test]
    fn effective_mass_is_backward_euler() {
        // m = 2 kg, k = 3 N s/m, dt = 0.5 s, F = −4 N, v₀ = 1 m/s: backward Euler gives
        // v₁ = (m v₀ + F dt)/(m + k dt) = (2 − 2)/3.5 = 0.
        let (m, k, dt, f, v0) = (2.0, 3.0, 0.5, -4.0, 1.0);
        let (lin, ang) = effective_mass_factors(k * dt / m, 0.25).unwrap();
        assert_eq!((lin, ang), (1.75, 1.25));
        // Rapier with mass m·lin from velocity v₀/lin under force F (real weight only).
        let v1 = v0 / lin + f / (m * lin) * dt;
        assert!((v1 - (m * v0 + f * dt) / (m + k * dt)).abs() < 1e-15);
        assert_eq!(effective_mass_factors(0.0, 0.25), None);
        assert_eq!(effective_mass_factors(0.1, 0.0), None);
    }

    #[test]
    fn contact_travel_speed() {
        // s = 1, g = 10, dt = 0.1, damping 1: 1 + 1/2.
        assert_eq!(contact_travel_speed_m_s(1.0, 10.0, 0.1, 1.0), 1.5);
    }

    #[test]
    fn rolling_torque_clamp() {
        // μ_r = 0.1, d = 0.02 m, Σ|F_n| = 10 N: 0.1 × 0.01 × 10 = 0.01 N m.
        let t = rolling_torque_n_m(0.1, 0.02, 10.0, 1e-3, 100.0, 1e-3).unwrap();
        assert!((t - 0.01).abs() < 1e-15);
        // I |ω|/dt = 1e-6 × 1 / 1e-3 = 1e-3 N m < 0.01: clamped.
        let t = rolling_torque_n_m(0.1, 0.02, 10.0, 1e-6, 1.0, 1e-3).unwrap();
        assert!((t - 1e-3).abs() < 1e-15);
        assert_eq!(rolling_torque_n_m(0.0, 0.02, 10.0, 1e-6, 1.0, 1e-3), None);
        assert_eq!(rolling_torque_n_m(0.1, 0.02, 0.0, 1e-6, 1.0, 1e-3), None);
        assert_eq!(rolling_torque_n_m(0.1, 0.02, 10.0, 1e-6, 0.0, 1e-3), None);
    }
}
