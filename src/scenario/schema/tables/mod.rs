//! The tables of one kind each (serde), with the checks that read the table alone: one file per
//! kind under `tables/`, named as the kind. A leaf: the scenario ([`super::Scenario`]) holds
//! them, and the kinds' specs (`kinds/`) read them with the rest of the scenario.

pub mod funnel_pour;
pub mod restitution_drop;
pub mod sedimentation;
pub mod tilt_friction;
