//! `src/api.rs`: the library API (load, override, run in memory, tables, write), against the
//! command line it stands for.

mod lab;
mod run;
