//! A parameter sweep's plan (every point of the grid prepared and validated before any runs),
//! the parallel run of its cases into a [`VaryTable`], and the outputs of a finished table.

use super::chart::{charts, console_lines};
use super::grid::{count, points, Axis, Level, MAX_CASES};
use super::table::VaryTable;
use crate::error::{BadInput, Error};
use crate::io::Outputs;
use crate::run::prepare;
use crate::scenes::Prepared;
use crate::sweep::plan::Case;
use crate::sweep::targets::Target;
use crate::sweep::values::Shard;
use std::path::Path;

/// One case of a parameter sweep: its point (a value per key) and the scenario with those
/// values applied, validated.
#[derive(Clone, Debug)]
pub(crate) struct VaryCase {
    /// The value of each key, in the order of the axes.
    pub point: Vec<Level>,
    /// The scenario with `--set` and the point's values applied.
    pub prepared: Prepared,
}

/// A parameter sweep of one scenario: the axes and the cases this process runs, every case of
/// the grid validated.
#[derive(Clone, Debug)]
pub(crate) struct VaryPlan {
    /// The scenario with `--set` applied, without the varied values.
    pub base: Prepared,
    /// The varied keys and their values.
    pub axes: Vec<Axis>,
    /// The cases to run: the shard's, or every case.
    pub cases: Vec<VaryCase>,
    /// Run only this slice of the grid (cases whose index ≡ I − 1 mod N).
    pub shard: Option<Shard>,
}

impl VaryPlan {
    /// Loads `file` with `set` and plans `axes` on it ([`VaryPlan::build`]), each point loaded
    /// again from the file with `set` and the point's values.
    pub fn new(
        file: &Path,
        set: &[String],
        axes: &[Axis],
        shard: Option<Shard>,
    ) -> Result<Self, Error> {
        let base = prepare(file, None, set)?;
        Self::build(base, axes, shard, |point| {
            prepare(file, None, &[set, point].concat())
        })
    }

    /// Refuses a kind that cannot be swept, a key given twice and a grid over [`MAX_CASES`],
    /// then prepares and validates every point of the grid (`prepare_point` takes the point's
    /// `KEY=VALUE` overrides, applied after the scenario's own): a bad key or an out-of-range
    /// value is a bad input naming the key, the value and the allowed range, before any case
    /// runs.
    pub fn build(
        base: Prepared,
        axes: &[Axis],
        shard: Option<Shard>,
        prepare_point: impl Fn(&[String]) -> Result<Prepared, BadInput>,
    ) -> Result<Self, Error> {
        Target::of(&base)?;
        for (i, a) in axes.iter().enumerate() {
            if axes[..i].iter().any(|b| b.key == a.key) {
                return Err(Error::bad_argument(
                    "--vary",
                    Path::new(&a.key),
                    "this key is varied twice: allowed one --vary per key",
                ));
            }
        }
        let n = count(axes);
        if n > MAX_CASES {
            return Err(Error::bad_argument(
                "--vary",
                &base.path,
                format!("the grid has {n} cases: allowed at most {MAX_CASES} (one run each)"),
            ));
        }
        let mut cases = Vec::new();
        for (i, point) in points(axes).into_iter().enumerate() {
            let ov: Vec<String> = axes
                .iter()
                .zip(&point)
                .map(|(a, v)| format!("{}={}", a.key, v.override_text()))
                .collect();
            let text: Vec<String> = axes
                .iter()
                .zip(&point)
                .map(|(a, v)| format!("{} = {v}", a.key))
                .collect();
            let prepared = prepare_point(&ov).map_err(|e| {
                Error::BadInput(BadInput {
                    message: format!("--vary {}: {}", text.join(", "), e.message),
                    ..e
                })
            })?;
            if shard.is_none_or(|s| i % s.count == s.index - 1) {
                cases.push(VaryCase { point, prepared });
            }
        }
        Ok(Self {
            base,
            axes: axes.to_vec(),
            cases,
            shard,
        })
    }

    /// The varied keys.
    pub fn keys(&self) -> Vec<String> {
        self.axes.iter().map(|a| a.key.clone()).collect()
    }

    /// The output folder's name: `<name>_vary`.
    pub fn folder(&self) -> String {
        format!("{}_vary", self.base.common.name)
    }

    /// The owner of [`VaryPlan::folder`] ([`crate::io::Owner`]).
    pub fn owner(&self) -> crate::io::Owner {
        crate::io::Owner::scenario("sweep --vary", &self.base.common.name)
    }
}

/// Runs the plan's cases (in parallel; `done` after each) into a table. Ctrl-C/SIGTERM: no new
/// case starts, the running ones stop at their next check, and the sweep is an interrupted
/// run with nothing to write.
pub(crate) fn run(plan: &VaryPlan, done: &(dyn Fn() + Sync)) -> Result<VaryTable, Error> {
    use rayon::prelude::*;
    let cases: Vec<(Vec<Level>, Vec<crate::sweep::table::Row>)> = plan
        .cases
        .par_iter()
        .map(|c| {
            if crate::interrupt::requested() {
                return (c.point.clone(), Vec::new());
            }
            let p = &c.prepared;
            let case = Case {
                integrator: p.common.time.integrator,
                dt_s: p.common.time.dt_s,
            };
            let rows = Target::of(p)
                .map(|t| t.run_case(p, &case))
                .unwrap_or_default();
            done();
            (c.point.clone(), rows)
        })
        .collect();
    if crate::interrupt::requested() {
        return Err(Error::InterruptedUnwritten(plan.base.path.clone()));
    }
    Ok(VaryTable::from_cases(&plan.keys(), cases))
}

/// The outputs of a finished table titled `title` (`vary.csv` and the charts, no report page)
/// and its console lines.
pub(crate) fn results(title: &str, table: &VaryTable) -> Result<(Outputs, Vec<String>), Error> {
    let mut outputs = Outputs::new();
    outputs.table(table.to_table("vary.csv"));
    charts(&mut outputs, title, table)?;
    Ok((outputs, console_lines(title, table)))
}
