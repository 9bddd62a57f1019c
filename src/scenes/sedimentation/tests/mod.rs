//! Unit tests of the sedimentation cylinder (moved from `tests/scenes/`, `tests/instruments/` and
//! `tests/regression/`): contacts and squeeze-film lubrication between representative grains,
//! the instruments on the simulated cylinder.

mod contacts;
mod ideal_stokes;
mod instruments;
mod issue_12_contacts_honoured;
mod packed;

pub(super) use crate::scenes::tests::prepare;
