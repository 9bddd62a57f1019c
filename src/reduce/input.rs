//! Reading and checking a readings file (the format of `docs/commands/reduce.md`): the test's
//! figures from its `# key = value` lines, its readings from the table. Every refusal is one
//! [`Error::BadInput`] naming the file, the key or the row and column (1-based), and what is
//! allowed.

use super::instrument::{setup, RowRules};
use super::Request;
use crate::error::Error;
use crate::instruments::reduction::{HydrometerType, LabReading, Standard, TestSetup};
use crate::io::num;
use std::collections::BTreeMap;
use std::path::Path;

/// Keys of the `# key = value` lines: the test's figures (every instrument's; which apply to
/// which instrument: [`super::instrument`]).
pub(super) const FIGURE_KEYS: [&str; 27] = [
    "instrument",
    "standard",
    "hydrometer",
    "dry_mass_g",
    "specific_gravity",
    "meniscus_correction",
    "blank_reading",
    "suspension_volume_ml",
    "temperature_c",
    "h_r1_cm",
    "h_r2_cm",
    "r1",
    "r2",
    "bulb_volume_ml",
    "cylinder_area_cm2",
    "cylinder_diameter_cm",
    "hydrometer_bulb_length_cm",
    "pipette_volume_ml",
    "pipette_depth_cm",
    "pipette_region",
    "pipette_radius_cm",
    "sphere_diameter_mm",
    "sphere_mass_g",
    "sphere_depth_cm",
    "fluid_density_kg_m3",
    "gravity_m_s2",
    "column_height_cm",
];
/// Keys of free text a laboratory may add (kept in reduce.toml, not used).
const TEXT_KEYS: [&str; 6] = ["sample", "source", "date", "operator", "note", "dispersant"];
/// The columns a readings file may have (which apply to which instrument: [`columns`]).
const COLUMNS: [&str; 7] = [
    "time_s",
    "time_min",
    "reading",
    "drawn_mass_g",
    "apparent_mass_g",
    "temperature_c",
    "blank_reading",
];

/// A readings file split into its figures (key → (value, line)) and its table.
pub(super) struct Parsed {
    pub(super) figures: BTreeMap<String, (String, usize)>,
    pub(super) header: Vec<String>,
    /// (line number, fields).
    pub(super) rows: Vec<(usize, Vec<String>)>,
}

pub(super) fn bad(file: &Path, msg: String) -> Error {
    Error::bad_input(file, None, msg)
}

/// Splits the text of a readings file; refuses duplicate or unknown keys and a missing header.
fn split(file: &Path, text: &str) -> Result<Parsed, Error> {
    let mut figures = BTreeMap::new();
    let mut header: Option<Vec<String>> = None;
    let mut rows = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let l = raw.trim();
        if l.is_empty() {
            continue;
        }
        if let Some(c) = l.strip_prefix('#') {
            let Some((k, v)) = c.split_once('=').filter(|_| header.is_none()) else {
                continue;
            };
            let k = k.trim().to_string();
            if !FIGURE_KEYS.contains(&k.as_str()) && !TEXT_KEYS.contains(&k.as_str()) {
                return Err(Error::bad_input(
                    file,
                    Some(&k),
                    format!(
                        "line {line}: unknown key; allowed: {}, and the free text {}",
                        FIGURE_KEYS.join(", "),
                        TEXT_KEYS.join(", ")
                    ),
                ));
            }
            if let Some((_, first)) = figures.insert(k.clone(), (v.trim().to_string(), line)) {
                return Err(Error::bad_input(
                    file,
                    Some(&k),
                    format!("line {line}: given twice (first on line {first})"),
                ));
            }
            continue;
        }
        let fields: Vec<String> = l.split(',').map(|f| f.trim().to_string()).collect();
        match &header {
            None => header = Some(fields),
            Some(_) => rows.push((line, fields)),
        }
    }
    let header = header.ok_or_else(|| {
        bad(
            file,
            "no header line: expected `time_min,reading,temperature_c[,blank_reading]` (or \
             time_s) after the `# key = value` lines"
                .into(),
        )
    })?;
    Ok(Parsed {
        figures,
        header,
        rows,
    })
}

/// The figure `key` as a number within [lo, hi] (`unit` for the message), None if absent.
pub(super) fn figure(
    file: &Path,
    p: &Parsed,
    key: &str,
    (lo, hi): (f64, f64),
    allowed: &str,
) -> Result<Option<f64>, Error> {
    let Some((v, line)) = p.figures.get(key) else {
        return Ok(None);
    };
    let x: f64 = v.parse().map_err(|_| {
        Error::bad_input(
            file,
            Some(key),
            format!("line {line}: `{v}` is not a number; allowed: {allowed}"),
        )
    })?;
    if !(x.is_finite() && x >= lo && x <= hi) {
        return Err(Error::bad_input(
            file,
            Some(key),
            format!("line {line}: {v} is out of range; allowed: {allowed}"),
        ));
    }
    Ok(Some(x))
}

pub(super) fn required(file: &Path, key: &str, x: Option<f64>, what: &str) -> Result<f64, Error> {
    x.ok_or_else(|| {
        Error::bad_input(
            file,
            Some(key),
            format!("missing: add the line `# {key} = …` ({what})"),
        )
    })
}

/// The standard and the hydrometer: the command line's, else the file's.
pub(super) fn kinds(
    file: &Path,
    p: &Parsed,
    req: &Request,
) -> Result<(Standard, HydrometerType), Error> {
    let standard = choice(
        file,
        p,
        &req.standard,
        ("standard", "d422, d7928", "d7928"),
        Standard::parse,
    )?;
    let hydrometer = choice(
        file,
        p,
        &req.hydrometer,
        ("hydrometer", "152H, 151H", "152H"),
        HydrometerType::parse,
    )?;
    Ok((standard, hydrometer))
}

/// One of the test's named choices (`standard`, `hydrometer`): the command-line option wins
/// over the file's `# key = value` line; missing or unknown is bad input naming where it came
/// from, the `allowed` values and an `example`.
pub(super) fn choice<T>(
    file: &Path,
    p: &Parsed,
    option: &Option<String>,
    (key, allowed, example): (&str, &str, &str),
    parse: impl Fn(&str) -> Option<T>,
) -> Result<T, Error> {
    let given = option.clone().map(|v| (v, format!("--{key}"))).or_else(|| {
        p.figures
            .get(key)
            .map(|(v, l)| (v.clone(), format!("line {l}")))
    });
    let Some((v, at)) = given else {
        return Err(Error::bad_input(
            file,
            Some(key),
            format!(
                "missing: give --{key} {} or the line `# {key} = {example}`",
                allowed.replace(", ", "|")
            ),
        ));
    };
    parse(&v).ok_or_else(|| {
        Error::bad_input(
            file,
            Some(key),
            format!("{at}: unknown {key} `{v}`; allowed: {allowed}"),
        )
    })
}

/// Reads and checks a readings file: the test's figures and its readings.
pub fn read(file: &Path, req: &Request) -> Result<(TestSetup, Vec<LabReading>), Error> {
    let text = std::fs::read_to_string(file).map_err(|e| Error::Io(file.to_path_buf(), e))?;
    // A spreadsheet's UTF-8 byte-order mark is not part of the first key or column name.
    let p = split(file, text.trim_start_matches('\u{feff}'))?;
    let (s, rules) = setup(file, &p, req)?;
    let readings = rows(file, &p, &rules)?;
    Ok((s, readings))
}

/// The column index of each known column; refuses unknown, duplicate and missing ones, and
/// the reading columns of other instruments (`reading` is the instrument's own, `optional`
/// the columns it may have besides the time and the reading).
fn columns(
    file: &Path,
    header: &[String],
    reading: &str,
    optional: &[&str],
) -> Result<BTreeMap<&'static str, usize>, Error> {
    let mut at = BTreeMap::new();
    let allowed: Vec<&str> = ["time_min", "time_s", reading]
        .into_iter()
        .chain(optional.iter().copied())
        .collect();
    for (j, h) in header.iter().enumerate() {
        let c = COLUMNS
            .iter()
            .find(|c| **c == h.as_str() && allowed.contains(c));
        let Some(c) = c else {
            let other = if COLUMNS.contains(&h.as_str()) {
                format!("column `{h}` is not one of this instrument's")
            } else {
                format!("unknown column `{h}`")
            };
            return Err(bad(
                file,
                format!(
                    "header, column {}: {other}; allowed: {}",
                    j + 1,
                    allowed.join(", ")
                ),
            ));
        };
        if at.insert(*c, j).is_some() {
            return Err(bad(
                file,
                format!("header, column {}: `{h}` given twice", j + 1),
            ));
        }
    }
    if at.contains_key("time_s") == at.contains_key("time_min") {
        return Err(bad(
            file,
            "header: give one time column, time_min or time_s".into(),
        ));
    }
    if !at.contains_key(reading) {
        return Err(bad(file, format!("header: missing column `{reading}`")));
    }
    Ok(at)
}

/// The readings of the table, each value checked by `rules`.
fn rows(file: &Path, p: &Parsed, rules: &RowRules) -> Result<Vec<LabReading>, Error> {
    let at = columns(file, &p.header, rules.reading, &rules.optional_columns())?;
    let (temperature, blank) = rules.check_columns(file, &at)?;
    if p.rows.is_empty() {
        return Err(bad(
            file,
            "no readings: the table has a header but no rows".into(),
        ));
    }
    let mut out: Vec<LabReading> = Vec::new();
    for (n, (line, fields)) in p.rows.iter().enumerate() {
        let row = n + 1;
        if fields.len() != p.header.len() {
            return Err(bad(
                file,
                format!(
                    "row {row} (line {line}): {} fields, the header has {}",
                    fields.len(),
                    p.header.len()
                ),
            ));
        }
        let value = |c: &str, (lo, hi): (f64, f64), allowed: &str| -> Result<f64, Error> {
            let j = at[c];
            let v = &fields[j];
            let where_ = format!("row {row} (line {line}), column {} `{c}`", j + 1);
            let x: f64 = v.parse().map_err(|_| {
                bad(
                    file,
                    format!("{where_}: `{v}` is not a number; allowed: {allowed}"),
                )
            })?;
            if !(x.is_finite() && x >= lo && x <= hi) {
                return Err(bad(
                    file,
                    format!("{where_}: {v} is out of range; allowed: {allowed}"),
                ));
            }
            Ok(x)
        };
        let time_s = if at.contains_key("time_s") {
            value("time_s", (1e-9, 1e7), "a time > 0 s")?
        } else {
            60.0 * value("time_min", (1e-9, 1e6), "a time > 0 min")?
        };
        let reading = value(rules.reading, rules.range, &rules.allowed)?;
        let temp = match temperature {
            Some(t) => t,
            None => value(
                "temperature_c",
                rules.temperature_range,
                &rules.temperature_text,
            )?,
        };
        let blank_reading = match blank {
            Some(b) => b,
            None => value("blank_reading", rules.blank_range, &rules.blank_allowed)?,
        };
        if let Some(prev) = out.last().filter(|prev| time_s <= prev.time_s) {
            let c = if at.contains_key("time_s") {
                "time_s"
            } else {
                "time_min"
            };
            return Err(bad(
                file,
                format!(
                    "row {row} (line {line}), column {} `{c}`: {} is not after the previous \
                     reading's {}; times must increase strictly",
                    at[c] + 1,
                    fields[at[c]],
                    if c == "time_s" {
                        num(prev.time_s)
                    } else {
                        num(prev.time_s / 60.0)
                    }
                ),
            ));
        }
        out.push(LabReading {
            time_s,
            reading,
            temperature_c: temp,
            blank_reading,
        });
    }
    Ok(out)
}
