//! Regression test for issue 12, "Data loss and hangs" items 5 and 6 (estimate part): 100 000
//! `[[spheres]]` in one TOML passed the cost guard, used 9.2 GB of memory and wrote a 5.3 GB time
//! series (the guard counted bodies × steps only, not the time-series rows, their memory or the
//! disk); 3 million sedimentation particles passed with no estimate shown. The guard now
//! estimates rows, memory and disk for every kind, refuses what exceeds the limits (exit 2,
//! naming the limit and the estimate) and prints the estimate of a long run before it starts.
//!
//! Set `SETTLE_BIN` to run these checks against another binary (e.g. the one before the fix).

use crate::common::{settle, tmp, wait_for, HANG};
use std::io::{BufRead, BufReader};
use std::process::Stdio;
use std::time::Instant;

#[test]
fn hundred_thousand_spheres_are_refused_for_their_time_series() {
    let dir = tmp();
    let base = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenarios/stokes_single.toml"
    ))
    .unwrap();
    // The scenario up to its [[spheres]], then 100 000 spheres, then the rest.
    let (head, tail) = base.split_once("[[spheres]]").unwrap();
    let (_, rest) = tail.split_once("[measure]").unwrap();
    let mut text = head.to_string();
    for i in 0..100_000 {
        text.push_str(&format!(
            "[[spheres]]\nid = \"s{i}\"\ndiameter_m = 1e-4\ndensity_kg_m3 = 2700.0\n\n"
        ));
    }
    text.push_str("[measure]");
    // Every step recorded, up to 2000 rows a sphere (the default).
    text.push_str(&rest.replace("every_s = 1e-4", ""));
    let file = dir.path().join("many.toml");
    std::fs::write(&file, text).unwrap();
    let out = dir.path().join("out");
    let mut child = settle()
        .args(["run", "-q", "--out"])
        .arg(&out)
        .arg(&file)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Refused within seconds; the old binary runs for minutes (it is killed after HANG, which
    // only catches that).
    let ended = wait_for(HANG, || child.try_wait().unwrap().is_some());
    if !ended {
        child.kill().unwrap();
    }
    let status = Some(child.wait().unwrap()).filter(|_| ended);
    let mut err = String::new();
    std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut err).unwrap();
    assert_eq!(status.and_then(|s| s.code()), Some(2), "not refused: {err}");
    assert!(err.contains("many.toml"), "{err}");
    assert!(err.contains("GB"), "names the estimate: {err}");
    assert!(err.contains("--force"), "names the way round: {err}");
    assert!(
        !out.exists() || std::fs::read_dir(&out).unwrap().count() == 0,
        "something was written"
    );
}

#[test]
fn three_million_particles_show_their_estimate_before_the_run() {
    let dir = tmp();
    let mut child = settle()
        .args(["run", "--out"])
        .arg(dir.path())
        .arg(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/scenarios/sedimentation_sample1.toml"
        ))
        .args(["--set", "sample.particles=3000000"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stderr = child.stderr.take().unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines() {
            let Ok(line) = line else { break };
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    // The estimate comes before the run, after reading the scenario: within seconds; HANG (from
    // the start, not per line) only catches a binary that never prints it.
    let mut seen = Vec::new();
    let deadline = Instant::now() + HANG;
    let found = loop {
        let left = deadline.saturating_duration_since(Instant::now());
        match rx.recv_timeout(left) {
            Ok(l) if l.contains("estimate") => break Some(l),
            Ok(l) => seen.push(l),
            Err(_) => break None,
        }
    };
    let _ = child.kill();
    let _ = child.wait();
    let line = found.unwrap_or_else(|| panic!("no estimate shown within {HANG:?}: {seen:?}"));
    assert!(line.contains("sedimentation_sample1.toml"), "{line}");
    assert!(line.contains("3.000e6 bodies"), "{line}");
    assert!(
        line.contains("GB on disk") && line.contains("wall time"),
        "{line}"
    );
}
