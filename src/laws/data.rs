//! The spheres `settle laws` evaluates: measured terminal velocities with their fluids.
//!
//! Two CSV files: the spheres (`sphere_id, suspension, diameter_m, density_kg_m3,
//! v_terminal_measured_m_s`, optionally `re_bingham_tabulated, cd_tabulated`: the published
//! (Re′, C_d) points) and their fluids (`suspension, density_kg_m3, yield_stress_pa`, and
//! `plastic_viscosity_pa_s` for a Bingham plastic or `consistency_pa_sn, flow_index` for a
//! Herschel–Bulkley fluid). The default is the 121 spheres of Valentik & Whitmore (1965) in six
//! clay suspensions, as tabulated in f-EDEM Tables 2 and 3 (`data/valentik_whitmore_1965_*.csv`,
//! built into the binary).

use crate::error::{BadInput, Error};
use crate::fluid::bingham::YieldFluid;
use crate::io::lab_file::LabFile;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

/// The default spheres (Valentik & Whitmore 1965, f-EDEM Table 3).
pub const VALENTIK_SPHERES_CSV: &str =
    include_str!("../../data/valentik_whitmore_1965_spheres.csv");
/// The default fluids (Valentik & Whitmore 1965, f-EDEM Table 2).
pub const VALENTIK_FLUIDS_CSV: &str =
    include_str!("../../data/valentik_whitmore_1965_suspensions.csv");

/// One fluid (suspension) of the data set.
#[derive(Clone, Debug, PartialEq)]
pub struct Fluid {
    /// Its name in the spheres file's `suspension` column.
    pub name: String,
    /// Density ρ_f, kg/m³.
    pub density_kg_m3: f64,
    /// Its rheogram (Bingham: n = 1, K = η_B).
    pub rheogram: YieldFluid,
}

impl Fluid {
    /// True for a Bingham plastic (flow index 1).
    pub fn is_bingham(&self) -> bool {
        self.rheogram.flow_index == 1.0
    }
}

/// One sphere with its measured terminal velocity.
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    /// Identifier (`S3-04`).
    pub id: String,
    /// Index into [`DataSet::fluids`].
    pub fluid: usize,
    /// Diameter d, m.
    pub diameter_m: f64,
    /// Density ρ_p, kg/m³.
    pub density_kg_m3: f64,
    /// Measured terminal velocity, m/s.
    pub v_measured_m_s: f64,
    /// Published Bingham Reynolds number Re′ at the measured speed, if given.
    pub re_tabulated: Option<f64>,
    /// Published drag coefficient at the measured speed, if given.
    pub cd_tabulated: Option<f64>,
}

/// Spheres and their fluids, with where they came from.
#[derive(Clone, Debug)]
pub struct DataSet {
    /// Where the spheres came from (a path, or the built-in data set's name).
    pub source: String,
    /// The fluids, in file order.
    pub fluids: Vec<Fluid>,
    /// The spheres, in file order.
    pub spheres: Vec<Sphere>,
}

impl DataSet {
    /// The built-in 121 Valentik–Whitmore spheres.
    pub fn valentik() -> Self {
        let file = PathBuf::from("data/valentik_whitmore_1965_spheres.csv");
        let ffile = PathBuf::from("data/valentik_whitmore_1965_suspensions.csv");
        let fluids = parse_fluids(
            LabFile::from_text(&ffile, VALENTIK_FLUIDS_CSV).expect("built-in fluids read"),
        )
        .expect("built-in fluids parse");
        let spheres = parse_spheres(
            LabFile::from_text(&file, VALENTIK_SPHERES_CSV).expect("built-in spheres read"),
            &fluids,
        )
        .expect("built-in spheres parse");
        Self {
            source: "Valentik & Whitmore (1965), 121 spheres (f-EDEM Tables 2-3)".into(),
            fluids,
            spheres,
        }
    }

    /// Reads a spheres file and its fluids file.
    pub fn read(spheres: &Path, fluids: &Path) -> Result<Self, Error> {
        let fl = parse_fluids(LabFile::read(fluids)?)?;
        let sp = parse_spheres(LabFile::read(spheres)?, &fl)?;
        Ok(Self {
            source: spheres.display().to_string(),
            fluids: fl,
            spheres: sp,
        })
    }
}

/// A CSV's header and its rows as maps column → text.
type Table = (Vec<String>, Vec<HashMap<String, String>>);

/// The rows of a lab file ([`LabFile`]: CSV with commas, semicolons or tabs, decimal points or
/// commas, any common encoding, or an `.xlsx` / `.ods` sheet) as maps column → text, with the
/// header; a row wider than the header is bad input naming its line.
fn rows(lab: LabFile) -> Result<Table, Error> {
    let (header, data) = lab.table()?;
    let out = data
        .into_iter()
        .map(|r| header.iter().cloned().zip(r.cells).collect())
        .collect();
    Ok((header, out))
}

/// The number in column `col` of data row `i` (1-based), checked by `ok`.
fn number(
    file: &Path,
    row: &HashMap<String, String>,
    i: usize,
    col: &str,
    ok: (fn(f64) -> bool, &str),
) -> Result<Option<f64>, Error> {
    let Some(t) = row.get(col).filter(|t| !t.is_empty()) else {
        return Ok(None);
    };
    let key = format!("row {i}, column {col}");
    let x: f64 = t.parse().map_err(|_| {
        Error::BadInput(BadInput::new(
            file,
            Some(&key),
            format!("`{t}` is not a number"),
        ))
    })?;
    if !(x.is_finite() && (ok.0)(x)) {
        return Err(Error::BadInput(BadInput::new(
            file,
            Some(&key),
            format!("{t} is out of range: allowed {}", ok.1),
        )));
    }
    Ok(Some(x))
}

fn required<T>(file: &Path, x: Option<T>, i: usize, col: &str) -> Result<T, Error> {
    x.ok_or_else(|| {
        Error::BadInput(BadInput::new(
            file,
            Some(&format!("row {i}, column {col}")),
            "missing value",
        ))
    })
}

fn need_columns(file: &Path, header: &[String], cols: &[&str]) -> Result<(), Error> {
    for c in cols {
        if !header.iter().any(|h| h == c) {
            return Err(Error::BadInput(BadInput::new(
                file,
                Some(c),
                format!("missing column; the file needs {}", cols.join(", ")),
            )));
        }
    }
    Ok(())
}

const POSITIVE: (fn(f64) -> bool, &str) = (|x| x > 0.0, "> 0");
const NON_NEGATIVE: (fn(f64) -> bool, &str) = (|x| x >= 0.0, "≥ 0");
const FLOW_INDEX: (fn(f64) -> bool, &str) = (|x| (0.1..=2.0).contains(&x), "0.1 ≤ n ≤ 2");

/// Parses a fluids file.
pub fn parse_fluids(lab: LabFile) -> Result<Vec<Fluid>, Error> {
    let file = &lab.path.clone();
    let (header, rows) = rows(lab)?;
    need_columns(
        file,
        &header,
        &["suspension", "density_kg_m3", "yield_stress_pa"],
    )?;
    let mut out: Vec<Fluid> = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        let i = i + 1;
        let name = r.get("suspension").cloned().unwrap_or_default();
        if name.is_empty() || out.iter().any(|f| f.name == name) {
            return Err(Error::BadInput(BadInput::new(
                file,
                Some(&format!("row {i}, column suspension")),
                format!("`{name}` is empty or repeated: each fluid needs its own name"),
            )));
        }
        let rho = required(
            file,
            number(file, r, i, "density_kg_m3", POSITIVE)?,
            i,
            "density_kg_m3",
        )?;
        let ty = required(
            file,
            number(file, r, i, "yield_stress_pa", NON_NEGATIVE)?,
            i,
            "yield_stress_pa",
        )?;
        let eb = number(file, r, i, "plastic_viscosity_pa_s", POSITIVE)?;
        let k = number(file, r, i, "consistency_pa_sn", POSITIVE)?;
        let n = number(file, r, i, "flow_index", FLOW_INDEX)?;
        let rheogram = match (eb, k, n) {
            (Some(eb), None, None) => YieldFluid::bingham(ty, eb),
            (None, Some(k), Some(n)) => YieldFluid {
                yield_stress_pa: ty,
                consistency_pa_sn: k,
                flow_index: n,
            },
            _ => {
                return Err(Error::BadInput(BadInput::new(
                    file,
                    Some(&format!("row {i}")),
                    "give either plastic_viscosity_pa_s (Bingham) or consistency_pa_sn and \
                     flow_index (Herschel-Bulkley), not both",
                )))
            }
        };
        out.push(Fluid {
            name,
            density_kg_m3: rho,
            rheogram,
        });
    }
    Ok(out)
}

/// Parses a spheres file against its fluids.
pub fn parse_spheres(lab: LabFile, fluids: &[Fluid]) -> Result<Vec<Sphere>, Error> {
    let file = &lab.path.clone();
    let (header, rows) = rows(lab)?;
    need_columns(
        file,
        &header,
        &[
            "sphere_id",
            "suspension",
            "diameter_m",
            "density_kg_m3",
            "v_terminal_measured_m_s",
        ],
    )?;
    let index: BTreeMap<&str, usize> = fluids
        .iter()
        .enumerate()
        .map(|(i, f)| (f.name.as_str(), i))
        .collect();
    let mut out: Vec<Sphere> = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        let i = i + 1;
        let id = r.get("sphere_id").cloned().unwrap_or_default();
        if id.is_empty() || out.iter().any(|s| s.id == id) {
            return Err(Error::BadInput(BadInput::new(
                file,
                Some(&format!("row {i}, column sphere_id")),
                format!("`{id}` is empty or repeated"),
            )));
        }
        let susp = r.get("suspension").cloned().unwrap_or_default();
        let fluid = *index.get(susp.as_str()).ok_or_else(|| {
            Error::BadInput(BadInput::new(
                file,
                Some(&format!("row {i}, column suspension")),
                format!("`{susp}` is not a fluid of the fluids file"),
            ))
        })?;
        let d = required(
            file,
            number(file, r, i, "diameter_m", POSITIVE)?,
            i,
            "diameter_m",
        )?;
        let rho = required(
            file,
            number(file, r, i, "density_kg_m3", POSITIVE)?,
            i,
            "density_kg_m3",
        )?;
        if rho <= fluids[fluid].density_kg_m3 {
            return Err(Error::BadInput(BadInput::new(
                file,
                Some(&format!("row {i}, column density_kg_m3")),
                format!(
                    "{rho} kg/m³ does not exceed its fluid's density: the sphere would not sink"
                ),
            )));
        }
        let v = required(
            file,
            number(file, r, i, "v_terminal_measured_m_s", POSITIVE)?,
            i,
            "v_terminal_measured_m_s",
        )?;
        out.push(Sphere {
            id,
            fluid,
            diameter_m: d,
            density_kg_m3: rho,
            v_measured_m_s: v,
            re_tabulated: number(file, r, i, "re_bingham_tabulated", POSITIVE)?,
            cd_tabulated: number(file, r, i, "cd_tabulated", POSITIVE)?,
        });
    }
    if out.is_empty() {
        return Err(Error::BadInput(BadInput::new(file, None, "no spheres")));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The CSV `text` as a European spreadsheet exports it: semicolons, decimal commas,
    /// Windows-1252 (a `°` in a comment line) and CRLF.
    fn as_exported(text: &str) -> Vec<u8> {
        let mut out = String::from("# exported \u{b0}C\r\n");
        for line in text.lines().filter(|l| !l.trim().is_empty()) {
            if line.starts_with('#') {
                continue;
            }
            let cells: Vec<String> = line.split(',').map(|c| c.replace('.', ",")).collect();
            out.push_str(&cells.join(";"));
            out.push_str("\r\n");
        }
        let (bytes, _, bad) = encoding_rs::WINDOWS_1252.encode(&out);
        assert!(!bad);
        bytes.into_owned()
    }

    /// Issue 26 item 1: the fluids and spheres of `settle laws --spheres/--fluids` are read as
    /// labs keep them; the built-in 121 Valentik spheres written as a semicolon, decimal-comma,
    /// Windows-1252, CRLF export read exactly as the CSVs do.
    #[test]
    fn an_exported_sheet_reads_as_the_csv() {
        let dir = tempfile::tempdir().unwrap();
        let (s, f) = (dir.path().join("s.csv"), dir.path().join("f.csv"));
        std::fs::write(&s, as_exported(VALENTIK_SPHERES_CSV)).unwrap();
        std::fs::write(&f, as_exported(VALENTIK_FLUIDS_CSV)).unwrap();
        let read = DataSet::read(&s, &f).unwrap();
        let builtin = DataSet::valentik();
        assert_eq!(read.fluids, builtin.fluids);
        assert_eq!(read.spheres.len(), 121);
        assert_eq!(read.spheres, builtin.spheres);
    }

    /// A row wider than the header is refused naming its line.
    #[test]
    fn a_row_wider_than_the_header_names_its_line() {
        let lab = LabFile::from_text(
            Path::new("f.csv"),
            "suspension,density_kg_m3,yield_stress_pa,plastic_viscosity_pa_s\n1,1280,30.5,0.0131,9\n",
        )
        .unwrap();
        let e = parse_fluids(lab).unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("5 fields"), "{e}");
    }
}
