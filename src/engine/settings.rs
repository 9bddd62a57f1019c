//! Numerical settings of a Rapier world ([`EngineSettings`]) and how they reach Rapier's
//! integration parameters ([`EngineSettings::apply`]), in one place for every scene.

use serde::{Deserialize, Serialize};

/// Numerical settings of a Rapier world, derived from the scene. SI units. Recorded in run.toml.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EngineSettings {
    /// Rapier's `length_unit`, m: scales slop, prediction distance, contact recycling, sleep
    /// threshold and the speed cap. Default: the smallest particle diameter of the scene.
    pub length_unit_m: f64,
    /// Natural frequency of the contact constraints, Hz, for dynamic–dynamic and static contacts
    /// alike. Resting penetration ≈ g′/(2πf)², independent of the size. Default 1e4.
    pub contact_natural_frequency_hz: f64,
    /// Damping ratio of the contact constraints. Default 10 (Rapier's).
    pub damping_ratio: f64,
    /// Rapier's speed cap, m/s: must exceed every real speed (bodies above half of it are reported
    /// as unstable). Default: max(400 × length unit, 4 × the scene's largest expected speed).
    pub max_linear_velocity_m_s: f64,
    /// Rapier's `num_solver_iterations` = number of substeps K per step. Default 4 (Rapier's).
    pub num_solver_iterations: usize,
    /// Whether bodies may fall asleep. Default false: grains settling at µm/s must not sleep.
    pub can_sleep: bool,
    /// Coulomb friction coefficient of every collider (balls, floor, walls). Default 0.5 (Rapier's).
    pub friction: f64,
    /// How the drag acts on a body in contact. Default [`ContactDrag::EffectiveMass`].
    pub contact_drag: ContactDrag,
    /// Overlap of a contact, as a fraction of the body's diameter, beyond which the run stops as
    /// unstable (bodies passing through each other or through a wall). Default 0.25; 0 turns the
    /// check off. Resting overlaps are ~1e-4 d at the default contact frequency, impacts ~1e-2 d.
    #[serde(default = "default_max_penetration")]
    pub max_penetration_fraction: f64,
    /// Largest distance of a body's centre from the origin, m, beyond which the run stops as
    /// unstable (a body that left the domain). Default None: no bound.
    #[serde(default)]
    pub max_distance_m: Option<f64>,
}

fn default_max_penetration() -> f64 {
    0.25
}

/// How the drag of a body in contact is handed to Rapier's contact solver (see the module doc
/// of [`crate::engine`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContactDrag {
    /// Backward-Euler drag inside the solve: for the step, the body's Rapier mass and inertia are
    /// raised to `m + k dt` and `I + k_rot dt` with its momentum kept. Contact forces and velocities
    /// consistent at any dt/τ; positions in contact lag by up to 3/8 when dt ≫ τ.
    #[default]
    EffectiveMass,
    /// Rapier's `linear_damping` = k/m (and `angular_damping` = k_rot/I). Right velocities and
    /// resting forces, but positions advance with the undamped velocity: loaded grains move about
    /// (1 + k dt/m) too far per step, which breaks piles once dt ≫ τ.
    Damping,
}

impl EngineSettings {
    /// Settings for a scene whose smallest particle has diameter `min_diameter_m` and whose
    /// fastest body is expected to move at `max_speed_m_s` (e.g. the largest terminal velocity):
    /// length unit = `min_diameter_m`, 1e4 Hz contacts, damping ratio 10, speed cap
    /// max(400·lu, 4·`max_speed_m_s`), 4 solver iterations, no sleeping, friction 0.5,
    /// effective-mass contact drag, runs stopped at overlaps beyond 0.25 d, no domain bound.
    pub fn for_scene(min_diameter_m: f64, max_speed_m_s: f64) -> Self {
        assert!(
            min_diameter_m > 0.0 && min_diameter_m.is_finite(),
            "smallest diameter must be positive and finite, got {min_diameter_m}"
        );
        Self {
            length_unit_m: min_diameter_m,
            contact_natural_frequency_hz: 1e4,
            damping_ratio: 10.0,
            max_linear_velocity_m_s: (400.0 * min_diameter_m).max(4.0 * max_speed_m_s.abs()),
            num_solver_iterations: 4,
            can_sleep: false,
            friction: 0.5,
            contact_drag: ContactDrag::EffectiveMass,
            max_penetration_fraction: default_max_penetration(),
            max_distance_m: None,
        }
    }

    /// Writes these settings into Rapier's integration parameters of either dimension
    /// (`rapier2d_f64::prelude::IntegrationParameters` or `rapier3d_f64::…`): `length_unit` =
    /// `length_unit_m`; `contact_softness` and `static_contact_softness` = springs of natural
    /// frequency `contact_natural_frequency_hz` and damping ratio `damping_ratio`;
    /// `normalized_max_linear_velocity` = `max_linear_velocity_m_s / length_unit_m`;
    /// `num_solver_iterations` = `num_solver_iterations` (at least 1). Nothing else is touched
    /// (`dt`, the prediction distance and gravity are the caller's). Every engine world is built
    /// through it, so a scene driving its own Rapier world with it integrates like the engine.
    pub fn apply(&self, params: &mut impl RapierIntegrationParameters) {
        params.set_engine_settings(self);
    }
}

/// Rapier's `IntegrationParameters` of either dimension, written by [`EngineSettings::apply`].
/// Implemented for `rapier2d_f64::prelude::IntegrationParameters` and
/// `rapier3d_f64::prelude::IntegrationParameters` (in the engine's per-dimension worlds).
pub trait RapierIntegrationParameters {
    /// Sets the parameters listed at [`EngineSettings::apply`] from `settings`.
    fn set_engine_settings(&mut self, settings: &EngineSettings);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_defaults() {
        let s = EngineSettings::for_scene(2e-3, 0.1);
        assert_eq!(s.length_unit_m, 2e-3);
        assert_eq!(s.contact_natural_frequency_hz, 1e4);
        assert_eq!(s.damping_ratio, 10.0);
        // max(400 × 2e-3 = 0.8, 4 × 0.1 = 0.4).
        assert_eq!(s.max_linear_velocity_m_s, 0.8);
        assert_eq!(
            EngineSettings::for_scene(2e-3, 1.0).max_linear_velocity_m_s,
            4.0
        );
        assert_eq!(s.num_solver_iterations, 4);
        assert!(!s.can_sleep);
        assert_eq!(s.friction, 0.5);
        assert_eq!(s.contact_drag, ContactDrag::EffectiveMass);
        assert_eq!(s.max_penetration_fraction, 0.25);
        assert_eq!(s.max_distance_m, None);
    }
}
