//! The shape of the crate: the import layers of `src/lib.rs`, file and function lengths.

mod layers;
mod shape;
