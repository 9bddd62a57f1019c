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

/// Schiller–Naumann drag coefficient: C_d = 24/Re (1 + 0.15 Re^0.687).
///
/// Source: Schiller, L. & Naumann, A. (1933), Z. Ver. Dtsch. Ing. 77:318; as given in Clift,
/// Grace & Weber (1978), *Bubbles, Drops and Particles*, ch. 5 (table of standard drag curve
/// correlations). Range Re < 800 ([`SCHILLER_NAUMANN_RE_MAX`]); accuracy about ±5 % against the
/// standard drag curve there (as quoted from Clift et al.; the page was not checked here).
pub fn cd_schiller_naumann(re: f64) -> f64 {
    24.0 / re * (1.0 + 0.15 * re.powf(0.687))
}

/// Largest Reynolds number of Schiller–Naumann's correlation: 800.
pub const SCHILLER_NAUMANN_RE_MAX: f64 = 800.0;

/// Clift–Gauvin drag coefficient: C_d = 24/Re (1 + 0.15 Re^0.687) + 0.42 / (1 + 42500 Re^−1.16).
///
/// Source: Clift, R. & Gauvin, W. H. (1971), Can. J. Chem. Eng. 49:439 (and Proc. Chemeca '70,
/// 1:14); as given in Clift, Grace & Weber (1978), ch. 5. Schiller–Naumann plus a term that
/// levels C_d off near 0.4–0.5 in the Newton regime. Range Re < 3·10⁵
/// ([`CLIFT_GAUVIN_RE_MAX`], below the drag crisis); accuracy about ±6 % (as quoted from Clift
/// et al.; the page was not checked here).
pub fn cd_clift_gauvin(re: f64) -> f64 {
    cd_schiller_naumann(re) + 0.42 / (1.0 + 42500.0 * re.powf(-1.16))
}

/// Largest Reynolds number of Clift–Gauvin's correlation: 3·10⁵.
pub const CLIFT_GAUVIN_RE_MAX: f64 = 3e5;

/// Morrison drag coefficient, a five-term fit of the standard drag curve through the drag crisis:
///
/// C_d = 24/Re + 2.6 (Re/5) / (1 + (Re/5)^1.52) + 0.411 (Re/263000)^−7.94 / (1 + (Re/263000)^−8)
/// + Re^0.8 / 461000.
///
/// Source: Morrison, F. A. (2013), *An Introduction to Fluid Mechanics*, Cambridge University
/// Press, ch. 8 (the sphere drag correlation, Re ≤ 10⁶; reproduced in Barati et al. 2014, Powder
/// Technol. 257:11). Range Re ≤ 10⁶ ([`MORRISON_RE_MAX`]); no accuracy figure is stated. The
/// third term is evaluated as 0.411 x^0.06 / (x⁸ + 1), x = Re/263000 (the same value, no overflow
/// at small Re). Through the drag crisis (Re ≈ 2.4·10⁵–3.6·10⁵) the drag *force* C_d Re² falls
/// with speed: the law is not monotone there.
pub fn cd_morrison(re: f64) -> f64 {
    let x = re / 263_000.0;
    let r5 = re / 5.0;
    24.0 / re
        + 2.6 * r5 / (1.0 + r5.powf(1.52))
        + 0.411 * x.powf(0.06) / (x.powi(8) + 1.0)
        + re.powf(0.8) / 461_000.0
}

/// Largest Reynolds number of Morrison's correlation: 10⁶.
pub const MORRISON_RE_MAX: f64 = 1e6;

/// A single-sphere drag-coefficient correlation C_d(Re) of a Newtonian fluid (`drag.law`
/// `schiller-naumann`, `clift-gauvin`, `morrison`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum CdCorrelation {
    /// [`cd_schiller_naumann`], Re < 800.
    SchillerNaumann,
    /// [`cd_clift_gauvin`], Re < 3·10⁵.
    CliftGauvin,
    /// [`cd_morrison`], Re ≤ 10⁶.
    Morrison,
}

impl CdCorrelation {
    /// C_d at Reynolds number `re` > 0.
    pub fn cd(self, re: f64) -> f64 {
        match self {
            Self::SchillerNaumann => cd_schiller_naumann(re),
            Self::CliftGauvin => cd_clift_gauvin(re),
            Self::Morrison => cd_morrison(re),
        }
    }

    /// Largest Reynolds number of the correlation's stated range.
    pub fn re_max(self) -> f64 {
        match self {
            Self::SchillerNaumann => SCHILLER_NAUMANN_RE_MAX,
            Self::CliftGauvin => CLIFT_GAUVIN_RE_MAX,
            Self::Morrison => MORRISON_RE_MAX,
        }
    }

    /// Human name with its source year, e.g. `Schiller–Naumann (1933)`.
    pub fn label(self) -> &'static str {
        match self {
            Self::SchillerNaumann => "Schiller–Naumann (1933)",
            Self::CliftGauvin => "Clift–Gauvin (1971)",
            Self::Morrison => "Morrison (2013)",
        }
    }

    /// The `drag.law` value that selects it.
    pub fn key(self) -> &'static str {
        match self {
            Self::SchillerNaumann => "schiller-naumann",
            Self::CliftGauvin => "clift-gauvin",
            Self::Morrison => "morrison",
        }
    }
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

/// Dallavalle drag with the Di Felice voidage factor and its first two derivatives in the speed
/// at one speed: (F, dF/dv, d²F/dv²), N, N s/m and N s²/m², for a sphere of diameter `d_m`
/// moving at `speed_m_s` > 0 through a fluid of density `fluid_density_kg_m3` and viscosity
/// `viscosity_pa_s` at local voidage `voidage` ε ∈ (0, 1], given `ln_voidage` = ln ε (computed
/// once per voidage cell).
///
/// F = S G with S = ½ C_d(Re) ρ_f A v², G = ε^(1−χ(Re)), Re = ρ_f ε v d / η,
/// C_d = (0.63 + 4.8/√Re)², χ = 3.7 − 0.65 exp(−(1.5 − log₁₀ Re)²/2) (seed 000 eqs. 7–9;
/// Dallavalle 1948, Di Felice 1994), as [`crate::fluid::SphereDrag::force_n`] computes it
/// ([`cd_dallavalle`], [`di_felice_factor`]), with G = exp((1−χ) ln ε). The derivatives are exact
/// (not difference quotients). With a = 0.63 + 4.8/√Re, b = 1.26 + 4.8/√Re
/// (a' = b' = −2.4/(v√Re)), L = 1.5 − log₁₀ Re, E = exp(−L²/2) and q = 0.65 E L ln ε / ln 10:
/// S' = ½ ρ_f A v a b, S'' = ½ ρ_f A (a b − 2.4 (a + b)/√Re), G' = G q / v,
/// G'' = G (q² − q + 0.65 E (L² − 1) ln ε / ln² 10) / v², F' = S'G + S G',
/// F'' = S''G + 2S'G' + S G''. One square root, one logarithm and two exponentials, against
/// three transcendentals for the force alone and six more for a central-difference slope.
pub fn dallavalle_di_felice_derivatives(
    speed_m_s: f64,
    voidage: f64,
    ln_voidage: f64,
    d_m: f64,
    fluid_density_kg_m3: f64,
    viscosity_pa_s: f64,
) -> (f64, f64, f64) {
    use std::f64::consts::LN_10;
    let v = speed_m_s;
    let rho = fluid_density_kg_m3;
    let re = reynolds(rho, voidage * v, d_m, viscosity_pa_s);
    let root = re.sqrt();
    let a = 0.63 + 4.8 / root;
    let b = 1.26 + 4.8 / root;
    let half_rho_area = 0.5 * rho * sphere_area_m2(d_m);
    let s0 = half_rho_area * (a * a) * v * v;
    let s1 = half_rho_area * v * a * b;
    let s2 = half_rho_area * (a * b - 2.4 * (a + b) / root);
    let l = 1.5 - re.log10();
    let e = (-0.5 * l * l).exp();
    let chi = 3.7 - 0.65 * e;
    let g0 = ((1.0 - chi) * ln_voidage).exp();
    let q = 0.65 * e * l * ln_voidage / LN_10;
    let g1 = g0 * q / v;
    let g2 = g0 * (q * q - q + 0.65 * e * (l * l - 1.0) * ln_voidage / (LN_10 * LN_10)) / (v * v);
    (
        s0 * g0,
        s1 * g0 + s0 * g1,
        s2 * g0 + 2.0 * s1 * g1 + s0 * g2,
    )
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
    fn correlations_at_hand_checked_points() {
        // Schiller–Naumann at Re = 1: 24 · 1.15 = 27.6; Clift–Gauvin adds 0.42/42501.
        assert!((cd_schiller_naumann(1.0) - 27.6).abs() < 1e-12);
        assert!((cd_clift_gauvin(1.0) - 27.6 - 0.42 / 42501.0).abs() < 1e-12);
        // Morrison at Re = 200: 0.767731559965 (the `fluids` library's doc example of the same
        // formula, an independent transcription).
        assert!((cd_morrison(200.0) - 0.767731559965).abs() < 1e-9);
        // Every correlation tends to Stokes as Re → 0 (C_d Re / 24 → 1).
        for c in [
            CdCorrelation::SchillerNaumann,
            CdCorrelation::CliftGauvin,
            CdCorrelation::Morrison,
        ] {
            assert!((c.cd(1e-9) * 1e-9 / 24.0 - 1.0).abs() < 1e-4, "{c:?}");
            assert!(c.cd(1e-300).is_finite());
        }
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
