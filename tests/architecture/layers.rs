//! The crate's layers (see the crate doc of `src/lib.rs`): each module may import only from its
//! own layer or the layers below it,
//!
//! | layer | modules |
//! |---|---|
//! | 0 infrastructure | `error`, `numerics`, `io`, `checkpoint`, `interrupt`, `progress` |
//! | 1 physics | `fluid`, `contact`, `dynamics`, `sample`, `instruments` |
//! | 2 engine | `engine` |
//! | 3 scenario | `scenario` |
//! | 4 scenes | `scenes` |
//! | 5 application | `api`, `run`, `sweep`, `bench`, `reduce`, `invert`, `laws`, `fit`, `slurm`, `cli` |
//!
//! Every `crate::X` path in the code of `src/` (comments excluded) is checked against this table.
//! A module missing from the table fails the test too, so a new top-level module must be placed.

use super::sources;
use std::path::{Path, PathBuf};

/// The layer of a top-level module of the crate, or None if the table does not place it.
fn layer(module: &str) -> Option<u8> {
    Some(match module {
        "error" | "numerics" | "io" | "checkpoint" | "interrupt" | "progress" => 0,
        "fluid" | "contact" | "dynamics" | "sample" | "instruments" => 1,
        "engine" => 2,
        "scenario" => 3,
        "scenes" => 4,
        "api" | "run" | "sweep" | "bench" | "reduce" | "invert" | "laws" | "fit" | "slurm"
        | "cli" => 5,
        _ => return None,
    })
}

/// The top-level module a source file belongs to (`src/fluid/drag.rs` → `fluid`), None for the
/// crate roots `lib.rs` and `main.rs`.
fn module_of(rel: &Path) -> Option<String> {
    let mut parts = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned());
    let first = parts.next()?;
    if first == "lib.rs" || first == "main.rs" {
        return None;
    }
    Some(first.trim_end_matches(".rs").to_string())
}

/// The top-level modules named by `crate::` paths in one line of code (`crate::a::b`,
/// `crate::{a::B, c}`, nested groups included).
fn crate_refs(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = line;
    while let Some(i) = rest.find("crate::") {
        // `settle::crate::` cannot occur; skip identifiers that merely end in `crate`.
        let before = rest[..i].chars().last();
        rest = &rest[i + "crate::".len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        if let Some(group) = rest.strip_prefix('{') {
            // Top-level names of a group: split at commas at brace depth 0.
            let mut depth = 0usize;
            let mut item = String::new();
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        out.push(first_ident(&item));
                        item.clear();
                        continue;
                    }
                    _ => {}
                }
                if depth == 0 || c != '{' {
                    item.push(c);
                }
            }
            out.push(first_ident(&item));
        } else {
            out.push(first_ident(rest));
        }
    }
    out.retain(|m| !m.is_empty() && m != "self");
    out
}

fn first_ident(s: &str) -> String {
    s.trim_start()
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect()
}

/// Every import that breaks the table, as `file:line: module (layer) imports target (layer)`.
fn violations(files: &[(PathBuf, String)]) -> Vec<String> {
    let mut bad = Vec::new();
    for (rel, text) in files {
        let Some(module) = module_of(rel) else {
            continue;
        };
        let Some(own) = layer(&module) else {
            bad.push(format!(
                "{}: module `{module}` is not in the layer table",
                rel.display()
            ));
            continue;
        };
        for (n, line) in text.lines().enumerate() {
            let code = line.trim_start();
            if code.starts_with("//") {
                continue;
            }
            let code = code.split(" //").next().unwrap_or(code);
            for target in crate_refs(code) {
                match layer(&target) {
                    Some(l) if l <= own => {}
                    Some(l) => bad.push(format!(
                        "{}:{}: `{module}` (layer {own}) imports `{target}` (layer {l})",
                        rel.display(),
                        n + 1
                    )),
                    None => bad.push(format!(
                        "{}:{}: `{target}` is not in the layer table",
                        rel.display(),
                        n + 1
                    )),
                }
            }
        }
    }
    bad
}

#[test]
fn every_import_respects_the_layer_table() {
    let files = sources();
    assert!(files.len() > 20, "found only {} source files", files.len());
    let bad = violations(&files);
    assert!(
        bad.is_empty(),
        "imports against the layers:\n{}",
        bad.join("\n")
    );
}

#[test]
fn a_forbidden_import_is_caught() {
    let case = |path: &str, text: &str| violations(&[(PathBuf::from(path), text.to_string())]);
    // Physics importing the application layer, in each spelling.
    assert_eq!(case("fluid/drag.rs", "use crate::run::Prepared;").len(), 1);
    assert_eq!(
        case("fluid/drag.rs", "use crate::{dynamics::X, scenes::Y};").len(),
        1
    );
    assert_eq!(
        case(
            "engine/world/mod.rs",
            "    let x = crate::scenario::Submergence::Full;"
        )
        .len(),
        1
    );
    assert_eq!(
        case("io/mod.rs", "use crate::{fluid::{a, b}, error::E};").len(),
        1
    );
    // Allowed: downward and same-layer imports; comments; the crate roots.
    assert!(case(
        "scenes/x.rs",
        "use crate::{engine::dim2, fluid::{a, b}, io};"
    )
    .is_empty());
    assert!(case("dynamics/mod.rs", "use crate::fluid::DragLaw;").is_empty());
    assert!(case("fluid/drag.rs", "/// see [`crate::run::Prepared`]").is_empty());
    assert!(case("lib.rs", "use crate::cli;").is_empty());
    // A module the table does not place.
    assert_eq!(case("widgets.rs", "").len(), 1);
}
