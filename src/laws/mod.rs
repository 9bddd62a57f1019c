//! `settle laws`: every drag law of a yield-stress fluid on a set of spheres with measured
//! terminal velocities, evaluated the same way (issue 15).
//!
//! By default the 121 spheres of Valentik & Whitmore (1965) in six clay suspensions (f-EDEM
//! Tables 2 and 3). Per law: the velocity error of the force-balance terminal velocity (mean,
//! median and max |error|, bias, within 10 % and 25 %), the force error at the measured speed
//! (drag(v_measured)/net weight − 1, the fair figure where the yield term dominates and the
//! velocity is ill-conditioned), the spheres predicted static or held on a jump, and for the law
//! with constants fitted to these spheres (f-EDEM's eq. 19) the leave-one-suspension-out
//! figures. Writes `OUT/laws/`: `laws.csv` (one row per law), `predictions.csv` (one row per law
//! and sphere), `cd_vs_re.svg` (f-EDEM Fig. 1 with every law), `parity.svg` (one panel per law)
//! and `error_vs_yield_number.svg`.
//!
//! # From Rust
//!
//! [`laws`] runs the command in memory ([`LawsOptions`]: the built-in spheres by default, or a
//! spheres file and its fluids file); it returns a [`LawsResult`] with both tables, the charts
//! as SVG text and the typed figures, and [`LawsResult::write`] writes the folder the command
//! writes.

pub mod charts;
pub mod data;
pub mod eval;
pub mod loso;

use crate::error::Error;
use crate::io::fmt::{g, num, opt, pct, sig};
use crate::io::metrics::ErrorStats;
use crate::io::{self, Outputs, Table};
use data::DataSet;
use eval::{Law, LawResult, State};
use std::path::{Path, PathBuf};

/// The sphere issue 15 follows: measured at 0.22 m/s, held static by f-EDEM's law.
pub const WATCHED_SPHERE: &str = "S3-04";

/// The options of `settle laws`: the spheres and their fluids (both files, or neither for the
/// built-in Valentik–Whitmore spheres).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LawsOptions {
    /// `SPHERES`: a spheres CSV (needs `fluids`); None for the built-in spheres.
    pub spheres: Option<PathBuf>,
    /// `--fluids`: the fluids CSV of `spheres` (needs `spheres`).
    pub fluids: Option<PathBuf>,
}

/// What `settle laws` is asked to do on the command line ([`run`]).
#[derive(Clone, Debug, Default)]
pub struct Request {
    /// A spheres CSV and its fluids CSV; None for the built-in Valentik–Whitmore spheres.
    pub files: Option<(PathBuf, PathBuf)>,
    /// Output folder; results go to `out_dir/laws/`.
    pub out_dir: PathBuf,
}

/// What `settle laws` produced, in memory: the tables and files it writes (`laws.csv`,
/// `predictions.csv`, `cd_vs_re.svg`, `parity.svg`, `error_vs_yield_number.svg`) and the
/// typed figures.
#[derive(Clone, Debug)]
pub struct LawsResult {
    /// The results folder's name, `laws`.
    pub name: String,
    /// The data set evaluated.
    pub data: DataSet,
    /// One result per law, in [`Law::ALL`] order.
    pub results: Vec<LawResult>,
    /// Refitted eq. 19 constants (a, b) on all spheres, if any Bingham fluid has points in range.
    pub refit_all: Option<(f64, f64)>,
    /// Validity warnings (none so far: the command prints none).
    pub warnings: Vec<String>,
    /// The tables and files of `OUT/laws/`.
    pub outputs: Outputs,
}

impl LawsResult {
    /// The table of the file `name` (`laws`, `predictions`, or with `.csv`).
    pub fn table(&self, name: &str) -> Option<&Table> {
        self.outputs.get(name)
    }

    /// Writes `out_dir/laws/` as `settle laws --out OUT_DIR` does (staged, then moved into
    /// place; refused when that folder exists and was not made by settle); returns the folder.
    pub fn write(&self, out_dir: impl AsRef<Path>) -> Result<PathBuf, Error> {
        self.outputs.write_folder(out_dir.as_ref(), &self.name)
    }

    /// The console table of `settle laws`, the results written to `out`.
    pub fn lines(&self, out: &Path) -> Vec<String> {
        console(&self.data, &self.results, self.refit_all, out)
    }
}

/// What `settle laws` did on the command line ([`run`]).
#[derive(Clone, Debug)]
pub struct Report {
    /// The results folder.
    pub out: PathBuf,
    /// Console lines.
    pub lines: Vec<String>,
    /// The evaluation.
    pub result: LawsResult,
}

/// `settle laws` in memory: reads the spheres and fluids (or takes the built-in ones),
/// evaluates every law and makes the outputs. A spheres file without its fluids file (or the
/// reverse) is [`Error::BadInput`] naming the missing option; a bad file names the file, row
/// and column, as on the command line.
///
/// ```no_run
/// use settle::laws::{laws, LawsOptions};
/// let r = laws(&LawsOptions::default())?;
/// let mean = r.table("laws").unwrap().f64s("mean_abs_rel_error");
/// r.write("out")?; // out/laws/
/// # Ok::<(), settle::Error>(())
/// ```
pub fn laws(opts: &LawsOptions) -> Result<LawsResult, Error> {
    let data = match (&opts.spheres, &opts.fluids) {
        (Some(s), Some(f)) => DataSet::read(s, f)?,
        (None, None) => DataSet::valentik(),
        (Some(s), None) => {
            return Err(Error::bad_argument(
                "--fluids",
                s,
                "missing: a spheres file needs the fluids file of its suspensions (--fluids)",
            ))
        }
        (None, Some(f)) => {
            return Err(Error::bad_argument(
                "SPHERES",
                f,
                "missing: a fluids file needs the spheres file it describes (SPHERES)",
            ))
        }
    };
    let results = evaluate(&data);
    let pts: Vec<(f64, f64)> = data
        .spheres
        .iter()
        .filter_map(|s| loso::point(&data, s))
        .collect();
    let refit_all = loso::fit_eq19(&pts);
    let ioe =
        |file: &'static str| move |e: std::io::Error| Error::Io(Path::new("laws").join(file), e);
    let mut outputs = Outputs::new();
    outputs.set_owner(owner(opts));
    outputs.table(laws_table(&data, &results));
    outputs.table(predictions_table(&data, &results));
    outputs
        .chart("cd_vs_re.svg", &charts::cd_vs_re(&data, &results))
        .map_err(ioe("cd_vs_re.svg"))?;
    outputs
        .grid_chart(
            "parity.svg",
            charts::PARITY_TITLE,
            &charts::parity(&data, &results),
            3,
        )
        .map_err(ioe("parity.svg"))?;
    outputs
        .chart(
            "error_vs_yield_number.svg",
            &charts::error_vs_yield_number(&data, &results),
        )
        .map_err(ioe("error_vs_yield_number.svg"))?;
    Ok(LawsResult {
        name: "laws".into(),
        data,
        results,
        refit_all,
        warnings: Vec::new(),
        outputs,
    })
}

/// The owner of `OUT/laws/` for `opts`: the built-in data or the two files.
fn owner(opts: &LawsOptions) -> io::Owner {
    match (&opts.spheres, &opts.fluids) {
        (Some(s), Some(f)) => io::Owner::of_files("laws", &[s, f]),
        _ => io::Owner::new("laws", "the built-in data of Valentik & Whitmore (1965)"),
    }
}

/// Runs `settle laws`: [`laws`], then [`LawsResult::write`] into `OUT/laws/` (the output folder
/// checked first).
pub fn run(req: &Request) -> Result<Report, Error> {
    let (spheres, fluids) = req.files.clone().unzip();
    let opts = LawsOptions { spheres, fluids };
    io::owner::check_out_dir(&req.out_dir)?;
    io::owner::check_owned(&req.out_dir.join("laws"), &owner(&opts))?;
    let result = laws(&opts)?;
    let out = result.write(&req.out_dir)?;
    Ok(Report {
        lines: result.lines(&out),
        out,
        result,
    })
}

/// Every law of [`Law::ALL`] on `data`, with the leave-one-suspension-out figures of the law
/// with fitted constants.
pub fn evaluate(data: &DataSet) -> Vec<LawResult> {
    Law::ALL
        .iter()
        .map(|&law| {
            let mut r = LawResult::of(law, data);
            if law.fitted_to_valentik() {
                let (preds, _) = loso::loso_fedem(data);
                let errs: Vec<f64> = preds
                    .iter()
                    .map(|&(i, v, _)| v / data.spheres[i].v_measured_m_s - 1.0)
                    .collect();
                if !errs.is_empty() {
                    r.loso = Some(ErrorStats::of(law.key(), &errs));
                }
            }
            r
        })
        .collect()
}

/// Columns of `laws.csv`.
pub const LAWS_HEADER: [&str; 20] = [
    "law",
    "fitted_to_these_spheres",
    "n",
    "n_static",
    "n_jump",
    "mean_abs_rel_error",
    "median_abs_rel_error",
    "max_abs_rel_error",
    "bias_rel_error",
    "fraction_within_10pct",
    "fraction_within_25pct",
    "force_mean_abs_rel_error",
    "force_median_abs_rel_error",
    "force_bias_rel_error",
    "force_fraction_within_10pct",
    "loso_mean_abs_rel_error",
    "loso_fraction_within_25pct",
    "meets_aim",
    "watched_sphere_v_predicted_m_s",
    "watched_sphere_state",
];

/// `laws.csv`: one row per law.
fn laws_table(data: &DataSet, results: &[LawResult]) -> Table {
    let rows: Vec<Vec<String>> = results
        .iter()
        .map(|r| {
            let w = r.for_sphere(data, WATCHED_SPHERE);
            vec![
                r.law.key(),
                r.law.fitted_to_valentik().to_string(),
                r.velocity.n.to_string(),
                r.n_static.to_string(),
                r.n_jump.to_string(),
                num(r.velocity.mean_abs),
                num(r.velocity.median_abs),
                num(r.velocity.max_abs),
                num(r.velocity.bias),
                num(r.velocity.within_10pct),
                num(r.velocity.within_25pct),
                num(r.force.mean_abs),
                num(r.force.median_abs),
                num(r.force.bias),
                num(r.force.within_10pct),
                opt(r.loso.as_ref().map(|l| l.mean_abs)),
                opt(r.loso.as_ref().map(|l| l.within_25pct)),
                r.meets_aim().to_string(),
                opt(w.map(|p| p.v_predicted_m_s)),
                w.map(|p| p.state.label()).unwrap_or("").to_string(),
            ]
        })
        .collect();
    Table::with_rows("laws.csv", LAWS_HEADER, rows)
}

/// Columns of `predictions.csv`.
pub const PREDICTIONS_HEADER: [&str; 10] = [
    "law",
    "sphere_id",
    "suspension",
    "diameter_m",
    "yield_number",
    "v_measured_m_s",
    "v_predicted_m_s",
    "state",
    "rel_error",
    "force_rel_error",
];

/// `predictions.csv`: one row per law and sphere.
fn predictions_table(data: &DataSet, results: &[LawResult]) -> Table {
    let mut rows = Vec::new();
    for r in results {
        for p in &r.predictions {
            let s = &data.spheres[p.sphere];
            rows.push(vec![
                r.law.key(),
                s.id.clone(),
                data.fluids[s.fluid].name.clone(),
                num(s.diameter_m),
                num(eval::yield_number(data, s)),
                num(s.v_measured_m_s),
                num(p.v_predicted_m_s),
                p.state.label().to_string(),
                num(p.rel_error),
                num(p.force_rel_error),
            ]);
        }
    }
    Table::with_rows("predictions.csv", PREDICTIONS_HEADER, rows)
}

/// The console table and the closing verdict.
fn console(
    data: &DataSet,
    results: &[LawResult],
    refit_all: Option<(f64, f64)>,
    out: &std::path::Path,
) -> Vec<String> {
    let mut lines =
        vec![
            format!(
                "settle laws: {} spheres, {}",
                data.spheres.len(),
                data.source
            ),
            format!(
            "  {:<22} {:>3} {:>9} {:>9} {:>9} {:>9} {:>7} {:>7} {:>10} {:>4} {:>4} {:>9} {:>10}",
            "law", "n", "mean|err|", "median", "max", "bias", "≤10%", "≤25%", "F mean|err|",
            "stat", "jump", "LOSO mean", WATCHED_SPHERE
        ),
        ];
    // A law with no sphere to judge (a Bingham law on Herschel–Bulkley fluids) has no figures:
    // `-`, explained below the table, rather than `NaN%`.
    let p = |x: f64| if x.is_finite() { pct(x, 3) } else { "-".into() };
    let u = |x: f64| {
        if x.is_finite() {
            format!("{}%", sig(100.0 * x, 3))
        } else {
            "-".into()
        }
    };
    let no_figures: Vec<String> = results
        .iter()
        .filter(|r| r.velocity.n == 0 || !r.velocity.mean_abs.is_finite())
        .map(|r| r.law.key())
        .collect();
    for r in results {
        let v = &r.velocity;
        let none = v.n == 0;
        let u = |x: f64| if none { "-".into() } else { u(x) };
        let p = |x: f64| if none { "-".into() } else { p(x) };
        let w = r
            .for_sphere(data, WATCHED_SPHERE)
            .map(|p| match p.state {
                State::Moving => format!("{} m/s", g(p.v_predicted_m_s)),
                st => st.label().to_string(),
            })
            .unwrap_or_else(|| "-".into());
        lines.push(format!(
            "  {:<22} {:>3} {:>9} {:>9} {:>9} {:>9} {:>7} {:>7} {:>10} {:>4} {:>4} {:>9} {:>10}",
            r.law.key() + if r.law.fitted_to_valentik() { " *" } else { "" },
            v.n,
            u(v.mean_abs),
            u(v.median_abs),
            u(v.max_abs),
            p(v.bias),
            u(v.within_10pct),
            u(v.within_25pct),
            u(r.force.mean_abs),
            r.n_static,
            r.n_jump,
            r.loso
                .as_ref()
                .map(|l| u(l.mean_abs))
                .unwrap_or_else(|| "-".into()),
            w
        ));
    }
    lines.push(
        "  * constants fitted to these spheres (f-EDEM eq. 19); LOSO: refitted on the other \
         suspensions, predicting the held-out one"
            .into(),
    );
    if !no_figures.is_empty() {
        lines.push(format!(
            "  -: no figure for {}: no sphere of these fluids has a prediction by that law (a \
             law for Bingham fluids is not applied to a Herschel–Bulkley fluid, flow_index ≠ 1)",
            no_figures.join(", ")
        ));
    }
    if let Some((a, b)) = refit_all {
        lines.push(format!(
            "  eq. 19 refitted to all (Re′, C_d) points with 1 ≤ Re′ ≤ 150 (least squares in C_d): \
             C_d = {}/Re′ + {} (f-EDEM: 29.12/Re′ + 0.195)",
            g(a),
            g(b)
        ));
    }
    lines.push(verdict(results));
    lines.push(format!("-> {}", out.display()));
    lines
}

/// The closing sentence: which laws reach the aim (mean |error| ≤ 15 % and ≥ 85 % within 25 %)
/// without being tuned to these spheres.
pub fn verdict(results: &[LawResult]) -> String {
    let untuned: Vec<String> = results
        .iter()
        .filter(|r| !r.law.fitted_to_valentik() && r.meets_aim())
        .map(|r| r.law.key())
        .collect();
    if untuned.is_empty() {
        "  aim (mean |error| ≤ 15 % and ≥ 85 % within 25 %, untuned): no law reaches it".into()
    } else {
        format!(
            "  aim (mean |error| ≤ 15 % and ≥ 85 % within 25 %, untuned): reached by {}",
            untuned.join(", ")
        )
    }
}
