//! `settle sweep` in memory: [`sweep`] runs a dt sweep of one [`Scenario`] and returns its
//! tables and files ([`SweepResult`]); [`SweepResult::write`] writes the folder the command
//! line writes. The command line runs through the same function for each scenario file.

use super::analysis::rayleigh_time_of;
use super::cases::run;
use super::page::add_report;
use super::plan::{Plan, SweepOptions};
use super::report::{caveat, results, Context, Recommended, Report};
use super::table::Row;
use super::targets::Target;
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

/// Runs the whole grid of `plan` (not a shard) of `p` with a progress bar (hidden unless
/// `progress`) and makes every output.
/// The owner of the folder of the sweep of the scenario named `name`.
pub(crate) fn owner(name: &str) -> crate::io::Owner {
    crate::io::Owner::scenario("sweep", name)
}

pub(crate) fn compute(p: &Prepared, plan: Plan, progress: bool) -> Result<SweepResult, Error> {
    let cases = plan.cases_to_run();
    let bar = crate::progress::bar(
        cases.len() as u64,
        &p.common.name,
        "cases, {per_sec},",
        !progress,
    );
    let rows = run(p, &plan, &|| bar.inc(1))?;
    bar.finish_and_clear();
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
