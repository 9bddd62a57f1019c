//! Kind `sedimentation`: `[sample]` and `[instruments]`.

use super::super::{within_run, Contacts, Container, Dim, Scenario};
use crate::error::BadInput;
use crate::instruments::hydrometer::{Hydrometer, HydrometerSpec};
use crate::sample::Distribution;
use crate::scenario::check::{oc, Check};
use crate::scenario::inputs::read_sample;
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

impl SampleSpec {
    /// Whether the squeeze-film lubrication is on: `lubrication` if given, else as `contacts`.
    pub fn lubrication_on(&self) -> bool {
        self.lubrication.unwrap_or(self.contacts)
    }

    /// Thickness h_z of the 2D projection of the modelled wedges of a cylinder of diameter
    /// `width_m`, m: h_z = π B f / 4 (two opposing 1° wedges, f = 1/180: h_z = π B / 720; seed
    /// 000 §4.4), so that B H h_z = f π B² H / 4.
    pub fn projection_thickness_m(&self, width_m: f64) -> f64 {
        std::f64::consts::PI * width_m * self.wedge_fraction / 4.0
    }

    /// Mass, density (denser than the fluid), counts, fractions, lubrication cut-offs and times
    /// in range.
    pub(crate) fn check(&self, c: &Check, s: &Scenario) -> Result<(), BadInput> {
        c.range("sample.mass_kg", self.mass_kg, oc(0.0, 1e3, "kg"))?;
        c.range(
            "sample.density_kg_m3",
            self.density_kg_m3,
            oc(
                s.fluid.density_kg_m3,
                25_000.0,
                "kg/m³ (denser than the fluid)",
            ),
        )?;
        c.count_in("sample.n_diameters", self.n_diameters, 2, 100_000)?;
        if self.particles == 0 {
            return Err(c.err(
                "sample.particles",
                "0 is out of range: allowed particles ≥ 1 (the memory and time limits are \
                 checked by the run against its cost estimate)",
            ));
        }
        c.count_in("sample.layers", self.layers, 1, 1_000_000)?;
        c.table(
            "sample",
            &[
                ("wedge_fraction", self.wedge_fraction, oc(0.0, 1.0, "")),
                ("voidage_cell_m", self.voidage_cell_m, oc(0.0, 1.0, "m")),
                ("bed_packing", self.bed_packing, oc(0.0, 0.75, "")),
                ("max_step_s", self.max_step_s, oc(0.0, 1e6, "s")),
                (
                    "lubrication_outer_cutoff",
                    self.lubrication_outer_cutoff,
                    oc(0.0, 1.0, "(fraction of the effective radius a_eff)"),
                ),
            ],
        )?;
        // The cylinder's contact solve is 2D discs with friction and restitution only: a key it
        // would ignore is refused rather than accepted silently.
        if let Some(ct) = s
            .contacts
            .as_ref()
            .filter(|ct| ct.rolling_resistance != 0.0)
        {
            return Err(c.err(
                "contacts.rolling_resistance",
                format!(
                    "{} is not modelled in the sedimentation cylinder (its grains are discs with friction and restitution only): allowed 0",
                    ct.rolling_resistance
                ),
            ));
        }
        if self.lubrication == Some(true) && !self.contacts {
            return Err(c.err(
                "sample.lubrication",
                "the squeeze film is solved inside the contact solve: allowed lubrication = true only with sample.contacts = true (set lubrication = false too)",
            ));
        }
        let (inner, outer) = (self.lubrication_inner_cutoff, self.lubrication_outer_cutoff);
        if !(inner > 0.0 && inner < outer) {
            return Err(c.err(
                "sample.lubrication_inner_cutoff",
                format!(
                    "{inner} is out of range: allowed 0 < lubrication_inner_cutoff < lubrication_outer_cutoff = {outer} (fractions of the effective radius a_eff)"
                ),
            ));
        }
        c.each(
            "sample.record_times_s",
            &self.record_times_s,
            within_run(s.time.end_s),
        )?;
        c.each(
            "sample.snapshot_times_s",
            &self.snapshot_times_s,
            within_run(s.time.end_s),
        )
    }
}

/// Radial clearance a hydrometer bulb needs between itself and the cylinder wall, m (5 mm a
/// side). A hydrometer floats within about 1° of vertical; over the 28 cm of a 152H that moves
/// its lower end 4.9 mm off the axis, and a bulb that touches the wall is held by it (and by the
/// meniscus between them) and reads wrong. The 152H (Ø 27.75 mm) in the 63.5 mm cylinder of
/// ASTM D422 has 17.9 mm.
pub const BULB_WALL_CLEARANCE_M: f64 = 5e-3;

/// Keeps, of the record, snapshot and reading times a sedimentation scenario `s` did not give
/// (their defaults: snapshots at 60, 300, 900 s, the ASTM reading times up to 1440 min), those
/// within `time.end_s`, so that `--set time.end_s=600` shortens a run without touching them.
/// `given` is the scenario's TOML table (after `--set`): a time list written there is kept as
/// written, and validation refuses its times after the end, naming the key. (Default record
/// times are computed from the end time by the scene.)
pub(crate) fn trim_default_times(s: &mut Scenario, given: &toml::Table) {
    let end_s = s.time.end_s;
    let written = |table: &str, key: &str| {
        given
            .get(table)
            .and_then(|t| t.as_table())
            .is_some_and(|t| t.contains_key(key))
    };
    let trim = |times: &mut Vec<f64>| times.retain(|&t| t <= end_s);
    if let Some(sm) = s.sample.as_mut() {
        if !written("sample", "snapshot_times_s") {
            trim(&mut sm.snapshot_times_s);
        }
    }
    if let Some(ins) = s.instruments.as_mut() {
        for (key, times) in [
            ("hydrometer_times_s", &mut ins.hydrometer_times_s),
            ("buoyancy_times_s", &mut ins.buoyancy_times_s),
            ("pipette_times_s", &mut ins.pipette_times_s),
        ] {
            if !written("instruments", key) {
                trim(times);
            }
        }
    }
}

impl InstrumentsSpec {
    /// The hydrometer figures of this table.
    pub fn hydrometer(&self) -> HydrometerSpec {
        HydrometerSpec {
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

    /// The hydrometer bulb fits the cylinder: its diameter 2 R_b (from the bulb volume, length
    /// and taper, [`Hydrometer::new`]) at most the cylinder's inside diameter `b`
    /// (`container.width_m`, the 2D projection's width) less [`BULB_WALL_CLEARANCE_M`] on each
    /// side. The error names the bulb length that would fit with the same volume and taper.
    fn check_bulb_fits(&self, c: &Check, s: &Scenario, b: f64) -> Result<(), BadInput> {
        let allowed = b - 2.0 * BULB_WALL_CLEARANCE_M;
        let diameter = |len: f64| {
            let spec = HydrometerSpec {
                bulb_length_m: len,
                ..self.hydrometer()
            };
            2.0 * Hydrometer::new(spec, s.fluid.density_kg_m3).bulb_radius_m
        };
        let d = diameter(self.hydrometer_bulb_length_m);
        if d <= allowed {
            return Ok(());
        }
        // The bulb narrows as it lengthens (same volume): bisect for the length that fits.
        let (lo, hi) = (self.hydrometer_bulb_length_m, 10.0);
        let hint = if diameter(hi) > allowed || allowed <= 0.0 {
            "a smaller hydrometer_bulb_volume_m3".to_string()
        } else {
            let (_, hi) =
                crate::numerics::bisect(lo, hi, crate::numerics::Bisection::halvings(60), |len| {
                    diameter(len) > allowed
                });
            format!(
                "with this volume and taper, hydrometer_bulb_length_m ≥ {} m, or a smaller \
                 hydrometer_bulb_volume_m3",
                crate::io::fmt::sig_trim((hi * 1e4).ceil() / 1e4, 4)
            )
        };
        Err(c.err(
            "instruments.hydrometer_bulb_length_m",
            format!(
                "{} m gives a bulb of {} cm³ a diameter of {} mm, which does not fit the \
                 cylinder (container.width_m = {b} m) with {} mm of clearance on each side: \
                 allowed bulb diameter ≤ {} mm ({hint})",
                self.hydrometer_bulb_length_m,
                crate::io::fmt::sig_trim(self.hydrometer_bulb_volume_m3 * 1e6, 4),
                crate::io::fmt::sig_trim(d * 1e3, 4),
                BULB_WALL_CLEARANCE_M * 1e3,
                crate::io::fmt::sig_trim(allowed * 1e3, 4),
            ),
        ))
    }

    /// The instruments (seed 000 §4.5): reading times within the run, hydrometer figures that
    /// give a floating body inside the cylinder (height `h`, width `b`), sphere and pipette
    /// disc inside the suspension.
    pub(crate) fn check(
        &self,
        c: &Check,
        s: &Scenario,
        sample: &SampleSpec,
        h: f64,
        b: f64,
    ) -> Result<(), BadInput> {
        let run = within_run(s.time.end_s);
        c.each(
            "instruments.hydrometer_times_s",
            &self.hydrometer_times_s,
            run,
        )?;
        c.each("instruments.buoyancy_times_s", &self.buoyancy_times_s, run)?;
        c.each("instruments.pipette_times_s", &self.pipette_times_s, run)?;
        c.table(
            "instruments",
            &[
                (
                    "hydrometer_bulb_volume_m3",
                    self.hydrometer_bulb_volume_m3,
                    oc(0.0, 1e-2, "m³"),
                ),
                (
                    "hydrometer_bulb_length_m",
                    self.hydrometer_bulb_length_m,
                    oc(0.0, h, "m (within container.height_m)"),
                ),
                (
                    "hydrometer_taper_m",
                    self.hydrometer_taper_m,
                    oc(
                        0.0,
                        0.5 * self.hydrometer_bulb_length_m,
                        "m (at most half the bulb length)",
                    ),
                ),
                (
                    "hydrometer_stem_length_m",
                    self.hydrometer_stem_length_m,
                    oc(0.0, 10.0, "m"),
                ),
                (
                    "hydrometer_effective_depth_zero_m",
                    self.hydrometer_effective_depth_zero_m,
                    oc(0.0, h, "m (within container.height_m)"),
                ),
                (
                    "hydrometer_effective_depth_slope_m",
                    self.hydrometer_effective_depth_slope_m,
                    oc(0.0, 1.0, "m per g/L"),
                ),
                (
                    "hydrometer_full_scale",
                    self.hydrometer_full_scale,
                    oc(0.0, 1e3, "g/L"),
                ),
                (
                    "hydrometer_astm_cylinder_area_m2",
                    self.hydrometer_astm_cylinder_area_m2,
                    oc(0.0, 10.0, "m²"),
                ),
                (
                    "sphere_diameter_m",
                    self.sphere_diameter_m,
                    oc(0.0, b, "m (within container.width_m)"),
                ),
                ("sphere_mass_kg", self.sphere_mass_kg, oc(0.0, 1e3, "kg")),
                (
                    "pipette_volume_m3",
                    self.pipette_volume_m3,
                    oc(0.0, 1.0, "m³"),
                ),
                (
                    "hydrometer_calibration_specific_gravity",
                    self.hydrometer_calibration_specific_gravity,
                    oc(1.0, 30.0, ""),
                ),
            ],
        )?;
        self.check_bulb_fits(c, s, b)?;
        let hy = Hydrometer::new(self.hydrometer(), s.fluid.density_kg_m3);
        let full = hy.mark_m(self.hydrometer_full_scale);
        if !(hy.stem_radius_m > 0.0
            && hy.bulb_radius_m > hy.stem_radius_m
            && hy.zero_mark_m > 0.0
            && hy.zero_mark_m <= self.hydrometer_stem_length_m
            && full >= 0.0
            && hy.clear_tip_depth_m() < h)
        {
            return Err(c.err("instruments", format!(
                "the hydrometer figures give no floating body that fits: stem radius {:.3e} m, bulb radius {:.3e} m (allowed 0 < stem < bulb), marks 0 and full scale at {:.3e} and {:.3e} m up the stem (allowed 0 ≤ marks ≤ stem length), clear-fluid tip depth {:.3e} m (allowed < container.height_m = {h} m)",
                hy.stem_radius_m, hy.bulb_radius_m, hy.zero_mark_m, full, hy.clear_tip_depth_m())));
        }
        let rs = 0.5 * self.sphere_diameter_m / h;
        c.range(
            "instruments.sphere_depth_fraction",
            self.sphere_depth_fraction,
            oc(rs, 1.0 - rs, "of H (the whole sphere in the suspension)"),
        )?;
        let hz = sample.projection_thickness_m(b);
        let rp =
            (sample.wedge_fraction * self.pipette_volume_m3 / (hz * std::f64::consts::PI)).sqrt();
        if rp > 0.5 * b {
            return Err(c.err("instruments.pipette_volume_m3", format!(
                "{} m³ is a disc of radius {rp:.3e} m in the 2D projection, wider than the cylinder (allowed radius ≤ B/2 = {} m)",
                self.pipette_volume_m3, 0.5 * b)));
        }
        c.range(
            "instruments.pipette_depth_fraction",
            self.pipette_depth_fraction,
            oc(
                rp / h,
                1.0 - rp / h,
                "of H (the whole sampled disc in the suspension)",
            ),
        )
    }
}

/// The 2D projection of the sedimentation cylinder (kind `sedimentation`).
#[derive(Clone, Debug, PartialEq)]
pub struct SedimentationSpec {
    /// The soil sample (`[sample]`).
    pub sample: SampleSpec,
    /// Width B of the projected cylinder, m (`container.width_m`).
    pub width_m: f64,
    /// Height H of the fluid column, m (`container.height_m`).
    pub height_m: f64,
    /// The hydrometer, buoyancy sphere and pipette (`[instruments]`; absent: every default).
    pub instruments: InstrumentsSpec,
    /// The grain contacts (`[contacts]`; absent: the scene's defaults).
    pub contacts: Option<Contacts>,
    /// The particle-size distribution of the sample, read from `sample.csv` (relative to the
    /// scenario file) once, as the scenario is parsed.
    pub distribution: Distribution,
}

/// The spec of a `sedimentation` scenario: `[sample]`, a `[container]` with its width,
/// dimension 2, `[instruments]` if given, and the sample's distribution read from its CSV.
pub(crate) fn spec(c: &Check, s: &Scenario) -> Result<SedimentationSpec, BadInput> {
    let missing = |key: &str, what: &str| {
        c.err(
            key,
            format!("missing: kind = \"sedimentation\" needs {what}"),
        )
    };
    let sm = s.sample.as_ref().ok_or_else(|| {
        missing(
            "sample",
            "a [sample] table (csv, sample, mass_kg, density_kg_m3)",
        )
    })?;
    let (h, b) = match &s.container {
        Some(Container {
            height_m,
            width_m: Some(b),
            ..
        }) => (*height_m, *b),
        _ => {
            return Err(missing(
                "container.width_m",
                "a [container] with width_m (B) and height_m (H)",
            ))
        }
    };
    if s.dimension != Dim::Two {
        return Err(c.err("dimension", "kind = \"sedimentation\" is the 2D projection of the cylinder (seed 000 §4.4): allowed 2"));
    }
    sm.check(c, s)?;
    let instruments = s.instruments.clone().unwrap_or_default();
    if s.instruments.is_some() {
        instruments.check(c, s, sm, h, b)?;
    }
    Ok(SedimentationSpec {
        sample: sm.clone(),
        width_m: b,
        height_m: h,
        instruments,
        contacts: s.contacts.clone(),
        distribution: read_sample(sm, c.file)?,
    })
}
