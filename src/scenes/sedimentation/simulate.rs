//! The step loop of the cylinder, as a short sequence of named stages.

use super::contacts::{ContactStage, StageEnd};
use super::observer::Observer;
use super::schedule::Schedule;
use super::setup::Setup;
use super::state::State;
use super::step::{advance_clock, clock_after, IdealCache, Interval, StepStart, Stepper};
use super::suspension::Suspension;
use super::voidage::VoidageGrid;
use crate::dynamics::Integrator;
use crate::scenario::{SampleSpec, Scenario};
use std::time::Instant;

/// Runs scenario `s` (prepared as `setup`, whose spec gives the `[sample]` settings) from
/// `state` (the initial one, [`State::initial`], or one saved by a checkpoint) to `time.end_s`,
/// landing on every record and snapshot time and on every time of `reading_times_s`, and
/// telling `obs` at each (and after every step). Returns
/// the final state: `interrupted` if a stop was requested (Ctrl-C/SIGTERM; honoured within a
/// step, which is then undone so that the state stays resumable), `fault` if the run went
/// unstable. The same state gives the same continuation, bit for bit: every step depends on the
/// state only (the per-grain updates are independent, the sums serial).
///
/// Each step: schedule (next event) → voidage grid and step size → free update → fault scan →
/// contact stage (pairs, clusters, their solve) → deposition → clock and events.
///
/// In ideal-Stokes with the exponential integrator, the grains do not interact and every step
/// size is known in advance, so the steps up to the next event are made at once, grain by grain
/// ([`Stepper::ideal_interval`], the same arithmetic in the same order: the same result bit for
/// bit); `obs` is then told once per interval, at its end.
///
/// In full physics without contacts (the default), the suspended grains are stepped packed
/// apart from the state ([`Suspension`], the loop of `Packed::simulate`): the same steps, the
/// same result bit for bit, with the grains' heights and speeds reaching the state only when
/// something reads them there (events, checkpoints, a fault, the end).
pub fn simulate(
    s: &Scenario,
    setup: &Setup,
    state: State,
    reading_times_s: &[f64],
    obs: &mut impl Observer,
) -> State {
    let sm: &SampleSpec = &setup.spec.sample;
    let mut st = state;
    st.interrupted = false;
    let schedule = Schedule::new(s, sm, reading_times_s);
    let stepper = Stepper::new(s, sm, setup, &st);
    let mut grid = voidage_grid(setup, &stepper, &st);
    let with_contacts = !stepper.ideal && sm.contacts;
    if !stepper.ideal && !with_contacts {
        if let Some((suspension, suspect)) = Suspension::new(&st, &grid, &stepper, setup) {
            let run = Packed {
                setup,
                schedule: &schedule,
                stepper: &stepper,
            };
            return run.simulate(st, suspension, suspect, &mut grid, obs);
        }
    }
    let mut contacts = ContactStage::new(sm, setup, &stepper);
    let mut start = StepStart::default();
    let mut by_interval = stepper.ideal && stepper.integrator == Integrator::Exponential;
    let (speeds, volumes) = if stepper.ideal {
        (Vec::new(), Vec::new())
    } else {
        (stepper.stokes_speeds_m_s(&st), grid.grain_volumes_m3(&st))
    };
    let cache = if by_interval {
        IdealCache::new(&stepper, &st)
    } else {
        IdealCache::default()
    };
    let mut runs: Vec<(f64, u64)> = Vec::new();
    // The grains the per-step passes visit: every grain (without contacts, full physics steps
    // the suspended grains packed instead, above).
    let active: Vec<usize> = (0..st.grains.len()).collect();
    // The largest suspended speed after the last deposition (full physics), for the next step.
    let mut vmax: Option<f64> = None;
    while schedule.running(&st) {
        if crate::interrupt::requested() {
            st.interrupted = true;
            break;
        }
        let next_event = schedule.next_event_s(&st);
        if by_interval {
            interval_runs(&stepper, &schedule, st.time_s, next_event, &mut runs);
            let t0 = Instant::now();
            start.capture_all(&st);
            let (end, moved) = stepper.ideal_interval(&mut st, setup, &runs, &cache);
            st.stages.free_update_s += t0.elapsed().as_secs_f64();
            match end {
                Interval::Done => {
                    st.stages.grain_steps += moved;
                    let t0 = Instant::now();
                    for &(dt, count) in &runs {
                        for _ in 0..count {
                            advance_clock(&mut st, dt, next_event);
                        }
                    }
                    schedule.dispatch(&mut st, obs);
                    obs.wants_grains();
                    obs.step(&st);
                    st.stages.deposit_events_s += t0.elapsed().as_secs_f64();
                    continue;
                }
                Interval::Interrupted => {
                    start.rewind_all(&mut st);
                    st.interrupted = true;
                    break;
                }
                Interval::Fault => {
                    // Redo the interval step by step: the fault scan reports the grain.
                    start.rewind_all(&mut st);
                    by_interval = false;
                }
            }
        }
        let t0 = Instant::now();
        let dt = match vmax {
            Some(v) => stepper.step_with_vmax_s(st.time_s, next_event, v),
            None => stepper.step_size_s(&st, next_event, &speeds),
        };
        let t1 = Instant::now();
        st.stages.step_size_s += (t1 - t0).as_secs_f64();
        if !stepper.ideal {
            grid.fill(&st, &volumes, &active);
        }
        start.capture(&st);
        let t2 = Instant::now();
        st.stages.voidage_s += (t2 - t1).as_secs_f64();
        let Some((moved, suspect)) = stepper.free_update(&mut st, setup, &grid, dt, &active) else {
            // Interrupted within the step: back to its start, which stays resumable.
            start.rewind(&mut st);
            st.interrupted = true;
            break;
        };
        st.stages.grain_steps += moved;
        let t3 = Instant::now();
        st.stages.free_update_s += (t3 - t2).as_secs_f64();
        // Faults of the free update (the contact solve's clusters the engine checks itself),
        // tested grain by grain in the update; the scan names the first.
        if suspect {
            if let Some(u) = stepper.grain_fault(&st, setup, dt, Some(stepper.speed_bound_m_s)) {
                st.fault = Some(u);
                break;
            }
        }
        let t4 = Instant::now();
        st.stages.fault_scan_s += (t4 - t3).as_secs_f64();
        if with_contacts {
            match contacts.run(&mut st, &start, &grid, dt) {
                StageEnd::Interrupted => {
                    st.interrupted = true;
                    break;
                }
                // A small grain squeezed by a large one may briefly move faster than the free
                // bound (its speed is the cluster engine's to check).
                StageEnd::Done { moved: true } => {
                    if let Some(u) = stepper.grain_fault(&st, setup, dt, None) {
                        st.fault = Some(u);
                        break;
                    }
                }
                StageEnd::Done { moved: false } => {}
            }
        }
        let t5 = Instant::now();
        st.stages.contacts_s += (t5 - t4).as_secs_f64();
        if stepper.ideal {
            stepper.deposit(&mut st, &active);
        } else {
            vmax = Some(stepper.deposit_vmax(&mut st, &speeds, &active));
        }
        advance_clock(&mut st, dt, next_event);
        schedule.dispatch(&mut st, obs);
        obs.wants_grains();
        obs.step(&st);
        st.stages.deposit_events_s += t5.elapsed().as_secs_f64();
    }
    st
}

/// The voidage grid of a run of `setup` with the step constants `stepper`, from `st` (its
/// grains' terminal-state tables).
fn voidage_grid(setup: &Setup, stepper: &Stepper, st: &State) -> VoidageGrid {
    let sm = &setup.spec.sample;
    VoidageGrid::new(
        setup,
        sm.voidage_cell_m,
        stepper.ideal,
        stepper.fluid_density_kg_m3,
    )
    .with_hindered(sm.hindered)
    .with_terminal_tables(st, stepper.grain_density_kg_m3, stepper.gravity_m_s2)
}

/// The step loop of full physics without contacts, on the suspended grains packed in a
/// [`Suspension`]: the same steps as the loop of [`simulate`], with the same arithmetic on the
/// same grains in the same order (the same result, bit for bit), but each pass streams through
/// the suspended grains only, and their heights and speeds reach the state only when something
/// reads them there. One step of 10⁷ grains takes well under a second, so an interrupt request
/// is honoured between steps (nothing to undo).
struct Packed<'a> {
    setup: &'a Setup,
    schedule: &'a Schedule,
    stepper: &'a Stepper,
}

impl Packed<'_> {
    /// Runs from `st`, whose suspended grains are `sus` (`suspect`: a grain of `st` fails the
    /// fault test already), with the voidage grid `grid`, telling `obs` as [`simulate`] does.
    fn simulate(
        &self,
        mut st: State,
        mut sus: Suspension,
        suspect: bool,
        grid: &mut VoidageGrid,
        obs: &mut impl Observer,
    ) -> State {
        let (setup, schedule, stepper) = (self.setup, self.schedule, self.stepper);
        let mut vmax = sus.vmax_m_s();
        // A settled grain fails the fault test: the next free update's scan reports it.
        let mut pending = suspect;
        while schedule.running(&st) {
            if crate::interrupt::requested() {
                st.interrupted = true;
                break;
            }
            let next_event = schedule.next_event_s(&st);
            let t0 = Instant::now();
            let dt = stepper.step_with_vmax_s(st.time_s, next_event, vmax);
            sus.fill(grid);
            let t1 = Instant::now();
            st.stages.voidage_s += (t1 - t0).as_secs_f64();
            let (moved, bad) = sus.free_update(stepper, grid, setup, st.bed_height_m, dt);
            st.stages.grain_steps += moved;
            let t2 = Instant::now();
            st.stages.free_update_s += (t2 - t1).as_secs_f64();
            if bad || pending {
                sus.write_back(&mut st);
                if let Some(u) = stepper.grain_fault(&st, setup, dt, Some(stepper.speed_bound_m_s))
                {
                    st.fault = Some(u);
                    break;
                }
            }
            let t3 = Instant::now();
            st.stages.fault_scan_s += (t3 - t2).as_secs_f64();
            (vmax, pending) = sus.deposit_vmax(&mut st, stepper, setup);
            advance_clock(&mut st, dt, next_event);
            if schedule.due(&st) {
                sus.write_back(&mut st);
            }
            schedule.dispatch(&mut st, obs);
            if obs.wants_grains() {
                sus.write_back(&mut st);
            }
            obs.step(&st);
            st.stages.deposit_events_s += t3.elapsed().as_secs_f64();
        }
        sus.write_back(&mut st);
        st
    }
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
