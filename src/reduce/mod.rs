//! `settle reduce READINGS.csv`: the standard data reduction of laboratory hydrometer readings
//! (ASTM D422 or D7928), pipette draws and buoyancy-sphere weighings (seed 000 eqs. 16–18, 22;
//! `# instrument = pipette | buoyancy-sphere`, [`crate::instruments::reduction`]) into
//! `OUT/<stem>_reduced/`: `percent_finer.csv`, `percent_finer.svg` and `reduce.toml`.
//! [`read`] is the one entry point that reads a readings file, for every instrument
//! (`settle invert` reads through it too).
//!
//! # The readings file
//!
//! A plain CSV (no quoted fields) whose first lines are the test's figures as `# key = value`
//! comments, then a header and one row per reading (see `docs/commands/reduce.md`):
//!
//! ```text
//! # standard = d7928
//! # hydrometer = 152H
//! # dry_mass_g = 50.0
//! # specific_gravity = 2.70
//! # meniscus_correction = 1.0
//! # h_r1_cm = 20.3
//! # h_r2_cm = 8.6
//! # bulb_volume_ml = 55
//! # cylinder_area_cm2 = 27.8
//! time_min,reading,temperature_c,blank_reading
//! 1,45.5,21.5,6.0
//! ```
//!
//! Every bad input (a missing or unknown key or column, a value out of range, a reading off the
//! hydrometer's scale, times not strictly increasing, a temperature outside the standard's range)
//! is one error naming the file, the key or the row and column (1-based), and what is allowed;
//! exit 2, nothing written.

mod figures;
mod input;
mod instrument;

pub use input::read;

use crate::error::Error;
use crate::instruments::reduction::{
    reduce, Instrument, LabReading, PipetteRegion, Reduced, TestSetup,
};
use crate::io::chart::{scatter_svg, Scale, Series};
use crate::io::fmt::{clean, sig_plain};
use crate::io::{self, StagedDir};
use std::path::{Path, PathBuf};

/// What `settle reduce` is asked to do.
#[derive(Clone, Debug, Default)]
pub struct Request {
    /// The readings file.
    pub file: PathBuf,
    /// `--standard`, overriding the file's `standard`.
    pub standard: Option<String>,
    /// `--hydrometer`, overriding the file's `hydrometer`.
    pub hydrometer: Option<String>,
    /// Output folder; results go to `out_dir/<stem>_reduced/`.
    pub out_dir: PathBuf,
}

/// What a reduction produced.
#[derive(Clone, Debug)]
pub struct Report {
    /// The results folder.
    pub out: PathBuf,
    /// The test's figures as read.
    pub setup: TestSetup,
    /// Every reading reduced.
    pub reduced: Vec<Reduced>,
    /// Console summary, one line each.
    pub lines: Vec<String>,
    /// Validity warnings (percent finer outside 0–100 %).
    pub warnings: Vec<String>,
}

/// Runs `settle reduce`: reads, checks, reduces and writes `OUT/<stem>_reduced/`.
pub fn run(req: &Request) -> Result<Report, Error> {
    let file = &req.file;
    let (setup, readings) = read(file, req)?;
    let stem = file
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "readings".into());
    let name = format!("{stem}_reduced");
    let dest = req.out_dir.join(&name);
    if io::check_destination(&dest).is_err() {
        return Err(Error::bad_argument(
            "--out",
            &dest,
            "exists and was not created by settle (no .settle-run marker), so settle will not \
             replace it: choose another --out",
        ));
    }
    let reduced = reduce(&setup, &readings);
    let ioe = |e: std::io::Error| Error::Io(dest.clone(), e);
    let stage = StagedDir::new(&req.out_dir, &name).map_err(ioe)?;
    write_csv(&stage.path("percent_finer.csv"), &reduced).map_err(ioe)?;
    write_chart(&stage.path("percent_finer.svg"), &stem, &setup, &reduced).map_err(ioe)?;
    let record = record(file, &setup, &readings);
    io::write_atomic(&stage.path("reduce.toml"), record.as_bytes()).map_err(ioe)?;
    let out = stage.commit().map_err(ioe)?;
    let warnings = reduced
        .iter()
        .filter(|r| !(0.0..=100.0).contains(&r.percent_finer))
        .map(|r| {
            format!(
                "percent finer {} % at t = {} min is outside 0–100 %: check dry_mass_g, \
                 specific_gravity and the blank reading",
                sig_plain(r.percent_finer, 3),
                sig_plain(r.reading.time_s / 60.0, 4)
            )
        })
        .collect();
    let lines = summary(file, &out, &setup, &reduced);
    Ok(Report {
        out,
        setup,
        reduced,
        lines,
        warnings,
    })
}

/// How the readings were reduced, for the console and the chart: `ASTM D7928, 152H`,
/// `pipette, seed 000 eq. 17`, `buoyancy sphere, seed 000 eq. 22`.
pub fn method(s: &TestSetup) -> String {
    match s.instrument {
        Instrument::Hydrometer(h) => {
            format!("ASTM {}, {}", s.standard.name().to_uppercase(), h.name())
        }
        Instrument::Pipette { .. } => "pipette, seed 000 eq. 17".into(),
        Instrument::BuoyancySphere { .. } => "buoyancy sphere, seed 000 eq. 22".into(),
    }
}

fn summary(file: &Path, out: &Path, s: &TestSetup, red: &[Reduced]) -> Vec<String> {
    let mut lines = vec![format!(
        "{} ({}, {} readings) -> {}",
        file.display(),
        method(s),
        red.len(),
        out.display()
    )];
    let reading = match s.instrument {
        Instrument::Hydrometer(_) => "reading",
        Instrument::Pipette { .. } => "drawn_g",
        Instrument::BuoyancySphere { .. } => "app_g",
    };
    lines.push(format!(
        "  {:>9} {:>8} {:>6} {:>7} {:>8} {:>8} {:>8}",
        "t_min", reading, "blank", "T_C", "depth_cm", "d_um", "finer_%"
    ));
    for r in red {
        let x = &r.reading;
        lines.push(format!(
            "  {:>9} {:>8} {:>6} {:>7} {:>8} {:>8} {:>8}",
            sig_plain(x.time_s / 60.0, 4),
            sig_plain(x.reading, 4),
            sig_plain(x.blank_reading, 4),
            sig_plain(x.temperature_c, 3),
            sig_plain(r.effective_depth_m * 100.0, 3),
            sig_plain(r.diameter_m * 1e6, 3),
            sig_plain(r.percent_finer, 3)
        ));
    }
    lines
}

fn write_csv(path: &Path, red: &[Reduced]) -> std::io::Result<()> {
    let rows: Vec<Vec<String>> = red
        .iter()
        .map(|r| {
            let x = &r.reading;
            vec![
                clean(x.time_s),
                clean(x.time_s / 60.0),
                clean(x.reading),
                clean(x.blank_reading),
                clean(r.net_reading),
                clean(x.temperature_c),
                clean(r.viscosity_pa_s),
                clean(r.effective_depth_m),
                clean(r.diameter_m),
                clean(r.percent_finer),
            ]
        })
        .collect();
    io::write_csv(
        path,
        &[
            "time_s",
            "time_min",
            "reading",
            "blank_reading",
            "net_reading",
            "temperature_c",
            "viscosity_pa_s",
            "effective_depth_m",
            "diameter_m",
            "percent_finer",
        ],
        &rows,
    )
}

fn write_chart(path: &Path, stem: &str, s: &TestSetup, red: &[Reduced]) -> std::io::Result<()> {
    let points = red
        .iter()
        .map(|r| (r.diameter_m * 1e6, r.percent_finer))
        .collect();
    scatter_svg(
        path,
        &format!("{stem}: percent finer ({})", method(s)),
        "particle diameter [µm]",
        "percent finer [%]",
        Scale::Log,
        Scale::Linear,
        &[Series::sorted_line(
            match s.instrument {
                Instrument::Hydrometer(_) => {
                    format!("{} reduction", s.standard.name().to_uppercase())
                }
                _ => format!("{} reduction", s.instrument.name()),
            },
            points,
            0,
        )],
    )
}

/// reduce.toml: what was reduced, how, by which settle.
fn record(file: &Path, s: &TestSetup, readings: &[LabReading]) -> String {
    let mut t = format!(
        "# written by settle reduce\n[reduce]\nsettle_version = \"{}\"\ninput = {:?}\n\
         instrument = \"{}\"\n",
        env!("CARGO_PKG_VERSION"),
        file.display().to_string(),
        s.instrument.name(),
    );
    if let Instrument::Hydrometer(h) = s.instrument {
        t.push_str(&format!(
            "standard = \"{}\"\nhydrometer = \"{}\"\n",
            s.standard.name(),
            h.name()
        ));
    }
    t.push_str(&format!(
        "readings = {}\ndry_mass_g = {}\nspecific_gravity = {}\n",
        readings.len(),
        clean(s.dry_mass_kg * 1e3),
        clean(s.specific_gravity),
    ));
    if let Instrument::Hydrometer(_) = s.instrument {
        t.push_str(&format!(
            "meniscus_correction = {}\n",
            clean(s.meniscus_correction)
        ));
    }
    t.push_str(&format!(
        "suspension_volume_ml = {}\n",
        clean(s.suspension_volume_m3 * 1e6)
    ));
    t.push_str(&instrument_record(s));
    if let Some(m) = &s.measured {
        t.push_str(&format!(
            "\n[d7928]\nh_r1_cm = {}\nh_r2_cm = {}\nr1 = {}\nr2 = {}\nbulb_volume_ml = {}\n\
             cylinder_area_cm2 = {}\n",
            clean(m.h_r1_m * 1e2),
            clean(m.h_r2_m * 1e2),
            clean(m.r1),
            clean(m.r2),
            clean(m.bulb_volume_m3 * 1e6),
            clean(m.cylinder_area_m2 * 1e4)
        ));
    }
    t
}

/// reduce.toml's `[pipette]` or `[sphere]` table and the `[model]` figures given.
fn instrument_record(s: &TestSetup) -> String {
    let mut t = String::new();
    match s.instrument {
        Instrument::Hydrometer(_) => {}
        Instrument::Pipette {
            volume_m3,
            depth_m,
            region,
        } => {
            t.push_str(&format!(
                "\n[pipette]\npipette_volume_ml = {}\npipette_depth_cm = {}\n",
                clean(volume_m3 * 1e6),
                clean(depth_m * 1e2)
            ));
            match region {
                PipetteRegion::Sphere => t.push_str("pipette_region = \"sphere\"\n"),
                PipetteRegion::Disc { radius_m } => t.push_str(&format!(
                    "pipette_region = \"disc\"\npipette_radius_cm = {}\n",
                    clean(radius_m * 1e2)
                )),
            }
        }
        Instrument::BuoyancySphere {
            diameter_m,
            mass_kg,
            depth_m,
        } => t.push_str(&format!(
            "\n[sphere]\nsphere_diameter_mm = {}\nsphere_mass_g = {}\nsphere_depth_cm = {}\n",
            clean(diameter_m * 1e3),
            clean(mass_kg * 1e3),
            clean(depth_m * 1e2)
        )),
    }
    let m = &s.model;
    let given: Vec<String> = [
        ("fluid_density_kg_m3", m.fluid_density_kg_m3, 1.0),
        ("gravity_m_s2", m.gravity_m_s2, 1.0),
        ("column_height_cm", m.column_height_m, 1e2),
        ("hydrometer_bulb_length_cm", m.hydrometer_bulb_length_m, 1e2),
    ]
    .iter()
    .filter_map(|(k, v, f)| v.map(|v| format!("{k} = {}\n", clean(v * f))))
    .collect();
    if !given.is_empty() {
        t.push_str("\n[model]\n");
        t.push_str(&given.concat());
    }
    t
}
