//! Kind `sedimentation`: the methods and checks of `[sample]` and `[instruments]` (which read
//! the whole scenario), and the kind's spec. The tables are in `tables/sedimentation.rs`.

use super::super::tables::sedimentation::REAL_PARTICLES;
use super::super::{within_run, Contacts, Container, Dim, InstrumentsSpec, SampleSpec, Scenario};
use crate::error::BadInput;
use crate::instruments::hydrometer::{Hydrometer, HydrometerSpec};
use crate::sample::Distribution;
use crate::scenario::check::{oc, Check};
use crate::scenario::inputs::read_sample;

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
    let distribution = read_sample(sm, c.file)?;
    let mut sample = sm.clone();
    if sample.particles == REAL_PARTICLES {
        // Every real grain of the modelled part, weight 1: the memory and time this takes are
        // the run's cost estimate's to refuse, naming sample.particles.
        let classes = crate::sample::discretize(&distribution, sample.n_diameters);
        let model_mass_kg = sample.mass_kg * sample.wedge_fraction;
        sample.particles =
            crate::sample::real_total(&classes, model_mass_kg, sample.density_kg_m3).max(1);
        sample.real_grains = true;
    }
    Ok(SedimentationSpec {
        sample,
        width_m: b,
        height_m: h,
        instruments,
        contacts: s.contacts.clone(),
        distribution,
    })
}
