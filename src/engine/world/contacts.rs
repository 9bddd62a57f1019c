//! Contacts of the world: fixed floors, walls and colliders, rolling resistance, and what the
//! contacts did during the last step (forces, whether a body touches).

use super::{rapier, to_na, to_rapier, up, Body, RVector, Vector, World};
use crate::engine::BodyId;
use rapier::prelude::{nalgebra::Unit, ColliderBuilder, ColliderHandle};

impl World {
    /// Adds a fixed floor: the half-space below height `height_m` on the last axis.
    pub fn add_floor(&mut self, height_m: f64) {
        self.add_wall(up() * height_m, up());
    }

    /// Adds a fixed wall: the half-space behind the plane through `point_m` whose normal
    /// `inward_normal` points into the domain (it need not be unit length).
    pub fn add_wall(&mut self, point_m: Vector, inward_normal: Vector) {
        let n = to_rapier(&inward_normal.normalize());
        let collider = ColliderBuilder::halfspace(Unit::new_unchecked(n))
            .translation(to_rapier(&point_m))
            .friction(self.settings.friction)
            .restitution(0.0);
        self.physics.insert_collider(collider, None);
    }

    /// Adds a fixed collider built by the caller (any Rapier shape, with its own friction and
    /// restitution) and returns its handle, e.g. the faces of a funnel or a removable plug.
    pub fn add_fixed_collider(
        &mut self,
        collider: rapier::prelude::ColliderBuilder,
    ) -> ColliderHandle {
        self.physics.insert_collider(collider, None)
    }

    /// Removes a fixed collider added by [`World::add_fixed_collider`] (e.g. opens an outlet).
    pub fn remove_fixed_collider(&mut self, handle: ColliderHandle) {
        self.physics.remove_collider(handle);
    }

    /// Sets the rolling-resistance coefficient μ_r (default 0) of every contact: each step a body
    /// in contact feels the torque −μ_r r Σ|F_n| ω̂ (r its radius, Σ|F_n| the magnitudes of its
    /// contact pairs' normal forces over the previous step, ω̂ its spin direction), f-EDEM's and
    /// EDEM's "type A" rolling friction. The torque is clamped so that it can at most stop the spin
    /// within the step (|T| dt ≤ I |ω|): it never reverses it. A solid sphere rolling on a plate
    /// then decelerates at (5/7) μ_r g (src/scenes/funnel_pour/tests/mod.rs).
    pub fn set_rolling_resistance(&mut self, mu_r: f64) {
        assert!(
            mu_r >= 0.0 && mu_r.is_finite(),
            "rolling resistance must be ≥ 0, got {mu_r}"
        );
        self.rolling_resistance = mu_r;
    }

    /// Σ|F_n| over a body's contact pairs during the last step, N (as [`World::contact_force_n`]
    /// but summing magnitudes pair by pair).
    pub(super) fn normal_force_sum_n(&self, body: &Body) -> f64 {
        if self.last_dt_s <= 0.0 {
            return 0.0;
        }
        let sum: f64 = self
            .physics
            .narrow_phase
            .contact_pairs_with(body.collider)
            .map(|pair| to_na(pair.total_impulse()).norm())
            .sum();
        sum * (body.mass_kg / body.rapier_mass_kg()) / self.last_dt_s
    }

    /// Total normal contact force on a body during the last step, N: the sum of its contact
    /// pairs' normal impulses divided by dt (friction impulses excluded). Zero before any step.
    pub fn contact_force_n(&self, body: BodyId) -> Vector {
        if self.last_dt_s <= 0.0 {
            return Vector::zeros();
        }
        let b = &self.bodies[body.0];
        let impulse = self
            .physics
            .narrow_phase
            .contact_pairs_with(b.collider)
            .fold(RVector::ZERO, |acc, pair| {
                // Σ impulse × normal, the normal pointing from collider1 to collider2: the push
                // collider1 gives collider2.
                let j = pair.total_impulse();
                if pair.collider1 == b.collider {
                    acc - j
                } else {
                    acc + j
                }
            });
        // Rapier's forces are per its (unboosted) body mass: convert through the acceleration.
        let scale = b.mass_kg / b.rapier_mass_kg();
        to_na(impulse) * (scale / self.last_dt_s)
    }

    /// True if the narrow phase reported an active (possibly speculative) contact for the body at
    /// the last step: the body was then driven with damping-style drag.
    pub fn in_contact(&self, body: BodyId) -> bool {
        self.physics
            .narrow_phase
            .contact_pairs_with(self.bodies[body.0].collider)
            .any(|p| p.has_any_active_contact())
    }
}
