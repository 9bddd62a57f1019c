//! One step of the world, as named stages: the loads of each body (fluid forces at the start of
//! the step, normal forces of the last), the coupling of each body to Rapier (free flight or in
//! contact, [`crate::engine::coupling`]), the holds and effective momenta, the contact prediction
//! distance, Rapier's step, the free-flight velocity corrections and the fault scan
//! ([`crate::engine::faults`]).

use super::{boost_added_mass, rapier, to_na, to_rapier, Body, Vector, World, DEFAULT_PREDICTION};
use crate::dynamics::{Integrator, Unstable};
use crate::engine::coupling;
use crate::engine::faults::{self, unstable, FaultLimits};
use crate::engine::{sphere_inertia_kg_m2, ContactDrag};
use crate::fluid::{sphere_mass_kg, SphereDrag};
use rapier::prelude::RigidBody;

/// What acts on a body over a step besides gravity and the contacts.
struct Loads {
    /// Drag, with the free surface's immersed fraction applied.
    drag: SphereDrag,
    /// Body force (buoyancy, …), with the immersed fraction applied, N.
    body_force_n: Vector,
    /// Rotational drag rate k_rot/I, with the immersed fraction applied, 1/s.
    spin_drag_rate_hz: f64,
    /// Added mass C_m m_f of the immersed volume, kg (0: off or out of the fluid).
    added_mass_kg: f64,
    /// Σ|F_n| over the body's contacts during the last step, N (0 without rolling resistance).
    normal_force_sum_n: f64,
}

/// The step's parameters, shared by every body's coupling.
struct StepParams {
    dt_s: f64,
    integrator: Integrator,
    /// Rapier's substeps per step, K.
    substeps: f64,
    /// Rapier's speed cap, m/s.
    speed_cap_m_s: f64,
    /// Gravity, m/s².
    gravity_m_s2: Vector,
    rolling_resistance: f64,
    yield_hold: bool,
    contact_drag: ContactDrag,
}

/// What the coupling stage leaves to the rest of the step.
struct Coupled {
    /// Fastest motion expected over the step, m/s (for the contact prediction distance).
    max_speed_m_s: f64,
    /// Force limits of the yield-stress holds for the step, N, by body index.
    holds: Vec<(usize, f64)>,
}

impl World {
    /// Advances the world by `dt_s`, the fluid forces integrated by `integrator` (see the module
    /// doc of [`crate::engine`]). The contact prediction distance is raised to twice the largest
    /// expected travel over the step when that exceeds Rapier's default (0.02 length units), so
    /// that fast bodies meet their contacts before they overlap.
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
        let params = self.step_params(dt_s, integrator);
        let loads = self.loads();
        let coupled = self.couple(&params, &loads)?;
        for (i, force_n) in coupled.holds {
            self.set_hold_force(i, force_n);
        }
        self.apply_effective_momenta();
        self.predict_contacts(coupled.max_speed_m_s, dt_s);
        self.rapier_step(dt_s);
        self.correct_free_velocities();
        self.scan_faults(dt_s, integrator)
    }

    /// The step's parameters; sets Rapier's dt.
    fn step_params(&mut self, dt_s: f64, integrator: Integrator) -> StepParams {
        self.physics.integration_parameters.dt = dt_s;
        StepParams {
            dt_s,
            integrator,
            substeps: self.physics.integration_parameters.num_solver_iterations as f64,
            speed_cap_m_s: self.settings.max_linear_velocity_m_s,
            gravity_m_s2: self.gravity_m_s2,
            rolling_resistance: self.rolling_resistance,
            yield_hold: self.yield_hold,
            contact_drag: self.settings.contact_drag,
        }
    }

    /// Per body: the fluid forces now (free surface applied) and Σ|F_n| of the last step.
    fn loads(&self) -> Vec<Loads> {
        self.bodies
            .iter()
            .map(|b| {
                let normal_force_sum_n = if self.rolling_resistance > 0.0 {
                    self.normal_force_sum_n(b)
                } else {
                    0.0
                };
                let (drag, body_force_n, spin_drag_rate_hz, immersed) = self.fluid_now(b);
                let c_m = self.added_mass_coefficient;
                let added_mass_kg = if c_m > 0.0 && immersed > 0.0 {
                    let m_f = sphere_mass_kg(b.drag.diameter_m, b.drag.fluid_density_kg_m3);
                    c_m * m_f * immersed
                } else {
                    0.0
                };
                Loads {
                    drag,
                    body_force_n,
                    spin_drag_rate_hz,
                    added_mass_kg,
                    normal_force_sum_n,
                }
            })
            .collect()
    }

    /// Hands every awake dynamic body its forces, mass boost and damping for the step: the
    /// in-contact coupling when the narrow phase has an active (possibly speculative) contact
    /// for it, else the exact free-flight scheme. Refuses the step (before Rapier moved anything)
    /// when a free body's substeps would exceed the speed cap.
    fn couple(&mut self, params: &StepParams, loads: &[Loads]) -> Result<Coupled, Unstable> {
        let mut coupled = Coupled {
            max_speed_m_s: 0.0,
            holds: Vec::new(),
        };
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
            rb.reset_forces(false);
            rb.reset_torques(false);
            let speed = if in_contact {
                let (hold_force_n, speed) = couple_in_contact(rb, body, &loads[i], params);
                coupled.holds.push((i, hold_force_n));
                speed
            } else {
                coupled.holds.push((i, 0.0));
                couple_free(rb, body, &loads[i], params).map_err(|fault| {
                    unstable(
                        i,
                        self.time_s,
                        params.dt_s,
                        fault.quantity,
                        fault.value,
                        fault.suggested_dt_s,
                    )
                })?
            };
            coupled.max_speed_m_s = coupled.max_speed_m_s.max(speed);
        }
        Ok(coupled)
    }

    /// Divides the velocities of the bodies with an effective mass by its factors (momentum
    /// kept), once no body has refused the step.
    fn apply_effective_momenta(&mut self) {
        for body in &self.bodies {
            if let Some((linear, angular)) = body.momentum_scale {
                let rb = &mut self.physics.bodies[body.handle];
                rb.set_linvel(rb.linvel() / linear, false);
                rb.set_angvel(rb.angvel() / angular, false);
            }
        }
    }

    /// Contacts must be predicted before bodies meet: the prediction distance is at least twice
    /// the largest travel `max_speed_m_s · dt_s`, Rapier's default and the world's floor.
    fn predict_contacts(&mut self, max_speed_m_s: f64, dt_s: f64) {
        let lu = self.settings.length_unit_m;
        self.physics
            .integration_parameters
            .normalized_prediction_distance = DEFAULT_PREDICTION
            .max(2.0 * max_speed_m_s * dt_s / lu)
            .max(self.min_prediction_m / lu);
    }

    /// Rapier's step (with the restitution hook when e depends on the impact speed).
    fn rapier_step(&mut self, dt_s: f64) {
        if self.restitution.is_speed_dependent() {
            self.physics
                .step_with_events(&super::restitution::RestitutionHook(self.restitution), &());
        } else {
            self.physics.step_with_events(&(), &());
        }
        self.time_s += dt_s;
        self.last_dt_s = dt_s;
    }

    /// Adds each free body's velocity correction `v_target − (v₀ + a dt)`.
    fn correct_free_velocities(&mut self) {
        for body in &self.bodies {
            if let Some(c) = body.correction_m_s {
                let rb = &mut self.physics.bodies[body.handle];
                let v = rb.linvel() + to_rapier(&c);
                rb.set_linvel(v, false);
            }
        }
    }

    /// The fault scan ([`faults::scan`]) of every body after the step: the first at fault.
    fn scan_faults(&self, dt_s: f64, integrator: Integrator) -> Result<(), Unstable> {
        let quarantined = self.physics.quarantine().bodies();
        let limits = FaultLimits {
            speed_cap_m_s: self.settings.max_linear_velocity_m_s,
            max_distance_m: self.settings.max_distance_m,
            max_penetration_fraction: self.settings.max_penetration_fraction,
        };
        for (i, body) in self.bodies.iter().enumerate() {
            let rb = &self.physics.bodies[body.handle];
            let x = to_na(rb.translation());
            let v = to_na(rb.linvel());
            let fault = faults::scan(
                &x,
                &v,
                body.drag.diameter_m,
                quarantined.contains(&body.handle),
                &limits,
                || self.deepest_overlap_m(body),
            );
            if let Some(f) = fault {
                let suggested = suggested_dt_s(integrator, body, v.norm(), dt_s);
                return Err(unstable(
                    i,
                    self.time_s,
                    dt_s,
                    f.quantity,
                    f.value,
                    suggested,
                ));
            }
        }
        Ok(())
    }

    /// Deepest overlap of a body's contacts, m (0 without contact).
    fn deepest_overlap_m(&self, body: &Body) -> f64 {
        self.physics
            .narrow_phase
            .contact_pairs_with(body.collider)
            .flat_map(|pair| pair.manifolds().iter())
            .flat_map(|m| m.points.iter())
            .map(|pt| -pt.dist)
            .fold(0.0, f64::max)
    }
}

/// A free body's step refused: what and the step suggested.
struct Refused {
    quantity: &'static str,
    value: f64,
    suggested_dt_s: f64,
}

/// The in-contact coupling of one body ([`coupling::in_contact`]): explicit force, rolling
/// torque, and the drag's slope as an effective mass (or Rapier's damping). Returns the hold's
/// force limit and the fastest speed expected over the step.
fn couple_in_contact(
    rb: &mut RigidBody,
    body: &mut Body,
    loads: &Loads,
    params: &StepParams,
) -> (f64, f64) {
    let (dt_s, g) = (params.dt_s, params.gravity_m_s2);
    let m = body.mass_kg;
    // The inertia m_p + C_m m_f (added mass) carries the momentum and takes the drag's slope.
    let added = loads.added_mass_kg;
    let inertia = m + added;
    let m_rapier = body.rapier_mass_kg();
    let v0 = to_na(rb.linvel());
    let c = coupling::in_contact(
        &loads.drag,
        inertia,
        &loads.body_force_n,
        &v0,
        dt_s,
        params.yield_hold,
    );
    // Rolling resistance −μ_r r Σ|F_n| ω̂, at most stopping the spin in the step.
    let spin = rb.angvel();
    let spin_norm = super::super::spin_norm(spin);
    let d = body.drag.diameter_m;
    if let Some(t) = coupling::rolling_torque_n_m(
        params.rolling_resistance,
        d,
        loads.normal_force_sum_n,
        sphere_inertia_kg_m2(m, d),
        spin_norm,
        dt_s,
    ) {
        rb.add_torque(spin * (-t / spin_norm), false);
    }
    let speed = coupling::contact_travel_speed_m_s(v0.norm(), g.norm(), dt_s, c.damping);
    let spin_rate = loads.spin_drag_rate_hz;
    let spin_damping = spin_rate * dt_s;
    let mut force_rapier = c.force_n * (m_rapier / m);
    match (
        params.contact_drag,
        coupling::effective_mass_factors(c.damping, spin_damping),
    ) {
        (ContactDrag::EffectiveMass, Some(factors)) => {
            // Backward-Euler drag inside the solve: mass M + k dt carrying the momentum M v₀
            // (M = m + C_m m_f, the inertia), so (M + k dt) v₁ = M v₀ + F dt + contact impulses;
            // the same for the spin with the rotational drag (no added moment of inertia).
            let extra = added / m + c.damping * (inertia / m);
            let mut boost = body.rapier_mprops;
            boost.inv_mass /= extra;
            boost.inv_principal_inertia /= spin_damping;
            rb.set_additional_mass_properties(boost, false);
            body.boosted = true;
            // Applied by `apply_effective_momenta`, once no body has refused the step.
            body.momentum_scale = Some(factors);
            rb.set_linear_damping(0.0);
            rb.set_angular_damping(0.0);
            // Rapier pulls the boosted mass down with g: only m g is real.
            force_rapier -= g * (m_rapier * extra);
        }
        _ => {
            let m_boosted = boost_added_mass(rb, body, added);
            if added > 0.0 {
                force_rapier -= g * (m_boosted - m_rapier);
            }
            rb.set_linear_damping(c.damping / dt_s);
            rb.set_angular_damping(spin_rate);
        }
    }
    rb.add_force(to_rapier(&force_rapier), false);
    (c.hold_force_n, speed)
}

/// The exact free-flight coupling of one body ([`coupling::free_flight`]): the force that lands
/// Rapier's substeps on the integrator's displacement, and the velocity correction for after
/// the step. Returns the fastest speed expected over the step, or the refusal when the substeps
/// would reach Rapier's speed cap.
fn couple_free(
    rb: &mut RigidBody,
    body: &mut Body,
    loads: &Loads,
    params: &StepParams,
) -> Result<f64, Refused> {
    let (dt_s, g) = (params.dt_s, params.gravity_m_s2);
    let m = body.mass_kg;
    let v0 = to_na(rb.linvel());
    // The integrator's inertia is m + C_m m_f (added mass); the weight stays m g.
    let flight = coupling::free_flight(
        params.integrator,
        &loads.drag,
        m + loads.added_mass_kg,
        &(g * m + loads.body_force_n),
        &v0,
        dt_s,
        params.substeps,
    );
    if let Some(f) = faults::intermediate_speed(&flight.substep_velocity_m_s, params.speed_cap_m_s)
    {
        return Err(Refused {
            quantity: f.quantity,
            value: f.value,
            suggested_dt_s: suggested_dt_s(params.integrator, body, v0.norm(), dt_s),
        });
    }
    // Rapier's mass carries the added mass too, so that a contact met within the step sees it.
    let m_rapier = boost_added_mass(rb, body, loads.added_mass_kg);
    rb.set_linear_damping(0.0);
    rb.set_angular_damping(loads.spin_drag_rate_hz);
    rb.add_force(
        to_rapier(&((flight.acceleration_m_s2 - g) * m_rapier)),
        false,
    );
    body.correction_m_s = Some(flight.correction_m_s());
    Ok(v0.norm().max(flight.target.velocity_m_s.norm()))
}

/// [`faults::suggested_dt_s`] for a body (its mass and unscaled drag).
fn suggested_dt_s(integrator: Integrator, body: &Body, speed_m_s: f64, dt_s: f64) -> f64 {
    faults::suggested_dt_s(integrator, body.mass_kg, &body.drag, speed_m_s, dt_s)
}
