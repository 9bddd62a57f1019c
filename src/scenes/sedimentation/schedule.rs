//! The times a run lands on exactly: records, snapshots and instrument readings, with their
//! cursors (saved in the state, so that a resumed run continues where it stopped).

use super::observer::Observer;
use super::setup::{default_record_times, Setup};
use super::state::State;

/// Sorted record, snapshot and reading times, and the end time, s.
#[derive(Clone, Debug)]
pub struct Schedule {
    records: Vec<f64>,
    snapshots: Vec<f64>,
    readings: Vec<f64>,
    end_s: f64,
}

impl Schedule {
    /// The times of the run of `setup` (its `[sample]` times and its end time) and the
    /// instruments' `reading_times_s`.
    pub fn new(setup: &Setup, reading_times_s: &[f64]) -> Self {
        let (sm, end_s) = (&setup.spec.sample, setup.common.time.end_s);
        let mut records: Vec<f64> = if sm.record_times_s.is_empty() {
            default_record_times(end_s)
        } else {
            sm.record_times_s.clone()
        };
        records.sort_by(f64::total_cmp);
        let mut snapshots = sm.snapshot_times_s.clone();
        snapshots.sort_by(f64::total_cmp);
        let mut readings = reading_times_s.to_vec();
        readings.sort_by(f64::total_cmp);
        readings.dedup();
        Self {
            records,
            snapshots,
            readings,
            end_s,
        }
    }

    /// True while `st` has not reached the end time.
    pub fn running(&self, st: &State) -> bool {
        self.running_at(st.time_s)
    }

    /// True while time `t_s` has not reached the end time.
    pub fn running_at(&self, t_s: f64) -> bool {
        t_s < self.end_s * (1.0 - 1e-12)
    }

    /// True when an event at `event_s` is reached at time `t_s` (within a relative 1e-12).
    pub fn reached(event_s: f64, t_s: f64) -> bool {
        event_s <= t_s * (1.0 + 1e-12)
    }

    /// The next time to land on from the cursors of `st`: the earliest pending record, snapshot
    /// or reading, or the end.
    pub fn next_event_s(&self, st: &State) -> f64 {
        let [ti, si, ri] = st.cursor;
        let at = |v: &[f64], i: usize| v.get(i).copied().unwrap_or(f64::INFINITY);
        at(&self.records, ti)
            .min(at(&self.snapshots, si))
            .min(at(&self.readings, ri))
            .min(self.end_s)
    }

    /// True when `st` has reached its next event ([`Schedule::next_event_s`], the end included):
    /// [`Schedule::dispatch`] will hand it to the observer (or the run ends).
    pub fn due(&self, st: &State) -> bool {
        Self::reached(self.next_event_s(st), st.time_s)
    }

    /// Hands `st` to `obs` for every event it has reached, in the order records, snapshots,
    /// readings, and advances the cursors of `st`.
    pub fn dispatch(&self, st: &mut State, obs: &mut impl Observer) {
        let reached = Self::reached;
        let [mut ti, mut si, mut ri] = st.cursor;
        while ti < self.records.len() && reached(self.records[ti], st.time_s) {
            obs.record(st);
            ti += 1;
        }
        while si < self.snapshots.len() && reached(self.snapshots[si], st.time_s) {
            obs.snapshot(st);
            si += 1;
        }
        while ri < self.readings.len() && reached(self.readings[ri], st.time_s) {
            obs.reading(st);
            ri += 1;
        }
        st.cursor = [ti, si, ri];
    }
}
