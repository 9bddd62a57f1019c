//! `src/scenes/<kind>/`: one module per scene kind.

mod charts_contacts;
mod charts_free_settling;
mod charts_funnel;
mod charts_sedimentation;
mod charts_sweep;
mod funnel;
mod restitution_drop_and_tilt;
mod sedimentation;
