//! `src/engine/`: the Rapier worlds.

mod added_mass;
mod faults;
mod free_settling;
mod rest;
