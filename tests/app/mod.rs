//! The application layer: `src/run.rs`, `src/checkpoint.rs`, `src/interrupt.rs`, `src/sweep/`,
//! `src/reduce/`, `src/invert/`, `src/laws/`, `src/fit/`.

#[cfg(unix)]
mod checkpoint;
pub(crate) mod console;
mod doc_links;
mod fit;
mod interrupt;
mod invert;
mod laws;
mod readings;
mod reduce;
mod report;
mod rerun;
mod tutorial;
mod vary;
