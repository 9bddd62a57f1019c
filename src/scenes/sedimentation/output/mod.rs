//! Every output of a sedimentation run, made in memory ([`Outputs`]: tables, charts as SVG
//! text, other files as bytes; nothing is read back): `profiles.csv`, `bed.csv`,
//! `max_diameter.csv`/`.svg` ([`charts`]), `summary.csv`, `snapshots/` ([`pictures`]),
//! `cylinder.csv`/`.svg` ([`cylinder`]), `transient.csv`/`.svg` and `terminal_time.csv`/`.svg`
//! ([`transient`]), the instruments' tables and charts ([`granulometry`], [`charts`]) and the
//! laboratory reading files ([`readings`], files rather than tables: their `#` lines are part
//! of the format).

pub mod charts;
pub mod cylinder;
pub mod granulometry;
pub mod pictures;
pub mod plot;
pub mod readings;
pub mod transient;

use super::instruments::{BulbRow, InstrumentReading};
use super::setup::{limiting_diameter_m, Setup};
use super::state::{concentration, Profile, State};
use crate::io::fmt::num;
use crate::io::{Outputs, Table};
use crate::sample::Grains;
use crate::scenario::{Physics, SampleSpec};
use crate::scenes::SceneReport;
use std::io;

/// What a run has recorded: saved with the state in a checkpoint, written at the end.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Recorded {
    /// The profiles at the record times.
    pub profiles: Vec<Profile>,
    /// (time, band mass fractions, bed included) of each snapshot (kept for checkpoints;
    /// `cylinder.svg` is drawn from the snapshots, the bed apart).
    pub pictures: Vec<(f64, Vec<f64>)>,
    /// The grains at the snapshot times (written to `snapshots/` at the end).
    pub snapshots: Vec<Snapshot>,
    /// The instruments' readings.
    pub readings: Vec<InstrumentReading>,
    /// Suspension density along the hydrometer bulb at its readings.
    pub bulb: Vec<BulbRow>,
}

/// The state at a snapshot time, as much of it as the snapshot's outputs read
/// ([`pictures::write_snapshot`], [`cylinder::panels`], the profiles of `max_diameter.csv` and
/// `readings_d7928.csv`): each grain's height, settled flag and (if a contact moved it)
/// horizontal position; its diameter, weight and class are those of the setup's grains, which
/// never change. [`Snapshot::state`] gives the state back for those outputs.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct Snapshot {
    /// Time, s.
    pub time_s: f64,
    /// Bed height, m.
    pub bed_height_m: f64,
    /// Height of each grain's centre, m.
    pub y_m: Vec<f64>,
    /// Horizontal position of each grain, m; empty when every grain is still where the setup
    /// put it (always without contacts).
    pub x_m: Vec<f64>,
    /// Whether each grain has joined the bed.
    pub settled: Vec<bool>,
}

impl Snapshot {
    /// The snapshot of `st`, a state of a run of `setup`.
    pub fn of(st: &State, setup: &Setup) -> Self {
        let moved = !st.x_m.is_empty()
            && (st.x_m.len() != setup.grains.len()
                || st
                    .x_m
                    .iter()
                    .zip(&setup.grains.x_m)
                    .any(|(x, x0)| x.to_bits() != x0.to_bits()));
        Self {
            time_s: st.time_s,
            bed_height_m: st.bed_height_m,
            y_m: st.y_m.clone(),
            x_m: if moved { st.x_m.clone() } else { Vec::new() },
            settled: st.settled.clone(),
        }
    }

    /// The state the snapshot was taken of, as its outputs read it: heights, horizontal
    /// positions, settled flags, time and bed height (speeds zero, counters and statistics those
    /// of a new run).
    pub fn state(&self) -> State {
        let mut st = State::at_heights(self.y_m.clone());
        st.x_m.clone_from(&self.x_m);
        st.settled.copy_from_slice(&self.settled);
        st.time_s = self.time_s;
        st.bed_height_m = self.bed_height_m;
        st
    }
}

/// Adds every output of a run of `setup` that ended in `st` with what it `rec`orded to `out`,
/// and returns its report (`wall_s`: wall time of the simulation, s). An error is a chart that
/// could not be drawn.
pub fn write_all(
    out: &mut Outputs,
    setup: &Setup,
    st: &State,
    rec: Recorded,
    wall_s: f64,
) -> io::Result<SceneReport> {
    let (c, sm) = (&setup.common, &setup.spec.sample);
    let Recorded {
        profiles,
        pictures: _,
        snapshots,
        readings,
        bulb,
    } = rec;
    if !snapshots.is_empty() {
        let grains = pictures::GrainColumns::of(&setup.grains);
        for snap in &snapshots {
            pictures::write_snapshot(
                out,
                snap.time_s,
                &grains,
                snap.y_m.as_slice().into(),
                (!snap.x_m.is_empty()).then(|| snap.x_m.as_slice().into()),
                snap.settled.as_slice().into(),
            );
        }
    }
    let instrument_errors = granulometry::write_all(out, setup, &readings, &bulb)?;
    readings::write_all(out, setup, &readings, &profiles, &snapshots);
    if !snapshots.is_empty() {
        let panels = cylinder::panels(&snapshots, setup);
        out.table(cylinder::table(&panels, setup.height_m));
        let title = format!(
            "{}: the cylinder at {} (seed 000 Fig. 11)",
            c.name,
            times_text(&panels.iter().map(|p| p.time_s).collect::<Vec<_>>())
        );
        out.file(
            "cylinder.svg",
            cylinder::svg(&title, &panels, setup.width_m, setup.height_m)?,
        );
    }
    let classes: Vec<f64> = setup
        .classes
        .iter()
        .filter(|c| c.mass_fraction > 0.0)
        .map(|c| c.diameter_m)
        .collect();
    let grains = transient::Grains {
        density_kg_m3: sm.density_kg_m3,
        fluid_density_kg_m3: c.fluid_density_kg_m3,
        viscosity_pa_s: setup.viscosity_pa_s,
        gravity_m_s2: c.gravity_m_s2,
        stokes: c.physics == Physics::IdealStokes,
    };
    transient::write_all(out, &c.name, grains, &classes)?;
    let k = Densities {
        grain_kg_m3: sm.density_kg_m3,
        fluid_kg_m3: c.fluid_density_kg_m3,
    };
    out.table(profiles_table(&profiles, setup, sm.layers, k));
    out.table(bed_table(&profiles, setup));
    // Fig. 12's times: those recorded, and the snapshot times (60, 300, 900 s by default) that
    // the default record times miss.
    let from_snapshots: Vec<Profile> = snapshots
        .iter()
        .filter(|sn| !profiles.iter().any(|p| p.time_s == sn.time_s))
        .map(|sn| super::state::profile(&sn.state(), setup, sm.layers, sm.density_kg_m3))
        .collect();
    let mut at: Vec<&Profile> = profiles.iter().chain(&from_snapshots).collect();
    at.sort_by(|a, b| a.time_s.total_cmp(&b.time_s));
    let dmax = max_diameter_rows(&at, setup, sm.layers, k, c.gravity_m_s2);
    out.table(max_diameter_table(&dmax));
    if !dmax.is_empty() {
        out.chart(
            "max_diameter.svg",
            &charts::max_diameter_chart(
                &format!(
                    "{}: largest grain above each depth against eq. 16 (seed 000 Fig. 12)",
                    c.name
                ),
                &dmax,
            ),
        )?;
    }
    let summary = Summary::of(st, &setup.grains);
    out.table(summary_table(sm, setup, st, &summary));
    let mut report = report(sm, setup, st, &summary, wall_s, &instrument_errors);
    report
        .lines
        .extend(instrument_table(&instrument_errors, &readings));
    report.warnings = warnings(setup, &readings);
    Ok(report)
}

/// The validity warnings of a cylinder run: one-way coupling beyond the seed's concentration
/// limits ([`crate::fluid::validity::one_way_coupling_warning`], on the initial homogeneous
/// suspension: the modelled mass in the modelled volume B H h_z), and percent finer above 100 %
/// explained by the counting noise of the grains
/// ([`crate::fluid::validity::percent_finer_above_100_warning`], with each reading's 1σ).
fn warnings(setup: &Setup, readings: &[InstrumentReading]) -> Vec<String> {
    use crate::fluid::validity::{one_way_coupling_warning, percent_finer_above_100_warning};
    let sm = &setup.spec.sample;
    let volume = setup.width_m * setup.height_m * setup.thickness_m;
    let fraction = setup.model_mass_kg / sm.density_kg_m3 / volume;
    let over: Vec<_> = readings
        .iter()
        .map(|r| {
            (
                r.kind.name().to_string(),
                r.point.time_s,
                r.point.percent_finer,
                r.point.sd_percent,
            )
        })
        .collect();
    one_way_coupling_warning(fraction, sm.density_kg_m3, setup.common.fluid_density_kg_m3)
        .into_iter()
        .chain(percent_finer_above_100_warning(&over, setup.grains.len()))
        .collect()
}

/// Grain and fluid densities, kg/m³.
#[derive(Clone, Copy, Debug)]
struct Densities {
    grain_kg_m3: f64,
    fluid_kg_m3: f64,
}

/// `profiles.csv`: per record time and layer (top first) the solid volume, concentration,
/// suspension density, grain count, the count's relative uncertainty 1/√n and the largest and
/// smallest diameter.
fn profiles_table(profiles: &[Profile], setup: &Setup, layers: usize, k: Densities) -> Table {
    let h_ly = setup.height_m / layers as f64;
    let layer_volume = setup.width_m * h_ly * setup.thickness_m;
    let (rho_p, rho_f) = (k.grain_kg_m3, k.fluid_kg_m3);
    let mut t = Table::new(
        "profiles.csv",
        [
            "time_s",
            "layer",
            "depth_m",
            "solid_volume_m3",
            "concentration",
            "suspension_density_kg_m3",
            "grains",
            "concentration_rel_uncertainty",
            "d_max_m",
            "d_min_m",
        ],
    );
    for pr in profiles {
        for k in 0..layers {
            let c = concentration(pr.solid_m3[k], layer_volume);
            let n = pr.count[k];
            t.push(vec![
                num(pr.time_s),
                k.to_string(),
                num((k as f64 + 0.5) * h_ly),
                num(pr.solid_m3[k]),
                num(c),
                num(rho_f + c * (rho_p - rho_f)),
                n.to_string(),
                if n > 0 {
                    num(1.0 / (n as f64).sqrt())
                } else {
                    String::new()
                },
                if n > 0 {
                    num(pr.d_max_m[k])
                } else {
                    String::new()
                },
                if n > 0 {
                    num(pr.d_min_m[k])
                } else {
                    String::new()
                },
            ]);
        }
    }
    t
}

/// `bed.csv`: bed height, mass and mass fraction at every record time.
fn bed_table(profiles: &[Profile], setup: &Setup) -> Table {
    let mut t = Table::new(
        "bed.csv",
        ["time_s", "bed_height_m", "bed_mass_kg", "bed_mass_fraction"],
    );
    for pr in profiles {
        t.push(vec![
            num(pr.time_s),
            num(pr.bed_height_m),
            num(pr.bed_mass_kg),
            num(pr.bed_mass_kg / setup.model_mass_kg),
        ]);
    }
    t
}

/// The rows of `max_diameter.csv`: at 60, 120, 300 and 900 s (those among the `profiles`), the
/// largest grain above each depth (every hundredth of the layers) against the limiting diameter
/// of seed eq. 16.
fn max_diameter_rows(
    profiles: &[&Profile],
    setup: &Setup,
    layers: usize,
    k: Densities,
    gravity_m_s2: f64,
) -> Vec<charts::MaxDiameterRow> {
    let h_ly = setup.height_m / layers as f64;
    let (rho_p, rho_f, mu) = (k.grain_kg_m3, k.fluid_kg_m3, setup.viscosity_pa_s);
    let mut rows = Vec::new();
    for pr in profiles.iter().filter(|pr| {
        [60.0, 120.0, 300.0, 900.0]
            .iter()
            .any(|t| (pr.time_s - t).abs() < 1e-6)
    }) {
        let mut dmax: f64 = 0.0;
        for k in 0..layers {
            dmax = dmax.max(pr.d_max_m[k]);
            if (k + 1) % (layers / 100).max(1) == 0 {
                let depth = (k as f64 + 1.0) * h_ly;
                let limit = limiting_diameter_m(depth, pr.time_s, mu, rho_p, rho_f, gravity_m_s2);
                rows.push((pr.time_s, depth, dmax, limit));
            }
        }
    }
    rows
}

/// `max_diameter.csv` of the `rows` of [`max_diameter_rows`].
fn max_diameter_table(rows: &[charts::MaxDiameterRow]) -> Table {
    let mut t = Table::new(
        "max_diameter.csv",
        [
            "time_s",
            "depth_m",
            "d_max_above_m",
            "limiting_diameter_eq16_m",
        ],
    );
    for &(time, depth, dmax, limit) in rows {
        t.push(vec![num(time), num(depth), num(dmax), num(limit)]);
    }
    t
}

/// The times of the panels as a title says them: `60, 300 and 900 s`.
fn times_text(times_s: &[f64]) -> String {
    let t: Vec<String> = times_s
        .iter()
        .map(|t| crate::io::fmt::sig_shortest(*t, 6))
        .collect();
    match t.split_last() {
        None => String::new(),
        Some((last, [])) => format!("{last} s"),
        Some((last, rest)) => format!("{} and {last} s", rest.join(", ")),
    }
}

/// Figures of the final state shared by `summary.csv` and the report.
struct Summary {
    /// Real grains the representative ones stand for.
    real: f64,
    /// Smallest and largest statistical weight.
    weight_min: f64,
    weight_max: f64,
    /// Grains in the bed at the end.
    settled: usize,
}

impl Summary {
    fn of(st: &State, grains: &Grains) -> Self {
        let weight = |&k: &u32| grains.kinds[k as usize].weight;
        let real: f64 = grains.kind.iter().map(weight).sum();
        let (weight_min, weight_max) = grains
            .kind
            .iter()
            .map(weight)
            .fold((f64::INFINITY, 0.0f64), |a, w| (a.0.min(w), a.1.max(w)));
        Self {
            real,
            weight_min,
            weight_max,
            settled: st.settled.iter().filter(|x| **x).count(),
        }
    }
}

/// `summary.csv`: `quantity, value` rows of the run (sample, grains, steps, bed, contacts).
fn summary_table(sm: &SampleSpec, setup: &Setup, st: &State, su: &Summary) -> Table {
    let rows: [(&str, String); 18] = [
        ("sample", sm.sample.to_string()),
        ("representative_grains", st.len().to_string()),
        ("real_grains_modelled", num(su.real)),
        ("weight_min", num(su.weight_min)),
        ("weight_max", num(su.weight_max)),
        ("model_mass_kg", num(setup.model_mass_kg)),
        ("projection_thickness_m", num(setup.thickness_m)),
        ("steps", st.steps.to_string()),
        ("dt_min_s", num(st.dt_range_s.0)),
        ("dt_max_s", num(st.dt_range_s.1)),
        ("grains_settled_at_end", su.settled.to_string()),
        ("bed_height_m", num(st.bed_height_m)),
        ("contact_pairs", st.contacts.pairs.to_string()),
        (
            "contact_steps_with_pairs",
            st.contacts.steps_with_pairs.to_string(),
        ),
        (
            "contact_max_pairs_per_step",
            st.contacts.max_pairs_per_step.to_string(),
        ),
        ("contact_grains_handed", st.contacts.grains.to_string()),
        ("contact_rapier_steps", st.contacts.rapier_steps.to_string()),
        ("contact_fallbacks", st.contacts.fallbacks.to_string()),
    ];
    Table::with_rows(
        "summary.csv",
        ["quantity", "value"],
        rows.into_iter()
            .map(|(k, v)| vec![k.to_string(), v])
            .collect(),
    )
}

/// The run's report: its console lines (times also in minutes; the instruments' largest and
/// mean errors against the input curve, as in `instrument_errors.csv`) and counts.
fn report(
    sm: &SampleSpec,
    setup: &Setup,
    st: &State,
    su: &Summary,
    wall: f64,
    instrument_errors: &[granulometry::ErrorRow],
) -> SceneReport {
    use crate::io::fmt::{g, short};
    let mut lines = vec![
        format!(
            "sample {}: {} representative grains for {} real ones (weights {}–{}), h_z = {} m",
            sm.sample,
            st.len(),
            g(su.real),
            g(su.weight_min),
            g(su.weight_max),
            g(setup.thickness_m)
        ),
        format!(
            "{} steps (dt {}–{} s) to t = {} min ({} s) in {} s wall; {} grains settled, bed {} mm",
            st.steps,
            g(st.dt_range_s.0),
            g(st.dt_range_s.1),
            g(st.time_s / 60.0),
            short(st.time_s),
            g(wall),
            su.settled,
            g(st.bed_height_m * 1e3)
        ),
        format!(
            "contacts: {} close pairs over {} steps (at most {} in one step), {} grains handed to the contact solve, {} Rapier steps, {} fallbacks, {} s wall",
            st.contacts.pairs,
            st.contacts.steps_with_pairs,
            st.contacts.max_pairs_per_step,
            st.contacts.grains,
            st.contacts.rapier_steps,
            st.contacts.fallbacks,
            g(st.contacts.wall_s)
        ),
    ];
    if !instrument_errors.is_empty() {
        lines.push(
            "instruments against the input curve (|Δ percent finer|, percentage points; 1σ: counting noise):"
                .into(),
        );
    }
    SceneReport {
        warnings: Vec::new(),
        steps: st.steps,
        bodies: st.len(),
        engine_settings: None,
        lines,
        interrupted: st.interrupted,
        reached_s: st.interrupted.then_some(st.time_s),
    }
}

/// The instruments' errors as aligned rows: readings and their times (min), largest and mean
/// error on the simulation, largest error of the instrument's own approximation (on the ideal
/// suspension), mean 1σ.
fn instrument_table(
    rows: &[granulometry::ErrorRow],
    readings: &[InstrumentReading],
) -> Vec<String> {
    use crate::io::fmt::{g, short};
    let times_min = |name: &str| {
        let t: Vec<f64> = readings
            .iter()
            .filter(|r| r.kind.name() == name)
            .map(|r| r.point.time_s / 60.0)
            .collect();
        match (t.first(), t.last()) {
            (Some(a), Some(b)) if a != b => format!("{}–{}", short(*a), short(*b)),
            (Some(a), _) => short(*a),
            _ => "-".into(),
        }
    };
    let mut cells = vec![[
        "instrument",
        "readings",
        "times_min",
        "max_error_%",
        "mean_error_%",
        "max_error_ideal_%",
        "mean_1sigma_%",
    ]
    .map(String::from)
    .to_vec()];
    cells.extend(rows.iter().map(|e| {
        vec![
            e.instrument.clone(),
            e.readings.to_string(),
            times_min(&e.instrument),
            g(e.max_abs_error),
            g(e.mean_abs_error),
            g(e.max_abs_ideal_error),
            g(e.mean_sd),
        ]
    }));
    let width: Vec<usize> = (0..cells[0].len())
        .map(|i| {
            cells
                .iter()
                .map(|r| r[i].chars().count())
                .max()
                .unwrap_or(0)
        })
        .collect();
    cells
        .iter()
        .map(|r| {
            let c: Vec<String> = r
                .iter()
                .enumerate()
                .map(|(i, x)| match i {
                    0 => format!("{x:<w$}", w = width[i]),
                    _ => format!("{x:>w$}", w = width[i]),
                })
                .collect();
            format!("  {}", c.join("  "))
        })
        .collect()
}

/// Name of the physics in the instruments' files and chart titles.
fn physics_label(physics: Physics, long: bool) -> &'static str {
    match (physics, long) {
        (Physics::IdealStokes, _) => "ideal-stokes",
        (_, true) => "full physics",
        (_, false) => "full",
    }
}
