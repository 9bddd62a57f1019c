//! `percent_finer.ags`: the reduced curve as an AGS4 data file (edition 4.1.1, the Association
//! of Geotechnical and Geoenvironmental Specialists' transfer format), checked in the tests by
//! the `python-ags4` validator (`python/tests/test_ags4.py`).
//!
//! The particle-size groups of the AGS4 dictionary are GRAG (particle size distribution
//! analysis, general: one row per specimen) and GRAT (its data: one row per size, `GRAT_SIZE`
//! in mm and `GRAT_PERP` the percentage finer). Their parent groups SAMP and LOCA, and the
//! groups every AGS4 file needs (PROJ, TRAN, ABBR, TYPE, UNIT), are written too. The location,
//! sample and project identifiers are the readings file's stem (a laboratory replaces them with
//! its own); the specimen reference is `1`. The headings and their order are those of the
//! dictionary bundled with python-ags4 (`Standard_dictionary_v4_1_1.ags`).
//!
//! Format (AGS4 rules 1–5): ASCII only, every field in double quotes (a quote doubled),
//! separated by commas, CRLF line ends, a blank line between groups.

use super::method;
use crate::instruments::reduction::{Instrument, Reduced, TestSetup};
use crate::io::fmt::sig_plain;

/// One AGS4 group: its name, headings, units, types and data rows.
struct Group {
    name: &'static str,
    headings: Vec<&'static str>,
    units: Vec<&'static str>,
    types: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Group {
    fn new(name: &'static str, columns: &[(&'static str, &'static str, &str)]) -> Self {
        Self {
            name,
            headings: columns.iter().map(|c| c.0).collect(),
            units: columns.iter().map(|c| c.1).collect(),
            types: columns.iter().map(|c| c.2.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    fn text(&self) -> String {
        let line = |kind: &str, fields: &[String]| {
            let mut l = format!("\"{kind}\"");
            for f in fields {
                l.push_str(&format!(",\"{}\"", field(f)));
            }
            l + "\r\n"
        };
        let own = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        let mut t = line("GROUP", &[self.name.to_string()]);
        t += &line("HEADING", &own(&self.headings));
        t += &line("UNIT", &own(&self.units));
        t += &line("TYPE", &self.types);
        for r in &self.rows {
            t += &line("DATA", r);
        }
        t
    }
}

/// A field as AGS4 takes it: ASCII only (any other character becomes `?`, a control character
/// a space), a double quote doubled.
fn field(s: &str) -> String {
    s.chars()
        .map(|c| match c {
            '"' => "\"\"".to_string(),
            c if c.is_ascii_control() => " ".into(),
            c if c.is_ascii() => c.to_string(),
            _ => "?".into(),
        })
        .collect()
}

/// `x` rounded to `n` significant figures and written with them (AGS4 type `nSF`, as the
/// validator writes it: `0.00325`, `10.0`).
fn sf(x: f64, n: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return sig_plain(x, n);
    }
    let scale = 10f64.powi(n as i32 - 1 - x.abs().log10().floor() as i32);
    sig_plain((x * scale).round() / scale, n)
}

/// The fewest significant figures, from 3 (the dictionary's `GRAT_SIZE` type) up to 10, that
/// keep the sizes (mm) apart: `GRAT_SIZE` is a key of GRAT.
fn size_figures(sizes_mm: &[f64]) -> usize {
    (3..=10)
        .find(|&n| {
            let mut s: Vec<String> = sizes_mm.iter().map(|&d| sf(d, n)).collect();
            s.sort();
            s.dedup();
            s.len() == sizes_mm.len()
        })
        .unwrap_or(10)
}

/// The date (UTC) today, `yyyy-mm-dd` (TRAN_DATE: the date the file was produced).
fn today() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let (y, m, d) = civil_from_days((secs / 86_400) as i64);
    format!("{y:04}-{m:02}-{d:02}")
}

/// The proleptic Gregorian date of a day count since 1970-01-01 (H. Hinnant's
/// `civil_from_days`, chrono-compatible algorithms, public domain).
fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    (yoe + era * 400 + i64::from(m <= 2), m, d)
}

/// The GRAT_TYPE abbreviation of the instrument, with its description (defined in the file's
/// ABBR group).
fn test_type(i: &Instrument) -> (&'static str, &'static str) {
    match i {
        Instrument::Hydrometer(_) => ("HYD", "Hydrometer (sedimentation)"),
        Instrument::Pipette { .. } => ("PIP", "Pipette (sedimentation)"),
        Instrument::BuoyancySphere { .. } => ("BSPH", "Buoyancy sphere (sedimentation)"),
    }
}

/// PROJ, TRAN and LOCA: the project and location `id`, the file's date and producer.
fn header_groups(file: &str, id: &str) -> [Group; 3] {
    let id = id.to_string();
    let mut proj = Group::new(
        "PROJ",
        &[
            ("PROJ_ID", "", "ID"),
            ("PROJ_NAME", "", "X"),
            ("PROJ_MEMO", "", "X"),
        ],
    );
    proj.rows.push(vec![
        id.clone(),
        id.clone(),
        format!("reduced by settle reduce from {file}"),
    ]);
    let mut tran = Group::new(
        "TRAN",
        &[
            ("TRAN_ISNO", "", "X"),
            ("TRAN_DATE", "yyyy-mm-dd", "DT"),
            ("TRAN_PROD", "", "X"),
            ("TRAN_STAT", "", "X"),
            ("TRAN_DESC", "", "X"),
            ("TRAN_AGS", "", "X"),
            ("TRAN_RECV", "", "X"),
        ],
    );
    tran.rows.push(vec![
        "1".into(),
        today(),
        format!("settle {}", env!("CARGO_PKG_VERSION")),
        "Draft".into(),
        "Particle size distribution by sedimentation (settle reduce)".into(),
        "4.1.1".into(),
        "Not specified".into(),
    ]);
    let mut loca = Group::new("LOCA", &[("LOCA_ID", "", "ID")]);
    loca.rows.push(vec![id.clone()]);
    [proj, tran, loca]
}

/// ABBR, UNIT and TYPE: the test type `code` (`desc`), the units, and the data types with the
/// size's `size_type` (`n` significant figures).
fn dictionary_groups(code: &str, desc: &str, size_type: &str, n: usize) -> [Group; 3] {
    let mut abbr = Group::new(
        "ABBR",
        &[
            ("ABBR_HDNG", "", "X"),
            ("ABBR_CODE", "", "X"),
            ("ABBR_DESC", "", "X"),
            ("ABBR_LIST", "", "X"),
        ],
    );
    abbr.rows.push(vec![
        "GRAT_TYPE".into(),
        code.into(),
        desc.into(),
        "settle".into(),
    ]);
    let mut unit = Group::new("UNIT", &[("UNIT_UNIT", "", "X"), ("UNIT_DESC", "", "X")]);
    for (u, d) in [
        ("%", "percentage"),
        ("m", "metre"),
        ("mm", "millimetre"),
        ("Mg/m3", "megagrams per cubic metre"),
        ("yyyy-mm-dd", "year month day"),
    ] {
        unit.rows.push(vec![u.into(), d.into()]);
    }
    let mut types = Group::new("TYPE", &[("TYPE_TYPE", "", "X"), ("TYPE_DESC", "", "X")]);
    for (t, d) in [
        ("1DP".to_string(), "Value; 1 decimal place".to_string()),
        ("2DP".into(), "Value; 2 decimal places".into()),
        (
            size_type.to_string(),
            format!("Value; {n} significant figures"),
        ),
        ("DT".into(), "Date time in international format".into()),
        ("ID".into(), "Unique identifier".into()),
        ("PA".into(), "Text listed in ABBR Group".into()),
        ("X".into(), "Text".into()),
        ("XN".into(), "Text / numeric".into()),
    ] {
        types.rows.push(vec![t, d]);
    }
    [abbr, unit, types]
}

/// The text of `percent_finer.ags` for the readings `file` (its stem `stem`) reduced to `red`.
pub(crate) fn ags_text(file: &str, stem: &str, s: &TestSetup, red: &[Reduced]) -> String {
    let id = stem.to_string();
    let key = |spec: bool| {
        let mut k = vec![
            id.clone(),
            String::new(),
            String::new(),
            String::new(),
            id.clone(),
        ];
        if spec {
            k.extend(["1".to_string(), String::new()]);
        }
        k
    };
    const KEYS: [(&str, &str, &str); 7] = [
        ("LOCA_ID", "", "ID"),
        ("SAMP_TOP", "m", "2DP"),
        ("SAMP_REF", "", "X"),
        ("SAMP_TYPE", "", "PA"),
        ("SAMP_ID", "", "ID"),
        ("SPEC_REF", "", "X"),
        ("SPEC_DPTH", "m", "2DP"),
    ];
    let [proj, tran, loca] = header_groups(file, &id);
    let mut samp = Group::new("SAMP", &KEYS[..5]);
    samp.rows.push(key(false));
    let mut grag_cols = KEYS.to_vec();
    grag_cols.extend([
        ("GRAG_REM", "", "X"),
        ("GRAG_METH", "", "X"),
        ("GRAG_PDEN", "Mg/m3", "XN"),
    ]);
    let mut grag = Group::new("GRAG", &grag_cols);
    let mut row = key(true);
    row.extend([
        "Sedimentation only (no sieving): sizes are Stokes diameters; percentages of the \
         specimen's dry mass in suspension; particle density = specific gravity x 1 Mg/m3"
            .to_string(),
        method(s),
        sf(s.specific_gravity, 3),
    ]);
    grag.rows.push(row);
    let sizes: Vec<f64> = red.iter().map(|r| r.diameter_m * 1e3).collect();
    let n = size_figures(&sizes);
    let size_type = format!("{n}SF");
    let mut grat_cols = KEYS.to_vec();
    grat_cols.extend([
        ("GRAT_SIZE", "mm", size_type.as_str()),
        ("GRAT_PERP", "%", "1DP"),
        ("GRAT_TYPE", "", "PA"),
        ("GRAT_REM", "", "X"),
    ]);
    let mut grat = Group::new("GRAT", &grat_cols);
    let (code, desc) = test_type(&s.instrument);
    for (r, d) in red.iter().zip(&sizes) {
        let mut row = key(true);
        row.extend([
            sf(*d, n),
            format!("{:.1}", r.percent_finer),
            code.to_string(),
            format!(
                "t = {} min, T = {} deg C",
                sig_plain(r.reading.time_s / 60.0, 4),
                sig_plain(r.reading.temperature_c, 3)
            ),
        ]);
        grat.rows.push(row);
    }
    let [abbr, unit, types] = dictionary_groups(code, desc, &size_type, n);
    [proj, tran, loca, samp, grag, grat, abbr, unit, types]
        .iter()
        .map(Group::text)
        .collect::<Vec<_>>()
        .join("\r\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_figures_as_the_validator_writes_them() {
        assert_eq!(sf(0.003_254, 3), "0.00325");
        assert_eq!(sf(9.9996, 3), "10.0");
        assert_eq!(sf(0.0409_96, 3), "0.0410");
        assert_eq!(size_figures(&[0.003_251, 0.003_254]), 4);
        assert_eq!(size_figures(&[0.05, 0.02]), 3);
    }

    #[test]
    fn dates_and_fields() {
        assert_eq!(civil_from_days(0), (1970, 1, 1));
        assert_eq!(civil_from_days(20_793), (2026, 12, 6));
        assert_eq!(civil_from_days(11_016), (2000, 2, 29));
        assert_eq!(field("a \"b\" 21.5 °C"), "a \"\"b\"\" 21.5 ?C");
    }
}
