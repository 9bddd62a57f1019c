//! Time-step sensitivity sweeps (`settle sweep`): every (integrator, dt) of a grid runs the
//! scenario; each measured quantity is compared with its analytic or force-balance reference
//! where one exists and with the finest stable dt of the same integrator. Cases run in
//! parallel; `--shard I/N` runs a slice of the grid so a cluster job array can share it, and
//! `--merge` joins the parts (see `docs/cluster.md`).
//!
//! # From Rust
//!
//! [`sweep`] runs a dt sweep of a [`crate::Scenario`] in memory with the options of the command
//! line ([`SweepOptions`], its defaults those of `settle sweep`) and returns a [`SweepResult`]:
//! every table and chart of `OUT/<name>_sweep/`, the typed rows and recommended time steps, the
//! console lines; [`SweepResult::write`] writes the folder the command writes. [`vary()`] does the
//! same for a parameter sweep (`settle sweep --vary`): [`VaryResult`], `OUT/<name>_vary/`.
//! [`sweep_part`] and [`sweep_merge`] ([`vary_part`], [`vary_merge`]) are `--shard` and
//! `--merge` in memory: each part runs anywhere (another process, another machine) and travels
//! as the text of its part file; the merge of all parts equals the whole sweep.
//!
//! ```no_run
//! use settle::sweep::{sweep, vary, Axis, SweepOptions, VaryOptions};
//! let scenario = settle::load("scenarios/stokes_single.toml")?;
//! let dt = sweep(&scenario, &SweepOptions { dts: vec![1e-3, 1e-4], ..Default::default() })?;
//! println!("{}", dt.lines.join("\n"));
//! let mu = Axis::parse("fluid.viscosity_pa_s=log:1e-3:1e-2:3")?; // viscosity, Pa·s
//! let v = vary(&scenario, &[mu], &VaryOptions::default())?;
//! println!("{:?}", v.table("vary").unwrap().f64s("terminal_velocity_m_s"));
//! # Ok::<(), settle::Error>(())
//! ```
//!
//! | file | job |
//! |---|---|
//! | `api.rs` | [`sweep`], [`SweepResult`]: a whole dt sweep in memory (the command line's too) |
//! | `args.rs` | the command line (clap), value parsers for `I/N`, `LO:HI`, `--tol` |
//! | `plan.rs` | [`SweepOptions`], [`Plan`]: integrators × dts (+ shard, tol) from the options and `[sweep]`; pure |
//! | `cases.rs` | runs the cases of a grid in parallel into rows |
//! | `targets.rs` | which kinds can be swept and the quantities each case yields; refuses others |
//! | `table.rs` | typed [`Row`]s, CSV read/write, `finish` (error against the finest dt) |
//! | `analysis.rs` | per-case summaries, recommended dt, Rayleigh time |
//! | `report.rs` | charts, `recommended_dt.csv`, console table, into an [`Outputs`](crate::Outputs) |
//! | `page.rs` | the report page `report.html` of the outputs |
//! | `vary/` | parameter sweeps on any key (`--vary KEY=GRID`): grid, table, charts, [`vary()`] |
//!
//! Every input is checked before any case runs: a scenario that does not load, a kind that
//! cannot be swept, or a scenario without time steps exits 2 with nothing written.

mod analysis;
mod api;
mod args;
mod cases;
pub(crate) mod costs;
mod page;
mod plan;
mod report;
pub(crate) mod shards;
mod table;
mod targets;
#[cfg(test)]
mod tests;
mod values;
pub mod vary;

pub use api::{sweep, sweep_cases, sweep_merge, sweep_part, SweepPart, SweepResult};
pub(crate) use args::Args;
pub(crate) use cases::run_cases;
pub use plan::{grid, Case, Plan, SweepOptions, DEFAULT_PER_DECADE, DEFAULT_TOL};
pub use report::Recommended;
pub(crate) use table::finish;
pub use table::{Row, Status};
pub use values::Shard;
pub use vary::{
    vary, vary_cases, vary_merge, vary_part, Axis, Level, VaryOptions, VaryPart, VaryResult,
};

use analysis::rayleigh_time_of;
use report::{results, Context};
use shards::PART_PREFIX;
#[cfg(test)]
use table::read_rows;
use table::write_rows;
use targets::Target;

use crate::error::Error;
use crate::run::prepare;
use crate::scenes::Prepared;
use std::path::{Path, PathBuf};
// Re-exported for the unit tests only.
#[cfg(test)]
pub(crate) use analysis::summarise;
#[cfg(test)]
pub(crate) use plan::{dt_range, shard};
#[cfg(test)]
use table::HEADER;
#[cfg(test)]
pub(crate) use table::{from_csv, to_csv};
#[cfg(test)]
pub(crate) use values::{parse_dt, parse_dt_range, parse_shard, parse_tol, DtRange};

/// `settle sweep`: checks every scenario and plan, then sweeps each file into
/// `OUT/<name>_sweep/` (or writes its shard's part file there), or merges part files; with
/// `--vary`, a parameter sweep ([`vary::main`]).
pub(crate) fn main(args: &Args) -> Result<(), Error> {
    if !args.merge.is_empty() {
        return merge(args);
    }
    if !args.vary.is_empty() {
        return vary::main(args);
    }
    let mut jobs = Vec::new();
    for f in &args.scenarios {
        let p = prepare(f, None, &args.set)?;
        Target::of(&p)?;
        let plan = Plan::resolve(args, &p)?;
        jobs.push((p, plan));
    }
    let out = args.out.clone().unwrap_or_else(|| PathBuf::from("out"));
    // A whole sweep replaces OUT/<name>_sweep/: refused before any case runs if settle did not
    // create it. (Shards only add their part files to it.)
    for (p, plan) in &jobs {
        if plan.shard.is_none() {
            let dest = out.join(format!("{}_sweep", p.common.name));
            crate::run::destination_allowed(&dest, &p.path, &api::owner(&p.common.name))?;
        }
    }
    for (p, plan) in &jobs {
        sweep_file(p, plan, &out, args.quiet)?;
    }
    Ok(())
}

/// Sweeps one prepared scenario into `out` (the whole grid through [`api::compute`], or one
/// shard into its part file).
fn sweep_file(p: &Prepared, plan: &Plan, out: &Path, quiet: bool) -> Result<(), Error> {
    let Some(Shard { index, count }) = plan.shard else {
        let r = api::compute(p, plan.clone(), !quiet)?;
        if !quiet {
            println!("{}", r.lines.join("\n"));
        }
        let dest = r.write(out)?;
        if !quiet {
            println!("  -> {}", dest.display());
        }
        return Ok(());
    };
    let rows = api::run_with_bar(p, plan, !quiet)?;
    let dir = out.join(format!("{}_sweep", p.common.name));
    std::fs::create_dir_all(&dir).map_err(|e| Error::Io(dir.clone(), e))?;
    let file = dir.join(format!("{PART_PREFIX}{index}_of_{count}.csv"));
    write_rows(&file, &rows).map_err(|e| Error::Io(file.clone(), e))?;
    shards::ShardCommand::of_this_process(count).record(&dir)?;
    if !quiet {
        println!(
            "{}: shard {index}/{count} ({} rows) -> {}",
            p.common.name,
            rows.len(),
            file.display()
        );
    }
    Ok(())
}

/// `--merge DIR` (repeatable): joins the part files, finishes and reports them into `--out`
/// (default: the first folder). A scenario file, if given, supplies the title, `[sweep] tol` and
/// the Rayleigh time.
fn merge(args: &Args) -> Result<(), Error> {
    let has = |prefix: &str| {
        args.merge
            .iter()
            .any(|d| !shards::Parts::of(d, prefix).files.is_empty())
    };
    match (has(PART_PREFIX), has(vary::PART_PREFIX)) {
        (true, true) => Err(Error::bad_argument(
            "--merge",
            &args.merge[0],
            "these folders hold parts of a dt sweep (sweep_part_*.csv) and of a parameter sweep \
             (vary_part_*.csv): merge each sweep's folder on its own",
        )),
        (false, true) => vary::merge(args),
        (_, false) => merge_dt(args),
    }
}

/// `--merge` of a dt sweep: see [`merge`].
fn merge_dt(args: &Args) -> Result<(), Error> {
    let prepared = args
        .scenarios
        .first()
        .map(|f| prepare(f, None, &args.set))
        .transpose()?;
    let files = shards::read_parts(&args.merge, PART_PREFIX, |f| {
        api::parse_part(&std::fs::read_to_string(f).map_err(|e| e.to_string())?)
    })?;
    if files.is_empty() {
        let dirs: Vec<String> = args.merge.iter().map(|d| d.display().to_string()).collect();
        return Err(Error::bad_argument(
            "--merge",
            Path::new(&dirs.join(" ")),
            "no sweep_part_*.csv in the given folders",
        ));
    }
    let mut rows: Vec<Row> = Vec::new();
    for (_, part) in &files {
        rows.extend_from_slice(part);
    }
    finish(&mut rows);
    let dest = args.out.clone().unwrap_or_else(|| args.merge[0].clone());
    std::fs::create_dir_all(&dest).map_err(|e| Error::Io(dest.clone(), e))?;
    let tol = args
        .tol
        .or_else(|| prepared.as_ref()?.common.sweep.as_ref()?.tol)
        .unwrap_or(DEFAULT_TOL);
    let cx = Context {
        title: prepared
            .as_ref()
            .map(|p| p.common.name.as_str())
            .unwrap_or("sweep"),
        tol,
        rayleigh_time_s: prepared.as_ref().and_then(rayleigh_time_of),
    };
    let report = results(&rows, &cx)?;
    if !args.quiet {
        println!("{}", report.lines.join("\n"));
    }
    // The page of the folder as it is: the merged outputs beside the part files.
    let io = |e| Error::Io(dest.clone(), e);
    report.outputs.write_into(&dest).map_err(io)?;
    crate::io::report::write_report(&dest, &crate::io::report::Page::sweep(cx.title))
        .map_err(io)?;
    if !args.quiet {
        println!(
            "merged {} parts ({} rows) -> {}",
            files.len(),
            rows.len(),
            dest.join("sweep.csv").display()
        );
    }
    Ok(())
}
