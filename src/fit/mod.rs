//! Calibration: `settle fit SCENARIO --fit KEY=LO:HI [--fit …] --measured M.csv` finds the
//! values of scenario keys that make the scenario's outputs match measurements, and
//! `settle fit slump` computes a yield stress from slump tests ([`slump()`]).
//!
//! Each evaluation of the objective is a whole run of the scenario in memory (the run of
//! [`crate::Scenario::run`], with the fitted keys set as `--set KEY=VALUE` on top of the
//! scenario's overrides); the measured quantities are read from its tables. The objective is
//! χ² = Σ ((model_i − measured_i)/σ_i)², minimised by Brent's method for one key and by
//! Nelder–Mead for several ([`optim`]; written here: a few dozen lines each, bounded, and
//! counting runs — no crate needed).
//!
//! # From Rust
//!
//! [`fit()`] runs the calibration in memory: a [`crate::Scenario`] (its overrides are the
//! `--set` list), the keys and their bounds ([`Bound`], `Bound::parse("KEY=LO:HI")`), the
//! measurements as a file or an in-memory table ([`Measured`]); it returns a [`FitResult`]
//! with every table and file `settle fit` writes ([`crate::Outputs`]) and the typed figures
//! ([`Fit`]); [`FitResult::write`] writes the folder the command line writes, byte for byte.
//!
//! ```no_run
//! use settle::fit::{fit, Bound, FitOptions};
//! let paste = settle::load("scenarios/paste_single_ball.toml")?
//!     .set("release.fall_heights_m", "[0.255]")?;
//! let eta = Bound::parse("fluid.plastic_viscosity_pa_s=0.1:3")?;
//! let r = fit(&paste, &[eta], "M.csv", &FitOptions::default())?;
//! println!("eta_B = {} Pa s +/- {:?}", r.fit.values[0], r.fit.sigma[0]);
//! println!("{:?}", r.table("residuals").unwrap().f64s("residual"));
//! r.write("out")?; // out/paste_single_ball_fit/
//! # Ok::<(), settle::Error>(())
//! ```
//!
//! | file | job |
//! |---|---|
//! | `args.rs` | the command line: arguments, destination check, console |
//! | `bound.rs` | `--fit KEY=LO:HI` |
//! | `calibrate.rs` | [`fit()`]: the checks, the search, the result |
//! | `measure.rs` | M.csv (or its table), and reading a measurement from a run's tables |
//! | `optim.rs` | Brent, Nelder–Mead, Gauss–Newton covariance, χ² crossing; pure |
//! | `problem.rs` | the objective: one run per evaluation |
//! | `output.rs` | fitted.csv, residuals.csv, objective.csv and chart, fit.toml, console |
//! | `slump.rs` | `settle fit slump` |

mod args;
mod bound;
mod calibrate;
mod measure;
pub mod optim;
mod output;
mod problem;
mod slump;

pub(crate) use args::{main, Args};
pub use bound::Bound;
pub use calibrate::{fit, FitOptions, FitResult};
pub use measure::{Measured, Measurement};
pub use problem::Fit;
pub use slump::{slump, Slump, SlumpTest};
