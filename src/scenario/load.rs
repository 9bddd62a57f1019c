//! Loading a scenario: TOML parsing, `--set KEY=VALUE` overrides, schema errors that name the
//! file and the key, then validation of ranges.

use super::schema::Scenario;
use super::spec::Parsed;
use super::validate::check_tables;
use std::path::Path;

/// A scenario that cannot be run: one line naming the file, the key and what is allowed. The
/// crate's one bad-input type (exit 2), [`crate::error::BadInput`].
pub type ScenarioError = crate::error::BadInput;

/// Reads, overrides, parses and validates a scenario file. `overrides` are `KEY=VALUE` strings
/// (`fluid.viscosity_pa_s=0.002`, `spheres[0].diameter_m=1e-4`, `physics=ideal-stokes`).
pub fn load(path: &Path, overrides: &[String]) -> Result<Scenario, ScenarioError> {
    parse(path, overrides).map(|p| p.scenario)
}

/// As [`load`], from the text of a file; `path` names it in errors.
pub fn load_str(text: &str, path: &Path, overrides: &[String]) -> Result<Scenario, ScenarioError> {
    parse_str(text, path, overrides).map(|p| p.scenario)
}

/// As [`load`], with the typed parts of the scenario: the spec of its kind and its rheology.
pub fn parse(path: &Path, overrides: &[String]) -> Result<Parsed, ScenarioError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| ScenarioError::new(path, None, format!("cannot read the file: {e}")))?;
    parse_str(&text, path, overrides)
}

/// As [`parse`], from the text of a file; `path` names it in errors.
pub fn parse_str(text: &str, path: &Path, overrides: &[String]) -> Result<Parsed, ScenarioError> {
    let mut table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
        let line = e
            .span()
            .map(|s| format!("line {}: ", text[..s.start].lines().count().max(1)))
            .unwrap_or_default();
        ScenarioError::new(
            path,
            None,
            format!("TOML syntax error: {line}{}", e.message()),
        )
    })?;
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
    let value = toml::Value::Table(table);
    let scenario: Scenario = serde_path_to_error::deserialize(value).map_err(|e| {
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
        let key = if key == "." { None } else { Some(key) };
        ScenarioError::new(path, key.as_deref(), msg)
    })?;
    Parsed::new(scenario, path)
}

/// Applies one `KEY=VALUE` override to a TOML table. The value is parsed as TOML (number,
/// boolean, array, quoted string) and otherwise taken as a bare string. Keys are dotted paths;
/// `name[i]` indexes an array of tables. Missing tables are created.
pub fn apply_override(
    table: &mut toml::Table,
    assignment: &str,
    path: &Path,
) -> Result<(), ScenarioError> {
    let bad = |m: String| ScenarioError::new(path, None, m);
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
            return Err(bad(format!("--set `{key}`: empty key segment")));
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
