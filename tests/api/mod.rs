//! The library API against the command line it stands for: `src/api.rs` (load, override, run
//! in memory, tables, write) and `settle::fit` (calibration in memory).

mod fit;
mod run;
