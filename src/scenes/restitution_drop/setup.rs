//! Setup of a restitution drop: the Rapier settings of the scene (see the [module doc](super)).

use super::Setup;
use crate::engine::EngineSettings;
use crate::scenario::Common;

/// Engine settings of a drop scene: [`EngineSettings::for_scene`] for the ball's diameter and the
/// largest impact speed √(2 g H_max), with the contact's friction.
pub fn drop_settings(s: &Common, setup: &Setup, max_drop_height_m: f64) -> EngineSettings {
    let v_impact = (2.0 * s.gravity_m_s2 * max_drop_height_m).sqrt();
    let mut settings = EngineSettings::for_scene(setup.ball.diameter_m, v_impact);
    settings.friction = setup.friction;
    settings
}
