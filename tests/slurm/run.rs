//! `settle run --slurm`: a sedimentation cylinder signalled before its time limit,
//! checkpointed, requeued and resumed on the local Slurm, byte for byte the uninterrupted run.

use super::require_slurm;
use crate::common::{settle, tmp, tree};
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");
/// 20 000 grains with contacts: about 30 s of CPU, checkpointed every 0.5 s.
const RUN: &[&str] = &[
    "run",
    "scenarios/sedimentation_sample2.toml",
    "--set",
    "sample.particles=20000",
    "--set",
    "sample.contacts=true",
    "--checkpoint-every",
    "0.5",
    "-q",
];

/// `scontrol show job ID` as one line (empty once Slurm forgot the job).
fn job(id: &str) -> String {
    let o = Command::new("scontrol")
        .args(["show", "job", "-o", id])
        .output()
        .unwrap();
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The value of `KEY=` in a line of `scontrol show job -o`.
fn field<'a>(line: &'a str, key: &str) -> &'a str {
    line.split_whitespace()
        .find_map(|w| w.strip_prefix(&format!("{key}=")))
        .unwrap_or("")
}

/// Polls `ready` every 0.2 s for up to 10 minutes.
fn until(what: &str, mut ready: impl FnMut() -> bool) {
    let t0 = Instant::now();
    while !ready() {
        assert!(
            t0.elapsed() < Duration::from_secs(600),
            "timed out waiting: {what}"
        );
        std::thread::sleep(Duration::from_millis(200));
    }
}

/// Every file of a run's folder but run.toml and report.html (which show the wall time and
/// `resumed = true`), with its bytes.
fn outputs(dir: &Path) -> Vec<(std::path::PathBuf, Vec<u8>)> {
    tree(dir)
        .into_iter()
        .filter(|p| dir.join(p).is_file())
        .filter(|p| p != Path::new("run.toml") && p != Path::new("report.html"))
        .map(|p| {
            let b = std::fs::read(dir.join(&p)).unwrap();
            (p, b)
        })
        .collect()
}

#[test]
fn a_sedimentation_run_signalled_before_its_limit_is_requeued_and_resumed_identically() {
    require_slurm();
    let dir = tmp();
    let out = dir.path().join("cluster");
    let o = settle()
        .current_dir(ROOT)
        .args(RUN)
        .args([
            "--slurm",
            "--sbatch-arg=--time=1",
            "--sbatch-arg=--signal=B:USR1@10",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{said}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // The first line ends with `job ID`.
    let id = said
        .lines()
        .next()
        .and_then(|l| l.split_whitespace().last())
        .unwrap_or_else(|| panic!("no job id in {said}"))
        .to_string();
    assert!(id.chars().all(|c| c.is_ascii_digit()), "{said}");
    let script = std::fs::read_to_string(out.join("slurm_run_sedimentation_sample2.sh")).unwrap();
    assert!(script.contains("#SBATCH --requeue\n"), "{script}");
    assert!(script.contains("#SBATCH --signal=B:USR1@10\n"), "{script}");
    // The warning, as Slurm sends it W seconds before the limit (--signal=B:USR1@W: to the
    // batch shell), once the run has a checkpoint: sent here rather than waited for, as Slurm's
    // timer fires within a minute of the moment asked.
    until("a checkpoint", || {
        out.join("checkpoint/sedimentation_sample2.state.bin")
            .is_file()
    });
    // (Slurm's own warning may come first: the job is then requeued already and scancel,
    // finding no batch shell, fails; either way the job restarts.)
    let _ = Command::new("scancel")
        .args(["--batch", "--signal=USR1", &id])
        .status();
    // Requeued jobs wait 2 min before they are eligible again (Slurm's rule): each restart
    // (this warning's, and Slurm's own at --time=1 with @10) is started at once.
    until("the end of the job", || {
        let s = job(&id);
        if field(&s, "JobState") == "PENDING" && field(&s, "Reason") == "BeginTime" {
            let _ = Command::new("scontrol")
                .args(["update", &format!("JobId={id}"), "StartTime=now"])
                .status();
        }
        ![
            "PENDING",
            "RUNNING",
            "COMPLETING",
            "REQUEUED",
            "CONFIGURING",
        ]
        .contains(&field(&s, "JobState"))
    });
    let j = job(&id);
    let log = std::fs::read_to_string(out.join("slurm_run_sedimentation_sample2.out")).unwrap();
    assert_eq!(field(&j, "JobState"), "COMPLETED", "{j}\n{log}");
    let restarts: u32 = field(&j, "Restarts").parse().unwrap_or(0);
    assert!(restarts >= 1, "never requeued: {j}\n{log}");
    eprintln!("requeued {restarts} times");
    assert!(
        log.contains("requeueing job") && log.contains("run --resume"),
        "{log}"
    );
    let record = std::fs::read_to_string(out.join("sedimentation_sample2/run.toml")).unwrap();
    assert!(record.contains("resumed = true") && record.contains("status = \"complete\""));
    assert!(!out.join("checkpoint").exists(), "checkpoint left behind");
    // The same run, uninterrupted and off Slurm.
    let local = dir.path().join("local");
    let o = settle()
        .current_dir(ROOT)
        .args(RUN)
        .arg("--out")
        .arg(&local)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (a, b) = (
        outputs(&out.join("sedimentation_sample2")),
        outputs(&local.join("sedimentation_sample2")),
    );
    assert!(a.len() > 20, "{} files", a.len());
    let names =
        |v: &[(std::path::PathBuf, Vec<u8>)]| v.iter().map(|x| x.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(&a), names(&b));
    for ((f, x), (_, y)) in a.iter().zip(&b) {
        assert!(x == y, "{} differs from the uninterrupted run", f.display());
    }
}
