//! The typed setup of a tilt run, from the scenario's `[tilt]`, `[contacts]`, gravity and time
//! step.

use crate::engine::EngineSettings;
use crate::scenario::{Common, TiltFrictionSpec};

/// Everything one tilt run needs. SI units, angles in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TiltSetup {
    /// Block edge lengths (x along the slope, y across, z normal to the plate), m.
    pub block_size_m: [f64; 3],
    /// Block density, kg/m³.
    pub block_density_kg_m3: f64,
    /// Coulomb friction coefficient of the block and the plate (static = dynamic in Rapier).
    pub friction: f64,
    /// Restitution of the block and the plate.
    pub restitution: f64,
    /// Magnitude of gravity, m/s².
    pub gravity_m_s2: f64,
    /// Simulated time per angle, s.
    pub duration_s: f64,
    /// Time step, s.
    pub dt_s: f64,
    /// Displacement along the slope above which the block slides, m.
    pub slide_distance_m: f64,
    /// Rapier settings (length unit, contact softness, speed cap, substeps, sleeping).
    pub settings: EngineSettings,
}

impl TiltSetup {
    /// The setup of a `tilt_friction` scenario: its `[tilt]` table, `[contacts]`, gravity and
    /// `time.dt_s`; engine settings for the block's smallest edge and the fastest slide over
    /// the largest angle.
    pub fn new(s: &Common, tf: &TiltFrictionSpec) -> Self {
        let (spec, size) = (&tf.tilt, tf.block_size_m);
        let friction = tf.contacts.friction;
        let max_angle = spec.angles_deg.iter().copied().fold(0.0, f64::max);
        let max_speed = s.gravity_m_s2 * max_angle.to_radians().sin() * spec.duration_s;
        let mut settings = EngineSettings::for_scene(
            size.iter().copied().fold(f64::INFINITY, f64::min),
            max_speed,
        );
        settings.friction = friction;
        Self {
            block_size_m: size,
            block_density_kg_m3: spec.block_density_kg_m3,
            friction,
            restitution: tf.contacts.restitution,
            gravity_m_s2: s.gravity_m_s2,
            duration_s: spec.duration_s,
            dt_s: s.time.dt_s,
            slide_distance_m: spec.slide_distance_m,
            settings,
        }
    }

    /// Number of steps of one run.
    pub fn steps(&self) -> u64 {
        (self.duration_s / self.dt_s).round().max(1.0) as u64
    }
}
