//! Calibration: `settle fit SCENARIO --fit KEY=LO:HI [--fit …] --measured M.csv` finds the
//! values of scenario keys that make the scenario's outputs match measurements, and
//! `settle fit slump` computes a yield stress from slump tests ([`crate::fluid::slump`]).
//!
//! Each evaluation of the objective is a whole run of the scenario (the library's run path,
//! [`crate::run::prepare`] and [`crate::run::run_one`], with the `--set` list and then
//! `KEY=VALUE` for each fitted key) into a scratch folder outside `--out`; the measured
//! quantities are read back from its output CSVs ([`measure`]). The objective is
//! χ² = Σ ((model_i − measured_i)/σ_i)², minimised by Brent's method for one key and by
//! Nelder–Mead for several ([`optim`]; written here: a few dozen lines each, bounded, and
//! counting runs — no crate needed). Outputs ([`output`]) are staged and committed only on
//! success.
//!
//! | file | job |
//! |---|---|
//! | `measure.rs` | M.csv, and reading a measurement from a run's CSVs |
//! | `optim.rs` | Brent, Nelder–Mead, Gauss–Newton covariance, χ² crossing; pure |
//! | `problem.rs` | the objective: one run per evaluation |
//! | `output.rs` | fitted.csv, residuals.csv, objective.csv and chart, fit.toml, console |

pub mod measure;
pub mod optim;
pub mod output;
pub mod problem;

use crate::error::Error;
use problem::Problem;
pub use problem::{Bound, Fit};
use std::path::{Path, PathBuf};

/// Parses `KEY=LO:HI` (finite numbers, LO < HI).
pub fn parse_bound(s: &str) -> Result<Bound, String> {
    const ALLOWED: &str = "allowed KEY=LO:HI with numbers LO < HI, e.g. \
                           fluid.plastic_viscosity_pa_s=0.1:3";
    let (key, range) = s
        .split_once('=')
        .ok_or_else(|| format!("`{s}`: {ALLOWED}"))?;
    let key = key.trim();
    if !crate::scenario::is_key_path(key) {
        return Err(format!("`{key}` is not a scenario key: {ALLOWED}"));
    }
    let num = |t: &str| t.trim().parse::<f64>().ok().filter(|x| x.is_finite());
    let (lo, hi) = range
        .split_once(':')
        .and_then(|(a, b)| Some((num(a)?, num(b)?)))
        .ok_or_else(|| format!("`{range}` is not LO:HI: {ALLOWED}"))?;
    if lo >= hi {
        return Err(format!("bounds {lo}:{hi} are reversed or empty: {ALLOWED}"));
    }
    Ok(Bound {
        key: key.to_string(),
        lo,
        hi,
    })
}

/// Arguments of `settle fit` (see `settle fit --help`).
#[derive(clap::Args, Clone, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct Args {
    /// Calculators that need no scenario.
    #[command(subcommand)]
    pub calc: Option<Calc>,
    /// The scenario file (TOML) whose keys are fitted.
    #[arg(required = true)]
    pub scenario: Option<PathBuf>,
    /// A real-valued scenario key to fit and its bounds, KEY=LO:HI (LO < HI, in the key's unit),
    /// e.g. fluid.plastic_viscosity_pa_s=0.1:3. Repeatable (Nelder–Mead for several keys).
    #[arg(long = "fit", value_name = "KEY=LO:HI", required = true,
          allow_hyphen_values = true, value_parser = parse_bound)]
    pub fit: Vec<Bound>,
    /// The measurements: a CSV with columns file, column, row, value [, sigma].
    #[arg(long, value_name = "M.csv", required = true)]
    pub measured: Option<PathBuf>,
    /// Override any other scenario key for every run, as in `settle run --set`. Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Output folder; results go to `OUT/<name>_fit/`.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

/// The calculators of `settle fit`.
#[derive(clap::Subcommand, Clone, Debug)]
pub enum Calc {
    /// The yield stress of a paste from cylinder slump tests (Pashias & Boger 1996; f-EDEM
    /// Appendix I, eqs. A1-A3): prints τ_y per slump and their mean. Writes nothing.
    Slump {
        /// Height H of the cylinder mould, mm.
        #[arg(long)]
        height_mm: f64,
        /// Slump S of each test, mm (comma-separated or repeated), 0 < S < H.
        #[arg(long, value_delimiter = ',', required = true)]
        slump_mm: Vec<f64>,
        /// Density of the paste, kg/m³.
        #[arg(long)]
        density: f64,
        /// Gravitational acceleration, m/s².
        #[arg(long, default_value_t = crate::fluid::slump::G_M_S2)]
        g: f64,
    },
}

/// `settle fit`: the slump calculator, or a calibration; returns the console lines.
pub fn main(args: &Args) -> Result<Vec<String>, Error> {
    if let Some(Calc::Slump {
        height_mm,
        slump_mm,
        density,
        g,
    }) = &args.calc
    {
        return slump_lines(*height_mm, slump_mm, *density, *g);
    }
    let (Some(file), Some(measured)) = (&args.scenario, &args.measured) else {
        return Err(Error::bad_argument(
            "--measured",
            Path::new(""),
            "settle fit needs a scenario, --fit and --measured",
        ));
    };
    let fit = run(file, &args.fit, measured, &args.set, &args.out)?;
    Ok(if args.quiet { Vec::new() } else { fit.lines })
}

/// The slump calculator's lines: τ_y of each slump and the mean.
fn slump_lines(
    height_mm: f64,
    slumps_mm: &[f64],
    density: f64,
    g: f64,
) -> Result<Vec<String>, Error> {
    use crate::io::fmt::{g as fmt, short};
    let mut lines = Vec::new();
    let mut sum = 0.0;
    for s in slumps_mm {
        let t = crate::fluid::slump::yield_stress_pa(height_mm * 1e-3, s * 1e-3, density, g)
            .ok_or_else(|| {
                Error::bad_argument(
                    "--slump-mm",
                    Path::new(&short(*s)),
                    format!(
                        "out of range: allowed 0 < slump < height ({} mm), with height, \
                         density and g > 0",
                        short(height_mm)
                    ),
                )
            })?;
        sum += t;
        lines.push(format!(
            "H = {} mm, S = {} mm, rho = {} kg/m3: S' = {}, tau_y = {} Pa",
            short(height_mm),
            short(*s),
            short(density),
            fmt(s / height_mm),
            fmt(t)
        ));
    }
    lines.push(format!(
        "mean tau_y = {} Pa over {} slumps (eqs. A1-A3, Pashias & Boger 1996)",
        fmt(sum / slumps_mm.len() as f64),
        slumps_mm.len()
    ));
    Ok(lines)
}

/// Grid points of the objective chart (one key).
const CHART_POINTS: usize = 13;

/// Fits `bounds` of the scenario `file` (with `set`) to the measurements in `measured`, writing
/// `OUT/<name>_fit/`. Every bad input — a bound outside the key's range, a key that is not a
/// real number, a measurement the run does not write, a fit that does not converge or ends on a
/// bound — is an error before anything is written.
pub fn run(
    file: &Path,
    bounds: &[Bound],
    measured: &Path,
    set: &[String],
    out: &Path,
) -> Result<Fit, Error> {
    for (i, b) in bounds.iter().enumerate() {
        if bounds[..i].iter().any(|a| a.key == b.key) {
            return Err(Error::bad_argument(
                "--fit",
                Path::new(&b.key),
                "this key is fitted twice: allowed one --fit per key",
            ));
        }
    }
    let meas = measure::read(measured)?;
    let mut pb = Problem::new(file, set, bounds, measured, meas)?;
    let folder = format!("{}_fit", pb.name());
    if out.exists() && !out.is_dir() {
        return Err(Error::bad_argument(
            "--out",
            out,
            "exists and is not a folder: give a folder (it is created if absent)",
        ));
    }
    crate::run::destination_allowed(&out.join(&folder), file)?;
    let (lo, hi): (Vec<f64>, Vec<f64>) = bounds.iter().map(|b| (b.lo, b.hi)).unzip();
    // The first run, at the centre of the box, finds every measurement or fails as bad input.
    let centre: Vec<f64> = lo.iter().zip(&hi).map(|(a, b)| 0.5 * (a + b)).collect();
    pb.chi2(&centre)?;
    let (min, method) = if bounds.len() == 1 {
        let xtol = 1e-6 * (hi[0] - lo[0]);
        let m = optim::brent(&mut |x| pb.chi2(&[x]), lo[0], hi[0], xtol, 80)?;
        (m, "brent")
    } else {
        let n = bounds.len();
        let m = optim::nelder_mead(&mut |x| pb.chi2(x), &lo, &hi, 1e-5, 150 * n)?;
        (m, "nelder-mead")
    };
    if !min.converged {
        return Err(Error::bad_input(
            measured,
            None,
            format!(
                "the fit did not converge in {} runs ({method}): narrow the --fit bounds or \
                 check the measurements",
                pb.runs()
            ),
        ));
    }
    for (b, x) in bounds.iter().zip(&min.x) {
        if (x - b.lo).abs() < 1e-4 * (b.hi - b.lo) || (b.hi - x).abs() < 1e-4 * (b.hi - b.lo) {
            return Err(Error::bad_argument(
                "--fit",
                Path::new(&format!("{}={}:{}", b.key, b.lo, b.hi)),
                format!(
                    "the best value {} lies on a bound: the minimum is outside the bounds \
                     (widen them) or the measurements do not depend on this key",
                    crate::io::fmt::g(*x)
                ),
            ));
        }
    }
    let fit = pb.finish(&min, method, CHART_POINTS)?;
    for (j, b) in bounds.iter().enumerate() {
        if fit.jacobian.iter().all(|row| row[j] == 0.0) {
            return Err(Error::bad_argument(
                "--fit",
                Path::new(&format!("{}={}:{}", b.key, b.lo, b.hi)),
                "no measurement depends on this key (every sensitivity is 0): fit another key \
                 or measure another quantity",
            ));
        }
    }
    output::write(out, &folder, file, measured, set, fit)
}
