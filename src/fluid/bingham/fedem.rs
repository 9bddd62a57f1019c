//! Drag on a sphere in a Bingham plastic after f-EDEM §2 (Dedegil 1987).
//!
//! F_d = (π d / 2)² τ_y + ½ C_d ρ_f v² A                        (f-EDEM eq. 9)
//! Re' = ρ_f v² / (τ_y + η_B v / d)                              (f-EDEM eq. 14)
//! C_d = 24/Re' (Re' < 1); 29.12/Re' + 0.195 (1 ≤ Re' ≤ 150); 0.4 (Re' > 150)   (f-EDEM eq. 19)
//!
//! Substituting eq. 14 into eq. 19 makes every branch a quadratic in the speed v:
//! - Re' < 1:        F = F_y + 12 A (τ_y + η_B v/d)
//! - 1 ≤ Re' ≤ 150:  F = F_y + 14.56 A (τ_y + η_B v/d) + 0.0975 ρ_f A v²
//! - Re' > 150:      F = F_y + 0.2 ρ_f A v²
//!
//! with F_y = (π d/2)² τ_y and A = π d²/4. As v → 0 the drag tends to the finite static
//! resistance F_y + 12 A τ_y = (π²/4 + 3π) d² τ_y: at rest the drag is set-valued, like Coulomb
//! friction. Eq. 19 jumps upwards at Re' = 1 (C_d 24 → 29.315) and Re' = 150 (0.389 → 0.4), so
//! the drag is a monotone increasing function of v with two upward jumps.

use crate::fluid::buoyancy::{sphere_area_m2, sphere_volume_m3};
use std::f64::consts::PI;

/// Lower branch limit of f-EDEM eq. 19: Re' = 1.
pub const BINGHAM_RE_LOW: f64 = 1.0;
/// Upper branch limit of f-EDEM eq. 19: Re' = 150.
pub const BINGHAM_RE_HIGH: f64 = 150.0;

/// Branch of f-EDEM eq. 19 a Bingham Reynolds number falls in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinghamRegime {
    /// Re' < 1: C_d = 24/Re'.
    Creeping,
    /// 1 ≤ Re' ≤ 150: C_d = 29.12/Re' + 0.195.
    Intermediate,
    /// Re' > 150: C_d = 0.4.
    Newton,
}

impl BinghamRegime {
    /// The regime of a Bingham Reynolds number (f-EDEM eq. 19's branch conditions).
    pub fn of(re_bingham: f64) -> Self {
        if re_bingham < BINGHAM_RE_LOW {
            Self::Creeping
        } else if re_bingham <= BINGHAM_RE_HIGH {
            Self::Intermediate
        } else {
            Self::Newton
        }
    }

    /// Short label used in CSV output: `re<1`, `1<=re<=150`, `re>150`.
    pub fn label(self) -> &'static str {
        match self {
            Self::Creeping => "re<1",
            Self::Intermediate => "1<=re<=150",
            Self::Newton => "re>150",
        }
    }
}

/// Bingham particle Reynolds number, dimensionless: Re' = ρ_f v² / (τ_y + η_B v/d)
/// (f-EDEM eq. 14; eq. 18 at the terminal velocity).
pub fn reynolds_bingham(
    fluid_density_kg_m3: f64,
    speed_m_s: f64,
    d_m: f64,
    yield_stress_pa: f64,
    plastic_viscosity_pa_s: f64,
) -> f64 {
    fluid_density_kg_m3 * speed_m_s * speed_m_s
        / (yield_stress_pa + plastic_viscosity_pa_s * speed_m_s / d_m)
}

/// Drag coefficient in a Bingham plastic, f-EDEM eq. 19 (a fit to Valentik & Whitmore 1965).
pub fn cd_fedem(re_bingham: f64) -> f64 {
    match BinghamRegime::of(re_bingham) {
        BinghamRegime::Creeping => 24.0 / re_bingham,
        BinghamRegime::Intermediate => 29.12 / re_bingham + 0.195,
        BinghamRegime::Newton => 0.4,
    }
}

/// Yield-stress part of the drag, N: F_y = (π d / 2)² τ_y (first term of f-EDEM eq. 9).
pub fn yield_drag_n(d_m: f64, yield_stress_pa: f64) -> f64 {
    let a = 0.5 * PI * d_m;
    a * a * yield_stress_pa
}

/// Total Bingham drag magnitude at speed v > 0, N (f-EDEM eq. 9 with eqs. 14 and 19).
pub fn bingham_drag_n(
    fluid_density_kg_m3: f64,
    d_m: f64,
    yield_stress_pa: f64,
    plastic_viscosity_pa_s: f64,
    speed_m_s: f64,
) -> f64 {
    let re = reynolds_bingham(
        fluid_density_kg_m3,
        speed_m_s,
        d_m,
        yield_stress_pa,
        plastic_viscosity_pa_s,
    );
    yield_drag_n(d_m, yield_stress_pa)
        + 0.5 * cd_fedem(re) * fluid_density_kg_m3 * sphere_area_m2(d_m) * speed_m_s * speed_m_s
}

/// Static resistance of a sphere at rest in a Bingham plastic, N: the limit of eq. 9 as v → 0⁺,
/// F_s = F_y + 12 A τ_y = (π²/4 + 3π) d² τ_y. A sphere whose net weight is below F_s stays at rest.
pub fn bingham_static_resistance_n(d_m: f64, yield_stress_pa: f64) -> f64 {
    yield_drag_n(d_m, yield_stress_pa) + 12.0 * sphere_area_m2(d_m) * yield_stress_pa
}

/// Speed at which the Bingham Reynolds number equals `re_bingham`, m/s: the positive root of
/// ρ_f v² − Re' (η_B/d) v − Re' τ_y = 0 (eq. 14 solved for v). Locates the jumps of eq. 19.
pub fn speed_at_reynolds_bingham(
    fluid_density_kg_m3: f64,
    d_m: f64,
    yield_stress_pa: f64,
    plastic_viscosity_pa_s: f64,
    re_bingham: f64,
) -> f64 {
    let b = re_bingham * plastic_viscosity_pa_s / d_m;
    (b + (b * b + 4.0 * fluid_density_kg_m3 * re_bingham * yield_stress_pa).sqrt())
        / (2.0 * fluid_density_kg_m3)
}

/// Drag coefficient implied by a measured terminal velocity, f-EDEM eq. 17:
/// C_d = 2/(v² ρ_f) · [⅔ (ρ_p − ρ_f) d g − π τ_y].
pub fn cd_from_terminal_velocity(
    particle_density_kg_m3: f64,
    fluid_density_kg_m3: f64,
    d_m: f64,
    yield_stress_pa: f64,
    terminal_velocity_m_s: f64,
    g_m_s2: f64,
) -> f64 {
    let v = terminal_velocity_m_s;
    2.0 / (v * v * fluid_density_kg_m3)
        * (2.0 / 3.0 * (particle_density_kg_m3 - fluid_density_kg_m3) * d_m * g_m_s2
            - PI * yield_stress_pa)
}

/// Net weight of a submerged sphere, N: (ρ_p − ρ_f) g π d³/6 (f-EDEM eq. 16's first two terms).
pub fn net_weight_n(
    d_m: f64,
    particle_density_kg_m3: f64,
    fluid_density_kg_m3: f64,
    g_m_s2: f64,
) -> f64 {
    (particle_density_kg_m3 - fluid_density_kg_m3) * g_m_s2 * sphere_volume_m3(d_m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eq19_branches_and_jumps() {
        assert_eq!(cd_fedem(0.5), 48.0);
        assert!((cd_fedem(1.0) - 29.315).abs() < 1e-12);
        assert!((cd_fedem(150.0) - (29.12 / 150.0 + 0.195)).abs() < 1e-12);
        assert_eq!(cd_fedem(150.0 + 1e-9), 0.4);
        assert_eq!(BinghamRegime::of(0.999), BinghamRegime::Creeping);
        assert_eq!(BinghamRegime::of(1.0), BinghamRegime::Intermediate);
        assert_eq!(BinghamRegime::of(150.0001), BinghamRegime::Newton);
    }

    #[test]
    fn closed_form_branches_match_eq9() {
        // Suspension 1 of Valentik & Whitmore, d = 19 mm, at speeds in each branch.
        let (rho, d, ty, eb) = (1280.0, 0.019, 30.5, 0.0131);
        let a = sphere_area_m2(d);
        let fy = yield_drag_n(d, ty);
        for v in [1e-4, 0.05, 0.2, 0.5, 1.0, 3.0] {
            let re = reynolds_bingham(rho, v, d, ty, eb);
            let closed = match BinghamRegime::of(re) {
                BinghamRegime::Creeping => fy + 12.0 * a * (ty + eb * v / d),
                BinghamRegime::Intermediate => {
                    fy + 14.56 * a * (ty + eb * v / d) + 0.0975 * rho * a * v * v
                }
                BinghamRegime::Newton => fy + 0.2 * rho * a * v * v,
            };
            let f = bingham_drag_n(rho, d, ty, eb, v);
            assert!((f / closed - 1.0).abs() < 1e-12, "v = {v}: {f} vs {closed}");
        }
    }

    #[test]
    fn static_resistance_is_the_limit_at_zero_speed() {
        let (rho, d, ty, eb) = (1843.0, 0.0126, 136.0, 0.7);
        let lim = bingham_drag_n(rho, d, ty, eb, 1e-12);
        let fs = bingham_static_resistance_n(d, ty);
        assert!((lim / fs - 1.0).abs() < 1e-9);
        assert!((fs / (d * d * ty) - (PI * PI / 4.0 + 3.0 * PI)).abs() < 1e-12);
    }

    #[test]
    fn jump_speeds_have_the_right_reynolds_number() {
        let (rho, d, ty, eb) = (1226.0, 0.0254, 17.5, 0.0081);
        for re in [BINGHAM_RE_LOW, BINGHAM_RE_HIGH] {
            let v = speed_at_reynolds_bingham(rho, d, ty, eb, re);
            assert!((reynolds_bingham(rho, v, d, ty, eb) / re - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn eq17_inverts_the_force_balance() {
        // At a velocity that balances eq. 16, eq. 17 returns the C_d of eq. 9 at that speed.
        let (rho_f, rho_p, d, ty, g) = (1254.0, 6698.0, 0.0127, 22.5, 9.81);
        let v = 0.395;
        let cd = cd_from_terminal_velocity(rho_p, rho_f, d, ty, v, g);
        let drag = yield_drag_n(d, ty) + 0.5 * cd * rho_f * sphere_area_m2(d) * v * v;
        assert!((drag / net_weight_n(d, rho_p, rho_f, g) - 1.0).abs() < 1e-12);
    }
}
