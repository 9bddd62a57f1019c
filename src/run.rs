//! Running scenario files: load and validate all of them first (so bad input writes nothing),
//! run each, stage its outputs and move them into place only on success.

use crate::dynamics::Unstable;
use crate::output::{self, StagedDir};
use crate::scenario::{self, EngineChoice, Kind, Scenario, ScenarioError};
use crate::scenes::free_settling::{self, output as out_fs};
use crate::scenes::spheres;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What `settle run` was asked to do.
#[derive(Clone, Debug, Default)]
pub struct RunRequest {
    /// Scenario files.
    pub files: Vec<PathBuf>,
    /// Output folder; each scenario writes `out/<name>/`.
    pub out_dir: PathBuf,
    /// Time step override, s.
    pub dt_s: Option<f64>,
    /// `KEY=VALUE` overrides applied to every file.
    pub overrides: Vec<String>,
    /// Checkpoint period, s of wall time (`--checkpoint-every`; None: only on interruption).
    pub checkpoint_every_s: Option<f64>,
    /// Continue the checkpointed run in `out_dir` (`--resume`); files, overrides, dt and period
    /// then come from its `checkpoint/request.toml`.
    pub resume: bool,
    /// Run even if the cost estimate exceeds the time or soft memory limit (`--force`).
    pub force: bool,
    /// No progress bars.
    pub quiet: bool,
}

/// How a run is carried out beyond its scenario: checkpoints, resumption, progress display.
#[derive(Clone, Debug, Default)]
pub struct RunContext {
    /// Where and how often to write checkpoints (None: never, not even on interruption).
    pub checkpoints: Option<crate::checkpoint::Checkpoints>,
    /// Continue from the checkpoints found there (`--resume`).
    pub resume: bool,
    /// No progress bar.
    pub quiet: bool,
}

/// Why a run failed; [`RunError::exit_code`] maps it to the process exit code.
#[derive(Debug)]
pub enum RunError {
    /// Bad input (exit 2).
    Scenario(ScenarioError),
    /// The run went unstable (exit 3).
    Unstable(PathBuf, Unstable),
    /// Could not write outputs (exit 1).
    Io(PathBuf, std::io::Error),
    /// Stopped by Ctrl-C/SIGTERM; what was done is in the folder (exit 130).
    Interrupted(PathBuf),
    /// Anything else (exit 1).
    Other(String),
}

impl RunError {
    /// Process exit code: 2 bad input, 3 unstable, 1 other.
    pub fn exit_code(&self) -> i32 {
        match self {
            Self::Scenario(_) => 2,
            Self::Unstable(..) => 3,
            Self::Interrupted(_) => 130,
            _ => 1,
        }
    }
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Scenario(e) => write!(f, "{e}"),
            Self::Unstable(p, u) => write!(f, "{}: {u}; nothing was written", p.display()),
            Self::Io(p, e) => write!(f, "{}: cannot write outputs: {e}", p.display()),
            Self::Interrupted(p) => write!(
                f,
                "interrupted: what was simulated so far is in {} (run.toml status = \"interrupted\")",
                p.display()
            ),
            Self::Other(m) => write!(f, "{m}"),
        }
    }
}

impl std::error::Error for RunError {}

/// A loaded scenario ready to run.
#[derive(Clone, Debug)]
pub struct Prepared {
    /// The file.
    pub path: PathBuf,
    /// The effective scenario (overrides applied).
    pub scenario: Scenario,
    /// Its spheres.
    pub spheres: Vec<spheres::SphereCase>,
}

/// Loads and validates a scenario with the request's overrides (`--dt` is `time.dt_s`).
pub fn prepare(
    path: &Path,
    dt_s: Option<f64>,
    overrides: &[String],
) -> Result<Prepared, ScenarioError> {
    let mut ov = overrides.to_vec();
    if let Some(dt) = dt_s.filter(|d| !d.is_finite()) {
        return Err(ScenarioError::new(
            path,
            Some("time.dt_s"),
            format!("--dt {dt} is out of range: allowed 0 < dt_s ≤ time.end_s s"),
        ));
    }
    if let Some(dt) = dt_s {
        ov.push(format!("time.dt_s={dt:e}"));
    }
    let scenario = scenario::load(path, &ov)?;
    let spheres = spheres::spheres(&scenario, path)?;
    Ok(Prepared {
        path: path.to_path_buf(),
        scenario,
        spheres,
    })
}

/// Result of one scenario file.
pub struct FileReport {
    /// The prepared scenario.
    pub prepared: Prepared,
    /// Per-sphere results (free settling and drops).
    pub results: Vec<free_settling::SphereResult>,
    /// Summary lines of contact scenes.
    pub lines: Vec<String>,
    /// Where the outputs went.
    pub out: PathBuf,
    /// Wall time of the simulation, s.
    pub wall_time_s: f64,
}

#[derive(Serialize)]
struct RunMeta<'a> {
    settle_version: &'a str,
    scenario_file: String,
    status: &'a str,
    engine: &'a str,
    integrator: &'a str,
    dt_s: f64,
    steps: u64,
    bodies: usize,
    /// Wall time of this process's part of the run, s (a resumed run counts from the resume).
    wall_time_s: f64,
    /// Continued from a checkpoint (`--resume`).
    resumed: bool,
}

#[derive(Serialize)]
struct RunToml<'a> {
    run: RunMeta<'a>,
    /// Rapier settings derived from the scene (engine = "rapier"): each sphere has its own world
    /// with these settings and length_unit_m = its diameter; shown for the smallest sphere.
    #[serde(skip_serializing_if = "Option::is_none")]
    engine_settings: Option<crate::engine::EngineSettings>,
    scenario: &'a Scenario,
}

/// Which engine a scenario runs on after `auto` is resolved.
pub fn engine_name(s: &Scenario) -> &'static str {
    match (s.kind, s.engine) {
        (_, EngineChoice::Rapier) => "rapier",
        (Kind::FreeSettling | Kind::Drop | Kind::Sedimentation, _) => "free",
        (Kind::RestitutionDrop | Kind::TiltFriction | Kind::FunnelPour, _) => "rapier",
    }
}

/// What a scene of a contact kind (restitution drop, tilt, funnel pour) reports to `run_one`
/// after writing its own files into the staging folder.
#[derive(Clone, Debug, Default)]
pub struct SceneReport {
    /// Total steps over all worlds.
    pub steps: u64,
    /// Number of bodies (over all worlds).
    pub bodies: usize,
    /// Rapier settings used (recorded in run.toml).
    pub engine_settings: Option<crate::engine::EngineSettings>,
    /// Lines printed after the run (a short human-readable summary).
    pub lines: Vec<String>,
    /// The run stopped early on Ctrl-C/SIGTERM (outputs hold what was done).
    pub interrupted: bool,
}

/// Runs one prepared scenario and writes its outputs under `out_dir` (no checkpoints, no
/// progress bar).
pub fn run_one(p: &Prepared, out_dir: &Path) -> Result<FileReport, RunError> {
    run_one_with(
        p,
        out_dir,
        &RunContext {
            quiet: true,
            ..RunContext::default()
        },
    )
}

/// [`run_one`] with checkpoints, resumption and progress as `ctx` says.
pub fn run_one_with(
    p: &Prepared,
    out_dir: &Path,
    ctx: &RunContext,
) -> Result<FileReport, RunError> {
    let s = &p.scenario;
    let io = |e: std::io::Error| RunError::Io(p.path.clone(), e);
    let t0 = Instant::now();
    let stage = StagedDir::new(out_dir, &s.name).map_err(io)?;
    let (results, report) = match s.kind {
        Kind::FreeSettling | Kind::Drop => free_settling::run_scene(p, &stage)?,
        Kind::RestitutionDrop => (Vec::new(), crate::scenes::restitution_drop::run(p, &stage)?),
        Kind::TiltFriction => (Vec::new(), crate::scenes::tilt_friction::run(p, &stage)?),
        Kind::FunnelPour => (Vec::new(), crate::scenes::funnel::run(p, &stage, ctx)?),
        Kind::Sedimentation => (
            Vec::new(),
            crate::scenes::sedimentation::run(p, &stage, ctx)?,
        ),
    };
    let wall = t0.elapsed().as_secs_f64();
    let meta = RunToml {
        run: RunMeta {
            settle_version: env!("CARGO_PKG_VERSION"),
            scenario_file: p.path.display().to_string(),
            status: if report.interrupted {
                "interrupted"
            } else {
                "complete"
            },
            engine: engine_name(s),
            integrator: s.time.integrator.name(),
            dt_s: s.time.dt_s,
            steps: report.steps,
            bodies: report.bodies,
            wall_time_s: wall,
            resumed: ctx.resume,
        },
        engine_settings: report.engine_settings,
        scenario: s,
    };
    let text = toml::to_string(&meta).map_err(|e| RunError::Other(e.to_string()))?;
    output::write_atomic(&stage.path("run.toml"), text.as_bytes()).map_err(io)?;
    let out = stage.commit().map_err(io)?;
    if report.interrupted {
        return Err(RunError::Interrupted(out));
    }
    Ok(FileReport {
        prepared: p.clone(),
        results,
        lines: report.lines,
        out,
        wall_time_s: wall,
    })
}

/// Runs every file of a request. All files are validated, and their cost estimated
/// ([`crate::scenario::cost`]), before any runs; with several files a combined `summary.csv` and
/// `metrics.csv` go to `out_dir/combined/`. Checkpoints go to `out_dir/checkpoint/` (every
/// `checkpoint_every_s`, and when interrupted) and are removed once every file has completed.
pub fn run_files(req: &RunRequest) -> Result<Vec<FileReport>, RunError> {
    use crate::checkpoint::{Checkpoints, SavedRequest};
    let mut req = req.clone();
    let saved = if req.resume {
        let saved = Checkpoints::load_request(&req.out_dir).map_err(RunError::Other)?;
        req.files = saved.files.clone();
        req.overrides = saved.overrides.clone();
        req.dt_s = saved.dt_s;
        req.checkpoint_every_s = req.checkpoint_every_s.or(saved.checkpoint_every_s);
        req.force |= saved.force;
        Some(saved)
    } else {
        None
    };
    let prepared: Vec<Prepared> = req
        .files
        .iter()
        .map(|f| prepare(f, req.dt_s, &req.overrides))
        .collect::<Result<_, _>>()
        .map_err(RunError::Scenario)?;
    let mut names = std::collections::HashSet::new();
    for p in &prepared {
        if !names.insert(p.scenario.name.clone()) {
            return Err(RunError::Scenario(ScenarioError::new(
                &p.path,
                Some("name"),
                format!(
                    "`{}` is used by another scenario of this run: names must be unique",
                    p.scenario.name
                ),
            )));
        }
        scenario::cost::check(&p.scenario, &p.path, req.force).map_err(RunError::Scenario)?;
    }
    let fingerprints: Vec<String> = prepared
        .iter()
        .map(|p| toml::to_string(&p.scenario).unwrap_or_default())
        .collect();
    let mut checkpoints = Checkpoints::new(&req.out_dir, req.checkpoint_every_s);
    let ck_dir = checkpoints.dir().to_path_buf();
    let io_ck = |e: std::io::Error| RunError::Io(ck_dir.clone(), e);
    match &saved {
        Some(saved) => {
            if saved.scenarios != fingerprints {
                return Err(RunError::Other(format!(
                    "{}: cannot resume: the scenario files changed since the checkpoint (run them \
                     afresh, without --resume)",
                    ck_dir.join("request.toml").display()
                )));
            }
        }
        None => {
            checkpoints.clear().map_err(io_ck)?;
            checkpoints = checkpoints.with_request(SavedRequest {
                files: req.files.clone(),
                overrides: req.overrides.clone(),
                dt_s: req.dt_s,
                checkpoint_every_s: req.checkpoint_every_s,
                force: req.force,
                scenarios: fingerprints,
            });
        }
    }
    let ctx = RunContext {
        checkpoints: Some(checkpoints.clone()),
        resume: req.resume,
        quiet: req.quiet,
    };
    let mut reports = Vec::new();
    for p in &prepared {
        if crate::interrupt::requested() {
            return Err(RunError::Interrupted(req.out_dir.clone()));
        }
        match run_one_with(p, &req.out_dir, &ctx) {
            Ok(r) => reports.push(r),
            Err(e @ RunError::Interrupted(_)) => return Err(e),
            Err(e) => {
                // Nothing to resume from a run that failed: leave no checkpoint behind.
                let _ = checkpoints.clear();
                return Err(e);
            }
        }
    }
    if reports.len() > 1 {
        write_combined(&req.out_dir, &reports)?;
    }
    checkpoints.clear().map_err(io_ck)?;
    Ok(reports)
}

fn write_combined(out_dir: &Path, reports: &[FileReport]) -> Result<(), RunError> {
    let p = Path::new("combined");
    let io = |e: std::io::Error| RunError::Io(p.to_path_buf(), e);
    let stage = StagedDir::new(out_dir, "combined").map_err(io)?;
    let mut rows = Vec::new();
    let mut all = Vec::new();
    for r in reports {
        let s = &r.prepared.scenario;
        for x in &r.results {
            rows.push(out_fs::summary_row(
                x,
                s.time.dt_s,
                s.time.integrator.name(),
            ));
        }
        all.extend(r.results.iter().cloned());
    }
    out_fs::write_summary(&stage.path("summary.csv"), &rows).map_err(io)?;
    let stats = out_fs::metrics(&all);
    if !stats.is_empty() {
        out_fs::write_metrics(&stage.path("metrics.csv"), &stats).map_err(io)?;
    }
    // Sedimentation: one table of each instrument's error against the input curve per sample.
    let sed: Vec<&Path> = reports
        .iter()
        .filter(|r| r.prepared.scenario.kind == Kind::Sedimentation)
        .map(|r| r.out.as_path())
        .collect();
    if !sed.is_empty() {
        output::granulometry::write_combined_errors(&stage.path("instrument_errors.csv"), &sed)
            .map_err(io)?;
    }
    stage.commit().map_err(io)?;
    Ok(())
}
