//! Reading and checking a readings file (the format of `docs/commands/reduce.md`): the test's
//! figures from its `# key = value` lines, its readings from the table. Every refusal is one
//! [`Error::BadInput`] naming the file, the key or the row and column (1-based), and what is
//! allowed.

use super::Request;
use crate::error::Error;
use crate::instruments::reduction::d7928::MeasuredHydrometer;
use crate::instruments::reduction::{HydrometerType, LabReading, Standard, TestSetup};
use crate::io::num;
use std::collections::BTreeMap;
use std::path::Path;

/// Keys of the `# key = value` lines: the test's figures.
const FIGURE_KEYS: [&str; 14] = [
    "standard",
    "hydrometer",
    "dry_mass_g",
    "specific_gravity",
    "meniscus_correction",
    "blank_reading",
    "suspension_volume_ml",
    "h_r1_cm",
    "h_r2_cm",
    "r1",
    "r2",
    "bulb_volume_ml",
    "cylinder_area_cm2",
    "cylinder_diameter_cm",
];
/// Keys of free text a laboratory may add (kept in reduce.toml, not used).
const TEXT_KEYS: [&str; 6] = ["sample", "source", "date", "operator", "note", "dispersant"];
/// The D7928-only keys (the hydrometer's measured dimensions).
const D7928_KEYS: [&str; 7] = [
    "h_r1_cm",
    "h_r2_cm",
    "r1",
    "r2",
    "bulb_volume_ml",
    "cylinder_area_cm2",
    "cylinder_diameter_cm",
];
/// The columns a readings file may have.
const COLUMNS: [&str; 5] = [
    "time_s",
    "time_min",
    "reading",
    "temperature_c",
    "blank_reading",
];

/// A readings file split into its figures (key → (value, line)) and its table.
struct Parsed {
    figures: BTreeMap<String, (String, usize)>,
    header: Vec<String>,
    /// (line number, fields).
    rows: Vec<(usize, Vec<String>)>,
}

fn bad(file: &Path, msg: String) -> Error {
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
fn figure(
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

fn required(file: &Path, key: &str, x: Option<f64>, what: &str) -> Result<f64, Error> {
    x.ok_or_else(|| {
        Error::bad_input(
            file,
            Some(key),
            format!("missing: add the line `# {key} = …` ({what})"),
        )
    })
}

/// The standard and the hydrometer: the command line's, else the file's.
fn kinds(file: &Path, p: &Parsed, req: &Request) -> Result<(Standard, HydrometerType), Error> {
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
fn choice<T>(
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

/// The hydrometer's measured dimensions (D7928), in SI.
fn measured(file: &Path, p: &Parsed, h: HydrometerType) -> Result<MeasuredHydrometer, Error> {
    let len = (0.1, 100.0);
    let (s0, s1) = h.scale();
    let r1 = figure(file, p, "r1", (s0, s1), "a reading on the scale")?.unwrap_or(s0);
    let r2 = figure(file, p, "r2", (s0, s1), "a reading on the scale")?.unwrap_or(s1);
    let cm = "a length of 0.1–100 cm";
    let h1 = required(
        file,
        "h_r1_cm",
        figure(file, p, "h_r1_cm", len, cm)?,
        "D7928: distance from the bulb's centre of volume to the mark r1, cm",
    )?;
    let h2 = required(
        file,
        "h_r2_cm",
        figure(file, p, "h_r2_cm", len, cm)?,
        "D7928: distance from the bulb's centre of volume to the mark r2, cm",
    )?;
    let vb = required(
        file,
        "bulb_volume_ml",
        figure(file, p, "bulb_volume_ml", (1.0, 1000.0), "1–1000 mL")?,
        "D7928: the bulb's volume, mL",
    )?;
    let area = figure(file, p, "cylinder_area_cm2", (1.0, 1000.0), "1–1000 cm²")?;
    let diameter = figure(file, p, "cylinder_diameter_cm", len, cm)?;
    let area_cm2 = match (area, diameter) {
        (Some(a), None) => a,
        (None, Some(d)) => std::f64::consts::PI * d * d / 4.0,
        (Some(_), Some(_)) => {
            return Err(Error::bad_input(
                file,
                Some("cylinder_diameter_cm"),
                "give cylinder_area_cm2 or cylinder_diameter_cm, not both",
            ))
        }
        (None, None) => {
            return Err(Error::bad_input(
                file,
                Some("cylinder_area_cm2"),
                "missing: add `# cylinder_area_cm2 = …` or `# cylinder_diameter_cm = …` \
                 (D7928: the sedimentation cylinder's inside section)",
            ))
        }
    };
    if !(r1 < r2 && h1 > h2) {
        return Err(Error::bad_input(
            file,
            Some("h_r1_cm"),
            format!(
                "the mark r1 = {r1} must be above the mark r2 = {r2} on the stem: r1 < r2 and \
                 h_r1_cm ({h1}) > h_r2_cm ({h2})"
            ),
        ));
    }
    Ok(MeasuredHydrometer {
        h_r1_m: h1 * 1e-2,
        h_r2_m: h2 * 1e-2,
        r1,
        r2,
        bulb_volume_m3: vb * 1e-6,
        cylinder_area_m2: area_cm2 * 1e-4,
    })
}

/// The test's figures of a readings file.
fn setup(file: &Path, p: &Parsed, req: &Request) -> Result<(TestSetup, Option<f64>), Error> {
    let (standard, h) = kinds(file, p, req)?;
    let mass = required(
        file,
        "dry_mass_g",
        figure(file, p, "dry_mass_g", (1e-3, 1e4), "0.001–10000 g")?,
        "the oven-dry mass of the specimen in suspension, g",
    )?;
    let gs = required(
        file,
        "specific_gravity",
        figure(file, p, "specific_gravity", (1.5, 5.0), "1.5–5")?,
        "G_s of the soil solids",
    )?;
    let (s0, s1) = h.scale();
    let cm_max = 0.1 * (s1 - s0);
    let cm = required(
        file,
        "meniscus_correction",
        figure(
            file,
            p,
            "meniscus_correction",
            (0.0, cm_max),
            &format!(
                "0–{} {} (0 if read at the liquid level)",
                num(cm_max),
                h.unit()
            ),
        )?,
        "reading at the liquid level minus reading at the top of the meniscus",
    )?;
    let volume = figure(
        file,
        p,
        "suspension_volume_ml",
        (100.0, 1e4),
        "100–10000 mL",
    )?
    .unwrap_or(1000.0);
    let blank = figure(file, p, "blank_reading", (s0, s1), &scale_text(h))?;
    let measured = match standard {
        Standard::D7928 => Some(measured(file, p, h)?),
        Standard::D422 => {
            if let Some(k) = D7928_KEYS.iter().find(|k| p.figures.contains_key(**k)) {
                return Err(Error::bad_input(
                    file,
                    Some(k),
                    "used by d7928 only (D422 takes the effective depth from its Table 2): \
                     remove it or reduce with --standard d7928",
                ));
            }
            None
        }
    };
    let s = TestSetup {
        standard,
        hydrometer: h,
        dry_mass_kg: mass * 1e-3,
        specific_gravity: gs,
        meniscus_correction: cm,
        suspension_volume_m3: volume * 1e-6,
        measured,
    };
    Ok((s, blank))
}

fn scale_text(h: HydrometerType) -> String {
    let (a, b) = h.scale();
    format!(
        "{} to {} {} (the {}'s scale)",
        num(a),
        num(b),
        h.unit(),
        h.name()
    )
}

/// Reads and checks a readings file: the test's figures and its readings.
pub fn read(file: &Path, req: &Request) -> Result<(TestSetup, Vec<LabReading>), Error> {
    let text = std::fs::read_to_string(file).map_err(|e| Error::Io(file.to_path_buf(), e))?;
    // A spreadsheet's UTF-8 byte-order mark is not part of the first key or column name.
    let p = split(file, text.trim_start_matches('\u{feff}'))?;
    let (s, blank) = setup(file, &p, req)?;
    let readings = rows(file, &p, &s, blank)?;
    Ok((s, readings))
}

/// The column index of each known column; refuses unknown, duplicate and missing ones.
fn columns(file: &Path, header: &[String]) -> Result<BTreeMap<&'static str, usize>, Error> {
    let mut at = BTreeMap::new();
    for (j, h) in header.iter().enumerate() {
        let Some(c) = COLUMNS.iter().find(|c| **c == h.as_str()) else {
            return Err(bad(
                file,
                format!(
                    "header, column {}: unknown column `{h}`; allowed: {}",
                    j + 1,
                    COLUMNS.join(", ")
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
    for c in ["reading", "temperature_c"] {
        if !at.contains_key(c) {
            return Err(bad(file, format!("header: missing column `{c}`")));
        }
    }
    Ok(at)
}

/// The readings of the table, each value checked.
fn rows(
    file: &Path,
    p: &Parsed,
    s: &TestSetup,
    blank: Option<f64>,
) -> Result<Vec<LabReading>, Error> {
    let at = columns(file, &p.header)?;
    match (blank, at.contains_key("blank_reading")) {
        (Some(_), true) => {
            return Err(Error::bad_input(
                file,
                Some("blank_reading"),
                "given both as a column and as a `# blank_reading` line: keep one",
            ))
        }
        (None, false) => {
            return Err(Error::bad_input(
                file,
                Some("blank_reading"),
                "missing: add a `blank_reading` column (the companion cylinder's reading at each \
                 reading, D7928) or a line `# blank_reading = …` (the control cylinder's reading, \
                 D422's composite correction plus the scale's zero)",
            ))
        }
        _ => {}
    }
    if p.rows.is_empty() {
        return Err(bad(
            file,
            "no readings: the table has a header but no rows".into(),
        ));
    }
    let (t0, t1) = s.standard.temperature_range_c();
    let (s0, s1) = s.hydrometer.scale();
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
        let value = |c: &str, lo: f64, hi: f64, allowed: &str| -> Result<f64, Error> {
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
            value("time_s", 1e-9, 1e7, "a time > 0 s")?
        } else {
            60.0 * value("time_min", 1e-9, 1e6, "a time > 0 min")?
        };
        let scale = scale_text(s.hydrometer);
        let reading = value("reading", s0, s1, &scale)?;
        let temp = value(
            "temperature_c",
            t0,
            t1,
            &format!("{t0}–{t1} °C for {}", s.standard.name()),
        )?;
        let blank_reading = match blank {
            Some(b) => b,
            None => value("blank_reading", s0, s1, &scale)?,
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
