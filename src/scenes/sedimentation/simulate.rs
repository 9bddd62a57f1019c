//! The step loop of the cylinder, as a short sequence of named stages.

use super::contacts::{ContactStage, StageEnd};
use super::observer::Observer;
use super::schedule::Schedule;
use super::setup::Setup;
use super::state::{Laps, Stage, State};
use super::step::{advance_clock, clock_after, IdealCache, Interval, StepStart, Stepper};
use super::suspension::Suspension;
use super::voidage::VoidageGrid;
use crate::dynamics::Integrator;

/// Runs the scenario prepared as `setup` (its common part and its spec's `[sample]` settings) from
/// `state` (the initial one, [`State::initial`], or one saved by a checkpoint) to `time.end_s`,
/// landing on every record and snapshot time and on every time of `reading_times_s`, and
/// telling `obs` at each (and after every step). Returns
/// the final state: `interrupted` if a stop was requested (Ctrl-C/SIGTERM; honoured within a
/// step, which is then undone so that the state stays resumable), `fault` if the run went
/// unstable. The same state gives the same continuation, bit for bit: every step depends on the
/// state only (the per-grain updates are independent, the sums serial).
///
/// Each step: schedule (next event) → voidage grid and step size → free update → fault scan →
/// contact stage (pairs, clusters, their solve) → deposition → clock and events. The free
/// update of every grain is that of [`super::step::kernel`]; the loop that visits the grains
/// follows the run's modes ([`StepLoop::Chosen`]):
///
/// - full physics without contacts (the default): the suspended grains are stepped packed apart
///   from the state ([`Suspension`]), their heights and speeds reaching the state only when
///   something reads them there (events, checkpoints, a fault, the end);
/// - ideal Stokes with the exponential integrator: the grains do not interact and every step
///   size is known in advance, so the steps up to the next event are made at once, grain by
///   grain ([`Stepper::ideal_interval`]); `obs` is then told once per interval, at its end;
/// - otherwise (contacts, other integrators in ideal Stokes), every grain of the state at every
///   step ([`StepLoop::PerGrain`]).
///
/// Every loop gives the same result, bit for bit, where more than one applies.
pub fn simulate(
    setup: &Setup,
    state: State,
    reading_times_s: &[f64],
    obs: &mut impl Observer,
) -> State {
    simulate_on(StepLoop::Chosen, setup, state, reading_times_s, obs)
}

/// The loop that visits the grains at each step ([`simulate_on`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepLoop {
    /// The loop the run's modes call for (see [`simulate`]).
    Chosen,
    /// Every grain of the state at every step, whatever the modes: the loop the others must
    /// agree with (runs with contacts take it anyway).
    #[cfg_attr(not(test), allow(dead_code))] // chosen by the unit tests only
    PerGrain,
    /// The packed loop of full physics without contacts with every path taken however few the
    /// grains ([`Suspension::every_path`]: tables per cell, parallel deposition): they must
    /// agree with the per-grain loop too.
    #[cfg_attr(not(test), allow(dead_code))] // chosen by the unit tests only
    PackedEveryPath,
}

/// [`simulate`], the grains visited by the loop `step_loop`.
pub fn simulate_on(
    step_loop: StepLoop,
    setup: &Setup,
    state: State,
    reading_times_s: &[f64],
    obs: &mut impl Observer,
) -> State {
    let sm = &setup.spec.sample;
    let mut st = state;
    st.interrupted = false;
    let stepper = Stepper::new(setup);
    let run = Run {
        setup,
        schedule: &Schedule::new(setup, reading_times_s),
        stepper: &stepper,
    };
    let mut grid = voidage_grid(setup, &stepper);
    let every = step_loop == StepLoop::PackedEveryPath;
    let chosen = step_loop == StepLoop::Chosen || every;
    if chosen && !stepper.ideal && !sm.contacts {
        if let Some((mut suspension, suspect)) = Suspension::new(&mut st, &grid, &stepper, setup) {
            if every {
                suspension.every_path();
            }
            return run.packed(st, suspension, suspect, &mut grid, obs);
        }
    }
    if chosen && stepper.ideal && stepper.integrator == Integrator::Exponential {
        match run.intervals(st, obs) {
            (st, Interval::Fault) => run.per_grain(st, &mut grid, obs),
            (st, _) => st,
        }
    } else {
        run.per_grain(st, &mut grid, obs)
    }
}

/// The voidage grid of a run of `setup` with the step constants `stepper` (with its grains'
/// terminal-state tables).
pub(super) fn voidage_grid(setup: &Setup, stepper: &Stepper) -> VoidageGrid {
    let sm = &setup.spec.sample;
    VoidageGrid::new(
        setup,
        sm.voidage_cell_m,
        stepper.ideal,
        stepper.fluid_density_kg_m3,
    )
    .with_hindered(sm.hindered)
    .with_terminal_tables(
        &setup.grains,
        stepper.grain_density_kg_m3,
        stepper.gravity_m_s2,
    )
}

/// What every loop of a run reads: the cylinder, the events and the step constants.
struct Run<'a> {
    setup: &'a Setup,
    schedule: &'a Schedule,
    stepper: &'a Stepper,
}

impl Run<'_> {
    /// Ends a step of `dt_s` towards `next_event_s`: the clock, the events due, then `obs` told
    /// of the step. With a packed suspension `sus`, the heights of its grains are written into
    /// `st` for the events ([`Suspension::write_back`]), and for a step whose observer wants the
    /// grains (a checkpoint) their speeds too, for that call only (the state's speeds are empty
    /// again after it: [`Suspension::new`]).
    fn end_step(
        &self,
        st: &mut State,
        dt_s: f64,
        next_event_s: f64,
        obs: &mut impl Observer,
        sus: Option<&Suspension>,
    ) {
        advance_clock(st, dt_s, next_event_s);
        if let (Some(sus), true) = (sus, self.schedule.due(st)) {
            sus.write_back(st);
        }
        self.schedule.dispatch(st, obs);
        let speeds = match (sus, obs.wants_grains()) {
            (Some(sus), true) => {
                sus.write_back(st);
                st.velocity_m_s = sus.speeds_m_s(st.len());
                true
            }
            _ => false,
        };
        obs.step(st);
        if speeds {
            st.velocity_m_s = Vec::new();
        }
    }

    /// The step loop of full physics without contacts, on the suspended grains packed in a
    /// [`Suspension`] (`sus`; `suspect`: a grain of `st` fails the fault test already), with the
    /// voidage grid `grid`: each pass streams through the suspended grains only, and their
    /// heights reach the state only when something reads them there, and their speeds only at
    /// checkpoints, a fault scan and the end (`st.velocity_m_s` is empty in between:
    /// [`Suspension::new`]). One step of 10⁷ grains takes well under a second, so an interrupt
    /// request is honoured between steps (nothing to undo).
    fn packed(
        &self,
        mut st: State,
        mut sus: Suspension,
        suspect: bool,
        grid: &mut VoidageGrid,
        obs: &mut impl Observer,
    ) -> State {
        let (setup, stepper) = (self.setup, self.stepper);
        let mut vmax = sus.vmax_m_s();
        // A settled grain fails the fault test: the next free update's scan reports it.
        let mut pending = suspect;
        while self.schedule.running(&st) {
            if crate::interrupt::requested() {
                st.interrupted = true;
                break;
            }
            let next_event = self.schedule.next_event_s(&st);
            let mut laps = Laps::start();
            let dt = stepper.step_with_vmax_s(st.time_s, next_event, vmax);
            sus.fill(grid);
            laps.lap(&mut st.stages, Stage::Voidage);
            let (moved, bad) = sus.free_update(stepper, grid, setup, st.bed_height_m, dt);
            st.stages.grain_steps += moved;
            laps.lap(&mut st.stages, Stage::FreeUpdate);
            if bad || pending {
                sus.write_back(&mut st);
                st.velocity_m_s = sus.speeds_m_s(st.len());
                let fault = stepper.grain_fault(&st, setup, dt, Some(stepper.speed_bound_m_s));
                st.velocity_m_s = Vec::new();
                if let Some(u) = fault {
                    st.fault = Some(u);
                    break;
                }
            }
            laps.lap(&mut st.stages, Stage::FaultScan);
            (vmax, pending) = sus.deposit_vmax(&mut st, stepper, setup);
            self.end_step(&mut st, dt, next_event, obs, Some(&sus));
            laps.lap(&mut st.stages, Stage::DepositEvents);
        }
        sus.into_state(&mut st);
        st
    }

    /// The step loop of ideal Stokes with the exponential integrator, by intervals between two
    /// events ([`Stepper::ideal_interval`]); `obs` is told once per interval, at its end.
    /// Returns the state and how the last interval ended: on [`Interval::Fault`] the state is
    /// at the start of that interval, for the per-grain loop to redo it step by step (its fault
    /// scan reports the grain).
    fn intervals(&self, mut st: State, obs: &mut impl Observer) -> (State, Interval) {
        let cache = IdealCache::new(self.stepper, &self.setup.grains);
        let mut start = StepStart::default();
        let mut runs: Vec<(f64, u64)> = Vec::new();
        while self.schedule.running(&st) {
            if crate::interrupt::requested() {
                st.interrupted = true;
                break;
            }
            let next_event = self.schedule.next_event_s(&st);
            interval_runs(
                self.stepper,
                self.schedule,
                st.time_s,
                next_event,
                &mut runs,
            );
            let mut laps = Laps::start();
            start.capture_all(&st);
            let (end, moved) = self
                .stepper
                .ideal_interval(&mut st, self.setup, &runs, &cache);
            laps.lap(&mut st.stages, Stage::FreeUpdate);
            if end != Interval::Done {
                start.rewind_all(&mut st);
                st.interrupted = end == Interval::Interrupted;
                return (st, end);
            }
            st.stages.grain_steps += moved;
            for &(dt, count) in &runs {
                for _ in 0..count {
                    advance_clock(&mut st, dt, next_event);
                }
            }
            self.schedule.dispatch(&mut st, obs);
            obs.wants_grains();
            obs.step(&st);
            laps.lap(&mut st.stages, Stage::DepositEvents);
        }
        (st, Interval::Done)
    }

    /// The step loop over every grain of the state ([`StepLoop::PerGrain`]), with the contact
    /// stage if the run has contacts, and the voidage grid `grid`.
    fn per_grain(&self, mut st: State, grid: &mut VoidageGrid, obs: &mut impl Observer) -> State {
        let (setup, stepper) = (self.setup, self.stepper);
        let sm = &setup.spec.sample;
        let mut contacts =
            (!stepper.ideal && sm.contacts).then(|| ContactStage::new(sm, setup, stepper));
        let (speeds, volumes) = if stepper.ideal {
            (Vec::new(), Vec::new())
        } else {
            (
                stepper.stokes_speeds_m_s(&setup.grains),
                grid.grain_volumes_m3(&setup.grains),
            )
        };
        // The grains the per-step passes visit: every grain.
        let active: Vec<usize> = (0..st.len()).collect();
        let mut start = StepStart::default();
        // The largest suspended speed (full physics), for the next step.
        let mut vmax = stepper.vmax_m_s(&st, &speeds);
        while self.schedule.running(&st) {
            if crate::interrupt::requested() {
                st.interrupted = true;
                break;
            }
            let next_event = self.schedule.next_event_s(&st);
            let mut laps = Laps::start();
            let dt = stepper.step_with_vmax_s(st.time_s, next_event, vmax);
            laps.lap(&mut st.stages, Stage::StepSize);
            if !stepper.ideal {
                grid.fill(&st, &setup.grains, &volumes, &active);
            }
            start.capture(&st);
            laps.lap(&mut st.stages, Stage::Voidage);
            let step = Move {
                grid,
                dt_s: dt,
                active: &active,
                start: &start,
            };
            if !self.move_grains(&mut st, &step, contacts.as_mut(), &mut laps) {
                break;
            }
            vmax = stepper.deposit_vmax(&mut st, &setup.grains, &speeds, &active);
            self.end_step(&mut st, dt, next_event, obs, None);
            laps.lap(&mut st.stages, Stage::DepositEvents);
        }
        st
    }

    /// The free update of the step `m` of the per-grain loop, its fault scan and (with
    /// `contacts`) the contact stage, each lap timed in `laps`. False if the run stops here:
    /// interrupted (the step undone) or in a fault (reported in `st`).
    fn move_grains(
        &self,
        st: &mut State,
        m: &Move,
        contacts: Option<&mut ContactStage>,
        laps: &mut Laps,
    ) -> bool {
        let (setup, stepper, dt) = (self.setup, self.stepper, m.dt_s);
        let Some((moved, suspect)) = stepper.free_update(st, setup, m.grid, dt, m.active) else {
            // Interrupted within the step: back to its start, which stays resumable.
            m.start.rewind(st);
            st.interrupted = true;
            return false;
        };
        st.stages.grain_steps += moved;
        laps.lap(&mut st.stages, Stage::FreeUpdate);
        // Faults of the free update (the contact solve's clusters the engine checks itself),
        // tested grain by grain in the update; the scan names the first.
        if suspect {
            st.fault = stepper.grain_fault(st, setup, dt, Some(stepper.speed_bound_m_s));
            if st.fault.is_some() {
                return false;
            }
        }
        laps.lap(&mut st.stages, Stage::FaultScan);
        if let Some(contacts) = contacts {
            match contacts.run(st, &setup.grains, m.start, m.grid, dt) {
                StageEnd::Interrupted => {
                    st.interrupted = true;
                    return false;
                }
                // A small grain squeezed by a large one may briefly move faster than the free
                // bound (its speed is the cluster engine's to check).
                StageEnd::Done { moved: true } => {
                    st.fault = stepper.grain_fault(st, setup, dt, None);
                    if st.fault.is_some() {
                        return false;
                    }
                }
                StageEnd::Done { moved: false } => {}
            }
        }
        laps.lap(&mut st.stages, Stage::Contacts);
        true
    }
}

/// One step of the per-grain loop: the voidage grid, the step (s), the grains visited and
/// their state at the step's start.
struct Move<'a> {
    grid: &'a VoidageGrid,
    dt_s: f64,
    active: &'a [usize],
    start: &'a StepStart,
}

/// The steps from `t_s` up to the event `next_event_s` (or the end of the run), as the step loop
/// of [`simulate`] would take them, as runs of equal steps `(dt, count)` into `runs`.
fn interval_runs(
    stepper: &Stepper,
    schedule: &Schedule,
    t_s: f64,
    next_event_s: f64,
    runs: &mut Vec<(f64, u64)>,
) {
    runs.clear();
    let mut t = t_s;
    loop {
        let dt = stepper.clock_step_s(t, next_event_s);
        match runs.last_mut() {
            Some((d, c)) if *d == dt => *c += 1,
            _ => runs.push((dt, 1)),
        }
        t = clock_after(t, dt, next_event_s);
        if Schedule::reached(next_event_s, t) || !schedule.running_at(t) {
            break;
        }
    }
}
