//! Unit tests of the output layer (moved from `tests/regression/`): atomic writes.

mod issue_8_concurrent_atomic_writes;
