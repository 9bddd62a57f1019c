//! The console table of each kind and the validity warnings (issue 13, items 3 and 4): what a
//! run prints on stdout, checked on its content and number format, and the warnings as written
//! to `run.toml [run] warnings`.

use crate::common::{read_csv, read_csv_records, settle, tmp};
use std::path::Path;

/// Runs `settle run FILE --out OUT` with `--set` overrides (no `-q`: the table is the point) and
/// returns stdout; exit 0 required.
pub fn run(file: &str, out: &Path, sets: &[&str]) -> String {
    let mut c = settle();
    c.arg("run").arg(file).arg("--out").arg(out);
    for s in sets {
        c.arg("--set").arg(s);
    }
    let o = c.output().unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(
        o.status.code(),
        Some(0),
        "stdout: {text}\nstderr: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    text
}

/// The `[run] warnings` of a run folder's run.toml.
pub fn toml_warnings(dir: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(dir.join("run.toml")).unwrap();
    let v: toml::Value = toml::from_str(&text).unwrap();
    v["run"]["warnings"]
        .as_array()
        .expect("[run] warnings")
        .iter()
        .map(|w| w.as_str().unwrap().to_string())
        .collect()
}

/// Every number printed is in the one format: no exponent `e0` (nor `e+`/`e-0`), no negative
/// zero, no float noise (at most 6 significant digits in a plain or exponent number).
pub fn assert_one_number_format(text: &str) {
    for token in text.split(|c: char| c.is_whitespace() || "(),;:=[]%/–".contains(c)) {
        let t = token.trim_start_matches('+');
        let Ok(x) = t.parse::<f64>() else { continue };
        assert!(
            !t.contains("e0") && !t.contains("e+") && !t.contains("e-0"),
            "{t} in:\n{text}"
        );
        assert!(
            !(x == 0.0 && t.starts_with('-')),
            "negative zero {t} in:\n{text}"
        );
        let mantissa = t.split('e').next().unwrap();
        let digits = mantissa
            .trim_start_matches(['-', '0', '.'])
            .replace('.', "");
        assert!(digits.len() <= 6, "float noise {t} in:\n{text}");
    }
}

/// The console cell `cell` shows `x` as console tables print it (`io::fmt::g`: 4 significant
/// digits): it parses to `x` within half a unit of its 4th significant digit, and prints at least
/// 4 significant digits. (The cell is parsed, not compared with the formatter's text, which is
/// internal to the crate; [`assert_one_number_format`] checks the format itself.)
pub fn shows(cell: &str, x: f64) -> bool {
    let Ok(p) = cell.parse::<f64>() else {
        return false;
    };
    if x == 0.0 {
        return p == 0.0;
    }
    let half_unit = 0.5 * 10f64.powi(x.abs().log10().floor() as i32 - 3);
    let mantissa = cell.split('e').next().unwrap();
    let digits = mantissa
        .trim_start_matches(['-', '0', '.'])
        .replace('.', "");
    (p - x).abs() <= half_unit * (1.0 + 1e-9) && digits.len() >= 4
}

/// The header row of the table (the line after the title) split into column names.
fn columns(text: &str) -> Vec<String> {
    text.lines()
        .nth(1)
        .unwrap()
        .split_whitespace()
        .map(String::from)
        .collect()
}

/// stokes_single (f-EDEM's sphere in water) runs at Re = 0.93, above Stokes' range Re < 0.5:
/// it warns, printed and written; at half the diameter (Re ≈ 0.12) it does not. Its table and
/// summary.csv give the Reynolds number ρ_f v d / η of the simulated velocity.
#[test]
fn stokes_single_prints_its_reynolds_number_and_no_warning() {
    let dir = tmp();
    let small = run(
        "scenarios/stokes_single.toml",
        dir.path(),
        &["spheres[0].diameter_m=5e-5"],
    );
    assert!(!small.contains("warning"), "{small}");
    assert!(toml_warnings(&dir.path().join("stokes_single")).is_empty());
    let text = run("scenarios/stokes_single.toml", dir.path(), &[]);
    let w = toml_warnings(&dir.path().join("stokes_single"));
    assert!(
        w.len() == 1 && w[0].contains("largest Re = 0.9265"),
        "{w:?}"
    );
    assert!(
        text.contains("warning: Stokes drag used above its range"),
        "{text}"
    );
    let cols = columns(&text);
    assert!(cols.contains(&"Re".to_string()), "{cols:?}");
    let rows = read_csv_records(&dir.path().join("stokes_single/summary.csv"));
    let r = &rows[0];
    let f = |k: &str| r[k].parse::<f64>().unwrap();
    let re = 1000.0 * f("v_simulated_m_s") * f("diameter_m") / 1e-3;
    assert!((f("reynolds") / re - 1.0).abs() < 1e-12, "{r:?}");
    assert!((0.9..0.95).contains(&re), "{re}");
    let printed = text
        .lines()
        .nth(2)
        .unwrap()
        .split_whitespace()
        .nth(8)
        .unwrap();
    assert!(shows(printed, re), "{printed} is not {re}:\n{text}");
    assert_one_number_format(&text);
}

/// f-EDEM's Bingham drag is validated for 8–57.1 mm and 1314–8135 kg/m³: the paste drop's balls
/// (8–16 mm steel) are inside, a 5 mm ball is not.
#[test]
fn the_bingham_law_warns_outside_its_validated_range_only() {
    let dir = tmp();
    let text = run("scenarios/paste_single_ball.toml", dir.path(), &[]);
    assert!(!text.contains("warning"), "{text}");
    let text = run(
        "scenarios/paste_single_ball.toml",
        dir.path(),
        &["spheres[0].diameter_m=0.005"],
    );
    let w = toml_warnings(&dir.path().join("paste_single_ball"));
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].contains("f-EDEM's Bingham drag") && w[0].contains("8–57.1 mm"),
        "{w:?}"
    );
    assert!(
        w[0].contains("6 of 18 sphere(s)") && w[0].contains("5 mm"),
        "{w:?}"
    );
    assert!(text.contains(&format!("  warning: {}", w[0])), "{text}");
}

/// The cylinder's table gives the instruments' largest errors against the input curve (those
/// of instrument_errors.csv) and the times in minutes; its one-way coupling is checked against
/// seed 000's limits (60 g in the 1.447 L cylinder: 1.66 % by volume, above 1.6 %), and a
/// percent finer above 100 % is explained exactly when one was read.
#[test]
fn the_cylinder_table_and_its_warnings() {
    let dir = tmp();
    let text = run(
        "scenarios/sedimentation_sample1.toml",
        dir.path(),
        &[
            "sample.particles=2000",
            "sample.contacts=false",
            "sample.lubrication=false",
        ],
    );
    let run_dir = dir.path().join("sedimentation_sample1");
    assert!(text.contains("to t = 1440 min (86400 s)"), "{text}");
    let (h, rows) = read_csv(&run_dir.join("instrument_errors.csv"));
    let at = |name: &str| h.iter().position(|c| c == name).unwrap();
    for r in &rows {
        let line = text
            .lines()
            .find(|l| {
                l.trim_start()
                    .starts_with(&format!("{} ", r[at("instrument")]))
            })
            .unwrap_or_else(|| panic!("no row for {} in:\n{text}", r[at("instrument")]));
        let max: f64 = r[at("max_abs_error_percent")].parse().unwrap();
        assert!(
            line.split_whitespace().any(|c| shows(c, max)),
            "{line} lacks {max}"
        );
    }
    let w = toml_warnings(&run_dir);
    assert!(
        w.iter()
            .any(|x| x.contains("one-way coupling") && x.contains("1.66 % by volume")),
        "{w:?}"
    );
    let readings = read_csv_records(&run_dir.join("instruments.csv"));
    let over = readings
        .iter()
        .filter(|r| r["percent_finer"].parse::<f64>().unwrap() > 100.0)
        .count();
    let explained = w.iter().find(|x| x.contains("percent finer above 100 %"));
    assert_eq!(
        explained.is_some(),
        over > 0,
        "{over} readings above 100 %: {w:?}"
    );
    if let Some(x) = explained {
        assert!(
            x.contains(&format!("in {over} reading(s)")) && x.contains("1σ = "),
            "{x}"
        );
    }
    for x in &w {
        assert!(text.contains(&format!("  warning: {x}")), "{text}");
    }
    assert_one_number_format(&text);
}

/// A lighter sample (30 g: 0.83 % by volume, 2.0 % by mass) is within the one-way limits.
#[test]
fn a_dilute_cylinder_has_no_coupling_warning() {
    let dir = tmp();
    run(
        "scenarios/sedimentation_sample1.toml",
        dir.path(),
        &[
            "sample.particles=500",
            "sample.mass_kg=0.03",
            "sample.contacts=false",
            "sample.lubrication=false",
        ],
    );
    let w = toml_warnings(&dir.path().join("sedimentation_sample1"));
    assert!(!w.iter().any(|x| x.contains("one-way")), "{w:?}");
}
