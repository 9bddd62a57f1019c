// One Rapier world, compiled once per dimension by `include!` from `super` (see `mod.rs`, where
// `rapier` is aliased to rapier2d-f64 or rapier3d-f64). Everything dimension-specific comes from
// `rapier::math::DIM` and glam's slice/array conversions.

use super::{
    rotational_drag_n_m_s, sphere_inertia_kg_m2, unstable, BodyId, ContactDrag, EngineSettings,
    Unstable,
};
use crate::contact::RestitutionLaw;
use crate::dynamics::{self, Integrator};
use crate::fluid::{buoyancy_n, sphere_mass_kg, SphereDrag};
use rapier::prelude::{
    nalgebra::Unit, ActiveHooks, ColliderBuilder, ColliderHandle, ContactModificationContext,
    MassProperties, ModifiableContacts, PhysicsHooks, PhysicsWorld, RigidBodyBuilder,
    RigidBodyHandle, SpringCoefficients,
};

/// Number of space dimensions of this world.
pub const DIM: usize = rapier::math::DIM;

/// A vector of this world (nalgebra), SI units.
pub type Vector = nalgebra::SVector<f64, DIM>;

type RVector = rapier::math::Vector;

/// Rapier's default contact prediction distance, in length units.
const DEFAULT_PREDICTION: f64 = 0.02;

fn to_rapier(v: &Vector) -> RVector {
    RVector::from_slice(v.as_slice())
}

fn to_na(v: RVector) -> Vector {
    Vector::from_column_slice(&v.to_array())
}

/// Unit vector along the gravity axis, pointing up (the last axis).
pub fn up() -> Vector {
    let mut e = Vector::zeros();
    e[DIM - 1] = 1.0;
    e
}

/// A sphere in the fluid, as handed to [`World::add_sphere`]. SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FluidBody {
    /// Initial centre, m.
    pub position_m: Vector,
    /// Initial velocity, m/s (relative to the fluid at rest).
    pub velocity_m_s: Vector,
    /// Diameter d, m.
    pub diameter_m: f64,
    /// Particle density ρp, kg/m³. Mass m = ρp π d³/6 (a sphere, also in 2D).
    pub density_kg_m3: f64,
    /// Drag law bound to this sphere and its fluid.
    pub drag: SphereDrag,
    /// Constant body force other than gravity and drag, N: buoyancy (+ρf π d³ g/6 upwards) and
    /// anything else that acts on the sphere. Gravity is added by the world.
    pub body_force_n: Vector,
}

impl FluidBody {
    /// A sphere at rest at `position_m`, of diameter `diameter_m` and density `density_kg_m3`,
    /// with drag `drag` and the buoyancy of its fluid (`drag.fluid_density_kg_m3`) under gravity
    /// `gravity_m_s2` as its body force.
    pub fn at_rest(
        position_m: Vector,
        diameter_m: f64,
        density_kg_m3: f64,
        drag: SphereDrag,
        gravity_m_s2: f64,
    ) -> Self {
        Self {
            position_m,
            velocity_m_s: Vector::zeros(),
            diameter_m,
            density_kg_m3,
            drag,
            body_force_n: up() * buoyancy_n(diameter_m, drag.fluid_density_kg_m3, gravity_m_s2),
        }
    }

    /// Mass of the sphere, kg (ρp π d³/6).
    pub fn mass_kg(&self) -> f64 {
        sphere_mass_kg(self.diameter_m, self.density_kg_m3)
    }
}

/// Our per-body state beside Rapier's.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
struct Body {
    handle: RigidBodyHandle,
    collider: ColliderHandle,
    /// Sphere mass m, kg.
    mass_kg: f64,
    /// Rotational drag rate k_rot/I of the sphere, 1/s.
    spin_drag_rate_hz: f64,
    drag: SphereDrag,
    body_force_n: Vector,
    /// Rapier's own mass properties of the ball (its collider's), without any boost.
    rapier_mprops: MassProperties,
    /// True while Rapier's mass carries the effective-mass drag boost.
    boosted: bool,
    /// Velocity correction of the exact free-flight scheme, added after the Rapier step.
    correction_m_s: Option<Vector>,
    /// Effective-mass factors (1 + k dt/m, 1 + k_rot dt/I) dividing the velocities before the step.
    momentum_scale: Option<(f64, f64)>,
    /// Yield-stress hold while it acts: a joint to the world's fixed ground body whose linear
    /// velocity motors (target 0) are limited to `hold_force_n` (inserted and removed as needed,
    /// so that bodies not held cost the solver nothing).
    hold: Option<rapier::prelude::ImpulseJointHandle>,
    /// Force limit currently set on every linear axis of the hold, N (0: no hold).
    hold_force_n: f64,
}

impl Body {
    fn rapier_mass_kg(&self) -> f64 {
        self.rapier_mprops.mass()
    }
}

/// A Rapier world of fluid-immersed spheres, fixed floors and walls. See the module doc of
/// [`crate::engine`] for how the fluid forces are coupled.
///
/// Serializable (serde) with everything it holds, Rapier's world included, for checkpoints: a
/// world restored from its bytes continues bit for bit as the original would have (Rapier's
/// pipeline is a workspace only; measured in `tests/checkpoint.rs`).
#[derive(serde::Serialize, serde::Deserialize)]
pub struct World {
    physics: PhysicsWorld,
    settings: EngineSettings,
    gravity_m_s2: Vector,
    bodies: Vec<Body>,
    time_s: f64,
    last_dt_s: f64,
    /// Where the fluid is (None: everywhere); see [`World::set_free_surface`].
    surface: Option<FreeSurface>,
    /// Rolling-resistance coefficient μ_r; see [`World::set_rolling_resistance`].
    rolling_resistance: f64,
    /// Fixed body without collider holding the yield-stress joints (created with the first).
    ground: Option<RigidBodyHandle>,
    /// Whether the yield-stress holds act (default true); see [`World::set_yield_hold`].
    yield_hold: bool,
    /// Restitution of every contact; see [`World::set_restitution_law`].
    restitution: RestitutionLaw,
    /// Smallest contact prediction distance, m; see [`World::set_min_prediction_distance_m`].
    min_prediction_m: f64,
}

/// Rapier hook that sets each contact manifold's restitution from its impact speed (see
/// [`World::set_restitution_law`]).
struct RestitutionHook(RestitutionLaw);

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
            .map(|c| (velocity(rb1, c.anchor1) - velocity(rb2, c.anchor2)).dot(n).abs())
            .fold(0.0, f64::max);
        *manifold.restitution = self.0.at(speed);
    }
}

/// The fluid's extent, for scenes where bodies travel through air before they enter the fluid
/// (see [`World::set_free_surface`]). SI units.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FreeSurface {
    /// Height of the free surface on the last axis, m: the fluid lies below it.
    pub height_m: f64,
    /// Radius of the fluid column about the vertical axis through the origin, m (a cylindrical
    /// container); None: the fluid extends sideways without bound.
    pub radius_m: Option<f64>,
    /// How the fluid forces act on a sphere crossing the surface (f-EDEM: full).
    pub submergence: crate::scenario::Submergence,
}

impl World {
    /// An empty world with the given settings and gravity `gravity_m_s2` (> 0, m/s²) pointing
    /// along the negative last axis (−y in 2D, −z in 3D).
    pub fn new(settings: EngineSettings, gravity_m_s2: f64) -> Self {
        let mut physics = PhysicsWorld::new();
        let g = -up() * gravity_m_s2;
        physics.gravity = to_rapier(&g);
        let p = &mut physics.integration_parameters;
        p.length_unit = settings.length_unit_m;
        let springs = SpringCoefficients::new(
            settings.contact_natural_frequency_hz,
            settings.damping_ratio,
        );
        p.contact_softness = springs;
        p.static_contact_softness = springs;
        p.normalized_max_linear_velocity =
            settings.max_linear_velocity_m_s / settings.length_unit_m;
        p.num_solver_iterations = settings.num_solver_iterations.max(1);
        Self {
            physics,
            settings,
            gravity_m_s2: g,
            bodies: Vec::new(),
            time_s: 0.0,
            last_dt_s: 0.0,
            surface: None,
            rolling_resistance: 0.0,
            ground: None,
            yield_hold: true,
            restitution: RestitutionLaw::constant(0.0),
            min_prediction_m: 0.0,
        }
    }

    /// Sets a floor under the contact prediction distance, m (default 0: Rapier's 0.02 length
    /// units, or twice the largest travel of the step). Pairs within it get (speculative)
    /// contacts at the next step, and so the effective-mass drag: a short first step then
    /// registers pairs that are close but not yet touching.
    pub fn set_min_prediction_distance_m(&mut self, distance_m: f64) {
        self.min_prediction_m = distance_m.max(0.0);
    }

    /// Adds a dynamic sphere (a disc in 2D) and returns its id. Its Rapier mass is the 3D sphere
    /// mass; it has no restitution and the settings' friction; it may sleep only if
    /// `settings.can_sleep`.
    pub fn add_sphere(&mut self, body: FluidBody) -> BodyId {
        let mass_kg = body.mass_kg();
        let rb = RigidBodyBuilder::dynamic()
            .translation(to_rapier(&body.position_m))
            .linvel(to_rapier(&body.velocity_m_s))
            .can_sleep(self.settings.can_sleep);
        let collider = ColliderBuilder::ball(0.5 * body.diameter_m)
            .mass(mass_kg)
            .friction(self.settings.friction)
            .restitution(0.0);
        let (handle, collider) = self.physics.insert(rb, collider);
        let rapier_mprops = self.physics.colliders[collider].mass_properties();
        let inertia = sphere_inertia_kg_m2(mass_kg, body.diameter_m);
        self.bodies.push(Body {
            handle,
            collider,
            mass_kg,
            spin_drag_rate_hz: rotational_drag_n_m_s(&body.drag) / inertia,
            drag: body.drag,
            body_force_n: body.body_force_n,
            rapier_mprops,
            boosted: false,
            correction_m_s: None,
            momentum_scale: None,
            hold: None,
            hold_force_n: 0.0,
        });
        BodyId(self.bodies.len() - 1)
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
                .motor_velocity(axis, 0.0, super::HOLD_DAMPING)
                .motor_max_force(axis, force_n);
        }
        self.physics.insert_impulse_joint(ground, body, joint)
    }

    /// Sets the force limit of a body's yield-stress hold: inserts the hold, changes its limit or
    /// removes it (force 0); no-op if unchanged.
    fn set_hold_force(&mut self, index: usize, force_n: f64) {
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
        let (axis1, axis2) = (
            ra.rotation().inverse() * n,
            rb.rotation().inverse() * n,
        );
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

    /// Restricts the fluid to the region below a free surface (and within a cylinder), for scenes
    /// where bodies fall through air into the fluid (f-EDEM §4.2 funnel pour). Each step, a body's
    /// drag (and its rotational drag) is scaled by the immersed fraction of its projected area and
    /// its body force (`FluidBody::body_force_n`, the buoyancy) by the immersed fraction of its
    /// volume, both from [`crate::scenes::free_settling::immersion`] at the start of the step:
    /// with `full` submergence both are 1 as soon as the sphere's lowest point is below the
    /// surface, 0 above; with `partial`, the spherical cap below it. Outside `radius_m` (measured
    /// from the vertical axis through the origin, at the sphere's centre) there is no fluid. Entry
    /// is not located within the step (a body enters up to one step late: |v| dt).
    pub fn set_free_surface(&mut self, surface: FreeSurface) {
        self.surface = Some(surface);
    }

    /// Sets the rolling-resistance coefficient μ_r (default 0) of every contact: each step a body
    /// in contact feels the torque −μ_r r Σ|F_n| ω̂ (r its radius, Σ|F_n| the magnitudes of its
    /// contact pairs' normal forces over the previous step, ω̂ its spin direction), f-EDEM's and
    /// EDEM's "type A" rolling friction. The torque is clamped so that it can at most stop the spin
    /// within the step (|T| dt ≤ I |ω|): it never reverses it. A solid sphere rolling on a plate
    /// then decelerates at (5/7) μ_r g (tests/funnel.rs).
    pub fn set_rolling_resistance(&mut self, mu_r: f64) {
        assert!(
            mu_r >= 0.0 && mu_r.is_finite(),
            "rolling resistance must be ≥ 0, got {mu_r}"
        );
        self.rolling_resistance = mu_r;
    }

    /// Turns the yield-stress holds on (default) or off. On: a body in contact whose drag has a
    /// static resistance F_s (Bingham) and whose momentum the yield stress can cancel within the
    /// step (m s ≤ F_s dt) gets F_s as the force limit of rigid velocity motors (target 0) on each
    /// linear axis, solved with the contacts: it stays at rest unless pushed harder than F_s (per
    /// axis) and a push passes on its full impulse less F_s dt. Off: the engine's former
    /// behaviour, the static part dropped at rest (kept to show the creep it causes).
    pub fn set_yield_hold(&mut self, on: bool) {
        self.yield_hold = on;
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

    /// Fluid forces on a body at the start of a step: (drag, body force, spin-drag rate), with the
    /// free surface's immersed fractions applied if one is set.
    fn fluid_now(&self, body: &Body) -> (SphereDrag, Vector, f64) {
        let Some(fs) = self.surface else {
            return (body.drag, body.body_force_n, body.spin_drag_rate_hz);
        };
        let x = to_na(self.physics.bodies[body.handle].translation());
        let mut horizontal = x;
        horizontal[DIM - 1] = 0.0;
        let outside = fs.radius_m.is_some_and(|r| horizontal.norm() > r);
        let (fv, fa) = if outside {
            (0.0, 0.0)
        } else {
            crate::scenes::free_settling::immersion(
                fs.height_m - x[DIM - 1],
                body.drag.diameter_m,
                fs.submergence,
            )
        };
        (
            body.drag.scaled(fa),
            body.body_force_n * fv,
            body.spin_drag_rate_hz * fa,
        )
    }

    /// Σ|F_n| over a body's contact pairs during the last step, N (as [`World::contact_force_n`]
    /// but summing magnitudes pair by pair).
    fn normal_force_sum_n(&self, body: &Body) -> f64 {
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

    /// Advances the world by `dt_s`, the fluid forces integrated by `integrator` (see the module
    /// doc). The contact prediction distance is raised to twice the largest expected travel over
    /// the step when that exceeds Rapier's default (0.02 length units), so that fast bodies meet
    /// their contacts before they overlap.
    ///
    /// Errors with [`Unstable`] for the first body whose state is non-finite or faster than half
    /// the speed cap after the step, or whose free-flight force would need an intermediate speed
    /// above the cap; in that last case the step is not taken and the bodies' states are
    /// untouched, so it may be retried with a smaller dt.
    pub fn step(&mut self, dt_s: f64, integrator: Integrator) -> Result<(), Unstable> {
        assert!(
            dt_s > 0.0 && dt_s.is_finite(),
            "dt must be positive, got {dt_s}"
        );
        let k = self.physics.integration_parameters.num_solver_iterations as f64;
        let cap = self.settings.max_linear_velocity_m_s;
        self.physics.integration_parameters.dt = dt_s;
        let g = self.gravity_m_s2;
        // Fastest motion expected over this step, for the contact prediction distance.
        let mut max_speed: f64 = 0.0;
        // Per body: fluid forces now (free surface applied) and Σ|F_n| of the last step.
        let fluid: Vec<((SphereDrag, Vector, f64), f64)> = self
            .bodies
            .iter()
            .map(|b| {
                let n = if self.rolling_resistance > 0.0 {
                    self.normal_force_sum_n(b)
                } else {
                    0.0
                };
                (self.fluid_now(b), n)
            })
            .collect();
        // Force limits of the yield-stress holds for this step.
        let mut holds: Vec<(usize, f64)> = Vec::new();
        let mu_r = self.rolling_resistance;

        for (i, body) in self.bodies.iter_mut().enumerate() {
            body.correction_m_s = None;
            body.momentum_scale = None;
            let in_contact = self
                .physics
                .narrow_phase
                .contact_pairs_with(body.collider)
                .any(|p| p.has_any_active_contact());
            let rb = &mut self.physics.bodies[body.handle];
            if rb.is_sleeping() || !rb.is_dynamic() {
                continue;
            }
            let m = body.mass_kg;
            let m_rapier = body.rapier_mass_kg();
            let v0 = to_na(rb.linvel());
            let ((drag, body_force, spin_rate), normal_sum) = fluid[i];
            let spin_damping = spin_rate * dt_s;
            rb.reset_forces(false);
            rb.reset_torques(false);
            if in_contact {
                // Drag linearised about the current speed s: F(v) ≈ F₀ v̂ + k v.
                let s = v0.norm();
                let slope = drag.slope_n_s_m(s);
                let mut force = body_force;
                // Static (yield-stress) resistance F_s: when it can stop the body within the step
                // (m s ≤ F_s dt) it is the hold's job, set-valued inside the contact solve; else
                // F₀ v̂ as an explicit force.
                let fs = drag.static_resistance_n();
                let held = self.yield_hold && fs > 0.0 && m * s <= fs * dt_s;
                holds.push((i, if held { fs } else { 0.0 }));
                if s > 0.0 && !held {
                    let f0 = (drag.force_n(s) - slope * s).min(m * s / dt_s);
                    force -= v0 * (f0 / s);
                }
                // Rolling resistance −μ_r r Σ|F_n| ω̂, at most stopping the spin in the step.
                let spin = rb.angvel();
                let spin_norm = super::SpinNorm::spin_norm(&spin);
                if mu_r > 0.0 && normal_sum > 0.0 && spin_norm > 0.0 {
                    let d = body.drag.diameter_m;
                    let inertia = sphere_inertia_kg_m2(m, d);
                    let t = (mu_r * 0.5 * d * normal_sum).min(inertia * spin_norm / dt_s);
                    rb.add_torque(spin * (-t / spin_norm), false);
                }
                let damping = slope / m * dt_s;
                max_speed = max_speed.max(v0.norm() + g.norm() * dt_s / (1.0 + damping));
                let mut force_rapier = force * (m_rapier / m);
                match self.settings.contact_drag {
                    ContactDrag::EffectiveMass if damping > 0.0 && spin_damping > 0.0 => {
                        // Backward-Euler drag inside the solve: mass m + k dt carrying the
                        // momentum m v₀, so (m + k dt) v₁ = m v₀ + F dt + contact impulses; the
                        // same for the spin with the rotational drag.
                        let mut boost = body.rapier_mprops;
                        boost.inv_mass /= damping;
                        boost.inv_principal_inertia /= spin_damping;
                        rb.set_additional_mass_properties(boost, false);
                        body.boosted = true;
                        // Applied below, once no body has refused the step.
                        body.momentum_scale = Some((1.0 + damping, 1.0 + spin_damping));
                        rb.set_linear_damping(0.0);
                        rb.set_angular_damping(0.0);
                        // Rapier pulls the boosted mass down with g: only m g is real.
                        force_rapier -= g * (m_rapier * damping);
                    }
                    _ => {
                        unboost(rb, body);
                        rb.set_linear_damping(damping / dt_s);
                        rb.set_angular_damping(spin_rate);
                    }
                }
                rb.add_force(to_rapier(&force_rapier), false);
            } else {
                // Exact scheme: land on the integrator's displacement, then fix the velocity.
                unboost(rb, body);
                holds.push((i, 0.0));
                let w = g * m + body_force;
                let target = if drag.slope_n_s_m(0.0) == 0.0 && drag.static_resistance_n() == 0.0 {
                    // No fluid (above a free surface): ballistic.
                    let a = w / m;
                    dynamics::Step {
                        velocity_m_s: v0 + a * dt_s,
                        displacement_m: v0 * dt_s + a * (0.5 * dt_s * dt_s),
                        motion: dynamics::Motion::Moving,
                        drag_slope_n_s_m: 0.0,
                    }
                } else {
                    dynamics::advance(integrator, &drag, m, &w, &v0, dt_s)
                };
                let a = (target.displacement_m - v0 * dt_s) * (2.0 * k / ((k + 1.0) * dt_s * dt_s));
                let v_end = v0 + a * dt_s;
                if v_end.norm().is_nan() || v_end.norm() >= cap {
                    return Err(unstable(
                        i,
                        self.time_s,
                        dt_s,
                        "intermediate speed",
                        v_end.norm(),
                        suggested_dt(integrator, body, v0.norm(), dt_s),
                    ));
                }
                max_speed = max_speed.max(v0.norm()).max(target.velocity_m_s.norm());
                rb.set_linear_damping(0.0);
                rb.set_angular_damping(spin_rate);
                rb.add_force(to_rapier(&((a - g) * m_rapier)), false);
                body.correction_m_s = Some(target.velocity_m_s - v_end);
            }
        }

        for (i, force_n) in holds {
            self.set_hold_force(i, force_n);
        }
        for body in &self.bodies {
            if let Some((linear, angular)) = body.momentum_scale {
                let rb = &mut self.physics.bodies[body.handle];
                rb.set_linvel(rb.linvel() / linear, false);
                rb.set_angvel(rb.angvel() / angular, false);
            }
        }
        // Contacts must be predicted before bodies meet: at least twice the largest travel.
        let lu = self.settings.length_unit_m;
        self.physics
            .integration_parameters
            .normalized_prediction_distance = DEFAULT_PREDICTION
            .max(2.0 * max_speed * dt_s / lu)
            .max(self.min_prediction_m / lu);
        if self.restitution.is_speed_dependent() {
            self.physics
                .step_with_events(&RestitutionHook(self.restitution), &());
        } else {
            self.physics.step_with_events(&(), &());
        }
        self.time_s += dt_s;
        self.last_dt_s = dt_s;

        let quarantined = self.physics.quarantine().bodies().to_vec();
        let mut first_error = None;
        for (i, body) in self.bodies.iter().enumerate() {
            let rb = &mut self.physics.bodies[body.handle];
            if let Some(c) = body.correction_m_s {
                let v = rb.linvel() + to_rapier(&c);
                rb.set_linvel(v, false);
            }
            if first_error.is_some() {
                continue;
            }
            let x = to_na(rb.translation());
            let v = to_na(rb.linvel());
            let speed = v.norm();
            let d = body.drag.diameter_m;
            let (quantity, value) = if quarantined.contains(&body.handle) {
                ("quarantined", f64::NAN)
            } else if !x.iter().all(|c| c.is_finite()) {
                ("position", x.norm())
            } else if !speed.is_finite() {
                ("velocity", speed)
            } else if speed > 0.5 * cap {
                ("speed", speed)
            } else if self.settings.max_distance_m.is_some_and(|r| x.norm() > r) {
                ("distance from the origin (outside the domain), m", x.norm())
            } else {
                let frac = self.settings.max_penetration_fraction;
                let depth = if frac > 0.0 {
                    self.physics
                        .narrow_phase
                        .contact_pairs_with(body.collider)
                        .flat_map(|pair| pair.manifolds().iter())
                        .flat_map(|m| m.points.iter())
                        .map(|pt| -pt.dist)
                        .fold(0.0, f64::max)
                } else {
                    0.0
                };
                if frac > 0.0 && depth > frac * d {
                    ("penetration depth, m", depth)
                } else {
                    continue;
                }
            };
            first_error = Some(unstable(
                i,
                self.time_s,
                dt_s,
                quantity,
                value,
                suggested_dt(integrator, body, speed, dt_s),
            ));
        }
        match first_error {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Position of a body's centre, m.
    pub fn position_m(&self, body: BodyId) -> Vector {
        to_na(self.rigid_body(body).translation())
    }

    /// Velocity of a body, m/s.
    pub fn velocity_m_s(&self, body: BodyId) -> Vector {
        to_na(self.rigid_body(body).linvel())
    }

    /// Angular velocity of a body, rad/s (Rapier's type: a scalar in 2D, a vector in 3D).
    pub fn angular_velocity_rad_s(&self, body: BodyId) -> rapier::math::AngVector {
        self.rigid_body(body).angvel()
    }

    /// Mass of a body (3D sphere mass, also in 2D), kg.
    pub fn mass_kg(&self, body: BodyId) -> f64 {
        self.bodies[body.0].mass_kg
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

    /// True if Rapier put the body to sleep (never, unless `settings.can_sleep`).
    pub fn is_sleeping(&self, body: BodyId) -> bool {
        self.rigid_body(body).is_sleeping()
    }

    /// Number of spheres.
    pub fn len(&self) -> usize {
        self.bodies.len()
    }

    /// True if the world has no sphere.
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// Simulated time, s.
    pub fn time_s(&self) -> f64 {
        self.time_s
    }

    /// The settings the world was built with.
    pub fn settings(&self) -> &EngineSettings {
        &self.settings
    }

    /// The underlying Rapier world (read-only), for queries and snapshots.
    pub fn rapier(&self) -> &PhysicsWorld {
        &self.physics
    }

    fn rigid_body(&self, body: BodyId) -> &rapier::prelude::RigidBody {
        &self.physics.bodies[self.bodies[body.0].handle]
    }
}

/// Removes the effective-mass boost, if any (takes effect at the next Rapier step).
fn unboost(rb: &mut rapier::prelude::RigidBody, body: &mut Body) {
    if body.boosted {
        rb.set_additional_mass(0.0, false);
        body.boosted = false;
    }
}

/// Half the step, and for the explicit integrator at most half its stability limit 2m/(dF/dv).
fn suggested_dt(integrator: Integrator, body: &Body, speed_m_s: f64, dt_s: f64) -> f64 {
    let half = 0.5 * dt_s;
    match integrator {
        Integrator::Explicit => {
            let s = if speed_m_s.is_finite() {
                speed_m_s
            } else {
                0.0
            };
            half.min(0.5 * dynamics::explicit_stable_dt_s(body.mass_kg, body.drag.slope_n_s_m(s)))
        }
        _ => half,
    }
}
