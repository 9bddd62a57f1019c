//! Restitution of the world's contacts: one coefficient for every collider, or a law e(v) of the
//! impact speed applied by a Rapier contact-modification hook.

use super::{rapier, RVector, World};
use crate::contact::RestitutionLaw;
use rapier::prelude::{
    ActiveHooks, ContactModificationContext, ModifiableContacts, PhysicsHooks, RigidBodyHandle,
};

/// Rapier hook that sets each contact manifold's restitution from its impact speed (see
/// [`World::set_restitution_law`]).
pub(super) struct RestitutionHook(pub(super) RestitutionLaw);

impl PhysicsHooks for RestitutionHook {
    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        let (bodies, rb1, rb2) = (context.bodies, context.rigid_body1, context.rigid_body2);
        let ModifiableContacts::Rigid(manifold) = &mut context.contacts else {
            return;
        };
        let velocity = |handle: Option<RigidBodyHandle>, point: RVector| {
            handle.map_or(RVector::ZERO, |h| bodies[h].velocity_at_point(point))
        };
        // Approach speed: the largest normal relative speed over the manifold's contact points
        // (start-of-step velocities, within g·dt of the impact speed).
        let n = *manifold.normal;
        let speed = manifold
            .solver_contacts
            .iter()
            .map(|c| {
                (velocity(rb1, c.anchor1) - velocity(rb2, c.anchor2))
                    .dot(n)
                    .abs()
            })
            .fold(0.0, f64::max);
        *manifold.restitution = self.0.at(speed);
    }
}

impl World {
    /// Sets the coefficient of restitution e of every collider already in the world (spheres,
    /// floors, walls; [`World::add_sphere`] and [`World::add_wall`] create them with e = 0).
    /// Rapier combines the coefficients of the two colliders of a contact by the rule of higher
    /// priority of the two; every collider here keeps Rapier's default,
    /// `CoefficientCombineRule::Average`, so with one e for all colliders every contact's
    /// restitution is exactly e (a ball with e against a floor with 0 would get e/2). Call it once
    /// the scene is built: colliders added afterwards still get 0.
    pub fn set_restitution(&mut self, restitution: f64) {
        self.set_restitution_law(RestitutionLaw::constant(restitution));
    }

    /// Sets the restitution of every contact between colliders already in the world to the law
    /// `law`. A constant law is [`World::set_restitution`]. A speed-dependent one also sets the
    /// colliders' coefficient to `law.coefficient` and makes Rapier call a contact-modification
    /// hook, which sets each manifold's restitution to e(v), v the largest normal approach speed
    /// over its contact points at the start of the step. Call it once the scene is built.
    pub fn set_restitution_law(&mut self, law: RestitutionLaw) {
        self.restitution = law;
        let hooks = if law.is_speed_dependent() {
            ActiveHooks::MODIFY_SOLVER_CONTACTS
        } else {
            ActiveHooks::empty()
        };
        for (_, collider) in self.physics.colliders.iter_mut() {
            collider.set_restitution(law.coefficient);
            collider.set_active_hooks(hooks);
        }
    }
}
