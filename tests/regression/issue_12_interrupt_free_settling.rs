//! Issue 12, "Data loss and hangs" item 5 (interruption part): a free-settling scenario with
//! 100 000 `[[spheres]]` ignored the first SIGTERM for 9 minutes: the sphere loops (free engine
//! and Rapier path) never looked at the interruption flag, so the run went on to the end and
//! wrote everything. Now every sphere checks it every few hundred microseconds of work, and an
//! interrupted free-settling run writes nothing (a partial set of spheres is no result) and exits
//! with 130, leaving neither a result folder nor a staging folder.

use crate::common::{cpu_time, isolated, settle, tmp};
#[cfg(unix)]
use crate::common::{signalled, HANG};
use std::path::Path;
use std::time::{Duration, Instant};

/// A scenario of `n` Stokes spheres in water, each taking 10⁶ steps (dt = 1 µs, 1 s): hours of
/// work in all, seconds for a few spheres, little memory.
fn many_spheres_toml(engine: &str, n: usize) -> String {
    let mut s = format!(
        r#"name = "many"
kind = "free_settling"
dimension = 3
engine = "{engine}"

[fluid]
density_kg_m3 = 1000.0
rheology = "newtonian"
viscosity_pa_s = 0.001

[drag]
law = "stokes"

[time]
dt_s = 1e-6
end_s = 1.0
integrator = "exponential"

[release]
depth_m = 0.01
velocity_m_s = 0.0
"#
    );
    for i in 0..n {
        s.push_str(&format!(
            "\n[[spheres]]\nid = \"s{i}\"\ndiameter_m = 1e-4\ndensity_kg_m3 = {}\n",
            2000.0 + i as f64 * 0.01
        ));
    }
    s
}

/// Runs the scenario, sends SIGTERM once it has used 1.5 s of CPU (however loaded the machine)
/// and checks the exit: within 5 s (the aim is about a second; 5 s, by the wall clock or by CPU
/// time on a loaded machine, spares a busy runner and still catches the old binary, which ran
/// on for minutes), code 130, no folder `many` and no `.many.partial-*` left.
#[cfg(unix)]
fn sigterm_stops(engine: &str) {
    let dir = tmp();
    let file = dir.path().join("many.toml");
    std::fs::write(&file, many_spheres_toml(engine, 20_000)).unwrap();
    let out = dir.path().join("out");
    let mut cmd = settle();
    cmd.args(["run", "--force", "--quiet", "--out"])
        .arg(&out)
        .arg(&file);
    let o = signalled(cmd, "TERM", Duration::from_millis(1500), HANG);
    o.assert_stopped_within(Duration::from_secs(5), engine);
    assert_eq!(o.code, Some(130), "{engine}: {}", o.stderr);
    assert_no_result(&out, engine);
}

fn assert_no_result(out: &Path, engine: &str) {
    let Ok(entries) = std::fs::read_dir(out) else {
        return;
    };
    for e in entries {
        let name = e.unwrap().file_name().to_string_lossy().to_string();
        assert!(
            name != "many" && !name.contains("partial"),
            "{engine}: an interrupted run left {name}"
        );
    }
}

#[cfg(unix)]
#[test]
fn sigterm_stops_many_spheres_on_the_free_engine() {
    sigterm_stops("free");
}

#[cfg(unix)]
#[test]
fn sigterm_stops_many_spheres_on_rapier() {
    sigterm_stops("rapier");
}

/// In the library: with an interruption requested, a run returns at once as interrupted
/// ([`settle::Error::InterruptedUnwritten`]: a free-settling run keeps no partial result)
/// instead of simulating.
///
/// The interrupt flag is process-wide, and all tests share one process: the body runs in a process
/// of its own ([`isolated`]), so that the other tests are not interrupted.
#[test]
fn an_interrupted_runner_returns_interrupted() {
    if !isolated(
        "regression::issue_12_interrupt_free_settling::an_interrupted_runner_returns_interrupted",
    ) {
        return;
    }
    let dir = tmp();
    let file = dir.path().join("many.toml");
    std::fs::write(&file, many_spheres_toml("free", 100)).unwrap();
    let scenario = settle::load(&file).unwrap();
    settle::interrupt::request();
    // The CPU time of this process (it runs alone: [`isolated`]), which a loaded machine does
    // not stretch; wall time where there is no /proc.
    let me = std::process::id();
    let (t0, cpu0) = (Instant::now(), cpu_time(me));
    let r = scenario.run();
    match &r {
        Ok(done) => assert_eq!(done.status(), settle::Status::Interrupted),
        Err(e) => assert!(
            matches!(
                e,
                settle::Error::InterruptedUnwritten(_) | settle::Error::Interrupted(_)
            ),
            "{e}"
        ),
    }
    // At once: 100 spheres of 10⁶ steps (about a second of CPU each) would take minutes.
    let used = cpu_time(me)
        .zip(cpu0)
        .map_or(t0.elapsed(), |(b, a)| b.saturating_sub(a));
    assert!(used < Duration::from_secs(1), "returned after {used:?}");
}
