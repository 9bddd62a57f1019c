//! The kinds' specs, one file per kind, named as the kind: the checks of its tables that read
//! the whole scenario, and the typed spec of the kind built from them. The tables themselves
//! are in `tables/`.

pub mod free_settling;
pub mod funnel_pour;
pub mod restitution_drop;
pub mod sedimentation;
pub mod tilt_friction;
