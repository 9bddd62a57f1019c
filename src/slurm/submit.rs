//! Writing job scripts (never over a file settle did not write) and submitting them with
//! `sbatch --parsable`.

use super::script::MARK;
use crate::error::Error;
use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};

/// Writes the script `text` to `path` (executable), atomically; a file there that settle did not
/// write is refused (bad input naming it).
pub fn write_script(path: &Path, text: &str) -> Result<(), Error> {
    if let Ok(old) = std::fs::read_to_string(path) {
        if !old.lines().nth(1).is_some_and(|l| l.starts_with(MARK)) {
            return Err(Error::bad_argument(
                "--slurm",
                path,
                "exists and was not written by settle, which will not replace it: move it away \
                 or choose another --out",
            ));
        }
    } else if path.exists() {
        return Err(Error::bad_argument(
            "--slurm",
            path,
            "exists and is not a script settle wrote: move it away or choose another --out",
        ));
    }
    let io = |e| Error::Io(path.to_path_buf(), e);
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(io)?;
    }
    crate::io::write_atomic(path, text.as_bytes()).map_err(io)?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755)).map_err(io)?;
    }
    Ok(())
}

/// The `sbatch` command with `--parsable`, `extra` options and the script.
fn sbatch_command(extra: &[String], script: &Path) -> Command {
    let mut c = Command::new("sbatch");
    c.arg("--parsable").args(extra).arg(script);
    c
}

fn not_found(e: std::io::Error) -> Error {
    Error::Io(
        "sbatch".into(),
        std::io::Error::new(
            e.kind(),
            format!(
                "cannot run sbatch ({e}): is this a Slurm login node? --no-submit writes the job \
                 scripts without submitting them"
            ),
        ),
    )
}

/// The job id of `sbatch --parsable`'s first line (`ID` or `ID;CLUSTER`).
fn job_id(line: &str, script: &Path) -> Result<String, Error> {
    let id = line.trim().split(';').next().unwrap_or("").to_string();
    if id.is_empty() || !id.chars().all(|c| c.is_ascii_digit()) {
        return Err(Error::Io(
            script.to_path_buf(),
            std::io::Error::other(format!("sbatch printed no job id: `{}`", line.trim())),
        ));
    }
    Ok(id)
}

/// Submits `script` with `extra` options; returns the job id. A refusal by sbatch is an I/O
/// error with sbatch's message.
pub fn sbatch(extra: &[String], script: &Path) -> Result<String, Error> {
    let o = sbatch_command(extra, script).output().map_err(not_found)?;
    if !o.status.success() {
        return Err(Error::Io(
            script.to_path_buf(),
            std::io::Error::other(format!(
                "sbatch refused the job: {}",
                String::from_utf8_lossy(&o.stderr).trim()
            )),
        ));
    }
    job_id(&String::from_utf8_lossy(&o.stdout), script)
}

/// Submits `script` with `--wait`: returns its job id as soon as sbatch prints it, and the
/// running sbatch, whose exit code will be the job's.
pub fn sbatch_wait(extra: &[String], script: &Path) -> Result<(String, Child), Error> {
    let mut extra = extra.to_vec();
    extra.push("--wait".into());
    let mut child = sbatch_command(&extra, script)
        .stdout(Stdio::piped())
        .spawn()
        .map_err(not_found)?;
    let mut line = String::new();
    if let Some(out) = child.stdout.take() {
        BufReader::new(out)
            .read_line(&mut line)
            .map_err(|e| Error::Io(script.to_path_buf(), e))?;
    }
    match job_id(&line, script) {
        Ok(id) => Ok((id, child)),
        Err(e) => {
            let _ = child.wait();
            Err(e)
        }
    }
}

/// Waits for the `sbatch --wait` of job `id` to end; the job's final state (`COMPLETED`,
/// `FAILED`, `CANCELLED`…, as `scontrol show job` gives it; `UNKNOWN` once Slurm forgot the job)
/// and exit code: the job's, or 1 for a job that did not complete (sbatch exits 0 for a job
/// cancelled before it started, e.g. by a dependency that can no longer be met).
pub fn finish(mut child: Child, id: &str, script: &Path) -> Result<(String, i32), Error> {
    let status = child
        .wait()
        .map_err(|e| Error::Io(script.to_path_buf(), e))?;
    let waited = status.code().unwrap_or(1);
    let shown = Command::new("scontrol")
        .args(["show", "job", "-o", id])
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
        .unwrap_or_default();
    let field = |key: &str| {
        shown
            .split_whitespace()
            .find_map(|w| w.strip_prefix(key).map(str::to_string))
    };
    let Some(state) = field("JobState=") else {
        return Ok(("UNKNOWN".into(), waited));
    };
    let code: i32 = field("ExitCode=")
        .and_then(|c| c.split(':').next()?.parse().ok())
        .unwrap_or(waited);
    Ok(match state.as_str() {
        "COMPLETED" => (state, code),
        _ => (state, code.max(waited).max(1)),
    })
}
