//! Running scenario files: load and validate all of them first (so bad input writes nothing),
//! check that every destination folder may be written (settle's own, or new) and estimate the
//! cost, then run each, stage its outputs and move them into place only on success.

use crate::error::BadInput;
use crate::error::Error;
use crate::io::{self as output, StagedDir};
use crate::scenario::{self, Common, Kind};
use crate::scenes::free_settling::{self, output as out_fs};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::scenes::{Prepared, RunContext};

/// Scenario names refused because the layout of the output folder uses them: `checkpoint`
/// (the checkpoints of a long run) and `combined` (the joint summary of a several-file run).
pub const RESERVED_NAMES: &[&str] = &[crate::checkpoint::DIR_NAME, "combined"];

/// Longest scenario name, bytes: the name is a folder name, and its staging folder
/// `.NAME.partial-PID` must stay within the 255 bytes a file name may have.
pub const MAX_NAME_BYTES: usize = 200;

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
    /// Run even if the cost estimate exceeds the time, memory or disk limit (`--force`).
    pub force: bool,
    /// No progress bars and no cost line.
    pub quiet: bool,
}

/// Refuses names the output layout reserves ([`RESERVED_NAMES`]) and names too long for a
/// folder ([`MAX_NAME_BYTES`]).
fn check_name(s: &Common, path: &Path) -> Result<(), BadInput> {
    if RESERVED_NAMES.contains(&s.name.as_str()) {
        return Err(BadInput::new(
            path,
            Some("name"),
            format!(
                "`{}` is reserved (settle writes OUT/{}/ itself): choose another name; reserved: {}",
                s.name,
                s.name,
                RESERVED_NAMES.join(", ")
            ),
        ));
    }
    if s.name.len() > MAX_NAME_BYTES {
        return Err(BadInput::new(
            path,
            Some("name"),
            format!(
                "{} bytes long: allowed at most {MAX_NAME_BYTES} (it names the output folder)",
                s.name.len()
            ),
        ));
    }
    Ok(())
}

/// Loads and validates a scenario with the request's overrides (`--dt` is `time.dt_s`), reads
/// its input files (`spheres_csv`, a sedimentation's `sample.csv`), and refuses reserved and
/// over-long names: every bad input is found here, before anything runs. `path` may be a run
/// record (`OUT/NAME/run.toml`): its effective scenario runs again, the overrides on top.
pub fn prepare(path: &Path, dt_s: Option<f64>, overrides: &[String]) -> Result<Prepared, BadInput> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| BadInput::new(path, None, crate::io::arg::unreadable("scenario", &e)))?;
    prepare_str(&text, path, dt_s, overrides)
}

/// As [`prepare`], from the text of a scenario file; `path` names it in errors, and its folder
/// is where relative input files are found.
pub fn prepare_str(
    text: &str,
    path: &Path,
    dt_s: Option<f64>,
    overrides: &[String],
) -> Result<Prepared, BadInput> {
    Prepared::parse(text, path, dt_s, overrides, |s| check_name(s, path))
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
    /// Validity warnings ([`crate::scenes::SceneReport::warnings`]).
    pub warnings: Vec<String>,
    /// The run's tables and files in memory, as written to `out` (without `run.toml` and the
    /// report page).
    pub outputs: output::Outputs,
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
    /// The simulated time an interrupted run reached, s (absent when complete).
    #[serde(skip_serializing_if = "Option::is_none")]
    reached_s: Option<f64>,
    /// Validity warnings of the run ([`crate::scenes::SceneReport::warnings`]); empty when none.
    warnings: &'a [String],
    /// The overrides as given (`set`: the `--set` list; `dt_s`: `--dt`), already applied to
    /// `[scenario]`.
    overrides: &'a scenario::Overrides,
}

/// The first lines of `run.toml`: how to run the case again.
const RUN_TOML_HEAD: &str = "\
# The record of a settle run. `settle run THIS_FILE` runs the same case again: it reads only
# [scenario], the effective scenario (the overrides of [run.overrides] already applied, input
# files as absolute paths); more --set options apply on top of it.
";

#[derive(Serialize)]
struct RunToml<'a> {
    run: RunMeta<'a>,
    /// Rapier settings derived from the scene (engine = "rapier"): each sphere has its own world
    /// with these settings and length_unit_m = its diameter; shown for the smallest sphere.
    #[serde(skip_serializing_if = "Option::is_none")]
    engine_settings: Option<crate::engine::EngineSettings>,
    /// The effective scenario ([`Prepared::record_table`]).
    scenario: toml::Table,
}

/// Runs one prepared scenario and writes its outputs under `out_dir`, with checkpoints,
/// resumption and progress as `ctx` says.
pub fn run_one_with(p: &Prepared, out_dir: &Path, ctx: &RunContext) -> Result<FileReport, Error> {
    let done = execute(p, ctx)?;
    let out = write(p, &done, out_dir)?;
    if done.report.interrupted {
        return Err(Error::Interrupted(out));
    }
    Ok(FileReport {
        prepared: p.clone(),
        results: done.results,
        lines: done.report.lines,
        out,
        wall_time_s: done.wall_time_s,
        warnings: done.report.warnings,
        outputs: done.outputs,
    })
}

/// A run carried out in memory: its outputs and what the scene reported, nothing written yet.
#[derive(Clone, Debug)]
pub struct Executed {
    /// The tables and files of the run (without `run.toml` and the report page, which
    /// [`write`](fn@write) adds).
    pub outputs: output::Outputs,
    /// Per-sphere results (free settling and drops).
    pub results: Vec<free_settling::SphereResult>,
    /// What the scene reported (steps, bodies, warnings, interrupted).
    pub report: crate::scenes::SceneReport,
    /// Wall time of the simulation, s.
    pub wall_time_s: f64,
    /// Continued from a checkpoint.
    pub resumed: bool,
}

/// Runs the scene of `p` into memory.
pub fn execute(p: &Prepared, ctx: &RunContext) -> Result<Executed, Error> {
    let t0 = Instant::now();
    let mut outputs = output::Outputs::new();
    let (results, report) = crate::scenes::run_scene(p, &mut outputs, ctx)?;
    Ok(Executed {
        outputs,
        results,
        report,
        wall_time_s: t0.elapsed().as_secs_f64(),
        resumed: ctx.resume,
    })
}

/// The text of `run.toml` of the run `done` of `p`: the record of the run and its effective
/// scenario.
pub fn run_toml(p: &Prepared, done: &Executed) -> Result<String, Error> {
    let c = &p.common;
    let report = &done.report;
    let meta = RunToml {
        run: RunMeta {
            settle_version: env!("CARGO_PKG_VERSION"),
            scenario_file: p.path.display().to_string(),
            status: if report.interrupted {
                "interrupted"
            } else {
                "complete"
            },
            engine: c.engine.name(),
            integrator: c.time.integrator.name(),
            dt_s: c.time.dt_s,
            steps: report.steps,
            bodies: report.bodies,
            wall_time_s: done.wall_time_s,
            resumed: done.resumed,
            reached_s: report.reached_s,
            warnings: &report.warnings,
            overrides: &p.overrides,
        },
        engine_settings: report.engine_settings,
        scenario: p.record_table()?,
    };
    let text =
        toml::to_string(&meta).map_err(|e| Error::Io(p.path.clone(), std::io::Error::other(e)))?;
    Ok(format!("{RUN_TOML_HEAD}{text}"))
}

/// Writes the run `done` of `p` to `out_dir/<name>/`: its outputs, `run.toml` and the report
/// page, staged and moved into place ([`StagedDir`]); returns the folder.
pub fn write(p: &Prepared, done: &Executed, out_dir: &Path) -> Result<PathBuf, Error> {
    let name = &p.common.name;
    let stage = StagedDir::new(out_dir, name)
        .map_err(|e| Error::Io(out_dir.join(name), e))?
        .owned_by(output::Owner::scenario("run", name));
    let io = |e: std::io::Error| Error::Io(stage.dest().to_path_buf(), e);
    done.outputs.write_into(&stage.path("")).map_err(io)?;
    let text = run_toml(p, done)?;
    output::write_atomic(&stage.path("run.toml"), text.as_bytes()).map_err(io)?;
    output::report::write_report(&stage.path(""), &output::report::Page::run(name)).map_err(io)?;
    commit(stage, &p.path)
}

/// Moves a staged folder into place; a destination settle may not replace (a folder it did not
/// create, or a user's file in the way) is bad input naming the scenario file's key `name`.
fn commit(stage: StagedDir, file: &Path) -> Result<PathBuf, Error> {
    let dest = stage.dest().to_path_buf();
    stage.commit().map_err(|e| {
        if e.kind() == std::io::ErrorKind::AlreadyExists {
            Error::bad_input(file, Some("name"), e.to_string())
        } else {
            Error::Io(dest, e)
        }
    })
}

/// Runs every file of a request. All files are validated, their destinations checked
/// ([`check_destinations`]) and their cost estimated ([`crate::scenes::cost`]) before any
/// runs; with several files a combined `summary.csv` and `metrics.csv` go to
/// `out_dir/combined/`. Checkpoints go to `out_dir/checkpoint/` (every `checkpoint_every_s`, and
/// when interrupted) and are removed once every file has completed.
pub fn run_files(req: &RunRequest) -> Result<Vec<FileReport>, Error> {
    use crate::checkpoint::{Checkpoints, SavedRequest};
    let (req, saved) = resolve_resume(req)?;
    let prepared = prepare_all(&req)?;
    check_destinations(&req.out_dir, &prepared)?;
    let fingerprints: Vec<String> = prepared.iter().map(Prepared::fingerprint).collect();
    let mut checkpoints = Checkpoints::new(&req.out_dir, req.checkpoint_every_s);
    let ck_dir = checkpoints.dir().to_path_buf();
    let io_ck = |e: std::io::Error| Error::Io(ck_dir.clone(), e);
    match &saved {
        Some(saved) => {
            if saved.scenarios != fingerprints {
                return Err(Error::bad_input(
                    &ck_dir.join("request.toml"),
                    None,
                    "cannot resume: the scenario files changed since the checkpoint (run them \
                     afresh, without --resume)",
                ));
            }
        }
        None => {
            checkpoints.clear().map_err(io_ck)?;
            let files = req
                .files
                .iter()
                .map(|f| std::path::absolute(f).unwrap_or_else(|_| f.clone()))
                .collect();
            checkpoints = checkpoints.with_request(SavedRequest {
                files,
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
            return Err(Error::InterruptedUnwritten(p.path.clone()));
        }
        match run_one_with(p, &req.out_dir, &ctx) {
            Ok(r) => reports.push(r),
            Err(e) if e.is_interrupted() => return Err(e),
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

/// The request itself, or with `--resume` the request saved in `OUT/checkpoint/request.toml`
/// (scenario files as absolute paths, so a resume works from any directory).
fn resolve_resume(
    req: &RunRequest,
) -> Result<(RunRequest, Option<crate::checkpoint::SavedRequest>), Error> {
    let mut req = req.clone();
    if !req.resume {
        return Ok((req, None));
    }
    let saved = crate::checkpoint::Checkpoints::load_request(&req.out_dir)?;
    req.files = saved.files.clone();
    req.overrides = saved.overrides.clone();
    req.dt_s = saved.dt_s;
    req.checkpoint_every_s = req.checkpoint_every_s.or(saved.checkpoint_every_s);
    req.force |= saved.force;
    Ok((req, Some(saved)))
}

/// Prepares every file, refuses duplicate names, and checks each cost (printing the estimate of
/// a long run on stderr unless quiet).
fn prepare_all(req: &RunRequest) -> Result<Vec<Prepared>, Error> {
    let prepared: Vec<Prepared> = req
        .files
        .iter()
        .map(|f| prepare(f, req.dt_s, &req.overrides))
        .collect::<Result<_, _>>()
        .map_err(Error::BadInput)?;
    let mut names = std::collections::HashSet::new();
    for p in &prepared {
        if !names.insert(p.common.name.clone()) {
            return Err(Error::BadInput(BadInput::new(
                &p.path,
                Some("name"),
                format!(
                    "`{}` is used by another scenario of this run: names must be unique",
                    p.common.name
                ),
            )));
        }
        let cost = crate::scenes::cost::estimate(p);
        if !req.quiet && cost.is_long() {
            eprintln!("{}: {}", p.path.display(), cost.describe());
        }
        crate::scenes::cost::check(p, req.force).map_err(Error::BadInput)?;
    }
    Ok(prepared)
}

/// Refuses, before anything runs, an output folder that is a file, and a destination
/// `OUT/NAME/` (or `OUT/combined/`) that settle did not create: settle never deletes or replaces
/// a folder it did not make.
pub fn check_destinations(out_dir: &Path, prepared: &[Prepared]) -> Result<(), Error> {
    output::owner::check_out_dir(out_dir)?;
    for p in prepared {
        let owner = output::Owner::scenario("run", &p.common.name);
        destination_allowed(&out_dir.join(&p.common.name), &p.path, &owner)?;
    }
    let combined = out_dir.join("combined");
    let owner = combined_owner();
    if prepared.len() > 1 {
        if let Err(r) = output::check_destination_for(&combined, Some(&owner)) {
            return Err(Error::bad_argument(
                "--out",
                out_dir,
                format!(
                    "the joint summary of several files goes to {}",
                    output::owner::refusal_text(
                        &combined,
                        &r,
                        Some(&owner),
                        "choose another --out"
                    )
                ),
            ));
        }
    }
    Ok(())
}

/// The owner of `OUT/combined/`: any run of several scenario files.
fn combined_owner() -> output::Owner {
    output::Owner::new("run", "several scenario files (their joint summary)")
}

/// Refuses (bad input naming `file` and its key `name`) an output folder `dest` that settle may
/// not write for `owner`: a file, a folder settle did not create and not empty, or the results
/// of another command or scenario ([`output::check_destination_for`]).
pub fn destination_allowed(dest: &Path, file: &Path, owner: &output::Owner) -> Result<(), Error> {
    match output::check_destination_for(dest, Some(owner)) {
        Ok(()) => Ok(()),
        Err(r) => Err(Error::bad_input(
            file,
            Some("name"),
            format!(
                "the output folder {}",
                output::owner::refusal_text(
                    dest,
                    &r,
                    Some(owner),
                    "choose another --out or another name"
                )
            ),
        )),
    }
}

fn write_combined(out_dir: &Path, reports: &[FileReport]) -> Result<(), Error> {
    let dest = out_dir.join("combined");
    let io = |e: std::io::Error| Error::Io(dest.clone(), e);
    let stage = StagedDir::new(out_dir, "combined")
        .map_err(io)?
        .owned_by(combined_owner());
    let mut rows = Vec::new();
    let mut all = Vec::new();
    for r in reports {
        let time = &r.prepared.common.time;
        for x in &r.results {
            rows.push(out_fs::summary_row(x, time.dt_s, time.integrator.name()));
        }
        all.extend(r.results.iter().cloned());
    }
    let mut combined = output::Outputs::new();
    combined.table(out_fs::summary_table(rows));
    out_fs::combined_charts(
        &mut combined,
        reports.iter().map(|r| (&r.prepared.common, &r.results[..])),
    )
    .map_err(io)?;
    let stats = out_fs::metrics(&all);
    if !stats.is_empty() {
        combined.table(out_fs::metrics_table(&stats));
    }
    combined.write_into(&stage.path("")).map_err(io)?;
    // Sedimentation: one table of each instrument's error against the input curve per sample.
    let sed: Vec<&output::Outputs> = reports
        .iter()
        .filter(|r| r.prepared.common.kind == Kind::Sedimentation)
        .map(|r| &r.outputs)
        .collect();
    if !sed.is_empty() {
        let t = crate::scenes::sedimentation::output::granulometry::combined_errors_table(sed);
        output::write_atomic(&stage.path(t.name()), &t.to_csv().map_err(io)?).map_err(io)?;
    }
    let names: Vec<String> = reports
        .iter()
        .map(|r| r.prepared.common.name.clone())
        .collect();
    output::report::write_report(&stage.path(""), &output::report::Page::combined(&names))
        .map_err(io)?;
    // Checked before the run (check_destinations); a folder appearing since is an I/O error.
    stage.commit().map_err(io)?;
    Ok(())
}
