//! Rapier joints of the world: the yield-stress holds (a joint to a fixed ground body with
//! force-limited velocity motors, see the module doc of [`crate::engine`]) and the squeeze-film
//! dampers between pairs of bodies.

use super::super::LIN_AXES;
use super::{rapier, World};
use crate::engine::BodyId;
use rapier::prelude::{RigidBodyBuilder, RigidBodyHandle};

/// Damping of the yield-stress holds' velocity motors, N s/m (Rapier's force-based motor model):
/// large enough that the motor is a rigid velocity constraint (its compliance 1/(h·D) is ~1e-7
/// kg⁻¹, against 1/m ≥ 1 kg⁻¹ for any grain up to 1 kg) until it reaches its force limit.
const HOLD_DAMPING: f64 = 1e12;

impl World {
    /// Turns the yield-stress holds on (default) or off. On: a body in contact whose drag has a
    /// static resistance F_s (Bingham) and whose momentum the yield stress can cancel within the
    /// step (m s ≤ F_s dt) gets F_s as the force limit of rigid velocity motors (target 0) on each
    /// linear axis, solved with the contacts: it stays at rest unless pushed harder than F_s (per
    /// axis) and a push passes on its full impulse less F_s dt. Off: the engine's former
    /// behaviour, the static part dropped at rest (kept to show the creep it causes).
    pub fn set_yield_hold(&mut self, on: bool) {
        self.yield_hold = on;
    }

    /// Inserts a yield-stress hold on a body: a joint from the fixed ground body with no locked
    /// axis and a velocity motor (target 0, rigid) on every linear axis, anchored at the body's
    /// centre (no lever arm: it exerts no torque), its force limit `force_n`.
    fn insert_hold(
        &mut self,
        body: RigidBodyHandle,
        force_n: f64,
    ) -> rapier::prelude::ImpulseJointHandle {
        use rapier::prelude::{GenericJointBuilder, JointAxesMask, MotorModel};
        let ground = *self
            .ground
            .get_or_insert_with(|| self.physics.insert_body(RigidBodyBuilder::fixed()));
        let mut joint = GenericJointBuilder::new(JointAxesMask::empty());
        for axis in LIN_AXES {
            joint = joint
                .motor_model(axis, MotorModel::ForceBased)
                .motor_velocity(axis, 0.0, HOLD_DAMPING)
                .motor_max_force(axis, force_n);
        }
        self.physics.insert_impulse_joint(ground, body, joint)
    }

    /// Sets the force limit of a body's yield-stress hold: inserts the hold, changes its limit or
    /// removes it (force 0); no-op if unchanged.
    pub(super) fn set_hold_force(&mut self, index: usize, force_n: f64) {
        let (handle, current, hold) = {
            let b = &self.bodies[index];
            (b.handle, b.hold_force_n, b.hold)
        };
        if current == force_n {
            return;
        }
        self.bodies[index].hold_force_n = force_n;
        match hold {
            None => {
                let joint = self.insert_hold(handle, force_n);
                self.bodies[index].hold = Some(joint);
            }
            Some(joint) if force_n <= 0.0 => {
                self.physics.remove_impulse_joint(joint);
                self.bodies[index].hold = None;
            }
            Some(joint) => {
                if let Some(j) = self.physics.impulse_joints.get_mut(joint, false) {
                    for axis in LIN_AXES {
                        j.data.set_motor_max_force(axis, force_n);
                    }
                }
            }
        }
    }

    /// Adds a linear damper between two bodies along the line of their centres at this moment
    /// (the squeeze film of [`crate::fluid::lubrication`]): a Rapier joint with no locked axis and
    /// a force-based velocity motor (target 0, damping `damping_n_s_m`, no stiffness) on the axis
    /// from `a` to `b`, anchored at the centres. Rapier solves it implicitly with the contacts
    /// (constraint compliance 1/(h·c)): the pair's relative normal velocity is damped by c v_n
    /// with backward Euler inside the solve, together with the effective-mass drag, so it stays
    /// stable however stiff c is. The axis is frozen: remove the damper and add a new one when
    /// the pair has moved ([`World::remove_pair_damper`]).
    pub fn add_pair_damper(
        &mut self,
        a: BodyId,
        b: BodyId,
        damping_n_s_m: f64,
    ) -> rapier::prelude::ImpulseJointHandle {
        use rapier::prelude::{GenericJointBuilder, JointAxesMask, JointAxis, MotorModel};
        let (ha, hb) = (self.bodies[a.0].handle, self.bodies[b.0].handle);
        let (ra, rb) = (&self.physics.bodies[ha], &self.physics.bodies[hb]);
        let n = (rb.translation() - ra.translation()).normalize();
        let (axis1, axis2) = (ra.rotation().inverse() * n, rb.rotation().inverse() * n);
        let joint = GenericJointBuilder::new(JointAxesMask::empty())
            .local_axis1(axis1)
            .local_axis2(axis2)
            .contacts_enabled(true)
            .motor_model(JointAxis::LinX, MotorModel::ForceBased)
            .motor_velocity(JointAxis::LinX, 0.0, damping_n_s_m);
        self.physics.insert_impulse_joint(ha, hb, joint)
    }

    /// Removes a damper added by [`World::add_pair_damper`].
    pub fn remove_pair_damper(&mut self, joint: rapier::prelude::ImpulseJointHandle) {
        self.physics.remove_impulse_joint(joint);
    }
}
