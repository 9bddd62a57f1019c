//! The step loop of the cylinder, as a short sequence of named stages.

use super::contacts::{ContactStage, StageEnd};
use super::observer::Observer;
use super::schedule::Schedule;
use super::setup::Setup;
use super::state::State;
use super::step::{advance_clock, StepStart, Stepper};
use super::voidage::VoidageGrid;
use crate::scenario::{SampleSpec, Scenario};

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
    let mut grid = VoidageGrid::new(
        setup,
        sm.voidage_cell_m,
        stepper.ideal,
        stepper.fluid_density_kg_m3,
    )
    .with_hindered(sm.hindered);
    let with_contacts = !stepper.ideal && sm.contacts;
    let mut contacts = ContactStage::new(sm, setup, &stepper);
    let mut start = StepStart::default();
    while schedule.running(&st) {
        if crate::interrupt::requested() {
            st.interrupted = true;
            break;
        }
        let next_event = schedule.next_event_s(&st);
        let dt = stepper.step_size_s(&st, next_event);
        if !stepper.ideal {
            grid.fill(&st);
        }
        start.capture(&st);
        if !stepper.free_update(&mut st, &grid, dt) {
            // Interrupted within the step: back to its start, which stays resumable.
            start.rewind(&mut st);
            st.interrupted = true;
            break;
        }
        // Faults of the free update (the contact solve's clusters the engine checks itself).
        if let Some(u) = stepper.grain_fault(&st, setup, dt, Some(stepper.speed_bound_m_s)) {
            st.fault = Some(u);
            break;
        }
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
        stepper.deposit(&mut st);
        advance_clock(&mut st, dt, next_event);
        schedule.dispatch(&mut st, obs);
        obs.step(&st);
    }
    st
}
