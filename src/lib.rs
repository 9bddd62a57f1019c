//! # settle
//!
//! Solid particles settling in Newtonian and Bingham fluids. Fluid forces (buoyancy, drag,
//! yield-stress drag) act as body forces on the particles of a DEM scene, after f-EDEM
//! (Zhang & Li 2024) and the one-way coupled hydrometer DEM of seed 000.

pub mod bench;
pub mod checkpoint;
pub mod cli;
pub mod contact;
pub mod dynamics;
pub mod engine;
pub mod error;
pub mod fluid;
pub mod instruments;
pub mod interrupt;
pub mod io;
pub mod output;
pub mod progress;
pub mod run;
pub mod sample;
pub mod scenario;
pub mod scenes;
pub mod sweep;
pub mod sweep_cmd;
