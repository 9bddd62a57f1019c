//! Unit tests of the Rapier worlds (moved from `tests/engine/`): free fall against the analytic
//! Stokes solution, rest on a floor, added mass, faults.

mod added_mass;
mod faults;
mod rest;
