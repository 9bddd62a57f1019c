//! ASTM D422-63(2007) (withdrawn 2016): the hydrometer part of the particle-size analysis, as
//! seed 000 uses it.
//!
//! - Effective depth: Table 2, L = L₁ + ½ (L₂ − V_B/A) with the 152H's figures (L₂ = 14.0 cm,
//!   V_B = 67 cm³, A = 27.8 cm²), i.e. L = 16.29 − 0.164 R cm for the 152H
//!   ([`HydrometerSpec`]'s defaults, the law `src/instruments/hydrometer.rs` is built on), read
//!   with the reading corrected for the meniscus only ([`effective_depth_m`]).
//! - Diameter: D = K √(L/T), K = √(30 n / (980 (G − G₁))) with n the viscosity of water in
//!   poises, L in cm, T in min, D in mm, G₁ = 1 (Table 3 tabulates K for 16–30 °C and
//!   G = 2.45–2.85); here K is computed from [`water_viscosity_pa_s`] ([`diameter_m`], [`k`]).
//! - Percent finer (the section "Percentages of soil in suspension"): 152H: P = R a / W · 100
//!   with a = 1.65 G / (2.65 (G − 1)) (Table 1); 151H: P = (100 000 / W) · G/(G − G₁) · (R − G₁)
//!   with G₁ = 1; R is the reading minus the composite correction, W the oven-dry mass in g in
//!   1000 mL ([`percent_finer`]).
//!
//! Sources: the formulas as quoted from D422-63 by textbooks (Das, *Advanced Soil Mechanics*,
//! eqs. 3.28–3.29: L = L₁ + ½(L₂ − V_h/A) and, for the 152H, L = 16.3 − 0.1641 R "for any reading
//! R (corrected for meniscus)"; Das, *Soil Mechanics Laboratory Manual*), and by the R package
//! envalysis (Steinmetz, `texture()`, which implements D422 and publishes a reduced worked
//! example, used by the tests). The standard itself could not be read here; its clause numbers
//! are therefore not cited, only its tables' numbers (1: a, 2: L, 3: K).

use super::{
    stokes_diameter_m, water_viscosity_pa_s, HydrometerType, LabReading, Reduced, TestSetup,
};
use crate::instruments::hydrometer::HydrometerSpec;

/// D422's reading times, min (2, 5, 15, 30, 60, 250, 1440).
pub const TIMES_MIN: [f64; 7] = crate::instruments::HYDROMETER_TIMES_MIN;

/// Slope of Table 2 for the 151H, m of effective depth per unit of specific gravity: 8.2 cm
/// over 0.031, the linear law of envalysis' Table 2 (L = 16.3 cm at 1.000, 6.2 cm at 1.038);
/// not checked against the standard.
pub const H151_DEPTH_SLOPE_M: f64 = 0.082 / 0.031;

/// Effective depth L of Table 2, m, for the reading `reading_cm` corrected for the meniscus
/// only (R + C_m): 152H L = 16.29 − 0.164 R cm ([`HydrometerSpec::default`]); 151H
/// L = 16.29 − 264.5 (R − 1) cm ([`H151_DEPTH_SLOPE_M`]).
pub fn effective_depth_m(hydrometer: HydrometerType, reading_corrected: f64) -> f64 {
    let s = HydrometerSpec::default();
    match hydrometer {
        HydrometerType::H152 => {
            s.effective_depth_zero_m - s.effective_depth_slope_m * reading_corrected
        }
        HydrometerType::H151 => {
            s.effective_depth_zero_m - H151_DEPTH_SLOPE_M * (reading_corrected - 1.0)
        }
    }
}

/// Table 1's correction factor a = 1.65 G / (2.65 (G − 1)) of the 152H (its scale is grams of
/// soil of G = 2.65 per litre; a = 1 at G = 2.65).
pub fn correction_factor_a(specific_gravity: f64) -> f64 {
    let gc = HydrometerSpec::default().calibration_specific_gravity;
    (gc - 1.0) * specific_gravity / (gc * (specific_gravity - 1.0))
}

/// Percent finer, %: 152H P = R a / W · 100; 151H P = (100 000 / W) · G/(G − 1) · (R − 1),
/// with `net` = R minus the composite correction minus the scale's zero (= reading − blank),
/// W the dry mass in g, scaled to the suspension's volume (W per 1000 mL in D422).
pub fn percent_finer(
    hydrometer: HydrometerType,
    net: f64,
    specific_gravity: f64,
    dry_mass_kg: f64,
    suspension_volume_m3: f64,
) -> f64 {
    let w_g_per_l = dry_mass_kg * 1e3 / (suspension_volume_m3 * 1e3);
    match hydrometer {
        HydrometerType::H152 => net * correction_factor_a(specific_gravity) / w_g_per_l * 100.0,
        HydrometerType::H151 => {
            100_000.0 / w_g_per_l * specific_gravity / (specific_gravity - 1.0) * net
        }
    }
}

/// D422's gravity, m/s² (980 cm/s² in K).
pub const GRAVITY_M_S2: f64 = 9.80;

/// K of Table 3, mm·(min/cm)^½: K = √(30 n / (980 (G − 1))), n = 10 μ in poises.
pub fn k(temperature_c: f64, specific_gravity: f64) -> f64 {
    let n_poise = 10.0 * water_viscosity_pa_s(temperature_c);
    (30.0 * n_poise / (980.0 * (specific_gravity - 1.0))).sqrt()
}

/// D = K √(L/T) in SI, m: √(18 μ L / (ρ₁ g (G − 1) t)) with ρ₁ = 1000 kg/m³ (G₁ = 1) and
/// g = 9.80 m/s², D422's constants.
pub fn diameter_m(temperature_c: f64, specific_gravity: f64, depth_m: f64, time_s: f64) -> f64 {
    stokes_diameter_m(
        water_viscosity_pa_s(temperature_c),
        depth_m,
        time_s,
        1000.0 * (specific_gravity - 1.0),
        GRAVITY_M_S2,
    )
}

/// Reduces one reading by D422.
pub fn reduce_one(s: &TestSetup, r: &LabReading) -> Reduced {
    let net = r.reading - r.blank_reading;
    let depth = effective_depth_m(s.hydrometer(), r.reading + s.meniscus_correction);
    Reduced {
        reading: *r,
        net_reading: net,
        effective_depth_m: depth,
        viscosity_pa_s: water_viscosity_pa_s(r.temperature_c),
        diameter_m: diameter_m(r.temperature_c, s.specific_gravity, depth, r.time_s),
        percent_finer: percent_finer(
            s.hydrometer(),
            net,
            s.specific_gravity,
            s.dry_mass_kg,
            s.suspension_volume_m3,
        ),
    }
}
