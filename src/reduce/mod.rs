//! `settle reduce READINGS.csv`: the standard data reduction of laboratory hydrometer readings
//! (ASTM D422 or D7928), pipette draws and buoyancy-sphere weighings (seed 000 eqs. 16–18, 22;
//! `# instrument = pipette | buoyancy-sphere`, [`crate::instruments::reduction`]) into
//! `OUT/<stem>_reduced/`: `percent_finer.csv` (also as `.xlsx` and as the AGS4 file
//! `percent_finer.ags`), `percent_finer.svg` and `reduce.toml`.
//! `read_checked` is the one place that reads readings, for every instrument (`settle invert`
//! reads through it too).
//!
//! # From Rust
//!
//! [`reduce`] runs the command in memory: the readings as a file or as a table
//! ([`Readings`]), the options of the command line ([`ReduceOptions`], its defaults those of
//! `settle reduce`); it returns a [`ReduceResult`] with every table, the chart as SVG text and
//! the typed figures, and [`ReduceResult::write`] writes the folder the command writes.
//!
//! ```no_run
//! use settle::Table;
//! use settle::reduce::{reduce, Readings, ReduceOptions};
//! let mut t = Table::new("soil_a.csv", ["time_min", "reading", "temperature_c"]);
//! t.push(vec!["1".into(), "45.5".into(), "21.5".into()]);
//! let figures = [("standard", "d422"), ("hydrometer", "152H"), ("dry_mass_g", "50"),
//!     ("specific_gravity", "2.7"), ("meniscus_correction", "1"), ("blank_reading", "6")];
//! let r = reduce(Readings::table(figures, t), &ReduceOptions::default())?;
//! println!("{:?}", r.table("percent_finer").unwrap().f64s("diameter_m"));
//! # Ok::<(), settle::Error>(())
//! ```
//!
//! # The readings file
//!
//! A CSV (or an `.xlsx` / `.ods` sheet laid out the same way, read by [`crate::io::lab_file`])
//! whose first lines are the test's figures as `# key = value`
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

mod ags;
mod checks;
mod figures;
mod input;
mod instrument;
mod template;

pub use crate::io::lab_file::{Detected, Format};
pub use figures::ReduceOptions;
pub(crate) use input::read_checked;
pub use input::Readings;
pub use template::template;

use crate::error::Error;
use crate::instruments::reduction::{
    reduce as reduce_readings, Instrument, LabReading, PipetteRegion, Reduced, TestSetup,
};
use crate::io::chart::{Chart, Scale, Series};
use crate::io::fmt::{clean, sig_plain};
use crate::io::{Outputs, Table};
use std::path::{Path, PathBuf};

/// What a reduction produced, in memory: the tables and files `settle reduce` writes
/// (`percent_finer.csv`, `.xlsx`, `.ags`, `percent_finer.svg`, `reduce.toml`) and the typed
/// figures.
#[derive(Clone, Debug)]
pub struct ReduceResult {
    /// The results folder's name, `<stem>_reduced`.
    pub name: String,
    /// The readings file (or the name of the table in memory).
    pub input: PathBuf,
    /// The test's figures as read.
    pub setup: TestSetup,
    /// Every reading reduced.
    pub reduced: Vec<Reduced>,
    /// Validity warnings: doubtful inputs (specific gravity, temperature, a virtual test's
    /// schedule), percent finer outside 0–100 %, diameters above the 75 µm sieve.
    pub warnings: Vec<String>,
    /// What the format layer detected in the readings file: format, sheet, encoding,
    /// delimiter, decimal mark (also in `reduce.toml`'s `[input]` table).
    pub detected: Detected,
    /// The tables and files of `OUT/<stem>_reduced/`.
    pub outputs: Outputs,
}

impl ReduceResult {
    /// The table of the file `name` (`percent_finer` or `percent_finer.csv`).
    pub fn table(&self, name: &str) -> Option<&Table> {
        self.outputs.get(name)
    }

    /// Writes `out_dir/<stem>_reduced/` as `settle reduce --out OUT_DIR` does (staged, then
    /// moved into place; refused when that folder exists and was not made by settle); returns
    /// the folder.
    pub fn write(&self, out_dir: impl AsRef<Path>) -> Result<PathBuf, Error> {
        self.outputs.write_folder(out_dir.as_ref(), &self.name)
    }

    /// The console summary of `settle reduce`, the results written to `out`.
    /// A file that is not a plain UTF-8, comma-separated CSV with decimal points gets a second
    /// line saying how it was read (`  read as: CSV, Windows-1252, semicolon-separated, …`).
    pub fn lines(&self, out: &Path) -> Vec<String> {
        let mut l = summary(&self.input, out, &self.setup, &self.reduced);
        if let Some(s) = read_as(&self.detected) {
            l.insert(1, s);
        }
        l
    }
}

/// `settle reduce` in memory: reads and checks the readings (a file or a table), reduces every
/// reading by the standard (or the instrument's equations) and makes the outputs. Bad input is
/// [`Error::BadInput`] naming the file (or table), the key or the row and column.
///
/// ```no_run
/// use settle::reduce::{reduce, ReduceOptions};
/// let r = reduce("lab/soil_a.csv", &ReduceOptions::default())?;
/// let finer = r.table("percent_finer").unwrap().f64s("percent_finer");
/// r.write("out")?; // out/soil_a_reduced/
/// # Ok::<(), settle::Error>(())
/// ```
pub fn reduce(readings: impl Into<Readings>, opts: &ReduceOptions) -> Result<ReduceResult, Error> {
    let readings = readings.into();
    let read = read_checked(&readings, opts)?;
    let (setup, lab) = (read.setup, read.readings);
    let file = readings.path();
    let stem = readings.stem();
    let reduced = reduce_readings(&setup, &lab);
    let ioe = |e: std::io::Error| Error::Io(file.clone(), e);
    let mut outputs = Outputs::new();
    let table = csv_table(&reduced);
    outputs.file(
        "percent_finer.xlsx",
        crate::io::xlsx::table_xlsx(&table).map_err(ioe)?,
    );
    outputs.file(
        "percent_finer.ags",
        ags::ags_text(&file.display().to_string(), &stem, &setup, &reduced),
    );
    outputs.table(table);
    outputs.file(
        "percent_finer.svg",
        chart(&stem, &setup, &reduced).map_err(ioe)?,
    );
    let mut warnings = read.warnings;
    warnings.extend(
        reduced
            .iter()
            .filter(|r| !(0.0..=100.0).contains(&r.percent_finer))
            .map(|r| {
                format!(
                    "percent finer {} % at t = {} min is outside 0–100 %: check dry_mass_g, \
                     specific_gravity and the blank reading",
                    sig_plain(r.percent_finer, 3),
                    sig_plain(r.reading.time_s / 60.0, 4)
                )
            }),
    );
    let diameters: Vec<f64> = reduced.iter().map(|r| r.diameter_m).collect();
    warnings.extend(checks::result_warnings(&diameters));
    outputs.file(
        "reduce.toml",
        record(&file, &setup, &lab) + &input_record(&read.detected, &warnings),
    );
    outputs.set_owner(crate::io::Owner::new("reduce", readings.owner_input()));
    Ok(ReduceResult {
        name: format!("{stem}_reduced"),
        input: file,
        setup,
        reduced,
        warnings,
        detected: read.detected,
        outputs,
    })
}

/// `  read as: …` for a file that is not a plain UTF-8 comma-separated CSV (None for one).
pub(crate) fn read_as(d: &Detected) -> Option<String> {
    let plain = d.format == crate::io::lab_file::Format::Csv
        && d.encoding.as_deref() == Some("UTF-8")
        && d.delimiter == Some(',')
        && d.decimal_mark == '.';
    (!plain).then(|| format!("  read as: {}", d.summary()))
}

/// reduce.toml's `[input]` table: what the format layer detected in the readings file, and
/// the warnings.
pub(crate) fn input_record(d: &Detected, warnings: &[String]) -> String {
    format!("\n[input]\n{}warnings = {:?}\n", d.toml(), warnings)
}

/// How the readings were reduced, for the console and the chart: `ASTM D7928, 152H`,
/// `pipette, seed 000 eq. 17`, `buoyancy sphere, seed 000 eq. 22`.
pub(crate) fn method(s: &TestSetup) -> String {
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

fn csv_table(red: &[Reduced]) -> Table {
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
    Table::with_rows(
        "percent_finer.csv",
        [
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
        rows,
    )
}

fn chart(stem: &str, s: &TestSetup, red: &[Reduced]) -> std::io::Result<String> {
    let points = red
        .iter()
        .map(|r| (r.diameter_m * 1e6, r.percent_finer))
        .collect();
    Chart::new(format!("{stem}: percent finer ({})", method(s)))
        .x("particle diameter [µm]", Scale::Log)
        .y("percent finer [%]", Scale::Linear)
        .series(Series::sorted_line(
            match s.instrument {
                Instrument::Hydrometer(_) => {
                    format!("{} reduction", s.standard.name().to_uppercase())
                }
                _ => format!("{} reduction", s.instrument.name()),
            },
            points,
            0,
        ))
        .svg_string()
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
