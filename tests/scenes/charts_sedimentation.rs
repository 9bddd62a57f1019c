//! The charts of a sedimentation run read as issue 13 asks (title, axis labels with units, tick
//! labels of at most 6 significant digits), and say what their CSV says: seed 000 Figs. 4,
//! 11–18, on one small run of the binary (2000 grains to 900 s: the snapshots at 60, 300 and
//! 900 s, and the hydrometer at 2, 5 and 15 min).

use crate::common::chart::{assert_readable_chart, svg_texts};
use crate::common::{num, read_csv_records, settle};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The output folder of the small run, made once for every test of this file.
fn out() -> &'static Path {
    static OUT: OnceLock<PathBuf> = OnceLock::new();
    OUT.get_or_init(|| {
        let dir = crate::common::tmp().keep();
        let o = settle()
            .args([
                "run",
                "scenarios/sedimentation_sample1.toml",
                "--set",
                "sample.particles=2000",
                "--set",
                "time.end_s=900",
                "--quiet",
                "--out",
            ])
            .arg(&dir)
            .output()
            .expect("settle runs");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        dir.join("sedimentation_sample1")
    })
}

/// Seed Fig. 11: one panel per snapshot time with the time written out, a depth axis in cm and a
/// grey scale in % of the sample's mass; `cylinder.csv` holds the grey levels and the bed, which
/// together account for the whole sample at every time.
#[test]
fn the_cylinder_shows_each_time_with_a_depth_axis_and_a_grey_scale() {
    let texts = assert_readable_chart(
        &out().join("cylinder.svg"),
        "the cylinder at 60, 300 and 900 s",
        &["depth below the surface (cm)", "suspended mass fraction"],
    );
    for t in [
        "t = 60 s (1 min)",
        "t = 300 s (5 min)",
        "t = 900 s (15 min)",
    ] {
        assert!(texts.iter().any(|x| x == t), "no panel `{t}` in {texts:?}");
    }
    assert!(
        !out().join("cylinder.png").exists(),
        "the unreadable PNG is gone"
    );
    let rows = read_csv_records(&out().join("cylinder.csv"));
    assert_eq!(rows.len(), 3 * 100, "100 bands at each of 3 times");
    for t in [60.0, 300.0, 900.0] {
        let of_t: Vec<_> = rows.iter().filter(|r| num(r, "time_s") == t).collect();
        let suspended: f64 = of_t.iter().map(|r| num(r, "suspended_mass_fraction")).sum();
        let bed = num(of_t[0], "bed_mass_fraction");
        assert!(
            (suspended + bed - 1.0).abs() < 1e-9,
            "t = {t}: {suspended} + {bed}"
        );
        assert!((num(of_t[0], "time_min") - t / 60.0).abs() < 1e-12);
        let bottom = num(of_t[99], "depth_bottom_m");
        assert!((bottom - 0.457).abs() < 1e-12, "bands reach H: {bottom}");
    }
    // The bed grows: more of the sample has settled at 900 s than at 60 s.
    let bed = |t: f64| {
        rows.iter()
            .find(|r| num(r, "time_s") == t)
            .map(|r| num(r, "bed_mass_fraction"))
            .unwrap()
    };
    assert!(bed(900.0) > bed(60.0) && bed(60.0) > 0.0);
}

/// Seed Fig. 12: the largest diameter above each depth against eq. 16, in µm against cm, at the
/// record and snapshot times among 60, 120, 300 and 900 s.
#[test]
fn the_largest_diameter_is_charted_against_eq_16() {
    let texts = assert_readable_chart(
        &out().join("max_diameter.svg"),
        "largest grain above each depth against eq. 16",
        &[
            "depth below the surface (cm)",
            "largest diameter above the depth (µm)",
        ],
    );
    for l in [
        "simulation, t = 60 s (1 min)",
        "simulation, t = 300 s (5 min)",
        "eq. 16, t = 900 s (15 min)",
    ] {
        assert!(texts.iter().any(|x| x == l), "no legend `{l}` in {texts:?}");
    }
    // 300 s is no record time of this run: its rows come from the snapshot at 300 s.
    let rows = read_csv_records(&out().join("max_diameter.csv"));
    for t in [60.0, 300.0, 900.0] {
        let n = rows.iter().filter(|r| num(r, "time_s") == t).count();
        assert_eq!(n, 100, "t = {t}");
    }
    assert_eq!(rows.len(), 300);
}

/// Seed Fig. 13: one line per hydrometer time (t = 0 and 2, 5, 15 min), labelled with the time.
#[test]
fn the_bulb_density_has_one_labelled_line_per_time() {
    let texts = assert_readable_chart(
        &out().join("bulb_density.svg"),
        "suspension density along the hydrometer bulb",
        &[
            "distance below the top of the bulb h_hd (cm)",
            "suspension density, mean over 1 cm (kg/m³)",
        ],
    );
    for l in [
        "t = 0 s (0 min)",
        "t = 120 s (2 min)",
        "t = 300 s (5 min)",
        "t = 900 s (15 min)",
    ] {
        assert!(texts.iter().any(|x| x == l), "no line `{l}` in {texts:?}");
    }
    let rows = read_csv_records(&out().join("bulb_density.csv"));
    assert!(rows
        .iter()
        .all(|r| (num(r, "time_min") * 60.0 - num(r, "time_s")).abs() < 1e-9));
}

/// Seed Fig. 14: the bulb-mean density against eq. 19, against time in minutes.
#[test]
fn the_bulb_mean_density_is_charted_against_eq_19() {
    let texts = assert_readable_chart(
        &out().join("bulb_mean_density.svg"),
        "mean density around the bulb against eq. 19",
        &[
            "time, log scale (min)",
            "suspension density around the bulb (kg/m³)",
        ],
    );
    assert!(texts
        .iter()
        .any(|x| x == "eq. 19 from the hydrometer's depth"));
    assert!(texts.iter().any(|x| x == "mean over the bulb (simulation)"));
}

/// Seed Figs. 15–17: depth, diameter and percent finer of each instrument against time in
/// minutes, each on its own axis with its unit; `instruments.csv` and `granulometry.csv` carry
/// the time in minutes beside the time in seconds.
#[test]
fn the_instruments_are_charted_against_time_in_minutes() {
    for (file, title, y) in [
        (
            "instrument_depths.svg",
            "depth of each reading",
            "depth below the surface (cm)",
        ),
        (
            "instrument_diameters.svg",
            "limiting diameter of each reading",
            "limiting diameter φ_o, log scale (µm)",
        ),
        (
            "instruments.svg",
            "percent finer read against time",
            "percent finer w_o (%)",
        ),
    ] {
        let texts = assert_readable_chart(&out().join(file), title, &["time, log scale (min)", y]);
        for k in ["hydrometer", "buoyancy", "pipette"] {
            assert!(
                texts.iter().any(|x| x == k),
                "{file}: no `{k}` in {texts:?}"
            );
        }
    }
    for file in ["instruments.csv", "granulometry.csv"] {
        let rows = read_csv_records(&out().join(file));
        let timed: Vec<_> = rows.iter().filter(|r| !r["time_s"].is_empty()).collect();
        assert_eq!(
            timed.len(),
            3 + 2 * 5,
            "{file}: hydrometer at 2, 5, 15 min; sphere and pipette at 0.5, 1, 2, 4, 15 min"
        );
        for r in timed {
            assert_eq!(num(r, "time_min") * 60.0, num(r, "time_s"), "{file}");
        }
    }
    for (file, title, y, k) in [
        (
            "sphere_mass.svg",
            "apparent mass of the buoyancy sphere",
            "apparent mass of the sphere (g)",
            "buoyancy",
        ),
        (
            "pipette_mass.svg",
            "dry mass drawn by the pipette",
            "dry mass in the pipette (g)",
            "pipette",
        ),
    ] {
        let texts = assert_readable_chart(&out().join(file), title, &["time, log scale (min)", y]);
        assert!(
            texts.iter().any(|x| x == k),
            "{file}: no `{k}` in {texts:?}"
        );
    }
    let header = std::fs::read_to_string(out().join("instruments.csv")).unwrap();
    assert!(header.starts_with("time_s,time_min,instrument,"));
}

/// Seed Fig. 18: percent finer against log diameter with the input curve.
#[test]
fn the_granulometry_has_the_input_curve_and_the_three_instruments() {
    let texts = assert_readable_chart(
        &out().join("granulometry.svg"),
        "percent finer, input and instruments",
        &["diameter, log scale (µm)", "percent finer (%)"],
    );
    for k in ["input", "hydrometer", "buoyancy", "pipette"] {
        assert!(texts.iter().any(|x| x == k), "no `{k}` in {texts:?}");
    }
}

/// Seed Fig. 4: the velocity from rest of six diameters of the sample, and the time to 95 % of
/// the terminal velocity of every class, which for these Stokes-range grains (Re < 0.3) is the
/// Stokes τ ln 20 to within 15 % (Dallavalle's C_d is not exactly 24/Re).
#[test]
fn the_transient_reaches_the_terminal_velocity_in_about_tau_ln_20() {
    let texts = assert_readable_chart(
        &out().join("transient.svg"),
        "velocity from rest in the clear fluid",
        &[
            "time since release, log scale (ms)",
            "velocity / terminal velocity v/v_t (-)",
        ],
    );
    assert_eq!(texts.iter().filter(|x| x.starts_with("d = ")).count(), 6);
    assert_readable_chart(
        &out().join("terminal_time.svg"),
        "time to reach the terminal velocity",
        &[
            "diameter, log scale (µm)",
            "time to 95 or 99 % of the terminal velocity, log scale (ms)",
        ],
    );
    assert!(svg_texts(&out().join("terminal_time.svg"))
        .iter()
        .any(|t| t.starts_with("seed 000 Table 1 t_tr")));
    let table1 = read_csv_records(&out().join("terminal_time_table1.csv"));
    assert_eq!(table1.len(), 6, "the six diameters of seed 000 Table 1");
    let rows = read_csv_records(&out().join("terminal_time.csv"));
    assert!(rows.len() > 100, "every class: {}", rows.len());
    for r in &rows {
        let ratio = num(r, "t95_s") / num(r, "t95_stokes_s");
        assert!((0.85..1.15).contains(&ratio), "{r:?}");
        let ratio = num(r, "t99_s") / num(r, "t99_stokes_s");
        assert!((0.85..1.15).contains(&ratio), "{r:?}");
        assert!(num(r, "reynolds") < 0.3, "{r:?}");
    }
    let curves = read_csv_records(&out().join("transient.csv"));
    assert_eq!(curves.len(), 6 * 41);
    for c in curves.chunks(41) {
        let last = num(&c[40], "velocity_fraction");
        assert!((last - 1.0).abs() < 1e-3, "at 10 τ: {last}");
        assert!(c
            .windows(2)
            .all(|w| num(&w[1], "velocity_m_s") >= num(&w[0], "velocity_m_s")));
    }
}

#[test]
fn every_svg_of_the_run_is_a_chart_with_units() {
    let svgs: Vec<PathBuf> = std::fs::read_dir(out())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "svg"))
        .collect();
    assert_eq!(svgs.len(), 12, "{svgs:?}");
    for p in svgs {
        assert!(svg_texts(&p).len() > 5, "{}", p.display());
    }
}
