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
//!   disc. The run lands on every reading time ([`simulate`](fn@simulate)) and writes
//!   `granulometry.csv`/`.svg`, `instruments.csv`/`.svg`, `bulb_density.csv`/`.svg` and
//!   `instrument_errors.csv`.
//! - **Contacts and lubrication** (`physics = "full"`, `sample.contacts` and
//!   `sample.lubrication`, both off by default (lubrication follows contacts); never in `ideal-stokes`): after the free update
//!   of a step, a cell list ([`contacts::PairFinder`]: columns in x as wide
//!   as the largest pair reach, sorted by height; real diameters) finds every pair of suspended
//!   grains whose gap falls below the lubrication cut-off h_out = 0.1 a_eff at some time of the
//!   step on their free (vertical) paths, exactly. Linked pairs form clusters; each cluster is
//!   re-done from the start of the step in its own Rapier 2D world
//!   ([`contacts::resolve`](fn@contacts::resolve): [`crate::engine::dim2::World`] with its
//!   effective-mass drag, discs with the Coulomb friction and restitution of `[contacts]` (frictionless and perfectly inelastic without it), walls at x = 0 and B, the bed surface as floor),
//!   only over the window in which the pair is close, with the squeeze film
//!   F = 6πμ a_eff² v_n / max(h, h_in) ([`crate::fluid::lubrication`], h_in = 1e-3 a_eff) as an
//!   implicit damper along the line of centres. Grains then leave with the horizontal position
//!   the contact gave them (x changes) and a vertical velocity only: their horizontal velocity
//!   relaxes within the Stokes time (≤ 0.7 ms) and is dropped. Every other grain keeps the exact
//!   update. A lone grain reaching the bed joins it, as before (contact with a flat bed that
//!   absorbs it; the film against the bed, which would delay arrival by ~(a/v_t) ln(h_out/h_in)
//!   ≤ 40 ms, is not modelled). Representative grains are sparse (area fraction ~1e-3), but they
//!   fall through each other's columns: sample 1 (N = 100 000) has ~2 300 close pairs per step
//!   while the 70 µm grains settle (1.7 million in the first 300 s) — see
//!   `docs/validation/sedimentation.md` for the cost and the effect on the readings.
//!
//! # Layout
//!
//! | file | stage |
//! |---|---|
//! | `setup.rs` | the typed setup: geometry, representative grains, viscosity, contact properties |
//! | `state.rs` | the state a checkpoint saves, profiles, contact statistics |
//! | `schedule.rs` | record, snapshot and reading times and their cursors; the next event |
//! | `voidage.rs` | the voidage grid and the drag it gives |
//! | `step.rs` | free update, deposition, clock, fault scan |
//! | `step/stepper.rs` | the step constants and the step size |
//! | `step/kernel.rs` | the free update of one grain, written once for every loop |
//! | `step/interval.rs` | ideal Stokes: the steps between two events at once, grain by grain |
//! | `contacts/` | pair search, clusters, the Rapier solve of each cluster, the contact stage |
//! | `simulate.rs` | the step loop, a short sequence of the stages above |
//! | `observer.rs` | what the loop tells its caller (records, snapshots, readings, steps) |
//! | `instruments.rs` | the instruments read on the state |
//! | `suspension.rs` | the suspended grains packed apart (full physics without contacts) |
//! | `output/` | every table and file of the run, in memory ([`Outputs`]) |
//! | `cost.rs` | the run's cost estimate |

pub mod contacts;
pub mod cost;
pub mod instruments;
pub mod observer;
pub mod output;
pub mod schedule;
pub mod setup;
pub mod simulate;
pub mod state;
pub mod step;
pub mod suspension;
#[cfg(test)]
mod tests;
pub mod voidage;

pub use instruments::{initial_bulb_profile, read_instruments, InstrumentSet};
pub use observer::Observer;
pub use setup::{setup, setup_of, Setup};
pub use simulate::simulate;
pub use state::{band_mass_fractions, State, PICTURE_BANDS};

use crate::checkpoint::Timer;
use crate::error::Error;
use crate::io::Outputs;
use crate::scenario::SedimentationSpec;
use crate::scenes::{Prepared, RunContext, SceneReport};
use output::Recorded;
// Re-exported for the unit tests only.
#[cfg(test)]
pub(crate) use observer::OnRecord;
#[cfg(test)]
pub(crate) use setup::{
    limiting_diameter_m, GrainContacts, CONTACT_FILM_CHANGE_PER_STEP, CONTACT_TRAVEL_PER_SUBSTEP,
};
#[cfg(test)]
pub(crate) use state::ContactStats;

/// Runs a sedimentation scenario (its common part and its spec `spec`, nothing else of it) and
/// adds its outputs to `out`: `profiles.csv`, `bed.csv`, `max_diameter.csv`, `snapshots/`,
/// `summary.csv` and the instruments' tables and charts (see the module doc). With
/// checkpoints in `ctx` it saves its state and what it recorded every period and when
/// interrupted (part `state`, see [`crate::checkpoint`]); with `ctx.resume` it continues from
/// the saved state. An interrupted run adds what it did and reports `interrupted`.
pub fn run(
    p: &Prepared,
    spec: &SedimentationSpec,
    out: &mut Outputs,
    ctx: &RunContext,
) -> Result<SceneReport, Error> {
    let sm = &spec.sample;
    let setup = setup_of(p, spec);
    let c = &setup.common;
    let instruments = InstrumentSet::new(&setup);
    let saved = match (&ctx.checkpoints, ctx.resume) {
        (Some(ck), true) => ck.load::<(State, Recorded)>(&c.name, "state")?,
        _ => None,
    };
    if let (Some(ck), Some((st, _))) = (&ctx.checkpoints, &saved) {
        check_saved(st, &setup, ck.dir())?;
    }
    let (start, recorded) = saved.unwrap_or_else(|| {
        let recorded = Recorded {
            bulb: initial_bulb_profile(&instruments, &setup),
            ..Recorded::default()
        };
        (State::initial(&setup), recorded)
    });
    let t0 = std::time::Instant::now();
    let mut obs = RunObserver {
        setup: &setup,
        instruments: &instruments,
        layers: sm.layers,
        grain_density_kg_m3: sm.density_kg_m3,
        rec: recorded,
        ctx,
        name: &c.name,
        timer: ctx.checkpoints.as_ref().map(|ck| ck.timer()),
        save_err: None,
        bar: crate::progress::bar(
            c.time.end_s.ceil() as u64,
            &c.name,
            "s simulated,",
            ctx.quiet,
        ),
        t0,
        save_due: false,
    };
    let st = simulate(&setup, start, &instruments.all_times_s(), &mut obs);
    obs.bar.finish_and_clear();
    if let Some(u) = st.fault.clone() {
        // Nothing to resume from a run that went unstable.
        return Err(Error::Unstable(p.path.clone(), u));
    }
    if st.interrupted {
        obs.save(&st);
    }
    if let Some(e) = obs.save_err.take() {
        return Err(Error::Io(p.path.clone(), e));
    }
    let wall = t0.elapsed().as_secs_f64();
    output::write_all(out, &setup, &st, obs.rec, wall).map_err(|e| Error::Io(p.path.clone(), e))
}

/// Refuses a saved state `st` (in the checkpoint folder `dir`) whose per-grain arrays do not
/// match the grains of `setup` (one entry per grain; horizontal positions none or one per grain).
fn check_saved(st: &State, setup: &Setup, dir: &std::path::Path) -> Result<(), Error> {
    let n = setup.grains.len();
    let ok = [st.y_m.len(), st.velocity_m_s.len(), st.settled.len()]
        .iter()
        .all(|&k| k == n)
        && (st.x_m.is_empty() || st.x_m.len() == n);
    if ok {
        return Ok(());
    }
    Err(Error::bad_input(
        dir,
        None,
        format!(
            "the saved state holds {} grains, the scenario makes {n}; delete the checkpoint to start afresh",
            st.y_m.len()
        ),
    ))
}

/// The observer of [`run`]: records profiles, pictures, snapshots and instrument readings, moves
/// the progress bar and saves checkpoints when due.
struct RunObserver<'a> {
    setup: &'a Setup,
    instruments: &'a InstrumentSet,
    layers: usize,
    grain_density_kg_m3: f64,
    rec: Recorded,
    ctx: &'a RunContext,
    name: &'a str,
    timer: Option<Timer>,
    save_err: Option<std::io::Error>,
    bar: indicatif::ProgressBar,
    t0: std::time::Instant,
    /// A checkpoint is due at the next [`Observer::step`] (set by [`Observer::wants_grains`]).
    save_due: bool,
}

impl RunObserver<'_> {
    /// Saves the state and the records (with checkpoints on); keeps the first error.
    fn save(&mut self, st: &State) {
        if let Some(c) = &self.ctx.checkpoints {
            if let Err(e) = c.save(self.name, "state", &(st, &self.rec)) {
                self.save_err.get_or_insert(e);
            }
        }
    }
}

impl Observer for RunObserver<'_> {
    fn record(&mut self, st: &State) {
        let pr = state::profile(st, self.setup, self.layers, self.grain_density_kg_m3);
        self.rec.profiles.push(pr);
    }

    fn snapshot(&mut self, st: &State) {
        let bands = band_mass_fractions(st, self.setup, PICTURE_BANDS);
        self.rec.pictures.push((st.time_s, bands));
        self.rec
            .snapshots
            .push(output::Snapshot::of(st, self.setup));
    }

    fn reading(&mut self, st: &State) {
        let r = &mut self.rec;
        r.readings.extend(read_instruments(
            self.instruments,
            st,
            self.setup,
            &mut r.bulb,
        ));
    }

    fn step(&mut self, st: &State) {
        if st.steps.is_multiple_of(256) {
            self.bar.set_position(st.time_s as u64);
            self.bar
                .set_message(crate::progress::step_message(st.steps, self.t0));
        }
        if std::mem::take(&mut self.save_due) {
            self.save(st);
        }
    }

    fn wants_grains(&mut self) -> bool {
        self.save_due = self.timer.as_mut().is_some_and(|t| t.due());
        self.save_due
    }
}
