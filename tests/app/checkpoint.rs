//! Long runs that survive (issue 8): a run killed with SIGKILL at a random moment, or stopped by
//! SIGINT, and resumed with `settle run --resume DIR`, writes the same files, byte for byte, as an
//! uninterrupted run; only `run.toml` differs (its wall time and `resumed = true`), and the
//! `report.html` that shows it. Also: the checkpoint refuses a scenario changed since, and the
//! cost guard refuses runs that would take days or more memory than allowed, naming the file,
//! the key and the estimate.

use crate::common::{assert_exit, settle, tmp, tree};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Every file under `dir`, relative, sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    tree(dir)
        .into_iter()
        .filter(|p| dir.join(p).is_file())
        .collect()
}

/// Asserts that two result folders hold the same files with the same bytes, run.toml aside.
fn assert_same_outputs(a: &Path, b: &Path) {
    let (fa, fb) = (files(a), files(b));
    assert_eq!(fa, fb, "different file sets");
    assert!(fa.len() > 3, "too few files: {fa:?}");
    for f in fa {
        // report.html shows run.toml's record (wall time, resumed), so it differs with it.
        if f == Path::new("run.toml") || f == Path::new("report.html") {
            continue;
        }
        let (x, y) = (
            std::fs::read(a.join(&f)).unwrap(),
            std::fs::read(b.join(&f)).unwrap(),
        );
        assert!(x == y, "{} differs after resuming", f.display());
    }
}

fn run(args: &[&str], out: &Path) -> Output {
    let o = settle()
        .args(args)
        .arg("--quiet")
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

/// A delay drawn from the clock's nanoseconds, in [lo, hi) ms: a different moment every run.
fn random_delay(lo_ms: u64, hi_ms: u64) -> Duration {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .subsec_nanos() as u64;
    Duration::from_millis(lo_ms + nanos % (hi_ms - lo_ms))
}

/// Starts a run with checkpoints every 0.2 s, sends `signal` after a random delay in
/// [lo, hi) ms (once a checkpoint exists), and waits for it.
fn start_and_signal(args: &[&str], out: &Path, signal: &str, lo_ms: u64, hi_ms: u64) -> Output {
    let child = settle()
        .args(args)
        .args(["--quiet", "--checkpoint-every", "0.2", "--out"])
        .arg(out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let delay = random_delay(lo_ms, hi_ms);
    let t0 = Instant::now();
    // Wait for a first checkpoint, then for the random moment.
    while !out.join("checkpoint/request.toml").exists() && t0.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(delay.saturating_sub(t0.elapsed()));
    let pid = child.id().to_string();
    assert!(Command::new("kill")
        .args([signal, &pid])
        .status()
        .unwrap()
        .success());
    eprintln!("{signal} after {:?}", t0.elapsed());
    child.wait_with_output().unwrap()
}

fn resume(out: &Path) -> Output {
    let o = settle()
        .arg("run")
        .arg("--resume")
        .arg(out)
        .arg("--quiet")
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "resume failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// With contacts on (off by default), so that the Rapier world of the clusters is checkpointed.
const SEDIMENTATION: [&str; 6] = [
    "run",
    "scenarios/sedimentation_sample2.toml",
    "--set",
    "sample.particles=20000",
    "--set",
    "sample.contacts=true",
];

/// The sedimentation cylinder (20 000 grains, full physics, 1440 min), killed with SIGKILL at a
/// random moment and resumed: every output file is identical to an uninterrupted run's, the
/// stale staging folder of the killed process is gone, and so is the checkpoint folder.
#[test]
fn sedimentation_killed_and_resumed_matches_an_uninterrupted_run() {
    let dir = tmp();
    let reference = dir.path().join("ref");
    let o = run(&SEDIMENTATION, &reference);
    assert!(o.stderr.is_empty(), "no progress bar when stderr is a pipe");
    let killed = dir.path().join("killed");
    let o = start_and_signal(&SEDIMENTATION, &killed, "-KILL", 600, 2500);
    assert_eq!(o.status.code(), None, "killed by a signal");
    assert!(killed
        .join("checkpoint/sedimentation_sample2.state.bin")
        .is_file());
    assert!(!killed.join("sedimentation_sample2").exists());
    resume(&killed);
    assert_same_outputs(
        &reference.join("sedimentation_sample2"),
        &killed.join("sedimentation_sample2"),
    );
    let run_toml = std::fs::read_to_string(killed.join("sedimentation_sample2/run.toml")).unwrap();
    assert!(run_toml.contains("resumed = true"), "{run_toml}");
    assert!(run_toml.contains("status = \"complete\""), "{run_toml}");
    let left: Vec<_> = std::fs::read_dir(&killed)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(left, ["sedimentation_sample2"], "left behind: {left:?}");
}

/// SIGINT: the run stops at the end of a step, writes what it recorded (status "interrupted",
/// exit 130) and a checkpoint; resumed, it ends with the uninterrupted run's files.
#[test]
fn sedimentation_interrupted_and_resumed_matches_an_uninterrupted_run() {
    let dir = tmp();
    let reference = dir.path().join("ref");
    run(&SEDIMENTATION, &reference);
    let stopped = dir.path().join("stopped");
    let o = start_and_signal(&SEDIMENTATION, &stopped, "-INT", 600, 2500);
    assert_exit(&o, 130);
    let partial = std::fs::read_to_string(stopped.join("sedimentation_sample2/run.toml")).unwrap();
    assert!(partial.contains("status = \"interrupted\""), "{partial}");
    assert!(stopped
        .join("checkpoint/sedimentation_sample2.state.bin")
        .is_file());
    resume(&stopped);
    assert_same_outputs(
        &reference.join("sedimentation_sample2"),
        &stopped.join("sedimentation_sample2"),
    );
}

const FUNNEL: [&str; 6] = [
    "run",
    "scenarios/paste_68_balls.toml",
    "--set",
    "repeats.count=2",
    "--dt",
    "1e-4",
];

/// The 68-ball pour (2 repeats in parallel, Rapier worlds serialized with their contacts and
/// joints), killed at a random moment and resumed: identical files.
#[test]
fn funnel_pour_killed_and_resumed_matches_an_uninterrupted_run() {
    let dir = tmp();
    let reference = dir.path().join("ref");
    run(&FUNNEL, &reference);
    let killed = dir.path().join("killed");
    let o = start_and_signal(&FUNNEL, &killed, "-KILL", 300, 1200);
    if o.status.success() {
        // The run finished before the signal: nothing to resume, outputs must still match.
        assert_same_outputs(
            &reference.join("paste_68_balls"),
            &killed.join("paste_68_balls"),
        );
        return;
    }
    resume(&killed);
    assert_same_outputs(
        &reference.join("paste_68_balls"),
        &killed.join("paste_68_balls"),
    );
}

/// A scenario edited between the kill and the resume is refused: its state would not belong to
/// it.
#[test]
fn resume_refuses_a_changed_scenario() {
    let dir = tmp();
    let scenario = dir.path().join("pour.toml");
    std::fs::copy("scenarios/paste_68_balls.toml", &scenario).unwrap();
    let out = dir.path().join("out");
    let args = [
        "run",
        scenario.to_str().unwrap(),
        "--set",
        "repeats.count=2",
        "--dt",
        "1e-4",
    ];
    let o = start_and_signal(&args, &out, "-INT", 200, 400);
    if o.status.success() {
        return; // finished first; nothing to resume
    }
    let text = std::fs::read_to_string(&scenario).unwrap();
    std::fs::write(
        &scenario,
        text.replace("friction = 0.341", "friction = 0.4"),
    )
    .unwrap();
    let o = settle()
        .args(["run", "--resume"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("request.toml") && e.contains("changed"), "{e}");
}

/// `--resume` on a folder without a checkpoint says so.
#[test]
fn resume_without_checkpoint_is_refused() {
    let dir = tmp();
    let o = settle()
        .args(["run", "--resume"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("no checkpointed run"), "{e}");
}

/// The cost guard: 10¹² grains would need 300 TB, more than any machine here: refused with the
/// estimate even with --force; 3.5·10⁷ grains (10.5 GB) is over the 8 GB limit: refused, naming
/// --force; a 68-ball pour of 15 repeats at dt = 1e-8 s (1e8 steps × 1020 bodies ≈ 28 h) is
/// refused for its time. Nothing is written.
#[test]
fn cost_guard_refuses_runs_beyond_the_limits() {
    let dir = tmp();
    let cases: [(&[&str], &[&str]); 3] = [
        (
            &[
                "scenarios/sedimentation_sample5.toml",
                "--set",
                "sample.particles=1000000000000",
                "--force",
            ],
            &["sample.particles", "GB", "even with --force"],
        ),
        (
            &[
                "scenarios/sedimentation_sample5.toml",
                "--set",
                "sample.particles=35000000",
            ],
            &["sample.particles", "10.5 GB", "--force"],
        ),
        (
            &[
                "scenarios/paste_68_balls.toml",
                "--set",
                "repeats.count=15",
                "--dt",
                "1e-8",
            ],
            &["time.dt_s", "h of wall time", "--force"],
        ),
    ];
    for (args, words) in cases {
        let o = settle()
            .arg("run")
            .args(args)
            .arg("--out")
            .arg(dir.path())
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2));
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(e.contains(args[0]), "names the file: {e}");
        for w in words {
            assert!(e.contains(w), "`{w}` missing: {e}");
        }
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    // --force lifts the time limit (checked without running it).
    let p = settle::run::prepare(
        Path::new("scenarios/paste_68_balls.toml"),
        Some(1e-8),
        &["repeats.count=15".into()],
    )
    .unwrap();
    let path = Path::new("scenarios/paste_68_balls.toml");
    assert!(settle::scenes::cost::check(&p.scenario, path, false).is_err());
    let c = settle::scenes::cost::check(&p.scenario, path, true).unwrap();
    assert!(c.wall_s > 24.0 * 3600.0, "{c:?}");
}
