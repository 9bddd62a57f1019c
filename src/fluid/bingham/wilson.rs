//! Wilson, Horsley, Kealy, Reizes & Horsley (2003): the fall of a sphere in a non-Newtonian
//! fluid computed as in a Newtonian fluid of an *equivalent* viscosity, the secant viscosity
//! τ/γ̇ of the rheogram at the sphere's surface stress. It needs only the rheogram, so it serves
//! Herschel–Bulkley fluids τ = τ_y + K γ̇ⁿ (Bingham: n = 1, K = η_B) as well.
//!
//! Wilson et al. take the mean surface shear stress τ_s = W/(π d²) = Δρ g d/6 of a sphere of net
//! weight W, read the shear rate γ̇_s at τ_s off the rheogram, and use μ_eq = τ_s/γ̇_s in a
//! Newtonian fall-velocity relation. settle needs a drag *law* F(v) for the same sphere at any
//! speed, so the construction is written at the surface shear rate of a Stokes sphere,
//! γ̇ = 3 v / d (Stokes: τ_s = 3 η v/d):
//!
//! μ_sec(v) = τ(γ̇)/γ̇,  Re_eq = ρ_f v d / μ_sec,  F = ½ C_N(Re_eq) ρ_f A v² = (C_N Re_eq) π d² τ(γ̇)/24,
//!
//! with C_N the Clift–Gauvin standard drag curve. At the terminal velocity in creeping flow
//! F = π d² τ(3v/d) = W, i.e. τ(γ̇) = τ_s: the same secant viscosity as Wilson et al.'s, and the
//! same velocity. Above creeping flow the two differ (theirs stays at τ_s, this one follows the
//! speed). As v → 0 the law tends to π d² τ_y: a sphere moves when τ_s > τ_y, i.e.
//! τ_y/(Δρ g d) < 1/6.
//!
//! Source: Wilson, K. C., Horsley, R. R., Kealy, T., Reizes, J. A. & Horsley, M. (2003). Direct
//! prediction of fall velocities in non-Newtonian materials. *Int. J. Miner. Process.* 71:17–30.
//! The paper could not be consulted here: τ_s = Δρ g d/6 and the secant viscosity at τ_s are
//! from recollection; any further shift factor of the paper (for the part of the surface that
//! is below the mean stress, or for the Newtonian fall-velocity chart they use) is NOT included
//! and the law is NOT checked against the paper's worked examples.

use super::additive::cd_re_clift_gauvin;
use std::f64::consts::PI;

/// Surface shear rate of a sphere moving at `speed_m_s`, 1/s: γ̇ = 3 v/d (Stokes flow).
pub fn surface_shear_rate_hz(speed_m_s: f64, d_m: f64) -> f64 {
    3.0 * speed_m_s.max(0.0) / d_m
}

/// Herschel–Bulkley shear stress, Pa: τ = τ_y + K γ̇ⁿ (Bingham for n = 1, K = η_B).
pub fn herschel_bulkley_stress_pa(
    yield_stress_pa: f64,
    consistency_pa_sn: f64,
    flow_index: f64,
    shear_rate_hz: f64,
) -> f64 {
    yield_stress_pa + consistency_pa_sn * shear_rate_hz.max(0.0).powf(flow_index)
}

/// Mean surface shear stress of a sphere of diameter `d_m` whose net weight is carried by its
/// surface, Pa: τ_s = W/(π d²) = Δρ g d/6 (Wilson et al. 2003).
pub fn mean_surface_stress_pa(density_difference_kg_m3: f64, g_m_s2: f64, d_m: f64) -> f64 {
    density_difference_kg_m3 * g_m_s2 * d_m / 6.0
}

/// Secant viscosity of the Herschel–Bulkley rheogram at shear stress `stress_pa`, Pa s: τ/γ̇ with
/// γ̇ = ((τ − τ_y)/K)^(1/n). Infinite at or below the yield stress.
pub fn secant_viscosity_at_stress_pa_s(
    yield_stress_pa: f64,
    consistency_pa_sn: f64,
    flow_index: f64,
    stress_pa: f64,
) -> f64 {
    if stress_pa <= yield_stress_pa {
        return f64::INFINITY;
    }
    let rate = ((stress_pa - yield_stress_pa) / consistency_pa_sn).powf(1.0 / flow_index);
    stress_pa / rate
}

/// Drag magnitude of the secant-viscosity law at speed `speed_m_s` ≥ 0, N:
/// F = (C_N Re_eq) π d² τ(3v/d)/24 with Re_eq = ρ_f v d γ̇/τ(γ̇). At v = 0 the static
/// resistance π d² τ_y.
pub fn wilson_drag_n(
    fluid_density_kg_m3: f64,
    d_m: f64,
    yield_stress_pa: f64,
    consistency_pa_sn: f64,
    flow_index: f64,
    speed_m_s: f64,
) -> f64 {
    let v = speed_m_s.max(0.0);
    let rate = surface_shear_rate_hz(v, d_m);
    let tau = herschel_bulkley_stress_pa(yield_stress_pa, consistency_pa_sn, flow_index, rate);
    let re = if tau > 0.0 {
        fluid_density_kg_m3 * v * d_m * rate / tau
    } else {
        0.0
    };
    cd_re_clift_gauvin(re) * PI * d_m * d_m * tau / 24.0
}

/// Static resistance of the secant-viscosity law, N: π d² τ_y (the sphere moves when its mean
/// surface stress exceeds the yield stress).
pub fn wilson_static_resistance_n(d_m: f64, yield_stress_pa: f64) -> f64 {
    PI * d_m * d_m * yield_stress_pa
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::bingham::net_weight_n;

    #[test]
    fn newtonian_limit_is_stokes_at_low_re() {
        // τ_y = 0, n = 1: F → 3π K d v.
        let (rho, d, k) = (1000.0, 1e-4, 1.0);
        let v = 1e-6;
        let f = wilson_drag_n(rho, d, 0.0, k, 1.0, v);
        assert!((f / (3.0 * PI * k * d * v) - 1.0).abs() < 1e-4);
    }

    #[test]
    fn creeping_terminal_state_uses_the_secant_viscosity_at_the_mean_surface_stress() {
        // A slow heavy sphere in a stiff HB paste (Re_eq ≪ 1): where F(v) = W, the rheogram
        // stress at 3v/d is τ_s = Δρ g d/6 and v is Stokes' velocity with μ_eq = τ_s/γ̇_s.
        let (rho_f, rho_p, d, g) = (1800.0, 7800.0, 0.005, 9.81);
        let (ty, k, n) = (20.0, 40.0, 0.5);
        let w = net_weight_n(d, rho_p, rho_f, g);
        let ts = mean_surface_stress_pa(rho_p - rho_f, g, d);
        let mu = secant_viscosity_at_stress_pa_s(ty, k, n, ts);
        let v_stokes = (rho_p - rho_f) * g * d * d / (18.0 * mu);
        let f = wilson_drag_n(rho_f, d, ty, k, n, v_stokes);
        assert!((f / w - 1.0).abs() < 2e-3, "F/W = {}", f / w);
    }

    #[test]
    fn static_resistance_is_the_zero_speed_limit_and_increasing() {
        let (rho, d, ty, k, n) = (1280.0, 0.019, 30.5, 0.0131, 1.0);
        let f0 = wilson_drag_n(rho, d, ty, k, n, 0.0);
        assert!((f0 / wilson_static_resistance_n(d, ty) - 1.0).abs() < 1e-12);
        let mut prev = f0;
        for i in 1..3000 {
            let f = wilson_drag_n(rho, d, ty, k, n, i as f64 * 1e-3);
            assert!(f > prev);
            prev = f;
        }
    }
}
