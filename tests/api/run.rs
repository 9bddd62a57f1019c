//! The library's `Scenario::run` against `settle run`: the same tables (cell for cell: a
//! table's CSV bytes equal the file's), the same overrides, the same errors, the same files
//! written.

use crate::common::{settle, tmp, tree};
use settle::{Error, Kind, Scenario, Status};
use std::path::{Path, PathBuf};

fn scenario(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(file)
}

/// Runs `settle run FILE --set ... --out OUT -q` and returns the run's folder.
fn cli_run(file: &Path, set: &[&str], out: &Path) -> PathBuf {
    let mut cmd = settle();
    cmd.arg("run").arg(file).arg("--out").arg(out).arg("-q");
    for s in set {
        cmd.arg("--set").arg(s);
    }
    let o = cmd.output().expect("settle runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let name = std::fs::read_dir(out)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.is_dir() && !p.file_name().unwrap().to_string_lossy().starts_with('.'))
        .expect("one run folder");
    name
}

/// Every CSV file of the command line's run is a table of the library's run with the same
/// bytes, and the library has no table the command line lacks; every chart is the same SVG.
fn assert_same_outputs(file: &str, set: &[&str], kind: Kind) {
    let mut s = Scenario::load(scenario(file)).unwrap();
    for kv in set {
        let (k, v) = kv.split_once('=').unwrap();
        s = s.set(k, v).unwrap();
    }
    assert_eq!(s.kind(), kind);
    let r = s.run().unwrap();
    assert_eq!(r.status(), Status::Complete);
    let dir = tmp();
    let run_dir = cli_run(&scenario(file), set, dir.path());
    let files: Vec<PathBuf> = tree(&run_dir)
        .into_iter()
        .filter(|p| run_dir.join(p).is_file())
        .collect();
    let csvs: Vec<String> = files
        .iter()
        .map(|p| p.to_string_lossy().replace('\\', "/"))
        .filter(|p| p.ends_with(".csv"))
        .collect();
    let mut names: Vec<String> = r.tables().iter().map(|t| t.name().to_string()).collect();
    names.sort();
    let mut want = csvs.clone();
    want.sort();
    assert_eq!(names, want, "{file}: the tables are the CSV files");
    for name in &csvs {
        let bytes = std::fs::read(run_dir.join(name)).unwrap();
        let t = r.table(name).unwrap();
        assert!(
            t.to_csv().unwrap() == bytes,
            "{file}: {name} differs between the library and the command line"
        );
    }
    for p in files
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "svg"))
    {
        let name = p.to_string_lossy().replace('\\', "/");
        assert_eq!(
            r.outputs().bytes(&name).as_deref(),
            Some(std::fs::read(run_dir.join(p)).unwrap().as_slice()),
            "{file}: chart {name}"
        );
    }
    // The kind's main chart is a file of the run and has its data (for `Result.plot`): the
    // texts of its panels are the texts of the SVG file.
    let main = r.main_chart();
    assert!(
        files.iter().any(|p| p.to_string_lossy() == main),
        "{file}: {main} is written"
    );
    let (_, fig) = r
        .outputs()
        .figures()
        .iter()
        .find(|(n, _)| n == main)
        .unwrap_or_else(|| panic!("{file}: {main} has no figure data"));
    let texts = crate::common::chart::svg_texts(&run_dir.join(main)).join(" ");
    for p in &fig.panels {
        for t in [&p.x_label, &p.y_label] {
            assert!(
                texts.contains(t.as_str()),
                "{file}: {main}: {t} not in the SVG"
            );
        }
        assert!(!p.items.is_empty(), "{file}: {main} draws nothing");
    }
}

#[test]
fn free_settling_tables_equal_the_files_of_settle_run() {
    assert_same_outputs("valentik_susp1.toml", &[], Kind::FreeSettling);
}

#[test]
fn drop_tables_equal_the_files_of_settle_run() {
    assert_same_outputs("paste_single_ball.toml", &[], Kind::Drop);
}

#[test]
fn restitution_drop_tables_equal_the_files_of_settle_run() {
    assert_same_outputs("restitution_drop.toml", &[], Kind::RestitutionDrop);
}

#[test]
fn tilt_friction_tables_equal_the_files_of_settle_run() {
    assert_same_outputs("tilt_friction.toml", &[], Kind::TiltFriction);
}

#[test]
fn funnel_pour_tables_equal_the_files_of_settle_run() {
    assert_same_outputs(
        "paste_68_balls.toml",
        // A short pour at the coarsest dt of its sweep: every table, in a second.
        &[
            "repeats.count=1",
            "time.dt_s=1e-4",
            "funnel.count_time_s=0.15",
            "time.end_s=0.2",
        ],
        Kind::FunnelPour,
    );
}

#[test]
fn sedimentation_tables_equal_the_files_of_settle_run() {
    assert_same_outputs(
        "sedimentation_sample1.toml",
        &["sample.particles=2000"],
        Kind::Sedimentation,
    );
}

/// `Scenario::set` is `--set`: the same value reaches the run (the summary's viscosity
/// column changes as asked), and a bad value is refused with the command line's message.
#[test]
fn set_is_the_command_lines_set() {
    let s = Scenario::load(scenario("stokes_single.toml")).unwrap();
    let thick = s.set("fluid.viscosity_pa_s", "0.002").unwrap();
    assert_eq!(thick.overrides(), ["fluid.viscosity_pa_s=0.002"]);
    let (a, b) = (s.run().unwrap(), thick.run().unwrap());
    let va = a.table("summary").unwrap().f64s("v_simulated_m_s").unwrap();
    let vb = b.table("summary").unwrap().f64s("v_simulated_m_s").unwrap();
    // Stokes: the terminal speed is inversely proportional to the viscosity.
    let ratio = va[0] / vb[0];
    assert!(
        (ratio - 2.0).abs() < 0.02,
        "v(1 mPa s)/v(2 mPa s) = {ratio}"
    );

    let err = s.set("fluid.viscosity_pa_s", "-1").unwrap_err();
    let o = settle()
        .arg("run")
        .arg(scenario("stokes_single.toml"))
        .args(["--set", "fluid.viscosity_pa_s=-1", "--out"])
        .arg(tmp().path())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(matches!(err, Error::BadInput(_)));
    assert!(
        stderr.contains(&err.to_string()),
        "library: {err}\ncommand line: {stderr}"
    );
}

/// A scenario from text runs as the file it was written from, and `to_toml` is a scenario
/// that runs to the same tables.
#[test]
fn text_and_to_toml_run_as_the_file() {
    let path = scenario("stokes_single.toml");
    let from_file = Scenario::load(&path).unwrap().run().unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let from_text = Scenario::from_toml(&text).unwrap().run().unwrap();
    let again = Scenario::from_toml(&Scenario::load(&path).unwrap().to_toml().unwrap())
        .unwrap()
        .run()
        .unwrap();
    for r in [&from_text, &again] {
        assert_eq!(r.table("summary"), from_file.table("summary"));
        assert_eq!(r.table("timeseries"), from_file.table("timeseries"));
    }
}

/// Bad text names the origin and the key, as the command line does for a file.
#[test]
fn bad_text_is_bad_input_naming_the_key() {
    let text = std::fs::read_to_string(scenario("stokes_single.toml")).unwrap();
    let err = Scenario::from_toml(&text.replace("[fluid]", "[fluid]\ncolour = 1"))
        .unwrap_err()
        .to_string();
    assert!(err.contains(settle::api::TEXT_ORIGIN), "{err}");
    assert!(err.contains("colour"), "{err}");
}

/// `RunResult::write` writes the files `settle run` writes (same names; the same bytes for
/// every CSV and chart), and refuses a folder settle did not make.
#[test]
fn write_writes_what_settle_run_writes() {
    let path = scenario("restitution_drop.toml");
    let r = Scenario::load(&path).unwrap().run().unwrap();
    let lib = tmp();
    let folder = r.write(lib.path()).unwrap();
    let cli = tmp();
    let cli_dir = cli_run(&path, &[], cli.path());
    assert_eq!(tree(&folder), tree(&cli_dir));
    for p in tree(&folder) {
        let ext = p.extension().map(|e| e.to_string_lossy().into_owned());
        if matches!(ext.as_deref(), Some("csv" | "svg")) {
            assert_eq!(
                std::fs::read(folder.join(&p)).unwrap(),
                std::fs::read(cli_dir.join(&p)).unwrap(),
                "{}",
                p.display()
            );
        }
    }
    let theirs = tmp();
    std::fs::create_dir(theirs.path().join(r.scenario().name())).unwrap();
    std::fs::write(
        theirs.path().join(r.scenario().name()).join("notes.txt"),
        "mine",
    )
    .unwrap();
    let err = r.write(theirs.path()).unwrap_err();
    assert!(matches!(err, Error::BadInput(_)), "{err}");
    assert_eq!(
        std::fs::read_to_string(theirs.path().join(r.scenario().name()).join("notes.txt")).unwrap(),
        "mine"
    );
}
