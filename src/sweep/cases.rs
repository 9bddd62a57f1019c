//! Runs the cases of a sweep grid in parallel into rows: the one loop of every dt sweep (the
//! command line's, its shards', the library's [`super::sweep`] and the benchmark's).

use super::plan::{Case, Plan};
use super::table::{finish, Row};
use super::targets::Target;
use crate::error::Error;
use crate::scenes::Prepared;

/// Runs `cases` of a sweepable scenario (in parallel) and returns their rows, without
/// `error_vs_finest`; a bad input (exit 2) for other kinds.
pub(crate) fn run_cases(p: &Prepared, cases: &[Case]) -> Result<Vec<Row>, Error> {
    run_cases_with(p, cases, &|| {})
}

/// As [`run_cases`], calling `done` after each case (for a progress bar).
pub(crate) fn run_cases_with(
    p: &Prepared,
    cases: &[Case],
    done: &(dyn Fn() + Sync),
) -> Result<Vec<Row>, Error> {
    use rayon::prelude::*;
    let target = Target::of(p)?;
    let rows: Vec<Row> = cases
        .par_iter()
        .map(|c| {
            // Ctrl-C/SIGTERM: no new case starts, and the running ones stop within their
            // interrupt checks (about a millisecond of work on the free engine).
            if crate::interrupt::requested() {
                return Vec::new();
            }
            let rows = target.run_case(p, c);
            done();
            rows
        })
        .flatten()
        .collect();
    if crate::interrupt::requested() {
        return Err(Error::InterruptedUnwritten(p.path.clone()));
    }
    Ok(rows)
}

/// Runs the plan's cases of one scenario: finished rows (see [`finish`]) for a whole grid, the
/// unfinished rows of the shard for a sharded plan.
pub(crate) fn run(p: &Prepared, plan: &Plan, done: &(dyn Fn() + Sync)) -> Result<Vec<Row>, Error> {
    let mut rows = run_cases_with(p, &plan.cases_to_run(), done)?;
    if plan.shard.is_none() {
        finish(&mut rows);
    }
    Ok(rows)
}
