//! `settle sweep --slurm N`: a job array and a merge job on the local Slurm.

use super::require_slurm;
use crate::common::{assert_exit, settle, tmp};
use std::path::Path;
use std::time::Instant;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// The rows of a sweep.csv without the wall-time column, sorted.
fn rows_without_wall_time(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut rdr = csv::Reader::from_reader(text.as_bytes());
    let wall = rdr
        .headers()
        .unwrap()
        .iter()
        .position(|h| h == "wall_time_s")
        .unwrap();
    let mut rows: Vec<String> = rdr
        .records()
        .map(|r| {
            let r = r.unwrap();
            let v: Vec<&str> = r
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != wall)
                .map(|(_, v)| v)
                .collect();
            v.join(",")
        })
        .collect();
    rows.sort();
    rows
}

/// The sweep of the README's scenario, locally, into `out`.
fn local(out: &Path, grid: &[&str]) -> Vec<String> {
    let o = settle()
        .current_dir(ROOT)
        .args(["sweep", "scenarios/valentik_susp1.toml", "-q", "--out"])
        .arg(out)
        .args(grid)
        .output()
        .unwrap();
    assert_exit(&o, 0);
    rows_without_wall_time(&out.join("valentik_susp1_sweep/sweep.csv"))
}

#[test]
fn a_sixteen_task_array_and_its_merge_equal_the_local_sweep() {
    require_slurm();
    let dir = tmp();
    let out = dir.path().join("cluster");
    let t0 = Instant::now();
    let o = settle()
        .current_dir(ROOT)
        .args([
            "sweep",
            "scenarios/valentik_susp1.toml",
            "--slurm",
            "16",
            "--wait",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&o.stdout);
    assert_exit(&o, 0);
    eprintln!(
        "16-task array + merge on the local Slurm: {:.1} s",
        t0.elapsed().as_secs_f64()
    );
    assert!(
        said.contains("job array") && said.contains("merge job"),
        "{said}"
    );
    let folder = out.join("valentik_susp1_sweep");
    let array = std::fs::read_to_string(folder.join("slurm_array.sh")).unwrap();
    assert!(array.contains("#SBATCH --array=1-16\n"), "{array}");
    assert!(
        array.contains("#SBATCH --time=") && array.contains("#SBATCH --mem="),
        "{array}"
    );
    assert!(
        array.contains("--shard \"${SLURM_ARRAY_TASK_ID}/16\""),
        "{array}"
    );
    assert!(
        !array.contains("--slurm") && !array.contains("--wait"),
        "{array}"
    );
    for i in 1..=16 {
        assert!(
            folder.join(format!("sweep_part_{i}_of_16.csv")).is_file(),
            "part {i}"
        );
    }
    let merged = rows_without_wall_time(&folder.join("sweep.csv"));
    assert_eq!(merged.len(), 2430);
    assert_eq!(merged, local(&dir.path().join("local"), &[]));
}

#[test]
fn a_failed_task_is_reported_by_the_merge_and_rerun() {
    require_slurm();
    let dir = tmp();
    let out = dir.path().join("cluster");
    let grid = [
        "--dt",
        "1e-2,1e-3,1e-4",
        "--integrator",
        "explicit,exponential",
    ];
    let folder = out.join("valentik_susp1_sweep");
    // Task 3 cannot write its part: a folder stands where its file goes (a full disk, a dead
    // node: the task fails, the merge job that needs every task is cancelled).
    std::fs::create_dir_all(folder.join("sweep_part_3_of_4.csv")).unwrap();
    let o = settle()
        .current_dir(ROOT)
        .args([
            "sweep",
            "scenarios/valentik_susp1.toml",
            "--slurm",
            "4",
            "--wait",
            "--out",
        ])
        .arg(&out)
        .args(grid)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_ne!(o.status.code(), Some(0), "the merge job ran: {err}");
    assert!(
        err.contains("merge job") && err.contains("--merge"),
        "{err}"
    );
    assert!(!folder.join("sweep.csv").exists());
    let log = std::fs::read_to_string(folder.join("slurm_logs/shard_3.out")).unwrap();
    assert!(log.contains("sweep_part_3_of_4.csv"), "{log}");
    // The merge names the failed shard and the command that reruns it on Slurm.
    let o = settle()
        .current_dir(ROOT)
        .args(["sweep", "--merge"])
        .arg(&folder)
        .arg("scenarios/valentik_susp1.toml")
        .output()
        .unwrap();
    assert_exit(&o, 2);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("failed shard 3:"), "{err}");
    let sbatch = err
        .lines()
        .find_map(|l| l.trim().strip_prefix("or on Slurm: "))
        .unwrap_or_else(|| panic!("no sbatch line: {err}"));
    assert!(sbatch.starts_with("sbatch --array=3 "), "{sbatch}");
    // The cause fixed, the printed line reruns task 3 (--wait added to wait for it).
    std::fs::remove_dir(folder.join("sweep_part_3_of_4.csv")).unwrap();
    let rerun = std::process::Command::new("sh")
        .arg("-c")
        .arg(sbatch.replacen("sbatch ", "sbatch --wait ", 1))
        .output()
        .unwrap();
    assert_exit(&rerun, 0);
    let o = settle()
        .current_dir(ROOT)
        .args(["sweep", "-q", "--merge"])
        .arg(&folder)
        .arg("scenarios/valentik_susp1.toml")
        .output()
        .unwrap();
    assert_exit(&o, 0);
    assert_eq!(
        rows_without_wall_time(&folder.join("sweep.csv")),
        local(&dir.path().join("local"), &grid)
    );
}
