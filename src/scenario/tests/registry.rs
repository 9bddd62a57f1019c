//! The registry of scene kinds (`crate::scenario::KINDS`) holds every kind, and each
//! registered kind has every piece `CONTRIBUTING.md` ("Add a scene kind") asks for: its spec
//! (the example scenario parses into the spec of that kind), its scene (a folder
//! `src/scenes/<folder>/` declared in `src/scenes/mod.rs`, with its `cost.rs`), its reference
//! page `docs/scenarios/<name>.md` naming its outputs, every table it reads documented there or
//! in `docs/scenarios/common.md`, and an example scenario in `scenarios/`. The check is a
//! function of a plain description of a kind, so that a deliberately incomplete kind shows it
//! failing (`an_incomplete_kind_is_named_with_what_it_lacks`).

use crate::scenario::{KindInfo, KINDS};
use std::path::Path;

/// A kind as the check sees it: the registry entry's names and lists.
struct Entry<'a> {
    name: &'a str,
    folder: &'a str,
    example: &'a str,
    tables: &'a [&'a str],
    outputs: &'a [&'a str],
}

impl<'a> From<&'a KindInfo> for Entry<'a> {
    fn from(k: &'a KindInfo) -> Self {
        Entry {
            name: k.name,
            folder: k.folder,
            example: k.example,
            tables: k.tables,
            outputs: k.outputs,
        }
    }
}

/// What kind `k` lacks, one line each, read from the tree at `root` (empty: complete).
fn missing(k: &Entry, root: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let name = k.name;
    // Scene: its folder, declared in scenes/mod.rs, with its cost model.
    let folder = root.join("src/scenes").join(k.folder);
    if !folder.join("mod.rs").is_file() {
        out.push(format!(
            "{name}: scene folder src/scenes/{}/ (mod.rs)",
            k.folder
        ));
    }
    if !folder.join("cost.rs").is_file() {
        out.push(format!(
            "{name}: cost model src/scenes/{}/cost.rs",
            k.folder
        ));
    }
    let scenes = std::fs::read_to_string(root.join("src/scenes/mod.rs")).unwrap_or_default();
    if !scenes.contains(&format!("pub mod {};", k.folder)) {
        out.push(format!(
            "{name}: `pub mod {};` in src/scenes/mod.rs",
            k.folder
        ));
    }
    // Example scenario: present, of this kind, parsing into this kind's spec.
    let example = root.join("scenarios").join(k.example);
    match std::fs::read_to_string(&example) {
        Err(_) => out.push(format!("{name}: example scenario scenarios/{}", k.example)),
        Ok(text) => {
            if !text.contains(&format!("kind = \"{name}\"")) {
                out.push(format!(
                    "{name}: scenarios/{} has kind = \"{name}\"",
                    k.example
                ));
            }
            match crate::scenario::parse(&example, &[]) {
                Ok(p) if p.scene.kind_name() == name => {}
                Ok(p) => out.push(format!(
                    "{name}: spec: scenarios/{} parses into the spec of `{}`",
                    k.example,
                    p.scene.kind_name()
                )),
                Err(e) => out.push(format!("{name}: spec: scenarios/{}: {e}", k.example)),
            }
        }
    }
    // Reference page: present, naming every output and every table (or common.md does).
    let page = root.join("docs/scenarios").join(format!("{name}.md"));
    let Ok(doc) = std::fs::read_to_string(&page) else {
        out.push(format!("{name}: docs page docs/scenarios/{name}.md"));
        return out;
    };
    let common = std::fs::read_to_string(root.join("docs/scenarios/common.md")).unwrap_or_default();
    for t in k.tables {
        let named = |d: &str| d.contains(&format!("`[{t}]`")) || d.contains(&format!("[[{t}]]"));
        if !named(&doc) && !named(&common) {
            out.push(format!(
                "{name}: table [{t}] documented in docs/scenarios/{name}.md or common.md"
            ));
        }
    }
    if k.outputs.is_empty() {
        out.push(format!("{name}: outputs listed in its registry entry"));
    }
    for o in k.outputs {
        if !doc.contains(&format!("`{o}`")) {
            out.push(format!(
                "{name}: output `{o}` named in docs/scenarios/{name}.md"
            ));
        }
    }
    out
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn every_registered_kind_has_every_piece() {
    let lacks: Vec<String> = KINDS
        .iter()
        .flat_map(|k| missing(&Entry::from(k), root()))
        .collect();
    assert!(lacks.is_empty(), "missing:\n{}", lacks.join("\n"));
}

#[test]
fn an_incomplete_kind_is_named_with_what_it_lacks() {
    // A kind registered with a folder, an example and a page that do not exist.
    let ghost = Entry {
        name: "ghost_kind",
        folder: "ghost_kind",
        example: "ghost_kind.toml",
        tables: &["ghost_table"],
        outputs: &["ghost.csv"],
    };
    let lacks = missing(&ghost, root());
    for piece in [
        "ghost_kind: scene folder src/scenes/ghost_kind/",
        "ghost_kind: cost model src/scenes/ghost_kind/cost.rs",
        "ghost_kind: `pub mod ghost_kind;` in src/scenes/mod.rs",
        "ghost_kind: example scenario scenarios/ghost_kind.toml",
        "ghost_kind: docs page docs/scenarios/ghost_kind.md",
    ] {
        assert!(
            lacks.iter().any(|l| l.starts_with(piece)),
            "`{piece}` not reported: {lacks:?}"
        );
    }
    // A real kind with one piece taken away: an output its page does not name, a table no page
    // documents, an example of another kind.
    let tilt = KINDS.iter().find(|k| k.name == "tilt_friction").unwrap();
    let broken = Entry {
        outputs: &["summary.csv", "never_written.csv"],
        tables: &["contacts", "tilt", "undocumented"],
        example: "stokes_single.toml",
        ..Entry::from(tilt)
    };
    let lacks = missing(&broken, root());
    assert_eq!(
        lacks,
        [
            "tilt_friction: scenarios/stokes_single.toml has kind = \"tilt_friction\"",
            "tilt_friction: spec: scenarios/stokes_single.toml parses into the spec of `free_settling`",
            "tilt_friction: table [undocumented] documented in docs/scenarios/tilt_friction.md or common.md",
            "tilt_friction: output `never_written.csv` named in docs/scenarios/tilt_friction.md",
        ],
        "{lacks:#?}"
    );
    assert!(missing(&Entry::from(tilt), root()).is_empty());
}

/// Every variant of the `kind` key (as serde lists them) is registered once, under its name.
#[test]
fn every_kind_is_registered_once_under_its_name() {
    let text = "name = \"t\"\nkind = \"no_such_kind\"\n";
    let e = crate::scenario::load_str(text, Path::new("t.toml"), &[]).unwrap_err();
    let listed = e
        .message
        .split_once("expected one of ")
        .map(|(_, rest)| rest)
        .unwrap_or_else(|| panic!("{e}"));
    let names: Vec<&str> = listed.split('`').skip(1).step_by(2).collect();
    let registered: Vec<&str> = KINDS.iter().map(|k| k.name).collect();
    assert_eq!(names, registered, "serde's kinds against the registry");
    for k in KINDS {
        let kind: crate::scenario::Kind = toml::Value::String(k.name.into()).try_into().unwrap();
        assert_eq!(kind, k.kind, "{}", k.name);
        assert_eq!(kind.name(), k.name);
        assert_eq!(crate::scenario::info(kind).name, k.name);
    }
}

/// Scenes read the typed scenario (`Prepared::common` and their spec), never a raw one: no
/// `.scenario` field access anywhere in `src/scenes/`, their unit tests included (`Prepared` has
/// no such field; `tests/architecture/typed_scenario.rs` checks that no scene names the raw type).
#[test]
fn scenes_read_their_spec_not_the_raw_scenario() {
    fn walk(dir: &Path, out: &mut Vec<String>) {
        for e in std::fs::read_dir(dir).unwrap().flatten() {
            let path = e.path();
            if path.is_dir() {
                walk(&path, out);
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            for (i, line) in text.lines().enumerate() {
                let code = line.split("//").next().unwrap_or("");
                let reads = code.match_indices(".scenario").any(|(at, m)| {
                    let next = code[at + m.len()..].chars().next();
                    !next.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':')
                });
                if reads {
                    out.push(format!("{}:{}: {}", path.display(), i + 1, line.trim()));
                }
            }
        }
    }
    let mut found = Vec::new();
    walk(&root().join("src/scenes"), &mut found);
    assert!(
        found.is_empty(),
        "raw scenario read by a scene:\n{}",
        found.join("\n")
    );
}
