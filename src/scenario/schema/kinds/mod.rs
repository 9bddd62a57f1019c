//! The tables of one kind each, with their checks and the typed spec of the kind built from
//! them (one file per kind, named as the kind).

pub mod free_settling;
pub mod funnel_pour;
pub mod restitution_drop;
pub mod sedimentation;
pub mod tilt_friction;
