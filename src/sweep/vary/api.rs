//! `settle sweep --vary` in memory: [`vary`] runs a parameter sweep of one [`Scenario`] and
//! returns its tables and files ([`VaryResult`]); [`VaryResult::write`] writes the folder the
//! command line writes. The command line runs through the same function for each file.
//! [`vary_part`] runs one shard of the grid (`--shard I/N`) into a [`VaryPart`], whose text is
//! the part file's ([`VaryPart::to_csv`]), and [`vary_merge`] joins the parts of one split into
//! the [`VaryResult`] that [`vary`] returns (`--merge`).

use super::grid::{Axis, Level};
use super::plan::{results, run, VaryPlan};
use super::table::VaryTable;
use crate::api::Scenario;
use crate::error::Error;
use crate::io::{Outputs, Table};
use crate::sweep::api::{check_parts, shard_of};
use crate::sweep::page::add_report;
use crate::sweep::values::Shard;
use std::path::{Path, PathBuf};

/// Name prefix of the part files of a sharded parameter sweep.
pub const PART_PREFIX: &str = "vary_part_";

/// How [`vary`] runs.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct VaryOptions {
    /// Show a progress bar on stderr (default false; `settle sweep` shows one unless `-q`).
    pub progress: bool,
}

/// What a parameter sweep made, in memory: the tables and files of `OUT/<name>_vary/`
/// (`vary.csv`, one chart `<quantity>_vs_<first key>.svg` per result quantity, `report.html`),
/// the typed table and the lines `settle sweep --vary` prints.
#[derive(Clone, Debug)]
pub struct VaryResult {
    name: String,
    /// The typed table (the rows of `vary.csv`: one per case and body).
    pub data: VaryTable,
    /// The tables and files of `OUT/<name>_vary/`; `vary.csv` equals the file the command line
    /// writes, cell for cell (wall times aside: `wall_time_s` measures the machine).
    pub outputs: Outputs,
    /// The cases that went unstable, one line each (`KEY = VALUE, …: unstable (why)`); the
    /// command line prints them among [`VaryResult::lines`].
    pub warnings: Vec<String>,
    /// The lines `settle sweep --vary` prints: a heading, then one line per case (without the
    /// last line, `  -> <folder>`, which names where it wrote).
    pub lines: Vec<String>,
}

impl VaryResult {
    /// The results folder's name, `<scenario name>_vary`.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The table of the file `name`, by stem (`vary`) or file name (`vary.csv`).
    pub fn table(&self, name: &str) -> Option<&Table> {
        self.outputs.get(name)
    }

    /// Writes `out_dir/<name>_vary/` as `settle sweep --vary … --out OUT_DIR` does (the same
    /// files, byte for byte except wall times): staged, then moved into place; refused when
    /// that folder exists and was not made by settle. Returns the folder.
    pub fn write(&self, out_dir: impl AsRef<Path>) -> Result<PathBuf, Error> {
        self.outputs.write_folder(out_dir.as_ref(), &self.name)
    }
}

/// `settle sweep --vary` in memory: runs `scenario` once per point of the full grid of `axes`
/// (the first key outermost and the charts' x axis; each value applied as `--set KEY=VALUE`
/// after the scenario's own overrides, at its own dt and integrator), in parallel. Every point
/// is prepared and validated before any runs: a bad key or out-of-range value, a key varied
/// twice, a grid over [`super::MAX_CASES`] cases, no axis at all or a kind that cannot be swept
/// is [`Error::BadInput`] with the command line's message. Ctrl-C
/// ([`crate::interrupt::request`]) stops it with [`Error::InterruptedUnwritten`].
///
/// ```no_run
/// use settle::sweep::{vary, Axis, VaryOptions};
/// let scenario = settle::load("scenarios/stokes_single.toml")?;
/// let axes = [
///     Axis::list("fluid.viscosity_pa_s", &["0.001", "0.002", "0.005"])?, // Pa·s
///     Axis::parse("drag.law=stokes,dallavalle")?,
/// ];
/// let r = vary(&scenario, &axes, &VaryOptions::default())?;
/// let v = r.table("vary").unwrap().f64s("terminal_velocity_m_s"); // m/s, one per case
/// r.write("out")?; // out/stokes_single_vary/
/// # Ok::<(), settle::Error>(())
/// ```
pub fn vary(scenario: &Scenario, axes: &[Axis], opts: &VaryOptions) -> Result<VaryResult, Error> {
    compute(plan_of(scenario, axes, None)?, opts.progress)
}

/// The plan of `axes` on `scenario` (every point prepared and validated; the cases of `shard`,
/// or all): the errors of [`vary`].
fn plan_of(scenario: &Scenario, axes: &[Axis], shard: Option<Shard>) -> Result<VaryPlan, Error> {
    if axes.is_empty() {
        return Err(Error::bad_argument(
            "--vary",
            scenario.path(),
            "no key to vary: give at least one axis KEY=GRID",
        ));
    }
    VaryPlan::build(scenario.prepared().clone(), axes, shard, |point| {
        scenario.prepared_with(point)
    })
}

/// Runs every case of `plan` (not a shard) with a progress bar (hidden unless `progress`) and
/// makes every output.
pub(crate) fn compute(plan: VaryPlan, progress: bool) -> Result<VaryResult, Error> {
    let data = run_with_bar(&plan, progress)?;
    assemble(&plan, data)
}

/// Runs the cases of `plan` (its shard's, or all) into a table, with a progress bar (hidden
/// unless `progress`).
pub(crate) fn run_with_bar(plan: &VaryPlan, progress: bool) -> Result<VaryTable, Error> {
    let bar = crate::progress::bar(
        plan.cases.len() as u64,
        &plan.base.common.name,
        "cases, {per_sec},",
        !progress,
    );
    let data = run(plan, &|| bar.inc(1))?;
    bar.finish_and_clear();
    Ok(data)
}

/// The result of the table `data` of every case of `plan`: every output, the unstable cases,
/// the console lines.
fn assemble(plan: &VaryPlan, data: VaryTable) -> Result<VaryResult, Error> {
    let name = plan.folder();
    let (mut outputs, lines) = results(&plan.base.common.name, &data)?;
    add_report(&mut outputs, &name)?;
    outputs.set_owner(plan.owner());
    let warnings = unstable_cases(&data);
    Ok(VaryResult {
        name,
        data,
        outputs,
        warnings,
        lines,
    })
}

/// One shard of a parameter sweep ([`vary_part`]): shard `index` of `count` (1-based, as
/// `--shard I/N`) and the table of its cases.
#[derive(Clone, Debug, PartialEq)]
pub struct VaryPart {
    /// Which shard, 1 ≤ index ≤ count.
    pub index: usize,
    /// How many shards the grid was split into.
    pub count: usize,
    /// The rows of the shard's cases, as `vary_part_I_of_N.csv` holds them.
    pub table: VaryTable,
}

impl VaryPart {
    /// The table as the text of the part file `vary_part_I_of_N.csv`.
    pub fn to_csv(&self) -> Result<String, Error> {
        let name = self.file_name();
        let io = |e| Error::Io(name.clone().into(), e);
        let bytes = self.table.to_table(&name).to_csv().map_err(io)?;
        String::from_utf8(bytes).map_err(|e| io(std::io::Error::other(e)))
    }

    /// Shard `index` of `count` from the text of its part file ([`VaryPart::to_csv`]); text
    /// that is not a parameter sweep table is a bad argument naming the part.
    pub fn from_csv(index: usize, count: usize, text: &str) -> Result<Self, Error> {
        let table = VaryTable::from_csv(text.as_bytes()).map_err(|e| {
            Error::bad_argument(
                "part",
                std::path::Path::new(&format!("{index}/{count}")),
                format!("not a vary part table: {e}"),
            )
        })?;
        Ok(Self {
            index,
            count,
            table,
        })
    }

    /// The name of the part file, `vary_part_I_of_N.csv`.
    pub fn file_name(&self) -> String {
        format!("{PART_PREFIX}{}_of_{}.csv", self.index, self.count)
    }
}

/// The points of the grid of `axes` on `scenario` (a value per key, the first key outermost,
/// as [`vary`] runs them), each prepared and validated as [`vary`] does it; nothing runs. For
/// choosing how many parts to split a parameter sweep into ([`vary_part`]).
pub fn vary_cases(scenario: &Scenario, axes: &[Axis]) -> Result<Vec<Vec<Level>>, Error> {
    let plan = plan_of(scenario, axes, None)?;
    Ok(plan.cases.into_iter().map(|c| c.point).collect())
}

/// Shard `index` of `count` (1-based, as `settle sweep --vary … --shard I/N`: the cases whose
/// position in the grid ≡ index − 1 mod count) of the parameter sweep [`vary`] runs with the
/// same `scenario` and `axes`; every point is validated as [`vary`] does it. Join the parts
/// with [`vary_merge`]; a part travels as the text of [`VaryPart::to_csv`].
///
/// ```no_run
/// use settle::sweep::{vary_merge, vary_part, Axis, VaryOptions, VaryPart};
/// let scenario = settle::load("scenarios/stokes_single.toml")?;
/// let axes = [Axis::parse("fluid.viscosity_pa_s=log:1e-3:1e-2:4")?]; // Pa·s
/// let opts = VaryOptions::default();
/// let mut parts = Vec::new();
/// for i in 1..=2 {
///     let text = vary_part(&scenario, &axes, &opts, i, 2)?.to_csv()?; // anywhere
///     parts.push(VaryPart::from_csv(i, 2, &text)?);
/// }
/// let r = vary_merge(&scenario, &axes, &opts, parts)?; // what vary(…) returns
/// println!("{}", r.lines.join("\n"));
/// # Ok::<(), settle::Error>(())
/// ```
pub fn vary_part(
    scenario: &Scenario,
    axes: &[Axis],
    opts: &VaryOptions,
    index: usize,
    count: usize,
) -> Result<VaryPart, Error> {
    let plan = plan_of(scenario, axes, Some(shard_of(index, count)?))?;
    let table = run_with_bar(&plan, opts.progress)?;
    Ok(VaryPart {
        index,
        count,
        table,
    })
}

/// Joins the parts of one split of the parameter sweep of `axes` on `scenario` ([`vary_part`],
/// each index 1..=count exactly once, any order) into what [`vary`] returns: the same table,
/// charts and lines, cell for cell (wall times aside). Parts missing, given twice, of different
/// splits, varying other keys or with a point outside the grid are a bad argument saying which;
/// nothing is merged then.
pub fn vary_merge(
    scenario: &Scenario,
    axes: &[Axis],
    opts: &VaryOptions,
    parts: Vec<VaryPart>,
) -> Result<VaryResult, Error> {
    let _ = opts; // how the merge runs: nothing to show, it runs no case
    let plan = plan_of(scenario, axes, None)?;
    let mut parts = parts;
    parts.sort_by_key(|p| p.index);
    let shards: Vec<(usize, usize)> = parts.iter().map(|s| (s.index, s.count)).collect();
    check_parts(&shards)?;
    let same = |a: &[Level], b: &[Level]| {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.order(y).is_eq())
    };
    let mut table = VaryTable::default();
    for part in parts {
        let file = part.file_name();
        let refuse = |why: String| {
            Error::bad_argument(
                "parts",
                std::path::Path::new(&file),
                format!("{why}: the parts are of another sweep; nothing merged"),
            )
        };
        if part.table.keys != plan.keys() {
            return Err(refuse(format!(
                "varies {} where the axes are {}",
                part.table.keys.join(", "),
                plan.keys().join(", ")
            )));
        }
        let outside = part
            .table
            .rows
            .iter()
            .find(|r| !plan.cases.iter().any(|c| same(&c.point, &r.point)));
        if let Some(r) = outside {
            let point: Vec<String> = r.point.iter().map(Level::to_string).collect();
            return Err(refuse(format!(
                "has a point outside the grid ({})",
                point.join(", ")
            )));
        }
        table
            .merge(part.table)
            .map_err(|e| refuse(format!("it {e}")))?;
    }
    table.sort();
    assemble(&plan, table)
}

/// One line per unstable case: its key values and the first body's reason.
fn unstable_cases(t: &VaryTable) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut seen: Vec<&[Level]> = Vec::new();
    for r in t.rows.iter().filter(|r| !r.reason.is_empty()) {
        if seen.contains(&r.point.as_slice()) {
            continue;
        }
        seen.push(&r.point);
        let keys: Vec<String> = t
            .keys
            .iter()
            .zip(&r.point)
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        out.push(format!("{}: unstable ({})", keys.join(", "), r.reason));
    }
    out
}
