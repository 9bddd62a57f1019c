//! # settle
//!
//! Solid particles settling in Newtonian and Bingham fluids. Fluid forces (buoyancy, drag,
//! yield-stress drag) act as body forces on the particles of a DEM scene, after f-EDEM
//! (Zhang & Li 2024) and the one-way coupled hydrometer DEM of seed 000.
//!
//! # Using settle as a library
//!
//! A scenario file is loaded (or given as text, or as TOML values), changed with overrides
//! (the keys of `settle run --set`), run in memory, and its tables read; writing its files is
//! a separate step. Every bad input is an [`Error::BadInput`] naming the file and the key.
//!
//! ```
//! # fn main() -> Result<(), settle::Error> {
//! # let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
//! // A 0.1 mm quartz grain in water (f-EDEM Table 1), at twice water's viscosity.
//! let scenario = settle::load(root.join("scenarios/stokes_single.toml"))?
//!     .set("fluid.viscosity_pa_s", "0.002")?;
//! assert_eq!(scenario.kind(), settle::Kind::FreeSettling);
//! let result = scenario.run()?;
//! let summary = result.table("summary").expect("a free-settling run has a summary");
//! let v = summary.f64s("v_simulated_m_s").expect("a number column")[0];
//! // Stokes' law: v = (ρ_p − ρ_f) g d² / (18 μ) = 1700 × 9.81 × 1e-8 / 0.036 m/s.
//! assert!((v / (1700.0 * 9.81 * 1e-8 / 0.036) - 1.0).abs() < 1e-3);
//! # let out = std::env::temp_dir().join(format!("settle-doc-{}", std::process::id()));
//! let folder = result.write(&out)?; // OUT/stokes_single/: what `settle run --out OUT` writes
//! # std::fs::remove_dir_all(&out).ok();
//! # Ok(())
//! # }
//! ```
//!
//! | step | call |
//! |---|---|
//! | load | [`load`], [`Scenario::from_toml`], [`Scenario::from_table`] |
//! | override | [`Scenario::set`] (as `--set KEY=VALUE`), [`Scenario::with_dt`] (as `--dt`) |
//! | run | [`Scenario::run`], [`Scenario::run_with`] ([`RunOptions`]) |
//! | read | [`RunResult::tables`], [`RunResult::table`] ([`Table`], [`Column`]), [`RunResult::warnings`], [`RunResult::status`], [`RunResult::record`] |
//! | write | [`RunResult::write`] |
//! | other commands | [`reduce`], [`invert`], [`laws`], [`fit::fit`] and [`sweep`] ([`sweep::sweep`], [`sweep::vary()`]) in memory, as `run` ([`fit::slump`] the slump calculator) |
//! | physics | [`fluid`] (drag laws, buoyancy, Bingham drag), [`dynamics`] (integrators), [`contact`], [`instruments`] (hydrometer, pipette, buoyancy sphere, reductions), [`sample`] |
//!
//! Ctrl-C: [`interrupt::request`] stops a run at its next check; the run returns what it did
//! with [`Status::Interrupted`].
//!
//! # Layers
//!
//! Each layer imports only from its own layer and the layers above it in this table
//! (`tests/architecture/layers.rs` checks every `crate::` path in `src/` against it):
//!
//! | layer | modules | what |
//! |---|---|---|
//! | 0 infrastructure | [`error`], `numerics`, `io`, `checkpoint`, [`interrupt`], `progress` | the error type and exit codes, bracketing root finders, staged output folders, atomic writes, charts, checkpoints, interruption, progress bars; no domain types |
//! | 1 physics | [`fluid`], [`contact`], [`dynamics`], [`sample`], [`instruments`] | pure functions with their equations: no I/O, no Rapier |
//! | 2 engine | `engine` | the Rapier worlds |
//! | 3 scenario | `scenario` | schema, loading, validation, input files, the typed scenario and the registry of kinds |
//! | 4 scenes | `scenes` | one folder per kind (its scene and its cost), and the scene API (`scenes::Prepared`, `scenes::RunContext`, `scenes::SceneReport`) |
//! | 5 application | [`api`], `run`, [`sweep`], `bench`, [`reduce`], [`invert`], [`laws`], [`fit`], `slurm`, `cli` | the commands (`slurm`: studies submitted to a Slurm cluster) |

// Layer 0: infrastructure.
pub(crate) mod checkpoint;
pub mod error;
pub mod interrupt;
pub(crate) mod io;
pub(crate) mod numerics;
pub(crate) mod progress;
// Layer 1: physics.
pub mod contact;
pub mod dynamics;
pub mod fluid;
pub mod instruments;
pub mod sample;
// Layer 2: engine.
pub(crate) mod engine;
// Layer 3: scenario.
pub(crate) mod scenario;
// Layer 4: scenes.
pub(crate) mod scenes;
// Layer 5: application.
pub mod api;
pub(crate) mod bench;
pub(crate) mod cli;
pub mod fit;
pub mod invert;
pub mod laws;
pub mod reduce;
pub(crate) mod run;
pub(crate) mod slurm;
pub mod sweep;

pub use api::{load, run, RunOptions, RunResult, Scenario, Status};
pub use error::Error;
pub use io::chart::data::{Drawn, Figure, Panel};
pub use io::{Column, Outputs, Table};
pub use progress::{Shown, Watch};
pub use scenario::Kind;

/// The command line `settle` (the binary's `main`): parses the arguments, runs the command,
/// returns the exit code ([`error`] lists them).
#[doc(hidden)]
pub fn cli_main() -> i32 {
    cli::main()
}
