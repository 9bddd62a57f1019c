//! The library's `settle::fit` against `settle fit`: the same tables (a table's CSV bytes equal
//! the file's), the same chart and record, the same files written, the same refusals.

use crate::common::{settle, tmp, tree};
use settle::fit::{fit, slump, Bound, FitOptions, FitResult, Measured};
use settle::{Error, Scenario, Table};
use std::path::{Path, PathBuf};

fn scenario(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(file)
}

/// docs/commands/fit.md's first worked case: η_B of paste from the settling distance of the
/// 12.6 mm ball dropped from 255 mm (one fall height keeps each run to one ball).
const PASTE_M: &str = "file,column,row,value,sigma\n\
                       summary.csv,settling_distance_m,id=d12.6mm-H255mm,0.05063,5e-4\n";
const ONE_HEIGHT: &str = "release.fall_heights_m=[0.255]";
const ETA: &str = "fluid.plastic_viscosity_pa_s=0.1:3";

/// The second: a constant restitution fitted to f-EDEM Table A2's rebound heights (at dt =
/// 1e-4 s, as scripts/regress_outputs.py runs it, to stay short).
const REBOUND_M: &str = "file,column,row,value\n\
    summary.csv,rebound_height_m,drop_height_m=0.095,0.0370\n\
    summary.csv,rebound_height_m,drop_height_m=0.188,0.0720\n\
    summary.csv,rebound_height_m,drop_height_m=0.252,0.0909\n\
    summary.csv,rebound_height_m,drop_height_m=0.318,0.1180\n\
    summary.csv,rebound_height_m,drop_height_m=0.398,0.1469\n";
const REBOUND_SET: [&str; 2] = ["time.dt_s=1e-4", "contacts.restitution_exponent=0"];
const E: &str = "contacts.restitution=0.4:0.8";

/// `file` loaded with `set` (`KEY=VALUE`) applied as `--set` applies them.
fn load(file: &Path, set: &[&str]) -> Scenario {
    let mut s = Scenario::load(file).unwrap();
    for kv in set {
        let (k, v) = kv.split_once('=').unwrap();
        s = s.set(k, v).unwrap();
    }
    s
}

/// `settle fit FILE --set … --fit … --measured M --out OUT -q`.
fn cli_fit(file: &Path, set: &[&str], fits: &[&str], m: &Path, out: &Path) -> std::process::Output {
    let mut cmd = settle();
    cmd.arg("fit")
        .arg(file)
        .arg("--measured")
        .arg(m)
        .arg("--out")
        .arg(out)
        .arg("-q");
    for s in set {
        cmd.args(["--set", s]);
    }
    for f in fits {
        cmd.args(["--fit", f]);
    }
    cmd.output().expect("settle runs")
}

/// Every file the command line wrote into `dir` is in `r` with the same bytes (tables as
/// tables, the others as files; `fit.toml` too when `same_record`), and `r` has no other.
fn assert_same_files(r: &FitResult, dir: &Path, same_record: bool) {
    let files: Vec<String> = tree(dir)
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .filter(|p| !p.starts_with('.'))
        .collect();
    let mut lib: Vec<String> = r
        .outputs
        .tables()
        .iter()
        .map(|t| t.name().to_string())
        .collect();
    lib.extend(r.outputs.file_names().map(str::to_string));
    lib.sort();
    assert_eq!(
        lib, files,
        "the library's outputs are the command line's files"
    );
    for name in &files {
        let bytes = std::fs::read(dir.join(name)).unwrap();
        if name.ends_with(".csv") {
            let t = r.table(name).unwrap();
            assert!(
                t.to_csv().unwrap() == bytes,
                "{name} differs from the command line's"
            );
        } else if name != "fit.toml" || same_record {
            assert!(r.outputs.bytes(name).unwrap() == bytes, "{name} differs");
        }
    }
}

/// The η_B case from M.csv: every table's CSV bytes, the chart and `fit.toml` equal the files
/// of `settle fit`; the typed figures are the tables' numbers; `write` writes the same folder.
#[test]
fn paste_eta_b_tables_equal_the_files_of_settle_fit() {
    let dir = tmp();
    let m = dir.path().join("m.csv");
    std::fs::write(&m, PASTE_M).unwrap();
    let file = scenario("paste_single_ball.toml");
    let cli = dir.path().join("cli");
    let o = cli_fit(&file, &[ONE_HEIGHT], &[ETA], &m, &cli);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let cli_dir = cli.join("paste_single_ball_fit");

    let s = load(&file, &[ONE_HEIGHT]);
    let r = fit(
        &s,
        &[Bound::parse(ETA).unwrap()],
        m.as_path(),
        &FitOptions::default(),
    )
    .unwrap();
    assert_eq!(r.name, "paste_single_ball_fit");
    assert_same_files(&r, &cli_dir, true);
    let fitted = r.table("fitted").unwrap();
    assert_eq!(fitted.f64s("value").unwrap(), r.fit.values);
    assert_eq!(
        r.fit.value("fluid.plastic_viscosity_pa_s"),
        Some(r.fit.values[0])
    );
    assert!(
        (r.fit.values[0] / 0.7 - 1.0).abs() < 0.01,
        "η_B = {}",
        r.fit.values[0]
    );
    assert_eq!(
        fitted.f64s("uncertainty_1sigma").unwrap()[0],
        r.fit.sigma[0].unwrap()
    );
    assert_eq!(r.fit.method, "brent");
    assert!(r.fit.runs > 13, "{} runs", r.fit.runs);
    assert!(r.lines[0].starts_with("fit (brent, "), "{:?}", r.lines);
    assert!(r
        .outputs
        .bytes("objective_vs_plastic_viscosity_pa_s.svg")
        .is_some());

    let lib = dir.path().join("lib");
    let folder = r.write(&lib).unwrap();
    assert_eq!(folder, lib.join("paste_single_ball_fit"));
    assert_eq!(tree(&folder), tree(&cli_dir));
    for p in tree(&folder).iter().filter(|p| !p.starts_with(".")) {
        assert_eq!(
            std::fs::read(folder.join(p)).unwrap(),
            std::fs::read(cli_dir.join(p)).unwrap(),
            "{}",
            p.display()
        );
    }
    // A folder settle did not make (and not empty) is refused, naming --out.
    let theirs = dir.path().join("theirs");
    std::fs::create_dir_all(theirs.join("paste_single_ball_fit")).unwrap();
    std::fs::write(theirs.join("paste_single_ball_fit/notes.txt"), "mine").unwrap();
    let e = r.write(&theirs).unwrap_err().to_string();
    assert!(
        e.contains("key `--out`") && e.contains("not created by settle"),
        "{e}"
    );
}

/// The restitution case with its measurements as an in-memory table: the tables equal the
/// command line's files (the record names the table instead of the file).
#[test]
fn measurements_as_a_table_give_the_files_of_settle_fit() {
    let dir = tmp();
    let m = dir.path().join("rebound.csv");
    std::fs::write(&m, REBOUND_M).unwrap();
    let file = scenario("restitution_drop.toml");
    let cli = dir.path().join("cli");
    let o = cli_fit(&file, &REBOUND_SET, &[E], &m, &cli);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));

    let table = Table::from_csv("rebound.csv", REBOUND_M.as_bytes()).unwrap();
    let s = load(&file, &REBOUND_SET);
    let r = fit(
        &s,
        &[Bound::new("contacts.restitution", 0.4, 0.8).unwrap()],
        table,
        &FitOptions::default(),
    )
    .unwrap();
    assert_same_files(&r, &cli.join("restitution_drop_fit"), false);
    let record = String::from_utf8(r.outputs.bytes("fit.toml").unwrap()).unwrap();
    assert!(
        record.contains("measured_file = \"rebound.csv\""),
        "{record}"
    );
    assert!(
        record.contains("set = [\"time.dt_s=1e-4\", \"contacts.restitution_exponent=0\"]"),
        "{record}"
    );
}

/// The first line of the command line's message for `args`, without `error: `.
fn cli_error(file: &Path, set: &[&str], fits: &[&str], m: &Path) -> String {
    let out = tmp();
    let o = cli_fit(file, set, fits, m, out.path());
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        tree(out.path()).is_empty(),
        "the command line wrote nothing"
    );
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    e.trim().trim_start_matches("error: ").to_string()
}

/// A bound outside the key's range, a key fitted twice, a key that is not a real number and a
/// measurement the run does not write are bad input naming the key (or the row), with the
/// command line's message; nothing runs far: each is found before or at the first run.
#[test]
fn bad_bounds_are_errors_naming_the_key() {
    let dir = tmp();
    let m = dir.path().join("m.csv");
    std::fs::write(&m, PASTE_M).unwrap();
    let file = scenario("paste_single_ball.toml");
    let s = load(&file, &[ONE_HEIGHT]);
    let opts = FitOptions::default();
    let bad = |fits: &[&str]| -> (Error, String) {
        let bounds: Vec<Bound> = fits.iter().map(|f| Bound::parse(f).unwrap()).collect();
        let e = fit(&s, &bounds, m.as_path(), &opts).unwrap_err();
        (e, cli_error(&file, &[ONE_HEIGHT], fits, &m))
    };
    // Outside the key's range: η_B must be > 0.
    let (e, cli) = bad(&["fluid.plastic_viscosity_pa_s=-1:3"]);
    let Error::BadInput(b) = &e else {
        panic!("{e}")
    };
    assert_eq!(b.key.as_deref(), Some("fluid.plastic_viscosity_pa_s"));
    assert!(
        b.message
            .contains("--fit fluid.plastic_viscosity_pa_s=-1:3"),
        "{e}"
    );
    assert!(b.message.contains("out of range"), "{e}");
    assert_eq!(e.to_string(), cli);
    // Fitted twice.
    let (e, cli) = bad(&[ETA, "fluid.plastic_viscosity_pa_s=0.2:2"]);
    let Error::BadInput(b) = &e else {
        panic!("{e}")
    };
    assert_eq!(b.key.as_deref(), Some("--fit"));
    assert_eq!(b.file, Path::new("fluid.plastic_viscosity_pa_s"));
    assert!(b.message.contains("fitted twice"), "{e}");
    assert_eq!(e.to_string(), cli);
    // Not a real number.
    let (e, cli) = bad(&["name=0:1"]);
    assert!(e.to_string().contains("must be a real number"), "{e}");
    assert_eq!(e.to_string(), cli);
    // A column the run does not write: found at the first run, naming M.csv's row.
    let m2 = dir.path().join("m2.csv");
    std::fs::write(&m2, "file,column,row,value\nsummary.csv,nope_m,0,1\n").unwrap();
    let e = fit(
        &s,
        &[Bound::parse(ETA).unwrap()],
        Measured::from(m2.as_path()),
        &opts,
    )
    .unwrap_err();
    assert!(e.to_string().contains("no column `nope_m`"), "{e}");
    assert_eq!(e.to_string(), cli_error(&file, &[ONE_HEIGHT], &[ETA], &m2));
    // No key at all.
    assert!(fit(&s, &[], m.as_path(), &opts).is_err());
}

/// `settle::fit::slump` returns the yield stresses `settle fit slump` prints, its lines
/// those the command line prints.
#[test]
fn slump_returns_what_settle_fit_slump_prints() {
    let s = slump(152.0, &[102.0, 103.0, 100.0], 1843.0, 9.81).unwrap();
    let o = settle()
        .args([
            "fit",
            "slump",
            "--height-mm",
            "152",
            "--slump-mm",
            "102,103,100",
        ])
        .args(["--density", "1843"])
        .output()
        .unwrap();
    assert!(o.status.success());
    let printed: Vec<String> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(String::from)
        .collect();
    assert_eq!(s.lines, printed);
    assert_eq!(s.tests.len(), 3);
    assert!((s.tests[2].yield_stress_pa - 144.6).abs() < 0.05);
}
