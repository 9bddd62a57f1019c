//! Squeeze-film lubrication between two spheres (or a sphere and a plane) approaching along the
//! line of centres. SI units.
//!
//! Leading-order normal resistance of two rigid spheres of radii a₁, a₂ at surface gap h ≪ a,
//! approaching at relative normal speed v_n (Kim & Karrila 1991, *Microhydrodynamics*, §9.3; as
//! used in DEM of suspensions by Marshall 2009, *J. Comput. Phys.* 228, 1541, and Ness & Sun 2015,
//! *Phys. Rev. E* 91, 012201):
//!
//! F = 6π μ a_eff² v_n / h,  a_eff = a₁a₂/(a₁ + a₂)  (a sphere and a plane: a_eff = a),
//!
//! repulsive when the spheres approach, attractive when they separate. It is cut off:
//! - **outside** h_out (default 0.1 a_eff): the leading term is within ~10 % of the exact
//!   resistance only for h ≲ 0.1 a; beyond, the pair's drag already describes it (Ness & Sun
//!   2015 use 0.05 a, Marshall 2009 about 0.1);
//! - **inside** h_in (default 1e-3 a_eff): the gap is floored at h_in (asperities, roughness), so
//!   the force stays finite and surfaces can touch in finite time.
//!
//! Seed 000 §4 names lubrication (its eq. 10 is garbled in the text we have); the form above is
//! the standard one.
//!
//! The force is a stiff pair damping with coefficient c = 6π μ a_eff²/h: its time scale
//! m_red/c is nanoseconds for micrometre grains. [`implicit_pair_step`] integrates it exactly
//! with the gap frozen over the step: the relative normal velocity of the pair decays as
//! exp(−c dt (1/m₁ + 1/m₂)), through a momentum-conserving impulse.

use std::f64::consts::PI;

/// Effective radius a_eff = a₁a₂/(a₁ + a₂), m; a plane is `f64::INFINITY` (a_eff = the other
/// radius).
pub fn effective_radius_m(a1_m: f64, a2_m: f64) -> f64 {
    if a1_m.is_infinite() {
        a2_m
    } else if a2_m.is_infinite() {
        a1_m
    } else {
        a1_m * a2_m / (a1_m + a2_m)
    }
}

/// Cut-offs of the lubrication force, as fractions of a_eff.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cutoffs {
    /// h_in / a_eff: the gap is floored at h_in. Default 1e-3.
    pub inner: f64,
    /// h_out / a_eff: no force at gaps ≥ h_out. Default 0.1.
    pub outer: f64,
}

impl Default for Cutoffs {
    fn default() -> Self {
        Self {
            inner: 1e-3,
            outer: 0.1,
        }
    }
}

/// Squeeze-film damping coefficient c = 6π μ a_eff² / max(h, h_in) for h < h_out, else 0, N s/m.
/// `gap_m` is the surface gap h (may be ≤ 0 in contact: then h_in).
pub fn damping_n_s_m(a1_m: f64, a2_m: f64, gap_m: f64, viscosity_pa_s: f64, cut: Cutoffs) -> f64 {
    let a = effective_radius_m(a1_m, a2_m);
    if gap_m >= cut.outer * a {
        return 0.0;
    }
    6.0 * PI * viscosity_pa_s * a * a / gap_m.max(cut.inner * a)
}

/// Lubrication force on sphere 2 along the unit normal from 1 to 2, N: −c v_n, with v_n the
/// relative normal velocity (v₂ − v₁)·n (negative when approaching: the force then pushes 2
/// away from 1). Sphere 1 feels the opposite.
pub fn force_n(
    a1_m: f64,
    a2_m: f64,
    gap_m: f64,
    normal_speed_m_s: f64,
    viscosity_pa_s: f64,
    cut: Cutoffs,
) -> f64 {
    -damping_n_s_m(a1_m, a2_m, gap_m, viscosity_pa_s, cut) * normal_speed_m_s
}

/// One implicit lubrication step of a pair, with the gap frozen: the relative normal velocity
/// v_n = (v₂ − v₁)·n decays exactly as v_n e^(−c dt (1/m₁ + 1/m₂)). Returns the normal impulse
/// J on sphere 2 (sphere 1 gets −J), N s: J = m_red (v_n′ − v_n), m_red = m₁m₂/(m₁ + m₂), so
/// momentum is conserved and Δv₂ = J/m₂, Δv₁ = −J/m₁ along n. Stable at any dt; a plane is
/// `m1_kg = f64::INFINITY`.
pub fn implicit_pair_step(
    damping_n_s_m: f64,
    m1_kg: f64,
    m2_kg: f64,
    normal_speed_m_s: f64,
    dt_s: f64,
) -> f64 {
    let inv = 1.0 / m1_kg + 1.0 / m2_kg;
    let m_red = 1.0 / inv;
    let decay = (-damping_n_s_m * dt_s * inv).exp();
    m_red * normal_speed_m_s * (decay - 1.0)
}

/// Overdamped approach of two spheres pushed together by a constant force F (no inertia, no
/// other drag), surface gap h(t) for h_in < h < h_out, m: dh/dt = −F h/(6π μ a_eff²), so
/// h(t) = h₀ exp(−F t/(6π μ a_eff²)).
pub fn gap_under_constant_force_m(
    a1_m: f64,
    a2_m: f64,
    gap0_m: f64,
    force_n: f64,
    viscosity_pa_s: f64,
    time_s: f64,
) -> f64 {
    let a = effective_radius_m(a1_m, a2_m);
    gap0_m * (-force_n * time_s / (6.0 * PI * viscosity_pa_s * a * a)).exp()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::sphere_mass_kg;

    const MU: f64 = 1e-3;

    /// Two spheres pushed together by ±F along x, gap from the pair's own implicit steps:
    /// inertia + lubrication, the force applied inside the exact pair update (relaxation of the
    /// relative velocity towards −F/c over the step with the gap frozen).
    fn pushed_pair(a1: f64, a2: f64, h0: f64, f: f64, dt: f64, t_end: f64) -> f64 {
        let (m1, m2) = (
            sphere_mass_kg(2.0 * a1, 2500.0),
            sphere_mass_kg(2.0 * a2, 2500.0),
        );
        let (mut v1, mut v2, mut h) = (0.0f64, 0.0f64, h0);
        let steps = (t_end / dt).round() as usize;
        let cut = Cutoffs::default();
        for _ in 0..steps {
            let c = damping_n_s_m(a1, a2, h, MU, cut);
            // External force then lubrication, both exact for the frozen gap: the relative
            // velocity relaxes to the terminal −F (1/m1 + 1/m2)/(c (1/m1 + 1/m2)) = −F/c.
            let vn = v2 - v1;
            let inv = 1.0 / m1 + 1.0 / m2;
            let terminal = -f / c;
            let decay = (-c * dt * inv).exp();
            let vn_new = terminal + (vn - terminal) * decay;
            // Mean relative speed over the step (exact for the exponential relaxation).
            let mean = terminal + (vn - terminal) * (1.0 - decay) / (c * dt * inv);
            h += mean * dt;
            // Momentum: centre of mass at rest (equal and opposite forces).
            let j = (vn_new - vn) / inv;
            v2 += j / m2;
            v1 -= j / m1;
        }
        h
    }

    #[test]
    fn constant_force_closes_the_gap_exponentially() {
        // 35 µm and 2.5 µm spheres, F = 1e-10 N: lubrication time 6πμ a_eff²/F ≈ 1e-3 s. The
        // inertial time m_red/c is ~1e-9 s: the overdamped solution holds. Tolerance 1e-3
        // relative (first-order error of the frozen gap, dt = 1e-6 s, 0.1 % of the time scale).
        let (a1, a2, f) = (35e-6, 2.5e-6, 1e-10);
        let a = effective_radius_m(a1, a2);
        let h0 = 0.09 * a;
        let tau = 6.0 * PI * MU * a * a / f;
        for t in [0.5 * tau, tau, 2.0 * tau] {
            let h = pushed_pair(a1, a2, h0, f, 1e-3 * tau, t);
            let exact = gap_under_constant_force_m(a1, a2, h0, f, MU, t);
            assert!(exact > 1e-3 * a, "inside the cut-offs");
            let err = (h / exact - 1.0).abs();
            assert!(
                err < 1e-3,
                "t = {t:e}: h = {h:e}, exact {exact:e}, err {err:e}"
            );
        }
    }

    #[test]
    fn the_impulse_conserves_momentum_and_decays_the_relative_speed() {
        let (m1, m2) = (3e-12, 7e-14);
        let (v1, v2) = (-2e-3, -1e-4); // 1 falls faster onto 2, n from 1 to 2 pointing down
        let n = -1.0;
        let vn = (v2 - v1) * n; // approach: negative
        assert!(vn < 0.0);
        let c = damping_n_s_m(35e-6, 2.5e-6, 1e-8, MU, Cutoffs::default());
        let dt = 1e-9;
        let j = implicit_pair_step(c, m1, m2, vn, dt);
        let (w1, w2) = (v1 - j / m1 * n, v2 + j / m2 * n);
        let p0 = m1 * v1 + m2 * v2;
        let p1 = m1 * w1 + m2 * w2;
        assert!(
            ((p1 - p0) / p0).abs() < 1e-12,
            "momentum {p0:e} -> {p1:e} (tolerance 1e-12 relative)"
        );
        let vn1 = (w2 - w1) * n;
        let expected = vn * (-c * dt * (1.0 / m1 + 1.0 / m2)).exp();
        assert!(
            ((vn1 - expected) / expected).abs() < 1e-9,
            "relative speed {vn1:e}, expected {expected:e} (tolerance 1e-9)"
        );
    }

    #[test]
    fn stable_at_steps_far_beyond_the_lubrication_time() {
        // dt = 1 s against a lubrication time m_red/c of ~2e-9 s: the relative speed is
        // removed, never reversed or amplified, and momentum is kept.
        let (m1, m2) = (1e-12, 1e-13);
        let c = damping_n_s_m(30e-6, 3e-6, 1e-9, MU, Cutoffs::default());
        assert!(c * (1.0 / m1 + 1.0 / m2) > 1e8);
        for vn in [-1e-2, -1e-6, 3e-4] {
            let j = implicit_pair_step(c, m1, m2, vn, 1.0);
            let vn1 = vn + j * (1.0 / m1 + 1.0 / m2);
            assert!(
                j.is_finite() && vn1.abs() <= 1e-12 * vn.abs(),
                "vn {vn} -> {vn1}"
            );
        }
        // A plane (infinite mass) takes the impulse without moving.
        let j = implicit_pair_step(c, f64::INFINITY, m2, -1e-3, 1.0);
        assert!(
            (j / m2 - 1e-3).abs() < 1e-15,
            "the sphere stops: Δv = {}",
            j / m2
        );
    }

    #[test]
    fn cut_offs_bound_the_force() {
        let cut = Cutoffs::default();
        let a = effective_radius_m(10e-6, 10e-6);
        assert_eq!(a, 5e-6);
        assert_eq!(damping_n_s_m(10e-6, 10e-6, 0.1 * a, MU, cut), 0.0);
        let inner = damping_n_s_m(10e-6, 10e-6, 1e-3 * a, MU, cut);
        assert_eq!(damping_n_s_m(10e-6, 10e-6, 0.0, MU, cut), inner);
        assert_eq!(damping_n_s_m(10e-6, 10e-6, -1e-7, MU, cut), inner);
        let f = force_n(10e-6, 10e-6, 0.05 * a, -1e-3, MU, cut);
        let hand = 6.0 * PI * MU * a * a * 1e-3 / (0.05 * a);
        assert!(
            (f / hand - 1.0).abs() < 1e-12,
            "F = {f:e}, by hand {hand:e}"
        );
        assert_eq!(effective_radius_m(f64::INFINITY, 4e-6), 4e-6);
    }
}
