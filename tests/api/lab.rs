//! `settle::invert::invert` and `settle::laws::laws` against `settle invert` and `settle laws`:
//! every table's CSV bytes are the file's, every chart the same SVG, `write` writes the same
//! folder, and a bad option is refused naming it, with the command line's message.

use crate::common::{settle, tmp, tree};
use settle::invert::{invert, InvertOptions};
use settle::laws::{laws, LawsOptions};
use settle::reduce::Readings;
use settle::{Error, Outputs, Table};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The four instruments' readings of sample 2 (data/invert/sample2_full/).
fn sample2() -> Vec<PathBuf> {
    [
        "readings.csv",
        "readings_d7928.csv",
        "readings_pipette.csv",
        "readings_sphere.csv",
    ]
    .iter()
    .map(|f| root().join("data/invert/sample2_full").join(f))
    .collect()
}

/// Runs the command line `settle ARGS --out OUT`, expecting success.
fn cli<S: AsRef<std::ffi::OsStr>>(args: &[S], out: &Path) {
    let o = settle().args(args).arg("--out").arg(out).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// The files of a results folder (no marker), relative, sorted.
fn files(dir: &Path) -> Vec<String> {
    tree(dir)
        .into_iter()
        .filter(|p| dir.join(p).is_file())
        .map(|p| p.to_string_lossy().replace('\\', "/"))
        .filter(|p| !p.starts_with(".settle"))
        .collect()
}

/// The bytes of a file, its `wall_time_s` lines left out (they measure the machine).
fn without_wall_time(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes)
        .lines()
        .filter(|l| !l.starts_with("wall_time_s"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every CSV file of `dir` is a table of `outputs` with the same bytes (and there is no other
/// table); every other file is the same bytes (wall times aside).
fn assert_same(outputs: &Outputs, dir: &Path, what: &str) {
    let all = files(dir);
    let csvs: Vec<&String> = all.iter().filter(|p| p.ends_with(".csv")).collect();
    assert!(!csvs.is_empty(), "{what}: no CSV file in {}", dir.display());
    let mut names: Vec<String> = outputs
        .tables()
        .iter()
        .map(|t| t.name().to_string())
        .collect();
    names.sort();
    assert_eq!(
        names,
        csvs.iter().map(|s| s.to_string()).collect::<Vec<_>>(),
        "{what}: the tables are the CSV files"
    );
    for name in &csvs {
        let t = outputs.get(name).unwrap();
        assert!(
            t.to_csv().unwrap() == std::fs::read(dir.join(name)).unwrap(),
            "{what}: {name} differs from the command line's file"
        );
    }
    for name in all.iter().filter(|p| !p.ends_with(".csv")) {
        let got = outputs
            .bytes(name)
            .unwrap_or_else(|| panic!("{what}: no file {name}"));
        assert_eq!(
            without_wall_time(&got),
            without_wall_time(&std::fs::read(dir.join(name)).unwrap()),
            "{what}: {name} differs from the command line's file"
        );
    }
}

#[test]
fn invert_tables_equal_the_files_of_settle_invert() {
    let files = sample2();
    let out = tmp();
    let mut args: Vec<std::ffi::OsString> = vec!["invert".into()];
    args.extend(files.iter().map(|f| f.clone().into_os_string()));
    args.extend(["--model".into(), "full".into(), "--bounds".into()]);
    cli(&args, out.path());
    let opts = InvertOptions {
        model: "full".into(),
        bounds: Some(settle::invert::DEFAULT_BOUNDS_CONFIDENCE),
        ..InvertOptions::default()
    };
    let readings: Vec<Readings> = files.iter().map(|f| Readings::from(f.as_path())).collect();
    let r = invert(&readings, &opts).unwrap();
    assert_eq!(r.name, "readings_inverted");
    let dir = out.path().join("readings_inverted");
    assert_same(&r.outputs, &dir, "invert");
    // the typed figures are the table's (which rounds them to 12 significant digits)
    let finer = r.table("inverted").unwrap().f64s("percent_finer").unwrap();
    assert_eq!(finer.len(), r.curve.len());
    for (f, c) in finer.iter().zip(&r.curve) {
        assert!((f - c.percent_finer).abs() <= 1e-11 * c.percent_finer.abs().max(1e-300));
    }
    assert!(r.curve.iter().any(|c| c.bounds.is_some()), "--bounds: none");
    // write: the same files
    let again = tmp();
    let written = r.write(again.path()).unwrap();
    assert_eq!(written, again.path().join("readings_inverted"));
    assert_eq!(self::files(&written), self::files(&dir));
    assert_same(&Outputs::read_dir(&written).unwrap(), &dir, "invert write");
    // the console lines name the folder written
    assert!(r.lines(&written)[0].ends_with(&format!("-> {}", written.display())));
}

/// A readings file's content as readings in memory: its `# key = value` figures and its table,
/// named as the file.
fn in_memory(file: &Path) -> Readings {
    let text = std::fs::read_to_string(file).unwrap();
    let mut figures = Vec::new();
    let mut table: Option<Table> = None;
    for l in text.lines().filter(|l| !l.trim().is_empty()) {
        if let Some(c) = l.strip_prefix('#') {
            if let Some((k, v)) = c.split_once('=') {
                figures.push((k.trim().to_string(), v.trim().to_string()));
            }
            continue;
        }
        let cells: Vec<String> = l.split(',').map(|c| c.trim().to_string()).collect();
        match &mut table {
            None => table = Some(Table::new(file.to_string_lossy(), cells)),
            Some(t) => t.push(cells),
        }
    }
    Readings::table(figures, table.unwrap())
}

#[test]
fn invert_of_readings_in_memory_equals_the_files_of_settle_invert() {
    let file = root().join("data/lab/envalysis_clayloam_d422.csv");
    let out = tmp();
    cli(&[Path::new("invert"), &file], out.path());
    let r = invert(&[in_memory(&file)], &InvertOptions::default()).unwrap();
    assert_eq!(r.name, "envalysis_clayloam_d422_inverted");
    assert_same(
        &r.outputs,
        &out.path().join("envalysis_clayloam_d422_inverted"),
        "invert in memory",
    );
}

#[test]
fn laws_tables_equal_the_files_of_settle_laws() {
    let out = tmp();
    cli(&["laws"], out.path());
    let r = laws(&LawsOptions::default()).unwrap();
    let dir = out.path().join("laws");
    assert_same(&r.outputs, &dir, "laws");
    assert_eq!(r.table("laws").unwrap().len(), r.results.len());
    let again = tmp();
    let written = r.write(again.path()).unwrap();
    assert_eq!(files(&written), files(&dir));
    assert_same(&Outputs::read_dir(&written).unwrap(), &dir, "laws write");
    assert_eq!(
        r.lines(&written).last().unwrap(),
        &format!("-> {}", written.display())
    );
}

/// The option an error names and its message.
fn refused(e: Error) -> (Option<String>, String) {
    let text = e.to_string();
    match e {
        Error::BadInput(b) => (b.key, text),
        other => panic!("expected bad input, got {other}"),
    }
}

#[test]
fn a_bad_option_is_refused_naming_it() {
    let file = root().join("data/lab/envalysis_clayloam_d422.csv");
    let readings = [Readings::from(file.as_path())];
    let cases: [(InvertOptions, &str, &str); 4] = [
        (
            InvertOptions {
                model: "hindered".into(),
                ..InvertOptions::default()
            },
            "--model",
            "unknown model; allowed: ideal-stokes, full",
        ),
        (
            InvertOptions {
                lambda: "-1".into(),
                ..InvertOptions::default()
            },
            "--lambda",
            "allowed: discrepancy, gcv or a number ≥ 0",
        ),
        (
            InvertOptions {
                bins: Some(1),
                ..InvertOptions::default()
            },
            "--bins",
            "allowed: 2–200",
        ),
        (
            InvertOptions {
                diameters_um: Some("75:2".into()),
                ..InvertOptions::default()
            },
            "--diameters-um",
            "reversed or empty range",
        ),
    ];
    for (opts, key, msg) in cases {
        let (k, text) = refused(invert(&readings, &opts).unwrap_err());
        assert_eq!(k.as_deref(), Some(key), "{text}");
        assert!(text.contains(msg), "{key}: {text}");
    }
    // The command line says the same.
    let o = settle()
        .arg("invert")
        .arg(&file)
        .args(["--model", "hindered"])
        .output()
        .unwrap();
    let (_, text) = refused(invert(&readings, &cases_model()).unwrap_err());
    assert_eq!(
        String::from_utf8_lossy(&o.stderr).trim(),
        format!("error: {text}")
    );
    let (k, text) = refused(invert(&[], &InvertOptions::default()).unwrap_err());
    assert_eq!(k.as_deref(), Some("READINGS.csv"), "{text}");
    let (k, text) = refused(
        laws(&LawsOptions {
            spheres: Some(root().join("data/valentik_whitmore_1965_spheres.csv")),
            fluids: None,
        })
        .unwrap_err(),
    );
    assert_eq!(k.as_deref(), Some("--fluids"), "{text}");
    // a spheres file without its columns: refused naming it
    let dir = tmp();
    let bad = dir.path().join("bad_spheres.csv");
    std::fs::write(&bad, "sphere_id,suspension\nS1,1\n").unwrap();
    let (k, text) = refused(
        laws(&LawsOptions {
            spheres: Some(bad),
            fluids: Some(root().join("data/valentik_whitmore_1965_suspensions.csv")),
        })
        .unwrap_err(),
    );
    assert!(text.contains("bad_spheres.csv"), "{k:?}: {text}");
}

fn cases_model() -> InvertOptions {
    InvertOptions {
        model: "hindered".into(),
        ..InvertOptions::default()
    }
}
