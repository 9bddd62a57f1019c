//! Ansley & Smith (1967): a sphere in a Bingham plastic follows the Newtonian standard drag
//! curve at a modified Reynolds number that counts the yield stress as extra viscosity.
//!
//! Re* = ρ_f v d / [η_B (1 + (7π/24) Bi)],  Bi = τ_y d / (η_B v)   (so Re* = ρ_f v² d / (η_B v + (7π/24) τ_y d))
//! C_d = C_N(Re*),  F = ½ C_d ρ_f A v²,
//!
//! with C_N the Clift–Gauvin fit of the standard drag curve (Ansley & Smith plotted their data
//! against the standard curve itself). The factor 7π/24 comes from their slip-line (plastic
//! zone) estimate of the yield-stress resistance. As v → 0, C_d → 24/Re* gives a finite static
//! resistance F_s = 3π · (7π/24) d² τ_y = (7π²/8) d² τ_y ≈ 8.64 d² τ_y, i.e. a sphere moves when
//! τ_y/(Δρ g d) < 4/(21π) ≈ 0.061.
//!
//! Source: Ansley, R. W. & Smith, T. N. (1967). Motion of spherical particles in a Bingham
//! plastic. *AIChE Journal* 13(6):1193–1196. **Not verified against the paper: no page or
//! equation number can be given.** Checked in December 2026 with the search tools (documentation
//! pages, web pages, public code, issue threads): neither the paper nor a text that reproduces
//! its formula (Chhabra, *Bubbles, Drops and Particles in Non-Newtonian Fluids*, 2nd ed., CRC,
//! ch. 4 "Rigid particles in visco-plastic liquids", of which only the first page, p. 123, was
//! found; Chhabra & Richardson, *Non-Newtonian Flow and Applied Rheology*, 2008, not found) could
//! be read, and no public code implements the law. What was found:
//! - the structure "the Newtonian standard drag curve at a modified Reynolds number" is
//!   confirmed by the abstract of Woo, H., *Drag characteristics of spheres in Bingham fluids*
//!   (ASCE conference paper, <https://cedb.asce.org/CEDBsearch/record.jsp?dockey=0057498>):
//!   "Ansley and Smith's type of drag relation can be traced back closely, if not completely,
//!   to the Newtonian drag curve";
//! - the constant 7π/24 and the form 1 + (7π/24) Bi are NOT confirmed by any source read; they
//!   remain a recollection of the secondary literature. A different constant changes the static
//!   resistance 3π k d² τ_y in proportion (k = 7/6 would give Beris et al.'s 14π R² τ_y); the
//!   paper's own figure (C_d against Re* with the standard curve) is the check still to do.

use super::additive::cd_re_clift_gauvin;
use std::f64::consts::PI;

/// Ansley & Smith's plastic factor 7π/24 ≈ 0.916 (the yield-stress term of Re*).
pub const ANSLEY_SMITH_FACTOR: f64 = 7.0 * PI / 24.0;

/// Ansley & Smith's modified Reynolds number Re* = ρ_f v² d / (η_B v + (7π/24) τ_y d).
pub fn reynolds_ansley_smith(
    fluid_density_kg_m3: f64,
    speed_m_s: f64,
    d_m: f64,
    yield_stress_pa: f64,
    plastic_viscosity_pa_s: f64,
) -> f64 {
    let v = speed_m_s.max(0.0);
    fluid_density_kg_m3 * v * v * d_m
        / (plastic_viscosity_pa_s * v + ANSLEY_SMITH_FACTOR * yield_stress_pa * d_m)
}

/// Drag magnitude of Ansley & Smith's law at speed `speed_m_s` ≥ 0, N:
/// F = ½ C_N(Re*) ρ_f A v² = (C_N Re*) · (π d/8) · (η_B v + (7π/24) τ_y d). At v = 0 the static
/// resistance (7π²/8) d² τ_y.
pub fn ansley_smith_drag_n(
    fluid_density_kg_m3: f64,
    d_m: f64,
    yield_stress_pa: f64,
    plastic_viscosity_pa_s: f64,
    speed_m_s: f64,
) -> f64 {
    let v = speed_m_s.max(0.0);
    let re = reynolds_ansley_smith(
        fluid_density_kg_m3,
        v,
        d_m,
        yield_stress_pa,
        plastic_viscosity_pa_s,
    );
    cd_re_clift_gauvin(re)
        * (PI * d_m / 8.0)
        * (plastic_viscosity_pa_s * v + ANSLEY_SMITH_FACTOR * yield_stress_pa * d_m)
}

/// Static resistance of Ansley & Smith's law, N: (7π²/8) d² τ_y.
pub fn ansley_smith_static_resistance_n(d_m: f64, yield_stress_pa: f64) -> f64 {
    7.0 * PI * PI / 8.0 * d_m * d_m * yield_stress_pa
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::sphere_area_m2;

    #[test]
    fn drag_coefficient_is_the_standard_curve_at_re_star() {
        let (rho, d, ty, eb) = (1254.0, 0.019, 22.5, 0.0095);
        for v in [0.01, 0.1, 0.5, 2.0] {
            let re = reynolds_ansley_smith(rho, v, d, ty, eb);
            let cd =
                ansley_smith_drag_n(rho, d, ty, eb, v) / (0.5 * rho * sphere_area_m2(d) * v * v);
            let want = crate::fluid::newtonian::cd_clift_gauvin(re);
            assert!((cd / want - 1.0).abs() < 1e-12, "v = {v}");
        }
    }

    #[test]
    fn static_limit_and_newtonian_limit() {
        let (rho, d, ty, eb) = (1254.0, 0.019, 22.5, 0.0095);
        let f0 = ansley_smith_drag_n(rho, d, ty, eb, 0.0);
        assert!((f0 / ansley_smith_static_resistance_n(d, ty) - 1.0).abs() < 1e-12);
        assert!((f0 / (d * d * ty) - 8.6359).abs() < 1e-3);
        // τ_y = 0: Re* is the Newtonian Reynolds number.
        let re = reynolds_ansley_smith(rho, 0.3, d, 0.0, eb);
        assert!((re / (rho * 0.3 * d / eb) - 1.0).abs() < 1e-12);
    }
}
