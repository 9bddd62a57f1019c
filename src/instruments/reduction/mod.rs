//! The standard data reduction of soil-hydrometer readings: from (time, reading, temperature,
//! blank reading) and the test's figures to (effective depth, Stokes diameter, percent finer),
//! as a laboratory does it by ASTM D422 ([`d422`], withdrawn 2016, what seed 000 uses) or ASTM
//! D7928-17/21 ([`d7928`], its replacement); and of the pipette's draws ([`pipette`]) and the
//! buoyancy sphere's weighings ([`sphere`]) by seed 000's eqs. 16–18 and 22 ([`Instrument`]).
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
pub mod pipette;
pub mod sphere;

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

/// One reading as a laboratory records it (hydrometer, pipette or sphere).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LabReading {
    /// Time since the end of the agitation, s.
    pub time_s: f64,
    /// Reading in the suspension, in the instrument's unit ([`Instrument::unit`]): hydrometer
    /// at the top of the meniscus (g/L or specific gravity), pipette the oven-dry mass of one
    /// draw (g), sphere its apparent mass (g).
    pub reading: f64,
    /// Temperature of the suspension, °C.
    pub temperature_c: f64,
    /// Reading of the same hydrometer in the companion cylinder (water + dispersant, same
    /// temperature, same meniscus position); pipette: the dispersant's dry mass in one draw, g
    /// (0 unless given); sphere: 0.
    pub blank_reading: f64,
}

/// The instrument a test was read with, and its figures (SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Instrument {
    /// A soil hydrometer of ASTM E100 (the file's `hydrometer` key), reduced by `standard`.
    Hydrometer(HydrometerType),
    /// A pipette drawing `volume_m3` around its tip at `depth_m` below the free surface
    /// (seed 000 §4.5.3): the reading is the oven-dry mass of solids in one draw.
    Pipette {
        /// Volume of one draw V_p, m³.
        volume_m3: f64,
        /// Depth of the tip below the free surface, m.
        depth_m: f64,
        /// The region the draw comes from (used by the forward model, not by the reduction).
        region: PipetteRegion,
    },
    /// A sphere of `diameter_m` and `mass_kg` (in air) hung with its centre at `depth_m` below
    /// the free surface from a dynamometer (seed 000 §4.5.2): the reading is its apparent mass.
    BuoyancySphere {
        /// Diameter of the sphere, m.
        diameter_m: f64,
        /// Mass of the sphere in air m_sp,a, kg.
        mass_kg: f64,
        /// Depth of its centre below the free surface, m.
        depth_m: f64,
    },
}

/// Where a pipette's draw comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PipetteRegion {
    /// A sphere of the draw's volume centred on the tip (the laboratory's pipette).
    Sphere,
    /// A disc of the 2D plane centred on the tip (settle's 2D model, [`crate::instruments::pipette`]).
    Disc {
        /// Radius of the disc, m.
        radius_m: f64,
    },
}

impl Instrument {
    /// Its name in a readings file: `hydrometer`, `pipette` or `buoyancy-sphere`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Hydrometer(_) => "hydrometer",
            Self::Pipette { .. } => "pipette",
            Self::BuoyancySphere { .. } => "buoyancy-sphere",
        }
    }

    /// The hydrometer, if it is one.
    pub fn hydrometer(&self) -> Option<HydrometerType> {
        match self {
            Self::Hydrometer(h) => Some(*h),
            _ => None,
        }
    }

    /// The column of its readings in a readings file: `reading` (hydrometer, in its unit),
    /// `drawn_mass_g` (pipette) or `apparent_mass_g` (sphere).
    pub fn reading_column(&self) -> &'static str {
        match self {
            Self::Hydrometer(_) => "reading",
            Self::Pipette { .. } => "drawn_mass_g",
            Self::BuoyancySphere { .. } => "apparent_mass_g",
        }
    }

    /// The unit of its readings (`LabReading::reading`).
    pub fn unit(&self) -> &'static str {
        match self {
            Self::Hydrometer(h) => h.unit(),
            _ => "g",
        }
    }
}

/// Figures of the test that the forward model of `settle invert` uses and the standard
/// reductions do not (all optional, SI). The pipette and sphere reductions take the Stokes
/// diameter's ρ_f and g from here when given.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ModelFigures {
    /// Density of the clear fluid (water + dispersant) ρ_f, kg/m³ (`fluid_density_kg_m3`).
    pub fluid_density_kg_m3: Option<f64>,
    /// Gravity g, m/s² (`gravity_m_s2`).
    pub gravity_m_s2: Option<f64>,
    /// Height of the suspension in the cylinder H, m (`column_height_cm`).
    pub column_height_m: Option<f64>,
    /// Length of the hydrometer's bulb L₂, m (`hydrometer_bulb_length_cm`, hydrometer only).
    pub hydrometer_bulb_length_m: Option<f64>,
}

/// The test's figures the reduction needs besides the readings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TestSetup {
    /// The standard a hydrometer's readings are reduced by. The pipette and the sphere have no
    /// standard choice (seed 000 eqs. 16–18 and 22, [`pipette`], [`sphere`]): [`Standard::D7928`]
    /// there, whose water properties at T their Stokes diameter uses.
    pub standard: Standard,
    /// The instrument and its figures.
    pub instrument: Instrument,
    /// Oven-dry mass of the specimen in suspension, kg.
    pub dry_mass_kg: f64,
    /// Specific gravity of the soil solids, G_s.
    pub specific_gravity: f64,
    /// Meniscus correction C_m, in the hydrometer's unit (reading at the liquid level minus
    /// reading at the top of the meniscus, ≥ 0; 0 for the pipette and the sphere).
    pub meniscus_correction: f64,
    /// Volume of the suspension, m³ (1000 mL in both standards).
    pub suspension_volume_m3: f64,
    /// D7928: the hydrometer's measured dimensions (None for D422, which uses its Table 2).
    pub measured: Option<d7928::MeasuredHydrometer>,
    /// The forward model's figures (`settle invert`).
    pub model: ModelFigures,
}

impl TestSetup {
    /// The hydrometer type (152H when the instrument is not a hydrometer: the standards'
    /// functions are only called for hydrometers).
    pub fn hydrometer(&self) -> HydrometerType {
        self.instrument.hydrometer().unwrap_or(HydrometerType::H152)
    }
}

/// One reading reduced.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reduced {
    /// The reading it comes from.
    pub reading: LabReading,
    /// The soil's contribution: reading minus the blank (hydrometer, pipette), or the clear-fluid
    /// apparent mass minus the apparent mass (sphere, g).
    pub net_reading: f64,
    /// Effective depth (hydrometer), the tip's depth (pipette) or the centre's (sphere), m.
    pub effective_depth_m: f64,
    /// Viscosity of water at the reading's temperature, Pa s.
    pub viscosity_pa_s: f64,
    /// Stokes diameter, m.
    pub diameter_m: f64,
    /// Mass percent finer than the diameter, % of the specimen's dry mass.
    pub percent_finer: f64,
}

/// Reduces every reading: a hydrometer's by `setup`'s standard (D422 as in [`d422`], D7928 as
/// in [`d7928`]), a pipette's as in [`pipette`], a sphere's as in [`sphere`]. The inputs must
/// have been checked (scale, times, temperatures, figures): see `settle::reduce` for the checks.
pub fn reduce(setup: &TestSetup, readings: &[LabReading]) -> Vec<Reduced> {
    readings
        .iter()
        .map(|r| match (setup.instrument, setup.standard) {
            (Instrument::Hydrometer(_), Standard::D422) => d422::reduce_one(setup, r),
            (Instrument::Hydrometer(_), Standard::D7928) => d7928::reduce_one(setup, r),
            (Instrument::Pipette { .. }, _) => pipette::reduce_one(setup, r),
            (Instrument::BuoyancySphere { .. }, _) => sphere::reduce_one(setup, r),
        })
        .collect()
}
