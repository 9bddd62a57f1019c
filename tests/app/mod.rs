//! The application layer: `src/run.rs`, `src/checkpoint.rs`, `src/interrupt.rs`, `src/sweep/`,
//! `src/reduce/`.

#[cfg(unix)]
mod checkpoint;
mod interrupt;
mod reduce;
mod sweep;
