//! `settle sweep --vary` in memory: [`vary`] runs a parameter sweep of one [`Scenario`] and
//! returns its tables and files ([`VaryResult`]); [`VaryResult::write`] writes the folder the
//! command line writes. The command line runs through the same function for each file.

use super::grid::{Axis, Level};
use super::plan::{results, run, VaryPlan};
use super::table::VaryTable;
use crate::api::Scenario;
use crate::error::Error;
use crate::io::{Outputs, Table};
use crate::sweep::page::add_report;
use std::path::{Path, PathBuf};

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
    if axes.is_empty() {
        return Err(Error::bad_argument(
            "--vary",
            scenario.path(),
            "no key to vary: give at least one axis KEY=GRID",
        ));
    }
    let plan = VaryPlan::build(scenario.prepared().clone(), axes, None, |point| {
        scenario.prepared_with(point)
    })?;
    compute(plan, opts.progress)
}

/// Runs every case of `plan` (not a shard) with a progress bar (hidden unless `progress`) and
/// makes every output.
pub(crate) fn compute(plan: VaryPlan, progress: bool) -> Result<VaryResult, Error> {
    let title = plan.base.common.name.clone();
    let bar = crate::progress::bar(
        plan.cases.len() as u64,
        &title,
        "cases, {per_sec},",
        !progress,
    );
    let data = run(&plan, &|| bar.inc(1))?;
    bar.finish_and_clear();
    let name = plan.folder();
    let (mut outputs, lines) = results(&title, &data)?;
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
