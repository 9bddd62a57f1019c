//! Contact mechanics: the quantities that set DEM time steps ([`rayleigh_time_s`]), and the
//! restitution law with its calibration on drop tests ([`restitution`]).

pub mod restitution;

pub use restitution::{
    constant_fit, restitution_fits, ConstantFit, LawFit, RestitutionLaw, MAX_RESTITUTION,
};

use std::f64::consts::PI;

/// Rayleigh time of a sphere, s: T_R = π r / (0.8766 + 0.163 ν) · √(ρ_p / G), G = E / (2(1 + ν))
/// (f-EDEM eq. 22; Li et al. 2005). The usual DEM rule takes 10–20 % of it as the time step.
pub fn rayleigh_time_s(
    diameter_m: f64,
    density_kg_m3: f64,
    youngs_modulus_pa: f64,
    poisson_ratio: f64,
) -> f64 {
    let g = youngs_modulus_pa / (2.0 * (1.0 + poisson_ratio));
    PI * 0.5 * diameter_m / (0.8766 + 0.163 * poisson_ratio) * (density_kg_m3 / g).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fedem_table1_rayleigh_time() {
        // f-EDEM §3: d = 0.1 mm, ρ = 2700, E = 30 GPa, ν = 0.25 → T_R = 8.12e-8 s.
        let tr = rayleigh_time_s(1e-4, 2700.0, 30e9, 0.25);
        assert!((tr - 8.12e-8).abs() < 0.005e-8, "{tr}");
    }
}
