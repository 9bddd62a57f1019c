//! The state of a sedimentation run (what a checkpoint saves), its profiles and contact
//! statistics.

use super::setup::Setup;
use crate::sample::{Grain, Grains};

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
    /// Sum over the representative grains of each layer of their squared solid volume, m⁶
    /// (real grains: (weight · volume)²), for the counting noise of the instruments
    /// ([`crate::instruments::counting`]).
    pub solid_sq_m6: Vec<f64>,
    /// Largest diameter per layer, m (0 if empty).
    pub d_max_m: Vec<f64>,
    /// Smallest diameter per layer, m (∞ if empty).
    pub d_min_m: Vec<f64>,
    /// Bed height, m.
    pub bed_height_m: f64,
    /// Mass in the bed (real units, modelled wedges), kg.
    pub bed_mass_kg: f64,
}

/// State of the simulation: everything a resumed run needs (see [`crate::checkpoint`]) beside
/// the setup's grains ([`Setup::grains`]: their kinds and horizontal positions at t = 0, which
/// never change), grain i of the setup being entry i of every per-grain array.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct State {
    /// Height of each grain's centre above the bottom, m.
    pub y_m: Vec<f64>,
    /// Horizontal position of each grain, m, once a contact has moved one (the contact stage
    /// fills it); empty while every grain is where the setup put it ([`State::x_m`]).
    pub x_m: Vec<f64>,
    /// Vertical velocity of each grain (negative downwards), m/s. Empty while a run without
    /// contacts holds the suspended grains' speeds packed apart
    /// ([`super::suspension::Suspension::new`]): its records, snapshots and readings read
    /// heights only; a checkpoint, the fault scan and the end of the run get every speed.
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
    /// Where this process's wall time went, by stage, and the grain-steps of the free update
    /// (not checkpointed: it measures the machine, for `settle bench`).
    #[serde(skip)]
    pub stages: StageTimes,
}

impl State {
    /// The state at t = 0: every grain of `setup` at rest in suspension.
    pub fn initial(setup: &Setup) -> Self {
        Self::at_heights(setup.grains.initial_heights_m())
    }

    /// The state at t = 0 with the grains at heights `y_m` (m), at rest in suspension, where the
    /// setup put them across.
    pub fn at_heights(y_m: Vec<f64>) -> Self {
        let n = y_m.len();
        Self {
            y_m,
            x_m: Vec::new(),
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
            stages: StageTimes::default(),
        }
    }

    /// Number of grains.
    pub fn len(&self) -> usize {
        self.y_m.len()
    }

    /// True when there is no grain.
    #[allow(dead_code)] // the pair of `len` (clippy's len_without_is_empty)
    pub fn is_empty(&self) -> bool {
        self.y_m.is_empty()
    }

    /// Horizontal position of grain `i` of `grains` (the setup's grains), m.
    #[inline(always)]
    pub fn x_m(&self, grains: &Grains, i: usize) -> f64 {
        match self.x_m.get(i) {
            Some(&x) => x,
            None => grains.x_m[i],
        }
    }

    /// Grain `i` of `grains` (the setup's grains) whole, where it is now.
    #[inline(always)]
    pub fn grain(&self, grains: &Grains, i: usize) -> Grain {
        grains.grain(i, self.x_m(grains, i), self.y_m[i])
    }

    /// Keeps every grain's horizontal position in the state (before a contact moves one).
    pub fn own_x(&mut self, grains: &Grains) {
        if self.x_m.is_empty() {
            self.x_m = grains.x_m.clone();
        }
    }
}

/// Wall time of the stages of the step loop ([`super::simulate`](fn@super::simulate)), s, and the
/// work of the free update: what `settle bench` reports (never a CSV output of a run).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageTimes {
    /// Grain-steps of the free update: suspended grains advanced, summed over the steps (in
    /// ideal-Stokes, the steps a grain takes within an interval between two events, advanced
    /// all at once, count one each).
    pub grain_steps: u64,
    /// Step-size scan, s.
    pub step_size_s: f64,
    /// Voidage grid fill, s.
    pub voidage_s: f64,
    /// Free update (with the in-line fault checks of the ideal-Stokes intervals), s.
    pub free_update_s: f64,
    /// Fault scan after the free update, s.
    pub fault_scan_s: f64,
    /// Contact stage (pairs, clusters, solves), s.
    pub contacts_s: f64,
    /// Deposition, clock and events (records, snapshots, readings, observer), s.
    pub deposit_events_s: f64,
}

impl StageTimes {
    /// Adds `s` seconds to the wall time of `stage`.
    pub fn add(&mut self, stage: Stage, s: f64) {
        *match stage {
            Stage::StepSize => &mut self.step_size_s,
            Stage::Voidage => &mut self.voidage_s,
            Stage::FreeUpdate => &mut self.free_update_s,
            Stage::FaultScan => &mut self.fault_scan_s,
            Stage::Contacts => &mut self.contacts_s,
            Stage::DepositEvents => &mut self.deposit_events_s,
        } += s;
    }
}

/// A stage of the step loop, as [`StageTimes`] counts its wall time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Step size ([`StageTimes::step_size_s`]).
    StepSize,
    /// Voidage grid fill ([`StageTimes::voidage_s`]).
    Voidage,
    /// Free update ([`StageTimes::free_update_s`]).
    FreeUpdate,
    /// Fault scan ([`StageTimes::fault_scan_s`]).
    FaultScan,
    /// Contact stage ([`StageTimes::contacts_s`]).
    Contacts,
    /// Deposition, clock and events ([`StageTimes::deposit_events_s`]).
    DepositEvents,
}

/// The stopwatch of the stages of one step: each [`Laps::lap`] adds the wall time since the
/// previous lap (or the start) to a stage of [`StageTimes`]. The physics never reads it.
#[derive(Clone, Copy, Debug)]
pub struct Laps(std::time::Instant);

impl Laps {
    /// Starts the stopwatch now.
    pub fn start() -> Self {
        Self(std::time::Instant::now())
    }

    /// Adds the wall time since the previous lap to `stage` of `times`, and starts the next lap.
    pub fn lap(&mut self, times: &mut StageTimes, stage: Stage) {
        let now = std::time::Instant::now();
        times.add(stage, (now - self.0).as_secs_f64());
        self.0 = now;
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

/// The profile of `st` over `layers` layers of the suspension height (grains of density
/// `rho_p`, kg/m³).
pub fn profile(st: &State, setup: &Setup, layers: usize, rho_p: f64) -> Profile {
    let h_ly = setup.height_m / layers as f64;
    let mut p = Profile {
        time_s: st.time_s,
        solid_m3: vec![0.0; layers],
        count: vec![0; layers],
        solid_sq_m6: vec![0.0; layers],
        d_max_m: vec![0.0; layers],
        d_min_m: vec![f64::INFINITY; layers],
        bed_height_m: st.bed_height_m,
        bed_mass_kg: 0.0,
    };
    let grains = &setup.grains;
    let volumes: Vec<f64> = grains.kinds.iter().map(|k| k.volume_m3()).collect();
    for (i, (&y, &settled)) in st.y_m.iter().zip(&st.settled).enumerate() {
        let kind = grains.kind[i] as usize;
        let v = volumes[kind];
        if settled {
            p.bed_mass_kg += v * rho_p;
            continue;
        }
        let d = grains.kinds[kind].diameter_m;
        let depth = setup.height_m - y;
        let k = ((depth / h_ly) as usize).min(layers - 1);
        p.solid_m3[k] += v;
        p.count[k] += 1;
        p.solid_sq_m6[k] += v * v;
        p.d_max_m[k] = p.d_max_m[k].max(d);
        p.d_min_m[k] = p.d_min_m[k].min(d);
    }
    p
}

/// Number of horizontal bands of the cylinder pictures.
pub const PICTURE_BANDS: usize = 100;

/// Mass fraction of the modelled sample in each of `bands` horizontal bands (top first), bed
/// included, as in seed Fig. 11.
pub fn band_mass_fractions(st: &State, setup: &Setup, bands: usize) -> Vec<f64> {
    let mut f = vec![0.0; bands];
    let mut total = 0.0;
    let grains = &setup.grains;
    let volumes: Vec<f64> = grains.kinds.iter().map(|k| k.volume_m3()).collect();
    for (&y, &kind) in st.y_m.iter().zip(&grains.kind) {
        let v = volumes[kind as usize];
        let k = (((setup.height_m - y) / setup.height_m * bands as f64) as usize).min(bands - 1);
        f[k] += v;
        total += v;
    }
    f.iter_mut().for_each(|x| *x /= total);
    f
}

/// Concentration (solid volume fraction) of a profile layer, given the layer volume.
pub fn concentration(solid_m3: f64, layer_volume_m3: f64) -> f64 {
    solid_m3 / layer_volume_m3
}
