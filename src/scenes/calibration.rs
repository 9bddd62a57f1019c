//! Old path of the contact calibration scenes, now [`super::restitution_drop`] and
//! [`super::tilt_friction`] (the fits in [`crate::contact::restitution`]). Re-exports only, kept
//! so that branches written against the old path still compile; the lead removes it after the
//! merge.

pub use super::restitution_drop::run as run_restitution;
pub use super::restitution_drop::{drop_settings, simulate_drop, DropError, DropOutcome};
pub use super::tilt_friction::run as run_tilt;
pub use super::tilt_friction::{simulate_tilt, tilt_threshold, TiltOutcome, TiltSearch, TiltSetup};
pub use crate::contact::{constant_fit, restitution_fits, ConstantFit, LawFit};
