//! `src/api.rs` and `src/sweep/`: the library API (load, override, run in memory, tables, write;
//! dt and parameter sweeps), against the command line it stands for.

mod run;
mod sweep;
