//! What a sedimentation run tells its caller while it steps: the records, snapshots and
//! instrument readings it lands on, and every step (progress, checkpoints).

use super::state::State;

/// Receives the state of a run at its events. Every method does nothing by default.
pub trait Observer {
    /// At every record time (`sample.record_times_s`, or the defaults).
    fn record(&mut self, _st: &State) {}
    /// At every snapshot time (`sample.snapshot_times_s`).
    fn snapshot(&mut self, _st: &State) {}
    /// At every instrument reading time passed to [`super::simulate`](fn@super::simulate).
    fn reading(&mut self, _st: &State) {}
    /// After every step, events included (decides itself whether to save a checkpoint).
    fn step(&mut self, _st: &State) {}
    /// Asked before every [`Observer::step`]: whether that call reads the grains of the state
    /// (e.g. to save a checkpoint). When it answers false, the heights and speeds of the grains
    /// still suspended in the state passed to `step` may be those of an earlier step (a run
    /// without contacts keeps them elsewhere, [`super::suspension::Suspension`]); its time, step
    /// count and everything else are current. The records, snapshots and readings always get
    /// current heights and settled flags; speeds only when this answers true (a run without
    /// contacts hands the state's speeds to the suspension between those calls).
    fn wants_grains(&mut self) -> bool {
        true
    }
}

/// Observes nothing.
impl Observer for () {
    fn wants_grains(&mut self) -> bool {
        false
    }
}

/// Calls the closure at every record time, and does nothing else.
#[cfg_attr(not(test), allow(dead_code))] // built by the unit tests only
pub struct OnRecord<F: FnMut(&State)>(pub F);

impl<F: FnMut(&State)> Observer for OnRecord<F> {
    fn record(&mut self, st: &State) {
        (self.0)(st)
    }

    fn wants_grains(&mut self) -> bool {
        false
    }
}
