//! `src/scenes/<kind>/`: one module per scene kind.

mod funnel;
mod restitution_drop_and_tilt;
mod sedimentation;
mod sedimentation_contacts;
