//! One Rapier world of fluid-immersed spheres, compiled once per dimension: `engine/dim2.rs` and
//! `engine/dim3.rs` each include this module tree with `rapier` aliased to rapier2d-f64 or
//! rapier3d-f64. Everything dimension-specific comes from `rapier::math::DIM`, glam's slice and
//! array conversions, and the parent's `LIN_AXES` and `spin_norm`.
//!
//! - `mod.rs`: the bodies, the world's state, construction and state queries;
//! - [`step`](World::step) (`step.rs`): one step as named stages, the coupling maths from
//!   [`crate::engine::coupling`] and the fault scan from [`crate::engine::faults`];
//! - `holds.rs`: Rapier joints (yield-stress holds, squeeze-film dampers);
//! - `free_surface.rs`: the free surface (where the fluid is);
//! - `immersed.rs`: the fluid forces a body feels at the start of a step;
//! - `contacts.rs`: walls, fixed colliders, rolling resistance and contact-force queries;
//! - `restitution.rs`: constant and speed-dependent restitution.

mod contacts;
mod free_surface;
mod holds;
mod immersed;
mod restitution;
mod step;

pub use free_surface::FreeSurface;

use super::rapier;
use crate::contact::RestitutionLaw;
use crate::engine::settings::RapierIntegrationParameters;
use crate::engine::{rotational_drag_n_m_s, sphere_inertia_kg_m2, BodyId, EngineSettings};
use crate::fluid::{buoyancy_n, sphere_mass_kg, SphereDrag};
use rapier::prelude::{
    ColliderBuilder, ColliderHandle, IntegrationParameters, MassProperties, PhysicsWorld,
    RigidBodyBuilder, RigidBodyHandle, SpringCoefficients,
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
    /// True while Rapier's mass carries a boost (the effective-mass drag, the added mass).
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
/// pipeline is a workspace only; measured in `tests/app/checkpoint.rs`).
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
    /// Added-mass coefficient C_m (0: off); see [`World::set_added_mass_coefficient`].
    #[serde(default)]
    added_mass_coefficient: f64,
}

impl RapierIntegrationParameters for IntegrationParameters {
    fn set_engine_settings(&mut self, settings: &EngineSettings) {
        self.length_unit = settings.length_unit_m;
        let springs = SpringCoefficients::new(
            settings.contact_natural_frequency_hz,
            settings.damping_ratio,
        );
        self.contact_softness = springs;
        self.static_contact_softness = springs;
        self.normalized_max_linear_velocity =
            settings.max_linear_velocity_m_s / settings.length_unit_m;
        self.num_solver_iterations = settings.num_solver_iterations.max(1);
    }
}

impl World {
    /// An empty world with the given settings and gravity `gravity_m_s2` (> 0, m/s²) pointing
    /// along the negative last axis (−y in 2D, −z in 3D).
    pub fn new(settings: EngineSettings, gravity_m_s2: f64) -> Self {
        let mut physics = PhysicsWorld::new();
        let g = -up() * gravity_m_s2;
        physics.gravity = to_rapier(&g);
        settings.apply(&mut physics.integration_parameters);
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
            added_mass_coefficient: 0.0,
        }
    }

    /// Turns the added mass on with coefficient `c_m` = C_m ≥ 0 (default 0: off; ½ for a sphere
    /// in an unbounded fluid). A body then accelerates as
    /// `(m_p + C_m m_f) dv/dt = m_p g + F_b + F_d + F_c` (fluid at rest; Maxey & Riley 1983,
    /// Auton, Hunt & Prud'homme 1988), with m_f = ρ_f π d³/6 times its immersed volume fraction
    /// at the start of the step (ρ_f the drag's fluid density; the free surface's
    /// [`crate::fluid::immersion::immersion`]). The inertia m_p + C_m m_f is the integrator's mass
    /// in free flight and Rapier's mass for the step (so contacts see it too, see the module doc
    /// of [`crate::engine`]); gravity stays m_p g; the moment of inertia is unchanged (a
    /// sphere's added moment of inertia is zero in potential flow).
    pub fn set_added_mass_coefficient(&mut self, c_m: f64) {
        assert!(
            c_m >= 0.0 && c_m.is_finite(),
            "added-mass coefficient must be finite and ≥ 0, got {c_m}"
        );
        self.added_mass_coefficient = c_m;
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

/// Sets Rapier's additional mass of a body to `added_kg` (a real mass, kg; converted to
/// Rapier's mass units) with no moment of inertia, or removes any boost when `added_kg` is 0
/// (takes effect at the next Rapier step). Returns the body's Rapier mass for the step.
fn boost_added_mass(rb: &mut rapier::prelude::RigidBody, body: &mut Body, added_kg: f64) -> f64 {
    if added_kg > 0.0 {
        let mut props = body.rapier_mprops;
        props.inv_mass *= body.mass_kg / added_kg;
        props.inv_principal_inertia = Default::default();
        rb.set_additional_mass_properties(props, false);
        body.boosted = true;
        body.rapier_mass_kg() * ((body.mass_kg + added_kg) / body.mass_kg)
    } else {
        unboost(rb, body);
        body.rapier_mass_kg()
    }
}

/// Removes the effective-mass boost, if any (takes effect at the next Rapier step).
fn unboost(rb: &mut rapier::prelude::RigidBody, body: &mut Body) {
    if body.boosted {
        rb.set_additional_mass(0.0, false);
        body.boosted = false;
    }
}

/// The dimension-generic view of the world that scenes drive ([`crate::engine::SphereWorld`]).
impl crate::engine::SphereWorld<DIM> for World {
    fn with_sphere(
        settings: EngineSettings,
        g_m_s2: f64,
        centre_m: Vector,
        velocity_m_s: Vector,
        d_m: f64,
        rho_kg_m3: f64,
        drag: SphereDrag,
    ) -> (Self, BodyId) {
        let mut world = Self::new(settings, g_m_s2);
        let mut body = FluidBody::at_rest(centre_m, d_m, rho_kg_m3, drag, g_m_s2);
        body.velocity_m_s = velocity_m_s;
        let id = world.add_sphere(body);
        (world, id)
    }
    fn step_s(
        &mut self,
        dt_s: f64,
        integrator: crate::dynamics::Integrator,
    ) -> Result<(), crate::engine::Unstable> {
        self.step(dt_s, integrator)
    }
    fn centre_m(&self, id: BodyId) -> Vector {
        self.position_m(id)
    }
    fn speed_m_s(&self, id: BodyId) -> Vector {
        self.velocity_m_s(id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_reach_rapier() {
        let mut s = EngineSettings::for_scene(1e-4, 0.05);
        s.num_solver_iterations = 0;
        let mut p = IntegrationParameters::default();
        s.apply(&mut p);
        assert_eq!(p.length_unit, 1e-4);
        let springs = SpringCoefficients::new(1e4, 10.0);
        assert_eq!(p.contact_softness, springs);
        assert_eq!(p.static_contact_softness, springs);
        // Speed cap max(400 × 1e-4, 4 × 0.05) = 0.2 m/s = 2000 length units per second.
        assert!((p.normalized_max_linear_velocity - 2000.0).abs() < 1e-9);
        assert_eq!(p.num_solver_iterations, 1);
        // The world is built with it, with gravity along the last axis.
        let w = World::new(EngineSettings::for_scene(1e-4, 0.05), 9.81);
        let q = &w.rapier().integration_parameters;
        assert_eq!((q.length_unit, q.num_solver_iterations), (1e-4, 4));
        assert_eq!(to_na(w.rapier().gravity), up() * -9.81);
    }
}
