//! `settle invert READINGS.csv [READINGS2.csv …]`: the grain-size distribution that explains
//! one or several instruments' readings of the same soil, through settle's own forward model
//! ([`crate::instruments::forward`]) and each instrument's exact geometry, into
//! `OUT/<stem>_inverted/`: `inverted.csv`, `misfit.csv`, `standard.csv`, `inverted.svg` and
//! `invert.toml` (see `docs/commands/invert.md`).
//!
//! # From Rust
//!
//! [`invert`] runs the command in memory: the readings as files or tables
//! ([`crate::reduce::Readings`], the format of `settle reduce`), the options of the command line
//! ([`InvertOptions`], its defaults those of `settle invert`); it returns an [`InvertResult`]
//! with every table, the chart as SVG text, the record and the typed figures, and
//! [`InvertResult::write`] writes the folder the command writes.
//!
//! # Method
//!
//! 1. Each file gives a [`problem::Test`]: the column (c₀ = dry mass / suspension volume, G_s,
//!    μ_w(T) and ρ_w(T) at the mean temperature of its readings) and its instrument (the 152H
//!    of ASTM D422 Table 2, or built from the D7928 measured dimensions).
//! 2. Unknowns: the mass fraction w_j of each diameter bin, even in ln d over the diameters the
//!    readings resolve, plus a bin finer and a bin coarser than those ([`bins_for`]).
//! 3. Predicted reading i = instrument(ρ_f + Σ_j w_j u_ij) + offset, u_ij the unit fields. The
//!    pipette and the sphere are affine in w; the hydrometer floats, so it is linearised
//!    (analytic Jacobian, [`problem::Test::predict`]) and the linear problem solved again
//!    (Gauss–Newton); with `--model full` the unit fields are recomputed at the current w
//!    (hindered settling depends on the distribution: a fixed point). Iterations stop when the
//!    cumulative curve moves less than 0.01 points.
//! 4. Each linear problem: [`solve`] (Tikhonov, w ≥ 0, Σw = 1, λ by the discrepancy principle
//!    or GCV).
//! 5. Band: Monte Carlo over the readings' uncertainty (rounding to the resolution and a
//!    reading error, [`problem::Test::sigma`]) and over the smoothing prior (randomise then
//!    optimise: each repeat also draws the target of the Tikhonov penalty from its Gaussian
//!    prior, and chooses λ again), re-solving the last linear problem; the 5th and 95th
//!    percentiles of the cumulative curve at each diameter.

mod diagnose;
mod options;
mod output;
pub mod problem;
mod setup;
pub mod solve;

use options::options;
pub use options::{InvertOptions, Model, Request, DEFAULT_BOUNDS_CONFIDENCE};
pub use setup::{
    read_test, DEFAULT_CYLINDER_AREA_M2, HYDROMETER_RESOLUTION, PIPETTE_RESOLUTION_G,
    SPHERE_RESOLUTION_G,
};

use crate::error::Error;
use crate::instruments::forward::{unit_fields, Bins};
use crate::instruments::reduction::Reduced;
use crate::io::{Outputs, Table};
use crate::reduce::Readings;
use nalgebra::{DMatrix, DVector};
use problem::Test;
use rand::{Rng, SeedableRng};
use solve::{LambdaRule, Linear};
use std::path::{Path, PathBuf};

/// The recovered curve at one diameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurvePoint {
    /// Diameter (a bin edge), m.
    pub diameter_m: f64,
    /// Percent finer, %.
    pub percent_finer: f64,
    /// 5th percentile of the Monte Carlo, %.
    pub p5: f64,
    /// 95th percentile of the Monte Carlo, %.
    pub p95: f64,
    /// Strict bounds (`--bounds`): the smallest and largest percent finer at this diameter over
    /// every distribution of the bins (no smoothing) whose χ² is at most the number of
    /// readings, %; None when not asked for or when no distribution fits that well.
    pub bounds: Option<(f64, f64)>,
}

/// One reading against its prediction.
#[derive(Clone, Debug, PartialEq)]
pub struct Misfit {
    /// Index of the file in the request.
    pub file: usize,
    /// Time of the reading, s.
    pub time_s: f64,
    /// The reading, in the file's unit.
    pub reading: f64,
    /// The recovered distribution's predicted reading.
    pub predicted: f64,
    /// Its standard deviation σ.
    pub sigma: f64,
}

/// What an inversion produced, in memory: the tables and files `settle invert` writes
/// (`inverted.csv`, `misfit.csv`, `standard.csv`, `inverted.svg`, `invert.toml`) and the typed
/// figures.
#[derive(Clone, Debug)]
pub struct InvertResult {
    /// The results folder's name, `<stem of the first readings>_inverted`.
    pub name: String,
    /// The readings (files, or the names of the tables in memory), in order.
    pub inputs: Vec<PathBuf>,
    /// The options, as given.
    pub options: InvertOptions,
    /// The forward model.
    pub model: Model,
    /// How λ was chosen.
    pub lambda_rule: LambdaRule,
    /// The files' tests.
    pub tests: Vec<Test>,
    /// The bins (finest and coarsest are the "finer than" and "coarser than" bins).
    pub bins: Bins,
    /// Recovered mass fraction of each bin.
    pub w: Vec<f64>,
    /// The recovered curve at the resolved bin edges.
    pub curve: Vec<CurvePoint>,
    /// Every reading against its prediction.
    pub misfit: Vec<Misfit>,
    /// The standard reduction of every file (file index, reduced reading).
    pub standard: Vec<(usize, Reduced)>,
    /// λ of the last linear problem.
    pub lambda: f64,
    /// χ² of the recovered distribution.
    pub chi2: f64,
    /// Iterations of the Gauss–Newton / fixed-point loop.
    pub iterations: usize,
    /// Whether the curve moved less than 0.01 points in the last iteration.
    pub converged: bool,
    /// Wall time of the inversion, s.
    pub wall_time_s: f64,
    /// Warnings (misfit larger than the readings' uncertainty, no convergence).
    pub warnings: Vec<String>,
    /// The tables and files of `OUT/<stem>_inverted/`.
    pub outputs: Outputs,
}

impl InvertResult {
    /// The table of the file `name` (`inverted`, `misfit`, `standard`, or with `.csv`).
    pub fn table(&self, name: &str) -> Option<&Table> {
        self.outputs.get(name)
    }

    /// Writes `out_dir/<stem>_inverted/` as `settle invert --out OUT_DIR` does (staged, then
    /// moved into place; refused when that folder exists and was not made by settle); returns
    /// the folder.
    pub fn write(&self, out_dir: impl AsRef<Path>) -> Result<PathBuf, Error> {
        self.outputs.write_folder(out_dir.as_ref(), &self.name)
    }

    /// The console summary of `settle invert`, the results written to `out`.
    pub fn lines(&self, out: &Path) -> Vec<String> {
        output::summary(self, out)
    }
}

/// What `settle invert` did on the command line ([`run`]).
#[derive(Clone, Debug)]
pub struct Report {
    /// The results folder.
    pub out: PathBuf,
    /// Console summary.
    pub lines: Vec<String>,
    /// Warnings (misfit larger than the readings' uncertainty, no convergence).
    pub warnings: Vec<String>,
    /// The inversion.
    pub result: InvertResult,
}

/// The bins: `n` even in ln d over the resolved range [lo, hi], a bin [lo/4, lo] finer and a
/// bin [hi, 4 hi] coarser. The resolved range, unless given: from the smallest Stokes diameter
/// at the shallowest depth an instrument averages over at a reading (the hydrometer floating at
/// the mark it reads), to the largest at the deepest (every grain coarser has left the
/// instrument before each reading, every grain finer is still throughout it).
pub fn bins_for(tests: &[Test], n: usize, range: Option<(f64, f64)>) -> Bins {
    let (lo, hi) = range.unwrap_or_else(|| {
        let mut lo = f64::INFINITY;
        let mut hi: f64 = 0.0;
        for t in tests {
            let an = &t.col.analysis;
            for (i, &time) in t.times_s.iter().enumerate() {
                let (top, bottom) = t.probe.depth_span_m(t.readings[i] - t.offsets[i]);
                lo = lo.min(an.limiting_diameter_m(top.max(1e-3), time));
                hi = hi.max(an.limiting_diameter_m(bottom, time));
            }
        }
        (lo, hi)
    });
    let mid = Bins::log_spaced(lo, hi, n);
    let mut edges = vec![lo / 4.0];
    edges.extend(mid.edges_m);
    edges.push(4.0 * hi);
    Bins { edges_m: edges }
}

/// The resolved bin edges (all but the outermost two).
fn resolved_edges(bins: &Bins) -> &[f64] {
    &bins.edges_m[1..bins.edges_m.len() - 1]
}

/// The linearised problem of all files at `w`: (design, readings − prediction + J w, σ),
/// with each file's unit fields `units[f][t]`.
fn linearise(
    tests: &[Test],
    units: &[Vec<Vec<Vec<f64>>>],
    w: &[f64],
) -> Result<(Linear, Vec<f64>), Error> {
    let m: usize = tests.iter().map(|t| t.readings.len()).sum();
    let n = w.len();
    let mut j = DMatrix::zeros(m, n);
    let mut b = DVector::zeros(m);
    let mut sigma = DVector::zeros(m);
    let mut pred = Vec::with_capacity(m);
    let mut row = 0;
    for (t, u) in tests.iter().zip(units) {
        for (i, ui) in u.iter().enumerate().take(t.readings.len()) {
            let (p, d) = t.predict(i, ui, w)?;
            let jw: f64 = d.iter().zip(w).map(|(a, b)| a * b).sum();
            for (k, x) in d.iter().enumerate() {
                j[(row, k)] = *x;
            }
            b[row] = t.readings[i] - p + jw;
            sigma[row] = t.sigma_at(i);
            pred.push(p);
            row += 1;
        }
    }
    Ok((Linear { j, b, sigma }, pred))
}

/// `settle invert` in memory: reads and checks the readings (files or tables in memory, one
/// test of one soil each, any instrument), inverts them together and makes the outputs. A bad
/// option is [`Error::BadInput`] naming it (`--model`, `--bins`, ...), bad readings name the
/// file (or table), the key or the row and column, as on the command line.
///
/// ```no_run
/// use settle::invert::{invert, InvertOptions};
/// use settle::reduce::Readings;
/// let opts = InvertOptions { model: "full".into(), ..InvertOptions::default() };
/// let r = invert(&[Readings::from("lab/soil_a.csv")], &opts)?;
/// let finer = r.table("inverted").unwrap().f64s("percent_finer");
/// r.write("out")?; // out/soil_a_inverted/
/// # Ok::<(), settle::Error>(())
/// ```
pub fn invert(readings: &[Readings], opts: &InvertOptions) -> Result<InvertResult, Error> {
    let clock = std::time::Instant::now();
    let (model, rule, range) = options(opts, readings.len())?;
    let mut tests = Vec::new();
    let mut standard = Vec::new();
    for (k, r) in readings.iter().enumerate() {
        let res = opts.resolution.get(k).or(opts.resolution.first()).copied();
        let (test, reduced) = setup::read_test_of(r, res)?;
        tests.push(test);
        standard.extend(reduced.into_iter().map(|r| (k, r)));
    }
    let m: usize = tests.iter().map(|t| t.readings.len()).sum();
    let n = opts.bins.unwrap_or((2 * m).clamp(8, 30));
    if m < 3 {
        return Err(Error::bad_input(
            &readings[0].path(),
            None,
            format!("{m} readings in all: an inversion needs at least 3"),
        ));
    }
    if n > 4 * m {
        return Err(Error::bad_argument(
            "--bins",
            Path::new(&n.to_string()),
            format!(
                "{m} readings cannot determine {n} bins: allowed at most 4 per reading ({})",
                4 * m
            ),
        ));
    }
    let bins = bins_for(&tests, n, range);
    let fit = fit(
        &tests,
        &bins,
        model,
        rule,
        opts.repeats,
        opts.seed,
        opts.bounds,
    )?;
    let mut misfit = Vec::new();
    let mut row = 0;
    for (k, t) in tests.iter().enumerate() {
        for i in 0..t.readings.len() {
            misfit.push(Misfit {
                file: k,
                time_s: t.times_s[i],
                reading: t.readings[i],
                predicted: fit.predicted[row],
                sigma: t.sigma_at(i),
            });
            row += 1;
        }
    }
    let mut r = InvertResult {
        name: inverted_name(&readings[0]),
        inputs: readings.iter().map(Readings::path).collect(),
        options: opts.clone(),
        model,
        lambda_rule: rule,
        tests,
        bins,
        w: fit.w,
        curve: fit.curve,
        misfit,
        standard,
        lambda: fit.lambda,
        chi2: fit.chi2,
        iterations: fit.iterations,
        converged: fit.converged,
        wall_time_s: 0.0,
        warnings: Vec::new(),
        outputs: Outputs::new(),
    };
    r.warnings = output::warnings(&r);
    r.wall_time_s = clock.elapsed().as_secs_f64();
    r.outputs = output::outputs(&r)?;
    r.outputs.set_owner(owner(readings));
    Ok(r)
}

/// The owner of the results folder of `readings`: their files, in order.
fn owner(readings: &[Readings]) -> crate::io::Owner {
    let inputs: Vec<String> = readings.iter().map(Readings::owner_input).collect();
    crate::io::Owner::new("invert", inputs.join(" + "))
}

/// The results folder's name of readings whose first is `first`: `<stem>_inverted`.
fn inverted_name(first: &Readings) -> String {
    format!("{}_inverted", first.stem())
}

/// Runs `settle invert`: [`invert`] of the files, then [`InvertResult::write`] into
/// `OUT/<stem>_inverted/`. The options and the output folder are checked before the inversion.
pub fn run(req: &Request) -> Result<Report, Error> {
    let opts = &req.options;
    options(opts, req.files.len())?;
    let readings: Vec<Readings> = req
        .files
        .iter()
        .map(|f| Readings::from(f.as_path()))
        .collect();
    crate::io::owner::check_out_dir(&req.out_dir)?;
    let dest = req.out_dir.join(inverted_name(&readings[0]));
    crate::io::owner::check_owned(&dest, &owner(&readings))?;
    let result = invert(&readings, opts)?;
    let out = result.write(&req.out_dir)?;
    Ok(Report {
        lines: result.lines(&out),
        warnings: result.warnings.clone(),
        out,
        result,
    })
}

/// What an inversion of some tests found.
#[derive(Clone, Debug)]
pub struct Fit {
    /// Mass fraction of each bin.
    pub w: Vec<f64>,
    /// The curve at the resolved edges, with its band.
    pub curve: Vec<CurvePoint>,
    /// Predicted readings, the files' readings in order.
    pub predicted: Vec<f64>,
    /// λ of the last linear problem.
    pub lambda: f64,
    /// χ² of the predicted readings.
    pub chi2: f64,
    /// Gauss–Newton / fixed-point iterations.
    pub iterations: usize,
    /// Whether the curve moved less than 0.01 points in the last one.
    pub converged: bool,
}

/// Inverts the readings of `tests` over `bins` with `model` and the λ `rule`; the band from
/// `repeats` Monte Carlo repeats seeded `seed`; with `bounds` = Some(P), the strict bounds of
/// the curve at each resolved edge at confidence P: the range of F(d) over every distribution of
/// `bins` (w ≥ 0, Σw = 1, no smoothing) whose χ² of the last linear problem is at most
/// χ²_m(P), the P-quantile of χ² with m degrees of freedom (m readings; [`solve::chi2_bar`];
/// Backus 1970; Stark 1992). Unlike the band, they show what the readings alone leave open, e.g. a
/// steep curve between two readings.
pub fn fit(
    tests: &[Test],
    bins: &Bins,
    model: Model,
    rule: LambdaRule,
    repeats: usize,
    seed: u64,
    bounds: Option<f64>,
) -> Result<Fit, Error> {
    // Ctrl-C/SIGTERM: checked at each iteration, repeat and bounded edge (issue 26: the first
    // signal used to be acknowledged and ignored); nothing is written.
    let stopped = || Error::InterruptedUnwritten(tests[0].file.clone());
    let inv = iterate(tests, bins, model, rule)?;
    let mut curve = band(&inv, tests, bins, rule, repeats, seed).ok_or_else(stopped)?;
    if let Some(confidence) = bounds {
        let bar = solve::chi2_bar(inv.predicted.len(), confidence);
        for p in &mut curve {
            if crate::interrupt::requested() {
                return Err(stopped());
            }
            let c: Vec<f64> = (0..bins.len())
                .map(|j| bins.fraction_finer(j, p.diameter_m))
                .collect();
            p.bounds = inv
                .linear
                .strict_bounds(&c, bar)
                .map(|(lo, hi)| ((100.0 * lo).max(0.0), (100.0 * hi).min(100.0)));
        }
    }
    Ok(Fit {
        w: inv.solution.w.clone(),
        curve,
        predicted: inv.predicted,
        lambda: inv.solution.lambda,
        chi2: inv.chi2,
        iterations: inv.iterations,
        converged: inv.converged,
    })
}

/// The result of the iterations.
struct Inversion {
    solution: solve::Solution,
    /// The last linear problem (for the band).
    linear: Linear,
    /// Predicted readings at the solution.
    predicted: Vec<f64>,
    chi2: f64,
    iterations: usize,
    converged: bool,
}

/// Largest change of the cumulative curve at the bin edges, points.
fn curve_change(bins: &Bins, a: &[f64], b: &[f64]) -> f64 {
    bins.edges_m
        .iter()
        .map(|&d| 100.0 * (bins.cumulative(a, d) - bins.cumulative(b, d)).abs())
        .fold(0.0, f64::max)
}

/// Gauss–Newton (and, for the full model, fixed point on the unit fields) until the curve
/// moves < 0.01 points (at most 40 iterations).
fn iterate(
    tests: &[Test],
    bins: &Bins,
    model: Model,
    rule: LambdaRule,
) -> Result<Inversion, Error> {
    let n = bins.len();
    let mut w = vec![1.0 / n as f64; n];
    let fields = |w: &[f64]| -> Vec<Vec<Vec<Vec<f64>>>> {
        tests
            .iter()
            .map(|t| unit_fields(&t.col, model.settling(), bins, w, &t.times_s))
            .collect()
    };
    let mut units = fields(&w);
    let (mut iterations, mut converged) = (0, false);
    let mut last = None;
    while iterations < 40 {
        if crate::interrupt::requested() {
            return Err(Error::InterruptedUnwritten(tests[0].file.clone()));
        }
        iterations += 1;
        let (lin, _) = linearise(tests, &units, &w)?;
        let sol = lin.solve(rule);
        let change = curve_change(bins, &sol.w, &w);
        w = sol.w.clone();
        last = Some((sol, lin));
        if model == Model::Full {
            units = fields(&w);
        }
        if change < 0.01 {
            converged = true;
            break;
        }
    }
    let (solution, _) = last.expect("at least one iteration");
    let (linear, predicted) = linearise(tests, &units, &w)?;
    let chi2 = tests
        .iter()
        .flat_map(|t| {
            t.readings
                .iter()
                .enumerate()
                .map(move |(i, r)| (r, t.sigma_at(i)))
        })
        .zip(&predicted)
        .map(|((r, s), p)| ((r - p) / s).powi(2))
        .sum();
    Ok(Inversion {
        solution,
        linear,
        predicted,
        chi2,
        iterations,
        converged,
    })
}

/// A standard normal deviate (Box–Muller).
fn normal(rng: &mut impl Rng) -> f64 {
    let u: f64 = rng.random::<f64>().max(1e-300);
    let v: f64 = rng.random();
    (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
}

/// p-th percentile (0–1) of sorted values, linear between ranks.
fn percentile(sorted: &[f64], p: f64) -> f64 {
    let x = p * (sorted.len() - 1) as f64;
    let (i, f) = (x.floor() as usize, x - x.floor());
    if i + 1 < sorted.len() {
        sorted[i] * (1.0 - f) + sorted[i + 1] * f
    } else {
        sorted[i]
    }
}

/// The recovered curve at the resolved edges with its 5–95 % Monte Carlo band: each repeat adds
/// to every reading a rounding error U(−Δ/2, Δ/2), a reading error N(0, Δ/√6) and its counting
/// error N(0, σ_count) (a run's readings files, [`Test::counting_sigma`]), draws the
/// penalty's target η = z/√λ (z standard normal: the Gaussian prior of the Tikhonov term) and
/// solves the last linear problem again with λ chosen by the same rule: a draw of the
/// constrained posterior, λ's own uncertainty included. None when a stop was requested
/// ([`crate::interrupt::requested`], checked at every repeat).
fn band(
    inv: &Inversion,
    tests: &[Test],
    bins: &Bins,
    rule: LambdaRule,
    repeats: usize,
    seed: u64,
) -> Option<Vec<CurvePoint>> {
    let edges = resolved_edges(bins);
    let w = &inv.solution.w;
    let mut samples: Vec<Vec<f64>> = vec![Vec::with_capacity(repeats); edges.len()];
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let res: Vec<(f64, f64)> = tests
        .iter()
        .flat_map(|t| (0..t.readings.len()).map(move |i| (t.resolution, t.counting_sigma[i])))
        .collect();
    for _ in 0..repeats {
        if crate::interrupt::requested() {
            return None;
        }
        let mut lin = inv.linear.clone();
        for (i, (d, c)) in res.iter().enumerate() {
            lin.b[i] += d * (rng.random::<f64>() - 0.5) + d / 6f64.sqrt() * normal(&mut rng);
            if *c > 0.0 {
                lin.b[i] += c * normal(&mut rng);
            }
        }
        let z: Vec<f64> = (0..w.len()).map(|_| normal(&mut rng)).collect();
        let s = lin.solve_drawn(rule, Some(&z));
        for (k, &d) in edges.iter().enumerate() {
            samples[k].push(100.0 * bins.cumulative(&s.w, d));
        }
    }
    let curve = edges
        .iter()
        .zip(samples.iter_mut())
        .map(|(&d, s)| {
            let f = 100.0 * bins.cumulative(w, d);
            s.sort_by(f64::total_cmp);
            let (p5, p95) = if s.is_empty() {
                (f, f)
            } else {
                (percentile(s, 0.05), percentile(s, 0.95))
            };
            CurvePoint {
                diameter_m: d,
                percent_finer: f,
                p5,
                p95,
                bounds: None,
            }
        })
        .collect();
    Some(curve)
}
