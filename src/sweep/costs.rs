//! What each shard of a split sweep will cost: the cost estimate of every case of the grid
//! (`crate::scenes::cost`, the estimate `settle run` makes), summed over the cases of each
//! shard, so that a job array can ask the scheduler for the time and memory of its largest
//! task (`settle sweep --slurm N`).

use super::args::Args;
use super::plan::Plan;
use super::shards::PART_PREFIX;
use super::targets::Target;
use super::vary::plan::VaryPlan;
use crate::error::Error;
use crate::run::prepare;
use crate::scenes::cost::{estimate, Cost};
use std::path::PathBuf;

/// A sweep of one scenario file about to be split into shards.
#[derive(Clone, Debug)]
pub struct Study {
    /// The scenario's name.
    pub name: String,
    /// Its output folder: `OUT/<name>_sweep/` (or `_vary/`).
    pub folder: PathBuf,
    /// The name prefix of its part files.
    pub prefix: &'static str,
    /// The estimate of every case of the grid, in the grid's order (case `k` runs in shard
    /// `k mod N + 1`).
    pub cases: Vec<Cost>,
}

impl Study {
    /// Plans the sweep of `args` (one scenario file, every case validated as the sweep itself
    /// validates it) and estimates each case.
    pub fn plan(args: &Args) -> Result<Self, Error> {
        let file = &args.scenarios[0];
        let out = args.out.clone().unwrap_or_else(|| PathBuf::from("out"));
        if !args.vary.is_empty() {
            let plan = VaryPlan::new(file, &args.set, &args.vary, None)?;
            return Ok(Self {
                name: plan.base.common.name.clone(),
                folder: out.join(plan.folder()),
                prefix: super::vary::PART_PREFIX,
                cases: plan.cases.iter().map(|c| estimate(&c.prepared)).collect(),
            });
        }
        let p = prepare(file, None, &args.set)?;
        Target::of(&p)?;
        let plan = Plan::resolve(args, &p)?;
        let cases = plan
            .cases()
            .iter()
            .map(|c| {
                let mut q = p.clone();
                q.common.time.dt_s = c.dt_s;
                estimate(&q)
            })
            .collect();
        Ok(Self {
            name: p.common.name.clone(),
            folder: out.join(format!("{}_sweep", p.common.name)),
            prefix: PART_PREFIX,
            cases,
        })
    }

    /// The largest wall time (s, one core) and the largest memory of one case (bytes) over the
    /// `count` shards: the wall time of a shard is the sum of its cases'.
    pub fn largest_shard(&self, count: usize) -> (f64, f64) {
        let mut wall = vec![0.0; count.max(1)];
        let mut mem: f64 = 0.0;
        for (k, c) in self.cases.iter().enumerate() {
            wall[k % count.max(1)] += c.wall_s;
            mem = mem.max(c.memory_bytes);
        }
        (wall.iter().cloned().fold(0.0, f64::max), mem)
    }
}
