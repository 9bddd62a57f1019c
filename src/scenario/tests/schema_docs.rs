//! The scenario reference (`docs/scenarios/*.md`) documents every key the schema accepts (moved
//! from `tests/scenario/schema_docs.rs`).
//!
//! The keys come from the code, not from a list: [`trace`] drives the `Deserialize`
//! implementation of [`crate::scenario::Scenario`] with a deserializer of its own that records
//! what serde asks for. A derived `Deserialize` of a struct hands the deserializer the names of
//! all its fields (`deserialize_struct(name, FIELDS, visitor)`, after `rename` and `rename_all`),
//! and of an enum the names of all its variants; the tracer answers every field with a value of
//! the type serde asks for (`Some` for options, one element for lists, the first variant of an
//! enum, 3 for integers so that `dimension` (`try_from = "i64"`) reads), so it walks into every
//! nested table. A field added to any schema struct therefore appears here without any list to
//! update. No dependency is needed: serde's data model is enough, and the schema uses no
//! `flatten`, `untagged` or data-carrying enum (the tracer refuses one, naming it).
//!
//! Which kinds accept a table also comes from the code: a scenario holding only that table is
//! loaded for each kind, and the loader refuses a table its kind does not use before anything
//! else is checked.
//!
//! The reference format: a section per table, its heading holding `` `[table]` `` (or
//! `` `[[table]]` ``, or the words "Top-level keys"), and one markdown table row per key,
//! `` | `key` | unit | default | allowed | meaning | ``. `common.md` holds the tables several
//! kinds share, each section with a line `Used by: …` naming those kinds.

use std::cell::RefCell;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde::de::{self, value::Error, DeserializeSeed, IntoDeserializer, Visitor};
use serde::Deserialize;

/// What serde asked for at one key path.
#[derive(Clone, Debug, Default)]
struct Leaf {
    /// The names of the enum's variants, if the value (or a list's element) is an enum.
    variants: Vec<&'static str>,
}

type Paths = RefCell<BTreeMap<String, Leaf>>;

/// A deserializer that records the key path of every value serde asks for.
struct Tracer<'a> {
    path: String,
    out: &'a Paths,
}

impl<'a> Tracer<'a> {
    fn record(&self, variants: &'static [&'static str]) {
        let mut out = self.out.borrow_mut();
        let leaf = out.entry(self.path.clone()).or_default();
        for v in variants {
            if !leaf.variants.contains(v) {
                leaf.variants.push(v);
            }
        }
    }
    fn child(&self, field: &str) -> Tracer<'a> {
        let path = if self.path.is_empty() {
            field.to_string()
        } else {
            format!("{}.{field}", self.path)
        };
        Tracer {
            path,
            out: self.out,
        }
    }
}

macro_rules! leaf {
    ($($method:ident => $visit:ident($($value:expr)?)),* $(,)?) => {
        $(fn $method<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
            self.record(&[]);
            v.$visit($($value)?)
        })*
    };
}

impl<'de> de::Deserializer<'de> for Tracer<'_> {
    type Error = Error;

    leaf! {
        deserialize_bool => visit_bool(true),
        deserialize_i8 => visit_i64(3), deserialize_i16 => visit_i64(3),
        deserialize_i32 => visit_i64(3), deserialize_i64 => visit_i64(3),
        deserialize_u8 => visit_u64(3), deserialize_u16 => visit_u64(3),
        deserialize_u32 => visit_u64(3), deserialize_u64 => visit_u64(3),
        deserialize_f32 => visit_f64(1.0), deserialize_f64 => visit_f64(1.0),
        deserialize_char => visit_char('x'), deserialize_str => visit_str("x"),
        deserialize_string => visit_str("x"), deserialize_bytes => visit_bytes(b"x"),
        deserialize_byte_buf => visit_bytes(b"x"), deserialize_unit => visit_unit(),
        deserialize_identifier => visit_str("x"), deserialize_ignored_any => visit_unit(),
    }

    fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Error> {
        Err(de::Error::custom(format!(
            "`{}`: a self-describing value (deserialize_any): extend the tracer",
            self.path
        )))
    }
    fn deserialize_option<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        v.visit_some(self)
    }
    fn deserialize_unit_struct<V: Visitor<'de>>(
        self,
        _: &'static str,
        v: V,
    ) -> Result<V::Value, Error> {
        self.deserialize_unit(v)
    }
    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _: &'static str,
        v: V,
    ) -> Result<V::Value, Error> {
        v.visit_newtype_struct(self)
    }
    fn deserialize_seq<V: Visitor<'de>>(self, v: V) -> Result<V::Value, Error> {
        self.record(&[]);
        v.visit_seq(One(Some(self)))
    }
    fn deserialize_tuple<V: Visitor<'de>>(self, _: usize, v: V) -> Result<V::Value, Error> {
        self.deserialize_seq(v)
    }
    fn deserialize_tuple_struct<V: Visitor<'de>>(
        self,
        _: &'static str,
        _: usize,
        v: V,
    ) -> Result<V::Value, Error> {
        self.deserialize_seq(v)
    }
    fn deserialize_map<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Error> {
        Err(de::Error::custom(format!(
            "`{}`: a map with free keys: extend the tracer",
            self.path
        )))
    }
    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _: &'static str,
        fields: &'static [&'static str],
        v: V,
    ) -> Result<V::Value, Error> {
        v.visit_map(Fields {
            tracer: self,
            fields: fields.iter(),
            current: "",
        })
    }
    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _: &'static str,
        variants: &'static [&'static str],
        v: V,
    ) -> Result<V::Value, Error> {
        self.record(variants);
        v.visit_enum(Variant(self.path.clone(), variants[0]))
    }
}

/// A list of one element.
struct One<'a>(Option<Tracer<'a>>);

impl<'de> de::SeqAccess<'de> for One<'_> {
    type Error = Error;
    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, Error> {
        self.0.take().map(|t| seed.deserialize(t)).transpose()
    }
}

/// Every field of a struct, each with a traced value.
struct Fields<'a> {
    tracer: Tracer<'a>,
    fields: std::slice::Iter<'static, &'static str>,
    current: &'static str,
}

impl<'de> de::MapAccess<'de> for Fields<'_> {
    type Error = Error;
    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, Error> {
        let Some(&f) = self.fields.next() else {
            return Ok(None);
        };
        self.current = f;
        seed.deserialize(f.into_deserializer()).map(Some)
    }
    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, Error> {
        seed.deserialize(self.tracer.child(self.current))
    }
}

/// The first variant of an enum; only unit variants are traced.
struct Variant(String, &'static str);

impl<'de> de::EnumAccess<'de> for Variant {
    type Error = Error;
    type Variant = Self;
    fn variant_seed<V: DeserializeSeed<'de>>(self, seed: V) -> Result<(V::Value, Self), Error> {
        let name: de::value::StrDeserializer<Error> = self.1.into_deserializer();
        Ok((seed.deserialize(name)?, self))
    }
}

impl<'de> de::VariantAccess<'de> for Variant {
    type Error = Error;
    fn unit_variant(self) -> Result<(), Error> {
        Ok(())
    }
    fn newtype_variant_seed<T: DeserializeSeed<'de>>(self, _: T) -> Result<T::Value, Error> {
        Err(self.data_carrying())
    }
    fn tuple_variant<V: Visitor<'de>>(self, _: usize, _: V) -> Result<V::Value, Error> {
        Err(self.data_carrying())
    }
    fn struct_variant<V: Visitor<'de>>(
        self,
        _: &'static [&'static str],
        _: V,
    ) -> Result<V::Value, Error> {
        Err(self.data_carrying())
    }
}

impl Variant {
    fn data_carrying(&self) -> Error {
        de::Error::custom(format!(
            "`{}`: the variant `{}` carries data: extend the tracer to trace every variant",
            self.0, self.1
        ))
    }
}

/// Every leaf key path of the scenario schema (`fluid.density_kg_m3`, `spheres.diameter_m` for
/// the tables of `[[spheres]]`, `name`), with the variants of the enum keys.
fn trace() -> BTreeMap<String, Leaf> {
    let out = Paths::default();
    crate::scenario::Scenario::deserialize(Tracer {
        path: String::new(),
        out: &out,
    })
    .expect("the tracer walks the whole schema");
    let all = out.into_inner();
    let parents: BTreeSet<String> = all
        .keys()
        .filter_map(|k| k.rsplit_once('.').map(|(p, _)| p.to_string()))
        .collect();
    all.into_iter()
        .filter(|(k, _)| !parents.contains(k))
        .collect()
}

/// The table of a key path (`""` for a top-level key) and the key within it.
fn split(path: &str) -> (&str, &str) {
    path.rsplit_once('.').unwrap_or(("", path))
}

/// Whether kind `kind` accepts the top-level table `table` (every kind accepts the top-level
/// keys): the loader refuses a table the kind does not use before it parses anything else.
fn accepts(kind: &str, table: &str) -> bool {
    if table.is_empty() {
        return true;
    }
    let text = format!("name = \"t\"\nkind = \"{kind}\"\n[{table}]\n");
    match crate::scenario::load_str(&text, Path::new("t.toml"), &[]) {
        Ok(_) => true,
        Err(e) => !e.message.contains("is not used by kind"),
    }
}

/// One documented key: its section's table, the key, the cells of its row, and where.
struct Row {
    table: String,
    key: String,
    cells: Vec<String>,
    at: String,
}

/// A reference file: its key rows, and the `Used by:` line of each section.
struct Doc {
    rows: Vec<Row>,
    used_by: BTreeMap<String, String>,
    text: String,
}

fn docs_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/scenarios")
}

/// Reads a reference file: sections by heading, key rows by their first cell.
fn read_doc(name: &str) -> Doc {
    let path = docs_dir().join(name);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (every kind needs its reference)", path.display()));
    let mut table: Option<String> = None;
    let mut rows = Vec::new();
    let mut used_by = BTreeMap::new();
    for (i, line) in text.lines().enumerate() {
        let at = format!("docs/scenarios/{name}:{}", i + 1);
        if line.starts_with('#') {
            table = if line.contains("Top-level keys") {
                Some(String::new())
            } else {
                line.split('`').find_map(|w| {
                    let w = w.trim_start_matches('[').trim_end_matches(']');
                    (line.contains(&format!("`[{w}]`")) || line.contains(&format!("`[[{w}]]`")))
                        .then(|| w.to_string())
                })
            };
        } else if let (Some(t), Some(rest)) = (&table, line.strip_prefix("Used by:")) {
            used_by.insert(t.clone(), rest.to_string());
        } else if let (Some(t), Some(rest)) = (&table, line.strip_prefix("| `")) {
            let key = rest.split('`').next().unwrap_or("").to_string();
            // `\|` is a pipe inside a cell.
            let cells: Vec<String> = line
                .replace("\\|", "¦")
                .trim()
                .trim_matches('|')
                .split('|')
                .map(|c| c.trim().to_string())
                .collect();
            rows.push(Row {
                table: t.clone(),
                key,
                cells,
                at,
            });
        }
    }
    Doc {
        rows,
        used_by,
        text,
    }
}

/// The kinds, from the variants of the `kind` key.
fn kinds(schema: &BTreeMap<String, Leaf>) -> Vec<&'static str> {
    schema["kind"].variants.clone()
}

/// Every key the schema accepts is documented, for every kind that accepts it, in the kind's
/// reference or in `common.md` (which the kind's reference links to), in a row with a unit, a
/// default, an allowed range and a meaning; an enum key's row names every allowed value.
#[test]
fn every_schema_key_is_documented_for_every_kind_that_accepts_it() {
    let schema = trace();
    assert!(
        schema.contains_key("fluid.density_kg_m3") && schema.contains_key("spheres.diameter_m")
    );
    assert!(schema.len() > 100, "{} keys traced", schema.len());
    let common = read_doc("common.md");
    let mut missing = Vec::new();
    for kind in kinds(&schema) {
        let doc = read_doc(&format!("{kind}.md"));
        assert!(
            doc.text.contains("(common.md)"),
            "docs/scenarios/{kind}.md must link to common.md"
        );
        for (path, leaf) in &schema {
            let (table, key) = split(path);
            if !accepts(kind, table) {
                continue;
            }
            let row = doc
                .rows
                .iter()
                .chain(&common.rows)
                .find(|r| r.table == table && r.key == key);
            let Some(row) = row else {
                missing.push(format!("{kind}: `{path}`"));
                continue;
            };
            assert!(
                row.cells.len() == 5 && row.cells.iter().all(|c| !c.is_empty()),
                "{}: `{path}` needs five filled cells (key, unit, default, allowed, meaning): {:?}",
                row.at,
                row.cells
            );
            for v in &leaf.variants {
                assert!(
                    row.cells[3].contains(&format!("`{v}`")),
                    "{}: the allowed values of `{path}` must name `{v}`",
                    row.at
                );
            }
        }
    }
    assert!(
        missing.is_empty(),
        "keys the schema accepts but docs/scenarios/ does not document:\n{}",
        missing.join("\n")
    );
}

/// No documented key is stale: each row names a key of its section's table, in a reference of
/// a kind that accepts that table; each section of `common.md` says which kinds use it, and
/// that is exactly the kinds that accept it.
#[test]
fn every_documented_key_exists_and_is_accepted_where_it_is_documented() {
    let schema = trace();
    let kinds = kinds(&schema);
    let mut files: Vec<(String, Vec<&str>)> = kinds
        .iter()
        .map(|k| (format!("{k}.md"), vec![*k]))
        .collect();
    files.push(("common.md".to_string(), kinds.clone()));
    for (file, file_kinds) in files {
        let doc = read_doc(&file);
        for r in &doc.rows {
            let path = if r.table.is_empty() {
                r.key.clone()
            } else {
                format!("{}.{}", r.table, r.key)
            };
            assert!(
                schema.contains_key(&path),
                "{}: `{path}` is not a key of the schema",
                r.at
            );
            assert!(
                file_kinds.iter().any(|k| accepts(k, &r.table)),
                "{}: `{path}` is documented for a kind that refuses [{}]",
                r.at,
                r.table
            );
        }
        if file != "common.md" {
            continue;
        }
        let tables: BTreeSet<&str> = doc.rows.iter().map(|r| r.table.as_str()).collect();
        for t in tables {
            let line = doc.used_by.get(t).unwrap_or_else(|| {
                panic!("common.md: the section of [{t}] needs a `Used by:` line")
            });
            let users: Vec<&str> = kinds.iter().copied().filter(|k| accepts(k, t)).collect();
            if users.len() == kinds.len() {
                assert!(
                    line.contains("every kind"),
                    "common.md [{t}]: used by every kind: {line}"
                );
            } else {
                for k in &kinds {
                    assert_eq!(
                        line.contains(&format!("`{k}`")),
                        users.contains(k),
                        "common.md [{t}]: `Used by:` must list exactly {users:?}: {line}"
                    );
                }
            }
        }
    }
}

/// Each kind's page lists, after `- Refused:`, exactly the top-level tables its kind refuses.
#[test]
fn each_kind_page_lists_the_tables_its_kind_refuses() {
    let schema = trace();
    let tables: BTreeSet<&str> = schema
        .keys()
        .filter_map(|k| k.split_once('.'))
        .map(|(t, _)| t)
        .collect();
    for kind in kinds(&schema) {
        let doc = read_doc(&format!("{kind}.md"));
        let start = doc
            .text
            .find("- Refused:")
            .unwrap_or_else(|| panic!("{kind}.md: no `- Refused:` list"));
        let rest = &doc.text[start..];
        let end = rest.find("\n\n").unwrap_or(rest.len());
        let listed: BTreeSet<&str> = rest[..end]
            .split('`')
            .skip(1)
            .step_by(2)
            .map(|w| w.trim_start_matches('[').trim_end_matches(']'))
            .collect();
        let refused: BTreeSet<&str> = tables
            .iter()
            .copied()
            .filter(|t| !accepts(kind, t))
            .collect();
        assert_eq!(listed, refused, "{kind}.md: the `- Refused:` list");
    }
}

/// The tracer sees what serde sees: nested tables, lists of tables, enum values, and a field
/// of a table read through `#[serde(default)]` on the whole struct (`[instruments]`).
#[test]
fn the_tracer_finds_nested_keys_and_enum_values() {
    let schema = trace();
    for k in [
        "name",
        "dimension",
        "spheres.diameter_m",
        "spheres_csv.path",
        "instruments.pipette_volume_m3",
        "sample.lubrication_inner_cutoff",
        "sweep.integrators",
    ] {
        assert!(schema.contains_key(k), "`{k}` not traced");
    }
    assert!(
        !schema.contains_key("spheres"),
        "a list of tables is not a leaf"
    );
    assert_eq!(
        schema["sweep.integrators"].variants,
        ["explicit", "implicit", "exponential"]
    );
    assert!(schema["drag.law"].variants.contains(&"bingham-fedem"));
    assert!(accepts("sedimentation", "sample") && !accepts("free_settling", "sample"));
}
