//! One tilt run: the block on the plate in a bare Rapier 3D world, gravity tilted by the angle.

use super::TiltSetup;
use crate::engine::{unstable, Unstable};
use rapier3d_f64::prelude::{
    nalgebra::Unit, ColliderBuilder, PhysicsWorld, RigidBodyBuilder, RigidBodyHandle,
};

type RVector = rapier3d_f64::math::Vector;

/// Result of one tilt angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TiltOutcome {
    /// Tilt angle, degrees.
    pub angle_deg: f64,
    /// Displacement of the block's centre down the slope after the run, m.
    pub displacement_m: f64,
    /// Displacement above `slide_distance_m`.
    pub slides: bool,
    /// Found by bisection (not one of the angles given).
    pub bisection: bool,
}

/// The tilted scene: a plate (the half-space z ≤ 0) and the block resting on it, gravity
/// `g (sin θ, 0, −cos θ)`. Returns the world and the block's handle.
fn tilted_world(t: &TiltSetup, angle_deg: f64) -> (PhysicsWorld, RigidBodyHandle) {
    let st = &t.settings;
    let mut w = PhysicsWorld::new();
    let th = angle_deg.to_radians();
    w.gravity = RVector::new(t.gravity_m_s2 * th.sin(), 0.0, -t.gravity_m_s2 * th.cos());
    st.apply(&mut w.integration_parameters);
    w.integration_parameters.dt = t.dt_s;
    let plate = ColliderBuilder::halfspace(Unit::new_unchecked(RVector::Z))
        .friction(t.friction)
        .restitution(t.restitution);
    w.insert_collider(plate, None);
    let [lx, ly, lz] = t.block_size_m;
    let rb = RigidBodyBuilder::dynamic()
        .translation(RVector::new(0.0, 0.0, 0.5 * lz))
        .can_sleep(st.can_sleep);
    let block = ColliderBuilder::cuboid(0.5 * lx, 0.5 * ly, 0.5 * lz)
        .density(t.block_density_kg_m3)
        .friction(t.friction)
        .restitution(t.restitution);
    let (handle, _) = w.insert(rb, block);
    (w, handle)
}

/// Why a tilt run gave no outcome.
#[derive(Clone, Debug, PartialEq)]
pub enum TiltError {
    /// The block's position turned non-finite or its speed exceeded half the speed cap.
    Unstable(Unstable),
    /// Ctrl-C or SIGTERM ([`crate::interrupt::requested`]) during the run: no result.
    Interrupted,
}

impl From<Unstable> for TiltError {
    fn from(u: Unstable) -> Self {
        Self::Unstable(u)
    }
}

/// Runs the block at one angle (gravity tilted about y; +x is down the slope). Errors with
/// [`TiltError::Unstable`] when the block's position turns non-finite or its speed exceeds half
/// the speed cap of the settings, and [`TiltError::Interrupted`] at Ctrl-C (checked every 4096
/// steps, a few milliseconds of Rapier).
pub fn simulate_tilt(t: &TiltSetup, angle_deg: f64) -> Result<TiltOutcome, TiltError> {
    let (mut w, handle) = tilted_world(t, angle_deg);
    let cap = t.settings.max_linear_velocity_m_s;
    for i in 1..=t.steps() {
        if i.is_multiple_of(4096) && crate::interrupt::requested() {
            return Err(TiltError::Interrupted);
        }
        w.step_with_events(&(), &());
        let rb = &w.bodies[handle];
        let speed = rb.linvel().length();
        let bad = if !rb.translation().is_finite() {
            Some(("position", rb.translation().length()))
        } else if !speed.is_finite() || speed > 0.5 * cap {
            Some(("speed", speed))
        } else {
            None
        };
        if let Some((what, value)) = bad {
            let time = i as f64 * t.dt_s;
            return Err(unstable(0, time, t.dt_s, what, value, 0.5 * t.dt_s).into());
        }
    }
    let displacement_m = w.bodies[handle].translation().x;
    Ok(TiltOutcome {
        angle_deg,
        displacement_m,
        slides: displacement_m > t.slide_distance_m,
        bisection: false,
    })
}
