//! The `# key = value` lines of a readings file (the format of `docs/commands/reduce.md`): the
//! one list of the keys it may give, its split into figures and table, and the checked reading
//! of one figure or named choice. Below [`super::input`] (the table) and [`super::instrument`]
//! (which figures apply to which instrument), which both read the figures through it.

use crate::error::Error;
use crate::instruments::reduction::{HydrometerType, Standard};
use crate::io::fmt::sig_trim;
use crate::io::lab_file::{number_hint, Detected, LabFile, Loc};
use std::collections::BTreeMap;
use std::path::Path;

/// The options of `settle reduce` (and of the reduction `settle invert` makes of each file): the
/// standard and the hydrometer, overriding the readings' `# standard` and `# hydrometer` lines.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ReduceOptions {
    /// `--standard`: `d422` or `d7928` (None: the file's `# standard`).
    pub standard: Option<String>,
    /// `--hydrometer`: `152H` or `151H` (None: the file's `# hydrometer`).
    pub hydrometer: Option<String>,
}

/// The instrument that uses only the hydrometer's figures.
pub(super) const HYDROMETER: &str = "hydrometer";
/// The instrument that uses only the pipette's figures.
pub(super) const PIPETTE: &str = "pipette";
/// The instrument that uses only the buoyancy sphere's figures.
pub(super) const SPHERE: &str = "buoyancy-sphere";

/// The one list of the test's figures a readings file may give, in the order its error
/// message lists them: `(key, the only instrument that uses it (None: every instrument), whether
/// it is a D7928 dimension)`. The D7928 dimensions are the hydrometer's measured dimensions and
/// its cylinder, used by ASTM D7928 only.
const FIGURES: [(&str, Option<&str>, bool); 27] = [
    ("instrument", None, false),
    ("standard", Some(HYDROMETER), false),
    ("hydrometer", Some(HYDROMETER), false),
    ("dry_mass_g", None, false),
    ("specific_gravity", None, false),
    ("meniscus_correction", Some(HYDROMETER), false),
    ("blank_reading", None, false),
    ("suspension_volume_ml", None, false),
    ("temperature_c", None, false),
    ("h_r1_cm", Some(HYDROMETER), true),
    ("h_r2_cm", Some(HYDROMETER), true),
    ("r1", Some(HYDROMETER), true),
    ("r2", Some(HYDROMETER), true),
    ("bulb_volume_ml", Some(HYDROMETER), true),
    ("cylinder_area_cm2", None, true),
    ("cylinder_diameter_cm", None, true),
    ("hydrometer_bulb_length_cm", Some(HYDROMETER), false),
    ("pipette_volume_ml", Some(PIPETTE), false),
    ("pipette_depth_cm", Some(PIPETTE), false),
    ("pipette_region", Some(PIPETTE), false),
    ("pipette_radius_cm", Some(PIPETTE), false),
    ("sphere_diameter_mm", Some(SPHERE), false),
    ("sphere_mass_g", Some(SPHERE), false),
    ("sphere_depth_cm", Some(SPHERE), false),
    ("fluid_density_kg_m3", None, false),
    ("gravity_m_s2", None, false),
    ("column_height_cm", None, false),
];

/// Every figure key, in the order of [`FIGURES`].
fn figure_keys() -> impl Iterator<Item = &'static str> {
    FIGURES.iter().map(|(k, _, _)| *k)
}

/// The figure keys that only `instrument` uses, in the order of [`FIGURES`].
pub(super) fn keys_of(instrument: &str) -> impl Iterator<Item = &'static str> + '_ {
    FIGURES
        .iter()
        .filter(move |(_, only, _)| *only == Some(instrument))
        .map(|(k, _, _)| *k)
}

/// The D7928 dimensions (the hydrometer's measured dimensions and its cylinder), in the order
/// of [`FIGURES`].
pub(super) fn d7928_keys() -> impl Iterator<Item = &'static str> {
    FIGURES.iter().filter(|(_, _, d)| *d).map(|(k, _, _)| *k)
}

/// Keys of free text a laboratory may add (kept in reduce.toml, not used).
const TEXT_KEYS: [&str; 6] = ["sample", "source", "date", "operator", "note", "dispersant"];
/// A readings file split into its figures (key → (value, where)) and its table.
pub(super) struct Parsed {
    pub(super) figures: BTreeMap<String, (String, Loc)>,
    pub(super) header: Vec<String>,
    /// (where the row is, fields).
    pub(super) rows: Vec<(Loc, Vec<String>)>,
    /// What the format layer detected (format, sheet, encoding, delimiter, decimal mark).
    pub(super) detected: Detected,
}

/// Bad input in `file`, naming no key.
pub(super) fn bad(file: &Path, msg: String) -> Error {
    Error::bad_input(file, None, msg)
}

/// Splits a readings file read by the format layer ([`LabFile`]); refuses duplicate or unknown
/// keys and a missing header.
pub(super) fn split(file: &Path, lab: LabFile) -> Result<Parsed, Error> {
    let mut figures = BTreeMap::new();
    let mut header: Option<Vec<String>> = None;
    let mut rows = Vec::new();
    for r in lab.rows {
        let line = r.loc;
        if r.cells.len() == 1 && r.cells[0].starts_with('#') {
            let c = &r.cells[0][1..];
            let Some((k, v)) = c.split_once('=').filter(|_| header.is_none()) else {
                continue;
            };
            let k = k.trim().to_string();
            if !figure_keys().any(|f| f == k) && !TEXT_KEYS.contains(&k.as_str()) {
                return Err(Error::bad_input(
                    file,
                    Some(&k),
                    format!(
                        "{line}: unknown key; allowed: {}, and the free text {}",
                        figure_keys().collect::<Vec<_>>().join(", "),
                        TEXT_KEYS.join(", ")
                    ),
                ));
            }
            if let Some((_, first)) =
                figures.insert(k.clone(), (v.trim().to_string(), line.clone()))
            {
                return Err(Error::bad_input(
                    file,
                    Some(&k),
                    format!("{line}: given twice (first on {first})"),
                ));
            }
            continue;
        }
        match &header {
            None => header = Some(r.cells),
            Some(_) => rows.push((line, r.cells)),
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
        detected: lab.detected,
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
            format!(
                "{line}: `{v}` is not a number{}; allowed: {allowed}",
                number_hint(v, &p.detected)
            ),
        )
    })?;
    if !(x.is_finite() && x >= lo && x <= hi) {
        return Err(Error::bad_input(
            file,
            Some(key),
            format!(
                "{line}: {v} is out of range; allowed: {allowed}{}",
                figure_hint(key, x)
            ),
        ));
    }
    Ok(Some(x))
}

/// The figure `key`, or bad input asking for its line (`what` it is) when absent.
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
    req: &ReduceOptions,
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
    let given = option
        .clone()
        .map(|v| (v, format!("--{key}")))
        .or_else(|| p.figures.get(key).map(|(v, l)| (v.clone(), l.to_string())));
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

/// The likely cause of a figure out of its range (empty when none is likely): a density for
/// G_s, litres for mL, metres for cm, °F for °C.
pub(super) fn figure_hint(key: &str, x: f64) -> String {
    let hint = |s: String| format!(" ({s})");
    match key {
        "specific_gravity" if (1000.0..=5000.0).contains(&x) => hint(format!(
            "a density in kg/m³? G_s is the solids' density over water's: give {}",
            sig_trim(x / 1000.0, 4)
        )),
        "suspension_volume_ml" if (0.1..=10.0).contains(&x) => hint(format!(
            "in litres? give millilitres: {}",
            sig_trim(x * 1000.0, 4)
        )),
        "column_height_cm"
        | "pipette_depth_cm"
        | "sphere_depth_cm"
        | "h_r1_cm"
        | "h_r2_cm"
        | "hydrometer_bulb_length_cm"
            if x > 0.0 && x < 1.0 =>
        {
            hint(format!(
                "in metres? give centimetres: {}",
                sig_trim(x * 100.0, 4)
            ))
        }
        "temperature_c" if (50.0..=110.0).contains(&x) => hint(format!(
            "°F? {} °F is {} °C: give degrees Celsius",
            sig_trim(x, 4),
            sig_trim((x - 32.0) / 1.8, 3)
        )),
        "fluid_density_kg_m3" if (0.5..=3.0).contains(&x) => hint(format!(
            "in g/cm³ or t/m³? give kg/m³: {}",
            sig_trim(x * 1000.0, 4)
        )),
        "sphere_diameter_mm" if x > 0.0 && x < 1.0 => hint(format!(
            "in centimetres or metres? give millimetres: {} mm if centimetres",
            sig_trim(x * 10.0, 4)
        )),
        _ => String::new(),
    }
}
