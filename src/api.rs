//! The library API: load a scenario, apply overrides, run it in memory, read its tables, write
//! its files; the same steps `settle run` takes, as functions. The other commands have theirs,
//! in memory too, each with a result holding its [`Outputs`] and a `write`:
//! [`crate::reduce::reduce`], [`crate::invert::invert`], [`crate::laws::laws`],
//! [`crate::fit::fit`] (and [`crate::fit::slump`]), `crate::sweep`.
//!
//! ```no_run
//! let scenario = settle::load("scenarios/stokes_single.toml")?
//!     .set("fluid.viscosity_pa_s", "0.002")?;
//! let result = scenario.run()?;
//! let summary = result.table("summary").expect("every free-settling run has a summary");
//! println!("{:?}", summary.f64s("v_simulated_m_s"));
//! result.write("out")?; // out/stokes_single/: the files `settle run` writes
//! # Ok::<(), settle::Error>(())
//! ```

use crate::error::Error;
use crate::io::{Outputs, Table};
use crate::run::{self as runner, Executed};
use crate::scenario::Kind;
use crate::scenes::{Prepared, RunContext};
use std::path::{Path, PathBuf};

/// The name under which a scenario given as text appears in error messages; its relative input
/// files are found from the current folder.
pub const TEXT_ORIGIN: &str = "<scenario text>";

/// A scenario ready to run: read, its overrides applied, validated, its input files read.
/// Every bad input is found when it is made (the errors of `settle run`, naming the file and
/// the key), so that [`Scenario::run`] fails only on the run itself.
#[derive(Clone, Debug)]
pub struct Scenario {
    text: String,
    origin: PathBuf,
    overrides: Vec<String>,
    dt_s: Option<f64>,
    prepared: Prepared,
}

impl Scenario {
    /// Reads the scenario file `path` (or a run record `OUT/NAME/run.toml`, which runs its
    /// effective scenario again).
    pub fn load(path: impl AsRef<Path>) -> Result<Self, Error> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| {
            Error::bad_input(path, None, crate::io::arg::unreadable("scenario", &e))
        })?;
        Self::from_toml_at(&text, path)
    }

    /// A scenario from the text of a scenario file; errors name it [`TEXT_ORIGIN`], and its
    /// relative input files are found from the current folder.
    pub fn from_toml(text: &str) -> Result<Self, Error> {
        Self::from_toml_at(text, Path::new(TEXT_ORIGIN))
    }

    /// A scenario from the text of a scenario file that stands for the file `origin`: errors
    /// name `origin`, relative input files are found from its folder.
    pub fn from_toml_at(text: &str, origin: impl AsRef<Path>) -> Result<Self, Error> {
        Self::make(
            text.to_string(),
            origin.as_ref().to_path_buf(),
            Vec::new(),
            None,
        )
    }

    /// A scenario from typed values: the tables and keys of a scenario file.
    pub fn from_table(table: toml::Table) -> Result<Self, Error> {
        let text = toml::to_string(&table).map_err(|e| {
            Error::bad_input(Path::new(TEXT_ORIGIN), None, format!("not a scenario: {e}"))
        })?;
        Self::from_toml(&text)
    }

    fn make(
        text: String,
        origin: PathBuf,
        overrides: Vec<String>,
        dt_s: Option<f64>,
    ) -> Result<Self, Error> {
        let prepared = runner::prepare_str(&text, &origin, dt_s, &overrides)?;
        Ok(Self {
            text,
            origin,
            overrides,
            dt_s,
            prepared,
        })
    }

    /// The scenario file `path` with the overrides `set` (`KEY=VALUE`, as `--set` gives them)
    /// applied in one step, as a command line loads it.
    pub(crate) fn load_with(path: &Path, set: &[String]) -> Result<Self, Error> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            Error::bad_input(path, None, crate::io::arg::unreadable("scenario", &e))
        })?;
        Self::make(text, path.to_path_buf(), set.to_vec(), None)
    }

    /// The time step given by [`Scenario::with_dt`] (`--dt`), if any.
    pub(crate) fn dt_override(&self) -> Option<f64> {
        self.dt_s
    }

    /// A new scenario with the override `key = value` applied on top of this one's, exactly as
    /// `settle run --set KEY=VALUE` applies it (same keys, same validation): `value` is a TOML
    /// value (`0.002`, `"ideal-stokes"`, `[1, 2]`) or a bare word read as a string.
    pub fn set(&self, key: &str, value: &str) -> Result<Self, Error> {
        let mut overrides = self.overrides.clone();
        overrides.push(format!("{key}={value}"));
        Self::make(self.text.clone(), self.origin.clone(), overrides, self.dt_s)
    }

    /// A new scenario with the time step `dt_s`, s (as `settle run --dt`).
    pub fn with_dt(&self, dt_s: f64) -> Result<Self, Error> {
        Self::make(
            self.text.clone(),
            self.origin.clone(),
            self.overrides.clone(),
            Some(dt_s),
        )
    }

    /// The scenario's name (its output folder is `OUT/<name>/`).
    pub fn name(&self) -> &str {
        &self.prepared.common.name
    }

    /// The scenario's kind.
    pub fn kind(&self) -> Kind {
        self.prepared.common.kind
    }

    /// The file the scenario came from ([`TEXT_ORIGIN`] for text).
    pub fn path(&self) -> &Path {
        &self.origin
    }

    /// The overrides applied, in order (`KEY=VALUE`).
    pub fn overrides(&self) -> &[String] {
        &self.overrides
    }

    /// The time step, s.
    pub fn dt_s(&self) -> f64 {
        self.prepared.common.time.dt_s
    }

    /// The effective scenario (overrides applied, defaults filled in, input files as absolute
    /// paths) as the text of a scenario file: the `[scenario]` table of `run.toml`.
    pub fn to_toml(&self) -> Result<String, Error> {
        let table = self.prepared.record_table()?;
        toml::to_string(&table)
            .map_err(|e| Error::Io(self.origin.clone(), std::io::Error::other(e)))
    }

    /// The prepared scenario, for the crate's other commands ([`crate::sweep`]).
    pub(crate) fn prepared(&self) -> &Prepared {
        &self.prepared
    }

    /// This scenario prepared again with the overrides `extra` after its own, in one
    /// preparation (a point of a parameter sweep, a run of `settle fit`): the errors of
    /// `--set`. With no `extra`, the prepared scenario itself.
    pub(crate) fn prepared_with(
        &self,
        extra: &[String],
    ) -> Result<Prepared, crate::error::BadInput> {
        if extra.is_empty() {
            return Ok(self.prepared.clone());
        }
        let mut overrides = self.overrides.clone();
        overrides.extend_from_slice(extra);
        runner::prepare_str(&self.text, &self.origin, self.dt_s, &overrides)
    }

    /// Runs the scenario in memory with the default [`RunOptions`].
    pub fn run(&self) -> Result<RunResult, Error> {
        self.run_with(&RunOptions::default())
    }

    /// Runs the scenario in memory. A run whose cost estimate exceeds the limits of `settle
    /// run` is refused unless `opts.force`; an unstable run is [`Error::Unstable`]; a run
    /// stopped by [`crate::interrupt::request`] (Ctrl-C) returns what it did with
    /// [`Status::Interrupted`].
    pub fn run_with(&self, opts: &RunOptions) -> Result<RunResult, Error> {
        let p = &self.prepared;
        crate::scenes::cost::check(p, opts.force)?;
        let ctx = RunContext {
            quiet: !opts.progress,
            ..RunContext::default()
        };
        let watch = crate::progress::Watch::current();
        let done = match opts.threads {
            None => runner::execute(p, &ctx)?,
            Some(n) => rayon::ThreadPoolBuilder::new()
                .num_threads(n.max(1))
                .build()
                .map_err(|e| {
                    Error::bad_argument("threads", Path::new(&n.to_string()), e.to_string())
                })?
                .install(|| {
                    // the run goes on in the pool's thread: the caller's progress watch with it
                    match &watch {
                        Some(w) => w.scope(|| runner::execute(p, &ctx)),
                        None => runner::execute(p, &ctx),
                    }
                })?,
        };
        Ok(RunResult {
            record: runner::run_toml(p, &done)?,
            scenario: self.clone(),
            done,
        })
    }
}

/// Reads the scenario file `path` ([`Scenario::load`]).
pub fn load(path: impl AsRef<Path>) -> Result<Scenario, Error> {
    Scenario::load(path)
}

/// Runs `scenario` in memory ([`Scenario::run`]).
pub fn run(scenario: &Scenario) -> Result<RunResult, Error> {
    scenario.run()
}

/// How [`Scenario::run_with`] runs.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Show a progress bar on stderr (default false).
    pub progress: bool,
    /// Run even when the cost estimate exceeds the time, memory or disk limits (`--force`;
    /// default false).
    pub force: bool,
    /// Threads of the run's own parallel loops (the spheres of a free-settling scenario, the
    /// grains of a cylinder); default None: every core (rayon's global pool). `Some(1)` runs on
    /// the calling thread's pool of one, for callers that run many small scenarios in parallel
    /// threads of their own (the Python package's `threads=1`).
    pub threads: Option<usize>,
}

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// It reached its end time.
    Complete,
    /// It was stopped by an interruption; its outputs hold what was done.
    Interrupted,
}

impl Status {
    /// `complete` or `interrupted`, as `run.toml` says.
    pub fn name(self) -> &'static str {
        match self {
            Status::Complete => "complete",
            Status::Interrupted => "interrupted",
        }
    }
}

/// The outcome of a run, in memory: its tables and files as `settle run` writes them.
#[derive(Clone, Debug)]
pub struct RunResult {
    scenario: Scenario,
    done: Executed,
    record: String,
}

impl RunResult {
    /// The scenario that ran.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// Every table, in the order the run made them; each equals the CSV file `settle run`
    /// writes of it, cell for cell.
    pub fn tables(&self) -> &[Table] {
        self.done.outputs.tables()
    }

    /// The table of the file `name`, by stem (`summary`) or file name (`summary.csv`).
    pub fn table(&self, name: &str) -> Option<&Table> {
        self.done.outputs.get(name)
    }

    /// The tables and the other files (charts) of the run.
    pub fn outputs(&self) -> &Outputs {
        &self.done.outputs
    }

    /// The file name of the main chart of the scenario's kind (`velocity.svg`,
    /// `granulometry.svg`, …); its data is in [`Outputs::figures`].
    pub fn main_chart(&self) -> &'static str {
        crate::scenario::info(self.scenario.kind()).main_chart
    }

    /// The validity warnings of the run (a law used outside its range, …).
    pub fn warnings(&self) -> &[String] {
        &self.done.report.warnings
    }

    /// The lines `settle run` prints after the run of a contact scene.
    pub fn lines(&self) -> &[String] {
        &self.done.report.lines
    }

    /// How the run ended.
    pub fn status(&self) -> Status {
        if self.done.report.interrupted {
            Status::Interrupted
        } else {
            Status::Complete
        }
    }

    /// The text of the run's `run.toml` (its record and effective scenario).
    pub fn record(&self) -> &str {
        &self.record
    }

    /// Wall time of the run, s.
    pub fn wall_time_s(&self) -> f64 {
        self.done.wall_time_s
    }

    /// Total steps over all worlds.
    pub fn steps(&self) -> u64 {
        self.done.report.steps
    }

    /// Writes the run's files to `out_dir/<name>/`, as `settle run --out OUT_DIR` does (the
    /// same files, byte for byte except wall times): refused when that folder exists and was
    /// not made by settle; staged and moved into place, so nothing is ever half-written.
    pub fn write(&self, out_dir: impl AsRef<Path>) -> Result<PathBuf, Error> {
        let out_dir = out_dir.as_ref();
        let p = &self.scenario.prepared;
        runner::check_destinations(out_dir, std::slice::from_ref(p))?;
        runner::write(p, &self.done, out_dir)
    }
}
