//! The application layer: `src/run.rs`, `src/checkpoint.rs`, `src/interrupt.rs`, `src/sweep/`,
//! `src/reduce/`, `src/invert/`, `src/laws/`, `src/fit/`.

mod bad_input;
mod bad_lab_inputs;
#[cfg(unix)]
mod checkpoint;
pub(crate) mod console;
mod doc_links;
mod fit;
mod interrupt;
mod invert;
mod lab_files;
mod laws;
mod readings;
mod reduce;
mod report;
mod rerun;
mod sweep_merge;
mod tutorial;
mod vary;
