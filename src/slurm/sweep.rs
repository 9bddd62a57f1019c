//! `settle sweep S.toml … --slurm N`: a job array of N shards and a merge job after it.

use super::options::{FLAGS, WITH_VALUE};
use super::script::{directives, render, Resources};
use super::submit::{finish, sbatch, sbatch_wait, write_script};
use crate::error::Error;
use crate::sweep::costs::Study;
use crate::sweep::shards::{quote, this_command, Parts, ARRAY_SCRIPT};
use crate::sweep::Args;
use std::path::{Path, PathBuf};

/// The merge job's script, in the sweep's folder.
pub const MERGE_SCRIPT: &str = "slurm_merge.sh";
/// The folder of the jobs' logs, in the sweep's folder.
pub const LOGS: &str = "slurm_logs";
/// What the merge job asks for: 30 min and 2 GB (merging 10 000 parts takes seconds and
/// about 100 MB; see docs/cluster.md).
const MERGE: Resources = Resources {
    time_s: 1800.0,
    mem_bytes: 2e9,
    cpus: 1,
};

/// `settle sweep … --slurm N`: plans and estimates the sweep (bad input exits 2 with nothing
/// written), writes the array and merge scripts into the sweep's folder, submits them (unless
/// `--no-submit`) and prints the job ids; with `--wait`, the merge job's exit code.
pub fn sweep(args: &Args) -> Result<i32, Error> {
    let count = args.slurm.unwrap_or(1) as usize;
    if args.scenarios.len() != 1 {
        return Err(Error::bad_argument(
            "--slurm",
            Path::new(&count.to_string()),
            format!(
                "submits the sweep of one scenario file (got {}): submit each file on its own",
                args.scenarios.len()
            ),
        ));
    }
    let study = Study::plan(args)?;
    if count > study.cases.len() {
        return Err(Error::bad_argument(
            "--slurm",
            Path::new(&count.to_string()),
            format!(
                "more tasks than the {} cases of the grid: allowed 1 to {}",
                study.cases.len(),
                study.cases.len()
            ),
        ));
    }
    let user = &args.submit.sbatch_arg;
    let cpus = cpus_of(user);
    let (wall_s, mem) = study.largest_shard(count);
    let task = Resources::from_estimate(wall_s, mem * cpus as f64, cpus);
    let dir = std::path::absolute(&study.folder).unwrap_or(study.folder.clone());
    let cwd = std::env::current_dir().map_err(|e| Error::Io(".".into(), e))?;
    let logs = dir.join(LOGS);
    std::fs::create_dir_all(&logs).map_err(|e| Error::Io(logs.clone(), e))?;
    let stale = remove_parts(&dir, study.prefix)?;
    let array = dir.join(ARRAY_SCRIPT);
    let merge = dir.join(MERGE_SCRIPT);
    write_script(
        &array,
        &array_script(&study, count, &task, user, &cwd, &logs),
    )?;
    write_script(&merge, &merge_script(args, &study, &dir, user, &cwd, &logs))?;
    let quiet = args.quiet;
    if !quiet && stale > 0 {
        println!(
            "removed {stale} part files of an earlier split from {}",
            dir.display()
        );
    }
    let dep = |id: &str| {
        vec![
            format!("--dependency=afterok:{id}"),
            "--kill-on-invalid-dep=yes".into(),
        ]
    };
    if args.submit.no_submit {
        println!(
            "{}: {count} tasks, each {}; merge job after them",
            study.name,
            describe(&task)
        );
        println!("submit with:");
        println!(
            "  id=$(sbatch --parsable {})",
            quote(&array.display().to_string())
        );
        println!(
            "  sbatch {} {}",
            dep("$id").join(" "),
            quote(&merge.display().to_string())
        );
        return Ok(0);
    }
    let array_id = sbatch(&[], &array)?;
    let out = dir.join(if study.prefix.starts_with("vary") {
        "vary.csv"
    } else {
        "sweep.csv"
    });
    let say = |merge_id: &str| {
        println!(
            "{}: job array {array_id} ({count} tasks: --shard i/{count}, each {}), merge job \
             {merge_id} after it",
            study.name,
            describe(&task)
        );
        if !quiet {
            println!("  scripts: {} and {}", array.display(), merge.display());
            println!("  logs: {}/", logs.display());
            println!(
                "  results: {} when job {merge_id} completes (squeue -j {array_id},{merge_id})",
                out.display()
            );
        }
    };
    if args.submit.wait {
        let (merge_id, child) = sbatch_wait(&dep(&array_id), &merge)?;
        say(&merge_id);
        let (state, code) = finish(child, &merge_id, &merge)?;
        if code != 0 {
            eprintln!(
                "error: merge job {merge_id} ended {state} with exit code {code} (a failed task \
                 cancels it: `settle sweep --merge {}` lists the missing shards and how to rerun \
                 them)",
                quote(&dir.display().to_string())
            );
        }
        return Ok(code);
    }
    let merge_id = sbatch(&dep(&array_id), &merge)?;
    say(&merge_id);
    Ok(0)
}

/// `--cpus-per-task` of the user's sbatch options, else 1.
fn cpus_of(user: &[String]) -> usize {
    user.iter()
        .find_map(|a| {
            a.strip_prefix("--cpus-per-task=")
                .or_else(|| a.strip_prefix("-c"))
                .and_then(|v| v.trim().parse().ok())
        })
        .unwrap_or(1)
}

fn describe(r: &Resources) -> String {
    format!(
        "{} CPU, --time={}, --mem={}",
        r.cpus,
        super::script::time_limit(r.time_s),
        super::script::mem(r.mem_bytes)
    )
}

/// Removes the part files of an earlier split from `dir` (settle's, by their names) and its
/// `shards.toml`, so that the merge cannot take a stale part for a failed task's; how many.
fn remove_parts(dir: &Path, prefix: &str) -> Result<usize, Error> {
    let parts = Parts::of(dir, prefix);
    let mut removed = 0;
    for (_, f) in parts.files.iter().filter(|(_, f)| f.is_file()) {
        std::fs::remove_file(f).map_err(|e| Error::Io(f.clone(), e))?;
        removed += 1;
    }
    let record = dir.join(crate::sweep::shards::COMMAND_FILE);
    if record.is_file() {
        std::fs::remove_file(&record).map_err(|e| Error::Io(record.clone(), e))?;
    }
    Ok(removed)
}

/// The job array: task i runs this command with `--shard i/N` instead of the submission options.
fn array_script(
    study: &Study,
    count: usize,
    task: &Resources,
    user: &[String],
    cwd: &Path,
    logs: &Path,
) -> String {
    let mut d = vec![format!("--job-name=settle-{}", study.name)];
    // The user's --array (a throttle `1-N%K`, or a subset) replaces the whole range.
    if !user
        .iter()
        .any(|a| a.starts_with("--array") || a.starts_with("-a"))
    {
        d.push(format!("--array=1-{count}"));
    }
    d.push(format!("--output={}/shard_%a.out", logs.display()));
    d.extend(directives(task, user));
    let args: Vec<String> = this_command(&[WITH_VALUE, &["--shard"]].concat(), FLAGS)
        .iter()
        .map(|a| quote(a))
        .collect();
    render(
        &format!(
            "shard ${{SLURM_ARRAY_TASK_ID}} of {count} of the sweep of {}",
            study.name
        ),
        &d,
        &[
            format!("cd {}", quote(&cwd.display().to_string())),
            "export RAYON_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-1}\"".into(),
            format!(
                "exec {} --shard \"${{SLURM_ARRAY_TASK_ID}}/{count}\"",
                args.join(" ")
            ),
        ],
    )
}

/// The merge job: `settle sweep --merge DIR S.toml [--set …] [--tol …]`.
fn merge_script(
    args: &Args,
    study: &Study,
    dir: &Path,
    user: &[String],
    cwd: &Path,
    logs: &Path,
) -> String {
    let exe = this_command(&[], &[])
        .into_iter()
        .next()
        .unwrap_or_else(|| "settle".into());
    let mut cmd: Vec<String> = vec![exe, "sweep".into(), "--merge".into(), path(dir)];
    cmd.push(path(&args.scenarios[0]));
    for s in &args.set {
        cmd.push("--set".into());
        cmd.push(s.clone());
    }
    if let Some(t) = args.tol {
        cmd.push(format!("--tol={t}"));
    }
    let mut d = vec![
        format!("--job-name=settle-{}-merge", study.name),
        format!("--output={}/merge_%j.out", logs.display()),
    ];
    // The user's time and memory are for the tasks; the merge keeps its own.
    let own: Vec<String> = user
        .iter()
        .filter(|a| {
            !["--time", "-t", "--mem", "--array", "-a"]
                .iter()
                .any(|o| a.starts_with(o))
        })
        .cloned()
        .collect();
    d.extend(directives(&MERGE, &own));
    let cmd: Vec<String> = cmd.iter().map(|a| quote(a)).collect();
    render(
        &format!("merge the shards of the sweep of {}", study.name),
        &d,
        &[
            format!("cd {}", quote(&cwd.display().to_string())),
            format!("exec {}", cmd.join(" ")),
        ],
    )
}

fn path(p: &Path) -> String {
    let p: PathBuf = p.to_path_buf();
    p.display().to_string()
}
