//! The arguments of `settle sweep` (clap), with value parsers that refuse bad values with a
//! message naming the option and what is allowed (clap exits 2).

use super::values::{parse_dt, parse_dt_range, parse_shard, parse_tol, DtRange, Shard};
use super::vary::{parse_vary, Axis};
use crate::dynamics::Integrator;
use clap::builder::PossibleValue;
use std::path::PathBuf;

/// Arguments of `settle sweep` (see `settle sweep --help`).
#[derive(clap::Args, Clone, Debug, Default)]
pub struct Args {
    /// Scenario files (TOML). Each gets its own sweep.
    #[arg(required_unless_present = "merge")]
    pub scenarios: Vec<PathBuf>,
    /// Comma-separated time steps, s (e.g. 1e-1,1e-2,1e-3); each > 0.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true,
          value_parser = dt_arg, conflicts_with = "dt_range")]
    pub dt: Vec<f64>,
    /// Log-spaced range of time steps LO:HI, s, 0 < LO < HI (with --per-decade).
    #[arg(long, value_name = "LO:HI", allow_hyphen_values = true, value_parser = dt_range_arg)]
    pub dt_range: Option<DtRange>,
    /// Steps per decade for --dt-range (at least 1).
    #[arg(long, default_value_t = 3, allow_negative_numbers = true, value_parser = per_decade_arg)]
    pub per_decade: u32,
    /// Comma-separated integrators (default: sweep.integrators of the scenario, else all).
    #[arg(long, value_delimiter = ',')]
    pub integrator: Vec<Integrator>,
    /// Tolerance of the recommended dt: the largest relative error against the finest stable dt
    /// accepted, 0 < TOL ≤ 1 (default: sweep.tol of the scenario, else 0.01).
    #[arg(long, allow_hyphen_values = true, value_parser = tol_arg)]
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
    #[arg(long, value_name = "KEY=GRID", allow_hyphen_values = true, value_parser = vary_arg,
          conflicts_with_all = ["dt", "dt_range", "integrator", "tol"])]
    pub vary: Vec<Axis>,
    /// Merge the partial CSVs (sweep_part_*.csv, or vary_part_*.csv of a --vary sweep) found in
    /// folder DIR (repeat for several folders), then chart; a scenario file given beside it
    /// supplies the title and `[sweep] tol`. Missing or unreadable shards are listed by index
    /// with the command that reruns them (exit 2, nothing written).
    #[arg(long, value_name = "DIR",
          conflicts_with_all = ["shard", "dt", "dt_range", "integrator", "vary"])]
    pub merge: Vec<PathBuf>,
    /// Override any scenario key (as for `run`).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
    /// Submit the sweep to Slurm as a job array of N tasks (task i runs `--shard i/N`) and a
    /// merge job after it; scripts and logs go to the sweep's folder (see docs/cluster.md).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=1_000_000),
          conflicts_with_all = ["shard", "merge"])]
    pub slurm: Option<u64>,
    /// Options of the submission (with --slurm).
    #[command(flatten)]
    pub submit: crate::slurm::options::Submit,
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

/// The numbers of `text` (split at `,`, `:` and `=`, words skipped when `words` allows them)
/// read by [`crate::io::arg::number_problem`] in `unit`, then `parse`'s own check.
fn checked<T, E: std::fmt::Display>(
    text: &str,
    unit: &str,
    parse: impl Fn(&str) -> Result<T, E>,
) -> Result<T, String> {
    for t in text.split([',', ':']) {
        if let Some(p) = crate::io::arg::number_problem(t, unit) {
            let e = parse(text).err().map(|e| e.to_string()).unwrap_or_default();
            return Err(format!("{p}; {e}"));
        }
    }
    parse(text).map_err(|e| e.to_string())
}

/// `--dt`: [`parse_dt`] after the number check.
fn dt_arg(s: &str) -> Result<f64, String> {
    checked(s, "seconds", parse_dt)
}

/// `--dt-range`: [`parse_dt_range`] after the number check.
fn dt_range_arg(s: &str) -> Result<DtRange, String> {
    checked(s, "seconds", parse_dt_range)
}

/// `--tol`: [`parse_tol`] after the number check.
fn tol_arg(s: &str) -> Result<f64, String> {
    checked(s, "", parse_tol)
}

/// `--vary`: [`parse_vary`], a number out of range said so.
fn vary_arg(s: &str) -> Result<Axis, String> {
    parse_vary(s).map_err(|e| {
        let grid = s.split_once('=').map_or("", |(_, g)| g);
        let huge = grid
            .split([',', ':'])
            .find(|t| t.trim().parse::<f64>().is_ok_and(f64::is_infinite));
        match huge {
            Some(t) => format!("{} is out of range; {e}", t.trim()),
            None => e.to_string(),
        }
    })
}

/// `--per-decade`: a whole number ≥ 1.
fn per_decade_arg(s: &str) -> Result<u32, String> {
    let n = crate::io::arg::count1(s)?;
    u32::try_from(n).map_err(|_| format!("{n} is out of range: allowed a whole number ≥ 1"))
}
