//! The additive Bingham law: the static resistance of a sphere plus the Newtonian drag at the
//! Bingham Reynolds number. No constant is fitted to sphere data.
//!
//! F(v) = (π²/4 + 3π) d² τ_y + ½ C_N(Re_B) ρ_f A v²,  Re_B = ρ_f v d / η_B,  A = π d²/4,
//!
//! with C_N the Clift–Gauvin standard drag curve ([`crate::fluid::newtonian::cd_clift_gauvin`]).
//! The first term is f-EDEM's static resistance (the v → 0⁺ limit of its eq. 9 with eq. 19,
//! [`super::fedem::bingham_static_resistance_n`]); the second is the drag the same sphere would feel in
//! a Newtonian fluid of viscosity η_B. In creeping flow (Re_B → 0) the law equals f-EDEM's
//! branch Re′ < 1 exactly (F = F_s + 3π η_B d v); it differs at larger Re′, where f-EDEM's eq. 19
//! has its fitted constants 29.12 and 0.195 and this law has none. The superposition is a
//! modelling choice of issue 15 (the "additive" idea of summing a plastic and a viscous part goes
//! back to Dedegil 1987, on which f-EDEM builds); it is not a published correlation and there is
//! no paper example to check it against beyond the creeping limit tested here.

use super::super::newtonian::cd_clift_gauvin;
use super::fedem::bingham_static_resistance_n;
use std::f64::consts::PI;

/// C_d·Re of the Clift–Gauvin curve, finite as Re → 0 (limit 24). Dimensionless.
pub fn cd_re_clift_gauvin(re: f64) -> f64 {
    if re <= 0.0 {
        24.0
    } else {
        cd_clift_gauvin(re) * re
    }
}

/// Drag magnitude of the additive law at speed `speed_m_s` ≥ 0, N: (π²/4 + 3π) d² τ_y plus the
/// Newtonian (Clift–Gauvin) drag at Re_B = ρ_f v d/η_B. At v = 0 the static resistance.
pub fn additive_drag_n(
    fluid_density_kg_m3: f64,
    d_m: f64,
    yield_stress_pa: f64,
    plastic_viscosity_pa_s: f64,
    speed_m_s: f64,
) -> f64 {
    let v = speed_m_s.max(0.0);
    let re = fluid_density_kg_m3 * v * d_m / plastic_viscosity_pa_s;
    // ½ C ρ A v² = (C Re) · (A/2) · η v / d = (C Re) · π η d v / 8.
    bingham_static_resistance_n(d_m, yield_stress_pa)
        + cd_re_clift_gauvin(re) * PI * plastic_viscosity_pa_s * d_m * v / 8.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::bingham::bingham_drag_n;

    #[test]
    fn creeping_limit_is_fedem_branch_one() {
        // Re' < 1 branch of f-EDEM: F = F_s + 3π η_B d v; the additive law has the same limit.
        let (rho, d, ty, eb) = (1280.0, 0.0159, 30.5, 0.0131);
        let v = 1e-4;
        let a = additive_drag_n(rho, d, ty, eb, v);
        let f = bingham_drag_n(rho, d, ty, eb, v);
        assert!((a / f - 1.0).abs() < 1e-5, "{a} vs {f}");
        assert_eq!(
            additive_drag_n(rho, d, ty, eb, 0.0),
            bingham_static_resistance_n(d, ty)
        );
    }

    #[test]
    fn newtonian_part_is_the_clift_gauvin_drag() {
        // With τ_y = 0 the law is Clift–Gauvin's: at Re = 100, C_d = 24/100 (1 + 0.15·100^0.687)
        // + 0.42/(1 + 42500·100^−1.16) = 1.0938 (hand value).
        let (rho, d, eb) = (1000.0, 0.01, 0.001);
        let v = 100.0 * eb / (rho * d);
        let cd = additive_drag_n(rho, d, 0.0, eb, v) / (0.5 * rho * PI * d * d / 4.0 * v * v);
        assert!((cd - 1.0938).abs() < 1e-4, "C_d = {cd}");
    }

    #[test]
    fn increasing_in_speed() {
        let (rho, d, ty, eb) = (1226.0, 0.0254, 17.5, 0.0081);
        let mut prev = additive_drag_n(rho, d, ty, eb, 0.0);
        for i in 1..4000 {
            let f = additive_drag_n(rho, d, ty, eb, i as f64 * 1e-3);
            assert!(f > prev);
            prev = f;
        }
    }
}
