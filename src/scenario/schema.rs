//! The scenario schema (serde). Defaults are documented on each field.

use crate::dynamics::Integrator;
use serde::{Deserialize, Serialize};

/// Standard gravity used when a scenario does not set `gravity_m_s2`, m/s².
pub const DEFAULT_GRAVITY_M_S2: f64 = 9.81;

/// A whole scenario file.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// Name of the run; results go to `OUT/<name>/`. Letters, digits, `_`, `-`, `.` only.
    pub name: String,
    /// What kind of scene this is.
    pub kind: Kind,
    /// 2 or 3. Default 3.
    #[serde(default = "default_dimension")]
    pub dimension: u8,
    /// Free text shown in `run.toml`.
    #[serde(default)]
    pub description: String,
    /// `full` (default) or `ideal-stokes`: Stokes drag with the fluid's (plastic) viscosity, no
    /// yield stress, no voidage, no contacts — the reference case for checking the pipeline.
    #[serde(default)]
    pub physics: Physics,
    /// Which engine advances the bodies. Default `auto`.
    #[serde(default)]
    pub engine: EngineChoice,
    /// Magnitude of gravity, m/s², acting along −z in 3D and −y in 2D. Default 9.81.
    #[serde(default = "default_gravity")]
    pub gravity_m_s2: f64,
    /// The fluid.
    pub fluid: Fluid,
    /// The drag law.
    pub drag: Drag,
    /// Time step, duration and integrator.
    pub time: Time,
    /// The container (tank, cylinder); none for an unbounded fluid.
    #[serde(default)]
    pub container: Option<Container>,
    /// How bodies are released.
    #[serde(default)]
    pub release: Release,
    /// Spheres listed inline.
    #[serde(default)]
    pub spheres: Vec<SphereSpec>,
    /// Spheres read from a CSV file (in addition to `spheres`).
    #[serde(default)]
    pub spheres_csv: Option<SpheresCsv>,
    /// How terminal velocity and other quantities are measured.
    #[serde(default)]
    pub measure: Option<Measure>,
    /// What to record.
    #[serde(default)]
    pub record: Record,
    /// Default settings for `settle sweep`.
    #[serde(default)]
    pub sweep: Option<SweepSpec>,
    /// Contact properties (scenes with contacts).
    #[serde(default)]
    pub contacts: Option<Contacts>,
    /// Restitution drop settings (kind `restitution_drop`).
    #[serde(default)]
    pub restitution_drop: Option<RestitutionDropSpec>,
    /// Tilt test settings (kind `tilt_friction`).
    #[serde(default)]
    pub tilt: Option<TiltSpec>,
    /// Funnel geometry and release (kind `funnel_pour`).
    #[serde(default)]
    pub funnel: Option<FunnelSpec>,
    /// Repeated runs with different seeds (kind `funnel_pour`).
    #[serde(default)]
    pub repeats: Option<Repeats>,
    /// The soil sample (kind `sedimentation`).
    #[serde(default)]
    pub sample: Option<SampleSpec>,
    /// The hydrometer, buoyancy sphere and pipette read during a sedimentation run (kind
    /// `sedimentation`; absent: every default of [`InstrumentsSpec`]).
    #[serde(default)]
    pub instruments: Option<InstrumentsSpec>,
}

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
    /// number of real grains it stands for). Default 100 000.
    #[serde(default = "default_particles")]
    pub particles: usize,
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
    /// Times of the snapshots (CSV, VTK and picture), s. Default 60, 300, 900.
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
    /// x = 0 and B and the bed surface as floor. Default true.
    #[serde(default = "default_true")]
    pub contacts: bool,
    /// Squeeze-film lubrication between close grains (`physics = "full"` only):
    /// F = 6πμ a_eff² v_n / h ([`crate::fluid::lubrication`]) for gaps below the outer cut-off.
    /// Default true.
    #[serde(default = "default_true")]
    pub lubrication: bool,
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
}

fn default_true() -> bool {
    true
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

fn default_reference_speed() -> f64 {
    1.0
}

/// Contact properties of every collider of a scene with contacts.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Contacts {
    /// Coefficient of restitution, 0 ≤ e ≤ 1 (f-EDEM Table 4: 0.612, steel on steel); with a
    /// non-zero `restitution_exponent`, the value at `restitution_reference_speed_m_s`.
    pub restitution: f64,
    /// Exponent k of the speed-dependent restitution e(v) = e (v / v_ref)^(−k), clamped below 1
    /// ([`crate::contact::RestitutionLaw`]), v the impact (approach) speed; 0 ≤ k ≤ 1.
    /// Default 0: a constant coefficient.
    #[serde(default)]
    pub restitution_exponent: f64,
    /// Reference speed v_ref of the speed-dependent restitution, m/s, 1e-3 ≤ v_ref ≤ 100.
    /// Default 1 m/s.
    #[serde(default = "default_reference_speed")]
    pub restitution_reference_speed_m_s: f64,
    /// Coulomb (static) friction coefficient ≥ 0 (f-EDEM Table 4: 0.341).
    pub friction: f64,
    /// Rolling resistance coefficient μ_r ≥ 0: a torque μ_r · r · |F_n| opposing the rolling
    /// (f-EDEM Table 4: 0.002). Default 0.
    #[serde(default)]
    pub rolling_resistance: f64,
}

impl Contacts {
    /// The restitution law these settings give.
    pub fn restitution_law(&self) -> crate::contact::RestitutionLaw {
        crate::contact::RestitutionLaw {
            coefficient: self.restitution,
            exponent: self.restitution_exponent,
            reference_speed_m_s: self.restitution_reference_speed_m_s,
        }
    }
}

/// Restitution drop test (f-EDEM Appendix II): one ball (the scenario's single `[[spheres]]`)
/// dropped from rest on a fixed plate, in the scenario's fluid (air), once per drop height; the
/// apex after the first bounce is the rebound height. The contact restitution is
/// `contacts.restitution`.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RestitutionDropSpec {
    /// Drop heights of the ball's lowest point above the plate, m.
    pub drop_heights_m: Vec<f64>,
    /// Measured rebound heights, m (same length; optional).
    #[serde(default)]
    pub measured_rebound_heights_m: Vec<f64>,
    /// Relative tolerance on |simulated / measured rebound height − 1| that the source states as
    /// its acceptance (f-EDEM App. II: 3 %). Reported (how many heights meet it), not enforced.
    /// Default 0.03.
    #[serde(default = "default_rebound_tolerance")]
    pub tolerance: f64,
}

fn default_rebound_tolerance() -> f64 {
    0.03
}

/// Tilt friction test (f-EDEM Appendix III): a cuboid block at rest on a fixed plate tilted by
/// each angle (gravity is tilted instead of the plate: the same thing in the plate's frame).
/// The contact friction is `contacts.friction`; the threshold angle is bracketed by the angles
/// given and refined by bisection.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TiltSpec {
    /// Block edge lengths (x, y, z), m: x along the slope, z normal to the plate.
    pub block_size_m: Vec<f64>,
    /// Block density, kg/m³.
    pub block_density_kg_m3: f64,
    /// Tilt angles to test, degrees (0 ≤ angle < 90).
    pub angles_deg: Vec<f64>,
    /// Simulated time at each angle, s.
    pub duration_s: f64,
    /// Displacement along the slope after `duration_s` above which the block counts as sliding,
    /// m. Default 1e-3.
    #[serde(default = "default_slide_distance")]
    pub slide_distance_m: f64,
    /// The threshold angle is bisected until the bracket (largest sticking angle, smallest
    /// sliding angle) is at most this wide, degrees. Default 0.1.
    #[serde(default = "default_bisection_tolerance")]
    pub bisection_tolerance_deg: f64,
}

fn default_slide_distance() -> f64 {
    1e-3
}

fn default_bisection_tolerance() -> f64 {
    0.1
}

/// Funnel pour (f-EDEM §4.2, Fig. 17): the funnel is not described in the source; see the
/// scenario file for the geometry used.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FunnelSpec {
    /// Number of balls.
    pub count: usize,
    /// Inner diameter of the funnel at its top, m.
    pub top_diameter_m: f64,
    /// Inner diameter of the outlet, m.
    pub outlet_diameter_m: f64,
    /// Height of the conical part, m.
    pub cone_height_m: f64,
    /// Height of the outlet above the fluid surface, m (f-EDEM: 0.15).
    pub outlet_above_surface_m: f64,
    /// Time at which the balls in the fluid and in the domain are counted (f-EDEM Fig. 20), s.
    #[serde(default)]
    pub count_time_s: Option<f64>,
    /// Heights above the cylinder bottom of the horizontal planes of the presence maps, m.
    #[serde(default)]
    pub planes_z_m: Vec<f64>,
    /// Height of a vertical cylindrical section (inner diameter `top_diameter_m`) on top of the
    /// cone, m: room for the random initial placement of the balls. Default 0.
    #[serde(default)]
    pub column_height_m: f64,
    /// Time the balls, placed at random without overlap, fall and settle in the funnel on the
    /// plug closing the outlet before it is removed at t = 0, s. Default 0.3.
    #[serde(default = "default_fill_time")]
    pub fill_time_s: f64,
    /// Height of the cylinder wall above the paste surface, m. Default 0: the mould is filled to
    /// the brim (f-EDEM: paste 150 mm deep in a cylinder 150 mm high).
    #[serde(default)]
    pub wall_above_surface_m: f64,
    /// Wall thickness of the funnel and the cylinder (boxes around the circles), m. Default 4e-3.
    #[serde(default = "default_wall_thickness")]
    pub wall_thickness_m: f64,
    /// Number of flat faces approximating each circle of the funnel and the cylinder. Default 64.
    #[serde(default = "default_facets")]
    pub facets: usize,
    /// The run of a repeat ends before `time.end_s` once t ≥ `count_time_s` and every ball has
    /// been slower than this for 0.05 s, m/s. Default 1e-3.
    #[serde(default = "default_rest_speed")]
    pub rest_speed_m_s: f64,
    /// Bin width of the vertical distribution (`z_distribution.csv`), m. Default 5e-3.
    #[serde(default = "default_z_bin")]
    pub z_bin_m: f64,
    /// Cell size of the presence-probability grids (`presence.csv`), m. Default 2.5e-3.
    #[serde(default = "default_grid_cell")]
    pub grid_cell_m: f64,
}

fn default_fill_time() -> f64 {
    0.3
}
fn default_wall_thickness() -> f64 {
    4e-3
}
fn default_facets() -> usize {
    64
}
fn default_rest_speed() -> f64 {
    1e-3
}
fn default_z_bin() -> f64 {
    5e-3
}
fn default_grid_cell() -> f64 {
    2.5e-3
}

/// Repetitions with different seeds.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Repeats {
    /// Number of runs. Default 1.
    #[serde(default = "one_usize")]
    pub count: usize,
    /// Seed of the first run; run i uses seed + i. Default 0.
    #[serde(default)]
    pub seed: u64,
}

fn one_usize() -> usize {
    1
}

fn default_dimension() -> u8 {
    3
}
fn default_gravity() -> f64 {
    DEFAULT_GRAVITY_M_S2
}

/// Kinds of scene.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// Independent spheres settling from rest in a still fluid, no contacts between them
    /// (f-EDEM §3 single sphere, §4.1 Valentik–Whitmore tanks). Each sphere runs alone.
    FreeSettling,
    /// Spheres dropped from `release.fall_heights_m` above the free surface through air into the
    /// fluid, each alone, until they stop (f-EDEM §4.2 steel balls in paste backfill).
    Drop,
    /// A ball dropped on a plate in air; rebound heights against measurements (f-EDEM App. II).
    RestitutionDrop,
    /// A block on a plate tilted to a series of angles: sticks or slides (f-EDEM App. III).
    TiltFriction,
    /// Many balls released from a funnel into the fluid-filled cylinder, with contacts (f-EDEM
    /// §4.2, 68 steel balls into paste backfill), repeated with different seeds.
    FunnelPour,
    /// A 2D projection of the ASTM D422 sedimentation cylinder: a soil sample of representative
    /// grains settling from a homogeneous suspension (seed 000 §4–5).
    Sedimentation,
}

/// How fluid forces act on a sphere crossing the free surface.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "lowercase")]
pub enum Submergence {
    /// f-EDEM: the whole buoyancy and drag act from the moment the sphere's lowest point
    /// touches the surface.
    #[default]
    Full,
    /// Buoyancy on the immersed spherical cap's volume, drag scaled by the immersed fraction of
    /// the projected area, while the sphere crosses the surface.
    Partial,
}

/// Physics switch.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Physics {
    /// Everything the scenario asks for.
    #[default]
    Full,
    /// Stokes drag only, no yield stress, no voidage, no contacts.
    IdealStokes,
}

/// Engine choice.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum EngineChoice {
    /// `free` where the scene has no contacts, `rapier` otherwise.
    #[default]
    Auto,
    /// Our own integrator only (no contact pipeline): exact free flight, fastest.
    Free,
    /// Every body in a Rapier world, fluid forces through the force hook.
    Rapier,
}

/// Rheology of the fluid.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Rheology {
    /// Newtonian: needs `viscosity_pa_s`.
    Newtonian,
    /// Bingham plastic: needs `plastic_viscosity_pa_s` and `yield_stress_pa`.
    Bingham,
}

/// The fluid.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Fluid {
    /// Density ρ_f, kg/m³ (0 < ρ_f ≤ 25 000).
    pub density_kg_m3: f64,
    /// `newtonian` or `bingham`.
    pub rheology: Rheology,
    /// Dynamic viscosity η, Pa s (Newtonian only; > 0).
    #[serde(default)]
    pub viscosity_pa_s: Option<f64>,
    /// Plastic viscosity η_B, Pa s (Bingham only; > 0).
    #[serde(default)]
    pub plastic_viscosity_pa_s: Option<f64>,
    /// Yield stress τ_y, Pa (Bingham only; ≥ 0).
    #[serde(default)]
    pub yield_stress_pa: Option<f64>,
    /// `full` (default) or `partial`: fluid forces on a sphere crossing the free surface.
    #[serde(default)]
    pub submergence: Submergence,
}

/// Names of the drag laws.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum DragLawName {
    /// Stokes' law, f-EDEM eq. 7.
    Stokes,
    /// Dallavalle C_d with Di Felice voidage, seed 000 eqs. 7–9.
    Dallavalle,
    /// f-EDEM eqs. 9, 14, 19 (Bingham fluids only).
    BinghamFedem,
}

/// The drag law.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Drag {
    /// `stokes`, `dallavalle` or `bingham-fedem`.
    pub law: DragLawName,
    /// Fluid volume fraction ε for `dallavalle`, in (0, 1]. Default 1 (isolated sphere).
    #[serde(default = "one")]
    pub voidage: f64,
}

fn one() -> f64 {
    1.0
}

/// Time settings.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Time {
    /// Time step, s (> 0, ≤ `end_s`). `settle run --dt` overrides it.
    pub dt_s: f64,
    /// Simulated duration, s (> 0). A free-settling sphere also stops at the container bottom
    /// or when it is held at rest by the yield stress.
    pub end_s: f64,
    /// `explicit`, `implicit` or `exponential` (default).
    #[serde(default)]
    pub integrator: Integrator,
}

/// The container.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Container {
    /// Height of the fluid column from the bottom to the free surface, m (> 0).
    pub height_m: f64,
    /// Diameter of a cylindrical container, m (3D only). Walls are not modelled in free settling.
    #[serde(default)]
    pub diameter_m: Option<f64>,
    /// Width of a rectangular container, m (2D, or 3D square section).
    #[serde(default)]
    pub width_m: Option<f64>,
}

/// Release of the bodies.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct Release {
    /// Depth of the sphere's centre below the free surface at release, m. Default 0, which
    /// means "just submerged": the centre at one radius below the surface.
    #[serde(default)]
    pub depth_m: f64,
    /// Initial downward speed, m/s. Default 0 (from rest).
    #[serde(default)]
    pub velocity_m_s: f64,
    /// Fall heights of the sphere's lowest point above the free surface, m (kind `drop`): every
    /// sphere is dropped from each, from rest, as an independent case.
    #[serde(default)]
    pub fall_heights_m: Vec<f64>,
}

/// One sphere.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    /// Identifier in outputs. Default `sphere-<index>`.
    #[serde(default)]
    pub id: Option<String>,
    /// Diameter d, m (0 < d ≤ 10).
    pub diameter_m: f64,
    /// Density ρ_p, kg/m³ (0 < ρ_p ≤ 25 000).
    pub density_kg_m3: f64,
    /// Young's modulus E, Pa (optional; for the Rayleigh time, f-EDEM eq. 22).
    #[serde(default)]
    pub youngs_modulus_pa: Option<f64>,
    /// Poisson's ratio ν (optional; −1 < ν < 0.5).
    #[serde(default)]
    pub poisson_ratio: Option<f64>,
    /// Measured terminal velocity, m/s (optional; compared in the summary).
    #[serde(default)]
    pub v_measured_m_s: Option<f64>,
    /// Suspension or group number (optional; reported in the summary).
    #[serde(default)]
    pub suspension: Option<u32>,
}

/// Spheres from a CSV file with columns `sphere_id, suspension, diameter_m, density_kg_m3,
/// v_terminal_measured_m_s` (extra columns ignored), as `data/valentik_whitmore_1965_spheres.csv`.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SpheresCsv {
    /// Path, relative to the scenario file.
    pub path: String,
    /// Keep only rows of this suspension (optional).
    #[serde(default)]
    pub suspension: Option<u32>,
}

/// Measurement settings.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Measure {
    /// Depth below the surface of the first detector of the measuring section, m (optional;
    /// give both detectors or neither).
    #[serde(default)]
    pub section_top_depth_m: Option<f64>,
    /// Depth of the second detector, m (> top, within the container).
    #[serde(default)]
    pub section_bottom_depth_m: Option<f64>,
    /// Steadiness criterion: the velocity at the two detectors may differ by at most this
    /// fraction of the section velocity for the reading to count as terminal. Default 0.005.
    #[serde(default = "default_steady")]
    pub steady_tolerance: f64,
    /// Length of the rolling window used to read the simulated terminal velocity, m (optional).
    /// When set, the sphere keeps falling (past the container bottom if need be, in an
    /// unbounded column) until the velocities at both ends of the last window differ by at
    /// most `terminal_tolerance` of the window's mean velocity; that mean is the terminal
    /// velocity. Without it, the terminal velocity is the section reading or the final velocity.
    #[serde(default)]
    pub terminal_window_m: Option<f64>,
    /// Steadiness criterion of the rolling window (relative). Default 1e-4.
    #[serde(default = "default_terminal_tol")]
    pub terminal_tolerance: f64,
    /// Times at which the velocity is probed (`probes.csv`, used by sweeps), s.
    #[serde(default)]
    pub velocity_at_s: Vec<f64>,
}

fn default_steady() -> f64 {
    0.005
}

fn default_terminal_tol() -> f64 {
    1e-4
}

/// Recording settings.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Record {
    /// Write `timeseries.csv`. Default true.
    #[serde(default = "yes")]
    pub timeseries: bool,
    /// Interval between time-series rows, s. Default: every step up to 2000 rows per body.
    #[serde(default)]
    pub every_s: Option<f64>,
}

impl Default for Record {
    fn default() -> Self {
        Self {
            timeseries: true,
            every_s: None,
        }
    }
}

fn yes() -> bool {
    true
}

/// Default settings of `settle sweep` for this scenario.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// Time steps to run, s.
    #[serde(default)]
    pub dt_s: Vec<f64>,
    /// Integrators to compare. Default: all three.
    #[serde(default)]
    pub integrators: Vec<Integrator>,
    /// Relative tolerance for the recommended dt. Default 0.01.
    #[serde(default)]
    pub tol: Option<f64>,
}

impl Fluid {
    /// The viscosity the drag uses, Pa s: η (`viscosity_pa_s`) of a Newtonian fluid, the plastic
    /// viscosity η_B (`plastic_viscosity_pa_s`) of a Bingham one. None if the scenario lacks it
    /// (validation requires it).
    pub fn drag_viscosity_pa_s(&self) -> Option<f64> {
        match self.rheology {
            Rheology::Newtonian => self.viscosity_pa_s,
            Rheology::Bingham => self.plastic_viscosity_pa_s,
        }
    }
}

impl InstrumentsSpec {
    /// The hydrometer figures of this `[instruments]` table.
    pub fn hydrometer(&self) -> crate::instruments::hydrometer::HydrometerSpec {
        crate::instruments::hydrometer::HydrometerSpec {
            bulb_volume_m3: self.hydrometer_bulb_volume_m3,
            bulb_length_m: self.hydrometer_bulb_length_m,
            taper_m: self.hydrometer_taper_m,
            stem_length_m: self.hydrometer_stem_length_m,
            effective_depth_zero_m: self.hydrometer_effective_depth_zero_m,
            effective_depth_slope_m: self.hydrometer_effective_depth_slope_m,
            full_scale: self.hydrometer_full_scale,
            astm_cylinder_area_m2: self.hydrometer_astm_cylinder_area_m2,
            calibration_specific_gravity: self.hydrometer_calibration_specific_gravity,
        }
    }
}

/// Thickness of the 2D projection of a wedge fraction f of a cylinder of diameter B, m:
/// h_z = π B f / 4 (so that B H h_z = f π B² H / 4; two opposing 1° wedges, f = 1/180, give
/// h_z = π B / 720).
pub fn projection_thickness_m(width_m: f64, wedge_fraction: f64) -> f64 {
    std::f64::consts::PI * width_m * wedge_fraction / 4.0
}

impl SampleSpec {
    /// Thickness h_z of the 2D projection of this sample's wedges in a cylinder of width
    /// `width_m`, m ([`projection_thickness_m`]).
    pub fn projection_thickness_m(&self, width_m: f64) -> f64 {
        projection_thickness_m(width_m, self.wedge_fraction)
    }
}
