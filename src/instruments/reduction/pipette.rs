//! The pipette reduction (seed 000 §4.5.3, eqs. 16–17; the pipette method of BS 1377-2 and
//! ISO 17892-4): a volume V_p drawn at the depth z_p at the time t, dried and weighed.
//!
//! - Percent finer: the mass concentration of the draw over that of the initial suspension,
//!   P = 100 (m_p − m_b)/V_p / (M_d/V_sp), m_p the oven-dry mass of the draw, m_b that of the
//!   dispersant in one draw (the blank), M_d the specimen's dry mass, V_sp the suspension's
//!   volume (seed eq. 17 with c_o = m_p/V_p; in BS 1377-2 the same ratio is written
//!   P = (m_p − m_b) · V_sp/(V_p M_d) · 100).
//! - Diameter: Stokes' limiting diameter at the tip's depth (seed eq. 16),
//!   D = √(18 μ z_p / (ρ_f (G_s − 1) g t)), μ = μ_w(T), ρ_f the clear fluid's density
//!   (`fluid_density_kg_m3` if given, else ρ_w(T)), g = `gravity_m_s2` if given, else D7928's
//!   9.807 m/s².
//!
//! The standards also fix the depth (BS 1377-2: 100 mm) and a reading schedule from Stokes'
//! law for chosen sizes; the reduction takes the depth and times the file gives. The standards
//! themselves could not be read here; the formula is the one their method implies and seed 000
//! states (eq. 17), not a quoted clause.

use super::{
    d7928, stokes_diameter_m, water_density_kg_m3, water_viscosity_pa_s, Instrument, LabReading,
    Reduced, TestSetup,
};

/// Density of the clear fluid ρ_f (kg/m³) and gravity g (m/s²) the pipette and sphere
/// reductions use: the file's model figures, else ρ_w(T) and D7928's g.
pub fn fluid_and_gravity(s: &TestSetup, temperature_c: f64) -> (f64, f64) {
    (
        s.model
            .fluid_density_kg_m3
            .unwrap_or_else(|| water_density_kg_m3(temperature_c)),
        s.model.gravity_m_s2.unwrap_or(d7928::GRAVITY_M_S2),
    )
}

/// Stokes' limiting diameter at `depth_m` (seed eq. 16) with the fluid of [`fluid_and_gravity`]
/// and Δρ = ρ_f (G_s − 1), m.
pub fn diameter_m(s: &TestSetup, r: &LabReading, depth_m: f64) -> f64 {
    let (rho_f, g) = fluid_and_gravity(s, r.temperature_c);
    stokes_diameter_m(
        water_viscosity_pa_s(r.temperature_c),
        depth_m,
        r.time_s,
        rho_f * (s.specific_gravity - 1.0),
        g,
    )
}

/// P = 100 (m_p − m_b)/V_p / (M_d/V_sp), % (`net_g` = m_p − m_b in g, `volume_m3` = V_p).
pub fn percent_finer(s: &TestSetup, net_g: f64, volume_m3: f64) -> f64 {
    100.0 * (net_g * 1e-3 / volume_m3) / (s.dry_mass_kg / s.suspension_volume_m3)
}

/// Reduces one pipette draw (`s.instrument` must be a pipette).
pub fn reduce_one(s: &TestSetup, r: &LabReading) -> Reduced {
    let Instrument::Pipette {
        volume_m3, depth_m, ..
    } = s.instrument
    else {
        panic!("pipette::reduce_one called for a {}", s.instrument.name());
    };
    let net = r.reading - r.blank_reading;
    Reduced {
        reading: *r,
        net_reading: net,
        effective_depth_m: depth_m,
        viscosity_pa_s: water_viscosity_pa_s(r.temperature_c),
        diameter_m: diameter_m(s, r, depth_m),
        percent_finer: percent_finer(s, net, volume_m3),
    }
}
