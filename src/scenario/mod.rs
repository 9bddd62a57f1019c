//! Scenario files: the TOML schema, loading with `--set` overrides, and validation.
//!
//! A scenario names its kind, dimension, fluid, drag law, time settings, bodies and what to
//! record. Every quantity is in SI units with the unit in the key name. Unknown keys are errors.
//! See `README.md` ("Scenario format") for a commented example of every table.

pub mod cost;
mod load;
mod schema;
mod validate;

pub use load::{apply_override, load, load_str, ScenarioError};
pub use schema::*;
pub(crate) use validate::check_sphere;
