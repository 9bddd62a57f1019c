//! The yield stress of a paste from a cylinder slump test (Pashias & Boger 1996), as f-EDEM
//! Appendix I uses it (eqs. A1–A3, Table A1).
//!
//! A cylinder of height H is filled, lifted, and the paste slumps by S. With the dimensionless
//! slump S′ = S/H (A2) and the dimensionless yield stress τ′_y = τ_y/(ρ g H) (A3),
//!
//! S′ = 1 − 2τ′_y (1 − ln 2τ′_y)     (A1)
//!
//! which is monotone in τ′_y on 0 < τ′_y ≤ ½ (d S′/d(2τ′_y) = ln 2τ′_y < 0), so every slump
//! 0 < S < H has exactly one yield stress. Pure functions, SI units.
//!
//! Sources: Pashias, N., Boger, D. V., Summers, J. & Glenister, D. J. (1996), *J. Rheol.* 40,
//! 1179; f-EDEM (Zhang & Li 2024) Appendix I, eqs. A1–A3, Table A1 (H = 152 mm, ρ = 1843
//! kg/m³, slumps 102, 103, 100 mm: printed 135, 131, 143 Pa, mean 136 Pa; recomputing from
//! A1–A3 with g = 9.81 m/s² gives 136.6, 132.7, 144.6 Pa).

use crate::numerics::{bisect, Bisection, Stop};

/// Gravitational acceleration of the slump calculator, m/s² (the value that reproduces
/// f-EDEM's Table A1 to its printed rounding).
pub const G_M_S2: f64 = 9.81;

/// Eq. A1: the dimensionless slump S′ = S/H of a dimensionless yield stress τ′_y = τ_y/(ρ g H),
/// for 0 < τ′_y ≤ ½ (S′ = 1 at τ′_y → 0, S′ = 0 at τ′_y = ½). Outside that range: NaN.
pub fn dimensionless_slump(tau_dimensionless: f64) -> f64 {
    let x = 2.0 * tau_dimensionless;
    if !(x > 0.0 && x <= 1.0) {
        return f64::NAN;
    }
    1.0 - x * (1.0 - x.ln())
}

/// Inverse of eq. A1: the dimensionless yield stress τ′_y of a dimensionless slump
/// 0 < S′ < 1, by bisection on the monotone A1 to machine precision; None outside (0, 1).
pub fn dimensionless_yield_stress(slump_dimensionless: f64) -> Option<f64> {
    let s = slump_dimensionless;
    if !(s > 0.0 && s < 1.0) {
        return None;
    }
    // x = 2τ′ in (0, 1]; S′(x) decreases from 1 to 0.
    let rule = Bisection::until(Stop::Adjacent, 200);
    let (lo, hi) = bisect(0.0, 1.0, rule, |mid| dimensionless_slump(0.5 * mid) > s);
    Some(0.25 * (lo + hi))
}

/// Eqs. A1–A3: the yield stress τ_y, Pa, of a paste of density `density_kg_m3` that slumps by
/// `slump_m` from a cylinder of height `height_m`, under gravity `g_m_s2`:
/// τ_y = τ′_y(S/H) ρ g H. None unless 0 < S < H and ρ, g, H > 0 (all finite).
pub fn yield_stress_pa(
    height_m: f64,
    slump_m: f64,
    density_kg_m3: f64,
    g_m_s2: f64,
) -> Option<f64> {
    let ok = |x: f64| x.is_finite() && x > 0.0;
    if !(ok(height_m) && ok(density_kg_m3) && ok(g_m_s2) && slump_m.is_finite()) {
        return None;
    }
    dimensionless_yield_stress(slump_m / height_m).map(|t| t * density_kg_m3 * g_m_s2 * height_m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a1_round_trips() {
        for t in [1e-4, 0.01, 0.1, 0.2, 0.37, 0.49] {
            let s = dimensionless_slump(t);
            let back = dimensionless_yield_stress(s).unwrap();
            assert!(
                (back - t).abs() < 1e-12 * t.max(1e-3),
                "{t} -> {s} -> {back}"
            );
        }
    }

    #[test]
    fn a1_ends_and_range() {
        assert_eq!(dimensionless_slump(0.5), 0.0);
        assert!(dimensionless_slump(0.6).is_nan());
        assert!(dimensionless_slump(0.0).is_nan());
        assert_eq!(dimensionless_yield_stress(0.0), None);
        assert_eq!(dimensionless_yield_stress(1.0), None);
        assert_eq!(yield_stress_pa(0.152, 0.2, 1843.0, G_M_S2), None);
        assert_eq!(yield_stress_pa(0.0, 0.1, 1843.0, G_M_S2), None);
    }
}
