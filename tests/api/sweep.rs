//! The library's `settle::sweep::sweep` and `vary` against `settle sweep`: the same tables (each
//! table's CSV bytes are the file's, the wall times aside), the same charts and console lines,
//! the same files written, and the command line's errors for bad options. The parts of a split
//! sweep (`sweep_part`/`vary_part`, sent as text) merge into the whole sweep, cell for cell.

use crate::common::{settle, tmp, tree};
use settle::sweep::{
    sweep, sweep_cases, sweep_merge, sweep_part, vary, vary_cases, vary_merge, vary_part, Axis,
    SweepOptions, SweepPart, VaryOptions, VaryPart,
};
use settle::{Error, Scenario, Table};
use std::path::{Path, PathBuf};

fn scenario(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(file)
}

/// Runs `settle sweep ARGS --out OUT` and returns its stdout; fails on a non-zero exit.
fn cli_sweep(args: &[&str], out: &Path) -> String {
    let o = settle()
        .arg("sweep")
        .args(args)
        .arg("--out")
        .arg(out)
        .output()
        .expect("settle runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout).unwrap()
}

/// The stderr of `settle sweep ARGS`, which must exit 2.
fn cli_refuses(args: &[&str]) -> String {
    let dir = tmp();
    let o = settle()
        .arg("sweep")
        .args(args)
        .arg("--out")
        .arg(dir.path())
        .output()
        .expect("settle runs");
    assert_eq!(o.status.code(), Some(2), "{args:?}");
    assert!(tree(dir.path()).is_empty(), "{args:?}: nothing written");
    String::from_utf8(o.stderr).unwrap()
}

/// CSV bytes with every `wall_time_s` cell emptied (wall times measure the machine).
fn without_wall_times(name: &str, bytes: &[u8]) -> Vec<u8> {
    let t = Table::from_csv(name, bytes).unwrap();
    let k = t.header().iter().position(|h| h == "wall_time_s");
    let rows = t
        .rows()
        .iter()
        .map(|r| {
            let mut r = r.clone();
            if let Some(k) = k {
                r[k].clear();
            }
            r
        })
        .collect();
    Table::with_rows(name, t.header().to_vec(), rows)
        .to_csv()
        .unwrap()
}

/// The files of a results folder but settle's marker, relative, `/`-separated, sorted.
fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = tree(dir)
        .into_iter()
        .filter(|p| dir.join(p).is_file() && !p.starts_with(".settle-run"))
        .map(|p| p.to_string_lossy().replace('\\', "/"))
        .collect();
    v.sort();
    v
}

/// Every CSV file of `dir` is a table of `outputs` with the same bytes (wall times aside) and
/// every other file is one of its files; the charts in `same_bytes` are equal byte for byte.
fn assert_outputs_are_the_folder(outputs: &settle::Outputs, dir: &Path, same_bytes: &[&str]) {
    let on_disk = files(dir);
    let mut mine: Vec<String> = outputs
        .tables()
        .iter()
        .map(|t| t.name().to_string())
        .chain(outputs.file_names().map(str::to_string))
        .collect();
    mine.sort();
    assert_eq!(mine, on_disk, "the outputs are the folder's files");
    for name in on_disk.iter().filter(|n| n.ends_with(".csv")) {
        let file = std::fs::read(dir.join(name)).unwrap();
        let table = outputs.get(name).unwrap().to_csv().unwrap();
        assert!(
            without_wall_times(name, &table) == without_wall_times(name, &file),
            "{name} differs between the library and the command line"
        );
    }
    for name in same_bytes {
        assert_eq!(
            outputs.bytes(name).as_deref(),
            Some(std::fs::read(dir.join(name)).unwrap().as_slice()),
            "{name}"
        );
    }
}

/// A dt sweep of 2 integrators × 3 time steps: the tables, the wall-time-free chart, the
/// console lines (wall times aside) and the folder written equal those of `settle sweep`.
#[test]
fn a_dt_sweep_equals_settle_sweep() {
    let file = scenario("stokes_single.toml");
    let s = Scenario::load(&file).unwrap();
    let opts = SweepOptions {
        dts: vec![1e-3, 1e-4, 1e-5],
        integrators: vec!["explicit".into(), "exponential".into()],
        ..SweepOptions::default()
    };
    let r = sweep(&s, &opts).unwrap();
    assert_eq!(r.name(), "stokes_single_sweep");
    assert_eq!(r.rows.len(), 2 * 3 * 3, "cases × quantities");
    assert_eq!(r.table("sweep").unwrap().len(), r.rows.len());
    assert_eq!(r.table("recommended_dt.csv").unwrap().len(), 2);
    let out = tmp();
    let stdout = cli_sweep(
        &[
            file.to_str().unwrap(),
            "--dt",
            "1e-3,1e-4,1e-5",
            "--integrator",
            "explicit,exponential",
        ],
        out.path(),
    );
    let dir = out.path().join("stokes_single_sweep");
    assert_outputs_are_the_folder(&r.outputs, &dir, &["quantity_vs_dt.svg"]);
    // The console: the same lines, then where it wrote; only the wall-time column differs.
    let cli: Vec<&str> = stdout.lines().collect();
    assert_eq!(cli.len(), r.lines.len() + 1);
    assert!(cli.last().unwrap().starts_with("  -> "));
    let wall_free = |l: &str| {
        let mut w: Vec<&str> = l.split_whitespace().collect();
        if w.len() > 3 && (w[0] == "explicit" || w[0] == "exponential") {
            w[3] = "";
        }
        w.join(" ")
    };
    for (a, b) in r.lines.iter().zip(&cli) {
        assert_eq!(wall_free(a), wall_free(b));
    }
    assert!(r
        .lines
        .iter()
        .any(|l| l.contains("recommended dt (exponential")));
    // The explicit scheme's recommendation is its finest dt: unverified, a warning.
    assert_eq!(r.warnings.len(), 1, "{:?}", r.warnings);
    assert!(r.warnings[0].starts_with("explicit: the recommended dt 1e-5 s is unverified"));
    // write(): the command line's files, the tables' bytes.
    let again = tmp();
    let written = r.write(again.path()).unwrap();
    assert_eq!(written, again.path().join("stokes_single_sweep"));
    assert_eq!(files(&written), files(&dir));
    for t in r.outputs.tables() {
        assert_eq!(
            std::fs::read(written.join(t.name())).unwrap(),
            t.to_csv().unwrap()
        );
    }
}

/// A parameter sweep of the viscosity over 3 values: `vary.csv` (wall times aside), every chart
/// and every console line equal those of `settle sweep --vary`; an axis from a list of values
/// is the axis of `--vary KEY=V1,V2,V3`.
#[test]
fn a_parameter_sweep_equals_settle_sweep_vary() {
    let file = scenario("stokes_single.toml");
    let s = Scenario::load(&file).unwrap();
    let axis = Axis::list("fluid.viscosity_pa_s", &["0.005", "0.001", "0.002"]).unwrap();
    assert_eq!(
        axis,
        Axis::parse("fluid.viscosity_pa_s=0.001,0.002,0.005").unwrap()
    );
    let r = vary(&s, &[axis], &VaryOptions::default()).unwrap();
    assert_eq!(r.name(), "stokes_single_vary");
    assert_eq!(r.table("vary").unwrap().len(), 3);
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    let out = tmp();
    let stdout = cli_sweep(
        &[
            file.to_str().unwrap(),
            "--vary",
            "fluid.viscosity_pa_s=0.001,0.002,0.005",
        ],
        out.path(),
    );
    let dir = out.path().join("stokes_single_vary");
    let charts: Vec<String> = files(&dir)
        .into_iter()
        .filter(|n| n.ends_with(".svg"))
        .collect();
    assert_eq!(charts.len(), 3, "{charts:?}");
    let charts: Vec<&str> = charts.iter().map(String::as_str).collect();
    assert_outputs_are_the_folder(&r.outputs, &dir, &charts);
    let mut expected = r.lines.clone();
    expected.push(format!("  -> {}", dir.display()));
    assert_eq!(stdout.lines().collect::<Vec<_>>(), expected);
    // Stokes: v ∝ 1/μ.
    let v = r
        .table("vary")
        .unwrap()
        .f64s("terminal_velocity_m_s")
        .unwrap();
    assert!((v[0] / v[2] - 5.0).abs() < 1e-3, "{v:?}");
    let again = tmp();
    let written = r.write(again.path()).unwrap();
    assert_eq!(files(&written), files(&dir));
}

/// A bad option is a bad input naming the option and the value, with what the command line
/// says is allowed; nothing runs.
#[test]
fn bad_sweep_options_are_the_command_lines_errors() {
    let file = scenario("stokes_single.toml");
    let s = Scenario::load(&file).unwrap();
    let f = file.to_str().unwrap();
    let refused = |opts: SweepOptions| match sweep(&s, &opts) {
        Err(e @ Error::BadInput(_)) => e.to_string(),
        other => panic!("{opts:?}: {other:?}"),
    };
    // The text clap prints after the option's name: what is allowed.
    let allowed = |stderr: &str| {
        let first = stderr.lines().next().unwrap().to_string();
        first.split_once("': ").map(|(_, a)| a.to_string())
    };
    let e = refused(SweepOptions {
        integrators: vec!["exponential".into(), "rk4".into()],
        ..SweepOptions::default()
    });
    assert!(e.contains("rk4") && e.contains("--integrator"), "{e}");
    let cli = cli_refuses(&[f, "--dt", "1e-3", "--integrator", "rk4"]);
    assert!(cli.contains("[possible values: explicit, implicit, exponential]"));
    assert!(
        e.ends_with("allowed explicit, implicit, exponential"),
        "{e}"
    );
    let e = refused(SweepOptions {
        dts: vec![1e-3, -1e-3],
        ..SweepOptions::default()
    });
    assert!(e.starts_with("-0.001: key `--dt`"), "{e}");
    let cli = allowed(&cli_refuses(&[f, "--dt", "-1e-3"])).unwrap();
    assert!(e.ends_with(&cli), "{e} | {cli}");
    let e = refused(SweepOptions {
        dts: vec![1e-3],
        tol: Some(2.0),
        ..SweepOptions::default()
    });
    let cli = allowed(&cli_refuses(&[f, "--dt", "1e-3", "--tol", "2"])).unwrap();
    assert!(e.contains("--tol") && e.ends_with(&cli), "{e} | {cli}");
    let e = refused(SweepOptions {
        dt_range: Some((1e-3, 1e-5)),
        ..SweepOptions::default()
    });
    let cli = allowed(&cli_refuses(&[f, "--dt-range", "1e-3:1e-5"])).unwrap();
    assert!(e.contains("--dt-range") && e.ends_with(&cli), "{e} | {cli}");
    // No time steps at all: the scenario has no [sweep] table.
    let e = refused(SweepOptions::default());
    assert_eq!(format!("error: {e}"), cli_refuses(&[f]).trim_end());
    // A kind that cannot be swept.
    let tilt = scenario("tilt_friction.toml");
    let e = sweep(&Scenario::load(&tilt).unwrap(), &SweepOptions::default()).unwrap_err();
    let cli = cli_refuses(&[tilt.to_str().unwrap(), "--dt", "1e-3"]);
    assert_eq!(format!("error: {e}"), cli.trim_end());
}

/// An unknown key or an out-of-range value of a parameter sweep is the command line's error,
/// word for word; a bad grid names `--vary` and what is allowed.
#[test]
fn bad_vary_axes_are_the_command_lines_errors() {
    let file = scenario("stokes_single.toml");
    let s = Scenario::load(&file).unwrap();
    let f = file.to_str().unwrap();
    for (key, values) in [
        ("fluid.no_such_m", ["1", "2"]),
        ("fluid.viscosity_pa_s", ["-1", "1e-3"]),
    ] {
        let axis = Axis::list(key, &values).unwrap();
        let e = vary(&s, &[axis], &VaryOptions::default()).unwrap_err();
        assert!(matches!(e, Error::BadInput(_)), "{e}");
        assert!(e.to_string().contains(key), "{e}");
        let grid = format!("{key}={}", values.join(","));
        let cli = cli_refuses(&[f, "--vary", &grid]);
        assert_eq!(format!("error: {e}"), cli.trim_end());
    }
    let e = Axis::parse("bad key=1,2").unwrap_err().to_string();
    let cli = cli_refuses(&[f, "--vary", "bad key=1,2"]);
    let allowed = cli.lines().next().unwrap().split_once("': ").unwrap().1;
    assert!(
        e.contains("--vary") && e.ends_with(allowed),
        "{e} | {allowed}"
    );
    assert!(Axis::list("fluid.viscosity_pa_s", &["1", "nan"]).is_err());
    assert!(Axis::list("fluid.viscosity_pa_s", &[] as &[&str]).is_err());
    let e = vary(&s, &[], &VaryOptions::default()).unwrap_err();
    assert!(e.to_string().contains("--vary"), "{e}");
    let twice = [
        Axis::parse("fluid.viscosity_pa_s=1e-3,2e-3").unwrap(),
        Axis::parse("fluid.viscosity_pa_s=3e-3,4e-3").unwrap(),
    ];
    let e = vary(&s, &twice, &VaryOptions::default()).unwrap_err();
    let cli = cli_refuses(&[
        f,
        "--vary",
        "fluid.viscosity_pa_s=1e-3,2e-3",
        "--vary",
        "fluid.viscosity_pa_s=3e-3,4e-3",
    ]);
    assert_eq!(format!("error: {e}"), cli.trim_end());
}

/// Every table of `a` equals that of `b` (wall times aside), and they have the same files.
fn assert_same_outputs(a: &settle::Outputs, b: &settle::Outputs) {
    let names = |o: &settle::Outputs| -> Vec<String> {
        o.tables()
            .iter()
            .map(|t| t.name().to_string())
            .chain(o.file_names().map(str::to_string))
            .collect()
    };
    assert_eq!(names(a), names(b));
    for t in a.tables() {
        let other = b.get(t.name()).unwrap().to_csv().unwrap();
        assert!(
            without_wall_times(t.name(), &t.to_csv().unwrap())
                == without_wall_times(t.name(), &other),
            "{} differs between the merged parts and the whole sweep",
            t.name()
        );
    }
}

/// A console line without its wall-time column (the 4th word of a case's line).
fn wall_free(l: &str) -> String {
    let mut w: Vec<&str> = l.split_whitespace().collect();
    if w.len() > 3 && ["explicit", "implicit", "exponential"].contains(&w[0]) {
        w[3] = "";
    }
    w.join(" ")
}

/// The 6 cases of a dt sweep split into 4 parts (shards of 2, 2, 1 and 1 cases), each sent as
/// the text of its part file and merged in reverse order: every table (wall times aside), the
/// wall-time-free chart, the recommended dt, the warnings and the console lines equal those of
/// the whole sweep. A part's text is the part file `settle sweep --shard I/N` writes.
#[test]
fn the_parts_of_a_dt_sweep_merge_into_the_whole_sweep() {
    let file = scenario("stokes_single.toml");
    let s = Scenario::load(&file).unwrap();
    let opts = SweepOptions {
        dts: vec![1e-3, 1e-4, 1e-5],
        integrators: vec!["explicit".into(), "exponential".into()],
        ..SweepOptions::default()
    };
    assert_eq!(sweep_cases(&s, &opts).unwrap().len(), 6);
    let whole = sweep(&s, &opts).unwrap();
    let texts: Vec<String> = (1..=4)
        .map(|i| sweep_part(&s, &opts, i, 4).unwrap().to_csv().unwrap())
        .collect();
    let parts: Vec<SweepPart> = (1..=4)
        .rev()
        .map(|i| SweepPart::from_csv(i, 4, &texts[i - 1]).unwrap())
        .collect();
    assert_eq!(
        parts[3].rows.len(),
        2 * 3,
        "shard 1/4: 2 cases × 3 quantities"
    );
    let merged = sweep_merge(&s, &opts, parts).unwrap();
    assert_eq!(merged.name(), whole.name());
    assert_eq!(merged.plan, whole.plan);
    assert_eq!(merged.recommended, whole.recommended);
    assert_eq!(merged.warnings, whole.warnings);
    assert_same_outputs(&merged.outputs, &whole.outputs);
    assert_eq!(
        merged.outputs.bytes("quantity_vs_dt.svg"),
        whole.outputs.bytes("quantity_vs_dt.svg")
    );
    let lines = |r: &settle::sweep::SweepResult| -> Vec<String> {
        r.lines.iter().map(|l| wall_free(l)).collect()
    };
    assert_eq!(lines(&merged), lines(&whole));
    // The text of part 2/4 is the part file of `settle sweep --shard 2/4` (wall times aside).
    let out = tmp();
    cli_sweep(
        &[
            file.to_str().unwrap(),
            "--dt",
            "1e-3,1e-4,1e-5",
            "--integrator",
            "explicit,exponential",
            "--shard",
            "2/4",
            "-q",
        ],
        out.path(),
    );
    let part_file = out.path().join("stokes_single_sweep/sweep_part_2_of_4.csv");
    let name = "sweep_part_2_of_4.csv";
    assert!(
        without_wall_times(name, texts[1].as_bytes())
            == without_wall_times(name, &std::fs::read(part_file).unwrap()),
        "{}",
        texts[1]
    );
}

/// Parts that are not one whole split are refused, each saying what is wrong, and nothing is
/// merged: a shard missing or given twice, parts of two splits, an index out of 1..=N, no
/// parts, a part of another grid, a text that is not a part file.
#[test]
fn incomplete_or_foreign_parts_are_refused() {
    let s = Scenario::load(scenario("stokes_single.toml")).unwrap();
    let opts = SweepOptions {
        dts: vec![1e-3, 1e-4],
        integrators: vec!["exponential".into()],
        ..SweepOptions::default()
    };
    let part = |i, n| sweep_part(&s, &opts, i, n).unwrap();
    let refused = |parts: Vec<SweepPart>| match sweep_merge(&s, &opts, parts) {
        Err(e @ Error::BadInput(_)) => e.to_string(),
        other => panic!("{other:?}"),
    };
    let e = refused(vec![part(1, 3), part(3, 3)]);
    assert!(e.contains("1 of 3 shards missing (2)"), "{e}");
    assert!(e.contains("nothing merged"), "{e}");
    let e = refused(vec![part(1, 2), part(2, 2), part(2, 2)]);
    assert!(e.contains("shards 2 given more than once"), "{e}");
    let e = refused(vec![part(1, 2), part(2, 3)]);
    assert!(e.contains("a split into 2 and of a split into 3"), "{e}");
    let e = refused(vec![]);
    assert!(e.contains("no parts"), "{e}");
    let e = refused(vec![SweepPart {
        index: 0,
        ..part(1, 1)
    }]);
    assert!(e.contains("0/1") && e.contains("--shard"), "{e}");
    let e = sweep_part(&s, &opts, 3, 2).unwrap_err().to_string();
    assert!(e.contains("3/2") && e.contains("1 ≤ I ≤ N"), "{e}");
    let other = SweepOptions {
        dts: vec![1e-3, 2e-4],
        ..opts.clone()
    };
    let foreign = sweep_part(&s, &other, 2, 2).unwrap();
    let e = refused(vec![part(1, 2), foreign]);
    assert!(
        e.contains("outside the grid") && e.contains("dt 0.0002 s"),
        "{e}"
    );
    let e = SweepPart::from_csv(1, 2, "a,b\n1,2\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("not a sweep part table") && e.contains("1/2"),
        "{e}"
    );
    // The whole split merges.
    assert!(sweep_merge(&s, &opts, vec![part(2, 2), part(1, 2)]).is_ok());
}

/// A parameter sweep of 2 viscosities × 2 drag laws (a numeric and a categorical axis) split
/// into 3 parts sent as text: the merge equals the whole sweep, table (wall times aside),
/// charts byte for byte and console lines; vary_cases lists its 4 points, and a part of other
/// axes is refused.
#[test]
fn the_parts_of_a_parameter_sweep_merge_into_the_whole_sweep() {
    let s = Scenario::load(scenario("stokes_single.toml")).unwrap();
    let axes = [
        Axis::parse("fluid.viscosity_pa_s=0.001,0.004").unwrap(),
        Axis::parse("drag.law=stokes,dallavalle").unwrap(),
    ];
    let opts = VaryOptions::default();
    let points = vary_cases(&s, &axes).unwrap();
    assert_eq!(points.len(), 4);
    assert_eq!(points[1][1].to_string(), "stokes");
    let whole = vary(&s, &axes, &opts).unwrap();
    let parts: Vec<VaryPart> = [3, 1, 2]
        .into_iter()
        .map(|i| {
            let text = vary_part(&s, &axes, &opts, i, 3).unwrap().to_csv().unwrap();
            VaryPart::from_csv(i, 3, &text).unwrap()
        })
        .collect();
    let merged = vary_merge(&s, &axes, &opts, parts.clone()).unwrap();
    assert_eq!(merged.name(), whole.name());
    assert_same_outputs(&merged.outputs, &whole.outputs);
    for name in whole.outputs.file_names() {
        if name.ends_with(".svg") {
            assert_eq!(
                merged.outputs.bytes(name),
                whole.outputs.bytes(name),
                "{name}"
            );
        }
    }
    assert_eq!(merged.lines, whole.lines);
    assert_eq!(merged.warnings, whole.warnings);
    let other = [Axis::parse("fluid.viscosity_pa_s=0.001,0.002").unwrap()];
    let foreign = vary_part(&s, &other, &opts, 1, 3).unwrap();
    let mut mixed = parts.clone();
    mixed[1] = foreign;
    let e = vary_merge(&s, &axes, &opts, mixed).unwrap_err().to_string();
    assert!(e.contains("varies fluid.viscosity_pa_s where"), "{e}");
    let e = vary_merge(&s, &axes, &opts, parts[..2].to_vec())
        .unwrap_err()
        .to_string();
    assert!(e.contains("1 of 3 shards missing (2)"), "{e}");
}
