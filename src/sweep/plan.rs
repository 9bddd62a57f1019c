//! The sweep grid: which (integrator, dt) cases run, resolved from the command line and the
//! scenario's `[sweep]` table. Pure: no I/O, no simulation.

use super::args::Args;
use super::values::Shard;
use crate::dynamics::Integrator;
use crate::error::BadInput;
use crate::error::Error;
use crate::scenes::Prepared;

/// Tolerance of the recommended dt when neither `--tol` nor `[sweep] tol` gives one: a 1 %
/// relative error against the finest stable dt.
pub const DEFAULT_TOL: f64 = 0.01;

/// One case of the sweep grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Case {
    /// Integrator.
    pub integrator: Integrator,
    /// Time step, s.
    pub dt_s: f64,
}

/// The grid: every integrator × every dt, integrators outermost, dt descending.
pub fn grid(integrators: &[Integrator], dts: &[f64]) -> Vec<Case> {
    let mut dts = dts.to_vec();
    dts.sort_by(|a, b| b.total_cmp(a));
    dts.dedup();
    integrators
        .iter()
        .flat_map(|&i| {
            dts.iter().map(move |&dt_s| Case {
                integrator: i,
                dt_s,
            })
        })
        .collect()
}

/// `--dt-range LO:HI --per-decade N`: log-spaced steps from HI down to LO inclusive, s.
pub fn dt_range(lo: f64, hi: f64, per_decade: u32) -> Vec<f64> {
    let n = ((hi / lo).log10() * per_decade as f64).round() as i64;
    (0..=n)
        .map(|k| {
            let x = hi * 10f64.powf(-(k as f64) / per_decade as f64);
            // Round to 12 significant digits so 1e-3 prints as 1e-3.
            let e = x.log10().floor();
            (x / 10f64.powf(e) * 1e11).round() / 1e11 * 10f64.powf(e)
        })
        .collect()
}

/// Slice `shard` (1-based) of `of` slices: cases whose index ≡ shard − 1 (mod of).
pub fn shard(cases: &[Case], shard: usize, of: usize) -> Vec<Case> {
    cases
        .iter()
        .enumerate()
        .filter(|(i, _)| i % of == shard - 1)
        .map(|(_, c)| *c)
        .collect()
}

/// What to run for one scenario: integrators × time steps (optionally one shard of them) and
/// the tolerance of the recommended dt.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Integrators, in the order given.
    pub integrators: Vec<Integrator>,
    /// Time steps, s (any order; [`grid`] sorts them).
    pub dts_s: Vec<f64>,
    /// Tolerance of the recommended dt: relative error against the finest stable dt, in (0, 1].
    pub tol: f64,
    /// Run only this slice of the grid.
    pub shard: Option<Shard>,
}

impl Plan {
    /// Resolves the command line against the scenario's `[sweep]` defaults: `--integrator`,
    /// else `[sweep] integrators`, else all three; `--dt`/`--dt-range`, else `[sweep] dt_s`
    /// (none at all is an error naming the file); `--tol`, else `[sweep] tol`, else
    /// [`DEFAULT_TOL`].
    pub fn resolve(args: &Args, p: &Prepared) -> Result<Self, Error> {
        let table = p.scenario.sweep.as_ref();
        let integrators = if !args.integrator.is_empty() {
            args.integrator.clone()
        } else {
            match table.map(|s| s.integrators.clone()).unwrap_or_default() {
                v if v.is_empty() => Integrator::ALL.to_vec(),
                v => v,
            }
        };
        let mut dts_s = args.dt.clone();
        if let Some(r) = args.dt_range {
            dts_s.extend(dt_range(r.lo_s, r.hi_s, args.per_decade));
        }
        if dts_s.is_empty() {
            dts_s = table.map(|s| s.dt_s.clone()).unwrap_or_default();
        }
        if dts_s.is_empty() {
            return Err(Error::BadInput(BadInput::new(
                &p.path,
                Some("sweep.dt_s"),
                "no time steps to sweep: give --dt or --dt-range, or a [sweep] dt_s list in the scenario",
            )));
        }
        let tol = args
            .tol
            .or_else(|| table.and_then(|s| s.tol))
            .unwrap_or(DEFAULT_TOL);
        Ok(Self {
            integrators,
            dts_s,
            tol,
            shard: args.shard,
        })
    }

    /// Every case of the grid (all shards).
    pub fn cases(&self) -> Vec<Case> {
        grid(&self.integrators, &self.dts_s)
    }

    /// The cases this process runs: its shard of [`Plan::cases`], or all of them.
    pub fn cases_to_run(&self) -> Vec<Case> {
        let all = self.cases();
        match self.shard {
            Some(s) => shard(&all, s.index, s.count),
            None => all,
        }
    }
}
