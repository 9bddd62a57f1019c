//! The calibration in memory: [`fit()`] and what it returns.

use super::bound::{Bound, ALLOWED};
use super::measure::{self, Measured};
use super::problem::{Fit, Problem};
use super::{optim, output};
use crate::api::Scenario;
use crate::error::Error;
use crate::io::{Outputs, Table};
use std::path::{Path, PathBuf};

/// How [`fit()`] runs.
#[derive(Clone, Debug, Default)]
pub struct FitOptions {
    /// Show a progress bar of the runs on stderr (default false; `settle fit` shows none).
    pub progress: bool,
}

/// What a calibration produced, in memory: the tables and files `settle fit` writes
/// (`fitted.csv`, `residuals.csv`, for one key `objective.csv` and `objective_vs_<key>.svg`,
/// and `fit.toml`) and the typed figures.
#[derive(Clone, Debug)]
pub struct FitResult {
    /// The results folder's name, `<scenario name>_fit`.
    pub name: String,
    /// The fitted values, their uncertainties, χ², the model at the best values, the runs
    /// made and the method.
    pub fit: Fit,
    /// The validity warnings of the scenario's run at the fitted values.
    pub warnings: Vec<String>,
    /// The lines `settle fit` prints (the first without the folder written).
    pub lines: Vec<String>,
    /// The tables and files of `OUT/<name>_fit/`.
    pub outputs: Outputs,
}

impl FitResult {
    /// The table of the file `name` (`fitted` or `fitted.csv`, `residuals`, `objective`).
    pub fn table(&self, name: &str) -> Option<&Table> {
        self.outputs.get(name)
    }

    /// Writes `out_dir/<name>_fit/` as `settle fit --out OUT_DIR` does, the same files byte
    /// for byte (staged, then moved into place): refused as bad input on `--out` when that
    /// folder exists and was not made by settle ([`Outputs::write_folder`]); returns the folder.
    pub fn write(&self, out_dir: impl AsRef<Path>) -> Result<PathBuf, Error> {
        self.outputs.write_folder(out_dir.as_ref(), &self.name)
    }
}

/// `settle fit` in memory: fits the keys of `bounds` of `scenario` (with its overrides applied
/// to every run) to the measurements. Every bad input — a key fitted twice, a bound outside
/// the key's allowed range or a key that is not a real number (each key is loaded at both
/// bounds before anything runs), a measurement the run does not write, a fit that does not
/// converge or ends on a bound, a key no measurement depends on — is [`Error::BadInput`] with
/// the command line's message; an unstable run is [`Error::Unstable`]; Ctrl-C
/// ([`crate::interrupt::request`]) stops it at its next run with
/// [`Error::InterruptedUnwritten`]. Nothing is written.
pub fn fit(
    scenario: &Scenario,
    bounds: &[Bound],
    measured: impl Into<Measured>,
    opts: &FitOptions,
) -> Result<FitResult, Error> {
    calibrate(scenario, bounds, &measured.into(), opts, |_| Ok(()))
}

/// Grid points of the objective chart (one key).
const CHART_POINTS: usize = 13;

/// The owner of the results folder `folder` (`<scenario name>_fit`) of a calibration.
pub(crate) fn owner(folder: &str) -> crate::io::Owner {
    crate::io::Owner::scenario("fit", folder.strip_suffix("_fit").unwrap_or(folder))
}

/// [`fit()`], calling `before_runs` with the results folder's name once the input is checked
/// and before the first run (the command line checks its destination there).
pub(crate) fn calibrate(
    scenario: &Scenario,
    bounds: &[Bound],
    measured: &Measured,
    opts: &FitOptions,
    before_runs: impl FnOnce(&str) -> Result<(), Error>,
) -> Result<FitResult, Error> {
    if bounds.is_empty() {
        return Err(Error::bad_argument(
            "--fit",
            Path::new(""),
            format!("no key to fit: {ALLOWED}"),
        ));
    }
    for (i, b) in bounds.iter().enumerate() {
        if bounds[..i].iter().any(|a| a.key == b.key) {
            return Err(Error::bad_argument(
                "--fit",
                Path::new(&b.key),
                "this key is fitted twice: allowed one --fit per key",
            ));
        }
    }
    let measured_file = measured.path();
    let meas = measure::read(measured)?;
    let n = bounds.len();
    // The most runs a fit makes: the centre, the search, the sensitivities, and for one key
    // both Δχ² = 1 crossings and the chart's grid.
    let budget = if n == 1 {
        1 + 80 + 3 + 2 * 41 + CHART_POINTS
    } else {
        2 + 150 * n + 2 * n
    };
    let bar = crate::progress::bar(budget as u64, scenario.name(), "runs", !opts.progress);
    let mut pb = Problem::new(scenario, bounds, &measured_file, meas, bar)?;
    let folder = format!("{}_fit", pb.name());
    before_runs(&folder)?;
    let (lo, hi): (Vec<f64>, Vec<f64>) = bounds.iter().map(|b| (b.lo, b.hi)).unzip();
    // The first run, at the centre of the box, finds every measurement or fails as bad input.
    let centre: Vec<f64> = lo.iter().zip(&hi).map(|(a, b)| 0.5 * (a + b)).collect();
    pb.chi2(&centre)?;
    let (min, method) = if n == 1 {
        let xtol = 1e-6 * (hi[0] - lo[0]);
        let m = optim::brent(&mut |x| pb.chi2(&[x]), lo[0], hi[0], xtol, 80)?;
        (m, "brent")
    } else {
        let m = optim::nelder_mead(&mut |x| pb.chi2(x), &lo, &hi, 1e-5, 150 * n)?;
        (m, "nelder-mead")
    };
    if !min.converged {
        return Err(Error::bad_input(
            &measured_file,
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
    pb.finish_bar();
    let request = output::Request {
        scenario: scenario.path(),
        measured: &measured_file,
        set: scenario.overrides(),
        dt_s: scenario.dt_override(),
    };
    let mut outputs = output::outputs(&request, &fit)?;
    outputs.set_owner(owner(&folder));
    Ok(FitResult {
        name: folder,
        warnings: pb.warnings_at(&fit.values),
        lines: output::lines(&fit, None),
        outputs,
        fit,
    })
}
