//! `settle run S.toml --slurm`: one long run as a job that survives its time limit and
//! preemption. The job asks for `--requeue` and `--signal=B:USR1@W`: W seconds before the limit
//! Slurm signals the job script, which asks settle to stop (SIGTERM: a sedimentation or
//! funnel-pour run writes its checkpoint to `OUT/checkpoint/` and exits with 130) and requeues
//! the job; the next start finds the checkpoint and runs `settle run --resume OUT`. The outputs
//! are those of an uninterrupted run, byte for byte (`run.toml` aside: its wall time and
//! `resumed = true`).

use super::options::{Submit, FLAGS, WITH_VALUE};
use super::script::{directives, render, Resources};
use super::submit::{finish, sbatch, sbatch_wait, write_script};
use crate::error::Error;
use crate::run::{check_destinations, prepare, RunRequest};
use crate::scenes::cost::estimate;
use crate::scenes::Prepared;
use crate::sweep::shards::{quote, this_command};
use std::path::Path;

/// Seconds before the time limit at which Slurm sends the warning (`--signal=B:USR1@W`): time
/// to write the checkpoint of a large cylinder on a shared filesystem, with the minute of
/// slack of Slurm's signal timer.
pub const WARNING_S: u64 = 180;

/// Writes the job script into the output folder and submits it (see the module doc); the exit
/// code (with `--wait`, the job's).
pub fn run(req: &RunRequest, submit: &Submit) -> Result<i32, Error> {
    let prepared: Vec<Prepared> = req
        .files
        .iter()
        .map(|f| prepare(f, req.dt_s, &req.overrides))
        .collect::<Result<_, _>>()
        .map_err(Error::BadInput)?;
    check_destinations(&req.out_dir, &prepared)?;
    let wall: f64 = prepared.iter().map(|p| estimate(p).wall_s).sum();
    let mem = prepared
        .iter()
        .map(|p| estimate(p).memory_bytes)
        .fold(0.0, f64::max);
    let user = &submit.sbatch_arg;
    let task = Resources::from_estimate(wall, mem, 1);
    let name = &prepared[0].common.name;
    let out = std::path::absolute(&req.out_dir).unwrap_or(req.out_dir.clone());
    let script = script_path(&out, name);
    let log = out.join(format!("slurm_run_{name}.out"));
    let cwd = std::env::current_dir().map_err(|e| Error::Io(".".into(), e))?;
    let mut d = vec![
        format!("--job-name=settle-run-{name}"),
        "--requeue".into(),
        "--open-mode=append".into(),
        format!("--output={}", log.display()),
    ];
    if !user.iter().any(|a| a.starts_with("--signal")) {
        d.push(format!("--signal=B:USR1@{WARNING_S}"));
    }
    d.extend(directives(&task, user));
    let flags = [FLAGS, &["--slurm"]].concat();
    let args: Vec<String> = this_command(WITH_VALUE, &flags)
        .iter()
        .map(|a| quote(a))
        .collect();
    let exe = quote(&this_command(&[], &[])[0]);
    let o = quote(&out.display().to_string());
    let body: Vec<String> = vec![
        format!("cd {}", quote(&cwd.display().to_string())),
        "export RAYON_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-1}\"".into(),
        format!("if [ -f {o}/checkpoint/request.toml ]; then"),
        format!("    set -- {exe} run --resume {o}"),
        "else".into(),
        format!("    set -- {}", args.join(" ")),
        "fi".into(),
        "echo \"settle: job $SLURM_JOB_ID (restart ${SLURM_RESTART_COUNT:-0}) on $(hostname): $*\""
            .into(),
        "# The warning before the time limit (--signal=B:USR1) reaches this shell: ask settle to"
            .into(),
        "# stop (it checkpoints and exits with 130), then requeue the job, which resumes.".into(),
        "warned=0".into(),
        "trap 'warned=1; kill -TERM \"$pid\" 2>/dev/null' USR1".into(),
        "\"$@\" &".into(),
        "pid=$!".into(),
        "while :; do".into(),
        "    wait \"$pid\"; rc=$?".into(),
        "    kill -0 \"$pid\" 2>/dev/null || break".into(),
        "done".into(),
        "# 130: stopped by the warning (checkpointed if it had started; else it starts afresh)."
            .into(),
        "if [ \"$warned\" = 1 ] && [ \"$rc\" -eq 130 ]; then".into(),
        "    echo \"settle: stopped before the time limit; requeueing job $SLURM_JOB_ID\"".into(),
        "    scontrol requeue \"$SLURM_JOB_ID\"".into(),
        "    exit 0".into(),
        "fi".into(),
        "exit \"$rc\"".into(),
    ];
    let text = render(
        &format!("the run of {name}, requeued and resumed from its checkpoint until done"),
        &d,
        &body,
    );
    write_script(&script, &text)?;
    let what = format!(
        "{name}: one job (--requeue, checkpoint on the warning signal), {} CPU, --time={}, --mem={}",
        task.cpus,
        super::script::time_limit(task.time_s),
        super::script::mem(task.mem_bytes)
    );
    if submit.no_submit {
        println!(
            "{what}\nsubmit with:\n  sbatch {}",
            quote(&script.display().to_string())
        );
        return Ok(0);
    }
    let say = |id: &str| {
        println!("{what}: job {id}");
        if !req.quiet {
            println!("  script: {}", script.display());
            println!("  log: {}", log.display());
            println!(
                "  results: {}/ when job {id} completes (squeue -j {id})",
                out.join(name).display()
            );
        }
    };
    if submit.wait {
        let (id, child) = sbatch_wait(&[], &script)?;
        say(&id);
        let (state, code) = finish(child, &id, &script)?;
        if code != 0 {
            eprintln!(
                "error: job {id} ended {state} with exit code {code}; see {}",
                log.display()
            );
        }
        return Ok(code);
    }
    let id = sbatch(&[], &script)?;
    say(&id);
    Ok(0)
}

/// The job script of a run whose output folder is `out` and first scenario `name` (its log:
/// the same name ending in `.out`).
pub fn script_path(out: &Path, name: &str) -> std::path::PathBuf {
    out.join(format!("slurm_run_{name}.sh"))
}
