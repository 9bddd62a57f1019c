//! The objective of a fit: each evaluation runs the scenario in memory with the fitted keys
//! set (nothing is written), and reads the measured quantities from the run's tables.

use super::bound::Bound;
use super::measure::{self, Measurement};
use super::optim::{self, Minimum};
use crate::api::Scenario;
use crate::error::{BadInput, Error};
use crate::scenes::{Prepared, RunContext};
use indicatif::ProgressBar;
use std::path::{Path, PathBuf};

/// The outcome of a calibration: the typed figures of `fitted.csv`, `residuals.csv` and
/// `objective.csv`.
#[derive(Clone, Debug)]
pub struct Fit {
    /// The fitted keys, in the order given.
    pub bounds: Vec<Bound>,
    /// The best values found.
    pub values: Vec<f64>,
    /// 1σ uncertainty of each value from the curvature of χ² (Gauss–Newton); None when the
    /// data do not give one (no σ and as many measurements as keys).
    pub sigma: Vec<Option<f64>>,
    /// One key with every σ given: where χ² = χ²_min + 1 below and above the value (None
    /// beyond the bound).
    pub profile: Option<(Option<f64>, Option<f64>)>,
    /// χ² at the best values.
    pub chi2: f64,
    /// The measurements.
    pub measured: Vec<Measurement>,
    /// The model's value of each measurement at the best values.
    pub model: Vec<f64>,
    /// ∂model_i/∂key_j at the best values (the sensitivity of each measurement to each key).
    pub jacobian: Vec<Vec<f64>>,
    /// One key: χ² against the key's value (a grid over the bounds and every point evaluated),
    /// sorted by the value.
    pub objective: Vec<(f64, f64)>,
    /// Runs of the scenario made.
    pub runs: usize,
    /// The method: `brent` or `nelder-mead`.
    pub method: &'static str,
}

impl Fit {
    /// The best value of `key`, if it was fitted.
    pub fn value(&self, key: &str) -> Option<f64> {
        let j = self.bounds.iter().position(|b| b.key == key)?;
        Some(self.values[j])
    }
}

/// One evaluation: the point, its model values, χ² and the run's validity warnings.
struct Eval {
    x: Vec<f64>,
    model: Vec<f64>,
    chi2: f64,
    warnings: Vec<String>,
}

/// The runs of a fit: the scenario, the keys, the measurements and every point evaluated.
pub(crate) struct Problem {
    scenario: Scenario,
    bounds: Vec<Bound>,
    measured_file: PathBuf,
    measured: Vec<Measurement>,
    base: Prepared,
    /// Every evaluation, in order.
    history: Vec<Eval>,
    /// The fit's progress bar (runs made; hidden unless asked for or watched).
    bar: ProgressBar,
}

/// A value as `--set` writes it for a real key: exponent notation (TOML reads `7e-1` as a
/// float, and refuses it for an integer or text key).
fn text(x: f64) -> String {
    format!("{x:e}")
}

impl Problem {
    /// The scenario (its overrides applied) with each key at its lower and at its upper bound:
    /// a key that does not exist, that is not a real number, or a bound outside its allowed
    /// range is bad input naming the key, before anything runs.
    pub fn new(
        scenario: &Scenario,
        bounds: &[Bound],
        measured_file: &Path,
        measured: Vec<Measurement>,
        bar: ProgressBar,
    ) -> Result<Self, Error> {
        let base = scenario.prepared_with(&[])?;
        for b in bounds {
            for v in [b.lo, b.hi] {
                let ov = [format!("{}={}", b.key, text(v))];
                scenario.prepared_with(&ov).map_err(|e| {
                    Error::BadInput(BadInput {
                        message: format!(
                            "--fit {}={}:{} (the key must be a real number and both bounds \
                             allowed): {}",
                            b.key, b.lo, b.hi, e.message
                        ),
                        ..e
                    })
                })?;
            }
        }
        Ok(Self {
            scenario: scenario.clone(),
            bounds: bounds.to_vec(),
            measured_file: measured_file.to_path_buf(),
            measured,
            base,
            history: Vec::new(),
            bar,
        })
    }

    /// The scenario's name.
    pub fn name(&self) -> &str {
        &self.base.common.name
    }

    /// Runs of the scenario made so far.
    pub fn runs(&self) -> usize {
        self.history.len()
    }

    /// The measured quantities of one run at `x` (one value per key). A measurement the run
    /// does not write is bad input naming M.csv and its row; an unstable run is
    /// [`Error::Unstable`].
    pub fn model(&mut self, x: &[f64]) -> Result<Vec<f64>, Error> {
        if let Some(e) = self.history.iter().find(|e| e.x == x) {
            return Ok(e.model.clone());
        }
        if crate::interrupt::requested() {
            return Err(Error::InterruptedUnwritten(self.scenario.path().into()));
        }
        let ov: Vec<String> = self
            .bounds
            .iter()
            .zip(x)
            .map(|(b, v)| format!("{}={}", b.key, text(*v)))
            .collect();
        let p = self.scenario.prepared_with(&ov)?;
        let ctx = RunContext {
            quiet: true,
            ..RunContext::default()
        };
        // The runs' own bars go to a watch of their own: the fit's bar is the one shown.
        let done = crate::progress::Watch::new().scope(|| crate::run::execute(&p, &ctx))?;
        if done.report.interrupted {
            return Err(Error::InterruptedUnwritten(self.scenario.path().into()));
        }
        let tables = done.outputs.tables();
        let mut values = Vec::with_capacity(self.measured.len());
        for (i, m) in self.measured.iter().enumerate() {
            let bad = |msg: String| {
                Error::bad_input(
                    &self.measured_file,
                    Some(&format!("row {}", i + 1)),
                    format!("{}: {msg}", m.label()),
                )
            };
            let Some(t) = tables.iter().find(|t| t.name() == m.file) else {
                let mut have: Vec<&str> = tables
                    .iter()
                    .map(|t| t.name())
                    .filter(|n| !n.contains('/'))
                    .collect();
                have.sort();
                return Err(bad(format!(
                    "a {} run writes no such CSV: it writes {}",
                    self.base.common.kind.name(),
                    have.join(", ")
                )));
            };
            values.push(measure::extract(m, t).map_err(bad)?);
        }
        let chi2 = self.chi2_of(&values);
        self.history.push(Eval {
            x: x.to_vec(),
            model: values.clone(),
            chi2,
            warnings: done.report.warnings,
        });
        self.tick(chi2);
        Ok(values)
    }

    /// Moves the bar on by one run: the runs so far, the best χ² so far.
    fn tick(&self, chi2: f64) {
        let n = self.history.len() as u64;
        if self.bar.length().is_some_and(|len| n >= len) {
            self.bar.set_length(n + 1);
        }
        self.bar.set_position(n);
        let best = self.history.iter().map(|e| e.chi2).fold(chi2, f64::min);
        self.bar.set_message(format!(
            "run {n}: chi2 = {}, best {}",
            crate::io::fmt::g(chi2),
            crate::io::fmt::g(best)
        ));
    }

    /// Fills the bar: every run made.
    pub fn finish_bar(&self) {
        let n = self.history.len() as u64;
        self.bar.set_length(n);
        self.bar.set_position(n);
    }

    /// The validity warnings of the run at `x` (empty if it was not run).
    pub fn warnings_at(&self, x: &[f64]) -> Vec<String> {
        self.history
            .iter()
            .find(|e| e.x == x)
            .map(|e| e.warnings.clone())
            .unwrap_or_default()
    }

    /// χ² = Σ ((model_i − measured_i)/σ_i)² of model values.
    fn chi2_of(&self, model: &[f64]) -> f64 {
        model
            .iter()
            .zip(&self.measured)
            .map(|(y, m)| ((y - m.value) / m.sigma_or_one()).powi(2))
            .sum()
    }

    /// χ² at `x` (one run, or the remembered result of the same point).
    pub fn chi2(&mut self, x: &[f64]) -> Result<f64, Error> {
        let m = self.model(x)?;
        Ok(self.chi2_of(&m))
    }

    /// ∂model_i/∂key_j at `x` by central differences (step 1e-3 of each key's range, one-sided
    /// at a bound).
    fn jacobian(&mut self, x: &[f64]) -> Result<Vec<Vec<f64>>, Error> {
        let n = self.measured.len();
        let mut jac = vec![vec![0.0; x.len()]; n];
        for j in 0..x.len() {
            let b = self.bounds[j].clone();
            let h = 1e-3 * (b.hi - b.lo);
            let up = (x[j] + h).min(b.hi);
            let down = (x[j] - h).max(b.lo);
            let at = |v: f64| {
                let mut p = x.to_vec();
                p[j] = v;
                p
            };
            let (fu, fd) = (self.model(&at(up))?, self.model(&at(down))?);
            for i in 0..n {
                jac[i][j] = (fu[i] - fd[i]) / (up - down);
            }
        }
        Ok(jac)
    }

    /// Everything reported at the minimum: the model values, the sensitivities, the
    /// uncertainty (Gauss–Newton; scaled by χ²/(n − p) when no σ is given and n > p), for one
    /// key the Δχ² = 1 interval (every σ given) and the objective on `grid` points.
    pub fn finish(
        &mut self,
        min: &Minimum,
        method: &'static str,
        grid: usize,
    ) -> Result<Fit, Error> {
        let x = min.x.clone();
        let model = self.model(&x)?;
        let jacobian = self.jacobian(&x)?;
        let (n, p) = (self.measured.len(), x.len());
        let all_sigma = self.measured.iter().all(|m| m.sigma.is_some());
        let none_sigma = self.measured.iter().all(|m| m.sigma.is_none());
        let sig: Vec<f64> = self
            .measured
            .iter()
            .map(Measurement::sigma_or_one)
            .collect();
        let scale = if all_sigma {
            Some(1.0)
        } else if none_sigma && n > p {
            Some(min.f / (n - p) as f64)
        } else {
            None
        };
        let cov = optim::covariance(&jacobian, &sig);
        let sigma: Vec<Option<f64>> = (0..p)
            .map(|j| {
                let c = cov.as_ref()?;
                Some((c[j][j] * scale?).sqrt()).filter(|s| s.is_finite())
            })
            .collect();
        let mut profile = None;
        let mut objective = Vec::new();
        if p == 1 {
            let b = self.bounds[0].clone();
            if all_sigma {
                let level = min.f + 1.0;
                let xtol = 1e-5 * (b.hi - b.lo);
                let mut f = |v: f64| self.chi2(&[v]);
                // Bracket each crossing at 2σ of the curvature when χ² is above the level
                // there (one run), else search up to the bound.
                let mut side = |bound: f64| -> Result<Option<f64>, Error> {
                    let guess = sigma[0].map(|s| x[0] + 2.0 * s * (bound - x[0]).signum());
                    let outside = match guess.filter(|g| (g - x[0]).abs() < (bound - x[0]).abs()) {
                        Some(g) if f(g)? >= level => g,
                        _ => bound,
                    };
                    optim::crossing(&mut f, level, x[0], outside, xtol, 40)
                };
                let below = side(b.lo)?;
                let above = side(b.hi)?;
                profile = Some((below, above));
            }
            for k in 0..grid {
                let v = b.lo + (b.hi - b.lo) * k as f64 / (grid - 1) as f64;
                self.chi2(&[v])?;
            }
            objective = self.history.iter().map(|e| (e.x[0], e.chi2)).collect();
            objective.sort_by(|a, b| a.0.total_cmp(&b.0));
            objective.dedup_by(|a, b| a.0 == b.0);
        }
        Ok(Fit {
            bounds: self.bounds.clone(),
            values: x,
            sigma,
            profile,
            chi2: min.f,
            measured: self.measured.clone(),
            model,
            jacobian,
            objective,
            runs: self.runs(),
            method,
        })
    }
}
