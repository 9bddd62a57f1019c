//! Setup of a restitution drop: what it reads of its scenario ([`Setup`]) and the Rapier
//! settings of the scene (see the [module doc](super)).

use crate::contact::RestitutionLaw;
use crate::engine::EngineSettings;
use crate::scenario::{Common, RestitutionDropSpec, RestitutionSpec, SphereSpec};

/// What a restitution drop needs from its prepared scenario.
#[derive(Clone, Copy, Debug)]
pub struct Setup<'a> {
    /// The `[restitution_drop]` table: heights, measurements, tolerance.
    pub spec: &'a RestitutionDropSpec,
    /// The ball (the scenario's one `[[spheres]]` entry).
    pub ball: &'a SphereSpec,
    /// The contact's restitution law (`[contacts]`).
    pub law: RestitutionLaw,
    /// The contact's Coulomb friction coefficient (`contacts.friction`).
    pub friction: f64,
}

impl<'a> Setup<'a> {
    /// The setup of a `restitution_drop` scenario from its spec.
    pub fn of(spec: &'a RestitutionSpec) -> Self {
        Self {
            spec: &spec.drop,
            ball: &spec.ball,
            law: spec.contacts.restitution_law(),
            friction: spec.contacts.friction,
        }
    }

    /// Largest drop height, m.
    pub fn max_drop_height_m(&self) -> f64 {
        self.spec.drop_heights_m.iter().copied().fold(0.0, f64::max)
    }
}

/// Engine settings of a drop scene: [`EngineSettings::for_scene`] for the ball's diameter and the
/// largest impact speed √(2 g H_max), with the contact's friction.
pub fn drop_settings(s: &Common, setup: &Setup, max_drop_height_m: f64) -> EngineSettings {
    let v_impact = (2.0 * s.gravity_m_s2 * max_drop_height_m).sqrt();
    let mut settings = EngineSettings::for_scene(setup.ball.diameter_m, v_impact);
    settings.friction = setup.friction;
    settings
}
