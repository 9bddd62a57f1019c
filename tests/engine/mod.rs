//! `src/engine/`: free settling through Rapier (the worlds' unit tests are in `src/engine/tests/`).
