//! Long runs that survive (issue 8): a run killed with SIGKILL at a random moment, or stopped by
//! SIGINT, and resumed with `settle run --resume DIR`, writes the same files, byte for byte, as an
//! uninterrupted run; only `run.toml` differs (its wall time and `resumed = true`), and the
//! `report.html` that shows it. Also: the checkpoint refuses a scenario changed since, and the
//! cost guard refuses runs that would take days or more memory than allowed, naming the file,
//! the key and the estimate.

use crate::common::{
    has_checkpoint, random_between, run_measured, settle, test_seed, tmp, tree, try_signal_when,
    Signalled, HANG,
};
use std::path::{Path, PathBuf};
use std::process::Output;
use std::sync::OnceLock;
use std::time::Duration;

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

/// Runs `settle ARGS --quiet --out OUT` to its end; its output and the CPU time it used.
fn run(args: &[&str], out: &Path) -> (Output, Duration) {
    let mut cmd = settle();
    cmd.args(args).arg("--quiet").arg("--out").arg(out);
    let (o, cpu) = run_measured(cmd);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (o, cpu)
}

/// Starts a run with checkpoints every 0.2 s and sends it `signal` (`"KILL"`, `"INT"`) at a
/// random moment after its first checkpoint: once it has used a fraction in [0.05, 0.4) of
/// `whole`, the CPU time of the same run uninterrupted (the fraction drawn from
/// [`test_seed`]). Measured in CPU time, the moment falls inside the run however loaded the
/// machine. The CPU time of a parallel run varies with the load (by a third between two runs
/// of the funnel), so a run that ends before the signal is started again (in a fresh folder) at
/// half the fraction, up to [`ATTEMPTS`] times: the signal always comes while the run is going
/// and there is a checkpoint to resume from, or the test fails.
fn start_and_signal(args: &[&str], out: &Path, signal: &str, whole: Duration) -> Signalled {
    let seed = test_seed();
    let mut fraction = random_between(seed, 0.05, 0.4);
    for attempt in 1..=ATTEMPTS {
        let mut cmd = settle();
        cmd.args(args)
            .args(["--quiet", "--checkpoint-every", "0.2", "--out"])
            .arg(out);
        let at = whole.mul_f64(fraction);
        eprintln!("attempt {attempt}: {signal} once the run has a checkpoint and {at:?} of CPU");
        let ready = |_, used| used >= at && has_checkpoint(out);
        match try_signal_when(cmd, signal, ready, HANG) {
            Ok(o) => return o,
            Err(e) => eprintln!("{e}"),
        }
        let _ = std::fs::remove_dir_all(out);
        fraction /= 2.0;
    }
    panic!("the run ended before the {signal} {ATTEMPTS} times (SETTLE_TEST_SEED={seed})");
}

/// Runs of [`start_and_signal`] before it gives up.
const ATTEMPTS: u32 = 3;

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
    "sample.particles=10000",
    "--set",
    "sample.contacts=true",
];

/// The uninterrupted run of [`SEDIMENTATION`], made once for the tests that compare with it
/// (in cargo's folder for integration tests' files, replaced at each test run): its results
/// folder and the CPU time it used.
fn sedimentation_reference() -> &'static (PathBuf, Duration) {
    static REFERENCE: OnceLock<(PathBuf, Duration)> = OnceLock::new();
    REFERENCE.get_or_init(|| {
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("checkpoint_reference");
        let _ = std::fs::remove_dir_all(&out);
        let (o, whole) = run(&SEDIMENTATION, &out);
        assert!(o.stderr.is_empty(), "no progress bar when stderr is a pipe");
        (out.join("sedimentation_sample2"), whole)
    })
}

/// The sedimentation cylinder (10 000 grains, full physics, 1440 min), killed with SIGKILL at a
/// random moment and resumed: every output file is identical to an uninterrupted run's, the
/// stale staging folder of the killed process is gone, and so is the checkpoint folder.
#[test]
fn sedimentation_killed_and_resumed_matches_an_uninterrupted_run() {
    let dir = tmp();
    let (reference, whole) = sedimentation_reference();
    let killed = dir.path().join("killed");
    let o = start_and_signal(&SEDIMENTATION, &killed, "KILL", *whole);
    assert_eq!(o.code, None, "killed by a signal");
    assert!(killed
        .join("checkpoint/sedimentation_sample2.state.bin")
        .is_file());
    assert!(!killed.join("sedimentation_sample2").exists());
    resume(&killed);
    assert_same_outputs(reference, &killed.join("sedimentation_sample2"));
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
    let (reference, whole) = sedimentation_reference();
    let stopped = dir.path().join("stopped");
    let o = start_and_signal(&SEDIMENTATION, &stopped, "INT", *whole);
    assert_eq!(o.code, Some(130), "{}", o.stderr);
    let partial = std::fs::read_to_string(stopped.join("sedimentation_sample2/run.toml")).unwrap();
    assert!(partial.contains("status = \"interrupted\""), "{partial}");
    // The record says which simulated time the run reached (issue 26); a complete run's does not.
    let reached: f64 = partial
        .lines()
        .find_map(|l| l.strip_prefix("reached_s = "))
        .unwrap_or_else(|| panic!("no reached_s in {partial}"))
        .parse()
        .unwrap();
    assert!(reached > 0.0 && reached < 86_400.0, "{partial}");
    let complete = std::fs::read_to_string(reference.join("run.toml")).unwrap();
    assert!(!complete.contains("reached_s"), "{complete}");
    assert!(stopped
        .join("checkpoint/sedimentation_sample2.state.bin")
        .is_file());
    resume(&stopped);
    assert_same_outputs(reference, &stopped.join("sedimentation_sample2"));
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
/// joints), killed at a random moment after its first checkpoint and resumed: identical files,
/// and the run says it was resumed.
#[test]
fn funnel_pour_killed_and_resumed_matches_an_uninterrupted_run() {
    let dir = tmp();
    let reference = dir.path().join("ref");
    let (_, whole) = run(&FUNNEL, &reference);
    let killed = dir.path().join("killed");
    let o = start_and_signal(&FUNNEL, &killed, "KILL", whole);
    assert_eq!(o.code, None, "killed by a signal");
    assert!(has_checkpoint(&killed), "no checkpoint to resume from");
    assert!(
        !killed.join("paste_68_balls").exists(),
        "finished before the kill"
    );
    resume(&killed);
    assert_same_outputs(
        &reference.join("paste_68_balls"),
        &killed.join("paste_68_balls"),
    );
    let run_toml = std::fs::read_to_string(killed.join("paste_68_balls/run.toml")).unwrap();
    assert!(run_toml.contains("resumed = true"), "{run_toml}");
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
    let (_, whole) = run(&args, &dir.path().join("ref"));
    let o = start_and_signal(&args, &out, "INT", whole);
    assert_eq!(o.code, Some(130), "{}", o.stderr);
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
            &[
                "sample.particles",
                "9.6 GB",
                "--force",
                "sample.snapshot_times_s",
            ],
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
    // --force lifting the time limit: `scenes::tests::cost_guard_force` (a unit test).
}
