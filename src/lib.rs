//! # settle
//!
//! Solid particles settling in Newtonian and Bingham fluids. Fluid forces (buoyancy, drag,
//! yield-stress drag) act as body forces on the particles of a DEM scene, after f-EDEM
//! (Zhang & Li 2024) and the one-way coupled hydrometer DEM of seed 000.
//!
//! # Layers
//!
//! Each layer imports only from its own layer and the layers above it in this table
//! (`tests/architecture/layers.rs` checks every `crate::` path in `src/` against it):
//!
//! | layer | modules | what |
//! |---|---|---|
//! | 0 infrastructure | [`error`], [`numerics`], [`io`], [`checkpoint`], [`interrupt`], [`progress`] | the error type and exit codes, bracketing root finders, staged output folders, atomic writes, charts, checkpoints, interruption, progress bars; no domain types |
//! | 1 physics | [`fluid`], [`contact`], [`dynamics`], [`sample`], [`instruments`] | pure functions with their equations: no I/O, no Rapier |
//! | 2 engine | [`engine`] | the Rapier worlds |
//! | 3 scenario | [`scenario`] | schema, loading, validation, input files, the typed scenario and the registry of kinds |
//! | 4 scenes | [`scenes`] | one folder per kind (its scene and its cost), and the scene API ([`scenes::Prepared`], [`scenes::RunContext`], [`scenes::SceneReport`]) |
//! | 5 application | [`api`], [`run`], [`sweep`], [`bench`](mod@bench), [`reduce`], [`invert`], [`laws`], [`fit`], [`cli`] | the commands |

// Layer 0: infrastructure.
pub mod checkpoint;
pub mod error;
pub mod interrupt;
pub mod io;
pub mod numerics;
pub mod progress;
// Layer 1: physics.
pub mod contact;
pub mod dynamics;
pub mod fluid;
pub mod instruments;
pub mod sample;
// Layer 2: engine.
pub mod engine;
// Layer 3: scenario.
pub mod scenario;
// Layer 4: scenes.
pub mod scenes;
// Layer 5: application.
pub mod api;
pub mod bench;
pub mod cli;
pub mod fit;
pub mod invert;
pub mod laws;
pub mod reduce;
pub mod run;
pub mod sweep;

pub use api::{load, run, RunOptions, RunResult, Scenario, Status};
pub use error::Error;
pub use io::{Column, Table};
pub use scenario::Kind;
