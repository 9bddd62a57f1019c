//! The input files a scenario names, read and checked while the scenario is prepared, so that a
//! bad file is refused (exit 2) before anything runs: the spheres of `[spheres_csv]` (with the
//! inline `[[spheres]]`, [`spheres`]), the sample distribution of a sedimentation run
//! ([`read_sample`]) and the measured curves of `[reference]` ([`read_reference`]). Every error names the scenario file, the key that names the input file,
//! the input file, the line of the file and the data row (both 1-based: line 1 is the header,
//! data row 1 the first line of data), the column (1-based) and what is allowed.

use super::schema::{ReferenceSpec, SampleSpec, Scenario, SphereSpec};
use crate::error::BadInput;
use crate::io::lab_file::{LabFile, Loc};
use crate::sample::Distribution;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// One sphere to simulate, with its identifier resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct SphereCase {
    /// Identifier (`id` of `[[spheres]]`, `id` or `sphere_id` column of the CSV).
    pub id: String,
    /// The sphere's properties.
    pub spec: SphereSpec,
    /// Fall height of the lowest point above the free surface, m (kind `drop`).
    pub fall_height_m: Option<f64>,
}

/// A column of the spheres CSV: the name it is written under (the TOML key of `[[spheres]]`
/// first, then the old names still read) and the field it fills.
struct SphereColumn {
    names: &'static [&'static str],
    field: Field,
}

#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
enum Field {
    Id,
    Suspension,
    Diameter,
    Density,
    Youngs,
    Poisson,
    VMeasured,
    /// A reference column kept in the file for the reader (tabulated figures); not read.
    Ignored,
}

const SPHERE_COLUMNS: &[SphereColumn] = &[
    SphereColumn {
        names: &["id", "sphere_id"],
        field: Field::Id,
    },
    SphereColumn {
        names: &["suspension"],
        field: Field::Suspension,
    },
    SphereColumn {
        names: &["diameter_m"],
        field: Field::Diameter,
    },
    SphereColumn {
        names: &["density_kg_m3"],
        field: Field::Density,
    },
    SphereColumn {
        names: &["youngs_modulus_pa"],
        field: Field::Youngs,
    },
    SphereColumn {
        names: &["poisson_ratio"],
        field: Field::Poisson,
    },
    SphereColumn {
        names: &["v_measured_m_s", "v_terminal_measured_m_s"],
        field: Field::VMeasured,
    },
    SphereColumn {
        names: &["re_bingham_tabulated", "cd_tabulated"],
        field: Field::Ignored,
    },
];

/// An input CSV being read: builds errors naming the scenario file, the key and the CSV.
struct CsvInput<'a> {
    scenario_path: &'a Path,
    key: &'static str,
    csv_path: PathBuf,
}

impl CsvInput<'_> {
    fn err(&self, msg: impl std::fmt::Display) -> BadInput {
        BadInput::new(
            self.scenario_path,
            Some(self.key),
            format!("`{}`: {msg}", self.csv_path.display()),
        )
    }

    /// Reads the input table through the lab format layer ([`crate::io::lab_file`]: CSV with
    /// commas or semicolons, decimal points or commas, UTF-8 or Windows-1252, or an `.xlsx` /
    /// `.ods` sheet; `#` rows skipped, spaces around fields trimmed) and returns its data rows
    /// (each as wide as the header) and its header.
    fn open(&self) -> Result<(Vec<Rec>, Vec<String>), BadInput> {
        let bytes = std::fs::read(&self.csv_path).map_err(|e| {
            BadInput::new(
                self.scenario_path,
                Some(self.key),
                format!(
                    "cannot read `{}` (the path is relative to the scenario file's folder): {e}",
                    self.csv_path.display()
                ),
            )
        })?;
        let lab = LabFile::from_bytes(&self.csv_path, &bytes).map_err(|e| match e {
            crate::error::Error::BadInput(b) => self.err(b.message),
            other => self.err(other),
        })?;
        let mut rows = lab.rows.into_iter().filter(|r| !r.is_comment());
        let header = rows
            .next()
            .map(|r| r.cells)
            .ok_or_else(|| self.err("header: the file has no header line"))?;
        let mut recs = Vec::new();
        for (i, r) in rows.enumerate() {
            let rec = Rec {
                loc: r.loc,
                row: i + 1,
                cells: r.cells,
            };
            if rec.cells.len() != header.len() {
                return Err(self.err(format!(
                    "{}: {} fields where the header has {}: allowed one field per column (an \
                     empty field for an absent value)",
                    row_of(&rec),
                    rec.cells.len(),
                    header.len()
                )));
            }
            recs.push(rec);
        }
        Ok((recs, header))
    }

    /// The number in `rec`'s column `col` (0-based), `None` if the field is empty.
    fn number(&self, rec: &Rec, header: &[String], col: usize) -> Result<Option<f64>, BadInput> {
        let raw = rec.get(col).unwrap_or("");
        if raw.is_empty() {
            return Ok(None);
        }
        raw.parse::<f64>().map(Some).map_err(|_| {
            self.err(format!(
                "{}, column {} (`{}`): `{raw}` is not a number",
                row_of(rec),
                col + 1,
                header[col]
            ))
        })
    }

    /// As [`Self::number`], required.
    fn required(&self, rec: &Rec, header: &[String], col: usize) -> Result<f64, BadInput> {
        self.number(rec, header, col)?.ok_or_else(|| {
            self.err(format!(
                "{}, column {} (`{}`): empty: a number is required",
                row_of(rec),
                col + 1,
                header[col]
            ))
        })
    }
}

/// One data row of an input table: where it is, its place among the data rows (1-based) and
/// its cells.
struct Rec {
    loc: Loc,
    row: usize,
    cells: Vec<String>,
}

impl Rec {
    fn get(&self, col: usize) -> Option<&str> {
        self.cells.get(col).map(String::as_str)
    }
}

/// Where a record is, both 1-based: `line L (data row R)`, L the line of the file as an editor
/// numbers it (line 1 is the header; comment lines count), R the record among the data rows
/// (row 1 is the first line of data). Every error about a row of an input CSV names it so.
fn row_of(rec: &Rec) -> String {
    format!("{} (data row {})", rec.loc, rec.row)
}

/// The column of each field of the spheres CSV, from its header; refuses an unknown or
/// repeated column, and a missing required one, listing the columns it reads.
fn sphere_columns(input: &CsvInput, header: &[String]) -> Result<HashMap<Field, usize>, BadInput> {
    let known = || {
        SPHERE_COLUMNS
            .iter()
            .map(|c| c.names.join(" or "))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut cols = HashMap::new();
    for (i, name) in header.iter().enumerate() {
        let Some(c) = SPHERE_COLUMNS
            .iter()
            .find(|c| c.names.contains(&name.as_str()))
        else {
            return Err(input.err(format!(
                "column {} `{name}` is unknown: allowed columns {}",
                i + 1,
                known()
            )));
        };
        if c.field != Field::Ignored && cols.insert(c.field, i).is_some() {
            return Err(input.err(format!(
                "column {} `{name}` repeats a column already given (allowed once: {})",
                i + 1,
                c.names.join(" or ")
            )));
        }
    }
    for f in [Field::Id, Field::Diameter, Field::Density] {
        if !cols.contains_key(&f) {
            let c = SPHERE_COLUMNS
                .iter()
                .find(|c| c.field == f)
                .expect("listed");
            return Err(input.err(format!(
                "missing column `{}` (required: id or sphere_id, diameter_m, density_kg_m3; allowed {})",
                c.names[0],
                known()
            )));
        }
    }
    Ok(cols)
}

/// One row of the spheres CSV: its id, the sphere and its 1-based line.
fn sphere_row(
    input: &CsvInput,
    header: &[String],
    cols: &HashMap<Field, usize>,
    rec: &Rec,
) -> Result<(String, SphereSpec, String), BadInput> {
    let opt = |f: Field| match cols.get(&f) {
        Some(&c) => input.number(rec, header, c),
        None => Ok(None),
    };
    let id = rec.get(cols[&Field::Id]).unwrap_or("").to_string();
    if id.is_empty() {
        return Err(input.err(format!(
            "{}, column {} (`{}`): empty: every sphere needs an id",
            row_of(rec),
            cols[&Field::Id] + 1,
            header[cols[&Field::Id]]
        )));
    }
    let suspension = match opt(Field::Suspension)? {
        None => None,
        Some(x) if x >= 0.0 && x.fract() == 0.0 && x <= u32::MAX as f64 => Some(x as u32),
        Some(x) => {
            return Err(input.err(format!(
                "{}, column {} (`suspension`): {x} is out of range: allowed a whole number ≥ 0",
                row_of(rec),
                cols[&Field::Suspension] + 1
            )))
        }
    };
    let spec = SphereSpec {
        id: Some(id.clone()),
        diameter_m: input.required(rec, header, cols[&Field::Diameter])?,
        density_kg_m3: input.required(rec, header, cols[&Field::Density])?,
        youngs_modulus_pa: opt(Field::Youngs)?,
        poisson_ratio: opt(Field::Poisson)?,
        v_measured_m_s: opt(Field::VMeasured)?,
        suspension,
    };
    Ok((id, spec, row_of(rec)))
}

/// Checks a sphere read from the CSV like an inline one; an error on one of its values names
/// the row and the column (both 1-based) of that value.
fn check_row(
    input: &CsvInput,
    header: &[String],
    cols: &HashMap<Field, usize>,
    row: &str,
    spec: &SphereSpec,
    scenario: &Scenario,
) -> Result<(), BadInput> {
    let label = format!("spheres_csv `{}` {row}", input.csv_path.display());
    super::check_sphere(input.scenario_path, &label, spec, scenario).map_err(|e| {
        let field = e
            .key
            .as_deref()
            .and_then(|k| k.strip_prefix(&format!("{label}.")))
            .and_then(|name| SPHERE_COLUMNS.iter().find(|c| c.names[0] == name))
            .and_then(|c| cols.get(&c.field));
        match field {
            Some(&col) => input.err(format!(
                "{row}, column {} (`{}`): {}",
                col + 1,
                header[col],
                e.message
            )),
            None => e,
        }
    })
}

/// Resolves the spheres of `scenario`: the inline `[[spheres]]`, then the rows of
/// `[spheres_csv]` (of its `suspension` if given; the path is relative to `scenario_path`'s
/// folder), each checked like an inline sphere; with `release.fall_heights_m`, one case per
/// sphere and height. Refuses two spheres with one id.
pub fn spheres(scenario: &Scenario, scenario_path: &Path) -> Result<Vec<SphereCase>, BadInput> {
    let mut out: Vec<SphereCase> = scenario
        .spheres
        .iter()
        .enumerate()
        .map(|(i, s)| SphereCase {
            id: s.id.clone().unwrap_or_else(|| format!("sphere-{i}")),
            spec: s.clone(),
            fall_height_m: None,
        })
        .collect();
    // First index of every id: a hash map keeps 10⁵ spheres linear (a scan of the earlier
    // ones took 26 s there).
    let mut first: HashMap<String, usize> = HashMap::with_capacity(out.len());
    for (i, c) in out.iter().enumerate() {
        if let Some(&j) = first.get(&c.id) {
            return Err(BadInput::new(
                scenario_path,
                Some(&format!("spheres[{i}].id")),
                format!(
                    "`{}` is the id of spheres[{j}] already: allowed one sphere per id",
                    c.id
                ),
            ));
        }
        first.insert(c.id.clone(), i);
    }
    if let Some(src) = &scenario.spheres_csv {
        let base = scenario_path.parent().unwrap_or(Path::new("."));
        let input = CsvInput {
            scenario_path,
            key: "spheres_csv.path",
            csv_path: base.join(&src.path),
        };
        let (recs, header) = input.open()?;
        let cols = sphere_columns(&input, &header)?;
        let mut seen: HashMap<String, String> = HashMap::new();
        let mut kept = 0;
        for rec in &recs {
            let (id, spec, row) = sphere_row(&input, &header, &cols, rec)?;
            if let Some(first) = seen.insert(id.clone(), row.clone()) {
                return Err(input.err(format!(
                    "{row}: sphere id `{id}` is already the id of {first}: allowed one row per id"
                )));
            }
            if src.suspension.is_some() && spec.suspension != src.suspension {
                continue;
            }
            if first.contains_key(&id) {
                return Err(input.err(format!(
                    "{row}: sphere id `{id}` is already the id of an inline [[spheres]] table: allowed one sphere per id"
                )));
            }
            check_row(&input, &header, &cols, &row, &spec, scenario)?;
            kept += 1;
            out.push(SphereCase {
                id,
                spec,
                fall_height_m: None,
            });
        }
        if kept == 0 {
            return Err(input.err(format!(
                "has no sphere{}",
                src.suspension
                    .map(|s| format!(" of suspension {s}"))
                    .unwrap_or_default()
            )));
        }
    }
    if !scenario.release.fall_heights_m.is_empty() {
        out = out
            .iter()
            .flat_map(|c| {
                scenario
                    .release
                    .fall_heights_m
                    .iter()
                    .map(move |h| SphereCase {
                        id: format!("{}-H{}mm", c.id, (h * 1e3 * 10.0).round() / 10.0),
                        spec: c.spec.clone(),
                        fall_height_m: Some(*h),
                    })
            })
            .collect();
    }
    Ok(out)
}

/// The measured curves of a scenario's `[reference]`, read and checked while it is prepared.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct MeasuredCurves {
    /// Where they come from (`reference.source`), for the legends.
    pub source: String,
    /// (time_s, velocity_m_s) of `reference.velocity_csv`, in file order (empty if not given).
    pub velocity: Vec<(f64, f64)>,
    /// (time_s, gap_m) of `reference.gap_csv`, in file order (empty if not given).
    pub gap: Vec<(f64, f64)>,
}

/// Reads the curves of `scenario`'s `[reference]` (None without one): a non-empty `source` and
/// at least one of `velocity_csv` (columns `time_s`, `velocity_m_s`) and `gap_csv` (columns
/// `time_s`, `gap_m`), each relative to `scenario_path`'s folder, other columns ignored, every
/// row a finite number in both columns, at least one row. Errors name the scenario file, the
/// key, the CSV and its line, data row and column (1-based).
pub fn read_reference(
    scenario: &Scenario,
    scenario_path: &Path,
) -> Result<Option<MeasuredCurves>, BadInput> {
    let Some(r) = &scenario.reference else {
        return Ok(None);
    };
    let ReferenceSpec {
        source,
        velocity_csv,
        gap_csv,
    } = r;
    if source.trim().is_empty() {
        return Err(BadInput::new(
            scenario_path,
            Some("reference.source"),
            "empty: name where the measured curves come from (it labels them in the charts)",
        ));
    }
    if velocity_csv.is_none() && gap_csv.is_none() {
        return Err(BadInput::new(
            scenario_path,
            Some("reference"),
            "names no file: give velocity_csv, gap_csv or both",
        ));
    }
    let base = scenario_path.parent().unwrap_or(Path::new("."));
    let read = |key: &'static str, file: &Option<String>, column: &str| match file {
        None => Ok(Vec::new()),
        Some(f) => curve(
            &CsvInput {
                scenario_path,
                key,
                csv_path: base.join(f),
            },
            column,
        ),
    };
    Ok(Some(MeasuredCurves {
        source: source.trim().to_string(),
        velocity: read("reference.velocity_csv", velocity_csv, "velocity_m_s")?,
        gap: read("reference.gap_csv", gap_csv, "gap_m")?,
    }))
}

/// The (time_s, `column`) pairs of a measured curve's CSV (see [`read_reference`]).
fn curve(input: &CsvInput, column: &str) -> Result<Vec<(f64, f64)>, BadInput> {
    let (recs, header) = input.open()?;
    let find = |name: &str| {
        header.iter().position(|h| h == name).ok_or_else(|| {
            input.err(format!(
                "missing column `{name}` (required: time_s, {column}; other columns are ignored)"
            ))
        })
    };
    let (ct, cv) = (find("time_s")?, find(column)?);
    let mut out = Vec::new();
    for rec in &recs {
        let mut pair = [0.0; 2];
        for (k, c) in [ct, cv].into_iter().enumerate() {
            let x = input.required(rec, &header, c)?;
            if !x.is_finite() {
                return Err(input.err(format!(
                    "{}, column {} (`{}`): {x} is out of range: allowed a finite number",
                    row_of(rec),
                    c + 1,
                    header[c]
                )));
            }
            pair[k] = x;
        }
        out.push((pair[0], pair[1]));
    }
    if out.is_empty() {
        return Err(input.err("has no data row: allowed at least one"));
    }
    Ok(out)
}

/// Columns of the sample CSV, in the order of the data file.
const SAMPLE_COLUMNS: [&str; 3] = ["sample", "diameter_m", "percent_finer"];

/// Reads and checks the grain-size distribution of a sedimentation scenario's `[sample]`:
/// sample `sample.sample` of the CSV `sample.csv` (relative to `scenario_path`'s folder) with
/// columns `sample, diameter_m, percent_finer` (any order; no other column). Every row must hold
/// a whole sample number ≥ 0, a diameter > 0 m and a percent finer within [0, 100]; the rows of
/// the chosen sample (at least two) must have increasing diameters and non-decreasing percent
/// finer. Errors (key `sample.csv`) name the CSV, the row and column (1-based) and the allowed
/// range. The distribution is the one [`Distribution::load`] reads from a good file.
pub fn read_sample(sample: &SampleSpec, scenario_path: &Path) -> Result<Distribution, BadInput> {
    let base = scenario_path.parent().unwrap_or(Path::new("."));
    let input = CsvInput {
        scenario_path,
        key: "sample.csv",
        csv_path: base.join(&sample.csv),
    };
    let (recs, header) = input.open()?;
    let mut cols = [usize::MAX; 3];
    for (i, name) in header.iter().enumerate() {
        match SAMPLE_COLUMNS.iter().position(|k| k == name) {
            Some(k) if cols[k] == usize::MAX => cols[k] = i,
            _ => {
                return Err(input.err(format!(
                    "column {} `{name}` is unknown or repeated: allowed columns {} (once each)",
                    i + 1,
                    SAMPLE_COLUMNS.join(", ")
                )))
            }
        }
    }
    if let Some(k) = cols.iter().position(|&c| c == usize::MAX) {
        return Err(input.err(format!(
            "missing column `{}` (required: {})",
            SAMPLE_COLUMNS[k],
            SAMPLE_COLUMNS.join(", ")
        )));
    }
    let mut points: Vec<(f64, f64, String)> = Vec::new();
    for rec in &recs {
        let row = row_of(rec);
        let bad = |k: usize, x: f64, allowed: &str| {
            input.err(format!(
                "{row}, column {} (`{}`): {x} is out of range: allowed {allowed}",
                cols[k] + 1,
                SAMPLE_COLUMNS[k]
            ))
        };
        let n = input.required(rec, &header, cols[0])?;
        if !(n >= 0.0 && n.fract() == 0.0 && n <= u32::MAX as f64) {
            return Err(bad(0, n, "a whole sample number ≥ 0"));
        }
        let d = input.required(rec, &header, cols[1])?;
        if !(d.is_finite() && d > 0.0) {
            return Err(bad(1, d, "0 < diameter_m (m)"));
        }
        let f = input.required(rec, &header, cols[2])?;
        if !(0.0..=100.0).contains(&f) {
            return Err(bad(2, f, "0 ≤ percent_finer ≤ 100 (%)"));
        }
        if n as u32 != sample.sample {
            continue;
        }
        if let Some((d0, f0, r0)) = points.last() {
            let (d0, f0) = (*d0, *f0);
            if d <= d0 {
                return Err(bad(
                    1,
                    d,
                    &format!("diameters increasing within a sample: > {d0} m of {r0}"),
                ));
            }
            if f < f0 {
                return Err(bad(
                    2,
                    f,
                    &format!("percent finer not decreasing within a sample: ≥ {f0} % of {r0}"),
                ));
            }
        }
        points.push((d, f, row));
    }
    if points.len() < 2 {
        return Err(input.err(format!(
            "{} row(s) for sample {}: allowed at least two rows with sample = {} (key sample.sample)",
            points.len(),
            sample.sample,
            sample.sample
        )));
    }
    Ok(Distribution {
        points: points.into_iter().map(|(d, f, _)| (d, f)).collect(),
    })
}

#[cfg(test)]
mod lab_file_tests {
    use super::*;

    /// A scenario's sample table saved by a spreadsheet (semicolons, decimal commas,
    /// Windows-1252, CRLF) reads as the CSV does; a bad cell names the line and the column.
    #[test]
    fn a_sample_table_saved_by_a_spreadsheet_reads_as_the_csv() {
        let text = std::fs::read_to_string("data/sedimentation_samples.csv").unwrap();
        let sheet: String = text
            .lines()
            .map(|l| {
                if l.starts_with('#') {
                    l.replace("log10", "log₁₀ °").replace(',', " ")
                } else {
                    l.split(',')
                        .map(|c| {
                            if c.parse::<f64>().is_ok() {
                                c.replace('.', ",")
                            } else {
                                c.to_string()
                            }
                        })
                        .collect::<Vec<_>>()
                        .join(";")
                }
            })
            .collect::<Vec<_>>()
            .join("\r\n");
        let (latin1, _, bad) = encoding_rs::WINDOWS_1252.encode(&sheet);
        assert!(!bad || sheet.contains('₁'));
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("samples.csv"), &latin1).unwrap();
        std::fs::copy(
            "data/sedimentation_samples.csv",
            dir.path().join("plain.csv"),
        )
        .unwrap();
        let spec = |csv: &str| -> SampleSpec {
            toml::from_str(&format!(
                "csv = \"{csv}\"\nsample = 2\nmass_kg = 0.06\ndensity_kg_m3 = 2500.0\n"
            ))
            .unwrap()
        };
        let scenario = dir.path().join("s.toml");
        let plain = read_sample(&spec("plain.csv"), &scenario).unwrap();
        let sheet = read_sample(&spec("samples.csv"), &scenario).unwrap();
        assert_eq!(plain, sheet);
        let broken = String::from_utf8_lossy(&latin1).replacen("\r\n2;", "\r\nzero;", 1);
        std::fs::write(dir.path().join("broken.csv"), broken.as_bytes()).unwrap();
        let e = read_sample(&spec("broken.csv"), &scenario).unwrap_err();
        assert!(
            e.message.contains("`zero` is not a number"),
            "{}",
            e.message
        );
        assert!(e.message.contains("line "), "{}", e.message);
        assert!(e.message.contains("(data row "), "{}", e.message);
    }
}
