//! The DEM engine: a [Rapier](https://rapier.rs) world (f64) whose spheres feel the fluid forces
//! of [`crate::fluid`], integrated by [`crate::dynamics::advance`]. One source serves both
//! dimensions: [`dim2`] (rapier2d, gravity along −y) and [`dim3`] (rapier3d, gravity along −z) each
//! compile the module tree `engine/world/` against their Rapier crate; gravity acts along the
//! **last** axis.
//!
//! # Layout
//!
//! - [`settings`](EngineSettings): the numerical settings and [`EngineSettings::apply`], which
//!   writes them into Rapier's integration parameters;
//! - [`coupling`]: the dimension-free coupling maths below (free-flight force, effective mass,
//!   clamps, hold decision), const-generic over the dimension and tested without Rapier;
//! - [`faults`]: the fault scan after each step, the refused step and the [`Unstable`] report;
//! - [`dim2`], [`dim3`]: the Rapier worlds, `world/{mod,step,holds,surface,contacts,restitution}.rs`
//!   compiled once per dimension.
//!
//! The engine imports only from the physics layer (fluid, contact, dynamics) and Rapier.
//!
//! # Design
//!
//! Rapier integrates contacts and positions; our integrators decide what the fluid does. Before
//! every Rapier step, [`dim3::World::step`] (same in 2D) computes for every awake dynamic body the
//! target step `advance(integrator, drag, m, W, v₀, dt)` (`W` = gravity + buoyancy, `m` the 3D sphere
//! mass ρ π d³/6, also in 2D) and hands it to Rapier in one of two ways:
//!
//! - **Free body** (no active contact pair in the narrow phase): the exact scheme. One Rapier step
//!   does `K` = `num_solver_iterations` Euler substeps with a force held constant, so the body lands at
//!   `x₀ + v₀dt + a dt² (K+1)/(2K)` with velocity `v₀ + a dt`. We add the force whose acceleration
//!   `a = (Δx − v₀dt)·2K/((K+1)dt²)` lands exactly on the target displacement `Δx` (minus gravity,
//!   which Rapier adds itself) and, after the step, add `v_target − (v₀ + a dt)` to the velocity.
//!   Free flight is then exactly what the integrator says, at any dt (for Stokes drag and the
//!   exponential integrator: the analytic solution to round-off).
//! - **Body in contact** (an active contact pair, speculative ones included): the drag must act
//!   *inside* the contact solve, or the solver does not see the weight (with the exact scheme the
//!   drag balances gravity before any contact force is needed: a resting 2.5 µm grain at dt = 1e-3 s
//!   loads the floor with 0.2 % of its weight). The drag is linearised about the current speed `s`,
//!   `F(v) ≈ F₀ v̂ + k v` with `k = dF/dv(s)`, and handed over as
//!   [`ContactDrag::EffectiveMass`] (default): backward Euler in the solver's own variables. For the
//!   step the body's Rapier mass becomes `m + k dt` and its velocity `m v₀/(m + k dt)` (momentum
//!   kept), so that Rapier's update gives `(m + k dt) v₁ = m v₀ + (W + buoyancy − F₀ v̂) dt + J`,
//!   `J` the contact impulses: exactly backward Euler on the drag, unconditionally stable, with the
//!   contact solver seeing the real forces and the drag as extra inertia. The spin gets the same
//!   treatment with the rotational Stokes drag `π η d³` (inertia `I + π η d³ dt`). At rest the
//!   contact force equals the net weight at any dt. `F₀` is clamped so that it can at most stop the
//!   body within the step.
//! - **Yield stress of a body in contact** (laws with a static resistance `F_s`, the Bingham law:
//!   `F_s = (π²/4 + 3π) d² τ_y`): the drag is set-valued at rest (any force up to `F_s`), which no
//!   explicit force can represent. When the yield stress can stop the body within the step
//!   (`m |v| ≤ F_s dt`, rest included), `F₀` is not applied; instead the body gets a **hold**: a
//!   Rapier joint to a fixed ground body with a rigid velocity motor (target 0, force limit `F_s`)
//!   on each linear axis, anchored at the centre. The contact solver then treats the yield stress
//!   like Coulomb friction: a body stays at rest (creep 0 to round-off, `src/scenes/funnel_pour/tests/mod.rs`) unless
//!   the weight and contacts push it harder than `F_s`, and an impact passes on its whole impulse
//!   less `F_s dt` (a struck ball leaves at (1 + e)/2 of the striker's speed, as without yield
//!   stress). Holds are inserted and removed as bodies stop and start ([`dim3::World::set_yield_hold`]
//!   turns them off).
//! - **Rolling resistance** ([`dim3::World::set_rolling_resistance`], μ_r): a body in contact feels
//!   the torque `−μ_r r Σ|F_n| ω̂` (normal forces of the previous step), clamped so that it at most
//!   stops the spin in the step; a sphere rolling on a plate decelerates at (5/7) μ_r g.
//! - **Free surface** ([`dim3::World::set_free_surface`]): the fluid may be restricted to the region
//!   below a height (and within a cylinder); each body's drag and buoyancy are scaled by its
//!   immersed fractions at the start of the step (full or partial submergence), and a body with no
//!   fluid at all moves ballistically.
//! - **Added mass** ([`dim3::World::set_added_mass_coefficient`], C_m, default 0: off): in a
//!   fluid at rest `(m + C_m m_f) dv/dt = m g + F_b + F_d + F_c` (Maxey & Riley 1983), m_f the
//!   fluid mass of the immersed volume at the start of the step (free surface). The inertia
//!   `M = m + C_m m_f` replaces `m` everywhere the body's inertia enters: the free-flight target
//!   `advance(integrator, drag, M, W, v₀, dt)` (W keeps m g), the in-contact coupling (effective
//!   mass `M + k dt` carrying the momentum `M v₀`, the hold decision `M s ≤ F_s dt` and the clamp
//!   of `F₀`), and Rapier's mass for the step: the body gets C_m m_f as Rapier additional mass
//!   properties **with no moment of inertia** (a sphere's added moment of inertia is zero in
//!   potential flow), and the force subtracts the gravity Rapier puts on it, so that gravity
//!   stays m g while the contact solver sees the effective mass M (+ k dt). Rapier recomputes
//!   the mass properties at the next step whenever they change (it compares them, so a body
//!   fully immersed costs nothing more per step). This "effective mass in the contacts" is a
//!   modelling choice: the added mass of a sphere touching a wall or another sphere is not ½
//!   (it grows as the gap closes, and a pair's added masses couple), and an impact's
//!   restitution is Rapier's velocity ratio whatever the mass.
//!
//!   [`ContactDrag::Damping`] (Rapier's `linear_damping` = k/m) is kept for comparison: it gets
//!   velocities and resting forces right, but Rapier damps only after integrating positions, so a
//!   loaded grain moves ≈ (1 + k dt/m) too far per step: 20 grains of 2.5 µm (τ = 0.87 µs) piled with
//!   dt = 1e-5 s pass through each other (overlaps of 1.5 d), where the effective mass keeps overlaps
//!   below 1.2e-3 d up to dt = 3e-3 s.
//!
//! Forces go to Rapier as accelerations: `force = acceleration × Rapier's body mass`. Each ball's
//! Rapier mass is set to the 3D sphere mass, also in 2D (where a disc would otherwise weigh ρ·area
//! per metre of depth), so contact forces read back in newtons in both dimensions and 2D piles load
//! their grains like 3D spheres of the same diameters would. Free bodies feel the rotational drag
//! through Rapier's `angular_damping`.
//!
//! Before each step the contact prediction distance is raised to twice the largest travel expected
//! over the step (when that exceeds Rapier's 0.02 length units), so bodies moving more than that per
//! step still meet their contacts before they overlap.
//!
//! # Limits
//!
//! - **In contact, positions lag when dt ≫ τ** (τ = m/k, the drag response time): Rapier's K
//!   substeps ramp the velocity from `m v₀/(m + k dt)` to `v₁`, so a body in steady motion while in
//!   contact (sliding, rolling, or crossing the speculative-contact margin above a floor) advances
//!   between (K+1)/(2K) = 5/8 (dt ≫ τ) and 1 (dt ≪ τ) of `v₁ dt`. Velocities, contact forces and
//!   resting states are not affected; transients in contact are slowed by up to 3/8.
//! - The contact state is the narrow phase's from the previous step (one step of lag): the step in
//!   which a free body first touches uses the free scheme, and its velocity correction is added on
//!   top of the contact response.
//! - The drag linearisation is explicit in the speed at which it is taken (the start of the step):
//!   exact for Stokes drag, first order for non-linear laws.
//! - The yield-stress hold acts per axis (x, y, z): the force it can exert is the cube
//!   `|F_i| ≤ F_s`, not the ball `|F| ≤ F_s`; a push along a diagonal can reach √2 F_s (√3 F_s) before
//!   the body moves. The hold's switch uses the speed at the start of the step.
//! - Rolling resistance uses each body's own spin (EDEM's type A), not the relative rolling of the
//!   pair, and in 2D Rapier's disc inertia.
//! - With a free surface, a body enters the fluid up to one step late (no event location); its
//!   added mass switches on (full submergence) or grows with the immersed cap (partial) with the
//!   velocity kept: the entry impulse `−v dM/dt` of a growing added mass is not modelled.
//! - Fluid torque is the rotational Stokes drag only; no hindered settling, lubrication or
//!   fluid-mediated interaction between grains beyond what the drag law itself contains.
//! - `World::contact_force_n` sums the normal contact impulses only (friction impulses are not
//!   included): on a floor or in a frictionless pile it is the full contact force.
//! - One length unit and one contact stiffness per world: grains whose diameters differ by orders of
//!   magnitude do not share a well-tuned world.
//! - Rapier silently caps every substep's speed at `max_linear_velocity_m_s`; `step` reports any
//!   body faster than half of it (or non-finite) as [`Unstable`], and refuses a step whose exact
//!   free-flight force would need an intermediate speed above the cap.
//! - dt is bounded by travel, not by τ: once grains move ≳ 0.1 d per step, transient overlaps pass
//!   1 % of d (20 grains of 70 µm: worst overlap 1.7e-3 d at dt = 1e-3 s, 1.9e-2 d at 4e-3 s), and
//!   a frictionless 2.5 µm pile stepped at dt = 1e-2 s kept a grain jittering at 1 % of v_t. See the
//!   survey in `src/engine/tests/rest.rs`.

mod body_id;
pub mod coupling;
pub mod dim2;
pub mod dim3;
pub mod faults;
mod settings;
#[cfg(test)]
mod tests;

pub use crate::dynamics::Unstable;
pub use body_id::BodyId;
pub(crate) use faults::unstable;
pub use settings::{ContactDrag, EngineSettings};

use crate::dynamics::Integrator;
use crate::fluid::SphereDrag;
use nalgebra::SVector;
// Re-exported for the unit tests only.

/// Rotational drag coefficient of a sphere, N m s: torque = π η d³ ω (Stokes), with η the law's
/// (plastic) viscosity.
pub fn rotational_drag_n_m_s(drag: &SphereDrag) -> f64 {
    let eta = drag.law.viscosity_pa_s();
    std::f64::consts::PI * eta * drag.diameter_m.powi(3)
}

/// Moment of inertia of a sphere about a diameter, kg m²: m d²/10.
pub fn sphere_inertia_kg_m2(mass_kg: f64, diameter_m: f64) -> f64 {
    0.1 * mass_kg * diameter_m * diameter_m
}

/// A Rapier world of `D` dimensions as a scene generic over the dimension drives it: one sphere
/// added, steps taken, its state read ([`dim2::World`] and [`dim3::World`]).
pub trait SphereWorld<const D: usize>: Sized {
    /// A world with one sphere of diameter `d_m`, density `rho_kg_m3` and drag `drag`, centred
    /// at `centre_m`, moving at `velocity_m_s`.
    #[allow(clippy::too_many_arguments)]
    fn with_sphere(
        settings: EngineSettings,
        g_m_s2: f64,
        centre_m: SVector<f64, D>,
        velocity_m_s: SVector<f64, D>,
        d_m: f64,
        rho_kg_m3: f64,
        drag: SphereDrag,
    ) -> (Self, BodyId);
    /// One step of `dt_s`.
    fn step_s(&mut self, dt_s: f64, integrator: Integrator) -> Result<(), Unstable>;
    /// Position of the body's centre, m.
    fn centre_m(&self, id: BodyId) -> SVector<f64, D>;
    /// Velocity of the body, m/s.
    fn speed_m_s(&self, id: BodyId) -> SVector<f64, D>;
}
