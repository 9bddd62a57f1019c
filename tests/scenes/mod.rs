//! `src/scenes/<kind>/`: one module per scene kind.

mod charts_funnel;
mod charts_sedimentation;
mod funnel;
mod restitution_drop_and_tilt;
mod sedimentation;
mod sedimentation_contacts;
