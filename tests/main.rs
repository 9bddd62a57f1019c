//! settle's tests, in one test crate whose modules mirror `src/` (as nalgebra's do): one binary
//! links rapier2d, rapier3d and plotters once, instead of once per file.
//!
//! | module | tests |
//! |---|---|
//! | `common` | helpers only: spawn the `settle` binary, temp folders, CSV and printed figures |
//! | `scenario` | `src/scenario/`: every bad input refused before anything runs (`bad_scenarios/`) |
//! | `scenes` | `src/scenes/<kind>/`: sedimentation (+ its contacts), funnel, restitution drop and tilt |
//! | `instruments` | `src/instruments/`: hydrometer, buoyancy sphere, pipette |
//! | `api` | `src/api.rs`: the library API against the command line (tables, overrides, errors, files) |
//! | `app` | `src/run.rs`, `src/checkpoint.rs`, `src/interrupt.rs`, `src/sweep/` |
//! | `validation` | validation cases: scenario + reference data + test with a stated tolerance |
//! | `architecture` | the crate's shape: import layers, file and function lengths |
//! | `slurm` | `src/slurm/` on a real one-node Slurm (`scripts/slurm_local.sh`): job arrays, requeue |
//! | `regression` | one file `issue_<N>_<slug>.rs` per fixed item, opening with its symptom |
//!
//! Run everything with `cargo test --release`; one area with `cargo test --release --test main
//! engine::` (a module path prefix: `scenes::funnel_pour::`, `regression::issue_12_`); a single test
//! with its full path and `--exact`. Tests spawn `target/release/settle` through
//! [`common::settle`]; set `SETTLE_BIN` to run them against another binary (e.g. the one before a
//! fix).
//!
//! All tests share one process: none may change process-wide state (environment, current
//! directory, the interrupt flag of `settle::interrupt`). A test that must, runs its body in a
//! child process of its own through [`common::isolated`].

mod common;

mod api;
mod app;
mod architecture;
mod instruments;
mod regression;
mod scenario;
mod scenes;
mod slurm;
mod validation;
