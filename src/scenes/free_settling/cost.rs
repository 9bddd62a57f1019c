//! The cost of a free-settling or drop run ([`crate::scenes::cost`]): each sphere alone over
//! `time.end_s / time.dt_s` steps on its engine, with its time series.

use crate::scenario::{Common, Engine};
use crate::scenes::cost::{Load, BODY_DISK_BYTES, FREE_BODY_STEP_S, RAPIER_BODY_BYTES};
use crate::scenes::cost::{LOWER_IT, RAPIER_BODY_STEP_S, STEP_HINT};

/// One row of `timeseries.csv` (free settling and drops): in memory (a time, a depth, a speed and
/// two optional analytic values, plus vector growth) and on disk (CSV text, measured on the
/// scenarios of `scenarios/`: 53–110 bytes), bytes.
const TIMESERIES_ROW_MEMORY_BYTES: f64 = 64.0;
const TIMESERIES_ROW_DISK_BYTES: f64 = 100.0;
/// Time-series rows per body without `record.every_s` (as the free-settling scene records).
const DEFAULT_ROWS_PER_BODY: f64 = 2000.0;
/// The load of a free-settling or drop scenario of `cases` sphere cases (each sphere once per
/// fall height of a drop: each runs alone).
pub fn load(c: &Common, cases: usize) -> Load {
    let steps = c.time.end_s / c.time.dt_s;
    let bodies = cases.max(1) as f64;
    let rows = bodies * rows_per_body(c, steps);
    let key = if rows > 0.0 {
        if cases > 1 {
            "spheres"
        } else {
            "record.every_s"
        }
    } else {
        "time.dt_s"
    };
    Load {
        steps,
        bodies,
        body_step_s: if c.engine == Engine::Rapier {
            RAPIER_BODY_STEP_S
        } else {
            FREE_BODY_STEP_S
        },
        body_bytes: RAPIER_BODY_BYTES,
        rows,
        row_bytes: TIMESERIES_ROW_MEMORY_BYTES,
        disk_bytes: rows * TIMESERIES_ROW_DISK_BYTES + bodies * BODY_DISK_BYTES,
        key,
        memory_hint: LOWER_IT,
        wall: ("time.dt_s", STEP_HINT),
    }
}

/// Time-series rows of one body of a free-settling or drop scenario, as the scene records them:
/// every `record.every_s`, or every step up to [`DEFAULT_ROWS_PER_BODY`] rows.
fn rows_per_body(c: &Common, steps: f64) -> f64 {
    if !c.record.timeseries {
        return 0.0;
    }
    let steps = steps.round().max(1.0);
    let every = match c.record.every_s {
        Some(e) => (e / c.time.dt_s).round().max(1.0),
        None => (steps / DEFAULT_ROWS_PER_BODY).floor().max(1.0),
    };
    (steps / every).floor() + 1.0
}
