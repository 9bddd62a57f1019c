//! Unit tests of the scenario (moved from `tests/scenario/`): the registry of kinds, the
//! spheres CSV reader.

mod registry;
mod spheres_csv;
