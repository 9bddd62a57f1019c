//! Kind `sedimentation`: the tables `[sample]` and `[instruments]` (serde). Their methods and
//! checks (which read the whole scenario) and the kind's spec are in `kinds/sedimentation.rs`.

use serde::{Deserialize, Serialize};

/// The laboratory instruments of a sedimentation run (seed 000 §4.5): the ASTM E100 152H
/// hydrometer, the buoyancy sphere and the pipette. Every field has a default.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct InstrumentsSpec {
    /// Hydrometer reading times, s. Default ASTM D422: 2, 5, 15, 30, 60, 250, 1440 min (those
    /// within `time.end_s`).
    pub hydrometer_times_s: Vec<f64>,
    /// Buoyancy sphere reading times, s. Default 0.5, 1, 2, 4, 15, 30, 60, 120, 240, 480 min.
    pub buoyancy_times_s: Vec<f64>,
    /// Pipette draw times, s. Default: those of the buoyancy sphere.
    pub pipette_times_s: Vec<f64>,
    /// Hydrometer bulb volume V_B, m³. Default 67e-6 (152H).
    pub hydrometer_bulb_volume_m3: f64,
    /// Hydrometer bulb length L₂, m. Default 0.14 (152H).
    pub hydrometer_bulb_length_m: f64,
    /// Length of each conical end of the bulb, m. Default 0.025.
    pub hydrometer_taper_m: f64,
    /// Hydrometer stem length, m. Default 0.14.
    pub hydrometer_stem_length_m: f64,
    /// ASTM D422 Table 2 effective depth at R = 0, m. Default 0.1629.
    pub hydrometer_effective_depth_zero_m: f64,
    /// Decrease of the effective depth per g/L of reading, m. Default 0.00164.
    pub hydrometer_effective_depth_slope_m: f64,
    /// Full scale of the hydrometer, g/L. Default 60.
    pub hydrometer_full_scale: f64,
    /// Cylinder section A of ASTM D422's L = L₁ + ½(L₂ − V_B/A), m². Default 27.8e-4.
    pub hydrometer_astm_cylinder_area_m2: f64,
    /// Specific gravity of the soil the scale is calibrated for. Default 2.65.
    pub hydrometer_calibration_specific_gravity: f64,
    /// Buoyancy sphere diameter, m. Default 0.025 (Teflon).
    pub sphere_diameter_m: f64,
    /// Buoyancy sphere mass in air, kg. Default 0.020.
    pub sphere_mass_kg: f64,
    /// Depth of the sphere's centre y_bt as a fraction of H. Default 0.3.
    pub sphere_depth_fraction: f64,
    /// Pipette volume, m³ (real cylinder). Default 35e-6.
    pub pipette_volume_m3: f64,
    /// Depth of the pipette tip y_pt as a fraction of H. Default 0.3.
    pub pipette_depth_fraction: f64,
}

impl Default for InstrumentsSpec {
    fn default() -> Self {
        let min = |m: &[f64]| m.iter().map(|x| x * 60.0).collect::<Vec<_>>();
        Self {
            hydrometer_times_s: min(&[2.0, 5.0, 15.0, 30.0, 60.0, 250.0, 1440.0]),
            buoyancy_times_s: min(&[0.5, 1.0, 2.0, 4.0, 15.0, 30.0, 60.0, 120.0, 240.0, 480.0]),
            pipette_times_s: min(&[0.5, 1.0, 2.0, 4.0, 15.0, 30.0, 60.0, 120.0, 240.0, 480.0]),
            hydrometer_bulb_volume_m3: 67e-6,
            hydrometer_bulb_length_m: 0.14,
            hydrometer_taper_m: 0.025,
            hydrometer_stem_length_m: 0.14,
            hydrometer_effective_depth_zero_m: 0.1629,
            hydrometer_effective_depth_slope_m: 0.00164,
            hydrometer_full_scale: 60.0,
            hydrometer_astm_cylinder_area_m2: 27.8e-4,
            hydrometer_calibration_specific_gravity: 2.65,
            sphere_diameter_m: 0.025,
            sphere_mass_kg: 0.020,
            sphere_depth_fraction: 0.3,
            pipette_volume_m3: 35e-6,
            pipette_depth_fraction: 0.3,
        }
    }
}

/// A soil sample for the sedimentation cylinder (seed 000 §4.4, §5.1).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SampleSpec {
    /// CSV of cumulative distributions (`sample, diameter_m, percent_finer`), relative to the
    /// scenario file; piecewise linear in log d between its points.
    pub csv: String,
    /// Which sample of the file.
    pub sample: u32,
    /// Dry mass of soil in the whole cylinder, kg (seed: 0.06).
    pub mass_kg: f64,
    /// Grain density ρ_p, kg/m³ (seed: 2500).
    pub density_kg_m3: f64,
    /// Number of discrete diameters n_φ, log-spaced over the distribution (seed eq. 15: 220).
    #[serde(default = "default_n_diameters")]
    pub n_diameters: usize,
    /// Number of representative grains N simulated; each carries a statistical weight (the
    /// number of real grains it stands for). Default 100 000. `"real"` in the scenario file:
    /// every real grain of the modelled part, each of weight 1 ([`crate::sample::real_grains`]);
    /// read as [`REAL_PARTICLES`] and resolved to the real count by the kind's spec, which then
    /// sets [`SampleSpec::real_grains`].
    #[serde(
        default = "default_particles",
        deserialize_with = "particles::read",
        serialize_with = "particles::write"
    )]
    pub particles: usize,
    /// Whether `particles` counts every real grain (`particles = "real"`): set by the kind's
    /// spec, never read from the file.
    #[serde(skip)]
    pub real_grains: bool,
    /// Seed of the stratified random placement. Default 0.
    #[serde(default)]
    pub seed: u64,
    /// Fraction of the cylinder modelled: two opposing 1° wedges = 1/180 (seed §4.4).
    #[serde(default = "default_wedge")]
    pub wedge_fraction: f64,
    /// Number of horizontal layers of the profiles (seed: n_ly = 4000).
    #[serde(default = "default_layers")]
    pub layers: usize,
    /// Times of the profiles, s. Default: every 10 s to 60 s, then growing by ×1.25 to end_s.
    #[serde(default)]
    pub record_times_s: Vec<f64>,
    /// Times of the snapshots (CSV, VTK and picture), s. Default 60, 300, 900 (those within
    /// `time.end_s`; times written here after the end are refused).
    #[serde(default = "default_snapshots")]
    pub snapshot_times_s: Vec<f64>,
    /// Edge of the square cells of the solid-fraction grid that sets the voidage ε of the
    /// Di Felice factor, m. Default 2e-3 (about 30 of the largest grains).
    #[serde(default = "default_cell")]
    pub voidage_cell_m: f64,
    /// Solid fraction of the deposited bed (its height grows with the deposited volume).
    /// Default 0.6.
    #[serde(default = "default_packing")]
    pub bed_packing: f64,
    /// Largest time step, s. The step also keeps the fastest suspended grain within half a
    /// voidage cell per step, and lands on every record time. Default 10.
    #[serde(default = "default_max_step")]
    pub max_step_s: f64,
    /// Grain–grain and grain–wall contacts of suspended grains (`physics = "full"` only; the
    /// `ideal-stokes` reference has none): each step, the pairs whose gap can close within the
    /// step are resolved in a Rapier 2D world ([`crate::engine::dim2::World`]) with walls at
    /// x = 0 and B and the bed surface as floor. Default false: a representative grain stands
    /// for 7 to 160 000 real ones, so its encounters are a sample of the real ones whose effect
    /// grows with N and is not converged at any N a run can afford (docs/validation/
    /// sedimentation.md, convergence in N); without contacts the readings converge in N.
    #[serde(default)]
    pub contacts: bool,
    /// Squeeze-film lubrication between close grains (`physics = "full"` only):
    /// F = 6πμ a_eff² v_n / h ([`crate::fluid::lubrication`]) for gaps below the outer cut-off.
    /// Default: as `contacts` ([`SampleSpec::lubrication_on`]); allowed only with contacts.
    #[serde(default)]
    pub lubrication: Option<bool>,
    /// Outer cut-off of the lubrication force, as a fraction of the pair's effective radius
    /// a_eff = a₁a₂/(a₁ + a₂): no squeeze force beyond h_out = this × a_eff (the leading-order
    /// term is within ~10 % of the exact two-sphere resistance up to h ≈ 0.1 a_eff, Kim &
    /// Karrila 1991 §9; Ness & Sun 2015 and Marshall 2009 cut off at 0.05–0.1). Also the gap
    /// below which a pair is handed to the contact solve. Default 0.1; allowed (0, 1].
    #[serde(default = "default_lub_outer")]
    pub lubrication_outer_cutoff: f64,
    /// Inner cut-off of the lubrication force, as a fraction of a_eff: the gap is floored at
    /// h_in = this × a_eff (surface roughness), keeping the force finite. Default 1e-3; allowed
    /// (0, lubrication_outer_cutoff).
    #[serde(default = "default_lub_inner")]
    pub lubrication_inner_cutoff: f64,
    /// Hindered-settling factor of full physics ([`crate::fluid::hindered`]): `"di-felice"`
    /// (seed 000 eq. 7, the default; settles at ≈ U₀ ε^3.7 in this one-way model) or
    /// `"richardson-zaki"` (single-grain drag × ε^(−4.65): settles at U₀ ε^4.65, Richardson &
    /// Zaki 1954, return flow included).
    #[serde(default)]
    pub hindered: crate::fluid::HinderedLaw,
}

fn default_lub_outer() -> f64 {
    0.1
}
fn default_lub_inner() -> f64 {
    1e-3
}

fn default_n_diameters() -> usize {
    220
}
/// `particles = "real"` as read from the file, before the kind's spec resolves it.
pub const REAL_PARTICLES: usize = usize::MAX;

/// `sample.particles`: a whole number, or the word `"real"` ([`REAL_PARTICLES`]).
mod particles {
    use super::REAL_PARTICLES;
    use serde::de::{self, Visitor};
    use serde::{Deserializer, Serializer};

    /// A count or the word `real`. Asked for as a u64, so that a schema walker sees a number;
    /// TOML hands a string to `visit_str`.
    struct Count;

    const ALLOWED: &str = "allowed: a whole number ≥ 1 or \"real\" (every real grain, weight 1)";

    impl Visitor<'_> for Count {
        type Value = usize;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str(ALLOWED)
        }
        fn visit_u64<E: de::Error>(self, n: u64) -> Result<usize, E> {
            usize::try_from(n).map_err(|_| E::custom(format!("{n}: {ALLOWED}")))
        }
        fn visit_i64<E: de::Error>(self, n: i64) -> Result<usize, E> {
            usize::try_from(n).map_err(|_| E::custom(format!("{n}: {ALLOWED}")))
        }
        fn visit_f64<E: de::Error>(self, x: f64) -> Result<usize, E> {
            Err(E::custom(format!("{x}: {ALLOWED}")))
        }
        fn visit_str<E: de::Error>(self, w: &str) -> Result<usize, E> {
            if w.trim().eq_ignore_ascii_case("real") {
                Ok(REAL_PARTICLES)
            } else {
                Err(E::custom(format!("\"{w}\": {ALLOWED}")))
            }
        }
    }

    pub fn read<'de, D: Deserializer<'de>>(d: D) -> Result<usize, D::Error> {
        d.deserialize_u64(Count)
    }

    pub fn write<S: Serializer>(n: &usize, s: S) -> Result<S::Ok, S::Error> {
        if *n == REAL_PARTICLES {
            s.serialize_str("real")
        } else {
            s.serialize_u64(*n as u64)
        }
    }
}

fn default_particles() -> usize {
    100_000
}
fn default_wedge() -> f64 {
    1.0 / 180.0
}
fn default_layers() -> usize {
    4000
}
fn default_snapshots() -> Vec<f64> {
    vec![60.0, 300.0, 900.0]
}
fn default_cell() -> f64 {
    2e-3
}
fn default_packing() -> f64 {
    0.6
}
fn default_max_step() -> f64 {
    10.0
}
