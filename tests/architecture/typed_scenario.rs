//! Parse, don't validate (issue 24, item 1): the raw scenario (`crate::scenario::Scenario`, the
//! serde form of a scenario file) stops at the loader. `Prepared`, what a scene runs, holds no
//! field of that type (only the typed common part, the kind's spec and the record of the run,
//! kept private), and no file under `src/scenes/` names the type, so that a scene can read only
//! its typed spec. Both are read from the source text, comments and string literals excluded.

use super::shape::strip;
use super::sources;
use std::path::Path;

/// The raw scenario's type name.
const RAW: &str = "Scenario";

/// Whether the code `code` names the identifier `word` (not as part of a longer identifier:
/// `ScenarioError`, `scenario` do not count).
fn names(code: &str, word: &str) -> bool {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    code.match_indices(word).any(|(at, _)| {
        let before = code[..at].chars().next_back();
        let after = code[at + word.len()..].chars().next();
        !before.is_some_and(ident) && !after.is_some_and(ident)
    })
}

/// The lines of code (1-based line, text) of the body of `pub struct Prepared { … }` in `text`,
/// None if `text` does not define it.
fn prepared_fields(text: &str) -> Option<Vec<(usize, String)>> {
    let lines: Vec<&str> = text.lines().collect();
    let start = lines
        .iter()
        .position(|l| strip(l).trim_start().starts_with("pub struct Prepared {"))?;
    let mut out = Vec::new();
    for (i, l) in lines.iter().enumerate().skip(start + 1) {
        let code = strip(l);
        if code.trim_start().starts_with('}') {
            break;
        }
        if !code.trim().is_empty() {
            out.push((i + 1, code));
        }
    }
    Some(out)
}

/// What is wrong with the fields of `Prepared` in `text` (the file `file`): a field whose type
/// names the raw scenario, public or not.
fn prepared_violations(file: &Path, text: &str) -> Vec<String> {
    let Some(fields) = prepared_fields(text) else {
        return Vec::new();
    };
    fields
        .into_iter()
        .filter_map(|(line, code)| {
            let (name, ty) = code.split_once(':')?;
            names(ty, RAW).then(|| {
                let public = name.trim_start().starts_with("pub");
                format!(
                    "{}:{line}: Prepared has a {} field of the raw type `{RAW}`: {}",
                    file.display(),
                    if public { "public" } else { "private" },
                    code.trim()
                )
            })
        })
        .collect()
}

/// Every line of `text` (the file `file` under `src/scenes/`) that names the raw scenario.
fn scene_violations(file: &Path, text: &str) -> Vec<String> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| names(&strip(l), RAW))
        .map(|(i, l)| {
            format!(
                "{}:{}: names the raw `{RAW}`: {}",
                file.display(),
                i + 1,
                l.trim()
            )
        })
        .collect()
}

#[test]
fn prepared_holds_no_raw_scenario() {
    let mut found = false;
    let mut bad = Vec::new();
    for (rel, text) in sources() {
        if prepared_fields(&text).is_some() {
            found = true;
            bad.extend(prepared_violations(&rel, &text));
        }
    }
    assert!(
        found,
        "no `pub struct Prepared {{` under src/: the test lost its target"
    );
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn scenes_never_name_the_raw_scenario() {
    let mut bad = Vec::new();
    let mut files = 0;
    for (rel, text) in sources() {
        if rel.starts_with("scenes") {
            files += 1;
            bad.extend(scene_violations(&rel, &text));
        }
    }
    assert!(files > 20, "{files} files under src/scenes/");
    assert!(
        bad.is_empty(),
        "a scene reads its typed spec (Prepared::common, Prepared::scene), never the raw \
         scenario:\n{}",
        bad.join("\n")
    );
}

/// The checks above on deliberate violations: each is caught, and the lawful forms are not.
#[test]
fn the_checks_catch_a_raw_scenario() {
    let file = Path::new("scenes/mod.rs");
    let prepared = "pub struct Prepared {\n    /// The raw Scenario.\n    pub path: PathBuf,\n    \
                    pub scenario: crate::scenario::Scenario,\n    record: Scenario,\n}\n";
    let v = prepared_violations(file, prepared);
    assert_eq!(v.len(), 2, "{v:?}");
    assert!(v[0].contains(":4: Prepared has a public field"), "{v:?}");
    assert!(v[1].contains(":5: Prepared has a private field"), "{v:?}");
    let clean =
        "pub struct Prepared {\n    pub common: Common,\n    record: crate::scenario::Record,\n}\n";
    assert!(prepared_violations(file, clean).is_empty());
    let scene = "use crate::scenario::{Common, Scenario};\n// a Scenario in a comment\nlet e: ScenarioError = \"Scenario\";\nfn f(s: &Scenario) {}\n";
    let v = scene_violations(file, scene);
    assert_eq!(v.len(), 2, "{v:?}");
    assert!(v[0].contains(":1:") && v[1].contains(":4:"), "{v:?}");
}
