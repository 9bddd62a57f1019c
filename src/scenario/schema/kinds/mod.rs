//! The tables of one kind each, with their checks.

pub mod funnel;
pub mod restitution_drop;
pub mod sedimentation;
pub mod tilt;
