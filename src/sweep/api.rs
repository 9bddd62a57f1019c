//! `settle sweep` in memory: [`sweep`] runs a dt sweep of one [`Scenario`] and returns its
//! tables and files ([`SweepResult`]); [`SweepResult::write`] writes the folder the command
//! line writes. The command line runs through the same function for each scenario file.
//!
//! Split over processes or machines: [`sweep_part`] runs one shard of the grid (`--shard I/N`)
//! into a [`SweepPart`] (the rows of the part file `sweep_part_I_of_N.csv`, as CSV text with
//! [`SweepPart::to_csv`]), and [`sweep_merge`] joins the parts of one split into the
//! [`SweepResult`] that [`sweep`] returns (`--merge`). The Python package spreads the parts over
//! any `concurrent.futures.Executor` this way.

use super::analysis::rayleigh_time_of;
use super::cases::run;
use super::page::add_report;
use super::plan::{Case, Plan, SweepOptions};
use super::report::{caveat, results, Context, Recommended, Report};
use super::shards::{ranges, PART_PREFIX};
use super::table::Row;
use super::table::{finish, from_csv, to_csv, HEADER};
use super::targets::Target;
use super::values::{parse_shard, Shard};
use crate::api::Scenario;
use crate::error::Error;
use crate::io::{Outputs, Table};
use crate::scenes::Prepared;
use std::path::{Path, PathBuf};

/// What a dt sweep made, in memory: the tables and files of `OUT/<name>_sweep/` (`sweep.csv`,
/// `recommended_dt.csv`, the charts `quantity_vs_dt.svg`, `speed_accuracy.svg` (and
/// `counts_vs_dt.svg` for a funnel pour), `report.html`), the typed rows and recommended time
/// steps, and the lines `settle sweep` prints.
#[derive(Clone, Debug)]
pub struct SweepResult {
    name: String,
    /// The grid that ran: integrators × time steps, and the tolerance.
    pub plan: Plan,
    /// Every row of `sweep.csv` (one per integrator, dt, body and quantity), in its order.
    pub rows: Vec<Row>,
    /// The recommended dt of each integrator swept (the rows of `recommended_dt.csv`).
    pub recommended: Vec<Recommended>,
    /// The tables and files of `OUT/<name>_sweep/`; each table equals the CSV file the command
    /// line writes, cell for cell (wall times aside: `wall_time_s` measures the machine).
    pub outputs: Outputs,
    /// The caveats of the recommended time steps: an integrator with none in the grid, or whose
    /// recommended dt is the finest stable dt tried (unverified). The command line prints them
    /// among [`SweepResult::lines`].
    pub warnings: Vec<String>,
    /// The lines `settle sweep` prints: the table of cases, then one line per recommended dt
    /// (without the last line, `  -> <folder>`, which names where it wrote).
    pub lines: Vec<String>,
}

impl SweepResult {
    /// The results folder's name, `<scenario name>_sweep`.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The table of the file `name`, by stem (`sweep`, `recommended_dt`) or file name.
    pub fn table(&self, name: &str) -> Option<&Table> {
        self.outputs.get(name)
    }

    /// Every table, in the order they were made.
    pub fn tables(&self) -> &[Table] {
        self.outputs.tables()
    }

    /// Writes `out_dir/<name>_sweep/` as `settle sweep --out OUT_DIR` does (the same files,
    /// byte for byte except wall times): staged, then moved into place; refused when that
    /// folder exists and was not made by settle. Returns the folder.
    pub fn write(&self, out_dir: impl AsRef<Path>) -> Result<PathBuf, Error> {
        self.outputs.write_folder(out_dir.as_ref(), &self.name)
    }
}

/// `settle sweep` in memory: runs `scenario` at every (integrator, dt) of the grid `opts`
/// gives (with the defaults of `settle sweep`: the scenario's `[sweep]` table), in parallel,
/// and compares each quantity with its reference and with the finest stable dt of the same
/// integrator. Kinds `free_settling`, `drop` and `funnel_pour` can be swept. A bad option (a
/// dt ≤ 0, an unknown integrator, a tolerance outside (0, 1]) or a kind that cannot be swept
/// is [`Error::BadInput`] with the command line's message, before anything runs; Ctrl-C
/// ([`crate::interrupt::request`]) stops it with [`Error::InterruptedUnwritten`].
///
/// ```no_run
/// use settle::sweep::{sweep, SweepOptions};
/// let scenario = settle::load("scenarios/stokes_single.toml")?;
/// let opts = SweepOptions {
///     dts: vec![1e-3, 1e-4, 1e-5], // s
///     integrators: vec!["explicit".into(), "exponential".into()],
///     ..SweepOptions::default()
/// };
/// let r = sweep(&scenario, &opts)?;
/// for rec in &r.recommended {
///     println!("{}: {:?} s", rec.integrator.name(), rec.dt_s);
/// }
/// let errors = r.table("sweep").unwrap().f64s("error_vs_finest");
/// r.write("out")?; // out/stokes_single_sweep/: what `settle sweep --out out` writes
/// # Ok::<(), settle::Error>(())
/// ```
pub fn sweep(scenario: &Scenario, opts: &SweepOptions) -> Result<SweepResult, Error> {
    let p = scenario.prepared();
    Target::of(p)?;
    let plan = Plan::new(opts, p, None)?;
    compute(p, plan, opts.progress)
}

/// The owner of the folder of the sweep of the scenario named `name`.
pub(crate) fn owner(name: &str) -> crate::io::Owner {
    crate::io::Owner::scenario("sweep", name)
}

/// Runs the whole grid of `plan` (not a shard) of `p` with a progress bar (hidden unless
/// `progress`) and makes every output.
pub(crate) fn compute(p: &Prepared, plan: Plan, progress: bool) -> Result<SweepResult, Error> {
    let rows = run_with_bar(p, &plan, progress)?;
    assemble(p, plan, rows)
}

/// Runs the cases of `plan` (its shard, or all: then finished) with a progress bar hidden
/// unless `progress`.
pub(crate) fn run_with_bar(p: &Prepared, plan: &Plan, progress: bool) -> Result<Vec<Row>, Error> {
    let bar = crate::progress::bar(
        plan.cases_to_run().len() as u64,
        &p.common.name,
        "cases, {per_sec},",
        !progress,
    );
    let rows = run(p, plan, &|| bar.inc(1))?;
    bar.finish_and_clear();
    Ok(rows)
}

/// The result of the finished `rows` of the whole grid of `plan`: every output, the
/// recommended time steps and their caveats, the console lines.
fn assemble(p: &Prepared, plan: Plan, rows: Vec<Row>) -> Result<SweepResult, Error> {
    let name = format!("{}_sweep", p.common.name);
    let cx = Context {
        title: &p.common.name,
        tol: plan.tol,
        rayleigh_time_s: rayleigh_time_of(p),
    };
    let Report {
        mut outputs,
        recommended,
        lines,
    } = results(&rows, &cx)?;
    add_report(&mut outputs, &name)?;
    outputs.set_owner(owner(&p.common.name));
    let warnings = recommended.iter().filter_map(|r| caveat(r, &cx)).collect();
    Ok(SweepResult {
        name,
        plan,
        rows,
        recommended,
        outputs,
        warnings,
        lines,
    })
}

/// One shard of a dt sweep ([`sweep_part`]): shard `index` of `count` (1-based, as
/// `--shard I/N`) and its rows, without `error_vs_finest` (filled by [`sweep_merge`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SweepPart {
    /// Which shard, 1 ≤ index ≤ count.
    pub index: usize,
    /// How many shards the grid was split into.
    pub count: usize,
    /// The rows of the shard's cases, as `sweep_part_I_of_N.csv` holds them.
    pub rows: Vec<Row>,
}

impl SweepPart {
    /// The rows as the text of the part file `sweep_part_I_of_N.csv` (the header of
    /// `sweep.csv`, numbers that read back to the same `f64`).
    pub fn to_csv(&self) -> Result<String, Error> {
        let io = |e| Error::Io(self.file_name().into(), e);
        let bytes = to_csv(&self.rows).map_err(io)?;
        String::from_utf8(bytes).map_err(|e| io(std::io::Error::other(e)))
    }

    /// Shard `index` of `count` from the text of its part file ([`SweepPart::to_csv`]); text
    /// that is not a sweep part table is a bad argument naming the part.
    pub fn from_csv(index: usize, count: usize, text: &str) -> Result<Self, Error> {
        let rows = parse_part(text)
            .map_err(|e| Error::bad_argument("part", Path::new(&format!("{index}/{count}")), e))?;
        Ok(Self { index, count, rows })
    }

    /// The name of the part file, `sweep_part_I_of_N.csv`.
    pub fn file_name(&self) -> String {
        format!("{PART_PREFIX}{}_of_{}.csv", self.index, self.count)
    }
}

/// The rows of a part file's text: the header of `sweep.csv`, then rows; else why not.
pub(crate) fn parse_part(text: &str) -> Result<Vec<Row>, String> {
    if text.lines().next() != Some(HEADER.join(",").as_str()) {
        return Err("not a sweep part table: its first line is not the header of sweep.csv".into());
    }
    from_csv(text.as_bytes()).map_err(|e| format!("not a sweep part table: {e}"))
}

/// `index/count` as a shard, 1 ≤ index ≤ count; else a bad argument of `--shard`.
pub(crate) fn shard_of(index: usize, count: usize) -> Result<Shard, Error> {
    let text = format!("{index}/{count}");
    parse_shard(&text).map_err(|e| Error::bad_argument("--shard", Path::new(&text), e.to_string()))
}

/// Checks that `parts` (index, count of each) are one whole split: the same count, each index
/// 1..=count exactly once; else a bad argument of `parts` saying what is missing or extra.
/// Returns the count.
pub(crate) fn check_parts(parts: &[(usize, usize)]) -> Result<usize, Error> {
    let listed: Vec<String> = parts.iter().map(|(i, n)| format!("{i}/{n}")).collect();
    let bad = |why: String| {
        Error::bad_argument(
            "parts",
            Path::new(&listed.join(", ")),
            format!("{why}: nothing merged"),
        )
    };
    let Some(&(_, count)) = parts.first() else {
        return Err(bad("no parts".into()));
    };
    if let Some((_, n)) = parts.iter().find(|(_, n)| *n != count) {
        return Err(bad(format!(
            "parts of a split into {count} and of a split into {n} shards: give the parts of \
             one split"
        )));
    }
    let mut seen = vec![0usize; count + 1];
    for &(i, n) in parts {
        shard_of(i, n)?;
        seen[i] += 1;
    }
    let twice: Vec<usize> = (1..=count).filter(|&i| seen[i] > 1).collect();
    let missing: Vec<usize> = (1..=count).filter(|&i| seen[i] == 0).collect();
    if !twice.is_empty() {
        return Err(bad(format!(
            "shards {} given more than once: allowed each index 1..={count} exactly once",
            ranges(&twice)
        )));
    }
    if !missing.is_empty() {
        return Err(bad(format!(
            "{} of {count} shards missing ({}): give each index 1..={count} exactly once",
            missing.len(),
            ranges(&missing)
        )));
    }
    Ok(count)
}

/// The cases of the grid `opts` gives for `scenario` (integrators × time steps, as [`sweep`]
/// runs them), every option checked as [`sweep`] checks it; nothing runs. For choosing how
/// many parts to split a sweep into ([`sweep_part`]).
pub fn sweep_cases(scenario: &Scenario, opts: &SweepOptions) -> Result<Vec<Case>, Error> {
    let p = scenario.prepared();
    Target::of(p)?;
    Ok(Plan::new(opts, p, None)?.cases())
}

/// Shard `index` of `count` (1-based, as `settle sweep --shard I/N`: the cases whose position
/// in the grid ≡ index − 1 mod count) of the dt sweep [`sweep`] runs with the same `scenario`
/// and `opts`; the options are checked as [`sweep`] checks them, and `index`/`count` must
/// satisfy 1 ≤ index ≤ count. Join the parts with [`sweep_merge`]; a part travels as the text
/// of [`SweepPart::to_csv`] (read back with [`SweepPart::from_csv`]).
///
/// ```no_run
/// use settle::sweep::{sweep_merge, sweep_part, SweepOptions, SweepPart};
/// let scenario = settle::load("scenarios/stokes_single.toml")?;
/// let opts = SweepOptions { dts: vec![1e-3, 1e-4, 1e-5], ..SweepOptions::default() }; // s
/// let mut parts = Vec::new();
/// for i in 1..=3 {
///     // each could run in another process or on another machine
///     let text = sweep_part(&scenario, &opts, i, 3)?.to_csv()?;
///     parts.push(SweepPart::from_csv(i, 3, &text)?);
/// }
/// let r = sweep_merge(&scenario, &opts, parts)?; // what sweep(&scenario, &opts) returns
/// println!("{}", r.lines.join("\n"));
/// # Ok::<(), settle::Error>(())
/// ```
pub fn sweep_part(
    scenario: &Scenario,
    opts: &SweepOptions,
    index: usize,
    count: usize,
) -> Result<SweepPart, Error> {
    let shard = shard_of(index, count)?;
    let p = scenario.prepared();
    Target::of(p)?;
    let plan = Plan::new(opts, p, Some(shard))?;
    let rows = run_with_bar(p, &plan, opts.progress)?;
    Ok(SweepPart { index, count, rows })
}

/// Joins the parts of one split of the dt sweep of `scenario` with `opts` ([`sweep_part`],
/// each index 1..=count exactly once, any order) into what [`sweep`] returns: the same rows,
/// tables, charts and lines, cell for cell (wall times aside). Parts missing, given twice, of
/// different splits, or with a case outside the grid of `opts` are a bad argument saying which;
/// nothing is merged then.
pub fn sweep_merge(
    scenario: &Scenario,
    opts: &SweepOptions,
    parts: Vec<SweepPart>,
) -> Result<SweepResult, Error> {
    let p = scenario.prepared();
    Target::of(p)?;
    let plan = Plan::new(opts, p, None)?;
    let shards: Vec<(usize, usize)> = parts.iter().map(|s| (s.index, s.count)).collect();
    check_parts(&shards)?;
    let cases = plan.cases();
    let mut rows: Vec<Row> = Vec::new();
    for part in parts {
        let outside = part.rows.iter().find(|r| {
            !cases
                .iter()
                .any(|c| c.integrator == r.integrator && c.dt_s == r.dt_s)
        });
        if let Some(r) = outside {
            return Err(Error::bad_argument(
                "parts",
                Path::new(&part.file_name()),
                format!(
                    "has a case outside the grid of the options ({}, dt {} s): the parts are \
                     of another sweep; nothing merged",
                    r.integrator.name(),
                    crate::io::fmt::num(r.dt_s)
                ),
            ));
        }
        rows.extend(part.rows);
    }
    finish(&mut rows);
    assemble(p, plan, rows)
}
