//! Bad input: every defective scenario must be refused before anything runs.
//!
//! `settle run FILE... --out DIR` on a bad scenario must exit with code 2, print exactly one line
//! on stderr (`error: FILE: key `KEY`: what is wrong and what is allowed`) and write nothing: no
//! output folder at all. Each file of `tests/bad_scenarios/` is a copy of a good scenario
//! (`scenarios/stokes_single.toml` or `scenarios/valentik_susp1.toml`) with one defect, described
//! in its header comment.
//!
//! A property test (`scenario::tests::fuzz`, a unit test) also feeds random mutations of the good
//! scenarios to `scenario::load_str`, which must return `Ok` or `Err` (one line), never panic.

use crate::common::{settle, tmp, tree};
use std::ffi::OsString;
use std::path::PathBuf;

fn crate_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn bad_dir() -> PathBuf {
    crate_dir().join("tests").join("bad_scenarios")
}

fn bad(file: &str) -> PathBuf {
    let p = bad_dir().join(file);
    assert!(p.is_file(), "missing test file {}", p.display());
    p
}

fn good(file: &str) -> PathBuf {
    let p = crate_dir().join("scenarios").join(file);
    assert!(p.is_file(), "missing good scenario {}", p.display());
    p
}

/// Outcome of one `settle run`.
struct Outcome {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    /// Root of the temporary tree; `--out` was `root/a/b/out`.
    root: tempfile::TempDir,
}

/// Runs `settle run FILES... --out ROOT/a/b/out EXTRA...` in a fresh temporary tree. The output
/// folder sits two levels down so that a name such as `../../etc` escaping it would still land
/// inside the tree, where [`assert_nothing_written`] sees it.
fn settle_run(files: &[PathBuf], extra: &[&str]) -> Outcome {
    let root = tmp();
    std::fs::create_dir_all(root.path().join("a").join("b")).expect("mkdir");
    let out = root.path().join("a").join("b").join("out");
    let mut args: Vec<OsString> = vec!["run".into()];
    args.extend(files.iter().map(|f| f.clone().into_os_string()));
    args.push("--out".into());
    args.push(out.into_os_string());
    args.extend(extra.iter().map(OsString::from));
    let o = settle()
        .args(&args)
        // Relative paths in the scenarios are resolved from the scenario file, not the cwd; run
        // from inside the temp tree so that nothing could be written next to the sources either.
        .current_dir(root.path())
        .output()
        .expect("run settle");
    Outcome {
        code: o.status.code(),
        stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
        root,
    }
}

/// The temporary tree holds only the folders made by [`settle_run`] (and at most an empty `out`).
fn assert_nothing_written(o: &Outcome) {
    let allowed: Vec<PathBuf> = ["a", "a/b", "a/b/out"].iter().map(PathBuf::from).collect();
    let t = tree(o.root.path());
    let extra: Vec<&PathBuf> = t.iter().filter(|p| !allowed.contains(p)).collect();
    assert!(
        extra.is_empty(),
        "bad input wrote {extra:?}\nstderr: {}",
        o.stderr
    );
}

/// Exit code 2, nothing on stdout, one line on stderr starting `error: ` and naming the file
/// `file_name`, and the key `key` (in backticks) if given, containing every word of `words`;
/// nothing written. Returns the error line.
fn assert_refused(o: &Outcome, file_name: &str, key: Option<&str>, words: &[&str]) -> String {
    let e = &o.stderr;
    assert_eq!(o.code, Some(2), "exit code; stderr: {e}");
    assert_eq!(o.stdout, "", "stdout on bad input; stderr: {e}");
    assert_eq!(e.lines().count(), 1, "stderr must be one line, got:\n{e}");
    assert!(
        e.ends_with('\n') && e.matches('\n').count() == 1,
        "one line: {e:?}"
    );
    assert!(
        e.starts_with("error: "),
        "stderr must start with `error: `: {e}"
    );
    assert!(
        e.contains(file_name),
        "stderr must name the file `{file_name}`: {e}"
    );
    if let Some(k) = key {
        assert!(
            e.contains(&format!("`{k}`")),
            "stderr must name the key `{k}`: {e}"
        );
    }
    for w in words {
        assert!(e.contains(w), "stderr must contain `{w}`: {e}");
    }
    assert_nothing_written(o);
    e.trim_end().to_string()
}

/// One test per bad scenario file: `case!(test_name, "file.toml", key, [words...])`.
macro_rules! case {
    ($test:ident, $file:literal, $key:expr, [$($w:literal),* $(,)?]) => {
        #[test]
        fn $test() {
            let o = settle_run(&[bad($file)], &[]);
            assert_refused(&o, $file, $key, &[$($w),*]);
        }
    };
}

/// Every file of `tests/bad_scenarios/` must have a case below (keep this list in step).
const CASES: &[&str] = &[
    "missing_fluid_density.toml",
    "missing_time_table.toml",
    "unknown_top_key.toml",
    "unknown_nested_key.toml",
    "negative_diameter.toml",
    "dt_zero.toml",
    "dt_negative.toml",
    "dt_above_end.toml",
    "syntax_error.toml",
    "string_for_number.toml",
    "dim2_cylinder.toml",
    "bingham_drag_newtonian.toml",
    "unknown_integrator.toml",
    "bad_name.toml",
    "poisson_07.toml",
    "section_inverted.toml",
    "csv_missing.toml",
    "unused_table_funnel.toml",
    "unused_table_sample.toml",
    "duplicate_sphere_id.toml",
    "csv_duplicate_id.toml",
    "sphere_wider_than_cylinder.toml",
    "drop_10km.toml",
    "csv_unknown_column.toml",
    "bulb_wider_than_cylinder.toml",
];

#[test]
fn every_bad_file_has_a_case() {
    let mut files: Vec<String> = std::fs::read_dir(bad_dir())
        .expect("tests/bad_scenarios")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    files.sort();
    let mut cases: Vec<String> = CASES.iter().map(|s| s.to_string()).collect();
    cases.sort();
    assert_eq!(files, cases);
}

// Missing keys.
case!(
    missing_fluid_density,
    "missing_fluid_density.toml",
    Some("fluid.density_kg_m3"),
    ["missing"]
);
case!(
    missing_time_table,
    "missing_time_table.toml",
    Some("time"),
    ["missing"]
);
// Unknown keys: the error lists the keys that are allowed.
case!(
    unknown_top_level_key,
    "unknown_top_key.toml",
    Some("dimenson"),
    ["unknown field", "`dimension`"]
);
case!(
    unknown_nested_key,
    "unknown_nested_key.toml",
    Some("fluid.viscosity"),
    ["unknown field", "`viscosity_pa_s`"]
);
// Ranges.
case!(
    negative_diameter,
    "negative_diameter.toml",
    Some("spheres[0].diameter_m"),
    ["-0.0001", "allowed", "0 < diameter_m"]
);
case!(
    dt_zero,
    "dt_zero.toml",
    Some("time.dt_s"),
    ["allowed", "0 < dt_s"]
);
case!(
    dt_negative,
    "dt_negative.toml",
    Some("time.dt_s"),
    ["-0.001", "allowed", "0 < dt_s"]
);
case!(
    dt_above_end,
    "dt_above_end.toml",
    Some("time.dt_s"),
    ["0.05", "allowed", "end_s"]
);
case!(
    poisson_ratio_07,
    "poisson_07.toml",
    Some("spheres[0].poisson_ratio"),
    ["0.7", "allowed", "0.5"]
);
case!(
    section_bottom_above_top,
    "section_inverted.toml",
    Some("measure.section_bottom_depth_m"),
    ["allowed", "section_top_depth_m"]
);
// Types and enum values.
case!(
    string_for_number,
    "string_for_number.toml",
    Some("spheres[0].diameter_m"),
    ["\"0.1 mm\" is not a number", "without a unit"]
);
case!(
    unknown_integrator,
    "unknown_integrator.toml",
    Some("time.integrator"),
    ["rk4", "`explicit`", "`implicit`", "`exponential`"]
);
// Cross-field rules.
case!(
    cylinder_in_2d,
    "dim2_cylinder.toml",
    Some("container.diameter_m"),
    ["3D", "width_m"]
);
case!(
    bingham_drag_with_newtonian_fluid,
    "bingham_drag_newtonian.toml",
    Some("drag.law"),
    ["bingham", "`stokes`", "`dallavalle`"]
);
// Output paths must stay in the output folder.
case!(
    name_escaping_out_dir,
    "bad_name.toml",
    Some("name"),
    ["../../etc", "letters", "digits"]
);
// A CSV of spheres that does not exist.
case!(
    spheres_csv_missing,
    "csv_missing.toml",
    Some("spheres_csv.path"),
    ["no_such_spheres.csv", "cannot read"]
);

// A table the kind does not use names the table and the kind.
case!(
    unused_table_funnel_on_free_settling,
    "unused_table_funnel.toml",
    Some("funnel"),
    ["[funnel]", "not used", "free_settling"]
);
case!(
    unused_table_sample_on_drop,
    "unused_table_sample.toml",
    Some("sample"),
    ["[sample]", "not used", "\"drop\""]
);
// Issue 12, data loss 8: accepted silently by the old binary.
case!(
    duplicate_sphere_id,
    "duplicate_sphere_id.toml",
    Some("spheres[1].id"),
    ["fedem-table1", "spheres[0]", "allowed one sphere per id"]
);
case!(
    csv_duplicate_sphere_id,
    "csv_duplicate_id.toml",
    Some("spheres_csv.path"),
    [
        "spheres_duplicate_id.csv",
        "line 4 (data row 2)",
        "S1-01",
        "line 3 (data row 1)",
        "allowed one row per id"
    ]
);
case!(
    sphere_wider_than_cylinder,
    "sphere_wider_than_cylinder.toml",
    Some("spheres[0].diameter_m"),
    ["0.003", "allowed", "< container.diameter_m = 0.002 m"]
);
case!(
    hydrometer_bulb_wider_than_cylinder,
    "bulb_wider_than_cylinder.toml",
    Some("instruments.hydrometer_bulb_length_m"),
    [
        "0.02 m",
        "79.22 mm",
        "container.width_m = 0.0635 m",
        "allowed bulb diameter ≤ 53.5 mm",
        "hydrometer_bulb_length_m ≥ 0.0361 m"
    ]
);
/// The bulb the refusal suggests (4 cm long, Ø 50.3 mm: 6.6 mm from the wall) is accepted and runs.
#[test]
fn the_suggested_hydrometer_bulb_fits() {
    let o = settle_run(
        &[bad("bulb_wider_than_cylinder.toml")],
        &[
            "--quiet",
            "--set",
            "instruments.hydrometer_bulb_length_m=0.04",
        ],
    );
    assert_eq!(o.code, Some(0), "stderr: {}", o.stderr);
    use settle::instruments::hydrometer::{Hydrometer, HydrometerSpec};
    let bulb_mm = |len: f64, taper: f64| {
        let spec = HydrometerSpec {
            bulb_length_m: len,
            taper_m: taper,
            ..HydrometerSpec::default()
        };
        2e3 * Hydrometer::new(spec, 1000.0).bulb_radius_m
    };
    // The 152H, the impossible 2 cm bulb and the suggested 4 cm one (docs/validation/instruments.md).
    for (len, taper, mm) in [
        (0.14, 0.025, 27.75),
        (0.02, 0.005, 79.22),
        (0.04, 0.005, 50.27),
    ] {
        assert!(
            (bulb_mm(len, taper) - mm).abs() < 0.01,
            "{len} m: {}",
            bulb_mm(len, taper)
        );
    }
}

case!(
    drop_not_reaching_the_surface,
    "drop_10km.toml",
    Some("release.fall_heights_m[0]"),
    [
        "10000",
        "time.end_s = 2 s",
        "allowed 0 ≤ fall height < 19.62"
    ]
);
case!(
    csv_unknown_column,
    "csv_unknown_column.toml",
    Some("spheres_csv.path"),
    [
        "spheres_unknown_column.csv",
        "column 5",
        "`v_terminal_m_s`",
        "unknown",
        "v_measured_m_s or v_terminal_measured_m_s",
        "id or sphere_id"
    ]
);

/// A bad sample CSV is refused by the scenario layer's reader with its row, column and range
/// (a `BadInput`: exit 2) as the scenario is loaded (the sample is part of the typed
/// sedimentation spec), before anything runs.
#[test]
fn sample_csv_percent_out_of_range() {
    let path = good("sedimentation_sample1.toml");
    let e = settle::load(&path)
        .expect("good scenario")
        .set(
            "sample.csv",
            "\"../tests/bad_scenarios/bad_sample_percent.csv\"",
        )
        .expect_err("percent finer 120 must be refused");
    let line = e.to_string();
    let settle::Error::BadInput(e) = e else {
        panic!("not a bad input: {line}");
    };
    assert_eq!(e.key.as_deref(), Some("sample.csv"), "{line}");
    for w in [
        "sedimentation_sample1.toml",
        "bad_sample_percent.csv",
        "line 5 (data row 3), column 3 (`percent_finer`)",
        "120",
        "allowed 0 ≤ percent_finer ≤ 100",
    ] {
        assert!(line.contains(w), "`{w}` missing from: {line}");
    }
}

// The good sample CSV reads as the physics layer's reader reads it: `scenario::tests::sample_csv`
// (a unit test).

/// Every scenario of `scenarios/` loads (its tables all used by its kind) and its input files
/// (spheres CSV, sample CSV) read.
#[test]
fn every_good_scenario_loads_with_its_inputs() {
    let dir = crate_dir().join("scenarios");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).expect("scenarios/") {
        let path = e.expect("entry").path();
        if path.extension().is_none_or(|x| x != "toml") {
            continue;
        }
        // `settle::load` reads the scenario and its input files (spheres CSV, sample CSV).
        settle::load(&path).unwrap_or_else(|e| panic!("{} does not load: {e}", path.display()));
        n += 1;
    }
    assert!(n >= 16, "{n} scenarios");
}

/// A TOML syntax error names no key but the line (the broken `[drag` header is line 15).
#[test]
fn toml_syntax_error() {
    let o = settle_run(&[bad("syntax_error.toml")], &[]);
    let e = assert_refused(
        &o,
        "syntax_error.toml",
        None,
        &["TOML syntax error", "line 15"],
    );
    assert!(!e.contains("key `"), "a syntax error names no key: {e}");
}

/// One bad file among good ones: all are validated first, so nothing at all is written, not
/// even for the good files before it.
#[test]
fn one_bad_file_among_good_ones_writes_nothing() {
    let files = [
        good("stokes_single.toml"),
        good("valentik_susp1.toml"),
        bad("dt_zero.toml"),
    ];
    let o = settle_run(&files, &[]);
    assert_refused(&o, "dt_zero.toml", Some("time.dt_s"), &["allowed"]);
}

/// Same with the bad file first and a good one after it.
#[test]
fn bad_file_first_writes_nothing() {
    let files = [bad("poisson_07.toml"), good("stokes_single.toml")];
    let o = settle_run(&files, &[]);
    assert_refused(
        &o,
        "poisson_07.toml",
        Some("spheres[0].poisson_ratio"),
        &["0.5"],
    );
}

/// `--set` with a bad value is checked like the file itself.
#[test]
fn set_negative_dt() {
    let o = settle_run(&[good("stokes_single.toml")], &["--set", "time.dt_s=-1"]);
    assert_refused(
        &o,
        "stokes_single.toml",
        Some("time.dt_s"),
        &["-1", "allowed", "0 < dt_s"],
    );
}

/// A restitution exponent outside [0, 1] is refused with its key and range.
#[test]
fn set_restitution_exponent_out_of_range() {
    let o = settle_run(
        &[good("restitution_drop.toml")],
        &["--set", "contacts.restitution_exponent=1.5"],
    );
    assert_refused(
        &o,
        "restitution_drop.toml",
        Some("contacts.restitution_exponent"),
        &["1.5", "allowed"],
    );
}

/// `[transient]` in the Rapier scenes (issue 16): the added mass is accepted; the history force
/// and the wall are refused with their key; a coefficient out of range names key and range.
#[test]
fn set_transient_in_the_rapier_scenes() {
    for file in ["restitution_drop.toml", "paste_68_balls.toml"] {
        // The accepted added mass and its coefficient 0.5: `scenario::tests::transient_rapier`.
        let o = settle_run(&[good(file)], &["--set", "transient.history=basset"]);
        assert_refused(
            &o,
            file,
            Some("transient.history"),
            &["Rapier scenes", "history = \"off\"", "added_mass"],
        );
        let o = settle_run(
            &[good(file)],
            &[
                "--set",
                "transient.added_mass=true",
                "--set",
                "transient.added_mass_coefficient=2.5",
            ],
        );
        assert_refused(
            &o,
            file,
            Some("transient.added_mass_coefficient"),
            &["2.5", "allowed", "≤ 2"],
        );
        let o = settle_run(&[good(file)], &["--set", "transient.wall=brenner"]);
        assert_refused(&o, file, Some("transient.wall"), &["free_settling"]);
    }
}

/// Lubrication cut-offs of the sedimentation cylinder out of range are refused with key and range.
#[test]
fn set_lubrication_cutoffs_out_of_range() {
    for (set, key, words) in [
        (
            "sample.lubrication_outer_cutoff=0",
            "sample.lubrication_outer_cutoff",
            &["0", "allowed", "≤ 1"][..],
        ),
        (
            "sample.lubrication_outer_cutoff=1.5",
            "sample.lubrication_outer_cutoff",
            &["1.5", "allowed", "≤ 1"][..],
        ),
        (
            "sample.lubrication_inner_cutoff=0.2",
            "sample.lubrication_inner_cutoff",
            &["0.2", "allowed", "< lubrication_outer_cutoff = 0.1"][..],
        ),
        (
            "sample.lubrication_inner_cutoff=-1e-3",
            "sample.lubrication_inner_cutoff",
            &["-0.001", "allowed", "0 < lubrication_inner_cutoff"][..],
        ),
    ] {
        let o = settle_run(&[good("sedimentation_sample1.toml")], &["--set", set]);
        assert_refused(&o, "sedimentation_sample1.toml", Some(key), words);
    }
}

/// Lubrication without contacts is refused (the squeeze film is solved in the contact solve).
#[test]
fn set_lubrication_without_contacts() {
    let o = settle_run(
        &[good("sedimentation_sample1.toml")],
        &["--set", "sample.lubrication=true"],
    );
    assert_refused(
        &o,
        "sedimentation_sample1.toml",
        Some("sample.lubrication"),
        &["allowed", "contacts = true"],
    );
}

/// A `[contacts]` key the cylinder's contact solve does not model is refused, not ignored
/// (issue 12: `[contacts]` on a sedimentation scenario used to be accepted and ignored whole).
#[test]
fn set_rolling_resistance_on_sedimentation() {
    let o = settle_run(
        &[good("sedimentation_sample1.toml")],
        &[
            "--set",
            "contacts.restitution=0.0",
            "--set",
            "contacts.friction=0.3",
            "--set",
            "contacts.rolling_resistance=0.002",
        ],
    );
    assert_refused(
        &o,
        "sedimentation_sample1.toml",
        Some("contacts.rolling_resistance"),
        &["0.002", "not modelled", "allowed 0"],
    );
}

/// `--set` naming an unknown key is refused like a typo in the file.
#[test]
fn set_unknown_key() {
    let o = settle_run(
        &[good("stokes_single.toml")],
        &["--set", "fluid.viscosity=0.002"],
    );
    assert_refused(
        &o,
        "stokes_single.toml",
        Some("fluid.viscosity"),
        &["unknown field", "`viscosity_pa_s`"],
    );
}

/// `--dt 0` is `time.dt_s = 0`.
#[test]
fn dt_flag_zero() {
    let o = settle_run(&[good("stokes_single.toml")], &["--dt", "0"]);
    assert_refused(
        &o,
        "stokes_single.toml",
        Some("time.dt_s"),
        &["allowed", "0 < dt_s"],
    );
}

/// `--dt 0` applies to every file: with two good files, the first is named and nothing written.
#[test]
fn dt_flag_zero_two_files() {
    let files = [good("valentik_susp1.toml"), good("stokes_single.toml")];
    let o = settle_run(&files, &["--dt", "0"]);
    assert_refused(&o, "valentik_susp1.toml", Some("time.dt_s"), &["allowed"]);
}

// Random mutations of the good scenarios never make the loader panic: `scenario::tests::fuzz`
// (a property test of `load_str`, a unit test).
