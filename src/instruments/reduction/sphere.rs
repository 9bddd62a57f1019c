//! The buoyancy-sphere reduction (seed 000 §4.5.2, eqs. 16 and 22): a sphere of volume V_sp
//! and mass m_sp,a in air, hung with its centre at the depth z_b from a dynamometer that reads
//! its apparent mass m_sp at the time t.
//!
//! - Percent finer, eq. 22:
//!   w = 100 (ρ_f/c₀) (m_sp,w − m_sp)/(m_sp,w − m_sp,a) / (ρ_f/ρ_p − 1), with m_sp,w the
//!   apparent mass in the clear fluid, m_sp,w = m_sp,a − ρ_f V_sp, and c₀ = M_d/V_susp. With
//!   G_s = ρ_p/ρ_f this is w = 100 (V_susp/M_d) · G_s/(G_s − 1) · (m_sp,w − m_sp)/V_sp: the
//!   suspension's excess density around the sphere, (m_sp,w − m_sp)/V_sp, turned into a mass
//!   concentration (eq. 18) over the initial one.
//! - Diameter: Stokes at the centre's depth (eq. 16) as for the pipette
//!   ([`super::pipette::diameter_m`]).
//!
//! ρ_f is `fluid_density_kg_m3` if given (water + dispersant: the sphere's clear-fluid apparent
//! mass depends on it), else ρ_w(T) at the reading's temperature.

use super::pipette::{diameter_m, fluid_and_gravity};
use super::{water_viscosity_pa_s, Instrument, LabReading, Reduced, TestSetup};
use std::f64::consts::PI;

/// Volume of a sphere of diameter `d` (m), m³.
pub fn volume_m3(diameter_m: f64) -> f64 {
    PI * diameter_m.powi(3) / 6.0
}

/// The sphere's apparent mass in the clear fluid m_sp,w = m_sp,a − ρ_f V_sp, kg.
pub fn clear_apparent_mass_kg(mass_kg: f64, diameter_m: f64, fluid_density_kg_m3: f64) -> f64 {
    mass_kg - fluid_density_kg_m3 * volume_m3(diameter_m)
}

/// w = 100 (V_susp/M_d) · G_s/(G_s − 1) · (m_sp,w − m_sp)/V_sp (eq. 22), %, with `net_kg` =
/// m_sp,w − m_sp.
pub fn percent_finer(s: &TestSetup, net_kg: f64, diameter_m: f64) -> f64 {
    let g = s.specific_gravity;
    let excess_kg_m3 = net_kg / volume_m3(diameter_m);
    100.0 * g / (g - 1.0) * excess_kg_m3 / (s.dry_mass_kg / s.suspension_volume_m3)
}

/// Reduces one dynamometer reading (`s.instrument` must be a buoyancy sphere).
pub fn reduce_one(s: &TestSetup, r: &LabReading) -> Reduced {
    let Instrument::BuoyancySphere {
        diameter_m: d,
        mass_kg,
        depth_m,
    } = s.instrument
    else {
        panic!("sphere::reduce_one called for a {}", s.instrument.name());
    };
    let (rho_f, _) = fluid_and_gravity(s, r.temperature_c);
    let net_g = clear_apparent_mass_kg(mass_kg, d, rho_f) * 1e3 - r.reading;
    Reduced {
        reading: *r,
        net_reading: net_g,
        effective_depth_m: depth_m,
        viscosity_pa_s: water_viscosity_pa_s(r.temperature_c),
        diameter_m: diameter_m(s, r, depth_m),
        percent_finer: percent_finer(s, net_g * 1e-3, d),
    }
}
