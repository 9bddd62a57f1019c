//! The application layer: `src/run.rs`, `src/checkpoint.rs`, `src/interrupt.rs`, `src/sweep/`.

#[cfg(unix)]
mod checkpoint;
mod interrupt;
mod report;
mod sweep;
