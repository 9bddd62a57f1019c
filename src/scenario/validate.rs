//! Validation of a parsed scenario: which tables its kind uses, then each table's checks (which
//! sit next to their structs in [`super::schema`]), then the rules between tables. Each failure
//! names the file, the key and the allowed range.

use super::check::Check;
use super::kinds::{info, SceneSpec, KINDS};
use super::schema::*;
use crate::error::BadInput;
use std::path::Path;

/// Whether `key` is an optional top-level table: one a kind of [`KINDS`] lists among its
/// tables (a table no kind lists is read by every kind, or is a plain key).
fn optional_table(key: &str) -> bool {
    KINDS.iter().any(|k| k.tables.contains(&key))
}

/// Whether the top-level key `key` may appear in a scenario of `kind`: the plain keys and the
/// tables every kind uses always, an optional table for the kinds that list it.
pub fn table_used_by(key: &str, kind: Kind) -> bool {
    !optional_table(key) || info(kind).tables.contains(&key)
}

/// Refuses a top-level table (of `present`, the keys of the file after `--set`) that `kind`
/// does not use, naming the table and the kind and listing the tables it uses.
pub fn check_tables(kind: Kind, present: &[&str], file: &Path) -> Result<(), BadInput> {
    for key in present {
        if !table_used_by(key, kind) {
            let used: Vec<String> = info(kind).tables.iter().map(|t| format!("[{t}]")).collect();
            return Err(BadInput::new(
                file,
                Some(key),
                format!(
                    "the [{key}] table is not used by kind = \"{}\" (allowed: [fluid], [drag], [time]{}{})",
                    kind.name(),
                    if used.is_empty() { "" } else { ", " },
                    used.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

/// Validates ranges and cross-table rules, and builds the typed parts of the scenario: the
/// spec of its kind and the rheology of its fluid.
pub fn validate(s: &Scenario, file: &Path) -> Result<(SceneSpec, RheologyModel), BadInput> {
    let c = Check { file };
    s.check_common(&c)?;
    let rheology = s.fluid.check(&c)?;
    s.drag.check(&c, &s.fluid, s.physics)?;
    s.time.check(&c)?;
    if let Some(ct) = &s.container {
        ct.check(&c, s.dimension)?;
    }
    s.release.check(&c, s)?;
    let scene = (info(s.kind).spec)(&c, s)?;
    if let Some(ct) = &s.contacts {
        ct.check(&c)?;
    }
    if let Some(r) = &s.repeats {
        r.check(&c)?;
    }
    if info(s.kind).needs_spheres && s.spheres.is_empty() && s.spheres_csv.is_none() {
        return Err(c.err(
            "spheres",
            "missing: give at least one [[spheres]] table or a [spheres_csv] file",
        ));
    }
    for (i, sp) in s.spheres.iter().enumerate() {
        sp.check(&c, &format!("spheres[{i}]"), s)?;
    }
    if let Some(m) = &s.measure {
        let h = s
            .container
            .as_ref()
            .map(|c| c.height_m)
            .unwrap_or(f64::INFINITY);
        m.check(&c, h, s.time.end_s)?;
    }
    s.record.check(&c, s.time.end_s)?;
    if let Some(t) = &s.transient {
        t.check(&c, s)?;
    }
    if let Some(sw) = &s.sweep {
        sw.check(&c, s.time.end_s)?;
    }
    Ok((scene, rheology))
}
