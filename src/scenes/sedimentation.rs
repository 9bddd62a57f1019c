//! The sedimentation cylinder of seed 000 (ASTM D422), in its 2D projection: two opposing 1°
//! wedges (1/180 of the cylinder) projected on a B × H rectangle of thickness
//! h_z = π B / 720 (so that B H h_z is 1/180 of the cylinder's volume π B² H / 4; the seed
//! prints 2.26e-4 m, which does not follow from its own formula: for B = 0.0635 m it is
//! 2.771e-4 m).
//!
//! # Design: model no more than the scene needs
//!
//! - **N representative grains** ([`crate::sample`]) with statistical weights stand for the
//!   10⁶–10⁹ real grains; every concentration, density and mass is reported in real units.
//! - **Suspension**: in a still fluid each grain only settles vertically; it is advanced by the
//!   exponential integrator of [`crate::dynamics`] (exact for Stokes drag at any dt) outside any
//!   contact pipeline, in parallel. With `physics = "full"` the drag is Dallavalle's with the
//!   Di Felice voidage factor, ε taken from a grid of the local solid fraction (square cells of
//!   `voidage_cell_m`); the step then keeps the fastest suspended grain within half a cell per
//!   step (so ε is never stale by more than that), lands on every record time, and grows as the
//!   large grains leave the suspension (seed §4.6).
//! - **Bed**: a grain reaching the bottom leaves the suspension and joins the bed, whose height
//!   grows with the deposited volume at packing fraction `bed_packing` (full physics; the
//!   `ideal-stokes` reference stops grains at the floor). Nothing reads the bed's inner structure,
//!   so it costs nothing per step.
//! - **Instruments** ([`crate::instruments`], seed §4.5): the 152H hydrometer and the buoyancy
//!   sphere read the layered suspension density of the profile at their reading times (real
//!   densities, applied to the full axisymmetric bodies); the pipette weighs the grains in its
//!   disc. The run lands on every reading time ([`simulate_with`]) and writes
//!   `granulometry.csv`/`.svg`, `instruments.csv`/`.svg`, `bulb_density.csv`/`.svg` and
//!   `instrument_errors.csv`.
//! - **Contacts and lubrication** (`physics = "full"`, `sample.contacts` and
//!   `sample.lubrication`, both on by default; never in `ideal-stokes`): after the free update
//!   of a step, a cell list ([`crate::scenes::grain_contacts::PairFinder`]: columns in x as wide
//!   as the largest pair reach, sorted by height; real diameters) finds every pair of suspended
//!   grains whose gap falls below the lubrication cut-off h_out = 0.1 a_eff at some time of the
//!   step on their free (vertical) paths, exactly. Linked pairs form clusters; each cluster is
//!   re-done from the start of the step in its own Rapier 2D world
//!   ([`crate::scenes::grain_contacts::resolve`]: [`crate::engine::dim2::World`] with its
//!   effective-mass drag, frictionless discs, walls at x = 0 and B, the bed surface as floor),
//!   only over the window in which the pair is close, with the squeeze film
//!   F = 6πμ a_eff² v_n / max(h, h_in) ([`crate::fluid::lubrication`], h_in = 1e-3 a_eff) as an
//!   implicit damper along the line of centres. Grains then leave with the horizontal position
//!   the contact gave them (x changes) and a vertical velocity only: their horizontal velocity
//!   relaxes within the Stokes time (≤ 0.7 ms) and is dropped. Every other grain keeps the exact
//!   update. A lone grain reaching the bed joins it, as before (contact with a flat bed that
//!   absorbs it; the film against the bed, which would delay arrival by ~(a/v_t) ln(h_out/h_in)
//!   ≤ 40 ms, is not modelled). Representative grains are sparse (area fraction ~1e-3), but they
//!   fall through each other's columns: sample 1 (N = 100 000) has ~2 300 close pairs per step
//!   while the 70 µm grains settle (1.7 million in the first 300 s) — see the README for the
//!   cost and the effect on the readings.

use crate::dynamics::advance;
use crate::fluid::lubrication::Cutoffs;
use crate::fluid::newtonian::{stokes_response_time_s, stokes_terminal_velocity_m_s};
use crate::fluid::{sphere_mass_kg, sphere_volume_m3, DragLaw, SphereDrag};
use crate::instruments::buoyancy::{BuoyancyReading, BuoyancySphere};
use crate::instruments::hydrometer::{Hydrometer, HydrometerReading, HydrometerSpec};
use crate::instruments::pipette::{GrainSample, Pipette, PipetteReading};
use crate::instruments::{Analysis, LayeredField, Point};
use crate::output::{num, StagedDir};
use crate::run::{Prepared, RunContext, RunError, SceneReport};
use crate::sample::{discretize, representative_grains, Distribution, Grain, SizeClass};
use crate::scenario::{InstrumentsSpec, Physics, Rheology, SampleSpec, Scenario};
use crate::scenes::grain_contacts::{
    clusters, resolve, ClusterGrain, ContactScene, PairFinder, Probe, Resolved, Solve,
};
use nalgebra::SVector;
use rayon::prelude::*;
use std::collections::HashMap;
use std::io::Write;
use std::path::Path;

/// Largest travel of the fastest grain of a contact cluster per Rapier step, in diameters of
/// the cluster's smallest grain.
pub const CONTACT_TRAVEL_PER_SUBSTEP: f64 = 1.0;

/// Largest relative change of a squeeze film's gap per Rapier step of the contact solve in the
/// run. The approach from h_out to h_in takes ln(h_out/h_in)/f Rapier steps; the frozen gap
/// makes the film approach too fast by a first-order error in f (see
/// `tests/sedimentation_contacts.rs` for the measured figures).
pub const CONTACT_FILM_CHANGE_PER_STEP: f64 = 0.25;

/// Thickness of the 2D projection of two opposing 1° wedges, m: h_z = π B / 720, generalised to a
/// wedge fraction f of the cylinder as h_z = π B f / 4 (B H h_z = f π B² H / 4).
pub fn projection_thickness_m(width_m: f64, wedge_fraction: f64) -> f64 {
    std::f64::consts::PI * width_m * wedge_fraction / 4.0
}

/// Limiting diameter of seed eq. 16 (Stokes), m: the largest grain still above depth y at time
/// t, φ_o = √(18 μ y / ((ρ_p − ρ_f) g t)).
pub fn limiting_diameter_m(
    depth_m: f64,
    time_s: f64,
    mu: f64,
    rho_p: f64,
    rho_f: f64,
    g: f64,
) -> f64 {
    (18.0 * mu * depth_m / ((rho_p - rho_f) * g * time_s)).sqrt()
}

/// The prepared sample of a sedimentation scenario.
pub struct Setup {
    /// Distribution.
    pub distribution: Distribution,
    /// Discrete classes.
    pub classes: Vec<SizeClass>,
    /// Representative grains at t = 0.
    pub grains: Vec<Grain>,
    /// Modelled sample mass (wedge fraction of the sample), kg.
    pub model_mass_kg: f64,
    /// Width B, height H and projection thickness h_z, m.
    pub width_m: f64,
    /// Height H of the suspension, m.
    pub height_m: f64,
    /// Projection thickness h_z, m.
    pub thickness_m: f64,
}

/// Builds the sample of a scenario.
pub fn setup(s: &Scenario, path: &Path) -> Result<Setup, String> {
    let sm = s.sample.as_ref().ok_or("no [sample]")?;
    let ct = s.container.as_ref().ok_or("no [container]")?;
    let width = ct.width_m.ok_or("no container.width_m")?;
    let csv = path.parent().unwrap_or(Path::new(".")).join(&sm.csv);
    let distribution = Distribution::load(&csv, sm.sample)?;
    let classes = discretize(&distribution, sm.n_diameters);
    let model_mass = sm.mass_kg * sm.wedge_fraction;
    let grains = representative_grains(
        &classes,
        sm.particles,
        model_mass,
        sm.density_kg_m3,
        width,
        ct.height_m,
        sm.seed,
    );
    Ok(Setup {
        distribution,
        classes,
        grains,
        model_mass_kg: model_mass,
        width_m: width,
        height_m: ct.height_m,
        thickness_m: projection_thickness_m(width, sm.wedge_fraction),
    })
}

/// Default record times: every 10 s to 60 s, then ×1.25 up to `end_s` (and `end_s`).
pub fn default_record_times(end_s: f64) -> Vec<f64> {
    let mut t = vec![10.0, 20.0, 30.0, 40.0, 50.0, 60.0];
    let mut x = 60.0;
    while x * 1.25 < end_s {
        x = (x * 1.25).round();
        t.push(x);
    }
    t.push(end_s);
    t.retain(|&x| x <= end_s);
    t
}

/// One profile: per layer (top first) the solid volume of suspended grains (real units), their
/// count, and the largest and smallest diameter present.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Profile {
    /// Time, s.
    pub time_s: f64,
    /// Solid volume per layer, m³ (real grains).
    pub solid_m3: Vec<f64>,
    /// Representative grains per layer.
    pub count: Vec<usize>,
    /// Largest diameter per layer, m (0 if empty).
    pub d_max_m: Vec<f64>,
    /// Smallest diameter per layer, m (∞ if empty).
    pub d_min_m: Vec<f64>,
    /// Bed height, m.
    pub bed_height_m: f64,
    /// Mass in the bed (real units, modelled wedges), kg.
    pub bed_mass_kg: f64,
}

/// State of the simulation: everything a resumed run needs (see [`crate::checkpoint`]).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct State {
    /// Grains (positions updated in place).
    pub grains: Vec<Grain>,
    /// Vertical velocity of each grain (negative downwards), m/s.
    pub velocity_m_s: Vec<f64>,
    /// Grain has joined the bed (or stopped on the floor).
    pub settled: Vec<bool>,
    /// Bed height, m.
    pub bed_height_m: f64,
    /// Time, s.
    pub time_s: f64,
    /// Steps taken.
    pub steps: u64,
    /// Step sizes taken: (min, max), s.
    pub dt_range_s: (f64, f64),
    /// The run stopped early on Ctrl-C/SIGTERM.
    pub interrupted: bool,
    /// Next record, snapshot and reading time to land on (indices into the sorted times).
    pub cursor: [usize; 3],
    /// Contact statistics of the run (full physics with contacts or lubrication).
    pub contacts: ContactStats,
    /// The numerical fault that stopped the run, if any (not checkpointed: a faulted run writes
    /// nothing).
    #[serde(skip)]
    pub fault: Option<crate::dynamics::Unstable>,
}

impl State {
    /// The state at t = 0: every grain of `setup` at rest in suspension.
    pub fn initial(setup: &Setup) -> Self {
        let n = setup.grains.len();
        Self {
            grains: setup.grains.clone(),
            velocity_m_s: vec![0.0; n],
            settled: vec![false; n],
            bed_height_m: 0.0,
            time_s: 0.0,
            steps: 0,
            dt_range_s: (f64::INFINITY, 0.0),
            interrupted: false,
            cursor: [0; 3],
            contacts: ContactStats::default(),
            fault: None,
        }
    }
}

/// How much the contact and lubrication pipeline did over a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactStats {
    /// Close pairs found, summed over the steps.
    pub pairs: u64,
    /// Grains handed to the contact solve, summed over the steps.
    pub grains: u64,
    /// Most close pairs in one step.
    pub max_pairs_per_step: usize,
    /// Steps with at least one close pair.
    pub steps_with_pairs: u64,
    /// Rapier steps taken by the contact solve (all clusters, all substeps).
    pub rapier_steps: u64,
    /// Cluster-steps the engine found unstable, advanced by the free update instead.
    pub fallbacks: u64,
    /// Wall time spent finding pairs and resolving them, s (this process's part of the run).
    pub wall_s: f64,
}

fn profile(st: &State, setup: &Setup, layers: usize, rho_p: f64) -> Profile {
    let h_ly = setup.height_m / layers as f64;
    let mut p = Profile {
        time_s: st.time_s,
        solid_m3: vec![0.0; layers],
        count: vec![0; layers],
        d_max_m: vec![0.0; layers],
        d_min_m: vec![f64::INFINITY; layers],
        bed_height_m: st.bed_height_m,
        bed_mass_kg: 0.0,
    };
    for (g, &settled) in st.grains.iter().zip(&st.settled) {
        let v = g.weight * sphere_volume_m3(g.diameter_m);
        if settled {
            p.bed_mass_kg += v * rho_p;
            continue;
        }
        let depth = setup.height_m - g.y_m;
        let k = ((depth / h_ly) as usize).min(layers - 1);
        p.solid_m3[k] += v;
        p.count[k] += 1;
        p.d_max_m[k] = p.d_max_m[k].max(g.diameter_m);
        p.d_min_m[k] = p.d_min_m[k].min(g.diameter_m);
    }
    p
}

/// Runs the simulation, calling `record` at every record time and `snapshot` at every snapshot
/// time. Returns the final state.
pub fn simulate(
    s: &Scenario,
    setup: &Setup,
    record: impl FnMut(&State),
    snapshot: impl FnMut(&State),
) -> State {
    simulate_with(s, setup, &[], record, snapshot, |_| {})
}

/// [`simulate`] that also lands on every time of `reading_times` (within `time.end_s`) and calls
/// `reading` there (the instruments' readings, which need the grains themselves).
pub fn simulate_with(
    s: &Scenario,
    setup: &Setup,
    reading_times: &[f64],
    record: impl FnMut(&State),
    snapshot: impl FnMut(&State),
    reading: impl FnMut(&State),
) -> State {
    simulate_from(
        s,
        setup,
        reading_times,
        State::initial(setup),
        record,
        snapshot,
        reading,
        |_| {},
    )
}

/// [`simulate_with`] from a given state (the initial one, or one saved by a checkpoint), calling
/// `checkpoint` after every step (it decides whether to save). The same state gives the same
/// continuation, bit for bit: every step depends on the state only (the per-grain updates are
/// independent, the sums serial).
#[allow(clippy::too_many_arguments)]
pub fn simulate_from(
    s: &Scenario,
    setup: &Setup,
    reading_times: &[f64],
    state: State,
    mut record: impl FnMut(&State),
    mut snapshot: impl FnMut(&State),
    mut reading: impl FnMut(&State),
    mut checkpoint: impl FnMut(&State),
) -> State {
    let sm: &SampleSpec = s.sample.as_ref().expect("validated");
    let g = s.gravity_m_s2;
    let rho_f = s.fluid.density_kg_m3;
    let mu = match s.fluid.rheology {
        Rheology::Newtonian => s.fluid.viscosity_pa_s.unwrap_or(1e-3),
        Rheology::Bingham => s.fluid.plastic_viscosity_pa_s.unwrap_or(1e-3),
    };
    let ideal = s.physics == Physics::IdealStokes;
    let integrator = s.time.integrator;
    let mut times: Vec<f64> = if sm.record_times_s.is_empty() {
        default_record_times(s.time.end_s)
    } else {
        sm.record_times_s.clone()
    };
    times.sort_by(f64::total_cmp);
    let mut snaps = sm.snapshot_times_s.clone();
    snaps.sort_by(f64::total_cmp);
    let mut reads = reading_times.to_vec();
    reads.sort_by(f64::total_cmp);
    reads.dedup();
    let mut st = state;
    st.interrupted = false;
    let [mut ti, mut si, mut ri] = st.cursor;
    // Voidage grid.
    let cell = sm.voidage_cell_m;
    let (ncx, ncy) = (
        ((setup.width_m / cell).ceil() as usize).max(1),
        ((setup.height_m / cell).ceil() as usize).max(1),
    );
    let cell_volume =
        (setup.width_m / ncx as f64) * (setup.height_m / ncy as f64) * setup.thickness_m;
    let mut solid = vec![0.0; ncx * ncy];
    let cell_of = |x: f64, y: f64| -> usize {
        let i = ((x / setup.width_m * ncx as f64) as usize).min(ncx - 1);
        let j = ((y / setup.height_m * ncy as f64) as usize).min(ncy - 1);
        j * ncx + i
    };
    let bed_area = setup.width_m * setup.thickness_m * sm.bed_packing;
    let mass = |d: f64| sphere_mass_kg(d, sm.density_kg_m3);
    let (mut y_start, mut v_start): (Vec<f64>, Vec<f64>) = (Vec::new(), Vec::new());
    let v_stokes = |d: f64| stokes_terminal_velocity_m_s(d, sm.density_kg_m3, rho_f, mu, g);
    let speed_bound = 2.0
        * st.grains
            .iter()
            .map(|gr| v_stokes(gr.diameter_m))
            .fold(0.0, f64::max);
    let mut finder = PairFinder::default();
    while st.time_s < s.time.end_s * (1.0 - 1e-12) {
        if crate::interrupt::requested() {
            st.interrupted = true;
            break;
        }
        let next_event = times
            .get(ti)
            .copied()
            .unwrap_or(f64::INFINITY)
            .min(snaps.get(si).copied().unwrap_or(f64::INFINITY))
            .min(reads.get(ri).copied().unwrap_or(f64::INFINITY))
            .min(s.time.end_s);
        // Step size: up to the next event, at most max_step; full physics also keeps the fastest
        // suspended grain within half a voidage cell per step.
        let mut dt = (next_event - st.time_s).min(sm.max_step_s);
        if !ideal {
            let vmax = st
                .velocity_m_s
                .iter()
                .zip(&st.settled)
                .zip(&st.grains)
                .filter(|((_, s), _)| !**s)
                .map(|((v, _), gr)| {
                    // Terminal speed bound (Stokes) covers grains still accelerating.
                    v.abs().max(v_stokes(gr.diameter_m))
                })
                .fold(0.0, f64::max);
            if vmax > 0.0 {
                dt = dt.min(0.5 * cell / vmax);
            }

            solid.iter_mut().for_each(|x| *x = 0.0);
            for (gr, &settled) in st.grains.iter().zip(&st.settled) {
                if !settled {
                    solid[cell_of(gr.x_m, gr.y_m)] += gr.weight * sphere_volume_m3(gr.diameter_m);
                }
            }
        }
        let dt = dt.max(1e-12);
        // Start-of-step heights and speeds, for the pair search and the contact solve.
        let with_pairs = !ideal && sm.contacts;
        if with_pairs {
            y_start.clear();
            y_start.extend(st.grains.iter().map(|g| g.y_m));
            v_start.clear();
            v_start.extend_from_slice(&st.velocity_m_s);
        }
        let solid_ref = &solid;
        // Drag of a grain of diameter d in voidage cell `cell`.
        let drag_of = |d: f64, cell: usize| {
            let law = if ideal {
                DragLaw::Stokes { viscosity_pa_s: mu }
            } else {
                let eps = (1.0 - solid_ref[cell] / cell_volume).clamp(0.3, 1.0);
                DragLaw::Dallavalle {
                    viscosity_pa_s: mu,
                    voidage: eps,
                }
            };
            SphereDrag::new(law, d, rho_f)
        };
        let floor = st.bed_height_m;
        st.grains
            .par_iter_mut()
            .zip(st.velocity_m_s.par_iter_mut())
            .zip(st.settled.par_iter())
            .filter(|((_, _), s)| !**s)
            .for_each(|((gr, v), _)| {
                let d = gr.diameter_m;
                let drag = drag_of(d, cell_of(gr.x_m, gr.y_m));
                let m = mass(d);
                let w = SVector::<f64, 1>::new(-(m - sphere_mass_kg(d, rho_f)) * g);
                let step = advance(integrator, &drag, m, &w, &SVector::<f64, 1>::new(*v), dt);
                *v = step.velocity_m_s[0];
                gr.y_m += step.displacement_m[0];
                // Grains that reach the floor or the bed surface are flagged below.
                if gr.y_m - 0.5 * d <= floor {
                    gr.y_m = floor + 0.5 * d;
                }
            });
        // Numerical faults of the free update (before the contact solve, whose clusters the engine
        // checks with its own bounds): an explicit blow-up shows here.
        if let Some(u) = grain_fault(&st, setup, dt, Some(speed_bound), integrator, mu, sm) {
            st.fault = Some(u);
            break;
        }
        if with_pairs {
            let t0 = std::time::Instant::now();
            let probes: Vec<Option<Probe>> = st
                .grains
                .iter()
                .zip(&st.settled)
                .zip(&y_start)
                .map(|((g, &settled), &y0)| {
                    (!settled).then_some(Probe {
                        x_m: g.x_m,
                        y_start_m: y0,
                        y_end_m: g.y_m,
                        radius_m: 0.5 * g.diameter_m,
                    })
                })
                .collect();
            let pairs = finder.pairs(&probes, setup.width_m, sm.lubrication_outer_cutoff);
            let groups = clusters(&pairs);
            // Each cluster from the start of the step, in its own Rapier world (in parallel).
            let scene = ContactScene {
                width_m: setup.width_m,
                floor_m: floor,
                density_kg_m3: sm.density_kg_m3,
                fluid_density_kg_m3: rho_f,
                gravity_m_s2: g,
                viscosity_pa_s: mu,
                lubrication: sm.lubrication.then_some(Cutoffs {
                    inner: sm.lubrication_inner_cutoff,
                    outer: sm.lubrication_outer_cutoff,
                }),
                outer_fraction: sm.lubrication_outer_cutoff,
                integrator,
                travel_per_substep: CONTACT_TRAVEL_PER_SUBSTEP,
                film_change_per_step: CONTACT_FILM_CHANGE_PER_STEP,
            };
            let mut local: HashMap<usize, (usize, usize)> = HashMap::new();
            for (c, grp) in groups.iter().enumerate() {
                for (k, &i) in grp.iter().enumerate() {
                    local.insert(i, (c, k));
                }
            }
            let mut group_pairs: Vec<Vec<(usize, usize)>> = vec![Vec::new(); groups.len()];
            for &(i, j) in &pairs {
                let (c, a) = local[&i];
                group_pairs[c].push((a, local[&j].1));
            }
            let grains_ref = &st.grains;
            let (y0s, v0s) = (&y_start, &v_start);
            let results: Vec<(Vec<Resolved>, Solve)> = groups
                .par_iter()
                .zip(&group_pairs)
                .map(|(grp, gp)| {
                    let members: Vec<ClusterGrain> = grp
                        .iter()
                        .map(|&i| {
                            let gr = &grains_ref[i];
                            ClusterGrain {
                                x_m: gr.x_m,
                                y_m: y0s[i],
                                vy_m_s: v0s[i],
                                diameter_m: gr.diameter_m,
                                drag: drag_of(gr.diameter_m, cell_of(gr.x_m, y0s[i])),
                            }
                        })
                        .collect();
                    resolve(&members, gp, &scene, dt)
                })
                .collect();
            for (grp, (res, n)) in groups.iter().zip(results) {
                st.contacts.rapier_steps += n.rapier_steps;
                st.contacts.fallbacks += u64::from(n.fallback);
                for (&i, r) in grp.iter().zip(res) {
                    st.grains[i].x_m = r.x_m;
                    st.grains[i].y_m = r.y_m;
                    st.velocity_m_s[i] = r.vy_m_s;
                }
            }
            let cs = &mut st.contacts;
            cs.pairs += pairs.len() as u64;
            cs.grains += groups.iter().map(Vec::len).sum::<usize>() as u64;
            cs.max_pairs_per_step = cs.max_pairs_per_step.max(pairs.len());
            cs.steps_with_pairs += u64::from(!pairs.is_empty());
            cs.wall_s += t0.elapsed().as_secs_f64();
            // After a contact solve: a small grain squeezed by a large one may briefly move faster
            // than the free bound (its speed is the cluster engine's to check).
            let moved = !pairs.is_empty();
            if let Some(u) = moved
                .then(|| grain_fault(&st, setup, dt, None, integrator, mu, sm))
                .flatten()
            {
                st.fault = Some(u);
                break;
            }
        }
        // Deposition (serial: the bed grows as grains join it).
        for ((gr, v), settled) in st
            .grains
            .iter_mut()
            .zip(st.velocity_m_s.iter_mut())
            .zip(st.settled.iter_mut())
        {
            if !*settled && gr.y_m - 0.5 * gr.diameter_m <= st.bed_height_m + 1e-15 {
                *settled = true;
                *v = 0.0;
                gr.y_m = st.bed_height_m + 0.5 * gr.diameter_m;
                if !ideal {
                    st.bed_height_m += gr.weight * sphere_volume_m3(gr.diameter_m) / bed_area;
                }
            }
        }
        st.time_s += dt;
        st.steps += 1;
        st.dt_range_s = (st.dt_range_s.0.min(dt), st.dt_range_s.1.max(dt));
        if (next_event - st.time_s).abs() <= 1e-9 * next_event.max(1.0) {
            st.time_s = next_event;
        }
        while ti < times.len() && times[ti] <= st.time_s * (1.0 + 1e-12) {
            record(&st);
            ti += 1;
        }
        while si < snaps.len() && snaps[si] <= st.time_s * (1.0 + 1e-12) {
            snapshot(&st);
            si += 1;
        }
        while ri < reads.len() && reads[ri] <= st.time_s * (1.0 + 1e-12) {
            reading(&st);
            ri += 1;
        }
        st.cursor = [ti, si, ri];
        checkpoint(&st);
    }
    st
}

/// The first grain in a numerical fault after a step of `dt_s` from `st` (state updated in
/// place, time not yet advanced), as an [`Unstable`] report: a non-finite position or velocity,
/// a centre outside the cylinder (beside the walls, or a diameter above the top), or, with
/// `speed_bound_m_s`, a speed above it. The suggested dt is the explicit drag limit 2τ of that
/// grain (Stokes τ = ρ_p d²/(18 μ)) with the explicit integrator, else half the step.
fn grain_fault(
    st: &State,
    setup: &Setup,
    dt_s: f64,
    speed_bound_m_s: Option<f64>,
    integrator: crate::dynamics::Integrator,
    mu: f64,
    sm: &SampleSpec,
) -> Option<crate::dynamics::Unstable> {
    use crate::dynamics::{DtBasis, Integrator};
    let (width, height) = (setup.width_m, setup.height_m);
    let bound = speed_bound_m_s.unwrap_or(f64::INFINITY);
    let i = st
        .grains
        .par_iter()
        .zip(st.velocity_m_s.par_iter())
        .position_first(|(gr, v)| {
            !(gr.y_m.is_finite() && v.is_finite() && gr.x_m.is_finite())
                || v.abs() > bound
                || gr.y_m > height + gr.diameter_m
                || gr.x_m < -1e-12
                || gr.x_m > width + 1e-12
        })?;
    let (gr, v) = (st.grains[i], st.velocity_m_s[i]);
    let d = gr.diameter_m;
    let (stable, basis) = if integrator == Integrator::Explicit {
        (
            2.0 * stokes_response_time_s(d, sm.density_kg_m3, mu),
            DtBasis::ExplicitDrag,
        )
    } else {
        (0.5 * dt_s, DtBasis::Halved)
    };
    let (quantity, value) = if !(gr.y_m.is_finite() && gr.x_m.is_finite()) {
        ("position", gr.y_m)
    } else if !v.is_finite() {
        ("velocity", v)
    } else if v.abs() > bound {
        (
            "speed (bound: twice the largest grain's Stokes terminal speed), m/s",
            v.abs(),
        )
    } else {
        ("height above the bottom (outside the cylinder), m", gr.y_m)
    };
    Some(crate::dynamics::Unstable {
        body: format!("grain {i} (d = {d:.3e} m)"),
        time_s: st.time_s + dt_s,
        step: st.steps + 1,
        what: format!("{quantity} = {value:.3e}"),
        dt_s,
        stable_dt_s: stable,
        dt_basis: basis,
    })
}

/// Number of horizontal bands of the cylinder pictures.
pub const PICTURE_BANDS: usize = 100;

/// Mass fraction of the modelled sample in each of `bands` horizontal bands (top first), bed
/// included, as in seed Fig. 11.
pub fn band_mass_fractions(st: &State, setup: &Setup, bands: usize) -> Vec<f64> {
    let mut f = vec![0.0; bands];
    let mut total = 0.0;
    for g in &st.grains {
        let v = g.weight * sphere_volume_m3(g.diameter_m);
        let k =
            (((setup.height_m - g.y_m) / setup.height_m * bands as f64) as usize).min(bands - 1);
        f[k] += v;
        total += v;
    }
    f.iter_mut().for_each(|x| *x /= total);
    f
}

/// Draws the cylinder at each snapshot time side by side: grey level = mass fraction per band
/// (black = the largest band fraction in suspension; the bed saturates), like seed Fig. 11. PNG; panels in the
/// order of `snapshot_times_s`, each topped by one tick per minute (up to 15).
fn draw_cylinder(path: &Path, pictures: &[(f64, Vec<f64>)]) -> Result<(), String> {
    use plotters::prelude::*;
    let (pw, ph, gap) = (80u32, 640u32, 40u32);
    let width = pictures.len() as u32 * (pw + gap) + gap;
    let root = BitMapBackend::new(path, (width, ph + 60)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    // Grey scale set by the suspension (the bottom band, with the bed, saturates to black).
    let fmax = pictures
        .iter()
        .flat_map(|p| p.1[..p.1.len().saturating_sub(1)].iter().copied())
        .fold(1e-300, f64::max);
    for (i, (t, f)) in pictures.iter().enumerate() {
        let t = *t;
        let x0 = (gap + i as u32 * (pw + gap)) as i32;
        let bands = f.len() as f64;
        for (k, frac) in f.iter().enumerate() {
            let grey = (255.0 * (1.0 - (frac / fmax).min(1.0))).round() as u8;
            let y0 = 30 + (k as f64 / bands * ph as f64) as i32;
            let y1 = 30 + ((k + 1) as f64 / bands * ph as f64).ceil() as i32;
            root.draw(&Rectangle::new(
                [(x0, y0), (x0 + pw as i32, y1)],
                RGBColor(grey, grey, grey).filled(),
            ))
            .map_err(|e| e.to_string())?;
        }
        root.draw(&Rectangle::new(
            [(x0, 30), (x0 + pw as i32, 30 + ph as i32)],
            BLACK.stroke_width(1),
        ))
        .map_err(|e| e.to_string())?;
        // Time marks as ticks above the panel, one per 60 s up to 15 (no fonts in the bitmap
        // backend; the panel times are the snapshot times, in order).
        let ticks = ((t / 60.0).round() as i32).clamp(1, 15);
        for j in 0..ticks {
            let x = x0 + 4 + j * 5;
            root.draw(&Rectangle::new([(x, 10), (x + 2, 22)], BLACK.filled()))
                .map_err(|e| e.to_string())?;
        }
    }
    root.present().map_err(|e| e.to_string())
}

/// Concentration (solid volume fraction) of a profile layer, given the layer volume.
fn concentration(solid_m3: f64, layer_volume_m3: f64) -> f64 {
    solid_m3 / layer_volume_m3
}

fn write_snapshot(dir: &Path, st: &State) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let stem = format!("t{:08.1}s", st.time_s);
    let mut w =
        csv::Writer::from_path(dir.join(format!("{stem}.csv"))).map_err(std::io::Error::other)?;
    w.write_record(["x_m", "y_m", "diameter_m", "weight", "settled"])
        .map_err(std::io::Error::other)?;
    for (g, s) in st.grains.iter().zip(&st.settled) {
        w.write_record([
            num(g.x_m),
            num(g.y_m),
            num(g.diameter_m),
            num(g.weight),
            s.to_string(),
        ])
        .map_err(std::io::Error::other)?;
    }
    w.flush()?;
    // VTK PolyData (ASCII .vtp) for ParaView: points with diameter and weight.
    let mut f = std::io::BufWriter::new(std::fs::File::create(dir.join(format!("{stem}.vtp")))?);
    let n = st.grains.len();
    writeln!(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>")?;
    writeln!(f, "<Piece NumberOfPoints=\"{n}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">")?;
    writeln!(f, "<PointData Scalars=\"diameter_m\">\n<DataArray type=\"Float64\" Name=\"diameter_m\" format=\"ascii\">")?;
    for g in &st.grains {
        write!(f, "{:e} ", g.diameter_m)?;
    }
    writeln!(
        f,
        "\n</DataArray>\n<DataArray type=\"Float64\" Name=\"weight\" format=\"ascii\">"
    )?;
    for g in &st.grains {
        write!(f, "{:e} ", g.weight)?;
    }
    writeln!(f, "\n</DataArray>\n</PointData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">")?;
    for g in &st.grains {
        write!(f, "{:e} {:e} 0 ", g.x_m, g.y_m)?;
    }
    writeln!(
        f,
        "\n</DataArray>\n</Points>\n</Piece>\n</PolyData>\n</VTKFile>"
    )?;
    f.flush()
}

/// What a run has recorded so far: saved with the state in a checkpoint.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
struct Recorded {
    profiles: Vec<Profile>,
    /// (time, band mass fractions) of each snapshot, for `cylinder.png`.
    pictures: Vec<(f64, Vec<f64>)>,
    /// The states at the snapshot times (written to `snapshots/` at the end).
    snapshots: Vec<State>,
    readings: Vec<InstrumentReading>,
    bulb: Vec<BulbRow>,
}

/// Runs a sedimentation scenario and writes `profiles.csv`, `bed.csv`, `max_diameter.csv`,
/// `snapshots/`, `summary.csv` and the instruments' files (see the module doc). With
/// checkpoints in `ctx` it saves its state and what it recorded every period and when
/// interrupted (part `state`, see [`crate::checkpoint`]); with `ctx.resume` it continues from
/// the saved state.
pub fn run(p: &Prepared, stage: &StagedDir, ctx: &RunContext) -> Result<SceneReport, RunError> {
    let s = &p.scenario;
    let sm = s.sample.as_ref().expect("validated");
    let setup = setup(s, &p.path)
        .map_err(|e| RunError::Other(format!("{}: key `sample.csv`: {e}", p.path.display())))?;
    let io = |e: std::io::Error| RunError::Io(p.path.clone(), e);
    let layers = sm.layers;
    let h_ly = setup.height_m / layers as f64;
    let layer_volume = setup.width_m * h_ly * setup.thickness_m;
    let rho_p = sm.density_kg_m3;
    let rho_f = s.fluid.density_kg_m3;
    let mu = s
        .fluid
        .viscosity_pa_s
        .or(s.fluid.plastic_viscosity_pa_s)
        .unwrap_or(1e-3);
    let instruments = InstrumentSet::new(s, &setup);
    let (start, recorded) = match (&ctx.checkpoints, ctx.resume) {
        (Some(c), true) => c
            .load::<(State, Recorded)>(&s.name, "state")
            .map_err(RunError::Other)?,
        _ => None,
    }
    .unwrap_or_else(|| {
        let recorded = Recorded {
            bulb: initial_bulb_profile(&instruments, &setup),
            ..Recorded::default()
        };
        (State::initial(&setup), recorded)
    });
    let rec = std::cell::RefCell::new(recorded);
    let save_err: std::cell::RefCell<Option<std::io::Error>> = Default::default();
    let save = |st: &State| {
        if let Some(c) = &ctx.checkpoints {
            if let Err(e) = c.save(&s.name, "state", &(st, &*rec.borrow())) {
                save_err.borrow_mut().get_or_insert(e);
            }
        }
    };
    let mut timer = ctx.checkpoints.as_ref().map(|c| c.timer());
    let bar = crate::progress::bar(
        s.time.end_s.ceil() as u64,
        &s.name,
        "s simulated,",
        ctx.quiet,
    );
    let t0 = std::time::Instant::now();
    let st = simulate_from(
        s,
        &setup,
        &instruments.all_times_s(),
        start,
        |st| {
            rec.borrow_mut()
                .profiles
                .push(profile(st, &setup, layers, rho_p))
        },
        |st| {
            let mut r = rec.borrow_mut();
            r.pictures
                .push((st.time_s, band_mass_fractions(st, &setup, PICTURE_BANDS)));
            r.snapshots.push(st.clone());
        },
        |st| {
            let r = &mut *rec.borrow_mut();
            r.readings
                .extend(read_instruments(&instruments, st, &setup, &mut r.bulb))
        },
        |st| {
            if st.steps % 256 == 0 {
                bar.set_position(st.time_s as u64);
                bar.set_message(crate::progress::step_message(st.steps, t0));
            }
            if timer.as_mut().is_some_and(|t| t.due()) {
                save(st);
            }
        },
    );
    bar.finish_and_clear();
    if let Some(u) = st.fault.clone() {
        // Nothing to resume from a run that went unstable.
        return Err(RunError::Unstable(p.path.clone(), u));
    }
    if st.interrupted {
        save(&st);
    }
    if let Some(e) = save_err.into_inner() {
        return Err(RunError::Io(p.path.clone(), e));
    }
    let Recorded {
        profiles,
        pictures,
        snapshots,
        readings,
        bulb,
    } = rec.into_inner();
    let snap_dir = stage.path("snapshots");
    for snap in &snapshots {
        write_snapshot(&snap_dir, snap).map_err(io)?;
    }
    let wall = t0.elapsed().as_secs_f64();
    // Instruments: granulometry.csv/.svg, instruments.csv/.svg, bulb_density.csv/.svg,
    // instrument_errors.csv.
    let instrument_errors = crate::output::granulometry::errors(&setup.distribution, &readings);
    {
        use crate::output::granulometry as gr;
        let err = |e: std::io::Error| RunError::Io(p.path.clone(), e);
        gr::write_granulometry(
            &stage.path("granulometry.csv"),
            sm.sample,
            &setup.distribution,
            &readings,
        )
        .map_err(err)?;
        gr::write_instruments(&stage.path("instruments.csv"), &readings).map_err(err)?;
        gr::write_bulb_density(&stage.path("bulb_density.csv"), &bulb).map_err(err)?;
        gr::write_chart(
            &stage.path("granulometry.svg"),
            &format!(
                "{}: percent finer, input and instruments ({})",
                s.name,
                match s.physics {
                    Physics::IdealStokes => "ideal-stokes",
                    _ => "full physics",
                }
            ),
            &setup.distribution,
            &readings,
        )
        .map_err(RunError::Other)?;
        gr::write_time_chart(
            &stage.path("instruments.svg"),
            &format!("{}: percent finer read against time", s.name),
            &readings,
        )
        .map_err(RunError::Other)?;
        gr::write_bulb_chart(
            &stage.path("bulb_density.svg"),
            &format!("{}: suspension density along the hydrometer bulb", s.name),
            &bulb,
            instruments.hydrometer.spec.bulb_length_m,
        )
        .map_err(RunError::Other)?;
        gr::write_errors(
            &stage.path("instrument_errors.csv"),
            &s.name,
            sm.sample,
            match s.physics {
                Physics::IdealStokes => "ideal-stokes",
                _ => "full",
            },
            setup.grains.len(),
            &instrument_errors,
        )
        .map_err(err)?;
    }
    if !pictures.is_empty() {
        draw_cylinder(&stage.path("cylinder.png"), &pictures).map_err(RunError::Other)?;
    }
    // profiles.csv
    let mut w = csv::Writer::from_path(stage.path("profiles.csv"))
        .map_err(|e| io(std::io::Error::other(e)))?;
    w.write_record([
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
    ])
    .map_err(|e| io(std::io::Error::other(e)))?;
    for pr in &profiles {
        for k in 0..layers {
            let c = concentration(pr.solid_m3[k], layer_volume);
            let n = pr.count[k];
            w.write_record([
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
            ])
            .map_err(|e| io(std::io::Error::other(e)))?;
        }
    }
    w.flush().map_err(io)?;
    // bed.csv
    let mut w =
        csv::Writer::from_path(stage.path("bed.csv")).map_err(|e| io(std::io::Error::other(e)))?;
    w.write_record(["time_s", "bed_height_m", "bed_mass_kg", "bed_mass_fraction"])
        .map_err(|e| io(std::io::Error::other(e)))?;
    for pr in &profiles {
        w.write_record([
            num(pr.time_s),
            num(pr.bed_height_m),
            num(pr.bed_mass_kg),
            num(pr.bed_mass_kg / setup.model_mass_kg),
        ])
        .map_err(|e| io(std::io::Error::other(e)))?;
    }
    w.flush().map_err(io)?;
    // max_diameter.csv: largest grain above each depth against seed eq. 16.
    let mut w = csv::Writer::from_path(stage.path("max_diameter.csv"))
        .map_err(|e| io(std::io::Error::other(e)))?;
    w.write_record([
        "time_s",
        "depth_m",
        "d_max_above_m",
        "limiting_diameter_eq16_m",
    ])
    .map_err(|e| io(std::io::Error::other(e)))?;
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
                w.write_record([
                    num(pr.time_s),
                    num(depth),
                    num(dmax),
                    num(limiting_diameter_m(
                        depth,
                        pr.time_s,
                        mu,
                        rho_p,
                        rho_f,
                        s.gravity_m_s2,
                    )),
                ])
                .map_err(|e| io(std::io::Error::other(e)))?;
            }
        }
    }
    w.flush().map_err(io)?;
    // summary.csv
    let real: f64 = st.grains.iter().map(|g| g.weight).sum();
    let (wmin, wmax) = st.grains.iter().fold((f64::INFINITY, 0.0f64), |a, g| {
        (a.0.min(g.weight), a.1.max(g.weight))
    });
    let settled = st.settled.iter().filter(|x| **x).count();
    let mut w = csv::Writer::from_path(stage.path("summary.csv"))
        .map_err(|e| io(std::io::Error::other(e)))?;
    let rows: [(&str, String); 18] = [
        ("sample", sm.sample.to_string()),
        ("representative_grains", st.grains.len().to_string()),
        ("real_grains_modelled", num(real)),
        ("weight_min", num(wmin)),
        ("weight_max", num(wmax)),
        ("model_mass_kg", num(setup.model_mass_kg)),
        ("projection_thickness_m", num(setup.thickness_m)),
        ("steps", st.steps.to_string()),
        ("dt_min_s", num(st.dt_range_s.0)),
        ("dt_max_s", num(st.dt_range_s.1)),
        ("grains_settled_at_end", settled.to_string()),
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
    w.write_record(["quantity", "value"])
        .map_err(|e| io(std::io::Error::other(e)))?;
    for (k, v) in &rows {
        w.write_record([k.to_string(), v.clone()])
            .map_err(|e| io(std::io::Error::other(e)))?;
    }
    w.flush().map_err(io)?;
    Ok(SceneReport {
        steps: st.steps,
        bodies: st.grains.len(),
        engine_settings: None,
        lines: vec![
            format!(
                "sample {}: {} representative grains for {:.3e} real ones (weights {:.3e}–{:.3e}), h_z = {:.4e} m",
                sm.sample,
                st.grains.len(),
                real,
                wmin,
                wmax,
                setup.thickness_m
            ),
            format!(
                "{} steps (dt {:.3e}–{:.3e} s) to t = {} s in {:.2} s wall; {} grains settled, bed {:.3e} m",
                st.steps, st.dt_range_s.0, st.dt_range_s.1, st.time_s, wall, settled, st.bed_height_m
            ),
            format!(
                "contacts: {} close pairs over {} steps (at most {} in one step), {} grains handed to the contact solve, {} Rapier steps, {} fallbacks, {:.2} s wall",
                st.contacts.pairs,
                st.contacts.steps_with_pairs,
                st.contacts.max_pairs_per_step,
                st.contacts.grains,
                st.contacts.rapier_steps,
                st.contacts.fallbacks,
                st.contacts.wall_s
            ),
            format!(
                "instruments against the input curve (largest / mean |Δ percent finer|): {}",
                instrument_errors
                    .iter()
                    .map(|e| format!(
                        "{} {:.1} / {:.1} %",
                        e.instrument, e.max_abs_error, e.mean_abs_error
                    ))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ],
        interrupted: st.interrupted,
    })
}

// ---------------------------------------------------------------------------------------------
// Instruments (seed 000 §4.5): hydrometer, buoyancy sphere and pipette read on the simulation.

/// The hydrometer figures of an `[instruments]` table.
pub fn hydrometer_spec(ins: &InstrumentsSpec) -> HydrometerSpec {
    HydrometerSpec {
        bulb_volume_m3: ins.hydrometer_bulb_volume_m3,
        bulb_length_m: ins.hydrometer_bulb_length_m,
        taper_m: ins.hydrometer_taper_m,
        stem_length_m: ins.hydrometer_stem_length_m,
        effective_depth_zero_m: ins.hydrometer_effective_depth_zero_m,
        effective_depth_slope_m: ins.hydrometer_effective_depth_slope_m,
        full_scale: ins.hydrometer_full_scale,
        astm_cylinder_area_m2: ins.hydrometer_astm_cylinder_area_m2,
        calibration_specific_gravity: ins.hydrometer_calibration_specific_gravity,
    }
}

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
    /// The instruments of scenario `s` (defaults of [`InstrumentsSpec`] without `[instruments]`).
    pub fn new(s: &Scenario, setup: &Setup) -> Self {
        let sm = s.sample.as_ref().expect("validated");
        let ins = s.instruments.clone().unwrap_or_default();
        let rho_f = s.fluid.density_kg_m3;
        let mu = match s.fluid.rheology {
            Rheology::Newtonian => s.fluid.viscosity_pa_s.unwrap_or(1e-3),
            Rheology::Bingham => s.fluid.plastic_viscosity_pa_s.unwrap_or(1e-3),
        };
        let within = |t: &[f64]| -> Vec<f64> {
            let mut t: Vec<f64> = t
                .iter()
                .copied()
                .filter(|&x| x > 0.0 && x <= s.time.end_s * (1.0 + 1e-12))
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
                gravity_m_s2: s.gravity_m_s2,
                c0_kg_m3: setup.model_mass_kg
                    / (setup.width_m * setup.height_m * setup.thickness_m),
            },
            hydrometer: Hydrometer::new(hydrometer_spec(&ins), rho_f),
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
        let field = layered_field(&profile(st, setup, layers, rho_p), setup, rho_p, rho_f);
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
            });
        }
    }
    if pip {
        let grains = st
            .grains
            .iter()
            .zip(&st.settled)
            .filter(|(_, s)| !**s)
            .map(|(g, _)| GrainSample {
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
