//! Parameter sweeps on any key (issue 13 item 6): `settle sweep S.toml --vary KEY=GRID` runs
//! one case per point of the grid and writes `OUT/<name>_vary/vary.csv` (the keys, then the
//! results with units) and a chart of each result against the first key; every case is
//! validated before any runs; shards merge to the unsharded table; a signal stops it with
//! nothing written. Words and booleans make a categorical axis (issue 16: `settle sweep`
//! compares quasi-steady and transient forces, `--vary transient.history=off,basset`).

use crate::common::chart::assert_readable_chart;
use crate::common::{assert_exit, col, read_csv, settle, tmp};
use std::path::Path;

const STOKES: &str = "scenarios/stokes_single.toml";
const TEN_CATE: &str = "scenarios/ten_cate_e1.toml";
/// Half a second of ten Cate E1: the sphere still accelerating (u∞ = 0.038 m/s), where the
/// history force matters most; 5000 steps a case.
const HALF_SECOND: &str = "time.end_s=0.5";

/// Runs `settle sweep ARGS --quiet --out OUT` and returns its output.
fn sweep(args: &[&str], out: &Path) -> std::process::Output {
    settle()
        .arg("sweep")
        .args(args)
        .arg("--quiet")
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

/// Under Stokes drag v_t = (ρ_p − ρ_f) g d² / (18 μ) (f-EDEM eq. 21): v_t ∝ 1/μ. Three
/// viscosities on a log grid give velocities in the inverse ratios, to 1e-6, and equal to the
/// force-balance reference column.
#[test]
fn terminal_velocity_varies_as_one_over_viscosity() {
    let dir = tmp();
    let o = sweep(
        &[STOKES, "--vary", "fluid.viscosity_pa_s=log:1e-3:4e-3:3"],
        dir.path(),
    );
    assert_exit(&o, 0);
    let out = dir.path().join("stokes_single_vary");
    let (h, rows) = read_csv(&out.join("vary.csv"));
    assert_eq!(h[0], "fluid.viscosity_pa_s");
    assert_eq!(h[1], "body");
    assert_eq!(h[2], "terminal_velocity_m_s");
    assert_eq!(h[3], "reference_terminal_velocity_m_s");
    assert_eq!(rows.len(), 3);
    let mu: Vec<f64> = rows
        .iter()
        .map(|r| col(&h, r, "fluid.viscosity_pa_s"))
        .collect();
    assert_eq!(mu, [1e-3, 2e-3, 4e-3]);
    let v: Vec<f64> = rows
        .iter()
        .map(|r| col(&h, r, "terminal_velocity_m_s"))
        .collect();
    for (i, r) in rows.iter().enumerate() {
        let ratio = v[i] / v[0];
        assert!(
            (ratio - mu[0] / mu[i]).abs() < 1e-6,
            "v ratio {ratio} at μ = {}",
            mu[i]
        );
        let reference = col(&h, r, "reference_terminal_velocity_m_s");
        assert!(
            (v[i] / reference - 1.0).abs() < 1e-6,
            "{} vs {reference}",
            v[i]
        );
    }
    assert_readable_chart(
        &out.join("terminal_velocity_m_s_vs_fluid.viscosity_pa_s.svg"),
        "terminal_velocity_m_s against fluid.viscosity_pa_s",
        &["fluid.viscosity_pa_s [Pa·s]", "terminal_velocity_m_s [m/s]"],
    );
}

/// Two keys make the full grid (2 × 3 cases, the first key outermost); at each density the
/// doubled diameter quadruples the Stokes velocity.
#[test]
fn two_keys_run_their_full_grid() {
    let dir = tmp();
    let o = sweep(
        &[
            STOKES,
            // 33 response times of the larger sphere (τ = ρ_p d²/18μ = 6 ms): at terminal speed.
            "--set",
            "time.end_s=0.2",
            "--vary",
            "spheres[0].diameter_m=1e-4,2e-4",
            "--vary",
            "fluid.density_kg_m3=1000:1200:3",
        ],
        dir.path(),
    );
    assert_exit(&o, 0);
    let out = dir.path().join("stokes_single_vary");
    let (h, rows) = read_csv(&out.join("vary.csv"));
    assert_eq!(
        h[..3],
        ["spheres[0].diameter_m", "fluid.density_kg_m3", "body"]
    );
    assert_eq!(rows.len(), 6);
    let at = |d: f64, rho: f64| {
        let r = rows
            .iter()
            .find(|r| {
                col(&h, r, "spheres[0].diameter_m") == d && col(&h, r, "fluid.density_kg_m3") == rho
            })
            .unwrap_or_else(|| panic!("no case d = {d}, ρ = {rho}"));
        col(&h, r, "terminal_velocity_m_s")
    };
    for rho in [1000.0, 1100.0, 1200.0] {
        let ratio = at(2e-4, rho) / at(1e-4, rho);
        assert!((ratio - 4.0).abs() < 1e-6, "ρ = {rho}: {ratio}");
    }
    // One series per value of the second key.
    let texts = assert_readable_chart(
        &out.join("terminal_velocity_m_s_vs_spheres_0_.diameter_m.svg"),
        "terminal_velocity_m_s against spheres[0].diameter_m",
        &["spheres[0].diameter_m [m]", "terminal_velocity_m_s [m/s]"],
    );
    for rho in ["1000", "1100", "1200"] {
        let label = format!("fedem-table1, fluid.density_kg_m3 = {rho}");
        assert!(
            texts.iter().any(|t| t.contains(&label)),
            "{label} in {texts:?}"
        );
    }
}

/// A misspelt key, an out-of-range value anywhere in the grid and a kind without results are
/// refused with exit 2 before any case runs, naming the key and what is allowed; nothing is
/// written.
#[test]
fn a_bad_key_or_value_is_refused_before_anything_runs() {
    let dir = tmp();
    let cases: [(&[&str], &[&str]); 4] = [
        (
            &[STOKES, "--vary", "fluid.viscosty_pa_s=1e-3,2e-3"],
            &["fluid.viscosty_pa_s", "unknown field"],
        ),
        (
            &[STOKES, "--vary", "fluid.viscosity_pa_s=-1e-3:1e-3:3"],
            &["fluid.viscosity_pa_s", "out of range", "allowed 0 <"],
        ),
        (
            &[STOKES, "--vary", "fluid.viscosity_pa_s=1e-3:2e-3"],
            &["--vary", "KEY=LO:HI:N"],
        ),
        (
            &[
                "scenarios/sedimentation_sample1.toml",
                "--vary",
                "fluid.viscosity_pa_s=1e-3,2e-3",
            ],
            &["kind", "cannot be swept"],
        ),
    ];
    for (args, words) in cases {
        refused(
            &sweep(args, dir.path()),
            &format!("{args:?}"),
            words,
            dir.path(),
        );
    }
}

/// `--shard I/N` runs a slice of the grid into `vary_part_I_of_N.csv`; `--merge` joins the
/// parts into the same table as the unsharded sweep (wall times aside) and its charts.
#[test]
fn merged_shards_equal_the_unsharded_parameter_sweep() {
    let dir = tmp();
    let vary = ["--vary", "fluid.viscosity_pa_s=1e-3:3e-3:5"];
    let whole = dir.path().join("whole");
    assert_exit(&sweep(&[&[STOKES][..], &vary].concat(), &whole), 0);
    let parts = dir.path().join("parts");
    for s in ["1/3", "2/3", "3/3"] {
        assert_exit(
            &sweep(&[&[STOKES, "--shard", s][..], &vary].concat(), &parts),
            0,
        );
    }
    let folder = parts.join("stokes_single_vary");
    assert!(folder.join("vary_part_2_of_3.csv").is_file());
    merge(&folder);
    let strip = |p: &Path| {
        let (h, rows) = read_csv(p);
        let w = h.iter().position(|c| c == "wall_time_s").unwrap();
        let rows: Vec<Vec<String>> = rows
            .into_iter()
            .map(|mut r| {
                r[w].clear();
                r
            })
            .collect();
        (h, rows)
    };
    let a = strip(&whole.join("stokes_single_vary/vary.csv"));
    let b = strip(&folder.join("vary.csv"));
    assert_eq!(a.1.len(), 5);
    assert_eq!(a, b);
    assert!(folder
        .join("terminal_velocity_m_s_vs_fluid.viscosity_pa_s.svg")
        .is_file());
}

/// SIGTERM during a long parameter sweep: exit 130 within seconds, nothing written (as the dt
/// sweep).
#[cfg(unix)]
#[test]
fn sigterm_stops_a_parameter_sweep_and_writes_nothing() {
    use crate::common::{signalled, HANG};
    use std::time::Duration;
    let dir = tmp();
    let out = dir.path().join("out");
    // 27 spheres at dt = 1e-7 s over up to 120 s, twice: far more than the test's patience.
    let mut cmd = settle();
    cmd.args([
        "sweep",
        "scenarios/valentik_susp1.toml",
        "--set",
        "time.dt_s=1e-7",
        "--vary",
        "fluid.yield_stress_pa=20,30",
        "--quiet",
        "--out",
    ])
    .arg(&out);
    // Signalled once the sweep has used 1.5 s of CPU, however loaded the machine. The aim is
    // about a second from the signal to the exit; 5 s (wall, or CPU on a loaded machine) keeps
    // the test from failing on a busy runner while still catching a sweep that runs on.
    let o = signalled(cmd, "TERM", Duration::from_millis(1500), HANG);
    o.assert_stopped_within(Duration::from_secs(5), "SIGTERM during a parameter sweep");
    assert_eq!(o.code, Some(130), "stderr: {}", o.stderr);
    assert!(o.stderr.contains("interrupted"), "stderr: {}", o.stderr);
    let left: Vec<_> = std::fs::read_dir(&out)
        .map(|d| d.flatten().map(|e| e.file_name()).collect())
        .unwrap_or_default();
    assert!(left.is_empty(), "an interrupted sweep wrote {left:?}");
}

/// `--vary transient.history=off,basset` on ten Cate E1 (0.5 s): a categorical axis whose
/// `vary.csv` cells hold the words, one row per value in canonical (byte) order. The history-off
/// case is the plain `settle run` with history off, to the last digit; the Basset history force
/// resists the acceleration, so at 0.5 s the sphere is at least 10 % slower (0.0299 against
/// 0.0381 m/s). The chart has one x position per value, labelled with it; the console prints one
/// line per value; the report page lists the table.
#[test]
fn a_categorical_axis_compares_history_off_and_basset_on_ten_cate() {
    let dir = tmp();
    let o = settle()
        .args(["sweep", TEN_CATE, "--set", HALF_SECOND])
        .args(["--vary", "transient.history=off,basset", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert_exit(&o, 0);
    let stdout = String::from_utf8_lossy(&o.stdout);
    for line in [
        "2 cases varying transient.history",
        "transient.history = basset: terminal_velocity_m_s 0.0",
        "transient.history = off: terminal_velocity_m_s 0.0",
    ] {
        assert!(stdout.contains(line), "`{line}` not in {stdout}");
    }
    let out = dir.path().join("ten_cate_e1_vary");
    let (h, rows) = read_csv(&out.join("vary.csv"));
    assert_eq!(
        h[..3],
        ["transient.history", "body", "terminal_velocity_m_s"]
    );
    let cells: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(cells, ["basset", "off"]);
    let v = |r: &[String]| col(&h, r, "terminal_velocity_m_s");
    let (basset, off) = (v(&rows[0]), v(&rows[1]));

    let run = dir.path().join("run");
    let o = settle()
        .args(["run", "-q", TEN_CATE, "--set", HALF_SECOND])
        .args(["--set", "transient.history=off", "--out"])
        .arg(&run)
        .output()
        .unwrap();
    assert_exit(&o, 0);
    let (sh, srows) = read_csv(&run.join("ten_cate_e1/summary.csv"));
    let plain = col(&sh, &srows[0], "v_simulated_m_s");
    assert_eq!(off, plain, "history off in the sweep against a plain run");
    assert!(
        (0.030..0.045).contains(&off),
        "v(0.5 s), history off: {off} m/s"
    );
    assert!(
        basset < 0.9 * off,
        "v(0.5 s): Basset {basset} m/s is not 10 % below history off {off} m/s"
    );

    let texts = assert_readable_chart(
        &out.join("terminal_velocity_m_s_vs_transient.history.svg"),
        "terminal_velocity_m_s against transient.history",
        &["transient.history [-]", "terminal_velocity_m_s [m/s]"],
    );
    for tick in ["basset", "off"] {
        assert!(
            texts.iter().any(|t| t == tick),
            "tick `{tick}` in {texts:?}"
        );
    }
    let report = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(report.contains("vary.csv") && report.contains("basset"));
}

/// A word the key does not take (`history=foo`, `added_mass=maybe`) is refused as `--set`
/// refuses it (the key, the value and the allowed values), exit 2, before any case runs and
/// with nothing written.
#[test]
fn a_categorical_value_the_key_does_not_take_is_refused() {
    let dir = tmp();
    let cases: [(&str, &[&str]); 2] = [
        (
            "transient.history=off,foo",
            &[
                "ten_cate_e1.toml",
                "transient.history",
                "foo",
                "`off`, `basset`, `mei-adrian`",
            ],
        ),
        (
            "transient.added_mass=false,maybe",
            &["transient.added_mass", "maybe", "true or false"],
        ),
    ];
    for (vary, words) in cases {
        let o = sweep(&[TEN_CATE, "--vary", vary], dir.path());
        refused(&o, vary, words, dir.path());
    }
}

/// A categorical axis with a numeric one (2 × 2 cases) runs its full grid, and its shards merge
/// into the same table as the unsharded sweep (the words survive the part files).
#[test]
fn a_categorical_grid_with_a_numeric_key_shards_and_merges() {
    let dir = tmp();
    let args = [
        TEN_CATE,
        "--set",
        "time.end_s=0.2",
        "--vary",
        "transient.added_mass=true,false",
        "--vary",
        "fluid.viscosity_pa_s=0.2,0.373",
    ];
    let whole = dir.path().join("whole");
    assert_exit(&sweep(&args, &whole), 0);
    let parts = dir.path().join("parts");
    for s in ["1/3", "2/3", "3/3"] {
        assert_exit(&sweep(&[&args[..], &["--shard", s]].concat(), &parts), 0);
    }
    let folder = parts.join("ten_cate_e1_vary");
    merge(&folder);
    let strip = |p: &Path| {
        let (h, mut rows) = read_csv(p);
        let w = h.iter().position(|c| c == "wall_time_s").unwrap();
        rows.iter_mut().for_each(|r| r[w].clear());
        (h, rows)
    };
    let a = strip(&whole.join("ten_cate_e1_vary/vary.csv"));
    let b = strip(&folder.join("vary.csv"));
    let keys: Vec<(&str, &str)> = a.1.iter().map(|r| (r[0].as_str(), r[1].as_str())).collect();
    assert_eq!(
        keys,
        [
            ("false", "0.2"),
            ("false", "0.373"),
            ("true", "0.2"),
            ("true", "0.373")
        ]
    );
    assert_eq!(a, b);
    assert_readable_chart(
        &folder.join("terminal_velocity_m_s_vs_transient.added_mass.svg"),
        "terminal_velocity_m_s against transient.added_mass",
        &["transient.added_mass [-]"],
    );
}

/// `o` exited 2 without a panic, its stderr names every word of `words`, and `out` holds
/// nothing (`what` labels the failure).
fn refused(o: &std::process::Output, what: &str, words: &[&str], out: &std::path::Path) {
    assert_exit(o, 2);
    let err = String::from_utf8_lossy(&o.stderr);
    for w in words {
        assert!(err.contains(w), "{what}: `{w}` not in {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        !out.exists() || std::fs::read_dir(out).unwrap().next().is_none(),
        "{what} wrote something"
    );
}

/// `settle sweep --merge FOLDER` succeeds.
fn merge(folder: &Path) {
    let o = settle()
        .args(["sweep", "--quiet", "--merge"])
        .arg(folder)
        .output()
        .unwrap();
    assert_exit(&o, 0);
}
