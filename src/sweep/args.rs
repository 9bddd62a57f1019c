//! The arguments of `settle sweep` (clap), with value parsers that refuse bad values with a
//! message naming the option and what is allowed (clap exits 2).

use super::plan::{DtRange, Shard};
use super::vary::{parse_vary, Axis};
use crate::dynamics::Integrator;
use clap::builder::PossibleValue;
use std::fmt;
use std::path::PathBuf;

/// Arguments of `settle sweep` (see `settle sweep --help`).
#[derive(clap::Args, Clone, Debug, Default)]
pub struct Args {
    /// Scenario files (TOML). Each gets its own sweep.
    #[arg(required_unless_present = "merge")]
    pub scenarios: Vec<PathBuf>,
    /// Comma-separated time steps, s (e.g. 1e-1,1e-2,1e-3); each > 0.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true,
          value_parser = parse_dt, conflicts_with = "dt_range")]
    pub dt: Vec<f64>,
    /// Log-spaced range of time steps LO:HI, s, 0 < LO < HI (with --per-decade).
    #[arg(long, value_name = "LO:HI", allow_hyphen_values = true, value_parser = parse_dt_range)]
    pub dt_range: Option<DtRange>,
    /// Steps per decade for --dt-range (at least 1).
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..))]
    pub per_decade: u32,
    /// Comma-separated integrators (default: sweep.integrators of the scenario, else all).
    #[arg(long, value_delimiter = ',')]
    pub integrator: Vec<Integrator>,
    /// Tolerance of the recommended dt: the largest relative error against the finest stable dt
    /// accepted, 0 < TOL ≤ 1 (default: sweep.tol of the scenario, else 0.01).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_tol)]
    pub tol: Option<f64>,
    /// Output folder [default: out; with --merge, the first merged folder].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Run only slice I of N of the grid (1-based), writing a partial CSV to merge later.
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    pub shard: Option<Shard>,
    /// Vary a scenario key instead of dt (a parameter sweep into `OUT/<name>_vary/`): KEY=LO:HI:N
    /// (N values from LO to HI), KEY=log:LO:HI:N (log-spaced) or KEY=V1,V2,… (numbers, or words
    /// and booleans: a categorical axis, e.g. transient.history=off,basset); each value is
    /// applied as --set KEY=VALUE at the scenario's own dt and integrator. Repeat for a full grid
    /// of several keys (the first key is the charts' x axis).
    #[arg(long, value_name = "KEY=GRID", allow_hyphen_values = true, value_parser = parse_vary,
          conflicts_with_all = ["dt", "dt_range", "integrator", "tol"])]
    pub vary: Vec<Axis>,
    /// Merge the partial CSVs (sweep_part_*.csv, or vary_part_*.csv of a --vary sweep) found in
    /// these folders, then chart.
    #[arg(long, num_args = 1.., value_name = "DIR",
          conflicts_with_all = ["shard", "dt", "dt_range", "integrator", "vary"])]
    pub merge: Vec<PathBuf>,
    /// Override any scenario key (as for `run`).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Integrators on the command line by their scenario-file names.
impl clap::ValueEnum for Integrator {
    fn value_variants<'a>() -> &'a [Self] {
        &Integrator::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        Some(PossibleValue::new(self.name()))
    }
}

/// A command-line value outside its allowed range; clap prints it after the option's name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BadValue {
    /// What is allowed, e.g. `0 < TOL ≤ 1`.
    pub allowed: &'static str,
}

impl fmt::Display for BadValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "allowed {}", self.allowed)
    }
}

impl std::error::Error for BadValue {}

const DT_ALLOWED: &str = "a time step dt > 0 s (finite), e.g. 1e-3";
const RANGE_ALLOWED: &str = "LO:HI with 0 < LO < HI (s, finite), e.g. 1e-8:1e-1";
const SHARD_ALLOWED: &str = "I/N with 1 ≤ I ≤ N, e.g. 2/8";
/// The allowed range of `--tol`: a relative error, above 0 (0 would admit no step) and at most
/// 1 (100 %, beyond which the comparison means nothing); as `[sweep] tol` in a scenario.
pub const TOL_ALLOWED: &str = "0 < TOL ≤ 1 (a relative error against the finest stable dt)";

fn positive_s(s: &str) -> Option<f64> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|x| *x > 0.0 && x.is_finite())
}

/// Parses one `--dt` value: a finite time step > 0, s.
pub fn parse_dt(s: &str) -> Result<f64, BadValue> {
    positive_s(s).ok_or(BadValue {
        allowed: DT_ALLOWED,
    })
}

/// Parses `--dt-range LO:HI`.
pub fn parse_dt_range(s: &str) -> Result<DtRange, BadValue> {
    let bad = BadValue {
        allowed: RANGE_ALLOWED,
    };
    let (lo, hi) = s.split_once(':').ok_or(bad)?;
    match (positive_s(lo), positive_s(hi)) {
        (Some(lo_s), Some(hi_s)) if lo_s < hi_s => Ok(DtRange { lo_s, hi_s }),
        _ => Err(bad),
    }
}

/// Parses `--shard I/N`.
pub fn parse_shard(s: &str) -> Result<Shard, BadValue> {
    let bad = BadValue {
        allowed: SHARD_ALLOWED,
    };
    let (i, n) = s.split_once('/').ok_or(bad)?;
    let (index, count): (usize, usize) = (
        i.trim().parse().map_err(|_| bad)?,
        n.trim().parse().map_err(|_| bad)?,
    );
    if index == 0 || index > count {
        return Err(bad);
    }
    Ok(Shard { index, count })
}

/// Parses `--tol`: a relative error in (0, 1], see [`TOL_ALLOWED`].
pub fn parse_tol(s: &str) -> Result<f64, BadValue> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|t| *t > 0.0 && *t <= 1.0)
        .ok_or(BadValue {
            allowed: TOL_ALLOWED,
        })
}
