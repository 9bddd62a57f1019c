//! The standard data reduction of soil-hydrometer readings: from (time, reading, temperature,
//! blank reading) and the test's figures to (effective depth, Stokes diameter, percent finer),
//! as a laboratory does it by ASTM D422 ([`d422`], withdrawn 2016, what seed 000 uses) or ASTM
//! D7928-17/21 ([`d7928`], its replacement).
//!
//! Pure functions, SI units inside (the laboratory units of the standards, g, mL, cm, min, are
//! converted where the standards' equations are quoted).
//!
//! # What the two standards share
//!
//! - The diameter is Stokes' limiting diameter of a grain that fell from the surface to the
//!   effective depth H in the time t: D = √(18 μ H / ((ρ_s − ρ_w) g t)) ([`stokes_diameter_m`]).
//! - The percent finer is the mass of soil per volume at the effective depth over the mass per
//!   volume of the initial suspension. The hydrometer reading r minus the reading r_d of the same
//!   hydrometer in a companion cylinder holding the same water and dispersant at the same
//!   temperature (the *blank*) is the soil's own contribution: D422 calls the blank's offset the
//!   composite correction (temperature, dispersant, meniscus; D422 §14 as quoted by textbooks),
//!   D7928 the dispersant correction r_d read in the companion cylinder at each reading.
//! - The effective depth uses the reading corrected for the meniscus only, r + C_m: readings
//!   are taken at the top of the meniscus in the opaque suspension, which is higher on the stem,
//!   so lower on the scale, than the liquid level by C_m.
//!
//! # Sources and what could be checked
//!
//! The standards themselves could not be read here. The equations are those of the public
//! implementations and textbooks named on each function; each doc comment says which.
//! Water properties: [`water_viscosity_pa_s`] (Kestin, Sokolov & Wakeham 1978) and
//! [`water_density_kg_m3`] (Tanaka et al. 2001), both checked by tests against tabulated values.

pub mod d422;
pub mod d7928;

/// The two soil hydrometers of ASTM E100 used by D422 and D7928.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HydrometerType {
    /// 152H: reads grams of soil of G_s = 2.65 per litre, scale −5 to 60 g/L.
    H152,
    /// 151H: reads the specific gravity of the suspension (20/20 °C), scale 0.995 to 1.038.
    H151,
}

impl HydrometerType {
    /// Parses `152H` / `151H` (case-insensitive, the `H` optional).
    pub fn parse(s: &str) -> Option<Self> {
        match s.trim().to_ascii_uppercase().trim_end_matches('H') {
            "152" => Some(Self::H152),
            "151" => Some(Self::H151),
            _ => None,
        }
    }

    /// Its name, `152H` or `151H`.
    pub fn name(self) -> &'static str {
        match self {
            Self::H152 => "152H",
            Self::H151 => "151H",
        }
    }

    /// The graduated scale (lowest, highest reading): 152H −5 to 60 g/L, 151H 0.995 to 1.038
    /// (the figures commonly quoted for ASTM E100's soil hydrometers, used by soiltestr for the
    /// 152H's H_r1/H_r2 marks; not checked against E100 itself). A reading outside cannot be
    /// read.
    pub fn scale(self) -> (f64, f64) {
        match self {
            Self::H152 => (-5.0, 60.0),
            Self::H151 => (0.995, 1.038),
        }
    }

    /// The reading in clear water at 20 °C: 0 (152H) or 1 (151H).
    pub fn zero(self) -> f64 {
        match self {
            Self::H152 => 0.0,
            Self::H151 => 1.0,
        }
    }

    /// The unit of its readings.
    pub fn unit(self) -> &'static str {
        match self {
            Self::H152 => "g/L",
            Self::H151 => "specific gravity",
        }
    }
}

/// The standard a reduction follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Standard {
    /// ASTM D422-63(2007), withdrawn 2016.
    D422,
    /// ASTM D7928-17 (and -21, whose calculation is unchanged as far as we know).
    D7928,
}

impl Standard {
    /// Parses `d422` / `d7928` (case-insensitive, `ASTM` prefix allowed).
    pub fn parse(s: &str) -> Option<Self> {
        let s = s.trim().to_ascii_lowercase().replace([' ', '-', '_'], "");
        match s.trim_start_matches("astm") {
            "d422" => Some(Self::D422),
            "d7928" => Some(Self::D7928),
            _ => None,
        }
    }

    /// Its name, `d422` or `d7928`.
    pub fn name(self) -> &'static str {
        match self {
            Self::D422 => "d422",
            Self::D7928 => "d7928",
        }
    }

    /// Temperatures the reduction accepts, °C. D422: 16–30 °C, the span of its Table 3 (K).
    /// D7928: 15–30 °C, our choice (its own water table could not be checked); the viscosity
    /// correlation used is valid 0–40 °C.
    pub fn temperature_range_c(self) -> (f64, f64) {
        match self {
            Self::D422 => (16.0, 30.0),
            Self::D7928 => (15.0, 30.0),
        }
    }
}

/// Dynamic viscosity of liquid water at 0.1 MPa, Pa s, 0–40 °C:
/// log₁₀(μ/μ₂₀) = (20 − t)/(t + 96) · [1.2364 − 1.37·10⁻³ (20 − t) + 5.7·10⁻⁶ (20 − t)²],
/// μ₂₀ = 1.0016 mPa s (Kestin, Sokolov & Wakeham 1978, J. Phys. Chem. Ref. Data 7, 941, with
/// the ITS-90 value of μ₂₀ used by the IAPWS 2008 formulation). Within 0.05 % of the IAPWS
/// values at 10–40 °C (tested).
pub fn water_viscosity_pa_s(t_c: f64) -> f64 {
    let d = 20.0 - t_c;
    let e = d / (t_c + 96.0) * (1.2364 - 1.37e-3 * d + 5.7e-6 * d * d);
    1.0016e-3 * 10f64.powf(e)
}

/// Density of air-free water at 0.1 MPa, kg/m³, 0–40 °C:
/// ρ = a₅ [1 − (t + a₁)² (t + a₂) / (a₃ (t + a₄))] (Tanaka, Girard, Davis, Peuto & Bignell
/// 2001, Metrologia 38, 301, the CIPM formula): 998.207 kg/m³ at 20 °C (tested).
pub fn water_density_kg_m3(t_c: f64) -> f64 {
    let (a1, a2, a3, a4, a5) = (-3.983035, 301.797, 522_528.9, 69.34881, 999.974950);
    a5 * (1.0 - (t_c + a1).powi(2) * (t_c + a2) / (a3 * (t_c + a4)))
}

/// Stokes' limiting diameter, m: D = √(18 μ H / (Δρ g t)) for a grain of density excess Δρ
/// (kg/m³) that fell the depth H (m) in the time t (s) through a fluid of viscosity μ (Pa s).
pub fn stokes_diameter_m(
    viscosity_pa_s: f64,
    depth_m: f64,
    time_s: f64,
    density_excess_kg_m3: f64,
    gravity_m_s2: f64,
) -> f64 {
    (18.0 * viscosity_pa_s * depth_m / (density_excess_kg_m3 * gravity_m_s2 * time_s)).sqrt()
}

/// One hydrometer reading as a laboratory records it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LabReading {
    /// Time since the end of the agitation, s.
    pub time_s: f64,
    /// Reading in the suspension (at the top of the meniscus), in the hydrometer's unit.
    pub reading: f64,
    /// Temperature of the suspension, °C.
    pub temperature_c: f64,
    /// Reading of the same hydrometer in the companion cylinder (water + dispersant, same
    /// temperature, same meniscus position).
    pub blank_reading: f64,
}

/// The test's figures the reduction needs besides the readings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TestSetup {
    /// The standard followed.
    pub standard: Standard,
    /// The hydrometer.
    pub hydrometer: HydrometerType,
    /// Oven-dry mass of the specimen in suspension, kg.
    pub dry_mass_kg: f64,
    /// Specific gravity of the soil solids, G_s.
    pub specific_gravity: f64,
    /// Meniscus correction C_m, in the hydrometer's unit (reading at the liquid level minus
    /// reading at the top of the meniscus, ≥ 0).
    pub meniscus_correction: f64,
    /// Volume of the suspension, m³ (1000 mL in both standards).
    pub suspension_volume_m3: f64,
    /// D7928: the hydrometer's measured dimensions (None for D422, which uses its Table 2).
    pub measured: Option<d7928::MeasuredHydrometer>,
}

/// One reading reduced.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reduced {
    /// The reading it comes from.
    pub reading: LabReading,
    /// Reading minus the blank (the soil's contribution), in the hydrometer's unit.
    pub net_reading: f64,
    /// Effective depth, m.
    pub effective_depth_m: f64,
    /// Viscosity of water at the reading's temperature, Pa s.
    pub viscosity_pa_s: f64,
    /// Stokes diameter, m.
    pub diameter_m: f64,
    /// Mass percent finer than the diameter, % of the specimen's dry mass.
    pub percent_finer: f64,
}

/// Reduces every reading by `setup`'s standard (D422 §§ as in [`d422`], D7928 as in [`d7928`]).
/// The inputs must have been checked (scale, times, temperatures, figures): see
/// `settle::reduce` for the checks.
pub fn reduce(setup: &TestSetup, readings: &[LabReading]) -> Vec<Reduced> {
    readings
        .iter()
        .map(|r| match setup.standard {
            Standard::D422 => d422::reduce_one(setup, r),
            Standard::D7928 => d7928::reduce_one(setup, r),
        })
        .collect()
}
