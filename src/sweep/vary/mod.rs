//! Parameter sweeps on any key: `settle sweep S.toml --vary KEY=GRID [--vary KEY2=GRID2 …]`
//! runs the scenario once per point of the full grid, each value applied as `--set KEY=VALUE`,
//! at the scenario's own dt and integrator, and writes `OUT/<name>_vary/`: `vary.csv` (one row
//! per case and body, [`VaryTable`]) and one chart per result quantity against the first key
//! (`<quantity>_vs_<key>.svg`). A key may take words or booleans (`transient.history=off,basset`,
//! a categorical axis: one x position per value on the charts). Every case is loaded and validated before any runs (a bad key
//! or an out-of-range value exits 2 with nothing written); the kinds are those of the dt sweep
//! ([`crate::scenario::KindInfo::sweepable`]). `--shard I/N` runs a slice of the grid into
//! `vary_part_I_of_N.csv`, and `--merge` joins the parts, as for dt sweeps.
//!
//! | file | job |
//! |---|---|
//! | `grid.rs` | `--vary` parsing, the grid's values and points; pure |
//! | `table.rs` | [`VaryTable`]: the wide CSV, read, write, merge |
//! | `chart.rs` | the charts and the console lines |

mod chart;
mod grid;
mod table;

pub use chart::{charts, console_lines, unit_of};
pub use grid::{count, parse_vary, points, Axis, Level, MAX_CASES};
pub use table::VaryTable;

use super::args::Args;
use super::plan::Case;
use super::targets::Target;
use super::values::Shard;
use crate::error::{BadInput, Error};
use crate::io::StagedDir;
use crate::run::prepare;
use crate::scenes::Prepared;
use std::path::{Path, PathBuf};
// Re-exported for the unit tests only.

/// Name prefix of the part files of a sharded parameter sweep.
pub const PART_PREFIX: &str = "vary_part_";

/// One case of a parameter sweep: its point (a value per key) and the scenario with those
/// values applied, validated.
#[derive(Clone, Debug)]
pub struct VaryCase {
    /// The value of each key, in the order of the axes.
    pub point: Vec<Level>,
    /// The scenario with `--set` and the point's values applied.
    pub prepared: Prepared,
}

/// A parameter sweep of one scenario: the axes and the cases this process runs, every case of
/// the grid validated.
#[derive(Clone, Debug)]
pub struct VaryPlan {
    /// The scenario with `--set` applied, without the varied values.
    pub base: Prepared,
    /// The varied keys and their values.
    pub axes: Vec<Axis>,
    /// The cases to run: the shard's, or every case.
    pub cases: Vec<VaryCase>,
    /// Run only this slice of the grid (cases whose index ≡ I − 1 mod N).
    pub shard: Option<Shard>,
}

impl VaryPlan {
    /// Loads `file` with `set`, refuses a kind that cannot be swept, a key given twice and a
    /// grid over [`MAX_CASES`], then loads and validates every point of the grid (values
    /// applied after `set`): a bad key or an out-of-range value is a bad input naming the key,
    /// the value and the allowed range, before any case runs.
    pub fn new(
        file: &Path,
        set: &[String],
        axes: &[Axis],
        shard: Option<Shard>,
    ) -> Result<Self, Error> {
        let base = prepare(file, None, set)?;
        Target::of(&base)?;
        for (i, a) in axes.iter().enumerate() {
            if axes[..i].iter().any(|b| b.key == a.key) {
                return Err(Error::bad_argument(
                    "--vary",
                    Path::new(&a.key),
                    "this key is varied twice: allowed one --vary per key",
                ));
            }
        }
        let n = count(axes);
        if n > MAX_CASES {
            return Err(Error::bad_argument(
                "--vary",
                file,
                format!("the grid has {n} cases: allowed at most {MAX_CASES} (one run each)"),
            ));
        }
        let mut cases = Vec::new();
        for (i, point) in points(axes).into_iter().enumerate() {
            let mut ov = set.to_vec();
            ov.extend(
                axes.iter()
                    .zip(&point)
                    .map(|(a, v)| format!("{}={}", a.key, v.override_text())),
            );
            let text: Vec<String> = axes
                .iter()
                .zip(&point)
                .map(|(a, v)| format!("{} = {v}", a.key))
                .collect();
            let prepared = prepare(file, None, &ov).map_err(|e| {
                Error::BadInput(BadInput {
                    message: format!("--vary {}: {}", text.join(", "), e.message),
                    ..e
                })
            })?;
            if shard.is_none_or(|s| i % s.count == s.index - 1) {
                cases.push(VaryCase { point, prepared });
            }
        }
        Ok(Self {
            base,
            axes: axes.to_vec(),
            cases,
            shard,
        })
    }

    /// The varied keys.
    pub fn keys(&self) -> Vec<String> {
        self.axes.iter().map(|a| a.key.clone()).collect()
    }

    /// The output folder's name: `<name>_vary`.
    pub fn folder(&self) -> String {
        format!("{}_vary", self.base.scenario.name)
    }
}

/// Runs the plan's cases (in parallel; `done` after each) into a table. Ctrl-C/SIGTERM: no new
/// case starts, the running ones stop at their next check, and the sweep is an interrupted
/// run with nothing to write.
pub fn run(plan: &VaryPlan, done: &(dyn Fn() + Sync)) -> Result<VaryTable, Error> {
    use rayon::prelude::*;
    let cases: Vec<(Vec<Level>, Vec<super::Row>)> = plan
        .cases
        .par_iter()
        .map(|c| {
            if crate::interrupt::requested() {
                return (c.point.clone(), Vec::new());
            }
            let p = &c.prepared;
            let case = Case {
                integrator: p.scenario.time.integrator,
                dt_s: p.scenario.time.dt_s,
            };
            let rows = Target::of(p)
                .map(|t| t.run_case(p, &case))
                .unwrap_or_default();
            done();
            (c.point.clone(), rows)
        })
        .collect();
    if crate::interrupt::requested() {
        return Err(Error::InterruptedUnwritten(plan.base.path.clone()));
    }
    Ok(VaryTable::from_cases(&plan.keys(), cases))
}

/// `settle sweep --vary …`: plans every scenario (every case validated), checks the output
/// folders, then sweeps each into `OUT/<name>_vary/` (or its shard's part file).
pub fn main(args: &Args) -> Result<(), Error> {
    let out = args.out.clone().unwrap_or_else(|| PathBuf::from("out"));
    let mut plans = Vec::new();
    for f in &args.scenarios {
        plans.push(VaryPlan::new(f, &args.set, &args.vary, args.shard)?);
    }
    for plan in plans.iter().filter(|p| p.shard.is_none()) {
        crate::run::destination_allowed(&out.join(plan.folder()), &plan.base.path)?;
    }
    for plan in &plans {
        sweep_file(plan, &out, args.quiet)?;
    }
    Ok(())
}

/// Runs one plan and writes its outputs under `out`.
fn sweep_file(plan: &VaryPlan, out: &Path, quiet: bool) -> Result<(), Error> {
    let name = &plan.base.scenario.name;
    let bar = crate::progress::bar(plan.cases.len() as u64, name, "cases, {per_sec},", quiet);
    let table = run(plan, &|| bar.inc(1))?;
    bar.finish_and_clear();
    let folder = plan.folder();
    if let Some(Shard { index, count }) = plan.shard {
        let dir = out.join(&folder);
        std::fs::create_dir_all(&dir).map_err(|e| Error::Io(dir.clone(), e))?;
        let file = dir.join(format!("{PART_PREFIX}{index}_of_{count}.csv"));
        table.write(&file).map_err(|e| Error::Io(file.clone(), e))?;
        if !quiet {
            println!(
                "{name}: shard {index}/{count} ({} rows) -> {}",
                table.rows.len(),
                file.display()
            );
        }
        return Ok(());
    }
    let io = |e| Error::Io(out.join(&folder), e);
    let stage = StagedDir::new(out, &folder).map_err(io)?;
    write_results(&stage.path(""), name, &table, quiet)?;
    crate::io::report::write_report(&stage.path(""), &crate::io::report::Page::sweep(&folder))
        .map_err(io)?;
    let dest = stage.commit().map_err(io)?;
    if !quiet {
        println!("  -> {}", dest.display());
    }
    Ok(())
}

/// Writes `vary.csv` and the charts of a finished table into `dir`, and prints its console lines
/// unless `quiet`.
pub fn write_results(dir: &Path, title: &str, table: &VaryTable, quiet: bool) -> Result<(), Error> {
    let csv = dir.join("vary.csv");
    table.write(&csv).map_err(|e| Error::Io(csv.clone(), e))?;
    charts(dir, title, table)?;
    if !quiet {
        println!("{}", console_lines(title, table).join("\n"));
    }
    Ok(())
}

/// The part files `vary_part_*.csv` of `dirs`, each folder's sorted by name (none: empty).
pub fn part_files(dirs: &[PathBuf]) -> Vec<PathBuf> {
    let mut all = Vec::new();
    for dir in dirs {
        let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
            .into_iter()
            .flatten()
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with(PART_PREFIX) && n.ends_with(".csv"))
            })
            .collect();
        files.sort();
        all.extend(files);
    }
    all
}

/// `--merge DIR…` of a sharded parameter sweep: joins the part `files` (same keys) into
/// `vary.csv` and its charts in `--out` (default: the first folder). The title is the name of
/// the scenario file if one is given, else the first folder's name without `_vary`.
pub fn merge(args: &Args, files: &[PathBuf]) -> Result<(), Error> {
    let mut table = VaryTable::default();
    for f in files {
        let part = VaryTable::read(f)
            .map_err(|e| Error::bad_input(f, None, format!("not a vary part table: {e}")))?;
        table
            .merge(part)
            .map_err(|e| Error::bad_input(f, None, format!("cannot merge this part: it {e}")))?;
    }
    table.sort();
    // The scenario's name: from its file if given, else from the folder `<name>_vary`.
    let title = match args.scenarios.first() {
        Some(f) => prepare(f, None, &args.set)?.scenario.name,
        None => args.merge[0]
            .file_name()
            .and_then(|n| n.to_str())
            .and_then(|n| n.strip_suffix("_vary"))
            .unwrap_or("vary")
            .to_string(),
    };
    let dest = args.out.clone().unwrap_or_else(|| args.merge[0].clone());
    std::fs::create_dir_all(&dest).map_err(|e| Error::Io(dest.clone(), e))?;
    write_results(&dest, &title, &table, args.quiet)?;
    if !args.quiet {
        println!(
            "merged {} parts ({} rows) -> {}",
            files.len(),
            table.rows.len(),
            dest.join("vary.csv").display()
        );
    }
    Ok(())
}
