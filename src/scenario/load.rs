//! Loading a scenario: TOML parsing, `--set KEY=VALUE` overrides, schema errors that name the
//! file and the key, then validation of ranges. A run record (`OUT/NAME/run.toml`, a file with
//! a `[run]` table) loads as its `[scenario]` table, the effective scenario of that run
//! ([`record_table`] writes it), so that `settle run OUT/NAME/run.toml` reruns the same case.

use super::common::Common;
use super::kinds::SceneSpec;
use super::schema::{RheologyModel, Scenario};
use super::validate::{check_tables, table_used_by, validate};
use crate::error::BadInput;
use serde::Serialize;
use std::path::Path;

/// The overrides of a run as given on the command line (`--set KEY=VALUE`…, `--dt`), recorded
/// in `run.toml` beside their effect (the effective scenario).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Overrides {
    /// The `--set KEY=VALUE` list, in the order given.
    pub set: Vec<String>,
    /// The `--dt` time step, s (None: not given).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dt_s: Option<f64>,
}

/// A validated scenario with its typed parts: the common part every kind reads, the scene
/// spec of its kind and the rheology of its fluid. The raw scenario stays inside the scenario
/// layer: out of it come only its input files ([`Parsed::spheres`], [`Parsed::reference`]) and
/// its [`Record`].
#[derive(Clone, Debug, PartialEq)]
pub struct Parsed {
    /// The scenario as read (overrides applied): the record written back to `run.toml`.
    pub(super) scenario: Scenario,
    /// What every kind reads, typed.
    pub common: Common,
    /// What the scenario's kind needs, typed.
    pub scene: SceneSpec,
    /// The fluid's rheology with its parameters (also [`Common::rheology`]).
    pub rheology: RheologyModel,
}

impl Parsed {
    /// Validates `scenario` (`file` names it in errors) and builds its typed parts: the same
    /// checks as [`load`], for a scenario built or changed in code.
    pub fn new(scenario: Scenario, file: &Path) -> Result<Self, BadInput> {
        let (scene, rheology) = validate(&scenario, file)?;
        Ok(Self {
            common: Common::of(&scenario, rheology),
            scenario,
            scene,
            rheology,
        })
    }
}

impl Parsed {
    /// The spheres of the scenario (read from `spheres_csv` when given, one case per fall
    /// height of a drop), relative input files found from `file`'s folder
    /// ([`super::inputs::spheres`]).
    pub fn spheres(&self, file: &Path) -> Result<Vec<super::inputs::SphereCase>, BadInput> {
        super::inputs::spheres(&self.scenario, file)
    }

    /// The measured curves of its `[reference]` (None without one;
    /// [`super::inputs::read_reference`]).
    pub fn reference(
        &self,
        file: &Path,
    ) -> Result<Option<super::inputs::MeasuredCurves>, BadInput> {
        super::inputs::read_reference(&self.scenario, file)
    }

    /// Its parts, the raw scenario consumed into its record: the common part, the kind's spec,
    /// the fluid's rheology and the record of the effective scenario (run.toml's `[scenario]`).
    pub fn into_parts(self) -> (Common, SceneSpec, RheologyModel, Record) {
        let record = Record {
            scenario: self.scenario,
        };
        (self.common, self.scene, self.rheology, record)
    }
}

/// The effective scenario of a run (overrides applied, defaults filled in), kept whole as the
/// record of the run and nothing else: what comes out of it is its TOML, never its raw keys
/// (scenes read the typed parts of [`Parsed`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    scenario: Scenario,
}

impl Record {
    /// The table written to `run.toml` as `[scenario]` ([`record_table`]): the tables the kind
    /// uses, input files as absolute paths (relative ones are found from `file`'s folder).
    pub fn table(&self, file: &Path) -> Result<toml::Table, toml::ser::Error> {
        record_table(&self.scenario, file)
    }

    /// The whole effective scenario as TOML text (every table, input files as given): a
    /// fingerprint that tells whether a scenario changed (the checkpoints of `settle run`).
    pub fn fingerprint(&self) -> String {
        toml::to_string(&self.scenario).unwrap_or_default()
    }
}

/// Reads, overrides, parses and validates a scenario file. `overrides` are `KEY=VALUE` strings
/// (`fluid.viscosity_pa_s=0.002`, `spheres[0].diameter_m=1e-4`, `physics=ideal-stokes`).
#[cfg(test)]
pub fn load(path: &Path, overrides: &[String]) -> Result<Scenario, BadInput> {
    parse(path, overrides).map(|p| p.scenario)
}

/// As [`load`], from the text of a file; `path` names it in errors.
#[cfg(test)]
pub fn load_str(text: &str, path: &Path, overrides: &[String]) -> Result<Scenario, BadInput> {
    parse_str(text, path, overrides).map(|p| p.scenario)
}

/// As [`load`], with the typed parts of the scenario: the spec of its kind and its rheology.
#[cfg(test)]
pub fn parse(path: &Path, overrides: &[String]) -> Result<Parsed, BadInput> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| BadInput::new(path, None, crate::io::arg::unreadable("scenario", &e)))?;
    parse_str(&text, path, overrides)
}

/// As [`parse`], from the text of a file; `path` names it in errors.
pub fn parse_str(text: &str, path: &Path, overrides: &[String]) -> Result<Parsed, BadInput> {
    let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
        let line = e
            .span()
            .map(|s| format!("line {}: ", text[..s.start].lines().count().max(1)))
            .unwrap_or_default();
        BadInput::new(
            path,
            None,
            format!("TOML syntax error: {line}{}", e.message()),
        )
    })?;
    let mut table = scenario_of_record(table, path)?;
    for o in overrides {
        apply_override(&mut table, o, path)?;
    }
    // A table the kind does not use is refused before the tables are parsed, so that the
    // error names the table and the kind rather than a key missing inside the unused table.
    if let Some(kind) = table
        .get("kind")
        .and_then(|k| k.clone().try_into::<super::schema::Kind>().ok())
    {
        let present: Vec<&str> = table.keys().map(String::as_str).collect();
        check_tables(kind, &present, path)?;
    }
    // The time lists written in the file, to tell them from defaults (trim_default_times).
    let given: toml::Table = ["sample", "instruments"]
        .into_iter()
        .filter_map(|k| Some((k.to_string(), table.get(k)?.clone())))
        .collect();
    let value = toml::Value::Table(table);
    let mut scenario: Scenario = serde_path_to_error::deserialize(value).map_err(|e| {
        let key = e.path().to_string();
        // `message()`, not `to_string()`: the latter appends ` in `table`` and a newline.
        let msg = e.inner().message().to_string();
        // serde names a missing field relative to its table; give the full path.
        let key = match (msg.strip_prefix("missing field `"), key.as_str()) {
            (Some(rest), parent) => {
                let field = rest.split('`').next().unwrap_or(rest);
                if parent == "." {
                    field.to_string()
                } else {
                    format!("{parent}.{field}")
                }
            }
            _ => key,
        };
        // A key of a --set: say which (`--set no.such.key=1` fails at `no`).
        let given = overrides.iter().find(|o| {
            o.split_once('=').is_some_and(|(k, _)| {
                let k = k.trim();
                k == key || k.starts_with(&format!("{key}.")) || k.starts_with(&format!("{key}["))
            })
        });
        let msg = match given {
            Some(o) if key != "." => format!("{msg} (from --set {o})"),
            _ => msg,
        };
        let key = if key == "." { None } else { Some(key) };
        BadInput::new(path, key.as_deref(), msg)
    })?;
    super::schema::trim_default_times(&mut scenario, &given);
    Parsed::new(scenario, path)
}

/// The scenario table of a file: the file itself, or for a run record (a file with a `[run]`
/// table, `OUT/NAME/run.toml`) its `[scenario]` table, the effective scenario of that run with
/// its overrides already applied; the rest of the record (`[run]`, `[engine_settings]`) is
/// ignored.
fn scenario_of_record(mut table: toml::Table, path: &Path) -> Result<toml::Table, BadInput> {
    if !table.contains_key("run") {
        return Ok(table);
    }
    match table.remove("scenario") {
        Some(toml::Value::Table(t)) => Ok(t),
        _ => Err(BadInput::new(
            path,
            Some("scenario"),
            "missing: a file with a [run] table is a run record (OUT/NAME/run.toml) and runs its \
             [scenario] table, which it lacks (a scenario file has no [run] table)",
        )),
    }
}

/// The effective scenario `s` (read from `file`) as written to `run.toml`, so that the record
/// runs again anywhere: the tables its kind does not use are left out (they hold only defaults:
/// validation refuses them when given), and the input files (`spheres_csv.path`, `sample.csv`,
/// `reference.velocity_csv`, `reference.gap_csv`), relative to `file`'s folder, become absolute
/// paths.
pub fn record_table(s: &Scenario, file: &Path) -> Result<toml::Table, toml::ser::Error> {
    let mut t = match toml::Value::try_from(s)? {
        toml::Value::Table(t) => t,
        _ => unreachable!("a scenario serializes as a table"),
    };
    t.retain(|key, _| table_used_by(key, s.kind));
    let base = file.parent().unwrap_or(Path::new("."));
    let absolute = |rel: &str| -> String {
        let p = base.join(rel);
        std::fs::canonicalize(&p)
            .or_else(|_| std::path::absolute(&p))
            .unwrap_or(p)
            .display()
            .to_string()
    };
    let mut resolve = |table: &str, key: &str| {
        if let Some(toml::Value::String(v)) = t
            .get_mut(table)
            .and_then(|x| x.as_table_mut()?.get_mut(key))
        {
            *v = absolute(v);
        }
    };
    resolve("spheres_csv", "path");
    resolve("sample", "csv");
    resolve("reference", "velocity_csv");
    resolve("reference", "gap_csv");
    Ok(t)
}

/// Whether `key` can name a scenario key: a dotted path of letters, digits and `_`, with `[i]`
/// indices (`fluid.yield_stress_pa`, `spheres[0].diameter_m`); not empty.
pub fn is_key_path(key: &str) -> bool {
    !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_.[]".contains(c))
}

/// Applies one `KEY=VALUE` override to a TOML table. The value is parsed as TOML (number,
/// boolean, array, quoted string) and otherwise taken as a bare string. Keys are dotted paths;
/// `name[i]` indexes an array of tables. Missing tables are created.
pub fn apply_override(
    table: &mut toml::Table,
    assignment: &str,
    path: &Path,
) -> Result<(), BadInput> {
    let bad = |m: String| BadInput::new(path, None, m);
    let (key, raw) = assignment
        .split_once('=')
        .ok_or_else(|| bad(format!("--set `{assignment}`: expected KEY=VALUE")))?;
    let key = key.trim();
    let raw = raw.trim();
    let mut value = Some(match format!("v = {raw}").parse::<toml::Table>() {
        Ok(mut t) => t.remove("v").expect("parsed key"),
        Err(_) => toml::Value::String(raw.to_string()),
    });
    let parts: Vec<&str> = key.split('.').collect();
    let mut cur = table;
    for (i, part) in parts.iter().enumerate() {
        let last = i + 1 == parts.len();
        let (name, index) = match part.split_once('[') {
            Some((n, rest)) => {
                let idx: usize = rest
                    .trim_end_matches(']')
                    .parse()
                    .map_err(|_| bad(format!("--set `{key}`: bad index in `{part}`")))?;
                (n, Some(idx))
            }
            None => (*part, None),
        };
        if name.is_empty() {
            return Err(bad(format!(
                "--set `{key}`: a part of the key is empty: allowed KEY=VALUE with KEY a scenario \
                 key such as fluid.viscosity_pa_s"
            )));
        }
        match index {
            None if last => {
                cur.insert(name.to_string(), value.take().expect("set once"));
                return Ok(());
            }
            None => {
                let entry = cur
                    .entry(name.to_string())
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()));
                cur = entry
                    .as_table_mut()
                    .ok_or_else(|| bad(format!("--set `{key}`: `{name}` is not a table")))?;
            }
            Some(idx) => {
                let arr = cur
                    .get_mut(name)
                    .and_then(|v| v.as_array_mut())
                    .ok_or_else(|| bad(format!("--set `{key}`: `{name}` is not an array")))?;
                let len = arr.len();
                let elem = arr.get_mut(idx).ok_or_else(|| {
                    bad(format!(
                        "--set `{key}`: index {idx} out of range (`{name}` has {len})"
                    ))
                })?;
                if last {
                    *elem = value.take().expect("set once");
                    return Ok(());
                }
                cur = elem
                    .as_table_mut()
                    .ok_or_else(|| bad(format!("--set `{key}`: `{name}[{idx}]` is not a table")))?;
            }
        }
    }
    Ok(())
}

/// Refuses a `--set KEY=…` of the list `set` whose key is `key`, which `option` (`--fit`,
/// `--vary`) also names: the `--set` value would be overridden, or override, without a word.
pub fn refuse_set_of(set: &[String], key: &str, option: &str) -> Result<(), crate::error::Error> {
    let same = set.iter().find(|s| {
        s.split_once('=')
            .is_some_and(|(k, _)| k.trim() == key.trim())
    });
    match same {
        Some(s) => Err(crate::error::Error::bad_argument(
            "--set",
            std::path::Path::new(s),
            format!(
                "{option} also names `{key}`: one key cannot be both set and {}; drop the \
                 --set or the {option}",
                if option == "--fit" {
                    "fitted"
                } else {
                    "varied"
                }
            ),
        )),
        None => Ok(()),
    }
}
