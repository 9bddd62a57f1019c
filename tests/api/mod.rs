//! The library API against the command line it stands for: `src/api.rs` (load, override, run
//! in memory, tables, write) and the other commands in memory (`settle::fit`, `settle::invert`,
//! `settle::laws`, `settle::sweep`).

mod fit;
mod lab;
mod run;
mod sweep;
