//! Tests that signal a running `settle` (issue 24, item 7): the moment of the signal is decided
//! by a condition on the child (the CPU time it used, a checkpoint it wrote), never by a fixed
//! sleep, and every wait is bounded by [`HANG`], which only catches a hang. A loaded two-core
//! machine then changes how long these tests take, not what they check.
//!
//! CPU time (`/proc/PID/stat`, Linux) measures how far a run got whatever the load: a child
//! given a tenth of a core for a second has done a tenth of a second of work. Where `/proc` is
//! missing, wall time stands in for it.

use std::io::Read;
use std::path::Path;
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The longest wait of any of these tests: reached only by a run that hangs or ignores a
/// signal (it is then killed, so that the test fails instead of hanging).
pub const HANG: Duration = Duration::from_secs(60);

/// Polls `cond` every 10 ms until it holds or `limit` has passed; whether it held.
pub fn wait_for(limit: Duration, mut cond: impl FnMut() -> bool) -> bool {
    let t0 = Instant::now();
    loop {
        if cond() {
            return true;
        }
        if t0.elapsed() >= limit {
            return false;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// The seed of a test's random moments: `SETTLE_TEST_SEED` if set, else drawn from the clock.
/// Printed on stderr (shown with a failing test's output), so that a failure is replayed with
/// `SETTLE_TEST_SEED=<seed> cargo test …`.
pub fn test_seed() -> u64 {
    let seed = match std::env::var("SETTLE_TEST_SEED") {
        Ok(s) => s
            .trim()
            .parse()
            .unwrap_or_else(|_| panic!("SETTLE_TEST_SEED = `{s}`: not an unsigned integer")),
        Err(_) => std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .expect("clock after 1970")
            .as_nanos() as u64,
    };
    eprintln!("SETTLE_TEST_SEED={seed}");
    seed
}

/// A number in [lo, hi) drawn from `seed` (one step of SplitMix64: every seed gives another
/// well-spread value).
pub fn random_between(seed: u64, lo: f64, hi: f64) -> f64 {
    let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    lo + (hi - lo) * (z >> 11) as f64 / (1u64 << 53) as f64
}

/// CPU time (user + system, every thread) that process `pid` has used so far, from
/// `/proc/PID/stat` (fields 14 and 15, in clock ticks of 1/100 s: Linux's USER_HZ). None where
/// there is no `/proc`, or once the process has exited.
pub fn cpu_time(pid: u32) -> Option<Duration> {
    let text = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name, in parentheses, may hold spaces: count the fields after it.
    let fields: Vec<&str> = text[text.rfind(')')? + 1..].split_whitespace().collect();
    if fields.first() == Some(&"Z") {
        return None;
    }
    let ticks: u64 = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    Some(Duration::from_millis(10 * ticks))
}

/// How far a child got: its CPU time, or the wall time since `start` where there is no
/// `/proc`.
fn progress(child: &Child, start: Instant) -> Duration {
    cpu_time(child.id()).unwrap_or_else(|| start.elapsed())
}

/// `cmd` started with stdout discarded and stderr read by a thread (so that a chatty run never
/// blocks on a full pipe); join the thread for the text.
fn spawn(mut cmd: Command) -> (Child, std::thread::JoinHandle<String>) {
    let mut child = cmd
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn settle");
    let mut err = child.stderr.take().expect("stderr");
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err.read_to_string(&mut s);
        s
    });
    (child, reader)
}

/// Runs `cmd` to its end; its output (stdout discarded) and the CPU time it used (the last
/// sample before it exited; wall time where there is no `/proc`). Killed after [`HANG`].
pub fn run_measured(cmd: Command) -> (Output, Duration) {
    let (mut child, reader) = spawn(cmd);
    let start = Instant::now();
    let mut used = Duration::ZERO;
    let ended = wait_for(HANG, || {
        used = used.max(progress(&child, start));
        child.try_wait().expect("wait").is_some()
    });
    if !ended {
        let _ = child.kill();
    }
    let status = child.wait().expect("wait");
    let stderr = reader.join().expect("stderr").into_bytes();
    assert!(ended, "the run did not end within {HANG:?}");
    let o = Output {
        status,
        stdout: Vec::new(),
        stderr,
    };
    (o, used)
}

/// What [`signal_when`] saw of a run it signalled.
#[cfg(unix)]
pub struct Signalled {
    /// Exit code (None: ended by a signal, e.g. SIGKILL, or killed after [`HANG`]).
    pub code: Option<i32>,
    /// Everything the run printed on stderr.
    pub stderr: String,
    /// Wall time from the signal to the exit (at least the limit when the run had to be killed).
    pub waited: Duration,
    /// CPU time the run used from the signal to its exit (its last sample; None without
    /// `/proc`): the work it did after the signal, whatever the load of the machine.
    pub cpu_after: Option<Duration>,
}

#[cfg(unix)]
impl Signalled {
    /// Asserts that the run stopped within `bound` of the signal: by the wall clock, or, on a
    /// machine so loaded that the wall time says little, by the CPU time it used after the
    /// signal (the work it did before stopping).
    pub fn assert_stopped_within(&self, bound: Duration, what: &str) {
        let by_cpu = self.cpu_after.is_some_and(|c| c < bound);
        assert!(
            self.code.is_some() && (self.waited < bound || by_cpu),
            "{what}: not stopped within {bound:?} of the signal (exit {:?} after {:?} of wall \
             time, {:?} of CPU time); stderr: {}",
            self.code,
            self.waited,
            self.cpu_after,
            self.stderr
        );
    }
}

/// Spawns `cmd` (stdout discarded, stderr kept), waits until `ready(pid, progress)` holds
/// (`progress`: the CPU time it used so far, see [`cpu_time`]), sends it `signal` (`"INT"`,
/// `"TERM"`, `"KILL"`) and waits at most `limit` for its exit; a run still going then is killed
/// (SIGKILL), so that a test of a binary that ignores the signal fails instead of hanging.
/// Panics, naming `what`, if the run ended before the signal or never got ready within
/// [`HANG`].
#[cfg(unix)]
pub fn signal_when(
    cmd: Command,
    signal: &str,
    ready: impl FnMut(u32, Duration) -> bool,
    limit: Duration,
    what: &str,
) -> Signalled {
    try_signal_when(cmd, signal, ready, limit).unwrap_or_else(|e| panic!("{what}: {e}"))
}

/// [`signal_when`], with Err (saying what happened, and the run's stderr) instead of a panic
/// when the run ended before the signal or never got ready within [`HANG`].
#[cfg(unix)]
pub fn try_signal_when(
    cmd: Command,
    signal: &str,
    mut ready: impl FnMut(u32, Duration) -> bool,
    limit: Duration,
) -> Result<Signalled, String> {
    let (mut child, reader) = spawn(cmd);
    let start = Instant::now();
    let pid = child.id();
    let mut ended = false;
    let got_ready = wait_for(HANG, || {
        ended = child.try_wait().expect("wait").is_some();
        !ended && ready(pid, progress(&child, start))
    });
    if ended || !got_ready {
        let _ = child.kill();
        let _ = child.wait();
        let err = reader.join().unwrap_or_default();
        return Err(format!(
            "{} before the signal; stderr: {err}",
            if ended {
                "the run ended"
            } else {
                "the run never got ready"
            }
        ));
    }
    let cpu0 = cpu_time(pid);
    let sent = Command::new("kill")
        .args([format!("-{signal}"), pid.to_string()])
        .status()
        .expect("kill");
    assert!(sent.success(), "kill -{signal} failed");
    let t0 = Instant::now();
    let mut cpu_last = cpu0;
    let stopped = wait_for(limit, || {
        if let Some(c) = cpu_time(pid) {
            cpu_last = Some(c);
        }
        child.try_wait().expect("wait").is_some()
    });
    let waited = t0.elapsed();
    if !stopped {
        let _ = child.kill();
    }
    let status = child.wait().expect("wait");
    Ok(Signalled {
        code: status.code(),
        stderr: reader.join().expect("stderr"),
        waited,
        cpu_after: cpu0.zip(cpu_last).map(|(a, b)| b.saturating_sub(a)),
    })
}

/// [`signal_when`] the run has used `cpu` of CPU time (wall time without `/proc`): past its
/// setup, into its work, however loaded the machine.
#[cfg(unix)]
pub fn signalled(cmd: Command, signal: &str, cpu: Duration, limit: Duration) -> Signalled {
    signal_when(cmd, signal, |_, used| used >= cpu, limit, "signalled")
}

/// Whether `dir` holds a checkpointed state (`<scenario>.<part>.bin`, written by a rename, so
/// complete once it is there).
pub fn has_checkpoint(dir: &Path) -> bool {
    std::fs::read_dir(dir.join("checkpoint")).is_ok_and(|d| {
        d.flatten()
            .any(|e| e.file_name().to_string_lossy().ends_with(".bin"))
    })
}
