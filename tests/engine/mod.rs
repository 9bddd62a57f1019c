//! `src/engine/`: the Rapier worlds.

mod faults;
mod free_settling;
mod rest;
