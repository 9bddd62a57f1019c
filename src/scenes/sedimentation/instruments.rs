//! Instruments (seed 000 §4.5): hydrometer, buoyancy sphere and pipette read on the simulation
//! (the adapter between the cylinder's state and [`crate::instruments`]).

use super::setup::Setup;
use super::state::{concentration, profile, Profile, State};
use crate::fluid::sphere_mass_kg;
use crate::instruments::buoyancy::{BuoyancyReading, BuoyancySphere};
use crate::instruments::counting::{effective_count, with_one_more_grain};
use crate::instruments::hydrometer::{Hydrometer, HydrometerReading};
use crate::instruments::pipette::{GrainSample, Pipette, PipetteReading};
use crate::instruments::{Analysis, LayeredField, Point};

/// The instruments of a run and their reading times (those within `time.end_s`).
pub struct InstrumentSet {
    /// Conversions of the analysis (μ, ρ_p, ρ_f, g, c_0).
    pub analysis: Analysis,
    /// The hydrometer.
    pub hydrometer: Hydrometer,
    /// The buoyancy sphere.
    pub sphere: BuoyancySphere,
    /// The pipette.
    pub pipette: Pipette,
    /// Hydrometer reading times, s.
    pub hydrometer_times_s: Vec<f64>,
    /// Sphere reading times, s.
    pub buoyancy_times_s: Vec<f64>,
    /// Pipette draw times, s.
    pub pipette_times_s: Vec<f64>,
    /// Layers of the density field the hydrometer and the sphere read (`sample.layers`).
    pub layers: usize,
}

impl InstrumentSet {
    /// The instruments of the run of `setup` (its spec's `[instruments]`, every default without
    /// one).
    pub fn new(setup: &Setup) -> Self {
        let c = &setup.common;
        let sm = &setup.spec.sample;
        let ins = &setup.spec.instruments;
        let rho_f = c.fluid_density_kg_m3;
        let mu = setup.viscosity_pa_s;
        let within = |t: &[f64]| -> Vec<f64> {
            let mut t: Vec<f64> = t
                .iter()
                .copied()
                .filter(|&x| x > 0.0 && x <= c.time.end_s * (1.0 + 1e-12))
                .collect();
            t.sort_by(f64::total_cmp);
            t.dedup();
            t
        };
        Self {
            analysis: Analysis {
                viscosity_pa_s: mu,
                grain_density_kg_m3: sm.density_kg_m3,
                fluid_density_kg_m3: rho_f,
                gravity_m_s2: c.gravity_m_s2,
                c0_kg_m3: setup.model_mass_kg
                    / (setup.width_m * setup.height_m * setup.thickness_m),
            },
            hydrometer: Hydrometer::new(ins.hydrometer(), rho_f),
            sphere: BuoyancySphere {
                diameter_m: ins.sphere_diameter_m,
                mass_kg: ins.sphere_mass_kg,
                depth_m: ins.sphere_depth_fraction * setup.height_m,
            },
            pipette: Pipette {
                volume_m3: ins.pipette_volume_m3,
                depth_m: ins.pipette_depth_fraction * setup.height_m,
                wedge_fraction: sm.wedge_fraction,
                thickness_m: setup.thickness_m,
                axis_x_m: 0.5 * setup.width_m,
            },
            hydrometer_times_s: within(&ins.hydrometer_times_s),
            buoyancy_times_s: within(&ins.buoyancy_times_s),
            pipette_times_s: within(&ins.pipette_times_s),
            layers: sm.layers,
        }
    }

    /// Every reading time, sorted, without repeats.
    pub fn all_times_s(&self) -> Vec<f64> {
        let mut t: Vec<f64> = self
            .hydrometer_times_s
            .iter()
            .chain(&self.buoyancy_times_s)
            .chain(&self.pipette_times_s)
            .copied()
            .collect();
        t.sort_by(f64::total_cmp);
        t.dedup();
        t
    }
}

/// The layered suspension density of a profile (real units: `suspension_density_kg_m3` of
/// `profiles.csv`), with the grain count of each layer.
pub fn layered_field(pr: &Profile, setup: &Setup, rho_p: f64, rho_f: f64) -> LayeredField {
    let layers = pr.solid_m3.len();
    let h = setup.height_m / layers as f64;
    let vol = setup.width_m * h * setup.thickness_m;
    LayeredField {
        layer_m: h,
        density_kg_m3: pr
            .solid_m3
            .iter()
            .map(|v| rho_f + concentration(*v, vol) * (rho_p - rho_f))
            .collect(),
        fluid_density_kg_m3: rho_f,
        grains: Some(pr.count.iter().map(|&n| n as f64).collect()),
    }
}

/// [`layered_field`] with, as each layer's grain count, its effective count (Σv)²/Σv²
/// ([`effective_count`]): the field's per-layer noise ([`LayeredField::excess_sd`]) is then the
/// compound-Poisson counting noise Σ (a_i m_i)² of the grains
/// ([`crate::instruments::counting`]).
pub fn counting_field(pr: &Profile, setup: &Setup, rho_p: f64, rho_f: f64) -> LayeredField {
    let mut f = layered_field(pr, setup, rho_p, rho_f);
    f.grains = Some(
        pr.solid_m3
            .iter()
            .zip(&pr.solid_sq_m6)
            .map(|(&v, &v2)| effective_count(v, v2))
            .collect(),
    );
    f
}

/// The solid volume of the mean representative grain, m³: the modelled mass over the number
/// of grains, over ρ_p.
fn mean_grain_m3(setup: &Setup, rho_p: f64) -> f64 {
    setup.model_mass_kg / setup.grains.len().max(1) as f64 / rho_p
}

/// `pr` with one mean representative grain more in the layer at `depth_m`.
fn with_one_grain(pr: &Profile, setup: &Setup, rho_p: f64, depth_m: f64) -> Profile {
    let mut p = pr.clone();
    let n = p.solid_m3.len();
    let k = ((depth_m.max(0.0) / (setup.height_m / n as f64)) as usize).min(n - 1);
    p.solid_m3[k] += mean_grain_m3(setup, rho_p);
    p
}

/// The counting σ of the hydrometer's reading on the profile `pr`, g/L of its scale: the
/// compound-Poisson σ of the grains ([`counting_field`]; σ_R = 1000 σ_ρ/(ρ_f (1 − 1/G)), the
/// reading being 1000 (ρ_s/ρ_f − 1)/(1 − 1/G) with ρ_s the mean density of the submerged volume)
/// with one mean grain more at the bulb's centre ([`with_one_more_grain`]). 0 if it does not
/// float.
pub fn hydrometer_counting_sd(
    h: &Hydrometer,
    pr: &Profile,
    setup: &Setup,
    rho_p: f64,
    rho_f: f64,
) -> f64 {
    let Some(base) = h.read(&layered_field(pr, setup, rho_p, rho_f)) else {
        return 0.0;
    };
    let sd = h
        .read(&counting_field(pr, setup, rho_p, rho_f))
        .map_or(0.0, |r| {
            1000.0 * r.density_sd_kg_m3
                / h.fluid_density_kg_m3
                / (1.0 - 1.0 / h.spec.calibration_specific_gravity)
        });
    let one = with_one_grain(pr, setup, rho_p, base.centre_depth_m);
    let one = h
        .read(&layered_field(&one, setup, rho_p, rho_f))
        .map_or(0.0, |r| r.reading - base.reading);
    with_one_more_grain(sd, one)
}

/// The counting σ of the sphere's apparent mass on the profile `pr`, g: the σ of the displaced
/// mass, σ_ρ V_sp ([`counting_field`]), with one mean grain more at its centre.
pub fn sphere_counting_sd(
    s: &BuoyancySphere,
    pr: &Profile,
    setup: &Setup,
    rho_p: f64,
    rho_f: f64,
) -> f64 {
    let sd = s
        .read(&counting_field(pr, setup, rho_p, rho_f))
        .density_sd_kg_m3
        * s.volume_m3();
    let base = s.read(&layered_field(pr, setup, rho_p, rho_f));
    let one = s.read(&layered_field(
        &with_one_grain(pr, setup, rho_p, s.depth_m),
        setup,
        rho_p,
        rho_f,
    ));
    1e3 * with_one_more_grain(sd, base.apparent_mass_kg - one.apparent_mass_kg)
}

/// The counting σ of the pipette's real drawn mass, g: √Σ m_i² of the grains in the draw
/// (`concentration_sd_kg_m3` V), with one mean grain more (its mass over the wedge fraction f).
fn pipette_counting_sd(p: &Pipette, r: &PipetteReading, setup: &Setup) -> f64 {
    let one = setup.model_mass_kg / setup.grains.len().max(1) as f64 / p.wedge_fraction;
    1e3 * with_one_more_grain(r.concentration_sd_kg_m3 * p.volume_m3, one)
}

/// Which instrument a reading comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum InstrumentKind {
    /// ASTM 152H hydrometer.
    Hydrometer,
    /// Buoyancy sphere.
    Buoyancy,
    /// Pipette.
    Pipette,
}

impl InstrumentKind {
    /// Name in the CSV files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Hydrometer => "hydrometer",
            Self::Buoyancy => "buoyancy",
            Self::Pipette => "pipette",
        }
    }
}

/// One reading of an instrument on the simulation, with what the same instrument reads on the
/// ideal Stokes suspension of the input curve at the same time (its own approximation).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct InstrumentReading {
    /// Instrument.
    pub kind: InstrumentKind,
    /// The (φ_o, w_o) pair on the simulation.
    pub point: Point,
    /// The pair on the ideal suspension of the input curve (None if the hydrometer does not
    /// float in it).
    pub ideal: Option<Point>,
    /// Hydrometer details.
    pub hydrometer: Option<HydrometerReading>,
    /// Sphere details.
    pub buoyancy: Option<BuoyancyReading>,
    /// Pipette details.
    pub pipette: Option<PipetteReading>,
    /// Suspension density the instrument measured, kg/m³.
    pub density_kg_m3: f64,
    /// The reading's counting noise (1σ of the representative grains, compound Poisson,
    /// [`crate::instruments::counting`]) in the readings file's unit: g/L of the hydrometer's
    /// scale, g drawn (pipette, the real draw), g of apparent mass (sphere).
    pub counting_sd: f64,
}

/// Suspension density along the hydrometer bulb at one time (seed Fig. 13): (time, distance
/// below the top of the bulb, depth, density) per layer.
pub type BulbRow = (f64, f64, f64, f64);

/// Reads every instrument due at `st.time_s` (within a relative 1e-9 of the time).
pub fn read_instruments(
    set: &InstrumentSet,
    st: &State,
    setup: &Setup,
    bulb: &mut Vec<BulbRow>,
) -> Vec<InstrumentReading> {
    let t = st.time_s;
    let (layers, input) = (set.layers, &setup.distribution);
    let (rho_p, rho_f) = (
        set.analysis.grain_density_kg_m3,
        set.analysis.fluid_density_kg_m3,
    );
    let due = |times: &[f64]| times.iter().any(|x| (x - t).abs() <= 1e-9 * t.max(1.0));
    let an = &set.analysis;
    let mut out = Vec::new();
    let (hyd, buo, pip) = (
        due(&set.hydrometer_times_s),
        due(&set.buoyancy_times_s),
        due(&set.pipette_times_s),
    );
    if !(hyd || buo || pip) {
        return out;
    }
    let finer = |d: f64| input.percent_finer(d) / 100.0;
    let ideal = crate::instruments::ideal_field(an, setup.height_m, layers, t, finer);
    if hyd || buo {
        let pr = profile(st, setup, layers, rho_p);
        let field = layered_field(&pr, setup, rho_p, rho_f);
        if hyd {
            if let Some(r) = set.hydrometer.read(&field) {
                bulb.extend(
                    set.hydrometer
                        .bulb_profile(&field, r.tip_depth_m)
                        .into_iter()
                        .map(|(a, b, c)| (t, a, b, c)),
                );
                out.push(InstrumentReading {
                    kind: InstrumentKind::Hydrometer,
                    point: set.hydrometer.point(an, &r, t),
                    ideal: set
                        .hydrometer
                        .read(&ideal)
                        .map(|ri| set.hydrometer.point(an, &ri, t)),
                    hydrometer: Some(r),
                    buoyancy: None,
                    pipette: None,
                    density_kg_m3: r.density_kg_m3,
                    counting_sd: hydrometer_counting_sd(&set.hydrometer, &pr, setup, rho_p, rho_f),
                });
            }
        }
        if buo {
            let r = set.sphere.read(&field);
            let ri = set.sphere.read(&ideal);
            out.push(InstrumentReading {
                kind: InstrumentKind::Buoyancy,
                point: set.sphere.point(an, &r, t),
                ideal: Some(set.sphere.point(an, &ri, t)),
                hydrometer: None,
                buoyancy: Some(r),
                pipette: None,
                density_kg_m3: r.density_kg_m3,
                counting_sd: sphere_counting_sd(&set.sphere, &pr, setup, rho_p, rho_f),
            });
        }
    }
    if pip {
        let grains = (0..st.len())
            .filter(|&i| !st.settled[i])
            .map(|i| st.grain(&setup.grains, i))
            .map(|g| GrainSample {
                x_m: g.x_m,
                depth_m: setup.height_m - g.y_m,
                mass_kg: g.weight * sphere_mass_kg(g.diameter_m, rho_p),
            });
        let r = set.pipette.read(grains);
        let ci = set.pipette.field_concentration(an, &ideal);
        let mut ideal_pt = set.pipette.point(an, &r, t);
        ideal_pt.percent_finer = an.percent_finer_from_concentration(ci);
        ideal_pt.sd_percent = 0.0;
        out.push(InstrumentReading {
            kind: InstrumentKind::Pipette,
            point: set.pipette.point(an, &r, t),
            ideal: Some(ideal_pt),
            hydrometer: None,
            buoyancy: None,
            pipette: Some(r),
            density_kg_m3: an.density_of_concentration(r.concentration_kg_m3),
            counting_sd: pipette_counting_sd(&set.pipette, &r, setup),
        });
    }
    out
}

/// The hydrometer's bulb density in the initial (homogeneous) suspension, for `bulb_density.csv`.
pub fn initial_bulb_profile(set: &InstrumentSet, setup: &Setup) -> Vec<BulbRow> {
    let st = State::initial(setup);
    let (rho_p, rho_f) = (
        set.analysis.grain_density_kg_m3,
        set.analysis.fluid_density_kg_m3,
    );
    let field = layered_field(&profile(&st, setup, set.layers, rho_p), setup, rho_p, rho_f);
    match set.hydrometer.float_tip_depth_m(&field) {
        Some(tip) => set
            .hydrometer
            .bulb_profile(&field, tip)
            .into_iter()
            .map(|(a, b, c)| (0.0, a, b, c))
            .collect(),
        None => Vec::new(),
    }
}
