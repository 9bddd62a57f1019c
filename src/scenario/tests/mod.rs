//! Unit tests of the scenario (moved from `tests/scenario/`): the registry of kinds, the
//! spheres CSV reader.

mod issue_12_csv_columns_named_like_keys;
mod issue_13_end_time_trims_defaults;
mod registry;
mod spheres_csv;
