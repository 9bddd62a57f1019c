//! Unit tests of the scenario (moved from `tests/scenario/` and `tests/regression/`): the registry
//! of kinds, the input CSV readers, the schema against its reference pages, the loader under
//! random mutations.

mod fuzz;
mod issue_12_csv_columns_named_like_keys;
mod issue_13_end_time_trims_defaults;
mod reference_csv;
mod registry;
mod sample_csv;
mod schema_docs;
mod spheres_csv;
mod transient_rapier;
