//! Scenario files: the TOML schema, loading with `--set` overrides, validation, and the input
//! files a scenario names (spheres CSV, sample CSV).
//!
//! A scenario names its kind, dimension, fluid, drag law, time settings, bodies and what to
//! record. Every quantity is in SI units with the unit in the key name. Unknown keys are errors,
//! and so is a table the kind does not use. `docs/scenarios/<kind>.md` documents every key of
//! every kind (unit, default, allowed range), checked against this schema by
//! `src/scenario/tests/schema_docs.rs`.
//!
//! Parse, don't validate: [`parse`] returns a [`Parsed`] scenario with the typed parts the
//! scenes take: the [`Common`] part every kind reads (its fluid as a [`RheologyModel`] and a
//! density, its drag as a [`crate::fluid::DragLaw`], the engine resolved) and the [`SceneSpec`]
//! of its kind (every table the kind needs present and checked, its input files read); the
//! dimension is read straight into a [`Dim`]. The raw [`Scenario`] stops here: beside the typed
//! parts it leaves this module only as an opaque [`Record`], the effective scenario written to
//! `run.toml`.
//!
//! What a kind is (its name, tables, spec, scene folder, example, outputs) is written once, in
//! the registry [`KINDS`].

mod check;
mod common;
pub mod inputs;
mod kinds;
mod load;
mod schema;
#[cfg(test)]
mod tests;
mod validate;

pub use common::Common;
pub use kinds::{info, sweepable_names, SceneSpec};
pub use load::{is_key_path, parse_str, refuse_set_of, Overrides, Parsed, Record};
pub(crate) use schema::check_sphere;
pub use schema::*;
// Re-exported for the unit tests only.
#[cfg(test)]
pub(crate) use kinds::{KindInfo, KINDS};
#[cfg(test)]
pub(crate) use load::{load, load_str, parse};
