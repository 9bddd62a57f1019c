//! The sweep grid: which (integrator, dt) cases run, resolved from the options (the command
//! line's or the library's [`SweepOptions`]) and the scenario's `[sweep]` table. Pure: no I/O,
//! no simulation.

use super::args::Args;
use super::values::{is_dt, is_tol, Shard, DT_ALLOWED, RANGE_ALLOWED, TOL_ALLOWED};
use crate::dynamics::Integrator;
use crate::error::BadInput;
use crate::error::Error;
use crate::io::fmt::num;
use crate::scenes::Prepared;
use std::path::Path;

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

/// The options of a dt sweep, as `settle sweep` takes them; every one left empty (`None`, an
/// empty list) takes the command line's default. [`Plan::new`] checks them (the command line's
/// checks, with its messages).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SweepOptions {
    /// Time steps, s, each > 0 and finite (`--dt`). Empty: `dt_range`, else the scenario's
    /// `[sweep] dt_s`.
    pub dts: Vec<f64>,
    /// Log-spaced time steps from `lo` to `hi`, s, 0 < lo < hi (`--dt-range LO:HI`); not with
    /// `dts`.
    pub dt_range: Option<(f64, f64)>,
    /// Steps per decade of `dt_range`, at least 1 (`--per-decade`; None: 3).
    pub per_decade: Option<u32>,
    /// Integrators by name: `explicit`, `implicit`, `exponential` (`--integrator`). Empty: the
    /// scenario's `[sweep] integrators`, else all three.
    pub integrators: Vec<String>,
    /// Tolerance of the recommended dt: the largest relative error against the finest stable
    /// dt accepted, 0 < tol ≤ 1 (`--tol`; None: the scenario's `[sweep] tol`, else
    /// [`DEFAULT_TOL`]).
    pub tol: Option<f64>,
    /// Show a progress bar on stderr (default false; `settle sweep` shows one unless `-q`).
    pub progress: bool,
}

/// `--per-decade` when not given.
pub const DEFAULT_PER_DECADE: u32 = 3;

impl SweepOptions {
    /// The options of the command line's arguments (already checked by clap).
    pub(crate) fn from_args(args: &Args) -> Self {
        Self {
            dts: args.dt.clone(),
            dt_range: args.dt_range.map(|r| (r.lo_s, r.hi_s)),
            per_decade: Some(args.per_decade),
            integrators: args
                .integrator
                .iter()
                .map(|i| i.name().to_string())
                .collect(),
            tol: args.tol,
            progress: !args.quiet,
        }
    }

    /// Checks every option as the command line does; a bad one is a bad argument naming the
    /// option (`--dt`, `--integrator`, …), the value and what is allowed.
    /// Returns the steps per decade and the integrators.
    fn check(&self) -> Result<(u32, Vec<Integrator>), Error> {
        let bad = |option: &str, value: String, allowed: &str| {
            Error::bad_argument(option, Path::new(&value), format!("allowed {allowed}"))
        };
        if let Some(x) = self.dts.iter().find(|x| !is_dt(**x)) {
            return Err(bad("--dt", num(*x), DT_ALLOWED));
        }
        if let Some((lo, hi)) = self.dt_range {
            if !self.dts.is_empty() {
                return Err(Error::bad_argument(
                    "--dt-range",
                    Path::new(&format!("{}:{}", num(lo), num(hi))),
                    "cannot be used with --dt: give the time steps one way",
                ));
            }
            if !(is_dt(lo) && is_dt(hi) && lo < hi) {
                return Err(bad(
                    "--dt-range",
                    format!("{}:{}", num(lo), num(hi)),
                    RANGE_ALLOWED,
                ));
            }
        }
        let per_decade = self.per_decade.unwrap_or(DEFAULT_PER_DECADE);
        if per_decade == 0 {
            return Err(bad(
                "--per-decade",
                "0".into(),
                "at least 1 step per decade",
            ));
        }
        if let Some(t) = self.tol.filter(|t| !is_tol(*t)) {
            return Err(bad("--tol", num(t), TOL_ALLOWED));
        }
        let names: Vec<&str> = Integrator::ALL.iter().map(|i| i.name()).collect();
        let integrators = self
            .integrators
            .iter()
            .map(|s| {
                Integrator::ALL
                    .into_iter()
                    .find(|i| i.name() == s.trim())
                    .ok_or_else(|| bad("--integrator", s.clone(), &names.join(", ")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok((per_decade, integrators))
    }
}

impl Plan {
    /// Resolves the command line against the scenario's `[sweep]` defaults ([`Plan::new`]).
    pub(crate) fn resolve(args: &Args, p: &Prepared) -> Result<Self, Error> {
        Self::new(&SweepOptions::from_args(args), p, args.shard)
    }

    /// Checks `opts` and resolves them against the scenario's `[sweep]` defaults: the
    /// integrators given, else `[sweep] integrators`, else all three; `dts`/`dt_range`, else
    /// `[sweep] dt_s` (none at all is an error naming the file); `tol`, else `[sweep] tol`,
    /// else [`DEFAULT_TOL`]. `shard`: run only that slice of the grid.
    pub fn new(opts: &SweepOptions, p: &Prepared, shard: Option<Shard>) -> Result<Self, Error> {
        let (per_decade, given) = opts.check()?;
        let table = p.common.sweep.as_ref();
        let integrators = if !given.is_empty() {
            given
        } else {
            match table.map(|s| s.integrators.clone()).unwrap_or_default() {
                v if v.is_empty() => Integrator::ALL.to_vec(),
                v => v,
            }
        };
        let mut dts_s = opts.dts.clone();
        if let Some((lo, hi)) = opts.dt_range {
            dts_s.extend(dt_range(lo, hi, per_decade));
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
        let tol = opts
            .tol
            .or_else(|| table.and_then(|s| s.tol))
            .unwrap_or(DEFAULT_TOL);
        Ok(Self {
            integrators,
            dts_s,
            tol,
            shard,
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
