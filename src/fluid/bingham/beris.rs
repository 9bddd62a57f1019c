//! The static criterion of Beris, Tsamopoulos, Armstrong & Brown (1985): a sphere in a Bingham
//! plastic stays at rest when its yield number is at or above a critical value.
//!
//! Beris et al. solved creeping flow of a Bingham plastic past a sphere by finite elements and
//! found that the sphere falls only while their yield-stress parameter Y_g is below 0.143 (their
//! abstract, JFM 158:219). Y_g = 3 τ_y / (2 Δρ g R) = 3 τ_y/(Δρ g d): the yield stress against
//! the net weight per unit surface, so the critical yield number in the form of issue 15,
//! Y = τ_y/(Δρ g d), is 0.143/3 ≈ 0.048 (the definition is checked only against a secondary
//! source, below).
//! As a force: a sphere of diameter d is held when its net weight W = π d² Δρ g d/6 does not
//! exceed π d² τ_y/(6 Y_c) ≈ 11.0 d² τ_y, close to f-EDEM's static resistance
//! (π²/4 + 3π) d² τ_y ≈ 11.9 d² τ_y (Y_c = 0.044) and above Ansley & Smith's 8.64 d² τ_y and
//! Wilson et al.'s π d² τ_y/0.3 ≈ 10.5 d² τ_y (Y_c = 0.05).
//!
//! Source: Beris, A. N., Tsamopoulos, J. A., Armstrong, R. C. & Brown, R. A. (1985). Creeping
//! motion of a sphere through a Bingham plastic. *J. Fluid Mech.* 158:219–244. The full paper
//! could not be read here (checked December 2026 with the search tools), so no page or equation
//! number is given for the definition of Y_g. What was checked, and against what:
//! - the critical value 0.143: the abstract ("The sphere will fall only when critical yield
//!   stress is below 0.143"), as reproduced on the page of the Tsamopoulos group,
//!   <https://fluidslab.chemeng.upatras.gr/index.php/2016/11/07/creeping-motion-of-a-sphere-through-a-bingham-plastic-2/>;
//! - the definition Y_g = 3 τ_y/(2 Δρ g R), i.e. a critical τ_y/(Δρ g d) of 0.143/3: consistent
//!   with an independent statement of the same criterion as a force, "σ_y,min = F/(14 π r²)"
//!   with F = (4/3) π r³ g Δρ, i.e. τ_y/(Δρ g d) = 1/21 = 0.0476 (repository rheopy/rheolite,
//!   `content/Particle_stability_in_yield_stress_fluids.ipynb`, citing Beris et al. 1985):
//!   14 π R² τ_y = W is Y_g = 1/7 = 0.1429 with the definition above. The constant
//!   [`BERIS_CRITICAL_YIELD_NUMBER`] = 0.143/3 = 0.04767 keeps the abstract's rounding (1/21 =
//!   0.04762, 0.1 % lower). Secondary sources, not the paper's own equation.

use std::f64::consts::PI;

/// Beris et al.'s critical yield-stress parameter Y_g = 3 τ_y/(Δρ g d): 0.143.
pub const BERIS_CRITICAL_YG: f64 = 0.143;

/// The same criterion as a yield number Y = τ_y/(Δρ g d): 0.143/3 ≈ 0.0477.
pub const BERIS_CRITICAL_YIELD_NUMBER: f64 = BERIS_CRITICAL_YG / 3.0;

/// Yield number Y = τ_y/(Δρ g d), dimensionless (issue 15's form; f-EDEM does not define one).
pub fn yield_number(
    yield_stress_pa: f64,
    density_difference_kg_m3: f64,
    g_m_s2: f64,
    d_m: f64,
) -> f64 {
    yield_stress_pa / (density_difference_kg_m3 * g_m_s2 * d_m)
}

/// The net weight up to which Beris et al.'s criterion holds a sphere at rest, N:
/// π d² τ_y / (6 Y_c) with Y_c = [`BERIS_CRITICAL_YIELD_NUMBER`] (≈ 10.99 d² τ_y).
pub fn beris_static_resistance_n(d_m: f64, yield_stress_pa: f64) -> f64 {
    PI * d_m * d_m * yield_stress_pa / (6.0 * BERIS_CRITICAL_YIELD_NUMBER)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::bingham::{bingham_static_resistance_n, net_weight_n};

    #[test]
    fn held_exactly_up_to_the_critical_yield_number() {
        let (ty, rho_f, g, d) = (30.5, 1280.0, 9.81, 0.01);
        // Density at which Y = Y_c: Δρ = τ_y/(Y_c g d).
        let drho = ty / (BERIS_CRITICAL_YIELD_NUMBER * g * d);
        let w = net_weight_n(d, rho_f + drho, rho_f, g);
        assert!((w / beris_static_resistance_n(d, ty) - 1.0).abs() < 1e-12);
        assert!((yield_number(ty, drho, g, d) * 3.0 - 0.143).abs() < 1e-12);
        assert!((beris_static_resistance_n(d, ty) / (d * d * ty) - 10.99).abs() < 0.01);
        // f-EDEM's own static resistance corresponds to Y_c = π/(6·11.89) ≈ 0.044.
        let yc_fedem = PI * d * d * ty / (6.0 * bingham_static_resistance_n(d, ty));
        assert!((yc_fedem - 0.0440).abs() < 1e-3);
    }

    #[test]
    fn criterion_is_the_force_14_pi_r_squared_tau_y() {
        // The same criterion as stated in rheopy/rheolite (citing Beris et al.): a sphere is held
        // while W ≤ 14 π R² τ_y, i.e. τ_y/(Δρ g d) ≥ 1/21. Equal within the abstract's rounding
        // of 1/7 to 0.143 (0.1 %).
        let (d, ty) = (0.02, 12.0);
        let f14 = 14.0 * PI * (d / 2.0) * (d / 2.0) * ty;
        assert!((beris_static_resistance_n(d, ty) / f14 - 1.0).abs() < 1.5e-3);
        assert!((BERIS_CRITICAL_YIELD_NUMBER * 21.0 - 1.0).abs() < 1.5e-3);
    }
}
