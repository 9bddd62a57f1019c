//! ASTM D7928-17 (and -21): the sedimentation (hydrometer) analysis that replaced D422's.
//!
//! What differs from D422 ([`super::d422`]):
//!
//! - Effective depth from the hydrometer's own measured dimensions instead of a table
//!   ([`MeasuredHydrometer::effective_depth_m`]): H_m = H_r2 + (H_r1 − H_r2)(r₂ − r)/(r₂ − r₁)
//!   − V_hb/(2 A_c), H_r1 and H_r2 the distances from the centre of volume of the bulb to the
//!   scale marks r₁ (top of the stem: −5 g/L on a 152H) and r₂ (bottom: 60 g/L), V_hb the bulb
//!   volume, A_c the cylinder's inside section, r the reading corrected for the meniscus.
//! - The dispersant correction r_d, read with the same hydrometer in a companion cylinder of
//!   water and dispersant at the same temperature at each reading, replaces D422's composite
//!   correction (temperature, dispersant and meniscus cancel in r − r_d).
//! - The viscosity and density of water at the test temperature enter the diameter
//!   ([`diameter_m`]): D = √(18 μ H_m / (ρ_w (G_s − 1) g t)).
//! - Percent finer ([`percent_finer`]): 152H N = 0.6226 · G_s/(G_s − 1) · (V_sp/M_d) · (r − r_d)
//!   · 100 (0.6226 = 1.65/2.65: the 152H reads grams per litre of a soil of G = 2.65); 151H
//!   N = ρ_c · G_s/(G_s − 1) · (V_sp/M_d) · (r − r_d) · 100 with ρ_c the density of water at the
//!   20 °C calibration temperature (the 151H reads the suspension's specific gravity 20/20 °C).
//! - Reading schedule 1, 2, 4, 15, 30, 60, 240 and 1440 min ([`TIMES_MIN`]).
//!
//! Sources: the 152H equations (percent finer, effective depth with H_r1/H_r2 at −5 and 60, the
//! diameter with μ and ρ_w at the test temperature and g = 980.7 cm/s²) are those of the R
//! package soiltestr (Mascitti, `compute_hydrometer_fines_pct_passing.R`, "sections 12.4–12.6 in
//! ASTM D7928-17"), with one change: soiltestr's code uses 60 − r + C_m; we correct the reading
//! for the meniscus as D422 does, r + C_m (a reading at the top of the meniscus is C_m below the
//! liquid level's). The 151H percent finer is derived from the meaning of its scale (we could
//! not read D7928's own equation). The schedule is as we recall D7928's, not checked. The
//! standard itself could not be read here; its clause numbers are not cited.

use super::{
    stokes_diameter_m, water_density_kg_m3, water_viscosity_pa_s, HydrometerType, LabReading,
    Reduced, TestSetup,
};
use crate::instruments::hydrometer::HydrometerSpec;

/// D7928's reading times, min.
pub const TIMES_MIN: [f64; 8] = [1.0, 2.0, 4.0, 15.0, 30.0, 60.0, 240.0, 1440.0];

/// Gravity, m/s² (980.7 cm/s²).
pub const GRAVITY_M_S2: f64 = 9.807;

/// Temperature at which the hydrometers are calibrated, °C.
pub const CALIBRATION_TEMPERATURE_C: f64 = 20.0;

/// The measured dimensions of one hydrometer and its cylinder (D7928's calibration).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeasuredHydrometer {
    /// H_r1: distance from the centre of volume of the bulb to the mark `r1`, m.
    pub h_r1_m: f64,
    /// H_r2: distance from the centre of volume of the bulb to the mark `r2`, m.
    pub h_r2_m: f64,
    /// Reading at the mark of H_r1 (the top of the stem's scale: −5 g/L or 0.995).
    pub r1: f64,
    /// Reading at the mark of H_r2 (the bottom of the scale: 60 g/L or 1.038).
    pub r2: f64,
    /// Bulb volume V_hb, m³.
    pub bulb_volume_m3: f64,
    /// Inside section of the sedimentation cylinder A_c, m².
    pub cylinder_area_m2: f64,
}

impl MeasuredHydrometer {
    /// H_m = H_r2 + (H_r1 − H_r2)(r₂ − r)/(r₂ − r₁) − V_hb/(2 A_c), m, for the reading `r`
    /// corrected for the meniscus: the depth of the bulb's centre below the surface, minus half
    /// the rise of the suspension when the bulb enters it (the same model as D422's
    /// L = L₁ + ½(L₂ − V_B/A)).
    pub fn effective_depth_m(&self, r: f64) -> f64 {
        self.h_r2_m + (self.h_r1_m - self.h_r2_m) * (self.r2 - r) / (self.r2 - self.r1)
            - self.bulb_volume_m3 / (2.0 * self.cylinder_area_m2)
    }

    /// The dimensions of the D422 hydrometer of Table 2 (`hydrometer`) in its 27.8 cm²
    /// cylinder: the mark r is at L(r) + V_B/(2A) from the bulb's centre, L(r) Table 2's law
    /// ([`super::d422::effective_depth_m`]). With these, D7928's H_m equals D422's L at every
    /// reading.
    pub fn table2(hydrometer: HydrometerType) -> Self {
        let spec = HydrometerSpec::default();
        let rise = spec.bulb_volume_m3 / (2.0 * spec.astm_cylinder_area_m2);
        let at = |r: f64| super::d422::effective_depth_m(hydrometer, r) + rise;
        let (r1, r2) = hydrometer.scale();
        Self {
            h_r1_m: at(r1),
            h_r2_m: at(r2),
            r1,
            r2,
            bulb_volume_m3: spec.bulb_volume_m3,
            cylinder_area_m2: spec.astm_cylinder_area_m2,
        }
    }
}

/// Mass percent finer N, %: 152H 0.6226 · G_s/(G_s − 1) · (V_sp/M_d) · (r − r_d) · 100, with
/// (V_sp/M_d) in L/g and r in g/L; 151H ρ_c · G_s/(G_s − 1) · (V_sp/M_d) · (r − r_d) · 100 with
/// (V_sp/M_d) in mL/g and ρ_c = ρ_w(20 °C) in g/mL.
pub fn percent_finer(
    hydrometer: HydrometerType,
    net: f64,
    specific_gravity: f64,
    dry_mass_kg: f64,
    suspension_volume_m3: f64,
) -> f64 {
    let gs = specific_gravity / (specific_gravity - 1.0);
    let m_g = dry_mass_kg * 1e3;
    match hydrometer {
        HydrometerType::H152 => {
            let gc = HydrometerSpec::default().calibration_specific_gravity;
            (gc - 1.0) / gc * gs * (suspension_volume_m3 * 1e3 / m_g) * net * 100.0
        }
        HydrometerType::H151 => {
            let rho_c = water_density_kg_m3(CALIBRATION_TEMPERATURE_C) * 1e-3;
            rho_c * gs * (suspension_volume_m3 * 1e6 / m_g) * net * 100.0
        }
    }
}

/// D = √(18 μ H_m / (ρ_w (G_s − 1) g t)), m, with μ and ρ_w of water at the temperature.
pub fn diameter_m(temperature_c: f64, specific_gravity: f64, depth_m: f64, time_s: f64) -> f64 {
    stokes_diameter_m(
        water_viscosity_pa_s(temperature_c),
        depth_m,
        time_s,
        water_density_kg_m3(temperature_c) * (specific_gravity - 1.0),
        GRAVITY_M_S2,
    )
}

/// Reduces one reading by D7928 with the measured dimensions `s.measured` (the Table 2
/// hydrometer of [`MeasuredHydrometer::table2`] if None; `settle reduce` requires them).
pub fn reduce_one(s: &TestSetup, r: &LabReading) -> Reduced {
    let m = s
        .measured
        .unwrap_or_else(|| MeasuredHydrometer::table2(s.hydrometer()));
    let net = r.reading - r.blank_reading;
    let depth = m.effective_depth_m(r.reading + s.meniscus_correction);
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
