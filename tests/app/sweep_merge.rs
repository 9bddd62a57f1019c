//! `settle sweep --merge DIR` (issue 27): one folder per `--merge` (repeatable), so that a
//! scenario file after it is the scenario (the README's `settle sweep --merge DIR
//! scenarios/valentik_susp1.toml` used to exit 2, the scenario taken for a second folder); a
//! merge lists the missing and failed shards by index with the exact command that reruns them;
//! 10 000 part files merge in seconds.

use crate::common::{assert_exit, settle, tmp};
use std::path::Path;
use std::time::Instant;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");
/// A short grid of the README's scenario: 2 integrators × 3 steps = 6 cases.
const GRID: &[&str] = &[
    "--dt",
    "1e-2,1e-3,1e-4",
    "--integrator",
    "explicit,exponential",
];

/// Runs `settle sweep scenarios/valentik_susp1.toml GRID EXTRA… --out OUT` from the crate root.
fn sweep(out: &Path, extra: &[&str]) -> std::process::Output {
    settle()
        .current_dir(ROOT)
        .args(["sweep", "scenarios/valentik_susp1.toml", "-q", "--out"])
        .arg(out)
        .args(GRID)
        .args(extra)
        .output()
        .unwrap()
}

/// The rows of a sweep.csv without the wall-time column (the only one that differs between
/// runs), sorted.
fn rows_without_wall_time(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut rdr = csv::Reader::from_reader(text.as_bytes());
    let header = rdr.headers().unwrap().clone();
    let wall = header.iter().position(|h| h == "wall_time_s").unwrap();
    let mut rows: Vec<String> = rdr
        .records()
        .map(|r| {
            let r = r.unwrap();
            r.iter()
                .enumerate()
                .filter(|(i, _)| *i != wall)
                .map(|(_, v)| v.to_string())
                .collect::<Vec<_>>()
                .join(",")
        })
        .collect();
    rows.sort();
    rows
}

#[test]
fn the_readme_merge_line_runs_as_written_and_equals_the_local_sweep() {
    let dir = tmp();
    let out = dir.path().join("parts");
    for i in 1..=3 {
        assert_exit(&sweep(&out, &["--shard", &format!("{i}/3")]), 0);
    }
    let folder = out.join("valentik_susp1_sweep");
    // As the README writes it: the folder, then the scenario file.
    let o = settle()
        .current_dir(ROOT)
        .args(["sweep", "-q", "--merge"])
        .arg(&folder)
        .arg("scenarios/valentik_susp1.toml")
        .output()
        .unwrap();
    assert_exit(&o, 0);
    let local = dir.path().join("local");
    assert_exit(&sweep(&local, &[]), 0);
    let merged = rows_without_wall_time(&folder.join("sweep.csv"));
    assert_eq!(
        merged.len(),
        6 * 81,
        "6 cases × 81 rows (spheres × quantities)"
    );
    assert_eq!(
        merged,
        rows_without_wall_time(&local.join("valentik_susp1_sweep/sweep.csv"))
    );
    // --merge takes one folder: a second folder needs its own --merge (here the same twice is
    // refused by the merge itself as duplicate rows would be; a scenario is never a folder).
    let help = settle().args(["sweep", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&help.stdout);
    assert!(help.contains("--merge <DIR>"), "{help}");
    assert!(!help.contains("--merge <DIR>..."), "{help}");
}

#[test]
fn missing_and_failed_shards_are_listed_with_the_command_that_reruns_them() {
    let dir = tmp();
    let out = dir.path().join("parts");
    for i in [1, 2, 4] {
        assert_exit(&sweep(&out, &["--shard", &format!("{i}/4")]), 0);
    }
    let folder = out.join("valentik_susp1_sweep");
    // Shard 3 never ran; shard 2's file is cut short (a node died while it was written).
    let part2 = folder.join("sweep_part_2_of_4.csv");
    let text = std::fs::read_to_string(&part2).unwrap();
    std::fs::write(&part2, "integrator,dt_s,sta").unwrap();
    let merge = || {
        settle()
            .current_dir(ROOT)
            .args(["sweep", "--merge"])
            .arg(&folder)
            .arg("scenarios/valentik_susp1.toml")
            .output()
            .unwrap()
    };
    let o = merge();
    assert_exit(&o, 2);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("missing shards") && err.contains(": 3\n"),
        "{err}"
    );
    assert!(
        err.contains("failed shard 2:") && err.contains("sweep_part_2_of_4.csv"),
        "{err}"
    );
    assert!(
        err.contains("2 of 4 shards missing or failed (2-3)"),
        "{err}"
    );
    assert!(
        !folder.join("sweep.csv").exists(),
        "an incomplete merge wrote sweep.csv"
    );
    // The printed command reruns exactly the missing shards.
    let line = err
        .lines()
        .skip_while(|l| !l.starts_with("rerun them with:"))
        .nth(1)
        .unwrap_or_else(|| panic!("no rerun command in {err}"));
    assert!(
        line.contains("for i in 2 3;") && line.contains("--shard $i/4"),
        "{line}"
    );
    let rerun = std::process::Command::new("sh")
        .args(["-c", line.trim()])
        .output()
        .unwrap();
    assert_exit(&rerun, 0);
    assert_ne!(std::fs::read_to_string(&part2).unwrap().len(), 19);
    assert_eq!(
        std::fs::read_to_string(&part2).unwrap().lines().count(),
        text.lines().count()
    );
    assert_exit(&merge(), 0);
    assert!(folder.join("sweep.csv").is_file());
}

#[test]
fn ten_thousand_part_files_merge() {
    let dir = tmp();
    let folder = dir.path().join("big_sweep");
    std::fs::create_dir_all(&folder).unwrap();
    // One case per part: explicit and exponential at 5 000 time steps each, one body and one
    // quantity, the value converging as dt → 0.
    let header = "integrator,dt_s,status,reason,wall_time_s,steps,body,quantity,value,reference,\
                  error_vs_reference,error_vs_finest";
    let n = 10_000;
    for i in 1..=n {
        let integrator = if i % 2 == 0 {
            "explicit"
        } else {
            "exponential"
        };
        let dt = 1e-2 * 0.999_f64.powi((i / 2) as i32);
        let v = 0.05 * (1.0 + dt);
        std::fs::write(
            folder.join(format!("sweep_part_{i}_of_{n}.csv")),
            format!(
                "{header}\n{integrator},{dt:e},stable,,1e-3,{},s1,terminal_velocity_m_s,{v:e},0.05,{:e},NaN\n",
                (1.0 / dt) as u64,
                v / 0.05 - 1.0
            ),
        )
        .unwrap();
    }
    let t0 = Instant::now();
    let o = settle()
        .args(["sweep", "-q", "--merge"])
        .arg(&folder)
        .output()
        .unwrap();
    let wall = t0.elapsed().as_secs_f64();
    assert_exit(&o, 0);
    let merged = std::fs::read_to_string(folder.join("sweep.csv")).unwrap();
    assert_eq!(merged.lines().count(), n + 1);
    // The figure of docs/cluster.md (no assertion on time: the machine may be loaded).
    eprintln!("merge of {n} part files: {wall:.2} s");
}
