//! Parameter sweeps on any key: `settle sweep S.toml --vary KEY=GRID [--vary KEY2=GRID2 …]`
//! runs the scenario once per point of the full grid, each value applied as `--set KEY=VALUE`,
//! at the scenario's own dt and integrator, and writes `OUT/<name>_vary/`: `vary.csv` (one row
//! per case and body, [`VaryTable`]) and one chart per result quantity against the first key
//! (`<quantity>_vs_<key>.svg`). A key may take words or booleans (`transient.history=off,basset`,
//! a categorical axis: one x position per value on the charts). Every case is loaded and
//! validated before any runs (a bad key or an out-of-range value exits 2 with nothing written);
//! the kinds are those of the dt sweep (`free_settling`, `drop`, `funnel_pour`). `--shard I/N`
//! runs a slice of the grid into `vary_part_I_of_N.csv`, and `--merge` joins the parts, as for
//! dt sweeps.
//!
//! From Rust, [`vary()`] runs a parameter sweep of a [`crate::Scenario`] in memory: the axes
//! as `--vary` gives them ([`Axis::parse`]) or as lists of values ([`Axis::list`]); its
//! [`VaryResult`] holds every table and chart, and [`VaryResult::write`] writes the folder.
//! [`vary_part`] and [`vary_merge`] are `--shard` and `--merge` in memory.
//!
//! | file | job |
//! |---|---|
//! | `api.rs` | [`vary()`], [`VaryResult`]: a whole parameter sweep in memory (the command line's too) |
//! | `grid.rs` | `--vary` parsing ([`Axis`]), the grid's values and points; pure |
//! | `plan.rs` | the plan (every point validated), running its cases, the outputs of a table |
//! | `table.rs` | [`VaryTable`]: the wide CSV, read, write, merge |
//! | `chart.rs` | the charts and the console lines |

mod api;
mod chart;
mod grid;
pub(crate) mod plan;
mod table;

pub use api::{
    vary, vary_cases, vary_merge, vary_part, VaryOptions, VaryPart, VaryResult, PART_PREFIX,
};
pub use chart::unit_of;
pub use grid::{Axis, Level, Spacing, MAX_CASES, VARY_ALLOWED};
pub use table::{VaryRow, VaryTable};

pub(crate) use grid::parse_vary;

use super::args::Args;
use super::values::Shard;
use crate::error::Error;
use crate::run::prepare;
use plan::{results, VaryPlan};
use std::path::{Path, PathBuf};

/// `settle sweep --vary …`: plans every scenario (every case validated), checks the output
/// folders, then sweeps each into `OUT/<name>_vary/` (or its shard's part file).
pub(crate) fn main(args: &Args) -> Result<(), Error> {
    let out = args.out.clone().unwrap_or_else(|| PathBuf::from("out"));
    for axis in &args.vary {
        crate::scenario::refuse_set_of(&args.set, &axis.key, "--vary")?;
    }
    let mut plans = Vec::new();
    for f in &args.scenarios {
        plans.push(VaryPlan::new(f, &args.set, &args.vary, args.shard)?);
    }
    for plan in plans.iter().filter(|p| p.shard.is_none()) {
        crate::run::destination_allowed(&out.join(plan.folder()), &plan.base.path, &plan.owner())?;
    }
    for plan in plans {
        sweep_file(plan, &out, args.quiet)?;
    }
    Ok(())
}

/// Runs one plan and writes its outputs under `out` (the whole grid through [`api::compute`],
/// or one shard into its part file).
fn sweep_file(plan: VaryPlan, out: &Path, quiet: bool) -> Result<(), Error> {
    let Some(Shard { index, count }) = plan.shard else {
        let r = api::compute(plan, !quiet)?;
        if !quiet {
            println!("{}", r.lines.join("\n"));
        }
        let dest = r.write(out)?;
        if !quiet {
            println!("  -> {}", dest.display());
        }
        return Ok(());
    };
    let name = &plan.base.common.name;
    let table = api::run_with_bar(&plan, !quiet)?;
    let dir = out.join(plan.folder());
    std::fs::create_dir_all(&dir).map_err(|e| Error::Io(dir.clone(), e))?;
    let file = dir.join(format!("{PART_PREFIX}{index}_of_{count}.csv"));
    table.write(&file).map_err(|e| Error::Io(file.clone(), e))?;
    super::shards::ShardCommand::of_this_process(count).record(&dir)?;
    if !quiet {
        println!(
            "{name}: shard {index}/{count} ({} rows) -> {}",
            table.rows.len(),
            file.display()
        );
    }
    Ok(())
}

/// `--merge DIR…` of a sharded parameter sweep: joins the part `files` (same keys) into
/// `vary.csv` and its charts in `--out` (default: the first folder). The title is the name of
/// the scenario file if one is given, else the first folder's name without `_vary`.
pub(crate) fn merge(args: &Args) -> Result<(), Error> {
    let files = super::shards::read_parts(&args.merge, PART_PREFIX, |f| {
        VaryTable::read(f).map_err(|e| format!("not a vary part table: {e}"))
    })?;
    let mut table = VaryTable::default();
    for (f, part) in files.iter().cloned() {
        table
            .merge(part)
            .map_err(|e| Error::bad_input(&f, None, format!("cannot merge this part: it {e}")))?;
    }
    table.sort();
    // The scenario's name: from its file if given, else from the folder `<name>_vary`.
    let title = match args.scenarios.first() {
        Some(f) => prepare(f, None, &args.set)?.common.name,
        None => args.merge[0]
            .file_name()
            .and_then(|n| n.to_str())
            .and_then(|n| n.strip_suffix("_vary"))
            .unwrap_or("vary")
            .to_string(),
    };
    let dest = args.out.clone().unwrap_or_else(|| args.merge[0].clone());
    std::fs::create_dir_all(&dest).map_err(|e| Error::Io(dest.clone(), e))?;
    let (outputs, lines) = results(&title, &table)?;
    if !args.quiet {
        println!("{}", lines.join("\n"));
    }
    outputs
        .write_into(&dest)
        .map_err(|e| Error::Io(dest.clone(), e))?;
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
