//! Newtonian drag on a sphere: Stokes' law and the general drag-coefficient form with the
//! Dallavalle coefficient and the Di Felice voidage correction.

use super::buoyancy::sphere_area_m2;
use std::f64::consts::PI;

/// Particle Reynolds number, dimensionless: Re = ρ_f v d / η (f-EDEM eq. 6).
///
/// `speed_m_s` is the magnitude of the particle velocity relative to the fluid.
pub fn reynolds(fluid_density_kg_m3: f64, speed_m_s: f64, d_m: f64, viscosity_pa_s: f64) -> f64 {
    fluid_density_kg_m3 * speed_m_s * d_m / viscosity_pa_s
}

/// Stokes drag magnitude, N: F_d = 3 π η v d (f-EDEM eq. 7; Stokes 1851).
pub fn stokes_drag_n(viscosity_pa_s: f64, d_m: f64, speed_m_s: f64) -> f64 {
    3.0 * PI * viscosity_pa_s * d_m * speed_m_s
}

/// General drag magnitude from a drag coefficient, N: F_d = ½ C_d ρ_f A v² (f-EDEM eq. 5),
/// with A = π d²/4.
pub fn drag_from_cd_n(cd: f64, fluid_density_kg_m3: f64, d_m: f64, speed_m_s: f64) -> f64 {
    0.5 * cd * fluid_density_kg_m3 * sphere_area_m2(d_m) * speed_m_s * speed_m_s
}

/// Stokes drag coefficient: C_d = 24 / Re (f-EDEM eq. 8).
pub fn cd_stokes(re: f64) -> f64 {
    24.0 / re
}

/// Dallavalle drag coefficient: C_d = (0.63 + 4.8/√Re)² (seed 000 eq. 8; Dallavalle 1948).
pub fn cd_dallavalle(re: f64) -> f64 {
    let a = 0.63 + 4.8 / re.sqrt();
    a * a
}

/// Di Felice exponent: χ = 3.7 − 0.65 exp(−(1.5 − log₁₀ Re)²/2) (seed 000 eq. 9; Di Felice 1994).
pub fn di_felice_chi(re: f64) -> f64 {
    let l = 1.5 - re.log10();
    3.7 - 0.65 * (-0.5 * l * l).exp()
}

/// Di Felice voidage factor ε^(1−χ) multiplying the single-particle drag (seed 000 eq. 7).
///
/// `voidage` is the local fluid volume fraction ε ∈ (0, 1]; the factor is 1 for a lone particle
/// (ε = 1) and grows as the suspension gets denser (hindered settling). Seed 000 writes the base
/// as the "concentration" c; only the fluid fraction makes the formula physical.
pub fn di_felice_factor(voidage: f64, re: f64) -> f64 {
    voidage.powf(1.0 - di_felice_chi(re))
}

/// Stokes terminal velocity, m/s: v_t = d² (ρ_p − ρ_f) g / (18 η) (f-EDEM eq. 21).
pub fn stokes_terminal_velocity_m_s(
    d_m: f64,
    particle_density_kg_m3: f64,
    fluid_density_kg_m3: f64,
    viscosity_pa_s: f64,
    g_m_s2: f64,
) -> f64 {
    d_m * d_m * (particle_density_kg_m3 - fluid_density_kg_m3) * g_m_s2 / (18.0 * viscosity_pa_s)
}

/// Particle response time under Stokes drag, s: τ = ρ_p d² / (18 η) = m / (3 π η d).
///
/// The velocity from rest is v(t) = v_t (1 − e^{−t/τ}) (integral of f-EDEM eq. 20); an explicit
/// drag update is stable only for dt < 2τ.
pub fn stokes_response_time_s(d_m: f64, particle_density_kg_m3: f64, viscosity_pa_s: f64) -> f64 {
    particle_density_kg_m3 * d_m * d_m / (18.0 * viscosity_pa_s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stokes_law_is_the_cd_form_with_24_over_re() {
        let (rho, mu, d, v) = (1000.0, 1e-3, 1e-4, 3e-3);
        let re = reynolds(rho, v, d, mu);
        let from_cd = drag_from_cd_n(cd_stokes(re), rho, d, v);
        assert!((from_cd / stokes_drag_n(mu, d, v) - 1.0).abs() < 1e-13);
    }

    #[test]
    fn fedem_table1_terminal_velocity_and_response_time() {
        // d = 0.1 mm, ρ_p = 2700, water: v_t = 1e-8·1700·9.81/0.018 = 9.265e-3 m/s, τ = 1.5 ms.
        let vt = stokes_terminal_velocity_m_s(1e-4, 2700.0, 1000.0, 1e-3, 9.81);
        assert!((vt - 9.265e-3).abs() < 1e-6);
        let tau = stokes_response_time_s(1e-4, 2700.0, 1e-3);
        assert!((tau - 1.5e-3).abs() < 1e-15);
    }

    #[test]
    fn dallavalle_limits() {
        // Low Re: 23.04/Re, i.e. 0.96 of Stokes; high Re: 0.63² = 0.3969.
        assert!((cd_dallavalle(1e-6) * 1e-6 - 23.04).abs() < 0.01);
        assert!((cd_dallavalle(1e12) - 0.3969).abs() < 1e-4);
        // Re = 1: (0.63 + 4.8)² = 29.4849.
        assert!((cd_dallavalle(1.0) - 29.4849).abs() < 1e-12);
    }

    #[test]
    fn di_felice_exponent_and_factor() {
        // χ reaches its minimum 3.05 at Re = 10^1.5 and tends to 3.7 far from it.
        assert!((di_felice_chi(10f64.powf(1.5)) - 3.05).abs() < 1e-12);
        assert!((di_felice_chi(1e-6) - 3.7).abs() < 1e-6);
        assert_eq!(di_felice_factor(1.0, 0.3), 1.0);
        // ε = 0.9 at Re → 0: 0.9^(−2.7) = 1.329.
        assert!((di_felice_factor(0.9, 1e-8) - 0.9f64.powf(-2.7)).abs() < 1e-6);
    }
}
