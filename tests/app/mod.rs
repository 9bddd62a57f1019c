//! The application layer: `src/run.rs`, `src/checkpoint.rs`, `src/interrupt.rs`, `src/sweep/`,
//! `src/reduce/`, `src/invert/`.

#[cfg(unix)]
mod checkpoint;
pub(crate) mod console;
mod interrupt;
mod invert;
mod readings;
mod reduce;
mod report;
mod rerun;
mod sweep;
mod tutorial;
mod vary;
